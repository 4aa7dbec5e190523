/* cantilever_sag.c - the 2D plate of benchmark A1 (scenes/plate2d.h) sagging under its own weight,
   brought to rest by damping: its static sag against Timoshenko beam theory (bench/VALIDATION.md).

   The plate L = 0.2 x H = 0.02 (rho0 1000, E 2e6, nu 0.3975, plane strain), clamped by its
   holder for x < 0, starts at rest; a uniform load g (downwards) acts from t = 0, through the
   world's gravity or (--load callback) through sps_body_set_acceleration, the same load. The
   body's damping c (sps_body_def.damping) takes the swing out: every mode decays as e^(-c t/2),
   and c = 2 omega_1 (the default, omega_1 of thin-plate theory, 0.2541 s) damps the first mode
   critically. At the end we compare the sag, the mean downward displacement of the end column
   of particles (x = L - dp/2), with the Timoshenko beam's w there (plate2d_timoshenko_sag), for
   the free length L = 0.2 from the holder's face: the clamped particles fill x < 0, the free ones
   x > 0 (the length the plate's period agrees with, bench/VALIDATION.md). The default load
   g = 1 m/s^2 gives a sag of 1.3 % of L, small enough for linear beam theory (the large-
   deflection correction is of order (sag/L)^2, 2e-4).

   Build: make examples        Run: ./build/cantilever_sag --res 10
   Expect: sag about 2.6 mm, within a few % of Timoshenko's 2.56 mm; CSV in out/cantilever_sag/
   (sag per row), a picture of the sagged plate.
   Smoke: cantilever_sag --res 3 --tend 0.01 --load callback */
#include "common.h"
#include "scenes/plate2d.h"

typedef struct {
    output_plan output;
    double dp, drift_from, sag_then; /* sag_then: the sag at the first row after drift_from */
    int sag_then_set;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[64];
    const double t = sps_world_time(w), sag = plate2d_end_sag(w, s->dp);
    snprintf(extra, sizeof extra, ",%.9g", sag);
    if (output_tick(w, &s->output, extra, &d) && t >= s->drift_from && !s->sag_then_set) {
        s->sag_then = sag;
        s->sag_then_set = 1;
    }
    return 0;
}

/* The load as an external acceleration: (0, -g) everywhere (--load callback). */
static void uniform_load(const sps_real x[3], const sps_real x0[3], const sps_real v[3], sps_real t, sps_real a[3], void* user) {
    (void)x, (void)x0, (void)v, (void)t;
    a[1] = -*(const double*)user;
}

int main(int argc, char** argv) {
    plate2d_params p = {.res = 10, .vf = 0};
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 0.6, .vtk_every = 0.1, .csv_every = 0.005,
                        .E = PLATE2D_E, .nu = PLATE2D_NU, .rho0 = PLATE2D_RHO0, .out = "out/cantilever_sag", .jitter = 0, .seed = 1,
                        PNG_DEFAULTS};
    double g = 1, damping = 0;
    int load = 0;
    opt_spec opts[] = {
        {"res", OPT_INT, &p.res, "resolution H/dp", 2, 200, NULL},
        {"g", OPT_REAL, &g, "load: acceleration downwards [m/s^2]", 0, 1e4, NULL},
        {"damping", OPT_REAL, &damping, "damping c [1/s], 0 = 2 omega_1 (thin-plate first mode: critical)", 0, 1e6, NULL},
        {"load", OPT_CHOICE, &load, "how the load acts: the world's gravity or sps_body_set_acceleration", 0, 0, "gravity|callback"},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body plate;
    sps_observer tip;
    sps_diagnostics d;
    sps_body all = {0};
    run_state s;
    double sag, x_end, theory, wall;

    ex_options(argc, argv, "2D cantilever sagging under its own weight, damped to rest, against Timoshenko beam theory",
               opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    if (damping == 0) damping = 2 * (2 * PI / plate2d_analytical_period(c.E, c.nu, c.rho0));
    bd.damping = damping;
    if (load == 0) wd.gravity[1] = -g;
    p.jitter = c.jitter;
    p.seed = c.seed;
    memset(&s, 0, sizeof s);
    plate2d_create(wd, &bd, &p, &w, &plate, &tip);
    if (load == 1) sps_body_set_acceleration(w, plate, uniform_load, &g);

    s.dp = PLATE2D_H / p.res;
    s.drift_from = c.t_end - 0.1;
    output_open(&s.output, &c, "cantilever_sag", "displacement", ",sag");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);

    sag = plate2d_end_sag(w, s.dp);
    x_end = PLATE2D_L - s.dp / 2;
    theory = plate2d_timoshenko_sag(x_end, g, c.E, c.nu, c.rho0, 1, 1);
    sps_world_diagnostics(w, all, &d);
    printf("RESULT case=cantilever_sag shear=%s res=%d g=%g load=%s damping=%g sag=%.6e timoshenko=%.6e err=%+.2f%% "
           "euler_bernoulli=%.6e shear_part=%.6e x=%.5f timoshenko_tip=%.6e sag_over_L=%.4f drift_last_0.1s=%.2e ke_end=%.3e %s "
           "particles=%d steps=%ld advection_steps=%ld wall_s=%.2f out=%s\n",
           shear_name(c.shear), p.res, g, load ? "callback" : "gravity", damping, sag, theory, 100 * (sag / theory - 1),
           plate2d_timoshenko_sag(x_end, g, c.E, c.nu, c.rho0, 1, 0), plate2d_timoshenko_sag(x_end, g, c.E, c.nu, c.rho0, 0, 1), x_end,
           plate2d_timoshenko_sag(PLATE2D_L, g, c.E, c.nu, c.rho0, 1, 1), sag / PLATE2D_L,
           s.sag_then_set && sag != 0 ? fabs(sag - s.sag_then) / sag : 0, (double)d.kinetic_energy, common_result_fields(&c),
           sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
