# caption: Load balance (the lesson's driver balance). A 2D system that is not uniform: a dense square (η = 0.45) in one quarter of a periodic box, a dilute gas (η = 0.05) in the rest, melted. (a) The committed events per cell of a pilot run (P = 8 along the Morton curve, even cuts, the first quarter of the measured time): the dense square does almost all the work. (b) The owners of the cells when the Morton curve is cut into 8 runs of equally many cells: three ranks hold nearly all of the dense square. (c) The owners when the curve is cut where the running total of the pilot's load reaches k/8 (lesson 06 §8): the dense square is shared out, and one large domain holds most of the dilute gas. (d) Each rank's committed events in the measured run, even and balanced cuts. (e) The imbalance, the largest rank's committed events over the mean, against P. (f) Speed-up against one rank in virtual time on the cluster (1 µs an event, 0.5 µs a message, 2 µs latency), with the best window for each run. Balance pays along the Morton curve at every P; along rows the balanced slabs in the dense part become thin, the share of the events in border cells (printed by the driver) doubles, and the rollbacks eat the gain — at P = 16 at full size (make lesson STAGE=06: 15 % to 27 %), already at P = 8 at demo size (9 % to 20 %, P ≤ 8). Every run commits the serial events, bit for bit.
set terminal pngcairo size 1400,900 font "sans,11"
set output 'balance.png'
set multiplot layout 2,3 title "Load balance: even cuts against cuts balanced on a pilot run's load"
set size ratio -1
unset key
set xlabel "x, σ"
set ylabel "y, σ"
stats 'balance_map.dat' u 1 nooutput name "X"
set xrange [0:X_max + X_min]
set yrange [0:X_max + X_min]

set title "(a) committed events per cell (pilot, log scale)"
set palette defined (0 "#ffffff", 1 "#fde0a0", 2 "#f08030", 3 "#a01010", 4 "#300000")
set cblabel "log_{10}(1 + events)"
set autoscale cb
plot 'balance_map.dat' u 1:2:(log10(1 + $3)) w image

set palette defined (0 "#1f77b4", 1 "#ff7f0e", 2 "#2ca02c", 3 "#d62728", 4 "#9467bd", 5 "#8c564b", 6 "#e377c2", 7 "#17becf")
set palette maxcolors 8
set cbrange [-0.5:7.5]
set cbtics 0, 1, 7
set cblabel "rank"
set title "(b) owners, even cuts (P = 8, Morton)"
plot 'balance_map.dat' u 1:2:4 w image
set title "(c) owners, balanced cuts"
plot 'balance_map.dat' u 1:2:5 w image

set size noratio
set autoscale xy
unset cbtics
set key top right font "sans,10" opaque box lc rgb "#cccccc" samplen 2
set grid ytics lc rgb "#e8e8e8"
set title "(d) each rank's committed events (P = 8, Morton)"
set xlabel "rank"
set ylabel "events committed"
set xrange [-0.6:7.6]
set yrange [0:*]
set style fill solid 0.8 noborder
set boxwidth 0.38
plot 'balance_ranks.dat' u ($1 - 0.2):2 w boxes lc rgb 0x999999 t "even cuts", \
     '' u ($1 + 0.2):3 w boxes lc rgb 0xd62728 t "balanced cuts"

set title "(e) imbalance: largest rank load / mean"
set xlabel "ranks P"
set ylabel "largest / mean"
set logscale x 2
stats 'balance.dat' u 1 nooutput name "P"
set xrange [P_min / 1.3 : P_max * 1.3]
set xtics 2
set yrange [0.9:*]
set key center right
sel(k, b) = ($2 == k && $3 == b)
plot 'balance.dat' u 1:(sel(0, 0) ? $4 : NaN) w lp pt 4 lw 2 dt 2 lc rgb 0x1f77b4 t "rows, even", \
     '' u 1:(sel(0, 1) ? $4 : NaN) w lp pt 5 lw 2 lc rgb 0x1f77b4 t "rows, balanced", \
     '' u 1:(sel(1, 0) ? $4 : NaN) w lp pt 6 lw 2 dt 2 lc rgb 0xd62728 t "Morton, even", \
     '' u 1:(sel(1, 1) ? $4 : NaN) w lp pt 7 lw 2 lc rgb 0xd62728 t "Morton, balanced", \
     1 w l dt 3 lc rgb "#555555" notitle

set title "(f) speed-up in virtual time (cluster)"
set ylabel "S = T(1) / T(P)"
set yrange [0:*]
set key bottom right
plot 'balance.dat' u 1:(sel(0, 0) ? $10 : NaN) w lp pt 4 lw 2 dt 2 lc rgb 0x1f77b4 t "rows, even", \
     '' u 1:(sel(0, 1) ? $10 : NaN) w lp pt 5 lw 2 lc rgb 0x1f77b4 t "rows, balanced", \
     '' u 1:(sel(1, 0) ? $10 : NaN) w lp pt 6 lw 2 dt 2 lc rgb 0xd62728 t "Morton, even", \
     '' u 1:(sel(1, 1) ? $10 : NaN) w lp pt 7 lw 2 lc rgb 0xd62728 t "Morton, balanced"
unset multiplot
