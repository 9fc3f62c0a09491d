#!/usr/bin/env bash
# A run killed while it writes its output leaves the previous output intact (ctest runs `bash
# tests/kill_during_write.sh BIN_DIR`).
#
# An output file holds known content. A long bar1d run (N = 2000, T = 1000: minutes of work) writes
# its time series to the same path; once its temporary file exists and has grown twice (the run is
# in the middle of writing), the run is stopped by a signal. Then:
#
#   - the run ended by that signal (exit status 128 + signal number);
#   - the output file still holds the old content, byte for byte;
#   - for SIGTERM, SIGINT and SIGHUP the temporary file is gone (cli::AtomicFile's handler removes
#     it); SIGKILL cannot be caught, so its temporary file stays: the test reports it, and checks
#     that the next run writing the same output removes it (the process that wrote it is gone);
#   - no other file appeared.
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

# Waits (up to 30 s) until the temporary file of process PID exists and its size has grown twice;
# prints its path and its last size. Its name is `.series.dat.tmp.PID.` and random characters
# (cli::AtomicFile).
wait_until_growing() {
  local pid=$1 file='' size=-1 growths=0 new tries=0 candidates
  while ((growths < 2 && tries < 600)); do
    [[ -z $file ]] && candidates=("$work/.series.dat.tmp.$pid."*) && [[ -e ${candidates[0]} ]] && file=${candidates[0]}
    if [[ -n $file && -e $file ]]; then
      new=$(stat -c %s "$file")
      if ((new > size && new > 0)); then
        ((size >= 0)) && growths=$((growths + 1))
        size=$new
      fi
    fi
    sleep 0.05
    tries=$((tries + 1))
  done
  ((growths >= 2)) && echo "$file $size"
}

for signal in TERM INT HUP KILL; do
  "$bar1d" --elements 2000 --courant 0.5 --final-time 1000 --output "$target" >/dev/null 2>"$work/stderr" &
  pid=$!
  read -r temporary size < <(wait_until_growing "$pid")
  if [[ -z $size ]]; then
    fail "SIG$signal: the temporary file .series.dat.tmp.$pid.* did not appear and grow within 30 s"
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
  left=$(cd "$work" && ls -A | grep -v -x -e reference -e series.dat -e stderr)
  if [[ $signal == KILL ]]; then
    if [[ $left == "${temporary##*/}" ]]; then
      echo "SIGKILL after $size bytes written: the temporary file ${temporary##*/} remains (SIGKILL cannot be caught)"
      # The next run writing the same output removes it.
      "$bar1d" --elements 10 --final-time 1 --output "$target" >/dev/null 2>"$work/stderr" ||
        fail "the run after SIGKILL failed: $(head -c 300 "$work/stderr")"
      [[ -e $temporary ]] && fail "the run after SIGKILL did not remove the stale temporary file"
      head -n 1 "$target" | grep -q '^# bar1d' || fail "the run after SIGKILL did not write its output"
      left=$(cd "$work" && ls -A | grep -v -x -e reference -e series.dat -e stderr)
      [[ -z $left ]] || fail "files left after the run that followed SIGKILL: $left"
    else
      fail "SIGKILL: expected the temporary file ${temporary##*/} alone to remain, found: ${left:-nothing}"
    fi
  else
    [[ -z $left ]] && echo "SIG$signal after $size bytes written: previous output intact, no temporary file left" ||
      fail "SIG$signal: files left: $left"
  fi
done

((failures == 0)) && echo "kill_during_write: all checks passed" || echo "kill_during_write: $failures failures"
((failures == 0))
