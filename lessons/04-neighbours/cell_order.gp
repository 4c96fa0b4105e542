# caption: Where the bytes are, measured by the lesson's driver cell_order on the system of table 2.2 (hard disks R = 12, packing 0.474, N = 1099 … 1.1 million; CL at skin 7, FNL at skin 32). Atom-steps per CPU second (median of 3, shared 2-core AMD EPYC) of the cell-list driver with linked lists (open circles, dashed) or fixed arrays (filled), the particles numbered as placed — random in space — or cell by cell in row-major or Morton order, and of the fast neighbour list as placed and in Morton order. In the caches the variants run alike (12–17 million); outside, numbering the particles cell by cell is what pays — at 1.1 million disks (full size, make lesson STAGE=04) 7.7 times for CL with arrays, 2.7 times for FNL; at demo size, 70 315 disks at most, 2.0 and 1.3 times — because a step reads the positions of its candidates. Linked lists are no slower than arrays once the numbering is right, and for a sweep row-major order beat Morton order.
set terminal pngcairo size 900,580 font "sans,11"
set output 'cell_order.png'
set grid xtics ytics mxtics lc rgb "#e8e8e8"
set key font "sans,10" samplen 3 opaque box lc rgb "#cccccc" bottom left
set logscale x
stats 'cell_order.dat' u 1 nooutput name "N"
set xrange [N_min / 1.5 : N_max * 1.5]
set yrange [0:*]
set format x "10^{%T}"
set xlabel "particles N"
set ylabel "10^6 atom-steps per CPU second"
set title "Cell lists: linked or arrays, particles as placed or numbered cell by cell"
# The rows go size by size, 8 variants each: every 8th row from row v is variant v.
plot 'cell_order.dat' every 8::0 u 1:($4 / 1e6) w lp lc rgb 0xd62728 pt 6 dt 2 lw 2 t "CL linked, as placed", \
     '' every 8::1 u 1:($4 / 1e6) w lp lc rgb 0xff7f0e pt 6 dt 2 lw 2 t "CL linked, row-major", \
     '' every 8::2 u 1:($4 / 1e6) w lp lc rgb 0x2ca02c pt 6 dt 2 lw 2 t "CL linked, Morton", \
     '' every 8::3 u 1:($4 / 1e6) w lp lc rgb 0xd62728 pt 7 lw 2 t "CL arrays, as placed", \
     '' every 8::4 u 1:($4 / 1e6) w lp lc rgb 0xff7f0e pt 7 lw 2 t "CL arrays, row-major", \
     '' every 8::5 u 1:($4 / 1e6) w lp lc rgb 0x2ca02c pt 7 lw 2 t "CL arrays, Morton", \
     '' every 8::6 u 1:($4 / 1e6) w lp lc rgb 0x1f77b4 pt 4 dt 3 lw 2 t "FNL, as placed", \
     '' every 8::7 u 1:($4 / 1e6) w lp lc rgb 0x1f77b4 pt 5 lw 2 t "FNL, Morton"
