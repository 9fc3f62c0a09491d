# The error estimate in time: at fixed h, the relative difference between Crank-Nicolson (left) or
# backward Euler (right) with step dt and a Crank-Nicolson reference with a much smaller step, in each
# measure of mathematics.md §5, on the fine mesh (top, data blocks 0 and 1) and on the coarse mesh whose
# steps reach the asymptotic range (bottom, blocks 2 and 3); grey lines are reference slopes dt^1 and dt^2.
# Usage: gnuplot -e "data='output/data/fig_time_error.dat'; output='output/figures/fig_time_error.pdf'" figures/fig_time_error.gp
if (!exists("data")) data = 'output/data/fig_time_error.dat'
if (!exists("output")) output = 'output/figures/fig_time_error.pdf'

set encoding utf8
set terminal pdfcairo size 16cm,16cm font "Helvetica,9" linewidth 1.5 enhanced
set output output

measure(k) = k == 1 ? "u(0,·), L^2_t" : k == 2 ? "λ, L^2_t" : k == 3 ? "u, L^∞_tL^2" : \
  k == 4 ? "u, L^∞_tH^1" : k == 5 ? "u_t, L^∞_tL^2" : k == 6 ? "u, L^2_tL^2" : \
  k == 7 ? "u, L^2_tH^1" : "u_t, L^2_tL^2"
colour(k) = word("#1f77b4 #ff7f0e #2ca02c #d62728 #9467bd #8c564b #e377c2 #17becf", k)
scheme(s) = s == 0 ? "Crank-Nicolson" : "backward Euler"
# The mesh of block b, read from the data file's header ("# block b: scheme = .., elements = N, ...").
elements(b) = system(sprintf("awk '/^# block %d:/{sub(/.*elements = /, \"\"); sub(/,.*/, \"\"); print; exit}' '%s'", b, data))

set logscale x 2
set format x "2^{%L}"
set logscale y 10
set format y "10^{%L}"
set xlabel "Δt / h"
set ylabel "relative difference to the reference"
set grid lc rgb "#dddddd" lw 0.5
set xrange [1/400.0:6]
set yrange [1e-7:1]
set multiplot layout 2,2 margins 0.09,0.98,0.07,0.88 spacing 0.08,0.09
set key at screen 0.5,0.995 center top vertical maxrows 2 font ",9" samplen 2 width 1
do for [i=0:1] {
  do for [s=0:1] {
    b = 2*i + s
    set title sprintf("%s, h = 1/%s", scheme(s), elements(b)) font ",10"
    plot for [k=1:8] data index b using 2:(column(2+k)) with linespoints lc rgb colour(k) pt (k+3) ps 0.6 lw 1.2 title measure(k), \
         0.03*(x/4)**1 with lines lc rgb "#777777" dt 4 lw 1 title "slope 1", \
         0.003*(x/4)**2 with lines lc rgb "#777777" dt 3 lw 1 title "slope 2"
    unset key
  }
}
unset multiplot
