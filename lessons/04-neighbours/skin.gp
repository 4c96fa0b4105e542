# caption: The trade (DESIGN §7), measured by skin.c on 4400 hard disks (R = 12, packing 0.474). Left: CPU ns per atom-step against the skin Δr at the safe refresh interval floor((Δr + 1)/2) sweeps — thin skins refresh often, thick ones test more candidates at every step (and FNL pays k² per particle at each refresh); each driver has its own best skin. Right: a work–precision diagram for refreshing later than is safe: FNL and CL at Δr = 4 (safe: 2 sweeps) and Δr = 8 (safe: 4), refreshed every 1 … 24 sweeps (labels); the vertical axis counts, before every refresh, the pairs closer than r_c that the driver cannot see, per 1000 disks. Points on the bottom line missed nothing. Past the safe interval a few per cent of time are bought with pairs walking through each other.
set terminal pngcairo size 1300,540 font "sans,11"
set output 'skin.png'
set datafile missing "nan"
set multiplot layout 1,2 title "Skin against refresh interval against cost against missed pairs"
set grid xtics ytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"
rgb(d) = d == 0 ? 0xd62728 : d == 1 ? 0x1f77b4 : 0x2ca02c
name(d) = d == 0 ? "NL" : d == 1 ? "FNL" : "CL"
pick(d, v) = ($3 == d) ? v : NaN

set title "(a) cost at the safe refresh interval"
set logscale xy
set xlabel "skin Δr  [lattice units]"
set ylabel "CPU ns per atom-step"
set key top right
plot for [d = 0:2] 'skin_cost.dat' u 1:(pick(d, $4)) w lp lc rgb rgb(d) pt 7 ps 1.1 lw 2 t name(d)

set title "(b) refreshing later: cost against missed pairs"
set xlabel "CPU ns per atom-step"
set ylabel "pairs missed per refresh per 1000 disks (+0.001)"
set logscale xy
set key top right
sel(d) = ($4 == d) ? 1 : 0
plot 'skin_trade.dat' u (sel(1) ? $5 : NaN):($6 + 1e-3) w lp lc rgb 0x1f77b4 pt 7 lw 2 t "FNL, Δr = 32 (safe: 16 sweeps)", \
     '' u (sel(2) ? $5 : NaN):($6 + 1e-3) w lp lc rgb 0x2ca02c pt 5 lw 2 t "CL, Δr = 7 (safe: 3 sweeps)", \
     '' u 5:($6 + 1e-3):(sprintf("%d", $2)) w labels offset 0.9,0.6 font "sans,8" notitle
unset multiplot
