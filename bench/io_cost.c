/* io_cost.c - what the files cost on the 2D plate (examples/plate2d.c, ENO-A with stress):
   the sizes of a legacy VTK snapshot in ASCII, in binary and in binary single precision, and of
   a restart file, and the wall time to write each, to restore, and of one advection step for scale (the minimum of --repeat
   runs of each). The restored run is checked against the saved one: a step from either gives
   the same positions bit for bit.

   Build: make build/io_cost      Run: ./build/io_cost --res 10 --tend 0.1 --threads 2 */
#define SPHSOLID_IMPLEMENTATION
#include "../examples/common.h"
#include "../examples/scenes/plate2d.h"

static sps_world* build_plate(int res, int threads) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    plate2d_params p = {res, 0.05, 0, 0};
    sps_world* w;
    sps_body plate;
    sps_observer tip;
    wd.threads = threads;
    wd.log = ex_log;
    bd.material.density = PLATE2D_RHO0;
    bd.material.youngs_modulus = PLATE2D_E;
    bd.material.poisson_ratio = PLATE2D_NU;
    bd.track_stress = 1;
    ex_check(NULL, plate2d_create(wd, &bd, &p, &w, &plate, &tip));
    return w;
}

static long size_of(const char* path) {
    FILE* f = fopen(path, "rb");
    long n = -1;
    if (f && fseek(f, 0, SEEK_END) == 0) n = ftell(f);
    if (f) fclose(f);
    return n;
}

int main(int argc, char** argv) {
    int res = 10, threads = 2, repeat = 20, k, same;
    double t_end = 0.1, best[6] = {1e30, 1e30, 1e30, 1e30, 1e30, 1e30};
    const char* dir = "out/io_cost";
    char vtk_a[512], vtk_b[512], vtk_s[512], restart[512];
    opt_spec opts[] = {
        {"res", OPT_INT, &res, "H/dp", 2, 200, NULL},
        {"tend", OPT_REAL, &t_end, "time of the snapshot [s]", 0, 10, NULL},
        {"threads", OPT_INT, &threads, "OpenMP threads, 0 = all", 0, 1024, NULL},
        {"repeat", OPT_INT, &repeat, "runs of each measurement (the minimum is reported)", 1, 1000, NULL},
        {"out", OPT_STRING, &dir, "output folder", 0, 0, NULL},
    };
    sps_vtk_options binary = sps_default_vtk_options(), single = sps_default_vtk_options();
    sps_world *w, *w2;
    opt_parse(argc, argv, "file sizes and costs of VTK snapshots and restart files (2D plate)", opts, (int)(sizeof opts / sizeof *opts));
    if (make_dirs(dir) != 0) { fprintf(stderr, "cannot create %s\n", dir); return 1; }
    snprintf(vtk_a, sizeof vtk_a, "%s/plate_ascii.vtk", dir);
    snprintf(vtk_b, sizeof vtk_b, "%s/plate_binary.vtk", dir);
    snprintf(vtk_s, sizeof vtk_s, "%s/plate_single.vtk", dir);
    snprintf(restart, sizeof restart, "%s/plate.restart", dir);
    binary.binary = 1;
    single.binary = 1;
    single.single_precision = 1;
    w = build_plate(res, threads);
    ex_check(w, sps_world_advance(w, t_end, NULL, NULL));
    w2 = build_plate(res, threads);
    for (k = 0; k < repeat; ++k) {
        double t0 = wall_seconds(), t1, t2, t3, t4, t5;
        ex_check(w, sps_world_write_vtk(w, vtk_a));
        t1 = wall_seconds();
        ex_check(w, sps_world_write_vtk_ex(w, vtk_b, &binary));
        t2 = wall_seconds();
        ex_check(w, sps_world_save(w, restart));
        t3 = wall_seconds();
        ex_check(w2, sps_world_restore(w2, restart));
        t4 = wall_seconds();
        ex_check(w, sps_world_write_vtk_ex(w, vtk_s, &single));
        t5 = wall_seconds();
        if (t5 - t4 < best[5]) best[5] = t5 - t4;
        if (t1 - t0 < best[0]) best[0] = t1 - t0;
        if (t2 - t1 < best[1]) best[1] = t2 - t1;
        if (t3 - t2 < best[2]) best[2] = t3 - t2;
        if (t4 - t3 < best[3]) best[3] = t4 - t3;
    }
    for (k = 0; k < repeat; ++k) { /* a step of the restored world, restored again each time */
        double t0;
        ex_check(w2, sps_world_restore(w2, restart));
        t0 = wall_seconds();
        ex_check(w2, sps_world_step(w2));
        if (wall_seconds() - t0 < best[4]) best[4] = wall_seconds() - t0;
    }
    ex_check(w, sps_world_step(w));
    same = memcmp(sps_world_field(w, SPS_FIELD_POSITION_X), sps_world_field(w2, SPS_FIELD_POSITION_X),
                  sizeof(sps_real) * (size_t)sps_world_particle_count(w)) == 0 &&
           memcmp(sps_world_field(w, SPS_FIELD_POSITION_Y), sps_world_field(w2, SPS_FIELD_POSITION_Y),
                  sizeof(sps_real) * (size_t)sps_world_particle_count(w)) == 0;
    printf("RESULT case=io_cost res=%d particles=%d threads=%d t=%g vtk_ascii_bytes=%ld vtk_binary_bytes=%ld vtk_single_bytes=%ld "
           "restart_bytes=%ld vtk_ascii_ms=%.3f vtk_binary_ms=%.3f vtk_single_ms=%.3f save_ms=%.3f restore_ms=%.3f step_ms=%.3f "
           "restored_same=%d\n",
           res, sps_world_particle_count(w), threads, (double)t_end, size_of(vtk_a), size_of(vtk_b), size_of(vtk_s), size_of(restart),
           1e3 * best[0], 1e3 * best[1], 1e3 * best[5], 1e3 * best[2], 1e3 * best[3], 1e3 * best[4], same);
    sps_world_destroy(w);
    sps_world_destroy(w2);
    return same ? 0 : 1;
}
