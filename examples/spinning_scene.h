/* spinning_scene.h - the spinning plate (2D, BENCHMARKS.md A3) or, with SPINNING_CUBE defined,
   the spinning cube (3D, A4): its defaults, its set-up and its angular-momentum error. Shared by
   examples/spinning_plate.c (and spinning_cube.c) and bench/realtime.c; include after common.h.

   A unit square (cube) centred at the origin, rho0 1100, E 1.7e7, nu 0.45 (cube: 0.3), starts
   in rigid rotation at omega about z with no constraint. */
#ifndef SPS_SPINNING_SCENE_H
#define SPS_SPINNING_SCENE_H

#ifdef SPINNING_CUBE
#define CASE "spinning_cube"
#define TITLE "3D spinning cube (BENCHMARKS.md A4)"
#define DIM 3
#define NU 0.3
#else
#define CASE "spinning_plate"
#define TITLE "2D spinning plate (BENCHMARKS.md A3)"
#define DIM 2
#define NU 0.45
#endif

/* The case's settings; every option of the program may override them. */
static common_options spinning_defaults(void) {
    common_options c = {.shear = SPS_SHEAR_GNO_A, .cfl = 0.4, .t_end = 0.5, .vtk_every = 0.1, .csv_every = 0.001,
                        .E = 1.7e7, .nu = NU, .rho0 = 1100, .out = "out/" CASE, .jitter = 0, .seed = 1};
    return c;
}

static void rigid_rotation(const sps_real x[3], sps_real v[3], void* user) {
    double omega = *(const double*)user; /* v = omega e_z x r */
    v[0] = -omega * x[1];
    v[1] = omega * x[0];
    v[2] = 0;
}

/* Creates the world: spacing dp, the settings of c, spinning at omega [rad/s]. Any error ends
   the program with its message and exit status 2 (ex_check). */
static void spinning_scene(const common_options* c, double dp, double omega, sps_world** w, sps_body* block) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_real lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {0.5, 0.5, 0.5};
    wd.dim = DIM;
    wd.dp = dp;
    bd.name = CASE;
    apply_common(c, &wd, &bd);
    *w = ex_create(&wd);
    ex_check(*w, sps_world_add_body(*w, &bd, block));
    ex_add_box(*w, *block, lo, hi, c->jitter, c->seed);
    ex_check(*w, sps_body_set_velocity(*w, *block, rigid_rotation, &omega));
}

/* |L_z(t) - L_z(0)| / |L_z(0)|: theory conserves the angular momentum exactly. */
static double angmom_error(const sps_diagnostics* d, const sps_diagnostics* d0) {
    return fabs(d->angular_momentum[2] - d0->angular_momentum[2]) / fabs(d0->angular_momentum[2]);
}

#endif
