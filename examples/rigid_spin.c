/* rigid_spin.c - a free rigid box with three different principal moments (sides 0.09 x 0.06 x
   0.03 m) spun about each principal axis in turn with a small perturbation: stable about the
   largest and smallest moments, and about the intermediate one it flips over and back (the
   tennis-racket theorem), at the period of the closed form (FREE RIGID BODIES in the header's
   manual).

   No gravity, no walls: nothing acts on the body, and the free turn (the implicit midpoint rule
   for Euler's equations with a Cayley rotation) keeps its energy and the magnitude of its angular
   momentum; the world's L is not changed by the turn at all. Each run starts with
   omega = omega0 (e_k + eps (e_i + e_j)) in the principal axes e_k (the box's x, y, z: k the axis
   of the run), and records omega in the body's frame. Stable: omega's component along e_k never
   changes sign. The time between flips of the intermediate axis, T/2, against Euler's equations'
   exact solution (Landau and Lifshitz, Mechanics, section 37): with I1 < I2 < I3, energy E and
   |L| = M (M^2 > 2 E I2, else I1 and I3 swap),
       T = 4 K(k) sqrt(I1 I2 I3 / ((I3 - I2)(M^2 - 2 E I1))),
       k^2 = (I2 - I1)(2 E I3 - M^2) / ((I3 - I2)(M^2 - 2 E I1)),
   K the complete elliptic integral of the first kind (by the arithmetic-geometric mean), the
   moments those of the particle set (sps_body_rigid_state). The contact stiffness (E) is low: the
   body touches nothing, and the time step follows it (sqrt(K / rho0) enters it as for any free
   rigid body).
   Output: rigid_spin.csv (and VTK, picture) for the intermediate axis, rigid_spin_x and _z for the others.
   RESULT: for each axis stable_x/y/z (1 or 0) and, for the intermediate axis, flip_period next
   to theory, and over the whole run (--turns turns of the fastest axis) energy_drift and
   L_drift, the largest relative changes of the kinetic energy and of |L|.

   Build: make build/rigid_spin     Run: ./build/rigid_spin
   Smoke: rigid_spin --turns 2 */
#include "common.h"

typedef struct {
    double t_flip_first, t_flip_last, e0, l0, e_drift, l_drift, last_sign, min_along;
    int flips, axis;
    sps_body body;
} spin_run;

static double agm(double a, double b) {
    int k;
    for (k = 0; k < 60 && fabs(a - b) > 1e-15 * a; ++k) {
        const double m = 0.5 * (a + b);
        b = sqrt(a * b);
        a = m;
    }
    return a;
}

/* The time between flips T/2 of Euler's equations' solution for moments I (any order), energy E
   and |L| = M (Landau and Lifshitz section 37). */
static double flip_time(const double I_[3], double E, double M) {
    double I[3] = {I_[0], I_[1], I_[2]}, t, k2, T;
    int a, b;
    for (a = 0; a < 3; ++a) /* sort ascending */
        for (b = a + 1; b < 3; ++b)
            if (I[b] < I[a]) { t = I[a]; I[a] = I[b]; I[b] = t; }
    if (M * M < 2 * E * I[1]) { t = I[0]; I[0] = I[2]; I[2] = t; } /* the other family of orbits */
    k2 = (I[1] - I[0]) * (2 * E * I[2] - M * M) / ((I[2] - I[1]) * (M * M - 2 * E * I[0]));
    T = 4 * (PI / (2 * agm(1, sqrt(1 - k2)))) * sqrt(I[0] * I[1] * I[2] / ((I[2] - I[1]) * (M * M - 2 * E * I[0])));
    return T / 2;
}

/* Records omega in the body frame: flips of its component along the run's axis, the drifts. */
static void record(sps_world* w, spin_run* r) {
    sps_rigid_state st;
    double wb[3], e = 0, l = 0, along;
    int a;
    sps_body_rigid_state(w, r->body, &st);
    for (a = 0; a < 3; ++a) {
        wb[a] = st.rotation[a] * st.angular_velocity[0] + st.rotation[3 + a] * st.angular_velocity[1] + st.rotation[6 + a] * st.angular_velocity[2];
        e += 0.5 * st.angular_velocity[a] * st.angular_momentum[a];
        l += st.angular_momentum[a] * st.angular_momentum[a];
    }
    l = sqrt(l);
    along = wb[r->axis] / sqrt(wb[0] * wb[0] + wb[1] * wb[1] + wb[2] * wb[2]);
    if (r->e0 == 0) { r->e0 = e; r->l0 = l; r->last_sign = along > 0 ? 1 : -1; r->min_along = 1; }
    if (fabs(e - r->e0) / r->e0 > r->e_drift) r->e_drift = fabs(e - r->e0) / r->e0;
    if (fabs(l - r->l0) / r->l0 > r->l_drift) r->l_drift = fabs(l - r->l0) / r->l0;
    if (along * r->last_sign < 0) {
        r->last_sign = -r->last_sign;
        if (r->flips++ == 0) r->t_flip_first = sps_world_time(w);
        r->t_flip_last = sps_world_time(w);
    }
    if (along * (r->flips % 2 ? -1 : 1) < r->min_along) r->min_along = along;
}

int main(int argc, char** argv) {
    double omega0 = 10, eps = 0.01, turns = 100, dp = 0.01, theory = 0, flip = 0, e_drift = 0, l_drift = 0, wall0;
    common_options c = {.shear = SPS_SHEAR_ENO_A, .rotation = SPS_ROTATION_PAIR, .cfl = 0.4, .t_end = 0, .vtk_every = 0,
                        .csv_every = 0.01, .E = 1e3, .nu = 0.3, .rho0 = 1000, .out = "out/rigid_spin", PNG_DEFAULTS};
    opt_spec opts[] = {
        {"omega", OPT_REAL, &omega0, "spin rate omega0 [rad/s]", 0.01, 1000, NULL},
        {"eps", OPT_REAL, &eps, "perturbation: omega's components off the axis relative to omega0", 1e-6, 0.5, NULL},
        {"turns", OPT_REAL, &turns, "turns of the run at omega0", 0.1, 10000, NULL},
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 0.002, 0.03, NULL},
    };
    const char* axis_names = "xyz";
    spin_run runs[3];
    long steps = 0;
    int axis, particles = 0, intermediate = 1, stable[3];
    double moments[3] = {0, 0, 0};
    output_plan output;
    sps_world_def world_def = sps_default_world_def();
    sps_body_def box_def = sps_default_body_def();

    ex_options(argc, argv, "a free rigid box spun about each principal axis: the intermediate one flips", opts, &c, &world_def, &box_def);
    world_def.dim = 3;
    world_def.dp = (sps_real)dp;
    box_def.name = "box";
    box_def.material.kind = SPS_MATERIAL_RIGID_DYNAMIC;
    box_def.rotation = SPS_ROTATION_AUTO; /* a rigid body has no shear formulation */
    box_def.track_stress = 0;
    memset(runs, 0, sizeof runs);
    wall0 = wall_seconds();
    for (axis = 0; axis < 3; ++axis) {
        const sps_real lo[3] = {-0.045, -0.03, -0.015}, hi[3] = {0.045, 0.03, 0.015}, v[3] = {0, 0, 0};
        sps_real omega[3];
        sps_rigid_state st;
        sps_diagnostics d;
        sps_world* w;
        char name[32], extra[128];
        spin_run* r = &runs[axis];
        int a;
        sps_world_create(&world_def, &w);
        sps_world_add_body(w, &box_def, &r->body);
        sps_body_add_box(w, r->body, lo, hi, NULL);
        for (a = 0; a < 3; ++a) omega[a] = (sps_real)(omega0 * (a == axis ? 1 : eps));
        sps_body_set_rigid_motion(w, r->body, v, omega);
        sps_body_rigid_state(w, r->body, &st);
        for (a = 0; a < 3; ++a) moments[a] = st.inertia[4 * a]; /* the box's axes are principal */
        r->axis = axis;
        if (axis == intermediate) snprintf(name, sizeof name, "rigid_spin"); /* the run that flips: the example's own files */
        else snprintf(name, sizeof name, "rigid_spin_%c", axis_names[axis]);
        c.t_end = turns * 2 * PI / omega0;
        output_open(&output, &c, name, "velocity", ",omega_body_x,omega_body_y,omega_body_z");
        record(w, r);
        while (sps_world_time(w) < c.t_end) {
            double wb[3];
            ex_check_step(w, sps_world_advance(w, sps_world_time(w) + (sps_real)c.csv_every, NULL, NULL), &output);
            record(w, r);
            sps_body_rigid_state(w, r->body, &st);
            for (a = 0; a < 3; ++a)
                wb[a] = st.rotation[a] * st.angular_velocity[0] + st.rotation[3 + a] * st.angular_velocity[1] + st.rotation[6 + a] * st.angular_velocity[2];
            snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g", wb[0], wb[1], wb[2]);
            output_tick(w, &output, extra, &d);
        }
        output_close(w, &output);
        sps_world_diagnostics(w, (sps_body){0}, &d);
        steps += d.acoustic_steps;
        particles = sps_world_particle_count(w);
        stable[axis] = r->flips == 0;
        if (r->e_drift > e_drift) e_drift = r->e_drift;
        if (r->l_drift > l_drift) l_drift = r->l_drift;
        if (axis == intermediate) {
            flip = r->flips > 1 ? (r->t_flip_last - r->t_flip_first) / (r->flips - 1) : 0;
            theory = flip_time(moments, r->e0, r->l0);
        }
        sps_world_destroy(w);
    }
    printf("RESULT case=rigid_spin omega=%g eps=%g turns=%g moments=%.4g,%.4g,%.4g stable_x=%d stable_y=%d stable_z=%d flips_y=%d "
           "flip_period=%.5g theory=%.5g rel_error=%.2f%% energy_drift=%.2e L_drift=%.2e particles=%d steps=%ld wall_s=%.2f out=%s\n",
           omega0, eps, turns, moments[0], moments[1], moments[2], stable[0], stable[1], stable[2], runs[intermediate].flips, flip,
           theory, theory > 0 ? 100 * fabs(flip - theory) / theory : 0, e_drift, l_drift, particles, steps,
           wall_seconds() - wall0, c.out);
    return 0;
}
