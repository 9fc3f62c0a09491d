# Where the ranking Mod 3 < Mod 2 < Mod 1 holds: per scheme (rows) and dt/h (columns), the number of
# measures ranked as the paper says in each cell (N, horizon), coloured from red (none) to green (all)
# (experiments/fig_ordering_map.cpp). Schemes, ratios, meshes and horizons are read from the data file
# (block headers "scheme = s, dt/h = r" and the cells themselves).
# Usage: gnuplot -e "data='output/data/fig_ordering_map.dat'; output='output/figures/fig_ordering_map.pdf'" figures/fig_ordering_map.gp
if (!exists("data")) data = 'output/data/fig_ordering_map.dat'
if (!exists("output")) output = 'output/figures/fig_ordering_map.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,13cm
set output output

# The first blocks of the file, one per (scheme, ratio) in order: "# block b: scheme = s, dt/h = r"
# (the blocks after them repeat the pairs with other columns).
cells = system(sprintf("awk '/^# block [0-9]+: scheme = /{sub(/,/, \"\", $6); if (seen[$6 \" \" $9]++) exit; print $6, $9}' '%s'", data))
ratios = system(sprintf("awk '/^# block [0-9]+: scheme = /{print $9}' '%s' | awk '!seen[$0]++' | head -n 32", data))
nr = words(ratios)
nb = words(cells) / 2
ns = nb / nr
scheme_of(b) = word(cells, 2 * b + 1)
ratio_of(b) = word(cells, 2 * b + 2)
fraction(r) = r eq "0.25" ? "¼" : r eq "0.5" ? "½" : r eq "0.75" ? "¾" : r eq "1" ? "" : r
# The meshes and horizons of the cells (first block), as tics.
meshes = system(sprintf("awk '/^# block 1:/{exit} !/^#/ && NF {print $1}' '%s' | awk '!seen[$0]++'", data))
horizons = system(sprintf("awk '/^# block 1:/{exit} !/^#/ && NF {print $2}' '%s' | awk '!seen[$0]++'", data))

set palette defined (0 "#d62728", 0.5 "#ffdd55", 1 "#2ca02c")
set cbrange [0:1]
unset colorbox
set logscale xy
small = font(7)
set xtics () font small
set ytics () font small
do for [k=1:words(meshes)] { set xtics add (word(meshes, k) word(meshes, k) + 0) }
set offsets graph 0.12, graph 0.12, graph 0.15, graph 0.15
set multiplot layout ns,nr margins 0.07,0.98,0.07,0.92 spacing 0.02,0.07 \
  title "measures ranked Mod 3 < Mod 2 < Mod 1, of those judged (green: all; red: none)" font font(9)
do for [b=0:nb-1] {
  s = scheme_of(b)
  # The title the data file gives the scheme (Paoli-Schatzman: judged in its velocity only).
  set title sprintf("%s, %s = %s%s", scheme_title(s), Delta_t, \
    fraction(ratio_of(b)), italic("h")) font font(8)
  # Tic labels of the horizons on the first column only.
  set ytics ()
  do for [k=1:words(horizons)] { set ytics add ((b % nr == 0 ? word(horizons, k) : "") word(horizons, k) + 0) }
  if (b % nr == 0) { set ylabel "horizon (periods)" } else { unset ylabel }
  if (b >= nb - nr) { set xlabel italic("N") } else { unset xlabel }
  plot data index b using 1:2:($3/$4) with points pt 5 ps 2.6 lc palette notitle, \
       '' index b using 1:2:(sprintf("%d", $3)) with labels font small notitle
}
unset multiplot
