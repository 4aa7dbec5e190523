/* fuzz_restore_scenes.h - the scenes whose saves the restart fuzzers mutate (tests/fuzz_restore.c,
   tests/fuzz_restore_libfuzzer.c). Small (a few hundred particles: a case restores in well
   under a millisecond), each stepped a few times so that every item of its state is set.
   Together: every material kind and both solvers; analytic walls, a wall body (prescribed
   work), contact, constraints, observers; the last good state, the kept pair forces
   (SPS_ROTATION_PAIR), the velocity gradient (GNO-A), damage, J2 and Drucker-Prager plastic
   state, the transport correction, Kelvin-Voigt damping. Include after sphsolid.h. */
#ifndef FUZZ_RESTORE_SCENES_H
#define FUZZ_RESTORE_SCENES_H

#define FUZZ_SCENES 6

static const char* fuzz_scene_name(int k) {
    static const char* const names[FUZZ_SCENES] = {"elastic", "tl_damage", "fluid", "granular", "j2_3d", "svk_frozen"};
    return names[k];
}

static void fuzz_quiet(int level, const char* msg, void* user) { (void)level; (void)msg; (void)user; }
/* A swirl about (0.1, 0.05): shears every body it is given to. */
static void fuzz_swirl(const sps_real x[3], sps_real v[3], void* user) {
    const sps_real speed = *(const sps_real*)user;
    v[0] = -speed * (x[1] - (sps_real)0.05) / (sps_real)0.05;
    v[1] = speed * (x[0] - (sps_real)0.1) / (sps_real)0.1;
    v[2] = 0;
}

/* Scene k at spacing dp (0.01; 0.02 for the smaller saves of the libFuzzer seeds), stepped a
   few times; NULL on failure (the message goes to stderr). */
static sps_world* fuzz_scene_build(int k, sps_real dp) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def(), rigid = sps_default_body_def();
    sps_world* w = NULL;
    sps_body a, b;
    sps_observer obs;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.06, 0.05}, floor_lo[3] = {-0.05, -0.04, 0}, floor_hi[3] = {0.25, -0.01, 0};
    sps_real clo[3] = {0, 0, 0}, chi[3] = {0.02, 0.06, 0.05}, at[3] = {0.1, 0.03, 0.02}, tank_hi[3] = {0.2, 0.3, 0};
    sps_real speed = 2;
    int ok = 1, steps = 5, s;
    wd.dp = dp;
    wd.threads = 1;
    wd.log = fuzz_quiet;
    if (k == 4) wd.dim = 3;
    if (k == 0 || k == 2 || k == 3) wd.gravity[1] = -9.81;
    if (k == 0) wd.keep_last_good_state = 1;
    if (k == 5) wd.frozen_geometry = 1;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    bd.track_stress = 1;
    switch (k) {
    case 0: /* elastic, updated Lagrangian, on a wall body: contact, pair rotation, damping */
        bd.rotation = SPS_ROTATION_PAIR;
        bd.contact = 1;
        bd.material.viscosity = 1e3; /* Kelvin-Voigt */
        rigid.material.kind = SPS_MATERIAL_RIGID;
        rigid.contact = 1;
        rigid.name = "floor";
        ok = sps_world_add_body(w, &rigid, &b) == SPS_OK && sps_body_add_box(w, b, floor_lo, floor_hi, NULL) == SPS_OK;
        break;
    case 1: /* total Lagrangian: Neo-Hookean with damage, beside a J2 body */
        bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
        bd.material.kind = SPS_MATERIAL_NEO_HOOKEAN;
        bd.material.tl.damage_strain = 2e-3;
        rigid = bd;
        rigid.material.kind = SPS_MATERIAL_J2;
        rigid.material.j2.yield_stress = 2e3;
        rigid.material.tl.damage_strain = 0;
        rigid.name = "tl_j2";
        ok = sps_world_add_body(w, &rigid, &b) == SPS_OK && sps_body_add_box(w, b, floor_lo, floor_hi, NULL) == SPS_OK &&
             sps_body_set_velocity(w, b, fuzz_swirl, &speed) == SPS_OK;
        break;
    case 2: /* water in a tank of analytic walls, with the transport correction */
        bd.material.kind = SPS_MATERIAL_FLUID;
        bd.material.density = 1000;
        bd.material.fluid.sound_speed = 20;
        bd.material.viscosity = 1e-3;
        bd.transport = SPS_TRANSPORT_UTVF;
        bd.track_stress = 0;
        speed = 0.2;
        ok = sps_world_add_box_walls(w, lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) == SPS_OK;
        break;
    case 3: /* granular on a wall, with stress diffusion */
        bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
        bd.material.density = 1850;
        bd.material.youngs_modulus = 1.8e6;
        bd.material.poisson_ratio = 0.3;
        bd.material.granular.cohesion = 5e3;
        bd.material.granular.friction_angle = 25;
        bd.material.granular.stress_diffusion = 0.1;
        bd.track_stress = 0;
        speed = 0.1;
        ok = sps_world_add_box_walls(w, lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) == SPS_OK;
        break;
    case 4: /* 3D, J2, GNO-A (the velocity gradient is state) */
        bd.shear = SPS_SHEAR_GNO_A;
        bd.material.kind = SPS_MATERIAL_J2;
        bd.material.j2.yield_stress = 2e3;
        hi[0] = 0.06; hi[1] = 0.05; hi[2] = 0.05;
        at[0] = 0.03;
        break;
    default: /* Saint Venant-Kirchhoff, frozen geometry, ENO with the mean rotation */
        bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
        bd.material.kind = SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF;
        bd.material.tl.artificial_viscosity = 0.5;
        break;
    }
    ok = ok && sps_world_add_body(w, &bd, &a) == SPS_OK && sps_body_add_box(w, a, lo, hi, NULL) == SPS_OK &&
         sps_body_set_velocity(w, a, fuzz_swirl, &speed) == SPS_OK && sps_world_add_observer(w, a, at, &obs) == SPS_OK;
    if (ok && k != 2 && k != 3) ok = sps_body_constrain_box(w, a, clo, chi, SPS_AXIS_ALL, NULL, NULL) == SPS_OK;
    for (s = 0; ok && s < steps; ++s) ok = sps_world_step(w) == SPS_OK;
    if (!ok) {
        fprintf(stderr, "fuzz scene %d: %s\n", k, sps_world_last_error(w));
        sps_world_destroy(w);
        return NULL;
    }
    return w;
}

#endif
