#!/usr/bin/env bash
# A sweep in this process gives the same bytes on every vector target and thread count (repro/sweep.hpp):
# a small grid run by the program sweep with --vector none (every run alone), widest and each target the
# processor has (as its help lists them), on 1 and 2 threads. The prediction: identical files, since each
# lane of the batched step is bitwise its run stepped alone (the doctests of lib/batched/batched_step.cpp) and the
# lines are written in grid order. The grid: five schemes x two masses x two meshes x two ratios, so that
# every (N, scheme) group of the sweep layer is a batch of four runs of different masses and steps.
# Usage: sweep_widths.sh BIN_DIR
set -euo pipefail
bin=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
grid=(--schemes cn,be,ps,ec,cn-switch --masses mod1,mod3 --elements 16,24 --courants 0.5,1.5 --final-time 4)

# The targets, from the help's list of choices of --vector ("one of: widest, none, AVX3, ...").
choices=$("$bin/sweep" --help | tr '\n' ' ' | tr -s ' ' | sed -n 's/.*--vector W.*(one of: \([^;]*\); default: widest).*/\1/p')
[[ -n $choices ]] || { echo "sweep --help lists no choices of --vector"; exit 1; }
IFS=', ' read -r -a widths <<< "$choices"
[[ " ${widths[*]} " == *" none "* && " ${widths[*]} " == *" widest "* ]] || { echo "unexpected --vector choices: $choices"; exit 1; }

"$bin/sweep" "${grid[@]}" --vector none --threads 1 --output "$dir/alone.dat"
runs=$(grep -vc '^#' "$dir/alone.dat")
[[ $runs == 40 ]] || { echo "the sweep has $runs result lines, expected 40"; exit 1; }
for w in "${widths[@]}"; do
  for j in 1 2; do
    "$bin/sweep" "${grid[@]}" --vector "$w" --threads "$j" --output "$dir/$w-$j.dat"
    cmp "$dir/alone.dat" "$dir/$w-$j.dat" || { echo "--vector $w --threads $j differs from every run alone"; diff "$dir/alone.dat" "$dir/$w-$j.dat" | head; exit 1; }
  done
done
echo "sweep_widths: $runs runs, --vector ${widths[*]} on 1 and 2 threads: identical bytes ($(wc -c < "$dir/alone.dat") bytes)"
