# The paper's Figure 1: u(0,t) (left) and the contact stress lambda(t) (right), one row per scheme,
# the exact solution (black) against Mod 1, Mod 2, Mod 3, and the baseline: Paoli-Schatzman with the
# consistent mass (purple, dashed; the data file's last block). Two rows, Crank-Nicolson and backward
# Euler: the paper's third row, Paoli-Schatzman with the contact row the report believes the paper used,
# coincides with Crank-Nicolson to round-off (the program measures the difference; the report quotes
# it), so drawing it would repeat the first row. Titles, masses and the time axis are read from the data
# file's header (blocks "scheme = s, mass = m"); the y-axes are set by the data: no curve is clipped.
# Usage: gnuplot -e "data='output/data/fig_contact_history.dat'; output='output/figures/fig_contact_history.pdf'" figures/fig_contact_history.gp
if (!exists("data")) data = 'output/data/fig_contact_history.dat'
if (!exists("output")) output = 'output/figures/fig_contact_history.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,14cm
set output output
set datafile missing "n/a"

# Block 1 + 3 s + m - 1 is scheme s, mass m: the schemes and masses in the file's order; the last block
# is the baseline.
blocks = system(sprintf("sed -n 's/^# block [0-9]*: scheme = \\([a-z]*\\), mass = \\([a-z0-9]*\\)$/\\1 \\2/p' '%s'", data))
scheme_id(s) = word(blocks, 2 * (3 * s) + 1)
mass_id(m) = word(blocks, 2 * (m - 1) + 2)
baseline = words(blocks) / 2
# The baseline's legend entry, short enough for one line of entries ("baseline: consistent mass").
baseline_title = "baseline: ".mass_name(word(blocks, words(blocks)))
title(s) = scheme_title(scheme_id(s))
final_time = header("final_time") + 0

set multiplot layout 2,2 margins 0.08,0.98,0.07,0.91 spacing 0.08,0.13
set xlabel italic("t")
set xrange [0:final_time]
set xtics 1
set offsets 0, 0, graph 0.05, graph 0.05
# One legend for the whole figure, above the panels, in one row: every colour named (the columns are
# narrowed to the short titles; the long one, the baseline's, comes last).
set key at screen 0.5,0.995 center top vertical maxrows 1 Left reverse samplen 3 width -12
do for [s=0:1] {
  set title title(s)
  set ylabel italic("u")."(0,".italic("t").")"
  plot NaN with lines lc rgb "black" lw 2.0 title "exact", \
       data index baseline using 1:2 with lines lc rgb mass_colour(4) lw 1.0 dt 2 notitle, \
       for [m=1:3] data index 1+3*s+m-1 using 1:2 with lines lc rgb mass_colour(m) lw 1.0 title mass_name(mass_id(m)), \
       data index 0 using 1:2 with lines lc rgb "black" lw 2.0 notitle, \
       NaN with lines lc rgb mass_colour(4) lw 1.0 dt 2 title baseline_title
  unset key
  set ylabel lambda_."(".italic("t").")"
  plot data index baseline using 3:4 with lines lc rgb mass_colour(4) lw 1.0 dt 2 notitle, \
       for [m=1:3] data index 1+3*s+m-1 using 3:4 with lines lc rgb mass_colour(m) lw 1.0 notitle, \
       data index 0 using 1:3 with lines lc rgb "black" lw 2.0 notitle
}
unset multiplot
