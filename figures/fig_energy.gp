# Energy: the discrete energy of every scheme and mass choice against the exact one. Crank–Nicolson and
# backward Euler show the two-level energy E_h = ½ VᵀMV + ½ UᵀSU; Paoli–Schatzman its own energy
# E_h^β (mathematics.md §4), the one its three-level step conserves. Schemes, masses, the exact energy
# and the time axis are read from the data file's header; the y-axes are set by the data.
# Usage: gnuplot -e "data='output/data/fig_energy.dat'; output='output/figures/fig_energy.pdf'" figures/fig_energy.gp
if (!exists("data")) data = 'output/data/fig_energy.dat'
if (!exists("output")) output = 'output/figures/fig_energy.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,17cm
set output output

# Block 3 s + m - 1 is scheme s, mass m.
blocks = system(sprintf("sed -n 's/^# block [0-9]*: scheme = \\([a-z]*\\), mass = \\([a-z0-9]*\\)$/\\1 \\2/p' '%s'", data))
scheme_id(s) = word(blocks, 2 * (3 * s) + 1)
mass_id(m) = word(blocks, 2 * (m - 1) + 2)
# The energy of scheme s (the data file's `# energy <id> = E_h` or `E_h^beta` line), in the report's symbols.
energy(s) = header("energy ".scheme_id(s)) eq "E_h^beta" ? E_h_beta : E_h
title(s) = scheme_title(scheme_id(s)).": ".energy(s)
energy_label(s) = energy(s)."(".italic("t").")"
exact_energy = header("exact_energy") + 0
final_time = header("final_time") + 0
exact_label = sprintf("exact %s = %g", italic("E"), exact_energy)

set multiplot layout 3,1 margins 0.10,0.97,0.06,0.91 spacing 0.0,0.08
set xrange [0:final_time]
set xtics 1
set offsets 0, 0, graph 0.05, graph 0.05
set key at screen 0.5,0.997 center top vertical maxrows 1 samplen 3 width 2
# The exact solution's impacts (t = 1 mod 3) and releases (t = 2 mod 3): thin vertical marks.
do for [k=0:int(final_time / 3)] {
  do for [j=1:2] {
    if (j + 3*k < final_time) {
      set arrow from first j+3*k, graph 0 to first j+3*k, graph 1 nohead lc rgb "#999999" dt 3 lw 0.5
    }
  }
}
do for [s=0:2] {
  # The panels share the time axis: its label under the last one only.
  if (s == 2) { set xlabel italic("t") }
  set title title(s)
  set ylabel energy_label(s)
  plot for [m=1:3] data index 3*s+m-1 using 1:2 with lines lc rgb mass_colour(m) lw 1.2 title mass_name(mass_id(m)), \
       exact_energy with lines lc rgb "black" lw 2.0 dt 2 title exact_label
  unset key
}
unset multiplot
