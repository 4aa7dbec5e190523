/* plate3d.c - 3D oscillating plate, simply supported, benchmark A2 (bench/VALIDATION.md) (ENO 6.2, ANG 5.1.2).

   A square plate L = W = 0.4, H = 0.01 (rho0 1000, E 1e8, nu 0.3) is simply supported
   (set-up: scenes/plate3d.h): the z-velocity of its mid-plane particles on the four lateral
   sides is held at zero, as ENO 6.2 describes it (--support edge). --support ring adds instead a one-particle ring outside
   [0, L] x [0, W] in the mid plane (the reference code, bench/VALIDATION.md); --support
   thick makes that ring as thick as the plate, all layers held in z (this reproduces the
   papers' particle counts: 44.7k / 204.0k / 1179.4k at H/dp = 3 / 5 / 9). It starts with v_z = sin(m pi x/L) sin(n pi y/W) and vibrates in mode
   (m, n). We measure the first period and compare it with ANG Table 3, with Kirchhoff plate
   theory (analytical=) and with Mindlin's thick-plate theory (mindlin=, 0.2-0.9% longer). The papers observe the plate centre; for even m or n the centre is a node of the
   mode (no signal), so we observe the first antinode (L/2m, W/2n, 0), which is the centre
   for mode (1,1).

   Build: make examples        Run: ./build/plate3d --res 3 --mode 2,2
   Expect: period 0.0149 s for mode (2,2) at H/dp = 3 (paper), 0.0133 s in theory.
   Smoke: plate3d --res 2 --tend 0.0002 --full */
#include "common.h"
#include "scenes/plate3d.h"

/* The period of mode (m, n) by Mindlin's thick-plate theory (shear deformation and rotary
   inertia, shear coefficient pi^2/12), the continuum answer thin-plate theory leaves out for
   H/L = 0.025. With w = W s, div psi = P s and laplacian(s) = -k^2 s, Mindlin's equations give
   (kGH k^2 - rho H w^2)(D k^2 + kGH - rho I w^2) = (kGH)^2 k^2, I = H^3/12 (D: the flexural
   rigidity of ANG eq. 55): the lower root. */
static double mindlin_period(double E, double nu, double D, double rho, plate3d_mode md) {
    const double kappa = PI * PI / 12, G = E / (2 * (1 + nu));
    const double I = pow(PLATE3D_H, 3) / 12, k2 = PI * PI * (pow(md.m / PLATE3D_L, 2) + pow(md.n / PLATE3D_W, 2));
    const double kgh = kappa * G * PLATE3D_H, a = kgh * k2, b = D * k2 + kgh;
    const double qa = rho * PLATE3D_H * rho * I, qb = -(a * rho * I + b * rho * PLATE3D_H), qc = a * b - kgh * kgh * k2;
    const double omega2 = (-qb - sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
    return 2 * PI / sqrt(omega2);
}

/* ANG Table 3 (ENO-A, GNO-A) and ENO Table 3 (ENO), H/dp = 3, 5, 9; -1 where the papers have no
   value. The plate is square, so mode (1,2) has the period of (2,1). */
static double paper_period(int shear, plate3d_mode md, int res) {
    static const double eno_a[3][3] = {{0.0573, 0.0543, 0.0528}, {0.0231, 0.0218, 0.0212}, {0.0149, 0.0141, 0.0136}};
    static const double gno_a[3][3] = {{0.0581, 0.0553, 0.0538}, {0.0241, 0.0226, 0.0220}, {0.0153, 0.0144, 0.0138}};
    static const double eno[3][3] = {{0.0572, 0.0543, 0.0529}, {0.0231, 0.0218, 0.0212}, {0.0148, 0.0140, 0.0136}};
    const int lo = md.m < md.n ? md.m : md.n, hi = md.m < md.n ? md.n : md.m;
    const int row = lo == 1 && hi == 1 ? 0 : lo == 1 && hi == 2 ? 1 : lo == 2 && hi == 2 ? 2 : -1;
    const int col = res == 3 ? 0 : res == 5 ? 1 : res == 9 ? 2 : -1;
    if (row < 0 || col < 0) return -1;
    if (shear == SPS_SHEAR_ENO) return eno[row][col];
    if (shear == SPS_SHEAR_ENO_A) return eno_a[row][col];
    if (shear == SPS_SHEAR_GNO_A) return gno_a[row][col];
    return -1;
}

typedef struct {
    sps_observer probe;
    period_detector period;
    output_plan output;
    int stop_at_period;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_real u[3];
    sps_diagnostics d;
    char extra[64];
    sps_observer_read(w, s->probe, u, NULL);
    period_feed(&s->period, sps_world_time(w), u[2]);
    snprintf(extra, sizeof extra, ",%.9g", (double)u[2]);
    output_tick(w, &s->output, extra, &d);
    return s->stop_at_period && s->period.n >= 2;
}

int main(int argc, char** argv) {
    plate3d_params p = {.res = 3, .mode = {1, 1}, .support = PLATE3D_SUPPORT_EDGE};
    int full = 0, md_arg[2] = {1, 1};
    /* t_end 0: stop once the first period is measured (at most 1.6 x theory) */
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 0, .vtk_every = 0, .csv_every = 2e-4,
                        .E = PLATE3D_E, .nu = PLATE3D_NU, .rho0 = PLATE3D_RHO0, .out = "out/plate3d",
                        .jitter = 0, .seed = 1, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"res", OPT_INT, &p.res, "resolution H/dp", 2, 40, NULL},
        {"mode", OPT_PAIR, md_arg, "vibration mode m,n", 1, 20, NULL},
        {"support", OPT_CHOICE, &p.support, "simple support: mid-plane edge particles | mid-plane ring outside | full-thickness ring outside", 0, 0, "edge|ring|thick"},
        {"full", OPT_FLAG, &full, "with --tend, run to the end even after the period is found", 0, 0, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body plate;
    run_state s;
    double D, analytical, mindlin, paper, period, wall;

    ex_options(argc, argv, "3D oscillating plate (benchmark A2, bench/VALIDATION.md)", opts, &c, &wd, &bd);
    p.mode.m = md_arg[0];
    p.mode.n = md_arg[1];
    D = c.E * pow(PLATE3D_H, 3) / (12 * (1 - c.nu * c.nu));                                                            /* ANG eq. 55 */
    analytical = 2 / PI / (pow(p.mode.m / PLATE3D_L, 2) + pow(p.mode.n / PLATE3D_W, 2)) * sqrt(c.rho0 * PLATE3D_H / D); /* ANG eq. 54 */
    mindlin = mindlin_period(c.E, c.nu, D, c.rho0, p.mode);
    if (c.t_end == 0) c.t_end = 1.6 * analytical; /* stops earlier, at the second zero crossing */
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    p.jitter = c.jitter;
    p.seed = c.seed;
    memset(&s, 0, sizeof s);
    plate3d_create(wd, &bd, &p, &w, &plate, &s.probe);

    s.stop_at_period = !full;
    output_open(&s.output, &c, "plate3d", "von-mises-or-velocity", ",deflection");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    paper = paper_period(c.shear, p.mode, p.res);
    period = period_first(&s.period);
    {
        sps_diagnostics d;
        sps_body all = {0};
        sps_world_diagnostics(w, all, &d);
        char paper_text[32] = "none", err_paper[16] = "none", err_analytical[16] = "none", err_mindlin[16] = "none"; /* none: no value */
        if (paper > 0) snprintf(paper_text, sizeof paper_text, "%.4f", paper);
        if (paper > 0 && period > 0) snprintf(err_paper, sizeof err_paper, "%.1f%%", 100 * (period - paper) / paper);
        if (period > 0) snprintf(err_analytical, sizeof err_analytical, "%.1f%%", 100 * (period - analytical) / analytical);
        if (period > 0) snprintf(err_mindlin, sizeof err_mindlin, "%.1f%%", 100 * (period - mindlin) / mindlin);
        printf("RESULT case=plate3d shear=%s res=%d mode=%d,%d stepping=%s period=%.6f paper=%s analytical=%.6f "
               "mindlin=%.6f err_paper=%s err_analytical=%s err_mindlin=%s hourglass_max=%.3g min_spacing=%.3f %s particles=%d steps=%ld advection_steps=%ld "
               "t_end=%.4g wall_s=%.2f out=%s\n",
               shear_name(c.shear), p.res, p.mode.m, p.mode.n, c.stepping ? "single" : "dual", period, paper_text, analytical,
               mindlin, err_paper, err_analytical, err_mindlin, s.output.hourglass_max, s.output.min_spacing, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, sps_world_time(w), wall, c.out);
    }
    sps_world_destroy(w);
    return 0;
}
