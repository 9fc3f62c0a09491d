#!/usr/bin/env bash
# The golden output of the README's bar1d example (ctest golden_bar1d). Usage:
#   bash tests/expected/compare.sh BAR1D_PROGRAM tests/expected/bar1d_readme           compare
#   bash tests/expected/compare.sh BAR1D_PROGRAM tests/expected/bar1d_readme --update  make it again
# The run is the README's first example, with --no-timing (the wall time changes from run to run) and
# --output (the series at the contact point), in a scratch directory so that the header's echo of the
# output name is the same wherever it runs. Its printed summary is compared with PREFIX.txt and its
# series with PREFIX.dat by numdiff, at a relative tolerance of 1e-12 or an absolute one of 1e-14
# (either suffices; see tests/expected/README.md for why).
set -euo pipefail
if (($# < 2)); then
  echo "usage: bash tests/expected/compare.sh BAR1D_PROGRAM PREFIX [--update]" >&2
  exit 2
fi
bar1d=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
prefix=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/golden_bar1d.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
(cd "$work" && "$bar1d" --scheme cn --mass mod3 --elements 50 --courant 0.5 --final-time 12 --no-timing \
  --output series.dat >summary.txt)
if [[ ${3:-} == --update ]]; then
  cp "$work/summary.txt" "$prefix.txt"
  cp "$work/series.dat" "$prefix.dat"
  echo "golden_bar1d: wrote $prefix.txt and $prefix.dat"
  exit 0
fi
status=0
for pair in "summary.txt:$prefix.txt" "series.dat:$prefix.dat"; do
  produced=$work/${pair%%:*} expected=${pair#*:}
  if numdiff --quiet --relative-tolerance=1e-12 --absolute-tolerance=1e-14 "$expected" "$produced" >/dev/null; then
    echo "golden_bar1d: ${expected##*/} matches (numdiff -r 1e-12 -a 1e-14)"
  else
    echo "golden_bar1d: ${expected##*/} differs (< expected, > this run):"
    numdiff --relative-tolerance=1e-12 --absolute-tolerance=1e-14 "$expected" "$produced" | head -n 40 || true
    status=1
  fi
done
exit $status
