# caption: Lozenge diagrams of explicit Euler and symplectic Euler. Euler takes every new value from the old time level only. Symplectic Euler kicks first and then drifts with the new velocity: the same two formulas as Euler, with one arrow moved, turn an energy that grows by (1 + Ω²) every step into one that only oscillates.
# Drawn by the script the lozenge driver generated (diagram_euler.gp); it writes
# lozenge_euler.png.
load 'diagram_euler.gp'
