# Energy over long times (experiments/fig_classes.cpp, block 3): E_h/E_h(0) every 10 periods of the
# paper's benchmark (one impact per period) on the long runs' mesh, one panel per class (small multiples
# on shared axes, log scale in y), one colour per Δt/h, solid with Mod 3, dashed with the consistent
# ("standard") mass; 1 (dotted) is the exact energy. The classes, masses and steps are read from the rows.
# Usage: gnuplot -e "data='output/data/fig_classes.dat'; output='output/figures/fig_classes_energy.pdf'" figures/fig_classes_energy.gp
if (!exists("data")) data = 'output/data/fig_classes.dat'
if (!exists("output")) output = 'output/figures/fig_classes_energy.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'
# The classes, masses, pairs, the long runs' dt/h and their energy, one block a dt/h and pair, read in one
# pass (figures/fig_classes_blocks.awk).
load sprintf("< awk -f '%sfig_classes_blocks.awk' '%s'", dir, data)
nc = words(classes)
nk = words(courants)
np = words(pairs)
nm = words(masses)
# A panel per class, three a row, the key above them.
grid_cols = 3
grid_rows = (nc + grid_cols - 1) / grid_cols
# Heights in cm: 1.6 for the key, 1.2 under the last row for its tic labels and N, 0.7 between rows for
# a title.
height = 2.8 + 4.0 * grid_rows
eval sprintf("set terminal %s size 16cm,%gcm", figure_terminal, height)
set output output
grid_left = 0.1; grid_right = 0.98; grid_bottom = 1.2 / height; grid_top = 1 - 1.6 / height; grid_gap_x = 0.025
grid_gap_y = 0.7 / height
@grid_setup
# The block of $energy that holds step q (1..nk) and the pair (class c, mass m), -1 if not run.
pair_of(c, m, k) = k > np ? 0 : word(pairs, k) eq c."/".m ? k : pair_of(c, m, k + 1)
energy_block(q, c, m) = pair_of(c, m, 1) == 0 ? -1 : (q - 1) * np + pair_of(c, m, 1) - 1
dash(m) = m eq "mod3" ? 1 : 2
step_name(q) = sprintf("%s = %.3g %s", Delta_t, word(courants, q) + 0, italic("h"))

# Shared axes: the periods and E_h/E_h(0) from 10^-8 to 10^8 (what leaves that range has lost or gained
# all meaning as an energy: the curve leaves the panel).
set xrange [0:*]
set xtics 250
set logscale y
set yrange [1e-8:1e8]
set ytics 1e-8, 1e4
unset key
set multiplot
do for [k=0:nc-1] {
  c = word(classes, k + 1)
  @grid_panel
  set title scheme_name(c)
  if (grid_left_column(k)) { set ylabel E_h." / ".E_h."(0)"; set format y "10^{%L}" } else { unset ylabel; set format y "" }
  if (grid_bottom_row(k, nc)) { set xlabel "periods (impacts)"; set format x "%g" } else { unset xlabel; set format x "" }
  plot 1 with lines lc rgb "#000000" dt 3 notitle, \
       for [q=1:nk] for [j=1:nm] $energy index (energy_block(q, c, word(masses, j)) >= 0 ? energy_block(q, c, word(masses, j)) : 0) \
         using (energy_block(q, c, word(masses, j)) >= 0 ? $4 : NaN):5 \
         with lines lc rgb curve_colour(q) dt dash(word(masses, j)) lw 1.2 notitle
}
# The key: a frameless plot across the top, the steps' colours and the masses' lines.
set lmargin at screen 0; set rmargin at screen 1; set tmargin at screen 1; set bmargin at screen grid_top + 0.5 / height
unset border; unset tics; unset xlabel; unset ylabel; unset title; unset logscale; unset grid
set xrange [0:1]; set yrange [0:1]
set key center center vertical maxrows 1 samplen 3 width 1
plot for [q=1:nk] NaN with lines lc rgb curve_colour(q) lw 1.2 title step_name(q), \
     for [j=1:nm] NaN with lines lc rgb "#000000" dt dash(word(masses, j)) lw 1.2 title mass_name(word(masses, j))
unset multiplot
