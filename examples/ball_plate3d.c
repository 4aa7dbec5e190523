/* ball_plate3d.c - a 3D rubber ball hitting a plate held on its four edges, benchmark A10 (ENO
   6.8): ball_plate2d.c built with BALL_PLATE_DIM 3 (plate 0.5 x 0.02 x 0.5, ball radius 0.05,
   v0 = 0.12 c0 by default, dp 0.01 by default; the paper's dp is 0.0025, see
   bench/results/contact_a.md for its particle count and cost per step).

   Build: make examples        Run: ./build/ball_plate3d --dp 0.01 --v0 0.12 --shear eno-a (--png-view xy, the default, shows the plate edge-on; iso looks at its far side) */
#define BALL_PLATE_DIM 3
#include "ball_plate2d.c"
