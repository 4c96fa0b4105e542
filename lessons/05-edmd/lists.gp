# caption: Cells or lists, and how wide a shell (the lesson's driver lists)? Hard spheres, N = 8000, melted at each packing η and loaded into the cells and into lists of eight shells S. (a) Collisions per CPU second against η: the cells (black) and every shell (colours); circles: the engine's automatic choice. (b) At each shell, what a list costs to keep — rebuilds per collision (solid; a particle rebuilds when it strays δ = (S − 1)/2 from where its list was built) — and what it saves: the candidates of a prediction (dashed), against the 27 cells' worth a cell prediction scans.
set terminal pngcairo size 1300,560 font "sans,11"
set output 'lists.png'
set multiplot layout 1,2 title "Neighbour lists for event-driven hard spheres: the shell trade"
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"
shells = "1.2 1.3 1.35 1.4 1.5 1.8 2.2 3.0"
rgb(k) = word("0x1f77b4 0x2ca02c 0x17becf 0xd62728 0xff7f0e 0x9467bd 0x8c564b 0xe377c2", k) + 0
pick(S, v) = abs($2 - S) < 1e-6 ? v : NaN

set title "(a) collisions per CPU second"
set logscale x
set format x "%g"
set xlabel "packing fraction η"
set ylabel "collisions per CPU second"
set logscale y
set format y "%.0t×10^{%T}"
set key bottom right
plot 'lists.dat' u 1:(pick(0, $3)) w lp lc rgb "black" pt 5 lw 2.5 t "cells", \
     for [k = 1:8] '' u 1:(pick(real(word(shells, k)), $3)) w lp lc rgb rgb(k) pt 7 ps 0.8 lw 1.5 t sprintf("lists, S = %s", word(shells, k)), \
     '' u 1:($8 == 1 ? $3 : NaN) w p lc rgb "black" pt 6 ps 2.6 lw 2 t "automatic choice"

set title "(b) the price and the gain of a shell"
set ylabel "rebuilds per collision (solid), candidates per prediction (dashed)"
set key top left
plot for [k = 1:8] 'lists.dat' u 1:(pick(real(word(shells, k)), $5)) w lp lc rgb rgb(k) pt 7 ps 0.7 lw 1.5 t sprintf("S = %s", word(shells, k)), \
     for [k = 1:8] '' u 1:(pick(real(word(shells, k)), $6)) w l lc rgb rgb(k) dt 2 lw 1.5 notitle
unset multiplot
