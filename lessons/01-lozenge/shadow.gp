# caption: Energy and shadow energy at the large step ω·dt = 0.5 (a twelfth of a period), relative to their start values. Euler's energy grows by the factor 1 + Ω² every step and leaves the plot. Symplectic Euler and velocity Verlet wobble without drifting, because each exactly conserves a nearby shadow energy (flat lines). Velocity Verlet's energy stays between −Ω²/4 and 0 (dashed).
set terminal pngcairo size 900,600 font "sans,11"
set output 'shadow.png'
set title "What is conserved at ω·dt = 0.5: the energy E, or a shadow energy"
set xlabel "time t [τ]   (ω = 1: one period is 2π τ)"
set ylabel "relative change  X(t)/X(0) − 1"
set grid lc rgb "#e8e8e8"
set xrange [0:30]
set yrange [-0.35:0.6]
set key top right font "sans,9" opaque box lc rgb "#cccccc" spacing 1.1
set arrow from 0,-0.0625 to 30,-0.0625 nohead lc rgb "#2ca02c" dt 3 lw 1
set label "−Ω²/4" at 30.3,-0.0625 left tc rgb "#2ca02c" font "sans,9"
set rmargin 8
plot 'shadow.dat' u 1:2 w lp lc rgb "#d62728" pt 7 ps 0.6 lw 1.5 t "Euler: E", \
     '' u 1:3 w lp lc rgb "#ff7f0e" pt 5 ps 0.6 lw 1.5 t "symplectic Euler: E", \
     '' u 1:4 w l lc rgb "#ff7f0e" lw 3 dt 1 t "symplectic Euler: shadow E − (dt ω²/2) x v", \
     '' u 1:5 w lp lc rgb "#2ca02c" pt 9 ps 0.7 lw 1.5 t "velocity Verlet: E", \
     '' u 1:6 w l lc rgb "#1b5e20" lw 3 dt 4 t "velocity Verlet: shadow v²/2 + (ω²x²/2)(1 − Ω²/4)"
