/* spinning.h - the spinning plate (2D, benchmark A3 (bench/VALIDATION.md), ENO 6.10, ANG 5.1.3) and the spinning
   cube (3D, A4, ANG 5.1.4): their material, set-up and angular-momentum error. Used by
   examples/spinning_plate.c, examples/spinning_cube.c, bench/realtime.c and the gallery; needs
   only sphsolid.h.

   A unit square (cube) centred at the origin, rho0 1100, E 1.7e7, nu 0.45 (cube: 0.3), starts
   in rigid rotation at omega about z with no constraint (and, with drift, carried along x).
   Linear and angular momentum are exactly conserved in theory (about the origin: the centre
   moves along the drift, so the drift adds no angular momentum). */
#ifndef SPS_SCENE_SPINNING_H
#define SPS_SCENE_SPINNING_H
#include "scene.h"

#define SPINNING_RHO0 1100
#define SPINNING_E 1.7e7
#define SPINNING_NU_2D 0.45
#define SPINNING_NU_3D 0.3

typedef struct {
    int dim;        /* 2: the plate, 3: the cube */
    double dp;      /* particle spacing [m] */
    double omega;   /* angular velocity [rad/s] */
    double drift;   /* a uniform velocity along x added to the rotation [m/s] (0: the benchmark) */
    double jitter;  /* lattice jitter in dp (scene_add_box), 0 = none */
    int seed;       /* of the jitter */
} spinning_params;

SCENE_UNUSED static void spinning_rigid_rotation(const sps_real x[3], sps_real v[3], void* user) {
    const spinning_params* p = (const spinning_params*)user; /* v = omega e_z x r + drift e_x */
    v[0] = -p->omega * x[1] + p->drift;
    v[1] = p->omega * x[0];
    v[2] = 0;
}

/* Creates the world of wd (dim and dp set here; the caller's other settings kept) holding the
   block, a body of def bd named name, spinning at p->omega. On error *w is NULL and the message
   went to wd.log. */
SCENE_UNUSED static sps_result spinning_create(sps_world_def wd, const sps_body_def* bd, const char* name, const spinning_params* p,
                                  sps_world** w, sps_body* block) {
    sps_body_def def = *bd;
    sps_real lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {0.5, 0.5, 0.5};
    sps_result r;
    wd.dim = p->dim;
    wd.dp = p->dp;
    def.name = name;
    if ((r = sps_world_create(&wd, w)) != SPS_OK) return r;
    SCENE_TRY(w, sps_world_add_body(*w, &def, block));
    SCENE_TRY(w, scene_add_box(*w, *block, lo, hi, p->jitter, p->seed));
    SCENE_TRY(w, sps_body_set_velocity(*w, *block, spinning_rigid_rotation, (void*)p));
    return SPS_OK;
}

/* sum m |v| (v_z = 0): the scale of the linear-momentum drift. */
SCENE_UNUSED static double spinning_momentum_scale(const sps_world* w) {
    const sps_real *vx = sps_world_field(w, SPS_FIELD_VELOCITY_X), *vy = sps_world_field(w, SPS_FIELD_VELOCITY_Y);
    const sps_real* m = sps_world_field(w, SPS_FIELD_MASS);
    double scale = 0;
    int i;
    for (i = 0; i < sps_world_particle_count(w); ++i) scale += m[i] * sqrt(vx[i] * vx[i] + vy[i] * vy[i]); /* v_z = 0 */
    return scale;
}

/* |L_z(t) - L_z(0)| / |L_z(0)|: theory conserves the angular momentum exactly. */
SCENE_UNUSED static double spinning_angmom_error(const sps_diagnostics* d, const sps_diagnostics* d0) {
    return fabs(d->angular_momentum[2] - d0->angular_momentum[2]) / fabs(d0->angular_momentum[2]);
}

#endif
