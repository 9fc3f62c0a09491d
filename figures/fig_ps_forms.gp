# Paoli-Schatzman (1/4, 0): u(0,t) (left) and the discrete energy (right) with the algebraic contact
# row (top), the literal three-level row (middle), both with a redistributed mass, and the literal row
# with the consistent mass (bottom). Exact solution in black.
# Usage: gnuplot -e "data='output/data/fig_ps_forms.dat'; output='output/figures/fig_ps_forms.pdf'" figures/fig_ps_forms.gp
if (!exists("data")) data = 'output/data/fig_ps_forms.dat'
if (!exists("output")) output = 'output/figures/fig_ps_forms.pdf'

set encoding utf8
set terminal pdfcairo size 16cm,18cm font "Helvetica,9" linewidth 1.5 enhanced
set output output

# The redistributed mass's name, read from the data file's header ("# mass = "mod3"").
mass = system(sprintf("sed -n 's/^# mass = \"mod\\([123]\\)\"$/Mod \\1/p' '%s'", data))
variant(v) = v == 1 ? "algebraic contact row, ".mass : v == 2 ? "literal contact row, ".mass : "literal row, consistent mass"
colour(v) = v == 1 ? "#2ca02c" : v == 2 ? "#d62728" : "#1f77b4"

set multiplot layout 3,2 margins 0.09,0.98,0.06,0.93 spacing 0.09,0.08
set grid lc rgb "#dddddd" lw 0.5
set xlabel "t"
set xtics 3
set key at screen 0.5,0.99 center top vertical maxrows 1 font ",10" samplen 3 width 2
do for [v=1:3] {
  set title variant(v) font ",10"
  set ylabel "u(0,t)"
  set yrange [-0.3:0.8]
  # The exact curve first and wide, the computed one over it: both stay visible where they agree.
  plot data index 0 using 1:2 with lines lc rgb "black" lw 3 title (v == 1 ? "exact" : ""), \
       data index v using 1:2 with lines lc rgb colour(v) lw 0.8 title (v == 1 ? "computed" : "")
  unset key
  set ylabel "E_h"
  set yrange [0.09:0.13]
  plot data index v using 3:4 with lines lc rgb colour(v) lw 1.2 notitle, \
       0.125 with lines lc rgb "black" lw 1.5 dt 2 notitle
}
unset multiplot
