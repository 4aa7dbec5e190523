/* demo_play.h - the demo's play, shared by the terminal (examples/demo.c) and the browser
   (examples/web/demo_web.c): the scene (jelly.h) and what a player does to it, by key or by
   pointer; the scripted run that --headless and the browser test replay; the checksum of the
   state a run ends in. The front ends add only their screens and clocks. Needs only sphsolid.h. */
#ifndef SPS_SCENE_DEMO_PLAY_H
#define SPS_SCENE_DEMO_PLAY_H
#include <stdio.h>
#include "jelly.h"

static const sps_shear demo_formulations[] = {SPS_SHEAR_ENO_A, SPS_SHEAR_GNO_A, SPS_SHEAR_ENO, SPS_SHEAR_GNO, SPS_SHEAR_OG};
static const char* const demo_formulation_names[] = {"eno-a", "gno-a", "eno", "gno", "og"}; /* shown on screen */
#define DEMO_FORMULATIONS ((int)(sizeof demo_formulations / sizeof *demo_formulations))

/* The drag: a block (0.24 m square, 57.6 kg/m) hangs 0.03 m below its target under gravity at
   this stiffness, and the damping is about a fifth of critical (2 sqrt(k m) = 2100 N s/m). */
#define DEMO_DRAG_STIFFNESS 2e4
#define DEMO_DRAG_DAMPING 400
#define DEMO_DRAG_STEP 0.08 /* [m] per key press */
#define DEMO_DRAG_RADIUS (2 * JELLY_DP * 2.5) /* the pull spread over this neighbourhood [m] */

/* The browser's canvas [px]: the view (JELLY_VIEW_W x JELLY_VIEW_H) at 300 pixels per metre; the
   terminal demo's --png-plain draws the same picture. */
#define DEMO_CANVAS_W 600
#define DEMO_CANVAS_H 330

typedef struct {
    jelly_scene scene;
    sps_drag drag;
    int dragging;
    int shear;      /* index into demo_formulations of the next block's formulation */
    int headless;   /* the scripted run: f cycles the -A variants only, a breakdown is an error */
    int resets;     /* scenes started afresh after a breakdown */
    int threads;
    sps_log_fn log;
    char note[256]; /* why the scene last started afresh ("" when it did not) */
} demo_play;

/* Starts the play in the playground (tank = 0) or the water tank (1). */
SCENE_UNUSED static sps_result demo_play_start(demo_play* p, int threads, sps_log_fn log, int tank, int headless) {
    memset(p, 0, sizeof *p);
    p->threads = threads;
    p->log = log;
    p->headless = headless;
    return jelly_create(threads, log, tank, &p->scene);
}

/* The scene afresh (particles cannot be removed), `tank` choosing which. */
SCENE_UNUSED static sps_result demo_play_restart(demo_play* p, int tank) {
    p->dragging = 0;
    sps_world_destroy(p->scene.w);
    return jelly_create(p->threads, p->log, tank, &p->scene);
}

/* The key the scripted run presses at frame `frame` (-1 none): in the playground a block every
   20 frames from frame 10, the next formulation every 20 frames, the first block grabbed at
   frame 15 and pulled right every third frame after; in the tank one raft at frame 10. */
SCENE_UNUSED static int demo_play_scripted_key(int frame, int tank) {
    if (tank) return frame == 10 ? ' ' : -1;
    return frame % 20 == 10 ? ' ' : frame % 20 == 0 && frame ? 'f' : frame == 15 ? 'g' : frame > 15 && frame % 3 == 0 ? 'l' : -1;
}

/* Grabs body b at point (a pointer press, or a block's centre). */
SCENE_UNUSED static sps_result demo_play_grab_body(demo_play* p, sps_body b, const sps_real point[3]) {
    sps_result r = sps_body_drag_begin(p->scene.w, b, point, DEMO_DRAG_STIFFNESS, DEMO_DRAG_DAMPING, DEMO_DRAG_RADIUS, &p->drag);
    p->dragging = r == SPS_OK;
    return r;
}

/* Lets go of the grabbed body, if one is. */
SCENE_UNUSED static sps_result demo_play_let_go(demo_play* p) {
    if (!p->dragging) return SPS_OK;
    p->dragging = 0;
    return sps_body_drag_end(p->scene.w, &p->drag);
}

/* A pointer press at point [m]: grabs the dropped block whose particle (current position) is
   nearest to it, if that is within a particle spacing (the pointer is on the block), else nothing. */
SCENE_UNUSED static sps_result demo_play_grab_at(demo_play* p, const sps_real point[3]) {
    const sps_real* x = sps_world_field(p->scene.w, SPS_FIELD_POSITION_X);
    const sps_real* y = sps_world_field(p->scene.w, SPS_FIELD_POSITION_Y);
    double best = JELLY_DP;
    int k, i, first, count, chosen = -1;
    sps_result r = demo_play_let_go(p);
    for (k = 0; r == SPS_OK && k < p->scene.n_drops; ++k) {
        if (!sps_body_field(p->scene.w, p->scene.drops[k].body, "density", NULL, &first, &count)) continue; /* dropped, not stepped yet */
        for (i = first; i < first + count; ++i) {
            const double d = hypot((double)(x[i] - point[0]), (double)(y[i] - point[1]));
            if (d < best) { best = d; chosen = k; }
        }
    }
    return r != SPS_OK || chosen < 0 ? r : demo_play_grab_body(p, p->scene.drops[chosen].body, point);
}

/* A key: space drops a block (the scene starts afresh when JELLY_MAX_DROPS are out), f the next
   formulation, g grabs the last block at its centre or lets go, h j k l move the grab, t the
   other scene. Other keys do nothing here. */
SCENE_UNUSED static sps_result demo_play_key(demo_play* p, int key) {
    sps_result r = SPS_OK;
    if (key == 'f') p->shear = (p->shear + 1) % (p->headless ? 2 : DEMO_FORMULATIONS); /* see demo_play_frame */
    if (key == 'g' && p->dragging) return demo_play_let_go(p);
    if (key == 'g' && p->scene.n_drops > 0) {
        const jelly_drop* d = &p->scene.drops[p->scene.n_drops - 1];
        sps_particle_state centre;
        if ((r = sps_world_particle(p->scene.w, d->centre_id, &centre)) != SPS_OK) return r;
        return demo_play_grab_body(p, d->body, centre.position);
    }
    if (key == 't') return demo_play_restart(p, !p->scene.tank);
    if (p->dragging && (key == 'h' || key == 'l')) p->drag.target[0] += key == 'l' ? DEMO_DRAG_STEP : -DEMO_DRAG_STEP;
    if (p->dragging && (key == 'j' || key == 'k')) p->drag.target[1] += key == 'k' ? DEMO_DRAG_STEP : -DEMO_DRAG_STEP;
    if (key == ' ') {
        if (p->scene.n_drops == JELLY_MAX_DROPS) {
            if ((r = demo_play_restart(p, p->scene.tank)) != SPS_OK) return r;
            snprintf(p->note, sizeof p->note, "scene reset after %d blocks: particles cannot be removed yet", JELLY_MAX_DROPS);
        }
        r = jelly_drop_block(&p->scene, demo_formulations[p->shear]);
    }
    return r;
}

/* One frame: 1/fps of simulated time within wall_budget_s (0: none, deterministic). The
   scripted run cycles the -A variants only: ENO and GNO do not turn the stored shear of a
   spinning block and OG breaks down, so a block of theirs may fly apart on impact; played, the
   scene then starts afresh with the message in p->note. */
SCENE_UNUSED static sps_result demo_play_frame(demo_play* p, double fps, double wall_budget_s) {
    sps_real covered;
    sps_result r = sps_world_advance_frame(p->scene.w, (sps_real)(1 / fps), wall_budget_s, &covered);
    if (r != SPS_ERR_UNSTABLE || p->headless) return r;
    snprintf(p->note, sizeof p->note, "%.*s: scene reset", (int)sizeof p->note - 16, sps_world_last_error(p->scene.w));
    ++p->resets;
    return demo_play_restart(p, p->scene.tank);
}

/* FNV-1a of the positions (as doubles) in stable-id order: the state a run ends in, as one number. */
SCENE_UNUSED static uint64_t demo_play_checksum(const sps_world* w) {
    uint64_t h = 1469598103934665603ULL;
    int id, n = sps_world_particle_count(w);
    for (id = 0; id < n; ++id) {
        sps_particle_state p;
        double x[3];
        size_t k;
        sps_world_particle(w, id, &p);
        x[0] = p.position[0]; x[1] = p.position[1]; x[2] = p.position[2];
        for (k = 0; k < sizeof x; ++k) h = (h ^ ((const unsigned char*)x)[k]) * 1099511628211ULL;
    }
    return h;
}

#endif
