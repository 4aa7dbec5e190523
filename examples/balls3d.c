/* balls3d.c - 3D colliding hollow rubber balls, benchmark A6 (ENO 6.4).

   Two shells (inner radius 0.03, outer 0.04; rho0 1200, E 1e7, nu 0.4), centres 0.09 apart,
   move towards each other at v0 = 0.08 c0 each and collide through the library's contact.
   The left ball is filled in a scratch world with sps_body_add_sdf_relaxed (--fill relaxed,
   the paper's body-fitted start) or a lattice; the right ball is its mirror image, so that the
   two are identical by symmetry. The
   paper (dp = 0.001) shows snapshots at t = 0.001 .. 0.007 (Fig. 20) and no numbers: smooth von
   Mises stress, uniform particles. We report the kinetic energy of each ball (its minimum and
   when), the total energy at start and end and its largest rise, the left/right difference,
   the smallest distance between the balls' particles, the hourglass indicator, the smallest
   spacing, the linear momentum of the pair (0 in theory) and the wall time per simulated
   microsecond. CSV: per-ball kinetic, strain and total energy and the gap over time.

   Build: make examples     Run: ./build/balls3d --dp 0.0025
   Expect: energy within 1 % (no rise), identical balls, gap above 0.5 dp, momentum ~ 0.
   Smoke: balls3d --dp 0.008 --tend 0.0002 --iterations 50 */
#include "common.h"

#define CASE "balls3d"
#define BALLS3D_R_IN 0.03
#define BALLS3D_R_OUT 0.04
#define BALLS3D_GAP 0.09 /* centre distance */
#define BALLS3D_RHO0 1200
#define BALLS3D_E 1e7
#define BALLS3D_NU 0.4

/* Signed distance of the shell centred at (cx, 0, 0) (user: &cx): negative inside the wall. */
static sps_real balls3d_shell_sdf(const sps_real x[3], void* user) {
    double cx = *(const double*)user, dx = x[0] - cx, r = sqrt(dx * dx + x[1] * x[1] + x[2] * x[2]);
    return (sps_real)fmax(r - BALLS3D_R_OUT, BALLS3D_R_IN - r);
}

/* Each ball's velocity (v, 0, 0), v [m/s] the user pointer. */
static void balls3d_velocity(const sps_real x[3], sps_real v[3], void* user) {
    (void)x;
    v[0] = (sps_real)*(const double*)user;
    v[1] = v[2] = 0;
}

/* The left ball's particles (*n points x y z, malloc'ed), filled in a scratch world of wd and bd:
   the lattice cut by the shell, or relaxed to a body-fitted distribution (the paper's Yu et al.
   fill); their quality, and the fill's wall time. */
static sps_real* left_ball_points(const sps_world_def* wd, const sps_body_def* bd, double dp, int relaxed, int iterations, int* n,
                                  sps_fill_quality* quality, double* fill_s) {
    double cx = -BALLS3D_GAP / 2, m = 2.5 * dp;
    sps_real lo[3] = {cx - BALLS3D_R_OUT - m, -BALLS3D_R_OUT - m, -BALLS3D_R_OUT - m};
    sps_real hi[3] = {cx + BALLS3D_R_OUT + m, BALLS3D_R_OUT + m, BALLS3D_R_OUT + m};
    const double t0 = wall_seconds();
    sps_world* scratch;
    sps_body ball;
    const sps_real* f[3];
    sps_real* xyz;
    int i, a;
    sps_world_create(wd, &scratch);
    sps_world_add_body(scratch, bd, &ball);
    if (relaxed) sps_body_add_sdf_relaxed(scratch, ball, lo, hi, balls3d_shell_sdf, &cx, iterations, n);
    else sps_body_add_sdf(scratch, ball, lo, hi, balls3d_shell_sdf, &cx, n);
    *n = sps_world_particle_count(scratch);
    f[0] = sps_world_field(scratch, SPS_FIELD_POSITION_X);
    f[1] = sps_world_field(scratch, SPS_FIELD_POSITION_Y);
    f[2] = sps_world_field(scratch, SPS_FIELD_POSITION_Z);
    if (!(xyz = (sps_real*)malloc(sizeof(sps_real) * 3 * (size_t)*n))) { fprintf(stderr, "%s: out of memory\n", g_prog); exit(2); }
    for (i = 0; i < *n; ++i)
        for (a = 0; a < 3; ++a) xyz[3 * i + a] = f[a][i];
    *fill_s = wall_seconds() - t0;
    sps_measure_fill(scratch, *n, xyz, lo, hi, balls3d_shell_sdf, &cx, quality);
    sps_world_destroy(scratch);
    return xyz;
}

/* Smallest distance between a particle of body a and one of body b (current positions), / dp.
   Only particles within 3 dp (in x) of the other body's x range are compared. After the first
   step (sps_body_field). Returns a large value when nothing is close. */
static double balls3d_min_gap(const sps_world* w, sps_body a, sps_body b) {
    const double dp = sps_world_get_def(w)->dp;
    const sps_real *ax, *ay, *az, *bx, *by, *bz;
    int na, nb, i, j, *ia, *ib, ka = 0, kb = 0;
    double amax = -1e30, bmin = 1e30, best = 1e30;
    ax = sps_body_field(w, a, "position_x", NULL, NULL, &na);
    ay = sps_body_field(w, a, "position_y", NULL, NULL, NULL);
    az = sps_body_field(w, a, "position_z", NULL, NULL, NULL);
    bx = sps_body_field(w, b, "position_x", NULL, NULL, &nb);
    by = sps_body_field(w, b, "position_y", NULL, NULL, NULL);
    bz = sps_body_field(w, b, "position_z", NULL, NULL, NULL);
    if (!ax || !bx || !ay || !by || !az || !bz) return -1;
    for (i = 0; i < na; ++i) amax = fmax(amax, ax[i]);
    for (j = 0; j < nb; ++j) bmin = fmin(bmin, bx[j]);
    if (bmin - amax > 3 * dp) return (bmin - amax) / dp;
    ia = (int*)malloc(sizeof(int) * (size_t)na);
    ib = (int*)malloc(sizeof(int) * (size_t)nb);
    if (!ia || !ib) { free(ia); free(ib); return -1; }
    for (i = 0; i < na; ++i) if (ax[i] > bmin - 3 * dp) ia[ka++] = i;
    for (j = 0; j < nb; ++j) if (bx[j] < amax + 3 * dp) ib[kb++] = j;
    for (i = 0; i < ka; ++i)
        for (j = 0; j < kb; ++j) {
            double dx = ax[ia[i]] - bx[ib[j]], dy = ay[ia[i]] - by[ib[j]], dz = az[ia[i]] - bz[ib[j]];
            double r2 = dx * dx + dy * dy + dz * dz;
            if (r2 < best) best = r2;
        }
    free(ia);
    free(ib);
    return sqrt(best) / dp;
}

static double norm3(const sps_real* a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

int main(int argc, char** argv) {
    double dp = 0.0025, v0_c0 = 0.08, fill_s, speed_left, speed_right;
    int iterations = 0, per_ball, i;
    sps_fill_quality quality;
    sps_real* xyz;
    int fill = 0; /* choice index: relaxed|lattice */
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 0.007, .vtk_every = 0.001, .csv_every = 0.00005,
                        .E = BALLS3D_E, .nu = BALLS3D_NU, .rho0 = BALLS3D_RHO0, .out = "out/" CASE, .jitter = 0, .seed = 1,
                        .contact_rest = SPS_CONTACT_REST_KERNEL /* the papers' contact law */, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (paper: 0.001)", 2e-4, 0.01, NULL},
        {"v0", OPT_REAL, &v0_c0, "speed of each ball / c0", 0, 1, NULL},
        {"fill", OPT_CHOICE, &fill, "particles of the shells", 0, 0, "relaxed|lattice"},
        {"iterations", OPT_INT, &iterations, "relaxation steps, 0 = the library's default (300)", 0, 100000, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body left, right, all = {0};
    sps_diagnostics dl, dr, da, dl0, dr0, da0;
    output_plan output;
    double wall, e0, e_end = 0, e_max, ke_min = 1e300, t_ke_min = 0, lr_max = 0, ke_lr_max = 0, gap_min = 1e30, t_gap = 0;
    double p_scale, p_max = 0, c0;
    int k = 0;
    sps_real c0r;

    ex_options(argc, argv, "3D colliding hollow rubber balls (benchmark A6, ENO 6.4)", opts, &c, &wd, &bd);
    if (c.shear == SPS_SHEAR_OAS) opt_fail(argv[0], "--shear %s: %s", "oas", "is 2D only");
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (ex_check_step) */
    wd.dim = 3;
    wd.dp = (sps_real)dp;
    xyz = left_ball_points(&wd, &bd, dp, fill == 0, iterations, &per_ball, &quality, &fill_s);
    sps_world_create(&wd, &w);
    bd.name = "left";
    sps_world_add_body(w, &bd, &left);
    sps_body_add_particles(w, left, per_ball, xyz, NULL);
    for (i = 0; i < per_ball; ++i) xyz[3 * i] = -xyz[3 * i]; /* the right ball: the left one's mirror image x -> -x */
    bd.name = "right";
    sps_world_add_body(w, &bd, &right);
    sps_body_add_particles(w, right, per_ball, xyz, NULL);
    free(xyz);
    sps_body_material_constants(w, left, &c0r, NULL, NULL);
    c0 = c0r;
    speed_left = v0_c0 * c0r; /* towards each other */
    speed_right = -speed_left;
    sps_body_set_velocity(w, left, balls3d_velocity, &speed_left);
    sps_body_set_velocity(w, right, balls3d_velocity, &speed_right);

    output_open(&output, &c, CASE, "von-mises-or-velocity",
                ",kinetic_left,kinetic_right,strain_left,strain_right,total_left,total_right,gap_dp");
    sps_world_diagnostics(w, left, &dl0);
    sps_world_diagnostics(w, right, &dr0);
    sps_world_diagnostics(w, all, &da0);
    e0 = da0.kinetic_energy + da0.strain_energy;
    e_max = e0;
    p_scale = 2 * dl0.linear_momentum[0]; /* sum m |v| */
    for (;;) {
        double t = sps_world_time(w), el, er, gap = sps_world_time(w) > 0 ? balls3d_min_gap(w, left, right) : -1;
        char extra[256];
        sps_world_diagnostics(w, left, &dl);
        sps_world_diagnostics(w, right, &dr);
        sps_world_diagnostics(w, all, &da);
        el = dl.kinetic_energy + dl.strain_energy;
        er = dr.kinetic_energy + dr.strain_energy;
        if (dl.kinetic_energy < ke_min) { ke_min = dl.kinetic_energy; t_ke_min = t; }
        e_end = da.kinetic_energy + da.strain_energy;
        if (e_end > e_max) e_max = e_end;
        lr_max = fmax(lr_max, fabs(el - er) / (dl0.kinetic_energy + dl0.strain_energy));
        ke_lr_max = fmax(ke_lr_max, fabs(dl.kinetic_energy - dr.kinetic_energy) / dl0.kinetic_energy);
        p_max = fmax(p_max, norm3(da.linear_momentum) / p_scale);
        if (gap >= 0 && gap < gap_min) { gap_min = gap; t_gap = t; }
        snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.5g", (double)dl.kinetic_energy, (double)dr.kinetic_energy,
                 (double)dl.strain_energy, (double)dr.strain_energy, el, er, gap);
        output_tick(w, &output, extra, &da);
        if (t >= (sps_real)c.t_end) break; /* the world's clock is an sps_real: a float 2e-4 is below the double */
        ex_check_step(w, sps_world_advance(w, (sps_real)fmin(++k * c.csv_every, c.t_end), NULL, NULL), &output); /* to the next CSV row */
    }
    wall = output_close(w, &output);
    printf("RESULT case=%s shear=%s dp=%g paper_dp=0.001 fill=%s v0=%g*c0 c0=%.4g per_ball=%d fill_s=%.2f fill_surface_rms=%.3f "
           "fill_density_spread=%.4f kinetic_start=%.6g kinetic_left_min=%.6g t_kinetic_min=%.5f kinetic_left_end=%.6g "
           "kinetic_right_end=%.6g total_start=%.6g total_end=%.6g total_change=%.3f%% total_max_rise=%.3f%% lr_energy_diff_max=%.2e "
           "lr_kinetic_diff_max=%.2e min_gap_dp=%.3f t_min_gap=%.5f linmom_max=%.2e hourglass_max=%.3g min_spacing=%.3f "
           "wall_per_us=%.4f paper=smooth_von_mises %s particles=%d steps=%ld wall_s=%.2f out=%s\n",
           CASE, shear_name(c.shear), dp, fill ? "lattice" : "relaxed", v0_c0, c0, per_ball, fill_s, (double)quality.surface_rms,
           (double)quality.density_spread, (double)dl0.kinetic_energy, ke_min, t_ke_min, (double)dl.kinetic_energy,
           (double)dr.kinetic_energy, e0, e_end, 100 * (e_end - e0) / e0, 100 * (e_max - e0) / e0, lr_max, ke_lr_max,
           gap_min, t_gap, p_max, output.hourglass_max, output.min_spacing, c.t_end > 0 ? wall / (c.t_end * 1e6) : 0,
           common_result_fields(&c), sps_world_particle_count(w), da.acoustic_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
