#!/usr/bin/env bash
# bar1d on every benchmark and on initial data from a file (ctest runs `bash tests/benchmarks_smoke.sh
# BIN_DIR`):
#   - `--benchmark paper` is the default: the same bytes on standard output as without the option;
#   - the smooth benchmarks and the sampled file tests/data/initial_data/left_going_wave.dat run, every
#     error is a finite number in (0, 1), and halving h lowers the error of u(0,·) (they converge:
#     orders 1 to 2 are predicted for the smooth ones, mathematics.md §11);
#   - the time series of a file's data carries the characteristic solution's exact values;
#   - for data other than the paper's benchmark no phase value that assumes its impacts is printed.
set -euo pipefail
if (($# != 1)) || [[ ! -x $1/bar1d ]]; then
  echo "usage: bash tests/benchmarks_smoke.sh BIN_DIR (with BIN_DIR/bar1d)" >&2
  exit 2
fi
bar1d=$(cd "$1" && pwd)/bar1d
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/benchmarks_smoke.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
failures=0
fail() {
  echo "FAIL $*"
  failures=$((failures + 1))
}

cmp -s <("$bar1d" --elements 40 --no-timing) <("$bar1d" --benchmark paper --elements 40 --no-timing) ||
  fail "--benchmark paper differs from the default"

value() { awk -v k="$1" '$1 == k {print $3}' "$2"; }
check_run() {  # check_run NAME ARGS...: two meshes, every error in (0, 1), u(0,.) error lower on the finer
  local name=$1
  shift
  "$bar1d" "$@" --elements 100 --no-timing >"$work/coarse" || { fail "$name: bar1d failed"; return; }
  "$bar1d" "$@" --elements 200 --no-timing >"$work/fine" || { fail "$name: bar1d failed"; return; }
  local key
  for key in err_u0_L2 err_lambda_L2 err_u_LinfL2 err_u_LinfH1 err_v_LinfL2 err_u_L2L2 err_u_L2H1 err_v_L2L2; do
    awk -v v="$(value $key "$work/coarse")" 'BEGIN {exit !(v > 0 && v < 1)}' ||
      fail "$name: $key = $(value $key "$work/coarse") is not in (0, 1)"
  done
  awk -v c="$(value err_u0_L2 "$work/coarse")" -v f="$(value err_u0_L2 "$work/fine")" 'BEGIN {exit !(f < c)}' ||
    fail "$name: err_u0_L2 does not decrease from N = 100 to 200"
  # The phase against exact impacts and the period law are the paper's benchmark's: not printed here.
  ! grep -E '^(first_impact_error|phase_drift_per_period|period_law_[a-z_]*) = ' "$work/coarse" ||
    fail "$name: prints phase values that belong to the paper's benchmark"
  echo "$name: err_u0_L2 $(value err_u0_L2 "$work/coarse") (N = 100), $(value err_u0_L2 "$work/fine") (N = 200)"
}
check_run smooth-impact --benchmark smooth-impact
check_run grazing --benchmark grazing
check_run left_going_wave.dat --initial-data "$here/data/initial_data/left_going_wave.dat" --final-time 2

# The series of a file's data: the header names the reference, and the exact u(0, 0) is the file's u0(0).
"$bar1d" --initial-data "$here/data/initial_data/left_going_wave.dat" --elements 20 --final-time 1 \
  --output "$work/series.dat" >/dev/null
grep -q '^# bar1d: .*initial data from a file; exact values: characteristic solution' "$work/series.dat" ||
  fail "the series header does not name the characteristic solution"
awk '!/^#/ {print $3; exit}' "$work/series.dat" | grep -qx '0.25' || fail "the series' exact u(0, 0) is not 0.25"

((failures == 0)) && echo "benchmarks_smoke: every benchmark and the file's data run and converge"
exit $((failures > 0))
