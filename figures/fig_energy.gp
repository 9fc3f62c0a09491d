# Energy: the discrete energy E_h(t) of every scheme and mass choice against the exact 1/8.
# Usage: gnuplot -e "data='output/data/fig_energy.dat'; output='output/figures/fig_energy.pdf'" figures/fig_energy.gp
if (!exists("data")) data = 'output/data/fig_energy.dat'
if (!exists("output")) output = 'output/figures/fig_energy.pdf'

set terminal pdfcairo size 16cm,17cm font "Helvetica,9" linewidth 1.5 enhanced
set output output

scheme(s) = s == 0 ? "Crank-Nicolson" : s == 1 ? "backward Euler" : "Paoli-Schatzman (1/4, 0), literal contact row"
set style line 1 lc rgb "black" lw 2.0 dt 2
set style line 2 lc rgb "#d62728" lw 1.2 dt 1
set style line 3 lc rgb "#1f77b4" lw 1.2 dt 1
set style line 4 lc rgb "#2ca02c" lw 1.2 dt 1

set multiplot layout 3,1 margins 0.10,0.97,0.06,0.93 spacing 0.0,0.08
set grid lc rgb "#dddddd" lw 0.5
set xlabel "t"
set xtics 1
set ylabel "E_h(t)"
set key at screen 0.5,0.985 center top vertical maxrows 1 font ",10" samplen 3 width 2
# Impact at t = 1 mod 3, release at t = 2 mod 3: thin vertical marks.
set for [k=0:2] arrow from first 1+3*k, graph 0 to first 1+3*k, graph 1 nohead lc rgb "#999999" dt 3 lw 0.5
set for [k=0:2] arrow from first 2+3*k, graph 0 to first 2+3*k, graph 1 nohead lc rgb "#999999" dt 3 lw 0.5
do for [s=0:2] {
  set title scheme(s) font ",10"
  if (s == 0) { set yrange [0.1175:0.1255] } else { if (s == 1) { set yrange [0:0.13] } else { set yrange [0.1:0.128] } }
  plot for [m=1:3] data index 3*s+m-1 using 1:2 with lines ls 1+m title sprintf("Mod %d", m), \
       0.125 with lines ls 1 title "exact E = 1/8"
  unset key
}
unset multiplot
