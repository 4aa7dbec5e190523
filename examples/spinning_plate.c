/* spinning_plate.c - 2D spinning plate, BENCHMARKS.md A3 (ENO 6.10, ANG 5.1.3); compiled with
   SPINNING_CUBE defined it is the 3D spinning cube, A4 (ANG 5.1.4): see spinning_cube.c.

   A unit square (cube) centred at the origin, rho0 1100, E 1.7e7, nu 0.45 (cube: 0.3), starts
   in rigid rotation at omega = 50 rad/s about z with no constraint. Linear and angular momentum
   are exactly conserved in theory; we report the largest relative angular-momentum error
   over the run next to ANG Fig. 13 / 16, the drift of the linear momentum, the smallest pair
   distance (clustering) and the hourglass indicator. CSV: momenta, energies, and the
   displacement and velocity of the top-right corner.

   Build: make examples     Run: ./build/spinning_plate --shear gno-a
   Expect: max_angmom_err about 0.5 % for GNO-A, a few % for ENO-A, tens of % for ENO. */
#include "common.h"

#ifdef SPINNING_CUBE
#define CASE "spinning_cube"
#define DIM 3
#define NU 0.3
/* ANG 5.1.4, rows in sps_shear order (ENO, ENO-A, OG, OAS, GNO, GNO-A); -1: not in the paper */
static const double paper_error[6] = {-1, 2.67, -1, -1, -1, 1.18};
#else
#define CASE "spinning_plate"
#define DIM 2
#define NU 0.45
static const double paper_error[6] = {59.17, 2.58, -1, -1, 1.12, 0.55}; /* ANG Fig. 13 [%] */
#endif

static void rigid_rotation(const sps_real x[3], sps_real v[3], void* user) {
    double omega = *(const double*)user; /* v = omega e_z x r */
    v[0] = -omega * x[1];
    v[1] = omega * x[0];
    v[2] = 0;
}

static double norm3(const sps_real* a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

int main(int argc, char** argv) {
    int shear = SPS_SHEAR_GNO_A, rotation = 0, stepping = 0, geometry = 0, threads = 0, quiet = 0, corner_id;
    double dp = 0.05, omega = 50, t_end = 0.5, vtk_every = 0.1, csv_every = 0.001, cfl = 0.4, E = 1.7e7, nu = NU, rho0 = 1100;
    const char* out = "out/" CASE;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 1e-3, 0.25, NULL},
        {"omega", OPT_REAL, &omega, "angular velocity [rad/s]", 0, 1e4, NULL},
        {"shear", OPT_CHOICE, &shear, "shear formulation", 0, 0, SHEAR_CHOICES},
        {"rotation", OPT_CHOICE, &rotation, "-A rotation", 0, 0, "mean|particle"},
        {"stepping", OPT_CHOICE, &stepping, "time stepping", 0, 0, "dual|single"},
        {"geometry", OPT_CHOICE, &geometry, "pair geometry in sub-steps", 0, 0, "recomputed|frozen"},
        {"cfl", OPT_REAL, &cfl, "acoustic CFL number", 0.01, 1, NULL},
        {"E", OPT_REAL, &E, "Young's modulus [Pa]", 1e-3, 1e15, NULL},
        {"nu", OPT_REAL, &nu, "Poisson ratio", -0.99, 0.4999, NULL},
        {"rho0", OPT_REAL, &rho0, "density [kg/m^3]", 1e-6, 1e6, NULL},
        {"tend", OPT_REAL, &t_end, "end time [s]", 0, 1e4, NULL},
        {"out", OPT_STRING, &out, "output folder", 0, 0, NULL},
        {"vtk-every", OPT_REAL, &vtk_every, "VTK snapshot interval [s], 0 = none", 0, 1e4, NULL},
        {"csv-every", OPT_REAL, &csv_every, "CSV row interval [s]", 1e-6, 1e4, NULL},
        {"threads", OPT_INT, &threads, "OpenMP threads, 0 = all", 0, 1024, NULL},
        {"quiet", OPT_FLAG, &quiet, "no progress line", 0, 0, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    sps_body block;
    sps_diagnostics d0, d;
    sps_body all = {0};
    sps_real lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {0.5, 0.5, 0.5}, corner[3] = {0.5, 0.5, 0.5};
    double wall0, max_err = 0, max_p_drift = 0, p_scale = 0;
    int i, n;
    output_plan output;

    opt_parse(argc, argv, "spinning " CASE " (BENCHMARKS.md A3/A4)", opts, (int)(sizeof opts / sizeof *opts));
    wd.dim = DIM;
    wd.dp = dp;
    wd.cfl_acoustic = cfl;
    wd.stepping = stepping ? SPS_STEPPING_SINGLE : SPS_STEPPING_DUAL;
    wd.frozen_geometry = geometry == 1;
    wd.threads = threads;
    if (sps_world_create(&wd, &w) != SPS_OK) return 2;
    bd.name = CASE;
    bd.material.density = rho0;
    bd.material.youngs_modulus = E;
    bd.material.poisson_ratio = nu;
    bd.shear = (sps_shear)shear;
    bd.rotation = rotation ? SPS_ROTATION_PER_PARTICLE : SPS_ROTATION_MEAN;
    bd.track_stress = 1;
    if (sps_world_add_body(w, &bd, &block) != SPS_OK) return 2;
    sps_body_add_box(w, block, lo, hi, NULL);
    sps_body_set_velocity(w, block, rigid_rotation, &omega);
    corner_id = sps_world_nearest_particle(w, block, corner);

    output_open(&output, out, CASE, csv_every, vtk_every, ",corner_ux,corner_uy,corner_vx,corner_vy");
    n = sps_world_particle_count(w);
    for (i = 0; i < n; ++i) { /* momentum scale sum m |v| for the linear-momentum drift */
        const sps_real *vx = sps_world_field(w, SPS_FIELD_VELOCITY_X), *vy = sps_world_field(w, SPS_FIELD_VELOCITY_Y);
        p_scale += sps_world_field(w, SPS_FIELD_MASS)[i] * sqrt(vx[i] * vx[i] + vy[i] * vy[i]); /* v_z = 0 */
    }
    sps_world_diagnostics(w, all, &d0);
    wall0 = wall_seconds();
    for (;;) {
        double t = sps_world_time(w);
        sps_particle_state c;
        char extra[160];
        sps_world_particle(w, corner_id, &c);
        snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g,%.9g", (double)c.displacement[0], (double)c.displacement[1],
                 (double)c.velocity[0], (double)c.velocity[1]);
        if (output_tick(w, &output, extra, &d)) {
            double err = fabs(d.angular_momentum[2] - d0.angular_momentum[2]) / fabs(d0.angular_momentum[2]);
            if (err > max_err) max_err = err;
            if (norm3(d.linear_momentum) / p_scale > max_p_drift) max_p_drift = norm3(d.linear_momentum) / p_scale;
        }
        if (t >= t_end) break;
        if (sps_world_advance(w, t + csv_every < t_end ? t + csv_every : t_end, NULL, NULL) != SPS_OK) {
            fprintf(stderr, "%s: %s\n", CASE, sps_world_last_error(w));
            return 1;
        }
        progress(sps_world_time(w), t_end, wall0, quiet);
    }
    fclose(output.csv);
    printf("RESULT case=%s shear=%s rotation=%s dp=%g omega=%g stepping=%s cfl=%g max_angmom_err=%.2f%% paper=%.2f%% "
           "max_linmom_drift=%.2e min_spacing=%.3f hourglass_max=%.3g kinetic_start=%.6g kinetic_end=%.6g particles=%d "
           "steps=%ld wall_s=%.2f out=%s\n",
           CASE, shear_name(shear), rotation ? "particle" : "mean", dp, omega, stepping ? "single" : "dual", cfl, 100 * max_err,
           paper_error[shear], max_p_drift, output.min_spacing, output.hourglass_max, (double)d0.kinetic_energy, (double)d.kinetic_energy, n,
           d.acoustic_steps, wall_seconds() - wall0, out);
    sps_world_destroy(w);
    return 0;
}
