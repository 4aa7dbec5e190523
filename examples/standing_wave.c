/* standing_wave.c - the first sloshing mode of a tank: its period against linear theory,
   omega^2 = g k tanh(k H), and its decay against Lamb's viscous rate 2 nu k^2.
   Water H = 0.5 m deep fills a tank of length L = pi / k between free-slip walls (analytic
   walls, open top), so that the tank holds half a wavelength: k H = --kh (0.5, 1, 2, 3 in the
   validation record; L rounded to whole columns of particles, k from it). It starts on the lattice, flat, at its hydrostatic pressure, with the
   velocity of the standing wave of amplitude a = --amplitude H as it passes through the level
   (linear theory: u = -a omega cosh(k y)/sinh(k H) sin(k x), v = a omega sinh(k y)/sinh(k H)
   cos(k x), y up from the floor). The wave's amplitude A(t) is the first Fourier mode of the
   surface particles' rise, (2/N) sum (y_i - y_i(0)) cos(k x_i); the period is the mean spacing
   of its zero crossings, the decay the ratio of its last peak to its first, per period.
   Build: make examples        Run: ./build/standing_wave [--kh 1] [--res 50]
   Expect: period within 1 % of linear theory at depth/dp 100 (bench/VALIDATION.md, "Still
   water"); an inviscid wave keeps its amplitude; CSV with A(t), VTK snapshots.
   Smoke: standing_wave --res 10 --periods 0.5 */
#include "common.h"
#define DEPTH 0.5
#define G_ACC 9.81
#define RHO_WATER 1000.0

typedef struct {
    double k, omega, amplitude;
} wave;

static sps_real hydrostatic(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(RHO_WATER * G_ACC * (DEPTH - (double)x[1]));
}

/* Linear theory's velocity of the standing wave as the surface passes through the level. */
static void wave_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const wave* s = (const wave*)user;
    const double scale = s->amplitude * s->omega / sinh(s->k * DEPTH);
    v[0] = (sps_real)(-scale * cosh(s->k * x[1]) * sin(s->k * x[0]));
    v[1] = (sps_real)(scale * sinh(s->k * x[1]) * cos(s->k * x[0]));
    v[2] = 0;
}

typedef struct {
    output_plan output;
    period_detector period;
    wave theory;
    int* surface_ids;   /* the particles of the top layer at the start */
    double* surface_y0; /* their heights then */
    int* slot_of_id;
    int nsurface;
    double amplitude_now, peak, first_peak, last_peak;
    int peaks;
} run_state;

/* The first Fourier mode of the surface particles' rise. */
static double surface_mode(const sps_world* w, run_state* s) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const int* ids = sps_world_particle_ids(w);
    const int n = sps_world_particle_count(w);
    double sum = 0;
    int i;
    for (i = 0; i < n; ++i) s->slot_of_id[ids[i]] = i;
    for (i = 0; i < s->nsurface; ++i) {
        const int slot = s->slot_of_id[s->surface_ids[i]];
        sum += (y[slot] - s->surface_y0[i]) * cos(s->theory.k * x[slot]);
    }
    return 2 * sum / s->nsurface;
}

static void on_step(sps_world* w, run_state* s) {
    sps_diagnostics d;
    char extra[64];
    const double t = sps_world_time(w), a = surface_mode(w, s);
    if (period_feed(&s->period, t, a)) {} /* crossings are read at the end */
    if (s->period.n > 0 && s->period.n != s->peaks) { /* a half cycle ended: its peak */
        if (s->peaks == 0) s->first_peak = s->peak;
        s->last_peak = s->peak;
        s->peaks = s->period.n;
        s->peak = 0;
    }
    if (fabs(a) > s->peak) s->peak = fabs(a);
    s->amplitude_now = a;
    snprintf(extra, sizeof extra, ",%.9g", a);
    output_tick(w, &s->output, extra, &d);
}

int main(int argc, char** argv) {
    common_options c = {.cfl = 0.4, .t_end = 0, .vtk_every = 0, .csv_every = 0.01, .rho0 = RHO_WATER, .out = "out/standing_wave", .h_over_dp = 2,
                        PNG_DEFAULTS};
    double kh = 1, res = 50, amplitude = 0.01, periods = 5, viscosity = 0, mach = 10;
    opt_spec opts[] = {
        {"kh", OPT_REAL, &kh, "k H of the first mode (tank length pi H / kh)", 0.1, 6, NULL},
        {"res", OPT_REAL, &res, "depth / dp", 4, 400, NULL},
        {"amplitude", OPT_REAL, &amplitude, "wave amplitude / depth", 1e-4, 0.1, NULL},
        {"periods", OPT_REAL, &periods, "run length in periods of linear theory (--tend overrides)", 0.01, 1000, NULL},
        {"viscosity", OPT_REAL, &viscosity, "dynamic viscosity mu [Pa s] (0: inviscid)", 0, 1e3, NULL},
        {"mach-factor", OPT_REAL, &mach, "c0 = factor sqrt(g H)", 2, 100, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def water_def = sps_default_body_def();
    sps_world* w;
    sps_body water;
    run_state s;
    sps_real tank_lo[3] = {0, 0, 0}, tank_hi[3], lo[3] = {0, 0, 0}, hi[3];
    double dp, length, period_theory, period = -1, decay = 1, lamb = 1, wall;
    const sps_real* y;
    int i, n, k, samples;
    ex_options(argc, argv, "2D standing gravity wave in a tank: period and decay against linear theory", opts, &c, &wd, &water_def);
    memset(&s, 0, sizeof s);
    dp = DEPTH / res;
    length = dp * floor(PI / kh * DEPTH / dp + 0.5); /* whole columns of particles: the walls dp/2 from the water's outer columns */
    s.theory.k = PI / length;
    kh = s.theory.k * DEPTH;
    s.theory.omega = sqrt(G_ACC * s.theory.k * tanh(kh));
    s.theory.amplitude = amplitude * DEPTH;
    period_theory = 2 * PI / s.theory.omega;
    if (c.t_end <= 0) c.t_end = periods * period_theory;
    water_def.material = sps_default_material_def(); /* the shared options' solid parameters are not the water's */
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-G_ACC;
    water_def.name = "water";
    water_def.material.kind = SPS_MATERIAL_FLUID;
    water_def.material.density = RHO_WATER;
    water_def.material.fluid.sound_speed = (sps_real)(mach * sqrt(G_ACC * DEPTH));
    water_def.material.viscosity = (sps_real)viscosity;
    ex_unset_unread(&water_def);
    tank_hi[0] = hi[0] = (sps_real)length;
    tank_hi[1] = 4 * DEPTH;
    hi[1] = DEPTH;
    tank_hi[2] = hi[2] = 0;
    sps_world_create(&wd, &w);
    sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP);
    sps_world_add_body(w, &water_def, &water);
    sps_body_add_box(w, water, lo, hi, NULL);
    sps_body_set_pressure(w, water, hydrostatic, NULL);
    sps_body_set_velocity(w, water, wave_velocity, &s.theory);
    /* the top layer: its particles' ids and heights */
    n = sps_world_particle_count(w);
    y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    s.surface_ids = (int*)malloc(sizeof(int) * (size_t)n);
    s.surface_y0 = (double*)malloc(sizeof(double) * (size_t)n);
    s.slot_of_id = (int*)malloc(sizeof(int) * (size_t)n);
    if (!s.surface_ids || !s.surface_y0 || !s.slot_of_id) { fprintf(stderr, "out of memory\n"); return 1; }
    for (i = 0; i < n; ++i) /* the water is the only body */
        if (y[i] > DEPTH - dp) {
            s.surface_ids[s.nsurface] = sps_world_particle_ids(w)[i];
            s.surface_y0[s.nsurface++] = y[i];
        }
    output_open(&s.output, &c, "standing_wave", "velocity", ",amplitude");
    on_step(w, &s);
    samples = (int)ceil(c.t_end / period_theory * 200); /* 200 samples a period for the crossings and peaks */
    for (k = 1; k <= samples; ++k) {
        ex_check_step(w, sps_world_advance(w, (sps_real)(c.t_end * k / samples), NULL, NULL), &s.output);
        on_step(w, &s);
    }
    wall = output_close(w, &s.output);
    if (s.period.n >= 3) { /* the mean spacing of the crossings after the first (the start is one) */
        const int last = (s.period.n < 64 ? s.period.n : 64) - 1;
        period = 2 * (s.period.crossing[last] - s.period.crossing[0]) / last;
    }
    if (s.peaks >= 3 && s.first_peak > 0) { /* peaks are half a period apart */
        decay = pow(s.last_peak / s.first_peak, 2.0 / (s.peaks - 1));
        lamb = exp(-2 * viscosity / RHO_WATER * s.theory.k * s.theory.k * period_theory);
    }
    printf("RESULT case=standing_wave kh=%g res=%g h_over_dp=%g amplitude=%g viscosity=%g c0=%.4g period=%.5f theory=%.5f err=%+.2f%% "
           "decay_per_period=%.4f lamb=%.4f first_peak=%.4g last_peak=%.4g half_periods=%d particles=%d steps=%ld wall_s=%.2f out=%s\n",
           kh, res, c.h_over_dp, amplitude, viscosity, (double)water_def.material.fluid.sound_speed, period, period_theory,
           period > 0 ? 100 * (period / period_theory - 1) : 0.0, decay, lamb, s.first_peak / s.theory.amplitude,
           s.last_peak / s.theory.amplitude, s.peaks, n, sps_world_substep_count(w), wall, c.out);
    free(s.surface_ids);
    free(s.surface_y0);
    free(s.slot_of_id);
    sps_world_destroy(w);
    return 0;
}
