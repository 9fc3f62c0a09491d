# The largest E_h^n/E_h(0) over 100 periods against dt/h, one panel per mesh N = 16, 32, 64, 128, for
# Crank-Nicolson, EC, CN-switch and backward Euler (fig_energy_schemes --view map; mass in the data header).
# Usage: gnuplot -e "data='output/data/fig_energy_schemes_map.dat'; output='output/figures/fig_energy_schemes_map.pdf'" figures/fig_energy_schemes_map.gp
if (!exists("data")) data = 'output/data/fig_energy_schemes_map.dat'
if (!exists("output")) output = 'output/figures/fig_energy_schemes_map.pdf'

set encoding utf8
set terminal pdfcairo size 16cm,13cm font "Helvetica,9" linewidth 1.5 enhanced
set output output

mesh(k) = k == 0 ? 16 : k == 1 ? 32 : k == 2 ? 64 : 128
label(s) = s == 0 ? "Crank-Nicolson" : s == 1 ? "EC" : s == 2 ? "CN-switch" : "backward Euler"
colour(s) = s == 0 ? "#d62728" : s == 1 ? "black" : s == 2 ? "#1f77b4" : "#2ca02c"
marker(s) = s == 0 ? 7 : s == 1 ? 6 : s == 2 ? 4 : 8

set multiplot layout 2,2 margins 0.09,0.98,0.08,0.90 spacing 0.09,0.11
set grid lc rgb "#dddddd" lw 0.5
set logscale x 2
set logscale y 10
set format y "10^{%L}"
set xrange [0.2:50]
set yrange [0.5:1e13]
set xlabel "Δt / h"
set ylabel "max_n E_h^n / E_h(0)"
set key at screen 0.5,0.985 center top vertical maxrows 1 font ",10" samplen 2 width 2
do for [k=0:3] {
  set title sprintf("N = %d", mesh(k)) font ",10"
  plot for [s=0:3] data index 4*s+k using 1:2 with linespoints lc rgb colour(s) pt marker(s) ps 0.8 title label(s)
  unset key
}
unset multiplot
