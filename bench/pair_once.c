/* pair_once - each pair computed once against each pair computed from both sides.

   The updated-Lagrangian passes sum, for each particle, its own neighbours (full lists, lane
   groups of SPS__LANES particles side by side): every pair is evaluated twice, once from each
   side. A half list evaluates each pair once (j > i) and adds its term to both particles: the
   i side into the lane's sums, the j side scattered into per-particle sums. This probe times
   both on the same neighbour lists, one thread, for the two passes of the default ENO-A body:
     pressure     -(p_i + p_j - Z u) dW e_ij V_j + (tau_i + tau_j) . e_ij dW V_j, and the
                  accumulated pair forces g_ij e_ij (SPS_ROTATION_PAIR): 2 dim values a pair;
     continuity   u dW V_j, -v_ij (x) e_ij dW V_j, -r e_ij (x) e_ij dW V_j and the pair force
                  increment (2D: 8 values a pair, 3D: 16).
   Variants, each over all of the body's lane groups:
     library      the body's own pair loop (b->model.pass.*_pairs): today's cost;
     full         the same terms written here on the full lists (checks that this probe's
                  terms cost what the library's do);
     half         the half lists: each lane group's slots keep the neighbours j > i only; each
                  pair's term goes into the lane's sums and, after each neighbour rank, a
                  scalar loop adds it to j's sums (the lanes of a rank often share a j, so the
                  scatter cannot be a vector store). Processed in group order, every
                  contribution to a group's particles comes from it or an earlier group, so
                  its sums are complete when its loop ends (a threaded version would need a
                  two-colour order of blocks of groups to stay deterministic; not built here).
                  --owner balanced splits each particle's pairs evenly instead (fewer padding
                  slots; the sums then complete only after the last group).
   Each figure: the best of 7 trials of --repeat sweeps, ns per particle; full and half must
   agree to rounding (their largest relative difference is printed). A probe of the library's
   private state, not an example of the API.

   Build: make build/pair_once   Run: ./build/pair_once [--scene plate2d|cube] [--res N] [--dp D] [--owner ordered|balanced] */
#define SPHSOLID_IMPLEMENTATION
#include "../examples/common.h"
#include "../examples/scenes/plate2d.h"
#include "../examples/scenes/spinning.h"

#define TRIALS 7
#define L SPS__LANES

typedef struct {
    int* j;        /* slots, lane layout as nb_j */
    int* start;    /* group starts, ngroups + 1 */
    sps_real* pf;  /* a pair force per half slot */
    int* full_of;  /* the full slot of each half slot (to copy the pair force) */
} half_lists;

/* Whether particle i evaluates pair (i, j): ordered, j > i (then a group's sums are complete when
   its loop ends); balanced, j > i for i + j even and j < i for i + j odd, so that each particle
   owns about half of its pairs (the ordered rule gives the first particles of a cell most of
   theirs, and a lane group is as long as its longest lane). */
static int owns(int i, int j, int balanced) {
    return j != i && (balanced ? (i < j) == (((i + j) & 1) == 0) : j > i);
}

/* The half lists of body b: lane l of group g keeps the neighbours it owns, in list order. */
static void build_half(const sps_world* w, const sps__body* b, half_lists* h, int balanced) {
    int g, l, k, total = 0;
    h->start = (int*)malloc(sizeof(int) * (size_t)(b->ngroups + 1));
    for (g = 0; g < b->ngroups; ++g) {
        int longest = 0;
        for (l = 0; l < L && b->begin + g * L + l < b->end; ++l) {
            const int i = b->begin + g * L + l;
            int m = 0;
            for (k = 0; k < w->nb_count[i]; ++k) m += owns(i, sps__neighbor(w, i, k), balanced);
            if (m > longest) longest = m;
        }
        h->start[g] = total;
        total += longest * L;
    }
    h->start[b->ngroups] = total;
    h->j = (int*)malloc(sizeof(int) * (size_t)(total + 1));
    h->pf = (sps_real*)malloc(sizeof(sps_real) * (size_t)(total + 1));
    h->full_of = (int*)malloc(sizeof(int) * (size_t)(total + 1));
    for (g = 0; g < b->ngroups; ++g) {
        const int len = (h->start[g + 1] - h->start[g]) / L;
        for (l = 0; l < L; ++l) {
            const int i = b->begin + g * L + l;
            int m = 0, s = h->start[g] + l;
            if (i < b->end)
                for (k = 0; k < w->nb_count[i]; ++k) {
                    const int j = sps__neighbor(w, i, k);
                    if (!owns(i, j, balanced)) continue;
                    h->j[s + m * L] = j;
                    h->full_of[s + m * L] = w->nb_first[i] + k * L;
                    h->pf[s + m * L] = w->pair_force ? w->pair_force[w->nb_first[i] + k * L] : 0;
                    ++m;
                }
            for (; m < len; ++m) {
                h->j[s + m * L] = i < b->end ? i : b->begin; /* padding: dW = 0 */
                h->pf[s + m * L] = 0;
                h->full_of[s + m * L] = -1;
            }
        }
    }
}

/* Outputs: per particle, pressure: acc (3) + shear (3); continuity: 16 sums. */
typedef struct {
    sps_real* v[16];
} outputs;

/* ---- pressure pass ---- */
SPS__INLINE void pressure_full(sps_world* w, const sps__body* b, outputs* o, const int dim) {
    const sps_real *SPS__RESTRICT p = w->p, *SPS__RESTRICT vol = w->vol, *SPS__RESTRICT tau = b->tau, *SPS__RESTRICT pf = w->pair_force;
    const sps_real z = b->z_riemann;
    const int begin = b->begin;
    int g, k, l, a;
    for (g = 0; g < b->ngroups; ++g) {
        const sps__group q = sps__group_of(w, b, g);
        sps_real acc[3][L], sh[3][L], tau_i[6][L];
        for (a = 0; a < 3; ++a)
            for (l = 0; l < L; ++l) acc[a][l] = sh[a][l] = 0;
        sps__own_lanes(tau, 6, q.i0 - begin, tau_i);
        SPS__PAIR_LOOP(w, q, dim, SPS__GEO_WENDLAND, k, l, {
            const sps_real ex = e.ex, ey = e.ey, ez = e.ez, dw = e.dw, u = sps__approach(w, i, j, ex, ey, ez, dim);
            const sps_real f2 = ((p[i] + p[j]) - z * u) * dw * vol[j], f = pf[s], dwv = dw * vol[j];
            const int tj = 6 * (j - begin);
            const sps_real sxx = tau_i[0][l] + tau[tj], sxy = tau_i[1][l] + tau[tj + 1], syy = tau_i[3][l] + tau[tj + 3];
            acc[0][l] -= f2 * ex;
            acc[1][l] -= f2 * ey;
            sh[0][l] += f * ex;
            sh[1][l] += f * ey;
            if (dim == 3) {
                const sps_real sxz = tau_i[2][l] + tau[tj + 2], syz = tau_i[4][l] + tau[tj + 4], szz = tau_i[5][l] + tau[tj + 5];
                acc[2][l] -= f2 * ez;
                sh[2][l] += f * ez;
                acc[0][l] += (sxx * ex + sxy * ey + sxz * ez) * dwv;
                acc[1][l] += (sxy * ex + syy * ey + syz * ez) * dwv;
                acc[2][l] += (sxz * ex + syz * ey + szz * ez) * dwv;
            } else {
                acc[0][l] += (sxx * ex + sxy * ey) * dwv;
                acc[1][l] += (sxy * ex + syy * ey) * dwv;
            }
        })
        for (l = 0; l < L && q.i0 + l < b->end; ++l)
            for (a = 0; a < dim; ++a) {
                o->v[a][q.i0 + l] = acc[a][l];
                o->v[3 + a][q.i0 + l] = sh[a][l];
            }
    }
}

SPS__INLINE void pressure_half(sps_world* w, const sps__body* b, const half_lists* h, outputs* o, const int dim) {
    const sps_real *SPS__RESTRICT p = w->p, *SPS__RESTRICT vol = w->vol, *SPS__RESTRICT tau = b->tau, *SPS__RESTRICT pf = h->pf;
    const sps_real z = b->z_riemann;
    const sps_real *vx = w->vel[0], *vy = w->vel[1], *vz = w->vel[2];
    const int begin = b->begin;
    int g, k, l, a;
    for (a = 0; a < 2 * 3; ++a) memset(o->v[a] + begin, 0, sizeof(sps_real) * (size_t)(b->end - begin));
    for (g = 0; g < b->ngroups; ++g) {
        const int i0 = b->begin + g * L, s0 = h->start[g], len = (h->start[g + 1] - s0) / L;
        sps_real acc[3][L], sh[3][L], tau_i[6][L], out[6][L];
        for (a = 0; a < 3; ++a)
            for (l = 0; l < L; ++l) acc[a][l] = sh[a][l] = 0;
        sps__own_lanes(tau, 6, i0 - begin, tau_i);
        for (k = 0; k < len; ++k) {
            const int* js = h->j + s0 + k * L;
            SPS__PRAGMA(omp simd)
            for (l = 0; l < L; ++l) {
                const int i = i0 + l, s = s0 + k * L + l, j = js[l];
                const sps__pair_geometry e = sps__pair(w, i, s, j, dim, SPS__GEO_WENDLAND); /* the library's pair geometry */
                const sps_real ex = e.ex, ey = e.ey, ez = e.ez, dw = e.dw;
                const sps_real u = (vx[i] - vx[j]) * ex + (vy[i] - vy[j]) * ey + (dim == 3 ? (vz[i] - vz[j]) * ez : 0);
                const sps_real f2 = ((p[i] + p[j]) - z * u) * dw, f = pf[s];
                const int tj = 6 * (j - begin);
                const sps_real sxx = tau_i[0][l] + tau[tj], sxy = tau_i[1][l] + tau[tj + 1], syy = tau_i[3][l] + tau[tj + 3];
                sps_real F[3];
                if (dim == 3) {
                    const sps_real sxz = tau_i[2][l] + tau[tj + 2], syz = tau_i[4][l] + tau[tj + 4], szz = tau_i[5][l] + tau[tj + 5];
                    F[0] = (sxx * ex + sxy * ey + sxz * ez) * dw - f2 * ex;
                    F[1] = (sxy * ex + syy * ey + syz * ez) * dw - f2 * ey;
                    F[2] = (sxz * ex + syz * ey + szz * ez) * dw - f2 * ez;
                } else {
                    F[0] = (sxx * ex + sxy * ey) * dw - f2 * ex;
                    F[1] = (sxy * ex + syy * ey) * dw - f2 * ey;
                    F[2] = 0;
                }
                acc[0][l] += F[0] * vol[j];
                acc[1][l] += F[1] * vol[j];
                sh[0][l] += f * ex;
                sh[1][l] += f * ey;
                out[0][l] = F[0] * vol[i];
                out[1][l] = F[1] * vol[i];
                out[3][l] = f * ex;
                out[4][l] = f * ey;
                if (dim == 3) {
                    acc[2][l] += F[2] * vol[j];
                    sh[2][l] += f * ez;
                    out[2][l] = F[2] * vol[i];
                    out[5][l] = f * ez;
                }
            }
            for (l = 0; l < L; ++l) { /* the j side: -F_ij V_i, -g_ij e_ij */
                const int j = js[l];
                for (a = 0; a < dim; ++a) {
                    o->v[a][j] -= out[a][l];
                    o->v[3 + a][j] -= out[3 + a][l];
                }
            }
        }
        for (l = 0; l < L && i0 + l < b->end; ++l) /* complete: every source of this group is at or before it */
            for (a = 0; a < dim; ++a) {
                o->v[a][i0 + l] += acc[a][l];
                o->v[3 + a][i0 + l] += sh[a][l];
            }
    }
}

/* ---- continuity pass (ENO-A: velocity gradient, moment, density rate, pair force increment) ---- */
enum { C_DRHO, C_M, C_A = C_M + 9, C_N = C_A + 6 };

SPS__INLINE void continuity_full(sps_world* w, const sps__body* b, outputs* o, sps_real* pair_force, const int dim) {
    const sps_real *vol = w->vol, *vx = w->vel[0], *vy = w->vel[1], *vz = w->vel[2], rate = 1e-9;
    int g, k, l, a;
    for (g = 0; g < b->ngroups; ++g) {
        const sps__group q = sps__group_of(w, b, g);
        sps_real sum[C_N][L];
        for (a = 0; a < C_N; ++a)
            for (l = 0; l < L; ++l) sum[a][l] = 0;
        SPS__PAIR_LOOP(w, q, dim, SPS__GEO_WENDLAND, k, l, {
            const sps_real ex = e.ex, ey = e.ey, ez = e.ez, dw = e.dw, dw_r = e.dw_r;
            const sps_real dvx = vx[i] - vx[j], dvy = vy[i] - vy[j], dvz = dim == 3 ? vz[i] - vz[j] : 0;
            const sps_real u = dvx * ex + dvy * ey + dvz * ez, dwv = dw * vol[j];
            const sps_real gx = dvx * dwv, gy = dvy * dwv, gz = dvz * dwv, rdwv = e.r * dwv;
            sum[C_DRHO][l] += u * dwv;
            pair_force[s] += rate * (u * dw_r) * (vol[i] * vol[j]);
            sum[C_M + 0][l] -= gx * ex; sum[C_M + 1][l] -= gx * ey;
            sum[C_M + 3][l] -= gy * ex; sum[C_M + 4][l] -= gy * ey;
            sum[C_A + 0][l] -= rdwv * ex * ex; sum[C_A + 1][l] -= rdwv * ex * ey; sum[C_A + 3][l] -= rdwv * ey * ey;
            if (dim == 3) {
                sum[C_M + 2][l] -= gx * ez; sum[C_M + 5][l] -= gy * ez;
                sum[C_M + 6][l] -= gz * ex; sum[C_M + 7][l] -= gz * ey; sum[C_M + 8][l] -= gz * ez;
                sum[C_A + 2][l] -= rdwv * ex * ez; sum[C_A + 4][l] -= rdwv * ey * ez; sum[C_A + 5][l] -= rdwv * ez * ez;
            }
        })
        for (l = 0; l < L && q.i0 + l < b->end; ++l)
            for (a = 0; a < C_N; ++a) o->v[a][q.i0 + l] = sum[a][l];
    }
}

/* the sums of a pair that dim has: density, M (dim x dim), A (its upper triangle) */
static const int c_used2[] = {C_DRHO, C_M + 0, C_M + 1, C_M + 3, C_M + 4, C_A + 0, C_A + 1, C_A + 3};
static const int c_used3[] = {C_DRHO, C_M + 0, C_M + 1, C_M + 2, C_M + 3, C_M + 4, C_M + 5, C_M + 6, C_M + 7, C_M + 8,
                              C_A + 0, C_A + 1, C_A + 2, C_A + 3, C_A + 4, C_A + 5};

SPS__INLINE void continuity_half(sps_world* w, const sps__body* b, const half_lists* h, outputs* o, sps_real* pair_force, const int dim) {
    const sps_real *vol = w->vol, *vx = w->vel[0], *vy = w->vel[1], *vz = w->vel[2], rate = 1e-9;
    const int* used = dim == 3 ? c_used3 : c_used2;
    const int nused = dim == 3 ? 16 : 8;
    int g, k, l, a;
    for (a = 0; a < nused; ++a) memset(o->v[used[a]] + b->begin, 0, sizeof(sps_real) * (size_t)(b->end - b->begin));
    for (g = 0; g < b->ngroups; ++g) {
        const int i0 = b->begin + g * L, s0 = h->start[g], len = (h->start[g + 1] - s0) / L;
        sps_real sum[C_N][L], out[C_N][L];
        for (a = 0; a < C_N; ++a)
            for (l = 0; l < L; ++l) sum[a][l] = 0;
        for (k = 0; k < len; ++k) {
            const int* js = h->j + s0 + k * L;
            SPS__PRAGMA(omp simd)
            for (l = 0; l < L; ++l) {
                const int i = i0 + l, s = s0 + k * L + l, j = js[l];
                const sps__pair_geometry e = sps__pair(w, i, s, j, dim, SPS__GEO_WENDLAND); /* the library's pair geometry */
                const sps_real ex = e.ex, ey = e.ey, ez = e.ez, dw = e.dw, dw_r = e.dw_r;
                const sps_real dvx = vx[i] - vx[j], dvy = vy[i] - vy[j], dvz = dim == 3 ? vz[i] - vz[j] : 0;
                const sps_real u = dvx * ex + dvy * ey + dvz * ez, vi = vol[i], vj = vol[j];
                const sps_real gx = dvx * dw, gy = dvy * dw, gz = dvz * dw, rdw = e.r * dw;
                sps_real Q[C_N];
                int c;
                pair_force[s] += rate * (u * dw_r) * (vi * vj); /* once per pair */
                Q[C_DRHO] = u * dw;
                Q[C_M + 0] = -gx * ex; Q[C_M + 1] = -gx * ey; Q[C_M + 3] = -gy * ex; Q[C_M + 4] = -gy * ey;
                Q[C_A + 0] = -rdw * ex * ex; Q[C_A + 1] = -rdw * ex * ey; Q[C_A + 3] = -rdw * ey * ey;
                if (dim == 3) {
                    Q[C_M + 2] = -gx * ez; Q[C_M + 5] = -gy * ez; Q[C_M + 6] = -gz * ex; Q[C_M + 7] = -gz * ey; Q[C_M + 8] = -gz * ez;
                    Q[C_A + 2] = -rdw * ex * ez; Q[C_A + 4] = -rdw * ey * ez; Q[C_A + 5] = -rdw * ez * ez;
                }
                SPS__UNROLL
                for (c = 0; c < C_N; ++c) {
                    if (dim == 2 && (c == C_M + 2 || c == C_M + 5 || (c >= C_M + 6 && c < C_A) || c == C_A + 2 || c == C_A + 4 || c == C_A + 5)) continue;
                    sum[c][l] += Q[c] * vj;
                    out[c][l] = Q[c] * vi;
                }
            }
            for (l = 0; l < L; ++l) { /* the j side: the same symmetric Q_ij times V_i */
                const int j = js[l];
                for (a = 0; a < nused; ++a) o->v[used[a]][j] += out[used[a]][l];
            }
        }
        for (l = 0; l < L && i0 + l < b->end; ++l)
            for (a = 0; a < nused; ++a) o->v[used[a]][i0 + l] += sum[used[a]][l];
    }
}

/* ---- timing ---- */
typedef enum { V_LIB_PRESSURE, V_FULL_PRESSURE, V_HALF_PRESSURE, V_LIB_CONTINUITY, V_FULL_CONTINUITY, V_HALF_CONTINUITY, V_N } variant;
static const char* variant_name[V_N] = {"pressure library", "pressure full", "pressure half", "continuity library", "continuity full",
                                        "continuity half"};

static void run(sps_world* w, const sps__body* b, const half_lists* h, outputs* o, sps_real* pf_full, sps_real* pf_half, variant v) {
    int g;
    sps__lane_sums sums;
    switch (v) {
    case V_LIB_PRESSURE:
        for (g = 0; g < b->ngroups; ++g) {
            sps__clear_sums(&sums, SPS__PRESSURE_SUMS);
            b->model.pass.pressure_pairs(w, b, g, 1e-7, b->model.pass.pressure_terms, &sums);
        }
        break;
    case V_LIB_CONTINUITY:
        for (g = 0; g < b->ngroups; ++g) {
            sps__clear_sums(&sums, SPS__NSUM);
            b->model.pass.continuity_pairs(w, b, g, 1e-7, b->model.pass.continuity_terms, &sums);
        }
        break;
    case V_FULL_PRESSURE: if (w->dim == 2) pressure_full(w, b, o, 2); else pressure_full(w, b, o, 3); break;
    case V_HALF_PRESSURE: if (w->dim == 2) pressure_half(w, b, h, o, 2); else pressure_half(w, b, h, o, 3); break;
    case V_FULL_CONTINUITY: if (w->dim == 2) continuity_full(w, b, o, pf_full, 2); else continuity_full(w, b, o, pf_full, 3); break;
    case V_HALF_CONTINUITY: if (w->dim == 2) continuity_half(w, b, h, o, pf_half, 2); else continuity_half(w, b, h, o, pf_half, 3); break;
    default: break;
    }
}

/* the largest |full - half| over the particles, relative to the largest |full| of that output */
static double compare(const outputs* a, const outputs* c, int from, int to, int n_out) {
    double worst = 0;
    int k, i;
    for (k = 0; k < n_out; ++k) {
        double scale = 0, diff = 0;
        for (i = from; i < to; ++i) {
            if (fabs(a->v[k][i]) > scale) scale = fabs(a->v[k][i]);
            if (fabs(a->v[k][i] - c->v[k][i]) > diff) diff = fabs(a->v[k][i] - c->v[k][i]);
        }
        if (scale > 0 && diff / scale > worst) worst = diff / scale;
    }
    return worst;
}

int main(int argc, char** argv) {
    int scene = 0, res = 10, repeat = 200, steps = 50, v, t, r, k, bi, best_b = 0, balanced = 0;
    double dp = 0.05, best[V_N];
    opt_spec opts[] = {
        {"scene", OPT_CHOICE, &scene, "the set-up", 0, 0, "plate2d|cube"},
        {"res", OPT_INT, &res, "plate2d: H/dp", 2, 1000, NULL},
        {"dp", OPT_REAL, &dp, "cube: particle spacing [m]", 0.005, 0.5, NULL},
        {"repeat", OPT_INT, &repeat, "sweeps per trial", 1, 1000000, NULL},
        {"owner", OPT_CHOICE, &balanced, "which particle of a pair evaluates it", 0, 0, "ordered|balanced"},
        {"steps", OPT_INT, &steps, "sub-steps before timing (stress, pressure, pair forces set)", 1, 100000, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body body, probe_body;
    sps_observer probe;
    const sps__body* b;
    half_lists h;
    outputs full, half;
    sps_real *pf_full, *pf_half;
    long slots_full, slots_half;
    opt_parse(argc, argv, "pairs computed once (half lists) against from both sides", opts, (int)(sizeof opts / sizeof *opts));
    wd.threads = 1;
    wd.log = ex_log;
    bd.shear = SPS_SHEAR_ENO_A;
    bd.track_stress = 1;
    if (scene == 0) {
        plate2d_params p = {.res = res, .vf = 0.05};
        bd.material.density = PLATE2D_RHO0; bd.material.youngs_modulus = PLATE2D_E; bd.material.poisson_ratio = PLATE2D_NU;
        ex_check(NULL, plate2d_create(wd, &bd, &p, &w, &body, &probe));
    } else {
        spinning_params p = {.dim = 3, .dp = dp, .omega = 50};
        bd.material.density = SPINNING_RHO0; bd.material.youngs_modulus = SPINNING_E; bd.material.poisson_ratio = SPINNING_NU_3D;
        ex_check(NULL, spinning_create(wd, &bd, "cube", &p, &w, &probe_body));
    }
    ex_check(w, sps_world_advance_substeps(w, steps, 0, NULL));
    for (bi = 0; bi < w->nbodies; ++bi)
        if (w->bodies[bi].end - w->bodies[bi].begin > w->bodies[best_b].end - w->bodies[best_b].begin) best_b = bi;
    b = &w->bodies[best_b];
    if (!w->pair_force || !b->tau) {
        fprintf(stderr, "pair_once: the body has no pair forces or no stress (ENO-A with stress tracking expected)\n");
        return 1;
    }
    build_half(w, b, &h, balanced);
    slots_full = w->nb_group_start[b->group0 + b->ngroups] - w->nb_group_start[b->group0];
    slots_half = h.start[b->ngroups];
    for (k = 0; k < 16; ++k) {
        full.v[k] = (sps_real*)calloc((size_t)w->n, sizeof(sps_real));
        half.v[k] = (sps_real*)calloc((size_t)w->n, sizeof(sps_real));
    }
    pf_full = (sps_real*)calloc((size_t)w->nb_group_start[b->group0 + b->ngroups] + 1, sizeof(sps_real)); /* the body's slots */
    pf_half = (sps_real*)calloc((size_t)slots_half + 1, sizeof(sps_real));
    run(w, b, &h, &full, pf_full, pf_half, V_FULL_PRESSURE);
    run(w, b, &h, &half, pf_full, pf_half, V_HALF_PRESSURE);
    printf("pressure: full and half differ by %.2e (relative to each output's largest)\n", compare(&full, &half, b->begin, b->end, 6));
    run(w, b, &h, &full, pf_full, pf_half, V_FULL_CONTINUITY);
    run(w, b, &h, &half, pf_full, pf_half, V_HALF_CONTINUITY);
    printf("continuity: full and half differ by %.2e\n", compare(&full, &half, b->begin, b->end, 16));
    for (v = 0; v < V_N; ++v) best[v] = 1e30;
    for (t = 0; t < TRIALS; ++t)
        for (v = 0; v < V_N; ++v) {
            const double t0 = wall_seconds();
            for (r = 0; r < repeat; ++r) run(w, b, &h, v % 3 == 2 ? &half : &full, pf_full, pf_half, (variant)v);
            if (wall_seconds() - t0 < best[v]) best[v] = wall_seconds() - t0;
        }
    printf("particles %d, dim %d, slots per particle: full %.1f, half %.1f (lane padding included)\n", b->end - b->begin, w->dim,
           (double)slots_full / (b->end - b->begin), (double)slots_half / (b->end - b->begin));
    for (v = 0; v < V_N; ++v)
        printf("%-20s %8.1f ns/particle\n", variant_name[v], 1e9 * best[v] / repeat / (b->end - b->begin));
    printf("RESULT case=pair_once scene=%s owner=%s particles=%d slots_full=%.1f slots_half=%.1f pressure_half_over_library=%.3f continuity_half_over_library=%.3f "
           "pressure_full_over_library=%.3f continuity_full_over_library=%.3f\n",
           scene == 0 ? "plate2d" : "cube", balanced ? "balanced" : "ordered", b->end - b->begin,
           (double)slots_full / (b->end - b->begin), (double)slots_half / (b->end - b->begin), best[V_HALF_PRESSURE] / best[V_LIB_PRESSURE],
           best[V_HALF_CONTINUITY] / best[V_LIB_CONTINUITY], best[V_FULL_PRESSURE] / best[V_LIB_PRESSURE],
           best[V_FULL_CONTINUITY] / best[V_LIB_CONTINUITY]);
    sps_world_destroy(w);
    return 0;
}
