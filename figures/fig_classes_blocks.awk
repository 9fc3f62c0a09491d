# fig_classes.dat's rows (experiments/fig_classes.cpp) read in one pass for the four figures
# figures/fig_classes_*.gp, which `load` this program's output (gnuplot commands), so that each curve
# reads its own block instead of the whole file:
# - `benchmarks` and `pairs` (scheme/mass): the words in the order of their first row in block 0;
# - `classes` and `masses`: the schemes and the masses of the pairs, in the same order;
# - the datablock $runs: block 0's runs at dt = h/2, one block per benchmark and pair in that order:
#   block (b - 1) * words(pairs) + p - 1 holds the rows of benchmark b and pair p;
# - `courants`: the dt/h of block 3 (the long runs' energy every 10 periods) in the order of their first
#   row, and the datablock $energy: block 3's rows, one block per dt/h and pair: block
#   (k - 1) * words(pairs) + p - 1 holds the rows of courant k and pair p.
# Rows in the file's order; a block with no row holds a comment alone.
# Usage: awk -f figures/fig_classes_blocks.awk output/data/fig_classes.dat
/^# block / { block = $3 + 0 }
!/^#/ && NF == 20 {
  pair = $2 "/" $3
  if (!($1 in benchmark_seen)) { benchmark_seen[$1] = 1; benchmark[++benchmarks] = $1 }
  if (!(pair in pair_seen)) { pair_seen[pair] = 1; pair_list[++pairs] = pair }
  if (!($2 in class_seen)) { class_seen[$2] = 1; class[++classes] = $2 }
  if (!($3 in mass_seen)) { mass_seen[$3] = 1; mass[++masses] = $3 }
  if ($4 == 0.5) runs[$1, pair] = runs[$1, pair] $0 "\n"
}
block == 3 && !/^#/ && NF == 5 {
  if (!($3 in courant_seen)) { courant_seen[$3] = 1; courant[++courants] = $3 }
  energy[$3, $1 "/" $2] = energy[$3, $1 "/" $2] $0 "\n"
}
function words(list, count,    i, s) {
  for (i = 1; i <= count; ++i) s = s (i > 1 ? " " : "") list[i]
  return s
}
END {
  print "benchmarks = \"" words(benchmark, benchmarks) "\""
  print "pairs = \"" words(pair_list, pairs) "\""
  print "classes = \"" words(class, classes) "\""
  print "masses = \"" words(mass, masses) "\""
  print "courants = \"" words(courant, courants) "\""
  print "$runs << EOD"
  for (b = 1; b <= benchmarks; ++b)
    for (p = 1; p <= pairs; ++p)
      printf "%s\n\n", ((benchmark[b], pair_list[p]) in runs) ? runs[benchmark[b], pair_list[p]] : "# none\n"
  print "EOD"
  print "$energy << EOD"
  for (k = 1; k <= courants; ++k)
    for (p = 1; p <= pairs; ++p)
      printf "%s\n\n", ((courant[k], pair_list[p]) in energy) ? energy[courant[k], pair_list[p]] : "# none\n"
  print "EOD"
}
