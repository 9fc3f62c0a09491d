# Profiles: the displacement u(x,t) along the bar at two instants of each phase (free flight, contact,
# release) in the first and the third period, exact (black) against Mod 1, Mod 2, Mod 3 (nodal values joined by lines).
# Usage: gnuplot -e "data='output/data/fig_profiles.dat'; output='output/figures/fig_profiles.pdf'" figures/fig_profiles.gp
if (!exists("data")) data = 'output/data/fig_profiles.dat'
if (!exists("output")) output = 'output/figures/fig_profiles.pdf'

set encoding utf8
set terminal pdfcairo size 16cm,11cm font "Helvetica,9" linewidth 1.5 enhanced
set output output

# The instants, from the block headers ("# block 0: exact, t = 0.5").
instants = system(sprintf("sed -n 's/^# block [0-9]*: exact, t = //p' '%s'", data))
count = words(instants)
phase(t) = (t - 3*floor(t/3)) < 1 ? "free flight" : (t - 3*floor(t/3)) < 2 ? "contact" : "release"
colour(m) = m == 1 ? "#d62728" : m == 2 ? "#1f77b4" : "#2ca02c"

set multiplot layout 2,(count+1)/2 margins 0.08,0.98,0.09,0.87 spacing 0.07,0.15
set grid lc rgb "#dddddd" lw 0.5
set xlabel "x"
set ylabel "u(x,t)"
set xrange [0:1]
set yrange [-0.3:0.55]
set key at screen 0.5,0.99 center top vertical maxrows 1 font ",10" samplen 3 width 2
do for [k=0:count-1] {
  t = word(instants, k+1) + 0
  set title sprintf("t = %s (%s)", word(instants, k+1), phase(t)) font ",10"
  plot data index 2*k using 1:2 with lines lc rgb "black" lw 2.5 title "exact", \
       for [m=1:3] data index 2*k+1 using 1:(column(1+m)) with linespoints lc rgb colour(m) lw 1 pt 7 ps 0.3 \
         title sprintf("Mod %d", m)
  unset key
}
unset multiplot
