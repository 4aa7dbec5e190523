/* punch2d.c - 2D punch test, benchmark A8 (ENO 6.6; Lee et al. 2013).

   A unit square rubber plate (rho0 1100, E 1.7e7, nu 0.45, plane strain) on rollers at the
   bottom, left and right (the first particle layer of each edge has its normal velocity held at
   0; the two bottom corners, on two rollers, are clamped); the right half of its top layer is
   punched down at v_punch = 100 m/s (horizontally free; the top-right corner, also on the right
   roller, has both held). The paper shows the deformed shape (Fig. 24, dp = 0.1) and the
   pressure and von Mises fields (Fig. 25, dp = 0.05) and asks for a smooth pressure, free of
   spurious modes; its text gives no numbers and the figures' times are not in the text. We
   report, every --shape-every seconds (default 1 ms): the punch depth, the height of the free
   top-left corner and of the highest point, the body's extent, the largest pressure and the
   pressure roughness: RMS over particles of (p_i - <p>_i)/max|p|, with <p>_i the Shepard kernel
   average of the neighbours' pressure (0 for a smooth field, O(1) for a checkerboard); plus
   the hourglass indicator and the smallest spacing. CSV: energies and these columns over time.

   Build: make examples     Run: ./build/punch2d --dp 0.05 --shear eno-a
   Expect: ENO-A smooth (roughness of a few %), OG rough or failing.
   Smoke: punch2d --dp 0.1 --tend 0.0005 */
#include "common.h"
#include "scenes/scene.h"

#define PUNCH2D_L 1.0
#define PUNCH2D_RHO0 1100
#define PUNCH2D_E 1.7e7
#define PUNCH2D_NU 0.45
#define PUNCH2D_V 100.0

#define CASE "punch2d"
#define MAX_SHAPES 64

/* Pressure smoothness: RMS over particles of (p_i - <p>_i) / max|p|, where <p>_i is the
   Shepard kernel average sum_{j != i} p_j W_ij / sum_{j != i} W_ij of the neighbours'
   pressure (current positions, world kernel). 0 for a linear or constant field inside;
   a checkerboard (spurious pressure mode) gives O(1). O(N^2): for the small punch plates. */
static double punch2d_pressure_roughness(const sps_world* w) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* p = sps_world_field(w, SPS_FIELD_PRESSURE);
    const sps_world_def* wd = sps_world_get_def(w);
    const double support = 2 * wd->h_over_dp * wd->dp;
    int n = sps_world_particle_count(w), i, j, m = 0;
    double pmax = 0, sum2 = 0;
    for (i = 0; i < n; ++i) pmax = fmax(pmax, fabs(p[i]));
    if (pmax == 0) return 0;
    for (i = 0; i < n; ++i) {
        double sw = 0, swp = 0;
        for (j = 0; j < n; ++j) {
            double dx = x[i] - x[j], dy = y[i] - y[j], r2 = dx * dx + dy * dy, wij;
            if (j == i || r2 >= support * support) continue;
            wij = sps_world_kernel(w, sqrt(r2));
            sw += wij;
            swp += wij * p[j];
        }
        if (sw > 0) {
            double d = (p[i] - swp / sw) / pmax;
            sum2 += d * d;
            ++m;
        }
    }
    return m ? sqrt(sum2 / m) : 0;
}

typedef struct {
    double t, depth, corner_y, max_y, min_x, max_x, min_y, pmax, pmin, rough;
} shape_row;

static shape_row measure(const sps_world* w, int corner_id, const int* punch_ids, int npunch) {
    shape_row s;
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* p = sps_world_field(w, SPS_FIELD_PRESSURE);
    int i, n = sps_world_particle_count(w);
    sps_particle_state ps;
    memset(&s, 0, sizeof s);
    s.t = sps_world_time(w);
    s.min_x = s.min_y = 1e30; s.max_x = s.max_y = -1e30; s.pmax = -1e30; s.pmin = 1e30;
    for (i = 0; i < n; ++i) {
        s.min_x = fmin(s.min_x, x[i]); s.max_x = fmax(s.max_x, x[i]);
        s.min_y = fmin(s.min_y, y[i]); s.max_y = fmax(s.max_y, y[i]);
        s.pmax = fmax(s.pmax, p[i]); s.pmin = fmin(s.pmin, p[i]);
    }
    sps_world_particle(w, corner_id, &ps);
    s.corner_y = ps.displacement[1];
    for (i = 0; i < npunch; ++i) {
        sps_world_particle(w, punch_ids[i], &ps);
        s.depth += -ps.displacement[1] / npunch;
    }
    s.rough = punch2d_pressure_roughness(w);
    return s;
}

int main(int argc, char** argv) {
    double dp = 0.05, v_punch = PUNCH2D_V;
    double shape_every = 0.001;
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 0.004, .vtk_every = 0.001, .csv_every = 0.0001,
                        .E = PUNCH2D_E, .nu = PUNCH2D_NU, .rho0 = PUNCH2D_RHO0, .out = "out/" CASE, .jitter = 0, .seed = 1,
                        .contact_rest = SPS_CONTACT_REST_KERNEL /* the papers' contact law */, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (paper: 0.1 and 0.05)", 0.005, 0.25, NULL},
        {"vpunch", OPT_REAL, &v_punch, "punch speed [m/s], downwards", 0, 1e4, NULL},
        {"shape-every", OPT_REAL, &shape_every, "interval of the shape and pressure report [s]", 1e-6, 1e4, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body plate;
    sps_diagnostics d;
    output_plan output;
    shape_row shapes[MAX_SHAPES], last;
    int nshapes = 0, corner_id, *punch_ids, npunch = 0, i, k = 0, kshape = 1;
    double wall, rough_max = 0;
    char fields[4096];
    size_t len = 0;

    ex_options(argc, argv, "2D punch test (benchmark A8, ENO 6.6)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (ex_check_step) */
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    sps_world_create(&wd, &w);
    bd.name = "plate";
    sps_world_add_body(w, &bd, &plate);
    { /* the plate [0, L]^2 on rollers, pressed by the punch; an edge layer: reference centre within dp/2 + e of the edge */
        const double L = PUNCH2D_L, e = 0.5 * dp;
        sps_real lo[3] = {0, 0, 0}, hi[3] = {L, L, 0}, down[3] = {0, 0, 0};
        sps_real bottom_lo[3] = {-1, -1, -1}, bottom_hi[3] = {2, dp / 2 + e, 1};
        sps_real left_lo[3] = {-1, -1, -1}, left_hi[3] = {dp / 2 + e, 2, 1};
        sps_real right_lo[3] = {L - dp / 2 - e, -1, -1}, right_hi[3] = {2, 2, 1};
        sps_real punch_lo[3] = {L / 2, L - dp / 2 - e, -1}, punch_hi[3] = {2, 2, 1};
        sps_real corner1_lo[3] = {-1, -1, -1}, corner1_hi[3] = {dp / 2 + e, dp / 2 + e, 1};
        sps_real corner2_lo[3] = {L - dp / 2 - e, -1, -1}, corner2_hi[3] = {2, dp / 2 + e, 1};
        sps_real corner3_lo[3] = {L - dp / 2 - e, L - dp / 2 - e, -1}, corner3_hi[3] = {2, 2, 1};
        down[1] = -v_punch;
        scene_add_box(w, plate, lo, hi, c.jitter, c.seed);
        /* rollers: the bottom layer's v_y and the left and right layers' v_x held at 0 */
        sps_body_constrain_box(w, plate, bottom_lo, bottom_hi, SPS_AXIS_Y, NULL, NULL);
        sps_body_constrain_box(w, plate, left_lo, left_hi, SPS_AXIS_X, NULL, NULL);
        sps_body_constrain_box(w, plate, right_lo, right_hi, SPS_AXIS_X, NULL, NULL);
        /* the punch: the top layer of the right half moves down at v_punch (horizontally free) */
        sps_body_constrain_box(w, plate, punch_lo, punch_hi, SPS_AXIS_Y, down, NULL);
        /* the corners on two constraints: the bottom two clamped, the top-right one moving with the punch */
        sps_body_constrain_box(w, plate, corner1_lo, corner1_hi, SPS_AXIS_ALL, NULL, NULL);
        sps_body_constrain_box(w, plate, corner2_lo, corner2_hi, SPS_AXIS_ALL, NULL, NULL);
        sps_body_constrain_box(w, plate, corner3_lo, corner3_hi, SPS_AXIS_ALL, down, NULL);
    }
    { /* the free top-left corner and the punch particles (top layer, x > 1/2), by reference position */
        sps_real corner[3] = {0.5 * dp, PUNCH2D_L - 0.5 * dp, 0};
        const sps_real *rx = sps_world_field(w, SPS_FIELD_REFERENCE_X), *ry = sps_world_field(w, SPS_FIELD_REFERENCE_Y);
        const int* ids = sps_world_particle_ids(w);
        int n = sps_world_particle_count(w);
        if ((corner_id = sps_world_nearest_particle(w, plate, corner)) < 0) ex_check(w, SPS_ERR_INVALID_ARG);
        if (!(punch_ids = (int*)malloc(sizeof(int) * (size_t)n))) { fprintf(stderr, "%s: out of memory\n", g_prog); return 2; }
        for (i = 0; i < n; ++i)
            if (rx[i] > PUNCH2D_L / 2 && ry[i] > PUNCH2D_L - dp) punch_ids[npunch++] = ids[i];
    }

    output_open(&output, &c, CASE, "pressure",
                ",punch_depth,corner_uy,max_y,pressure_max,pressure_min,pressure_roughness");
    for (;;) {
        double t = sps_world_time(w);
        char extra[256];
        last = measure(w, corner_id, punch_ids, npunch);
        if (last.rough > rough_max) rough_max = last.rough;
        snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g,%.9g,%.9g,%.6g", last.depth, last.corner_y, last.max_y, last.pmax, last.pmin, last.rough);
        output_tick(w, &output, extra, &d);
        if (t >= kshape * shape_every - 1e-12 && nshapes < MAX_SHAPES) { shapes[nshapes++] = last; ++kshape; }
        if (t >= (sps_real)c.t_end) break; /* the world's clock is an sps_real: a float 2e-4 is below the double */
        ex_check_step(w, sps_world_advance(w, (sps_real)fmin(++k * c.csv_every, c.t_end), NULL, NULL), &output); /* to the next CSV row */
    }
    wall = output_close(w, &output);
    for (i = 0; i < nshapes && len < sizeof fields - 200; ++i)
        len += (size_t)snprintf(fields + len, sizeof fields - len,
                                " t%d=%.4g depth%d=%.4f corner_uy%d=%.4f max_y%d=%.4f extent%d=%.4f:%.4fx%.4f:%.4f pmax%d=%.4g pmin%d=%.4g rough%d=%.4f",
                                i + 1, shapes[i].t, i + 1, shapes[i].depth, i + 1, shapes[i].corner_y, i + 1, shapes[i].max_y, i + 1,
                                shapes[i].min_x, shapes[i].max_x, shapes[i].min_y, shapes[i].max_y, i + 1, shapes[i].pmax, i + 1,
                                shapes[i].pmin, i + 1, shapes[i].rough);
    printf("RESULT case=%s shear=%s dp=%g vpunch=%g nu=%g stepping=%s jitter=%g punched=%d depth_end=%.4f corner_uy_end=%.4f "
           "max_y_end=%.4f pressure_roughness_end=%.4f pressure_roughness_max=%.4f paper=smooth_pressure paper_dp=0.1,0.05 "
           "hourglass_max=%.3g hourglass_end=%.3g min_spacing=%.3f%s kinetic_end=%.6g strain_end=%.6g %s particles=%d steps=%ld "
           "wall_s=%.2f out=%s\n",
           CASE, shear_name(c.shear), dp, v_punch, c.nu, c.stepping ? "single" : "dual", c.jitter, npunch, last.depth,
           last.corner_y, last.max_y, last.rough, rough_max, output.hourglass_max, (double)d.hourglass, output.min_spacing, fields,
           (double)d.kinetic_energy, (double)d.strain_energy, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps,
           wall, c.out);
    free(punch_ids);
    sps_world_destroy(w);
    return 0;
}
