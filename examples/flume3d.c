/* flume3d.c - cohesive granular flow down a flume against a barrier (benchmark C7, UTVF 5.4).

   A rectangular mass of the C5 soil (rho0 = 1850, E = 1.8 MPa, nu = 0.3, c = 5 kPa, phi = 25
   degrees, psi = 0), x in [-2, -1] m, up to y = 3.5 m and 0.5 m wide, stands on a bed inclined
   at 50 degrees (the bed's foot at the origin), is released from zero stress, flows down onto
   a horizontal run-out and against a rigid barrier 0.5 m high, 2 m downstream of the foot,
   between two side walls. The paper gives the angle and the material only (the set-up of its
   Fig. 25a is a picture): these sizes are ours, chosen so that the mass fails (its downhill
   face, 2.3 m high, is a third above the 1.7 m a vertical cut of this soil stands, 4 c /
   (rho g) tan(45 + phi/2); a layer 0.4 m thick parallel to the bed holds). The bed and the
   floor are no-slip analytic walls, the side walls free-slip (no-slip sides held the whole
   mass by its cohesion); the barrier is a wall body of rigid particles. --transport
   none|tvf|utvf (UTVF, the paper's, by default). We print every 0.5 s the front (the farthest
   particle along the flow), the largest speed, the clustering count (particles closer than
   0.5 dp to another; the paper's claim: none with UTVF) and the surface-particle count, and
   at the end the share of the soil held behind the barrier. dp = 0.04 m by default (13 200
   particles, about 2.5 minutes on 2 cores).

   Build: make examples     Run: ./build/flume3d (--dp 0.08: a quick look)
   Expect: the soil flows down, piles against the barrier and comes to rest; no clustering.
   Smoke: flume3d --dp 0.2 --tend 0.01 */
#include "common.h"

#define SLOPE_DEG 50.0
#define WIDTH 0.5
#define BARRIER_X 2.0
#define BARRIER_HEIGHT 0.5

typedef struct {
    double n_along[2];    /* the bed's normal (x, y) */
    double x0, x1, y_top; /* the mass: x in [x0, x1], y below y_top, above the bed */
} block_shape;

/* Signed distance (approximate: the largest of the planes') to the mass on the bed. */
static sps_real block_sdf(const sps_real x[3], void* user) {
    const block_shape* b = (const block_shape*)user;
    const double above_bed = x[0] * b->n_along[0] + x[1] * b->n_along[1];
    double d = fmax(b->x0 - x[0], x[0] - b->x1);
    d = fmax(d, fmax(x[1] - b->y_top, -above_bed));
    d = fmax(d, fmax(-(double)x[2], (double)x[2] - WIDTH));
    return (sps_real)d;
}

typedef struct {
    output_plan output;
    double next_report, dp;
    sps_body soil;
} run_state;

/* The front: the largest x of the soil (downstream), + dp/2. */
static double front(const sps_world* w, sps_body soil, double dp) {
    int first, count, i;
    const sps_real* x = sps_body_field(w, soil, "position_x", NULL, &first, &count);
    double xmax = -1e30;
    for (i = 0; x && i < count; ++i)
        if (x[i] > xmax) xmax = x[i];
    return xmax + 0.5 * dp;
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    const double t = sps_world_time(w);
    output_tick(w, &s->output, "", &d);
    if (t >= s->next_report - 1e-9) {
        sps_world_diagnostics(w, s->soil, &d);
        printf("  t = %.2f s: front x = %.3f m, max speed %.3f m/s, %d particles closer than 0.5 dp to another (smallest spacing %.3f dp), "
               "surface particles %d, wall %.0f s\n",
               t, front(w, s->soil, s->dp), (double)d.max_speed, ex_clustered_particles(w, s->dp, 0.5), (double)d.min_spacing,
               d.surface_particles, wall_seconds() - s->output.wall0);
        fflush(stdout);
        s->next_report += 0.5;
    }
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_OG, .cfl = 0.4, .t_end = 3, .vtk_every = 0.1, .csv_every = 0.01, .E = 1.8e6, .nu = 0.3,
                        .rho0 = 1850, .out = "out/flume3d", .jitter = 0, .seed = 1, .transport = 2, PNG_DEFAULTS};
    double dp = 0.04;
    granular_options g = {5e3, 25, 0.1, SPS_CONE_PAPERS};
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 0.005, 0.25, NULL},
        GRANULAR_OPTION_SPECS(g),
    };
    const double a = SLOPE_DEG * PI / 180;
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def(), rd = sps_default_body_def();
    sps_world* w;
    sps_body soil, barrier;
    sps_diagnostics d;
    block_shape shape;
    sps_real origin[3] = {0, 0, 0}, bed_normal[3], up[3] = {0, 1, 0}, side_lo[3] = {0, 0, 0}, side_hi[3] = {0, 0, WIDTH};
    sps_real plus_z[3] = {0, 0, 1}, minus_z[3] = {0, 0, -1}, blo[3], bhi[3], lo[3], hi[3];
    run_state s;
    double wall, held = 0;
    int i, first, count;

    ex_options(argc, argv, "3D cohesive granular flow in a 50-degree flume against a barrier (C7, UTVF 5.4)", opts, &c, &wd, &bd);
    wd.keep_last_good_state = 1; /* a failed step writes the last good state (output_close) */
    memset(&s, 0, sizeof s);
    bed_normal[0] = (sps_real)sin(a);
    bed_normal[1] = (sps_real)cos(a);
    bed_normal[2] = 0;
    shape.n_along[0] = sin(a);
    shape.n_along[1] = cos(a);
    shape.x0 = -2;
    shape.x1 = -1;
    shape.y_top = 3.5;
    wd.dim = 3;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-GRANULAR_GRAVITY;
    sps_world_create(&wd, &w);
    sps_world_add_wall(w, origin, bed_normal, SPS_WALL_NO_SLIP); /* the bed: solid below y = -tan(a) x */
    sps_world_add_wall(w, origin, up, SPS_WALL_NO_SLIP);         /* the run-out floor, beyond the foot */
    /* smooth side walls (a flume's glass): no-slip ones held the whole mass by its cohesion,
       2 x 1.6 m^2 x 5 kPa against its 7.8 kN weight */
    sps_world_add_wall(w, side_lo, plus_z, SPS_WALL_FREE_SLIP);
    sps_world_add_wall(w, side_hi, minus_z, SPS_WALL_FREE_SLIP);
    bd.name = "soil";
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    apply_granular(&g, &bd);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &soil);
    lo[0] = (sps_real)shape.x0; hi[0] = (sps_real)shape.x1;
    lo[1] = (sps_real)(-tan(a) * shape.x1); hi[1] = (sps_real)shape.y_top;
    lo[2] = 0; hi[2] = (sps_real)WIDTH;
    sps_body_add_sdf(w, soil, lo, hi, block_sdf, &shape, NULL);
    rd.name = "barrier";
    rd.material.kind = SPS_MATERIAL_RIGID;
    rd.material.density = 2500;
    rd.material.youngs_modulus = 1e8; /* its contact stiffness: the soil's own K sets the harmonic mean */
    sps_world_add_body(w, &rd, &barrier);
    blo[0] = (sps_real)BARRIER_X; bhi[0] = (sps_real)(BARRIER_X + 4 * dp);
    blo[1] = 0; bhi[1] = (sps_real)BARRIER_HEIGHT;
    blo[2] = 0; bhi[2] = (sps_real)WIDTH;
    sps_body_add_box(w, barrier, blo, bhi, NULL);

    printf("granular flume: slope %g deg, dp = %g m, %d particles (soil and barrier), c = %g Pa, phi = %g deg, zeta = %g, transport %s\n",
           SLOPE_DEG, dp, sps_world_particle_count(w), g.cohesion, g.phi, g.diffusion,
           transport_name(c.transport));
    s.next_report = 0.5;
    s.dp = dp;
    s.soil = soil;
    output_open(&s.output, &c, "flume3d", "velocity", "");
    on_step(w, &s); /* t = 0: the first CSV row and snapshot */
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    sps_world_diagnostics(w, soil, &d);
    {
        const sps_real* x = sps_body_field(w, soil, "position_x", NULL, &first, &count);
        for (i = 0; x && i < count; ++i) held += x[i] < BARRIER_X;
        held /= count > 0 ? count : 1;
    }
    printf("  end: %.1f %% of the soil behind the barrier, front x = %.3f m, max speed %.3f m/s, %d particles closer than 0.5 dp\n",
           100 * held, front(w, soil, dp), (double)d.max_speed, ex_clustered_particles(w, dp, 0.5));
    printf("RESULT case=flume3d dp=%g cohesion=%g phi=%g zeta=%g t=%.4g front=%.4f held=%.4f max_speed=%.4g clustered=%d "
           "min_spacing=%.3f surface_particles=%d %s particles=%d steps=%ld advection_steps=%ld wall_s=%.2f ns_per_particle_step=%.1f out=%s\n",
           dp, g.cohesion, g.phi, g.diffusion, (double)d.time, front(w, soil, dp), held, (double)d.max_speed, ex_clustered_particles(w, dp, 0.5),
           (double)d.min_spacing, d.surface_particles, common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps,
           d.advection_steps, wall, ns_per_particle_step(w, wall, d.acoustic_steps),
           c.out);
    sps_world_destroy(w);
    return 0;
}
