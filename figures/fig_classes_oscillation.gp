# Stress oscillation (experiments/fig_classes.cpp, block 0): TV(λ)/TV(λ_exact) over the run against N,
# one panel per benchmark, Δt = h/2; one colour per class, solid with Mod 3, dashed with the consistent
# ("standard") mass; 1 is the exact solution's variation.
# Usage: gnuplot -e "data='output/data/fig_classes.dat'; output='output/figures/fig_classes_oscillation.pdf'" figures/fig_classes_oscillation.gp
if (!exists("data")) data = 'output/data/fig_classes.dat'
if (!exists("output")) output = 'output/figures/fig_classes_oscillation.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'
# The benchmarks, the pairs and their runs at dt = h/2, one block a benchmark and pair, read in one pass
# (figures/fig_classes_blocks.awk).
load sprintf("< awk -f '%sfig_classes_blocks.awk' '%s'", dir, data)
# One row of panels for up to four benchmarks, two rows beyond (the field's benchmarks, doc/benchmarks.md).
rows = words(benchmarks) > 4 ? 2 : 1
cols = (words(benchmarks) + rows - 1) / rows
eval sprintf("set terminal %s size 16cm,%dcm", figure_terminal, rows == 2 ? 12 : 7)
set output output
scheme_of(p) = p[1:strstrt(p, "/") - 1]
mass_of(p) = p[strstrt(p, "/") + 1:]
dash(p) = mass_of(p) eq "mod3" ? 1 : 2
set logscale xy
set xlabel italic("N")
set ylabel "TV(".lambda_.") / TV(".lambda_."_{exact})"
# Panels placed by hand (a layout would also place the key's plot): cols a row, the key above them.
set multiplot
panel_height = rows == 2 ? 0.40 : 0.66
unset key
do for [b=1:words(benchmarks)] {
  set origin 0.01 + ((b - 1) % cols) * 0.98 / cols, (rows - 1 - (b - 1) / cols) * panel_height
  set size 0.98 / cols, panel_height
  set title word(benchmarks, b)
  plot 1 with lines lc rgb "#000000" dt 3 notitle, \
       for [p=1:words(pairs)] $runs index (b - 1) * words(pairs) + p - 1 \
       using (strcol(1) eq word(benchmarks, b) && strcol(2) eq scheme_of(word(pairs, p)) && strcol(3) eq mass_of(word(pairs, p)) && $4 == 0.5 ? $5 : NaN):16 \
       with linespoints lc rgb scheme_colour(scheme_of(word(pairs, p))) dt dash(word(pairs, p)) pt 7 ps 0.4 \
       notitle
}
# The key: one frameless plot across the top of the page, four entries a row (a panel's width is too
# narrow for a horizontal key).
set origin 0, rows * panel_height
set size 1, 1 - rows * panel_height
unset border; unset tics; unset xlabel; unset ylabel; unset title; unset logscale; unset grid
set xrange [0:1]; set yrange [0:1]
set key center center horizontal maxcols 4 samplen 2 width 0
plot for [p=1:words(pairs)] NaN with linespoints lc rgb scheme_colour(scheme_of(word(pairs, p))) \
     dt dash(word(pairs, p)) pt 7 ps 0.4 title scheme_of(word(pairs, p))." + ".mass_of(word(pairs, p))
unset multiplot
