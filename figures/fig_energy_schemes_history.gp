# Energy histories: E_h(t)/E_h(0) of each scheme of the file, one panel per ratio dt/h
# (fig_energy_schemes --view history). Schemes, ratios, mesh, mass and horizon are read from the data
# file's header (blocks "scheme = s, dt/h = r"); the axes are set by the data.
# Usage: gnuplot -e "data='output/data/fig_energy_schemes_history.dat'; output='output/figures/fig_energy_schemes_history.pdf'" figures/fig_energy_schemes_history.gp
if (!exists("data")) data = 'output/data/fig_energy_schemes_history.dat'
if (!exists("output")) output = 'output/figures/fig_energy_schemes_history.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,17cm
set output output

blocks = system(sprintf("awk '/^# block [0-9]+: scheme = /{sub(/,/, \"\", $6); print $6, $9}' '%s'", data))
nb = words(blocks) / 2
schemes = system(sprintf("awk '/^# block [0-9]+: scheme = /{sub(/,/, \"\", $6); print $6}' '%s' | awk '!seen[$0]++'", data))
ns = words(schemes)
nr = nb / ns
step(r) = r eq "1" ? italic("h") : (r + 0 < 1 ? italic("h")."/".sprintf("%g", 1 / (r + 0)) : r.italic("h"))
final_time = header("T") + 0
# The scheme that conserves the energy (EC, the header's `conserving`), dashed and thicker, so that the
# curves it covers stay visible.
conserving = header("conserving")
width_of(id) = id eq conserving ? 2.0 : 1.2
dash_of(id) = id eq conserving ? 2 : 1

# A row per step; left: every scheme on one axis; right: Crank-Nicolson and EC alone, on an axis fitted to
# them (on the left, Crank-Nicolson's jumps of a few thousandths at the small steps hide under EC's line).
set multiplot layout nr,2 margins 0.09,0.98,0.06,0.92 spacing 0.08,0.08
# The time axis is labelled under the last row only (under the others the label met the next title).
set xrange [0:final_time]
set xtics 6
set ylabel E_h."(".italic("t").") / ".E_h."(0)"
set key at screen 0.5,0.995 center top vertical maxrows 1 samplen 3 width 1
do for [c=0:nr-1] {
  if (c == nr - 1) { set xlabel italic("t") } else { unset xlabel }
  run = sprintf("%s = %s, %s = %s, %s", Delta_t, step(word(blocks, 2 * ns * c + 2)), italic("N"), header("N"), \
    mass_name(header("mass")))
  set title run
  set autoscale y
  set offsets 0, 0, graph 0.05, graph 0.05
  plot for [s=1:ns] data index ns*c+s-1 using 1:2 with lines lc rgb scheme_colour(word(schemes, s)) \
         lw width_of(word(schemes, s)) dashtype dash_of(word(schemes, s)) title scheme_name(word(schemes, s))
  unset key
  set title scheme_name(word(schemes, 1))." and ".scheme_name(conserving)." alone"
  plot for [s=1:ns] data index ns*c+s-1 using 1:(word(schemes, s) eq conserving || s == 1 ? $2 : NaN) with lines \
         lc rgb scheme_colour(word(schemes, s)) lw width_of(word(schemes, s)) dashtype dash_of(word(schemes, s)) notitle
}
unset multiplot
