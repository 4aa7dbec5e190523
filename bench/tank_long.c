/* tank_long - the demo's water tank left running: does what floats stay afloat, and does the
   energy stay down?

   The tank scene of examples/scenes/jelly.h (2 m wide, free-slip walls, water 0.32 m deep at rest
   and hydrostatic, dp 0.04, c0 = 10 sqrt(2 g H)) with --drops blocks dropped one a second from
   0.5 s on by the demo's own jelly_drop_block: jelly rafts 0.40 x 0.20 m of density 500, every
   third a free rigid crate 0.16 m of density 600, each from 0.28 m above the water. The run goes
   to --tend s (60). Every --every s it samples the mechanical energy (kinetic + strain + contact
   + gravity potential, sps_diagnostics: the bodies' damping and Kelvin-Voigt viscosity dissipate
   it, nothing drives it after the last drop), the water's mean pressure and mass, and each
   block's submerged fraction: its part below the free surface beside it (each particle's dp x
   dp cell counted by its part below; the surface from the water's highest particles within 4 dp
   of the block's sides) over its area, which Archimedes puts at rho / 1000. At the end: each block's fraction
   averaged over the last --window s against Archimedes, the largest rise of the energy between
   two samples after the last drop has settled (--settle s after it), the water's mean pressure
   drift from the first sample after the drops to the end against rho0 g H, the mass; the largest
   rise also from 10 --settle after the last drop on (the splashes' sloshing long calmed).

   Build: make build/tank_long     Run: ./build/tank_long [--drops 5] [--tend 60] [--threads 1]
   bench/VALIDATION.md, "Water left running". */
#define SPHSOLID_IMPLEMENTATION
#include "../examples/common.h"
#include "../examples/scenes/jelly.h"

#define G_ACC 9.81

/* Each block's part below its local water level (m^2): the free surface beside it, the mean
   height of the highest water particle of each dp-wide column within 4 dp of its sides, plus
   dp/2 (a level from the water's volume assumes one flat surface, which a tank crowded with
   blocks has only in equilibrium). */
static void blocks_below(const jelly_scene* s, double* below_out) {
    const sps_real *x = sps_world_field(s->w, SPS_FIELD_POSITION_X), *y = sps_world_field(s->w, SPS_FIELD_POSITION_Y);
    int i, k, c, wfirst, wcount, first, count, components;
    sps_body_field(s->w, s->water, "density", &components, &wfirst, &wcount);
    for (k = 0; k < s->n_drops; ++k) {
        double lo = 1e30, hi = -1e30, top[8], level = 0;
        int columns = 0;
        below_out[k] = 0;
        if (!sps_body_field(s->w, s->drops[k].body, "density", &components, &first, &count)) continue;
        for (i = first; i < first + count; ++i) {
            if (x[i] < lo) lo = x[i];
            if (x[i] > hi) hi = x[i];
        }
        lo -= 0.5 * JELLY_DP;
        hi += 0.5 * JELLY_DP;
        for (c = 0; c < 8; ++c) top[c] = -1e30; /* columns 0-3 left of the block, 4-7 right */
        for (i = wfirst; i < wfirst + wcount; ++i) {
            const double left = (lo - x[i]) / JELLY_DP, right = (x[i] - hi) / JELLY_DP;
            c = left >= 0 && left < 4 ? 3 - (int)left : right >= 0 && right < 4 ? 4 + (int)right : -1;
            if (c >= 0 && y[i] > top[c]) top[c] = y[i];
        }
        for (c = 0; c < 8; ++c)
            if (top[c] > -1e29) { level += top[c] + 0.5 * JELLY_DP; ++columns; }
        if (!columns) continue; /* no water beside it: out of the water */
        level /= columns;
        for (i = first; i < first + count; ++i) {
            const double part = (level - y[i]) / JELLY_DP + 0.5;
            below_out[k] += JELLY_DP * JELLY_DP * (part < 0 ? 0 : part > 1 ? 1 : part);
        }
    }
}

/* The water's mean pressure [Pa] and mass [kg/m]. */
static void water_state(const jelly_scene* s, double* pressure, double* mass) {
    const sps_real *p = sps_world_field(s->w, SPS_FIELD_PRESSURE), *m = sps_world_field(s->w, SPS_FIELD_MASS);
    int i, first, count, components;
    *pressure = *mass = 0;
    sps_body_field(s->w, s->water, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i) {
        *pressure += p[i] / count;
        *mass += m[i];
    }
}

int main(int argc, char** argv) {
    int drops = 3, threads = 1, k, samples = 0, window_samples = 0, warnings_before;
    double t_end = 60, every = 0.1, window = 5, settle = 3;
    double fraction_sum[JELLY_MAX_DROPS] = {0}, below[JELLY_MAX_DROPS];
    double energy_prev = 0, largest_rise = 0, rise_time = 0, late_rise = 0, energy_settled = 0, pressure_start = 0, pressure_end = 0, mass_start = 0, mass_end = 0;
    double t_last_drop, wall0;
    opt_spec opts[] = {
        {"drops", OPT_INT, &drops, "blocks dropped, one a second (every third a rigid crate)", 0, JELLY_MAX_DROPS, NULL},
        {"tend", OPT_REAL, &t_end, "simulated time [s]", 1, 1e5, NULL},
        {"every", OPT_REAL, &every, "sampling interval [s]", 1e-3, 10, NULL},
        {"window", OPT_REAL, &window, "the fractions are averaged over the last window seconds", 0.1, 1e4, NULL},
        {"settle", OPT_REAL, &settle, "the energy is watched from this long after the last drop [s]", 0, 1e4, NULL},
        {"threads", OPT_INT, &threads, "OpenMP threads, 0 = all", 0, 1024, NULL},
    };
    jelly_scene s;
    sps_diagnostics d;
    sps_body all = {0};
    opt_parse(argc, argv, "the demo's water tank with rafts and crates, left running", opts, (int)(sizeof opts / sizeof *opts));
    t_last_drop = drops > 0 ? 0.5 + (drops - 1) : 0;
    if (t_end < t_last_drop + settle + window) {
        fprintf(stderr, "tank_long: --tend %g leaves no time after the last drop (%g s) + --settle %g + --window %g\n", t_end, t_last_drop, settle, window);
        return 2;
    }
    ex_check(NULL, jelly_create(threads, ex_log, 1, &s));
    wall0 = wall_seconds();
    for (k = 0; k < drops; ++k) {
        ex_check(s.w, sps_world_advance(s.w, (sps_real)(0.5 + k), NULL, NULL));
        ex_check(s.w, jelly_drop_block(&s, SPS_SHEAR_ENO_A));
    }
    ex_check(s.w, sps_world_diagnostics(s.w, all, &d));
    warnings_before = d.energy_growth_events;
    printf("# t [s]  energy [J/m]  water mean p [Pa]  fraction of each block (Archimedes: raft 0.5, crate 0.6)\n");
    for (k = 1;; ++k) {
        const double t = t_last_drop + k * every;
        double energy, pressure, mass;
        int b;
        if (t > t_end + 1e-9) break;
        ex_check(s.w, sps_world_advance(s.w, (sps_real)t, NULL, NULL));
        ex_check(s.w, sps_world_diagnostics(s.w, all, &d));
        energy = (double)(d.kinetic_energy + d.strain_energy + d.contact_energy + d.potential_energy);
        blocks_below(&s, below);
        water_state(&s, &pressure, &mass);
        if (k == 1) { pressure_start = pressure; mass_start = mass; }
        if (t >= t_last_drop + settle) {
            if (energy_settled == 0) energy_settled = energy;
            else if (energy - energy_prev > largest_rise) { largest_rise = energy - energy_prev; rise_time = t; }
            if (t >= t_last_drop + 10 * settle && energy - energy_prev > late_rise) late_rise = energy - energy_prev;
        }
        energy_prev = energy;
        if (t > t_end - window - 1e-9) {
            for (b = 0; b < s.n_drops; ++b) fraction_sum[b] += below[b] / (s.drops[b].crate ? JELLY_CRATE * JELLY_CRATE : JELLY_RAFT_W * JELLY_RAFT_H);
            ++window_samples;
        }
        pressure_end = pressure;
        mass_end = mass;
        ++samples;
        if (fmod(t + 1e-9, 1.0) < every - 1e-9 || t > t_end - 1e-9) {
            printf("%7.2f  %12.4f  %9.2f ", t, energy, pressure);
            for (b = 0; b < s.n_drops; ++b) printf(" %.4f", below[b] / (s.drops[b].crate ? JELLY_CRATE * JELLY_CRATE : JELLY_RAFT_W * JELLY_RAFT_H));
            printf("\n");
            fflush(stdout);
        }
    }
    {
        double worst = 0;
        int b;
        printf("RESULT case=tank_long drops=%d t_end=%g dp=%g", drops, t_end, JELLY_DP);
        for (b = 0; b < s.n_drops; ++b) {
            const double archimedes = (s.drops[b].crate ? JELLY_CRATE_RHO0 : JELLY_RAFT_RHO0) / 1000.0;
            const double err = 100 * (fraction_sum[b] / window_samples / archimedes - 1);
            printf(" %s%d=%+.2f%%", s.drops[b].crate ? "crate" : "raft", b, err);
            if (fabs(err) > fabs(worst)) worst = err;
        }
        printf(" worst=%+.2f%% energy_settled=%.4f energy_end=%.4f largest_rise=%.3e (at %.2f s) largest_rise_late=%.3e (from %.1f s) pressure_drift=%+.3f%% water_mass_ratio=%.12f "
               "watchdog_events=%d threads=%d wall_s=%.1f\n",
               worst, energy_settled, energy_prev, largest_rise, rise_time, late_rise, t_last_drop + 10 * settle,
               100 * (pressure_end - pressure_start) / (1000 * G_ACC * JELLY_WATER_DEPTH), mass_end / mass_start,
               d.energy_growth_events - warnings_before, threads, wall_seconds() - wall0);
    }
    sps_world_destroy(s.w);
    return 0;
}
