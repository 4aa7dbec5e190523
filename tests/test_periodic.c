/* test_periodic.c - periodic axes (world def periodic[3]; PERIODIC in the header's manual):
   momentum across the boundary, a body across it, bad input, thread counts and restart.
   Included by test_sphsolid.c; its list of tests is
   run_periodic_tests at its end. */

/* A 2D world of spacing dp whose axes x (and y if both) repeat with period L from the origin;
   threads as given. */
static sps_world* periodic_world(double dp, double L, int both, int threads) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w = NULL;
    wd.dp = dp;
    wd.threads = threads;
    wd.periodic[0] = L;
    wd.periodic[1] = both ? L : 0;
    wd.log = quiet_log;
    return sps_world_create(&wd, &w) == SPS_OK ? w : NULL;
}

static void periodic_uniform_flow(const sps_real x[3], sps_real v[3], void* user) {
    (void)x; (void)user;
    v[0] = 0.3; v[1] = -0.2; v[2] = 0;
}

/* A fluid filling a fully periodic box, moving as one at (0.3, -0.2) m/s: every particle
   crosses both boundaries within 0.5 s and keeps its velocity (no pair across a boundary is
   missed or counted twice: either would push the particles near it), the momentum stays to
   round-off, and every position is in the box after each step. */
static int test_periodic_crossing_keeps_momentum(void) {
    const double L = 0.1;
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0};
    sps_world* w = periodic_world(0.005, L, 1, 1);
    sps_body_def bd = sps_default_body_def();
    sps_body fluid;
    sps_diagnostics d0, d;
    int steps = 0, i, outside = 0;
    ENSURE(w);
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 5;
    ENSURE(sps_world_add_body(w, &bd, &fluid) == SPS_OK && sps_body_add_box(w, fluid, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_set_velocity(w, fluid, periodic_uniform_flow, NULL) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d0) == SPS_OK);
    while (sps_world_time(w) < 0.5) {
        const sps_real *x, *y;
        ENSURE(sps_world_step(w) == SPS_OK);
        ++steps;
        x = sps_world_field(w, SPS_FIELD_POSITION_X);
        y = sps_world_field(w, SPS_FIELD_POSITION_Y);
        for (i = 0; i < sps_world_particle_count(w); ++i) outside += !(x[i] >= 0 && x[i] < L && y[i] >= 0 && y[i] < L);
    }
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
    printf("    %d steps, t = %.3f s (%.1f periods along x): momentum (%.3e, %.3e) relative change, max speed %.6f m/s, %d positions "
           "outside\n", steps, (double)d.time, 0.3 * (double)d.time / L, (double)((d.linear_momentum[0] - d0.linear_momentum[0]) / d0.linear_momentum[0]),
           (double)((d.linear_momentum[1] - d0.linear_momentum[1]) / d0.linear_momentum[1]), (double)d.max_speed, outside);
    ENSURE(outside == 0);
    /* round-off of the pair sums, 1e-16 a pair, over ~1000 sub-steps */
    ENSURE_NEAR(d.linear_momentum[0], d0.linear_momentum[0], 1e-10 * fabs(d0.linear_momentum[0]));
    ENSURE_NEAR(d.linear_momentum[1], d0.linear_momentum[1], 1e-10 * fabs(d0.linear_momentum[1]));
    /* a missed or doubled image would accelerate the particles at the boundary by c0^2 drho/rho dW:
       metres per second within a step; the uniform flow stays uniform to round-off */
    ENSURE_NEAR(d.max_speed, sqrt(0.3 * 0.3 + 0.2 * 0.2), 1e-9);
    sps_world_destroy(w);
    return 0;
}

static void periodic_shake(const sps_real x[3], sps_real v[3], void* user) {
    const double lo = *(const double*)user; /* the block's left edge: the field follows the block */
    v[0] = 0;
    v[1] = 0.05 * sin(3.14159265358979 * (x[0] - lo) / 0.06);
    v[2] = 0;
}

/* A body across the boundary is the same body: an elastic, a granular and a fluid block 0.06 m
   wide, given a transverse velocity field, run once in the middle of a periodic box and once
   across its boundary (x from 0.07 to 0.13, period 0.1): the kinetic energy and the momentum
   agree to round-off after 200 sub-steps (a pair missed across the boundary would split the
   block in two). At rest, the straddling elastic block stays at rest (in equilibrium). */
static int periodic_straddle_energy(sps_material_kind kind, double lo, double* energy, double* momentum_y) {
    const sps_real blo[3] = {(sps_real)lo, 0.02, 0}, bhi[3] = {(sps_real)(lo + 0.06), 0.06, 0};
    sps_world* w = periodic_world(0.004, 0.1, 0, 1);
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    sps_diagnostics d;
    if (!w) return 1;
    bd.material.kind = kind;
    if (kind == SPS_MATERIAL_FLUID) bd.material.fluid.sound_speed = 10;
    if (kind == SPS_MATERIAL_DRUCKER_PRAGER) { bd.material.granular.cohesion = 1e4; bd.material.granular.friction_angle = 30; }
    if (sps_world_add_body(w, &bd, &b) != SPS_OK || sps_body_add_box(w, b, blo, bhi, NULL) != SPS_OK) return 1;
    if (sps_body_set_velocity(w, b, periodic_shake, &lo) != SPS_OK) return 1;
    if (step_acoustic(w, 200) != SPS_OK || sps_world_diagnostics(w, ALL_BODIES, &d) != SPS_OK) return 1;
    *energy = (double)d.kinetic_energy;
    *momentum_y = (double)d.linear_momentum[1];
    sps_world_destroy(w);
    return 0;
}
static int test_periodic_body_across_boundary(void) {
    const sps_material_kind kinds[3] = {SPS_MATERIAL_ELASTIC, SPS_MATERIAL_DRUCKER_PRAGER, SPS_MATERIAL_FLUID};
    int k;
    for (k = 0; k < 3; ++k) {
        double e_mid, e_across, p_mid, p_across;
        ENSURE(periodic_straddle_energy(kinds[k], 0.02, &e_mid, &p_mid) == 0);
        ENSURE(periodic_straddle_energy(kinds[k], 0.07, &e_across, &p_across) == 0);
        printf("    kind %d: kinetic energy %.9e J/m in the middle, %.9e across the boundary; momentum %.3e, %.3e\n", (int)kinds[k], e_mid,
               e_across, p_mid, p_across);
        ENSURE(e_mid > 0);
        ENSURE_NEAR(e_across, e_mid, 1e-8 * e_mid); /* the offsets differ by the rounding of x - L */
        ENSURE_NEAR(p_across, p_mid, 1e-8 * sqrt(e_mid * 1e-3));
    }
    { /* at rest across the boundary: no force */
        const sps_real blo[3] = {0.07, 0.02, 0}, bhi[3] = {0.13, 0.06, 0};
        sps_world* w = periodic_world(0.004, 0.1, 0, 1);
        sps_body_def bd = sps_default_body_def();
        sps_body b;
        sps_diagnostics d;
        ENSURE(w);
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, blo, bhi, NULL) == SPS_OK);
        ENSURE(step_acoustic(w, 200) == SPS_OK && sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
        ENSURE(d.max_speed < 1e-12); /* a lattice at rest: every force sums to zero but round-off */
        sps_world_destroy(w);
    }
    return 0;
}

/* Bad input names the field, its value and the allowed range: a negative, a too short and a NaN
   period, z periodic in 2D, frozen geometry with a periodic axis, a wall across a periodic
   axis, a total-Lagrangian and a free rigid body in a periodic world; a wall surface velocity
   along the wall's normal or for a wall that does not exist. */
static int test_periodic_bad_input(void) {
    sps_world_def wd = sps_default_world_def();
    char msg[512];
    sps_world* w;
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    const sps_real point[3] = {0, 0, 0}, across[3] = {1, 0, 0}, along[3] = {0, 1, 0};
    wd.log = quiet_log;
    wd.periodic[0] = -1;
    ENSURE(sps_world_def_check(&wd, msg, sizeof msg) == SPS_ERR_INVALID_ARG && strstr(msg, "periodic[0] = -1 m, allowed 0"));
    wd.periodic[0] = 0.03; /* 6 h = 0.078 m at dp = 0.01, h = 1.3 dp */
    ENSURE(sps_world_def_check(&wd, msg, sizeof msg) == SPS_ERR_INVALID_ARG && strstr(msg, "periodic[0] = 0.03 m") && strstr(msg, "0.078"));
    wd.periodic[0] = (sps_real)NAN;
    ENSURE(sps_world_def_check(&wd, msg, sizeof msg) == SPS_ERR_INVALID_ARG && strstr(msg, "periodic[0] = nan"));
    wd.periodic[0] = 0;
    wd.periodic[2] = 1;
    ENSURE(sps_world_def_check(&wd, msg, sizeof msg) == SPS_ERR_INVALID_ARG && strstr(msg, "periodic[2] = 1 m in a 2D world"));
    wd.periodic[2] = 0;
    wd.periodic[1] = 1;
    wd.frozen_geometry = 1;
    ENSURE(sps_world_def_check(&wd, msg, sizeof msg) == SPS_ERR_INVALID_ARG && strstr(msg, "frozen_geometry = 1 with a periodic axis"));
    wd.frozen_geometry = 0;
    wd.periodic_origin[1] = (sps_real)INFINITY;
    ENSURE(sps_world_def_check(&wd, msg, sizeof msg) == SPS_ERR_INVALID_ARG && strstr(msg, "periodic_origin[1] = inf"));
    wd.periodic_origin[1] = 0;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    ENSURE(sps_world_add_wall(w, point, along, SPS_WALL_NO_SLIP) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "periodic axis 1"));
    ENSURE(sps_world_add_wall(w, point, across, SPS_WALL_NO_SLIP) == SPS_OK); /* parallel to y: allowed */
    { /* a moving surface: along the wall only, on a wall that exists */
        const sps_real normal_speed[3] = {1, 0.5, 0}, belt[3] = {0, 0.5, 0};
        ENSURE(sps_world_set_wall_velocity(w, 0, normal_speed) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "along wall 0's normal"));
        ENSURE(sps_world_set_wall_velocity(w, 1, belt) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "wall = 1, allowed 0..0"));
        ENSURE(sps_world_set_wall_velocity(w, 0, belt) == SPS_OK);
    }
    bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
    bd.material.kind = SPS_MATERIAL_NEO_HOOKEAN;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "total-Lagrangian"));
    bd = sps_default_body_def();
    bd.material.kind = SPS_MATERIAL_RIGID_DYNAMIC;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "free rigid body"));
    sps_world_destroy(w);
    return 0;
}

/* The Taylor-Green vortex u = -cos(2 pi x) sin(2 pi y), v = sin(2 pi x) cos(2 pi y) [m/s] of
   the unit box, with its pressure -rho0/4 (cos 4 pi x + cos 4 pi y). */
static void taylor_green_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const double pi = 3.14159265358979323846;
    (void)user;
    v[0] = (sps_real)(-cos(2 * pi * x[0]) * sin(2 * pi * x[1]));
    v[1] = (sps_real)(sin(2 * pi * x[0]) * cos(2 * pi * x[1]));
    v[2] = 0;
}
static sps_real taylor_green_pressure(const sps_real x[3], void* user) {
    const double pi = 3.14159265358979323846;
    (void)user;
    return (sps_real)(-1000.0 / 4 * (cos(4 * pi * x[0]) + cos(4 * pi * x[1])));
}
/* The kinetic energy E(0.2 s) / E(0) of the Taylor-Green vortex at Re 100 (examples/taylor_green.c
   at 1/dp = 20, h = 1.5 dp, c0 = 10 U, TVF) with the given fluid dissipation; -1 on failure. */
static double taylor_green_energy_ratio(sps_fluid_dissipation dissipation) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0};
    sps_world* w = NULL;
    sps_body fluid;
    sps_diagnostics d0, d;
    double ratio = -1;
    wd.dp = (sps_real)(1.0 / 20);
    wd.h_over_dp = (sps_real)1.5;
    wd.periodic[0] = wd.periodic[1] = 1;
    wd.log = quiet_log;
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 10;
    bd.material.viscosity = 10; /* rho0 U L / Re */
    bd.transport = SPS_TRANSPORT_TVF;
    bd.material.fluid.dissipation = dissipation;
    if (sps_world_create(&wd, &w) == SPS_OK && sps_world_add_body(w, &bd, &fluid) == SPS_OK && sps_body_add_box(w, fluid, lo, hi, NULL) == SPS_OK &&
        sps_body_set_velocity(w, fluid, taylor_green_velocity, NULL) == SPS_OK &&
        sps_body_set_pressure(w, fluid, taylor_green_pressure, NULL) == SPS_OK && sps_world_diagnostics(w, ALL_BODIES, &d0) == SPS_OK &&
        sps_world_advance(w, (sps_real)0.2, NULL, NULL) == SPS_OK && sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK)
        ratio = (double)(d.kinetic_energy / d0.kinetic_energy);
    sps_world_destroy(w);
    return ratio;
}

/* material.fluid.dissipation: the Taylor-Green vortex at Re 100 decays at its physical rate, E/E0 =
   exp(-16 pi^2 t / Re), only without the Riemann solver's momentum dissipation, an artificial
   viscosity of about 3 |v_ij . e_ij| h, which at 1/dp = 20 is of the order of nu; and the
   setting is refused for an inviscid fluid and out of its range. */
static int test_periodic_taylor_green_decay(void) {
    const double exact = exp(-16 * 3.14159265358979323846 * 3.14159265358979323846 * 0.2 / 100);
    const double riemann = taylor_green_energy_ratio(SPS_FLUID_DISSIPATION_RIEMANN), none = taylor_green_energy_ratio(SPS_FLUID_DISSIPATION_NONE);
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body b;
    printf("    E(0.2 s)/E0: exact %.4f, Riemann dissipation %.4f (%+.1f %%), none %.4f (%+.1f %%)\n", exact, riemann,
           100 * (riemann / exact - 1), none, 100 * (none / exact - 1));
    ENSURE(riemann > 0 && none > 0);
    /* measured -1.4 %: the particles' disorder under TVF and the lattice Laplacian's truncation
       at 1/dp = 20; 3 % leaves room for the float build */
    ENSURE_NEAR(none, exact, 0.03 * exact);
    /* measured -15.7 %: the Riemann term's numerical viscosity; 10 % is what the option is for */
    ENSURE(riemann < 0.9 * exact);
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 10;
    bd.material.fluid.dissipation = SPS_FLUID_DISSIPATION_NONE;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG &&
           strstr(sps_world_last_error(w), "material.fluid.dissipation = 1 or 2 with material.viscosity = 0"));
    bd.material.viscosity = 1;
    bd.material.fluid.dissipation = (sps_fluid_dissipation)3;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "material.fluid.dissipation = 3, allowed 0"));
    sps_world_destroy(w);
    return 0;
}

/* Thread counts and restart: a fluid crossing a periodic channel between two no-slip walls,
   driven by gravity along it, at 1 and 2 threads: bit for bit; saved at 1 thread and restored
   into a fresh world, the run goes on bit for bit; a world with another period refuses the file. */
static sps_world* periodic_channel(int threads, double L) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.05, 0}, floor_[3] = {0, 0, 0}, up[3] = {0, 1, 0}, roof[3] = {0, 0.05, 0}, down[3] = {0, -1, 0};
    sps_world* w = NULL;
    sps_body b;
    wd.dp = 0.005;
    wd.threads = threads;
    wd.periodic[0] = L;
    wd.gravity[0] = 2;
    wd.log = quiet_log;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 10;
    bd.material.viscosity = 1;
    sps_world_add_wall(w, floor_, up, SPS_WALL_NO_SLIP);
    sps_world_add_wall(w, roof, down, SPS_WALL_NO_SLIP);
    if (sps_world_add_body(w, &bd, &b) != SPS_OK || sps_body_add_box(w, b, lo, hi, NULL) != SPS_OK) {
        sps_world_destroy(w);
        return NULL;
    }
    return w;
}
static int periodic_same_state(sps_world* a, sps_world* b) {
    const sps_field f[4] = {SPS_FIELD_POSITION_X, SPS_FIELD_POSITION_Y, SPS_FIELD_VELOCITY_X, SPS_FIELD_VELOCITY_Y};
    int k;
    if (sps_world_particle_count(a) != sps_world_particle_count(b)) return 0;
    for (k = 0; k < 4; ++k)
        if (memcmp(sps_world_field(a, f[k]), sps_world_field(b, f[k]), sizeof(sps_real) * (size_t)sps_world_particle_count(a)) != 0) return 0;
    return 1;
}
static int test_periodic_threads_and_restart(void) {
    char path[] = "/tmp/sps_periodic_XXXXXX";
    sps_world *w1 = periodic_channel(1, 0.1), *w2 = periodic_channel(2, 0.1), *w3 = periodic_channel(2, 0.1), *other = periodic_channel(1, 0.12);
    sps_diagnostics d;
    int fd;
    ENSURE(w1 && w2 && w3 && other);
    ENSURE(sps_world_advance(w1, 0.05, NULL, NULL) == SPS_OK && sps_world_advance(w2, 0.05, NULL, NULL) == SPS_OK);
    ENSURE(periodic_same_state(w1, w2));
    ENSURE((fd = mkstemp(path)) >= 0);
    close(fd);
    ENSURE(sps_world_save(w1, path) == SPS_OK);
    ENSURE(sps_world_restore(w3, path) == SPS_OK);
    ENSURE(sps_world_restore(other, path) != SPS_OK);
    printf("    another period: %s\n", sps_world_last_error(other));
    ENSURE(strstr(sps_world_last_error(other), "periodic[0]"));
    remove(path);
    ENSURE(sps_world_advance(w1, 0.1, NULL, NULL) == SPS_OK && sps_world_advance(w2, 0.1, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_advance(w3, 0.1, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_diagnostics(w1, ALL_BODIES, &d) == SPS_OK);
    printf("    t = %.2f s: mean flow %.4f m/s, %ld sub-steps\n", (double)d.time, (double)(d.linear_momentum[0] / (1000 * 0.1 * 0.05)),
           d.acoustic_steps);
    ENSURE(d.linear_momentum[0] > 0); /* driven along x */
    ENSURE(periodic_same_state(w1, w2)); /* 1 and 2 threads: bit for bit */
    ENSURE(periodic_same_state(w1, w3)); /* restored: bit for bit */
    sps_world_destroy(w1);
    sps_world_destroy(w2);
    sps_world_destroy(w3);
    sps_world_destroy(other);
    return 0;
}

/* ============================================================================================ */
/* This file's tests, in the order the runner runs them (tests/test_sphsolid.c calls run_periodic_tests). */
static void run_periodic_tests(void) {
    RUN(test_periodic_crossing_keeps_momentum);
    RUN(test_periodic_body_across_boundary);
    RUN(test_periodic_bad_input);
    RUN(test_periodic_taylor_green_decay);
    RUN(test_periodic_threads_and_restart);
}
