# caption: The parallel run is the serial run (the lesson's driver equal). Each point is one run of P ranks of the optimistic engine (2D disks, 3D spheres; a periodic elastic gas, a gas falling onto a floor under gravity, a cooling granular gas in a closed box; domains along rows or the Morton curve; ranks interleaved at random with messages held back 0–3 turns, or in virtual time), all from the lattice start and audited at every cut. Left: the events processed per event committed — the work the run threw away in rollbacks comes on top of the 1 that counts; right: how many windows were rolled back or replaced by a conservative step. The histories differ from run to run by factors of ten, yet every run committed exactly the serial run's events (the same count of each kind, the same log record by record) and ended with every particle record — position, velocity, its own clock, its collision count, its cell: all 64 bytes — equal to the serial run's (memcmp). One rank (P = 1) never rolls back. The audit at every cut checks that each particle is owned once and every ghost equals its owner's record. The 3D periodic gas on 8 ranks along rows in virtual time processed 2.2 events for each one it committed; the random runs process at least twice as many, since the rollback check runs every window again. The elastic gases conserve energy to 5·10⁻¹⁵; the cooling ones (restitution 0.8) lose 23 % (2D) and 47 % (3D) of it.
set terminal pngcairo size 1300,540 font "sans,11"
set output 'equal.png'
stats 'equal.dat' u 1 nooutput name "R"
stats 'equal.dat' u ($15 * $16) nooutput name "OK"
set multiplot layout 1,2 title sprintf("%d parallel runs, %d of them identical to the serial run bit for bit", R_records, OK_sum)
set grid ytics lc rgb "#e8e8e8"
set key top left font "sans,10" opaque box lc rgb "#cccccc" samplen 1
set xlabel "run (grouped: 2D then 3D; periodic, gravity, box; P = 1, 2, 3, 4, 8)"
set xrange [0:R_max + 1]
# one colour per P: P = 1, 2, 3, 4, 8 -> 0 .. 4
idx(P) = P == 8 ? 4 : P - 1
set palette defined (0 "#1f77b4", 1 "#2ca02c", 2 "#ff7f0e", 3 "#d62728", 4 "#9467bd")
set palette maxcolors 5
set cbrange [-0.5:4.5]
set cblabel "ranks P"
set cbtics ("1" 0, "2" 1, "3" 2, "4" 3, "8" 4)
set arrow 1 from R_max / 2 + 0.5, graph 0 to R_max / 2 + 0.5, graph 1 nohead lc rgb "#888888" dt 2
set label 1 "2D ←" at graph 0.49, graph 0.06 right
set label 2 "→ 3D" at graph 0.51, graph 0.06 left

set title "(a) events processed per event committed"
set ylabel "processed / committed"
set yrange [0.9:*]
plot 'equal.dat' u 1:($6 == 0 ? $9 / $7 : NaN):(idx($4)) w p pt 7 ps 1 lc palette t "random interleaving", \
     '' u 1:($6 == 1 ? $9 / $7 : NaN):(idx($4)) w p pt 5 ps 0.9 lc palette t "virtual time"

set title "(b) windows rolled back or stepped conservatively"
set ylabel "rollbacks + conservative steps"
set logscale y
set yrange [0.8:*]
plot 'equal.dat' u 1:($6 == 0 ? $11 + $12 + 1e-9 : NaN):(idx($4)) w p pt 7 ps 1 lc palette t "random interleaving", \
     '' u 1:($6 == 1 ? $11 + $12 + 1e-9 : NaN):(idx($4)) w p pt 5 ps 0.9 lc palette t "virtual time"
unset multiplot
