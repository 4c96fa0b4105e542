# caption: Relative error of the sum of 1/k² for k = 1…n, four ways, log-log. Largest terms first (naive), the small terms meet a partial sum near 1.64 and lose their low bits, so the error climbs with n. Adding the same numbers smallest first, pairwise, or with Kahan compensation stays at a few units of ε = 2⁻⁵³ ≈ 1.1·10⁻¹⁶ (dashed) for any n. The dotted guides show the naive error bounds ε√n (random rounding) and εn (worst case).
set terminal pngcairo size 900,600 font "sans,11"
set output 'summation.png'
set title "Summing 1/k², k = 1 … n: the order and the method matter"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "number of terms n"
set ylabel "relative error of the sum"
set grid xtics ytics lc rgb "#e8e8e8"
stats 'summation.dat' u 1 nooutput name "N"
set xrange [N_min / 1.25 : N_max * 1.25]
set yrange [1e-18:1e-10]
set key top left Left reverse font "sans,9" opaque box lc rgb "#cccccc" spacing 1.1 samplen 2
eps = 2.0**-53
plot 'summation.dat' u 1:2 w lp lc rgb "#d62728" pt 7 ps 0.8 lw 2 t "naive, largest first", \
     '' u 1:3 w lp lc rgb "#2ca02c" pt 9 ps 0.9 lw 2 t "naive, smallest first (like magnitudes meet)", \
     '' u 1:4 w lp lc rgb "#ff7f0e" pt 4 ps 0.9 lw 1.5 t "pairwise (two halves, each summed pairwise)", \
     '' u 1:5 w lp lc rgb "#1f77b4" pt 6 ps 1.0 lw 1.5 t "Kahan-compensated", \
     eps * x w l lc rgb "#999999" dt 3 lw 1.5 t "ε n, ε √n", \
     eps * sqrt(x) w l lc rgb "#999999" dt 3 lw 1.5 notitle, \
     eps w l lc rgb "#444444" dt 2 lw 1 t "ε = 2^{-53}"
