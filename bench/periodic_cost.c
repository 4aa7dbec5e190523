/* periodic_cost - what a periodic axis costs: a viscous fluid channel (--res particles across,
   4 x as long) between no-slip walls y = 0 and y = H, driven along x by a body force, once with
   x periodic and once closed by two more no-slip walls at its ends (the same particles, the
   same passes, the walls' images instead of the periodic neighbours). Prints per scene the
   median over --runs runs of the time per particle sub-step after a warm-up, and the ratio
   periodic / walls. bench/VALIDATION.md, "Periodic and viscous flows".

   Usage: ./build/periodic_cost [--res 40] [--steps 200] [--runs 5] [--threads 1] */
#define _POSIX_C_SOURCE 199309L
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Seconds per particle sub-step of steps advection steps of the channel (periodic or walled). */
static double channel_cost(int res, int steps, int threads, int periodic) {
    const double H = 1, L = 4, dp = H / res;
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)L, (sps_real)H, 0};
    sps_world* w = NULL;
    sps_body b;
    long sub0;
    double t0;
    int k;
    wd.dp = (sps_real)dp;
    wd.threads = threads;
    wd.gravity[0] = 0.1;
    wd.energy_growth_limit = (sps_real)INFINITY;
    if (periodic) wd.periodic[0] = (sps_real)L;
    if (sps_world_create(&wd, &w) != SPS_OK) exit(1);
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 10;
    bd.material.viscosity = 10;
    if (sps_world_add_body(w, &bd, &b) != SPS_OK || sps_body_add_box(w, b, lo, hi, NULL) != SPS_OK) exit(1);
    if (sps_world_add_box_walls(w, lo, hi, periodic ? SPS_FACE_X_LO | SPS_FACE_X_HI : 0, SPS_WALL_NO_SLIP) != SPS_OK) exit(1);
    for (k = 0; k < 20; ++k) sps_world_step(w); /* warm-up: lists and caches */
    sub0 = sps_world_substep_count(w);
    t0 = now();
    for (k = 0; k < steps; ++k)
        if (sps_world_step(w) != SPS_OK) { fprintf(stderr, "%s\n", sps_world_last_error(w)); exit(1); }
    t0 = now() - t0;
    t0 /= (double)(sps_world_substep_count(w) - sub0) * sps_world_particle_count(w);
    sps_world_destroy(w);
    return t0;
}

static int cmp(const void* a, const void* b) { return *(const double*)a < *(const double*)b ? -1 : *(const double*)a > *(const double*)b; }

int main(int argc, char** argv) {
    int res = 40, steps = 200, runs = 5, threads = 1, k, periodic;
    double cost[2][64];
    for (k = 1; k + 1 < argc; k += 2) {
        if (strcmp(argv[k], "--res") == 0) res = atoi(argv[k + 1]);
        else if (strcmp(argv[k], "--steps") == 0) steps = atoi(argv[k + 1]);
        else if (strcmp(argv[k], "--runs") == 0) runs = atoi(argv[k + 1]);
        else if (strcmp(argv[k], "--threads") == 0) threads = atoi(argv[k + 1]);
    }
    if (res < 10 || steps < 1 || runs < 1 || runs > 64 || threads < 1) { fprintf(stderr, "usage: %s [--res N] [--steps N] [--runs N] [--threads N]\n", argv[0]); return 2; }
    for (k = 0; k < runs; ++k) /* alternated, so a change of the machine's load hits both */
        for (periodic = 0; periodic < 2; ++periodic) cost[periodic][k] = channel_cost(res, steps, threads, periodic);
    qsort(cost[0], (size_t)runs, sizeof(double), cmp);
    qsort(cost[1], (size_t)runs, sizeof(double), cmp);
    printf("scene,res,particles,threads,ns_per_particle_substep\nwalls,%d,%d,%d,%.2f\nperiodic,%d,%d,%d,%.2f\nratio periodic/walls: %.3f\n", res,
           4 * res * res, threads, 1e9 * cost[0][runs / 2], res, 4 * res * res, threads, 1e9 * cost[1][runs / 2],
           cost[1][runs / 2] / cost[0][runs / 2]);
    return 0;
}
