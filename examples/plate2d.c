/* plate2d.c - 2D oscillating plate (cantilever), benchmark A1 (bench/VALIDATION.md) (ENO 6.1, ANG 5.1.1).

   A plate L = 0.2 x H = 0.02 (rho0 1000, E 2e6, nu 0.3975, plane strain) continues into a
   holder for x < 0 whose particles are clamped. It starts from the first bending mode,
   v_y(x) = v_f c0 f(x)/f(L), and swings freely. We measure the first period at the free end
   (x = L, y = 0) and compare it with the papers' (ANG Table 1, H/dp = 30) and with thin-plate
   theory (0.254 s). The scene (world, plate, clamp, start, run) is main; the plate's dimensions,
   mode shape and theory are in scenes/plate2d.h, which the tests and cantilever_sag.c share. With --viscosity eta (Kelvin-Voigt material damping) the amplitude decays:
   zeta is the damping ratio fitted to the cycles' amplitudes (ln A_k = c - 2 pi zeta k; the
   Riemann dissipation's share is what eta = 0 gives), zeta_kv_theory the share of eta,
   omega E'_v / (2 E') of a viscoelastic plane-strain beam (kelvin_voigt_ratio).

   With --shear og --transport tvf|utvf it is benchmark C3 (UTVF 4.3): the original shear
   formulation held together by a transport-velocity correction.

   Build: make examples        Run: ./build/plate2d --res 10 --shear eno-a --vf 0.05
   Expect: period about 0.27 s at H/dp = 10; CSV in out/plate2d/, VTK every 0.1 s, a picture
   (PNG and SVG) of the end state.
   Smoke: plate2d --res 3 --tend 0.01 */
#include "common.h"
#include "scenes/plate2d.h"

/* ANG Table 1 (H/dp = 30), columns v_f = 0.001, 0.01, 0.03, 0.05, rows in sps_shear order
   (ENO, ENO-A, OG, OAS, GNO, GNO-A), then OG with TVF and with UTVF (benchmark C3, the
   table's SPH-TVF and SPH-UTVF rows); -1 where the paper has no value (OG alone breaks down). */
static double paper_period(int shear, int transport, double vf) {
    static const double vfs[4] = {0.001, 0.01, 0.03, 0.05};
    static const double table[8][4] = {{0.262, 0.263, 0.268, 0.279}, {0.265, 0.265, 0.266, 0.269}, {-1, -1, -1, -1},
                                       {0.273, 0.273, 0.275, 0.278}, {0.275, 0.273, 0.272, 0.272}, {0.274, 0.274, 0.274, 0.275},
                                       {0.275, 0.277, 0.283, 0.284}, {0.274, 0.271, 0.271, 0.271}};
    const int row = transport == 0 ? shear : shear == SPS_SHEAR_OG ? 5 + transport : -1;
    int k;
    for (k = 0; k < 4 && row >= 0; ++k)
        if (fabs(vf - vfs[k]) < 1e-12) return table[row][k];
    return -1;
}

typedef struct {
    sps_observer tip;
    period_detector period;
    output_plan output;
    double amp_first, amp_last, amp_cur; /* amplitudes: max |deflection| per cycle */
    double amp[64];       /* every cycle's (--viscosity: the decay fit) */
    int cycles;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_real u[3];
    sps_diagnostics d;
    char extra[64];
    double t = sps_world_time(w);
    sps_observer_read(w, s->tip, u, NULL);
    if (fabs(u[1]) > s->amp_cur) s->amp_cur = fabs(u[1]);
    if (period_feed(&s->period, t, u[1])) { /* a cycle ended */
        if (s->amp_first == 0) s->amp_first = s->amp_cur;
        s->amp_last = s->amp_cur;
        if (s->cycles < 64) s->amp[s->cycles++] = s->amp_cur;
        s->amp_cur = 0;
    }
    snprintf(extra, sizeof extra, ",%.9g", (double)u[1]);
    output_tick(w, &s->output, extra, &d);
    return 0;
}

/* The modal damping ratio from the cycles' amplitudes: ln A_k = c - 2 pi zeta k, a line fit. */
static double decay_ratio(const double* amp, int n) {
    double sk = 0, sy = 0, skk = 0, sky = 0;
    int k;
    for (k = 0; k < n; ++k) {
        sk += k; sy += log(amp[k]); skk += (double)k * k; sky += k * log(amp[k]);
    }
    return n > 1 ? -(n * sky - sk * sy) / (n * skk - sk * sk) / (2 * PI) : 0;
}

/* The damping ratio a Kelvin-Voigt viscosity eta adds to a plane-strain beam's bending mode of
   angular frequency omega: zeta = omega E'_v / (2 E'), E' = 4 mu (lambda + mu)/(lambda + 2 mu) and
   E'_v = eta (dE'/dlambda + dE'/dmu), the library's viscous stress having Lame viscosities
   lambda_v = mu_v = eta (the correspondence principle, to first order in omega eta / E'). */
static double kelvin_voigt_ratio(double E, double nu, double eta, double omega) {
    const double mu = E / (2 * (1 + nu)), lambda = 2 * mu * nu / (1 - 2 * nu), D = lambda + 2 * mu;
    const double e_plane = 4 * mu * (lambda + mu) / D;
    const double d_lambda = 4 * mu * mu / (D * D), d_mu = (4 * D * D - 8 * mu * (lambda + mu)) / (D * D);
    return omega * eta * (d_lambda + d_mu) / (2 * e_plane);
}

int main(int argc, char** argv) {
    int res = 10;         /* H/dp */
    double vf = 0.05;     /* initial velocity factor v_f */
    int solver = 0;       /* ul | tl */
    double alpha = 50;    /* TL eq. 32 */
    double artificial_viscosity = 0; /* TL artificial viscosity q1 (none: the paper's) */
    int hourglass_form = SPS_HOURGLASS_VARIATIONAL;
    double viscosity = 0; /* Kelvin-Voigt eta [Pa s] */
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 1.0, .vtk_every = 0.1, .csv_every = 0.002,
                        .E = PLATE2D_E, .nu = PLATE2D_NU, .rho0 = PLATE2D_RHO0, .out = "out/plate2d", .jitter = 0, .seed = 1,
                        PNG_DEFAULTS};
    opt_spec opts[] = {
        {"res", OPT_INT, &res, "resolution H/dp", 2, 200, NULL},
        {"vf", OPT_REAL, &vf, "initial velocity factor v_f", 0, 1, NULL},
        {"solver", OPT_CHOICE, &solver, "ul: updated Lagrangian (--shear); tl: total Lagrangian, Saint Venant-Kirchhoff", 0, 0, "ul|tl"},
        {"alpha", OPT_REAL, &alpha, "tl: hourglass coefficient alpha (TL eq. 32)", 0, 1000, NULL},
        EX_HOURGLASS_OPTIONS(hourglass_form, artificial_viscosity),
        {"viscosity", OPT_REAL, &viscosity, "Kelvin-Voigt viscosity eta [Pa s]: material damping (prints the decay ratio)", 0, 1e9, NULL},
    };
    sps_world_def wd = sps_default_world_def(); /* the shared options (--cfl, --kernel, ...) are applied by ex_options */
    sps_body_def bd = sps_default_body_def();   /* and --E, --nu, --rho0, --shear, ... */
    sps_world* w;
    sps_body plate;
    sps_real K;
    plate2d_start start;
    sps_diagnostics d;
    run_state s;
    double dp, analytical, paper, period, wall;

    ex_options(argc, argv, "2D oscillating plate (benchmark A1, bench/VALIDATION.md)", opts, &c, &wd, &bd);
    memset(&s, 0, sizeof s);

    /* the world: 2D, H/dp = res */
    dp = PLATE2D_H / res;
    wd.dim = 2;
    wd.dp = dp;
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    sps_world_create(&wd, &w);

    /* the plate, L x H, and its holder for x < 0, clamped (more layers than the kernel reaches) */
    bd.name = "plate";
    if (solver == 1) {
        bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
        bd.material.kind = SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF;
        bd.material.tl.hourglass_alpha = alpha;
        bd.material.tl.hourglass = (sps_hourglass)hourglass_form;
        bd.material.tl.artificial_viscosity = (sps_real)artificial_viscosity;
    }
    bd.material.viscosity = viscosity;
    ex_unset_unread(&bd); /* --solver tl: no shear formulation */
    sps_world_add_body(w, &bd, &plate);
    {
        const sps_real lo[3] = {-PLATE2D_HOLDER_LAYERS * dp, -PLATE2D_H / 2, 0}, hi[3] = {PLATE2D_L, PLATE2D_H / 2, 0};
        const sps_real holder_lo[3] = {-1, -1, -1}, holder_hi[3] = {0, 1, 1}, free_end[3] = {PLATE2D_L, 0, 0};
        scene_add_box(w, plate, lo, hi, c.jitter, c.seed); /* sps_body_add_box, or the lattice jittered (--jitter) */
        sps_body_constrain_box(w, plate, holder_lo, holder_hi, SPS_AXIS_ALL, NULL, NULL);
        /* the first bending mode, v_y(x) = v_f c0 f(x)/f(L) with the papers' c0 = sqrt(K/rho0) (a
           total-Lagrangian body's own signal speed is the P-wave speed) */
        sps_body_material_constants(w, plate, NULL, NULL, &K);
        start.vf = vf;
        start.c0 = (sps_real)sqrt(K / bd.material.density);
        sps_body_set_velocity(w, plate, plate2d_initial_velocity, &start);
        sps_world_add_observer(w, plate, free_end, &s.tip); /* the deflection at the free end */
    }

    /* the run: on_step writes the CSV row, snapshots and pictures due, and follows the free end */
    output_open(&s.output, &c, "plate2d", "von-mises-or-velocity", ",deflection");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);

    analytical = plate2d_analytical_period(c.E, c.nu, c.rho0);
    paper = solver == 1 ? -1 : paper_period(c.shear, c.transport, vf);
    period = period_first(&s.period);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    printf("RESULT case=plate2d solver=%s alpha=%g hourglass=%s artificial_viscosity=%g shear=%s res=%d vf=%g stepping=%s nu=%g jitter=%g period=%.6f paper=%.3f paper_res=30 "
           "analytical=%.6f err_analytical=%.1f%% err_paper=%.1f%% cycles=%d amp_first=%.5f amp_last=%.5f hourglass_max=%.3g "
           "hourglass_end=%.3g min_spacing=%.3f viscosity=%g zeta=%.5f zeta_kv_theory=%.5f %s particles=%d steps=%ld advection_steps=%ld "
           "wall_s=%.2f out=%s\n",
           solver ? "tl" : "ul", solver ? alpha : 0, solver ? ex_hourglass_name(hourglass_form) : "-", solver ? artificial_viscosity : 0,
           solver ? "-" : shear_name(c.shear), res, vf, c.stepping ? "single" : "dual", c.nu, c.jitter, period, paper, analytical,
           period > 0 ? 100 * (period - analytical) / analytical : 0, period > 0 && paper > 0 ? 100 * (period - paper) / paper : 0,
           s.period.n / 2, s.amp_first, s.amp_last, s.output.hourglass_max, (double)d.hourglass, s.output.min_spacing, viscosity,
           decay_ratio(s.amp, s.cycles), period > 0 ? kelvin_voigt_ratio(c.E, c.nu, viscosity, 2 * PI / period) : 0, common_result_fields(&c),
           sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
