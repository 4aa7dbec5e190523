/* spinning_cube.c - 3D spinning cube, BENCHMARKS.md A4 (ANG 5.1.4): a unit cube, nu = 0.3, in
   rigid rotation at omega = (0, 0, 50) rad/s. The program is spinning_plate.c in 3D; reading
   that file explains both.
   Build: make examples     Run: ./build/spinning_cube --shear gno-a
   Expect: max_angmom_err about 1.2 % for GNO-A, 2.7 % for ENO-A (ANG Fig. 16). */
#define SPINNING_CUBE
#include "spinning_plate.c"
