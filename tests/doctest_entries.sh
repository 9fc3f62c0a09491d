#!/usr/bin/env bash
# Every doctest test case is one ctest entry of label `unit`, under its own name, and no entry names a
# test case that does not exist. CMake's doctest_discover_tests turns each test case into an entry that
# runs `doctests --test-case=NAME`; a name that CMake reads as a list (a `;` in it) becomes two entries
# whose filters match no test case, and doctest passes a run that matched nothing: such a test case
# would never run under ctest. This compares the two lists, name by name, and fails on any difference.
# Usage: doctest_entries.sh BIN_DIR (BIN_DIR/doctests; the build directory is its parent).
set -euo pipefail
if (($# < 1)) || [[ ! -x $1/doctests ]]; then
  echo "usage: bash tests/doctest_entries.sh BIN_DIR (with BIN_DIR/doctests)" >&2
  exit 2
fi
bin=$(cd "$1" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/doctest_entries.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
# The test cases, one per line (doctest's listing has a header line and a summary after a rule).
"$bin/doctests" --list-test-cases --no-version | grep -v -E '^\[doctest\]|^=+$' | LC_ALL=C sort >"$work/cases"
# The ctest entries of label unit ("  Test  #12: NAME").
(cd "$bin/.." && ctest -N -L unit) | sed -n -E 's/^ *Test +#[0-9]+: //p' | LC_ALL=C sort >"$work/entries"
cases=$(wc -l <"$work/cases")
((cases > 0)) || { echo "doctest_entries: doctests lists no test case"; exit 1; }
if ! diff "$work/cases" "$work/entries" >"$work/diff"; then
  echo "doctest_entries: the test cases and the ctest entries differ (< a test case without its own entry, > an entry that is no test case):"
  grep -E '^[<>]' "$work/diff" | head -n 20
  exit 1
fi
echo "doctest_entries: $cases test cases, each one ctest entry"
