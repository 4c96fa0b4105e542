# caption: A load that moves (the lesson's driver cooling): 10000 disks at η = 0.3 with restitution 0.7 in a periodic box cool from the lattice start (Haff's law) and gather into dense clusters, and the events gather with them. P = 8 ranks along the Morton curve on the cluster of the virtual-time model; each point is a slice of the run holding one sixteenth of the committed events, drawn at the time the slice ends. The imbalance is the busiest rank's committed events in the slice over the mean (1: every rank does the same). With the cuts fixed (even), the ranks whose domains hold a cluster do most of the work, three to six times the mean once the clusters have formed. Moving the cuts at a cut every 64 windows when the busiest rank gains 25 % keeps every slice within 15 % of even, and both runs are the serial run bit for bit — yet the moved run takes longer in virtual time (printed by the driver): the new cuts run through the clusters, where the events are, and their borders cost more rollbacks than the balance saves.
set terminal pngcairo size 900,560 font "sans,11"
set output 'cooling.png'
set title "Load balance of a cooling, clustering gas: 8 ranks, fixed and moving cuts"
set grid xtics ytics lc rgb "#e8e8e8"
set key top left opaque box lc rgb "#cccccc"
set xlabel "simulated time at the end of the slice (τ)"
set ylabel "busiest rank's events / mean"
stats 'cooling.dat' u 3 nooutput name "F"
set yrange [0.9:F_max * 1.15]
plot 1 w l dt 3 lc rgb "#888888" t "even load", \
     'cooling.dat' u 2:3 w lp pt 7 lw 2 lc rgb 0xd62728 t "cuts fixed (even)", \
     '' u 4:5 w lp pt 5 lw 2 lc rgb 0x1f77b4 t "cuts moved during the run"
