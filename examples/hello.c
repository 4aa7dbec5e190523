/* hello.c - the quick start of README.md, as a file: a rubber strip clamped at one end swings
   under gravity for 1 s; writes strip.vtk. Built by make as build/hello. */
#define SPHSOLID_IMPLEMENTATION
#include "sphsolid.h"
#include <stdio.h>

static int progress(sps_world* w, void* user) {               /* after every step */
    static double shown = 0;
    (void)user;
    if (sps_world_time(w) >= shown) { fprintf(stderr, "t = %.1f s\r", (double)sps_world_time(w)); shown += 0.1; }
    return 0;                                              /* nonzero stops */
}

int main(void) {
    sps_world_def wd = sps_default_world_def();
    wd.dim = 2; wd.dp = 0.002; wd.gravity[1] = -9.81;     /* SI units */
    sps_world* w;
    if (sps_world_create(&wd, &w) != SPS_OK) return 1;
    sps_body_def bd = sps_default_body_def();              /* SPH-ENO-A, rho0 1000, E 1e6, nu 0.3 */
    bd.material.youngs_modulus = 2e6;
    sps_body strip;
    sps_world_add_body(w, &bd, &strip);
    sps_real lo[3] = {-0.008, -0.01, 0}, hi[3] = {0.2, 0.01, 0};
    sps_body_add_box(w, strip, lo, hi, NULL);              /* lattice fill, spacing dp */
    sps_real clo[3] = {-1, -1, -1}, chi[3] = {0, 1, 1};
    sps_body_constrain_box(w, strip, clo, chi, SPS_AXIS_ALL, NULL, NULL); /* clamp x < 0 */
    if (sps_world_advance(w, 1.0, progress, NULL) != SPS_OK) puts(sps_world_last_error(w));
    sps_world_write_vtk(w, "strip.vtk");                   /* open in ParaView */
    sps_world_destroy(w);
    return 0;
}
