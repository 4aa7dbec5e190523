/* ball_plate.h - a rubber ball hitting a plate held at its ends, benchmarks A9 (2D, ENO 6.7) and
   A10 (3D, ENO 6.8). Used by examples/ball_plate2d.c (built as ball_plate3d too) and
   bench/particle_cost.c; needs only sphsolid.h.

   Ball radius 0.05 centred at (0, 0.1, 0), moving at (0, -v0, 0); plate 0.5 long (x, and z in
   3D) and 0.02 thick (y in [-0.01, 0.01]), both rho0 1200, E 1e7, nu 0.49 (c0 = 372.68 m/s).
   The plate continues into holders of BALL_PLATE_HOLDER_LAYERS layers beyond its ends (2D: x
   < -0.25 and x > 0.25; 3D: all four edges) whose particles are clamped. The two bodies touch
   through the library's contact (body def contact = 1). */
#ifndef SPS_SCENE_BALL_PLATE_H
#define SPS_SCENE_BALL_PLATE_H
#include <stdlib.h>
#include "scene.h"

#define BALL_PLATE_RADIUS 0.05
#define BALL_PLATE_CENTRE_Y 0.1
#define BALL_PLATE_LENGTH 0.5
#define BALL_PLATE_THICKNESS 0.02
#define BALL_PLATE_RHO0 1200
#define BALL_PLATE_E 1e7
#define BALL_PLATE_NU 0.49
#define BALL_PLATE_HOLDER_LAYERS 4 /* more than the kernel support (2.6 dp) */

typedef struct {
    int dim;
    double dp;
    double v0;          /* ball speed [m/s] (downwards) */
    int relaxed;        /* 1: ball by sps_body_add_sdf_relaxed, 0: lattice (sps_body_add_sdf) */
    int relax_iterations; /* 0: the library's default (300) */
} ball_plate_params;

typedef struct { int dim; } ball_plate_sdf_ctx;
SCENE_UNUSED static sps_real ball_plate_sdf(const sps_real x[3], void* user) {
    const ball_plate_sdf_ctx* c = (const ball_plate_sdf_ctx*)user;
    double dy = x[1] - BALL_PLATE_CENTRE_Y, r2 = x[0] * x[0] + dy * dy + (c->dim == 3 ? x[2] * x[2] : 0);
    return (sps_real)(sqrt(r2) - BALL_PLATE_RADIUS);
}
SCENE_UNUSED static void ball_plate_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)x;
    v[0] = 0; v[1] = -*(const double*)user; v[2] = 0;
}

/* Creates the world of wd (dim and dp set here) with the plate (named "plate") and the ball
   ("ball"), both of def bd. On error *w is NULL and the message went to wd.log. */
SCENE_UNUSED static sps_result ball_plate_create(sps_world_def wd, const sps_body_def* bd, const ball_plate_params* p, sps_world** w,
                                                 sps_body* ball, sps_body* plate) {
    const double dp = p->dp, hl = BALL_PLATE_HOLDER_LAYERS * dp, a = 0.5 * BALL_PLATE_LENGTH, t = 0.5 * BALL_PLATE_THICKNESS;
    const double R = BALL_PLATE_RADIUS, cy = BALL_PLATE_CENTRE_Y;
    sps_body_def pd = *bd, bdd = *bd;
    sps_real lo[3] = {-a - hl, -t, p->dim == 3 ? -a - hl : 0}, hi[3] = {a + hl, t, p->dim == 3 ? a + hl : 0};
    sps_real blo[3] = {-R - dp, cy - R - dp, p->dim == 3 ? -R - dp : 0}, bhi[3] = {R + dp, cy + R + dp, p->dim == 3 ? R + dp : 0};
    ball_plate_sdf_ctx sdf = {p->dim};
    double v0 = p->v0;
    int axis;
    sps_result r;
    wd.dim = p->dim;
    wd.dp = dp;
    pd.name = "plate";
    bdd.name = "ball";
    if ((r = sps_world_create(&wd, w)) != SPS_OK) return r;
    SCENE_TRY(w, sps_world_add_body(*w, &pd, plate));
    SCENE_TRY(w, sps_world_add_body(*w, &bdd, ball));
    SCENE_TRY(w, sps_body_add_box(*w, *plate, lo, hi, NULL));
    for (axis = 0; axis < (p->dim == 3 ? 3 : 1); axis += 2) { /* the holders beyond x = +-a (and z = +-a in 3D) */
        sps_real clo[3] = {-1, -1, -1}, chi[3] = {1, 1, 1};
        chi[axis] = -a; /* x < -a */
        SCENE_TRY(w, sps_body_constrain_box(*w, *plate, clo, chi, SPS_AXIS_ALL, NULL, NULL));
        chi[axis] = 1; clo[axis] = a; /* x > a */
        SCENE_TRY(w, sps_body_constrain_box(*w, *plate, clo, chi, SPS_AXIS_ALL, NULL, NULL));
    }
    if (p->relaxed) SCENE_TRY(w, sps_body_add_sdf_relaxed(*w, *ball, blo, bhi, ball_plate_sdf, &sdf, p->relax_iterations, NULL));
    else SCENE_TRY(w, sps_body_add_sdf(*w, *ball, blo, bhi, ball_plate_sdf, &sdf, NULL));
    SCENE_TRY(w, sps_body_set_velocity(*w, *ball, ball_plate_velocity, &v0));
    return SPS_OK;
}

#endif
