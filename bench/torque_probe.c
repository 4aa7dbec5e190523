/* torque_probe - where the spurious torque of a spinning body comes from.

   Spins the unit square (benchmark A3, bench/VALIDATION.md) or cube (A4) about z and, every 0.02 s, prints the
   torque about the centre of the two accelerations the kick applies: the pressure force acc_p
   (at the half-step positions it was computed at) and the accumulated shear acceleration a_s
   (rotated half a step ahead, at the positions of the next kick, as sps__kick applies it). Their
   sum is dL/dt: compare with the printed angular momentum. This program reads library
   internals (world fields), so it is a diagnostic, not an example of the API.

   Usage: ./build/torque_probe [dim 2|3] [dp] [nu] [shear 0..5]   (defaults: 2 0.05 0.45 1 = ENO-A) */
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "kick_shear.h"

static void rigid_rotation(const sps_real x[3], sps_real v[3], void* user) {
    double omega = *(const double*)user;
    v[0] = -omega * x[1];
    v[1] = omega * x[0];
    v[2] = 0;
}

/* z-torques of m acc_p at x - dt/2 v (the half-step positions it was computed at) and of m a_s as
   the next kick applies it (kick_shear.h) */
static void torques(const sps_world* w, double* pressure, double* shear) {
    const double dt = w->dt;
    sps_real H[9];
    double xs[2], as[2];
    int i;
    kick_half_rotation(w, H);
    *pressure = *shear = 0;
    for (i = 0; i < w->n; ++i) {
        const double m = w->mass[i], x = w->pos[0][i] - 0.5 * dt * w->vel[0][i], y = w->pos[1][i] - 0.5 * dt * w->vel[1][i];
        *pressure += m * (x * w->acc_p[1][i] - y * w->acc_p[0][i]);
        kick_shear_xy(w, H, i, xs, as);
        *shear += m * (xs[0] * as[1] - xs[1] * as[0]);
    }
}

int main(int argc, char** argv) {
    const int dim = argc > 1 ? atoi(argv[1]) : 2, shear = argc > 4 ? atoi(argv[4]) : SPS_SHEAR_ENO_A;
    double omega = 50, t, L0 = 0;
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_real lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {0.5, 0.5, 0.5};
    sps_world* w;
    sps_body body, all = {0};
    wd.dim = dim;
    wd.dp = argc > 2 ? atof(argv[2]) : 0.05;
    bd.material.density = 1100;
    bd.material.youngs_modulus = 1.7e7;
    bd.material.poisson_ratio = argc > 3 ? atof(argv[3]) : 0.45;
    bd.shear = (sps_shear)shear;
    if (sps_world_create(&wd, &w) != SPS_OK || sps_world_add_body(w, &bd, &body) != SPS_OK ||
        sps_body_add_box(w, body, lo, hi, NULL) != SPS_OK || sps_body_set_velocity(w, body, rigid_rotation, &omega) != SPS_OK) {
        fprintf(stderr, "torque_probe: bad arguments\n");
        return 2;
    }
    printf("     t   torque(acc_p)   torque(a_s)   L_z        dL_z/dt (last 0.02 s)\n");
    for (t = 0.02; t <= 0.2 + 1e-9; t += 0.02) {
        sps_diagnostics d;
        double tp, ts, L_prev = L0;
        if (sps_world_advance(w, (sps_real)t, NULL, NULL) != SPS_OK) {
            fprintf(stderr, "torque_probe: %s\n", sps_world_last_error(w));
            return 1;
        }
        torques(w, &tp, &ts);
        sps_world_diagnostics(w, all, &d);
        L0 = d.angular_momentum[2];
        printf("%6.2f %14.3g %13.4g %10.2f %10.4g\n", t, tp, ts, L0, t > 0.021 ? (L0 - L_prev) / 0.02 : 0.0);
    }
    sps_world_destroy(w);
    return 0;
}
