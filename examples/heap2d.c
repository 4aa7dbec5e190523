/* heap2d.c - the angle of repose of a cohesionless heap: a column lifted slowly (2D).

   A column W = 0.05 m wide and H = 0.1 m high of cohesionless Drucker-Prager soil (the C4
   material: rho0 = 2040, E = 5.84 MPa, nu = 0.3, c = 0, psi = 0; friction angle phi = --phi)
   stands in the middle of a rough (no-slip) floor 0.5 m long, is released from zero stress under
   g = 9.8 and slumps into a heap. The standard measurement lifts the cylinder slowly (the
   "lifting cylinder" method), so that the heap forms without inertia; here the body's velocity
   damping (--damping c [1/s], sps_body_def.damping) keeps the collapse quasi-static in the
   same way (with --damping 0 it is the fast collapse, whose deposit runs out farther and stands
   lower). At the end the heap's flanks are fitted by straight lines between 20 % and 80 % of its
   height, on both sides: the angle of repose is the mean of the two slopes' angles. With the
   cone fitted to Mohr-Coulomb in plane strain (material.granular.yield_cone's default, --cone) an
   infinite slope stands up to the friction angle, so the quasi-static heap's flanks should stand
   at about phi (a heap of dry grains: angle of repose close to the internal friction angle);
   --cone papers (UTVF eq. 14) acts as a smaller angle with psi = 0 (28.7 degrees for 30).

   With --pour the same volume is poured instead: rows of particles COLUMN_WIDTH wide are added
   at rest at the inlet, POUR_HEIGHT above the floor in the middle, one every sqrt(2 dp/g) (the
   time the row before needs to fall dp), so the heap builds from a falling stream. Refused
   without damping and with UTVF, for the measured reasons pour_refusal gives.

   Build: make examples     Run: ./build/heap2d --phi 30 [--pour]
   Expect: angle within 3 degrees of phi (20, 30, 40).
   Smoke: heap2d --dp 0.01 --tend 0.01
   Smoke: heap2d --dp 0.005 --tend 0.2 --pour */
#include "common.h"

#define FLOOR_LENGTH 0.5
#define COLUMN_WIDTH 0.05
#define COLUMN_HEIGHT 0.1
#define POUR_HEIGHT 0.15

typedef struct {
    output_plan output;
    double zigzag_max;
} run_state;

/* At every CSV row: the largest zigzag indicator (DIAGNOSTICS: near 0 while the soil flows
   smoothly, above 1 when the particle-scale zigzag mode carries the motion). */
static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    if (output_tick(w, &s->output, "", &d) && d.zigzag > s->zigzag_max) s->zigzag_max = d.zigzag;
    return 0;
}

/* Pours the column's volume: one row at the inlet every sqrt(2 dp / g), each added between steps
   (sps_body_add_box), then advances to t_end; a failed step ends the program (ex_check_step, or
   output_close for the last). */
static void pour(sps_world* w, sps_body soil, double dp, double t_end, run_state* s) {
    const double interval = sqrt(2 * dp / 9.8);
    const int rows = (int)(COLUMN_HEIGHT / dp + 0.5);
    sps_real lo[3] = {0.5 * (FLOOR_LENGTH - COLUMN_WIDTH), POUR_HEIGHT, 0}, hi[3] = {0.5 * (FLOOR_LENGTH + COLUMN_WIDTH), POUR_HEIGHT + dp, 0};
    int k;
    for (k = 0; k < rows && k * interval < t_end; ++k) {
        if (k > 0) ex_check_step(w, sps_world_advance(w, (sps_real)(k * interval), on_step, s), &s->output);
        sps_body_add_box(w, soil, lo, hi, NULL);
    }
    sps_world_advance(w, (sps_real)t_end, on_step, s); /* a failed step: output_close reports it */
}

/* Why a pour is refused (NULL: it is not), measured (bench/VALIDATION.md, "Granular media that
   hold their shape"). */
static const char* pour_refusal(double damping, int transport) {
    if (damping == 0)
        return "--pour needs --damping > 0: undamped, the rows hit the floor at 1.7 m/s and a grain of the first rows was shot "
               "off at 5.6 m/s and escaped at t = 0.46 s (dp 0.0025, with or without --transport utvf)";
    if (transport == SPS_TRANSPORT_UTVF)
        return "--pour with --transport utvf: UTVF does not shift the falling stream (all its particles are surface particles) "
               "and in the heap it builds pulled particles together: smallest spacing 5e-11 dp at dp 0.005 (0.33 dp without), "
               "0.35 dp at dp 0.0025 (0.49 dp without)";
    return NULL;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_OG, .cfl = 0.4, .t_end = 3, .vtk_every = 0.1, .csv_every = 0.01, .E = 5.84e6, .nu = 0.3,
                        .rho0 = 2040, .out = "out/heap2d", .jitter = 0, .seed = 1, .transport = 0, PNG_DEFAULTS};
    double dp = 0.0025, damping = 100; /* 30 lifts too fast: the heap runs out to 26.8 degrees at phi 30 */
    int pouring = 0;
    granular_options g = {0, 30, 0.1, SPS_CONE_PLANE_STRAIN};
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 5e-4, 0.01, NULL},
        {"damping", OPT_REAL, &damping, "velocity damping c [1/s] that keeps the collapse quasi-static (0: the fast collapse)", 0, 1e3, NULL},
        {"pour", OPT_FLAG, &pouring, "pour the column's volume from POUR_HEIGHT = 0.15 m instead of releasing it", 0, 0, NULL},
        GRANULAR_OPTION_SPECS(g),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body soil, all = {0};
    sps_diagnostics d;
    sps_real lo[3] = {0.5 * (FLOOR_LENGTH - COLUMN_WIDTH), 0, 0}, hi[3] = {0.5 * (FLOOR_LENGTH + COLUMN_WIDTH), COLUMN_HEIGHT, 0};
    sps_real tank_lo[3] = {0, 0, 0}, tank_hi[3] = {FLOOR_LENGTH, 2 * COLUMN_HEIGHT, 0};
    run_state s;
    double wall, height = 0, left, right, angle, *top;
    int columns, k, peak = 0;

    ex_options(argc, argv, "2D angle of repose: a cohesionless column lifted slowly slumps into a heap", opts, &c, &wd, &bd);
    if (pouring && pour_refusal(damping, c.transport)) {
        fprintf(stderr, "heap2d: %s\n", pour_refusal(damping, c.transport));
        return 2;
    }
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    memset(&s, 0, sizeof s);
    bd.name = "soil";
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    apply_granular(&g, &bd);
    bd.damping = (sps_real)damping;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-GRANULAR_GRAVITY;
    sps_world_create(&wd, &w);
    sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_NO_SLIP);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &soil);
    if (!pouring) sps_body_add_box(w, soil, lo, hi, NULL);

    output_open(&s.output, &c, "heap2d", "velocity", "");
    if (pouring) pour(w, soil, dp, c.t_end, &s);
    else {
        on_step(w, &s); /* t = 0: the first CSV row and snapshot */
        sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    }
    wall = output_close(w, &s.output);
    sps_world_diagnostics(w, all, &d);

    columns = (int)(FLOOR_LENGTH / dp) + 1;
    top = (double*)calloc((size_t)columns, sizeof(double));
    if (!top) return 1;
    ex_heap_surface(w, all, dp, columns, NULL, 2, top, NULL);
    for (k = 0; k < columns; ++k)
        if (top[k] > height) { height = top[k]; peak = k; }
    left = ex_flank_slope(top, dp, peak, 0, height);
    right = ex_flank_slope(top, dp, peak, columns - 1, height);
    angle = 0.5 * (atan(fabs(left)) + atan(fabs(right))) * 180 / 3.14159265358979323846;
    printf("heap: column %g m x %g m, dp = %g, %d particles, phi = %g deg, damping %g 1/s, t = %.3g s\n", COLUMN_WIDTH, COLUMN_HEIGHT, dp,
           sps_world_particle_count(w), g.phi, damping, (double)d.time);
    printf("  height %.4f m; flanks %.1f and %.1f degrees: angle of repose %.1f deg against phi = %g deg (%+.1f deg); largest speed %.3g m/s\n",
           height, atan(fabs(left)) * 180 / 3.14159265358979323846, atan(fabs(right)) * 180 / 3.14159265358979323846, angle, g.phi,
           angle - g.phi, (double)d.max_speed);
    printf("  zigzag indicator (0: smooth flow, above 1: zigzag): %.3f at the end, largest %.3f (CSV rows)\n", (double)d.zigzag,
           s.zigzag_max);
    printf("RESULT case=heap2d angle=%.2f phi=%g height=%.4f damping=%g dp=%g t=%.4g max_speed=%.3g zigzag=%.3f zigzag_max=%.3f "
           "zigzag_limit=1 clustered=%d pour=%d %s particles=%d steps=%ld wall_s=%.2f out=%s\n",
           angle, g.phi, height, damping, dp, (double)d.time, (double)d.max_speed, (double)d.zigzag, s.zigzag_max,
           ex_clustered_particles(w, dp, 0.5), pouring, common_result_fields(&c),
           sps_world_particle_count(w), d.acoustic_steps, wall, c.out);
    free(top);
    sps_world_destroy(w);
    return 0;
}
