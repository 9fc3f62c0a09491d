# The largest E_h^n/E_h(0) against dt/h, one panel per scheme of the file, one curve per mesh
# (fig_energy_schemes --view map). Schemes, meshes, mass and horizon are read from the data file's header
# (blocks "scheme = s, N = n", up to the long runs); the axes are set by the data, each panel its own: a
# scheme whose energy grows by more than a factor 2 on a log axis, the others, which stay at E_h(0) up to
# round-off, as (max E_h^n/E_h(0) - 1)/eps, eps the spacing of doubles at 1, on a linear one (on one
# shared log axis, they hid under each other on the line 1).
# Usage: gnuplot -e "data='output/data/fig_energy_schemes_map.dat'; output='output/figures/fig_energy_schemes_map.pdf'" figures/fig_energy_schemes_map.gp
if (!exists("data")) data = 'output/data/fig_energy_schemes_map.dat'
if (!exists("output")) output = 'output/figures/fig_energy_schemes_map.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,13cm
set output output

schemes = system(sprintf("awk '/^# block [0-9]+: scheme = .*, N = /{sub(/,/, \"\", $6); print $6}' '%s' | awk '!seen[$0]++'", data))
meshes = system(sprintf("awk '/^# block [0-9]+: scheme = .*, N = /{print $9}' '%s' | awk '!seen[$0]++'", data))
ns = words(schemes)
nm = words(meshes)
marker(k) = word("7 6 5 4 9 8", k) + 0
size(k) = word("0.9 1.3 0.8 1.2 0.9 1.3", k) + 0

set multiplot layout (ns + 1) / 2,2 margins 0.1,0.98,0.08,0.9 spacing 0.1,0.13
set logscale x 2
set autoscale xfix
set offsets graph 0.03, graph 0.03, graph 0.05, graph 0.05
set xlabel Delta_t." / ".italic("h")
set key at screen 0.5,0.995 center top vertical maxrows 1 samplen 2 width 2
# The spacing of doubles at 1 (2^-52): the unit of round-off.
epsilon = 2.0**-52
largest = "max_{/:Italic n} ".E_h."^{/:Italic n} / ".E_h."(0)"
do for [s=1:ns] {
  set title sprintf("%s, %s, %s = %s", scheme_name(word(schemes, s)), mass_name(header("mass")), italic("T"), header("T"))
  stats data index nm*(s-1):nm*s-1 using 2 nooutput
  grows = STATS_max > 2
  if (grows) {
    set logscale y 10
    set format y "10^{%L}"
    set ylabel largest
  } else {
    unset logscale y
    set format y "%g"
    set ylabel "(".largest." − 1) / ".epsilon_
    if (STATS_max == STATS_min) { set yrange [-1:1] } else { set autoscale y }
  }
  plot for [k=1:nm] data index nm*(s-1)+k-1 using 1:(grows ? $2 : ($2 - 1) / epsilon) with linespoints \
         lc rgb curve_colour(k) pt marker(k) ps size(k) title sprintf("%s = %s", italic("N"), word(meshes, k))
  unset key
}
unset multiplot
