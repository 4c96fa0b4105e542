# caption: How many cells? (Miller and Luding's fig. 3, J. Comput. Phys. 193, 306 (2004), measured by the lesson's driver cells.) (a) CPU µs per collision — the cost of simulated time, since every cell count runs the same melted system — against cells per particle C/N, for hard disks (N = 10 000) and spheres (N = 8000), dilute (η = 0.05) and dense (η = 0.65 disks, 0.45 spheres); circles: the engine's automatic choice (lesson 05 §6); dotted: Miller and Luding's dilute optima C/N ≈ 1.5 (2D) and 8 (3D). Few cells: every prediction tests the 3^dim·N/C particles of the block; many: a particle crosses many faces between collisions. The dilute curves have a broad minimum near those optima; a dense fluid is cheapest with as many cells as fit (side ≥ σ), where its curve ends. (b) The two competing costs — events per collision (1 + crossings + stale events, solid) grow as C/N rises, the particles in the block (dashed) fall as (C/N)^-1.
set terminal pngcairo size 1300,540 font "sans,11"
set output 'cells.png'
set multiplot layout 1,2 title "Cells per particle against the cost of event-driven hard spheres"
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"
set logscale xy
set format x "10^{%T}"
set xrange [0.005:30]
set xlabel "cells per particle C/N"
rgb(s) = s == 0 ? 0x1f77b4 : s == 1 ? 0x2ca02c : s == 2 ? 0xd62728 : 0xff7f0e
name(s) = s == 0 ? "2D, η = 0.05" : s == 1 ? "2D, η = 0.65" : s == 2 ? "3D, η = 0.05" : "3D, η = 0.45"
pick(s, v) = ($1 == s) ? v : NaN

set title "(a) cost per collision"
set ylabel "CPU µs per collision"
set key bottom left
set arrow 1 from 1.5, graph 0 to 1.5, graph 1 nohead dt 3 lc rgb 0x1f77b4
set arrow 2 from 8, graph 0 to 8, graph 1 nohead dt 3 lc rgb 0xd62728
set label 1 "Miller and Luding's\ndilute optimum, 2D" at 1.5, graph 0.95 right offset -0.5,0 font "sans,9" tc rgb 0x1f77b4
set label 2 "3D" at 8, graph 0.95 left offset 0.5,0 font "sans,9" tc rgb 0xd62728
plot for [s = 0:3] 'cells.dat' u 5:(pick(s, $6)) w lp lc rgb rgb(s) pt 7 ps 0.9 lw 2 t name(s), \
     'cells.dat' u 5:($10 == 1 ? $6 : NaN) w p lc rgb "black" pt 6 ps 2.6 lw 2 t "automatic choice"
unset arrow 1
unset arrow 2
unset label 1
unset label 2

set title "(b) the two costs: events per collision, particles in the block"
set ylabel "events per collision (solid), block particles 3^{dim}N/C (dashed)"
set yrange [0.5:3000]
set key top right
plot for [s = 0:3] 'cells.dat' u 5:(pick(s, $8)) w lp lc rgb rgb(s) pt 7 ps 0.8 lw 2 t name(s), \
     for [s = 0:3] 'cells.dat' u 5:(pick(s, $9)) w l lc rgb rgb(s) dt 2 lw 1.5 notitle
unset multiplot
