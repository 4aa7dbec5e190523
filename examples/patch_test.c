/* patch_test.c - patch test stability, benchmark D1 (TL section 4.1; bench/VALIDATION.md).

   A free 1 x 1 patch (rho 1, E 1, nu 0.3, plane strain; Saint Venant-Kirchhoff, which is TL
   eq. 19) of irregular particles (a lattice of --n x --n points, each coordinate jittered by
   U(-j/2, j/2) dp; the paper: 444 Voronoi cells) with about 12 neighbours (h = dp, support 2 dp:
   pi 2^2 = 12.6), stretched isotropically by 10 % about its centre and let go: it breathes. We
   count the breathing periods from the zero crossings of the mean radial strain
   s(t) = mean_i (x_i - x_c).(X_i - X_c)/|X_i - X_c|^2 - 1, report its period, and stop when the
   particle motion is no longer coherent: the hourglass indicator (DIAGNOSTICS) above --fail
   (default 0.05, 5 % of the spacing per unit distance) or a step failing. The paper: with
   alpha = 50 stable for hundreds of periods, stiffening about 3 %; with alpha = 0 disordered
   after the first contraction and dominated by artefacts after eight.

   Build: make examples   Run: ./build/patch_test --alpha 50 --periods 300; ./build/patch_test --alpha 0
   Measured (bench/VALIDATION.md): alpha 0 stops at once (0.06 s); alpha 50 (the variational
   hourglass force) after 37 periods (103 on the regular lattice, --jitter 0) with its energy
   kept (-0.7 % over 300 periods with --fail 10); with --artificial-viscosity 0.005 it runs 300 periods
   (indicator at most 0.038); --hourglass paper (TL eq. 32) stops after 3.4 periods (17.5
   regular), its force feeding energy in.
   Smoke: patch_test --n 8 --tend 0.05 */
#include "common.h"
#include "scenes/scene.h"

typedef struct {
    output_plan output;
    double fail, hourglass_max, last_s, last_t, t_fail, crossing_first, crossing_last;
    int crossings, failed;
    const int* ids;
} run_state;

/* The mean radial strain s(t) about the centre (0.5, 0.5). */
static double radial_strain(const sps_world* w) {
    const int n = sps_world_particle_count(w);
    double s = 0;
    int id;
    for (id = 0; id < n; ++id) {
        sps_particle_state p;
        double X[2], x[2];
        sps_world_particle(w, id, &p);
        X[0] = p.position[0] - p.displacement[0] - 0.5;
        X[1] = p.position[1] - p.displacement[1] - 0.5;
        x[0] = p.position[0] - 0.5;
        x[1] = p.position[1] - 0.5;
        if (X[0] * X[0] + X[1] * X[1] > 1e-6) s += (x[0] * X[0] + x[1] * X[1]) / (X[0] * X[0] + X[1] * X[1]) - 1;
    }
    return s / n;
}

static int on_step(sps_world* w, void* user) {
    run_state* st = (run_state*)user;
    sps_diagnostics d;
    char extra[64];
    const double t = sps_world_time(w), s = radial_strain(w);
    if (t > 0 && (st->last_s > 0) != (s > 0)) { /* a zero crossing of s, interpolated linearly */
        const double tc = st->last_t + (t - st->last_t) * st->last_s / (st->last_s - s);
        if (st->crossings == 0) st->crossing_first = tc;
        st->crossing_last = tc;
        st->crossings++;
    }
    st->last_s = s;
    st->last_t = t;
    snprintf(extra, sizeof extra, ",%.9g", s);
    if (output_tick(w, &st->output, extra, &d)) {
        if (d.hourglass > st->hourglass_max) st->hourglass_max = d.hourglass;
        if (d.hourglass > st->fail) {
            st->failed = 1;
            st->t_fail = t;
            return 1; /* no longer coherent: stop */
        }
    }
    return 0;
}

/* Stretches x = c + 1.1 (X - c) about the centre c = (0.5, 0.5). */
static void stretch(sps_world* w, double f) {
    int id;
    for (id = 0; id < sps_world_particle_count(w); ++id) {
        sps_particle_state p;
        sps_real x[3] = {0, 0, 0};
        sps_world_particle(w, id, &p);
        x[0] = (sps_real)(0.5 + f * (p.position[0] - 0.5));
        x[1] = (sps_real)(0.5 + f * (p.position[1] - 0.5));
        sps_world_set_particle(w, id, x, NULL);
    }
}

/* The n x n jittered points of the patch, each with the Shepard volume V_i = 1 / sum_j W_ij
   (itself included), scaled so that they add up to the patch's area 1: irregular points with
   volumes that fit them, as the paper's Voronoi cells do. Without jitter: the lattice, dp^2 each. */
static void add_patch(sps_world* w, sps_body patch, int n, double jitter, int seed) {
    sps_world* probe;
    sps_body b;
    sps_world_def wd = *sps_world_get_def(w);
    sps_body_def bd = sps_default_body_def();
    sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0}, *xyz, *vol;
    const sps_real* x[2];
    double total = 0;
    int i, j, m;
    if (jitter == 0) {
        sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0};
        sps_body_add_box(w, patch, lo, hi, NULL);
        return;
    }
    sps_world_create(&wd, &probe); /* the jittered points, from scene_add_box */
    ex_unset_unread(&bd);
    sps_world_add_body(probe, &bd, &b);
    scene_add_box(probe, b, lo, hi, jitter, seed);
    m = sps_world_particle_count(probe);
    x[0] = sps_world_field_by_name(probe, "position_x", NULL);
    x[1] = sps_world_field_by_name(probe, "position_y", NULL);
    xyz = (sps_real*)calloc((size_t)3 * m, sizeof *xyz);
    vol = (sps_real*)calloc((size_t)m, sizeof *vol);
    if (!xyz || !vol || m != n * n) { fprintf(stderr, "patch_test: out of memory\n"); exit(1); }
    for (i = 0; i < m; ++i) {
        double sum = 0;
        for (j = 0; j < m; ++j) sum += sps_world_kernel(w, (sps_real)hypot(x[0][i] - x[0][j], x[1][i] - x[1][j]));
        xyz[3 * i] = x[0][i];
        xyz[3 * i + 1] = x[1][i];
        vol[i] = (sps_real)(1 / sum);
        total += vol[i];
    }
    for (i = 0; i < m; ++i) vol[i] = (sps_real)(vol[i] / total);
    sps_body_add_particles(w, patch, m, xyz, vol);
    free(xyz);
    free(vol);
    sps_world_destroy(probe);
}

int main(int argc, char** argv) {
    int n = 21, periods = 300;
    double alpha = 50, fail = 0.05, h_over_dp = 1;
    double artificial_viscosity = 0; /* TL artificial viscosity q1 (none: the paper's) */
    int hourglass_form = SPS_HOURGLASS_VARIATIONAL;
    common_options c = {.cfl = 0.4, .t_end = 0, .vtk_every = 0, .csv_every = 0.01, .E = 1, .nu = 0.3, .rho0 = 1,
                        .out = "out/patch_test", .jitter = 0.4, .seed = 1, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"n", OPT_INT, &n, "particles per side (n^2 in all; 21: 441, the paper 444)", 4, 400, NULL},
        {"alpha", OPT_REAL, &alpha, "hourglass coefficient alpha (TL eq. 32)", 0, 1000, NULL},
        EX_HOURGLASS_OPTIONS(hourglass_form, artificial_viscosity),
        {"periods", OPT_INT, &periods, "breathing periods to run (the end time is periods x the period estimate)", 1, 100000, NULL},
        {"h", OPT_REAL, &h_over_dp, "smoothing length / dp (1: support 2 dp, about 12 neighbours)", 0.8, 3, NULL},
        {"fail", OPT_REAL, &fail, "stop when the hourglass indicator exceeds this", 1e-6, 10, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body patch;
    sps_real c0, K, G;
    run_state st;
    double wall, period = 0, estimate;

    ex_options(argc, argv, "patch test stability (benchmark D1, bench/VALIDATION.md)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    wd.dim = 2;
    wd.dp = (sps_real)(1.0 / n);
    wd.h_over_dp = (sps_real)h_over_dp; /* 1: support 2 dp, about 12 neighbours, as the paper's */
    wd.max_substeps = 4; /* a sample of s(t) every 4 sub-steps (about 1/150 of a period) for the crossings */
    wd.energy_growth_limit = (sps_real)INFINITY; /* the hourglass force is not in the energy account */
    bd.name = "patch";
    bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
    bd.material.kind = SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF;
    bd.material.tl.hourglass_alpha = (sps_real)alpha;
    bd.material.tl.hourglass = (sps_hourglass)hourglass_form;
    bd.material.tl.artificial_viscosity = (sps_real)artificial_viscosity;
    sps_world_create(&wd, &w);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &patch);
    add_patch(w, patch, n, c.jitter, c.seed);
    stretch(w, 1.1);
    sps_body_material_constants(w, patch, &c0, &G, &K);
    /* the breathing period is of order the time a P wave needs to cross the patch and back */
    estimate = 2.0 / sqrt((K + 4 * G / 3) / c.rho0);
    if (c.t_end <= 0) c.t_end = periods * estimate * 1.2;

    memset(&st, 0, sizeof st);
    st.fail = fail; st.last_s = 0.1;
    output_open(&st.output, &c, "patch_test", "velocity", ",radial_strain");
    on_step(w, &st); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &st);
    wall = output_close(w, &st.output);
    if (st.crossings >= 3) period = 2 * (st.crossing_last - st.crossing_first) / (st.crossings - 1);
    printf("RESULT case=patch_test alpha=%g hourglass=%s artificial_viscosity=%g n=%d jitter=%g particles=%d period=%.6f periods_run=%.1f failed=%d t_fail=%.4g "
           "periods_at_fail=%.1f hourglass_max=%.3g paper_stiffening=3%% %s steps=%ld wall_s=%.2f out=%s\n",
           alpha, ex_hourglass_name(hourglass_form), artificial_viscosity, n, c.jitter, sps_world_particle_count(w), period, period > 0 ? sps_world_time(w) / period : 0, st.failed, st.t_fail,
           st.failed && period > 0 ? st.t_fail / period : 0, st.hourglass_max, common_result_fields(&c), (long)0, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
