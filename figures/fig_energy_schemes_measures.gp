# The eight relative errors of EC, CN-switch and backward Euler divided by Crank-Nicolson's, with Mod 1, 2, 3,
# at N = 100 and N = 400, dt = h/2, T = 30 (fig_energy_schemes --view measures); 1 = as accurate as CN.
# Usage: gnuplot -e "data='output/data/fig_energy_schemes_measures.dat'; output='output/figures/fig_energy_schemes_measures.pdf'" figures/fig_energy_schemes_measures.gp
if (!exists("data")) data = 'output/data/fig_energy_schemes_measures.dat'
if (!exists("output")) output = 'output/figures/fig_energy_schemes_measures.pdf'

set encoding utf8
set terminal pdfcairo size 16cm,13cm font "Helvetica,9" linewidth 1.5 enhanced
set output output

mesh(b) = b == 0 ? 100 : 400
label(s) = s == 1 ? "EC" : s == 2 ? "CN-switch" : "backward Euler"
colour(s) = s == 1 ? "black" : s == 2 ? "#1f77b4" : "#2ca02c"
marker(m) = m == 0 ? 4 : m == 1 ? 6 : 7
# Rows of a block: 3 s + m for scheme s in (cn, ec, cn-switch, be) and mass m in (mod1, mod2, mod3);
# columns 11..18 the ratios to Crank-Nicolson's error with the same mass.
set multiplot layout 2,1 margins 0.09,0.98,0.10,0.90 spacing 0.0,0.12
set grid ytics lc rgb "#dddddd" lw 0.5
set logscale y 10
set yrange [0.5:20]
set ytics (0.5, 0.7, 1, 1.5, 2, 3, 5, 10, 20)
set xrange [0.5:8.5]
set xtics ("u(0,·) L^2_t" 1, "λ L^2_t" 2, "u L^∞_tL^2" 3, "u L^∞_tH^1" 4, "u_t L^∞_tL^2" 5, "u L^2_tL^2" 6, \
           "u L^2_tH^1" 7, "u_t L^2_tL^2" 8)
set ylabel "error / Crank-Nicolson's"
set key at screen 0.5,0.985 center top vertical maxrows 1 font ",10" samplen 1 width 2
do for [b=0:1] {
  set title sprintf("N = %d, Δt = h/2, T = 30 (marks: Mod 1 square, Mod 2 circle, Mod 3 disc)", mesh(b)) font ",10"
  plot 1 with lines lc rgb "#999999" dt 2 notitle, \
       for [s=1:3] for [m=0:2] for [k=0:7] data index b every ::(3*s+m)::(3*s+m) \
         using (k + 1 + 0.22*(s-2) + 0.06*(m-1)):(column(11+k)) with points lc rgb colour(s) pt marker(m) ps 0.7 \
         title (m == 2 && k == 0 ? label(s) : "")
  unset key
}
unset multiplot
