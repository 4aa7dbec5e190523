/* beam_reference - a beam-theory reference for the first period of the 2D oscillating plate.

   What it computes
     The first oscillation period of the clamped cantilever of benchmark A1 (the 2D oscillating
     plate), with the effects that thin-plate (Euler-Bernoulli) theory leaves out:
       - thickness: shear deformation and rotary inertia (Timoshenko beam), which lengthen the
         period of a beam as thick as this one (H/L = 0.1, slenderness L/r = L sqrt(12)/H = 34.6);
       - amplitude: large rotations of the cross-sections (geometric nonlinearity); at v_f = 0.05
         the tip swings about L/2.
     The SPH plate is a 2D continuum; this program is an independent check of how far the SPH
     periods are from the continuum truth, not a model of the SPH clamp (see "Limits").

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
         N = E' A eps,  Q = kappa G A gamma,  M = E' I kappa_b,   A = H, I = H^3 / 12 per unit depth,
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

   Assumptions and limits
     A beam is one-dimensional: cross-sections stay plane (warping enters only through the
     shear coefficient kappa), the transverse normal stress is neglected except through the
     plane-strain modulus E', and the clamp fixes the section's centre and rotation. The SPH
     plate is a 2D continuum held by a block of clamped particles: near the root the stress
     field is two-dimensional and the root is somewhat compliant, which a beam does not see.
     For H/L = 0.1 those root effects are of order (H/L)^2 like the Timoshenko correction
     itself, so this program bounds the thickness effect rather than settling the last 1%.

   Usage
     ./build/beam_reference                  the table below (all runs, about a second or two)
     ./build/beam_reference [--vf 0.05] [--elements 80] [--tend 1] [--linear]
                            [--euler-bernoulli] [--kappa 0.8333] [--every 0.01]
         one run: the tip trace every --every seconds (t, u_x, u_y, theta at the tip, relative
         energy error), then every period found (successive up-crossings) and the first one.
     Any option other than --kappa selects the single run; --kappa alone changes the table.

   Expected output (default run; the numbers of bench/results/beam_reference.txt)
     A table of first periods for v_f = 0.001, 0.01, 0.03, 0.05: the nonlinear Timoshenko beam at
     N = 20, 40, 80, 160 elements, the linear Timoshenko beam (N = 160), thin-plate theory and the
     tip amplitude of the first cycle; then the Euler-Bernoulli check (the beam code with
     --euler-bernoulli at v_f = 0.001 against 0.2541 s, within 0.1%), the time steps and the run
     time. Build: make build/beam_reference (gcc -std=c99 -O2, libc and libm only). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const double PI = 3.14159265358979323846;
static const double KL_FIRST_MODE = 1.875; /* the benchmark's k L (the root is 1.8751040687) */
static const double SAFETY = 0.8;          /* fraction of the stable time step used */
static const double EB_SHEAR_FACTOR = 1e3;   /* --euler-bernoulli: shear rigidity x this */
static const double EB_INERTIA_FACTOR = 1e-3; /* --euler-bernoulli: rotary inertia x this */

/* ---- the case ---- */

typedef struct {
    double length, thickness, density, youngs, poisson, shear_coefficient;
} plate_case;

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

/* the benchmark's velocity scale (a bulk-like wave speed of the SPH setup) */
static double velocity_scale(const plate_case* c) {
    return sqrt(c->youngs / (3 * (1 - 2 * c->poisson) * c->density));
}

/* thin-plate (Euler-Bernoulli, plane strain) first period for a given k L */
static double thin_plate_period(const plate_case* c, double kL) {
    double k = kL / c->length;
    double omega2 = plane_strain_modulus(c) * c->thickness * c->thickness * pow(k, 4)
                    / (12 * c->density);
    return 2 * PI / sqrt(omega2);
}

/* the Euler-Bernoulli first mode of a cantilever and its slope, x from the clamp */
static double mode_shape(double k, double L, double x) {
    return (sin(k * L) + sinh(k * L)) * (cos(k * x) - cosh(k * x))
           - (cos(k * L) + cosh(k * L)) * (sin(k * x) - sinh(k * x));
}

static double mode_slope(double k, double L, double x) {
    return k * ((sin(k * L) + sinh(k * L)) * (-sin(k * x) - sinh(k * x))
                - (cos(k * L) + cosh(k * L)) * (cos(k * x) - cosh(k * x)));
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
    run_result r = {0, 0, 0, 0, 0};
    double dt = stable_time_step(&b), t = 0, next_print = 0;
    double strain_energy, initial_energy, last_up_crossing = 0;
    double previous_tip = 0;
    int tip = b.nodes - 1, down_crossings = 0, periods = 0;
    r.time_step = dt;
    set_initial_velocity(&b, c, o->vf);
    strain_energy = compute_forces(&b);
    initial_energy = kinetic_energy(&b) + strain_energy;
    if (o->print_every > 0)
        printf("#        t       tip u_x      tip u_y    tip theta   energy err\n");
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
    beam_free(&b);
    return r;
}

/* ---- the default table ---- */

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
    printf("# thin-plate theory: T = %.6f s (kL = 1.875), %.6f s (kL = 1.8751040687)\n",
           thin_plate_period(c, KL_FIRST_MODE), thin_plate_period(c, 1.8751040687));
}

static void print_table(const plate_case* c) {
    static const double vfs[] = {0.001, 0.01, 0.03, 0.05};
    static const int meshes[] = {20, 40, 80, 160};
    enum { N_VF = 4, N_MESH = 4, FINEST = 160 };
    double thin = thin_plate_period(c, KL_FIRST_MODE);
    clock_t start = clock();
    int i, m;
    print_case(c);
    printf("# first period [s]: nonlinear Timoshenko beam at N elements, linear Timoshenko (N = %d),\n"
           "# thin-plate theory; tip amplitude = largest tip deflection of the first cycle (N = %d)\n",
           FINEST, FINEST);
    printf("#   v_f    nonlin N=20   N=40      N=80      N=160   | linear    | theory  | nonlin/linear |"
           " tip amplitude [m]\n");
    for (i = 0; i < N_VF; i++) {
        run_result nonlinear = {0, 0, 0, 0, 0}, linear;
        run_options o;
        printf("%7.3f  ", vfs[i]);
        for (m = 0; m < N_MESH; m++) {
            o = table_run(meshes[m], NONLINEAR_TIMOSHENKO, vfs[i]);
            nonlinear = simulate(c, &o);
            printf(" %.6f", nonlinear.first_period);
        }
        o = table_run(FINEST, LINEAR_TIMOSHENKO, vfs[i]);
        linear = simulate(c, &o);
        printf(" | %.6f | %.4f  | %+.3f%%       | %.5f\n", linear.first_period, thin,
               100 * (nonlinear.first_period / linear.first_period - 1), nonlinear.tip_amplitude);
    }
    {
        run_options o = table_run(FINEST, LINEAR_TIMOSHENKO, 0.001);
        printf("# linear Timoshenko vs thin-plate theory (N = %d): %+.3f%%\n", FINEST,
               100 * (simulate(c, &o).first_period / thin - 1));
    }
    printf("# time step (safety %.1f): ", SAFETY);
    for (m = 0; m < N_MESH; m++) {
        run_options o = table_run(meshes[m], NONLINEAR_TIMOSHENKO, 0.001);
        beam b = beam_create(c, &o);
        printf("N=%d %.3e s%s", meshes[m], stable_time_step(&b), m + 1 < N_MESH ? ", " : "\n");
        beam_free(&b);
    }
    printf("# Euler-Bernoulli check (--euler-bernoulli --linear, v_f 0.001) against %.6f s:\n", thin);
    for (m = 1; m < N_MESH; m++) {
        run_options o = table_run(meshes[m], LINEAR_TIMOSHENKO, 0.001);
        run_result r;
        o.euler_bernoulli = 1;
        r = simulate(c, &o);
        printf("#   N=%3d dt %.3e s: T = %.6f s (%+.3f%%)\n", meshes[m], r.time_step, r.first_period,
               100 * (r.first_period / thin - 1));
    }
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

static double number_argument(int argc, char** argv, int* i) {
    char* end;
    double value;
    if (*i + 1 >= argc) usage();
    value = strtod(argv[++*i], &end);
    if (*end != '\0') usage();
    return value;
}

int main(int argc, char** argv) {
    plate_case c = benchmark_case();
    run_options o = {80, NONLINEAR_TIMOSHENKO, 0, 0.05, 1.0, 0.01};
    int single_run = 0, i;
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--kappa")) {
            c.shear_coefficient = number_argument(argc, argv, &i);
            continue;
        }
        single_run = 1;
        if (!strcmp(argv[i], "--vf")) o.vf = number_argument(argc, argv, &i);
        else if (!strcmp(argv[i], "--elements")) o.elements = (int)number_argument(argc, argv, &i);
        else if (!strcmp(argv[i], "--tend")) o.tend = number_argument(argc, argv, &i);
        else if (!strcmp(argv[i], "--every")) o.print_every = number_argument(argc, argv, &i);
        else if (!strcmp(argv[i], "--linear")) o.kind = LINEAR_TIMOSHENKO;
        else if (!strcmp(argv[i], "--euler-bernoulli")) o.euler_bernoulli = 1;
        else usage();
    }
    if (o.elements < 1 || o.vf <= 0 || o.tend <= 0 || o.print_every <= 0 || c.shear_coefficient <= 0)
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
