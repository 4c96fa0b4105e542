# caption: The off-lattice reference of lesson 02, now from dynamics (the lesson's driver gr): the pair distribution g(r) of 201 hard disks at η = 0.4 — the state lesson 02's lattice walkers were measured against — from event-driven MD (line) and from lesson 02's Metropolis Monte Carlo in continuous space (points), bins of σ/50, ±1 error bar from 8 blocks. (a) The two methods sample the same ensemble and agree bin by bin ((b): their difference, within the error bars). (c) The contact value g(σ+), which sets the pressure Z = 1 + 2η g(σ+): extrapolated from the histograms (a line through ln g over [σ, 1.1σ]), and exactly from the MD collision impulses with no histogram at all; beside them (Z_ref − 1)/2η from the reference equation of state and Henderson's (1 − 7η/16)/(1 − η)². MD samples g(r) at fixed times: sampled right after an event, the pair that just collided sits at exactly σ and inflates the first bin by a few per cent.
set terminal pngcairo size 1400,500 font "sans,11"
set output 'gr.png'
set multiplot layout 1,3 title "Hard disks, N = 201, η = 0.4: event-driven MD against Monte Carlo"
set grid xtics ytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"

set title "(a) g(r)"
set xlabel "r, σ"
set ylabel "g(r)"
set xrange [0.8:3]
set yrange [0:2.5]
set key top right
plot 'gr.dat' u 1:4:5 w yerrorbars lc rgb 0x1f77b4 pt 7 ps 0.5 t "Monte Carlo (stage 02)", \
     '' u 1:2 w l lc rgb 0xd62728 lw 2 t "event-driven MD", \
     1 w l lc rgb "#888888" dt 2 notitle

set title "(b) MD − MC"
set ylabel "g_{MD}(r) − g_{MC}(r)"
set xrange [1:3]
set yrange [-0.1:0.1]
set key top right
plot 'gr.dat' u 1:($2 - $4):(sqrt($3**2 + $5**2)) w yerrorbars lc rgb 0x9467bd pt 7 ps 0.5 t "difference ±1 combined error bar", \
     0 w l lc rgb "black" notitle

set title "(c) the contact value g(σ+), five ways"
set ylabel "g(σ+)"
set xrange [-0.6:4.6]
set yrange [*:*]
set xtics ("MD\nimpulses" 0, "MD\nhistogram" 1, "MC\nhistogram" 2, "from\nZ_{ref}" 3, "Hender-\nson" 4) font "sans,9"
set xlabel " "
set bmargin 5
unset key
plot 'gr_contact.dat' u 1:2:3 w yerrorbars lc rgb 0xd62728 pt 7 ps 1.5 lw 2
unset multiplot
