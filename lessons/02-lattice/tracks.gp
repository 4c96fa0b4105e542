# caption: The unwrapped path of one hard disk among 40 (R = 2, box 128², packing 0.03) for 2000 sweeps (1000 at demo size), after thesis fig. 2.3. Top: random walk, a new random direction every step — a tangle that has wandered some √t lattice units. Bottom: ballistic, one direction kept until the disk meets another — straight flights of tens of lattice units (the mean run, printed by the experiment, is near the free path 1/(2nσ)), then a turn by a multiple of 90° (square) or 60° (triangular). The triangular tracks are drawn in Cartesian coordinates, not the sheared storage ones. Note the different scales.
set terminal pngcairo size 1000,900 font "sans,11"
set output 'tracks.png'
set multiplot layout 2,2 title "One disk's path: random walk against ballistic motion (thesis fig. 2.3)"
set grid xtics ytics lc rgb "#e8e8e8"
set size ratio -1
unset key
set xlabel "x [lattice units]"
set ylabel "y [lattice units]"
sel(k, c) = ($1 == k) ? column(c) : NaN
title(k) = k == 0 ? "square, random walk" : k == 1 ? "square, ballistic" : k == 2 ? "triangular, random walk" : "triangular, ballistic"
# each path in a square window around it, so that every panel is equally large at
# its own scale (x and y share one scale within a panel: the turns keep their angles)
do for [k in "0 2 1 3"] {
	stats 'tracks.dat' u (sel(k + 0, 2)):(sel(k + 0, 3)) nooutput name "P"
	half = 0.55 * ((P_max_x - P_min_x) > (P_max_y - P_min_y) ? P_max_x - P_min_x : P_max_y - P_min_y) + 1
	cx = 0.5 * (P_max_x + P_min_x)
	cy = 0.5 * (P_max_y + P_min_y)
	set xrange [cx - half : cx + half]
	set yrange [cy - half : cy + half]
	set title title(k + 0)
	plot 'tracks.dat' u (sel(k + 0, 2)):(sel(k + 0, 3)) w l lw 1 lc rgb (k + 0 < 2 ? "#1f77b4" : "#d62728")
	set xrange [*:*]
	set yrange [*:*]
}
unset multiplot
