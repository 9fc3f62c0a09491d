# The mechanism of the ranking: errors against time (top) and the impact-time errors against the period
# law's prediction (bottom), for each mass of the file (experiments/fig_phase.cpp). The masses, the
# scheme, the mesh and the step are read from the data file's header (blocks "..., mass = m"); the axes
# are set by the data.
# Usage: gnuplot -e "data='output/data/fig_phase.dat'; output='output/figures/fig_phase.pdf'" figures/fig_phase.gp
if (!exists("data")) data = 'output/data/fig_phase.dat'
if (!exists("output")) output = 'output/figures/fig_phase.pdf'
dir = ARG0[1:strstrt(ARG0, "/") > 0 ? strlen(ARG0) - strlen(system("basename '".ARG0."'")) : 0]
load dir.'style.gp'

set terminal @figure_terminal size 16cm,17cm
set output output

# Blocks 0..n-1: the error histories, blocks n..2n-1: the impacts, one per mass in the same order.
histories = system(sprintf("sed -n 's/^# block [0-9]*: error history, mass = \\([a-z0-9]*\\)$/\\1/p' '%s'", data))
n = words(histories)
mass_index(id) = id eq "mod1" ? 1 : id eq "mod2" ? 2 : id eq "mod3" ? 3 : 4
run_title = sprintf("%s, %s = 1/%s, %s = %s%s", scheme_name(header("scheme")), italic("h"), header("elements"), \
  Delta_t, header("courant"), italic("h"))

set multiplot layout 3,1 margins 0.11,0.97,0.06,0.91 spacing 0.0,0.105 title run_title
# The keys where no curve is: above the errors, which grow with time (the top centre stays free), and
# below the impact-time errors at the start, where every mass is still on time.
set key top center horizontal samplen 2
set autoscale xfix
set offsets 0, 0, graph 0.05, graph 0.05

set title "error of the contact point, |".italic("u")."_0^".italic("n")." − ".italic("u")."(0,".italic("t_n").")|"
set ylabel "error"
plot for [m=1:n] data index m-1 using 1:2 with lines lc rgb mass_colour(mass_index(word(histories, m))) lw 1.0 \
  title mass_name(word(histories, m))

# The first two panels share the time axis: its label under the second only.
set xlabel italic("t")
set title "error of ".italic("u")." in ".italic("L")."^2(0,".italic("L").")"
plot for [m=1:n] data index m-1 using 1:3 with lines lc rgb mass_colour(mass_index(word(histories, m))) lw 1.0 \
  title mass_name(word(histories, m))

set title "impact-time errors: measured (points) and the period law (dashed lines)"
set key at graph 0.03, graph 0.05 left bottom vertical maxrows 3 samplen 2
set xlabel "exact impact time ".italic("t_k")
set ylabel "time error"
plot for [m=1:n] data index n+m-1 using 2:3 with points lc rgb mass_colour(mass_index(word(histories, m))) pt 7 ps 0.4 \
       title mass_name(word(histories, m))." measured", \
     for [m=1:n] data index n+m-1 using 2:4 with lines lc rgb mass_colour(mass_index(word(histories, m))) lw 1.0 dt 2 \
       title mass_name(word(histories, m))." law"
unset multiplot
