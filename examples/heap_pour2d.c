/* heap_pour2d.c - a heap poured from a hopper: the angle of repose, grains shot out (2D).

   A 2D hopper (two rigid wall plates at HOPPER_ANGLE = 60 degrees from the horizontal, an
   orifice ORIFICE_WIDTH = 0.025 m wide, --drop above a rough (no-slip) floor 0.5 m long) holds
   the volume of heap2d's column (0.005 m^2) of cohesionless Drucker-Prager soil (heap2d's: the C4
   material, phi = --phi, psi = 0, the plane-strain cone) at rest at t = 0. It drains through
   the orifice under g = 9.8, falls --drop and builds a heap on the floor; no velocity damping
   by default (the grains fall freely). Rigid wall bodies touch the soil by the contact law,
   without friction (CONTACT: Drucker-Prager bodies have none), so the hopper empties.
   At the end: the heap's flanks fitted between 20 % and 80 % of its height, as heap2d (the
   angle of repose, the mean of the two flanks); grains shot out: particles whose speed ever
   exceeded 1.5 times the free-fall speed from the top of the fill to the floor (sqrt(2 g
   H_fall): no grain gets faster by falling, so one that does took energy from a collision:
   1.5 is 2.25 times the energy a fall gives); strays: particles that end more than 2 dp beyond
   the heap's toes; clustered particles (another closer than dp/2). --transport utvf pours with
   the transport correction; compare the default (none).

   Build: make examples     Run: ./build/heap_pour2d [--transport utvf] [--phi 30] [--dp D]
   Expect: no grain shot out (at most one passes the bound, by a few %), clustered 1-2 % with
   UTVF (3-5 % without); the heap spreads to 2-7 degrees, not phi: the pour's inertia
   (bench/VALIDATION.md, "Pouring from a hopper"; --damping 100 --tend 3: a quasi-static pour).
   Smoke: heap_pour2d --dp 0.005 --tend 0.05 --transport utvf */
#include "common.h"

#define FLOOR_LENGTH 0.5
#define ORIFICE_WIDTH 0.025
#define HOPPER_ANGLE 60.0  /* degrees from the horizontal: steeper than the grains' friction, mass flow */
#define HOPPER_HEIGHT 0.1  /* the plates' height above the orifice [m] */
#define SOIL_AREA 0.005    /* heap2d's column, 0.05 m x 0.1 m [m^2] */
#define WALL_ROWS 3        /* the plates' thickness in dp: beyond the kernel's support 2h = 2.6 dp */
#define PEAK_RANGE 0.05    /* the heap's top is sought this far [m] either side of the orifice's axis */
#define FILL_GAP 0.5       /* the soil filled dp/2 (across) off the plates: filled flush against their lattice
                              staircase, it started in the contact's push (a corner grain left at 6 m/s in 5 ms) */

typedef struct {
    double orifice_y, dp; /* the orifice's height [m], the spacing */
} hopper;

/* Horizontal distance [m] of x beyond the hopper's inner face at height x[1] (negative inside). */
static double beyond_face(const hopper* h, const sps_real x[3]) {
    const double half = 0.5 * ORIFICE_WIDTH + (x[1] - h->orifice_y) / tan(HOPPER_ANGLE * PI / 180);
    return fabs(x[0] - 0.5 * FLOOR_LENGTH) - half;
}
/* The plates: WALL_ROWS dp thick across their face, from the orifice up HOPPER_HEIGHT. */
static sps_real plate_sdf(const sps_real x[3], void* user) {
    const hopper* h = (const hopper*)user;
    const double across = beyond_face(h, x) * sin(HOPPER_ANGLE * PI / 180);
    const double below_or_above = fmax(h->orifice_y - x[1], x[1] - h->orifice_y - HOPPER_HEIGHT);
    return (sps_real)fmax(fmax(-across, across - WALL_ROWS * h->dp), below_or_above);
}
/* The fill's height above the orifice: ORIFICE_WIDTH z + z^2 / tan(angle) = SOIL_AREA. */
static double fill_height(void) {
    const double a = 1 / tan(HOPPER_ANGLE * PI / 180), b = ORIFICE_WIDTH;
    return (-b + sqrt(b * b + 4 * a * SOIL_AREA)) / (2 * a);
}
/* The soil: inside the plates, FILL_GAP dp off them, from the orifice up to the fill's height. */
static sps_real soil_sdf(const sps_real x[3], void* user) {
    const hopper* h = (const hopper*)user;
    const double below_or_above = fmax(h->orifice_y - x[1], x[1] - h->orifice_y - fill_height());
    return (sps_real)fmax(beyond_face(h, x) * sin(HOPPER_ANGLE * PI / 180) + FILL_GAP * h->dp, below_or_above);
}

typedef struct {
    output_plan output;
    sps_body soil;
    double speed_bound, max_speed, max_speed_at[3]; /* the largest speed, and its time and place (t, x, y) */
    unsigned char* shot; /* per particle id: its speed exceeded speed_bound */
    int shot_out;
} run_state;

/* After every step: the soil's largest speed and the grains that exceed the bound. */
static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    const sps_real *vx = sps_world_field(w, SPS_FIELD_VELOCITY_X), *vy = sps_world_field(w, SPS_FIELD_VELOCITY_Y);
    const int* id = sps_world_particle_ids(w);
    sps_diagnostics d;
    int i, first, count;
    if (sps_world_time(w) > 0 && sps_body_field(w, s->soil, "velocity_x", NULL, &first, &count)) /* the body's range: after the first step */
        for (i = first; i < first + count; ++i) {
            const double speed = sqrt(vx[i] * vx[i] + vy[i] * vy[i]);
            if (speed > s->max_speed) {
                const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
                s->max_speed = speed;
                s->max_speed_at[0] = (double)sps_world_time(w);
                s->max_speed_at[1] = (double)x[i];
                s->max_speed_at[2] = (double)y[i];
            }
            if (speed > s->speed_bound && !s->shot[id[i]]) { s->shot[id[i]] = 1; ++s->shot_out; }
        }
    output_tick(w, &s->output, "", &d);
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_OG, .cfl = 0.4, .t_end = 1.5, .vtk_every = 0.05, .csv_every = 0.01, .E = 5.84e6, .nu = 0.3,
                        .rho0 = 2040, .out = "out/heap_pour2d", .jitter = 0, .seed = 1, .transport = 0, PNG_DEFAULTS};
    double dp = 0.0025, damping = 0, drop = 0.1;
    int rough_floor = 0;
    granular_options g = {0, 30, 0.1, SPS_CONE_PLANE_STRAIN};
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 5e-4, 0.01, NULL},
        {"drop", OPT_REAL, &drop, "the orifice's height above the floor [m]", 0.02, 0.3, NULL},
        {"floor", OPT_CHOICE, &rough_floor, "the floor and side walls: no-slip, or free-slip with Coulomb friction mu = tan(phi)", 0, 0, "no-slip|friction"},
        {"damping", OPT_REAL, &damping, "the soil's velocity damping c [1/s] (0: free fall)", 0, 1e3, NULL},
        GRANULAR_OPTION_SPECS(g),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def(), wall_def;
    sps_world* w;
    sps_body plates, all = {0};
    sps_diagnostics d;
    sps_real tank_lo[3] = {0, 0, 0}, tank_hi[3] = {FLOOR_LENGTH, 1, 0}, lo[3], hi[3];
    hopper h;
    run_state s;
    const sps_real* x;
    double wall, height = 0, left, right, angle, left_toe, right_toe, *top;
    int columns, k, peak = 0, soil_count, first, strays = 0, clustered, k0, k1;

    ex_options(argc, argv, "2D angle of repose of a heap poured from a hopper", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    memset(&s, 0, sizeof s);
    h.orifice_y = drop;
    h.dp = dp;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-GRANULAR_GRAVITY;
    sps_world_create(&wd, &w);
    sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, rough_floor ? SPS_WALL_FREE_SLIP : SPS_WALL_NO_SLIP);
    if (rough_floor) sps_world_set_wall_friction(w, -1, (sps_real)tan(g.phi * PI / 180));

    wall_def = sps_default_body_def(); /* the plates: a wall body with the soil's stiffness (the contact's modulus) */
    wall_def.name = "hopper";
    wall_def.material = bd.material;
    wall_def.material.kind = SPS_MATERIAL_RIGID;
    sps_world_add_body(w, &wall_def, &plates);
    lo[0] = 0; lo[1] = (sps_real)drop; lo[2] = 0; /* one lattice for plates and soil: filled flush */
    hi[0] = FLOOR_LENGTH; hi[1] = (sps_real)(drop + HOPPER_HEIGHT + dp); hi[2] = 0;
    sps_body_add_sdf(w, plates, lo, hi, plate_sdf, &h, NULL);

    bd.name = "soil";
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    apply_granular(&g, &bd);
    bd.damping = (sps_real)damping;
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &s.soil);
    sps_body_add_sdf(w, s.soil, lo, hi, soil_sdf, &h, &soil_count);

    s.speed_bound = 1.5 * sqrt(2 * GRANULAR_GRAVITY * (drop + fill_height()));
    s.shot = (unsigned char*)calloc((size_t)sps_world_particle_count(w), 1);
    if (!s.shot) return 1;
    output_open(&s.output, &c, "heap_pour2d", "velocity", "");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    sps_world_diagnostics(w, all, &d);

    /* the heap: the soil's columns holding 2 particles or more, contiguous about the highest
       within PEAK_RANGE of the orifice's axis (grains spread to a side wall are not its top) */
    columns = (int)(FLOOR_LENGTH / dp) + 1;
    top = (double*)calloc((size_t)columns, sizeof(double));
    if (!top) return 1;
    ex_heap_surface(w, s.soil, dp, columns, NULL, 2, top, NULL);
    for (k = 0; k < columns; ++k)
        if (fabs((k + 0.5) * dp - 0.5 * FLOOR_LENGTH) < PEAK_RANGE && top[k] > height) { height = top[k]; peak = k; }
    for (k0 = peak; k0 > 0 && top[k0 - 1] > 0; --k0) {}
    for (k1 = peak; k1 < columns - 1 && top[k1 + 1] > 0; ++k1) {}
    left_toe = k0 * dp;
    right_toe = (k1 + 1) * dp;
    x = sps_world_field(w, SPS_FIELD_POSITION_X);
    if (!sps_body_field(w, s.soil, "position_x", NULL, &first, &soil_count)) return 1;
    for (k = first; k < first + soil_count; ++k)
        if (x[k] < left_toe - 2 * dp || x[k] > right_toe + 2 * dp) ++strays;
    left = ex_flank_slope(top, dp, peak, 0, height);
    right = ex_flank_slope(top, dp, peak, columns - 1, height);
    angle = 0.5 * (atan(fabs(left)) + atan(fabs(right))) * 180 / PI;
    clustered = ex_clustered_particles(w, dp, 0.5);
    printf("heap poured from a hopper: orifice %g m wide, %g m above the floor; %d soil particles, dp = %g, phi = %g deg, %s, "
           "damping %g 1/s, t = %.3g s\n",
           ORIFICE_WIDTH, drop, soil_count, dp, g.phi, transport_name(c.transport), damping, (double)d.time);
    printf("  height %.4f m, toes at %.4f and %.4f m; flanks %.1f and %.1f degrees: angle of repose %.1f deg against phi = %g deg (%+.1f deg)\n",
           height, left_toe, right_toe, atan(fabs(left)) * 180 / PI, atan(fabs(right)) * 180 / PI, angle, g.phi, angle - g.phi);
    printf("  shot out (speed above %.2f m/s): %d; strays (beyond the toes): %d; largest speed %.3g m/s (t = %.3f s at x = %.3f, y = %.3f m); clustered %d (%.2f %%); "
           "smallest spacing %.3f dp\n",
           s.speed_bound, s.shot_out, strays, s.max_speed, s.max_speed_at[0], s.max_speed_at[1], s.max_speed_at[2], clustered, 100.0 * clustered / soil_count, (double)d.min_spacing);
    printf("RESULT case=heap_pour2d angle=%.2f phi=%g height=%.4f shot_out=%d strays=%d speed_bound=%.3f max_speed=%.3g max_speed_t=%.3f clustered=%d "
           "clustered_fraction=%.4f min_spacing=%.3f drop=%g floor=%s damping=%g dp=%g t=%.4g %s particles=%d steps=%ld wall_s=%.2f out=%s\n",
           angle, g.phi, height, s.shot_out, strays, s.speed_bound, s.max_speed, s.max_speed_at[0], clustered, (double)clustered / soil_count,
           (double)d.min_spacing, drop, rough_floor ? "friction" : "no-slip", damping, dp, (double)d.time, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps,
           wall, c.out);
    free(top);
    free(s.shot);
    sps_world_destroy(w);
    return 0;
}
