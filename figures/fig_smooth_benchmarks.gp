# The smooth benchmarks (mathematics.md sec. 11): the contact point's displacement u(0,t) and the contact
# stress λ(t), exact (the characteristic solution, black) against Mod 1/2/3 with Crank-Nicolson on a coarse
# mesh; left S1 (generic impact at t* = 1/2), right S2 (grazing contact from t* to t_r).
# Usage: gnuplot -e "data='output/data/fig_smooth_benchmarks.dat'; output='output/figures/fig_smooth_benchmarks.pdf'" figures/fig_smooth_benchmarks.gp
if (!exists("data")) data = 'output/data/fig_smooth_benchmarks.dat'
if (!exists("output")) output = 'output/figures/fig_smooth_benchmarks.pdf'

set encoding utf8
set terminal pdfcairo size 16cm,11cm font "Helvetica,9" linewidth 1.5 enhanced
set output output

benchmark(b) = b == 0 ? "S1, generic impact" : "S2, grazing contact"
colour(m) = m == 1 ? "#d62728" : m == 2 ? "#1f77b4" : "#2ca02c"
set grid lc rgb "#dddddd" lw 0.5
set xlabel "t"
set multiplot layout 2,2 margins 0.08,0.98,0.08,0.86 spacing 0.08,0.1
# Columns: t u0_exact lambda_exact, then u0 and lambda of Mod 1, 2, 3 (blocks: 0 = S1, 1 = S2).
do for [q=0:1] {
  do for [b=0:1] {
    set title (q == 0 ? "u(0,t), " : "λ(t), ").benchmark(b) font ",10"
    set ylabel (q == 0 ? "u(0,t)" : "λ(t)")
    if (q == 0 && b == 0) {
      set key at screen 0.5,0.97 center top horizontal font ",9" samplen 3
    } else {
      unset key
    }
    plot for [m=1:3] data index b using 1:(column(2 + q + 2*m)) with lines lc rgb colour(m) lw 1 \
           title sprintf("Mod %d", m), \
         data index b using 1:(column(2 + q)) with lines lc rgb "black" dt 2 lw 1.2 title "exact"
  }
}
unset multiplot
