# caption: Square-well disks (R = 3 on the square lattice, 256², coverage 0.20, well to λ = 1.5σ, depth ε) after Metropolis moves with the acceptance looked up from a table (4×10⁴ sweeps cold, 2.2×10⁴ hot). Left: kT = 0.4 ε — the gas has condensed into dense liquid-like clusters with a thin vapour between them. Middle: kT = 2 ε — a uniform fluid with short-lived pairs. Right: the energy per particle, recorded every 100 sweeps from the random start: the hot fluid settles at once near −0.78 ε; the cold one drops to about −2.5 ε and keeps creeping down as the clusters coarsen (the error bar in the summary does not see that drift). From the scenes 03-well-cold and 03-well-hot.
set terminal pngcairo size 1500,540 font "sans,11"
set output 'well.png'
set multiplot layout 1,3
set size ratio -1
unset key
set style fill solid 0.6 border lc rgb "#333333"
set xlabel "x [lattice units]"; set ylabel "y [lattice units]"
set xrange [0:256]; set yrange [0:256]
set title "kT = 0.4 ε: clusters in a vapour"
plot 'runs/03-well-cold/config.dat' u 1:2:3 w circles lc rgb "#2171b5"
set title "kT = 2 ε: a uniform fluid"
plot 'runs/03-well-hot/config.dat' u 1:2:3 w circles lc rgb "#cb181d"
set size noratio
set autoscale xy
set key bottom left
set title "energy per particle"
set xlabel "sweep"; set ylabel "E / N [ε]"
set grid xtics ytics lc rgb "#e8e8e8"
set xtics 10000
plot 'runs/03-well-cold/energy.dat' u 1:2 w l lw 2 lc rgb "#2171b5" t "kT = 0.4 ε", \
     'runs/03-well-hot/energy.dat' u 1:2 w l lw 2 lc rgb "#cb181d" t "kT = 2 ε"
unset multiplot
