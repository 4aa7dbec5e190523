/* ball_plate2d.c - a rubber ball hitting a plate held at both ends, benchmark A9 (ENO 6.7); built
   with -DBALL_PLATE_DIM=3 as build/ball_plate3d, benchmark A10 (ENO 6.8: plate 0.5 x 0.02 x 0.5
   held on its four edges, v0 = 0.12 c0 and dp 0.01 by default; the paper's dp is 0.0025).

   Ball radius 0.05 centred 0.1 above the plate's centre, moving down at v0 = --v0 c0 (c0 =
   372.68 m/s); plate 0.5 x 0.02 (3D: 0.5 x 0.02 x 0.5) clamped beyond its ends (3D: its four
   edges); rho0 1200, E 1e7, nu 0.49 for both. The bodies touch
   through the library's contact. The ball is body-fitted (sps_body_add_sdf_relaxed, --fill
   relaxed) or a lattice cut by the sphere (--fill lattice).
   We report the hourglass indicator and minimum spacing (max / min over the run and at the
   end, world and plate), per-body energies (CSV), the total energy (kinetic + strain) at the
   start and end and its largest rise (the strain energy's small-strain formula over-reads at
   large deflection: see bench/results/contact_a.md), the largest kinetic energy over the run
   relative to the starting energy (kinetic_max_rel: above 1 only if energy was created), the smallest distance between ball and plate particles
   over the run (in dp), the ball's momentum before and after (the system is held by its clamps:
   its total momentum is not conserved), the wall time. The paper shows pictures only: OG
   zigzags and fractures at 0.02 c0, OAS zigzags (and fractures from t = 0.012 at 0.06 c0),
   ENO stays smooth up to 0.12 c0.

   Build: make examples        Run: ./build/ball_plate2d --v0 0.02 --shear eno-a
   Expect: the ball bounces off; for ENO-A the hourglass indicator stays ~1e-3, the gap above
   0.5 dp and the total energy below its start.
   Smoke: ball_plate2d --dp 0.01 --v0 0.12 --tend 0.0015
   Smoke: ball_plate3d --dp 0.02 --v0 0.12 --tend 0.0015 */
#include "common.h"
#include "scenes/ball_plate.h"
#include <stdlib.h>

#ifndef BALL_PLATE_DIM
#define BALL_PLATE_DIM 2
#endif
#if BALL_PLATE_DIM == 3
#define BP_NAME "ball_plate3d"
#define BP_ABOUT "3D rubber ball hitting a plate held on its four edges (benchmark A10, ENO 6.8)"
#else
#define BP_NAME "ball_plate2d"
#define BP_ABOUT "2D rubber ball hitting a plate held at both ends (benchmark A9, ENO 6.7)"
#endif

/* The smallest distance between a particle of body a and one of body b, in dp (brute force over
   the particles of each within the other's bounding box widened by 3 dp); 1e30 if none is that
   close, -1 before the first step (the bodies' ranges are not known yet). */
static double ball_plate_min_gap(const sps_world* w, sps_body a, sps_body b) {
    const int dim = sps_world_get_def(w)->dim;
    const double dp = sps_world_get_def(w)->dp, m = 3 * dp;
    const sps_real* x = sps_world_field(w, SPS_FIELD_POSITION_X);
    const sps_real* y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* z = dim == 3 ? sps_world_field(w, SPS_FIELD_POSITION_Z) : NULL;
    int fa, na, fb, nb, i, j, k, ns[2] = {0, 0}, *sel[2];
    double box[2][6], best = 1e30;
    if (!sps_body_field(w, a, "mass", NULL, &fa, &na) || !sps_body_field(w, b, "mass", NULL, &fb, &nb)) return -1;
    for (k = 0; k < 2; ++k) {
        int f = k ? fb : fa, n = k ? nb : na;
        box[k][0] = box[k][2] = box[k][4] = 1e30;
        box[k][1] = box[k][3] = box[k][5] = -1e30;
        for (i = f; i < f + n; ++i) {
            double p[3] = {x[i], y[i], z ? z[i] : 0};
            for (j = 0; j < 3; ++j) {
                if (p[j] < box[k][2 * j]) box[k][2 * j] = p[j];
                if (p[j] > box[k][2 * j + 1]) box[k][2 * j + 1] = p[j];
            }
        }
    }
    sel[0] = (int*)malloc(sizeof(int) * (size_t)(na + nb + 2));
    sel[1] = sel[0] + na + 1;
    for (k = 0; k < 2; ++k) { /* the particles of body k within the other's box */
        int f = k ? fb : fa, n = k ? nb : na;
        const double* o = box[1 - k];
        for (i = f; i < f + n; ++i) {
            double p[3] = {x[i], y[i], z ? z[i] : 0};
            int in = 1;
            for (j = 0; j < 3; ++j) in &= p[j] >= o[2 * j] - m && p[j] <= o[2 * j + 1] + m;
            if (in) sel[k][ns[k]++] = i;
        }
    }
    for (i = 0; i < ns[0]; ++i) {
        int p = sel[0][i];
        for (j = 0; j < ns[1]; ++j) {
            int q = sel[1][j];
            double dx = x[p] - x[q], dy = y[p] - y[q], dz = z ? z[p] - z[q] : 0, d2 = dx * dx + dy * dy + dz * dz;
            if (d2 < best) best = d2;
        }
    }
    free(sel[0]);
    return best < 1e30 ? sqrt(best) / dp : 1e30;
}

typedef struct {
    sps_body ball, plate;
    output_plan output;
    double t_end, e_start, e_max, ke_max, gap_min, t_gap_min, plate_hourglass_max, t_contact;
    int quiet, started;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d, db, dpl;
    char extra[256] = "";
    double t = sps_world_time(w), gap;
    if (t < s->output.next_csv - 1e-12) { progress(t, s->t_end, s->output.wall0, s->quiet); return 0; }
    sps_world_diagnostics(w, s->ball, &db);
    sps_world_diagnostics(w, s->plate, &dpl);
    gap = ball_plate_min_gap(w, s->ball, s->plate);
    if (gap >= 0 && gap < s->gap_min) { s->gap_min = gap; s->t_gap_min = t; }
    if (gap >= 0 && gap < 2.6 && s->t_contact < 0) s->t_contact = t; /* first pair within the support 2h = 2.6 dp */
    if (dpl.hourglass > s->plate_hourglass_max) s->plate_hourglass_max = dpl.hourglass;
    snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6g,%.9g", (double)db.kinetic_energy, (double)db.strain_energy,
             (double)(db.kinetic_energy + db.strain_energy), (double)dpl.kinetic_energy, (double)dpl.strain_energy,
             (double)(dpl.kinetic_energy + dpl.strain_energy), gap >= 0 && gap < 1e29 ? gap : -1, (double)db.linear_momentum[1]);
    if (output_tick(w, &s->output, extra, &d)) {
        double e = d.kinetic_energy + d.strain_energy;
        if (!s->started) { s->e_start = s->e_max = e; s->started = 1; }
        if (e > s->e_max) s->e_max = e;
        if (d.kinetic_energy > s->ke_max) s->ke_max = d.kinetic_energy;
    }
    return 0;
}

static const char* paper_expectation(int shear, double v0) {
    switch (shear) {
    case SPS_SHEAR_OG: return "zigzag_and_fracture(Fig27a)";
    case SPS_SHEAR_OAS: return v0 >= 0.06 - 1e-9 ? "zigzag_fracture_from_t0.012(Fig28a)" : "zigzag_no_fracture(Fig27b)";
    case SPS_SHEAR_ENO: case SPS_SHEAR_ENO_A: return "smooth(ENOG,Fig27c-29)";
    default: return "not_in_paper";
    }
}

int main(int argc, char** argv) {
    double dp = BALL_PLATE_DIM == 3 ? 0.01 : 0.0025, v0 = BALL_PLATE_DIM == 3 ? 0.12 : 0.02; /* v0 in units of c0 */
    int relax_iterations = 0;
    int fill = 0; /* relaxed|lattice */
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 0.015, .vtk_every = 0.001, .csv_every = 5e-5,
                        .E = BALL_PLATE_E, .nu = BALL_PLATE_NU, .rho0 = BALL_PLATE_RHO0, .out = "out/" BP_NAME, .jitter = 0, .seed = 1,
                        .contact_rest = SPS_CONTACT_REST_KERNEL /* the papers' contact law */, PNG_DEFAULTS};
    damping_options k = {0, 0};
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (paper: 0.0025)", 5e-4, 0.02, NULL},
        {"v0", OPT_REAL, &v0, "ball speed in units of c0 (paper: 0.02, 0.06, 0.12)", 0, 1, NULL},
        {"fill", OPT_CHOICE, &fill, "ball particles: body-fitted (sps_body_add_sdf_relaxed) or the lattice", 0, 0, "relaxed|lattice"},
        {"relax-iterations", OPT_INT, &relax_iterations, "shifting steps of the relaxed fill, 0 = the library's 300", 0, 100000, NULL},
        DAMPING_OPTION_SPECS(k),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    run_state s;
    sps_diagnostics d, db0, db, dpl;
    double wall, setup, c0, v0_ms, py0;
    sps_real c0r;

    ex_options(argc, argv, BP_ABOUT, opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    apply_damping(&k, &bd);
    memset(&s, 0, sizeof s);
    /* c0 of the material, for v0 in units of c0: K = E / (3 (1 - 2 nu)) */
    c0 = sqrt(c.E / (3 * (1 - 2 * c.nu)) / c.rho0);
    v0_ms = v0 * c0;
    setup = wall_seconds();
    {
        ball_plate_params p = {.dim = BALL_PLATE_DIM, .dp = dp, .v0 = v0_ms, .relaxed = fill == 0, .relax_iterations = relax_iterations};
        ball_plate_create(wd, &bd, &p, &w, &s.ball, &s.plate);
    }
    setup = wall_seconds() - setup;
    sps_body_material_constants(w, s.ball, &c0r, NULL, NULL);
    s.quiet = c.quiet; s.t_end = c.t_end; s.gap_min = 1e30; s.t_contact = -1;
    output_open(&s.output, &c, BP_NAME, "von-mises-or-velocity",
                ",ball_kinetic,ball_strain,ball_total,plate_kinetic,plate_strain,plate_total,min_gap_dp,ball_momentum_y");
    sps_world_diagnostics(w, s.ball, &db0);
    py0 = db0.linear_momentum[1];
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    {
        sps_body all = {0};
        double e_end;
        sps_world_diagnostics(w, all, &d);
        sps_world_diagnostics(w, s.ball, &db);
        sps_world_diagnostics(w, s.plate, &dpl);
        e_end = d.kinetic_energy + d.strain_energy;
        printf("RESULT case=%s shear=%s v0=%g v0_ms=%.4f c0=%.2f dp=%g fill=%s tend=%g hourglass_max=%.3g hourglass_end=%.3g "
               "plate_hourglass_max=%.3g plate_hourglass_end=%.3g min_spacing=%.3f min_spacing_end=%.3f energy_start=%.6g "
               "energy_end=%.6g energy_end_rel=%.2f%% energy_max_rise=%.3f%% energy_ok=%s kinetic_max_rel=%.4f ball_kinetic_end=%.6g ball_strain_end=%.6g "
               "plate_kinetic_end=%.6g plate_strain_end=%.6g min_gap_dp=%.3f t_min_gap=%.5f gap_ok=%s t_contact=%.5f "
               "ball_py_start=%.6g ball_py_end=%.6g rebound=%.3f paper=%s %s particles=%d steps=%ld advection_steps=%ld "
               "us_per_step=%.1f setup_s=%.2f wall_s=%.2f%s out=%s\n",
               BP_NAME, shear_name(c.shear), v0, v0_ms, (double)c0r, dp, fill ? "lattice" : "relaxed", c.t_end,
               s.output.hourglass_max, (double)d.hourglass, s.plate_hourglass_max, (double)dpl.hourglass, s.output.min_spacing,
               (double)d.min_spacing, s.e_start, e_end, 100 * (e_end - s.e_start) / s.e_start,
               100 * (s.e_max - s.e_start) / s.e_start, s.e_max <= 1.01 * s.e_start ? "yes" : "NO", s.ke_max / s.e_start, (double)db.kinetic_energy,
               (double)db.strain_energy, (double)dpl.kinetic_energy, (double)dpl.strain_energy, s.gap_min < 1e29 ? s.gap_min : -1,
               s.t_gap_min, s.gap_min > 0.5 ? "yes" : "NO", s.t_contact, py0, (double)db.linear_momentum[1],
               py0 != 0 ? -db.linear_momentum[1] / py0 : 0, paper_expectation(c.shear, v0), common_result_fields(&c),
               sps_world_particle_count(w), d.acoustic_steps, d.advection_steps,
               d.acoustic_steps > 0 ? 1e6 * wall / (double)d.acoustic_steps : 0, setup, wall, damping_result_fields(&k), c.out);
    }
    sps_world_destroy(w);
    return 0;
}
