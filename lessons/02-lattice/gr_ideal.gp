# caption: g(r) of an ideal gas — 256 points thrown independently on the sites of a periodic box, 4000 configurations (400 at demo size) — on the square (L = 64), triangular (sheared, L = 64) and simple cubic (L = 32) lattices, up to r = L/2. The true g is 1 everywhere. Red: the raw g, pairs per shell over the exact shell area (volume); it is the lattice measure M(k) (grey line) and nothing else, 0.32, 0.28 and 0.24 in the first shell and jagged by several percent beyond. Blue: the corrected g, pairs over the shell's lattice-point count, flat at 1. On the triangular lattice the green curve bins the same pairs with the thesis's square table alone: exact up to √3L/4 ≈ 0.43L (dotted line), then short of pairs because part of each shell is given a too-long image. Bottom right: the corrected g's deviation from 1 in error bars, shell by shell; all lie within ±4.
set terminal pngcairo size 1100,800 font "sans,11"
set output 'gr_ideal.png'
set datafile missing "nan"
set multiplot layout 2,2 title "g(r) of an ideal gas on a lattice: raw against corrected"
set grid xtics ytics lc rgb "#e8e8e8"
set key bottom right font "sans,9" opaque box lc rgb "#cccccc" spacing 1.1 samplen 2
set xlabel "r [lattice units] (shell k ≤ r < k+1 at k + 1/2)"
set ylabel "g(r)"
set yrange [0.15:1.3]
sel(l, c) = ($1 == l) ? column(c) : NaN

do for [l = 0:2] {
	set title (l == 0 ? "square, L = 64" : l == 1 ? "triangular (sheared), L = 64" : "simple cubic, L = 32")
	set xrange [0:(l == 2 ? 16 : 32)]
	if (l == 1) {
		set arrow 1 from sqrt(3) * 16, graph 0 to sqrt(3) * 16, graph 1 nohead lc rgb "#2ca02c" dt 3
		plot 'gr_ideal.dat' u (sel(l, 3)):8 w l lc rgb "#aaaaaa" lw 1 t "lattice measure M(k)", \
		     '' u (sel(l, 3)):5 w p lc rgb "#d62728" pt 7 ps 0.6 t "raw g (exact area)", \
		     '' u (sel(l, 3)):9 w lp lc rgb "#2ca02c" pt 9 ps 0.6 lw 1.5 t "table alone (thesis)", \
		     '' u (sel(l, 3)):6:7 w yerrorbars lc rgb "#1f77b4" pt 5 ps 0.5 t "corrected g (lattice count)"
		unset arrow 1
	} else {
		plot 'gr_ideal.dat' u (sel(l, 3)):8 w l lc rgb "#aaaaaa" lw 1 t "lattice measure M(k)", \
		     '' u (sel(l, 3)):5 w p lc rgb "#d62728" pt 7 ps 0.6 t "raw g (exact area)", \
		     '' u (sel(l, 3)):6:7 w yerrorbars lc rgb "#1f77b4" pt 5 ps 0.5 t "corrected g (lattice count)"
	}
}

set title "corrected g − 1 in error bars"
set xrange [0:0.5]
set yrange [-6:6]
set xlabel "r / L"
set ylabel "(g_{corr} − 1) / error"
set key top right
plot 'gr_ideal.dat' u (sel(0, 4)):(($6 - 1) / $7) w lp lc rgb "#d62728" pt 7 ps 0.5 t "square", \
     '' u (sel(1, 4)):(($6 - 1) / $7) w lp lc rgb "#2ca02c" pt 9 ps 0.5 t "triangular", \
     '' u (sel(2, 4)):(($6 - 1) / $7) w lp lc rgb "#1f77b4" pt 5 ps 0.5 t "cubic", \
     4 w l lc rgb "#777777" dt 2 t "±4", -4 w l lc rgb "#777777" dt 2 notitle
unset multiplot
