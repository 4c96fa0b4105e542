# caption: Left: the final configuration of scene 02-walk-square — hard disks R = 3 at packing 0.3 after 2200 random-walk sweeps on the square lattice (128²), each disk a circle of its true radius. Right: g(r) of hard disks R = 3 at packing 0.4 on the triangular lattice (scene 02-walk-triangular, 200 configurations), per unit-width shell. Grey: the raw g, pairs over the exact shell area — the fluid's structure with the lattice's own jagged pattern on top. Blue: the corrected g, pairs over the shell's lattice point count — the contact peak at r = σ, the second shell near 2σ and g → 1 beyond, smooth.
set terminal pngcairo size 1100,520 font "sans,11"
set output 'walkers.png'
set multiplot layout 1,2 title "Hard disks that walk on a lattice (scenes 02-walk-square, 02-walk-triangular)"
set title "square lattice, R = 3, packing 0.3"
set size ratio -1
unset key
set xlabel "x [lattice units]"
set ylabel "y [lattice units]"
set xrange [0:128]
set yrange [0:128]
plot 'runs/02-walk-square/config.dat' u 1:2:3 w circles fs transparent solid 0.45 lc rgb "#1f77b4"
set size noratio
set autoscale
set title "g(r), triangular lattice, R = 3, packing 0.4"
set grid xtics ytics lc rgb "#e8e8e8"
set key top right font "sans,10" opaque box lc rgb "#cccccc" width -6
set xlabel "r / σ"
set ylabel "g(r)"
set xrange [0:4]
set yrange [0:2.8]
plot 'runs/02-walk-triangular/gr.dat' u 1:2 w l lw 1 lc rgb "#aaaaaa" t "raw: over the exact shell area", \
     '' u 1:3 w lp pt 7 ps 0.5 lw 2 lc rgb "#1f77b4" t "corrected: over the lattice point count", \
     1 w l dt 2 lc rgb "black" t "ideal gas"
unset multiplot
