/* mesh_float3d.c - a body from a mesh file: a jelly torus, read from the binary STL this program
   writes, dropped into a tank of water, floats half under (geometry from files, chapter
   >>geometry in sphsolid.h; the fluid-structure coupling, chapter >>coupling).

   The torus (ring radius 0.15 m, tube radius 0.06 m, --segments around each circle) is written
   as a binary STL in millimetres, loaded with scale 0.001 and filled body-fitted
   (sps_body_add_mesh: the relaxed fill). Its density is half the water's (rho0 500, E 2 MPa,
   nu 0.3), so it floats with its tube half under: its centre at the water level. The tank (0.8 m
   square, analytic free-slip walls, open top) holds water 0.3 m deep at rest. The torus is
   released with its bottom --drop above the water; only it is damped (--damping, DAMPING in the
   header), so it settles while the water keeps its waves. The level is the water's volume at
   rho0 plus the torus's submerged half spread over the tank. Ours: the torus's centre of mass
   minus the level, over the last --window seconds; Archimedes: 0.

   Build: make examples        Run: ./build/mesh_float3d --png-view iso
   Expect (dp 0.03): the STL's volume -0.32 % of 2 pi^2 R r^2 at 64 segments, the particles'
   -1.91 % of the STL's; the torus bobs and floats with its centre 0.36 dp above the level
   (bench/VALIDATION.md, "Geometry from files").
   Smoke: mesh_float3d --dp 0.04 --segments 24 --tend 0.01 --iterations 20 */
#include "common.h"

#define TANK 0.8
#define DEPTH 0.3
#define RING 0.15
#define TUBE 0.06
#define RHO_WATER 1000.0
#define G_ACC 9.81

static sps_real hydrostatic(const sps_real x[3], void* user) { (void)user; return (sps_real)(RHO_WATER * G_ACC * (DEPTH - (double)x[2])); }

/* The torus about the z axis as a binary STL in millimetres (n x n quads, two triangles each). */
static void write_torus_stl(const char* path, int n) {
    FILE* f = fopen(path, "wb");
    unsigned char header[84] = "torus written by mesh_float3d.c";
    const unsigned count = 2u * (unsigned)n * (unsigned)n;
    int i, j, k, c;
    if (!f) { fprintf(stderr, "cannot write %s\n", path); exit(1); }
    for (k = 0; k < 4; ++k) header[80 + k] = (unsigned char)(count >> (8 * k) & 255);
    fwrite(header, 1, 84, f);
    for (i = 0; i < n; ++i)
        for (j = 0; j < n; ++j) {
            static const int corners[2][3][2] = {{{0, 0}, {1, 0}, {1, 1}}, {{0, 0}, {1, 1}, {0, 1}}};
            for (k = 0; k < 2; ++k) {
                unsigned char rec[50] = {0};
                for (c = 0; c < 3; ++c) {
                    const double u = 2 * PI * ((i + corners[k][c][0]) % n) / n, v = 2 * PI * ((j + corners[k][c][1]) % n) / n; /* the seam: the same numbers */
                    const float xyz[3] = {(float)(1000 * (RING + TUBE * cos(v)) * cos(u)), (float)(1000 * (RING + TUBE * cos(v)) * sin(u)),
                                          (float)(1000 * TUBE * sin(v))};
                    memcpy(rec + 12 + 12 * c, xyz, sizeof xyz); /* little-endian hosts, as STL is */
                }
                fwrite(rec, 1, 50, f);
            }
        }
    fclose(f);
}

typedef struct {
    output_plan output;
    sps_body water, torus;
    double t_end, window, sum, torus_volume;
    int rows;
} run_state;

/* The torus's centre of mass height minus the water level. */
static double height_over_level(const sps_world* w, const run_state* s) {
    const sps_real *z = sps_world_field(w, SPS_FIELD_POSITION_Z), *m = sps_world_field(w, SPS_FIELD_MASS);
    double centre = 0, volume = 0;
    int i, first, count, components;
    sps_body_field(w, s->torus, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) centre += z[i];
    centre /= count;
    sps_body_field(w, s->water, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) volume += m[i] / RHO_WATER;
    return centre - (volume + 0.5 * s->torus_volume) / (TANK * TANK);
}

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[64];
    const double t = sps_world_time(w), h = t > 0 ? height_over_level(w, s) : 0;
    snprintf(extra, sizeof extra, ",%.9g", h);
    if (output_tick(w, &s->output, extra, &d) && t > 0 && t >= s->t_end - s->window - 1e-12) { s->sum += h; s->rows++; }
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 2, .vtk_every = 0.1, .csv_every = 0.01, .E = 2e6, .nu = 0.3,
                        .rho0 = 500, .out = "out/mesh_float3d", .jitter = 0, .seed = 1, PNG_DEFAULTS};
    double dp = 0.02, drop = 0.05, damping = 10, window = 0.5, segments = 64, iterations = 300;
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m] (tube 0.12 m across, water 0.3 m deep)", 5e-3, 0.05, NULL},
        {"segments", OPT_REAL, &segments, "the STL's segments around each circle of the torus", 8, 1000, NULL},
        {"iterations", OPT_REAL, &iterations, "relaxation iterations of the fill (0: the default 300)", 0, 10000, NULL},
        {"drop", OPT_REAL, &drop, "height of the torus's bottom above the water at the start [m]", 0, 1, NULL},
        {"damping", OPT_REAL, &damping, "damping of the torus only [1/s]", 0, 1e4, NULL},
        {"window", OPT_REAL, &window, "the height is averaged over the last window seconds", 1e-3, 1e4, NULL},
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def water_def = sps_default_body_def(), torus_def = sps_default_body_def();
    sps_mesh_def md = sps_default_mesh_def();
    sps_mesh* mesh;
    sps_mesh_info info;
    sps_world* w;
    run_state s;
    sps_real tank_lo[3] = {0, 0, 0}, tank_hi[3] = {TANK, TANK, 2}, water_hi[3] = {TANK, TANK, DEPTH};
    char path[600], msg[512];
    double wall, exact;
    int n_torus;

    ex_options(argc, argv, "3D jelly torus from an STL file floating in a water tank", opts, &c, &wd, &torus_def);
    memset(&s, 0, sizeof s);
    make_dirs(c.out);
    snprintf(path, sizeof path, "%s/torus.stl", c.out);
    write_torus_stl(path, (int)segments);
    md.scale = (sps_real)0.001; /* the file is in millimetres */
    md.translate[0] = md.translate[1] = (sps_real)(0.5 * TANK);
    md.translate[2] = (sps_real)(DEPTH + drop + TUBE);
    if (sps_mesh_load(path, &md, &mesh, msg, sizeof msg) != SPS_OK) { fprintf(stderr, "%s\n", msg); return 1; }
    info = sps_mesh_get_info(mesh);

    wd.keep_last_good_state = 1;
    wd.dim = 3;
    wd.dp = (sps_real)dp;
    wd.gravity[2] = (sps_real)-G_ACC;
    water_def.name = "water";
    water_def.material.kind = SPS_MATERIAL_FLUID;
    water_def.material.density = RHO_WATER;
    water_def.material.fluid.sound_speed = (sps_real)(10 * sqrt(2 * G_ACC * DEPTH));
    torus_def.name = "torus";
    torus_def.damping = (sps_real)damping;
    sps_world_create(&wd, &w);
    sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Z_HI, SPS_WALL_FREE_SLIP);
    sps_world_add_body(w, &water_def, &s.water);
    sps_body_add_box(w, s.water, tank_lo, water_hi, NULL);
    sps_body_set_pressure(w, s.water, hydrostatic, NULL);
    sps_world_add_body(w, &torus_def, &s.torus);
    sps_body_add_mesh(w, s.torus, mesh, NULL, NULL, (int)iterations, &n_torus);
    s.torus_volume = n_torus * dp * dp * dp;

    s.t_end = c.t_end; s.window = window;
    output_open(&s.output, &c, "mesh_float3d", "pressure", ",height_over_level");
    on_step(w, &s);
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);

    exact = 2 * PI * PI * RING * TUBE * TUBE;
    printf("RESULT case=mesh_float3d dp=%g segments=%d triangles=%d closed=%d stl_volume=%.6f torus_volume=%.6f stl_rel=%+.3f%% "
           "particles_volume=%.6f particles_rel=%+.2f%% height_over_level=%.5f archimedes=0 dp_fraction=%+.3f %s particles=%d wall_s=%.2f out=%s\n",
           dp, (int)segments, info.elements, info.closed, (double)info.volume, exact, 100 * ((double)info.volume / exact - 1), s.torus_volume,
           100 * (s.torus_volume / (double)info.volume - 1), s.rows ? s.sum / s.rows : 0.0, s.rows ? s.sum / s.rows / dp : 0.0,
           common_result_fields(&c), sps_world_particle_count(w), wall, c.out);
    sps_mesh_destroy(mesh);
    sps_world_destroy(w);
    return 0;
}
