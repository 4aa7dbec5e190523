/* fuzz_api.c - randomized API test of sphsolid.h.

   Each case builds tiny worlds from random, often hostile defs (NaN, inf, negative, huge, zero,
   out-of-range enums, broken cookies, failing allocators) and calls the API in a random order:
   bodies, boxes, SDF fills, particles, velocities, constraints, observers, a few steps,
   diagnostics, VTK output, restart files, validation, destruction; with handles of other or destroyed worlds
   and NULL arguments. Properties checked after every call:
     - no crash, no hang (an alarm stops a case that runs too long), no sanitizer report;
     - every error result is a known code and comes with a fresh, non-empty message (the world's
       last error, also sent to the log callback);
     - a step that returns SPS_OK advanced the time (so sps_world_advance cannot loop forever);
     - sps_world_validate returns SPS_OK or SPS_ERR_STATE, never crashes on a broken world;
     - sps_world_destroy returns every block to the allocator.
   Case k uses seed S + k. A failing case prints its seed; replay it alone with
   ./build/fuzz_api --seed SEED --cases 1 --verbose.

   Build: make build/fuzz_api (optimised) or build/fuzz_sanitize (ASan + UBSan).
   Usage: fuzz_api [--seed S] [--cases N] [--out DIR] [--verbose] */
#define _POSIX_C_SOURCE 200809L
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#define FUZZ_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FUZZ_SANITIZED 1
#endif
#endif
#ifdef FUZZ_SANITIZED
#include <sanitizer/common_interface_defs.h>
#endif

/* ---- random numbers: splitmix64 ---- */
static uint64_t g_rng;
static uint64_t next_u64(void) {
    uint64_t z = (g_rng += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}
static double uniform(double lo, double hi) { return lo + (hi - lo) * (double)(next_u64() >> 11) / 9007199254740992.0; }
static int below(int n) { return (int)(next_u64() % (uint64_t)n); }
static int chance(double p) { return uniform(0, 1) < p; }

/* A hostile real: one of the values that must be rejected or survived. */
static double hostile_real(void) {
    static const double v[] = {0.0, -0.0, -1.0, 1e-300, -1e-300, 1e300, -1e300, 1e30, 5e-324};
    switch (below(4)) {
    case 0: return NAN;
    case 1: return chance(0.5) ? INFINITY : -INFINITY;
    default: return v[below((int)(sizeof v / sizeof *v))];
    }
}
/* valid with probability 1 - p, hostile otherwise */
static double maybe_hostile(double valid, double p) { return chance(p) ? hostile_real() : valid; }
static int hostile_int(void) {
    static const int v[] = {-1, 0, 2, 3, 4, 5, 7, 99, -2147483647 - 1, 2147483647};
    return v[below((int)(sizeof v / sizeof *v))];
}

/* ---- failure reporting ---- */
static uint64_t g_case_seed;
static int g_verbose;

static void print_seed_and_die(const char* why) {
    char buf[160];
    int len = snprintf(buf, sizeof buf, "\nfuzz_api: case seed %llu %s; replay: build/fuzz_api --seed %llu --cases 1 --verbose\n",
                       (unsigned long long)g_case_seed, why, (unsigned long long)g_case_seed);
    if (write(2, buf, (size_t)len) < 0) { /* nothing more to do */ }
}
static void on_signal(int sig) {
    print_seed_and_die(sig == SIGALRM ? "hung (no end within the alarm)" : "crashed (signal)");
    _exit(1);
}
#ifdef FUZZ_SANITIZED
static void on_sanitizer_death(void) { print_seed_and_die("tripped a sanitizer"); }
#endif

#define FAIL(...)                                                                          \
    do {                                                                                   \
        printf("fuzz_api: case seed %llu: ", (unsigned long long)g_case_seed);             \
        printf(__VA_ARGS__);                                                               \
        printf("\n  replay: build/fuzz_api --seed %llu --cases 1 --verbose\n", (unsigned long long)g_case_seed); \
        return 1;                                                                          \
    } while (0)

/* ---- log capture: every error must reach the log with a message ---- */
static long g_log_count;
static char g_log_last[1100];
static void capture_log(int level, const char* message, void* user) {
    (void)level; (void)user;
    snprintf(g_log_last, sizeof g_log_last, "%s", message ? message : "");
    ++g_log_count;
}

/* ---- allocators: plain, or failing at random (out-of-memory paths) ---- */
typedef struct { double fail_p; long live; } fuzz_alloc;
typedef union { size_t size; double d; void* p; long double ld; } fuzz_header;
static void* fuzz_malloc(size_t size, void* user) {
    fuzz_alloc* a = (fuzz_alloc*)user;
    fuzz_header* h;
    if (a->fail_p > 0 && chance(a->fail_p)) return NULL;
    if (size > ((size_t)1 << 30)) return NULL; /* the machine is shared: refuse > 1 GiB blocks */
    if (!(h = (fuzz_header*)malloc(sizeof *h + size))) return NULL;
    h->size = size;
    a->live++;
    return h + 1;
}
static void fuzz_free(void* p, void* user) {
    fuzz_alloc* a = (fuzz_alloc*)user;
    a->live--;
    free((fuzz_header*)p - 1);
}

/* ---- the state of one case ---- */
#define MAX_WORLDS 3
#define MAX_HANDLES 16
#define MAX_PARTICLES 500 /* stop adding beyond this: worlds stay tiny */
typedef struct {
    sps_world* w[MAX_WORLDS];
    fuzz_alloc alloc[MAX_WORLDS];
    double dp[MAX_WORLDS];
    int dim[MAX_WORLDS];
    sps_body bodies[MAX_HANDLES];     /* from any world, live or destroyed */
    sps_observer observers[MAX_HANDLES];
    int body_world[MAX_HANDLES];      /* the world slot each body was made in, -1 once destroyed */
    int nbodies, nobservers;
    double load[MAX_HANDLES];         /* the scale of the external acceleration given to each body
                                         (read by the step's threads at once: written only between steps) */
    const char* out_dir;
    long calls, errors, steps;
} fuzz_state;

/* A body handle for world slot k: mostly one of its own, else another world's, a destroyed
   world's, the invalid 0 or garbage. */
static sps_body any_body(const fuzz_state* s, int k) {
    sps_body b = {0};
    int i, own[MAX_HANDLES], nown = 0;
    if (chance(0.05)) { b.id = (uint32_t)next_u64(); return b; } /* garbage */
    if (s->nbodies == 0 || chance(0.03)) return b;               /* the invalid handle */
    for (i = 0; i < s->nbodies; ++i)
        if (s->body_world[i] == k) own[nown++] = i;
    if (nown && chance(0.85)) return s->bodies[own[below(nown)]];
    return s->bodies[below(s->nbodies)];
}
static sps_observer any_observer(const fuzz_state* s) {
    sps_observer o = {0};
    if (chance(0.1)) { o.id = (uint32_t)next_u64(); return o; }
    if (s->nobservers == 0) return o;
    return s->observers[below(s->nobservers)];
}
static void keep_body(fuzz_state* s, sps_body b, int k) {
    int slot;
    if (!b.id) return;
    slot = s->nbodies < MAX_HANDLES ? s->nbodies++ : below(MAX_HANDLES);
    s->bodies[slot] = b;
    s->body_world[slot] = k;
}
static int has_own_body(const fuzz_state* s, int k) {
    int i;
    for (i = 0; i < s->nbodies; ++i)
        if (s->body_world[i] == k) return 1;
    return 0;
}
/* The handles of world slot k now belong to a destroyed world. */
static void orphan_bodies(fuzz_state* s, int k) {
    int i;
    for (i = 0; i < s->nbodies; ++i)
        if (s->body_world[i] == k) s->body_world[i] = -1;
}
static void keep_observer(fuzz_state* s, sps_observer o) {
    if (o.id) s->observers[s->nobservers < MAX_HANDLES ? s->nobservers++ : below(MAX_HANDLES)] = o;
}

/* Checks the result r of a call on world w (may be NULL) that logged log_before messages before. */
static int check_result(fuzz_state* s, const sps_world* w, sps_result r, long log_before, const char* call) {
    s->calls++;
    if (r == SPS_OK) return 0;
    s->errors++;
    if (r != SPS_ERR_INVALID_ARG && r != SPS_ERR_OUT_OF_MEMORY && r != SPS_ERR_UNSTABLE && r != SPS_ERR_IO && r != SPS_ERR_STATE)
        FAIL("%s returned the unknown code %d", call, (int)r);
    if (!w) {
        if (r != SPS_ERR_INVALID_ARG) FAIL("%s with a NULL world returned %d", call, (int)r);
        return 0;
    }
    if (g_log_count == log_before || g_log_last[0] == 0) FAIL("%s returned %s without logging a message", call, sps_result_string(r));
    if (sps_world_last_error(w)[0] == 0) FAIL("%s returned %s with an empty last error", call, sps_result_string(r));
    if (g_verbose) printf("    %s -> %s: %s\n", call, sps_result_string(r), sps_world_last_error(w));
    return 0;
}
#define CALL(s, w, call)                                                 \
    do {                                                                 \
        long before_ = g_log_count;                                      \
        sps_result r_ = call;                                            \
        if (check_result(s, w, r_, before_, #call)) return 1;            \
    } while (0)

/* ---- defs ---- */
static sps_world_def random_world_def(fuzz_alloc* a) {
    sps_world_def d = sps_default_world_def();
    const double p = 0.015; /* per field: most defs valid, about one in five with a hostile field */
    d.dim = chance(p) ? hostile_int() : 2 + below(2);
    d.dp = maybe_hostile(uniform(0.005, 0.05), p);
    d.h_over_dp = chance(0.7) ? 1.3 : maybe_hostile(uniform(0.9, 3.1), p);
    d.kernel = (sps_kernel_type)(chance(p) ? hostile_int() : below(2));
    d.stepping = (sps_stepping)(chance(p) ? hostile_int() : chance(0.2));
    d.cfl_acoustic = maybe_hostile(chance(0.5) ? 0.4 : uniform(0.05, 1.05), p);
    d.cfl_advection = maybe_hostile(chance(0.5) ? 0.2 : uniform(0.05, 1.05), p);
    d.max_substeps = chance(p) ? hostile_int() : 1 + below(8);
    d.gravity[below(3)] = maybe_hostile(uniform(-20, 20), p);
    d.frozen_geometry = chance(p) ? hostile_int() : below(2);
    d.neighbor_capacity = maybe_hostile(chance(0.6) ? 2 : uniform(0.9, 4), p);
    d.threads = chance(p) ? hostile_int() : below(3);
    d.escape_distance = chance(0.3) ? (chance(0.5) ? INFINITY : uniform(0.01, 1)) : maybe_hostile(0, p);
    d.keep_last_good_state = chance(p) ? hostile_int() : below(2);
    d.report_fragments = chance(p) ? hostile_int() : below(2);
    d.energy_growth_limit = chance(0.2) ? (chance(0.5) ? INFINITY : uniform(0.001, 0.5)) : maybe_hostile(0.05, p);
    d.energy_growth_stops = chance(p) ? hostile_int() : below(2);
    d.log = capture_log;
    a->fail_p = chance(0.08) ? uniform(0.005, 0.1) : 0;
    a->live = 0;
    if (!chance(0.1)) { d.allocator.alloc = fuzz_malloc; d.allocator.free = fuzz_free; d.allocator.user = a; }
    if (chance(0.01)) d.allocator.free = NULL; /* one-sided */
    if (chance(0.01)) d.internal_cookie = 0;
    return d;
}

static sps_body_def random_body_def(void) {
    static const char* names[] = {"plate", "", "a name longer than the thirty-one characters kept", "x"};
    sps_body_def d = sps_default_body_def();
    const double p = 0.015;
    d.name = chance(0.2) ? NULL : names[below(4)];
    d.material.density = maybe_hostile(uniform(100, 1e4), p);
    d.material.youngs_modulus = maybe_hostile(exp(uniform(log(1e4), log(1e8))), p);
    d.material.poisson_ratio = chance(p) ? (chance(0.5) ? 0.5 : hostile_real()) : uniform(-0.5, 0.4999);
    d.shear = (sps_shear)(chance(p) ? hostile_int() : below(6));
    d.rotation = (sps_rotation)(chance(p) ? hostile_int() : below(3));
    d.material.kind = (sps_material_kind)(chance(p) ? hostile_int() /* sometimes a wall body, sometimes plastic */
                                                    : chance(0.15) ? SPS_MATERIAL_RIGID : chance(0.2) ? SPS_MATERIAL_J2
                                                    : chance(0.2) ? SPS_MATERIAL_FLUID : chance(0.15) ? SPS_MATERIAL_DRUCKER_PRAGER
                                                    : SPS_MATERIAL_ELASTIC);
    d.material.granular.cohesion = chance(0.3) ? 0 : maybe_hostile(d.material.youngs_modulus * exp(uniform(log(1e-4), log(1e-2))), p);
    d.material.granular.friction_angle = maybe_hostile(uniform(0, 45), p);
    d.material.granular.dilatancy_angle = chance(0.6) ? 0 : maybe_hostile(uniform(0, 1) * d.material.granular.friction_angle, p);
    d.material.granular.stress_diffusion = chance(0.3) ? 0 : maybe_hostile(uniform(0, 1), p);
    d.material.fluid.sound_speed = maybe_hostile(exp(uniform(log(1), log(1e3))), p);
    d.material.viscosity = chance(0.6) ? 0 : maybe_hostile(exp(uniform(log(1e-3), log(10))), p);
    d.transport = (sps_transport)(chance(p) ? hostile_int() : below(3));
    d.transport_coefficient = chance(0.7) ? 0 : maybe_hostile(uniform(0, 1), p);
    d.material.j2.yield_stress = maybe_hostile(d.material.youngs_modulus * exp(uniform(log(1e-4), log(1e-2))), p);
    d.material.j2.hardening_modulus = chance(0.5) ? 0 : maybe_hostile(d.material.youngs_modulus * uniform(0, 0.01), p);
    d.contact = chance(p) ? hostile_int() : !chance(0.1);
    d.zeta = chance(0.7) ? 0 : maybe_hostile(uniform(0, 10), p);
    d.xi = chance(0.7) ? 0 : maybe_hostile(uniform(0, 10), p);
    d.oas_epsilon = maybe_hostile(uniform(0, 1), p);
    d.oas_exponent = maybe_hostile(uniform(1, 12), p);
    d.track_stress = chance(p) ? hostile_int() : below(2);
    d.damping = chance(0.7) ? 0 : maybe_hostile(exp(uniform(log(1e-2), log(1e6))), p);
    d.friction = chance(0.6) ? 0 : maybe_hostile(uniform(0, 1), p); /* Coulomb friction */
    d.contact_damping = chance(0.6) ? 0 : maybe_hostile(uniform(0, 1), p); /* normal contact damping */
    if (chance(0.01)) d.internal_cookie = 12345;
    return d;
}

/* A box near the origin of a few dp per side (up to ~100-200 particles), or a hostile one. */
static void random_box(double dp, int dim, sps_real lo[3], sps_real hi[3]) {
    int a;
    if (!(dp > 0 && dp < 1e6)) dp = 0.01;
    for (a = 0; a < 3; ++a) {
        lo[a] = uniform(-5, 5) * dp;
        hi[a] = lo[a] + (dim == 3 ? below(6) : below(14)) * dp + uniform(0, 1) * dp;
    }
    if (chance(0.05)) lo[below(3)] = hostile_real();
    if (chance(0.05)) hi[below(3)] = hostile_real();
    if (chance(0.03)) { hi[0] = lo[0] + 1e30; hi[1] = lo[1] + 1e30; } /* too many particles: rejected */
}

static double g_sdf_radius;
static sps_real sdf_disc(const sps_real x[3], void* user) {
    (void)user;
    if (g_sdf_radius < 0) return (sps_real)NAN; /* hostile callback */
    return (sps_real)(sqrt(x[0] * x[0] + x[1] * x[1]) - g_sdf_radius);
}

typedef struct { double scale; uint64_t rng; } velocity_field;
static void random_velocity(const sps_real x[3], sps_real v[3], void* user) {
    velocity_field* f = (velocity_field*)user;
    int a;
    (void)x;
    for (a = 0; a < 3; ++a) {
        uint64_t z = (f->rng += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        v[a] = (sps_real)(f->scale * ((double)(z >> 11) / 9007199254740992.0 - 0.5));
    }
}

/* An external acceleration of every kind of argument: a spring to the reference position, a
   drag, a pull growing with time, all scaled by *user (hostile scales included: NaN and
   overflow must end in SPS_ERR_UNSTABLE, never a crash). Reads only its arguments. */
static void random_acceleration(const sps_real x[3], const sps_real x0[3], const sps_real v[3], sps_real t, sps_real a[3], void* user) {
    const double scale = *(const double*)user;
    int k;
    for (k = 0; k < 3; ++k) a[k] = (sps_real)(scale * (-(x[k] - x0[k]) - 0.1 * v[k] + (k == 1 ? -1 - t : 0)));
}

static int stop_after_three(sps_world* w, void* user) {
    (void)w;
    return ++*(int*)user >= 3;
}

/* ---- one random call on one of the case's worlds ---- */
static int random_call(fuzz_state* s) {
    int k = below(MAX_WORLDS), op = below(33);
    sps_world* w = s->w[k];
    sps_real lo[3], hi[3], x[3];
    double dp = s->dp[k];
    int dim = s->dim[k];
    int a;
    if (!(dp > 0 && dp < 1e6)) dp = 0.01;
    for (a = 0; a < 3; ++a) x[a] = uniform(-5, 10) * dp;
    if (chance(0.03)) x[below(3)] = hostile_real();
    /* steer towards worlds that can step: create, then a body, then particles (mostly) */
    if (!w && op != 0 && !chance(0.1)) op = 0;
    else if (w && !has_own_body(s, k) && chance(0.8)) op = 2;
    else if (w && sps_world_particle_count(w) == 0 && chance(0.7)) op = 4;
    switch (op) {
    case 0: { /* create (replacing: destroy first) */
        sps_world_def d;
        long before = g_log_count;
        sps_result r;
        sps_world_destroy(s->w[k]);
        s->w[k] = NULL;
        orphan_bodies(s, k);
        d = random_world_def(&s->alloc[k]);
        r = sps_world_create(&d, chance(0.01) ? NULL : &s->w[k]);
        s->calls++;
        if (r != SPS_OK) {
            s->errors++;
            if (s->w[k] != NULL) FAIL("sps_world_create failed (%d) but set the world", (int)r);
            if (g_log_count == before || !g_log_last[0]) FAIL("sps_world_create returned %d without a logged message", (int)r);
            if (g_verbose) printf("    create -> %s: %s\n", sps_result_string(r), g_log_last);
        } else {
            s->dp[k] = d.dp;
            s->dim[k] = d.dim;
        }
    } break;
    case 1: /* destroy: its handles stay in the pool as handles of a destroyed world */
        if (w && w->def.allocator.alloc == fuzz_malloc) {
            sps_world_destroy(w);
            if (s->alloc[k].live != 0) FAIL("sps_world_destroy left %ld blocks", s->alloc[k].live);
        } else {
            sps_world_destroy(w);
        }
        s->w[k] = NULL;
        orphan_bodies(s, k);
        break;
    case 2: case 3: { /* add body */
        sps_body_def d = random_body_def();
        sps_body b = {0};
        CALL(s, w, sps_world_add_body(w, chance(0.02) ? NULL : &d, &b));
        keep_body(s, b, k);
    } break;
    case 4: case 5: case 6: /* box */
        if (sps_world_particle_count(w) > MAX_PARTICLES) break;
        random_box(dp, dim, lo, hi);
        CALL(s, w, sps_body_add_box(w, any_body(s, k), chance(0.02) ? NULL : lo, hi, chance(0.5) ? NULL : &a));
        break;
    case 7: /* sdf */
        if (sps_world_particle_count(w) > MAX_PARTICLES) break;
        random_box(dp, dim, lo, hi);
        g_sdf_radius = chance(0.1) ? -1 : uniform(0, 6) * dp;
        CALL(s, w, sps_body_add_sdf(w, any_body(s, k), lo, hi, chance(0.05) ? NULL : sdf_disc, NULL, NULL));
        break;
    case 8: { /* particles */
        sps_real xyz[3 * 8], vol[8];
        int n = below(8) + (chance(0.05) ? -3 : 0), i;
        if (sps_world_particle_count(w) > MAX_PARTICLES) break;
        for (i = 0; i < 8; ++i) {
            for (a = 0; a < 3; ++a) xyz[3 * i + a] = uniform(-5, 10) * dp;
            vol[i] = (sps_real)(dp * dp * uniform(0.5, 1.5));
        }
        if (chance(0.05)) xyz[below(24)] = hostile_real();
        if (chance(0.05)) vol[below(8)] = hostile_real();
        if (chance(0.02)) xyz[below(24)] = 1e300; /* finite, far away */
        CALL(s, w, sps_body_add_particles(w, any_body(s, k), n, chance(0.02) ? NULL : xyz, chance(0.5) ? NULL : vol));
    } break;
    case 9: { /* velocities */
        static const double scales[] = {0, 0.1, 1, 10, 100, 1e4, 1e200};
        velocity_field f;
        f.scale = chance(0.05) ? hostile_real() : scales[below(7)];
        f.rng = next_u64();
        CALL(s, w, sps_body_set_velocity(w, any_body(s, k), chance(0.02) ? NULL : random_velocity, &f));
        if (chance(0.2)) /* a geostatic stress (refused but for Drucker-Prager bodies under gravity) */
            CALL(s, w, sps_body_set_geostatic_stress(w, any_body(s, k), (sps_real)maybe_hostile(uniform(-1, 2), 0.02),
                                                     (sps_real)(chance(0.5) ? 0 : maybe_hostile(uniform(0, 2), 0.05))));
    } break;
    case 10: { /* constraint */
        sps_real v[3];
        for (a = 0; a < 3; ++a) v[a] = maybe_hostile(uniform(-1, 1), 0.03);
        random_box(dp, dim, lo, hi);
        CALL(s, w, sps_body_constrain_box(w, any_body(s, k), lo, hi, chance(0.05) ? (unsigned)hostile_int() : 1u + (unsigned)below(7),
                                          chance(0.3) ? NULL : v, chance(0.5) ? NULL : &a));
    } break;
    case 11: { /* observer */
        sps_observer o = {0};
        CALL(s, w, sps_world_add_observer(w, any_body(s, k), chance(0.02) ? NULL : x, &o));
        keep_observer(s, o);
    } break;
    case 12: { /* observer read */
        sps_real u[3], v[3];
        CALL(s, w, sps_observer_read(w, any_observer(s), chance(0.3) ? NULL : u, chance(0.3) ? NULL : v));
    } break;
    case 13: case 14: case 15: case 22: case 23: case 24: case 25: { /* step or advance */
        double t0 = sps_world_time(w);
        long before = g_log_count;
        int count = 0;
        sps_result r = op == 15 ? sps_world_advance(w, chance(0.05) ? hostile_real() : t0 + uniform(0, 1e-3), stop_after_three, &count)
                                : sps_world_step(w);
        if (check_result(s, w, r, before, op == 15 ? "sps_world_advance" : "sps_world_step")) return 1;
        s->steps++;
        if (w && r == SPS_OK && op != 15 && !(sps_world_time(w) > t0)) FAIL("sps_world_step returned SPS_OK without advancing t = %g", t0);
    } break;
    case 16: { /* diagnostics */
        sps_diagnostics d;
        char row[1024];
        CALL(s, w, sps_world_diagnostics(w, chance(0.5) ? any_body(s, k) : (sps_body){0}, chance(0.02) ? NULL : &d));
        if (w && sps_world_diagnostics(w, (sps_body){0}, &d) == SPS_OK && sps_diagnostics_csv_row(&d, row, sizeof row) <= 0)
            FAIL("sps_diagnostics_csv_row wrote nothing");
    } break;
    case 17: { /* VTK output */
        char path[512];
        const char* p = path;
        if (!chance(0.3)) break; /* files are slow: 30 % of the draws */
        snprintf(path, sizeof path, "%s/fuzz_%d.vtk", s->out_dir, k);
        if (chance(0.1)) p = "/nonexistent-dir/fuzz.vtk";
        if (chance(0.05)) p = NULL;
        if (chance(0.5)) {
            CALL(s, w, sps_world_write_vtk(w, p));
        } else { /* binary or ASCII, with or without the stress tensor; sometimes an option out of range */
            sps_vtk_options o = sps_default_vtk_options();
            o.binary = chance(0.05) ? hostile_int() : below(2);
            o.stress = chance(0.05) ? hostile_int() : below(2);
            CALL(s, w, sps_world_write_vtk_ex(w, p, chance(0.1) ? NULL : &o));
        }
    } break;
    case 18: { /* queries */
        sps_particle_state ps;
        int n = sps_world_particle_count(w), id = n ? below(n + 2) - 1 : below(3) - 1;
        CALL(s, w, sps_world_particle(w, id, chance(0.02) ? NULL : &ps));
        (void)sps_world_field(w, (sps_field)(chance(0.1) ? hostile_int() : below(12)));
        (void)sps_world_nearest_particle(w, any_body(s, k), x);
        (void)sps_world_kernel(w, (sps_real)uniform(0, 3 * dp));
        (void)sps_world_kernel_derivative(w, (sps_real)uniform(0, 3 * dp));
        (void)sps_body_is_valid(w, any_body(s, k));
        (void)sps_world_particle_ids(w);
        (void)sps_world_get_def(w);
    } break;
    case 19: { /* material constants */
        sps_real c0, G, K;
        CALL(s, w, sps_body_material_constants(w, any_body(s, k), &c0, chance(0.5) ? &G : NULL, &K));
    } break;
    case 20: { /* validate */
        char msg[2048];
        sps_result r = sps_world_validate(w, chance(0.1) ? NULL : msg, sizeof msg);
        s->calls++;
        if (!w && r != SPS_ERR_INVALID_ARG) FAIL("sps_world_validate(NULL) returned %d", (int)r);
        if (w && r != SPS_OK && r != SPS_ERR_STATE) FAIL("sps_world_validate returned %d", (int)r);
    } break;
    case 21: { /* NULL world calls */
        sps_diagnostics d;
        sps_body b = any_body(s, k);
        CALL(s, NULL, sps_world_step(NULL));
        CALL(s, NULL, sps_world_diagnostics(NULL, b, &d));
        CALL(s, NULL, sps_body_add_box(NULL, b, x, x, NULL));
        (void)sps_world_time(NULL);
    } break;
    case 27: { /* a wall, or the walls of a box */
        sps_real normal[3];
        for (a = 0; a < 3; ++a) normal[a] = chance(0.1) ? 0 : uniform(-1, 1);
        if (chance(0.03)) normal[below(3)] = hostile_real();
        if (chance(0.5)) {
            CALL(s, w, sps_world_add_wall(w, chance(0.02) ? NULL : x, chance(0.02) ? NULL : normal, (sps_wall_slip)below(3)));
        } else {
            random_box(dp, dim, lo, hi);
            CALL(s, w, sps_world_add_box_walls(w, lo, hi, (unsigned)below(80), (sps_wall_slip)below(3)));
        }
        if (chance(0.5)) /* wall friction, on any wall or all of them, sometimes hostile */
            CALL(s, w, sps_world_set_wall_friction(w, (int)below(4) - 1, chance(0.05) ? hostile_real() : uniform(0, 1)));
    } break;
    case 28: /* which bodies touch */
        CALL(s, w, sps_world_set_contact(w, any_body(s, k), any_body(s, k), below(3)));
        break;
    case 29: { /* write a particle's position or velocity */
        sps_real v[3];
        for (a = 0; a < 3; ++a) v[a] = chance(0.03) ? hostile_real() : uniform(-1, 1);
        CALL(s, w, sps_world_set_particle(w, chance(0.9) ? below(sps_world_particle_count(w) + 2) - 1 : hostile_int(),
                                          chance(0.5) ? x : NULL, chance(0.5) ? v : NULL));
    } break;
    case 30: { /* an external acceleration, or none */
        static const double scales[] = {0, 1, 10, 1e3, 1e300};
        const int slot = s->nbodies ? below(s->nbodies) : 0;
        sps_body b = s->nbodies && chance(0.95) ? s->bodies[slot] : any_body(s, k);
        s->load[slot] = chance(0.03) ? hostile_real() : scales[below(5)];
        CALL(s, w, sps_body_set_acceleration(w, b, chance(0.2) ? NULL : random_acceleration, &s->load[slot]));
    } break;
    case 31: { /* save; then restore the world's own save, which must give back the same state */
        char path[512];
        const char* p = path;
        long before = g_log_count;
        sps_result r;
        if (!chance(0.3)) break; /* files are slow: 30 % of the draws */
        snprintf(path, sizeof path, "%s/fuzz_%d.restart", s->out_dir, k);
        if (chance(0.1)) p = "/nonexistent-dir/fuzz.restart";
        if (chance(0.05)) p = NULL;
        r = sps_world_save(w, p);
        if (check_result(s, w, r, before, "sps_world_save")) return 1;
        if (w && r == SPS_OK && p == path) {
            const double t = sps_world_time(w);
            before = g_log_count;
            r = sps_world_restore(w, path);
            if (check_result(s, w, r, before, "sps_world_restore")) return 1;
            if (r != SPS_OK && r != SPS_ERR_OUT_OF_MEMORY) FAIL("sps_world_restore of the world's own save returned %d: %s", (int)r, sps_world_last_error(w));
            if (r == SPS_OK && sps_world_time(w) != t) FAIL("sps_world_restore of the world's own save moved the time from %g to %g", t, sps_world_time(w));
        }
    } break;
    case 32: { /* restore from the save of any world of the case (or of none: no file) */
        char path[512];
        if (!chance(0.3)) break;
        snprintf(path, sizeof path, "%s/fuzz_%d.restart", s->out_dir, below(MAX_WORLDS));
        CALL(s, w, sps_world_restore(w, chance(0.05) ? NULL : path));
    } break;
    default: /* 26: destroy and forget every world of the case */
        for (a = 0; a < MAX_WORLDS; ++a) {
            sps_world_destroy(s->w[a]);
            s->w[a] = NULL;
            orphan_bodies(s, a);
        }
        break;
    }
    return 0;
}

static int run_case(uint64_t seed, const char* out_dir, long* calls, long* errors, long* steps) {
    fuzz_state s;
    int k, ncalls, i, r = 0;
    memset(&s, 0, sizeof s);
    s.out_dir = out_dir;
    g_rng = seed;
    g_case_seed = seed;
    ncalls = 10 + below(50);
    for (i = 0; i < ncalls && r == 0; ++i) r = random_call(&s);
    for (k = 0; k < MAX_WORLDS; ++k) {
        int tracked = s.w[k] && s.w[k]->def.allocator.alloc == fuzz_malloc;
        sps_world_destroy(s.w[k]);
        if (r == 0 && tracked && s.alloc[k].live != 0) { printf("fuzz_api: case seed %llu: %ld blocks leaked\n", (unsigned long long)seed, s.alloc[k].live); r = 1; }
    }
    *calls += s.calls;
    *errors += s.errors;
    *steps += s.steps;
    return r;
}

int main(int argc, char** argv) {
    unsigned long long seed = 1;
    long cases = 10000, k, calls = 0, errors = 0, steps = 0;
    const char* out_dir = "/tmp";
    double t0;
    struct timespec ts;
    int i, failed = 0;
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc) seed = strtoull(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--cases") == 0 && i + 1 < argc) cases = strtol(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) out_dir = argv[++i];
        else if (strcmp(argv[i], "--verbose") == 0) g_verbose = 1;
        else {
            printf("usage: %s [--seed S] [--cases N] [--out DIR] [--verbose]\n", argv[0]);
            return strcmp(argv[i], "--help") == 0 ? 0 : 2;
        }
    }
    signal(SIGSEGV, on_signal);
    signal(SIGBUS, on_signal);
    signal(SIGFPE, on_signal);
    signal(SIGILL, on_signal);
    signal(SIGABRT, on_signal);
    signal(SIGALRM, on_signal);
#ifdef FUZZ_SANITIZED
    __sanitizer_set_death_callback(on_sanitizer_death);
#endif
    clock_gettime(CLOCK_MONOTONIC, &ts);
    t0 = (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
    for (k = 0; k < cases && !failed; ++k) {
        alarm(60); /* a case takes milliseconds; a minute means it hangs */
        failed = run_case(seed + (unsigned long long)k, out_dir, &calls, &errors, &steps);
    }
    alarm(0);
    clock_gettime(CLOCK_MONOTONIC, &ts);
    printf("fuzz_api: %ld cases (seeds %llu..%llu), %ld calls, %ld errors returned (each with a message), %ld steps, %.1f s: %s\n",
           k, seed, seed + (unsigned long long)k - 1, calls, errors, steps, (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec - t0,
           failed ? "FAILED" : "ok");
    return failed ? 1 : 0;
}
