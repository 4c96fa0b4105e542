# caption: A granular gas cools (haff.c): inelastic hard disks at η = 0.25, restitution e = 0.9 and 0.7, melted elastically, then left to collide. Left: the temperature against time in units of Haff's t0 = 2d/((1 − e²)Γ0) — not fitted: Γ0 is the collision rate measured in the elastic start (kinetic theory: each collision loses (1 − e²)kT on average, and collisions slow down as √T, so T = T0/(1 + t/t0)², black). Right: the ratio to Haff's law. Early on both restitutions follow it to a few per cent (green: checked, within 3 % up to t0/4, T down to 0.64 T0); then the molecular chaos that kinetic theory assumes wears off — partners that just collided move alike and meet again more gently, so a collision loses 2–3 % less than (1 − e²)kT and T runs a few per cent above the law by t0/2; later the homogeneous cooling state is unstable — denser regions collide more, cool faster, lose pressure and draw in more particles — and clusters and vortices store kinetic energy that collisions no longer dissipate: T falls slower than Haff's law, sooner for the more inelastic gas. At full size the e = 0.7 run ends early, at inelastic collapse: a cluster where collisions pile up without end (lz_edmd_run stops with LZ_EPHYS and the run ends at the time reached).
set terminal pngcairo size 1300,540 font "sans,11"
set output 'haff.png'
set multiplot layout 1,2 title "Haff's law: the cooling of inelastic hard disks, η = 0.25"
set grid xtics ytics mxtics mytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"
set logscale x
set format x "10^{%T}"
set xlabel "time t / t0"
sel(r, v) = (abs($1 - r) < 1e-9) ? v : NaN

set title "(a) temperature against time"
set logscale y
set format y "10^{%T}"
set ylabel "kT / kT0"
set key bottom left
plot 1 / (1 + x)**2 w l lc rgb "black" lw 2 t "Haff: 1/(1 + t/t0)^2", \
     'haff.dat' u 3:(sel(0.9, $4)) w p lc rgb 0x1f77b4 pt 7 ps 1 t "e = 0.9", \
     '' u 3:(sel(0.7, $4)) w p lc rgb 0xd62728 pt 5 ps 1 t "e = 0.7"

set title "(b) the ratio to Haff's law"
set format y "%g"
set ytics (0.9, 1, 1.2, 1.5, 2, 3, 5, 10, 20, 50, 100)
set yrange [0.9:150]
set ylabel "T / T_{Haff}  (log scale)"
set key top left
set object 1 rect from graph 0, first 0.97 to 0.25, first 1.03 fc rgb "#5cb85c" fs solid 0.9 noborder behind
set label 1 "green: checked, within 3 % up to t0/4" at 0.012, first 1.13 font "sans,9"
plot 1 w l lc rgb "black" lw 2 t "Haff", \
     'haff.dat' u 3:(sel(0.9, $5)) w lp lc rgb 0x1f77b4 pt 7 ps 1 t "e = 0.9", \
     '' u 3:(sel(0.7, $5)) w lp lc rgb 0xd62728 pt 5 ps 1 t "e = 0.7"
unset multiplot
