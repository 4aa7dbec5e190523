/* demo.c - jelly in the terminal, in real time: a cantilever, a tree and two spinning wheels
   swing under gravity (scenes/jelly.h), and `space` drops new jelly blocks while it runs; or
   (--scene tank, key t) a water tank into which `space` drops jelly rafts that float.
   No dependency: 24-bit ANSI colours and the half block (two pixel rows per character cell),
   termios raw mode (the terminal is restored on exit and on Ctrl-C).

   Keys: space  drop a block (with the formulation shown)     f  next shear formulation
         g      grab / let go of the last block (a drag)       h j k l  move the grab left, down, up, right
         t      the other scene (playground / water tank)      p  pause      q  quit
   The blocks land in a tank (rigid walls) and bounce off the floor, each other and the rest.

   Each frame runs sps_world_advance_frame (sphsolid.h, REAL-TIME FRAMES): 1/fps of simulated
   time, within a wall budget of 80% of the frame period (a slow machine shows slow motion).
   The drag (sps_body_drag_begin) pulls the grabbed block's centre towards a target moved by the
   keys, with a spring spread over a neighbourhood, so the block follows without tearing.
   --headless runs --frames frames with no terminal and no budget (deterministic: the same
   checksum for any thread count), drops a block every 20 frames, grabs the first block at frame
   15 and pulls it to the right, and prints a RESULT line with a checksum of the positions and
   the frame timing (physics and drawing). In the tank scene it drops one raft at frame 10 and
   prints its submerged fraction, the mean over 2-5 s (the splash sets the water sloshing:
   period 2.4 s, undamped; later the raft rises as the water's density drifts up at its free
   surface: bench/VALIDATION.md, fluid-structure), next to Archimedes' (its density over the
   water's, 0.5), and the water level.

   The play (keys, the headless script, the drag, the checksum) is scenes/demo_play.h, which the
   browser's version (examples/web/, make web) shares: the same checksum there (make test-web).

   Build: make demo        Run: ./build/demo      Measure: OMP_NUM_THREADS=1 ./build/demo --headless
   Expect: >= 30 frames per second on one core of a 2020s machine at 80 x 24. */
#include "common.h"
#include "scenes/demo_play.h"
#include <signal.h>
#include <stdarg.h>
#include <sys/ioctl.h>
#include <termios.h>

#define STATUS_LINES 2

/* ---- terminal: raw mode, restored however the program ends ---- */
static struct termios g_saved_termios;
static int g_raw;
static volatile sig_atomic_t g_stop;

static void on_signal(int sig) { (void)sig; g_stop = 1; }

static void terminal_restore(void) {
    if (!g_raw) return;
    tcsetattr(STDIN_FILENO, TCSAFLUSH, &g_saved_termios);
    fputs("\x1b[0m\x1b[?25h\x1b[?1049l", stdout); /* colours off, cursor on, main screen back */
    fflush(stdout);
    g_raw = 0;
}

/* Keys arrive unbuffered and unechoed, read() never waits; Ctrl-C still raises SIGINT, whose
   handler ends the loop so that the terminal is restored. */
static void terminal_raw(void) {
    struct termios raw;
    struct sigaction sa;
    if (tcgetattr(STDIN_FILENO, &g_saved_termios) != 0) { fprintf(stderr, "%s: stdin is not a terminal (try --headless)\n", g_prog); exit(2); }
    raw = g_saved_termios;
    raw.c_lflag &= ~(tcflag_t)(ICANON | ECHO);
    raw.c_cc[VMIN] = 0;
    raw.c_cc[VTIME] = 0;
    tcsetattr(STDIN_FILENO, TCSAFLUSH, &raw);
    g_raw = 1;
    atexit(terminal_restore);
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    fputs("\x1b[?1049h\x1b[?25l\x1b[2J", stdout); /* alternate screen, cursor off, cleared */
}

static int read_key(void) {
    unsigned char c;
    return read(STDIN_FILENO, &c, 1) == 1 ? c : -1;
}

/* The terminal's columns and rows (80 x 24 when it does not say). */
static void terminal_size(int size[2]) {
    struct winsize ws;
    size[0] = 80; size[1] = 24;
    if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col >= 20 && ws.ws_row >= 8) { size[0] = ws.ws_col; size[1] = ws.ws_row; }
}

/* ---- a frame as text: each cell the upper half block, foreground the upper pixel, background the lower ---- */
typedef struct {
    render_options view;
    render_image img;
    char* text;
    size_t length, capacity;
} screen;

static void screen_open(screen* s, int cols, int rows) {
    memset(s, 0, sizeof *s);
    s->view.width = s->img.width = cols;
    s->view.height = s->img.height = 2 * (rows - STATUS_LINES);
    s->view.field = render_field_by_name("velocity");
    s->view.window[0] = -JELLY_VIEW_W / 2; s->view.window[1] = 0; s->view.window[2] = JELLY_VIEW_W / 2; s->view.window[3] = JELLY_VIEW_H;
    s->view.range[0] = 0; s->view.range[1] = 3; /* [m/s]: fixed, so that colours do not flicker */
    s->capacity = (size_t)cols * rows * 40 + 1024; /* two colour codes and a 3-byte character per cell at most */
    s->img.pixels = (unsigned char*)malloc((size_t)s->img.width * s->img.height);
    s->text = (char*)malloc(s->capacity);
    if (!s->img.pixels || !s->text) { fprintf(stderr, "%s: out of memory\n", g_prog); exit(2); }
}

/* The terminal's colour of a palette index: the picture's white background turns dark. */
static const unsigned char* cell_colour(unsigned char index) {
    static const unsigned char dark[3] = {16, 18, 28};
    return index == RENDER_BACKGROUND ? dark : render_palette() + 3 * index;
}

static void screen_printf(screen* s, const char* fmt, ...) {
    va_list ap;
    int n;
    va_start(ap, fmt);
    n = vsnprintf(s->text + s->length, s->capacity - s->length, fmt, ap);
    va_end(ap);
    if (n > 0) s->length += (size_t)n < s->capacity - s->length ? (size_t)n : s->capacity - s->length - 1;
}

/* Draws the world into s->text (the picture rows, then the status lines). */
static void screen_draw(screen* s, const sps_world* w, const char* status, const char* hint) {
    render_layout L;
    int x, row, last_fg = -1, last_bg = -1;
    if (render_layout_make(w, &s->view, &L) != 0) { fprintf(stderr, "%s: out of memory\n", g_prog); exit(2); }
    render_raster(&L, &s->img);
    render_layout_free(&L);
    s->length = 0;
    for (row = 0; 2 * row < s->img.height; ++row) {
        screen_printf(s, "\x1b[%d;1H", row + 1);
        for (x = 0; x < s->img.width; ++x) {
            const unsigned char top = s->img.pixels[(size_t)2 * row * s->img.width + x], bottom = s->img.pixels[(size_t)(2 * row + 1) * s->img.width + x];
            if (top != last_fg) { const unsigned char* c = cell_colour(top); screen_printf(s, "\x1b[38;2;%d;%d;%dm", c[0], c[1], c[2]); last_fg = top; }
            if (bottom != last_bg) { const unsigned char* c = cell_colour(bottom); screen_printf(s, "\x1b[48;2;%d;%d;%dm", c[0], c[1], c[2]); last_bg = bottom; }
            screen_printf(s, "\xe2\x96\x80"); /* U+2580 upper half block */
        }
    }
    screen_printf(s, "\x1b[0m\x1b[%d;1H\x1b[2K%.*s\x1b[%d;1H\x1b[2K%.*s", s->img.height / 2 + 1, s->img.width, status, s->img.height / 2 + 2,
                  s->img.width, hint);
}

/* The library's warnings (an impact faster than 0.2 c0, the energy watchdog): printed when
   headless, shown in the hint line in the terminal, where a printed line would scroll the
   picture away. */
static int g_in_terminal;
static const char* const scene_names[] = {"playground", "tank"};
static char g_warning[256];
static void demo_log(int level, const char* message, void* user) {
    if (level == 0 || !g_in_terminal) ex_log(level, message, user);
    else snprintf(g_warning, sizeof g_warning, "%s", message);
}

int main(int argc, char** argv) {
    int headless = 0, frames = 300, threads = 0, size[2] = {80, 24}, frame, paused = 0, tank = 0, plain = 0;
    double fps = 30, start, physics = 0, drawing = 0, slowest = 0, next, shown_fps = 0, fps_clock;
    const char* png = "";
    opt_spec opts[] = {
        {"headless", OPT_FLAG, &headless, "no terminal: run --frames frames, print a RESULT line (checksum, timing)", 0, 0, NULL},
        {"frames", OPT_INT, &frames, "headless: frames to run", 1, 1e7, NULL},
        {"fps", OPT_REAL, &fps, "frames per second (simulated 1/fps s each)", 1, 240, NULL},
        {"threads", OPT_INT, &threads, "OpenMP threads, 0 = all", 0, 1024, NULL},
        {"size", OPT_PAIR, size, "headless: screen columns,rows (interactive: the terminal's)", 20, 1000, NULL},
        {"png", OPT_STRING, &png, "write the last frame as a PNG picture (600 x 400) to this file; empty = none", 0, 0, NULL},
        {"png-plain", OPT_FLAG, &plain, "the PNG is the view alone (600 x 330), as the browser's canvas draws it", 0, 0, NULL},
        {"scene", OPT_CHOICE, &tank, "the scene at the start (key t switches)", 0, 0, "playground|tank"},
    };
    demo_play play;
    screen scr;
    char status[256], hint[256] = "space drop  f formulation  g grab  hjkl move  t tank/playground  p pause  q quit";
    double level = 0, submerged = 0; /* the tank scene's water level and the rafts' summed submerged fraction */
    int float_frames = 0;
    int fps_frames = 0;

    ex_short_openmp_spin(argv);
    opt_parse(argc, argv, "jelly in the terminal, in real time (scenes/jelly.h)", opts, (int)(sizeof opts / sizeof *opts));
    if (!headless) terminal_size(size);
    g_in_terminal = !headless;
    ex_check(NULL, demo_play_start(&play, threads, demo_log, tank, headless));
    screen_open(&scr, size[0], size[1]);
    if (!headless) terminal_raw();
    start = next = fps_clock = wall_seconds();
    for (frame = 0; headless ? frame < frames : !g_stop; ++frame) {
        double t0 = wall_seconds(), t1;
        const int key = headless ? demo_play_scripted_key(frame, play.scene.tank) : read_key();
        if (key == 'q') break;
        if (key == 'p') paused = !paused;
        ex_check(play.scene.w, demo_play_key(&play, key));
        if (!paused) ex_check(play.scene.w, demo_play_frame(&play, fps, headless ? 0 : 0.8 / fps));
        if (*play.note) { /* the scene started afresh: why */
            snprintf(hint, sizeof hint, "%s", play.note);
            *play.note = 0;
        }
        t1 = wall_seconds();
        if (play.scene.tank && frame >= 2 * fps && frame < 5 * fps) { /* the mean float depth over 2-5 s */
            double fraction;
            jelly_float_report(&play.scene, &level, &fraction);
            submerged += fraction;
            ++float_frames;
        }
        if (*g_warning) { /* the last warning, until the next */
            snprintf(hint, sizeof hint, "%s", g_warning);
            *g_warning = 0;
        }
        snprintf(status, sizeof status, "t = %6.2f s  %5d particles  %5.1f fps  new blocks: %s%s", (double)sps_world_time(play.scene.w),
                 sps_world_particle_count(play.scene.w), shown_fps, demo_formulation_names[play.shear], paused ? "  (paused)" : "");
        screen_draw(&scr, play.scene.w, status, hint);
        physics += t1 - t0;
        drawing += wall_seconds() - t1;
        slowest = fmax(slowest, wall_seconds() - t0);
        if (headless) continue;
        fwrite(scr.text, 1, scr.length, stdout);
        fflush(stdout);
        if (++fps_frames, wall_seconds() - fps_clock >= 1) { shown_fps = fps_frames / (wall_seconds() - fps_clock); fps_frames = 0; fps_clock = wall_seconds(); }
        next += 1 / fps;
        if (next < wall_seconds()) next = wall_seconds(); /* a late frame shifts the schedule: no catch-up burst */
        sleep_until(next);
    }
    terminal_restore();
    if (*png) {
        render_options picture = scr.view;
        picture.width = DEMO_CANVAS_W;
        picture.height = plain ? DEMO_CANVAS_H : 400;
        picture.decorations = !plain;
        if (render_world(play.scene.w, &picture, RENDER_PNG, png) != 0) { fprintf(stderr, "%s: cannot write %s\n", g_prog, png); exit(1); }
    }
    {
        const double wall = wall_seconds() - start;
        sps_diagnostics d;
        sps_body all = {0};
        char floating[160] = "";
        ex_check(play.scene.w, sps_world_diagnostics(play.scene.w, all, &d));
        if (float_frames) submerged /= float_frames;
        if (submerged > 0)
            snprintf(floating, sizeof floating, " water_level=%.4f submerged=%.4f archimedes=%.4f rel_error=%+.2f%%", level, submerged,
                     JELLY_RAFT_RHO0 / 1000.0, 100 * (submerged / (JELLY_RAFT_RHO0 / 1000.0) - 1));
        printf("RESULT case=demo frames=%d substeps_per_frame=%.1f sim_s=%.4f particles=%d blocks=%d resets=%d checksum=%016llx "
               "size=%dx%d ms_per_frame=%.2f physics_ms=%.2f drawing_ms=%.2f slowest_frame_ms=%.2f fps=%.1f threads=%d steps=%ld wall_s=%.2f scene=%s%s\n",
               frame, (double)d.acoustic_steps / frame, (double)sps_world_time(play.scene.w), sps_world_particle_count(play.scene.w),
               play.scene.n_drops, play.resets, (unsigned long long)demo_play_checksum(play.scene.w), size[0], size[1], 1e3 * (physics + drawing) / frame,
               1e3 * physics / frame, 1e3 * drawing / frame, 1e3 * slowest, frame / (physics + drawing), threads, d.acoustic_steps, wall,
               scene_names[play.scene.tank], floating);
    }
    sps_world_destroy(play.scene.w);
    free(scr.img.pixels);
    free(scr.text);
    return 0;
}
