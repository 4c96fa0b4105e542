# caption: Energy conservation in a Lennard-Jones liquid (ρ = 0.8, T ≈ 1, rc = 2.5, velocity Verlet, runs of 5.12 τ). Left: rms spread of the energy per particle against dt, log-log. At working steps it grows like dt² (slope-2 guide) and falls like 1/√N with system size (N = 108 … 864 at full size, make lesson STAGE=01; 108 alone at demo size); below dt ≈ 0.001 the force jump at the cutoff leaves a slope-1 floor, and single precision (open symbols) turns up again as its round-off piles up. Right: at dt = 0.000125 the double-precision energy stays within a few 10⁻⁶ ε per particle while the float run wanders off by rounding.
set terminal pngcairo size 900,600 font "sans,11"
set output 'ljnve.png'
set multiplot layout 1,2 title "Lennard-Jones NVE: how well is the energy conserved?"
set grid lc rgb "#e8e8e8"

stats 'ljnve.dat' u 1 nooutput
nmax = STATS_max
set title "spread of E/N over a run"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "time step dt [τ]"
set ylabel "rms spread of E/N [ε]"
set xrange [9e-5:0.022]
set yrange [5e-7:1e-2]
set key top left Left reverse font "sans,9" opaque box lc rgb "#cccccc" spacing 1.05 samplen 2
col(n) = n == 108 ? "#1f77b4" : n == 256 ? "#2ca02c" : n == 500 ? "#ff7f0e" : "#d62728"
sel(n, p) = ($1 == n && $2 == p) ? $3 : NaN
plot for [n in "108 256 500 864"] 'ljnve.dat' \
         u (n + 0 <= nmax ? sel(n + 0, 0) : NaN):4 w lp lc rgb col(n + 0) pt 7 ps 0.8 lw 2 \
         t (n + 0 <= nmax ? sprintf("N = %s, double", n) : ""), \
     'ljnve.dat' u (sel(108, 1)):4 w lp lc rgb "#1f77b4" pt 6 ps 1.2 lw 1 dt 2 t "N = 108, float", \
     8.0 * x**2 w l lc rgb "#777777" dt 2 lw 1.5 t "∝ dt² (guide)", \
     0.009 * x w l lc rgb "#bbbbbb" dt 3 lw 1.5 t "∝ dt (guide)"

set title "E/N(t) − E/N(0) at dt = 0.000125, N = 108"
unset logscale
set format x "%g"
set format y "%g"
set xlabel "time t [τ]"
set ylabel "energy change per particle [10^{-5} ε]"
set xrange [0:5.12]
set yrange [*:*]
set key bottom left Left reverse font "sans,9" opaque box lc rgb "#cccccc" spacing 1.05 samplen 2
plot 'ljnve_trace.dat' u 1:($2 * 1e5) w l lc rgb "#1f77b4" lw 2 t "double precision", \
     '' u 1:($10 * 1e5) w l lc rgb "#d62728" lw 2 t "single precision (float)"
unset multiplot
