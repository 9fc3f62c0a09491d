#!/usr/bin/env bash
# A sweep that leaves the process (repro/sweep.hpp): a small grid run in-process on 2 threads, and the same
# grid written out as a job list, run by GNU parallel (2 jobs at a time), its result files merged. The
# prediction: the same bytes, since each job runs its configuration with the same code as the in-process
# sweep and the merge writes the same header and the lines in grid order. Also: the list has one
# command per run, a missing result file is an error naming it. Usage: sweep_job_list.sh BIN_DIR
set -euo pipefail
bin=$1
command -v parallel > /dev/null || { echo "GNU parallel is missing (tools/deps.sh installs the Debian package parallel)"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
grid=(--schemes cn,be,ps,ec,cn-switch --masses mod1,mod3 --elements 16,24 --courants 0.5,1.5 --final-time 4)
runs=$((5 * 2 * 2 * 2))

"$bin/sweep" "${grid[@]}" --threads 2 --output "$dir/in_process.dat"
"$bin/sweep" "${grid[@]}" --job-list "$dir/jobs.txt" --results "$dir/runs"
lines=$(wc -l < "$dir/jobs.txt")
[[ $lines == "$runs" ]] || { echo "the job list has $lines lines, expected $runs"; exit 1; }
mkdir "$dir/runs"
parallel --will-cite --halt now,fail=1 --jobs 2 < "$dir/jobs.txt"
"$bin/sweep" "${grid[@]}" --merge "$dir/runs" --output "$dir/merged.dat"
data=$(grep -vc '^#' "$dir/merged.dat")
[[ $data == "$runs" ]] || { echo "the merged file has $data result lines, expected $runs"; exit 1; }
cmp "$dir/in_process.dat" "$dir/merged.dat" || { echo "the job list's merged results differ from the in-process sweep"; diff "$dir/in_process.dat" "$dir/merged.dat" | head; exit 1; }
echo "sweep_job_list: $runs runs, in-process and through GNU parallel: identical bytes ($(wc -c < "$dir/merged.dat") bytes)"

# A missing result is an error naming the file, and no merged file is left.
rm "$dir/runs/run-000007.dat"
status=0
"$bin/sweep" "${grid[@]}" --merge "$dir/runs" --output "$dir/broken.dat" 2> "$dir/err" || status=$?
[[ $status == 1 ]] || { echo "merge with a missing file: expected exit status 1, got $status"; exit 1; }
grep -q 'run-000007.dat: missing' "$dir/err" || { echo "the message does not name the missing file:"; cat "$dir/err"; exit 1; }
[[ ! -e $dir/broken.dat ]] || { echo "a merge that failed left its output"; exit 1; }
