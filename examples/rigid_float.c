/* rigid_float.c - a free rigid box floating in a water tank: its draft against Archimedes, and
   whether it floats upright or capsizes against the metacentric criterion (FREE RIGID BODIES and
   FLUID-STRUCTURE in the header's manual).

   The tank of floating_block.c: 1 m wide (analytic free-slip walls, open top), water 0.5 m deep
   at rest and hydrostatic (c0 = 10 sqrt(2 g H)), h = 1.3 dp as in the fluid-structure examples
   (water held a box fixed at its Archimedes draft with 3.7 % more than rho g V at dp 0.02 and 3.5 %
   at 0.01, so the box floats that much high; at h = 2 dp the held box got 0.31 % more, but the
   floating box stood off the water and floated 14 % high: bench/VALIDATION.md, "Free rigid bodies"). A free rigid box (material.kind =
   SPS_MATERIAL_RIGID_DYNAMIC) --width x --height of density --rho0 is set on the water (its
   bottom touching it), tilted by --tilt degrees, and let go; its heave and roll are damped
   (--damping c [1/s] on its velocity and angular momentum: the equilibrium does not depend on c).
   The water pushes on it only through its pressure (its particles are moving walls for the
   water); their sum of forces and torques moves it.
   Archimedes: the box floats where its submerged area is rho_box / rho_water of its area. Upright
   (tilt 0) that is the draft d = (rho_box / rho_water) height; the metacentric height of the
   upright box, GM = I_waterline / V_displaced - (z_G - z_B) = width^2 / (12 d) - (height - d) / 2
   (per unit length in 2D), says whether upright is stable (GM > 0) or the box capsizes (GM < 0;
   a square of density 500 comes to rest on a corner). Measured, averaged over the last --window
   seconds: the tilt angle, upright = |tilt| < 10 degrees, and the draft, the water level minus
   the box's lowest corner, next to Archimedes' draft at the box's measured tilt (the depth of
   the lowest corner below a waterline that cuts off rho_box / rho_water of its area). The level
   is that of the water's volume at rho0 plus the box's submerged part filling the tank's width.

   Build: make build/rigid_float     Run: ./build/rigid_float     (the square: --width 0.2 --height 0.2)
   Smoke: rigid_float --dp 0.05 --tend 0.01 */
#include "common.h"

#define WIDTH 1.0
#define DEPTH 0.5
#define RHO_WATER 1000.0
#define G_ACC 9.81

static sps_real hydrostatic(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(RHO_WATER * G_ACC * (DEPTH - (double)x[1]));
}

typedef struct {
    double half[2]; /* half width and height */
    double centre[2], angle;
} box_pose;

/* The area of the box below the line y = level (its polygon clipped by the half-plane). */
static double area_below(const box_pose* b, double level) {
    const double c = cos(b->angle), s = sin(b->angle), sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    double px[4], py[4], qx[8], qy[8], area = 0;
    int k, n = 0;
    for (k = 0; k < 4; ++k) {
        px[k] = b->centre[0] + c * sx[k] * b->half[0] - s * sy[k] * b->half[1];
        py[k] = b->centre[1] + s * sx[k] * b->half[0] + c * sy[k] * b->half[1];
    }
    for (k = 0; k < 4; ++k) { /* Sutherland-Hodgman against y <= level */
        const int l = (k + 1) % 4;
        const int in_k = py[k] <= level, in_l = py[l] <= level;
        if (in_k) { qx[n] = px[k]; qy[n] = py[k]; ++n; }
        if (in_k != in_l) {
            const double f = (level - py[k]) / (py[l] - py[k]);
            qx[n] = px[k] + f * (px[l] - px[k]); qy[n] = level; ++n;
        }
    }
    for (k = 0; k < n; ++k) area += qx[k] * qy[(k + 1) % n] - qx[(k + 1) % n] * qy[k];
    return 0.5 * fabs(area);
}
static double lowest_corner(const box_pose* b) {
    return b->centre[1] - fabs(sin(b->angle)) * b->half[0] - fabs(cos(b->angle)) * b->half[1];
}

typedef struct {
    output_plan output;
    sps_body water, box;
    box_pose pose;
    double t_end, window, draft_sum, archimedes_sum, tilt_sum, ratio;
    int rows;
} run_state;

/* The box's pose, the water level (the water's area at rho0 plus the box's part below the level
   fill the tank: bisection), its draft and Archimedes' draft at its tilt. */
static void measure(sps_world* w, run_state* s, double* draft, double* archimedes) {
    const sps_real* m = sps_world_field(w, SPS_FIELD_MASS);
    sps_rigid_state st;
    double water = 0, lo = 0, hi = 2, bottom;
    int i, first, count, components, k;
    sps_body_rigid_state(w, s->box, &st);
    s->pose.centre[0] = st.position[0];
    s->pose.centre[1] = st.position[1];
    s->pose.angle = atan2(st.rotation[3], st.rotation[0]);
    sps_body_field(w, s->water, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) water += m[i] / RHO_WATER;
    for (k = 0; k < 60; ++k) {
        const double level = 0.5 * (lo + hi);
        if (water + area_below(&s->pose, level) > WIDTH * level) lo = level; else hi = level;
    }
    bottom = lowest_corner(&s->pose);
    *draft = lo - bottom;
    for (lo = 0, hi = 4 * (s->pose.half[0] + s->pose.half[1]), k = 0; k < 60; ++k) { /* Archimedes at this tilt */
        const double depth = 0.5 * (lo + hi);
        if (area_below(&s->pose, bottom + depth) < s->ratio * 4 * s->pose.half[0] * s->pose.half[1]) lo = depth; else hi = depth;
    }
    *archimedes = lo;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[96];
    const double t = sps_world_time(w);
    double draft = 0, archimedes = 0;
    if (t > 0) measure(w, s, &draft, &archimedes); /* the bodies' ranges are set at the first step */
    snprintf(extra, sizeof extra, ",%.9g,%.9g,%.9g", draft, archimedes, s->pose.angle * 180 / PI);
    if (output_tick(w, &s->output, extra, &d) && t >= s->t_end - s->window - 1e-12) {
        s->draft_sum += draft;
        s->archimedes_sum += archimedes;
        s->tilt_sum += fabs(s->pose.angle);
        s->rows++;
    }
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 6, .vtk_every = 0.2, .csv_every = 0.01, .E = 1e6, .nu = 0.3,
                        .rho0 = 500, .out = "out/rigid_float", .jitter = 0, .seed = 1, PNG_DEFAULTS};
    double dp = 0.02, damping = 10, window = 2.4, width = 0.3, height = 0.16, tilt = 5;
    int lock = 0;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (water 0.5 m deep)", 2e-3, 0.05, NULL},
        {"width", OPT_REAL, &width, "box width [m]", 0.02, 0.8, NULL},
        {"height", OPT_REAL, &height, "box height [m]", 0.02, 0.8, NULL},
        {"tilt", OPT_REAL, &tilt, "initial tilt [degrees]", -45, 45, NULL},
        {"damping", OPT_REAL, &damping, "damping of the box's motion [1/s] (0: none)", 0, 1e4, NULL},
        {"lock", OPT_FLAG, &lock, "lock its rotation (sps_body_lock_axes): it only heaves and sways", 0, 0, NULL},
        {"window", OPT_REAL, &window, "the draft and tilt are averaged over the last window seconds", 1e-3, 1e4, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def water_def = sps_default_body_def(), box_def = sps_default_body_def();
    sps_world* w;
    sps_diagnostics d;
    run_state s;
    sps_real tank_lo[3] = {0, 0, 0}, tank_hi[3] = {WIDTH, 2, 0}, lo[3] = {0, 0, 0}, hi[3] = {WIDTH, DEPTH, 0};
    double wall, draft, archimedes, upright_draft, gm, tilt_mean;

    ex_options(argc, argv, "2D free rigid box floating in a water tank: draft and metacentric stability", opts, &c, &wd, &box_def);
    memset(&s, 0, sizeof s);
    box_def.rotation = SPS_ROTATION_AUTO; /* a rigid body has no shear formulation */
    box_def.track_stress = 0;
    wd.keep_last_good_state = 1;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-G_ACC;
    water_def.name = "water";
    water_def.material.kind = SPS_MATERIAL_FLUID;
    water_def.material.density = RHO_WATER;
    water_def.material.fluid.sound_speed = (sps_real)(10 * sqrt(2 * G_ACC * DEPTH));
    box_def.name = "box";
    box_def.material.kind = SPS_MATERIAL_RIGID_DYNAMIC;
    box_def.damping = (sps_real)damping;
    sps_world_create(&wd, &w);
    sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP);
    sps_world_add_body(w, &water_def, &s.water);
    sps_body_add_box(w, s.water, lo, hi, NULL);
    sps_body_set_pressure(w, s.water, hydrostatic, NULL);
    sps_world_add_body(w, &box_def, &s.box);
    lo[0] = 0.5 * (WIDTH - width); hi[0] = lo[0] + width;
    lo[1] = DEPTH + 0.5 * dp; hi[1] = lo[1] + height;
    sps_body_add_box(w, s.box, lo, hi, NULL);
    {
        const double a = tilt * PI / 180, half_extent = 0.5 * (fabs(sin(a)) * width + fabs(cos(a)) * height);
        const sps_real centre[3] = {(sps_real)(0.5 * WIDTH), (sps_real)(DEPTH + 0.5 * dp + half_extent), 0};
        const sps_real rotation[9] = {(sps_real)cos(a), (sps_real)-sin(a), 0, (sps_real)sin(a), (sps_real)cos(a), 0, 0, 0, 1};
        sps_body_set_rigid_pose(w, s.box, centre, rotation); /* its lowest corner on the water */
        if (lock) sps_body_lock_axes(w, s.box, 0, SPS_AXIS_ALL);
    }
    s.pose.half[0] = 0.5 * width;
    s.pose.half[1] = 0.5 * height;
    s.ratio = c.rho0 / RHO_WATER;
    s.t_end = c.t_end;
    s.window = window;
    output_open(&s.output, &c, "rigid_float", "pressure", ",draft,archimedes,tilt_degrees");
    on_step(w, &s);
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);

    if (!s.rows) measure(w, &s, &s.draft_sum, &s.archimedes_sum), s.tilt_sum = fabs(s.pose.angle), s.rows = 1;
    draft = s.draft_sum / s.rows;
    archimedes = s.archimedes_sum / s.rows;
    tilt_mean = s.tilt_sum / s.rows * 180 / PI;
    upright_draft = s.ratio * height;
    gm = width * width / (12 * upright_draft) - 0.5 * (height - upright_draft);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    printf("RESULT case=rigid_float dp=%g rho_box=%g width=%g height=%g tilt0=%g damping=%g window=%g draft=%.5f archimedes=%.5f "
           "rel_error=%+.2f%% tilt=%.2f upright=%d predicted_upright=%d GM=%.4f upright_draft=%.5f particles=%d steps=%ld wall_s=%.2f out=%s\n",
           dp, c.rho0, width, height, tilt, damping, window, draft, archimedes, 100 * (draft / archimedes - 1), tilt_mean,
           tilt_mean < 10, gm > 0, gm, upright_draft, sps_world_particle_count(w), d.acoustic_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
