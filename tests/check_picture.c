/* check_picture.c - reads back the pictures of examples/render.h: a body must be visible.

   PNG: the signature, every chunk's CRC-32, IHDR (size, 8-bit indexed colour), PLTE, the IDAT
   data as one zlib stream of stored deflate blocks (LEN = ~NLEN) with its Adler-32, one filter
   byte 0 per scanline; then it counts the particles' pixels: colour-ramp indices (>= 3; 0 is the
   background, 1 and 2 text and lines) left of the colour bar's panel, the rightmost 140 pixels
   (76 below 300 pixels of height: render_place in examples/render.h).
   SVG: an <svg> root that is closed, and the <circle> elements (one per particle).
   The checksums are computed here bit by bit, not with render.h's table, so that a shared
   mistake cannot pass.

   Usage: check_picture [--min N] FILE.png|FILE.svg ...   (N: particle pixels or circles
   a picture must have, default 300). Prints one line per file; exit status 1 on the first bad one. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int g_failed;
static void fail(const char* path, const char* why) {
    printf("check_picture: %s: %s\n", path, why);
    g_failed = 1;
}

static uint32_t get32(const unsigned char* p) { return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]; }

static uint32_t crc32_bitwise(const unsigned char* p, size_t n) {
    uint32_t c = 0xffffffffu;
    size_t i;
    int b;
    for (i = 0; i < n; ++i)
        for (c ^= p[i], b = 0; b < 8; ++b) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1)));
    return ~c;
}

static unsigned char* read_all(const char* path, size_t* size) {
    FILE* f = fopen(path, "rb");
    unsigned char* data = NULL;
    long n;
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) > 0 && fseek(f, 0, SEEK_SET) == 0 && (data = (unsigned char*)malloc((size_t)n + 1)))
        *size = fread(data, 1, (size_t)n, f);
    fclose(f);
    if (data) data[*size] = 0;
    return data;
}

/* Concatenates the IDAT chunks after checking every chunk; fills width and height. Returns the
   zlib stream (caller frees) or NULL after reporting. */
static unsigned char* png_chunks(const char* path, const unsigned char* d, size_t n, uint32_t* width, uint32_t* height, size_t* zlen) {
    static const unsigned char signature[8] = {137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
    unsigned char* z = (unsigned char*)malloc(n);
    size_t at = 8;
    int seen_ihdr = 0, seen_plte = 0, seen_iend = 0;
    *zlen = 0;
    if (!z) return NULL;
    if (n < 8 || memcmp(d, signature, 8) != 0) { fail(path, "no PNG signature"); free(z); return NULL; }
    while (at + 12 <= n && !seen_iend) {
        uint32_t len = get32(d + at);
        const unsigned char* type = d + at + 4;
        if (len > n - at - 12) { fail(path, "chunk runs past the end of the file"); free(z); return NULL; }
        if (crc32_bitwise(type, len + 4) != get32(d + at + 8 + len)) { fail(path, "bad chunk CRC"); free(z); return NULL; }
        if (memcmp(type, "IHDR", 4) == 0) {
            if (len != 13 || type[12] != 8 || type[13] != 3) { fail(path, "IHDR is not 8-bit indexed colour"); free(z); return NULL; }
            *width = get32(type + 4);
            *height = get32(type + 8);
            seen_ihdr = 1;
        } else if (memcmp(type, "PLTE", 4) == 0) {
            seen_plte = len % 3 == 0 && len > 0;
        } else if (memcmp(type, "IDAT", 4) == 0) {
            memcpy(z + *zlen, type + 4, len);
            *zlen += len;
        } else if (memcmp(type, "IEND", 4) == 0) {
            seen_iend = 1;
        }
        at += 12 + len;
    }
    if (!seen_ihdr || !seen_plte || !seen_iend || *zlen == 0) { fail(path, "IHDR, PLTE, IDAT or IEND missing"); free(z); return NULL; }
    return z;
}

/* Unpacks the stored blocks of zlib stream z into raw (size expected); returns 0 or reports. */
static int inflate_stored(const char* path, const unsigned char* z, size_t zlen, unsigned char* raw, size_t expected) {
    size_t at = 2, out = 0, i;
    uint32_t s1 = 1, s2 = 0;
    int final = 0;
    if (zlen < 6 || (z[0] & 15) != 8 || (z[0] * 256 + z[1]) % 31 != 0) { fail(path, "bad zlib header"); return -1; }
    while (!final) {
        size_t len;
        if (at + 5 > zlen) { fail(path, "zlib stream ends inside a block header"); return -1; }
        final = z[at] & 1;
        if ((z[at] >> 1 & 3) != 0) { fail(path, "a deflate block is not stored (BTYPE 00)"); return -1; }
        len = (size_t)z[at + 1] | (size_t)z[at + 2] << 8;
        if ((len ^ ((size_t)z[at + 3] | (size_t)z[at + 4] << 8)) != 0xffff) { fail(path, "stored block: LEN != ~NLEN"); return -1; }
        at += 5;
        if (at + len > zlen || out + len > expected) { fail(path, "stored block longer than the data"); return -1; }
        memcpy(raw + out, z + at, len);
        at += len;
        out += len;
    }
    if (out != expected || at + 4 != zlen) { fail(path, "image data size does not match IHDR"); return -1; }
    for (i = 0; i < out; ++i) {
        s1 = (s1 + raw[i]) % 65521;
        s2 = (s2 + s1) % 65521;
    }
    if ((s2 << 16 | s1) != get32(z + at)) { fail(path, "bad Adler-32"); return -1; }
    return 0;
}

static void check_png(const char* path, const unsigned char* d, size_t n, long min) {
    uint32_t w = 0, h = 0, x, y;
    size_t zlen;
    unsigned char *z = png_chunks(path, d, n, &w, &h, &zlen), *raw;
    long visible = 0;
    char line[160];
    uint32_t panel = h >= 300 ? 140 : 76;
    if (!z) return;
    if (w <= panel || h == 0 || w > 16384 || h > 16384 || !(raw = (unsigned char*)malloc((size_t)(w + 1) * h))) {
        fail(path, "implausible size");
        free(z);
        return;
    }
    if (inflate_stored(path, z, zlen, raw, (size_t)(w + 1) * h) == 0) {
        for (y = 0; y < h; ++y) {
            if (raw[(size_t)y * (w + 1)] != 0) { fail(path, "a scanline filter is not 0"); break; }
            for (x = 1; x <= w - panel; ++x) visible += raw[(size_t)y * (w + 1) + x] >= 3;
        }
        snprintf(line, sizeof line, "%ux%u, %ld particle pixels", w, h, visible);
        if (visible < min) fail(path, line);
        else if (!g_failed) printf("check_picture: %s: %s: ok\n", path, line);
    }
    free(raw);
    free(z);
}

static void check_svg(const char* path, const char* text, long min) {
    const char* at = text;
    long circles = 0;
    char line[96];
    if (!strstr(text, "<svg ") || !strstr(text, "</svg>")) { fail(path, "no <svg> root, or it is not closed"); return; }
    while ((at = strstr(at, "<circle ")) != NULL) ++circles, ++at;
    snprintf(line, sizeof line, "%ld circles", circles);
    if (circles < min) fail(path, line);
    else printf("check_picture: %s: %s: ok\n", path, line);
}

int main(int argc, char** argv) {
    long min = 300;
    int i;
    for (i = 1; i < argc && !g_failed; ++i) {
        size_t n = 0, len = strlen(argv[i]);
        unsigned char* data;
        if (strcmp(argv[i], "--min") == 0 && i + 1 < argc) { min = atol(argv[++i]); continue; }
        if (!(data = read_all(argv[i], &n))) { fail(argv[i], "cannot read"); break; }
        if (len > 4 && strcmp(argv[i] + len - 4, ".svg") == 0) check_svg(argv[i], (const char*)data, min);
        else check_png(argv[i], data, n, min);
        free(data);
    }
    return g_failed;
}
