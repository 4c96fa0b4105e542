# caption: The bits of the first 96 outputs of two generators from the same seed: draw n across, bit k up (bit 31, the most significant, at the top; black = 1). Top: the thesis's LCG x → 69069x + 1 mod 2^32. Its lowest bit alternates, bit k repeats with period 2^(k+1), so the bottom rows are regular stripes and only the top rows look random. Bottom: GSL's mt19937, the course's default generator, has no visible pattern in any bit.
set terminal pngcairo size 900,700 font "sans,11"
set output 'lowbits.png'
set multiplot layout 2,1 title "Which bits of a random number are random?"
set palette defined (0 "white", 1 "black")
unset colorbox
set xrange [-0.5:95.5]
set yrange [-0.5:31.5]
set ytics 0,4,31
set xlabel "draw n"
set ylabel "bit k"
set title "LCG a = 69069, c = 1, m = 2^{32}: bit k has period 2^{k+1}"
plot 'lowbits.dat' u 1:2:3 w image notitle
set title "GSL mt19937"
plot 'lowbits.dat' u 1:2:4 w image notitle
unset multiplot
