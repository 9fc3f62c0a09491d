# Convergence on the smooth benchmarks (mathematics.md sec. 11): every relative error of sec. 5 against h,
# with dt = h (solid, filled marks) and dt = h/2 (dashed, open marks), Mod 1/2/3 in colour; one page per
# benchmark (S1 generic impact, S2 grazing) and scheme (Crank-Nicolson, backward Euler), one panel per
# measure; the grey lines are reference slopes h^1 and h^2.
# Usage: gnuplot -e "data='output/data/fig_smooth_convergence.dat'; output='output/figures/fig_smooth_convergence.pdf'" figures/fig_smooth_convergence.gp
if (!exists("data")) data = 'output/data/fig_smooth_convergence.dat'
if (!exists("output")) output = 'output/figures/fig_smooth_convergence.pdf'

set encoding utf8
set terminal pdfcairo size 16cm,21cm font "Helvetica,9" linewidth 1.5 enhanced
set output output

benchmark(b) = b == 0 ? "S1 (generic impact)" : "S2 (grazing contact)"
scheme(s) = s == 0 ? "Crank-Nicolson" : "backward Euler"
measure(k) = k == 1 ? "u(0,·) in L^2(0,T)" : k == 2 ? "λ in L^2(0,T)" : k == 3 ? "u in L^∞(0,T;L^2)" : \
  k == 4 ? "u in L^∞(0,T;H^1)" : k == 5 ? "u_t in L^∞(0,T;L^2)" : k == 6 ? "u in L^2(0,T;L^2)" : \
  k == 7 ? "u in L^2(0,T;H^1)" : "u_t in L^2(0,T;L^2)"
dash(j) = j % 2 == 0 ? 1 : 2
marker(j) = j % 2 == 0 ? 7 : 6
ratio(j) = j % 2 == 0 ? "h" : "h/2"
colour(m) = m == 1 ? "#d62728" : m == 2 ? "#1f77b4" : "#2ca02c"
# Data block of benchmark b, scheme s, mass m (0..2), ratio c (0: dt = h, 1: dt = h/2).
block(b, s, m, c) = 2 * (3 * (2 * b + s) + m) + c

set logscale x 2
set logscale y 10
set format x "2^{%L}"
set format y "10^{%L}"
set grid lc rgb "#dddddd" lw 0.5
set mxtics 1
set xtics 2
do for [b=0:1] {
  do for [s=0:1] {
    stats data index block(b, s, 0, 0) using 2 nooutput
    set xrange [STATS_min / 1.5:STATS_max * 1.5]
    set multiplot layout 4,2 title benchmark(b)." with ".scheme(s) font ",11" margins 0.09,0.98,0.05,0.86 spacing 0.09,0.05
    do for [k=1:8] {
      set title measure(k) font ",9"
      # Reference slopes through the Mod 3, dt = h error on the coarsest mesh, shifted down by 2.
      stats data index block(b, s, 2, 0) using 2 nooutput
      h0 = STATS_max
      stats data index block(b, s, 2, 0) every ::0::0 using (column(3+k)) nooutput
      e0 = STATS_max / 2.0
      if (k >= 7) { set xlabel "h" } else { unset xlabel }
      if (k == 1) {
        set key at screen 0.5,0.945 center top vertical maxrows 2 font ",9" samplen 3 width 1
      } else {
        unset key
      }
      plot for [j=0:5] data index block(b, s, j/2, j%2) using 2:(column(3+k)) with linespoints lc rgb colour(j/2+1) \
             lw 1.2 dt dash(j) pt marker(j) ps 0.55 title sprintf("Mod %d, Δt = %s", j/2+1, ratio(j)), \
           e0*(x/h0) with lines lc rgb "#777777" dt 3 lw 1 title "slope 1", \
           e0*(x/h0)**2 with lines lc rgb "#777777" dt 4 lw 1 title "slope 2"
    }
    unset multiplot
  }
}
