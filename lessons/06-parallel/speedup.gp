# caption: Speed-up at a fixed system size (strong scaling; the lesson's driver speedup), in the virtual time of the stub: the cluster charges 1 µs per event carried out (rolled back ones included), 0.5 µs per message at each end and 2 µs of latency per message and per reduction; the ideal network charges the events only. S(P) = T(1)/T(P), T(1) one rank (the serial engine's cost, to 0.01 %). (a) 2D disks at η = 0.3; (b) 3D spheres at η = 0.25 (the volume fractions of Miller and Luding's figs. 6 and 7; their N were 5·10⁵ and 2·10⁶, the full size here 10⁵ and 5·10⁴). Dotted: S = P; dashed grey: the exponents Miller and Luding measured on their cluster (0.49 in 2D, 0.45 in 3D), drawn through our S(2); the legend gives our fitted exponent (P ≥ 2). For every P the fastest of the first windows c = 1/64 … 4 events per rank is used. (c) The efficiency, committed over processed events: the part of the work that was not rolled back. (d) The same against the share of the cells that are BORDER cells (their changes must be sent, and late news there forces a rollback): the efficiency falls as the border grows, and the 3D domains of this N have several times the border share of the 2D ones at the same P — 30 % against 4 % at P = 8. (e) The messages each committed event costs: ten times more in 3D, and on the cluster each costs half an event's CPU at either end, which is most of the gap between the cluster and the ideal network in (b). (f) The best first window shrinks as P grows: more neighbours, more late news. In 2D it goes from c = 4 at P = 2 to c = 1/4 at P = 32. The costs: stage 05 does about 1.8 million events a second on one core and a rank does more per event; 0.5 µs is a small MPI message's software cost, 2 µs InfiniBand's latency. The exponents are fitted with a least-squares line on log–log; the paper's systems were 5 and 40 times larger than ours.
set terminal pngcairo size 1650,1000 font "sans,11"
set output 'speedup.png'
set multiplot layout 2,3 title "Optimistic parallel event-driven hard particles: speed-up in virtual time"
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key top left font "sans,10" opaque box lc rgb "#cccccc" samplen 2
do for [d = 2:3] { do for [s = 0:2] {
	stats 'speedup_fit.dat' u (($1 == d && $2 == s) ? $3 : NaN) nooutput name sprintf("A%d%d", d, s)
	stats 'speedup_fit.dat' u (($1 == d && $2 == s) ? $5 : NaN) nooutput name sprintf("B%d%d", d, s)
} }
stats 'speedup.dat' u 3 nooutput name "PP"
stats 'speedup_fit.dat' u (($1 == 2) ? $7 : NaN) nooutput name "N2"
stats 'speedup_fit.dat' u (($1 == 3) ? $7 : NaN) nooutput name "N3"
sel(d, s) = ($1 == d && $2 == s)
set logscale xy 2
set xrange [0.8:PP_max * 1.25]
set xlabel "ranks P"
set ylabel "speed-up S = T(1) / T(P)"
set format y "%g"

set title sprintf("(a) 2D disks, N = %g, η = 0.3", N2_mean)
set yrange [0.8:PP_max * 1.25]
plot x w l dt 3 lc rgb "#888888" t "S = P", \
     B21_mean * (x / 2)**0.49 w l dt 2 lw 1.5 lc rgb "#999999" t "Miller and Luding 2D: P^{0.49}", \
     'speedup.dat' u 3:(sel(2, 0) ? $6 : NaN) w lp pt 5 lw 2 lc rgb 0x1f77b4 t sprintf("rows, cluster (P^{%.2f})", A20_mean), \
     '' u 3:(sel(2, 1) ? $6 : NaN) w lp pt 7 lw 2 lc rgb 0xd62728 t sprintf("Morton, cluster (P^{%.2f})", A21_mean), \
     '' u 3:(sel(2, 2) ? $6 : NaN) w lp pt 6 lw 2 dt 2 lc rgb 0xd62728 t sprintf("Morton, ideal network (P^{%.2f})", A22_mean)

set title sprintf("(b) 3D spheres, N = %g, η = 0.25", N3_mean)
set yrange [0.25:PP_max * 1.25]
plot x w l dt 3 lc rgb "#888888" t "S = P", \
     B31_mean * (x / 2)**0.45 w l dt 2 lw 1.5 lc rgb "#999999" t "Miller and Luding 3D: P^{0.45}", \
     'speedup.dat' u 3:(sel(3, 0) ? $6 : NaN) w lp pt 5 lw 2 lc rgb 0x1f77b4 t sprintf("rows, cluster (P^{%.2f})", A30_mean), \
     '' u 3:(sel(3, 1) ? $6 : NaN) w lp pt 7 lw 2 lc rgb 0xd62728 t sprintf("Morton, cluster (P^{%.2f})", A31_mean), \
     '' u 3:(sel(3, 2) ? $6 : NaN) w lp pt 6 lw 2 dt 2 lc rgb 0xd62728 t sprintf("Morton, ideal network (P^{%.2f})", A32_mean)

set title "(c) efficiency: committed / processed events"
unset logscale y
set logscale x 2
set yrange [0:1.05]
set ylabel "committed / processed"
set key bottom left
plot 'speedup.dat' u 3:(sel(2, 0) ? $7 : NaN) w lp pt 5 lw 2 lc rgb 0x1f77b4 t "2D rows", \
     '' u 3:(sel(2, 1) ? $7 : NaN) w lp pt 7 lw 2 lc rgb 0xd62728 t "2D Morton", \
     '' u 3:(sel(3, 0) ? $7 : NaN) w lp pt 4 lw 2 dt 2 lc rgb 0x1f77b4 t "3D rows", \
     '' u 3:(sel(3, 1) ? $7 : NaN) w lp pt 6 lw 2 dt 2 lc rgb 0xd62728 t "3D Morton"

set title "(d) efficiency against the border share of the cells (cluster)"
set logscale x 10
set xrange [*:*]
set format x "%g"
set xlabel "BORDER cells / all cells (labels: P)"
set key bottom left
plot 'speedup.dat' u 17:(sel(2, 0) ? $7 : NaN) w p pt 5 ps 1.3 lc rgb 0x1f77b4 t "2D rows", \
     '' u 17:(sel(2, 1) ? $7 : NaN) w p pt 7 ps 1.3 lc rgb 0xd62728 t "2D Morton", \
     '' u 17:(sel(3, 0) ? $7 : NaN) w p pt 4 ps 1.3 lw 2 lc rgb 0x1f77b4 t "3D rows", \
     '' u 17:(sel(3, 1) ? $7 : NaN) w p pt 6 ps 1.3 lw 2 lc rgb 0xd62728 t "3D Morton", \
     '' u 17:(($1 == 2 && $2 < 2 && $3 > 1) ? $7 : NaN):(sprintf("%d", $3)) w labels offset 0,0.9 font "sans,8" notitle, \
     '' u 17:(($1 == 3 && $2 < 2 && $3 > 1) ? $7 : NaN):(sprintf("%d", $3)) w labels offset 0,-0.9 font "sans,8" notitle

set title "(e) messages sent per committed event (cluster)"
set logscale x 2
set xrange [0.8:PP_max * 1.25]
set xlabel "ranks P"
set logscale y 10
set yrange [0.005:*]
set format y "%g"
set ylabel "messages / committed event"
set key top left
plot 'speedup.dat' u 3:(sel(2, 0) && $3 > 1 ? $12 : NaN) w lp pt 5 lw 2 lc rgb 0x1f77b4 t "2D rows", \
     '' u 3:(sel(2, 1) && $3 > 1 ? $12 : NaN) w lp pt 7 lw 2 lc rgb 0xd62728 t "2D Morton", \
     '' u 3:(sel(3, 0) && $3 > 1 ? $12 : NaN) w lp pt 4 lw 2 dt 2 lc rgb 0x1f77b4 t "3D rows", \
     '' u 3:(sel(3, 1) && $3 > 1 ? $12 : NaN) w lp pt 6 lw 2 dt 2 lc rgb 0xd62728 t "3D Morton"

set title "(f) the best first window (Morton, cluster)"
set ylabel "c: events per rank in the first window"
set yrange [0.01:10]
set logscale y 2
set key top right
plot 'speedup.dat' u 3:(sel(2, 1) && $3 > 1 ? $4 : NaN) w lp pt 7 lw 2 lc rgb 0xd62728 t "2D", \
     '' u 3:(sel(3, 1) && $3 > 1 ? $4 : NaN) w lp pt 6 lw 2 dt 2 lc rgb 0xd62728 t "3D"
unset multiplot
