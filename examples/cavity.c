/* cavity.c - the lid-driven cavity: a viscous fluid in a unit square box of no-slip analytic walls
   whose lid (y = 1) slides at U = 1 m/s (sps_world_set_wall_velocity; FLUIDS in sphsolid.h's
   manual), at Re = U L / nu = 100 or 1000 (--re). rho0 = 1000, c0 = 10 U; the fluid starts at
   rest on the lattice. At --tend the centre-line profiles, u(y) along x = 0.5 and v(x) along
   y = 0.5 (a line fitted through the particles near each point, velocity_on_line), are compared
   with Ghia, Ghia and Shin 1982's tables (J. Comput. Phys. 48, 387-411, Tables I and II: bench/ghia1982.csv, read
   at run time, --ghia PATH): max_dev is the largest |ours - theirs| / U over their interior
   points (the walls' own values left out).

   Build: make examples        Run: ./build/cavity --res 40 --tend 15
   Expect (Re 100, TVF carrying the velocity, h = 2 dp, material.fluid.dissipation none): max_dev 0.018
   at --res 30 --tend 10, 0.012 at --res 40 --tend 15 (0.017 at 20 s, 0.025 at 25 s: the flow
   is steady to a few per cent only, no density diffusion damping the box's sound), 0.005 at
   --res 60 --tend 15; Re 1000 at --res 40 --tend 15 0.26. --carry-velocity 0: 0.029 at --res 40
   --tend 15 and pairs of particles 1e-4 dp apart at the walls; with the library's defaults
   (--carry-velocity 0 --dissipation riemann --h-over-dp 1.3) 0.061 (bench/VALIDATION.md,
   "Viscous flows without the Riemann solver's dissipation"); CSV (diagnostics per row, and
   profiles.csv with both profiles next to Ghia's), VTK snapshots, a picture coloured by speed.
   Smoke: cavity --res 20 --tend 0.02 */
#include "common.h"

#define LID 1.0
#define GHIA_MAX 40

typedef struct {
    double pos[GHIA_MAX], vel[GHIA_MAX];
    int n;
} ghia_line;

/* Reads Ghia's values for Reynolds number re from path: u(y) into u, v(x) into v. Exits with
   status 2 if the file or the Reynolds number is not there. */
static void read_ghia(const char* path, double re, ghia_line* u, ghia_line* v) {
    FILE* f = fopen(path, "r");
    char line[256], comp;
    double r, pos, vel;
    u->n = v->n = 0;
    if (!f) { fprintf(stderr, "%s: cannot read %s (run from the repository's top folder, or give --ghia PATH)\n", g_prog, path); exit(2); }
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "%lf,%c,%lf,%lf", &r, &comp, &pos, &vel) == 4 && r == re) {
            ghia_line* g = comp == 'u' ? u : v;
            if (g->n < GHIA_MAX) { g->pos[g->n] = pos; g->vel[g->n] = vel; g->n++; }
        }
    fclose(f);
    if (u->n == 0 || v->n == 0) { fprintf(stderr, "%s: %s has no values for Re = %g (it has 100 and 1000)\n", g_prog, path, re); exit(2); }
}

/* Velocity component c along a centre line at position p: a straight line fitted by least
   squares through the particles within dp of the line and 1.5 dp of p (along the line), and the
   wall's own value where the line meets it (no slip: 0, the lid's U at y = 1), so that a point
   next to a wall is not an average of the particles on one side of it only. line 0: the
   vertical line x = 0.5 (p = y, c = u); 1: the horizontal line y = 0.5 (p = x, c = v). */
static double velocity_on_line(const sps_world* w, int line, double p, double dp) {
    const sps_real *px = sps_world_field(w, SPS_FIELD_POSITION_X), *py = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* v = sps_world_field(w, line == 0 ? SPS_FIELD_VELOCITY_X : SPS_FIELD_VELOCITY_Y);
    double s0 = 0, s1 = 0, s2 = 0, sv = 0, sqv = 0, det;
    int i, n = sps_world_particle_count(w), end;
    for (i = -2; i < n; ++i) { /* -2, -1: the walls at either end of the line */
        const double across = i < 0 ? 0 : line == 0 ? px[i] - 0.5 : py[i] - 0.5;
        const double along = i == -2 ? 0 : i == -1 ? 1 : line == 0 ? py[i] : px[i];
        const double value = i == -2 ? 0 : i == -1 ? (line == 0 ? LID : 0) : v[i], q = along - p;
        if (fabs(across) >= dp || fabs(q) >= 1.5 * dp) continue;
        s0 += 1; s1 += q; s2 += q * q; sv += value; sqv += q * value;
    }
    det = s0 * s2 - s1 * s1;
    end = det > 1e-12 * s0 * s0 * dp * dp;
    return end ? (s2 * sv - s1 * sqv) / det : s0 > 0 ? sv / s0 : 0;
}

typedef struct {
    output_plan output;
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    output_tick(w, &s->output, "", &d);
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.cfl = 0.4, .t_end = 20, .vtk_every = 5, .csv_every = 0.1, .E = 1e6, .nu = 0.3, .rho0 = 1000,
                        .out = "out/cavity", .transport = 1, .h_over_dp = 2, PNG_DEFAULTS};
    int res = 50, k, line, dissipation = SPS_FLUID_DISSIPATION_NONE, carry_velocity = 1;
    double re = 100, c0_factor = 10, max_dev = 0, dev_at = 0, wall;
    const char* ghia_path = "bench/ghia1982.csv";
    opt_spec opts[] = {
        {"res", OPT_INT, &res, "particles along the cavity's side, L/dp", 10, 1000, NULL},
        {"re", OPT_REAL, &re, "Reynolds number U L / nu (Ghia's tables: 100 or 1000)", 1, 1e4, NULL},
        {"c0-factor", OPT_REAL, &c0_factor, "sound speed / U", 2, 1000, NULL},
        {"carry-velocity", OPT_INT, &carry_velocity, "1: the transport shift carries the velocity and sees the walls (transport_carries_velocity)", 0, 1, NULL},
        {"dissipation", OPT_CHOICE, &dissipation, "the fluid's numerical dissipation (material.fluid.dissipation): the Riemann solver's, its density diffusion only, none", 0, 0,
         "riemann|density|none"},
        {"ghia", OPT_STRING, &ghia_path, "Ghia et al.'s table (CSV)", 0, 0, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0}, lid[3] = {LID, 0, 0};
    sps_world* w;
    sps_body fluid;
    sps_diagnostics d;
    ghia_line gu, gv;
    run_state s;
    FILE* profiles;

    ex_options(argc, argv, "lid-driven cavity against Ghia, Ghia and Shin 1982", opts, &c, &wd, &bd);
    read_ghia(ghia_path, re, &gu, &gv);
    wd.dim = 2;
    wd.dp = (sps_real)(1.0 / res);
    wd.energy_growth_limit = (sps_real)INFINITY; /* the lid's work is not in the energy account */
    bd.name = "fluid";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = (sps_real)(c0_factor * LID);
    bd.material.fluid.dissipation = (sps_fluid_dissipation)dissipation;
    bd.transport_carries_velocity = carry_velocity;
    bd.material.viscosity = (sps_real)(c.rho0 * LID / re);
    sps_world_create(&wd, &w);
    ex_unset_unread(&bd);
    sps_world_add_body(w, &bd, &fluid);
    sps_body_add_box(w, fluid, lo, hi, NULL);
    sps_world_add_box_walls(w, lo, hi, 0, SPS_WALL_NO_SLIP);
    sps_world_set_wall_velocity(w, 3, lid); /* the faces: x lo, x hi, y lo, y hi */

    memset(&s, 0, sizeof s);
    output_open(&s.output, &c, "cavity", "velocity", "");
    printf("cavity: L/dp = %d, %d particles, Re = %g, c0 = %g m/s, h = %g dp, transport %s, dissipation %s, to t = %g s\n", res,
           sps_world_particle_count(w), re, c0_factor * LID, c.h_over_dp, c.transport == 0 ? "none" : c.transport == 1 ? "TVF" : "UTVF",
           dissipation_name(dissipation), c.t_end);
    on_step(w, &s);
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    profiles = open_out(c.out, "profiles.csv");
    fprintf(profiles, "component,position,ours,ghia\n");
    printf("  line          position   ours      Ghia et al.  difference / U\n");
    for (line = 0; line < 2; ++line) {
        const ghia_line* g = line == 0 ? &gu : &gv;
        for (k = 0; k < g->n; ++k) {
            const double p = g->pos[k], ours = velocity_on_line(w, line, p, 1.0 / res);
            const int interior = p > 0 && p < 1;
            fprintf(profiles, "%c,%.4f,%.6f,%.5f\n", line == 0 ? 'u' : 'v', p, ours, g->vel[k]);
            if (!interior) continue;
            printf("  %s  %.4f   %+.5f   %+.5f     %+.4f\n", line == 0 ? "u(x = 0.5, y)" : "v(x, y = 0.5)", p, ours, g->vel[k],
                   (ours - g->vel[k]) / LID);
            if (fabs(ours - g->vel[k]) / LID > max_dev) { max_dev = fabs(ours - g->vel[k]) / LID; dev_at = p + 10 * line; }
        }
    }
    fclose(profiles);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    printf("RESULT case=cavity res=%d Re=%g c0_factor=%g t=%.4g max_dev=%.4f max_dev_at=%s%.4f paper=Ghia1982 %s h_over_dp=%g dissipation=%s carry_velocity=%d "
           "particles=%d "
           "steps=%ld wall_s=%.2f out=%s\n", res, re, c0_factor, (double)sps_world_time(w), max_dev, dev_at >= 10 ? "v:" : "u:", fmod(dev_at, 10),
           common_result_fields(&c), c.h_over_dp, dissipation_name(dissipation), carry_velocity, sps_world_particle_count(w), d.acoustic_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
