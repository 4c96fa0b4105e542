# caption: Error against step size for the harmonic oscillator (ω = 1, T = 10), log-log: the slope is the order of the method (fitted slopes in the legend). Euler and symplectic Euler follow the slope-1 guide and the Verlet family the slope-2 guide; the three Verlet curves lie on top of each other. Halving dt divides a first-order error by 2 and a second-order one by 4.
set terminal pngcairo size 900,600 font "sans,11"
set output 'convergence.png'
load 'convergence_fit.gp'

set multiplot layout 1,2 title "Convergence on the harmonic oscillator (ω = 1, T = 10)"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "time step dt [τ]"
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key top left Left reverse opaque font "sans,9" spacing 1.1 box lc rgb "#cccccc"
set xrange [1.5e-4:0.3]

# guide lines, drawn a little below the data: y0 at the finest step dt = 10/51200
g1(x, y0) = y0 * (x / 1.953125e-4)
g2(x, y0) = y0 * (x / 1.953125e-4)**2

set style line 1 lc rgb "#d62728" lw 2 pt 7 ps 0.9
set style line 2 lc rgb "#ff7f0e" lw 2 pt 5 ps 0.9
set style line 3 lc rgb "#1f77b4" lw 2 pt 6 ps 1.4
set style line 4 lc rgb "#2ca02c" lw 2 pt 8 ps 1.1
set style line 5 lc rgb "#9467bd" lw 1 pt 2 ps 0.9
set style line 9 lc rgb "#777777" lw 1.5 dt 2

set title "max relative energy error |E - E_0|/E_0"
set ylabel "energy error (relative)"
set yrange [1e-9:30]
plot 'convergence.dat' u 1:2 w lp ls 1 t sprintf("Euler (%.2f)", sE0), \
     '' u 1:3 w lp ls 2 t sprintf("symplectic Euler (%.2f)", sE1), \
     '' u 1:4 w lp ls 3 t sprintf("Verlet (%.2f)", sE2), \
     '' u 1:5 w lp ls 4 t sprintf("velocity Verlet (%.2f)", sE3), \
     '' u 1:6 w lp ls 5 t sprintf("leapfrog (%.2f)", sE4), \
     g1(x, 6e-4) w l ls 9 t "slope 1, slope 2", \
     g2(x, 3e-9) w l ls 9 notitle

set title "position error |x(T) - cos ωT|"
set ylabel "position error [σ]"
set yrange [1e-9:30]
plot 'convergence.dat' u 1:7 w lp ls 1 t sprintf("Euler (%.2f)", sX0), \
     '' u 1:8 w lp ls 2 t sprintf("symplectic Euler (%.2f)", sX1), \
     '' u 1:9 w lp ls 3 t sprintf("Verlet (%.2f)", sX2), \
     '' u 1:10 w lp ls 4 t sprintf("velocity Verlet (%.2f)", sX3), \
     '' u 1:11 w lp ls 5 t sprintf("leapfrog (%.2f)", sX4), \
     g1(x, 2.5e-4) w l ls 9 t "slope 1, slope 2", \
     g2(x, 2.5e-9) w l ls 9 notitle
unset multiplot
