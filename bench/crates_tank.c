/* crates_tank - the game-demo scene of free rigid bodies: the demo's water tank (examples/scenes/
   jelly.h: 2 m wide, water 0.32 m deep, dp 0.04) with --crates free rigid crates (0.16 m,
   density 600) and --rafts jelly rafts (0.40 x 0.20 m, density 500) released in rows above the
   water, run for --frames frames of 1/--fps s each (sps_world_advance_frame without a budget: the
   deterministic frames, every one computed in full). Prints the physics time per frame (mean,
   median and the slowest after the first second), the frames per second it sustains and whether
   that reaches --fps; the scene is the library's alone (no drawing).

   Usage: ./build/crates_tank [--crates N] [--rafts N] [--frames N] [--fps F] [--threads N] */
#define SPHSOLID_IMPLEMENTATION
#include "../examples/common.h"
#include "../examples/scenes/jelly.h"

static int compare(const void* a, const void* b) {
    const double x = *(const double*)a, y = *(const double*)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char** argv) {
    int crates = 20, rafts = 10, frames = 600, threads = 2, k, f;
    double fps = 60, *ms, sum = 0;
    opt_spec opts[] = {
        {"crates", OPT_INT, &crates, "free rigid crates", 0, 200, NULL},
        {"rafts", OPT_INT, &rafts, "jelly rafts", 0, 100, NULL},
        {"frames", OPT_INT, &frames, "frames to run", 61, 1e6, NULL},
        {"fps", OPT_REAL, &fps, "frames per second (simulated 1/fps s each)", 1, 240, NULL},
        {"threads", OPT_INT, &threads, "OpenMP threads, 0 = all", 0, 1024, NULL},
    };
    jelly_scene s;
    sps_diagnostics d;
    ex_short_openmp_spin(argv);
    opt_parse(argc, argv, "crates and jelly rafts in the demo's water tank, timed per frame", opts, (int)(sizeof opts / sizeof *opts));
    ex_check(NULL, jelly_create(threads, ex_log, 1, &s));
    for (k = 0; k < crates + rafts; ++k) { /* rows of 4 above the water, 0.3 m apart */
        const int crate = k < crates, column = k % 4, row = k / 4;
        const double cx = -0.75 + 0.5 * column, y0 = JELLY_WATER_DEPTH + 0.1 + 0.3 * row;
        sps_body_def bd = jelly_body_def(SPS_SHEAR_ENO_A, crate ? "crate" : "raft");
        sps_body b;
        if (crate) {
            const sps_real lo[3] = {(sps_real)(cx - JELLY_CRATE / 2), (sps_real)y0, 0}, hi[3] = {(sps_real)(cx + JELLY_CRATE / 2), (sps_real)(y0 + JELLY_CRATE), 0};
            bd.material.kind = SPS_MATERIAL_RIGID_DYNAMIC;
            bd.material.density = JELLY_CRATE_RHO0;
            bd.material.youngs_modulus = (sps_real)(JELLY_E * JELLY_CRATE_RHO0 / JELLY_RHO0);
            bd.rotation = SPS_ROTATION_AUTO;
            bd.friction = (sps_real)0.5;
            bd.contact_damping = (sps_real)0.5;
            bd.damping = 1;
            ex_check(s.w, sps_world_add_body(s.w, &bd, &b));
            ex_check(s.w, sps_body_add_box(s.w, b, lo, hi, NULL));
        } else {
            const sps_real lo[3] = {(sps_real)(cx - JELLY_RAFT_W / 2), (sps_real)y0, 0}, hi[3] = {(sps_real)(cx + JELLY_RAFT_W / 2), (sps_real)(y0 + JELLY_RAFT_H), 0};
            bd.material.density = JELLY_RAFT_RHO0;
            bd.damping = 2;
            ex_check(s.w, sps_world_add_body(s.w, &bd, &b));
            ex_check(s.w, sps_body_add_box(s.w, b, lo, hi, NULL));
        }
    }
    ms = (double*)malloc(sizeof(double) * (size_t)frames);
    for (f = 0; f < frames; ++f) {
        const double t0 = wall_seconds();
        ex_check(s.w, sps_world_advance_frame(s.w, (sps_real)(1 / fps), 0, NULL));
        ms[f] = 1e3 * (wall_seconds() - t0);
    }
    ex_check(s.w, sps_world_diagnostics(s.w, (sps_body){0}, &d));
    for (f = (int)fps; f < frames; ++f) sum += ms[f];
    qsort(ms + (int)fps, (size_t)(frames - (int)fps), sizeof(double), compare);
    printf("RESULT case=crates_tank crates=%d rafts=%d particles=%d frames=%d fps_target=%g substeps_per_frame=%.1f ms_per_frame_mean=%.2f "
           "ms_median=%.2f ms_slowest=%.2f fps=%.1f real_time=%s threads=%d sim_s=%.2f\n",
           crates, rafts, sps_world_particle_count(s.w), frames, fps, (double)d.acoustic_steps / frames, sum / (frames - (int)fps),
           ms[(int)fps + (frames - (int)fps) / 2], ms[frames - 1], 1e3 * (frames - (int)fps) / sum, 1e3 / fps >= sum / (frames - (int)fps) ? "yes" : "no",
           threads, (double)sps_world_time(s.w));
    free(ms);
    sps_world_destroy(s.w);
    return 0;
}
