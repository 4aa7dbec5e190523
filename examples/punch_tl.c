/* punch_tl.c - rubber block compressed between rigid tools, benchmark D3 (TL section 4.3;
   bench/VALIDATION.md).

   A 6 mm x 3 mm block of compressible Neo-Hookean rubber (TL eq. 44; E 1 GPa, nu 0.45, rho0
   1000, plane strain), spacing 1/15 mm, between two rigid tools 6 mm wide (wall bodies,
   SPS_MATERIAL_RIGID, 3 particle layers: the kernel support) that move towards each other at
   --v each until the block is compressed by --compression (50 %). Contact is the library's
   (CONTACT: frictionless repulsion of the contact density, the rubber's stiffness). The paper
   compresses at 1 mm/s; here v = 5 m/s (default), 0.0026 of the P-wave speed: quasi-static
   in 3e4 sub-steps. The tool force [N per m of depth] comes from the work the tools do,
   F = dW/ds (the prescribed work of DIAGNOSTICS over the closure s of both tools, per tool; in
   the CSV between rows, noisy with the stress waves the tools send, and printed as its mean
   over each 10 % of compression) next to homogeneous plane-strain compression between frictionless
   platens, F = sigma_yy(a, s) a W0 with stretch s of the height and a of the width from
   sigma_xx = 0 (Neo-Hookean, closed form solved by Newton): what a block that slides freely
   on its tools carries. We also report the hourglass indicator and the range of J.

   Build: make examples   Run: ./build/punch_tl; ./build/punch_tl --alpha 0
   The paper: smooth to 50 %. Measured (bench/VALIDATION.md): the force within 2 % of the
   homogeneous one over 10-20 %, 17-41 % below it beyond; 50 % is reached, with particle disorder
   (hourglass indicator 0.28) in the last 10 %.
   Smoke: punch_tl --dp 0.3 --compression 0.02 */
#include "common.h"

typedef struct {
    output_plan output;
    double v, H, W0, last_work, last_s, hourglass_max, next_report, mu, lambda;
    double report_work, report_s; /* at the last report: the mean force over each 10 % is the secant */
} run_state;

/* Homogeneous plane-strain compression of the Neo-Hookean block: height stretch s, width stretch
   a from sigma_xx = (mu (a^2 - 1) + lambda ln(a s)) / (a s) = 0; returns the force per depth
   sigma_yy a W0 (compressive: negative). */
static double homogeneous_force(const run_state* st, double s) {
    double a = 1;
    int k;
    for (k = 0; k < 50; ++k) { /* Newton on g(a) = mu (a^2 - 1) + lambda ln(a s) */
        const double g = st->mu * (a * a - 1) + st->lambda * log(a * s), dg = 2 * st->mu * a + st->lambda / a;
        a -= g / dg;
    }
    return (st->mu * (s * s - 1) + st->lambda * log(a * s)) / (a * s) * a * st->W0;
}

static int on_step(sps_world* w, void* user) {
    run_state* st = (run_state*)user;
    sps_diagnostics d;
    char extra[128];
    const double t = sps_world_time(w), s = 2 * st->v * t; /* closure of the two tools */
    double force = 0;
    sps_world_diagnostics(w, (sps_body){0}, &d);
    if (s > st->last_s) force = (d.prescribed_work - st->last_work) / (s - st->last_s); /* per tool: both do the same work */
    if (d.hourglass > st->hourglass_max) st->hourglass_max = d.hourglass;
    snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g", s / st->H, force, -homogeneous_force(st, 1 - s / st->H));
    output_tick(w, &st->output, extra, &d);
    if (s / st->H >= st->next_report - 1e-9) { /* the mean force over the last 10 %, against the homogeneous one mid-way */
        const double mean = (d.prescribed_work - st->report_work) / (s - st->report_s), mid = 0.5 * (s + st->report_s) / st->H;
        printf("compression %4.1f-%4.1f %%: mean tool force %.6g N/m, homogeneous at %.1f %% %.6g N/m (%+.1f %%), hourglass %.3g\n",
               100 * st->report_s / st->H, 100 * s / st->H, mean, 100 * mid, -homogeneous_force(st, 1 - mid),
               100 * (mean / -homogeneous_force(st, 1 - mid) - 1), (double)d.hourglass);
        st->report_work = d.prescribed_work;
        st->report_s = s;
        st->next_report += 0.1;
    }
    st->last_work = d.prescribed_work;
    st->last_s = s;
    return 0;
}

static void tool_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)x;
    v[0] = v[2] = 0;
    v[1] = *(const sps_real*)user;
}

int main(int argc, char** argv) {
    double alpha = 50, v = 5, compression = 0.5, dp_mm = 1.0 / 15;
    double artificial_viscosity = 0; /* TL artificial viscosity q1 (none: the paper's) */
    int hourglass_form = SPS_HOURGLASS_VARIATIONAL;
    common_options c = {.cfl = 0.4, .t_end = 0, .vtk_every = 0, .csv_every = 0, .E = 1e9, .nu = 0.45, .rho0 = 1000,
                        .out = "out/punch_tl", .seed = 1, .contact_rest = SPS_CONTACT_REST_KERNEL /* the papers' contact law */, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"alpha", OPT_REAL, &alpha, "hourglass coefficient alpha (TL eq. 32)", 0, 1000, NULL},
        EX_HOURGLASS_OPTIONS(hourglass_form, artificial_viscosity),
        {"v", OPT_REAL, &v, "speed of each tool [m/s]", 1e-6, 1000, NULL},
        {"compression", OPT_REAL, &compression, "final compression (closure / height)", 0.01, 0.9, NULL},
        {"dp", OPT_REAL, &dp_mm, "particle spacing [mm]", 0.005, 1, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def(), td = sps_default_body_def();
    sps_world* w;
    sps_body block, top, bottom;
    run_state st;
    double wall, dp, jmin = 1e30, jmax = 0;
    const double W0 = 6e-3, H = 3e-3;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)W0, (sps_real)H, 0}, tlo[3], thi[3], vdown, vup;
    int id, n;

    ex_options(argc, argv, "rubber block between rigid tools (benchmark D3, bench/VALIDATION.md)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    dp = dp_mm * 1e-3;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    bd.name = "rubber";
    bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
    bd.material.kind = SPS_MATERIAL_NEO_HOOKEAN;
    bd.material.tl.hourglass_alpha = (sps_real)alpha;
    bd.material.tl.hourglass = (sps_hourglass)hourglass_form;
    bd.material.tl.artificial_viscosity = (sps_real)artificial_viscosity;
    td.material = bd.material;
    td.material.kind = SPS_MATERIAL_RIGID;
    memset(&st, 0, sizeof st);
    st.v = v; st.H = H; st.W0 = W0; st.next_report = 0.1;
    st.mu = c.E / (2 * (1 + c.nu));
    st.lambda = c.E * c.nu / ((1 + c.nu) * (1 - 2 * c.nu));
    if (c.t_end <= 0) c.t_end = compression * H / (2 * v);
    if (c.csv_every <= 0) c.csv_every = c.t_end / 200;
    if (c.vtk_every == 0) c.vtk_every = c.t_end / 5;
    sps_world_create(&wd, &w);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &block);
    sps_body_add_box(w, block, lo, hi, NULL);
    td.name = "top tool";
    sps_world_add_body(w, &td, &top);
    tlo[0] = 0; thi[0] = (sps_real)W0; tlo[2] = thi[2] = 0;
    tlo[1] = (sps_real)H; thi[1] = (sps_real)(H + 3 * dp);
    sps_body_add_box(w, top, tlo, thi, NULL);
    td.name = "bottom tool";
    sps_world_add_body(w, &td, &bottom);
    tlo[1] = (sps_real)(-3 * dp); thi[1] = 0;
    sps_body_add_box(w, bottom, tlo, thi, NULL);
    vdown = (sps_real)-v;
    vup = (sps_real)v;
    sps_body_set_velocity(w, top, tool_velocity, &vdown);
    sps_body_set_velocity(w, bottom, tool_velocity, &vup);
    output_open(&st.output, &c, "punch_tl", "displacement", ",compression,force,homogeneous_force");
    on_step(w, &st); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &st);
    wall = output_close(w, &st.output);
    n = sps_world_particle_count(w);
    for (id = 0; id < n; ++id) {
        sps_particle_state p;
        sps_world_particle(w, id, &p);
        if (p.body_index != 0) continue;
        if (c.rho0 / p.density < jmin) jmin = c.rho0 / p.density;
        if (c.rho0 / p.density > jmax) jmax = c.rho0 / p.density;
    }
    printf("RESULT case=punch_tl alpha=%g hourglass=%s artificial_viscosity=%g v=%g dp_mm=%g particles=%d compression_pct=%.1f J_min=%.4f J_max=%.4f hourglass_max=%.3g "
           "%s wall_s=%.2f out=%s\n",
           alpha, ex_hourglass_name(hourglass_form), artificial_viscosity, v, dp_mm, n, 100 * 2 * v * sps_world_time(w) / H, jmin, jmax, st.hourglass_max, common_result_fields(&c), wall, c.out);
    sps_world_destroy(w);
    return 0;
}
