/* clamp_reference - the first period of the 2D oscillating plate as a plane-strain continuum,
   with three root conditions, from a linear finite-element eigenvalue problem.

   What it computes
     The period T = 2 pi / omega of the lowest bending mode of the clamped cantilever of
     benchmark A1 (the 2D oscillating plate), treated as what the SPH plate is: a 2D linear
     elastic continuum in plane strain, not a beam. Three root conditions on the face x = 0:
       (a) held:  u_x = u_y = 0 on the whole face. This is what a block of fixed SPH particles
           does: the root cannot contract sideways (Poisson effect) where the bending moment
           is largest, which stiffens it. The figure the SPH periods are compared with.
       (b) beam clamp:  u_x = 0 on the face, and the mean of u_y over the face is zero. The face
           stays plane and upright but may contract sideways, and the shear force is taken up
           over the whole face: the clamp of a beam theory (bench/beam_reference.c). It checks
           this program against the Timoshenko beam.
       (c) point:  u_x = 0 on the face, u_y = 0 at mid-height only (the earlier throwaway
           check's version of the beam clamp). The whole shear force then enters through one
           point: in 2D a point force has infinite strain energy (the displacement under it
           grows like log(1/r)), so the period never converges: it grows by a constant amount
           each time the mesh is halved (+0.0000342 s here). Printed as a warning, not a
           reference: the earlier check's 0.2569 s for "the root free to contract" was (c).
     For each, a mesh sequence and a Richardson extrapolation.

   The case (SI units, plane strain, unit depth)
     free length L = 0.2 (root at x = 0), thickness H = 0.02 (y from -H/2 to H/2), rho0 = 1000,
     E = 2e6, nu = 0.3975. Thin-plate theory: omega^2 = E' H^2 k^4 / (12 rho0), E' = E/(1-nu^2),
     kL = 1.8751 (0.2540 s); --thickness changes H (L stays 0.2).

   The model
     - Linear elasticity, small displacements: the linear eigenperiod only. The amplitude effect
       (large rotations) is not here; bench/beam_reference.c gives it (-0.47% at v_f = 0.05).
       A normal mode needs no initial condition: the SPH setup's initial velocity (v_x = 0,
       sections not turning) excites mostly this mode (see bench/results/beam_reference.txt).
     - Elements: 9-node Lagrange quadrilaterals (biquadratic), full 3x3 Gauss integration.
       Why not bilinear quads: they lock in bending (a bilinear element cannot bend without
       spurious shear strain), so the period converges slowly, from below. A biquadratic
       element contains the pure-bending field exactly (u_x ~ xy, u_y ~ x^2, y^2), does not
       lock, and its eigenvalue error falls as h^4 where the solution is smooth.
     - Consistent mass (the same shape functions as the displacements). With it the discrete
       problem is a Rayleigh-Ritz approximation: omega^2 is an upper bound that falls
       monotonically as the mesh is refined, so T rises monotonically towards the limit.
     - Mesh: ny elements across H, nx = ny L/H along L (square elements in the default case);
       ny = 2, 4, 8, 16, 32 (--max-ny). All elements are the same rectangle, so one element
       stiffness and one element mass matrix serve the whole mesh.
     - Eigenvalue: inverse iteration, x <- K^-1 M x, with the Rayleigh quotient as estimate. It
       converges to the lowest mode (the first bending mode of a cantilever; the next one is
       about 6 times higher in omega, so each iteration cuts the error by about 40^2).
       K is factorised once by a banded Cholesky factorisation; the nodes are numbered across
       the thickness first, so the half-bandwidth b is about 2 (2 (2 ny + 1) + 2) equations
       (an element spans three node columns of 2 ny + 1 nodes): memory 8 n b bytes, work
       n b^2 / 2 for n equations (ny = 32: 83,200 equations, b = 265, 180 MB, 2 s).
     - Condition (b) needs no second factorisation: see mass_operator below.
     - Why not explicit time stepping (as the earlier throwaway check did): the eigenvalue
       problem gives the linear period directly, to round-off for a given mesh, with no time
       step or zero-crossing error, in seconds.

   Convergence and what limits it
     (a) The root corners (held face meeting a free face) are stress singularities, stresses
         ~ r^(lambda - 1) with lambda < 1, so a uniform mesh converges more slowly than h^4:
         the observed order falls with refinement (ratio of successive changes 2.9, 2.7, 2.5
         for ny 8, 16, 32, order 1.3 at the end) towards the singularity's 2 lambda. The
         extrapolation uses the last observed order; if the order kept falling, the limit
         would be slightly higher (ratio 2.2 would add 0.000005 s).
     (b) Smooth but for a jump of the shear traction at the root corners: order about 2.5-3,
         converged to 1e-7 s at ny = 16.
     (c) Diverges logarithmically (see above): order 0.
     Richardson: from the last three meshes, p = log2(d1/d2) with d1, d2 the last two
     changes, and T_inf = T_last + d2 / (2^p - 1).

   Verification (printed)
     - (b) against the exact linear Timoshenko cantilever (shooting as in beam_reference.c,
       kappa = 5/6): within a few tenths of a percent (a beam keeps sections plane and uses a
       shear coefficient; the continuum does neither).
     - --thickness 0.002 --max-ny 4: a slender plate (L/H = 100), where (b) must approach
       thin-plate theory for that H to within the Timoshenko correction (+0.010%): it gives
       2.540551 s at ny = 2 and 4 (thin plate 2.540324 s, +0.009%; Timoshenko 2.540569 s,
       -0.001%). Finer meshes (nx = 800, 1600 square elements) are limited by round-off: K
       of so long a strip is ill-conditioned, and the period moves by 1e-5 .. 3e-5 relative,
       not monotonically. The default case (nx <= 320) is far from that.

   Usage
     ./build/clamp_reference [--thickness H] [--max-ny N]
       the table for ny = 2, 4, 8, ... up to N (default H 0.02, N 32); nx = ny L / H, so a
       thin plate needs a smaller N (--thickness 0.002 --max-ny 16: 211,000 equations, 0.2 GB).
       --max-ny 64: 1.4 GB and about a minute.
     ./build/clamp_reference --sag G
       instead of the period, the static sag under the plate's weight in gravity G (downwards)
       for root conditions (a) and (b), against Timoshenko's (examples/cantilever_sag.c; the
       output of --sag 1 is in bench/results/cantilever_sag.txt).
     Build: make build/clamp_reference (gcc -std=c99 -O2, libc and libm only, one thread).

   Expected output (default run, about 5 s on one core; all of it in
   bench/results/beam_reference.txt)
       ny   (a) held    (b) beam clamp   (c) point u_y
        2   0.2542886   0.2563183        0.2567441
        4   0.2548954   0.2563348        0.2567940
        8   0.2551035   0.2563363        0.2568294
       16   0.2551802   0.2563365        0.2568636
       32   0.2552106   0.2563365        0.2568978
     extrapolated: (a) 0.255231 s (order 1.33), (b) 0.256337 s; (a) vs (b) -0.43%;
     (b) vs the exact Timoshenko beam (0.256467 s) -0.05%; (a) vs thin plate +0.47%.
*/
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cantilever.h"


enum { NODES = 9, ELEMENT_DOFS = 18, GAUSS = 3 };

typedef enum { ROOT_HELD, ROOT_MID_HEIGHT } root_condition;

/* ---- the case: plate_case, its moduli and thin_plate_period are in cantilever.h ---- */

/* ---- the 9-node element: one stiffness and one mass matrix for every element ----
   Local node (a, b), a along x and b along y, each 0, 1, 2 (left/middle/right); local number
   3 a + b, matching the global numbering (across the thickness first). Degrees of freedom:
   2 node (u_x) and 2 node + 1 (u_y). */

typedef struct {
    double stiffness[ELEMENT_DOFS][ELEMENT_DOFS];
    double mass[ELEMENT_DOFS][ELEMENT_DOFS];
} element_matrices;

/* 1D quadratic shape functions on [-1, 1] (nodes at -1, 0, 1) and their derivatives */
static void quadratic_shape(double s, double n[3], double dn[3]) {
    n[0] = 0.5 * s * (s - 1);
    n[1] = 1 - s * s;
    n[2] = 0.5 * s * (s + 1);
    dn[0] = s - 0.5;
    dn[1] = -2 * s;
    dn[2] = s + 0.5;
}

/* plane-strain elasticity matrix: stress (xx, yy, xy) = D strain (xx, yy, engineering xy) */
static void plane_strain_matrix(const plate_case* c, double d[3][3]) {
    double nu = c->poisson, scale = c->youngs / ((1 + nu) * (1 - 2 * nu));
    memset(d, 0, 9 * sizeof(double));
    d[0][0] = d[1][1] = scale * (1 - nu);
    d[0][1] = d[1][0] = scale * nu;
    d[2][2] = scale * (1 - 2 * nu) / 2;
}

/* Full 3x3 Gauss integration over a hx by hy rectangle (exact for the mass, and for the
   stiffness of a rectangle) */
static element_matrices element_create(const plate_case* c, double hx, double hy) {
    static const double point[GAUSS] = {-0.774596669241483377, 0, 0.774596669241483377};
    static const double weight[GAUSS] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    element_matrices e;
    double d[3][3], jacobian = hx * hy / 4;
    int gx, gy, a, b, p, q, r, s;
    plane_strain_matrix(c, d);
    memset(&e, 0, sizeof e);
    for (gx = 0; gx < GAUSS; gx++)
        for (gy = 0; gy < GAUSS; gy++) {
            double nx[3], dnx[3], ny[3], dny[3], n[NODES], strain[3][ELEMENT_DOFS] = {{0}};
            double w = weight[gx] * weight[gy] * jacobian;
            quadratic_shape(point[gx], nx, dnx);
            quadratic_shape(point[gy], ny, dny);
            for (a = 0; a < 3; a++)
                for (b = 0; b < 3; b++) {
                    int node = 3 * a + b;
                    double dx = dnx[a] * ny[b] * 2 / hx, dy = nx[a] * dny[b] * 2 / hy;
                    n[node] = nx[a] * ny[b];
                    strain[0][2 * node] = dx;     /* eps_xx = du_x/dx */
                    strain[1][2 * node + 1] = dy; /* eps_yy = du_y/dy */
                    strain[2][2 * node] = dy;     /* gamma_xy = du_x/dy + du_y/dx */
                    strain[2][2 * node + 1] = dx;
                }
            for (p = 0; p < ELEMENT_DOFS; p++)
                for (q = 0; q < ELEMENT_DOFS; q++) {
                    double sum = 0;
                    for (r = 0; r < 3; r++)
                        for (s = 0; s < 3; s++) sum += strain[r][p] * d[r][s] * strain[s][q];
                    e.stiffness[p][q] += w * sum;
                    if (p % 2 == q % 2) /* consistent mass: u_x with u_x, u_y with u_y */
                        e.mass[p][q] += w * c->density * n[p / 2] * n[q / 2];
                }
        }
    return e;
}

/* ---- the mesh and the equation numbering ---- */

typedef struct {
    int ny, nx;               /* elements across H and along L */
    int rows;                 /* nodes across H: 2 ny + 1 */
    int equations, bandwidth; /* free unknowns; half-bandwidth of K */
    int* equation;            /* per degree of freedom: its equation, or -1 if held */
} mesh;

static int node_index(const mesh* m, int column, int row) {
    return column * m->rows + row;
}

/* global degrees of freedom of element (ex, ey), in local order */
static void element_dofs(const mesh* m, int ex, int ey, int dofs[ELEMENT_DOFS]) {
    int a, b;
    for (a = 0; a < 3; a++)
        for (b = 0; b < 3; b++) {
            int node = node_index(m, 2 * ex + a, 2 * ey + b), local = 3 * a + b;
            dofs[2 * local] = 2 * node;
            dofs[2 * local + 1] = 2 * node + 1;
        }
}

static int is_held(const mesh* m, root_condition root, int node, int component) {
    int column = node / m->rows, row = node % m->rows;
    if (column != 0) return 0;
    if (root == ROOT_HELD || component == 0) return 1;
    return row == m->ny; /* u_y held at mid-height only */
}

static mesh mesh_create(const plate_case* c, int ny, root_condition root) {
    mesh m;
    int dof, dofs_total, ex, ey, i;
    m.ny = ny;
    m.nx = (int)floor(ny * c->length / c->thickness + 0.5);
    if (m.nx < 1) m.nx = 1;
    m.rows = 2 * ny + 1;
    dofs_total = 2 * (2 * m.nx + 1) * m.rows;
    m.equation = malloc(dofs_total * sizeof(int));
    if (!m.equation) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    m.equations = 0;
    for (dof = 0; dof < dofs_total; dof++)
        m.equation[dof] = is_held(&m, root, dof / 2, dof % 2) ? -1 : m.equations++;
    m.bandwidth = 0;
    for (ex = 0; ex < m.nx; ex++)
        for (ey = 0; ey < m.ny; ey++) {
            int dofs[ELEMENT_DOFS], low = m.equations, high = -1;
            element_dofs(&m, ex, ey, dofs);
            for (i = 0; i < ELEMENT_DOFS; i++) {
                int e = m.equation[dofs[i]];
                if (e < 0) continue;
                if (e < low) low = e;
                if (e > high) high = e;
            }
            if (high - low > m.bandwidth) m.bandwidth = high - low;
        }
    return m;
}

/* ---- banded symmetric matrix: the lower band, row by row ----
   Row i holds columns i - bandwidth .. i; entry (i, j) at data[i (b + 1) + j - i + b]. */

typedef struct {
    int n, bandwidth;
    double* data;
} band_matrix;

static double* band_entry(band_matrix* k, int i, int j) {
    return k->data + (size_t)i * (k->bandwidth + 1) + (j - i + k->bandwidth);
}

static band_matrix assemble_stiffness(const mesh* m, const element_matrices* e) {
    band_matrix k;
    int ex, ey, p, q;
    k.n = m->equations;
    k.bandwidth = m->bandwidth;
    k.data = calloc((size_t)k.n * (k.bandwidth + 1), sizeof(double));
    if (!k.data) {
        fprintf(stderr, "out of memory for a %d x %d band\n", k.n, k.bandwidth + 1);
        exit(1);
    }
    for (ex = 0; ex < m->nx; ex++)
        for (ey = 0; ey < m->ny; ey++) {
            int dofs[ELEMENT_DOFS];
            element_dofs(m, ex, ey, dofs);
            for (p = 0; p < ELEMENT_DOFS; p++) {
                int i = m->equation[dofs[p]];
                if (i < 0) continue;
                for (q = 0; q < ELEMENT_DOFS; q++) {
                    int j = m->equation[dofs[q]];
                    if (j >= 0 && j <= i) *band_entry(&k, i, j) += e->stiffness[p][q];
                }
            }
        }
    return k;
}

/* four partial sums: lets the compiler keep several multiply-adds in flight */
static double dot(const double* a, const double* b, int n) {
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    int i = 0;
    for (; i + 3 < n; i += 4) {
        s0 += a[i] * b[i];
        s1 += a[i + 1] * b[i + 1];
        s2 += a[i + 2] * b[i + 2];
        s3 += a[i + 3] * b[i + 3];
    }
    for (; i < n; i++) s0 += a[i] * b[i];
    return (s0 + s1) + (s2 + s3);
}

/* K = L L^T in place (row by row). Fails only if K is not positive definite (a mechanism). */
static void cholesky(band_matrix* k) {
    int i, j;
    for (i = 0; i < k->n; i++) {
        int first = i - k->bandwidth > 0 ? i - k->bandwidth : 0;
        for (j = first; j <= i; j++) {
            double s = *band_entry(k, i, j)
                       - dot(band_entry(k, i, first), band_entry(k, j, first), j - first);
            if (j < i) {
                *band_entry(k, i, j) = s / *band_entry(k, j, j);
            } else if (s > 0) {
                *band_entry(k, i, i) = sqrt(s);
            } else {
                fprintf(stderr, "stiffness not positive definite at equation %d\n", i);
                exit(1);
            }
        }
    }
}

/* solve L L^T x = b, x overwriting b */
static void cholesky_solve(band_matrix* k, double* x) {
    int i, j;
    for (i = 0; i < k->n; i++) {
        int first = i - k->bandwidth > 0 ? i - k->bandwidth : 0;
        x[i] = (x[i] - dot(band_entry(k, i, first), x + first, i - first)) / *band_entry(k, i, i);
    }
    for (i = k->n - 1; i >= 0; i--) {
        int first = i - k->bandwidth > 0 ? i - k->bandwidth : 0;
        x[i] /= *band_entry(k, i, i);
        for (j = first; j < i; j++) x[j] -= *band_entry(k, i, j) * x[i];
    }
}

/* The mass operator. Root conditions (a) and (c) use M itself. For (b), the mean of u_y over
   the root face is held instead of its mid-height value: a field u with that mean zero is
   u = v + t e_y, v the same field with u_y(mid-height) = 0 and t e_y a rigid translation in y
   with t = -(w . v) / H (w: the face's integration weights, so w . v = int v_y dy). A rigid
   translation strains nothing, so the stiffness of u is that of v (the K of condition c, no
   new factorisation), and only the mass changes: M_b = P^T M P with P v = v + t(v) e_y.
   This holds the mean exactly, and the root reaction becomes a traction spread over the face
   instead of a point force. */
typedef struct {
    const mesh* m;
    const element_matrices* e;
    const double* face_weight; /* per equation: int N dy over the root face for u_y, else 0 */
    double face_length;        /* H, the sum of all face weights (held node's included) */
} mass_operator;

/* out = A (x + shift e_y) in equation space, element by element (A = M or K, never
   assembled); returns the total y component of A (x + shift e_y), held ones included */
static double element_times(const mesh* m, const double (*matrix)[ELEMENT_DOFS],
                            const double* x, double shift, double* out) {
    int ex, ey, p, q;
    double total_y = 0;
    memset(out, 0, m->equations * sizeof(double));
    for (ex = 0; ex < m->nx; ex++)
        for (ey = 0; ey < m->ny; ey++) {
            int dofs[ELEMENT_DOFS], eq[ELEMENT_DOFS];
            double local[ELEMENT_DOFS];
            element_dofs(m, ex, ey, dofs);
            for (p = 0; p < ELEMENT_DOFS; p++) {
                eq[p] = m->equation[dofs[p]];
                local[p] = (eq[p] >= 0 ? x[eq[p]] : 0) + (p % 2 ? shift : 0);
            }
            for (p = 0; p < ELEMENT_DOFS; p++) {
                double f = 0;
                for (q = 0; q < ELEMENT_DOFS; q++) f += matrix[p][q] * local[q];
                if (eq[p] >= 0) out[eq[p]] += f;
                if (p % 2) total_y += f;
            }
        }
    return total_y;
}

static void mass_times(const mass_operator* op, const double* x, double* out) {
    int i, n = op->m->equations;
    double shift, total_y;
    if (!op->face_weight) {
        element_times(op->m, op->e->mass, x, 0, out);
        return;
    }
    shift = -dot(op->face_weight, x, n) / op->face_length; /* u = P x */
    total_y = element_times(op->m, op->e->mass, x, shift, out); /* M u */
    for (i = 0; i < n; i++) out[i] -= op->face_weight[i] * total_y / op->face_length; /* P^T */
}

/* int N_j dy over the root face for every u_y equation there (Simpson: 1, 4, 1 times hy/6) */
static double* root_face_weights(const mesh* m, double hy) {
    double* w = calloc(m->equations, sizeof(double));
    int ey, b;
    static const double simpson[3] = {1.0 / 6, 4.0 / 6, 1.0 / 6};
    if (!w) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    for (ey = 0; ey < m->ny; ey++)
        for (b = 0; b < 3; b++) {
            int e = m->equation[2 * node_index(m, 0, 2 * ey + b) + 1];
            if (e >= 0) w[e] += simpson[b] * hy;
        }
    return w;
}

/* start: u_y = (x/L)^2, u_x = 0 (close to the first bending mode, no other mode favoured) */
static void starting_vector(const mesh* m, double* x) {
    int dof, dofs_total = 2 * (2 * m->nx + 1) * m->rows;
    for (dof = 0; dof < dofs_total; dof++) {
        int e = m->equation[dof], column = dof / 2 / m->rows;
        double s = (double)column / (2 * m->nx);
        if (e >= 0) x[e] = dof % 2 ? s * s : 0;
    }
}

/* Inverse iteration for the lowest omega^2 of K phi = omega^2 M phi (K already factorised).
   With z = K^-1 M x, the Rayleigh quotient of z is (z.Mx)/(z.Mz), no product with K needed.
   (An explicit z.Kz is worse, not better: round-off in the solve leaves a little of the
   highest modes in z, and z.Kz weighs them by their huge stiffness.) */
static double lowest_eigenvalue(const mass_operator* op, band_matrix* k, int* iterations) {
    enum { MAX_ITERATIONS = 100 };
    const double TOLERANCE = 1e-14;
    int n = op->m->equations, it, i;
    double *x = calloc(n, sizeof(double)), *mx = calloc(n, sizeof(double));
    double *z = calloc(n, sizeof(double)), *mz = calloc(n, sizeof(double));
    double previous = 0, omega2 = 0;
    if (!x || !mx || !z || !mz) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    starting_vector(op->m, x);
    for (it = 1; it <= MAX_ITERATIONS; it++) {
        double zmz, scale;
        mass_times(op, x, mx);
        memcpy(z, mx, n * sizeof(double));
        cholesky_solve(k, z);
        mass_times(op, z, mz);
        zmz = dot(z, mz, n);
        omega2 = dot(z, mx, n) / zmz;
        scale = 1 / sqrt(zmz); /* x = z normalised in the mass norm */
        for (i = 0; i < n; i++) x[i] = z[i] * scale;
        if (it > 1 && fabs(omega2 - previous) < TOLERANCE * omega2) break;
        previous = omega2;
    }
    *iterations = it;
    free(x);
    free(mx);
    free(z);
    free(mz);
    return omega2;
}

typedef struct {
    double period, period_mean; /* period_mean: condition (b), with ROOT_MID_HEIGHT only */
    double seconds;
    int equations, bandwidth, iterations;
} mesh_result;

/* ROOT_HELD: condition (a). ROOT_MID_HEIGHT: condition (c), and (b) from the same K. */
static mesh_result first_period(const plate_case* c, int ny, root_condition root) {
    clock_t start = clock();
    mesh m = mesh_create(c, ny, root);
    double hy = c->thickness / ny;
    element_matrices e = element_create(c, c->length / m.nx, hy);
    band_matrix k = assemble_stiffness(&m, &e);
    mass_operator op = {0, 0, 0, 0};
    mesh_result r = {0, 0, 0, 0, 0, 0};
    op.m = &m;
    op.e = &e;
    cholesky(&k);
    r.period = 2 * PI / sqrt(lowest_eigenvalue(&op, &k, &r.iterations));
    if (root == ROOT_MID_HEIGHT) {
        double* w = root_face_weights(&m, hy);
        op.face_weight = w;
        op.face_length = c->thickness;
        r.period_mean = 2 * PI / sqrt(lowest_eigenvalue(&op, &k, &r.iterations));
        free(w);
    }
    r.equations = m.equations;
    r.bandwidth = m.bandwidth;
    r.seconds = (double)(clock() - start) / CLOCKS_PER_SEC;
    free(k.data);
    free(m.equation);
    return r;
}

/* ---- the static sag under the plate's own weight (--sag; examples/cantilever_sag.c) ----
   K u = f, f the consistent load of a uniform acceleration g downwards (f = M (-g e_y), with
   element_times' shift). The sag is the mean downward u_y over the free end face x = L
   (Simpson weights): the deflection a beam theory computes. (a) held: K of the held face.
   (b) beam clamp, as in the mass operator: u = v + t e_y with v in the space of condition (c)
   and t = -(w . v) / H, so the potential energy 1/2 v.Kv - f.u is least where
   K v = f - w F / H (F the total y load, held nodes included: the face takes it as a uniform
   traction), and the sag adds t. */
static double end_face_mean_uy(const mesh* m, const double* u, double hy, double thickness) {
    static const double simpson[3] = {1.0 / 6, 4.0 / 6, 1.0 / 6};
    double sum = 0;
    int ey, b;
    for (ey = 0; ey < m->ny; ey++)
        for (b = 0; b < 3; b++) {
            int e = m->equation[2 * node_index(m, 2 * m->nx, 2 * ey + b) + 1];
            if (e >= 0) sum += simpson[b] * hy * u[e];
        }
    return sum / thickness;
}

static double static_sag(const plate_case* c, int ny, root_condition root, double g) {
    mesh m = mesh_create(c, ny, root);
    double hy = c->thickness / ny, load, sag;
    const element_matrices e = element_create(c, c->length / m.nx, hy);
    band_matrix k = assemble_stiffness(&m, &e);
    double *zero = calloc(m.equations, sizeof(double)), *u = calloc(m.equations, sizeof(double));
    int i;
    if (!zero || !u) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    load = element_times(&m, e.mass, zero, -g, u); /* u = f, load its total y */
    cholesky(&k);
    if (root == ROOT_HELD) {
        cholesky_solve(&k, u);
        sag = -end_face_mean_uy(&m, u, hy, c->thickness);
    } else {
        double* w = root_face_weights(&m, hy);
        for (i = 0; i < m.equations; i++) u[i] -= w[i] * load / c->thickness;
        cholesky_solve(&k, u);
        sag = -(end_face_mean_uy(&m, u, hy, c->thickness) - dot(w, u, m.equations) / c->thickness);
        free(w);
    }
    free(zero);
    free(u);
    free(k.data);
    free(m.equation);
    return sag;
}

/* Timoshenko's tip deflection under the weight (plane strain, kappa 5/6; cf. plate2d_timoshenko_sag) */
static double timoshenko_sag(const plate_case* c, double g) {
    double q = c->density * g * c->thickness, L = c->length, H = c->thickness;
    return q * pow(L, 4) / (8 * plane_strain_modulus(c) * H * H * H / 12)
           + q * L * L / (2 * c->shear_coefficient * shear_modulus(c) * H);
}

/* ---- the exact linear Timoshenko cantilever (the check for root condition b): cantilever.h ---- */

/* ---- the table ---- */

enum { MAX_MESHES = 12 };

typedef struct {
    double order, limit; /* observed order, extrapolated period (0 if not available) */
} extrapolation;

/* from the last three periods of a sequence with h halving each time */
static extrapolation richardson(const double* period, int count) {
    extrapolation x = {0, 0};
    double d1, d2;
    if (count < 3) return x;
    d1 = period[count - 2] - period[count - 3];
    d2 = period[count - 1] - period[count - 2];
    if (d1 == 0 || d2 / d1 <= 0 || d2 / d1 >= 1) return x; /* not converging monotonically */
    x.order = log(d1 / d2) / log(2.0);
    x.limit = period[count - 1] + d2 / (pow(2.0, x.order) - 1);
    return x;
}

/* change from the previous mesh and the ratio of successive changes */
static void print_changes(const double* period, int i) {
    if (i >= 1) printf(" %+.7f", period[i] - period[i - 1]);
    else printf("           ");
    if (i >= 2) printf(" %5.2f", (period[i - 1] - period[i - 2]) / (period[i] - period[i - 1]));
    else printf("      ");
}

static void print_header(const plate_case* c, double thin, double timoshenko) {
    printf("# 2D oscillating plate as a plane-strain continuum: L %g, H %g, rho0 %g, E %g, "
           "nu %g\n", c->length, c->thickness, c->density, c->youngs, c->poisson);
    printf("# linear FE eigenproblem K phi = omega^2 M phi, lowest (bending) mode, T = 2 pi / "
           "omega; 9-node quads,\n# 3x3 Gauss, consistent mass, banded Cholesky + inverse "
           "iteration; ny elements across H, %g ny along L\n", c->length / c->thickness);
    printf("# thin-plate theory (kL = 1.8751040687): %.6f s; exact linear Timoshenko beam "
           "(kappa 5/6): %.6f s\n#\n", thin, timoshenko);
    printf("# First period T [s]; change: from the previous mesh; ratio: of successive changes "
           "(2^order). Root (x = 0):\n");
    printf("#  (a) held: u_x = u_y = 0 on the face;  (b) beam clamp: u_x = 0 on the face, mean "
           "u_y = 0;\n#  (c) u_x = 0 on the face, u_y = 0 at mid-height only (a point support)\n");
    printf("#       (a) held                    | (b) beam clamp, mean u_y    | (c) point u_y"
           "               |\n");
    printf("#  ny  T [s]     change     ratio  | T [s]     change     ratio  | T [s]     change     "
           "ratio  | equations bandwidth CPU [s]\n");
}

static void print_row(int ny, const double* held, const double* mean, const double* point,
                      int i, mesh_result r, double seconds) {
    printf("  %3d %.7f", ny, held[i]);
    print_changes(held, i);
    printf(" | %.7f", mean[i]);
    print_changes(mean, i);
    printf(" | %.7f", point[i]);
    print_changes(point, i);
    printf(" | %9d %6d %8.2f\n", r.equations, r.bandwidth, seconds);
    fflush(stdout);
}

static double print_extrapolation(const char* name, const double* period, int count) {
    extrapolation x = richardson(period, count);
    if (x.limit > 0) {
        printf("#   %-28s observed order %.2f, T = %.6f s\n", name, x.order, x.limit);
        return x.limit;
    }
    if (count < 3)
        printf("#   %-28s fewer than three meshes; finest mesh %.6f s\n", name,
               period[count - 1]);
    else if (fabs(period[count - 1] - period[count - 2]) < 1e-7 * period[count - 1])
        printf("#   %-28s converged (last change below 1e-7 relative), T = %.6f s\n", name,
               period[count - 1]);
    else
        printf("#   %-28s no monotone convergence; finest mesh %.6f s\n", name,
               period[count - 1]);
    return period[count - 1];
}

static void print_summary(const double* held, const double* mean, const double* point,
                          int count, double thin, double timoshenko) {
    double a, b;
    printf("# Richardson from the last three meshes (T_last + change / (ratio - 1)):\n");
    a = print_extrapolation("(a) held:", held, count);
    b = print_extrapolation("(b) beam clamp, mean u_y:", mean, count);
    print_extrapolation("(c) point u_y (see header):", point, count);
    printf("# (a) vs (b) %+.3f%%;  (b) vs Timoshenko beam %+.3f%%;  vs thin plate: (b) %+.3f%%, "
           "(a) %+.3f%%\n", 100 * (a / b - 1), 100 * (b / timoshenko - 1), 100 * (b / thin - 1),
           100 * (a / thin - 1));
}

static void print_table(const plate_case* c, int max_ny) {
    double held[MAX_MESHES], mean[MAX_MESHES], point[MAX_MESHES];
    double thin = thin_plate_period(c, KL_EXACT_ROOT), timoshenko = timoshenko_exact_period(c, 1, 1);
    clock_t start = clock();
    int ny, count = 0;
    print_header(c, thin, timoshenko);
    for (ny = 2; ny <= max_ny && count < MAX_MESHES; ny *= 2, count++) {
        mesh_result a = first_period(c, ny, ROOT_HELD), b = first_period(c, ny, ROOT_MID_HEIGHT);
        held[count] = a.period;
        mean[count] = b.period_mean;
        point[count] = b.period;
        print_row(ny, held, mean, point, count, a, a.seconds + b.seconds);
    }
    print_summary(held, mean, point, count, thin, timoshenko);
    printf("# CPU time %.1f s\n", (double)(clock() - start) / CLOCKS_PER_SEC);
}

/* the Richardson limit of a sag sequence (the finest mesh's if there is none), printed */
static double sag_limit(const char* name, const double* sag, int count) {
    extrapolation x = richardson(sag, count);
    if (x.limit > 0) printf("#   %-28s observed order %.2f, sag = %.7e m\n", name, x.order, x.limit);
    else printf("#   %-28s finest mesh (no monotone sequence of three), sag = %.7e m\n", name, sag[count - 1]);
    return x.limit > 0 ? x.limit : sag[count - 1];
}

static void print_sag_table(const plate_case* c, int max_ny, double g) {
    double held[MAX_MESHES], mean[MAX_MESHES], beam = timoshenko_sag(c, g), a, b;
    int ny, count = 0;
    printf("# Static sag under the plate's weight, g = %g m/s^2 downwards: mean u_y over the end face x = L [m]\n", g);
    printf("# Timoshenko beam (kappa 5/6, plane strain): %.7e m\n", beam);
    printf("#  ny  (a) held        (b) beam clamp\n");
    for (ny = 2; ny <= max_ny && count < MAX_MESHES; ny *= 2, count++) {
        held[count] = static_sag(c, ny, ROOT_HELD, g);
        mean[count] = static_sag(c, ny, ROOT_MID_HEIGHT, g);
        printf("  %3d %.7e   %.7e\n", ny, held[count], mean[count]);
        fflush(stdout);
    }
    a = sag_limit("(a) held:", held, count);
    b = sag_limit("(b) beam clamp, mean u_y:", mean, count);
    printf("# (a) vs Timoshenko %+.3f%%;  (b) vs Timoshenko %+.3f%%;  (a) vs (b) %+.3f%%\n", 100 * (a / beam - 1),
           100 * (b / beam - 1), 100 * (a / b - 1));
}

static void usage(void) {
    fprintf(stderr, "usage: clamp_reference [--thickness H] [--max-ny N] [--sag G]\n"
                    "  the table for ny = 2, 4, ... up to N (default H 0.02, N 32);\n"
                    "  --sag G: the static sag under the plate's weight in gravity G [m/s^2] instead of the period\n");
    exit(2);
}

int main(int argc, char** argv) {
    plate_case c = benchmark_case();
    int max_ny = 32, i;
    double sag_gravity = 0;
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--thickness")) c.thickness = number_argument(argc, argv, &i, usage);
        else if (!strcmp(argv[i], "--sag")) sag_gravity = number_argument(argc, argv, &i, usage);
        else if (!strcmp(argv[i], "--max-ny")) max_ny = (int)number_argument(argc, argv, &i, usage);
        else usage();
    }
    if (c.thickness <= 0 || c.thickness > c.length || max_ny < 2 || sag_gravity < 0) usage();
    if (sag_gravity > 0) print_sag_table(&c, max_ny, sag_gravity);
    else print_table(&c, max_ny);
    return 0;
}
