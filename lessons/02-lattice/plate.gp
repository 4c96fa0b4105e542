# caption: A uniform FHP flow (u_0 = 0.3 along x, d = 0.2, L = 512) past a plate of 64 wall sites (55 lattice spacings) across it at x = L/4: the velocity averaged over steps 1001–2000 in 16×16-site blocks, arrows for u and colour for u_x (white: at rest, blue: backwards), the middle half of the box. The flow parts around the plate and speeds up past its edges; behind it a wake of nearly still fluid stretches several plate lengths downstream. The wall sites take momentum (5.7 units per step: the scene's obstacle drag), and with nothing to drive it the mean flow slows from 0.298 to 0.262 over the run; the mass stays exact.
set terminal pngcairo size 1100,560 enhanced font "Sans,11"
set output 'plate.png'
run = 'runs/02-fhp-plate/'
json(k) = real(system(sprintf("awk -F': *' '/\"%s\"/ { sub(/,$/, \"\", $2); print $2 }' %ssummary.json", k, run)))
L = json("size")
u0 = json("amplitude")
b = json("block")
# velocity.dat: block centre x, y, mean velocity ux, uy, density; obstacle.dat: wall sites.
set size ratio -1
set xrange [0:L]
set yrange [L * sqrt(3) / 4 - L / 4:L * sqrt(3) / 4 + L / 4]
set cbrange [-u0:u0]
set palette defined (-1 "#2166ac", -0.5 "#92c5de", 0 "#f7f7f7", 0.5 "#f4a582", 1 "#b2182b")
set cblabel "u_x [lattice spacings / step]"
set xlabel "x [lattice spacings]"
set ylabel "y [lattice spacings]"
set title sprintf("FHP flow past a plate: u_0 = %g at t = 0, d = %g, L = %d; mean over steps %d-%d in %d×%d blocks", \
                  u0, json("density"), L, json("steps") - json("average") + 1, json("steps"), b, b)
set key at graph 0.99, graph 0.97 right top opaque box lc rgb "#cccccc" font "Sans,10" samplen 1
s = 0.9 * b / u0
plot run.'velocity.dat' u 1:2:3 w image notitle, \
     '' u 1:2:($3 * s):($4 * s) w vectors head size 3,25 filled lc rgb "#303030" \
        t sprintf("u (an arrow of %g is %d spacings long)", u0, 0.9 * b), \
     run.'obstacle.dat' u 1:2 w p pt 5 ps 0.45 lc rgb "black" t "plate (wall sites)"
