/* taylor_square.c - square Taylor bar, benchmark B2 (ANG 5.2.2); built with -DTAYLOR_ROUND as
   build/taylor_round, the round Taylor bar, benchmark B1 (ANG 5.2.1).

   A J2 elastic-plastic bar hits a rigid frictionless wall (the analytic wall z = 0,
   SPS_WALL_FREE_SLIP). The wall repels the particles within 2h of it (chapter >>contact), and
   a lattice laid on the wall would start inside that layer with contact energy K V sigma^2
   (at L/dp = 8 it came out at ~100 J, 40 % of the impact's kinetic energy, and showed up as a
   rebound of the impact face): so the bar starts with its lowest
   particles 2h above the wall, and the impact time t = 0 is when its face (half a spacing
   below them) would reach the wall plane, (2h - dp/2)/v0 later. Times below are from then.
   B2: height 0.03, square section 0.006 x 0.006 centred on the z axis, v0 = (0, 0, -227);
   rho0 8930, E 1.17e11, nu 0.35, sigma_Y 4e8, hardening kappa 1e8 (Haider et al.).
   --res = L/dp (paper: 8, 12, 16, 20). We report x of the observation point s = (0.003, 0, 0)
   (mid-side of the impact face) at the end, against ANG Table 4 (5.21, 5.91, 6.46, 6.86 mm) and
   Haider et al.'s 6.93 mm: observed as the paper's observer does, by kernel interpolation of
   the displacement at s (sps_world_add_observer: the Shepard average of the neighbours, which
   lie inside the bar, so it reads the displacement of a point about h/2 inward of the edge),
   and as the outermost particle of the impact-face layer near y = 0 (x of its centre, a lower
   bound of the surface that lies half a deformed spacing further out).
   B1: radius R = 3.91e-3, length 2.346e-2, v0 = (0, 0, -373); rho0 2700, E 7.82e10, nu 0.3,
   sigma_Y 2.9e8, perfect plasticity. --res = R/dp (paper: 12, and coarser). We report the final
   length (highest particle) and the radius of the impact face (outermost particle), each
   offset by its value at t = 0 so that both start at the bar's dimensions, and the kinetic
   energy at t = 0, its minimum (and when) and its value at 59 us against the reference code's
   209.58 J, 0.0256 J at about 32 us and 0.0303 J at 59 us (BENCHMARKS.md B1).
   Both: the energy account kinetic + strain + contact + plastic work against the initial kinetic energy
   (its largest deviation over the run), the largest equivalent plastic strain, the hourglass
   indicator, particles, steps and wall time. VTK files carry von Mises and plastic strain.
   Shear: GNO-A by default (ANG's choice for plastic bodies, with the reference code's penalty
   scaled by the radial-return factors); OG and GNO beside it; ENO and ENO-A are refused for a
   J2 body (the library says why); --material elastic runs the same scene elastic (ENO-A allowed),
   to compare the formulations' costs.

   Build: make examples        Run: ./build/taylor_square --res 8 --threads 2
   Expect (B2, --res 8): x_s about 5.5-6 mm, the account within 2 % of the initial energy.
   Smoke: taylor_square --res 4 --tend 2e-6
   Smoke: taylor_round --res 3 --tend 2e-6 */
#include "common.h"

#ifdef TAYLOR_ROUND
#define TB_NAME "taylor_round"
#define TB_ABOUT "round Taylor bar on a rigid frictionless wall (benchmark B1, ANG 5.2.1)"
#define TB_RADIUS 3.91e-3
#define TB_LENGTH 2.346e-2
#define TB_SPEED 373.0
#define TB_RHO0 2700.0
#define TB_E 7.82e10
#define TB_NU 0.3
#define TB_YIELD 2.9e8
#define TB_HARDENING 0.0
#define TB_RES 6
#else
#define TB_NAME "taylor_square"
#define TB_ABOUT "square Taylor bar on a rigid frictionless wall (benchmark B2, ANG 5.2.2)"
#define TB_HALF_WIDTH 0.003
#define TB_LENGTH 0.03
#define TB_SPEED 227.0
#define TB_RHO0 8930.0
#define TB_E 1.17e11
#define TB_NU 0.35
#define TB_YIELD 4e8
#define TB_HARDENING 1e8
#define TB_RES 8
#endif

#ifdef TAYLOR_ROUND
static sps_real cylinder_sdf(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(sqrt((double)x[0] * x[0] + (double)x[1] * x[1]) - TB_RADIUS);
}
#endif

static void impact_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)x; (void)user;
    v[0] = v[1] = 0;
    v[2] = (sps_real)-TB_SPEED;
}

/* The bar's extent from the particle positions: the highest z, the largest distance from the
   axis (round: radius; square: |x|) and x of the outermost particle of the impact-face layer
   near the plane y = 0 (reference z below dp, |y| below dp). */
typedef struct { double top, bottom, side, face_x; } bar_extent;
static bar_extent measure_bar(const sps_world* w, double dp, double gap) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *z = sps_world_field(w, SPS_FIELD_POSITION_Z);
    const sps_real* y0 = sps_world_field(w, SPS_FIELD_REFERENCE_Y);
    const sps_real* z0 = sps_world_field(w, SPS_FIELD_REFERENCE_Z);
    bar_extent e = {-1e30, 1e30, 0, -1e30};
    int i;
    for (i = 0; i < sps_world_particle_count(w); ++i) {
#ifdef TAYLOR_ROUND
        const sps_real* y = sps_world_field(w, SPS_FIELD_POSITION_Y);
        const double side = sqrt((double)x[i] * x[i] + (double)y[i] * y[i]);
#else
        const double side = fabs((double)x[i]);
#endif
        if (z[i] > e.top) e.top = z[i];
        if (z[i] < e.bottom) e.bottom = z[i];
        if (side > e.side) e.side = side;
        if (z0[i] < gap + dp && fabs((double)y0[i]) < dp && x[i] > e.face_x) e.face_x = x[i];
    }
    return e;
}

typedef struct {
    sps_observer point; /* B2's observation point s */
    output_plan output;
    double t_contact, t_end, e0, account_dev_max, ke_min, t_ke_min, ke_59us;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    sps_real u[3] = {0, 0, 0};
    char extra[64];
    const double t = sps_world_time(w) - s->t_contact; /* from the impact */
    if (s->point.id) sps_observer_read(w, s->point, u, NULL);
    snprintf(extra, sizeof extra, ",%.9g,%.9g", t, 0.003 + (double)u[0]);
    if (output_tick(w, &s->output, extra, &d)) {
        const double account = d.kinetic_energy + d.strain_energy + d.contact_energy + d.plastic_work;
        if (s->e0 == 0) s->e0 = d.kinetic_energy;
        if (fabs(account - s->e0) > s->account_dev_max) s->account_dev_max = fabs(account - s->e0);
        if (t >= 0 && d.kinetic_energy < s->ke_min) { s->ke_min = d.kinetic_energy; s->t_ke_min = t; }
        if (s->ke_59us < 0 && t >= 59e-6 - 1e-12) s->ke_59us = d.kinetic_energy;
    }
    return 0;
}

int main(int argc, char** argv) {
    int res = TB_RES, material = 0; /* j2|elastic */
    double yield = TB_YIELD, hardening = TB_HARDENING;
    common_options c = {.shear = SPS_SHEAR_GNO_A, .cfl = 0.4, .t_end = 6e-5, .vtk_every = 1e-5, .csv_every = 5e-7,
                        .E = TB_E, .nu = TB_NU, .rho0 = TB_RHO0, .out = "out/" TB_NAME, .jitter = 0, .seed = 1, .contact_rest = SPS_CONTACT_REST_KERNEL /* the papers' contact law */, PNG_DEFAULTS};
    opt_spec opts[] = {
#ifdef TAYLOR_ROUND
        {"res", OPT_INT, &res, "resolution R/dp (paper: 12; also 6 and 9)", 2, 60, NULL},
#else
        {"res", OPT_INT, &res, "resolution L/dp of the square section (paper: 8, 12, 16, 20)", 2, 80, NULL},
#endif
        {"yield", OPT_REAL, &yield, "yield stress sigma_Y [Pa]", 1, 1e12, NULL},
        {"hardening", OPT_REAL, &hardening, "linear hardening modulus kappa [Pa]", 0, 1e13, NULL},
        {"material", OPT_CHOICE, &material, "the bar's material (elastic: the same scene for ENO-A, e.g. to compare costs)", 0, 0, "j2|elastic"},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body bar;
    run_state s;
    sps_diagnostics d;
    bar_extent start, end;
    double dp, wall, gap;
    const sps_real wall_point[3] = {0, 0, 0}, up[3] = {0, 0, 1};
    int added;

    c.png_view = RENDER_VIEW_XZ;
    ex_options(argc, argv, TB_ABOUT, opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
#ifdef TAYLOR_ROUND
    dp = TB_RADIUS / res;
#else
    dp = 2 * TB_HALF_WIDTH / res;
#endif
    wd.dim = 3;
    wd.dp = (sps_real)dp;
    gap = (2 * (double)wd.h_over_dp - 0.5) * dp; /* from the wall plane to the impact face: lowest particles at 2h */
    /* escape_distance: the default (10 bar lengths beyond the bar's box) never stops a bar that stays whole */
    bd.name = "bar";
    bd.material.kind = material == 0 ? SPS_MATERIAL_J2 : SPS_MATERIAL_ELASTIC;
    bd.material.j2.yield_stress = (sps_real)yield;
    bd.material.j2.hardening_modulus = (sps_real)hardening;
    sps_world_create(&wd, &w);
    sps_world_add_body(w, &bd, &bar);
    {
#ifdef TAYLOR_ROUND
        const sps_real lo[3] = {(sps_real)-TB_RADIUS, (sps_real)-TB_RADIUS, (sps_real)gap};
        const sps_real hi[3] = {(sps_real)TB_RADIUS, (sps_real)TB_RADIUS, (sps_real)(gap + TB_LENGTH)};
        sps_body_add_sdf(w, bar, lo, hi, cylinder_sdf, NULL, &added);
#else
        const sps_real lo[3] = {(sps_real)-TB_HALF_WIDTH, (sps_real)-TB_HALF_WIDTH, (sps_real)gap};
        const sps_real hi[3] = {(sps_real)TB_HALF_WIDTH, (sps_real)TB_HALF_WIDTH, (sps_real)(gap + TB_LENGTH)};
        sps_body_add_box(w, bar, lo, hi, &added);
#endif
    }
    sps_body_set_velocity(w, bar, impact_velocity, NULL);
    sps_world_add_wall(w, wall_point, up, SPS_WALL_FREE_SLIP);
    memset(&s, 0, sizeof s);
#ifndef TAYLOR_ROUND
    {
        const sps_real point[3] = {(sps_real)TB_HALF_WIDTH, 0, (sps_real)gap};
        sps_world_add_observer(w, bar, point, &s.point);
    }
#endif
    s.t_end = c.t_end; s.ke_min = 1e300; s.ke_59us = -1;
    s.t_contact = gap / TB_SPEED;
    output_open(&s.output, &c, TB_NAME, "plastic-strain", ",t_impact,x_observation");
    s.output.t_end = s.t_contact + c.t_end; /* the run goes on for --tend after the contact */
    start = measure_bar(w, dp, gap);
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)(s.t_contact + c.t_end), on_step, &s);
    wall = output_close(w, &s.output);
    end = measure_bar(w, dp, gap);
    {
        sps_body all = {0};
        double account;
        sps_world_diagnostics(w, all, &d);
        account = d.kinetic_energy + d.strain_energy + d.contact_energy + d.plastic_work;
#ifdef TAYLOR_ROUND
        printf("RESULT case=%s shear=%s res=%d dp=%g tend=%g length=%.6g radius=%.6g length0=%.6g radius0=%.6g "
               "kinetic_start=%.6g paper_kinetic_start=209.58 kinetic_min=%.4g t_kinetic_min=%.3g paper_kinetic_min=0.0256 paper_t_min=3.2e-05 "
               "kinetic_59us=%.4g paper_kinetic_59us=0.0303 ",
               TB_NAME, shear_name(c.shear), res, dp, c.t_end, end.top - end.bottom + (TB_LENGTH - (start.top - start.bottom)), end.side + (TB_RADIUS - start.side),
               TB_LENGTH, TB_RADIUS, s.e0, s.ke_min, s.t_ke_min, s.ke_59us);
#else
        sps_real u[3];
        double x_obs;
        sps_observer_read(w, s.point, u, NULL);
        x_obs = TB_HALF_WIDTH + (double)u[0];
        printf("RESULT case=%s shear=%s res=%d dp=%g tend=%g x_observation_mm=%.4f x_face_particle_mm=%.4f paper_mm=%s haider_mm=6.93 "
               "length=%.6g half_width=%.6g kinetic_start=%.6g kinetic_end=%.4g ",
               TB_NAME, shear_name(c.shear), res, dp, c.t_end, 1e3 * x_obs, 1e3 * end.face_x,
               res == 8 ? "5.21" : res == 12 ? "5.91" : res == 16 ? "6.46" : res == 20 ? "6.86" : "none", end.top - end.bottom + (TB_LENGTH - (start.top - start.bottom)),
               end.side + (TB_HALF_WIDTH - start.side), s.e0, (double)d.kinetic_energy);
#endif
        printf("material=%s strain_end=%.4g plastic_work_end=%.6g account_end_rel=%.3f%% account_max_dev=%.3f%% account_ok=%s max_plastic_strain=%.4g "
               "hourglass_max=%.3g min_spacing=%.3f yield=%g hardening=%g rho0=%g %s particles=%d steps=%ld advection_steps=%ld "
               "us_per_particle_step=%.4f wall_s=%.2f out=%s\n",
               material == 0 ? "j2" : "elastic", (double)d.strain_energy, (double)d.plastic_work, 100 * (account - s.e0) / s.e0, 100 * s.account_dev_max / s.e0,
               s.account_dev_max <= 0.02 * s.e0 ? "yes" : "NO", (double)d.max_plastic_strain, s.output.hourglass_max, s.output.min_spacing,
               yield, hardening, c.rho0, common_result_fields(&c), added, d.acoustic_steps, d.advection_steps,
               d.acoustic_steps > 0 ? 1e6 * wall / ((double)d.acoustic_steps * added) : 0, wall, c.out);
    }
    sps_world_destroy(w);
    return 0;
}
