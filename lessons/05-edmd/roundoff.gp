# caption: The absolute-time problem (the round-off control of the DynamO paper: Bannerman, Sargant and Lue, J. Comput. Chem. 32, 3329 (2011)), measured by the lesson's driver roundoff on hard spheres at η = 0.3: the same run with its clock started at T0 = 1 … 10¹⁴. Without re-basing (blue) every stored time is near T0, so the differences now − t0 and now + (time to the event) lose their low digits: collisions are carried out up to one ulp(T0) ≈ 2.2·10⁻¹⁶·T0 early or late, and the spheres overlap by about |v_rel|·ulp(T0) (grey line, v_rel = √6 the rms relative speed) — 10⁻⁴ σ at T0 = 10¹²; crosses: the engine's audit finds particles outside their cells (tolerance 10⁻⁹ σ) — from T0 = 10¹³ on at demo size, 10¹¹ at full size, where the run is longer — so partners can be missed altogether. The energy is conserved to 10⁻¹⁴ all the same: every bounce conserves it, wherever it happens — energy is no test for this. Re-based (red, what the engine does: the clock stays small and the elapsed time is kept apart; lesson 05 §7) the overlaps stay at round-off (at demo size exactly 0), and the trajectory is the same bit for bit whatever T0.
set terminal pngcairo size 900,580 font "sans,11"
set output 'roundoff.png'
set grid xtics ytics lc rgb "#e8e8e8"
set key font "sans,10" samplen 3 opaque box lc rgb "#cccccc" top left
# an overlap of exactly 0 has no place on a log axis: said in words instead
stats 'roundoff.dat' u 4 nooutput name "REB"
set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
set xrange [0.3:3e14]
set yrange [1e-17:1]
set xlabel "absolute time at the start T0"
set ylabel "largest overlap 1 − r_{ij} during the run, σ"
set title "Overlaps against the absolute time, with and without re-basing"
if (REB_max == 0) {
	set label 1 "re-based: no overlap at all (exactly 0 at every T0)" at graph 0.03, graph 0.06 font "sans,10" tc rgb 0xd62728
}
plot 'roundoff.dat' u 1:3 w l lc rgb "#888888" lw 2 dt 2 t "|v_{rel}|·ulp(T0)", \
     '' u 1:($6 > 0 ? $6 : NaN) w lp lc rgb 0x1f77b4 pt 7 ps 1.3 lw 2 t "not re-based", \
     '' u 1:($8 == 0 ? $6 : NaN) w p lc rgb "black" pt 2 ps 2.5 lw 2 t "not re-based: particles outside their cells", \
     '' u 1:($4 > 0 ? $4 : NaN) w lp lc rgb 0xd62728 pt 5 ps 1.3 lw 2 t (REB_max > 0 ? "re-based, as the engine runs" : "")
