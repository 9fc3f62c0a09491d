#!/usr/bin/env bash
# The committed fine-mesh study (doc/results/field_asymptotics.{dat,tex}, written by `make
# field-asymptotics` and read by the report) against this build: field_asymptotics on N = 20 … 160 must
# give, byte for byte, the committed rows of N = 80 and 160 in each of the 15 error blocks and in the
# release block (54 rows), so that the committed file stays this code's output where a rerun is cheap.
# Usage: field_asymptotics_committed.sh BIN_DIR
set -euo pipefail
bin=$1
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
committed=$root/doc/results/field_asymptotics.dat
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin/field_asymptotics" --coarsest 20 --refinements 4 --threads 2 --output "$tmp/coarse.dat" > "$tmp/stdout" 2> "$tmp/stderr"
# The rows of N = 80 and 160, each prefixed by its block: an error row starts with N, a release row has
# N in its third field.
rows() {
  awk '/^# block / { block = $3; sub(":", "", block) } !/^#/ && NF > 0 && ($1 == 80 || $1 == 160 || $3 == 80 || $3 == 160) { print block ": " $0 }' "$1"
}
rows "$committed" > "$tmp/committed.rows"
rows "$tmp/coarse.dat" > "$tmp/rerun.rows"
count=$(wc -l < "$tmp/rerun.rows")
if ((count != 54)); then
  echo "field_asymptotics_committed: the rerun has $count rows of N = 80 and 160, not 54"
  exit 1
fi
if ! diff "$tmp/committed.rows" "$tmp/rerun.rows"; then
  echo "field_asymptotics_committed: doc/results/field_asymptotics.dat is not this build's output (above:"
  echo "  < committed, > rerun); regenerate it with make field-asymptotics"
  exit 1
fi
echo "field_asymptotics_committed: the $count rows of N = 80 and 160 equal the committed ones"
