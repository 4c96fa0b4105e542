# caption: The four drivers of the thesis's table 2.2 on one system, measured by the lesson's driver table22: hard disks of radius 12 random-walking on the square lattice at packing 0.474, boxes 1024 … 32768 (N = 1099 … 1.1 million), each driver at its best safe skin (NL and FNL Δr = 32, CL 7). FNL, CL and FR walk the very same trajectory (checked; NL too where it runs as many sweeps), with no missed pair and no overlap. Left: atom-steps per CPU second on a shared 2-core AMD EPYC (median of 3 up to 70 315 disks, bars from the slowest to the fastest run; single runs above); open symbols and dashed lines are the thesis's numbers (433 MHz Alpha, 2000) on the same axis. NL rebuilds from all pairs and falls as N^-0.92; over the thesis's sizes FNL (N^-0.03) and CL (N^-0.19) hold their speed as in the thesis (exponents at full size, make lesson STAGE=04; the demo size stops at 70 315 disks, with −0.8, 0.0 and −0.26); beyond, with the particles in random order, all drivers lose to the memory (cell_order shows the cure). Right: the bytes each driver keeps besides the positions, per particle: two copies of short lists (128 B) or cells (120 B) against the field's byte per lattice site (954 B).
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
stats 'table22.dat' u 1 nooutput name "N"
set xrange [N_min / 1.5 : N_max * 1.5]
set yrange [1e4:3e9]
set key top right
plot for [d = 0:3] 'table22.dat' u 1:(pick(d, $4)):(pick(d, $5)):(pick(d, $6)) w yerrorlines lc rgb rgb(d) pt 7 ps 1 lw 2 t name(d), \
     for [d = 0:3] '' u 1:(pick(d, $7)) w lp lc rgb rgb(d) pt 6 ps 1.2 dt 2 lw 1.5 t name(d)." (thesis)"

set title "(b) memory of the neighbour structure"
set ylabel "bytes per particle"
set yrange [10:5000]
set key top left
plot for [d = 0:3] 'table22.dat' u 1:(pick(d, $8)) w lp lc rgb rgb(d) pt 7 ps 1 lw 2 t name(d)
unset multiplot
