/* rotating_patch.c - the rotating square patch of fluid, benchmark C2 (bench/VALIDATION.md)
   (UTVF 4.2, after Colagrossi 2005).

   A unit square of inviscid fluid centred at the origin starts in rigid rotation, v = (omega y,
   -omega x), with the pressure of the incompressible solution (UTVF eq. 44, the double series
   over odd m, n, here to m, n < 200). Nothing acts on it, so its kinetic energy should stay; the
   corners are flung out into arms while the centre pressure, negative, follows the BEM-MEL
   reference of the paper's Fig. 9b. Defaults are the reference code's run: rho0 = 1, c0 = 10,
   dp = 0.01, to t = 8 (kinetic energy 0.083325 -> 0.082972; x 1000 at the paper's rho0 = 1000).
   Without a transport correction the negative pressure opens voids (tensile instability): the
   count of surface particles (div r < 0.75 d), which starts at the perimeter's, says how many.

   Build: make examples     Run: ./build/rotating_patch --transport utvf
   Expect: kinetic energy within ~0.5 % of the start at t = 8; surface particles near the
   perimeter's with UTVF, many more without.
   Smoke: rotating_patch --dp 0.1 --tend 0.01 */
#include "common.h"

#define SIDE 1.0

static double g_omega = 1, g_rho0 = 1;

static void initial_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = (sps_real)(g_omega * x[1]);
    v[1] = (sps_real)(-g_omega * x[0]);
}

/* UTVF eq. 44: p = -rho sum_{m,n odd} 32 omega^2 / (m n pi^2 ((m pi/L)^2 + (n pi/L)^2))
   sin(m pi xs / L) sin(n pi ys / L), xs = x + L/2, ys = y + L/2 (converges like 1/(m n (m^2 + n^2))). */
static double patch_pressure(double x, double y) {
    const double xs = x + SIDE / 2, ys = y + SIDE / 2;
    double p = 0;
    int m, n;
    for (m = 1; m < 200; m += 2)
        for (n = 1; n < 200; n += 2) {
            const double km = m * PI / SIDE, kn = n * PI / SIDE;
            p += 32 * g_omega * g_omega / (m * n * PI * PI * (km * km + kn * kn)) * sin(km * xs) * sin(kn * ys);
        }
    return -g_rho0 * p;
}
static sps_real initial_pressure(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)patch_pressure((double)x[0], (double)x[1]);
}

typedef struct {
    output_plan output;
    double dp;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[64];
    snprintf(extra, sizeof extra, ",%.9g", ex_centre_pressure(w, s->dp));
    output_tick(w, &s->output, extra, &d);
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 8, .vtk_every = 0.5, .csv_every = 0.02, .E = 1e6, .nu = 0.3,
                        .rho0 = 1, .out = "out/rotating_patch", .jitter = 0, .seed = 1, .transport = 2, PNG_DEFAULTS};
    double dp = 0.01, c0 = 10;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (the paper: L/100)", 1e-3, 0.1, NULL},
        {"c0", OPT_REAL, &c0, "artificial sound speed [m/s]", 1e-3, 1e5, NULL},
        {"omega", OPT_REAL, &g_omega, "angular velocity [rad/s]", 1e-3, 1e3, NULL},
    };
    static const double reference_ke[2] = {0.083325, 0.082972}; /* the reference code at rho0 = 1, omega = 1 */
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body patch, all = {0};
    sps_diagnostics d0, d;
    sps_real lo[3] = {-SIDE / 2, -SIDE / 2, 0}, hi[3] = {SIDE / 2, SIDE / 2, 0};
    run_state s;
    double wall, scale;

    ex_options(argc, argv, "rotating square patch of fluid (benchmark C2, bench/VALIDATION.md)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    g_rho0 = c.rho0;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    bd.name = "patch";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = (sps_real)c0;
    sps_world_create(&wd, &w);
    sps_world_add_body(w, &bd, &patch);
    sps_body_add_box(w, patch, lo, hi, NULL);
    sps_body_set_velocity(w, patch, initial_velocity, NULL);
    sps_body_set_pressure(w, patch, initial_pressure, NULL);
    sps_world_diagnostics(w, all, &d0);

    memset(&s, 0, sizeof s);
    s.dp = dp;
    output_open(&s.output, &c, "rotating_patch", "pressure", ",centre_pressure");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    sps_world_diagnostics(w, all, &d);
    scale = c.rho0 * g_omega * g_omega; /* the reference's figures scale with rho0 omega^2 */
    printf("RESULT case=rotating_patch dp=%g c0=%g rho0=%g omega=%g t=%.4g kinetic_start=%.6g kinetic_end=%.6g decay=%+.3f%% "
           "reference_start=%.6g reference_end=%.6g reference_decay=%+.3f%% centre_pressure_start=%.5g centre_pressure_end=%.5g "
           "surface_particles_start=%d surface_particles_end=%d min_spacing=%.3f max_linmom=%.2e %s particles=%d steps=%ld "
           "advection_steps=%ld wall_s=%.2f out=%s\n",
           dp, c0, c.rho0, g_omega, (double)d.time, (double)d0.kinetic_energy, (double)d.kinetic_energy,
           100 * (d.kinetic_energy / d0.kinetic_energy - 1), reference_ke[0] * scale, reference_ke[1] * scale,
           100 * (reference_ke[1] / reference_ke[0] - 1), patch_pressure(0, 0), ex_centre_pressure(w, dp), d0.surface_particles,
           d.surface_particles, s.output.min_spacing, fmax(fabs((double)d.linear_momentum[0]), fabs((double)d.linear_momentum[1])),
           common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
