# Convergence: every relative error of mathematics.md §5 against h, with dt = h (solid, filled marks)
# and dt = h/2 (dashed, open marks), Mod 1/2/3 in colour; one page per scheme, one panel per measure;
# the grey dashed lines are reference slopes h^(1/2) and h^1.
# Usage: gnuplot -e "data='output/data/fig_convergence.dat'; output='output/figures/fig_convergence.pdf'" figures/fig_convergence.gp
if (!exists("data")) data = 'output/data/fig_convergence.dat'
if (!exists("output")) output = 'output/figures/fig_convergence.pdf'

set encoding utf8
set terminal pdfcairo size 16cm,21cm font "Helvetica,9" linewidth 1.5 enhanced
set output output

scheme(s) = s == 0 ? "Crank-Nicolson" : s == 1 ? "backward Euler" : "Paoli-Schatzman (1/4, 0), literal contact row"
measure(k) = k == 1 ? "u(0,·) in L^2(0,T)" : k == 2 ? "λ in L^2(0,T)" : k == 3 ? "u in L^∞(0,T;L^2)" : \
  k == 4 ? "u in L^∞(0,T;H^1)" : k == 5 ? "u_t in L^∞(0,T;L^2)" : k == 6 ? "u in L^2(0,T;L^2)" : \
  k == 7 ? "u in L^2(0,T;H^1)" : "u_t in L^2(0,T;L^2)"
dash(j) = j % 2 == 0 ? 1 : 2
marker(j) = j % 2 == 0 ? 7 : 6
ratio(j) = j % 2 == 0 ? "h" : "h/2"
colour(m) = m == 1 ? "#d62728" : m == 2 ? "#1f77b4" : "#2ca02c"

set logscale x 2
set logscale y 10
set format x "2^{%L}"
set format y "10^{%L}"
set xlabel "h"
set ylabel "relative error"
set grid lc rgb "#dddddd" lw 0.5
set mxtics 1
set xrange [1/5000.0:1/100.0]
set xtics 2
do for [s=0:2] {
  set multiplot layout 4,2 title scheme(s) font ",11" margins 0.09,0.98,0.05,0.86 spacing 0.09,0.05
  do for [k=1:8] {
    set title measure(k) font ",9"
    # Reference slopes through the Mod 3, dt = h error on the coarsest mesh, shifted down by 2.
    stats data index 2*(3*s+2) using 2:(column(3+k)) nooutput
    h0 = STATS_max_x
    e0 = STATS_max_y / 2.0
    stats data index 2*(3*s+2) every ::0::0 using (column(3+k)) nooutput
    e0 = STATS_max / 2.0
    if (k >= 7) { set xlabel "h" } else { unset xlabel }
    if (k == 1) {
      set key at screen 0.5,0.945 center top vertical maxrows 2 font ",9" samplen 3 width 1
    } else {
      unset key
    }
    # Entries ordered Mod 1 (dt = h, h/2), Mod 2 (...), Mod 3 (...): the key's columns are the masses.
    plot for [j=0:5] data index 2*(3*s+j/2)+j%2 using 2:(column(3+k)) with linespoints lc rgb colour(j/2+1) lw 1.2 \
           dt dash(j) pt marker(j) ps 0.55 title sprintf("Mod %d, Δt = %s", j/2+1, ratio(j)), \
         e0*(x/h0)**0.5 with lines lc rgb "#777777" dt 3 lw 1 title "slope 1/2", \
         e0*(x/h0) with lines lc rgb "#777777" dt 4 lw 1 title "slope 1"
  }
  unset multiplot
}
