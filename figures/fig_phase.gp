# The mechanism of the ranking: errors against time (top) and the impact-time errors against the period
# law's prediction (bottom), for Mod 1, Mod 2 and Mod 3 (experiments/fig_phase.cpp).
# Usage: gnuplot -e "data='output/data/fig_phase.dat'; output='output/figures/fig_phase.pdf'" figures/fig_phase.gp
if (!exists("data")) data = 'output/data/fig_phase.dat'
if (!exists("output")) output = 'output/figures/fig_phase.pdf'

set terminal pdfcairo size 16cm,17cm font "Helvetica,9" linewidth 1.5 enhanced
set output output
set style line 1 lc rgb "#d62728" lw 1.0
set style line 2 lc rgb "#1f77b4" lw 1.0
set style line 3 lc rgb "#2ca02c" lw 1.0
set grid lc rgb "#dddddd" lw 0.5
set multiplot layout 3,1 margins 0.11,0.97,0.06,0.95 spacing 0.0,0.07
set key top left font ",9"

set title "Error of the contact point |u_0^n - u(0,t_n)|" font ",10"
set xlabel "t"
set ylabel "error"
plot for [m=0:2] data index m using 1:2 with lines ls m+1 title sprintf("Mod %d", m+1)

set title "L^2 error of u, ||u_h - u_I||" font ",10"
plot for [m=0:2] data index m using 1:3 with lines ls m+1 title sprintf("Mod %d", m+1)

set title "Impact-time errors t_k - (1 + 3k): measured (points) and period law e_0 + k {/Symbol D}P (lines)" font ",10"
set xlabel "exact impact time t_k"
set ylabel "time error"
plot for [m=0:2] data index 3+m using 2:3 with points ls m+1 pt 7 ps 0.4 title sprintf("Mod %d measured", m+1), \
     for [m=0:2] data index 3+m using 2:4 with lines ls m+1 dt 2 title sprintf("Mod %d law", m+1)
unset multiplot
