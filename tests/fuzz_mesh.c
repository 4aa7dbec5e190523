/* fuzz_mesh.c - damaged mesh files: sps_mesh_load must refuse them with a message or make a
   valid mesh, and never touch memory it does not own.

   Seven valid files are built in memory: a binary STL, an ASCII STL and an OBJ of a box and of
   a small sphere, an outline with a hole and an SVG drawing of curves, lines and a polygon.
   Case k mutates file (S + k) % 7 deterministically (seed S + k): flipped bits, truncation, bytes
   overwritten with words of the formats or with numbers that break them (NaN, infinite, huge,
   negative and out-of-range indices), the binary STL's count set small, huge or off by one,
   chunks deleted, doubled or copied from elsewhere; then loads it with a random def (flip,
   allow_open, chord error). Properties checked for every case:
     - no crash, no sanitizer report (make test runs it under ASan and UBSan);
     - a refusal sets the mesh to NULL and its message names the file;
     - an accepted mesh reports elements > 0, finite bounds, volume and area, and its signed
       distance is finite at points in and around its box.
   The counts are printed at the end; the exit status is 0 only when every case held.

   Build: make build/fuzz_mesh_sanitize (ASan + UBSan).
   Usage: fuzz_mesh [--seed S] [--cases N] [--dir DIR] [--verbose]; replay a case: --seed S+k --cases 1 --verbose */
#define _POSIX_C_SOURCE 200809L
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_files.h"

static unsigned long long g_rng;
static unsigned long long next_u64(void) { /* splitmix64 */
    unsigned long long z = (g_rng += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}
static size_t below(size_t n) { return n ? (size_t)(next_u64() % n) : 0; }

typedef struct {
    unsigned char* bytes;
    size_t size;
    const char* name;
} seed_file;

/* A text file of a mesh (ASCII STL or OBJ) in memory, through a temporary file. */
static seed_file text_of(const char* dir, const char* name, const test_mesh* m, int obj) {
    char path[600];
    seed_file f;
    FILE* in;
    long size;
    snprintf(path, sizeof path, "%s/seed_%s", dir, name);
    if (obj) test_write_obj(path, m); else test_write_stl_ascii(path, m);
    in = fopen(path, "rb");
    fseek(in, 0, SEEK_END); size = ftell(in); fseek(in, 0, SEEK_SET);
    f.bytes = (unsigned char*)malloc((size_t)size + 1);
    f.size = fread(f.bytes, 1, (size_t)size, in);
    fclose(in);
    f.name = name;
    return f;
}
static seed_file string_of(const char* name, const char* text) {
    seed_file f;
    f.size = strlen(text);
    f.bytes = (unsigned char*)malloc(f.size + 1);
    memcpy(f.bytes, text, f.size);
    f.name = name;
    return f;
}

static const char* words[] = {"nan", "inf", "-inf", "1e999", "-1e308", "0", "-0", "1e-320", "9999999999", "-2147483648", "2147483647", "-1",
                              "/", "//", "\n", " ", "\r\n", ",", "#", "solid", "endsolid", "facet", "normal", "outer", "loop", "vertex",
                              "endloop", "endfacet", "v", "f", "vt", "vn", "g", "<path d=\"", "\"/>", "<svg>", "<polygon points=\"", "M",
                              "m", "L", "l", "H", "h", "V", "v", "C", "c", "S", "s", "Q", "q", "T", "t", "Z", "z", "A", "transform=", "<",
                              ">", "\"", "'", "e", "E", ".", "-", "+", "\t", "\f"};

/* One mutation of f (in place; f->bytes has room for f->size + extra bytes). */
static void mutate(seed_file* f, size_t cap, int is_binary_stl) {
    const int kind = (int)below(9);
    size_t i, n;
    switch (kind) {
    case 0: /* flipped bits */
        for (n = 1 + below(8), i = 0; i < n && f->size; ++i) f->bytes[below(f->size)] ^= (unsigned char)(1u << below(8));
        break;
    case 1: /* truncation */
        f->size = below(f->size + 1);
        break;
    case 2: case 3: { /* a word written over the bytes at a random place */
        const char* w = words[below(sizeof words / sizeof *words)];
        const size_t at = below(f->size + 1), len = strlen(w);
        if (at + len <= cap) { memcpy(f->bytes + at, w, len); if (at + len > f->size) f->size = at + len; }
        break;
    }
    case 4: { /* a word inserted */
        const char* w = words[below(sizeof words / sizeof *words)];
        const size_t at = below(f->size + 1), len = strlen(w);
        if (f->size + len <= cap) { memmove(f->bytes + at + len, f->bytes + at, f->size - at); memcpy(f->bytes + at, w, len); f->size += len; }
        break;
    }
    case 5: { /* a chunk deleted */
        const size_t at = below(f->size + 1), len = below(f->size - at + 1);
        memmove(f->bytes + at, f->bytes + at + len, f->size - at - len);
        f->size -= len;
        break;
    }
    case 6: { /* a chunk copied over another place (or appended: doubled) */
        const size_t from = below(f->size + 1), len = below(f->size - from + 1), to = below(f->size + 1);
        if (to + len <= cap) { memmove(f->bytes + to, f->bytes + from, len); if (to + len > f->size) f->size = to + len; }
        break;
    }
    case 7: /* the binary STL's count: small, huge or off by one (a text file: random bytes) */
        if (f->size >= 84) {
            const unsigned old = (unsigned)f->bytes[80] | (unsigned)f->bytes[81] << 8 | (unsigned)f->bytes[82] << 16 | (unsigned)f->bytes[83] << 24;
            const unsigned counts[5] = {0, 1, old + 1, old - 1, 0xffffffffu};
            test_put_le32(f->bytes + 80, is_binary_stl ? counts[below(5)] : (unsigned)next_u64());
        }
        break;
    default: /* random bytes */
        for (n = 1 + below(4), i = 0; i < n && f->size; ++i) f->bytes[below(f->size)] = (unsigned char)next_u64();
        break;
    }
}

/* Loads path; checks the properties. 0 if they held. */
static int check(const char* path, int verbose, int* accepted) {
    sps_mesh_def d = sps_default_mesh_def();
    sps_mesh* m = (sps_mesh*)&d;
    char msg[1024] = "";
    sps_result r;
    d.flip = below(8) == 0;
    d.allow_open = below(3) == 0;
    d.chord_error = below(2) ? 0 : (sps_real)(0.05 + 0.5 * (double)below(100) / 100);
    r = sps_mesh_load(path, &d, &m, msg, sizeof msg);
    if (verbose) printf("  %s -> %s\n", path, r == SPS_OK ? "accepted" : msg);
    if (r != SPS_OK) {
        if (m != NULL || !strstr(msg, path)) { printf("  refusal without a clean state or the file's name: %s\n", msg); return 1; }
        return 0;
    }
    {
        const sps_mesh_info info = sps_mesh_get_info(m);
        int a, k, bad = info.elements <= 0 || !(info.volume - info.volume == 0) || !(info.area - info.area == 0);
        for (a = 0; a < 3; ++a) bad |= !(info.lo[a] <= info.hi[a]) || !(info.hi[a] - info.lo[a] < (sps_real)INFINITY);
        for (k = 0; k < 16 && !bad; ++k) {
            sps_real x[3], s;
            for (a = 0; a < 3; ++a) x[a] = info.lo[a] + (info.hi[a] - info.lo[a]) * (sps_real)(1.4 * (double)below(1000) / 1000 - 0.2);
            s = sps_mesh_sdf(x, m);
            bad |= !(s - s == 0);
        }
        sps_mesh_destroy(m);
        ++*accepted;
        if (bad) printf("  accepted mesh with a bad report or distance\n");
        return bad;
    }
}

int main(int argc, char** argv) {
    unsigned long long seed = 1;
    int cases = 1000, verbose = 0, i, failed = 0, accepted = 0, k;
    const char* dir = "build";
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 0.5}, c[3] = {0.1, 0.2, 0.3};
    seed_file files[7];
    char path[600];
    size_t cap = 0;
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--seed") && i + 1 < argc) seed = strtoull(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--cases") && i + 1 < argc) cases = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--dir") && i + 1 < argc) dir = argv[++i];
        else if (!strcmp(argv[i], "--verbose")) verbose = 1;
        else { printf("usage: fuzz_mesh [--seed S] [--cases N] [--dir DIR] [--verbose]\n"); return 2; }
    }
    {
        test_mesh box = test_mesh_box(lo, hi), ball = test_mesh_sphere(0.5, c, 5, 6);
        files[0].bytes = test_stl_binary(&box, &files[0].size); files[0].name = "box_binary.stl";
        files[1].bytes = test_stl_binary(&ball, &files[1].size); files[1].name = "ball_binary.stl";
        files[2] = text_of(dir, "box_ascii.stl", &box, 0);
        files[3] = text_of(dir, "ball.obj", &ball, 1);
        test_mesh_free(&box); test_mesh_free(&ball);
    }
    files[4] = string_of("frame.txt", "# outer\n0 0\n4 0\n4 4\n0 4\n\n# hole\n1,1\n1,3\n3,3\n3,1\n");
    files[5] = string_of("drawing.svg", "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\">\n"
                                        "<path d=\"M20,10 C25.5,10 30,14.5 30,20 S25.5,30 20,30 q-10,0 -10,-10 t10,-10z\"/>\n"
                                        "<path d=\"m 40 40 h 10 v 10 H 40 Z M 42 42 L 42 48 L 48 48 L 48 42 z\"/>\n"
                                        "<polygon points=\"60,0 70,0 65,8\"/>\n</svg>\n");
    files[6] = string_of("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3/1 4\nf -4 -1 -2\n");
    for (k = 0; k < 7; ++k) if (files[k].size > cap) cap = files[k].size;
    cap += 4096;
    for (i = 0; i < cases; ++i) {
        seed_file f;
        int m, rounds;
        g_rng = seed + (unsigned long long)i;
        k = (int)((seed + (unsigned long long)i) % 7);
        f.bytes = (unsigned char*)malloc(cap);
        memcpy(f.bytes, files[k].bytes, files[k].size);
        f.size = files[k].size;
        f.name = files[k].name;
        rounds = 1 + (int)below(3);
        for (m = 0; m < rounds; ++m) mutate(&f, cap, k < 2);
        snprintf(path, sizeof path, "%s/fuzz_mesh_%s", dir, f.name);
        if (test_write_bytes(path, f.bytes, f.size)) { printf("cannot write %s\n", path); return 2; }
        if (check(path, verbose, &accepted)) { printf("case %d (seed %llu) failed\n", i, seed + (unsigned long long)i); ++failed; }
        free(f.bytes);
    }
    for (k = 0; k < 7; ++k) free(files[k].bytes);
    printf("fuzz_mesh: %d damaged files, %d accepted as valid meshes, %d refused with a message, %d failed\n", cases, accepted, cases - accepted - failed,
           failed);
    return failed != 0;
}
