# The contact stresses (experiments/fig_stress.cpp), paper's benchmark, ten periods:
# top left, TV(stress)/TV(λ) against N for CN + Mod 3 at Δt/h = 1/2 with the four stresses of
# lib/measures/contact_stress.hpp, the B-spline window on the phase-matched run and the multiplier of CN-switch
# (A = 1/4), with the predicted slope 1/2 of the multiplier; top right, the relative L² error of the
# same; bottom, the four stresses and the exact λ over the last period (the blocks are found by their
# `# block benchmark:variant:stress = k` lines).
# Usage: gnuplot -e "data='output/data/fig_stress.dat'; output='output/figures/fig_stress.pdf'" figures/fig_stress.gp
if (!exists("data")) data = 'output/data/fig_stress.dat'
if (!exists("output")) output = 'output/figures/fig_stress.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

# The report includes it at 0.9 \textwidth.
eval sprintf("set terminal %s size %.2fcm,17cm", figure_terminal, 0.9 * text_width)
set output output
set multiplot

block(key) = int(header("block ".key))
keys = "paper:cn:c12:multiplier paper:cn:c12:box paper:cn:c12:window paper:cn:c12:recovered paper:pm:c12:window paper:sw:c12:multiplier"
titles = "'multiplier' 'box window 8W' 'B-spline window 8W' 'recovered, k = 4W/h' 'B-spline window, A = 1/4' 'CN-switch multiplier, A = 1/4'"
colour(k) = curve_colour(k)
tv0 = real(header("tv_multiplier_N0"))
n0 = real(header("st_N0"))

# Top: two panels against N, one key above them (inside the left panel it covered its curves and
# stretched its axis to 400 for data below 30); each y axis spans the decades of its data.
set lmargin at screen 0.1; set rmargin at screen 0.5; set tmargin at screen 0.87; set bmargin at screen 0.6
set logscale xy
set xrange [n0 / 1.5 : real(header("st_Nmax")) * 1.5]
set format y "%g"
set key at screen 0.5, 0.995 center top vertical maxrows 3 samplen 2 width 1
set title "TV(stress)/TV(".lambda_.")"
set xlabel italic("N")
set ylabel "ratio"
lo = 1e300; hi = 0
do for [k=1:6] {
  stats data index block(word(keys, k)) using (positive($2)) nooutput
  lo = STATS_min < lo ? STATS_min : lo; hi = STATS_max > hi ? STATS_max : hi
}
STATS_min = lo; STATS_max = hi
@fit_log_y
plot for [k=1:6] data index block(word(keys, k)) using 1:2 with linespoints lc rgb colour(k) @measured_style title word(titles, k), \
  tv0 * (x / n0)**0.5 with lines @reference_style dt 3 title italic("N")."^{1/2} (the multiplier's prediction)"
unset key

set lmargin at screen 0.59; set rmargin at screen 0.98
set title "relative error of ".lambda_." in ".italic("L")."^2(0,".italic("T").")"
set ylabel "error"
set autoscale y
lo = 1e300; hi = 0
do for [k=1:6] {
  stats data index block(word(keys, k)) using (positive($3)) nooutput
  lo = STATS_min < lo ? STATS_min : lo; hi = STATS_max > hi ? STATS_max : hi
}
STATS_min = lo; STATS_max = hi
@fit_log_y
plot for [k=1:6] data index block(word(keys, k)) using 1:3 with linespoints lc rgb colour(k) @measured_style notitle

unset logscale
set autoscale
set lmargin at screen 0.1; set rmargin at screen 0.98; set tmargin at screen 0.48; set bmargin at screen 0.07
set key bottom right
set title "the stresses over the last period, CN + Mod 3, ".Delta_t."/".italic("h")." = 1/2, ".italic("N")." = ".header("history_N")
set xlabel italic("t")
set ylabel lambda_
# The exact stress first, under the others (the B-spline window lies on it).
plot data index block("history") using 1:2 with lines @exact_style title "exact", \
  data index block("history") using 1:3 with lines lc rgb colour(1) lw 1.2 title "multiplier", \
  data index block("history") using 1:4 with lines lc rgb colour(2) lw 1.2 title "box window", \
  data index block("history") using 1:6 with lines lc rgb colour(4) lw 1.2 title "recovered", \
  data index block("history") using 1:5 with lines lw 1.5 lc rgb colour(3) title "B-spline window"
unset multiplot
