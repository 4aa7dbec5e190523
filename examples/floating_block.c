/* floating_block.c - a jelly block dropped into a water tank floats at the depth Archimedes gives
   (the fluid-structure coupling, chapter >>coupling: fluid-structure in sphsolid.h).

   A tank 1 m wide (analytic free-slip walls, open top) holds water 0.5 m deep, at rest and
   hydrostatic (c0 = 10 sqrt(2 g H)). An elastic block 0.2 x 0.2 m of density --rho0 (500: half
   as dense as water; E = 2 MPa, nu 0.3) is released with its bottom --drop above the water (0:
   touching it; --drop 0.1 for a splash) and falls in. The water pushes on the block only through its own pressure: the block's
   particles are moving walls for it. The block alone is damped (--damping c [1/s]: DAMPING in
   the header, the equilibrium does not depend on c; the water is inviscid and undamped), so the
   heave settles while the water keeps its waves (the tank's first sloshing mode, period 1.2 s).
   Its draft, the water level minus the block's bottom, is averaged over 1.5-2.5 s and over the
   last --window seconds (two sloshing periods); the level is that of the water's volume as it
   is, sum m / rho (compressed by its own pressure), plus the block's submerged part, filling
   the tank's width (a mean over the waves; the volume at rho0, sum m / rho0, would put it
   higher by the column's mean compression, H (g H / (2 c0^2)) = 1.25 mm here). Archimedes:
   draft = (rho_block / rho_water) x 0.2 m. The RESULT line adds the water's mean pressure over
   the same two windows, their difference against rho0 g H (a tank whose pressure creeps shows
   it) and the water's mass at the end against its start.

   --dim 3: a cube in a square tank (--width, --depth, --size set all three: e.g. --width 0.4
   --depth 0.2 --size 0.1); the RESULT line adds the water's largest kinetic energy in the
   first and in the last second (water_ke_first, water_ke_last: a tank that churns grows it).

   Build: make examples        Run: ./build/floating_block
   Expect: the block sinks in, bobs and floats (the water on the hexagonal lattice: FLUIDS);
   dp 0.02, --tend 30 --window 2: draft -0.8 % from the free surface over 28-30 s (-2.9 % at
   2 s, still settling), -3.1 % from the water's volume; pressure drift +0.11 % of rho g H; the
   mass exact; dp 0.04: -5.6 % (2.5 particles of draft).
   CSV with the draft per row, VTK snapshots, a picture coloured by pressure.
   Smoke: floating_block --dp 0.05 --tend 0.01 */
#include "common.h"

#define RHO_WATER 1000.0
#define G_ACC 9.81

static double WIDTH = 1.0, DEPTH = 0.5, SIZE = 0.2; /* the tank's width (and breadth in 3D), the water's depth, the block's side */
static int DIM = 2;

static sps_real hydrostatic(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(RHO_WATER * G_ACC * (DEPTH - (double)x[1]));
}

/* The water's mean pressure [Pa] and its mass [kg] (kg/m in 2D). */
static void water_state(const sps_world* w, sps_body water, double* mean_pressure, double* mass) {
    const sps_real *p = sps_world_field(w, SPS_FIELD_PRESSURE), *m = sps_world_field(w, SPS_FIELD_MASS);
    int i, first, count, components;
    *mean_pressure = *mass = 0;
    sps_body_field(w, water, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) {
        *mean_pressure += p[i] / count;
        *mass += m[i];
    }
}

/* A running mean over the output rows of a time window. */
typedef struct {
    double draft, draft_volume, pressure;
    int rows;
} window_mean;
static void window_add(window_mean* m, double draft, double draft_volume, double pressure) {
    m->draft += draft;
    m->draft_volume += draft_volume;
    m->pressure += pressure;
    m->rows++;
}

#define EARLY_FROM 1.5 /* the early window [s]: the draft "at 2 s" */
#define EARLY_TO 2.5

typedef struct {
    output_plan output;
    sps_body water, block;
    window_mean early, late;
    double t_end, window, drop, mass_start, dp;
    double water_ke_first, water_ke_last, last_second_start; /* the water's largest kinetic energy in the first and last second */
} run_state;

/* The block's bottom: its particles' mean height less SIZE/2. */
static double block_bottom(const sps_world* w, sps_body block) {
    const sps_real* y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    double bottom = 0;
    int i, first, count, components;
    sps_body_field(w, block, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) bottom += y[i];
    return bottom / count - 0.5 * SIZE;
}

/* The draft from the free surface: the mean over the tank's dp-wide columns (dp x dp in 3D)
   clear of the block (beyond 2 dp from its sides) of the highest water particle plus dp/2,
   less the block's bottom. NaN if no column has water. */
static double draft_of(const sps_world* w, sps_body water, sps_body block, double dp) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* z = sps_world_field(w, SPS_FIELD_POSITION_Z);
    const int n = (int)(WIDTH / dp + 0.5), columns = DIM == 3 ? n * n : n;
    double* top = malloc(sizeof *top * (size_t)columns), level = 0;
    int i, c, used = 0, first, count, components;
    if (!top) return NAN;
    for (c = 0; c < columns; ++c) top[c] = -1e30;
    sps_body_field(w, water, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) {
        const int cx = (int)(x[i] / dp), cz = DIM == 3 ? (int)(z[i] / dp) : 0;
        if (cx < 0 || cx >= n || cz < 0 || cz >= n) continue;
        c = cz * n + cx;
        if (y[i] > top[c]) top[c] = y[i];
    }
    for (c = 0; c < columns; ++c) {
        const double ax = fabs((c % n + 0.5) * dp - 0.5 * WIDTH), az = DIM == 3 ? fabs((c / n + 0.5) * dp - 0.5 * WIDTH) : 0;
        if ((ax > az ? ax : az) < 0.5 * SIZE + 2 * dp || !(top[c] > -1e29)) continue;
        level += top[c] + 0.5 * dp;
        ++used;
    }
    free(top);
    return used ? level / used - block_bottom(w, block) : NAN;
}

/* The draft from the water's volume: the level of the water's area sum m / rho (compressed by
   its pressure as it is) and the block's part below the level filling the tank (level (WIDTH -
   SIZE) + SIZE bottom = area; in 3D with WIDTH^2, SIZE^2 and volumes), less the bottom. */
static double draft_volume_of(const sps_world* w, sps_body water, sps_body block) {
    const sps_real *m = sps_world_field(w, SPS_FIELD_MASS), *rho = sps_world_field(w, SPS_FIELD_DENSITY);
    const double bottom = block_bottom(w, block);
    double area = 0;
    int i, first, count, components;
    sps_body_field(w, water, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) area += m[i] / rho[i];
    if (DIM == 3) return (area - SIZE * SIZE * bottom) / (WIDTH * WIDTH - SIZE * SIZE) - bottom;
    return (area - SIZE * bottom) / (WIDTH - SIZE) - bottom;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[64];
    const double t = sps_world_time(w);
    /* the bodies' ranges are set at the first step */
    const double draft = t > 0 ? draft_of(w, s->water, s->block, s->dp) : -s->drop;
    const double draft_volume = t > 0 ? draft_volume_of(w, s->water, s->block) : -s->drop;
    snprintf(extra, sizeof extra, ",%.9g,%.9g", draft, draft_volume);
    if (output_tick(w, &s->output, extra, &d)) {
        sps_diagnostics dw;
        double pressure = 0, mass = 0;
        if (t > 0) water_state(w, s->water, &pressure, &mass);
        if (t >= EARLY_FROM && t <= EARLY_TO) window_add(&s->early, draft, draft_volume, pressure);
        if (t >= s->t_end - s->window - 1e-12) window_add(&s->late, draft, draft_volume, pressure);
        if (t > 0 && sps_world_diagnostics(w, s->water, &dw) == SPS_OK) {
            if (t <= 1 && dw.kinetic_energy > s->water_ke_first) s->water_ke_first = dw.kinetic_energy;
            if (t >= s->last_second_start && dw.kinetic_energy > s->water_ke_last) s->water_ke_last = dw.kinetic_energy;
        }
    }
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 4, .vtk_every = 0.1, .csv_every = 0.005, .E = 2e6, .nu = 0.3,
                        .rho0 = 500, .out = "out/floating_block", .jitter = 0, .seed = 1, PNG_DEFAULTS};
    double dp = 0.02, drop = 0, damping = 10, window = 2.4;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (block 0.2 m, water 0.5 m deep)", 2e-3, 0.05, NULL},
        {"drop", OPT_REAL, &drop, "height of the block's bottom above the water at the start [m]", 0, 1, NULL},
        {"damping", OPT_REAL, &damping, "damping of the block only [1/s] (0: none)", 0, 1e4, NULL},
        {"window", OPT_REAL, &window, "the draft is averaged over the last window seconds", 1e-3, 1e4, NULL},
        {"dim", OPT_INT, &DIM, "2 or 3 (3: a cube in a square tank)", 2, 3, NULL},
        {"width", OPT_REAL, &WIDTH, "tank width [m] (and breadth in 3D)", 0.05, 10, NULL},
        {"depth", OPT_REAL, &DEPTH, "water depth [m]", 0.02, 10, NULL},
        {"size", OPT_REAL, &SIZE, "block side [m]", 0.01, 5, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def water_def = sps_default_body_def(), block_def = sps_default_body_def();
    sps_world* w;
    sps_diagnostics d;
    sps_body all = {0};
    int water_count;
    run_state s;
    sps_real tank_lo[3] = {0, 0, 0}, tank_hi[3], lo[3] = {0, 0, 0}, hi[3];
    double wall, draft, draft_volume, archimedes, early_draft, early_draft_volume, early_pressure, late_pressure, mass_end;

    ex_options(argc, argv, "2D jelly block dropped into a water tank: its floating draft against Archimedes", opts, &c, &wd, &block_def);
    memset(&s, 0, sizeof s);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    wd.dim = DIM;
    wd.dp = (sps_real)dp;
    tank_hi[0] = tank_hi[2] = (sps_real)WIDTH; tank_hi[1] = (sps_real)(DEPTH + 4 * SIZE);
    hi[0] = hi[2] = (sps_real)WIDTH; hi[1] = (sps_real)DEPTH;
    wd.gravity[1] = (sps_real)-G_ACC;
    water_def.name = "water";
    water_def.material.kind = SPS_MATERIAL_FLUID;
    water_def.material.density = RHO_WATER;
    water_def.material.fluid.sound_speed = (sps_real)(10 * sqrt(2 * G_ACC * DEPTH));
    block_def.name = "block";
    block_def.damping = (sps_real)damping;
    sps_world_create(&wd, &w);
    sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP);
    sps_world_add_body(w, &water_def, &s.water);
    sps_body_add_box(w, s.water, lo, hi, NULL);
    sps_body_set_pressure(w, s.water, hydrostatic, NULL);
    water_count = sps_world_particle_count(w);
    sps_world_add_body(w, &block_def, &s.block);
    lo[0] = lo[2] = (sps_real)(0.5 * (WIDTH - SIZE)); hi[0] = hi[2] = (sps_real)(lo[0] + SIZE);
    lo[1] = DEPTH + drop; hi[1] = lo[1] + SIZE;
    sps_body_add_box(w, s.block, lo, hi, NULL);

    s.t_end = c.t_end;
    s.window = window;
    s.drop = drop;
    s.last_second_start = c.t_end - 1;
    s.dp = dp;
    output_open(&s.output, &c, "floating_block", "pressure", ",draft,draft_volume");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    {
        const sps_real* m = sps_world_field(w, SPS_FIELD_MASS);
        int i;
        for (i = 0; i < water_count; ++i) s.mass_start += m[i]; /* the water's particles come first */
    }
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);

    draft = s.late.rows ? s.late.draft / s.late.rows : draft_of(w, s.water, s.block, dp);
    draft_volume = s.late.rows ? s.late.draft_volume / s.late.rows : draft_volume_of(w, s.water, s.block);
    early_draft = s.early.rows ? s.early.draft / s.early.rows : NAN; /* NaN: the run ends before the early window */
    early_draft_volume = s.early.rows ? s.early.draft_volume / s.early.rows : NAN;
    early_pressure = s.early.rows ? s.early.pressure / s.early.rows : NAN;
    water_state(w, s.water, &late_pressure, &mass_end);
    if (s.late.rows) late_pressure = s.late.pressure / s.late.rows;
    archimedes = c.rho0 / RHO_WATER * SIZE;
    sps_world_diagnostics(w, all, &d);
    printf("RESULT case=floating_block dim=%d dp=%g rho_block=%g damping=%g drop=%g window=%g draft=%.5f archimedes=%.5f rel_error=%+.2f%% "
           "draft_2s=%.5f rel_error_2s=%+.2f%% draft_volume=%.5f rel_error_volume=%+.2f%% rel_error_volume_2s=%+.2f%% pressure_drift=%+.3f%% "
           "water_mass_ratio=%.12f "
           "ke_end=%.3e water_ke_first=%.4e water_ke_last=%.4e %s particles=%d steps=%ld advection_steps=%ld wall_s=%.2f out=%s\n",
           DIM, dp, c.rho0, damping, drop, window, draft, archimedes, 100 * (draft / archimedes - 1), early_draft,
           100 * (early_draft / archimedes - 1), draft_volume, 100 * (draft_volume / archimedes - 1), 100 * (early_draft_volume / archimedes - 1),
           100 * (late_pressure - early_pressure) / (RHO_WATER * G_ACC * DEPTH), mass_end / s.mass_start,
           (double)d.kinetic_energy, s.water_ke_first, s.water_ke_last, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps,
           d.advection_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
