# The eight relative errors of each scheme of the file divided by Crank-Nicolson's with the same mass,
# one panel per mesh (fig_energy_schemes --view measures); 1 = as accurate as Crank-Nicolson. Schemes
# and masses are read from the rows (columns scheme, mass), the measures, meshes, step and horizon from
# the data file's header; the y-axis is set by the data.
# Usage: gnuplot -e "data='output/data/fig_energy_schemes_measures.dat'; output='output/figures/fig_energy_schemes_measures.pdf'" figures/fig_energy_schemes_measures.gp
if (!exists("data")) data = 'output/data/fig_energy_schemes_measures.dat'
if (!exists("output")) output = 'output/figures/fig_energy_schemes_measures.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,13cm
set output output

# Row layout: scheme mass, the 8 errors, the 8 ratios to Crank-Nicolson's, the energy lost.
measures = system(sprintf("sed -n 's/^# columns: .*sec. 5: //p' '%s' | head -n 1", data))
nk = words(measures)
meshes = system(sprintf("sed -n 's/^# block [0-9]*: N = \\([0-9]*\\)$/\\1/p' '%s'", data))
schemes = system(sprintf("awk '!/^#/ && NF && $1 != \"cn\" {print $1}' '%s' | awk '!seen[$0]++'", data))
masses = system(sprintf("awk '!/^#/ && NF {print $2}' '%s' | awk '!seen[$0]++'", data))
ns = words(schemes)
nm = words(masses)
marker(m) = word("4 6 7 8", m) + 0
step(r) = r eq "1" ? italic("h") : (r + 0 < 1 ? italic("h")."/".sprintf("%g", 1 / (r + 0)) : r.italic("h"))

set multiplot layout words(meshes),1 margins 0.09,0.98,0.10,0.9 spacing 0.0,0.14
set grid ytics lc rgb "#dddddd" lw 0.5
set logscale y 10
# The y-range: the smallest and largest ratio of any panel, with a margin.
lo = 1; hi = 1
do for [b=1:words(meshes)] { do for [k=1:nk] {
  stats data index b-1 using (column(2 + nk + k)) nooutput
  lo = STATS_min < lo ? STATS_min : lo
  hi = STATS_max > hi ? STATS_max : hi
} }
set yrange [lo / 1.3:hi * 1.3]
set ytics (0.1, 0.2, 0.5, 0.7, 1, 1.5, 2, 3, 5, 10, 20, 50, 100, 200, 500, 1000)
set xrange [0.5:nk + 0.5]
set xtics ()
do for [k=1:nk] { set xtics add (measure_short("err_".word(measures, k)) k) }
set ylabel "error / Crank–Nicolson's"
# One legend above the panels, in one row: the colours (schemes), then the marks (masses).
set key at screen 0.5,0.995 center top vertical maxrows 1 samplen 1 width 1
do for [b=1:words(meshes)] {
  set title sprintf("%s = %s, %s = %s, %s = %s", italic("N"), word(meshes, b), Delta_t, step(header("dt\\/h")), \
    italic("T"), header("T"))
  plot 1 with lines lc rgb "#999999" dt 2 notitle, \
       for [s=1:ns] for [m=1:nm] for [k=1:nk] data index b-1 \
         using (strcol(1) eq word(schemes, s) && strcol(2) eq word(masses, m) ? k + 0.27*(s-(ns+1)/2.0) + 0.08*(m-(nm+1)/2.0) : NaN):(column(2 + nk + k)) \
         with points lc rgb scheme_colour(word(schemes, s)) pt marker(m) ps 0.7 notitle, \
       for [s=1:ns] NaN with points lc rgb scheme_colour(word(schemes, s)) pt 5 ps 0.9 title scheme_name(word(schemes, s)), \
       for [m=1:nm] NaN with points lc rgb "black" pt marker(m) ps 0.7 title mass_name(word(masses, m))
  unset key
}
unset multiplot
