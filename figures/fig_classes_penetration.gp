# Penetration (experiments/fig_classes.cpp, block 0): the largest penetration against N, Δt = h/2, one
# panel per benchmark, each with its own linear axis from 0 and its unit in the label (the benchmarks are
# in different units: impacting in SI, the others dimensionless; benchmark_length_unit below; a shared
# axis flattened every benchmark but bouncing); one colour and marker per class, solid with Mod 3, dashed
# with the consistent ("standard") mass. The classes, masses and benchmarks are read from the rows.
# Usage: gnuplot -e "data='output/data/fig_classes.dat'; output='output/figures/fig_classes_penetration.pdf'" figures/fig_classes_penetration.gp
if (!exists("data")) data = 'output/data/fig_classes.dat'
if (!exists("output")) output = 'output/figures/fig_classes_penetration.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'
# The benchmarks, classes, masses, pairs and their runs at dt = h/2, one block a benchmark and pair, read
# in one pass (figures/fig_classes_blocks.awk).
load sprintf("< awk -f '%sfig_classes_blocks.awk' '%s'", dir, data)
nc = words(classes)
nb = words(benchmarks)
np = words(pairs)
nm = words(masses)
# The unit of length of a benchmark's data (doc/benchmarks.md): impacting is Code_Aster's bar in SI
# units; the others are dimensionless ("" here).
benchmark_length_unit(b) = b eq "impacting" ? "m" : ""
# A panel per benchmark, three a row, the key above them.
grid_cols = 3
grid_rows = (nb + grid_cols - 1) / grid_cols
# Heights in cm: 3.0 for the key, 1.2 under the last row for its tic labels and N, 1.2 between rows for
# a title and the tic labels of the row above (N is labelled under the last panel of each column only).
height = 4.2 + 5.0 * grid_rows
eval sprintf("set terminal %s size 16cm,%gcm", figure_terminal, height)
set output output
grid_left = 0.1; grid_right = 0.98; grid_bottom = 1.2 / height; grid_top = 1 - 3.0 / height; grid_gap_x = 0.11
grid_gap_y = 1.2 / height
@grid_setup
pair_of(c, m, k) = k > np ? 0 : word(pairs, k) eq c."/".m ? k : pair_of(c, m, k + 1)
runs_block(b, c, m) = pair_of(c, m, 1) == 0 ? -1 : (b - 1) * np + pair_of(c, m, 1) - 1
dash(m) = m eq "mod3" ? 1 : 2
# One marker per class (two classes may share a colour in the data file's palette).
marker(k) = word("7 5 9 11 13 6 4 8 10 12 14 1 2 3", (k - 1) % 14 + 1) + 0

set logscale x
stats $runs using 5 nooutput
set xrange [STATS_min / 1.2:STATS_max * 1.2]
set xtics STATS_min, 2
unset key
set multiplot
do for [k=0:nb-1] {
  b = word(benchmarks, k + 1)
  @grid_panel
  set title b
  if (grid_bottom_row(k, nb)) { set xlabel italic("N") } else { unset xlabel }
  # This benchmark's largest penetration: the axis runs from 0 to it, in a power of ten of the unit
  # chosen so that the tic labels have a few digits (given in the label).
  set autoscale y
  hi = 0
  do for [p=1:np] {
    stats $runs index k * np + p - 1 using 17 nooutput
    if (STATS_records > 0) { hi = STATS_max > hi ? STATS_max : hi }
  }
  e = hi > 0 ? floor(log10(hi)) : 0
  e = e < -1 ? e : 0
  scale = 10.0**e
  unit = benchmark_length_unit(b)
  unit_text = (e != 0 ? "10^{".e."}".(unit eq "" ? "" : " ") : "").unit
  set ylabel "max penetration".(unit_text eq "" ? "" : " (".unit_text.")")
  set yrange [-0.05 * (hi > 0 ? hi : 1) / scale:1.1 * (hi > 0 ? hi : 1) / scale]
  plot for [c=1:nc] for [j=1:nm] $runs index (runs_block(k + 1, word(classes, c), word(masses, j)) >= 0 ? runs_block(k + 1, word(classes, c), word(masses, j)) : 0) \
         using (runs_block(k + 1, word(classes, c), word(masses, j)) >= 0 ? $5 : NaN):($17 / scale) \
         with linespoints lc rgb scheme_colour(word(classes, c)) dt dash(word(masses, j)) pt marker(c) ps 0.5 notitle
}
# The key: a frameless plot across the top, the classes' colours and markers and the masses' lines.
set lmargin at screen 0; set rmargin at screen 1; set tmargin at screen 1; set bmargin at screen grid_top + 0.6 / height
unset border; unset tics; unset xlabel; unset ylabel; unset title; unset logscale; unset grid
set xrange [0:1]; set yrange [0:1]
set key center center vertical maxrows 5 samplen 2 width 1
plot for [c=1:nc] NaN with linespoints lc rgb scheme_colour(word(classes, c)) pt marker(c) ps 0.5 title scheme_name(word(classes, c)), \
     for [j=1:nm] NaN with lines lc rgb "#000000" dt dash(word(masses, j)) title mass_name(word(masses, j))
unset multiplot
