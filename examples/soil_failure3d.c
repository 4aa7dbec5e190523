/* soil_failure3d.c - the failure of a cube of cohesive soil under its own weight (benchmark C6,
   UTVF 5.3).

   A cube of edge 2 m of the C5 soil (rho0 = 1850, E = 1.8 MPa, nu = 0.3, c = 5 kPa, phi = 25
   degrees, psi = 0) stands on a no-slip floor, free on its four sides and its top (our reading
   of UTVF Fig. 22, a picture: the paper gives the edge and dp only), started from its
   geostatic stress, and fails under gravity; dp = 0.04 m (--res edge/dp = 50: 125 000
   particles), to t = 1 s (the paper's snapshots: 0.5 s and 1 s). --transport none|tvf|utvf. We
   print at each snapshot time the cube's top, its footprint's half width (the farthest
   particle from the vertical centre line), the smallest spacing (clustering below ~0.5 dp)
   and the surface-particle count (voids and cracks raise it), and the wall time.

   Build: make examples     Run: ./build/soil_failure3d --transport utvf (--res 25: a quick look)
   Expect: with UTVF no clustering (smallest spacing above 0.5 dp), without a correction
   clustering and cracks.
   Smoke: soil_failure3d --res 5 --tend 0.01 */
#include "common.h"

#define EDGE 2.0

typedef struct {
    output_plan output;
    double next_report;
} run_state;

/* The top of the soil and the largest horizontal distance of a particle from the cube's axis. */
static void extent(const sps_world* w, double dp, double* top, double* half_width) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y),
                   *z = sps_world_field(w, SPS_FIELD_POSITION_Z);
    int i, n = sps_world_particle_count(w);
    *top = *half_width = 0;
    for (i = 0; i < n; ++i) {
        const double rx = fabs(x[i]), rz = fabs(z[i]);
        if (y[i] + 0.5 * dp > *top) *top = y[i] + 0.5 * dp;
        if (rx + 0.5 * dp > *half_width) *half_width = rx + 0.5 * dp;
        if (rz + 0.5 * dp > *half_width) *half_width = rz + 0.5 * dp;
    }
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    const double t = sps_world_time(w);
    output_tick(w, &s->output, "", &d);
    if (t >= s->next_report - 1e-9) {
        double top, half_width;
        sps_world_diagnostics(w, (sps_body){0}, &d);
        extent(w, (double)sps_world_get_def(w)->dp, &top, &half_width);
        printf("  t = %.3f s: top %.3f m, half width %.3f m (1 at the start), %d particles closer than 0.5 dp to another (smallest "
               "spacing %.3f dp), surface particles %d, max speed %.3f m/s, wall %.0f s\n",
               t, top, half_width, ex_clustered_particles(w, (double)sps_world_get_def(w)->dp, 0.5), (double)d.min_spacing,
               d.surface_particles, (double)d.max_speed, wall_seconds() - s->output.wall0);
        fflush(stdout);
        s->next_report += 0.25;
    }
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_OG, .cfl = 0.4, .t_end = 1, .vtk_every = 0.25, .csv_every = 0.01, .E = 1.8e6, .nu = 0.3,
                        .rho0 = 1850, .out = "out/soil_failure3d", .jitter = 0, .seed = 1, .transport = 2, PNG_DEFAULTS};
    double res = 50;
    granular_options g = {5e3, 25, 0.1, SPS_CONE_PAPERS};
    opt_spec opts[] = {
        {"res", OPT_REAL, &res, "resolution edge/dp (the paper: 50, dp = 0.04 m)", 5, 200, NULL},
        GRANULAR_OPTION_SPECS(g),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body soil, all = {0};
    sps_diagnostics d;
    sps_real lo[3] = {-EDGE / 2, 0, -EDGE / 2}, hi[3] = {EDGE / 2, EDGE, EDGE / 2}, floor_point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    run_state s;
    double wall, dp;

    ex_options(argc, argv, "3D failure of a cube of cohesive soil (C6, UTVF 5.3): Drucker-Prager with none, TVF or UTVF",
               opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    memset(&s, 0, sizeof s);
    dp = EDGE / res;
    bd.name = "soil";
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    apply_granular(&g, &bd);
    wd.dim = 3;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-GRANULAR_GRAVITY;
    sps_world_create(&wd, &w);
    sps_world_add_wall(w, floor_point, up, SPS_WALL_NO_SLIP);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &soil);
    sps_body_add_box(w, soil, lo, hi, NULL);
    sps_body_set_geostatic_stress(w, soil, (sps_real)EDGE, 0);

    printf("3D cohesive soil failure: edge/dp = %g (dp = %g m), %d particles, c = %g Pa, phi = %g deg, zeta = %g, transport %s\n", res,
           dp, sps_world_particle_count(w), g.cohesion, g.phi, g.diffusion, transport_name(c.transport));
    s.next_report = 0.25;
    output_open(&s.output, &c, "soil_failure3d", "plastic-strain", "");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    sps_world_diagnostics(w, all, &d);
    printf("RESULT case=soil_failure3d res=%g dp=%g cohesion=%g phi=%g zeta=%g t=%.4g clustered=%d min_spacing=%.3f surface_particles=%d "
           "max_plastic_strain=%.3f %s particles=%d steps=%ld advection_steps=%ld wall_s=%.2f ns_per_particle_step=%.1f out=%s\n",
           res, dp, g.cohesion, g.phi, g.diffusion, (double)d.time, ex_clustered_particles(w, dp, 0.5), (double)d.min_spacing, d.surface_particles, (double)d.max_plastic_strain,
           common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall,
           ns_per_particle_step(w, wall, d.acoustic_steps), c.out);
    sps_world_destroy(w);
    return 0;
}
