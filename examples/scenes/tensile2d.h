/* tensile2d.h - the tensile test of benchmark A7 (ENO 6.5, after Lee et al. 2013): a unit square
   plate (rho0 7000, E 2.1e10, nu 0.3, plane strain) whose bottom edge is fixed and whose top
   edge is pulled up at v_pull = 500 m/s. Used by examples/tensile2d.c; needs only sphsolid.h.

   The plate [0, 1] x [0, 1] continues into two holders of TENSILE2D_HOLDER_LAYERS layers: below
   y = 0 (clamped) and above y = 1 (velocity held at (0, v_pull)). */
#ifndef SPS_SCENE_TENSILE2D_H
#define SPS_SCENE_TENSILE2D_H
#include "scene.h"

#define TENSILE2D_L 1.0
#define TENSILE2D_RHO0 7000
#define TENSILE2D_E 2.1e10
#define TENSILE2D_NU 0.3
#define TENSILE2D_HOLDER_LAYERS 4 /* more than the kernel support (2.6 dp) */

typedef struct {
    double dp;     /* particle spacing */
    double v_pull; /* velocity of the top holder [m/s] */
} tensile2d_params;

/* Creates the world of wd (dim set here, dp = L / round(L / p->dp)) holding the plate, a body of def bd (named
   "plate"), clamped below y = 0 and pulled above y = L. On error *w is NULL. */
SCENE_UNUSED static sps_result tensile2d_create(sps_world_def wd, const sps_body_def* bd, const tensile2d_params* p, sps_world** w,
                                                sps_body* plate) {
    /* dp rounded to a whole number of particles across L (--dp 0.0666667 is 1/15, not 14 columns) */
    const double dp = TENSILE2D_L / floor(TENSILE2D_L / p->dp + 0.5), hl = TENSILE2D_HOLDER_LAYERS * dp;
    sps_body_def def = *bd;
    sps_real lo[3] = {0, -hl, 0}, hi[3] = {TENSILE2D_L, TENSILE2D_L + hl, 0};
    sps_real bot_lo[3] = {-1, -1, -1}, bot_hi[3] = {2, 0, 1}, top_lo[3] = {-1, TENSILE2D_L, -1}, top_hi[3] = {2, 3, 1};
    sps_real v[3] = {0, 0, 0};
    sps_result r;
    v[1] = p->v_pull;
    wd.dim = 2;
    wd.dp = dp;
    def.name = "plate";
    if ((r = sps_world_create(&wd, w)) != SPS_OK) return r;
    SCENE_TRY(w, sps_world_add_body(*w, &def, plate));
    SCENE_TRY(w, sps_body_add_box(*w, *plate, lo, hi, NULL));
    SCENE_TRY(w, sps_body_constrain_box(*w, *plate, bot_lo, bot_hi, SPS_AXIS_ALL, NULL, NULL));
    SCENE_TRY(w, sps_body_constrain_box(*w, *plate, top_lo, top_hi, SPS_AXIS_ALL, v, NULL));
    return SPS_OK;
}

/* The deformed extent of the plate proper (reference 0 <= y <= L): the width of the row of
   particles nearest mid height (max x - min x, plus dp for the particles' own extent), its
   height (max y - min y, plus dp) and the narrowest row width over all rows (the neck). */
SCENE_UNUSED static void tensile2d_extent(const sps_world* w, double* width_mid, double* height, double* neck) {
    const double dp = sps_world_get_def(w)->dp;
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* y0 = sps_world_field(w, SPS_FIELD_REFERENCE_Y);
    int n = sps_world_particle_count(w), i, rows = (int)floor(TENSILE2D_L / dp + 0.5), k;
    double ylo = 1e30, yhi = -1e30, *rlo, *rhi, ymid = 0.5 * TENSILE2D_L, best = 1e30;
    int kmid = 0;
    rlo = (double*)malloc(sizeof(double) * 2 * (size_t)rows);
    rhi = rlo + rows;
    for (k = 0; k < rows; ++k) { rlo[k] = 1e30; rhi[k] = -1e30; }
    for (k = 0; k < rows; ++k) /* the row whose reference y is nearest mid height */
        if (fabs((k + 0.5) * dp - ymid) < best) { best = fabs((k + 0.5) * dp - ymid); kmid = k; }
    for (i = 0; i < n; ++i) {
        if (y0[i] < 0 || y0[i] > TENSILE2D_L) continue;
        k = (int)floor(y0[i] / dp);
        if (k < 0 || k >= rows) continue;
        if (y[i] < ylo) ylo = y[i];
        if (y[i] > yhi) yhi = y[i];
        if (x[i] < rlo[k]) rlo[k] = x[i];
        if (x[i] > rhi[k]) rhi[k] = x[i];
    }
    *width_mid = rhi[kmid] - rlo[kmid] + dp;
    *height = yhi - ylo + dp;
    *neck = 1e30;
    for (k = 0; k < rows; ++k)
        if (rhi[k] >= rlo[k] && rhi[k] - rlo[k] + dp < *neck) *neck = rhi[k] - rlo[k] + dp;
    free(rlo);
}

#endif
