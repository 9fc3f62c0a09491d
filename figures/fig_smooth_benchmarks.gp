# The smooth benchmarks (mathematics.md sec. 11) at the contact point: u(0,t), its error u_h(0,t) - u(0,t)
# and the contact stress lambda(t), exact (the characteristic solution, black dashed) against each mass
# of the file on a coarse mesh; one column per benchmark (S1 generic impact, S2 grazing contact). The
# benchmarks, masses, mesh and step are read from the data file's header (blocks "benchmark = b",
# columns u0_M lambda_M); the axes are set by the data.
# Usage: gnuplot -e "data='output/data/fig_smooth_benchmarks.dat'; output='output/figures/fig_smooth_benchmarks.pdf'" figures/fig_smooth_benchmarks.gp
if (!exists("data")) data = 'output/data/fig_smooth_benchmarks.dat'
if (!exists("output")) output = 'output/figures/fig_smooth_benchmarks.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,16cm
set output output

benchmarks = system(sprintf("sed -n 's/^# block [0-9]*: benchmark = \\([a-z-]*\\)$/\\1/p' '%s'", data))
benchmark_name(id) = id eq "smooth-impact" ? "S1, an impact" : id eq "grazing" ? "S2, a grazing contact" : id
# The masses: columns u0_M after t u0_exact lambda_exact, in pairs (u0_M lambda_M).
nm = (words(columns) - 3) / 2
mass_of(m) = word(columns, 2 + 2 * m)[4:]
mass_index(id) = id eq "mod1" ? 1 : id eq "mod2" ? 2 : id eq "mod3" ? 3 : 4
u0 = italic("u")."(0,".italic("t").")"
quantity(q) = q == 0 ? u0 : q == 1 ? italic("u_h")."(0,".italic("t").") − ".u0 : lambda_."(".italic("t").")"

set multiplot layout 3,words(benchmarks) margins 0.1,0.98,0.06,0.91 spacing 0.09,0.05
set autoscale xfix
set offsets 0, 0, graph 0.05, graph 0.05
do for [q=0:2] {
  do for [b=1:words(benchmarks)] {
    # A column per benchmark: its title over the first row only.
    if (q == 0) {
      set title sprintf("%s, %s = 1/%s, %s = %s%s", benchmark_name(word(benchmarks, b)), italic("h"), header("elements"), \
        Delta_t, header("courant"), italic("h"))
    } else {
      unset title
    }
    set ylabel quantity(q)
    if (q == 2) { set xlabel italic("t") } else { unset xlabel }
    if (q == 0 && b == 1) {
      set key at screen 0.5,0.99 center top horizontal samplen 3 width 1
    } else {
      unset key
    }
    if (q == 1) {
      plot for [m=1:nm] data index b-1 using 1:(column(2 + 2*m) - column(2)) with lines \
             lc rgb mass_colour(mass_index(mass_of(m))) lw 1 title mass_name(mass_of(m)), \
           0 with lines lc rgb "black" dt 2 lw 1.2 title "exact"
    } else {
      plot for [m=1:nm] data index b-1 using 1:(column(2 + q/2 + 2*m)) with lines \
             lc rgb mass_colour(mass_index(mass_of(m))) lw 1 title mass_name(mass_of(m)), \
           data index b-1 using 1:(column(2 + q/2)) with lines lc rgb "black" dt 2 lw 1.2 title "exact"
    }
  }
}
unset multiplot
