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
   NULL and the message went to wd.log. The tests, the bench and cantilever_sag.c build the
   plate with it; examples/plate2d.c writes the same steps out in its main, as a scene. */
SCENE_UNUSED static sps_result plate2d_create(sps_world_def wd, const sps_body_def* bd, const plate2d_params* p, sps_world** w,
                                 sps_body* plate, sps_observer* tip) {
    const double dp = PLATE2D_H / p->res;
    sps_body_def def = *bd;
    sps_real lo[3] = {-PLATE2D_HOLDER_LAYERS * dp, -PLATE2D_H / 2, 0}, hi[3] = {PLATE2D_L, PLATE2D_H / 2, 0};
    sps_real clamp_lo[3] = {-1, -1, -1}, clamp_hi[3] = {0, 1, 1}, x_tip[3] = {PLATE2D_L, 0, 0};
    plate2d_start start;
    sps_real c0, K;
    sps_result r;
    wd.dim = 2;
    wd.dp = dp;
    def.name = "plate";
    if ((r = sps_world_create(&wd, w)) != SPS_OK) return r;
    SCENE_TRY(w, sps_world_add_body(*w, &def, plate));
    SCENE_TRY(w, scene_add_box(*w, *plate, lo, hi, p->jitter, p->seed));
    SCENE_TRY(w, sps_body_constrain_box(*w, *plate, clamp_lo, clamp_hi, SPS_AXIS_ALL, NULL, NULL)); /* holder x < 0 */
    /* the papers' c0 = sqrt(K/rho0) (a total-Lagrangian body's own signal speed is the P-wave speed) */
    SCENE_TRY(w, sps_body_material_constants(*w, *plate, NULL, NULL, &K));
    c0 = (sps_real)sqrt(K / def.material.density);
    start.vf = p->vf;
    start.c0 = c0;
    SCENE_TRY(w, sps_body_set_velocity(*w, *plate, plate2d_initial_velocity, &start));
    SCENE_TRY(w, sps_world_add_observer(*w, *plate, x_tip, tip));
    return SPS_OK;
}

/* The static deflection w(x) (downwards) of the plate as a Timoshenko beam clamped at x = 0
   under its own weight in gravity g pointing down: q = rho0 g H per unit depth, plane strain
   (E' = E/(1 - nu^2)), I = H^3/12, A = H, kappa = 5/6 (a rectangular section):
       w(x) = q (x^4 - 4 L x^3 + 6 L^2 x^2)/(24 E' I) + q (L x - x^2/2)/(kappa G A),
   at the tip q L^4/(8 E' I) + q L^2/(2 kappa G A). bending = 0 keeps only the shear part,
   shear = 0 only the bending part (Euler-Bernoulli). */
SCENE_UNUSED static double plate2d_timoshenko_sag(double x, double g, double E, double nu, double rho0, int bending, int shear) {
    const double L = PLATE2D_L, H = PLATE2D_H, q = rho0 * g * H, E_plane = E / (1 - nu * nu), I = H * H * H / 12;
    const double kappa_G_A = 5.0 / 6.0 * E / (2 * (1 + nu)) * H;
    return bending * q * (x * x * x * x - 4 * L * x * x * x + 6 * L * L * x * x) / (24 * E_plane * I) + shear * q * (L * x - x * x / 2) / kappa_G_A;
}

/* The mean downward displacement of the particles of the plate's end column (reference
   x > L - dp, at x = L - dp/2): the beam's w there (a Timoshenko deflection is the mean over the
   section). */
SCENE_UNUSED static double plate2d_end_sag(const sps_world* w, double dp) {
    const sps_real *x0 = sps_world_field(w, SPS_FIELD_REFERENCE_X), *y0 = sps_world_field(w, SPS_FIELD_REFERENCE_Y);
    const sps_real* y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    double sum = 0;
    int i, n = 0;
    for (i = 0; i < sps_world_particle_count(w); ++i)
        if (x0[i] > PLATE2D_L - dp) {
            sum += y0[i] - y[i];
            ++n;
        }
    return n ? sum / n : 0;
}

/* Thin-plate theory's first period (ANG eq. 52), plane strain. */
SCENE_UNUSED static double plate2d_analytical_period(double E, double nu, double rho0) {
    double omega = sqrt(E * PLATE2D_H * PLATE2D_H * pow(PLATE2D_KL / PLATE2D_L, 4) / (12 * rho0 * (1 - nu * nu)));
    return 2 * SCENE_PI / omega;
}

#endif
