# Convergence: every relative error of mathematics.md §5 against h, one page per scheme, one panel per
# measure, Mod 1/2/3 in colour, the first ratio Δt/h of the file solid with filled marks, the second
# dashed with open marks; the grey lines are reference slopes h^(1/2) and h^1 through the Mod 3 errors.
# Schemes, masses, ratios and measures are read from the data file's block and column headers; the axes
# are set by the data (each panel's y axis spans the decades of its errors; a reference slope is clipped
# to them).
# Usage: gnuplot -e "data='output/data/fig_convergence.dat'; output='output/figures/fig_convergence.pdf'" figures/fig_convergence.gp
if (!exists("data")) data = 'output/data/fig_convergence.dat'
if (!exists("output")) output = 'output/figures/fig_convergence.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

# The report includes each page at 0.95 \textwidth.
eval sprintf("set terminal %s size %.2fcm,21cm", figure_terminal, 0.95 * text_width)
set output output

# Block 2 (3 s + m - 1) + c is scheme s, mass m, ratio c.
blocks = system(sprintf("sed -n 's/^# block [0-9]*: scheme = \\([a-z]*\\), mass = \\([a-z0-9]*\\), dt\\/h = \\(.*\\)$/\\1 \\2 \\3/p' '%s'", data))
scheme_id(s) = word(blocks, 3 * (6 * s) + 1)
mass_id(m) = word(blocks, 3 * (2 * (m - 1)) + 2)
ratio(c) = word(blocks, 3 * c + 3)
ratio_label(c) = ratio(c) eq "1" ? italic("h") : ratio(c) eq "0.5" ? italic("h")."/2" : ratio(c).italic("h")
title(s) = scheme_title(scheme_id(s))
dash(c) = c == 0 ? 1 : 2
marker(c) = c == 0 ? 7 : 6

set logscale x 2
set logscale y 10
set format x "2^{%L}"
set format y "10^{%L}"
set ylabel "relative error"
set mxtics 1
set xtics 2
set autoscale xfix
set offsets graph 0.03, graph 0.03, 0, 0
do for [s=0:2] {
  set multiplot layout 4,2 title title(s) font font(11) margins 0.09,0.98,0.05,0.86 spacing 0.09,0.075
  do for [k=1:8] {
    set title measure_name(word(columns, 3 + k))
    set autoscale y
    # Reference slopes through the Mod 3 error of the first ratio on the coarsest mesh, shifted down by 2.
    stats data index 2*(3*s+2) every ::0::0 using 2 nooutput
    h0 = STATS_max
    stats data index 2*(3*s+2) every ::0::0 using (column(3+k)) nooutput
    e0 = STATS_max / 2.0
    stats data index 2*(3*s):2*(3*s)+5 using (positive(column(3+k))) nooutput
    @fit_log_y
    if (k >= 7) { set xlabel italic("h") } else { unset xlabel }
    if (k == 1) {
      set key at screen 0.5,0.945 center top vertical maxrows 2 samplen 3 width 1
    } else {
      unset key
    }
    # Entries ordered Mod 1 (first ratio, second), Mod 2 (...), Mod 3 (...): the key's columns are the masses.
    plot for [j=0:5] data index 2*(3*s+j/2)+j%2 using 2:(column(3+k)) with linespoints lc rgb mass_colour(j/2+1) lw 1.2 \
           dt dash(j%2) pt marker(j%2) ps 0.55 title sprintf("%s, %s = %s", mass_name(mass_id(j/2+1)), Delta_t, ratio_label(j%2)), \
         e0*(x/h0)**0.5 with lines @reference_style dt 3 title "slope 1/2", \
         e0*(x/h0) with lines @reference_style dt 4 title "slope 1"
  }
  unset multiplot
}
