/* particle_cost - what one particle costs: wall time per particle and acoustic sub-step, bytes of
   the world's allocations per particle, neighbours and pair slots per particle, contact pairs,
   and what one sps_world_diagnostics call (the examples' CSV row) costs: the best of --diagnostics
   calls, per particle and in sub-steps.

   Scenes (the examples' set-ups, from examples/scenes/): plate2d (A1, --res H/dp), plate3d (A2,
   --res H/dp), ball_plate3d (A10, --dp; the ball body-fitted as in the example) and cube (the
   spinning cube of A4, --dp). The run: one sub-step untimed (the first configuration update,
   the allocations), then --substeps sub-steps timed (sps_world_advance_substeps, no budget).
   Memory: the world's allocator counts its live bytes; the peak over the run, over the particle
   count, is bytes_per_particle (the scene's set-up, e.g. the relaxed fill, allocates through the
   same allocator and is in the peak; bytes_live_per_particle is what stays allocated while it
   steps). This program reads the library's private state (neighbour counts, contact pairs), so
   it is a probe, not an example of the API.

   Build: make build/particle_cost     Run: ./build/particle_cost --scene plate3d --res 3 --threads 1
   bench/scaling.sh runs it from 1e3 to 1e6 particles. */
#define SPHSOLID_IMPLEMENTATION
#include "../examples/common.h"
#include "../examples/scenes/plate2d.h"
#include "../examples/scenes/plate3d.h"
#include "../examples/scenes/ball_plate.h"
#include "../examples/scenes/spinning.h"

/* The counting allocator: each block carries its size in front, so free knows what to subtract;
   the live blocks are listed (most recent last) so that the breakdown can name them. */
typedef struct {
    size_t live, peak;
    void** blocks;
    int nblocks, blocks_cap;
} alloc_count;
typedef union {
    size_t size;
    long double align; /* C99 has no max_align_t */
} block_head;
static void* counting_alloc(size_t size, void* user) {
    alloc_count* c = (alloc_count*)user;
    block_head* h = (block_head*)malloc(sizeof(block_head) + size);
    if (!h) return NULL;
    h->size = size;
    c->live += size;
    if (c->live > c->peak) c->peak = c->live;
    if (c->nblocks == c->blocks_cap) {
        void** more = (void**)realloc(c->blocks, sizeof(void*) * (size_t)(c->blocks_cap = 2 * c->blocks_cap + 64));
        if (!more) { c->live -= size; free(h); return NULL; }
        c->blocks = more;
    }
    c->blocks[c->nblocks++] = h + 1;
    return h + 1;
}
static void counting_free(void* p, void* user) {
    alloc_count* c = (alloc_count*)user;
    block_head* h;
    int k;
    if (!p) return;
    h = (block_head*)p - 1;
    c->live -= h->size;
    for (k = c->nblocks - 1; k >= 0; --k)
        if (c->blocks[k] == p) { c->blocks[k] = c->blocks[--c->nblocks]; break; }
    free(h);
}

/* The bytes of the live block p (0 if p is not one), taken off the list so that each block is
   named once. */
static size_t take_block(alloc_count* c, const void* p) {
    int k;
    for (k = 0; p && k < c->nblocks; ++k)
        if (c->blocks[k] == p) {
            c->blocks[k] = c->blocks[--c->nblocks];
            return ((const block_head*)p - 1)->size;
        }
    return 0;
}

/* What the live blocks hold, per particle: the neighbour storage array by array, the particle
   fields (the world's and the bodies'), the rest. Reads the library's private state. */
static void print_breakdown(const sps_world* w, alloc_count* c) {
    const struct { const char* name; const void* p; } named[] = {
        {"nb_j", w->nb_j}, {"list_chunk", w->list_chunk}, {"nb_dw", w->nb_dw}, {"nb_inv_r", w->nb_inv_r},
        {"pair_force", w->pair_force}, {"kept_force", w->kept_force}, {"kept_neighbor_id", w->kept_neighbor_id},
        {"kept_first", w->kept_first}, {"kept_count", w->kept_count}, {"nb_first", w->nb_first}, {"nb_count", w->nb_count},
        {"nb_group_start", w->nb_group_start}, {"group_sum", w->group_sum}, {"cell_of", w->cell_of}, {"cell_start", w->cell_start},
        {"perm", w->perm}, {"scratch", w->scratch}, {"diag_scratch", w->diag_scratch}, {"good", w->good}, {"good_id", w->good_id},
    };
    const double n = w->n;
    size_t fields = 0, total;
    int k, a, bi;
    printf("BREAKDOWN particles=%d capacity=%d", w->n, w->cap);
    for (k = 0; k < (int)(sizeof named / sizeof *named); ++k) {
        const size_t bytes = take_block(c, named[k].p);
        if (bytes) printf(" %s=%.1f", named[k].name, bytes / n);
    }
    for (k = 0; k < SPS__NFIELDS; ++k)
        for (a = 0; a < sps__field_arrays(&sps__fields[k]); ++a) {
            if (!sps__fields[k].per_body) fields += take_block(c, *(void**)sps__field_slot(w, NULL, &sps__fields[k], a));
            else
                for (bi = 0; bi < w->nbodies; ++bi) fields += take_block(c, *(void**)sps__field_slot(w, &w->bodies[bi], &sps__fields[k], a));
        }
    for (k = 0, total = 0; k < c->nblocks; ++k) total += ((const block_head*)c->blocks[k] - 1)->size;
    printf(" particle_fields=%.1f other=%.1f live=%.1f\n", fields / n, total / n, c->live / n);
}

enum { SCENE_PLATE2D, SCENE_PLATE3D, SCENE_BALL_PLATE3D, SCENE_CUBE };

int main(int argc, char** argv) {
    int scene = SCENE_PLATE2D, res = 10, substeps = 200, threads = 1, shear = SPS_SHEAR_ENO_A, diagnostics = 3;
    double dp = 0.01;
    opt_spec opts[] = {
        {"scene", OPT_CHOICE, &scene, "the set-up", 0, 0, "plate2d|plate3d|ball_plate3d|cube"},
        {"res", OPT_INT, &res, "plate2d, plate3d: resolution H/dp", 1, 2000, NULL},
        {"dp", OPT_REAL, &dp, "ball_plate3d, cube: particle spacing [m]", 1e-4, 0.5, NULL},
        {"substeps", OPT_INT, &substeps, "acoustic sub-steps timed", 1, 10000000, NULL},
        {"threads", OPT_INT, &threads, "OpenMP threads, 0 = all", 0, 1024, NULL},
        {"shear", OPT_CHOICE, &shear, "shear formulation", 0, 0, SHEAR_CHOICES},
        {"diagnostics", OPT_INT, &diagnostics, "sps_world_diagnostics calls timed after the run (0: none)", 0, 1000, NULL},
    };
    alloc_count count = {0, 0, NULL, 0, 0};
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body body, other, all = {0};
    sps_observer probe;
    sps_diagnostics d;
    double start, wall, diag_best = 0, slots = 0, neighbours = 0;
    long steps0;
    int i, nb_max = 0, n, k;

    ex_short_openmp_spin(argv);
    opt_parse(argc, argv, "what one particle costs (time, bytes, neighbours)", opts, (int)(sizeof opts / sizeof *opts));
    wd.threads = threads;
    wd.log = ex_log;
    wd.allocator.alloc = counting_alloc;
    wd.allocator.free = counting_free;
    wd.allocator.user = &count;
    bd.shear = (sps_shear)shear;
    bd.track_stress = 1; /* as the examples by default (--stress on) */
    if (scene == SCENE_PLATE2D) {
        plate2d_params p = {.res = res, .vf = 0.05};
        bd.material.density = PLATE2D_RHO0; bd.material.youngs_modulus = PLATE2D_E; bd.material.poisson_ratio = PLATE2D_NU;
        ex_check(NULL, plate2d_create(wd, &bd, &p, &w, &body, &probe));
    } else if (scene == SCENE_PLATE3D) {
        plate3d_params p = {.res = res, .mode = {1, 1}, .support = PLATE3D_SUPPORT_EDGE};
        bd.material.density = PLATE3D_RHO0; bd.material.youngs_modulus = PLATE3D_E; bd.material.poisson_ratio = PLATE3D_NU;
        ex_check(NULL, plate3d_create(wd, &bd, &p, &w, &body, &probe));
    } else if (scene == SCENE_BALL_PLATE3D) {
        ball_plate_params p = {.dim = 3, .dp = dp, .relaxed = 1};
        bd.material.density = BALL_PLATE_RHO0; bd.material.youngs_modulus = BALL_PLATE_E; bd.material.poisson_ratio = BALL_PLATE_NU;
        p.v0 = 0.12 * sqrt(BALL_PLATE_E / (3 * (1 - 2 * BALL_PLATE_NU)) / BALL_PLATE_RHO0); /* 0.12 c0, c0 = sqrt(K / rho0) */
        ex_check(NULL, ball_plate_create(wd, &bd, &p, &w, &other, &body));
    } else {
        spinning_params p = {.dim = 3, .dp = dp, .omega = 50};
        bd.material.density = SPINNING_RHO0; bd.material.youngs_modulus = SPINNING_E; bd.material.poisson_ratio = SPINNING_NU_3D;
        ex_check(NULL, spinning_create(wd, &bd, "cube", &p, &w, &body));
    }
    ex_check(w, sps_world_advance_substeps(w, 1, 0, NULL)); /* the first configuration update: untimed */
    ex_check(w, sps_world_diagnostics(w, all, &d));
    steps0 = d.acoustic_steps;
    start = wall_seconds();
    ex_check(w, sps_world_advance_substeps(w, substeps, 0, NULL));
    wall = wall_seconds() - start;
    n = w->n;
    for (i = 0; i < n; ++i) { /* the lists of the last configuration update */
        neighbours += w->nb_count[i];
        if (w->nb_count[i] > nb_max) nb_max = w->nb_count[i];
    }
    for (i = 0; i < w->nbodies; ++i) slots += w->nb_group_start[w->bodies[i].group0 + w->bodies[i].ngroups] - w->nb_group_start[w->bodies[i].group0];
    for (k = 0; k < diagnostics; ++k) { /* the examples' CSV row: one call on the whole world; the best of the calls */
        const double t0 = wall_seconds();
        ex_check(w, sps_world_diagnostics(w, all, &d));
        if (k == 0 || wall_seconds() - t0 < diag_best) diag_best = wall_seconds() - t0;
    }
    ex_check(w, sps_world_diagnostics(w, all, &d));
    printf("RESULT scene=%s particles=%d threads=%d real=%s substeps=%ld advection_steps=%ld ns_per_particle_step=%.1f "
           "bytes_per_particle=%.0f bytes_live_per_particle=%.0f neighbours_mean=%.1f neighbours_max=%d slots_per_particle=%.1f "
           "contact_pairs=%d diagnostics_ns_per_particle=%.1f diagnostics_in_substeps=%.2f wall_s=%.3f\n",
           scene == SCENE_PLATE2D ? "plate2d" : scene == SCENE_PLATE3D ? "plate3d" : scene == SCENE_BALL_PLATE3D ? "ball_plate3d" : "cube",
           n, threads, sps_is_double() ? "double" : "float", d.acoustic_steps - steps0, d.advection_steps,
           1e9 * wall / ((double)n * (double)(d.acoustic_steps - steps0)), (double)count.peak / n, (double)count.live / n, neighbours / n,
           nb_max, slots / n, w->contact_bodies ? w->ct_first[n] : 0,
           1e9 * diag_best / n, diagnostics > 0 ? diag_best / (wall / (double)(d.acoustic_steps - steps0)) : 0, wall);
    print_breakdown(w, &count); /* last: it takes the named blocks off the list */
    sps_world_destroy(w);
    return 0;
}
