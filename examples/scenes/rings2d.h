/* rings2d.h - two rubber rings thrown at each other, benchmark A5 (ENO 6.3; bench/VALIDATION.md):
   rings of inner radius 0.03 and outer radius 0.04, centres 0.09 apart, each moving towards the
   other at v0; rho0 = 1200, E = 1e7, nu = 0.4 (c0 = 117.85 m/s), dp = 0.001 in the paper. The
   right ring is the mirror image (x -> -x) of the left one's particles, so the two are the same
   body by symmetry. Used by examples/rings2d.c. */
#ifndef SPS_SCENE_RINGS2D_H
#define SPS_SCENE_RINGS2D_H
#include "scene.h"

#define RINGS2D_RHO0 1200.0
#define RINGS2D_E 1e7
#define RINGS2D_NU 0.4
#define RINGS2D_INNER 0.03
#define RINGS2D_OUTER 0.04
#define RINGS2D_HALF_GAP 0.045 /* each centre's distance from x = 0 */

typedef struct {
    double dp;      /* particle spacing [m] */
    double v0_c0;   /* speed of each ring in units of c0 */
    int relaxed;    /* 1: body-fitted particles (sps_body_add_sdf_relaxed), 0: lattice */
    int iterations; /* of the relaxation (0: the library's default) */
} rings2d_params;

/* The left ring's signed distance: |r - r_mid| - half the wall thickness, centre (-0.045, 0). */
static sps_real rings2d_sdf(const sps_real x[3], void* user) {
    const double dx = x[0] + RINGS2D_HALF_GAP, dy = x[1], r = sqrt(dx * dx + dy * dy);
    (void)user;
    return (sps_real)(fabs(r - 0.5 * (RINGS2D_INNER + RINGS2D_OUTER)) - 0.5 * (RINGS2D_OUTER - RINGS2D_INNER));
}

/* Analytical kinetic energy of one ring [J/m]: 1/2 rho0 pi (R^2 - r^2) v0^2. */
SCENE_UNUSED static double rings2d_kinetic_energy(double v0) {
    return 0.5 * RINGS2D_RHO0 * SCENE_PI * (RINGS2D_OUTER * RINGS2D_OUTER - RINGS2D_INNER * RINGS2D_INNER) * v0 * v0;
}

static void rings2d_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)x;
    v[0] = *(const sps_real*)user;
    v[1] = v[2] = 0;
}

/* The left ring's particles, lattice or relaxed, filled into a scratch world (same dp and h):
   *xyz (malloc'ed, 3 reals each) and *n. */
static sps_result rings2d_left_particles(sps_world_def wd, const sps_body_def* bd, const rings2d_params* p, sps_real** xyz, int* n) {
    const sps_real lo[3] = {(sps_real)(-RINGS2D_HALF_GAP - RINGS2D_OUTER), (sps_real)-RINGS2D_OUTER, 0};
    const sps_real hi[3] = {(sps_real)(-RINGS2D_HALF_GAP + RINGS2D_OUTER), (sps_real)RINGS2D_OUTER, 0};
    sps_world* scratch;
    sps_body ring;
    sps_result r;
    const sps_real *x, *y;
    int k;
    *xyz = NULL;
    *n = 0;
    if ((r = sps_world_create(&wd, &scratch)) != SPS_OK) return r;
    if ((r = sps_world_add_body(scratch, bd, &ring)) == SPS_OK)
        r = p->relaxed ? sps_body_add_sdf_relaxed(scratch, ring, lo, hi, rings2d_sdf, NULL, p->iterations, n)
                       : sps_body_add_sdf(scratch, ring, lo, hi, rings2d_sdf, NULL, n);
    if (r == SPS_OK && !(*xyz = (sps_real*)malloc(sizeof(sps_real) * 3 * (size_t)(*n > 0 ? *n : 1)))) r = SPS_ERR_OUT_OF_MEMORY;
    x = sps_world_field(scratch, SPS_FIELD_POSITION_X); /* in the order of addition: no step taken */
    y = sps_world_field(scratch, SPS_FIELD_POSITION_Y);
    for (k = 0; r == SPS_OK && k < *n; ++k) {
        (*xyz)[3 * k] = x[k];
        (*xyz)[3 * k + 1] = y[k];
        (*xyz)[3 * k + 2] = 0;
    }
    sps_world_destroy(scratch);
    return r;
}

/* Creates the world (wd: dim 2, dp from p), the left ring and its mirror image moving towards
   each other at v0 = p->v0_c0 c0. */
SCENE_UNUSED static sps_result rings2d_create(sps_world_def wd, const sps_body_def* bd_in, const rings2d_params* p, sps_world** out,
                                              sps_body* left, sps_body* right) {
    sps_body_def bd = *bd_in;
    sps_real *xyz = NULL, c0, v;
    sps_result r;
    int n = 0, k;
    *out = NULL;
    wd.dim = 2;
    wd.dp = (sps_real)p->dp;
    if ((r = rings2d_left_particles(wd, &bd, p, &xyz, &n)) != SPS_OK) { free(xyz); return r; }
    if ((r = sps_world_create(&wd, out)) != SPS_OK) { free(xyz); return r; }
    bd.name = "left ring";
    if ((r = sps_world_add_body(*out, &bd, left)) == SPS_OK) r = sps_body_add_particles(*out, *left, n, xyz, NULL);
    for (k = 0; k < n; ++k) xyz[3 * k] = -xyz[3 * k]; /* mirror image */
    bd.name = "right ring";
    if (r == SPS_OK && (r = sps_world_add_body(*out, &bd, right)) == SPS_OK) r = sps_body_add_particles(*out, *right, n, xyz, NULL);
    free(xyz);
    if (r == SPS_OK) r = sps_body_material_constants(*out, *left, &c0, NULL, NULL);
    v = (sps_real)(p->v0_c0 * c0);
    if (r == SPS_OK) r = sps_body_set_velocity(*out, *left, rings2d_velocity, &v);
    v = -v;
    if (r == SPS_OK) r = sps_body_set_velocity(*out, *right, rings2d_velocity, &v);
    return r;
}
#endif
