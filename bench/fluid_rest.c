/* fluid_rest - water at rest in a tank of analytic walls over tens of seconds: does it stay at rest?

   Water --depth deep (rounded down to whole layers of --dp) in a tank --width wide (free-slip
   walls, open top), c0 = 10 sqrt(2 g 0.5), started hydrostatic, inviscid, one thread. Every
   --every seconds it prints the mean pressure c0^2 (mean rho - rho0) next to the column's
   rho0 g H / 2, the mid-depth pressure next to rho0 g (H - y) at the particles' mean height y,
   the top layer's pressure (rho0 g dp/2 at rest), the top particle's height and the largest
   speed; at the end the drift rates per second from --from s on (least squares): water at rest
   has them 0. bench/VALIDATION.md, "Fluid at rest over long times".
   The lattice's shear mode (bench/VALIDATION.md, "Water left running"): --rows N prints at
   every sample the mean horizontal velocity of each of the N lowest rows of particles (the
   square lattice's rows slide in alternate directions, from round-off); --periodic 1 makes x
   periodic (no side walls); --lattice 0|1|2 is the water's body def lattice (sps_lattice:
   auto, hexagonal here; square; hexagonal).

   Usage: ./build/fluid_rest [--dp 0.04] [--width 1] [--depth 0.5] [--tend 20] [--every 1] [--from 2]
                             [--rows 0] [--periodic 0] [--lattice 0] */
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define G_ACC 9.81
#define RHO0 1000.0

static double surface; /* the water's height: whole layers of dp */

static sps_real hydrostatic(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(RHO0 * G_ACC * (surface - (double)x[1]));
}

static void print_log(int level, const char* message, void* user) {
    (void)level;
    (void)user;
    printf("# %s\n", message);
}

/* Prints the mean horizontal velocity of each of the lowest `rows` rows of particles. */
static void print_rows(const sps_world* w, double dp, int rows) {
    const sps_real *vx = sps_world_field(w, SPS_FIELD_VELOCITY_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    double sum[64] = {0};
    int count[64] = {0}, i, r, n = sps_world_particle_count(w);
    for (i = 0; i < n; ++i) {
        r = (int)(y[i] / dp);
        if (r >= 0 && r < rows) { sum[r] += vx[i]; count[r]++; }
    }
    printf("# mean vx of rows 0..%d [m/s]:", rows - 1);
    for (r = 0; r < rows; ++r) printf(" %+.2e", count[r] ? sum[r] / count[r] : 0.0);
    printf("\n");
}

/* Least-squares slope of y over x, n samples. */
static double slope(const double* x, const double* y, int n) {
    double mx = 0, my = 0, sxy = 0, sxx = 0;
    int k;
    for (k = 0; k < n; ++k) { mx += x[k] / n; my += y[k] / n; }
    for (k = 0; k < n; ++k) { sxy += (x[k] - mx) * (y[k] - my); sxx += (x[k] - mx) * (x[k] - mx); }
    return sxx > 0 ? sxy / sxx : 0;
}

int main(int argc, char** argv) {
    double dp = 0.04, width = 1, depth = 0.5, t_end = 20, every = 1, from = 2, rows = 0, periodic = 0, lattice = 0;
    double times[1024], p_means[1024], p_mids[1024], p_tops[1024], tops[1024];
    const double c0 = 10 * sqrt(2 * G_ACC * 0.5);
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body water, all = {0};
    sps_real lo[3] = {0, 0, 0}, hi[3], tank_hi[3];
    int k, samples = 0, a;
    for (a = 1; a + 1 < argc; a += 2) {
        double* opt = !strcmp(argv[a], "--dp") ? &dp : !strcmp(argv[a], "--width") ? &width : !strcmp(argv[a], "--depth") ? &depth
                    : !strcmp(argv[a], "--tend") ? &t_end : !strcmp(argv[a], "--every") ? &every : !strcmp(argv[a], "--from") ? &from
                    : !strcmp(argv[a], "--rows") ? &rows : !strcmp(argv[a], "--periodic") ? &periodic : !strcmp(argv[a], "--lattice") ? &lattice : NULL;
        if (!opt) break;
        *opt = atof(argv[a + 1]);
    }
    if (a < argc || !(dp > 0) || !(width > 2 * dp) || !(depth > 2 * dp) || !(t_end > 0) || !(every > 0) || t_end / every > 1000 || !(rows >= 0) ||
        rows > 64 || !(lattice == 0 || lattice == 1 || lattice == 2)) {
        fprintf(stderr, "usage: %s [--dp 0.04] [--width 1] [--depth 0.5] [--tend 20] [--every 1] [--from 2] [--rows 0..64] [--periodic 0|1] "
                "[--lattice 0|1|2] (tend/every <= 1000)\n", argv[0]);
        return 2;
    }
    surface = floor(depth / dp + 1e-9) * dp;
    hi[0] = tank_hi[0] = (sps_real)width;
    hi[1] = (sps_real)surface;
    tank_hi[1] = (sps_real)(4 * depth);
    hi[2] = tank_hi[2] = 0;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.threads = 1;
    wd.gravity[1] = (sps_real)-G_ACC;
    if (periodic != 0) wd.periodic[0] = (sps_real)width; /* x repeats: the side walls left out below */
    wd.log = print_log;
    if (sps_world_create(&wd, &w) != SPS_OK) return 1;
    bd.name = "water";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.density = (sps_real)RHO0;
    bd.material.fluid.sound_speed = (sps_real)c0;
    bd.lattice = (sps_lattice)lattice;
    if (sps_world_add_box_walls(w, lo, tank_hi, SPS_FACE_Y_HI | (periodic != 0 ? SPS_FACE_X_LO | SPS_FACE_X_HI : 0), SPS_WALL_FREE_SLIP) != SPS_OK ||
        sps_world_add_body(w, &bd, &water) != SPS_OK ||
        sps_body_add_box(w, water, lo, hi, NULL) != SPS_OK ||
        sps_body_set_pressure(w, water, hydrostatic, NULL) != SPS_OK) {
        fprintf(stderr, "%s\n", sps_world_last_error(w));
        return 1;
    }
    printf("# water %.3g m deep (%d layers of dp %g), tank %g m wide, c0 %.4g m/s; column's mean pressure %.1f Pa\n", surface,
           (int)floor(surface / dp + 0.5), dp, width, c0, RHO0 * G_ACC * surface / 2);
    printf("# t [s]  mean p [Pa]  mid p [Pa]  rho0 g (H - y_mid)  top layer p [Pa]  top y [m]  max speed [m/s]\n");
    for (k = 1; k * every <= t_end + 1e-9; ++k) {
        const sps_real *y, *p, *rho;
        double rho_sum = 0, p_mid = 0, y_mid = 0, p_top = 0, top = -1e30;
        int i, n, mid = 0, layer = 0;
        sps_diagnostics d;
        if (sps_world_advance(w, (sps_real)(k * every), NULL, NULL) != SPS_OK) {
            printf("# stopped: %s\n", sps_world_last_error(w));
            break;
        }
        y = sps_world_field(w, SPS_FIELD_POSITION_Y);
        p = sps_world_field(w, SPS_FIELD_PRESSURE);
        rho = sps_world_field(w, SPS_FIELD_DENSITY);
        n = sps_world_particle_count(w);
        for (i = 0; i < n; ++i) {
            rho_sum += rho[i];
            if (y[i] > top) top = y[i];
            if (fabs(y[i] - surface / 2) < dp / 2) { p_mid += p[i]; y_mid += y[i]; ++mid; }
        }
        for (i = 0; i < n; ++i)
            if (y[i] > top - dp / 2) { p_top += p[i]; ++layer; }
        p_mid /= mid > 0 ? mid : 1;
        y_mid /= mid > 0 ? mid : 1;
        sps_world_diagnostics(w, all, &d);
        times[samples] = k * every;
        p_means[samples] = c0 * c0 * (rho_sum / n - RHO0);
        p_mids[samples] = p_mid;
        p_tops[samples] = p_top / layer;
        tops[samples] = top;
        printf("%7.2f  %10.1f  %10.1f  %10.1f  %10.1f  %9.4f  %9.3g\n", times[samples], p_means[samples], p_mid,
               RHO0 * G_ACC * (surface - y_mid), p_tops[samples], top, (double)d.max_speed);
        ++samples;
        if (rows > 0) print_rows(w, dp, (int)rows);
    }
    for (k = 0; k < samples && times[k] < from - 1e-9; ++k) continue;
    printf("RESULT case=fluid_rest dp=%g width=%g depth=%g t_end=%g from=%g mean_p_rate=%.3g mid_p_rate=%.3g top_p_rate=%.3g "
           "level_rate=%.3g (Pa/s, Pa/s, Pa/s, m/s; at rest: 0) mean_p_end=%.1f column_mean_p=%.1f\n", dp, width, surface, t_end, from,
           slope(times + k, p_means + k, samples - k), slope(times + k, p_mids + k, samples - k), slope(times + k, p_tops + k, samples - k),
           slope(times + k, tops + k, samples - k), samples ? p_means[samples - 1] : 0.0, RHO0 * G_ACC * surface / 2);
    sps_world_destroy(w);
    return 0;
}
