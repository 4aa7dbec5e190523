/* test_geometry.c - tests of geometry from files and arrays (the header's chapter >>geometry:
   sps_mesh_load, sps_mesh_from_triangles, sps_mesh_from_rings, sps_mesh_sdf, sps_body_add_mesh,
   sps_body_add_mesh_shell).

   Build and run (from the top of the repository):
       make build/test_geometry && ./build/test_geometry   (make test runs it)
   Writes its files into build/geometry/ (or the directory given as the first argument). Prints
   the measured figures and, last, "N passed, M failed"; the exit status is 0 iff M == 0. Every
   tolerance carries a comment with its reason. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int g_passed, g_failed;
static const char* g_dir = "build/geometry";

#include "ensure.h"
#include "mesh_files.h"

static const char* path_of(const char* name) {
    static char path[4][512];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", g_dir, name);
    return path[k];
}
static int write_text(const char* name, const char* text) { return test_write_bytes(path_of(name), text, strlen(text)); }

static void quiet_log(int level, const char* message, void* user) { (void)level; (void)message; (void)user; }
static sps_world* make_world(int dim, double dp, sps_body* b, sps_material_kind kind) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    wd.dim = dim; wd.dp = (sps_real)dp; wd.threads = 1; wd.log = quiet_log;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    bd.material.kind = kind;
    if (sps_world_add_body(w, &bd, b) != SPS_OK) { sps_world_destroy(w); return NULL; }
    return w;
}
static sps_real* world_points(const sps_world* w, int* n) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y),
                   *z = sps_world_field(w, SPS_FIELD_POSITION_Z);
    sps_real* p;
    int i;
    *n = sps_world_particle_count(w);
    p = (sps_real*)malloc(sizeof(sps_real) * 3 * (size_t)(*n > 0 ? *n : 1));
    for (i = 0; i < *n; ++i) { p[3 * i] = x[i]; p[3 * i + 1] = y[i]; p[3 * i + 2] = z ? z[i] : 0; }
    return p;
}
static double uniform(unsigned long long* s) { /* splitmix64 in [0, 1) */
    unsigned long long z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return (double)((z ^ (z >> 31)) >> 11) / 9007199254740992.0;
}

/* The smallest distance from the centre to a triangle of the sphere: R minus it is the mesh's
   chord error against the sphere (every vertex lies on it). */
static double sphere_chord_error(const test_mesh* m, double R, const double c[3]) {
    sps_mesh* mesh;
    double smallest = R;
    int i;
    (void)m;
    (void)mesh;
    for (i = 0; i < m->nt; ++i) { /* the plane's distance is the triangle's (the foot lies inside it for these triangles) */
        const double *a = m->v + 3 * m->t[3 * i], *b = m->v + 3 * m->t[3 * i + 1], *d = m->v + 3 * m->t[3 * i + 2];
        double u[3], v[3], n[3], len, dist;
        int k;
        for (k = 0; k < 3; ++k) { u[k] = b[k] - a[k]; v[k] = d[k] - a[k]; }
        n[0] = u[1] * v[2] - u[2] * v[1]; n[1] = u[2] * v[0] - u[0] * v[2]; n[2] = u[0] * v[1] - u[1] * v[0];
        len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        dist = fabs(n[0] * (a[0] - c[0]) + n[1] * (a[1] - c[1]) + n[2] * (a[2] - c[2])) / len;
        if (dist < smallest) smallest = dist;
    }
    return R - smallest;
}

/* ---- the same triangles as binary STL, ASCII STL and OBJ give bit-identical bodies ---- */
static int fill_from(const char* path, sps_real** xyz, int* n, int relax) {
    sps_mesh* m = NULL;
    char msg[512];
    sps_body b;
    sps_world* w = make_world(3, 0.2, &b, SPS_MATERIAL_ELASTIC);
    if (!w || sps_mesh_load(path, NULL, &m, msg, sizeof msg) != SPS_OK) { printf("    %s\n", msg); sps_world_destroy(w); return 1; }
    if (sps_body_add_mesh(w, b, m, NULL, NULL, relax ? 40 : -1, NULL) != SPS_OK) { sps_mesh_destroy(m); sps_world_destroy(w); return 1; }
    *xyz = world_points(w, n);
    sps_mesh_destroy(m);
    sps_world_destroy(w);
    return 0;
}
static int test_formats_identical(void) {
    const double c[3] = {0.013, -0.021, 0.007};
    test_mesh s = test_mesh_sphere(1, c, 24, 32);
    const char* names[3] = {"sphere_binary.stl", "sphere_ascii.stl", "sphere.obj"};
    sps_real* xyz[3];
    int n[3], k, relax;
    ENSURE(test_write_stl_binary(path_of(names[0]), &s) == 0 && test_write_stl_ascii(path_of(names[1]), &s) == 0
           && test_write_obj(path_of(names[2]), &s) == 0);
    for (relax = 0; relax <= 1; ++relax) {
        for (k = 0; k < 3; ++k) ENSURE(fill_from(path_of(names[k]), &xyz[k], &n[k], relax) == 0);
        printf("    %s fill: %d, %d, %d particles\n", relax ? "relaxed" : "lattice", n[0], n[1], n[2]);
        for (k = 1; k < 3; ++k) ENSURE(n[k] == n[0] && memcmp(xyz[k], xyz[0], sizeof(sps_real) * 3 * (size_t)n[0]) == 0);
        for (k = 0; k < 3; ++k) free(xyz[k]);
    }
    test_mesh_free(&s);
    return 0;
}

/* ---- the sphere of 20,000 triangles ---- */
static int test_sphere(void) {
    const double R = 1, c[3] = {0, 0, 0}, dp = R / 10;
    test_mesh s = test_mesh_sphere(R, c, 100, 100);
    sps_mesh* m = NULL;
    sps_mesh_info info;
    char msg[512];
    sps_body bl, br;
    sps_world *wl = make_world(3, dp, &bl, SPS_MATERIAL_ELASTIC), *wr = make_world(3, dp, &br, SPS_MATERIAL_ELASTIC);
    unsigned long long seed = 12345;
    double chord, worst = 0, tol_volume;
    sps_real lo[3], hi[3], *p;
    sps_fill_quality ql, qr;
    int i, n, nl;
    ENSURE(wl && wr);
    ENSURE(test_write_stl_binary(path_of("sphere20k.stl"), &s) == 0);
    ENSURE(sps_mesh_load(path_of("sphere20k.stl"), NULL, &m, msg, sizeof msg) == SPS_OK);
    info = sps_mesh_get_info(m);
    chord = sphere_chord_error(&s, R, c);
    printf("    %d triangles, %d vertices, closed %d, oriented %d, volume %.6f (sphere %.6f), area %.6f (%.6f), chord error %.3g R\n",
           info.elements, info.vertices, info.closed, info.oriented, (double)info.volume, 4.18879020478639, (double)info.area,
           12.5663706143592, chord);
    ENSURE(info.elements == s.nt && info.vertices == s.nv && info.closed && info.oriented && info.degenerate == 0);
    /* the inscribed mesh's volume lies below the sphere's by at most its area x chord error */
    ENSURE(info.volume < 4.18879020478639 && info.volume > 4.18879020478639 - 12.6 * chord);
    for (i = 0; i < 10000; ++i) { /* random points in [-1.5 R, 1.5 R]^3 */
        sps_real x[3];
        double d, exact;
        int a;
        for (a = 0; a < 3; ++a) x[a] = (sps_real)(3 * R * (uniform(&seed) - 0.5));
        d = (double)sps_mesh_sdf(x, m);
        exact = sqrt((double)x[0] * x[0] + (double)x[1] * x[1] + (double)x[2] * x[2]) - R;
        if (fabs(d - exact) > worst) worst = fabs(d - exact);
    }
    printf("    10,000 random points: largest |mesh - sphere| distance %.3g R (chord error %.3g R)\n", worst, chord);
    /* the mesh lies between the sphere and the sphere shrunk by the chord error: the distances
       differ by no more (a rounding's worth of slack) */
    ENSURE(worst <= chord * (1 + 1e-9) + 1e-12);
    for (i = 0; i < 3; ++i) { lo[i] = (sps_real)(-R - 2 * dp); hi[i] = (sps_real)(R + 2 * dp); }
    ENSURE(sps_body_add_mesh(wl, bl, m, NULL, NULL, -1, &nl) == SPS_OK);
    ENSURE(sps_body_add_mesh(wr, br, m, NULL, NULL, 100, &n) == SPS_OK); /* bench/geometry_cost: the 300 of the default */
    tol_volume = 0.01 * (double)info.volume; /* the acceptance figure: 1 % */
    printf("    R/dp 10: %d particles, volume %.5f (%+.3f %% of the mesh's)\n", n, n * dp * dp * dp, 100 * (n * dp * dp * dp / (double)info.volume - 1));
    ENSURE(n == nl);
    ENSURE_NEAR(n * dp * dp * dp, (double)info.volume, tol_volume);
    p = world_points(wl, &nl);
    ENSURE(sps_measure_fill(wl, nl, p, lo, hi, sps_mesh_sdf, m, &ql) == SPS_OK);
    free(p);
    p = world_points(wr, &n);
    ENSURE(sps_measure_fill(wr, n, p, lo, hi, sps_mesh_sdf, m, &qr) == SPS_OK);
    free(p);
    printf("    surface depth RMS (depth - dp/2)/dp: lattice %.4f, relaxed %.4f (%d surface particles)\n", (double)ql.surface_rms, (double)qr.surface_rms,
           qr.surface);
    ENSURE(qr.surface_rms <= 0.1); /* the acceptance figure: within dp/10 of dp/2 */
    sps_mesh_destroy(m);
    sps_world_destroy(wl); sps_world_destroy(wr);
    test_mesh_free(&s);
    return 0;
}

/* ---- the mesh's report and its transform ---- */
static int test_box_and_transform(void) {
    const double lo[3] = {0, 0, 0}, hi[3] = {2, 1, 0.5};
    test_mesh b = test_mesh_box(lo, hi);
    sps_real v[24], x[3] = {0, 0, 0};
    sps_mesh* m = NULL;
    sps_mesh_def d = sps_default_mesh_def();
    sps_mesh_info info;
    char msg[512];
    int i;
    for (i = 0; i < 24; ++i) v[i] = (sps_real)(1000 * b.v[i]); /* millimetres */
    d.scale = (sps_real)0.001;
    d.centre = 1;
    d.rotate[2] = (sps_real)(0.5 * 3.14159265358979323846); /* a quarter turn about z: x -> y */
    d.translate[2] = 10;
    ENSURE(sps_mesh_from_triangles(8, v, 12, b.t, &d, &m, msg, sizeof msg) == SPS_OK);
    info = sps_mesh_get_info(m);
    printf("    box 2 x 1 x 0.5 m from mm, centred, turned, lifted: bounds (%g %g %g)-(%g %g %g), volume %g, area %g\n", (double)info.lo[0],
           (double)info.lo[1], (double)info.lo[2], (double)info.hi[0], (double)info.hi[1], (double)info.hi[2], (double)info.volume, (double)info.area);
    /* rounding of the scale and the quarter turn's cosine: 1e-12 m */
    ENSURE_NEAR(info.lo[0], -0.5, 1e-12); ENSURE_NEAR(info.hi[0], 0.5, 1e-12);
    ENSURE_NEAR(info.lo[1], -1, 1e-12); ENSURE_NEAR(info.hi[1], 1, 1e-12);
    ENSURE_NEAR(info.lo[2], 9.75, 1e-12); ENSURE_NEAR(info.hi[2], 10.25, 1e-12);
    ENSURE_NEAR(info.volume, 1, 1e-12);
    ENSURE_NEAR(info.area, 2 * (2 + 1 + 0.5), 1e-12);
    /* the distance inside the box's centre: its half thickness; outside a corner: to the corner (the vertex's pseudo-normal) */
    x[2] = 10;
    ENSURE_NEAR(sps_mesh_sdf(x, m), -0.25, 1e-12);
    x[0] = 1.5; x[1] = 2; x[2] = 11.25;
    ENSURE_NEAR(sps_mesh_sdf(x, m), sqrt(3.0), 1e-12);
    x[0] = 0.5; x[1] = 1; x[2] = 10.25 + 1e-9; /* just outside a corner, and just inside it */
    ENSURE(sps_mesh_sdf(x, m) > 0);
    x[0] = 0.5 - 1e-9; x[1] = 1 - 1e-9; x[2] = 10.25 - 1e-9;
    ENSURE(sps_mesh_sdf(x, m) < 0);
    sps_mesh_destroy(m);
    test_mesh_free(&b);
    return 0;
}

/* ---- bad input: each refused with a message naming the file and what is wrong ---- */
static int refused(const char* name, const sps_mesh_def* d, const char* expect1, const char* expect2) {
    sps_mesh* m = (sps_mesh*)&m; /* not NULL: a refusal sets it to NULL */
    char msg[512] = "";
    const sps_result r = sps_mesh_load(path_of(name), d, &m, msg, sizeof msg);
    printf("    %-22s -> %s\n", name, msg);
    if (r == SPS_OK) { sps_mesh_destroy(m); return 0; }
    return m == NULL && strstr(msg, name) && strstr(msg, expect1) && (!expect2 || strstr(msg, expect2));
}
static int test_bad_files(void) {
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    test_mesh b = test_mesh_box(lo, hi);
    unsigned char* bytes;
    size_t size;
    sps_mesh_def d = sps_default_mesh_def();
    sps_mesh* m = NULL;
    sps_mesh_info info;
    char msg[512];
    float inf = (float)HUGE_VAL;
    unsigned u;
    FILE* f;
    ENSURE(refused("missing.stl", NULL, "cannot open", NULL));
    ENSURE(write_text("empty.stl", "") == 0 && refused("empty.stl", NULL, "empty", NULL));
    bytes = test_stl_binary(&b, &size);
    ENSURE(test_write_bytes(path_of("short.stl"), bytes, size - 7) == 0 && refused("short.stl", NULL, "12 triangles needs 684 bytes", "has 677"));
    memcpy(&u, &inf, 4);
    test_put_le32(bytes + 84 + 50 * 4 + 12 + 4, u); /* triangle 5, vertex 1, y */
    ENSURE(test_write_bytes(path_of("inf.stl"), bytes, size) == 0 && refused("inf.stl", NULL, "triangle 5, vertex 1: coordinate y", "not finite"));
    free(bytes);
    bytes = (unsigned char*)calloc(100, 1);
    memcpy(bytes, "\x89PNG\r\n\x1a\n", 8);
    ENSURE(test_write_bytes(path_of("picture.png"), bytes, 100) == 0 && refused("picture.png", NULL, "not a mesh file", NULL));
    free(bytes);
    ENSURE(write_text("words.txt", "Dear reader,\nthis is a letter.\n") == 0 && refused("words.txt", NULL, "not a mesh file", "'Dear'"));
    ENSURE(write_text("nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n") == 0
           && refused("nan.stl", NULL, "line 5", "'nan' is not a finite number"));
    ENSURE(write_text("syntax.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n") == 0
           && refused("syntax.stl", NULL, "line 6", "expected 'vertex', found 'endloop'"));
    ENSURE(write_text("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n") == 0 && refused("index.obj", NULL, "line 4", "'4': vertex index out of range"));
    ENSURE(write_text("negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n") == 0 && refused("negative.obj", NULL, "line 4", "'-4'"));
    ENSURE(write_text("corners.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n") == 0 && refused("corners.obj", NULL, "line 3", "3 corners"));
    ENSURE(write_text("inf.obj", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n") == 0 && refused("inf.obj", NULL, "line 2", "'inf' is not a finite number"));
    /* the box without its top (triangles 3, 4): 4 boundary edges */
    f = fopen(path_of("open.obj"), "w");
    ENSURE(f != NULL);
    {
        int i;
        for (i = 0; i < 8; ++i) fprintf(f, "v %g %g %g\n", b.v[3 * i], b.v[3 * i + 1], b.v[3 * i + 2]);
        for (i = 0; i < 12; ++i) if (i != 2 && i != 3) fprintf(f, "f %d %d %d\n", b.t[3 * i] + 1, b.t[3 * i + 1] + 1, b.t[3 * i + 2] + 1);
        fclose(f);
    }
    ENSURE(refused("open.obj", NULL, "not closed", "4 boundary"));
    d.allow_open = 1;
    ENSURE(sps_mesh_load(path_of("open.obj"), &d, &m, msg, sizeof msg) == SPS_OK);
    info = sps_mesh_get_info(m);
    ENSURE(info.boundary_edges == 4 && !info.closed && info.elements == 10);
    sps_mesh_destroy(m);
    d.allow_open = 0;
    /* inverted: every triangle turned over */
    {
        test_mesh inv = test_mesh_box(lo, hi);
        int i;
        for (i = 0; i < 12; ++i) { const int t = inv.t[3 * i + 1]; inv.t[3 * i + 1] = inv.t[3 * i + 2]; inv.t[3 * i + 2] = t; }
        ENSURE(test_write_stl_ascii(path_of("inverted.stl"), &inv) == 0);
        ENSURE(refused("inverted.stl", NULL, "face inwards", "flip = 1"));
        d.flip = 1;
        ENSURE(sps_mesh_load(path_of("inverted.stl"), &d, &m, msg, sizeof msg) == SPS_OK);
        ENSURE_NEAR(sps_mesh_get_info(m).volume, 1, 1e-12);
        sps_mesh_destroy(m);
        d.flip = 0;
        /* one triangle turned over: inconsistently oriented */
        test_mesh_free(&inv);
        inv = test_mesh_box(lo, hi);
        { const int t = inv.t[1]; inv.t[1] = inv.t[2]; inv.t[2] = t; }
        ENSURE(test_write_obj(path_of("inconsistent.obj"), &inv) == 0);
        ENSURE(refused("inconsistent.obj", NULL, "not consistently oriented", "3 inconsistently"));
        test_mesh_free(&inv);
    }
    /* a degenerate triangle (three points on a line) is skipped and counted */
    f = fopen(path_of("degenerate.obj"), "w");
    ENSURE(f != NULL);
    {
        int i;
        for (i = 0; i < 8; ++i) fprintf(f, "v %g %g %g\n", b.v[3 * i], b.v[3 * i + 1], b.v[3 * i + 2]);
        fprintf(f, "v 0.5 0 0\n");
        for (i = 0; i < 12; ++i) fprintf(f, "f %d %d %d\n", b.t[3 * i] + 1, b.t[3 * i + 1] + 1, b.t[3 * i + 2] + 1);
        fprintf(f, "f 1 9 2\nf 1 1 2\n");
        fclose(f);
    }
    ENSURE(sps_mesh_load(path_of("degenerate.obj"), NULL, &m, msg, sizeof msg) == SPS_OK);
    info = sps_mesh_get_info(m);
    ENSURE(info.degenerate == 2 && info.elements == 12 && info.closed);
    sps_mesh_destroy(m);
    ENSURE(write_text("all_degenerate.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n") == 0 && refused("all_degenerate.obj", NULL, "no triangle", "1 degenerate"));
    /* 2D */
    ENSURE(write_text("bowtie.txt", "0 0\n1 1\n1 0\n0 1\n") == 0 && refused("bowtie.txt", NULL, "ring 1 crosses itself", NULL));
    ENSURE(write_text("two_rings.txt", "0 0\n2 0\n2 2\n0 2\n\n1 1\n3 1\n3 3\n1 3\n") == 0 && refused("two_rings.txt", NULL, "crosses another ring", NULL));
    ENSURE(write_text("two_points.txt", "0 0\n1 0\n\n0 0\n1 0\n1 1\n") == 0 && refused("two_points.txt", NULL, "line 3: ring 1 has 2", NULL));
    ENSURE(write_text("three_numbers.txt", "0 0\n1 0 5\n1 1\n") == 0 && refused("three_numbers.txt", NULL, "line 2", "more than two"));
    ENSURE(write_text("arc.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<path d=\"M 0 0 A 5 5 0 0 1 10 0 Z\"/>\n</svg>\n") == 0
           && refused("arc.svg", NULL, "line 2", "arcs"));
    ENSURE(write_text("transform.svg", "<svg>\n<g transform=\"translate(5,0)\">\n<path d=\"M 0 0 L 1 0 L 0 1 Z\"/></g>\n</svg>\n") == 0
           && refused("transform.svg", NULL, "line 2", "transform"));
    ENSURE(write_text("badpath.svg", "<svg>\n\n<path d=\"M 0 0 L 1 Z\"/>\n</svg>\n") == 0 && refused("badpath.svg", NULL, "line 3", "'L' needs 2"));
    ENSURE(write_text("nopath.svg", "<svg>\n</svg>\n") == 0 && refused("nopath.svg", NULL, "without paths", NULL));
    /* nothing is added to the world: a mesh of the wrong dimension */
    {
        sps_body body;
        sps_world* w = make_world(2, 0.1, &body, SPS_MATERIAL_ELASTIC);
        ENSURE(w != NULL);
        ENSURE(sps_mesh_load(path_of("degenerate.obj"), NULL, &m, msg, sizeof msg) == SPS_OK);
        ENSURE(sps_body_add_mesh(w, body, m, NULL, NULL, -1, NULL) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "the mesh is 3D"));
        ENSURE(sps_body_add_mesh_shell(w, body, m, NULL, NULL, 0, NULL) == SPS_ERR_INVALID_ARG);
        ENSURE(sps_world_particle_count(w) == 0);
        sps_mesh_destroy(m);
        sps_world_destroy(w);
    }
    /* the arrays' checks */
    {
        sps_real v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        int t[3] = {0, 1, 3}, counts[1] = {3};
        ENSURE(sps_mesh_from_triangles(3, v, 1, t, NULL, &m, msg, sizeof msg) == SPS_ERR_INVALID_ARG && m == NULL && strstr(msg, "triangle 0: vertex index 3"));
        v[4] = (sps_real)NAN;
        t[2] = 2;
        ENSURE(sps_mesh_from_triangles(3, v, 1, t, NULL, &m, msg, sizeof msg) == SPS_ERR_INVALID_ARG && strstr(msg, "vertex 1"));
        ENSURE(sps_mesh_from_rings(1, counts, v, NULL, &m, msg, sizeof msg) == SPS_ERR_INVALID_ARG && strstr(msg, "ring 0, point 2"));
        d.scale = 0;
        ENSURE(sps_mesh_from_rings(1, counts, v, &d, &m, msg, sizeof msg) == SPS_ERR_INVALID_ARG && strstr(msg, "scale = 0"));
    }
    test_mesh_free(&b);
    return 0;
}

/* ---- 2D outlines: a square with a square hole (text), a disc of Bezier curves (SVG) ---- */
static int test_outlines(void) {
    sps_mesh* m = NULL;
    sps_mesh_info info;
    sps_mesh_def d = sps_default_mesh_def();
    char msg[512];
    sps_real x[3] = {0, 0, 0};
    const double k = 0.5522847498307936; /* the cubic Bezier quarter circle (radius error 2.7e-4) */
    char svg[1024];
    double worst = 0;
    int i;
    ENSURE(write_text("frame.txt", "# a 4 x 4 square with a 2 x 2 hole\n0 0\n4 0\n4 4\n0 4\n0 0\n\n# the hole, clockwise\n1,1\n1,3\n3,3\n3,1\n") == 0);
    ENSURE(sps_mesh_load(path_of("frame.txt"), NULL, &m, msg, sizeof msg) == SPS_OK);
    info = sps_mesh_get_info(m);
    ENSURE(info.dim == 2 && info.rings == 2 && info.elements == 8 && info.degenerate == 1);
    ENSURE_NEAR(info.volume, 12, 1e-12);
    ENSURE_NEAR(info.area, 16 + 8, 1e-12);
    x[0] = 0.5; x[1] = 2; ENSURE_NEAR(sps_mesh_sdf(x, m), -0.5, 1e-12);  /* in the frame */
    x[0] = 2; ENSURE_NEAR(sps_mesh_sdf(x, m), 1, 1e-12);                 /* in the hole */
    x[0] = 5; x[1] = 5; ENSURE_NEAR(sps_mesh_sdf(x, m), sqrt(2.0), 1e-12); /* outside a corner */
    x[0] = 1; x[1] = 2; ENSURE_NEAR(sps_mesh_sdf(x, m), 0, 1e-12);
    sps_mesh_destroy(m);
    /* a disc of radius 10 as four cubic curves, y down as SVG draws; relative and smooth commands */
    snprintf(svg, sizeof svg,
             "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 40 40\">\n"
             "<path fill=\"black\" d=\"M20,10 C%.17g,10 30,%.17g 30,20 S%.17g,30 20,30 c%.17g,0 -10,%.17g -10,-10 s%.17g,-10 10,-10z\"/>\n</svg>\n",
             20 + 10 * k, 20 - 10 * k, 20 + 10 * k, -10 * k, -10 + 10 * k, 10 - 10 * k);
    ENSURE(write_text("disc.svg", svg) == 0);
    d.chord_error = (sps_real)1e-3;
    ENSURE(sps_mesh_load(path_of("disc.svg"), &d, &m, msg, sizeof msg) == SPS_OK);
    info = sps_mesh_get_info(m);
    printf("    SVG disc r = 10 (chord error 1e-3): %d segments, area %.5f (pi r^2 %.5f), perimeter %.5f\n", info.elements, (double)info.volume,
           314.159265358979, (double)info.area);
    for (i = 0; i < 3600; ++i) { /* on circles r 5 .. 15 about (20, -20) */
        const double r = 5 + 10 * (i % 11) / 10.0, a = 2 * 3.14159265358979323846 * i / 3600;
        double e;
        x[0] = (sps_real)(20 + r * cos(a)); x[1] = (sps_real)(-20 + r * sin(a));
        e = fabs((double)sps_mesh_sdf(x, m) - (r - 10));
        if (e > worst) worst = e;
    }
    printf("    largest |distance - circle's| %.3g (chord error 1e-3 + Bezier's 2.7e-3)\n", worst);
    ENSURE(worst <= 1e-3 + 2.8e-3); /* the flattening's chord error and the 4-curve circle's own 2.7e-4 r */
    ENSURE_NEAR(info.volume, 314.159265358979, 0.01 * 314.16); /* the same errors over the perimeter */
    sps_mesh_destroy(m);
    return 0;
}

/* ---- a container: a wall shell around a mesh, water filled inside ---- */
static int test_container(void) {
    /* a U-tube: two legs 0.2 wide joined at the bottom, 0.6 high (an outline, counter-clockwise) */
    const sps_real xy[] = {0, 0, 0.6, 0, 0.6, 0.6, 0.4, 0.6, 0.4, 0.2, 0.2, 0.2, 0.2, 0.6, 0, 0.6};
    const int count[1] = {8};
    const double dp = 0.02;
    sps_mesh* m = NULL;
    sps_body wall, water;
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w;
    char msg[512];
    const sps_real *x, *y;
    const sps_real lo[3] = {-1, -1, -1}, top[3] = {1, (sps_real)0.6, 1}, level[3] = {1, (sps_real)0.5, 1};
    int n_wall, n_water, i, j, n;
    double closest = 1e30;
    ENSURE(sps_mesh_from_rings(1, count, xy, NULL, &m, msg, sizeof msg) == SPS_OK);
    wd.dim = 2; wd.dp = (sps_real)dp; wd.threads = 1; wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.material.kind = SPS_MATERIAL_RIGID;
    ENSURE(sps_world_add_body(w, &bd, &wall) == SPS_OK);
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 20;
    ENSURE(sps_world_add_body(w, &bd, &water) == SPS_OK);
    ENSURE(sps_body_add_mesh_shell(w, wall, m, lo, top, 3, &n_wall) == SPS_OK); /* open at the top */
    ENSURE(sps_body_add_mesh(w, water, m, lo, level, -1, &n_water) == SPS_OK);  /* water 0.5 deep */
    printf("    U-tube: %d wall particles (3 layers), %d water particles (outline area / dp^2 = %.1f)\n", n_wall, n_water,
           (double)sps_mesh_get_info(m).volume / (dp * dp));
    ENSURE(n_water == (int)((0.5 * 0.6 - 0.3 * 0.2) / (dp * dp) + 0.5)); /* the lattice cells of the outline below 0.5 (it lies on the cells' faces) */
    n = sps_world_particle_count(w);
    x = sps_world_field(w, SPS_FIELD_POSITION_X);
    y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    for (i = 0; i < n; ++i) /* one lattice: no two particles closer than dp */
        for (j = i + 1; j < n; ++j) {
            const double dx = x[i] - x[j], dy = y[i] - y[j];
            if (dx * dx + dy * dy < closest) closest = dx * dx + dy * dy;
        }
    ENSURE_NEAR(sqrt(closest), dp, 1e-9 * dp);
    /* the shell: none above the top */
    for (i = 0; i < n; ++i) ENSURE(y[i] < 0.6);
    /* 3 layers outside: 3 x 30 beside each leg and below, the corners' 8 of 9 (the farthest
       is 3.5 dp off), and in the notch between the legs 3 x 10 above the bridge and 2 x 3 x 17 beside it */
    ENSURE(n_wall == 3 * 90 + 2 * 8 + 30 + 102);
    sps_mesh_destroy(m);
    sps_world_destroy(w);
    return 0;
}

static void run(const char* name, int (*fn)(void)) {
    double t0 = wall_seconds();
    int r;
    printf("%s\n", name);
    fflush(stdout);
    r = fn();
    printf("  %.2f s\n", wall_seconds() - t0);
    if (r == 0) g_passed++; else { g_failed++; printf("  FAILED %s\n", name); }
}

int main(int argc, char** argv) {
    char cmd[600];
    if (argc > 1) g_dir = argv[1];
    snprintf(cmd, sizeof cmd, "mkdir -p '%s'", g_dir);
    if (system(cmd) != 0) { printf("cannot make %s\n", g_dir); return 1; }
    run("formats_identical", test_formats_identical);
    run("sphere_20k", test_sphere);
    run("box_and_transform", test_box_and_transform);
    run("bad_files", test_bad_files);
    run("outlines", test_outlines);
    run("container", test_container);
    printf("%d passed, %d failed\n", g_passed, g_failed);
    return g_failed != 0;
}
