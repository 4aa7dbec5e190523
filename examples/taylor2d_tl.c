/* taylor2d_tl.c - 2D Taylor impact with J2 plasticity in the total-Lagrangian frame, benchmark D5
   (TL section 4.5; bench/VALIDATION.md).

   An aluminium bar 3.91 mm x 23.46 mm (E 78.2 GPa, nu 0.3, rho0 2700, perfectly plastic with
   sigma_Y --yield, the paper's 1.0 GPa; plane strain), spacing 0.35 mm, kernel support 3
   spacings (h = 1.5 dp), hits a rigid frictionless wall (an analytic wall, CONTACT) at
   373 m/s. The model is the multiplicative J2 law of the TL frame (material.kind = J2 with the
   total-Lagrangian solver) and the hourglass force with the yield-strength switch (TL section
   4.5: a particle that has flowed uses sigma_Y instead of E in TL eq. 32). The paper shows
   pictures; we report the final length and the width of the mushroomed foot, the largest
   plastic strain, the rebound speed and the energy account (kinetic + strain + contact +
   plastic work against the impact energy).

   Build: make examples   Run: ./build/taylor2d_tl; ./build/taylor2d_tl --alpha 0
   Expect: a mushroomed foot, a smooth plastic strain field with alpha = 50.
   Smoke: taylor2d_tl --dp 1 --tend 2e-6 */
#include "common.h"

typedef struct {
    output_plan output;
    double e0, account_dev;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    if (output_tick(w, &s->output, "", &d) && s->e0 > 0) {
        const double account = d.kinetic_energy + d.strain_energy + d.contact_energy + d.plastic_work;
        if (fabs(account / s->e0 - 1) > s->account_dev) s->account_dev = fabs(account / s->e0 - 1);
    }
    return 0;
}

static void impact_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)x;
    v[0] = v[2] = 0;
    v[1] = -*(const sps_real*)user;
}

int main(int argc, char** argv) {
    double alpha = 50, yield = 1.0e9, v0 = 373, dp_mm = 0.35;
    double artificial_viscosity = 0; /* TL artificial viscosity q1 (none: the paper's) */
    int hourglass_form = SPS_HOURGLASS_VARIATIONAL;
    common_options c = {.cfl = 0.4, .t_end = 50e-6, .vtk_every = 10e-6, .csv_every = 0.5e-6, .E = 78.2e9, .nu = 0.3, .rho0 = 2700,
                        .out = "out/taylor2d_tl", .seed = 1, .contact_rest = SPS_CONTACT_REST_KERNEL /* the papers' contact law */, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"alpha", OPT_REAL, &alpha, "hourglass coefficient alpha (TL eq. 32)", 0, 1000, NULL},
        EX_HOURGLASS_OPTIONS(hourglass_form, artificial_viscosity),
        {"yield", OPT_REAL, &yield, "yield stress sigma_Y [Pa]", 1e3, 1e12, NULL},
        {"v0", OPT_REAL, &v0, "impact speed [m/s]", 0, 1e4, NULL},
        {"dp", OPT_REAL, &dp_mm, "particle spacing [mm]", 0.02, 2, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body bar;
    run_state s;
    const double W = 3.91e-3, L = 23.46e-3;
    sps_real lo[3] = {(sps_real)(-W / 2), 0, 0}, hi[3] = {(sps_real)(W / 2), (sps_real)L, 0}, wall_point[3] = {0, 0, 0},
             wall_normal[3] = {0, 1, 0}, v;
    double wall, dp, ymin = 1e30, ymax = -1e30, xmin = 1e30, xmax = -1e30;
    sps_diagnostics d;
    int id, n;

    ex_options(argc, argv, "2D Taylor impact, J2 in the total-Lagrangian frame (benchmark D5, bench/VALIDATION.md)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    dp = dp_mm * 1e-3;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.h_over_dp = 1.5; /* kernel support 3 dp, as the paper's */
    bd.name = "bar";
    bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
    bd.material.kind = SPS_MATERIAL_J2;
    bd.material.j2.yield_stress = (sps_real)yield;
    bd.material.tl.hourglass_alpha = (sps_real)alpha;
    bd.material.tl.hourglass = (sps_hourglass)hourglass_form;
    bd.material.tl.artificial_viscosity = (sps_real)artificial_viscosity;
    sps_world_create(&wd, &w);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &bar);
    lo[1] = (sps_real)(0.5 * dp); /* the foot half a spacing above the wall */
    hi[1] = (sps_real)(L + 0.5 * dp);
    sps_body_add_box(w, bar, lo, hi, NULL);
    sps_world_add_wall(w, wall_point, wall_normal, SPS_WALL_FREE_SLIP);
    v = (sps_real)v0;
    sps_body_set_velocity(w, bar, impact_velocity, &v);
    memset(&s, 0, sizeof s);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    s.e0 = d.kinetic_energy;
    output_open(&s.output, &c, "taylor2d_tl", "plastic-strain", "");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    n = sps_world_particle_count(w);
    for (id = 0; id < n; ++id) {
        sps_particle_state p;
        sps_world_particle(w, id, &p);
        if (p.position[1] < ymin) ymin = p.position[1];
        if (p.position[1] > ymax) ymax = p.position[1];
        if (p.position[1] < ymin + 2 * dp) { /* the foot */
            if (p.position[0] < xmin) xmin = p.position[0];
            if (p.position[0] > xmax) xmax = p.position[0];
        }
    }
    printf("RESULT case=taylor2d_tl alpha=%g hourglass=%s artificial_viscosity=%g yield=%g v0=%g dp_mm=%g particles=%d t=%g length_mm=%.3f length0_mm=%.3f foot_width_mm=%.3f "
           "width0_mm=%.3f max_plastic_strain=%.3f kinetic_end_rel=%.4f account_max_dev=%.4f hourglass=%.3g %s steps=%ld wall_s=%.2f out=%s\n",
           alpha, ex_hourglass_name(hourglass_form), artificial_viscosity, yield, v0, dp_mm, n, (double)sps_world_time(w), 1e3 * (ymax - ymin + dp), 1e3 * L, 1e3 * (xmax - xmin + dp), 1e3 * W,
           (double)d.max_plastic_strain, d.kinetic_energy / s.e0, s.account_dev, (double)d.hourglass, common_result_fields(&c),
           d.acoustic_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
