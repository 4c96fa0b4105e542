# caption: A density pulse (background d = 0.1 per link, three times that in a disk of radius L/8) after 240 steps on a 1024² lattice: HPP (left) and FHP (right), in Cartesian coordinates (the triangular lattice's rows are √3/2 apart, and its sheared period is drawn as a rectangle), averaged over 16×16-site blocks, one colour scale with white at the background density. Both fronts have moved out at about the sound speed 1/√2, but on the square lattice the excess runs ahead along the four axes, while on the triangular lattice the ring is round. Bottom: the ring's excess density by direction, over its mean (1 everywhere for a round front). Its angular harmonic of the lattice's own symmetry, the scene's front anisotropy, is H_4 = 0.173 ± 0.006 on HPP and H_6 = 0.011 ± 0.004 on FHP.
set terminal pngcairo size 1200,1000 enhanced font "Sans,11"
set output 'pulse.png'
hpp = 'runs/02-hpp-pulse/'
fhp = 'runs/02-fhp-pulse/'
json(run, k) = real(system(sprintf("awk -F': *' '/\"%s\"/ { sub(/,$/, \"\", $2); print $2 }' %ssummary.json", k, run)))
L = json(hpp, "size")
d = json(hpp, "density")
T = json(hpp, "steps")
a = json(hpp, "amplitude")
H4 = json(hpp, "front_anisotropy")
e4 = json(hpp, "front_anisotropy_err")
H6 = json(fhp, "front_anisotropy")
e6 = json(fhp, "front_anisotropy_err")

set multiplot title sprintf("A density pulse: d = %g per link, %g times that inside r < L/8, L = %d, after %d steps", d, 1 + a, L, T)
# The maps: one colour scale, white at the background density d.
set palette defined (0 "#2166ac", 0.25 "#92c5de", 0.5 "#f7f7f7", 0.75 "#f4a582", 1 "#b2182b")
set cbrange [0:2 * d]
set cblabel "density per link"
set size ratio -1
set xlabel "x [lattice spacings]"
set ylabel "y [lattice spacings]"
set xrange [0:L]
set xtics L / 4
set ytics L / 4
unset key

set origin 0.0, 0.38
set size 0.5, 0.58
unset colorbox
set title "HPP (square lattice, 4 directions)"
set yrange [0:L]
plot hpp.'density.dat' u 1:2:3 w image

set origin 0.47, 0.38
set size 0.53, 0.58
set colorbox
set title "FHP (triangular lattice, 6 directions)"
set yrange [0:L * sqrt(3) / 2]
plot fhp.'density.dat' u 1:2:3 w image

# The ring's excess density against the angle, relative to its mean: 1 for a round front.
set origin 0.0, 0.0
set size 1.0, 0.38
set size noratio
unset colorbox
set title "excess density in the ring the pulse spread into, by direction, in 15° bins; dotted: 1 + 2 H_m cos mθ"
set xlabel "direction θ [degrees] (0 = the lattice's direction 0, along x)"
set ylabel "excess / its mean"
set xrange [-7.5:352.5]
set xtics 45
set ytics 0.5
set yrange [0:2.2]
set grid xtics ytics lc rgb "#e8e8e8"
set key top center horizontal font "Sans,10" opaque box lc rgb "#cccccc" samplen 2 width 1
plot 1 w l lc rgb "#777777" dt 2 t "round front", \
     hpp.'front.dat' u 1:3 w lp lc rgb "#d62728" pt 7 ps 0.8 t sprintf("HPP: H_4 = %.3f ± %.3f", H4, e4), \
     '' u 1:4 w l lc rgb "#d62728" lw 1.5 dt 3 notitle, \
     fhp.'front.dat' u 1:3 w lp lc rgb "#1f77b4" pt 5 ps 0.8 t sprintf("FHP: H_6 = %.3f ± %.3f", H6, e6), \
     '' u 1:4 w l lc rgb "#1f77b4" lw 1.5 dt 3 notitle
unset multiplot
