# caption: The order of indices, measured: CPU time per element of one sweep a[i][j] += 1 over an n×n int32 array, against the array size, log-log. Row order (last index innermost, consecutive addresses) stays near 0.1–0.25 ns per site at every size. Column order (first index innermost, stride 4n bytes) is about 3 times slower even inside L1 (2.6–3.6 between runs), where only vectorisation separates them; once a column no longer fits it costs one cache line per element. With power-of-two rows the stride maps a column onto a few cache sets, and the cost jumps as soon as the array outgrows L1; padding each row by 64 bytes removes that jump. The vertical lines mark this machine's L1d (48 kB) and L2 (1 MB).
set terminal pngcairo size 900,600 font "sans,11"
set output 'indices.png'
set title "Row order against column order: a C array is stored row after row"
set logscale xy
set format x "%.0s %cB"
set format y "10^{%L}"
set xlabel "array size n² × 4 bytes"
set ylabel "CPU time per element [ns]"
set grid xtics ytics lc rgb "#e8e8e8"
set yrange [0.03:60]
set key top left Left reverse font "sans,9" opaque box lc rgb "#cccccc" spacing 1.1 samplen 2
set arrow from 49152,0.03 to 49152,60 nohead lc rgb "#999999" dt 3
set label "L1d 48 kB" at 52000,0.04 tc rgb "#777777" font "sans,9"
set arrow from 1048576,0.03 to 1048576,60 nohead lc rgb "#999999" dt 3
set label "L2 1 MB" at 1.1e6,0.04 tc rgb "#777777" font "sans,9"
plot 'indices.dat' u 2:3 w lp lc rgb "#2ca02c" pt 7 ps 0.9 lw 2 t "row order: a[i][j], j inner", \
     '' u 2:4 w lp lc rgb "#d62728" pt 5 ps 0.9 lw 2 t "column order, row length n = 2^k", \
     '' u 2:5 w lp lc rgb "#1f77b4" pt 9 ps 1.0 lw 2 t "column order, row length n + 16 (padded)"
