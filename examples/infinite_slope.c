/* infinite_slope.c - a layer of cohesionless soil on an incline: stands below its limit angle,
   flows above it (2D; GRANULAR and PERIODIC in sphsolid.h's manual).

   A layer D = 0.05 m deep of the C4 soil (rho0 = 2040, E = 5.84 MPa, nu = 0.3, c = 0, friction
   angle --phi, dilatancy angle --psi) lies on a rough (no-slip) floor, periodic along the slope
   (a period of 16 dp): an infinite slope (examples/scenes/infinite_slope.h). The frame is the
   slope's: gravity's normal part g cos(theta) is the world's, and the layer starts from its
   geostatic stress under it (Jaky's K0); the part along the slope, g sin(theta), is an external
   acceleration raised from 0 over the first 0.5 s (quasi-static: the layer's shear-wave period
   is 6 ms), then held.

   In an infinite slope the soil can only shear parallel to the floor (simple shear, no strain
   along it or out of the plane). A Mohr-Coulomb soil whose plastic flow keeps its volume (psi =
   0) then fails where the slope's stress ratio tan(theta) reaches sin(phi) cos(psi) / (1 -
   sin(phi) sin(psi)) (Davis 1968: the strength mobilised on the planes of zero extension), which
   is tan(phi) for associated flow (psi = phi) and sin(phi) for psi = 0: 26.6 degrees for phi =
   30. The plane-strain cone (material.granular.yield_cone's default) reproduces Mohr-Coulomb in plane
   strain, so the layer holds below that angle and flows above it. Measured: the top layer's
   displacement along the slope after the ramp (the velocity integrated over the hold, in dp)
   and its speed at the end; the layer "flows" when the displacement passes 1 dp.

   Build: make examples        Run: ./build/infinite_slope --angle 24 (and --angle 36)
   Expect (phi 30, psi 0): at 24 degrees (0.8 phi) a displacement far below 1 dp; at 36 (1.2 phi)
   the layer flows, its top accelerating; the limit printed next to Davis's; CSV, VTK, a picture.
   Smoke: infinite_slope --tend 0.05 */
#include "common.h"
#include "scenes/infinite_slope.h"

typedef struct {
    output_plan output;
    double t_prev;
    double displacement; /* of the top rows along the slope after the ramp [m] */
    double top_speed;    /* their mean speed along the slope now [m/s] */
} run_state;

static int on_step(sps_world* w, void* user) {
    run_state* s = (run_state*)user;
    sps_diagnostics d;
    char extra[64];
    slope_track(w, &s->t_prev, &s->displacement, &s->top_speed);
    snprintf(extra, sizeof extra, ",%.6e,%.6e", s->top_speed, s->displacement);
    output_tick(w, &s->output, extra, &d);
    return 0;
}

int main(int argc, char** argv) {
    common_options c = {.shear = SPS_SHEAR_OG, .cfl = 0.4, .t_end = 2.5, .vtk_every = 0.5, .csv_every = 0.01, .E = SLOPE_E, .nu = SLOPE_NU,
                        .rho0 = SLOPE_RHO0, .out = "out/infinite_slope", .transport = 0, PNG_DEFAULTS};
    slope_params p = {24, 30, 0, SPS_CONE_PLANE_STRAIN, 20, 0};
    granular_options g = {0, 30, 0.1, SPS_CONE_PLANE_STRAIN};
    opt_spec opts[] = {
        {"angle", OPT_REAL, &p.angle, "the slope's angle theta [degrees]", 0, 80, NULL},
        {"psi", OPT_REAL, &p.psi, "dilatancy angle [degrees], at most phi", 0, 89, NULL},
        {"res", OPT_INT, &p.res, "particles across the layer, D/dp", 4, 200, NULL},
        GRANULAR_OPTION_SPECS(g),
    };
    sps_world_def wd = sps_default_world_def();
    sps_body_def bd = sps_default_body_def();
    sps_world* w = NULL;
    sps_body soil;
    sps_diagnostics d;
    run_state s;
    double wall, limit;
    int flows;

    ex_options(argc, argv, "an infinite slope of cohesionless soil: stands below its limit angle, flows above it", opts, &c, &wd, &bd);
    if (p.psi > g.phi) {
        fprintf(stderr, "infinite_slope: --psi %g above --phi %g: the dilatancy angle is at most the friction angle\n", p.psi, g.phi);
        return 2;
    }
    bd.material.granular.stress_diffusion = (sps_real)g.diffusion; /* the soil's angles and cone are p's (slope_create): */
    p.phi = g.phi;
    p.cone = (sps_yield_cone)g.cone;
    /* a granular body's energy account holds no deviatoric strain energy: the geostatic start
       (Jaky's K0, not the elastic lateral ratio) releases some, 1e-6 J, which against a layer at
       rest (3e-5 J of mechanical energy) reads as growth */
    wd.energy_growth_limit = (sps_real)INFINITY;
    bd.name = "soil";
    slope_create(&p, &wd, &bd, &w, &soil);

    memset(&s, 0, sizeof s);
    limit = slope_limit_angle(p.phi, p.psi);
    output_open(&s.output, &c, "infinite_slope", "velocity", ",top_speed,top_displacement");
    printf("infinite_slope: theta = %g degrees, phi = %g, psi = %g, D/dp = %d, %d particles; limit angle (Davis 1968, simple shear) "
           "%.2f degrees: the layer should %s\n", p.angle, p.phi, p.psi, p.res, sps_world_particle_count(w), limit,
           p.angle < limit ? "stand" : "flow");
    on_step(w, &s);
    sps_world_advance(w, (sps_real)c.t_end, on_step, &s);
    wall = output_close(w, &s.output);
    sps_world_diagnostics(w, (sps_body){0}, &d);
    flows = s.displacement > wd.dp;
    printf("RESULT case=infinite_slope angle=%g phi=%g psi=%g cone=%d limit_davis=%.2f predicted=%s displacement_dp=%.4e top_speed=%.4e "
           "flows=%d agrees=%d %s particles=%d steps=%ld wall_s=%.2f out=%s\n", p.angle, p.phi, p.psi, g.cone, limit,
           p.angle < limit ? "stands" : "flows", s.displacement / wd.dp, s.top_speed, flows, flows == (p.angle >= limit),
           common_result_fields(&c), sps_world_particle_count(w), d.acoustic_steps, wall, c.out);
    sps_world_destroy(w);
    return 0;
}
