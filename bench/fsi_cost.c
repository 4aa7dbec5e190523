/* fsi_cost - what the fluid-structure coupling costs against the fluid's own passes.

   Builds water 0.4 x 0.4 m at rest in a U-shaped rigid tank 3 dp thick (dp = --dp, default
   0.01: 1600 water particles), takes one step (the neighbour and contact lists), then times on
   one thread, interleaved in rounds, the best of --rounds rounds of --repeat calls each:
     fluid      the water's pressure and continuity passes with the coupling's terms switched off
                (the body's coupled flag cleared): the fluid passes alone;
     coupled    the same two passes with the coupling's continuity terms, plus the coupling's
                forces (the contact pass's force loop over the water's particles and over the
                tank's: each fluid-solid pair is evaluated once from each side).
   Prints ns per water particle-step for both and the ratio coupled / fluid, and the share of the
   water particles that have a solid neighbour (the only ones that pay for the coupling). The
   machine may be shared: only the ratio, measured in one process, means anything. This program
   reads library internals (a body's pass kernels, the contact force), so it is a probe.

   Usage: ./build/fsi_cost [--dp X] [--repeat R] [--rounds N] */
#define SPHSOLID_IMPLEMENTATION
#include "../examples/common.h"

static sps_real hydrostatic(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(1000 * 9.81 * (0.4 - (double)x[1]));
}

/* The water's fluid passes: pressure, then continuity (with its coupling terms if coupled). */
static void fluid_passes(sps_world* w, sps__body* water, sps_real dt) {
    sps__run_groups(w, water, water->model.pass.pressure, dt);
    sps__run_groups(w, water, water->model.pass.continuity, dt);
}

/* The coupling's forces: the contact force loop over every particle (all pairs are coupled). */
static void coupling_forces(sps_world* w, sps_real dt) {
    int i;
    for (i = 0; i < w->n; ++i) sps__contact_force(w, i, dt);
}

int main(int argc, char** argv) {
    double dp = 0.01, t = 0, best_fluid = 1e30, best_coupled = 1e30;
    int repeat = 20, rounds = 7, k, r, i, coupled_particles = 0;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (water 0.4 x 0.4 m)", 1e-3, 0.05, NULL},
        {"repeat", OPT_INT, &repeat, "calls per timing", 1, 100000, NULL},
        {"rounds", OPT_INT, &rounds, "interleaved rounds (the best is kept)", 1, 1000, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def water_def = sps_default_body_def(), tank_def = sps_default_body_def();
    sps_world* w;
    sps_body water, tank;
    sps__body* b;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.4, 0.4, 0};
    const double wall_t = 3 * dp;
    opt_parse(argc, argv, "cost of the fluid-structure coupling against the fluid passes alone", opts, (int)(sizeof opts / sizeof *opts));
    wd.dim = 2; wd.dp = (sps_real)dp; wd.threads = 1; wd.gravity[1] = (sps_real)-9.81; wd.log = ex_log;
    water_def.material.kind = SPS_MATERIAL_FLUID;
    water_def.material.fluid.sound_speed = (sps_real)(10 * sqrt(2 * 9.81 * 0.4));
    tank_def.material.kind = SPS_MATERIAL_RIGID;
    ex_check(NULL, sps_world_create(&wd, &w));
    ex_check(w, sps_world_add_body(w, &water_def, &water));
    ex_check(w, sps_body_add_box(w, water, lo, hi, NULL));
    ex_check(w, sps_body_set_pressure(w, water, hydrostatic, NULL));
    ex_check(w, sps_world_add_body(w, &tank_def, &tank));
    lo[0] = lo[1] = (sps_real)-wall_t; hi[0] = (sps_real)(0.4 + wall_t); hi[1] = 0;
    ex_check(w, sps_body_add_box(w, tank, lo, hi, NULL));
    lo[1] = 0; hi[0] = 0; hi[1] = 0.6;
    ex_check(w, sps_body_add_box(w, tank, lo, hi, NULL));
    lo[0] = 0.4; hi[0] = (sps_real)(0.4 + wall_t);
    ex_check(w, sps_body_add_box(w, tank, lo, hi, NULL));
    ex_check(w, sps_world_step(w)); /* lists and contact pairs */
    b = &w->bodies[sps_body_index(w, water)];
    for (i = b->begin; i < b->end; ++i) coupled_particles += w->ct_first[i + 1] > w->ct_first[i];
    for (r = 0; r < rounds; ++r) {
        double start = wall_seconds();
        b->coupled = 0;
        for (k = 0; k < repeat; ++k) fluid_passes(w, b, w->dt);
        t = wall_seconds() - start;
        if (t < best_fluid) best_fluid = t;
        start = wall_seconds();
        b->coupled = 1;
        for (k = 0; k < repeat; ++k) {
            fluid_passes(w, b, w->dt);
            coupling_forces(w, w->dt);
        }
        t = wall_seconds() - start;
        if (t < best_coupled) best_coupled = t;
    }
    best_fluid *= 1e9 / ((double)repeat * (b->end - b->begin));
    best_coupled *= 1e9 / ((double)repeat * (b->end - b->begin));
    printf("RESULT case=fsi_cost dp=%g water=%d with_solid_neighbours=%d (%.1f%%) fluid_ns=%.1f coupled_ns=%.1f ratio=%.3f "
           "coupling_share=%.3f (ns per water particle-step, best of %d rounds of %d)\n",
           dp, b->end - b->begin, coupled_particles, 100.0 * coupled_particles / (b->end - b->begin), best_fluid, best_coupled,
           best_coupled / best_fluid, (best_coupled - best_fluid) / best_fluid, rounds, repeat);
    sps_world_destroy(w);
    return 0;
}
