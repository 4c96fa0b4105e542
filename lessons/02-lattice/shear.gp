# caption: The FHP shear wave of 02-fhp-shear (L = 256, d = 0.2, u_0 = 0.1) decays exponentially: its amplitude on a log axis against time, with the fitted exp(−ν k² t) (red, ν = 0.694 ± 0.073; open circles: the first 5% of the run, left out of the fit) and the Boltzmann predictions of this particle-hole symmetric model (ν = 0.641, dashed) and of FHP-I without four-body collisions (ν = 0.689, green, on top of the fit). One run cannot tell the two theories apart at d = 0.2; the lesson's table over seeds and densities can.
set terminal pngcairo size 900,600 enhanced font "Sans,11"
set output 'shear.png'
run = 'runs/02-fhp-shear/'
json(k) = real(system(sprintf("awk -F': *' '/\"%s\"/ { sub(/,$/, \"\", $2); print $2 }' %ssummary.json", k, run)))
nu = json("viscosity")
dnu = json("viscosity_err")
nu_m = json("viscosity_theory")
nu_1 = json("viscosity_theory_fhp1")
k = json("wave_number")
# decay.dat: t, amplitude, Boltzmann theory of this model, fitted line, fitted (1/0).
set title sprintf("FHP shear wave u_x(y) = u_0 sin ky: L = %d, d = %g, u_0 = %g, k = %.4f", json("size"), json("density"), json("amplitude"), k)
set xlabel "time t [steps]"
set ylabel "amplitude of the momentum wave [momentum/site]"
stats run.'decay.dat' u 2 nooutput
set logscale y
set yrange [STATS_min / 1.15:STATS_max * 1.1]
set format y "%.2f"
set ytics (0.02, 0.03, 0.04, 0.05, 0.06, 0.08, 0.1, 0.12)
set grid xtics ytics lc rgb "#e8e8e8"
set key bottom left Left reverse font "Sans,10" opaque box lc rgb "#cccccc" spacing 1.2 samplen 2
plot run.'decay.dat' u 1:($5 > 0.5 ? $2 : 1/0) w p pt 7 ps 0.5 lc rgb "#1f77b4" t "measured (fitted)", \
     '' u 1:($5 > 0.5 ? 1/0 : $2) w p pt 6 ps 0.5 lc rgb "#1f77b4" t "measured (left out of the fit)", \
     '' u 1:4 w l lw 2 lc rgb "#d62728" t sprintf("fit exp(-ν k^2 t): ν = %.3f ± %.3f", nu, dnu), \
     '' u 1:3 w l lw 2 dt 2 lc rgb "#333333" t sprintf("Boltzmann, this model: ν = %.3f", nu_m), \
     '' u 1:($3 * exp(-(nu_1 - nu_m) * k**2 * $1)) w l lw 2 dt (6, 4) lc rgb "#2ca02c" t sprintf("Boltzmann, FHP-I: ν = %.3f", nu_1)
