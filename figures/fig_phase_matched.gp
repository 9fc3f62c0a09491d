# The phase-matched interior mass (experiments/fig_phase_matched.cpp): top, the relative
# phase-speed error |ω̃/k − 1| of Crank–Nicolson against ξ = kh (block 0) for Δt/h = ½ with A = 0 and
# A = ¼ and Δt/h = 1/√2 with A = 0, with the slopes 2 and 4 of the derivation; bottom, the error of u in
# L²(0,T;L²) of CN + Mod 3 on the paper's benchmark over ten periods (T = 30) against N for the same
# three variants (the blocks found by their header lines; column 9 is err_u_L2L2, see "# columns").
# Usage: gnuplot -e "data='output/data/fig_phase_matched.dat'; output='output/figures/fig_phase_matched.pdf'" figures/fig_phase_matched.gp
if (!exists("data")) data = 'output/data/fig_phase_matched.dat'
if (!exists("output")) output = 'output/figures/fig_phase_matched.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

# The report includes it at 0.9 \textwidth.
eval sprintf("set terminal %s size %.2fcm,16cm", figure_terminal, 0.9 * text_width)
set output output
set multiplot layout 2,1 margins 0.12,0.97,0.07,0.95 spacing 0.0,0.125

dt_h = Delta_t."/".italic("h")
# (a function, not a word list: math()'s font name is quoted)
title_of(k) = k == 1 ? dt_h." = 1/2, ".italic("A")." = 0" : k == 2 ? dt_h." = 1/2, ".italic("A")." = 1/4 (matched)" : \
  dt_h." = 2^{−1/2}, ".italic("A")." = 0 (matched)"
colour(k) = curve_colour(k)
set logscale xy
set format y "10^{%T}"
# The x axes end at the data (autoscaled to whole decades they ran to 10 and to 10^4).
set autoscale xfix
set offsets graph 0.02, graph 0.02, 0, 0
set key top left
set title "relative phase-speed error of Crank–Nicolson with the blended mass"
set xlabel xi_." = ".italic("kh")
set ylabel "|".math("𝜔̃")."/".italic("k")." − 1|"
plot for [k=1:3] data index 0 using 1:(column(k+1)) with lines lc rgb colour(k) lw 1.2 title title_of(k), \
  x**2/48 with lines @reference_style dt 3 title xi_."^2/48 (slope 2)", \
  x**4/512 with lines @reference_style dt 4 title xi_."^4/512 (slope 4)"

# The blocks of the three variants, paper's benchmark, T = 30.
block(pattern) = int(system(sprintf("sed -n 's/^# block \\([0-9]*\\): benchmark = paper, scheme = cn, mass = mod3, interior_mass = %s, dt\\/h = %s, T = 30$/\\1/p' '%s'", pattern[1:strstrt(pattern, "|")-1], pattern[strstrt(pattern, "|")+1:], data)))
b1 = block("consistent|0.5")
b2 = block("blend:0.25|0.5")
b3 = block("consistent|0.7071067811865475")
set title "error of ".italic("u")." in ".italic("L")."^2(0,".italic("T").";".italic("L")."^2), CN + Mod 3, paper's benchmark, ".italic("T")." = 30"
set xlabel italic("N")
set ylabel "relative error"
set format x "%g"
stats data index b1 using 1 nooutput
set xtics STATS_min, 2
plot data index b1 using 1:9 with linespoints lc rgb colour(1) @measured_style title title_of(1), \
  data index b2 using 1:9 with linespoints lc rgb colour(2) @measured_style title title_of(2), \
  data index b3 using 1:9 with linespoints lc rgb colour(3) @measured_style title title_of(3)
unset multiplot
