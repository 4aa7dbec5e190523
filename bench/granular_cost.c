/* granular_cost.c - what the granular hourglass control costs per particle and acoustic
   sub-step, as a ratio measured in one process in interleaved rounds (the machine may be
   shared: only the ratio means anything): the column collapse (examples/column_collapse2d.c,
   C4, dp 0.004) with shear = OG (the default, the paper's formulation without a penalty) and
   with GNO-A (the penalty, switched off on the cone), each from its
   start to --tend (the column fails and flows: both states, elastic and on the cone, are in
   it). The best round of each is kept.

   Build: make build/granular_cost      Run: ./build/granular_cost --rounds 3 --threads 1 */
#define SPHSOLID_IMPLEMENTATION
#include "../examples/common.h"

static sps_world* build(int controlled, int threads) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body soil;
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.1, 0}, tank_hi[3] = {0.5, 0.15, 0};
    granular_options g = {0, 21.9, 0.1, SPS_CONE_PAPERS}; /* C4, as column_collapse2d */
    wd.threads = threads;
    wd.log = ex_log;
    wd.cfl_acoustic = (sps_real)0.4;
    bd.material.density = 2040;
    bd.material.youngs_modulus = (sps_real)5.84e6;
    bd.material.poisson_ratio = (sps_real)0.3;
    bd.name = "soil";
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    apply_granular(&g, &bd);
    bd.shear = controlled ? SPS_SHEAR_GNO_A : SPS_SHEAR_OG;
    wd.dim = 2;
    wd.dp = (sps_real)0.004;
    wd.gravity[1] = (sps_real)-GRANULAR_GRAVITY;
    ex_check(NULL, sps_world_create(&wd, &w));
    ex_check(w, sps_world_add_box_walls(w, lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_NO_SLIP));
    ex_check(w, sps_world_add_body(w, &bd, &soil));
    ex_check(w, sps_body_add_box(w, soil, lo, hi, NULL));
    return w;
}

int main(int argc, char** argv) {
    int rounds = 3, threads = 1, k, r, particles[2] = {0, 0};
    double t_end = 0.1, best[2] = {1e30, 1e30};
    long steps[2] = {0, 0};
    const char* names[2] = {"OG (no penalty)", "GNO-A (on elastic particles)"};
    opt_spec opts[] = {
        {"rounds", OPT_INT, &rounds, "interleaved rounds (the best of each variant is kept)", 1, 100, NULL},
        {"threads", OPT_INT, &threads, "OpenMP threads", 0, 1024, NULL},
        {"tend", OPT_REAL, &t_end, "simulated time of each run [s]", 1e-5, 10, NULL},
    };
    ex_short_openmp_spin(argv);
    opt_parse(argc, argv, "the price of the granular hourglass control per particle-step", opts, 3);
    for (r = 0; r < rounds; ++r)
        for (k = 0; k < 2; ++k) {
            sps_world* w = build(k, threads);
            sps_diagnostics d;
            double t0, per;
            ex_check(w, sps_world_step(w)); /* the first step's allocations are not the price */
            t0 = wall_seconds();
            ex_check(w, sps_world_advance(w, (sps_real)t_end, NULL, NULL));
            per = wall_seconds() - t0;
            ex_check(w, sps_world_diagnostics(w, (sps_body){0}, &d));
            particles[k] = sps_world_particle_count(w);
            steps[k] = d.acoustic_steps;
            per /= (double)particles[k] * (double)steps[k];
            if (per < best[k]) best[k] = per;
            sps_world_destroy(w);
        }
    for (k = 0; k < 2; ++k) printf("%-28s particles=%d substeps=%ld ns_per_particle_step=%.1f\n", names[k], particles[k], steps[k], 1e9 * best[k]);
    printf("RESULT case=granular_cost control_ratio=%.3f threads=%d rounds=%d tend=%g\n", best[1] / best[0], threads, rounds, t_end);
    return 0;
}
