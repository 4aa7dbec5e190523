/* test_sphsolid.c - unit, invariant and regression tests of sphsolid.h: the runner, its helpers
   and the RUN list; the tests are in one file per part of the library, included below
   (test_numerics.c, test_api.c, test_solids.c, test_fluids.c, test_rigid.c,
   test_periodic.c).

   Build and run:    make build/test_sphsolid && ./build/test_sphsolid
   Under sanitizers: make build/test_sanitize && ./build/test_sanitize --quick
   Options: --quick skips the long physics regressions (the three plate periods); --no-fork
   runs every test in this process (for a debugger); --exclude text skips the tests whose names
   contain text; any other argument is a substring filter on the test names (e.g.
   ./build/test_sphsolid riemann).

   Each test is a short function returning 0 on pass. ENSURE(c) and ENSURE_NEAR(a, b, tol) print
   the failing line and return 1. Every tolerance carries a comment with its reason. Each test
   runs in a child process, so a crash fails that test only. The last line printed is
   "N passed, M failed"; the exit status is 0 iff M == 0.

   Most worlds here use threads = 1: results are bit-identical for any thread count (checked by
   test_determinism_threads), and one thread keeps the small runs fast on a busy machine. */
#define _POSIX_C_SOURCE 200809L /* mkstemp, clock_gettime */
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

/* ============================================================================================ */
/* >>runner                                                                                     */

static int g_quick;             /* --quick: skip the long physics regressions */
static const char* g_filter;    /* substring filter on test names, or NULL */
static const char* g_exclude[8]; /* --exclude (repeatable): skip the tests whose names contain one */
static int g_excluded;
static int g_passed, g_failed, g_skipped;

#include "ensure.h"

/* Runs one test in a child process (fork), so a crash is reported as that test's failure and
   the other tests still run; --no-fork runs it in-process (for a debugger). */
static int g_no_fork;
/* is_long: 0 a quick test, 1 a long one (skipped by --quick), 2 a validation run of a minute or
   more, run only when named (its figure is in bench/VALIDATION.md; make test stays short). */
static void run_test(const char* name, int (*fn)(void), int is_long) {
    double t0;
    int failed, status = 0;
    pid_t pid;
    int k;
    for (k = 0; k < g_excluded; ++k)
        if (strstr(name, g_exclude[k])) return;
    if (g_filter && !strstr(name, g_filter)) return;
    if (is_long == 2 && !g_filter) {
        printf("%-40s skipped (run it by name: about a minute)\n", name);
        ++g_skipped;
        return;
    }
    if (is_long && g_quick) {
        printf("%-40s skipped (--quick)\n", name);
        ++g_skipped;
        return;
    }
    printf("%s\n", name);
    fflush(stdout);
    t0 = wall_seconds();
    if (g_no_fork || (pid = fork()) < 0) {
        failed = fn() != 0;
    } else if (pid == 0) {
        int r = fn();
        fflush(stdout);
        exit(r == 0 ? 0 : 1);
    } else {
        waitpid(pid, &status, 0);
        failed = !(WIFEXITED(status) && WEXITSTATUS(status) == 0);
        if (WIFSIGNALED(status)) printf("    CRASHED with signal %d\n", WTERMSIG(status));
    }
    printf("%-40s %-6s %7.2f s\n", name, failed ? "FAILED" : "ok", wall_seconds() - t0);
    fflush(stdout);
    if (failed) ++g_failed; else ++g_passed;
}
#define RUN(fn) run_test(#fn, fn, 0)
#define RUN_LONG(fn) run_test(#fn, fn, 1)
#define RUN_NAMED(fn) run_test(#fn, fn, 2)

/* ============================================================================================ */
/* >>helpers                                                                                    */

#define PI 3.14159265358979323846
static const sps_body ALL_BODIES = {0};

/* A log callback that keeps stderr clean and remembers the last message. */
static char g_log_last[2048];
static int g_log_count;
static void quiet_log(int level, const char* message, void* user) {
    (void)level; (void)user;
    snprintf(g_log_last, sizeof g_log_last, "%s", message);
    ++g_log_count;
}

/* An allocator that counts: live bytes, peak live bytes, total bytes and calls; it refuses the
   call number fail_at (1-based; 0: none) to exercise the out-of-memory paths. */
typedef struct { size_t live, peak, total; long calls, fail_at; } counting_allocator;
typedef union { size_t size; double align_d; void* align_p; long double align_ld; } alloc_header;
static void* counting_alloc(size_t size, void* user) {
    counting_allocator* c = (counting_allocator*)user;
    alloc_header* h;
    if (c->fail_at && c->calls + 1 == c->fail_at) { c->calls++; return NULL; }
    h = (alloc_header*)malloc(sizeof(alloc_header) + size);
    if (!h) return NULL;
    h->size = size;
    c->live += size;
    c->total += size;
    c->calls++;
    if (c->live > c->peak) c->peak = c->live;
    return h + 1;
}
static void counting_free(void* ptr, void* user) {
    counting_allocator* c = (counting_allocator*)user;
    alloc_header* h = (alloc_header*)ptr - 1;
    c->live -= h->size;
    free(h);
}

/* Deterministic pseudo-random numbers in [-1, 1) (64-bit LCG, Knuth's MMIX constants). */
static double rnd(unsigned long long* s) {
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 4503599627370496.0 - 1.0; /* 2^52 */
}

/* A world with the defaults, dim, dp and one thread, the quiet logger. NULL on failure. */
static sps_world* new_world(int dim, double dp) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w = NULL;
    wd.dim = dim;
    wd.dp = dp;
    wd.threads = 1;
    wd.log = quiet_log;
    return sps_world_create(&wd, &w) == SPS_OK ? w : NULL;
}

/* Fills [lo, hi) of a new body with the given shear formulation. */
static sps_body add_block_rotation(sps_world* w, sps_shear shear, sps_rotation rotation, const double lo_[3], const double hi_[3],
                                   int* count) {
    sps_body_def bd = sps_default_body_def();
    sps_body b = {0};
    sps_real lo[3], hi[3];
    int a;
    for (a = 0; a < 3; ++a) { lo[a] = lo_[a]; hi[a] = hi_[a]; }
    bd.shear = shear;
    bd.rotation = rotation;
    if (sps_world_add_body(w, &bd, &b) != SPS_OK) return b;
    if (sps_body_add_box(w, b, lo, hi, count) != SPS_OK) b.id = 0;
    return b;
}
static sps_body add_block(sps_world* w, sps_shear shear, const double lo_[3], const double hi_[3], int* count) {
    return add_block_rotation(w, shear, SPS_ROTATION_MEAN, lo_, hi_, count);
}

/* Steps until at least n acoustic sub-steps have been taken. */
static sps_result step_acoustic(sps_world* w, long n) {
    sps_diagnostics d;
    do {
        sps_result r = sps_world_step(w);
        if (r != SPS_OK) return r;
        sps_world_diagnostics(w, ALL_BODIES, &d);
    } while (d.acoustic_steps < n);
    return SPS_OK;
}

/* Von Mises stress of a symmetric stress (xx xy xz yy yz zz); in 2D sigma_zz is not part of
   the state (the library's 2D deviator uses tr/2), so the 2D formula has sigma_zz = 0. */
static double von_mises(const double s[6], int dim) {
    if (dim == 2) return sqrt(s[0] * s[0] + s[3] * s[3] - s[0] * s[3] + 3 * s[1] * s[1]);
    return sqrt(0.5 * ((s[0] - s[3]) * (s[0] - s[3]) + (s[3] - s[5]) * (s[3] - s[5]) + (s[5] - s[0]) * (s[5] - s[0])) +
                3 * (s[1] * s[1] + s[2] * s[2] + s[4] * s[4]));
}

/* ============================================================================================ */
/* The tests, one file per part of the library (each is a block of static test functions). */
#include "test_numerics.c"
#include "test_api.c"
#include "test_solids.c"
#include "test_fluids.c"
#include "test_rigid.c"
#include "test_periodic.c"
#include "test_open.c"

int main(int argc, char** argv) {
    int i;
    /* OpenMP's default wait policy spins in barriers. On a machine whose cores are busy with
       other jobs, a spinning thread waits a whole scheduler time slice for a descheduled team
       mate at each of the ~8 barriers of an acoustic sub-step (measured: the determinism test
       took 82 s instead of 2 s). The tests measure no speed, so ask for passive waiting; the
       runtime reads the variable at start-up, hence the one re-execution. */
    if (!getenv("OMP_WAIT_POLICY") && setenv("OMP_WAIT_POLICY", "passive", 1) == 0) execvp(argv[0], argv);
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--quick") == 0) g_quick = 1;
        else if (strcmp(argv[i], "--no-fork") == 0) g_no_fork = 1;
        else if (strcmp(argv[i], "--exclude") == 0 && i + 1 < argc && g_excluded < 8) g_exclude[g_excluded++] = argv[++i];
        else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            printf("usage: %s [--quick] [--no-fork] [--exclude text]... [name-filter]\n"
                   "  --quick         skip the long physics regressions\n"
                   "  --no-fork       run the tests in this process (for a debugger)\n"
                   "  --exclude text  skip the tests whose names contain text (up to 8 times)\n", argv[0]);
            return 0;
        } else g_filter = argv[i];
    }
    printf("sphsolid %s (%s), %s run\n", sps_version(), sps_is_double() ? "double" : "float", g_quick ? "quick" : "full");

    RUN(test_kernel_partition_of_unity);
    RUN(test_kernel_integral);
    RUN(test_kernel_derivative);
    RUN(test_gradient_antisymmetry);
    RUN(test_moment_matrix_lattice);
    RUN(test_velocity_gradient_affine);
    RUN(test_rodrigues_matrix);
    RUN(test_riemann_pressure);
    RUN(test_rigid_rotation_zero_increment);
    RUN(test_spinning_disc_stays_rigid);
    RUN(test_translation_keeps_steps);
    RUN(test_momentum_conservation);
    RUN(test_tl_reference_state);
    RUN(test_tl_homogeneous_stretch);
    RUN(test_tl_hourglass_affine);
    RUN(test_tl_momentum);
    RUN(test_tl_j2_return);
    RUN(test_tl_damage_rate);
    RUN(test_tl_damage_tension_only);
    RUN(test_uniform_translation);
    RUN(test_damping_decays_velocity_exactly);
    RUN(test_external_acceleration);
    RUN(test_add_after_step_and_constraints);
    RUN(test_determinism_threads);
    RUN(test_bodies_independent);
    RUN(test_contact_momentum);
    RUN(test_still_water);
    RUN(test_fluid_corner_images);
    RUN(test_fluid_smoothing_warning);
    RUN(test_fluid_churn_warned);
    RUN(test_fluid_hexagonal_rest);
    RUN(test_fluid_hexagonal_fill);
    RUN(test_standing_wave_period);
    RUN(test_drucker_prager_return_on_cone);
    RUN(test_drucker_prager_cones_match_mohr_coulomb);
    RUN(test_granular_limiter_off_in_expansion);
    RUN(test_granular_block_at_rest);
    RUN(test_coincident_particles_stay_finite);
    RUN(test_granular_bad_input);
    RUN(test_transport_keeps_linear_momentum);
    RUN(test_tvf_counts_walls);
    RUN(test_fluid_bad_input);
    RUN(test_fluid_transport_carries_velocity);
    RUN(test_contact_determinism);
    RUN(test_j2_radial_return_on_surface);
    RUN(test_j2_hardening_raises_surface);
    RUN(test_j2_uniaxial_strain_closed_form);
    RUN(test_j2_bad_input);
    RUN_LONG(test_j2_taylor_bar_coarse); /* 2-4 s; 22 s under the sanitizers, which run --quick */
    RUN(test_wall_stops_body);
    RUN(test_contact_bad_input);
    RUN(test_rigid_wall_body);
    RUN(test_pair_forces_survive_adds);
    RUN(test_frame_arguments_rejected);
    RUN(test_frame_single_stepping_equals_steps);
    RUN(test_frame_whole_advection_steps_equal_steps);
    RUN(test_frame_cuts_advection_steps);
    RUN(test_frame_wall_budget);
    RUN(test_validation_world_def);
    RUN(test_validation_zero_def);
    RUN(test_validation_body_def);
    RUN(test_validation_handles_and_args);
    RUN(test_handle_foreign_world_same_tag);
    RUN(test_step_empty_world);
    RUN(test_result_strings_and_version);
    RUN(test_unstable_run_reported);
    RUN(test_unstable_huge_velocity);
    RUN(test_memory_runaway_particle);
    RUN(test_null_world_arguments);
    RUN(test_bad_arguments_named);
    RUN(test_field_by_name);
    RUN(test_set_particle);
    RUN(test_warnings_for_silent_cases);
    RUN(test_energy_watchdog);
    RUN(test_energy_account_driven);
    RUN(test_foreign_and_destroyed_handles);
    RUN(test_flat_box_is_empty);
    RUN(test_step_empty_body);
    RUN(test_add_after_step_stress_output);
    RUN(test_guard_escape);
    RUN(test_guard_time_step_collapse);
    RUN(test_guard_nonfinite_state);
    RUN(test_last_good_state);
    RUN(test_world_validate);
    RUN(test_memory_no_allocation_in_steps);
    RUN(test_memory_out_of_memory_everywhere);
    RUN(test_determinism_repeated_runs);
    RUN(test_vtk_writer);
    RUN(test_vtk_series);
    RUN(test_restart_round_trip);
    RUN(test_restart_last_good_state);
    RUN(test_restart_refused);
    RUN(test_restart_crafted);
    RUN(test_csv_row);
    RUN_LONG(test_plate2d_period_eno_a);
    RUN_LONG(test_plate2d_period_eno);
    RUN_LONG(test_plate2d_period_eno_a_pair);
    RUN_LONG(test_hourglass_og_breaks_others_do_not);
    RUN_LONG(test_damped_cantilever_sag);
    RUN_NAMED(test_plate3d_period_mode22); /* 1 min on 2 cores: ./build/test_sphsolid plate3d_period */
    RUN(test_tl_hourglass_is_energy_gradient);
    RUN(test_tl_hourglass_stiffness_symmetric);
    RUN(test_tl_time_step_frequency);
    RUN(test_tl_artificial_viscosity);
    /* friction and material damping */
    RUN(test_friction_block_on_slope);
    RUN(test_friction_momentum_exact);
    RUN(test_friction_unused_is_free);
    RUN(test_kelvin_voigt_rigid_motion_free);
    RUN(test_friction_damping_bad_input);
    RUN(test_coupling_momentum);
    RUN(test_coupling_hydrostatic_rest);
    RUN(test_coupling_floating_block);
    RUN(test_coupling_light_soft_block);
    RUN(test_coupling_bad_input);
    /* the scenes users write */
    RUN(test_user_scene_tumbling_default);
    RUN(test_watchdog_names_rotation);
    RUN(test_setup_body_behind_wall);
    RUN(test_setup_quiet_mistakes_warn);
    RUN(test_warnings_print_once);
    RUN(test_setup_mistakes_named);
    RUN(test_rigid_motion_about_current_centre);
    RUN(test_frame_in_seconds);
    RUN(test_user_scene_dragged_jelly);
    RUN(test_kelvin_voigt_decay_account);
    RUN(test_contact_damping_pair);
    RUN(test_contact_damping_wall);
    RUN(test_contact_damping_thread_count);
    RUN(test_contact_damping_bad_input);
    RUN(test_granular_block_holds_shape);
    RUN(test_granular_lattice_moment);
    RUN(test_granular_free_grain_stops);
    RUN_LONG(test_granular_infinite_slope_stands_and_flows);
    RUN_LONG(test_granular_slope_floor_holds);
    RUN(test_restart_every_def_field);
    RUN(test_restart_ul_j2_into_tl_j2);
    RUN(test_unread_parameter_warned);
    RUN(test_missing_pass_instance);
    RUN(test_fluid_rest_long);
    RUN(test_zigzag_tells_zigzag_from_flow);
    RUN(test_generic_dispatch_per_kind);
    RUN(test_oas_instances_2d_only);
    RUN(test_frame_budget_always_advances);
    RUN(test_penalty_in_pressure_pass_matches_paper);
    RUN(test_penalty_in_pressure_pass_holds_plate);
    RUN(test_penalty_in_pressure_pass_def);
    RUN(test_rigid_free_invariants);
    RUN(test_rigid_rests_on_floor);
    RUN(test_rigid_bad_input);
    RUN(test_rigid_restart_and_threads);
    RUN(test_periodic_crossing_keeps_momentum);
    RUN(test_periodic_body_across_boundary);
    RUN(test_periodic_bad_input);
    RUN(test_periodic_taylor_green_decay);
    RUN(test_periodic_threads_and_restart);
    RUN(test_open_channel_steady);
    RUN(test_open_kill_zone);
    RUN(test_open_threads_and_restart);
    RUN(test_open_ramped_inflow_counted);
    RUN(test_open_bad_input);
    RUN(test_open_restart_every_zone_item);

    if (g_skipped) printf("(%d long tests skipped)\n", g_skipped);
    printf("%d passed, %d failed\n", g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}
