# caption: The lattice measure M(k): lattice points in the unit shell k ≤ r < k+1 divided by the exact shell area π(2k+1) (triangular: in units of the site area √3/2) or volume 4π/3·(3k²+3k+1), for the first 150 shells (shell 0, the single point r = 0, is 0.32, 0.28 and 0.24: below the axis). A continuum would give 1 everywhere. The square and triangular lattices scatter by several percent, and not even monotonically (square: 40 points in [5,6), 36 in [6,7)); the cubic lattice is smoother because a 3D shell holds many more points. A raw lattice g(r) carries exactly this pattern, and dividing by M removes it.
set terminal pngcairo size 900,600 font "sans,11"
set output 'shells.png'
set title "Lattice points per unit shell over the exact shell measure"
set xlabel "shell k (k ≤ r < k+1) [lattice units]"
set ylabel "M(k) = points / exact measure"
set grid xtics ytics lc rgb "#e8e8e8"
set xrange [0:150]
# shell 0 holds the one point r = 0 against the area of a whole disk: far below the
# axis, so it is given in words and the curves start at k = 1
stats 'shells.dat' u ($1 == 0 ? $5 : NaN) nooutput name "S0"
stats 'shells.dat' u ($1 == 0 ? $6 : NaN) nooutput name "T0"
stats 'shells.dat' u ($1 == 0 ? $7 : NaN) nooutput name "C0"
set yrange [0.7:1.3]
set key top right font "sans,9" opaque box lc rgb "#cccccc" spacing 1.1 samplen 2
set label 1 sprintf("k = 0 (one point, r = 0), not drawn: M = %.2f square, %.2f triangular, %.2f cubic", S0_max, T0_max, C0_max) at graph 0.03, graph 0.05 font "sans,9"
from1(v) = $1 >= 1 ? v : NaN
plot 'shells.dat' u 1:(from1($5)) w lp lc rgb "#d62728" pt 7 ps 0.4 lw 1 t "square", \
     '' u 1:(from1($6)) w lp lc rgb "#2ca02c" pt 9 ps 0.5 lw 1 t "triangular", \
     '' u 1:(from1($7)) w lp lc rgb "#1f77b4" pt 5 ps 0.4 lw 1.5 t "cubic", \
     1 w l lc rgb "#444444" dt 2 t "continuum"
