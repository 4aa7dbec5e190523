/* floating_block.c - a jelly block dropped into a water tank floats at the depth Archimedes gives
   (the fluid-structure coupling, chapter >>coupling: fluid-structure in sphsolid.h).

   A tank 1 m wide (analytic free-slip walls, open top) holds water 0.5 m deep, at rest and
   hydrostatic (c0 = 10 sqrt(2 g H)). An elastic block 0.2 x 0.2 m of density --rho0 (500: half
   as dense as water; E = 2 MPa, nu 0.3) is released with its bottom --drop above the water (0:
   touching it; --drop 0.1 for a splash) and falls in. The water pushes on the block only through its own pressure: the block's
   particles are moving walls for it. The block alone is damped (--damping c [1/s]: DAMPING in
   the header, the equilibrium does not depend on c; the water is inviscid and undamped), so the
   heave settles while the water keeps its waves (the tank's first sloshing mode, period 1.2 s).
   Its draft, the water level minus the block's bottom, is averaged over the last --window
   seconds (two sloshing periods); the level is that of the water's volume at rho0 plus the
   block's submerged part filling the tank's width (a mean over the waves).
   Archimedes: draft = (rho_block / rho_water) x 0.2 m.

   --dim 3: a cube in a square tank (--width, --depth, --size set all three: e.g. --width 0.4
   --depth 0.2 --size 0.1); the RESULT line adds the water's largest kinetic energy in the
   first and in the last second (water_ke_first, water_ke_last: a tank that churns grows it).

   Build: make examples        Run: ./build/floating_block
   Expect: the block sinks in, bobs and floats with a draft within 1 % of 0.1 m (dp 0.02: -0.8 %);
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

typedef struct {
    output_plan output;
    sps_body water, block;
    double t_end, window, draft_sum, drop;
    double water_ke_first, water_ke_last, last_second_start; /* the water's largest kinetic energy in the first and last second */
    int quiet, draft_rows;
} run_state;

/* The draft: the level of the water (its area at rho0 and the block's part below the level
   fill the tank: level (WIDTH - SIZE) + SIZE bottom = area; in 3D the same with WIDTH^2 and
   SIZE^2 and volumes) minus the block's bottom (its mean height - SIZE/2). */
static double draft_of(const sps_world* w, sps_body water, sps_body block) {
    const sps_real *y = sps_world_field(w, SPS_FIELD_POSITION_Y), *m = sps_world_field(w, SPS_FIELD_MASS);
    double bottom = 0, area = 0;
    int i, first, count, components;
    sps_body_field(w, block, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) bottom += y[i];
    bottom = bottom / count - 0.5 * SIZE;
    sps_body_field(w, water, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) area += m[i] / RHO_WATER;
    if (DIM == 3) return (area - SIZE * SIZE * bottom) / (WIDTH * WIDTH - SIZE * SIZE) - bottom;
    return (area - SIZE * bottom) / (WIDTH - SIZE) - bottom;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[64];
    const double t = sps_world_time(w);
    const double draft = t > 0 ? draft_of(w, s->water, s->block) : -s->drop; /* the bodies' ranges are set at the first step */
    snprintf(extra, sizeof extra, ",%.9g", draft);
    if (output_tick(w, &s->output, extra, &d)) {
        sps_diagnostics dw;
        if (t >= s->t_end - s->window - 1e-12) {
            s->draft_sum += draft;
            s->draft_rows++;
        }
        if (t > 0 && sps_world_diagnostics(w, s->water, &dw) == SPS_OK) {
            if (t <= 1 && dw.kinetic_energy > s->water_ke_first) s->water_ke_first = dw.kinetic_energy;
            if (t >= s->last_second_start && dw.kinetic_energy > s->water_ke_last) s->water_ke_last = dw.kinetic_energy;
        }
    }
    progress(t, s->t_end, s->output.wall0, s->quiet);
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
        COMMON_OPTION_SPECS(c),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def water_def = sps_default_body_def(), block_def = sps_default_body_def();
    sps_world* w;
    sps_diagnostics d;
    sps_body all = {0};
    run_state s;
    sps_real tank_lo[3] = {0, 0, 0}, tank_hi[3], lo[3] = {0, 0, 0}, hi[3];
    double wall, draft, archimedes;

    ex_short_openmp_spin(argv);
    opt_parse(argc, argv, "2D jelly block dropped into a water tank: its floating draft against Archimedes", opts, (int)(sizeof opts / sizeof *opts));
    memset(&s, 0, sizeof s);
    apply_common(&c, &wd, &block_def);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (ex_check_step) */
    wd.dim = DIM;
    wd.dp = (sps_real)dp;
    tank_hi[0] = tank_hi[2] = (sps_real)WIDTH; tank_hi[1] = (sps_real)(DEPTH + 4 * SIZE);
    hi[0] = hi[2] = (sps_real)WIDTH; hi[1] = (sps_real)DEPTH;
    wd.gravity[1] = (sps_real)-G_ACC;
    wd.log = ex_log;
    water_def.name = "water";
    water_def.material.kind = SPS_MATERIAL_FLUID;
    water_def.material.density = RHO_WATER;
    water_def.material.sound_speed = (sps_real)(10 * sqrt(2 * G_ACC * DEPTH));
    block_def.name = "block";
    block_def.damping = (sps_real)damping;
    wd.log = ex_log;
    ex_check(NULL, sps_world_create(&wd, &w));
    ex_check(w, sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP));
    ex_check(w, sps_world_add_body(w, &water_def, &s.water));
    ex_check(w, sps_body_add_box(w, s.water, lo, hi, NULL));
    ex_check(w, sps_body_set_pressure(w, s.water, hydrostatic, NULL));
    ex_check(w, sps_world_add_body(w, &block_def, &s.block));
    lo[0] = lo[2] = (sps_real)(0.5 * (WIDTH - SIZE)); hi[0] = hi[2] = (sps_real)(lo[0] + SIZE);
    lo[1] = DEPTH + drop; hi[1] = lo[1] + SIZE;
    ex_check(w, sps_body_add_box(w, s.block, lo, hi, NULL));

    s.quiet = c.quiet;
    s.t_end = c.t_end;
    s.window = window;
    s.drop = drop;
    s.last_second_start = c.t_end - 1;
    output_open(&s.output, &c, "floating_block", "pressure", ",draft");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    ex_check_step(w, sps_world_advance(w, (sps_real)c.t_end, on_step, &s), &s.output);
    wall = output_close(w, &s.output);

    draft = s.draft_rows ? s.draft_sum / s.draft_rows : draft_of(w, s.water, s.block);
    archimedes = c.rho0 / RHO_WATER * SIZE;
    ex_check(w, sps_world_diagnostics(w, all, &d));
    printf("RESULT case=floating_block dim=%d dp=%g rho_block=%g damping=%g drop=%g window=%g draft=%.5f archimedes=%.5f rel_error=%+.2f%% "
           "ke_end=%.3e water_ke_first=%.4e water_ke_last=%.4e %s particles=%d steps=%ld advection_steps=%ld wall_s=%.2f out=%s\n",
           DIM, dp, c.rho0, damping, drop, window, draft, archimedes, 100 * (draft / archimedes - 1), (double)d.kinetic_energy,
           s.water_ke_first, s.water_ke_last, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, d.advection_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
