# caption: What orders the events (the lesson's driver queues)? Hard spheres at η = 0.5 against N: collisions per CPU second with the cells and the binary heap of the assignment (black), and with lists ordered by the binary heap, a 4-ary heap and a calendar queue.
set terminal pngcairo size 900,600 font "sans,11"
set output 'queues.png'
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 3 opaque box lc rgb "#cccccc" bottom left
set logscale xy
set format x "10^{%T}"
set format y "%.0t×10^{%T}"
set xlabel "particles N"
set ylabel "collisions per second of CPU time"
stats 'queues.dat' u 1 nooutput name "N"
stats 'queues.dat' u 3 nooutput name "C"
set xrange [N_min / 1.5 : N_max * 1.5]
set yrange [C_min / 1.3 : C_max * 1.3]
set title "Hard spheres at η = 0.5: which queue?"
names = "'cells, binary heap' 'lists, binary heap' 'lists, 4-ary heap' 'lists, calendar'"
name(o) = word(names, o + 1)
rgb(o) = word("0x000000 0x1f77b4 0xff7f0e 0xd62728", o + 1) + 0
# the rows cycle through the four options at each N: every fourth row is one option
plot for [o = 0:3] 'queues.dat' u 1:3 every 4::o w lp lc rgb rgb(o) pt 7 lw 2 t name(o)
