/* taylor_green.c - the Taylor-Green vortex: a viscous fluid in a periodic unit box (both axes
   periodic; PERIODIC and FLUIDS in sphsolid.h's manual), the decaying array of vortices
       u = -U cos(2 pi x) sin(2 pi y) e^(-8 pi^2 t / Re),  v = U sin(2 pi x) cos(2 pi y) e^(...),
       p = -rho0 U^2 / 4 (cos 4 pi x + cos 4 pi y) e^(-16 pi^2 t / Re)
   (an exact solution of the Navier-Stokes equations), so that the kinetic energy decays as
   exp(-16 pi^2 t / Re). U = 1 m/s, L = 1 m, rho0 = 1000, nu = U L / Re, c0 = 10 U; the initial
   velocity and pressure are the solution's at t = 0. The decay error is the largest relative
   difference of E(t) / E(0) from exp(-16 pi^2 t / Re) over the CSV rows (every 0.02 s) up to
   --tend (2 s). Without a transport-velocity correction the particles cluster along the
   vortices' stretching directions (at --res 30 the run stops at t = 0.9 s, a particle with more
   neighbours than the capacity); --transport tvf (the default here) keeps them apart.

   Build: make examples        Run: ./build/taylor_green --res 60
   Expect (Re 100, TVF, h = 1.5 dp, material.fluid.dissipation none): decay_error 1.40 % at --res 30
   (1/dp), 0.95 % at --res 60, 0.80 % at --res 100; with --dissipation riemann (the library's
   default, whose momentum term is an artificial viscosity of the order of nu here) 28.4 % and
   9.4 %, with --dissipation density 5.3 % and 2.4 %, with --carry-velocity 1 2.1 % and 1.1 %
   (bench/VALIDATION.md, "Viscous flows without the Riemann solver's dissipation"); CSV with
   E/E0 and the exact decay per row, VTK snapshots, a picture coloured by speed.
   Smoke: taylor_green --res 20 --tend 0.02 */
#include "common.h"

#define U0 1.0

typedef struct {
    double rho0, re;
} tg_case;

static void tg_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = (sps_real)(-U0 * cos(2 * PI * x[0]) * sin(2 * PI * x[1]));
    v[1] = (sps_real)(U0 * sin(2 * PI * x[0]) * cos(2 * PI * x[1]));
    v[2] = 0;
}
static sps_real tg_pressure(const sps_real x[3], void* user) {
    const tg_case* c = (const tg_case*)user;
    return (sps_real)(-c->rho0 * U0 * U0 / 4 * (cos(4 * PI * x[0]) + cos(4 * PI * x[1])));
}

typedef struct {
    output_plan output;
    double re, e0, worst, worst_t;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[96] = "";
    const double t = sps_world_time(w), exact = exp(-16 * PI * PI * t / s->re);
    if (t >= s->output.next_csv - 1e-12) { /* a row is due: the energy against the closed form */
        sps_world_diagnostics(w, (sps_body){0}, &d);
        if (fabs(d.kinetic_energy / s->e0 / exact - 1) > s->worst) { s->worst = fabs(d.kinetic_energy / s->e0 / exact - 1); s->worst_t = t; }
        snprintf(extra, sizeof extra, ",%.9g,%.9g", d.kinetic_energy / s->e0, exact);
    }
    output_tick(w, &s->output, extra, &d);
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.cfl = 0.4, .t_end = 2.0, .vtk_every = 0.5, .csv_every = 0.02, .E = 1e6, .nu = 0.3, .rho0 = 1000,
                        .out = "out/taylor_green", .transport = 1, .h_over_dp = 1.5, PNG_DEFAULTS};
    int res = 50;
    double c0_factor = 10, alpha = 0;
    int dissipation = SPS_FLUID_DISSIPATION_NONE, carry_velocity = 0;
    tg_case tc;
    opt_spec opts[] = {
        {"res", OPT_INT, &res, "particles along the box's side, 1/dp", 10, 1000, NULL},
        {"re", OPT_REAL, &tc.re, "Reynolds number U L / nu", 1, 1e4, NULL},
        {"c0-factor", OPT_REAL, &c0_factor, "sound speed / U", 2, 1000, NULL},
        {"carry-velocity", OPT_INT, &carry_velocity, "1: the transport shift carries the velocity and sees the walls (transport_carries_velocity)", 0, 1, NULL},
        {"dissipation", OPT_CHOICE, &dissipation, "the fluid's numerical dissipation (material.fluid.dissipation): the Riemann solver's, its density diffusion only, none", 0, 0,
         "riemann|density|none"},
        {"tvf-alpha", OPT_REAL, &alpha, "transport_coefficient alpha of TVF, 0: the library's (0.2)", 0, 1, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0};
    sps_world* w;
    sps_body fluid;
    sps_diagnostics d;
    run_state s;
    double wall;
    int i;

    tc.re = 100;
    ex_options(argc, argv, "Taylor-Green vortex in a periodic box", opts, &c, &wd, &bd);
    tc.rho0 = c.rho0;
    wd.dim = 2;
    wd.dp = (sps_real)(1.0 / res);
    wd.periodic[0] = wd.periodic[1] = 1;
    bd.name = "fluid";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = (sps_real)(c0_factor * U0);
    bd.material.fluid.dissipation = (sps_fluid_dissipation)dissipation;
    bd.transport_carries_velocity = carry_velocity;
    bd.material.viscosity = (sps_real)(c.rho0 * U0 * 1.0 / tc.re);
    bd.transport_coefficient = (sps_real)alpha;
    sps_world_create(&wd, &w);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &fluid);
    sps_body_add_box(w, fluid, lo, hi, NULL);
    sps_body_set_velocity(w, fluid, tg_velocity, NULL);
    sps_body_set_pressure(w, fluid, tg_pressure, &tc);

    memset(&s, 0, sizeof s);
    s.re = tc.re;
    sps_world_diagnostics(w, (sps_body){0}, &d);
    s.e0 = d.kinetic_energy;
    output_open(&s.output, &c, "taylor_green", "velocity", ",energy_ratio,energy_ratio_exact");
    printf("taylor_green: 1/dp = %d, %d particles, Re = %g, c0 = %g m/s, h = %g dp, transport %s, dissipation %s\n", res,
           sps_world_particle_count(w), tc.re, c0_factor * U0, c.h_over_dp, c.transport == 0 ? "none" : c.transport == 1 ? "TVF" : "UTVF",
           dissipation_name(dissipation));
    printf("     t [s]    E / E0      exp(-16 pi^2 t / Re)   error\n");
    on_step(w, &s);
    for (i = 1; i <= 4; ++i) {
        const double t = c.t_end * i / 4, exact = exp(-16 * PI * PI * t / tc.re);
        ex_check_step(w, sps_world_advance(w, (sps_real)t, on_step, &s), &s.output);
        sps_world_diagnostics(w, (sps_body){0}, &d);
        printf("  %8.4f   %9.6f   %9.6f              %+.3f%%\n", t, d.kinetic_energy / s.e0, exact, 100 * (d.kinetic_energy / s.e0 / exact - 1));
    }
    wall = output_close(w, &s.output);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    printf("RESULT case=taylor_green res=%d Re=%g c0_factor=%g t=%.4g decay_error=%.4e decay_error_pct=%.3f%% worst_t=%.3g "
           "energy_ratio=%.6f exact=%.6f min_spacing=%.3f %s h_over_dp=%g dissipation=%s carry_velocity=%d particles=%d steps=%ld wall_s=%.2f out=%s\n", res, tc.re, c0_factor,
           (double)sps_world_time(w), s.worst, 100 * s.worst, s.worst_t, d.kinetic_energy / s.e0,
           exp(-16 * PI * PI * sps_world_time(w) / tc.re), s.output.min_spacing, common_result_fields(&c), c.h_over_dp,
           dissipation_name(dissipation), carry_velocity, sps_world_particle_count(w),
           d.acoustic_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
