#!/usr/bin/env bash
# ctest readme_generated: the README cannot go stale.
#   - Its generated blocks (tools/readme.sh: the times of the two commands from doc/build_times.txt, the
#     claims and their verdicts from the claims detail) are what their files give: the claims detail is
#     the one the ctest entry check_claims wrote in this build (a fixture: check_claims runs first), or,
#     under `make test`, the one make's claims rule wrote (MRM_CLAIMS_DETAIL; the Makefile's rule `test`).
#   - Its first screen, everything above the line `<!-- the first screen ends here -->`, fits in 60 lines.
#   - Its figure table lists every figure `make all` draws, and no other: the figures are read from make's
#     database of `all` (make -pn, nothing run).
# Usage: readme_generated.sh BIN_DIR   (the claims detail: $MRM_CLAIMS_DETAIL if set, else
#        BIN_DIR/../check_claims_detail.txt)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bin=${1:?usage: readme_generated.sh BIN_DIR}
detail=${MRM_CLAIMS_DETAIL:-$bin/../check_claims_detail.txt}
work=$(mktemp -d -t readme_generated.XXXXXX)
trap 'rm -rf -- "$work"' EXIT
status=0

# 1. The generated blocks.
if [[ -f $detail ]]; then
  bash "$root/tools/readme.sh" --check "$detail" || status=1
else
  echo "readme_generated: no claims detail at $detail (the ctest entry check_claims writes it, or make's claims rule)"
  status=1
fi

# 2. The first screen.
lines=$(awk '/^<!-- the first screen ends here -->$/ { print NR - 1; found = 1; exit } END { if (!found) print -1 }' "$root/README.md")
if ((lines < 0)); then
  echo "readme_generated: the README has no line '<!-- the first screen ends here -->'"
  status=1
elif ((lines > 60)); then
  echo "readme_generated: the README's first screen has $lines lines (at most 60)"
  status=1
else
  echo "readme_generated: the first screen has $lines lines (at most 60)"
fi

# 3. The figure table against the figures of `make all`.
env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -C "$root" -pn all OUT="$work/out" BUILD="$work/build" >"$work/database.txt" 2>&1 ||
  { echo "readme_generated: make -pn all failed"; cat "$work/database.txt"; exit 1; }
grep -o "^$work/out/figures/[^ :%]*\.pdf:" "$work/database.txt" | sed "s|^$work/out/figures/||; s|:$||" | sort -u >"$work/made"
sed -n 's#^| `output/figures/\([^`]*\.pdf\)` |.*#\1#p' "$root/README.md" | sort >"$work/listed"
if ! diff "$work/made" "$work/listed" >"$work/diff"; then
  echo "readme_generated: the README's figure table differs from the figures make all draws (< made, not listed; > listed, not made):"
  grep '^[<>]' "$work/diff"
  status=1
else
  echo "readme_generated: the figure table lists the $(wc -l <"$work/made") figures of make all"
fi
exit $status
