/* render.h - pictures of a world with no library beyond libc: the particles as discs coloured
   by a field, a colour bar with its minimum and maximum, a length scale bar and the simulated
   time, written as PNG or SVG. The PNG encoder is written here: 8-bit indexed colour (a
   palette keeps a 600 x 400 picture at 240 KB although nothing is compressed), one zlib stream
   of stored deflate blocks, CRC-32 and Adler-32 computed below; the text uses a built-in 5 x 7
   bitmap font. 3D worlds are projected orthographically on a plane (or an isometric view) and
   drawn back to front (painter's order); 2D worlds directly. Used by examples/common.h (the
   --png-* options) and examples/demo.c (the terminal frames). Static functions, include once. */
#ifndef SPS_RENDER_H
#define SPS_RENDER_H
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../sphsolid.h"

/* A program uses part of the renderer. */
#if defined(__GNUC__) || defined(__clang__)
#define RENDER_UNUSED __attribute__((unused))
#else
#define RENDER_UNUSED
#endif

/* ---- fields: what colours the discs; one row per field, chosen by name ---- */
typedef struct {
    const char* name;  /* as --png-field takes it */
    const char* label; /* the colour bar's title */
    double (*value)(const sps_particle_state* s);
} render_field;

RENDER_UNUSED static double render_norm3(const sps_real v[3]) { return sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]); }
RENDER_UNUSED static double render_speed(const sps_particle_state* s) { return render_norm3(s->velocity); }
RENDER_UNUSED static double render_pressure(const sps_particle_state* s) { return s->pressure; }
RENDER_UNUSED static double render_von_mises(const sps_particle_state* s) { return s->von_mises; } /* 0 unless the body tracks stress */
RENDER_UNUSED static double render_displacement(const sps_particle_state* s) { return render_norm3(s->displacement); }
RENDER_UNUSED static double render_body(const sps_particle_state* s) { return s->body_index; }
RENDER_UNUSED static double render_plastic_strain(const sps_particle_state* s) { return s->plastic_strain; } /* 0 unless J2 */
RENDER_UNUSED static double render_damage(const sps_particle_state* s) { return s->damage; } /* 0 unless the body has damage */

/* More fields are more rows here. */
static const render_field render_fields[] = {
    {"velocity", "velocity [m/s]", render_speed},
    {"pressure", "pressure [Pa]", render_pressure},
    {"von-mises", "von Mises [Pa]", render_von_mises},
    {"displacement", "displacement [m]", render_displacement},
    {"body", "body index", render_body},
    {"plastic-strain", "equivalent plastic strain", render_plastic_strain},
    {"damage", "damage D", render_damage},
};
#define RENDER_FIELD_COUNT ((int)(sizeof render_fields / sizeof *render_fields))

/* The field called name, or NULL. */
RENDER_UNUSED static const render_field* render_field_by_name(const char* name) {
    int k;
    for (k = 0; k < RENDER_FIELD_COUNT; ++k)
        if (strcmp(render_fields[k].name, name) == 0) return &render_fields[k];
    return NULL;
}

/* ---- views: how 3D positions map to the picture (u right, v up, depth towards the eye) ---- */
typedef enum { RENDER_VIEW_XY, RENDER_VIEW_XZ, RENDER_VIEW_YZ, RENDER_VIEW_ISO } render_view;
#define RENDER_VIEW_CHOICES "xy|xz|yz|iso" /* in render_view order */

RENDER_UNUSED static void render_project(render_view view, const sps_real p[3], double* u, double* v, double* depth) {
    const double x = p[0], y = p[1], z = p[2];
    switch (view) {
    case RENDER_VIEW_XY: *u = x; *v = y; *depth = z; break;
    case RENDER_VIEW_XZ: *u = x; *v = z; *depth = -y; break; /* seen from -y */
    case RENDER_VIEW_YZ: *u = y; *v = z; *depth = x; break;  /* seen from +x */
    case RENDER_VIEW_ISO: /* seen from (1, -1, 1): x runs right and down, y right and up, z up */
        *u = (x + y) / sqrt(2.0);
        *v = (-x + y + 2 * z) / sqrt(6.0);
        *depth = (x - y + z) / sqrt(3.0);
        break;
    }
}

/* ---- palette: 0 background, 1 ink, 2 frame, then the colour ramp ---- */
enum { RENDER_BACKGROUND, RENDER_INK, RENDER_FRAME, RENDER_RAMP0, RENDER_RAMP_N = 256 - RENDER_RAMP0 };

/* Viridis (perceptually uniform, readable in grey), as a degree-6 polynomial fit in t in [0, 1]. */
RENDER_UNUSED static void render_viridis(double t, unsigned char rgb[3]) {
    static const double c[7][3] = {{0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
                                   {0.1050930431085774, 1.404613529898575, 1.384590162594685},
                                   {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
                                   {-4.634230498983486, -5.799100973351585, -19.33244095627987},
                                   {6.228269936347081, 14.17993336680509, 56.69055260068105},
                                   {4.776384997670288, -13.74514537774601, -65.35303263337234},
                                   {-5.435455855934631, 4.645852612178535, 26.3124352495832}};
    int a, k;
    for (a = 0; a < 3; ++a) {
        double s = c[6][a];
        for (k = 5; k >= 0; --k) s = c[k][a] + t * s; /* Horner */
        rgb[a] = (unsigned char)(255 * (s < 0 ? 0 : s > 1 ? 1 : s) + 0.5);
    }
}

/* The 256 RGB entries of the palette. */
RENDER_UNUSED static const unsigned char* render_palette(void) {
    static unsigned char pal[256 * 3];
    int k;
    if (pal[0] == 0) {
        static const unsigned char fixed[RENDER_RAMP0 * 3] = {255, 255, 255, 20, 20, 20, 150, 150, 150};
        memcpy(pal, fixed, sizeof fixed);
        for (k = 0; k < RENDER_RAMP_N; ++k) render_viridis((double)k / (RENDER_RAMP_N - 1), pal + 3 * (RENDER_RAMP0 + k));
    }
    return pal;
}

/* ---- 5 x 7 bitmap font: the characters of numbers, units and labels ---- */
static const char render_font_chars[] = "0123456789.-+=[]/|: abcdefghijklmnopqrstuvwxyzMP";
static const unsigned char render_font_rows[][7] = { /* 5 bits a row, top row first, bit 4 = left */
    {14, 17, 19, 21, 25, 17, 14}, {4, 12, 4, 4, 4, 4, 14},    {14, 17, 1, 2, 4, 8, 31},    {31, 2, 4, 2, 1, 17, 14},
    {2, 6, 10, 18, 31, 2, 2},     {31, 16, 30, 1, 1, 17, 14}, {6, 8, 16, 30, 17, 17, 14},  {31, 1, 2, 4, 8, 8, 8},
    {14, 17, 17, 14, 17, 17, 14}, {14, 17, 17, 15, 1, 2, 12}, {0, 0, 0, 0, 0, 12, 12},     {0, 0, 0, 31, 0, 0, 0},
    {0, 4, 4, 31, 4, 4, 0},       {0, 0, 31, 0, 31, 0, 0},    {14, 8, 8, 8, 8, 8, 14},     {14, 2, 2, 2, 2, 2, 14},
    {0, 1, 2, 4, 8, 16, 0},       {4, 4, 4, 4, 4, 4, 4},      {0, 12, 12, 0, 12, 12, 0},   {0, 0, 0, 0, 0, 0, 0},
    {0, 0, 14, 1, 15, 17, 15},    {16, 16, 22, 25, 17, 17, 30}, {0, 0, 14, 16, 16, 17, 14}, {1, 1, 13, 19, 17, 17, 15},
    {0, 0, 14, 17, 31, 16, 14},   {6, 9, 8, 28, 8, 8, 8},     {0, 15, 17, 17, 15, 1, 14},  {16, 16, 22, 25, 17, 17, 17},
    {4, 0, 12, 4, 4, 4, 14},      {2, 0, 6, 2, 2, 18, 12},    {16, 16, 18, 20, 24, 20, 18}, {12, 4, 4, 4, 4, 4, 14},
    {0, 0, 26, 21, 21, 17, 17},   {0, 0, 22, 25, 17, 17, 17}, {0, 0, 14, 17, 17, 17, 14},  {0, 0, 30, 17, 30, 16, 16},
    {0, 0, 13, 19, 15, 1, 1},     {0, 0, 22, 25, 16, 16, 16}, {0, 0, 14, 16, 14, 1, 30},   {8, 8, 28, 8, 8, 9, 6},
    {0, 0, 17, 17, 17, 19, 13},   {0, 0, 17, 17, 17, 10, 4},  {0, 0, 17, 17, 21, 21, 10},  {0, 0, 17, 10, 4, 10, 17},
    {0, 0, 17, 17, 15, 1, 14},    {0, 0, 31, 2, 4, 8, 31},    {17, 27, 21, 21, 17, 17, 17}, {30, 17, 17, 30, 16, 16, 16},
};

/* The glyph of c; a capital without its own glyph takes the small letter's, anything else a blank. */
RENDER_UNUSED static const unsigned char* render_glyph(char c) {
    const char* at = c ? strchr(render_font_chars, c) : NULL;
    if (!at && c >= 'A' && c <= 'Z') at = strchr(render_font_chars, c - 'A' + 'a');
    return render_font_rows[at ? at - render_font_chars : strchr(render_font_chars, ' ') - render_font_chars];
}

/* ---- an indexed image ---- */
typedef struct {
    int width, height;
    unsigned char* pixels; /* palette indices, row by row from the top */
} render_image;

RENDER_UNUSED static void render_fill_rect(render_image* img, int x0, int y0, int x1, int y1, unsigned char colour) {
    int x, y;
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > img->width) x1 = img->width;
    if (y1 > img->height) y1 = img->height;
    for (y = y0; y < y1; ++y)
        for (x = x0; x < x1; ++x) img->pixels[(size_t)y * img->width + x] = colour;
}

RENDER_UNUSED /* A disc of radius r at (cx, cy), clipped to the rectangle clip (x0, y0, x1, y1). */
static void render_disc_pixels(render_image* img, const int clip[4], double cx, double cy, double r, unsigned char colour) {
    int x, y, x0 = (int)floor(cx - r), x1 = (int)ceil(cx + r), y0 = (int)floor(cy - r), y1 = (int)ceil(cy + r);
    if (r < 0.75) { /* smaller than a pixel: one pixel, so that no particle vanishes */
        x = (int)floor(cx);
        y = (int)floor(cy);
        if (x >= clip[0] && x < clip[2] && y >= clip[1] && y < clip[3]) img->pixels[(size_t)y * img->width + x] = colour;
        return;
    }
    for (y = y0 < clip[1] ? clip[1] : y0; y <= y1 && y < clip[3]; ++y)
        for (x = x0 < clip[0] ? clip[0] : x0; x <= x1 && x < clip[2]; ++x)
            if ((x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy) <= r * r) img->pixels[(size_t)y * img->width + x] = colour;
}

/* Text with its top-left corner at (x, y), each font pixel scale x scale image pixels. */
RENDER_UNUSED static void render_text(render_image* img, int x, int y, int scale, const char* s, unsigned char colour) {
    int row, col;
    for (; *s; ++s, x += 6 * scale) {
        const unsigned char* g = render_glyph(*s);
        for (row = 0; row < 7; ++row)
            for (col = 0; col < 5; ++col)
                if (g[row] >> (4 - col) & 1) render_fill_rect(img, x + col * scale, y + row * scale, x + (col + 1) * scale, y + (row + 1) * scale, colour);
    }
}

/* ---- layout: the particles projected into the picture, and where the decorations go ---- */
typedef struct {
    int width, height;         /* [px] */
    render_view view;
    const render_field* field;
    int decorations;           /* 1: colour bar, scale bar, time and field name; 0: particles only */
    double window[4];          /* u_lo, v_lo, u_hi, v_hi [m] to show; all 0: fit the particles */
    double range[2];           /* field values at the ends of the colour bar; equal: the data's */
} render_options;

typedef struct { double x, y, depth, value; } render_disc; /* [px] from the top-left corner */

typedef struct {
    render_options o;
    render_disc* discs;        /* back to front */
    int n;
    double lo, hi;             /* the colour bar's range */
    double radius;             /* of a disc [px] */
    double px_per_m;
    double time;               /* [s] */
    int plot[4];               /* x0, y0, x1, y1 of the particles' area [px] */
    int font;                  /* font scale */
    int bar[4];                /* the colour bar */
    double scale_m;            /* the length scale bar [m]: 1, 2 or 5 x 10^k */
} render_layout;

RENDER_UNUSED static int render_by_depth(const void* a, const void* b) {
    double da = ((const render_disc*)a)->depth, db = ((const render_disc*)b)->depth;
    return (da > db) - (da < db);
}

/* Margins: a title line on top, the scale bar below, the colour bar and its labels on the right. */
RENDER_UNUSED static void render_place(render_layout* L) {
    const int w = L->o.width, h = L->o.height, s = L->font = h >= 300 ? 2 : 1;
    if (!L->o.decorations) {
        L->plot[0] = L->plot[1] = 0; L->plot[2] = w; L->plot[3] = h;
        return;
    }
    L->plot[0] = 8; L->plot[1] = 7 * s + 14; L->plot[2] = w - (10 * s + 12 + 9 * 6 * s + 8); L->plot[3] = h - (7 * s + 20);
    L->bar[0] = L->plot[2] + 12; L->bar[1] = L->plot[1] + 7 * s; L->bar[2] = L->bar[0] + 10 * s; L->bar[3] = L->plot[3] - 7 * s;
}

/* Projects every particle of w into L->discs (world units still) and its value; box gets the
   bounds of the current and the reference positions, so that a view fits both. */
RENDER_UNUSED static void render_collect(const sps_world* w, render_layout* L, double box[4]) {
    int id, k;
    box[0] = box[1] = 1e300; box[2] = box[3] = -1e300;
    L->lo = 1e300; L->hi = -1e300;
    for (id = 0; id < L->n; ++id) {
        sps_particle_state s;
        sps_real ref[3];
        double u, v, depth;
        render_disc* d = &L->discs[id];
        sps_world_particle(w, id, &s);
        for (k = 0; k < 3; ++k) ref[k] = s.position[k] - s.displacement[k];
        render_project(L->o.view, ref, &u, &v, &depth);
        box[0] = fmin(box[0], u); box[1] = fmin(box[1], v); box[2] = fmax(box[2], u); box[3] = fmax(box[3], v);
        render_project(L->o.view, s.position, &d->x, &d->y, &d->depth);
        box[0] = fmin(box[0], d->x); box[1] = fmin(box[1], d->y); box[2] = fmax(box[2], d->x); box[3] = fmax(box[3], d->y);
        d->value = L->o.field->value(&s);
        L->lo = fmin(L->lo, d->value); L->hi = fmax(L->hi, d->value);
    }
    if (L->n == 0) { box[0] = box[1] = 0; box[2] = box[3] = 1; L->lo = L->hi = 0; }
}

/* Scales the view box (u_lo, v_lo, u_hi, v_hi) [m] into the plot area, centred, and moves the
   discs from world units to pixels (image y runs down). */
RENDER_UNUSED static void render_fit(render_layout* L, const double box[4], double dp) {
    int id;
    L->px_per_m = fmin((L->plot[2] - L->plot[0]) / (box[2] - box[0]), (L->plot[3] - L->plot[1]) / (box[3] - box[1]));
    L->radius = 0.75 * dp * L->px_per_m; /* over dp/sqrt(2): a square lattice's discs leave no holes, a body looks solid */
    for (id = 0; id < L->n; ++id) {
        render_disc* d = &L->discs[id];
        d->x = 0.5 * (L->plot[0] + L->plot[2]) + (d->x - 0.5 * (box[0] + box[2])) * L->px_per_m;
        d->y = 0.5 * (L->plot[1] + L->plot[3]) - (d->y - 0.5 * (box[1] + box[3])) * L->px_per_m;
    }
    { /* the scale bar: a round length near a quarter of the plot's width */
        double target = 0.25 * (L->plot[2] - L->plot[0]) / L->px_per_m, decade = pow(10, floor(log10(target)));
        L->scale_m = target >= 5 * decade ? 5 * decade : target >= 2 * decade ? 2 * decade : decade;
    }
}

/* Lays out the world's particles for options o (frees with render_layout_free). Returns 0, or
   -1 when out of memory. */
RENDER_UNUSED static int render_layout_make(const sps_world* w, const render_options* o, render_layout* L) {
    const double dp = sps_world_get_def(w)->dp;
    const int fit = o->window[0] == o->window[2];
    double box[4];
    memset(L, 0, sizeof *L);
    L->o = *o;
    L->time = sps_world_time(w);
    L->n = sps_world_particle_count(w);
    if (!(L->discs = (render_disc*)malloc(sizeof(render_disc) * (size_t)(L->n > 0 ? L->n : 1)))) return -1;
    render_collect(w, L, box);
    if (o->range[0] != o->range[1]) { L->lo = o->range[0]; L->hi = o->range[1]; }
    if (fit) { /* the particles' bounds, with room for a disc and a margin */
        const double pad = 0.5 * dp + 0.03 * fmax(box[2] - box[0], box[3] - box[1]);
        box[0] -= pad; box[1] -= pad; box[2] += pad; box[3] += pad;
    } else {
        memcpy(box, o->window, sizeof box);
    }
    render_place(L);
    render_fit(L, box, dp);
    qsort(L->discs, (size_t)L->n, sizeof *L->discs, render_by_depth); /* painter's order: far first */
    return 0;
}

RENDER_UNUSED static void render_layout_free(render_layout* L) { free(L->discs); L->discs = NULL; }

/* Palette index of a field value: the ramp from lo to hi (its middle when the range is empty). */
RENDER_UNUSED static unsigned char render_colour(const render_layout* L, double value) {
    double t = L->hi > L->lo ? (value - L->lo) / (L->hi - L->lo) : 0.5;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return (unsigned char)(RENDER_RAMP0 + (int)(t * (RENDER_RAMP_N - 1) + 0.5));
}

/* The texts of the decorations, shared by the PNG and the SVG. */
typedef struct { char title[64], hi[24], lo[24], scale[24]; } render_labels;
RENDER_UNUSED static void render_label(const render_layout* L, render_labels* t) {
    snprintf(t->title, sizeof t->title, "%s   t = %.4g s", L->o.field->label, L->time);
    snprintf(t->hi, sizeof t->hi, "%.3g", L->hi);
    snprintf(t->lo, sizeof t->lo, "%.3g", L->lo);
    snprintf(t->scale, sizeof t->scale, "%g m", L->scale_m);
}

/* Draws L into img (width x height of L's options; pixels allocated by the caller). */
RENDER_UNUSED static void render_raster(const render_layout* L, render_image* img) {
    const int s = L->font;
    int k, y;
    memset(img->pixels, RENDER_BACKGROUND, (size_t)img->width * img->height);
    for (k = 0; k < L->n; ++k) render_disc_pixels(img, L->plot, L->discs[k].x, L->discs[k].y, L->radius, render_colour(L, L->discs[k].value));
    if (L->o.decorations) {
        render_labels t;
        const int bar_len = (int)(L->scale_m * L->px_per_m + 0.5), sy = L->plot[3] + 8;
        render_label(L, &t);
        render_text(img, L->plot[0], 6, s, t.title, RENDER_INK);
        for (y = L->bar[1]; y < L->bar[3]; ++y) /* the colour bar: hi at the top */
            render_fill_rect(img, L->bar[0], y, L->bar[2], y + 1,
                             render_colour(L, L->hi - (L->hi - L->lo) * (y - L->bar[1]) / (double)(L->bar[3] - L->bar[1] - 1)));
        render_text(img, L->bar[2] + 6, L->bar[1], s, t.hi, RENDER_INK);
        render_text(img, L->bar[2] + 6, L->bar[3] - 7 * s, s, t.lo, RENDER_INK);
        render_fill_rect(img, L->plot[0], sy + 3 * s, L->plot[0] + bar_len, sy + 4 * s + 1, RENDER_INK); /* scale bar with end ticks */
        render_fill_rect(img, L->plot[0], sy, L->plot[0] + s, sy + 7 * s, RENDER_INK);
        render_fill_rect(img, L->plot[0] + bar_len - s, sy, L->plot[0] + bar_len, sy + 7 * s, RENDER_INK);
        render_text(img, L->plot[0] + bar_len + 8, sy, s, t.scale, RENDER_INK);
    }
}

/* ---- PNG: signature, IHDR, PLTE, one IDAT (zlib, stored deflate blocks), IEND ---- */
RENDER_UNUSED static uint32_t render_crc32(uint32_t crc, const unsigned char* p, size_t n) {
    static uint32_t table[256];
    size_t i;
    if (!table[1]) { /* the reflected polynomial 0xedb88320 (PNG spec, annex D) */
        uint32_t c, k, b;
        for (k = 0; k < 256; ++k) {
            for (c = k, b = 0; b < 8; ++b) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
            table[k] = c;
        }
    }
    crc = ~crc;
    for (i = 0; i < n; ++i) crc = table[(crc ^ p[i]) & 255] ^ (crc >> 8);
    return ~crc;
}

RENDER_UNUSED static void render_put32(unsigned char* p, uint32_t v) { p[0] = (unsigned char)(v >> 24); p[1] = (unsigned char)(v >> 16); p[2] = (unsigned char)(v >> 8); p[3] = (unsigned char)v; }

/* One chunk: length, type, data, CRC of type and data. */
RENDER_UNUSED static void render_png_chunk(FILE* f, const char* type, const unsigned char* data, size_t len) {
    unsigned char head[8], tail[4];
    render_put32(head, (uint32_t)len);
    memcpy(head + 4, type, 4);
    render_put32(tail, len ? render_crc32(render_crc32(0, head + 4, 4), data, len) : render_crc32(0, head + 4, 4));
    fwrite(head, 1, 8, f);
    if (len) fwrite(data, 1, len, f); /* IEND has no data (and a NULL pointer) */
    fwrite(tail, 1, 4, f);
}

/* Writes img with the palette as an 8-bit indexed PNG. Returns 0, or -1 (cannot write, out of memory). */
RENDER_UNUSED static int render_write_png(const render_image* img, const char* path) {
    static const unsigned char signature[8] = {137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
    const size_t row = (size_t)img->width + 1, raw = row * img->height, blocks = (raw + 65534) / 65535;
    const size_t zlen = 2 + raw + 5 * blocks + 4;
    unsigned char ihdr[13] = {0}, *z, *out;
    uint32_t s1 = 1, s2 = 0; /* Adler-32 of the raw scanlines */
    size_t i, done;
    FILE* f;
    int ok;
    if (!(z = (unsigned char*)malloc(zlen))) return -1;
    z[0] = 0x78; z[1] = 0x01; /* deflate, 32K window, no dictionary; (z0 * 256 + z1) % 31 == 0 */
    out = z + 2;
    for (done = 0; done < raw;) { /* stored blocks of at most 65535 bytes of the scanlines (filter byte 0, then the indices) */
        size_t len = raw - done < 65535 ? raw - done : 65535;
        out[0] = (unsigned char)(done + len == raw); /* BFINAL on the last block, BTYPE 00 */
        out[1] = (unsigned char)(len & 255); out[2] = (unsigned char)(len >> 8);
        out[3] = (unsigned char)(~len & 255); out[4] = (unsigned char)((~len >> 8) & 255);
        out += 5;
        for (i = 0; i < len; ++i, ++done) { /* byte `done` of the stream: a filter byte or a pixel */
            size_t x = done % row;
            out[i] = x == 0 ? 0 : img->pixels[(done / row) * img->width + x - 1];
            s1 = (s1 + out[i]) % 65521;
            s2 = (s2 + s1) % 65521;
        }
        out += len;
    }
    render_put32(out, s2 << 16 | s1);
    render_put32(ihdr, (uint32_t)img->width);
    render_put32(ihdr + 4, (uint32_t)img->height);
    ihdr[8] = 8; ihdr[9] = 3; /* bit depth 8, colour type 3 (palette); compression, filter, interlace 0 */
    if (!(f = fopen(path, "wb"))) { free(z); return -1; }
    fwrite(signature, 1, 8, f);
    render_png_chunk(f, "IHDR", ihdr, 13);
    render_png_chunk(f, "PLTE", render_palette(), 256 * 3);
    render_png_chunk(f, "IDAT", z, zlen);
    render_png_chunk(f, "IEND", NULL, 0);
    ok = ferror(f) == 0;
    ok = fclose(f) == 0 && ok;
    free(z);
    return ok ? 0 : -1;
}

/* ---- SVG: the same layout as circles, rectangles and text ---- */
RENDER_UNUSED static void render_svg_colour(const render_layout* L, double value, char out[8]) {
    const unsigned char* c = render_palette() + 3 * render_colour(L, value);
    snprintf(out, 8, "#%02x%02x%02x", c[0], c[1], c[2]);
}

/* Writes L as an SVG file. Returns 0, or -1 if it cannot write. */
RENDER_UNUSED static int render_write_svg(const render_layout* L, const char* path) {
    const int s = L->font, steps = 64;
    FILE* f = fopen(path, "w");
    char colour[8];
    int k, ok;
    if (!f) return -1;
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
               "viewBox=\"0 0 %d %d\" font-family=\"monospace\" font-size=\"%d\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"#ffffff\"/>\n",
            L->o.width, L->o.height, L->o.width, L->o.height, 9 * s);
    fprintf(f, "<clipPath id=\"plot\"><rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\"/></clipPath>\n<g clip-path=\"url(#plot)\">\n",
            L->plot[0], L->plot[1], L->plot[2] - L->plot[0], L->plot[3] - L->plot[1]); /* the PNG's clipping */
    for (k = 0; k < L->n; ++k) {
        render_svg_colour(L, L->discs[k].value, colour);
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\"/>\n", L->discs[k].x, L->discs[k].y, fmax(L->radius, 0.5), colour);
    }
    fprintf(f, "</g>\n");
    if (L->o.decorations) {
        render_labels t;
        const double h = (L->bar[3] - L->bar[1]) / (double)steps, sy = L->plot[3] + 8, bar_len = L->scale_m * L->px_per_m;
        render_label(L, &t);
        fprintf(f, "<text x=\"%d\" y=\"%d\">%s</text>\n", L->plot[0], 6 + 7 * s, t.title);
        for (k = 0; k < steps; ++k) {
            render_svg_colour(L, L->hi - (L->hi - L->lo) * (k + 0.5) / steps, colour);
            fprintf(f, "<rect x=\"%d\" y=\"%.2f\" width=\"%d\" height=\"%.2f\" fill=\"%s\"/>\n", L->bar[0], L->bar[1] + k * h,
                    L->bar[2] - L->bar[0], h + 0.5, colour);
        }
        fprintf(f, "<text x=\"%d\" y=\"%d\">%s</text>\n<text x=\"%d\" y=\"%d\">%s</text>\n", L->bar[2] + 6, L->bar[1] + 7 * s, t.hi,
                L->bar[2] + 6, L->bar[3], t.lo);
        fprintf(f, "<path d=\"M%d %.1f v%d M%d %.1f h%.1f M%.1f %.1f v%d\" stroke=\"#141414\" stroke-width=\"%d\" fill=\"none\"/>\n",
                L->plot[0], sy, 7 * s, L->plot[0], sy + 3.5 * s, bar_len, L->plot[0] + bar_len, sy, 7 * s, s);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\">%s</text>\n", L->plot[0] + bar_len + 8, sy + 7 * s, t.scale);
    }
    fprintf(f, "</svg>\n");
    ok = ferror(f) == 0;
    ok = fclose(f) == 0 && ok;
    return ok ? 0 : -1;
}

/* ---- one call per picture ---- */
typedef enum { RENDER_PNG, RENDER_SVG } render_format;

/* Draws world w with options o into a file of the given format. Returns 0, or -1 (cannot
   write, out of memory). */
RENDER_UNUSED static int render_world(const sps_world* w, const render_options* o, render_format format, const char* path) {
    render_layout L;
    int r = -1;
    if (render_layout_make(w, o, &L) != 0) return -1;
    if (format == RENDER_SVG) {
        r = render_write_svg(&L, path);
    } else {
        render_image img;
        img.width = o->width;
        img.height = o->height;
        if ((img.pixels = (unsigned char*)malloc((size_t)o->width * o->height))) {
            render_raster(&L, &img);
            r = render_write_png(&img, path);
            free(img.pixels);
        }
    }
    render_layout_free(&L);
    return r;
}

#endif
