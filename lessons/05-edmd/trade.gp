# caption: The trade of cost against accuracy, measured by the lesson's driver trade on hard spheres at η = 0.3 (mean free time ≈ 0.1 τ, τ = σ√(m/kT)), all runs from the same melted start for the same simulated time. (a) A work–precision diagram: the relative error of the pressure Z = βP/ρ from the collision impulses against Z_ref = 3.9840 (the Padé-resummed virial series), against the CPU seconds per unit of simulated time, ±1 error bar. An error less than two error bars from zero is noise: it is drawn as an open marker at its upper bound, |error| + 2 error bars, with an arrow down. The time-stepped scheme (move by v·dt, find the overlapping pairs with the cell list of lesson 04, bounce them along the line of centres, push them apart; labels: dt) bounces every pair late, at a separation below σ: its pressure is low by an error proportional to dt (fitted order 1.0–1.1), and each halving of the error doubles the cost. The event-driven run shows no bias — its error is noise — for the CPU time of a time step between 0.02 and 0.05, where the time-stepped pressure is 6.5–16 % low. At full size (make lesson STAGE=05: N = 4000, on 2 cores) the time-stepped pressure is still 0.5 % low at dt = 0.001, for about 20 times the event-driven CPU time; at demo size (N = 1000, half the run) the noise hides its bias from dt = 0.002 on. A bias does not average away. (b) How deep the spheres overlap before the time-stepped scheme notices (mean and largest over the run) and how many overlapping pairs it finds per particle per step — both ∝ dt; the event-driven spheres never overlap (the largest overlap at the block ends is exactly 0).
set terminal pngcairo size 1300,560 font "sans,11"
set output 'trade.png'
set multiplot layout 1,2 title "Event-driven against time-stepped hard spheres, η = 0.3"
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"
set logscale xy
set format y "10^{%T}"

# A relative error that is not two error bars away from 0 is noise: it is drawn as an
# upper bound, |error| + 2 error bars, with an arrow down, and not joined to the line.
bias(rel, err) = rel > 2 * err ? rel : NaN
bound(rel, err) = rel > 2 * err ? NaN : rel + 2 * err
shown(rel, err) = rel > 2 * err ? rel : rel + 2 * err
stats 'trade.dat' u ($4 > 2 * $5 ? 0 : 1) nooutput name "TS"
stats 'trade_ed.dat' u ($3 > 2 * $4 ? 1 : 0) nooutput name "ED"

set title "(a) pressure error against cost"
set xlabel "CPU seconds per unit of simulated time τ"
set ylabel "relative error |Z − Z_{ref}| / Z_{ref}"
set key top right
set yrange [1e-3:1]
set offsets graph 0.04, graph 0.08, 0, 0
plot 'trade.dat' u 6:(bias($4, $5)):5 w yerrorlines lc rgb 0x1f77b4 pt 7 lw 2 t "time-stepped (labels: dt / τ)", \
     '' u 6:(bound($4, $5)) w p lc rgb 0x1f77b4 pt 6 ps 1.5 lw 2 t (TS_sum > 0 ? "time-stepped, within noise: upper bound" : ""), \
     '' u 6:(bound($4, $5)):(0):(-0.45 * bound($4, $5)) w vectors head filled size screen 0.008,25 lc rgb 0x1f77b4 lw 1.5 notitle, \
     '' u 6:(shown($4, $5)):(sprintf("%g", $1)) w labels offset 1.6,0.8 font "sans,9" notitle, \
     'trade_ed.dat' u 5:(bias($3, $4)):4 w yerrorbars lc rgb 0xd62728 pt 5 ps 1.8 lw 2 t (ED_sum > 0 ? "event-driven (±1 error bar)" : ""), \
     '' u 5:(bound($3, $4)) w p lc rgb 0xd62728 pt 4 ps 1.8 lw 2 t (ED_sum > 0 ? "" : "event-driven: upper bound (no bias seen)"), \
     '' u 5:(bound($3, $4)):(0):(-0.45 * bound($3, $4)) w vectors head filled size screen 0.008,25 lc rgb 0xd62728 lw 1.5 notitle

set title "(b) overlaps of the time-stepped spheres against dt"
set xlabel "time step dt / τ"
set ylabel "overlap depth 1 − r_{ij} / σ;  overlapping pairs per particle per step"
set key bottom right
set autoscale y
set offsets 0, 0, 0, 0
set xrange [7e-4:0.15]
set format x "%g"
set label 1 "event-driven: no overlap at all\n(largest overlap at the block ends: exactly 0)" at graph 0.04, graph 0.93 font "sans,10" tc rgb 0xd62728
plot 'trade.dat' u 1:8 w lp lc rgb 0x1f77b4 pt 7 lw 2 t "mean depth", \
     '' u 1:9 w lp lc rgb 0x2ca02c pt 5 lw 2 t "largest depth", \
     '' u 1:7 w lp lc rgb 0x9467bd pt 9 lw 2 t "overlapping pairs per particle per step"
unset multiplot
