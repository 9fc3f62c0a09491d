# Where the ranking Mod 3 < Mod 2 < Mod 1 holds: per scheme (rows) and dt/h (columns), the number of
# measures ranked as the paper says in each cell (N, horizon); green = all (experiments/fig_ordering_map.cpp).
# Usage: gnuplot -e "data='output/data/fig_ordering_map.dat'; output='output/figures/fig_ordering_map.pdf'" figures/fig_ordering_map.gp
if (!exists("data")) data = 'output/data/fig_ordering_map.dat'
if (!exists("output")) output = 'output/figures/fig_ordering_map.pdf'

set terminal pdfcairo size 17cm,13cm font "Helvetica,8" linewidth 1.0 enhanced
set output output
set palette defined (0 "#d62728", 0.5 "#ffdd55", 1 "#2ca02c")
set cbrange [0:1]
unset colorbox
set logscale xy
set xrange [16:1250]
set yrange [0.6:50]
set xtics ("25" 25, "50" 50, "100" 100, "200" 200, "400" 400, "800" 800) font ",7"
set ytics ("1" 1, "4" 4, "10" 10, "30" 30) font ",7"
scheme(s) = s == 0 ? "CN" : s == 1 ? "BE" : "PS (velocity)"
ratio(j) = j == 0 ? "1/4" : j == 1 ? "1/2" : j == 2 ? "3/4" : "1"
set multiplot layout 3,4 margins 0.07,0.98,0.07,0.95 spacing 0.02,0.06
do for [s=0:2] {
  do for [j=0:3] {
    set title sprintf("%s, {/Symbol D}t/h = %s", scheme(s), ratio(j)) font ",8"
    if (j == 0) { set ylabel "periods" } else { unset ylabel }
    if (s == 2) { set xlabel "N" } else { unset xlabel }
    plot data index 4*s+j using 1:2:($3/$4) with points pt 5 ps 2.6 lc palette notitle, \
         '' index 4*s+j using 1:2:(sprintf("%d", $3)) with labels font ",7" notitle
  }
}
unset multiplot
