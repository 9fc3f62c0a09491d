# Energy over long times (experiments/fig_classes.cpp, block 3): E_h/E_h(0) every 10 periods of the
# paper's benchmark (one impact per period) on the long runs' mesh, one panel per Δt/h; one colour per
# class, solid with Mod 3, dashed with the consistent ("standard") mass. Log scale in y.
# Usage: gnuplot -e "data='output/data/fig_classes.dat'; output='output/figures/fig_classes_energy.pdf'" figures/fig_classes_energy.gp
if (!exists("data")) data = 'output/data/fig_classes.dat'
if (!exists("output")) output = 'output/figures/fig_classes_energy.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'
set terminal @figure_terminal size 16cm,8.5cm
set output output
# The pairs, the long runs' dt/h and their energy, one block a dt/h and pair, read in one pass
# (figures/fig_classes_blocks.awk).
load sprintf("< awk -f '%sfig_classes_blocks.awk' '%s'", dir, data)
scheme_of(p) = p[1:strstrt(p, "/") - 1]
mass_of(p) = p[strstrt(p, "/") + 1:]
dash(p) = mass_of(p) eq "mod3" ? 1 : 2
set logscale y
set xlabel "periods (impacts)"
set xtics 250
set ylabel E_h." / ".E_h."(0)"
set yrange [1e-8:1e8]
set format y "10^{%L}"
# Panels placed by hand, one a Δt/h, the key above them in a frameless plot across the page (a panel is
# too narrow for a horizontal key; inside one, the key covered the curves of the middle panel).
n = words(courants)
panel_width = (0.98 - 0.08 - (n - 1) * 0.06) / n
set multiplot
unset key
do for [k=1:n] {
  set lmargin at screen 0.08 + (k - 1) * (panel_width + 0.06)
  set rmargin at screen 0.08 + (k - 1) * (panel_width + 0.06) + panel_width
  set tmargin at screen 0.66
  set bmargin at screen 0.14
  set title sprintf("%s = %.3g %s, %s = %s", Delta_t, word(courants, k) + 0, italic("h"), italic("N"), header("long_mesh"))
  plot 1 with lines lc rgb "#000000" dt 3 notitle, \
       for [p=1:words(pairs)] $energy index (k - 1) * words(pairs) + p - 1 \
       using (strcol(1) eq scheme_of(word(pairs, p)) && strcol(2) eq mass_of(word(pairs, p)) && strcol(3) eq word(courants, k) ? $4 : NaN):5 \
       with lines lc rgb scheme_colour(scheme_of(word(pairs, p))) dt dash(word(pairs, p)) notitle
}
set lmargin at screen 0; set rmargin at screen 1; set tmargin at screen 1; set bmargin at screen 0.74
unset border; unset tics; unset xlabel; unset ylabel; unset title; unset logscale; unset grid
set xrange [0:1]; set yrange [0:1]
set key center center horizontal maxcols 4 samplen 2 width 0
plot for [p=1:words(pairs)] NaN with lines lc rgb scheme_colour(scheme_of(word(pairs, p))) dt dash(word(pairs, p)) \
     title scheme_of(word(pairs, p))." + ".mass_of(word(pairs, p))
unset multiplot
