# bench-05-edmd.gp — make bench, stage 05: events per CPU second of the event loop
# against N, hard disks and hard spheres at three packings, with the N at which the
# particle data (N · state_bytes_per_particle) outgrows the L2 and the L3 cache: beyond
# it a prediction reads its neighbours from memory and the speed drops.
# bench.sh runs it as: gnuplot -e "table='BUILD/bench/05-edmd.tsv';
#   out='BUILD/bench/05-edmd.png'; l2=BYTES; l3=BYTES" (cache sizes 0 when unknown).
set terminal pngcairo size 1000,620 enhanced font 'Sans,11'
set output out
set datafile separator "\t"
set logscale xy
set format x "10^{%L}"
set grid
set key outside right top
set xlabel 'N (particles)'
set ylabel 'million events per CPU second'
set format y '%g'
set title 'event-driven hard disks and spheres: speed against N (make bench)'

stats table using "state_bytes_per_particle" nooutput
bytes = STATS_mean
stats table using "n" nooutput
nmin = STATS_min
nmax = STATS_max
set xrange [nmin / 2 : nmax * 2]
# the caches, as the N whose particle data fills them
if (l2 > 0) {
	set arrow 1 from l2 / bytes, graph 0 to l2 / bytes, graph 1 nohead dt 2 lw 2 lc rgb '#808080'
	set label 1 sprintf("N · %.0f B = L2, %.0f KiB", bytes, l2 / 1024.) at l2 / bytes, graph 0.05 rotate left offset -1, 0
}
if (l3 > 0) {
	set arrow 2 from l3 / bytes, graph 0 to l3 / bytes, graph 1 nohead dt 4 lw 2 lc rgb '#808080'
	set label 2 sprintf("N · %.0f B = L3, %.0f MiB", bytes, l3 / 1048576.) at l3 / bytes, graph 0.05 rotate left offset -1, 0
}

# the rows sorted by dim, packing and N, so that each curve's points are consecutive
rows = sprintf("< (head -n 1 %s; tail -n +2 %s | sort -k2,2n -k3,3g -k4,4g)", table, table)
pick(d, p) = column("dim") == d && abs(column("packing") - p) < 1e-9 ? column("n") : NaN
plot for [d in "2 3"] for [p in "0.1 0.3 0.45"] \
	rows using (pick(d + 0, p + 0)):(column("events_per_s") / 1e6) \
	w lp lw 2 pt (d eq "2" ? 6 : 7) t sprintf("%sD, η = %s", d, p)
