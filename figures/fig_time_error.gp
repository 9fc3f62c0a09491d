# The error estimate in time: at fixed h, the relative difference between each scheme of the file
# (Crank-Nicolson left, backward Euler right) with step dt and a Crank-Nicolson reference with a much
# smaller step, in each measure of mathematics.md §5, on the fine mesh (top, data blocks 0 and 1) and on
# the coarse mesh whose steps reach the asymptotic range (bottom, blocks 2 and 3); grey lines are
# reference slopes dt^1 and dt^2 through each panel's smallest-step value of u in L^inf(0,T;L^2).
# Schemes, measures, meshes and reference ratios are read from the data file's header (blocks
# "scheme = s, elements = N, reference_ratio = R"); the axes are set by the data (y: the decades of the
# panel's errors, the reference slopes clipped to them).
# Usage: gnuplot -e "data='output/data/fig_time_error.dat'; output='output/figures/fig_time_error.pdf'" figures/fig_time_error.gp
if (!exists("data")) data = 'output/data/fig_time_error.dat'
if (!exists("output")) output = 'output/figures/fig_time_error.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,16cm
set output output

colour(k) = curve_colour(k)
# The value of `key = ` in the header line of block b ("# block b: scheme = cn, elements = 256, ...").
block_value(b, key) = system(sprintf("sed -n 's/^# block %d: .*%s = \\([a-z0-9]*\\).*$/\\1/p' '%s' | head -n 1", \
  b, key, data))
blocks = system(sprintf("grep -c '^# block [0-9]*: scheme = ' '%s'", data)) + 0

set logscale x 2
set logscale y 10
set format x "2^{%L}"
set format y "10^{%L}"
set xlabel Delta_t." / ".italic("h")
set ylabel "relative difference to the reference"
set autoscale xfix
set offsets graph 0.03, graph 0.03, 0, 0
# The anchor of the reference slopes: u in L^inf(0,T;L^2).
anchor = 0
do for [k=1:8] { if (word(columns, 2 + k) eq "err_u_LinfL2") { anchor = k } }
set multiplot layout blocks/2,2 margins 0.09,0.98,0.07,0.86 spacing 0.08,0.14
set key at screen 0.5,0.995 center top vertical maxrows 2 samplen 2 width 1
do for [b=0:blocks-1] {
  set autoscale y
  stats data index b using 2 nooutput
  x0 = STATS_min
  stats data index b using (column(2 + anchor)) nooutput
  e0 = STATS_min / 3.0
  # The y axis spans the decades of the panel's data; the reference slopes are clipped to it (drawn in
  # full, slope 2 ran the backward Euler panels up to 10^2 above data that stay below 1).
  stats data index b using (positive(column(3))) nooutput
  lo = STATS_min; hi = STATS_max
  do for [k=2:8] {
    stats data index b using (positive(column(2 + k))) nooutput
    lo = STATS_min < lo ? STATS_min : lo; hi = STATS_max > hi ? STATS_max : hi
  }
  STATS_min = lo; STATS_max = hi
  @fit_log_y
  set title sprintf("%s, %s = 1/%s, reference %s = %s/%s", scheme_name(block_value(b, "scheme")), italic("h"), \
    block_value(b, "elements"), Delta_t."_{ref}", italic("h"), block_value(b, "reference_ratio"))
  plot for [k=1:8] data index b using 2:(column(2+k)) with linespoints lc rgb colour(k) pt (k+3) ps 0.6 lw 1.2 \
         title measure_name(word(columns, 2+k)), \
       e0*(x/x0)**1 with lines @reference_style dt 3 title "slope 1", \
       e0*(x/x0)**2 with lines @reference_style dt 4 title "slope 2"
  unset key
}
unset multiplot
