/* relax_chapter.h - body-fitted particles for sphsolid.h: lattice particles inside a signed-distance
   shape relaxed to a uniform, surface-conforming distribution (sps_body_add_sdf_relaxed).

   Written to be pasted verbatim as a chapter of sphsolid.h's implementation (after the particle
   chapter). Until then, include it after the implementation:
         #define SPHSOLID_IMPLEMENTATION
         #include "sphsolid.h"
         #include "relax_chapter.h"
   It uses the library's PUBLIC API only (sps_world_get_def, sps_body_is_valid,
   sps_world_kernel, sps_world_kernel_derivative, sps_body_add_particles), so it compiles against
   today's header. Integration notes (marked INTEGRATION below):
     - sps_body_add_sdf_relaxed becomes SPSDEF, declared next to sps_body_add_sdf;
     - sps__relax_alloc / sps__relax_free become the world's allocator (sps__alloc / sps__free);
     - sps__relax_error becomes sps__set_error(w, 0, ...) (today it can only reach the log
       callback of sps_world_get_def(w), so sps_world_last_error does not show these messages);
     - the includes below are already at the top of sphsolid.h (drop them). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* >>relax

   BODY-FITTED PARTICLES (sps_body_add_sdf_relaxed)
   The lattice fill of sps_body_add_sdf gives curved bodies staircase surfaces. Following the
   level-set based pre-processing of Yu, Zhu, Zhang, Haidn & Hu (Comput. Phys. Commun. 289 (2023)
   108744; ENO ref. [55], used for the rings and balls of ENO sections 6.3-6.8), the lattice
   particles are relaxed inside the shape:
   1. Lattice: x = lo + (i + 1/2) dp per axis where phi(x) < 0 (the points of sps_body_add_sdf),
      with phi(x) = max(sdf(x), box(x)), box(x) = max_a max(lo_a - x_a, x_a - hi_a): the body is
      the shape cut by the box, as for the lattice fill.
   2. Shifting (the particle-shifting / transport-velocity form, Lind et al. 2012; Adami, Hu &
      Adams 2013; Yu et al. 2023 eq. for the relaxation "acceleration" -2 p0 sum grad W V): every
      iteration moves every particle (Jacobi: all shifts from the old positions) by
          dx_i = -alpha h^2 G_i,       G_i = sum_j grad_i W_ij V_j + S_i,       alpha = 0.3,
      grad_i W_ij = dW/dr(r_ij) (x_i - x_j)/r_ij, V_j = dp^d, |dx_i| capped at 0.2 dp. Our
      change: below the distance of its peak (h/2 for Wendland C2) dW/dr is held at the peak,
      since the kernel's repulsion vanishes as r -> 0 and pressed pairs (sharp corners, parts
      thinner than 2 dp) would merge and stay merged; coincident points split along x.
      G_i is the gradient of the particle number density sum_j W_ij V_j; it vanishes for a
      uniform distribution with full support, so the shift drives particles towards one.
   3. The surface: the neighbours missing beyond the surface are represented by the surface
      itself (the level-set "kernel gradient integral" of Yu et al., here for a locally flat
      surface): a uniform continuum filling phi > 0 would add
          S_i = integral_{phi > 0} grad_i W(x_i - y) dy = n_i Wp(d_i),
          Wp(z) = integral over the plane at distance z of W   (2D: 2 int_0^sqrt(4h^2 - z^2)
                  W(sqrt(z^2 + s^2)) ds; 3D: 2 pi int_z^2h W(r) r dr; tabulated once),
      with d_i = -phi(x_i) (the depth; phi must be a signed distance near the surface) and n_i
      the outward normal grad phi / |grad phi| (central differences, step dp/10). S_i pushes a
      particle closer than about dp/2 to the surface back in; the rows inside (at dp/2, 3dp/2, ...
      deep) balance it when the outer row lies dp/2 inside, so the outer layer settles on a
      smooth surface dp/2 inside the shape (the particle volumes then tile the shape).
   4. Bounding (Yu et al.'s "surface bounding", as in SPHinXsys' ShapeSurfaceBounding): after
      each move, a particle closer than dp/2 to the surface (phi > -dp/2; this includes any that
      crossed it) is projected along the gradient onto the layer phi = -dp/2:
      x -= (phi + dp/2) grad phi / |grad phi|^2 (a Newton step; two at most).
   alpha = 0.3 is 2.5x below the measured stability limit (~0.8: the shift then overshoots and
   the particles jitter at the 0.2 dp cap); convergence is diffusive (long waves need ~(L/h)^2
   iterations), 300 iterations by default.
   The number of particles is the lattice's (no particle is added or removed). Cost O(N) per
   iteration (a cell list of cell size 2h, rebuilt every iteration), O(N) sdf calls per
   iteration plus 2 d per particle within 2h of the surface. Deterministic: no threads, sums in
   a fixed order; the same input gives the same particles bit for bit. */

#define SPS__RELAX_TABLE 128           /* Wp(z) table points on z in [0, 2h] */
#define SPS__RELAX_ALPHA SPS_R(0.3)    /* shift coefficient: unstable from ~0.8 (2D ring, 3D ball, h = 1.3 dp) */
#define SPS__RELAX_MAX_STEP SPS_R(0.2) /* largest shift per iteration [dp] */
#define SPS__RELAX_BOUND SPS_R(0.5)     /* surface bounding: depth < dp/2 is projected to dp/2 */
#define SPS__RELAX_DEFAULT_ITERATIONS 300
#define SPS__RELAX_MAX_POINTS 200000000.0 /* the world's particle cap (2e8) */

typedef struct sps__relax_ctx {
    const sps_world* w;
    int dim;
    sps_real dp, h, support, vol; /* support = 2h, vol = dp^d */
    sps_real (*sdf)(const sps_real x[3], void* user);
    void* user;
    sps_real lo[3], hi[3];
    int bad;             /* the sdf returned NaN (or the gradient was not finite) */
    sps_real bad_x[3];   /* where */
    sps_real wp[SPS__RELAX_TABLE + 1]; /* Wp(z_k), z_k = k 2h / TABLE */
    sps_real wf[SPS__RELAX_TABLE + 1]; /* F(z_k) = int_{z_k}^{2h} Wp: kernel mass beyond a flat surface */
    sps_real dw_peak, r_peak; /* the most negative dW/dr and where (sampled on 1024 points of 2h) */
    /* cell list */
    int cap_cells, nc[3];
    sps_real cmin[3], csize;
    int *start, *order, *cell;
} sps__relax_ctx;

/* INTEGRATION: the world's allocator (sps__alloc / sps__free) */
static void* sps__relax_alloc(const sps_world* w, size_t size) { (void)w; return malloc(size ? size : 1); }
static void sps__relax_free(const sps_world* w, void* p) { (void)w; free(p); }

/* INTEGRATION: sps__set_error(w, 0, ...). Today: the world's log callback only. */
static void sps__relax_error(const sps_world* w, const char* fmt, ...) {
    const sps_world_def* d = sps_world_get_def(w);
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (d && d->log) d->log(0, msg, d->log_user);
}

/* phi = max(sdf, box); NaN is recorded in c->bad (and returned as +1e30: outside). */
static sps_real sps__relax_phi(sps__relax_ctx* c, const sps_real x[3]) {
    sps_real p = c->sdf(x, c->user);
    int a;
    if (p != p) {
        if (!c->bad) { c->bad = 1; memcpy(c->bad_x, x, sizeof c->bad_x); }
        return SPS_R(1e30);
    }
    for (a = 0; a < c->dim; ++a) {
        sps_real e = c->lo[a] - x[a] > x[a] - c->hi[a] ? c->lo[a] - x[a] : x[a] - c->hi[a];
        if (e > p) p = e;
    }
    return p;
}

/* Central-difference gradient of phi, step dp/10; returns |g|^2 (0 if not usable). */
static sps_real sps__relax_grad(sps__relax_ctx* c, const sps_real x[3], sps_real g[3]) {
    sps_real e = SPS_R(0.1) * c->dp, y[3], g2 = 0;
    int a;
    g[0] = g[1] = g[2] = 0;
    for (a = 0; a < c->dim; ++a) {
        sps_real fp, fm;
        memcpy(y, x, sizeof y);
        y[a] = x[a] + e; fp = sps__relax_phi(c, y);
        y[a] = x[a] - e; fm = sps__relax_phi(c, y);
        g[a] = (fp - fm) / (2 * e);
        g2 += g[a] * g[a];
    }
    if (!(g2 < SPS_R(1e30)) && !c->bad) { c->bad = 1; memcpy(c->bad_x, x, sizeof c->bad_x); }
    return g2 > SPS_R(1e-12) && g2 < SPS_R(1e30) ? g2 : 0;
}

/* Linear interpolation in a table on [0, 2h] (0 beyond 2h; the value at 0 for z < 0). */
static sps_real sps__relax_table(const sps__relax_ctx* c, const sps_real* t, sps_real z) {
    sps_real u = z / c->support * SPS__RELAX_TABLE, f;
    int k;
    if (!(u > 0)) return t[0];
    if (u >= SPS__RELAX_TABLE) return 0;
    k = (int)u;
    f = u - (sps_real)k;
    return t[k] + f * (t[k + 1] - t[k]);
}

/* Fills the constants and the Wp, F tables (Simpson's rule, 64 intervals per entry). */
static void sps__relax_setup(sps__relax_ctx* c, const sps_world* w, const sps_real lo[3], const sps_real hi[3],
                             sps_real (*sdf)(const sps_real x[3], void* user), void* user) {
    const sps_world_def* d = sps_world_get_def(w);
    const int m = 64;
    int k, s, a;
    memset(c, 0, sizeof *c);
    c->w = w; c->dim = d->dim; c->dp = d->dp; c->h = d->h_over_dp * d->dp; c->support = 2 * c->h;
    c->vol = d->dim == 2 ? c->dp * c->dp : c->dp * c->dp * c->dp;
    c->sdf = sdf; c->user = user;
    for (a = 0; a < 3; ++a) {
        c->lo[a] = a < c->dim ? lo[a] : 0;
        c->hi[a] = a < c->dim ? hi[a] : 0;
    }
    for (k = 0; k <= SPS__RELAX_TABLE; ++k) {
        sps_real z = c->support * (sps_real)k / SPS__RELAX_TABLE, sum = 0, len, ds;
        len = c->dim == 2 ? (sps_real)sqrt((double)(c->support * c->support - z * z)) : c->support - z;
        ds = len / m;
        for (s = 0; s <= m; ++s) {
            sps_real t = ds * (sps_real)s, wgt = s == 0 || s == m ? 1 : (s & 1) ? 4 : 2, f;
            if (c->dim == 2) f = 2 * sps_world_kernel(w, (sps_real)sqrt((double)(z * z + t * t)));
            else f = 2 * SPS_R(3.14159265358979323846) * sps_world_kernel(w, z + t) * (z + t);
            sum += wgt * f;
        }
        c->wp[k] = sum * ds / 3;
    }
    c->dw_peak = 0; c->r_peak = 0;
    for (k = 1; k < 1024; ++k) {
        sps_real r = c->support * (sps_real)k / 1024, dw = sps_world_kernel_derivative(w, r);
        if (dw < c->dw_peak) { c->dw_peak = dw; c->r_peak = r; }
    }
    c->wf[SPS__RELAX_TABLE] = 0; /* trapezoid on the table (Wp is smooth, its error ~1e-5) */
    for (k = SPS__RELAX_TABLE - 1; k >= 0; --k)
        c->wf[k] = c->wf[k + 1] + SPS_R(0.5) * (c->wp[k] + c->wp[k + 1]) * c->support / SPS__RELAX_TABLE;
}

/* Lattice points lo + (i + 1/2) dp with phi < 0 (the points of sps_body_add_sdf, same count
   rule); writes them to xyz (3 reals each) if not NULL. Returns the count, or -1 when the box
   holds more than the world's particle cap. */
static long sps__relax_lattice(sps__relax_ctx* c, sps_real* xyz) {
    int cnt[3] = {1, 1, 1}, a, i, j, l;
    double cells = 1;
    long n = 0;
    for (a = 0; a < c->dim; ++a) {
        /* the slack of sps__fill (absorbs the rounding of lo, hi and dp) */
        double q = floor((double)((c->hi[a] - c->lo[a]) / c->dp +
                                  (sizeof(sps_real) == sizeof(float) ? SPS_R(1e-3) : SPS_R(1e-6))));
        if (q < 1) return 0;
        cells *= q;
        if (cells > SPS__RELAX_MAX_POINTS) return -1;
        cnt[a] = (int)q;
    }
    for (l = 0; l < cnt[2]; ++l)
        for (j = 0; j < cnt[1]; ++j)
            for (i = 0; i < cnt[0]; ++i) {
                sps_real x[3], p;
                x[0] = c->lo[0] + (i + SPS_R(0.5)) * c->dp;
                x[1] = c->lo[1] + (j + SPS_R(0.5)) * c->dp;
                x[2] = c->dim == 3 ? c->lo[2] + (l + SPS_R(0.5)) * c->dp : 0;
                p = c->sdf(x, c->user);
                if (!(p < 0)) { /* sps__fill's test, on the sdf alone; NaN is an error here */
                    if (p != p && !c->bad) { c->bad = 1; memcpy(c->bad_x, x, sizeof x); }
                    continue;
                }
                if (xyz) memcpy(xyz + 3 * n, x, sizeof x);
                ++n;
            }
    return n;
}

/* Cell list of the n points: cells of side >= 2h over their bounding box, at most cap_cells
   cells (the side grows when the box is large). Counting sort: the points of cell k are
   order[start[k] .. start[k+1]); cell[i] is point i's cell. */
static void sps__relax_grid(sps__relax_ctx* c, int n, const sps_real* xyz) {
    sps_real mx[3] = {0, 0, 0};
    double total;
    int a, i, k, ncell;
    for (a = 0; a < 3; ++a) { c->cmin[a] = 0; c->nc[a] = 1; }
    for (a = 0; a < c->dim; ++a) {
        c->cmin[a] = mx[a] = xyz[a];
        for (i = 1; i < n; ++i) {
            if (xyz[3 * i + a] < c->cmin[a]) c->cmin[a] = xyz[3 * i + a];
            if (xyz[3 * i + a] > mx[a]) mx[a] = xyz[3 * i + a];
        }
    }
    c->csize = c->support;
    for (;;) {
        total = 1;
        for (a = 0; a < c->dim; ++a) total *= floor((double)((mx[a] - c->cmin[a]) / c->csize)) + 1;
        if (total <= c->cap_cells) break;
        c->csize *= SPS_R(1.25);
    }
    for (a = 0; a < c->dim; ++a) c->nc[a] = (int)floor((double)((mx[a] - c->cmin[a]) / c->csize)) + 1;
    ncell = c->nc[0] * c->nc[1] * c->nc[2];
    memset(c->start, 0, sizeof(int) * (size_t)(ncell + 1));
    for (i = 0; i < n; ++i) {
        int ci[3] = {0, 0, 0};
        for (a = 0; a < c->dim; ++a) {
            ci[a] = (int)((xyz[3 * i + a] - c->cmin[a]) / c->csize);
            if (ci[a] >= c->nc[a]) ci[a] = c->nc[a] - 1;
            if (ci[a] < 0) ci[a] = 0;
        }
        c->cell[i] = (ci[2] * c->nc[1] + ci[1]) * c->nc[0] + ci[0];
        c->start[c->cell[i] + 1]++;
    }
    for (k = 0; k < ncell; ++k) c->start[k + 1] += c->start[k];
    for (i = 0; i < n; ++i) c->order[c->start[c->cell[i]]++] = i; /* start[k] now ends cell k */
    for (k = ncell; k > 0; --k) c->start[k] = c->start[k - 1];
    c->start[0] = 0;
}

/* Over the neighbours j != i within 2h of point i (cell list current): grad_out (if not NULL) +=
   sum_j grad_i W_ij V, and returns sum_j W_ij V (without the self term); *rmin gets the
   smallest distance. Fixed order (cells, then points in index order). */
static sps_real sps__relax_sums(const sps__relax_ctx* c, const sps_real* xyz, int i, sps_real grad_out[3], sps_real* rmin) {
    int ci[3], a, dz, dy, dx;
    sps_real nd = 0, s2 = c->support * c->support, r2min = SPS_R(1e30);
    const sps_real* xi = xyz + 3 * i;
    ci[0] = c->cell[i] % c->nc[0];
    ci[1] = (c->cell[i] / c->nc[0]) % c->nc[1];
    ci[2] = c->cell[i] / (c->nc[0] * c->nc[1]);
    for (dz = -1; dz <= 1; ++dz) {
        if (ci[2] + dz < 0 || ci[2] + dz >= c->nc[2]) continue;
        for (dy = -1; dy <= 1; ++dy) {
            if (ci[1] + dy < 0 || ci[1] + dy >= c->nc[1]) continue;
            for (dx = -1; dx <= 1; ++dx) {
                int k, p;
                if (ci[0] + dx < 0 || ci[0] + dx >= c->nc[0]) continue;
                k = ((ci[2] + dz) * c->nc[1] + ci[1] + dy) * c->nc[0] + ci[0] + dx;
                for (p = c->start[k]; p < c->start[k + 1]; ++p) {
                    int j = c->order[p];
                    sps_real d[3], r2 = 0, r;
                    if (j == i) continue;
                    for (a = 0; a < 3; ++a) { d[a] = xi[a] - xyz[3 * j + a]; r2 += d[a] * d[a]; }
                    if (r2 < r2min) r2min = r2;
                    if (!(r2 < s2)) continue;
                    r = (sps_real)sqrt((double)r2);
                    nd += sps_world_kernel(c->w, r) * c->vol;
                    if (grad_out) {
                        /* dW/dr, but not weaker than its peak below the peak's distance: the
                           kernel's repulsion vanishes at r -> 0 (Wendland C2: peak at r = h/2),
                           so pressed pairs (corners, thin parts) could merge and stay merged */
                        sps_real f = (r < c->r_peak ? c->dw_peak : sps_world_kernel_derivative(c->w, r)) * c->vol;
                        if (r > 0) f /= r;
                        else { d[0] = j < i ? 1 : -1; d[1] = d[2] = 0; } /* coincident: split along x, by index */
                        for (a = 0; a < 3; ++a) grad_out[a] += f * d[a];
                    }
                }
            }
        }
    }
    if (rmin) *rmin = (sps_real)sqrt((double)r2min);
    return nd;
}

/* Moves x onto the layer phi = target (Newton steps along grad phi, two at most); returns phi. */
static sps_real sps__relax_project(sps__relax_ctx* c, sps_real x[3], sps_real phi, sps_real target) {
    int it, a;
    for (it = 0; it < 2 && phi > target + SPS_R(1e-3) * c->dp; ++it) { /* stop once well inside */
        sps_real g[3], g2 = sps__relax_grad(c, x, g);
        if (g2 == 0) break;
        for (a = 0; a < c->dim; ++a) x[a] -= (phi - target) * g[a] / g2;
        phi = sps__relax_phi(c, x);
    }
    return phi;
}

/* The relaxation of n points xyz (3 reals each, inside the shape) in place: iterations steps
   of the shift (see the chapter's comment). phi (n) and dx (3n) and the cell list come from
   sps__relax_work. Every particle stays inside (phi < 0) after every iteration. */
static void sps__relax_iterate(sps__relax_ctx* c, int n, sps_real* xyz, sps_real* phi, sps_real* dx, int iterations) {
    int it, i, a;
    sps_real alpha_h2 = SPS__RELAX_ALPHA * c->h * c->h, cap = SPS__RELAX_MAX_STEP * c->dp;
    for (i = 0; i < n; ++i) phi[i] = sps__relax_phi(c, xyz + 3 * i);
    for (it = 0; it < iterations && !c->bad; ++it) {
        sps__relax_grid(c, n, xyz);
        for (i = 0; i < n; ++i) {
            sps_real gsum[3] = {0, 0, 0}, depth = -phi[i], len2 = 0;
            sps__relax_sums(c, xyz, i, gsum, NULL);
            if (depth < c->support) { /* the surface stands in for the missing neighbours: n Wp(d) */
                sps_real g[3], g2 = sps__relax_grad(c, xyz + 3 * i, g);
                if (g2 > 0) {
                    sps_real f = sps__relax_table(c, c->wp, depth) / (sps_real)sqrt((double)g2);
                    for (a = 0; a < c->dim; ++a) gsum[a] += f * g[a];
                }
            }
            for (a = 0; a < 3; ++a) { dx[3 * i + a] = -alpha_h2 * gsum[a]; len2 += dx[3 * i + a] * dx[3 * i + a]; }
            if (len2 > cap * cap) {
                sps_real s = cap / (sps_real)sqrt((double)len2);
                for (a = 0; a < 3; ++a) dx[3 * i + a] *= s;
            }
        }
        for (i = 0; i < n; ++i) {
            sps_real* x = xyz + 3 * i, old[3], p;
            memcpy(old, x, sizeof old);
            for (a = 0; a < c->dim; ++a) x[a] += dx[3 * i + a];
            p = sps__relax_phi(c, x);
            if (p > -SPS__RELAX_BOUND * c->dp) p = sps__relax_project(c, x, p, -SPS_R(0.5) * c->dp);
            if (p < 0) phi[i] = p;
            else memcpy(x, old, sizeof old); /* no layer dp/2 deep here (a shape thinner than dp,
                                                a sharp corner): the particle stays where it was,
                                                so every particle stays inside (phi < 0) */
        }
    }
}

/* Allocation in one place: the work arrays of n points. Returns the block (NULL: out of memory). */
static void* sps__relax_work(sps__relax_ctx* c, int n, sps_real** phi, sps_real** dx) {
    size_t nr = (size_t)n * 4, ni;
    char* blk;
    c->cap_cells = 2 * n + 64; /* at most ~2 cells per point: O(N) memory whatever the box */
    ni = (size_t)n * 2 + (size_t)c->cap_cells + 1;
    blk = (char*)sps__relax_alloc(c->w, nr * sizeof(sps_real) + ni * sizeof(int));
    if (!blk) return NULL;
    *phi = (sps_real*)blk;
    *dx = *phi + n;
    c->start = (int*)(void*)(*dx + 3 * (size_t)n);
    c->order = c->start + c->cap_cells + 1;
    c->cell = c->order + n;
    return blk;
}

/* Quality of a particle set (the tests and the report):
     nd_spread         std/mean of the Shepard number density sum_j W_ij V_j (self included,
                       V_j = dp^d) completed by the kernel mass beyond the surface F(d_i) (flat-
                       surface estimate), over all particles: 0 for an ideal body-fitted set;
     nd_spread_inner   std/mean of the plain sum_j W_ij V_j over the particles at depth > 2h
                       (full support inside; exactly 0 for the lattice);
     min_spacing       smallest pair distance / dp;
     surface_rms       RMS of (depth - dp/2)/dp over the outer layer (the particles with depth
                       < dp): the lattice's is ~0.29 (depths uniform in (0, dp)). */
typedef struct sps__relax_quality {
    int n, inner, layer;
    sps_real nd_spread, nd_spread_inner, min_spacing, surface_rms;
} sps__relax_quality;

static sps_result sps__relax_measure(const sps_world* w, int n, const sps_real* xyz, const sps_real lo[3], const sps_real hi[3],
                                     sps_real (*sdf)(const sps_real x[3], void* user), void* user, sps__relax_quality* q) {
    sps__relax_ctx c;
    sps_real *phi, *dx, rmin = SPS_R(1e30);
    double s1 = 0, s2 = 0, t1 = 0, t2 = 0, e2 = 0;
    void* blk;
    int i;
    memset(q, 0, sizeof *q);
    if (!w || !sdf || !xyz || n <= 0) return SPS_ERR_INVALID_ARG;
    sps__relax_setup(&c, w, lo, hi, sdf, user);
    if (!(blk = sps__relax_work(&c, n, &phi, &dx))) return SPS_ERR_OUT_OF_MEMORY;
    sps__relax_grid(&c, n, xyz);
    q->n = n;
    for (i = 0; i < n; ++i) {
        sps_real r, depth = -sps__relax_phi(&c, xyz + 3 * i);
        double nd = (double)(sps__relax_sums(&c, xyz, i, NULL, &r) + sps_world_kernel(w, 0) * c.vol);
        double full = nd + (double)(depth >= 0 ? sps__relax_table(&c, c.wf, depth) : 1 - sps__relax_table(&c, c.wf, -depth));
        if (r < rmin) rmin = r;
        s1 += full; s2 += full * full;
        if (depth > c.support) { q->inner++; t1 += nd; t2 += nd * nd; }
        if (depth < c.dp) { double e = (double)(depth / c.dp) - 0.5; q->layer++; e2 += e * e; }
    }
    sps__relax_free(w, blk);
    s1 /= n; s2 /= n;
    q->nd_spread = (sps_real)(sqrt(fmax(s2 - s1 * s1, 0)) / s1);
    if (q->inner) { t1 /= q->inner; t2 /= q->inner; q->nd_spread_inner = (sps_real)(sqrt(fmax(t2 - t1 * t1, 0)) / t1); }
    q->min_spacing = rmin / c.dp;
    q->surface_rms = q->layer ? (sps_real)sqrt(e2 / q->layer) : 0;
    return c.bad ? SPS_ERR_INVALID_ARG : SPS_OK;
}

/* Lattice fill of [lo, hi) where sdf(x, user) < 0 (the points of sps_body_add_sdf), relaxed to a
   uniform distribution whose outer layer lies on a smooth surface dp/2 inside the shape (see
   BODY-FITTED PARTICLES above). sdf must be a signed distance (|grad| = 1) within 2h of the
   surface, negative inside; the box should contain the shape (a shape cut by the box is relaxed
   as the intersection). iterations: shifting steps, >= 0; 0 selects 300. *added (may be NULL)
   gets the number added: the lattice's count (the particles keep their volume dp^d).
   Errors: SPS_ERR_INVALID_ARG for a NULL world, sdf or lo/hi, an invalid body, a box not finite
   with lo < hi, iterations < 0, more lattice points than the world's cap, or an sdf that returns
   NaN (at a lattice point or during the relaxation): nothing is added. The message goes to the
   world's log callback (INTEGRATION: sps__set_error, so that sps_world_last_error has it).
   SPS_ERR_OUT_OF_MEMORY; errors of sps_body_add_particles. Allocates O(N) scratch; O(N) per
   iteration; deterministic. INTEGRATION: SPSDEF. */
static sps_result sps_body_add_sdf_relaxed(sps_world* w, sps_body b, const sps_real lo[3], const sps_real hi[3],
                                           sps_real (*sdf)(const sps_real x[3], void* user), void* user, int iterations, int* added) {
    static const char* fn = "sps_body_add_sdf_relaxed";
    sps__relax_ctx c;
    sps_real *xyz, *phi, *dx;
    void* blk;
    long n;
    int a;
    sps_result r;
    if (added) *added = 0;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (!sps_body_is_valid(w, b)) { sps__relax_error(w, "%s: body handle %u is not a body of this world", fn, (unsigned)b.id); return SPS_ERR_INVALID_ARG; }
    if (!sdf) { sps__relax_error(w, "%s: sdf must not be NULL", fn); return SPS_ERR_INVALID_ARG; }
    if (!lo || !hi) { sps__relax_error(w, "%s: lo and hi must not be NULL", fn); return SPS_ERR_INVALID_ARG; }
    if (iterations < 0) { sps__relax_error(w, "%s: iterations = %d, allowed >= 0 (0: %d)", fn, iterations, SPS__RELAX_DEFAULT_ITERATIONS); return SPS_ERR_INVALID_ARG; }
    for (a = 0; a < sps_world_get_def(w)->dim; ++a)
        if (!(lo[a] - lo[a] == 0) || !(hi[a] - hi[a] == 0) || !(lo[a] < hi[a])) {
            sps__relax_error(w, "%s: box axis %d is [%g, %g), allowed finite with lo < hi", fn, a, (double)lo[a], (double)hi[a]);
            return SPS_ERR_INVALID_ARG;
        }
    if (iterations == 0) iterations = SPS__RELAX_DEFAULT_ITERATIONS;
    sps__relax_setup(&c, w, lo, hi, sdf, user);
    n = sps__relax_lattice(&c, NULL);
    if (n < 0) { sps__relax_error(w, "%s: the box holds more than %.0f lattice points", fn, SPS__RELAX_MAX_POINTS); return SPS_ERR_INVALID_ARG; }
    if (c.bad) {
        sps__relax_error(w, "%s: sdf returned NaN at (%g, %g, %g)", fn, (double)c.bad_x[0], (double)c.bad_x[1], (double)c.bad_x[2]);
        return SPS_ERR_INVALID_ARG;
    }
    if (n == 0) return SPS_OK;
    if (!(blk = sps__relax_work(&c, (int)n, &phi, &dx))) { sps__relax_error(w, "%s: out of memory for the work arrays of %ld points", fn, n); return SPS_ERR_OUT_OF_MEMORY; }
    xyz = (sps_real*)sps__relax_alloc(w, sizeof(sps_real) * 3 * (size_t)n);
    if (!xyz) { sps__relax_free(w, blk); sps__relax_error(w, "%s: out of memory for %ld points", fn, n); return SPS_ERR_OUT_OF_MEMORY; }
    sps__relax_lattice(&c, xyz);
    sps__relax_iterate(&c, (int)n, xyz, phi, dx, iterations);
    if (c.bad) {
        sps__relax_error(w, "%s: sdf returned NaN (or a gradient that is not finite) near (%g, %g, %g)", fn,
                         (double)c.bad_x[0], (double)c.bad_x[1], (double)c.bad_x[2]);
        r = SPS_ERR_INVALID_ARG;
    } else {
        r = sps_body_add_particles(w, b, (int)n, xyz, NULL);
        if (r == SPS_OK && added) *added = (int)n;
    }
    sps__relax_free(w, xyz);
    sps__relax_free(w, blk);
    return r;
}
