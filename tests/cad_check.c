/* cad_check.c - a part exported by a CAD tool, read by sps_mesh_load: its volume against the one
   admesh computes from the same file, and filled at 20 particles across its smallest feature,
   the particles' volume against the mesh's (tests/cad_check.sh makes the files).

   Usage: cad_check FILE.stl ADMESH_VOLUME_MM3 SMALLEST_FEATURE_MM
   Prints a RESULT line; the exit status is 0 iff both figures hold. */
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static void quiet_log(int level, const char* message, void* user) { (void)level; (void)message; (void)user; }

int main(int argc, char** argv) {
    sps_mesh_def md = sps_default_mesh_def();
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_mesh* m;
    sps_mesh_info info;
    sps_world* w;
    sps_body b;
    char msg[512];
    double admesh, feature, volume, particles, dp;
    int n, ok;
    if (argc != 4) { fprintf(stderr, "usage: cad_check FILE.stl ADMESH_VOLUME_MM3 SMALLEST_FEATURE_MM\n"); return 2; }
    admesh = 1e-9 * atof(argv[2]); /* mm^3 -> m^3 */
    feature = 1e-3 * atof(argv[3]);
    md.scale = (sps_real)0.001; /* the part is drawn in millimetres */
    if (sps_mesh_load(argv[1], &md, &m, msg, sizeof msg) != SPS_OK) { printf("cad_check: %s\n", msg); return 1; }
    info = sps_mesh_get_info(m);
    volume = (double)info.volume;
    dp = feature / 20;
    wd.dim = 3; wd.dp = (sps_real)dp; wd.log = quiet_log;
    if (sps_world_create(&wd, &w) != SPS_OK || sps_world_add_body(w, &bd, &b) != SPS_OK || sps_body_add_mesh(w, b, m, NULL, NULL, -1, &n) != SPS_OK) {
        printf("cad_check: %s\n", sps_world_last_error(w));
        return 1;
    }
    particles = n * dp * dp * dp;
    /* targets: the mesh's volume within 1e-6 of admesh's (it reads the same numbers, in float);
       the lattice's volume within 2 % at 20 particles across the smallest feature */
    ok = fabs(volume / admesh - 1) <= 1e-6 && fabs(particles / volume - 1) <= 0.02;
    printf("RESULT case=cad_check file=%s triangles=%d closed=%d oriented=%d volume_m3=%.9g admesh_m3=%.9g volume_rel=%.2e dp=%g particles=%d "
           "particles_rel=%+.3f%% %s\n",
           argv[1], info.elements, info.closed, info.oriented, volume, admesh, volume / admesh - 1, dp, n, 100 * (particles / volume - 1),
           ok ? "ok" : "FAILED");
    sps_world_destroy(w);
    sps_mesh_destroy(m);
    return ok ? 0 : 1;
}
