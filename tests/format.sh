#!/usr/bin/env bash
# The C++ style: every C++ file of the project is as clang-format lays it out with the
# repository's .clang-format, so that one style is kept rather than re-applied from time to time.
# The files: lib/, repro/, experiments/ and tests/ (*.cpp, *.hpp), given to one clang-format process
# (from Debian's package, tools/deps.sh); a file that differs is named with the first place clang-format
# would change.
# Usage: format.sh BIN_DIR (unused: the sources are found beside this test).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
command -v clang-format >/dev/null || { echo "format: clang-format is not installed (tools/deps.sh installs it)"; exit 1; }
mapfile -t files < <(cd "$root" && find lib repro experiments tests -name '*.cpp' -o -name '*.hpp' | LC_ALL=C sort)
((${#files[@]} > 0)) || { echo "format: no C++ file found under $root"; exit 1; }
# --dry-run prints "FILE:LINE:COLUMN: warning: code should be clang-formatted" for each place to change.
report=$(cd "$root" && clang-format --dry-run "${files[@]}" 2>&1 || true)
mapfile -t differing < <(grep -o '^[^:]*:[0-9]*:[0-9]*: warning: code should be clang-formatted' <<<"$report" |
  cut -d: -f1 | LC_ALL=C sort -u)
if ((${#differing[@]} > 0)); then
  for file in "${differing[@]}"; do
    echo "format: $file is not clang-formatted (clang-format -i $file); first place:"
    grep -m 1 -A 2 "^$file:" <<<"$report"
  done
  exit 1
fi
if grep -q . <<<"$report"; then
  echo "format: clang-format failed:"
  head -n 5 <<<"$report"
  exit 1
fi
echo "format: ${#files[@]} C++ files as clang-format lays them out"
