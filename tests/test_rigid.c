/* test_rigid.c - free rigid bodies (material.kind = SPS_MATERIAL_RIGID_DYNAMIC; FREE RIGID BODIES
   in the header's manual): the free turn's invariants, rest on a floor, bad input, restart and
   thread counts. Included by test_sphsolid.c; its list of tests is
   run_rigid_tests at its end. */

/* A world (threads, gravity g downwards along y) with a free rigid box [lo, hi) of spacing dp;
   friction mu and contact damping zeta on the body. */
static sps_world* rigid_box_world(int dim, double dp, int threads, double g, const double lo_[3], const double hi_[3], double mu,
                                  double zeta, sps_body* body) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_real lo[3], hi[3];
    int a;
    wd.dim = dim;
    wd.dp = dp;
    wd.threads = threads;
    wd.gravity[1] = -g;
    wd.log = quiet_log;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    bd.material.kind = SPS_MATERIAL_RIGID_DYNAMIC;
    bd.friction = mu;
    bd.contact_damping = zeta;
    for (a = 0; a < 3; ++a) { lo[a] = lo_[a]; hi[a] = hi_[a]; }
    if (sps_world_add_body(w, &bd, body) != SPS_OK || sps_body_add_box(w, *body, lo, hi, NULL) != SPS_OK) {
        sps_world_destroy(w);
        return NULL;
    }
    return w;
}

/* An isolated asymmetric box (3D, sides 6 x 4 x 2 dp) spinning about an axis that is not
   principal, and moving: over 1e5 sub-steps its linear and angular momentum and its kinetic
   energy stay at their start to round-off (the implicit midpoint turn keeps |L| and the energy,
   the Cayley rotation the world's L; nothing else acts). In 2D the same for a disc-free box. */
static int test_rigid_free_invariants(void) {
    const double lo[3] = {-0.03, -0.02, -0.01}, hi[3] = {0.03, 0.02, 0.01};
    int dim;
    for (dim = 2; dim <= 3; ++dim) {
        sps_body b;
        sps_world* w = rigid_box_world(dim, 0.01, 1, 0, lo, hi, 0, 0, &b);
        const sps_real v[3] = {0.3, -0.2, 0.1}, omega[3] = {3, 20, 5};
        sps_diagnostics d0, d;
        sps_rigid_state st, s0;
        int a;
        ENSURE(w);
        ENSURE(sps_body_set_rigid_motion(w, b, v, omega) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d0) == SPS_OK);
        ENSURE(sps_body_rigid_state(w, b, &s0) == SPS_OK);
        ENSURE(step_acoustic(w, 100000) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
        ENSURE(sps_body_rigid_state(w, b, &st) == SPS_OK);
        printf("    %dD: %ld sub-steps, %.1f turns: energy %.3e, |p| %.3e, L about the centre %.3e, about the origin %.3e relative change\n",
               dim, d.acoustic_steps,
               (double)(d.time * SPS__SQRT(st.angular_velocity[0] * st.angular_velocity[0] + st.angular_velocity[1] * st.angular_velocity[1] +
                                            st.angular_velocity[2] * st.angular_velocity[2]) / (2 * PI)),
               (double)((d.kinetic_energy - d0.kinetic_energy) / d0.kinetic_energy),
               (double)((d.linear_momentum[0] - d0.linear_momentum[0]) / d0.linear_momentum[0]),
               (double)((st.angular_momentum[2] - s0.angular_momentum[2]) / s0.angular_momentum[2]),
               (double)((d.angular_momentum[2] - d0.angular_momentum[2]) / d0.angular_momentum[2]));
        /* round-off of the turn: about 1e-16 a sub-step, a random walk over 1e5 of them (1e-13) */
        ENSURE_NEAR(d.kinetic_energy, d0.kinetic_energy, 1e-11 * d0.kinetic_energy);
        for (a = 0; a < dim; ++a) ENSURE(d.linear_momentum[a] == d0.linear_momentum[a]); /* no force: v is not changed */
        for (a = 0; a < 3; ++a) ENSURE(st.angular_momentum[a] == s0.angular_momentum[a]); /* no torque, and the turn leaves L */
        /* about the origin M x X v joins: x, 1.3 m out at the end, carries the round-off of 2e5 additions */
        for (a = dim == 2 ? 2 : 0; a < 3; ++a) ENSURE_NEAR(d.angular_momentum[a], d0.angular_momentum[a], 1e-9 * fabs(d0.angular_momentum[2]));
        ENSURE(dim == 2 || fabs(st.angular_velocity[0] - 3) > 0.1); /* the axis is not principal: omega moves, L stays */
        sps_world_destroy(w);
    }
    return 0;
}

/* A free rigid box dropped on a floor with friction and contact damping comes to rest and stays:
   over 0.5 s after settling its centre moves less than 1e-6 m (no creep) and its speed stays
   below 1e-4 m/s (no jitter). The floor is tilted by nothing: gravity is along -y. */
static int test_rigid_rests_on_floor(void) {
    const double lo[3] = {-0.05, 0.01, -0.02}, hi[3] = {0.05, 0.06, 0.02};
    sps_body b;
    sps_world* w = rigid_box_world(2, 0.005, 1, 9.81, lo, hi, 0.5, 0.5, &b);
    const sps_real point[3] = {0, 0, 0}, normal[3] = {0, 1, 0};
    sps_rigid_state s0, s1;
    sps_diagnostics d;
    ENSURE(w);
    ENSURE(sps_world_add_wall(w, point, normal, SPS_WALL_FREE_SLIP) == SPS_OK);
    ENSURE(sps_world_set_wall_friction(w, 0, 0.5) == SPS_OK);
    ENSURE(sps_world_advance(w, 1.0, NULL, NULL) == SPS_OK);
    ENSURE(sps_body_rigid_state(w, b, &s0) == SPS_OK);
    ENSURE(sps_world_advance(w, 1.5, NULL, NULL) == SPS_OK);
    ENSURE(sps_body_rigid_state(w, b, &s1) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
    printf("    moved (%.3e, %.3e) m, rotated %.3e, speed %.3e m/s, max particle speed %.3e m/s\n",
           (double)(s1.position[0] - s0.position[0]), (double)(s1.position[1] - s0.position[1]), (double)(s1.rotation[3] - s0.rotation[3]),
           (double)SPS__SQRT(s1.velocity[0] * s1.velocity[0] + s1.velocity[1] * s1.velocity[1]), (double)d.max_speed);
    ENSURE(fabs(s1.position[0] - s0.position[0]) < 1e-6 && fabs(s1.position[1] - s0.position[1]) < 1e-6); /* 2e-4 dp: no creep */
    ENSURE(d.max_speed < 1e-4); /* no jitter: 1e-4 m/s is 1e-4 of the speed of a 5 cm fall */
    { /* its frame was taken at the first step: more particles are refused, not snapped into a reset frame */
        const sps_real more_lo[3] = {0.2, 0.2, 0}, more_hi[3] = {0.25, 0.25, 0};
        ENSURE(sps_body_add_box(w, b, more_lo, more_hi, NULL) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "before the first step"));
    }
    sps_world_destroy(w);
    return 0;
}

/* Bad input names the field: mass 0 and -1, an inertia tensor that is not positive definite or
   not symmetric, a free rigid body without particles (at the step), a fluid (or any other kind)
   given rigid-body calls, lock masks beyond 7, a rotation that is not one. */
static int test_rigid_bad_input(void) {
    const double lo[3] = {-0.03, -0.02, -0.01}, hi[3] = {0.03, 0.02, 0.01};
    const sps_real not_pd[9] = {1, 0, 0, 0, -1, 0, 0, 0, 1}, not_symmetric[9] = {1, 0.5, 0, 0, 1, 0, 0, 0, 1};
    const sps_real stretch[9] = {2, 0, 0, 0, 1, 0, 0, 0, 1}, position[3] = {0, 0, 0};
    sps_body b, empty, fluid;
    sps_rigid_state state;
    sps_world* w = rigid_box_world(3, 0.01, 1, 0, lo, hi, 0, 0, &b);
    sps_body_def bd = sps_default_body_def();
    ENSURE(w);
    ENSURE(sps_body_set_mass_properties(w, b, 0, NULL) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "mass = 0"));
    ENSURE(sps_body_set_mass_properties(w, b, -1, NULL) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "mass = -1"));
    ENSURE(sps_body_set_mass_properties(w, b, 1, not_pd) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "inertia"));
    ENSURE(sps_body_set_mass_properties(w, b, 1, not_symmetric) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "not symmetric"));
    ENSURE(sps_body_set_mass_properties(w, b, 2, NULL) == SPS_OK);
    ENSURE(sps_body_lock_axes(w, b, 8, 0) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "translation = 8"));
    ENSURE(sps_body_set_rigid_pose(w, b, position, stretch) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "rotation"));
    ENSURE(sps_body_apply_impulse(w, b, NULL, NULL) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "impulse"));
    { /* a constraint box would hold particles the body moves as one: refused, pointing to the locks */
        const sps_real clo[3] = {-1, -1, -1}, chi[3] = {1, 1, 1};
        ENSURE(sps_body_constrain_box(w, b, clo, chi, SPS_AXIS_ALL, NULL, NULL) == SPS_ERR_INVALID_ARG &&
               strstr(sps_world_last_error(w), "sps_body_lock_axes"));
    }
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 20;
    ENSURE(sps_world_add_body(w, &bd, &fluid) == SPS_OK);
    ENSURE(sps_body_set_mass_properties(w, fluid, 1, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "material.kind = 3 (fluid), allowed 7")); /* a fluid made rigid */
    bd = sps_default_body_def();
    bd.material.kind = SPS_MATERIAL_RIGID_DYNAMIC;
    bd.name = "crate";
    ENSURE(sps_world_add_body(w, &bd, &empty) == SPS_OK);
    ENSURE(sps_body_rigid_state(w, empty, &state) == SPS_ERR_STATE && strstr(sps_world_last_error(w), "'crate' has no particles"));
    ENSURE(sps_world_step(w) == SPS_ERR_STATE && strstr(sps_world_last_error(w), "'body' (index 1) has no particles")); /* the fluid, first */
    sps_world_destroy(w);
    return 0;
}

/* Restart and thread counts: a free rigid box thrown spinning onto a floor with friction next to
   an elastic block it hits; saved at 1 thread, restored at 2: the run goes on bit for bit, and
   the 2-thread run from the start ends where the 1-thread run does. */
static void rigid_scene(sps_world* w, sps_body* rigid) {
    const sps_real point[3] = {0, 0, 0}, normal[3] = {0, 1, 0}, v[3] = {1, -0.5, 0}, omega[3] = {0, 0, 8};
    const sps_real lo[3] = {0.08, 0.001, 0}, hi[3] = {0.12, 0.04, 0};
    sps_body_def bd = sps_default_body_def();
    sps_body elastic;
    bd.friction = 0.4;
    sps_world_add_wall(w, point, normal, SPS_WALL_FREE_SLIP);
    sps_world_set_wall_friction(w, 0, 0.4);
    sps_world_add_body(w, &bd, &elastic);
    sps_body_add_box(w, elastic, lo, hi, NULL);
    sps_body_set_rigid_motion(w, *rigid, v, omega);
}
static int test_rigid_restart_and_threads(void) {
    const double lo[3] = {-0.03, 0.01, 0}, hi[3] = {0.03, 0.04, 0};
    char path[] = "/tmp/sps_rigid_XXXXXX";
    sps_body b1, b2, b3;
    sps_world *w1 = rigid_box_world(2, 0.004, 1, 9.81, lo, hi, 0.4, 0.3, &b1), *w2 = rigid_box_world(2, 0.004, 2, 9.81, lo, hi, 0.4, 0.3, &b2);
    sps_world* w3 = rigid_box_world(2, 0.004, 1, 9.81, lo, hi, 0.4, 0.3, &b3);
    sps_rigid_state s1, s2, s3;
    int fd;
    ENSURE(w1 && w2 && w3);
    rigid_scene(w1, &b1);
    rigid_scene(w2, &b2);
    rigid_scene(w3, &b3);
    ENSURE(sps_world_advance(w1, 0.03, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_advance(w2, 0.03, NULL, NULL) == SPS_OK); /* the same steps: the last one lands on 0.03 */
    ENSURE((fd = mkstemp(path)) >= 0);
    close(fd);
    ENSURE(sps_world_save(w1, path) == SPS_OK);
    ENSURE(sps_world_restore(w3, path) == SPS_OK);
    remove(path);
    ENSURE(sps_world_advance(w1, 0.06, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_advance(w2, 0.06, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_advance(w3, 0.06, NULL, NULL) == SPS_OK);
    ENSURE(sps_body_rigid_state(w1, b1, &s1) == SPS_OK && sps_body_rigid_state(w2, b2, &s2) == SPS_OK && sps_body_rigid_state(w3, b3, &s3) == SPS_OK);
    printf("    centre (%.6f, %.6f), omega %.4f rad/s\n", (double)s1.position[0], (double)s1.position[1], (double)s1.angular_velocity[2]);
    ENSURE(s1.position[0] > 0.02); /* it moved, and hit something */
    ENSURE(memcmp(&s1, &s2, sizeof s1) == 0); /* 1 and 2 threads: bit for bit */
    ENSURE(memcmp(&s1, &s3, sizeof s1) == 0); /* restored: bit for bit */
    sps_world_destroy(w1);
    sps_world_destroy(w2);
    sps_world_destroy(w3);
    return 0;
}

/* ============================================================================================ */
/* This file's tests, in the order the runner runs them (tests/test_sphsolid.c calls run_rigid_tests). */
static void run_rigid_tests(void) {
    RUN(test_rigid_free_invariants);
    RUN(test_rigid_rests_on_floor);
    RUN(test_rigid_bad_input);
    RUN(test_rigid_restart_and_threads);
}
