# caption: The particle as a painted shape. (a) The excluded disk of a particle with R = 4 on the square lattice (all sites closer than σ = 8 to its centre, a site at exactly 8 is outside) and what a step along +x changes: it gains the green head points and loses the red tail points; the grey body is not touched. (b) Circles of radius 6, 8, 10 and 10.9 on the triangular lattice, drawn where the sites are (only the rim of each set is shown). (c) The same point sets in the sheared storage coordinates the program uses: ellipses x² + xy + y² < r² (thesis fig. 2.14). (d) Points per shape (area) and head points per step (perimeter) against r, with the continuum values πr²/cell and 2ra/cell (4/3πr³ and πr²a in 3D, a the step length): moving costs r^(d−1), painting r^d. The cubic head points lie on top of the square |S| points: the crescent a sphere sweeps in one step is a disk of its radius. Exact counts from the lesson's driver shapes.
set terminal pngcairo size 1100,1000 font "sans,11"
set output 'shapes.png'
set multiplot layout 2,2
set size ratio -1
set grid xtics ytics lc rgb "#eeeeee"
set key below font "sans,9" samplen 1
sel(p, s, c) = ($1 == p && $2 == s) ? column(c) : NaN
set title "(a) square lattice, σ = 8: a step along +x"
set xlabel "x [lattice units]"; set ylabel "y [lattice units]"
set xrange [-9:10]; set yrange [-9:9]
plot 'shapes.dat' u (sel(0,0,3)):4 w p pt 5 ps 0.9 lc rgb "#bbbbbb" t "body (kept)", \
     '' u (sel(0,1,3)):4 w p pt 5 ps 0.9 lc rgb "#2ca02c" t "head (+1)", \
     '' u (sel(0,2,3)):4 w p pt 5 ps 0.9 lc rgb "#d62728" t "tail (−1)", \
     '+' u (0):(0) every ::0::0 w p pt 3 ps 2 lw 2 lc rgb "black" t "centre"
set xrange [-13:13]; set yrange [-13:13]
set title "(b) triangular lattice: circles where the sites are"
set xlabel "X [lattice units]"; set ylabel "Y [lattice units]"
plot for [c = 0:3] 'shapes.dat' u (sel(1,c,5)):6 w p pt 7 ps 0.5 t sprintf("r = %s", c == 0 ? "6" : c == 1 ? "8" : c == 2 ? "10" : "10.9")
set xrange [-14:14]; set yrange [-14:14]
set title "(c) the same sites in storage coordinates: ellipses"
set xlabel "x (storage)"; set ylabel "y (storage)"
plot for [c = 0:3] 'shapes.dat' u (sel(1,c,3)):4 w p pt 7 ps 0.5 t sprintf("r = %s", c == 0 ? "6" : c == 1 ? "8" : c == 2 ? "10" : "10.9")
set size noratio
set autoscale xy
set logscale xy
set title "(d) cost of painting (area) and of a step (perimeter)"
set xlabel "r = 2R [lattice units]"; set ylabel "points"
set key below font "sans,9" samplen 2 maxrows 3
set format y "10^{%L}"
# shapes_cost.dat: square8 rows 0-47 (8 steps per r), triangular 48-83 (6), cubic26 84- (26);
# every n::first picks the axis step of each radius
plot 'shapes_cost.dat' every 8::0::47 u 2:($5*pi*$2**2) w lp pt 5 lc rgb "#1f77b4" t "|S|, square", \
     '' every 8::0::47 u 2:7 w lp pt 4 lc rgb "#1f77b4" t "head, square axis step", \
     '' every 6::48::83 u 2:7 w lp pt 8 lc rgb "#2ca02c" t "head, triangular", \
     '' every 26::84 u 2:($5*4.0/3*pi*$2**3) w lp pt 7 lc rgb "#9467bd" t "|S|, cubic", \
     '' every 26::84 u 2:7 w lp pt 6 lc rgb "#9467bd" t "head, cubic face step", \
     [3:96] 2*x w l dt 2 lc rgb "#444444" t "2r (continuum)", \
     [3:96] pi*x**2 w l dt 3 lc rgb "#444444" t "πr² (continuum)"
unset multiplot
