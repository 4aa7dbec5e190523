/* spinning_plate.c - 2D spinning plate, benchmark A3 (bench/VALIDATION.md) (ENO 6.10, ANG 5.1.3);
   built with -DSPINNING_DIM=3 as build/spinning_cube, the 3D spinning cube of benchmark A4
   (ANG 5.1.4: a unit cube, nu 0.3, omega = (0, 0, 50) rad/s, against ANG Fig. 16).

   A unit square centred at the origin, rho0 1100, E 1.7e7, nu 0.45, starts in rigid rotation
   at omega = 50 rad/s about z with no constraint (set-up: scenes/spinning.h). Linear and
   angular momentum are exactly conserved in theory; we report the largest relative
   angular-momentum error over the run next to ANG Fig. 13, the drift of the linear momentum,
   the smallest pair distance (clustering) and the hourglass indicator. CSV: momenta, energies,
   and the displacement and velocity of the top-right corner (in 3D: (0.5, 0.5, 0.5)).

   Build: make examples     Run: ./build/spinning_plate --shear gno-a
   Expect: max_angmom_err about 0.5 % for GNO-A, a few % for ENO-A, tens of % for ENO (the
   cube: 1.2 % GNO-A, 2.7 % ENO-A in the paper).
   Smoke: spinning_plate --dp 0.1 --tend 0.01
   Smoke: spinning_cube --dp 0.2 --tend 0.01 */
#include "common.h"
#include "scenes/spinning.h"

#ifndef SPINNING_DIM
#define SPINNING_DIM 2
#endif
#if SPINNING_DIM == 2
#define CASE "spinning_plate"
#define TITLE "2D spinning plate (benchmark A3, bench/VALIDATION.md)"
#define NU SPINNING_NU_2D
static const double paper_error[6] = {59.17, 2.58, -1, -1, 1.12, 0.55}; /* ANG Fig. 13 [%], rows in sps_shear order */
#else
#define CASE "spinning_cube"
#define TITLE "3D spinning cube (benchmark A4, bench/VALIDATION.md)"
#define NU SPINNING_NU_3D
static const double paper_error[6] = {-1, 2.67, -1, -1, -1, 1.18}; /* ANG 5.1.4 [%], rows in sps_shear order; -1: not in the paper */
#endif

static double norm3(const sps_real* a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

int main(int argc, char** argv) {
    spinning_params p = {.dim = SPINNING_DIM, .dp = 0.05, .omega = 50};
    common_options c = {.shear = SPS_SHEAR_GNO_A, .cfl = 0.4, .t_end = 0.5, .vtk_every = 0.1, .csv_every = 0.001,
                        .E = SPINNING_E, .nu = NU, .rho0 = SPINNING_RHO0, .out = "out/" CASE, .jitter = 0, .seed = 1,
                        PNG_DEFAULTS};
    opt_spec opts[] = {
        {"dp", OPT_REAL, &p.dp, "particle spacing [m]", 1e-3, 0.25, NULL},
        {"omega", OPT_REAL, &p.omega, "angular velocity [rad/s]", 0, 1e4, NULL},
        {"drift", OPT_REAL, &p.drift, "uniform velocity along x added (Galilean check: the same steps as at rest) [m/s]", -1e4, 1e4, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body block;
    sps_diagnostics d0, d;
    sps_body all = {0};
    sps_real corner[3] = {0.5, 0.5, 0.5};
    double wall, max_err = 0, max_p_drift = 0, p_scale;
    int corner_id;
    output_plan output;

    ex_options(argc, argv, TITLE, opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (ex_check_step) */
    p.jitter = c.jitter;
    p.seed = c.seed;
    spinning_create(wd, &bd, CASE, &p, &w, &block);
    if ((corner_id = sps_world_nearest_particle(w, block, corner)) < 0) ex_check(w, SPS_ERR_INVALID_ARG);

    output_open(&output, &c, CASE, "velocity", ",corner_ux,corner_uy,corner_vx,corner_vy");
    p_scale = spinning_momentum_scale(w);
    sps_world_diagnostics(w, all, &d0);
    for (;;) {
        double t = sps_world_time(w);
        sps_particle_state pc;
        char extra[160];
        sps_world_particle(w, corner_id, &pc);
        snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g,%.9g", (double)pc.displacement[0], (double)pc.displacement[1],
                 (double)pc.velocity[0], (double)pc.velocity[1]);
        if (output_tick(w, &output, extra, &d)) {
            max_err = fmax(max_err, spinning_angmom_error(&d, &d0));
            sps_real dP[3];
            int a;
            for (a = 0; a < 3; ++a) dP[a] = d.linear_momentum[a] - d0.linear_momentum[a];
            max_p_drift = fmax(max_p_drift, norm3(dP) / p_scale);
        }
        if (t >= (sps_real)c.t_end) break; /* the world's clock is an sps_real: a float 2e-4 is below the double */
        {
            sps_result r = sps_world_advance(w, t + c.csv_every < c.t_end ? t + c.csv_every : c.t_end, NULL, NULL);
            ex_check_step(w, r, &output);
        }
    }
    wall = output_close(w, &output);
    printf("RESULT case=%s shear=%s dp=%g omega=%g drift=%g stepping=%s nu=%g jitter=%g max_angmom_err=%.4g%% paper=%.2f%% "
           "max_linmom_drift=%.2e min_spacing=%.3f hourglass_max=%.3g kinetic_start=%.6g kinetic_end=%.6g %s particles=%d "
           "steps=%ld advection_steps=%ld wall_s=%.2f out=%s\n",
           CASE, shear_name(c.shear), p.dp, p.omega, p.drift, c.stepping ? "single" : "dual", c.nu, c.jitter, 100 * max_err,
           paper_error[c.shear], max_p_drift, output.min_spacing, output.hourglass_max, (double)d0.kinetic_energy, (double)d.kinetic_energy,
           common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
