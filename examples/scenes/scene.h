/* scene.h - what the shared scenes (examples/scenes/: the ones the tests, the bench or the demo
   build too; an example's own scene is in its file) use: pi and the jittered lattice.
   Needs only sphsolid.h, so that the tests build their worlds with the examples' set-up code;
   every function returns an sps_result instead of ending the program. */
#ifndef SPS_SCENE_H
#define SPS_SCENE_H
#include <math.h>
#include <stdlib.h>
#include "../../sphsolid.h"

#define SCENE_PI 3.14159265358979323846

/* A program uses part of a scene's functions. */
#if defined(__GNUC__) || defined(__clang__)
#define SCENE_UNUSED __attribute__((unused))
#else
#define SCENE_UNUSED
#endif

/* Fills [lo, hi) of body b like sps_body_add_box (points lo + (i + 1/2) dp), each coordinate
   then moved by a uniform random amount in [-j/2, j/2] dp (splitmix64 from seed), so neighbours
   start at least (1 - j) dp apart along an axis. j = 0 is sps_body_add_box itself. */
SCENE_UNUSED static sps_result scene_add_box(sps_world* w, sps_body b, const sps_real lo[3], const sps_real hi[3], double j, int seed) {
    const sps_world_def* wd = sps_world_get_def(w);
    const double dp = wd->dp;
    int cnt[3] = {1, 1, 1}, a, i, k, l, n = 0;
    uint64_t rng = (uint64_t)seed;
    sps_real* xyz;
    sps_result r;
    if (j == 0) return sps_body_add_box(w, b, lo, hi, NULL);
    /* the library's lattice count (sps__fill), slack included: float rounding of lo, hi and dp */
    for (a = 0; a < wd->dim; ++a) cnt[a] = (int)floor((hi[a] - lo[a]) / dp + (sps_is_double() ? 1e-6 : 1e-3));
    if (!(xyz = (sps_real*)malloc(sizeof(sps_real) * 3 * (size_t)cnt[0] * cnt[1] * cnt[2]))) return SPS_ERR_OUT_OF_MEMORY;
    for (l = 0; l < cnt[2]; ++l)
        for (k = 0; k < cnt[1]; ++k)
            for (i = 0; i < cnt[0]; ++i, ++n) {
                int idx[3] = {i, k, l};
                for (a = 0; a < 3; ++a) {
                    uint64_t z = (rng += 0x9e3779b97f4a7c15ULL); /* splitmix64 */
                    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
                    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
                    z ^= z >> 31;
                    xyz[3 * n + a] = a < wd->dim ? lo[a] + (idx[a] + 0.5 + j * ((double)(z >> 11) / 9007199254740992.0 - 0.5)) * dp : 0;
                }
            }
    r = sps_body_add_particles(w, b, n, xyz, NULL);
    free(xyz);
    return r;
}

/* Ends a scene's set-up on the first error: destroys the half-built world (its message went to
   the world def's log) and returns the error. */
#define SCENE_TRY(w, call)                          \
    do {                                            \
        sps_result scene_r_ = (call);               \
        if (scene_r_ != SPS_OK) {                   \
            sps_world_destroy(*(w));                \
            *(w) = NULL;                            \
            return scene_r_;                        \
        }                                           \
    } while (0)

#endif
