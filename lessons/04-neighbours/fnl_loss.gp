# caption: What the fast refresh can lose, measured by the lesson's driver fnl_loss. Left: 4400 hard disks (R = 12, σ = 24, packing 0.474, box 2048) walked by the FNL driver at skins Δr = 4 … 48, refreshed at the safe interval floor(Δr/2) sweeps, with one copy of the lists rewritten in place (red) and with source and target copies (blue), from the same start with the same random numbers. Before every refresh an audit counts the pairs closer than r_c = σ + 1 that the lists do not hold (per refresh per 1000 disks; points on the bottom line missed nothing). The refresh finds newcomers only through common neighbours: with short lists (grey, right axis: entries per disk) it goes blind, two copies or not; from Δr = 32 (r_l ≈ 2.4σ) on it misses nothing (at 24 it still misses 0.07 per refresh per 1000 disks). The one-copy loss of thesis fig. 2.7 is real but small beside it. Right: two copies at Δr = 32 against the packing; NL, rebuilt from all pairs with the same skin, misses nothing (crosses). In a thinner fluid the lists are shorter and the bet is lost now and then.
set terminal pngcairo size 1300,520 font "sans,11"
set output 'fnl_loss.png'
set multiplot layout 1,2 title "The fast neighbour-list refresh: a bet on common neighbours"
set grid xtics ytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"
# a log axis has no 0: a run that missed nothing is drawn on the line labelled 0, a
# decade below the axis proper, which starts at 10^-3
zero = 1e-4
y(v) = v > 0 ? v : zero
set format y "10^{%L}"

set title "(a) packing 0.474: missed pairs against the skin"
set xlabel "skin Δr  [lattice units]"
set ylabel "pairs missed per refresh per 1000 disks"
set logscale y
set yrange [5e-5:2000]
set ytics ("0" zero)
set ytics add (1e-3, 1e-2, 0.1, 1, 10, 100, 1000)
set y2label "list entries per disk"
set y2range [0:20]
set y2tics
set ytics nomirror
set key top right
plot 'fnl_skin.dat' u 1:(y($4)) w lp lc rgb 0xd62728 pt 7 ps 1.2 lw 2 t "one copy (rows rewritten in place)", \
     '' u 1:(y($5)) w lp lc rgb 0x1f77b4 pt 5 ps 1 lw 2 t "two copies (source and target)", \
     '' u 1:3 axes x1y2 w l lc rgb "#999999" dt 2 lw 2 t "list entries per disk (right)"

set title "(b) two copies at Δr = 32 against the packing"
unset y2label
unset y2tics
set ytics mirror
set logscale x
set xlabel "packing fraction"
set ylabel "pairs missed per refresh per 1000 disks"
set xrange [0.008:0.6]
set yrange [5e-5:100]
set key top right
plot 'fnl_density.dat' u 1:(y($3)) w lp lc rgb 0x1f77b4 pt 5 ps 1.2 lw 2 t "FNL, two copies", \
     '' u 1:(y($4)) w p lc rgb 0xd62728 pt 2 ps 1.6 lw 2 t "NL (all pairs)"
unset multiplot
