/* still_water - a tank of water at rest, left alone: does it stay still?

   Water H = 0.5 m deep (depth/dp = --res layers) in a tank --width wide (2D; 3D: --width by
   --breadth), open top, free-slip walls: analytic walls (--walls analytic) or a rigid wall body
   three layers thick (--walls body). c0 = --mach-factor sqrt(g H) (10 by default), started on the
   lattice at its hydrostatic pressure with no velocity. Every --sample seconds it reads the
   water's particle speeds; for each second it keeps the RMS over the samples and particles and
   the largest speed, in units of sqrt(g H). From --from s on (5) it prints the worst second of
   each, the mean pressure at the floor (the bottom layer's pressure plus rho0 g y) against
   rho0 g H, how flat the free surface is (the spread of the top particles of the columns 2 dp wide, in dp) and
   the water's mass inside the tank. Targets: RMS <= 2e-4, largest <= 1e-3 sqrt(g H), floor
   within 1 %, surface within dp/5, mass constant (bench/VALIDATION.md, "Still water").

   Usage: ./build/still_water [--dim 2] [--res 25] [--width 1] [--breadth 0.25] [--walls analytic|body]
          [--tend 60] [--from 5] [--sample 0.05] [--mach-factor 10] [--viscosity 0] [--h-over-dp 2] [--cfl 0.4] [--threads 1]
          [--csv FILE] */
#define SPHSOLID_IMPLEMENTATION
#include "../examples/common.h"

#define G_ACC 9.81
#define RHO0 1000.0
#define DEPTH 0.5
#define WALL_LAYERS 3

static double surface; /* the water's height: whole layers of dp */

static sps_real hydrostatic(const sps_real x[3], void* user) {
    const int up = *(const int*)user;
    return (sps_real)(RHO0 * G_ACC * (surface - (double)x[up]));
}

static void print_log(int level, const char* message, void* user) {
    (void)level;
    (void)user;
    printf("# %s\n", message);
}

typedef struct {
    double rms2_sum, max_speed;
    int samples;
} second_bin;

/* The tank's walls: analytic half-planes, or a rigid body of WALL_LAYERS layers round the
   water's box (floor and sides up to twice the depth). */
static int add_tank(sps_world* w, int dim, int as_body, const double size[3], double dp) {
    const int up = dim - 1;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    int a, side;
    for (a = 0; a < dim; ++a) hi[a] = (sps_real)size[a];
    hi[up] = (sps_real)(4 * DEPTH);
    if (!as_body) return sps_world_add_box_walls(w, lo, hi, up == 1 ? SPS_FACE_Y_HI : SPS_FACE_Z_HI, SPS_WALL_FREE_SLIP) == SPS_OK;
    {
        sps_body_def td = sps_default_body_def();
        sps_body tank;
        const double t = WALL_LAYERS * dp;
        td.name = "tank";
        td.material.kind = SPS_MATERIAL_RIGID;
        if (sps_world_add_body(w, &td, &tank) != SPS_OK) return 0;
        /* the floor under the whole footprint and its rim, then each side wall */
        for (a = 0; a < dim; ++a) { lo[a] = (sps_real)-t; hi[a] = (sps_real)(size[a] + t); }
        lo[up] = (sps_real)-t; hi[up] = 0;
        if (sps_body_add_box(w, tank, lo, hi, NULL) != SPS_OK) return 0;
        for (a = 0; a < up; ++a)
            for (side = 0; side < 2; ++side) {
                int b;
                for (b = 0; b < dim; ++b) { lo[b] = (sps_real)(b == a ? 0 : -t); hi[b] = (sps_real)(b == a ? 0 : size[b] + t); }
                /* the walls along axis a cover the corners; the other walls stop at the water */
                for (b = 0; b < a; ++b) { lo[b] = 0; hi[b] = (sps_real)size[b]; }
                lo[a] = (sps_real)(side ? size[a] : -t); hi[a] = (sps_real)(side ? size[a] + t : 0);
                lo[up] = 0; hi[up] = (sps_real)(2 * DEPTH);
                if (sps_body_add_box(w, tank, lo, hi, NULL) != SPS_OK) return 0;
            }
    }
    return 1;
}

int main(int argc, char** argv) {
    double res = 25, width = 1, breadth = 0.25, t_end = 60, from = 5, sample = 0.05, mach_factor = 10, viscosity = 0, dimd = 2,
           threadsd = 1, h_over_dp = 2, cfl = 0.4;
    const char *walls = "analytic", *csv_path = NULL;
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body water;
    second_bin* bins;
    FILE* csv = NULL;
    double size[3], dp, c0, u_ref, worst_rms = 0, worst_max = 0, floor_err = 0, flat = 0, mass0 = -1, mass_err = 0, wall0 = wall_seconds();
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    int a, dim, up, nbins, k, as_body, samples_total, first, count, components;
    for (a = 1; a + 1 < argc; a += 2) {
        double* opt = !strcmp(argv[a], "--res") ? &res : !strcmp(argv[a], "--width") ? &width : !strcmp(argv[a], "--breadth") ? &breadth
                    : !strcmp(argv[a], "--tend") ? &t_end : !strcmp(argv[a], "--from") ? &from : !strcmp(argv[a], "--sample") ? &sample
                    : !strcmp(argv[a], "--mach-factor") ? &mach_factor : !strcmp(argv[a], "--viscosity") ? &viscosity
                    : !strcmp(argv[a], "--dim") ? &dimd : !strcmp(argv[a], "--threads") ? &threadsd
                    : !strcmp(argv[a], "--h-over-dp") ? &h_over_dp : !strcmp(argv[a], "--cfl") ? &cfl : NULL;
        if (!strcmp(argv[a], "--walls")) { walls = argv[a + 1]; continue; }
        if (!strcmp(argv[a], "--csv")) { csv_path = argv[a + 1]; continue; }
        if (!opt) break;
        *opt = atof(argv[a + 1]);
    }
    dim = (int)dimd;
    as_body = !strcmp(walls, "body");
    if (a < argc || (dim != 2 && dim != 3) || !(res >= 4 && res <= 400) || !(width > 0.1) || !(breadth > 0.05) || !(t_end > 0)
        || !(sample > 0) || !(from >= 0) || !(mach_factor > 0) || !(viscosity >= 0) || !(h_over_dp >= 1 && h_over_dp <= 3) || !(cfl > 0 && cfl <= 1) || (!as_body && strcmp(walls, "analytic"))) {
        fprintf(stderr, "usage: %s [--dim 2|3] [--res 25] [--width 1] [--breadth 0.25] [--walls analytic|body] [--tend 60] [--from 5] "
                        "[--sample 0.05] [--mach-factor 10] [--viscosity 0] [--h-over-dp 2] [--cfl 0.4] [--threads 1] [--csv FILE]\n", argv[0]);
        return 2;
    }
    up = dim - 1;
    dp = DEPTH / res;
    surface = floor(res + 1e-9) * dp;
    u_ref = sqrt(G_ACC * surface);
    c0 = mach_factor * u_ref;
    size[0] = width; size[1] = dim == 3 ? breadth : surface; size[2] = surface;
    size[up] = surface;
    nbins = (int)ceil(t_end - 1e-9);
    bins = (second_bin*)calloc((size_t)nbins, sizeof *bins);
    wd.h_over_dp = (sps_real)h_over_dp;
    wd.cfl_acoustic = (sps_real)cfl;
    wd.dim = dim;
    wd.dp = (sps_real)dp;
    wd.threads = (int)threadsd;
    wd.gravity[up] = (sps_real)-G_ACC;
    wd.log = print_log;
    if (!bins || sps_world_create(&wd, &w) != SPS_OK) return 1;
    bd.name = "water";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.density = (sps_real)RHO0;
    bd.material.fluid.sound_speed = (sps_real)c0;
    bd.material.viscosity = (sps_real)viscosity;
    for (k = 0; k < dim; ++k) hi[k] = (sps_real)size[k];
    if (!add_tank(w, dim, as_body, size, dp) || sps_world_add_body(w, &bd, &water) != SPS_OK || sps_body_add_box(w, water, lo, hi, NULL) != SPS_OK
        || sps_body_set_pressure(w, water, hydrostatic, &up) != SPS_OK) {
        fprintf(stderr, "%s\n", sps_world_last_error(w));
        return 1;
    }
    if (csv_path && !(csv = fopen(csv_path, "w"))) { fprintf(stderr, "cannot write %s\n", csv_path); return 1; }
    if (csv) fprintf(csv, "t,rms_speed,max_speed,floor_pressure_ratio,surface_spread_dp,mass_ratio\n");
    printf("# still water: %dD, depth %.3g m = %d dp (dp %g), width %g%s, %s walls, c0 %.4g m/s = %g sqrt(g H), viscosity %g Pa s, h/dp %g\n", dim,
           surface, (int)floor(res + 1e-9), dp, width, dim == 3 ? " x breadth" : "", walls, c0, mach_factor, viscosity, h_over_dp);
    printf("# second  rms/sqrt(gH)  max/sqrt(gH)  floor p/(rho0 g H)  surface spread/dp  mass ratio\n");
    samples_total = (int)floor(t_end / sample + 1e-9);
    for (k = 1; k <= samples_total; ++k) {
        const double t = k * sample;
        const sps_real *v[3], *x[3], *p, *m;
        double rms2 = 0, vmax = 0, floor_sum = 0, mass = 0, top_lo = 1e30, top_hi = -1e30;
        int i, nfloor = 0, bin;
        static double tops[4096];
        int ncols = (int)floor(width / (2 * dp)); /* columns 2 dp wide: each holds a particle of the top row on either lattice */
        if (sps_world_advance(w, (sps_real)t, NULL, NULL) != SPS_OK) {
            printf("# stopped at %.3f s: %s\n", t, sps_world_last_error(w));
            break;
        }
        for (a = 0; a < 3; ++a) {
            v[a] = sps_world_field(w, (sps_field)(SPS_FIELD_VELOCITY_X + a));
            x[a] = sps_world_field(w, (sps_field)(SPS_FIELD_POSITION_X + a));
        }
        p = sps_world_field(w, SPS_FIELD_PRESSURE);
        m = sps_world_field(w, SPS_FIELD_MASS);
        sps_body_field(w, water, "density", &components, &first, &count);
        for (i = 0; i < ncols && i < 4096; ++i) tops[i] = -1e30;
        for (i = first; i < first + count; ++i) {
            double s2 = 0, inside = 1;
            int col;
            for (a = 0; a < dim; ++a) {
                s2 += (double)v[a][i] * v[a][i];
                if (a != up && (x[a][i] < 0 || x[a][i] > size[a])) inside = 0;
            }
            if (x[up][i] < 0) inside = 0;
            rms2 += s2;
            if (s2 > vmax * vmax) vmax = sqrt(s2);
            mass += inside * m[i];
            if (x[up][i] < dp) { floor_sum += p[i] + RHO0 * G_ACC * x[up][i]; ++nfloor; }
            col = (int)floor(x[0][i] / (2 * dp));
            if (col >= 0 && col < ncols && col < 4096 && x[up][i] > tops[col]) tops[col] = x[up][i];
        }
        for (i = 1; i + 1 < ncols && i < 4096; ++i) /* the columns beside the side walls excluded */
            if (tops[i] > -1e29) { if (tops[i] < top_lo) top_lo = tops[i]; if (tops[i] > top_hi) top_hi = tops[i]; }
        rms2 /= count;
        bin = (int)ceil(t - 1e-9) - 1;
        if (bin >= nbins) bin = nbins - 1;
        bins[bin].rms2_sum += rms2;
        bins[bin].max_speed = vmax > bins[bin].max_speed ? vmax : bins[bin].max_speed;
        bins[bin].samples++;
        if (mass0 < 0) mass0 = mass;
        {
            const double floor_ratio = nfloor ? floor_sum / nfloor / (RHO0 * G_ACC * surface) : 0, spread = (top_hi - top_lo) / dp;
            if (csv) fprintf(csv, "%.4f,%.6e,%.6e,%.6f,%.4f,%.8f\n", t, sqrt(rms2) / u_ref, vmax / u_ref, floor_ratio, spread, mass / mass0);
            if (t >= from - 1e-9) {
                if (fabs(floor_ratio - 1) > floor_err) floor_err = fabs(floor_ratio - 1);
                if (spread > flat) flat = spread;
                if (fabs(mass / mass0 - 1) > mass_err) mass_err = fabs(mass / mass0 - 1);
            }
            if (fabs(t - (bin + 1)) < 0.5 * sample) {
                const double brms = sqrt(bins[bin].rms2_sum / bins[bin].samples) / u_ref, bmax = bins[bin].max_speed / u_ref;
                printf("%6d  %12.3e  %12.3e  %18.5f  %17.3f  %.8f\n", bin + 1, brms, bmax, floor_ratio, spread, mass / mass0);
                fflush(stdout);
                if (bin + 1 > from + 1e-9) {
                    if (brms > worst_rms) worst_rms = brms;
                    if (bmax > worst_max) worst_max = bmax;
                }
            }
        }
    }
    printf("RESULT case=still_water dim=%d res=%g width=%g walls=%s c0=%.4g viscosity=%g particles=%d t_end=%g from=%g "
           "worst_rms=%.3e (target 2e-4) worst_max=%.3e (target 1e-3) floor_err=%.3f%% (target 1%%) surface_spread=%.3f dp (target 0.2) "
           "mass_err=%.2e h_over_dp=%g cfl=%g steps=%ld wall_s=%.1f\n", dim, res, width, walls, c0, viscosity, count, t_end, from, worst_rms, worst_max,
           100 * floor_err, flat, mass_err, h_over_dp, cfl, sps_world_substep_count(w), wall_seconds() - wall0);
    if (csv) fclose(csv);
    free(bins);
    sps_world_destroy(w);
    return 0;
}
