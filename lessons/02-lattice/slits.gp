# caption: Hard disks (R = 6 lattice units, square lattice, reduced density ρσ² = 0.55) between two hard walls, the width left to the centres w running from a quarter of a diameter to four. The density across the slit, centred on its middle. Left: narrow slits. At w = σ/4 the disks can only queue and the profile is flat; from w = σ/2 they push each other against the walls and the profile bends up; by w = σ two wall layers hold nearly every disk. Right: wider slits. At w = 2σ a middle layer has formed between the wall layers (three layers); at 3σ and 4σ the layers multiply and the middle flattens toward the bulk. 2×10⁵ sweeps per width (2×10⁴ at demo size), profiles every 10 sweeps.
set terminal pngcairo size 1100,520 font "sans,11"
set output 'slits.png'
set multiplot layout 1,2 title "Layers of hard disks in narrow slits (thesis figs. 2.31–2.32)"
set grid xtics ytics lc rgb "#e8e8e8"
set key below font "sans,9" samplen 2
set xlabel "z / σ from the middle of the slit"
set ylabel "ρσ²"
set yrange [0:*]
sel(k, c) = ($1 == k) ? column(c) : NaN
wid(k) = sprintf("w = %g σ", k == 0 ? 0.25 : k == 1 ? 0.5 : k == 2 ? 0.75 : k == 3 ? 1 : k == 4 ? 1.25 : k == 5 ? 1.5 : k == 6 ? 2 : k == 7 ? 2.5 : k == 8 ? 3 : 4)
set title "narrow: from a queue to two wall layers"
set xrange [-0.8:0.8]
plot for [k = 0:5] 'slits.dat' u (sel(k, 3)):4 w l lw 2 t wid(k)
set title "wider: a middle layer forms, then more"
set xrange [-2.1:2.1]
plot for [k = 5:9] 'slits.dat' u (sel(k, 3)):4 w l lw 2 t wid(k)
unset multiplot
