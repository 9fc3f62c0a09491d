#!/usr/bin/env bash
# tools/build_times_tex.sh, the article's times of `make all` and `make test`: from a build_times file
# with several runs, each command's median with its minimum and maximum (the README's words), the
# machine, the day and the share of other processes; from a file with one run, the one value; from a
# file with no run, "not measured yet"; a file that lacks a key is an error.
# Usage: build_times_tex.sh BIN_DIR (unused: the script is found beside this test).
set -euo pipefail
tool=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tools/build_times_tex.sh
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
expect() {  # expect FILE LINE: the output has this line
  grep -qxF "$2" <<< "$1" || { echo "build_times_tex: expected the line $2 in:"; echo "$1"; exit 1; }
}

cat > "$dir/three.txt" <<'TIMES'
# a comment
date = 2026-01-02 03:04 UTC
commit = abc1234
cpu = Some CPU
cores = 4
runs = 3
own_cpu_seconds = 1000
other_cpu_seconds = 5
make_all_seconds = 170.4 204.7 210.0
make_test_seconds = 58.3 59.6 61.9
make_all_again_seconds = 0.2 0.2 0.3
TIMES
out=$("$tool" "$dir/three.txt")
expect "$out" '\mrmdef{times:all}{3 min 25 s (2 min 50 s -- 3 min 30 s)}'
expect "$out" '\mrmdef{times:test}{60 s (58 s -- 1 min 2 s)}'
expect "$out" '\mrmdef{times:again}{0.2 s (0.2 s -- 0.3 s)}'
expect "$out" '\mrmdef{times:date}{2026-01-02}'
expect "$out" '\mrmdef{times:cores}{4}'
expect "$out" '\mrmdef{times:cpu}{Some CPU}'
expect "$out" '\mrmdef{times:other}{0.5}'
expect "$out" '\mrmdef{times:measured}{median (min -- max) of 3 runs}'

sed -e 's/^runs = .*/runs = 1/' -e 's/^make_all_seconds = .*/make_all_seconds = 9.87/' "$dir/three.txt" > "$dir/one.txt"
out=$("$tool" "$dir/one.txt")
expect "$out" '\mrmdef{times:all}{9.9 s}'
expect "$out" '\mrmdef{times:measured}{measured once}'
# A time is rounded to whole seconds before it is split into minutes: 179.6 s is 3 min 0 s, not 2 min 60 s.
sed -e 's/^make_all_seconds = .*/make_all_seconds = 119.5 179.6 181.1/' "$dir/three.txt" > "$dir/round.txt"
out=$("$tool" "$dir/round.txt")
expect "$out" '\mrmdef{times:all}{3 min 0 s (2 min 0 s -- 3 min 1 s)}'

printf 'runs = 0\n' > "$dir/none.txt"
out=$("$tool" "$dir/none.txt")
expect "$out" '\mrmdef{times:all}{not measured yet}'

grep -v '^cpu' "$dir/three.txt" > "$dir/lacking.txt"
if "$tool" "$dir/lacking.txt" > /dev/null 2>&1; then echo "build_times_tex: a file without cpu was accepted"; exit 1; fi
echo "build_times_tex test passed"
