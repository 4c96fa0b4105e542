# caption: The clusters of a cooling granular gas (the lesson's driver haff): the inelastic hard disks (restitution 0.7, η = 0.25) at the end of the run (100 t0 at demo size; at full size where inelastic collapse stopped it, near 400 t0), long after Haff's law stopped holding — each disk drawn to scale, coloured by its speed in units of the rms speed at that moment. The homogeneous gas has broken up into dense clusters and strands with nearly empty space between them, and whole clusters share one colour: they move together. What is left of the kinetic energy is mostly in this collective flow (clusters and vortices), not in the random motion that collisions dissipate — which is why T falls ever slower than Haff's law.
set terminal pngcairo size 1000,1000 font "sans,11"
set output 'haff_picture.png'
stats 'haff_config.dat' u 1 nooutput name "X"
stats 'haff_config.dat' u 2 nooutput name "Y"
side = ceil(X_max > Y_max ? X_max : Y_max)
set size ratio -1
set xrange [0:side]
set yrange [0:side]
set xlabel "x, σ"
set ylabel "y, σ"
set title "Inelastic hard disks, restitution 0.7, η = 0.25, late in the cooling"
set palette defined (0 "#1a2a6c", 0.5 "#2c7fb8", 1 "#7fcdbb", 1.6 "#fdae61", 3 "#d7191c")
set cbrange [0:3]
set cblabel "speed / rms speed"
set style fill solid 1.0 noborder
plot 'haff_config.dat' u 1:2:(0.5):3 w circles lc palette notitle
