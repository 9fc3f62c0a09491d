# Crank-Nicolson's largest energy relative to E_h(0): against dt/h (left, Mod 3, one line per mesh) and
# over the long runs at dt = h (right, one line per mass) (experiments/fig_stability_map.cpp). The
# meshes, the horizons and the threshold of "bounded" are read from the data file's header; the axes
# are set by the data.
# Usage: gnuplot -e "data='output/data/fig_stability_map.dat'; output='output/figures/fig_stability_map.pdf'" figures/fig_stability_map.gp
if (!exists("data")) data = 'output/data/fig_stability_map.dat'
if (!exists("output")) output = 'output/figures/fig_stability_map.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,7.5cm
set output output

# Blocks 0..n-1: one mesh each ("# block b: N = 16"); block n: the long runs.
meshes = system(sprintf("sed -n 's/^# block [0-9]*: N = \\([0-9]*\\)$/\\1/p' '%s'", data))
n = words(meshes)
threshold = header("threshold") + 0
masses = "mod1 mod2 mod3"
mesh_colour(b) = word("#1b9e77 #d95f02 #7570b3 #e7298a #66a61e #e6ab02", b)

set logscale xy
set format y "10^{%L}"
set autoscale xfix
set offsets graph 0.03, graph 0.03, 0, 0
set multiplot layout 1,2 margins 0.09,0.98,0.14,0.9 spacing 0.1,0.0
set title sprintf("%s periods, %s", header("periods"), mass_name("mod3"))
set xlabel Delta_t." / ".italic("h")
# Tics at every factor of 2 from the smallest ratio of the data.
stats data index 0 using 1 nooutput
set xtics STATS_min, 2
set format x "%g"
set ylabel "max ".E_h." / ".E_h."(0)"
set key top left samplen 2
plot for [b=1:n] data index b-1 using 1:2 with linespoints lc rgb mesh_colour(b) pt 7 ps 0.4 \
       title sprintf("%s = %s", italic("N"), word(meshes, b)), \
     threshold with lines lc rgb "black" dt 2 title sprintf("%g %s(0)", threshold, E_h)
long_step = header("long_courant") eq "1" ? italic("h") : header("long_courant").italic("h")
set title sprintf("%s periods, %s = %s", header("long_periods"), Delta_t, long_step)
set xlabel italic("N")
# Mod 1 starts high on the coarsest mesh (top left): the key goes where no curve is.
set key top right
set xtics ()
do for [b=1:n] { set xtics add (word(meshes, b) word(meshes, b) + 0) }
# Within a decade or two, tics at every factor of 2 (powers of ten alone left two labels).
set ytics 2
set format y "%g"
plot for [m=1:3] data index n using ($1 == m ? $2 : NaN):3 with linespoints lc rgb mass_colour(m) pt 7 ps 0.5 \
       title mass_name(word(masses, m)), \
     threshold with lines lc rgb "black" dt 2 title sprintf("%g %s(0)", threshold, E_h)
unset multiplot
