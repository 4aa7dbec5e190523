/* realtime.c - a real-time loop: the spinning plate (examples/spinning_plate.c) shown at a fixed
   frame rate. Each frame advances the world with sps_world_advance_frame by one frame period of
   simulated time (the library chooses the sub-steps), within a wall budget (a fraction of the
   frame period, a hard cap), then waits for the next frame as a renderer with vsync would.
   It reports simulated seconds per wall second (1: real time; below 1 the budget cut frames
   short and the scene ran in slow motion), the physics time per frame, the worst frame and how
   many frames overran the budget by more than one sub-step (the API's promise), and the
   angular-momentum error of the run, sampled at the CSV rows (--csv-every, 0.5 s of simulated
   time by default: a row is an sps_world_diagnostics call, about two sub-steps' cost, and the
   loop's cost, not the library's).

   Build: make        Run: ./build/realtime --dp 0.05 --fps 60 --threads 1
   The acceptance (1089 particles, 600 frames): ./build/realtime --dp 0.03 --fps 60 --threads 1 --frames 600 --tend 100
   Also: ./build/float/realtime (sps_real = float). --budget 0 runs the deterministic frames
   only: the loop then shows how far from real time the machine is. --substeps k > 0 runs k
   sub-steps per frame instead (sps_world_advance_substeps). --dim 3 spins the cube instead: the
   3D jelly (2197 particles, E 1e5, 2 threads): ./build/float/realtime --dim 3 --dp 0.077 --E 1e5
   --omega 2 --threads 2 --frames 600 --tend 100 */
#define SPHSOLID_IMPLEMENTATION /* this program's own copy: common.h asks for POSIX before any
                                   header, so the frame budget gets the monotonic clock */
#include "../examples/common.h"
#include "../examples/scenes/spinning.h"


int main(int argc, char** argv) {
    spinning_params p = {.dim = 2, .dp = 0.05, .omega = 50};
    double fps = 60, budget = 0.8, period, start, next, physics = 0, physics_max = 0, max_err = 0, substep_max = 0;
    int substeps = 0, max_frames = 0;
    long frames = 0, over_budget = 0, over_one_substep = 0;
    common_options c = {.shear = SPS_SHEAR_GNO_A, .cfl = 0.4, .t_end = 0.5, .vtk_every = 0, .csv_every = 0.5, .E = SPINNING_E,
                        .nu = SPINNING_NU_2D, .rho0 = SPINNING_RHO0, .out = "out/realtime", .jitter = 0, .seed = 1, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"dim", OPT_INT, &p.dim, "2: the spinning plate (A3); 3: the spinning cube (A4, nu 0.3 unless --nu)", 2, 3, NULL},
        {"dp", OPT_REAL, &p.dp, "particle spacing [m]", 1e-3, 0.25, NULL},
        {"omega", OPT_REAL, &p.omega, "angular velocity [rad/s]", 0, 1e4, NULL},
        {"fps", OPT_REAL, &fps, "frames per second", 1, 1000, NULL},
        {"budget", OPT_REAL, &budget, "wall budget of a frame's physics, fraction of the frame period; 0 = none", 0, 1, NULL},
        {"frames", OPT_INT, &max_frames, "stop after this many frames (0: at --tend of simulated time)", 0, 1e7, NULL},
        {"substeps", OPT_INT, &substeps, "acoustic sub-steps per frame (sps_world_advance_substeps); 0 = one frame period of simulated time", 0, 1e7, NULL},
        COMMON_OPTION_SPECS(c),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body block, all = {0};
    sps_diagnostics d0, d;
    output_plan output;

    c.png_every = 0; /* no picture unless asked for: the loop's wall time is the measurement */
    opt_parse(argc, argv, "real-time loop of the spinning plate (sps_world_advance_frame)", opts, (int)(sizeof opts / sizeof *opts));
    if (p.dim == 3 && c.nu == SPINNING_NU_2D) c.nu = SPINNING_NU_3D; /* the cube's (A4) unless --nu was given */
    apply_common(&c, &wd, &bd);
    wd.keep_last_good_state = 1; /* as the examples set it (apply_common sets options only) */
    p.jitter = c.jitter;
    p.seed = c.seed;
    wd.log = ex_log;
    ex_check(NULL, spinning_create(wd, &bd, "spinning_plate", &p, &w, &block));
    sps_world_diagnostics(w, all, &d0);
    d = d0;
    period = 1 / fps;
    (void)block;
    output_open(&output, &c, "realtime", "velocity", ",frame_physics_ms");

    start = next = wall_seconds();
    while (sps_world_time(w) < c.t_end && (max_frames == 0 || frames < max_frames)) {
        const long steps_before = sps_world_substep_count(w);
        const double t0 = wall_seconds();
        double spent;
        long steps;
        sps_real covered;
        char extra[32];
        sps_result r = substeps > 0 ? sps_world_advance_substeps(w, substeps, budget * period, &covered)
                                    : sps_world_advance_frame(w, (sps_real)period, budget * period, &covered);
        if (r != SPS_OK) {
            fprintf(stderr, "realtime: %s\n", sps_world_last_error(w));
            return 1;
        }
        spent = wall_seconds() - t0;
        steps = sps_world_substep_count(w) - steps_before;
        ++frames;
        physics += spent;
        if (spent > physics_max) physics_max = spent;
        if (steps > 0 && spent / steps > substep_max) substep_max = spent / steps; /* the frame's mean sub-step: the overrun allowed */
        if (budget > 0 && spent > budget * period) ++over_budget;
        if (budget > 0 && spent > budget * period + spent / (double)(steps > 0 ? steps : 1))
            ++over_one_substep;
        snprintf(extra, sizeof extra, ",%.3f", 1e3 * spent);
        if (output_tick(w, &output, extra, &d) && spinning_angmom_error(&d, &d0) > max_err) max_err = spinning_angmom_error(&d, &d0);
        progress(sps_world_time(w), c.t_end, start, c.quiet);
        next += period;
        if (next < wall_seconds()) next = wall_seconds(); /* a late frame shifts the schedule: no catch-up burst */
        sleep_until(next);
    }
    output_close(w, &output);
    sps_world_diagnostics(w, all, &d);
    printf("RESULT case=realtime dim=%d shear=%s dp=%g fps=%g budget=%g substeps_per_frame=%d frames=%ld sim_s=%.4f wall_s=%.2f "
           "sim_per_wall=%.3f mean_substeps=%.1f physics_ms_mean=%.2f physics_ms_max=%.2f frames_over_budget=%ld "
           "frames_over_budget_plus_one_substep=%ld "
           "max_angmom_err=%.4g%% %s particles=%d steps=%ld advection_steps=%ld out=%s\n",
           p.dim, shear_name(c.shear), p.dp, fps, budget, substeps, frames, (double)sps_world_time(w), wall_seconds() - start,
           sps_world_time(w) / (wall_seconds() - start), (double)d.acoustic_steps / frames, 1e3 * physics / frames, 1e3 * physics_max,
           over_budget, over_one_substep, 100 * max_err, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, c.out);
    sps_world_destroy(w);
    return 0;
}
