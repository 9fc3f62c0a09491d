# The paper's Figure 1: u(0,t) (left) and the contact stress lambda(t) (right), one row per scheme,
# the exact solution (black) against Mod 1, Mod 2, Mod 3, and the baseline Paoli-Schatzman with the
# consistent mass (grey). The third row is Paoli-Schatzman with the contact row the report believes the
# paper used (the data file's ps_form). The axes are fitted to the data: no curve is clipped.
# Usage: gnuplot -e "data='output/data/fig_contact_history.dat'; output='output/figures/fig_contact_history.pdf'" figures/fig_contact_history.gp
if (!exists("data")) data = 'output/data/fig_contact_history.dat'
if (!exists("output")) output = 'output/figures/fig_contact_history.pdf'

set terminal pdfcairo size 16cm,20cm font "Helvetica,9" linewidth 1.5 enhanced
set output output
set datafile missing NaN

scheme(s) = s == 0 ? "Crank-Nicolson" : s == 1 ? "backward Euler" : "Paoli-Schatzman (1/4, 0), algebraic contact row (= CN in u, {/Symbol l})"
set style line 1 lc rgb "black" lw 2.0 dt 1
set style line 2 lc rgb "#d62728" lw 1.0 dt 1
set style line 3 lc rgb "#1f77b4" lw 1.0 dt 1
set style line 4 lc rgb "#2ca02c" lw 1.0 dt 1
set style line 5 lc rgb "#7f7f7f" lw 1.0 dt 2

set multiplot layout 3,2 margins 0.08,0.98,0.05,0.93 spacing 0.08,0.07
set grid lc rgb "#dddddd" lw 0.5
set xlabel "t"
set xrange [0:*]
set xtics 1
# One legend for the whole figure, above the panels.
set key at screen 0.5,0.985 center top vertical maxrows 1 font ",10" samplen 3 width 2
do for [s=0:2] {
  set title scheme(s) font ",10"
  set ylabel "u(0,t)"
  set autoscale y
  plot data index 10 using 1:2 with lines ls 5 title "PS, consistent mass (baseline)", \
       for [m=1:3] data index 1+3*s+m-1 using 1:2 with lines ls 1+m title sprintf("Mod %d", m), \
       data index 0 using 1:2 with lines ls 1 title "exact"
  unset key
  set ylabel "{/Symbol l}(t)"
  set autoscale y
  plot data index 10 using 3:4 with lines ls 5 notitle, \
       for [m=1:3] data index 1+3*s+m-1 using 3:4 with lines ls 1+m notitle, \
       data index 0 using 1:3 with lines ls 1 notitle
}
unset multiplot
