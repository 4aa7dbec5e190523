/* fuzz_restore.c - crafted restart files: sps_world_restore must refuse them or restore a valid
   world, and never touch memory it does not own.

   Six scenes are built and saved after a few steps; together they hold every material and
   solver, walls, wall bodies, contact, constraints, observers, the last good state, kept pair
   forces, damage, plastic state and material damping (tests/fuzz_restore_scenes.h). Case k
   mutates the save of scene k % 6 deterministically (seed S + k): flipped bits, truncation (the
   header's length fixed up or not), overwritten words, NaN, infinite, huge and negative reals,
   small and extreme ints, ids swapped, duplicated or out of range, body, constraint and
   neighbour indices out of range, chunks copied from elsewhere; then recomputes the checksum,
   as a crafted or re-saved damaged file has it, and restores it into the world it was saved
   from. Properties checked for every case:
     - no crash, no sanitizer report (make test runs it under ASan and UBSan);
     - a restored world passes sps_world_validate and takes a step without a memory error;
     - a refusal's message names the item that broke a rule (a field, a list, a header item);
     - a refused restore leaves the world's state bit-identical (its save, hashed, before and after).
   The counts are printed at the end; the exit status is 0 only when every case held.

   Build: make build/fuzz_restore_sanitize (ASan + UBSan) or build/fuzz_restore.
   Usage: fuzz_restore [--seed S] [--cases N] [--dir DIR] [--verbose]; replay a case: --seed S+k --cases 1 --verbose;
          fuzz_restore --seeds DIR writes the saves of the scenes at dp = 0.02 (the libFuzzer seeds) into DIR */
#define _POSIX_C_SOURCE 200809L
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"
#include "fuzz_restore_scenes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t g_rng;
static uint64_t next_u64(void) { /* splitmix64 */
    uint64_t z = (g_rng += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}
static size_t below(size_t n) { return n ? (size_t)(next_u64() % n) : 0; }

/* ---- the files ---- */
typedef struct {
    unsigned char* bytes;
    size_t size;
} file_bytes;
static int read_file(const char* path, file_bytes* f) {
    FILE* in = fopen(path, "rb");
    long size;
    if (!in || fseek(in, 0, SEEK_END) != 0 || (size = ftell(in)) < 0 || fseek(in, 0, SEEK_SET) != 0) { if (in) fclose(in); return 1; }
    f->bytes = (unsigned char*)malloc((size_t)size + 1);
    f->size = (size_t)size;
    if (!f->bytes || fread(f->bytes, 1, f->size, in) != f->size) { fclose(in); return 1; }
    fclose(in);
    return 0;
}
static int write_file(const char* path, const unsigned char* bytes, size_t size) {
    FILE* out = fopen(path, "wb");
    if (!out) return 1;
    if (fwrite(bytes, 1, size, out) != size) { fclose(out); return 1; }
    return fclose(out) != 0;
}
/* The world's state as its save holds it, hashed (the save covers every item a restore writes). */
static uint64_t state_hash(sps_world* w, const char* path) {
    file_bytes f;
    uint64_t h;
    if (sps_world_save(w, path) != SPS_OK || read_file(path, &f)) return 0;
    h = sps__fnv(SPS__FNV_OFFSET, f.bytes, f.size);
    free(f.bytes);
    return h;
}

/* ---- the layout of a save: where the payload starts, and landmarks in it ---- */
typedef struct {
    sps_world* w;
    const char* name;
    file_bytes base;     /* the save */
    size_t payload;      /* its payload's offset (the header before it) */
    size_t ids, lists;   /* offsets of the id array and of the neighbour counts (0: not found) */
    int n;
    uint64_t hash;       /* state_hash of the world as saved */
    char path[512];      /* the save's file */
} scene_file;

/* The payload's checksum and length, recomputed: the file a crafted or re-saved one would be. */
static void fix_up(unsigned char* bytes, size_t size, size_t payload) {
    uint64_t length, hash;
    if (size < payload + 8) return;
    length = size - payload - 8;
    memcpy(bytes + 16 + 12, &length, sizeof length);
    hash = sps__fnv(SPS__FNV_OFFSET, bytes + payload, (size_t)length);
    memcpy(bytes + size - 8, &hash, sizeof hash);
}
/* The first offset in the payload where n ints are the permutation 0..n-1 found by the world's
   own id array: the world saved them in slot order (its ids, as bytes). */
static size_t find_bytes(const file_bytes* f, size_t from, const void* needle, size_t size) {
    size_t k;
    for (k = from; k + size <= f->size; ++k)
        if (memcmp(f->bytes + k, needle, size) == 0) return k;
    return 0;
}

/* The saves of the scenes at dp = 0.02 into dir: the seeds of tests/fuzz_restore_libfuzzer.c. */
static int write_seeds(const char* dir) {
    int k;
    for (k = 0; k < FUZZ_SCENES; ++k) {
        char path[512];
        sps_world* w = fuzz_scene_build(k, (sps_real)0.02);
        snprintf(path, sizeof path, "%s/%s.restart", dir, fuzz_scene_name(k));
        if (!w || sps_world_save(w, path) != SPS_OK) { printf("fuzz_restore: seed %s: not written\n", path); return 1; }
        sps_world_destroy(w);
    }
    return 0;
}

/* ---- mutations ---- */
static void put_int(unsigned char* at, int v) { memcpy(at, &v, sizeof v); }
static void put_real(unsigned char* at, sps_real v) { memcpy(at, &v, sizeof v); }
static sps_real hostile_real(void) {
    static const double v[] = {-1, 0, -0.0, 1e300, -1e300, 1e-310, 5e-324, 2, 1e30};
    switch (below(4)) {
    case 0: return (sps_real)NAN;
    case 1: return (sps_real)(below(2) ? INFINITY : -INFINITY);
    default: return (sps_real)v[below(sizeof v / sizeof v[0])];
    }
}
static int hostile_int(int n) {
    const int v[] = {-1, 0, 1, n - 1, n, n + 1, -2147483647 - 1, 2147483647, 1000000, 2};
    return v[below(sizeof v / sizeof v[0])];
}

static const char* const mutation_names[] = {"bits",   "truncate", "word", "real", "int",   "id swap",
                                            "id dup", "index",    "list", "copy", "header", "scalars"};
#define MUTATIONS ((int)(sizeof mutation_names / sizeof mutation_names[0]))

/* Applies mutation kind to the copy m (size *size, room for the base's size) of scene s's save. */
static void mutate(const scene_file* s, int kind, unsigned char* m, size_t* size) {
    const size_t pay = s->payload, body = pay + (*size - pay - 8);
    const size_t span = body - pay;
    size_t at = pay + below(span), k;
    int n = s->n;
    switch (kind) {
    case 0: /* 1 to 8 flipped bits */
        for (k = 1 + below(8); k > 0; --k) { at = pay + below(span); m[at] ^= (unsigned char)(1u << below(8)); }
        break;
    case 1: /* truncated, the header's length fixed up for half of them */
        *size = pay + below(span) + (below(2) ? 8 : 0);
        break;
    case 2: /* a word of random bytes */
        for (k = 0; k < 8 && at + k < body; ++k) m[at + k] = (unsigned char)next_u64();
        break;
    case 3: /* a hostile real, anywhere */
        if (at + sizeof(sps_real) <= body) put_real(m + at, hostile_real());
        break;
    case 4: /* a hostile int, anywhere */
        if (at + sizeof(int) <= body) put_int(m + at, hostile_int(n));
        break;
    case 5: /* two ids swapped (their particles' states no longer theirs) */
        if (s->ids) {
            size_t i = below((size_t)n), j = below((size_t)n);
            unsigned char t[sizeof(int)];
            memcpy(t, m + s->ids + i * sizeof(int), sizeof t);
            memcpy(m + s->ids + i * sizeof(int), m + s->ids + j * sizeof(int), sizeof t);
            memcpy(m + s->ids + j * sizeof(int), t, sizeof t);
        }
        break;
    case 6: /* an id duplicated or out of range */
        if (s->ids) put_int(m + s->ids + below((size_t)n) * sizeof(int), below(2) ? (int)below((size_t)n) : hostile_int(n));
        break;
    case 7: /* a body or constraint index (the arrays after the ids, each after its presence byte) */
        if (s->ids) {
            const size_t array = s->ids + (size_t)n * sizeof(int) + 1 + (below(2) ? (size_t)n * sizeof(int) + 1 : 0);
            if (array + (size_t)n * sizeof(int) <= body) put_int(m + array + below((size_t)n) * sizeof(int), hostile_int(n));
        }
        break;
    case 8: /* a neighbour count or index */
        if (s->lists) {
            const size_t off = s->lists + below((size_t)n * sizeof(int) * 8);
            if (off + sizeof(int) <= body) put_int(m + off - (off - s->lists) % sizeof(int), below(2) ? hostile_int(n) : (int)below((size_t)n));
        }
        break;
    case 9: { /* a chunk copied from elsewhere in the payload */
        const size_t from = pay + below(span), len = 1 + below(64);
        if (from + len <= body && at + len <= body) memmove(m + at, m + from, len);
        break;
    }
    case 10: /* the header and fingerprint */
        m[below(pay)] ^= (unsigned char)(1u << below(8));
        break;
    default: /* the first items: time, time step, speed, counters, flags, message */
        at = pay + below(64);
        if (below(2)) put_real(m + at - (at - pay) % sizeof(sps_real), hostile_real());
        else put_int(m + at - (at - pay) % sizeof(int), hostile_int(2));
        break;
    }
}

/* ---- what a refusal must name ---- */
/* Every item a refusal can be about: the fields, the items of the payload, the header's. */
static const char* const item_names[] = {
    "time", "time step", "maximum speed", "step count", "stopped flag", "failure message", "energy watchdog",
    "impact warning flag", "mean rotation", "mean spin", "fragment warning flag", "list flag", "neighbour", "kept pair",
    "last good", "payload length", "bodies, reference positions, masses or constraints", "truncated", "too long",
    "checksum", "another scene", "restart header", "format version", "byte-order", "-byte reals"};
static int names_an_item(const char* msg) {
    size_t k;
    for (k = 0; k < sizeof item_names / sizeof item_names[0]; ++k)
        if (strstr(msg, item_names[k])) return 1;
    for (k = 0; k < (size_t)SPS__NFIELDS; ++k) /* the "what" of every per-particle field */
        if (strstr(msg, sps__fields[k].what)) return 1;
    return 0;
}

typedef struct {
    long cases, restored, refused, by_code[8], by_mutation_refused[MUTATIONS], by_mutation[MUTATIONS];
    long invalid, unnamed, changed, reset_failed;
} counts;

static int run_case(scene_file* s, const char* path, int verbose, counts* c) {
    unsigned char* m = (unsigned char*)malloc(s->base.size + 8);
    size_t size = s->base.size;
    const int kind = (int)below(MUTATIONS);
    char msg[2048];
    sps_result r;
    int bad = 0;
    memcpy(m, s->base.bytes, size);
    mutate(s, kind, m, &size);
    if (kind != 10 && (kind != 1 || below(2))) fix_up(m, size, s->payload); /* the header's own damage is kept as is */
    if (write_file(path, m, size)) { free(m); return 1; }
    free(m);
    ++c->cases;
    ++c->by_mutation[kind];
    r = sps_world_restore(s->w, path);
    if (r == SPS_OK) {
        ++c->restored;
        if (sps_world_validate(s->w, msg, sizeof msg) != SPS_OK) {
            ++c->invalid;
            bad = 1;
            printf("  %s/%s: restored a world that validate refuses: %s\n", s->name, mutation_names[kind], msg);
        }
        sps_world_step(s->w); /* any result; the sanitizers watch the memory */
        if (sps_world_restore(s->w, s->path) != SPS_OK) { ++c->reset_failed; bad = 1; } /* back to the scene as saved */
    } else {
        const char* e = sps_world_last_error(s->w);
        ++c->refused;
        ++c->by_code[-(int)r & 7];
        ++c->by_mutation_refused[kind];
        if (verbose) printf("  %s/%s: %s\n", s->name, mutation_names[kind], e);
        if (!names_an_item(e)) { ++c->unnamed; bad = 1; printf("  %s/%s: the refusal names no item: %s\n", s->name, mutation_names[kind], e); }
        strncpy(msg, e, sizeof msg - 1);
        msg[sizeof msg - 1] = 0;
        if (state_hash(s->w, path) != s->hash) { ++c->changed; bad = 1; printf("  %s/%s: refused (%s) but the state changed\n", s->name, mutation_names[kind], msg); }
    }
    return bad;
}

int main(int argc, char** argv) {
    uint64_t seed = 1;
    long cases = 1000, k;
    const char* dir = "build";
    int verbose = 0, i, nscenes, failed = 0;
    scene_file scenes[FUZZ_SCENES];
    char path[512];
    counts c;
    memset(&c, 0, sizeof c);
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc) seed = strtoull(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--cases") == 0 && i + 1 < argc) cases = atol(argv[++i]);
        else if (strcmp(argv[i], "--dir") == 0 && i + 1 < argc) dir = argv[++i];
        else if (strcmp(argv[i], "--verbose") == 0) verbose = 1;
        else if (strcmp(argv[i], "--seeds") == 0 && i + 1 < argc) return write_seeds(argv[i + 1]);
        else { fprintf(stderr, "usage: %s [--seed S] [--cases N] [--dir DIR] [--verbose] | --seeds DIR\n", argv[0]); return 2; }
    }
    snprintf(path, sizeof path, "%s/fuzz_restore_case.restart", dir);
    for (nscenes = 0; nscenes < FUZZ_SCENES; ++nscenes) {
        scene_file* s = &scenes[nscenes];
        uint64_t length;
        memset(s, 0, sizeof *s);
        s->name = fuzz_scene_name(nscenes);
        snprintf(s->path, sizeof s->path, "%s/fuzz_restore_%s.restart", dir, s->name);
        if (!(s->w = fuzz_scene_build(nscenes, (sps_real)0.01)) || sps_world_save(s->w, s->path) != SPS_OK || read_file(s->path, &s->base)) {
            printf("fuzz_restore: scene %s: %s\n", s->name, s->w ? sps_world_last_error(s->w) : "not built");
            return 1;
        }
        s->n = s->w->n;
        memcpy(&length, s->base.bytes + 16 + 12, sizeof length); /* the header's payload length */
        s->payload = s->base.size - 8 - (size_t)length;
        s->ids = find_bytes(&s->base, s->payload, s->w->id, sizeof(int) * (size_t)s->n);
        if (s->w->lists_valid) s->lists = find_bytes(&s->base, s->payload, s->w->nb_count, sizeof(int) * (size_t)s->n);
        s->hash = state_hash(s->w, path);
        if (sps_world_restore(s->w, s->path) != SPS_OK || state_hash(s->w, path) != s->hash) { /* its own save: as it was */
            printf("fuzz_restore: scene %s: its own save does not restore bit for bit: %s\n", s->name, sps_world_last_error(s->w));
            return 1;
        }
        printf("scene %-10s %5d particles, %6lu bytes (ids at %lu, lists at %lu)\n", s->name, s->n, (unsigned long)s->base.size,
               (unsigned long)s->ids, (unsigned long)s->lists);
    }
    for (k = 0; k < cases; ++k) {
        scene_file* s = &scenes[k % FUZZ_SCENES];
        g_rng = seed + (uint64_t)k;
        if (verbose) printf("case %ld (seed %llu), scene %s\n", k, (unsigned long long)(seed + (uint64_t)k), s->name);
        if (run_case(s, path, verbose, &c)) {
            printf("  case %ld failed: replay with --seed %llu --cases 1 --verbose\n", k, (unsigned long long)(seed + (uint64_t)k));
            ++failed;
        }
    }
    printf("fuzz_restore: %ld cases over %d scenes: %ld restored, %ld refused (SPS_ERR_IO %ld, SPS_ERR_STATE %ld, "
           "SPS_ERR_INVALID_ARG %ld, other %ld)\n",
           c.cases, FUZZ_SCENES, c.restored, c.refused, c.by_code[(-(int)SPS_ERR_IO) & 7],
           c.by_code[(-(int)SPS_ERR_STATE) & 7], c.by_code[(-(int)SPS_ERR_INVALID_ARG) & 7],
           c.refused - c.by_code[(-(int)SPS_ERR_IO) & 7] - c.by_code[(-(int)SPS_ERR_STATE) & 7] - c.by_code[(-(int)SPS_ERR_INVALID_ARG) & 7]);
    printf("  by mutation (refused/cases):");
    for (i = 0; i < MUTATIONS; ++i) printf(" %s %ld/%ld%s", mutation_names[i], c.by_mutation_refused[i], c.by_mutation[i], i + 1 < MUTATIONS ? "," : "\n");
    printf("  broken: %ld restored worlds invalid, %ld refusals naming no item, %ld refusals that changed the state, %ld resets failed "
           "(crashes and sanitizer reports: none, or this line would not print)\n",
           c.invalid, c.unnamed, c.changed, c.reset_failed);
    for (i = 0; i < FUZZ_SCENES; ++i) { sps_world_destroy(scenes[i].w); free(scenes[i].base.bytes); remove(scenes[i].path); }
    remove(path);
    return failed ? 1 : 0;
}
