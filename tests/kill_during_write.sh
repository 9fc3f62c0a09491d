#!/usr/bin/env bash
# A run killed while it writes its output never leaves a partial file under the output's name (ctest
# runs `bash tests/kill_during_write.sh BIN_DIR`).
#
# An output file holds known content. A long bar1d run (N = 2000, T = 1000: minutes of work) writes
# its time series to the same path; once its temporary file `.series.dat.tmp.PID.0` exists and has
# grown (the run is in the middle of writing), the run is stopped by a signal. Then:
#
#   - the run ended by that signal (exit status 128 + signal number);
#   - the output file still holds the old content, byte for byte;
#   - nothing else is left but the hidden temporary (no handler removes it: the threat model of
#     doc/robustness.md, "Output files", allows it);
#   - the next run writing the same output succeeds and replaces it.
#
# Job control is switched on so that the background run does not inherit an ignored SIGINT (a
# non-interactive shell starts background commands with SIGINT and SIGQUIT ignored).
set -u
set -m

if (($# != 1)) || [[ ! -x $1/bar1d ]]; then
  echo "usage: bash tests/kill_during_write.sh BIN_DIR (with BIN_DIR/bar1d)" >&2
  exit 2
fi
bar1d=$(cd "$1" && pwd)/bar1d
work=$(mktemp -d "${TMPDIR:-/tmp}/kill_during_write.XXXXXX")
pid=''
cleanup() {
  [[ -n $pid ]] && kill -KILL "$pid" 2>/dev/null
  rm -rf -- "$work"
}
trap cleanup EXIT

failures=0
fail() {
  printf 'FAIL %s\n' "$*"
  failures=$((failures + 1))
}

target=$work/series.dat
printf '# the previous output\n1 2 3\n' >"$work/reference"
cp "$work/reference" "$target"

# Waits (up to 30 s) until the file exists and holds data (its first buffer written out); prints its
# size.
wait_until_written() {
  local file=$1 size=0 tries=0
  while ((tries < 600)); do
    size=$(stat -c %s "$file" 2>/dev/null || echo 0)
    ((size > 0)) && { echo "$size"; return 0; }
    sleep 0.05
    tries=$((tries + 1))
  done
  return 1
}

for signal in TERM INT KILL; do
  "$bar1d" --elements 2000 --courant 0.5 --final-time 1000 --output "$target" >/dev/null 2>"$work/stderr" &
  pid=$!
  temporary=$work/.series.dat.tmp.$pid.0
  if ! size=$(wait_until_written "$temporary"); then
    fail "SIG$signal: the temporary file ${temporary##*/} did not appear and grow within 30 s"
    kill -KILL "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    pid=''
    continue
  fi
  kill "-$signal" "$pid"
  wait "$pid"
  status=$?
  pid=''
  expected=$((128 + $(kill -l "$signal")))
  ((status == expected)) || fail "SIG$signal: exit status $status, expected $expected ($(head -c 300 "$work/stderr"))"
  cmp -s "$work/reference" "$target" || fail "SIG$signal: the previous output was changed"
  left=$(cd "$work" && ls -A | grep -v -x -e reference -e series.dat -e stderr -e "${temporary##*/}")
  [[ -z $left ]] || fail "SIG$signal: files left besides the hidden temporary: $left"
  echo "SIG$signal after $size bytes written: previous output intact, at most ${temporary##*/} left"
  rm -f -- "$temporary"
done

# A leftover temporary does not stop the next run.
printf 'left by a killed run\n' >"$work/.series.dat.tmp.leftover"
"$bar1d" --elements 10 --final-time 1 --output "$target" >/dev/null 2>"$work/stderr" ||
  fail "the run after the kills failed: $(head -c 300 "$work/stderr")"
head -n 1 "$target" | grep -q '^# bar1d' || fail "the run after the kills did not write its output"

((failures == 0)) && echo "kill_during_write: all checks passed" || echo "kill_during_write: $failures failures"
((failures == 0))
