# Observed orders in h against the horizon, at one ratio dt/h (the variable `ratio`, 0.5 unless given):
# u(0,.) in L^2(0,T) (a displacement) and u in L^inf(0,T;H^1) (energy-type) for each mass, Crank-Nicolson
# (top) and backward Euler (bottom), with the Paoli-Schatzman baseline on the Crank-Nicolson panels,
# beside the predicted orders (dashed: the smearing of the fronts; dotted: the phase error of Mod 1 and
# Mod 2) (experiments/fig_order_map.cpp). Blocks are found by their headers ("scheme = s, mass = m,
# dt/h = r"), columns by their names; the axes are set by the data.
# Usage: gnuplot -e "data='output/data/fig_order_map.dat'; output='output/figures/fig_order_map.pdf'" figures/fig_order_map.gp
if (!exists("data")) data = 'output/data/fig_order_map.dat'
if (!exists("output")) output = 'output/figures/fig_order_map.pdf'
if (!exists("ratio")) ratio = "0.5"
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,12cm
set output output

# The index of the first block with this scheme, mass and ratio (-1 if none): the number after "# block "
# on its header line, read from the data file's comment lines (style.gp's `comments`) without starting a
# process.
block_at(p) = (p > 6 ? word(comments[p-6:p-1], words(comments[p-6:p-1])) + 0 : -1)
block(s, m) = block_at(strstrt(comments, ": scheme = ".s.", mass = ".m.", dt/h = ".ratio."\n"))
column_of(name) = sum [k=1:words(columns)] (word(columns, k) eq name ? k : 0)
mass_index(id) = id eq "mod1" ? 1 : id eq "mod2" ? 2 : id eq "mod3" ? 3 : 4
masses = "mod1 mod2 mod3"
measures = "err_u0_L2 err_u_LinfH1"
predicted = "predicted_u predicted_energy"

set logscale x
# The horizons of the sweep (the first column of a block) as the tics.
horizons = system(sprintf("awk '/^# block 1:/{exit} !/^#/ && NF {print $1}' '%s'", data))
set xtics ()
do for [k=1:words(horizons)] { set xtics add (word(horizons, k) word(horizons, k) + 0) }
set autoscale xfix
set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05
set yrange [0:*]
# One legend for the whole figure, above the panels (inside a panel it covered the curves): the first
# panel, which has every entry (the baseline's too), draws it; the others draw none.
set key at screen 0.5,0.955 center top vertical maxrows 2 samplen 2 width 1
set ylabel "order in ".italic("h")
set multiplot layout 2,2 margins 0.08,0.98,0.08,0.81 spacing 0.08,0.1 \
  title sprintf("%s = %s%s", Delta_t, ratio, italic("h"))
first_panel = 1
do for [scheme in header("panels")] {
  # The rows share the horizon axis: its label under the last row only.
  if (scheme eq word(header("panels"), words(header("panels")))) { set xlabel "horizon (periods)" }
  do for [q=1:2] {
    col = column_of(word(measures, q))
    pcol = column_of(word(predicted, q))
    phase = q == 1 ? 1.0 : 0.5
    set title scheme_name(scheme).", ".measure_name(word(measures, q))
    if (!first_panel) { unset key }
    base = block("ps-consistent", "consistent")
    if (scheme eq header("baseline_with") && base >= 0) {
      plot for [m=1:3] data index block(scheme, word(masses, m)) using 1:col with linespoints \
             lc rgb mass_colour(m) lw 1.2 pt 6+m ps 0.6 title mass_name(word(masses, m)), \
           data index base using 1:col with linespoints lc rgb mass_colour(4) lw 1.2 dt 2 pt 13 ps 0.6 \
             title scheme_title("ps-consistent"), \
           data index block(scheme, "mod3") using 1:pcol with lines lc rgb "black" dt 2 title "predicted", \
           phase with lines lc rgb "black" dt 3 title "phase error (Mod 1, 2)"
    } else {
      plot for [m=1:3] data index block(scheme, word(masses, m)) using 1:col with linespoints \
             lc rgb mass_colour(m) lw 1.2 pt 6+m ps 0.6 title mass_name(word(masses, m)), \
           data index block(scheme, "mod3") using 1:pcol with lines lc rgb "black" dt 2 title "predicted", \
           phase with lines lc rgb "black" dt 3 title "phase error (Mod 1, 2)"
    }
    first_panel = 0
  }
}
unset multiplot
