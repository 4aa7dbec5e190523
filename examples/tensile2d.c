/* tensile2d.c - tensile test, benchmark A7 (ENO 6.5, after Lee et al. 2013).

   A unit square plate (rho0 7000, E 2.1e10, nu 0.3, plane strain; c0 = 1581 m/s) has its bottom
   edge fixed and its top edge pulled up at v_pull = 500 m/s (its holders: a
   clamped one below y = 0, one moving at (0, v_pull) above y = 1). We report the
   extent of the plate (width of the row at mid height, height, the narrowest row: the neck) at
   t = 0.25, 0.5, ... ms up to --tend, and the hourglass indicator and minimum spacing. The
   paper compares shapes only (its Fig. 22 against FEM and CCFVM, no times in the text), so the
   RESULT line gives our figures and the paper's finding (smooth, no fracture, no zigzag).

   Build: make examples        Run: ./build/tensile2d --dp 0.0666667 --shear eno-a
   Expect: the plate necks smoothly (width at mid height shrinking as it stretches), hourglass
   indicator ~1e-3 for ENO-A; OG zigzags.
   Smoke: tensile2d --dp 0.1 --tend 0.0002 --report-every 0.0001 */
#include "common.h"

#define TENSILE2D_L 1.0
#define TENSILE2D_RHO0 7000
#define TENSILE2D_E 2.1e10
#define TENSILE2D_NU 0.3
#define TENSILE2D_HOLDER_LAYERS 4 /* more than the kernel support (2.6 dp) */

#define TENSILE2D_MAX_REPORTS 16

/* The deformed extent of the plate proper (reference 0 <= y <= L): the width of the row of
   particles nearest mid height (max x - min x, plus dp for the particles' own extent), its
   height (max y - min y, plus dp) and the narrowest row width over all rows (the neck). */
static void tensile2d_extent(const sps_world* w, double* width_mid, double* height, double* neck) {
    const double dp = sps_world_get_def(w)->dp;
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* y0 = sps_world_field(w, SPS_FIELD_REFERENCE_Y);
    int n = sps_world_particle_count(w), i, rows = (int)floor(TENSILE2D_L / dp + 0.5), k;
    double ylo = 1e30, yhi = -1e30, *rlo, *rhi, ymid = 0.5 * TENSILE2D_L, best = 1e30;
    int kmid = 0;
    rlo = (double*)malloc(sizeof(double) * 2 * (size_t)rows);
    rhi = rlo + rows;
    for (k = 0; k < rows; ++k) { rlo[k] = 1e30; rhi[k] = -1e30; }
    for (k = 0; k < rows; ++k) /* the row whose reference y is nearest mid height */
        if (fabs((k + 0.5) * dp - ymid) < best) { best = fabs((k + 0.5) * dp - ymid); kmid = k; }
    for (i = 0; i < n; ++i) {
        if (y0[i] < 0 || y0[i] > TENSILE2D_L) continue;
        k = (int)floor(y0[i] / dp);
        if (k < 0 || k >= rows) continue;
        if (y[i] < ylo) ylo = y[i];
        if (y[i] > yhi) yhi = y[i];
        if (x[i] < rlo[k]) rlo[k] = x[i];
        if (x[i] > rhi[k]) rhi[k] = x[i];
    }
    *width_mid = rhi[kmid] - rlo[kmid] + dp;
    *height = yhi - ylo + dp;
    *neck = 1e30;
    for (k = 0; k < rows; ++k)
        if (rhi[k] >= rlo[k] && rhi[k] - rlo[k] + dp < *neck) *neck = rhi[k] - rlo[k] + dp;
    free(rlo);
}

typedef struct {
    output_plan output;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[96];
    double width, height, neck;
    tensile2d_extent(w, &width, &height, &neck);
    snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g", width, height, neck);
    output_tick(w, &s->output, extra, &d);
    return 0;
}

int main(int argc, char** argv) {
    double dp = 1.0 / 15, v_pull = 500; /* the paper's */
    double report_every = 2.5e-4;
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 1e-3, .vtk_every = 2.5e-4, .csv_every = 1e-5,
                        .E = TENSILE2D_E, .nu = TENSILE2D_NU, .rho0 = TENSILE2D_RHO0, .out = "out/tensile2d", .jitter = 0, .seed = 1,
                        PNG_DEFAULTS};
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m], rounded to L/n (paper: 1/15 = 0.0666667 and 0.025)", 0.002, 0.25, NULL},
        {"vpull", OPT_REAL, &v_pull, "velocity of the top edge [m/s]", 0, 1e4, NULL},
        {"report-every", OPT_REAL, &report_every, "interval of the extents in the RESULT line [s]", 1e-6, 1, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body plate;
    run_state s;
    char reports[TENSILE2D_MAX_REPORTS * 64] = "";
    size_t len = 0;
    double wall, t_next;
    int k;

    ex_options(argc, argv, "tensile test of a unit square (benchmark A7, ENO 6.5)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (ex_check_step) */
    dp = TENSILE2D_L / floor(TENSILE2D_L / dp + 0.5); /* a whole number across L: --dp 0.0666667 is 1/15, not 14 columns */
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    sps_world_create(&wd, &w);
    bd.name = "plate";
    sps_world_add_body(w, &bd, &plate);
    { /* the plate [0, L]^2 and its holders: clamped below y = 0, pulled up at v_pull above y = L */
        const double hl = TENSILE2D_HOLDER_LAYERS * dp;
        sps_real lo[3] = {0, -hl, 0}, hi[3] = {TENSILE2D_L, TENSILE2D_L + hl, 0};
        sps_real bottom_lo[3] = {-1, -1, -1}, bottom_hi[3] = {2, 0, 1}, top_lo[3] = {-1, TENSILE2D_L, -1}, top_hi[3] = {2, 3, 1};
        sps_real pull[3] = {0, 0, 0};
        pull[1] = v_pull;
        sps_body_add_box(w, plate, lo, hi, NULL);
        sps_body_constrain_box(w, plate, bottom_lo, bottom_hi, SPS_AXIS_ALL, NULL, NULL);
        sps_body_constrain_box(w, plate, top_lo, top_hi, SPS_AXIS_ALL, pull, NULL);
    }
    memset(&s, 0, sizeof s);

    output_open(&s.output, &c, "tensile2d", "von-mises-or-velocity", ",width_mid,height,neck");
    on_step(w, &s);
    for (k = 1; k <= TENSILE2D_MAX_REPORTS && (t_next = k * report_every) <= c.t_end * (1 + 1e-9); ++k) {
        double width, height, neck;
        sps_result r = sps_world_advance(w, t_next, on_step, &s);
        ex_check_step(w, r, &s.output);
        tensile2d_extent(w, &width, &height, &neck);
        len += (size_t)snprintf(reports + len, sizeof reports - len, " width_%gms=%.4f height_%gms=%.4f neck_%gms=%.4f", 1e3 * t_next,
                                width, 1e3 * t_next, height, 1e3 * t_next, neck);
    }
    if (sps_world_time(w) < c.t_end) {
        sps_result r = sps_world_advance(w, c.t_end, on_step, &s);
        ex_check_step(w, r, &s.output);
    }
    wall = output_close(w, &s.output);
    {
        sps_diagnostics d;
        sps_world_diagnostics(w, plate, &d);
        printf("RESULT case=tensile2d shear=%s dp=%.6g vpull=%g tend=%g%s hourglass_max=%.3g hourglass_end=%.3g min_spacing=%.3f "
               "min_spacing_end=%.3f kinetic_end=%.6g strain_end=%.6g paper=smooth_no_fracture_no_zigzag paper_ref=FEM_shape(Fig22) "
               "%s particles=%d steps=%ld advection_steps=%ld wall_s=%.2f out=%s\n",
               shear_name(c.shear), (double)sps_world_get_def(w)->dp, v_pull, c.t_end, reports, s.output.hourglass_max, (double)d.hourglass,
               s.output.min_spacing, (double)d.min_spacing, (double)d.kinetic_energy, (double)d.strain_energy,
               common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall, c.out);
    }
    sps_world_destroy(w);
    return 0;
}
