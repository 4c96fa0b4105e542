# caption: Density across a slit 11 diameters wide in 2D (left: hard disks R = 4 on the square lattice, packing 0.45, 202 disks, 4×10⁴ sweeps) and 8 diameters wide in 3D (right: hard spheres R = 3 on the simple cubic lattice, packing 0.30, 522 spheres, 6000 sweeps), from the scenes 02-slit-2d and 02-slit-3d. The walls (thick lines) stand half a diameter outside the first allowed centre position. The disks pack against each wall in a dense layer, a second and third layer follow a diameter apart, and the middle is flat at the bulk density (dashed). Compare thesis figs. 2.28 and 2.29. The contact density is, by the contact theorem, the pressure on the wall: βP = ρ(contact).
set terminal pngcairo size 1100,480 font "sans,11"
set output 'slit_profiles.png'
set multiplot layout 1,2 title "Hard particles between two walls: layering (scenes 02-slit-2d, 02-slit-3d)"
set grid xtics ytics lc rgb "#e8e8e8"
unset key
set xlabel "z / σ above contact with the lower wall"
set yrange [0:*]
mid(f) = system(sprintf("sed -n 's/.*\"middle_density\": *\\([0-9.eE+-]*\\).*/\\1/p' %s", f)) + 0
set title "2D: disks, walls 11σ apart"
set ylabel "ρσ²"
set arrow 1 from -0.5, graph 0 to -0.5, graph 1 nohead lw 4
set arrow 2 from 10.5, graph 0 to 10.5, graph 1 nohead lw 4
set xrange [-0.7:10.7]
m = mid('runs/02-slit-2d/summary.json')
plot 'runs/02-slit-2d/profile.dat' u 1:2 w l lw 2 lc rgb "#1f77b4", m w l dt 2 lc rgb "#555555"
set title "3D: spheres, walls 8σ apart"
set ylabel "ρσ³"
set arrow 2 from 7.5, graph 0 to 7.5, graph 1 nohead lw 4
set xrange [-0.7:7.7]
m = mid('runs/02-slit-3d/summary.json')
plot 'runs/02-slit-3d/profile.dat' u 1:2 w l lw 2 lc rgb "#d62728", m w l dt 2 lc rgb "#555555"
unset multiplot
