#!/usr/bin/env bash
# Hostile input, odd outputs and closed descriptors (ctest runs `bash tests/hostile.sh BIN_DIR`).
#
# The programs are run as a careless user would run them on their own files (the threat model of
# doc/robustness.md, "Output files"), one class at a time, each with cases of its own. What every
# case demands:
#
#   - nothing lost: an output that existed keeps its old bytes unless the run succeeds;
#   - nothing overwritten that the user did not name, and nothing left behind (no temporary file);
#   - no wrong number printed: a run that cannot compute its values fails with a message, it never
#     exits 0 with a non-finite or a wrong value;
#   - a bad request is refused at once (exit status 2, one line naming the option), before any work;
#   - no crash (death by a signal) and no hang: every run has a time limit.
#
# The classes (the summary at the end counts the cases of each):
#
#   temporary      the temporary file of an output: a file or symbolic link at a name the program
#                  would use is never followed nor reused; a new output has the permissions the umask
#                  gives, a replaced one keeps its own;
#   nonregular     `--output -` is the standard output; a device, a FIFO, a directory are refused with
#                  status 2 and left as they were; a symbolic link to a file is followed;
#   descriptors    closed standard descriptors (<&-, >&-, 2>&-) never let an output file take their
#                  place; a program whose standard output cannot be written fails (status 1) and
#                  commits nothing;
#   numbers        the ends of the documented ranges of the bar's length and amplitude give the same
#                  relative errors and scaled energies as the unit bar, all finite;
#   ranges         values inside the documented ranges (or refused with status 2) never crash nor hang;
#   late           sizes, step counts and resources that cannot run are refused with status 2 naming
#                  the option, at once (no late std::bad_alloc, no pivot message, no zero-step run);
#                  allowed values run to the end (a value that does not apply written n/a with its
#                  reason), never fail after the work began;
#   two_outputs    a write error (a file-size limit, a full file system) fails the run with status 1,
#                  and no output of the run is replaced (all or nothing); a file-size limit never kills
#                  a program by SIGXFSZ;
#   leftovers      a valid long file name (up to NAME_MAX) is accepted, a longer one refused;
#   non_finite     no nan or inf in any output: runs at the edges that cannot compute a value exit 0 with n/a
#                  and its reason, or fail and commit nothing;
#   closed_stdout  long_runs (C stdio) fails with a closed standard output or on /dev/full;
#   memory         what does not fit under ulimit -v is refused at once, naming the option; what fails to
#                  allocate all the same is an error with a message, never a crash;
#   inputs         a file to read that is not a regular file (a FIFO, a process substitution, a device) is
#                  refused at once with what it is, never read half or waited on;
#   messages       user text echoed in a message (sweep's lists too) is quoted: one line, escapes escaped,
#                  a long token cut with its size.
#
# Cases that need root (a device node of its own, a full file system) are skipped with a note when not
# run as root.
set -u
set -m  # background runs get the default SIGINT/SIGQUIT, as from a terminal (see kill_during_write.sh)
ulimit -c 0

if (($# != 1)) || [[ ! -x $1/bar1d ]]; then
  echo "usage: bash tests/hostile.sh BIN_DIR (with BIN_DIR/bar1d)" >&2
  exit 2
fi
bin=$(cd "$1" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/hostile.XXXXXX")
background=()
cleanup() {
  local p
  for p in "${background[@]}"; do kill -KILL "$p" 2>/dev/null; done
  chmod -R u+rwx "$work" 2>/dev/null
  if [[ -n ${full_mount:-} ]]; then umount "$full_mount" 2>/dev/null; fi
  rm -rf -- "$work"
}
trap cleanup EXIT

# Time limits: a refusal must come at once; a small run takes well under a second (more under the
# sanitizers).
quick=10
small=60
ranges_limit=30
root=0
((EUID == 0)) && root=1
# AddressSanitizer keeps its own handlers for SIGSEGV, SIGBUS and SIGFPE and reserves terabytes of
# address space (no memory limit can be set): the cases that depend on those are skipped under it.
sanitized=0
grep -q -a __asan_init "$bin/bar1d" && sanitized=1

start_seconds=$SECONDS
declare -A cases failures skips milliseconds
class='' name='' case_failed=0 case_start=0
now_ms() { local t=${EPOCHREALTIME/./}; echo $((t / 1000)); }
finish_case() {
  if [[ -n $name ]] && ((case_failed)); then failures[$class]=$((${failures[$class]:-0} + 1)); fi
  [[ -n $class ]] && milliseconds[$class]=$((${milliseconds[$class]:-0} + $(now_ms) - case_start))
  name=''
}
# begin CLASS NAME: a new case (in a fresh directory, which becomes the working directory).
case_number=0
begin() {
  finish_case
  class=$1 name=$2 case_failed=0 case_start=$(now_ms)
  cases[$class]=$((${cases[$class]:-0} + 1))
  case_number=$((case_number + 1))
  dir=$work/case.$case_number
  mkdir -p "$dir"
  cd "$dir" || exit 1
}
fail() {
  printf 'FAIL [%s] %s: %s\n' "$class" "$name" "$*"
  case_failed=1
}
skip() {
  printf 'SKIP [%s] %s: %s\n' "$class" "$name" "$*"
  cases[$class]=$((${cases[$class]} - 1))
  skips[$class]=$((${skips[$class]:-0} + 1))
  name=''
}

out=$work/stdout
err=$work/stderr
# run LIMIT PROGRAM ARGS...: runs BIN_DIR/PROGRAM in the case's directory, stdout and stderr to files.
run() {
  local limit=$1 program=$2
  shift 2
  timeout -k 5 "$limit" "$bin/$program" "$@" >"$out" 2>"$err"
  status=$?
}
shown_error() { head -c 300 "$err" | tr '\n' ' '; }

# The entries of the case's directory, hidden ones included, one per line.
entries() { ls -A "$dir" | LC_ALL=C sort; }
expect_entries() {
  local expected got
  expected=$(printf '%s\n' "$@" | LC_ALL=C sort | sed '/^$/d')
  got=$(entries)
  [[ $got == "$expected" ]] || fail "files in the directory: [$(echo $got)], expected [$(echo $expected)]"
}
expect_status() {
  local expected=$1
  if ((status == 124 || status == 137)); then
    fail "did not finish within the time limit"
  elif ((status != expected)); then
    fail "exit status $status, expected $expected ($(shown_error))"
  fi
}
# A refusal: status 2, one line on stderr "PROGRAM: ..." containing FRAGMENT, nothing on stdout.
expect_refusal() {
  local program=$1 fragment=$2
  expect_status 2
  local lines message
  lines=$(wc -l <"$err")
  message=$(head -n 1 "$err")
  ((lines == 1)) || fail "stderr has $lines lines, expected 1: $(shown_error)"
  [[ $message == "$program: "*"$fragment"* ]] || fail "the message does not contain \"$fragment\": $message"
  [[ -s $out ]] && fail "wrote to stdout: $(head -c 200 "$out")"
}
# usage_case CLASS NAME PROGRAM FRAGMENT ARGS...: refused at once, nothing created.
usage_case() {
  local case_class=$1 case_name=$2 program=$3 fragment=$4
  shift 4
  begin "$case_class" "$case_name"
  run "$quick" "$program" "$@"
  expect_refusal "$program" "$fragment"
  expect_entries
}
old_content() { printf '# the previous output\n1 2 3\n'; }
# A file with the previous output in it, and its reference copy outside the case's directory.
plant_old() {
  old_content >"$1"
  old_content >"$work/reference"
}
is_old() { cmp -s "$1" "$work/reference"; }

# Small runs of each program (a second or less).
declare -A small_args=(
  [bar1d]="-n 10 -T 1"
  [fig_energy]="-n 10 -T 3"
  [fig_contact_history]="-n 10 -T 3 --exact-points 100"
  [fig_profiles]="-n 10 --instants 0.5,1.5 --exact-points 50"
  [fig_ps_forms]="-n 10 -T 3 --exact-points 100"
  [fig_time_error]="-n 8 -r 16 --largest 2 -k 3 --coarse-elements 4 --coarse-reference-ratio 16 --coarse-steps 3 -T 1.5 --family-from 4 --family-to 4 --family-powers-to 4 --family-reference-ratio 64 --impact-elements 4 --impact-finest 16"
  [fig_convergence]="-n 4 -k 2 -T 1 -j 1"
)
figure_programs=(fig_energy fig_contact_history fig_profiles fig_ps_forms fig_time_error fig_convergence)
# The reference outputs of the small runs, made once in their own directory with nothing unusual.
reference_dir=$work/references
mkdir -p "$reference_dir"
for program in bar1d "${figure_programs[@]}"; do
  [[ -x $bin/$program ]] || continue
  # shellcheck disable=SC2086
  (cd "$reference_dir" && timeout -k 5 "$small" "$bin/$program" ${small_args[$program]} \
    --output "$program.dat" >"$program.stdout" 2>"$program.stderr") ||
    echo "note: the reference run of $program failed: $(head -c 300 "$reference_dir/$program.stderr")"
done
# The small run of PROGRAM with extra arguments: run_small LIMIT PROGRAM ARGS...
run_small() {
  local limit=$1 program=$2
  shift 2
  # shellcheck disable=SC2086
  run "$limit" "$program" ${small_args[$program]} "$@"
}
# same_as_reference FILE PROGRAM: FILE holds the data of the reference run (the header lines that
# echo the output options, `# output = "..."` and `# tex = "..."`, aside).
without_output_names() { grep -v -E '^# (output|tex) = ' "$1"; }
same_as_reference() {
  cmp -s <(without_output_names "$1") <(without_output_names "$reference_dir/$2.dat") ||
    fail "${1##*/} differs from the data of a normal run"
}

# ==== temporary: the temporary file of an output ===================================================

# The temporary names are `.out.dat.tmp.PID.N`, N = 0, 1, ...: the shell's pid is known before exec,
# so a leftover file and symbolic links can be put at the first names before the program starts. The
# creation is exclusive and follows no link: none of them may be written, and the next name is used.
for program in bar1d fig_energy; do
  begin temporary "$program: a file and links at its first temporary names are neither followed nor reused"
  printf 'victim\n' >"$work/victim"
  # shellcheck disable=SC2016
  timeout -k 5 "$small" bash -c '
    printf "left by a killed run\n" > ".out.dat.tmp.$$.0"
    for n in 1 2 3; do ln -s "$1" ".out.dat.tmp.$$.$n"; done
    program=$2; shift 2; exec "$program" "$@"' _ "$work/victim" "$bin/$program" ${small_args[$program]} --output out.dat \
    >"$out" 2>"$err"
  status=$?
  expect_status 0
  [[ $(cat "$work/victim") == victim ]] || fail "the file a planted link points to was written"
  [[ $(cat .out.dat.tmp.*.0) == "left by a killed run" ]] || fail "the file at the first name was changed"
  [[ -f out.dat && ! -L out.dat ]] || fail "out.dat is not a regular file"
  [[ $program == bar1d ]] || same_as_reference out.dat "$program"
  links=$(find . -maxdepth 1 -type l | wc -l)
  ((links == 3)) || fail "the planted links were removed or replaced ($links of 3 left)"
done

for mask in 022 077 002; do
  begin temporary "a new output has the permissions of the umask $mask"
  (umask "$mask" && cd "$dir" && timeout -k 5 "$small" "$bin/bar1d" -n 10 -T 1 --output out.dat >"$out" 2>"$err")
  status=$?
  expect_status 0
  expected=$(printf '%o' $((0666 & ~8#$mask)))
  mode=$(stat -c %a out.dat 2>/dev/null)
  [[ $mode == "$expected" ]] || fail "out.dat has mode $mode, expected $expected"
done

for old_mode in 600 640 664; do
  begin temporary "a replaced output keeps its permissions ($old_mode, under the umask 022)"
  old_content >out.dat
  chmod "$old_mode" out.dat
  (umask 022 && cd "$dir" && timeout -k 5 "$small" "$bin/bar1d" -n 10 -T 1 --output out.dat >"$out" 2>"$err")
  status=$?
  expect_status 0
  mode=$(stat -c %a out.dat 2>/dev/null)
  [[ $mode == "$old_mode" ]] || fail "out.dat has mode $mode, expected $old_mode"
  head -n 1 out.dat | grep -q '^# bar1d' || fail "out.dat does not hold the series"
  expect_entries out.dat
done

# ==== nonregular: outputs that are not regular files ===============================================

begin nonregular "--output -: the data on the standard output, no file named -"
run_small "$small" fig_energy --output -
expect_status 0
same_as_reference "$out" fig_energy
expect_entries

begin nonregular "bar1d --output -: the series and the summary on the standard output"
run_small "$small" bar1d --output - --no-timing
expect_status 0
grep -q '^# bar1d' "$out" || fail "the series is not on the standard output"
grep -q '^err_u0_L2 = ' "$out" || fail "the summary is not on the standard output"
expect_entries

# Anything that exists and is not a regular file is refused before any work, and left as it was: a
# device (as root a private null device, so that a failing program could never replace the system's),
# a FIFO (which would block the program), a directory.
begin nonregular "a character device as the output: refused with status 2, still the device"
null_device=/dev/null
((root)) && mknod null c 1 3 2>/dev/null && null_device=$dir/null
run_small "$quick" fig_energy --output "$null_device"
expect_refusal fig_energy "--output: cannot write \"$null_device\": not a regular file"
[[ -c $null_device ]] || fail "$null_device is no longer a character device"
[[ $null_device == /dev/null ]] && expect_entries || expect_entries null

begin nonregular "a FIFO as the output: refused at once with status 2, no hang"
mkfifo fifo
run_small "$quick" fig_energy --output fifo
expect_refusal fig_energy --output
[[ -p fifo ]] || fail "fifo is no longer a FIFO"
expect_entries fifo

for target in . .. sub sub/ "$work"; do
  begin nonregular "a directory as the output ($target): refused with status 2"
  mkdir sub
  run_small "$quick" bar1d --output "$target"
  expect_refusal bar1d --output
  expect_entries sub
done

begin nonregular "a symbolic link to a regular file: the file replaced, the link kept"
mkdir elsewhere
plant_old elsewhere/real.dat
ln -s elsewhere/real.dat link.dat
run_small "$small" bar1d --output link.dat
expect_status 0
[[ -L link.dat ]] || fail "link.dat is no longer a symbolic link"
head -n 1 elsewhere/real.dat | grep -q '^# bar1d' || fail "elsewhere/real.dat does not hold the series"
expect_entries elsewhere link.dat
[[ $(ls -A elsewhere) == real.dat ]] || fail "files left beside real.dat: $(ls -A elsewhere | tr '\n' ' ')"

# ==== descriptors: closed standard descriptors ====================================================

begin descriptors "fig_energy 2>&-: exit 0, no progress line in the data file"
# shellcheck disable=SC2086
timeout -k 5 "$small" "$bin/fig_energy" ${small_args[fig_energy]} --output out.dat >"$out" 2>&-
status=$?
expect_status 0
same_as_reference out.dat fig_energy
expect_entries out.dat

begin descriptors "fig_energy --tex t.tex 2>&-: neither output takes the place of stderr"
# shellcheck disable=SC2086
timeout -k 5 "$small" "$bin/fig_energy" ${small_args[fig_energy]} --output out.dat --tex t.tex >"$out" 2>&-
status=$?
expect_status 0
same_as_reference out.dat fig_energy
grep -q 'fig_energy:' t.tex && fail "progress lines in t.tex"
expect_entries out.dat t.tex

begin descriptors "fig_energy >&- (writes nothing on stdout): exit 0, data intact"
# shellcheck disable=SC2086
timeout -k 5 "$small" "$bin/fig_energy" ${small_args[fig_energy]} --output out.dat >&- 2>"$err"
status=$?
expect_status 0
same_as_reference out.dat fig_energy

begin descriptors "fig_energy <&- >&- 2>&-: exit 0, data intact, nothing else created"
# shellcheck disable=SC2086
timeout -k 5 "$small" "$bin/fig_energy" ${small_args[fig_energy]} --output out.dat <&- >&- 2>&-
status=$?
expect_status 0
same_as_reference out.dat fig_energy
expect_entries out.dat

begin descriptors "fig_profiles <&-: exit 0, data intact"
# shellcheck disable=SC2086
timeout -k 5 "$small" "$bin/fig_profiles" ${small_args[fig_profiles]} --output out.dat <&- >"$out" 2>"$err"
status=$?
expect_status 0
same_as_reference out.dat fig_profiles

begin descriptors "bar1d >&- (its results go to stdout): status 1, the series not committed"
plant_old out.dat
timeout -k 5 "$small" "$bin/bar1d" -n 10 -T 1 --output out.dat >&- 2>"$err"
status=$?
expect_status 1
grep -q 'standard output' "$err" || fail "the message does not mention the standard output: $(shown_error)"
is_old out.dat || fail "out.dat was replaced although the results could not be delivered"
expect_entries out.dat

begin descriptors "bar1d >&- 2>&-: status 1, no summary inside the series"
timeout -k 5 "$small" "$bin/bar1d" -n 10 -T 1 --output out.dat >&- 2>&-
status=$?
expect_status 1
[[ -e out.dat ]] && grep -q '^err_' out.dat && fail "the summary went into out.dat"
expect_entries

begin descriptors "bar1d > /dev/full: status 1 and a message"
plant_old out.dat
timeout -k 5 "$small" "$bin/bar1d" -n 10 -T 1 --output out.dat >/dev/full 2>"$err"
status=$?
expect_status 1
grep -q 'standard output' "$err" || fail "the message does not mention the standard output: $(shown_error)"
is_old out.dat || fail "out.dat was replaced although the results could not be delivered"

for request in --help --version; do
  begin descriptors "bar1d $request > /dev/full: status 1"
  timeout -k 5 "$quick" "$bin/bar1d" "$request" >/dev/full 2>"$err"
  status=$?
  expect_status 1
  begin descriptors "fig_energy $request >&-: status 1"
  timeout -k 5 "$quick" "$bin/fig_energy" "$request" >&- 2>"$err"
  status=$?
  expect_status 1
done

begin descriptors "fig_energy 2> /dev/full (its progress lines fail): status 1, nothing committed"
plant_old out.dat
# shellcheck disable=SC2086
timeout -k 5 "$small" "$bin/fig_energy" ${small_args[fig_energy]} --output out.dat >"$out" 2>/dev/full
status=$?
expect_status 1
is_old out.dat || fail "out.dat was replaced"
expect_entries out.dat

begin descriptors "a refusal with stderr closed still exits 2 and creates nothing"
timeout -k 5 "$quick" "$bin/bar1d" --elements 1 --output out.dat >"$out" 2>&-
status=$?
expect_status 2
expect_entries

# ==== numbers: the ends of the documented ranges ==================================================
# bar1d accepts L and a in [1e-100, 1e100]. Under x → Lx, t → Lt, u → aLu the benchmark is the one
# with L = a = 1 whatever L and a: the relative errors must be those of the unit bar and the
# energies those of the unit bar times a²L, up to the rounding of the data (1e-16 relative each,
# over 120 steps: 1e-9 is far above it, and far below any real error). The phase (the impact-time
# errors and the period law's predictions) is in time units: divided by L, it is the unit bar's, to
# 1e-9 of the unit bar's time scale (an impact time of order L read to round-off; the drifts it
# measures are of order h/3 = 0.017 on this mesh).
compare_with_unit() {  # compare_with_unit L A: the summary in $out against the unit bar's
  local length=$1 amplitude=$2
  awk -v L="$length" -v a="$amplitude" -v unit="$work/unit_summary" '
    function finite(x) { return x ~ /^-?[0-9]+(\.[0-9]+)?(e[-+][0-9]+)?$/ }
    BEGIN { while ((getline line < unit) > 0) { split(line, f, " = "); base[f[1]] = f[2] } }
    /^# / { next }  # the configuration bar1d echoes first, not a measure
    {
      split($0, f, " = "); key = f[1]; value = f[2]
      if (key == "stress") { if (value != base[key]) printf "stress = %s, the unit bar reports %s\n", value, base[key]; next }
      if (!finite(value)) { printf "%s = %s is not a finite number\n", key, value; next }
      if (!(key in base)) next
      expected = base[key] + 0
      if (key ~ /^energy_/) { value = value / (a * a * L) }
      if (key == "steps" || key ~ /^impacts/) { if (value != expected) printf "%s = %s, the unit bar gives %s\n", key, value, expected; next }
      tolerance = 1e-9 * (expected < 0 ? -expected : expected) + 1e-300
      if (key ~ /impact_error$|drift_per_period$|^final_time_reached$/) { value = value / L; tolerance = 1e-9 }
      difference = value - expected; if (difference < 0) difference = -difference
      if (difference > tolerance) printf "%s = %s (scaled), the unit bar gives %s\n", key, value, expected
    }' "$out"
}
(cd "$work" && timeout -k 5 "$small" "$bin/bar1d" -n 20 -L 1 -a 1 -T 3 --no-timing >"$work/unit_summary" 2>/dev/null)
for length in 1e-100 1e100 1; do
  for amplitude in 1e-100 1e100 1; do
    [[ $length == 1 && $amplitude == 1 ]] && continue
    begin numbers "bar1d -L $length -a $amplitude: the unit bar's relative errors and scaled energies"
    final_time=$(awk -v L="$length" 'BEGIN { printf "%.17g", 3 * L }')
    run "$small" bar1d -n 20 -L "$length" -a "$amplitude" -T "$final_time" --no-timing
    expect_status 0
    problems=$(compare_with_unit "$length" "$amplitude")
    [[ -z $problems ]] || fail "$(echo "$problems" | head -n 3 | tr '\n' ';')"
  done
done
for scheme in be ps; do
  begin numbers "bar1d -s $scheme -L 1e100 -a 1e100: every value finite"
  run "$small" bar1d -s "$scheme" -n 20 -L 1e100 -a 1e100 -T 3e100 --no-timing
  expect_status 0
  grep -v -E '^([A-Za-z_0-9]+ = (-?[0-9.]+(e[-+][0-9]+)?|n/a: .+)|stress = [a-z]+|# [a-z_0-9]+ = .+)$' "$out" | grep -q . && fail "non-finite values: $(grep -v -E '= -?[0-9]' "$out" | head -n 2 | tr '\n' ' ')"
  begin numbers "bar1d -s $scheme -L 1e-100 -a 1e-100 --output: every value of the series finite"
  run "$small" bar1d -s "$scheme" -n 20 -L 1e-100 -a 1e-100 -T 3e-100 --no-timing --output s.dat
  expect_status 0
  # Column 5 (lambda_h) is nan where a level has no multiplier yet (documented); nothing else.
  bad=$(grep -v '^#' s.dat | awk '{ for (i = 1; i <= NF; ++i) if (i != 5 && $i !~ /^-?[0-9.]+(e[-+][0-9]+)?$/) { print; exit } }')
  [[ -z $bad ]] || fail "a non-finite value in the series: $bad"
  # (max_penetration is exactly 0 for these schemes: they enforce the constraint at the levels.)
  grep -v -e '^max_penetration = ' -e '^# ' "$out" | grep -q ' = 0$' && fail "an error of exactly 0: $(grep ' = 0$' "$out" | head -n 1)"
done
# A value that cannot be computed is printed as "name = n/a: the reason" (never nan): accepted beside
# the finite numbers, here and above; so are the name of the contact stress bar1d reports (stress = NAME)
# and the configuration it echoes first (# key = value).
begin numbers "bar1d at the ends of the other ranges (-c 1e6, -b 1e6): finite values or a refusal"
for arguments in "-c 1e6 -n 2 -T 3" "-s ps -b 1e6 -T 3" "-s ps -b 1e6 -c 1e6 -n 2 -T 1e6" "-s be -c 1e6 -n 1000 -T 3" \
  "-s ps --ps-form literal -b 1e-300 -T 3" "-s ps --ps-form literal -b 4.9e-324 -n 4 -T 1" "-e 1 -s ps -T 3"; do
  # shellcheck disable=SC2086
  run "$small" bar1d $arguments --no-timing
  if ((status == 0)); then
    grep -v -E '^([A-Za-z_0-9]+ = (-?[0-9.]+(e[-+][0-9]+)?|n/a: .+)|stress = [a-z]+|# [a-z_0-9]+ = .+)$' "$out" | grep -q . && fail "bar1d $arguments: non-finite values"
  elif ((status == 2)); then
    [[ $(wc -l <"$err") == 1 ]] || fail "bar1d $arguments: refusal without one line"
  else
    fail "bar1d $arguments: exit status $status ($(shown_error)), expected 0 or a refusal (2)"
  fi
done

# ==== ranges: inside the documented ranges, no crash and no hang ==================================
# Each value is allowed by the help. Whatever the program does with it, it must not die by a
# signal, hang, or leave a file: it either runs (status 0) or refuses the value (status 2) naming the
# option.
range_case() {  # range_case PROGRAM OPTION-NAME ARGS...
  local program=$1 option=$2
  shift 2
  begin ranges "$program $*"
  run "$ranges_limit" "$program" "$@" --output out.dat
  if ((status == 0)); then
    [[ -s out.dat ]] || fail "status 0 but no output"
    expect_entries out.dat
  elif ((status == 2)); then
    expect_refusal "$program" "$option"
    expect_entries
  else
    expect_status 2
    expect_entries
  fi
}
range_case fig_profiles --instants --instants 1e20
range_case fig_profiles --instants --instants 1e12
range_case fig_profiles --instants --instants 0,1e300
range_case fig_profiles --exact-points --exact-points 2000000000
range_case fig_profiles --exact-points --exact-points 9223372036854775807
range_case fig_contact_history --exact-points --exact-points 2000000000
range_case fig_ps_forms --exact-points --exact-points 2000000000
range_case fig_ps_forms --final-time --final-time 1e-300
range_case fig_contact_history --final-time --final-time 1e-300
range_case fig_energy --final-time --final-time 1e300
range_case fig_time_error --reference-ratio -r 1099511627776
range_case fig_time_error --reference-ratio -r 4611686018427387904
range_case fig_time_error --largest --largest 4611686018427387904
range_case fig_time_error --steps -k 9223372036854775807
range_case fig_time_error --elements -n 9223372036854775807
range_case fig_convergence --threads -n 4 -k 2 -T 1 -j 100000
range_case fig_convergence --threads -n 4 -k 2 -T 1 -j 9223372036854775807
range_case fig_convergence --coarsest -n 4611686018427387904 -k 2
range_case fig_convergence --coarsest -n 1099511627776 -k 20
range_case fig_convergence --refinements -n 2 -k 9223372036854775807
range_case fig_energy --elements -n 9223372036854775807
range_case fig_contact_history --elements -n 4611686018427387904
range_case fig_profiles --elements -n 9223372036854775807 --instants 0
range_case fig_ps_forms --courant -c 1e-320

# ==== late: what cannot run is refused at once, naming the option ==================================
for program in fig_energy fig_contact_history fig_profiles fig_ps_forms fig_time_error; do
  usage_case late "$program --elements 100000000: refused before any work" "$program" --elements --elements 100000000
done
usage_case late "fig_convergence --coarsest 100000000: refused before any work" fig_convergence --coarsest --coarsest 100000000
for program in fig_energy fig_contact_history fig_profiles fig_ps_forms; do
  usage_case late "$program --courant 1e300: refused" "$program" --courant --courant 1e300
  usage_case late "$program --courant 1e-300: refused" "$program" --courant --courant 1e-300
done
usage_case late "bar1d --final-time 1e-300: zero steps refused" bar1d --final-time --final-time 1e-300
usage_case late "bar1d --final-time 1e-12 (zero steps) refused" bar1d --final-time --final-time 1e-12
usage_case late "bar1d -L 1e100 --final-time 1: zero steps refused" bar1d --final-time -L 1e100 --final-time 1
usage_case late "fig_energy --final-time 1e-300: zero steps refused" fig_energy --final-time --final-time 1e-300
usage_case late "fig_convergence --final-time 1e-300: zero steps refused" fig_convergence --final-time --final-time 1e-300 -n 4 -k 2
usage_case late "fig_time_error --final-time 1e-300: zero steps refused" fig_time_error --final-time --final-time 1e-300
usage_case late "fig_profiles --instants 1e300: refused" fig_profiles --instants --instants 1e300
usage_case late "cn_large_step --final-time 1e-300: zero steps refused" cn_large_step --final-time --final-time 1e-300
usage_case late "bench_step --repetitions 4611686018427387904: refused" bench_step --repetitions --repetitions 4611686018427387904
usage_case late "bench_step --batch-ms 1e300: refused" bench_step --batch-ms --batch-ms 1e300

# Memory: a run that needs more memory than the process may have is refused before it starts.
begin late "bar1d --elements 1e7 with 300 MB of address space: refused, naming --elements"
if ((sanitized)); then
  skip "AddressSanitizer reserves its shadow memory: no address-space limit can be set"
else
  (ulimit -v 300000 && cd "$dir" && timeout -k 5 "$quick" "$bin/bar1d" --elements 10000000 -T 1e-6 -c 1e-6 >"$out" 2>"$err")
  status=$?
  expect_refusal bar1d --elements
  expect_entries
fi
begin late "fig_convergence -n 65536 -k 8 with 300 MB: refused, naming the option"
if ((sanitized)); then
  skip "AddressSanitizer reserves its shadow memory: no address-space limit can be set"
else
  (ulimit -v 300000 && cd "$dir" && timeout -k 5 "$quick" "$bin/fig_convergence" -n 65536 -k 8 -j 1 >"$out" 2>"$err")
  status=$?
  expect_refusal fig_convergence --
  expect_entries
fi

# ==== two_outputs: all or nothing, write errors ====================================================
# A write error is an error, never a truncated file: with the file-size limit at 1 kB (ulimit -f 1,
# SIGXFSZ ignored so that the write fails with EFBIG instead of killing the run), every output fails;
# none is replaced and no temporary is left.
for program in fig_energy bar1d; do
  begin two_outputs "$program with a write error (file-size limit): status 1, the outputs intact, nothing left"
  plant_old out.dat
  old_content >t.tex
  extra=(--tex t.tex)
  [[ $program == bar1d ]] && extra=()
  # shellcheck disable=SC2086
  (cd "$dir" && trap '' XFSZ && ulimit -f 1 && exec timeout -k 5 "$small" "$bin/$program" ${small_args[$program]} \
    --output out.dat "${extra[@]}" >"$out" 2>"$err")
  status=$?
  expect_status 1
  grep -q 'out.dat' "$err" || fail "the message does not name the output: $(shown_error)"
  is_old out.dat || fail "out.dat was replaced although its write failed"
  is_old t.tex || fail "t.tex was replaced although the other output failed"
  expect_entries out.dat t.tex
done
begin two_outputs "--tex on a full file system: the output keeps its old content, no temporary left"
full_mount=''
if ((root)) && mkdir "$work/fullfs" && mount -t tmpfs -o size=64k tmpfs "$work/fullfs" 2>/dev/null; then
  full_mount=$work/fullfs
  head -c 60000 /dev/zero >"$full_mount/filler" 2>/dev/null
  head -c 100000 /dev/zero >>"$full_mount/filler" 2>/dev/null
  plant_old out.dat
  run "$small" fig_energy -n 40 -T 30 --output out.dat --tex "$full_mount/t.tex"
  ((status == 1 || status == 2)) || fail "exit status $status, expected a failure"
  is_old out.dat || fail "out.dat was replaced although --tex failed"
  expect_entries out.dat
  [[ $(ls -A "$full_mount") == filler ]] || fail "left on the full file system: $(ls -A "$full_mount" | tr '\n' ' ')"
  umount "$full_mount"
  full_mount=''
else
  skip "needs root to mount a small tmpfs"
fi

# ==== leftovers: interrupted runs and long names ==================================================
# An interrupted run leaves the old output intact and at most its hidden temporary (the signals
# themselves: tests/kill_during_write.sh).
for length in 244 255; do
  begin leftovers "an output name of $length characters is accepted"
  long=$(printf 'x%.0s' $(seq $((length - 4)))).dat
  run_small "$small" fig_energy --output "$long"
  expect_status 0
  same_as_reference "$long" fig_energy
  expect_entries "$long"
done
begin leftovers "an output name of 256 characters: refused with status 2 naming --output"
long=$(printf 'x%.0s' $(seq 252)).dat
run_small "$quick" fig_energy --output "$long"
expect_refusal fig_energy --output
expect_entries

# ==== non_finite: no nan or inf in any output ======================================================

# Runs at the edges (two elements, Courant numbers far above one, few exact points), and their
# neighbours: each exits 0 with every output free of a non-finite
# word (a value that cannot be computed is written n/a with the reason), or fails (status 1 or 2) and
# commits nothing. The check is the word test of output_file.hpp (NonFiniteWatch): a word of letters,
# digits and '_' that reads nan, inf or infinity in any case.
has_non_finite() { grep -q -i -w -E 'nan|inf|infinity' "$@" 2>/dev/null; }
non_finite_case() {
  local program=$1
  shift
  begin non_finite "$program $*: no nan in its outputs"
  run "$small" "$program" "$@" --output o.dat --tex o.tex
  if ((status == 0)); then
    has_non_finite o.dat o.tex "$out" && fail "a non-finite word in an output: $(grep -i -w -E -m1 'nan|inf|infinity' o.dat o.tex "$out")"
  elif ((status == 1 || status == 2)); then
    [[ -e o.dat || -e o.tex ]] && fail "status $status but an output was committed"
  else
    expect_status 0
  fi
}
non_finite_case fig_contact_history --elements 2
non_finite_case fig_contact_history --courant 1e6
non_finite_case fig_contact_history --exact-points 10
non_finite_case fig_contact_history
non_finite_case fig_contact_history --elements 2 --courant 1e6 --exact-points 10 --final-time 0.1
non_finite_case fig_smooth_benchmarks --courant 100
non_finite_case fig_smooth_benchmarks --elements 2 --courant 16
non_finite_case fig_profiles --elements 2 --courant 1e6
non_finite_case fig_energy --elements 2 --courant 1e6
non_finite_case fig_phase --elements 2 --courant 10 --periods 2
begin non_finite "bench_step --repetitions 1 on sizes below 2^10: the slopes are n/a, not nan"
run 120 bench_step --quick --repetitions 1 --min-log2 4 --max-log2 6 --output b.dat --tex b.tex --markdown b.md
expect_status 0
has_non_finite b.dat b.tex b.md "$out" && fail "a non-finite word: $(grep -i -w -E -m1 'nan|inf|infinity' b.dat b.tex b.md "$out")"
grep -q '^# slope_cn = n/a' b.dat || fail "the slope of cn is not n/a with its reason"
begin non_finite "bar1d -s ps --output: the level without a multiplier is n/a"
run "$small" bar1d -s ps --no-timing --output o.dat
expect_status 0
has_non_finite o.dat "$out" && fail "a non-finite word in an output"
grep -q ' n/a ' o.dat || fail "no n/a for the level without a multiplier"

# ==== closed_stdout: every program, the test programs included, fails on a closed or full stdout ====

# (long_runs prints with C's stdio, which guarded_main checks as well.)
for target in closed full; do
  begin closed_stdout "long_runs with its standard output $target: status 1"
  if [[ $target == closed ]]; then
    timeout -k 5 "$small" "$bin/long_runs" --elements 4 --periods 1 --large-step-periods 1 >&- 2>"$err"
  else
    timeout -k 5 "$small" "$bin/long_runs" --elements 4 --periods 1 --large-step-periods 1 >/dev/full 2>"$err"
  fi
  status=$?
  expect_status 1
  grep -q '^long_runs: error: writing the standard output failed' "$err" || fail "no message: $(shown_error)"
done

# ==== memory: sizes that do not fit under a memory limit are refused before the run (class 4) ======

if ((sanitized)); then
  begin memory "under ulimit -v: skipped"
  skip "AddressSanitizer reserves terabytes of address space"
else
  begin memory "bar1d --benchmark smooth-impact -T 1e5 under a 1 GB limit: refused naming --final-time"
  (ulimit -v 1000000 && exec timeout -k 5 "$quick" "$bin/bar1d" --benchmark smooth-impact -T 1e5 >"$out" 2>"$err")
  status=$?
  expect_refusal bar1d "--final-time: the exact solution of"
  begin memory "a million-sample --initial-data file under a 1 GB limit: refused naming --initial-data"
  awk 'BEGIN { n = 1000000; for (k = 0; k <= n; ++k) printf "%.17g %.17g 0\n", k / n, 0.5 * (1 - k / n) }' >big.dat
  (ulimit -v 1000000 && exec timeout -k 5 "$small" "$bin/bar1d" --initial-data big.dat >"$out" 2>"$err")
  status=$?
  expect_refusal bar1d "--initial-data: "
fi

# ==== late, continued: allowed values run to the end ==============================================
# Each value is inside its documented range; the run exits 0 with finite values (a value that does not
# apply written n/a with its reason), before or without any error. The configuration lines that open the
# output (`# key = value`: what ran, as given) are not computed values and are not checked.
finite_summary() {
  grep -v -E '^(# [a-z_0-9]+ = .+|[A-Za-z_0-9]+ = (-?[0-9.]+(e[-+][0-9]+)?|n/a: .+)|stress = [a-z]+)$' "$out" | head -n 2
}
late_run_case() {  # late_run_case NAME ARGS...: status 0, one line per value, each finite or n/a
  local case_name=$1
  shift
  begin late "$case_name"
  run "$small" bar1d "$@" --no-timing
  expect_status 0
  [[ -z $(finite_summary) ]] || fail "values that are not finite numbers nor n/a: $(finite_summary | tr '\n' ' ')"
  [[ -s $err ]] && fail "wrote to stderr: $(shown_error)"
  expect_entries
}
late_run_case "bar1d --grading 1.05 -m consistent: the first-order law's value n/a (no massless node)" --grading 1.05 -m consistent
grep -q '^period_law_first_order_drift_change_vs_mod3 = n/a: ' "$out" || fail "the first-order law is not n/a with its reason"
late_run_case "bar1d --grading 1.05 -n 2: the graded mesh's error measures on two elements" --grading 1.05 -n 2
late_run_case "bar1d --benchmark smooth-impact -T 1e-9: one short step, the solution not tabulated" --benchmark smooth-impact -T 1e-9
late_run_case "bar1d --benchmark grazing -T 1e-9" --benchmark grazing -T 1e-9

# ==== inputs: files to read that are not regular files ==============================================
# A FIFO would block the program until a writer comes, a pipe (a process substitution) cannot be read
# twice (counted, then parsed): both are refused at once, with what they are.
begin inputs "bar1d --initial-data FIFO: refused at once, not blocked"
mkfifo fifo
run "$quick" bar1d --initial-data fifo
expect_refusal bar1d '--initial-data: "fifo": is a FIFO or a pipe'
expect_entries fifo
begin inputs "bar1d --initial-data <(cat FILE): refused as a pipe, not as a short file"
printf '0 0.5 0\n0.5 0.25 0\n1 0 0\n' >"$work/data.dat"
timeout -k 5 "$quick" "$bin/bar1d" --initial-data <(cat "$work/data.dat") >"$out" 2>"$err"
status=$?
expect_refusal bar1d ': is a FIFO or a pipe (a process substitution <(...) is one), not a regular file'
begin inputs "bar1d --initial-data /dev/zero: refused as a device, not read forever"
run "$quick" bar1d --initial-data /dev/zero
expect_refusal bar1d '--initial-data: "/dev/zero": is a character device, not a regular file'
begin inputs "fig_order_map --sweep FIFO: refused at once, not blocked"
mkfifo fifo
run "$quick" fig_order_map --sweep fifo --output o.dat
expect_refusal fig_order_map '--sweep: cannot read "fifo": it is a FIFO or a pipe'
expect_entries fifo

# ==== messages: every echo of user text quoted, one line, cut ======================================
begin messages "sweep --schemes with a 100 kB token: one line, cut with its size"
run "$quick" sweep --schemes "$(printf 'c%.0s' $(seq 100000))" --output s.dat
expect_refusal sweep '--schemes: unknown value "cccccccccc'
grep -q '…" (100000 bytes) (allowed: ' "$err" || fail "the token is not cut with its size: $(head -c 200 "$err")"
(($(wc -c <"$err") < 400)) || fail "the message has $(wc -c <"$err") bytes"
expect_entries
begin messages "sweep --masses with an escape sequence: escaped"
run "$quick" sweep --masses $'mod3\e[2J' --output s.dat
expect_refusal sweep '--masses: "mod3\u001b[2J"'
grep -q $'\e' "$err" && fail "the escape character reached the terminal"
expect_entries

# ==== write errors: a file-size limit is an error, not a signal ===================================
# Under ulimit -f (SIGXFSZ at its default, as a shell leaves it) a write beyond the limit fails as a
# write error: status 1, a message naming the output, nothing committed, no death by SIGXFSZ.
for program in fig_energy bar1d sweep; do
  begin two_outputs "$program under ulimit -f 1 (SIGXFSZ not ignored by the caller): status 1 naming the output"
  plant_old out.dat
  case $program in
    sweep) arguments=(--schemes cn,be --masses mod1,mod2,mod3 --elements 16,24,32 --courants 0.5,1,1.5) ;;
    *) read -r -a arguments <<<"${small_args[$program]}" ;;
  esac
  # (perl restores SIGXFSZ's default, which a shell that found it ignored cannot.)
  (cd "$dir" && ulimit -f 1 && exec perl -e '$SIG{XFSZ} = "DEFAULT"; exec @ARGV or die' timeout -k 5 "$small" \
    "$bin/$program" "${arguments[@]}" --output out.dat >"$out" 2>"$err")
  status=$?
  expect_status 1
  grep -q 'out.dat' "$err" || fail "the message does not name the output: $(shown_error)"
  is_old out.dat || fail "out.dat was replaced although its write failed"
  expect_entries out.dat
done

# ==== memory, continued: what cannot be allocated is an error, never a crash =======================
if ((sanitized)); then
  begin memory "under ulimit -v: skipped"
  skip "AddressSanitizer reserves terabytes of address space"
else
  # The batched step's aligned arrays are checked (lib/batched/batched_step.cpp): a failed allocation is
  # an error with a message (status 1), or the run is refused before it starts (status 2), never SIGSEGV.
  begin memory "fig_convergence -n 2 -k 20 -T 3 under a 4 GB limit: an error or a refusal, no crash"
  (ulimit -v 4194304 && cd "$dir" && exec timeout -k 5 120 "$bin/fig_convergence" -n 2 -k 20 -T 3 -o o.dat >"$out" 2>"$err")
  status=$?
  ((status == 1 || status == 2 || status == 0)) || fail "exit status $status ($(shown_error)): a crash or a hang"
  ((status == 0)) || [[ $(wc -l <"$err") == 1 && ! -e o.dat ]] || fail "status $status without one line, or an output: $(shown_error)"
  begin memory "sweep of N = 1e5 on 2 threads under a 500 MB limit: refused naming --elements"
  (ulimit -v 500000 && cd "$dir" && exec timeout -k 5 "$quick" "$bin/sweep" --schemes cn,be --masses mod1,mod2,mod3,consistent \
    --elements 100000 --courants 50,60,70,80 -T 0.01 --threads 2 --output s.dat >"$out" 2>"$err")
  status=$?
  expect_refusal sweep "--elements: "
  expect_entries
  begin memory "fig_family --threads 256 under a 1 GB limit: the threads' stacks refused naming --threads"
  (ulimit -v 1000000 && ulimit -s 8192 && cd "$dir" && exec timeout -k 5 "$quick" "$bin/fig_family" --threads 256 --output o.dat >"$out" 2>"$err")
  status=$?
  expect_refusal fig_family "--threads: the stacks of 255 more threads"
  expect_entries
fi

finish_case
cd "$work" || exit 1

# ==== Summary =====================================================================================
total=0
total_failed=0
echo
echo "hostile: cases by class (failed, skipped, time)"
for c in temporary nonregular descriptors numbers ranges late inputs messages two_outputs leftovers non_finite closed_stdout memory; do
  printf '  %-12s %3d cases, %3d failed, %d skipped, %5.1f s\n' "$c" "${cases[$c]:-0}" "${failures[$c]:-0}" \
    "${skips[$c]:-0}" "$((${milliseconds[$c]:-0} / 100))e-1"
  total=$((total + ${cases[$c]:-0}))
  total_failed=$((total_failed + ${failures[$c]:-0}))
done
echo "hostile: $total cases, $total_failed failed, in $((SECONDS - start_seconds)) s"
((total_failed == 0))
