# caption: Successive pairs of the low byte, (x_n mod 256, x_{n+1} mod 256), for 4096 draws. Left: the 69069 LCG. The low 8 bits of the next number depend only on the low 8 bits of this one (x' = 205x + 1 mod 256), so 4096 draws visit exactly 256 of the 65536 possible pairs, all on five parallel lines. Right: mt19937 visits 3975 distinct pairs, as many as truly random draws would (3971 expected).
set terminal pngcairo size 1000,520 font "sans,11"
set output 'lowpairs.png'
set multiplot layout 1,2 title "Successive low bytes: 4096 pairs (x_n mod 256, x_{n+1} mod 256)"
set size ratio -1
set xrange [0:255]
set yrange [0:255]
set xtics 0,64,256
set ytics 0,64,256
set xlabel "x_n mod 256"
set ylabel "x_{n+1} mod 256"
set title "LCG 69069: 256 distinct pairs"
plot 'lowpairs.dat' u 1:2 w p pt 7 ps 0.35 lc rgb "#d62728" notitle
set title "mt19937: 3975 distinct pairs"
plot 'lowpairs.dat' u 3:4 w p pt 7 ps 0.35 lc rgb "#1f77b4" notitle
unset multiplot
