/* dam_break2d.c - the collapse of a water column in a tank, against the experiments
   (bench/VALIDATION.md, "The dam break against the experiments").

   A column a wide and n^2 a high (--height n^2; 2 by default: Martin and Moyce 1952's n^2 = 2,
   Koshizuka and Oka 1996's set-up) stands at the left wall of a tank (--tank, in a; 4 by
   default) with an open top, under g = 9.81, in hydrostatic equilibrium (sps_body_set_pressure),
   and is released at t = 0. The tank is four analytic walls (sps_world_add_box_walls, free slip
   unless --no-slip). The water is inviscid by default (--viscosity sets mu), c0 = 10 sqrt(2 g n^2 a)
   (--c0-factor), started at its hydrostatic pressure (--zero-pressure: at p = 0).
   In Martin and Moyce's units, Z = front / a against T = n t sqrt(g / a) (the front: the
   rightmost particle + dp/2), and the water's height at the left wall over n^2 a; the front is
   followed until it reaches the far wall. Ours is printed next to each experiment of the same
   aspect (data and sources: bench/dam_break_experiments.csv), as measured, then with the
   experiment's clock delayed by the one delay that fits it best over T = 1-3 (a fitted
   parameter, printed as such): an experiment frees its column by removing a gate, which takes
   time, and its time origin need not be the instant the whole column is free.
   --lobovsky: Lobovsky et al. 2014's tank (a = 0.6 m, water 0.3 m deep, tank 1.61 m long) with
   their pressure sensors on the far wall 3, 15, 30 and 80 mm above the floor, against their
   H = 300 mm record (impact time, peak, and the pressure averaged over windows of t sqrt(g/H)).

   Build: make examples     Run: ./build/dam_break2d --dp 0.025
   Expect: converged in dp (a/dp 40 and 80 within 0.6 %); as measured, ahead of Martin and Moyce and
   of Koshizuka and Oka by 19-22 % over T = 1-3; with Martin and Moyce's clock delayed by T = 0.28-0.30
   (fitted: 16 ms at their a = 2.25 in) within 0.2-3.4 %; Koshizuka and Oka's front is slower, not
   later (7 % with the best delay); Lobovsky's impact on the far wall within 2 % with no delay; a
   no-slip floor with water's viscosity changes the front by < 0.5 %.
   Smoke: dam_break2d --dp 0.05 --tend 0.01
   Smoke: dam_break2d --dp 0.05 --tend 0.01 --lobovsky */
#include "common.h"

#define G_ACC 9.81
#define SENSORS 4
#define MAX_ROWS 8192

/* The experiments (bench/dam_break_experiments.csv names each source). Front: Z = x/a against
   T = n t sqrt(g/a); height at the left wall: h/(n^2 a) against the same T. */
typedef struct {
    const char* who;
    double aspect;       /* n^2 of the experiment's column */
    double a_m;          /* its column width [m] (0: not stated by the source) */
    const double *T, *V; /* time and value */
    int n;
} experiment;

static const double mm225_T[] = {0.832, 1.219, 1.997, 2.547, 3.345}, mm225_Z[] = {1.217, 1.474, 2.292, 2.995, 4.134};
static const double mm1125_T[] = {0.849, 1.212, 1.602, 2.283, 2.950, 3.598}, mm1125_Z[] = {1.245, 1.443, 1.884, 2.689, 3.728, 4.528};
static const double mmtab_T[] = {0.41, 0.84, 1.19, 1.43, 1.63, 1.82, 1.97, 2.2, 2.32, 2.5, 2.64, 2.82, 2.96};
static const double mmtab_Z[] = {1.11, 1.23, 1.44, 1.67, 1.89, 2.11, 2.33, 2.56, 2.78, 3.0, 3.22, 3.44, 3.67};
static const double ko_T[] = {0.381, 0.769, 1.153, 1.537, 1.935, 2.323, 2.719, 3.096}, ko_Z[] = {1.111, 1.252, 1.505, 1.892, 2.241, 2.615, 3.003, 3.624};
static const double mm1_T[] = {0.43, 0.62, 0.80, 0.97, 1.14, 1.29, 1.45, 1.62, 1.76, 1.93, 2.07, 2.24, 2.40, 2.54, 2.71, 2.87, 3.04, 3.21, 3.29, 3.32};
static const double mm1_Z[] = {1.11, 1.22, 1.44, 1.67, 1.89, 2.11, 2.33, 2.56, 2.78, 3.00, 3.22, 3.44, 3.67, 3.89, 4.11, 4.33, 4.56, 4.78, 4.89, 5.0};
static const double mm1h_T[] = {0.80, 1.29, 1.74, 2.15, 2.57, 3.08, 4.27, 6.29}, mm1h_H[] = {0.89, 0.78, 0.67, 0.56, 0.44, 0.33, 0.22, 0.11};
#define EXPERIMENT(who, aspect, a, T, V) {who, aspect, a, T, V, (int)(sizeof T / sizeof *T)}
static const experiment fronts[] = {
    EXPERIMENT("Martin-Moyce a=2.25in", 2, 0.05715, mm225_T, mm225_Z),
    EXPERIMENT("Martin-Moyce a=1.125in", 2, 0.028575, mm1125_T, mm1125_Z),
    EXPERIMENT("Martin-Moyce (table)", 2, 0, mmtab_T, mmtab_Z),
    EXPERIMENT("Koshizuka-Oka", 2, 0.146, ko_T, ko_Z),
    EXPERIMENT("Martin-Moyce n2=1", 1, 0, mm1_T, mm1_Z),
};
static const experiment heights[] = {EXPERIMENT("Martin-Moyce n2=1", 1, 0, mm1h_T, mm1h_H)};

/* Lobovsky et al. 2014, H = 300 mm, their event 5 (Fig. 18's record): p/(rho g H) against
   t sqrt(g/H) at the sensors 3, 15, 30, 80 mm above the floor on the far wall. Impact: the first
   time above 0.5; windows: the mean over [2.5, 3.5), [3.5, 4.5), [4.5, 5.5), [5.5, 6.5). */
static const double lob_height_mm[SENSORS] = {3, 15, 30, 80};
static const double lob_impact[SENSORS] = {2.445, 2.467, 2.538, 3.064}, lob_peak[SENSORS] = {3.044, 1.950, 1.544, 0.844};
static const double lob_window[SENSORS][4] = {{1.173, 0.694, 0.647, 0.853}, {1.108, 0.658, 0.665, 0.851}, {1.029, 0.580, 0.598, 0.768}, {0.327, 0.563, 0.477, 0.616}};

typedef struct {
    double width, height, tank; /* column width a [m], column height and tank length [m] */
    double rho0, dp;
} scene;

typedef struct {
    output_plan output;
    scene sc;
    double T[MAX_ROWS], Z[MAX_ROWS], H[MAX_ROWS], p[MAX_ROWS][SENSORS];
    double sensor_y[SENSORS];
    int n, to_the_far_wall;
} run_state;

/* The hydrostatic pressure of the column at rest (user: the scene). */
static sps_real hydrostatic(const sps_real x[3], void* user) {
    const scene* sc = (const scene*)user;
    return (sps_real)(sc->rho0 * G_ACC * (sc->height - (double)x[1]));
}

static double time_unit(const scene* sc) { return sqrt(G_ACC * sc->height) / sc->width; } /* T = t n sqrt(g/a) */

/* The front (rightmost particle + dp/2) over a, and the water's height at the left wall (the
   highest particle within dp of it, + dp/2) over the column's height. */
static void front_and_height(const sps_world* w, const scene* sc, double* Z, double* H) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    double xmax = 0, ymax = 0;
    int i, n = sps_world_particle_count(w);
    for (i = 0; i < n; ++i) {
        if (x[i] > xmax) xmax = x[i];
        if (x[i] < sc->dp && y[i] > ymax) ymax = y[i];
    }
    *Z = (xmax + 0.5 * sc->dp) / sc->width;
    *H = (ymax + 0.5 * sc->dp) / sc->height;
}

/* The pressure at a point on the far wall, p/(rho0 g H): the kernel-weighted (Shepard) mean of
   the particles' pressure within the kernel's support (0 when no water reaches it). */
static double wall_pressure(const sps_world* w, const scene* sc, double y_sensor) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* p = sps_world_field(w, SPS_FIELD_PRESSURE);
    double sum_w = 0, sum_pw = 0;
    int i, n = sps_world_particle_count(w);
    for (i = 0; i < n; ++i) {
        const double dx = x[i] - sc->tank, dy = y[i] - y_sensor, W = sps_world_kernel(w, (sps_real)sqrt(dx * dx + dy * dy));
        sum_w += W;
        sum_pw += W * p[i];
    }
    return sum_w > 0 ? sum_pw / sum_w / (sc->rho0 * G_ACC * sc->height) : 0;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[160];
    double Z, H, p[SENSORS];
    const double T = sps_world_time(w) * time_unit(&s->sc);
    int k;
    front_and_height(w, &s->sc, &Z, &H);
    for (k = 0; k < SENSORS; ++k) p[k] = wall_pressure(w, &s->sc, s->sensor_y[k]);
    snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g,%.6g,%.6g,%.6g,%.6g", T, Z, H, p[0], p[1], p[2], p[3]);
    if (output_tick(w, &s->output, extra, &d) && s->n < MAX_ROWS) {
        s->T[s->n] = T;
        s->Z[s->n] = Z;
        s->H[s->n] = H;
        memcpy(s->p[s->n++], p, sizeof p);
    }
    /* the front at the far wall ends the front's comparison (the pressure record goes on) */
    return s->to_the_far_wall && Z * s->sc.width >= s->sc.tank - 0.5 * s->sc.dp;
}

/* A recorded series at time T by linear interpolation (-1 outside the record, or past the
   front's arrival at the far wall for the front and height). */
static double series_at(const run_state* s, const double* v, double T) {
    int k;
    if (T < s->T[0]) return -1;
    for (k = 1; k < s->n; ++k)
        if (s->T[k] >= T) return v[k - 1] + (v[k] - v[k - 1]) * (T - s->T[k - 1]) / (s->T[k] - s->T[k - 1]);
    return -1;
}

/* The largest relative difference of ours against e over its points in [lo, hi] with the
   experiment's clock delayed by shift (ours at T - shift against the experiment at T); -1 if
   no point is in range. */
static double worst_error(const run_state* s, const double* v, const experiment* e, double shift, double lo, double hi) {
    double worst = -1;
    int k;
    for (k = 0; k < e->n; ++k) {
        const double ours = series_at(s, v, e->T[k] - shift);
        if (e->T[k] < lo || e->T[k] > hi || ours < 0) continue;
        if (fabs(ours / e->V[k] - 1) > worst) worst = fabs(ours / e->V[k] - 1);
    }
    return worst;
}

/* The delay of the experiment's clock in [0, 1] (steps of 0.005) that minimises the worst error
   over T = 1-3. */
static double best_shift(const run_state* s, const double* v, const experiment* e, double* worst) {
    double shift, best = 0;
    *worst = 1e30;
    for (shift = 0; shift <= 1 + 1e-9; shift += 0.005) {
        const double err = worst_error(s, v, e, shift, 1, 3);
        if (err >= 0 && err < *worst) { *worst = err; best = shift; }
    }
    return best;
}

/* Prints ours next to e, as measured and with the fitted delay; returns the worst errors over
   T = 1-3 as measured (raw) and delayed (shifted), and the delay (shift); 0 for a run that
   ends before T = 1. */
static void compare(const run_state* s, const double* v, const char* what, const experiment* e, double* raw, double* shifted, double* shift) {
    int k;
    *shift = best_shift(s, v, e, shifted);
    *raw = worst_error(s, v, e, 0, 1, 3);
    printf("  %s, %s (n^2 = %g):\n", e->who, what, e->aspect);
    for (k = 0; k < e->n; ++k) {
        const double ours = series_at(s, v, e->T[k]), later = series_at(s, v, e->T[k] - *shift);
        if (ours < 0) continue;
        printf("    T = %5.3f  measured %6.3f   ours %6.3f %+6.1f%%   ours at T - %.3f %6.3f %+6.1f%%\n", e->T[k], e->V[k], ours,
               100 * (ours / e->V[k] - 1), *shift, later, later < 0 ? 0 : 100 * (later / e->V[k] - 1));
    }
    if (*raw < 0) { /* a short run: no point of T = 1-3 reached */
        printf("    over T = 1-3: not reached\n");
        *raw = *shifted = *shift = 0;
        return;
    }
    printf("    over T = 1-3: worst %.1f %% as measured; %.1f %% with the experiment's clock delayed by T = %.3f", 100 * *raw,
           100 * *shifted, *shift);
    if (e->a_m > 0) printf(" (%.1f ms at its a = %.4g m)", 1e3 * *shift / sqrt(G_ACC * e->aspect / e->a_m), e->a_m);
    printf("\n");
}

/* Lobovsky et al.'s sensors against ours: the first time above 0.5 rho g H (-1: none), the
   peak, the window means. */
static void compare_lobovsky(const run_state* s) {
    int k, r, j;
    printf("  Lobovsky et al. 2014 (H = 300 mm, event 5), far wall, p/(rho g H) against t sqrt(g/H):\n");
    for (k = 0; k < SENSORS; ++k) {
        double impact = -1, peak = 0, sum[4] = {0}, count[4] = {0};
        for (r = 0; r < s->n; ++r) {
            const double tstar = s->T[r] * s->sc.width / s->sc.height, p = s->p[r][k]; /* T = t sqrt(g H)/a -> t sqrt(g/H) */
            if (impact < 0 && p > 0.5) impact = tstar;
            if (p > peak) peak = p;
            for (j = 0; j < 4; ++j)
                if (tstar >= 2.5 + j && tstar < 3.5 + j) { sum[j] += p; count[j] += 1; }
        }
        printf("    %2.0f mm: impact %.3f (measured %.3f)  peak %.2f (measured %.2f)  windows", lob_height_mm[k], impact, lob_impact[k], peak,
               lob_peak[k]);
        for (j = 0; j < 4; ++j) /* -1: the run ended before the window */
            printf("  %.2f (%.2f)", count[j] > 0 ? sum[j] / count[j] : -1, lob_window[k][j]);
        printf("\n");
    }
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 2, .vtk_every = 0.1, .csv_every = 0.005, .E = 1e6, .nu = 0.3,
                        .rho0 = 1000, .out = "out/dam_break2d", .h_over_dp = 2, .jitter = 0, .seed = 1, .transport = 0, PNG_DEFAULTS};
    double dp = 0.025, viscosity = 0, aspect = 2, tank = 4, c0_factor = 10;
    int no_slip = 0, lobovsky = 0, start_at_rest = 0;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (column width a = 1 m; 0.6 m with --lobovsky)", 2e-3, 0.25, NULL},
        {"height", OPT_REAL, &aspect, "column height over its width, n^2 (Martin and Moyce: 1 or 2)", 0.25, 4, NULL},
        {"tank", OPT_REAL, &tank, "tank length over the column's width", 1.5, 20, NULL},
        {"viscosity", OPT_REAL, &viscosity, "dynamic viscosity mu [Pa s]", 0, 1e6, NULL},
        {"no-slip", OPT_FLAG, &no_slip, "no-slip tank walls (else free slip)", 0, 0, NULL},
        {"c0-factor", OPT_REAL, &c0_factor, "sound speed over sqrt(2 g n^2 a), the fastest free fall's speed", 5, 100, NULL},
        {"zero-pressure", OPT_FLAG, &start_at_rest, "start at p = 0 (else hydrostatic)", 0, 0, NULL},
        {"lobovsky", OPT_FLAG, &lobovsky, "Lobovsky et al. 2014's tank and sensors (H = 300 mm; sets --height, --tank)", 0, 0, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body water, all = {0};
    sps_diagnostics d;
    run_state* s = (run_state*)calloc(1, sizeof(run_state));
    double wall, c0, worst_raw = 0, worst_shifted = 0;
    int k;

    ex_options(argc, argv, "2D dam break: a water column collapsing in a tank, against Martin and Moyce (1952), Koshizuka and Oka (1996), Lobovsky et al. (2014)",
               opts, &c, &wd, &bd);
    if (!s) { fprintf(stderr, "%s: out of memory\n", g_prog); return 1; }
    s->sc.width = lobovsky ? 0.6 : 1;
    s->sc.height = (lobovsky ? 0.5 : aspect) * s->sc.width;
    s->sc.tank = lobovsky ? 1.61 : tank * s->sc.width;
    s->sc.rho0 = c.rho0;
    s->sc.dp = dp;
    for (k = 0; k < SENSORS; ++k) s->sensor_y[k] = 1e-3 * lob_height_mm[k] * s->sc.width / 0.6;
    s->to_the_far_wall = !lobovsky;
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    c0 = c0_factor * sqrt(2 * G_ACC * s->sc.height);
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-G_ACC;
    bd.name = "water";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = (sps_real)c0;
    bd.material.viscosity = (sps_real)viscosity;
    sps_world_create(&wd, &w);
    {
        const sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)s->sc.width, (sps_real)s->sc.height, 0};
        const sps_real tank_lo[3] = {0, 0, 0}, tank_hi[3] = {(sps_real)s->sc.tank, (sps_real)(1.5 * s->sc.height), 0};
        sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, no_slip ? SPS_WALL_NO_SLIP : SPS_WALL_FREE_SLIP);
        ex_unset_unread(&bd); /* a fluid reads no shear formulation */
        sps_world_add_body(w, &bd, &water);
        sps_body_add_box(w, water, lo, hi, NULL);
    }
    if (!start_at_rest) sps_body_set_pressure(w, water, hydrostatic, &s->sc);

    output_open(&s->output, &c, "dam_break2d", "velocity", ",T,front_Z,wall_height_H,p_3mm,p_15mm,p_30mm,p_80mm");
    on_step(w, s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, s);
    wall = output_close(w, &s->output);
    sps_world_diagnostics(w, all, &d);
    printf("dam break: a = %g m, n^2 = %g, tank %g a, dp = %g (a/dp = %g), %d particles, c0 = %g m/s, %s walls, mu = %g Pa s, transport %s\n",
           s->sc.width, s->sc.height / s->sc.width, s->sc.tank / s->sc.width, dp, s->sc.width / dp, sps_world_particle_count(w), c0,
           no_slip ? "no-slip" : "free-slip", viscosity, c.transport == 0 ? "none" : c.transport == 1 ? "TVF" : "UTVF");
    if (lobovsky) compare_lobovsky(s);
    else {
        const double n2 = s->sc.height / s->sc.width;
        for (k = 0; k < (int)(sizeof fronts / sizeof *fronts); ++k) {
            double raw, shifted, shift;
            if (fabs(fronts[k].aspect - n2) > 1e-9) continue;
            compare(s, s->Z, "front Z", &fronts[k], &raw, &shifted, &shift);
            if (k == 0 || fronts[k].aspect == 1) { worst_raw = raw; worst_shifted = shifted; }
        }
        for (k = 0; k < (int)(sizeof heights / sizeof *heights); ++k) {
            double raw, shifted, shift;
            if (fabs(heights[k].aspect - n2) < 1e-9) compare(s, s->H, "height at the left wall H", &heights[k], &raw, &shifted, &shift);
        }
    }
    printf("RESULT case=dam_break2d dp=%g aspect=%g tank=%g c0=%g start=%s walls=%s viscosity=%g t=%.4g T=%.4f front_Z=%.4f "
           "mm_worst_T1-3=%.2f%% mm_worst_shifted_T1-3=%.2f%% energy=%.6g min_spacing=%.3f %s particles=%d steps=%ld advection_steps=%ld "
           "wall_s=%.2f out=%s\n",
           dp, s->sc.height / s->sc.width, s->sc.tank / s->sc.width, c0, start_at_rest ? "zero" : "hydrostatic", no_slip ? "no-slip" : "free-slip", viscosity, (double)d.time,
           s->n ? s->T[s->n - 1] : 0, s->n ? s->Z[s->n - 1] : 0, 100 * worst_raw, 100 * worst_shifted,
           (double)(d.kinetic_energy + d.strain_energy + d.potential_energy + d.contact_energy), s->output.min_spacing, common_result_fields(&c),
           sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall, c.out);
    sps_world_destroy(w);
    free(s);
    return 0;
}
