# caption: Is an event O(1)? (The scaling figure of the DynamO paper, Bannerman, Sargant and Lue, J. Comput. Chem. 32, 3329 (2011), measured by the lesson's driver scaling.) Events (filled) and collisions (open) per second of CPU time against N for hard spheres (red) and disks (blue) at η = 0.3, the particles renumbered cell by cell at every re-base (solid; the scene key sort = true) or shuffled once at the start and never renumbered (dashed; the engine's default is not to renumber). Top axis: the memory of the 3D system, about 110 bytes per particle; dotted: where it outgrows the L2 cache (and the L3, when in range) as the machine reports them. The work per event is O(1) (plus a heap of log₂N levels), but the time is not: once the heap, the particles and the cell lists no longer fit in the cache, an event waits for memory — 4 to 5.5 times slower at N = 10⁶ than at 10³. Renumbering the particles cell by cell does not pay, which is why it is off by default: from 32768 particles on the loop prefetches — the candidates of a prediction, the next event's cells, the heap's lower levels — so the reads of a prediction are in flight together wherever they lie (lesson 05 §9). Sorted over shuffled at the largest N: 0.72–0.77 (3D) and 0.94–1.00 (2D) at demo size (N = 10⁵, two runs), 0.87 and 1.01 at full size (N = 10⁶; make lesson STAGE=05, 2 cores). The driver also times the sorted state without prefetching: prefetching is 1.35–1.55 (3D) and 1.15–1.35 (2D) times as fast at 10⁵, 2.0 and 1.5 at 10⁶. The machine is shared, and these ratios move by 10–15 % from run to run. The events per collision (1.76 in 3D, 2.17 in 2D) are the same at every N: the work per unit of physics is O(1). On a shared virtual machine the L3 it reports is the host's, not what one core gets.
set terminal pngcairo size 900,600 font "sans,11"
set output 'scaling.png'
load 'scaling_cache.gp'
set grid xtics ytics mxtics lc rgb "#e8e8e8"
set key font "sans,10" samplen 3 opaque box lc rgb "#cccccc" bottom left
set logscale xy
set format x "10^{%T}"
set format y "%.0t×10^{%T}"
set ytics add (2e5, 3e5, 5e5, 2e6, 3e6, 5e6)
set xlabel "particles N"
set ylabel "events or collisions per second of CPU time"
# the axes span the data: N from the rows, the speeds from both columns
stats 'scaling.dat' u 1 nooutput name "N"
stats 'scaling.dat' u 4 nooutput name "EV"
stats 'scaling.dat' u 5 nooutput name "CO"
stats 'scaling.dat' u ($2 == 3 ? $6 : NaN) nooutput name "B"
bytes = B_mean
nlo = N_min / 1.4
nhi = N_max * 1.4
set xrange [nlo:nhi]
set yrange [CO_min / 1.6 : EV_max * 1.6]
set x2range [nlo * bytes / 1048576 : nhi * bytes / 1048576]
set logscale x2
set x2tics
set format x2 "%g"
set x2label "memory of the 3D system, MiB"
set title "Event-driven hard particles at η = 0.3: speed against N"
if (L2 / bytes > nlo && L2 / bytes < nhi) {
	set arrow 1 from L2 / bytes, graph 0 to L2 / bytes, graph 1 nohead dt 3 lw 2 lc rgb "#555555"
	set label 1 sprintf("L2 %.3g MiB", L2 / 1048576) at L2 / bytes, graph 0.96 left offset 0.5,0 font "sans,9"
}
if (L3 / bytes < nhi) {
	set arrow 2 from L3 / bytes, graph 0 to L3 / bytes, graph 1 nohead dt 3 lw 2 lc rgb "#555555"
	set label 2 sprintf("L3 %.3g MiB", L3 / 1048576) at L3 / bytes, graph 0.96 left offset 0.5,0 font "sans,9"
}
sel(d, s) = ($2 == d && $3 == s) ? 1 : 0
plot 'scaling.dat' u 1:(sel(3, 1) ? $4 : NaN) w lp lc rgb 0xd62728 pt 7 lw 2 t "3D events, sorted", \
     '' u 1:(sel(3, 0) ? $4 : NaN) w lp lc rgb 0xd62728 pt 7 dt 2 lw 1.5 t "3D events, shuffled", \
     '' u 1:(sel(3, 1) ? $5 : NaN) w lp lc rgb 0xd62728 pt 6 lw 2 t "3D collisions, sorted", \
     '' u 1:(sel(2, 1) ? $4 : NaN) w lp lc rgb 0x1f77b4 pt 5 lw 2 t "2D events, sorted", \
     '' u 1:(sel(2, 0) ? $4 : NaN) w lp lc rgb 0x1f77b4 pt 5 dt 2 lw 1.5 t "2D events, shuffled", \
     '' u 1:(sel(2, 1) ? $5 : NaN) w lp lc rgb 0x1f77b4 pt 4 lw 2 t "2D collisions, sorted"
