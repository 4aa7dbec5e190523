/* damping_cost.c - what friction and Kelvin-Voigt damping cost per particle and acoustic
   sub-step, as ratios measured in one process in interleaved rounds (the machine may be shared:
   only the ratios mean anything): the ring collision (examples/rings2d.c, A5) without and with
   friction 0.5 between the rings, and the 2D plate (examples/plate2d.c, A1, ENO-A) without and
   with eta = 200 Pa s. Each round runs every variant from its start to --tend; the best round
   of each is kept. Damping also shortens the time step (the viscous bound of the acoustic
   step): that is printed as the sub-step count, apart from the price per sub-step.

   Build: make build/damping_cost      Run: ./build/damping_cost --rounds 3 --threads 1 */
#define SPHSOLID_IMPLEMENTATION
#include "../examples/common.h"
#include "../examples/scenes/plate2d.h"
#include "../examples/scenes/rings2d.h"

static sps_world* build(int variant, int threads) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body a, b;
    sps_observer tip;
    wd.threads = threads;
    wd.log = ex_log;
    bd.shear = SPS_SHEAR_ENO_A;
    bd.rotation = SPS_ROTATION_MEAN;
    if (variant < 2) { /* rings: 0 plain, 1 friction */
        rings2d_params p = {0.002, 0.06, 0, 0};
        bd.material.density = RINGS2D_RHO0;
        bd.material.youngs_modulus = RINGS2D_E;
        bd.material.poisson_ratio = RINGS2D_NU;
        bd.friction = variant == 1 ? (sps_real)0.5 : 0;
        ex_check(NULL, rings2d_create(wd, &bd, &p, &w, &a, &b));
    } else { /* plate: 2 plain, 3 Kelvin-Voigt */
        plate2d_params p = {10, 0.05, 0, 0};
        bd.material.density = PLATE2D_RHO0;
        bd.material.youngs_modulus = PLATE2D_E;
        bd.material.poisson_ratio = PLATE2D_NU;
        bd.material.viscosity = variant == 3 ? 200 : 0;
        ex_check(NULL, plate2d_create(wd, &bd, &p, &w, &a, &tip));
    }
    return w;
}

int main(int argc, char** argv) {
    int rounds = 3, threads = 1, k, r;
    double t_end[2] = {0.004, 0.004}, best[4] = {1e30, 1e30, 1e30, 1e30};
    long steps[4] = {0, 0, 0, 0};
    int particles[4] = {0, 0, 0, 0};
    const char* names[4] = {"rings", "rings+friction", "plate", "plate+kelvin-voigt"};
    opt_spec opts[] = {
        {"rounds", OPT_INT, &rounds, "interleaved rounds (the best of each variant is kept)", 1, 100, NULL},
        {"threads", OPT_INT, &threads, "OpenMP threads", 0, 1024, NULL},
        {"tend", OPT_REAL, &t_end[0], "simulated time of each run [s]", 1e-5, 10, NULL},
    };
    ex_short_openmp_spin(argv);
    opt_parse(argc, argv, "the price of friction and Kelvin-Voigt damping per particle-step", opts, 3);
    t_end[1] = t_end[0];
    for (r = 0; r < rounds; ++r)
        for (k = 0; k < 4; ++k) {
            sps_world* w = build(k, threads);
            sps_diagnostics d;
            double t0;
            ex_check(w, sps_world_step(w)); /* the first step's allocations are not the price */
            t0 = wall_seconds();
            ex_check(w, sps_world_advance(w, (sps_real)t_end[k / 2], NULL, NULL));
            ex_check(w, sps_world_diagnostics(w, (sps_body){0}, &d));
            particles[k] = sps_world_particle_count(w);
            steps[k] = d.acoustic_steps;
            if ((wall_seconds() - t0) / (double)particles[k] / (double)steps[k] < best[k])
                best[k] = (wall_seconds() - t0) / (double)particles[k] / (double)steps[k];
            sps_world_destroy(w);
        }
    for (k = 0; k < 4; ++k) printf("%-20s particles=%d substeps=%ld ns_per_particle_step=%.1f\n", names[k], particles[k], steps[k], 1e9 * best[k]);
    printf("RESULT case=damping_cost friction_ratio=%.3f kelvin_voigt_ratio=%.3f kelvin_voigt_substeps_ratio=%.2f threads=%d rounds=%d\n",
           best[1] / best[0], best[3] / best[2], (double)steps[3] / (double)steps[2], threads, rounds);
    return 0;
}
