/* balls3d.h - the 3D colliding hollow rubber balls of benchmark A6 (ENO 6.4): shells of inner
   radius 0.03 and outer radius 0.04, centres 0.09 apart on the x axis, each moving towards the
   other at v0 (rho0 1200, E 1e7, nu 0.4). Used by examples/balls3d.c; needs only sphsolid.h.

   The left ball is filled (lattice, or relaxed to a body-fitted distribution with
   sps_body_add_sdf_relaxed, as the paper's Yu et al. fill) in a scratch world; the right ball
   is the mirror image x -> -x of its particles, so that the two are identical by symmetry. */
#ifndef SPS_SCENE_BALLS3D_H
#define SPS_SCENE_BALLS3D_H
#include <string.h>
#include "scene.h"

#define BALLS3D_R_IN 0.03
#define BALLS3D_R_OUT 0.04
#define BALLS3D_GAP 0.09 /* centre distance */
#define BALLS3D_RHO0 1200
#define BALLS3D_E 1e7
#define BALLS3D_NU 0.4

/* Signed distance of the shell centred at (cx, 0, 0) (user: &cx): negative inside the wall. */
SCENE_UNUSED static sps_real balls3d_shell_sdf(const sps_real x[3], void* user) {
    double cx = *(const double*)user, dx = x[0] - cx, r = sqrt(dx * dx + x[1] * x[1] + x[2] * x[2]);
    return (sps_real)fmax(r - BALLS3D_R_OUT, BALLS3D_R_IN - r);
}

typedef struct { double v; } balls3d_speed;
SCENE_UNUSED static void balls3d_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)x;
    v[0] = ((const balls3d_speed*)user)->v;
    v[1] = v[2] = 0;
}

typedef struct {
    double dp;       /* particle spacing [m] */
    double v0_c0;    /* speed of each ball / c0 */
    int relaxed;     /* 1: sps_body_add_sdf_relaxed, 0: lattice */
    int iterations;  /* relaxation steps, 0 = the library's default */
    /* out */
    int per_ball;
    double fill_s;   /* wall time of the fill [s] */
    sps_fill_quality quality; /* of the left ball's points */
} balls3d_params;

/* Creates the world of wd (dim 3, dp set here) with bodies left and right of def bd (named
   "left", "right"), moving towards each other at v0_c0 c0. wall_fn (may be NULL) times the fill.
   On error *w is NULL and the message went to wd.log. */
SCENE_UNUSED static sps_result balls3d_create(sps_world_def wd, const sps_body_def* bd, balls3d_params* p, double (*wall_fn)(void),
                                              sps_world** w, sps_body* left, sps_body* right) {
    double cx = -BALLS3D_GAP / 2, m = 2.5 * p->dp;
    sps_real lo[3] = {cx - BALLS3D_R_OUT - m, -BALLS3D_R_OUT - m, -BALLS3D_R_OUT - m};
    sps_real hi[3] = {cx + BALLS3D_R_OUT + m, BALLS3D_R_OUT + m, BALLS3D_R_OUT + m};
    sps_body_def def = *bd;
    sps_world* tmp = NULL;
    sps_body tb;
    sps_real *xyz = NULL, c0;
    balls3d_speed sl, sr;
    const sps_real* f[3];
    int n, i, a;
    double t0 = wall_fn ? wall_fn() : 0;
    sps_result r;
    wd.dim = 3;
    wd.dp = p->dp;
    *w = NULL;
    /* the left ball in a scratch world */
    if ((r = sps_world_create(&wd, &tmp)) != SPS_OK) return r;
    SCENE_TRY(&tmp, sps_world_add_body(tmp, &def, &tb));
    if (p->relaxed) SCENE_TRY(&tmp, sps_body_add_sdf_relaxed(tmp, tb, lo, hi, balls3d_shell_sdf, &cx, p->iterations, &n));
    else SCENE_TRY(&tmp, sps_body_add_sdf(tmp, tb, lo, hi, balls3d_shell_sdf, &cx, &n));
    n = sps_world_particle_count(tmp);
    f[0] = sps_world_field(tmp, SPS_FIELD_POSITION_X);
    f[1] = sps_world_field(tmp, SPS_FIELD_POSITION_Y);
    f[2] = sps_world_field(tmp, SPS_FIELD_POSITION_Z);
    if (!(xyz = (sps_real*)malloc(sizeof(sps_real) * 3 * (size_t)n))) { sps_world_destroy(tmp); return SPS_ERR_OUT_OF_MEMORY; }
    for (i = 0; i < n; ++i)
        for (a = 0; a < 3; ++a) xyz[3 * i + a] = f[a][i];
    p->fill_s = wall_fn ? wall_fn() - t0 : 0;
    r = sps_measure_fill(tmp, n, xyz, lo, hi, balls3d_shell_sdf, &cx, &p->quality);
    sps_world_destroy(tmp);
    if (r != SPS_OK) { free(xyz); return r; }
    p->per_ball = n;
    /* the two balls: left as filled, right its mirror image */
    if ((r = sps_world_create(&wd, w)) != SPS_OK) { free(xyz); return r; }
    def.name = "left";
    if ((r = sps_world_add_body(*w, &def, left)) != SPS_OK || (r = sps_body_add_particles(*w, *left, n, xyz, NULL)) != SPS_OK) goto fail;
    for (i = 0; i < n; ++i) xyz[3 * i] = -xyz[3 * i];
    def.name = "right";
    if ((r = sps_world_add_body(*w, &def, right)) != SPS_OK || (r = sps_body_add_particles(*w, *right, n, xyz, NULL)) != SPS_OK) goto fail;
    if ((r = sps_body_material_constants(*w, *left, &c0, NULL, NULL)) != SPS_OK) goto fail;
    sl.v = p->v0_c0 * c0;
    sr.v = -sl.v;
    if ((r = sps_body_set_velocity(*w, *left, balls3d_velocity, &sl)) != SPS_OK) goto fail;
    if ((r = sps_body_set_velocity(*w, *right, balls3d_velocity, &sr)) != SPS_OK) goto fail;
    free(xyz);
    return SPS_OK;
fail:
    free(xyz);
    sps_world_destroy(*w);
    *w = NULL;
    return r;
}

/* Smallest distance between a particle of body a and one of body b (current positions), / dp.
   Only particles within 3 dp (in x) of the other body's x range are compared. After the first
   step (sps_body_field). Returns a large value when nothing is close. */
SCENE_UNUSED static double balls3d_min_gap(const sps_world* w, sps_body a, sps_body b) {
    const double dp = sps_world_get_def(w)->dp;
    const sps_real *ax, *ay, *az, *bx, *by, *bz;
    int na, nb, i, j, *ia, *ib, ka = 0, kb = 0;
    double amax = -1e30, bmin = 1e30, best = 1e30;
    ax = sps_body_field(w, a, "position_x", NULL, NULL, &na);
    ay = sps_body_field(w, a, "position_y", NULL, NULL, NULL);
    az = sps_body_field(w, a, "position_z", NULL, NULL, NULL);
    bx = sps_body_field(w, b, "position_x", NULL, NULL, &nb);
    by = sps_body_field(w, b, "position_y", NULL, NULL, NULL);
    bz = sps_body_field(w, b, "position_z", NULL, NULL, NULL);
    if (!ax || !bx || !ay || !by || !az || !bz) return -1;
    for (i = 0; i < na; ++i) amax = fmax(amax, ax[i]);
    for (j = 0; j < nb; ++j) bmin = fmin(bmin, bx[j]);
    if (bmin - amax > 3 * dp) return (bmin - amax) / dp;
    ia = (int*)malloc(sizeof(int) * (size_t)na);
    ib = (int*)malloc(sizeof(int) * (size_t)nb);
    if (!ia || !ib) { free(ia); free(ib); return -1; }
    for (i = 0; i < na; ++i) if (ax[i] > bmin - 3 * dp) ia[ka++] = i;
    for (j = 0; j < nb; ++j) if (bx[j] < amax + 3 * dp) ib[kb++] = j;
    for (i = 0; i < ka; ++i)
        for (j = 0; j < kb; ++j) {
            double dx = ax[ia[i]] - bx[ib[j]], dy = ay[ia[i]] - by[ib[j]], dz = az[ia[i]] - bz[ib[j]];
            double r2 = dx * dx + dy * dy + dz * dz;
            if (r2 < best) best = r2;
        }
    free(ia);
    free(ib);
    return sqrt(best) / dp;
}

#endif
