#!/usr/bin/env bash
# How long the README's two commands take on this machine, measured as a new user meets them: in a fresh
# clone of this repository's last commit (the Debian packages already installed; a new build directory,
# no compiler cache), `make all`, then `make test`, then `make all` again (nothing left to do), RUNS
# times. Writes doc/build_times.txt (`key = value` lines: the date, the processor, the cores, the 1-, 5-
# and 15-minute load averages before and after each command, and each command's wall time: its one value
# for one run, its minimum, median and maximum for several), from which tools/readme.sh writes the
# README's sentence.
# Timings depend on the machine and its load: run it on an otherwise idle machine. Other work running at
# the same time lengthens them; the file records how much CPU time other processes used meanwhile (the
# machine's busy time from /proc/stat less the commands' own user and system time), and its note says
# whether there was any.
#
# Usage: tools/measure_commands.sh [--keep DIR] [RUNS]   (RUNS: 1 by default, 1 to 20)
#   --keep DIR  makes the clones in DIR (a new directory) instead of a temporary one, and keeps the last:
#               its results and its build, to compare or to reuse without building again.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
usage() { echo "usage: tools/measure_commands.sh [--keep DIR] [RUNS 1..20]" >&2; exit 2; }
keep=
if [[ ${1:-} == --keep ]]; then
  [[ -n ${2:-} && ! -e $2 ]] || { echo "measure_commands: --keep needs a directory that does not exist yet" >&2; usage; }
  keep=$(realpath -m -- "$2")
  shift 2
fi
runs=${1:-1}
[[ $runs =~ ^[0-9]+$ ]] && ((runs >= 1 && runs <= 20)) || usage
work=$(mktemp -d -t mrm-measure.XXXXXX)
trap 'rm -rf -- "$work"' EXIT
clone=${keep:-$work/clone}

# A build as a new user's: no compiler launcher (a cache would hide the compilation), no make flags
# inherited from a calling make.
unset CMAKE_CXX_COMPILER_LAUNCHER CMAKE_C_COMPILER_LAUNCHER MAKEFLAGS MFLAGS MAKELEVEL JOBS

now() { date +%s.%N; }
loadavg() { cut -d' ' -f1-3 /proc/loadavg; }
# The machine's busy CPU time so far, in clock ticks: user, nice, system, irq and softirq of every core
# (/proc/stat; the time the hypervisor took, steal, is not this machine's work).
busy_ticks() { awk '/^cpu / { print $2 + $3 + $4 + $7 + $8 }' /proc/stat; }
ticks=$(getconf CLK_TCK)
loads=()
own_cpu=0 other_cpu=0
# Runs a command in the clone, its output to a log, and records the load averages before and after it,
# its own CPU time (user + system of it and every process it waited for) and the CPU time the machine
# spent on other work meanwhile; sets `elapsed` to its wall time in seconds.
elapsed=
timed() {
  local start end busy_start busy_end cpu
  loads+=("$(loadavg)")
  busy_start=$(busy_ticks)
  start=$(now)
  local TIMEFORMAT='%3U %3S'
  # (the command's output is redirected inside the timed subshell: a redirection of the timed command
  # itself would take time's own report too)
  if ! { time (cd "$clone" && "$@" >>"$work/log" 2>&1); } 2>"$work/cpu"; then
    echo "measure_commands: '$*' failed; the end of its output:" >&2
    tail -n 40 "$work/log" >&2
    exit 1
  fi
  end=$(now)
  busy_end=$(busy_ticks)
  loads+=("$(loadavg)")
  elapsed=$(awk -v s="$start" -v e="$end" 'BEGIN { printf "%.1f", e - s }')
  cpu=$(awk '{ print $1 + $2 }' "$work/cpu")
  own_cpu=$(awk -v a="$own_cpu" -v c="$cpu" 'BEGIN { printf "%.1f", a + c }')
  other_cpu=$(awk -v a="$other_cpu" -v c="$cpu" -v b0="$busy_start" -v b1="$busy_end" -v t="$ticks" \
    'BEGIN { o = (b1 - b0) / t - c; printf "%.1f", a + (o > 0 ? o : 0) }')
}
# The one value of one run; the minimum, median and maximum of several.
stats() {
  if (($# == 1)); then
    echo "$1"
  else
    printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2; printf "%s %.1f %s\n", v[1], m, v[NR] }'
  fi
}

date=$(date -u '+%Y-%m-%d %H:%M UTC')
commit=$(git -C "$root" rev-parse --short HEAD)  # what every run clones
all=() test=() again=()
for ((run = 1; run <= runs; ++run)); do
  rm -rf -- "$clone"
  git clone -q "$root" "$clone"
  echo "measure_commands: run $run of $runs (load average $(loadavg))" >&2
  timed make all
  all+=("$elapsed")
  timed make test
  test+=("$elapsed")
  timed make all
  again+=("$elapsed")
  echo "measure_commands: make all ${all[-1]} s, make test ${test[-1]} s, make all again ${again[-1]} s" >&2
  grep -E '^[0-9]+% tests passed' "$work/log" | tail -n 1 | sed 's/^/measure_commands: make test: /' >&2
done
[[ -z $keep ]] || echo "measure_commands: the last clone is kept in $keep" >&2

# Other work: the CPU time other processes used while the commands ran. Below 2 % of the commands' own
# (the clock ticks' rounding, this script, the system's daemons), the machine was theirs alone.
cores=$(nproc)
load_before=$(echo "${loads[0]}" | cut -d' ' -f1)
load_max=$(printf '%s\n' "${loads[@]}" | awk '{ print $1 }' | sort -g | tail -n 1)
share=$(awk -v o="$other_cpu" -v c="$own_cpu" 'BEGIN { printf "%.1f", 100 * o / c }')
note="no other work ran on the machine: other processes used $other_cpu CPU seconds, $share % of the commands' own $own_cpu"
if awk -v s="$share" 'BEGIN { exit !(s > 2) }'; then
  note="other work ran on the machine during the measurement: other processes used $other_cpu CPU seconds, $share % of the commands' own $own_cpu; the times are longer than on an idle machine"
fi
{
  echo "# Generated by tools/measure_commands.sh (do not edit): wall seconds of the README's commands in a"
  echo "# fresh clone with the packages present (new build directory, no compiler cache): one value for one"
  echo "# run, min median max for several. load_before_after: the 1-, 5- and 15-minute load averages before"
  echo "# and after each command, in order (make all, make test, make all again, for each run)."
  echo "date = $date"
  echo "commit = $commit"
  echo "cpu = $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)"
  echo "cores = $cores"
  echo "runs = $runs"
  echo "load_before_after = $(printf '%s; ' "${loads[@]}" | sed 's/; $//')"
  echo "load_1min_before = $load_before"
  echo "load_1min_max = $load_max"
  echo "own_cpu_seconds = $own_cpu"
  echo "other_cpu_seconds = $other_cpu"
  echo "note = $note"
  echo "make_all_seconds = $(stats "${all[@]}")"
  echo "make_test_seconds = $(stats "${test[@]}")"
  echo "make_all_again_seconds = $(stats "${again[@]}")"
} >"$root/doc/build_times.txt.tmp"
mv "$root/doc/build_times.txt.tmp" "$root/doc/build_times.txt"
cat "$root/doc/build_times.txt"
