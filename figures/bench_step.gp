# bench_step.gp: the cost of one time step per node against the mesh size (make bench).
#
#   gnuplot -e "data='output/bench/bench_step.dat'; output='output/bench/bench_step.pdf'" figures/bench_step.gp
#   gnuplot -e "data='...'; output='....png'; format='png'" figures/bench_step.gp
#
# Input: the data file of experiments/bench_step.cpp, columns
#   log2N N, then for cn, be, ps, cn+errors, bare, eigen, bare2, cn_ref, be_ref, ps_ref in turn: median,
#   minimum, steps per batch (cn, be, ps: the fast step; *_ref: the reference step of lib/time/schemes.cpp).
# A flat curve is a cost linear in N; the bare solve is the practical limit of a step.
if (!exists("data")) data = 'output/bench/bench_step.dat'
if (!exists("output")) output = 'output/bench/bench_step.pdf'
if (!exists("format")) format = 'pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

if (format eq 'png') {
  set terminal pngcairo size 900,560 font font(12) enhanced
} else {
  set terminal @figure_terminal size 14cm,8.6cm
}
set output output

set logscale x 2
set format x '2^{%L}'
set xlabel italic('N').' (elements)'
set ylabel 'ns per node per step (median)'
set yrange [0:*]
set key outside right top box
set grid

# median of variant k (0-based) is column 3 + 3k
median(k) = column(3 + 3 * k)
plot data using 2:(median(0)) with linespoints lw 2 pt 7 title 'Crank-Nicolson', \
     data using 2:(median(1)) with linespoints lw 2 pt 5 title 'backward Euler', \
     data using 2:(median(2)) with linespoints lw 2 pt 9 title 'Paoli-Schatzman', \
     data using 2:(median(3)) with linespoints lw 1 pt 6 dt 2 title 'CN + error measures', \
     data using 2:(median(4)) with linespoints lw 2 pt 4 lc rgb 'black' title 'bare solve (limit)', \
     data using 2:(median(6)) with linespoints lw 1 pt 12 lc rgb 'gray40' dt 3 title 'bare solve, two chains', \
     data using 2:(median(5)) with linespoints lw 1 pt 3 lc rgb 'dark-red' title 'Eigen SimplicialLDLT', \
     data using 2:(median(7)) with linespoints lw 1 pt 6 lc 1 dt 4 title 'CN, reference step', \
     data using 2:(median(8)) with linespoints lw 1 pt 4 lc 2 dt 4 title 'BE, reference step', \
     data using 2:(median(9)) with linespoints lw 1 pt 8 lc 3 dt 4 title 'PS, reference step'
