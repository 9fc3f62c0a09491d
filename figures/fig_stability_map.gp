# Crank-Nicolson's largest energy relative to E_h(0): against dt/h over 100 periods (left, Mod 3, one
# line per mesh) and over 1000 periods at dt = h (right, Mod 1, 2, 3) (experiments/fig_stability_map.cpp).
# Usage: gnuplot -e "data='output/data/fig_stability_map.dat'; output='output/figures/fig_stability_map.pdf'" figures/fig_stability_map.gp
if (!exists("data")) data = 'output/data/fig_stability_map.dat'
if (!exists("output")) output = 'output/figures/fig_stability_map.pdf'

set terminal pdfcairo size 16cm,7cm font "Helvetica,9" linewidth 1.5 enhanced
set output output
set grid lc rgb "#dddddd" lw 0.5
set logscale xy
set format y "10^{%L}"
set multiplot layout 1,2 margins 0.09,0.98,0.14,0.9 spacing 0.1,0.0
set title "100 periods, Mod 3" font ",10"
set xlabel "{/Symbol D}t/h"
set ylabel "max E_h / E_h(0)"
set key top left font ",8"
plot for [b=0:3] data index b using 1:2 with linespoints pt 7 ps 0.4 title sprintf("N = %d", 16*2**b), \
     2 with lines lc rgb "black" dt 2 title "2 E_h(0)"
set title "1000 periods, {/Symbol D}t = h" font ",10"
set xlabel "N"
set xrange [12:170]
set xtics (16, 32, 64, 128)
plot for [m=1:3] data index 4 using ($1 == m ? $2 : NaN):3 with linespoints pt 7 title sprintf("Mod %d", m), \
     2 with lines lc rgb "black" dt 2 title "2 E_h(0)"
unset multiplot
