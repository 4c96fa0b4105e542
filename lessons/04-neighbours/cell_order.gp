# caption: Where the bytes are, measured by cell_order.c on the system of table 2.2 (hard disks R = 12, packing 0.474, skin 4, N = 1099 … 1.1 million). Atom-steps per CPU second (median of 3, shared 2-core AMD EPYC) of the cell-list driver with linked lists (dashed) or fixed arrays (solid), the particles numbered as placed — random in space — or cell by cell in row-major or Morton order, and of the fast neighbour list as placed and in Morton order. In the caches the variants run alike; outside, numbering the particles cell by cell is what pays, because a step reads the positions of its candidates.
set terminal pngcairo size 900,580 font "sans,11"
set output 'cell_order.png'
set grid xtics ytics mxtics lc rgb "#e8e8e8"
set key font "sans,10" samplen 3 opaque box lc rgb "#cccccc" bottom left
set logscale x
set format x "10^{%T}"
set xlabel "particles N"
set ylabel "10^6 atom-steps per CPU second"
set title "Cell lists: linked or arrays, particles as placed or numbered cell by cell"
pick(v) = ($3 == v) ? $4 / 1e6 : NaN
plot 'cell_order.dat' u 1:(pick(0)) w lp lc rgb 0xd62728 pt 6 dt 2 lw 2 t "CL linked, as placed", \
     '' u 1:(pick(1)) w lp lc rgb 0xff7f0e pt 6 dt 2 lw 2 t "CL linked, row-major", \
     '' u 1:(pick(2)) w lp lc rgb 0x2ca02c pt 6 dt 2 lw 2 t "CL linked, Morton", \
     '' u 1:(pick(3)) w lp lc rgb 0xd62728 pt 7 lw 2 t "CL arrays, as placed", \
     '' u 1:(pick(4)) w lp lc rgb 0xff7f0e pt 7 lw 2 t "CL arrays, row-major", \
     '' u 1:(pick(5)) w lp lc rgb 0x2ca02c pt 7 lw 2 t "CL arrays, Morton", \
     '' u 1:(pick(6)) w lp lc rgb 0x1f77b4 pt 4 dt 3 lw 2 t "FNL, as placed", \
     '' u 1:(pick(7)) w lp lc rgb 0x1f77b4 pt 5 lw 2 t "FNL, Morton"
