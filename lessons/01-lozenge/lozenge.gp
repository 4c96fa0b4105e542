# caption: Lozenge diagrams of the Verlet family, redrawn after figure 1.1 of the thesis. Each diagram has columns r, v, a, b (position and its first three time derivatives), time runs downward, and the v and b columns sit half a step off. Filled dots are the samples a formula uses, the ringed point is what it computes, and the arrows carry the weights; going right to left is integration, so a enters r with a factor dt². Verlet needs no velocity, the central difference recovers it, and leapfrog and velocity Verlet keep v at half or whole steps.
# The picture itself is drawn by the script the lozenge driver generated with
# lz_lozenge_gnuplot (diagram_verlet.gp, in this directory); it writes lozenge.png.
load 'diagram_verlet.gp'
