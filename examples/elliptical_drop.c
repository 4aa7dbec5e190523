/* elliptical_drop.c - the elliptical water drop, benchmark C1 (bench/VALIDATION.md) (UTVF 4.1).

   A disc of water of radius 1 m (rho0 1000, inviscid, c0 1400 m/s: Monaghan 1994's value, which
   the paper does not state) starts with the velocity (-100 x, 100 y) m/s and the pressure that
   goes with it, rho0 A0^2 (R^2 - r^2)/2, and stretches into an ellipse. With a(t) b(t) = R^2 and the velocity field (-A x, A y) the Euler
   equations give dA/dt = A^2 (a^2 - b^2)/(a^2 + b^2), da/dt = -A a (Monaghan 1994; integrated
   here by RK4). The semi-axes are measured from the second moments of the particles, a =
   2 sqrt(<x^2>) (exact for a uniformly filled ellipse: no offset of the outer particles dp/2
   inside the surface), and, for comparison, from the outermost particles plus dp/2 stretched.
   Linear and angular momentum are conserved in theory: their drifts are printed relative to
   sum m |v| and sum m |x| |v| at the start.

   Build: make examples     Run: ./build/elliptical_drop --dp 0.02 --transport utvf
   Expect: b within 1 % of 1.94452 at t = 0.0076 s (dp 0.02), linear momentum drift ~1e-15.
   Smoke: elliptical_drop --dp 0.1 --tend 0.0005 */
#include "common.h"

#define R_DROP 1.0
#define A0 100.0

/* The analytical semi-axes (a shrinking along x, b = R^2 / a) at time t by RK4 of the ODEs above. */
static void drop_axes(double t, double* a_out, double* b_out) {
    const int n = 4000;
    double A = A0, a = R_DROP, h = t / n;
    int k;
    for (k = 0; k < n; ++k) {
        double kA[4], ka[4], As = A, as = a;
        int s;
        for (s = 0; s < 4; ++s) {
            const double b = R_DROP * R_DROP / as;
            kA[s] = As * As * (as * as - b * b) / (as * as + b * b);
            ka[s] = -As * as;
            if (s < 3) {
                const double f = s < 2 ? 0.5 : 1.0;
                As = A + f * h * kA[s];
                as = a + f * h * ka[s];
            }
        }
        A += h / 6 * (kA[0] + 2 * kA[1] + 2 * kA[2] + kA[3]);
        a += h / 6 * (ka[0] + 2 * ka[1] + 2 * ka[2] + ka[3]);
    }
    *a_out = a;
    *b_out = R_DROP * R_DROP / a;
}

static sps_real disc_sdf(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(sqrt((double)(x[0] * x[0] + x[1] * x[1])) - R_DROP);
}

/* The pressure that goes with the initial flow: from the Euler equations with dA/dt = 0 at
   t = 0 (a = b), p = rho0 A0^2 (R^2 - r^2) / 2, zero on the surface (5e6 Pa at the centre). */
static sps_real initial_pressure(const sps_real x[3], void* user) {
    const double rho0 = *(const double*)user, r2 = (double)(x[0] * x[0] + x[1] * x[1]);
    return (sps_real)(0.5 * rho0 * A0 * A0 * (R_DROP * R_DROP - r2));
}

static void initial_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = (sps_real)(-A0 * x[0]);
    v[1] = (sps_real)(A0 * x[1]);
}

typedef struct {
    double a_moment, b_moment, a_edge, b_edge, centre_pressure;
} drop_shape;

/* The semi-axes from the second moments and from the outermost particles, and the centre
   pressure. */
static drop_shape measure(const sps_world* w, double dp) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* m = sps_world_field(w, SPS_FIELD_MASS);
    double mx = 0, my = 0, msum = 0, xmax = 0, ymax = 0;
    drop_shape s;
    int i, n = sps_world_particle_count(w);
    memset(&s, 0, sizeof s);
    for (i = 0; i < n; ++i) {
        const double xi = x[i], yi = y[i];
        msum += m[i];
        mx += m[i] * xi * xi;
        my += m[i] * yi * yi;
        if (fabs(xi) > xmax) xmax = fabs(xi);
        if (fabs(yi) > ymax) ymax = fabs(yi);
    }
    s.centre_pressure = ex_centre_pressure(w, dp);
    s.a_moment = 2 * sqrt(mx / msum);
    s.b_moment = 2 * sqrt(my / msum);
    /* the outer particles sit dp/2 inside the disc; the stretch scales that offset */
    s.a_edge = xmax + 0.5 * dp * s.a_moment / R_DROP;
    s.b_edge = ymax + 0.5 * dp * s.b_moment / R_DROP;
    return s;
}

typedef struct {
    output_plan output;
    double dp, p_scale, l_scale, p0[2], l0, max_dp, max_dl;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[200];
    drop_shape sh = measure(w, s->dp);
    double a, b;
    drop_axes(sps_world_time(w), &a, &b);
    snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", sh.a_moment, sh.b_moment, sh.a_edge, sh.b_edge, a, b,
             sh.centre_pressure);
    if (output_tick(w, &s->output, extra, &d)) {
        const double dpx = fabs(d.linear_momentum[0] - s->p0[0]), dpy = fabs(d.linear_momentum[1] - s->p0[1]);
        const double dl = fabs(d.angular_momentum[2] - s->l0);
        if (fmax(dpx, dpy) / s->p_scale > s->max_dp) s->max_dp = fmax(dpx, dpy) / s->p_scale;
        if (dl / s->l_scale > s->max_dl) s->max_dl = dl / s->l_scale;
    }
    return 0;
}

int main(int argc, char** argv) {
    static const double check_t[5] = {0.002, 0.004, 0.006, 0.0076, 0.008};
    static const double paper_pc[5] = {4.29e6, 2.93e6, 1.81e6, 1.22e6, 1.11e6}; /* BENCHMARKS C1, analytical centre pressure */
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 0.0076, .vtk_every = 0.002, .csv_every = 0.0002,
                        .E = 1e6, .nu = 0.3, .rho0 = 1000, .out = "out/elliptical_drop", .jitter = 0, .seed = 1, .transport = 2,
                        PNG_DEFAULTS};
    double dp = 0.02, c0 = 1400;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (the paper: 0.1, 0.05, 0.02)", 1e-3, 0.25, NULL},
        {"c0", OPT_REAL, &c0, "artificial sound speed [m/s]", 1, 1e5, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body drop, all = {0};
    sps_diagnostics d0, d;
    sps_real lo[3] = {-R_DROP, -R_DROP, 0}, hi[3] = {R_DROP, R_DROP, 0};
    run_state s;
    drop_shape sh;
    double a, b, wall, t_prev = 0;
    int k, i, n;

    ex_options(argc, argv, "elliptical water drop (benchmark C1, bench/VALIDATION.md)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (ex_check_step) */
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    bd.name = "drop";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = (sps_real)c0;
    sps_world_create(&wd, &w);
    ex_unset_unread(&bd); /* a fluid reads no shear formulation */
    sps_world_add_body(w, &bd, &drop);
    sps_body_add_sdf(w, drop, lo, hi, disc_sdf, NULL, NULL);
    sps_body_set_velocity(w, drop, initial_velocity, NULL);
    sps_body_set_pressure(w, drop, initial_pressure, &c.rho0);

    memset(&s, 0, sizeof s);
    s.dp = dp;
    sps_world_diagnostics(w, all, &d0);
    s.p0[0] = d0.linear_momentum[0];
    s.p0[1] = d0.linear_momentum[1];
    s.l0 = d0.angular_momentum[2];
    {
        const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
        const sps_real* m = sps_world_field(w, SPS_FIELD_MASS);
        n = sps_world_particle_count(w);
        for (i = 0; i < n; ++i) {
            const double r = sqrt((double)(x[i] * x[i] + y[i] * y[i]));
            s.p_scale += m[i] * A0 * r; /* sum m |v| */
            s.l_scale += m[i] * A0 * r * r; /* sum m |x| |v| */
        }
    }
    output_open(&s.output, &c, "elliptical_drop", "pressure", ",a_moment,b_moment,a_edge,b_edge,a_exact,b_exact,centre_pressure");
    printf("elliptical drop: dp = %g, %d particles, c0 = %g m/s, transport %s\n", dp, sps_world_particle_count(w), c0,
           c.transport == 0 ? "none" : c.transport == 1 ? "TVF" : "UTVF");
    printf("     t [s]   a (moments)  a (edge)  a exact   b (moments)  b (edge)  b exact   err b     centre p [Pa]  exact\n");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    wall = 0;
    for (k = 0; k < 5 && check_t[k] <= c.t_end + 1e-12; ++k) {
        const double w0 = wall_seconds();
        sps_result r = sps_world_advance(w, (sps_real)check_t[k], on_step, &s);
        ex_check_step(w, r, &s.output);
        wall += wall_seconds() - w0;
        sh = measure(w, dp);
        drop_axes(sps_world_time(w), &a, &b);
        printf("  %8.4f   %9.5f   %9.5f  %8.5f   %9.5f   %9.5f  %8.5f  %+7.3f%%  %12.4g  %9.3g\n", (double)sps_world_time(w), sh.a_moment,
               sh.a_edge, a, sh.b_moment, sh.b_edge, b, 100 * (sh.b_moment / b - 1), sh.centre_pressure, paper_pc[k]);
        t_prev = check_t[k];
    }
    if (c.t_end > t_prev + 1e-12) {
        sps_result r = sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
        ex_check_step(w, r, &s.output);
    }
    output_close(w, &s.output);
    sps_world_diagnostics(w, all, &d);
    sh = measure(w, dp);
    drop_axes(sps_world_time(w), &a, &b);
    printf("RESULT case=elliptical_drop dp=%g c0=%g t=%.6g a=%.6f b=%.6f a_exact=%.6f b_exact=%.6f err_a=%+.3f%% err_b=%+.3f%% "
           "a_edge=%.6f b_edge=%.6f centre_pressure=%.5g max_linmom_drift=%.2e max_angmom_drift=%.2e min_spacing=%.3f "
           "surface_particles=%d %s particles=%d steps=%ld advection_steps=%ld wall_s=%.2f out=%s\n",
           dp, c0, (double)sps_world_time(w), sh.a_moment, sh.b_moment, a, b, 100 * (sh.a_moment / a - 1), 100 * (sh.b_moment / b - 1),
           sh.a_edge, sh.b_edge, sh.centre_pressure, s.max_dp, s.max_dl, s.output.min_spacing, d.surface_particles,
           common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
