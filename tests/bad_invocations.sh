#!/usr/bin/env bash
# Bad command lines, given to every program of BIN_DIR (ctest runs `bash tests/bad_invocations.sh
# BIN_DIR`). Every program shares mrm::cli::Parser, so every program must answer a bad command line
# the same way:
#
#   - exit status 2 (or the status listed for the case);
#   - one line on stderr, "<program>: ...", that contains the expected fragment (at least the
#     option's name);
#   - nothing on stdout;
#   - no file created, removed or changed in the working directory, and an existing output file
#     given with the bad options left byte for byte as it was.
#
# and `--help`, `-h` and `--version` must exit 0 with their text on stdout and nothing on stderr.
#
# The cases come from two sources:
#
#   1. generic cases, derived for each program from its own `--help` (the format printed by
#      cli::Parser::print_help): unknown options, positional arguments, every option without its
#      value and given twice, every numeric option given malformed numbers ("", "1e", "nan", "inf",
#      "12abc", "1e400", ...), every choice given a value outside its list, every flag given a
#      value, every pair of options the help says exclude each other ("excludes --x"), and every
#      output file option given a missing directory, a directory and an empty path. The kind of
#      each option (integer, real, choice, string) is found by probing: `--option zzz --zz-probe`
#      fails on the value for a number or a choice, with the message saying which, and on the
#      unknown option `--zz-probe` for a string, so the probe never runs the program. Programs added
#      later are covered without editing this file.
#   2. the table tests/bad_invocations.txt, one case per line,
#        program | arguments (shell words) | expected exit status | expected message fragment
#      for what cannot be derived from the help: values out of an option's range, contradictory
#      combinations, failures during the run. Lines for programs that are not built are skipped.
#
# When a program has output file options (a string option whose name contains "output" or whose
# help says "write"), each case also gives every such option not already in the case an existing
# file with known content (appended after the case's arguments, so that the case's own error comes
# first), and checks that the file is left intact. Each run has a time limit (a hang fails).
#
# It prints the number of bad invocations tried for each program; bar1d must have at least 30.
set -u
shopt -s nullglob

if (($# != 1)) || [[ ! -d $1 ]]; then
  echo "usage: bash tests/bad_invocations.sh BIN_DIR" >&2
  exit 2
fi
bin=$(cd "$1" && pwd)
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
table=$here/bad_invocations.txt
scratch=$(mktemp -d "${TMPDIR:-/tmp}/bad_invocations.XXXXXX")
trap 'rm -rf -- "$scratch"' EXIT
time_limit=30

failures=0
fail() {
  printf 'FAIL %s\n' "$*"
  failures=$((failures + 1))
}

# The state of a directory: name, type, size, inode and modification time (to the nanosecond) of
# every entry, hidden ones included. A file rewritten in place changes its time, one replaced by a
# rename its inode.
snapshot() {
  find "$1" -mindepth 1 -printf '%P %y %s %i %T@\n' | sort
}

# ---- One bad invocation --------------------------------------------------------------------------
# check_bad PROGRAM EXPECTED_STATUS FRAGMENT ARGS... : runs PROGRAM in its working directory with
# ARGS (plus the existing output files, see above) and checks status, stdout, stderr and the files.
declare -A tried
check_bad() {
  local program=$1 expected_status=$2 fragment=$3
  shift 3
  local -a args=("$@")
  local work=$scratch/work.$program
  local option given
  # Existing output files for the output options not in the case.
  for option in "${output_options[@]}"; do
    given=0
    for argument in "${args[@]}"; do
      if [[ $argument == "$option" || $argument == "$option="* ||
        (-n ${short_of[$option]:-} && $argument == "${short_of[$option]}") ]]; then
        given=1
      fi
    done
    if ((!given)); then
      args+=("$option" "$work/existing${option//-/_}.dat")
    fi
  done
  local before after status
  before=$(snapshot "$work")
  (cd "$work" && timeout "$time_limit" "$bin/$program" "${args[@]}" >"$scratch/stdout" 2>"$scratch/stderr")
  status=$?
  after=$(snapshot "$work")
  tried[$program]=$((${tried[$program]:-0} + 1))
  local shown
  shown=$(printf '%q ' "${args[@]}")
  local problems=()
  if ((status == 124)); then
    problems+=("did not finish within ${time_limit} s")
  elif ((status != expected_status)); then
    problems+=("exit status $status, expected $expected_status")
  fi
  [[ -s $scratch/stdout ]] && problems+=("wrote to stdout: $(head -c 200 "$scratch/stdout")")
  local lines
  lines=$(wc -l <"$scratch/stderr")
  if ((lines != 1)); then
    problems+=("stderr has $lines lines, expected 1: $(head -c 400 "$scratch/stderr")")
  fi
  local message
  message=$(head -n 1 "$scratch/stderr")
  [[ $message == "$program: "* ]] || problems+=("stderr does not start with \"$program: \": $message")
  [[ $message == *"$fragment"* ]] || problems+=("stderr does not contain \"$fragment\": $message")
  [[ $before == "$after" ]] || problems+=("files changed: $(diff <(echo "$before") <(echo "$after") | grep '^[<>]' | head -5 | tr '\n' ' ')")
  if ((${#problems[@]} > 0)); then
    local p
    for p in "${problems[@]}"; do fail "$program $shown: $p"; done
  fi
}

# ---- The options of a program, read from its help ------------------------------------------------
# Fills option_names (long names), short_of, metavar_of, help_of, default_of, choices_of, kind_of
# (flag, integer, real, choice, string), output_options and conflicts ("--a --b" pairs).
read_options() {
  local program=$1 help line
  option_names=()
  output_options=()
  conflicts=()
  short_of=()
  metavar_of=()
  help_of=()
  default_of=()
  choices_of=()
  kind_of=()
  help=$("$bin/$program" --help 2>/dev/null)
  local in_options=0
  local pattern='^  (-[A-Za-z], |    )(--[A-Za-z0-9-]+)( ([^ ]+))?  +(.*)$'
  while IFS= read -r line; do
    if [[ $line == "Options:" ]]; then in_options=1; continue; fi
    ((in_options)) || continue
    [[ -z $line ]] && break
    [[ $line =~ $pattern ]] || continue
    local short=${BASH_REMATCH[1]%, } long=${BASH_REMATCH[2]} metavar=${BASH_REMATCH[4]} text=${BASH_REMATCH[5]}
    short=${short// /}
    [[ $long == --help || $long == --version ]] && continue
    option_names+=("$long")
    short_of[$long]=$short
    metavar_of[$long]=$metavar
    help_of[$long]=$text
    if [[ $text =~ \(one\ of:\ ([^\;]*)\;\ default:\ ([^\)]*)\)$ ]]; then
      choices_of[$long]=${BASH_REMATCH[1]}
      default_of[$long]=${BASH_REMATCH[2]}
    elif [[ $text =~ \(default:\ ([^\)]*)\)$ ]]; then
      default_of[$long]=${BASH_REMATCH[1]}
    else
      default_of[$long]=''
    fi
    if [[ $text =~ excludes\ (--[A-Za-z0-9-]+) ]]; then
      conflicts+=("$long ${BASH_REMATCH[1]}")
    fi
  done <<<"$help"
}

# The kind of a value option, by the probe described at the top.
probe_kind() {
  local program=$1 option=$2 message
  message=$(cd "$scratch/work.$program" && timeout "$time_limit" "$bin/$program" "$option" zzz --zz-probe 2>&1 >/dev/null)
  case $message in
    *"is not an integer"*) echo integer ;;
    *"is not a finite decimal number"*) echo real ;;
    *"unknown value"*) echo choice ;;
    *'unknown option "--zz-probe"'*) echo string ;;
    *) echo "unknown: $message" ;;
  esac
}

# ---- --help, -h and --version --------------------------------------------------------------------
check_help_and_version() {
  local program=$1 request status work=$scratch/work.$program before after
  for request in --help -h --version; do
    before=$(snapshot "$work")
    (cd "$work" && timeout "$time_limit" "$bin/$program" "$request" >"$scratch/stdout" 2>"$scratch/stderr")
    status=$?
    after=$(snapshot "$work")
    ((status == 0)) || fail "$program $request: exit status $status, expected 0"
    [[ -s $scratch/stderr ]] && fail "$program $request: wrote to stderr: $(head -c 200 "$scratch/stderr")"
    [[ $before == "$after" ]] || fail "$program $request: files changed"
    case $request in
      --version) grep -qx "$program [^ ]*" "$scratch/stdout" && (($(wc -l <"$scratch/stdout") == 1)) ||
        fail "$program --version: expected one line \"$program VERSION\", got: $(head -c 200 "$scratch/stdout")" ;;
      *) head -n 1 "$scratch/stdout" | grep -qx "Usage: $program \[options\]" ||
        fail "$program $request: the help does not start with \"Usage: $program [options]\"" ;;
    esac
  done
}

# ---- The generic cases ---------------------------------------------------------------------------
malformed_numbers=('' '1e' 'nan' 'NaN' 'inf' '-inf' 'infinity' '12abc' 'abc' '0x10' ' 1' '1 ' '1,5' '1..2'
  '+-1' '--1' '1e400' '-1e400' 'e5' '.')
malformed_integers=('1.5' '1e3' '99999999999999999999' '-99999999999999999999' '2.')
malformed_reals=('1e-400' '1e+' '5%')

generic_cases() {
  local program=$1 option kind value valid pair first second
  check_bad "$program" 2 '"--zz-no-such-option"' --zz-no-such-option
  check_bad "$program" 2 '"--zz-no-such-option"' --zz-no-such-option=1
  check_bad "$program" 2 '"positional"' positional
  check_bad "$program" 2 '"-"' -
  check_bad "$program" 2 '"--"' --
  check_bad "$program" 2 '"--help"' --help=yes
  local used_short=" "
  for option in "${option_names[@]}"; do used_short+="${short_of[$option]} "; done
  local letter
  for letter in Z Q; do
    if [[ $used_short != *" -$letter "* ]]; then
      check_bad "$program" 2 "\"-$letter\"" "-$letter" 1
      break
    fi
  done

  for option in "${option_names[@]}"; do
    if [[ -z ${metavar_of[$option]} ]]; then
      kind_of[$option]=flag
      check_bad "$program" 2 "$option: takes no value" "$option=1"
      check_bad "$program" 2 "$option: given more than once" "$option" "$option"
      continue
    fi
    kind=$(probe_kind "$program" "$option")
    kind_of[$option]=$kind
    if [[ $kind == unknown* ]]; then
      fail "$program $option: cannot tell the kind of the option from the probe (${kind#unknown: })"
      continue
    fi
    # A valid value: the default, or a plain word for a string without default.
    valid=${default_of[$option]}
    [[ -z $valid && $kind == string ]] && valid=x
    [[ -z $valid && $kind == integer ]] && valid=2
    [[ -z $valid && $kind == real ]] && valid=1
    check_bad "$program" 2 "$option: missing value" "$option"
    check_bad "$program" 2 "$option: given more than once" "$option" "$valid" "$option" "$valid"
    if [[ -n ${short_of[$option]} ]]; then
      check_bad "$program" 2 "$option: missing value" "${short_of[$option]}"
      check_bad "$program" 2 "$option: given more than once" "${short_of[$option]}" "$valid" "$option=$valid"
    fi
    case $kind in
      integer | real)
        local -a values=("${malformed_numbers[@]}")
        if [[ $kind == integer ]]; then values+=("${malformed_integers[@]}"); else values+=("${malformed_reals[@]}"); fi
        for value in "${values[@]}"; do
          check_bad "$program" 2 "$option: " "$option=$value"
        done
        # The separate form too, for the values that are not taken for an option.
        for value in '' nan 12abc 1e; do
          check_bad "$program" 2 "$option: " "$option" "$value"
        done
        ;;
      choice)
        for value in zz-not-a-choice '' "${valid^^}" "$valid " "$valid,$valid"; do
          check_bad "$program" 2 "$option: unknown value" "$option=$value"
        done
        ;;
    esac
  done

  for pair in "${conflicts[@]}"; do
    read -r first second <<<"$pair"
    check_bad "$program" 2 "$first and $second cannot be given together" \
      "$first" "${default_of[$first]:-1}" "$second" "${default_of[$second]:-1}"
  done

  for option in "${output_options[@]}"; do
    check_bad "$program" 2 "$option: cannot write" "$option" "$scratch/missing-directory/x.dat"
    check_bad "$program" 2 "$option: cannot write" "$option" "$scratch/work.$program"
    check_bad "$program" 2 "$option: cannot write" "$option="
  done
}

# ---- The table -----------------------------------------------------------------------------------
table_cases() {
  local program=$1 line number=0 name arguments status fragment
  while IFS= read -r line || [[ -n $line ]]; do
    number=$((number + 1))
    [[ $line =~ ^[[:space:]]*(#|$) ]] && continue
    IFS='|' read -r name arguments status fragment <<<"$line"
    name=$(echo $name)
    [[ $name == "$program" ]] || continue
    status=$(echo $status)
    fragment=${fragment#"${fragment%%[![:space:]]*}"}
    fragment=${fragment%"${fragment##*[![:space:]]}"}
    local -a words=()
    eval "words=($arguments)" || { fail "$table:$number: cannot split the arguments"; continue; }
    check_bad "$program" "$status" "$fragment" "${words[@]}"
  done <"$table"
}

# ---- Every program -------------------------------------------------------------------------------
programs=()
for path in "$bin"/*; do
  [[ -f $path && -x $path ]] || continue
  name=${path##*/}
  [[ $name == doctests ]] && continue
  programs+=("$name")
done
((${#programs[@]} > 0)) || { echo "no program in $bin"; exit 1; }

declare -A short_of metavar_of help_of default_of choices_of kind_of
total=0
for program in "${programs[@]}"; do
  mkdir -p "$scratch/work.$program"
  read_options "$program"
  if ((${#option_names[@]} == 0)) && ! "$bin/$program" --help >/dev/null 2>&1; then
    fail "$program: --help fails"
  fi
  for option in "${option_names[@]}"; do
    if [[ -n ${metavar_of[$option]} && ($option == *output* || ${help_of[$option]} == *write*) ]]; then
      output_options+=("$option")
      printf 'known content of %s for %s\n' "$option" "$program" >"$scratch/work.$program/existing${option//-/_}.dat"
    fi
  done
  check_help_and_version "$program"
  before_failures=$failures
  generic_cases "$program"
  generic=${tried[$program]:-0}
  table_cases "$program"
  count=${tried[$program]:-0}
  total=$((total + count))
  kinds=''
  for option in "${option_names[@]}"; do kinds+=" ${option}:${kind_of[$option]:-?}"; done
  printf '%-16s %4d bad invocations (%d generic, %d from the table), %d failed; options:%s\n' \
    "$program" "$count" "$generic" $((count - generic)) $((failures - before_failures)) "$kinds"
done

if [[ " ${programs[*]} " == *" bar1d "* ]] && ((${tried[bar1d]:-0} < 30)); then
  fail "bar1d: only ${tried[bar1d]:-0} bad invocations, expected at least 30"
fi
printf '%d programs, %d bad invocations, %d failures\n' "${#programs[@]}" "$total" "$failures"
((failures == 0))
