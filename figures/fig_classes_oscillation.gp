# Stress oscillation (experiments/fig_classes.cpp, block 0): TV(λ)/TV(λ_exact) over the run against N,
# Δt = h/2, one panel per class (small multiples on shared axes), one colour per benchmark, solid with
# filled marks with Mod 3, dashed with open marks with the consistent ("standard") mass; 1 (dotted) is
# the exact solution's variation. The classes, masses and benchmarks are read from the rows.
# Usage: gnuplot -e "data='output/data/fig_classes.dat'; output='output/figures/fig_classes_oscillation.pdf'" figures/fig_classes_oscillation.gp
if (!exists("data")) data = 'output/data/fig_classes.dat'
if (!exists("output")) output = 'output/figures/fig_classes_oscillation.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'
# The benchmarks, classes, masses, pairs and their runs at dt = h/2, one block a benchmark and pair, read
# in one pass (figures/fig_classes_blocks.awk).
load sprintf("< awk -f '%sfig_classes_blocks.awk' '%s'", dir, data)
nc = words(classes)
nb = words(benchmarks)
np = words(pairs)
nm = words(masses)
# A panel per class, three a row, the key above them.
grid_cols = 3
grid_rows = (nc + grid_cols - 1) / grid_cols
# Heights in cm: 1.8 for the key, 1.2 under the last row for its tic labels and N, 0.7 between rows for
# a title.
height = 3.0 + 4.4 * grid_rows
eval sprintf("set terminal %s size 16cm,%gcm", figure_terminal, height)
set output output
grid_left = 0.1; grid_right = 0.98; grid_bottom = 1.2 / height; grid_top = 1 - 1.8 / height; grid_gap_x = 0.025
grid_gap_y = 0.7 / height
@grid_setup
# The block of $runs that holds benchmark b (1..nb) and the pair (class c, mass m), -1 if not run.
pair_of(c, m, k) = k > np ? 0 : word(pairs, k) eq c."/".m ? k : pair_of(c, m, k + 1)
runs_block(b, c, m) = pair_of(c, m, 1) == 0 ? -1 : (b - 1) * np + pair_of(c, m, 1) - 1
dash(m) = m eq "mod3" ? 1 : 2
marker(m) = m eq "mod3" ? 7 : 6

# Shared axes: N (log) and the decades of every run's TV ratio.
set logscale xy
stats $runs using 5 nooutput
set xrange [STATS_min / 1.2:STATS_max * 1.2]
set xtics STATS_min, 2
stats $runs using (positive($16)) nooutput
@fit_log_y
set format y "10^{%L}"
unset key
set multiplot
do for [k=0:nc-1] {
  c = word(classes, k + 1)
  @grid_panel
  set title scheme_name(c)
  if (grid_left_column(k)) { set ylabel "TV(".lambda_.") / TV(".lambda_."_{exact})"; set format y "10^{%L}" } else { unset ylabel; set format y "" }
  if (grid_bottom_row(k, nc)) { set xlabel italic("N"); set format x "%g" } else { unset xlabel; set format x "" }
  plot 1 with lines lc rgb "#000000" dt 3 notitle, \
       for [b=1:nb] for [j=1:nm] $runs index (runs_block(b, c, word(masses, j)) >= 0 ? runs_block(b, c, word(masses, j)) : 0) \
         using (runs_block(b, c, word(masses, j)) >= 0 ? $5 : NaN):16 \
         with linespoints lc rgb curve_colour(b) dt dash(word(masses, j)) pt marker(word(masses, j)) ps 0.5 notitle
}
# The key: a frameless plot across the top, the benchmarks' colours and the masses' lines.
set lmargin at screen 0; set rmargin at screen 1; set tmargin at screen 1; set bmargin at screen grid_top + 0.5 / height
unset border; unset tics; unset xlabel; unset ylabel; unset title; unset logscale; unset grid
set xrange [0:1]; set yrange [0:1]
set key center center vertical maxrows 2 samplen 2 width 1
plot for [b=1:nb] NaN with linespoints lc rgb curve_colour(b) pt 7 ps 0.5 title word(benchmarks, b), \
     for [j=1:nm] NaN with linespoints lc rgb "#000000" dt dash(word(masses, j)) pt marker(word(masses, j)) ps 0.5 \
       title mass_name(word(masses, j))
unset multiplot
