# caption: Thesis table 2.1 and fig. 2.21 again (the lesson's driver insert_time): CPU seconds to drop N disks of radius 4 lattice units (σ = 8) at random into a periodic square box, up to coverage 0.3, the box growing with N, by three methods that draw the same random sites and build the very same configuration, disk by disk (checked). Left: time against N, medians of 3 repeats on a shared 2-core AMD EPYC, with the power laws t ∝ N^b fitted over all but the smallest box (lines; the legend gives this run's exponents, which vary by up to ±0.1 between runs). Coordinates tested against all pairs, b ≈ 2.0–2.1 — the thesis's neighbour-list generator: 5 s for 25 000 disks, stopped there (400 000 would take some 20 minutes); the field, b ≈ 1.1–1.25: one look-up per try and the excluded disk painted per disk, 0.9–1.2 s for 400 000 disks; coordinates in a grid of cells of side σ, b ≈ 1.05–1.1: 9 cells per try, 0.11–0.17 s for 400 000 disks. The two O(N) methods are slightly super-linear because their memory outgrows the caches. Middle: the same per disk. Unlike the thesis's guess (a cell list "not as fast as the field"), on today's machine the grid is 5–10 times faster than the field: a try costs the field a cache miss, and a placement paints 193 bytes on 15 rows, where the grid reads a few coordinates. Right: the memory. The field needs L² bytes, 176 bytes per disk at this coverage, against 16 (all pairs) and 30 (grid) bytes per disk: at N = 400 000 the field is 70 MB, the grid 12 MB.
set terminal pngcairo size 1500,520 font "sans,11"
set output 'insert_time.png'
set datafile missing "nan"
set multiplot layout 1,3 title "Random insertion of N disks (R = 4, coverage 0.3): the field against coordinates"
set grid xtics ytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc" bottom right
# The fitted exponents, read back from the fitted columns (exact power laws).
stats 'insert_time.dat' u (log($2)):(log($6)) name "F" nooutput
stats 'insert_time.dat' u (log($2)):(log($7)) name "A" nooutput
stats 'insert_time.dat' u (log($2)):(log($8)) name "G" nooutput
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "disks N"
stats 'insert_time.dat' u 2 name "N" nooutput
set xrange [N_min / 1.3 : N_max * 1.3]

set title "(a) CPU time, with fitted t ∝ N^b"
set ylabel "CPU seconds"
plot 'insert_time.dat' u 2:4 w p lc rgb "#d62728" pt 7 ps 1.2 t sprintf("all pairs, b = %.2f", A_slope), \
     '' u 2:7 w l lc rgb "#d62728" lw 1.5 notitle, \
     '' u 2:3 w p lc rgb "#1f77b4" pt 5 ps 1.2 t sprintf("field, b = %.2f", F_slope), \
     '' u 2:6 w l lc rgb "#1f77b4" lw 1.5 notitle, \
     '' u 2:5 w p lc rgb "#2ca02c" pt 9 ps 1.3 t sprintf("cell grid, b = %.2f", G_slope), \
     '' u 2:8 w l lc rgb "#2ca02c" lw 1.5 notitle

set title "(b) CPU time per disk"
set key top left
set ylabel "CPU µs per disk"
plot 'insert_time.dat' u 2:(1e6 * $4 / $2) w lp lc rgb "#d62728" pt 7 ps 1.2 lw 1.5 t "all pairs", \
     '' u 2:(1e6 * $3 / $2) w lp lc rgb "#1f77b4" pt 5 ps 1.2 lw 1.5 t "field", \
     '' u 2:(1e6 * $5 / $2) w lp lc rgb "#2ca02c" pt 9 ps 1.3 lw 1.5 t "cell grid"

set title "(c) memory of the method's data"
set key bottom right
set ylabel "bytes"
plot 'insert_time.dat' u 2:9 w lp lc rgb "#1f77b4" pt 5 ps 1.2 lw 1.5 t "field: L² + 8 per disk", \
     '' u 2:11 w lp lc rgb "#2ca02c" pt 9 ps 1.3 lw 1.5 t "cell grid: 20 per disk + 4 per cell", \
     '' u 2:10 w lp lc rgb "#d62728" pt 7 ps 1.2 lw 1.5 t "all pairs: 16 per disk"
unset multiplot
