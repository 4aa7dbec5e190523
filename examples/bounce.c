/* bounce.c - a rubber disc (2D) or ball (3D) dropped on, or thrown at, a floor: the normal
   contact damping and Kelvin-Voigt material damping bring it to rest, Coulomb friction makes a
   thrown one leave rolling (DAMPING and CONTACT in the header's manual).

   A disc or ball of radius 0.05 (body-fitted, sps_body_add_sdf_relaxed), rho0 1000, E 1e6,
   nu 0.3, Kelvin-Voigt viscosity --viscosity eta [Pa s], ENO-A with pair rotation and the shear
   stress tracked (the strain energy's shear part is in the account), set here so that a change
   of the library's defaults does not move the figures; the floor is the analytic wall y = 0 with
   friction --mu (the body's too: the pair's sqrt(mu mu) = mu); the body's normal contact
   damping ratio --contact-damping zeta (sps_body_def.contact_damping); gravity 9.81 down.
   Dropped (--speed 0): released at rest with its lowest point --height above the floor. We
   report when its kinetic energy first stays below 1e-6 of the energy it fell through, m g
   height (t_rest; "never" within --tend), the number of bounces (contacts that ended), and the
   energy account E = kinetic + strain + contact + gravity potential + dissipated work (the
   Kelvin-Voigt and Riemann viscous work, sps_diagnostics.viscous_work): its largest departure
   from the start over the run relative to m g height (account_error); and the restitution of
   the first bounce, e = v_out / v_in of the centre of mass (v_in when the first contact starts,
   v_out when it ends), next to spring_dashpot_restitution = exp(-pi zeta / sqrt(1 - zeta^2)),
   the DEM closed form of one mass on one linear spring-dashpot (which this contact is not: the
   figures in bench/VALIDATION.md).
   Thrown (--speed V > 0): starts just above the floor moving at V, --angle degrees below the
   horizontal. A rigid disc (I = m R^2 / 2) that reaches rolling during the impact leaves with
   v_t = omega R = 2/3 of its tangential speed (ball: 5/7), which takes a friction impulse of
   1/3 (2/7) of m v_t; we report v_t and omega R (about the centre of mass) at the end of the
   first flight (both stay constant in the air), and their ratio next to 1. --rigid makes the
   body a free rigid body (SPS_MATERIAL_RIGID_DYNAMIC: friction at its contact surface's velocity;
   no Kelvin-Voigt viscosity).

   Build: make build/bounce      Run: ./build/bounce --contact-damping 1
   Expect (bench/VALIDATION.md, "Friction and material damping"): with --contact-damping 1 it
   rests from t = 2.558 s (eta 20) and 1.985 s (--viscosity 200), account_error 1.27 % and
   1.37 %, restitution 0.832 and 0.727; without contact damping eta 20 and 200 still bounce at
   3 s, eta 1000 with --tend 6 rests from t = 4.77 s; account_error 1.8-3.9 % (ENO-A's strain
   energy is not its force's potential). Thrown with
   --speed 2 --angle 20 --mu 0.5: rolling_ratio 1.09 (rolling: 1).
   Smoke: bounce --dp 0.01 --tend 0.01
   Smoke: bounce --dp 0.01 --height 0.05 --tend 0.2 --contact-damping 1 */
#include "common.h"

#define G 9.81
#define RADIUS 0.05

typedef struct {
    output_plan output;
    sps_body body;
    double e_fall, account0, account_error, t_rest, t_below, v_t, omega_r, v_y_before, v_in, v_out;
    int dim, bounces, touching, thrown;
} run_state;

typedef struct {
    int dim;
    double centre_y;
} ball_shape;
static sps_real ball_sdf(const sps_real x[3], void* user) {
    const ball_shape* b = (const ball_shape*)user;
    const double dy = x[1] - b->centre_y, dz = b->dim == 3 ? x[2] : 0;
    return (sps_real)(sqrt(x[0] * x[0] + dy * dy + dz * dz) - RADIUS);
}

typedef struct {
    double v[2];
} launch;
static void launch_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const launch* l = (const launch*)user;
    (void)x;
    v[0] = (sps_real)l->v[0];
    v[1] = (sps_real)l->v[1];
    v[2] = 0;
}

/* The body's mean velocity along x and y and its spin omega R about its centre of mass (z axis;
   the sign of rolling towards +x). */
static void slide_and_spin(const sps_world* w, double* v_t, double* v_y, double* omega_r) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real *vx = sps_world_field(w, SPS_FIELD_VELOCITY_X), *vy = sps_world_field(w, SPS_FIELD_VELOCITY_Y);
    const sps_real* m = sps_world_field(w, SPS_FIELD_MASS);
    double mass = 0, c[2] = {0, 0}, v[2] = {0, 0}, moment = 0, inertia = 0;
    int i, n = sps_world_particle_count(w);
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
    *v_t = v[0];
    *v_y = v[1];
    *omega_r = -moment / inertia * RADIUS;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    double t = sps_world_time(w), account, v_t, v_y, omega_r;
    int touching;
    sps_world_diagnostics(w, s->body, &d);
    touching = d.contact_energy > 0;
    slide_and_spin(w, &v_t, &v_y, &omega_r);
    if (touching && !s->touching && s->bounces == 0) s->v_in = -s->v_y_before; /* the first impact: the speed of the fall */
    if (s->touching && !touching && ++s->bounces == 1) s->v_out = v_y;   /* the first rebound: e = v_out / v_in */
    if (!touching && s->bounces == 1) { s->v_t = v_t; s->omega_r = omega_r; } /* the first flight: until it lands again */
    s->touching = touching;
    s->v_y_before = v_y;
    if (d.kinetic_energy < 1e-6 * s->e_fall) {
        if (s->t_below < 0) s->t_below = t;
    } else {
        s->t_below = -1;
    }
    account = d.kinetic_energy + d.strain_energy + d.contact_energy + d.potential_energy + d.viscous_work;
    if (t == 0) s->account0 = account;
    if (fabs(account - s->account0) > s->account_error) s->account_error = fabs(account - s->account0);
    if (t >= s->output.next_csv - 1e-12) {
        char extra[64];
        snprintf(extra, sizeof extra, ",%.9g", account);
        output_tick(w, &s->output, extra, &d);
    }
    return 0;
}

/* The restitution of a mass on a linear spring-dashpot of damping ratio zeta, the standard DEM
   closed form e = exp(-pi zeta / sqrt(1 - zeta^2)) (0 from critical damping on). */
static double spring_dashpot_restitution(double zeta) { return zeta < 1 ? exp(-PI * zeta / sqrt(1 - zeta * zeta)) : 0; }

int main(int argc, char** argv) {
    int dim = 2, rigid = 0;
    double height = 0.2, viscosity = 20, mu = 0, speed = 0, angle = 20, dp = 0.005, contact_damping = 0;
    common_options c = {.shear = SPS_SHEAR_ENO_A, .rotation = SPS_ROTATION_PAIR, .cfl = 0.4, .t_end = 3, .vtk_every = 0.05,
                        .csv_every = 0.002, .E = 1e6, .nu = 0.3, .rho0 = 1000, .out = "out/bounce", .contact_rest = SPS_CONTACT_REST_KERNEL /* the figures of bench/VALIDATION.md were measured with the papers' contact law */, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"dim", OPT_INT, &dim, "space dimension (2: disc, 3: ball)", 2, 3, NULL},
        {"height", OPT_REAL, &height, "drop height of the lowest point above the floor [m]", 0.001, 100, NULL},
        {"viscosity", OPT_REAL, &viscosity, "Kelvin-Voigt viscosity eta [Pa s] (0: none)", 0, 1e9, NULL},
        {"contact-damping", OPT_REAL, &contact_damping, "damping ratio zeta of the normal contact dashpot (0: none)", 0, 1, NULL},
        {"mu", OPT_REAL, &mu, "Coulomb friction coefficient of the floor and the body", 0, 10, NULL},
        {"speed", OPT_REAL, &speed, "throw speed [m/s] (0: dropped)", 0, 100, NULL},
        {"angle", OPT_REAL, &angle, "throw angle below the horizontal [degrees]", 0, 90, NULL},
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 0.001, 0.025, NULL},
        {"rigid", OPT_FLAG, &rigid, "a free rigid body (no viscosity)", 0, 0, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    run_state s;
    sps_diagnostics d;
    ball_shape ball;
    double wall, mass, gap;

    ex_options(argc, argv, "a rubber disc or ball dropped on, or thrown at, a floor", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    wd.dim = dim;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-G;
    bd.name = "ball";
    bd.track_stress = 1;
    bd.friction = (sps_real)mu;
    bd.material.viscosity = (sps_real)viscosity;
    bd.contact_damping = (sps_real)contact_damping;
    if (rigid) { /* what a rigid body does not read, at the defaults */
        const sps_body_def defaults = sps_default_body_def();
        bd.material.kind = SPS_MATERIAL_RIGID_DYNAMIC;
        bd.material.viscosity = 0;
        bd.track_stress = 0;
        bd.shear = defaults.shear;
        bd.rotation = defaults.rotation;
    }
    sps_world_create(&wd, &w);
    memset(&s, 0, sizeof s);
    sps_world_add_body(w, &bd, &s.body);
    gap = speed > 0 ? 3 * dp : height; /* thrown: just outside the contact's reach (2h = 2.6 dp) */
    ball.dim = dim;
    ball.centre_y = RADIUS + gap;
    {
        const sps_real lo[3] = {-RADIUS, (sps_real)gap, -RADIUS}, hi[3] = {RADIUS, (sps_real)(2 * RADIUS + gap), RADIUS};
        const sps_real point[3] = {0, 0, 0}, normal[3] = {0, 1, 0};
        sps_body_add_sdf_relaxed(w, s.body, lo, hi, ball_sdf, &ball, 0, NULL);
        sps_world_add_wall(w, point, normal, SPS_WALL_FREE_SLIP);
        if (mu > 0) sps_world_set_wall_friction(w, 0, (sps_real)mu);
    }
    if (speed > 0) {
        launch l = {{speed * cos(angle * PI / 180), -speed * sin(angle * PI / 180)}};
        sps_body_set_velocity(w, s.body, launch_velocity, &l);
    }
    sps_world_diagnostics(w, s.body, &d);
    mass = 0;
    {
        const sps_real* m = sps_world_field(w, SPS_FIELD_MASS);
        int i;
        for (i = 0; i < sps_world_particle_count(w); ++i) mass += m[i];
    }
    s.e_fall = speed > 0 ? 0.5 * mass * speed * speed : mass * G * height;
    s.dim = dim; s.thrown = speed > 0; s.t_below = -1;
    output_open(&s.output, &c, "bounce", "velocity", ",account");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    sps_world_diagnostics(w, s.body, &d);
    if (s.thrown) {
        const double ideal = dim == 2 ? 2.0 / 3 : 5.0 / 7;
        printf("RESULT case=bounce dim=%d kind=%s thrown speed=%g angle=%g mu=%g viscosity=%g dp=%g v_t_out=%.5g omega_R_out=%.5g rolling_ratio=%.4f "
               "theory=1 rel_error=%.2f%% v_t_over_v_t0=%.4f rigid_rolling=%.4f shear=%s %s particles=%d steps=%ld wall_s=%.2f out=%s\n",
               dim, rigid ? "rigid" : "elastic", speed, angle, mu, viscosity, dp, s.v_t, s.omega_r, s.v_t != 0 ? s.omega_r / s.v_t : 0,
               100 * fabs(s.v_t != 0 ? s.omega_r / s.v_t - 1 : 1), s.v_t / (speed * cos(angle * PI / 180)), ideal, shear_name(c.shear),
               common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, wall, c.out);
    } else {
        char rest[32];
        if (s.t_below >= 0) snprintf(rest, sizeof rest, "%.3f", s.t_below);
        else snprintf(rest, sizeof rest, "never");
        printf("RESULT case=bounce dim=%d dropped height=%g mu=%g viscosity=%g contact_damping=%g dp=%g t_rest=%s "
               "kinetic_end_rel=%.3g bounces=%d restitution=%.4f spring_dashpot_restitution=%.4f v_in=%.4f v_out=%.4f viscous_work=%.5g fall_energy=%.5g "
               "account_error=%.3f%% target=2%% shear=%s %s particles=%d steps=%ld wall_s=%.2f out=%s\n",
               dim, height, mu, viscosity, contact_damping, dp, rest, (double)d.kinetic_energy / s.e_fall, s.bounces,
               s.v_in > 0 && s.bounces > 0 ? s.v_out / s.v_in : 0, spring_dashpot_restitution(contact_damping), s.v_in, s.v_out, (double)d.viscous_work, s.e_fall,
               100 * s.account_error / s.e_fall, shear_name(c.shear), common_result_fields(&c), sps_world_particle_count(w),
               d.acoustic_steps, wall, c.out);
    }
    sps_world_destroy(w);
    return 0;
}
