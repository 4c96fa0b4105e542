# caption: Truncation against round-off: error at T = 1 of an oscillator centred 1000 σ from the origin, against dt, log-log. Going left, every method first follows the truncation line ∝ dt². Then rounding takes over: position Verlet, which adds dt²a to the difference of two large positions, turns up first, and below dt ≈ 2e-7 it cannot move at all (error 1 − cos 1). Leapfrog and naive velocity Verlet level off near 1e-11. Velocity Verlet with Kahan-compensated r and v keeps improving to 3e-16.
set terminal pngcairo size 900,600 font "sans,11"
set output 'roundoff.png'
set title "Round-off overtakes truncation at tiny steps (unless the sums are compensated)"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "time step dt [τ]"
set ylabel "position error |x(T) − X_0 − cos T| [σ]"
set grid xtics ytics lc rgb "#e8e8e8"
set xrange [5e-8:0.2]
set yrange [1e-17:3]
set key bottom right Left reverse font "sans,9" opaque box lc rgb "#cccccc" spacing 1.1 samplen 2
ulp_half = 2.0**-43 / 2          # doubles in [512, 1024) are 2^-43 apart
set arrow from 5e-8,ulp_half to 0.2,ulp_half nohead lc rgb "#999999" dt 3
set label "half an ulp of x ≈ 1000: 5.7·10^{-14}" at 1.2e-7,ulp_half*3 tc rgb "#777777" font "sans,9"
set arrow from 5e-8,1-cos(1) to 0.2,1-cos(1) nohead lc rgb "#f4a6a6" dt 3
set label "x never moves: 1 − cos 1" at 1e-5,1.1 tc rgb "#d62728" font "sans,9"
plot 'roundoff.dat' u 1:2 w lp lc rgb "#d62728" pt 7 ps 0.8 lw 2 t "position Verlet  r + (r − r_{prev}) + dt²a", \
     '' u 1:4 w lp lc rgb "#2ca02c" pt 8 ps 0.9 lw 2 t "velocity Verlet, naive r += dt·v", \
     '' u 1:3 w lp lc rgb "#9467bd" pt 2 ps 1.6 lw 1 t "leapfrog (small terms grouped first)", \
     '' u 1:5 w lp lc rgb "#1f77b4" pt 5 ps 0.8 lw 2 t "velocity Verlet, Kahan-compensated r and v", \
     0.035 * x**2 w l lc rgb "#444444" dt 2 lw 1.5 t "truncation ∝ dt²"
