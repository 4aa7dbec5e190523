/* soil_failure2d.c - the failure of a cohesive soil block under its own weight (benchmark C5,
   UTVF 5.2, after Bui et al. 2008).

   A block L = 4 m long and H = 2 m high of Drucker-Prager soil (rho0 = 1850, E = 1.8 MPa,
   nu = 0.3, c = 5 kPa, phi = 25 degrees, psi = 0) stands against the left wall of a box 5 m x
   2.5 m with no-slip walls, started from its geostatic stress (K0 = 1 - sin phi), and fails
   under gravity (g = 9.8) to t = 2 s. --transport none|tvf|utvf selects the correction against
   tensile instability (the paper's comparison), --res L/dp (100, 200). We print the surface
   at the end: the crest (the first point, from the left, where the top has dropped 5 % of H:
   how far the failure reached back), the toe (the rightmost particle), the
   step-path rise (the largest rise of the surface profile from a point to any point right of
   it: 0 for a surface that only descends, the paper's "descent then rise" when positive), and
   the clustering and void indicators (the smallest spacing, and the particles whose position
   divergence marks them as surface: voids and cracks inside raise the count).

   Build: make examples     Run: ./build/soil_failure2d --transport utvf (--res 200)
   Expect: with UTVF a uniform distribution (smallest spacing above 0.5 dp); without a
   correction clustering (spacing well below 0.5 dp) and more surface particles.
   Smoke: soil_failure2d --res 10 --tend 0.01 */
#include "common.h"

#define BLOCK_LENGTH 4.0
#define BLOCK_HEIGHT 2.0

/* The surface profile in columns dp wide: each column's highest particle + dp/2 (0: empty). */
#define MAX_COLUMNS 4096
typedef struct {
    double top[MAX_COLUMNS];
    int columns;
} surface_profile;
static void surface_of(const sps_world* w, double dp, surface_profile* sp) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    int i, n = sps_world_particle_count(w);
    memset(sp, 0, sizeof *sp);
    for (i = 0; i < n; ++i) {
        int k = (int)(x[i] / dp);
        if (k < 0 || k >= MAX_COLUMNS) continue;
        if (y[i] + 0.5 * dp > sp->top[k]) sp->top[k] = y[i] + 0.5 * dp;
        if (k + 1 > sp->columns) sp->columns = k + 1;
    }
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_OG, .cfl = 0.4, .t_end = 2, .vtk_every = 0.1, .csv_every = 0.01, .E = 1.8e6, .nu = 0.3,
                        .rho0 = 1850, .out = "out/soil_failure2d", .jitter = 0, .seed = 1, .transport = 2, PNG_DEFAULTS};
    double res = 100;
    granular_options g = {5e3, 25, 0.1, SPS_CONE_PAPERS};
    opt_spec opts[] = {
        {"res", OPT_REAL, &res, "resolution L/dp (the paper: 100 and 200)", 10, 800, NULL},
        GRANULAR_OPTION_SPECS(g),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body soil, all = {0};
    sps_diagnostics d;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {BLOCK_LENGTH, BLOCK_HEIGHT, 0}, box_hi[3] = {5, 2.5, 0};
    output_plan output;
    surface_profile* sp = (surface_profile*)calloc(1, sizeof(surface_profile));
    double wall, dp, crest = -1, toe = 0, rise = 0, rise_at = 0, lowest = 1e30, lowest_at = 0, low_x = 0;
    int k, n, surface0, clustered;

    ex_options(argc, argv, "2D failure of a cohesive soil block (C5, UTVF 5.2): Drucker-Prager with none, TVF or UTVF", opts, &c, &wd, &bd);
    if (!sp) { fprintf(stderr, "%s: out of memory\n", g_prog); return 1; }
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    dp = BLOCK_LENGTH / res;
    bd.name = "soil";
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    apply_granular(&g, &bd);
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-GRANULAR_GRAVITY;
    sps_world_create(&wd, &w);
    sps_world_add_box_walls(w, lo, box_hi, SPS_FACE_Y_HI, SPS_WALL_NO_SLIP);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &soil);
    sps_body_add_box(w, soil, lo, hi, NULL);
    sps_body_set_geostatic_stress(w, soil, (sps_real)BLOCK_HEIGHT, 0);
    sps_world_diagnostics(w, all, &d);
    surface0 = d.surface_particles;

    output_open(&output, &c, "soil_failure2d", "plastic-strain", "");
    ex_plain_step(w, &output); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, ex_plain_step, &output);
    wall = output_close(w, &output);
    sps_world_diagnostics(w, all, &d);
    surface_of(w, dp, sp);
    n = sp->columns;
    for (k = 0; k < n; ++k) {
        const double x = (k + 0.5) * dp;
        if (sp->top[k] > 0) toe = (k + 1) * dp;
        if (crest < 0 && sp->top[k] < 0.95 * BLOCK_HEIGHT) crest = x;
    }
    for (k = 0; k < n; ++k) { /* the largest rise of the profile above its lowest point to the left */
        const double x = (k + 0.5) * dp;
        if (sp->top[k] <= 0 || x < crest) continue;
        if (sp->top[k] < lowest) { lowest = sp->top[k]; low_x = x; }
        if (sp->top[k] - lowest > rise) { rise = sp->top[k] - lowest; rise_at = x; lowest_at = low_x; }
    }
    printf("cohesive soil failure: L/dp = %g (dp = %g m), %d particles, c = %g Pa, phi = %g deg, zeta = %g, transport %s\n", res, dp,
           sps_world_particle_count(w), g.cohesion, g.phi, g.diffusion, transport_name(c.transport));
    printf("  at t = %.3g s: crest at x = %.3f m (%.3f m behind the block's edge), toe at x = %.3f m (%.3f m beyond it)\n", (double)d.time,
           crest, BLOCK_LENGTH - crest, toe, toe - BLOCK_LENGTH);
    printf("  step path: the surface rises %.3f m (%.1f dp) from its low at x = %.3f m to x = %.3f m\n", rise, rise / dp, lowest_at, rise_at);
    clustered = ex_clustered_particles(w, dp, 0.5);
    printf("  clustering: %d particles with another closer than 0.5 dp (smallest spacing %.3f dp); surface particles %d (%d at the\n"
           "  start: voids and cracks raise it); largest accumulated deviatoric plastic strain %.3f\n",
           clustered, (double)d.min_spacing, d.surface_particles, surface0, (double)d.max_plastic_strain);
    printf("RESULT case=soil_failure2d res=%g dp=%g cohesion=%g phi=%g zeta=%g t=%.4g crest=%.4f toe=%.4f rise=%.4f rise_at=%.4f "
           "clustered=%d min_spacing=%.3f surface_particles=%d surface_start=%d %s particles=%d steps=%ld advection_steps=%ld wall_s=%.2f "
           "ns_per_particle_step=%.1f out=%s\n",
           res, dp, g.cohesion, g.phi, g.diffusion, (double)d.time, crest, toe, rise, rise_at, clustered, (double)d.min_spacing, d.surface_particles, surface0,
           common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall,
           ns_per_particle_step(w, wall, d.acoustic_steps), c.out);
    sps_world_destroy(w);
    free(sp);
    return 0;
}
