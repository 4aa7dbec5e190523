/* dam_break2d.c - the collapse of a water column in a tank (bench/VALIDATION.md, "dam break").

   A column a = 1 m wide and 2a high (Martin and Moyce 1952's n^2 = 2, Koshizuka and Oka 1996's
   set-up) stands at the left wall of a tank 4a wide with an open top, under g = 9.81, in
   hydrostatic equilibrium (sps_body_set_pressure), and is released at t = 0. The tank is four
   analytic walls (sps_world_add_box_walls, free slip unless --no-slip): the contact chapter's
   repulsion holds the water. The water is inviscid by default (--viscosity sets mu), c0 =
   10 sqrt(2 g 2a). We follow the surge front (the rightmost particle + dp/2) in the
   experiments' units, Z = x/a against T = t sqrt(2 g / a), until it reaches the far wall, and
   print it next to the measured fronts (Martin and Moyce's Fig. 3 for n^2 = 2, a = 2.25 in, and
   Koshizuka and Oka's Fig. 5, as digitised in PySPH's examples/db_exp_data.py).

   Build: make examples     Run: ./build/dam_break2d --dp 0.025
   Expect: the front within a few % of the experiments after T = 1.5; ahead of them at first (the
   experiments' gate takes time to lift).
   Smoke: dam_break2d --dp 0.05 --tend 0.01 */
#include "common.h"

#define A_COLUMN 1.0
#define G_ACC 9.81

/* Front positions Z = x/a against T = t sqrt(2 g / a). */
static const double mm_T[] = {0.832, 1.219, 1.997, 2.547, 3.345}, mm_Z[] = {1.217, 1.474, 2.292, 2.995, 4.134};
static const double ko_T[] = {0.381, 0.769, 1.153, 1.537, 1.935, 2.323, 2.719, 3.096}, ko_Z[] = {1.111, 1.252, 1.505, 1.892, 2.241, 2.615, 3.003, 3.624};

static double g_rho0 = 1000, g_height = 2 * A_COLUMN;
static sps_real hydrostatic(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(g_rho0 * G_ACC * (g_height - (double)x[1]));
}

typedef struct {
    output_plan output;
    double t_end, dp, T[4096], Z[4096];
    int n, quiet;
} run_state;

static double front(const sps_world* w, double dp) {
    const sps_real* x = sps_world_field(w, SPS_FIELD_POSITION_X);
    double xmax = 0;
    int i, n = sps_world_particle_count(w);
    for (i = 0; i < n; ++i)
        if (x[i] > xmax) xmax = x[i];
    return (xmax + 0.5 * dp) / A_COLUMN;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[96];
    const double Z = front(w, s->dp), T = sps_world_time(w) * sqrt(2 * G_ACC / A_COLUMN);
    snprintf(extra, sizeof extra, ",%.9g,%.9g", T, Z);
    if (output_tick(w, &s->output, extra, &d) && s->n < 4096) {
        s->T[s->n] = T;
        s->Z[s->n++] = Z;
    }
    progress(sps_world_time(w), s->t_end, s->output.wall0, s->quiet);
    return Z >= 4 * A_COLUMN - 0.5 * s->dp; /* the front at the far wall: the comparison ends */
}

/* Our front at time T by linear interpolation of the recorded rows (-1 past the last). */
static double front_at(const run_state* s, double T) {
    int k;
    for (k = 1; k < s->n; ++k)
        if (s->T[k] >= T) return s->Z[k - 1] + (s->Z[k] - s->Z[k - 1]) * (T - s->T[k - 1]) / (s->T[k] - s->T[k - 1]);
    return -1;
}

static void compare(const run_state* s, const char* who, const double* T, const double* Z, int n, double* worst_late) {
    int k;
    for (k = 0; k < n; ++k) {
        const double ours = front_at(s, T[k]);
        if (ours < 0) continue;
        printf("  %-18s T = %5.3f   Z: ours %6.3f  measured %6.3f  %+6.1f%%\n", who, T[k], ours, Z[k], 100 * (ours / Z[k] - 1));
        if (T[k] >= 1.5 && fabs(ours / Z[k] - 1) > *worst_late) *worst_late = fabs(ours / Z[k] - 1);
    }
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 2, .vtk_every = 0.1, .csv_every = 0.005, .E = 1e6, .nu = 0.3,
                        .rho0 = 1000, .out = "out/dam_break2d", .h_over_dp = 2, .jitter = 0, .seed = 1, .transport = 0, PNG_DEFAULTS};
    double dp = 0.025, viscosity = 0;
    int no_slip = 0;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (column width a = 1 m)", 2e-3, 0.25, NULL},
        {"viscosity", OPT_REAL, &viscosity, "dynamic viscosity mu [Pa s]", 0, 1e6, NULL},
        {"no-slip", OPT_FLAG, &no_slip, "no-slip tank walls (else free slip)", 0, 0, NULL},
        COMMON_OPTION_SPECS(c),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body water, all = {0};
    sps_diagnostics d;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {A_COLUMN, 2 * A_COLUMN, 0}, tank_lo[3] = {0, 0, 0}, tank_hi[3] = {4 * A_COLUMN, 3 * A_COLUMN, 0};
    run_state* s = (run_state*)calloc(1, sizeof(run_state));
    double wall, worst_late = 0, c0;

    ex_short_openmp_spin(argv);
    opt_parse(argc, argv, "2D dam break: a water column collapsing in a tank, against Martin and Moyce (1952), Koshizuka and Oka (1996)",
              opts, (int)(sizeof opts / sizeof *opts));
    if (!s) { fprintf(stderr, "%s: out of memory\n", g_prog); return 1; }
    apply_common(&c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (ex_check_step) */
    g_rho0 = c.rho0;
    c0 = 10 * sqrt(2 * G_ACC * g_height);
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-G_ACC;
    bd.name = "water";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.sound_speed = (sps_real)c0;
    bd.material.viscosity = (sps_real)viscosity;
    wd.log = ex_log;
    ex_check(NULL, sps_world_create(&wd, &w));
    ex_check(w, sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, no_slip ? SPS_WALL_NO_SLIP : SPS_WALL_FREE_SLIP));
    ex_unset_unread(&bd); /* a fluid reads no shear formulation */
    ex_check(w, sps_world_add_body(w, &bd, &water));
    ex_check(w, sps_body_add_box(w, water, lo, hi, NULL));
    ex_check(w, sps_body_set_pressure(w, water, hydrostatic, NULL));

    s->dp = dp;
    s->t_end = c.t_end;
    s->quiet = c.quiet;
    output_open(&s->output, &c, "dam_break2d", "velocity", ",T,front_Z");
    on_step(w, s); /* t = 0: the first CSV row and snapshot */
    ex_check_step(w, sps_world_advance(w, (sps_real)c.t_end, on_step, s), &s->output);
    wall = output_close(w, &s->output);
    ex_check(w, sps_world_diagnostics(w, all, &d));
    printf("dam break: dp = %g (a/dp = %g), %d particles, c0 = %g m/s, %s walls, transport %s\n", dp, A_COLUMN / dp,
           sps_world_particle_count(w), c0, no_slip ? "no-slip" : "free-slip", c.transport == 0 ? "none" : c.transport == 1 ? "TVF" : "UTVF");
    compare(s, "Martin-Moyce 1952", mm_T, mm_Z, (int)(sizeof mm_T / sizeof *mm_T), &worst_late);
    compare(s, "Koshizuka-Oka 1996", ko_T, ko_Z, (int)(sizeof ko_T / sizeof *ko_T), &worst_late);
    printf("RESULT case=dam_break2d dp=%g c0=%g walls=%s viscosity=%g t=%.4g T=%.4f front_Z=%.4f worst_err_after_T1.5=%.2f%% "
           "energy=%.6g min_spacing=%.3f %s particles=%d steps=%ld advection_steps=%ld wall_s=%.2f out=%s\n",
           dp, c0, no_slip ? "no-slip" : "free-slip", viscosity, (double)d.time, s->n ? s->T[s->n - 1] : 0, s->n ? s->Z[s->n - 1] : 0,
           100 * worst_late, (double)(d.kinetic_energy + d.strain_energy + d.potential_energy + d.contact_energy), s->output.min_spacing,
           common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall, c.out);
    sps_world_destroy(w);
    free(s);
    return 0;
}
