/* mesh_files.h - meshes and the files that hold them, for the geometry tests, the mesh fuzz test
   and the geometry bench (tests/test_geometry.c, tests/fuzz_mesh.c, bench/mesh_cost.c): a
   latitude-longitude sphere, a box, and writers of binary STL, ASCII STL and OBJ. Coordinates
   are rounded to float (what binary STL stores) and written with 17 digits, so the three files
   of one mesh hold the same numbers. Include after <stdio.h>, <stdlib.h>, <math.h>. */
#ifndef SPS_TESTS_MESH_FILES_H
#define SPS_TESTS_MESH_FILES_H
/* each program uses some of these */
#if defined(__GNUC__) || defined(__clang__)
#define TEST_MESH_FN static __attribute__((unused))
#else
#define TEST_MESH_FN static
#endif

typedef struct test_mesh {
    int nv, nt;
    double* v; /* 3 per vertex */
    int* t;    /* 3 per triangle, counter-clockwise seen from outside */
} test_mesh;

TEST_MESH_FN void test_mesh_free(test_mesh* m) { free(m->v); free(m->t); m->v = NULL; m->t = NULL; }

/* A sphere of radius R about c: nlat rings of latitude between the poles (nlat >= 2), nlon
   points each; 2 nlon (nlat - 1) triangles. The vertices lie on the sphere (to float rounding). */
TEST_MESH_FN test_mesh test_mesh_sphere(double R, const double c[3], int nlat, int nlon) {
    test_mesh m;
    const double pi = 3.14159265358979323846;
    int i, j, k = 0, n;
    m.nv = 2 + (nlat - 1) * nlon;
    m.nt = 2 * nlon * (nlat - 1);
    m.v = (double*)malloc(sizeof(double) * 3 * (size_t)m.nv);
    m.t = (int*)malloc(sizeof(int) * 3 * (size_t)m.nt);
    m.v[0] = c[0]; m.v[1] = c[1]; m.v[2] = c[2] - R; /* south pole: vertex 0 */
    for (i = 1; i < nlat; ++i)
        for (j = 0; j < nlon; ++j) {
            const double th = pi * i / nlat, ph = 2 * pi * j / nlon;
            n = 1 + (i - 1) * nlon + j;
            m.v[3 * n] = c[0] + R * sin(th) * cos(ph);
            m.v[3 * n + 1] = c[1] + R * sin(th) * sin(ph);
            m.v[3 * n + 2] = c[2] - R * cos(th);
        }
    n = m.nv - 1; /* north pole */
    m.v[3 * n] = c[0]; m.v[3 * n + 1] = c[1]; m.v[3 * n + 2] = c[2] + R;
    for (i = 0; i < 3 * m.nv; ++i) m.v[i] = (double)(float)m.v[i];
    for (j = 0; j < nlon; ++j) { /* the caps, then the bands (outward: counter-clockwise seen from outside) */
        const int a = 1 + j, b = 1 + (j + 1) % nlon, top = 1 + (nlat - 2) * nlon;
        m.t[k++] = 0; m.t[k++] = b; m.t[k++] = a;
        m.t[k++] = m.nv - 1; m.t[k++] = top + j; m.t[k++] = top + (j + 1) % nlon;
    }
    for (i = 1; i < nlat - 1; ++i)
        for (j = 0; j < nlon; ++j) {
            const int a = 1 + (i - 1) * nlon + j, b = 1 + (i - 1) * nlon + (j + 1) % nlon, c2 = a + nlon, d = b + nlon;
            m.t[k++] = a; m.t[k++] = b; m.t[k++] = d;
            m.t[k++] = a; m.t[k++] = d; m.t[k++] = c2;
        }
    return m;
}

/* The box [lo, hi]: 8 vertices, 12 triangles. */
TEST_MESH_FN test_mesh test_mesh_box(const double lo[3], const double hi[3]) {
    static const int tri[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
    test_mesh m;
    int i;
    m.nv = 8; m.nt = 12;
    m.v = (double*)malloc(sizeof(double) * 24);
    m.t = (int*)malloc(sizeof(int) * 36);
    for (i = 0; i < 8; ++i) {
        m.v[3 * i] = (i & 1) ^ (i >> 1 & 1) ? hi[0] : lo[0];
        m.v[3 * i + 1] = i & 2 ? hi[1] : lo[1];
        m.v[3 * i + 2] = i & 4 ? hi[2] : lo[2];
    }
    for (i = 0; i < 36; ++i) m.t[i] = tri[i];
    return m;
}

TEST_MESH_FN void test_put_le32(unsigned char* p, unsigned u) {
    p[0] = (unsigned char)(u & 255); p[1] = (unsigned char)(u >> 8 & 255); p[2] = (unsigned char)(u >> 16 & 255); p[3] = (unsigned char)(u >> 24 & 255);
}
/* The binary STL of m in memory (caller frees); *size its length. */
TEST_MESH_FN unsigned char* test_stl_binary(const test_mesh* m, size_t* size) {
    unsigned char* b;
    int i, k, a;
    *size = 84 + 50 * (size_t)m->nt;
    b = (unsigned char*)calloc(*size, 1);
    memcpy(b, "binary STL written by mesh_files.h", 34);
    test_put_le32(b + 80, (unsigned)m->nt);
    for (i = 0; i < m->nt; ++i)
        for (k = 0; k < 3; ++k)
            for (a = 0; a < 3; ++a) {
                const float f = (float)m->v[3 * m->t[3 * i + k] + a];
                unsigned u;
                memcpy(&u, &f, 4);
                test_put_le32(b + 84 + 50 * (size_t)i + 12 + 12 * k + 4 * a, u);
            }
    return b;
}
TEST_MESH_FN int test_write_bytes(const char* path, const void* bytes, size_t size) {
    FILE* f = fopen(path, "wb");
    if (!f) return 1;
    if (fwrite(bytes, 1, size, f) != size) { fclose(f); return 1; }
    return fclose(f) != 0;
}
TEST_MESH_FN int test_write_stl_binary(const char* path, const test_mesh* m) {
    size_t size;
    unsigned char* b = test_stl_binary(m, &size);
    const int bad = test_write_bytes(path, b, size);
    free(b);
    return bad;
}
TEST_MESH_FN int test_write_stl_ascii(const char* path, const test_mesh* m) {
    FILE* f = fopen(path, "w");
    int i, k;
    if (!f) return 1;
    fprintf(f, "solid test\n");
    for (i = 0; i < m->nt; ++i) {
        fprintf(f, "  facet normal 0 0 0\n    outer loop\n");
        for (k = 0; k < 3; ++k) {
            const double* p = m->v + 3 * m->t[3 * i + k];
            fprintf(f, "      vertex %.17g %.17g %.17g\n", p[0], p[1], p[2]);
        }
        fprintf(f, "    endloop\n  endfacet\n");
    }
    fprintf(f, "endsolid test\n");
    return fclose(f) != 0;
}
TEST_MESH_FN int test_write_obj(const char* path, const test_mesh* m) {
    FILE* f = fopen(path, "w");
    int i;
    if (!f) return 1;
    fprintf(f, "# written by mesh_files.h\no test\n");
    for (i = 0; i < m->nv; ++i) fprintf(f, "v %.17g %.17g %.17g\n", m->v[3 * i], m->v[3 * i + 1], m->v[3 * i + 2]);
    fprintf(f, "vn 0 0 1\ng part\n");
    for (i = 0; i < m->nt; ++i) /* negative (relative) indices on every other face */
        if (i % 2) fprintf(f, "f %d//1 %d//1 %d//1\n", m->t[3 * i] + 1, m->t[3 * i + 1] + 1, m->t[3 * i + 2] + 1);
        else fprintf(f, "f %d %d %d\n", m->t[3 * i] - m->nv, m->t[3 * i + 1] - m->nv, m->t[3 * i + 2] - m->nv);
    return fclose(f) != 0;
}
#endif
