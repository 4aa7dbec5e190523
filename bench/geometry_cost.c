/* geometry_cost.c - the figures of geometry from files (bench/VALIDATION.md, "Geometry from
   files"): what a distance query costs on spheres of 1,000 and 100,000 triangles, a relaxed fill
   from a 100,000-triangle sphere against the same fill from the analytic sphere, and water at
   rest in a mesh container (a U-tube outline) for 10 s.

   Build: make build/geometry_cost. Usage: geometry_cost [queries] [fill] [container] (all by
   default); prints one RESULT line per figure. One thread; run it on an idle core. */
#define _POSIX_C_SOURCE 200809L
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../tests/ensure.h"
#include "../tests/mesh_files.h"

static sps_mesh* sphere_mesh(int nlat, int* triangles) {
    const double c[3] = {0, 0, 0};
    test_mesh s = test_mesh_sphere(1, c, nlat, nlat);
    sps_real* v = (sps_real*)malloc(sizeof(sps_real) * 3 * (size_t)s.nv);
    sps_mesh* m = NULL;
    char msg[512];
    int i;
    for (i = 0; i < 3 * s.nv; ++i) v[i] = (sps_real)s.v[i];
    if (sps_mesh_from_triangles(s.nv, v, s.nt, s.t, NULL, &m, msg, sizeof msg) != SPS_OK) { printf("%s\n", msg); exit(1); }
    *triangles = s.nt;
    free(v);
    test_mesh_free(&s);
    return m;
}
static double uniform(unsigned long long* s) {
    unsigned long long z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return (double)((z ^ (z >> 31)) >> 11) / 9007199254740992.0;
}
/* Microseconds per query at n points: in the box [-1.5, 1.5]^3 (near = 0), or within 0.1 R of
   the sphere (near = 1). The best of 3 rounds. */
static double query_cost(sps_mesh* m, int near, int n) {
    double best = 1e30, sink = 0;
    int round, i, a;
    for (round = 0; round < 3; ++round) {
        unsigned long long seed = 99;
        const double t0 = wall_seconds();
        for (i = 0; i < n; ++i) {
            sps_real x[3];
            for (a = 0; a < 3; ++a) x[a] = (sps_real)(3 * (uniform(&seed) - 0.5));
            if (near) { /* onto the shell 0.9 .. 1.1 */
                const double r = sqrt((double)(x[0] * x[0] + x[1] * x[1] + x[2] * x[2])), to = 0.9 + 0.2 * uniform(&seed);
                for (a = 0; a < 3; ++a) x[a] = (sps_real)(x[a] * to / r);
            }
            sink += (double)sps_mesh_sdf(x, m);
        }
        if (wall_seconds() - t0 < best) best = wall_seconds() - t0;
    }
    if (sink == 12345.678) printf(" ");
    return 1e6 * best / n;
}
static void queries(void) {
    int t1, t2, near;
    sps_mesh *small = sphere_mesh(23, &t1), *large = sphere_mesh(224, &t2);
    for (near = 0; near <= 1; ++near) {
        const double c1 = query_cost(small, near, 20000), c2 = query_cost(large, near, 20000);
        printf("RESULT case=geometry_queries points=%s triangles_small=%d us_small=%.3f triangles_large=%d us_large=%.3f ratio=%.2f\n",
               near ? "near_surface" : "in_box", t1, c1, t2, c2, c2 / c1);
    }
    sps_mesh_destroy(small); sps_mesh_destroy(large);
}

static sps_real ball_sdf(const sps_real x[3], void* user) { (void)user; return (sps_real)sqrt((double)(x[0] * x[0] + x[1] * x[1] + x[2] * x[2])) - 1; }
static void quiet_log(int level, const char* message, void* user) { (void)level; (void)message; (void)user; }
/* Relaxed fill (300 iterations) of the unit ball at dp = R / 10: from the mesh and from the analytic distance. */
static void fill(void) {
    int triangles, n_mesh, n_ball, k;
    sps_mesh* m = sphere_mesh(224, &triangles);
    double t_mesh = 1e30, t_ball = 1e30;
    for (k = 0; k < 2; ++k) { /* the best of 2, interleaved */
        sps_world_def wd = sps_default_world_def();
        sps_body_def bd = sps_default_body_def();
        sps_world* w;
        sps_body b;
        const sps_real lo[3] = {-1.2, -1.2, -1.2}, hi[3] = {1.2, 1.2, 1.2};
        double t0;
        wd.dim = 3; wd.dp = (sps_real)0.1; wd.threads = 1; wd.log = quiet_log;
        sps_world_create(&wd, &w); sps_world_add_body(w, &bd, &b);
        t0 = wall_seconds();
        sps_body_add_mesh(w, b, m, NULL, NULL, 0, &n_mesh);
        if (wall_seconds() - t0 < t_mesh) t_mesh = wall_seconds() - t0;
        sps_world_destroy(w);
        sps_world_create(&wd, &w); sps_world_add_body(w, &bd, &b);
        t0 = wall_seconds();
        sps_body_add_sdf_relaxed(w, b, lo, hi, ball_sdf, NULL, 0, &n_ball);
        if (wall_seconds() - t0 < t_ball) t_ball = wall_seconds() - t0;
        sps_world_destroy(w);
    }
    printf("RESULT case=geometry_relaxed_fill triangles=%d particles_mesh=%d s_mesh=%.2f particles_analytic=%d s_analytic=%.2f ratio=%.2f\n", triangles,
           n_mesh, t_mesh, n_ball, t_ball, t_mesh / t_ball);
    sps_mesh_destroy(m);
}

/* Water 0.5 m deep at rest in a U-tube outline (legs 0.2 m wide, 0.7 m high, joined over 0.6 m
   at the bottom), 3 layers of wall, dp = H / 20, h = 2 dp (FLUIDS: still water), c0 = 10 sqrt(g H),
   started at its hydrostatic pressure; 10 s. */
static sps_real at_rest(const sps_real x[3], void* user) { (void)user; return (sps_real)(1000 * 9.81 * (0.5 - (double)x[1])); }
static void container(void) {
    const sps_real xy[] = {0, 0, 0.6, 0, 0.6, 0.7, 0.4, 0.7, 0.4, 0.2, 0.2, 0.2, 0.2, 0.7, 0, 0.7};
    const int count[1] = {8};
    const double H = 0.5, dp = H / 20, g = 9.81, rho_g_h = 1000 * g * H;
    const sps_real lo[3] = {-1, -1, -1}, top[3] = {1, (sps_real)0.7, 1}, level[3] = {1, (sps_real)H, 1};
    sps_mesh* m = NULL;
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body wall, water;
    char msg[512];
    int n_water, k, worst_lost = 0;
    double worst_error = 0, t0 = wall_seconds();
    if (sps_mesh_from_rings(1, count, xy, NULL, &m, msg, sizeof msg) != SPS_OK) { printf("%s\n", msg); return; }
    wd.dim = 2; wd.dp = (sps_real)dp; wd.h_over_dp = 2; wd.threads = 1; wd.gravity[1] = (sps_real)-g; wd.log = quiet_log;
    sps_world_create(&wd, &w);
    bd.material.kind = SPS_MATERIAL_RIGID;
    sps_world_add_body(w, &bd, &wall);
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = (sps_real)(10 * sqrt(g * H));
    sps_world_add_body(w, &bd, &water);
    if (sps_body_add_mesh_shell(w, wall, m, lo, top, 3, NULL) != SPS_OK || sps_body_add_mesh(w, water, m, lo, level, -1, &n_water) != SPS_OK) {
        printf("%s\n", sps_world_last_error(w));
        return;
    }
    sps_body_set_pressure(w, water, at_rest, NULL);
    for (k = 1; k <= 100; ++k) {
        const sps_real *x, *y, *p;
        double floor_sum = 0;
        int i, first, count, nfloor = 0, lost = 0;
        if (sps_world_advance(w, (sps_real)(0.1 * k), NULL, NULL) != SPS_OK) { printf("stopped: %s\n", sps_world_last_error(w)); break; }
        x = sps_world_field(w, SPS_FIELD_POSITION_X);
        y = sps_world_field(w, SPS_FIELD_POSITION_Y);
        p = sps_world_field(w, SPS_FIELD_PRESSURE);
        sps_body_field(w, water, "pressure", NULL, &first, &count);
        for (i = first; i < first + count; ++i) {
            sps_real at[3];
            at[0] = x[i]; at[1] = y[i]; at[2] = 0;
            if (y[i] < 0.7 && sps_mesh_sdf(at, m) > 0) ++lost; /* through a wall (not over the top) */
            if (y[i] < dp) { floor_sum += p[i] + 1000 * g * y[i]; ++nfloor; }
        }
        if (lost > worst_lost) worst_lost = lost;
        if (k >= 10 && fabs(floor_sum / nfloor / rho_g_h - 1) > worst_error) worst_error = fabs(floor_sum / nfloor / rho_g_h - 1);
        if (k % 10 == 0)
            printf("  t %4.1f s: floor p + rho g y %.4f rho g H, %d outside the walls\n", 0.1 * k, floor_sum / nfloor / rho_g_h, lost);
    }
    printf("RESULT case=geometry_container water=%d seconds=10 floor_pressure_worst_error=%.4f (from 1 s) lost_worst=%d wall_s=%.1f\n", n_water,
           worst_error, worst_lost, wall_seconds() - t0);
    sps_world_destroy(w);
    sps_mesh_destroy(m);
}

int main(int argc, char** argv) {
    int i, all = argc < 2;
    for (i = 1; i < argc || all; ++i) {
        const char* what = all ? "" : argv[i];
        if (all || !strcmp(what, "queries")) queries();
        if (all || !strcmp(what, "fill")) fill();
        if (all || !strcmp(what, "container")) container();
        if (all) break;
    }
    return 0;
}
