/* heap3d.c - the angle of repose of a cohesionless cone: a cylinder of grains lifted slowly (3D).

   A cylinder D = 0.05 m across and H = 0.1 m high of cohesionless Drucker-Prager soil (the C4
   material: rho0 = 2040, E = 5.84 MPa, nu = 0.3, c = 0, psi = 0; friction angle phi = --phi)
   stands in the middle of a rough (no-slip) floor 0.3 m x 0.3 m, is released from zero stress
   under g = 9.8 (along -y) and slumps into a cone. As in heap2d, the body's velocity damping
   (--damping c [1/s]) keeps the collapse quasi-static, like a cylinder lifted slowly. At the end
   the cone's surface is read in rings dp wide about the axis (the highest particle + dp/2 in
   each ring, rings of fewer than 3 particles left out) and its flank fitted by a straight line
   between 20 % and 80 % of its height: the angle of repose. The yield cone is --cone (default
   the plane-strain fit: a slope stands at phi; a conical heap's flank is not in plane strain,
   so the 3D cones, --cone compression / extension / compromise, bracket it).

   Build: make examples     Run: ./build/heap3d --phi 30 --threads 2
   Expect: see bench/VALIDATION.md, "Angle of repose"; CSV, VTK snapshots, a picture.
   Smoke: heap3d --dp 0.01 --tend 0.01 */
#include "common.h"

#define FLOOR_LENGTH 0.3
#define COLUMN_RADIUS 0.025
#define COLUMN_HEIGHT 0.1

/* The cylinder about the vertical axis through the floor's middle. */
static sps_real cylinder_sdf(const sps_real x[3], void* user) {
    const double dx = x[0] - 0.5 * FLOOR_LENGTH, dz = x[2] - 0.5 * FLOOR_LENGTH;
    (void)user;
    return (sps_real)(sqrt(dx * dx + dz * dz) - COLUMN_RADIUS);
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_OG, .cfl = 0.4, .t_end = 2, .vtk_every = 0.25, .csv_every = 0.01, .E = 5.84e6, .nu = 0.3,
                        .rho0 = 2040, .out = "out/heap3d", .jitter = 0, .seed = 1, .transport = 0, PNG_DEFAULTS};
    double dp = 0.005, damping = 100, height = 0, slope, angle, wall, *top;
    granular_options g = {0, 30, 0.1, SPS_CONE_PLANE_STRAIN};
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 1e-3, 0.02, NULL},
        {"damping", OPT_REAL, &damping, "velocity damping c [1/s] that keeps the collapse quasi-static (0: the fast collapse)", 0, 1e3, NULL},
        GRANULAR_OPTION_SPECS(g),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body soil, all = {0};
    sps_diagnostics d;
    const sps_real lo[3] = {0.5 * FLOOR_LENGTH - COLUMN_RADIUS, 0, 0.5 * FLOOR_LENGTH - COLUMN_RADIUS},
                   hi[3] = {0.5 * FLOOR_LENGTH + COLUMN_RADIUS, COLUMN_HEIGHT, 0.5 * FLOOR_LENGTH + COLUMN_RADIUS};
    const sps_real tank_lo[3] = {0, 0, 0}, tank_hi[3] = {FLOOR_LENGTH, 2 * COLUMN_HEIGHT, FLOOR_LENGTH};
    output_plan output;
    double axis[2]; /* x and z of the cylinder's axis */
    int rings, k;

    ex_options(argc, argv, "3D angle of repose: a cohesionless cylinder lifted slowly slumps into a cone", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    bd.name = "soil";
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    apply_granular(&g, &bd);
    bd.damping = (sps_real)damping;
    wd.dim = 3;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-GRANULAR_GRAVITY;
    sps_world_create(&wd, &w);
    sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_NO_SLIP);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &soil);
    sps_body_add_sdf(w, soil, lo, hi, cylinder_sdf, NULL, NULL);

    output_open(&output, &c, "heap3d", "velocity", "");
    ex_plain_step(w, &output); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, ex_plain_step, &output);
    wall = output_close(w, &output);
    sps_world_diagnostics(w, all, &d);

    rings = (int)(0.5 * FLOOR_LENGTH / dp);
    axis[0] = axis[1] = 0.5 * FLOOR_LENGTH;
    top = (double*)calloc((size_t)rings, sizeof(double));
    if (!top) return 1;
    ex_heap_surface(w, all, dp, rings, axis, 3, top, NULL);
    for (k = 0; k < rings; ++k)
        if (top[k] > height) height = top[k];
    slope = ex_flank_slope(top, dp, 0, rings - 1, height);
    angle = atan(fabs(slope)) * 180 / PI;
    printf("heap3d: cylinder %g m across, %g m high, dp = %g, %d particles, phi = %g deg, cone %d, damping %g 1/s, t = %.3g s\n",
           2 * COLUMN_RADIUS, COLUMN_HEIGHT, dp, sps_world_particle_count(w), g.phi, g.cone, damping, (double)d.time);
    printf("  height %.4f m; flank %.1f degrees against phi = %g deg (%+.1f deg); largest speed %.3g m/s\n", height, angle, g.phi,
           angle - g.phi, (double)d.max_speed);
    printf("RESULT case=heap3d angle=%.2f phi=%g cone=%d height=%.4f damping=%g dp=%g t=%.4g max_speed=%.3g %s particles=%d steps=%ld "
           "wall_s=%.2f out=%s\n", angle, g.phi, g.cone, height, damping, dp, (double)d.time, (double)d.max_speed, common_result_fields(&c),
           sps_world_particle_count(w), d.acoustic_steps, wall, c.out);
    free(top);
    sps_world_destroy(w);
    return 0;
}
