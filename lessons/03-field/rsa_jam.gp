# caption: Random sequential adsorption to exact jamming on lattices (the lesson's driver rsa_jam; thesis 2.5.1): disks of radius R lattice units dropped at random free sites until the field has no free site left, mean and standard error of 8–32 runs of 2400 or more disks (860 or more spheres) each at full size (make lesson STAGE=03), 8–16 runs of 270 or more disks (360 or more spheres, R ≤ 8) at demo size; the figures below are the full size's. Left: the coverage θ = N·πR²/area (4πR³/3 in 3D) against R, with the continuum jamming coverages 0.547069 (disks) and 0.38413 (spheres). At R = 1/2 the excluded shape is the centre site alone, every site takes a particle and θ is the lattice's own limit, exactly π/4 (square), π/(2√3) (triangular: the close packing) and π/6 (cubic); at R = 1 the square lattice excludes a 3×3 block, which is RSA of 2×2 squares (measured 0.74820 ± 0.00020 of the sites covered, against 0.74788 in the literature). From R ≈ 2 on θ stays a few 10⁻³ to 10⁻² below the continuum and does not converge smoothly: the lattice disk excludes the sites strictly inside 2R, fewer than the area π(2R)² by an amount that jumps with R (Gauss's circle problem; 4 % at R = 4, 0.14 % at R = 48). Right: θ_eff = θ × (excluded sites × site area)/π(2R)² — the coverage of disks as large as the lattice disk really is — minus the continuum, against 1/R (filled), with θ minus the continuum (small open). θ_eff approaches the continuum on a straight line in 1/R with the same slope, −0.11 to −0.12, on all three lattices: the last gaps of a packing must hold a lattice site. The fits (solid: θ∞ + a/R, dashed: + b/R², over R ≥ 3) give θ∞ = 0.5466 ± 0.0005 (square), 0.5471 ± 0.0021 (triangular) and 0.3816 ± 0.0017 (cubic, R ≤ 12 only), within 0.9, 0.0 and 1.4 error bars of the continuum. The 1/R² term is not resolved (b within 2 error bars of 0), but it moves the intercept — in 3D the linear fit lands some 0.002 low in every seed tried, the quadratic one 0.001 — so the error bars include the difference of the two fits. At demo size the fits give 0.5468 ± 0.0031, 0.5467 ± 0.0025 and 0.380 ± 0.006, and the 2×2 squares cover 0.74816 ± 0.00029.
set terminal pngcairo size 1400,580 font "sans,11"
set output 'rsa_jam.png'
set datafile missing "nan"
set multiplot layout 1,2 title "Random sequential adsorption to exact jamming on lattices: coverage against the particle radius R"
set grid xtics ytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 2 opaque box lc rgb "#cccccc"
sel(k, c) = ($1 == k) ? column(c) : NaN
lname(k) = k == 0 ? "square" : k == 1 ? "triangular" : "cubic (3D)"
lrgb(k) = k == 0 ? 0xd62728 : k == 1 ? 0x2ca02c : 0x1f77b4
lpt(k) = k == 0 ? 5 : k == 1 ? 9 : 7
load 'rsa_ref.gp'  # theta_disks, theta_spheres: rsa_jam.c writes them from datasets/reference/rsa.csv
cont(k) = k < 2 ? theta_disks : theta_spheres

set title "(a) coverage at jamming θ = N · (πR² or 4πR³/3) / volume"
set logscale x 2
set xrange [0.25:64]
set yrange [0.25:0.95]
set xlabel "particle radius R  [lattice units]"
set ylabel "θ at jamming"
set key top right
set label 1 "π/(2√3)" at 0.46, 0.907 right font "sans,9"
set label 2 "π/4" at 0.46, 0.785 right font "sans,9"
set label 3 "π/6" at 0.46, 0.524 right font "sans,9"
set label 4 "every site\ntaken" at 0.27, 0.68 font "sans,9"
set label 5 "2×2 squares" at 1.1, 0.6 font "sans,9"
plot for [k = 0:2] 'rsa_jam.dat' u (sel(k, 3)):7:8 w yerrorlines lc rgb lrgb(k) pt lpt(k) ps 1 lw 1.5 t lname(k), \
     theta_disks w l lc rgb "#444444" dt 2 lw 1.5 t sprintf("continuum disks %.6f", theta_disks), \
     theta_spheres w l lc rgb "#444444" dt 4 lw 1.5 t sprintf("continuum spheres %.5f", theta_spheres)

set title "(b) the approach to the continuum: θ_{eff} = θ × lattice shape size / continuum size"
unset label
unset logscale
set xrange [0:0.52]
set yrange [-0.065:0.012]
set xlabel "1 / R  [1 / lattice units]"
set ylabel "θ − θ_{continuum}"
set key bottom left
plot 0 w l lc rgb "#444444" dt 2 notitle, \
     for [k = 0:2] 'rsa_jam.dat' u (sel(k, 3) >= 2 ? 1 / $3 : NaN):($11 - cont(k)):12 w yerrorbars lc rgb lrgb(k) pt lpt(k) ps 1 lw 1.5 t lname(k) . ": θ_{eff}", \
     for [k = 0:2] '' u (sel(k, 3) >= 2 ? 1 / $3 : NaN):($7 - cont(k)) w p lc rgb lrgb(k) pt lpt(k) - 1 ps 0.7 notitle, \
     for [k = 0:2] 'rsa_fit.dat' u (sel(k, 2)):($3 - cont(k)) w l lc rgb lrgb(k) lw 1.5 notitle, \
     for [k = 0:2] '' u (sel(k, 2)):($4 - cont(k)) w l lc rgb lrgb(k) lw 1 dt 2 notitle, \
     1/0 w p lc rgb "#555555" pt 4 ps 0.7 t "θ itself (open)", \
     1/0 w l lc rgb "#555555" lw 1.5 t "fit θ_∞ + a/R, R ≥ 3", \
     1/0 w l lc rgb "#555555" lw 1 dt 2 t "fit θ_∞ + a/R + b/R²"
unset multiplot
