/* debris_barrier3d.c - bouldery debris against a flexible barrier (benchmark A11, ENO 6.9, a
   showcase).

   Five elastic boulders (spheres of radius 0.45 to 0.75 m; rho0 = 2500, E = 10 GPa, nu = 0.2)
   start at rest at the release gate just above (2h) a baseplate inclined at 30 degrees (a free-slip
   analytic wall), slide and roll down under gravity and strike a flexible elastic barrier
   (rho0 = 1200, E = 10 MPa, nu = 0.47), a plate 4.5 m wide, 4.5 m high and 0.3 m thick
   standing across the slope 10.5 m downstream of the gate (--distance), clamped along its
   bottom and side edges. Contact is the library's (CONTACT). The paper shows pictures only:
   we report the impact (when the first boulder touches the barrier and its speed then) and
   the barrier's largest deflection (the largest displacement of one of its particles) and
   when, then stop once the barrier has swung back by a quarter of it (--tend bounds the run).
   dp = 0.15 m by default (about 3000 particles); the boulders' sound speed, 1490 m/s, sets the
   time step (50 us), so a run takes a few minutes.

   Build: make examples     Run: ./build/debris_barrier3d (--distance 3: a quick look)
   Expect: the barrier bulges under the boulders and springs back; no particle escapes.
   Smoke: debris_barrier3d --dp 0.3 --distance 2 --tend 0.01 */
#include "common.h"

#define SLOPE_DEG 30.0
#define G_ACC 9.81
#define BARRIER_SIZE 4.5
#define BARRIER_THICKNESS 0.3
#define NBOULDERS 5

typedef struct {
    double centre[3], radius;
} sphere;
static sps_real sphere_sdf(const sps_real x[3], void* user) {
    const sphere* s = (const sphere*)user;
    const double dx = x[0] - s->centre[0], dy = x[1] - s->centre[1], dz = x[2] - s->centre[2];
    return (sps_real)(sqrt(dx * dx + dy * dy + dz * dz) - s->radius);
}

typedef struct {
    output_plan output;
    double dp, barrier_x, impact_t, impact_speed, max_deflection, max_t;
    sps_body barrier, boulders[NBOULDERS];
    int done;
} run_state;

/* The largest displacement of a barrier particle from its reference position. */
static double barrier_deflection(const sps_world* w, sps_body barrier) {
    int first, count, i, a;
    const sps_real* x[3];
    const sps_real* x0[3];
    static const char* pos[3] = {"position_x", "position_y", "position_z"};
    static const char* ref[3] = {"reference_x", "reference_y", "reference_z"};
    double largest = 0;
    for (a = 0; a < 3; ++a) {
        x[a] = sps_body_field(w, barrier, pos[a], NULL, &first, &count);
        x0[a] = sps_body_field(w, barrier, ref[a], NULL, &first, &count);
        if (!x[a] || !x0[a]) return 0;
    }
    for (i = 0; i < count; ++i) {
        double d2 = 0;
        for (a = 0; a < 3; ++a) d2 += (x[a][i] - x0[a][i]) * (x[a][i] - x0[a][i]);
        if (d2 > largest * largest) largest = sqrt(d2);
    }
    return largest;
}

/* The speed of a body's centre of mass: |sum m v| / sum m. */
static double body_speed(const sps_world* w, sps_body b) {
    static const char* vel[3] = {"velocity_x", "velocity_y", "velocity_z"};
    int first, count, i, a;
    const sps_real* m = sps_body_field(w, b, "mass", NULL, &first, &count);
    double p[3] = {0, 0, 0}, mass = 0;
    for (a = 0; a < 3; ++a) {
        const sps_real* v = sps_body_field(w, b, vel[a], NULL, &first, &count);
        for (i = 0; v && m && i < count; ++i) p[a] += m[i] * v[i];
    }
    for (i = 0; m && i < count; ++i) mass += m[i];
    return mass > 0 ? sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / mass : 0;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    const double t = sps_world_time(w);
    double deflection;
    int k, first, count, i;
    output_tick(w, &s->output, "", &d);
    if (s->impact_t < 0) /* the first boulder particle within dp of the barrier's face */
        for (k = 0; k < NBOULDERS && s->impact_t < 0; ++k) {
            const sps_real* x = sps_body_field(w, s->boulders[k], "position_x", NULL, &first, &count);
            for (i = 0; x && i < count; ++i)
                if (x[i] > s->barrier_x - 1.5 * s->dp) {
                    s->impact_t = t;
                    s->impact_speed = body_speed(w, s->boulders[k]);
                    printf("  impact at t = %.3f s: boulder %d at %.2f m/s\n", t, k, s->impact_speed);
                    break;
                }
        }
    if (s->impact_t >= 0) {
        deflection = barrier_deflection(w, s->barrier);
        if (deflection > s->max_deflection) { s->max_deflection = deflection; s->max_t = t; }
        if (s->max_deflection > 0.05 * s->dp && deflection < 0.75 * s->max_deflection) s->done = 1; /* swung back: the maximum is behind us */
    }
    return s->done;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 4, .vtk_every = 0.1, .csv_every = 0.005, .E = 1e10, .nu = 0.2,
                        .rho0 = 2500, .out = "out/debris_barrier3d", .jitter = 0, .seed = 1, .transport = 0, .contact_rest = SPS_CONTACT_REST_KERNEL /* the papers' contact law */, PNG_DEFAULTS};
    static const double radius[NBOULDERS] = {0.75, 0.6, 0.6, 0.45, 0.45};
    static const double place[NBOULDERS][2] = {{-1.0, 0}, {-2.6, -1.2}, {-2.6, 1.2}, {-3.9, -0.6}, {-3.9, 0.6}}; /* along the slope, across */
    double dp = 0.15, distance = 10.5;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 0.05, 0.5, NULL},
        {"distance", OPT_REAL, &distance, "from the release gate to the barrier, along the slope [m]", 1, 50, NULL},
    };
    const double a = SLOPE_DEG * PI / 180, t_x = cos(a), t_y = -sin(a), n_x = sin(a), n_y = cos(a);
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def(), fd = sps_default_body_def();
    sps_world* w;
    sps_diagnostics d;
    sps_real origin[3] = {0, 0, 0}, plate_normal[3], lo[3], hi[3];
    sphere balls[NBOULDERS];
    run_state s;
    double wall, base_y;
    int k;

    ex_options(argc, argv, "3D boulders against a flexible barrier on a 30-degree slope (A11, ENO 6.9)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    memset(&s, 0, sizeof s);
    s.impact_t = -1;
    wd.dim = 3;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-G_ACC;
    plate_normal[0] = (sps_real)n_x;
    plate_normal[1] = (sps_real)n_y;
    plate_normal[2] = 0;
    sps_world_create(&wd, &w);
    sps_world_add_wall(w, origin, plate_normal, SPS_WALL_FREE_SLIP); /* the baseplate through the gate at the origin */
    bd.name = "boulder";
    for (k = 0; k < NBOULDERS; ++k) { /* each just above the plate: its particles beyond the wall's contact range 2h */
        const double r = radius[k], along = place[k][0], gap = r + 2 * (double)wd.h_over_dp * dp;
        balls[k].centre[0] = along * t_x + gap * n_x;
        balls[k].centre[1] = along * t_y + gap * n_y;
        balls[k].centre[2] = place[k][1];
        balls[k].radius = r;
        sps_world_add_body(w, &bd, &s.boulders[k]);
        lo[0] = (sps_real)(balls[k].centre[0] - r); hi[0] = (sps_real)(balls[k].centre[0] + r);
        lo[1] = (sps_real)(balls[k].centre[1] - r); hi[1] = (sps_real)(balls[k].centre[1] + r);
        lo[2] = (sps_real)(balls[k].centre[2] - r); hi[2] = (sps_real)(balls[k].centre[2] + r);
        sps_body_add_sdf(w, s.boulders[k], lo, hi, sphere_sdf, &balls[k], NULL);
    }
    /* the barrier: a vertical plate across the slope, its upstream face at barrier_x, its foot
       level with the baseplate under that face (so none of its particles starts inside the
       plate, whose height falls downstream) */
    s.barrier_x = distance * t_x;
    base_y = -tan(a) * s.barrier_x;
    fd = bd;
    fd.name = "barrier";
    fd.material.density = 1200;
    fd.material.youngs_modulus = 1e7;
    fd.material.poisson_ratio = 0.47;
    sps_world_add_body(w, &fd, &s.barrier);
    lo[0] = (sps_real)s.barrier_x; hi[0] = (sps_real)(s.barrier_x + BARRIER_THICKNESS);
    lo[1] = (sps_real)base_y; hi[1] = (sps_real)(base_y + BARRIER_SIZE);
    lo[2] = (sps_real)(-BARRIER_SIZE / 2); hi[2] = (sps_real)(BARRIER_SIZE / 2);
    sps_body_add_box(w, s.barrier, lo, hi, NULL);
    { /* clamped: its bottom edge and its two side edges, 2 dp deep */
        sps_real clo[3], chi[3];
        clo[0] = lo[0]; chi[0] = hi[0];
        clo[1] = lo[1]; chi[1] = (sps_real)(lo[1] + 2 * dp);
        clo[2] = lo[2]; chi[2] = hi[2];
        sps_body_constrain_box(w, s.barrier, clo, chi, SPS_AXIS_ALL, NULL, NULL);
        chi[1] = hi[1];
        chi[2] = (sps_real)(lo[2] + 2 * dp);
        sps_body_constrain_box(w, s.barrier, clo, chi, SPS_AXIS_ALL, NULL, NULL);
        clo[2] = (sps_real)(hi[2] - 2 * dp);
        chi[2] = hi[2];
        sps_body_constrain_box(w, s.barrier, clo, chi, SPS_AXIS_ALL, NULL, NULL);
    }
    printf("debris against a flexible barrier: slope %g deg, gate-barrier %g m, dp = %g m, %d particles, %d boulders\n", SLOPE_DEG,
           distance, dp, sps_world_particle_count(w), NBOULDERS);
    s.dp = dp;
    output_open(&s.output, &c, "debris_barrier3d", "velocity", "");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    if (s.impact_t < 0) printf("  no impact by t = %.3g s\n", (double)d.time);
    else
        printf("  barrier's largest deflection %.3f m (%.1f dp) at t = %.3f s, %.3f s after the impact\n", s.max_deflection,
               s.max_deflection / dp, s.max_t, s.max_t - s.impact_t);
    printf("RESULT case=debris_barrier3d dp=%g distance=%g t=%.4g impact_t=%.4f impact_speed=%.3f max_deflection=%.4f max_t=%.4f %s "
           "particles=%d steps=%ld advection_steps=%ld wall_s=%.2f ns_per_particle_step=%.1f out=%s\n",
           dp, distance, (double)d.time, s.impact_t, s.impact_speed, s.max_deflection, s.max_t, common_result_fields(&c),
           sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall,
           1e9 * wall / ((double)sps_world_particle_count(w) * (double)(d.acoustic_steps > 0 ? d.acoustic_steps : 1)), c.out);
    sps_world_destroy(w);
    return 0;
}
