# Paoli-Schatzman (1/4, 0): u(0,t) (left) and its energy E_h^β (right, mathematics.md §4) for each
# block of the file: the algebraic contact row and the literal three-level row with a redistributed
# mass, and the literal row with the consistent mass. Exact solution in black. The forms, masses, the
# exact energy and the time axis are read from the data file's header; the y-axes are set by the data.
# Usage: gnuplot -e "data='output/data/fig_ps_forms.dat'; output='output/figures/fig_ps_forms.pdf'" figures/fig_ps_forms.gp
if (!exists("data")) data = 'output/data/fig_ps_forms.dat'
if (!exists("output")) output = 'output/figures/fig_ps_forms.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,18cm
set output output

# Blocks 1..3: "form = f, mass = m".
blocks = system(sprintf("sed -n 's/^# block [0-9]*: form = \\([a-z]*\\), mass = \\([a-z0-9]*\\)$/\\1 \\2/p' '%s'", data))
form(v) = word(blocks, 2 * v - 1)
mass_of(v) = word(blocks, 2 * v)
variant(v) = form(v)." contact row, ".mass_name(mass_of(v))
colour(v) = mass_of(v) eq "consistent" ? mass_colour(4) : form(v) eq "algebraic" ? mass_colour(3) : mass_colour(1)
exact_energy = header("exact_energy") + 0
final_time = header("final_time") + 0

set multiplot layout 3,2 margins 0.09,0.98,0.06,0.89 spacing 0.09,0.08
set xrange [0:final_time]
set xtics 3
set offsets 0, 0, graph 0.05, graph 0.05
# One legend for the figure, above the panels (drawn with the first panel): every colour named.
set key at screen 0.5,0.995 center top vertical maxrows 2 samplen 3 width 2
do for [v=1:3] {
  # The rows share the time axis: its label under the last row only.
  if (v == 3) { set xlabel italic("t") }
  set title variant(v)
  set ylabel italic("u")."(0,".italic("t").")"
  # The exact curve first and wide, the computed one over it: both stay visible where they agree.
  plot data index 0 using 1:2 with lines lc rgb "black" lw 3 title "exact", \
       data index v using 1:2 with lines lc rgb colour(v) lw 0.8 notitle, \
       for [w=1:(v == 1 ? 3 : 0)] NaN with lines lc rgb colour(w) lw 1.2 title variant(w), \
       for [w=1:(v == 1 ? 1 : 0)] NaN with lines lc rgb "black" lw 1.5 dt 2 title sprintf("exact energy %g", exact_energy)
  unset key
  set ylabel E_h_beta
  plot data index v using 3:4 with lines lc rgb colour(v) lw 1.2 notitle, \
       exact_energy with lines lc rgb "black" lw 1.5 dt 2 notitle
}
unset multiplot
