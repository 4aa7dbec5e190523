/* demo_web.c - the demo (scenes/demo_play.h: jelly blocks, crates, the water tank) as a
   WebAssembly module for the browser page demo.html and its script demo.js. The module keeps
   the play and an RGBA picture of it; the script calls web_frame once per animation frame,
   copies web_pixels() into the canvas and passes keys and the pointer on. Built by `make web`
   with clang's wasm32 target and Debian's wasi-libc (no OpenMP: one thread), SIMD128 on, the
   kinds the scene has no body of compiled out (SPHSOLID_NO_*; see the Makefile). */
/* the frame budget's clock is the page's (performance.now), imported: WASI's clocks are not in a page */
__attribute__((import_module("env"), import_name("now_seconds"))) double web_now_seconds(void);
#define SPHSOLID_WALL_SECONDS() web_now_seconds()
#define SPHSOLID_IMPLEMENTATION
#include "../scenes/demo_play.h"
#include "../render.h"

#define WEB_EXPORT(name) __attribute__((export_name(#name)))
#define WEB_WIDTH DEMO_CANVAS_W
#define WEB_HEIGHT DEMO_CANVAS_H
#define WEB_FPS 30

static demo_play g_play;
static render_options g_view;
static unsigned char g_indexed[WEB_WIDTH * WEB_HEIGHT], g_rgba[WEB_WIDTH * WEB_HEIGHT * 4];
static char g_status[256], g_message[512];

/* The library's messages: the last one is shown under the canvas (and goes to the console). */
static void web_log(int level, const char* message, void* user) {
    (void)user;
    snprintf(g_message, sizeof g_message, "%s", message);
    fprintf(stderr, "%s: %s\n", level == 0 ? "error" : "warning", message);
}

/* Starts the playground (tank 0) or the water tank (1); scripted 1 replays the headless run of
   examples/demo.c (demo_play_scripted_key), deterministic. Returns an sps_result. */
WEB_EXPORT(web_start) int web_start(int tank, int scripted) {
    g_view.width = WEB_WIDTH;
    g_view.height = WEB_HEIGHT;
    g_view.field = render_field_by_name("velocity");
    g_view.window[0] = -JELLY_VIEW_W / 2; g_view.window[1] = 0; g_view.window[2] = JELLY_VIEW_W / 2; g_view.window[3] = JELLY_VIEW_H;
    g_view.range[0] = 0; g_view.range[1] = 3; /* [m/s]: fixed, as in the terminal */
    return demo_play_start(&g_play, 1, web_log, tank, scripted);
}

/* A pointer event at pixel (x, y) of the canvas: 0 press (grabs a dropped block under it),
   1 move (the grab's target follows), 2 release. */
WEB_EXPORT(web_pointer) int web_pointer(int kind, double x, double y) {
    const double px_per_m = WEB_WIDTH / JELLY_VIEW_W;
    const sps_real point[3] = {(sps_real)(x / px_per_m - JELLY_VIEW_W / 2), (sps_real)(JELLY_VIEW_H - y / px_per_m), 0};
    if (kind == 0) return demo_play_grab_at(&g_play, point);
    if (kind == 1 && g_play.dragging) memcpy(g_play.drag.target, point, sizeof point);
    return kind == 2 ? demo_play_let_go(&g_play) : SPS_OK;
}

/* Frame `frame`: the key (-1 none; scripted runs press their own), then 1/30 s of simulated
   time within wall_budget_s (0: none), then the picture. Returns an sps_result. */
WEB_EXPORT(web_frame) int web_frame(int frame, int key, double wall_budget_s) {
    render_layout L;
    render_image img;
    const unsigned char* palette = render_palette();
    static const unsigned char dark[3] = {16, 18, 28};
    sps_result r;
    int k;
    if (g_play.headless) key = demo_play_scripted_key(frame, g_play.scene.tank);
    if ((r = demo_play_key(&g_play, key)) != SPS_OK || (r = demo_play_frame(&g_play, WEB_FPS, wall_budget_s)) != SPS_OK) return r;
    if (*g_play.note) {
        snprintf(g_message, sizeof g_message, "%s", g_play.note);
        *g_play.note = 0;
    }
    img.width = WEB_WIDTH; img.height = WEB_HEIGHT; img.pixels = g_indexed;
    if (render_layout_make(g_play.scene.w, &g_view, &L) != 0) return SPS_ERR_OUT_OF_MEMORY;
    render_raster(&L, &img);
    render_layout_free(&L);
    for (k = 0; k < WEB_WIDTH * WEB_HEIGHT; ++k) { /* the picture's white background turns dark, as in the terminal */
        const unsigned char* c = g_indexed[k] == RENDER_BACKGROUND ? dark : palette + 3 * g_indexed[k];
        g_rgba[4 * k] = c[0]; g_rgba[4 * k + 1] = c[1]; g_rgba[4 * k + 2] = c[2]; g_rgba[4 * k + 3] = 255;
    }
    snprintf(g_status, sizeof g_status, "t = %.2f s, %d particles, %d blocks, new blocks: %s", (double)sps_world_time(g_play.scene.w),
             sps_world_particle_count(g_play.scene.w), g_play.scene.n_drops, demo_formulation_names[g_play.shear]);
    return SPS_OK;
}

WEB_EXPORT(web_pixels) unsigned char* web_pixels(void) { return g_rgba; }
WEB_EXPORT(web_width) int web_width(void) { return WEB_WIDTH; }
WEB_EXPORT(web_height) int web_height(void) { return WEB_HEIGHT; }
WEB_EXPORT(web_status) const char* web_status(void) { return g_status; }
WEB_EXPORT(web_formulation) const char* web_formulation(void) { return demo_formulation_names[g_play.shear]; }
/* The last message of the library or the play ("" when none). */
WEB_EXPORT(web_message) const char* web_message(void) { return g_message; }
WEB_EXPORT(web_error) const char* web_error(void) { return sps_world_last_error(g_play.scene.w); }
/* demo_play_checksum of the current state, as examples/demo.c --headless prints it. */
WEB_EXPORT(web_checksum) uint64_t web_checksum(void) { return demo_play_checksum(g_play.scene.w); }
