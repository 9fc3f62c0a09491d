#!/usr/bin/env bash
# bar1d's two paths beyond one uniform bar, two bars and a graded mesh (ctest runs
# `bash tests/two_bars_graded.sh BIN_DIR`):
#   - golden: `--benchmark two-bars` (two meshes, one contact multiplier, lib/time/two_bodies.hpp) and a
#     graded mesh (`--grading 1.01` on the paper's benchmark) against their committed outputs in
#     tests/expected/ (numdiff -r 1e-12 -a 1e-14, the tolerance of tests/expected/README.md: a few
#     thousand Crank-Nicolson steps on values of order one); `--update` makes them again;
#   - two-bars: the exact windows are [0, 20] (2L/c), the measured release within 2h of it (0.14 h here,
#     Mod 3, N = 40; the release error falls at an order near 2/3, so in units of h it grows: measured
#     from N = 10 to 640 for Mod 1, 2, 3, at most 1.7 h, Mod 1 at N = 640), and the same bytes twice;
#   - graded: the measured drift per period within 0.15 h0 of the eigenvalue law's prediction (the
#     resolution of the measurement, fig_benchmark_convergence's graded table);
#   - hostile: a closed standard output is an error (exit status not 0), for both paths.
set -euo pipefail
if (($# < 1)) || [[ ! -x $1/bar1d ]]; then
  echo "usage: bash tests/two_bars_graded.sh BIN_DIR [--update] (with BIN_DIR/bar1d)" >&2
  exit 2
fi
bar1d=$(cd "$1" && pwd)/bar1d
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/two_bars_graded.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
failures=0
fail() {
  echo "FAIL $*"
  failures=$((failures + 1))
}
value() { awk -v k="$1" '$1 == k {print $3}' "$2"; }

two_bars=(--benchmark two-bars --scheme cn --mass mod3 --elements 40 --no-timing)
graded=(--grading 1.01 --mass mod1 --elements 100 --final-time 30 --no-timing)
"$bar1d" "${two_bars[@]}" >"$work/two_bars.txt"
"$bar1d" "${graded[@]}" >"$work/graded.txt"
if [[ ${2:-} == --update ]]; then
  cp "$work/two_bars.txt" "$here/expected/bar1d_two_bars.txt"
  cp "$work/graded.txt" "$here/expected/bar1d_graded.txt"
  echo "two_bars_graded: wrote tests/expected/bar1d_two_bars.txt and bar1d_graded.txt"
  exit 0
fi
for name in two_bars graded; do
  if numdiff --quiet --relative-tolerance=1e-12 --absolute-tolerance=1e-14 "$here/expected/bar1d_$name.txt" \
    "$work/$name.txt" >/dev/null; then
    echo "two_bars_graded: bar1d_$name.txt matches (numdiff -r 1e-12 -a 1e-14)"
  else
    fail "bar1d_$name.txt differs (< expected, > this run):"
    numdiff --relative-tolerance=1e-12 --absolute-tolerance=1e-14 "$here/expected/bar1d_$name.txt" \
      "$work/$name.txt" | head -n 40 || true
  fi
done

# two-bars: windows, determinism.
grep -q '^exact_contact_windows = \[0, 20\]$' "$work/two_bars.txt" || fail "two-bars: exact windows not [0, 20]"
release=$(awk '$1 == "measured_contact_windows" {gsub(/[],]/, "", $4); print $4}' "$work/two_bars.txt")
awk -v r="$release" 'BEGIN {exit !(r > 20 - 2 * 10 / 40 && r < 20 + 2 * 10 / 40)}' ||
  fail "two-bars: measured release $release not within 2h = 0.5 of 20"
cmp -s "$work/two_bars.txt" <("$bar1d" "${two_bars[@]}") || fail "two-bars: two runs differ"

# graded: the measured drift against the eigenvalue law's prediction, within 0.15 h0.
drift=$(value phase_drift_per_period "$work/graded.txt")
law=$(value period_law_drift_per_period "$work/graded.txt")
h0=$(value h0 "$work/graded.txt")
awk -v d="$drift" -v p="$law" -v h="$h0" 'BEGIN {x = d - p; if (x < 0) x = -x; exit !(h > 0 && x <= 0.15 * h)}' ||
  fail "graded: drift $drift against the law's $law: more than 0.15 h0 = 0.15 * $h0"

# hostile: a closed standard output is an error.
for args in two_bars graded; do
  declare -n list=$args
  if "$bar1d" "${list[@]}" >&- 2>/dev/null; then fail "$args: exit 0 with a closed standard output"; fi
done

if ((failures > 0)); then
  echo "two_bars_graded: $failures failure(s)"
  exit 1
fi
echo "two_bars_graded: all checks passed"
