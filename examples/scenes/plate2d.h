/* plate2d.h - the 2D oscillating plate (cantilever) of benchmark A1 (bench/VALIDATION.md) (ENO 6.1, ANG 5.1.1):
   its dimensions, material, first-mode start and set-up. Used by examples/plate2d.c, the tests
   and the gallery; needs only sphsolid.h.

   A plate L = 0.2 x H = 0.02 (rho0 1000, E 2e6, nu 0.3975, plane strain) continues into a
   holder for x < 0 whose particles are clamped. It starts from the first bending mode,
   v_y(x) = v_f c0 f(x)/f(L), and swings freely. */
#ifndef SPS_SCENE_PLATE2D_H
#define SPS_SCENE_PLATE2D_H
#include "scene.h"

#define PLATE2D_L 0.2
#define PLATE2D_H 0.02
#define PLATE2D_RHO0 1000
#define PLATE2D_E 2e6
#define PLATE2D_NU 0.3975
#define PLATE2D_HOLDER_LAYERS 4 /* clamp depth in dp: more than the kernel support (2.6 dp), so
                                   longer holders (the reference code uses 0.06) give identical results */
#define PLATE2D_KL 1.875        /* first root of cos(kL) cosh(kL) = -1 */

/* First-mode shape f(x) of a clamped-free beam (ENO eq. 33). */
SCENE_UNUSED static double plate2d_mode_shape(double x) {
    double k = PLATE2D_KL / PLATE2D_L, kl = PLATE2D_KL;
    return (sin(kl) + sinh(kl)) * (cos(k * x) - cosh(k * x)) - (cos(kl) + cosh(kl)) * (sin(k * x) - sinh(k * x));
}

typedef struct { double vf, c0; } plate2d_start;
SCENE_UNUSED static void plate2d_initial_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const plate2d_start* s = (const plate2d_start*)user;
    v[0] = 0;
    v[1] = x[0] > 0 ? s->vf * s->c0 * plate2d_mode_shape(x[0]) / plate2d_mode_shape(PLATE2D_L) : 0; /* ENO eq. 32 */
}

typedef struct {
    int res;         /* H/dp */
    double vf;       /* initial velocity factor v_f */
    double jitter;   /* lattice jitter in dp (scene_add_box), 0 = none */
    int seed;        /* of the jitter */
} plate2d_params;

/* Creates the world of wd (dim and dp set here; the caller's other settings kept) holding the
   plate, a body of def bd (named "plate"; the caller chooses material and shear), clamped for
   x < 0 and started in the first mode, and an observer at the free end (L, 0). On error *w is
   NULL and the message went to wd.log. */
SCENE_UNUSED static sps_result plate2d_create(sps_world_def wd, const sps_body_def* bd, const plate2d_params* p, sps_world** w,
                                 sps_body* plate, sps_observer* tip) {
    const double dp = PLATE2D_H / p->res;
    sps_body_def def = *bd;
    sps_real lo[3] = {-PLATE2D_HOLDER_LAYERS * dp, -PLATE2D_H / 2, 0}, hi[3] = {PLATE2D_L, PLATE2D_H / 2, 0};
    sps_real clamp_lo[3] = {-1, -1, -1}, clamp_hi[3] = {0, 1, 1}, x_tip[3] = {PLATE2D_L, 0, 0};
    plate2d_start start;
    sps_real c0;
    sps_result r;
    wd.dim = 2;
    wd.dp = dp;
    def.name = "plate";
    if ((r = sps_world_create(&wd, w)) != SPS_OK) return r;
    SCENE_TRY(w, sps_world_add_body(*w, &def, plate));
    SCENE_TRY(w, scene_add_box(*w, *plate, lo, hi, p->jitter, p->seed));
    SCENE_TRY(w, sps_body_constrain_box(*w, *plate, clamp_lo, clamp_hi, SPS_AXIS_ALL, NULL, NULL)); /* holder x < 0 */
    SCENE_TRY(w, sps_body_material_constants(*w, *plate, &c0, NULL, NULL));
    start.vf = p->vf;
    start.c0 = c0;
    SCENE_TRY(w, sps_body_set_velocity(*w, *plate, plate2d_initial_velocity, &start));
    SCENE_TRY(w, sps_world_add_observer(*w, *plate, x_tip, tip));
    return SPS_OK;
}

/* Thin-plate theory's first period (ANG eq. 52), plane strain. */
SCENE_UNUSED static double plate2d_analytical_period(double E, double nu, double rho0) {
    double omega = sqrt(E * PLATE2D_H * PLATE2D_H * pow(PLATE2D_KL / PLATE2D_L, 4) / (12 * rho0 * (1 - nu * nu)));
    return 2 * SCENE_PI / omega;
}

#endif
