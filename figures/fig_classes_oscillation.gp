# Stress oscillation (experiments/fig_classes.cpp, block 0): TV(λ)/TV(λ_exact) over the run against N,
# one panel per benchmark, Δt = h/2; one colour per class, solid with Mod 3, dashed with the consistent
# ("standard") mass; 1 is the exact solution's variation.
# Usage: gnuplot -e "data='output/data/fig_classes.dat'; output='output/figures/fig_classes_oscillation.pdf'" figures/fig_classes_oscillation.gp
if (!exists("data")) data = 'output/data/fig_classes.dat'
if (!exists("output")) output = 'output/figures/fig_classes_oscillation.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'
set terminal pdfcairo size 16cm,7cm font font(9) linewidth 1.5 enhanced
set output output
benchmarks = system(sprintf("awk '!/^#/ && NF == 20 {print $1}' '%s' | awk '!seen[$0]++'", data))
pairs = system(sprintf("awk '!/^#/ && NF == 20 {print $2\"/\"$3}' '%s' | awk '!seen[$0]++'", data))
scheme_of(p) = p[1:strstrt(p, "/") - 1]
mass_of(p) = p[strstrt(p, "/") + 1:]
dash(p) = mass_of(p) eq "mod3" ? 1 : 2
set logscale xy
set xlabel italic("N")
set ylabel "TV(".lambda_.") / TV(".lambda_."_{exact})"
set multiplot layout 1,words(benchmarks) margins 0.08,0.98,0.16,0.66 spacing 0.06,0
set key at screen 0.5,0.995 center top horizontal maxcols 5 samplen 2 width 0
do for [b=1:words(benchmarks)] {
  set title word(benchmarks, b)
  plot 1 with lines lc rgb "#000000" dt 3 notitle, \
       for [p=1:words(pairs)] data index 0 \
       using (strcol(1) eq word(benchmarks, b) && strcol(2) eq scheme_of(word(pairs, p)) && strcol(3) eq mass_of(word(pairs, p)) && $4 == 0.5 ? $5 : NaN):16 \
       with linespoints lc rgb scheme_colour(scheme_of(word(pairs, p))) dt dash(word(pairs, p)) pt 7 ps 0.4 \
       title (b == 1 ? scheme_of(word(pairs, p))." + ".mass_of(word(pairs, p)) : "")
  unset key
}
unset multiplot
