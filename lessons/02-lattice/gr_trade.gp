# caption: The trade of lesson 02: lattice resolution against accuracy against cost, for 201 hard disks at packing 0.4005. Left: g(r) off the lattice (Metropolis Monte Carlo in continuous space, grey, error bars from 8 blocks; its contact value gives Z = 2.830 ± 0.005 against 2.8345 from the equation of state) against the corrected g of random walkers on the triangular lattice with disk radius R = 3 (σ = 6 lattice units, red) and R = 24 (σ = 48, blue), one point per lattice shell. Middle: the lattice g minus the reference averaged over the same shell (the red bars span R = 3's shells). At R = 3 the first shells are 0.10 (5 %) low and the oscillation is weaker: the lattice disk is not round — it keeps other centres off 121 sites where a true disk of the same σ covers 130.6, so it acts like a disk 4 % smaller, at packing 0.371 instead of 0.4005. At R = 6 (packing 0.392 in that sense) a smaller dip of 0.04 remains near 1.2σ; from R = 12 on the deviations are within the noise, which grows as the shells get thinner. Right: the work–precision diagram, rms error of g over 1 ≤ r/σ < 2.5 against the CPU seconds of the sweeps, each run covering the same physical diffusion (sweeps ∝ R², since a step is σ/(2R)) at the same 6.5–7 × 10⁵ atom-steps per second. Filled circles: corrected g on the run's own shells, 0.055, 0.020, 0.015, 0.015 for R = 3, 6, 12, 24 in about 0.4, 1.7, 6.5 and 27 s (timings vary by some 10 % between runs) — at R = 24 equal to its statistical floor (crosses); triangles: the corrected g on the common σ/6 grid of R = 3, where the noise is alike at every R and the lattice's own error shows, 0.055 → 0.007; open squares: the raw g (exact-area normalisation), 0.09 → 0.037, still carrying the lattice measure. Each doubling of R costs four times the sweeps; R = 6 buys most of the accuracy for 6 % of the cost of R = 24. (These are the full size's figures, make lesson STAGE=02 on 2 cores. At demo size the runs are 18 times shorter and the noise about 4 times larger: the corrected g's errors are 0.07, 0.03, 0.05 and 0.06, from R = 6 on at their statistical floor, and in (b) only R = 3 stands out of the noise.)
set terminal pngcairo size 1500,560 font "sans,11"
set output 'gr_trade.png'
set datafile missing "nan"
set multiplot layout 1,3 title "Hard disks at η = 0.4: g(r) on a lattice against the off-lattice reference, and what resolution costs"
set grid xtics ytics lc rgb "#e8e8e8"
sel(R, c) = ($1 == R) ? column(c) : NaN

set title "(a) g(r): reference and lattice walkers"
set xlabel "r / σ"
set ylabel "g(r)"
set xrange [0.8:3]
set yrange [0:2.6]
set key top right font "sans,10" opaque box lc rgb "#cccccc" samplen 2
plot 'gr_ref.dat' u 3:4 w l lc rgb "#555555" lw 2 t "off-lattice reference", \
     'gr_lattice.dat' u (sel(3, 3)):4 w p lc rgb "#d62728" pt 7 ps 0.8 t "lattice R = 3, corrected", \
     '' u (sel(24, 3)):4 w p lc rgb "#1f77b4" pt 7 ps 0.35 t "lattice R = 24, corrected"

set title "(b) lattice minus reference, shell by shell"
# every shell in view: the axis from the deviations of all four R (R = 3 with its bars)
set xrange [*:*]
set yrange [*:*]
stats 'gr_lattice.dat' u (($3 > 1 && $3 <= 2.5) ? $4 - $7 : NaN) nooutput name "D"
set xrange [1:2.5]
set yrange [D_min - 0.04 : D_max + 0.04]
set ylabel "g_{lattice} − g_{reference}  (same shell)"
set key bottom right
dev(R) = ($1 == R && $3 > 1) ? $4 - $7 : NaN
plot 0 w l lc rgb "#555555" notitle, \
     'gr_lattice.dat' u (sel(24, 3)):(dev(24)) w l lc rgb "#9ecae1" lw 1 t "R = 24", \
     '' u (sel(12, 3)):(dev(12)) w l lc rgb "#a1d99b" lw 1.5 t "R = 12", \
     '' u (sel(6, 3)):(dev(6)) w lp lc rgb "#ff7f0e" pt 5 ps 0.6 lw 1.5 t "R = 6", \
     '' u (sel(3, 3)):(dev(3)):(1 / 12.0):(sqrt($5**2 + $8**2)) w xyerrorbars lc rgb "#d62728" pt 7 ps 0.9 lw 1.5 t "R = 3 (bar: the shell)"

set title "(c) error against cost (one point per R)"
set logscale xy
set xlabel "CPU seconds of the sweeps"
set ylabel "rms error of g(r) on [σ, 2.5σ)"
set xrange [*:*]
set autoscale xfix
set yrange [0.003:0.3]
set offsets graph 0.08, graph 0.25, 0, 0
set key top right
plot 'gr_trade.dat' u 5:3 w lp lc rgb "#d62728" pt 4 ps 1.2 dt 2 t "raw g", \
     '' u 5:2 w lp lc rgb "#1f77b4" pt 7 ps 1.2 lw 2 t "corrected g, own shells", \
     '' u 5:7 w lp lc rgb "#2ca02c" pt 9 ps 1.2 t "corrected g, σ/6 grid", \
     '' u 5:4 w lp lc rgb "#888888" pt 2 ps 1 dt 3 t "statistical floor", \
     '' u 5:2:(sprintf("R = %d", $1)) w labels left offset 0.8,0.9 font "sans,10" notitle
unset multiplot
