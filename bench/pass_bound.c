/* pass_bound - each neighbour pass of a body against what this machine allows.

   Builds the 2D plate of benchmark A1 (H/dp 10 unless --res) with the chosen shear formulation
   and its neighbour lists (a configuration update; the arithmetic build could not advance it:
   its passes take the wrong neighbours), then times on one thread, over all of the plate's lane
   groups, with the acoustic sub-step of the plate at rest:
     pass        the pass kernel the body runs (its pressure and continuity passes, and the
                 penalty pass of GNO and GNO-A);
     gathers     the neighbour values that pass reads (positions, velocities, pressure, volume
                 and, as the pass needs them, stress, artificial stress, mass, velocity gradient),
                 each gathered slot by slot and summed, nothing else: the memory side alone;
     arithmetic  (build/pass_bound_arith, compiled with -DPASS_BOUND_ARITHMETIC) the pass kernel
                 itself with every lane taking lane 0's neighbour (SPS__PAIR_NEIGHBOR): one
                 broadcast load per value instead of a gather, the arithmetic side alone.
   Each figure is the best of 7 trials of --repeat calls, in ns per pair slot (padding included:
   the lanes compute padding slots too). A pass cannot run faster than the larger of its two
   sides (the bound: both overlap fully) and should not run slower than their sum (no overlap,
   2x the bound when the sides are equal). bench/pass_bound.sh runs both builds and writes the
   table of pass / bound. This program reads library internals (the body's pass kernels and
   neighbour lists), so it is a probe, not an example of the API.

   Usage: ./build/pass_bound [--shear S] [--res N] [--kernel K] [--geometry G] [--repeat R] */
#define SPHSOLID_IMPLEMENTATION
#ifdef PASS_BOUND_ARITHMETIC
#define SPS__PAIR_NEIGHBOR(js_, l) (js_)[0]
#endif
#include "../examples/common.h"
#include "../examples/scenes/plate2d.h"

#define TRIALS 7

/* One neighbour array a pass reads: value (j - origin) * stride + offset of base. */
typedef struct {
    const sps_real* base;
    int origin, stride, offset;
} neighbour_read;

typedef struct {
    neighbour_read reads[32];
    int count;
} read_list;

#ifndef PASS_BOUND_ARITHMETIC /* the arithmetic build gathers nothing */
static void add_read(read_list* r, const sps_real* base, int origin, int stride, int offset) {
    neighbour_read* n = &r->reads[r->count++];
    n->base = base;
    n->origin = origin;
    n->stride = stride;
    n->offset = offset;
}

/* The in-plane entries of a symmetric 3 x 3 tensor stored as (xx xy xz yy yz zz), or of a
   row-major 3 x 3 matrix: those a 2D pass reads. */
static void add_tensor(read_list* r, const sps_real* base, int origin, int stride, int dim) {
    static const int sym2[3] = {0, 1, 3}, full2[4] = {0, 1, 3, 4};
    int a;
    if (stride == 6)
        for (a = 0; a < (dim == 3 ? 6 : 3); ++a) add_read(r, base, origin, 6, dim == 3 ? a : sym2[a]);
    else
        for (a = 0; a < (dim == 3 ? 9 : 4); ++a) add_read(r, base, origin, 9, dim == 3 ? a : full2[a]);
}

/* What each pass reads of a neighbour j (its pair geometry: the positions; its terms). */
static read_list pass_reads(const sps_world* w, const sps__body* b, const char* pass) {
    const sps__model* m = &b->model;
    read_list r;
    int a;
    r.count = 0;
    for (a = 0; a < w->dim; ++a) add_read(&r, w->pos[a], 0, 1, 0);
    for (a = 0; a < w->dim; ++a) add_read(&r, w->vel[a], 0, 1, 0);
    add_read(&r, w->vol, 0, 1, 0);
    if (strcmp(pass, "pressure") == 0) {
        add_read(&r, w->p, 0, 1, 0);
        if (m->stabilisation->stress_force) add_tensor(&r, b->tau, b->begin, 6, w->dim);
        if (m->stabilisation->artificial_stress) {
            for (a = 0; a < 3; ++a) add_read(&r, b->art, b->begin, 3, a);
            add_read(&r, w->mass, 0, 1, 0);
        }
    } else if (strcmp(pass, "continuity") == 0) {
        if (m->riemann_density) add_read(&r, w->p, 0, 1, 0);
    } else { /* penalty */
        add_tensor(&r, b->grad, b->begin, 9, w->dim);
        if (m->scaled_penalty) add_read(&r, b->return_factor, b->begin, 1, 0);
    }
    return r;
}
#endif

/* The sweep over body b's pair slots that gathers `width` arrays per slot (bases b0.., index
   (j - o) s + f) and stores each slot's sum in out[s]: no sum is carried from slot to slot, so
   the sweep waits on nothing but the loads. */
#define GATHER_SWEEP(width)                                                                        \
    for (g = 0; g < b->ngroups; ++g) {                                                             \
        const sps__group q = sps__group_of(w, b, g);                                               \
        for (k = 0; k < q.len; ++k) {                                                              \
            const int* SPS__RESTRICT js = w->nb_j + q.s0 + k * SPS__LANES;                         \
            sps_real* SPS__RESTRICT row = out + q.s0 + k * SPS__LANES;                             \
            SPS__PRAGMA(omp simd)                                                                  \
            for (l = 0; l < SPS__LANES; ++l) {                                                     \
                const int j = js[l];                                                               \
                sps_real v = b0[(j - o[0]) * st[0] + f[0]];                                        \
                if (width > 1) v += b1[(j - o[1]) * st[1] + f[1]];                                 \
                if (width > 2) v += b2[(j - o[2]) * st[2] + f[2]];                                 \
                if (width > 3) v += b3[(j - o[3]) * st[3] + f[3]];                                 \
                row[l] = v;                                                                        \
            }                                                                                      \
        }                                                                                          \
    }

/* Reads n .. n + width - 1 of the list (width 1 to 4) gathered in one sweep, as a pass gathers
   several arrays per slot and loads each neighbour index once, into out (a value per slot). */
static void gather_sweep(const sps_world* w, const sps__body* b, const read_list* r, int n, int width, sps_real* SPS__RESTRICT out) {
    const sps_real *SPS__RESTRICT b0 = r->reads[n].base, *SPS__RESTRICT b1 = r->reads[n + (width > 1)].base,
                   *SPS__RESTRICT b2 = r->reads[n + 2 * (width > 2)].base, *SPS__RESTRICT b3 = r->reads[n + 3 * (width > 3)].base;
    int o[4], st[4], f[4], c, g, k, l;
    for (c = 0; c < 4; ++c) {
        const neighbour_read* rd = &r->reads[n + (c < width ? c : 0)];
        o[c] = rd->origin;
        st[c] = rd->stride;
        f[c] = rd->offset;
    }
    if (width == 1) GATHER_SWEEP(1)
    else if (width == 2) GATHER_SWEEP(2)
    else if (width == 3) GATHER_SWEEP(3)
    else GATHER_SWEEP(4)
}

/* The memory side of a pass: every read of the list gathered over body b's pair slots, four
   arrays per sweep (more would not fit the registers), into out (a value per slot, offset by the
   body's first slot). Returns a sum of out, that the sweeps be kept. */
static double gather_reads(const sps_world* w, const sps__body* b, const read_list* r, sps_real* out) {
    int n;
    for (n = 0; n < r->count; n += 4) gather_sweep(w, b, r, n, r->count - n < 4 ? r->count - n : 4, out);
    return out[w->nb_group_start[b->group0]];
}

static volatile double sink; /* keeps the gathered sums alive */

/* Best of TRIALS of `repeat` calls, in ns per slot: the pass kernel (kernel != NULL) over
   sub-step dt or the gathers of reads into out. */
static double best_ns(sps_world* w, sps__body* b, sps__group_kernel kernel, sps_real dt, const read_list* reads, sps_real* out, int repeat,
                      long slots) {
    double best = 1e300;
    int t, r;
    for (t = 0; t < TRIALS; ++t) {
        const double start = wall_seconds();
        for (r = 0; r < repeat; ++r) {
            if (kernel) sps__run_groups(w, b, kernel, dt);
            else sink = gather_reads(w, b, reads, out);
        }
        const double ns = (wall_seconds() - start) * 1e9 / ((double)repeat * (double)slots);
        if (ns < best) best = ns;
    }
    return best;
}

int main(int argc, char** argv) {
    plate2d_params p = {.res = 10, .vf = 0.05, .jitter = 0, .seed = 1};
    int repeat = 200, a;
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 0.01, .vtk_every = 0, .csv_every = 1, .E = PLATE2D_E,
                        .nu = PLATE2D_NU, .rho0 = PLATE2D_RHO0, .out = "out/pass_bound", .jitter = 0, .seed = 1, .threads = 1, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"res", OPT_INT, &p.res, "H/dp", 2, 100, NULL},
        {"repeat", OPT_INT, &repeat, "calls per trial", 1, 1e6, NULL},
        COMMON_OPTION_SPECS(c),
    };
    const char* passes[3] = {"pressure", "continuity", "penalty"};
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body plate;
    sps_observer tip;
    sps__body* b;
    sps_real dt;
    long slots;

    opt_parse(argc, argv, "each neighbour pass's time against its gathers and its arithmetic", opts, (int)(sizeof opts / sizeof *opts));
    c.threads = 1; /* one core: what a pass costs, not how it shares */
    apply_common(&c, &wd, &bd);
    wd.keep_last_good_state = 1; /* as the examples set it (apply_common sets options only) */
    wd.log = ex_log;
    ex_check(NULL, plate2d_create(wd, &bd, &p, &w, &plate, &tip));
    ex_check(w, sps__update_configuration(w));
    dt = wd.cfl_acoustic * w->h / w->c0_max;
    b = &w->bodies[0];
    slots = w->nb_group_start[b->group0 + b->ngroups] - w->nb_group_start[b->group0];
    for (a = 0; a < 3; ++a) {
        const sps__group_kernel kernel = a == 0 ? b->model.pass.pressure : a == 1 ? b->model.pass.continuity : b->model.pass.penalty;
        if (!kernel) continue;
#ifdef PASS_BOUND_ARITHMETIC
        printf("PASS shear=%s pass=%s particles=%d slots=%ld arithmetic_ns=%.3f\n", shear_name(c.shear), passes[a], b->end - b->begin,
               slots, best_ns(w, b, kernel, dt, NULL, NULL, repeat, slots));
#else
        {
            const read_list reads = pass_reads(w, b, passes[a]);
            sps_real* out = (sps_real*)calloc((size_t)w->nb_group_start[b->group0 + b->ngroups], sizeof *out);
            printf("PASS shear=%s pass=%s particles=%d slots=%ld reads=%d pass_ns=%.3f gathers_ns=%.3f\n", shear_name(c.shear),
                   passes[a], b->end - b->begin, slots, reads.count, best_ns(w, b, kernel, dt, NULL, NULL, repeat, slots),
                   best_ns(w, b, NULL, 0, &reads, out, repeat, slots));
            free(out);
        }
#endif
    }
    sps_world_destroy(w);
    return 0;
}
