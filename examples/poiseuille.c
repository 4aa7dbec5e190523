/* poiseuille.c - plane Poiseuille flow: a viscous fluid between two no-slip walls, periodic along
   the channel, driven from rest by a body force F along it (Morris, Fox and Zhu 1997, JCP 136,
   section 4.1, here at Re = u_max H / nu = 1). PERIODIC and FLUIDS in sphsolid.h's manual.

   The channel is H = 0.01 m wide (walls y = 0 and y = H, analytic, no slip: mirror particles
   with the velocity reversed) and 16 dp long, periodic in x; water-like rho0 = 1000, mu = 0.1
   Pa s (nu = 1e-4 m^2/s), F = 8 nu u_max / H^2 for u_max = 0.01 m/s, c0 = 10 u_max. The start-up
   has the series solution (Morris et al. eq. 22)
       u(y, t) = F/(2 nu) y (H - y) - sum_n 4 F H^2 / (nu pi^3 (2n+1)^3) sin((2n+1) pi y / H)
                 exp(-(2n+1)^2 pi^2 nu t / H^2),
   which the example compares with at every CSV row: the L2 error is the RMS over the particles
   of u - u(y, t), as a fraction of u_max. The steady state is reached to 1e-4 at t = 1 s.

   Build: make examples        Run: ./build/poiseuille --res 40
   Expect: l2_error 0.23 % at --res 20 (H/dp), 0.06 % at --res 40 (second order); the transient's
   largest error below 1 %; CSV (with the error per row), the final profile (profile.csv), VTK
   snapshots and a picture coloured by speed.
   Smoke: poiseuille --res 10 --tend 0.02 */
#include "common.h"

#define H 0.01
#define U_MAX 0.01
#define RE 1.0
#define NU (U_MAX * H / RE)
#define FORCE (8 * NU * U_MAX / (H * H))
#define LENGTH_DP 16 /* the channel's periodic length in dp: at least 6 h = 7.8 dp */

/* The start-up solution u(y, t) (Morris et al. 1997, eq. 22), summed until the terms are below
   1e-12 u_max. */
static double poiseuille_u(double y, double t) {
    double u = FORCE / (2 * NU) * y * (H - y);
    int n;
    for (n = 0; n < 10000; ++n) {
        const double k = 2 * n + 1, term = 4 * FORCE * H * H / (NU * PI * PI * PI * k * k * k) * exp(-k * k * PI * PI * NU * t / (H * H));
        u -= term * sin(k * PI * y / H);
        if (term < 1e-12 * U_MAX) break;
    }
    return u;
}

/* The RMS of u_x - u(y, t) over the particles, a fraction of u_max. */
static double l2_error(const sps_world* w) {
    const sps_real *y = sps_world_field(w, SPS_FIELD_POSITION_Y), *u = sps_world_field(w, SPS_FIELD_VELOCITY_X);
    const double t = sps_world_time(w);
    double sum = 0;
    int i, n = sps_world_particle_count(w);
    for (i = 0; i < n; ++i) sum += pow(u[i] - poiseuille_u(y[i], t), 2);
    return sqrt(sum / n) / U_MAX;
}

typedef struct {
    output_plan output;
    double worst, worst_t;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[96];
    const double e = l2_error(w);
    if (e > s->worst) { s->worst = e; s->worst_t = sps_world_time(w); }
    snprintf(extra, sizeof extra, ",%.6e,%.9g", e, poiseuille_u(H / 2, sps_world_time(w)));
    output_tick(w, &s->output, extra, &d);
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.cfl = 0.4, .t_end = 1.0, .vtk_every = 0.25, .csv_every = 0.01, .E = 1e6, .nu = 0.3, .rho0 = 1000,
                        .out = "out/poiseuille", .transport = 0, PNG_DEFAULTS};
    int res = 20;
    double c0_factor = 10;
    opt_spec opts[] = {
        {"res", OPT_INT, &res, "particles across the channel, H/dp", 4, 400, NULL},
        {"c0-factor", OPT_REAL, &c0_factor, "sound speed / u_max", 2, 1000, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real floor_point[3] = {0, 0, 0}, up[3] = {0, 1, 0}, roof_point[3] = {0, H, 0}, down[3] = {0, -1, 0};
    sps_world* w;
    sps_body fluid;
    sps_diagnostics d;
    run_state s;
    FILE* profile;
    double dp, e, centre = 0, wall;
    int i, n, near = 0;

    ex_options(argc, argv, "plane Poiseuille flow in a periodic channel (Morris et al. 1997)", opts, &c, &wd, &bd);
    dp = H / res;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.gravity[0] = (sps_real)FORCE; /* the driving body force */
    wd.periodic[0] = (sps_real)(LENGTH_DP * dp);
    bd.name = "fluid";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = (sps_real)(c0_factor * U_MAX);
    bd.material.viscosity = (sps_real)(NU * c.rho0);
    sps_world_create(&wd, &w);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &fluid);
    {
        const sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)(LENGTH_DP * dp), (sps_real)H, 0};
        sps_body_add_box(w, fluid, lo, hi, NULL);
    }
    sps_world_add_wall(w, floor_point, up, SPS_WALL_NO_SLIP);
    sps_world_add_wall(w, roof_point, down, SPS_WALL_NO_SLIP);

    memset(&s, 0, sizeof s);
    output_open(&s.output, &c, "poiseuille", "velocity", ",l2_error,u_centre_exact");
    printf("poiseuille: H/dp = %d, %d particles, Re = %g, u_max = %g m/s, nu = %g m^2/s, F = %g m/s^2, c0 = %g m/s\n", res,
           sps_world_particle_count(w), RE, U_MAX, NU, FORCE, c0_factor * U_MAX);
    printf("     t [s]   u_centre / u_max   exact     L2 error / u_max\n");
    on_step(w, &s);
    for (i = 1; i <= 5; ++i) {
        const double t = c.t_end * i / 5;
        const sps_real *y, *u;
        ex_check_step(w, sps_world_advance(w, (sps_real)t, on_step, &s), &s.output);
        y = sps_world_field(w, SPS_FIELD_POSITION_Y);
        u = sps_world_field(w, SPS_FIELD_VELOCITY_X);
        centre = 0, near = 0;
        for (n = 0; n < sps_world_particle_count(w); ++n)
            if (fabs(y[n] - H / 2) < 0.6 * dp) { centre += u[n]; ++near; }
        printf("  %8.4f   %10.5f        %8.5f   %9.3e\n", t, near ? centre / near / U_MAX : 0, poiseuille_u(H / 2, t) / U_MAX, l2_error(w));
    }
    wall = output_close(w, &s.output);
    profile = open_out(c.out, "profile.csv"); /* the final profile, every particle: y, u, the series */
    fprintf(profile, "y,u,u_exact\n");
    {
        const sps_real *y = sps_world_field(w, SPS_FIELD_POSITION_Y), *u = sps_world_field(w, SPS_FIELD_VELOCITY_X);
        for (n = 0; n < sps_world_particle_count(w); ++n)
            fprintf(profile, "%.9g,%.9g,%.9g\n", (double)y[n], (double)u[n], poiseuille_u(y[n], sps_world_time(w)));
    }
    fclose(profile);
    e = l2_error(w);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    printf("RESULT case=poiseuille res=%d Re=%g c0_factor=%g t=%.4g l2_error=%.4e l2_error_pct=%.3f%% transient_max=%.4e transient_max_t=%.3g "
           "%s particles=%d steps=%ld wall_s=%.2f out=%s\n", res, RE, c0_factor, (double)sps_world_time(w), e, 100 * e, s.worst,
           s.worst_t, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
