# caption: The trade of cost against accuracy, measured by the lesson's driver skin on 4400 hard disks (R = 12, σ = 24, packing 0.474, box 2048), CPU ns per atom-step on a shared 2-core AMD EPYC. Left: the cost against the skin Δr at the safe refresh interval floor(Δr/2) sweeps. NL pays for its all-pairs rebuild and wants a thick skin (9.3 µs at Δr = 2, 0.28 µs at 64, still falling); FNL is fast and wrong below Δr = 32 (crosses: its lists are too short to find newcomers, see fnl_loss) and pays k² per refresh above (83 ns at 32, 146 at 64); CL costs 80–84 ns while r_l ≤ 32 keeps its cells at 32, and doubles each time the cells jump to the next power of two (Δr = 8, 48). Right: a work–precision diagram for refreshing later than is safe — FNL at Δr = 32 (safe: 16 sweeps) and CL at Δr = 7 (safe: 3), refreshed every N sweeps (labels); up: the pairs closer than r_c the driver could not see, counted before every refresh, per 1000 disks (points on the line labelled 0 missed nothing). The safe interval is a worst case: FNL stays clean up to 64 sweeps, 43 % faster; CL gains little (its refresh is a cheap re-binning); from 128 sweeps on it misses pairs, and disks walk through each other. These are the full size's figures (make lesson STAGE=04); at demo size NL costs 10 µs at Δr = 2 and 0.40 µs at 64, FNL 80 ns at 32 and 122 at 64, CL 76–80 ns, and FNL refreshed every 64 sweeps is 37 % faster.
set terminal pngcairo size 1300,540 font "sans,11"
set output 'skin.png'
set datafile missing "nan"
set multiplot layout 1,2 title "Skin against refresh interval against cost against missed pairs"
set grid xtics ytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"
# (b): a log axis has no 0: a run that missed nothing is drawn on the line labelled 0
zero = 1e-3
y(v) = v > 0 ? v : zero
rgb(d) = d == 0 ? 0xd62728 : d == 1 ? 0x1f77b4 : 0x2ca02c
name(d) = d == 0 ? "NL" : d == 1 ? "FNL" : "CL"
pick(d, v) = ($3 == d) ? v : NaN

set title "(a) cost at the safe refresh interval"
set logscale xy
set xlabel "skin Δr  [lattice units]"
set ylabel "CPU ns per atom-step"
set key top right
plot for [d = 0:2] 'skin_cost.dat' u 1:(pick(d, $4)) w lp lc rgb rgb(d) pt 7 ps 1.1 lw 2 t name(d), \
     'skin_cost.dat' u 1:(($6 > 0 || $7 > 0) ? $4 : NaN) w p lc rgb "black" pt 2 ps 2 lw 2 t "missed pairs (FNL: lists too short)"

set title "(b) refreshing later: cost against missed pairs"
set autoscale xfix
set offsets graph 0.06, graph 0.08, 0, 0
set xtics (30, 40, 50, 60, 80, 100, 150, 200)
set xlabel "CPU ns per atom-step"
set ylabel "pairs missed per refresh per 1000 disks"
set logscale xy
set yrange [5e-4:2000]
set ytics ("0" zero)
set ytics add (1e-2, 0.1, 1, 10, 100, 1000)
set key top right
sel(d) = ($4 == d) ? 1 : 0
plot 'skin_trade.dat' u (sel(1) ? $5 : NaN):(y($6)) w lp lc rgb 0x1f77b4 pt 7 lw 2 t "FNL, Δr = 32 (safe: 16 sweeps)", \
     '' u (sel(2) ? $5 : NaN):(y($6)) w lp lc rgb 0x2ca02c pt 5 lw 2 t "CL, Δr = 7 (safe: 3 sweeps)", \
     '' u 5:(y($6)):(sprintf("%d", $2)) w labels offset 0.9,0.6 font "sans,8" notitle
unset multiplot
