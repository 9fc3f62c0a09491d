# Convergence on the field's benchmarks (bouncing, impacting, gravity-paper, layered, two-bars; Crank–Nicolson,
# dt = h/(2c)): four relative errors against h, one panel per benchmark and measure, one curve per mass
# (Mod 1 red, Mod 2 blue, Mod 3 green); the grey lines are reference slopes h^{1/3} and h^{2/3} (the
# conjectured orders with a release). Blocks 0..14 of the data file (two-bars: h of one bar) ("benchmark = b, mass = m"); the axes are set by the data (y: the decades of the panel's errors, the
# reference slopes clipped to them).
# Usage: gnuplot -e "data='output/data/fig_benchmark_convergence.dat'; output='output/figures/fig_benchmark_convergence.pdf'" figures/fig_benchmark_convergence.gp
if (!exists("data")) data = 'output/data/fig_benchmark_convergence.dat'
if (!exists("output")) output = 'output/figures/fig_benchmark_convergence.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

# The report includes it at 0.88 \textwidth.
eval sprintf("set terminal %s size %.2fcm,22cm", figure_terminal, 0.88 * text_width)
set output output

benchmarks = "bouncing impacting gravity-paper layered two-bars"
masses = "mod1 mod2 mod3"
measures = "err_u_L2L2 err_lambda_L2 err_u_L2H1 err_v_L2L2"
# The block of (benchmark, mass): the number after "# block " on its header line, read from the data
# file's comment lines (style.gp's `comments`) without starting a process; -1 if it has none.
block_key(b, m) = ": benchmark = ".b.", mass = ".m.","
block_at(s) = (s > 6 ? word(comments[s-6:s-1], words(comments[s-6:s-1])) + 0 : -1)
block_of(b, m) = block_at(strstrt(comments, block_key(b, m)))
column_of(name) = sum [k=1:words(columns)] (word(columns, k) eq name ? k : 0)
mass_index(id) = id eq "mod1" ? 1 : id eq "mod2" ? 2 : 3

set logscale x 2
set logscale y 10
set format x "2^{%L}"
set format y "10^{%L}"
set autoscale xfix
set offsets graph 0.05, graph 0.05, 0, 0
set multiplot layout 5,4 title "Convergence on the field's benchmarks (Crank–Nicolson, ".Delta_t." = ".italic("h")."/2".italic("c").")" \
  margins 0.1,0.98,0.05,0.9 spacing 0.07,0.045
do for [i=1:5] {
  b = word(benchmarks, i)
  do for [k=1:4] {
    id = word(measures, k)
    c = column_of(id)
    set title b.": ".measure_short(id)
    anchor = block_of(b, "mod1")
    set autoscale y
    stats data index anchor using 2 nooutput
    h0 = STATS_max
    stats data index anchor every ::0::0 using (column(c)) nooutput
    e0 = STATS_max / 2.0
    lo = 1e300; hi = 0
    do for [m in masses] {
      stats data index block_of(b, m) using (positive(column(c))) nooutput
      lo = STATS_min < lo ? STATS_min : lo; hi = STATS_max > hi ? STATS_max : hi
    }
    STATS_min = lo; STATS_max = hi
    @fit_log_y
    # The rows share the h axis: its tic labels and label under the last row only.
    if (i == 5) { set xlabel italic("h"); set format x "2^{%L}" } else { unset xlabel; set format x "" }
    if (i == 1 && k == 1) {
      set key at screen 0.5,0.955 center top vertical maxrows 1 samplen 3 width 1
    } else {
      unset key
    }
    plot for [m in masses] data index block_of(b, m) using 2:(column(c) > 0 ? column(c) : 1/0) \
           with linespoints lc rgb mass_colour(mass_index(m)) @measured_style title mass_name(m), \
         e0*(x/h0)**(1.0/3) with lines @reference_style dt 3 title "slope 1/3", \
         e0*(x/h0)**(2.0/3) with lines @reference_style dt 4 title "slope 2/3"
  }
}
unset multiplot
