# caption: Resolution against lattice noise: the rms of M − 1 over the shells that sample 1 < r/σ < 3 for particles of radius R = 3, 6, 12, 24 lattice units (σ = 2R), log-log, with the number of distance² bins the histogram needs to reach 3σ on the right axis scale. Doubling R shrinks the noise of a raw g(r) only slowly (the lattice-point error of a circle grows more slowly than its perimeter, but it grows), while memory and, for field methods, work grow like R² — which is why the noise is divided out rather than out-resolved.
set terminal pngcairo size 900,600 font "sans,11"
set output 'shells_res.png'
set title "Lattice noise of a raw g(r) on 1 < r/σ < 3 against the particle radius"
set logscale xy
set xlabel "particle radius R [lattice units]"
set ylabel "rms |M(k) − 1| over 2R ≤ k < 6R"
set y2label "distance² bins to reach 3σ"
set logscale y2
set y2tics
set ytics nomirror
set xtics (3, 6, 12, 24)
set xrange [2.5:30]
set grid xtics ytics lc rgb "#e8e8e8"
set key top right font "sans,9" opaque box lc rgb "#cccccc" spacing 1.1 samplen 2
plot 'shells_res.dat' u 1:2 w lp lc rgb "#d62728" pt 7 lw 2 t "square", \
     '' u 1:3 w lp lc rgb "#2ca02c" pt 9 lw 2 t "triangular", \
     '' u 1:4 w lp lc rgb "#1f77b4" pt 5 lw 2 t "cubic", \
     '' u 1:6 axes x1y2 w lp lc rgb "#777777" dt 2 pt 4 t "d² bins, 36 R² (right axis)"
