# Convergence on the smooth benchmarks (mathematics.md sec. 11): every relative error of sec. 5 against h,
# one curve per mass (colour) and ratio dt/h (solid with filled marks for the first ratio, dashed with
# open marks for the second); one page per benchmark (S1 generic impact, S2 grazing) and scheme, one
# panel per measure; the grey lines are reference slopes h^1 and h^2. Benchmarks, schemes, masses,
# ratios and measures are read from the data file (block headers "benchmark = b, scheme = s, mass = m,
# dt/h = r" and the columns line); the axes are set by the data.
# Usage: gnuplot -e "data='output/data/fig_smooth_convergence.dat'; output='output/figures/fig_smooth_convergence.pdf'" figures/fig_smooth_convergence.gp
if (!exists("data")) data = 'output/data/fig_smooth_convergence.dat'
if (!exists("output")) output = 'output/figures/fig_smooth_convergence.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

# The report includes a page at 0.95 \textwidth.
eval sprintf("set terminal %s size %.2fcm,21cm", figure_terminal, 0.95 * text_width)
set output output

# The blocks in file order: benchmark scheme mass ratio, four words per block.
blocks = system(sprintf("awk '/^# block [0-9]+: benchmark = /{gsub(/,/, \"\"); print $6, $9, $12, $15}' '%s'", data))
unique(k) = system(sprintf("echo '%s' | tr ' ' '\\n' | awk 'NR %% 4 == %d' | awk '!seen[$0]++'", blocks, k % 4))
benchmarks = unique(1)
schemes = unique(2)
masses = unique(3)
ratios = unique(0)
# The block of each (benchmark, scheme, mass, ratio), read once: "b s m r=index" lines (style.gp's comment).
block_table = "\n".system(sprintf("awk '/^# block [0-9]+: benchmark = /{gsub(/,/, \"\"); sub(/:/, \"\", $3); print $6, $9, $12, $15 \"=\" $3}' '%s'", data))."\n"
block_of(b, s, m, r) = comment(block_table, b." ".s." ".m." ".r."=") + 0
benchmark_name(id) = id eq "smooth-impact" ? "S1 (an impact)" : id eq "grazing" ? "S2 (a grazing contact)" : id
mass_index(id) = id eq "mod1" ? 1 : id eq "mod2" ? 2 : id eq "mod3" ? 3 : 4
step(r) = r eq "1" ? italic("h") : (r + 0 < 1 ? italic("h")."/".sprintf("%g", 1 / (r + 0)) : r.italic("h"))
nk = words(columns) - 3
dash(j) = j == 1 ? 1 : 2
marker(j) = j == 1 ? 7 : 6

set logscale x 2
set logscale y 10
set format x "2^{%L}"
set format y "10^{%L}"
set autoscale xfix
set offsets graph 0.05, graph 0.05, 0, 0
do for [b in benchmarks] {
  do for [s in schemes] {
    set multiplot layout 4,2 title benchmark_name(b)." with ".scheme_name(s) font font(11) \
      margins 0.09,0.98,0.05,0.86 spacing 0.09,0.075
    # Reference slopes through the last mass's error at the first ratio on the coarsest mesh, halved.
    anchor = block_of(b, s, word(masses, words(masses)), word(ratios, 1))
    do for [k=1:nk] {
      set title measure_name(word(columns, 3 + k))
      set autoscale y
      stats data index anchor using 2 nooutput
      h0 = STATS_max
      stats data index anchor every ::0::0 using (column(3 + k)) nooutput
      e0 = STATS_max / 2.0
      # The y axis spans the decades of the panel's errors; the reference slopes are clipped to it.
      lo = 1e300; hi = 0
      do for [m in masses] {
        do for [j=1:words(ratios)] {
          stats data index block_of(b, s, m, word(ratios, j)) using (positive(column(3 + k))) nooutput
          lo = STATS_min < lo ? STATS_min : lo; hi = STATS_max > hi ? STATS_max : hi
        }
      }
      STATS_min = lo; STATS_max = hi
      @fit_log_y
      if (k > nk - 2) { set xlabel italic("h") } else { unset xlabel }
      if (k == 1) {
        set key at screen 0.5,0.945 center top vertical maxrows 2 samplen 3 width 1
      } else {
        unset key
      }
      plot for [m in masses] for [j=1:words(ratios)] data index block_of(b, s, m, word(ratios, j)) using 2:(column(3 + k)) \
             with linespoints lc rgb mass_colour(mass_index(m)) lw 1.2 dashtype dash(j) pt marker(j) ps 0.55 \
             title sprintf("%s, %s = %s", mass_name(m), Delta_t, step(word(ratios, j))), \
           e0*(x/h0) with lines @reference_style dt 3 title "slope 1", \
           e0*(x/h0)**2 with lines @reference_style dt 4 title "slope 2"
    }
    unset multiplot
  }
}
