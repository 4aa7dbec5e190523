/* rotation_probe - does the mean rotation of ENO-A (ANG eqs. 41-42) turn a_s with the body?

   Spins the unit square (benchmark A3, bench/VALIDATION.md) or cube (A4) about z, like torque_probe, and hooks
   the end of every acoustic sub-step (sps__finish, renamed by the macro trick below, so the
   library header is used unmodified) to integrate three rotation angles about z:
     th_mean  the angle of the mean Rodrigues matrix of the step (what rotates a_s),
     th_fit   the body's best-fit rotation: polar angle of sum m (x - xc)(X - Xc)^T against the
              initial positions X (about z; the cube spins about z),
     th_L     int L_z / I_z dt (the rigid angular velocity with the body's L and inertia).
   Every --every seconds it prints the angular-momentum error, the angle differences, the
   z-torque Ts of m a_s (as the kick applies it, see torque_probe.c), the "virial" Vs = sum m
   x.a_s (in the xy plane) and Ts/Vs (the angle by which a_s would have to be turned back
   to make it torque-free if the torque came from a uniform misalignment).

   Variants (--variant, each replaces the matrix that turns a_s in sps__finish, and the spin
   the next kick uses for its half step):
     0 library (mean Rodrigues matrix of this step, ANG eq. 41)
     1 the best-fit body rotation of this step (th_fit increment)
     2 the rotation by omega_L dt, omega_L = L_z/I_z
     3 the previous step's mean matrix (ANG eq. 42 read literally: R^n from Omega^n)
     4 no half-step rotation in the kick (mean_spin = 0 after each step)
     5 3 and 4 together: ANG Algorithm 1 to the letter
   --damp-from T1 --damp-to T2 [--damp c]: between T1 and T2, after every advection step, scale
   the non-rigid velocity (v minus the rigid motion with the same P and L_z) by 1 - c (0.05);
   P and L_z are unchanged, the breathing oscillation is removed.
   --ramp T: start at rest and spin the body up to omega along (1 - cos(pi t/T))/2 by rigid
   velocity increments after every advection step; the error is then measured from t = T.

   Usage: ./build/rotation_probe [--dim 2|3] [--dp 0.05] [--nu 0.3] [--shear 1] [--variant 0]
                                 [--tend 0.5] [--every 0.05] [--ramp 0] [--cfl 0.4]
   Reads library internals (world fields): a diagnostic, not an example of the API. Serial
   only (run with OMP_NUM_THREADS=1; the hook does its sums in one thread). */
#include "../sphsolid.h"
static void probe_finish(sps_world* w, sps_real dt);
/* sps__finish(sps_world* w, sps_real dt) (the definition) -> sps__finish_lib(...);
   sps__finish(w, dt) (the call) -> probe_finish(w, dt) */
#define sps__finish(a, b) PROBE_FIN_##a, b)
#define PROBE_FIN_sps_world sps__finish_lib(sps_world
#define PROBE_FIN_w probe_finish(w
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "kick_shear.h"

static const double PI = 3.14159265358979323846;
static int variant = 0;
static double *X0, th_mean, th_fit, th_fit_prev, th_L, R_prev[9];
static int have_prev;

static double wrap(double a) {
    while (a > PI) a -= 2 * PI;
    while (a <= -PI) a += 2 * PI;
    return a;
}

/* centre of mass, best-fit angle about z (unwrapped near th_fit_prev), L_z, I_z */
static void body_state(const sps_world* w, double* fit, double* Lz, double* Iz) {
    double M = 0, xc = 0, yc = 0, Xc = 0, Yc = 0, s = 0, c = 0, l = 0, I = 0, vx = 0, vy = 0;
    int i;
    for (i = 0; i < w->n; ++i) {
        double m = w->mass[i];
        M += m;
        xc += m * w->pos[0][i]; yc += m * w->pos[1][i];
        Xc += m * X0[3 * w->id[i]]; Yc += m * X0[3 * w->id[i] + 1];
        vx += m * w->vel[0][i]; vy += m * w->vel[1][i];
    }
    xc /= M; yc /= M; Xc /= M; Yc /= M; vx /= M; vy /= M;
    for (i = 0; i < w->n; ++i) {
        double m = w->mass[i], x = w->pos[0][i] - xc, y = w->pos[1][i] - yc;
        double X = X0[3 * w->id[i]] - Xc, Y = X0[3 * w->id[i] + 1] - Yc;
        s += m * (y * X - x * Y);
        c += m * (x * X + y * Y);
        l += m * (x * (w->vel[1][i] - vy) - y * (w->vel[0][i] - vx));
        I += m * (x * x + y * y);
    }
    *fit = th_fit_prev + wrap(atan2(s, c) - th_fit_prev);
    *Lz = l;
    *Iz = I;
}

static void rotz(double th, int dim, sps_real R[9]) {
    int a;
    for (a = 0; a < 9; ++a) R[a] = (a % 4 == 0) ? 1 : 0;
    R[0] = R[4] = (sps_real)cos(th);
    R[3] = (sps_real)sin(th);
    R[1] = -R[3];
    if (dim == 2) R[8] = 1;
}

static void probe_finish(sps_world* w, sps_real dt) {
    sps__body* b = &w->bodies[0];
    double fit, Lz, Iz, saved[9];
    int a;
    body_state(w, &fit, &Lz, &Iz);
    th_mean += atan2(b->mean_rotation[3] - b->mean_rotation[1], b->mean_rotation[0] + b->mean_rotation[4]);
    th_L += Lz / Iz * dt;
    for (a = 0; a < 9; ++a) saved[a] = b->mean_rotation[a];
    if (variant == 1) rotz(fit - th_fit_prev, w->dim, b->mean_rotation);
    if (variant == 2) rotz(Lz / Iz * dt, w->dim, b->mean_rotation);
    if ((variant == 3 || variant == 5) && have_prev)
        for (a = 0; a < 9; ++a) b->mean_rotation[a] = (sps_real)R_prev[a];
    if (variant >= 1 && variant <= 3) sps__spin_of_rotation(b->mean_rotation, dt, w->dim, b->mean_spin);
    for (a = 0; a < 9; ++a) R_prev[a] = saved[a];
    have_prev = 1;
    th_fit_prev = th_fit = fit;
    sps__finish_lib(w, dt);
    if (variant == 4 || variant == 5)
        for (a = 0; a < 9; ++a) b->mean_spin[a] = 0;
}

/* z-torque and xy virial of m H a_s at x + dt/2 v (as the next kick applies it) */
static void shear_moments(const sps_world* w, double* torque, double* virial) {
    sps_real H[9];
    double x[2], a[2];
    int i;
    kick_half_rotation(w, H);
    *torque = *virial = 0;
    for (i = 0; i < w->n; ++i) {
        kick_shear_xy(w, H, i, x, a);
        *torque += w->mass[i] * (x[0] * a[1] - x[1] * a[0]);
        *virial += w->mass[i] * (x[0] * a[0] + x[1] * a[1]);
    }
}

/* kinetic energy of the motion that is not rigid (v - v_cm - omega_L e_z x (x - xc)); with
   c > 0 that motion is also scaled by (1 - c), which changes neither P nor L_z */
static double deform_motion(sps_world* w, double c) {
    double M = 0, xc = 0, yc = 0, vx = 0, vy = 0, l = 0, I = 0, om, e = 0;
    int i;
    for (i = 0; i < w->n; ++i) {
        double m = w->mass[i];
        M += m; xc += m * w->pos[0][i]; yc += m * w->pos[1][i]; vx += m * w->vel[0][i]; vy += m * w->vel[1][i];
    }
    xc /= M; yc /= M; vx /= M; vy /= M;
    for (i = 0; i < w->n; ++i) {
        double m = w->mass[i], x = w->pos[0][i] - xc, y = w->pos[1][i] - yc;
        l += m * (x * (w->vel[1][i] - vy) - y * (w->vel[0][i] - vx));
        I += m * (x * x + y * y);
    }
    om = l / I;
    for (i = 0; i < w->n; ++i) {
        double m = w->mass[i], x = w->pos[0][i] - xc, y = w->pos[1][i] - yc;
        double ux = w->vel[0][i] - vx + om * y, uy = w->vel[1][i] - vy - om * x, uz = w->dim == 3 ? w->vel[2][i] : 0;
        e += 0.5 * m * (ux * ux + uy * uy + uz * uz);
        if (c > 0) {
            w->vel[0][i] -= (sps_real)(c * ux);
            w->vel[1][i] -= (sps_real)(c * uy);
            if (w->dim == 3) w->vel[2][i] -= (sps_real)(c * uz);
        }
    }
    return e;
}

static double arg(int argc, char** argv, const char* name, double def) {
    int k;
    for (k = 1; k + 1 < argc; ++k)
        if (!strcmp(argv[k], name)) return atof(argv[k + 1]);
    return def;
}

static double omega_now;
static void rigid_rotation(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = (sps_real)(-omega_now * x[1]);
    v[1] = (sps_real)(omega_now * x[0]);
    v[2] = 0;
}

int main(int argc, char** argv) {
    const int dim = (int)arg(argc, argv, "--dim", 2), shear = (int)arg(argc, argv, "--shear", SPS_SHEAR_ENO_A);
    const double omega = 50, t_end = arg(argc, argv, "--tend", 0.5), every = arg(argc, argv, "--every", 0.05);
    const double ramp = arg(argc, argv, "--ramp", 0), damp0 = arg(argc, argv, "--damp-from", 0);
    const double damp1 = arg(argc, argv, "--damp-to", 0), damp_c = arg(argc, argv, "--damp", 0.05);
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_real lo[3] = {-0.5, -0.5, -0.5}, hi[3] = {0.5, 0.5, 0.5};
    sps_world* w;
    sps_body body, all = {0};
    double L0 = 0, Lprev = 0, tprev = 0, max_err = 0, t;
    int i, k = 1;
    variant = (int)arg(argc, argv, "--variant", 0);
    wd.dim = dim;
    wd.dp = arg(argc, argv, "--dp", 0.05);
    wd.threads = 1;
    wd.cfl_acoustic = arg(argc, argv, "--cfl", wd.cfl_acoustic);
    bd.material.density = 1100;
    bd.material.youngs_modulus = 1.7e7;
    bd.material.poisson_ratio = arg(argc, argv, "--nu", 0.3);
    bd.shear = (sps_shear)shear;
    omega_now = ramp > 0 ? 0 : omega;
    if (sps_world_create(&wd, &w) != SPS_OK || sps_world_add_body(w, &bd, &body) != SPS_OK ||
        sps_body_add_box(w, body, lo, hi, NULL) != SPS_OK || sps_body_set_velocity(w, body, rigid_rotation, NULL) != SPS_OK) {
        fprintf(stderr, "rotation_probe: bad arguments\n");
        return 2;
    }
    X0 = (double*)malloc(sizeof(double) * 3 * (size_t)w->n);
    for (i = 0; i < w->n; ++i)
        for (k = 0; k < 3; ++k) X0[3 * w->id[i] + k] = k < dim ? w->pos[k][i] : 0;
    if (ramp <= 0) {
        sps_diagnostics d;
        sps_world_diagnostics(w, all, &d);
        Lprev = L0 = d.angular_momentum[2];
    }
    printf("# dim %d nu %g shear %d variant %d ramp %g particles %d\n", dim, (double)bd.material.poisson_ratio, shear, variant, ramp, w->n);
    printf("#     t   err%%    th_mean-th_fit  th_L-th_fit     Ts          Vs        Ts/Vs      dL/dt      E_deform\n");
    for (k = 1; (t = ramp + k * every) <= ramp + t_end + 1e-9; ++k) {
        sps_diagnostics d;
        double ts, vs, err;
        while (w->time < t - 1e-12) {
            double t0 = w->time, target = t, s0, s1;
            const int stepwise = (ramp > 0 && t0 < ramp) || (t0 >= damp0 && t0 < damp1);
            sps_result r = stepwise ? sps_world_step(w) : sps_world_advance(w, (sps_real)target, NULL, NULL);
            if (t0 >= damp0 && t0 < damp1) deform_motion(w, damp_c);
            if (r != SPS_OK) { fprintf(stderr, "rotation_probe: %s\n", sps_world_last_error(w)); return 1; }
            if (ramp > 0 && t0 < ramp) { /* rigid velocity increment about the centre of mass */
                double tt = w->time < ramp ? w->time : ramp, M = 0, xc = 0, yc = 0;
                s0 = 0.5 * (1 - cos(PI * t0 / ramp));
                s1 = 0.5 * (1 - cos(PI * tt / ramp));
                for (i = 0; i < w->n; ++i) { M += w->mass[i]; xc += w->mass[i] * w->pos[0][i]; yc += w->mass[i] * w->pos[1][i]; }
                xc /= M; yc /= M;
                for (i = 0; i < w->n; ++i) {
                    w->vel[0][i] -= (sps_real)(omega * (s1 - s0) * (w->pos[1][i] - yc));
                    w->vel[1][i] += (sps_real)(omega * (s1 - s0) * (w->pos[0][i] - xc));
                }
                if (w->time >= ramp) { /* the error is measured from here */
                    sps_world_diagnostics(w, all, &d);
                    Lprev = L0 = d.angular_momentum[2];
                    tprev = w->time;
                }
            }
        }
        shear_moments(w, &ts, &vs);
        sps_world_diagnostics(w, all, &d);
        err = 100 * fabs(d.angular_momentum[2] - L0) / fabs(L0);
        if (err > max_err) max_err = err;
        printf("%7.3f %7.3f %14.4e %12.4e %11.4g %11.4g %11.4e %10.4g %10.4g\n", (double)w->time, err, th_mean - th_fit, th_L - th_fit, ts,
               vs, ts / vs, (d.angular_momentum[2] - Lprev) / (w->time - tprev), deform_motion(w, 0));
        fflush(stdout);
        Lprev = d.angular_momentum[2];
        tprev = w->time;
    }
    printf("RESULT dim=%d nu=%g variant=%d ramp=%g max_angmom_err=%.3f%%\n", dim, (double)bd.material.poisson_ratio, variant, ramp, max_err);
    sps_world_destroy(w);
    free(X0);
    return 0;
}
