# caption: Random sequential adsorption run to exact jamming: no lattice site is left where another centre could go. Left: disks of radius R = 12 on the square lattice, box 1024 × 1024 (1257 disks, θ = 0.542; compare thesis fig. 2.18). Middle: the same on the triangular lattice (box drawn as the L × L√3/2 rectangle the sheared storage maps to; 1088 disks, θ = 0.542). Right: spheres R = 8 on the cubic lattice, box 128³ (366 spheres, θ = 0.374): the cross-sections of the spheres that cut the plane z = 64. Typical RSA: no order, many gaps just too small for one more disk, and pairs that touch. From the scenes 03-rsa-square, 03-rsa-triangular and 03-rsa-3d (placement takes 0.01–0.04 s each).
set terminal pngcairo size 1500,540 font "sans,11"
set output 'rsa_pictures.png'
set multiplot layout 1,3
set size ratio -1
unset key
set style fill solid 0.55 border lc rgb "#1f4e79"
set xlabel "x [lattice units]"; set ylabel "y [lattice units]"
set title "square lattice, R = 12, jammed"
set xrange [0:1024]; set yrange [0:1024]
plot 'runs/03-rsa-square/config.dat' u 1:2:3 w circles lc rgb "#6baed6"
set title "triangular lattice, R = 12, jammed"
set yrange [0:1024*sqrt(3)/2]
plot 'runs/03-rsa-triangular/config.dat' u 1:2:3 w circles lc rgb "#74c476"
set title "cubic lattice, R = 8, jammed: the slice z = 64"
set xrange [0:128]; set yrange [0:128]
# only the spheres that cut the plane; NaN in x drops a row (a NaN radius would not)
in(z, R) = abs(z - 64) < R
plot 'runs/03-rsa-3d/config.dat' u (in($3, $4) ? $1 : NaN):2:(sqrt(abs($4**2 - ($3 - 64)**2))) w circles lc rgb "#9e9ac8"
unset multiplot
