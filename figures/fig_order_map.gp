# Observed orders in h against the horizon, at dt = h/2: u(0,.) (displacement) and u in L^inf(H^1)
# (energy-type) for Mod 1/2/3, Crank-Nicolson (top) and backward Euler (bottom), beside the predicted
# orders (dashed: smearing of the fronts; dotted: phase error of Mod 1 and Mod 2) (experiments/fig_order_map.cpp).
# Usage: gnuplot -e "data='output/data/fig_order_map.dat'; output='output/figures/fig_order_map.pdf'" figures/fig_order_map.gp
if (!exists("data")) data = 'output/data/fig_order_map.dat'
if (!exists("output")) output = 'output/figures/fig_order_map.pdf'

set terminal pdfcairo size 16cm,12cm font "Helvetica,9" linewidth 1.5 enhanced
set output output
set style line 1 lc rgb "#d62728" lw 1.2 pt 7
set style line 2 lc rgb "#1f77b4" lw 1.2 pt 5
set style line 3 lc rgb "#2ca02c" lw 1.2 pt 9
set style line 4 lc rgb "#7f7f7f" lw 1.2 pt 13
set logscale x
set xrange [0.8:40]
set xtics ("1" 1, "4" 4, "10" 10, "30" 30)
set yrange [0:1.2]
set grid lc rgb "#dddddd" lw 0.5
set key bottom right font ",8"
# Block of (scheme s, mass m, ratio j = 1 for dt/h = 1/2): (3 s + m) 4 + 1; the baseline is scheme 3.
b(s, m) = (3*s + m)*4 + 1
set multiplot layout 2,2 margins 0.08,0.98,0.08,0.94 spacing 0.08,0.1
do for [s=0:1] {
  do for [q=0:1] {
    col = q == 0 ? 2 : 5
    set title sprintf("%s, %s", s == 0 ? "Crank-Nicolson" : "backward Euler", q == 0 ? "u(0,.) in L^2(0,T)" : "u in L^{/Symbol \245}(H^1)") font ",10"
    set xlabel "horizon (periods)"
    set ylabel "order in h"
    if (s == 0) {
      plot for [m=0:2] data index b(s, m) using 1:col with linespoints ls m+1 title sprintf("Mod %d", m+1), \
           data index b(3, 0) using 1:col with linespoints ls 4 title "PS consistent", \
           data index b(s, 2) using 1:(q == 0 ? $10 : $11) with lines lc rgb "black" dt 2 title "predicted", \
           (q == 0 ? 1.0 : 0.5) with lines lc rgb "black" dt 3 title "phase error (Mod 1, 2)"
    } else {
      plot for [m=0:2] data index b(s, m) using 1:col with linespoints ls m+1 title sprintf("Mod %d", m+1), \
           data index b(s, 2) using 1:(q == 0 ? $10 : $11) with lines lc rgb "black" dt 2 title "predicted"
    }
  }
}
unset multiplot
