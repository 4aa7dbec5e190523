/* pinned.c - pinned results: the library's answers, bit for bit, across commits.

   Runs short cases over dimension x shear formulation x rotation x pair geometry x kernel (and
   single stepping, tracked stress, several bodies in one world, J2 plasticity), each at 1 and 2
   threads, and compares a 64-bit FNV-1a hash of every particle's position, velocity, density,
   pressure and von Mises stress (and plastic strain: J2 cases) in id order, and of the world's
   diagnostics (energies, momenta, hourglass indicator, smallest spacing; plastic work and
   largest plastic strain: J2 cases), after a few advection steps with the value stored below.
   A change that moves any result by one bit fails here: a commit that changes results on
   purpose regenerates the table (--print) and says why in its message.

   The stored values are for the Makefile's flags (-std=c99 -O2, which keeps floating-point
   contraction off, so every operation is rounded as written and the vector width does not
   matter) with double sps_real; build with -DSPHSOLID_FLOAT for the float table.

   Usage: pinned [--print] [name-filter]
     --print   print the table of current hashes (C initialisers) instead of checking
   The last line is "N passed, M failed"; exit status 0 iff M == 0. */
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A case, written with named fields (a field left out is 0: Wendland, no transport, ...). */
typedef struct pinned_case {
    const char* name;
    int dim;
    sps_shear shear;
    sps_rotation rotation; /* of the -A formulations (omitted: 0, mean) */
    int frozen;            /* world def frozen_geometry */
    sps_kernel_type kernel;
    int single;            /* single stepping */
    int track_stress;
    int all_shears;        /* one body of every formulation the dimension allows, side by side */
    int plastic;           /* 1: J2 material (yields within the run); 2: Drucker-Prager in a tank of walls;
                              its plastic strain and work are hashed too */
    int fluid;             /* 1: a fluid in a tank of walls (mirror particles); 2: also viscous; 3: with an
                              elastic block lying on it (the fluid-structure coupling) */
    sps_transport transport;
    int tl;                /* 0: updated Lagrangian; else the material kind of a total-Lagrangian body (J2 with plastic) */
    int damage;            /* total Lagrangian with damage (TL eqs. 45-46; a threshold the motion passes): its damage is hashed too */
} pinned_case;
/* A case named "...-damped-friction" has Kelvin-Voigt viscosity and friction 0.5 on a floor wall
   with friction 0.5, and no clamp. */
#define DAMPED(c) (strstr((c)->name, "-damped-friction") != NULL)

#define W SPS_KERNEL_WENDLAND_C2
#define S SPS_KERNEL_CUBIC_SPLINE
#define MEAN SPS_ROTATION_MEAN
#define PART SPS_ROTATION_PER_PARTICLE
#define PAIR SPS_ROTATION_PAIR

/* The case list. Every formulation and rotation in 2D and 3D with both pair geometries and
   both kernels; the -A rotations where they apply (the others ignore the rotation). */
static const pinned_case g_cases[] = {
#define GEOMETRIES(nm, d, sh, rot)                                                    \
    {.name = nm "/wendland", .dim = d, .shear = sh, .rotation = rot},                 \
    {.name = nm "/spline", .dim = d, .shear = sh, .rotation = rot, .kernel = S},      \
    {.name = nm "/frozen", .dim = d, .shear = sh, .rotation = rot, .frozen = 1},      \
    {.name = nm "/frozen-spline", .dim = d, .shear = sh, .rotation = rot, .frozen = 1, .kernel = S}
    GEOMETRIES("2d/eno", 2, SPS_SHEAR_ENO, MEAN),
    GEOMETRIES("2d/eno-a-mean", 2, SPS_SHEAR_ENO_A, MEAN),
    GEOMETRIES("2d/eno-a-particle", 2, SPS_SHEAR_ENO_A, PART),
    GEOMETRIES("2d/eno-a-pair", 2, SPS_SHEAR_ENO_A, PAIR),
    GEOMETRIES("2d/og", 2, SPS_SHEAR_OG, MEAN),
    GEOMETRIES("2d/oas", 2, SPS_SHEAR_OAS, MEAN),
    GEOMETRIES("2d/gno", 2, SPS_SHEAR_GNO, MEAN),
    GEOMETRIES("2d/gno-a-mean", 2, SPS_SHEAR_GNO_A, MEAN),
    GEOMETRIES("2d/gno-a-particle", 2, SPS_SHEAR_GNO_A, PART),
    GEOMETRIES("2d/gno-a-pair", 2, SPS_SHEAR_GNO_A, PAIR),
    GEOMETRIES("3d/eno", 3, SPS_SHEAR_ENO, MEAN),
    GEOMETRIES("3d/eno-a-mean", 3, SPS_SHEAR_ENO_A, MEAN),
    GEOMETRIES("3d/eno-a-particle", 3, SPS_SHEAR_ENO_A, PART),
    GEOMETRIES("3d/eno-a-pair", 3, SPS_SHEAR_ENO_A, PAIR),
    GEOMETRIES("3d/og", 3, SPS_SHEAR_OG, MEAN),
    GEOMETRIES("3d/gno", 3, SPS_SHEAR_GNO, MEAN),
    GEOMETRIES("3d/gno-a-mean", 3, SPS_SHEAR_GNO_A, MEAN),
    GEOMETRIES("3d/gno-a-particle", 3, SPS_SHEAR_GNO_A, PART),
    GEOMETRIES("3d/gno-a-pair", 3, SPS_SHEAR_GNO_A, PAIR),
#undef GEOMETRIES
    {.name = "2d/eno-a-mean/single", .dim = 2, .shear = SPS_SHEAR_ENO_A, .single = 1},
    {.name = "2d/eno/stress", .dim = 2, .shear = SPS_SHEAR_ENO, .track_stress = 1},
    {.name = "2d/eno-a-pair/stress", .dim = 2, .shear = SPS_SHEAR_ENO_A, .rotation = PAIR, .track_stress = 1},
    {.name = "3d/eno-a-mean/stress", .dim = 3, .shear = SPS_SHEAR_ENO_A, .track_stress = 1},
    {.name = "2d/all-shears", .dim = 2, .shear = SPS_SHEAR_ENO_A, .all_shears = 1},
    {.name = "3d/all-shears", .dim = 3, .shear = SPS_SHEAR_ENO_A, .all_shears = 1},
    {.name = "2d/j2-og", .dim = 2, .shear = SPS_SHEAR_OG, .plastic = 1},
    {.name = "2d/j2-gno-a-mean", .dim = 2, .shear = SPS_SHEAR_GNO_A, .plastic = 1},
    {.name = "3d/j2-og", .dim = 3, .shear = SPS_SHEAR_OG, .plastic = 1},
    {.name = "3d/j2-gno-a-mean", .dim = 3, .shear = SPS_SHEAR_GNO_A, .plastic = 1},
    {.name = "3d/j2-gno-a-pair", .dim = 3, .shear = SPS_SHEAR_GNO_A, .rotation = PAIR, .plastic = 1},
    {.name = "3d/j2-gno", .dim = 3, .shear = SPS_SHEAR_GNO, .plastic = 1},
    {.name = "2d/fluid", .dim = 2, .shear = SPS_SHEAR_ENO_A, .fluid = 1},
    {.name = "2d/fluid-viscous-tvf", .dim = 2, .shear = SPS_SHEAR_ENO_A, .fluid = 2, .transport = SPS_TRANSPORT_TVF},
    {.name = "2d/fluid-utvf", .dim = 2, .shear = SPS_SHEAR_ENO_A, .fluid = 1, .transport = SPS_TRANSPORT_UTVF},
    {.name = "3d/fluid-utvf", .dim = 3, .shear = SPS_SHEAR_ENO_A, .fluid = 1, .transport = SPS_TRANSPORT_UTVF},
    {.name = "2d/og-utvf", .dim = 2, .shear = SPS_SHEAR_OG, .transport = SPS_TRANSPORT_UTVF},
    {.name = "3d/og-tvf", .dim = 3, .shear = SPS_SHEAR_OG, .transport = SPS_TRANSPORT_TVF},
    /* Drucker-Prager bodies (their shear is not used but for GNO and GNO-A: the default ENO-A) */
    {.name = "2d/drucker-prager", .dim = 2, .shear = SPS_SHEAR_ENO_A, .plastic = 2},
    {.name = "2d/drucker-prager-utvf", .dim = 2, .shear = SPS_SHEAR_ENO_A, .plastic = 2, .transport = SPS_TRANSPORT_UTVF},
    {.name = "3d/drucker-prager", .dim = 3, .shear = SPS_SHEAR_ENO_A, .plastic = 2},
    {.name = "2d/drucker-prager-gno-a", .dim = 2, .shear = SPS_SHEAR_GNO_A, .plastic = 2},
    /* total-Lagrangian bodies (their shear is not used) */
    {.name = "2d/tl-svk", .dim = 2, .shear = SPS_SHEAR_ENO_A, .tl = SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF},
    {.name = "2d/tl-neo-hookean", .dim = 2, .shear = SPS_SHEAR_ENO_A, .tl = SPS_MATERIAL_NEO_HOOKEAN},
    {.name = "2d/tl-j2", .dim = 2, .shear = SPS_SHEAR_ENO_A, .plastic = 1, .tl = SPS_MATERIAL_J2},
    {.name = "3d/tl-svk", .dim = 3, .shear = SPS_SHEAR_ENO_A, .tl = SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF},
    {.name = "3d/tl-neo-hookean", .dim = 3, .shear = SPS_SHEAR_ENO_A, .tl = SPS_MATERIAL_NEO_HOOKEAN},
    {.name = "3d/tl-j2", .dim = 3, .shear = SPS_SHEAR_ENO_A, .plastic = 1, .tl = SPS_MATERIAL_J2},
    {.name = "3d/tl-svk-damage", .dim = 3, .shear = SPS_SHEAR_ENO_A, .tl = SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF, .damage = 1},
    /* friction and Kelvin-Voigt damping in every pressure-pass variant and the TL force pass */
    {.name = "2d/all-shears-damped-friction", .dim = 2, .shear = SPS_SHEAR_ENO_A, .all_shears = 1},
    {.name = "3d/eno-a-pair-damped-friction", .dim = 3, .shear = SPS_SHEAR_ENO_A, .rotation = PAIR},
    {.name = "2d/j2-gno-a-pair-damped-friction", .dim = 2, .shear = SPS_SHEAR_GNO_A, .rotation = PAIR, .plastic = 1},
    {.name = "2d/tl-neo-hookean-damped-friction", .dim = 2, .shear = SPS_SHEAR_ENO_A, .tl = SPS_MATERIAL_NEO_HOOKEAN},
    /* a fluid and an elastic body coupled (its shear: the block's) */
    {.name = "2d/fluid-elastic", .dim = 2, .shear = SPS_SHEAR_ENO_A, .fluid = 3},
    {.name = "3d/fluid-elastic", .dim = 3, .shear = SPS_SHEAR_ENO_A, .fluid = 3},
};
#define NCASES ((int)(sizeof g_cases / sizeof g_cases[0]))

/* The stored hashes, in case order: made with --print. */
static const uint64_t g_pinned[] = {
#ifdef SPHSOLID_FLOAT
#include "pinned_float.inc"
#else
#include "pinned_double.inc"
#endif
};

/* A deterministic velocity field: a rigid spin (omega 4 rad/s about the body's centre, so the
   -A rotations matter), a bending wave, and a small pseudo-random part (so zigzag modes and
   the hourglass controls are exercised). */
typedef struct { double centre[3]; } field_ctx;
static void case_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const field_ctx* c = (const field_ctx*)user;
    const double dx = x[0] - c->centre[0], dy = x[1] - c->centre[1], dz = x[2] - c->centre[2];
    uint64_t h = 1469598103934665603ull;
    const double q[3] = {x[0], x[1], x[2]};
    unsigned char bytes[sizeof q];
    size_t k;
    memcpy(bytes, q, sizeof q);
    for (k = 0; k < sizeof bytes; ++k) h = (h ^ bytes[k]) * 1099511628211ull;
    v[0] = (sps_real)(-4 * dy + 0.02 * ((double)(h & 1023) / 1023 - 0.5));
    v[1] = (sps_real)(4 * dx + 0.3 * sin(10 * x[0]) + 0.02 * ((double)((h >> 10) & 1023) / 1023 - 0.5));
    v[2] = (sps_real)(0.5 * dz + 0.02 * ((double)((h >> 20) & 1023) / 1023 - 0.5));
}

static uint64_t fnv_bytes(uint64_t h, const void* p, size_t n) {
    const unsigned char* b = (const unsigned char*)p;
    size_t k;
    for (k = 0; k < n; ++k) h = (h ^ b[k]) * 1099511628211ull;
    return h;
}

/* An elastic block (of c's shear) lying on the fluid [lo, hi], at rest, over the middle third of
   its length (and depth in 3D), 0.06 high. */
static sps_result add_floating_block(sps_world* w, const pinned_case* c, const sps_real lo[3], const sps_real hi[3]) {
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    sps_real blo[3], bhi[3];
    sps_result r;
    int a;
    bd.shear = c->shear;
    bd.rotation = c->rotation;
    bd.material.density = 600;
    for (a = 0; a < 3; ++a) {
        blo[a] = lo[a] + (hi[a] - lo[a]) / 3;
        bhi[a] = hi[a] - (hi[a] - lo[a]) / 3;
    }
    blo[1] = hi[1];
    bhi[1] = hi[1] + (sps_real)0.06;
    if ((r = sps_world_add_body(w, &bd, &b)) != SPS_OK) return r;
    return sps_body_add_box(w, b, blo, bhi, NULL);
}

/* Adds one block body with its velocity field; one end of it clamped (constraints). */
static int add_case_body(sps_world* w, const pinned_case* c, sps_shear shear, double x0, int index) {
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    field_ctx ctx;
    const double len = c->dim == 2 ? 0.30 : 0.10, hgt = c->dim == 2 ? 0.20 : 0.09, dep = 0.08;
    sps_real lo[3], hi[3], clo[3], chi[3];
    int added = 0;
    bd.shear = shear;
    bd.track_stress = c->track_stress;
    bd.material.youngs_modulus = (sps_real)(1e6 * (1 + 0.25 * index)); /* bodies differ */
    if (c->plastic == 2) { /* a weak soil: the motion takes it onto the cone at once */
        bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
        bd.material.granular.cohesion = (sps_real)2e3;
        bd.material.granular.friction_angle = 30;
        bd.material.granular.dilatancy_angle = 5;
        bd.material.granular.yield_cone = SPS_CONE_PAPERS; /* the cone these hashes were pinned with */
    } else if (c->plastic) { /* a yield stress a quarter of the shear stress the motion builds in the run: it yields */
        bd.material.kind = SPS_MATERIAL_J2;
        bd.material.j2.yield_stress = (sps_real)5e3;
        bd.material.j2.hardening_modulus = (sps_real)1e5;
    }
    bd.transport = c->transport;
    if (c->fluid) {
        bd.material.kind = SPS_MATERIAL_FLUID;
        bd.material.fluid.sound_speed = 20;
        bd.material.viscosity = c->fluid == 2 ? (sps_real)0.5 : 0;
    }
    if (c->tl) {
        bd.solver = SPS_SOLVER_TOTAL_LAGRANGIAN;
        bd.material.kind = (sps_material_kind)c->tl;
        bd.material.tl.damage_strain = c->damage ? (sps_real)1e-3 : 0;
    }
    if (DAMPED(c)) {
        bd.material.viscosity = 20;
        bd.friction = (sps_real)0.5;
    }
    if (sps__reads_rotation(&bd)) bd.rotation = c->rotation; /* the -A formulations' (the others would warn) */
    if (sps_world_add_body(w, &bd, &b) != SPS_OK) return -1;
    lo[0] = (sps_real)x0; lo[1] = 0; lo[2] = 0;
    hi[0] = (sps_real)(x0 + len); hi[1] = (sps_real)hgt; hi[2] = (sps_real)dep;
    if (sps_body_add_box(w, b, lo, hi, &added) != SPS_OK || added == 0) return -1;
    ctx.centre[0] = x0 + 0.5 * len; ctx.centre[1] = 0.5 * hgt; ctx.centre[2] = 0.5 * dep;
    if (sps_body_set_velocity(w, b, case_velocity, &ctx) != SPS_OK) return -1;
    if (c->fluid || c->plastic == 2) { /* a tank with an open top: the walls' mirror particles */
        sps_real tank_hi[3];
        tank_hi[0] = hi[0]; tank_hi[1] = 2 * hi[1]; tank_hi[2] = hi[2];
        if (c->fluid == 3 && add_floating_block(w, c, lo, hi) != SPS_OK) return -1;
        return sps_world_add_box_walls(w, lo, tank_hi, c->dim == 2 ? SPS_FACE_Y_HI : SPS_FACE_Z_HI, SPS_WALL_NO_SLIP) == SPS_OK ? added : -1;
    }
    if (DAMPED(c)) { /* a floor with friction, flush under the lowest particles (its contact's rest) */
        const sps_real point[3] = {0, 0, 0}, up[3] = {0, 1, 0};
        if (index == 0 && (sps_world_add_wall(w, point, up, SPS_WALL_FREE_SLIP) != SPS_OK || sps_world_set_wall_friction(w, 0, (sps_real)0.5) != SPS_OK))
            return -1;
        return added;
    }
    clo[0] = lo[0] - 1; clo[1] = -1; clo[2] = -1;
    chi[0] = (sps_real)(x0 + 0.021); chi[1] = 1; chi[2] = 1;
    if (sps_body_constrain_box(w, b, clo, chi, SPS_AXIS_ALL, NULL, NULL) != SPS_OK) return -1;
    return added;
}

/* Runs case c with the given threads; its hash, or 0 if a call failed (message printed). */
static uint64_t run_case(const pinned_case* c, int threads) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w = NULL;
    uint64_t h = 1469598103934665603ull;
    int n, id, k, step, damaged = 0;
    wd.dim = c->dim;
    wd.dp = (sps_real)0.01;
    wd.kernel = c->kernel;
    wd.frozen_geometry = c->frozen;
    wd.stepping = c->single ? SPS_STEPPING_SINGLE : SPS_STEPPING_DUAL;
    wd.gravity[1] = (sps_real)-9.81;
    wd.threads = threads;
    if (sps_world_create(&wd, &w) != SPS_OK) return 0;
    if (c->all_shears) {
        const sps_shear all[6] = {SPS_SHEAR_ENO, SPS_SHEAR_ENO_A, SPS_SHEAR_OG, SPS_SHEAR_OAS, SPS_SHEAR_GNO, SPS_SHEAR_GNO_A};
        for (k = 0; k < 6; ++k) {
            if (all[k] == SPS_SHEAR_OAS && c->dim == 3) continue;
            if (add_case_body(w, c, all[k], 0.35 * k, k) < 0) goto fail;
        }
    } else if (add_case_body(w, c, c->shear, 0, 0) < 0) goto fail;
    for (step = 0; step < 4; ++step)
        if (sps_world_step(w) != SPS_OK) goto fail;
    n = sps_world_particle_count(w);
    for (id = 0; id < n; ++id) {
        sps_particle_state ps;
        double v[3 + 3 + 3];
        if (sps_world_particle(w, id, &ps) != SPS_OK) goto fail;
        for (k = 0; k < 3; ++k) { v[k] = (double)ps.position[k]; v[3 + k] = (double)ps.velocity[k]; }
        v[6] = (double)ps.density; v[7] = (double)ps.pressure; v[8] = (double)ps.von_mises;
        h = fnv_bytes(h, v, sizeof v);
        if (c->plastic) {
            const double alpha = (double)ps.plastic_strain;
            h = fnv_bytes(h, &alpha, sizeof alpha);
        }
        if (c->damage) {
            const double D = (double)ps.damage;
            h = fnv_bytes(h, &D, sizeof D);
            damaged += ps.damage > 0;
        }
    }
    if (c->damage && damaged == 0) { printf("    %s: no particle was damaged\n", c->name); goto fail; }
    h = fnv_bytes(h, &n, sizeof n);
    {   /* the diagnostics too: energies, momenta, the hourglass indicator (its B_i) and spacing */
        sps_diagnostics d;
        sps_body all = {0};
        double v[10];
        if (sps_world_diagnostics(w, all, &d) != SPS_OK) goto fail;
        v[0] = (double)d.kinetic_energy; v[1] = (double)d.strain_energy; v[2] = (double)d.hourglass;
        v[3] = (double)d.min_spacing;
        for (k = 0; k < 3; ++k) { v[4 + k] = (double)d.linear_momentum[k]; v[7 + k] = (double)d.angular_momentum[k]; }
        h = fnv_bytes(h, v, sizeof v);
        if (c->plastic) {
            const double p[2] = {(double)d.plastic_work, (double)d.max_plastic_strain};
            if (!(d.max_plastic_strain > 0)) { printf("    %s: the body did not yield\n", c->name); goto fail; }
            h = fnv_bytes(h, p, sizeof p);
        }
    }
    sps_world_destroy(w);
    return h;
fail:
    printf("    %s (%d threads): %s\n", c->name, threads, sps_world_last_error(w));
    sps_world_destroy(w);
    return 0;
}

int main(int argc, char** argv) {
    int print = 0, k, passed = 0, failed = 0;
    const char* filter = NULL;
    for (k = 1; k < argc; ++k) {
        if (strcmp(argv[k], "--print") == 0) print = 1;
        else filter = argv[k];
    }
    if (!print && (int)(sizeof g_pinned / sizeof g_pinned[0]) != NCASES) {
        printf("pinned: the table holds %d hashes for %d cases: regenerate it with --print\n",
               (int)(sizeof g_pinned / sizeof g_pinned[0]), NCASES);
        printf("0 passed, 1 failed\n");
        return 1;
    }
    for (k = 0; k < NCASES; ++k) {
        const pinned_case* c = &g_cases[k];
        uint64_t h1, h2;
        if (filter && !strstr(c->name, filter)) continue;
        h1 = run_case(c, 1);
        /* the double build also checks that 2 threads give the same bits; the float build
           checks the precision alone (half the time of make test's pinned part) */
        h2 = sps_is_double() ? run_case(c, 2) : h1;
        if (print) {
            printf("    0x%016llxull, /* %s%s */\n", (unsigned long long)h1, c->name, h1 == h2 ? "" : " (THREADS DIFFER)");
            continue;
        }
        if (h1 && h1 == h2 && h1 == g_pinned[k]) ++passed;
        else {
            ++failed;
            printf("pinned %-28s 1 thread 0x%016llx, 2 threads 0x%016llx, stored 0x%016llx\n", c->name,
                   (unsigned long long)h1, (unsigned long long)h2, (unsigned long long)g_pinned[k]);
        }
    }
    if (print) return 0;
    printf("pinned results (%s): %d passed, %d failed\n", sps_is_double() ? "double" : "float", passed, failed);
    return failed == 0 ? 0 : 1;
}
