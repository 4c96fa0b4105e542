# caption: The stability limit of the Verlet family (velocity Verlet, ω = 1, x(0) = 1). Left: at ω·dt = 1.99 the stored positions (dots) stay within ±1 but turn by 169° per step instead of the true 114° (grey curve). Right: at ω·dt = 2.01 |x| grows by the factor |λ| = 1.221 per step, exactly the larger root of λ² − (2 − Ω²)λ + 1 = 0 (dashed); at 1.99 it stays bounded.
set terminal pngcairo size 900,600 font "sans,11"
set output 'stability.png'
set multiplot layout 1,2 title "Just below and just above the stability limit ω·dt = 2"
set grid lc rgb "#e8e8e8"
set xlabel "step n"

set title "ω·dt = 1.99: bounded, but the phase is wrong"
set ylabel "position x_n [σ]"
set xrange [0:40]
set yrange [-1.25:1.6]
set samples 2000
set key top right font "sans,9" opaque box lc rgb "#cccccc"
plot cos(1.99 * x) w l lc rgb "#aaaaaa" lw 1 t "exact cos(ωt), t = n·dt", \
     'stability.dat' u 1:3 w lp lc rgb "#1f77b4" lw 1.5 pt 7 ps 0.8 t "velocity Verlet"

set title "|x_n| on a log scale"
set ylabel "|x_n| [σ]"
set logscale y
set format y "10^{%L}"
set xrange [0:200]
set yrange [1e-4:1e20]
set key top left font "sans,9" opaque box lc rgb "#cccccc"
plot 'stability.dat' u 1:(abs($5)) w p lc rgb "#d62728" pt 7 ps 0.5 t "ω·dt = 2.01", \
     '' u 1:6 w l lc rgb "#444444" dt 2 lw 2 t "|λ|^n, |λ| = 1.2213", \
     '' u 1:(abs($3)) w p lc rgb "#1f77b4" pt 7 ps 0.5 t "ω·dt = 1.99"
unset multiplot
