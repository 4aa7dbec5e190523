/* beam_reference - a beam-theory reference for the first period of the 2D oscillating plate.

   What it computes
     The first oscillation period of the clamped cantilever of benchmark A1 (the 2D oscillating
     plate), with the effects that thin-plate (Euler-Bernoulli) theory leaves out:
       - thickness: shear deformation and rotary inertia (Timoshenko beam), which lengthen the
         period of a beam as thick as this one (H/L = 0.1, slenderness L/r = L sqrt(12)/H = 34.6);
       - amplitude: large rotations of the cross-sections (geometric nonlinearity); at v_f = 0.05
         the tip swings about L/2.
     The SPH plate is a 2D continuum; this program is an independent check of how far the SPH
     periods are from the continuum truth, not a model of the SPH clamp (see "Assumptions and
     limits").

   The case (SI units, plane strain, unit depth)
     free length L = 0.2 (clamped at x = 0), thickness H = 0.02, rho0 = 1000, E = 2e6, nu = 0.3975.
     Plane strain: the bending and axial modulus is E' = E / (1 - nu^2); G = E / (2 (1 + nu)).
     Initial velocity, transverse only, the Euler-Bernoulli first mode (x from the clamp):
       v_y(x) = v_f c0 f(x) / f(L),  c0 = sqrt(E / (3 (1 - 2 nu) rho0)),  k = 1.875 / L,
       f(x) = (sin kL + sinh kL)(cos kx - cosh kx) - (cos kL + cosh kL)(sin kx - sinh kx).
     The cross-sections start turning at the rate dv_y/dx: the Euler-Bernoulli mode, in which
     the sections stay normal to the centre line (a Timoshenko beam's own first mode differs
     slightly, so a little of its higher modes is excited; they barely move the zero crossings).
     Thin-plate theory: omega^2 = E' H^2 k^4 / (12 rho0), T = 2 pi / omega = 0.2541 s.
     First period: the time of the second zero crossing of the tip deflection u_y(L) (it starts
     at zero going up), linearly interpolated between time steps.

   The model: a geometrically exact planar beam (Reissner / Simo-Reissner, Timoshenko kinematics)
     - N two-node elements; every node carries a displacement (u_x, u_y) and a section rotation
       theta. Node 0 is the clamp: u_x = u_y = theta = 0 for all time.
     - Beam strains in the frame that turns with the section (theta_m = mean of the two nodes):
         axial  eps   = cos(theta_m) x' + sin(theta_m) y' - 1
         shear  gamma = -sin(theta_m) x' + cos(theta_m) y'
         bending kappa_b = theta'
       where (x', y') is the derivative of the deformed centre line along the reference length.
       These are exact for any rotation: a rigid turn of the whole beam gives zero strain, so
       tip deflections of L/2 are handled without error from the rotation itself.
     - Linear elastic in these strains (small strains, large rotations):
         N = E' A eps,  Q = kappa G A gamma,  M = E' I kappa_b,  A = H, I = H^3/12 (unit depth),
       with the Timoshenko shear coefficient kappa = 5/6 (rectangular section; --kappa changes it).
     - One-point (mid-element) integration: strains constant over each element. This is the
       classical locking-free choice for linear-interpolation Timoshenko elements; it leaves
       no spurious zero-energy modes (3 strains for the 3 deformation modes of an element).
     - Lumped mass: translational rho0 A and rotary rho0 I per unit length, half an element's
       share to each of its nodes.
     - Explicit central differences (leapfrog, kick-drift-kick). Stable if dt < 2 / omega_max;
       omega_max is bounded by the largest frequency of a single free element (a theorem:
       the assembled mesh cannot vibrate faster than its fastest element), which is that of
       its axial mode, its bending mode (the ends rotating opposite ways) or its shear mode:
         omega_axial^2 = 4 E' / (rho0 h^2),  omega_bending^2 = 4 E' A / (rho0 J h^2),
         omega_shear^2 = 4 kappa G / (rho0 h^2) + kappa G A / J,   J = rotary inertia per length
       (h = L / N). dt = SAFETY x 2 / omega_max, SAFETY = 0.8 (room for the geometric stiffness
       of the large-amplitude runs, which the bound leaves out).
     --linear: the same element with small-displacement kinematics (eps = u_x', gamma =
       u_y' - theta_m, kappa_b = theta'): the linear Timoshenko beam. Its period does not depend
       on v_f; comparing it with the nonlinear beam separates the amplitude effect from the
       thickness effect.
     --euler-bernoulli: thin-beam limit. A zero rotary inertia and an infinite shear rigidity
       cannot be integrated explicitly (the rotation would have no mass, the shear mode an
       infinite frequency), so the shear rigidity is multiplied by EB_SHEAR_FACTOR = 1e3 and the
       rotary inertia by EB_INERTIA_FACTOR = 1e-3. Both corrections to the period scale with
       these factors: what is left of them is about 1e-3 of the Timoshenko correction (< 1e-5
       of the period). The time step shrinks by about 1000.

   Independent checks (printed with the table)
     1. The exact first period of the linear Timoshenko cantilever, from its ordinary
        differential equations by shooting (Runge-Kutta 4 and bisection), with the shear and the
        rotary-inertia parts separately: checks the element, the masses and the clamp.
     2. A one-mode estimate of the amplitude effect (an inextensible thin beam to fourth order,
        harmonic balance): checks the sign and size of the geometric nonlinearity.
     3. The --euler-bernoulli run against thin-plate theory (the verification of the code).

   Assumptions and limits
     A beam is one-dimensional: cross-sections stay plane (warping enters only through the
     shear coefficient kappa), the stress across the thickness is neglected (plane strain only
     enters through E'), and the clamp fixes the section's centre and rotation but lets the
     section contract sideways. The stresses are linear in the beam strains: at v_f = 0.05 the
     bending strain at the skin of the root reaches 10%, where real material laws differ from
     each other by terms of order strain^2 (an estimated 0.1% on the period). The SPH plate is a
     2D continuum whose root is held by a block of fixed particles: it cannot contract sideways
     at the clamp, which stiffens the root. bench/clamp_reference.c (a plane-strain
     finite-element eigenvalue program, 9-node elements refined to 32 across H and
     extrapolated) puts that effect at -0.43% on the period (0.2552 s against 0.2563 s for a
     root free to contract, which itself is within 0.05% of the Timoshenko beam's 0.2565 s),
     half the shear correction: at H/L = 0.1 the details of the clamp matter at the 0.5% level
     and a beam cannot settle them. The initial rotation rate of the sections barely matters:
     an earlier explicit check with v_x = 0 (the SPH setup: no section rotation at t = 0)
     moved the period by 0.006%.

   Usage
     ./build/beam_reference                  the table below (all runs, a few seconds)
     ./build/beam_reference [--vf 0.05] [--elements 80] [--tend 1] [--linear]
                            [--euler-bernoulli] [--kappa 0.8333] [--every 0.01]
         one run: the tip trace every --every seconds (t, u_x, u_y, theta at the tip, relative
         energy error), then every period found (successive up-crossings) and the first one.
     Any option other than --kappa selects the single run; --kappa alone changes the table.
     Build: make build/beam_reference (gcc -std=c99 -O2, libc and libm only, one thread).

   Expected output (default run; all of it in bench/results/beam_reference.txt)
     First period [s] (nonlinear: geometrically exact Timoshenko beam; linear: N = 160):
            nonlinear Timoshenko beam, N elements | linear   |        | amplitude effect
       v_f    N=20     N=40     N=80     N=160   | N=160    | theory | beam    1-mode
      0.001  0.256643 0.256518 0.256487 0.256479 | 0.256480 | 0.2541 | -0.000% -0.000%
      0.010  0.256594 0.256470 0.256439 0.256431 | 0.256480 | 0.2541 | -0.019% -0.026%
      0.030  0.256184 0.256064 0.256035 0.256027 | 0.256480 | 0.2541 | -0.176% -0.208%
      0.050  0.255412 0.255302 0.255274 0.255267 | 0.256480 | 0.2541 | -0.473% -0.475%
     (the last two columns, tip amplitude 0.0023 .. 0.107 m and skin strain, are left out here)
     Thickness: exact linear Timoshenko eigenperiod 0.256467 s, +0.958% over thin-plate theory
     with the exact root kL (shear +0.769%, rotary inertia +0.194%). Euler-Bernoulli check,
     N = 160: 0.254037 s, -0.009% from 0.254061 s. Time step at N = 160: 2.05e-5 s (3.6e-7 s
     with --euler-bernoulli).
     CPU time about 4 s. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cantilever.h"

static const double KL_FIRST_MODE = 1.875;        /* the benchmark's k L */
static const double SAFETY = 0.8;          /* fraction of the stable time step used */
static const double EB_SHEAR_FACTOR = 1e3;   /* --euler-bernoulli: shear rigidity x this */
static const double EB_INERTIA_FACTOR = 1e-3; /* --euler-bernoulli: rotary inertia x this */

/* ---- the case (its struct, values and moduli: cantilever.h) ---- */

/* the benchmark's velocity scale (a bulk-like wave speed of the SPH setup) */
static double velocity_scale(const plate_case* c) {
    return sqrt(c->youngs / (3 * (1 - 2 * c->poisson) * c->density));
}

/* the Euler-Bernoulli first mode of a cantilever, its slope and curvature, x from the clamp */
static double mode_shape(double k, double L, double x) {
    return (sin(k * L) + sinh(k * L)) * (cos(k * x) - cosh(k * x))
           - (cos(k * L) + cosh(k * L)) * (sin(k * x) - sinh(k * x));
}

static double mode_slope(double k, double L, double x) {
    return k * ((sin(k * L) + sinh(k * L)) * (-sin(k * x) - sinh(k * x))
                - (cos(k * L) + cosh(k * L)) * (cos(k * x) - cosh(k * x)));
}

static double mode_curvature(double k, double L, double x) {
    return k * k * ((sin(k * L) + sinh(k * L)) * (-cos(k * x) - cosh(k * x))
                    - (cos(k * L) + cosh(k * L)) * (-sin(k * x) - sinh(k * x)));
}

/* ---- the beam ---- */

typedef enum { NONLINEAR_TIMOSHENKO, LINEAR_TIMOSHENKO } kinematics;

typedef struct {
    int elements;
    kinematics kind;
    int euler_bernoulli; /* penalised shear, nearly no rotary inertia */
    double vf, tend;
    double print_every;  /* > 0: print the tip trace (single-run mode) */
} run_options;

typedef struct {
    int nodes;
    kinematics kind;
    double element_length;
    double axial_rigidity, bending_rigidity, shear_rigidity; /* E'A, E'I, kappa G A */
    double *mass, *rotary_inertia;                           /* lumped, per node */
    double *ux, *uy, *theta;                                 /* displacements, rotation */
    double *vx, *vy, *spin;                                  /* their rates */
    double *fx, *fy, *moment;                                /* nodal forces (external sign) */
    double peak_curvature;                                   /* largest |theta'| seen so far */
} beam;

static double* zeros(int n) {
    double* a = calloc((size_t)n, sizeof *a);
    if (!a) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    return a;
}

static beam beam_create(const plate_case* c, const run_options* o) {
    beam b;
    double area = c->thickness, second_moment = pow(c->thickness, 3) / 12;
    double rotary_per_length = c->density * second_moment;
    int i;
    b.nodes = o->elements + 1;
    b.kind = o->kind;
    b.element_length = c->length / o->elements;
    b.axial_rigidity = plane_strain_modulus(c) * area;
    b.bending_rigidity = plane_strain_modulus(c) * second_moment;
    b.shear_rigidity = c->shear_coefficient * shear_modulus(c) * area;
    if (o->euler_bernoulli) {
        b.shear_rigidity *= EB_SHEAR_FACTOR;
        rotary_per_length *= EB_INERTIA_FACTOR;
    }
    b.mass = zeros(b.nodes);
    b.rotary_inertia = zeros(b.nodes);
    b.ux = zeros(b.nodes), b.uy = zeros(b.nodes), b.theta = zeros(b.nodes);
    b.vx = zeros(b.nodes), b.vy = zeros(b.nodes), b.spin = zeros(b.nodes);
    b.fx = zeros(b.nodes), b.fy = zeros(b.nodes), b.moment = zeros(b.nodes);
    b.peak_curvature = 0;
    /* lumped mass: each element gives half its mass and rotary inertia to each end */
    for (i = 0; i < o->elements; i++) {
        double m = c->density * area * b.element_length / 2;
        double j = rotary_per_length * b.element_length / 2;
        b.mass[i] += m, b.mass[i + 1] += m;
        b.rotary_inertia[i] += j, b.rotary_inertia[i + 1] += j;
    }
    return b;
}

static void beam_free(beam* b) {
    free(b->mass), free(b->rotary_inertia);
    free(b->ux), free(b->uy), free(b->theta);
    free(b->vx), free(b->vy), free(b->spin);
    free(b->fx), free(b->fy), free(b->moment);
}

/* the stable time step: the fastest free element bounds the fastest mode of the mesh */
static double stable_time_step(const beam* b) {
    double h = b->element_length;
    double m = b->mass[1] / h, j = b->rotary_inertia[1] / h; /* per unit length */
    double axial2 = 4 * b->axial_rigidity / (m * h * h);
    double bending2 = 4 * b->bending_rigidity / (j * h * h);
    double shear2 = 4 * b->shear_rigidity / (m * h * h) + b->shear_rigidity / j;
    double omega2 = axial2;
    if (bending2 > omega2) omega2 = bending2;
    if (shear2 > omega2) omega2 = shear2;
    return SAFETY * 2 / sqrt(omega2);
}

/* the strains and stress resultants of one element, and the force its end e+1 feels from it */
typedef struct {
    double axial_strain, shear_strain, curvature;
    double axial_force, shear_force, bending_moment;
    double fx, fy;   /* N and Q as a vector: node e+1 is pulled by -f, node e by +f */
    double couple;   /* moment of that pair of end forces, which the end moments balance */
} element_state;

static element_state element_nonlinear(const beam* b, int e) {
    element_state s;
    double h = b->element_length;
    double dx = h + b->ux[e + 1] - b->ux[e], dy = b->uy[e + 1] - b->uy[e];
    double theta_mid = 0.5 * (b->theta[e] + b->theta[e + 1]);
    double cs = cos(theta_mid), sn = sin(theta_mid);
    /* the centre-line tangent seen from the section: (1 + eps, gamma) */
    s.axial_strain = (cs * dx + sn * dy) / h - 1;
    s.shear_strain = (-sn * dx + cs * dy) / h;
    s.curvature = (b->theta[e + 1] - b->theta[e]) / h;
    s.axial_force = b->axial_rigidity * s.axial_strain;
    s.shear_force = b->shear_rigidity * s.shear_strain;
    s.bending_moment = b->bending_rigidity * s.curvature;
    /* N along the section normal, Q along the section: turned to the global frame */
    s.fx = s.axial_force * cs - s.shear_force * sn;
    s.fy = s.axial_force * sn + s.shear_force * cs;
    /* the end forces +f and -f, a chord (dx, dy) apart, make a couple the ends must absorb */
    s.couple = dx * s.fy - dy * s.fx;
    return s;
}

static element_state element_linear(const beam* b, int e) {
    element_state s;
    double h = b->element_length;
    s.axial_strain = (b->ux[e + 1] - b->ux[e]) / h;
    s.shear_strain = (b->uy[e + 1] - b->uy[e]) / h - 0.5 * (b->theta[e] + b->theta[e + 1]);
    s.curvature = (b->theta[e + 1] - b->theta[e]) / h;
    s.axial_force = b->axial_rigidity * s.axial_strain;
    s.shear_force = b->shear_rigidity * s.shear_strain;
    s.bending_moment = b->bending_rigidity * s.curvature;
    s.fx = s.axial_force; /* the frame never turns: forces act along x and y */
    s.fy = s.shear_force;
    s.couple = h * s.fy; /* the chord stays (h, 0) */
    return s;
}

static element_state element_evaluate(const beam* b, int e) {
    return b->kind == LINEAR_TIMOSHENKO ? element_linear(b, e) : element_nonlinear(b, e);
}

/* nodal forces and moments from all elements (virtual work of N, Q, M); returns the strain
   energy. The internal moments, -couple/2 -/+ M at the two ends, make the element's forces
   free of net moment: angular momentum is conserved. */
static double compute_forces(beam* b) {
    double h = b->element_length, strain_energy = 0;
    int i, e;
    for (i = 0; i < b->nodes; i++) b->fx[i] = b->fy[i] = b->moment[i] = 0;
    for (e = 0; e + 1 < b->nodes; e++) {
        element_state s = element_evaluate(b, e);
        b->fx[e] += s.fx, b->fy[e] += s.fy;
        b->fx[e + 1] -= s.fx, b->fy[e + 1] -= s.fy;
        b->moment[e] += 0.5 * s.couple + s.bending_moment;
        b->moment[e + 1] += 0.5 * s.couple - s.bending_moment;
        if (fabs(s.curvature) > b->peak_curvature) b->peak_curvature = fabs(s.curvature);
        strain_energy += 0.5 * h * (s.axial_force * s.axial_strain + s.shear_force * s.shear_strain
                                    + s.bending_moment * s.curvature);
    }
    return strain_energy;
}

static double kinetic_energy(const beam* b) {
    double energy = 0;
    int i;
    for (i = 0; i < b->nodes; i++)
        energy += 0.5 * (b->mass[i] * (b->vx[i] * b->vx[i] + b->vy[i] * b->vy[i])
                         + b->rotary_inertia[i] * b->spin[i] * b->spin[i]);
    return energy;
}

/* the benchmark's initial velocity; the sections turn with the slope of the mode */
static void set_initial_velocity(beam* b, const plate_case* c, double vf) {
    double k = KL_FIRST_MODE / c->length, L = c->length;
    double scale = vf * velocity_scale(c) / mode_shape(k, L, L);
    int i;
    for (i = 1; i < b->nodes; i++) {
        double x = i * b->element_length;
        b->vy[i] = scale * mode_shape(k, L, x);
        b->spin[i] = scale * mode_slope(k, L, x);
    }
}

/* half a kick: rates += dt/2 * forces / inertia; node 0 (the clamp) never moves */
static void half_kick(beam* b, double dt) {
    int i;
    for (i = 1; i < b->nodes; i++) {
        b->vx[i] += 0.5 * dt * b->fx[i] / b->mass[i];
        b->vy[i] += 0.5 * dt * b->fy[i] / b->mass[i];
        b->spin[i] += 0.5 * dt * b->moment[i] / b->rotary_inertia[i];
    }
}

static void drift(beam* b, double dt) {
    int i;
    for (i = 1; i < b->nodes; i++) {
        b->ux[i] += dt * b->vx[i];
        b->uy[i] += dt * b->vy[i];
        b->theta[i] += dt * b->spin[i];
    }
}

/* ---- one run ---- */

typedef struct {
    double first_period;   /* second zero crossing of the tip deflection (0 if not reached) */
    double tip_amplitude;  /* largest tip deflection before the first down-crossing */
    double time_step;
    double energy_error;   /* max |E(t) - E(0)| / E(0) */
    double peak_surface_strain; /* H/2 x the largest curvature: the bending strain at the skin */
    long steps;
} run_result;

/* time where the line through (t0, y0) and (t1, y1) crosses zero */
static double crossing_time(double t0, double y0, double t1, double y1) {
    return t0 + (t1 - t0) * y0 / (y0 - y1);
}

static void print_trace_line(const beam* b, double t, double energy_error) {
    int tip = b->nodes - 1;
    printf("%8.4f %12.6f %12.6f %12.6f %12.3e\n", t, b->ux[tip], b->uy[tip], b->theta[tip],
           energy_error);
}

/* Integrate to o->tend. Without a trace, stop once the first period is known. */
static run_result simulate(const plate_case* c, const run_options* o) {
    beam b = beam_create(c, o);
    run_result r = {0, 0, 0, 0, 0, 0};
    double dt = stable_time_step(&b), t = 0, next_print = o->print_every;
    double strain_energy, initial_energy, last_up_crossing = 0;
    double previous_tip = 0;
    int tip = b.nodes - 1, down_crossings = 0, periods = 0;
    r.time_step = dt;
    set_initial_velocity(&b, c, o->vf);
    strain_energy = compute_forces(&b);
    initial_energy = kinetic_energy(&b) + strain_energy;
    if (o->print_every > 0) {
        printf("#        t       tip u_x      tip u_y    tip theta   energy err\n");
        print_trace_line(&b, t, 0);
    }
    while (t < o->tend) {
        double energy_error;
        half_kick(&b, dt);
        drift(&b, dt);
        strain_energy = compute_forces(&b);
        half_kick(&b, dt);
        t += dt, r.steps++;
        energy_error = fabs(kinetic_energy(&b) + strain_energy - initial_energy) / initial_energy;
        if (energy_error > r.energy_error) r.energy_error = energy_error;
        if (down_crossings == 0 && b.uy[tip] > r.tip_amplitude) r.tip_amplitude = b.uy[tip];
        if (previous_tip > 0 && b.uy[tip] <= 0) down_crossings++;
        if (previous_tip < 0 && b.uy[tip] >= 0) {
            double crossing = crossing_time(t - dt, previous_tip, t, b.uy[tip]);
            if (periods == 0) r.first_period = crossing;
            if (o->print_every > 0)
                printf("# period %d: %.6f s (up-crossing at %.6f s)\n", periods + 1,
                       crossing - last_up_crossing, crossing);
            last_up_crossing = crossing, periods++;
            if (o->print_every <= 0) break;
        }
        previous_tip = b.uy[tip];
        if (o->print_every > 0 && t >= next_print) {
            print_trace_line(&b, t, energy_error);
            next_print += o->print_every;
        }
    }
    r.peak_surface_strain = 0.5 * c->thickness * b.peak_curvature;
    beam_free(&b);
    return r;
}

/* ---- independent check 2: the amplitude effect from one mode of an inextensible thin beam ----
   Put v(s, t) = L q(t) phi(s/L), phi the initial mode with phi(1) = 1, into the energies of an
   inextensible Euler-Bernoulli beam, kept to fourth order in q (as Crespo da Silva and Glynn,
   1978): the curvature squared is v''^2 (1 + v'^2), and the tip's pull-in u = -int v'^2 / 2
   adds kinetic energy:
       U = E'I/2 int v''^2 (1 + v'^2) ds,   T = rho0 A/2 int (v_t^2 + u_t^2) ds.
   Lagrange's equation is  M0 q'' + M2 (q^2 q'' + q q'^2) + K0 q + 2 K2 q^3 = 0  with
       M0 = int phi^2,  M2 = int (int_0^x phi'^2)^2,  K0 = int phi''^2,  K2 = int phi''^2 phi'^2
   over x in [0, 1], and one harmonic, q = a cos(w t) (harmonic balance), gives
       (w / w0)^2 = (1 + 3/2 (K2 / K0) a^2) / (1 + 1/2 (M2 / M0) a^2),   a = tip amplitude / L:
   the curvature stiffens, the axial inertia softens; for the first mode the stiffening wins. */
static double one_mode_period_ratio(double tip_amplitude_over_length) {
    enum { POINTS = 4000 };
    double k = KL_FIRST_MODE, tip = mode_shape(k, 1, 1), dx = 1.0 / POINTS, a2;
    double m0 = 0, m2 = 0, k0 = 0, k2 = 0, pull_in = 0; /* pull_in = int_0^x phi'^2 */
    int i;
    for (i = 0; i < POINTS; i++) {
        double x = (i + 0.5) * dx, phi = mode_shape(k, 1, x) / tip;
        double slope = mode_slope(k, 1, x) / tip, curvature = mode_curvature(k, 1, x) / tip;
        double pull_in_mid = pull_in + 0.5 * dx * slope * slope;
        m0 += phi * phi * dx;
        m2 += pull_in_mid * pull_in_mid * dx;
        k0 += curvature * curvature * dx;
        k2 += curvature * curvature * slope * slope * dx;
        pull_in += slope * slope * dx;
    }
    a2 = tip_amplitude_over_length * tip_amplitude_over_length;
    return sqrt((1 + 0.5 * m2 / m0 * a2) / (1 + 1.5 * k2 / k0 * a2)); /* T / T0 */
}

/* ---- the default table ---- */

static const double TABLE_VF[] = {0.001, 0.01, 0.03, 0.05};
static const int TABLE_MESHES[] = {20, 40, 80, 160};
enum { TABLE_N_VF = 4, TABLE_N_MESH = 4, TABLE_FINEST = 160 };

static double seconds_since(clock_t start) {
    return (double)(clock() - start) / CLOCKS_PER_SEC;
}

static run_options table_run(int elements, kinematics kind, double vf) {
    run_options o;
    o.elements = elements, o.kind = kind, o.euler_bernoulli = 0;
    o.vf = vf, o.tend = 0.5, o.print_every = 0;
    return o;
}

static void print_case(const plate_case* c) {
    double L = c->length, H = c->thickness;
    printf("# 2D oscillating plate as a clamped beam: L %g, H %g, rho0 %g, E %g, nu %g (plane strain)\n",
           L, H, c->density, c->youngs, c->poisson);
    printf("# E' = %.6g, G = %.6g, kappa = %.6g, E'/(kappa G) = %.4f, L/r = %.2f, c0 = %.4f m/s\n",
           plane_strain_modulus(c), shear_modulus(c), c->shear_coefficient,
           plane_strain_modulus(c) / (c->shear_coefficient * shear_modulus(c)), L * sqrt(12.0) / H,
           velocity_scale(c));
    printf("# thin-plate theory: T = %.6f s (kL = 1.875), %.6f s (kL = %.10f)\n",
           thin_plate_period(c, KL_FIRST_MODE), thin_plate_period(c, KL_EXACT_ROOT), KL_EXACT_ROOT);
}

/* one row: the nonlinear beam on every mesh, the linear beam, the amplitude effect */
static void print_table_row(const plate_case* c, double vf) {
    run_result nonlinear = {0, 0, 0, 0, 0, 0}, linear;
    run_options o;
    int m;
    printf("%6.3f ", vf);
    for (m = 0; m < TABLE_N_MESH; m++) {
        o = table_run(TABLE_MESHES[m], NONLINEAR_TIMOSHENKO, vf);
        nonlinear = simulate(c, &o); /* the last one, the finest, is kept */
        printf(" %.6f", nonlinear.first_period);
    }
    o = table_run(TABLE_FINEST, LINEAR_TIMOSHENKO, vf);
    linear = simulate(c, &o);
    printf(" | %.6f | %.4f | %+.3f%% %+.3f%% | %.5f  %.4f\n", linear.first_period,
           thin_plate_period(c, KL_FIRST_MODE),
           100 * (nonlinear.first_period / linear.first_period - 1),
           100 * (one_mode_period_ratio(nonlinear.tip_amplitude / c->length) - 1),
           nonlinear.tip_amplitude, nonlinear.peak_surface_strain);
}

static void print_period_table(const plate_case* c) {
    int i;
    printf("#\n# First period [s]. nonlinear: geometrically exact Timoshenko beam, N elements;\n"
           "# linear: linear Timoshenko beam (N = %d); theory: thin plate (Euler-Bernoulli).\n"
           "# amplitude effect: nonlinear / linear - 1 (N = %d), and the one-mode thin-beam estimate\n"
           "# (check 2) at the same tip amplitude. tip amp.: largest tip deflection in the first\n"
           "# half cycle [m]; skin strain: largest bending strain H/2 |theta'| (at the root).\n",
           TABLE_FINEST, TABLE_FINEST);
    printf("#       nonlinear Timoshenko beam, N elements | linear   |        | amplitude effect\n"
           "#  v_f    N=20     N=40     N=80     N=160   | N=160    | theory | beam    1-mode  |"
           " tip amp. skin strain\n");
    for (i = 0; i < TABLE_N_VF; i++) print_table_row(c, TABLE_VF[i]);
}

static void print_thickness_check(const plate_case* c) {
    double thin = thin_plate_period(c, KL_EXACT_ROOT);
    double exact = timoshenko_exact_period(c, 1, 1);
    double shear_only = timoshenko_exact_period(c, 1, 0);
    double rotary_only = timoshenko_exact_period(c, 1e6, 1);
    run_options o = table_run(TABLE_FINEST, LINEAR_TIMOSHENKO, 0.001);
    double beam_period = simulate(c, &o).first_period;
    printf("#\n# Thickness effect (check 1, exact linear Timoshenko cantilever, against the thin\n"
           "# plate with the exact root kL = %.10f, %.6f s):\n", KL_EXACT_ROOT, thin);
    printf("#   exact eigenperiod %.6f s (%+.3f%%): shear alone %+.3f%%, rotary inertia alone %+.3f%%\n",
           exact, 100 * (exact / thin - 1), 100 * (shear_only / thin - 1),
           100 * (rotary_only / thin - 1));
    printf("#   linear beam above, N = %d, first zero-crossing period %.6f s (%+.4f%% from exact)\n",
           TABLE_FINEST, beam_period, 100 * (beam_period / exact - 1));
}

static void print_time_steps(const plate_case* c) {
    int m;
    printf("# time step (safety %.1f x the stable one): ", SAFETY);
    for (m = 0; m < TABLE_N_MESH; m++) {
        run_options o = table_run(TABLE_MESHES[m], NONLINEAR_TIMOSHENKO, 0.001);
        beam b = beam_create(c, &o);
        printf("N=%d %.3e s%s", TABLE_MESHES[m], stable_time_step(&b),
               m + 1 < TABLE_N_MESH ? ", " : "\n");
        beam_free(&b);
    }
}

/* the verification: the same code in its thin-beam limit must give thin-plate theory */
static void print_euler_bernoulli_check(const plate_case* c) {
    double thin = thin_plate_period(c, KL_FIRST_MODE);
    double thin_exact_root = thin_plate_period(c, KL_EXACT_ROOT);
    int m;
    printf("#\n# Euler-Bernoulli check: --euler-bernoulli --linear, v_f 0.001, against %.6f s\n"
           "# (kL = 1.875) and %.6f s (the exact root, which the discrete beam converges to)\n",
           thin, thin_exact_root);
    for (m = 1; m < TABLE_N_MESH; m++) {
        run_options o = table_run(TABLE_MESHES[m], LINEAR_TIMOSHENKO, 0.001);
        run_result r;
        o.euler_bernoulli = 1;
        r = simulate(c, &o);
        printf("#   N=%3d dt %.3e s: T = %.6f s (%+.3f%%, %+.3f%%)\n", TABLE_MESHES[m], r.time_step,
               r.first_period, 100 * (r.first_period / thin - 1),
               100 * (r.first_period / thin_exact_root - 1));
    }
}

static void print_table(const plate_case* c) {
    clock_t start = clock();
    print_case(c);
    print_period_table(c);
    print_time_steps(c);
    print_thickness_check(c);
    print_euler_bernoulli_check(c);
    printf("# CPU time %.2f s\n", seconds_since(start));
}

/* ---- command line ---- */

static void usage(void) {
    fprintf(stderr,
            "usage: beam_reference [--vf V] [--elements N] [--tend T] [--linear] [--euler-bernoulli]\n"
            "                      [--kappa K] [--every DT]\n"
            "no options (or only --kappa): the table of first periods\n");
    exit(2);
}

int main(int argc, char** argv) {
    plate_case c = benchmark_case();
    run_options o = {80, NONLINEAR_TIMOSHENKO, 0, 0.05, 1.0, 0.01};
    int single_run = 0, i;
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--kappa")) {
            c.shear_coefficient = number_argument(argc, argv, &i, usage);
            continue;
        }
        single_run = 1;
        if (!strcmp(argv[i], "--vf")) o.vf = number_argument(argc, argv, &i, usage);
        else if (!strcmp(argv[i], "--elements")) o.elements = (int)number_argument(argc, argv, &i, usage);
        else if (!strcmp(argv[i], "--tend")) o.tend = number_argument(argc, argv, &i, usage);
        else if (!strcmp(argv[i], "--every")) o.print_every = number_argument(argc, argv, &i, usage);
        else if (!strcmp(argv[i], "--linear")) o.kind = LINEAR_TIMOSHENKO;
        else if (!strcmp(argv[i], "--euler-bernoulli")) o.euler_bernoulli = 1;
        else usage();
    }
    if (o.elements < 1 || o.vf <= 0 || o.tend <= 0 || o.print_every <= 0
        || c.shear_coefficient <= 0)
        usage();
    if (!single_run) {
        print_table(&c);
        return 0;
    }
    {
        clock_t start = clock();
        run_result r;
        print_case(&c);
        printf("# %s%s beam, N = %d, v_f = %g\n",
               o.kind == LINEAR_TIMOSHENKO ? "linear" : "nonlinear",
               o.euler_bernoulli ? " Euler-Bernoulli (penalised shear, 1e-3 rotary inertia)"
                                 : " Timoshenko",
               o.elements, o.vf);
        r = simulate(&c, &o);
        printf("# first period %.6f s (%+.3f%% vs thin-plate theory), tip amplitude %.5f m\n",
               r.first_period, 100 * (r.first_period / thin_plate_period(&c, KL_FIRST_MODE) - 1),
               r.tip_amplitude);
        printf("# dt %.3e s, %ld steps, max energy error %.2e, CPU time %.2f s\n", r.time_step,
               r.steps, r.energy_error, seconds_since(start));
    }
    return 0;
}
