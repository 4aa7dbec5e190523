/* letter2d.c - a body from a drawn outline: a rubber letter A with its hole, read from the
   outline file this program writes, dropped on a floor (geometry from files, chapter >>geometry
   in sphsolid.h).

   The letter is 14 cm wide and high, drawn in centimetres: an outer ring of 8 points and a
   triangular hole, one "x y" line per point and a blank line between the rings (the plain
   outline format; sps_mesh_load also reads SVG paths). It is loaded with scale 0.01 and filled
   body-fitted (sps_body_add_mesh: relaxed), rho0 1000, E --E (1 MPa), nu 0.3, and released with
   its feet --height above the floor (the analytic wall y = 0, contact damping ratio 1 so it comes
   to rest). We report the outline's area against the polygon's (the shoelace formula over the
   points written), the particles' area against the outline's, and at the end the letter's
   height against its drawn height (its own weight squeezes it by rho g H^2 / (2 E), 0.1 %).

   Build: make examples        Run: ./build/letter2d
   Expect: the outline's area the polygon's exactly, the particles' -2.84 % of it (the lattice
   of the fill, 35 particles across); the letter bounces, rests and keeps its hole (its height
   0.14005 m at 1.5 s, bench/VALIDATION.md "Geometry from files").
   Smoke: letter2d --dp 0.01 --tend 0.01 */
#include "common.h"

#define G_ACC 9.81
/* the letter in centimetres: the outer ring counter-clockwise, then the hole */
static const double outer[8][2] = {{0, 0}, {4, 0}, {5.2, 3}, {8.8, 3}, {10, 0}, {14, 0}, {9, 14}, {5, 14}};
static const double hole[3][2] = {{5.9, 5.5}, {8.1, 5.5}, {7, 9.5}};

static double shoelace(const double (*p)[2], int n) {
    double a = 0;
    int i;
    for (i = 0; i < n; ++i) a += 0.5 * (p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1]);
    return fabs(a);
}
static void write_outline(const char* path) {
    FILE* f = fopen(path, "w");
    int i;
    if (!f) { fprintf(stderr, "cannot write %s\n", path); exit(1); }
    fprintf(f, "# the letter A in centimetres: outer ring\n");
    for (i = 0; i < 8; ++i) fprintf(f, "%g %g\n", outer[i][0], outer[i][1]);
    fprintf(f, "\n# its hole\n");
    for (i = 0; i < 3; ++i) fprintf(f, "%g %g\n", hole[i][0], hole[i][1]);
    fclose(f);
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
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 1.5, .vtk_every = 0.05, .csv_every = 0.005, .E = 1e6, .nu = 0.3,
                        .rho0 = 1000, .out = "out/letter2d", .jitter = 0, .seed = 1, PNG_DEFAULTS};
    double dp = 0.004, height = 0.05;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (the letter 0.14 m high, its legs 0.04 m wide)", 1e-3, 0.01, NULL},
        {"height", OPT_REAL, &height, "height of the letter's feet above the floor at the start [m]", 0, 1, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_mesh_def md = sps_default_mesh_def();
    sps_mesh* mesh;
    sps_mesh_info info;
    sps_world* w;
    sps_body letter;
    run_state s;
    const sps_real floor_point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    const sps_real *y;
    char path[600], msg[512];
    double wall, polygon, top = -1e30, bottom = 1e30;
    int n, i;

    ex_options(argc, argv, "2D rubber letter A from an outline file dropped on a floor", opts, &c, &wd, &bd);
    memset(&s, 0, sizeof s);
    make_dirs(c.out);
    snprintf(path, sizeof path, "%s/letter_A.txt", c.out);
    write_outline(path);
    md.scale = (sps_real)0.01; /* centimetres */
    md.translate[1] = (sps_real)height;
    if (sps_mesh_load(path, &md, &mesh, msg, sizeof msg) != SPS_OK) { fprintf(stderr, "%s\n", msg); return 1; }
    info = sps_mesh_get_info(mesh);
    polygon = 1e-4 * (shoelace(outer, 8) - shoelace(hole, 3));

    wd.keep_last_good_state = 1;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = (sps_real)-G_ACC;
    bd.name = "letter";
    bd.contact_damping = 1;
    sps_world_create(&wd, &w);
    sps_world_add_wall(w, floor_point, up, SPS_WALL_FREE_SLIP);
    sps_world_add_body(w, &bd, &letter);
    sps_body_add_mesh(w, letter, mesh, NULL, NULL, 0, &n);

    output_open(&s.output, &c, "letter2d", "von-mises", "");
    on_step(w, &s);
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    for (i = 0; i < sps_world_particle_count(w); ++i) {
        if (y[i] > top) top = y[i];
        if (y[i] < bottom) bottom = y[i];
    }
    printf("RESULT case=letter2d dp=%g rings=%d segments=%d outline_area=%.8f polygon_area=%.8f particles_area=%.6f particles_rel=%+.2f%% "
           "height_end=%.5f height_drawn=%.5f (particles' extent + dp) %s particles=%d wall_s=%.2f out=%s\n",
           dp, info.rings, info.elements, (double)info.volume, polygon, n * dp * dp, 100 * (n * dp * dp / (double)info.volume - 1),
           top - bottom + dp, 0.14, common_result_fields(&c), n, wall, c.out);
    sps_mesh_destroy(mesh);
    sps_world_destroy(w);
    return 0;
}
