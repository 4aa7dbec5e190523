/* jelly.h - the playground of examples/demo.c: soft jelly under gravity in a tank (analytic
   rigid walls: the floor and both sides, no-slip; sphsolid.h CONTACT):
   - a cantilever clamped in the left wall, which sags and swings;
   - a tree clamped in the floor, started with a sway;
   - two blocks spinning on fixed axles (the centre particle held: a rigid rotation about it
     leaves it at rest, while holding more particles would weld the block to the axle);
   - blocks dropped from the top while the scene runs (sps_world_add_body after steps): they
     land on the floor, on each other and on the others, and bounce (bodies touch by default).
     Particles cannot be removed, so after JELLY_MAX_DROPS the scene starts afresh.
   The tank scene (jelly_create with tank = 1) is water 0.32 m deep in the same tank (free-slip
   walls) and nothing else: the dropped blocks are jelly rafts half as dense as water, which
   splash in and float at the depth Archimedes gives (sphsolid.h FLUID-STRUCTURE: the water
   pushes on them through its own pressure). Needs only sphsolid.h. */
#ifndef SPS_SCENE_JELLY_H
#define SPS_SCENE_JELLY_H
#include "scene.h"

#define JELLY_DP 0.04       /* [m]: about one terminal pixel at 80 columns */
#define JELLY_VIEW_W 2.0    /* the view: x in [-1, 1], y in [0, JELLY_VIEW_H] [m] */
#define JELLY_VIEW_H 1.1
#define JELLY_RHO0 1000
#define JELLY_E 4e5         /* soft: c0 18 m/s, so a frame of 1/30 s takes about 30 sub-steps */
#define JELLY_NU 0.3
#define JELLY_MAX_DROPS 16  /* then the scene starts afresh (particles cannot be removed) */
#define JELLY_BLOCK 0.24    /* side of a dropped block [m] */
#define JELLY_WATER_DEPTH 0.32 /* the tank scene's water [m] (8 particles: 400, a frame in real time) */
#define JELLY_RAFT_W 0.40   /* a raft of the tank scene [m]: wider than twice its height, so that it */
#define JELLY_RAFT_H 0.20   /* floats flat (metacentre above the centre of mass: W/H > 1.22 at half density) */
#define JELLY_RAFT_RHO0 500 /* half as dense as water: it floats half immersed */
#define JELLY_CRATE 0.16    /* side of a crate (a free rigid body, every third drop) [m] */
#define JELLY_CRATE_RHO0 600 /* floats in the tank scene, 0.6 immersed (a square floats upright above 0.79) */

typedef struct {
    sps_body body;
    int centre_id;          /* stable id of its centre particle, to see where it is */
    int crate;              /* a free rigid crate (every third drop), not jelly */
} jelly_drop;

typedef struct {
    sps_world* w;
    jelly_drop drops[JELLY_MAX_DROPS];
    int n_drops;
    int tank;               /* 1: the water tank scene */
    sps_body water;         /* the tank scene's water */
} jelly_scene;

SCENE_UNUSED static sps_body_def jelly_body_def(sps_shear shear, const char* name) {
    sps_body_def bd = sps_default_body_def();
    bd.name = name;
    bd.material.density = JELLY_RHO0;
    bd.material.youngs_modulus = JELLY_E;
    bd.material.poisson_ratio = JELLY_NU;
    bd.shear = shear;
    /* the -A variants turn their stored increments with each pair: with the mean rotation the
       colliding, spinning blocks gain energy (bench/VALIDATION.md, A5) and the scene heats up */
    bd.rotation = SPS_ROTATION_PAIR;
    return bd;
}

/* Velocity fields of the start: the tree's sway, a block's spin about its centre. */
SCENE_UNUSED static void jelly_sway(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = 0.8 * (x[1] / 0.64) * (x[1] / 0.64);
    v[1] = v[2] = 0;
}
typedef struct { double omega, cx, cy; } jelly_spin;
SCENE_UNUSED static void jelly_spinning(const sps_real x[3], sps_real v[3], void* user) {
    const jelly_spin* s = (const jelly_spin*)user;
    v[0] = -s->omega * (x[1] - s->cy);
    v[1] = s->omega * (x[0] - s->cx);
    v[2] = 0;
}

/* A square block of side `side` centred at (cx, cy) spinning at omega, free or (axle = 1) on
   an axle through its centre particle (side an odd number of dp puts one there). */
SCENE_UNUSED static sps_result jelly_add_block(sps_world* w, sps_body b, double cx, double cy, double side, double omega, int axle) {
    sps_real lo[3] = {cx - side / 2, cy - side / 2, 0}, hi[3] = {cx + side / 2, cy + side / 2, 0};
    sps_real axle_lo[3] = {cx - JELLY_DP / 4, cy - JELLY_DP / 4, -1}, axle_hi[3] = {cx + JELLY_DP / 4, cy + JELLY_DP / 4, 1};
    jelly_spin spin;
    sps_result r;
    spin.omega = omega; spin.cx = cx; spin.cy = cy;
    if ((r = sps_body_add_box(w, b, lo, hi, NULL)) != SPS_OK || (r = sps_body_set_velocity(w, b, jelly_spinning, &spin)) != SPS_OK) return r;
    return axle ? sps_body_constrain_box(w, b, axle_lo, axle_hi, SPS_AXIS_ALL, NULL, NULL) : SPS_OK;
}

/* The tank scene's water at rest: hydrostatic pressure. */
SCENE_UNUSED static sps_real jelly_hydrostatic(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(1000 * 9.81 * (JELLY_WATER_DEPTH - x[1]));
}

/* The tank scene (see the head): water at rest filling the tank's floor to JELLY_WATER_DEPTH. */
SCENE_UNUSED static sps_result jelly_add_water(jelly_scene* s) {
    sps_body_def water_def = sps_default_body_def();
    const sps_real lo[3] = {-JELLY_VIEW_W / 2, 0, 0}, hi[3] = {JELLY_VIEW_W / 2, JELLY_WATER_DEPTH, 0};
    sps_result r;
    water_def.name = "water";
    water_def.material.kind = SPS_MATERIAL_FLUID;
    water_def.material.density = 1000;
    water_def.material.fluid.sound_speed = (sps_real)(10 * sqrt(2 * 9.81 * JELLY_WATER_DEPTH)); /* 10 times the fastest flow */
    if ((r = sps_world_add_body(s->w, &water_def, &s->water)) != SPS_OK || (r = sps_body_add_box(s->w, s->water, lo, hi, NULL)) != SPS_OK)
        return r;
    return sps_body_set_pressure(s->w, s->water, jelly_hydrostatic, NULL);
}

/* Builds the scene (tank = 0: the playground; 1: the water tank) with `threads` OpenMP threads
   (0: all) into s; log receives the errors. */
SCENE_UNUSED static sps_result jelly_create(int threads, sps_log_fn log, int tank, jelly_scene* s) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def cantilever_def = jelly_body_def(SPS_SHEAR_ENO_A, "cantilever"), tree_def = jelly_body_def(SPS_SHEAR_ENO_A, "tree");
    sps_body_def wheel_def = jelly_body_def(SPS_SHEAR_GNO_A, "wheel");
    sps_real beam_lo[3] = {-1.0, 0.40, 0}, beam_hi[3] = {-0.2, 0.64, 0}, wall_lo[3] = {-2, -2, -1}, wall_hi[3] = {-0.88, 2, 1};
    sps_real trunk_lo[3] = {0.52, 0, 0}, trunk_hi[3] = {0.76, 0.44, 0}, crown_lo[3] = {0.40, 0.44, 0}, crown_hi[3] = {0.88, 0.64, 0};
    sps_real floor_lo[3] = {-2, -2, -1}, floor_hi[3] = {2, 0.12, 1};
    sps_body cantilever, tree, wheel;
    sps_result r;
    memset(s, 0, sizeof *s);
    wd.dim = 2;
    wd.dp = JELLY_DP;
    wd.gravity[1] = -9.81;
    wd.threads = threads;
    wd.log = log;
    if ((r = sps_world_create(&wd, &s->w)) != SPS_OK) return r;
    s->tank = tank;
    {   /* the tank: the view's floor and sides, open at the top */
        const sps_real tank_lo[3] = {-JELLY_VIEW_W / 2, 0, 0}, tank_hi[3] = {JELLY_VIEW_W / 2, 4 * JELLY_VIEW_H, 0};
        SCENE_TRY(&s->w, sps_world_add_box_walls(s->w, tank_lo, tank_hi, SPS_FACE_Y_HI, tank ? SPS_WALL_FREE_SLIP : SPS_WALL_NO_SLIP));
    }
    if (tank) {
        SCENE_TRY(&s->w, jelly_add_water(s));
        return SPS_OK;
    }
    SCENE_TRY(&s->w, sps_world_add_body(s->w, &cantilever_def, &cantilever));
    SCENE_TRY(&s->w, sps_body_add_box(s->w, cantilever, beam_lo, beam_hi, NULL));
    SCENE_TRY(&s->w, sps_body_constrain_box(s->w, cantilever, wall_lo, wall_hi, SPS_AXIS_ALL, NULL, NULL));
    SCENE_TRY(&s->w, sps_world_add_body(s->w, &tree_def, &tree));
    SCENE_TRY(&s->w, sps_body_add_box(s->w, tree, trunk_lo, trunk_hi, NULL));
    SCENE_TRY(&s->w, sps_body_add_box(s->w, tree, crown_lo, crown_hi, NULL));
    SCENE_TRY(&s->w, sps_body_set_velocity(s->w, tree, jelly_sway, NULL));
    SCENE_TRY(&s->w, sps_body_constrain_box(s->w, tree, floor_lo, floor_hi, SPS_AXIS_ALL, NULL, NULL));
    SCENE_TRY(&s->w, sps_world_add_body(s->w, &wheel_def, &wheel));
    SCENE_TRY(&s->w, jelly_add_block(s->w, wheel, -0.55, 0.84, 9 * JELLY_DP, 5, 1));
    SCENE_TRY(&s->w, sps_world_add_body(s->w, &wheel_def, &wheel));
    SCENE_TRY(&s->w, jelly_add_block(s->w, wheel, 0.08, 0.5, 9 * JELLY_DP, -5, 1));
    return SPS_OK;
}

/* Drops block number s->n_drops (shear formulation `shear`) from above the view, at an
   x that cycles over the view's width: a spinning block, or in the tank scene a raft (at rest,
   density JELLY_RAFT_RHO0, its heave damped at 2/s so that it comes to float) from 0.28 m above
   the water (it hits it at 2.3 m/s, a tenth of the water's c0); every third drop is a crate, a
   free rigid body (SPS_MATERIAL_RIGID_DYNAMIC, density JELLY_CRATE_RHO0, friction and contact
   damping) that tumbles onto the others or floats. SPS_ERR_STATE when JELLY_MAX_DROPS are out. */
SCENE_UNUSED static sps_result jelly_drop_block(jelly_scene* s, sps_shear shear) {
    static const double x_of[5] = {-0.7, 0.3, -0.2, 0.75, -0.45};
    jelly_drop* d = &s->drops[s->n_drops];
    sps_body_def bd = jelly_body_def(shear, "dropped");
    /* dropped blocks settle: friction among them (the scene's other bodies have none, so the
       pair's sqrt(mu_a mu_b) is 0 there) and Kelvin-Voigt damping low enough (nu / h = 0.4 m/s
       against c0 18 m/s) to leave the sub-step as it is (DAMPING, CONTACT) */
    bd.friction = (sps_real)0.5;
    bd.material.viscosity = 20;
    /* just above the view, clear of the spinning wheels' corners (bodies must not start overlapping) */
    const double cx = x_of[s->n_drops % 5], cy = JELLY_VIEW_H + JELLY_BLOCK / 2 + 0.06;
    sps_real centre[3] = {cx, cy, 0};
    sps_result r;
    if (s->n_drops == JELLY_MAX_DROPS) return SPS_ERR_STATE;
    d->crate = s->n_drops % 3 == 2;
    if (d->crate) { /* its E sets only its contact stiffness: the jelly's sound speed, so the sub-steps stay */
        const double y0 = s->tank ? JELLY_WATER_DEPTH + 0.28 : cy - JELLY_CRATE / 2;
        const sps_real lo[3] = {cx - JELLY_CRATE / 2, y0, 0}, hi[3] = {cx + JELLY_CRATE / 2, y0 + JELLY_CRATE, 0}, v[3] = {0, -1.5, 0};
        const sps_real omega[3] = {0, 0, 3}; /* thrown down, spinning like a jelly block */
        bd.material.kind = SPS_MATERIAL_RIGID_DYNAMIC;
        bd.material.density = JELLY_CRATE_RHO0;
        bd.material.youngs_modulus = (sps_real)(JELLY_E * JELLY_CRATE_RHO0 / JELLY_RHO0);
        bd.material.viscosity = 0;
        bd.shear = SPS_SHEAR_ENO_A; /* not read: the defaults */
        bd.rotation = SPS_ROTATION_AUTO;
        bd.contact_damping = (sps_real)0.5;
        bd.damping = s->tank ? 1 : 0; /* it comes to float */
        if ((r = sps_world_add_body(s->w, &bd, &d->body)) != SPS_OK || (r = sps_body_add_box(s->w, d->body, lo, hi, NULL)) != SPS_OK ||
            (r = sps_body_set_rigid_motion(s->w, d->body, v, omega)) != SPS_OK)
            return r;
    } else if (s->tank) {
        const sps_real lo[3] = {cx - JELLY_RAFT_W / 2, JELLY_WATER_DEPTH + 0.28, 0}, hi[3] = {cx + JELLY_RAFT_W / 2, lo[1] + JELLY_RAFT_H, 0};
        bd.material.density = JELLY_RAFT_RHO0;
        bd.friction = 0; /* rafts meet only water, and each other now and then */
        bd.damping = 2;
        if ((r = sps_world_add_body(s->w, &bd, &d->body)) != SPS_OK || (r = sps_body_add_box(s->w, d->body, lo, hi, NULL)) != SPS_OK) return r;
    } else if ((r = sps_world_add_body(s->w, &bd, &d->body)) != SPS_OK || (r = jelly_add_block(s->w, d->body, cx, cy, JELLY_BLOCK, 3, 0)) != SPS_OK)
        return r;
    d->centre_id = sps_world_nearest_particle(s->w, d->body, centre);
    ++s->n_drops;
    return SPS_OK;
}

/* The tank scene's floating rafts against Archimedes: the water level (the water's area at rho0
   and the rafts' parts below the level fill the tank's width: solved by fixed-point iteration)
   and the rafts' submerged fraction (each particle's dp x dp cell counted by its part below the
   level), which a raft of density rho floats at: rho / 1000. *fraction is 0 without rafts. */
SCENE_UNUSED static void jelly_float_report(const jelly_scene* s, double* level_out, double* fraction) {
    const sps_real *y = sps_world_field(s->w, SPS_FIELD_POSITION_Y), *m = sps_world_field(s->w, SPS_FIELD_MASS);
    double water_area = 0, level = JELLY_WATER_DEPTH, below = 0, raft_below = 0;
    int i, k, it, first, count, components, rafts = 0;
    *fraction = 0;
    if (!s->tank || !sps_body_field(s->w, s->water, "density", &components, &first, &count)) return;
    for (i = first; i < first + count; ++i) water_area += m[i] / 1000;
    for (it = 0; it < 20; ++it) {
        below = raft_below = 0;
        rafts = 0;
        for (k = 0; k < s->n_drops; ++k) {
            double part_below = 0;
            if (!sps_body_field(s->w, s->drops[k].body, "density", &components, &first, &count)) continue;
            for (i = first; i < first + count; ++i) {
                const double part = (level - y[i]) / JELLY_DP + 0.5;
                part_below += JELLY_DP * JELLY_DP * (part < 0 ? 0 : part > 1 ? 1 : part);
            }
            below += part_below; /* crates displace water too */
            if (!s->drops[k].crate) { raft_below += part_below; ++rafts; }
        }
        level = (water_area + below) / JELLY_VIEW_W;
    }
    *level_out = level;
    if (rafts) *fraction = raft_below / (rafts * JELLY_RAFT_W * JELLY_RAFT_H);
}

#endif
