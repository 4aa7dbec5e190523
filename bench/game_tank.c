/* game_tank.c - the game-demo author's water scene in a real-time loop: a 2D tank 0.6 m wide with
   water 0.2 m deep and five jelly blocks (0.06 m, density 500, E --E) dropped onto it, shown at
   60 frames a second with sps_world_advance_frame (no wall budget: every frame is simulated in
   full, so the wall time per frame is the measurement). The water's sound speed comes from
   sps_fluid_sound_speed(g, depth, 0, --density-error): 0.01 the papers' (10 sqrt(2 g H)), 0.05
   the game preset. Reports the sub-steps and physics milliseconds per frame, the frames' share
   of real time, the water's largest density error |rho/rho0 - 1| over the run, its kinetic
   energy in the first and last second, and the rafts' mean draft against Archimedes' (half
   their height) over the last second.

   Build: make build/game_tank
   Run:   ./build/game_tank --dp 0.01 --density-error 0.05 --threads 1 --frames 600 */
#define SPHSOLID_IMPLEMENTATION
#include "../examples/common.h"

#define WIDTH 0.6
#define DEPTH 0.2
#define BLOCK 0.06
#define RAFTS 5

static double g_depth;
static sps_real hydrostatic(const sps_real x[3], void* user) {
    (void)user;
    return (sps_real)(1000 * 9.81 * (g_depth - (double)x[1]));
}

static double water_density_error(const sps_world* w, sps_body water) {
    const sps_real* rho = sps_world_field(w, SPS_FIELD_DENSITY);
    int i, first, count, components;
    double worst = 0;
    sps_body_field(w, water, "density", &components, &first, &count);
    for (i = first; i < first + count; ++i)
        if (fabs(rho[i] / 1000 - 1) > worst) worst = fabs(rho[i] / 1000 - 1);
    return worst;
}

int main(int argc, char** argv) {
    double dp = 0.01, density_error = SPS_DENSITY_ERROR_GAME, fps = 60, E = 1e5, physics = 0, physics_max = 0, rho_err = 0;
    double ke_first = 0, ke_last = 0, draft_sum = 0, start;
    int frames = 600, frame, drafts = 0, k;
    common_options c = {.shear = SPS_SHEAR_ENO_A, .cfl = 0.4, .t_end = 0, .vtk_every = 0, .csv_every = 1, .E = 1e5, .nu = 0.3,
                        .rho0 = 500, .out = "out/game_tank", .jitter = 0, .seed = 1, PNG_DEFAULTS};
    opt_spec opts[] = {
        {"dp", OPT_REAL, &dp, "particle spacing [m]", 2e-3, 0.05, NULL},
        {"density-error", OPT_REAL, &density_error, "the water's allowed density error (sps_fluid_sound_speed)", 1e-4, 0.5, NULL},
        {"fps", OPT_REAL, &fps, "frames per second", 1, 1000, NULL},
        {"frames", OPT_INT, &frames, "frames to run", 1, 1e7, NULL},
        COMMON_OPTION_SPECS(c),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def water_def = sps_default_body_def(), raft_def = sps_default_body_def();
    sps_world* w;
    sps_body water, rafts[RAFTS];
    sps_diagnostics d;
    sps_real tank_lo[3] = {0, 0, 0}, tank_hi[3] = {WIDTH, 1, 0}, lo[3] = {0, 0, 0}, hi[3] = {WIDTH, DEPTH, 0};
    c.png_every = 0;
    opt_parse(argc, argv, "game-demo water tank with jelly rafts in a real-time loop", opts, (int)(sizeof opts / sizeof *opts));
    E = c.E;
    apply_common(&c, &wd, &raft_def);
    wd.dim = 2;
    wd.dp = (sps_real)dp;
    wd.gravity[1] = -9.81;
    wd.log = ex_log;
    g_depth = DEPTH;
    water_def.name = "water";
    water_def.material.kind = SPS_MATERIAL_FLUID;
    water_def.material.density = 1000;
    water_def.material.fluid.sound_speed = sps_fluid_sound_speed((sps_real)9.81, (sps_real)DEPTH, 0, (sps_real)density_error);
    raft_def.name = "raft";
    ex_check(NULL, sps_world_create(&wd, &w));
    ex_check(w, sps_world_add_box_walls(w, tank_lo, tank_hi, SPS_FACE_Y_HI, SPS_WALL_FREE_SLIP));
    ex_check(w, sps_world_add_body(w, &water_def, &water));
    ex_check(w, sps_body_add_box(w, water, lo, hi, NULL));
    ex_check(w, sps_body_set_pressure(w, water, hydrostatic, NULL));
    for (k = 0; k < RAFTS; ++k) { /* flush on the water, spread over the tank */
        const sps_real blo[3] = {(sps_real)(0.03 + 0.12 * k), (sps_real)DEPTH, 0}, bhi[3] = {(sps_real)(0.03 + 0.12 * k + BLOCK), (sps_real)(DEPTH + BLOCK), 0};
        ex_check(w, sps_world_add_body(w, &raft_def, &rafts[k]));
        ex_check(w, sps_body_add_box(w, rafts[k], blo, bhi, NULL));
    }
    start = wall_seconds();
    for (frame = 0; frame < frames; ++frame) {
        const double t0 = wall_seconds(), t = sps_world_time(w);
        double spent;
        sps_real covered;
        ex_check(w, sps_world_advance_frame(w, (sps_real)(1 / fps), 0, &covered));
        spent = wall_seconds() - t0;
        physics += spent;
        if (spent > physics_max) physics_max = spent;
        if (water_density_error(w, water) > rho_err) rho_err = water_density_error(w, water);
        ex_check(w, sps_world_diagnostics(w, water, &d));
        if (t < 1 && d.kinetic_energy > ke_first) ke_first = d.kinetic_energy;
        if (frame >= frames - fps && d.kinetic_energy > ke_last) ke_last = d.kinetic_energy;
        if (frame >= frames - fps) { /* the level: the water's area at rho0 and the rafts' parts below it fill the tank */
            const sps_real *y = sps_world_field(w, SPS_FIELD_POSITION_Y), *m = sps_world_field(w, SPS_FIELD_MASS);
            int first, count, components, i;
            double bottom[RAFTS], bottoms = 0, area = 0, level;
            for (k = 0; k < RAFTS; ++k) {
                bottom[k] = 0;
                sps_body_field(w, rafts[k], "density", &components, &first, &count);
                for (i = first; i < first + count; ++i) bottom[k] += y[i];
                bottom[k] = bottom[k] / count - 0.5 * BLOCK;
                bottoms += bottom[k];
            }
            sps_body_field(w, water, "density", &components, &first, &count);
            for (i = first; i < first + count; ++i) area += m[i] / 1000;
            level = (area - BLOCK * bottoms) / (WIDTH - RAFTS * BLOCK);
            for (k = 0; k < RAFTS; ++k, ++drafts) draft_sum += level - bottom[k];
        }
    }
    ex_check(w, sps_world_diagnostics(w, (sps_body){0}, &d));
    printf("RESULT case=game_tank dp=%g density_error=%g c0=%.3f E=%g fps=%g frames=%d substeps_per_frame=%.1f physics_ms_mean=%.2f "
           "physics_ms_max=%.2f real_time=%.3f water_density_error_max=%.4f water_ke_first=%.4e water_ke_last=%.4e draft=%.5f "
           "archimedes_about=%.5f %s particles=%d wall_s=%.2f\n",
           dp, density_error, (double)water_def.material.fluid.sound_speed, E, fps, frames, (double)d.acoustic_steps / frames,
           1e3 * physics / frames, 1e3 * physics_max, (frames / fps) / physics, rho_err, ke_first, ke_last, drafts ? draft_sum / drafts : 0,
           0.5 * BLOCK, common_result_fields(&c), sps_world_particle_count(w), wall_seconds() - start);
    sps_world_destroy(w);
    return 0;
}
