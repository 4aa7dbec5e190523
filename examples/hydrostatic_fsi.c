/* hydrostatic_fsi.c - a water column on an elastic plate clamped at both ends settles to the
   static deflection of a clamped-clamped beam under the hydrostatic load (the fluid-structure
   coupling, chapter >>coupling: fluid-structure in sphsolid.h; the reference code's
   hydrostatic_fsi case, with a softer plate so that one time step serves both media).

   The plate spans L = 1 m between its clamps (thickness t = 0.1 m, rho_s 2000, E 1e7 Pa, nu
   0.3, plane strain; clamped: the particles of the 4 dp beyond each end are held). Water H =
   0.2 m deep (rho 1000, c0 = 10 sqrt(2 g H)) stands on it between two rigid side walls (a wall
   body standing on the held ends: the water sees every solid through the coupling), at rest and
   hydrostatic, and loads the plate from t = 0. The plate's own weight is cancelled by an external acceleration +g
   (sps_body_set_acceleration), so the load is the water's alone: q = rho g H, the column's
   weight per length. The plate alone is damped (--damping c, default 2 omega_1 of the dry
   plate: its first mode critically damped; DAMPING in the header: the equilibrium does not
   depend on c); the water is not. We compare the mid-span deflection (the mean displacement of
   the particle columns within dp of x = L/2, over the last --window seconds) with the
   Timoshenko beam, clamped at both ends under a uniform load:
       w = q L^4 / (384 D) + q L^2 / (8 kappa G t),   D = E t^3 / (12 (1 - nu^2)), kappa = 5/6
   (bending 88 %, shear 12 % here; w/t = 0.06, so the membrane stiffening of the held ends, of
   order (w/t)^2, is a few tenths of a %). --load body takes the water away and puts its weight
   on the plate as a body force: the same beam problem without the coupling, so the two runs
   part the coupling's error from the plate's own discretisation error.

   --dim 3: the same plate and water extruded along z over --breadth particle layers (default 8),
   the z axis periodic with that period: every section bends alike, so the strain along z is
   zero and the plane-strain closed form above holds unchanged. --sides walls bounds the breadth
   with free-slip walls at z = 0 and z = breadth instead (the water and the plate both meet them):
   they push the plate's fibres that widen under bending but cannot pull those that narrow (the
   Poisson contraction of the stretched fibres draws them off the walls), so the plate there is
   nearer plane stress, whose D is smaller by (1 - nu^2), and deflects more than the closed form.

   Build: make examples        Run: ./build/hydrostatic_fsi --res 20
   Expect: deflection 6.34 mm; +5.9 % at --res 10 (t/dp; the plate's bending stiffness at 10
   particles across, --load body: +5.0 %), +0.3 % at --res 20, -1.4 % at --res 30; --dim 3: +7.6 %
   at --res 10 (26,560 particles, 2.4 min on one core), +2.1 % at --res 20 (101,120, 20 min; --load
   body +6.7 / +1.4 %: the 3D plate 1.7 points softer than 2D's, ENO-A's zeta), --sides walls +23 %
   at --res 10; CSV with the deflection per row, VTK snapshots, a picture coloured by pressure.
   Smoke: hydrostatic_fsi --res 2 --tend 0.005
   Smoke: hydrostatic_fsi --dim 3 --res 2 --tend 0.005 */
#include "common.h"

#define SPAN 1.0
#define THICK 0.1
#define DEPTH 0.2
#define RHO_WATER 1000.0
#define G_ACC 9.81
#define CLAMP_LAYERS 4 /* held particles beyond each end: more than the kernel's reach, 2h = 2.6 dp */

static sps_real hydrostatic(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(RHO_WATER * G_ACC * (DEPTH - (double)x[1]));
}

/* The plate's weight cancelled (+g), and with --load body the water's weight q per length
   spread over the plate's section instead (-q / (rho_s t)): *user is that acceleration. */
static void plate_load(const sps_real x[3], const sps_real x0[3], const sps_real v[3], sps_real t, sps_real a[3], void* user) {
    (void)x, (void)x0, (void)v, (void)t;
    a[1] = (sps_real)(G_ACC + *(const double*)user);
}

typedef struct {
    output_plan output;
    sps_body plate;
    double dp, t_end, window, sum;
    int rows;
} run_state;

/* The downward displacement at mid-span: the mean over the plate's particles whose reference x
   is within dp of L/2 (two columns, symmetric about it; a Timoshenko deflection is the mean
   over the section). */
static double mid_deflection(const sps_world* w, sps_body plate, double dp) {
    const sps_real *x0 = sps_world_field(w, SPS_FIELD_REFERENCE_X), *y0 = sps_world_field(w, SPS_FIELD_REFERENCE_Y);
    const sps_real* y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    double sum = 0;
    int i, first, count, components, n = 0;
    if (!sps_body_field(w, plate, "density", &components, &first, &count)) return 0; /* before the first step */
    for (i = first; i < first + count; ++i)
        if (fabs(x0[i] - 0.5 * SPAN) < dp) {
            sum += y0[i] - y[i];
            ++n;
        }
    return n ? sum / n : 0;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[64];
    const double t = sps_world_time(w), deflection = t > 0 ? mid_deflection(w, s->plate, s->dp) : 0;
    snprintf(extra, sizeof extra, ",%.9g", deflection);
    if (output_tick(w, &s->output, extra, &d) && t >= s->t_end - s->window - 1e-12) {
        s->sum += deflection;
        s->rows++;
    }
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 0.6, .vtk_every = 0.1, .csv_every = 0.002, .E = 1e7, .nu = 0.3,
                        .rho0 = 2000, .out = "out/hydrostatic_fsi", .jitter = 0, .seed = 1, PNG_DEFAULTS};
    int res = 10, body_load = 0, dim = 2, breadth = 8, walls_sides = 0;
    double damping = 0, window = 0.1, load_acceleration = 0;
    opt_spec opts[] = {
        {"res", OPT_INT, &res, "resolution t/dp (plate thickness 0.1 m)", 2, 40, NULL},
        {"damping", OPT_REAL, &damping, "damping of the plate only [1/s], 0 = 2 omega_1 (the dry plate's first mode: critical)", 0, 1e6, NULL},
        {"window", OPT_REAL, &window, "the deflection is averaged over the last window seconds", 1e-4, 1e4, NULL},
        {"load", OPT_CHOICE, &body_load, "what loads the plate: the water, or (no water) its weight as a body force on the plate", 0, 0, "water|body"},
        {"dim", OPT_INT, &dim, "2, or 3: the plate and the water extruded along z over --breadth layers", 2, 3, NULL},
        {"breadth", OPT_INT, &breadth, "3D: the breadth along z in particle layers (periodic: at least 8, three supports)", 1, 1000, NULL},
        {"sides", OPT_CHOICE, &walls_sides, "3D: what bounds the breadth: a periodic z axis (plane strain), or free-slip walls at z = 0 and z = breadth", 0, 0,
         "periodic|walls"},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def water_def = sps_default_body_def(), plate_def = sps_default_body_def(), wall_def = sps_default_body_def();
    sps_world* w;
    sps_body water, walls, all = {0};
    sps_diagnostics d;
    run_state s;
    double dp, clamp, breadth_m, D, kappa_G_t, q, bending, shear, theory, deflection, omega1, wall;

    ex_options(argc, argv, "water column on a clamped-clamped elastic plate: static deflection against beam theory",
               opts, &c, &wd, &plate_def);
    memset(&s, 0, sizeof s);
    dp = THICK / res;
    clamp = CLAMP_LAYERS * dp;
    breadth_m = dim == 3 ? breadth * dp : 0;
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    D = c.E * THICK * THICK * THICK / (12 * (1 - c.nu * c.nu));
    omega1 = 4.730 * 4.730 * sqrt(D / (c.rho0 * THICK)) / (SPAN * SPAN); /* clamped-clamped Euler-Bernoulli beam */
    if (damping == 0) damping = 2 * omega1;
    wd.dim = dim;
    wd.dp = (sps_real)dp;
    if (dim == 3 && !walls_sides) wd.periodic[2] = (sps_real)breadth_m;
    wd.gravity[1] = (sps_real)-G_ACC;
    water_def.name = "water";
    water_def.material.kind = SPS_MATERIAL_FLUID;
    water_def.material.density = RHO_WATER;
    water_def.material.fluid.sound_speed = (sps_real)(10 * sqrt(2 * G_ACC * DEPTH));
    plate_def.name = "plate";
    plate_def.damping = (sps_real)damping;
    wall_def.name = "side walls";
    wall_def.material.kind = SPS_MATERIAL_RIGID;
    sps_world_create(&wd, &w);
    {
        sps_real lo[3] = {0, 0, 0}, hi[3] = {SPAN, DEPTH, (sps_real)breadth_m}, held_lo[3] = {-1, -1, -1}, held_hi[3] = {0, 1, (sps_real)(breadth_m + 1)};
        if (dim == 3 && walls_sides) { /* free slip: they push the plate's fibres that widen, never pull those that narrow */
            const sps_real z_lo[3] = {0, 0, 0}, z_hi[3] = {0, 0, (sps_real)breadth_m}, up[3] = {0, 0, 1}, down[3] = {0, 0, -1};
            sps_world_add_wall(w, z_lo, up, SPS_WALL_FREE_SLIP);
            sps_world_add_wall(w, z_hi, down, SPS_WALL_FREE_SLIP);
        }
        if (!body_load) {
            sps_world_add_body(w, &water_def, &water);
            sps_body_add_box(w, water, lo, hi, NULL);
            sps_body_set_pressure(w, water, hydrostatic, NULL);
        } else load_acceleration = -RHO_WATER * G_ACC * DEPTH / (c.rho0 * THICK);
        sps_world_add_body(w, &plate_def, &s.plate);
        lo[0] = (sps_real)-clamp; lo[1] = -THICK; hi[0] = (sps_real)(SPAN + clamp); hi[1] = 0;
        sps_body_add_box(w, s.plate, lo, hi, NULL);
        sps_body_constrain_box(w, s.plate, held_lo, held_hi, SPS_AXIS_ALL, NULL, NULL); /* x < 0 */
        held_lo[0] = SPAN; held_hi[0] = 2 * SPAN;
        sps_body_constrain_box(w, s.plate, held_lo, held_hi, SPS_AXIS_ALL, NULL, NULL); /* x > L */
        sps_body_set_acceleration(w, s.plate, plate_load, &load_acceleration);
        sps_world_add_body(w, &wall_def, &walls);
        lo[0] = (sps_real)-clamp; lo[1] = 0; hi[0] = 0; hi[1] = (sps_real)(1.5 * DEPTH);
        sps_body_add_box(w, walls, lo, hi, NULL);
        lo[0] = SPAN; hi[0] = (sps_real)(SPAN + clamp);
        sps_body_add_box(w, walls, lo, hi, NULL);
        sps_world_set_contact(w, walls, s.plate, 0); /* they meet only over the held ends */
    }

    s.dp = dp;
    s.t_end = c.t_end;
    s.window = window;
    output_open(&s.output, &c, "hydrostatic_fsi", "pressure", ",deflection");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);

    deflection = s.rows ? s.sum / s.rows : mid_deflection(w, s.plate, dp);
    q = RHO_WATER * G_ACC * DEPTH;
    kappa_G_t = 5.0 / 6.0 * c.E / (2 * (1 + c.nu)) * THICK;
    bending = q * pow(SPAN, 4) / (384 * D);
    shear = q * SPAN * SPAN / (8 * kappa_G_t);
    theory = bending + shear;
    sps_world_diagnostics(w, all, &d);
    printf("RESULT case=hydrostatic_fsi load=%s dim=%d breadth=%d sides=%s res=%d dp=%g E=%g nu=%g rho_s=%g damping=%g window=%g deflection=%.6e theory=%.6e "
           "rel_error=%+.2f%% bending=%.6e shear=%.6e w_over_t=%.4f ke_end=%.3e %s particles=%d steps=%ld advection_steps=%ld "
           "wall_s=%.2f out=%s\n",
           body_load ? "body" : "water", dim, dim == 3 ? breadth : 0, dim == 3 ? (walls_sides ? "walls" : "periodic") : "none", res, dp, c.E, c.nu, c.rho0, damping, window, deflection, theory, 100 * (deflection / theory - 1), bending, shear,
           deflection / THICK, (double)d.kinetic_energy, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps,
           d.advection_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
