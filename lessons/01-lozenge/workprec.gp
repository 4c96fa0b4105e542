# caption: Work–precision diagram: rms position error at T = 10 against cost, for oscillators started at random, log-log (down and to the left is better). Left, cost in force evaluations: first-order methods gain one digit per tenfold work, the Verlet family two, and GSL's adaptive rk8pd (tolerances 1e-1 to 1e-12) about eight. Right, the same runs in CPU seconds, where rk8pd also pays for its 13-stage bookkeeping.
set terminal pngcairo size 900,600 font "sans,11"
set output 'workprec.png'
set multiplot layout 1,2 title "What accuracy costs: harmonic oscillators to T = 10"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set grid xtics ytics lc rgb "#e8e8e8"
set ylabel "rms position error at T (relative)"
set yrange [1e-14:10]
set key bottom left font "sans,9" opaque box lc rgb "#cccccc" spacing 1.05 samplen 2 width -4

set style line 1 lc rgb "#d62728" lw 2 pt 7 ps 0.7
set style line 2 lc rgb "#ff7f0e" lw 2 pt 5 ps 0.7
set style line 3 lc rgb "#1f77b4" lw 2 pt 6 ps 1.2
set style line 4 lc rgb "#2ca02c" lw 2 pt 8 ps 0.9
set style line 5 lc rgb "#9467bd" lw 1 pt 2 ps 0.8
set style line 6 lc rgb "#222222" lw 2 pt 13 ps 0.9

set title "cost = force evaluations"
set xlabel "force evaluations"
set autoscale xfix
set offsets graph 0.04, graph 0.04, 0, 0
plot 'workprec_euler.dat' u 2:4 w lp ls 1 t "Euler", \
     'workprec_symplectic-euler.dat' u 2:4 w lp ls 2 t "symplectic Euler", \
     'workprec_verlet.dat' u 2:4 w lp ls 3 t "Verlet", \
     'workprec_velocity-verlet.dat' u 2:4 w lp ls 4 t "velocity Verlet", \
     'workprec_leapfrog.dat' u 2:4 w lp ls 5 t "leapfrog", \
     'workprec_rk8pd.dat' u 2:4 w lp ls 6 t "GSL rk8pd (adaptive)"

set title "cost = CPU time (same symbols)"
set xlabel "CPU time [s]"
unset key
plot 'workprec_euler.dat' u 3:4 w lp ls 1 t "Euler", \
     'workprec_symplectic-euler.dat' u 3:4 w lp ls 2 t "symplectic Euler", \
     'workprec_verlet.dat' u 3:4 w lp ls 3 t "Verlet", \
     'workprec_velocity-verlet.dat' u 3:4 w lp ls 4 t "velocity Verlet", \
     'workprec_leapfrog.dat' u 3:4 w lp ls 5 t "leapfrog", \
     'workprec_rk8pd.dat' u 3:4 w lp ls 6 t "GSL rk8pd (adaptive)"
unset multiplot
