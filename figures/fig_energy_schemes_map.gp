# The largest E_h^n/E_h(0) against dt/h, one panel per mesh, one curve per scheme of the file
# (fig_energy_schemes --view map). Schemes, meshes, mass and horizon are read from the data file's header
# (blocks "scheme = s, N = n", up to the long runs); the axes are set by the data.
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
marker(s) = word("7 6 4 8 5 9", s) + 0

set multiplot layout 2,(nm + 1) / 2 margins 0.09,0.98,0.08,0.9 spacing 0.09,0.14
set logscale x 2
set logscale y 10
set format y "10^{%L}"
set autoscale xfix
set offsets graph 0.03, graph 0.03, 0, 0
set xlabel Delta_t." / ".italic("h")
set ylabel "max_{/:Italic n} ".E_h."^{/:Italic n} / ".E_h."(0)"
set key at screen 0.5,0.995 center top vertical maxrows 1 samplen 2 width 2
do for [k=1:nm] {
  set title sprintf("%s = %s, %s, %s = %s", italic("N"), word(meshes, k), mass_name(header("mass")), italic("T"), \
    header("T"))
  plot for [s=1:ns] data index nm*(s-1)+k-1 using 1:2 with linespoints lc rgb scheme_colour(word(schemes, s)) \
         pt marker(s) ps 0.8 title scheme_name(word(schemes, s))
  unset key
}
unset multiplot
