/* strip_pull.c - rubber strip pulled to 500 %, benchmark D4 (TL section 4.4; bench/VALIDATION.md).

   A 2 mm x 2 mm strip of compressible Neo-Hookean rubber (TL eq. 44; E 1 GPa, nu 0.45, rho0
   1000, plane strain) on a square lattice of spacing 1/15 mm, kernel support 2 spacings
   (h = dp). The top and the bottom row are pulled apart at +-v (no lateral motion, as in a
   test stand's clamps) until the strip is --length long (12 mm: +500 %). The paper pulls at
   0.1 mm/s; here v = 10 m/s (the default), still 0.005 of the P-wave speed, so the strip
   stretches quasi-statically while the run takes 1e5 sub-steps instead of 1e10. We report
   whether it gets there, the hourglass indicator (DIAGNOSTICS) and the smallest spacing along
   the way, the range of J = rho0/rho, and the width at mid-height (the neck) next to its
   incompressible estimate 2 mm / 6 = 0.33 mm (the strip is 6 times as long).

   Build: make examples   Run: ./build/strip_pull; ./build/strip_pull --alpha 0
   The paper: 500 % smooth with alpha 50, disorder without. Measured (bench/VALIDATION.md): with
   TL eq. 32 as printed (--hourglass paper) the run stopped with a NaN at 167 % (alpha 0: 234 %),
   the energy that force feeds in inverting particles; the variational default keeps the energy
   account exact and reaches 500 % (J 0.97 .. 4.26, neck 0.39 mm; 733 s on 2 threads).
   Smoke: strip_pull --dp 0.2 --length 2.2e-3 */
#include "common.h"

typedef struct {
    output_plan output;
    double hourglass_max, spacing_min;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    if (output_tick(w, &s->output, "", &d)) {
        if (d.hourglass > s->hourglass_max) s->hourglass_max = d.hourglass;
        if (d.min_spacing < s->spacing_min) s->spacing_min = d.min_spacing;
    }
    return 0;
}

int main(int argc, char** argv) {
    double alpha = 50, v = 10, length = 12e-3, dp_mm = 1.0 / 15, h_over_dp = 1;
    double artificial_viscosity = 0; /* TL artificial viscosity q1 (none: the paper's) */
    int hourglass_form = SPS_HOURGLASS_VARIATIONAL;
    common_options c = {.cfl = 0.4, .t_end = 0, .vtk_every = 0, .csv_every = 0, .E = 1e9, .nu = 0.45, .rho0 = 1000,
                        .out = "out/strip_pull", .seed = 1, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"alpha", OPT_REAL, &alpha, "hourglass coefficient alpha (TL eq. 32)", 0, 1000, NULL},
        EX_HOURGLASS_OPTIONS(hourglass_form, artificial_viscosity),
        {"v", OPT_REAL, &v, "pull speed of each clamped row [m/s]", 1e-6, 1000, NULL},
        {"length", OPT_REAL, &length, "final length [m] (12 mm: +500 %)", 2.1e-3, 0.1, NULL},
        {"dp", OPT_REAL, &dp_mm, "particle spacing [mm]", 0.005, 1, NULL},
        {"h", OPT_REAL, &h_over_dp, "smoothing length / dp (1: kernel support 2 dp, the paper's)", 0.8, 3, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body strip;
    run_state s;
    double wall, dp, width = 0, jmin = 1e30, jmax = 0;
    const double H = 2e-3;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)H, (sps_real)H, 0}, vt[3] = {0, 0, 0}, vb[3] = {0, 0, 0};
    sps_real top_lo[3], top_hi[3], bot_lo[3], bot_hi[3];
    int id, n;

    ex_options(argc, argv, "rubber strip pulled to 500 % (benchmark D4, bench/VALIDATION.md)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    dp = dp_mm * 1e-3;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.h_over_dp = (sps_real)h_over_dp; /* 1: kernel support 2 dp, as the paper's */
    bd.name = "strip";
    bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
    bd.material.kind = SPS_MATERIAL_NEO_HOOKEAN;
    bd.material.tl.hourglass_alpha = (sps_real)alpha;
    bd.material.tl.hourglass = (sps_hourglass)hourglass_form;
    bd.material.tl.artificial_viscosity = (sps_real)artificial_viscosity;
    if (c.t_end <= 0) c.t_end = (length - H) / (2 * v);
    if (c.csv_every <= 0) c.csv_every = c.t_end / 200;
    if (c.vtk_every == 0) c.vtk_every = c.t_end / 5;
    sps_world_create(&wd, &w);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &strip);
    sps_body_add_box(w, strip, lo, hi, NULL);
    /* the clamped rows: the top one (y > H - dp) up at v, the bottom one (y < dp) down at v */
    top_lo[0] = bot_lo[0] = -1; top_hi[0] = bot_hi[0] = 1; top_lo[2] = bot_lo[2] = -1; top_hi[2] = bot_hi[2] = 1;
    top_lo[1] = (sps_real)(H - dp); top_hi[1] = 1; bot_lo[1] = -1; bot_hi[1] = (sps_real)dp;
    vt[1] = (sps_real)v;
    vb[1] = (sps_real)-v;
    sps_body_constrain_box(w, strip, top_lo, top_hi, SPS_AXIS_ALL, vt, NULL);
    sps_body_constrain_box(w, strip, bot_lo, bot_hi, SPS_AXIS_ALL, vb, NULL);
    memset(&s, 0, sizeof s);
    s.spacing_min = 1e30;
    output_open(&s.output, &c, "strip_pull", "displacement", "");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    { /* the neck: the width of the particles whose reference height is mid-strip */
        double xmin = 1e30, xmax = -1e30, ymin = 1e30, ymax = -1e30;
        n = sps_world_particle_count(w);
        for (id = 0; id < n; ++id) {
            sps_particle_state p;
            sps_world_particle(w, id, &p);
            if (fabs(p.position[1] - p.displacement[1] - H / 2) < dp) {
                if (p.position[0] < xmin) xmin = p.position[0];
                if (p.position[0] > xmax) xmax = p.position[0];
            }
            if (p.position[1] < ymin) ymin = p.position[1];
            if (p.position[1] > ymax) ymax = p.position[1];
            if (c.rho0 / p.density < jmin) jmin = c.rho0 / p.density;
            if (c.rho0 / p.density > jmax) jmax = c.rho0 / p.density;
        }
        width = xmax - xmin + dp;
        printf("RESULT case=strip_pull alpha=%g hourglass=%s artificial_viscosity=%g v=%g dp_mm=%g particles=%d length_mm=%.4f strain_pct=%.1f neck_width_mm=%.4f "
               "incompressible_mm=%.4f J_min=%.4f J_max=%.4f hourglass_max=%.3g min_spacing=%.3f %s wall_s=%.2f out=%s\n",
               alpha, ex_hourglass_name(hourglass_form), artificial_viscosity, v, dp_mm, n, 1e3 * (ymax - ymin + dp), 100 * ((ymax - ymin + dp) / H - 1), 1e3 * width, 1e3 * H * H / (ymax - ymin + dp),
               jmin, jmax, s.hourglass_max, s.spacing_min, common_result_fields(&c), wall, c.out);
    }
    sps_world_destroy(w);
    return 0;
}
