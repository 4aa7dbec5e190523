/* open_cost - what open boundaries cost while the particle count changes: a viscous channel
   (H = 0.01 m, --res particles across, 2 H long, no-slip walls y = 0 and y = H) that starts empty
   but for its inflow buffer, filled by a parabolic inflow (U = 0.01 m/s, Re = 1, c0 = 30 U, as
   examples/channel_flow.c) and drained by an outflow zone at its end, so that particles are
   created every few advection steps (a row of the buffer crosses every dp / (u dt) steps) and
   removed once the front arrives. Per advection step the wall time per particle sub-step (the count
   grows 15-fold while the channel fills), from the step the channel holds a quarter of its
   final count on (a few dozen particles are all fixed costs); printed per scene (with
   sps_world_reserve of the final count ahead, and without it: the arrays grow by half when full)
   its median, its largest and their ratio (the acceptance: no step above 2x the median), the
   count at the start and the end and how many steps changed it, and the median of the steps that
   changed the count against the median of those that did not (what a creation or removal adds). Timed in the process's CPU time
   (one thread by default: with more, the CPU time is the team's), so that a step preempted by
   another process does not count; the machine's load average is printed with them.
   bench/VALIDATION.md, "Open boundaries".

   Usage: ./build/open_cost [--res 20] [--steps 3000] [--threads 1] */
#define _POSIX_C_SOURCE 200112L
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define H 0.01
#define U 0.01

/* The process's CPU time [s]: what the step did, without the time slices other processes took
   (a 2-core machine shared with others preempts a 0.1 ms step for milliseconds). */
static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void parabola(const sps_real x[3], sps_real t, void* user, sps_real v[3]) {
    (void)t; (void)user;
    v[0] = (sps_real)(4 * U * x[1] * (H - x[1]) / (H * H));
    v[1] = v[2] = 0;
}

static int cmp(const void* a, const void* b) { return *(const double*)a < *(const double*)b ? -1 : *(const double*)a > *(const double*)b; }

/* The channel filled for steps advection steps, reserve: sps_world_reserve of the channel's full
   count first. Prints its line. */
static void run(int res, int steps, int threads, int reserve) {
    const double dp = H / res, L = 2 * H;
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_zone_def in = sps_default_zone_def(), drain = sps_default_zone_def();
    const sps_real floor_point[3] = {0, 0, 0}, up[3] = {0, 1, 0}, roof_point[3] = {0, (sps_real)H, 0}, down[3] = {0, -1, 0};
    double* per_substep = (double*)malloc(sizeof(double) * (size_t)steps * 3); /* all, then the changing and the other steps */
    int n_changing = 0, n_other = 0;
    sps_world* w = NULL;
    sps_body b;
    const int full = (int)(L / dp) * res;
    int k, n0, changed = 0, first = 0;
    if (!per_substep) exit(1);
    wd.dp = (sps_real)dp;
    wd.threads = threads;
    if (sps_world_create(&wd, &w) != SPS_OK) exit(1);
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 30 * U;
    bd.material.viscosity = (sps_real)(1000 * U * H); /* Re = 1 */
    in.kind = SPS_ZONE_INFLOW; in.lo[0] = (sps_real)(-4 * dp); in.hi[1] = (sps_real)H; in.velocity_fn = parabola;
    drain.kind = SPS_ZONE_OUTFLOW; drain.lo[0] = (sps_real)(L - 4 * dp); drain.hi[0] = (sps_real)L; drain.hi[1] = (sps_real)H;
    if (sps_world_add_body(w, &bd, &b) != SPS_OK || sps_world_add_wall(w, floor_point, up, SPS_WALL_NO_SLIP) != SPS_OK ||
        sps_world_add_wall(w, roof_point, down, SPS_WALL_NO_SLIP) != SPS_OK || sps_body_add_zone(w, b, &in, NULL) != SPS_OK ||
        sps_body_add_zone(w, b, &drain, NULL) != SPS_OK) {
        fprintf(stderr, "%s\n", sps_world_last_error(w));
        exit(1);
    }
    if (reserve && sps_world_reserve(w, (int)(1.2 * (L / dp + 8) * res)) != SPS_OK) exit(1);
    n0 = sps_world_particle_count(w);
    for (k = 0; k < steps; ++k) {
        const long sub0 = sps_world_substep_count(w);
        const int n = sps_world_particle_count(w);
        double t0 = now();
        if (sps_world_step(w) != SPS_OK) { fprintf(stderr, "step %d: %s\n", k, sps_world_last_error(w)); exit(1); }
        t0 = now() - t0;
        per_substep[k] = t0 / (double)(sps_world_substep_count(w) - sub0) / n;
        changed += sps_world_particle_count(w) != n;
        if (4 * n < full) first = k + 1;
        else if (sps_world_particle_count(w) != n) per_substep[steps + n_changing++] = per_substep[k];
        else per_substep[2 * steps + n_other++] = per_substep[k];
    }
    {
        const int count = sps_world_particle_count(w);
        const int m = steps - first;
        int worst = first;
        for (k = first; k < steps; ++k)
            if (per_substep[k] > per_substep[worst]) worst = k;
        printf("%s,%d,%d,%d,%d,%d,%d,", reserve ? "reserve" : "no reserve", res, threads, n0, count, changed, first);
        printf("%d,", worst);
        qsort(per_substep + first, (size_t)m, sizeof(double), cmp);
        printf("%.1f,%.1f,%.1f,%.2f,", 1e9 * per_substep[first + m / 2], 1e9 * per_substep[first + (int)(0.99 * (m - 1))], 1e9 * per_substep[steps - 1],
               per_substep[steps - 1] / per_substep[first + m / 2]);
        qsort(per_substep + steps, (size_t)n_changing, sizeof(double), cmp);
        qsort(per_substep + 2 * steps, (size_t)n_other, sizeof(double), cmp);
        if (n_changing > 0 && n_other > 0) /* what a creation or removal adds to a step */
            printf("%.1f,%.1f,%.3f\n", 1e9 * per_substep[steps + n_changing / 2], 1e9 * per_substep[2 * steps + n_other / 2],
                   per_substep[steps + n_changing / 2] / per_substep[2 * steps + n_other / 2]);
        else printf(",,\n");
    }
    sps_world_destroy(w);
    free(per_substep);
}

int main(int argc, char** argv) {
    int res = 20, steps = 3000, threads = 1, k;
    double load[3] = {0, 0, 0};
    FILE* f;
    for (k = 1; k + 1 < argc; k += 2) {
        if (strcmp(argv[k], "--res") == 0) res = atoi(argv[k + 1]);
        else if (strcmp(argv[k], "--steps") == 0) steps = atoi(argv[k + 1]);
        else if (strcmp(argv[k], "--threads") == 0) threads = atoi(argv[k + 1]);
    }
    if (res < 8 || steps < 10 || threads < 1) { fprintf(stderr, "usage: %s [--res N] [--steps N] [--threads N]\n", argv[0]); return 2; }
    if ((f = fopen("/proc/loadavg", "r")) != NULL) {
        if (fscanf(f, "%lf %lf %lf", &load[0], &load[1], &load[2]) != 3) load[0] = load[1] = load[2] = -1;
        fclose(f);
    }
    printf("load average %.2f %.2f %.2f\n", load[0], load[1], load[2]);
    printf("scene,res,threads,particles_start,particles_end,steps_changing_count,first_timed_step,worst_step,median_ns_per_particle_substep,"
           "p99_ns,max_ns_per_particle_substep,max_over_median,median_ns_steps_changing_count,median_ns_other_steps,changing_over_other\n");
    run(res, steps, threads, 1);
    run(res, steps, threads, 0);
    return 0;
}
