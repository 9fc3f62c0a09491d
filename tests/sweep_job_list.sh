#!/usr/bin/env bash
# A sweep that leaves the process (repro/sweep.hpp): a grid of 40 runs in-process on 2 threads, and the same
# grid written out as a job list, run by GNU parallel (2 jobs at a time), its result files merged. The
# prediction: the same bytes, since each job runs its configuration with the same code as the in-process
# sweep and the merge writes the same header and the lines in grid order; the merge reads the grid from the
# results (each records its run and its grid), with or without the grid options.
# Then the merge is complete and exact or fails: the results are damaged in every way a job list's results
# can be (missing, extra, copied, swapped, linked, another grid's, truncated, garbled, not a file), and each
# merge must fail with the file named and leave no output; an output that is one of the results, and a job
# list whose lines a path would split, are refused. Usage: sweep_job_list.sh BIN_DIR
set -uo pipefail
bin=$(cd "$1" && pwd)
command -v parallel >/dev/null || {
  echo "GNU parallel is missing (tools/deps.sh installs the Debian package parallel)"
  exit 1
}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
grid=(--schemes cn,be,ps,ec,cn-switch --masses mod1,mod3 --elements 16,24 --courants 0.5,1.5 --final-time 4)
runs=$((5 * 2 * 2 * 2))
failed=0
fail() {
  echo "FAIL: $*"
  failed=$((failed + 1))
}

# ---- The same bytes both ways ----------------------------------------------------------------------------
"$bin/sweep" "${grid[@]}" --threads 2 --output "$dir/in_process.dat" || fail "the in-process sweep failed"
"$bin/sweep" "${grid[@]}" --job-list "$dir/jobs.txt" --results "$dir/runs" || fail "the job list failed"
lines=$(wc -l <"$dir/jobs.txt")
[[ $lines == "$runs" ]] || fail "the job list has $lines lines, expected $runs"
mkdir "$dir/runs"
parallel --will-cite --halt now,fail=1 --jobs 2 <"$dir/jobs.txt" || fail "a job failed"
for with in "" grid; do
  options=()
  [[ $with == grid ]] && options=("${grid[@]}")
  "$bin/sweep" "${options[@]}" --merge "$dir/runs" --output "$dir/merged.dat" || fail "the merge failed"
  data=$(grep -vc '^#' "$dir/merged.dat")
  [[ $data == "$runs" ]] || fail "the merged file has $data result lines, expected $runs"
  cmp "$dir/in_process.dat" "$dir/merged.dat" ||
    fail "the merge (${with:-no} grid options) differs from the in-process sweep: $(diff "$dir/in_process.dat" "$dir/merged.dat" | head -3)"
done
echo "sweep_job_list: $runs runs, in-process and through GNU parallel: identical bytes ($(wc -c <"$dir/merged.dat") bytes)"

# ---- Damaged results: every merge fails, naming the file, and writes nothing -------------------------------
# Results of other grids, to plant: the same index of a grid with another T, another mass list.
mkdir "$dir/other_t" "$dir/other_mass"
for k in 0 5; do
  "$bin/sweep" --schemes cn,be,ps,ec,cn-switch --masses mod1,mod3 --elements 16,24 --courants 0.5,1.5 --final-time 5 \
    --run $k --result "$dir/other_t/run-00000$k.dat" || fail "a run of another grid failed"
done
"$bin/sweep" --schemes cn,be,ps,ec,cn-switch --masses mod1,mod2 --elements 16,24 --courants 0.5,1.5 --final-time 4 \
  --run 1 --result "$dir/other_mass/run-000001.dat" || fail "a run of another grid failed"
damaged=0
# damage NAME STATUS FRAGMENT COMMAND: a copy of the results, COMMAND run in it, then the merge.
damage() {
  local name=$1 expected=$2 fragment=$3 command=$4
  shift 4
  damaged=$((damaged + 1))
  rm -rf "$dir/d" "$dir/out.dat"
  cp -a "$dir/runs" "$dir/d"
  (cd "$dir/d" && eval "$command") || {
    fail "$name: could not damage the results"
    return
  }
  local status=0
  timeout -k 5 30 "$bin/sweep" --merge "$dir/d" --output "$dir/out.dat" "$@" >"$dir/stdout" 2>"$dir/stderr" || status=$?
  local message
  message=$(head -c 400 "$dir/stderr")
  [[ $status == "$expected" ]] || fail "$name: exit status $status, expected $expected ($message)"
  [[ $(wc -l <"$dir/stderr") == 1 ]] || fail "$name: stderr has $(wc -l <"$dir/stderr") lines, expected 1"
  [[ $message == "sweep: "*"$fragment"* ]] || fail "$name: the message does not contain \"$fragment\": $message"
  [[ ! -e $dir/out.dat ]] || fail "$name: a merge that failed left its output"
  [[ -z $(ls -A "$dir" | grep '^\.out\.dat') ]] || fail "$name: a merge that failed left a temporary"
}
damage missing 1 'run-000007.dat": missing' 'rm run-000007.dat'
damage "missing first" 1 'run-000000.dat": missing' 'rm run-000000.dat'
damage "missing last" 1 'run-000039.dat": missing' 'rm run-000039.dat'
damage "extra run" 1 'run-000040.dat": run 40 is not in the grid of 40 runs' 'cp run-000000.dat run-000040.dat'
damage "extra name" 1 'run-000003.dat~": not the name of a result' 'cp run-000003.dat run-000003.dat~'
damage "short name" 1 'run-3.dat": not the name of a result' 'cp run-000003.dat run-3.dat'
damage copied 1 'run-000001.dat": holds run 0, not run 1' 'cp run-000000.dat run-000001.dat'
damage swapped 1 'run-000002.dat": holds run 3, not run 2' 'mv run-000002.dat t && mv run-000003.dat run-000002.dat && mv t run-000003.dat'
damage "symbolic link" 1 'run-000001.dat": holds run 0, not run 1' 'ln -sf run-000000.dat run-000001.dat'
damage "hard link" 1 'run-000009.dat": holds run 8, not run 9' 'ln -f run-000008.dat run-000009.dat'
damage "another T" 1 'run-000005.dat": the result of another grid' "cp '$dir/other_t/run-000005.dat' run-000005.dat"
damage "another mass" 1 'run-000001.dat": the result of another grid' "cp '$dir/other_mass/run-000001.dat' run-000001.dat"
damage "all of another T" 2 '--final-time: not the grid of the results' 'true' --final-time 5
damage "another mass list" 2 '--masses: not the grid of the results' 'true' --masses mod1,mod2
damage "another scheme list" 2 '--schemes: not the grid of the results' 'true' --schemes cn,be
damage "truncated line" 1 'run-000004.dat": truncated: the result line does not end' 'truncate -s -20 run-000004.dat'
damage "truncated header" 1 'run-000004.dat": truncated at line' 'head -c 200 run-000004.dat > t && mv t run-000004.dat'
damage "header only" 1 'run-000004.dat": truncated: no result line' 'head -n 8 run-000004.dat > t && mv t run-000004.dat'
damage empty 1 'run-000006.dat": truncated at line 1' ': > run-000006.dat'
damage "extra column" 1 'run-000010.dat": the result line has 18 fields, expected 17' "sed -i '\$s/\$/ 0.5/' run-000010.dat"
damage "missing column" 1 'run-000010.dat": the result line has 16 fields' "sed -i '\$s/ [^ ]*\$//' run-000010.dat"
damage "two lines" 1 'run-000011.dat": more than one result line' 'tail -n 1 run-000011.dat >> run-000011.dat'
# last_line AWK-PROGRAM FILE: the file's result line rewritten by awk (fields joined by single spaces).
last_line() { head -n 8 "$2" >t && tail -n 1 "$2" | awk "$1" >>t && mv t "$2"; }
damage "garbage number" 1 'run-000012.dat": field 9 of the result line, "abc"' "last_line '{ \$9 = \"abc\"; print }' run-000012.dat"
damage "number not as written" 1 'run-000012.dat": field 6 of the result line' "last_line '{ \$6 = \$6 \"0\"; print }' run-000012.dat"
damage "a negative zero" 1 'run-000012.dat": field 10 of the result line' "last_line '{ \$10 = \"-0\" \$10; print }' run-000012.dat"
damage "another run's parameters" 1 'run-000012.dat": the result line is of "cn mod3 16 0.5", not of run 12' \
  "tail -n 1 run-000000.dat | sed 's/ mod1 / mod3 /' > line && head -n 8 run-000012.dat > t && cat line >> t && mv t run-000012.dat && rm line"
damage CRLF 1 'run-000013.dat": line 1 is' "sed -i 's/\$/\r/' run-000013.dat"
damage "CR at the end" 1 'run-000013.dat": field 17 of the result line' "sed -i '\$s/\$/\r/' run-000013.dat"
damage NUL 1 'run-000014.dat": line 4 is "# masses = mod1\u0000' "sed -i '4s/mod1/mod1\x00/' run-000014.dat"
damage "NUL in the line" 1 'run-000014.dat": field 6' "sed -i '\$s/ 0\./ \x000./2' run-000014.dat"
damage "garbage file" 1 'run-000015.dat": line 1 is' 'head -c 300 /dev/urandom | tr -d "\n" > run-000015.dat; echo >> run-000015.dat'
damage "huge file" 1 'run-000016.dat": 10' 'head -c 100000 /dev/zero >> run-000016.dat'
damage "a directory" 1 'run-000017.dat": not a regular file' 'rm run-000017.dat && mkdir run-000017.dat'
damage "a FIFO (no hang)" 1 'run-000018.dat": not a regular file' 'rm run-000018.dat && mkfifo run-000018.dat'
damage "a dangling link" 1 'run-000019.dat": cannot read it' 'rm run-000019.dat && ln -s nowhere run-000019.dat'
damage "the first of another grid" 1 'run-000001.dat": the result of another grid' "cp '$dir/other_t/run-000000.dat' run-000000.dat"
damage "no results" 1 'holds no result file' 'rm run-*'
echo "sweep_job_list: $damaged damaged result sets, each merge failed naming the file (or the option)"

# ---- Refusals before any work: an output among the results, a path that splits a job list ---------------
refused=0
refuse() {  # refuse FRAGMENT ARGS...: exit 2, one line containing FRAGMENT, the results untouched
  local fragment=$1
  shift
  refused=$((refused + 1))
  local before status=0
  before=$(cd "$dir/runs" && ls -A | sort && cat run-*.dat | sha256sum)
  (cd "$dir" && timeout -k 5 30 "$bin/sweep" "$@" >"$dir/stdout" 2>"$dir/stderr") || status=$?
  [[ $status == 2 ]] || fail "sweep $*: exit status $status, expected 2 ($(head -c 300 "$dir/stderr"))"
  [[ $(wc -l <"$dir/stderr") == 1 && $(head -n 1 "$dir/stderr") == "sweep: "*"$fragment"* ]] ||
    fail "sweep $*: the message does not contain \"$fragment\": $(head -c 300 "$dir/stderr")"
  [[ $(cd "$dir/runs" && ls -A | sort && cat run-*.dat | sha256sum) == "$before" ]] || fail "sweep $*: the results changed"
}
ln -s runs/run-000000.dat "$dir/link.dat"
ln -s runs "$dir/runs_link"
refuse '--output: "runs/run-000000.dat" is the result file of run 0' --merge runs --output runs/run-000000.dat
refuse '--output: "./runs/run-000000.dat" is the result file of run 0' --merge runs --output ./runs/run-000000.dat
refuse '--output: "runs/./run-000003.dat" is the result file of run 3' --merge runs --output runs/./run-000003.dat
refuse '--output: "link.dat" is the result file of run 0' --merge runs --output link.dat
refuse '--output: "runs_link/run-000002.dat" is the result file of run 2' --merge runs --output runs_link/run-000002.dat
refuse 'is the result file of run 4' --merge runs_link --output "$dir/runs/run-000004.dat"
refuse "--output: \"runs/run-000099.dat\" is a result's name in the directory" --merge runs --output runs/run-000099.dat
refuse '--results: "r\nx" holds a control character' "${grid[@]}" --job-list jobs2.txt --results $'r\nx'
refuse '--results: "r\rx" holds a control character' "${grid[@]}" --job-list jobs2.txt --results $'r\rx'
refuse '--merge: "nowhere": cannot read the directory' --merge nowhere --output m.dat
refuse '--threads: does not apply with --merge "runs"' --merge runs --output m.dat --threads 2
refuse '--vector: does not apply with --job-list' "${grid[@]}" --job-list jobs2.txt --results runs --vector none
refuse '--threads: does not apply with --result' --run 3 --result r.dat "${grid[@]}" -j 1
refuse '--run: 40 is not a run of the grid (allowed: 0 to 39)' "${grid[@]}" --run 40 --result r.dat
refuse '--run: needs --result' "${grid[@]}" --run 3 --output m.dat
refuse '--merge: needs --output' --merge runs
refuse '--result: one run only (every list of one value, or --run K), not 40' "${grid[@]}" --result r.dat
[[ ! -e $dir/jobs2.txt && ! -e $dir/m.dat && ! -e $dir/r.dat ]] || fail "a refused command left a file"
# A job list whose paths hold a quote or a space is still one command per line, and runs.
mkdir "$dir/it's a dir"
"$bin/sweep" --schemes cn --masses mod3 --elements 16 --courants 0.5,1 --job-list "$dir/jobs3.txt" \
  --results "$dir/it's a dir" || fail "a job list with a quote in its directory failed"
[[ $(wc -l <"$dir/jobs3.txt") == 2 ]] || fail "the job list with a quote in its directory is not 2 lines"
bash "$dir/jobs3.txt" && "$bin/sweep" --merge "$dir/it's a dir" --output "$dir/m3.dat" ||
  fail "the job list with a quote in its directory did not run and merge"
echo "sweep_job_list: $refused refusals before any work"
((failed == 0)) || {
  echo "sweep_job_list: $failed failures"
  exit 1
}
