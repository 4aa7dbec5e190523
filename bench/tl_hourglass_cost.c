/* tl_hourglass_cost - what the variational hourglass force costs against the paper's (TL eq. 32).

   Two worlds in one process, the same total-Lagrangian plate (A1: 2D, H/dp 10, Saint Venant-
   Kirchhoff, alpha 50, v_f 0.05 swing), one with hourglass = variational and one with
   hourglass = paper, stepped in alternating rounds of one advection step each, so that both see
   the same machine load; prints the wall time per particle and sub-step of each and their ratio.
   Only the ratio means anything on a shared machine.

   Build: make build/tl_hourglass_cost
   Run:   ./build/tl_hourglass_cost [rounds]   (default 200) */
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void swing(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = 0;
    v[1] = (sps_real)(0.05 * 10 * x[0] * x[0]); /* a smooth transverse velocity growing from the clamp */
    v[2] = 0;
}

static sps_world* plate(sps_hourglass form) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body b;
    sps_real lo[3] = {-0.06, 0, 0}, hi[3] = {0.2, 0.02, 0}, clamp_lo[3] = {-1, -1, -1}, clamp_hi[3] = {0, 1, 1};
    wd.dim = 2;
    wd.dp = (sps_real)0.002;
    wd.threads = 1;
    bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
    bd.material.kind = SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF;
    bd.material.density = 1000;
    bd.material.youngs_modulus = (sps_real)2e6;
    bd.material.poisson_ratio = (sps_real)0.3975;
    bd.material.tl.hourglass = form;
    if (sps_world_create(&wd, &w) != SPS_OK || sps_world_add_body(w, &bd, &b) != SPS_OK || sps_body_add_box(w, b, lo, hi, NULL) != SPS_OK ||
        sps_body_constrain_box(w, b, clamp_lo, clamp_hi, SPS_AXIS_ALL, NULL, NULL) != SPS_OK || sps_body_set_velocity(w, b, swing, NULL) != SPS_OK) {
        fprintf(stderr, "tl_hourglass_cost: set-up failed\n");
        exit(1);
    }
    return w;
}

int main(int argc, char** argv) {
    const int rounds = argc > 1 ? atoi(argv[1]) : 200;
    sps_world* w[2] = {plate(SPS_HOURGLASS_VARIATIONAL), plate(SPS_HOURGLASS_PAPER)};
    double wall[2] = {0, 0}, us[2];
    int r, k;
    for (r = 0; r < rounds; ++r)
        for (k = 0; k < 2; ++k) {
            const double t0 = now();
            if (sps_world_step(w[k]) != SPS_OK) {
                fprintf(stderr, "tl_hourglass_cost: %s\n", sps_world_last_error(w[k]));
                return 1;
            }
            wall[k] += now() - t0;
        }
    for (k = 0; k < 2; ++k) {
        sps_diagnostics d;
        sps_world_diagnostics(w[k], (sps_body){0}, &d);
        us[k] = 1e6 * wall[k] / ((double)d.acoustic_steps * sps_world_particle_count(w[k]));
        printf("%-12s %d particles, %ld sub-steps, %.3f us per particle and sub-step\n", k ? "paper" : "variational",
               sps_world_particle_count(w[k]), d.acoustic_steps, us[k]);
        sps_world_destroy(w[k]);
    }
    printf("RESULT case=tl_hourglass_cost rounds=%d variational_us=%.3f paper_us=%.3f ratio=%.2f\n", rounds, us[0], us[1], us[0] / us[1]);
    return 0;
}
