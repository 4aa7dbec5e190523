/* incline.c - a block, disc (2D) or ball (3D) released on a slope with Coulomb friction: sliding,
   sticking and rolling against their closed forms (CONTACT: friction in the header's manual).

   The slope is the analytic wall y = 0 with friction mu (sps_world_set_wall_friction; the body's
   friction is mu too, so the pair's sqrt(mu mu) = mu) and gravity tilted by the angle theta,
   g = 9.81 (sin theta, -cos theta): the same physics as a tilted wall under vertical gravity. The
   body starts at rest on it (block 0.1 x 0.05 (x 0.05 in 3D); disc or ball of radius 0.05,
   body-fitted by sps_body_add_sdf_relaxed so that it rolls on a smooth surface), rubber-like
   (rho0 1000, E 1e6, nu 0.3), ENO-A with pair rotation (exact angular momentum), set here so that
   a change of the library's defaults does not move the figures. Its centre's position along the
   The contact with the slope has no normal damping, so the body's landing would go on rattling
   it on the contact's stiffness (and a rattling block creeps down a slope it should stick to):
   the first --settle seconds are a kinetic relaxation, the velocities set to zero every CSV
   interval, so that the body starts at rest on the contact; from then its centre's position
   along the slope is fitted by least squares with x = x0 + v0 t + a t^2 / 2 up to --tend, the
   spin omega R (about the centre of mass) with a line.
   Closed forms (g_t = g sin theta, g_n = g cos theta):
     block: slides with a = g_t - mu g_n if tan theta > mu, else sticks (a = 0);
     disc (I = m R^2 / 2) and ball (I = 2 m R^2 / 5): roll with a = g_t / (1 + I / (m R^2)), i.e.
       2/3 g_t and 5/7 g_t, if mu >= tan theta I / (I + m R^2) (the friction rolling needs), else
       slide with a = g_t - mu g_n while friction spins them up at d(omega R)/dt = mu g_n m R^2 / I.
   RESULT (times from the release): accel (fitted) next to theory and rel_error (|accel - theory| / theory, or / g_t when
   the theory is 0: sticking), spin (fitted d(omega R)/dt) next to spin_theory, and for a sticking
   body creep = the distance slid over the run relative to the frictionless 1/2 g_t t^2.

   Build: make build/incline      Run: ./build/incline --dim 2 --shape block --mu 0.3 --angle 30
   Expect: accel = theory = 2.3563 m/s^2 here; at --angle 10 creep 0.36 %; a disc or ball rolls
   a few % slow at R/dp 10 (friction acts at its outer particles, R - dp/2: 2 % at --dp 0.0025).
   Smoke: incline --dp 0.01 --settle 0.01 --tend 0.02 */
#include "common.h"

#define G 9.81
#define SIZE 0.05 /* block height, disc and ball radius [m] */

typedef struct {
    output_plan output;
    double t_end, settle, g_t;
    sps_body body;
    int quiet, dim;
    double sum[5], sum_x[3], sum_s[3]; /* least-squares sums: t^0..t^4, x t^0..2, omega R t^0..2 */
    double x_start, x_end;
} run_state;

/* The body's centre (along the slope) and its spin omega R about the centre of mass (z axis). */
static void centre_and_spin(const sps_world* w, int dim, double* x_centre, double* spin) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real *vx = sps_world_field(w, SPS_FIELD_VELOCITY_X), *vy = sps_world_field(w, SPS_FIELD_VELOCITY_Y);
    const sps_real* m = sps_world_field(w, SPS_FIELD_MASS);
    double mass = 0, c[2] = {0, 0}, v[2] = {0, 0}, moment = 0, inertia = 0;
    int i, n = sps_world_particle_count(w);
    (void)dim;
    for (i = 0; i < n; ++i) {
        mass += m[i];
        c[0] += m[i] * x[i]; c[1] += m[i] * y[i];
        v[0] += m[i] * vx[i]; v[1] += m[i] * vy[i];
    }
    c[0] /= mass; c[1] /= mass; v[0] /= mass; v[1] /= mass;
    for (i = 0; i < n; ++i) {
        const double rx = x[i] - c[0], ry = y[i] - c[1];
        moment += m[i] * (rx * (vy[i] - v[1]) - ry * (vx[i] - v[0]));
        inertia += m[i] * (rx * rx + ry * ry);
    }
    *x_centre = c[0];
    *spin = -moment / inertia * SIZE; /* rolling down +x turns clockwise: omega_z < 0 */
}

static void at_rest(const sps_real x[3], sps_real v[3], void* user) {
    (void)x; (void)user;
    v[0] = v[1] = v[2] = 0;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    double t = sps_world_time(w), x, spin, tt = 1;
    int k;
    if (t < s->output.next_csv - 1e-12) { progress(t, s->t_end, s->output.wall0, s->quiet); return 0; }
    centre_and_spin(w, s->dim, &x, &spin);
    if (t < s->settle - 1e-12) sps_body_set_velocity(w, s->body, at_rest, NULL); /* kinetic relaxation */
    if (t >= s->settle - 1e-12) {
        if (s->sum[0] == 0) s->x_start = x;
        for (k = 0; k < 5; ++k, tt *= t) {
            s->sum[k] += tt;
            if (k < 3) { s->sum_x[k] += tt * x; s->sum_s[k] += tt * spin; }
        }
    }
    s->x_end = x;
    {
        char extra[96];
        snprintf(extra, sizeof extra, ",%.9g,%.9g", x, spin);
        output_tick(w, &s->output, extra, &d);
    }
    return 0;
}

int main(int argc, char** argv) {
    int dim = 2, shape = 0; /* block|disc|ball (ball: 3D; disc: 2D) */
    double mu = 0.3, angle = 30, dp = 0.005, settle = 0.2, viscosity = 0, lift = 0;
    common_options c = {.shear = SPS_SHEAR_ENO_A, .rotation = SPS_ROTATION_PAIR, .cfl = 0.4, .t_end = 1.2, .vtk_every = 0.1,
                        .csv_every = 0.005, .E = 1e6, .nu = 0.3, .rho0 = 1000, .out = "out/incline", PNG_DEFAULTS};
    opt_spec opts[] = {
        {"dim", OPT_INT, &dim, "space dimension", 2, 3, NULL},
        {"shape", OPT_CHOICE, &shape, "the body (disc: 2D; ball: 3D)", 0, 0, "block|disc|ball"},
        {"mu", OPT_REAL, &mu, "Coulomb friction coefficient of the slope and the body", 0, 10, NULL},
        {"angle", OPT_REAL, &angle, "slope angle theta [degrees]", 0, 89, NULL},
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 0.001, 0.025, NULL},
        {"lift", OPT_REAL, &lift, "gap between the body's surface and the slope at the start [dp] (0: flush, the contact's rest)", 0, 10, NULL},
        {"settle", OPT_REAL, &settle, "kinetic relaxation before the release [s]: the body comes to rest on the slope", 0, 100, NULL},
        {"viscosity", OPT_REAL, &viscosity, "Kelvin-Voigt viscosity eta of the body [Pa s]", 0, 1e9, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    run_state s;
    sps_diagnostics d;
    const char* shape_names[] = {"block", "disc", "ball"};
    double theta, g_t, g_n, inertia_ratio = 0, theory, spin_theory = 0, accel, spin, rel, wall;
    int rolls = 0;

    ex_options(argc, argv, "a block, disc or ball released on a slope with Coulomb friction", opts, &c, &wd, &bd);
    if (shape == 1 && dim != 2) opt_fail("incline", "--shape %s needs --dim 2%s", "disc", "");
    if (shape == 2 && dim != 3) opt_fail("incline", "--shape %s needs --dim 3%s", "ball", "");
    if (!(settle < c.t_end)) opt_fail("incline", "--settle must be below --tend%s%s", "", "");
    theta = angle * PI / 180;
    g_t = G * sin(theta);
    g_n = G * cos(theta);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    wd.dim = dim;
    wd.dp = (sps_real)dp;
    wd.gravity[0] = (sps_real)g_t;
    wd.gravity[1] = (sps_real)-g_n;
    bd.name = shape_names[shape];
    bd.friction = (sps_real)mu;
    bd.material.viscosity = (sps_real)viscosity;
    sps_world_create(&wd, &w);
    memset(&s, 0, sizeof s);
    sps_world_add_body(w, &bd, &s.body);
    ex_add_slope_body(w, s.body, shape == 0, dim, SIZE, lift * dp, mu);
    if (shape != 0) inertia_ratio = shape == 1 ? 0.5 : 0.4; /* I / (m R^2) */
    /* the closed forms */
    if (shape == 0) theory = tan(theta) > mu ? g_t - mu * g_n : 0;
    else {
        rolls = mu >= tan(theta) * inertia_ratio / (1 + inertia_ratio);
        theory = rolls ? g_t / (1 + inertia_ratio) : g_t - mu * g_n;
        spin_theory = rolls ? theory : mu * g_n / inertia_ratio;
    }
    s.t_end = c.t_end; s.settle = settle; s.quiet = c.quiet; s.dim = dim; s.g_t = g_t;
    output_open(&s.output, &c, "incline", "velocity", ",centre_x,spin_omega_R");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    accel = ex_fitted_acceleration(s.sum, s.sum_x);
    spin = (s.sum[0] * s.sum_s[1] - s.sum[1] * s.sum_s[0]) / (s.sum[0] * s.sum[2] - s.sum[1] * s.sum[1]); /* the slope of a line fit */
    rel = fabs(accel - theory) / (theory > 0 ? theory : g_t);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    printf("RESULT case=incline dim=%d shape=%s mu=%g angle=%g dp=%g viscosity=%g accel=%.5g theory=%.5g rel_error=%.2f%% motion=%s "
           "spin=%.5g spin_theory=%.5g creep=%.3f%% shear=%s %s particles=%d steps=%ld wall_s=%.2f out=%s\n",
           dim, shape_names[shape], mu, angle, dp, viscosity, accel, theory, 100 * rel,
           shape == 0 ? (theory > 0 ? "sliding" : "sticking") : (rolls ? "rolling" : "sliding"), spin, spin_theory,
           100 * (s.x_end - s.x_start) / (0.5 * g_t * (c.t_end - settle) * (c.t_end - settle)), shear_name(c.shear), common_result_fields(&c),
           sps_world_particle_count(w), d.acoustic_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
