/* fuzz_restore_libfuzzer.c - coverage-guided fuzzing of the restart reader (clang's libFuzzer).

   Each input is a restart file. Its payload checksum is recomputed first (when the header's
   length fits the input), so that the fuzzer explores the reader past the checksum, as a
   crafted file would. It is restored into each of the six worlds of tests/fuzz_restore_scenes.h
   (built at dp = 0.02: the seeds in tests/restore_corpus/ are their saves; the fingerprint
   picks the one it matches). A finding is a crash, a sanitizer report, or abort() on:
     - a restored world that sps_world_validate refuses;
     - a refused restore that changed the world's state (its save, hashed, before and after).
   A restored world takes a step for one input in eight (the sanitizers watch it), then is put
   back to its scene's save.

   Build and run: make fuzz-libfuzzer FUZZ_SECONDS=600 (clang -fsanitize=fuzzer,address,undefined). */
#define _POSIX_C_SOURCE 200809L
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"
#include "fuzz_restore_scenes.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static sps_world* g_world[FUZZ_SCENES];
static unsigned char* g_save[FUZZ_SCENES]; /* each world's own save, to put it back */
static size_t g_save_size[FUZZ_SCENES];
static uint64_t g_hash[FUZZ_SCENES];
static FILE* g_null;

/* The world's state as its save's payload holds it, hashed (sps__writer hashes what it writes). */
static uint64_t state_hash(sps_world* w) {
    sps__writer out = {NULL, NULL, 0, SPS__FNV_OFFSET, 0};
    sps__stream writing = {NULL, NULL};
    out.f = g_null;
    writing.out = &out;
    sps__transfer_state(w, &writing);
    return out.hash;
}
static sps_result restore_bytes(sps_world* w, const unsigned char* bytes, size_t size) {
    FILE* f = fmemopen((void*)bytes, size, "rb");
    sps_result r;
    if (!f) abort();
    r = sps__restore(w, f, "input");
    fclose(f);
    return r;
}

int LLVMFuzzerInitialize(int* argc, char*** argv);
int LLVMFuzzerInitialize(int* argc, char*** argv) {
    int k;
    char path[64];
    (void)argc; (void)argv;
    g_null = fopen("/dev/null", "wb");
    for (k = 0; k < FUZZ_SCENES; ++k) {
        FILE* f;
        long size;
        snprintf(path, sizeof path, "/tmp/fuzz_restore_seed_%d_%d", (int)getpid(), k);
        if (!g_null || !(g_world[k] = fuzz_scene_build(k, (sps_real)0.02)) || sps_world_save(g_world[k], path) != SPS_OK) abort();
        if (!(f = fopen(path, "rb")) || fseek(f, 0, SEEK_END) != 0 || (size = ftell(f)) <= 0 || fseek(f, 0, SEEK_SET) != 0) abort();
        g_save_size[k] = (size_t)size;
        if (!(g_save[k] = (unsigned char*)malloc(g_save_size[k])) || fread(g_save[k], 1, g_save_size[k], f) != g_save_size[k]) abort();
        fclose(f);
        remove(path);
        if (restore_bytes(g_world[k], g_save[k], g_save_size[k]) != SPS_OK) abort();
        g_hash[k] = state_hash(g_world[k]);
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const size_t header = 16 + 12 + 8; /* magic, three words, the payload's length */
    unsigned char* bytes;
    uint64_t length, hash;
    int k;
    if (size < header) return 0;
    bytes = (unsigned char*)malloc(size);
    memcpy(bytes, data, size);
    memcpy(&length, bytes + header - 8, sizeof length);
    if (length <= size - header && size - 8 - length >= header) { /* the checksum a crafted file would carry */
        hash = sps__fnv(SPS__FNV_OFFSET, bytes + size - 8 - length, (size_t)length);
        memcpy(bytes + size - 8, &hash, sizeof hash);
    }
    for (k = 0; k < FUZZ_SCENES; ++k) {
        sps_world* w = g_world[k];
        if (restore_bytes(w, bytes, size) == SPS_OK) {
            char msg[1024];
            if (sps_world_validate(w, msg, sizeof msg) != SPS_OK) {
                fprintf(stderr, "restored into scene %s a world that validate refuses: %s\n", fuzz_scene_name(k), msg);
                abort();
            }
            if (sps__fnv(SPS__FNV_OFFSET, data, size) % 8 == 0) sps_world_step(w);
            if (restore_bytes(w, g_save[k], g_save_size[k]) != SPS_OK || state_hash(w) != g_hash[k]) abort();
        } else if (state_hash(w) != g_hash[k]) {
            fprintf(stderr, "refused in scene %s (%s) but the state changed\n", fuzz_scene_name(k), sps_world_last_error(w));
            abort();
        }
    }
    free(bytes);
    return 0;
}
