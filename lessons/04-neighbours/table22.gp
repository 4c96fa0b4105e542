# caption: The four drivers of the thesis's table 2.2 on one system, measured by table22.c: hard disks of radius 12 random-walking on the square lattice at packing 0.474, boxes 1024 … 32768 (N = 1099 … 1.1 million), skin 4, lists refreshed at the safe interval of 2 sweeps. Every driver walks the very same trajectory (checked). Left: atom-steps per CPU second (median of 3 on a shared 2-core AMD EPYC, bars from the slowest to the fastest repeat); open symbols and dashed lines are the thesis's numbers (433 MHz Alpha, 2000), on the same axis, about 100 times lower. NL rebuilds its lists from all pairs and falls as 1/N once that dominates; FNL, CL and FR stay nearly flat — O(N) — and sag where the data leave the caches. Right: the bytes each driver keeps besides the positions, per particle: lists of a few entries against the field's byte per lattice site (1/packing × πR² ≈ 950 bytes per disk).
set terminal pngcairo size 1300,560 font "sans,11"
set output 'table22.png'
set datafile missing "nan"
set multiplot layout 1,2 title "Table 2.2 remeasured: hard disks R = 12, packing 0.474, random walk"
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"
set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
rgb(d) = d == 0 ? 0xd62728 : d == 1 ? 0x1f77b4 : d == 2 ? 0x2ca02c : 0x9467bd
name(d) = d == 0 ? "NL" : d == 1 ? "FNL" : d == 2 ? "CL" : "FR"
pick(d, v) = ($3 == d) ? v : NaN

set title "(a) atom-steps per second against N"
set xlabel "particles N"
set ylabel "atom-steps per CPU second"
set xrange [700:2e6]
set yrange [5e3:1e9]
set key top right
plot for [d = 0:3] 'table22.dat' u 1:(pick(d, $4)):(pick(d, $5)):(pick(d, $6)) w yerrorlines lc rgb rgb(d) pt 7 ps 1 lw 2 t name(d), \
     for [d = 0:3] '' u 1:(pick(d, $7)) w lp lc rgb rgb(d) pt 6 ps 1.2 dt 2 lw 1.5 t name(d)." (thesis)"

set title "(b) memory of the neighbour structure"
set ylabel "bytes per particle"
set yrange [10:5000]
set key top left
plot for [d = 0:3] 'table22.dat' u 1:(pick(d, $8)) w lp lc rgb rgb(d) pt 7 ps 1 lw 2 t name(d)
unset multiplot
