/* user_scenes.c - the scenes a new user writes first, with the public API only:
     drop     a rubber cube (3D, side 0.1 m) or disc (2D, radius 0.05 m), E 1e6, nu 0.3, rho0 1000,
              spinning at --spin rad/s about z, its lowest point 0.2 m above a floor (y = 0), under
              gravity; --slip noslip|free
     ramp     the 2D disc (or 3D cube) released on a 30-degree no-slip ramp, rolling (or tumbling) down
     collide  two such bodies spinning in opposite senses, thrown at each other at 2 m/s each
     stack    three blocks (0.1 m high; 0.3, 0.2, 0.1 m wide, a square column in 3D) filled flush on
              the floor and on each other
     slide    a block 0.1 x 0.05 m filled flush on a floor, mu 0.3 (body and wall), thrown at 1 m/s
     tank     water 0.1 m deep in a tank 0.3 m wide (0.2 x 0.2 m in 3D; h = 2 dp, c0 from
              sps_fluid_sound_speed at 1 %) with jelly blocks (density 500) filled flush on it
     gravity-z   the drop scene in 2D with gravity along z (a mistake: warned, nothing moves)
     friction-deg the slide with friction 30 (degrees typed for mu: warned, it sticks)
     slot     the tank's water filled 1.5 dp short of its far wall (warned: it runs into the slot)
     drop-stack  two such bodies, one on the other, dropped 0.05 m onto the floor (a free-slip
              floor, friction 0.5 between the bodies and with the floor)
     float    the body, half as dense as water, dropped from 0.05 m into water 0.2 m deep in a
              tank 0.6 m wide (analytic walls, h_over_dp 2)
   --kind rigid makes the bodies free rigid bodies (SPS_MATERIAL_RIGID_DYNAMIC; shear and
   rotation are not read); they get contact_damping 0.5 in drop-stack.
   It prints one RESULT line: watchdog_growth, the energy watchdog's largest finding
   (sps_diagnostics.energy_growth: the account kinetic + volumetric strain + contact + gravity
   potential - prescribed work above its start, as a fraction of the largest mechanical energy
   seen; the acceptance: below 0.02) and its count of checks above 2 %; max_gain,
   the diagnostics' E = kinetic + strain (with the shear part of the tracked stress) + contact +
   potential above its start over the start's kinetic + strain energy (or its potential energy
   above the floor when it starts at rest): with ENO and ENO-A the tracked Jaumann stress is not
   the stress their forces come from, and reads high during an impact; and the run's status.
   The stability map (bench/stability_map.sh, user-scene rows) runs it for every formulation x
   rotation. --rotation default keeps sps_default_body_def()'s.

   Build: make build/user_scenes      Run: ./build/user_scenes --scene drop --dim 3 --spin 20 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#define PI 3.14159265358979323846
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"

typedef struct scene_options {
    const char* scene;
    int dim, noslip, rotation, shear; /* rotation, shear: -1 = sps_default_body_def()'s */
    int rigid;                        /* --kind rigid: free rigid bodies */
    double spin, t_end, dp, cfl;
    double gravity, E; /* [m/s^2] along -y (default 9.81); Young's modulus (0: the default body's) */
    int contact_rest;  /* sps_contact_rest: 0 flush (default), 1 the papers' kernel-edge law */
} scene_options;

static int choice(const char* value, const char* const* names, int n, const char* option) {
    int k;
    for (k = 0; k < n; ++k)
        if (strcmp(value, names[k]) == 0) return k;
    fprintf(stderr, "user_scenes: %s %s: allowed", option, value);
    for (k = 0; k < n; ++k) fprintf(stderr, " %s", names[k]);
    fprintf(stderr, "\n");
    exit(2);
}

static const char* const shear_names[] = {"eno", "eno-a", "og", "oas", "gno", "gno-a"};
static const char* const rotation_names[] = {"mean", "particle", "pair"};

static const char* const contact_rests[] = {"flush", "kernel"};
static void parse(int argc, char** argv, scene_options* o) {
    static const char* const scenes[] = {"drop", "ramp", "collide", "stack", "slide", "tank", "gravity-z", "friction-deg", "slot",
                                         "drop-stack", "float"};
    static const char* const slips[] = {"free", "noslip"};
    static const char* const kinds[] = {"elastic", "rigid"};
    int i;
    for (i = 1; i + 1 < argc; i += 2) {
        const char *key = argv[i], *value = argv[i + 1];
        if (!strcmp(key, "--scene")) o->scene = scenes[choice(value, scenes, 11, key)];
        else if (!strcmp(key, "--kind")) o->rigid = choice(value, kinds, 2, key);
        else if (!strcmp(key, "--dim")) o->dim = atoi(value);
        else if (!strcmp(key, "--slip")) o->noslip = choice(value, slips, 2, key);
        else if (!strcmp(key, "--shear")) o->shear = strcmp(value, "default") ? choice(value, shear_names, 6, key) : -1;
        else if (!strcmp(key, "--rotation")) o->rotation = strcmp(value, "default") ? choice(value, rotation_names, 3, key) : -1;
        else if (!strcmp(key, "--spin")) o->spin = atof(value);
        else if (!strcmp(key, "--tend")) o->t_end = atof(value);
        else if (!strcmp(key, "--dp")) o->dp = atof(value);
        else if (!strcmp(key, "--cfl")) o->cfl = atof(value);
        else if (!strcmp(key, "--gravity")) o->gravity = atof(value);
        else if (!strcmp(key, "--contact-rest")) o->contact_rest = choice(value, contact_rests, 2, key);
        else if (!strcmp(key, "--E")) o->E = atof(value);
        else { fprintf(stderr, "user_scenes: unknown option %s\n", key); exit(2); }
    }
    if (i < argc || (o->dim != 2 && o->dim != 3)) {
        fprintf(stderr, "usage: user_scenes [--scene drop|ramp|collide|stack|slide|tank|gravity-z|friction-deg|slot|drop-stack|float] "
                        "[--kind elastic|rigid] [--dim 2|3] [--slip free|noslip] [--shear default|eno|eno-a|og|oas|gno|gno-a] "
                        "[--rotation default|mean|particle|pair] [--spin rad/s] [--tend s] [--dp m] [--cfl c] [--gravity g] [--E Pa] "
                        "[--contact-rest flush|kernel]\n");
        exit(2);
    }
}

/* Rigid spin about z through the body's centre plus a translation (sps_body_set_rigid_motion). */
static sps_result throw_body(sps_world* w, sps_body b, double vx, double vy, double spin) {
    const sps_real v[3] = {(sps_real)vx, (sps_real)vy, 0}, omega[3] = {0, 0, (sps_real)spin};
    return sps_body_set_rigid_motion(w, b, v, omega);
}

/* The cube (3D) or disc (2D) of side / diameter 0.1 m centred at c. */
static double disc_sdf(const sps_real x[3], const void* user) {
    const double* c = (const double*)user;
    return sqrt((x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1])) - 0.05;
}
static sps_real disc_sdf_real(const sps_real x[3], void* user) { return (sps_real)disc_sdf(x, user); }

static sps_result add_block(sps_world* w, const sps_body_def* bd, int dim, const double c[3], sps_body* out) {
    const sps_real lo[3] = {(sps_real)(c[0] - 0.05), (sps_real)(c[1] - 0.05), (sps_real)(c[2] - 0.05)};
    const sps_real hi[3] = {(sps_real)(c[0] + 0.05), (sps_real)(c[1] + 0.05), (sps_real)(c[2] + 0.05)};
    sps_result r = sps_world_add_body(w, bd, out);
    if (r != SPS_OK) return r;
    return dim == 3 ? sps_body_add_box(w, *out, lo, hi, NULL) : sps_body_add_sdf(w, *out, lo, hi, disc_sdf_real, (void*)c, NULL);
}

static int g_warnings;
static void quiet_log(int level, const char* message, void* user) {
    (void)user;
    if (level == 0) fprintf(stderr, "%s\n", message);
    if (level == 1) ++g_warnings; /* the mistakes' scenes must warn */
}

/* A box body [lo, hi] of def bd (z ignored in 2D), thrown at vx. */
static sps_result add_box_body(sps_world* w, const sps_body_def* bd, const double lo[3], const double hi[3], double vx, sps_body* out) {
    const sps_real l[3] = {(sps_real)lo[0], (sps_real)lo[1], (sps_real)lo[2]}, h[3] = {(sps_real)hi[0], (sps_real)hi[1], (sps_real)hi[2]};
    sps_result r = sps_world_add_body(w, bd, out);
    if (r == SPS_OK) r = sps_body_add_box(w, *out, l, h, NULL);
    return r == SPS_OK && vx != 0 ? throw_body(w, *out, vx, 0, 0) : r;
}

static double g_depth;
static sps_real hydrostatic(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(1000 * 9.81 * (g_depth - (double)x[1]));
}

/* The tank scene (slot: the water 1.5 dp short of the far wall). */
static sps_result build_tank(sps_world* w, sps_body_def bd, const scene_options* o, int slot) {
    const double width = o->dim == 3 ? 0.2 : 0.3, depth = 0.1, block = 0.05, short_by = slot ? 1.5 * o->dp : 0;
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)width, 1, (sps_real)width};
    const double wlo[3] = {0, 0, 0}, whi[3] = {width - short_by, depth, width};
    sps_body_def water = sps_default_body_def();
    sps_body b;
    sps_result r;
    int k;
    g_depth = depth;
    water.name = "water";
    water.material.kind = SPS_MATERIAL_FLUID;
    water.material.fluid.sound_speed = sps_fluid_sound_speed((sps_real)9.81, (sps_real)depth, 0, (sps_real)SPS_DENSITY_ERROR_ACCURATE);
    if ((r = sps_world_add_box_walls(w, lo, hi, o->dim == 3 ? SPS_FACE_Y_HI : SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP)) != SPS_OK) return r;
    if ((r = add_box_body(w, &water, wlo, whi, 0, &b)) != SPS_OK || (r = sps_body_set_pressure(w, b, hydrostatic, NULL)) != SPS_OK) return r;
    bd.material.density = 500;
    bd.name = "raft";
    for (k = 0; k < (o->dim == 3 ? 1 : 3); ++k) { /* flush on the water */
        const double x0 = o->dim == 3 ? 0.075 : 0.025 + 0.1 * k, blo[3] = {x0, depth, 0.075}, bhi[3] = {x0 + block, depth + block, 0.125};
        if ((r = add_box_body(w, &bd, blo, bhi, 0, &b)) != SPS_OK) return r;
    }
    return SPS_OK;
}

static double total_energy(const sps_diagnostics* d) {
    return d->kinetic_energy + d->strain_energy + d->contact_energy + d->potential_energy - d->prescribed_work;
}

/* The float scene: water 0.2 m deep in a tank 0.6 m wide, the body (density 500) dropped in. */
static sps_result build_float(const scene_options* o, sps_world* w, sps_body_def* bd, double centre[3]) {
    sps_body_def water = sps_default_body_def();
    const sps_real tank_lo[3] = {-0.3, 0, -0.15}, tank_hi[3] = {0.3, 1, 0.15};
    const sps_real lo[3] = {-0.3, 0, -0.15}, hi[3] = {0.3, 0.2, 0.15};
    sps_body body;
    sps_result r;
    water.material.kind = SPS_MATERIAL_FLUID;
    water.material.fluid.sound_speed = (sps_real)(10 * sqrt(2 * 9.81 * 0.2));
    water.name = "water";
    g_depth = 0.2;
    if ((r = sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP)) != SPS_OK) return r;
    if ((r = sps_world_add_body(w, &water, &body)) != SPS_OK || (r = sps_body_add_box(w, body, lo, hi, NULL)) != SPS_OK ||
        (r = sps_body_set_pressure(w, body, hydrostatic, NULL)) != SPS_OK)
        return r;
    bd->material.density = 500;
    centre[1] = 0.2 + 0.05 + 0.05 + o->dp;
    if ((r = add_block(w, bd, o->dim, centre, &body)) != SPS_OK) return r;
    return throw_body(w, body, 0, 0, o->spin);
}

static sps_result build(const scene_options* o, sps_world** out) {
    static double centre[2][3];
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real origin[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    sps_body a, b;
    sps_result r;
    wd.dim = o->dim;
    wd.dp = (sps_real)o->dp;
    wd.threads = 1;
    if (o->cfl > 0) wd.cfl_acoustic = (sps_real)o->cfl;
    wd.gravity[1] = (sps_real)-o->gravity;
    wd.contact_rest = (sps_contact_rest)o->contact_rest;
    if (o->E > 0) bd.material.youngs_modulus = (sps_real)o->E;
    wd.energy_growth_limit = 0.02; /* the watchdog reports the growth above 2 % (sps_diagnostics.energy_growth) */
    wd.log = quiet_log;
    if (o->shear >= 0) bd.shear = (sps_shear)o->shear;
    if (o->rotation >= 0) bd.rotation = (sps_rotation)o->rotation;
    bd.track_stress = 1; /* the strain energy of the ENO family needs the stress */
    if (o->rigid) { /* the defaults of what a rigid body does not read */
        bd = sps_default_body_def();
        bd.material.kind = SPS_MATERIAL_RIGID_DYNAMIC;
    }
    if (!strcmp(o->scene, "tank") || !strcmp(o->scene, "slot") || !strcmp(o->scene, "float")) wd.h_over_dp = 2; /* water under gravity */
    if (!strcmp(o->scene, "gravity-z")) { wd.dim = 2; wd.gravity[1] = 0; wd.gravity[2] = -9.81; }
    if ((r = sps_world_create(&wd, out)) != SPS_OK) return r;
    if (!strcmp(o->scene, "tank") || !strcmp(o->scene, "slot")) return build_tank(*out, bd, o, !strcmp(o->scene, "slot"));
    if (!strcmp(o->scene, "float")) return build_float(o, *out, &bd, centre[0]);
    if (!strcmp(o->scene, "ramp")) { /* a 30-degree ramp through the origin, going down towards +x */
        const sps_real normal[3] = {(sps_real)sin(PI / 6), (sps_real)cos(PI / 6), 0};
        /* the disc's radius, or the axis-aligned cube's deepest corner (half side (sin + cos 30 deg)),
           plus half a spacing of air */
        const double lift = (o->dim == 2 ? 0.05 : 0.05 * (normal[0] + normal[1])) + 0.5 * o->dp;
        centre[0][0] = -0.3 + lift * normal[0];
        centre[0][1] = 0.3 * tan(PI / 6) + lift * normal[1];
        if ((r = sps_world_add_wall(*out, origin, normal, SPS_WALL_NO_SLIP)) != SPS_OK) return r;
        if ((r = add_block(*out, &bd, o->dim, centre[0], &a)) != SPS_OK) return r;
        return throw_body(*out, a, 0, 0, 0);
    }
    if ((r = sps_world_add_wall(*out, origin, up, o->noslip && strcmp(o->scene, "slide") && strcmp(o->scene, "friction-deg") ? SPS_WALL_NO_SLIP : SPS_WALL_FREE_SLIP)) != SPS_OK)
        return r; /* the slides: a free-slip floor with Coulomb friction */
    if (!strcmp(o->scene, "stack")) { /* flush: the first row dp/2 above the floor, the blocks' rows dp apart */
        const double width[3] = {0.3, 0.2, 0.1};
        int k;
        for (k = 0; k < 3; ++k) {
            const double lo[3] = {-width[k] / 2, 0.1 * k, -0.05}, hi[3] = {width[k] / 2, 0.1 * (k + 1), 0.05};
            if ((r = add_box_body(*out, &bd, lo, hi, 0, &a)) != SPS_OK) return r;
        }
        return SPS_OK;
    }
    if (!strcmp(o->scene, "slide") || !strcmp(o->scene, "friction-deg")) {
        const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.05, 0.05};
        bd.friction = !strcmp(o->scene, "slide") ? 0.3 : 30;
        if ((r = sps_world_set_wall_friction(*out, 0, bd.friction)) != SPS_OK) return r;
        return add_box_body(*out, &bd, lo, hi, 1, &a);
    }
    if (!strcmp(o->scene, "drop") || !strcmp(o->scene, "gravity-z")) {
        centre[0][1] = 0.25;
        if ((r = add_block(*out, &bd, o->dim, centre[0], &a)) != SPS_OK) return r;
        return throw_body(*out, a, 0, 0, !strcmp(o->scene, "gravity-z") ? 0 : o->spin);
    }
    if (!strcmp(o->scene, "drop-stack")) { /* one on the other, dropped 0.05 m */
        const sps_real mu = (sps_real)0.5;
        bd.friction = mu;
        if (o->rigid) bd.contact_damping = (sps_real)0.5;
        if ((r = sps_world_set_wall_friction(*out, 0, o->noslip ? 0 : mu)) != SPS_OK) return r;
        centre[0][1] = 0.1 + o->dp;
        centre[1][1] = 0.2 + 2 * o->dp;
        if ((r = add_block(*out, &bd, o->dim, centre[0], &a)) != SPS_OK) return r;
        return add_block(*out, &bd, o->dim, centre[1], &b);
    }
    centre[0][0] = -0.1; centre[0][1] = 0.1; /* collide: resting on the floor, 0.1 m apart */
    centre[1][0] = 0.1; centre[1][1] = 0.1;
    if ((r = add_block(*out, &bd, o->dim, centre[0], &a)) != SPS_OK) return r;
    if ((r = add_block(*out, &bd, o->dim, centre[1], &b)) != SPS_OK) return r;
    if ((r = throw_body(*out, a, 2, 0, o->spin)) != SPS_OK) return r;
    return throw_body(*out, b, -2, 0, -o->spin);
}

/* The mean x of all particles (the slide's distance). */
static double mean_x(const sps_world* w) {
    const sps_real* x = sps_world_field(w, SPS_FIELD_POSITION_X);
    const int n = sps_world_particle_count(w);
    double sum = 0;
    int i;
    for (i = 0; i < n; ++i) sum += x[i];
    return n > 0 ? sum / n : 0;
}

int main(int argc, char** argv) {
    scene_options o = {"drop", 3, 1, -1, -1, 0, 20, 1, 0.01, 0, 9.81, 0, 0};
    double speed_10ms = 0, x_start = 0;
    const sps_body all = {0};
    sps_world* w = NULL;
    sps_diagnostics d0, d;
    double e0, mech0, gain = 0;
    sps_result r;
    parse(argc, argv, &o);
    r = build(&o, &w);
    if (r != SPS_OK) {
        fprintf(stderr, "user_scenes: %s\n", w ? sps_world_last_error(w) : sps_result_string(r));
        return 2;
    }
    sps_world_diagnostics(w, all, &d0);
    e0 = total_energy(&d0);
    mech0 = d0.kinetic_energy + d0.strain_energy;
    if (mech0 <= 0) mech0 = -d0.potential_energy; /* a body released at rest: its potential energy [J] sets the scale */
    if (mech0 <= 0) mech0 = 1e-30;
    x_start = mean_x(w);
    while (sps_world_time(w) < o.t_end - 1e-12) {
        /* the first 10 ms sampled every millisecond (an advection step of a scene at rest is longer) */
        if ((r = sps_world_time(w) < 0.01 ? sps_world_advance(w, sps_world_time(w) + (sps_real)0.001, NULL, NULL) : sps_world_step(w)) != SPS_OK)
            break;
        sps_world_diagnostics(w, all, &d);
        if (sps_world_time(w) <= 0.01 + 1e-9 && d.max_speed > speed_10ms) speed_10ms = d.max_speed;
        if ((total_energy(&d) - e0) / mech0 > gain) gain = (total_energy(&d) - e0) / mech0;
    }
    sps_world_diagnostics(w, all, &d);
    printf("RESULT scene=%s kind=%s dim=%d slip=%s spin=%g shear=%s rotation=%s t=%.4f status=%s energy_start=%.6g mech_start=%.6g "
           "max_gain=%.5f watchdog_growth=%.5f target=0.02 watchdog_events=%d warnings=%d max_speed_10ms=%.4g slid=%.5f slide_theory=%.5f max_speed=%.4g min_spacing=%.3f particles=%d\n",
           o.scene, o.rigid ? "rigid" : "elastic", o.dim, o.noslip ? "noslip" : "free", o.spin, o.shear < 0 ? "default" : shear_names[o.shear],
           o.rotation < 0 ? "default" : rotation_names[o.rotation], (double)sps_world_time(w), r == SPS_OK ? "ok" : r == SPS_ERR_UNSTABLE ? "unstable" : "refused", e0,
           mech0, gain, (double)d.energy_growth, d.energy_growth_events, g_warnings, speed_10ms, mean_x(w) - x_start,
           o.gravity > 0 ? 1 / (2 * 0.3 * o.gravity) : 0 /* v0^2 / (2 mu g): the slide's 1 m/s at mu 0.3 */, (double)d.max_speed, (double)d.min_spacing, d.particles);
    if (r != SPS_OK) fprintf(stderr, "user_scenes: %s\n", sps_world_last_error(w));
    sps_world_destroy(w);
    return r == SPS_OK ? 0 : 2;
}
