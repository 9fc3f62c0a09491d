#!/usr/bin/env bash
# bar1d on every benchmark and on initial data from a file (ctest runs `bash tests/benchmarks_smoke.sh
# BIN_DIR`):
#   - `--benchmark paper` is the default: the same bytes on standard output as without the option;
#   - the smooth benchmarks and the sampled file tests/data/initial_data/left_going_wave.dat run, every
#     error is a finite number in (0, 1), and halving h lowers the error of u(0,·) (they converge:
#     orders 1 to 2 are predicted for the smooth ones, mathematics.md §11);
#   - the time series of a file's data carries the characteristic solution's exact values;
#   - the phase is measured for every data against the exact impacts: on S1 the first impact, a
#     transversal one, is on time with Mod 3 to 0.05h (the period law, mathematics.md §8; the doctest
#     in lib/measures/phase.cpp checks Mod 1 and 2 too), and the paper's data given as a file give the paper's
#     phase lines to 1e-9; the period law's predictions are printed for the paper's benchmark alone.
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
  # The period law's predictions are the paper's benchmark's: not printed here. The phase is, when the
  # run and the exact solution both have an impact (every case here), as finite numbers.
  ! grep -E '^period_law_[a-z_]* = ' "$work/coarse" || fail "$name: prints the period law of the paper's benchmark"
  awk -v v="$(value first_impact_error "$work/coarse")" 'BEGIN {exit !(v ~ /^-?[0-9.]+(e[-+][0-9]+)?$/)}' ||
    fail "$name: first_impact_error = '$(value first_impact_error "$work/coarse")' is not a finite number"
  echo "$name: err_u0_L2 $(value err_u0_L2 "$work/coarse") (N = 100), $(value err_u0_L2 "$work/fine") (N = 200)"
}
check_run smooth-impact --benchmark smooth-impact
check_run grazing --benchmark grazing
check_run left_going_wave.dat --initial-data "$here/data/initial_data/left_going_wave.dat" --final-time 2

# S1's first impact is transversal: with Mod 3 (the default) it is on time to 0.05h on both meshes.
for elements in 100 200; do
  "$bar1d" --benchmark smooth-impact --elements "$elements" --no-timing >"$work/s1"
  awk -v e="$(value first_impact_error "$work/s1")" -v h="$(awk "BEGIN {print 1 / $elements}")" \
    'BEGIN {exit !(e != "" && (e < 0 ? -e : e) <= 0.05 * h)}' ||
    fail "S1, N = $elements: first_impact_error = $(value first_impact_error "$work/s1"), not within 0.05h of 0"
done

# The paper's data as a file (u0 = (1 - x)/2 is linear: two rows are exact) give the paper's phase: the
# characteristic solution's impacts are L + 3Lk to round-off (lib/measures/phase.cpp), 1e-9 is far above it.
printf '0 0.5 0\n1 0 0\n' >"$work/paper.dat"
"$bar1d" --elements 40 --final-time 15 --no-timing >"$work/paper_default"
"$bar1d" --initial-data "$work/paper.dat" --elements 40 --final-time 15 --no-timing >"$work/paper_file"
for key in impacts impacts_compared first_impact_error phase_drift_per_period phase_period; do
  awk -v a="$(value $key "$work/paper_default")" -v b="$(value $key "$work/paper_file")" \
    'BEGIN {d = a - b; exit !(a != "" && b != "" && (d < 0 ? -d : d) <= 1e-9)}' ||
    fail "the paper's data as a file: $key = $(value $key "$work/paper_file"), the benchmark gives $(value $key "$work/paper_default")"
done

# The series of a file's data: the header names the reference, and the exact u(0, 0) is the file's u0(0).
"$bar1d" --initial-data "$here/data/initial_data/left_going_wave.dat" --elements 20 --final-time 1 \
  --output "$work/series.dat" >/dev/null
grep -q '^# bar1d: .*initial data from a file; exact values: characteristic solution' "$work/series.dat" ||
  fail "the series header does not name the characteristic solution"
awk '!/^#/ {print $3; exit}' "$work/series.dat" | grep -qx '0.25' || fail "the series' exact u(0, 0) is not 0.25"

((failures == 0)) && echo "benchmarks_smoke: every benchmark and the file's data run and converge"
exit $((failures > 0))
