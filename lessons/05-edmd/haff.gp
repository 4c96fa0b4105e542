# caption: A granular gas cools (the lesson's driver haff): inelastic hard disks at η = 0.25, restitution e = 0.9 and 0.7, melted elastically, then left to collide. (a) The temperature against time in units of Haff's t0 = 2d/((1 − e²)Γ0) — not fitted: Γ0 is the collision rate measured in the elastic start (kinetic theory: each collision loses (1 − e²)kT on average, and collisions slow down as √T, so T = T0/(1 + t/t0)², black). (b) The ratio to Haff's law over the first 2 t0, on a linear scale. Early on both restitutions follow it (green: checked, within 3 % up to t0/4, where T is down to 0.64 T0); then the molecular chaos that kinetic theory assumes wears off — partners that just collided move alike and meet again more gently, so a collision loses 1–3 % less than (1 − e²)kT, and T runs 2–5 % above the law by t0/2 and 7–20 % by 2 t0. Later, in (a), the homogeneous cooling state is unstable — denser regions collide more, cool faster, lose pressure and draw in more particles — and clusters and vortices store kinetic energy that collisions no longer dissipate: T falls ever slower than Haff's law, sooner for the more inelastic gas. At full size (make lesson STAGE=05) the e = 0.7 run ends early, at inelastic collapse: a cluster where collisions pile up without end, which the engine detects and reports instead of hanging (lesson 05 §12); the curve ends at the time reached.
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

set title "(b) the ratio to Haff's law over the first 2 t0"
unset logscale y
set format y "%.2f"
set ytics 0.05
set mytics 5
set xrange [0.01:2]
# only the points of t <= 2 t0, all of them in view: the top of the axis from their data
early(r, v) = $3 <= 2 ? sel(r, v) : NaN
stats 'haff.dat' u ($3 <= 2 ? $5 : NaN) nooutput name "R"
set yrange [0.95:(R_max > 1.1 ? R_max + 0.02 : 1.12)]
set ylabel "T / T_{Haff}"
set key top left
set object 1 rect from 0.01, 0.97 to 0.25, 1.03 fc rgb "#5cb85c" fs transparent solid 0.35 noborder behind
set arrow 1 from 0.25, 0.95 to 0.25, 1.03 nohead dt 2 lc rgb "#3d8b3d" lw 1.5 back
set label 1 "checked: within 3 %\nup to t0/4" at 0.012, 1.045 font "sans,9" tc rgb "#2d6b2d"
plot 1 w l lc rgb "black" lw 2 t "Haff", \
     'haff.dat' u 3:(early(0.9, $5)) w lp lc rgb 0x1f77b4 pt 7 ps 1 t "e = 0.9", \
     '' u 3:(early(0.7, $5)) w lp lc rgb 0xd62728 pt 5 ps 1 t "e = 0.7"
unset multiplot
