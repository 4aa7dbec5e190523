/* channel_flow.c - a viscous fluid through a 2D channel between no-slip walls, fed by a parabolic
   inflow and drained at a fixed outlet pressure: open boundaries (OPEN BOUNDARIES in sphsolid.h's
   manual; the buffer zones of Lastiwka, Basa and Quinlan 2009).

   The channel is H = 0.01 m wide (walls y = 0 and y = H, analytic, no slip) and 3 H long; an
   inflow buffer of 4 dp at x < 0 moves at the plane Poiseuille profile u(y) = 4 U y (H - y) / H^2,
   U = 0.01 m/s, and creates the particles that leave it; an outflow buffer of 4 dp at the end
   holds the outlet pressure p_out and removes what leaves it. Water-like rho0 = 1000, mu = 0.1
   Pa s (Re = U H / nu = 1; --re sets nu), c0 = 30 U. The fluid starts at rest and develops into the Poiseuille
   flow of the inflow: the example compares, over the last third of the run, the flux through
   the cross-section at x = 2 H (sum of u m / rho0 over a slab 2 dp thick / its thickness) with the
   inflow's 2/3 U H, the profile there with the parabola (RMS of u - u(y) over the slab's
   particles, a fraction of U), and the particle count with the lattice count of the channel and
   its buffers.

   Build: make examples        Run: ./build/channel_flow --res 20
   Expect: flux within 1 % of the inflow's, the profile within about 2 % (L2), the count within
   a few % of the lattice's; CSV (with the flux and the count per row), the final profile
   (profile.csv), VTK snapshots and a picture coloured by speed.
   Smoke: channel_flow --res 8 --tend 0.05 */
#include "common.h"

#define H 0.01
#define U_MAX 0.01
static double g_re = 1.0; /* --re: U H / nu */
#define NU (U_MAX * H / g_re)
#define LENGTH (3 * H)
#define BUFFER_DP 4 /* buffer depth in dp: at least the kernel support 2h = 2.6 dp */

static double parabola(double y) { return 4 * U_MAX * y * (H - y) / (H * H); }
static void inflow_velocity(const sps_real x[3], sps_real t, void* user, sps_real v[3]) {
    (void)t; (void)user;
    v[0] = (sps_real)parabola(x[1]);
    v[1] = v[2] = 0;
}

typedef struct {
    output_plan output;
    double t_end, dp, rho0, flux_sum, l2_sum;
    int samples, n_lo, n_hi;
} run_state;

/* The flux through the slab |x - 2H| < dp per unit depth [m^2/s], as its mass flux over rho0
   (what the inflow creates: particles of mass rho0 dp^2; the fluid is denser downstream by its
   pressure over rho0 c0^2, about 2 %, and its volume flux smaller by as much), and the RMS of
   u - u(y) over its particles, a fraction of U. */
static void measure(const sps_world* w, double dp, double rho0, double* flux, double* l2) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real *u = sps_world_field(w, SPS_FIELD_VELOCITY_X), *mass = sps_world_field(w, SPS_FIELD_MASS);
    double q = 0, e = 0;
    int i, m = 0;
    for (i = 0; i < sps_world_particle_count(w); ++i)
        if (fabs(x[i] - 2 * H) < dp) {
            q += u[i] * mass[i] / rho0;
            e += pow(u[i] - parabola(y[i]), 2);
            ++m;
        }
    *flux = q / (2 * dp);
    *l2 = m ? sqrt(e / m) / U_MAX : 0;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[96];
    double q, e;
    const int n = sps_world_particle_count(w);
    measure(w, s->dp, s->rho0, &q, &e);
    snprintf(extra, sizeof extra, ",%.6e,%.6e,%d", q, e, n);
    if (output_tick(w, &s->output, extra, &d) && sps_world_time(w) >= s->t_end * 2 / 3) { /* the steady part: every CSV row */
        s->flux_sum += q;
        s->l2_sum += e;
        s->samples++;
        if (n < s->n_lo) s->n_lo = n;
        if (n > s->n_hi) s->n_hi = n;
    }
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.cfl = 0.4, .t_end = 10.0, .vtk_every = 1, .csv_every = 0.05, .E = 1e6, .nu = 0.3, .rho0 = 1000,
                        .out = "out/channel_flow", .transport = 0, PNG_DEFAULTS};
    int res = 20, inflow, outflow, lattice;
    double c0_factor = 30, p_out = 1.0;
    opt_spec opts[] = {
        {"res", OPT_INT, &res, "particles across the channel, H/dp", 4, 400, NULL},
        {"re", OPT_REAL, &g_re, "Reynolds number U H / nu (U the peak speed)", 0.01, 1000, NULL},
        {"c0-factor", OPT_REAL, &c0_factor, "sound speed / U", 2, 1000, NULL},
        {"p-out", OPT_REAL, &p_out, "outlet pressure [Pa]", -1e4, 1e4, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_zone_def in = sps_default_zone_def(), out = sps_default_zone_def();
    const sps_real floor_point[3] = {0, 0, 0}, up[3] = {0, 1, 0}, roof_point[3] = {0, H, 0}, down[3] = {0, -1, 0};
    sps_world* w;
    sps_body fluid;
    sps_diagnostics d;
    run_state s;
    FILE* profile;
    double dp, flux, l2, wall;
    long created, removed;
    int n;

    ex_options(argc, argv, "a 2D channel with a parabolic inflow and an outlet at fixed pressure (open boundaries)", opts, &c, &wd, &bd);
    dp = H / res;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    bd.name = "fluid";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = (sps_real)(c0_factor * U_MAX);
    bd.material.viscosity = (sps_real)(NU * c.rho0);
    sps_world_create(&wd, &w);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &fluid);
    {
        const sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)LENGTH, (sps_real)H, 0};
        sps_body_add_box(w, fluid, lo, hi, NULL);
    }
    sps_world_add_wall(w, floor_point, up, SPS_WALL_NO_SLIP);
    sps_world_add_wall(w, roof_point, down, SPS_WALL_NO_SLIP);
    in.kind = SPS_ZONE_INFLOW; /* x in [-4 dp, 0): its lattice joins the channel's */
    in.lo[0] = (sps_real)(-BUFFER_DP * dp); in.hi[0] = 0; in.hi[1] = (sps_real)H;
    in.velocity_fn = inflow_velocity;
    sps_body_add_zone(w, fluid, &in, &inflow);
    out.kind = SPS_ZONE_OUTFLOW; /* the channel's last 4 dp */
    out.lo[0] = (sps_real)(LENGTH - BUFFER_DP * dp); out.hi[0] = (sps_real)LENGTH; out.hi[1] = (sps_real)H;
    out.pressure = (sps_real)p_out;
    sps_body_add_zone(w, fluid, &out, &outflow);
    lattice = sps_world_particle_count(w);
    sps_world_reserve(w, 2 * lattice); /* the count varies by a few %: no allocation in a step */

    memset(&s, 0, sizeof s);
    s.t_end = c.t_end;
    s.dp = dp;
    s.rho0 = c.rho0;
    s.n_lo = 1 << 30;
    output_open(&s.output, &c, "channel_flow", "velocity", ",flux,l2_error,particles");
    printf("channel_flow: H/dp = %d, %d particles (lattice of the channel and its buffers), Re = %g, U = %g m/s, nu = %g m^2/s, "
           "c0 = %g m/s, p_out = %g Pa\n", res, lattice, g_re, U_MAX, NU, c0_factor * U_MAX, p_out);
    printf("     t [s]   flux / inflow's   L2 error / U   particles\n");
    on_step(w, &s);
    for (n = 1; n <= 5; ++n) {
        const double t = c.t_end * n / 5;
        ex_check_step(w, sps_world_advance(w, (sps_real)t, on_step, &s), &s.output);
        measure(w, dp, c.rho0, &flux, &l2);
        printf("  %8.3f   %10.4f        %9.3e     %6d\n", t, flux / (2.0 / 3 * U_MAX * H), l2, sps_world_particle_count(w));
    }
    wall = output_close(w, &s.output);
    profile = open_out(c.out, "profile.csv"); /* the final profile across x = 2 H: y, u, the parabola */
    fprintf(profile, "y,u,u_exact\n");
    {
        const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
        const sps_real* u = sps_world_field(w, SPS_FIELD_VELOCITY_X);
        for (n = 0; n < sps_world_particle_count(w); ++n)
            if (fabs(x[n] - 2 * H) < dp) fprintf(profile, "%.9g,%.9g,%.9g\n", (double)y[n], (double)u[n], parabola(y[n]));
    }
    fclose(profile);
    if (s.samples == 0) measure(w, dp, c.rho0, &s.flux_sum, &s.l2_sum), s.samples = 1, s.n_lo = s.n_hi = sps_world_particle_count(w);
    flux = s.flux_sum / s.samples;
    l2 = s.l2_sum / s.samples;
    sps_world_zone_counts(w, inflow, &created, NULL);
    sps_world_zone_counts(w, outflow, NULL, &removed);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    printf("RESULT case=channel_flow res=%d Re=%g c0_factor=%g p_out=%g t=%.4g flux=%.6e flux_inflow=%.6e flux_ratio=%.4f l2_error=%.4e "
           "l2_error_pct=%.2f%% count_min=%d count_max=%d lattice=%d created=%ld removed=%ld %s particles=%d steps=%ld wall_s=%.2f out=%s\n",
           res, g_re, c0_factor, p_out, (double)sps_world_time(w), flux, 2.0 / 3 * U_MAX * H, flux / (2.0 / 3 * U_MAX * H), l2, 100 * l2,
           s.n_lo, s.n_hi, lattice, created, removed, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
