# caption: The speed of the field method (thesis table 2.3), measured by the lesson's driver locality: 1100 hard disks at coverage 0.4746 random-walking on the square lattice with radius R = 12, 6, 3, 1.5 in boxes of 1024, 512, 256, 128 (the same physical system at four resolutions), each in its box alone (open circles) and in the corner of allocated lattices of side P = 1024 … 8192 — the very same walk in every allocation (checked). Left: atom-steps per CPU second, median of 5 repeats on a shared 2-core AMD EPYC, bars from the slowest to the fastest repeat (between runs the medians vary by some 10 %). A step repaints 4R − 1 head and as many tail points, so halving R should double the speed, and more, since small disks are refused more often (acceptance 0.87 at R = 12, 0.47 at R = 1.5): the painting per offered step falls 2.3, 2.6 and 2.9 times. In the box alone the speed goes up 2.1–2.3 times from R = 12 to 6, but only 1.7 and 1.4 times below, where the fixed cost of a step (the random direction, the test, the calls) takes over. In a large allocation spread-out memory costs large disks dearly: R = 12 runs 2.6 times slower at P ≥ 4096 than in its box alone — from there on every row of the box is on its own 4 kB page, and a step touches 47 rows — R = 6 1.6 times, R = 3 1.15 times, R = 1.5 hardly at all. The thesis (433 MHz Alpha, P = 1024 against 8192) had 1.3, 1.7 and 1.2 for R = 12, 6, 3. Right: the time of an offered step against the points it repaints (acceptance × 2 × head points), one colour per allocation, with the fitted t = c0 + c1·points (dashed): in the box alone and up to P = 2048 about 15–21 ns fixed and 1.6–2.3 ns a point (between runs); at P ≥ 4096 the line no longer fits (c1 ≈ 5–5.6 ns, c0 < 0): a point costs more the more rows a step touches.
set terminal pngcairo size 1300,560 font "sans,11"
set output 'locality.png'
set datafile missing "nan"
set multiplot layout 1,2 title "Field method: speed against particle radius and allocated memory (1100 disks, θ = 0.4746)"
set grid xtics ytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"
col(R, k) = ($1 == R && $4 >= k) ? $3 : NaN
alone(R) = ($1 == R && $4 == 0) ? $3 : NaN
rgb(i) = i == 0 ? 0xd62728 : i == 1 ? 0xff7f0e : i == 2 ? 0x2ca02c : 0x1f77b4
Rof(i) = i == 0 ? 12 : i == 1 ? 6 : i == 2 ? 3 : 1.5

set title "(a) speed against the allocated side P"
set logscale x 2
set logscale y
stats 'locality.dat' u 3 nooutput name "P"
set xrange [P_min / 1.4 : P_max * 1.4]
set yrange [1.5:50]
set xlabel "allocated lattice side P  [sites]"
set ylabel "10^6 atom-steps per CPU second"
set ytics (2, 3, 5, 7, 10, 15, 20, 30, 50)
set key bottom left
plot for [i = 0:3] 'locality.dat' u (col(Rof(i), 1)):($5 / 1e6):($6 / 1e6):($7 / 1e6) w yerrorlines lc rgb rgb(i) pt 7 ps 0.9 lw 2 t sprintf("R = %g, box %d", Rof(i), 1024 * Rof(i) / 12), \
     for [i = 0:3] '' u (alone(Rof(i))):($5 / 1e6) w p lc rgb rgb(i) pt 6 ps 2.2 lw 2 notitle, \
     1/0 w p lc rgb "#555555" pt 6 ps 2.2 lw 2 t "box alone (P = L)"

set title "(b) time of an offered step against the points it repaints"
unset logscale
set ytics auto
set xrange [0:90]
set yrange [0:*]
set xlabel "points repainted per offered step (acceptance × 2 × head points)"
set ylabel "CPU ns per offered step"
set key top left
cname(k) = k == 0 ? "box alone" : sprintf("P = %d", 1024 * 2**(k - 1))
crgb(k) = k == 0 ? 0x555555 : k == 1 ? 0x9467bd : k == 2 ? 0x17becf : k == 3 ? 0xbcbd22 : 0xe377c2
stats 'locality.dat' u 4 nooutput
NC = int(STATS_max) + 1
# The rows go radius by radius, NC allocations each: every NC-th row is one allocation.
plot for [k = 0:NC - 1] 'locality.dat' every NC::k u 10:11 w p lc rgb crgb(k) pt 7 ps 1.2 t cname(k), \
     for [k = 0:NC - 1] '' every NC::k u 10:12 w l lc rgb crgb(k) lw 1.5 dt 2 notitle, \
     '' every NC::NC - 1 u 10:11:(sprintf("R = %g", $1)) w labels left offset 1,0 font "sans,10" notitle
unset multiplot
