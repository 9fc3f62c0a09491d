# Profiles: the displacement u(x,t) along the bar at the instants of the data file (block headers
# "exact, t = ..."), exact (black) against Mod 1, Mod 2, Mod 3 (nodal values joined by lines). The
# scheme and the instants are read from the data file; all panels share one y-range, set by the data.
# Usage: gnuplot -e "data='output/data/fig_profiles.dat'; output='output/figures/fig_profiles.pdf'" figures/fig_profiles.gp
if (!exists("data")) data = 'output/data/fig_profiles.dat'
if (!exists("output")) output = 'output/figures/fig_profiles.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,12cm
set output output

# The instants, from the block headers ("# block 0: exact, t = 0.5").
instants = system(sprintf("sed -n 's/^# block [0-9]*: exact, t = //p' '%s'", data))
count = words(instants)
scheme = scheme_name(header("scheme"))
# The masses, from the nodal blocks' column names ("x u_mod1 u_mod2 u_mod3").
nodal = system(sprintf("sed -n 's/^# columns: x u_\\(mod.\\) u_\\(mod.\\) u_\\(mod.\\)$/\\1 \\2 \\3/p' '%s' | head -n 1", data))
# One y-range for every panel: the extreme values of every displacement in the file.
ylimits = system(sprintf("awk '!/^#/ && NF > 1 { for (i = 2; i <= NF; ++i) { if (lo == \"\" || $i < lo) lo = $i; if (hi == \"\" || $i > hi) hi = $i } } END { print lo, hi }' '%s'", data))
ymin = word(ylimits, 1) + 0
ymax = word(ylimits, 2) + 0
margin = 0.05 * (ymax - ymin)
phase(t) = (t - 3*floor(t/3)) < 1 ? "free flight" : (t - 3*floor(t/3)) < 2 ? "contact" : "release"

cols = (count+1)/2
set multiplot layout 2,cols margins 0.08,0.98,0.08,0.83 spacing 0.05,0.11 \
  title scheme.", ".italic("N")." = ".header("elements").", ".Delta_t." = ".header("dt")
set autoscale xfix
set yrange [ymin - margin:ymax + margin]
set key at screen 0.5,0.925 center top vertical maxrows 1 samplen 3 width 2
do for [k=0:count-1] {
  t = word(instants, k+1) + 0
  set title sprintf("%s = %s (%s)", italic("t"), word(instants, k+1), phase(t))
  # The panels share their axes: the labels on the outer panels only.
  if (k % cols == 0) { set ylabel italic("u")."(".italic("x").",".italic("t").")"; set format y "%g" } else { unset ylabel; set format y "" }
  if (k >= count - cols) { set xlabel italic("x") } else { unset xlabel }
  plot data index 2*k using 1:2 with lines lc rgb "black" lw 2.5 title "exact", \
       for [m=1:3] data index 2*k+1 using 1:(column(1+m)) with linespoints lc rgb mass_colour(m) lw 1 pt 7 ps 0.3 \
         title mass_name(word(nodal, m))
  unset key
}
unset multiplot
