# caption: The trade of cost against accuracy, measured by trade.c on hard spheres at η = 0.3 (mean free time ≈ 0.1), all runs from the same melted start, the same simulated time. Left: a work–precision diagram — the relative error of the pressure Z = βP/ρ from the collision impulses against Z_ref = 3.9840 (Padé-resummed virial series), against CPU seconds per unit of simulated time. The time-stepped scheme (move by v·dt, find the overlapping pairs with the cell list of stage 04, bounce them along the line of centres, push them apart; labels: dt) bounces every pair late, at a separation below σ: its pressure is low by an error proportional to dt, and each halving of the error doubles the cost. The event-driven run (red square) lands on Z_ref within its statistical error bar (its error is noise, not bias) for the CPU time of a time step of 0.02–0.05, where the time-stepped pressure is 6–16 % low; to get within 0.5 % the time-stepped scheme needs dt ≈ 0.001 and some 25 times the CPU time — and its error is a bias, which no amount of averaging removes. Right: how deep the spheres overlap before the time-stepped scheme notices (mean and largest over the run) and how many overlapping pairs it finds per particle per step — both ∝ dt; the event-driven spheres never overlap (largest overlap at the block ends: exactly 0, drawn at the 10⁻¹⁶ round-off floor).
set terminal pngcairo size 1300,560 font "sans,11"
set output 'trade.png'
set multiplot layout 1,2 title "Event-driven against time-stepped hard spheres, η = 0.3"
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"
set logscale xy
set format y "10^{%T}"

set title "(a) pressure error against cost"
set xlabel "CPU seconds per unit of simulated time"
set ylabel "relative error |Z − Z_{ref}| / Z_{ref}"
set key top right
set yrange [1e-4:1]
plot 'trade.dat' u 6:4:5 w yerrorlines lc rgb 0x1f77b4 pt 7 lw 2 t "time-stepped (dt labelled)", \
     '' u 6:4:(sprintf("%g", $1)) w labels offset 1.2,0.7 font "sans,9" notitle, \
     'trade_ed.dat' u 5:($3 > 1e-4 ? $3 : 1e-4):4 w yerrorbars lc rgb 0xd62728 pt 5 ps 1.8 lw 2 t "event-driven (±1 error bar)"

set title "(b) overlaps of the time-stepped spheres against dt"
set xlabel "time step dt"
set ylabel "overlap depth 1 − r_{ij}, σ;  pairs found per particle per step"
set key bottom right
set yrange [1e-17:2]
set format x "%g"
plot 'trade.dat' u 1:8 w lp lc rgb 0x1f77b4 pt 7 lw 2 t "mean depth", \
     '' u 1:9 w lp lc rgb 0x2ca02c pt 5 lw 2 t "largest depth", \
     '' u 1:7 w lp lc rgb 0x9467bd pt 9 lw 2 t "overlapping pairs per particle per step", \
     'trade_ed.dat' u (1e-3):($6 > 1e-16 ? $6 : 1e-16) w p lc rgb 0xd62728 pt 5 ps 1.8 t "event-driven largest overlap (round-off floor)", \
     1e-16 w l dt 3 lc rgb "#888888" notitle
unset multiplot
