/* check_compile_out.c - the compile-out switches (CONFIG MACROS: SPHSOLID_NO_FLUID,
   SPHSOLID_NO_GRANULAR, SPHSOLID_NO_PLASTICITY, SPHSOLID_NO_TOTAL_LAGRANGIAN; SPHSOLID_NO_GEOMETRY
   refuses no kind), built by make
   check with each one and with all of them: an elastic block still runs, a body of a kind the
   build left out is refused with a message naming the macro, and the kinds kept are accepted.
   Exit status 0 iff all holds. */
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"
#include <stdio.h>
#include <string.h>

/* The macro that should refuse this def in this build, or NULL. */
static const char* expected_refusal(const sps_body_def* bd) {
#ifdef SPHSOLID_NO_FLUID
    if (bd->material.kind == SPS_MATERIAL_FLUID) return "SPHSOLID_NO_FLUID";
#endif
#ifdef SPHSOLID_NO_GRANULAR
    if (bd->material.kind == SPS_MATERIAL_DRUCKER_PRAGER) return "SPHSOLID_NO_GRANULAR";
#endif
#ifdef SPHSOLID_NO_PLASTICITY
    if (bd->material.kind == SPS_MATERIAL_J2) return "SPHSOLID_NO_PLASTICITY";
#endif
#ifdef SPHSOLID_NO_TOTAL_LAGRANGIAN
    if (bd->solver == SPS_SOLVER_TOTAL_LAGRANGIAN) return "SPHSOLID_NO_TOTAL_LAGRANGIAN";
#endif
    (void)bd;
    return NULL;
}

static void quiet(int level, const char* message, void* user) { (void)level; (void)message; (void)user; }

int main(void) {
    static const struct { sps_material_kind kind; sps_solver solver; sps_shear shear; } bodies[] = {
        {SPS_MATERIAL_FLUID, SPS_SOLVER_UPDATED_LAGRANGIAN, SPS_SHEAR_ENO_A},
        {SPS_MATERIAL_DRUCKER_PRAGER, SPS_SOLVER_UPDATED_LAGRANGIAN, SPS_SHEAR_ENO_A},
        {SPS_MATERIAL_J2, SPS_SOLVER_UPDATED_LAGRANGIAN, SPS_SHEAR_GNO_A},
        {SPS_MATERIAL_NEO_HOOKEAN, SPS_SOLVER_TOTAL_LAGRANGIAN, SPS_SHEAR_ENO_A}};
    const sps_real lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.05, 0};
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body b;
    int k, failed = 0;
    wd.log = quiet;
    if (sps_world_create(&wd, &w) != SPS_OK || sps_world_add_body(w, &bd, &b) != SPS_OK || sps_body_add_box(w, b, lo, hi, NULL) != SPS_OK)
        return 1;
    for (k = 0; k < 3; ++k) failed |= sps_world_step(w) != SPS_OK; /* an elastic block runs */
    for (k = 0; k < (int)(sizeof bodies / sizeof bodies[0]); ++k) {
        const char* macro;
        sps_result r;
        bd = sps_default_body_def();
        bd.material.kind = bodies[k].kind; bd.solver = bodies[k].solver; bd.shear = bodies[k].shear;
        bd.material.fluid.sound_speed = bd.material.kind == SPS_MATERIAL_FLUID ? 20 : 0;
        bd.material.j2.yield_stress = bd.material.kind == SPS_MATERIAL_J2 ? 1e4 : 0;
        bd.material.granular.friction_angle = bd.material.kind == SPS_MATERIAL_DRUCKER_PRAGER ? 30 : 0;
        macro = expected_refusal(&bd);
        r = sps_world_add_body(w, &bd, &b);
        if (macro ? r != SPS_ERR_INVALID_ARG || !strstr(sps_world_last_error(w), macro) : r != SPS_OK) {
            printf("check_compile_out: kind %d solver %d: %s (expected %s)\n", (int)bd.material.kind, (int)bd.solver,
                   r == SPS_OK ? "accepted" : sps_world_last_error(w), macro ? macro : "accepted");
            failed = 1;
        }
    }
    sps_world_destroy(w);
    return failed;
}
