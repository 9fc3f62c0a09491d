# Where the ranking Mod 3 < Mod 2 < Mod 1 holds: per scheme (rows) and dt/h (columns), the number of
# measures ranked as the paper says in each cell (N, horizon), coloured by the fraction of the judged
# measures it is, from red (none) to green (all), with a colour box that says so
# (experiments/fig_ordering_map.cpp). The cells are drawn as tiles of an even grid, one column per mesh
# and one row per horizon, in the order of the data. Schemes, ratios, meshes and horizons are read from the data file
# (block headers "scheme = s, dt/h = r" and the cells themselves).
# Usage: gnuplot -e "data='output/data/fig_ordering_map.dat'; output='output/figures/fig_ordering_map.pdf'" figures/fig_ordering_map.gp
if (!exists("data")) data = 'output/data/fig_ordering_map.dat'
if (!exists("output")) output = 'output/figures/fig_ordering_map.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,15cm
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
nm = words(meshes)
nh = words(horizons)
# The position of value v in a list of words (0 for the first; NaN if absent): the cell's column or row.
position(v, list, k) = k > words(list) ? NaN : word(list, k) + 0 == v ? k - 1 : position(v, list, k + 1)

set palette defined (0 "#d62728", 0.5 "#ffdd55", 1 "#2ca02c")
set cbrange [0:1]
unset colorbox
set xrange [-0.5:nm - 0.5]
set yrange [-0.5:nh - 0.5]
set xtics scale 0
set ytics scale 0
unset grid
# Three rows of panels, one per scheme, headed by its name; the step of each column above the first row;
# a column of room on the right for the colour box.
left = 0.09; right = 0.86; bottom = 0.08; top = 0.91; gap = 0.075
panel_height = (top - bottom - (ns - 1) * gap) / ns
set multiplot layout ns,nr margins left,right,bottom,top spacing 0.025,gap
do for [b=0:nb-1] {
  s = scheme_of(b)
  row = b / nr
  if (row == 0) { set title sprintf("%s = %s%s", Delta_t, fraction(ratio_of(b)), italic("h")) } else { unset title }
  # The row's heading: the title the data file gives the scheme (Paoli-Schatzman: judged in its velocity
  # only), drawn with the row's first panel.
  if (b % nr == 0) {
    set label 100 scheme_title(s) at screen (left + right) / 2, screen top - row * (panel_height + gap) + (row == 0 ? 0.055 : 0.02) center
  } else {
    unset label 100
  }
  # Tic labels of the horizons on the first column only, of the meshes on the last row only.
  set ytics ()
  do for [k=1:nh] { set ytics add ((b % nr == 0 ? word(horizons, k) : "") k - 1) }
  set xtics ()
  do for [k=1:nm] { set xtics add ((b >= nb - nr ? word(meshes, k) : "") k - 1) }
  if (b % nr == 0) { set ylabel "horizon (periods)" } else { unset ylabel }
  if (b >= nb - nr) { set xlabel italic("N") } else { unset xlabel }
  # One colour box for the figure, beside the panels.
  if (b == nb - 1) {
    set colorbox user origin screen right + 0.03, screen bottom size screen 0.025, screen top - bottom
    set cbtics 0.25
    set cblabel "fraction of the judged measures ranked Mod 3 < Mod 2 < Mod 1" offset 0.5,0
  }
  plot data index b using (position($1, meshes, 1)):(position($2, horizons, 1)):(position($1, meshes, 1) - 0.5):(position($1, meshes, 1) + 0.5):(position($2, horizons, 1) - 0.5):(position($2, horizons, 1) + 0.5):($3/$4) \
         with boxxyerror fs solid 1.0 noborder lc palette notitle, \
       '' index b using (position($1, meshes, 1)):(position($2, horizons, 1)):(sprintf("%d", $3)) with labels notitle
}
unset multiplot
