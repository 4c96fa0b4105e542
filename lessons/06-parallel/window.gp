# caption: The trade (the lesson's driver window): how long a rank may run ahead before the ranks meet at a cut. 2D disks at η = 0.3, P = 8 ranks along the Morton curve, on the cluster of the virtual-time model (1 µs an event, 0.5 µs a message at each end, 2 µs latency). The first window holds about c events per rank (c·P/R in time, R the serial event rate) and adapts — an eighth longer after a commit, halved after a rollback — within 1/64 and 64 times that. The result is exact at every c (each run commits the serial events and ends with the serial records, bit for bit): what c trades is speed against memory and wasted work. (a) Virtual time: short windows pay a cut (reductions of one latency each) for a few events; long ones are rolled back more often. Dotted: one rank's time, and that over 8 (perfect speed-up). (b) What a long window costs: the fraction of windows rolled back, the events processed that were not committed (1 − efficiency), and the most state one rank saved in one window (right axis, kB; only the particles a window touched are saved, at most some 750 records of 128 bytes, against 64 bytes for each of the N particles in a full copy). From c ≈ 2 on little changes: the window no longer reaches its cap, the rollbacks set its length, and about one window in eight is rolled back — the equilibrium of slow growth after success and halving after failure. (c) The events a rank carries out per turn before it reads its messages, at the best c: reading them late lets a rank run further past news from its neighbours. 64 events per turn before looking, instead of 1, took 0.028 s instead of 0.022 s, with 88 rollbacks instead of 25. At c = 1/64 the run needs 13108 windows and commits 99.3 % of the events it processes.
set terminal pngcairo size 1400,500 font "sans,11"
set output 'window.png'
stats 'window.dat' u 13 nooutput name "T1"
set multiplot layout 1,3 title "The window: speed against memory and wasted work (the result is exact at every setting)"
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key font "sans,10" opaque box lc rgb "#cccccc" samplen 2
set logscale x 2
set format x "2^{%L}"
set xlabel "c: events per rank in the first window"

set title "(a) virtual time of the run"
set logscale y
set ylabel "virtual seconds"
set key top center
plot 'window.dat' u 1:3 w lp pt 7 lw 2 lc rgb 0xd62728 t "P = 8, work 1 event per turn", \
     T1_mean w l dt 3 lc rgb "#555555" t "one rank", \
     T1_mean / 8 w l dt 3 lc rgb "#1f77b4" t "one rank / 8"

set title "(b) what long windows cost"
unset logscale y
set ylabel "fraction"
set y2label "saved state, kB"
set y2tics
set ytics nomirror
# both axes leave the top fifth to the key
stats 'window.dat' u ($9 / 1024) nooutput name "SAVED"
stats 'window.dat' u (1 - $4) nooutput name "LOST"
set yrange [0:(LOST_max > 0.05 ? LOST_max : 0.05) * 1.4]
set y2range [0:SAVED_max * 1.4]
set key top left Left reverse
plot 'window.dat' u 1:5 w lp pt 5 lw 2 lc rgb 0x1f77b4 t "windows rolled back", \
     '' u 1:(1 - $4) w lp pt 7 lw 2 lc rgb 0xd62728 t "events not committed (1 − efficiency)", \
     '' u 1:($9 / 1024) axes x1y2 w lp pt 9 lw 2 lc rgb 0x2ca02c t "saved state (right axis)"

set title "(c) events per turn between looks at the messages"
unset y2tics
unset y2label
set ytics mirror
set logscale x 4
set format x "%g"
set xlabel "events carried out per turn"
set ylabel "virtual seconds"
set logscale y
set autoscale y
set key top left
plot 'window_work.dat' u 2:3 w lp pt 7 lw 2 lc rgb 0xd62728 t "virtual time", \
     '' u 2:3:(sprintf("%.0f rollbacks", $7)) w labels offset 0,1 font "sans,9" notitle
unset multiplot
