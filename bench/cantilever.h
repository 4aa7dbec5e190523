/* cantilever.h - what bench/beam_reference.c and bench/clamp_reference.c share: the 2D
   oscillating plate's case (benchmark A1, plane strain), its moduli, the thin-plate period and
   the exact first period of the linear Timoshenko cantilever (an independent check for both),
   and the parsing of a numeric option. Static functions, included once by each program. */
#ifndef SPS_BENCH_CANTILEVER_H
#define SPS_BENCH_CANTILEVER_H
#include <math.h>
#include <stdlib.h>

static const double PI = 3.14159265358979323846;
static const double KL_EXACT_ROOT = 1.8751040687; /* root of 1 + cos kL cosh kL = 0 */

/* ---- the case ---- */

typedef struct {
    double length, thickness, density, youngs, poisson, shear_coefficient;
} plate_case;

/* L = 0.2, H = 0.02, rho0 = 1000, E = 2e6, nu = 0.3975; kappa 5/6 (rectangular section) */
static plate_case benchmark_case(void) {
    plate_case c = {0.2, 0.02, 1000.0, 2e6, 0.3975, 5.0 / 6.0};
    return c;
}

static double plane_strain_modulus(const plate_case* c) {
    return c->youngs / (1 - c->poisson * c->poisson);
}

static double shear_modulus(const plate_case* c) {
    return c->youngs / (2 * (1 + c->poisson));
}

/* thin-plate (Euler-Bernoulli, plane strain) first period for a given k L */
static double thin_plate_period(const plate_case* c, double kL) {
    double k = kL / c->length;
    double omega2 = plane_strain_modulus(c) * c->thickness * c->thickness * pow(k, 4)
                    / (12 * c->density);
    return 2 * PI / sqrt(omega2);
}

/* ---- independent check 1: the exact first period of the linear Timoshenko cantilever ----
   The beam equations for a harmonic motion at angular frequency w,
       kappa G A (v'' - theta') + rho0 A w^2 v = 0,
       E' I theta'' + kappa G A (v' - theta) + rho0 I w^2 theta = 0,
   with v = theta = 0 at the clamp and no moment and no shear force at the free end
   (theta' = 0, v' - theta = 0). For a trial w, integrate from the clamp twice (v'(0) = 1, then
   theta'(0) = 1; Runge-Kutta 4): w is a natural frequency when a combination of the two meets
   both free-end conditions, i.e. when the 2x2 determinant of their residuals vanishes. It shares
   no code with the beam above, so it checks the element, the mass and the clamp. */

typedef struct {
    double bending, shear, mass, rotary; /* E'I, kappa G A, rho0 A, rho0 I */
    double omega2;
} timoshenko_ode;

/* y = (v, v', theta, theta') */
static void timoshenko_derivative(const timoshenko_ode* p, const double y[4], double dy[4]) {
    dy[0] = y[1];
    dy[1] = y[3] - p->mass * p->omega2 * y[0] / p->shear;
    dy[2] = y[3];
    dy[3] = -(p->shear * (y[1] - y[2]) + p->rotary * p->omega2 * y[2]) / p->bending;
}

static void runge_kutta_step(const timoshenko_ode* p, double h, double y[4]) {
    double k1[4], k2[4], k3[4], k4[4], trial[4];
    int i;
    timoshenko_derivative(p, y, k1);
    for (i = 0; i < 4; i++) trial[i] = y[i] + 0.5 * h * k1[i];
    timoshenko_derivative(p, trial, k2);
    for (i = 0; i < 4; i++) trial[i] = y[i] + 0.5 * h * k2[i];
    timoshenko_derivative(p, trial, k3);
    for (i = 0; i < 4; i++) trial[i] = y[i] + h * k3[i];
    timoshenko_derivative(p, trial, k4);
    for (i = 0; i < 4; i++) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
}

static double free_end_determinant(timoshenko_ode* p, double length, double omega) {
    enum { STEPS = 2000 };
    double a[4] = {0, 1, 0, 0}, b[4] = {0, 0, 0, 1};
    int s;
    p->omega2 = omega * omega;
    for (s = 0; s < STEPS; s++) {
        runge_kutta_step(p, length / STEPS, a);
        runge_kutta_step(p, length / STEPS, b);
    }
    return a[3] * (b[1] - b[2]) - b[3] * (a[1] - a[2]);
}

/* The first root lies below the thin-beam frequency (shear and rotary inertia only lower it);
   bisection from 0.8 of it. Returns 0 if the bracket holds no root (a far too soft shear). */
static double timoshenko_exact_period(const plate_case* c, double shear_factor,
                                      double rotary_factor) {
    timoshenko_ode p;
    double H = c->thickness, hi = 2 * PI / thin_plate_period(c, KL_EXACT_ROOT), lo = 0.8 * hi;
    double residual_lo;
    int i;
    p.bending = plane_strain_modulus(c) * H * H * H / 12;
    p.shear = c->shear_coefficient * shear_modulus(c) * H * shear_factor;
    p.mass = c->density * H;
    p.rotary = c->density * H * H * H / 12 * rotary_factor;
    residual_lo = free_end_determinant(&p, c->length, lo);
    if (residual_lo * free_end_determinant(&p, c->length, hi) > 0) return 0;
    for (i = 0; i < 50; i++) {
        double mid = 0.5 * (lo + hi), residual_mid = free_end_determinant(&p, c->length, mid);
        if (residual_lo * residual_mid <= 0) hi = mid;
        else lo = mid, residual_lo = residual_mid;
    }
    return 2 * PI / (0.5 * (lo + hi));
}

/* The number after option argv[*i] (advancing *i); calls usage (which exits) when it is missing or
   not a number. */
static double number_argument(int argc, char** argv, int* i, void (*usage)(void)) {
    char* end;
    double value;
    if (*i + 1 >= argc) usage();
    value = strtod(argv[++*i], &end);
    if (*end != '\0') usage();
    return value;
}

#endif
