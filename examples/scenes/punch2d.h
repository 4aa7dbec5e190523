/* punch2d.h - the 2D punch test of benchmark A8 (ENO 6.6; Lee et al. 2013): its dimensions,
   material, rollers and punch. Used by examples/punch2d.c; needs only sphsolid.h.

   A unit square rubber plate [0, 1]^2 (rho0 1100, E 1.7e7, nu 0.45, plane strain) rests on
   rollers at the bottom, left and right: the first particle layer of each edge has only its
   normal velocity held at 0 (mask SPS_AXIS_Y at the bottom, SPS_AXIS_X left and right; the two
   bottom corners, on two rollers, are clamped). The top layer of the right half (x > 1/2) is
   the punch: its vertical velocity is prescribed at -v_punch (mask SPS_AXIS_Y, horizontal free;
   the top-right corner, also on the right roller, has both held: (0, -v_punch)). */
#ifndef SPS_SCENE_PUNCH2D_H
#define SPS_SCENE_PUNCH2D_H
#include "scene.h"

#define PUNCH2D_L 1.0
#define PUNCH2D_RHO0 1100
#define PUNCH2D_E 1.7e7
#define PUNCH2D_NU 0.45
#define PUNCH2D_V 100.0

typedef struct {
    double dp;      /* particle spacing [m] */
    double v_punch; /* punch speed [m/s], downwards */
    double jitter;  /* lattice jitter in dp (scene_add_box), 0 = none */
    int seed;       /* of the jitter */
    int punched;    /* out: number of punch particles */
} punch2d_params;

/* Creates the world of wd (dim and dp set here; the caller's other settings kept) holding the
   plate, a body of def bd named "plate", with its rollers and punch. On error *w is NULL and the
   message went to wd.log. */
SCENE_UNUSED static sps_result punch2d_create(sps_world_def wd, const sps_body_def* bd, punch2d_params* p, sps_world** w, sps_body* plate) {
    const double dp = p->dp, L = PUNCH2D_L, e = 0.5 * dp; /* an edge layer: reference centre within dp/2 + e of the edge */
    sps_body_def def = *bd;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {L, L, 0};
    sps_real vpunch[3] = {0, -p->v_punch, 0};
    sps_result r;
    wd.dim = 2;
    wd.dp = dp;
    def.name = "plate";
    if ((r = sps_world_create(&wd, w)) != SPS_OK) return r;
    SCENE_TRY(w, sps_world_add_body(*w, &def, plate));
    SCENE_TRY(w, scene_add_box(*w, *plate, lo, hi, p->jitter, p->seed));
    { /* rollers: bottom (v_y = 0), left and right (v_x = 0) */
        sps_real blo[3] = {-1, -1, -1}, bhi[3] = {2, dp / 2 + e, 1};
        sps_real llo[3] = {-1, -1, -1}, lhi[3] = {dp / 2 + e, 2, 1};
        sps_real rlo[3] = {L - dp / 2 - e, -1, -1}, rhi[3] = {2, 2, 1};
        SCENE_TRY(w, sps_body_constrain_box(*w, *plate, blo, bhi, SPS_AXIS_Y, NULL, NULL));
        SCENE_TRY(w, sps_body_constrain_box(*w, *plate, llo, lhi, SPS_AXIS_X, NULL, NULL));
        SCENE_TRY(w, sps_body_constrain_box(*w, *plate, rlo, rhi, SPS_AXIS_X, NULL, NULL));
    }
    { /* the punch: top layer of the right half; then the corners on two constraints */
        sps_real plo[3] = {L / 2, L - dp / 2 - e, -1}, phi[3] = {2, 2, 1};
        sps_real c1lo[3] = {-1, -1, -1}, c1hi[3] = {dp / 2 + e, dp / 2 + e, 1};
        sps_real c2lo[3] = {L - dp / 2 - e, -1, -1}, c2hi[3] = {2, dp / 2 + e, 1};
        sps_real c3lo[3] = {L - dp / 2 - e, L - dp / 2 - e, -1}, c3hi[3] = {2, 2, 1};
        SCENE_TRY(w, sps_body_constrain_box(*w, *plate, plo, phi, SPS_AXIS_Y, vpunch, &p->punched));
        SCENE_TRY(w, sps_body_constrain_box(*w, *plate, c1lo, c1hi, SPS_AXIS_ALL, NULL, NULL));
        SCENE_TRY(w, sps_body_constrain_box(*w, *plate, c2lo, c2hi, SPS_AXIS_ALL, NULL, NULL));
        SCENE_TRY(w, sps_body_constrain_box(*w, *plate, c3lo, c3hi, SPS_AXIS_ALL, vpunch, NULL));
    }
    return SPS_OK;
}

/* Pressure smoothness: RMS over particles of (p_i - <p>_i) / max|p|, where <p>_i is the
   Shepard kernel average sum_{j != i} p_j W_ij / sum_{j != i} W_ij of the neighbours'
   pressure (current positions, world kernel). 0 for a linear or constant field inside;
   a checkerboard (spurious pressure mode) gives O(1). O(N^2): for the small punch plates. */
SCENE_UNUSED static double punch2d_pressure_roughness(const sps_world* w) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* p = sps_world_field(w, SPS_FIELD_PRESSURE);
    const sps_world_def* wd = sps_world_get_def(w);
    const double support = 2 * wd->h_over_dp * wd->dp;
    int n = sps_world_particle_count(w), i, j, m = 0;
    double pmax = 0, sum2 = 0;
    for (i = 0; i < n; ++i) pmax = fmax(pmax, fabs(p[i]));
    if (pmax == 0) return 0;
    for (i = 0; i < n; ++i) {
        double sw = 0, swp = 0;
        for (j = 0; j < n; ++j) {
            double dx = x[i] - x[j], dy = y[i] - y[j], r2 = dx * dx + dy * dy, wij;
            if (j == i || r2 >= support * support) continue;
            wij = sps_world_kernel(w, sqrt(r2));
            sw += wij;
            swp += wij * p[j];
        }
        if (sw > 0) {
            double d = (p[i] - swp / sw) / pmax;
            sum2 += d * d;
            ++m;
        }
    }
    return m ? sqrt(sum2 / m) : 0;
}

#endif
