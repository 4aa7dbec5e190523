/* test_fluids.c - fluids, granular media and the fluid-structure coupling.
   Included by tests/test_sphsolid.c (the runner and its helpers); its list of tests is run_fluids_tests at its end. */
#include "../examples/scenes/infinite_slope.h"

/* ============================================================================================ */


/* ---- fluids and transport corrections (FLUIDS, TRANSPORT) ---- */

static const double level_04 = 0.4, level_05 = 0.5, level_048 = 0.48; /* the tanks' water levels [m] */
/* The pressure of water at rest (rho0 1000, g 9.81) below the level *user [m]. */
static sps_real water_at_rest(const sps_real x[3], void* user) {
    const double level = *(const double*)user;
    return (sps_real)(1000 * 9.81 * (level - (double)x[1]));
}

/* Water H = 0.5 m deep and `width` wide at rest in a tank of free-slip analytic walls, open top,
   depth/dp = layers, h = h_over_dp dp, c0 = 10 sqrt(g H), started on the lattice at its
   hydrostatic pressure (bench/still_water's tank). */
static sps_world* still_tank(double width, int layers, double h_over_dp, sps_lattice lattice, sps_log_fn log, sps_body* water) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0, (sps_real)level_05, 0}, tank_hi[3] = {0, 2, 0};
    hi[0] = tank_hi[0] = (sps_real)width;
    wd.dim = 2;
    wd.dp = (sps_real)(level_05 / layers);
    wd.h_over_dp = (sps_real)h_over_dp;
    wd.threads = 1;
    wd.gravity[1] = -9.81;
    wd.log = log;
    if (sps_world_create(&wd, &w) != SPS_OK) return NULL;
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = (sps_real)(10 * sqrt(9.81 * level_05));
    bd.lattice = lattice;
    if (sps_world_add_box_walls(w, lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) != SPS_OK || sps_world_add_body(w, &bd, water) != SPS_OK
        || sps_body_add_box(w, *water, lo, hi, NULL) != SPS_OK || sps_body_set_pressure(w, *water, water_at_rest, (void*)&level_05) != SPS_OK) {
        sps_world_destroy(w);
        return NULL;
    }
    return w;
}

/* Water at rest fewer than 14 particles deep gains potential energy (its rows under the free
   surface close up towards it; bench/VALIDATION.md, "Shallow water"): the energy watchdog says
   so, naming the depth and the fix, not the time step (halving the CFL number does not change
   the gain: measured); 8 particles deep it gains 5.9 % of its compression energy in 1 s, and the
   same tank 16 particles deep loses energy over the same time, without a word. */
static int test_watchdog_names_shallow_water(void) {
    sps_world* w;
    sps_body water;
    g_warnings = 0;
    ENSURE((w = still_tank(2.0, 8, 1.3, SPS_LATTICE_AUTO, warning_log, &water)) != NULL && sps_world_advance(w, 1.2, NULL, NULL) == SPS_OK);
    printf("    %s\n", g_warning_first);
    ENSURE(g_warnings >= 1 && strstr(g_warning_first, "energy watchdog") && strstr(g_warning_first, "gained most"));
    ENSURE(strstr(g_warning_first, "it is 8 particles deep") && strstr(g_warning_first, "smaller dp") && !strstr(g_warning_first, "halve"));
    sps_world_destroy(w);
    g_warnings = 0;
    ENSURE((w = still_tank(2.0, 16, 1.3, SPS_LATTICE_AUTO, warning_log, &water)) != NULL && sps_world_advance(w, 1.2, NULL, NULL) == SPS_OK);
    ENSURE(g_warnings == 0);
    sps_world_destroy(w);
    return 0;
}

/* The particle speeds' mean square and largest value, and the bottom layer's mean of p + rho0 g y
   (rho0 g H at rest). */
static void still_tank_state(const sps_world* w, double dp, double* mean_square, double* largest, double* floor_pressure) {
    const sps_real *u = sps_world_field(w, SPS_FIELD_VELOCITY_X), *v = sps_world_field(w, SPS_FIELD_VELOCITY_Y);
    const sps_real *y = sps_world_field(w, SPS_FIELD_POSITION_Y), *p = sps_world_field(w, SPS_FIELD_PRESSURE);
    const int n = sps_world_particle_count(w);
    double sum = 0, floor_sum = 0;
    int i, nfloor = 0;
    *largest = 0;
    for (i = 0; i < n; ++i) {
        const double s2 = (double)u[i] * u[i] + (double)v[i] * v[i];
        sum += s2;
        if (s2 > *largest * *largest) *largest = sqrt(s2);
        if (y[i] < dp) { floor_sum += p[i] + 1000 * 9.81 * y[i]; ++nfloor; }
    }
    *mean_square = sum / n;
    *floor_pressure = floor_sum / (nfloor ? nfloor : 1);
}

/* A tank at rest is still once its start has rung down (FLUIDS; bench/VALIDATION.md, "Still
   water": its free surface bursts later, at 8-14 s): 20 layers, h = 2 dp;
   over 3-4 s (the start's ringing, 5e-3 sqrt(g H) at first, has died down) the speed's RMS and
   largest value stay within the acceptance figures of the long runs and the floor carries the
   column. At h = 1.3 dp the same tank churns from 2.5 s (RMS 9e-3 sqrt(g H) over 3-4 s), and
   at 2 dp without the corner images and with tr L as the divergence it reaches 3.5e-3. */
static int test_still_water(void) {
    sps_body water;
    sps_world* w = still_tank(0.5, 20, 2, SPS_LATTICE_AUTO, quiet_log, &water);
    const double u_ref = sqrt(9.81 * level_05), dp = level_05 / 20, rho_g_h = 1000 * 9.81 * level_05;
    double rms2 = 0, largest = 0, floor_pressure = 0;
    int k, samples = 0;
    ENSURE(w != NULL);
    ENSURE(sps_world_advance(w, 3, NULL, NULL) == SPS_OK);
    for (k = 1; k <= 10; ++k) {
        double ms, top;
        ENSURE(sps_world_advance(w, (sps_real)(3 + 0.1 * k), NULL, NULL) == SPS_OK);
        still_tank_state(w, dp, &ms, &top, &floor_pressure);
        rms2 += ms;
        ++samples;
        if (top > largest) largest = top;
    }
    printf("    3-4 s: speed RMS %.3g sqrt(g H), largest %.3g sqrt(g H); floor p + rho g y at 4 s %.5f rho g H\n", sqrt(rms2 / samples) / u_ref,
           largest / u_ref, floor_pressure / rho_g_h);
    /* the long runs' targets (bench/VALIDATION.md, below PySPH's 3.3e-4 and 1.1e-3; measured 4.1e-5 and 1.3e-4) */
    ENSURE(sqrt(rms2 / samples) < 2e-4 * u_ref);
    ENSURE(largest < 1e-3 * u_ref);
    /* 1 %: the acceptance figure; the bottom layer reads +0.75 % (its kernel cut by the floor, made up by images) */
    ENSURE_NEAR(floor_pressure, rho_g_h, 0.01 * rho_g_h);
    sps_world_destroy(w);
    return 0;
}

/* Water that churns speaks: the tank at rest at h = 1.3 dp (depth/dp 15, 0.3 m wide) on the
   square lattice bursts at about 3.5 s (its rows slide), and the churn watch names the body and
   the lattice before 5 s; on the hexagonal lattice (the default at 1.3) and on the square one at
   h = 2 dp it does not churn over the same 5 s, and the watch stays quiet. */
static int g_churns;
static char g_churn_message[1024];
static void churn_log(int level, const char* message, void* user) {
    (void)user;
    if (level == 1 && strstr(message, "churns at")) { ++g_churns; snprintf(g_churn_message, sizeof g_churn_message, "%s", message); }
}
static int churn_warnings(double h_over_dp, sps_lattice lattice) {
    sps_body water;
    sps_world* w = still_tank(0.3, 15, h_over_dp, lattice, churn_log, &water);
    g_churns = 0;
    if (!w) return -1;
    if (sps_world_advance(w, 5, NULL, NULL) != SPS_OK) { sps_world_destroy(w); return -1; }
    sps_world_destroy(w);
    return g_churns;
}
static int test_fluid_churn_warned(void) {
    ENSURE(churn_warnings(1.3, SPS_LATTICE_SQUARE) == 1);
    printf("    %s\n", g_churn_message);
    ENSURE(strstr(g_churn_message, "body 'body' churns") && strstr(g_churn_message, "hexagonal lattice")); /* the tank's body keeps the default name */
    ENSURE(churn_warnings(1.3, SPS_LATTICE_AUTO) == 0);
    ENSURE(churn_warnings(2, SPS_LATTICE_AUTO) == 0);
    return 0;
}

/* The square lattice's rows slide under hydrostatic pressure, the hexagonal lattice's do not: the
   tank at rest at h = 1.3 dp (depth/dp 15, 0.3 m wide), its largest particle speed over 3-4 s.
   1e-2 sqrt(g H): the hexagonal start's settling (its free surface and half particles are not
   quite in the balance the set pressure assumes) decays over seconds from about 4e-3 here,
   while the square lattice's sliding rows have grown from round-off past 2e-2 by then
   (bench/VALIDATION.md, "Water left running"). */
static double largest_speed_3_4(sps_lattice lattice) {
    sps_body water;
    sps_world* w = still_tank(0.3, 15, 1.3, lattice, quiet_log, &water);
    double largest = 0, mean_square, floor_pressure, sample;
    int k;
    if (!w) return -1;
    if (sps_world_advance(w, 3, NULL, NULL) != SPS_OK) { sps_world_destroy(w); return -1; }
    for (k = 1; k <= 10; ++k) {
        if (sps_world_advance(w, (sps_real)(3 + 0.1 * k), NULL, NULL) != SPS_OK) { sps_world_destroy(w); return -1; }
        still_tank_state(w, level_05 / 15, &mean_square, &sample, &floor_pressure);
        if (sample > largest) largest = sample;
    }
    sps_world_destroy(w);
    return largest;
}
static int test_fluid_hexagonal_rest(void) {
    const double v_ref = sqrt(9.81 * level_05), hexagonal = largest_speed_3_4(SPS_LATTICE_AUTO), square = largest_speed_3_4(SPS_LATTICE_SQUARE);
    printf("    largest speed over 3-4 s: hexagonal %.2e, square %.2e sqrt(g H)\n", hexagonal / v_ref, square / v_ref);
    ENSURE(hexagonal >= 0 && hexagonal < 1e-2 * v_ref);
    ENSURE(square > 1e-2 * v_ref);
    return 0;
}

/* The hexagonal fill tiles its box: the particles' volumes sum to the box's area, the shifted
   rows end in half particles a quarter spacing inside the x faces, the first row stands half a
   row spacing above the floor, no two particles are closer than a spacing along the row allows;
   a box spanning a periodic x axis gets whole rows; 3D is refused by name. */
static int test_fluid_hexagonal_fill(void) {
    const double dp = 0.02, width = 0.5, height = 0.3;
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body water;
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)width, (sps_real)height, 0};
    double area = 0, nearest_x = 1, nearest_y = 1, closest = 1;
    int i, j, n, added = 0, periodic;
    wd.dim = 2; wd.dp = (sps_real)dp; wd.threads = 1; wd.log = quiet_log; wd.gravity[1] = -9.81;
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 20;
    bd.lattice = SPS_LATTICE_HEXAGONAL;
    for (periodic = 0; periodic < 2; ++periodic) {
        const sps_real *x, *y, *m;
        wd.periodic[0] = periodic ? (sps_real)width : 0;
        ENSURE(sps_world_create(&wd, &w) == SPS_OK && sps_world_add_body(w, &bd, &water) == SPS_OK);
        ENSURE(sps_body_add_box(w, water, lo, hi, &added) == SPS_OK);
        x = sps_world_field(w, SPS_FIELD_POSITION_X); y = sps_world_field(w, SPS_FIELD_POSITION_Y); m = sps_world_field(w, SPS_FIELD_MASS);
        n = sps_world_particle_count(w);
        ENSURE(n == added);
        area = 0; nearest_x = nearest_y = closest = 1;
        for (i = 0; i < n; ++i) {
            area += m[i] / 1000;
            if (fmin(x[i], width - x[i]) < nearest_x) nearest_x = fmin(x[i], width - x[i]);
            if (fmin(y[i], height - y[i]) < nearest_y) nearest_y = fmin(y[i], height - y[i]);
            for (j = 0; j < i; ++j) {
                double dx = x[i] - x[j];
                if (periodic) dx -= width * floor(dx / width + 0.5);
                if (hypot(dx, y[i] - y[j]) < closest) closest = hypot(dx, y[i] - y[j]);
            }
        }
        printf("    %s: %d particles, area %.12f (box %.12f), nearest x face %.3f dp, y face %.3f dp, closest pair %.3f dp\n",
               periodic ? "periodic x" : "walls", n, area, width * height, nearest_x / dp, nearest_y / dp, closest / dp);
        ENSURE_NEAR(area, width * height, 1e-12); /* the volumes tile the box */
        /* a quarter of the row spacing dp sqrt(2 / sqrt 3) (0.269 dp), stretched to the width by the rounding of the count */
        if (!periodic) ENSURE(nearest_x > 0.26 * dp && nearest_x < 0.28 * dp);
        if (periodic) ENSURE(nearest_x < 1e-9); /* whole odd rows: one particle on the period's start */
        ENSURE(nearest_y > 0.45 * dp && nearest_y < 0.48 * dp); /* half a row spacing, sqrt(3)/2 of the row's */
        ENSURE(closest > (periodic ? 1.05 : 0.53) * dp); /* the half particles: half a spacing from their row's next */
        sps_world_destroy(w);
    }
    wd.dim = 3; wd.periodic[0] = 0;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK && sps_world_add_body(w, &bd, &water) == SPS_ERR_INVALID_ARG);
    ENSURE(strstr(sps_world_last_error(w), "lattice = 2 (hexagonal) in a 3D world"));
    sps_world_destroy(w);
    return 0;
}

/* Water under gravity on the square lattice at h_over_dp < 2, or on the hexagonal lattice above
   1.4, does not stay at rest: adding it says so, naming the setting; the default lattice at 1.3
   (hexagonal) and at 2 (square), or a world without gravity (no hydrostatic state to hold), say
   nothing. */
static int fluid_warnings_for(double h_over_dp, double gravity, sps_lattice lattice) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body water;
    wd.dim = 2; wd.dp = 0.02; wd.threads = 1; wd.log = warning_log;
    wd.h_over_dp = (sps_real)h_over_dp;
    wd.gravity[1] = (sps_real)-gravity;
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 20;
    bd.lattice = lattice;
    g_warnings = 0; g_warning_last[0] = 0;
    if (sps_world_create(&wd, &w) != SPS_OK) return -1;
    if (sps_world_add_body(w, &bd, &water) != SPS_OK) { sps_world_destroy(w); return -1; }
    sps_world_destroy(w);
    return g_warnings;
}
static int test_fluid_smoothing_warning(void) {
    ENSURE(fluid_warnings_for(1.3, 9.81, SPS_LATTICE_SQUARE) == 1);
    ENSURE(strstr(g_warning_last, "square lattice at h_over_dp = 1.3") && strstr(g_warning_last, "hexagonal lattice"));
    ENSURE(fluid_warnings_for(2, 9.81, SPS_LATTICE_HEXAGONAL) == 1);
    ENSURE(strstr(g_warning_last, "hexagonal lattice at h_over_dp = 2"));
    ENSURE(fluid_warnings_for(1.3, 9.81, SPS_LATTICE_AUTO) == 0);
    ENSURE(fluid_warnings_for(2, 9.81, SPS_LATTICE_AUTO) == 0);
    ENSURE(fluid_warnings_for(1.3, 0, SPS_LATTICE_AUTO) == 0);
    return 0;
}
/* A particle in a corner of two walls sees its images across both (FLUIDS): without the corner
   image it misses a quarter of its neighbours and is pulled into the corner (measured 53.6 m/s^2
   at h = 2 dp). Over the first 2 ms its acceleration stays that of its neighbours on the floor. */
static int test_fluid_corner_images(void) {
    sps_body water;
    sps_world* w = still_tank(0.5, 20, 2, SPS_LATTICE_AUTO, quiet_log, &water);
    const sps_real *x, *y, *u, *v;
    const double t = 0.002, dp = level_05 / 20;
    double corner = 0, floor_middle = 0;
    int i, n;
    ENSURE(w != NULL);
    ENSURE(sps_world_advance(w, (sps_real)t, NULL, NULL) == SPS_OK);
    x = sps_world_field(w, SPS_FIELD_POSITION_X);
    y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    u = sps_world_field(w, SPS_FIELD_VELOCITY_X);
    v = sps_world_field(w, SPS_FIELD_VELOCITY_Y);
    n = sps_world_particle_count(w);
    for (i = 0; i < n; ++i) {
        const double a = sqrt((double)u[i] * u[i] + (double)v[i] * v[i]) / t;
        if (y[i] < dp && (x[i] < dp || x[i] > 0.5 - dp) && a > corner) corner = a;
        if (y[i] < dp && fabs(x[i] - 0.25) < dp && a > floor_middle) floor_middle = a;
    }
    printf("    mean acceleration over the first %g s: corner particles %.3g m/s^2, mid-floor %.3g m/s^2\n", t, corner, floor_middle);
    /* 5 % of g: the start's hydrostatic imbalance on the lattice (corner and mid-floor both measured 0.21 m/s^2, 2 % of g) */
    ENSURE(corner < 0.05 * 9.81);
    sps_world_destroy(w);
    return 0;
}

/* Linear theory's velocity of a standing wave of amplitude 1 % of the depth as its surface passes
   through the level, in a tank 0.5 m deep; *user is its wavenumber k. */
static void standing_wave_velocity(const sps_real x[3], sps_real v[3], void* user) {
    const double k = *(const double*)user, omega = sqrt(9.81 * k * tanh(k * level_05));
    const double scale = 0.01 * level_05 * omega / sinh(k * level_05);
    v[0] = (sps_real)(-scale * cosh(k * x[1]) * sin(k * x[0]));
    v[1] = (sps_real)(scale * sinh(k * x[1]) * cos(k * x[0]));
    v[2] = 0;
}

/* The first sloshing mode of a tank (kh = 1, 10 layers, h = 2 dp, amplitude 1 % of the depth)
   runs at linear theory's period omega^2 = g k tanh(k H) (examples/standing_wave.c; bench/
   VALIDATION.md, "Still water"): the surface's first Fourier mode, started with the wave's
   velocity, crosses zero at half periods. At h = 1.3 dp the same wave runs 4.9 % fast (the
   lattice's unstable mode stiffens it; 17 % at 25 layers). */
static int test_standing_wave_period(void) {
    sps_body water;
    const int layers = 10;
    const double dp = level_05 / layers, length = dp * floor(PI / 1.0 * level_05 / dp + 0.5), k = PI / length;
    const double omega = sqrt(9.81 * k * tanh(k * level_05)), period = 2 * PI / omega;
    sps_world* w = still_tank(length, layers, 2, SPS_LATTICE_AUTO, quiet_log, &water);
    double crossings[8], previous = 0;
    int ncross = 0, step, i, n;
    ENSURE(w != NULL);
    ENSURE(sps_body_set_velocity(w, water, standing_wave_velocity, (void*)&k) == SPS_OK);
    n = sps_world_particle_count(w);
    for (step = 1; step <= 320 && ncross < 4; ++step) { /* 200 samples a period over 1.6 periods */
        const sps_real *x, *y;
        double mode = 0;
        int surface = 0;
        const double t = step * period / 200;
        ENSURE(sps_world_advance(w, (sps_real)t, NULL, NULL) == SPS_OK);
        x = sps_world_field(w, SPS_FIELD_POSITION_X);
        y = sps_world_field(w, SPS_FIELD_POSITION_Y);
        for (i = 0; i < n; ++i)
            if (y[i] > level_05 - dp) { mode += (y[i] - (level_05 - dp / 2)) * cos(k * x[i]); ++surface; } /* the top layer */
        mode /= surface;
        if (step > 1 && (mode > 0) != (previous > 0)) crossings[ncross++] = t - period / 200 * mode / (mode - previous);
        previous = mode;
    }
    ENSURE(ncross >= 3);
    printf("    period %.5f s, linear theory %.5f s (%+.2f %%)\n", crossings[2] - crossings[0], period, 100 * ((crossings[2] - crossings[0]) / period - 1));
    /* 2 %: 10 layers (measured -0.87 %; -0.74 % at 25 layers, the validation record's runs converge to theory) */
    ENSURE_NEAR(crossings[2] - crossings[0], period, 0.02 * period);
    sps_world_destroy(w);
    return 0;
}

/* ---- granular media (GRANULAR) ---- */

/* The C5 soil (rho0 1850, E 1.8 MPa, nu 0.3, c 5 kPa, phi 25 deg). */
static sps_material_def c5_soil(void) {
    sps_material_def m = sps_default_material_def();
    m.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    m.density = 1850;
    m.youngs_modulus = 1.8e6;
    m.poisson_ratio = 0.3;
    m.granular.cohesion = 5e3;
    m.granular.friction_angle = 25;
    return m;
}

/* f = alpha_phi I1 + sqrt(J2) - k_c of a stress (xx xy xz yy yz zz) on the cone of m. */
static double yield_function(const sps_real s[6], const sps_material_def* m) {
    const sps__yield_cone c = sps__yield_cone_of(m);
    const double i1 = (double)(s[0] + s[3] + s[5]);
    sps_real dev[6];
    int a;
    for (a = 0; a < 6; ++a) dev[a] = (sps_real)(s[a] - (a == 0 || a == 3 || a == 5 ? i1 / 3 : 0));
    return (double)c.alpha_phi * i1 + sqrt(0.5 * (double)sps__sym_contract(dev, dev)) - (double)c.k_c;
}

/* The Drucker-Prager return mapping puts a trial outside the cone onto it (f = 0), keeps the
   direction of its deviator, leaves a trial inside alone, and moves a tensile trial beyond the
   apex to the apex (I1 = k_c / alpha_phi, zero deviator). Random trials, with and without
   cohesion. */
static int test_drucker_prager_return_on_cone(void) {
    unsigned long long seed = 5;
    int k, a, outside = 0, inside = 0, apex = 0;
    for (k = 0; k < 400; ++k) {
        sps_material_def m = c5_soil();
        sps__yield_cone c;
        sps_real t[6], before[6];
        double scale = (k % 4 + 0.2) * 2e4, f0, i1, dev_before[6], dev_after[6], ratio = 0;
        if (k % 3 == 0) m.granular.cohesion = 0;
        c = sps__yield_cone_of(&m);
        for (a = 0; a < 6; ++a) before[a] = t[a] = (sps_real)(scale * rnd(&seed));
        f0 = yield_function(t, &m);
        i1 = (double)(t[0] + t[3] + t[5]);
        sps__drucker_prager_return(t, &c);
        if (f0 <= 0) { /* inside: untouched, up to the roundings of taking the mean out and back in */
            for (a = 0; a < 6; ++a) ENSURE_NEAR(t[a], before[a], 1e-15 * 4 * scale);
            ++inside;
            continue;
        }
        /* on the cone: f = 0 up to roundings of stresses of scale 1e5 Pa */
        ENSURE(fabs(yield_function(t, &m)) < 1e-9 * scale);
        if (c.alpha_phi > 0 && i1 > (double)(c.k_c / c.alpha_phi)) { /* beyond the apex: at the apex */
            ENSURE_NEAR(t[0] + t[3] + t[5], c.k_c / c.alpha_phi, 1e-12 * scale);
            ENSURE(fabs((double)(t[1])) < 1e-9 * scale && fabs((double)(t[0] - t[3])) < 1e-9 * scale);
            ++apex;
            continue;
        }
        for (a = 0; a < 6; ++a) { /* the deviator scaled, not turned */
            const int d = a == 0 || a == 3 || a == 5;
            dev_before[a] = (double)before[a] - (d ? i1 / 3 : 0);
            dev_after[a] = (double)t[a] - (d ? i1 / 3 : 0);
            if (fabs(dev_before[a]) > fabs(ratio * dev_before[a]) && fabs(dev_before[a]) > 1e-3 * scale) ratio = dev_after[a] / dev_before[a];
        }
        ENSURE(ratio > 0 && ratio < 1);
        for (a = 0; a < 6; ++a) ENSURE_NEAR(dev_after[a], ratio * dev_before[a], 1e-12 * scale);
        ENSURE_NEAR(t[0] + t[3] + t[5], i1, 1e-12 * scale); /* the mean stress kept */
        ++outside;
    }
    ENSURE(outside > 20 && inside > 20 && apex > 20); /* the random trials reached all three cases */
    return 0;
}

/* A principal stress state (s1, s2, s3 on the diagonal) as the stress vector xx xy xz yy yz zz. */
static void principal_stress(double s1, double s2, double s3, sps_real s[6]) {
    s[0] = (sps_real)s1; s[1] = 0; s[2] = 0; s[3] = (sps_real)s2; s[4] = 0; s[5] = (sps_real)s3;
}

/* Each cone of material.granular.yield_cone meets Mohr-Coulomb where it says it does (tension positive,
   Mohr's circle of centre p_m and radius t = c cos phi - p_m sin phi on the Coulomb line):
   plane strain, with the out-of-plane stress that the potential's flow leaves at zero strain
   (d g / d sigma_zz = 0); the compression cone at triaxial compression (the axial stress the
   most compressive, the two lateral equal), the extension cone at triaxial extension, the
   compromise cone between the two; the papers' cone is UTVF eq. 14 (tan phi / sqrt(9 + 12 tan^2
   phi), which with psi = 0 acts in plane strain as asin(3 alpha_phi): 28.7 degrees for 30). */
static int test_drucker_prager_cones_match_mohr_coulomb(void) {
    const double deg = 3.14159265358979323846 / 180, phis[3] = {20, 30, 40}, cohesions[2] = {0, 5e3};
    int i, j, k;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 2; ++j)
            for (k = 0; k < 3; ++k) {
                sps_material_def m = c5_soil();
                const double phi = phis[i] * deg, sin_phi = sin(phi), p_m = -2e4 * (k + 1), t = cohesions[j] * cos(phi) - p_m * sin_phi;
                const double scale = fabs(p_m) + t; /* the stresses' size: the tolerances are roundings of it */
                sps_real s[6];
                sps__yield_cone c;
                double a, d, sqrt_j2;
                m.granular.friction_angle = (sps_real)phis[i];
                m.granular.cohesion = (sps_real)cohesions[j];
                m.granular.dilatancy_angle = (sps_real)(k == 2 ? phis[i] : k * 10); /* psi 0, 10 and phi (associated) */
                m.granular.yield_cone = SPS_CONE_PLANE_STRAIN;
                c = sps__yield_cone_of(&m);
                a = (double)c.alpha_psi;
                d = -3 * a * t / sqrt(1 - 3 * a * a); /* sigma_zz - p_m at zero out-of-plane plastic strain */
                principal_stress(p_m + t, p_m - t, p_m + d, s);
                sqrt_j2 = sqrt(d * d / 3 + t * t);
                ENSURE_NEAR(a + (2 * d / 3) / (2 * sqrt_j2), 0, 1e-12); /* no flow out of the plane */
                ENSURE(fabs(yield_function(s, &m)) < 1e-12 * scale);
                m.granular.yield_cone = SPS_CONE_COMPRESSION; /* s3 axial; the lateral p_m + t twice */
                principal_stress(p_m + t, p_m + t, p_m - t, s);
                ENSURE(fabs(yield_function(s, &m)) < 1e-12 * scale);
                m.granular.yield_cone = SPS_CONE_COMPROMISE; /* outside it at compression ... */
                ENSURE(yield_function(s, &m) > 1e-3 * scale);
                m.granular.yield_cone = SPS_CONE_EXTENSION; /* s1 axial; the lateral p_m - t twice */
                principal_stress(p_m + t, p_m - t, p_m - t, s);
                ENSURE(fabs(yield_function(s, &m)) < 1e-12 * scale);
                m.granular.yield_cone = SPS_CONE_COMPROMISE; /* ... inside it at extension */
                ENSURE(yield_function(s, &m) < -1e-3 * scale);
            }
    {
        sps_material_def m = c5_soil();
        sps__yield_cone c;
        m.granular.friction_angle = 30;
        m.granular.yield_cone = SPS_CONE_PAPERS;
        c = sps__yield_cone_of(&m);
        ENSURE_NEAR(c.alpha_phi, tan(30 * deg) / sqrt(9 + 12 * tan(30 * deg) * tan(30 * deg)), 1e-15);
        ENSURE_NEAR(c.k_c, 3 * 5e3 / sqrt(9 + 12 * tan(30 * deg) * tan(30 * deg)), 1e-9);
        printf("    the papers' cone with psi = 0 acts in plane strain as phi = %.2f degrees for 30 (plane-strain cone: 30)\n",
               asin(3 * (double)c.alpha_phi) / deg);
        ENSURE_NEAR(asin(3 * (double)c.alpha_phi) / deg, 28.71, 0.01); /* the record's 28.7 */
    }
    return 0;
}

/* The infinite slope of examples/scenes/infinite_slope.h (phi 30, psi 0, the plane-strain cone,
   D/dp 20) to t = 1.5 s, 1 s after its ramp: the top rows' displacement along the slope [dp]. */
static double slope_displacement(double angle, sps_shear shear, int res) {
    slope_params p = {0, 30, 0, SPS_CONE_PLANE_STRAIN, 20, 0};
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body soil;
    double t_prev = 0, displacement = 0, speed = 0;
    p.angle = angle;
    p.res = res;
    wd.threads = 1;
    wd.log = quiet_log;
    wd.energy_growth_limit = (sps_real)INFINITY; /* the account holds no deviatoric strain energy (examples/infinite_slope.c) */
    bd.shear = shear;
    bd.material.density = SLOPE_RHO0;
    bd.material.youngs_modulus = (sps_real)SLOPE_E;
    bd.material.poisson_ratio = (sps_real)SLOPE_NU;
    bd.material.granular.stress_diffusion = (sps_real)0.1;
    if (slope_create(&p, &wd, &bd, &w, &soil) != SPS_OK) { sps_world_destroy(w); return NAN; }
    while (sps_world_time(w) < 1.5 - 1e-9) {
        if (sps_world_step(w) != SPS_OK) { sps_world_destroy(w); return NAN; }
        slope_track(w, &t_prev, &displacement, &speed);
    }
    sps_world_destroy(w);
    return displacement / (SLOPE_DEPTH / p.res);
}

/* An infinite slope of cohesionless soil with psi = 0 fails in simple shear at tan(theta) =
   sin(phi) (Davis 1968; 26.6 degrees for phi 30), which the plane-strain cone reproduces: at 0.8
   phi (24 degrees) the layer stands (its top moves less than 1 dp in the second after the ramp;
   measured 0.27 dp: the contained yielding of the K0 start, then creep), at 1.2 phi (36) it flows
   (measured hundreds of dp). */
static int test_granular_infinite_slope_stands_and_flows(void) {
    const double stands = slope_displacement(24, SPS_SHEAR_OG, 20), flows = slope_displacement(36, SPS_SHEAR_OG, 20);
    printf("    top displacement after the ramp: %.3g dp at 24 degrees, %.3g dp at 36 (limit %.2f degrees)\n", stands, flows,
           slope_limit_angle(30, 0));
    ENSURE(stands < 1);  /* the criterion: below 1 dp */
    ENSURE(flows > 10);  /* flowing: an accelerating layer, far past the creep of a standing one */
    return 0;
}

/* The floor holds a slope by its images' shear, continued across the wall by equilibrium with
   the body force (sphsolid.h, >>walls for fluids, the granular images' shear): with the GNO
   penalty a layer at 20 degrees (D/dp 10) stands. With the images carrying their particle's own
   shear (no gradient across the floor) its floor row slid: 8.8 dp in the second after the ramp,
   every row at 0.04 m/s; measured now 0.06 dp. */
static int test_granular_slope_floor_holds(void) {
    const double moved = slope_displacement(20, SPS_SHEAR_GNO, 10);
    printf("    GNO layer at 20 degrees, D/dp 10: the top moved %.3g dp after the ramp\n", moved);
    ENSURE(moved < 1); /* the criterion for a layer below its limit angle */
    return 0;
}

/* The granular limiter (eta = 20 d) dissipates between approaching particles only: beta = 0
   for every separating pair (u = v_ij . e_ij >= 0), 1 from an approach of c0 / eta on, linear
   between. */
static int test_granular_limiter_off_in_expansion(void) {
    const double c0 = 28.5, eta = 20 * 2;
    int k;
    for (k = -100; k <= 100; ++k) {
        const double u = k * 0.01 * c0 / 10, beta = (double)sps__riemann_limiter((sps_real)u, (sps_real)(eta / c0));
        if (u >= 0) ENSURE(beta == 0);
        else ENSURE_NEAR(beta, fmin(-eta * u / c0, 1), 1e-15);
    }
    return 0;
}

/* A block of cohesive soil (C5's), 2 m wide and 1 m deep, in a box of no-slip walls under
   gravity, started from its geostatic stress, with the given shear formulation, run to t_end:
   its diagnostics and the mean vertical stress of the particles at mid-depth. */
typedef struct granular_block {
    sps_diagnostics d;
    double sigma_mid; /* [Pa] */
} granular_block;
#define GRANULAR_BLOCK_G 9.8
#define GRANULAR_BLOCK_DEPTH 1.0
#define GRANULAR_BLOCK_RHO0 1850.0
static int granular_block_run(sps_shear shear, double t_end, granular_block* out) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body soil, all = {0};
    sps_real lo[3] = {0, 0, 0}, hi[3] = {2, GRANULAR_BLOCK_DEPTH, 0}, box_hi[3] = {2, 2, 0};
    const double dp = 0.05;
    const sps_real *y, *p, *tau;
    double sigma_mid = 0;
    int i, n, first, mid = 0;
    wd.dim = 2;
    wd.dp = dp;
    wd.threads = 1;
    wd.gravity[1] = -GRANULAR_BLOCK_G;
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.material = c5_soil();
    bd.shear = shear;
    ENSURE(sps_world_add_box_walls(w, lo, box_hi, SPS_FACE_Y_HI, SPS_WALL_NO_SLIP) == SPS_OK);
    ENSURE(sps_world_add_body(w, &bd, &soil) == SPS_OK);
    ENSURE(sps_body_add_box(w, soil, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_set_geostatic_stress(w, soil, (sps_real)GRANULAR_BLOCK_DEPTH, 0) == SPS_OK);
    ENSURE(sps_world_advance(w, (sps_real)t_end, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, all, &out->d) == SPS_OK);
    y = sps_world_field(w, SPS_FIELD_POSITION_Y);
    p = sps_world_field(w, SPS_FIELD_PRESSURE);
    tau = sps_body_field(w, soil, "shear_stress", NULL, &first, &n);
    ENSURE(tau && first == 0 && n == sps_world_particle_count(w)); /* the only body */
    for (i = 0; i < n; ++i)
        if (fabs(y[i] - GRANULAR_BLOCK_DEPTH / 2) < 0.6 * dp) { sigma_mid += tau[6 * i + 3] - p[i]; ++mid; }
    ENSURE(mid > 0);
    out->sigma_mid = sigma_mid / mid;
    sps_world_destroy(w);
    return 0;
}

/* The block of granular_block_run (the default formulation: the granular stress divergence)
   stays at rest: the vertical stress at mid-depth stays -rho0 g H/2 and no particle moves. */
static int test_granular_block_at_rest(void) {
    const double g = GRANULAR_BLOCK_G, depth = GRANULAR_BLOCK_DEPTH, rho0 = GRANULAR_BLOCK_RHO0, v_ref = sqrt(2 * g * depth);
    granular_block r;
    if (granular_block_run(sps_default_body_def().shear, 0.5, &r)) return 1; /* about 14 crossings of the block by sound */
    printf("    mid-depth vertical stress %.1f Pa (geostatic %.1f), max speed %.3g m/s (%.2g sqrt(2 g H)), max plastic strain %.3g\n",
           r.sigma_mid, -rho0 * g * depth / 2, (double)r.d.max_speed, (double)r.d.max_speed / v_ref, (double)r.d.max_plastic_strain);
    /* 5 % ("a few percent"; measured +0.7 %, 3.7 % before the divergence's lattice scale;
       test_granular_block_holds_shape holds 2 % over 2 s) */
    ENSURE_NEAR(r.sigma_mid, -rho0 * g * depth / 2, 0.05 * rho0 * g * depth / 2);
    /* 1 % of the speed a fall from the surface gives: at rest (measured 0.55 %, the zigzag mode) */
    ENSURE(r.d.max_speed < 0.01 * v_ref);
    return 0;
}

/* Bad granular input is refused with a message naming the field, its value and the range. */
static int test_granular_bad_input(void) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def d = sps_default_body_def(), bad;
    ENSURE(w);
    d.material = c5_soil();
    bad = d; bad.material.granular.cohesion = -1;         ENSURE(rejects_body_def(w, &bad, "material.granular.cohesion = -1") == 0);
    bad = d; bad.material.granular.friction_angle = 90;   ENSURE(rejects_body_def(w, &bad, "material.granular.friction_angle = 90") == 0);
    bad = d; bad.material.granular.dilatancy_angle = 30;  ENSURE(rejects_body_def(w, &bad, "material.granular.dilatancy_angle = 30") == 0);
    bad = d; bad.material.granular.stress_diffusion = 2;           ENSURE(rejects_body_def(w, &bad, "material.granular.stress_diffusion = 2") == 0);
    bad = d; bad.shear = SPS_SHEAR_GNO_A; bad.rotation = SPS_ROTATION_PAIR;
    ENSURE(rejects_body_def(w, &bad, "rotation = pair") == 0);
    ENSURE(sps_body_set_geostatic_stress(w, (sps_body){0}, 1, 0) == SPS_ERR_INVALID_ARG);
    { /* a soil body in a world without gravity, and an elastic one: both refused, with the reason */
        sps_body soil, plate;
        sps_body_def elastic = sps_default_body_def();
        const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
        ENSURE(sps_world_add_body(w, &d, &soil) == SPS_OK && sps_body_add_box(w, soil, lo, hi, NULL) == SPS_OK);
        ENSURE(sps_world_add_body(w, &elastic, &plate) == SPS_OK && sps_body_add_box(w, plate, lo, hi, NULL) == SPS_OK);
        ENSURE(sps_body_set_geostatic_stress(w, soil, 1, 0) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "gravity"));
        ENSURE(sps_body_set_geostatic_stress(w, plate, 1, 0) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "material.kind"));
    }
    sps_world_destroy(w);
    return 0;
}

/* Two particles at one point (a cluster collapsed by tensile instability within an advection
   step: the neighbour search leaves such pairs out, the pair geometry of the sub-steps meets
   them) have no direction between them: the pair is taken as a padding slot is, e = 0 and
   dW = 0 (it was 0/0, a NaN, and stopped the C7 flume), and the diagnostics stay finite. */
static int test_coincident_particles_stay_finite(void) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def bd = sps_default_body_def();
    sps_body b, all = {0};
    sps_diagnostics d;
    const sps_real twins[6] = {0.02, 0.03, 0, 0.02, 0.03, 0};
    sps__pair_geometry e;
    ENSURE(w);
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK);
    ENSURE(sps_body_add_particles(w, b, 2, twins, NULL) == SPS_OK);
    e = sps__pair(w, 0, 0, 1, 2, SPS__GEO_WENDLAND);
    ENSURE(e.ex == 0 && e.ey == 0 && e.ez == 0 && e.dw == 0 && e.dw_r == 0 && sps__finite(e.r));
    ENSURE(sps_world_diagnostics(w, all, &d) == SPS_OK);
    ENSURE(sps__finite(d.hourglass));
    sps_world_destroy(w);
    return 0;
}

static void swirl(const sps_real x[3], sps_real v[3], void* user) {
    (void)user;
    v[0] = (sps_real)(3 * sin(7 * x[1]) + 1);
    v[1] = (sps_real)(2 * cos(5 * x[0]) - x[0]);
}

/* A fluid block in a swirling flow with TVF and with UTVF (and an elastic one with UTVF): the
   corrections move particles but not their velocities, so linear momentum is kept to round-off. */
static int test_transport_keeps_linear_momentum(void) {
    static const int kinds[3][2] = {{SPS_MATERIAL_FLUID, SPS_TRANSPORT_TVF}, {SPS_MATERIAL_FLUID, SPS_TRANSPORT_UTVF},
                                    {SPS_MATERIAL_ELASTIC, SPS_TRANSPORT_UTVF}};
    int k;
    for (k = 0; k < 3; ++k) {
        double moved = 0, scale = 0, dP = 0;
        int pass, i, a, n = 0;
        sps_real* before = NULL;
        for (pass = 0; pass < 2; ++pass) { /* without, then with the correction */
            sps_world* w = new_world(2, 0.05);
            sps_body_def bd = sps_default_body_def();
            sps_body b, all = {0};
            sps_diagnostics d0, d1;
            sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 0.6, 0};
            const sps_real* x;
            ENSURE(w);
            bd.material.kind = (sps_material_kind)kinds[k][0];
            bd.material.fluid.sound_speed = 100;
            bd.transport = pass ? (sps_transport)kinds[k][1] : SPS_TRANSPORT_NONE;
            ENSURE(sps_world_add_body(w, &bd, &b) == SPS_OK);
            ENSURE(sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
            ENSURE(sps_body_set_velocity(w, b, swirl, NULL) == SPS_OK);
            ENSURE(sps_world_diagnostics(w, all, &d0) == SPS_OK);
            ENSURE(sps_world_advance(w, 0.02, NULL, NULL) == SPS_OK);
            ENSURE(sps_world_diagnostics(w, all, &d1) == SPS_OK);
            n = sps_world_particle_count(w);
            x = sps_world_field(w, SPS_FIELD_POSITION_X);
            if (!pass) {
                before = (sps_real*)malloc(sizeof(sps_real) * (size_t)n);
                ENSURE(before);
                memcpy(before, x, sizeof(sps_real) * (size_t)n);
            } else {
                const sps_real* m = sps_world_field(w, SPS_FIELD_MASS);
                for (i = 0; i < n; ++i) {
                    moved = fmax(moved, fabs(x[i] - before[i]));
                    scale += m[i] * 4;
                }
                for (a = 0; a < 2; ++a) dP = fmax(dP, fabs(d1.linear_momentum[a] - d0.linear_momentum[a]));
            }
            sps_world_destroy(w);
        }
        free(before);
        printf("    %s + %s: largest shift %.3g dp, momentum change %.2g of sum m |v|\n", kinds[k][0] ? "fluid" : "elastic",
               kinds[k][1] == SPS_TRANSPORT_TVF ? "TVF" : "UTVF", moved / 0.05, dP / scale);
        ENSURE(moved > 1e-6 * 0.05); /* the correction did move particles */
        ENSURE(dP < 1e-12 * scale);  /* round-off of a sum of ~240 momenta */
    }
    return 0;
}

/* TVF next to a wall (>>transport): the walls' images complete the sums, so a particle of the
   first layer pushed 0.2 dp towards a no-slip wall is shifted back from it, where the sums over
   the body alone took it (and the second layer) for the free surface and left it. A fluid at
   rest in a closed box without gravity, one acoustic sub-step with and one without TVF from the same state:
   the pressure pushes the particle back alike in both, the difference is TVF's. */
static double tvf_wall_distance(sps_transport transport) {
    const double dp = 0.01;
    sps_world* w = new_world(2, dp);
    sps_body_def bd = sps_default_body_def();
    sps_body b;
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.2, 0}, near[3] = {0.1, (sps_real)(dp / 2), 0};
    sps_particle_state p;
    double y;
    int id;
    if (!w) return -1;
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 10;
    bd.material.viscosity = 0.1;
    bd.transport = transport;
    if (sps_world_add_body(w, &bd, &b) != SPS_OK || sps_body_add_box(w, b, lo, hi, NULL) != SPS_OK ||
        sps_world_add_box_walls(w, lo, hi, 0, SPS_WALL_NO_SLIP) != SPS_OK || (id = sps_world_nearest_particle(w, b, near)) < 0 ||
        sps_world_particle(w, id, &p) != SPS_OK) {
        sps_world_destroy(w);
        return -1;
    }
    p.position[1] -= (sps_real)(0.2 * dp);
    if (sps_world_set_particle(w, id, p.position, NULL) != SPS_OK || sps_world_advance_substeps(w, 1, 0, NULL) != SPS_OK || sps_world_particle(w, id, &p) != SPS_OK) {
        sps_world_destroy(w);
        return -1;
    }
    y = p.position[1];
    sps_world_destroy(w);
    return y / dp;
}
static int test_tvf_counts_walls(void) {
    const double none = tvf_wall_distance(SPS_TRANSPORT_NONE), tvf = tvf_wall_distance(SPS_TRANSPORT_TVF);
    printf("    first-layer particle 0.3 dp from the wall after one sub-step: %.4f dp without TVF, %.4f dp with\n", none, tvf);
    ENSURE(none > 0 && tvf > 0);
    ENSURE(tvf > none + 0.01); /* TVF's shift back towards dp/2 (0.2 dp away): at least 5 % of it in one step */
    return 0;
}

static sps_real crushing(const sps_real x[3], void* user) {
    (void)x, (void)user;
    return -2e9;
}

static int test_fluid_bad_input(void) {
    sps_world* w = new_world(2, 0.01);
    sps_body_def d = sps_default_body_def(), bad;
    sps_body b;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.05, 0.05, 0};
    ENSURE(w);
    d.material.kind = SPS_MATERIAL_FLUID;
    d.material.fluid.sound_speed = 10;
    bad = d; bad.material.fluid.sound_speed = 0;    ENSURE(rejects_body_def(w, &bad, "material.fluid.sound_speed = 0") == 0);
    bad = d; bad.material.fluid.sound_speed = NAN;  ENSURE(rejects_body_def(w, &bad, "material.fluid.sound_speed = nan") == 0);
    bad = d; bad.material.viscosity = -1;     ENSURE(rejects_body_def(w, &bad, "material.viscosity = -1") == 0);
    bad = d; bad.material.density = 0;        ENSURE(rejects_body_def(w, &bad, "material.density = 0") == 0);
    bad = d; bad.transport = (sps_transport)7; ENSURE(rejects_body_def(w, &bad, "transport = 7") == 0);
    bad = d; bad.transport_coefficient = 2;   ENSURE(rejects_body_def(w, &bad, "transport_coefficient = 2") == 0);
    bad = sps_default_body_def(); bad.material.kind = SPS_MATERIAL_RIGID; bad.transport = SPS_TRANSPORT_UTVF;
    ENSURE(rejects_body_def(w, &bad, "transport = TVF or UTVF with material.kind = rigid") == 0);
    ENSURE(sps_world_add_body(w, &d, &b) == SPS_OK);
    ENSURE(sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_set_pressure(w, b, crushing, NULL) == SPS_ERR_INVALID_ARG); /* K = 1e5 Pa: rho would be negative */
    ENSURE(strstr(sps_world_last_error(w), "pressure = -2e+09 Pa") != NULL);
    ENSURE(sps_body_set_pressure(w, b, NULL, NULL) == SPS_ERR_INVALID_ARG);
    sps_world_destroy(w);
    return 0;
}

/* ---- fluid-structure coupling (chapter >>coupling: fluid-structure) ---- */

/* Adds the lattice of [x0, x1] x [y0, y1] to body b (2D). */
static int fsi_box(sps_world* w, sps_body b, double x0, double y0, double x1, double y1) {
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    lo[0] = (sps_real)x0; lo[1] = (sps_real)y0; hi[0] = (sps_real)x1; hi[1] = (sps_real)y1;
    return sps_body_add_box(w, b, lo, hi, NULL) == SPS_OK;
}

/* A 2D world with gravity g (downwards) and the tests' quiet log. */
static sps_world* fsi_world(double dp, double g, int threads) {
    sps_world_def wd = sps_default_world_def();
    sps_world* w = NULL;
    wd.dim = 2; wd.dp = (sps_real)dp; wd.threads = threads; wd.gravity[1] = (sps_real)-g; wd.log = quiet_log;
    return sps_world_create(&wd, &w) == SPS_OK ? w : NULL;
}

/* The coupling tests' water: on the square lattice, which tiles the boxes filled round a solid
   flush and stands dp/2 from the solid's surface (the hexagonal lattice's half particles stand
   0.27 dp from a box face, and the rows of two boxes do not meet: bench/VALIDATION.md, "Water
   left running", measures it in the U-tank). */
static sps_body_def fsi_water(double c0) {
    sps_body_def bd = sps_default_body_def();
    bd.name = "water";
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = (sps_real)c0;
    bd.lattice = SPS_LATTICE_SQUARE;
    return bd;
}

/* A water block at 0.1 c0 hits an elastic block at rest (no gravity, no walls): linear momentum
   is exact (each pair's force is computed once per side from the same values), the solid is
   pushed, no water gets nearer a solid particle than dp/2, and 1 and 2 threads agree bit for bit. */
static sps_world* fsi_collision(int threads, sps_body* water, sps_body* block) {
    sps_world* w = fsi_world(0.01, 0, threads);
    sps_body_def wd = fsi_water(20), sd = sps_default_body_def();
    sps_real v = 2;
    if (!w) return NULL;
    sd.name = "block";
    sd.material.density = 1000;
    sd.material.youngs_modulus = 1e6;
    if (sps_world_add_body(w, &wd, water) != SPS_OK || !fsi_box(w, *water, 0, 0, 0.2, 0.2) ||
        sps_body_set_velocity(w, *water, velocity_x, &v) != SPS_OK || sps_world_add_body(w, &sd, block) != SPS_OK ||
        !fsi_box(w, *block, 0.23, 0.05, 0.33, 0.15)) {
        sps_world_destroy(w);
        return NULL;
    }
    return w;
}
static int test_coupling_momentum(void) {
    sps_body water, block, water2, block2;
    sps_world *w = fsi_collision(1, &water, &block), *w2 = fsi_collision(2, &water2, &block2);
    sps_diagnostics d0, d1, db;
    double scale, gap = 1e30, *s1, *s2;
    int same;
    ENSURE(w && w2);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d0) == SPS_OK);
    scale = fabs((double)d0.linear_momentum[0]);
    ENSURE(sps_world_advance(w, 0.04, track_gap, &gap) == SPS_OK); /* the water arrives at 0.015 s */
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d1) == SPS_OK && sps_world_diagnostics(w, block, &db) == SPS_OK);
    printf("    momentum x %.6g -> %.6g (block %.4g), y %.3g; smallest gap %.3f dp\n", (double)d0.linear_momentum[0],
           (double)d1.linear_momentum[0], (double)db.linear_momentum[0], (double)d1.linear_momentum[1], gap);
    ENSURE_NEAR(d1.linear_momentum[0], d0.linear_momentum[0], 1e-12 * scale); /* round-off of sums of ~1e5 pair forces */
    ENSURE_NEAR(d1.linear_momentum[1], d0.linear_momentum[1], 1e-12 * scale);
    ENSURE(db.linear_momentum[0] > 0.05 * scale); /* the water pushed the block (measured 0.105) */
    ENSURE(gap > 0.5);                            /* the wall images keep the water off the solid (measured 1.14) */
    ENSURE(sps_world_advance(w2, 0.04, NULL, NULL) == SPS_OK);
    s1 = snapshot(w); s2 = snapshot(w2);
    ENSURE(s1 && s2);
    same = memcmp(s1, s2, sizeof(double) * 6 * (size_t)sps_world_particle_count(w)) == 0;
    free(s1); free(s2);
    sps_world_destroy(w); sps_world_destroy(w2);
    ENSURE(same);
    return 0;
}

/* Water 0.4 m deep at rest in a U-shaped tank that is a rigid body (no analytic walls), filled
   up to the tank on the lattice and started hydrostatic: no first-step kick, the first layer
   stays dp/2 from the solid's surface (dp from its surface particles) at the floor and at the
   wall, the mid-depth pressure stays that of the column and no current builds up. */
static int test_coupling_hydrostatic_rest(void) {
    const double dp = 0.02, depth = 0.4, width = 0.4, t = 3 * dp, g = 9.81, v_ref = sqrt(2 * g * depth);
    sps_world* w = fsi_world(dp, g, 1);
    sps_body_def wd = fsi_water(10 * v_ref), td = sps_default_body_def();
    sps_body water, tank;
    sps_diagnostics d;
    const sps_real *x, *y, *p;
    double floor_gap = 0, wall_gap = 0, p_mid = 0, first_speed;
    int i, first, count, components, nf = 0, nw = 0, nm = 0;
    ENSURE(w);
    td.name = "tank";
    td.material.kind = SPS_MATERIAL_RIGID;
    ENSURE(sps_world_add_body(w, &wd, &water) == SPS_OK && fsi_box(w, water, 0, 0, width, depth));
    ENSURE(sps_body_set_pressure(w, water, water_at_rest, (void*)&level_04) == SPS_OK);
    ENSURE(sps_world_add_body(w, &td, &tank) == SPS_OK && fsi_box(w, tank, -t, -t, width + t, 0));
    ENSURE(fsi_box(w, tank, -t, 0, 0, 0.6) && fsi_box(w, tank, width, 0, width + t, 0.6));
    ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, water, &d) == SPS_OK);
    first_speed = (double)d.max_speed;
    ENSURE(sps_world_advance(w, 0.5, NULL, NULL) == SPS_OK); /* about 35 acoustic crossings of the column */
    ENSURE(sps_world_diagnostics(w, water, &d) == SPS_OK);
    ENSURE(sps_body_field(w, water, "density", &components, &first, &count) != NULL);
    x = sps_world_field(w, SPS_FIELD_POSITION_X); y = sps_world_field(w, SPS_FIELD_POSITION_Y); p = sps_world_field(w, SPS_FIELD_PRESSURE);
    for (i = first; i < first + count; ++i) {
        if (x[i] > 0.25 * width && x[i] < 0.75 * width && y[i] < dp) { floor_gap += y[i]; ++nf; } /* surface y = 0 */
        if (y[i] > 0.25 * depth && y[i] < 0.75 * depth && x[i] < dp) { wall_gap += x[i]; ++nw; } /* surface x = 0 */
        if (fabs(y[i] - depth / 2) < dp) { p_mid += p[i]; ++nm; }
    }
    ENSURE(nf > 0 && nw > 0 && nm > 0);
    floor_gap /= nf * dp; wall_gap /= nw * dp; p_mid /= nm;
    printf("    first step max speed %.3g m/s; first layer %.3f dp (floor), %.3f dp (wall) from the surface; mid-depth p %.1f Pa "
           "(column %.1f), max speed %.3g m/s (%.2g sqrt(2 g H))\n", first_speed, floor_gap, wall_gap, p_mid, 1000 * g * depth / 2,
           (double)d.max_speed, (double)d.max_speed / v_ref);
    ENSURE(first_speed < 0.005 * v_ref);      /* no kick (measured 0.25 %; the penalty threw a particle at 130 %) */
    ENSURE(fabs(floor_gap - 0.5) < 0.1);      /* a lattice's first layer sits dp/2 from the surface; +- 0.1 dp (measured 0.53) */
    ENSURE(fabs(wall_gap - 0.5) < 0.1);       /* (measured 0.51) */
    /* 4 %: the column rings after its start, at h = 1.3 dp (measured +3.3 %) */
    ENSURE_NEAR(p_mid, 1000 * g * depth / 2, 0.04 * 1000 * g * depth / 2);
    ENSURE(d.max_speed < 0.03 * v_ref);       /* no current: the ripple (measured 2.0 %) */
    sps_world_destroy(w);
    return 0;
}

/* The draft of block b (its mean height minus half its height `size`) below the water's level
   (the water's area at rho0 plus the block's part below the level fill the tank's width). */
static double fsi_draft(const sps_world* w, sps_body water, sps_body block, double size, double width) {
    const sps_real *y = sps_world_field(w, SPS_FIELD_POSITION_Y), *m = sps_world_field(w, SPS_FIELD_MASS);
    double bottom = 0, area = 0;
    int i, first, count, components;
    sps_body_field(w, block, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) bottom += y[i];
    bottom = bottom / count - 0.5 * size;
    sps_body_field(w, water, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) area += m[i] / 1000;
    return (area - size * bottom) / (width - size) - bottom; /* level (width - size) + size bottom = area */
}

/* An elastic block of density 600 starts where a block of density 500 floats (water filled
   round it on the lattice) and, damped (the block only), sinks to the draft Archimedes gives,
   0.6 of its height. */
static int test_coupling_floating_block(void) {
    const double dp = 0.02, width = 1, depth = 0.5, size = 0.2, draft0 = 0.5 * size, draft = 0.6 * size;
    sps_world* w = fsi_world(dp, 9.81, 1);
    sps_body_def wd = fsi_water(10 * sqrt(2 * 9.81 * depth)), bd = sps_default_body_def();
    sps_body water, block;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 2, 0};
    double mean = 0;
    int k;
    ENSURE(w);
    bd.name = "block";
    bd.material.density = 600;
    bd.material.youngs_modulus = 2e6;
    bd.damping = 10; /* about critical for its heave (DAMPING: the equilibrium does not depend on it) */
    ENSURE(sps_world_add_box_walls(w, lo, hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) == SPS_OK);
    ENSURE(sps_world_add_body(w, &wd, &water) == SPS_OK && fsi_box(w, water, 0, 0, width, depth - draft0));
    ENSURE(fsi_box(w, water, 0, depth - draft0, 0.4, depth) && fsi_box(w, water, 0.6, depth - draft0, width, depth));
    ENSURE(sps_body_set_pressure(w, water, water_at_rest, (void*)&level_05) == SPS_OK);
    ENSURE(sps_world_add_body(w, &bd, &block) == SPS_OK && fsi_box(w, block, 0.4, depth - draft0, 0.6, depth - draft0 + size));
    for (k = 1; k <= 10; ++k) { /* the mean over 0.8 .. 1 s */
        ENSURE(sps_world_advance(w, (sps_real)(0.8 + 0.02 * k), NULL, NULL) == SPS_OK);
        mean += fsi_draft(w, water, block, size, width) / 10;
    }
    printf("    draft %.4f m, Archimedes %.4f m (%+.2f %%)\n", mean, draft, 100 * (mean / draft - 1));
    ENSURE_NEAR(mean, draft, 0.03 * draft); /* 3 %: Archimedes within the kernel's surface layer (measured -1.1 %) */
    sps_world_destroy(w);
    return 0;
}

/* Added mass: a block 50 times lighter than water and soft (E = 4 kPa: its own sound speed 14
   m/s, the water's 20) dropped onto water stays finite: the coupling's signal speed c0_f
   sqrt(rho_f / rho_s) = 141 m/s shortens the time step (without it: a negative density within
   2 ms). */
static int test_coupling_light_soft_block(void) {
    sps_world* w = fsi_world(0.02, 9.81, 1);
    sps_body_def wd = fsi_water(20), bd = sps_default_body_def();
    sps_body water, block;
    sps_diagnostics d;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0.4, 1, 0};
    ENSURE(w);
    ENSURE(sps_world_add_box_walls(w, lo, hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) == SPS_OK);
    bd.name = "block";
    bd.material.density = 20;
    bd.material.youngs_modulus = 4e3;
    ENSURE(sps_world_add_body(w, &wd, &water) == SPS_OK && fsi_box(w, water, 0, 0, 0.4, 0.2));
    ENSURE(sps_world_add_body(w, &bd, &block) == SPS_OK && fsi_box(w, block, 0.1, 0.2, 0.3, 0.3));
    ENSURE(sps_world_advance(w, 0.03, NULL, NULL) == SPS_OK);
    ENSURE(sps_world_diagnostics(w, ALL_BODIES, &d) == SPS_OK);
    printf("    max speed %.3g m/s, density %.4g .. %.4g\n", (double)d.max_speed, (double)d.min_density, (double)d.max_density);
    ENSURE(d.max_speed < 1); /* finite and calm: a fall of 0.03 s reaches 0.3 m/s (measured 0.125 m/s) */
    sps_world_destroy(w);
    return 0;
}

/* A fluid and a solid that do not touch get a warning naming both: the water would flow through. */
static int test_coupling_bad_input(void) {
    sps_world* w = fsi_world(0.02, 9.81, 1);
    sps_body_def wd = fsi_water(20), sd = sps_default_body_def();
    sps_body water, plate;
    ENSURE(w);
    sd.name = "plate";
    ENSURE(sps_world_add_body(w, &wd, &water) == SPS_OK && fsi_box(w, water, 0, 0.1, 0.2, 0.3));
    ENSURE(sps_world_add_body(w, &sd, &plate) == SPS_OK && fsi_box(w, plate, 0, 0, 0.2, 0.1));
    ENSURE(sps_world_set_contact(w, water, plate, 0) == SPS_OK);
    g_log_count = 0;
    ENSURE(sps_world_step(w) == SPS_OK);
    printf("    %s\n", g_log_last);
    ENSURE(g_log_count > 0 && strstr(g_log_last, "'water' and 'plate'") && strstr(g_log_last, "flows through"));
    ENSURE(sps_world_set_contact(w, water, plate, 1) == SPS_OK); /* touching again: no warning */
    g_log_count = 0;
    ENSURE(sps_world_step(w) == SPS_OK);
    ENSURE(g_log_count == 0);
    sps_world_destroy(w);
    return 0;
}

/* ---- granular media that hold their shape (GRANULAR; chapter >>material: Drucker-Prager,
   >>walls for fluids) ---- */

/* A geostatic block at rest for 2 s keeps its shape with the GNO-A
   penalty (switched off on the cone): hourglass indicator below 0.005 and the mid-depth
   vertical stress within 2 % of rho0 g H/2. The paper's formulation (the default, no
   penalty) fails the first (measured 0.11 at 2 s: the zigzag mode grows under the load), so
   the test can fail. */
static int test_granular_block_holds_shape(void) {
    const double geostatic = -GRANULAR_BLOCK_RHO0 * GRANULAR_BLOCK_G * GRANULAR_BLOCK_DEPTH / 2;
    granular_block r;
    double hourglass, error;
    if (granular_block_run(SPS_SHEAR_GNO_A, 2, &r)) return 1;
    hourglass = (double)r.d.hourglass;
    error = r.sigma_mid / geostatic - 1;
    printf("    GNO-A: hourglass %.4f, mid-depth stress %+.2f %%\n", hourglass, 100 * error);
    ENSURE(hourglass < 0.005); /* 0.005: ten times below a visible zigzag (measured 0.0000) */
    ENSURE(fabs(error) < 0.02); /* 2 % of the weight (measured +0.5 %: the lattice scale leaves 0.7 % of weight to the surface layer) */
    if (granular_block_run(SPS_SHEAR_OG, 2, &r)) return 1;
    hourglass = (double)r.d.hourglass;
    printf("    OG (no penalty): hourglass %.4f, mid-depth stress %+.2f %%\n", hourglass, 100 * (r.sigma_mid / geostatic - 1));
    ENSURE(hourglass > 0.05); /* the zigzag mode the penalty removes grows without it (measured 0.11) */
    return 0;
}

/* The lattice's kernel-gradient moment that scales a granular body's stress divergence: the
   direct sum over a lattice patch (Wendland C2, h = 1.3 dp, 2D) is 0.974, not 1 (the
   continuum's value); and 1 within 1e-3 at h = 1.5 dp, where the lattice sum is near the
   integral (both from an independent sum of the kernel's closed form). */
static int test_granular_lattice_moment(void) {
    const double ratios[2] = {1.3, 1.5};
    int k;
    for (k = 0; k < 2; ++k) {
        sps_world_def wd = sps_default_world_def();
        sps_world* w = NULL;
        const double h = ratios[k], norm = 7 / (4 * 3.14159265358979323846 * h * h);
        double sum = 0;
        int a, b;
        wd.dim = 2;
        wd.dp = 1;
        wd.h_over_dp = (sps_real)h;
        wd.log = quiet_log;
        ENSURE(sps_world_create(&wd, &w) == SPS_OK);
        for (a = -4; a <= 4; ++a)
            for (b = -4; b <= 4; ++b) {
                const double r = sqrt((double)(a * a + b * b)), q = r / h, f = 1 - q / 2;
                if (r > 0 && q < 2) sum += r * (-5 * q * f * f * f) * norm / h; /* r dW/dr, V = dp^2 = 1 */
            }
        ENSURE_NEAR(sps__lattice_gradient_moment(w, 0), -sum / 2, 1e-12);
        if (k == 0) ENSURE_NEAR(-sum / 2, 0.974, 0.001);
        else ENSURE_NEAR(-sum / 2, 1, 0.003);
        sps_world_destroy(w);
    }
    return 0;
}

/* A grain (a cohesionless particle alone) sent at v0 = 0.5 m/s along a free-slip floor with
   wall friction mu = tan(20 degrees) stops by Coulomb's law against its weight, after
   v0^2 / (2 g mu) = 0.035 m (measured 0.0350 m); without the friction it slides on. */
static int test_granular_free_grain_stops(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body grain;
    const double dp = 0.002, g = 9.8, v0 = 0.5, phi = 20, expected = v0 * v0 / (2 * g * tan(phi * 3.14159265358979323846 / 180));
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {(sps_real)dp, (sps_real)dp, 0}, box_lo[3] = {-1, 0, 0}, box_hi[3] = {1, 1, 0};
    sps_particle_state st;
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.threads = 1;
    wd.gravity[1] = (sps_real)-g;
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.material.kind = SPS_MATERIAL_DRUCKER_PRAGER;
    bd.material.density = 2040;
    bd.material.youngs_modulus = (sps_real)5.84e6;
    bd.material.granular.cohesion = 0;
    bd.material.granular.friction_angle = (sps_real)phi;
    ENSURE(sps_world_add_box_walls(w, box_lo, box_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) == SPS_OK);
    ENSURE(sps_world_set_wall_friction(w, -1, (sps_real)tan(phi * 3.14159265358979323846 / 180)) == SPS_OK);
    ENSURE(sps_world_add_body(w, &bd, &grain) == SPS_OK);
    ENSURE(sps_body_add_box(w, grain, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_world_particle_count(w) == 1);
    ENSURE(sps_world_advance(w, (sps_real)0.05, NULL, NULL) == SPS_OK); /* settles on the floor */
    ENSURE(sps_world_particle(w, 0, &st) == SPS_OK);
    st.velocity[0] = (sps_real)v0;
    st.velocity[1] = 0;
    ENSURE(sps_world_set_particle(w, 0, st.position, st.velocity) == SPS_OK);
    {
        const double x0 = (double)st.position[0];
        ENSURE(sps_world_advance(w, (sps_real)0.5, NULL, NULL) == SPS_OK);
        ENSURE(sps_world_particle(w, 0, &st) == SPS_OK);
        printf("    slid %.4f m (Coulomb: %.4f m), speed at 0.45 s after the kick %.2g m/s\n", (double)st.position[0] - x0, expected,
               (double)st.velocity[0]);
        ENSURE(fabs((double)st.velocity[0]) < 1e-3); /* at rest: the stick drag holds it */
        /* 15 %: the floor's normal force is the image's push, within a few % of the weight once the grain sits */
        ENSURE_NEAR((double)st.position[0] - x0, expected, 0.15 * expected);
    }
    sps_world_destroy(w);
    return 0;
}

/* ---- fluid at rest over long times (chapter >>material: weakly compressible fluid) ---- */

/* The mean pressure c0^2 (mean rho - rho0) and the mid-depth pressure of the tank's water. */
static void tank_pressures(const sps_world* w, double c2, double depth, double dp, double* p_mean, double* p_mid, double* p_mid_ref) {
    const sps_real *y = sps_world_field(w, SPS_FIELD_POSITION_Y), *p = sps_world_field(w, SPS_FIELD_PRESSURE);
    const sps_real* rho = sps_world_field(w, SPS_FIELD_DENSITY);
    const int n = sps_world_particle_count(w);
    double rho_sum = 0, y_mid = 0;
    int i, mid = 0;
    *p_mid = 0;
    for (i = 0; i < n; ++i) {
        rho_sum += rho[i];
        if (fabs(y[i] - depth / 2) < dp) { *p_mid += p[i]; y_mid += y[i]; ++mid; }
    }
    *p_mean = c2 * (rho_sum / n - 1000);
    *p_mid /= mid > 0 ? mid : 1;
    y_mid /= mid > 0 ? mid : 1;
    *p_mid_ref = 1000 * 9.81 * (depth - y_mid);
}

/* Water 0.48 m deep (12 particles) in a tank 1 m wide, started hydrostatic, stays at rest for
   seconds: its mean pressure does not grow and the mid-depth pressure stays that of the column.
   Where the free surface cuts the kernel, the density diffusion of the Riemann solver acting
   on the hydrostatic pressure difference made the density grow (measured: mean pressure +36
   Pa/s, the level up 9 mm/s, the mid-depth pressure +10 % of rho g h at 6 s). */
static int test_fluid_rest_long(void) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body water;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 0.48, 0}, tank_hi[3] = {1, 2, 0};
    const double g = 9.81, depth = 0.48, dp = 0.04, c0 = 10 * sqrt(2 * g * 0.5), p_scale = 1000 * g * depth / 2;
    double p_mean[2], p_mid[2], p_mid_ref[2];
    int k;
    wd.dim = 2;
    wd.dp = dp;
    wd.threads = 1;
    wd.gravity[1] = -g;
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = c0;
    ENSURE(sps_world_add_box_walls(w, lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP) == SPS_OK);
    ENSURE(sps_world_add_body(w, &bd, &water) == SPS_OK);
    ENSURE(sps_body_add_box(w, water, lo, hi, NULL) == SPS_OK);
    ENSURE(sps_body_set_pressure(w, water, water_at_rest, (void*)&level_048) == SPS_OK);
    for (k = 0; k < 2; ++k) { /* at 2 s (the start's ringing has died down) and at 6 s */
        ENSURE(sps_world_advance(w, 2 + 4 * k, NULL, NULL) == SPS_OK);
        tank_pressures(w, c0 * c0, depth, dp, &p_mean[k], &p_mid[k], &p_mid_ref[k]);
        printf("    t = %d s: mean pressure %.1f Pa (column %.1f), mid-depth %.1f Pa (rho g h %.1f)\n", 2 + 4 * k, p_mean[k], p_scale,
               p_mid[k], p_mid_ref[k]);
    }
    /* 1 % of the mean hydrostatic pressure over 4 s: the mean density only moves with the
       surface's ripple at rest (measured +0.1 Pa; diffusing the full pressure difference: +148 Pa) */
    ENSURE(fabs(p_mean[1] - p_mean[0]) < 0.01 * p_scale);
    /* 4 %: the column's pressure at mid-depth rings at h = 1.3 dp (measured +2 %) */
    ENSURE_NEAR(p_mid[1], p_mid_ref[1], 0.04 * p_mid_ref[1]);
    sps_world_destroy(w);
    return 0;
}

/* The lid-driven cavity of examples/cavity.c (Re 100, L/dp 20, h = 2 dp, c0 = 10 U,
   material.fluid.dissipation none, TVF) to t = 2 s: the smallest spacing over the run and the kinetic
   energy at its end, with the transport shift carrying the velocity or not. */
static double cavity_min_spacing(int carries, double* kinetic) {
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0}, lid[3] = {1, 0, 0};
    sps_world* w = NULL;
    sps_body fluid;
    sps_diagnostics d;
    double smallest = 1;
    wd.dp = (sps_real)(1.0 / 20);
    wd.h_over_dp = 2;
    wd.log = quiet_log;
    wd.energy_growth_limit = (sps_real)INFINITY; /* the lid's work is not in the energy account */
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 10;
    bd.material.viscosity = 10; /* rho0 U L / Re */
    bd.transport = SPS_TRANSPORT_TVF;
    bd.material.fluid.dissipation = SPS_FLUID_DISSIPATION_NONE;
    bd.transport_carries_velocity = carries;
    if (sps_world_create(&wd, &w) != SPS_OK || sps_world_add_body(w, &bd, &fluid) != SPS_OK ||
        sps_body_add_box(w, fluid, lo, hi, NULL) != SPS_OK || sps_world_add_box_walls(w, lo, hi, 0, SPS_WALL_NO_SLIP) != SPS_OK ||
        sps_world_set_wall_velocity(w, 3, lid) != SPS_OK)
        smallest = -1;
    *kinetic = 0;
    while (smallest >= 0 && sps_world_time(w) < 2) {
        if (sps_world_step(w) != SPS_OK || sps_world_diagnostics(w, ALL_BODIES, &d) != SPS_OK) smallest = -1;
        else if (d.min_spacing < smallest) smallest = d.min_spacing;
    }
    if (smallest >= 0) *kinetic = d.kinetic_energy;
    sps_world_destroy(w);
    return smallest;
}

/* transport_carries_velocity: in the lid-driven cavity TVF's sums take the walls' images, so
   no pair next to a wall closes up (without them a pair under the lid came within 0.001 dp);
   the shift alone leaves the velocities behind and the vortex weakens, the velocity carried
   with it keeps it. A fluid under gravity (no velocity gradient) is refused. */
static int test_fluid_transport_carries_velocity(void) {
    double plain_energy, carried_energy;
    const double plain = cavity_min_spacing(0, &plain_energy), carried = cavity_min_spacing(1, &carried_energy);
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body b;
    printf("    smallest spacing to t = 2 s: %.4f dp (positions shifted), %.4f dp (velocity carried); kinetic energy at 2 s %.4g J, %.4g J\n",
           plain, carried, plain_energy, carried_energy);
    ENSURE(plain >= 0 && carried >= 0);
    ENSURE(plain > 0.1 && carried > 0.1); /* measured 0.21, 0.14 dp: no pair closer than a seventh of the spacing */
    ENSURE(carried_energy > 1.01 * plain_energy); /* measured 24.3 J against 23.9 (+1.5 %) at 2 s; without the velocity carried the vortex dies by 15 s */
    wd.gravity[1] = -9.81;
    wd.log = quiet_log;
    ENSURE(sps_world_create(&wd, &w) == SPS_OK);
    bd.material.kind = SPS_MATERIAL_FLUID;
    bd.material.fluid.sound_speed = 10;
    bd.transport = SPS_TRANSPORT_TVF;
    bd.transport_carries_velocity = 1;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "transport_carries_velocity = 1 without a velocity gradient"));
    bd.transport_carries_velocity = 2;
    ENSURE(sps_world_add_body(w, &bd, &b) == SPS_ERR_INVALID_ARG && strstr(sps_world_last_error(w), "transport_carries_velocity = 2, allowed 0"));
    sps_world_destroy(w);
    return 0;
}

/* ============================================================================================ */
/* This file's tests, in the order the runner runs them (tests/test_sphsolid.c calls run_fluids_tests). */
static void run_fluids_tests(void) {
    RUN(test_still_water);
    RUN(test_watchdog_names_shallow_water);
    RUN(test_fluid_corner_images);
    RUN(test_fluid_smoothing_warning);
    RUN(test_fluid_churn_warned);
    RUN(test_fluid_hexagonal_rest);
    RUN(test_fluid_hexagonal_fill);
    RUN(test_standing_wave_period);
    RUN(test_drucker_prager_return_on_cone);
    RUN(test_drucker_prager_cones_match_mohr_coulomb);
    RUN(test_granular_limiter_off_in_expansion);
    RUN(test_granular_block_at_rest);
    RUN(test_coincident_particles_stay_finite);
    RUN(test_granular_bad_input);
    RUN(test_transport_keeps_linear_momentum);
    RUN(test_tvf_counts_walls);
    RUN(test_fluid_bad_input);
    RUN(test_fluid_transport_carries_velocity);
    RUN(test_coupling_momentum);
    RUN(test_coupling_hydrostatic_rest);
    RUN(test_coupling_floating_block);
    RUN(test_coupling_light_soft_block);
    RUN(test_coupling_bad_input);
    RUN(test_granular_block_holds_shape);
    RUN(test_granular_lattice_moment);
    RUN(test_granular_free_grain_stops);
    RUN_LONG(test_granular_infinite_slope_stands_and_flows);
    RUN_LONG(test_granular_slope_floor_holds);
    RUN(test_fluid_rest_long);
}
