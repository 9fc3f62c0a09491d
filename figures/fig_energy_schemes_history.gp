# Energy histories: E_h(t)/E_h(0) of Crank-Nicolson, EC, CN-switch and backward Euler over 10 periods,
# one panel per ratio dt/h = 1/2, 1, 5 (fig_energy_schemes --view history; mesh and mass in the data header).
# Usage: gnuplot -e "data='output/data/fig_energy_schemes_history.dat'; output='output/figures/fig_energy_schemes_history.pdf'" figures/fig_energy_schemes_history.gp
if (!exists("data")) data = 'output/data/fig_energy_schemes_history.dat'
if (!exists("output")) output = 'output/figures/fig_energy_schemes_history.pdf'

set encoding utf8
set terminal pdfcairo size 16cm,17cm font "Helvetica,9" linewidth 1.5 enhanced
set output output

ratio(c) = c == 0 ? "Δt = h/2" : c == 1 ? "Δt = h" : "Δt = 5h"
label(s) = s == 0 ? "Crank-Nicolson" : s == 1 ? "EC (energy-conserving CN)" : s == 2 ? "CN-switch" : "backward Euler"
set style line 1 lc rgb "#d62728" lw 1.2 dt 1
set style line 2 lc rgb "black" lw 2.0 dt 2
set style line 3 lc rgb "#1f77b4" lw 1.2 dt 1
set style line 4 lc rgb "#2ca02c" lw 1.2 dt 1

set multiplot layout 3,1 margins 0.10,0.97,0.06,0.93 spacing 0.0,0.08
set grid lc rgb "#dddddd" lw 0.5
set xlabel "t"
set xtics 3
set xrange [0:30]
set yrange [0:1.2]
set ylabel "E_h(t) / E_h(0)"
set key at screen 0.5,0.985 center top vertical maxrows 1 font ",9" samplen 2 width -1
do for [c=0:2] {
  set title ratio(c) font ",10"
  plot for [s=0:3] data index 4*c+s using 1:2 with lines ls s+1 title label(s)
  unset key
}
unset multiplot
