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
set autoscale xfix
set offsets graph 0.04, graph 0.04, 0, 0
set key top left Left reverse font "sans,9" opaque box lc rgb "#cccccc" spacing 1.1 samplen 2
# the caches of the machine the plot is drawn on (getconf; 0 or nothing: no line)
L1 = real(system("getconf LEVEL1_DCACHE_SIZE 2>/dev/null || echo 0"))
L2 = real(system("getconf LEVEL2_CACHE_SIZE 2>/dev/null || echo 0"))
if (L1 > 0) {
	set arrow 1 from L1, graph 0 to L1, graph 1 nohead lc rgb "#999999" dt 3
	set label 1 sprintf("L1d %.0f kB", L1 / 1024) at L1, graph 0.03 offset 0.5,0 tc rgb "#777777" font "sans,9"
}
if (L2 > 0) {
	set arrow 2 from L2, graph 0 to L2, graph 1 nohead lc rgb "#999999" dt 3
	set label 2 sprintf("L2 %.3g MB", L2 / 1048576) at L2, graph 0.03 offset 0.5,0 tc rgb "#777777" font "sans,9"
}
plot 'indices.dat' u 2:3 w lp lc rgb "#2ca02c" pt 7 ps 0.9 lw 2 t "row order: a[i][j], j inner", \
     '' u 2:4 w lp lc rgb "#d62728" pt 5 ps 0.9 lw 2 t "column order, row length n = 2^k", \
     '' u 2:5 w lp lc rgb "#1f77b4" pt 9 ps 1.0 lw 2 t "column order, row length n + 16 (padded)"
