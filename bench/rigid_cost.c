/* rigid_cost - what a free rigid body costs (FREE RIGID BODIES in sphsolid.h).

   1. Per particle-step: a 2D box 0.2 x 0.1 m (dp = --dp) resting on a floor wall under gravity,
      once as a free rigid body and once as an ENO-A elastic body (rho0 1000, E 1e6, nu 0.3),
      each timed on one thread over --substeps acoustic sub-steps (sps_world_advance_substeps,
      after a warm-up step), interleaved in --rounds rounds, best of each: ns per particle-step
      and the ratio rigid / ENO-A.
   2. The time step: the water tank of examples/rigid_float.c (1 m wide, 0.5 m deep, dp 0.02)
      over --tank-time seconds, without a crate and with a free rigid crate 0.1 x 0.1 m of
      density 7800 (steel; E 1e6, its contact stiffness) dropped in: the sub-step counts and their
      ratio.
   Prints one line per figure. The machine may be shared: only the ratios, measured in one
   process, mean anything.

   Usage: ./build/rigid_cost [--dp X] [--substeps N] [--rounds N] [--tank-time T] */
#define SPHSOLID_IMPLEMENTATION
#include "../examples/common.h"

static sps_real hydrostatic(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(1000 * 9.81 * (0.5 - (double)x[1]));
}

static sps_world* resting_box(double dp, sps_material_kind kind) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body b;
    const sps_real lo[3] = {0, 0.5 * (sps_real)dp, 0}, hi[3] = {0.2, 0.1 + 0.5 * (sps_real)dp, 0}, point[3] = {0, 0, 0}, normal[3] = {0, 1, 0};
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.threads = 1;
    wd.gravity[1] = -9.81;
    wd.log = ex_log;
    bd.material.kind = kind;
    ex_check(NULL, sps_world_create(&wd, &w));
    ex_check(w, sps_world_add_body(w, &bd, &b));
    ex_check(w, sps_body_add_box(w, b, lo, hi, NULL));
    ex_check(w, sps_world_add_wall(w, point, normal, SPS_WALL_FREE_SLIP));
    ex_check(w, sps_world_step(w));
    return w;
}

static long tank_substeps(double t_end, int crate) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def water = sps_default_body_def(), box = sps_default_body_def();
    sps_world* w;
    sps_body bw, bb;
    sps_real tank_lo[3] = {0, 0, 0}, tank_hi[3] = {1, 2, 0}, lo[3] = {0, 0, 0}, hi[3] = {1, 0.5, 0};
    sps_diagnostics d;
    wd.dim = 2;
    wd.dp = 0.02;
    wd.gravity[1] = -9.81;
    wd.log = ex_log;
    water.material.kind = SPS_MATERIAL_FLUID;
    water.material.fluid.sound_speed = (sps_real)(10 * sqrt(2 * 9.81 * 0.5));
    box.material.kind = SPS_MATERIAL_RIGID_DYNAMIC;
    box.material.density = 7800;
    ex_check(NULL, sps_world_create(&wd, &w));
    ex_check(w, sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP));
    ex_check(w, sps_world_add_body(w, &water, &bw));
    ex_check(w, sps_body_add_box(w, bw, lo, hi, NULL));
    ex_check(w, sps_body_set_pressure(w, bw, hydrostatic, NULL));
    if (crate) {
        lo[0] = 0.45; hi[0] = 0.55; lo[1] = 0.51; hi[1] = 0.61;
        ex_check(w, sps_world_add_body(w, &box, &bb));
        ex_check(w, sps_body_add_box(w, bb, lo, hi, NULL));
    }
    ex_check(w, sps_world_advance(w, (sps_real)t_end, NULL, NULL));
    ex_check(w, sps_world_diagnostics(w, (sps_body){0}, &d));
    sps_world_destroy(w);
    return d.acoustic_steps;
}

int main(int argc, char** argv) {
    double dp = 0.0025, tank_time = 1, best[2] = {1e30, 1e30};
    int substeps = 2000, rounds = 5, r, k, n[2] = {0, 0};
    long plain, crate;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing of the resting box [m]", 1e-4, 0.05, NULL},
        {"substeps", OPT_INT, &substeps, "acoustic sub-steps per timing", 1, 1000000, NULL},
        {"rounds", OPT_INT, &rounds, "interleaved rounds (best of)", 1, 100, NULL},
        {"tank-time", OPT_REAL, &tank_time, "simulated time of the tank runs [s]", 0.01, 100, NULL},
    };
    ex_short_openmp_spin(argv);
    opt_parse(argc, argv, "the cost of a free rigid body: per particle-step, and in a water tank's time step", opts, (int)(sizeof opts / sizeof *opts));
    for (r = 0; r < rounds; ++r)
        for (k = 0; k < 2; ++k) {
            sps_world* w = resting_box(dp, k == 0 ? SPS_MATERIAL_RIGID_DYNAMIC : SPS_MATERIAL_ELASTIC);
            double t0 = wall_seconds(), t;
            ex_check(w, sps_world_advance_substeps(w, substeps, 0, NULL));
            t = wall_seconds() - t0;
            n[k] = sps_world_particle_count(w);
            if (t < best[k]) best[k] = t;
            sps_world_destroy(w);
        }
    printf("rigid_cost particle_step: particles=%d substeps=%d rigid_ns=%.1f eno_a_ns=%.1f ratio=%.3f\n", n[0], substeps,
           1e9 * best[0] / ((double)n[0] * substeps), 1e9 * best[1] / ((double)n[1] * substeps), best[0] / n[0] / (best[1] / n[1]));
    plain = tank_substeps(tank_time, 0);
    crate = tank_substeps(tank_time, 1);
    printf("rigid_cost tank: t=%g substeps_without=%ld substeps_with_steel_crate=%ld ratio=%.4f\n", tank_time, plain, crate, (double)crate / plain);
    return 0;
}
