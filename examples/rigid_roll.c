/* rigid_roll.c - a free rigid disc (2D), ball (3D) or box (2D) released on a slope with Coulomb
   friction: rolling, sliding or sticking against their closed forms (FREE RIGID BODIES in the
   header's manual).

   The slope is the analytic wall y = 0 with friction mu (sps_world_set_wall_friction; the body's
   friction is mu too, so the pair's sqrt(mu mu) = mu) and gravity tilted by the angle theta,
   g = 9.81 (sin theta, -cos theta). The body (material.kind = SPS_MATERIAL_RIGID_DYNAMIC,
   density 1000, contact stiffness from E 1e6, nu 0.3, contact_damping --damping, 0) is a disc or ball of
   radius 0.05 filled body-fitted (sps_body_add_sdf_relaxed: a smooth surface to roll on) or a
   box 0.1 x 0.05. For the first --settle seconds its motion is set to rest at every CSV
   interval (a kinetic relaxation onto the contact); from then its centre's position along the
   slope is fitted by least squares with x = x0 + v0 t + a t^2 / 2 up to --tend.
   Closed forms (g_t = g sin theta, g_n = g cos theta; k = I / (m R^2): 1/2 disc, 2/5 ball):
     box:  slides with a = g_t - mu g_n if tan theta > mu, else sticks (a = 0);
     disc, ball: roll with a = g_t / (1 + k) (2/3 g_t, 5/7 g_t) if mu >= tan theta k / (1 + k),
       else slide with a = g_t - mu g_n.
   theory= is that closed form; theory_set= the same with the particle set's own inertia I
   (sps_body_rigid_state: each particle a cell of its volume) and its rolling radius R, the
   centre's height above its lowest particle plus dp/2 (friction acts at the body's surface):
   a = g_t / (1 + I / (m R^2)).
   RESULT: accel (fitted) next to theory and theory_set, rel_error against theory (or against
   g_t when the theory is 0: sticking), creep = distance slid / frictionless 1/2 g_t t^2,
   spin_ratio = omega R / v at the end with that R (1: rolling without slip).

   Build: make build/rigid_roll     Run: ./build/rigid_roll --shape disc --mu 0.5 --angle 30
   Smoke: rigid_roll --dp 0.01 --settle 0.01 --tend 0.02 */
#include "common.h"

#define G 9.81
#define SIZE 0.05 /* disc and ball radius, box height [m] */

typedef struct {
    output_plan output;
    double t_end, settle;
    sps_body body;
    int quiet;
    double sum[5], sum_x[3]; /* least-squares sums: t^0..t^4, x t^0..2 */
    double x_start, x_end, radius, spin_ratio, dp;
} run_state;

/* The centre's height above the body's lowest particle plus dp/2: its radius towards the slope. */
static double rolling_radius(const sps_world* w, double centre_y, double dp) {
    const sps_real* y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    double lowest = 1e30;
    int i;
    for (i = 0; i < sps_world_particle_count(w); ++i)
        if (y[i] < lowest) lowest = y[i];
    return centre_y - lowest + 0.5 * dp;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    const sps_real zero[3] = {0, 0, 0};
    sps_rigid_state st;
    sps_diagnostics d;
    double t = sps_world_time(w), x, tt = 1;
    int k;
    if (t < s->output.next_csv - 1e-12) { progress(t, s->t_end, s->output.wall0, s->quiet); return 0; }
    sps_body_rigid_state(w, s->body, &st);
    x = st.position[0];
    if (t < s->settle - 1e-12) sps_body_set_rigid_motion(w, s->body, zero, zero); /* kinetic relaxation */
    else {
        if (s->sum[0] == 0) { s->x_start = x; s->radius = rolling_radius(w, st.position[1], s->dp); }
        for (k = 0; k < 5; ++k, tt *= t) {
            s->sum[k] += tt;
            if (k < 3) s->sum_x[k] += tt * x;
        }
    }
    s->x_end = x;
    s->spin_ratio = fabs(st.velocity[0]) > 0 ? -st.angular_velocity[2] * s->radius / st.velocity[0] : 0;
    {
        char extra[128];
        snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g", x, (double)st.velocity[0], (double)st.angular_velocity[2]);
        output_tick(w, &s->output, extra, &d);
    }
    return 0;
}

int main(int argc, char** argv) {
    int shape = 0, dim; /* disc|ball|box */
    double mu = 0.5, angle = 30, dp = 0.0025, settle = 0.1, lift = 0, damping = 0;
    common_options c = {.shear = SPS_SHEAR_ENO_A, .rotation = SPS_ROTATION_PAIR, .cfl = 0.4, .t_end = 0.6, .vtk_every = 0.1,
                        .csv_every = 0.005, .E = 1e6, .nu = 0.3, .rho0 = 1000, .out = "out/rigid_roll", PNG_DEFAULTS};
    opt_spec opts[] = {
        {"shape", OPT_CHOICE, &shape, "the body (disc and box: 2D; ball: 3D)", 0, 0, "disc|ball|box"},
        {"mu", OPT_REAL, &mu, "Coulomb friction coefficient of the slope and the body", 0, 10, NULL},
        {"angle", OPT_REAL, &angle, "slope angle theta [degrees]", 0, 89, NULL},
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 0.001, 0.025, NULL},
        {"lift", OPT_REAL, &lift, "gap between the body's surface and the slope at the start [dp] (0: flush, the contact's rest)", 0, 10, NULL},
        {"settle", OPT_REAL, &settle, "kinetic relaxation before the release [s]", 0, 100, NULL},
        {"damping", OPT_REAL, &damping, "contact_damping of the body", 0, 1, NULL},
    };
    const char* shape_names[] = {"disc", "ball", "box"};
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    run_state s;
    sps_diagnostics d;
    sps_rigid_state st;
    double theta, g_t, g_n, k = 0, theory, theory_set, accel, rel, wall, inertia;
    int rolls = 0;

    ex_options(argc, argv, "a free rigid disc, ball or box released on a slope with Coulomb friction", opts, &c, &wd, &bd);
    if (!(settle < c.t_end)) opt_fail("rigid_roll", "--settle must be below --tend%s%s", "", "");
    dim = shape == 1 ? 3 : 2;
    theta = angle * PI / 180;
    g_t = G * sin(theta);
    g_n = G * cos(theta);
    bd.rotation = SPS_ROTATION_AUTO; /* a rigid body has no shear formulation */
    bd.track_stress = 0;
    wd.dim = dim;
    wd.dp = (sps_real)dp;
    wd.gravity[0] = (sps_real)g_t;
    wd.gravity[1] = (sps_real)-g_n;
    bd.name = shape_names[shape];
    bd.material.kind = SPS_MATERIAL_RIGID_DYNAMIC;
    bd.friction = (sps_real)mu;
    bd.contact_damping = (sps_real)damping;
    sps_world_create(&wd, &w);
    memset(&s, 0, sizeof s);
    sps_world_add_body(w, &bd, &s.body);
    ex_add_slope_body(w, s.body, shape == 2, dim, SIZE, lift * dp, mu);
    if (shape != 2) k = shape == 0 ? 0.5 : 0.4; /* I / (m R^2) */
    if (shape == 2) theory = tan(theta) > mu ? g_t - mu * g_n : 0;
    else {
        rolls = mu >= tan(theta) * k / (1 + k);
        theory = rolls ? g_t / (1 + k) : g_t - mu * g_n;
    }
    s.t_end = c.t_end; s.settle = settle; s.quiet = c.quiet; s.dp = dp;
    output_open(&s.output, &c, "rigid_roll", "velocity", ",centre_x,velocity_x,omega_z");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    sps_body_rigid_state(w, s.body, &st);
    inertia = dim == 2 ? st.inertia[8] : st.inertia[8]; /* about the rolling axis z */
    theory_set = shape == 2 ? theory : rolls ? g_t / (1 + inertia / (st.mass * s.radius * s.radius)) : theory;
    accel = ex_fitted_acceleration(s.sum, s.sum_x);
    rel = fabs(accel - theory) / (theory > 0 ? theory : g_t);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    printf("RESULT case=rigid_roll shape=%s mu=%g angle=%g dp=%g accel=%.5g theory=%.5g theory_set=%.5g rel_error=%.2f%% "
           "rel_error_set=%.2f%% motion=%s spin_ratio=%.4f inertia_ratio=%.4f creep=%.3f%% particles=%d steps=%ld wall_s=%.2f out=%s\n",
           shape_names[shape], mu, angle, dp, accel, theory, theory_set, 100 * rel,
           100 * fabs(accel - theory_set) / (theory_set > 0 ? theory_set : g_t),
           shape == 2 ? (theory > 0 ? "sliding" : "sticking") : (rolls ? "rolling" : "sliding"), s.spin_ratio,
           shape == 2 ? 0 : inertia / (st.mass * s.radius * s.radius),
           100 * (s.x_end - s.x_start) / (0.5 * g_t * (c.t_end - settle) * (c.t_end - settle)), sps_world_particle_count(w),
           d.acoustic_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
