# Penetration (experiments/fig_classes.cpp, block 0): the largest penetration max_t(−u(0, t)) against
# N, one panel per benchmark, Δt = h/2; one colour per class, solid with Mod 3, dashed with the
# consistent ("standard") mass. Linear in y: every class that enforces the constraint exactly sits at 0.
# Usage: gnuplot -e "data='output/data/fig_classes.dat'; output='output/figures/fig_classes_penetration.pdf'" figures/fig_classes_penetration.gp
if (!exists("data")) data = 'output/data/fig_classes.dat'
if (!exists("output")) output = 'output/figures/fig_classes_penetration.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'
set terminal pdfcairo size 16cm,7cm font font(9) linewidth 1.5 enhanced
set output output
benchmarks = system(sprintf("awk '!/^#/ && NF == 20 {print $1}' '%s' | awk '!seen[$0]++'", data))
pairs = system(sprintf("awk '!/^#/ && NF == 20 {print $2\"/\"$3}' '%s' | awk '!seen[$0]++'", data))
scheme_of(p) = p[1:strstrt(p, "/") - 1]
mass_of(p) = p[strstrt(p, "/") + 1:]
dash(p) = mass_of(p) eq "mod3" ? 1 : 2
set logscale x
set xlabel italic("N")
set ylabel "max penetration"
stats data index 0 using 17 nooutput
set yrange [-0.001 - STATS_max * 0.05:STATS_max * 1.1 + 0.001]
set multiplot layout 1,words(benchmarks) margins 0.08,0.98,0.16,0.66 spacing 0.06,0
set key at screen 0.5,0.995 center top horizontal maxcols 5 samplen 2 width 0
do for [b=1:words(benchmarks)] {
  set title word(benchmarks, b)
  plot for [p=1:words(pairs)] data index 0 \
       using (strcol(1) eq word(benchmarks, b) && strcol(2) eq scheme_of(word(pairs, p)) && strcol(3) eq mass_of(word(pairs, p)) && $4 == 0.5 ? $5 : NaN):17 \
       with linespoints lc rgb scheme_colour(scheme_of(word(pairs, p))) dt dash(word(pairs, p)) pt 7 ps 0.4 \
       title (b == 1 ? scheme_of(word(pairs, p))." + ".mass_of(word(pairs, p)) : "")
  unset key
}
unset multiplot
