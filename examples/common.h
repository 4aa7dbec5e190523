/* common.h - what every example program shares: GNU-style options with --help, errors as one
   line on stderr with exit status 2, a progress line on stderr, output folders (CSV, VTK, PNG
   and SVG pictures), wall time, short OpenMP spin waits and the zero-crossing period detector.
   Not part of the library; each example includes it once. POSIX (mkdir, isatty, clock_gettime,
   setenv, execvp). The harness only reads options and writes output: the scene (world def,
   bodies, walls, the time loop) is in each example's own file, or in examples/scenes/ where the
   tests, the bench or the demo share it.

   An example calls the harness at four places around its scene, and the library everywhere else:
       ex_options(argc, argv, about, opts, &c, &wd, &bd);   options: its table, then the shared ones
       ... the world, bodies and walls: sps_world_create, sps_world_add_body, ... (unchecked: a
           library error ends the program in ex_log, the log callback ex_options sets)
       output_open(&out, &c, name, picture_field, extra_csv_header);
       sps_world_advance(w, t_end, on_step, &state);        on_step calls output_tick once
       wall = output_close(w, &out);                        a failed run: its state written, exit 2
       printf("RESULT case=NAME ... %s ...", ..., common_result_fields(&c), ...);
   bench/scene_census.sh counts each example's library calls against these.

   Adding an example: write examples/NAME.c (the contract in the README's "Examples") with a line
   "Smoke: NAME OPTIONS" in its head comment (its brief run in make examples-smoke). The Makefile
   builds every .c file in examples/ but those it lists as not benchmarks; the README's table gets a row. */
#ifndef SPS_EXAMPLE_COMMON_H
#define SPS_EXAMPLE_COMMON_H
#if !defined(_POSIX_C_SOURCE) || _POSIX_C_SOURCE < 200809L
#undef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "../sphsolid.h"
#include "render.h"

#define PI 3.14159265358979323846

/* Every example includes all of this file and uses part of it. */
#if defined(__GNUC__) || defined(__clang__)
#define EX_UNUSED __attribute__((unused))
#else
#define EX_UNUSED
#endif

/* ---- OpenMP waits ---- */
/* A sub-step has about eight barriers. GCC's OpenMP spins about 300,000 times at each before it
   sleeps: on a shared machine a spinning thread then burns the time slice its descheduled team
   mate needs (2D plate, 0.1 s with two busy processes beside it: 3.4 s), while passive waits
   (OMP_WAIT_POLICY=passive) sleep at once and pay a wake-up at every barrier (4.7 s there, and
   3x slower than spinning on an idle machine: 24-29 s against 8 s for 1 s of the plate). A
   short spin, GOMP_SPINCOUNT=10000, is as fast as spinning on an idle machine and the fastest on
   a busy one (1.6 s), so the examples set it unless the user chose a policy or a count. The
   runtime reads the variables when it loads, before main, hence the one re-execution. Other
   OpenMP runtimes ignore GOMP_SPINCOUNT. */
EX_UNUSED static void ex_short_openmp_spin(char** argv) {
    if (!getenv("OMP_WAIT_POLICY") && !getenv("GOMP_SPINCOUNT") && setenv("GOMP_SPINCOUNT", "10000", 1) == 0) execvp(argv[0], argv);
}

/* ---- options ---- */
typedef enum { OPT_INT, OPT_REAL, OPT_STRING, OPT_CHOICE, OPT_FLAG, OPT_PAIR } opt_type;
typedef struct {
    const char* name;     /* without the leading "--" */
    opt_type type;
    void* value;          /* int*, double*, const char**, int* (choice index / flag), int[2] (pair) */
    const char* help;
    double min, max;      /* allowed range for OPT_INT / OPT_REAL / OPT_PAIR */
    const char* choices;  /* OPT_CHOICE: "a|b|c" */
} opt_spec;

/* The total-Lagrangian examples' hourglass options (material.tl.hourglass, .artificial_viscosity). */
#define EX_HOURGLASS_OPTIONS(form, q1)                                                                                     \
    {"hourglass", OPT_CHOICE, &(form), "TL hourglass force: variational (-grad of the springs' energy) or paper (TL eq. 32 alone)", \
     0, 0, "variational|paper"},                                                                                               \
    {"artificial-viscosity", OPT_REAL, &(q1), "TL artificial viscosity q1 (Monaghan's linear term; the TL author's LAMMPS input 0.06)", 0, 1, NULL}
EX_UNUSED static const char* ex_hourglass_name(int form) { return form == SPS_HOURGLASS_PAPER ? "paper" : "variational"; }

EX_UNUSED static void opt_usage(const char* prog, const char* about, const opt_spec* o, int n) {
    int i;
    printf("%s - %s\n\nOptions (default in brackets):\n", prog, about);
    for (i = 0; i < n; ++i) {
        char def[64] = "";
        switch (o[i].type) {
        case OPT_INT: snprintf(def, sizeof def, "%d", *(int*)o[i].value); break;
        case OPT_REAL: snprintf(def, sizeof def, "%g", *(double*)o[i].value); break;
        case OPT_STRING: snprintf(def, sizeof def, "%s", *(const char**)o[i].value); break;
        case OPT_FLAG: snprintf(def, sizeof def, "off"); break;
        case OPT_PAIR: snprintf(def, sizeof def, "%d,%d", ((int*)o[i].value)[0], ((int*)o[i].value)[1]); break;
        case OPT_CHOICE: {
            const char* c = o[i].choices;
            int k = *(int*)o[i].value;
            while (k-- > 0 && strchr(c, '|')) c = strchr(c, '|') + 1;
            snprintf(def, sizeof def, "%.*s", (int)(strchr(c, '|') ? (size_t)(strchr(c, '|') - c) : strlen(c)), c);
        } break;
        }
        printf("  --%-12s %s%s%s [%s]\n", o[i].name, o[i].help, o[i].choices ? ": " : "", o[i].choices ? o[i].choices : "", def);
    }
    printf("  --%-12s %s\n", "help", "print this help and exit");
}

/* Exits with status 2 and a one-line reason on a bad option or value. */
EX_UNUSED static void opt_fail(const char* prog, const char* fmt, const char* a, const char* b) {
    fprintf(stderr, "%s: ", prog);
    fprintf(stderr, fmt, a, b);
    fprintf(stderr, " (see --help)\n");
    exit(2);
}

/* ---- library errors: one line on stderr, exit status 2 ---- */
static const char* g_prog = "example"; /* argv[0], set by opt_parse */
static int g_advancing;                /* 1 from output_open to output_close: the world is being run */
static char g_run_error[1024];         /* an error logged while the world is run, for ex_check_step */

/* The examples' log callback (ex_options puts it in the world def): a library error ends the
   program, "prog: message" on stderr and exit status 2, so a scene calls the library without
   checking each result, as the README's quick start does. While the world is run (output_open
   to output_close) an error is kept instead: a failed step is reported by output_close (or
   ex_check_step), which first writes the state it failed in, and an error of a step callback's
   own calls by the next output_tick. Warnings are printed. */
EX_UNUSED static void ex_log(int level, const char* message, void* user) {
    (void)user;
    if (level == 0 && g_advancing) {
        if (!g_run_error[0]) snprintf(g_run_error, sizeof g_run_error, "%s", message);
        return;
    }
    fprintf(stderr, "%s: %s\n", g_prog, message);
    if (level == 0) exit(2);
}

/* Ends the program on an error the example finds itself (the library's own end it in ex_log):
   "prog: result: the world's last message" on stderr, exit status 2. */
EX_UNUSED static void ex_check(const sps_world* w, sps_result r) {
    if (r == SPS_OK) return;
    fprintf(stderr, "%s: %s: %s\n", g_prog, sps_result_string(r), w ? sps_world_last_error(w) : "");
    exit(2);
}

EX_UNUSED static int opt_choice_index(const char* choices, const char* s) {
    int k = 0;
    size_t len = strlen(s);
    const char* c = choices;
    for (;;) {
        const char* bar = strchr(c, '|');
        size_t l = bar ? (size_t)(bar - c) : strlen(c);
        if (l == len && strncmp(c, s, l) == 0) return k;
        if (!bar) return -1;
        c = bar + 1;
        ++k;
    }
}

EX_UNUSED static double opt_number(const char* prog, const opt_spec* o, const char* s) {
    char* end;
    double v;
    errno = 0;
    v = strtod(s, &end);
    if (end == s || *end || errno || !(v == v)) {
        char what[128];
        snprintf(what, sizeof what, "'%s' is not a number in [%g, %g]", s, o->min, o->max);
        opt_fail(prog, "--%s: %s", o->name, what);
    }
    if (v < o->min || v > o->max) {
        char range[96];
        snprintf(range, sizeof range, "'%s' is outside [%g, %g]", s, o->min, o->max);
        opt_fail(prog, "--%s: %s", o->name, range);
    }
    if (o->type == OPT_INT && v != floor(v)) {
        char what[128];
        snprintf(what, sizeof what, "'%s' is not an integer in [%g, %g]", s, o->min, o->max);
        opt_fail(prog, "--%s: %s", o->name, what);
    }
    return v;
}

/* Parses --name value, --name=value and --flag. */
EX_UNUSED static void opt_parse(int argc, char** argv, const char* about, const opt_spec* o, int n) {
    int i, k;
    g_prog = argv[0];
    for (i = 1; i < argc; ++i) {
        const char* arg = argv[i];
        const char* val = NULL;
        char name[64];
        const opt_spec* s = NULL;
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) { opt_usage(argv[0], about, o, n); exit(0); }
        if (strncmp(arg, "--", 2) != 0) opt_fail(argv[0], "unexpected argument '%s'%s", arg, "");
        snprintf(name, sizeof name, "%s", arg + 2);
        if (strchr(name, '=')) { val = strchr(arg, '=') + 1; *strchr(name, '=') = 0; }
        for (k = 0; k < n; ++k)
            if (strcmp(o[k].name, name) == 0) s = &o[k];
        if (!s) opt_fail(argv[0], "unknown option '--%s'%s", name, "");
        if (s->type == OPT_FLAG) {
            if (val) opt_fail(argv[0], "--%s takes no value%s", s->name, "");
            *(int*)s->value = 1;
            continue;
        }
        if (!val) {
            if (i + 1 >= argc) opt_fail(argv[0], "--%s needs a value%s", s->name, "");
            val = argv[++i];
        }
        switch (s->type) {
        case OPT_INT: *(int*)s->value = (int)opt_number(argv[0], s, val); break;
        case OPT_REAL: *(double*)s->value = opt_number(argv[0], s, val); break;
        case OPT_STRING:
            if (!*val) opt_fail(argv[0], "--%s: empty value%s", s->name, "");
            *(const char**)s->value = val;
            break;
        case OPT_CHOICE:
            if ((k = opt_choice_index(s->choices, val)) < 0) {
                char what[256];
                snprintf(what, sizeof what, "'%s' is not one of %s", val, s->choices);
                opt_fail(argv[0], "--%s: %s", s->name, what);
            }
            *(int*)s->value = k;
            break;
        case OPT_PAIR: {
            char buf[64], *comma;
            snprintf(buf, sizeof buf, "%s", val);
            if (!(comma = strchr(buf, ','))) opt_fail(argv[0], "--%s: '%s' is not of the form m,n", s->name, val);
            *comma = 0;
            ((int*)s->value)[0] = (int)opt_number(argv[0], s, buf);
            ((int*)s->value)[1] = (int)opt_number(argv[0], s, comma + 1);
        } break;
        case OPT_FLAG: break;
        }
    }
}

/* Shear names in the order of the sps_shear enum. */
#define SHEAR_CHOICES "eno|eno-a|og|oas|gno|gno-a"
EX_UNUSED static const char* shear_name(int s) {
    static const char* names[] = {"eno", "eno-a", "og", "oas", "gno", "gno-a"};
    return s >= 0 && s < 6 ? names[s] : "?";
}

/* Rotation names of the -A variants in the order of the sps_rotation enum. */
EX_UNUSED static const char* rotation_name(int r) {
    static const char* names[] = {"mean", "particle", "pair"};
    return r >= 0 && r < 3 ? names[r] : "?";
}
/* A fluid's fluid_dissipation (sps_fluid_dissipation) as the examples' --dissipation spells it. */
EX_UNUSED static const char* dissipation_name(int d) {
    static const char* names[] = {"riemann", "density", "none"};
    return d >= 0 && d < 3 ? names[d] : "?";
}

/* The a of the least-squares fit y = c0 + c1 t + a t^2 / 2 from the sums S[k] = sum t^k
   (k = 0..4) and Y[k] = sum y t^k (k = 0..2): Cramer's rule for the t^2 coefficient. */
EX_UNUSED static double ex_fitted_acceleration(const double* S, const double* Y) {
    const double A[3][3] = {{S[0], S[1], S[2]}, {S[1], S[2], S[3]}, {S[2], S[3], S[4]}};
    const double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                       A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    const double det2 = A[0][0] * (A[1][1] * Y[2] - Y[1] * A[2][1]) - A[0][1] * (A[1][0] * Y[2] - Y[1] * A[2][0]) +
                        Y[0] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    return 2 * det2 / det;
}

/* A disc (2D) or ball (3D) of `radius` centred at (0, centre_y, 0): the signed distance for
   sps_body_add_sdf(_relaxed). */
typedef struct {
    int dim;
    double centre_y, radius;
} ex_ball;
EX_UNUSED static sps_real ex_ball_sdf(const sps_real x[3], void* user) {
    const ex_ball* b = (const ex_ball*)user;
    const double dy = x[1] - b->centre_y, dz = b->dim == 3 ? x[2] : 0;
    return (sps_real)(sqrt(x[0] * x[0] + dy * dy + dz * dz) - b->radius);
}

/* The body of a slope scene (examples/incline.c, rigid_roll.c; gravity tilted, the slope the
   floor y = 0): a block 2 size x size (x size deep in 3D), or a disc / ball of radius size
   filled body-fitted, its surface `lift` [m] above the floor, on a free-slip floor with Coulomb
   coefficient mu. */
EX_UNUSED static sps_result ex_add_slope_body(sps_world* w, sps_body b, int block, int dim, double size, double lift, double mu) {
    const sps_real floor_point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    sps_result r;
    if (block) {
        const sps_real lo[3] = {(sps_real)-size, (sps_real)lift, (sps_real)(-size / 2)}, hi[3] = {(sps_real)size, (sps_real)(size + lift), (sps_real)(size / 2)};
        r = sps_body_add_box(w, b, lo, hi, NULL);
    } else {
        ex_ball ball;
        const sps_real lo[3] = {(sps_real)-size, (sps_real)lift, (sps_real)-size}, hi[3] = {(sps_real)size, (sps_real)(2 * size + lift), (sps_real)size};
        ball.dim = dim; ball.centre_y = size + lift; ball.radius = size;
        r = sps_body_add_sdf_relaxed(w, b, lo, hi, ex_ball_sdf, &ball, 0, NULL);
    }
    if (r == SPS_OK) r = sps_world_add_wall(w, floor_point, up, SPS_WALL_FREE_SLIP);
    return r == SPS_OK ? sps_world_set_wall_friction(w, 0, (sps_real)mu) : r;
}

/* ---- the options every example shares ---- */
typedef struct {
    int shear, rotation, stepping, geometry, kernel, stress, threads, quiet; /* choice indices and flags */
    int transport; /* sps_transport: none, TVF, UTVF */
    int penalty;   /* GNO, GNO-A: 0 the penalty's own pass (the paper's), 1 in the next pressure pass */
    double cfl, t_end, vtk_every, csv_every, E, nu, rho0;
    double h_over_dp;   /* smoothing length / dp; 0 = the library's default (1.3) */
    int contact_rest;   /* sps_contact_rest: 0 flush (the library's default), 1 the papers' kernel-edge law */
    double png_every;   /* > 0: a PNG every png_every s; 0: none; < 0: one PNG at the end */
    int svg;            /* 1: the final picture as SVG too (one circle per particle: large for big 3D runs) */
    int vtk_binary;     /* 1: binary legacy VTK (faster to write, exact values) */
    int vtk_single;     /* 1: VTK reals as 32-bit floats (half the binary size) */
    int png_field;      /* 0 = the example's choice, k = render_fields[k - 1] */
    int png_view;       /* render_view */
    int png_size[2];    /* width, height [px] */
    double zeta, xi; /* ENO and GNO coefficients; 0 = the papers' values (0.7 d + 2.1, and 2) */
    const char* out;
    double jitter; /* lattice jitter in dp */
    int seed;      /* of the jitter */
} common_options;

/* "auto|velocity|pressure|...": the --png-field choices, from render.h's table of fields. */
EX_UNUSED static const char* png_field_choices(void) {
    static char choices[256];
    int k;
    if (!choices[0]) {
        snprintf(choices, sizeof choices, "auto");
        for (k = 0; k < RENDER_FIELD_COUNT; ++k)
            snprintf(choices + strlen(choices), sizeof choices - strlen(choices), "|%s", render_fields[k].name);
    }
    return choices;
}

/* The defaults of the picture options; an example's common_options initialiser ends with them. */
#define PNG_DEFAULTS .png_every = -1, .png_field = 0, .png_view = RENDER_VIEW_XY, .png_size = {600, 400}

/* The opt_spec entries of common_options c, for an example's option table. */
#define COMMON_OPTION_SPECS(c)                                                                          \
    {"shear", OPT_CHOICE, &(c).shear, "shear formulation", 0, 0, SHEAR_CHOICES},                        \
    {"rotation", OPT_CHOICE, &(c).rotation, "-A variants: how the stored increments turn (pair: with their own pair)", 0, 0, "mean|particle|pair"}, \
    {"stepping", OPT_CHOICE, &(c).stepping, "time stepping", 0, 0, "dual|single"},                      \
    {"geometry", OPT_CHOICE, &(c).geometry, "pair geometry in sub-steps", 0, 0, "recomputed|frozen"},   \
    {"kernel", OPT_CHOICE, &(c).kernel, "smoothing kernel", 0, 0, "wendland|spline"},                    \
    {"stress", OPT_CHOICE, &(c).stress, "ENO bodies: integrate the shear stress (von Mises, strain energy)", 0, 0, "on|off"}, \
    {"transport", OPT_CHOICE, &(c).transport, "transport-velocity correction (UTVF sections 3.2-3.3)", 0, 0, "none|tvf|utvf"}, \
    {"cfl", OPT_REAL, &(c).cfl, "acoustic CFL number CFL_ac", 0.01, 1, NULL},                            \
    {"h-over-dp", OPT_REAL, &(c).h_over_dp, "smoothing length / dp (water under gravity: 2)", 1, 3, NULL},  \
    {"contact-rest", OPT_CHOICE, &(c).contact_rest, "where contacts rest: bodies filled flush, or the papers' law (about 1.5 dp off a wall)", 0, 0, "flush|kernel"}, \
    {"E", OPT_REAL, &(c).E, "Young's modulus [Pa]", 1e-3, 1e15, NULL},                                  \
    {"nu", OPT_REAL, &(c).nu, "Poisson ratio", -0.99, 0.4999, NULL},                                    \
    {"rho0", OPT_REAL, &(c).rho0, "density [kg/m^3]", 1e-6, 1e6, NULL},                                 \
    {"zeta", OPT_REAL, &(c).zeta, "ENO/ENO-A coefficient zeta, 0 = 0.7 d + 2.1 (ENO section 4)", 0, 100, NULL}, \
    {"xi", OPT_REAL, &(c).xi, "GNO/GNO-A penalty coefficient xi_G, 0 = 2 (ANG section 5)", 0, 100, NULL}, \
    {"penalty", OPT_CHOICE, &(c).penalty, "GNO/GNO-A: the penalty in a pass of its own (the paper's) or in the next sub-step's pressure pass", 0, 0, "paper|fused"}, \
    {"tend", OPT_REAL, &(c).t_end, "end time [s]", 0, 1e4, NULL},                                       \
    {"out", OPT_STRING, &(c).out, "output folder", 0, 0, NULL},                                         \
    {"vtk-every", OPT_REAL, &(c).vtk_every, "VTK snapshot interval [s], 0 = none", 0, 1e4, NULL},       \
    {"vtk-binary", OPT_FLAG, &(c).vtk_binary, "VTK files in binary (8-15x faster to write, exact values)", 0, 0, NULL}, \
    {"vtk-single", OPT_FLAG, &(c).vtk_single, "VTK reals as 32-bit floats (binary: half the size)", 0, 0, NULL}, \
    {"csv-every", OPT_REAL, &(c).csv_every, "CSV row interval [s]", 1e-7, 1e4, NULL},                   \
    {"threads", OPT_INT, &(c).threads, "OpenMP threads, 0 = all", 0, 1024, NULL},                       \
    {"jitter", OPT_REAL, &(c).jitter, "lattice jitter: each coordinate moved by U(-j/2, j/2) dp", 0, 0.5, NULL}, \
    {"seed", OPT_INT, &(c).seed, "seed of the jitter", 0, 2147483647, NULL},                           \
    {"png-every", OPT_REAL, &(c).png_every, "PNG snapshot interval [s], 0 = none, -1 = one PNG at the end", -1, 1e4, NULL}, \
    {"svg", OPT_FLAG, &(c).svg, "write the final picture as SVG too", 0, 0, NULL},                   \
    {"png-field", OPT_CHOICE, &(c).png_field, "what colours the particles (auto: von-mises for a plate whose stress is tracked, else velocity)", 0, 0, png_field_choices()}, \
    {"png-view", OPT_CHOICE, &(c).png_view, "3D: projection plane or isometric view", 0, 0, RENDER_VIEW_CHOICES}, \
    {"png-size", OPT_PAIR, (c).png_size, "picture width,height [px]", 160, 4096, NULL},                 \
    {"quiet", OPT_FLAG, &(c).quiet, "no progress line", 0, 0, NULL}

/* Copies the shared options' values into the world and body defs, and nothing else: what a
   scene sets for itself is written in its own file. */
EX_UNUSED static void apply_common(const common_options* c, sps_world_def* wd, sps_body_def* bd) {
    wd->stepping = c->stepping ? SPS_STEPPING_SINGLE : SPS_STEPPING_DUAL;
    wd->frozen_geometry = c->geometry == 1;
    wd->kernel = c->kernel ? SPS_KERNEL_CUBIC_SPLINE : SPS_KERNEL_WENDLAND_C2;
    wd->cfl_acoustic = c->cfl;
    if (c->h_over_dp > 0) wd->h_over_dp = c->h_over_dp;
    wd->contact_rest = (sps_contact_rest)c->contact_rest; /* choices in enum order */
    wd->threads = c->threads;
    bd->material.density = c->rho0;
    bd->material.youngs_modulus = c->E;
    bd->material.poisson_ratio = c->nu;
    bd->shear = (sps_shear)c->shear;
    bd->zeta = c->zeta;
    bd->xi = c->xi;
    bd->penalty_in_pressure_pass = c->penalty;
    bd->rotation = (sps_rotation)c->rotation; /* choices in enum order */
    bd->transport = (sps_transport)c->transport; /* likewise */
    bd->track_stress = c->stress == 0; /* von Mises output and the shear part of the strain energy */
}

/* An example's one call for its options: sets the short OpenMP spin (ex_short_openmp_spin),
   parses argv against the example's table opts followed by the shared options of c
   (COMMON_OPTION_SPECS; opt_parse: --help, a bad value ends the program with status 2), copies
   the shared options into the world and body defs (apply_common; bd NULL: the example applies
   them itself) and puts the examples' log callback in the world def (ex_log: a library error
   ends the program). */
#define ex_options(argc, argv, about, opts, c, wd, bd) ex_parse_options(argc, argv, about, opts, (int)(sizeof(opts) / sizeof *(opts)), c, wd, bd)
EX_UNUSED static void ex_parse_options(int argc, char** argv, const char* about, const opt_spec* opts, int n, common_options* c,
                                       sps_world_def* wd, sps_body_def* bd) {
    const opt_spec shared[] = {COMMON_OPTION_SPECS(*c)};
    const int n_shared = (int)(sizeof shared / sizeof *shared);
    opt_spec all[96];
    int k;
    if (n + n_shared > (int)(sizeof all / sizeof *all)) { fprintf(stderr, "%s: %d options: at most %d\n", argv[0], n, (int)(sizeof all / sizeof *all) - n_shared); exit(2); }
    for (k = 0; k < n; ++k) all[k] = opts[k];
    for (k = 0; k < n_shared; ++k) all[n + k] = shared[k];
    ex_short_openmp_spin(argv);
    opt_parse(argc, argv, about, all, n + n_shared);
    if (bd) apply_common(c, wd, bd);
    wd->log = ex_log;
}

/* The shared options set an updated-Lagrangian solid's formulation (shear, rotation, zeta, xi,
   penalty_in_pressure_pass, track_stress) on every body; a body that does not read one of them (a fluid; a total-Lagrangian
   body; Drucker-Prager without GNO's penalty; rotation outside the -A variants) would be warned
   about it by sps_world_add_body, so it gets the library's default back (no effect on results).
   Call it on a def just before sps_world_add_body. */
EX_UNUSED static void ex_unset_unread(sps_body_def* bd) {
    const sps_body_def d0 = sps_default_body_def();
    const int fluid = bd->material.kind == SPS_MATERIAL_FLUID;
    const int granular_without_penalty = bd->material.kind == SPS_MATERIAL_DRUCKER_PRAGER && bd->shear != SPS_SHEAR_GNO && bd->shear != SPS_SHEAR_GNO_A;
    const int reads_shear = bd->solver == SPS_SOLVER_UPDATED_LAGRANGIAN && !fluid && !granular_without_penalty;
    if (!reads_shear) {
        bd->shear = d0.shear;
        bd->zeta = d0.zeta;
        bd->xi = d0.xi;
    }
    if (!reads_shear || (bd->shear != SPS_SHEAR_GNO && bd->shear != SPS_SHEAR_GNO_A)) bd->penalty_in_pressure_pass = d0.penalty_in_pressure_pass;
    if (!reads_shear || (bd->shear != SPS_SHEAR_ENO_A && bd->shear != SPS_SHEAR_GNO_A)) bd->rotation = d0.rotation;
    if (fluid) bd->track_stress = d0.track_stress;
}

/* ---- contact friction and material damping (CONTACT and DAMPING in the header's manual) ---- */
typedef struct {
    double friction;  /* Coulomb mu of the bodies (a pair's: sqrt(mu_a mu_b)) */
    double viscosity; /* Kelvin-Voigt eta of the solids [Pa s] */
} damping_options;
#define DAMPING_OPTION_SPECS(k)                                                                      \
    {"friction", OPT_REAL, &(k).friction, "Coulomb friction coefficient mu of the bodies", 0, 10, NULL}, \
    {"viscosity", OPT_REAL, &(k).viscosity, "Kelvin-Voigt material damping eta [Pa s]", 0, 1e9, NULL}
/* Copies them into a solid's body def. */
EX_UNUSED static void apply_damping(const damping_options* k, sps_body_def* bd) {
    bd->friction = (sps_real)k->friction;
    bd->material.viscosity = (sps_real)k->viscosity;
}
/* The RESULT fields of the options, when set ("" otherwise: the default scene's line is unchanged). */
EX_UNUSED static const char* damping_result_fields(const damping_options* k) {
    static char fields[96];
    fields[0] = 0;
    if (k->friction > 0 || k->viscosity > 0) snprintf(fields, sizeof fields, " friction=%g viscosity=%g", k->friction, k->viscosity);
    return fields;
}

/* 1 if bodies made with these options integrate the shear stress (von Mises, strain energy):
   the OG family always, ENO and ENO-A bodies with --stress on. */
EX_UNUSED static int ex_tracks_stress(const common_options* c) {
    return c->stress == 0 || (c->shear != SPS_SHEAR_ENO && c->shear != SPS_SHEAR_ENO_A);
}

/* ---- time, progress, files ---- */
EX_UNUSED static double wall_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Sleeps until the wall clock reads t [s] (wall_seconds); at once if it is past. */
EX_UNUSED static void sleep_until(double t) {
    double left = t - wall_seconds();
    struct timespec ts;
    if (left <= 0) return;
    ts.tv_sec = (time_t)left;
    ts.tv_nsec = (long)((left - (double)ts.tv_sec) * 1e9);
    nanosleep(&ts, NULL);
}

/* Progress on stderr: on a terminal one line rewritten four times a second; elsewhere (a pipe,
   a log file) a full line every 5 s, so that a long run in a pipe shows it is alive. */
EX_UNUSED static void progress(double t, double t_end, double wall_start, int quiet) {
    static double last = -1;
    const int terminal = isatty(2);
    double now = wall_seconds(), eta;
    if (quiet) return;
    if (last < 0) last = terminal ? 0 : now; /* a pipe: the first line after 5 s */
    if (now - last < (terminal ? 0.25 : 5.0)) return;
    last = now;
    eta = t > 0 ? (now - wall_start) * (t_end - t) / t : 0;
    fprintf(stderr, terminal ? "\r  t = %.4g / %.4g s   %3.0f%%   ETA %.0f s   " : "  t = %.4g / %.4g s   %3.0f%%   ETA %.0f s\n", t, t_end,
            100 * t / t_end, eta);
    if (terminal && t >= t_end) fprintf(stderr, "\n");
}

/* Creates dir and its parents (mkdir -p); returns 0 on success. */
EX_UNUSED static int make_dirs(const char* dir) {
    char buf[1024];
    size_t i;
    snprintf(buf, sizeof buf, "%s", dir);
    for (i = 1; buf[i]; ++i)
        if (buf[i] == '/') {
            buf[i] = 0;
            if (mkdir(buf, 0755) != 0 && errno != EEXIST) return -1;
            buf[i] = '/';
        }
    return mkdir(buf, 0755) != 0 && errno != EEXIST ? -1 : 0;
}

EX_UNUSED static FILE* open_out(const char* dir, const char* name) {
    char path[1200];
    FILE* f;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (!(f = fopen(path, "w"))) { fprintf(stderr, "cannot write %s\n", path); exit(1); }
    return f;
}

/* The shared settings as RESULT fields, so that every RESULT line says what produced it. */
EX_UNUSED static const char* common_result_fields(const common_options* c) {
    static char fields[200];
    int n = snprintf(fields, sizeof fields, "rotation=%s kernel=%s cfl=%g geometry=%s threads=%d real=%s", rotation_name(c->rotation),
                     c->kernel ? "spline" : "wendland", c->cfl, c->geometry ? "frozen" : "recomputed", c->threads,
                     sps_is_double() ? "double" : "float");
    if (c->stress) n += snprintf(fields + n, sizeof fields - (size_t)n, " stress=off");
    if (c->transport) n += snprintf(fields + n, sizeof fields - (size_t)n, " transport=%s", c->transport == 1 ? "tvf" : "utvf");
    if (c->zeta > 0) n += snprintf(fields + n, sizeof fields - (size_t)n, " zeta=%g", c->zeta); /* only when not the papers' */
    if (c->xi > 0) n += snprintf(fields + n, sizeof fields - (size_t)n, " xi=%g", c->xi);
    if (c->penalty) snprintf(fields + n, sizeof fields - (size_t)n, " penalty=fused");
    return fields;
}

/* ---- CSV rows, VTK snapshots and PNG pictures at fixed intervals of simulated time ---- */
typedef struct {
    FILE* csv;
    const char *dir, *name;
    double csv_every, vtk_every, png_every, next_csv, next_vtk, next_png, hourglass_max, min_spacing;
    double wall0; /* wall_seconds() when it was opened: the run's start (progress's ETA, output_close) */
    double t_end; /* the world's time at the run's end (--tend; the progress line's 100 %) */
    int frames, pictures, svg;
    int quiet; /* --quiet: no progress line */
    sps_vtk_options vtk;
    render_options picture;
} output_plan;

/* Creates dir, opens dir/name.csv and writes the header: the diagnostics' columns, then the
   case's own (extra_header starts with a comma). Pictures show c's --png-field, or
   default_field for auto: a render.h field name, or "von-mises-or-velocity", the von Mises
   stress when the bodies track it (ex_tracks_stress), else the speed. Exits with a message if
   it cannot. */
EX_UNUSED static void output_open(output_plan* o, const common_options* c, const char* name, const char* default_field,
                                  const char* extra_header) {
    char file[256];
    memset(o, 0, sizeof *o);
    o->dir = c->out; o->name = name; o->csv_every = c->csv_every; o->vtk_every = c->vtk_every; o->png_every = c->png_every;
    o->svg = c->svg;
    o->quiet = c->quiet;
    o->t_end = c->t_end;
    o->vtk = sps_default_vtk_options();
    o->vtk.binary = c->vtk_binary;
    o->vtk.single_precision = c->vtk_single;
    o->min_spacing = 1e30;
    o->picture.width = c->png_size[0];
    o->picture.height = c->png_size[1];
    o->picture.view = (render_view)c->png_view;
    if (strcmp(default_field, "von-mises-or-velocity") == 0) default_field = ex_tracks_stress(c) ? "von-mises" : "velocity";
    o->picture.field = c->png_field ? &render_fields[c->png_field - 1] : render_field_by_name(default_field);
    o->picture.decorations = 1;
    if (make_dirs(o->dir) != 0) { fprintf(stderr, "cannot create %s\n", o->dir); exit(1); }
    snprintf(file, sizeof file, "%s.csv", name);
    o->csv = open_out(o->dir, file);
    fprintf(o->csv, "%s%s\n", sps_diagnostics_csv_header(), extra_header);
    o->wall0 = wall_seconds();
    g_advancing = 1; /* the run starts: a failed step is reported by output_close */
}

/* Writes a picture of w to dir/name_suffix.png (or .svg); exits with a message if it cannot. */
EX_UNUSED static void output_picture(const sps_world* w, const output_plan* o, const char* suffix, render_format format) {
    char path[1200];
    snprintf(path, sizeof path, "%s/%s_%s.%s", o->dir, o->name, suffix, format == RENDER_SVG ? "svg" : "png");
    if (render_world(w, &o->picture, format, path) != 0) { fprintf(stderr, "%s: cannot write %s\n", g_prog, path); exit(1); }
}

/* A step callback's one call: writes what is due at the world's time, a CSV row (diagnostics,
   then extra, the case's own columns starting with a comma), a VTK snapshot and a PNG picture
   (numbered like the VTK files), and shows the progress line (to o->t_end). Ends the program
   on an error the step callback's own calls logged (ex_log). Returns 1 and fills d when a row
   was written. */
EX_UNUSED static int output_tick(sps_world* w, output_plan* o, const char* extra, sps_diagnostics* d) {
    double t = sps_world_time(w);
    int wrote = 0;
    if (g_run_error[0]) { fprintf(stderr, "%s: %s\n", g_prog, g_run_error); exit(2); }
    progress(t, o->t_end, o->wall0, o->quiet);
    if (t >= o->next_csv - 1e-12) {
        char row[512];
        sps_body all = {0};
        ex_check(w, sps_world_diagnostics(w, all, d));
        sps_diagnostics_csv_row(d, row, sizeof row);
        fprintf(o->csv, "%s%s\n", row, extra);
        if (d->hourglass > o->hourglass_max) o->hourglass_max = d->hourglass;
        if (d->min_spacing < o->min_spacing) o->min_spacing = d->min_spacing;
        o->next_csv += o->csv_every;
        wrote = 1;
    }
    if (o->vtk_every > 0 && t >= o->next_vtk - 1e-12) { /* name_NNNN.vtk and name.vtk.series: their times for ParaView */
        ex_check(w, sps_world_write_vtk_series(w, o->dir, o->name, o->frames++, &o->vtk));
        o->next_vtk += o->vtk_every;
    }
    if (o->png_every > 0 && t >= o->next_png - 1e-12) {
        char number[16];
        snprintf(number, sizeof number, "%04d", o->pictures++);
        output_picture(w, o, number, RENDER_PNG);
        o->next_png += o->png_every;
    }
    return wrote;
}
/* sps_world_advance's step callback for a run whose steps only write the output due and show
   the progress line: user is its output_plan. */
EX_UNUSED static int ex_plain_step(sps_world* w, void* user) {
    sps_diagnostics d;
    output_tick(w, (output_plan*)user, "", &d);
    return 0;
}

/* Returns if the run is well (r is SPS_OK and no error was logged while the world ran);
   otherwise a step failed (or a step callback's call): writes the world to dir/name_failed.vtk
   (rolled back to its last good state if the example set keep_last_good_state), then exits
   with one line naming both. output_close calls it; a loop of sps_world_advance calls checks
   each (a failed step would fail again at once). */
EX_UNUSED static void ex_check_step(sps_world* w, sps_result r, const output_plan* o) {
    char path[1200], failure[1200];
    if (r == SPS_OK && !g_run_error[0]) return;
    snprintf(failure, sizeof failure, "%s%s%s", r != SPS_OK ? sps_result_string(r) : "", r != SPS_OK ? ": " : "",
             r != SPS_OK ? sps_world_last_error(w) : g_run_error);
    snprintf(path, sizeof path, "%s/%s_failed.vtk", o->dir, o->name);
    if (sps_world_write_vtk_ex(w, path, &o->vtk) != SPS_OK) snprintf(path, sizeof path, "(not written)");
    fprintf(stderr, "%s: %s (state at t = %g written to %s)\n", g_prog, failure, (double)sps_world_time(w), path);
    exit(2);
}

/* The end of the run: a run that failed is reported (ex_check_step: its state written, the
   program ended); else closes the CSV, writes the final picture dir/name_final.png when
   --png-every < 0, and dir/name_final.svg with --svg. Returns the run's wall time [s] since
   output_open, the closing left out. */
EX_UNUSED static double output_close(sps_world* w, output_plan* o) {
    const double wall = wall_seconds() - o->wall0;
    ex_check_step(w, SPS_OK, o);
    g_advancing = 0; /* the run is over: an error ends the program at once again */
    fclose(o->csv);
    if (o->png_every < 0) output_picture(w, o, "final", RENDER_PNG);
    if (o->svg) output_picture(w, o, "final", RENDER_SVG);
    return wall;
}

/* The mean pressure of the particles within 2.5 dp of the origin (2D; one particle's is noisy):
   the centre pressure of the fluid examples. */
EX_UNUSED static double ex_centre_pressure(const sps_world* w, double dp) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* p = sps_world_field(w, SPS_FIELD_PRESSURE);
    double sum = 0;
    int i, n = sps_world_particle_count(w), near = 0;
    for (i = 0; i < n; ++i)
        if (x[i] * x[i] + y[i] * y[i] < 6.25 * dp * dp) { sum += p[i]; ++near; }
    return near ? sum / near : 0;
}

/* ---- the soil of the granular examples (GRANULAR in the header's manual) ---- */
typedef struct {
    double cohesion, phi, diffusion; /* [Pa], [degrees], zeta */
    int cone;                        /* sps_yield_cone: the paper examples SPS_CONE_PAPERS */
} granular_options;
#define GRANULAR_OPTION_SPECS(g)                                                                     \
    {"cohesion", OPT_REAL, &(g).cohesion, "cohesion c [Pa]", 0, 1e9, NULL},                          \
    {"phi", OPT_REAL, &(g).phi, "friction angle [degrees]", 0, 89, NULL},                            \
    {"diffusion", OPT_REAL, &(g).diffusion, "stress diffusion coefficient zeta (0: off)", 0, 1, NULL}, \
    {"cone", OPT_CHOICE, &(g).cone, "the Drucker-Prager cone fitted to phi (sps_yield_cone)", 0, 0,   \
     "plane-strain|papers|compression|extension|compromise"}
/* Copies them into a Drucker-Prager body's def (its density, E and nu are the common options). */
EX_UNUSED static void apply_granular(const granular_options* g, sps_body_def* bd) {
    bd->material.granular.cohesion = (sps_real)g->cohesion;
    bd->material.granular.friction_angle = (sps_real)g->phi;
    bd->material.granular.yield_cone = (sps_yield_cone)g->cone;
    bd->material.granular.stress_diffusion = (sps_real)g->diffusion;
}
/* A heap's surface in bins dp wide: the highest particle + dp/2 of each bin, 0 where a bin holds
   fewer than min_count particles (loose grains are not the heap), and, if counts is not NULL,
   each bin's particle count. The bins are columns along x from 0 (axis NULL: heap2d) or rings
   about the vertical line through axis = {x, z} (heap3d, column_collapse3d). The particles of
   body heap, or of the whole world for heap = {0} (heap_pour2d leaves its hopper's out). */
EX_UNUSED static void ex_heap_surface(const sps_world* w, sps_body heap, double dp, int bins, const double* axis, int min_count, double* top,
                                      int* counts) {
    const sps_real *x = sps_world_field(w, SPS_FIELD_POSITION_X), *y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    const sps_real* z = sps_world_field(w, SPS_FIELD_POSITION_Z);
    int* count = counts ? counts : (int*)calloc((size_t)bins, sizeof(int));
    int i, k, first = 0, n = sps_world_particle_count(w);
    for (k = 0; k < bins; ++k) top[k] = 0;
    if (!count) return;
    for (k = 0; k < bins; ++k) count[k] = 0;
    if (heap.id != 0 && !sps_body_field(w, heap, "position_x", NULL, &first, &n)) n = 0;
    for (i = first; i < first + n; ++i) {
        const double r = axis ? sqrt(pow(x[i] - axis[0], 2) + pow(z[i] - axis[1], 2)) : x[i];
        k = (int)(r / dp);
        if (k < 0 || k >= bins) continue;
        if (y[i] + 0.5 * dp > top[k]) top[k] = y[i] + 0.5 * dp;
        ++count[k];
    }
    for (k = 0; k < bins; ++k)
        if (count[k] < min_count) top[k] = 0;
    if (!counts) free(count);
}
/* The slope [m/m] of the least-squares line through the surface heights top[k] at (k + 1/2) dp,
   k from k0 to k1 (either order), that lie between 20 % and 80 % of height: a heap's flank
   (heap2d's columns, heap3d's rings); 0 if fewer than 3 do. */
EX_UNUSED static double ex_flank_slope(const double* top, double dp, int k0, int k1, double height) {
    const int first = k0 < k1 ? k0 : k1, last = k0 < k1 ? k1 : k0;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int k, m = 0;
    for (k = first; k <= last; ++k) {
        const double x = (k + 0.5) * dp, y = top[k];
        if (y < 0.2 * height || y > 0.8 * height) continue;
        sx += x; sy += y; sxx += x * x; sxy += x * y; ++m;
    }
    if (m < 3) return 0;
    return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}
/* The UTVF paper's gravity [m/s^2] (down y) in the granular examples' worlds. */
#define GRANULAR_GRAVITY 9.8
EX_UNUSED static const char* transport_name(int t) { return t == 0 ? "none" : t == 1 ? "TVF" : "UTVF"; }
/* Wall time per particle and acoustic sub-step [ns]. */
EX_UNUSED static double ns_per_particle_step(const sps_world* w, double wall, long steps) {
    return 1e9 * wall / ((double)sps_world_particle_count(w) * (double)(steps > 0 ? steps : 1));
}

/* The clustering indicator of the granular examples: how many particles have another closer
   than fraction dp. The particles are sorted by a cell of edge dp (a hash of the cell's
   coordinates) and each is compared with the particles of its own and the neighbouring cells. */
typedef struct {
    long long cell;
    int i;
} ex_cell_entry;
EX_UNUSED static int ex_cell_order(const void* a, const void* b) {
    const long long ca = ((const ex_cell_entry*)a)->cell, cb = ((const ex_cell_entry*)b)->cell;
    return ca < cb ? -1 : ca > cb;
}
EX_UNUSED static long long ex_cell_key(long long cx, long long cy, long long cz) { return (cx + (1 << 20)) * (1LL << 42) + (cy + (1 << 20)) * (1LL << 21) + (cz + (1 << 20)); }
EX_UNUSED static int ex_clustered_particles(const sps_world* w, double dp, double fraction) {
    const int dim = sps_world_get_def(w)->dim, n = sps_world_particle_count(w);
    const sps_real* x[3] = {sps_world_field(w, SPS_FIELD_POSITION_X), sps_world_field(w, SPS_FIELD_POSITION_Y),
                            dim == 3 ? sps_world_field(w, SPS_FIELD_POSITION_Z) : NULL};
    ex_cell_entry* e = (ex_cell_entry*)malloc(sizeof(ex_cell_entry) * (size_t)(n > 0 ? n : 1));
    int i, count = 0;
    if (!e) return -1;
    for (i = 0; i < n; ++i) {
        e[i].cell = ex_cell_key((long long)floor(x[0][i] / dp), (long long)floor(x[1][i] / dp), dim == 3 ? (long long)floor(x[2][i] / dp) : 0);
        e[i].i = i;
    }
    qsort(e, (size_t)n, sizeof *e, ex_cell_order);
    for (i = 0; i < n; ++i) {
        const int a = e[i].i;
        const long long cx = (long long)floor(x[0][a] / dp), cy = (long long)floor(x[1][a] / dp), cz = dim == 3 ? (long long)floor(x[2][a] / dp) : 0;
        int dx, dy, dz, close = 0;
        for (dx = -1; dx <= 1 && !close; ++dx)
            for (dy = -1; dy <= 1 && !close; ++dy)
                for (dz = dim == 3 ? -1 : 0; dz <= (dim == 3 ? 1 : 0) && !close; ++dz) {
                    ex_cell_entry key, *hit;
                    key.cell = ex_cell_key(cx + dx, cy + dy, cz + dz);
                    hit = (ex_cell_entry*)bsearch(&key, e, (size_t)n, sizeof *e, ex_cell_order);
                    if (!hit) continue;
                    while (hit > e && hit[-1].cell == key.cell) --hit;
                    for (; hit < e + n && hit->cell == key.cell && !close; ++hit) {
                        double r2 = 0;
                        int k;
                        if (hit->i == a) continue;
                        for (k = 0; k < dim; ++k) r2 += (x[k][a] - x[k][hit->i]) * (x[k][a] - x[k][hit->i]);
                        close = r2 < fraction * fraction * dp * dp;
                    }
                }
        count += close;
    }
    free(e);
    return count;
}

/* ---- period of an oscillation from the zero crossings of a signal starting at zero ---- */
typedef struct {
    double t_prev, s_prev, crossing[64]; /* the first 64 crossing times */
    int n;                               /* all crossings seen */
} period_detector;

/* Feeds a sample; crossings are found by linear interpolation between samples. Returns 1 when
   this sample completed a full cycle (an even number of crossings). */
EX_UNUSED static int period_feed(period_detector* p, double t, double s) {
    int cycle = 0;
    if (t > 0 && p->t_prev > 0 && ((p->s_prev < 0 && s >= 0) || (p->s_prev > 0 && s <= 0))) {
        if (p->n < 64) p->crossing[p->n] = p->t_prev + (t - p->t_prev) * p->s_prev / (p->s_prev - s);
        cycle = ++p->n % 2 == 0;
    }
    p->t_prev = t;
    p->s_prev = s;
    return cycle;
}
/* First period: the second zero crossing after the start (the signal starts at zero). */
EX_UNUSED static double period_first(const period_detector* p) { return p->n >= 2 ? p->crossing[1] : -1; }

#endif
