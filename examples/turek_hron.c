/* turek_hron.c - the fluid-structure benchmark of Turek and Hron (2006, in Fluid-Structure
   Interaction, Lecture Notes in Computational Science and Engineering 53, 371-385): an elastic
   flag clamped behind a rigid cylinder in a channel flow, driven into self-sustained oscillation
   by the vortices the cylinder sheds (open boundaries, viscous fluid, fluid-structure coupling:
   OPEN BOUNDARIES, FLUIDS and FLUID-STRUCTURE in sphsolid.h's manual).

   The channel is 2.5 m long (--length; the reference code's runs use 1.1 m) and H = 0.41 m high (analytic no-slip walls at y = 0 and y = H); a
   rigid cylinder of radius 0.05 m centred at (0.2, 0.2) (a wall body of particles) holds a flag
   0.35 m long and 0.02 m thick whose centre line is y = 0.2 (filled from the cylinder's centre,
   its part inside the cylinder clamped). An inflow buffer of 4 dp at x < 0 moves at the
   parabolic profile u(y) = 1.5 U 4 y (H - y) / H^2, ramped up as (1 - cos(pi t / 2)) / 2 over
   the first 2 s; an outflow buffer of 4 dp at the end holds the pressure at p_out = rho_f (2 U)^2
   (--p-out): the fluid's pressure is then positive everywhere (the flow past the cylinder's
   flanks and in the vortices' cores is below the outlet's by up to rho_f u^2 / 2, u up to
   about 3 U), as the fluid in tension pulls away from the channel's analytic walls (at 0,
   FSI3's fluid left both walls within 1 s). A uniform pressure does not load the flag. Fluid rho_f =
   1000, nu_f = 1e-3 m^2/s; the flag plane-strain elastic, nu_s = 0.4:
       --case fsi2: U = 1 m/s (Re = U 2r / nu_f = 100), rho_s = 10 000, mu_s = 0.5 MPa (E = 1.4 MPa)
       --case fsi3: U = 2 m/s (Re = 200),              rho_s =  1 000, mu_s = 2 MPa   (E = 5.6 MPa)
   The published answer (Turek and Hron's finest grid, their Table 12 and 14): the tip's transverse
   displacement oscillates with amplitude 80.6e-3 m at 2.0 Hz (FSI2), 34.4e-3 m at 5.3 Hz (FSI3);
   its mean is 1.2e-3 and 1.5e-3 m. The example tracks the particle at the middle of the flag's
   free end and, over the last --window seconds, prints the amplitude (half of max - min of y)
   and the frequency (from the upward crossings of the mean) next to theirs.

   The flag is Turek and Hron's Saint Venant-Kirchhoff solid in --solver tl; the default is the
   updated-Lagrangian linear elastic body (ENO-A, each particle's increments turned with its own
   rotation: zones refuse the pair rotation, which holds particle ids, and the body's mean
   rotation is not the tip's), the same law at the strains of the benchmark (below 2 %).
   The fluid takes the transport-velocity correction (--transport tvf, the default here) against
   the clustering of the wake.

   Build: make examples        Run: ./build/turek_hron --case fsi3 --length 1.1 --tend 10 --window 4
   Expect (dp 0.01, two particles across the flag): FSI3 37.3 mm at 4.80 Hz (+8 %, -9 %); FSI2
   (--length 1.1 --tend 12) flutters from 3 s to 104-124 mm at 1.70 Hz (+29-54 %, -15 %: the flag
   two particles thick bends about 40 % too softly, and its rotations swing 30 degrees; past 18
   s it strikes the wall), bench/VALIDATION.md, "Turek-Hron". CSV with the tip's displacement
   per row, VTK snapshots, a picture coloured by speed.
   Smoke: turek_hron --res 1 --tend 0.01 */
#include "common.h"

#define CHANNEL_HEIGHT 0.41
#define CYLINDER_X 0.2
#define CYLINDER_Y 0.2
#define CYLINDER_R 0.05
#define FLAG_END 0.6 /* x of the flag's free end */
#define FLAG_THICK 0.02
#define RHO_FLUID 1000.0
#define NU_FLUID 1e-3
#define RAMP_TIME 2.0
#define BUFFER_DP 4 /* buffer depth in dp: at least the kernel support 2h = 2.6 dp */

typedef struct {
    const char* name;
    double u_mean, rho_s, mu_s;
    double amplitude, frequency, mean; /* Turek and Hron 2006, the tip's uy */
} th_case;

static const th_case th_cases[2] = {
    {"fsi2", 1.0, 10000.0, 0.5e6, 80.6e-3, 2.0, 1.23e-3},
    {"fsi3", 2.0, 1000.0, 2.0e6, 34.38e-3, 5.3, 1.48e-3},
};

/* The inflow: the parabola of mean speed U, ramped up smoothly over RAMP_TIME. */
static void inflow_velocity(const sps_real x[3], sps_real t, void* user, sps_real v[3]) {
    const th_case* c = (const th_case*)user;
    const double ramp = t < RAMP_TIME ? 0.5 * (1 - cos(PI * t / RAMP_TIME)) : 1;
    v[0] = (sps_real)(ramp * 1.5 * c->u_mean * 4 * x[1] * (CHANNEL_HEIGHT - x[1]) / (CHANNEL_HEIGHT * CHANNEL_HEIGHT));
    v[1] = v[2] = 0;
}

/* The fluid's initial pressure: the outlet's, so that it starts at rest in equilibrium with it. */
static sps_real uniform_pressure(const sps_real x[3], void* user) {
    (void)x;
    return (sps_real)*(const double*)user;
}

/* The shapes, as signed distances (negative inside). */
static double cylinder_distance(const sps_real x[3]) { return hypot(x[0] - CYLINDER_X, x[1] - CYLINDER_Y) - CYLINDER_R; }
static double flag_distance(const sps_real x[3]) { /* the rectangle from the cylinder's centre to the free end */
    const double dx = fmax(CYLINDER_X - x[0], x[0] - FLAG_END), dy = fabs(x[1] - CYLINDER_Y) - FLAG_THICK / 2;
    return dx > 0 && dy > 0 ? hypot(dx, dy) : fmax(dx, dy);
}
static sps_real cylinder_sdf(const sps_real x[3], void* user) { /* the cylinder without the flag's root */
    (void)user;
    return (sps_real)fmax(cylinder_distance(x), -flag_distance(x));
}
static sps_real fluid_sdf(const sps_real x[3], void* user) { /* the channel without the cylinder and the flag */
    (void)user;
    return (sps_real)fmax(-cylinder_distance(x), -flag_distance(x));
}

typedef struct {
    output_plan output;
    double t_end, window, tip0[2];
    int tip, samples, capacity;
    double *t, *y; /* the tip's history over the window */
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    sps_particle_state tip;
    char extra[96];
    const double t = sps_world_time(w);
    sps_world_particle(w, s->tip, &tip);
    snprintf(extra, sizeof extra, ",%.6e,%.6e,%d", tip.position[0] - s->tip0[0], tip.position[1] - s->tip0[1], sps_world_particle_count(w));
    if (output_tick(w, &s->output, extra, &d) && t >= s->t_end - s->window - 1e-12 && s->samples < s->capacity) {
        s->t[s->samples] = t;
        s->y[s->samples++] = tip.position[1] - s->tip0[1];
    }
    return 0;
}

/* Amplitude (half of max - min), mean and frequency (upward crossings of the mean: their count
   less one over the time between the first and the last) of the samples y(t). */
static void oscillation(const double* t, const double* y, int n, double* amplitude, double* mean, double* frequency) {
    double lo = 1e30, hi = -1e30, sum = 0, first = 0, last = 0;
    int i, crossings = 0;
    for (i = 0; i < n; ++i) {
        lo = fmin(lo, y[i]);
        hi = fmax(hi, y[i]);
        sum += y[i];
    }
    *amplitude = n ? (hi - lo) / 2 : 0;
    *mean = n ? sum / n : 0;
    for (i = 1; i < n; ++i)
        if (y[i - 1] < *mean && y[i] >= *mean) {
            const double tc = t[i - 1] + (t[i] - t[i - 1]) * (*mean - y[i - 1]) / (y[i] - y[i - 1]);
            if (crossings++ == 0) first = tc;
            last = tc;
        }
    *frequency = crossings > 1 ? (crossings - 1) / (last - first) : 0;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_ENO_A, .rotation = SPS_ROTATION_PER_PARTICLE, .cfl = 0.4, .t_end = 12.0, .vtk_every = 0.5, .csv_every = 0.005, .E = 0, .nu = 0.4, .rho0 = 0, /* 0: the case's */
                        .out = "out/turek_hron", .transport = 1, PNG_DEFAULTS};
    int res = 2, which = 0, solver = 0, dissipation = SPS_FLUID_DISSIPATION_DENSITY, inflow, outflow;
    double c0_factor = 10, window = 0, length = 2.5, p_out = -1, amplitude, mean, frequency, dp, wall;
    const char* case_choices = "fsi2|fsi3";
    opt_spec opts[] = {
        {"res", OPT_INT, &res, "particles across the flag's thickness (0.02 m / dp)", 1, 20, NULL},
        {"case", OPT_CHOICE, &which, "Turek and Hron's setting: fsi2 (Re 100, heavy flag) or fsi3 (Re 200, stiff light flag)", 0, 0, case_choices},
        {"solver", OPT_CHOICE, &solver, "the flag: updated-Lagrangian linear elastic (ul) or total-Lagrangian Saint Venant-Kirchhoff (tl)", 0, 0, "ul|tl"},
        {"length", OPT_REAL, &length, "the channel's length [m] (Turek and Hron: 2.5)", 1, 10, NULL},
        {"c0-factor", OPT_REAL, &c0_factor, "the fluid's sound speed / U", 2, 1000, NULL},
        {"dissipation", OPT_CHOICE, &dissipation, "the fluid's numerical dissipation (material.fluid.dissipation): the Riemann solver's, its density diffusion only, none", 0, 0,
         "riemann|density|none"},
        {"p-out", OPT_REAL, &p_out, "the outlet pressure [Pa], < 0: the default rho_f (2 U)^2", -1, 1e6, NULL},
        {"window", OPT_REAL, &window, "the last seconds over which amplitude and frequency are measured, 0: the last third", 0, 100, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def fluid_def = sps_default_body_def(), flag_def = sps_default_body_def(), cylinder_def = sps_default_body_def();
    sps_zone_def in = sps_default_zone_def(), out = sps_default_zone_def();
    const sps_real floor_point[3] = {0, 0, 0}, up[3] = {0, 1, 0}, roof_point[3] = {0, CHANNEL_HEIGHT, 0}, down[3] = {0, -1, 0};
    sps_world* w;
    sps_body fluid, flag, cylinder;
    sps_diagnostics d;
    sps_particle_state tip;
    run_state s;
    const th_case* tc;
    int lattice, flag_count, n;

    ex_options(argc, argv, "Turek and Hron's FSI benchmark: an elastic flag behind a cylinder in a channel flow", opts, &c, &wd, NULL);
    tc = &th_cases[which];
    if (c.rho0 == 0) c.rho0 = tc->rho_s;
    if (c.E == 0) c.E = 2 * tc->mu_s * (1 + c.nu); /* E = 2 mu (1 + nu) */
    dp = FLAG_THICK / res;
    if (p_out < 0) p_out = RHO_FLUID * 4 * tc->u_mean * tc->u_mean; /* above the suction of the cylinder's flanks and the vortices */
    apply_common(&c, &wd, &flag_def); /* the case's density and modulus are the defaults */
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    flag_def.name = "flag";
    if (solver == 1) {
        flag_def.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
        flag_def.material.kind = SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF;
    }
    cylinder_def.name = "cylinder";
    cylinder_def.material.kind = SPS_MATERIAL_RIGID;
    fluid_def.name = "fluid";
    fluid_def.material.kind = SPS_MATERIAL_FLUID;
    fluid_def.material.density = RHO_FLUID;
    fluid_def.material.fluid.sound_speed = (sps_real)(c0_factor * tc->u_mean);
    fluid_def.material.viscosity = (sps_real)(NU_FLUID * RHO_FLUID);
    fluid_def.material.fluid.dissipation = (sps_fluid_dissipation)dissipation;
    fluid_def.transport = flag_def.transport; /* the common --transport is for the fluid */
    flag_def.transport = SPS_TRANSPORT_NONE;
    sps_world_create(&wd, &w);
    { /* the solids first: their particle ids then stay put while the zones renumber the fluid's */
        const sps_real lo[3] = {(sps_real)(CYLINDER_X - CYLINDER_R - dp), (sps_real)(CYLINDER_Y - CYLINDER_R - dp), 0};
        const sps_real hi[3] = {(sps_real)(CYLINDER_X + CYLINDER_R + dp), (sps_real)(CYLINDER_Y + CYLINDER_R + dp), 0};
        const sps_real flag_lo[3] = {CYLINDER_X, (sps_real)(CYLINDER_Y - FLAG_THICK / 2), 0}, flag_hi[3] = {FLAG_END, (sps_real)(CYLINDER_Y + FLAG_THICK / 2), 0};
        const sps_real held_lo[3] = {0, 0, 0}, held_hi[3] = {(sps_real)(CYLINDER_X + sqrt(CYLINDER_R * CYLINDER_R - FLAG_THICK * FLAG_THICK / 4)), 1, 0};
        const sps_real tip_at[3] = {(sps_real)(FLAG_END - dp / 2), CYLINDER_Y, 0};
        sps_world_add_body(w, &cylinder_def, &cylinder);
        sps_body_add_sdf(w, cylinder, lo, hi, cylinder_sdf, NULL, NULL);
        ex_unset_unread(&flag_def);
        sps_world_add_body(w, &flag_def, &flag);
        sps_body_add_box(w, flag, flag_lo, flag_hi, &flag_count);
        sps_body_constrain_box(w, flag, held_lo, held_hi, SPS_AXIS_ALL, NULL, NULL); /* the root, inside the cylinder */
        sps_world_set_contact(w, cylinder, flag, 0); /* joined at the root, not held apart */
        s.tip = sps_world_nearest_particle(w, flag, tip_at);
        sps_world_particle(w, s.tip, &tip);
        s.tip0[0] = tip.position[0];
        s.tip0[1] = tip.position[1];
    }
    {
        const sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)length, CHANNEL_HEIGHT, 0};
        ex_unset_unread(&fluid_def);
        sps_world_add_body(w, &fluid_def, &fluid);
        sps_body_add_sdf(w, fluid, lo, hi, fluid_sdf, NULL, NULL);
        sps_body_set_pressure(w, fluid, uniform_pressure, &p_out);
    }
    sps_world_add_wall(w, floor_point, up, SPS_WALL_NO_SLIP);
    sps_world_add_wall(w, roof_point, down, SPS_WALL_NO_SLIP);
    in.kind = SPS_ZONE_INFLOW; /* x in [-4 dp, 0): its lattice joins the channel's */
    in.lo[0] = (sps_real)(-BUFFER_DP * dp); in.hi[0] = 0; in.hi[1] = CHANNEL_HEIGHT;
    in.velocity_fn = inflow_velocity;
    in.velocity_user = (void*)tc;
    sps_body_add_zone(w, fluid, &in, &inflow);
    out.kind = SPS_ZONE_OUTFLOW; /* the channel's last 4 dp, at p_out */
    out.pressure = (sps_real)p_out;
    out.lo[0] = (sps_real)(length - BUFFER_DP * dp); out.hi[0] = (sps_real)length; out.hi[1] = CHANNEL_HEIGHT;
    sps_body_add_zone(w, fluid, &out, &outflow);
    lattice = sps_world_particle_count(w);
    sps_world_reserve(w, lattice + lattice / 4); /* the count varies by a few %: no allocation in a step */

    memset(&s.output, 0, sizeof s.output);
    s.t_end = c.t_end;
    s.window = window > 0 ? fmin(window, c.t_end) : c.t_end / 3;
    s.samples = 0;
    s.capacity = (int)(s.window / c.csv_every) + 16;
    s.t = (double*)malloc(sizeof(double) * (size_t)s.capacity);
    s.y = (double*)malloc(sizeof(double) * (size_t)s.capacity);
    if (!s.t || !s.y) { fprintf(stderr, "turek_hron: out of memory\n"); return 1; }
    output_open(&s.output, &c, "turek_hron", "velocity", ",tip_dx,tip_dy,particles");
    printf("turek_hron: %s, dp = %g m (%d across the flag, H/dp = %.0f), %d particles (%d in the flag), Re = %g, U = %g m/s, c0 = %g m/s, p_out = %g Pa, "
           "flag %s E = %g Pa nu = %g rho = %g\n", tc->name, dp, res, CHANNEL_HEIGHT / dp, lattice, flag_count, tc->u_mean * 2 * CYLINDER_R / NU_FLUID,
           tc->u_mean, c0_factor * tc->u_mean, p_out, solver ? "TL Saint Venant-Kirchhoff" : "UL linear elastic", c.E, c.nu, c.rho0);
    on_step(w, &s);
    for (n = 1; n <= 8; ++n) {
        const double t = c.t_end * n / 8;
        sps_particle_state now;
        ex_check_step(w, sps_world_advance(w, (sps_real)t, on_step, &s), &s.output);
        sps_world_particle(w, s.tip, &now);
        printf("  t = %7.3f s   tip dx = %+9.3e  dy = %+9.3e m   particles %d\n", t, now.position[0] - s.tip0[0], now.position[1] - s.tip0[1],
               sps_world_particle_count(w));
    }
    wall = output_close(w, &s.output);
    oscillation(s.t, s.y, s.samples, &amplitude, &mean, &frequency);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    printf("the tip's transverse displacement over the last %.3g s: amplitude %.4e m (Turek-Hron %.4e), frequency %.3f Hz (%.2f), mean %.3e m (%.2e)\n",
           s.window, amplitude, tc->amplitude, frequency, tc->frequency, mean, tc->mean);
    printf("RESULT case=turek_hron setting=%s res=%d dp=%g length=%g solver=%s dissipation=%s c0_factor=%g p_out=%g window=%g amplitude=%.5e amplitude_paper=%.5e amplitude_dev=%+.2f%% "
           "frequency=%.4f frequency_paper=%.2f frequency_dev=%+.2f%% mean=%.4e %s particles=%d steps=%ld wall_s=%.2f out=%s\n",
           tc->name, res, dp, length, solver ? "tl" : "ul", dissipation_name(dissipation), c0_factor, p_out, s.window, amplitude, tc->amplitude, 100 * (amplitude / tc->amplitude - 1), frequency,
           tc->frequency, 100 * (frequency / tc->frequency - 1), mean, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, wall,
           c.out);
    free(s.t);
    free(s.y);
    sps_world_destroy(w);
    return 0;
}
