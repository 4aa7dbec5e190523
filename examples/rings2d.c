/* rings2d.c - two rubber rings thrown at each other, benchmark A5 (ENO 6.3; bench/VALIDATION.md).

   Rings of inner radius 0.03 and outer radius 0.04 (rho0 1200, E 1e7, nu 0.4), centres 0.09
   apart, each moving towards the other at v0 = 0.06 c0 (--v0), collide, bounce and fly apart
   (set-up: scenes/rings2d.h). The right ring is the mirror image of the left one. We print each
   ring's kinetic energy at the start next to the analytical 1/2 m v0^2 (65.97 J/m at 0.06 c0),
   the largest relative difference between the two rings' energies, the total energy at the
   start and the end next to the paper's (65.88 and 55.61 J/m per ring, ENO Fig. 12), the time
   of the kinetic-energy minimum (paper: about 0.005 s), the hourglass indicator, the smallest
   spacing and the smallest gap between the rings.

   Build: make examples        Run: ./build/rings2d --v0 0.06 --shear eno-a
   Expect: about a minute at the paper's dp = 0.001 on 2 cores; --dp 0.002 for a quick look.
   Smoke: rings2d --dp 0.004 --tend 0.002 --iterations 20 */
#include "common.h"
#include "scenes/rings2d.h"

typedef struct {
    sps_body left, right;
    output_plan output;
    double dp;
    double ke0, energy0, energy_max, kinetic_min, kinetic_min_t, mirror_err, gap_min;
} run_state;

/* The smallest distance between the rings [dp], from the particles near the plane of symmetry. */
static double rings_gap(const sps_world* w, double dp) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const int n = sps_world_particle_count(w);
    double best = 1e30;
    int i, j;
    for (i = 0; i < n; ++i) {
        if (!(x[i] < 0 && x[i] > -5 * dp)) continue;
        for (j = 0; j < n; ++j) {
            double d2;
            if (!(x[j] >= 0 && x[j] < 5 * dp)) continue;
            d2 = (double)(x[i] - x[j]) * (x[i] - x[j]) + (double)(y[i] - y[j]) * (y[i] - y[j]);
            if (d2 < best * best * dp * dp) best = sqrt(d2) / dp;
        }
    }
    return best;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d, dl, dr;
    char extra[160];
    double t = sps_world_time(w), e, el, er, gap;
    sps_world_diagnostics(w, s->left, &dl);
    sps_world_diagnostics(w, s->right, &dr);
    el = dl.kinetic_energy + dl.strain_energy;
    er = dr.kinetic_energy + dr.strain_energy;
    e = el + er;
    if (s->energy0 == 0) { s->energy0 = e; s->ke0 = dl.kinetic_energy; }
    if (e > s->energy_max) s->energy_max = e;
    if (dl.kinetic_energy < s->kinetic_min || s->kinetic_min < 0) { s->kinetic_min = dl.kinetic_energy; s->kinetic_min_t = t; }
    if (fabs(el - er) / el > s->mirror_err) s->mirror_err = fabs(el - er) / el;
    gap = rings_gap(w, s->dp);
    if (gap < s->gap_min) s->gap_min = gap;
    snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g,%.9g,%.5g", (double)dl.kinetic_energy, (double)dl.strain_energy,
             (double)dr.kinetic_energy, (double)dr.strain_energy, gap);
    output_tick(w, &s->output, extra, &d);
    return 0;
}

int main(int argc, char** argv) {
    rings2d_params p = {.dp = 0.001, .v0_c0 = 0.06, .relaxed = 1, .iterations = 0};
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 0.012, .vtk_every = 0.001, .csv_every = 0.0001,
                        .E = RINGS2D_E, .nu = RINGS2D_NU, .rho0 = RINGS2D_RHO0, .out = "out/rings2d", .seed = 1, .contact_rest = SPS_CONTACT_REST_KERNEL /* the papers' contact law */, PNG_DEFAULTS};
    int fill = 0;
    damping_options k = {0, 0};
    opt_spec opts[] = {
        {"dp", OPT_REAL, &p.dp, "particle spacing [m]", 1e-4, 0.01, NULL},
        {"v0", OPT_REAL, &p.v0_c0, "speed of each ring [c0]", 0, 1, NULL},
        {"fill", OPT_CHOICE, &fill, "particles: body-fitted (sps_body_add_sdf_relaxed) or lattice", 0, 0, "relaxed|lattice"},
        {"iterations", OPT_INT, &p.iterations, "relaxation iterations, 0 = the library's default", 0, 100000, NULL},
        DAMPING_OPTION_SPECS(k),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    run_state s;
    sps_real c0;
    double ke_analytical, wall, e_end;

    ex_options(argc, argv, "two rubber rings colliding (benchmark A5, bench/VALIDATION.md)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    apply_damping(&k, &bd);
    p.relaxed = fill == 0;
    memset(&s, 0, sizeof s);
    s.kinetic_min = -1;
    s.gap_min = 1e30;
    s.dp = p.dp;
    rings2d_create(wd, &bd, &p, &w, &s.left, &s.right);
    sps_body_material_constants(w, s.left, &c0, NULL, NULL);
    ke_analytical = rings2d_kinetic_energy(p.v0_c0 * c0);

    output_open(&s.output, &c, "rings2d", "velocity", ",kinetic_left,strain_left,kinetic_right,strain_right,gap_dp");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    {
        sps_diagnostics d, dl;
        sps_body all = {0};
        sps_world_diagnostics(w, all, &d);
        sps_world_diagnostics(w, s.left, &dl);
        e_end = dl.kinetic_energy + dl.strain_energy;
        printf("RESULT case=rings2d shear=%s dp=%g v0=%g fill=%s ke0=%.4f ke0_analytical=%.4f energy_ring_start=%.4f energy_ring_end=%.4f "
               "paper_start=65.88 paper_end=55.61 energy_rise_max=%.3g%% mirror_err=%.3g ke_min=%.4f ke_min_t=%.5f paper_ke_min_t=0.005 "
               "momentum_x=%.3g hourglass_max=%.3g hourglass_end=%.3g min_spacing=%.3f gap_min=%.3f %s particles=%d steps=%ld "
               "advection_steps=%ld wall_s=%.2f%s out=%s\n",
               shear_name(c.shear), p.dp, p.v0_c0, p.relaxed ? "relaxed" : "lattice", s.ke0, ke_analytical, 0.5 * s.energy0, e_end, 100 * (s.energy_max - s.energy0) / s.energy0, s.mirror_err, s.kinetic_min,
               s.kinetic_min_t, (double)d.linear_momentum[0], s.output.hourglass_max, (double)d.hourglass, s.output.min_spacing,
               s.gap_min, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall,
               damping_result_fields(&k), c.out);
    }
    sps_world_destroy(w);
    return 0;
}
