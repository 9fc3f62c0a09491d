# Which redistribution, and why (experiments/fig_family.cpp): Crank–Nicolson on two meshes and two steps
# over the longer horizon (read from the data), for some twenty members of the weighted family.
# Left: the measured drift of the impact times per period, relative to Mod 3's in the same configuration,
# against the period law's prediction 2 dm_loc + 1.5 dm_glob (the diagonal: the law holds).
# Right: the geometric mean over the eight measures of error / Mod 3's error against the same measured
# drift: one V for every member, whatever the family.
# Usage: gnuplot -e "data='output/data/fig_family.dat'; output='output/figures/fig_family.pdf'" figures/fig_family.gp
if (!exists("data")) data = 'output/data/fig_family.dat'
if (!exists("output")) output = 'output/figures/fig_family.pdf'

dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,10cm
set output output

# Blocks 4a + 2b + c: two meshes, two steps, two horizons; the longer horizon's blocks are odd. Each
# block's N, dt/h and periods come from its "# block b: N = ..., dt/h = ..., periods = ..." line.
block_value(b, key) = system(sprintf("sed -n 's|^# block %d: .*%s = \\([^,]*\\).*|\\1|p' '%s'", b, key, data))
step_text(r) = r eq "1" ? italic("h") : r eq "0.5" ? italic("h")."/2" : r.italic("h")
label(b) = sprintf("%s = %s, %s = %s, %s periods", italic("N"), block_value(b, "N"), Delta_t, \
  step_text(block_value(b, "dt/h")), block_value(b, "periods"))
colour(f) = f eq "mod" ? 0x000000 : f eq "spread" ? 0x2ca02c : f eq "beta" ? 0x1f77b4 : 0xd62728
point(b) = b == 1 ? 7 : b == 3 ? 5 : b == 5 ? 9 : 11
# One key above both panels, two columns: the runs (marker) and the families (colour).
set multiplot layout 1,2 margins 0.08,0.98,0.12,0.74 spacing 0.1,0
set key at screen 0.5,0.995 center top vertical maxrows 4 samplen 1 width 2
h_ = italic("h")
drift = "measured drift − Mod 3's (per period, /".h_.")"

set title "drift per period against the period law (dashed)"
set xlabel "predicted Δ".italic("P")."/".h_." = 2".delta_.italic("m")."_{loc} + 1.5".delta_.italic("m")."_{glob}"
set ylabel drift
set xrange [-2.2:1.5]
set yrange [-2.2:1.5]
set size ratio -1
plot x with lines @reference_style dt 2 notitle, \
     for [b in "1 3 5 7"] data index (b+0) using 8:12:(colour(strcol(3))) with points pt point(b+0) ps 0.6 \
       lc rgb variable notitle, \
     for [b in "1 3 5 7"] keyentry with points pt point(b+0) ps 0.6 lc rgb "#555555" title label(b+0), \
     keyentry with points pt 7 ps 0.6 lc rgb "#000000" title "Mod 1/2/3", \
     keyentry with points pt 7 ps 0.6 lc rgb "#2ca02c" title "spread:".italic("K"), \
     keyentry with points pt 7 ps 0.6 lc rgb "#1f77b4" title "beta:".italic("B"), \
     keyentry with points pt 7 ps 0.6 lc rgb "#d62728" title "node1:".italic("X")
unset key
set size noratio
set title "error relative to Mod 3 (geometric mean of 8 measures)"
set xlabel drift
set ylabel "error / Mod 3's error"
set xrange [-2.2:1.5]
set yrange [0.9:*]
set logscale y
set ytics 1, 2
set format y "%g"
plot for [b in "1 3 5 7"] data index (b+0) using 12:13:(colour(strcol(3))) with points pt point(b+0) ps 0.6 \
       lc rgb variable notitle
unset multiplot
