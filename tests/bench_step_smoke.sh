#!/usr/bin/env bash
# Smoke test of the benchmark program (never a timed assertion): a tiny run writes its three outputs
# with the expected structure, and a bad option is a usage error (status 2). Usage: bench_step_smoke.sh BIN_DIR
set -euo pipefail
bin=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

"$bin/bench_step" --quick --min-log2 6 --max-log2 7 --repetitions 1 --batch-ms 0.5 \
  --output "$dir/b.dat" --tex "$dir/b.tex" --markdown "$dir/b.md" > "$dir/stdout" 2> /dev/null
# Two sizes: two data rows of 2 + 10*3 + 8 = 40 columns each (10 variants: the fast and the reference
# step of each scheme among them; 8 ratios and costs, the last the run with its error measures over the
# bare solve), all numbers, the reference step's timings positive.
rows=$(grep -v '^#' "$dir/b.dat" | awk 'NF == 40' | wc -l)
[[ $rows == 2 ]] || { echo "expected 2 data rows of 40 columns, got $rows"; cat "$dir/b.dat"; exit 1; }
grep -q '^# columns: .* cn_ref_median .* ps_ref_median .* ps_ref_over_bare cn_errors_over_bare$' "$dir/b.dat" \
  || { echo "no reference-step columns in the data file"; cat "$dir/b.dat"; exit 1; }
positive=$(grep -v '^#' "$dir/b.dat" | awk '$24 > 0 && $27 > 0 && $30 > 0 && $37 > 0 && $39 > 0 && $40 > 0' | wc -l)
[[ $positive == 2 ]] || { echo "reference-step timings or ratios missing"; cat "$dir/b.dat"; exit 1; }
grep -q '^| N | CN | BE | PS | CN ref | BE ref | PS ref |' "$dir/b.md" || { echo "no reference columns in the Markdown table"; exit 1; }
# The LaTeX file: two tables as report values, the fast step (with the ratio to Eigen) and the reference step.
grep -q '^\\mrmdef{bench:table:fast}{\\begin{tabular}' "$dir/b.tex" || { echo "no fast-step table in the LaTeX file"; exit 1; }
grep -q '^\\mrmdef{bench:table:ref}{\\begin{tabular}' "$dir/b.tex" || { echo "no reference-step table in the LaTeX file"; exit 1; }
grep -q 'CN/Eigen' "$dir/b.tex" || { echo "no ratio to Eigen in the LaTeX file"; exit 1; }
grep -q '^| 128 |' "$dir/b.md" || { echo "no row for N = 128 in the Markdown table"; exit 1; }
grep -q '^slope_cn = ' "$dir/stdout" || { echo "no slope on stdout"; exit 1; }

status=0
"$bin/bench_step" --max-log2 30 > /dev/null 2>&1 || status=$?
[[ $status == 2 ]] || { echo "--max-log2 30: expected exit status 2, got $status"; exit 1; }
echo "bench_step smoke test passed"
