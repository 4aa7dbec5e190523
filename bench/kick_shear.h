/* kick_shear.h - the accumulated shear acceleration a_s of a particle as the next kick applies it,
   for the diagnostics bench/torque_probe.c and bench/rotation_probe.c (they read library
   internals; include after the implementation of sphsolid.h).

   sps__kick turns a_s by half a step of the body's mean rotation (H below) and applies it half a
   step after the continuity pass, at x + dt/2 v: the torque of m a_s about the origin is the
   torque of these values. */
#ifndef SPS_BENCH_KICK_SHEAR_H
#define SPS_BENCH_KICK_SHEAR_H

/* H: the rotation by half a step of the first body's mean spin */
static void kick_half_rotation(const sps_world* w, sps_real H[9]) {
    sps__rodrigues(w->bodies[0].mean_spin, SPS_R(0.5) * w->dt, w->dim, H);
}

/* x and y of particle i's position at the next kick and of H a_s there */
static void kick_shear_xy(const sps_world* w, const sps_real H[9], int i, double pos[2], double acc[2]) {
    const double dt = w->dt, az = w->dim == 3 ? w->acc_s[2][i] : 0;
    pos[0] = w->pos[0][i] + 0.5 * dt * w->vel[0][i];
    pos[1] = w->pos[1][i] + 0.5 * dt * w->vel[1][i];
    acc[0] = H[0] * w->acc_s[0][i] + H[1] * w->acc_s[1][i] + H[2] * az;
    acc[1] = H[3] * w->acc_s[0][i] + H[4] * w->acc_s[1][i] + H[5] * az;
}

#endif
