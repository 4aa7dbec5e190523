/* column_collapse2d.c - the collapse of a cohesionless granular column (benchmark C4, UTVF 5.1).

   A column L = 0.2 m (or 0.1 m, --length) wide and H = 0.1 m high of Drucker-Prager soil
   (rho0 = 2040, E = 5.84 MPa, nu = 0.3, c = 0, phi = 21.9 degrees, psi = 0: Nguyen et al. 2017's
   aluminium rods) stands at the left wall of a tank 0.5 m x 0.15 m with no-slip walls, is
   released at t = 0 from zero stress under g = 9.8 and spreads to rest. dp = 0.002 (5000
   particles), stress diffusion on and no transport correction, as the reference code's case.
   We print the mechanical energy (kinetic + gravity potential, from the floor) next to the
   reference code's (19.992 J/m at the start, 13.97 J/m near 0.5 s, 13.79 J/m at 0.8 s), and the
   final runout (the toe: where the deposit, at least 2 dp deep, ends; and the farthest
   particle) and the final height at the left wall
   against the experiments' scaling for 2D columns of aspect ratio a = H/L < 1.8 (Lube et al.
   2005): runout (L_f - L)/L = 1.2 a, and a truncated column that keeps its height H at the wall
   for a < 1.15 (the figures of UTVF Figs. 15-16 are pictures we cannot read numbers from).

   --floor coulomb makes the floor free-slip with Coulomb friction mu = tan(phi) (the grains'
   own), on which a grain that leaves the bulk comes to rest; on the paper's no-slip floor such
   a grain carries no stress, its images no shear, and it slides on.

   Build: make examples     Run: ./build/column_collapse2d (--length 0.1) (--floor coulomb)
   Expect: the energy within a few % of the reference code's, the toe near 0.32 m (L = 0.2).
   Smoke: column_collapse2d --dp 0.01 --tend 0.01 */
#include "common.h"

#define TANK_LENGTH 0.5
#define TANK_HEIGHT 0.15
#define COLUMN_HEIGHT 0.1

typedef struct {
    output_plan output;
    double dp, energy_half, energy_end, zigzag_max;
} run_state;

static double mechanical_energy(const sps_diagnostics* d) { return (double)(d->kinetic_energy + d->potential_energy); }

/* The deposit in columns dp wide: the toe, where the contiguous deposit from the left wall
   ends (the first column holding fewer than 2 particles, a compact depth below 2 dp: the loose
   particles that slide on along the floor beyond it are not the deposit's), the farthest
   particle, and the height at the left wall (the first column's highest particle + dp/2). */
static void profile(const sps_world* w, double dp, double* toe, double* farthest, double* wall_height) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    int i, k, n = sps_world_particle_count(w), columns = (int)(TANK_LENGTH / dp) + 1;
    double* top = (double*)calloc((size_t)columns, sizeof(double));
    int* count = (int*)calloc((size_t)columns, sizeof(int));
    *toe = *farthest = *wall_height = 0;
    if (!top || !count) { free(top); free(count); return; }
    for (i = 0; i < n; ++i) {
        k = (int)(x[i] / dp);
        if (k < 0 || k >= columns) continue;
        if (y[i] + 0.5 * dp > top[k]) top[k] = y[i] + 0.5 * dp;
        ++count[k];
        if (x[i] + 0.5 * dp > *farthest) *farthest = x[i] + 0.5 * dp;
    }
    for (k = 0; k < columns && count[k] >= 2; ++k) *toe = (k + 1) * dp;
    *wall_height = top[0];
    free(top);
    free(count);
}

/* At every CSV row: the energies at 0.5 s (the last row at or before it) and at the end, and the
   largest zigzag indicator (DIAGNOSTICS: near 0 while the soil flows smoothly, above 1 when
   the particle-scale zigzag mode carries the motion). */
static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    const double t = sps_world_time(w);
    if (output_tick(w, &s->output, "", &d)) {
        if (t <= 0.5 + 1e-9) s->energy_half = mechanical_energy(&d);
        s->energy_end = mechanical_energy(&d);
        if (d.zigzag > s->zigzag_max) s->zigzag_max = d.zigzag;
    }
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_OG, .cfl = 0.4, .t_end = 0.8, .vtk_every = 0.05, .csv_every = 0.005, .E = 5.84e6, .nu = 0.3,
                        .rho0 = 2040, .out = "out/column_collapse2d", .jitter = 0, .seed = 1, .transport = 0, PNG_DEFAULTS};
    double dp = 0.002, length = 0.2;
    int floor_kind = 0; /* the --floor choice: 0 no-slip (the paper's), 1 free-slip with Coulomb friction */
    granular_options g = {0, 21.9, 0.1, SPS_CONE_PAPERS};
    opt_spec opts[] = {
        {"length", OPT_REAL, &length, "column length L [m] (0.2 and 0.1 in the paper; height 0.1 m)", 0.02, 0.45, NULL},
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 5e-4, 0.02, NULL},
        {"floor", OPT_CHOICE, &floor_kind, "the floor: no-slip (the paper's), or free-slip with Coulomb friction tan(phi)", 0, 0,
         "no-slip|coulomb"},
        GRANULAR_OPTION_SPECS(g),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body soil, all = {0};
    sps_diagnostics d0, d;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0, COLUMN_HEIGHT, 0}, tank_lo[3] = {0, 0, 0}, tank_hi[3] = {TANK_LENGTH, TANK_HEIGHT, 0};
    const sps_real floor_point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    run_state s;
    double wall, toe, farthest, wall_height, a, toe_expected;
    sps_real c0;

    ex_options(argc, argv, "2D granular column collapse (C4, UTVF 5.1): Drucker-Prager soil released in a tank", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    memset(&s, 0, sizeof s);
    hi[0] = (sps_real)length;
    bd.name = "soil";
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    apply_granular(&g, &bd);
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-GRANULAR_GRAVITY;
    sps_world_create(&wd, &w);
    if (floor_kind == 0) {
        sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_NO_SLIP);
    } else { /* the side walls no-slip; the floor resists sliding by Coulomb's tan(phi) times its normal force */
        sps_world_add_wall(w, floor_point, up, SPS_WALL_FREE_SLIP);
        sps_world_set_wall_friction(w, 0, (sps_real)tan(g.phi * 3.14159265358979323846 / 180));
        sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI | SPS_FACE_Y_LO, SPS_WALL_NO_SLIP);
    }
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &soil);
    sps_body_add_box(w, soil, lo, hi, NULL);
    sps_world_diagnostics(w, all, &d0);

    s.dp = dp;
    output_open(&s.output, &c, "column_collapse2d", "velocity", "");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    sps_world_diagnostics(w, all, &d);
    sps_body_material_constants(w, soil, &c0, NULL, NULL);
    profile(w, dp, &toe, &farthest, &wall_height);
    a = COLUMN_HEIGHT / length;
    toe_expected = length * (1 + 1.2 * a);
    printf("granular column collapse: L = %g m, H = %g m, dp = %g, %d particles, c0 = %.4g m/s, phi = %g deg, c = %g Pa, zeta = %g, transport %s\n",
           length, COLUMN_HEIGHT, dp, sps_world_particle_count(w), (double)c0, g.phi, g.cohesion, g.diffusion,
           transport_name(c.transport));
    printf("  mechanical energy [J/m]: start %.4f, t = 0.5 s: %.4f, t = %.3g s: %.4f\n", mechanical_energy(&d0), s.energy_half,
           (double)d.time, s.energy_end);
    if (fabs(length - 0.2) < 1e-9) /* the reference code's case */
        printf("  reference code (L = 0.2): 19.992, 13.97 at 0.5 s (ours %+.1f%%), 13.79 at 0.8 s (ours %+.1f%%)\n",
               100 * (s.energy_half / 13.97 - 1), 100 * (s.energy_end / 13.79 - 1));
    printf("  toe (final runout, the deposit at least 2 particles deep): %.4f m, experiments' scaling L (1 + 1.2 H/L) = %.4f m (%+.1f%%);\n"
           "  farthest particle %.4f m\n", toe, toe_expected, 100 * (toe / toe_expected - 1), farthest);
    printf("  height at the left wall: %.4f m, truncated column (a = %.2f < 1.15): %.4f m (%+.1f%%)\n", wall_height, a, COLUMN_HEIGHT,
           100 * (wall_height / COLUMN_HEIGHT - 1));
    printf("  plastic work %.4f J/m, largest accumulated deviatoric plastic strain %.3f, surface particles %d, %d particles closer than\n"
           "  0.5 dp to another (smallest spacing %.3f dp)\n",
           (double)d.plastic_work, (double)d.max_plastic_strain, d.surface_particles, ex_clustered_particles(w, dp, 0.5), (double)d.min_spacing);
    printf("  zigzag indicator (0: smooth flow, above 1: zigzag): %.3f at the end, largest %.3f (CSV rows); largest speed %.3g m/s\n",
           (double)d.zigzag, s.zigzag_max, (double)d.max_speed);
    printf("RESULT case=column_collapse2d length=%g dp=%g phi=%g cohesion=%g zeta=%g floor=%s t=%.4g energy_start=%.5g energy_0.5=%.5g "
           "energy_end=%.5g toe=%.4f farthest=%.4f wall_height=%.4f zigzag=%.3f zigzag_max=%.3f zigzag_limit=1 %s particles=%d steps=%ld "
           "advection_steps=%ld wall_s=%.2f ns_per_particle_step=%.1f out=%s\n",
           length, dp, g.phi, g.cohesion, g.diffusion, floor_kind == 0 ? "no-slip" : "coulomb", (double)d.time, mechanical_energy(&d0), s.energy_half, s.energy_end, toe, farthest, wall_height,
           (double)d.zigzag, s.zigzag_max, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall,
           ns_per_particle_step(w, wall, d.acoustic_steps), c.out);
    sps_world_destroy(w);
    return 0;
}
