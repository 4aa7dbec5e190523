/* infinite_slope.h - a layer of cohesionless soil on an incline, periodic along the slope: the
   scene of examples/infinite_slope.c and of the test that it stands below its limit angle and
   flows above it (tests/test_fluids.c); needs only sphsolid.h.

   A layer SLOPE_DEPTH = 0.05 m deep of the C4 soil (rho0 2040, E 5.84 MPa, nu 0.3, c = 0) on a
   no-slip floor y = 0, periodic along x with a period of SLOPE_LENGTH_DP dp. The frame is the
   slope's: gravity's normal part g cos(theta) is the world's, and the layer starts from its
   geostatic stress under it (Jaky's K0); the part along the slope, g sin(theta), is an external
   acceleration raised from 0 over the first SLOPE_RAMP seconds (quasi-static: the layer's
   shear-wave period is 6 ms), then held. */
#ifndef SPS_SCENE_INFINITE_SLOPE_H
#define SPS_SCENE_INFINITE_SLOPE_H
#include "scene.h"

#define SLOPE_DEPTH 0.05
#define SLOPE_LENGTH_DP 16 /* the period along the slope in dp: at least 6 h = 7.8 dp */
#define SLOPE_RAMP 0.5     /* [s] */
#define SLOPE_GRAVITY 9.8  /* [m/s^2] the UTVF paper's */
#define SLOPE_RHO0 2040    /* the C4 soil [kg/m^3], */
#define SLOPE_E 5.84e6     /* [Pa] */
#define SLOPE_NU 0.3

typedef struct {
    double angle, phi, psi; /* the slope's angle, the friction and dilatancy angles [degrees] */
    sps_yield_cone cone;
    int res;                /* particles across the layer, SLOPE_DEPTH / dp */
    double g_along;         /* set by slope_create: g sin(theta) [m/s^2], read by the ramp */
} slope_params;

/* The slope's part of gravity, raised linearly over SLOPE_RAMP seconds. */
SCENE_UNUSED static void slope_gravity(const sps_real x[3], const sps_real x0[3], const sps_real v[3], sps_real t, sps_real a[3],
                                       void* user) {
    const slope_params* p = (const slope_params*)user;
    (void)x, (void)x0, (void)v;
    a[0] = (sps_real)(p->g_along * (t < SLOPE_RAMP ? t / SLOPE_RAMP : 1));
    a[1] = a[2] = 0;
}

/* The limit angle of an infinite slope of a Mohr-Coulomb soil in simple shear (Davis 1968: the
   strength mobilised on the planes of zero extension, tan = sin phi cos psi / (1 - sin phi sin
   psi)) [degrees]: tan(phi) for associated flow, sin(phi) for psi = 0. */
SCENE_UNUSED static double slope_limit_angle(double phi, double psi) {
    const double r = SCENE_PI / 180;
    return atan(sin(phi * r) * cos(psi * r) / (1 - sin(phi * r) * sin(psi * r))) / r;
}

/* Builds the scene into the world def wd (its dim, dp, gravity and period set here; the rest the
   caller's) and body def bd (kind, cohesion and p's angles and cone set here; density, E and nu
   the caller's, SLOPE_RHO0, SLOPE_E and SLOPE_NU for the C4 soil); p must outlive the world (the
   ramp reads it). */
SCENE_UNUSED static sps_result slope_create(slope_params* p, sps_world_def* wd, sps_body_def* bd, sps_world** out, sps_body* soil) {
    const double dp = SLOPE_DEPTH / p->res, theta = p->angle * SCENE_PI / 180;
    const sps_real floor_point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)(SLOPE_LENGTH_DP * dp), (sps_real)SLOPE_DEPTH, 0};
    sps_world* w;
    sps_result r;
    wd->dim = 2;
    wd->dp = (sps_real)dp;
    wd->gravity[0] = wd->gravity[2] = 0;
    wd->gravity[1] = (sps_real)(-SLOPE_GRAVITY * cos(theta)); /* the slope's frame: the normal part */
    wd->periodic[0] = (sps_real)(SLOPE_LENGTH_DP * dp);
    bd->material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    bd->material.granular.cohesion = 0;
    bd->material.granular.friction_angle = (sps_real)p->phi;
    bd->material.granular.dilatancy_angle = (sps_real)p->psi;
    bd->material.granular.yield_cone = p->cone;
    p->g_along = SLOPE_GRAVITY * sin(theta);
    if ((r = sps_world_create(wd, &w)) != SPS_OK) return r;
    *out = w;
    if ((r = sps_world_add_body(w, bd, soil)) != SPS_OK || (r = sps_body_add_box(w, *soil, lo, hi, NULL)) != SPS_OK ||
        (r = sps_world_add_wall(w, floor_point, up, SPS_WALL_NO_SLIP)) != SPS_OK ||
        (r = sps_body_set_geostatic_stress(w, *soil, (sps_real)SLOPE_DEPTH, 0)) != SPS_OK)
        return r;
    return sps_body_set_acceleration(w, *soil, slope_gravity, p);
}

/* The mean velocity along the slope of the top two rows [m/s]. */
SCENE_UNUSED static double slope_top_speed(const sps_world* w) {
    const sps_real *y = sps_world_field(w, SPS_FIELD_POSITION_Y), *u = sps_world_field(w, SPS_FIELD_VELOCITY_X);
    const double top = SLOPE_DEPTH - 2 * sps_world_get_def(w)->dp;
    double sum = 0;
    int i, n = sps_world_particle_count(w), count = 0;
    for (i = 0; i < n; ++i)
        if (y[i] > top) { sum += u[i]; ++count; }
    return count ? sum / count : 0;
}

/* The top rows' displacement along the slope since the ramp ended, their speed integrated from
   step to step: called after every step with the step's end time t (t_prev: the last call's). */
SCENE_UNUSED static void slope_track(const sps_world* w, double* t_prev, double* displacement, double* top_speed) {
    const double t = sps_world_time(w);
    *top_speed = slope_top_speed(w);
    if (t > SLOPE_RAMP) *displacement += *top_speed * (t - (*t_prev > SLOPE_RAMP ? *t_prev : SLOPE_RAMP));
    *t_prev = t;
}
#endif
