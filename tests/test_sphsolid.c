/* test_sphsolid.c - unit, invariant and regression tests of sphsolid.h: the runner and its
   helpers; the tests are in one file per part of the library, included below (test_numerics.c,
   test_api.c, test_solids.c, test_fluids.c, test_rigid.c, test_periodic.c, test_open.c), and
   each file ends with its own list of tests (run_numerics_tests, ...), which main calls. A new
   test is a function and a RUN line in its file's list.

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

    /* each test file's list, in the order the files are included */
    run_numerics_tests();
    run_api_tests();
    run_solids_tests();
    run_fluids_tests();
    run_rigid_tests();
    run_periodic_tests();
    run_open_tests();

    if (g_skipped) printf("(%d long tests skipped)\n", g_skipped);
    printf("%d passed, %d failed\n", g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}
