# caption: The equation of state, measured twice over by the lesson's driver eos: hard spheres (N = 4000, left) and hard disks (N = 4096, right), each state point melted from the lattice and measured in 20 blocks. Top: Z = βP/ρ against the packing η — from the collision impulses (filled) and from the collision count alone through the identity Z = 1 + √(π/kT) Γ/(2d) (open) — beside Z_ref, the Padé-resummed virial series of the course's reference values (line), and Carnahan–Starling (3D) / Henderson (2D) (dashed). Bottom: the same as a relative deviation from Z_ref, in %, with ±1 error bar (grey bars: Z_ref's own uncertainty). Impulses and count agree with each other and with Z_ref within 3 error bars at every point (the driver checks it); Carnahan–Starling is visibly 0.3 % low from η = 0.3 on, and Henderson 0.5–2 % high above η = 0.5 — at η = 0.65 the disks approach the liquid–hexatic transition (η ≈ 0.70), where the pressure flattens below every fluid equation of state.
set terminal pngcairo size 1300,900 font "sans,11"
set output 'eos.png'
set multiplot layout 2,2 title "Hard spheres and hard disks: Z from the impulses and from the collision rate against Z_{ref}"
set grid xtics ytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc" top left
sel(d, v) = ($1 == d) ? v : NaN
rel(z, zr) = 100 * (z / zr - 1)

set xlabel "packing fraction η"
set ylabel "Z = βP/ρ"
set xrange [0:0.52]
set title "(a) hard spheres, N = 4000"
plot 'eos_ref.dat' u 1:2 w l lc rgb "black" lw 1.5 t "Z_{ref} (Padé)", \
     '' u 1:3 w l lc rgb 0x2ca02c dt 2 lw 1.5 t "Carnahan–Starling", \
     'eos.dat' u 2:(sel(3, $3)):4 w yerrorbars lc rgb 0xd62728 pt 7 ps 1.2 t "Z from the impulses", \
     '' u 2:(sel(3, $5)):6 w yerrorbars lc rgb 0x1f77b4 pt 6 ps 2 lw 1.5 t "Z_Γ from the collision rate"
set xrange [0:0.7]
set title "(b) hard disks, N = 4096"
plot 'eos_ref.dat' u 1:4 w l lc rgb "black" lw 1.5 t "Z_{ref} (Padé)", \
     '' u 1:5 w l lc rgb 0x2ca02c dt 2 lw 1.5 t "Henderson", \
     'eos.dat' u 2:(sel(2, $3)):4 w yerrorbars lc rgb 0xd62728 pt 7 ps 1.2 t "Z from the impulses", \
     '' u 2:(sel(2, $5)):6 w yerrorbars lc rgb 0x1f77b4 pt 6 ps 2 lw 1.5 t "Z_Γ from the collision rate"

set ylabel "(Z / Z_{ref} − 1), %"
set key bottom left
set xrange [0:0.52]
set yrange [-0.8:0.8]
set title "(c) hard spheres: deviation from Z_{ref}"
plot 'eos_ref.dat' u 1:(rel($3, $2)) w l lc rgb 0x2ca02c dt 2 lw 1.5 t "Carnahan–Starling", \
     'eos.dat' u 2:(sel(3, 0)):(100 * $8 / $7) w yerrorbars lc rgb "#999999" pt 0 lw 3 t "Z_{ref} uncertainty", \
     '' u ($2 - 0.004):(sel(3, rel($3, $7))):(100 * $4 / $7) w yerrorbars lc rgb 0xd62728 pt 7 ps 1.2 t "Z from the impulses", \
     '' u ($2 + 0.004):(sel(3, rel($5, $7))):(100 * $6 / $7) w yerrorbars lc rgb 0x1f77b4 pt 6 ps 2 lw 1.5 t "Z_Γ from the collision rate", \
     0 w l lc rgb "black" notitle
set xrange [0:0.7]
set yrange [-3:3]
set title "(d) hard disks: deviation from Z_{ref}"
plot 'eos_ref.dat' u 1:(rel($5, $4)) w l lc rgb 0x2ca02c dt 2 lw 1.5 t "Henderson", \
     'eos.dat' u 2:(sel(2, 0)):(100 * $8 / $7) w yerrorbars lc rgb "#999999" pt 0 lw 3 t "Z_{ref} uncertainty", \
     '' u ($2 - 0.005):(sel(2, rel($3, $7))):(100 * $4 / $7) w yerrorbars lc rgb 0xd62728 pt 7 ps 1.2 t "Z from the impulses", \
     '' u ($2 + 0.005):(sel(2, rel($5, $7))):(100 * $6 / $7) w yerrorbars lc rgb 0x1f77b4 pt 6 ps 2 lw 1.5 t "Z_Γ from the collision rate", \
     0 w l lc rgb "black" notitle
unset multiplot
