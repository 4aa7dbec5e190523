/* plate3d.h - the 3D simply supported plate of benchmark A2 (bench/VALIDATION.md) (ENO 6.2, ANG 5.1.2): its
   dimensions, material, mode start, supports and set-up. Used by examples/plate3d.c, the tests
   and the gallery; needs only sphsolid.h.

   A square plate L = W = 0.4, H = 0.01 (rho0 1000, E 1e8, nu 0.3) is simply supported: the
   z-velocity of its mid-plane particles on the four lateral sides is held at zero, as ENO 6.2
   describes it (PLATE3D_SUPPORT_EDGE). PLATE3D_SUPPORT_RING adds instead a one-particle ring
   outside [0, L] x [0, W] in the mid plane (the reference code, bench/VALIDATION.md);
   PLATE3D_SUPPORT_THICK makes that ring as thick as the plate, all layers held in z (this
   reproduces the papers' particle counts: 44.7k / 204.0k / 1179.4k at H/dp = 3 / 5 / 9). It
   starts with v_z = sin(m pi x/L) sin(n pi y/W) and vibrates in mode (m, n). */
#ifndef SPS_SCENE_PLATE3D_H
#define SPS_SCENE_PLATE3D_H
#include "scene.h"

#define PLATE3D_L 0.4
#define PLATE3D_W 0.4
#define PLATE3D_H 0.01
#define PLATE3D_RHO0 1000
#define PLATE3D_E 1e8
#define PLATE3D_NU 0.3

enum { PLATE3D_SUPPORT_EDGE, PLATE3D_SUPPORT_RING, PLATE3D_SUPPORT_THICK }; /* --support edge|ring|thick */

typedef struct { int m, n; } plate3d_mode;
SCENE_UNUSED static void plate3d_initial_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const plate3d_mode* md = (const plate3d_mode*)user;
    int inside = x[0] > 0 && x[0] < PLATE3D_L && x[1] > 0 && x[1] < PLATE3D_W;
    v[0] = v[1] = 0;
    v[2] = inside ? sin(md->m * SCENE_PI * x[0] / PLATE3D_L) * sin(md->n * SCENE_PI * x[1] / PLATE3D_W) : 0; /* ANG eq. 53 */
}

typedef struct {
    int res;          /* H/dp */
    plate3d_mode mode;
    int support;      /* PLATE3D_SUPPORT_* */
    double jitter;    /* lattice jitter in dp (scene_add_box), 0 = none */
    int seed;         /* of the jitter */
} plate3d_params;

/* The support ring: one row of particles just outside each edge, in the mid plane z = 0, or
   (full = 1) in every layer of the plate's thickness. */
SCENE_UNUSED static sps_result plate3d_add_support_ring(sps_world* w, sps_body plate, double dp, int res, int full) {
    int nx = (int)(PLATE3D_L / dp + 0.5), ny = (int)(PLATE3D_W / dp + 0.5), i, l, layers = full ? res : 1;
    sps_result r = SPS_OK;
    for (l = 0; l < layers && r == SPS_OK; ++l) {
        const sps_real z = full ? -PLATE3D_H / 2 + (l + 0.5) * dp : 0;
        for (i = -1; i <= nx && r == SPS_OK; ++i) { /* bottom and top rows, corners included */
            sps_real row[6] = {(i + 0.5) * dp, -0.5 * dp, z, (i + 0.5) * dp, PLATE3D_W + 0.5 * dp, z};
            r = sps_body_add_particles(w, plate, 1, row, NULL);
            if (r == SPS_OK) r = sps_body_add_particles(w, plate, 1, row + 3, NULL);
        }
        for (i = 0; i < ny && r == SPS_OK; ++i) { /* left and right columns */
            sps_real column[6] = {-0.5 * dp, (i + 0.5) * dp, z, PLATE3D_L + 0.5 * dp, (i + 0.5) * dp, z};
            r = sps_body_add_particles(w, plate, 1, column, NULL);
            if (r == SPS_OK) r = sps_body_add_particles(w, plate, 1, column + 3, NULL);
        }
    }
    return r;
}

/* The first antinode (L/2m, W/2n, 0) of mode (m, n), where the deflection is observed: the
   papers observe the centre, a node of the mode when m or n is even. */
SCENE_UNUSED static void plate3d_antinode(plate3d_mode md, sps_real x[3]) {
    x[0] = PLATE3D_L / (2 * md.m);
    x[1] = PLATE3D_W / (2 * md.n);
    x[2] = 0;
}

/* Creates the world of wd (dim and dp set here; the caller's other settings kept) holding the
   plate, a body of def bd (named "plate"), simply supported as p->support says, started in
   mode p->mode, and an observer at its first antinode. On error *w is NULL and the message went
   to wd.log. */
SCENE_UNUSED static sps_result plate3d_create(sps_world_def wd, const sps_body_def* bd, const plate3d_params* p, sps_world** w,
                                 sps_body* plate, sps_observer* probe) {
    const double dp = PLATE3D_H / p->res;
    sps_body_def def = *bd;
    sps_real lo[3] = {0, 0, -PLATE3D_H / 2}, hi[3] = {PLATE3D_L, PLATE3D_W, PLATE3D_H / 2}, antinode[3];
    sps_real side_lo[4][3] = {{-1, -1, -1}, {PLATE3D_L, -1, -1}, {-1, -1, -1}, {-1, PLATE3D_W, -1}};
    sps_real side_hi[4][3] = {{0, 1, 1}, {1, 1, 1}, {1, 0, 1}, {1, 1, 1}};
    plate3d_mode md = p->mode;
    sps_result r;
    int k;
    wd.dim = 3;
    wd.dp = dp;
    def.name = "plate";
    if ((r = sps_world_create(&wd, w)) != SPS_OK) return r;
    SCENE_TRY(w, sps_world_add_body(*w, &def, plate));
    SCENE_TRY(w, scene_add_box(*w, *plate, lo, hi, p->jitter, p->seed));
    if (p->support == PLATE3D_SUPPORT_EDGE) { /* the mid-plane particles (the two middle layers when H/dp is even) of the sides */
        for (k = 0; k < 4; ++k) {
            side_lo[k][2] = -0.5001 * dp;
            side_hi[k][2] = 0.5001 * dp;
        }
        side_hi[0][0] = dp; side_lo[1][0] = PLATE3D_L - dp; side_hi[2][1] = dp; side_lo[3][1] = PLATE3D_W - dp;
    } else {
        SCENE_TRY(w, plate3d_add_support_ring(*w, *plate, dp, p->res, p->support == PLATE3D_SUPPORT_THICK));
    }
    for (k = 0; k < 4; ++k) SCENE_TRY(w, sps_body_constrain_box(*w, *plate, side_lo[k], side_hi[k], SPS_AXIS_Z, NULL, NULL));
    SCENE_TRY(w, sps_body_set_velocity(*w, *plate, plate3d_initial_velocity, &md));
    plate3d_antinode(md, antinode);
    SCENE_TRY(w, sps_world_add_observer(*w, *plate, antinode, probe));
    return SPS_OK;
}

#endif
