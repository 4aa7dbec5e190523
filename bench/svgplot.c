/* svgplot.c - scatter plots of a CSV table as SVG, so the project renders its own figures with
   nothing beyond libc. One plot per run: the rows that pass every --where, column --x against
   column --y (linear or log axes), each point labelled; --group joins the points of a group in
   order of x and colours them; --pareto draws the Pareto front (lower is better on both axes).

   Build: make build/svgplot
   Run:   ./build/svgplot --csv bench/results/M/knobs.csv --where scene=plate2d --x cpu_s
              --y period_err_pct --abs-y --logx --logy --label setting --pareto
              --title "..." --xlabel "..." --ylabel "..." --out plot.svg
   Rows whose x or y is empty or not a number (or not > 0 on a log axis) are left out and
   counted on stderr. The CSV has a header line and no quoted fields. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_ROWS 2048
#define MAX_COLS 64
#define MAX_WHERE 8
#define MAX_GROUPS 16
#define LINE 4096

/* Canvas: the plot area is [LEFT, WIDTH - RIGHT] x [TOP, HEIGHT - BOTTOM] in SVG pixels. */
#define WIDTH 860
#define HEIGHT 600
#define LEFT 80
#define RIGHT 200 /* room for labels of the rightmost points and the legend */
#define TOP 50
#define BOTTOM 60
#define FONT 11
#define CHAR_W 6.2 /* mean glyph width at FONT px, for label boxes */

static const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

typedef struct {
    const char *csv, *x, *y, *label, *group, *title, *xlabel, *ylabel, *out;
    const char* where[MAX_WHERE];
    int nwhere, logx, logy, abs_y, pareto;
} options;

typedef struct {
    double x, y;
    char label[96], group[48];
    int pareto;
} point;

typedef struct { double lo, hi; int log; } axis;

static void fail(const char* what, const char* detail) {
    fprintf(stderr, "svgplot: %s%s\n", what, detail);
    exit(2);
}

/* ---- options ---- */
static void parse_options(int argc, char** argv, options* o) {
    int i;
    memset(o, 0, sizeof *o);
    for (i = 1; i < argc; ++i) {
        const char* a = argv[i];
        const char** value = NULL;
        if (!strcmp(a, "--logx")) { o->logx = 1; continue; }
        if (!strcmp(a, "--logy")) { o->logy = 1; continue; }
        if (!strcmp(a, "--abs-y")) { o->abs_y = 1; continue; }
        if (!strcmp(a, "--pareto")) { o->pareto = 1; continue; }
        if (!strcmp(a, "--csv")) value = &o->csv;
        else if (!strcmp(a, "--x")) value = &o->x;
        else if (!strcmp(a, "--y")) value = &o->y;
        else if (!strcmp(a, "--label")) value = &o->label;
        else if (!strcmp(a, "--group")) value = &o->group;
        else if (!strcmp(a, "--title")) value = &o->title;
        else if (!strcmp(a, "--xlabel")) value = &o->xlabel;
        else if (!strcmp(a, "--ylabel")) value = &o->ylabel;
        else if (!strcmp(a, "--out")) value = &o->out;
        else if (!strcmp(a, "--where")) {
            if (o->nwhere == MAX_WHERE) fail("too many --where", "");
            value = &o->where[o->nwhere++];
        } else fail("unknown option ", a);
        if (i + 1 >= argc) fail("missing value after ", a);
        *value = argv[++i];
    }
    if (!o->csv || !o->x || !o->y || !o->out) fail("--csv, --x, --y and --out are required", "");
}

/* ---- CSV ---- */
/* Splits line in place at commas (and the newline); returns the number of fields. */
static int split(char* line, char** field) {
    int n = 0;
    char* p = line;
    line[strcspn(line, "\r\n")] = 0;
    for (;;) {
        char* comma = strchr(p, ',');
        if (n == MAX_COLS) fail("too many columns", "");
        field[n++] = p;
        if (!comma) return n;
        *comma = 0;
        p = comma + 1;
    }
}

static int column(char** header, int ncols, const char* name) {
    int k;
    for (k = 0; k < ncols; ++k)
        if (!strcmp(header[k], name)) return k;
    fail("no column named ", name);
    return -1;
}

/* The number in s, or NAN when s is empty or not entirely a number. */
static double number(const char* s) {
    char* end;
    double v = strtod(s, &end);
    return end != s && *end == 0 ? v : NAN;
}

/* Rows passing every --where, with finite x and y (> 0 on log axes). Returns the count. */
static int read_points(const options* o, point* pts) {
    static char head_line[LINE], line[LINE];
    char *head[MAX_COLS], *f[MAX_COLS];
    int where_col[MAX_WHERE], ncols, k, n = 0, skipped = 0, xc, yc, lc = -1, gc = -1;
    FILE* in = fopen(o->csv, "r");
    if (!in) fail("cannot read ", o->csv);
    if (!fgets(head_line, sizeof head_line, in)) fail("empty file ", o->csv);
    ncols = split(head_line, head);
    xc = column(head, ncols, o->x);
    yc = column(head, ncols, o->y);
    if (o->label) lc = column(head, ncols, o->label);
    if (o->group) gc = column(head, ncols, o->group);
    for (k = 0; k < o->nwhere; ++k) {
        char name[64];
        const char* eq = strchr(o->where[k], '=');
        if (!eq || eq - o->where[k] >= (long)sizeof name) fail("--where needs COLUMN=VALUE: ", o->where[k]);
        snprintf(name, sizeof name, "%.*s", (int)(eq - o->where[k]), o->where[k]);
        where_col[k] = column(head, ncols, name);
    }
    while (fgets(line, sizeof line, in)) {
        int nf = split(line, f), keep = 1;
        double x, y;
        for (k = 0; k < o->nwhere; ++k)
            keep = keep && where_col[k] < nf && !strcmp(f[where_col[k]], strchr(o->where[k], '=') + 1);
        if (!keep) continue;
        x = xc < nf ? number(f[xc]) : NAN;
        y = yc < nf ? number(f[yc]) : NAN;
        if (o->abs_y) y = fabs(y);
        if (!isfinite(x) || !isfinite(y) || (o->logx && x <= 0) || (o->logy && y <= 0)) { ++skipped; continue; }
        if (n == MAX_ROWS) fail("too many rows", "");
        memset(&pts[n], 0, sizeof pts[n]);
        pts[n].x = x;
        pts[n].y = y;
        if (lc >= 0 && lc < nf) snprintf(pts[n].label, sizeof pts[n].label, "%s", f[lc]);
        if (gc >= 0 && gc < nf) snprintf(pts[n].group, sizeof pts[n].group, "%s", f[gc]);
        ++n;
    }
    fclose(in);
    if (skipped) fprintf(stderr, "svgplot: %s: %d row(s) without a plottable %s and %s left out\n", o->out, skipped, o->x, o->y);
    return n;
}

/* ---- axes ---- */
/* Range of the values with a margin: a factor 1.4 on log axes, 6% of the span on linear ones. */
static axis make_axis(const point* p, int n, int use_y, int log_scale) {
    axis a = {HUGE_VAL, -HUGE_VAL, log_scale};
    int i;
    for (i = 0; i < n; ++i) {
        double v = use_y ? p[i].y : p[i].x;
        if (v < a.lo) a.lo = v;
        if (v > a.hi) a.hi = v;
    }
    if (log_scale) {
        a.lo /= 1.4;
        a.hi *= 1.4;
    } else {
        double m = a.hi > a.lo ? 0.06 * (a.hi - a.lo) : fabs(a.hi) * 0.1 + 1;
        a.lo -= m;
        a.hi += m;
    }
    return a;
}

/* Position of v on the axis in [0, 1]. */
static double unit(const axis* a, double v) {
    return a->log ? (log10(v) - log10(a->lo)) / (log10(a->hi) - log10(a->lo)) : (v - a->lo) / (a->hi - a->lo);
}
static double px(const axis* a, double v) { return LEFT + unit(a, v) * (WIDTH - LEFT - RIGHT); }
static double py(const axis* a, double v) { return HEIGHT - BOTTOM - unit(a, v) * (HEIGHT - TOP - BOTTOM); }

/* Tick values: 1, 2, 5 x 10^k on log axes (1 x 10^k alone when they span more than 3 decades);
   on linear axes the 1-2-5 step that gives 4 to 10 ticks. Returns the count. */
static int ticks(const axis* a, double* t, int max) {
    int n = 0;
    if (a->log) {
        static const double mant[3] = {1, 2, 5};
        int e, m, every = log10(a->hi / a->lo) > 3 ? 3 : 1;
        for (e = (int)floor(log10(a->lo)); e <= (int)ceil(log10(a->hi)); ++e)
            for (m = 0; m < 3; m += every) {
                double v = mant[m] * pow(10, e);
                if (v >= a->lo && v <= a->hi && n < max) t[n++] = v;
            }
    } else {
        double step = pow(10, floor(log10((a->hi - a->lo) / 4))), v;
        if ((a->hi - a->lo) / step > 20) step *= 5;
        else if ((a->hi - a->lo) / step > 10) step *= 2;
        for (v = ceil(a->lo / step) * step; v <= a->hi && n < max; v += step) t[n++] = fabs(v) < 1e-12 * step ? 0 : v;
    }
    return n;
}

/* ---- SVG ---- */
static void text(FILE* f, double x, double y, const char* anchor, const char* extra, const char* s) {
    fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\" %s>", x, y, anchor, extra);
    for (; *s; ++s) {
        if (*s == '&') fputs("&amp;", f);
        else if (*s == '<') fputs("&lt;", f);
        else if (*s == '>') fputs("&gt;", f);
        else fputc(*s, f);
    }
    fputs("</text>\n", f);
}

static void draw_axes(FILE* f, const options* o, const axis* ax, const axis* ay) {
    double t[64];
    char s[32];
    int n, i;
    fprintf(f, "<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\" fill=\"none\" stroke=\"#444\"/>\n", LEFT, TOP,
            WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM);
    n = ticks(ax, t, 64);
    for (i = 0; i < n; ++i) {
        double x = px(ax, t[i]);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%d\" x2=\"%.1f\" y2=\"%d\" stroke=\"#ddd\"/>\n", x, TOP, x, HEIGHT - BOTTOM);
        snprintf(s, sizeof s, "%g", t[i]);
        text(f, x, HEIGHT - BOTTOM + 16, "middle", "", s);
    }
    n = ticks(ay, t, 64);
    for (i = 0; i < n; ++i) {
        double y = py(ay, t[i]);
        fprintf(f, "<line x1=\"%d\" y1=\"%.1f\" x2=\"%d\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", LEFT, y, WIDTH - RIGHT, y);
        snprintf(s, sizeof s, "%g", t[i]);
        text(f, LEFT - 6, y + 4, "end", "", s);
    }
    if (o->title) text(f, (LEFT + WIDTH - RIGHT) / 2.0, TOP - 20, "middle", "font-size=\"15\" font-weight=\"bold\"", o->title);
    text(f, (LEFT + WIDTH - RIGHT) / 2.0, HEIGHT - 18, "middle", "font-size=\"13\"", o->xlabel ? o->xlabel : o->x);
    fprintf(f, "<g transform=\"translate(22 %.1f) rotate(-90)\">", (TOP + HEIGHT - BOTTOM) / 2.0);
    text(f, 0, 0, "middle", "font-size=\"13\"", o->ylabel ? o->ylabel : o->y);
    fputs("</g>\n", f);
}

static int by_x(const void* a, const void* b) {
    double d = ((const point*)a)->x - ((const point*)b)->x;
    return d < 0 ? -1 : d > 0;
}

/* Marks the Pareto points (no other point has both a smaller or equal x and a smaller y) and
   draws the front as a staircase: for any cost between two front points, the best error
   measured within that cost is the left one's. Expects pts sorted by x. */
static void draw_pareto(FILE* f, point* pts, int n, const axis* ax, const axis* ay) {
    double best = HUGE_VAL;
    int i, first = 1;
    fputs("<path fill=\"none\" stroke=\"#000\" stroke-width=\"2\" stroke-dasharray=\"6 3\" d=\"", f);
    for (i = 0; i < n; ++i) {
        if (!(pts[i].y < best)) continue;
        if (first) fprintf(f, "M%.1f %.1f", px(ax, pts[i].x), py(ay, pts[i].y));
        else fprintf(f, " H%.1f V%.1f", px(ax, pts[i].x), py(ay, pts[i].y));
        best = pts[i].y;
        pts[i].pareto = 1;
        first = 0;
    }
    fputs("\"/>\n", f);
}

/* Index of a group name in groups (added when new); the colour index. */
static int group_index(char groups[][48], int* ngroups, const char* g) {
    int k;
    for (k = 0; k < *ngroups; ++k)
        if (!strcmp(groups[k], g)) return k;
    if (*ngroups == MAX_GROUPS) return MAX_GROUPS - 1;
    snprintf(groups[*ngroups], 48, "%s", g);
    return (*ngroups)++;
}

/* Joins the points of each group in order of x (pts sorted by x). */
static void draw_groups(FILE* f, const point* pts, int n, char groups[][48], int ngroups, const axis* ax, const axis* ay) {
    int g, i;
    for (g = 0; g < ngroups; ++g) {
        int first = 1;
        fprintf(f, "<path fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" d=\"", palette[g % 8]);
        for (i = 0; i < n; ++i) {
            if (strcmp(pts[i].group, groups[g])) continue;
            fprintf(f, "%s%.1f %.1f", first ? "M" : " L", px(ax, pts[i].x), py(ay, pts[i].y));
            first = 0;
        }
        fputs("\"/>\n", f);
    }
}

/* Label boxes placed so far, to keep labels from covering each other. */
typedef struct { double x0, y0, x1, y1; } box;
static int overlaps(const box* placed, int n, box b) {
    int k;
    if (b.x0 < LEFT || b.x1 > WIDTH - 4 || b.y0 < TOP || b.y1 > HEIGHT - BOTTOM) return 1;
    for (k = 0; k < n; ++k)
        if (b.x0 < placed[k].x1 && placed[k].x0 < b.x1 && b.y0 < placed[k].y1 && placed[k].y0 < b.y1) return 1;
    return 0;
}

/* Places a label near (x, y): right, left, above, below, then further away; the first free spot. */
static void place_label(FILE* f, box* placed, int* nplaced, double x, double y, const char* s) {
    static const double dx[8] = {10, -10, 0, 0, 8, 8, -8, -8}, dy[8] = {4, 4, -10, 18, -10, 18, -10, 18};
    double w = CHAR_W * (double)strlen(s), h = FONT;
    int k;
    for (k = 0; k < 8 * 3; ++k) {
        double far = 1 + k / 8, ox = dx[k % 8] * far, oy = dy[k % 8] + (far - 1) * (dy[k % 8] < 5 ? -6 : 6);
        double x0 = ox > 0 ? x + ox : ox < 0 ? x + ox - w : x - w / 2;
        box b;
        b.x0 = x0; b.x1 = x0 + w; b.y0 = y + oy - h + 2; b.y1 = y + oy + 2;
        if (!overlaps(placed, *nplaced, b) || k == 8 * 3 - 1) {
            if (*nplaced < MAX_ROWS) placed[(*nplaced)++] = b;
            if (far > 1) fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#aaa\"/>\n", x, y, x0 + w / 2, b.y1 - h / 2);
            text(f, x0, y + oy, "start", "fill=\"#333\"", s);
            return;
        }
    }
}

static void draw_points(FILE* f, const point* pts, int n, char groups[][48], int* ngroups, const axis* ax, const axis* ay) {
    static box placed[MAX_ROWS];
    int i, nplaced = 0;
    for (i = 0; i < n; ++i) { /* every marker is an obstacle for the labels */
        box b;
        b.x0 = px(ax, pts[i].x) - 7; b.x1 = b.x0 + 14; b.y0 = py(ay, pts[i].y) - 7; b.y1 = b.y0 + 14;
        placed[nplaced++] = b;
    }
    for (i = 0; i < n; ++i) {
        double x = px(ax, pts[i].x), y = py(ay, pts[i].y);
        const char* colour = pts[i].group[0] ? palette[group_index(groups, ngroups, pts[i].group) % 8] : palette[0];
        if (pts[i].pareto) fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"7\" fill=\"none\" stroke=\"#000\" stroke-width=\"1.5\"/>\n", x, y);
        fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"%s\"/>\n", x, y, colour);
    }
    for (i = 0; i < n; ++i)
        if (pts[i].label[0]) place_label(f, placed, &nplaced, px(ax, pts[i].x), py(ay, pts[i].y), pts[i].label);
}

static void draw_legend(FILE* f, char groups[][48], int ngroups, int pareto) {
    double x = WIDTH - RIGHT + 16, y = TOP + 10;
    int g;
    for (g = 0; g < ngroups; ++g, y += 18) {
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"2\"/>\n", x, y - 4, x + 18, y - 4, palette[g % 8]);
        fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"%s\"/>\n", x + 9, y - 4, palette[g % 8]);
        text(f, x + 24, y, "start", "", groups[g]);
    }
    if (pareto) {
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#000\" stroke-width=\"2\" stroke-dasharray=\"6 3\"/>\n", x, y - 4, x + 18, y - 4);
        text(f, x + 24, y, "start", "", "Pareto front");
    }
}

int main(int argc, char** argv) {
    static point pts[MAX_ROWS];
    char groups[MAX_GROUPS][48];
    int n, ngroups = 0, i;
    options o;
    axis ax, ay;
    FILE* f;
    parse_options(argc, argv, &o);
    n = read_points(&o, pts);
    if (n == 0) fail("no rows to plot in ", o.csv);
    qsort(pts, (size_t)n, sizeof *pts, by_x);
    for (i = 0; i < n; ++i)
        if (pts[i].group[0]) group_index(groups, &ngroups, pts[i].group);
    ax = make_axis(pts, n, 0, o.logx);
    ay = make_axis(pts, n, 1, o.logy);
    if (!(f = fopen(o.out, "w"))) fail("cannot write ", o.out);
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
               "font-family=\"Helvetica, Arial, sans-serif\" font-size=\"%d\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"#fff\"/>\n",
            WIDTH, HEIGHT, WIDTH, HEIGHT, FONT);
    draw_axes(f, &o, &ax, &ay);
    if (ngroups) draw_groups(f, pts, n, groups, ngroups, &ax, &ay);
    if (o.pareto) draw_pareto(f, pts, n, &ax, &ay);
    draw_points(f, pts, n, groups, &ngroups, &ax, &ay);
    draw_legend(f, groups, ngroups, o.pareto);
    fputs("</svg>\n", f);
    if (fclose(f) != 0) fail("error writing ", o.out);
    return 0;
}
