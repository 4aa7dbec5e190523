/* test_sphsolid.c - unit, invariant and regression tests of sphsolid.h.

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
/* >>kernel                                                                                     */

/* Partition of unity: sum_j W(x - x_j) dp^d over a lattice is the midpoint-rule value of the
   kernel's integral (= 1). It is not exact: the error is the aliasing of the kernel's Fourier
   transform at the lattice wavenumbers 2 pi/dp, which decays like (dp/h)^5 for Wendland C2
   (measured at a node: 3.8e-2 at h/dp = 1, 1.05e-2 at 1.3, 1.2e-3 at 2) and is ~3e-3 or less
   for the cubic spline. At the library's h/dp = 1.3 the tolerance is 1.5e-2; at h/dp = 2 it is
   2e-3, which shows the error is discretisation, not a normalisation constant. */
static int kernel_lattice_sum(int dim, sps_kernel_type kernel, double h_over_dp, const double x0[3], double* sum) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w;
    int i, j, k, reach = 5; /* 2h <= 4 dp < 5 dp */
    double dp = 0.01, vol = dim == 2 ? dp * dp : dp * dp * dp;
    wd.dim = dim; wd.dp = dp; wd.kernel = kernel; wd.h_over_dp = h_over_dp; wd.log = quiet_log;
    if (sps_world_create(&wd, &w) != SPS_OK) return 1;
    *sum = 0;
    for (i = -reach; i <= reach; ++i)
        for (j = -reach; j <= reach; ++j)
            for (k = (dim == 3 ? -reach : 0); k <= (dim == 3 ? reach : 0); ++k) {
                double d[3] = {(i - x0[0]) * dp, (j - x0[1]) * dp, dim == 3 ? (k - x0[2]) * dp : 0};
                *sum += sps_world_kernel(w, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])) * vol;
            }
    sps_world_destroy(w);
    return 0;
}

static int test_kernel_partition_of_unity(void) {
    static const double node[3] = {0, 0, 0}, off[3] = {0.3, 0.45, 0.2}; /* in units of dp */
    int dim, kernel;
    for (dim = 2; dim <= 3; ++dim)
        for (kernel = 0; kernel <= 1; ++kernel) {
            double s_node, s_off, s_node2, s_off2;
            ENSURE(kernel_lattice_sum(dim, (sps_kernel_type)kernel, 1.3, node, &s_node) == 0);
            ENSURE(kernel_lattice_sum(dim, (sps_kernel_type)kernel, 1.3, off, &s_off) == 0);
            ENSURE(kernel_lattice_sum(dim, (sps_kernel_type)kernel, 2.0, node, &s_node2) == 0);
            ENSURE(kernel_lattice_sum(dim, (sps_kernel_type)kernel, 2.0, off, &s_off2) == 0);
            printf("    dim %d %-8s h/dp 1.3: node %.6f off-node %.6f;  h/dp 2: node %.6f off-node %.6f\n", dim,
                   kernel ? "spline" : "wendland", s_node, s_off, s_node2, s_off2);
            ENSURE_NEAR(s_node, 1.0, 1.5e-2);  /* lattice aliasing at h/dp = 1.3, see above */
            ENSURE_NEAR(s_off, 1.0, 1.5e-2);   /* idem */
            ENSURE_NEAR(s_node2, 1.0, 2e-3);   /* ... which shrinks as h/dp grows */
            ENSURE_NEAR(s_off2, 1.0, 2e-3);    /* idem */
        }
    return 0;
}

/* The kernel integrates to one: int_0^2h W(r) 2 pi r dr (2D) or 4 pi r^2 dr (3D), by composite
   Simpson on 4000 intervals. W r^(d-1) is a polynomial of degree <= 7 on each piece and the
   spline's break at r = h falls on an interval end, so the quadrature error is ~1e-14: the
   tolerance 1e-6 can only be broken by a wrong normalisation constant or shape. */
static int test_kernel_integral(void) {
    int dim, kernel;
    for (dim = 2; dim <= 3; ++dim)
        for (kernel = 0; kernel <= 1; ++kernel) {
            sps_world_def wd = sps_default_world_def();
            sps_world* w;
            const int n = 4000;
            double h, a, step, sum = 0;
            int i;
            wd.dim = dim; wd.kernel = (sps_kernel_type)kernel; wd.log = quiet_log;
            ENSURE(sps_world_create(&wd, &w) == SPS_OK);
            h = wd.h_over_dp * wd.dp;
            step = 2 * h / n;
            for (i = 0; i <= n; ++i) {
                double r = i * step, f = sps_world_kernel(w, r) * (dim == 2 ? 2 * PI * r : 4 * PI * r * r);
                sum += f * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
            }
            a = sum * step / 3;
            ENSURE_NEAR(a, 1.0, 1e-6); /* quadrature error ~1e-14, see above */
            /* compact support of radius 2h */
            ENSURE(sps_world_kernel(w, 2 * h) == 0 && sps_world_kernel(w, 2.5 * h) == 0);
            ENSURE(sps_world_kernel_derivative(w, 2 * h) == 0);
            sps_world_destroy(w);
        }
    return 0;
}

/* dW/dr from sps_world_kernel_derivative matches a central finite difference of W, at 199
   radii in (0, 2h). Central differences with step e = 1e-6 h have truncation error
   e^2 |W'''| ~ 1e-12 |W'|max and round-off eps W / e ~ 1e-10 |W'|max: tolerance 1e-7 |W'|max. */
static int test_kernel_derivative(void) {
    int dim, kernel, i;
    for (dim = 2; dim <= 3; ++dim)
        for (kernel = 0; kernel <= 1; ++kernel) {
            sps_world_def wd = sps_default_world_def();
            sps_world* w;
            double h, e, dmax = 0;
            wd.dim = dim; wd.kernel = (sps_kernel_type)kernel; wd.log = quiet_log;
            ENSURE(sps_world_create(&wd, &w) == SPS_OK);
            h = wd.h_over_dp * wd.dp;
            e = 1e-6 * h;
            for (i = 1; i < 200; ++i) dmax = fmax(dmax, fabs(sps_world_kernel_derivative(w, i * 0.01 * h)));
            ENSURE(dmax > 0);
            for (i = 1; i < 200; ++i) {
                double r = i * 0.01 * h + 0.003 * h; /* off the spline's break at r = h */
                double fd = (sps_world_kernel(w, r + e) - sps_world_kernel(w, r - e)) / (2 * e);
                ENSURE_NEAR(sps_world_kernel_derivative(w, r), fd, 1e-7 * dmax); /* see above */
                ENSURE(sps_world_kernel_derivative(w, r) <= 0); /* monotone kernels */
            }
            ENSURE(sps_world_kernel_derivative(w, 0) == 0); /* smooth peak */
            sps_world_destroy(w);
        }
    return 0;
}

/* ============================================================================================ */
/* >>gradient                                                                                   */

/* grad_i W_ij = dW/dr(r_ij) e_ij with e_ij = (x_i - x_j)/r_ij is odd in the pair: grad_i W_ij =
   -grad_j W_ji, exactly in floating point because x_j - x_i is the exact negation of x_i - x_j.
   This is what makes the pairwise forces of the library cancel (see test_momentum_*). And on a
   lattice the gradients of an interior particle cancel: sum_j grad W_ij V_j = 0, up to round-off
   (tolerance 1e-13 of sum_j |grad W_ij| V_j: about 100 terms of relative error 1e-16). */
static int test_gradient_antisymmetry(void) {
    unsigned long long seed = 7;
    int dim, t;
    for (dim = 2; dim <= 3; ++dim) {
        sps_world* w = new_world(dim, 0.01);
        double dp = 0.01, vol = dim == 2 ? dp * dp : dp * dp * dp, sum[3] = {0, 0, 0}, norm = 0;
        int i, j, k, a;
        ENSURE(w);
        for (t = 0; t < 100; ++t) { /* random pairs within the support */
            double xi[3], xj[3], dij[3], dji[3], rij = 0, rji = 0;
            for (a = 0; a < 3; ++a) {
                xi[a] = a < dim ? 0.05 * rnd(&seed) : 0;
                xj[a] = a < dim ? xi[a] + 0.012 * rnd(&seed) : 0;
            }
            for (a = 0; a < 3; ++a) { dij[a] = xi[a] - xj[a]; dji[a] = xj[a] - xi[a]; rij += dij[a] * dij[a]; rji += dji[a] * dji[a]; }
            rij = sqrt(rij); rji = sqrt(rji);
            for (a = 0; a < dim; ++a) {
                double gi = sps_world_kernel_derivative(w, rij) * dij[a] / rij;
                double gj = sps_world_kernel_derivative(w, rji) * dji[a] / rji;
                ENSURE(gi == -gj); /* exact, see above */
            }
        }
        for (i = -4; i <= 4; ++i) /* interior lattice particle at the origin */
            for (j = -4; j <= 4; ++j)
                for (k = (dim == 3 ? -4 : 0); k <= (dim == 3 ? 4 : 0); ++k) {
                    double d[3] = {-i * dp, -j * dp, -k * dp}, r = dp * sqrt((double)(i * i + j * j + k * k)), dw;
                    if (r == 0) continue;
                    dw = sps_world_kernel_derivative(w, r);
                    for (a = 0; a < dim; ++a) sum[a] += dw * d[a] / r * vol;
                    norm += fabs(dw) * vol;
                }
        ENSURE(norm > 0);
        for (a = 0; a < dim; ++a) ENSURE_NEAR(sum[a] / norm, 0.0, 1e-13); /* round-off, see above */
        sps_world_destroy(w);
    }
    return 0;
}

/* ============================================================================================ */
/* >>correction                                                                                 */

/* The uncorrected moment matrix M_i = -sum_j r_ij (x) grad W_ij V_j (the inverse of B_i) on a
   square lattice: the identity up to the lattice error at an interior particle, far from it at a
   corner where half of the support is missing. This is why B is needed, and it shows that the
   next test (exact velocity gradients at every particle) can fail without B. */
static void lattice_moment(const sps_world* w, int dim, int corner, double M[9]) {
    double dp = 0.01, vol = dim == 2 ? dp * dp : dp * dp * dp;
    int i, j, k, a, c, lo = corner ? 0 : -4;
    for (a = 0; a < 9; ++a) M[a] = 0;
    for (i = lo; i <= 4; ++i)
        for (j = lo; j <= 4; ++j)
            for (k = (dim == 3 ? lo : 0); k <= (dim == 3 ? 4 : 0); ++k) {
                double d[3] = {-i * dp, -j * dp, -k * dp}, r = dp * sqrt((double)(i * i + j * j + k * k));
                if (r == 0) continue;
                for (a = 0; a < dim; ++a)
                    for (c = 0; c < dim; ++c) M[3 * a + c] -= d[a] * sps_world_kernel_derivative(w, r) * d[c] / r * vol;
            }
}

static double det3(const double M[9]) {
    return M[0] * (M[4] * M[8] - M[5] * M[7]) - M[1] * (M[3] * M[8] - M[5] * M[6]) + M[2] * (M[3] * M[7] - M[4] * M[6]);
}

static int test_moment_matrix_lattice(void) {
    int dim, a, c;
    for (dim = 2; dim <= 3; ++dim) {
        sps_world* w = new_world(dim, 0.01);
        double Mi[9], Mc[9], dev = 0;
        ENSURE(w);
        lattice_moment(w, dim, 0, Mi);
        lattice_moment(w, dim, 1, Mc);
        if (dim == 2) Mi[8] = Mc[8] = 1;
        for (a = 0; a < dim; ++a)
            for (c = 0; c < dim; ++c) dev = fmax(dev, fabs(Mi[3 * a + c] - (a == c)));
        printf("    dim %d: interior max |M - I| = %.4f; corner M_xx = %.3f, det M = %.4f\n", dim, dev, Mc[0], det3(Mc));
        ENSURE(dev < 4e-2);               /* lattice error, 2.6% measured (same origin as the partition of unity) */
        ENSURE(fabs(Mc[0] - 1) > 0.2);    /* a truncated support: at least 20% off */
        sps_world_destroy(w);
    }
    return 0;
}

/* Affine velocity v = A (x - c) (A row-major 3x3; zero third row and column in 2D). */
typedef struct { double A[9], c[3]; } affine_field;
static void affine_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const affine_field* f = (const affine_field*)user;
    int a, c;
    for (a = 0; a < 3; ++a) {
        v[a] = 0;
        for (c = 0; c < 3; ++c) v[a] += f->A[3 * a + c] * (x[c] - f->c[c]);
    }
}

/* The B-corrected velocity gradient is exact for an affine velocity field v = A x at EVERY
   particle of a lattice block, surface and corners included (ANG eqs. 20-21: L = A M B = A).
   Observable: with track_stress the first acoustic sub-step adds tau = 2 G dt dev(sym(L)) (the
   Jaumann terms vanish at tau = 0) while the pressure is still 0, so each particle's von Mises
   stress must equal that of 2 G dt dev(sym(A)). Errors allowed, relative to 2 G dt |A|max:
   - cfl_acoustic = 1e-6: the kick before the continuity pass changes v_ij at surface particles by
     a relative ~cfl h/dp (Riemann dissipation of the affine field): 1e-5 covers it;
   - B is a regularised inverse, w M^-1 + (1 - w) I with 1 - w = 1e-6/det(M)^2
     (sps__regularized_inverse), so a corner particle, where det M is smallest, carries an error
     (1e-6/det^2) |I - M^-1|: we allow 3e-6/det^2 with det M of a lattice corner from
     test_moment_matrix_lattice (0.135 in 2D, 0.023 in 3D: tolerances 1.8e-4 and 5.8e-3).
   Without B the corner gradients would be off by the 60-70% of that test. */
static int velocity_gradient_case(int dim, const double A[9], double* worst) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body b;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0}, G;
    affine_field f;
    double tau[6], tr = 0, dt, vm_expected, scale = 0, Aij;
    int n, id, a;
    static const int row[6] = {0, 0, 0, 1, 1, 2}, col[6] = {0, 1, 2, 1, 2, 2};
    if (dim == 3) hi[0] = hi[1] = hi[2] = 0.06;
    wd.dim = dim; wd.cfl_acoustic = 1e-6; wd.max_substeps = 1; wd.threads = 1; wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.shear = SPS_SHEAR_ENO_A;
    bd.track_stress = 1;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK);
    ENSURE(sps_body_add_box(w, b, lo, hi, &n) == SPS_OK && n >= 100);
    memcpy(f.A, A, sizeof f.A);
    for (a = 0; a < 3; ++a) f.c[a] = 0.5 * (lo[a] + hi[a]);
    ENSURE(sps_body_set_velocity(w, b, affine_velocity, &f) == SPS_OK);
    ENSURE(sps_world_step(w) == SPS_OK);
    dt = sps_world_time(w);
    ENSURE(dt > 0);
    ENSURE(sps_body_material_constants(w, b, NULL, &G, NULL) == SPS_OK);
    for (a = 0; a < dim; ++a) tr += A[4 * a];
    for (a = 0; a < 6; ++a) {
        Aij = row[a] < dim && col[a] < dim ? 0.5 * (A[3 * row[a] + col[a]] + A[3 * col[a] + row[a]]) : 0;
        tau[a] = 2 * G * dt * (Aij - (row[a] == col[a] && row[a] < dim ? tr / dim : 0));
    }
    for (a = 0; a < 9; ++a) scale = fmax(scale, 2 * G * dt * fabs(A[a]));
    vm_expected = von_mises(tau, dim);
    *worst = 0;
    for (id = 0; id < n; ++id) {
        sps_particle_state s;
        ENSURE(sps_world_particle(w, id, &s) == SPS_OK);
        ENSURE(s.pressure == 0); /* p is set from rho before the first density update */
        *worst = fmax(*worst, fabs(s.von_mises - vm_expected) / scale);
    }
    sps_world_destroy(w);
    return 0;
}

static int test_velocity_gradient_affine(void) {
    static const double shear2[9] = {0.4, 1.0, 0, -0.3, -0.4, 0, 0, 0, 0}; /* traceless, with spin */
    static const double dilate2[9] = {1, 0, 0, 0, 1, 0, 0, 0, 0};          /* dev = 0: no shear stress */
    static const double shear3[9] = {0.2, 1.0, -0.3, 0.1, -0.5, 0.4, 0.6, -0.2, 0.3};
    static const double dilate3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double* fields[4] = {shear2, dilate2, shear3, dilate3};
    int k;
    for (k = 0; k < 4; ++k) {
        int dim = k < 2 ? 2 : 3;
        sps_world* w = new_world(dim, 0.01);
        double worst, Mc[9], det, tol;
        ENSURE(w);
        lattice_moment(w, dim, 1, Mc);
        if (dim == 2) Mc[8] = 1;
        det = det3(Mc);
        sps_world_destroy(w);
        tol = 3e-6 / (det * det) + 1e-5; /* regularisation at a corner + cfl, see above */
        ENSURE(velocity_gradient_case(dim, fields[k], &worst) == 0);
        printf("    dim %d %-10s: max |vm - vm_exact| / (2 G dt |A|) = %.2e (tolerance %.1e)\n", dim,
               k % 2 ? "dilatation" : "shear", worst, tol);
        ENSURE(worst < tol);
    }
    return 0;
}

/* The Rodrigues matrix (ANG eqs. 38-40) of a pure spin, by its series (turn below 0.01 rad) and
   by sin and cos (above), against the rotation by angle th about the unit axis n written out:
   R = cos th I + sin th [n]x + (1 - cos th) n n^T. Tolerance: round-off of a few terms of order 1
   (1e-14), and the series must agree with the trigonometric form to the same digits. */
static int test_rodrigues_matrix(void) {
    static const double turns[4] = {1e-6, 4e-3, 0.0099, 0.8}; /* rad per dt: series x3, then sin/cos */
    const double n[3] = {2.0 / 7, -3.0 / 7, 6.0 / 7}, dt = 1e-3;
    int k, dim, a, c;
    for (dim = 2; dim <= 3; ++dim)
        for (k = 0; k < 4; ++k) {
            const double th = turns[k], om = th / dt;
            const double ax[3] = {dim == 3 ? n[0] : 0, dim == 3 ? n[1] : 0, dim == 3 ? n[2] : 1};
            sps_real L[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, R[9];
            double worst = 0;
            /* L = om [n]x (a skew velocity gradient: rigid rotation at om about n) */
            L[1] = (sps_real)(-om * ax[2]); L[3] = (sps_real)(om * ax[2]);
            L[2] = (sps_real)(om * ax[1]); L[6] = (sps_real)(-om * ax[1]);
            L[5] = (sps_real)(-om * ax[0]); L[7] = (sps_real)(om * ax[0]);
            sps__rodrigues(L, (sps_real)dt, dim, R);
            for (a = 0; a < 3; ++a)
                for (c = 0; c < 3; ++c) {
                    const double cross[9] = {0, -ax[2], ax[1], ax[2], 0, -ax[0], -ax[1], ax[0], 0};
                    double exact = (a == c ? cos(th) : 0) + sin(th) * cross[3 * a + c] + (1 - cos(th)) * ax[a] * ax[c];
                    worst = fmax(worst, fabs((double)R[3 * a + c] - exact));
                }
            printf("    dim %d turn %-7g rad: max |R - R_exact| = %.1e\n", dim, th, worst);
            ENSURE(worst < (sps_is_double() ? 1e-14 : 1e-6));
        }
    return 0;
}

/* ============================================================================================ */
/* >>riemann                                                                                    */

/* The low-dissipation Riemann pressure P* (ENO eqs. 14-16). All checks are algebraic identities
   of eq. 14, so the tolerances are round-off: a few ulps of the largest term (1e-14 relative). */
static int test_riemann_pressure(void) {
    unsigned long long seed = 11;
    int t, lim;
    for (t = 0; t < 200; ++t) {
        double rl = 1000 * (1 + 0.5 * rnd(&seed)), rr = 1000 * (1 + 0.5 * rnd(&seed));
        double cl = 50 * (1 + 0.5 * rnd(&seed)), cr = 50 * (1 + 0.5 * rnd(&seed));
        double ul = 2 * rnd(&seed), ur = 2 * rnd(&seed), pl = 1e5 * rnd(&seed), pr = 1e5 * rnd(&seed);
        double scale = fabs(pl) + fabs(pr) + rl * cl * (fabs(ul) + fabs(ur)), p1, p2;
        for (lim = 0; lim <= 1; ++lim) {
            /* symmetry: the mirrored problem (right becomes left, velocities flip sign) */
            p1 = sps_riemann_pressure(rl, ul, pl, cl, rr, ur, pr, cr, lim);
            p2 = sps_riemann_pressure(rr, -ur, pr, cr, rl, -ul, pl, cl, lim);
            ENSURE_NEAR(p1, p2, 1e-14 * scale);
            /* consistency: equal states give back the state's pressure */
            ENSURE_NEAR(sps_riemann_pressure(rl, ul, pl, cl, rl, ul, pl, cl, lim), pl, 1e-14 * scale);
        }
        /* beta = 1 with equal impedance Z: P* = (p_l + p_r)/2 + Z/2 (u_l - u_r) */
        ENSURE_NEAR(sps_riemann_pressure(rl, ul, pl, cl, rl, ur, pr, cl, 0), 0.5 * (pl + pr) + 0.5 * rl * cl * (ul - ur), 1e-14 * scale);
    }
    /* limiter, beta = min(3 max((u_l - u_r)/c, 0), 1) (ENO eq. 16 made dimensionless, see the
       header): no dissipation under expansion (u_l < u_r) ... */
    ENSURE_NEAR(sps_riemann_pressure(1000, -1, 2e5, 40, 1000, 1, 1e5, 40, 1), 1.5e5, 1e-9);
    /* ... full dissipation under strong compression: 3 * 20/40 = 1.5, clipped to 1 ... */
    ENSURE_NEAR(sps_riemann_pressure(1000, 10, 2e5, 40, 1000, -10, 1e5, 40, 1), 1.5e5 + 0.5 * 4e4 * 20, 1e-9);
    /* ... and partial dissipation in between: beta = 3 * 0.02/40 = 0.0015 */
    ENSURE_NEAR(sps_riemann_pressure(1000, 0.01, 2e5, 40, 1000, -0.01, 1e5, 40, 1), 1.5e5 + 0.0015 * 0.5 * 4e4 * 0.02, 1e-9);
    return 0;
}

/* ============================================================================================ */
/* >>rotation                                                                                   */

typedef struct { double omega, c[3]; } spin_field;
static void spin_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const spin_field* s = (const spin_field*)user;
    v[0] = -s->omega * (x[1] - s->c[1]);
    v[1] = s->omega * (x[0] - s->c[0]);
    v[2] = 0;
}
static sps_real disc_sdf(const sps_real x[3], void* user) {
    const double* r = (const double*)user;
    return (sps_real)(sqrt(x[0] * x[0] + x[1] * x[1]) - *r);
}

/* A spinning disc, radius R = 0.1 (314 particles), rim speed omega R = rim_mach c0, one thread. */
static sps_world* spinning_disc(sps_shear shear, sps_rotation rotation, int frozen, double rim_mach, spin_field* s, int* n) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body b;
    sps_real lo[3] = {-0.1, -0.1, 0}, hi[3] = {0.1, 0.1, 0}, c0;
    double R = 0.1;
    wd.threads = 1; wd.frozen_geometry = frozen; wd.log = quiet_log;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    bd.shear = shear;
    bd.rotation = rotation;
    if (sps_world_add_body(w, &bd, &b) != SPS_OK || sps_body_add_sdf(w, b, lo, hi, disc_sdf, &R, n) != SPS_OK ||
        sps_body_material_constants(w, b, &c0, NULL, NULL) != SPS_OK) {
        sps_world_destroy(w);
        return NULL;
    }
    s->omega = rim_mach * c0 / R;
    s->c[0] = s->c[1] = s->c[2] = 0;
    if (sps_body_set_velocity(w, b, spin_velocity, s) != SPS_OK) { sps_world_destroy(w); return NULL; }
    return w;
}

/* Largest |v_i - omega x (x_i - c)| over the particles, at their reference (X) or current (x)
   positions. */
static double rigid_deviation(const sps_world* w, int n, const spin_field* s, int current) {
    double worst = 0;
    int id;
    for (id = 0; id < n; ++id) {
        sps_particle_state ps;
        sps_real x[3], v[3];
        int a;
        sps_world_particle(w, id, &ps);
        for (a = 0; a < 3; ++a) x[a] = ps.position[a] - (current ? 0 : ps.displacement[a]);
        spin_velocity(x, v, (void*)s);
        worst = fmax(worst, hypot(ps.velocity[0] - v[0], ps.velocity[1] - v[1]));
    }
    return worst;
}

/* A rigid rotation v = omega x r has v_ij . e_ij = 0 for every pair, so the rotation-invariant
   Laplacian of ENO eq. 23, the density rate and the Riemann dissipation all vanish, at surface
   particles too. (A plain Laplacian sum_j v_ij/r_ij dW V_j = omega x sum_j e_ij dW V_j vanishes
   only where the support is full, not at the surface.) Without its centripetal stress the disc
   moves on straight lines x = X + t v(X), which stretch it by (omega t)^2 / 2: a physical
   breathing whose velocity is about that strain times c0, so relative to omega R it is
   (omega t)^2 c0 / (2 omega R) ~ 4 omega R / c0 after one advection step (omega t ~ 2.7
   omega R / c0). At omega R = 1e-14 c0 that is 4e-14, below round-off's share, while the
   terms ENO must cancel are linear in omega: each of the ~50 kicks of the first advection step
   must add only round-off, so every velocity stays omega x (X - c) to 1e-12 omega R (50
   sub-steps of ~20 pair terms of relative error 1e-16) and the pressure stays 0 to 1e-12
   rho0 c0 omega R, with either pair geometry. The motion is affine (x = X + t v(X)), so the
   hourglass indicator is zero up to the regularised inverse: 1e-6/det^2 (det M >= 0.13 at a
   2D surface) times the displacement gradient (the angle turned, 3e-14): < 1e-12. */
static int test_rigid_rotation_zero_increment(void) {
    const double rim_mach = 1e-14;
    int k;
    for (k = 0; k < 4; ++k) { /* ENO, ENO-A (k odd); recomputed, frozen geometry (k >= 2) */
        spin_field s;
        sps_diagnostics d;
        int n, id;
        double pmax = 0, dev, c0;
        sps_world* w = spinning_disc(k % 2 ? SPS_SHEAR_ENO_A : SPS_SHEAR_ENO, SPS_ROTATION_MEAN, k / 2, rim_mach, &s, &n);
        ENSURE(w && n > 250);
        c0 = s.omega * 0.1 / rim_mach;
        ENSURE(sps_world_step(w) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
        ENSURE(d.acoustic_steps >= 20); /* many kicks within the one frozen step */
        dev = rigid_deviation(w, n, &s, 0);
        for (id = 0; id < n; ++id) {
            sps_particle_state ps;
            ENSURE(sps_world_particle(w, id, &ps) == SPS_OK);
            pmax = fmax(pmax, fabs(ps.pressure));
        }
        printf("    %s, %s, %ld sub-steps: max |v - omega x X| / (omega R) = %.2e, max |p| / (rho0 c0 omega R) = %.2e, hourglass %.2e\n",
               k % 2 ? "ENO-A" : "ENO  ", k / 2 ? "frozen" : "recomputed", d.acoustic_steps, dev / (s.omega * 0.1), pmax / (1000 * c0 * s.omega * 0.1), d.hourglass);
        ENSURE(dev <= 1e-12 * s.omega * 0.1);              /* round-off, see above */
        ENSURE(pmax <= 1e-12 * 1000 * c0 * s.omega * 0.1); /* round-off, see above */
        ENSURE(d.hourglass < 1e-12);                       /* affine motion, see above */
        sps_world_destroy(w);
    }
    return 0;
}

/* With the default geometry (recomputed each sub-step) an ENO-A disc keeps spinning rigidly:
   after turning 0.5 rad (20 advection steps, ~1000 sub-steps) each velocity is omega x (x - c)
   at its current position to 1e-2 omega R, and the angular momentum is kept to 1e-3.
   Reasons: the disc starts without its centripetal stress, so it breathes with a strain of
   rho (omega R)^2 / E ~ 1e-4, i.e. velocities up to ~1e-4 c0 = 1e-2 omega R (damped by the
   Riemann dissipation: measured 4e-5 omega R); ENO-A rotates the accumulated a_s with the body
   (ANG eqs. 34-42), so its angular-momentum error follows the strain (1e-4; measured 6e-5).
   Plain ENO does not rotate a_s: measured 6e-2 omega R and +6% angular momentum (printed only;
   ANG Fig. 13 reports the same failure of ENO in the spinning plate). */
static int spin_for_half_radian(sps_shear shear, sps_rotation rotation, double* dev, double* dl) {
    spin_field s;
    sps_diagnostics d0, d1;
    int n, k;
    sps_world* w = spinning_disc(shear, rotation, 0, 0.01, &s, &n);
    ENSURE(w);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d0) == SPS_OK);
    for (k = 0; k < 20; ++k) ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d1) == SPS_OK);
    ENSURE(s.omega * d1.time > 0.45); /* turned about half a radian */
    *dev = rigid_deviation(w, n, &s, 1) / (s.omega * 0.1);
    *dl = fabs(d1.angular_momentum[2] / d0.angular_momentum[2] - 1);
    sps_world_destroy(w);
    return 0;
}

/* With SPS_ROTATION_PAIR every ENO increment stays a force along its own pair's current e_ij:
   all forces are central and antisymmetric, so the angular momentum is kept to round-off through
   the breathing and the ~20 list rebuilds (1000 sub-steps x 314 particles of ~1e-16 relative
   error each, summed with random signs: ~1e-13; tolerance 1e-11). A pair force lost or given to
   the wrong pair at a rebuild breaks the antisymmetry and shows here. */
static int test_spinning_disc_stays_rigid(void) {
    double dev_a, dl_a, dev_e, dl_e, dev_p, dl_p;
    ENSURE(spin_for_half_radian(SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, &dev_a, &dl_a) == 0);
    ENSURE(spin_for_half_radian(SPS_SHEAR_ENO, SPS_ROTATION_MEAN, &dev_e, &dl_e) == 0);
    ENSURE(spin_for_half_radian(SPS_SHEAR_ENO_A, SPS_ROTATION_PAIR, &dev_p, &dl_p) == 0);
    printf("    after 0.5 rad: ENO-A |v - v_rigid| / (omega R) = %.2e, |dL/L| = %.2e;  ENO %.2e, %.2e (not asserted);  "
           "ENO-A pair %.2e, %.2e\n", dev_a, dl_a, dev_e, dl_e, dev_p, dl_p);
    ENSURE(dev_a < 1e-2); /* breathing under the missing centripetal stress, see above */
    ENSURE(dl_a < 1e-3);  /* follows the strain ~1e-4, see above */
    ENSURE(dev_p < 1e-2); /* the same breathing */
    ENSURE(dl_p < 1e-11); /* round-off, see above */
    return 0;
}

/* Galilean invariance of the time steps: the spinning disc (rim at 0.05 c0, GNO-A) carried
   along at u = c0 (28.9 m/s, travelling 58 radii in 0.2 s) takes exactly the acoustic and
   advection steps it takes at rest, since both criteria measure speeds in the body's frame, and
   its particles move by u t relative to the resting run, to round-off (positions of ~20 m
   carry ~4e-15 relative error per step, 2e3 steps: tolerance 1e-9 m, 1e-8 R). Criteria on the
   absolute speed (1.05 c0 instead of 0.05 c0) would take twice the acoustic steps, and an
   escape guard around the initial positions would stop the disc after 10 disc sizes. */
typedef struct { spin_field spin; double u; } carried_spin;
static void carried_spin_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const carried_spin* c = (const carried_spin*)user;
    spin_velocity(x, v, (void*)&c->spin);
    v[0] += (sps_real)c->u;
}
static int test_translation_keeps_steps(void) {
    sps_world* w[2];
    sps_diagnostics d[2];
    carried_spin cs[2];
    double worst = 0, t_end = 0.2;
    int k, n, id;
    for (k = 0; k < 2; ++k) {
        ENSURE((w[k] = spinning_disc(SPS_SHEAR_GNO_A, SPS_ROTATION_MEAN, 0, 0.05, &cs[k].spin, &n)) != NULL);
        cs[k].u = k * cs[k].spin.omega * 0.1 / 0.05; /* c0 = omega R / 0.05 */
        for (id = 0; id < n; ++id) { /* the disc's particles, carried along */
            sps_particle_state p;
            sps_real v[3];
            ENSURE(sps_world_particle(w[k], id, &p) == SPS_OK);
            carried_spin_velocity(p.position, v, &cs[k]);
            ENSURE(sps_world_set_particle(w[k], id, NULL, v) == SPS_OK);
        }
        ENSURE(sps_world_advance(w[k], t_end, NULL, NULL) == SPS_OK);
        ENSURE(sps_world_diagnostics(w[k], ALL_BODIES, &d[k]) == SPS_OK);
    }
    for (id = 0; id < n; ++id) {
        sps_particle_state a, b;
        ENSURE(sps_world_particle(w[0], id, &a) == SPS_OK && sps_world_particle(w[1], id, &b) == SPS_OK);
        worst = fmax(worst, hypot(b.position[0] - cs[1].u * t_end - a.position[0], b.position[1] - a.position[1]));
    }
    printf("    at rest: %ld acoustic, %ld advection steps; carried at %.1f m/s: %ld, %ld; largest |x - u t - x_rest| %.2e m\n",
           d[0].acoustic_steps, d[0].advection_steps, cs[1].u, d[1].acoustic_steps, d[1].advection_steps, worst);
    ENSURE(d[1].acoustic_steps == d[0].acoustic_steps && d[1].advection_steps == d[0].advection_steps);
    ENSURE(worst < 1e-9); /* round-off, see above */
    sps_world_destroy(w[0]);
    sps_world_destroy(w[1]);
    return 0;
}

/* ============================================================================================ */
/* >>momentum                                                                                   */

static void random_velocity(const sps_real x[3], sps_real v[3], void* user) {
    unsigned long long* seed = (unsigned long long*)user;
    (void)x;
    v[0] = 0.3 * rnd(seed); /* about 1% of c0 = 28.9 m/s */
    v[1] = 0.3 * rnd(seed);
    v[2] = 0.3 * rnd(seed);
}

/* Relative change of the linear momentum of a free 2D block with random velocities after 1000
   acoustic sub-steps: |P(t) - P(0)| / sum_i m_i |v_i(0)|. */
static int momentum_drift(sps_shear shear, sps_rotation rotation, double* rel) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.2, 0};
    unsigned long long seed = 2024;
    sps_diagnostics d0, d1;
    double norm = 0;
    int n, id;
    ENSURE(w);
    bd.shear = shear;
    bd.rotation = rotation;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK);
    ENSURE(sps_body_add_box(w, b, lo, hi, &n) == SPS_OK);
    ENSURE(sps_body_set_velocity(w, b, random_velocity, &seed) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d0) == SPS_OK);
    for (id = 0; id < n; ++id) {
        sps_particle_state s;
        sps_world_particle(w, id, &s);
        norm += 1000 * 1e-4 * hypot(s.velocity[0], s.velocity[1]); /* m = rho0 dp^2 */
    }
    ENSURE(step_acoustic(w, 1000) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d1) == SPS_OK);
    *rel = hypot(d1.linear_momentum[0] - d0.linear_momentum[0], d1.linear_momentum[1] - d0.linear_momentum[1]) / norm;
    /* and the run is stable: the Riemann dissipation makes the energy decay (to 0.2% here). An
       unstable step would make it grow: measured x25 (ENO-A) and x60 (ENO) at cfl_acoustic = 0.6,
       x5e5 at 1, every step returning SPS_OK since the state stays finite. */
    ENSURE(d1.kinetic_energy + d1.strain_energy < d0.kinetic_energy + d0.strain_energy);
    sps_world_destroy(w);
    return 0;
}

/* Every pair force of the pressure pass and every ENO increment is antisymmetric in (i, j)
   (test_gradient_antisymmetry), so sum_i m_i v_i changes only by round-off. ENO-A with the mean
   rotation rotates every a_s by the same matrix, which keeps sum_i m_i a_s_i = 0 (ANG eq. 42).
   Tolerance 1e-12: 1000 sub-steps x 400 particles of round-off ~1e-16 each, summed with random
   signs (sqrt(4e5) ~ 600 x 1e-16). Per-particle rotation does not conserve it: printed only. */
static int test_momentum_conservation(void) {
    double eno, eno_a, eno_a_pp, eno_a_pair, gno_a_pair;
    ENSURE(momentum_drift(SPS_SHEAR_ENO, SPS_ROTATION_MEAN, &eno) == 0);
    ENSURE(momentum_drift(SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, &eno_a) == 0);
    ENSURE(momentum_drift(SPS_SHEAR_ENO_A, SPS_ROTATION_PER_PARTICLE, &eno_a_pp) == 0);
    ENSURE(momentum_drift(SPS_SHEAR_ENO_A, SPS_ROTATION_PAIR, &eno_a_pair) == 0);
    ENSURE(momentum_drift(SPS_SHEAR_GNO_A, SPS_ROTATION_PAIR, &gno_a_pair) == 0);
    printf("    |dP| / sum m|v|: ENO %.2e, ENO-A mean %.2e, ENO-A per particle %.2e (not asserted), ENO-A pair %.2e, GNO-A pair %.2e\n",
           eno, eno_a, eno_a_pp, eno_a_pair, gno_a_pair);
    ENSURE(eno < 1e-12);        /* round-off, see above */
    ENSURE(eno_a < 1e-12);      /* round-off, see above */
    ENSURE(eno_a_pair < 1e-12); /* g_ij = g_ji bit for bit: antisymmetric pair forces, round-off as above */
    ENSURE(gno_a_pair < 1e-12); /* the same for the penalty (and the stress divergence is antisymmetric) */
    return 0;
}

/* ============================================================================================ */
/* >>cases: the two plates of examples/plate2d.c and examples/plate3d.c, built by their scenes  */

#include "../examples/scenes/plate2d.h"
#include "../examples/scenes/plate3d.h"

/* The 2D cantilever of examples/scenes/plate2d.h: L x H plate (rho0 1000, E 2e6, nu 0.3975)
   with a clamped holder of 4 dp, first-mode start with v_f, observer at the free end (L, 0). */
static sps_world* plate2d_build(int res, sps_shear shear, sps_rotation rotation, double vf, int threads, sps_observer* tip) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    plate2d_params p = {res, vf, 0, 0};
    sps_world* w;
    sps_body plate;
    wd.threads = threads; wd.log = quiet_log;
    /* default (recomputed) pair geometry, as the example */
    bd.material.density = PLATE2D_RHO0;
    bd.material.youngs_modulus = PLATE2D_E;
    bd.material.poisson_ratio = PLATE2D_NU;
    bd.shear = shear;
    bd.rotation = rotation;
    bd.track_stress = 1;
    return plate2d_create(wd, &bd, &p, &w, &plate, tip) == SPS_OK ? w : NULL;
}

/* The cantilever of plate2d_build at rest (v_f = 0), damping c [1/s], loaded downwards by g
   through the world's gravity, or, with load non-NULL, by that acceleration callback instead. */
static sps_world* plate2d_loaded(int res, double c, double g, sps_acceleration_fn load, void* user, int threads, sps_observer* tip) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    plate2d_params p = {res, 0, 0, 0};
    sps_world* w;
    sps_body plate;
    wd.threads = threads; wd.log = quiet_log;
    if (!load) wd.gravity[1] = (sps_real)-g;
    bd.material.density = PLATE2D_RHO0;
    bd.material.youngs_modulus = PLATE2D_E;
    bd.material.poisson_ratio = PLATE2D_NU;
    bd.damping = (sps_real)c;
    if (plate2d_create(wd, &bd, &p, &w, &plate, tip) != SPS_OK) return NULL;
    if (load && sps_body_set_acceleration(w, plate, load, user) != SPS_OK) { sps_world_destroy(w); return NULL; }
    return w;
}

/* The simply supported 3D plate of examples/scenes/plate3d.h: L x W x H (rho0 1000, E 1e8,
   nu 0.3), v_z held at 0 on the mid-plane particles of the four sides (examples/plate3d.c
   --support edge, ENO 6.2's wording), mode (m, n) start, observer at the first antinode
   (L/2m, W/2n, 0). */
static sps_world* plate3d_build(int res, plate3d_mode md, int threads, sps_observer* obs) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    plate3d_params p = {res, md, PLATE3D_SUPPORT_EDGE, 0, 0};
    sps_world* w;
    sps_body plate;
    wd.threads = threads; wd.log = quiet_log;
    /* stored pair geometry: half the cost; the first period is the same to 0.1 % at H/dp = 3
       (0.0158 s both ways, measured); only long runs drift with it (bench/VALIDATION.md, design notes) */
    wd.frozen_geometry = 1;
    bd.material.density = PLATE3D_RHO0;
    bd.material.youngs_modulus = PLATE3D_E;
    bd.material.poisson_ratio = PLATE3D_NU;
    bd.shear = SPS_SHEAR_ENO_A;
    bd.track_stress = 1;
    return plate3d_create(wd, &bd, &p, &w, &plate, obs) == SPS_OK ? w : NULL;
}

/* First period from the zero crossings of a signal that starts at 0 (as examples/common.h):
   crossings by linear interpolation between samples; the period is the second crossing. */
typedef struct {
    sps_observer obs;
    int axis, n;
    double t_prev, s_prev, crossing[2];
} period_probe;
static int period_on_step(sps_world* w, void* user) {
    period_probe* p = (period_probe*)user;
    sps_real u[3];
    double t = sps_world_time(w), s;
    sps_observer_read(w, p->obs, u, NULL);
    s = u[p->axis];
    if (p->t_prev > 0 && p->n < 2 && ((p->s_prev < 0 && s >= 0) || (p->s_prev > 0 && s <= 0)))
        p->crossing[p->n++] = p->t_prev + (t - p->t_prev) * p->s_prev / (p->s_prev - s);
    p->t_prev = t;
    p->s_prev = s;
    return p->n >= 2; /* stop at the second crossing */
}

/* ============================================================================================ */
/* >>determinism                                                                                */

/* Positions and velocities (6 reals per particle) in stable-id order. Caller frees. */
static double* snapshot(const sps_world* w) {
    int n = sps_world_particle_count(w), id, a;
    double* s = (double*)malloc(sizeof(double) * 6 * (size_t)(n ? n : 1));
    if (!s) return NULL;
    for (id = 0; id < n; ++id) {
        sps_particle_state ps;
        sps_world_particle(w, id, &ps);
        for (a = 0; a < 3; ++a) { s[6 * id + a] = ps.position[a]; s[6 * id + 3 + a] = ps.velocity[a]; }
    }
    return s;
}

/* 2D: the cantilever at H/dp = 8 (672 particles, above the 512 where the step goes parallel),
   30 advection steps (~300 sub-steps, neighbour lists rebuilt and re-sorted 30 times), the
   default pair geometry (recomputed in every sub-step) as in examples/plate2d.c. */
static double* run_plate2d_rotation(int threads, int* n, sps_rotation rotation) {
    sps_observer tip;
    sps_world* w = plate2d_build(8, SPS_SHEAR_ENO_A, rotation, 0.05, threads, &tip);
    double* s = NULL;
    int k;
    if (!w) return NULL;
    for (k = 0; k < 30; ++k)
        if (sps_world_step(w) != SPS_OK) { sps_world_destroy(w); return NULL; }
    *n = sps_world_particle_count(w);
    s = snapshot(w);
    sps_world_destroy(w);
    return s;
}

static double* run_plate2d_small(int threads, int* n) { return run_plate2d_rotation(threads, n, SPS_ROTATION_MEAN); }
/* ... with the pair forces of SPS_ROTATION_PAIR (carried over the list rebuilds by id) */
static double* run_plate2d_pair_small(int threads, int* n) { return run_plate2d_rotation(threads, n, SPS_ROTATION_PAIR); }

/* Takes `steps` advection steps of w, then returns its state (snapshot) and destroys it; NULL if
   a step failed. */
static double* steps_then_snapshot(sps_world* w, int steps) {
    double* s = NULL;
    int k;
    for (k = 0; k < steps; ++k)
        if (sps_world_step(w) != SPS_OK) { sps_world_destroy(w); return NULL; }
    s = snapshot(w);
    sps_world_destroy(w);
    return s;
}

/* A load that depends on every argument of the callback: the reference position (heavier
   towards the tip), the current position, the velocity (a drag) and the time. */
static void varied_load(const sps_real x[3], const sps_real x0[3], const sps_real v[3], sps_real t, sps_real a[3], void* user) {
    (void)user;
    a[0] = (sps_real)(0.1 * (x[1] - x0[1]));
    a[1] = (sps_real)(-(1 + 10 * x0[0]) * (1 + t) - 0.1 * v[1]);
}
/* ... the cantilever at H/dp = 8, damped (c = 50/s) and under varied_load (both threads call it
   at once), 4 advection steps: starting at rest, each holds max_substeps (100) sub-steps, so
   about as many as the plate's 30 above */
static double* run_plate2d_loaded_small(int threads, int* n) {
    sps_observer tip;
    sps_world* w = plate2d_loaded(8, 50, 0, varied_load, NULL, threads, &tip);
    if (!w) return NULL;
    *n = sps_world_particle_count(w);
    return steps_then_snapshot(w, 4);
}

/* 3D: a free 9^3 block (729 particles) with random velocities, ENO-A mean rotation (lane-group
   sums), the default pair geometry (recomputed in every sub-step). */
static double* run_block3d_small(int threads, int* n) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w;
    sps_body b;
    unsigned long long seed = 99;
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.09, 0.09, 0.09};
    wd.dim = 3; wd.threads = threads; wd.log = quiet_log;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, n);
    if (!b.id || sps_body_set_velocity(w, b, random_velocity, &seed) != SPS_OK) { sps_world_destroy(w); return NULL; }
    return steps_then_snapshot(w, 10);
}

/* 2D: a free ENO-A block (40 x 20 particles, mean rotation) with random velocities and a row of
   40 stray particles 20 dp above it, 4 dp apart: they have no neighbours and sort last, so the
   body's last lane groups have no slots while their particles still add to the mean rotation.
   The threads split the body by slots, so those groups fall to the last thread. */
static double* run_block_with_strays(int threads, int* n) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w;
    sps_body b;
    unsigned long long seed = 7;
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.1, 0};
    sps_real strays[3 * 40];
    int k, added = 0;
    for (k = 0; k < 40; ++k) {
        strays[3 * k] = (sps_real)(0.0025 + 0.02 * k);
        strays[3 * k + 1] = (sps_real)0.2;
        strays[3 * k + 2] = 0;
    }
    wd.dim = 2; wd.dp = 0.005; wd.threads = threads; wd.log = quiet_log;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, &added);
    if (!b.id || sps_body_add_particles(w, b, 40, strays, NULL) != SPS_OK ||
        sps_body_set_velocity(w, b, random_velocity, &seed) != SPS_OK) {
        sps_world_destroy(w);
        return NULL;
    }
    *n = added + 40;
    return steps_then_snapshot(w, 10);
}

/* A smooth velocity field scaled by *(const double*)user. */
static void swirl_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const double scale = *(const double*)user;
    v[0] = (sps_real)(scale * sin(20 * x[0] + 3 * x[1]));
    v[1] = (sps_real)(scale * cos(17 * x[1] - 5 * x[0]));
    v[2] = 0;
}

/* 2D ENO-A blocks A (23 x 25 = 575 particles) and, with two_bodies, B (17 x 31 = 527) one dp to
   the right of A, well inside the kernel support of A's edge, and slower, so the global time
   step stays A's. Neither count is a multiple of the 8 lanes. 12 advection steps, B added
   before step add_step; returns A's state (ids 0 .. 574). */
static double* run_two_blocks(int threads, int two_bodies, double speed_b, sps_rotation rotation, int add_step) {
    static const double lo_a[3] = {0, 0, 0}, hi_a[3] = {0.23, 0.25, 0}, lo_b[3] = {0.24, 0, 0}, hi_b[3] = {0.41, 0.31, 0};
    const double speed_a = 1;
    sps_world* w = new_world(2, 0.01);
    sps_body a, b;
    double* s = NULL;
    int k, n;
    if (!w) return NULL;
    w->threads = threads;
    a = add_block_rotation(w, SPS_SHEAR_ENO_A, rotation, lo_a, hi_a, &n);
    if (!a.id || n != 575 || sps_body_set_velocity(w, a, swirl_velocity, (void*)&speed_a) != SPS_OK) goto done;
    for (k = 0; k < 12; ++k) {
        if (two_bodies && k == add_step) {
            b = add_block_rotation(w, SPS_SHEAR_ENO_A, rotation, lo_b, hi_b, &n);
            if (!b.id || n != 527 || sps_body_set_velocity(w, b, swirl_velocity, (void*)&speed_b) != SPS_OK) goto done;
            if (sps_world_set_contact(w, a, b, 0) != SPS_OK) goto done; /* one dp apart: they would touch */
        }
        if (sps_world_step(w) != SPS_OK) goto done;
    }
    s = snapshot(w);
done:
    sps_world_destroy(w);
    return s;
}

/* Bodies that do not touch (sps_world_set_contact) do not interact (neighbour lists are per body) and each body's
   sums (the mean rotation of ENO-A, per lane group) are its own: body A evolves bit for bit the
   same alone and beside body B one dp away, and the two-body world is the same with 1 and 2
   threads. The comparison is sharp: a faster B (a smaller global time step) changes A. */
static int test_bodies_independent(void) {
    double *alone = run_two_blocks(1, 0, 0, SPS_ROTATION_MEAN, 0), *pair1 = run_two_blocks(1, 1, 0.3, SPS_ROTATION_MEAN, 0);
    double *pair2 = run_two_blocks(2, 1, 0.3, SPS_ROTATION_MEAN, 0), *fast_b = run_two_blocks(1, 1, 3, SPS_ROTATION_MEAN, 0);
    int same_alone, same_threads, fast_differs;
    ENSURE(alone && pair1 && pair2 && fast_b);
    same_alone = memcmp(alone, pair1, sizeof(double) * 6 * 575) == 0;
    same_threads = memcmp(pair1, pair2, sizeof(double) * 6 * 575) == 0;
    fast_differs = memcmp(alone, fast_b, sizeof(double) * 6 * 575) != 0;
    free(alone); free(pair1); free(pair2); free(fast_b);
    ENSURE(same_alone);
    ENSURE(same_threads);
    ENSURE(fast_differs);
    return 0;
}

/* SPS_ROTATION_PAIR: adding a body between steps re-sorts the particles by body and grows the
   neighbour storage, and the pair forces of the bodies already there must come through that
   unchanged: a swirling ENO-A block evolves bit for bit the same whether a second block (at
   rest, so the time steps stay the same) is added after 4 of its 12 steps or never. */
static int test_pair_forces_survive_adds(void) {
    double *alone = run_two_blocks(1, 0, 0, SPS_ROTATION_PAIR, 0), *added = run_two_blocks(1, 1, 0, SPS_ROTATION_PAIR, 4);
    int same;
    ENSURE(alone && added);
    same = memcmp(alone, added, sizeof(double) * 6 * 575) == 0; /* body A: ids 0..574 */
    free(alone); free(added);
    ENSURE(same);
    return 0;
}

/* Every pass is a gather and every sum uses fixed blocks, so 1 and 2 threads must give
   bit-identical states (memcmp, no tolerance), and so must two runs with 2 threads. */
static int test_determinism_threads(void) {
    double* (*runs[5])(int, int*) = {run_plate2d_small, run_block3d_small, run_plate2d_pair_small, run_block_with_strays,
                                     run_plate2d_loaded_small};
    int k;
    for (k = 0; k < 5; ++k) {
        int n1 = 0, n2 = 0, n3 = 0, same12, same23;
        double *s1 = runs[k](1, &n1), *s2 = runs[k](2, &n2), *s3 = runs[k](2, &n3);
        ENSURE(s1 && s2 && s3);
        ENSURE(n1 > 512 && n1 == n2 && n2 == n3);
        same12 = memcmp(s1, s2, sizeof(double) * 6 * (size_t)n1) == 0;
        same23 = memcmp(s2, s3, sizeof(double) * 6 * (size_t)n1) == 0;
        free(s1); free(s2); free(s3);
        ENSURE(same12); /* 1 thread vs 2 threads */
        ENSURE(same23); /* 2 threads, twice */
    }
    return 0;
}

/* ============================================================================================ */
/* >>validation                                                                                 */

/* One broken world def field: sps_world_def_check and sps_world_create reject it, the message
   names the field and the value (needle), create leaves *out NULL and logs the message. */
static int rejects_world_def(const sps_world_def* def, const char* needle) {
    char msg[1024];
    sps_world* w = (sps_world*)&msg; /* must be overwritten with NULL */
    int logged;
    ENSURE(sps_world_def_check(def, msg, sizeof msg) == SPS_ERR_INVALID_ARG);
    if (!strstr(msg, needle)) printf("    message '%s' lacks '%s'\n", msg, needle);
    ENSURE(strstr(msg, needle) != NULL);
    logged = g_log_count;
    g_log_last[0] = 0;
    ENSURE(sps_world_create(def, &w) == SPS_ERR_INVALID_ARG);
    ENSURE(w == NULL);
    ENSURE(g_log_count == logged + 1); /* one message to the def's log callback */
    ENSURE(strstr(g_log_last, needle) != NULL);
    return 0;
}

static int test_validation_world_def(void) {
    sps_world_def d = sps_default_world_def(), bad;
    char msg[1024];
    d.log = quiet_log;
    ENSURE(sps_world_def_check(&d, msg, sizeof msg) == SPS_OK && msg[0] == 0);
    bad = d; bad.dim = 4;                 ENSURE(rejects_world_def(&bad, "dim = 4") == 0);
    bad = d; bad.dp = 0;                  ENSURE(rejects_world_def(&bad, "dp = 0") == 0);
    bad = d; bad.dp = -0.5;               ENSURE(rejects_world_def(&bad, "dp = -0.5") == 0);
    bad = d; bad.dp = NAN;                ENSURE(rejects_world_def(&bad, "nan") == 0);
    bad = d; bad.dp = NAN;                ENSURE(rejects_world_def(&bad, "dp = ") == 0);
    bad = d; bad.h_over_dp = 10;          ENSURE(rejects_world_def(&bad, "h_over_dp = 10") == 0);
    bad = d; bad.cfl_acoustic = 0;        ENSURE(rejects_world_def(&bad, "cfl_acoustic = 0") == 0);
    bad = d; bad.cfl_acoustic = 1.5;      ENSURE(rejects_world_def(&bad, "cfl_acoustic = 1.5") == 0);
    bad = d; bad.cfl_advection = -0.2;    ENSURE(rejects_world_def(&bad, "cfl_advection = -0.2") == 0);
    bad = d; bad.max_substeps = 0;        ENSURE(rejects_world_def(&bad, "max_substeps = 0") == 0);
    bad = d; bad.max_substeps = 10001;    ENSURE(rejects_world_def(&bad, "max_substeps = 10001, allowed [1, 10000]") == 0);
    bad = d; bad.neighbor_capacity = 0.5; ENSURE(rejects_world_def(&bad, "neighbor_capacity = 0.5") == 0);
    bad = d; bad.threads = -1;            ENSURE(rejects_world_def(&bad, "threads = -1") == 0);
    bad = d; bad.gravity[1] = INFINITY;   ENSURE(rejects_world_def(&bad, "gravity") == 0);
    bad = d; bad.kernel = (sps_kernel_type)5; ENSURE(rejects_world_def(&bad, "kernel = 5") == 0);
    bad = d; bad.dp = 1e-10;              ENSURE(rejects_world_def(&bad, "dp = 1e-10, allowed [1e-9, 1e9]") == 0);
    bad = d; bad.dp = 1e10;               ENSURE(rejects_world_def(&bad, "dp = 1e+10") == 0);
    bad = d; bad.dp = INFINITY;           ENSURE(rejects_world_def(&bad, "dp = inf") == 0);
    bad = d; bad.h_over_dp = 0.9;         ENSURE(rejects_world_def(&bad, "h_over_dp = 0.9, allowed [1, 3]") == 0);
    bad = d; bad.h_over_dp = NAN;         ENSURE(rejects_world_def(&bad, "h_over_dp = nan") == 0);
    bad = d; bad.stepping = (sps_stepping)2; ENSURE(rejects_world_def(&bad, "stepping = 2") == 0);
    bad = d; bad.cfl_acoustic = NAN;      ENSURE(rejects_world_def(&bad, "cfl_acoustic = nan") == 0);
    bad = d; bad.cfl_advection = 1.01;    ENSURE(rejects_world_def(&bad, "cfl_advection = 1.01") == 0);
    bad = d; bad.gravity[2] = NAN;        ENSURE(rejects_world_def(&bad, "gravity = (0, 0, nan)") == 0);
    bad = d; bad.frozen_geometry = 2;     ENSURE(rejects_world_def(&bad, "frozen_geometry = 2") == 0);
    bad = d; bad.neighbor_capacity = 65;  ENSURE(rejects_world_def(&bad, "neighbor_capacity = 65") == 0);
    bad = d; bad.neighbor_capacity = NAN; ENSURE(rejects_world_def(&bad, "neighbor_capacity = nan") == 0);
    bad = d; bad.threads = 1025;          ENSURE(rejects_world_def(&bad, "threads = 1025") == 0);
    bad = d; bad.escape_distance = -1;    ENSURE(rejects_world_def(&bad, "escape_distance = -1") == 0);
    bad = d; bad.escape_distance = NAN;   ENSURE(rejects_world_def(&bad, "escape_distance = nan") == 0);
    bad = d; bad.keep_last_good_state = 2; ENSURE(rejects_world_def(&bad, "keep_last_good_state = 2") == 0);
    bad = d; bad.allocator.alloc = counting_alloc; ENSURE(rejects_world_def(&bad, "allocator") == 0);
    bad = d; bad.escape_distance = INFINITY; /* allowed: no escape check */
    ENSURE(sps_world_def_check(&bad, msg, sizeof msg) == SPS_OK);
    /* every broken rule is listed, not just the first */
    bad = d; bad.dim = 1; bad.cfl_acoustic = 2;
    ENSURE(sps_world_def_check(&bad, msg, sizeof msg) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(msg, "dim = 1") && strstr(msg, "cfl_acoustic = 2"));
    /* a message buffer of size 0 is not touched (nor read); NULL is allowed */
    strcpy(msg, "untouched");
    ENSURE(sps_world_def_check(&bad, msg, 0) == SPS_ERR_INVALID_ARG && strcmp(msg, "untouched") == 0);
    ENSURE(sps_world_def_check(&bad, NULL, 100) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_world_def_check(NULL, msg, sizeof msg) == SPS_ERR_INVALID_ARG && strstr(msg, "world def is NULL"));
    return 0;
}

/* A def that did not come from sps_default_world_def() (zero-initialised) is caught by the
   cookie, for worlds and for bodies. */
static int test_validation_zero_def(void) {
    sps_world_def wd;
    sps_body_def bd;
    sps_world* w;
    sps_body b = {123};
    memset(&wd, 0, sizeof wd);
    wd.log = quiet_log;
    ENSURE(rejects_world_def(&wd, "sps_default_world_def") == 0);
    ENSURE((w = new_world(2, 0.01)) != NULL);
    memset(&bd, 0, sizeof bd);
    bd.material = sps_default_material_def();
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG);
    ENSURE(b.id == 0);
    ENSURE(strstr(sps_world_last_error(w), "sps_default_body_def") != NULL);
    sps_world_destroy(w);
    return 0;
}

/* One broken body def field: sps_world_add_body rejects it, names field and value in the
   world's last error and in the log, and returns the invalid handle 0. */
static int rejects_body_def(sps_world* w, const sps_body_def* def, const char* needle) {
    sps_body b = {77};
    g_log_last[0] = 0;
    ENSURE(sps_world_add_body(w, def, &b) == SPS_ERR_INVALID_ARG);
    ENSURE(b.id == 0 && !sps_body_is_valid(w, b));
    if (!strstr(sps_world_last_error(w), needle)) printf("    message '%s' lacks '%s'\n", sps_world_last_error(w), needle);
    ENSURE(strstr(sps_world_last_error(w), needle) != NULL);
    ENSURE(strstr(g_log_last, needle) != NULL);
    return 0;
}

static int test_validation_body_def(void) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def d = sps_default_body_def(), bad;
    ENSURE(w);
    bad = d; bad.material.poisson_ratio = 0.5;   ENSURE(rejects_body_def(w, &bad, "material.poisson_ratio = 0.5") == 0);
    bad = d; bad.material.poisson_ratio = 0.7;   ENSURE(rejects_body_def(w, &bad, "material.poisson_ratio = 0.7") == 0);
    bad = d; bad.material.youngs_modulus = 0;    ENSURE(rejects_body_def(w, &bad, "material.youngs_modulus = 0") == 0);
    bad = d; bad.material.youngs_modulus = -1e6; ENSURE(rejects_body_def(w, &bad, "material.youngs_modulus = -1e+06") == 0);
    bad = d; bad.material.density = 0;           ENSURE(rejects_body_def(w, &bad, "material.density = 0") == 0);
    bad = d; bad.material.density = -1000;       ENSURE(rejects_body_def(w, &bad, "material.density = -1000") == 0);
    bad = d; bad.material.density = NAN;         ENSURE(rejects_body_def(w, &bad, "material.density = ") == 0);
    bad = d; bad.shear = (sps_shear)99;          ENSURE(rejects_body_def(w, &bad, "shear = 99") == 0);
    bad = d; bad.zeta = -1;                      ENSURE(rejects_body_def(w, &bad, "zeta = -1") == 0);
    bad = d; bad.zeta = NAN;                     ENSURE(rejects_body_def(w, &bad, "zeta = nan") == 0);
    bad = d; bad.material.poisson_ratio = -1;    ENSURE(rejects_body_def(w, &bad, "material.poisson_ratio = -1") == 0);
    bad = d; bad.material.poisson_ratio = NAN;   ENSURE(rejects_body_def(w, &bad, "material.poisson_ratio = nan") == 0);
    bad = d; bad.material.youngs_modulus = NAN;  ENSURE(rejects_body_def(w, &bad, "material.youngs_modulus = nan") == 0);
    bad = d; bad.material.youngs_modulus = INFINITY; ENSURE(rejects_body_def(w, &bad, "material.youngs_modulus = inf") == 0);
    bad = d; bad.material.density = INFINITY;    ENSURE(rejects_body_def(w, &bad, "material.density = inf") == 0);
    bad = d; bad.xi = 101;                       ENSURE(rejects_body_def(w, &bad, "xi = 101") == 0);
    bad = d; bad.xi = NAN;                       ENSURE(rejects_body_def(w, &bad, "xi = nan") == 0);
    bad = d; bad.oas_epsilon = -0.1;             ENSURE(rejects_body_def(w, &bad, "oas_epsilon = -0.1") == 0);
    bad = d; bad.oas_exponent = 13;              ENSURE(rejects_body_def(w, &bad, "oas_exponent = 13") == 0);
    bad = d; bad.rotation = (sps_rotation)4;     ENSURE(rejects_body_def(w, &bad, "rotation = 4") == 0);
    bad = d; bad.track_stress = 2;               ENSURE(rejects_body_def(w, &bad, "track_stress = 2") == 0);
    bad = d; bad.damping = -1;                   ENSURE(rejects_body_def(w, &bad, "damping = -1, allowed finite >= 0") == 0);
    bad = d; bad.damping = NAN;                  ENSURE(rejects_body_def(w, &bad, "damping = nan") == 0);
    bad = d; bad.damping = INFINITY;             ENSURE(rejects_body_def(w, &bad, "damping = inf") == 0);
    bad = d; bad.damping = 1; bad.material.kind = SPS_MATERIAL_RIGID;
    ENSURE(rejects_body_def(w, &bad, "damping > 0 with material.kind = rigid") == 0);
    /* each field in range, but c0 = sqrt(K/rho0) underflows to 0 or overflows to inf */
    bad = d; bad.material.youngs_modulus = 1e-300; bad.material.density = 1e300;
    ENSURE(rejects_body_def(w, &bad, "sound speed c0 = 0") == 0);
    bad = d; bad.material.youngs_modulus = 1e300; bad.material.density = 1e-300;
    ENSURE(rejects_body_def(w, &bad, "sound speed c0 = inf") == 0);
    sps_world_destroy(w);
    w = new_world(3, 0.01); /* Gray's artificial stress is 2D only */
    ENSURE(w);
    bad = d; bad.shear = SPS_SHEAR_OAS;          ENSURE(rejects_body_def(w, &bad, "shear = OAS with dim = 3") == 0);
    sps_world_destroy(w);
    return 0;
}

/* Handles: a body handle of another world, the invalid handle 0 and bad boxes are rejected
   with a message, never used. */
static int test_validation_handles_and_args(void) {
    sps_world *w1 = new_world(2, 0.01), *w2 = new_world(2, 0.01);
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
    sps_real blo[3] = {0, 0, 0}, bhi[3] = {0.05, 0.05, 0}, bad_hi[3] = {-0.05, 0.05, 0};
    sps_body b1, none = {0};
    int added = -1;
    ENSURE(w1 && w2);
    b1 = add_block(w1, SPS_SHEAR_ENO_A, lo, hi, NULL);
    ENSURE(b1.id != 0 && sps_body_is_valid(w1, b1));
    ENSURE(!sps_body_is_valid(w2, b1) && sps_body_index(w2, b1) == -1);
    ENSURE(sps_body_add_box(w2, b1, blo, bhi, &added) == SPS_ERR_INVALID_ARG && added == 0);
    ENSURE(strstr(sps_world_last_error(w2), "not a body of this world") != NULL);
    ENSURE(sps_world_particle_count(w2) == 0);
    ENSURE(sps_body_add_box(w1, none, blo, bhi, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_body_add_box(w1, b1, blo, bad_hi, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w1), "box axis 0") != NULL);
    ENSURE(sps_world_advance(w1, NAN, NULL, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_world_particle(w1, sps_world_particle_count(w1), NULL) == SPS_ERR_INVALID_ARG);
    sps_world_destroy(w1);
    sps_world_destroy(w2);
    sps_world_destroy(NULL); /* allowed */
    return 0;
}

/* Stepping a world without particles is an error (SPS_ERR_STATE with a message), not a crash,
   with and without an (empty) body; diagnostics report the same error. Exposes a library bug:
   when no particle was ever added, the configuration update skips sps__commit (the function
   that reports "no particles") and sps__build_neighbors writes to the unallocated nb_start. */
static int test_step_empty_world(void) {
    sps_world* w = new_world(3, 0.01);
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    sps_diagnostics d;
    ENSURE(w);
    ENSURE(sps_world_step(w) == SPS_ERR_STATE);
    ENSURE(strlen(sps_world_last_error(w)) > 0);
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK);
    ENSURE(sps_world_step(w) == SPS_ERR_STATE);
    ENSURE(sps_world_advance(w, 1.0, NULL, NULL) == SPS_ERR_STATE);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d) != SPS_OK);
    ENSURE(sps_world_time(w) == 0);
    sps_world_destroy(w);
    return 0;
}

/* Result strings exist and differ; version macros agree with sps_version(). */
static int test_result_strings_and_version(void) {
    static const sps_result all[6] = {SPS_OK, SPS_ERR_INVALID_ARG, SPS_ERR_OUT_OF_MEMORY, SPS_ERR_UNSTABLE, SPS_ERR_IO, SPS_ERR_STATE};
    char v[32];
    int i, j;
    for (i = 0; i < 6; ++i)
        for (j = 0; j < i; ++j) ENSURE(strcmp(sps_result_string(all[i]), sps_result_string(all[j])) != 0);
    snprintf(v, sizeof v, "%d.%d.%d", SPHSOLID_VERSION_MAJOR, SPHSOLID_VERSION_MINOR, SPHSOLID_VERSION_PATCH);
    ENSURE(strcmp(v, sps_version()) == 0 && strcmp(v, SPHSOLID_VERSION_STRING) == 0);
    ENSURE(sps_is_double() == (sizeof(sps_real) == sizeof(double)));
    return 0;
}

/* ============================================================================================ */
/* >>handles: BUG exposure                                                                      */

/* An allocator that serves the next allocation from a given address (then malloc): lets us
   place two worlds exactly 512 KiB apart, as a pool allocator with 512 KiB blocks would. */
typedef struct { char* next; char *arena_lo, *arena_hi; } placing_allocator;
static void* placing_alloc(size_t size, void* user) {
    placing_allocator* p = (placing_allocator*)user;
    if (p->next) { void* q = p->next; p->next = NULL; return q; }
    return malloc(size);
}
static void placing_free(void* ptr, void* user) {
    placing_allocator* p = (placing_allocator*)user;
    if ((char*)ptr >= p->arena_lo && (char*)ptr < p->arena_hi) return; /* arena memory */
    free(ptr);
}

/* A body handle of one world must be rejected by another world whatever their addresses.
   The handle holds a 15-bit world tag computed from address bits 4..18 of the world
   (sps_world_create), so two worlds 2^19 bytes apart share the tag and accept each other's
   handles. (With malloc the same happens to a handle of a destroyed world when the next world
   reuses the address.) Exposes a library bug: fails with the current sphsolid.h. */
static int test_handle_foreign_world_same_tag(void) {
    const size_t apart = (size_t)1 << 19;
    char* arena = (char*)malloc(apart + (1 << 17));
    placing_allocator pa;
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world *w1 = NULL, *w2 = NULL;
    sps_body b1 = {0}, b2 = {0};
    int foreign_accepted;
    ENSURE(arena);
    pa.arena_lo = arena;
    pa.arena_hi = arena + apart + (1 << 17);
    wd.allocator.alloc = placing_alloc;
    wd.allocator.free = placing_free;
    wd.allocator.user = &pa;
    wd.log = quiet_log;
    pa.next = arena;
    ENSURE(sps_world_create(&wd, &w1) == SPS_OK && (char*)w1 == arena);
    pa.next = arena + apart;
    ENSURE(sps_world_create(&wd, &w2) == SPS_OK && (char*)w2 == arena + apart);
    ENSURE(sps_world_add_body(w1, &bd, &b1) == SPS_OK && sps_world_add_body(w2, &bd, &b2) == SPS_OK);
    foreign_accepted = sps_body_is_valid(w2, b1);
    if (foreign_accepted) printf("    BUG: world 2 accepts body handle %u of world 1 (same tag)\n", (unsigned)b1.id);
    sps_world_destroy(w1);
    sps_world_destroy(w2);
    free(arena);
    ENSURE(!foreign_accepted);
    return 0;
}

/* ============================================================================================ */
/* >>instability                                                                                */

/* A run that blows up is stopped with SPS_ERR_UNSTABLE and a message giving the time ("t =");
   the world stays readable: diagnostics, particle states and a VTK file still work.
   Scenario: zeta = 100 (ENO shear stiffness 2 zeta G ~ 30x the default) with cfl_acoustic = 1,
   far beyond the stability limit of the explicit step, from small random velocities: within
   two advection steps a density turns negative and the configuration update reports it. */
static int test_unstable_run_reported(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body b;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.2, 0};
    unsigned long long seed = 5;
    sps_diagnostics d;
    sps_particle_state ps;
    sps_result r = SPS_OK;
    char path[] = "/tmp/test_sphsolid_unstable_XXXXXX";
    int k, fd;
    wd.cfl_acoustic = 1; wd.threads = 1; wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.zeta = 100;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_set_velocity(w, b, random_velocity, &seed) == SPS_OK);
    for (k = 0; k < 100 && r == SPS_OK; ++k) r = sps_world_step(w);
    printf("    after %d steps: %s: %s\n", k, sps_result_string(r), sps_world_last_error(w));
    ENSURE(r == SPS_ERR_UNSTABLE);
    ENSURE(strstr(sps_world_last_error(w), "t = ") != NULL);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK && d.particles == 400);
    ENSURE(sps_world_particle(w, 0, &ps) == SPS_OK);
    ENSURE((fd = mkstemp(path)) >= 0);
    close(fd);
    ENSURE(sps_world_write_vtk(w, path) == SPS_OK);
    remove(path);
    ENSURE(sps_world_step(w) == SPS_ERR_UNSTABLE); /* stays stopped, no crash */
    sps_world_destroy(w);
    return 0;
}

static void huge_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)x; (void)user;
    v[0] = 1e200; /* finite, so sps_body_set_velocity accepts it; v^2 overflows to inf */
    v[1] = 0;
    v[2] = 0;
}

/* An absurd but finite initial velocity (1e200 m/s) must give an error (or at least progress),
   not a step that returns SPS_OK without advancing time: sps_world_advance() would then loop
   forever. Exposes a library bug: |v|^2 overflows, dt = 0 and sps_world_step() returns SPS_OK
   with t unchanged. */
static int test_unstable_huge_velocity(void) {
    sps_world* w = new_world(2, 0.01);
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0};
    sps_body b;
    sps_result r = SPS_OK;
    int k, stuck;
    ENSURE(w);
    b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, NULL);
    ENSURE(b.id != 0);
    ENSURE(sps_body_set_velocity(w, b, huge_velocity, NULL) == SPS_OK);
    for (k = 0; k < 3 && r == SPS_OK; ++k) r = sps_world_step(w);
    stuck = r == SPS_OK && sps_world_time(w) == 0;
    if (stuck) printf("    BUG: 3 steps returned SPS_OK, t = %g (no progress; sps_world_advance would hang)\n", sps_world_time(w));
    else printf("    %s: %s\n", sps_result_string(r), sps_world_last_error(w));
    sps_world_destroy(w);
    ENSURE(!stuck);
    ENSURE(r == SPS_ERR_UNSTABLE || r == SPS_OK); /* an instability, or a (finite) run */
    return 0;
}

/* ============================================================================================ */
/* >>memory                                                                                     */

static void runaway_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = x[0] > 1e11 ? 100 : 0; /* the far particle keeps flying */
    v[1] = v[2] = 0;
}

/* A 1024-particle block plus one particle 1e12 m away: the cell grid wraps (periodic hashing),
   so stepping works and memory stays bounded. Limit 64 MiB: the scene needs ~1 MiB (neighbour
   lists of 1025 x 41 slots, ~40 arrays of 1025 reals); a grid spanning the runaway would need
   (1e12 / 0.026)^2 cells. Also: once the first step has allocated, later steps never allocate
   (MEMORY in the doc block), and every byte is freed by sps_world_destroy. */
static int test_memory_runaway_particle(void) {
    counting_allocator ca = {0, 0, 0, 0, 0};
    sps_world_def wd = sps_default_world_def();
    sps_world* w;
    sps_body b;
    sps_particle_state ps;
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.32, 0.32, 0};
    sps_real far[3] = {1e12, 1e12, 0};
    long calls_after_first;
    int n, k;
    wd.threads = 1; wd.log = quiet_log;
    wd.allocator.alloc = counting_alloc; wd.allocator.free = counting_free; wd.allocator.user = &ca;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, &n);
    ENSURE(b.id != 0 && n == 1024);
    ENSURE(sps_body_add_particles(w, b, 1, far, NULL) == SPS_OK);
    ENSURE(sps_body_set_velocity(w, b, runaway_velocity, NULL) == SPS_OK);
    ENSURE(sps_world_step(w) == SPS_OK);
    calls_after_first = ca.calls;
    for (k = 0; k < 50; ++k) ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(ca.calls == calls_after_first); /* steps after the first never allocate */
    ENSURE(sps_world_particle(w, n, &ps) == SPS_OK);
    ENSURE(ps.position[0] > 1e12 && ps.velocity[0] == 100); /* it flew on, untouched */
    printf("    peak %.2f MiB, total %.2f MiB in %ld allocations\n", ca.peak / 1048576.0, ca.total / 1048576.0, ca.calls);
    ENSURE(ca.peak < ((size_t)64 << 20));  /* see above */
    ENSURE(ca.total < ((size_t)64 << 20)); /* see above */
    sps_world_destroy(w);
    ENSURE(ca.live == 0); /* everything freed */
    return 0;
}

/* ============================================================================================ */
/* >>reliability: arguments, guards, last good state, validation, memory                        */

/* The message of the world's last error, the log and the needle agree (the call reported it). */
static int error_names(const sps_world* w, const char* needle) {
    if (!strstr(sps_world_last_error(w), needle)) printf("    message '%s' lacks '%s'\n", sps_world_last_error(w), needle);
    ENSURE(strstr(sps_world_last_error(w), needle) != NULL);
    return 0;
}

/* NULL worlds never crash: fallible calls return SPS_ERR_INVALID_ARG, queries a neutral value. */
static int test_null_world_arguments(void) {
    sps_body b = {0x10001};
    sps_observer o = {0x10001};
    sps_body_def bd = sps_default_body_def();
    sps_world_def wd = sps_default_world_def();
    sps_real x[3] = {0, 0, 0}, c0;
    sps_diagnostics d;
    sps_particle_state ps;
    char msg[256];
    int added = -1, count = -1;
    memset(&d, 0, sizeof d);
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, NULL) == SPS_ERR_INVALID_ARG && strstr(g_log_last, "out must not be NULL"));
    ENSURE(sps_world_add_body(NULL, &bd, &b) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_body_add_box(NULL, b, x, x, &added) == SPS_ERR_INVALID_ARG && added == 0);
    ENSURE(sps_body_add_sdf(NULL, b, x, x, NULL, NULL, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_body_add_particles(NULL, b, 1, x, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_body_set_velocity(NULL, b, random_velocity, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_body_constrain_box(NULL, b, x, x, SPS_AXIS_ALL, NULL, &count) == SPS_ERR_INVALID_ARG && count == 0);
    ENSURE(sps_body_material_constants(NULL, b, &c0, NULL, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_world_add_observer(NULL, b, x, &o) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_observer_read(NULL, o, x, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_world_step(NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_world_advance(NULL, 1, NULL, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_world_diagnostics(NULL, b, &d) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_world_particle(NULL, 0, &ps) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_world_write_vtk(NULL, "/tmp/x.vtk") == SPS_ERR_INVALID_ARG);
    ENSURE(sps_world_validate(NULL, msg, sizeof msg) == SPS_ERR_INVALID_ARG && strstr(msg, "world is NULL"));
    ENSURE(sps_world_get_def(NULL) == NULL && sps_world_time(NULL) == 0 && sps_world_particle_count(NULL) == 0);
    ENSURE(sps_world_field(NULL, SPS_FIELD_DENSITY) == NULL && sps_world_particle_ids(NULL) == NULL);
    ENSURE(sps_world_nearest_particle(NULL, b, x) == -1 && !sps_body_is_valid(NULL, b) && sps_body_index(NULL, b) == -1);
    ENSURE(sps_world_kernel(NULL, 0) == 0 && sps_world_kernel_derivative(NULL, 0) == 0);
    ENSURE(strncmp(sps_world_last_error(NULL), "world is NULL", 13) == 0 && strstr(sps_world_last_error(NULL), "sps_world_def_check"));
    ENSURE(sps_diagnostics_csv_row(NULL, msg, sizeof msg) == -1 && sps_diagnostics_csv_row(&d, NULL, 10) == -1);
    return 0;
}

/* With a world, every NULL pointer and out-of-range argument is an error whose message names
   the argument, its value and what is allowed. */
static int test_bad_arguments_named(void) {
    sps_world* w = new_world(2, 0.01);
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
    sps_real x[3] = {0.01, 0.01, 0}, nan3[3] = {NAN, 0, 0}, big[3] = {0, 0, 0};
    sps_body b, none = {0}, b2;
    sps_observer o;
    sps_particle_state ps;
    ENSURE(w);
    b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, NULL);
    ENSURE(b.id);
    ENSURE(sps_world_add_body(w, NULL, &b2) == SPS_ERR_INVALID_ARG && error_names(w, "def and out must not be NULL") == 0);
    ENSURE(sps_body_add_box(w, b, NULL, x, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "lo and hi must not be NULL") == 0);
    ENSURE(sps_body_add_box(w, b, nan3, x, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "box axis 0 is [nan, ") == 0);
    big[0] = 1e6; big[1] = 1e6; /* (1e8)^2 lattice points */
    ENSURE(sps_body_add_box(w, b, x, big, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "allowed a total of 200000000") == 0);
    ENSURE(sps_body_add_sdf(w, b, x, x, NULL, NULL, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "sdf must not be NULL") == 0);
    ENSURE(sps_body_add_particles(w, b, -1, x, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "n = -1") == 0);
    ENSURE(sps_body_add_particles(w, b, 1, NULL, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "xyz NULL") == 0);
    ENSURE(sps_body_add_particles(w, b, 1, nan3, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "xyz[0] = nan, allowed finite") == 0);
    ENSURE(sps_body_set_velocity(w, b, NULL, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "fn must not be NULL") == 0);
    ENSURE(sps_body_constrain_box(w, b, x, big, 8, NULL, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "mask = 8") == 0);
    ENSURE(sps_body_constrain_box(w, b, x, big, SPS_AXIS_X, nan3, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "velocity[0] = nan") == 0);
    ENSURE(sps_world_add_observer(w, b, nan3, &o) == SPS_ERR_INVALID_ARG && error_names(w, "allowed a finite x") == 0);
    ENSURE(sps_world_add_observer(w, b, x, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "out NULL") == 0);
    ENSURE(sps_world_nearest_particle(w, b, nan3) == -1 && error_names(w, "x not finite") == 0);
    ENSURE(sps_world_nearest_particle(w, none, x) == -1 && error_names(w, "not a body of this world") == 0);
    ENSURE(sps_world_particle(w, 25, &ps) == SPS_ERR_INVALID_ARG && error_names(w, "id = 25 with out set, allowed id in [0, 25)") == 0);
    ENSURE(sps_world_particle(w, 0, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "out NULL") == 0);
    ENSURE(sps_world_field(w, (sps_field)12) == NULL && error_names(w, "field = 12, allowed 0..11") == 0);
    ENSURE(sps_world_field(w, (sps_field)-1) == NULL && error_names(w, "field = -1") == 0);
    ENSURE(sps_world_field(w, SPS_FIELD_POSITION_Z) == NULL); /* 2D: no z array, not an error */
    ENSURE(sps_world_diagnostics(w, b, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "out must not be NULL") == 0);
    ENSURE(sps_world_write_vtk(w, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "path must not be NULL") == 0);
    ENSURE(sps_world_advance(w, INFINITY, NULL, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "t_end = inf, allowed finite") == 0);
    sps_world_destroy(w);
    return 0;
}

/* Fields by name: the world's arrays are those of the enum access; the optional arrays belong
   to the bodies whose model needs them (an ENO body beside an OG body carries no stress), read
   by sps_body_field after the first step; unknown names and missing axes refused with a message. */
static int test_field_by_name(void) {
    sps_world* w = new_world(2, 0.01);
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.05, 0}, lo2[3] = {0.2, 0, 0}, hi2[3] = {0.3, 0.05, 0};
    int n = 0, n2 = 0, comps = -1, first = -1, count = -1;
    sps_body og, eno;
    ENSURE(w);
    ENSURE((og = add_block(w, SPS_SHEAR_OG, lo, hi, &n)).id != 0);
    ENSURE((eno = add_block(w, SPS_SHEAR_ENO, lo2, hi2, &n2)).id != 0);
    ENSURE(sps_world_field_by_name(w, "velocity_y", &comps) == sps_world_field(w, SPS_FIELD_VELOCITY_Y) && comps == 1);
    ENSURE(sps_world_field_by_name(w, "density", NULL) == sps_world_field(w, SPS_FIELD_DENSITY));
    ENSURE(sps_world_field_by_name(w, "shear_stress", NULL) == NULL && error_names(w, "use sps_body_field") == 0);
    ENSURE(sps_body_field(w, og, "shear_stress", NULL, NULL, NULL) == NULL && error_names(w, "step first") == 0);
    ENSURE(sps_world_field_by_name(w, "position_z", NULL) == NULL && error_names(w, "dim = 2") == 0);
    ENSURE(sps_world_field_by_name(w, "velocity", NULL) == NULL && error_names(w, "name = 'velocity'") == 0);
    ENSURE(sps_world_field_by_name(w, "id", NULL) == NULL && error_names(w, "name = 'id'") == 0);
    ENSURE(sps_world_field_by_name(w, NULL, NULL) == NULL && error_names(w, "name is NULL") == 0);
    ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(sps_body_field(w, og, "shear_stress", &comps, &first, &count) != NULL && comps == 6 && count == n); /* OG integrates tau */
    ENSURE(sps_body_field(w, og, "velocity_gradient", &comps, NULL, NULL) != NULL && comps == 9);
    ENSURE(sps_body_field(w, og, "density", NULL, &first, NULL) == sps_world_field(w, SPS_FIELD_DENSITY) + first);
    ENSURE(sps_body_field(w, eno, "shear_stress", NULL, NULL, NULL) == NULL && error_names(w, "does not need it") == 0);
    ENSURE(sps_body_field(w, eno, "density", NULL, &first, &count) != NULL && count == n2);
    ENSURE(sps_body_field(w, og, "artificial_stress", NULL, NULL, NULL) == NULL); /* no OAS body */
    sps_world_destroy(w);
    return 0;
}

/* Calls that do what they were asked but probably not what was meant warn through the log
   (level 1) and return SPS_OK: a box thinner than dp, a constraint box that matches no
   particle, a Poisson ratio within 1e-3 of 0.5 (with what it costs in time step). */
static int g_warnings;
static char g_warning_last[1024];
static void warning_log(int level, const char* message, void* user) {
    (void)user;
    if (level == 1) { ++g_warnings; snprintf(g_warning_last, sizeof g_warning_last, "%s", message); }
}
static int test_warnings_for_silent_cases(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body b;
    const sps_real lo[3] = {0, 0, 0}, thin[3] = {0.1, 0.005, 0}, hi[3] = {0.1, 0.1, 0}, far_lo[3] = {5, 5, 0}, far_hi[3] = {6, 6, 0};
    int added = -1, count = -1;
    wd.dp = 0.01;
    wd.log = warning_log;
    g_warnings = 0;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && g_warnings == 0); /* nu = 0.3: no warning */
    ENSURE(sps_body_add_box(w, b, lo, thin, &added) == SPS_OK && added == 0);
    ENSURE(g_warnings == 1 && strstr(g_warning_last, "got no particle") != NULL);
    ENSURE(sps_body_add_box(w, b, lo, hi, &added) == SPS_OK && added == 100 && g_warnings == 1);
    ENSURE(sps_body_constrain_box(w, b, far_lo, far_hi, SPS_AXIS_ALL, NULL, &count) == SPS_OK && count == 0);
    ENSURE(g_warnings == 2 && strstr(g_warning_last, "nothing is constrained") != NULL);
    bd.material.poisson_ratio = 0.4995;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK);
    printf("    %s\n", g_warning_last);
    ENSURE(g_warnings == 3 && strstr(g_warning_last, "within 1e-3 of 0.5") != NULL);
    ENSURE(strcmp(sps_world_last_error(w), "") == 0); /* warnings are not errors */
    sps_world_destroy(w);
    return 0;
}

/* ---- the energy watchdog ---- */

/* A 3D cantilever (the 2D plate's beam, L = 0.2, H = 0.02, as wide as thick, E = 2e6,
   nu = 0.3975) at H/dp = 4 (704 particles, 4 clamped layers), released with the first mode's
   shape at tip speed 0.05 c0, one thread, warnings counted by warning_log. */
typedef struct { double tip_speed, length; } mode_shape;
static void first_mode_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const mode_shape* m = (const mode_shape*)user;
    const double kl = 1.8751040687, k = kl / m->length, c = (cos(kl) + cosh(kl)) / (sin(kl) + sinh(kl));
    const double at = (cos(k * x[0]) - cosh(k * x[0])) - c * (sin(k * x[0]) - sinh(k * x[0]));
    const double tip = (cos(kl) - cosh(kl)) - c * (sin(kl) - sinh(kl));
    v[0] = v[2] = 0;
    v[1] = x[0] > 0 ? (sps_real)(m->tip_speed * at / tip) : 0;
}
static sps_world* cantilever3d(double cfl, int stops) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body b;
    const double H = 0.02, dp = H / 4;
    const sps_real lo[3] = {-4 * dp, 0, 0}, hi[3] = {0.2, H, H}, clo[3] = {-1, -1, -1}, chi[3] = {0, 1, 1};
    mode_shape m = {0, 0.2};
    sps_real c0;
    wd.dim = 3; wd.dp = dp; wd.cfl_acoustic = cfl; wd.threads = 1; wd.log = warning_log; wd.energy_growth_stops = stops;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    bd.name = "cantilever";
    bd.material.youngs_modulus = 2e6;
    bd.material.poisson_ratio = 0.3975;
    bd.track_stress = 1;
    if (sps_world_add_body(w, &bd, &b) != SPS_OK || sps_body_add_box(w, b, lo, hi, NULL) != SPS_OK ||
        sps_body_material_constants(w, b, &c0, NULL, NULL) != SPS_OK || (m.tip_speed = 0.05 * c0, 0) ||
        sps_body_set_velocity(w, b, first_mode_velocity, &m) != SPS_OK ||
        sps_body_constrain_box(w, b, clo, chi, SPS_AXIS_ALL, NULL, NULL) != SPS_OK) {
        sps_world_destroy(w);
        return NULL;
    }
    return w;
}

/* Past its stable time step a run can blow up and stay finite, every step returning SPS_OK:
   the 3D cantilever at cfl_acoustic = 0.8 nearly doubles its energy within 7 ms (measured) and
   keeps growing. The watchdog warns once, naming the time, the body and the growth, and with
   energy_growth_stops = 1 stops the run with SPS_ERR_UNSTABLE (a CFL above the measured stable
   limit is warned of when the body is added); at the default CFL 0.4 the same beam swings
   four times as long (0.03 s; the account only decays by the Riemann dissipation) without a
   word, and so does the 2D plate through its first period. */
static int test_energy_watchdog(void) {
    sps_world* w;
    g_warnings = 0;
    ENSURE((w = cantilever3d(0.8, 0)) != NULL);
    printf("    %s\n", g_warning_last);
    ENSURE(g_warnings == 1 && strstr(g_warning_last, "cfl_acoustic = 0.8 is above") != NULL); /* said when the body is added */
    ENSURE(sps_world_advance(w, 0.02, NULL, NULL) == SPS_OK);
    printf("    %s\n", g_warning_last);
    ENSURE(g_warnings == 2 && strstr(g_warning_last, "energy watchdog at t = ") != NULL);
    ENSURE(strstr(g_warning_last, "body 'cantilever' gained most") != NULL && strstr(g_warning_last, "cfl_acoustic = 0.8") != NULL);
    sps_world_destroy(w);
    ENSURE((w = cantilever3d(0.8, 1)) != NULL);
    ENSURE(sps_world_advance(w, 0.02, NULL, NULL) == SPS_ERR_UNSTABLE);
    ENSURE(strstr(sps_world_last_error(w), "unstable: energy watchdog at t = ") != NULL && sps_world_time(w) < 0.02);
    sps_world_destroy(w);
    g_warnings = 0;
    ENSURE((w = cantilever3d(0.4, 0)) != NULL);
    ENSURE(sps_world_advance(w, 0.03, NULL, NULL) == SPS_OK && g_warnings == 0);
    sps_world_destroy(w);
    { /* and the 2D plate (A1 at H/dp 5, ENO-A, v_f 0.05) through its first period: no message at all */
        sps_observer tip;
        long before;
        ENSURE((w = plate2d_build(5, SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0.05, 1, &tip)) != NULL);
        before = g_log_count;
        ENSURE(sps_world_advance(w, 0.3, NULL, NULL) == SPS_OK && g_log_count == before);
        sps_world_destroy(w);
    }
    return 0;
}

/* The work of the prescribed motions enters the account, so driven scenes do not read as energy
   gains. A bar 0.4 x 0.1 (GNO-A, stress tracked), clamped at x < 0.03, is pulled at its end
   x > 0.37 at 0.002 c0 by a velocity constraint, or pushed there by a rigid block moving at
   0.002 c0, placed touching it (its contact releases 36 J at the start: the contact energy is
   in the account). After 0.02 s the work done equals the energy gained within the Riemann
   dissipation: the energy gained is the work done within 5 % for the slow pull (measured 0.8 %
   above it, the end's kinetic energy at the start included), and below it for the push, which
   loses half of the contact's start to dissipation; the watchdog stays quiet. */
static int driven_bar(int rigid_pusher, double* gained, double* work) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body b, r;
    sps_diagnostics d0, d1;
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.4, 0.1, 0}, clo[3] = {-1, -1, 0}, chi[3] = {0.03, 1, 0};
    const sps_real plo[3] = {0.37, -1, 0}, phi[3] = {1, 1, 0}, rlo[3] = {0.4, 0, 0}, rhi[3] = {0.44, 0.1, 0};
    sps_real v[3] = {0, 0, 0}, c0;
    wd.threads = 1; wd.log = warning_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.shear = SPS_SHEAR_GNO_A;
    bd.track_stress = 1;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_material_constants(w, b, &c0, NULL, NULL) == SPS_OK);
    ENSURE(sps_body_constrain_box(w, b, clo, chi, SPS_AXIS_ALL, NULL, NULL) == SPS_OK);
    v[0] = (rigid_pusher ? -0.002 : 0.002) * c0;
    if (rigid_pusher) {
        bd.material.kind = SPS_MATERIAL_RIGID;
        bd.name = "pusher";
        ENSURE(sps_world_add_body(w, &bd, &r) == SPS_OK && sps_body_add_box(w, r, rlo, rhi, NULL) == SPS_OK);
        ENSURE(sps_body_constrain_box(w, r, rlo, rhi, SPS_AXIS_ALL, v, NULL) == SPS_OK);
    } else
        ENSURE(sps_body_constrain_box(w, b, plo, phi, SPS_AXIS_X, v, NULL) == SPS_OK);
    g_warnings = 0;
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d0) == SPS_OK);
    ENSURE(sps_world_advance(w, 0.02, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d1) == SPS_OK);
    *gained = (d1.kinetic_energy + d1.strain_energy + d1.contact_energy) - (d0.kinetic_energy + d0.strain_energy + d0.contact_energy);
    *work = d1.prescribed_work;
    ENSURE(g_warnings == 0);
    sps_world_destroy(w);
    return 0;
}
static int test_energy_account_driven(void) {
    double gained[2], work[2];
    ENSURE(driven_bar(0, &gained[0], &work[0]) == 0);
    ENSURE(driven_bar(1, &gained[1], &work[1]) == 0);
    printf("    pulled: energy gained %.4g J, work done %.4g J;  pushed by a rigid block: %.4g J, %.4g J\n", gained[0], work[0],
           gained[1], work[1]);
    ENSURE(work[0] > 0 && work[1] > 0);           /* both drive the bar */
    ENSURE(fabs(gained[0] - work[0]) < 0.05 * work[0]); /* the slow pull is nearly reversible: work -> energy */
    ENSURE(gained[1] - work[1] < 0);              /* dissipation only takes energy away */
    return 0;
}

/* A particle's position and velocity are writable by id between steps, and read back exactly;
   the next step starts from them. Bad ids and values are refused with a message. */
static int test_set_particle(void) {
    sps_world* w = new_world(2, 0.01);
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0};
    const sps_real x[3] = {0.3, 0.2, 0}, v[3] = {1.5, -2, 0}, nan3[3] = {NAN, 0, 0};
    sps_particle_state ps;
    int n = 0;
    ENSURE(w && add_block(w, SPS_SHEAR_ENO_A, lo, hi, &n).id);
    ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(sps_world_set_particle(w, 7, x, v) == SPS_OK);
    ENSURE(sps_world_particle(w, 7, &ps) == SPS_OK);
    ENSURE(ps.position[0] == x[0] && ps.position[1] == x[1] && ps.velocity[0] == v[0] && ps.velocity[1] == v[1]);
    ENSURE(sps_world_set_particle(w, 8, NULL, v) == SPS_OK && sps_world_particle(w, 8, &ps) == SPS_OK && ps.velocity[1] == v[1]);
    ENSURE(sps_world_step(w) == SPS_OK); /* the moved particle, away from its body, steps on alone */
    ENSURE(sps_world_particle(w, 7, &ps) == SPS_OK && ps.position[0] > x[0]);
    ENSURE(sps_world_set_particle(w, n, x, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "allowed id in [0, 100)") == 0);
    ENSURE(sps_world_set_particle(w, 0, nan3, NULL) == SPS_ERR_INVALID_ARG && error_names(w, "position not finite") == 0);
    ENSURE(sps_world_set_particle(NULL, 0, x, v) == SPS_ERR_INVALID_ARG);
    sps_world_destroy(w);
    return 0;
}

/* Handles of another world, or of a destroyed one, are rejected by every call taking one. */
static int test_foreign_and_destroyed_handles(void) {
    sps_world *w1 = new_world(2, 0.01), *w2;
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
    sps_real x[3] = {0.01, 0.01, 0}, c0, u[3];
    sps_body b1, b2;
    sps_observer o1, o2;
    sps_diagnostics d;
    ENSURE(w1);
    b1 = add_block(w1, SPS_SHEAR_ENO_A, lo, hi, NULL);
    ENSURE(b1.id && sps_world_add_observer(w1, b1, x, &o1) == SPS_OK);
    sps_world_destroy(w1); /* b1 and o1 now belong to a destroyed world */
    ENSURE((w2 = new_world(2, 0.01)) != NULL);
    b2 = add_block(w2, SPS_SHEAR_ENO_A, lo, hi, NULL);
    ENSURE(b2.id && sps_world_add_observer(w2, b2, x, &o2) == SPS_OK);
    ENSURE(b1.id != b2.id && o1.id != o2.id);
    ENSURE(!sps_body_is_valid(w2, b1) && sps_body_index(w2, b1) == -1);
    ENSURE(sps_body_add_box(w2, b1, x, x, NULL) == SPS_ERR_INVALID_ARG && error_names(w2, "not a body of this world") == 0);
    ENSURE(sps_body_add_particles(w2, b1, 1, x, NULL) == SPS_ERR_INVALID_ARG && error_names(w2, "not a body of this world") == 0);
    ENSURE(sps_body_set_velocity(w2, b1, random_velocity, NULL) == SPS_ERR_INVALID_ARG && error_names(w2, "not a body of this world") == 0);
    ENSURE(sps_body_constrain_box(w2, b1, x, x, 1, NULL, NULL) == SPS_ERR_INVALID_ARG && error_names(w2, "not a body of this world") == 0);
    ENSURE(sps_body_material_constants(w2, b1, &c0, NULL, NULL) == SPS_ERR_INVALID_ARG && error_names(w2, "not a body of this world") == 0);
    ENSURE(sps_world_add_observer(w2, b1, x, &o2) == SPS_ERR_INVALID_ARG && o2.id == 0 && error_names(w2, "not a body of this world") == 0);
    ENSURE(sps_world_diagnostics(w2, b1, &d) == SPS_ERR_INVALID_ARG && error_names(w2, "not a body of this world") == 0);
    ENSURE(sps_world_nearest_particle(w2, b1, x) == -1);
    ENSURE(sps_observer_read(w2, o1, u, NULL) == SPS_ERR_INVALID_ARG && error_names(w2, "not an observer of this world") == 0);
    sps_world_destroy(w2);
    return 0;
}

/* A box with no lattice point along one axis adds nothing, at once, however long the other axes
   (the count 0 x 1e32 x 1e32 must not turn into 1e18 empty loop turns). The alarm turns a hang
   into a failure. */
static int test_flat_box_is_empty(void) {
    sps_world* w = new_world(3, 0.01);
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.001, 1e30, 1e30};
    int added = -1;
    ENSURE(w && sps_world_add_body(w, &bd, &b) == SPS_OK);
    alarm(10);
    ENSURE(sps_body_add_box(w, b, lo, hi, &added) == SPS_OK && added == 0);
    alarm(0);
    sps_world_destroy(w);
    return 0;
}

/* A body without particles stops the first step with SPS_ERR_STATE naming it, also when other
   bodies are filled (a box narrower than dp holds no lattice point). */
static int test_step_empty_body(void) {
    sps_world* w = new_world(2, 0.01);
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
    sps_real tlo[3] = {0.2, 0.2, 0}, thi[3] = {0.205, 0.3, 0};
    sps_body_def bd = sps_default_body_def();
    sps_body full, thin;
    int added = -1;
    char msg[512];
    ENSURE(w);
    full = add_block(w, SPS_SHEAR_ENO_A, lo, hi, NULL);
    bd.name = "thin";
    ENSURE(full.id && sps_world_add_body(w, &bd, &thin) == SPS_OK);
    ENSURE(sps_body_add_box(w, thin, tlo, thi, &added) == SPS_OK && added == 0); /* 0.005 < dp */
    ENSURE(sps_world_step(w) == SPS_ERR_STATE && error_names(w, "body 'thin' (index 1) has no particles") == 0);
    ENSURE(sps_world_validate(w, msg, sizeof msg) == SPS_ERR_STATE && strstr(msg, "body 'thin' (index 1) has no particles"));
    thi[0] = 0.21;
    ENSURE(sps_body_add_box(w, thin, tlo, thi, &added) == SPS_OK && added == 10);
    ENSURE(sps_world_step(w) == SPS_OK);
    sps_world_destroy(w);
    return 0;
}

/* Particles added after a step to a body that tracks stress have a stress too: reading their
   von Mises stress before the next step reads zeros inside the array, not past its end. */
static int test_add_after_step_stress_output(void) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.16, 0.16, 0}, lo2[3] = {0.5, 0, 0}, hi2[3] = {0.9, 0.4, 0};
    sps_particle_state ps;
    int n1, n2, id;
    ENSURE(w);
    bd.track_stress = 1;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, lo, hi, &n1) == SPS_OK && n1 == 256);
    ENSURE(sps_world_step(w) == SPS_OK); /* stress array allocated for 256 particles */
    ENSURE(sps_body_add_box(w, b, lo2, hi2, &n2) == SPS_OK && n2 == 1600);
    for (id = n1; id < n1 + n2; ++id) {
        ENSURE(sps_world_particle(w, id, &ps) == SPS_OK);
        ENSURE(ps.von_mises == 0); /* at rest, never stepped */
    }
    ENSURE(sps_world_step(w) == SPS_OK);
    sps_world_destroy(w);
    return 0;
}

/* A two-body world: a resting block and a one-particle body "bullet" at x = 0.5 with speed v
   (flying away from the block). */
static sps_world* bullet_world(double v) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body block, bullet;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0}, x[3] = {0.5, 0.05, 0};
    sps_real clo[3] = {0.49, 0.04, 0}, chi[3] = {0.51, 0.06, 0}, vel[3] = {0, 0, 0};
    wd.threads = 1; wd.log = quiet_log;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    bd.name = "bullet";
    vel[0] = v;
    if (sps_world_add_body(w, &bd, &block) != SPS_OK || sps_body_add_box(w, block, lo, hi, NULL) != SPS_OK ||
        sps_world_add_body(w, &bd, &bullet) != SPS_OK || sps_body_add_particles(w, bullet, 1, x, NULL) != SPS_OK ||
        sps_body_constrain_box(w, bullet, clo, chi, SPS_AXIS_X, vel, NULL) != SPS_OK) { /* held at speed v */
        sps_world_destroy(w);
        return NULL;
    }
    return w;
}

/* A resting block 0.1 x 0.1 (100 particles, c0 = 28.9 m/s) moving at v_all along x, whose
   particle nearest to (0.095, 0.055) (the middle of its right side) is held at v_all + v_one. */
typedef struct { double vx; } uniform_x;
static void uniform_x_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)x;
    v[0] = (sps_real)((const uniform_x*)user)->vx;
    v[1] = v[2] = 0;
}
static sps_world* flung_world(double v_one, double v_all, double escape_distance, int report_fragments, int* flung_id) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body block;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0}, x[3] = {0.095, 0.055, 0};
    sps_real clo[3] = {0.094, 0.054, 0}, chi[3] = {0.096, 0.056, 0}, vel[3] = {0, 0, 0};
    uniform_x all;
    wd.threads = 1; wd.log = warning_log; wd.escape_distance = escape_distance; wd.report_fragments = report_fragments;
    wd.energy_growth_limit = INFINITY; /* a particle dragged at 0.35 c0 through the block: the account reads 10 % growth */
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    bd.name = "block";
    all.vx = v_all;
    vel[0] = (sps_real)(v_all + v_one);
    if (sps_world_add_body(w, &bd, &block) != SPS_OK || sps_body_add_box(w, block, lo, hi, NULL) != SPS_OK ||
        sps_body_set_velocity(w, block, uniform_x_velocity, &all) != SPS_OK ||
        sps_body_constrain_box(w, block, clo, chi, SPS_AXIS_X, vel, NULL) != SPS_OK) {
        sps_world_destroy(w);
        return NULL;
    }
    *flung_id = sps_world_nearest_particle(w, block, x);
    return w;
}

/* The escape guard judges a particle against its own body: farther than the body's size (its
   reach, 0.0636 m from the centre of mass to a corner) plus escape_distance from the body's
   current centre of mass stops the run with SPS_ERR_UNSTABLE naming time, body, particle and
   position. The flung particle starts 0.045 m from the centre and leaves at 10 m/s, dragging
   the block along: with escape_distance = 0.05 m it is 0.1136 m out after 6.9 ms at the
   earliest (measured 9.3 ms).
   The whole block translating at 10 m/s travels 0.2 m (four escape distances) in 20 ms and is
   never stopped; with the default escape distance (10 body sizes) the flung particle is not
   stopped within 20 ms either, and report_fragments = 1 says when it broke off. */
static int test_guard_escape(void) {
    char expect[64];
    int flung;
    sps_world* w = flung_world(10, 0, 0.05, 0, &flung);
    sps_result r = SPS_OK;
    int k;
    ENSURE(w);
    for (k = 0; k < 400 && r == SPS_OK; ++k) r = sps_world_step(w);
    printf("    %s\n", sps_world_last_error(w));
    ENSURE(r == SPS_ERR_UNSTABLE);
    snprintf(expect, sizeof expect, "particle %d of body 'block' escaped to (0.", flung);
    ENSURE(error_names(w, expect) == 0);
    ENSURE(error_names(w, "escape_distance (0.05 m)") == 0 && error_names(w, "from the body's centre of mass") == 0);
    /* not before 6.9 ms (the centre of mass, dragged along, only delays it), and well within 20 ms */
    ENSURE(sps_world_time(w) > 0.0068 && sps_world_time(w) < 0.02);
    sps_world_destroy(w);
    ENSURE((w = flung_world(0, 10, 0.05, 1, &flung)) != NULL);
    g_warnings = 0;
    ENSURE(sps_world_advance(w, 0.02, NULL, NULL) == SPS_OK && g_warnings == 0); /* nothing breaks off */
    sps_world_destroy(w);
    ENSURE((w = flung_world(10, 0, 0, 1, &flung)) != NULL);
    ENSURE(sps_world_advance(w, 0.02, NULL, NULL) == SPS_OK);
    printf("    %s\n", g_warning_last);
    snprintf(expect, sizeof expect, "particle %d of body 'block' broke off", flung);
    ENSURE(g_warnings >= 1 && strstr(g_warning_last, expect) != NULL); /* report_fragments = 1 */
    sps_world_destroy(w);
    return 0;
}

/* A time step collapsing by three orders of magnitude is an instability: the bullet, a body
   that can touch the block, flying at 1e5 m/s (3460 c0; c0 = 28.9 m/s) makes
   dt_ac = CFL h/(c0 + v) < 1e-3 CFL h/c0 at the first step, v the approach speed of the two
   bodies. At 2e4 m/s (692 c0) the run goes on. */
static int test_guard_time_step_collapse(void) {
    sps_world* w = bullet_world(1e5);
    ENSURE(w);
    ENSURE(sps_world_step(w) == SPS_ERR_UNSTABLE);
    printf("    %s\n", sps_world_last_error(w));
    ENSURE(error_names(w, "time step collapsed to dt = ") == 0);
    ENSURE(error_names(w, "approach each other or the walls at 100000 m/s") == 0);
    sps_world_destroy(w);
    ENSURE((w = bullet_world(2e4)) != NULL);
    ENSURE(sps_world_step(w) == SPS_OK && sps_world_step(w) == SPS_OK);
    sps_world_destroy(w);
    return 0;
}

/* Each checked quantity, made non-finite in one particle, stops the next step at the
   configuration update, naming the quantity. */
static int test_guard_nonfinite_state(void) {
    static const char* names[5] = {"velocity", "position", "density", "pressure", "shear stress"};
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
    int q;
    for (q = 0; q < 6; ++q) {
        sps_world* w = new_world(2, 0.01);
        sps_body b;
        int i;
        ENSURE(w);
        b = add_block(w, SPS_SHEAR_OG, lo, hi, NULL); /* OG: tracks the stress */
        ENSURE(b.id && sps_world_step(w) == SPS_OK);
        i = w->slot_of_id[7];
        switch (q) {
        case 0: w->vel[1][i] = NAN; break;
        case 1: w->pos[0][i] = INFINITY; break;
        case 2: w->rho[i] = -1; break;
        case 3: w->p[i] = NAN; break;
        case 4: w->bodies[0].tau[(size_t)6 * (i - w->bodies[0].begin) + 1] = INFINITY; break; /* the body owns its stress */
        default: w->acc_s[0][i] = NAN; break;
        }
        ENSURE(sps_world_step(w) == SPS_ERR_UNSTABLE);
        ENSURE(error_names(w, q < 5 ? names[q] : "shear acceleration") == 0);
        ENSURE(error_names(w, "particle 7 of body 'body'") == 0);
        sps_world_destroy(w);
    }
    return 0;
}

/* The blow-up of test_unstable_run_reported, with keep_last_good_state = 1: the world is rolled
   back to the last configuration update before the failure, so every value is finite, the
   diagnostics describe that state, and the VTK file holds no NaN; further steps are refused.
   Without the flag the state at the error is kept (a negative density here). */
static int run_blow_up(int keep, sps_world** out) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.2, 0};
    unsigned long long seed = 5;
    int k;
    sps_result r = SPS_OK;
    wd.cfl_acoustic = 1; wd.threads = 1; wd.log = quiet_log; wd.keep_last_good_state = keep;
    ENSURE(sps_world_create(&wd, out) == SPS_OK);
    bd.zeta = 100;
    ENSURE(sps_world_add_body(*out, &bd, &b) == SPS_OK && sps_body_add_box(*out, b, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_set_velocity(*out, b, random_velocity, &seed) == SPS_OK);
    for (k = 0; k < 100 && r == SPS_OK; ++k) r = sps_world_step(*out);
    ENSURE(r == SPS_ERR_UNSTABLE);
    return 0;
}

static int file_contains(const char* path, const char* needle) {
    char line[512];
    int found = 0;
    FILE* f = fopen(path, "r");
    if (!f) return -1;
    while (!found && fgets(line, sizeof line, f)) found = strstr(line, needle) != NULL;
    fclose(f);
    return found;
}

static int test_last_good_state(void) {
    sps_world *keep, *plain;
    char msg[2048], path[] = "/tmp/test_sphsolid_good_XXXXXX";
    sps_diagnostics d;
    double t_fail;
    int fd;
    ENSURE(run_blow_up(1, &keep) == 0 && run_blow_up(0, &plain) == 0);
    t_fail = sps_world_time(plain);
    printf("    failed at t = %g; rolled back to t = %g\n", t_fail, sps_world_time(keep));
    ENSURE(sps_world_time(keep) < t_fail && sps_world_time(keep) > 0);
    ENSURE(strcmp(sps_world_last_error(keep), sps_world_last_error(plain)) == 0); /* same failure */
    ENSURE(sps_world_validate(keep, msg, sizeof msg) == SPS_ERR_STATE);
    ENSURE(strstr(msg, "stopped at an instability") == msg); /* the only broken rule */
    ENSURE(sps_world_validate(plain, msg, sizeof msg) == SPS_ERR_STATE && strstr(msg, "density not finite > 0"));
    ENSURE(sps_world_diagnostics(keep, ALL_BODIES, &d) == SPS_OK);
    ENSURE(d.time == sps_world_time(keep) && d.min_density > 0 && d.kinetic_energy < 1e9 && d.hourglass < 1);
    ENSURE((fd = mkstemp(path)) >= 0);
    close(fd);
    ENSURE(sps_world_write_vtk(keep, path) == SPS_OK && file_contains(path, "nan") == 0);
    remove(path);
    ENSURE(sps_world_step(keep) == SPS_ERR_UNSTABLE && error_names(keep, "stopped at an instability") == 0);
    ENSURE(sps_world_advance(plain, 1, NULL, NULL) == SPS_ERR_UNSTABLE && error_names(plain, "cannot step further") == 0);
    sps_world_destroy(keep);
    sps_world_destroy(plain);
    return 0;
}

/* sps_world_validate lists every broken rule at once; a sound world passes with an empty
   message. The breakage is planted in the internals (the API refuses to make it). */
static int test_world_validate(void) {
    sps_world* w = new_world(2, 0.01);
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
    sps_real x[3] = {0.02, 0.02, 0};
    sps_body_def bd = sps_default_body_def();
    sps_body b, empty;
    sps_observer o;
    char msg[2048];
    ENSURE(w);
    b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, NULL);
    ENSURE(b.id && sps_world_add_observer(w, b, x, &o) == SPS_OK && sps_world_step(w) == SPS_OK);
    ENSURE(sps_world_validate(w, msg, sizeof msg) == SPS_OK && msg[0] == 0);
    bd.name = "hollow";
    ENSURE(sps_world_add_body(w, &bd, &empty) == SPS_OK);
    w->vel[0][w->slot_of_id[3]] = NAN;
    w->mass[w->slot_of_id[4]] = -1;
    w->obs_weights[0] *= 2;
    w->bodies[0].def.material.poisson_ratio = 0.6;
    ENSURE(sps_world_validate(w, msg, sizeof msg) == SPS_ERR_STATE);
    printf("    %s\n", msg);
    ENSURE(strstr(msg, "material.poisson_ratio = 0.6"));
    ENSURE(strstr(msg, "body 'hollow' (index 1) has no particles"));
    ENSURE(strstr(msg, "velocity not finite: 1 particle(s), the first id 3"));
    ENSURE(strstr(msg, "mass not finite > 0: 1 particle(s), the first id 4"));
    ENSURE(strstr(msg, "observer 0: weights sum to"));
    ENSURE(sps_world_validate(w, NULL, 0) == SPS_ERR_STATE); /* no message buffer: the verdict only */
    sps_world_destroy(w);
    return 0;
}

/* Once the first step has allocated (and the first diagnostics their scratch), neither steps nor
   diagnostics allocate, for every shear formulation (each needs other optional fields), both
   pair-geometry modes and the last-good-state copy; sps_world_destroy frees every byte. */
static int test_memory_no_allocation_in_steps(void) {
    int shear, variant, dim;
    for (dim = 2; dim <= 3; ++dim)
        for (shear = 0; shear < 6; ++shear)
            for (variant = 0; variant < 4; ++variant) { /* frozen geometry (odd), SPS_ROTATION_PAIR (2, 3; -A only) */
                counting_allocator ca = {0, 0, 0, 0, 0};
                sps_world_def wd = sps_default_world_def();
                sps_world* w;
                sps_body b;
                sps_diagnostics d;
                unsigned long long seed = 11;
                static const double lo[3] = {0, 0, 0}, hi[3] = {0.06, 0.06, 0.06};
                long calls;
                int k;
                const int frozen = variant % 2, pair = variant / 2;
                if (shear == SPS_SHEAR_OAS && dim == 3) continue;
                if (pair && shear != SPS_SHEAR_ENO_A && shear != SPS_SHEAR_GNO_A) continue;
                wd.dim = dim; wd.threads = 1; wd.log = quiet_log; wd.frozen_geometry = frozen; wd.keep_last_good_state = 1;
                wd.allocator.alloc = counting_alloc; wd.allocator.free = counting_free; wd.allocator.user = &ca;
                ENSURE(sps_world_create(&wd, &w) == SPS_OK);
                b = add_block_rotation(w, (sps_shear)shear, pair ? SPS_ROTATION_PAIR : SPS_ROTATION_MEAN, lo, hi, NULL);
                ENSURE(b.id && sps_body_set_velocity(w, b, random_velocity, &seed) == SPS_OK);
                ENSURE(sps_world_step(w) == SPS_OK && sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
                calls = ca.calls;
                for (k = 0; k < 5; ++k) ENSURE(sps_world_step(w) == SPS_OK && sps_world_diagnostics(w, b, &d) == SPS_OK);
                if (ca.calls != calls)
                    printf("    dim %d shear %d frozen %d pair %d: %ld allocations in steps\n", dim, shear, frozen, pair, ca.calls - calls);
                ENSURE(ca.calls == calls);
                sps_world_destroy(w);
                ENSURE(ca.live == 0);
            }
    return 0;
}

/* Refusing each allocation of a full scenario in turn (create, bodies, particles, constraint,
   observer, steps, diagnostics, output): the call that meets it returns SPS_ERR_OUT_OF_MEMORY
   with a message, nothing crashes, later calls work or fail cleanly, and destroy frees all. */
static int oom_scenario(counting_allocator* ca, sps_rotation rotation, int* failed_calls) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body b = {0};
    sps_observer o;
    sps_diagnostics d;
    sps_particle_state ps;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.1, 0}, clo[3] = {-1, -1, -1}, chi[3] = {0.02, 1, 1}, x[3] = {0.1, 0.05, 0};
    sps_real more[3] = {0.3, 0.3, 0};
    sps_result r[9];
    int k = 0, fd;
    char path[] = "/tmp/test_sphsolid_oom_XXXXXX";
    wd.threads = 1; wd.log = quiet_log; wd.keep_last_good_state = 1;
    wd.allocator.alloc = counting_alloc; wd.allocator.free = counting_free; wd.allocator.user = ca;
    bd.shear = SPS_SHEAR_GNO_A; bd.rotation = rotation; bd.track_stress = 1;
    g_log_last[0] = 0;
    if (sps_world_create(&wd, &w) != SPS_OK) {
        ENSURE(w == NULL && strstr(g_log_last, "out of memory"));
        ++*failed_calls;
        return 0;
    }
    ENSURE((fd = mkstemp(path)) >= 0);
    close(fd);
    /* after each call: an out-of-memory result carries its message; other errors follow from an
       earlier refusal (no body, no particles) */
#define OOM_CALL(call)                                                                                   \
    r[k] = call;                                                                                         \
    if (!(r[k] == SPS_OK || r[k] == SPS_ERR_OUT_OF_MEMORY || r[k] == SPS_ERR_INVALID_ARG || r[k] == SPS_ERR_STATE)) printf("    call %d: %s\n", k, sps_world_last_error(w)); \
    ENSURE(r[k] == SPS_OK || r[k] == SPS_ERR_OUT_OF_MEMORY || r[k] == SPS_ERR_INVALID_ARG || r[k] == SPS_ERR_STATE); \
    if (r[k] == SPS_ERR_OUT_OF_MEMORY) { ENSURE(strstr(sps_world_last_error(w), "out of memory")); ++*failed_calls; } \
    ++k;
    OOM_CALL(sps_world_add_body(w, &bd, &b))
    OOM_CALL(sps_body_add_box(w, b, lo, hi, NULL))
    OOM_CALL(sps_body_constrain_box(w, b, clo, chi, SPS_AXIS_ALL, NULL, NULL))
    OOM_CALL(sps_world_add_observer(w, b, x, &o))
    OOM_CALL(sps_world_step(w))
    OOM_CALL(sps_world_diagnostics(w, ALL_BODIES, &d))
    OOM_CALL(sps_body_add_particles(w, b, 1, more, NULL))
    OOM_CALL(sps_world_step(w))
    OOM_CALL(sps_world_write_vtk(w, path))
#undef OOM_CALL
    remove(path);
    for (k = 0; k < sps_world_particle_count(w); ++k) ENSURE(sps_world_particle(w, k, &ps) == SPS_OK);
    sps_world_destroy(w);
    return 0;
}

/* Both rotations: SPS_ROTATION_PAIR allocates the pair forces and their kept copy. */
static int test_memory_out_of_memory_everywhere(void) {
    int pair;
    for (pair = 0; pair < 2; ++pair) {
        const sps_rotation rotation = pair ? SPS_ROTATION_PAIR : SPS_ROTATION_MEAN;
        counting_allocator full = {0, 0, 0, 0, 0};
        long k;
        int failed = 0;
        ENSURE(oom_scenario(&full, rotation, &failed) == 0 && failed == 0 && full.live == 0);
        printf("    %s rotation: %ld allocations in the scenario; each refused in turn\n", pair ? "pair" : "mean", full.calls);
        for (k = 1; k <= full.calls; ++k) {
            counting_allocator ca = {0, 0, 0, 0, 0};
            ca.fail_at = k;
            failed = 0;
            ENSURE(oom_scenario(&ca, rotation, &failed) == 0);
            if (failed != 1) printf("    refusing allocation %ld: %d calls failed\n", k, failed);
            ENSURE(failed >= 1); /* the refusal was reported */
            ENSURE(ca.live == 0);
        }
    }
    return 0;
}

/* Repeated runs in one process give bit-identical states for every shear formulation (no state
   leaks between worlds; no uninitialised value reaches the results). */
static int test_determinism_repeated_runs(void) {
    int shear;
    for (shear = 0; shear < 6; ++shear) {
        double* s[2];
        int run, n = 0, same;
        for (run = 0; run < 2; ++run) {
            sps_world* w = new_world(2, 0.01);
            static const double lo[3] = {0, 0, 0}, hi[3] = {0.12, 0.08, 0};
            unsigned long long seed = 77;
            sps_body b;
            int k;
            ENSURE(w);
            b = add_block(w, (sps_shear)shear, lo, hi, &n);
            ENSURE(b.id && sps_body_set_velocity(w, b, random_velocity, &seed) == SPS_OK);
            for (k = 0; k < 10; ++k) ENSURE(sps_world_step(w) == SPS_OK);
            ENSURE((s[run] = snapshot(w)) != NULL);
            sps_world_destroy(w);
        }
        same = memcmp(s[0], s[1], sizeof(double) * 6 * (size_t)n) == 0;
        free(s[0]); free(s[1]);
        ENSURE(same);
    }
    return 0;
}

/* ============================================================================================ */
/* >>output                                                                                     */

/* A minimal reader of the legacy VTK files the library writes, after the format's spec: four
   header lines (version, title of at most 255 characters, ASCII or BINARY, DATASET POLYDATA),
   POINTS n type, VERTICES n 2n, POINT_DATA n, FIELD FieldData k and k arrays `name components
   tuples type`. Each keyword line is followed by its values: ASCII numbers, or big-endian binary
   right after the line's newline, with a newline after the block. */
#define VTK_MAX_ARRAYS 16
typedef struct vtk_array {
    char name[64], type[16];
    int components, tuples;
    double* v; /* components * tuples */
} vtk_array;
typedef struct vtk_file {
    int binary, n, arrays;
    double *points, *vertices; /* 3 n and 2 n values */
    vtk_array array[VTK_MAX_ARRAYS];
} vtk_file;

static int vtk_line(FILE* f, char* buf, int size) {
    size_t len;
    if (!fgets(buf, size, f)) return 0;
    len = strlen(buf);
    if (len && buf[len - 1] == '\n') buf[len - 1] = 0;
    return 1;
}

/* count values of type ("double", "float" or "int") into v. */
static int vtk_values(FILE* f, int binary, const char* type, long count, double* v) {
    const int size = strcmp(type, "double") == 0 ? 8 : 4;
    long k;
    ENSURE(strcmp(type, "double") == 0 || strcmp(type, "float") == 0 || strcmp(type, "int") == 0);
    for (k = 0; k < count; ++k) {
        unsigned char be[8], host[8];
        int b;
        if (!binary) {
            ENSURE(fscanf(f, "%lf", &v[k]) == 1);
            continue;
        }
        ENSURE(fread(be, 1, (size_t)size, f) == (size_t)size);
        for (b = 0; b < size; ++b) { /* big-endian to the host's order */
            const uint16_t one = 1;
            host[b] = *(const unsigned char*)&one ? be[size - 1 - b] : be[b];
        }
        if (size == 8) { double d; memcpy(&d, host, 8); v[k] = d; }
        else if (strcmp(type, "float") == 0) { float x; memcpy(&x, host, 4); v[k] = x; }
        else { int32_t x; memcpy(&x, host, 4); v[k] = x; }
    }
    ENSURE(fgetc(f) == '\n'); /* the end of the last ASCII line, or the newline after a binary block */
    return 0;
}

static void vtk_free(vtk_file* v) {
    int k;
    free(v->points); free(v->vertices);
    for (k = 0; k < v->arrays; ++k) free(v->array[k].v);
    memset(v, 0, sizeof *v);
}

static int vtk_read(const char* path, vtk_file* v) {
    char line[512], type[16], expect[128];
    FILE* f = fopen(path, "rb");
    int n2, k;
    memset(v, 0, sizeof *v);
    ENSURE(f);
    ENSURE(vtk_line(f, line, sizeof line) && strcmp(line, "# vtk DataFile Version 3.0") == 0);
    ENSURE(vtk_line(f, line, sizeof line) && strlen(line) < 256);
    ENSURE(vtk_line(f, line, sizeof line) && (strcmp(line, "ASCII") == 0 || strcmp(line, "BINARY") == 0));
    v->binary = strcmp(line, "BINARY") == 0;
    ENSURE(vtk_line(f, line, sizeof line) && strcmp(line, "DATASET POLYDATA") == 0);
    ENSURE(vtk_line(f, line, sizeof line) && sscanf(line, "POINTS %d %15s", &v->n, type) == 2 && v->n > 0);
    ENSURE((v->points = (double*)malloc(sizeof(double) * 3 * (size_t)v->n)) != NULL);
    ENSURE(vtk_values(f, v->binary, type, 3L * v->n, v->points) == 0);
    ENSURE(vtk_line(f, line, sizeof line) && sscanf(line, "VERTICES %d %d", &k, &n2) == 2 && k == v->n && n2 == 2 * v->n);
    ENSURE((v->vertices = (double*)malloc(sizeof(double) * 2 * (size_t)v->n)) != NULL);
    ENSURE(vtk_values(f, v->binary, "int", 2L * v->n, v->vertices) == 0);
    snprintf(expect, sizeof expect, "POINT_DATA %d", v->n);
    ENSURE(vtk_line(f, line, sizeof line) && strcmp(line, expect) == 0);
    ENSURE(vtk_line(f, line, sizeof line) && sscanf(line, "FIELD FieldData %d", &v->arrays) == 1);
    ENSURE(v->arrays > 0 && v->arrays <= VTK_MAX_ARRAYS);
    for (k = 0; k < v->arrays; ++k) {
        vtk_array* a = &v->array[k];
        ENSURE(vtk_line(f, line, sizeof line) && sscanf(line, "%63s %d %d %15s", a->name, &a->components, &a->tuples, a->type) == 4);
        ENSURE(a->components >= 1 && a->components <= 9 && a->tuples == v->n);
        ENSURE((a->v = (double*)malloc(sizeof(double) * (size_t)a->components * (size_t)v->n)) != NULL);
        ENSURE(vtk_values(f, v->binary, a->type, (long)a->components * v->n, a->v) == 0);
    }
    ENSURE(fgetc(f) == EOF); /* nothing after the last array */
    fclose(f);
    return 0;
}

static long file_size(const char* path) {
    FILE* f = fopen(path, "rb");
    long size = -1;
    if (f && fseek(f, 0, SEEK_END) == 0) size = ftell(f);
    if (f) fclose(f);
    return size;
}

/* Whether a file value equals the state's (rounded to float with single precision): exactly
   for binary (the reals as stored), to the 9 significant digits of ASCII otherwise (5e-9
   relative, plus 1e-300 for zeros). */
static int vtk_same(double file, double state, int binary, int single) {
    if (single) state = (float)state;
    return binary ? file == state : fabs(file - state) <= 5e-9 * fabs(state) + 1e-300;
}

/* Checks a file against the world: the points, the vertices, and every array (names and order
   of the table, sizes, values by particle id; the stress tensor, when written, against the
   von Mises stress it implies). */
static int vtk_matches_world(const vtk_file* v, const sps_world* w, int with_stress, int single) {
    static const char* names[] = {"velocity", "displacement", "pressure", "density", "von_mises", "stress", "body", "id"};
    static const int comps[] = {3, 3, 1, 1, 1, 9, 1, 1};
    const int* ids = sps_world_particle_ids(w);
    int i, k, c, a = 0, m;
    ENSURE(v->n == sps_world_particle_count(w));
    ENSURE(v->arrays == 7 + with_stress);
    for (k = 0; k < 8; ++k) {
        if (k == 5 && !with_stress) continue;
        ENSURE(strcmp(v->array[a].name, names[k]) == 0 && v->array[a].components == comps[k]);
        ENSURE(strcmp(v->array[a].type, k >= 6 ? "int" : single ? "float" : "double") == 0);
        for (i = 0; i < v->n; ++i) {
            sps_particle_state ps;
            const double* x = v->array[a].v + (size_t)comps[k] * i;
            double want[9] = {0};
            ENSURE(sps_world_particle(w, ids[i], &ps) == SPS_OK);
            for (c = 0; c < 3; ++c) {
                if (k == 0) want[c] = ps.velocity[c];
                if (k == 1) want[c] = ps.displacement[c];
            }
            if (k == 2) want[0] = ps.pressure;
            if (k == 3) want[0] = ps.density;
            if (k == 4) want[0] = ps.von_mises;
            if (k == 6) want[0] = ps.body_index;
            if (k == 7) want[0] = ids[i];
            if (k == 5) { /* symmetric, and the von Mises stress of it is the von_mises array's */
                const double s6[6] = {x[0], x[1], x[2], x[4], x[5], x[8]};
                ENSURE(x[1] == x[3] && x[2] == x[6] && x[5] == x[7]);
                /* round-off of the formula; ASCII: its 9 digits; single precision: float's 6e-8 */
                ENSURE_NEAR(von_mises(s6, 3), ps.von_mises, (single ? 1e-6 : v->binary ? 1e-12 : 1e-8) * (fabs(ps.von_mises) + fabs(ps.pressure)));
                continue;
            }
            for (m = 0; m < comps[k]; ++m) ENSURE(vtk_same(x[m], want[m], v->binary, single && k < 6));
            if (k == 0) /* the points are the positions */
                for (c = 0; c < 3; ++c) ENSURE(vtk_same(v->points[3 * i + c], ps.position[c], v->binary, single));
        }
        ++a;
    }
    for (i = 0; i < v->n; ++i) ENSURE(v->vertices[2 * i] == 1 && v->vertices[2 * i + 1] == i);
    return 0;
}

/* The VTK writer, ASCII and binary, double and single precision, with and without the stress
   tensor: every array in one FIELD block (what VTK's legacy reader shows with its default
   settings), read back by the reader above and compared with the state; the binary file
   decodes to the state exactly and is smaller. Two bodies, one tracking the stress (the stress
   tensor holds its tau) and one not (-p I). */
static int test_vtk_writer(void) {
    sps_world* w = new_world(3, 0.01);
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.04, 0.03}, lo2[3] = {0.06, 0, 0}, hi2[3] = {0.09, 0.04, 0.03};
    char ascii[] = "/tmp/test_sphsolid_vtk_XXXXXX", binary[] = "/tmp/test_sphsolid_vtkb_XXXXXX";
    unsigned long long seed = 3;
    sps_vtk_options opt = sps_default_vtk_options();
    sps_body_def bd = sps_default_body_def();
    sps_body b, b2;
    vtk_file v;
    sps_real blo[3], bhi[3];
    long ascii_size, binary_size;
    int n, fd, k, variant;
    ENSURE(w);
    b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, &n);
    ENSURE(b.id != 0 && n == 60);
    bd.track_stress = 1;
    for (k = 0; k < 3; ++k) { blo[k] = lo2[k]; bhi[k] = hi2[k]; }
    ENSURE(sps_world_add_body(w, &bd, &b2) == SPS_OK && sps_body_add_box(w, b2, blo, bhi, NULL) == SPS_OK);
    ENSURE(sps_body_set_velocity(w, b, random_velocity, &seed) == SPS_OK);
    ENSURE(sps_body_set_velocity(w, b2, random_velocity, &seed) == SPS_OK);
    for (k = 0; k < 3; ++k) ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE((fd = mkstemp(ascii)) >= 0); close(fd);
    ENSURE((fd = mkstemp(binary)) >= 0); close(fd);
    for (variant = 0; variant < 4; ++variant) {
        opt.stress = variant & 1;
        opt.single_precision = variant >> 1;
        opt.binary = 0;
        ENSURE(sps_world_write_vtk_ex(w, ascii, &opt) == SPS_OK);
        ENSURE(vtk_read(ascii, &v) == 0 && !v.binary);
        ENSURE(vtk_matches_world(&v, w, opt.stress, opt.single_precision) == 0);
        vtk_free(&v);
        opt.binary = 1;
        ENSURE(sps_world_write_vtk_ex(w, binary, &opt) == SPS_OK);
        ENSURE(vtk_read(binary, &v) == 0 && v.binary);
        ENSURE(vtk_matches_world(&v, w, opt.stress, opt.single_precision) == 0);
        vtk_free(&v);
        ascii_size = file_size(ascii);
        binary_size = file_size(binary);
        printf("    stress %d, single %d: ASCII %ld bytes, binary %ld bytes (%.2f)\n", opt.stress, opt.single_precision, ascii_size,
               binary_size, (double)binary_size / ascii_size);
        ENSURE(binary_size > 0 && binary_size < ascii_size);
    }
    ENSURE(sps_world_write_vtk(w, ascii) == SPS_OK); /* the plain call: the default options */
    ENSURE(vtk_read(ascii, &v) == 0 && !v.binary && vtk_matches_world(&v, w, 0, 0) == 0);
    vtk_free(&v);
    remove(ascii);
    remove(binary);
    opt.binary = 2;
    ENSURE(sps_world_write_vtk_ex(w, ascii, &opt) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "binary = 2"));
    ENSURE(sps_world_write_vtk(w, "/nonexistent-dir/x.vtk") == SPS_ERR_IO);
    ENSURE(strstr(sps_world_last_error(w), "/nonexistent-dir/x.vtk") != NULL);
    sps_world_destroy(w);
    return 0;
}

static int count_char(const char* s, char c) {
    int k = 0;
    for (; *s; ++s) k += *s == c;
    return k;
}

/* The diagnostics CSV row has as many fields as the header, is not truncated, and its first
   field is the time. */
static int test_csv_row(void) {
    sps_world* w = new_world(2, 0.01);
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
    unsigned long long seed = 4;
    sps_diagnostics d;
    char row[1024];
    int len;
    sps_body b;
    ENSURE(w);
    b = add_block(w, SPS_SHEAR_ENO, lo, hi, NULL);
    ENSURE(sps_body_set_velocity(w, b, random_velocity, &seed) == SPS_OK);
    ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
    len = sps_diagnostics_csv_row(&d, row, sizeof row);
    ENSURE(len > 0 && len < (int)sizeof row);
    ENSURE(count_char(row, ',') == count_char(sps_diagnostics_csv_header(), ','));
    ENSURE(strncmp(sps_diagnostics_csv_header(), "time,", 5) == 0);
    ENSURE_NEAR(strtod(row, NULL), d.time, 1e-8 * d.time); /* printed with %.9g */
    ENSURE(strchr(row, '\n') == NULL);
    sps_world_destroy(w);
    return 0;
}

/* ============================================================================================ */
/* >>plasticity (J2)                                                                            */

/* sqrt(t:t) of a symmetric stress stored as xx xy xz yy yz zz */
static double stress_norm(const sps_real t[6]) {
    return sqrt((double)(t[0] * t[0] + t[3] * t[3] + t[5] * t[5] + 2 * (t[1] * t[1] + t[2] * t[2] + t[4] * t[4])));
}

/* A trial stress outside the yield surface is returned exactly onto it, along its own
   direction, and the dissipated energy density is what the return removed from tau:tau/(4G);
   a trial inside is left alone (factor 1, no plastic strain). Random deviatoric trials. */
static int test_j2_radial_return_on_surface(void) {
    const double G = 2.6e10, yield = 2.9e8, radius = sqrt(2.0 / 3.0) * yield;
    unsigned long long seed = 11;
    int k, a;
    for (k = 0; k < 200; ++k) {
        sps_real t[6], before[6], alpha = 0, dissipated, r;
        const double scale = (k % 2 ? 3.0 : 0.5) * radius; /* odd k: outside, even k: inside */
        double n0, n1, tr;
        for (a = 0; a < 6; ++a) t[a] = (sps_real)rnd(&seed);
        tr = (double)(t[0] + t[3] + t[5]) / 3; /* deviatoric, like the library's tau */
        t[0] -= (sps_real)tr; t[3] -= (sps_real)tr; t[5] -= (sps_real)tr;
        n0 = stress_norm(t);
        for (a = 0; a < 6; ++a) before[a] = t[a] = (sps_real)(t[a] * scale / n0);
        n0 = stress_norm(t);
        r = sps__radial_return(t, 3, (sps_real)G, (sps_real)yield, 0, &alpha, &dissipated);
        n1 = stress_norm(t);
        if (n0 > radius) {
            ENSURE_NEAR(n1, radius, 4e-16 * radius); /* on the surface up to a few roundings */
            ENSURE_NEAR(alpha, sqrt(2.0 / 3.0) * (n0 - radius) / (2 * G), 1e-15 * (double)alpha); /* d_gamma = f / 2G */
            ENSURE_NEAR(dissipated, (n0 * n0 - n1 * n1) / (4 * G), 1e-12 * (double)dissipated); /* the energy the return took */
            for (a = 0; a < 6; ++a) ENSURE_NEAR(t[a], r * before[a], 1e-15 * radius); /* radial: the direction is kept */
        } else {
            ENSURE(r == 1 && alpha == 0 && dissipated == 0);
            for (a = 0; a < 6; ++a) ENSURE(t[a] == before[a]);
        }
    }
    return 0;
}

/* Linear hardening: after a sequence of returns the surface has grown by kappa alpha,
   sqrt(t:t) = sqrt(2/3)(sigma_Y + kappa alpha) (ANG eq. 11 with f = 0), and each increment of
   alpha is sqrt(2/3) f/(2G + 2 kappa/3) of the trial's overshoot f. */
static int test_j2_hardening_raises_surface(void) {
    const double G = 4.3e10, yield = 4e8, kappa = 1e8;
    sps_real t[6] = {0, 0, 0, 0, 0, 0}, alpha = 0, dissipated;
    int k;
    for (k = 1; k <= 50; ++k) {
        const double surface = sqrt(2.0 / 3.0) * (yield + kappa * (double)alpha);
        double trial, expected_alpha;
        t[0] = (sps_real)(surface * (1 + 0.1 * k) / sqrt(1.5)); /* uniaxial deviator (2, -1, -1)/3 shape */
        t[3] = t[5] = -t[0] / 2;
        trial = stress_norm(t);
        expected_alpha = (double)alpha + sqrt(2.0 / 3.0) * (trial - surface) / (2 * G + 2 * kappa / 3);
        sps__radial_return(t, 3, (sps_real)G, (sps_real)yield, (sps_real)kappa, &alpha, &dissipated);
        ENSURE_NEAR(alpha, expected_alpha, 1e-14 * expected_alpha); /* a few roundings */
        ENSURE_NEAR(stress_norm(t), sqrt(2.0 / 3.0) * (yield + kappa * (double)alpha), 1e-15 * yield);
    }
    ENSURE(alpha > 0.01); /* the loop really hardened the material: kappa alpha > 1e6 Pa */
    return 0;
}

/* Uniaxial strain of a 3D J2 block, every particle's velocity prescribed as v_x = rate x
   (one constraint per lattice slab), through the whole step (velocity gradient, Jaumann update,
   return map). The closed form for the logarithmic strain eps = ln(1 + rate t), e = |eps|:
   elastic while 2 G e < sigma_Y, with von Mises stress q = 2 G e; then
   alpha = (2 G e - sigma_Y)/(3 G + kappa) and q = sigma_Y + kappa alpha (radial return is
   exact on this proportional path). The von Mises stress of sigma = -p I + tau is q whatever
   the pressure. Checked on the interior particles (2h from the surface: the corrected
   gradient is exact for a linear field there). */
static int test_j2_uniaxial_strain_closed_form(void) {
    const double dp = 0.01, rate = -2.0, E = 2e8, nu = 0.3, yield = 4e5, kappa = 2e7;
    const double G = E / (2 * (1 + nu));
    sps_world* w = new_world(3, dp);
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)(10 * dp), (sps_real)(10 * dp), (sps_real)(10 * dp)};
    int slab, n, id, checked = 0, plastic_seen = 0;
    double eps, e, q, alpha, worst_q = 0, worst_alpha = 0;
    sps_diagnostics d;
    ENSURE(w);
    bd.shear = SPS_SHEAR_OG;
    bd.material.kind = SPS_MATERIAL_J2;
    bd.material.density = 1000;
    bd.material.youngs_modulus = (sps_real)E;
    bd.material.poisson_ratio = (sps_real)nu;
    bd.material.yield_stress = (sps_real)yield;
    bd.material.hardening_modulus = (sps_real)kappa;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK);
    ENSURE(sps_body_add_box(w, b, lo, hi, &n) == SPS_OK && n == 1000);
    for (slab = 0; slab < 10; ++slab) {
        const sps_real x = (sps_real)((slab + 0.5) * dp), clo[3] = {x - (sps_real)(0.1 * dp), -1, -1}, chi[3] = {x + (sps_real)(0.1 * dp), 1, 1};
        const sps_real v[3] = {(sps_real)(rate * (double)x), 0, 0};
        ENSURE(sps_body_constrain_box(w, b, clo, chi, SPS_AXIS_ALL, v, NULL) == SPS_OK);
    }
    ENSURE(sps_world_advance(w, (sps_real)(0.01 / -rate), NULL, NULL) == SPS_OK); /* to eps = ln(0.99) */
    eps = log(1 + rate * (double)sps_world_time(w));
    e = fabs(eps);
    alpha = 2 * G * e > yield ? (2 * G * e - yield) / (3 * G + kappa) : 0;
    q = alpha > 0 ? yield + kappa * alpha : 2 * G * e;
    ENSURE(alpha > 0.002); /* the test strains to ~4 x the yield strain: plastic flow, hardening */
    for (id = 0; id < n; ++id) {
        sps_particle_state ps;
        sps_real x0[3];
        int a, inside = 1;
        ENSURE(sps_world_particle(w, id, &ps) == SPS_OK);
        for (a = 0; a < 3; ++a) {
            x0[a] = ps.position[a] - ps.displacement[a];
            inside = inside && x0[a] > 3 * dp && x0[a] < 7 * dp;
        }
        if (ps.plastic_strain > 0) ++plastic_seen;
        if (!inside) continue;
        ++checked;
        if (fabs(ps.von_mises - q) / q > worst_q) worst_q = fabs(ps.von_mises - q) / q;
        if (fabs(ps.plastic_strain - alpha) / alpha > worst_alpha) worst_alpha = fabs(ps.plastic_strain - alpha) / alpha;
        /* explicit time integration of the rate: O(rate dt) relative, rate dt = 2.5e-5 here */
        ENSURE_NEAR(ps.von_mises, q, 3e-5 * q);
        ENSURE_NEAR(ps.plastic_strain, alpha, 3e-4 * alpha); /* alpha is the small difference 2Ge - sigma_Y: 10x the error */
    }
    printf("    q %.6g Pa, alpha %.6g (closed form); worst interior errors %.2g, %.2g\n", q, alpha, worst_q, worst_alpha);
    ENSURE(checked == 64 && plastic_seen == n);
    ENSURE(sps_world_diagnostics(w, b, &d) == SPS_OK);
    ENSURE(d.plastic_work > 0 && d.max_plastic_strain >= alpha * (1 - 1e-3));
    sps_world_destroy(w);
    return 0;
}

/* The square Taylor bar of ANG 5.2.2 (B2) at L/dp = 6 (1080 particles), GNO-A, the set-up of
   examples/taylor_square.c (lowest particles 2h above a free-slip wall, v0 = 227 m/s), to 60 us
   after the impact: the bar stops by plastic flow and mushrooms. Bounds, not figures: the
   kinetic energy left is below 1 % of the start (0.3 % is left ringing elastically); the
   plastic work is above 80 % of the impact energy (the strain energy left is ~3 %); the account
   kinetic + strain + plastic work is within 10 % of the start (at L/dp = 6 nearly every
   particle is within 2h of a surface, where the corrected velocity gradient feeds the stress
   more than the stress force takes from the motion: +5 % here, +14 % at L/dp = 4); the bar
   shortens to between 0.6 and 0.9 of its length (Taylor's rigid-plastic estimate with
   rho v^2/sigma_Y = 1.15 gives 0.7-0.75); and the observation point s = (0.003, 0, 0) moves out
   beyond 3.3 mm (10 % spread) but not past Haider et al.'s converged 6.93 mm + 3 % (coarse SPH
   under-predicts the spread: ANG Table 4 rises from 5.21 mm at L/dp = 8 to 6.86 mm at 20). */
static void taylor_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)x; (void)user;
    v[0] = v[1] = 0;
    v[2] = -227;
}
static int test_j2_taylor_bar_coarse(void) {
    const double dp = 0.006 / 6, gap = (2 * 1.3 - 0.5) * dp, t_contact = gap / 227;
    sps_world* w = new_world(3, dp);
    sps_body_def bd = sps_default_body_def();
    sps_body bar;
    sps_observer s;
    const sps_real lo[3] = {-0.003, -0.003, (sps_real)gap}, hi[3] = {0.003, 0.003, (sps_real)(gap + 0.03)};
    const sps_real wall_point[3] = {0, 0, 0}, up[3] = {0, 0, 1}, obs[3] = {0.003, 0, (sps_real)gap};
    sps_diagnostics d0, d;
    sps_real u[3];
    const sps_real* z;
    double top = -1, bottom = 1, account, x_obs;
    int n, i;
    ENSURE(w);
    bd.shear = SPS_SHEAR_GNO_A;
    bd.material.kind = SPS_MATERIAL_J2;
    bd.material.density = 8930;
    bd.material.youngs_modulus = (sps_real)1.17e11;
    bd.material.poisson_ratio = (sps_real)0.35;
    bd.material.yield_stress = (sps_real)4e8;
    bd.material.hardening_modulus = (sps_real)1e8;
    ENSURE(sps_world_add_body(w, &bd, &bar) == SPS_OK);
    ENSURE(sps_body_add_box(w, bar, lo, hi, &n) == SPS_OK && n == 1080);
    ENSURE(sps_body_set_velocity(w, bar, taylor_velocity, NULL) == SPS_OK);
    ENSURE(sps_world_add_wall(w, wall_point, up, SPS_WALL_FREE_SLIP) == SPS_OK);
    ENSURE(sps_world_add_observer(w, bar, obs, &s) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, bar, &d0) == SPS_OK);
    ENSURE(sps_world_advance(w, (sps_real)(t_contact + 6e-5), NULL, NULL) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, bar, &d) == SPS_OK);
    ENSURE(sps_observer_read(w, s, u, NULL) == SPS_OK);
    z = sps_world_field(w, SPS_FIELD_POSITION_Z);
    for (i = 0; i < n; ++i) {
        if (z[i] > top) top = z[i];
        if (z[i] < bottom) bottom = z[i];
    }
    account = (double)(d.kinetic_energy + d.strain_energy + d.plastic_work);
    x_obs = 0.003 + (double)u[0];
    printf("    kinetic %.3g of %.4g J, plastic work %.4g J, account %+.2f%%, length %.2f of 30 mm, x_s %.3f mm, alpha max %.3f\n",
           (double)d.kinetic_energy, (double)d0.kinetic_energy, (double)d.plastic_work, 100 * (account / (double)d0.kinetic_energy - 1),
           1e3 * (top - bottom + dp), 1e3 * x_obs, (double)d.max_plastic_strain);
    ENSURE(d.kinetic_energy < 0.01 * d0.kinetic_energy);
    ENSURE(d.plastic_work > 0.8 * d0.kinetic_energy);
    ENSURE(fabs(account - (double)d0.kinetic_energy) < 0.1 * (double)d0.kinetic_energy);
    ENSURE(top - bottom + dp > 0.6 * 0.03 && top - bottom + dp < 0.9 * 0.03);
    ENSURE(x_obs > 0.0033 && x_obs < 1.03 * 0.00693);
    sps_world_destroy(w);
    return 0;
}

/* A J2 body's def is checked (yield stress, hardening modulus) and ENO / ENO-A on a J2 body are
   refused with the combination rule's message; an elastic body carries no plastic field. */
static int test_j2_bad_input(void) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    int first, count;
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
    ENSURE(w);
    bd.material.kind = SPS_MATERIAL_J2;
    bd.shear = SPS_SHEAR_GNO_A;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG); /* yield_stress defaults to 0 */
    ENSURE(strstr(sps_world_last_error(w), "material.yield_stress = 0"));
    bd.material.yield_stress = 1e4;
    bd.material.hardening_modulus = -1;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "material.hardening_modulus = -1"));
    bd.material.hardening_modulus = (sps_real)NAN;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG);
    bd.material.hardening_modulus = 0;
    bd.shear = SPS_SHEAR_ENO_A;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "J2 with shear = ENO or ENO-A"));
    bd.shear = SPS_SHEAR_ENO;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG);
    bd.shear = SPS_SHEAR_GNO_A;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK);
    bd.material.kind = SPS_MATERIAL_ELASTIC; /* the J2 fields are ignored by an elastic body */
    bd.material.hardening_modulus = -5;
    {
        sps_real blo[3], bhi[3];
        sps_body e;
        int a;
        ENSURE(sps_world_add_body(w, &bd, &e) == SPS_OK);
        for (a = 0; a < 3; ++a) { blo[a] = (sps_real)lo[a]; bhi[a] = (sps_real)hi[a]; }
        ENSURE(sps_body_add_box(w, b, blo, bhi, NULL) == SPS_OK);
        blo[0] += (sps_real)0.1; bhi[0] += (sps_real)0.1;
        ENSURE(sps_body_add_box(w, e, blo, bhi, NULL) == SPS_OK);
        ENSURE(sps_world_step(w) == SPS_OK);
        ENSURE(sps_body_field(w, b, "plastic_strain", NULL, &first, &count) != NULL && count > 0);
        ENSURE(sps_body_field(w, e, "plastic_strain", NULL, &first, &count) == NULL); /* no field for the elastic body */
    }
    sps_world_destroy(w);
    return 0;
}

/* ============================================================================================ */
/* >>contact                                                                                    */

static void velocity_x(const sps_real x[3], sps_real v[3], void* user) {
    (void)x;
    v[0] = *(const sps_real*)user; v[1] = 0; v[2] = 0;
}
static void velocity_down(const sps_real x[3], sps_real v[3], void* user) {
    (void)x;
    v[0] = 0; v[1] = -*(const sps_real*)user; v[2] = 0;
}

/* Two blocks thrown at each other (0.1 c0 each), threads as given: returns the world after
   t_end, or NULL. */
static sps_world* colliding_blocks(int threads, double t_end, sps_body* left, sps_body* right) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w = NULL;
    static const double lo1[3] = {0, 0, 0}, hi1[3] = {0.2, 0.15, 0}, lo2[3] = {0.23, 0.05, 0}, hi2[3] = {0.43, 0.2, 0};
    sps_real c0, v;
    wd.dim = 2; wd.dp = 0.01; wd.threads = threads; wd.log = quiet_log;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    *left = add_block(w, SPS_SHEAR_ENO_A, lo1, hi1, NULL);
    *right = add_block(w, SPS_SHEAR_ENO_A, lo2, hi2, NULL);
    if (!left->id || !right->id || sps_body_material_constants(w, *left, &c0, NULL, NULL) != SPS_OK) goto fail;
    v = (sps_real)(0.1 * c0);
    if (sps_body_set_velocity(w, *left, velocity_x, &v) != SPS_OK) goto fail;
    v = -v;
    if (sps_body_set_velocity(w, *right, velocity_x, &v) != SPS_OK) goto fail;
    if (sps_world_advance(w, (sps_real)t_end, NULL, NULL) != SPS_OK) goto fail;
    return w;
fail:
    printf("    %s\n", sps_world_last_error(w));
    sps_world_destroy(w);
    return NULL;
}

/* The smallest distance between particles of different bodies, in dp. */
static double min_gap(const sps_world* w, double dp) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    int n = sps_world_particle_count(w), i, j;
    double best = 1e30;
    sps_particle_state a, b;
    for (i = 0; i < n; ++i)
        for (j = i + 1; j < n; ++j) {
            double d2 = (double)(x[i] - x[j]) * (x[i] - x[j]) + (double)(y[i] - y[j]) * (y[i] - y[j]);
            if (d2 >= best * best * dp * dp) continue;
            sps_world_particle(w, sps_world_particle_ids(w)[i], &a);
            sps_world_particle(w, sps_world_particle_ids(w)[j], &b);
            if (a.body_index != b.body_index) best = sqrt(d2) / dp;
        }
    return best;
}

/* A step callback: the smallest gap between bodies so far (user: a double, in dp). */
static int track_gap(sps_world* w, void* user) {
    const double g = min_gap(w, 0.01);
    if (g < *(double*)user) *(double*)user = g;
    return 0;
}
/* A step callback: the lowest particle so far (user: a double). */
static int track_lowest(sps_world* w, void* user) {
    const sps_real* y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    int i;
    for (i = 0; i < sps_world_particle_count(w); ++i)
        if (y[i] < *(double*)user) *(double*)user = y[i];
    return 0;
}

/* Two blocks collide and bounce: the contact forces are antisymmetric pair forces, so the total
   linear momentum stays at its start (here 0 in x, by symmetry of the set-up not needed) to
   round-off, the bodies never come closer than half a spacing, and they separate again. */
static int test_contact_momentum(void) {
    sps_body left, right;
    sps_diagnostics d0, d1, dl;
    sps_world* w = colliding_blocks(1, 0, &left, &right);
    sps_body all = {0};
    double scale, gap;
    ENSURE(w);
    ENSURE(sps_world_diagnostics(w, all, &d0) == SPS_OK && sps_world_diagnostics(w, left, &dl) == SPS_OK);
    scale = fabs((double)dl.linear_momentum[0]); /* one body's momentum */
    gap = 1e30;
    ENSURE(sps_world_advance(w, 0.012, track_gap, &gap) == SPS_OK); /* they meet at about 0.005 s */
    ENSURE(sps_world_diagnostics(w, all, &d1) == SPS_OK);
    printf("    momentum x %.3g -> %.3g (scale %.3g), y %.3g; smallest gap %.3f dp\n", (double)d0.linear_momentum[0],
           (double)d1.linear_momentum[0], scale, (double)d1.linear_momentum[1], gap);
    ENSURE_NEAR(d1.linear_momentum[0], d0.linear_momentum[0], 1e-12 * scale); /* round-off of sums of ~1e5 pair forces */
    ENSURE_NEAR(d1.linear_momentum[1], d0.linear_momentum[1], 1e-12 * scale);
    ENSURE(gap > 0.5); /* the issue's bound: contact keeps the bodies apart */
    ENSURE(sps_world_diagnostics(w, left, &dl) == SPS_OK && dl.linear_momentum[0] < 0.5 * scale); /* the collision slowed it */
    sps_world_destroy(w);
    return 0;
}

/* Contact at 1 and 2 threads: bit for bit the same (the pair lists are in cell order and each
   particle's sum runs in list order). */
static int test_contact_determinism(void) {
    sps_body l1, r1, l2, r2;
    sps_world *a = colliding_blocks(1, 0.003, &l1, &r1), *b = colliding_blocks(2, 0.003, &l2, &r2);
    double *sa, *sb;
    int n, same;
    ENSURE(a && b);
    n = sps_world_particle_count(a);
    ENSURE(n > 512 && n == sps_world_particle_count(b)); /* above the size where a step uses threads */
    sa = snapshot(a); sb = snapshot(b);
    ENSURE(sa && sb);
    same = memcmp(sa, sb, sizeof(double) * 6 * (size_t)n) == 0;
    free(sa); free(sb);
    sps_world_destroy(a); sps_world_destroy(b);
    ENSURE(same);
    return 0;
}

/* A block dropped on a floor (a free-slip analytic wall) at 0.05 c0 stays above it and bounces;
   with no-slip it does not slide. */
static int test_wall_stops_body(void) {
    int slip;
    for (slip = 0; slip < 2; ++slip) {
        sps_world* w = new_world(2, 0.01);
        static const double lo[3] = {0, 0.05, 0}, hi[3] = {0.1, 0.15, 0};
        const sps_real floor_point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
        sps_body b;
        sps_diagnostics d;
        sps_real c0, v;
        int n;
        double lowest = 1e30;
        ENSURE(w);
        b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, &n);
        ENSURE(b.id && sps_body_material_constants(w, b, &c0, NULL, NULL) == SPS_OK);
        ENSURE(sps_world_add_wall(w, floor_point, up, (sps_wall_slip)slip) == SPS_OK);
        v = (sps_real)(0.05 * c0);
        ENSURE(sps_body_set_velocity(w, b, velocity_down, &v) == SPS_OK);
        ENSURE(sps_world_advance(w, (sps_real)(0.1 / (0.05 * c0)), track_lowest, &lowest) == SPS_OK); /* twice the time to reach it */
        ENSURE(sps_world_diagnostics(w, b, &d) == SPS_OK);
        printf("    %s: lowest particle %.3f dp above the floor, momentum y %.3g (start %.3g)\n", slip ? "no-slip" : "free-slip",
               lowest / 0.01, (double)d.linear_momentum[1], -(double)v * n * 0.1);
        ENSURE(lowest > 0.25 * 0.01); /* a quarter spacing: inside the wall's contact layer, never through it */
        ENSURE(d.linear_momentum[1] > 0); /* it bounced */
        sps_world_destroy(w);
    }
    return 0;
}

/* A wall body (SPS_MATERIAL_RIGID) made of particles: a block dropped on a rigid plate bounces
   off it and stays above it, the plate's particles do not move (at rest) or move exactly with
   their prescribed velocity, and a world of rigid bodies only is refused. */
static int test_rigid_wall_body(void) {
    int moving;
    for (moving = 0; moving < 2; ++moving) {
        sps_world* w = new_world(2, 0.01);
        sps_body_def rd = sps_default_body_def();
        sps_body block, plate;
        static const double lo[3] = {0.05, 0.05, 0}, hi[3] = {0.15, 0.15, 0};
        const sps_real plo[3] = {0, -0.04, 0}, phi[3] = {0.2, 0, 0};
        sps_real c0, v, vplate = moving ? (sps_real)-1.0 : 0, x_before, y_before;
        sps_particle_state ps;
        double lowest = 1e30;
        int n, first_plate;
        ENSURE(w);
        block = add_block(w, SPS_SHEAR_ENO_A, lo, hi, &n);
        rd.material.kind = SPS_MATERIAL_RIGID;
        ENSURE(block.id && sps_world_add_body(w, &rd, &plate) == SPS_OK && sps_body_add_box(w, plate, plo, phi, NULL) == SPS_OK);
        ENSURE(sps_body_material_constants(w, block, &c0, NULL, NULL) == SPS_OK);
        v = (sps_real)(0.05 * c0);
        ENSURE(sps_body_set_velocity(w, block, velocity_down, &v) == SPS_OK);
        ENSURE(sps_body_set_velocity(w, plate, velocity_down, &vplate) == SPS_OK); /* moving: up at 1 m/s */
        first_plate = n; /* ids: the block's first */
        ENSURE(sps_world_particle(w, first_plate, &ps) == SPS_OK);
        x_before = ps.position[0]; y_before = ps.position[1];
        ENSURE(sps_world_advance(w, (sps_real)(0.1 / (0.05 * c0)), track_lowest, &lowest) == SPS_OK);
        ENSURE(sps_world_particle(w, first_plate, &ps) == SPS_OK);
        printf("    %s plate: plate particle moved (%.3g, %.3g) m in %.4g s\n", moving ? "moving" : "resting",
               (double)(ps.position[0] - x_before), (double)(ps.position[1] - y_before), (double)sps_world_time(w));
        ENSURE(ps.position[0] == x_before && ps.velocity[1] == -vplate); /* its velocity is kept */
        ENSURE_NEAR(ps.position[1] - y_before, -vplate * sps_world_time(w), 1e-12); /* x += v dt: round-off only */
        {
            sps_diagnostics d;
            ENSURE(sps_world_diagnostics(w, block, &d) == SPS_OK);
            printf("    block momentum y %.3g (start %.3g)\n", (double)d.linear_momentum[1], -(double)v * n * 0.1);
            ENSURE(d.linear_momentum[1] > 0); /* it bounced off the plate */
        }
        sps_world_destroy(w);
    }
    {   /* rigid bodies only: refused with a message */
        sps_world* w = new_world(2, 0.01);
        sps_body_def rd = sps_default_body_def();
        sps_body plate;
        const sps_real plo[3] = {0, 0, 0}, phi[3] = {0.1, 0.1, 0};
        ENSURE(w);
        rd.material.kind = SPS_MATERIAL_RIGID;
        ENSURE(sps_world_add_body(w, &rd, &plate) == SPS_OK && sps_body_add_box(w, plate, plo, phi, NULL) == SPS_OK);
        ENSURE(sps_world_step(w) == SPS_ERR_STATE && error_names(w, "only rigid bodies") == 0);
        sps_world_destroy(w);
    }
    return 0;
}

/* Bad wall and contact input is refused with a message naming it. */
static int test_contact_bad_input(void) {
    sps_world* w = new_world(2, 0.01);
    sps_world* other = new_world(2, 0.01);
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
    const sps_real p[3] = {0, 0, 0}, zero[3] = {0, 0, 0}, up[3] = {0, 1, 0}, nan3[3] = {NAN, 0, 0};
    const sps_real blo[3] = {0, 0, 0}, bhi[3] = {1, 1, 0};
    sps_body a, b, foreign;
    ENSURE(w && other);
    a = add_block(w, SPS_SHEAR_ENO_A, lo, hi, NULL);
    foreign = add_block(other, SPS_SHEAR_ENO_A, lo, hi, NULL);
    ENSURE(sps_world_add_wall(w, p, zero, SPS_WALL_FREE_SLIP) == SPS_ERR_INVALID_ARG && error_names(w, "has length 0, allowed > 0") == 0);
    ENSURE(sps_world_add_wall(w, nan3, up, SPS_WALL_FREE_SLIP) == SPS_ERR_INVALID_ARG && error_names(w, "allowed finite") == 0);
    ENSURE(sps_world_add_wall(w, p, NULL, SPS_WALL_FREE_SLIP) == SPS_ERR_INVALID_ARG && error_names(w, "normal NULL") == 0);
    ENSURE(sps_world_add_wall(w, p, up, (sps_wall_slip)2) == SPS_ERR_INVALID_ARG && error_names(w, "slip = 2") == 0);
    ENSURE(sps_world_add_box_walls(w, bhi, blo, 0, SPS_WALL_FREE_SLIP) == SPS_ERR_INVALID_ARG && error_names(w, "lo < hi") == 0);
    ENSURE(sps_world_add_box_walls(w, blo, bhi, 16, SPS_WALL_FREE_SLIP) == SPS_ERR_INVALID_ARG && error_names(w, "open_faces = 16") == 0);
    ENSURE(sps_world_set_contact(w, a, a, 0) == SPS_ERR_INVALID_ARG && error_names(w, "two different bodies") == 0);
    ENSURE(sps_world_set_contact(w, a, foreign, 0) == SPS_ERR_INVALID_ARG && error_names(w, "not a body of this world") == 0);
    sps_world_destroy(other);
    b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, NULL);
    ENSURE(sps_world_set_contact(w, a, b, 2) == SPS_ERR_INVALID_ARG && error_names(w, "touch = 2") == 0);
    ENSURE(sps_world_set_contact(w, a, b, 0) == SPS_OK && sps_world_set_contact(w, a, b, 1) == SPS_OK);
    ENSURE(sps_world_set_contact(w, a, foreign, 1) == SPS_ERR_INVALID_ARG); /* a handle of a destroyed world */
    ENSURE(sps_world_add_box_walls(w, blo, bhi, SPS_FACE_Y_HI, SPS_WALL_NO_SLIP) == SPS_OK);
    sps_world_destroy(w);
    return 0;
}

/* ============================================================================================ */
/* >>observers                                                                                  */

static void uniform_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)x; (void)user;
    v[0] = 0.1; v[1] = -0.2; v[2] = 0;
}

/* A uniform translation: no pair sees a relative velocity, so nothing changes but the position;
   the Shepard observer (weights summing to one) reads the exact velocity and the common
   displacement, and the diagnostics give P = M v and E_k = M v^2/2 (round-off: 1e-12). */
static int test_uniform_translation(void) {
    sps_world* w = new_world(2, 0.01);
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.05, 0};
    sps_real x_obs[3] = {0.033, 0.021, 0}, u[3], v[3];
    sps_observer o;
    sps_diagnostics d;
    sps_particle_state ps;
    sps_body b;
    double M;
    int n, k;
    ENSURE(w);
    b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, &n);
    ENSURE(b.id && n == 50);
    ENSURE(sps_body_set_velocity(w, b, uniform_velocity, NULL) == SPS_OK);
    ENSURE(sps_world_add_observer(w, b, x_obs, &o) == SPS_OK);
    for (k = 0; k < 5; ++k) ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(sps_observer_read(w, o, u, v) == SPS_OK);
    ENSURE(sps_world_particle(w, 0, &ps) == SPS_OK);
    ENSURE_NEAR(v[0], 0.1, 1e-12);
    ENSURE_NEAR(v[1], -0.2, 1e-12);
    ENSURE_NEAR(u[0], ps.displacement[0], 1e-12);
    ENSURE_NEAR(u[1], ps.displacement[1], 1e-12);
    ENSURE_NEAR(ps.displacement[0], 0.1 * sps_world_time(w), 1e-12);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
    M = 1000 * 1e-4 * n;
    ENSURE_NEAR(d.linear_momentum[0], 0.1 * M, 1e-12 * M);
    ENSURE_NEAR(d.linear_momentum[1], -0.2 * M, 1e-12 * M);
    ENSURE_NEAR(d.kinetic_energy, 0.5 * M * 0.05, 1e-12 * M);
    ENSURE(d.hourglass < 1e-12); /* a translation is affine */
    sps_world_destroy(w);
    return 0;
}

/* A free block in uniform translation (as above) feels no internal force at all, so damping c
   must give exactly the exact decay v = v0 e^(-c t) (the kick multiplies by e^(-c dt) each
   sub-step; 1e-12: the round-off of some hundred factors) and a displacement v0 (1 - e^(-c t))/c
   to the trapezoidal drift's error, (c dt)^2/12 = 3e-7 relative (1e-6). With c dt = 180 the
   velocity only decays (the exact factor is stable for any c dt), where an explicit
   v -= c dt v would blow up. */
static int damped_block(double c, double t_end, sps_particle_state* ps, double* t) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def bd = sps_default_body_def();
    sps_real blo[3] = {0, 0, 0}, bhi[3] = {0.1, 0.05, 0};
    sps_body b;
    ENSURE(w);
    bd.damping = (sps_real)c;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, blo, bhi, NULL) == SPS_OK);
    ENSURE(sps_body_set_velocity(w, b, uniform_velocity, NULL) == SPS_OK);
    ENSURE(sps_world_advance(w, (sps_real)t_end, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_particle(w, 7, ps) == SPS_OK);
    *t = sps_world_time(w);
    sps_world_destroy(w);
    return 0;
}
static int test_damping_decays_velocity_exactly(void) {
    sps_particle_state ps;
    double t, decay;
    ENSURE(damped_block(10, 0.05, &ps, &t) == 0);
    decay = exp(-10 * t);
    printf("    c = 10/s, t = %.3f s: v_x = %.15f, exact %.15f\n", t, (double)ps.velocity[0], 0.1 * decay);
    ENSURE_NEAR(ps.velocity[0], 0.1 * decay, 1e-12 * 0.1);
    ENSURE_NEAR(ps.velocity[1], -0.2 * decay, 1e-12 * 0.2);
    ENSURE_NEAR(ps.displacement[0], 0.1 * (1 - decay) / 10, 1e-6 * 0.1 * (1 - decay) / 10); /* see above */
    ENSURE_NEAR(ps.displacement[1], -0.2 * (1 - decay) / 10, 1e-6 * 0.2 * (1 - decay) / 10);
    ENSURE(damped_block(1e6, 0.01, &ps, &t) == 0); /* c dt = 1e6 * 1.8e-4 */
    ENSURE(fabs(ps.velocity[0]) < 1e-30 && fabs(ps.velocity[1]) < 1e-30);
    ENSURE(fabs(ps.displacement[0]) < 0.1 * 2e-4); /* at most half a first sub-step's drift */
    return 0;
}

/* sps_body_set_acceleration on the free block at rest (no internal force: every particle gets the
   same acceleration): a(t) = (k t, -2) gives v = (k t^2/2, -2 t) to round-off, because the
   callback is evaluated at the middle of each sub-step (the midpoint rule integrates a linear
   a exactly; at the start of each sub-step v_x would be short by k t dt/2, 4e-3 relative here:
   the test's 1e-9 sees that). x, x0, v and t reach the callback (it counts its calls and checks
   x0 is a lattice point of the block). fn NULL removes it: v stays. Errors: invalid body, wall body. */
typedef struct { double k; long calls; int bad_arguments; } ramp_load;
static void ramp_acceleration(const sps_real x[3], const sps_real x0[3], const sps_real v[3], sps_real t, sps_real a[3], void* user) {
    ramp_load* r = (ramp_load*)user;
    r->calls++; /* one thread (new_world) */
    if (!(x0[0] > 0 && x0[0] < 0.1 && x0[1] > 0 && x0[1] < 0.05 && fabs(x[0] - x0[0]) < 0.01 && fabs(v[1]) < 1 && t >= 0 && a[0] == 0))
        r->bad_arguments = 1;
    a[0] = (sps_real)(r->k * t);
    a[1] = -2;
}
static int test_external_acceleration(void) {
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.05, 0};
    sps_world* w = new_world(2, 0.01);
    sps_body_def wall_def = sps_default_body_def();
    sps_body b, wall, none = {0};
    sps_particle_state ps;
    ramp_load ramp = {30, 0, 0};
    double t;
    sps_real wlo[3] = {0.3, 0, 0}, whi[3] = {0.4, 0.05, 0};
    int n;
    ENSURE(w);
    b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, &n);
    ENSURE(b.id && n == 50);
    ENSURE(sps_body_set_acceleration(w, b, ramp_acceleration, &ramp) == SPS_OK);
    ENSURE(sps_world_advance(w, 0.05, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_particle(w, 11, &ps) == SPS_OK);
    t = sps_world_time(w);
    printf("    t = %.3f s: v = (%.15f, %.15f), exact (%.15f, %.15f); %ld calls\n", t, (double)ps.velocity[0], (double)ps.velocity[1],
           ramp.k * t * t / 2, -2 * t, ramp.calls);
    ENSURE_NEAR(ps.velocity[0], ramp.k * t * t / 2, 1e-9 * ramp.k * t * t / 2); /* see above */
    ENSURE_NEAR(ps.velocity[1], -2 * t, 1e-12 * 2 * t);
    ENSURE(!ramp.bad_arguments && ramp.calls > 0 && ramp.calls % n == 0);
    ENSURE(sps_body_set_acceleration(w, b, NULL, NULL) == SPS_OK); /* removed */
    ENSURE(sps_world_advance(w, 0.06, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_particle(w, 11, &ps) == SPS_OK);
    ENSURE_NEAR(ps.velocity[0], ramp.k * t * t / 2, 1e-9 * ramp.k * t * t / 2);
    ENSURE(sps_body_set_acceleration(w, none, ramp_acceleration, &ramp) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "sps_body_set_acceleration: body handle 0"));
    ENSURE(sps_body_set_acceleration(NULL, b, ramp_acceleration, &ramp) == SPS_ERR_INVALID_ARG);
    wall_def.material.kind = SPS_MATERIAL_RIGID;
    ENSURE(sps_world_add_body(w, &wall_def, &wall) == SPS_OK && sps_body_add_box(w, wall, wlo, whi, NULL) == SPS_OK);
    ENSURE(sps_body_set_acceleration(w, wall, ramp_acceleration, &ramp) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "wall body"));
    ENSURE(sps_body_set_acceleration(w, wall, NULL, NULL) == SPS_OK); /* nothing to remove: fine */
    sps_world_destroy(w);
    return 0;
}

/* Growing a world that has already stepped: a second body and more particles are added after
   some steps (every per-particle array grows and the particles are re-sorted by body), and
   the state of the old particles is kept by stable id (bit-exact: adding moves no data value).
   A prescribed-velocity constraint holds its particles at exactly that velocity. */
static int test_add_after_step_and_constraints(void) {
    sps_world* w = new_world(2, 0.01);
    static const double lo1[3] = {0, 0, 0}, hi1[3] = {0.1, 0.05, 0}, lo2[3] = {0.3, 0, 0}, hi2[3] = {0.4, 0.1, 0};
    sps_real clo[3] = {-1, -1, 0}, chi[3] = {0.01, 1, 0}, cv[3] = {0.05, 0, 0}, more[6] = {0.105, 0.005, 0, 0.105, 0.015, 0};
    sps_real probe[3] = {0.351, 0.052, 0};
    sps_particle_state before, after;
    sps_body a, b;
    int na, nb, nc, k, id;
    ENSURE(w);
    a = add_block(w, SPS_SHEAR_ENO_A, lo1, hi1, &na);
    ENSURE(a.id && na == 50);
    ENSURE(sps_body_constrain_box(w, a, clo, chi, SPS_AXIS_X, cv, &nc) == SPS_OK && nc == 5); /* the first column, x = 0.005 */
    for (k = 0; k < 5; ++k) ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(sps_world_particle(w, 7, &before) == SPS_OK);
    b = add_block(w, SPS_SHEAR_ENO, lo2, hi2, &nb);
    ENSURE(b.id && nb == 100 && sps_body_index(w, b) == 1);
    ENSURE(sps_body_add_particles(w, a, 2, more, NULL) == SPS_OK);
    ENSURE(sps_world_particle_count(w) == na + nb + 2);
    ENSURE(sps_world_particle(w, 7, &after) == SPS_OK);
    ENSURE(memcmp(&before, &after, sizeof before) == 0); /* untouched by the adds */
    for (k = 0; k < 5; ++k) ENSURE(sps_world_step(w) == SPS_OK);
    for (id = 0; id < na; id += 10) { /* ids 0, 10, ... lie in the constrained first column */
        ENSURE(sps_world_particle(w, id, &after) == SPS_OK);
        ENSURE(after.velocity[0] == 0.05); /* held exactly */
    }
    id = sps_world_nearest_particle(w, b, probe);
    ENSURE(id >= na && id < na + nb);
    ENSURE(sps_world_particle(w, id, &after) == SPS_OK && after.body_index == 1);
    sps_world_destroy(w);
    return 0;
}

/* ============================================================================================ */
/* >>regressions (long; skipped with --quick)                                                   */

/* First period of the 2D cantilever at H/dp = 10, v_f = 0.05 (examples/plate2d.c), against ANG
   Table 1 at H/dp = 30 (ENO-A 0.269, ENO 0.279; thin-plate theory 0.254). Tolerance 5%: ANG
   Fig. 5 shows the H/dp = 10 deflection within a few % of H/dp = 40 (convergence order ~1.5). */
static int plate2d_period(sps_shear shear, sps_rotation rotation, double* period) {
    period_probe p;
    sps_world* w;
    memset(&p, 0, sizeof p);
    p.axis = 1;
    ENSURE((w = plate2d_build(10, shear, rotation, 0.05, 1, &p.obs)) != NULL);
    ENSURE(sps_world_advance(w, 0.32, period_on_step, &p) == SPS_OK);
    sps_world_destroy(w);
    ENSURE(p.n == 2); /* a full period before t = 0.32 */
    *period = p.crossing[1];
    return 0;
}

/* The first period of shear formulation `shear` within 5% of the paper's value at H/dp = 30. */
static int check_plate2d_period(sps_shear shear, sps_rotation rotation, const char* name, double paper) {
    double T;
    ENSURE(plate2d_period(shear, rotation, &T) == 0);
    printf("    %-5s H/dp = 10: T = %.4f s (paper H/dp = 30: %.3f, theory 0.254)\n", name, T, paper);
    ENSURE_NEAR(T, paper, 0.05 * paper); /* 5%, see plate2d_period */
    return 0;
}

static int test_plate2d_period_eno_a(void) { return check_plate2d_period(SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, "ENO-A", 0.269); }
static int test_plate2d_period_eno(void) { return check_plate2d_period(SPS_SHEAR_ENO, SPS_ROTATION_MEAN, "ENO", 0.279); }

/* SPS_ROTATION_PAIR keeps the shear forces of ENO-A per pair and carries them over every list
   rebuild (about 100 here): the period must be that of the mean rotation within 1% (measured
   0.37% shorter: the pair forces follow the local rotation of the bending plate, the mean matrix
   only the average one). Forces lost at the rebuilds would leave the plate without most of its
   shear stiffness (period far longer); forces given to the wrong pairs would stiffen it at random. */
static int test_plate2d_period_eno_a_pair(void) {
    double T_mean, T_pair;
    ENSURE(plate2d_period(SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, &T_mean) == 0);
    ENSURE(plate2d_period(SPS_SHEAR_ENO_A, SPS_ROTATION_PAIR, &T_pair) == 0);
    printf("    ENO-A H/dp = 10: T = %.4f s (mean rotation), %.4f s (pair)\n", T_mean, T_pair);
    ENSURE_NEAR(T_pair, T_mean, 0.01 * T_mean); /* 1%, see above */
    return 0;
}

/* Damping brings the cantilever to the beam's sag (examples/cantilever_sag.c): the A1 plate at
   H/dp = 10, at rest, under its weight in g = 1 m/s^2 (sag 1.3 % of L: linear beam theory
   holds) and damped at c = 2 omega_1 (thin plate: critical for the first mode), comes to rest
   by t = 0.6 s (the sag changes by less than 1e-3 of itself from 0.5 s, measured 1.4e-4;
   undamped it swings by its whole size) within 3 % of the Timoshenko beam's w at the end
   column (x = L - dp/2), plane strain, free length L from the holder's face. 3 %: measured +2.7 %, the softness of the
   plate's bending at 10 particles across, which its first period shows too ((0.2600 s /
   0.2565 s)^2 = +2.7 %); at H/dp = 20 it is within 2 % (bench/VALIDATION.md). The same load
   through sps_body_set_acceleration gives the same sag at t = 0.1 s, mid-swing (1e-9: only the
   order of the sums differs). */
static void downward_load(const sps_real x[3], const sps_real x0[3], const sps_real v[3], sps_real t, sps_real a[3], void* user) {
    (void)x, (void)x0, (void)v, (void)t;
    a[1] = (sps_real)-*(const double*)user;
}
/* The sag of the damped, loaded cantilever (load NULL: gravity) at each of the n times t. */
static int cantilever_sag(sps_acceleration_fn load, int n, const double* t, double* sag) {
    const double g = 1, c = 2 * (2 * PI / plate2d_analytical_period(PLATE2D_E, PLATE2D_NU, PLATE2D_RHO0)), dp = PLATE2D_H / 10;
    sps_observer tip;
    sps_world* w = plate2d_loaded(10, c, g, load, (void*)&g, 2, &tip);
    int k;
    ENSURE(w);
    for (k = 0; k < n; ++k) {
        ENSURE(sps_world_advance(w, (sps_real)t[k], NULL, NULL) == SPS_OK);
        sag[k] = plate2d_end_sag(w, dp);
    }
    sps_world_destroy(w);
    return 0;
}
static int test_damped_cantilever_sag(void) {
    const double dp = PLATE2D_H / 10, theory = plate2d_timoshenko_sag(PLATE2D_L - dp / 2, 1, PLATE2D_E, PLATE2D_NU, PLATE2D_RHO0, 1, 1);
    static const double t[3] = {0.1, 0.5, 0.6};
    double sag[3], sag_callback;
    ENSURE(cantilever_sag(NULL, 3, t, sag) == 0);
    printf("    H/dp = 10: sag %.6e m at t = 0.6 s (%.6e at 0.5 s), Timoshenko %.6e m: %+.2f%%\n", sag[2], sag[1], theory,
           100 * (sag[2] / theory - 1));
    ENSURE_NEAR(sag[2], sag[1], 1e-3 * sag[2]);   /* at rest, see above */
    ENSURE_NEAR(sag[2], theory, 0.03 * theory);   /* 3 %, see above */
    ENSURE(cantilever_sag(downward_load, 1, t, &sag_callback) == 0);
    ENSURE_NEAR(sag_callback, sag[0], 1e-9 * sag[0]); /* the same load, see above */
    return 0;
}

/* The hourglass indicator turns the papers' pictures into numbers: on the 2D plate (H/dp = 10,
   v_f = 0.05) SPH-OG zigzags at t = 0.012 and fractures at 0.021 (ENO Fig. 9), so by t = 0.1 its
   indicator must exceed 0.02 or its particles cluster (min spacing < 0.5 dp); the non-hourglass
   formulations bend smoothly. Thresholds: smooth bending measures about 1e-3 (bench/VALIDATION.md), a
   zigzag of a tenth of the spacing about 0.05. */
static int test_hourglass_og_breaks_others_do_not(void) {
    static const sps_shear shears[5] = {SPS_SHEAR_OG, SPS_SHEAR_ENO, SPS_SHEAR_ENO_A, SPS_SHEAR_GNO, SPS_SHEAR_GNO_A};
    int s;
    for (s = 0; s < 5; ++s) {
        sps_observer tip;
        sps_diagnostics d;
        sps_body all = {0};
        sps_world* w = plate2d_build(10, shears[s], SPS_ROTATION_MEAN, 0.05, 0, &tip);
        sps_result r;
        ENSURE(w != NULL);
        r = sps_world_advance(w, 0.05, NULL, NULL); /* OG zigzags from 0.012 s and fractures at 0.021 s (A1) */
        ENSURE(sps_world_diagnostics(w, all, &d) == SPS_OK);
        printf("    shear %d: %s, hourglass %.4f, min spacing %.3f dp\n", (int)shears[s], sps_result_string(r), (double)d.hourglass, (double)d.min_spacing);
        sps_world_destroy(w);
        if (shears[s] == SPS_SHEAR_OG) {
            ENSURE(r != SPS_OK || d.hourglass > 0.02 || d.min_spacing < 0.5);
        } else {
            ENSURE(r == SPS_OK);
            ENSURE(d.hourglass < 0.005 && d.min_spacing > 0.8);
        }
    }
    return 0;
}

/* First period of the 3D simply supported plate, H/dp = 3, mode (2, 2), ENO-A
   (examples/plate3d.c), against ANG Table 3 at the same resolution: 0.0149 s (theory 0.0133).
   Tolerance 3%: same resolution and scheme as the paper, so only the details of the set-up
   (support, observer interpolation, sampling at advection steps) differ.
   The observer sits at (L/4, W/4), an antinode of mode (2, 2): the plate centre is a node of
   this mode (sin(pi) = 0) and sees only round-off.
   With a support ring dp/2 outside the edges (the other --support choices of the example) the
   span is L + dp and the period 0.0158 s, +5.7%; the sides' own mid-plane particles, as ENO 6.2
   and ANG 5.1.2 describe the support, give 0.0151 s. */
static int test_plate3d_period_mode22(void) {
    plate3d_mode md = {2, 2}; /* observed at its first antinode (L/4, W/4, 0) */
    period_probe p;
    sps_world* w;
    memset(&p, 0, sizeof p);
    p.axis = 2;
    ENSURE((w = plate3d_build(3, md, 0, &p.obs)) != NULL);
    ENSURE(sps_world_advance(w, 0.025, period_on_step, &p) == SPS_OK); /* 1.9 x theory; stops at 2nd crossing */
    sps_world_destroy(w);
    ENSURE(p.n == 2);
    printf("    ENO-A H/dp = 3 mode (2,2): T = %.5f s (paper 0.0149, theory 0.0133)\n", p.crossing[1]);
    ENSURE_NEAR(p.crossing[1], 0.0149, 0.03 * 0.0149); /* 3%, see above */
    return 0;
}

/* ============================================================================================ */
/* >>realtime: sps_world_advance_frame                                                          */

typedef struct { unsigned long long seed; double amplitude; } random_field;
static void random_velocity_of(const sps_real x[3], sps_real v[3], void* user) {
    random_field* f = (random_field*)user;
    (void)x;
    v[0] = f->amplitude * rnd(&f->seed);
    v[1] = f->amplitude * rnd(&f->seed);
    v[2] = 0;
}

/* A free 2D block of 16 x 16 particles (default material, c0 = 28.9 m/s) with random velocities
   up to `speed`, the given stepping and sub-step cap per advection step; ca (may be NULL)
   counts its allocations. */
static sps_world* frame_world(sps_stepping stepping, int max_substeps, double speed, counting_allocator* ca) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w;
    sps_body b;
    random_field field;
    static const double lo[3] = {0, 0, 0}, hi[3] = {0.16, 0.16, 0};
    int n;
    wd.threads = 1; wd.log = quiet_log;
    wd.stepping = stepping;
    wd.max_substeps = max_substeps;
    if (ca) { wd.allocator.alloc = counting_alloc; wd.allocator.free = counting_free; wd.allocator.user = ca; }
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    field.seed = 7;
    field.amplitude = speed;
    b = add_block(w, SPS_SHEAR_ENO_A, lo, hi, &n);
    if (!b.id || n != 256 || sps_body_set_velocity(w, b, random_velocity_of, &field) != SPS_OK) { sps_world_destroy(w); return NULL; }
    return w;
}

static long acoustic_steps_of(sps_world* w) {
    sps_diagnostics d;
    sps_world_diagnostics(w, ALL_BODIES, &d);
    return d.acoustic_steps;
}

/* Both worlds hold the same positions and velocities, bit for bit, at the same time. */
static int same_state(const sps_world* a, const sps_world* b) {
    int n = sps_world_particle_count(a), same;
    double *sa = snapshot(a), *sb = snapshot(b);
    ENSURE(sa && sb && n == sps_world_particle_count(b));
    same = memcmp(sa, sb, sizeof(double) * 6 * (size_t)n) == 0;
    free(sa); free(sb);
    ENSURE(same);
    ENSURE(sps_world_time(a) == sps_world_time(b));
    return 0;
}

/* Bad arguments are rejected before anything moves, with a message naming the argument, its
   value and the allowed range (every broken one); an empty world reports its state error. */
static int test_frame_arguments_rejected(void) {
    sps_world* w = frame_world(SPS_STEPPING_DUAL, 100, 0.3, NULL);
    sps_world* empty = new_world(2, 0.01);
    sps_real covered = 5;
    ENSURE(w && empty);
    ENSURE(sps_world_advance_substeps(NULL, 10, 0, &covered) == SPS_ERR_INVALID_ARG);
    ENSURE(covered == 0);
    ENSURE(sps_world_advance_substeps(w, 0, 0, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "max_substeps = 0, allowed >= 1"));
    ENSURE(strstr(g_log_last, "max_substeps = 0")); /* also logged */
    ENSURE(sps_world_advance_substeps(w, -3, 0, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "max_substeps = -3"));
    ENSURE(sps_world_advance_substeps(w, 10, -1, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "wall_budget_s = -1, allowed 0 (no budget) or finite > 0"));
    ENSURE(sps_world_advance_substeps(w, 10, NAN, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "wall_budget_s = ") && strstr(sps_world_last_error(w), "nan"));
    ENSURE(sps_world_advance_substeps(w, 10, INFINITY, NULL) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "wall_budget_s = inf"));
    ENSURE(sps_world_advance_substeps(w, 0, -2, &covered) == SPS_ERR_INVALID_ARG); /* both named */
    ENSURE(strstr(sps_world_last_error(w), "max_substeps = 0") && strstr(sps_world_last_error(w), "wall_budget_s = -2"));
    ENSURE(covered == 0 && sps_world_time(w) == 0 && acoustic_steps_of(w) == 0);
    ENSURE(sps_world_advance_substeps(empty, 10, 0, &covered) == SPS_ERR_STATE);
    ENSURE(covered == 0 && sps_world_get_def(empty)->max_substeps == 100); /* the cap is restored */
    sps_world_destroy(w);
    sps_world_destroy(empty);
    return 0;
}

/* Single stepping: an advection step is one sub-step, so 10 frames of 3 sub-steps are the same
   30 steps as sps_world_step's, bit for bit. */
static int test_frame_single_stepping_equals_steps(void) {
    sps_world *a = frame_world(SPS_STEPPING_SINGLE, 100, 0.3, NULL), *b = frame_world(SPS_STEPPING_SINGLE, 100, 0.3, NULL);
    int k;
    ENSURE(a && b);
    for (k = 0; k < 10; ++k) ENSURE(sps_world_advance_substeps(a, 3, 0, NULL) == SPS_OK);
    for (k = 0; k < 30; ++k) ENSURE(sps_world_step(b) == SPS_OK);
    ENSURE(acoustic_steps_of(a) == 30 && acoustic_steps_of(b) == 30);
    ENSURE(same_state(a, b) == 0);
    sps_world_destroy(a);
    sps_world_destroy(b);
    return 0;
}

/* Dual stepping where every advection step runs its full cap of 4 sub-steps (speeds of 1 mm/s
   against c0 = 28.9 m/s: the advection bound allows ~10^4): frames of 8 sub-steps end on
   advection-step boundaries and equal sps_world_step bit for bit. Frames never allocate after
   the first step, and the def's cap is left as it was. */
static int test_frame_whole_advection_steps_equal_steps(void) {
    counting_allocator ca;
    sps_world *a, *b;
    sps_real covered, sum = 0;
    long calls_after_first;
    int k;
    memset(&ca, 0, sizeof ca); /* whatever fields the counting allocator has */
    a = frame_world(SPS_STEPPING_DUAL, 4, 1e-3, &ca);
    b = frame_world(SPS_STEPPING_DUAL, 4, 1e-3, NULL);
    ENSURE(a && b);
    ENSURE(sps_world_advance_substeps(a, 8, 0, &covered) == SPS_OK);
    sum += covered;
    calls_after_first = ca.calls;
    for (k = 1; k < 10; ++k) {
        ENSURE(sps_world_advance_substeps(a, 8, 0, &covered) == SPS_OK);
        sum += covered;
    }
    ENSURE(ca.calls == calls_after_first); /* no allocation in frames */
    for (k = 0; k < 20; ++k) ENSURE(sps_world_step(b) == SPS_OK);
    ENSURE(acoustic_steps_of(a) == 80 && acoustic_steps_of(b) == 80);
    ENSURE(same_state(a, b) == 0);
    ENSURE(sps_world_get_def(a)->max_substeps == 4);
    ENSURE_NEAR(sum, sps_world_time(a), 1e-12 * sps_world_time(a)); /* rounding of the differences */
    sps_world_destroy(a);
    sps_world_destroy(b);
    return 0;
}

/* Frames that cut advection steps (the 2D plate at H/dp = 8, about 10 sub-steps per advection
   step, frames of 7): exactly 7 sub-steps per frame, covered adds up to the time, a frame of one
   sub-step covers that sub-step's dt, and the motion is the one of sps_world_advance to the same
   time: the cuts only rebuild the neighbour lists earlier, so the sub-steps differ in size by
   the change of the maximum speed within an advection step. Tolerance 1e-4 of the deflection
   (measured 2e-6). */
static int test_frame_cuts_advection_steps(void) {
    sps_observer tip_a, tip_b;
    sps_world *a = plate2d_build(8, SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0.05, 1, &tip_a);
    sps_world *b = plate2d_build(8, SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0.05, 1, &tip_b);
    sps_real covered, sum = 0, ua[3], ub[3];
    sps_diagnostics d;
    int k;
    ENSURE(a && b);
    for (k = 0; k < 30; ++k) {
        ENSURE(sps_world_advance_substeps(a, 7, 0, &covered) == SPS_OK);
        ENSURE(covered > 0);
        sum += covered;
    }
    ENSURE(acoustic_steps_of(a) == 210);
    ENSURE_NEAR(sum, sps_world_time(a), 1e-12 * sps_world_time(a)); /* rounding of the differences */
    for (k = 0; k < 5; ++k) {
        ENSURE(sps_world_advance_substeps(a, 1, 0, &covered) == SPS_OK);
        ENSURE(sps_world_diagnostics(a, ALL_BODIES, &d) == SPS_OK);
        ENSURE_NEAR(covered, d.dt_acoustic, 1e-9 * d.dt_acoustic); /* t + dt - t: rounding of t */
    }
    ENSURE(sps_world_get_def(a)->max_substeps == 100);
    ENSURE(sps_world_advance(b, sps_world_time(a), NULL, NULL) == SPS_OK);
    ENSURE(sps_observer_read(a, tip_a, ua, NULL) == SPS_OK && sps_observer_read(b, tip_b, ub, NULL) == SPS_OK);
    printf("    t = %.6f s: tip deflection %.9f (frames) vs %.9f (advance)\n", (double)sps_world_time(a), (double)ua[1], (double)ub[1]);
    ENSURE(fabs(ub[1]) > 1e-4); /* the plate has moved */
    ENSURE_NEAR(ua[1], ub[1], 1e-4 * fabs(ub[1])); /* see above */
    sps_world_destroy(a);
    sps_world_destroy(b);
    return 0;
}

/* The wall budget: with a budget too small for anything, the frame still runs its first
   advection step, exactly as sps_world_step would (bit for bit), and stops there; a 0.05 s
   budget stops a frame of 10^7 sub-steps (about 30 min of work here) early, after some. */
static int test_frame_wall_budget(void) {
    sps_observer tip_a, tip_b;
    sps_world *a = plate2d_build(8, SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0.05, 1, &tip_a);
    sps_world *b = plate2d_build(8, SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0.05, 1, &tip_b);
    sps_real covered;
    double t0;
    long before;
    ENSURE(a && b);
    ENSURE(sps_world_advance_substeps(a, 1000, 1e-9, &covered) == SPS_OK);
    ENSURE(sps_world_step(b) == SPS_OK);
    ENSURE(same_state(a, b) == 0);
    ENSURE(covered == sps_world_time(a));
    before = acoustic_steps_of(a);
    t0 = wall_seconds();
    ENSURE(sps_world_advance_substeps(a, 10000000, 0.05, &covered) == SPS_OK);
    printf("    0.05 s budget: %ld sub-steps, %.4f s simulated in %.3f s\n", acoustic_steps_of(a) - before, (double)covered, wall_seconds() - t0);
    ENSURE(covered > 0 && acoustic_steps_of(a) > before && acoustic_steps_of(a) - before < 10000000);
    ENSURE(wall_seconds() - t0 < 5); /* 100 x the budget: room for a busy machine's scheduling */
    sps_world_destroy(a);
    sps_world_destroy(b);
    return 0;
}

/* ============================================================================================ */
/* >>restart                                                                                    */

/* A small 2D scene for the restart tests (dp 5 mm, c0 = 28.9 m/s): a block of 40 x 20
   particles swirling at random (0.3 m/s), clamped at its left end, with an observer; with
   `contact`, a second block thrown at it at 2 m/s, within the contact range from the start,
   and a floor wall under both, with gravity. */
typedef struct restart_scene {
    sps_shear shear;
    sps_rotation rotation;
    int frozen_geometry, keep_last_good_state, contact, threads;
    double shift; /* [m] the first block moved along x */
    int tl_kind;  /* 0: updated Lagrangian; else the material kind of total-Lagrangian blocks */
    double damage_strain; /* total Lagrangian: the damage threshold (0: none) */
} restart_scene;

static void velocity_minus_x(const sps_real x[3], sps_real v[3], void* user) {
    (void)x; (void)user;
    v[0] = -2; v[1] = 0; v[2] = 0;
}

static sps_world* restart_build(const restart_scene* sc, int threads, sps_observer* obs) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body a, b;
    unsigned long long seed = 11;
    const sps_real lo[3] = {sc->shift, 0, 0}, hi[3] = {0.2 + sc->shift, 0.1, 0}, clo[3] = {-1, -1, -1}, chi[3] = {0.01, 1, 1};
    const sps_real blo[3] = {0.21, 0.03, 0}, bhi[3] = {0.3, 0.1, 0}, floor_point[3] = {0, -0.002, 0}, up[3] = {0, 1, 0};
    const sps_real x_obs[3] = {0.15, 0.05, 0};
    wd.dim = 2; wd.dp = 0.005; wd.threads = threads; wd.log = quiet_log;
    wd.max_substeps = 20; /* more configuration updates (sorts, list rebuilds) per sub-step: cheaper */
    wd.frozen_geometry = sc->frozen_geometry;
    wd.keep_last_good_state = sc->keep_last_good_state;
    if (sc->contact) wd.gravity[1] = -9.81;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    bd.shear = sc->shear;
    bd.rotation = sc->rotation;
    bd.track_stress = 1;
    if (sc->tl_kind) {
        bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
        bd.material.kind = (sps_material_kind)sc->tl_kind;
        bd.material.yield_stress = 2e3; /* J2: yields in the swirl */
        bd.damage_strain = sc->damage_strain;
    }
    if (sps_world_add_body(w, &bd, &a) != SPS_OK || sps_body_add_box(w, a, lo, hi, NULL) != SPS_OK ||
        sps_body_set_velocity(w, a, random_velocity, &seed) != SPS_OK ||
        sps_body_constrain_box(w, a, clo, chi, SPS_AXIS_ALL, NULL, NULL) != SPS_OK || sps_world_add_observer(w, a, x_obs, obs) != SPS_OK)
        goto fail;
    if (sc->contact && (sps_world_add_body(w, &bd, &b) != SPS_OK || sps_body_add_box(w, b, blo, bhi, NULL) != SPS_OK ||
                        sps_body_set_velocity(w, b, velocity_minus_x, NULL) != SPS_OK ||
                        sps_world_add_wall(w, floor_point, up, SPS_WALL_FREE_SLIP) != SPS_OK))
        goto fail;
    return w;
fail:
    printf("    %s\n", sps_world_last_error(w));
    sps_world_destroy(w);
    return NULL;
}

/* Everything a run's result is: per particle by id its position, velocity, density, pressure and
   von Mises stress (which holds the shear stress), then the time, the step counters and the
   observer. Caller frees. */
static double* restart_result(const sps_world* w, sps_observer obs) {
    const int n = sps_world_particle_count(w);
    double* s = (double*)malloc(sizeof(double) * (9 * (size_t)n + 9));
    sps_diagnostics d;
    sps_real u[3], v[3];
    int id, a;
    if (!s) return NULL;
    for (id = 0; id < n; ++id) {
        sps_particle_state ps;
        sps_world_particle(w, id, &ps);
        for (a = 0; a < 3; ++a) { s[9 * id + a] = ps.position[a]; s[9 * id + 3 + a] = ps.velocity[a]; }
        s[9 * id + 6] = ps.density; s[9 * id + 7] = ps.pressure; s[9 * id + 8] = ps.von_mises;
    }
    sps_world_diagnostics((sps_world*)w, ALL_BODIES, &d); /* lists valid after a step: changes nothing */
    sps_observer_read(w, obs, u, v);
    s[9 * n] = sps_world_time(w); s[9 * n + 1] = (double)d.acoustic_steps; s[9 * n + 2] = (double)d.advection_steps;
    for (a = 0; a < 3; ++a) { s[9 * n + 3 + a] = u[a]; s[9 * n + 6 + a] = v[a]; }
    return s;
}

/* The diagnostics that read the neighbour lists and the state: bit for bit the same. */
static int same_diagnostics(const sps_diagnostics* a, const sps_diagnostics* b) {
    return a->time == b->time && a->kinetic_energy == b->kinetic_energy && a->strain_energy == b->strain_energy &&
           a->hourglass == b->hourglass && a->min_spacing == b->min_spacing && a->angular_momentum[2] == b->angular_momentum[2] &&
           a->acoustic_steps == b->acoustic_steps && a->advection_steps == b->advection_steps && a->dt_acoustic == b->dt_acoustic;
}

/* Runs `before` advection steps of the scene at 3 - sc->threads threads, saves, runs `after`
   more; rebuilds the scene at sc->threads, restores, checks the diagnostics at the restore
   point and runs `after` steps: the two results must be the same bit for bit. */
static int restart_round_trip(const restart_scene* sc, int before, int after) {
    char path[] = "/tmp/test_sphsolid_restart_XXXXXX";
    sps_observer obs, obs2;
    sps_diagnostics d_saved, d_restored;
    sps_world *w = restart_build(sc, 3 - sc->threads, &obs), *w2;
    double *first, *second;
    int fd, k, n, same;
    ENSURE(w);
    for (k = 0; k < before; ++k) ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE((fd = mkstemp(path)) >= 0);
    close(fd);
    ENSURE(sps_world_save(w, path) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d_saved) == SPS_OK);
    if (sc->damage_strain > 0) { /* the saved state holds damage: a restore that lost it would change the stresses after it */
        double damage = 0;
        for (k = 0; k < sps_world_particle_count(w); ++k) {
            sps_particle_state ps;
            sps_world_particle(w, k, &ps);
            damage += ps.damage;
        }
        printf("    total damage at the save %.4g\n", damage);
        ENSURE(damage > 0);
    }
    for (k = 0; k < after; ++k) ENSURE(sps_world_step(w) == SPS_OK);
    n = sps_world_particle_count(w);
    first = restart_result(w, obs);
    sps_world_destroy(w);
    ENSURE((w2 = restart_build(sc, sc->threads, &obs2)) != NULL);
    if (sps_world_restore(w2, path) != SPS_OK) printf("    %s\n", sps_world_last_error(w2));
    ENSURE(sps_world_time(w2) == d_saved.time && d_saved.time > 0);
    ENSURE(sps_world_diagnostics(w2, ALL_BODIES, &d_restored) == SPS_OK);
    ENSURE(same_diagnostics(&d_saved, &d_restored)); /* the lists came back too */
    for (k = 0; k < after; ++k) ENSURE(sps_world_step(w2) == SPS_OK);
    second = restart_result(w2, obs2);
    sps_world_destroy(w2);
    remove(path);
    ENSURE(first && second);
    same = memcmp(first, second, sizeof(double) * (9 * (size_t)n + 9)) == 0;
    if (!same) printf("    the restored run differs from the uninterrupted one (t = %.17g vs %.17g)\n", first[9 * n], second[9 * n]);
    free(first); free(second);
    ENSURE(same);
    return 0;
}

/* Save after some steps, go on; rebuild, restore, go on: the same result bit for bit, for the
   formulations whose state differs (ENO-A's mean rotation and spin, GNO-A's velocity gradient,
   the pair forces of SPS_ROTATION_PAIR), contact with a wall, frozen geometry and the last good
   state, total-Lagrangian bodies (their reference lists rebuilt, Neo-Hookean with contact; J2
   with its plastic metric; Saint Venant-Kirchhoff with damage); saved at 1 thread and restored at 2, and once the other way round. */
static int test_restart_round_trip(void) {
    static const restart_scene scenes[] = {
        {SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0, 0, 0, 2, 0, 0, 0},
        {SPS_SHEAR_GNO_A, SPS_ROTATION_MEAN, 0, 0, 0, 2, 0, 0, 0},
        {SPS_SHEAR_ENO_A, SPS_ROTATION_PAIR, 0, 0, 0, 2, 0, 0, 0},
        {SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0, 0, 1, 2, 0, 0, 0},
        {SPS_SHEAR_GNO_A, SPS_ROTATION_MEAN, 1, 0, 1, 2, 0, 0, 0},
        {SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0, 1, 0, 1, 0, 0, 0},
        {SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0, 0, 1, 2, 0, SPS_MATERIAL_NEO_HOOKEAN, 0}, /* total Lagrangian, with contact */
        {SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0, 0, 0, 1, 0, SPS_MATERIAL_J2, 0},
        /* damage that grows in the swirl (threshold 2e-3), with the last good state */
        {SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0, 1, 0, 2, 0, SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF, 2e-3},
    };
    int k;
    for (k = 0; k < (int)(sizeof scenes / sizeof scenes[0]); ++k) {
        printf("    scene %d\n", k);
        if (restart_round_trip(&scenes[k], 5, 5)) return 1;
    }
    return 0;
}

/* keep_last_good_state: the copy of the last configuration update comes back too. A particle
   thrown beyond the escape distance right after the save stops the next step at its
   configuration update, and the world is rolled back to that copy: the same state, bit for
   bit, in the saved world and in the restored one. */
static int test_restart_last_good_state(void) {
    char path[] = "/tmp/test_sphsolid_restart_XXXXXX";
    const restart_scene sc = {SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0, 1, 0, 1, 0, 0, 0};
    const sps_real far[3] = {1e3, 0, 0};
    sps_observer obs, obs2;
    sps_world *w = restart_build(&sc, 1, &obs), *w2;
    double *first, *second;
    int fd, k, n, same;
    ENSURE(w);
    for (k = 0; k < 4; ++k) ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE((fd = mkstemp(path)) >= 0);
    close(fd);
    ENSURE(sps_world_save(w, path) == SPS_OK);
    ENSURE(sps_world_set_particle(w, 7, far, NULL) == SPS_OK);
    ENSURE(sps_world_step(w) == SPS_ERR_UNSTABLE && strstr(sps_world_last_error(w), "escaped"));
    n = sps_world_particle_count(w);
    first = restart_result(w, obs);
    sps_world_destroy(w);
    ENSURE((w2 = restart_build(&sc, 2, &obs2)) != NULL);
    ENSURE(sps_world_restore(w2, path) == SPS_OK);
    ENSURE(sps_world_set_particle(w2, 7, far, NULL) == SPS_OK);
    ENSURE(sps_world_step(w2) == SPS_ERR_UNSTABLE);
    second = restart_result(w2, obs2);
    sps_world_destroy(w2);
    remove(path);
    ENSURE(first && second);
    same = memcmp(first, second, sizeof(double) * (9 * (size_t)n + 9)) == 0;
    free(first); free(second);
    ENSURE(same);
    return 0;
}

/* Copies the first `bytes` of from into to (all of it when bytes < 0), with the byte at `flip`
   (if >= 0) changed. */
static int copy_file_part(const char* from, const char* to, long bytes, long flip) {
    FILE *in = fopen(from, "rb"), *out = fopen(to, "wb");
    long k;
    int c;
    if (!in || !out) { if (in) fclose(in); if (out) fclose(out); return 1; }
    for (k = 0; (bytes < 0 || k < bytes) && (c = fgetc(in)) != EOF; ++k) fputc(k == flip ? c ^ 0x5a : c, out);
    fclose(in);
    return fclose(out) != 0;
}

static int restore_refused(const restart_scene* sc, const char* path, sps_result expected, const char* needle) {
    sps_observer obs;
    sps_world* w = restart_build(sc, 1, &obs);
    sps_result r;
    ENSURE(w);
    r = sps_world_restore(w, path);
    if (r != expected || !strstr(sps_world_last_error(w), needle))
        printf("    restore gave %d '%s', expected %d with '%s'\n", (int)r, sps_world_last_error(w), (int)expected, needle);
    ENSURE(r == expected);
    ENSURE(strstr(sps_world_last_error(w), needle) != NULL);
    ENSURE(sps_world_time(w) == 0); /* the state is the rebuilt one: a step from it works */
    ENSURE(sps_world_step(w) == SPS_OK);
    sps_world_destroy(w);
    return 0;
}

/* A restart file meets only the scene it was saved from, whole: another scene (a body's count,
   its shear, its particles moved), a truncated or damaged file, a file of another kind and a
   missing one are refused with a message, and the world is left as it was. */
static int test_restart_refused(void) {
    char path[] = "/tmp/test_sphsolid_restart_XXXXXX", part[] = "/tmp/test_sphsolid_part_XXXXXX";
    restart_scene sc = {SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0, 0, 0, 1, 0, 0, 0}, other = sc;
    sps_observer obs;
    sps_world* w = restart_build(&sc, 1, &obs);
    long size;
    FILE* f;
    int fd, k;
    ENSURE(w);
    ENSURE((fd = mkstemp(path)) >= 0); close(fd);
    ENSURE((fd = mkstemp(part)) >= 0); close(fd);
    ENSURE(sps_world_save(w, path) == SPS_ERR_STATE && strstr(sps_world_last_error(w), "step first"));
    ENSURE(sps_world_save(w, NULL) == SPS_ERR_INVALID_ARG && sps_world_save(NULL, path) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_world_restore(w, NULL) == SPS_ERR_INVALID_ARG && sps_world_restore(NULL, path) == SPS_ERR_INVALID_ARG);
    for (k = 0; k < 3; ++k) ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(sps_world_save(w, "/nonexistent-dir/x.restart") == SPS_ERR_IO && strstr(sps_world_last_error(w), "/nonexistent-dir/x.restart"));
    ENSURE(sps_world_save(w, path) == SPS_OK);
    ENSURE(sps_world_restore(w, path) == SPS_OK); /* into the world it came from: nothing changes */
    sps_world_destroy(w);
    other.shear = SPS_SHEAR_GNO_A;
    ENSURE(restore_refused(&other, path, SPS_ERR_STATE, "shear = 1 in the file, 5 in this world") == 0);
    other = sc;
    other.contact = 1; /* gravity on, a second body and a wall: the def item is named first */
    ENSURE(restore_refused(&other, path, SPS_ERR_STATE, "gravity[1] = 0 in the file") == 0);
    other = sc;
    other.shift = 0.0005; /* the same counts and models, the particles a tenth of dp away */
    ENSURE(restore_refused(&other, path, SPS_ERR_STATE, "reference positions") == 0);
    f = fopen(path, "rb");
    ENSURE(f && fseek(f, 0, SEEK_END) == 0 && (size = ftell(f)) > 1000);
    fclose(f);
    ENSURE(copy_file_part(path, part, size / 2, -1) == 0);
    ENSURE(restore_refused(&sc, part, SPS_ERR_IO, "truncated") == 0);
    ENSURE(copy_file_part(path, part, 20, -1) == 0);
    ENSURE(restore_refused(&sc, part, SPS_ERR_IO, "truncated") == 0);
    ENSURE(copy_file_part(path, part, -1, size - 100) == 0);
    ENSURE(restore_refused(&sc, part, SPS_ERR_IO, "checksum") == 0);
    ENSURE(copy_file_part(path, part, -1, 3) == 0);
    ENSURE(restore_refused(&sc, part, SPS_ERR_INVALID_ARG, "not a sphsolid restart file") == 0);
    remove(part);
    ENSURE(restore_refused(&sc, part, SPS_ERR_IO, part) == 0); /* missing */
    remove(path);
    return 0;
}

/* ============================================================================================ */


/* ---- fluids and transport corrections (FLUIDS, TRANSPORT) ---- */

static sps_real hydrostatic_04(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(1000 * 9.81 * (0.4 - (double)x[1]));
}

/* A water column 0.4 m deep at rest in a tank of analytic walls, started hydrostatic, stays at
   rest: the pressure at mid-depth stays that of the column and no current builds up. */
static int test_fluid_hydrostatic_rest(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body water, all = {0};
    sps_diagnostics d;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.4, 0.4, 0}, tank_hi[3] = {0.4, 1, 0};
    const sps_real *y, *p;
    const double g = 9.81, depth = 0.4, v_ref = sqrt(2 * g * depth), dp = 0.02;
    double p_mid = 0;
    int i, n, mid = 0;
    wd.dim = 2;
    wd.dp = dp;
    wd.threads = 1;
    wd.gravity[1] = -g;
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.sound_speed = 10 * v_ref;
    ENSURE(sps_world_add_box_walls(w, lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) == SPS_OK);
    ENSURE(sps_world_add_body(w, &bd, &water) == SPS_OK);
    ENSURE(sps_body_add_box(w, water, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_set_pressure(w, water, hydrostatic_04, NULL) == SPS_OK);
    ENSURE(sps_world_advance(w, 1, NULL, NULL) == SPS_OK); /* about 70 acoustic crossings of the column */
    ENSURE(sps_world_diagnostics(w, all, &d) == SPS_OK);
    y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    p = sps_world_field(w, SPS_FIELD_PRESSURE);
    n = sps_world_particle_count(w);
    for (i = 0; i < n; ++i)
        if (fabs(y[i] - depth / 2) < dp) { p_mid += p[i]; ++mid; }
    ENSURE(mid > 0);
    p_mid /= mid;
    printf("    mid-depth pressure %.1f Pa (column %.1f), max speed %.3g m/s (%.2g sqrt(2 g H))\n", p_mid, 1000 * g * depth / 2,
           (double)d.max_speed, (double)d.max_speed / v_ref);
    /* 4 %: the column rings after its start (measured: mid-depth pressure within +5.5 % / -2 %
       over the first second at dp = 0.02, 20 particles deep) */
    ENSURE_NEAR(p_mid, 1000 * g * depth / 2, 0.04 * 1000 * g * depth / 2);
    /* 3 % of the speed a fall from the surface gives: the ripple (measured <= 2 %), no current
       (a particle leaking through a corner reached 30 % before the walls' backstop) */
    ENSURE(d.max_speed < 0.03 * v_ref);
    sps_world_destroy(w);
    return 0;
}

/* ---- granular media (GRANULAR) ---- */

/* The C5 soil (rho0 1850, E 1.8 MPa, nu 0.3, c 5 kPa, phi 25 deg). */
static sps_material_def c5_soil(void) {
    sps_material_def m = sps_default_material_def();
    m.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    m.density = 1850;
    m.youngs_modulus = 1.8e6;
    m.poisson_ratio = 0.3;
    m.cohesion = 5e3;
    m.friction_angle = 25;
    return m;
}

/* f = alpha_phi I1 + sqrt(J2) - k_c of a stress (xx xy xz yy yz zz) on the cone of m. */
static double yield_function(const sps_real s[6], const sps_material_def* m) {
    const sps__yield_cone c = sps__yield_cone_of(m);
    const double i1 = (double)(s[0] + s[3] + s[5]);
    sps_real dev[6];
    int a;
    for (a = 0; a < 6; ++a) dev[a] = (sps_real)(s[a] - (a == 0 || a == 3 || a == 5 ? i1 / 3 : 0));
    return (double)c.alpha_phi * i1 + sqrt(0.5 * (double)sps__sym_contract(dev, dev)) - (double)c.k_c;
}

/* The Drucker-Prager return mapping puts a trial outside the cone onto it (f = 0), keeps the
   direction of its deviator, leaves a trial inside alone, and moves a tensile trial beyond the
   apex to the apex (I1 = k_c / alpha_phi, zero deviator). Random trials, with and without
   cohesion. */
static int test_drucker_prager_return_on_cone(void) {
    unsigned long long seed = 5;
    int k, a, outside = 0, inside = 0, apex = 0;
    for (k = 0; k < 400; ++k) {
        sps_material_def m = c5_soil();
        sps__yield_cone c;
        sps_real t[6], before[6];
        double scale = (k % 4 + 0.2) * 2e4, f0, i1, dev_before[6], dev_after[6], ratio = 0;
        if (k % 3 == 0) m.cohesion = 0;
        c = sps__yield_cone_of(&m);
        for (a = 0; a < 6; ++a) before[a] = t[a] = (sps_real)(scale * rnd(&seed));
        f0 = yield_function(t, &m);
        i1 = (double)(t[0] + t[3] + t[5]);
        sps__drucker_prager_return(t, &c);
        if (f0 <= 0) { /* inside: untouched, up to the roundings of taking the mean out and back in */
            for (a = 0; a < 6; ++a) ENSURE_NEAR(t[a], before[a], 1e-15 * 4 * scale);
            ++inside;
            continue;
        }
        /* on the cone: f = 0 up to roundings of stresses of scale 1e5 Pa */
        ENSURE(fabs(yield_function(t, &m)) < 1e-9 * scale);
        if (c.alpha_phi > 0 && i1 > (double)(c.k_c / c.alpha_phi)) { /* beyond the apex: at the apex */
            ENSURE_NEAR(t[0] + t[3] + t[5], c.k_c / c.alpha_phi, 1e-12 * scale);
            ENSURE(fabs((double)(t[1])) < 1e-9 * scale && fabs((double)(t[0] - t[3])) < 1e-9 * scale);
            ++apex;
            continue;
        }
        for (a = 0; a < 6; ++a) { /* the deviator scaled, not turned */
            const int d = a == 0 || a == 3 || a == 5;
            dev_before[a] = (double)before[a] - (d ? i1 / 3 : 0);
            dev_after[a] = (double)t[a] - (d ? i1 / 3 : 0);
            if (fabs(dev_before[a]) > fabs(ratio * dev_before[a]) && fabs(dev_before[a]) > 1e-3 * scale) ratio = dev_after[a] / dev_before[a];
        }
        ENSURE(ratio > 0 && ratio < 1);
        for (a = 0; a < 6; ++a) ENSURE_NEAR(dev_after[a], ratio * dev_before[a], 1e-12 * scale);
        ENSURE_NEAR(t[0] + t[3] + t[5], i1, 1e-12 * scale); /* the mean stress kept */
        ++outside;
    }
    ENSURE(outside > 20 && inside > 20 && apex > 20); /* the random trials reached all three cases */
    return 0;
}

/* The granular limiter (eta = 20 d) dissipates between approaching particles only: beta = 0
   for every separating pair (u = v_ij . e_ij >= 0), 1 from an approach of c0 / eta on, linear
   between. */
static int test_granular_limiter_off_in_expansion(void) {
    const double c0 = 28.5, eta = 20 * 2;
    int k;
    for (k = -100; k <= 100; ++k) {
        const double u = k * 0.01 * c0 / 10, beta = (double)sps__riemann_limiter((sps_real)u, (sps_real)(eta / c0));
        if (u >= 0) ENSURE(beta == 0);
        else ENSURE_NEAR(beta, fmin(-eta * u / c0, 1), 1e-15);
    }
    return 0;
}

/* A block of cohesive soil, 2 m wide and 1 m deep, in a box of no-slip walls under gravity,
   started from its geostatic stress, stays at rest: the vertical stress at mid-depth stays
   -rho0 g H/2 and no particle moves. */
static int test_granular_block_at_rest(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body soil, all = {0};
    sps_diagnostics d;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {2, 1, 0}, box_hi[3] = {2, 2, 0};
    const double g = 9.8, depth = 1, dp = 0.05, rho0 = 1850, v_ref = sqrt(2 * g * depth);
    const sps_real *y, *p, *tau;
    double sigma_mid = 0;
    int i, n, first, mid = 0;
    wd.dim = 2;
    wd.dp = dp;
    wd.threads = 1;
    wd.gravity[1] = -g;
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.material = c5_soil();
    ENSURE(sps_world_add_box_walls(w, lo, box_hi, SPS_FACE_Y_HI, SPS_WALL_NO_SLIP) == SPS_OK);
    ENSURE(sps_world_add_body(w, &bd, &soil) == SPS_OK);
    ENSURE(sps_body_add_box(w, soil, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_set_geostatic_stress(w, soil, (sps_real)depth, 0) == SPS_OK);
    ENSURE(sps_world_advance(w, 0.5, NULL, NULL) == SPS_OK); /* about 14 crossings of the block by sound */
    ENSURE(sps_world_diagnostics(w, all, &d) == SPS_OK);
    y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    p = sps_world_field(w, SPS_FIELD_PRESSURE);
    tau = sps_body_field(w, soil, "shear_stress", NULL, &first, &n);
    ENSURE(tau && first == 0 && n == sps_world_particle_count(w)); /* the only body */
    for (i = 0; i < n; ++i)
        if (fabs(y[i] - depth / 2) < 0.6 * dp) { sigma_mid += tau[6 * i + 3] - p[i]; ++mid; }
    ENSURE(mid > 0);
    sigma_mid /= mid;
    printf("    mid-depth vertical stress %.1f Pa (geostatic %.1f), max speed %.3g m/s (%.2g sqrt(2 g H)), max plastic strain %.3g\n",
           sigma_mid, -rho0 * g * depth / 2, (double)d.max_speed, (double)d.max_speed / v_ref, (double)d.max_plastic_strain);
    /* 5 % ("a few percent"; measured +0.7 %, 3.7 % before the divergence's lattice scale;
       test_granular_block_holds_shape holds 2 % over 2 s) */
    ENSURE_NEAR(sigma_mid, -rho0 * g * depth / 2, 0.05 * rho0 * g * depth / 2);
    /* 1 % of the speed a fall from the surface gives: at rest (measured 0.55 %, the zigzag mode) */
    ENSURE(d.max_speed < 0.01 * v_ref);
    sps_world_destroy(w);
    return 0;
}

/* Bad granular input is refused with a message naming the field, its value and the range. */
static int test_granular_bad_input(void) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def d = sps_default_body_def(), bad;
    ENSURE(w);
    d.material = c5_soil();
    bad = d; bad.material.cohesion = -1;         ENSURE(rejects_body_def(w, &bad, "material.cohesion = -1") == 0);
    bad = d; bad.material.friction_angle = 90;   ENSURE(rejects_body_def(w, &bad, "material.friction_angle = 90") == 0);
    bad = d; bad.material.dilatancy_angle = 30;  ENSURE(rejects_body_def(w, &bad, "material.dilatancy_angle = 30") == 0);
    bad = d; bad.stress_diffusion = 2;           ENSURE(rejects_body_def(w, &bad, "stress_diffusion = 2") == 0);
    bad = d; bad.shear = SPS_SHEAR_GNO_A; bad.rotation = SPS_ROTATION_PAIR;
    ENSURE(rejects_body_def(w, &bad, "rotation = pair") == 0);
    ENSURE(sps_body_set_geostatic_stress(w, (sps_body){0}, 1, 0) == SPS_ERR_INVALID_ARG);
    { /* a soil body in a world without gravity, and an elastic one: both refused, with the reason */
        sps_body soil, plate;
        sps_body_def elastic = sps_default_body_def();
        const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
        ENSURE(sps_world_add_body(w, &d, &soil) == SPS_OK && sps_body_add_box(w, soil, lo, hi, NULL) == SPS_OK);
        ENSURE(sps_world_add_body(w, &elastic, &plate) == SPS_OK && sps_body_add_box(w, plate, lo, hi, NULL) == SPS_OK);
        ENSURE(sps_body_set_geostatic_stress(w, soil, 1, 0) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "gravity"));
        ENSURE(sps_body_set_geostatic_stress(w, plate, 1, 0) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "material.kind"));
    }
    sps_world_destroy(w);
    return 0;
}

/* Two particles at one point (a cluster collapsed by tensile instability within an advection
   step: the neighbour search leaves such pairs out, the pair geometry of the sub-steps meets
   them) have no direction between them: the pair is taken as a padding slot is, e = 0 and
   dW = 0 (it was 0/0, a NaN, and stopped the C7 flume), and the diagnostics stay finite. */
static int test_coincident_particles_stay_finite(void) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def bd = sps_default_body_def();
    sps_body b, all = {0};
    sps_diagnostics d;
    const sps_real twins[6] = {0.02, 0.03, 0, 0.02, 0.03, 0};
    sps__pair_geometry e;
    ENSURE(w);
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK);
    ENSURE(sps_body_add_particles(w, b, 2, twins, NULL) == SPS_OK);
    e = sps__pair(w, 0, 0, 1, 2, SPS__GEO_WENDLAND);
    ENSURE(e.ex == 0 && e.ey == 0 && e.ez == 0 && e.dw == 0 && e.dw_r == 0 && sps__finite(e.r));
    ENSURE(sps_world_diagnostics(w, all, &d) == SPS_OK);
    ENSURE(sps__finite(d.hourglass));
    sps_world_destroy(w);
    return 0;
}

static void swirl(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = (sps_real)(3 * sin(7 * x[1]) + 1);
    v[1] = (sps_real)(2 * cos(5 * x[0]) - x[0]);
}

/* A fluid block in a swirling flow with TVF and with UTVF (and an elastic one with UTVF): the
   corrections move particles but not their velocities, so linear momentum is kept to round-off. */
static int test_transport_keeps_linear_momentum(void) {
    static const int kinds[3][2] = {{SPS_MATERIAL_FLUID, SPS_TRANSPORT_TVF}, {SPS_MATERIAL_FLUID, SPS_TRANSPORT_UTVF},
                                    {SPS_MATERIAL_ELASTIC, SPS_TRANSPORT_UTVF}};
    int k;
    for (k = 0; k < 3; ++k) {
        double moved = 0, scale = 0, dP = 0;
        int pass, i, a, n = 0;
        sps_real* before = NULL;
        for (pass = 0; pass < 2; ++pass) { /* without, then with the correction */
            sps_world* w = new_world(2, 0.05);
            sps_body_def bd = sps_default_body_def();
            sps_body b, all = {0};
            sps_diagnostics d0, d1;
            sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 0.6, 0};
            const sps_real* x;
            ENSURE(w);
            bd.material.kind = (sps_material_kind)kinds[k][0];
            bd.material.sound_speed = 100;
            bd.transport = pass ? (sps_transport)kinds[k][1] : SPS_TRANSPORT_NONE;
            ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK);
            ENSURE(sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
            ENSURE(sps_body_set_velocity(w, b, swirl, NULL) == SPS_OK);
            ENSURE(sps_world_diagnostics(w, all, &d0) == SPS_OK);
            ENSURE(sps_world_advance(w, 0.02, NULL, NULL) == SPS_OK);
            ENSURE(sps_world_diagnostics(w, all, &d1) == SPS_OK);
            n = sps_world_particle_count(w);
            x = sps_world_field(w, SPS_FIELD_POSITION_X);
            if (!pass) {
                before = (sps_real*)malloc(sizeof(sps_real) * (size_t)n);
                ENSURE(before);
                memcpy(before, x, sizeof(sps_real) * (size_t)n);
            } else {
                const sps_real* m = sps_world_field(w, SPS_FIELD_MASS);
                for (i = 0; i < n; ++i) {
                    moved = fmax(moved, fabs(x[i] - before[i]));
                    scale += m[i] * 4;
                }
                for (a = 0; a < 2; ++a) dP = fmax(dP, fabs(d1.linear_momentum[a] - d0.linear_momentum[a]));
            }
            sps_world_destroy(w);
        }
        free(before);
        printf("    %s + %s: largest shift %.3g dp, momentum change %.2g of sum m |v|\n", kinds[k][0] ? "fluid" : "elastic",
               kinds[k][1] == SPS_TRANSPORT_TVF ? "TVF" : "UTVF", moved / 0.05, dP / scale);
        ENSURE(moved > 1e-6 * 0.05); /* the correction did move particles */
        ENSURE(dP < 1e-12 * scale);  /* round-off of a sum of ~240 momenta */
    }
    return 0;
}

static sps_real crushing(const sps_real x[3], void* user) {
    (void)x, (void)user;
    return -2e9;
}

static int test_fluid_bad_input(void) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def d = sps_default_body_def(), bad;
    sps_body b;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
    ENSURE(w);
    d.material.kind = SPS_MATERIAL_FLUID;
    d.material.sound_speed = 10;
    bad = d; bad.material.sound_speed = 0;    ENSURE(rejects_body_def(w, &bad, "material.sound_speed = 0") == 0);
    bad = d; bad.material.sound_speed = NAN;  ENSURE(rejects_body_def(w, &bad, "material.sound_speed = nan") == 0);
    bad = d; bad.material.viscosity = -1;     ENSURE(rejects_body_def(w, &bad, "material.viscosity = -1") == 0);
    bad = d; bad.material.density = 0;        ENSURE(rejects_body_def(w, &bad, "material.density = 0") == 0);
    bad = d; bad.transport = (sps_transport)7; ENSURE(rejects_body_def(w, &bad, "transport = 7") == 0);
    bad = d; bad.transport_coefficient = 2;   ENSURE(rejects_body_def(w, &bad, "transport_coefficient = 2") == 0);
    bad = sps_default_body_def(); bad.material.kind = SPS_MATERIAL_RIGID; bad.transport = SPS_TRANSPORT_UTVF;
    ENSURE(rejects_body_def(w, &bad, "transport = TVF or UTVF with material.kind = rigid") == 0);
    ENSURE(sps_world_add_body(w, &d, &b) == SPS_OK);
    ENSURE(sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_set_pressure(w, b, crushing, NULL) == SPS_ERR_INVALID_ARG); /* K = 1e5 Pa: rho would be negative */
    ENSURE(strstr(sps_world_last_error(w), "pressure = -2e+09 Pa") != NULL);
    ENSURE(sps_body_set_pressure(w, b, NULL, NULL) == SPS_ERR_INVALID_ARG);
    sps_world_destroy(w);
    return 0;
}

/* ============================================================================================ */
/* >>total-Lagrangian: the solver of TL sections 2-3 (chapter >>solver: total Lagrangian)        */

/* A total-Lagrangian box of n^dim particles (spacing 1e-3) of body def bd (solver set here);
   held = 1 constrains every particle to v = 0 (its positions, once set, stay). */
static sps_world* tl_box_of(int dim, sps_body_def bd, int n, int held, sps_body* out) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {n * 1e-3, n * 1e-3, dim == 3 ? n * 1e-3 : 0}, all_lo[3] = {-1, -1, -1}, all_hi[3] = {1, 1, 1};
    wd.dim = dim; wd.dp = 1e-3; wd.log = quiet_log; wd.threads = 1;
    bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    if (sps_world_add_body(w, &bd, out) != SPS_OK || sps_body_add_box(w, *out, lo, hi, NULL) != SPS_OK ||
        (held && sps_body_constrain_box(w, *out, all_lo, all_hi, SPS_AXIS_ALL, NULL, NULL) != SPS_OK)) {
        sps_world_destroy(w);
        return NULL;
    }
    return w;
}

/* The box of tl_box_of with the default material (rho0 1000, E 1e6, nu 0.3) of law kind and
   hourglass coefficient alpha. */
static sps_world* tl_box(int dim, sps_material_kind kind, double alpha, int n, int held, sps_body* out) {
    sps_body_def bd = sps_default_body_def();
    bd.material.kind = kind;
    bd.hourglass_alpha = alpha;
    return tl_box_of(dim, bd, n, held, out);
}

/* Moves every particle of w to x = A X + c (A row-major 3 x 3). */
static void tl_map(sps_world* w, const double A[9], const double c[3]) {
    int id, a, k;
    for (id = 0; id < sps_world_particle_count(w); ++id) {
        sps_particle_state s;
        sps_real x[3] = {0, 0, 0}, X[3];
        sps_world_particle(w, id, &s);
        for (a = 0; a < 3; ++a) X[a] = s.position[a] - s.displacement[a];
        for (a = 0; a < 3; ++a) {
            x[a] = (sps_real)c[a];
            for (k = 0; k < 3; ++k) x[a] += (sps_real)(A[3 * a + k] * X[k]);
        }
        sps_world_set_particle(w, id, x, NULL);
    }
}

/* The reference state: F = I, zero stress and zero force at every particle (boundaries included:
   the corrected gradients are first-order complete, TL eq. 16). */
static int test_tl_reference_state(void) {
    int dim;
    for (dim = 2; dim <= 3; ++dim) {
        sps_body b;
        sps_world* w = tl_box(dim, dim == 2 ? SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF : SPS_MATERIAL_NEO_HOOKEAN, 50, dim == 2 ? 8 : 5, 0, &b);
        const sps_real *F, *tau, *acc;
        int nc, first, count, i, k;
        double ferr = 0, smax = 0, amax = 0;
        ENSURE(w != NULL);
        ENSURE(sps_world_step(w) == SPS_OK);
        F = sps_body_field(w, b, "deformation_gradient", &nc, &first, &count);
        ENSURE(F != NULL && nc == 9 && count == sps_world_particle_count(w));
        tau = sps_body_field(w, b, "shear_stress", &nc, &first, &count);
        ENSURE(tau != NULL);
        for (i = 0; i < count; ++i) {
            for (k = 0; k < 9; ++k) ferr = fmax(ferr, fabs(F[9 * i + k] - (k % 4 == 0)));
            for (k = 0; k < 6; ++k) smax = fmax(smax, fabs(tau[6 * i + k]));
        }
        for (k = 0; k < dim; ++k) {
            static const char* names[3] = {"pressure_acceleration_x", "pressure_acceleration_y", "pressure_acceleration_z"};
            acc = sps_world_field_by_name(w, names[k], NULL);
            ENSURE(acc != NULL);
            for (i = 0; i < count; ++i) amax = fmax(amax, fabs(acc[first + i]));
        }
        printf("    %dD: max |F - I| %.2e, max |stress| %.2e Pa, max |a| %.2e m/s^2\n", dim, ferr, smax, amax);
        ENSURE(ferr < 1e-12);  /* round-off of sums of O(1) terms */
        ENSURE(smax < 1e-5);   /* E 1e6 Pa times the round-off of F */
        ENSURE(amax < 1e-2);   /* that stress over rho0 dp (1 m/s^2 per Pa): round-off */
        sps_world_destroy(w);
    }
    return 0;
}

/* A homogeneous stretch x = diag(l1, l2, l3) X gives F = diag(l) at every particle and the
   closed-form Cauchy stress sigma = F S F^T / J: Saint Venant-Kirchhoff S = lambda tr(E) I + 2 mu E
   (TL eq. 19), Neo-Hookean sigma = (mu (F F^T - I) + lambda ln J I)/J (TL eq. 44). */
static int test_tl_homogeneous_stretch(void) {
    int dim;
    for (dim = 2; dim <= 3; ++dim) {
        int law;
        for (law = 0; law < 2; ++law) {
            const sps_material_kind kind = law ? SPS_MATERIAL_NEO_HOOKEAN : SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF;
            const double E = 1e6, nu = 0.3, mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
            const double l[3] = {1.2, 0.9, dim == 3 ? 1.1 : 1}, A[9] = {l[0], 0, 0, 0, l[1], 0, 0, 0, l[2]}, c[3] = {1e-3, -2e-3, 0};
            double J = l[0] * l[1] * l[2], trE = 0, sigma[3], err = 0, ferr = 0;
            sps_body b;
            sps_world* w = tl_box(dim, kind, 50, dim == 2 ? 8 : 5, 1, &b);
            const sps_real *F, *tau, *p;
            int nc, first, count, i, a;
            ENSURE(w != NULL);
            for (a = 0; a < 3; ++a) trE += 0.5 * (l[a] * l[a] - 1);
            for (a = 0; a < 3; ++a)
                sigma[a] = law ? (mu * (l[a] * l[a] - 1) + lambda * log(J)) / J
                               : l[a] * l[a] * (lambda * trE + mu * (l[a] * l[a] - 1)) / J;
            tl_map(w, A, c);
            ENSURE(sps_world_step(w) == SPS_OK);
            F = sps_body_field(w, b, "deformation_gradient", &nc, &first, &count);
            tau = sps_body_field(w, b, "shear_stress", &nc, &first, &count);
            p = sps_world_field_by_name(w, "pressure", NULL);
            ENSURE(F && tau && p);
            for (i = 0; i < count; ++i) {
                for (a = 0; a < 9; ++a) ferr = fmax(ferr, fabs(F[9 * i + a] - A[a]));
                for (a = 0; a < dim; ++a) err = fmax(err, fabs(tau[6 * i + (a == 0 ? 0 : a == 1 ? 3 : 5)] - p[first + i] - sigma[a]));
            }
            printf("    %dD %s: sigma = (%.6g, %.6g, %.6g) Pa, max |F - F_exact| %.2e, max |sigma - exact| %.2e Pa\n", dim,
                   law ? "Neo-Hookean" : "SVK", sigma[0], sigma[1], sigma[2], ferr, err);
            ENSURE(ferr < 1e-11);  /* first-order completeness: exact for an affine map up to round-off (7e-13 in 3D) */
            ENSURE(err < 1e-6 * E); /* the closed form, up to the round-off of F times E */
            ENSURE(fabs(sigma[0]) > 1e4); /* the stretch is large enough to test anything */
            sps_world_destroy(w);
        }
    }
    return 0;
}

/* The hourglass force of TL eq. 32 vanishes for an affine deformation (rotation, stretch and
   shear): the accelerations with alpha = 50 and alpha = 0 agree to round-off; and it does not
   vanish when one particle is moved off the affine field (so the comparison can fail). */
static int test_tl_hourglass_affine(void) {
    const double A[9] = {1.05 * cos(0.3), -0.9 * sin(0.3) + 0.1, 0, 1.05 * sin(0.3), 0.9 * cos(0.3), 0, 0, 0, 1}, c[3] = {2e-3, 1e-3, 0};
    double diff_affine = 0, diff_kicked = 0, scale = 0, restoring = 0;
    int kicked;
    for (kicked = 0; kicked < 2; ++kicked) {
        double a_of[2][2][64];
        int run;
        for (run = 0; run < 2; ++run) {
            sps_body b;
            sps_world* w = tl_box(2, SPS_MATERIAL_NEO_HOOKEAN, run ? 50 : 0, 8, 1, &b);
            const int* ids;
            int i, a;
            ENSURE(w != NULL);
            tl_map(w, A, c);
            if (kicked) { /* particle 27 (inside) moved by 0.1 dp */
                sps_particle_state s;
                sps_world_particle(w, 27, &s);
                s.position[0] += (sps_real)1e-4;
                sps_world_set_particle(w, 27, s.position, NULL);
            }
            ENSURE(sps_world_step(w) == SPS_OK);
            ids = sps_world_particle_ids(w);
            for (a = 0; a < 2; ++a) {
                const sps_real* acc = sps_world_field_by_name(w, a ? "pressure_acceleration_y" : "pressure_acceleration_x", NULL);
                for (i = 0; i < 64; ++i) a_of[run][a][ids[i]] = acc[i];
            }
            sps_world_destroy(w);
        }
        if (kicked) restoring = a_of[1][0][27] - a_of[0][0][27]; /* the hourglass force on the moved particle, x */
        for (int i = 0; i < 64; ++i)
            for (int a = 0; a < 2; ++a) {
                const double d = fabs(a_of[1][a][i] - a_of[0][a][i]);
                if (kicked) diff_kicked = fmax(diff_kicked, d);
                else diff_affine = fmax(diff_affine, d);
                scale = fmax(scale, fabs(a_of[0][a][i]));
            }
    }
    printf("    max |a(alpha 50) - a(alpha 0)|: affine %.2e, one particle off by 0.1 dp %.2e m/s^2 (stress force up to %.2e)\n",
           diff_affine, diff_kicked, scale);
    ENSURE(diff_affine < 1e-9 * scale); /* round-off of the error vectors F X_ij - x_ij */
    ENSURE(diff_kicked > 1e-2 * scale); /* the non-affine part is resisted */
    printf("    hourglass acceleration of the moved particle (moved +x): %.3g m/s^2\n", restoring);
    ENSURE(restoring < 0); /* and pushed back */
    return 0;
}

/* A free TL body (Neo-Hookean, 2D and 3D) started with a translation, a spin and a shear keeps its
   linear and angular momentum: the stress force of TL eq. 24 is antisymmetric and, with F from
   the same corrected gradients, P F^T = J sigma is symmetric, so it exerts no net torque; the
   hourglass force is central. */
static int test_tl_momentum(void) {
    int dim;
    for (dim = 2; dim <= 3; ++dim) {
        sps_body b;
        sps_world* w = tl_box(dim, SPS_MATERIAL_NEO_HOOKEAN, 50, dim == 2 ? 10 : 5, 0, &b);
        sps_diagnostics d0, d1;
        double p0 = 0, dl = 0, da = 0, l0 = 0;
        int id, a, steps;
        ENSURE(w != NULL);
        for (id = 0; id < sps_world_particle_count(w); ++id) {
            sps_particle_state s;
            sps_real v[3];
            sps_world_particle(w, id, &s);
            v[0] = (sps_real)(1.0 - 200 * (s.position[1] - 5e-3) + 300 * (s.position[1] - 5e-3));
            v[1] = (sps_real)(-0.5 + 200 * (s.position[0] - 5e-3));
            v[2] = dim == 3 ? (sps_real)(0.3 + 100 * (s.position[0] - 2.5e-3)) : 0;
            sps_world_set_particle(w, id, NULL, v);
        }
        ENSURE(sps_world_diagnostics(w, (sps_body){0}, &d0) == SPS_OK);
        for (steps = 0; steps < 10; ++steps) ENSURE(sps_world_step(w) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, (sps_body){0}, &d1) == SPS_OK);
        for (a = 0; a < 3; ++a) {
            p0 += fabs(d0.linear_momentum[a]);
            l0 += fabs(d0.angular_momentum[a]);
            dl = fmax(dl, fabs(d1.linear_momentum[a] - d0.linear_momentum[a]));
            da = fmax(da, fabs(d1.angular_momentum[a] - d0.angular_momentum[a]));
        }
        printf("    %dD: %ld sub-steps, |dP|/|P| %.2e, |dL|/|L| %.2e, hourglass %.2e\n", dim, d1.acoustic_steps, dl / p0, da / l0,
               (double)d1.hourglass);
        ENSURE(dl / p0 < 1e-12);  /* antisymmetric pair forces: round-off */
        ENSURE(da / l0 < 1e-12);  /* no torque (B refined to the exact inverse): round-off */
        ENSURE(d1.acoustic_steps > 100); /* the body deformed for a while */
        sps_world_destroy(w);
    }
    return 0;
}

/* J2 in the TL frame: a homogeneous 3D stretch beyond yield leaves the Kirchhoff stress tau = J sigma
   on the yield surface, sqrt(3/2 |dev tau|^2) = sigma_Y (perfect plasticity), with plastic strain
   at every particle; below yield (a stretch 100 times smaller) none flows and the stress is Hencky's. */
static int test_tl_j2_return(void) {
    int big;
    for (big = 0; big < 2; ++big) {
        const double e = big ? 0.05 : 5e-4, A[9] = {1 + e, 0, 0, 0, 1 / (1 + e), 0, 0, 0, 1}, c[3] = {0, 0, 0}, Y = 1e3;
        sps_world_def wd = sps_default_world_def();
        sps_body_def bd = sps_default_body_def();
        sps_world* w;
        sps_body b;
        sps_real lo[3] = {0, 0, 0}, hi[3] = {4e-3, 4e-3, 4e-3}, all_lo[3] = {-1, -1, -1}, all_hi[3] = {1, 1, 1};
        const sps_real *tau, *p, *alpha;
        double qmax = 0, qmin = 1e300, amin = 1e300;
        int nc, first, count, i;
        wd.dim = 3; wd.dp = 1e-3; wd.log = quiet_log; wd.threads = 1;
        bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
        bd.material.kind = SPS_MATERIAL_J2;
        bd.material.yield_stress = (sps_real)Y; /* yield strain 1e-3 of E 1e6 */
        ENSURE(sps_world_create(&wd, &w) == SPS_OK);
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
        ENSURE(sps_body_constrain_box(w, b, all_lo, all_hi, SPS_AXIS_ALL, NULL, NULL) == SPS_OK);
        tl_map(w, A, c);
        ENSURE(sps_world_step(w) == SPS_OK);
        tau = sps_body_field(w, b, "shear_stress", &nc, &first, &count);
        p = sps_world_field_by_name(w, "pressure", NULL);
        alpha = sps_body_field(w, b, "plastic_strain", &nc, &first, &count);
        ENSURE(tau && p && alpha);
        for (i = 0; i < count; ++i) {
            const double J = 1 /* isochoric */, sx = tau[6 * i] - p[first + i], sy = tau[6 * i + 3] - p[first + i], sz = tau[6 * i + 5] - p[first + i];
            const double m = (sx + sy + sz) / 3, q = J * sqrt(1.5 * ((sx - m) * (sx - m) + (sy - m) * (sy - m) + (sz - m) * (sz - m) +
                                                                   2 * (tau[6 * i + 1] * tau[6 * i + 1] + tau[6 * i + 2] * tau[6 * i + 2] +
                                                                        tau[6 * i + 4] * tau[6 * i + 4])));
            qmax = fmax(qmax, q);
            qmin = fmin(qmin, q);
            amin = fmin(amin, alpha[i]);
        }
        printf("    stretch %g: von Mises of tau %.6g .. %.6g Pa (yield %g), smallest plastic strain %.3g\n", e, qmin, qmax, Y, amin);
        if (big) {
            ENSURE(fabs(qmax - Y) < 1e-9 * Y && fabs(qmin - Y) < 1e-9 * Y); /* on the surface: round-off (J = 1: isochoric stretch) */
            /* every particle flowed by the equivalent strain 2/sqrt(3) ln(1 + e) = 0.0563 less the elastic 2/3 (1 + nu) Y/E */
            ENSURE_NEAR(amin, 2 / sqrt(3) * log(1 + e) - 2.0 / 3 * 1.3 * Y / 1e6, 1e-9);
        } else {
            ENSURE(qmax < Y && amin == 0); /* elastic: below yield, no flow */
        }
        sps_world_destroy(w);
    }
    return 0;
}

/* The closed-form Cauchy stress of a Saint Venant-Kirchhoff body (E 1e6, nu 0.3) under the
   homogeneous stretch x = diag(l) X: sigma_a = l_a^2 (lambda tr(E) + mu (l_a^2 - 1)) / J (TL eq. 19). */
static void tl_svk_stretch_stress(const double l[3], double sigma[3]) {
    const double E = 1e6, nu = 0.3, mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), J = l[0] * l[1] * l[2];
    double trE = 0;
    int a;
    for (a = 0; a < 3; ++a) trE += 0.5 * (l[a] * l[a] - 1);
    for (a = 0; a < 3; ++a) sigma[a] = l[a] * l[a] * (lambda * trE + mu * (l[a] * l[a] - 1)) / J;
}

/* A held Saint Venant-Kirchhoff box (rho0 1000, E 1e6, nu 0.3; n^dim particles) with damage
   threshold eps_max, stretched homogeneously by diag(l) and advanced to time t; NULL on error. */
static sps_world* tl_damage_run(int dim, int n, double eps_max, const double l[3], double t, sps_body* b) {
    const double A[9] = {l[0], 0, 0, 0, l[1], 0, 0, 0, l[2]}, c[3] = {0, 0, 0};
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    bd.material.kind = SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF;
    bd.damage_strain = eps_max;
    if ((w = tl_box_of(dim, bd, n, 1, b)) == NULL) return NULL;
    tl_map(w, A, c);
    if (sps_world_advance(w, (sps_real)t, NULL, NULL) != SPS_OK) {
        sps_world_destroy(w);
        return NULL;
    }
    return w;
}

/* The damage rate of TL eq. 45: below the threshold (a uniaxial stretch of 5 %, Green-Lagrange
   strain 0.051 < 0.08) no damage; above it (10 %: 0.105) D^(1/3) = 0.4 c0 t / h at every
   particle, c0 = sqrt((K + 4G/3)/rho0) the P-wave speed and h the kernel radius 2 h_over_dp dp,
   and the tensile stress sigma_xx is the undamaged one times 1 - D (TL eq. 46). 2D, plane strain. */
static int test_tl_damage_rate(void) {
    const double E = 1e6, nu = 0.3, K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu)), c0 = sqrt((K + 4 * G / 3) / 1000);
    const double radius = 2 * 1.3 * 1e-3, t_full = radius / (0.4 * c0); /* default h_over_dp 1.3: D = 1 after t_full */
    int above;
    {   /* the def's checks: the range, and the solver that has a deformation gradient */
        sps_world_def wd = sps_default_world_def();
        sps_body_def bd = sps_default_body_def();
        sps_world* w;
        sps_body b;
        wd.log = quiet_log;
        ENSURE(sps_world_create(&wd, &w) == SPS_OK);
        bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
        bd.material.kind = SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF;
        bd.damage_strain = -0.5;
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG);
        ENSURE(strstr(sps_world_last_error(w), "damage_strain = -0.5, allowed [0, 100]") != NULL);
        bd.damage_strain = 0.08;
        bd.solver = SPS_SOLVER_UPDATED_LAGRANGIAN;
        bd.material.kind = SPS_MATERIAL_ELASTIC;
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG);
        ENSURE(strstr(sps_world_last_error(w), "damage_strain > 0 with solver = updated Lagrangian") != NULL);
        sps_world_destroy(w);
    }
    for (above = 0; above < 2; ++above) {
        const double l[3] = {above ? 1.1 : 1.05, 1, 1};
        double sigma[3], t, root_err = 0, stress_err = 0, dmin = 1, dmax = 0;
        sps_body b;
        sps_world* w = tl_damage_run(2, 8, 0.08, l, 0.5 * t_full, &b);
        const sps_real *D, *tau, *p;
        int nc, first, count, i;
        ENSURE(w != NULL);
        t = sps_world_time(w);
        D = sps_body_field(w, b, "damage", &nc, &first, &count);
        ENSURE(D != NULL && nc == 1 && count == 64);
        tau = sps_body_field(w, b, "shear_stress", &nc, &first, &count);
        p = sps_world_field_by_name(w, "pressure", NULL);
        ENSURE(sps_world_field_by_name(w, "damage", NULL) == NULL); /* a per-body field: sps_body_field's */
        ENSURE(tau && p);
        tl_svk_stretch_stress(l, sigma);
        for (i = 0; i < count; ++i) {
            dmin = fmin(dmin, D[i]);
            dmax = fmax(dmax, D[i]);
            root_err = fmax(root_err, fabs(cbrt(D[i]) - 0.4 * c0 * t / radius));
            stress_err = fmax(stress_err, fabs(tau[6 * i] - p[first + i] - (1 - D[i]) * sigma[0]));
        }
        printf("    stretch %g (Green-Lagrange %.4f): t = %.4g s, D %.6g .. %.6g, max |D^(1/3) - 0.4 c0 t/h| %.2e, "
               "max |sigma_xx - (1 - D) sigma_xx(undamaged)| %.2e Pa\n", l[0], 0.5 * (l[0] * l[0] - 1), t, dmin, dmax, root_err,
               stress_err);
        if (above) {
            ENSURE(root_err < 1e-9); /* the sum of the sub-steps' dt is the world's time: round-off */
            ENSURE(dmin > 0.1);      /* half way to full damage: D = 1/8 */
        } else {
            ENSURE(dmax == 0); /* below the threshold: none, exactly */
        }
        ENSURE(stress_err < 1e-9 * E); /* the closed form (TL eq. 46) up to the round-off of F times E */
        sps_world_destroy(w);
    }
    return 0;
}

/* Damage degrades only tension (TL eq. 46): a 3D box stretched by 20 % in x, compressed by 20 %
   in y (and held in z) until D = 1 everywhere loses its tensile stresses sigma_xx and
   sigma_zz (lambda tr(E) > 0) and keeps its compressive sigma_yy, the undamaged closed form. */
static int test_tl_damage_tension_only(void) {
    const double E = 1e6, nu = 0.3, K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu)), c0 = sqrt((K + 4 * G / 3) / 1000);
    const double l[3] = {1.2, 0.8, 1}, t = 1.2 * 2 * 1.3e-3 / (0.4 * c0); /* past full damage */
    double sigma[3], tension = 0, compression_err = 0, dmin = 1;
    sps_body b;
    sps_world* w = tl_damage_run(3, 5, 0.08, l, t, &b);
    const sps_real *D, *tau, *p;
    int nc, first, count, i;
    ENSURE(w != NULL);
    D = sps_body_field(w, b, "damage", &nc, &first, &count);
    tau = sps_body_field(w, b, "shear_stress", &nc, &first, &count);
    p = sps_world_field_by_name(w, "pressure", NULL);
    ENSURE(D && tau && p);
    tl_svk_stretch_stress(l, sigma);
    for (i = 0; i < count; ++i) {
        dmin = fmin(dmin, D[i]);
        tension = fmax(tension, fmax(fabs(tau[6 * i] - p[first + i]), fabs(tau[6 * i + 5] - p[first + i])));
        compression_err = fmax(compression_err, fabs(tau[6 * i + 3] - p[first + i] - sigma[1]));
    }
    printf("    undamaged sigma = (%.6g, %.6g, %.6g) Pa; damaged: smallest D %.6g, max |sigma_xx|, |sigma_zz| %.2e Pa, "
           "max |sigma_yy - undamaged| %.2e Pa\n", sigma[0], sigma[1], sigma[2], dmin, tension, compression_err);
    ENSURE(sigma[0] > 1e5 && sigma[1] < -5e4 && sigma[2] > 1e4); /* the state has both signs to test */
    ENSURE(dmin == 1);                        /* fully damaged */
    ENSURE(tension < 1e-9 * E);               /* tension gone: round-off of rebuilding P */
    ENSURE(compression_err < 1e-9 * E);       /* compression kept: round-off */
    sps_world_destroy(w);
    return 0;
}

/* ============================================================================================ */
/* Chapter >>solver: total Lagrangian: the variational hourglass force. Phi, the
   springs' energy sum_i sum_j 1/2 k_ij (delta^i_ij)^2, is read through sps__tl_energy (the law's
   energy plus the springs'), and the forces through the two passes at the current positions. */

/* A Neo-Hookean TL patch (E 1e6, alpha 50, the given hourglass form) of n^dim particles on a
   lattice of dp = 1e-3 jittered by U(-0.2, 0.2) dp per coordinate (a fixed seed): an irregular
   reference set. Held, so that the first step (which builds the reference lists) leaves it
   where it is. */
static sps_world* tl_irregular_patch(int dim, int n, sps_hourglass form, sps_body* out) {
    sps_body_def bd = sps_default_body_def();
    sps_world_def wd = sps_default_world_def();
    sps_real xyz[3 * 216], all_lo[3] = {-1, -1, -1}, all_hi[3] = {1, 1, 1};
    unsigned seed = 12345u;
    sps_world* w;
    int count = 0, i, j, k, a;
    for (k = 0; k < (dim == 3 ? n : 1); ++k)
        for (j = 0; j < n; ++j)
            for (i = 0; i < n && count < 216; ++i, ++count) {
                const int cell[3] = {i, j, k};
                for (a = 0; a < 3; ++a) {
                    seed = seed * 1664525u + 1013904223u; /* a fixed LCG: the same patch every run */
                    xyz[3 * count + a] = a < dim ? (sps_real)(1e-3 * (cell[a] + 0.4 * ((seed >> 8) / 16777216.0 - 0.5))) : 0;
                }
            }
    wd.dim = dim; wd.dp = 1e-3; wd.log = quiet_log; wd.threads = 1;
    bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
    bd.material.kind = SPS_MATERIAL_NEO_HOOKEAN;
    bd.hourglass = form;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    if (sps_world_add_body(w, &bd, out) != SPS_OK || sps_body_add_particles(w, *out, count, xyz, NULL) != SPS_OK ||
        sps_body_constrain_box(w, *out, all_lo, all_hi, SPS_AXIS_ALL, NULL, NULL) != SPS_OK || sps_world_step(w) != SPS_OK) {
        sps_world_destroy(w);
        return NULL;
    }
    return w;
}

/* Moves every particle to x = A X + noise U(-0.05, 0.05) dp per coordinate (noise 0: affine). */
static void tl_deform(sps_world* w, const double A[9], double noise) {
    unsigned seed = 777u;
    int i, a, c;
    for (i = 0; i < w->n; ++i)
        for (a = 0; a < w->dim; ++a) {
            double x = 0;
            for (c = 0; c < w->dim; ++c) x += A[3 * a + c] * w->ref[c][i];
            seed = seed * 1664525u + 1013904223u;
            w->pos[a][i] = (sps_real)(x + noise * 1e-3 * ((seed >> 8) / 16777216.0 - 0.5) * 2);
        }
}

/* The force on every particle at the current positions (the stress and force passes), into f
   (dim values per particle slot); the springs alone when springs_only (alpha 50 less alpha 0). */
static void tl_forces(sps_world* w, int springs_only, double* f) {
    sps__body* b = &w->bodies[0];
    const sps_real alpha = b->def.hourglass_alpha;
    int pass, i, a;
    for (pass = 0; pass < (springs_only ? 2 : 1); ++pass) {
        b->def.hourglass_alpha = pass ? 0 : alpha;
        sps__run_groups(w, b, b->model.pass.stress, 0);
        sps__run_groups(w, b, b->model.pass.pressure, 0);
        for (i = 0; i < w->n; ++i)
            for (a = 0; a < w->dim; ++a) f[w->dim * i + a] = (pass ? f[w->dim * i + a] : 0) + (pass ? -1 : 1) * (double)(w->acc_p[a][i] * w->mass[i]);
    }
    b->def.hourglass_alpha = alpha;
}

/* The stored energy sum_i sps__tl_energy at the current positions; the springs' Phi alone when
   springs_only. */
static double tl_stored_energy(sps_world* w, int springs_only) {
    sps__body* b = &w->bodies[0];
    const sps_real alpha = b->def.hourglass_alpha;
    double e = 0;
    int i;
    for (i = 0; i < w->n; ++i) e += (double)sps__tl_energy(w, b, i);
    if (springs_only) {
        b->def.hourglass_alpha = 0;
        for (i = 0; i < w->n; ++i) e -= (double)sps__tl_energy(w, b, i);
        b->def.hourglass_alpha = alpha;
    }
    return e;
}

/* The springs' force is -grad Phi: on an irregular patch (2D 10 x 10, 3D 5 x 5 x 5) under a
   stretch, shear and rotation plus non-affine noise of 0.05 dp, against central differences of
   Phi (step 1e-5 dp) at every particle and axis; it vanishes for the affine map alone (noise 0);
   and it exerts no net force or torque. The paper's form (TL eq. 32) fails the gradient check,
   so the check can fail. */
static int test_tl_hourglass_is_energy_gradient(void) {
    const double A[9] = {1.1 * cos(0.4), -0.9 * sin(0.4) + 0.15, 0, 1.1 * sin(0.4), 0.9 * cos(0.4), 0.05, 0.1, -0.05, 0.95};
    int dim, form;
    for (dim = 2; dim <= 3; ++dim)
        for (form = 0; form < 2; ++form) {
            sps_body b;
            sps_world* w = tl_irregular_patch(dim, dim == 2 ? 10 : 5, (sps_hourglass)form, &b);
            double f[3 * 216], affine_max = 0, ferr = 0, fmax_ = 0, err = 0, net[3] = {0, 0, 0}, torque[3] = {0, 0, 0};
            int i, a;
            const double eps = 1e-8; /* 1e-5 dp */
            ENSURE(w != NULL);
            tl_deform(w, A, 0);
            tl_forces(w, 1, f);
            for (i = 0; i < dim * w->n; ++i) affine_max = fmax(affine_max, fabs(f[i]));
            for (i = 0; i < 9 * w->n; ++i) /* the residue's source: F against the map */
                if ((i % 9) / 3 < dim && i % 3 < dim) ferr = fmax(ferr, fabs(w->bodies[0].tl_deformation[i] - A[i % 9]));
            tl_deform(w, A, 0.05);
            tl_forces(w, 1, f);
            for (i = 0; i < w->n; ++i) {
                const double x[3] = {w->pos[0][i], w->pos[1][i], dim == 3 ? w->pos[2][i] : 0};
                const double fi[3] = {f[dim * i], f[dim * i + 1], dim == 3 ? f[dim * i + 2] : 0};
                for (a = 0; a < 3; ++a) {
                    net[a] += fi[a];
                    torque[a] += x[(a + 1) % 3] * fi[(a + 2) % 3] - x[(a + 2) % 3] * fi[(a + 1) % 3];
                }
                for (a = 0; a < dim; ++a) {
                    const sps_real x0 = w->pos[a][i];
                    double up, down;
                    w->pos[a][i] = x0 + (sps_real)eps;
                    up = tl_stored_energy(w, 1);
                    w->pos[a][i] = x0 - (sps_real)eps;
                    down = tl_stored_energy(w, 1);
                    w->pos[a][i] = x0;
                    err = fmax(err, fabs(f[dim * i + a] + (up - down) / (2 * eps)));
                    fmax_ = fmax(fmax_, fabs(f[dim * i + a]));
                }
            }
            printf("    %dD %s: springs' force up to %.3e N, |f + dPhi/dx| %.2e (relative %.2e); affine map: %.2e N "
                   "(max |F - A| %.1e); net force %.1e, torque %.1e\n", dim, form ? "paper" : "variational", fmax_, err, err / fmax_, affine_max, ferr,
                   fabs(net[0]) + fabs(net[1]) + fabs(net[2]), fabs(torque[0]) + fabs(torque[1]) + fabs(torque[2]));
            if (form == SPS_HOURGLASS_VARIATIONAL) {
                ENSURE(err < 1e-6 * fmax_); /* central differences: truncation (1e-5)^2, round-off 1e-16 Phi / eps ~ 1e-9 */
            } else {
                ENSURE(err > 1e-2 * fmax_); /* TL eq. 32 is a partial gradient only: the check can fail */
            }
            ENSURE(ferr < 1e-7); /* F of an affine map: exact but for the Newton-refined B of this patch's corner particles */
            ENSURE(affine_max < 1e-6 * fmax_); /* no spring is stretched but by (F - A) X: 2e-8 x 2 dp against the noise's 0.05 dp */
            ENSURE(fabs(net[0]) + fabs(net[1]) + fabs(net[2]) < 1e-12 * fmax_ * w->n); /* antisymmetric pairs: round-off */
            ENSURE(fabs(torque[0]) + fabs(torque[1]) + fabs(torque[2]) < 1e-12 * fmax_ * w->n * 1e-2); /* round-off (lever ~1e-2 m) */
            sps_world_destroy(w);
        }
    return 0;
}

/* The linearised stiffness K = -df/dx (stress and springs, alpha 50) of an irregular patch
   (2D 6 x 6, 3D 4 x 4 x 4) at the deformed state of the test above is symmetric: the force is
   the gradient of one energy. By central differences of the forces (step 1e-5 dp). The
   paper's form is not (TL eq. 32: the flutter). */
static int test_tl_hourglass_stiffness_symmetric(void) {
    const double A[9] = {1.1 * cos(0.4), -0.9 * sin(0.4) + 0.15, 0, 1.1 * sin(0.4), 0.9 * cos(0.4), 0.05, 0.1, -0.05, 0.95};
    int dim, form;
    for (dim = 2; dim <= 3; ++dim)
        for (form = 0; form < 2; ++form) {
            sps_body b;
            sps_world* w = tl_irregular_patch(dim, dim == 2 ? 6 : 4, (sps_hourglass)form, &b);
            const int m = dim * (w ? w->n : 0);
            double *K = (double*)calloc((size_t)m * m, sizeof(double)), fp[3 * 64], fm[3 * 64], kmax = 0, asym = 0;
            const double eps = 1e-8;
            int col, r;
            ENSURE(w != NULL && K != NULL && m <= 3 * 64);
            tl_deform(w, A, 0.05);
            for (col = 0; col < m; ++col) {
                sps_real* x = &w->pos[col % dim][col / dim];
                const sps_real x0 = *x;
                *x = x0 + (sps_real)eps;
                tl_forces(w, 0, fp);
                *x = x0 - (sps_real)eps;
                tl_forces(w, 0, fm);
                *x = x0;
                for (r = 0; r < m; ++r) K[(size_t)r * m + col] = -(fp[r] - fm[r]) / (2 * eps);
            }
            for (r = 0; r < m; ++r)
                for (col = 0; col < m; ++col) {
                    kmax = fmax(kmax, fabs(K[(size_t)r * m + col]));
                    asym = fmax(asym, fabs(K[(size_t)r * m + col] - K[(size_t)col * m + r]));
                }
            printf("    %dD %s: max |K| %.3e N/m, max |K - K^T| %.2e (relative %.2e)\n", dim, form ? "paper" : "variational", kmax, asym,
                   asym / kmax);
            if (form == SPS_HOURGLASS_VARIATIONAL) {
                ENSURE(asym < 1e-6 * kmax); /* central differences of the forces: truncation (1e-5)^2, round-off 1e-16 f / eps */
            } else {
                ENSURE(asym > 1e-3 * kmax); /* TL eq. 32's stiffness is not symmetric: the check can fail */
            }
            free(K);
            sps_world_destroy(w);
        }
    return 0;
}

/* The artificial viscosity of TL bodies (artificial_viscosity = q1): a free Neo-Hookean patch
   (2D and 3D) started with a translation, a spin and a shear keeps its linear and angular
   momentum to round-off (central, antisymmetric pair forces), and after 5 steps (about 500
   sub-steps) it has lost mechanical energy (kinetic + stored, springs included), far more than
   the undamped run drifts (the variational force conserves energy, so the check can fail). Bad values are refused
   with the field's name. */
static int test_tl_artificial_viscosity(void) {
    int dim;
    for (dim = 2; dim <= 3; ++dim) {
        double energy[2] = {0, 0}, energy0 = 0, dl = 0, da = 0, p0 = 0, l0 = 0;
        long substeps = 0;
        int damped;
        for (damped = 0; damped < 2; ++damped) {
            sps_body_def bd = sps_default_body_def();
            sps_body b;
            sps_world* w;
            sps_diagnostics d0, d1;
            int id, a, steps;
            bd.material.kind = SPS_MATERIAL_NEO_HOOKEAN;
            bd.artificial_viscosity = damped ? (sps_real)0.5 : 0;
            w = tl_box_of(dim, bd, dim == 2 ? 10 : 5, 0, &b);
            ENSURE(w != NULL);
            for (id = 0; id < sps_world_particle_count(w); ++id) {
                sps_particle_state s;
                sps_real v[3];
                sps_world_particle(w, id, &s);
                v[0] = (sps_real)(1.0 + 100 * (s.position[1] - 5e-3));
                v[1] = (sps_real)(-0.5 + 200 * (s.position[0] - 5e-3));
                v[2] = dim == 3 ? (sps_real)(0.3 + 100 * (s.position[0] - 2.5e-3)) : 0;
                sps_world_set_particle(w, id, NULL, v);
            }
            ENSURE(sps_world_diagnostics(w, (sps_body){0}, &d0) == SPS_OK);
            for (steps = 0; steps < 5; ++steps) ENSURE(sps_world_step(w) == SPS_OK);
            ENSURE(sps_world_diagnostics(w, (sps_body){0}, &d1) == SPS_OK);
            energy0 = d0.kinetic_energy + d0.strain_energy;
            energy[damped] = d1.kinetic_energy + d1.strain_energy;
            substeps = d1.acoustic_steps;
            if (damped)
                for (a = 0; a < 3; ++a) {
                    p0 += fabs(d0.linear_momentum[a]);
                    l0 += fabs(d0.angular_momentum[a]);
                    dl = fmax(dl, fabs(d1.linear_momentum[a] - d0.linear_momentum[a]));
                    da = fmax(da, fabs(d1.angular_momentum[a] - d0.angular_momentum[a]));
                }
            sps_world_destroy(w);
        }
        printf("    %dD: energy %.6e J at the start, %.6e undamped, %.6e with q1 0.5 after %ld sub-steps; |dP|/|P| %.1e, |dL|/|L| %.1e\n",
               dim, energy0, energy[0], energy[1], substeps, dl / p0, da / l0);
        ENSURE(fabs(energy[0] - energy0) < 1e-2 * energy0); /* undamped: energy kept (time-stepping error, well below 1 %) */
        ENSURE(energy0 - energy[1] > 100 * fabs(energy0 - energy[0])); /* damped: a loss far above the time stepping's drift */
        ENSURE(dl / p0 < 1e-12);           /* antisymmetric pair forces: round-off */
        ENSURE(da / l0 < 1e-12);           /* central pair forces: round-off */
    }
    {
        sps_world_def wd = sps_default_world_def();
        sps_body_def bd = sps_default_body_def();
        sps_world* w;
        sps_body b;
        wd.log = quiet_log;
        ENSURE(sps_world_create(&wd, &w) == SPS_OK);
        bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
        bd.material.kind = SPS_MATERIAL_NEO_HOOKEAN;
        bd.artificial_viscosity = (sps_real)1.5;
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "artificial_viscosity = 1.5"));
        bd.artificial_viscosity = (sps_real)0.1;
        bd.hourglass = (sps_hourglass)2;
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "hourglass = 2"));
        bd = sps_default_body_def();
        bd.artificial_viscosity = (sps_real)0.1; /* an updated-Lagrangian body */
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "artificial_viscosity > 0"));
        sps_world_destroy(w);
    }
    return 0;
}

/* ============================================================================================ */
/* >>contact: Coulomb friction; >>material: Kelvin-Voigt                                       */

/* A 2D body def of the friction and damping tests: ENO-A with pair rotation (set here, not the
   library's default, so a change of defaults does not move these figures). */
static sps_body_def friction_test_body(double friction, double viscosity) {
    sps_body_def bd = sps_default_body_def();
    bd.shear = SPS_SHEAR_ENO_A;
    bd.rotation = SPS_ROTATION_PAIR;
    bd.friction = (sps_real)friction;
    bd.material.viscosity = (sps_real)viscosity;
    return bd;
}
static void at_rest(const sps_real x[3], sps_real v[3], void* user) {
    (void)x; (void)user;
    v[0] = v[1] = v[2] = 0;
}
/* The mass-weighted mean y of all particles. */
static double centre_y(const sps_world* w) {
    const sps_real *y = sps_world_field(w, SPS_FIELD_POSITION_Y), *m = sps_world_field(w, SPS_FIELD_MASS);
    double my = 0, mass = 0;
    int i;
    for (i = 0; i < sps_world_particle_count(w); ++i) { my += m[i] * y[i]; mass += m[i]; }
    return my / mass;
}
/* The mass-weighted mean x of all particles. */
static double centre_x(const sps_world* w) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *m = sps_world_field(w, SPS_FIELD_MASS);
    double mx = 0, mass = 0;
    int i;
    for (i = 0; i < sps_world_particle_count(w); ++i) { mx += m[i] * x[i]; mass += m[i]; }
    return mx / mass;
}

/* A block 0.1 x 0.05 (dp 0.005) resting on a floor wall with friction mu under gravity tilted by
   angle_deg (the slope along +x): settled by kinetic relaxation (velocities zeroed every 5 ms
   for 0.2 s, as examples/incline.c does: the contact has no normal damping), then released for
   t_slide. Returns the distance its centre slid, or -1 on failure. */
static double slope_slide(double mu, double angle_deg, double t_slide) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = friction_test_body(mu, 0);
    const double theta = angle_deg * 3.14159265358979323846 / 180;
    const sps_real lo[3] = {-0.05, 0.0075, 0}, hi[3] = {0.05, 0.0575, 0}, point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    sps_world* w = NULL;
    sps_body b;
    double x0, slid = -1;
    int k;
    wd.dim = 2; wd.dp = 0.005; wd.threads = 1; wd.log = quiet_log;
    wd.gravity[0] = (sps_real)(9.81 * sin(theta));
    wd.gravity[1] = (sps_real)(-9.81 * cos(theta));
    if (sps_world_create(&wd, &w) != SPS_OK) return -1;
    if (sps_world_add_body(w, &bd, &b) != SPS_OK || sps_body_add_box(w, b, lo, hi, NULL) != SPS_OK ||
        sps_world_add_wall(w, point, up, SPS_WALL_FREE_SLIP) != SPS_OK || sps_world_set_wall_friction(w, 0, (sps_real)mu) != SPS_OK)
        goto done;
    for (k = 1; k <= 40; ++k)
        if (sps_world_advance(w, (sps_real)(0.005 * k), NULL, NULL) != SPS_OK || sps_body_set_velocity(w, b, at_rest, NULL) != SPS_OK) goto done;
    x0 = centre_x(w);
    if (sps_world_advance(w, (sps_real)(0.2 + t_slide), NULL, NULL) != SPS_OK) goto done;
    slid = centre_x(w) - x0;
done:
    sps_world_destroy(w);
    return slid;
}

/* On a 30-degree slope with mu = 0.3 a block slides with a = g (sin - mu cos) (Coulomb); on a
   10-degree slope (tan 10 = 0.18 < mu) it sticks: it creeps less than 1 % of the frictionless
   distance (the issue's bound; the velocity-regularised stick lets it creep a little). */
static int test_friction_block_on_slope(void) {
    const double g = 9.81, pi = 3.14159265358979323846, t = 0.3, t_stick = 1; /* the issue's creep bound is over 1 s */
    const double a30 = g * (sin(pi / 6) - 0.3 * cos(pi / 6)), slid30 = slope_slide(0.3, 30, t), slid10 = slope_slide(0.3, 10, t_stick);
    const double free10 = 0.5 * g * sin(10 * pi / 180) * t_stick * t_stick;
    printf("    30 degrees: a = %.5g m/s^2 (Coulomb %.5g); 10 degrees: crept %.3g m, %.3f %% of the frictionless %.4g m\n",
           2 * slid30 / (t * t), a30, slid10, 100 * slid10 / free10, free10);
    ENSURE(slid30 > 0 && slid10 > -1);
    ENSURE_NEAR(2 * slid30 / (t * t), a30, 0.01 * a30); /* measured 0.01 % over 1 s (bench/VALIDATION.md, Friction); 1 %: the short run */
    ENSURE(fabs(slid10) < 0.01 * free10);                 /* the issue's bound (measured 0.36 % over 1 s) */
    return 0;
}

/* Two blocks, the upper sliding over the lower with friction (mu 0.5 both, pressed together):
   the friction pair forces are antisymmetric, so the total linear momentum stays at its start to
   round-off, while the upper block's tangential momentum is passed on (it slows, unlike mu = 0). */
static int test_friction_momentum_exact(void) {
    double px_upper[2] = {0, 0}, scale = 0;
    int with;
    for (with = 0; with < 2; ++with) {
        sps_world* w = new_world(2, 0.01);
        sps_body_def bd = friction_test_body(with ? 0.5 : 0, 0);
        const sps_real lo1[3] = {0, 0, 0}, hi1[3] = {0.3, 0.1, 0}, lo2[3] = {0.05, 0.12, 0}, hi2[3] = {0.2, 0.2, 0};
        sps_body lower, upper;
        sps_diagnostics d0, d1, du;
        sps_real c0, v[3];
        ENSURE(w);
        ENSURE(sps_world_add_body(w, &bd, &lower) == SPS_OK && sps_body_add_box(w, lower, lo1, hi1, NULL) == SPS_OK);
        ENSURE(sps_world_add_body(w, &bd, &upper) == SPS_OK && sps_body_add_box(w, upper, lo2, hi2, NULL) == SPS_OK);
        ENSURE(sps_body_material_constants(w, upper, &c0, NULL, NULL) == SPS_OK);
        v[0] = (sps_real)(0.05 * c0);
        ENSURE(sps_body_set_velocity(w, upper, velocity_x, &v[0]) == SPS_OK);
        v[0] = (sps_real)(0.02 * c0);
        ENSURE(sps_body_set_velocity(w, lower, velocity_down, &v[0]) == SPS_OK);
        v[0] = -v[0]; /* the lower block moves up into the upper one: they press together while they slide */
        ENSURE(sps_body_set_velocity(w, lower, velocity_down, &v[0]) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d0) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, upper, &du) == SPS_OK);
        scale = fabs((double)du.linear_momentum[0]);
        ENSURE(sps_world_advance(w, 0.03, NULL, NULL) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d1) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, upper, &du) == SPS_OK);
        px_upper[with] = du.linear_momentum[0];
        printf("    mu = %.1f: momentum x %.12g -> %.12g, y %.6g -> %.6g (scale %.3g); upper block's x momentum %.6g\n", with ? 0.5 : 0,
               (double)d0.linear_momentum[0], (double)d1.linear_momentum[0], (double)d0.linear_momentum[1], (double)d1.linear_momentum[1],
               scale, px_upper[with]);
        ENSURE_NEAR(d1.linear_momentum[0], d0.linear_momentum[0], 1e-12 * scale); /* round-off of sums of pair forces */
        ENSURE_NEAR(d1.linear_momentum[1], d0.linear_momentum[1], 1e-12 * scale);
        sps_world_destroy(w);
    }
    ENSURE(px_upper[1] < 0.98 * px_upper[0]); /* friction passed momentum on to the lower block */
    return 0;
}

/* Friction that a scene does not use costs nothing: a body with friction 0.5 over frictionless
   walls (the pair's sqrt(0.5 * 0) = 0), or on walls with friction while its own is 0, runs bit
   for bit as a body without friction; so does eta = 0 (the default) set explicitly. */
static int test_friction_unused_is_free(void) {
    double* s[3];
    int k, same;
    for (k = 0; k < 3; ++k) {
        sps_world* w = new_world(2, 0.01);
        sps_body_def bd = friction_test_body(k == 1 ? 0.5 : 0, 0);
        const sps_real lo[3] = {0, 0.02, 0}, hi[3] = {0.1, 0.1, 0}, point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
        sps_real v[3] = {1, -1, 0};
        sps_body b;
        ENSURE(w);
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
        ENSURE(sps_world_add_wall(w, point, up, SPS_WALL_FREE_SLIP) == SPS_OK);
        if (k == 2) ENSURE(sps_world_set_wall_friction(w, -1, 0.5) == SPS_OK);
        ENSURE(sps_body_set_velocity(w, b, velocity_x, &v[0]) == SPS_OK);
        ENSURE(sps_world_advance(w, 0.01, NULL, NULL) == SPS_OK);
        s[k] = snapshot(w);
        ENSURE(s[k]);
        if (k == 2) {
            same = memcmp(s[0], s[1], sizeof(double) * 6 * (size_t)sps_world_particle_count(w)) == 0 &&
                   memcmp(s[0], s[2], sizeof(double) * 6 * (size_t)sps_world_particle_count(w)) == 0;
            ENSURE(same);
        }
        sps_world_destroy(w);
    }
    for (k = 0; k < 3; ++k) free(s[k]);
    return 0;
}

/* Kelvin-Voigt damping does not brake rigid motion: a damped block falling and spinning keeps
   v = g t in its mean, and its spin: the viscous work stays below 1e-3 of its kinetic energy (the
   viscous pair force is central and zero for any rigid motion), and ENO-A with pair rotation and
   the total-Lagrangian Neo-Hookean body keep their angular momentum about the centre to
   round-off; GNO-A as well (its own stress divergence is not central). */
static int test_kelvin_voigt_rigid_motion_free(void) {
    int k;
    for (k = 0; k < 3; ++k) {
        sps_world_def wd = sps_default_world_def();
        sps_body_def bd = friction_test_body(0, 50);
        const sps_real lo[3] = {-0.05, -0.05, 0}, hi[3] = {0.05, 0.05, 0};
        sps_world* w = NULL;
        sps_body b;
        sps_diagnostics d0, d1;
        spin_field spin = {20, {0, 0, 0}};
        double lz0, lz1, mass;
        wd.dim = 2; wd.dp = 0.01; wd.threads = 1; wd.log = quiet_log; wd.gravity[1] = -9.81;
        if (k == 1) bd.shear = SPS_SHEAR_GNO_A;
        if (k == 2) { bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN; bd.material.kind = SPS_MATERIAL_NEO_HOOKEAN; }
        ENSURE(sps_world_create(&wd, &w) == SPS_OK);
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
        ENSURE(sps_body_set_velocity(w, b, spin_velocity, &spin) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, b, &d0) == SPS_OK);
        ENSURE(sps_world_advance(w, 0.02, NULL, NULL) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, b, &d1) == SPS_OK);
        mass = 0;
        {
            const sps_real* m = sps_world_field(w, SPS_FIELD_MASS);
            int i;
            for (i = 0; i < sps_world_particle_count(w); ++i) mass += m[i];
        }
        /* angular momentum about the centre of mass: L - x_c X p */
        lz0 = d0.angular_momentum[2];
        lz1 = d1.angular_momentum[2] - (centre_x(w) * d1.linear_momentum[1] - centre_y(w) * d1.linear_momentum[0]);
        ENSURE(d1.viscous_work < 1e-3 * d0.kinetic_energy); /* the spin is not braked (the centrifugal stretch's vibration only) */
        printf("    %s: mean v_y %.15g (g t = %.15g), L_z about the centre %.12g -> %.12g; viscous work %.3g J\n",
               k == 0 ? "ENO-A" : k == 1 ? "GNO-A" : "TL Neo-Hookean", (double)d1.linear_momentum[1] / mass, -9.81 * (double)d1.time,
               lz0, lz1, (double)d1.viscous_work);
        ENSURE_NEAR(d1.linear_momentum[1] / mass, -9.81 * d1.time, 1e-12 * 9.81 * d1.time); /* round-off */
        if (k != 1) ENSURE_NEAR(lz1, lz0, 1e-10 * fabs(lz0)); /* round-off (GNO-A's stress divergence is not central: 3e-6 here) */
        sps_world_destroy(w);
    }
    return 0;
}


/* Bad friction and viscosity input: a message naming the field, its value and the allowed range
   (or the rule), never a crash: negative or NaN mu and eta, friction on a body without contact
   or on a fluid, eta on a wall body, wall friction on a no-slip wall, out of range or without
   walls. */
static int test_friction_damping_bad_input(void) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def d = friction_test_body(0, 0), bad;
    const sps_real point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    ENSURE(w);
    bad = d; bad.friction = -0.1;                 ENSURE(rejects_body_def(w, &bad, "friction = -0.1, allowed finite >= 0") == 0);
    bad = d; bad.friction = (sps_real)NAN;        ENSURE(rejects_body_def(w, &bad, "friction = nan") == 0);
    bad = d; bad.friction = 0.3; bad.contact = 0; ENSURE(rejects_body_def(w, &bad, "friction > 0 with contact = 0") == 0);
    bad = d; bad.friction = 0.3; bad.material.kind = SPS_MATERIAL_FLUID; bad.material.sound_speed = 10;
    ENSURE(rejects_body_def(w, &bad, "friction > 0 with material.kind = fluid") == 0);
    bad = d; bad.material.viscosity = -2;         ENSURE(rejects_body_def(w, &bad, "material.viscosity = -2, allowed finite >= 0") == 0);
    bad = d; bad.material.viscosity = (sps_real)NAN; ENSURE(rejects_body_def(w, &bad, "material.viscosity = nan") == 0);
    bad = d; bad.material.viscosity = 5; bad.material.kind = SPS_MATERIAL_RIGID;
    ENSURE(rejects_body_def(w, &bad, "material.viscosity > 0 with material.kind = rigid") == 0);
    ENSURE(sps_world_set_wall_friction(w, -1, 0.3) == SPS_ERR_INVALID_ARG); /* no walls yet */
    ENSURE(strstr(sps_world_last_error(w), "wall = -1") != NULL);
    ENSURE(sps_world_add_wall(w, point, up, SPS_WALL_NO_SLIP) == SPS_OK);
    ENSURE(sps_world_set_wall_friction(w, 0, 0.3) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "wall 0 is no-slip") != NULL);
    ENSURE(sps_world_add_wall(w, point, up, SPS_WALL_FREE_SLIP) == SPS_OK);
    ENSURE(sps_world_set_wall_friction(w, 2, 0.3) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "wall = 2, allowed -1 (all) or 0..1") != NULL);
    ENSURE(sps_world_set_wall_friction(w, 1, -1) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "mu = -1, allowed finite >= 0") != NULL);
    ENSURE(sps_world_set_wall_friction(w, 1, (sps_real)NAN) == SPS_ERR_INVALID_ARG);
    ENSURE(sps_world_set_wall_friction(w, 1, 0.3) == SPS_OK);
    ENSURE(sps_world_set_wall_friction(NULL, 0, 0.3) == SPS_ERR_INVALID_ARG);
    sps_world_destroy(w);
    { /* friction where no contact has any: a warning naming the body and the value, not silence */
        const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
        sps_body_def bd = friction_test_body(0.4, 0);
        sps_body b;
        w = new_world(2, 0.01);
        ENSURE(w);
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
        g_log_last[0] = 0;
        ENSURE(sps_world_step(w) == SPS_OK);
        ENSURE(strstr(g_log_last, "friction = 0.4 in a scene without contact") != NULL);
        sps_world_destroy(w);
    }
    return 0;
}


/* Kelvin-Voigt decay: a 2D bar 1 x 0.1 set shearing in its first through-thickness mode,
   v_x = 0.1 cos(pi y / H) (GNO-A, pair rotation: a stress-based formulation whose strain energy
   is the one its force derives from), loses energy faster with eta = 25 Pa s than without, and
   its account kinetic + strain + viscous work (the Kelvin-Voigt and Riemann dissipation) stays at
   its start. */
static void shear_mode(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = (sps_real)(0.1 * cos(3.14159265358979323846 * x[1] / 0.1));
    v[1] = v[2] = 0;
}
static int test_kelvin_voigt_decay_account(void) {
    double energy[2], account = 0, start = 0;
    int k;
    for (k = 0; k < 2; ++k) {
        sps_world* w = new_world(2, 0.01);
        sps_body_def bd = friction_test_body(0, k ? 25 : 0);
        const sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 0.1, 0};
        sps_body b;
        sps_diagnostics d0, d1;
        ENSURE(w);
        bd.shear = SPS_SHEAR_GNO_A;
        bd.track_stress = 1;
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
        ENSURE(sps_body_set_velocity(w, b, shear_mode, NULL) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, b, &d0) == SPS_OK);
        ENSURE(sps_world_advance(w, 0.02, NULL, NULL) == SPS_OK); /* two periods of the mode */
        ENSURE(sps_world_diagnostics(w, b, &d1) == SPS_OK);
        start = d0.kinetic_energy + d0.strain_energy;
        energy[k] = (d1.kinetic_energy + d1.strain_energy) / start;
        if (k) account = (d1.kinetic_energy + d1.strain_energy + d1.viscous_work) / start;
        sps_world_destroy(w);
    }
    printf("    energy left after 0.02 s: %.4f (eta 0), %.4f (eta 25 Pa s); account with the viscous work %.4f of its start\n",
           energy[0], energy[1], account);
    ENSURE(energy[1] < 0.8 * energy[0]); /* the damping is felt (measured 0.70) */
    ENSURE_NEAR(account, 1, 0.01);       /* the work is summed at the velocities before the kick: first order in dt (measured 0.3 %) */
    return 0;
}

/* ---- fluid-structure coupling (chapter >>coupling: fluid-structure) ---- */

/* Adds the lattice of [x0, x1] x [y0, y1] to body b (2D). */
static int fsi_box(sps_world* w, sps_body b, double x0, double y0, double x1, double y1) {
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    lo[0] = (sps_real)x0; lo[1] = (sps_real)y0; hi[0] = (sps_real)x1; hi[1] = (sps_real)y1;
    return sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK;
}

/* A 2D world with gravity g (downwards) and the tests' quiet log. */
static sps_world* fsi_world(double dp, double g, int threads) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w = NULL;
    wd.dim = 2; wd.dp = (sps_real)dp; wd.threads = threads; wd.gravity[1] = (sps_real)-g; wd.log = quiet_log;
    return sps_world_create(&wd, &w) == SPS_OK ? w : NULL;
}

static sps_body_def fsi_water(double c0) {
    sps_body_def bd = sps_default_body_def();
    bd.name = "water";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.sound_speed = (sps_real)c0;
    return bd;
}

/* A water block at 0.1 c0 hits an elastic block at rest (no gravity, no walls): linear momentum
   is exact (each pair's force is computed once per side from the same values), the solid is
   pushed, no water gets nearer a solid particle than dp/2, and 1 and 2 threads agree bit for bit. */
static sps_world* fsi_collision(int threads, sps_body* water, sps_body* block) {
    sps_world* w = fsi_world(0.01, 0, threads);
    sps_body_def wd = fsi_water(20), sd = sps_default_body_def();
    sps_real v = 2;
    if (!w) return NULL;
    sd.name = "block";
    sd.material.density = 1000;
    sd.material.youngs_modulus = 1e6;
    if (sps_world_add_body(w, &wd, water) != SPS_OK || !fsi_box(w, *water, 0, 0, 0.2, 0.2) ||
        sps_body_set_velocity(w, *water, velocity_x, &v) != SPS_OK || sps_world_add_body(w, &sd, block) != SPS_OK ||
        !fsi_box(w, *block, 0.23, 0.05, 0.33, 0.15)) {
        sps_world_destroy(w);
        return NULL;
    }
    return w;
}
static int test_coupling_momentum(void) {
    sps_body water, block, water2, block2;
    sps_world *w = fsi_collision(1, &water, &block), *w2 = fsi_collision(2, &water2, &block2);
    sps_diagnostics d0, d1, db;
    double scale, gap = 1e30, *s1, *s2;
    int same;
    ENSURE(w && w2);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d0) == SPS_OK);
    scale = fabs((double)d0.linear_momentum[0]);
    ENSURE(sps_world_advance(w, 0.04, track_gap, &gap) == SPS_OK); /* the water arrives at 0.015 s */
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d1) == SPS_OK && sps_world_diagnostics(w, block, &db) == SPS_OK);
    printf("    momentum x %.6g -> %.6g (block %.4g), y %.3g; smallest gap %.3f dp\n", (double)d0.linear_momentum[0],
           (double)d1.linear_momentum[0], (double)db.linear_momentum[0], (double)d1.linear_momentum[1], gap);
    ENSURE_NEAR(d1.linear_momentum[0], d0.linear_momentum[0], 1e-12 * scale); /* round-off of sums of ~1e5 pair forces */
    ENSURE_NEAR(d1.linear_momentum[1], d0.linear_momentum[1], 1e-12 * scale);
    ENSURE(db.linear_momentum[0] > 0.05 * scale); /* the water pushed the block (measured 0.105) */
    ENSURE(gap > 0.5);                            /* the wall images keep the water off the solid (measured 1.14) */
    ENSURE(sps_world_advance(w2, 0.04, NULL, NULL) == SPS_OK);
    s1 = snapshot(w); s2 = snapshot(w2);
    ENSURE(s1 && s2);
    same = memcmp(s1, s2, sizeof(double) * 6 * (size_t)sps_world_particle_count(w)) == 0;
    free(s1); free(s2);
    sps_world_destroy(w); sps_world_destroy(w2);
    ENSURE(same);
    return 0;
}

static sps_real hydrostatic_fsi_04(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(1000 * 9.81 * (0.4 - (double)x[1]));
}

/* Water 0.4 m deep at rest in a U-shaped tank that is a rigid body (no analytic walls), filled
   up to the tank on the lattice and started hydrostatic: no first-step kick, the first layer
   stays dp/2 from the solid's surface (dp from its surface particles) at the floor and at the
   wall, the mid-depth pressure stays that of the column and no current builds up. */
static int test_coupling_hydrostatic_rest(void) {
    const double dp = 0.02, depth = 0.4, width = 0.4, t = 3 * dp, g = 9.81, v_ref = sqrt(2 * g * depth);
    sps_world* w = fsi_world(dp, g, 1);
    sps_body_def wd = fsi_water(10 * v_ref), td = sps_default_body_def();
    sps_body water, tank;
    sps_diagnostics d;
    const sps_real *x, *y, *p;
    double floor_gap = 0, wall_gap = 0, p_mid = 0, first_speed;
    int i, first, count, components, nf = 0, nw = 0, nm = 0;
    ENSURE(w);
    td.name = "tank";
    td.material.kind = SPS_MATERIAL_RIGID;
    ENSURE(sps_world_add_body(w, &wd, &water) == SPS_OK && fsi_box(w, water, 0, 0, width, depth));
    ENSURE(sps_body_set_pressure(w, water, hydrostatic_fsi_04, NULL) == SPS_OK);
    ENSURE(sps_world_add_body(w, &td, &tank) == SPS_OK && fsi_box(w, tank, -t, -t, width + t, 0));
    ENSURE(fsi_box(w, tank, -t, 0, 0, 0.6) && fsi_box(w, tank, width, 0, width + t, 0.6));
    ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, water, &d) == SPS_OK);
    first_speed = (double)d.max_speed;
    ENSURE(sps_world_advance(w, 0.5, NULL, NULL) == SPS_OK); /* about 35 acoustic crossings of the column */
    ENSURE(sps_world_diagnostics(w, water, &d) == SPS_OK);
    ENSURE(sps_body_field(w, water, "density", &components, &first, &count) != NULL);
    x = sps_world_field(w, SPS_FIELD_POSITION_X); y = sps_world_field(w, SPS_FIELD_POSITION_Y); p = sps_world_field(w, SPS_FIELD_PRESSURE);
    for (i = first; i < first + count; ++i) {
        if (x[i] > 0.25 * width && x[i] < 0.75 * width && y[i] < dp) { floor_gap += y[i]; ++nf; } /* surface y = 0 */
        if (y[i] > 0.25 * depth && y[i] < 0.75 * depth && x[i] < dp) { wall_gap += x[i]; ++nw; } /* surface x = 0 */
        if (fabs(y[i] - depth / 2) < dp) { p_mid += p[i]; ++nm; }
    }
    ENSURE(nf > 0 && nw > 0 && nm > 0);
    floor_gap /= nf * dp; wall_gap /= nw * dp; p_mid /= nm;
    printf("    first step max speed %.3g m/s; first layer %.3f dp (floor), %.3f dp (wall) from the surface; mid-depth p %.1f Pa "
           "(column %.1f), max speed %.3g m/s (%.2g sqrt(2 g H))\n", first_speed, floor_gap, wall_gap, p_mid, 1000 * g * depth / 2,
           (double)d.max_speed, (double)d.max_speed / v_ref);
    ENSURE(first_speed < 0.005 * v_ref);      /* no kick (measured 0.25 %; the penalty threw a particle at 130 %) */
    ENSURE(fabs(floor_gap - 0.5) < 0.1);      /* the issue's dp/2 +- 0.1 dp (measured 0.53) */
    ENSURE(fabs(wall_gap - 0.5) < 0.1);       /* (measured 0.51) */
    /* 4 %: as the analytic-wall tank (test_fluid_hydrostatic_rest), the column rings after its start (measured +3.3 %) */
    ENSURE_NEAR(p_mid, 1000 * g * depth / 2, 0.04 * 1000 * g * depth / 2);
    ENSURE(d.max_speed < 0.03 * v_ref);       /* no current: the ripple (measured 2.0 %) */
    sps_world_destroy(w);
    return 0;
}

static sps_real hydrostatic_fsi_05(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(1000 * 9.81 * (0.5 - (double)x[1]));
}

/* The draft of block b (its mean height minus half its height `size`) below the water's level
   (the water's area at rho0 plus the block's part below the level fill the tank's width). */
static double fsi_draft(const sps_world* w, sps_body water, sps_body block, double size, double width) {
    const sps_real *y = sps_world_field(w, SPS_FIELD_POSITION_Y), *m = sps_world_field(w, SPS_FIELD_MASS);
    double bottom = 0, area = 0;
    int i, first, count, components;
    sps_body_field(w, block, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) bottom += y[i];
    bottom = bottom / count - 0.5 * size;
    sps_body_field(w, water, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) area += m[i] / 1000;
    return (area - size * bottom) / (width - size) - bottom; /* level (width - size) + size bottom = area */
}

/* An elastic block of density 600 starts where a block of density 500 floats (water filled
   round it on the lattice) and, damped (the block only), sinks to the draft Archimedes gives,
   0.6 of its height. */
static int test_coupling_floating_block(void) {
    const double dp = 0.02, width = 1, depth = 0.5, size = 0.2, draft0 = 0.5 * size, draft = 0.6 * size;
    sps_world* w = fsi_world(dp, 9.81, 1);
    sps_body_def wd = fsi_water(10 * sqrt(2 * 9.81 * depth)), bd = sps_default_body_def();
    sps_body water, block;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 2, 0};
    double mean = 0;
    int k;
    ENSURE(w);
    bd.name = "block";
    bd.material.density = 600;
    bd.material.youngs_modulus = 2e6;
    bd.damping = 10; /* about critical for its heave (DAMPING: the equilibrium does not depend on it) */
    ENSURE(sps_world_add_box_walls(w, lo, hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) == SPS_OK);
    ENSURE(sps_world_add_body(w, &wd, &water) == SPS_OK && fsi_box(w, water, 0, 0, width, depth - draft0));
    ENSURE(fsi_box(w, water, 0, depth - draft0, 0.4, depth) && fsi_box(w, water, 0.6, depth - draft0, width, depth));
    ENSURE(sps_body_set_pressure(w, water, hydrostatic_fsi_05, NULL) == SPS_OK);
    ENSURE(sps_world_add_body(w, &bd, &block) == SPS_OK && fsi_box(w, block, 0.4, depth - draft0, 0.6, depth - draft0 + size));
    for (k = 1; k <= 10; ++k) { /* the mean over 0.8 .. 1 s */
        ENSURE(sps_world_advance(w, (sps_real)(0.8 + 0.02 * k), NULL, NULL) == SPS_OK);
        mean += fsi_draft(w, water, block, size, width) / 10;
    }
    printf("    draft %.4f m, Archimedes %.4f m (%+.2f %%)\n", mean, draft, 100 * (mean / draft - 1));
    ENSURE_NEAR(mean, draft, 0.03 * draft); /* the issue's 3 % (measured -1.1 %) */
    sps_world_destroy(w);
    return 0;
}

/* Added mass: a block 50 times lighter than water and soft (E = 4 kPa: its own sound speed 14
   m/s, the water's 20) dropped onto water stays finite: the coupling's signal speed c0_f
   sqrt(rho_f / rho_s) = 141 m/s shortens the time step (without it: a negative density within
   2 ms). */
static int test_coupling_light_soft_block(void) {
    sps_world* w = fsi_world(0.02, 9.81, 1);
    sps_body_def wd = fsi_water(20), bd = sps_default_body_def();
    sps_body water, block;
    sps_diagnostics d;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.4, 1, 0};
    ENSURE(w);
    ENSURE(sps_world_add_box_walls(w, lo, hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) == SPS_OK);
    bd.name = "block";
    bd.material.density = 20;
    bd.material.youngs_modulus = 4e3;
    ENSURE(sps_world_add_body(w, &wd, &water) == SPS_OK && fsi_box(w, water, 0, 0, 0.4, 0.2));
    ENSURE(sps_world_add_body(w, &bd, &block) == SPS_OK && fsi_box(w, block, 0.1, 0.2, 0.3, 0.3));
    ENSURE(sps_world_advance(w, 0.03, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
    printf("    max speed %.3g m/s, density %.4g .. %.4g\n", (double)d.max_speed, (double)d.min_density, (double)d.max_density);
    ENSURE(d.max_speed < 1); /* finite and calm: a fall of 0.03 s reaches 0.3 m/s (measured 0.125 m/s) */
    sps_world_destroy(w);
    return 0;
}

/* A fluid and a solid that do not touch get a warning naming both: the water would flow through. */
static int test_coupling_bad_input(void) {
    sps_world* w = fsi_world(0.02, 9.81, 1);
    sps_body_def wd = fsi_water(20), sd = sps_default_body_def();
    sps_body water, plate;
    ENSURE(w);
    sd.name = "plate";
    ENSURE(sps_world_add_body(w, &wd, &water) == SPS_OK && fsi_box(w, water, 0, 0.1, 0.2, 0.3));
    ENSURE(sps_world_add_body(w, &sd, &plate) == SPS_OK && fsi_box(w, plate, 0, 0, 0.2, 0.1));
    ENSURE(sps_world_set_contact(w, water, plate, 0) == SPS_OK);
    g_log_count = 0;
    ENSURE(sps_world_step(w) == SPS_OK);
    printf("    %s\n", g_log_last);
    ENSURE(g_log_count > 0 && strstr(g_log_last, "'water' and 'plate'") && strstr(g_log_last, "flows through"));
    ENSURE(sps_world_set_contact(w, water, plate, 1) == SPS_OK); /* touching again: no warning */
    g_log_count = 0;
    ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(g_log_count == 0);
    sps_world_destroy(w);
    return 0;
}

/* ============================================================================================ */
/* >>user scenes: safe for the scenes users write (default rotation, watchdog, set-up checks, game API) */

static sps_real disc_at_quarter_metre(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(sqrt(x[0] * x[0] + (x[1] - 0.25) * (x[1] - 0.25)) - 0.05);
}
static void rigid_translation_x(const sps_real x[3], sps_real v[3], void* user) {
    (void)x; (void)user;
    v[0] = 1;
}
static int stop_after_one_step(sps_world* w, void* user) {
    (void)w; (void)user;
    return 1;
}

/* The tumbling body with the public API: a rubber cube (3D, side 0.1 m, E 1e6,
   dp 0.01) or disc (2D, radius 0.05 m) spinning at spin rad/s about z, its lowest point 0.2 m
   above a no-slip floor, under gravity; the watchdog's limit 2 % (the issue's acceptance). */
static sps_world* tumbling_body(int dim, sps_shear shear, sps_rotation rotation, int use_default, double spin, int stops,
                                sps_wall_slip slip, sps_body* out) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {-0.05, 0.2, -0.05}, hi[3] = {0.05, 0.3, 0.05}, origin[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    const sps_real still[3] = {0, 0, 0}, omega[3] = {0, 0, (sps_real)spin};
    sps_world* w = NULL;
    wd.dim = dim;
    wd.dp = 0.01;
    wd.threads = 1;
    wd.gravity[1] = -9.81;
    wd.energy_growth_limit = 0.02;
    wd.energy_growth_stops = stops;
    wd.log = warning_log;
    bd.shear = shear;
    if (!use_default) bd.rotation = rotation;
    if (sps_world_create(&wd, &w) != SPS_OK || sps_world_add_body(w, &bd, out) != SPS_OK) return NULL;
    if (dim == 3 ? sps_body_add_box(w, *out, lo, hi, NULL) != SPS_OK
                 : sps_body_add_sdf(w, *out, lo, hi, disc_at_quarter_metre, NULL, NULL) != SPS_OK)
        return NULL;
    if (sps_world_add_wall(w, origin, up, slip) != SPS_OK || sps_body_set_rigid_motion(w, *out, still, omega) != SPS_OK)
        return NULL;
    return w;
}

/* The default body (rotation auto = pair) through the tumbling scene: the watchdog's account
   never rises 2 % above its start (the issue's acceptance), while the mean rotation, the old
   default, gains more than the limit in the 2D scene (so the check can fail). 2D over the
   issue's 1 s, 3D over 0.3 s (the first impact and rebound; bench/user_scenes runs the whole
   second: bench/VALIDATION.md). */
static int test_user_scene_tumbling_default(void) {
    int dim;
    for (dim = 2; dim <= 3; ++dim) {
        const double t_end = dim == 2 ? 1.0 : 0.3;
        sps_diagnostics d_default, d_mean;
        sps_body b;
        sps_world* w = tumbling_body(dim, SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 1, 20, 0, SPS_WALL_NO_SLIP, &b);
        ENSURE(w != NULL && sps_world_advance(w, t_end, NULL, NULL) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d_default) == SPS_OK);
        sps_world_destroy(w);
        printf("    %dD to t = %g s: default growth %.4f (%d events)\n", dim, t_end, (double)d_default.energy_growth,
               d_default.energy_growth_events);
        ENSURE(d_default.energy_growth < 0.02 && d_default.energy_growth_events == 0); /* the default must not gain: 2 % of the mechanical energy, the watchdog's noise */
        if (dim == 3) break;
        w = tumbling_body(dim, SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0, 20, 0, SPS_WALL_NO_SLIP, &b);
        ENSURE(w != NULL && sps_world_advance(w, t_end, NULL, NULL) == SPS_OK); /* warns, returns SPS_OK ... */
        ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d_mean) == SPS_OK);
        sps_world_destroy(w);
        printf("    %dD mean rotation: growth %.4f (%d events)\n", dim, (double)d_mean.energy_growth, d_mean.energy_growth_events);
        ENSURE(d_mean.energy_growth > 0.02 && d_mean.energy_growth_events > 0); /* ... but the caller can tell */
    }
    { /* GNO-A's default (auto = mean) in the user-scene map's worst cell for GNO-A with the pair
         rotation: the 2D disc at 50 rad/s on a free-slip floor (pair: 5.9 % growth) */
        sps_diagnostics d;
        sps_body b;
        sps_world* w = tumbling_body(2, SPS_SHEAR_GNO_A, SPS_ROTATION_MEAN, 1, 50, 0, SPS_WALL_FREE_SLIP, &b);
        ENSURE(w != NULL && sps_world_advance(w, 1.0, NULL, NULL) == SPS_OK && sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
        sps_world_destroy(w);
        printf("    2D GNO-A default, 50 rad/s, free slip: growth %.4f (%d events)\n", (double)d.energy_growth, d.energy_growth_events);
        ENSURE(d.energy_growth < 0.02 && d.energy_growth_events == 0); /* 2 % of the mechanical energy: the watchdog's noise */
    }
    return 0;
}

/* The watchdog's message names the likely cause and its fix (here the mean rotation), and with
   energy_growth_stops = 1 the run stops with SPS_ERR_UNSTABLE instead. */
static int test_watchdog_names_rotation(void) {
    sps_body b;
    sps_world* w = tumbling_body(2, SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0, 20, 0, SPS_WALL_NO_SLIP, &b);
    g_warnings = 0;
    ENSURE(w != NULL && sps_world_advance(w, 1.0, NULL, NULL) == SPS_OK);
    printf("    %s\n", g_warning_last);
    ENSURE(g_warnings == 1 && strstr(g_warning_last, "rotation = mean") && strstr(g_warning_last, "SPS_ROTATION_PAIR"));
    sps_world_destroy(w);
    w = tumbling_body(2, SPS_SHEAR_ENO_A, SPS_ROTATION_MEAN, 0, 20, 1, SPS_WALL_NO_SLIP, &b);
    ENSURE(w != NULL && sps_world_advance(w, 1.0, NULL, NULL) == SPS_ERR_UNSTABLE && sps_world_time(w) < 1.0);
    ENSURE(strstr(sps_world_last_error(w), "unstable: energy watchdog") && strstr(sps_world_last_error(w), "rotation = mean"));
    sps_world_destroy(w);
    return 0;
}

/* A wall whose normal points into the body under it: the first step refuses, naming the wall,
   the body and how many of its particles are on the solid side. */
static int test_setup_body_behind_wall(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {0, 0.1, 0}, hi[3] = {0.1, 0.2, 0}, origin[3] = {0, 0, 0}, down[3] = {0, -1, 0};
    sps_world* w = NULL;
    sps_body b;
    wd.log = quiet_log;
    bd.name = "block";
    ENSURE(sps_world_create(&wd, &w) == SPS_OK && sps_world_add_body(w, &bd, &b) == SPS_OK);
    ENSURE(sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_world_add_wall(w, origin, down, SPS_WALL_FREE_SLIP) == SPS_OK);
    ENSURE(sps_world_step(w) == SPS_ERR_STATE);
    printf("    %s\n", sps_world_last_error(w));
    ENSURE(strstr(sps_world_last_error(w), "wall 0") && strstr(sps_world_last_error(w), "100 of the 100 particles of body 'block'"));
    sps_world_destroy(w);
    return 0;
}

/* Set-up mistakes that used to pass silently: a velocity set on an empty body, an angle in
   radians, an advance to a past time, a run of years, an unknown field name, a stress asked of
   an ENO-A body. Each names the field, the value and the fix. */
static int test_setup_mistakes_named(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.1, 0}, v[3] = {1, 0, 0}, omega[3] = {0, 0, 0};
    sps_world* w = NULL;
    sps_body b, sand;
    wd.log = warning_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK && sps_world_add_body(w, &bd, &b) == SPS_OK);
    ENSURE(sps_body_set_velocity(w, b, rigid_translation_x, NULL) == SPS_ERR_STATE);
    ENSURE(strstr(sps_world_last_error(w), "has no particles yet: add them first"));
    ENSURE(sps_body_set_rigid_motion(w, b, v, omega) == SPS_ERR_STATE);
    ENSURE(sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK && sps_body_set_rigid_motion(w, b, v, omega) == SPS_OK);
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    bd.material.friction_angle = 0.52; /* 30 degrees in radians */
    g_warnings = 0;
    ENSURE(sps_world_add_body(w, &bd, &sand) == SPS_OK && g_warnings == 1);
    printf("    %s\n", g_warning_last);
    ENSURE(strstr(g_warning_last, "friction_angle = 0.52") && strstr(g_warning_last, "look like radians"));
    bd.material.friction_angle = 30; /* degrees: no warning */
    ENSURE(sps_world_add_body(w, &bd, &sand) == SPS_OK && g_warnings == 1);
    bd.shear = SPS_SHEAR_GNO_A; /* the default rotation (auto) keeps a granular GNO-A body valid: mean, not pair */
    ENSURE(bd.rotation == SPS_ROTATION_AUTO && sps_world_add_body(w, &bd, &sand) == SPS_OK);
    sps_world_destroy(w);
    wd.gravity[1] = 0;
    bd = sps_default_body_def();
    ENSURE(sps_world_create(&wd, &w) == SPS_OK && sps_world_add_body(w, &bd, &b) == SPS_OK);
    ENSURE(sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK && sps_world_step(w) == SPS_OK);
    ENSURE(sps_world_advance(w, 0, NULL, NULL) == SPS_ERR_INVALID_ARG);
    printf("    %s\n", sps_world_last_error(w));
    ENSURE(strstr(sps_world_last_error(w), "t_end = 0 s is before the world's time"));
    g_warnings = 0;
    ENSURE(sps_world_advance(w, 1e9, stop_after_one_step, NULL) == SPS_OK && g_warnings == 1);
    printf("    %s\n", g_warning_last);
    ENSURE(strstr(g_warning_last, "t_end = 1e+09 s is about") && strstr(g_warning_last, "acoustic sub-steps"));
    ENSURE(sps_world_field_by_name(w, "velocty_x", NULL) == NULL);
    ENSURE(strstr(sps_world_last_error(w), "name = 'velocty_x', allowed velocity_x/_y/_z, position_x/_y/_z"));
    ENSURE(sps_body_field(w, b, "shear_stress", NULL, NULL, NULL) == NULL);
    ENSURE(strstr(sps_world_last_error(w), "track_stress = 1"));
    { /* a drag through one frame (the long drag test is left out of the sanitized run) */
        sps_drag drag;
        const sps_real grab[3] = {0.05, 0.05, 0};
        ENSURE(sps_body_drag_begin(w, b, grab, 1e3, 10, 0, &drag) == SPS_OK && drag.weight_sum > 0);
        drag.target[0] += 0.01;
        ENSURE(sps_world_advance_frame(w, (sps_real)(1.0 / 60), 0, NULL) == SPS_OK && sps_body_drag_end(w, &drag) == SPS_OK);
    }
    sps_world_destroy(w);
    return 0;
}

/* sps_body_set_rigid_motion about the current centre of mass: after the body has moved, its
   momentum is M v and its angular momentum about the current centre is I omega (2D: I the
   polar moment sum m |x - x_cm|^2), to round-off. */
static int test_rigid_motion_about_current_centre(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.05, 0}, v[3] = {0.5, -0.2, 0}, omega[3] = {0, 0, 3};
    const sps_real *x, *y, *vx, *vy, *m;
    double mass = 0, cx = 0, cy = 0, px = 0, py = 0, lz = 0, inertia = 0;
    sps_world* w = NULL;
    sps_body b;
    int i, n;
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK && sps_world_add_body(w, &bd, &b) == SPS_OK);
    ENSURE(sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK && sps_body_set_velocity(w, b, rigid_translation_x, NULL) == SPS_OK);
    ENSURE(sps_world_advance(w, 0.05, NULL, NULL) == SPS_OK); /* moved 0.05 m along x */
    ENSURE(sps_body_set_rigid_motion(w, b, v, omega) == SPS_OK);
    n = sps_world_particle_count(w);
    x = sps_world_field(w, SPS_FIELD_POSITION_X); y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    vx = sps_world_field(w, SPS_FIELD_VELOCITY_X); vy = sps_world_field(w, SPS_FIELD_VELOCITY_Y); m = sps_world_field(w, SPS_FIELD_MASS);
    for (i = 0; i < n; ++i) { mass += m[i]; cx += m[i] * x[i]; cy += m[i] * y[i]; }
    cx /= mass; cy /= mass;
    for (i = 0; i < n; ++i) {
        px += m[i] * vx[i]; py += m[i] * vy[i];
        lz += m[i] * ((x[i] - cx) * vy[i] - (y[i] - cy) * vx[i]);
        inertia += m[i] * ((x[i] - cx) * (x[i] - cx) + (y[i] - cy) * (y[i] - cy));
    }
    printf("    centre (%.4f, %.4f) m; p = (%.6g, %.6g), M v = (%.6g, %.6g); L = %.6g, I omega = %.6g\n", cx, cy, px, py, mass * 0.5,
           mass * -0.2, lz, inertia * 3);
    ENSURE(cx > 0.095); /* the body has moved: the reference centre (0.05) would be wrong */
    ENSURE(fabs(px - mass * 0.5) < 1e-12 * mass && fabs(py + mass * 0.2) < 1e-12 * mass); /* round-off */
    ENSURE(fabs(lz - 3 * inertia) < 1e-12 * inertia);                                   /* round-off */
    sps_world_destroy(w);
    return 0;
}

/* sps_world_advance_frame in seconds: without a budget a frame lands exactly on its simulated
   time and is deterministic; a frame time that looks like a sub-step count is refused; with a
   budget too small for anything the frame runs at most one sub-step (the hard cap's promise:
   never more than one sub-step over). */
static int test_frame_in_seconds(void) {
    sps_world *a = frame_world(SPS_STEPPING_DUAL, 100, 0.5, NULL), *b = frame_world(SPS_STEPPING_DUAL, 100, 0.5, NULL);
    sps_diagnostics d;
    sps_real covered = 0;
    long before;
    int k;
    ENSURE(a && b);
    for (k = 0; k < 6; ++k) {
        ENSURE(sps_world_advance_frame(a, (sps_real)(1.0 / 60), 0, &covered) == SPS_OK);
        ENSURE(fabs(covered - 1.0 / 60) < 1e-12); /* the last step lands on the frame's end: round-off */
    }
    ENSURE(fabs(sps_world_time(a) - 0.1) < 1e-12 && sps_world_advance(b, 0.1, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_advance_frame(a, 40, 0, &covered) == SPS_ERR_INVALID_ARG && covered == 0);
    ENSURE(strstr(sps_world_last_error(a), "frame_seconds = 40, allowed (0, 1]") && strstr(sps_world_last_error(a), "sps_world_advance_substeps"));
    for (k = 0; k < 5; ++k) {
        ENSURE(sps_world_diagnostics(a, ALL_BODIES, &d) == SPS_OK);
        before = d.acoustic_steps;
        ENSURE(sps_world_advance_frame(a, (sps_real)(1.0 / 60), 1e-12, &covered) == SPS_OK);
        ENSURE(sps_world_diagnostics(a, ALL_BODIES, &d) == SPS_OK);
        ENSURE(d.acoustic_steps - before <= 1); /* a budget of 1e-12 s: one sub-step at most (the first ever measures the cost) */
    }
    sps_world_destroy(a);
    sps_world_destroy(b);
    return 0;
}

/* The drag: a 2D jelly of 1024 particles (0.32 m square, E 1e5) on a floor under gravity,
   grabbed at a corner region and pulled around a circle of radius 0.2 m (period 2 s, starting
   with a lift) for 3 s with advance_frame at 60 frames per second. Every particle keeps a
   neighbour within 2 dp (none torn out), and the grabbed point follows
   the target (within 0.1 m at the end: the spring's sag under the jelly's weight is 0.05 m). */
static int test_user_scene_dragged_jelly(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {-0.16, 0, 0}, hi[3] = {0.16, 0.32, 0}, origin[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    const sps_real grab[3] = {0.1, 0.26, 0};
    sps_world* w = NULL;
    sps_body b;
    sps_drag drag;
    sps_particle_state ps;
    double worst_gap = 0, miss = 0;
    int frame, n, i, j, grabbed;
    wd.dp = 0.01;
    wd.gravity[1] = -9.81;
    wd.log = quiet_log;
    bd.material.youngs_modulus = 1e5;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK && sps_world_add_body(w, &bd, &b) == SPS_OK);
    ENSURE(sps_body_add_box(w, b, lo, hi, &n) == SPS_OK && n == 1024);
    ENSURE(sps_world_add_wall(w, origin, up, SPS_WALL_NO_SLIP) == SPS_OK);
    ENSURE(sps_body_drag_begin(w, b, grab, 2e4, 800, 0.05, &drag) == SPS_OK);
    grabbed = sps_world_nearest_particle(w, b, grab);
    for (frame = 1; frame <= 180; ++frame) {
        const double t = frame / 60.0;
        const sps_real *x, *y;
        drag.target[0] = grab[0] + 0.2 * sin(PI * t) ;
        drag.target[1] = grab[1] + 0.2 * (1 - cos(PI * t)) + 0.1;
        ENSURE(sps_world_advance_frame(w, (sps_real)(1.0 / 60), 0, NULL) == SPS_OK);
        if (frame % 6) continue;
        x = sps_world_field(w, SPS_FIELD_POSITION_X);
        y = sps_world_field(w, SPS_FIELD_POSITION_Y);
        for (i = 0; i < n; ++i) { /* each particle's nearest neighbour */
            double nearest = 1e30;
            for (j = 0; j < n; ++j)
                if (j != i) nearest = fmin(nearest, (x[i] - x[j]) * (x[i] - x[j]) + (y[i] - y[j]) * (y[i] - y[j]));
            worst_gap = fmax(worst_gap, sqrt(nearest) / wd.dp);
        }
    }
    ENSURE(sps_world_particle(w, grabbed, &ps) == SPS_OK);
    miss = hypot(ps.position[0] - drag.target[0], ps.position[1] - drag.target[1]);
    printf("    3 s dragged: largest nearest-neighbour distance %.3f dp (limit 2); grabbed point %.3f m from the target\n", worst_gap, miss);
    ENSURE(worst_gap < 2);  /* no particle torn out: 2 dp is past the kernel's reach of a neighbour */
    ENSURE(miss < 0.1);     /* it follows: sag 0.05 m plus the lag of the moving target */
    ENSURE(sps_body_drag_end(w, &drag) == SPS_OK);
    ENSURE(sps_body_drag_begin(w, b, grab, -1, 0, 0, &drag) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "stiffness = -1"));
    sps_world_destroy(w);
    return 0;
}

/* ---- >>contact: normal contact damping (bodies that come to rest) ---- */

/* The x momentum of body b. */
static double body_momentum_x(sps_world* w, sps_body b) {
    sps_diagnostics d;
    return sps_world_diagnostics(w, b, &d) == SPS_OK ? (double)d.linear_momentum[0] : 0;
}

/* Two blocks meet head on at 0.02 c0 each (no gravity). With contact_damping 1 on both the pair
   dashpot takes energy: they part at a lower relative speed than the elastic contact's; the
   dashpot's pair forces are equal and opposite, so linear momentum stays at its start to
   round-off; and the energy account (kinetic + strain + contact + dissipated work) closes. */
static int test_contact_damping_pair(void) {
    double restitution[2] = {0, 0}, account = 0;
    int damped;
    for (damped = 0; damped < 2; ++damped) {
        sps_world* w = new_world(2, 0.01);
        sps_body_def bd = friction_test_body(0, 1e-3); /* a vanishing eta: the Riemann dissipation's work is counted too */
        const sps_real lo1[3] = {0, 0, 0}, hi1[3] = {0.1, 0.1, 0}, lo2[3] = {0.13, 0, 0}, hi2[3] = {0.23, 0.1, 0};
        sps_body left, right;
        sps_diagnostics d0, d1;
        sps_real c0, v;
        double p_in, scale;
        ENSURE(w);
        bd.track_stress = 1;
        bd.contact_damping = (sps_real)damped;
        ENSURE(sps_world_add_body(w, &bd, &left) == SPS_OK && sps_body_add_box(w, left, lo1, hi1, NULL) == SPS_OK);
        ENSURE(sps_world_add_body(w, &bd, &right) == SPS_OK && sps_body_add_box(w, right, lo2, hi2, NULL) == SPS_OK);
        ENSURE(sps_body_material_constants(w, left, &c0, NULL, NULL) == SPS_OK);
        v = (sps_real)(0.02 * c0);
        ENSURE(sps_body_set_velocity(w, left, velocity_x, &v) == SPS_OK);
        v = -v;
        ENSURE(sps_body_set_velocity(w, right, velocity_x, &v) == SPS_OK);
        p_in = body_momentum_x(w, left) - body_momentum_x(w, right); /* equal masses: momenta stand for velocities */
        ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d0) == SPS_OK);
        scale = p_in;
        ENSURE(sps_world_advance(w, (sps_real)(1.2 / c0), NULL, NULL) == SPS_OK); /* through the impact: about 6 transits of a block */
        ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d1) == SPS_OK);
        restitution[damped] = (body_momentum_x(w, right) - body_momentum_x(w, left)) / p_in;
        printf("    contact_damping %d: restitution %.4f, momentum x %.3g -> %.3g (scale %.3g), dissipated %.4g of %.4g J\n", damped,
               restitution[damped], (double)d0.linear_momentum[0], (double)d1.linear_momentum[0], scale, (double)d1.viscous_work,
               (double)d0.kinetic_energy);
        ENSURE(fabs(d1.contact_energy) < 1e-3 * d0.kinetic_energy); /* they have parted */
        ENSURE_NEAR(d1.linear_momentum[0], d0.linear_momentum[0], 1e-12 * scale); /* round-off of sums of pair forces */
        ENSURE_NEAR(d1.linear_momentum[1], d0.linear_momentum[1], 1e-12 * scale);
        if (damped) account = (d1.kinetic_energy + d1.strain_energy + d1.contact_energy + d1.viscous_work) / d0.kinetic_energy;
        sps_world_destroy(w);
    }
    printf("    energy account with the dissipated work: %.4f of its start\n", account);
    ENSURE(restitution[0] > 0 && restitution[1] < restitution[0] - 0.05); /* the dashpot is felt (measured: see the output) */
    ENSURE_NEAR(account, 1, 0.02); /* the issue's 2 %: the work is summed at the velocities before the kick (first order in dt) */
    return 0;
}

/* A block thrown at 0.02 c0 onto a floor wall (no gravity) leaves slower with contact_damping 0.5
   than with the elastic contact, and the energy account with the wall dashpot's work closes. */
static int test_contact_damping_wall(void) {
    double restitution[2] = {0, 0}, account = 0;
    int damped;
    for (damped = 0; damped < 2; ++damped) {
        sps_world* w = new_world(2, 0.01);
        sps_body_def bd = friction_test_body(0, 1e-3);
        const sps_real lo[3] = {0, 0.03, 0}, hi[3] = {0.1, 0.13, 0}, point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
        sps_body b;
        sps_diagnostics d0, d1;
        sps_real c0, v;
        ENSURE(w);
        bd.track_stress = 1;
        bd.contact_damping = (sps_real)(0.5 * damped);
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
        ENSURE(sps_world_add_wall(w, point, up, SPS_WALL_FREE_SLIP) == SPS_OK);
        ENSURE(sps_body_material_constants(w, b, &c0, NULL, NULL) == SPS_OK);
        v = (sps_real)(0.02 * c0);
        ENSURE(sps_body_set_velocity(w, b, velocity_down, &v) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, b, &d0) == SPS_OK);
        ENSURE(sps_world_advance(w, (sps_real)(3 / c0), NULL, NULL) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, b, &d1) == SPS_OK);
        restitution[damped] = d1.linear_momentum[1] / -d0.linear_momentum[1];
        printf("    contact_damping %.1f: restitution %.4f, dissipated %.4g of %.4g J\n", 0.5 * damped, restitution[damped],
               (double)d1.viscous_work, (double)d0.kinetic_energy);
        ENSURE(fabs(d1.contact_energy) < 1e-3 * d0.kinetic_energy); /* it has left the wall */
        if (damped) account = (d1.kinetic_energy + d1.strain_energy + d1.contact_energy + d1.viscous_work) / d0.kinetic_energy;
        sps_world_destroy(w);
    }
    printf("    energy account with the dissipated work: %.4f of its start\n", account);
    ENSURE(restitution[0] > 0 && restitution[1] < restitution[0] - 0.05); /* the dashpot is felt */
    ENSURE_NEAR(account, 1, 0.02); /* the issue's 2 % (first order in dt, as above) */
    return 0;
}

/* The dashpot is a gather like the rest of the contact pass: two damped blocks (800 particles,
   above the size where the step goes parallel) meeting head on give the same bits with 1 and 2
   threads. */
static int test_contact_damping_thread_count(void) {
    double* s[2];
    int threads, same;
    for (threads = 1; threads <= 2; ++threads) {
        sps_world_def wd = sps_default_world_def();
        sps_body_def bd = friction_test_body(0, 1e-3);
        const sps_real lo1[3] = {0, 0, 0}, hi1[3] = {0.1, 0.1, 0}, lo2[3] = {0.115, 0, 0}, hi2[3] = {0.215, 0.1, 0};
        sps_world* w = NULL;
        sps_body left, right;
        sps_real c0, v;
        wd.dim = 2; wd.dp = 0.005; wd.threads = threads; wd.log = quiet_log;
        ENSURE(sps_world_create(&wd, &w) == SPS_OK);
        bd.contact_damping = 1;
        ENSURE(sps_world_add_body(w, &bd, &left) == SPS_OK && sps_body_add_box(w, left, lo1, hi1, NULL) == SPS_OK);
        ENSURE(sps_world_add_body(w, &bd, &right) == SPS_OK && sps_body_add_box(w, right, lo2, hi2, NULL) == SPS_OK);
        ENSURE(sps_body_material_constants(w, left, &c0, NULL, NULL) == SPS_OK);
        v = (sps_real)(0.02 * c0);
        ENSURE(sps_body_set_velocity(w, left, velocity_x, &v) == SPS_OK);
        ENSURE(sps_world_advance(w, (sps_real)(0.5 / c0), NULL, NULL) == SPS_OK); /* into the impact */
        s[threads - 1] = snapshot(w);
        ENSURE(s[threads - 1]);
        if (threads == 2) {
            same = memcmp(s[0], s[1], sizeof(double) * 6 * (size_t)sps_world_particle_count(w)) == 0;
            ENSURE(same);
        }
        sps_world_destroy(w);
    }
    free(s[0]); free(s[1]);
    return 0;
}

/* Bad contact_damping is refused with a message naming the field, the value and the range. */
static int test_contact_damping_bad_input(void) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def bad = friction_test_body(0, 0);
    ENSURE(w);
    bad.contact_damping = -0.1; ENSURE(rejects_body_def(w, &bad, "contact_damping = -0.1, allowed [0, 1]") == 0);
    bad.contact_damping = 2;    ENSURE(rejects_body_def(w, &bad, "contact_damping = 2, allowed [0, 1]") == 0);
    bad.contact_damping = (sps_real)NAN; ENSURE(rejects_body_def(w, &bad, "contact_damping = nan, allowed [0, 1]") == 0);
    bad.contact_damping = (sps_real)0.5; bad.contact = 0;
    ENSURE(rejects_body_def(w, &bad, "contact_damping > 0 with contact = 0") == 0);
    bad = sps_default_body_def(); bad.material.kind = SPS_MATERIAL_FLUID; bad.contact_damping = (sps_real)0.5;
    ENSURE(rejects_body_def(w, &bad, "contact_damping > 0 with contact = 0 or material.kind = fluid") == 0);
    sps_world_destroy(w);
    return 0;
}

/* ---- granular media that hold their shape (GRANULAR; chapter >>material: Drucker-Prager,
   >>walls for fluids) ---- */

/* The C5 soil block of test_granular_block_at_rest in its box, started from its geostatic
   stress, with the given shear formulation, run to t_end: its hourglass indicator and its
   mid-depth vertical stress over the geostatic one, less 1. */
static int granular_block_run(sps_shear shear, double t_end, double* hourglass, double* stress_error) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body soil, all = {0};
    sps_diagnostics d;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {2, 1, 0}, box_hi[3] = {2, 2, 0};
    const double g = 9.8, depth = 1, dp = 0.05, rho0 = 1850;
    const sps_real *y, *p, *tau;
    double sigma_mid = 0;
    int i, n, first, mid = 0;
    wd.dim = 2;
    wd.dp = dp;
    wd.threads = 1;
    wd.gravity[1] = -g;
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.material = c5_soil();
    bd.shear = shear;
    ENSURE(sps_world_add_box_walls(w, lo, box_hi, SPS_FACE_Y_HI, SPS_WALL_NO_SLIP) == SPS_OK);
    ENSURE(sps_world_add_body(w, &bd, &soil) == SPS_OK);
    ENSURE(sps_body_add_box(w, soil, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_set_geostatic_stress(w, soil, (sps_real)depth, 0) == SPS_OK);
    ENSURE(sps_world_advance(w, (sps_real)t_end, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, all, &d) == SPS_OK);
    y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    p = sps_world_field(w, SPS_FIELD_PRESSURE);
    tau = sps_body_field(w, soil, "shear_stress", NULL, &first, &n);
    ENSURE(tau != NULL);
    for (i = 0; i < n; ++i)
        if (fabs(y[i] - depth / 2) < 0.6 * dp) { sigma_mid += tau[6 * i + 3] - p[i]; ++mid; }
    ENSURE(mid > 0);
    *hourglass = (double)d.hourglass;
    *stress_error = sigma_mid / mid / (-rho0 * g * depth / 2) - 1;
    sps_world_destroy(w);
    return 0;
}

/* The issue's acceptance: a geostatic block at rest for 2 s keeps its shape with the GNO-A
   penalty (switched off on the cone): hourglass indicator below 0.005 and the mid-depth
   vertical stress within 2 % of rho0 g H/2. The paper's formulation (the default, no
   penalty) fails the first (measured 0.11 at 2 s: the zigzag mode grows under the load), so
   the test can fail. */
static int test_granular_block_holds_shape(void) {
    double hourglass, error;
    if (granular_block_run(SPS_SHEAR_GNO_A, 2, &hourglass, &error)) return 1;
    printf("    GNO-A: hourglass %.4f, mid-depth stress %+.2f %%\n", hourglass, 100 * error);
    ENSURE(hourglass < 0.005); /* the issue's bound (measured 0.0000) */
    ENSURE(fabs(error) < 0.02); /* the issue's bound (measured +0.5 %: the lattice scale leaves 0.7 % of weight to the surface layer) */
    if (granular_block_run(SPS_SHEAR_OG, 2, &hourglass, &error)) return 1;
    printf("    OG (no penalty): hourglass %.4f, mid-depth stress %+.2f %%\n", hourglass, 100 * error);
    ENSURE(hourglass > 0.05); /* the zigzag mode the penalty removes grows without it (measured 0.11) */
    return 0;
}

/* The lattice's kernel-gradient moment that scales a granular body's stress divergence: the
   direct sum over a lattice patch (Wendland C2, h = 1.3 dp, 2D) is 0.974, not 1 (the
   continuum's value); and 1 within 1e-3 at h = 1.5 dp, where the lattice sum is near the
   integral (both from an independent sum of the kernel's closed form). */
static int test_granular_lattice_moment(void) {
    const double ratios[2] = {1.3, 1.5};
    int k;
    for (k = 0; k < 2; ++k) {
        sps_world_def wd = sps_default_world_def();
        sps_world* w = NULL;
        const double h = ratios[k], norm = 7 / (4 * 3.14159265358979323846 * h * h);
        double sum = 0;
        int a, b;
        wd.dim = 2;
        wd.dp = 1;
        wd.h_over_dp = (sps_real)h;
        wd.log = quiet_log;
        ENSURE(sps_world_create(&wd, &w) == SPS_OK);
        for (a = -4; a <= 4; ++a)
            for (b = -4; b <= 4; ++b) {
                const double r = sqrt((double)(a * a + b * b)), q = r / h, f = 1 - q / 2;
                if (r > 0 && q < 2) sum += r * (-5 * q * f * f * f) * norm / h; /* r dW/dr, V = dp^2 = 1 */
            }
        ENSURE_NEAR(sps__lattice_gradient_moment(w), -sum / 2, 1e-12);
        if (k == 0) ENSURE_NEAR(-sum / 2, 0.974, 0.001);
        else ENSURE_NEAR(-sum / 2, 1, 0.003);
        sps_world_destroy(w);
    }
    return 0;
}

/* A grain (a cohesionless particle alone) sent at v0 = 0.5 m/s along a free-slip floor with
   wall friction mu = tan(20 degrees) stops by Coulomb's law against its weight, after
   v0^2 / (2 g mu) = 0.035 m (measured 0.0350 m); without the friction it slides on. */
static int test_granular_free_grain_stops(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body grain;
    const double dp = 0.002, g = 9.8, v0 = 0.5, phi = 20, expected = v0 * v0 / (2 * g * tan(phi * 3.14159265358979323846 / 180));
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)dp, (sps_real)dp, 0}, box_lo[3] = {-1, 0, 0}, box_hi[3] = {1, 1, 0};
    sps_particle_state st;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.threads = 1;
    wd.gravity[1] = (sps_real)-g;
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    bd.material.density = 2040;
    bd.material.youngs_modulus = (sps_real)5.84e6;
    bd.material.cohesion = 0;
    bd.material.friction_angle = (sps_real)phi;
    ENSURE(sps_world_add_box_walls(w, box_lo, box_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) == SPS_OK);
    ENSURE(sps_world_set_wall_friction(w, -1, (sps_real)tan(phi * 3.14159265358979323846 / 180)) == SPS_OK);
    ENSURE(sps_world_add_body(w, &bd, &grain) == SPS_OK);
    ENSURE(sps_body_add_box(w, grain, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_world_particle_count(w) == 1);
    ENSURE(sps_world_advance(w, (sps_real)0.05, NULL, NULL) == SPS_OK); /* settles on the floor */
    ENSURE(sps_world_particle(w, 0, &st) == SPS_OK);
    st.velocity[0] = (sps_real)v0;
    st.velocity[1] = 0;
    ENSURE(sps_world_set_particle(w, 0, st.position, st.velocity) == SPS_OK);
    {
        const double x0 = (double)st.position[0];
        ENSURE(sps_world_advance(w, (sps_real)0.5, NULL, NULL) == SPS_OK);
        ENSURE(sps_world_particle(w, 0, &st) == SPS_OK);
        printf("    slid %.4f m (Coulomb: %.4f m), speed at 0.45 s after the kick %.2g m/s\n", (double)st.position[0] - x0, expected,
               (double)st.velocity[0]);
        ENSURE(fabs((double)st.velocity[0]) < 1e-3); /* at rest: the stick drag holds it */
        /* 15 %: the floor's normal force is the image's push, within a few % of the weight once the grain sits */
        ENSURE_NEAR((double)st.position[0] - x0, expected, 0.15 * expected);
    }
    sps_world_destroy(w);
    return 0;
}

/* ============================================================================================ */
/* >>restart: the fingerprint derived from the def items                                        */

/* One def field changed between the save and the restore: its name as the message writes it. */
typedef struct def_change {
    const char* name;
    int world; /* 1: a field of the world def, 0: of the body def */
    int tl;    /* 1: saved and restored with a total-Lagrangian Neo-Hookean body (the field is for those only) */
} def_change;

/* Changes field k of the list in restore_def_changes: a value the checks accept, not the default. */
static void change_def(int k, sps_world_def* wd, sps_body_def* bd) {
    sps_material_def* m = &bd->material;
    switch (k) {
    case 0: wd->dim = 3; break;
    case 1: wd->dp = 0.02; break;
    case 2: wd->h_over_dp = 1.5; break;
    case 3: wd->kernel = SPS_KERNEL_CUBIC_SPLINE; break;
    case 4: wd->stepping = SPS_STEPPING_SINGLE; break;
    case 5: wd->cfl_acoustic = 0.3; break;
    case 6: wd->cfl_advection = 0.1; break;
    case 7: wd->max_substeps = 50; break;
    case 8: wd->gravity[0] = 1; break;
    case 9: wd->gravity[1] = 1; break;
    case 10: wd->gravity[2] = 1; break;
    case 11: wd->frozen_geometry = 1; break;
    case 12: wd->neighbor_capacity = 3; break;
    case 13: wd->escape_distance = 1; break;
    case 14: wd->energy_growth_limit = 0.1; break;
    case 15: wd->energy_growth_stops = 1; break;
    case 16: wd->keep_last_good_state = 1; break;
    case 17: m->kind = SPS_MATERIAL_RIGID; break;
    case 18: m->density = 2000; break;
    case 19: m->youngs_modulus = 2e6; break;
    case 20: m->poisson_ratio = 0.25; break;
    case 21: m->yield_stress = 1e3; break;
    case 22: m->hardening_modulus = 1e3; break;
    case 23: m->sound_speed = 10; break;
    case 24: m->viscosity = 0.1; break;
    case 25: m->cohesion = 1; break;
    case 26: m->friction_angle = 10; break;
    case 27: m->friction_angle = 10; m->dilatancy_angle = 5; break; /* the file has friction_angle 0: named first */
    case 28: bd->shear = SPS_SHEAR_GNO_A; break;
    case 29: bd->rotation = SPS_ROTATION_MEAN; break;
    case 30: bd->zeta = 3; break;
    case 31: bd->xi = 3; break;
    case 32: bd->oas_epsilon = 0.2; break;
    case 33: bd->oas_exponent = 3; break;
    case 34: bd->track_stress = 1; break;
    case 35: bd->solver = SPS_SOLVER_TOTAL_LAGRANGIAN; m->kind = SPS_MATERIAL_NEO_HOOKEAN; break; /* solver named first */
    case 36: bd->transport = SPS_TRANSPORT_TVF; break;
    case 37: bd->contact = 0; break;
    case 38: bd->transport_coefficient = 0.3; break;
    case 39: bd->damping = 1; break;
    case 40: bd->hourglass_alpha = 10; break;
    case 41: bd->hourglass = SPS_HOURGLASS_PAPER; break;
    case 42: bd->artificial_viscosity = 0.5; break;
    case 43: bd->stress_diffusion = 0.2; break;
    case 44: bd->friction = 0.3; break;
    case 45: bd->contact_damping = 0.5; break;
    case 46: bd->damage_strain = 0.01; break;
    }
}

/* A block of one body, built from the defaults (tl: a total-Lagrangian Neo-Hookean body) with
   change k applied (k < 0: none). */
static sps_world* fingerprint_scene(int k, int tl, sps_result* added) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.05, 0.05};
    sps_world* w = NULL;
    sps_body b;
    wd.dp = 0.01; wd.threads = 1; wd.log = quiet_log;
    if (tl) { bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN; bd.material.kind = SPS_MATERIAL_NEO_HOOKEAN; }
    change_def(k, &wd, &bd);
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    *added = sps_world_add_body(w, &bd, &b);
    if (*added == SPS_OK) *added = sps_body_add_box(w, b, lo, hi, NULL);
    return w;
}

/* Every def field that changes results, changed between the save and the restore: the
   restore is refused with SPS_ERR_STATE, and the message names the field (the list is the
   test's own, not the library's table: a field missing from the table fails here). */
static int test_restart_every_def_field(void) {
#define WORLD_FIELD(name) {name, 1, 0}
#define BODY_FIELD(name) {name, 0, 0}
#define TL_FIELD(name) {name, 0, 1}
    static const def_change changes[] = {
        WORLD_FIELD("dim"), WORLD_FIELD("dp"), WORLD_FIELD("h_over_dp"), WORLD_FIELD("kernel"), WORLD_FIELD("stepping"),
        WORLD_FIELD("cfl_acoustic"), WORLD_FIELD("cfl_advection"), WORLD_FIELD("max_substeps"), WORLD_FIELD("gravity[0]"),
        WORLD_FIELD("gravity[1]"), WORLD_FIELD("gravity[2]"), WORLD_FIELD("frozen_geometry"), WORLD_FIELD("neighbor_capacity"),
        WORLD_FIELD("escape_distance"), WORLD_FIELD("energy_growth_limit"), WORLD_FIELD("energy_growth_stops"),
        WORLD_FIELD("keep_last_good_state"), BODY_FIELD("material.kind"), BODY_FIELD("material.density"),
        BODY_FIELD("material.youngs_modulus"), BODY_FIELD("material.poisson_ratio"), BODY_FIELD("material.yield_stress"),
        BODY_FIELD("material.hardening_modulus"), BODY_FIELD("material.sound_speed"), BODY_FIELD("material.viscosity"),
        BODY_FIELD("material.cohesion"), BODY_FIELD("material.friction_angle"), BODY_FIELD("material.friction_angle"),
        BODY_FIELD("shear"), BODY_FIELD("rotation"), BODY_FIELD("zeta"), BODY_FIELD("xi"), BODY_FIELD("oas_epsilon"),
        BODY_FIELD("oas_exponent"), BODY_FIELD("track_stress"), BODY_FIELD("solver"), BODY_FIELD("transport"),
        BODY_FIELD("contact"), BODY_FIELD("transport_coefficient"), BODY_FIELD("damping"), BODY_FIELD("hourglass_alpha"),
        BODY_FIELD("hourglass"), TL_FIELD("artificial_viscosity"), BODY_FIELD("stress_diffusion"), BODY_FIELD("friction"),
        BODY_FIELD("contact_damping"), TL_FIELD("damage_strain")};
#undef WORLD_FIELD
#undef BODY_FIELD
#undef TL_FIELD
    const int count = (int)(sizeof changes / sizeof changes[0]);
    char paths[2][40] = {"/tmp/test_sphsolid_fingerprint_XXXXXX", "/tmp/test_sphsolid_fingerprint_XXXXXX"}, needle[96];
    sps_result added = SPS_OK;
    sps_world* w;
    int fd, k, tl;
    for (tl = 0; tl < 2; ++tl) { /* the saved scenes: updated and total Lagrangian */
        w = fingerprint_scene(-1, tl, &added);
        ENSURE(w && added == SPS_OK && sps_world_step(w) == SPS_OK);
        ENSURE((fd = mkstemp(paths[tl])) >= 0);
        close(fd);
        ENSURE(sps_world_save(w, paths[tl]) == SPS_OK);
        sps_world_destroy(w);
    }
    /* one change per row of the library's tables (the dilatancy and solver changes need another
       field changed too, which the message names first) */
    ENSURE(count == SPS__WORLD_DEF_ITEMS + SPS__BODY_DEF_ITEMS);
    for (k = 0; k < count; ++k) {
        sps_result r;
        w = fingerprint_scene(k, changes[k].tl, &added);
        ENSURE(w != NULL);
        if (added != SPS_OK) printf("    change %d (%s): the scene was refused: %s\n", k, changes[k].name, sps_world_last_error(w));
        ENSURE(added == SPS_OK);
        r = sps_world_restore(w, paths[changes[k].tl]);
        snprintf(needle, sizeof needle, "%s%s = ", changes[k].world ? "another scene: " : "') ", changes[k].name);
        if (r != SPS_ERR_STATE || !strstr(sps_world_last_error(w), needle))
            printf("    change %d: restore gave %d '%s', expected SPS_ERR_STATE naming '%s'\n", k, (int)r, sps_world_last_error(w), needle);
        ENSURE(r == SPS_ERR_STATE && strstr(sps_world_last_error(w), needle));
        sps_world_destroy(w);
    }
    remove(paths[0]);
    remove(paths[1]);
    return 0;
}

/* The issue's case: an updated-Lagrangian J2 body saved, restored into a total-Lagrangian J2
   world: SPS_ERR_STATE naming the solver (it was SPS_ERR_IO, "its velocity gradient do not fit"). */
static int test_restart_ul_j2_into_tl_j2(void) {
    char path[] = "/tmp/test_sphsolid_fingerprint_XXXXXX";
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.05, 0};
    sps_world* w = NULL;
    sps_body b;
    int fd, solver;
    ENSURE((fd = mkstemp(path)) >= 0);
    close(fd);
    wd.dp = 0.01; wd.threads = 1; wd.log = quiet_log;
    bd.material.kind = SPS_MATERIAL_J2; bd.material.yield_stress = 1e4; bd.shear = SPS_SHEAR_GNO_A;
    for (solver = 0; solver < 2; ++solver) {
        bd.solver = solver ? SPS_SOLVER_TOTAL_LAGRANGIAN : SPS_SOLVER_UPDATED_LAGRANGIAN;
        ENSURE(sps_world_create(&wd, &w) == SPS_OK);
        ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK && sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
        if (solver == 0) ENSURE(sps_world_step(w) == SPS_OK && sps_world_save(w, path) == SPS_OK);
        else {
            ENSURE(sps_world_restore(w, path) == SPS_ERR_STATE);
            ENSURE(strstr(sps_world_last_error(w), "solver = 0 in the file, 1 in this world") != NULL);
        }
        sps_world_destroy(w);
    }
    remove(path);
    return 0;
}

/* ============================================================================================ */
/* >>defaults: a parameter a body does not read gets a warning naming it                       */

/* Adds a body of def bd to a fresh world; returns the warnings it logged (the last in g_log_last). */
static int unread_warnings(const sps_body_def* bd) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w = NULL;
    sps_body b;
    int before;
    wd.log = quiet_log;
    if (sps_world_create(&wd, &w) != SPS_OK) return -1;
    g_log_last[0] = 0;
    before = g_log_count;
    if (sps_world_add_body(w, bd, &b) != SPS_OK) { sps_world_destroy(w); return -1; }
    sps_world_destroy(w);
    return g_log_count - before;
}

/* cohesion on an elastic body, hourglass_alpha on an updated-Lagrangian body, zeta on a GNO-A
   body, sound_speed on a J2 body: one warning naming each field and its value; the same fields
   on bodies that read them, and the defaults, give none. */
static int test_unread_parameter_warned(void) {
    sps_body_def bd = sps_default_body_def();
    ENSURE(unread_warnings(&bd) == 0);
    bd.material.cohesion = 5;
    ENSURE(unread_warnings(&bd) == 1 && strstr(g_log_last, "material.cohesion = 5") && strstr(g_log_last, "(elastic, updated Lagrangian, ENO-A)"));
    bd = sps_default_body_def();
    bd.hourglass_alpha = 0;
    ENSURE(unread_warnings(&bd) == 1 && strstr(g_log_last, "hourglass_alpha = 0") && strstr(g_log_last, "updated Lagrangian"));
    bd = sps_default_body_def();
    bd.shear = SPS_SHEAR_GNO_A; bd.zeta = 3; bd.material.kind = SPS_MATERIAL_J2; bd.material.yield_stress = 1e4;
    bd.material.sound_speed = 20;
    ENSURE(unread_warnings(&bd) == 1 && strstr(g_log_last, "material.sound_speed = 20, zeta = 3") && strstr(g_log_last, "(J2, updated Lagrangian, GNO-A)"));
    /* the same fields where they are read: no warning */
    bd = sps_default_body_def();
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER; bd.material.cohesion = 5; bd.material.friction_angle = 30; bd.shear = SPS_SHEAR_GNO_A;
    bd.xi = 3; bd.rotation = SPS_ROTATION_MEAN;
    ENSURE(unread_warnings(&bd) == 0);
    bd = sps_default_body_def();
    bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN; bd.material.kind = SPS_MATERIAL_NEO_HOOKEAN; bd.hourglass_alpha = 10;
    ENSURE(unread_warnings(&bd) == 0);
    bd.zeta = 3; /* a total-Lagrangian body has no ENO term */
    ENSURE(unread_warnings(&bd) == 1 && strstr(g_log_last, "zeta = 3") && strstr(g_log_last, "total Lagrangian"));
    bd = sps_default_body_def();
    bd.material.kind = SPS_MATERIAL_FLUID; bd.material.sound_speed = 20; bd.material.youngs_modulus = 5e6;
    ENSURE(unread_warnings(&bd) == 1 && strstr(g_log_last, "material.youngs_modulus = 5e+06") && strstr(g_log_last, "(fluid, updated Lagrangian)"));
    return 0;
}

/* ============================================================================================ */
/* >>forces: a missing pass instance is an error at sps_world_add_body                          */

/* A model whose pressure-pass key no variant row holds (stress diffusion on an ENO-A body), or
   a total-Lagrangian model of an elastic kind, has no kernel, and sps__missing_pass names the
   pass and the choices; and every body def the checks
   accept finds all its kernels, in each of the eight world modes, in this (release) build. */
static int test_missing_pass_instance(void) {
    static const int shears[] = {SPS_SHEAR_ENO, SPS_SHEAR_ENO_A, SPS_SHEAR_OG, SPS_SHEAR_OAS, SPS_SHEAR_GNO, SPS_SHEAR_GNO_A};
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps__model m;
    sps__passes p;
    char msg[768];
    int mode, kind, shear, variant, accepted = 0;
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    m = sps__resolve_model(&bd);
    p = sps__choose_passes(w, &m);
    ENSURE(p.pressure && !sps__missing_pass(&m, &p, msg, sizeof msg));
    m.diffusion = 1;
    p = sps__choose_passes(w, &m);
    ENSURE(p.pressure == NULL);
    ENSURE(sps__missing_pass(&m, &p, msg, sizeof msg) && strstr(msg, "no pressure pass instance for material.kind = elastic with ENO-A"));
    ENSURE(strstr(msg, "stress diffusion 1") != NULL);
    /* a total-Lagrangian model of a kind without a law of F (sps__tl_law_of maps no kind silently) */
    bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN; bd.material.kind = SPS_MATERIAL_NEO_HOOKEAN;
    m = sps__resolve_model(&bd);
    m.material = sps__material_of(SPS_MATERIAL_ELASTIC);
    p = sps__choose_passes(w, &m);
    ENSURE(p.pressure == NULL && p.stress == NULL);
    ENSURE(sps__missing_pass(&m, &p, msg, sizeof msg) && strstr(msg, "no total-Lagrangian force pass instance for material.kind = elastic"));
    sps_world_destroy(w);
    for (mode = 0; mode < 8; ++mode) { /* dim x kernel x frozen_geometry: the six modes (frozen ones twice) */
        wd.dim = 2 + (mode & 1); wd.kernel = (sps_kernel_type)((mode >> 1) & 1); wd.frozen_geometry = mode >> 2;
        ENSURE(sps_world_create(&wd, &w) == SPS_OK);
        for (kind = 0; kind <= SPS_MATERIAL_DRUCKER_PRAGER; ++kind)
            for (shear = 0; shear < 6; ++shear)
                for (variant = 0; variant < 64; ++variant) { /* rotation, solver, viscosity, track_stress, stress diffusion */
                    sps_body b;
                    sps_result r;
                    bd = sps_default_body_def();
                    bd.material.kind = (sps_material_kind)kind; bd.shear = (sps_shear)shears[shear];
                    bd.material.yield_stress = 1e4; bd.material.sound_speed = 20; bd.material.friction_angle = 30;
                    bd.rotation = (sps_rotation)(variant & 3);
                    bd.solver = (sps_solver)((variant >> 2) & 1);
                    bd.material.viscosity = (variant >> 3) & 1 ? 0.1 : 0;
                    bd.track_stress = (variant >> 4) & 1;
                    bd.stress_diffusion = (variant >> 5) & 1 ? 0.1 : 0;
                    r = sps_world_add_body(w, &bd, &b);
                    if (r != SPS_OK && strstr(sps_world_last_error(w), "pass instance")) printf("    %s\n", sps_world_last_error(w));
                    ENSURE(r == SPS_OK || !strstr(sps_world_last_error(w), "pass instance"));
                    accepted += r == SPS_OK;
                }
        sps_world_destroy(w);
    }
    printf("    %d body defs accepted, each with all its pass kernels\n", accepted);
    ENSURE(accepted > 1000); /* the loop reached the combinations (about a third of 2688 per mode are refused by the rules) */
    return 0;
}

/* ---- fluid at rest over long times (chapter >>material: weakly compressible fluid) ---- */

static sps_real hydrostatic_048(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(1000 * 9.81 * (0.48 - (double)x[1]));
}

/* The mean pressure c0^2 (mean rho - rho0) and the mid-depth pressure of the tank's water. */
static void tank_pressures(const sps_world* w, double c2, double depth, double dp, double* p_mean, double* p_mid, double* p_mid_ref) {
    const sps_real *y = sps_world_field(w, SPS_FIELD_POSITION_Y), *p = sps_world_field(w, SPS_FIELD_PRESSURE);
    const sps_real* rho = sps_world_field(w, SPS_FIELD_DENSITY);
    const int n = sps_world_particle_count(w);
    double rho_sum = 0, y_mid = 0;
    int i, mid = 0;
    *p_mid = 0;
    for (i = 0; i < n; ++i) {
        rho_sum += rho[i];
        if (fabs(y[i] - depth / 2) < dp) { *p_mid += p[i]; y_mid += y[i]; ++mid; }
    }
    *p_mean = c2 * (rho_sum / n - 1000);
    *p_mid /= mid > 0 ? mid : 1;
    y_mid /= mid > 0 ? mid : 1;
    *p_mid_ref = 1000 * 9.81 * (depth - y_mid);
}

/* Water 0.48 m deep (12 particles) in a tank 1 m wide, started hydrostatic, stays at rest for
   seconds: its mean pressure does not grow and the mid-depth pressure stays that of the column.
   Where the free surface cuts the kernel, the density diffusion of the Riemann solver acting
   on the hydrostatic pressure difference made the density grow (measured: mean pressure +36
   Pa/s, the level up 9 mm/s, the mid-depth pressure +10 % of rho g h at 6 s). */
static int test_fluid_rest_long(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body water;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 0.48, 0}, tank_hi[3] = {1, 2, 0};
    const double g = 9.81, depth = 0.48, dp = 0.04, c0 = 10 * sqrt(2 * g * 0.5), p_scale = 1000 * g * depth / 2;
    double p_mean[2], p_mid[2], p_mid_ref[2];
    int k;
    wd.dim = 2;
    wd.dp = dp;
    wd.threads = 1;
    wd.gravity[1] = -g;
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.sound_speed = c0;
    ENSURE(sps_world_add_box_walls(w, lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) == SPS_OK);
    ENSURE(sps_world_add_body(w, &bd, &water) == SPS_OK);
    ENSURE(sps_body_add_box(w, water, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_set_pressure(w, water, hydrostatic_048, NULL) == SPS_OK);
    for (k = 0; k < 2; ++k) { /* at 2 s (the start's ringing has died down) and at 6 s */
        ENSURE(sps_world_advance(w, 2 + 4 * k, NULL, NULL) == SPS_OK);
        tank_pressures(w, c0 * c0, depth, dp, &p_mean[k], &p_mid[k], &p_mid_ref[k]);
        printf("    t = %d s: mean pressure %.1f Pa (column %.1f), mid-depth %.1f Pa (rho g h %.1f)\n", 2 + 4 * k, p_mean[k], p_scale,
               p_mid[k], p_mid_ref[k]);
    }
    /* 1 % of the mean hydrostatic pressure over 4 s: the mean density only moves with the
       surface's ripple at rest (measured +0.1 Pa; diffusing the full pressure difference: +148 Pa) */
    ENSURE(fabs(p_mean[1] - p_mean[0]) < 0.01 * p_scale);
    /* 4 %: the column's pressure at mid-depth, as test_fluid_hydrostatic_rest (measured +2 %) */
    ENSURE_NEAR(p_mid[1], p_mid_ref[1], 0.04 * p_mid_ref[1]);
    sps_world_destroy(w);
    return 0;
}

/* ---- the zigzag indicator (DIAGNOSTICS; chapter >>diagnostics) ---- */

#define ZIGZAG_DP 0.01
/* Velocity fields on the reference positions: an affine one (translation, rotation, shear and
   stretch at once), a smooth non-affine one (a shear flow with a sine profile over the block's
   0.2 m), and the affine one plus the particle-scale zigzag mode: +-u0 alternating from column
   to column and row to row, u0 twice the affine field's largest shear rate times dp (0.6 dp/s). */
static void affine_flow(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = SPS_R(0.1) + SPS_R(0.3) * x[1] + SPS_R(0.2) * x[0];
    v[1] = SPS_R(-0.2) + SPS_R(0.05) * x[0] - SPS_R(0.1) * x[1];
}
static void smooth_flow(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = (sps_real)(0.1 * sin(3.14159265358979323846 * x[1] / 0.2));
    v[1] = 0;
}
static void zigzag_flow(const sps_real x[3], sps_real v[3], void* user) {
    const int column = (int)floor(x[0] / ZIGZAG_DP), row = (int)floor(x[1] / ZIGZAG_DP);
    const sps_real u0 = 2 * SPS_R(0.3) * SPS_R(ZIGZAG_DP);
    affine_flow(x, v, user);
    v[0] += (column + row) % 2 ? u0 : -u0;
}

/* The zigzag indicator of a 0.2 m x 0.2 m block (dp 0.01) given each field above: ~0 for the
   affine field (the B-corrected gradient is exact for it), low for the smooth shear flow, and
   high for the zigzag mode on top of the same affine flow. It can fail: a measure that read the
   deformation rate (as the hourglass indicator reads the deformation) would not tell the affine
   field from the zigzag one. */
static int test_zigzag_tells_zigzag_from_flow(void) {
    static const sps_velocity_fn fields[3] = {affine_flow, smooth_flow, zigzag_flow};
    static const char* names[3] = {"affine", "smooth shear", "affine + zigzag"};
    const double lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.2, 0};
    double zigzag[3];
    int k;
    for (k = 0; k < 3; ++k) {
        sps_world* w = new_world(2, ZIGZAG_DP);
        sps_diagnostics d;
        sps_body b;
        ENSURE(w);
        b = add_block(w, SPS_SHEAR_OG, lo, hi, NULL);
        ENSURE(b.id);
        ENSURE(sps_body_set_velocity(w, b, fields[k], NULL) == SPS_OK);
        ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
        zigzag[k] = (double)d.zigzag;
        printf("    %-16s zigzag %.3g\n", names[k], zigzag[k]);
        sps_world_destroy(w);
    }
    ENSURE(zigzag[0] < 1e-6);  /* affine: round-off and the regularised inverse of B at the corners */
    ENSURE(zigzag[1] < 0.05);  /* smooth: the B-corrected gradient's error, O(h^2) of the curvature */
    ENSURE(zigzag[2] > 1);     /* the zigzag mode outweighs the flow: the documented threshold */
    return 0;
}

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

    RUN(test_kernel_partition_of_unity);
    RUN(test_kernel_integral);
    RUN(test_kernel_derivative);
    RUN(test_gradient_antisymmetry);
    RUN(test_moment_matrix_lattice);
    RUN(test_velocity_gradient_affine);
    RUN(test_rodrigues_matrix);
    RUN(test_riemann_pressure);
    RUN(test_rigid_rotation_zero_increment);
    RUN(test_spinning_disc_stays_rigid);
    RUN(test_translation_keeps_steps);
    RUN(test_momentum_conservation);
    RUN(test_tl_reference_state);
    RUN(test_tl_homogeneous_stretch);
    RUN(test_tl_hourglass_affine);
    RUN(test_tl_momentum);
    RUN(test_tl_j2_return);
    RUN(test_tl_damage_rate);
    RUN(test_tl_damage_tension_only);
    RUN(test_uniform_translation);
    RUN(test_damping_decays_velocity_exactly);
    RUN(test_external_acceleration);
    RUN(test_add_after_step_and_constraints);
    RUN(test_determinism_threads);
    RUN(test_bodies_independent);
    RUN(test_contact_momentum);
    RUN(test_fluid_hydrostatic_rest);
    RUN(test_drucker_prager_return_on_cone);
    RUN(test_granular_limiter_off_in_expansion);
    RUN(test_granular_block_at_rest);
    RUN(test_coincident_particles_stay_finite);
    RUN(test_granular_bad_input);
    RUN(test_transport_keeps_linear_momentum);
    RUN(test_fluid_bad_input);
    RUN(test_contact_determinism);
    RUN(test_j2_radial_return_on_surface);
    RUN(test_j2_hardening_raises_surface);
    RUN(test_j2_uniaxial_strain_closed_form);
    RUN(test_j2_bad_input);
    RUN_LONG(test_j2_taylor_bar_coarse); /* 2-4 s; 22 s under the sanitizers, which run --quick */
    RUN(test_wall_stops_body);
    RUN(test_contact_bad_input);
    RUN(test_rigid_wall_body);
    RUN(test_pair_forces_survive_adds);
    RUN(test_frame_arguments_rejected);
    RUN(test_frame_single_stepping_equals_steps);
    RUN(test_frame_whole_advection_steps_equal_steps);
    RUN(test_frame_cuts_advection_steps);
    RUN(test_frame_wall_budget);
    RUN(test_validation_world_def);
    RUN(test_validation_zero_def);
    RUN(test_validation_body_def);
    RUN(test_validation_handles_and_args);
    RUN(test_handle_foreign_world_same_tag);
    RUN(test_step_empty_world);
    RUN(test_result_strings_and_version);
    RUN(test_unstable_run_reported);
    RUN(test_unstable_huge_velocity);
    RUN(test_memory_runaway_particle);
    RUN(test_null_world_arguments);
    RUN(test_bad_arguments_named);
    RUN(test_field_by_name);
    RUN(test_set_particle);
    RUN(test_warnings_for_silent_cases);
    RUN(test_energy_watchdog);
    RUN(test_energy_account_driven);
    RUN(test_foreign_and_destroyed_handles);
    RUN(test_flat_box_is_empty);
    RUN(test_step_empty_body);
    RUN(test_add_after_step_stress_output);
    RUN(test_guard_escape);
    RUN(test_guard_time_step_collapse);
    RUN(test_guard_nonfinite_state);
    RUN(test_last_good_state);
    RUN(test_world_validate);
    RUN(test_memory_no_allocation_in_steps);
    RUN(test_memory_out_of_memory_everywhere);
    RUN(test_determinism_repeated_runs);
    RUN(test_vtk_writer);
    RUN(test_restart_round_trip);
    RUN(test_restart_last_good_state);
    RUN(test_restart_refused);
    RUN(test_csv_row);
    RUN_LONG(test_plate2d_period_eno_a);
    RUN_LONG(test_plate2d_period_eno);
    RUN_LONG(test_plate2d_period_eno_a_pair);
    RUN_LONG(test_hourglass_og_breaks_others_do_not);
    RUN_LONG(test_damped_cantilever_sag);
    RUN_NAMED(test_plate3d_period_mode22); /* 1 min on 2 cores: ./build/test_sphsolid plate3d_period */
    RUN(test_tl_hourglass_is_energy_gradient);
    RUN(test_tl_hourglass_stiffness_symmetric);
    RUN(test_tl_artificial_viscosity);
    /* friction and material damping */
    RUN(test_friction_block_on_slope);
    RUN(test_friction_momentum_exact);
    RUN(test_friction_unused_is_free);
    RUN(test_kelvin_voigt_rigid_motion_free);
    RUN(test_friction_damping_bad_input);
    RUN(test_coupling_momentum);
    RUN(test_coupling_hydrostatic_rest);
    RUN(test_coupling_floating_block);
    RUN(test_coupling_light_soft_block);
    RUN(test_coupling_bad_input);
    /* the scenes users write */
    RUN(test_user_scene_tumbling_default);
    RUN(test_watchdog_names_rotation);
    RUN(test_setup_body_behind_wall);
    RUN(test_setup_mistakes_named);
    RUN(test_rigid_motion_about_current_centre);
    RUN(test_frame_in_seconds);
    RUN(test_user_scene_dragged_jelly);
    RUN(test_kelvin_voigt_decay_account);
    RUN(test_contact_damping_pair);
    RUN(test_contact_damping_wall);
    RUN(test_contact_damping_thread_count);
    RUN(test_contact_damping_bad_input);
    RUN(test_granular_block_holds_shape);
    RUN(test_granular_lattice_moment);
    RUN(test_granular_free_grain_stops);
    RUN(test_restart_every_def_field);
    RUN(test_restart_ul_j2_into_tl_j2);
    RUN(test_unread_parameter_warned);
    RUN(test_missing_pass_instance);
    RUN(test_fluid_rest_long);
    RUN(test_zigzag_tells_zigzag_from_flow);

    if (g_skipped) printf("(%d long tests skipped)\n", g_skipped);
    printf("%d passed, %d failed\n", g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}
