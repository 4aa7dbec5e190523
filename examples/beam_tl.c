/* beam_tl.c - bending of a cantilever beam, benchmark D2 (TL section 4.2, Table 1; bench/VALIDATION.md).

   A beam 8 mm x 1 mm (E 100 GPa, nu 0.3, plane strain; Saint Venant-Kirchhoff) on a square
   lattice of (3 + 8n) x n particles, spacing 1/n mm, kernel support 2.41 spacings (h = 1.205 dp),
   the three left columns (x < 0) clamped. The top-right particle is pushed down by --u (0.1 mm)
   quasi-statically: its velocity is held at -u/T_ramp over T_ramp = --ramp periods (1) of the
   first bending mode, then at 0 while the body's numerical damping (c = 2 omega_1, critical for the
   first mode: DAMPING) brings it to rest over 3 more (the first mode decays as e^(-omega t),
   by e^-19). The reaction f is the internal force on that particle, -m a_y, and
   the compliance C = f/u (per 1 mm of depth) is compared with 3 E/(1 - nu^2) I / L^3 =
   0.053657 kN/mm (the author's input). --u 8 is the large deflection (TL Fig. 6): the
   hourglass indicator tells whether it stays smooth.

   Build: make examples   Run: for n in 4 8 16; do ./build/beam_tl --n $n --alpha 50; done
   The paper: rate about 2 with alpha 50, 6.6e-4 at n = 16. Measured (bench/VALIDATION.md): alpha 0
   errors 0.34 / 0.12 / 0.048 at n = 4 / 8 / 16; alpha 50 (variational) +0.107 / +0.0021 / -0.0056;
   alpha 50 with --hourglass paper (TL eq. 32) 0.70 / 0.22 and unstable at n = 16.
   Smoke: beam_tl --n 3 --periods 2 */
#include "common.h"

typedef struct {
    output_plan output;
    sps_body beam;
    int tip_id, held;
    double t_ramp, mass;
    sps_real lo[3], hi[3];
} run_state;

/* -m a_y of the tip particle: the force the constraint applies to hold it [N per m of depth]
   (negative: down, against the beam's elastic push up). */
static double reaction(const sps_world* w, const run_state* s) {
    const sps_real* ay = sps_world_field_by_name(w, "pressure_acceleration_y", NULL);
    const int* ids = sps_world_particle_ids(w);
    int i;
    for (i = 0; i < sps_world_particle_count(w); ++i)
        if (ids[i] == s->tip_id) return -s->mass * ay[i];
    return 0;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    sps_particle_state p;
    char extra[96];
    const double t = sps_world_time(w);
    if (!s->held && t >= s->t_ramp) { /* the ramp is done: hold the tip where it is */
        sps_real v[3] = {0, 0, 0};
        sps_body_constrain_box(w, s->beam, s->lo, s->hi, SPS_AXIS_Y, v, NULL);
        s->held = 1;
    }
    sps_world_particle(w, s->tip_id, &p);
    snprintf(extra, sizeof extra, ",%.9g,%.9g", (double)p.displacement[1], reaction(w, s));
    output_tick(w, &s->output, extra, &d);
    return 0;
}

int main(int argc, char** argv) {
    int n = 8;
    double alpha = 50, u = 1e-4, periods = 4, ramp = 1;
    double artificial_viscosity = 0; /* TL artificial viscosity q1 (none: the paper's) */
    int hourglass_form = SPS_HOURGLASS_VARIATIONAL;
    common_options c = {.cfl = 0.4, .t_end = 0, .vtk_every = 0, .csv_every = 1e-6, .E = 100e9, .nu = 0.3, .rho0 = 1000,
                        .out = "out/beam_tl", .seed = 1, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"n", OPT_INT, &n, "particles across the depth (the beam: (3 + 8n) x n)", 2, 64, NULL},
        {"alpha", OPT_REAL, &alpha, "hourglass coefficient alpha (TL eq. 32)", 0, 1000, NULL},
        EX_HOURGLASS_OPTIONS(hourglass_form, artificial_viscosity),
        {"u", OPT_REAL, &u, "tip displacement [m] (0.1 mm; 8 mm: the large deflection)", 1e-9, 0.02, NULL},
        {"periods", OPT_REAL, &periods, "run time in first-mode periods (--ramp of them to push, the rest to settle)", 2, 1000, NULL},
        {"ramp", OPT_REAL, &ramp, "time of the push in first-mode periods", 0.1, 1000, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    run_state s;
    const double L = 8e-3, H = 1e-3;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)L, (sps_real)H, 0}, clo[3] = {-1, -1, -1}, chi[3] = {0, 1, 1};
    sps_real tip[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    double Ep, omega, wall, f, C, theory, err, dp;
    sps_particle_state p;

    ex_options(argc, argv, "cantilever beam bending (benchmark D2, bench/VALIDATION.md)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    dp = H / n;
    lo[0] = (sps_real)(-3 * dp); /* the three clamped columns */
    tip[0] = (sps_real)(L - dp / 2);
    tip[1] = (sps_real)(H - dp / 2);
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.h_over_dp = (sps_real)(2.41 / 2); /* kernel support 2.41 dp, as the paper's */
    wd.energy_growth_limit = (sps_real)INFINITY; /* driven and damped: no energy account to watch */
    Ep = c.E / (1 - c.nu * c.nu);
    theory = 3 * Ep * (H * H * H / 12) / (L * L * L) * 1e-3 * 1e-6; /* kN/mm for 1 mm of depth */
    omega = 1.875 * 1.875 / (L * L) * sqrt(Ep * H * H / (12 * c.rho0)); /* first mode, Euler-Bernoulli */
    bd.name = "beam";
    bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
    bd.material.kind = SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF;
    bd.material.tl.hourglass_alpha = (sps_real)alpha;
    bd.material.tl.hourglass = (sps_hourglass)hourglass_form;
    bd.material.tl.artificial_viscosity = (sps_real)artificial_viscosity;
    bd.damping = (sps_real)(2 * omega); /* critical for the first mode */
    memset(&s, 0, sizeof s);
    s.t_ramp = ramp * 2 * PI / omega;
    if (c.t_end <= 0) c.t_end = periods * 2 * PI / omega;
    sps_world_create(&wd, &w);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &s.beam);
    sps_body_add_box(w, s.beam, lo, hi, NULL);
    sps_body_constrain_box(w, s.beam, clo, chi, SPS_AXIS_ALL, NULL, NULL);
    s.tip_id = sps_world_nearest_particle(w, s.beam, tip);
    sps_world_particle(w, s.tip_id, &p);
    for (int a = 0; a < 3; ++a) {
        s.lo[a] = p.position[a] - (sps_real)(dp / 4);
        s.hi[a] = p.position[a] + (sps_real)(dp / 4);
    }
    v[1] = (sps_real)(-u / s.t_ramp);
    sps_body_constrain_box(w, s.beam, s.lo, s.hi, SPS_AXIS_Y, v, NULL);
    s.mass = c.rho0 * dp * dp;
    if (c.csv_every < c.t_end / 2000) c.csv_every = c.t_end / 2000;
    output_open(&s.output, &c, "beam_tl", "displacement", ",tip_uy,reaction");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    sps_world_particle(w, s.tip_id, &p);
    f = reaction(w, &s);
    C = f / p.displacement[1] * 1e-3 * 1e-6; /* the reaction pushes up (f < 0 is down): C > 0 */
    err = fabs(C - theory) / theory;
    {
        sps_diagnostics d;
        sps_world_diagnostics(w, (sps_body){0}, &d);
        printf("RESULT case=beam_tl n=%d alpha=%g hourglass=%s artificial_viscosity=%g u=%g particles=%d tip_uy=%.6g reaction_N_per_m=%.6g C_kN_per_mm=%.6f theory=%.6f "
               "rel_error=%.3e hourglass=%.3g max_speed=%.3g %s steps=%ld wall_s=%.2f out=%s\n",
               n, alpha, ex_hourglass_name(hourglass_form), artificial_viscosity, u, sps_world_particle_count(w), (double)p.displacement[1], f, C, theory, err, (double)d.hourglass,
               (double)d.max_speed, common_result_fields(&c), d.acoustic_steps, wall, c.out);
    }
    sps_world_destroy(w);
    return 0;
}
