/* column_collapse3d.c - the axisymmetric collapse of a granular column against Lube et al. 2004 (3D).

   A cylinder of radius r0 = 0.05 m and height H0 = a r0 (the aspect ratio a = --aspect) of
   cohesionless Drucker-Prager soil (the C4 material of column_collapse2d: rho0 = 2040, E = 5.84
   MPa, nu = 0.3, c = 0, phi = 21.9 degrees, psi = 0; the plane-strain cone, --cone) stands on a
   floor (an analytic wall), is released at t = 0 under g = 9.8 (along -y) and spreads to rest.
   The floor (--floor) is free-slip with Coulomb friction mu = tan(phi) (the grains' own; Lube et
   al. found wood, baize, Plexiglas and sandpaper floors alike), or no-slip: grains that leave
   the bulk carry no stress and slide on along a no-slip wall (GRANULAR), and in 3D the whole
   deposit thins into such grains (at a = 2 a single layer still spreading at 0.9 m/s at 0.6 s).
   It starts from zero stress, as column_collapse2d and the reference code's C4: the lab's
   column stood in a tube whose wall friction set its stress, not a free layer's geostatic one,
   and it loads itself elastically within H0/c0 (2 ms at a = 2), short beside the fall's
   sqrt(H0/g) (0.1 s). At the end the deposit is read in rings dp wide about the axis (the highest
   particle + dp/2 in each, rings of fewer than 3 particles left out): the runout r_inf, where
   the deposit's bottom layer ends (the first ring out from the axis whose particles cover less
   than half its floor, fewer than pi (2k + 1) / 2 for ring k: the scattered grains beyond it are
   not the deposit), the farthest particle (+ dp/2), and the height at the centre H_inf (the
   ring on the axis). They are compared at the column the lattice holds: its height, and the
   radius of the cylinder of its volume (r0/dp should be whole: the lattice fills whole dp).

   Lube, Huppert, Sparks and Hallworth 2004 (J. Fluid Mech. 508, 175-199) released cylinders of
   sand, salt, couscous, rice and sugar (r0 1.7-9.7 cm) and found the deposit set by a alone, not
   by the grains' friction: runout (r_inf - r0)/r0 = 1.24 a for a < 1.7 and 1.6 a^(1/2) above; the
   height H_inf/r0 = a (the column's top left in place: a truncated cone) for a < 0.74 and
   0.88 a^(1/6) above. Checked against what could be read: 1.24 a (the paper's abstract, as
   quoted by others), the change of regime near a = 1.7 to a^(1/2), three regimes in a, and the
   independence of friction (the authors' ICTAM 2004 summary). NOT checked (the paper could not be
   read): the prefactors 1.6 and 0.88, the exponent 1/6 and the bound 0.74. The truncated cone
   cannot hold up to a = 1.7: a straight-flanked cone of height a r0 out to r0 (1 + 1.24 a) holds
   the column's volume only up to a = 0.59 (concave flanks hold less: the bound moves up a little).

   Build: make examples     Run: ./build/column_collapse3d (--aspect 0.5) (--dp 0.0041666667)
   Expect: the runout within 20 % of Lube's at 8 particles a radius (the default, 2.5-3 minutes on
   one core), within 6 % at 12; the height at the centre 8 % low at a = 0.5, 45 % low at a = 2
   (bench/VALIDATION.md, "Axisymmetric column collapse"); CSV, VTK snapshots, a picture.
   Smoke: column_collapse3d --dp 0.0125 --tend 0.01 */
#include "common.h"

#define COLUMN_RADIUS 0.05
#define FLOOR_RADIUS 0.25 /* the rings read: past Lube's runout at a = 4 (r0 (1 + 1.6 sqrt(4)) = 0.21 m) */

/* The cylinder about the vertical axis x = z = 0. */
static sps_real cylinder_sdf(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(sqrt((double)x[0] * x[0] + (double)x[2] * x[2]) - COLUMN_RADIUS);
}

/* The column the lattice holds: its height (the highest particle + dp/2) and the radius of the
   cylinder of that height holding its volume, n dp^3 (the lattice's height is a whole number of
   dp, and its circle's staircase holds 3.5 % more area than pi r0^2 at 8 particles a radius). */
static void lattice_column(const sps_world* w, double dp, double* height, double* radius) {
    const sps_real* y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const int n = sps_world_particle_count(w);
    int i;
    *height = 0;
    for (i = 0; i < n; ++i)
        if (y[i] + 0.5 * dp > *height) *height = y[i] + 0.5 * dp;
    *radius = sqrt(n * dp * dp * dp / (PI * *height));
}

/* Lube et al. 2004's scalings: the runout (r_inf - r0)/r0 and the height H_inf/r0 at aspect a. */
static double lube_runout(double a) { return a < 1.7 ? 1.24 * a : 1.6 * sqrt(a); }
static double lube_height(double a) { return a < 0.74 ? a : 0.88 * pow(a, 1.0 / 6); }

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_OG, .cfl = 0.4, .t_end = 0.6, .vtk_every = 0.05, .csv_every = 0.005, .E = 5.84e6, .nu = 0.3,
                        .rho0 = 2040, .out = "out/column_collapse3d", .jitter = 0, .seed = 1, .transport = 0, PNG_DEFAULTS};
    int floor_kind = 0; /* the --floor choice: 0 Coulomb, 1 no-slip */
    double dp = 0.00625, aspect = 2, mu, height, radius, a, toe = 0, farthest = 0, centre_height, wall, *top;
    double runout, runout_expected, height_expected;
    granular_options g = {0, 21.9, 0.1, SPS_CONE_PLANE_STRAIN};
    opt_spec opts[] = {
        {"aspect", OPT_REAL, &aspect, "aspect ratio a = H0/r0 (r0 = 0.05 m)", 0.2, 4, NULL},
        {"dp", OPT_REAL, &dp, "particle spacing [m]: r0/dp whole (0.00625: 8 particles a radius; 0.0041666667: 12)", 1e-3, 0.0125, NULL},
        {"floor", OPT_CHOICE, &floor_kind, "the floor: free-slip with Coulomb friction tan(phi), or no-slip", 0, 0, "coulomb|no-slip"},
        GRANULAR_OPTION_SPECS(g),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body soil, all = {0};
    sps_diagnostics d;
    sps_real lo[3] = {-COLUMN_RADIUS, 0, -COLUMN_RADIUS}, hi[3] = {COLUMN_RADIUS, 0, COLUMN_RADIUS};
    const sps_real floor_point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    const double axis[2] = {0, 0}; /* x and z of the cylinder's axis */
    const sps_real *x, *z;
    output_plan output;
    int rings, k, i, n, clustered, *counts;

    ex_options(argc, argv, "3D axisymmetric granular column collapse against Lube et al. 2004's scalings", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    hi[1] = (sps_real)(aspect * COLUMN_RADIUS);
    bd.name = "soil";
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    apply_granular(&g, &bd);
    wd.dim = 3;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-GRANULAR_GRAVITY;
    sps_world_create(&wd, &w);
    mu = floor_kind == 0 ? tan(g.phi * PI / 180) : 0;
    sps_world_add_wall(w, floor_point, up, floor_kind == 0 ? SPS_WALL_FREE_SLIP : SPS_WALL_NO_SLIP);
    if (floor_kind == 0) sps_world_set_wall_friction(w, 0, (sps_real)mu);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &soil);
    sps_body_add_sdf(w, soil, lo, hi, cylinder_sdf, NULL, NULL);
    lattice_column(w, dp, &height, &radius);
    a = height / radius;

    output_open(&output, &c, "column_collapse3d", "velocity", "");
    ex_plain_step(w, &output); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, ex_plain_step, &output);
    wall = output_close(w, &output);
    sps_world_diagnostics(w, all, &d);

    rings = (int)(FLOOR_RADIUS / dp);
    top = (double*)calloc((size_t)rings, sizeof(double));
    counts = (int*)calloc((size_t)rings, sizeof(int));
    if (!top || !counts) return 1;
    ex_heap_surface(w, soil, dp, rings, axis, 3, top, counts);
    for (k = 0; k < rings && counts[k] >= 0.5 * PI * (2 * k + 1); ++k) toe = (k + 1) * dp;
    centre_height = top[0];
    x = sps_world_field(w, SPS_FIELD_POSITION_X);
    z = sps_world_field(w, SPS_FIELD_POSITION_Z);
    n = sps_world_particle_count(w);
    for (i = 0; i < n; ++i) {
        const double r = sqrt((double)x[i] * x[i] + (double)z[i] * z[i]) + 0.5 * dp;
        if (r > farthest) farthest = r;
    }
    clustered = ex_clustered_particles(w, dp, 0.5);
    runout = (toe - radius) / radius;
    runout_expected = lube_runout(a);
    height_expected = lube_height(a);
    printf("column_collapse3d: a = %g, dp = %g (%.1f particles a radius), %d particles, phi = %g deg, cone %d, zeta = %g, floor %s (mu %.3f), "
           "t = %.3g s\n  the lattice's column: H0 = %.4f m, r0 = %.4f m (the radius of its volume), a = %.3f\n", aspect, dp, COLUMN_RADIUS / dp, n,
           g.phi, g.cone, g.diffusion, floor_kind == 0 ? "Coulomb" : "no-slip", mu, (double)d.time, height, radius, a);
    printf("  runout r_inf (where the deposit's bottom layer ends) %.4f m: (r_inf - r0)/r0 = %.3f, Lube et al. 2004 %.3f (%+.1f%%);\n"
           "  farthest particle %.4f m: %.3f\n", toe, runout, runout_expected, 100 * (runout / runout_expected - 1), farthest,
           (farthest - radius) / radius);
    printf("  height at the centre H_inf %.4f m: H_inf/r0 = %.3f, Lube et al. 2004 %.3f (%+.1f%%)\n", centre_height, centre_height / radius,
           height_expected, 100 * (centre_height / radius / height_expected - 1));
    printf("  largest speed at the end %.3g m/s, kinetic energy %.3g J, plastic work %.4g J, %d particles closer than 0.5 dp to another\n",
           (double)d.max_speed, (double)d.kinetic_energy, (double)d.plastic_work, clustered);
    printf("RESULT case=column_collapse3d aspect=%g aspect_lattice=%.4f radius_lattice=%.5f dp=%g phi=%g cone=%d zeta=%g floor=%s t=%.4g "
           "runout=%.4f runout_expected=%.4f runout_error=%.4f height=%.4f height_expected=%.4f height_error=%.4f toe=%.4f farthest=%.4f "
           "max_speed=%.3g clustered=%d %s particles=%d steps=%ld wall_s=%.2f ns_per_particle_step=%.1f out=%s\n",
           aspect, a, radius, dp, g.phi, g.cone, g.diffusion, floor_kind == 0 ? "coulomb" : "no-slip", (double)d.time, runout, runout_expected,
           runout / runout_expected - 1, centre_height / radius, height_expected, centre_height / radius / height_expected - 1, toe,
           farthest, (double)d.max_speed, clustered, common_result_fields(&c), n, d.acoustic_steps, wall,
           ns_per_particle_step(w, wall, d.acoustic_steps), c.out);
    free(top);
    free(counts);
    sps_world_destroy(w);
    return 0;
}
