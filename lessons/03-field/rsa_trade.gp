# caption: The trade of lesson 03 (the lesson's driver rsa_jam, the runs of the plot rsa_jam): what a finer lattice buys and costs when the field makes random jammed packings. Error: the jamming coverage on the lattice minus the continuum value (0.547069 disks, 0.38413 spheres), in absolute value; filled for θ itself, open for θ_eff (θ corrected for the lattice disk's true size: the part that falls smoothly, like 0.12/R); one point per radius, R = 1/2 … 48 in 2D and 1/2 … 12 in 3D, labelled on the square lattice; the bars are standard errors. Left: the cost in CPU microseconds per particle (allocation, random draws, painting and the final list of free sites; mean over the runs on a shared 2-core AMD EPYC). Right: the field's memory, L^d bytes per particle at jamming. Both grow like R^d — a particle paints its excluded area (volume), and the box must hold the particles — while the error falls only like 1/R: in 2D each halving of the error costs about 4 times the time and the memory, in 3D 8 times. Below R ≈ 2 the lattice is a different problem (at R = 1/2 every site is taken). On the square lattice the error is 1.6 % at R = 4 (about 1 µs and 93 bytes per disk), 0.7 % at R = 16 (9–18 µs, 1.5 kB) and 0.46 % at R = 48 (170–235 µs, 13 kB; timings vary with the load); and θ itself does not improve smoothly, because the lattice disk's size jumps with R. A sphere costs 3 to 50 times as much as a disk of the same R, more the larger R.
set terminal pngcairo size 1400,580 font "sans,11"
set output 'rsa_trade.png'
set datafile missing "nan"
set multiplot layout 1,2 title "Jamming coverage on a lattice: error against cost, one point per particle radius R"
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc" top right
sel(k, c) = ($1 == k) ? column(c) : NaN
lname(k) = k == 0 ? "square" : k == 1 ? "triangular" : "cubic (3D)"
lrgb(k) = k == 0 ? 0xd62728 : k == 1 ? 0x2ca02c : 0x1f77b4
lpt(k) = k == 0 ? 5 : k == 1 ? 9 : 7
load 'rsa_ref.gp'  # theta_disks, theta_spheres: rsa_jam.c writes them from datasets/reference/rsa.csv
cont(k) = k < 2 ? theta_disks : theta_spheres
# an error less than two standard errors from zero is noise: drawn as its upper bound,
# |error| + 2 standard errors, with an arrow down, and not joined to the line
dev(k) = abs($7 - cont(k))
bias(k) = dev(k) > 2 * $8 ? dev(k) : NaN
bound(k) = dev(k) > 2 * $8 ? NaN : dev(k) + 2 * $8
set logscale xy
set yrange [3e-4:0.5]
set ylabel "|θ − θ_{continuum}| at jamming"
set format x "10^{%L}"
set format y "10^{%L}"

do for [panel = 0:1] {
	c = panel == 0 ? 14 : 15
	if (panel == 0) {
		set title "(a) against CPU time per particle"
		set xlabel "CPU µs per particle (allocation + RSA to jamming)"
		set autoscale xfix
		set offsets graph 0.05, graph 0.08, 0, 0
	} else {
		set title "(b) against memory per particle"
		set xlabel "field bytes per particle, L^d / N"
		set autoscale xfix
	}
	plot for [k = 0:2] 'rsa_jam.dat' u (sel(k, c)):(bias(k)):8 w yerrorlines lc rgb lrgb(k) pt lpt(k) ps 1 lw 1.5 t lname(k) . ": θ", \
	     for [k = 0:2] '' u (sel(k, c)):(bound(k)):(0):(-0.5 * bound(k)) w vectors head filled size screen 0.006,25 lc rgb lrgb(k) lw 1.2 notitle, \
	     for [k = 0:2] '' u (sel(k, c)):(abs($11 - cont(k))) w lp lc rgb lrgb(k) pt lpt(k) - 1 ps 1 lw 1 dt 2 t lname(k) . ": θ_{eff}", \
	     1/0 w vectors head filled lc rgb "#555555" t "θ within 2 errors of the continuum: upper bound", \
	     '' u (sel(0, c)):(dev(0) > 2 * $8 ? dev(0) : bound(0)):(sprintf("%g", $3)) w labels left offset 0.7,0.6 font "sans,9" tc rgb "#d62728" notitle
}
unset multiplot
