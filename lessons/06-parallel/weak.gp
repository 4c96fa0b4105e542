# caption: Weak scaling (the lesson's driver weak): the system grows with the machine, 2500 disks (2D, η = 0.3) or 1500 spheres (3D, η = 0.25) per rank, along the Morton curve, on the cluster of the virtual-time model (1 µs an event, 0.5 µs a message at each end, 2 µs latency), each run bit for bit the serial run. (a) The scaled speed-up S_w = P·T(1)/T(P), T(P) the virtual time of P ranks on N = n·P particles for the same simulated time: P would mean the larger machine keeps pace. Dotted: S_w = P; dashed grey: Miller and Luding's weak scaling, P^0.50 (their fig. 8), drawn through our S_w(2); the legend gives our fitted exponent (P ≥ 2). In 3D two ranks are slower than one: a 3D domain of 1500 spheres is mostly border, and every border event costs messages. (b) Memory per rank (as their fig. 9): what the stub's ranks hold (records for all N particles, 64 bytes each, growing with P), against a lean rank that keeps only its own particles, its ghosts and the state it saves in one window (counted from the domains and the measured saved state; the stub builds no such rank). The lean rank is flat from P = 2 on (at P = 1 the one window runs to the re-base interval and saves every particle it touches): weak scaling costs no memory per rank once a rank stops holding the whole system.
set terminal pngcairo size 1300,520 font "sans,11"
set output 'weak.png'
set multiplot layout 1,2 title "Optimistic parallel event-driven hard particles: weak scaling in virtual time"
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key top left font "sans,10" opaque box lc rgb "#cccccc" samplen 2
stats 'weak.dat' u 2 nooutput name "PP"
stats 'weak.dat' u (($1 == 2 && $2 == 2) ? $6 : NaN) nooutput name "W2"
stats 'weak.dat' u (($1 == 3 && $2 == 2) ? $6 : NaN) nooutput name "W3"
fit2(x) = b2 + a2 * x
fit3(x) = b3 + a3 * x
set fit quiet logfile '/dev/null'
fit fit2(x) 'weak.dat' u (($1 == 2 && $2 >= 2) ? log($2) : NaN):(log($6)) via a2, b2
fit fit3(x) 'weak.dat' u (($1 == 3 && $2 >= 2) ? log($2) : NaN):(log($6)) via a3, b3
set logscale xy 2
set xrange [0.8:PP_max * 1.25]
set xlabel "ranks P (N = n·P)"
set title "(a) scaled speed-up"
set ylabel "S_w = P T(1) / T(P)"
set yrange [0.4:PP_max * 1.25]
set format y "%g"
plot x w l dt 3 lc rgb "#888888" t "S_w = P", \
     W2_mean * (x / 2)**0.5 w l dt 2 lw 1.5 lc rgb "#999999" t "Miller and Luding: P^{0.50}", \
     'weak.dat' u 2:(($1 == 2) ? $6 : NaN) w lp pt 7 lw 2 lc rgb 0xd62728 t sprintf("2D disks, 2500 per rank (P^{%.2f})", a2), \
     '' u 2:(($1 == 3) ? $6 : NaN) w lp pt 5 lw 2 lc rgb 0x1f77b4 t sprintf("3D spheres, 1500 per rank (P^{%.2f})", a3)
set title "(b) memory per rank"
set ylabel "kB per rank"
set yrange [*:*]
set key top left
plot 'weak.dat' u 2:(($1 == 2) ? $12 / 1024 : NaN) w lp pt 6 dt 2 lw 2 lc rgb 0xd62728 t "2D, stub rank (all N records)", \
     '' u 2:(($1 == 2) ? $11 / 1024 : NaN) w lp pt 7 lw 2 lc rgb 0xd62728 t "2D, lean rank (own + ghosts + saved)", \
     '' u 2:(($1 == 3) ? $12 / 1024 : NaN) w lp pt 4 dt 2 lw 2 lc rgb 0x1f77b4 t "3D, stub rank", \
     '' u 2:(($1 == 3) ? $11 / 1024 : NaN) w lp pt 5 lw 2 lc rgb 0x1f77b4 t "3D, lean rank"
unset multiplot
