#!/usr/bin/env bash
# The C++ style (issue 9): every C++ file of the project is as clang-format lays it out with the
# repository's .clang-format, so that one style is kept rather than re-applied from time to time.
# The files: lib/, repro/, experiments/ and tests/ (*.cpp, *.hpp). clang-format comes from Debian's
# package (tools/deps.sh); a file that differs is named with the first place clang-format would change.
# Usage: format.sh BIN_DIR (unused: the sources are found beside this test).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
command -v clang-format >/dev/null || { echo "format: clang-format is not installed (tools/deps.sh installs it)"; exit 1; }
mapfile -t files < <(cd "$root" && find lib repro experiments tests -name '*.cpp' -o -name '*.hpp' | LC_ALL=C sort)
((${#files[@]} > 0)) || { echo "format: no C++ file found under $root"; exit 1; }
failures=0
for file in "${files[@]}"; do
  if ! (cd "$root" && clang-format --dry-run --Werror "$file" >/dev/null 2>&1); then
    echo "format: $file is not clang-formatted (clang-format -i $file):"
    (cd "$root" && clang-format --dry-run "$file" 2>&1 | head -3)
    failures=$((failures + 1))
  fi
done
((failures == 0)) && echo "format: ${#files[@]} C++ files as clang-format lays them out"
exit $((failures > 0))
