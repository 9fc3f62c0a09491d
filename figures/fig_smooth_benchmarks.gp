# The smooth benchmarks (mathematics.md sec. 11) at the contact point: u(0,t), its error u_h(0,t) - u(0,t)
# and the contact stress λ(t), exact (the characteristic solution, black dashed) against Mod 1/2/3 with
# Crank-Nicolson on a coarse mesh; left S1 (generic impact at t* = 1/2), right S2 (grazing contact from t*
# to t_r).
# Usage: gnuplot -e "data='output/data/fig_smooth_benchmarks.dat'; output='output/figures/fig_smooth_benchmarks.pdf'" figures/fig_smooth_benchmarks.gp
if (!exists("data")) data = 'output/data/fig_smooth_benchmarks.dat'
if (!exists("output")) output = 'output/figures/fig_smooth_benchmarks.pdf'

set encoding utf8
set terminal pdfcairo size 16cm,16cm font "Helvetica,9" linewidth 1.5 enhanced
set output output

benchmark(b) = b == 0 ? "S1, generic impact" : "S2, grazing contact"
quantity(q) = q == 0 ? "u(0,t)" : q == 1 ? "u_h(0,t) - u(0,t)" : "λ(t)"
colour(m) = m == 1 ? "#d62728" : m == 2 ? "#1f77b4" : "#2ca02c"
set grid lc rgb "#dddddd" lw 0.5
set multiplot layout 3,2 margins 0.1,0.98,0.06,0.9 spacing 0.09,0.07
# Columns: t u0_exact lambda_exact, then u0 and lambda of Mod 1, 2, 3 (blocks: 0 = S1, 1 = S2).
do for [q=0:2] {
  do for [b=0:1] {
    set title quantity(q).", ".benchmark(b) font ",10"
    set ylabel quantity(q)
    if (q == 2) { set xlabel "t" } else { unset xlabel }
    if (q == 0 && b == 0) {
      set key at screen 0.5,0.97 center top horizontal font ",9" samplen 3
    } else {
      unset key
    }
    if (q == 1) {
      plot for [m=1:3] data index b using 1:(column(2 + 2*m) - column(2)) with lines lc rgb colour(m) lw 1 \
             title sprintf("Mod %d", m), \
           0 with lines lc rgb "black" dt 2 lw 1.2 title "exact"
    } else {
      plot for [m=1:3] data index b using 1:(column(2 + q/2 + 2*m)) with lines lc rgb colour(m) lw 1 \
             title sprintf("Mod %d", m), \
           data index b using 1:(column(2 + q/2)) with lines lc rgb "black" dt 2 lw 1.2 title "exact"
    }
  }
}
unset multiplot
