/* sphsolid.h - v0.17.0 - SPH solid dynamics - MIT (licence at the end of this file)

   An stb-style single-file C99 library for simulating elastic and elastic-plastic (J2) solids
   with updated-Lagrangian
   smoothed particle hydrodynamics (UL-SPH): Wendland C2 kernel, cell-linked-list neighbour search,
   low-dissipation Riemann solver, six shear formulations (SPH-OG, SPH-OAS, SPH-ENO, SPH-ENO-A,
   SPH-GNO, SPH-GNO-A; Rodrigues rotation for the -A variants), position-based Verlet with
   dual-criteria time stepping; and, per body, total-Lagrangian SPH with Ganzenmueller's
   hourglass control (Saint Venant-Kirchhoff and Neo-Hookean; TOTAL-LAGRANGIAN). libc and
   (optionally) OpenMP only.

   ========================================================================================
   USAGE
      In exactly ONE C or C++ file:
         #define SPHSOLID_IMPLEMENTATION
         #include "sphsolid.h"
      Everywhere else include "sphsolid.h" alone. Link with -lm; add -fopenmp for threads.
      For speed: -O2 -march=native -fno-math-errno -fno-trapping-math (so sqrt and, on AVX2, the pair loops vectorise), and with GCC on x86-64
      a -mtune that allows gather instructions (e.g. -mtune=icelake-server; GCC's generic
      tuning has none) and, on CPUs with AVX-512, -mprefer-vector-width=512 (GCC keeps 256-bit
      vectors otherwise; 1.2x on the 2D plate). The neighbour loops run one particle per SIMD
      lane (an OpenMP simd loop: build with -fopenmp, also for one thread; without it, or with
      -fopenmp-simd only, the pragmas are left out and one thread is 1.45x (2D) to 2x (3D)
      slower); on the 2D plate this is 1.6x the scalar speed.

   QUICK START (a clamped rubber strip that swings under gravity)
         sps_world_def wd = sps_default_world_def();
         wd.dim = 2; wd.dp = 0.002; wd.gravity[1] = -9.81;
         sps_world* w; if (sps_world_create(&wd, &w) != SPS_OK) return 1;
         sps_body_def bd = sps_default_body_def();          // ENO-A, rho0 1000, E 1e6, nu 0.3
         bd.material.youngs_modulus = 2e6;
         sps_body strip; sps_world_add_body(w, &bd, &strip);
         sps_real lo[3] = {-0.008, -0.01, 0}, hi[3] = {0.2, 0.01, 0};
         sps_body_add_box(w, strip, lo, hi, NULL);          // lattice fill, spacing dp
         sps_real clo[3] = {-1, -1, -1}, chi[3] = {0, 1, 1};
         sps_body_constrain_box(w, strip, clo, chi, SPS_AXIS_ALL, NULL, NULL); // clamp x < 0
         while (sps_world_time(w) < 1.0)
             if (sps_world_step(w) != SPS_OK) { puts(sps_world_last_error(w)); break; }
         sps_world_write_vtk(w, "strip.vtk");               // open in ParaView
         sps_world_destroy(w);

   CONFIG MACROS (define before including; "global" = must be the same in every file)
      SPHSOLID_IMPLEMENTATION  emit the implementation in this translation unit.
      SPHSOLID_STATIC          make every function static (private copy per file). Global.
      SPHSOLID_FLOAT           sps_real is float instead of double. Global: the float build
                               renames the entry points, so mixing builds fails at link time.
      SPHSOLID_MALLOC(sz,u) / SPHSOLID_FREE(p,u)
                               default allocator (malloc/free); define both or neither.
      SPS_ASSERT(c)            assertion for programmer errors (default: assert.h).
      SPHSOLID_NO_STDIO        drop the file writers and the default stderr logger.
      SPHSOLID_NO_GEOMETRY     leave out the meshes and outlines (GEOMETRY). Global.
      SPHSOLID_NO_FLUID, SPHSOLID_NO_GRANULAR, SPHSOLID_NO_PLASTICITY,
      SPHSOLID_NO_TOTAL_LAGRANGIAN
                               leave out the pass instances of fluids, Drucker-Prager bodies,
                               J2 bodies and total-Lagrangian bodies: a smaller, faster-compiling
                               build for a scene without them (e.g. elastic bodies only).
                               sps_world_add_body refuses a body of a kind left out, naming the
                               macro. Implementation-only.
      SPHSOLID_ALL_PAIR_LOOPS  vectorised pair loops for the cubic spline kernel too (by
                               default it runs generic loops, about 3x slower): a longer
                               compile. Implementation-only.
      SPHSOLID_WALL_SECONDS()  wall clock in seconds for the frame budget of
                               sps_world_advance_frame. Implementation-only. Default:
                               clock_gettime(CLOCK_MONOTONIC) where <time.h> declares it (POSIX:
                               define _POSIX_C_SOURCE >= 199309L before any #include in the
                               implementation file, or build with -std=gnu99), else C99 clock(),
                               which counts processor time (of all threads) instead.

   CONCEPTS & UNITS
      SI units throughout: m, s, kg, Pa. 2D runs are plane strain per unit depth, so "mass",
      "energy" and "momentum" are per metre of depth in 2D (kg/m, J/m, ...).
      dp   initial particle spacing; particle volume V = dp^d, mass m = rho0 V.
      h    smoothing length = h_over_dp * dp (default 1.3 dp); kernel support radius 2h.
      c0   artificial sound speed sqrt(K/rho0), K = E/(3(1-2nu)); p = c0^2 (rho - rho0).
      G    shear modulus E/(2(1+nu)).
      Time steps (dual-criteria, ENO eqs. 25-26): advection dt_ad = CFL_ad h/|v|max (particle
      configuration and neighbour lists updated), acoustic dt_ac = CFL_ac h/(c0 + |v|max)
      (all other variables updated). CFL_ad = 0.2, CFL_ac = 0.4. |v|max is measured in each
      body's frame (its mass-weighted mean velocity), or is the largest approach speed of two
      bodies that touch (or of a body towards the walls) if that is larger: a uniform motion
      does not change the time steps (a spinning plate translating at 20 m/s takes the same
      steps as at rest, tested).
      STABLE CFL: the largest cfl_acoustic measured stable (the stability map in
      bench/VALIDATION.md: 2D plate at H/dp 5 over 0.3 s, 3D plate at H/dp 3 over 2 ms; above
      it the energy grows) is, 2D / 3D: ENO 0.6 / 0.5, ENO-A 0.6 / 0.5, OG 0.8 / 0.8, OAS 1 / -,
      GNO 0.8 / 0.6, GNO-A 0.8 / 0.8. Adding a body with a larger value warns (the run may
      still be fine for another scene; the energy watchdog watches it).

   STEP BY STEP (one acoustic sub-step, position-based Verlet, ENO eqs. 27-29)
      1. rho += dt/2 drho/dt; p = c0^2 (rho - rho0); x += dt/2 v
      2. pressure pass: dv/dt_i = -(1/rho_i) sum_j (p_i + p_j - Z v_ij.e_ij) dW_ij e_ij V_j
         (the low-dissipation Riemann solver of ENO eqs. 13-16 with beta = 1 and Z = rho0 c0:
         what the reference code uses for elastic solids); OG family: + (1/rho_i) sum_j
         (tau_i + tau_j) e_ij dW_ij V_j (ENO eq. 17); OAS: + Gray's artificial stress
      3. v += dt (dv/dt + a_s + g + a_ext); velocity constraints; x += dt/2 v (a damped body:
         v = e^(-c dt) v + (1 - e^(-c dt))/c (dv/dt + a_s + g + a_ext); DAMPING)
      4. continuity pass: drho/dt_i = rho_i sum_j (v_ij.e_ij) dW_ij V_j; velocity gradient
         L_i = -sum_j v_ij (x) (B_i grad W_ij) V_j when needed (ANG eq. 20); Jaumann stress;
         ENO: da_i = 2 zeta G/rho_i sum_j (e_ij.v_ij)/r_ij dW_ij e_ij V_j dt (ENO eq. 24)
      4b. GNO family, after L is known everywhere: the hourglass penalty increment da_i
         (ANG eqs. 43-49). ENO, GNO: a_s += da; ENO-A, GNO-A: a_s = R a_s + da (ANG eqs. 34-42)
         (or in the next sub-step's pressure pass: PENALTY IN THE PRESSURE PASS)
      5. rho += dt/2 drho/dt
      The configuration update (every advection step) sorts particles by cell and rebuilds the
      CSR neighbour lists. The pair geometry e_ij, dW/dr and the correction matrix
      B_i = (-sum_j r_ij (x) grad W_ij V_j)^-1 (ANG eq. 21) come from the current positions in
      each pass (frozen_geometry = 0, default). With frozen_geometry = 1, dW/dr is stored at the
      configuration update, and e_ij, 1/r_ij (a Newton step from the stored 1/r_0) and B_i still
      follow the current positions (1.2-1.3x faster in double, no faster in float). The
      reference code stores e_ij too; a stored direction lags a rotating pair and makes it look
      shorter, which drifts the plate's period by 0.55% per cycle and gives the spinning plate
      33% angular-momentum error (see sps__pair).

   REAL-TIME FRAMES (demos, games: sps_world_advance_frame, sps_body_drag_begin)
      sps_world_advance_frame(w, 1.0 / F, budget, &covered) advances one frame of simulated time
      at F frames per second; the library picks the sub-steps and the last step lands on the
      frame's end. Without a budget the frame is deterministic (bit-identical for any thread
      count). With a wall budget (say 80 % of 1/F) the budget is a hard cap: each advection step
      is cut to the sub-steps that still fit (at the cost per sub-step measured in this frame, or
      in the last budgeted one, one sub-step's time kept for the neighbour-list rebuild), so a
      frame overruns by about one sub-step at most on an idle core, and a machine too slow for
      the scene shows slow motion (covered < 1/F, one sub-step per frame at least) instead of
      dropping frames. A frame continues the advection step the last frame left open, so the
      neighbour lists are rebuilt where a free-running step would rebuild them (every ~25
      sub-steps of a jelly), not at every frame's start (every 4-5); a change through the API
      in between (particles added or moved, velocities, masses, walls, contact; not forces,
      accelerations or drags, which the next sub-step reads) starts a fresh step, as do
      sps_world_step and sps_world_advance, and so does a periodic world at every frame (its
      positions are wrapped into the box between steps). A restart file holds no open step.
      The budget is measured
      with SPHSOLID_WALL_SECONDS() (CONFIG MACROS). sps_world_advance_substeps runs a fixed
      count of sub-steps instead. sps_body_drag_begin grabs a body for the mouse: a spring of
      the caller's stiffness and damping towards drag.target, spread by the kernel over a
      neighbourhood of the grabbed material point, so that no particle is torn out (a 2D jelly
      of 1024 particles dragged round a circle for 3 s keeps every particle within 1.03 dp of a
      neighbour; tested). bench/realtime.c measures a whole loop; examples/demo.c drags blocks.

   SHEAR FORMULATIONS (per body, sps_body_def.shear)
      SPS_SHEAR_OG     original: tau by the Jaumann rate, a = (1/rho) div tau (ENO eq. 17).
                       Zero-energy (hourglass) modes are not resisted: it zigzags and fractures.
      SPS_SHEAR_OAS    OG + Gray et al.'s artificial stress (2D only; eps = 0.3, n = 4,
                       f_ij = (W(r_ij)/W(dp))^n).
      SPS_SHEAR_ENO    essentially non-hourglass: a_s accumulates the rotation-invariant Laplacian
                       of velocity (ENO eq. 24). zeta = 0.7 d + 2.1 by default.
      SPS_SHEAR_ENO_A  ENO with the stored a_s rotated by the Rodrigues matrix of the spin before
                       each increment (ANG Algorithm 1).
      SPS_SHEAR_GNO    OG + an accumulated penalty on v^_ij = v_ij - 1/2 (L_i + L_j) r_ij, the
                       part of the velocity difference a linear field does not explain (ANG eq. 43).
      SPS_SHEAR_GNO_A  GNO with the penalty projected on e_ij (ANG eq. 46) and rotated like ENO-A
                       (ANG Algorithm 2). xi_G = 2.
      -A variants: rotation = SPS_ROTATION_MEAN uses the body's mean Rodrigues matrix (linear
      momentum exact, ANG eq. 41; the papers' choice, which the examples pass explicitly);
      SPS_ROTATION_PER_PARTICLE each particle's own (eq. 34). The default, SPS_ROTATION_AUTO, is
      SPS_ROTATION_PAIR below for ENO-A and the mean for GNO-A: with ENO-A the mean rotation
      gains energy when a body tumbles or hits something (a 0.1 m rubber cube spinning at 20
      rad/s dropped on a no-slip floor: the energy account grew by a factor 500 within 1 s; with
      the pair rotation it only falls), while GNO-A with the mean rotation gained in none of the
      user scenes and with the pair rotation in some (bench/VALIDATION.md, user scenes).
      SPS_ROTATION_PAIR (our extension, not in the papers) does what eq. 32 asks of the rotation,
      that every stored increment stay aligned with its pair, exactly: each ENO increment (or
      GNO-A penalty increment, eq. 46) is a force along e_ij, so the library stores one scalar
      per neighbour pair, g_ij = sum over sub-steps of the increment's magnitude (symmetric in
      i, j), and applies a_s_i = (1/m_i) sum_j g_ij e_ij with the current e_ij. ENO-A's forces
      are then all central pair forces: linear and angular momentum are exact for any motion
      (spinning cube: 1e-12 % instead of 19.8 %; GNO-A keeps its stress divergence, which is not
      central, and gains nothing: 0.15 % against 0.05 %). No rotation matrices or velocity
      gradient are needed (ENO-A without track_stress skips B and L), and g_ij is carried over
      neighbour-list rebuilds by particle id (a pair that enters the support starts at 0, one
      that leaves takes its g_ij, accumulated where dW is near 0, with it). Memory: 2 reals + 1
      int per pair slot.
      The shear stress tau (Jaumann rate, ENO eqs. 6-8) is integrated for the OG family always,
      for ENO bodies only with track_stress = 1 (von Mises output, strain energy).

   PENALTY IN THE PRESSURE PASS (sps_body_def.penalty_in_pressure_pass; GNO, GNO-A)
      The paper's sub-step runs three neighbour passes on a GNO body: pressure, continuity and
      the penalty (step 4b), which needs every neighbour's L_j from the continuity pass. With
      penalty_in_pressure_pass = 1 the penalty of sub-step n is summed in the pair loop of
      sub-step n+1's pressure pass instead, with the paper's inputs: v^(n+1) and L^(n+1) (nothing
      changes them in between), the pair geometry of x^(n+1), formed again in that loop from
      x - dt/2 v (the half drift's inverse), and sub-step n's own dt; its increments reach a_s
      before sub-step n+1's kick, as in the paper (the mean rotation turns a_s in sub-step n's
      step 5 and they are added after it). What lags: V_j and rho_i, which are those of one
      density update later (a relative change of dt drho/rho per sub-step). Each advection step's
      last sub-step runs the penalty as a pass of its own, so a step returns with the paper's
      state. Two neighbour passes per sub-step instead of three, for elastic and J2 bodies with
      the mean or per-particle rotation (not rotation = pair, whose pair forces the pressure pass
      reads, nor Drucker-Prager bodies, whose pressure pass is their own). Results are not bit
      for bit the paper form's (the pinned cases keep 0): the GNO-A plate's period agrees to 6
      digits; measured speed and every figure: bench/VALIDATION.md, "Pass fusion".
      Default 0, the paper's form.

   PLASTICITY (material.kind = SPS_MATERIAL_J2; ANG section 2.2)
      von Mises plasticity with linear isotropic hardening: after the Jaumann update (the trial
      stress tau*) a particle whose |tau*| = sqrt(2 J2) exceeds the yield radius
      sqrt(2/3)(sigma_Y + kappa alpha) (ANG eq. 11; sigma_Y = material.j2.yield_stress, kappa =
      material.j2.hardening_modulus) flows by d_gamma = f/(2G + 2 kappa/3), its equivalent plastic
      strain alpha grows by sqrt(2/3) d_gamma, and tau = r tau* with r = sqrt(2/3)(sigma_Y +
      kappa alpha)/|tau*| (radial return, ANG eq. 14): exactly on the hardened surface. The
      particle's plastic work grows by V (tau*:tau* - tau:tau)/(4G), the elastic energy the return
      removed (per particle, so sums are deterministic); kinetic + strain + plastic work is the
      energy account (diagnostics plastic_work; total_energy in the CSV). The equation of state
      and c0 are the elastic ones. J2 bodies need a stress-based shear formulation: GNO-A is
      ANG's (xi_G = 2), with the reference code's per-particle penalty scale: each pair's
      penalty term weighted by 1/2 (r_i + r_j) of the sub-step, and (our extension) the stored
      penalty relaxed by the same factors, as the stress is: scaled increments alone left a
      spring against plastic flow that created energy (the round Taylor bar at R/9 gained five
      times its impact energy; bench/VALIDATION.md, B). OG, OAS and GNO work too.
      ENO and ENO-A are refused (their shear force is not the divergence of tau, so the yield
      surface cannot limit it). Fields "plastic_strain" (alpha) and "plastic_work" [J] belong to
      J2 bodies only (VTK: plastic_strain; sps_particle_state.plastic_strain); an elastic body
      carries neither, and its kernels contain no return map.

   FLUIDS (material.kind = SPS_MATERIAL_FLUID; UTVF sections 2.1, 3.1.1)
      A weakly compressible fluid: p = c0^2 (rho - rho0) with c0 = material.fluid.sound_speed (about
      10 times the largest flow speed keeps the density within ~1 %; sps_fluid_sound_speed
      chooses it from the depth and speeds for a density error: SPS_DENSITY_ERROR_GAME trades
      5 % of it for half the sub-steps of a water scene), no shear stress (shear,
      rotation and track_stress are not used), and the Riemann solver of UTVF eqs. 16-20: the
      momentum equation's dissipation Z beta (v_ij . e_ij), Z = rho0 c0, with the limiter beta =
      min(3 max(-v_ij . e_ij / c0, 0), 1) (none while particles separate), and the continuity
      equation's pressure term (p_i - p_j)/(rho0 c0) dW V_j, which diffuses the density; with
      gravity it takes p_i - p_j - rho0 g . x_ij, so that the hydrostatic pressure of water at
      rest, cut by its free surface, does not make its density creep up (bench/VALIDATION.md,
      "Fluid at rest over long times"). Under gravity the velocity divergence is UTVF eq. 16's
      pair sum sum (v_ij . e_ij) dW V_j, the adjoint of the pressure force, so that the work of
      pressure and the change of stored energy balance and water at rest keeps its energy, and
      both are scaled by c = 1 / sum_j x_ij,x dW_ij/dx V_j of the lattice (0.974 for the Wendland
      kernel at h = 1.3 dp in 2D, 0.999 at 2 dp), so that a hydrostatic column weighs what its
      pressure carries (else the force is that much weak and water sinks into its floor). Without
      gravity it is tr L of the corrected velocity gradient, exact for a linear flow where a free
      surface cuts the kernel, so the elliptical drop converges (semi-axis +0.39 % at dp = 0.02,
      +0.27 % at 0.01; with the pair sum +0.65 % at 0.02, growing as dp shrinks); tr L is not
      the force's adjoint, and under gravity a tank at rest gained energy with it
      (bench/VALIDATION.md, "Still water").
      Water at rest (body def lattice): on the square lattice of the fills the rows of water
      under hydrostatic pressure slide in alternate directions (the lattice is a saddle of the
      pressure forces, the hexagonal packing lower), from round-off, at a rate that grows as
      sqrt(p) / dp (24/s over the floor of 0.5 m of water at dp 0.02, h = 1.3 dp: a tank at rest
      churns within 1.5 s; with either kernel), and the churned water's free surface carries
      0.1-0.2 dp of head too much, which floats bodies that much too high. A 2D fluid with a
      hydrostatic column at h_over_dp 1.3 is therefore filled on the hexagonal lattice
      (lattice = SPS_LATTICE_AUTO; sps_lattice), on which the same tank stays at rest (its start's
      settling decays to a largest speed of 1.3e-3 m/s by 20 s) with its surface's pressure at
      rho0 g dp/2; its pressure force
      takes that lattice's moment (0.985 at 1.3 dp). The hexagonal lattice holds at 1.3 dp only
      (1.5-2 dp: churning after 4-14 s), and waves at 1.3 dp run fast (a standing wave at
      depth/dp 25: period -5.7 %; -0.7 % at 2 dp on the square lattice). Boxes filled side by side do not meet row for row
      (fill one box, or a shape with sps_body_add_sdf), and its half particles stand 0.27 dp
      from a box's x faces, nearer a wall body's particles than the square lattice's (a first
      step's kick of 1 % of sqrt(2 g H) in a U-tank of particles). 3D has no close-packed fill:
      its cubic lattice's rows slide too; there, as on the square lattice in 2D, h_over_dp = 2
      holds water at rest for 8-14 s, after which its free surface bursts to about 1e-3 sqrt(g
      H), and standing waves run within 1 % of linear theory (twice the neighbours of 1.3 dp in
      2D); a fluid under gravity on the square lattice below 2 dp gets a warning
      (bench/VALIDATION.md, "Water left running", "Still water"). With
      material.viscosity = mu > 0 the viscous force (2 mu/rho_i) sum_j v_ij dW/r_ij V_j
      (Morris et al. 1997), divided by the lattice moment above (else it is 2.7 % weak at h =
      1.3 dp), joins; the acoustic step stays below h^2 / (14 nu) (its stability) and the
      advection step keeps nu/h below its speed. No-slip walls give it the images' velocity
      2 v_wall - v_j (analytic walls, wall bodies): plane Poiseuille flow (example poiseuille).
      Numerical dissipation (material.fluid.dissipation): the Riemann solver's momentum term
      Z beta (v_ij . e_ij) acts as an artificial viscosity of about 3 |v_ij . e_ij| h, of the
      order of nu at Re 100 on lattices of 30-60 particles per length, so a viscous flow decays
      too fast with it (the Taylor-Green vortex at Re 100, 1/dp 30, h = 1.5 dp: kinetic energy
      28 % low at t = 2 s). SPS_FLUID_DISSIPATION_DENSITY leaves it out (the pressure and the
      viscous force alone; the density diffusion kept: 5.3 %); SPS_FLUID_DISSIPATION_NONE
      leaves out the density diffusion too, which damps the pressure field that holds a vortex
      (1.4 %, and 0.95 % at 1/dp 60; 10 % at h = 1.3 dp, where the particles' disorder under
      TVF dissipates more). Both need material.viscosity > 0 (refused without: only the viscosity
      then damps the particles' noise); the default SPS_FLUID_DISSIPATION_RIEMANN is for free
      surfaces, impacts and water. Without the density diffusion a closed box's sound is damped
      by the viscosity alone: the lid-driven cavity's density varies by +-5 % at c0 = 10 U and
      its flow by a few per cent in time, its profiles within 2-6 % of Ghia et al.'s at L/dp 40
      (6 % with the default), 1.2-2.5 % with the transport shift carrying the velocity
      (TRANSPORT: transport_carries_velocity). bench/VALIDATION.md, "Viscous flows without the
      Riemann solver's dissipation".
      Free surfaces need nothing (particles carry their density). Walls: analytic walls
      (CONTACT) act on a fluid through mirror particles, the images of its particles across each
      wall within 2h (reflected velocity, hydrostatic pressure p_j + rho0 g . (x_j' - x_j)), and
      where two perpendicular walls meet, the images across both (a corner particle without them
      misses a quarter of its neighbours and was pulled into the corner at 33 m/s^2), so a column
      stands on its floor at its hydrostatic pressure; a backstop (the solids' contact pressure
      counted from dp/2) keeps particles out of corners the images do not close (walls at other
      angles). sps_body_set_pressure gives an initial pressure field (hydrostatic,
      or one that goes with an initial flow). Stored energy: p^2/(2 K), K = rho0 c0^2. A fluid
      meets a solid body through FLUID-STRUCTURE, another fluid or a granular body through the
      solids' contact penalty.

   FLUID-STRUCTURE (chapter >>coupling: fluid-structure; Zhang, Rezavand and Hu 2021, JCP)
      A fluid body and a solid body (elastic, J2, total Lagrangian or rigid) that touch (CONTACT:
      contact = 1 on both, the pair not separated) are coupled instead of held apart by the
      penalty: the fluid sees each solid particle within 2h as a wall image, with the solid's
      velocity (the image velocity 2 v_s - v_f) and the wall pressure p_f + rho_f g . (x_s -
      x_f), in its pressure force (Riemann solver) and continuity sums, and the solid receives
      the opposite of each pair's force: momentum is exact. Water at rest stands on a solid as on
      an analytic wall, its first layer dp from the solid's surface particles, and water filled
      up to a solid on the lattice starts at rest. Rigid bodies built from particles make tanks
      and obstacles of any shape. Cost: a fluid particle pays only for the solid particles
      within 2h of it; a scene without a fluid-solid pair runs none of it. Added mass: the time
      step takes the coupling's signal speed c0_f sqrt(rho0_f / rho0_s) beside the bodies' own
      (a light, soft solid held by the fluid's pressure); measured stable down to rho_s/rho_f =
      1/200 (bench/VALIDATION.md, fluid-structure). A fluid-solid pair that does not touch is
      warned of (the water would flow through the solid). Examples: hydrostatic_fsi (a plate
      under water, against beam theory), floating_block (Archimedes), elastic_gate (a dam break
      through a rubber gate, Antoci et al. 2007), the demo's water tank. Over tens of seconds a
      fluid at rest between analytic walls drifts (its pressure and surface rise slowly) and a
      floating body rises with it (bench/VALIDATION.md, the elastic gate and the demo's tank).

   TRANSPORT (transport = SPS_TRANSPORT_TVF or SPS_TRANSPORT_UTVF; UTVF sections 3.2-3.3)
      After every acoustic sub-step each particle is shifted by dr = -2 alpha h^2 sum_j grad W_ij V_j
      (alpha = transport_coefficient, default 0.2), towards a uniform spacing, against the
      clustering and voids of tensile instability; velocities are untouched, so linear momentum
      is exact. Surface particles (position divergence -sum r_ij . grad W_ij V_j below 0.75 d, or
      within h of one) are not moved by TVF and are moved along the surface only by UTVF (normal
      B_i g_i / |B_i g_i|); none with a divergence below 0.6 d. TVF's sums count the analytic walls'
      mirror images and a fluid's coupled solid particles as neighbours (its particles next to a
      wall are kept at their spacing from it, not frozen as surface particles); UTVF's count the
      body's own particles, as the paper's. For fluids and solids alike (not
      wall bodies, nor total-Lagrangian ones, whose neighbours are those of the reference). Costs two neighbour passes per sub-step; the diagnostics'
      surface_particles counts the particles below 0.75 d, which voids and cracks raise.
      transport_carries_velocity = 1: the shift carries the velocity, v_i += L_i dr_i (the
      velocity field's value at the new position to first order, L the body's velocity
      gradient), and UTVF's sums take the walls' mirror particles too (TVF's always do). A shift alone holds the particles near a lattice while the flow
      shears them and leaves their velocities behind (the role of Adami, Hu and Adams 2013's
      extra stress rho u (u~ - u)): with the walls' images but without the velocity carried the
      lid-driven cavity's vortex died; with both, at h = 2 dp, its profiles are within 1.2-2.5 %
      of Ghia et al.'s at L/dp 40 and 0.5 % at 60, and no pair closes up at a wall (without:
      pairs 1e-4 dp apart). Linear momentum is then not exact. Needs a velocity gradient
      (refused for a fluid under gravity). The cavity wants h = 2 dp with it: its largest
      deviation from Ghia et al.'s is 0.27 at h = 1.3 dp (L/dp 40: the vortex dies), 0.09 at
      1.5, 0.06 at 1.7 and 0.018 at 2 (L/dp 30; bench/VALIDATION.md, "Viscous flows without the
      Riemann solver's dissipation").

   PERIODIC (sps_world_def.periodic[3], periodic_origin[3]; chapter >>periodic)
      periodic[a] = L > 0 [m] makes axis a repeat with period L from periodic_origin[a]: a
      particle that leaves the box [origin, origin + L) comes back at the other side (positions
      are moved back at each configuration update and after each step, so outputs, VTK and
      diagnostics read positions in the box), and every pair sees its nearest image (the
      neighbour search, every pass, walls' images, fluid-structure, contact and diagnostics).
      Fluid, elastic, J2, granular and wall bodies work across the boundary and may straddle it
      (tested: a body across it moves as the same body in the middle, to round-off; a fluid
      crossing it keeps its momentum). L is at least 3 supports (6 h); a 2D world has no
      periodic z; walls may only be parallel to the periodic axes (a channel: periodic x, walls
      of normal +-y). Refused in a periodic world: total-Lagrangian bodies (their reference
      configuration has no images), free rigid bodies, frozen_geometry. A body's displacement
      (x - X) includes the periods it crossed; gravity's potential -m g.x jumps by m g L at a
      wrap (the energy watchdog accounts for it). A world without periodic axes runs none of it
      (its neighbour loops are compiled without the image). Examples: poiseuille, taylor_green.

   OPEN BOUNDARIES (sps_body_add_zone, sps_zone_def; chapter >>open boundaries)
      Boxes [lo, hi) [m] on a body where particles leave or enter the world, in the buffer-zone
      form of Lastiwka, Basa and Quinlan 2009. SPS_ZONE_KILL (any fluid, granular or
      updated-Lagrangian solid body): the body's particles in the box are removed (a drain).
      SPS_ZONE_INFLOW (fluids): the box is filled with the body's lattice at once and its
      particles move at the prescribed velocity (velocity_fn(x, t), or the constant velocity
      [m/s]; evaluated at each advection step); one that leaves the box on the domain's side
      (direction along axis) becomes fluid, and a new one is created a box depth behind it, one
      lattice spacing behind the last of its row, with its density: the creation rate is the flux
      over the particle volume dp^dim. SPS_ZONE_OUTFLOW (fluids): fluid that enters the box
      becomes buffer; a buffer particle is held at the outlet pressure (pressure [Pa], gauge as
      p = c0^2 (rho - rho0); density rho0 + p / c0^2) and at the mean velocity of the fluid within
      2h upstream of the box in its dp-wide bin of the cross-section (zero gradient along the
      axis: a velocity frozen at entry would hold fluid that starts at rest there as a plug), and
      is removed when it leaves the box downstream. The pressure condition is a Dirichlet one
      carried by a full kernel support of held particles: the fluid next to the box sees the
      outlet pressure, and the boundary lies within two spacings of the box's face (measured:
      a channel's pressure line meets p_out within 5 %, bench/VALIDATION.md). A zone's depth along
      its axis is at least the kernel support 2h; defaults: kind KILL, axis 0, direction +1,
      velocity 0, pressure 0. Fill the domain flush with the inflow box (the lattices continue).
      The particle count changes only at the start of an advection step, before the
      configuration update: removed particles are squeezed out of every array, their order kept,
      and the ids renumbered in creation order, so ids stay 0..n-1 and unique (a particle's id
      changes when an older one is removed: follow particles by id between removals only); new
      particles are appended with the next ids. The arrays grow by half when full, at a step; call
      sps_world_reserve(w, n) to size them (and, at the next step, the neighbour storage and the
      zone bodies' own arrays) ahead, so that no step allocates. sps_world_zone_counts tells what
      each zone created and removed; the field row "zone" (-1 none, else the zone's index) is in
      sps_world_field_by_name and the VTK files. Refused: a box inverted or not finite, reaching
      behind a wall or across a periodic axis's box, an inflow or outflow along a periodic axis,
      a flow zone on a body that is not a fluid, any zone on a total-Lagrangian, free rigid or
      wall body, zones with observers or SPS_ROTATION_PAIR bodies (both hold particle ids), a
      velocity or pressure that is not finite (and a velocity_fn that returns one, at the step).
      The energy watchdog starts its account again at every step (energy flows in and out)
      and counts the work of the buffers' held velocities as prescribed work (sps_diagnostics). A
      transport correction (TVF, UTVF) leaves buffer particles where their zone moves them.
      Cost: one pass over the zone bodies' particles per advection step (a step that creates or
      removes particles costs about 5 % more than one that does not, bench/open_cost.c); a world
      without zones runs none of it. Restart: the zones are part of the fingerprint (each def
      item, velocity_fn by whether it is set), the particle counts of the state are read from the
      file (the program builds the scene as it was built, then restores). Above Re of a few
      the fluid needs TVF (without it Turek and Hron's channel at Re 100 clustered within 2.4 s)
      and a positive pressure everywhere: set the outlet pressure above the flow's suction
      (about rho u_max^2 / 2 below the outlet's past an obstacle) and start the fluid at it
      (sps_body_set_pressure), as fluid in tension pulls away from analytic walls. Examples:
      channel_flow (Re 1-100), turek_hron (Re 100-200).

   GRANULAR (material.kind = SPS_MATERIAL_DRUCKER_PRAGER; UTVF sections 2.3, 3.1.3; chapter
   >>material: Drucker-Prager)
      Elastic-perfectly plastic soil: the linear elastic law (c0 = sqrt(K/rho0)), the cone
      f = alpha_phi I1 + sqrt(J2) - k_c and the potential g = alpha_psi I1 + sqrt(J2) (UTVF eqs.
      11-13; material.granular.cohesion c [Pa], friction_angle phi and dilatancy_angle psi [degrees]),
      the constants fitted to Mohr-Coulomb as material.granular.yield_cone says (sps_yield_cone). The
      default, SPS_CONE_PLANE_STRAIN, is Mohr-Coulomb's strength in plane strain with the
      body's dilatancy (alpha_phi = sin phi / 3, k_c = c cos phi for psi = 0), so a slope stands
      at phi; the papers' cone (UTVF eq. 14, SPS_CONE_PAPERS: alpha_phi = tan phi / sqrt(9 +
      12 tan^2 phi), k_c = 3c / sqrt(9 + 12 tan^2 phi)) is exact in plane strain only for
      associated flow (psi = phi) and acts as 19.6 / 28.7 / 37.1 degrees for phi 20 / 30 / 40
      with psi = 0. The 3D cones through Mohr-Coulomb's compression and extension meridians
      and their mean are there too (bench/VALIDATION.md, "The yield cone").
      The whole stress sigma = tau - p I is integrated, 3 x 3 also in 2D (plane strain keeps
      sigma_zz): each sub-step the Jaumann rate 2G dev(D) + K tr(D) I + W sigma - sigma W less
      the plastic flow gamma' (3K alpha_psi I + G s/sqrt(J2)) on the cone (eq. 13, gamma' >= 0),
      plus the stress diffusion, then the reference code's return mapping: the tension cut-off
      at the apex I1 = k_c/alpha_phi, then the deviator scaled back onto the cone. p is -I1/3
      of that stress, not a function of density; the density follows the pressure,
      rho = rho0 + p/c0^2 (the elastic volume change; with psi = 0 plastic flow keeps volume):
      integrated by the continuity equation instead, the cohesionless front particles of a
      column collapse expanded to a negative density. The momentum equation is the divergence
      of sigma with the Riemann solver's dissipation, limited by beta = min(20 d max(-v_ij.e_ij
      /c0, 0), 1) (UTVF section 3.1.3: none while particles separate), the divergence divided
      by the lattice's kernel-gradient moment c = -(1/d) sum_j r_ij dW_ij V_j (0.974 for the
      Wendland kernel at h = 1.3 dp in 2D; the correction B_i of a particle inside a lattice),
      without which a layer at rest balanced its weight only at 1/c of its geostatic stress
      and oscillated about it (+3.1 % at mid-depth). No hourglass penalty by default, as in
      the paper. Hourglass control, shear = SPS_SHEAR_GNO_A (or GNO; rotation mean or per
      particle): ANG's penalty acts between particles whose stress update was elastic; a
      particle on the cone (flowing, or a free grain at the apex) takes a penalty factor 0 and
      drops its stored penalty, so the penalty holds the zigzag mode of a layer at rest and
      leaves flow alone (J2's |s|/|s_trial| left it on in flow: C4 clustered 521 particles).
      It is not the default: C4 at L = 0.1 shot a particle off at 0.60 s with it. The other
      shear values are not used. Stress diffusion
      (Feng et al. 2021; material.granular.stress_diffusion = zeta, default 0.1, 0: off): d sigma_i/dt +=
      2 zeta h c0 sum_j (sigma_i - sigma_j - sigma_geo,ij) r_ij dW/(r_ij^2 + 0.01 h^2) V_j, the
      geostatic difference sigma_geo,ij = -rho0 (g . x_ij) [g^ g^ + K0 (I - g^ g^)] left alone so
      a layer at rest keeps its weight; its pair sums are taken in the pressure pass and used
      in the stress update of the same sub-step. Walls act through mirror particles as on a
      fluid (FLUIDS), the images carrying their particle's stress: reflected at a slip wall; at
      a no-slip wall, which takes the shear traction (friction), continued across it by
      equilibrium with the body force (gravity and the body's external acceleration; the images'
      shear then carries the gradient that holds a layer on a slope: chapter >>walls for fluids,
      the granular images' shear); the velocity gradient uses the no-slip image velocity -v_j. A free-slip wall with
      sps_world_set_wall_friction(mu) resists a particle's sliding by Coulomb's mu times the
      wall's normal force on it (the basal friction of a flow on a smooth bed); a grain that
      left the bulk has no stress to take a no-slip wall's shear with, and slides on along it:
      for a floor on which loose grains come to rest, use a free-slip wall with friction
      tan(phi) (examples/column_collapse2d.c --floor coulomb). sps_body_set_geostatic_stress starts a
      layer at rest (K0 = 1 - sin(phi) by default). Fields: "plastic_strain" is the accumulated
      deviatoric plastic strain, sum sqrt(2/3) |dev(d_eps_p)|, "plastic_work" [J] the work of
      the returned stress on the plastic strain increments (the energy account's dissipation),
      "shear_stress" the deviator tau (6 values, with zz in 2D). UTVF and TVF apply as to any
      body (TRANSPORT). Measured (bench/VALIDATION.md, "Granular media that hold their
      shape"): a geostatic block at rest for 2 s keeps its mid-depth stress within 0.6 % and,
      with GNO-A, its hourglass indicator at 0.0000 (by default 0.11: the zigzag mode grows);
      in flow the hourglass indicator reads the deformation, and the diagnostics' zigzag
      (DIAGNOSTICS) tells the zigzag mode (above 1) from flow (C4: 0.2-0.7);
      a grain sent along a floor with wall friction stops where Coulomb's law stops it;
      particles pressed onto a wall still gather in its first row.

   TOTAL-LAGRANGIAN (sps_body_def.solver = SPS_SOLVER_TOTAL_LAGRANGIAN; TL = Ganzenmueller's
   paper, chapter >>solver: total Lagrangian)
      A total-Lagrangian body computes everything in its reference configuration X (the
      positions its particles were added at): neighbours within 2h of X, the correction matrix
      L_i = sum_j V0_j grad W_i(X_ij) (x) X_ij (TL eq. 15) and the corrected gradients
      L_i^-1 grad W_i(X_ij) (TL eq. 14), with V0 = m/rho0. They are built once, at the first
      step (again after particles are added to the world: the sort by body moves the ranges):
      the body's particles are then sorted by reference cell and never re-sorted, and its lists
      are never rebuilt from the current positions, so a pair stays a pair however far apart
      its particles move, and particles that meet do not interact (no self-contact). L^-1 is the
      blended inverse of the updated-Lagrangian B refined by two Newton steps, exact to
      round-off, so F is exact for every affine motion (tested). Each acoustic sub-step, after
      the half drift: the stress pass, F_i = I + sum_j V0_j (u_j - u_i) (x) L_i^-1 grad W_i
      (TL eq. 17), the first Piola-Kirchhoff stress P_i of the body's law, the Cauchy stress
      sigma = P F^T / J and the density rho0/J (TL eq. 3); a barrier; the force pass,
      f_i = sum_j V0_i V0_j (P_i L_i^-1 grad W_i(X_ij) - P_j L_j^-1 grad W_j(X_ji)) (TL eq. 24)
      plus the hourglass force. Its springs (TL eqs. 25-32): particle i holds one to each
      neighbour j, of stiffness k_ij = 1/2 alpha E V0_i V0_j W_ij / X_ij^2 and stretch
      delta^i_ij = (F_i X_ij - x_ij) . x_ij/|x_ij|, E Young's modulus and alpha = material.tl.hourglass_alpha
      (default 50, TL Table 1; 0 turns it off); their energy is Phi = sum_i sum_j 1/2 k_ij
      (delta^i_ij)^2. material.tl.hourglass = SPS_HOURGLASS_VARIATIONAL (the default) applies -dPhi/dx in
      full: TL eq. 32, f_i += -sum_j (k_ij delta^i_ij + k_ji delta^j_ji) x_ij/|x_ij|, a force
      across the pair from the turn of its direction, and TL eq. 24 applied to the hourglass
      stress Pi_i = 1/V0_i dPhi/dF_i added to P_i (not to the Cauchy stress output), since
      delta depends on F_i and F_i on i's neighbours (chapter >>solver: total Lagrangian).
      SPS_HOURGLASS_PAPER applies TL eq. 32 alone, the paper's partial gradient: its stiffness is
      not symmetric and it feeds energy into the motion (bench/VALIDATION.md, D1-D6). Then the
      kick and the second half drift as for any body. No continuity equation is integrated; the
      pressure p = c0^2 (rho - rho0) is still set (output, guards), and the field "shear_stress"
      holds sigma + p I, so that -p I + tau, what the outputs read (von Mises, the VTK stress
      tensor), is sigma. All forces are antisymmetric in i, j: linear momentum is exact; the
      stress force exerts no torque since P F^T = J sigma is symmetric, and the springs' force is
      the gradient of a rotation-invariant energy (the paper's: central), so angular momentum is
      exact too (tested: 1e-15 relative in 2D and 3D over 1000 sub-steps). material.tl.
      artificial_viscosity = q1 > 0 adds Monaghan's linear artificial viscosity between reference neighbours, q1 c_p h
      rho0 V0_i V0_j |dW(X_ij)| (v_ij . x_ij) x_ij / (|x_ij| (|x_ij|^2 + 0.01 h^2)) (the TL
      author's LAMMPS input: q1 = 0.06; the paper's runs: none): it damps the pairs' stretching
      rates only, hourglass modes among them, and keeps both momenta.
      Laws (material.kind; in 2D plane strain, F_zz = 1):
      SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF  S = lambda tr(E) I + 2 mu E, E = (F^T F - I)/2,
                         P = F S (TL eqs. 18-20), energy lambda/2 tr(E)^2 + mu E:E per V0;
                         for small strains it is the linear elastic law.
      SPS_MATERIAL_NEO_HOOKEAN  S = mu (I - C^-1) + lambda ln(J) C^-1 (TL eq. 44),
                         energy mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2 per V0.
      SPS_MATERIAL_J2  (with this solver) the multiplicative elastic-plastic law of the TL
                         frame: F = F_e F_p, Hencky's law in the logarithmic elastic stretches of
                         b_e = F C_p^-1 F^T, the von Mises radial return in them (material.j2:
                         yield_stress, hardening_modulus; chapter >>material: J2 plasticity in the
                         total-Lagrangian frame), state C_p^-1 (field "plastic_metric", less I)
                         and alpha ("plastic_strain"), plastic work as for updated-Lagrangian J2.
                         The hourglass springs use the yield stress instead of E at particles
                         that have flowed (alpha > 0; TL section 4.5).
      with mu = G = E/(2(1 + nu)), lambda = K - 2G/3. Saint Venant-Kirchhoff and Neo-Hookean
      are for total-Lagrangian bodies only, and a total-Lagrangian body takes only these and J2
      (combination rules). Time step: the signal
      speed of a TL body in its reference state is c_ref = c_p omega_max(alpha) / omega_max(0),
      c_p the P-wave speed sqrt((K + 4G/3)/rho0) and omega_max the highest frequency of the
      body's discrete system linearised at its reference state with its hourglass springs and
      without (power iterations at the first step, which approach it from below: times 1.01):
      the springs take the elastic body's margin of the step and no more (the 2D plate runs at
      cfl_acoustic 0.8 and blows up at 1.0 for alpha 0, 10 and 50 alike; at alpha 50
      c_ref = 2.36 c_p); at every configuration update it is
      c = c_ref / s^2, s the body's smallest principal stretch (at most 1), since a direction
      compressed by s has its spacing shrunk by s and its stiffness grown as 1/s^2 (the D3 block
      reached 50 % compression only so). sps_body_material_constants gives c_p before the
      first step, c after. The strain energy of a TL body is the law's, sum V0 psi(F), plus the
      springs' Phi: exact under rotation, and counted by the energy watchdog, which so sees the
      energy the paper's form feeds in (with it and alpha = 50 the A1 plate blew up at 0.43 s and
      the irregular D1 patch after 3.6 breathing periods; alpha = 0 lets zigzag modes grow).
      The def
      fields shear, rotation, zeta, xi, oas_* and track_stress do not apply (the stress is
      always there). Fields of TL bodies: "deformation_gradient" (F, 9 values row-major, 3 x 3),
      "reference_correction" (-L^-1) and "corrected_piola_stress" (-(P + Pi) L^-1, the hourglass
      stress Pi of the variational form included). Contact with other
      bodies and walls is the shared contact pass (tested in the restart round trip: a
      Neo-Hookean block thrown at another over a floor wall).
      Damage (material.tl.damage_strain = eps_max > 0; TL section 4.6, chapter >>material: damage in the
      total-Lagrangian frame): each particle carries the damage D in [0, 1] (field "damage",
      VTK array damage, sps_particle_state.damage; saved by sps_world_save, in the last good
      state). While the largest principal Green-Lagrange strain of F_i exceeds eps_max,
      D^(1/3) grows at 0.4 c0 / h (TL eq. 45), c0 = sqrt((K + 4G/3)/rho0) the P-wave speed and
      h the kernel radius 2 h_over_dp dp: D = 1 after h / (0.4 c0) above the threshold; D never
      falls. The positive principal values of the stress are scaled by 1 - D, the compressive ones
      kept (TL eq. 46), so a broken particle carries no tension but resists being pushed into. The
      hourglass springs take (1 - D) E at a damaged particle: the paper degrades the
      stress only, but with E the hourglass springs of broken particles alone kept a broken section
      carrying load (the D6 specimen, bench/VALIDATION.md). Its stored energy is counted as (1 - D)
      V0 psi(F) (the rate model has no potential): the energy account falls by what damage
      dissipates. Costs two 3 x 3 eigen-decompositions per particle and sub-step; a body without
      damage has no damage field and runs as before.

   MODELS AND FIELDS
      A body's model is its material (material.kind: SPS_MATERIAL_ELASTIC, linear elastic;
      SPS_MATERIAL_J2, elastic-plastic (PLASTICITY); SPS_MATERIAL_FLUID (FLUIDS);
      SPS_MATERIAL_DRUCKER_PRAGER, granular (GRANULAR);
      SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF and SPS_MATERIAL_NEO_HOOKEAN, hyperelastic
      (TOTAL-LAGRANGIAN); the material gives c0, G, K, its checks and its stored energy), its
      solver (solver: SPS_SOLVER_UPDATED_LAGRANGIAN or SPS_SOLVER_TOTAL_LAGRANGIAN), its
      stabilisation (shear and rotation) and its transport
      correction (transport: SPS_TRANSPORT_NONE). sps_world_add_body checks each field's range
      and the table of allowed combinations (OAS only in 2D) and resolves the model once into
      the pass kernels the step runs for the body. Only a pass's pair loop is compiled per
      dimension, pair geometry and pair terms, one named function each (e.g.
      sps__continuity_pairs_eno_gradient_2d_wendland, what a profiler shows), its choices
      literals; what the pass does once per lane group after it (the velocity gradient, the
      stress update and return map, the rotation, the stores) is one function per pass compiled
      per dimension, which reads the body's model at run time. Adding a material is its value in
      sps_material_kind, its parameter sub-struct in sps_material_def (if it has parameters),
      its chapter (its row, check, constants, energy, parameter rows) and its case in each
      switch of chapter >>generic, which lists the places; a
      new stabilisation a row in sps__stabilisations and, where its pair terms differ, a pair
      loop of the passes.
      Per-particle arrays are rows of sps__fields (name, components, when needed, housekeeping).
      Every particle has position, velocity, reference position, density, pressure, mass and
      volume; the shear stress, the velocity gradient, the mean-rotation increments and Gray's
      artificial stress belong to the bodies whose model needs them (an ENO body beside an OG
      body carries no stress). Read them by name: sps_world_field_by_name and sps_body_field.
      The material def carries each family's parameters in a sub-struct of its own
      (material.j2, .fluid, .granular, .tl: the field's path names its reader); a field set
      away from its default on a body that does not read it (material.granular.cohesion on an
      elastic body, material.tl.hourglass_alpha on an updated-Lagrangian one, zeta on a GNO-A body, ...) gets one warning from
      sps_world_add_body naming each such field (the reads column of sps__body_def_items);
      fields whose combination cannot work are refused instead (the combination rules).
      What zero means, one rule: a term that can be switched off reads 0 as off (damping,
      material.tl.hourglass_alpha, .artificial_viscosity, .damage_strain,
      material.granular.stress_diffusion, .cohesion, material.j2.hardening_modulus,
      material.viscosity, friction, contact_damping); a coefficient for which 0 would
      be meaningless reads 0 as its published default, and SPS_AUTO (= 0) spells that: zeta
      (0.7 d + 2.1), xi (2), transport_coefficient (0.2), escape_distance (10 body sizes).

   CONTACT (chapter >>contact)
      Bodies touch each other when both defs have contact = 1 (the default) and no
      sps_world_set_contact(w, a, b, 0) separated the pair. A particle near another body gets the
      contact density sigma_i = sum_j W_ij V_j over the other body's particles within 2h, and the
      repulsion F_i = -V_i sum_j K_ij (sigma_i + sigma_j) dW_ij e_ij V_j, K_ij the harmonic mean of
      the two bulk moduli (the reference code's law). It is the exact gradient of the contact
      energy (K/2) sum_i V_i sigma_i^2 (not included in the strain energy), and antisymmetric:
      linear and angular momentum are exact. Pairs are found at each configuration update
      through one cell grid over the world (indices ordered by cell; nothing is re-sorted), so
      results are bit-identical for any thread count. A scene with one body and no walls runs
      no contact code. Self-contact of a body is not modelled (it would take the same pairs
      between particles of one body that are far apart in the reference configuration).
      Analytic walls (sps_world_add_wall, sps_world_add_box_walls): the solid half-space is a
      continuum of the same contact law, its sums the kernel integrals over the half-space
      (sigma_i += int W dV) and the wall plane (F_i += 2 V_i K sigma_i W_plane(d) n), tabulated
      once; a no-slip wall adds a drag -2 V_i rho0 c0 W_plane(d) v_t on the tangential velocity.
      They cost a distance test per particle and wall.
      Where bodies rest (sps_world_def.contact_rest): a body's surface lies dp/2 outside its
      outer particles (a box filled by sps_body_add_box from lo to hi has its surface at lo and
      hi). SPS_CONTACT_REST_FLUSH, the default: a wall pushes only with the contact density above
      its value at dp/2, and another body with the density above what a flush lattice of the same
      spacing gives a row dp away (the sum over its rows, computed once), so bodies filled flush
      on walls and on each other (their boxes sharing a face) start at rest: three blocks stacked
      flush on a floor without gravity stay at rest to round-off (in 2D and 3D, and shifted by a
      quarter or half dp along the face), and a block thrown at 1 m/s with mu 0.3 filled flush stops within 0.1 %
      of v0^2 / (2 mu g) (bench/VALIDATION.md, "The natural set-up"). Under gravity an elastic
      body filled stress-free still settles under its own weight (its sag, not the contact).
      SPS_CONTACT_REST_KERNEL: the papers' law above, every bit of the density pushes: a body
      rests about 1.5 dp off a wall (its first row 2 dp above it) and filled flush it is thrown
      off at a tenth of its sound speed; the examples that reproduce a paper's contact figures
      (ball_plate2d, balls3d, rings2d, impact2d, the Taylor bars, punches, debris_barrier3d)
      and bounce (its recorded figures) use it (--contact-rest flush|kernel).
      Friction (sps_body_def.friction, sps_world_set_wall_friction): Coulomb's law with a
      velocity-regularised stick. A contact's coefficient is the geometric mean sqrt(mu_a mu_b)
      of its two sides (a body and a wall, or two bodies; Box2D's rule: a frictionless side
      makes the contact frictionless). Each contact force of the penalty (a particle and a wall,
      or two particles of touching bodies) gets a tangential force against the tangential
      relative velocity v_t, F_t = -min(D |v_t|, mu F_n) v_t/|v_t|, F_n the contact's normal
      force: sliding, |F_t| = mu F_n; sticking, the drag D holds v_t near 0. At a wall D = rho_i
      V_i / (2 dt), the strongest drag the explicit kick carries (it halves v_t in a sub-step);
      the no-slip wall's impedance drag 2 V_i rho0 c0 W_plane(d) instead let a block on a
      10-degree slope with mu = 0.3 creep 4.5 % of its frictionless distance in 1 s, this one
      0.36 % (bench/VALIDATION.md, "Friction"). Between bodies D = -2 V_i V_j Z_ij dW_ij, Z_ij
      the harmonic mean of rho0 c0 (a stronger drag summed over a particle's many partners
      would exceed the kick's bound); the pair's friction forces are equal and opposite, so
      linear momentum stays exact (tested to 1e-12). Why not an elastic stick (a tangential
      spring per contact): it needs a history per pair and per particle and wall, carried over
      list rebuilds and restarts, for a creep the drag keeps below 1 %. SPS_WALL_NO_SLIP keeps its
      meaning: the impedance drag with no Coulomb bound (mu = infinity); wall friction on it is
      refused. Friction acts on the particles, so a disc sticks at its outer particle layer
      (radius R - dp/2), not at its surface: rolling and spin-up rates carry an O(dp/R) error
      (2D disc on 30 degrees, mu 0.5: a 3.9 % low at R/dp = 10, 2.0 % at 20). Fluids and
      Drucker-Prager bodies have no friction (walls act on them through mirror particles). A
      scene without friction runs none of it (bit-identical, pinned).
      Normal contact damping (sps_body_def.contact_damping = zeta in [0, 1]): the penalty is
      elastic (a dropped rubber disc bounced on at 3 s even with eta 200 Pa s); a dashpot on the
      normal relative velocity v_n of each contact force takes the bounce's energy: at a wall
      F_n,i -= zeta 2 V_i rho0 c0 W_plane(d) v_n (the no-slip drag's impedance, on the normal
      velocity), between bodies the pair friction's drag zeta_ij D on (v_i - v_j) . e_ij,
      zeta_ij = (zeta_a + zeta_b) / 2 (a damped ball on an undamped floor body still loses
      energy). The pair's forces are equal, opposite and central: linear momentum stays exact
      (tested to 1e-12), and angular momentum with it. While a contact opens the dashpot is
      bounded by the repulsion (a contact cannot pull). Its work goes to "viscous_work" and
      sps_diagnostics.viscous_work. Why a damping ratio of the contact's own impedance and not a
      restitution e converted the DEM way (zeta = -ln e / sqrt(pi^2 + ln^2 e)): that conversion
      holds for one mass on one spring-dashpot, but the dashpot acts on the contact layer's
      particles, in parallel with the stiff penalty, not on the body's mass: zeta = 1 (e = 0 by
      DEM) gives a measured restitution 0.83 for the rubber disc, 0.54 for two blocks meeting
      head on, 0.74 for a block on a wall at zeta 0.5 (bench/VALIDATION.md, "Friction and
      material damping"). zeta is dimensionless and its bound 1 keeps the explicit kick stable
      (the no-slip drag's size); the body-level restitution is a measured figure of the scene.
      Bodies without it run none of it (bit-identical, pinned).
      Wall bodies: material.kind = SPS_MATERIAL_RIGID. The particles keep the velocity given to
      them (sps_body_set_velocity, constraints) and move with it; they take part in contact only.

   FREE RIGID BODIES (material.kind = SPS_MATERIAL_RIGID_DYNAMIC; chapter >>material: free rigid
   bodies)
      Box2D's three kinds: static (the analytic walls), kinematic (wall bodies, prescribed motion)
      and dynamic: a free rigid body, whose particles move as one body by Newton-Euler in the
      world's sub-steps. Fill it like any body (box, SDF, relaxed, particles). Its mass and
      inertia come from its particles, each a cell of its volume V_i and mass rho0 V_i (the
      inertia sum m_i (|r_i|^2 1 - r_i r_i^T) plus each cell's own m_i V_i^(2/d) / 6), or from
      sps_body_set_mass_properties (mass > 0, a symmetric positive definite tensor). Each
      sub-step follows the particles' drift-kick-drift: the half drift moves its centre by dt/2
      v and turns it freely for dt/2; the force and torque on it are the sums of the forces its
      particles received (contact with bodies and walls, Coulomb friction and the contact
      dashpot, the fluid's coupling force, external accelerations and the drag, the force of
      sps_body_set_force) plus M g; the kick updates v and the angular momentum L; the second
      half drift. The free turn is the implicit midpoint rule for Euler's equations in the
      principal frame with a Cayley rotation: it keeps |L| and the rotational energy exactly
      (quadratic invariants) and leaves the world's L untouched, so an isolated body keeps its
      energy to 1e-13, its linear momentum and its angular momentum about its centre of mass to
      the last bit over 1e5 sub-steps (tested), and the
      intermediate axis flips at the closed form's period (examples/rigid_spin: 0.00 %). In 2D the
      turn is exact. It runs no stress, continuity or shear pass and builds no neighbour list;
      the time step sees its speed and its contact stiffness c0 = sqrt(K / rho0) (E and nu set K,
      the stiffness of its contacts; the fluid coupling's added-mass speed is not taken: the
      body's mass is not one particle's). Friction acts at the contact surface: the slip is the
      velocity of the contact point (on a wall's plane below the particle, or a pair's midpoint)
      as a point of the body, v + omega x r, the force acts there (its couple joins the torque),
      and the stick drag is the body's effective mass at the contact over the contact particles
      (a rolling disc on the particle layer's slip rolled on R - dp/2 and lost energy). A disc
      and a ball on a 30-degree slope roll within 0.2 % and 1 % of 2/3 and 5/7 g sin theta (R/dp
      20 and 10), a box slides and sticks at Coulomb's law, a thrown disc leaves rolling (omega R
      / v_t = 1.005); a box floating in water stands 4 % high, the coupling's pressure on a held
      body being 3.7 % above rho g V at h = 1.3 dp (bench/VALIDATION.md, "Free rigid bodies").
      damping > 0 damps its v and L (dv/dt = F/M - c v, exactly per sub-step). API: sps_body_rigid_state (pose, velocities, L, mass, inertia, the last
      sub-step's force and torque), sps_body_set_rigid_pose, sps_body_set_rigid_motion and
      sps_body_set_velocity (the rigid part of the velocities given), sps_body_apply_impulse,
      sps_body_set_force (at a material point, until set again), sps_body_lock_axes
      (translation and rotation per world axis: a wheel on an axle, a body that only
      translates), sps_body_set_acceleration and the drag. Diagnostics take its kinetic energy
      1/2 M v^2 + 1/2 omega . I omega, its momenta and its potential energy from the body's
      motion (not its particles'), which the energy watchdog counts; restart files carry its
      motion; VTK shows its particles. Joints are not modelled (a locked body turns about its
      centre of mass only).

   DAMPING AND EXTERNAL ACCELERATION (sps_body_def.damping, material.viscosity,
   sps_body_set_acceleration)
      Material damping: material.viscosity = eta > 0 on an elastic, J2, Saint Venant-Kirchhoff
      or Neo-Hookean body is a Kelvin-Voigt viscosity (chapter >>material: Kelvin-Voigt): the
      viscous stress sigma_v = 2 eta D + eta tr(D) I (Lame viscosities lambda_v = mu_v = eta: the
      volumetric part, eta (d + 2)/d, comes with the central pair force that carries it, the
      ENO Laplacian (2 (d + 2) eta / rho_i) sum_j (v_ij . e_ij) dW_ij / r_ij V_j e_ij, for every
      shear formulation and the total-Lagrangian bodies). It vanishes for any rigid motion (a
      damped body falls at g and spins on, tested), conserves linear and angular momentum, and
      its dissipated work, with that of the Riemann dissipation of the same body, is the field
      "viscous_work" and sps_diagnostics.viscous_work, part of the energy account. The 2D plate's
      first mode decays at the modal damping ratio of a viscoelastic beam, zeta = omega E'_v /
      (2 E'), E'_v = eta (dE'/dlambda + dE'/dmu) (bench/VALIDATION.md, "Kelvin-Voigt"). Cost: an
      explicit viscous term needs dt < d / (4 (d + 2) nu S), nu = eta / rho0, S ~ 3.5 / h^2 in
      2D: for nu / h above about c0 / 30 it, not the sound speed, sets the acoustic step.
      Numerical damping (damping):
      Damping is numerical, not a property of the material: it is there to bring a loaded body
      to its static equilibrium (a quasi-static run: load, let it settle, read the state). A
      body with damping c > 0 [1/s] integrates dv/dt = a - c v in the kick exactly over each
      sub-step for the kick's acceleration a, v <- e^(-c dt) v + (1 - e^(-c dt))/c a: stable
      for any c dt, and the equilibrium it reaches (a = 0 at v = 0) does not depend on c. Every
      mode decays at least as e^(-c t/2); a mode of angular frequency omega is critically damped
      at c = 2 omega (the 2D plate's first mode: c = 49/s; in examples/cantilever_sag.c its sag
      changes by 1.4e-4 of itself from t = 0.5 to 0.6 s). It acts on the absolute velocity, so it brakes a rigid motion too (a free
      body falls at |g|/c at most): damp bodies that are held, not bodies in free flight. Why
      not the velocity relative to the body's mean: that leaves the mean velocity undamped, and
      a cantilever's first mode has 61 % of its kinetic energy in it (its effective modal mass),
      it would still brake a rotation, and it needs a sum over the body in every sub-step (a
      barrier). The kick is chosen per body, not per particle: an undamped body (the default)
      runs the kick it ran before damping existed, bit for bit (tests/pinned.c).
      External acceleration: fn(x, x0, v, t, a, user) is called for every particle of the body
      in every acoustic sub-step, where the kick acts: x is the position half-drifted to the
      middle of the sub-step, t that middle (so a load that varies in time or space is
      integrated to second order, like the internal forces), v the velocity before the kick (a
      velocity-dependent force lags half a sub-step). a is added to gravity; "pressure_acceleration"
      then includes it. A granular body calls fn once more, in the contact pass, for each
      particle within 2h of a no-slip wall (its images' shear is continued by the body force). Why every sub-step and not once per advection step: at rest an advection
      step holds up to max_substeps (100) sub-steps, so a stored load would lag by 100 of them (a
      staircase in time, and a drag evaluated 100 sub-steps late), while a call costs about
      10 ns a particle (2D plate, H/dp 10, 1 thread: 3.98 s against 3.81 s with the same load as
      gravity; shared machine). Thread safety: with OpenMP the threads of the step call fn at
      once, each for its own particles: fn may read user but must not write to anything shared
      nor call the library on this world. If a depends only on fn's arguments (and data that
      does not change during the step), results are bit-identical for any thread count.

   DIAGNOSTICS (sps_world_diagnostics)
      kinetic energy     sum 1/2 m |v|^2 (a free rigid body: 1/2 M |v|^2 + 1/2 omega . I omega)
      strain energy      sum V (tau:tau/(4G) + p^2/(2K)); the shear part needs track_stress.
                         Total-Lagrangian bodies: sum V0 psi(F) plus the hourglass springs' Phi.
      contact energy     sum V (1/2 K sigma^2 + K sigma_w^2): the potential of the contact forces
                         (sigma: contact density from the other bodies, sigma_w: from the walls).
      potential energy   -sum m g.x over the deformable bodies (gravity).
      prescribed work    work done on the deformable bodies by moving velocity constraints, rigid
                         bodies and external accelerations (counted while the energy watchdog
                         is on).
      plastic work       sum over J2 particles of the energy their return maps dissipated
                         (PLASTICITY); max_plastic_strain the largest alpha.
      viscous work       sum over Kelvin-Voigt bodies (material.viscosity > 0) of the work their
                         viscous and Riemann dissipation forces dissipated (DAMPING), and over
                         bodies with contact_damping of the work of the contact dashpot (CONTACT).
      The account kinetic + strain + contact + potential + plastic work + viscous work - prescribed work is
      conserved by the continuous equations; the Riemann dissipation and no-slip walls lower it. Its growth is
      numerical: the energy watchdog (ERRORS) reports it. The shear part of the strain energy,
      from the Jaumann-rate stress, is not conserved under large rotations (it over-reads by
      5-24 % in a cantilever's large bending), so the watchdog leaves it out.
      linear momentum    sum m v;  angular momentum sum m x X v (about the origin; z in 2D)
      hourglass          sum_pairs |u_ij - 1/2 (Gu_i + Gu_j) r_ij| / sum_pairs r_ij, where u is the
                         displacement from the reference position and Gu_i its B-corrected
                         gradient: the non-affine (zigzag) part of the displacement per unit pair
                         distance. Zero for any affine motion (including rigid rotation), about
                         1e-4..1e-3 for smooth bending, >1e-2 when particles zigzag. It
                         measures deformation, not zigzag, in a flow (granular, fluid), where
                         the displacement from the start is no longer smooth.
      zigzag             sum_pairs |v_ij - L_ij r_ij| / sum_pairs |L_ij r_ij|, L_ij = 1/2 (Gv_i + Gv_j)
                         with Gv_i the B-corrected velocity gradient: the relative velocity of
                         neighbours that the velocity gradient does not explain, per unit of
                         the one it does, at this instant, whatever the deformation so far. 0
                         for an affine velocity field (shear, rotation, stretch, translation;
                         0 also when nothing moves), 0.2-0.7 in the flowing granular collapse
                         C4, above 1 when the particle-scale zigzag mode outweighs the flow
                         (1.9-9.8 in a granular layer at rest without hourglass control). At
                         rest, or in free fall, there is no gradient to compare with and any
                         motion reads high: read it with max_speed (bench/VALIDATION.md,
                         "Granular media that hold their shape").
      min spacing        smallest neighbour distance / dp: clustering when it falls below ~0.5.

   ERRORS
      Functions return sps_result (SPS_OK = 0, negative = error); sps_result_string() names it.
      Each world keeps the message of its last error (sps_world_last_error); there is no global
      error state. Every error of a call on a world sets that message and sends it to the world
      def's log callback (default: stderr); sps_world_create's errors go to the log, and
      sps_world_def_check(def, msg, size) returns them to the caller.
      Messages read "field = value, allowed range". A NULL world never crashes a call: fallible
      calls return SPS_ERR_INVALID_ARG, queries a neutral value (0, NULL, -1).
      Validated (SPS_ERR_INVALID_ARG, every broken rule of a def listed at once):
      world def: cookie (start from sps_default_world_def), dim (2, 3), dp [1e-9, 1e9] m,
      h_over_dp [1, 3], kernel, stepping, cfl_acoustic (0, 1], cfl_advection (0, 1],
      max_substeps [1, 10000], gravity finite, frozen_geometry 0/1, neighbor_capacity [1, 64],
      threads [0, 1024], escape_distance >= 0 (INFINITY allowed), keep_last_good_state 0/1,
      report_fragments 0/1, energy_growth_limit > 0 (INFINITY: off), energy_growth_stops 0/1,
      allocator (both or neither). Body def: cookie, material.density and .youngs_modulus
      (finite > 0), .poisson_ratio (-1, 0.5), the derived sound speed and shear modulus (finite,
      c0 > 0), for J2 material.j2.yield_stress (finite > 0) and .hardening_modulus (finite >= 0), the
      material and shear combination (J2 not with ENO, ENO-A), shear (0..5; OAS only in 2D),
      rotation (0..3), zeta [0, 100], xi [0, 100], penalty_in_pressure_pass 0/1 (1 not with
      rotation = pair or Drucker-Prager), oas_epsilon [0, 1], oas_exponent [1, 12], track_stress 0/1,
      damping finite >= 0 (0 for a wall body), friction finite >= 0 (0 without
      contact and for fluid and Drucker-Prager bodies), material.viscosity finite >= 0 (0 for
      wall and Drucker-Prager bodies), wall friction (finite >= 0, an existing free-slip wall),
      solver 0..1, material.tl.hourglass_alpha [0, 1000], .hourglass 0..1, .damage_strain [0, 100]
      and .artificial_viscosity [0, 1] (> 0 with the total-Lagrangian solver only),
      for Drucker-Prager material.granular.stress_diffusion [0, 1], .cohesion >= 0,
      .friction_angle [0, 90), .dilatancy_angle [0, friction_angle], .yield_cone 0..4, for a
      fluid material.fluid.dissipation 0..2, Saint Venant-Kirchhoff and Neo-Hookean with the total-Lagrangian
      solver only and that solver with those laws or J2 only. Calls: NULL pointers (defs, outputs,
      callbacks, points, paths), body and observer handles (of this world: a handle of another
      or a destroyed world is refused), boxes (finite, lo < hi), particle counts (a world holds
      at most 2e8), coordinates, volumes, points and velocities (finite, volumes > 0),
      constraint masks (1..7), particle ids [0, n), field enums, t_end (finite); zone defs (OPEN
      BOUNDARIES: cookie, kind 0..2, the box, axis [0, dim), direction +-1, velocity and pressure
      finite, a flow zone's depth >= 2h, the body's kind, walls, periodic axes, observers).
      Stepping: a world without particles, or a body without particles, gives SPS_ERR_STATE
      naming the body (a box narrower than dp holds no lattice point); at the first step, a
      deformable body with particles on the solid side of a wall gives SPS_ERR_STATE naming the
      wall, the body and the count (a normal that points into the body). sps_world_advance to a
      t_end before the world's time is SPS_ERR_INVALID_ARG; sps_body_set_velocity or
      _set_rigid_motion on a body without particles SPS_ERR_STATE.
      Warnings (log level 1, the call returns SPS_OK; the last error is untouched): a fill that
      adds no particle, a constraint box that matches none, a Poisson ratio within 1e-3 of 0.5
      (with the factor it shortens the time step by), bodies that can touch (or a body and the
      walls) moving at more than 0.2 c0 relative to each other (once per world), a CFL number
      above the measured stable limit of a body's formulation (STABLE CFL), the energy
      watchdog, threads > 1 in a build without OpenMP, a Drucker-Prager friction angle in
      (0, pi/2] (radians given for degrees), an sps_world_advance of more than 1e10 particle
      sub-steps (the estimated count), with report_fragments = 1 a particle that broke off
      its body, gravity along z in a 2D world, a friction above 2 (body or wall: the angle in
      degrees it likely is, with its tangent), a fluid or granular body whose particles come
      within the kernel of a wall leaving a slot of 3/4 dp or more (a fill not a multiple of dp), and a
      fluid that churns (its kinetic energy rising at least 2-fold three quarter-seconds in a
      row while below 1e-3 of its weight times its height, which the energy account cannot see:
      the water settles as it churns). A warning whose text was issued before is counted in
      sps_diagnostics.warnings, not printed again; sps_world_destroy logs how often each
      recurring one was issued.
      Run-time guards (SPS_ERR_UNSTABLE; the message names time, body, particle and value):
      - at every configuration update (once per advection step, ~0.25 % of its time): a
        non-finite velocity, position, pressure, shear stress or accumulated shear acceleration,
        or a density that is not finite > 0;
      - a particle farther than escape_distance beyond its body's size from the body's current
        centre of mass (default: 10 body sizes, at least 100 dp), so a body that travels or
        spins is never stopped; report_fragments = 1 warns (once per body) when a particle
        breaks off its body;
      - energy watchdog, at most every 10 sub-steps: the energy account (DIAGNOSTICS; without
        the shear strain energy, so a lower bound) above its start by more than
        energy_growth_limit (default 5 %) of the largest kinetic + volumetric + contact energy
        seen: a warning (log level 1) naming time, growth, the body that gained most and the
        likely cause with its fix (the mean or per-particle rotation, a CFL number above the
        measured stable one, a formulation without hourglass control, particles behind a wall),
        once; with energy_growth_stops = 1, SPS_ERR_UNSTABLE. The default warns and goes on: the
        user scenes with the default body never reach 2 % (bench/VALIDATION.md), and a game or
        demo loop should not die of a warning; every check above the limit is counted in
        sps_diagnostics.energy_growth_events (and the largest growth in .energy_growth), so a
        run that returned SPS_OK can still be told from a clean one. A run past its stable
        time step or formulation stays finite and would return SPS_OK silently (the 3D
        cantilever at cfl_acoustic = 0.8, the spinning plate with ENO-A at 100 rad/s; tested).
        A new start is taken after every call that changes the state on purpose (velocities,
        particles, constraints, walls, contacts);
      - an acoustic step below 1e-3 of its value at rest (CFL_ac h / c0), i.e. a particle faster
        than 999 c0 (named with its speed); a speed whose square overflows; a step that makes
        no progress; a particle with more neighbours than neighbor_capacity allows (clustering).
      After SPS_ERR_UNSTABLE the world is stopped: further steps return SPS_ERR_UNSTABLE (quoting
      the first failure), everything else works. With keep_last_good_state = 0 (default) the
      state is the one at the error (it may hold NaN; diagnostics need the neighbour lists and
      return the error if the failure was theirs). With keep_last_good_state = 1 the world is
      rolled back to the last configuration update before the failure (positions, velocities,
      densities, pressures, stresses, plastic strains and work, and the time; measured cost of
      the copy: ~0.05 % of the step time, 16 reals per particle), so diagnostics, sps_world_particle and
      sps_world_write_vtk show the last good state, and sps_world_time() tells its time.
      sps_world_validate(w, msg, size) checks a whole world at any time (debugging): the defs,
      empty bodies, every particle's state, constraints, observers and the stopped flag, and
      lists every broken rule.

   OUTPUT (sps_world_write_vtk, sps_world_write_vtk_ex, sps_world_write_vtk_series)
      Legacy VTK POLYDATA, a vertex per particle, its point data in one FIELD block (VTK's
      legacy reader shows every array of it with its default settings; of SCALARS and VECTORS
      blocks it shows only the first of each). The arrays are the rows of sps__vtk_arrays: a row
      of sps__fields (a per-body field is 0 for the bodies without it) or a value computed per
      particle (displacement, von Mises, the stress tensor), so a new output is one row. ASCII
      by default (9 significant digits); binary (big-endian, as the format requires) writes the
      values exactly, 8-15x faster, at 0.85-0.9x the ASCII size in double and 0.5x in single
      precision (bench/VALIDATION.md). Checked with VTK 9.1's vtkPolyDataReader.
      A time series (sps_world_write_vtk_series) numbers the files name_0000.vtk, ... and lists
      them with their physical times in name.vtk.series, ParaView's file-series JSON (ParaView
      5.5 and later; its .pvd collections take XML data sets only): opening it gives one data
      set with the times on its time slider (checked with ParaView 5.11's pvpython).

   RESTART (sps_world_save, sps_world_restore)
      Callbacks, the allocator and the log cannot be written to a file, so a restart is done by
      the program: it builds the scene again exactly as before (world def, bodies, fills,
      velocities, constraints, walls, contact settings, observers) and calls
      sps_world_restore(w, path) instead of stepping up to the saved time; the run then goes on
      bit for bit as the saved one would have, for any thread count (tested: ENO-A, GNO-A, pair
      rotation, contact with a wall, frozen geometry, the last good state, total-Lagrangian
      bodies (Neo-Hookean with contact, J2; their B_i recomputed from the restored reference
      lists); saved at 1 thread
      and restored at 2, and the other way round). sps_world_save(w, path) writes the state between steps: time, step
      counters, every per-particle array the step carries from one configuration update to the
      next (sps__fields rows marked SPS__CARRIED, so a new field is saved without changing the
      restart code) in the current particle order, each body's mean rotation and spin, the
      kept pair forces, the last good state, the stopped flag and the neighbour lists (so that
      diagnostics right after a restore agree too). The file starts with a fingerprint that
      must match the world: every world and body def field that changes results (all but
      threads, report_fragments, the body's name, callbacks, allocator and user data; one
      table, sps__world_def_items and sps__body_def_items, from which the fingerprint is
      written, checked and named), the particle, body, wall and constraint counts, each body's
      count, and a hash of every particle's body, reference position, mass and constraint; a
      difference is refused (SPS_ERR_STATE) naming the item (e.g. "body 0 ('plate') solver = 0
      in the file, 1 in this world"), before the world is changed. Native byte order and sps_real, both checked; a payload
      checksum refuses truncated or damaged files (SPS_ERR_IO). Size: about the state's own
      size plus one int per neighbour pair (2D plate at H/dp 10: bench/VALIDATION.md).

   GEOMETRY (sps_mesh_load, sps_mesh_from_triangles, sps_mesh_from_rings; chapter >>geometry)
      A body from a file in three lines:
         sps_mesh* m; if (sps_mesh_load("part.stl", NULL, &m, msg, sizeof msg) != SPS_OK) puts(msg);
         sps_body_add_mesh(w, body, m, NULL, NULL, 0, NULL);   // relaxed, body-fitted surface
         sps_mesh_destroy(m);
      The format is told by the content, not by the name: a binary STL by its size (84 + 50
      bytes per triangle: a header that starts with "solid" does not matter), else text: SVG (an
      <svg element), ASCII STL (first word "solid"), Wavefront OBJ (first statement v, f, o,
      g, ...: polygons fanned into triangles, negative indices, vt/vn/groups/materials ignored)
      or an outline (lines "x y" or "x,y", '#' comments, a blank line between rings). SVG: the
      d attributes of <path> (M L H V C S Q T Z, absolute and relative; curves flattened within
      chord_error) and the points of <polygon>; y turned upwards; the coordinates are the
      drawing's units (use scale); arcs, transform attributes and <rect>/<circle>/<ellipse> are
      refused with a message (convert them to paths in the editor). 3D meshes must be closed
      and consistently oriented with outward normals (refused otherwise, naming the edge or the
      signed volume; allow_open and flip accept them); 2D rings must not cross (refused, naming
      the segments); inside is inside an odd number of rings. Degenerate triangles are skipped
      and counted; equal vertices are welded. Every refusal leaves *out NULL and writes a
      message naming the file and the line or triangle; nothing is added to a world.
      Distance: exact to the nearest triangle (segment), found in a bounding-volume hierarchy;
      3D sign from the angle-weighted pseudo-normal of the nearest face, edge or vertex, 2D from
      the crossing parity. The fills need exact distances only within 2h (and the shell) of the
      surface: beyond it they take the sign from a ray's crossing parity, so deep particles cost
      O(log n). Containers: sps_body_add_mesh_shell fills a wall body with `layers` lattice
      layers outside the mesh (a cut at the top keeps a glass open); sps_body_add_mesh fills the
      fluid inside, cut at its level; both on the lattice (k + 1/2) dp, so the fluid's first
      layer stands dp from the wall's.

   MEMORY
      Allocation happens in sps_world_create, when particles, constraints or observers are added,
      and at the first step after particles were added (neighbour lists; the last-good-state
      copy; that step also trims the particle arrays, which adding grows by half, to the
      particles or to what sps_world_reserve asked for). The neighbour slots (and
      SPS_ROTATION_PAIR's pair forces) are sized from what a configuration update counts, an
      eighth more, and grow by the same rule only at a step whose update counts more (a body
      compressed, particles crowding at an impact); they never shrink. A scene in steady state
      never allocates in steps (tested for every shear formulation with a counting allocator).
      A failed allocation returns SPS_ERR_OUT_OF_MEMORY with a message naming what it was for
      and leaves the world usable (tested by refusing each allocation of a scenario in turn).
      Open boundaries (OPEN BOUNDARIES) grow the particle arrays by half at a step when they are
      full, unless sps_world_reserve sized them ahead. sps_world_diagnostics allocates its
      scratch on first use. The cell grid is capped at about 4 cells per particle and wraps
      around (periodic hashing), so a particle thrown far away never grows memory. A 3D bulk
      (the spinning cube, 1e6 particles, double) takes about 2.7 KB a particle with ENO-A's pair
      rotation and 0.94 KB with GNO-A (bench/VALIDATION.md, "Memory per particle").

   THREADING & DETERMINISM
      With OpenMP, each pass is a gather: the thread that owns particle i writes only particle i,
      with no atomics. Within a thread, SPS__LANES consecutive particles (16 doubles or 32
      floats) run side by side in SIMD lanes, each summing its own neighbours in list order, so
      the vector width does not change a result either. Sums (diagnostics, the mean rotation of
      ENO-A) use fixed blocks of particles (the lane groups, for the mean rotation) added in a
      fixed order. Results are bit-identical for any number of threads.
      A world must not be used from two threads at once; separate worlds are independent.

      Repeated runs are bit-identical too (tested, like the thread counts).

   DOES NOT (yet)
      self-contact, damage of updated-Lagrangian bodies; rolling friction;
      a prescribed coefficient of restitution (contact_damping is a damping ratio of the
      contact layer: the restitution it gives is measured, bench/VALIDATION.md); friction on
      the contact surface's velocity for deformable bodies (a thrown elastic disc leaves with
      omega R / v_t 1.09-1.21; free rigid bodies have it); joints between bodies.

   REVISION HISTORY
      0.21.0 (2026-12-07) the walls' mirror images in SIMD lane loops (each image term one inline
                         function, shared with the fluid-structure coupling's solid images; the
                         images that count gathered per lane before their terms; the force and
                         equilibrium passes over the particles near a wall, sixteen at a time):
                         bit for bit, the column collapse at 0.865 of its cost per
                         particle-step, a 3D soil cube 0.84, a dam break 0.91; the energy
                         watchdog names the body whose account grew most, and water at rest
                         fewer than 14 particles deep as the cause (bench/VALIDATION.md,
                         "Shallow water").
      0.20.0 (2026-12-07) memory: neighbour slots sized from the counts at each rebuild (grown
                         by an eighth, never shrunk), the lists found in chunks of lane groups
                         (no per-particle list array), particle arrays trimmed to the scene at
                         the first step (the 3D cube at 1e6: ENO-A 2.7 KB a particle, was 5.9;
                         GNO-A 0.94 KB, was 2.3); the granular stress diffusion summed per
                         particle; bench/pair_once.c (each pair computed once, measured against
                         full lists: not faster here, bench/VALIDATION.md).
      0.19.0 (2026-12-07) materials as modules: each kind's parameters in its sub-struct of the
                         material def (material.j2, .fluid, .granular, .tl; the body def's
                         fluid_dissipation, stress_diffusion, hourglass_alpha, hourglass,
                         artificial_viscosity and damage_strain moved there; restart format 8),
                         its defaults, total-Lagrangian law, stress update and pressure terms
                         reached through >>generic only (bench/material_census.sh); frames
                         continue the advection step the last frame left open; pair loops
                         instanced for the Wendland kernel's geometries, the cubic spline on a
                         generic loop (SPHSOLID_ALL_PAIR_LOOPS); the total-Lagrangian solver's
                         pair table built once, vectorised passes, the time step from the
                         measured highest frequency (the alpha 50 plate 1.26x the ENO-A plate's
                         cost per particle-step, was 4.9x); examples read as scenes.
      0.18.0 (2026-12-07) water at rest: body def lattice (a 2D fluid under gravity at h_over_dp
                         1.3 fills on the hexagonal lattice, on which it stays at rest; the
                         square lattice's rows slide under its pressure; restart format 7);
                         bench/tank_long (the demo tank left running); floating_block's drafts
                         from the free surface and the water's volume; hydrostatic_fsi --dim 3
                         (a periodic breadth: plane strain); dam_break2d and
                         elastic_gate against their experiments (bench/dam_break_experiments.csv,
                         bench/lobovsky2014_h300.csv, bench/antoci2007.csv).
      0.17.0 (2026-12-07) viscous flows: fluid_dissipation (the Riemann solver's momentum term
                         and density diffusion left out of a viscous fluid) and
                         transport_carries_velocity (the transport shift carries the velocity;
                         restart format 6); TVF's sums take the walls' images and coupled
                         solids; the open boundaries' held velocities count as prescribed work,
                         and the energy watchdog ignores growth below round-off; example
                         turek_hron (Turek and Hron's FSI2 and FSI3), channel_flow --re.
      0.16.0 (2026-12-06) a granular body's no-slip images carry the shear traction continued
                         across the wall by equilibrium with the body force (a slope holds on
                         its floor up to the closed-form angle; field "wall_equilibrium");
                         examples column_collapse3d (Lube et al. 2004) and heap_pour2d (a
                         hopper's pour); column_collapse2d --floor coulomb.
      0.15.0 (2026-12-06) periodic axes (world def periodic[3], periodic_origin[3]; chapter
                         >>periodic; restart format 4); the fluid's viscous force divided by the
                         lattice moment, its acoustic step capped by the viscosity; moving wall
                         surfaces (sps_world_set_wall_velocity); sps_world_write_vtk_series (a
                         .vtk.series index with the times, for ParaView); the demo as WebAssembly;
                         the Drucker-Prager cone fitted to Mohr-Coulomb (material.granular.yield_cone: plane
                         strain with the body's dilatancy by default, the papers' eq. 14 and the
                         3D cones kept); open boundaries (sps_body_add_zone: inflow, outflow
                         and kill zones after Lastiwka, Basa and Quinlan 2009; sps_world_reserve;
                         ids renumbered in creation order at removals); restart format 5.
      0.14.0 (2026-12-06) free rigid bodies (SPS_MATERIAL_RIGID_DYNAMIC: Newton-Euler with the
                         implicit midpoint rule, friction at the contact point's velocity);
                         geometry from files (chapter >>geometry: STL, OBJ, outlines, SVG; exact
                         signed distance with a tree; mesh fills and container shells); contact
                         at rest where bodies are filled flush (contact_rest; the papers' law
                         kept as SPS_CONTACT_REST_KERNEL); set-up warnings (gravity along z in
                         2D, friction in degrees, a slot at a wall), each printed once; the
                         churn watch; triple corner images in 3D; sps_fluid_sound_speed.
      0.13.0 (2026-12-06) sps_world_restore checks every field of an untrusted file before it
                         changes the world (fuzzed past its checksum); water under gravity: the
                         corner images of perpendicular walls, the pressure force and divergence
                         scaled by the lattice's gradient moment, the divergence the pair sum
                         adjoint to the pressure force (tr L without gravity), a warning below
                         h_over_dp = 2; still water and standing waves measured (bench/VALIDATION.md).
      0.12.0 (2026-12-03) GNO/GNO-A: the penalty may be summed in the next sub-step's pressure
                         pass (penalty_in_pressure_pass; two neighbour passes a sub-step instead
                         of three, 1.15-1.2x faster, the published figures' digits kept; the
                         paper's own pass stays the default); the Drucker-Prager return map
                         vectorised and the mirror walls' images beyond the support skipped
                         before their geometry (a granular particle-step 1.7x an elastic one's,
                         was 2.1x; bit-identical); sps_world_substep_count.
      0.11.0 (2026-12-03) one generic chapter of switches over the material kind (>>generic):
                         each material's row, check, constants, energy, rules and stress update
                         in its own chapter, no kind tested elsewhere (bench/kind_tests.sh); only
                         the pair loops compiled per dimension, pair geometry and pair terms, the
                         rest of each pass once per dimension (impl.o 59 % of its size, compile
                         about half the time; results bit-identical); a budgeted frame always
                         runs one sub-step; per-body diagnostics and a parallel contact pair
                         search (3D runs with contact faster, bit-identical); examples write
                         their scenes as library calls, a new example is its file.
      0.10.0 (2026-12-03) restart fingerprint from one table of def items (every field that
                         changes results is checked and named; format version 2), the payload
                         from one item list; a def field a body does not read is warned about;
                         a missing pass instance is refused at sps_world_add_body in every
                         build; SPHSOLID_NO_FLUID/_GRANULAR/_PLASTICITY/_TOTAL_LAGRANGIAN;
                         examples/hello.c; water at rest stays at rest (the Riemann density
                         diffusion leaves the hydrostatic difference alone; fluid results move);
                         granular stress divergence scaled by the lattice's kernel-gradient
                         moment, GNO-A's penalty only between elastic grains, Coulomb friction of
                         grains at free-slip walls (granular results move);
                         sps_diagnostics.zigzag tells the zigzag mode from flow; examples
                         elastic_gate, heap2d (--pour), the demo's water tank.
      0.9.0 (2026-12-03) default rotation SPS_ROTATION_AUTO (pair for ENO-A, mean for GNO-A):
                         the default body survives tumbling and impacts; the watchdog names the
                         likely cause and counts in sps_diagnostics (energy_growth,
                         energy_growth_events); set-up checks (bodies behind walls, velocity on
                         an empty body, angles in radians, past times, threads without OpenMP);
                         sps_world_advance_frame in simulated seconds (the old call is
                         sps_world_advance_substeps), the drag (sps_body_drag_begin/_end),
                         sps_body_set_rigid_motion; Coulomb friction (sps_body_def.friction,
                         sps_world_set_wall_friction) and Kelvin-Voigt damping
                         (material.viscosity of solids, sps_diagnostics.viscous_work), normal
                         contact damping (contact_damping); the
                         fluid-structure coupling (fluids see solids as moving walls); the
                         variational hourglass force of total-Lagrangian bodies as the default
                         (hourglass = SPS_HOURGLASS_PAPER keeps TL eq. 32), their artificial
                         viscosity. Results of earlier scenes unchanged except total-Lagrangian
                         bodies (tests/pinned.c).
      0.8.0 (2026-12-02) granular media (SPS_MATERIAL_DRUCKER_PRAGER, material kind 6: cohesion,
                         friction_angle, dilatancy_angle; stress_diffusion;
                         sps_body_set_geostatic_stress; mirror walls with the images' stress);
                         damage of total-Lagrangian bodies (damage_strain, the "damage" field,
                         sps_particle_state.damage). Results of earlier scenes unchanged
                         (tests/pinned.c).
      0.7.0 (2026-12-02) fluids (SPS_MATERIAL_FLUID: weakly compressible, Riemann solver with
                         its limiter, viscosity, mirror particles at walls), the transport
                         corrections TVF and UTVF for any updated-Lagrangian body (transport),
                         sps_body_set_pressure, the surface_particles diagnostic (a CSV column
                         appended); total-Lagrangian SPH (SPS_SOLVER_TOTAL_LAGRANGIAN): reference
                         neighbour lists and corrected gradients, Saint Venant-Kirchhoff and
                         Neo-Hookean (material kinds 4, 5) and multiplicative J2, Ganzenmueller's
                         hourglass force (hourglass_alpha) with its yield-strength switch. The
                         continuity pass of the GNO family no longer sums ENO's unused
                         Laplacian. Results of earlier scenes unchanged (tests/pinned.c).
      0.6.0 (2026-12-02) J2 plasticity (SPS_MATERIAL_J2); guards that judge the body: time steps
                         in each body's frame, the escape guard around each body's centre of
                         mass, the energy watchdog, warnings for CFL above the measured stable
                         value and impacts above 0.2 c0; damping, external accelerations,
                         restart files (sps_world_save, sps_world_restore), binary VTK with
                         every array in a FIELD block. Results of moving scenes change with the
                         frame speeds (tests/pinned.c regenerated).
      0.5.0 (2026-12-01) a body's model as data (material, stabilisation, solver and transport
                         rows, a table of allowed combinations; material.kind, solver and
                         transport in the defs), pass kernels chosen once per body, a field
                         registry (sps_world_field_by_name). Results bit for bit those of 0.4.2
                         (tests/pinned.c).
      0.4.2 (2026-11-22) frozen geometry keeps dW/dr and 1/r_0 but takes e_ij, 1/r_ij and B_i from the
                         current positions: the stored directions of 0.4.1 made rotating pairs
                         look shorter (2D plate: period +0.55% per cycle; spinning plate ENO-A
                         32.9% -> 1.02%, GNO-A 18.2% -> 0.011%). The default is unchanged, bit
                         for bit.
      0.4.1 (2026-11-22) speed: lane groups of 16 doubles (32 floats) in 512-bit vectors,
                         branch-free neighbour collection, lane-parallel Jaumann update and
                         frozen-geometry fill, literal-dimension kick and drift. Same results
                         (bit for bit, except ENO-A's mean rotation summed in the larger
                         groups). 2D plate, 2 threads: 1.33x.
      0.4.0 (2026-11-22) SPS_ROTATION_PAIR for ENO-A and GNO-A: the stored shear forces kept per
                         neighbour pair along the current e_ij (exact angular momentum; ENO-A
                         needs no velocity gradient unless it tracks stress).
      0.3.0 (2026-11-22) continuity pass balanced over threads (per-group mean-rotation sums)
                         and lane-parallel at its end; Rodrigues series; faster neighbour
                         search. 2D plate, 2 threads: 1.24x.
      0.2.0 (2026-11-22) neighbour passes one particle per SIMD lane (1.6x); fewer barriers
                         per sub-step; sps_world_validate, escape and time-step guards,
                         keep_last_good_state; sps_world_advance_frame (real-time frames).
      0.1.0 (2026-11-21) first release: UL-SPH with OG, OAS, ENO, ENO-A, GNO, GNO-A;
                         dual-criteria stepping; observers; diagnostics; CSV/VTK.
   ========================================================================================
*/
#ifndef SPHSOLID_H_INCLUDED
#define SPHSOLID_H_INCLUDED

#include <stddef.h>
#include <stdint.h>

#define SPHSOLID_VERSION_MAJOR 0
#define SPHSOLID_VERSION_MINOR 21
#define SPHSOLID_VERSION_PATCH 0
#define SPHSOLID_VERSION_STRING "0.21.0"
#define SPHSOLID_VERSION_NUMBER (SPHSOLID_VERSION_MAJOR * 10000 + SPHSOLID_VERSION_MINOR * 100 + SPHSOLID_VERSION_PATCH)

#ifndef SPSDEF
#ifdef SPHSOLID_STATIC
#if defined(__GNUC__) || defined(__clang__)
#define SPSDEF static __attribute__((unused)) /* a file may use only part of the API */
#else
#define SPSDEF static
#endif
#else
#define SPSDEF extern
#endif
#endif

#ifdef SPHSOLID_FLOAT
typedef float sps_real;
#define SPS_R(x) ((float)(x))
/* The float build renames the entry points: linking float code against a double build fails. */
#define sps_world_create sps_world_create_f32
#define sps_default_world_def sps_default_world_def_f32
#define sps_world_step sps_world_step_f32
#else
typedef double sps_real;
#define SPS_R(x) (x)
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* >>public */

/* Result codes. Every fallible function returns one; sps_result_string() describes it. */
typedef enum sps_result {
    SPS_OK = 0,
    SPS_ERR_INVALID_ARG = -1,   /* a def field or argument is out of range; see the message */
    SPS_ERR_OUT_OF_MEMORY = -2, /* the allocator returned NULL */
    SPS_ERR_UNSTABLE = -3,      /* NaN/Inf state, escape, time-step collapse, clustering (ERRORS) */
    SPS_ERR_IO = -4,            /* a file could not be opened, read or written, or is truncated or damaged */
    SPS_ERR_STATE = -5          /* the call is not valid in the world's current state */
} sps_result;

typedef enum sps_kernel_type {
    SPS_KERNEL_WENDLAND_C2 = 0, /* Wendland C2 ("5th order Wendland" of the papers), support 2h */
    SPS_KERNEL_CUBIC_SPLINE = 1 /* cubic B-spline, support 2h */
} sps_kernel_type;

typedef enum sps_stepping {
    SPS_STEPPING_DUAL = 0,  /* neighbour update every advection step (ENO section 5) */
    SPS_STEPPING_SINGLE = 1 /* neighbour update every acoustic step */
} sps_stepping;

typedef enum sps_shear {
    SPS_SHEAR_ENO = 0,   /* essentially non-hourglass (ENO eq. 24) */
    SPS_SHEAR_ENO_A = 1, /* ENO with Rodrigues rotation of the accumulated a_s (ANG Algorithm 1) */
    SPS_SHEAR_OG = 2,    /* original: Jaumann stress and its divergence (ENO eq. 17); hourglasses */
    SPS_SHEAR_OAS = 3,   /* OG + Gray et al. artificial stress (2D only) */
    SPS_SHEAR_GNO = 4,   /* OG + accumulated hourglass penalty (ANG eqs. 43-46, projected form) */
    SPS_SHEAR_GNO_A = 5  /* GNO with Rodrigues rotation of the penalty (ANG Algorithm 2) */
} sps_shear;

typedef enum sps_rotation {
    SPS_ROTATION_MEAN = 0,         /* the body's mean Rodrigues matrix (ANG eq. 41-42) */
    SPS_ROTATION_PER_PARTICLE = 1, /* each particle's own matrix (ANG eq. 34) */
    SPS_ROTATION_PAIR = 2,         /* each increment turned with its own pair (see SHEAR FORMULATIONS) */
    SPS_ROTATION_AUTO = 3          /* pair for ENO-A, mean for GNO-A: what survives tumbling and
                                      impacts (the default; SHEAR FORMULATIONS) */
} sps_rotation;

/* A def coefficient set to SPS_AUTO takes its published default (zeta, xi,
   transport_coefficient, escape_distance; MODELS AND FIELDS: what zero means). */
#define SPS_AUTO 0

/* Axis masks for velocity constraints. */
enum { SPS_AXIS_X = 1, SPS_AXIS_Y = 2, SPS_AXIS_Z = 4, SPS_AXIS_ALL = 7 };

/* Runtime allocator; alloc may return NULL (the library then reports SPS_ERR_OUT_OF_MEMORY). */
typedef struct sps_allocator {
    void* (*alloc)(size_t size, void* user);
    void (*free)(void* ptr, void* user);
    void* user;
} sps_allocator;

/* Log callback: level 0 = error, 1 = warning, 2 = info. */
typedef void (*sps_log_fn)(int level, const char* message, void* user);

/* Where two bodies, or a body and an analytic wall, are at rest against each other (CONTACT). */
typedef enum sps_contact_rest {
    SPS_CONTACT_REST_FLUSH = 0,  /* filled flush: a body's first row dp/2 from a wall, two bodies'
                                    rows dp apart (their surfaces meet) */
    SPS_CONTACT_REST_KERNEL = 1  /* the papers' contact density, repulsive from the kernel's edge:
                                    at rest about 1.5 dp from a wall and 2 dp between rows */
} sps_contact_rest;

/* World definition. Get one from sps_default_world_def(), edit, pass to sps_world_create(). */
typedef struct sps_world_def {
    int dim;                          /* space dimension, 2 or 3. Default 2. */
    sps_real dp;                      /* initial particle spacing [m], > 0. Default 0.01. */
    sps_real h_over_dp;               /* smoothing length / dp, in [1, 3]. Default 1.3. */
    sps_kernel_type kernel;           /* Default SPS_KERNEL_WENDLAND_C2. */
    sps_stepping stepping;            /* Default SPS_STEPPING_DUAL. */
    sps_real cfl_acoustic;            /* CFL_ac in (0, 1]. Default 0.4. */
    sps_real cfl_advection;           /* CFL_ad in (0, 1]. Default 0.2. */
    int max_substeps;                 /* acoustic sub-steps per advection step, [1, 10000]. Default 100. */
    sps_real gravity[3];              /* uniform body force [m/s^2]. Default 0. */
    sps_real periodic[3];             /* [m] the period of each axis (PERIODIC): 0: not periodic;
                                         > 0: the world repeats along the axis with this length,
                                         at least 3 supports (6 h, the cell grid's 3 cells). z
                                         only in 3D. Not with a wall across the axis, a total-
                                         Lagrangian or a free rigid body, or frozen_geometry.
                                         Default 0. */
    sps_real periodic_origin[3];      /* [m] where each periodic axis's box starts: positions are
                                         kept in [origin, origin + periodic). Default 0. */
    int frozen_geometry;              /* 0: pair geometry (e_ij, dW, B_i) from the current positions
                                         in every sub-step. 1: dW and 1/r_0 stored at each
                                         configuration update; e_ij, 1/r_ij (one Newton step
                                         from 1/r_0) and B_i from the current
                                         positions: 1.2-1.3x faster in double (not in float);
                                         dW lags the stretch within an advection step.
                                         Default 0 (bench/VALIDATION.md, design notes). */
    sps_real neighbor_capacity;       /* the most neighbours one particle may have, relative to a
                                         full lattice support, >= 1 (more stops the run: the
                                         particles are clustering). Default 2 (compression to
                                         rho/rho0 = 2). */
    int threads;                      /* OpenMP threads for this world; 0 = OpenMP default. */
    sps_real escape_distance;         /* [m] a particle farther than its body's size (the largest
                                         distance of a reference position from the reference
                                         centre of mass) plus this from the body's current centre
                                         of mass stops the run with SPS_ERR_UNSTABLE: a body that
                                         travels is never stopped. 0: 10 body sizes (20 x that
                                         largest distance), at least 100 dp. INFINITY: never.
                                         Default 0. */
    int report_fragments;             /* 1: a warning (log level 1), once per body, when one of
                                         its particles has no neighbour left within 2h (it broke
                                         off). Default 0. */
    sps_real energy_growth_limit;     /* energy watchdog (ERRORS): a warning, once, when the total
                                         energy (kinetic + strain + gravity potential - work of
                                         the prescribed motions) exceeds its value at the start by
                                         more than this fraction of the largest mechanical energy
                                         (kinetic + strain) seen (every such check is counted in
                                         sps_diagnostics.energy_growth_events); > 0, INFINITY:
                                         off. Default 0.05. */
    int energy_growth_stops;          /* 1: the watchdog's finding stops the run with
                                         SPS_ERR_UNSTABLE instead. Default 0. */
    sps_contact_rest contact_rest;    /* where contacts are at rest (CONTACT). Default
                                         SPS_CONTACT_REST_FLUSH. */
    int keep_last_good_state;         /* 1: copy positions, velocities, densities, pressures and
                                         stresses at every configuration update, and on
                                         SPS_ERR_UNSTABLE roll the world back to that copy (see
                                         ERRORS). Costs 16 reals per particle and ~0.05 % of
                                         the step time (measured, 2D plate). Default 0. */
    sps_allocator allocator;          /* Default: SPHSOLID_MALLOC / SPHSOLID_FREE. */
    sps_log_fn log;                   /* Default: errors to stderr (NULL with SPHSOLID_NO_STDIO). */
    void* log_user;                   /* passed to log. */
    void* user_data;                  /* yours. */
    int internal_cookie;              /* set by sps_default_world_def(); do not touch. */
} sps_world_def;

/* The constitutive model of a body (MATERIALS). */
typedef enum sps_material_kind {
    SPS_MATERIAL_ELASTIC = 0, /* linear elastic: p = c0^2 (rho - rho0), Jaumann-rate shear stress */
    SPS_MATERIAL_RIGID = 1,   /* a wall body: its particles keep the velocity given to them
                                 (sps_body_set_velocity, constraints) and push the other bodies
                                 by contact; density, E and nu set its mass and contact stiffness */
    SPS_MATERIAL_J2 = 2,      /* von Mises elastic-plastic: the linear elastic law, and the shear
                                 stress returned radially onto the yield surface
                                 sqrt(2 J2) = sqrt(2/3)(j2.yield_stress + j2.hardening_modulus alpha),
                                 alpha the equivalent plastic strain (ANG eqs. 11, 14; MATERIALS).
                                 Needs a stress-based shear formulation: OG, OAS, GNO or GNO-A
                                 (GNO-A is ANG's choice; ENO and ENO-A are refused) */
    SPS_MATERIAL_FLUID = 3,   /* weakly compressible fluid (UTVF section 2.1; FLUIDS): p = c0^2 (rho
                                 - rho0) with c0 = fluid.sound_speed, no shear stress (the body's shear
                                 formulation is not used), the Riemann solver with its
                                 dissipation limiter in the momentum and continuity equations
                                 (UTVF eqs. 16-20), and a Newtonian viscosity if viscosity > 0 */
    SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF = 4, /* hyperelastic S = lambda tr(E) I + 2 mu E, E the
                                 Green-Lagrange strain (TL eq. 19); total-Lagrangian bodies only */
    SPS_MATERIAL_NEO_HOOKEAN = 5, /* compressible Neo-Hookean S = mu (I - C^-1) + lambda ln(J) C^-1
                                 (TL eq. 44); total-Lagrangian bodies only */
    SPS_MATERIAL_DRUCKER_PRAGER = 6, /* granular: elastic-perfectly plastic Drucker-Prager (material.granular:
                                 cohesion, friction_angle, dilatancy_angle; UTVF section 2.3; GRANULAR): the
                                 whole stress integrated (Jaumann rate, the pressure is its
                                 trace, not a function of density), returned onto the cone, with
                                 the Riemann solver's limited dissipation and stress diffusion
                                 (granular.stress_diffusion); the shear formulation is not used */
    SPS_MATERIAL_RIGID_DYNAMIC = 7 /* a free rigid body (Box2D's dynamic body; FREE RIGID BODIES): its
                                 particles move as one rigid body by Newton-Euler under the sum
                                 of the forces they receive (contact, walls, fluid, gravity,
                                 drag); density gives its mass, E and nu its contact stiffness */
} sps_material_kind;

/* The solver of a body. */
typedef enum sps_solver {
    SPS_SOLVER_UPDATED_LAGRANGIAN = 0, /* neighbours and kernel gradients from the current positions */
    SPS_SOLVER_TOTAL_LAGRANGIAN = 1    /* neighbours, corrected kernel gradients and the deformation
                                          gradient in the reference configuration (TOTAL-LAGRANGIAN) */
} sps_solver;

/* The hourglass force of a total-Lagrangian body (TOTAL-LAGRANGIAN). */
typedef enum sps_hourglass {
    SPS_HOURGLASS_VARIATIONAL = 0, /* -grad Phi of the springs' energy Phi (TL eq. 32 plus its two
                                      missing terms): conserves energy, symmetric stiffness */
    SPS_HOURGLASS_PAPER = 1        /* TL eq. 32 as printed: a partial gradient of Phi, which can feed
                                      energy into the motion (kept to compare with the paper) */
} sps_hourglass;

/* The transport-velocity correction of a body (particles advected by a shifted velocity). */
typedef enum sps_transport {
    SPS_TRANSPORT_NONE = 0, /* particles move with their own velocity */
    SPS_TRANSPORT_TVF = 1,  /* after every acoustic sub-step the inner particles are shifted by
                               -2 alpha h^2 sum_j grad W_ij V_j towards zero-order consistency
                               (UTVF eq. 30); the free-surface particles are not (TRANSPORT) */
    SPS_TRANSPORT_UTVF = 2  /* TVF, and the free-surface particles shifted along the surface only
                               (UTVF eqs. 31-37) */
} sps_transport;

/* The numerical dissipation of a fluid body (material.fluid.dissipation; FLUIDS): which of the Riemann
   solver's two dissipative terms it keeps. */
typedef enum sps_fluid_dissipation {
    SPS_FLUID_DISSIPATION_RIEMANN = 0, /* both: the momentum equation's limited Z beta (v_ij . e_ij) and
                                          the continuity equation's density diffusion (UTVF eqs.
                                          16-20): free surfaces, impacts, inviscid water */
    SPS_FLUID_DISSIPATION_DENSITY = 1, /* the density diffusion only: the momentum equation has the
                                          pressure and the physical viscosity alone (a viscous flow;
                                          needs material.viscosity > 0) */
    SPS_FLUID_DISSIPATION_NONE = 2     /* neither: the physical viscosity is the only dissipation (a
                                          viscous flow; needs material.viscosity > 0; a closed box's
                                          sound is then damped by the viscosity alone) */
} sps_fluid_dissipation;

/* The lattice the fills (sps_body_add_box, sps_body_add_sdf) put a body's particles on
   (lattice; FLUIDS, "Water at rest"). */
typedef enum sps_lattice {
    SPS_LATTICE_AUTO = 0,      /* hexagonal for a 2D fluid with a hydrostatic column (gravity along an
                                  axis that is not periodic) at h_over_dp < 1.4, square otherwise */
    SPS_LATTICE_SQUARE = 1,    /* at lo + (i + 1/2) dp along each axis: the box tiled flush */
    SPS_LATTICE_HEXAGONAL = 2  /* 2D only: rows along x, every other row shifted by half a spacing,
                                  about dp sqrt(2/sqrt 3) = 1.075 dp apart, dp^2 a particle; the
                                  shifted rows end in half particles a quarter spacing inside the
                                  box's x faces. Water under gravity at h = 1.3 dp on it stays at
                                  rest, where the square lattice's rows slide within seconds */
} sps_lattice;

/* The Drucker-Prager cone of a granular body (material.granular.yield_cone; GRANULAR): which Mohr-Coulomb
   stress state the cone f = alpha_phi I1 + sqrt(J2) - k_c is fitted to, given phi, psi and c. */
typedef enum sps_yield_cone {
    SPS_CONE_PLANE_STRAIN = 0, /* Mohr-Coulomb's strength in plane strain with the body's dilatancy
                                  (sigma_zz from zero plastic strain out of the plane): a slope or
                                  a heap stands at phi, in 2D and on a 3D slope */
    SPS_CONE_PAPERS = 1,       /* UTVF eq. 14, alpha_phi = tan phi / sqrt(9 + 12 tan^2 phi): the cone
                                  inscribed in Mohr-Coulomb's pyramid, exact in plane strain only
                                  for psi = phi; with psi = 0 it acts as phi_eff = asin(3 alpha_phi)
                                  (28.7 degrees for 30). The papers' C4-C7 */
    SPS_CONE_COMPRESSION = 2,  /* through Mohr-Coulomb's compression meridian (the outer cone):
                                  triaxial compression */
    SPS_CONE_EXTENSION = 3,    /* through the extension meridian: triaxial extension */
    SPS_CONE_COMPROMISE = 4    /* alpha_phi and k_c the means of the compression and extension
                                  cones' */
} sps_yield_cone;

/* J2 plasticity's parameters (material.j2; chapter >>material: J2 plasticity). */
typedef struct sps_j2_def {
    sps_real yield_stress;      /* initial yield stress sigma_Y [Pa], finite > 0 (must be set for J2).
                                   Default 0. */
    sps_real hardening_modulus; /* linear isotropic hardening modulus kappa [Pa], finite >= 0 (0:
                                   perfect plasticity). Default 0. */
} sps_j2_def;

/* A weakly compressible fluid's parameters (material.fluid; chapter >>material: weakly
   compressible fluid). Its viscosity is material.viscosity, shared with the solids' Kelvin-Voigt
   damping: one Newtonian shear viscosity either way. */
typedef struct sps_fluid_def {
    sps_real sound_speed;  /* the artificial sound speed c0 [m/s], finite > 0 (must be set for a
                              fluid; about 10 times the largest flow speed keeps the density within
                              1 %, UTVF section 2.1; sps_fluid_sound_speed). The other kinds' c0
                              follows from E and nu. Default 0. */
    sps_fluid_dissipation dissipation; /* the Riemann solver's dissipative terms kept
                              (sps_fluid_dissipation; FLUIDS): a viscous flow that the viscosity
                              alone keeps stable decays at its physical rate only without the
                              momentum term (the Taylor-Green vortex, the lid-driven cavity).
                              Default SPS_FLUID_DISSIPATION_RIEMANN. */
} sps_fluid_def;

/* A Drucker-Prager (granular) body's parameters (material.granular; chapter >>material:
   Drucker-Prager; GRANULAR). */
typedef struct sps_granular_def {
    sps_real cohesion;        /* cohesion c [Pa], finite >= 0. Default 0. */
    sps_real friction_angle;  /* friction angle phi [degrees], in [0, 90). Default 0. */
    sps_real dilatancy_angle; /* dilatancy angle psi [degrees], in [0, friction_angle] (0: no volume
                                 change in plastic flow). Default 0. */
    sps_yield_cone yield_cone; /* the cone fitted to Mohr-Coulomb's phi, psi and c (sps_yield_cone).
                                 Default SPS_CONE_PLANE_STRAIN (a heap stands at phi);
                                 SPS_CONE_PAPERS reproduces UTVF's figures. */
    sps_real stress_diffusion; /* the coefficient zeta of the stress diffusion (Feng et al. 2021;
                                 GRANULAR), [0, 1] (0: off). Default 0.1. */
} sps_granular_def;

/* A total-Lagrangian body's parameters (material.tl, read by bodies with solver = total
   Lagrangian, whatever their kind; chapter >>solver: total Lagrangian; TOTAL-LAGRANGIAN). */
typedef struct sps_tl_def {
    sps_real hourglass_alpha;  /* the hourglass coefficient alpha of TL eq. 32, [0, 1000] (0: no
                                  hourglass control). Default 50. */
    sps_hourglass hourglass;   /* the form of the hourglass force, 0..1. Default
                                  SPS_HOURGLASS_VARIATIONAL. */
    sps_real artificial_viscosity; /* Monaghan's linear artificial viscosity q1 between reference
                                  neighbours (TOTAL-LAGRANGIAN), [0, 1]; 0: none. Default 0. */
    sps_real damage_strain;    /* the damage threshold eps_max of TL section 4.6, a principal
                                  Green-Lagrange strain (dimensionless), [0, 100]; past it the
                                  damage D grows and degrades the tensile stress
                                  (TOTAL-LAGRANGIAN). 0: no damage. Default 0. */
} sps_tl_def;

/* Material: its kind, the constants every kind shares, and one sub-struct of parameters per
   family of kinds, read only by the kinds (or the solver) it names: a body that sets one its
   kind does not read gets a warning (sps_world_add_body). */
typedef struct sps_material_def {
    sps_real density;        /* reference density rho0 [kg/m^3], > 0. Default 1000. */
    sps_real youngs_modulus; /* E [Pa], > 0 (not read by fluids). Default 1e6. */
    sps_real poisson_ratio;  /* nu, in (-1, 0.5) (not read by fluids). Default 0.3. */
    sps_material_kind kind;  /* Default SPS_MATERIAL_ELASTIC. */
    sps_real viscosity;      /* fluid: the dynamic viscosity mu [Pa s], finite >= 0 (0: inviscid).
                                Elastic, J2, Saint Venant-Kirchhoff, Neo-Hookean: the Kelvin-Voigt
                                viscosity eta [Pa s], finite >= 0, the material damping (DAMPING:
                                vibrations decay, rigid motion is not braked; 0: none). Refused
                                for the other kinds. Shared rather than per kind: it
                                is the one Newtonian shear viscosity of both. Default 0. */
    sps_j2_def j2;             /* SPS_MATERIAL_J2 */
    sps_fluid_def fluid;       /* SPS_MATERIAL_FLUID */
    sps_granular_def granular; /* SPS_MATERIAL_DRUCKER_PRAGER */
    sps_tl_def tl;             /* solver = SPS_SOLVER_TOTAL_LAGRANGIAN */
} sps_material_def;

/* Body definition: a material, a shear formulation and which outputs the body needs. */
typedef struct sps_body_def {
    const char* name;          /* for messages and output; copied (first 31 chars). Default "body". */
    sps_material_def material; /* Default sps_default_material_def(). */
    sps_shear shear;           /* Default SPS_SHEAR_ENO_A. */
    sps_rotation rotation;     /* the -A variants (ENO-A, GNO-A). Default SPS_ROTATION_AUTO (ENO-A:
                                  pair; GNO-A: mean). */
    sps_real zeta;             /* ENO coefficient; 0 selects 0.7 d + 2.1 (ENO section 4). Default 0. */
    sps_real xi;               /* GNO penalty coefficient xi_G; 0 selects 2 (ANG section 4.2). Default 0. */
    int penalty_in_pressure_pass; /* GNO, GNO-A: 1 sums each sub-step's hourglass penalty (ANG
                                  eqs. 43-46) in the next sub-step's pressure pass, two neighbour
                                  passes per sub-step instead of three (PENALTY IN THE PRESSURE
                                  PASS); 0: the paper's pass of its own. Not with rotation = pair
                                  or Drucker-Prager bodies. Default 0. */
    sps_real oas_epsilon;      /* OAS artificial-stress factor, [0, 1]. Default 0.3 (Gray et al.). */
    sps_real oas_exponent;     /* OAS exponent n of f = (W(r)/W(dp))^n, [1, 12]. Default 4. */
    int track_stress;          /* 1: integrate the shear stress (von Mises, strain energy). Default 0. */
    sps_solver solver;         /* Default SPS_SOLVER_UPDATED_LAGRANGIAN. */
    sps_transport transport;   /* Default SPS_TRANSPORT_NONE. */
    int contact;               /* 1: touches the other bodies with contact = 1 (CONTACT; pairs can be
                                  turned off by sps_world_set_contact). Default 1. */
    sps_real transport_coefficient; /* alpha of the transport correction (UTVF eq. 30), in
                                  [0, 1]; 0 selects 0.2 (the paper's). Default 0. */
    sps_real damping;          /* c [1/s], finite >= 0: every particle's velocity decays as
                                  dv/dt = a - c v (DAMPING; numerical, not a physical material
                                  damping: for reaching a static equilibrium). 0 = off. Not for
                                  wall bodies. Default 0. */
    sps_real friction;         /* Coulomb friction coefficient mu, finite >= 0, of its contacts
                                  with other bodies and walls (CONTACT); a pair's is the geometric
                                  mean sqrt(mu_a mu_b), so a frictionless partner (0) gives none.
                                  Needs contact = 1; not for fluid and Drucker-Prager bodies
                                  (their walls act through mirror particles). Default 0. */
    sps_real contact_damping;  /* normal contact damping: the damping ratio zeta of a dashpot on
                                  the normal relative velocity of its contacts with walls and
                                  bodies (CONTACT), [0, 1]; a pair's is the mean (zeta_a +
                                  zeta_b) / 2. 1: at a wall, the no-slip wall's impedance drag
                                  on the normal velocity. The bounce's restitution it gives is
                                  measured, not set (CONTACT). Needs contact = 1; not for fluid and
                                  Drucker-Prager bodies. 0: none (elastic contact). Default 0. */
    int transport_carries_velocity; /* 1: the transport correction's shift dr_i carries the
                                  velocity with it, v_i += L_i dr_i (L the velocity gradient), and
                                  UTVF's sums take the walls' images as TVF's (TRANSPORT); for bodies with a
                                  velocity gradient (not a fluid under gravity). 0: positions
                                  only (UTVF eq. 42). Default 0. */
    sps_lattice lattice;       /* the lattice of the fills (sps_lattice); a wall within a fifth
                                  of dp of a hexagonal body's particle holds it (the backstop,
                                  dp/2 for the others: the lattice's half particles stand closer).
                                  Default SPS_LATTICE_AUTO. */
    void* user_data;           /* yours. */
    int internal_cookie;       /* set by sps_default_body_def(); do not touch. */
} sps_body_def;

typedef struct sps_world sps_world;
typedef struct sps_body { uint32_t id; } sps_body;         /* value handle; id 0 = invalid */
typedef struct sps_observer { uint32_t id; } sps_observer; /* value handle; id 0 = invalid */

/* Global diagnostics of the world (or one body). See DIAGNOSTICS above for definitions. */
typedef struct sps_diagnostics {
    sps_real time;                /* simulated time [s] */
    sps_real kinetic_energy;      /* [J] (J/m in 2D) */
    sps_real strain_energy;       /* [J] (J/m in 2D) */
    sps_real contact_energy;      /* [J] stored in the contacts with other bodies and walls */
    sps_real potential_energy;    /* [J] in gravity: -sum m g.x over the deformable bodies */
    sps_real prescribed_work;     /* [J] done on the deformable bodies by the prescribed motions
                                     (moving velocity constraints, rigid bodies) and external
                                     accelerations since they were set; counted while the
                                     energy watchdog is on */
    sps_real plastic_work;        /* [J] (J/m in 2D) work dissipated by plastic flow since the start
                                     (J2 bodies; 0 for the others): kinetic + strain + plastic work
                                     is the energy account */
    sps_real viscous_work;        /* [J] (J/m in 2D) work dissipated by the Kelvin-Voigt viscosity
                                     (material.viscosity of a solid) and the contact dashpot
                                     (contact_damping) since the start; part of the
                                     energy account like plastic_work */
    sps_real max_plastic_strain;  /* largest equivalent plastic strain alpha (J2 bodies; else 0) */
    int surface_particles;        /* particles whose position divergence sum_j -r_ij . grad W_ij V_j
                                     is below 0.75 dim (UTVF eq. 31): the free surface, and any
                                     void or crack inside (a body keeps about its perimeter's
                                     count while it stays whole) */
    sps_real linear_momentum[3];  /* [kg m/s] */
    sps_real angular_momentum[3]; /* [kg m^2/s], about the origin */
    sps_real max_speed;           /* [m/s] */
    sps_real min_density, max_density; /* [kg/m^3] */
    sps_real hourglass;           /* dimensionless zigzag indicator of the displacement */
    sps_real zigzag;              /* the velocity's zigzag: the pairs' relative velocity the
                                     velocity gradient does not explain, per unit of the one it
                                     does (0 for smooth flow, above 1 for zigzag) */
    sps_real min_spacing;         /* smallest neighbour distance / dp (clustering below ~0.5) */
    long acoustic_steps, advection_steps;
    sps_real dt_acoustic;         /* last acoustic time step [s] */
    int particles;
    sps_real energy_growth;       /* the energy watchdog's largest finding so far (world-wide): the
                                     account's growth above its start as a fraction of the largest
                                     mechanical energy seen (ERRORS); 0 with the watchdog off */
    int energy_growth_events;     /* the watchdog's checks that found the growth above
                                     energy_growth_limit (world-wide): 0 for a clean run. A run
                                     that warned (energy_growth_stops = 0) returned SPS_OK, and
                                     this is how the caller knows */
    int warnings;                 /* warnings issued so far (world-wide), repeats included: a
                                     warning whose text was printed before is counted here and
                                     not printed again (the count per warning goes to the log
                                     when the world is destroyed) */
} sps_diagnostics;

/* Per-particle output state (sps_world_particle). */
typedef struct sps_particle_state {
    sps_real position[3], velocity[3], displacement[3];
    sps_real density, pressure, von_mises; /* von_mises is 0 unless the body tracks stress */
    int body_index;
    sps_real plastic_strain;  /* equivalent plastic strain alpha (0 unless the body is J2) */
    sps_real damage;          /* damage D in [0, 1] (0 unless the body has material.tl.damage_strain > 0) */
} sps_particle_state;

/* Callback of sps_body_set_velocity: v from the reference position x (both length 3). */
typedef void (*sps_velocity_fn)(const sps_real x[3], sps_real v[3], void* user);
/* Callback of sps_body_set_pressure: the pressure [Pa] at the reference position x (length 3). */
typedef sps_real (*sps_pressure_fn)(const sps_real x[3], void* user);
/* Callback of sps_body_set_acceleration: the external acceleration a [m/s^2] (length 3, zeroed
   before the call; z ignored in 2D) of one particle at time t [s] from its current position x,
   its reference position x0 and its velocity v (see EXTERNAL ACCELERATION for when and by which
   threads it is called). */
typedef void (*sps_acceleration_fn)(const sps_real x[3], const sps_real x0[3], const sps_real v[3], sps_real t, sps_real a[3],
                                    void* user);
/* Callback of sps_world_advance, after every step; return nonzero to stop. */
typedef int (*sps_step_fn)(sps_world* w, void* user);

/* Version string "MAJOR.MINOR.PATCH"; 1 if sps_real is double. Thread-safe, no allocation. */
SPSDEF const char* sps_version(void);
SPSDEF int sps_is_double(void);
/* A short English description of a result code. */
SPSDEF const char* sps_result_string(sps_result r);

/* Defaults (see each field). */
SPSDEF sps_world_def sps_default_world_def(void);
SPSDEF sps_material_def sps_default_material_def(void);
SPSDEF sps_body_def sps_default_body_def(void);

/* The sound speed c0 [m/s] for a fluid (material.fluid.sound_speed) whose density may vary by the
   fraction density_error e, in (0, 0.5]: U / sqrt(e), U the larger of flow_speed and the
   free-fall speed sqrt(2 g depth) of water `depth` deep under gravity of magnitude g (the
   dynamic pressure rho U^2 against rho c0^2; it also bounds the hydrostatic compression at the
   floor, g H / c0^2 = e / 2 at most). SPS_DENSITY_ERROR_ACCURATE gives the papers' 10 U;
   SPS_DENSITY_ERROR_GAME 4.5 U: 2.2 times fewer sub-steps when the water sets the time step,
   for a density within 5 % (bench/VALIDATION.md, "The natural set-up"). 0 for an
   argument out of range (not finite, negative, or e outside (0, 0.5]) and when g depth and
   flow_speed are all 0 (no speed to scale by), which the body's check then refuses as
   material.fluid.sound_speed = 0. */
#define SPS_DENSITY_ERROR_ACCURATE 0.01
#define SPS_DENSITY_ERROR_GAME 0.05
SPSDEF sps_real sps_fluid_sound_speed(sps_real gravity, sps_real depth, sps_real flow_speed, sps_real density_error);

/* Checks a world def; writes every broken rule (field, value, allowed range) into msg.
   Returns SPS_OK or SPS_ERR_INVALID_ARG. No allocation. */
SPSDEF sps_result sps_world_def_check(const sps_world_def* def, char* msg, size_t msg_size);

/* Creates a world from a def (copied). On error *out is NULL and the message goes to def->log.
   Allocates the world. Cost O(1). */
SPSDEF sps_result sps_world_create(const sps_world_def* def, sps_world** out);
/* Frees the world and everything it owns. NULL is allowed. */
SPSDEF void sps_world_destroy(sps_world* w);
/* The effective def (after defaults); NULL for a NULL world. */
SPSDEF const sps_world_def* sps_world_get_def(const sps_world* w);
/* The message of the last error of this world ("" if none; for NULL, "world is NULL" and how
   to read the errors of sps_world_create: sps_world_def_check). Valid until the next call. */
SPSDEF const char* sps_world_last_error(const sps_world* w);
/* Debug check of the whole world: the def, every body def, bodies not empty, every particle's
   state finite (density, mass, volume > 0), ids, constraints and observers consistent, and
   whether a step stopped at an instability. Writes EVERY broken rule into msg ("; "-separated,
   truncated to msg_size). Returns SPS_OK, SPS_ERR_STATE (a rule is broken) or
   SPS_ERR_INVALID_ARG (w NULL). O(N), no allocation; does not touch the world's last error. */
SPSDEF sps_result sps_world_validate(const sps_world* w, char* msg, size_t msg_size);

/* Adds a body (def copied, checked: density, modulus, Poisson ratio, zeta, shear, rotation).
   Allocates. */
SPSDEF sps_result sps_world_add_body(sps_world* w, const sps_body_def* def, sps_body* out);
SPSDEF int sps_body_is_valid(const sps_world* w, sps_body b);
/* The body's index (0..bodies-1), as written in output "body" fields; -1 if invalid. */
SPSDEF int sps_body_index(const sps_world* w, sps_body b);
/* Derived material constants of a body: sound speed c0 [m/s], shear modulus G [Pa], bulk K [Pa]. */
SPSDEF sps_result sps_body_material_constants(const sps_world* w, sps_body b, sps_real* c0, sps_real* G, sps_real* K);

/* Lattice fill of the box [lo, hi) (length-3 arrays; z ignored in 2D): particles at
   lo + (i + 1/2) dp per axis while inside. *added (may be NULL) gets the number added. Allocates. */
SPSDEF sps_result sps_body_add_box(sps_world* w, sps_body b, const sps_real lo[3], const sps_real hi[3], int* added);
/* Lattice fill of [lo, hi) where sdf(x, user) < 0. */
SPSDEF sps_result sps_body_add_sdf(sps_world* w, sps_body b, const sps_real lo[3], const sps_real hi[3],
                                   sps_real (*sdf)(const sps_real x[3], void* user), void* user, int* added);
/* Lattice fill of [lo, hi) where sdf(x, user) < 0, relaxed to a uniform distribution whose
   outer layer lies on a smooth surface dp/2 inside the shape (chapter >>fill): curved bodies
   (rings, balls) get smooth surfaces. sdf must be a signed distance (|grad| = 1) within 2h of
   the surface, negative inside; a shape cut by the box is relaxed as the intersection.
   iterations: shifting steps, >= 0; 0 selects 300. *added (may be NULL) gets the count (the
   lattice's: particles keep their volume dp^d). Errors: SPS_ERR_INVALID_ARG for a NULL sdf or
   lo/hi, an invalid body, a box not finite with lo < hi, iterations < 0, too many points, or an
   sdf that returns NaN (nothing is added); SPS_ERR_OUT_OF_MEMORY. Allocates O(N) scratch;
   O(N) per iteration; deterministic. */
SPSDEF sps_result sps_body_add_sdf_relaxed(sps_world* w, sps_body b, const sps_real lo[3], const sps_real hi[3],
                                           sps_real (*sdf)(const sps_real x[3], void* user), void* user, int iterations, int* added);
/* How well n points xyz (3 reals each) fill the shape sdf < 0 cut by [lo, hi] (sps_measure_fill). */
typedef struct sps_fill_quality {
    int particles, inner, surface; /* points; those deeper than 2h; those within dp of the surface */
    sps_real density_spread;       /* std/mean of the number density sum_j W_ij dp^d (self included)
                                      completed by the kernel mass beyond a flat surface at each
                                      point's depth: 0 for an ideal body-fitted set */
    sps_real density_spread_inner; /* the same without completion over the inner points (0 for a lattice) */
    sps_real min_spacing;          /* smallest pair distance / dp */
    sps_real surface_rms;          /* RMS of (depth - dp/2)/dp over the surface points (lattice ~0.29) */
} sps_fill_quality;
SPSDEF sps_result sps_measure_fill(const sps_world* w, int n, const sps_real* xyz, const sps_real lo[3], const sps_real hi[3],
                                  sps_real (*sdf)(const sps_real x[3], void* user), void* user, sps_fill_quality* q);
/* Adds n particles at xyz (3 reals each; z ignored in 2D) with volumes vol (NULL: dp^d each). */
SPSDEF sps_result sps_body_add_particles(sps_world* w, sps_body b, int n, const sps_real* xyz, const sps_real* vol);

/* Sets the velocity of every particle of the body from fn(reference position). SPS_ERR_STATE for
   a body without particles (add them first: a fill starts particles at rest). */
SPSDEF sps_result sps_body_set_velocity(sps_world* w, sps_body b, sps_velocity_fn fn, void* user);
/* Sets the body's velocity to a rigid motion about its CURRENT centre of mass x_cm:
   v_i = velocity + omega x (x_i - x_cm) (length-3 arrays; in 2D only omega[2] is used). For
   throwing, spinning or stopping a body that has moved (sps_body_set_velocity sees the
   reference positions only). SPS_ERR_INVALID_ARG for NULL or non-finite values, SPS_ERR_STATE
   for a body without particles. No allocation; O(N). */
SPSDEF sps_result sps_body_set_rigid_motion(sps_world* w, sps_body b, const sps_real velocity[3], const sps_real omega[3]);
/* Free rigid bodies (material.kind = SPS_MATERIAL_RIGID_DYNAMIC; FREE RIGID BODIES). Each call
   below returns SPS_ERR_INVALID_ARG for a body of another kind (naming its kind), NULL or
   non-finite arguments, and SPS_ERR_STATE for a body without particles; the first call on a body
   prepares the world for stepping as the first step would (sorts the particles, allocates). */
typedef struct sps_rigid_state {
    sps_real position[3];         /* centre of mass [m] */
    sps_real rotation[9];         /* row-major rotation from the configuration its particles were
                                     added in to the current one */
    sps_real velocity[3];         /* of the centre of mass [m/s] */
    sps_real angular_velocity[3]; /* [rad/s]; in 2D only z */
    sps_real angular_momentum[3]; /* about the centre of mass [kg m^2/s] (per metre in 2D) */
    sps_real mass;                /* [kg] (kg/m in 2D) */
    sps_real inertia[9];          /* about the centre of mass in world axes, current orientation
                                     [kg m^2]; in 2D only inertia[8] (zz) is used */
    sps_real force[3], torque[3]; /* the resultant of the last sub-step (gravity included; torque
                                     about the centre of mass) [N], [N m] */
} sps_rigid_state;
/* The state of free rigid body b. No allocation after the first call; O(1). */
SPSDEF sps_result sps_body_rigid_state(sps_world* w, sps_body b, sps_rigid_state* out);
/* Moves the body: its centre of mass to position and its orientation to rotation (row-major,
   from the configuration it was added in; NULL keeps the orientation; must be orthonormal
   with determinant 1 within 1e-6). Velocities are kept. O(its particles). */
SPSDEF sps_result sps_body_set_rigid_pose(sps_world* w, sps_body b, const sps_real position[3], const sps_real rotation[9]);
/* Mass [kg] (finite > 0) and inertia tensor about the centre of mass [kg m^2] (row-major, in the
   world axes of the configuration the body was added in; symmetric positive definite; in 2D
   only inertia[8] is read, > 0; NULL: the particles' own, scaled by mass / their mass). By
   default both come from the particles (FREE RIGID BODIES). Keeps the velocity of the centre
   of mass and the angular velocity. */
SPSDEF sps_result sps_body_set_mass_properties(sps_world* w, sps_body b, sps_real mass, const sps_real inertia[9]);
/* Applies the impulse [N s] at the world point (NULL: the centre of mass) now. */
SPSDEF sps_result sps_body_apply_impulse(sps_world* w, sps_body b, const sps_real impulse[3], const sps_real point[3]);
/* Applies the force [N] at the material point that is now at the world point (NULL: the
   centre of mass) in every sub-step from now on, turning with the body, until it is set again
   (force {0, 0, 0} removes it). Its work enters the energy account. */
SPSDEF sps_result sps_body_set_force(sps_world* w, sps_body b, const sps_real force[3], const sps_real point[3]);
/* Locks the body's translation along the world axes in translation (SPS_AXIS_* mask, 0..7) and
   its rotation about the world axes in rotation (in 2D only SPS_AXIS_Z turns): a locked axis
   keeps velocity 0 (a wheel on an axle: translation SPS_AXIS_ALL, rotation SPS_AXIS_X |
   SPS_AXIS_Y in 3D; a body that only translates: rotation SPS_AXIS_ALL). */
SPSDEF sps_result sps_body_lock_axes(sps_world* w, sps_body b, unsigned translation, unsigned rotation);

/* Sets the pressure of every particle of the body from fn(reference position) [Pa], and its
   density from the body's equation of state, rho = rho0 + p / c0^2 (its mass is kept, so its
   volume becomes m / rho): an initial pressure field such as the hydrostatic one. p must be
   finite and above -rho0 c0^2 (a positive density). Not for wall bodies. */
SPSDEF sps_result sps_body_set_pressure(sps_world* w, sps_body b, sps_pressure_fn fn, void* user);
/* Gives a Drucker-Prager body the geostatic stress of a layer at rest under the world's
   gravity (GRANULAR): at a depth d = surface_height - height below its free surface (height
   = -g^ . x of the reference position, g^ the direction of gravity; 0 above the surface) the
   vertical stress -rho0 |g| d and the horizontal ones k0 times it (in 2D also sigma_zz: plane
   strain); k0 = 0 selects Jaky's 1 - sin(phi). Call after the body's particles are added (it
   sorts the world's particles by body, as the first step would). SPS_ERR_INVALID_ARG for an
   invalid or non-Drucker-Prager body, zero gravity, k0 outside [0, 10] or a surface_height
   that is not finite. */
SPSDEF sps_result sps_body_set_geostatic_stress(sps_world* w, sps_body b, sps_real surface_height, sps_real k0);
/* Gives every particle of body b the external acceleration fn(x, x0, v, t, a, user) on top of
   the world's gravity, from the next sub-step on (EXTERNAL ACCELERATION); fn NULL removes it.
   SPS_ERR_INVALID_ARG for an invalid body or a wall body (its particles keep their velocity).
   No allocation; costs one call per particle and acoustic sub-step. */
SPSDEF sps_result sps_body_set_acceleration(sps_world* w, sps_body b, sps_acceleration_fn fn, void* user);
/* Constrains the particles whose reference position lies in [lo, hi]: on the axes in mask the
   velocity is held at velocity[axis] (NULL: zero), so mask SPS_AXIS_ALL with NULL clamps them
   (v = 0, x = x0). Later calls override earlier ones for the same particle. *count may be NULL. */
SPSDEF sps_result sps_body_constrain_box(sps_world* w, sps_body b, const sps_real lo[3], const sps_real hi[3],
                                         unsigned mask, const sps_real velocity[3], int* count);

/* Adds an observer at material point x (reference configuration) of body b: Shepard kernel
   interpolation of its neighbours' displacement and velocity. Allocates O(neighbours). */
SPSDEF sps_result sps_world_add_observer(sps_world* w, sps_body b, const sps_real x[3], sps_observer* out);
/* Interpolated displacement and velocity of an observer (length-3 arrays; either may be NULL). */
SPSDEF sps_result sps_observer_read(const sps_world* w, sps_observer o, sps_real displacement[3], sps_real velocity[3]);

/* Open boundaries (OPEN BOUNDARIES; chapter >>open boundaries): boxes where a body's particles
   are removed (a drain), created at an inflow or held at an outlet pressure. */
typedef enum sps_zone_kind {
    SPS_ZONE_KILL = 0,    /* the body's particles that enter the box are removed */
    SPS_ZONE_INFLOW = 1,  /* a buffer of lattice particles moving at the prescribed velocity: one that
                             leaves the box into the domain becomes fluid, and a new one is created
                             a box depth behind it (Lastiwka, Basa and Quinlan 2009) */
    SPS_ZONE_OUTFLOW = 2  /* fluid that enters the box becomes buffer: the outlet pressure, the velocity
                             it entered with; removed when it leaves the box downstream */
} sps_zone_kind;
/* A prescribed inflow velocity v [m/s] at position x [m] and time t [s] (z ignored in 2D). Called
   for each buffer particle at each advection step, from one thread at a time. */
typedef void (*sps_zone_velocity_fn)(const sps_real x[3], sps_real t, void* user, sps_real v[3]);
/* Zone definition. Get one from sps_default_zone_def(), edit, pass to sps_body_add_zone. */
typedef struct sps_zone_def {
    sps_zone_kind kind;        /* Default SPS_ZONE_KILL. */
    sps_real lo[3], hi[3];     /* [m] the box [lo, hi), inside the world (within a periodic axis's box,
                                  not across it), lo < hi; z ignored in 2D. Default 0 (set them). */
    int axis;                  /* inflow, outflow: the axis the flow crosses the box along, [0, dim).
                                  Default 0 (x). */
    int direction;             /* inflow, outflow: the flow's sense along axis, +1 or -1: an inflow's
                                  domain lies on that side of the box, an outflow's upstream of it.
                                  Default +1. */
    sps_real velocity[3];      /* inflow: the constant velocity [m/s] when velocity_fn is NULL,
                                  finite. Default 0. */
    sps_zone_velocity_fn velocity_fn; /* inflow: the velocity profile, or NULL. Default NULL. */
    void* velocity_user;       /* passed to velocity_fn. Default NULL. */
    sps_real pressure;         /* outflow: the outlet pressure [Pa] (gauge, as the fluid's p =
                                  c0^2 (rho - rho0)), finite. Default 0. */
    int internal_cookie;       /* set by sps_default_zone_def(); do not touch. */
} sps_zone_def;
SPSDEF sps_zone_def sps_default_zone_def(void);
/* Adds a zone to body b and returns its index (0, 1, ... in the order of addition) in *zone_id
   (may be NULL). An inflow zone fills its box with the body's lattice particles (as
   sps_body_add_box) at the prescribed velocity: fill the domain flush with it. Kill zones on
   fluid, granular and updated-Lagrangian solid bodies; inflow and outflow on fluid bodies; the
   box's depth along axis at least the kernel support 2h (a full support of buffer), its lo,
   hi within a periodic axis's box. Refused: a total-Lagrangian, free rigid or wall body, a
   body with SPS_ROTATION_PAIR in the world, a world with observers (they hold particle ids), a
   box reaching behind a wall, a def that fails its checks (the message names the field, its
   value and the allowed range). Allocates the zone index and velocity (four reals per particle)
   at the first zone, an outflow zone's bins (4 reals per dp of its cross-section). */
SPSDEF sps_result sps_body_add_zone(sps_world* w, sps_body b, const sps_zone_def* def, int* zone_id);
/* Sets an inflow zone's velocity: the constant velocity (length 3, finite; used when fn is NULL)
   and the profile fn (may be NULL) with its user pointer, from the next step on. No allocation. */
SPSDEF sps_result sps_world_set_zone_velocity(sps_world* w, int zone, const sps_real velocity[3], sps_zone_velocity_fn fn, void* user);
/* The particles zone `zone` created and removed so far (either output may be NULL). */
SPSDEF sps_result sps_world_zone_counts(const sps_world* w, int zone, long* created, long* removed);
/* Grows every particle array (and, at the next step, the neighbour storage and the zone bodies'
   own arrays) to hold n_particles, so that open boundaries create particles without allocating
   in a step (without it the arrays grow by half when full). Like adding particles, it asks for a
   step before sps_world_save. SPS_ERR_INVALID_ARG for n_particles outside [0, 2e8];
   SPS_ERR_OUT_OF_MEMORY. */
SPSDEF sps_result sps_world_reserve(sps_world* w, int n_particles);

/* Advances one advection step (dual stepping: several acoustic sub-steps; single: one).
   No allocation except at the first step after particles were added, when open boundaries
   create more particles than the capacity holds (sps_world_reserve), or when the neighbour
   lists outgrow their slots (MEMORY in the doc block). O(N neighbours). */
SPSDEF sps_result sps_world_step(sps_world* w);
/* Steps until time t_end (the last step is shortened to land on it), calling fn after each
   step (may be NULL; return nonzero to stop early). */
SPSDEF sps_result sps_world_advance(sps_world* w, sps_real t_end, sps_step_fn fn, void* user);
SPSDEF sps_real sps_world_time(const sps_world* w);
/* Acoustic sub-steps taken since the world was created (0 for NULL): what a real-time loop
   counts per frame without the cost of sps_world_diagnostics (which reports the same number). */
SPSDEF long sps_world_substep_count(const sps_world* w);
/* One frame of a real-time loop (see REAL-TIME FRAMES): runs max_substeps acoustic sub-steps,
   or fewer when wall_budget_s > 0 and the wall clock runs out first.
     max_substeps   acoustic sub-steps in the frame, >= 1. The frame continues the advection
                    step the last frame left open and leaves its last one open when the count
                    ends it early (REAL-TIME FRAMES).
     wall_budget_s  0: no budget; the frame always runs max_substeps sub-steps, and the state
                    after it depends only on the state before and max_substeps (bit-identical
                    for any thread count). > 0 (finite) [s]: wall time allowed from the call.
                    Between advection steps the frame estimates how many more sub-steps fit
                    (from its cost per sub-step so far), stops when not one does, and cuts the
                    next advection step to what fits (the next frame continues it); the first
                    advection step always runs. The frame then depends on the machine's speed.
     covered        (may be NULL) the simulated time the frame advanced [s], also on error.
   Returns SPS_OK, SPS_ERR_INVALID_ARG (message names the argument, its value and the allowed
   range) or an error of sps_world_step. No allocation (except, like sps_world_step, at the
   first step after particles were added or when the lists outgrow their slots). O(N
   neighbours) per sub-step. Not for two threads on
   one world at once. */
SPSDEF sps_result sps_world_advance_substeps(sps_world* w, int max_substeps, double wall_budget_s, sps_real* covered);
/* One frame of a game loop in simulated seconds (REAL-TIME FRAMES): advances the world by
   frame_seconds of simulated time, the sub-step count chosen by the library (the last step
   lands on the frame's end), or less when wall_budget_s > 0 and the wall clock runs out: a hard
   cap, overshot by at most about one sub-step (each step is cut to the sub-steps that fit at
   the cost per sub-step measured so far, or in the last budgeted frame), and the scene then
   runs in slow motion instead of dropping frames.
     frame_seconds  (0, 1] [s], e.g. 1/60 (a larger value is refused: the old sub-step count
                    passed here by mistake; sub-steps: sps_world_advance_substeps).
     wall_budget_s  0: none; the frame is deterministic (bit-identical for any thread count).
                    > 0 (finite) [s]: wall time allowed from the call.
     covered        (may be NULL) the simulated time advanced [s], also on error.
   Errors as sps_world_advance_substeps. */
SPSDEF sps_result sps_world_advance_frame(sps_world* w, sps_real frame_seconds, double wall_budget_s, sps_real* covered);

/* Drag (a mouse joint): pulls the particles of a body around a grabbed material point towards
   a target that the caller moves, by a spring of the caller's stiffness and damping spread over
   a kernel neighbourhood, so that no single particle is torn out. Particle i gets the external
   acceleration phi_i (stiffness (target - x_i) - damping v_i) / m_i with phi_i = m_i W(s_i) /
   sum_j m_j W(s_j), s_i its reference distance from the grabbed point scaled so the kernel's
   support is the radius: the total force is stiffness (target - x_grab) - damping v_grab, x_grab
   and v_grab the phi-weighted means. Keep the sps_drag alive and write drag.target each frame. */
typedef struct sps_drag {
    sps_real target[3];   /* where the grabbed point is pulled to [m]; the caller moves it */
    sps_real stiffness;   /* [N/m] (N/m per metre of depth in 2D), finite >= 0 */
    sps_real damping;     /* [N s/m], finite >= 0 */
    /* set by sps_body_drag_begin */
    sps_body body;
    const sps_world* world;
    sps_real anchor[3];   /* the grabbed material point (reference position of the nearest particle) */
    sps_real radius;      /* of the neighbourhood [m] */
    sps_real weight_sum;  /* sum_j m_j W(s_j) */
} sps_drag;
/* Grabs body b at the particle nearest to point (current positions): radius [m] of the
   neighbourhood, 0 selects the kernel's support 2h, else >= 2h (wider spreads the pull over
   more of the body). Installs the body's external acceleration (sps_body_set_acceleration; it
   replaces one the body had); drag->target starts at point. SPS_ERR_INVALID_ARG for NULL, a
   wall body, stiffness or damping not finite >= 0 or a radius below 2h; SPS_ERR_STATE for a
   body without particles. O(N). */
SPSDEF sps_result sps_body_drag_begin(sps_world* w, sps_body b, const sps_real point[3], sps_real stiffness, sps_real damping,
                                      sps_real radius, sps_drag* drag);
/* Lets go: removes the body's external acceleration. */
SPSDEF sps_result sps_body_drag_end(sps_world* w, sps_drag* drag);

/* Diagnostics for the whole world (b.id == 0) or one body. Allocates scratch on first call. O(N). */
SPSDEF sps_result sps_world_diagnostics(sps_world* w, sps_body b, sps_diagnostics* out);
/* CSV helpers for sps_diagnostics: header line and one row (no newline). */
SPSDEF const char* sps_diagnostics_csv_header(void);
SPSDEF int sps_diagnostics_csv_row(const sps_diagnostics* d, char* buf, size_t size);

/* Bulk particle data, zero-copy. Arrays are in the library's current order (sorted by cell,
   changes at every configuration update); use the ids to follow a particle. */
typedef enum sps_field {
    SPS_FIELD_POSITION_X, SPS_FIELD_POSITION_Y, SPS_FIELD_POSITION_Z,
    SPS_FIELD_VELOCITY_X, SPS_FIELD_VELOCITY_Y, SPS_FIELD_VELOCITY_Z,
    SPS_FIELD_REFERENCE_X, SPS_FIELD_REFERENCE_Y, SPS_FIELD_REFERENCE_Z,
    SPS_FIELD_DENSITY, SPS_FIELD_PRESSURE, SPS_FIELD_MASS
} sps_field;
SPSDEF int sps_world_particle_count(const sps_world* w);
/* The array of a field (NULL for z fields in 2D). Valid until the next step or add. */
SPSDEF const sps_real* sps_world_field(const sps_world* w, sps_field f);
/* Per-particle fields by name. Every particle has "position_x" .. "position_z", "velocity_x" ..,
   "reference_x" .. (per axis, up to dim), "density", "pressure", "mass", "volume",
   "density_rate" and the solver's "pressure_acceleration_x" .. (with contact and the external
   acceleration), "shear_acceleration_x" ..; a
   body has "shear_stress" (6: xx xy xz yy yz zz) and "velocity_gradient" (9, row-major) only
   if its model needs them (FIELDS), as well as "shear_increment_x" .. (mean rotation),
   "artificial_stress" (3: xx xy yy, OAS), and for J2 bodies "plastic_strain" (alpha),
   "plastic_work" [J] and, with a GNO penalty, "return_factor" (the last sub-step's r); a
   total-Lagrangian body with material.tl.damage_strain > 0 has "damage" (D, TOTAL-LAGRANGIAN); a
   Drucker-Prager body "plastic_strain" (accumulated deviatoric), "plastic_work" and, with
   stress diffusion, "stress_diffusion" (6: the last sub-step's rate, GRANULAR) and, in a world
   with a no-slip wall, "wall_equilibrium" (21: d sigma / dx and rho b of the particles within
   2h of one, >>walls for fluids); a body with a
   Kelvin-Voigt viscosity or contact damping "viscous_work" [J] (DAMPING, CONTACT).
   sps_world_field_by_name: the world's array of a field every particle has, *components (may
   be NULL) values per particle, particle i's at [components i]; same order and lifetime as
   sps_world_field. sps_body_field: the values of body b's particles for any field, the world's
   particles *first .. *first + *count - 1 in the current order (outputs may be NULL); after
   the first step (the bodies' ranges are set then). Both return NULL, and the world's last
   error says why, for an unknown name, an axis beyond dim or a field the body (or the world)
   does not have. */
SPSDEF const sps_real* sps_world_field_by_name(const sps_world* w, const char* name, int* components);
SPSDEF const sps_real* sps_body_field(const sps_world* w, sps_body b, const char* name, int* components, int* first, int* count);
/* Stable particle ids (0..count-1 in order of addition), in current order. Open boundaries
   renumber them, in the same order, when they remove particles (OPEN BOUNDARIES). */
SPSDEF const int* sps_world_particle_ids(const sps_world* w);
/* State of the particle with stable id. */
SPSDEF sps_result sps_world_particle(const sps_world* w, int id, sps_particle_state* out);
/* Writes the position and/or the velocity (length-3 arrays, z ignored in 2D; either may be NULL)
   of the particle with stable id, between steps (the next step rebuilds the neighbour lists
   from the new positions). A constrained axis keeps its prescribed velocity at the next kick.
   SPS_ERR_INVALID_ARG for an id outside [0, n) or a value that is not finite. No allocation. */
SPSDEF sps_result sps_world_set_particle(sps_world* w, int id, const sps_real position[3], const sps_real velocity[3]);
/* Stable id of the particle of body b whose reference position is nearest to x; -1 if none. */
SPSDEF int sps_world_nearest_particle(const sps_world* w, sps_body b, const sps_real x[3]);

/* Rigid walls (CONTACT): the half-space behind a wall is solid. */
typedef enum sps_wall_slip {
    SPS_WALL_FREE_SLIP = 0, /* normal repulsion only */
    SPS_WALL_NO_SLIP = 1    /* and a tangential drag that brings the contact layer to rest */
} sps_wall_slip;
/* Faces of sps_world_add_box_walls, to leave open. */
enum { SPS_FACE_X_LO = 1, SPS_FACE_X_HI = 2, SPS_FACE_Y_LO = 4, SPS_FACE_Y_HI = 8, SPS_FACE_Z_LO = 16, SPS_FACE_Z_HI = 32 };

/* Adds an analytic rigid wall through point with normal (length 3, any length > 0, pointing
   out of the solid half-space into the free side; z ignored in 2D). Every body's particles
   within 2h of it are pushed back (CONTACT). No particles, no cost beyond that distance test. */
SPSDEF sps_result sps_world_add_wall(sps_world* w, const sps_real point[3], const sps_real normal[3], sps_wall_slip slip);
/* Adds the walls of the box [lo, hi] facing inwards (a tank: 2 dim faces, those in open_faces
   left out, e.g. SPS_FACE_Y_HI for an open top in 2D). */
SPSDEF sps_result sps_world_add_box_walls(sps_world* w, const sps_real lo[3], const sps_real hi[3], unsigned open_faces, sps_wall_slip slip);
/* Sets the Coulomb friction coefficient mu (finite >= 0; default 0) of wall number `wall`
   (0, 1, ... in the order of addition; sps_world_add_box_walls adds its faces in the order x lo,
   x hi, y lo, y hi, z lo, z hi, leaving out the open ones), or of every wall added so far with
   wall = -1. A body touching it has the friction sqrt(mu_body mu) (CONTACT). A no-slip wall is
   refused: it holds the tangential velocity with no Coulomb bound already (mu = infinity).
   SPS_ERR_INVALID_ARG naming the value and the range. No allocation. */
SPSDEF sps_result sps_world_set_wall_friction(sps_world* w, int wall, sps_real mu);
/* Sets the tangential velocity [m/s] of the surface of wall number `wall` (numbered as for
   sps_world_set_wall_friction): a belt or a cavity's lid. The wall stays where it is; a
   fluid's no-slip images take the velocity 2 v_wall - v_j in its viscous force (FLUIDS), so the
   fluid at the wall moves with it. Solids' contact and free-slip walls do not read it. The
   energy account leaves out the work the moving surface does (a cavity's fluid gains its
   energy from it): set energy_growth_limit = INFINITY, or the watchdog warns.
   SPS_ERR_INVALID_ARG for a wall index out of range, a velocity not finite or with a component
   along the wall's normal. No allocation. */
SPSDEF sps_result sps_world_set_wall_velocity(sps_world* w, int wall, const sps_real velocity[3]);
/* Whether bodies a and b touch (CONTACT; default: every pair of bodies whose defs have
   contact = 1). a == b is refused: a body does not contact itself. */
SPSDEF sps_result sps_world_set_contact(sps_world* w, sps_body a, sps_body b, int touch);

/* Kernel value and derivative dW/dr for the world's kernel (for tests and teaching). */
SPSDEF sps_real sps_world_kernel(const sps_world* w, sps_real r);
SPSDEF sps_real sps_world_kernel_derivative(const sps_world* w, sps_real r);
/* Low-dissipation Riemann interface pressure P* (ENO eq. 14) for left state (rho_l, u_l, p_l, c_l)
   and right state (rho_r, u_r, p_r, c_r); u_l and u_r are the velocities along the direction
   from left to right, so u_l > u_r means compression (ANG eq. 18's convention). limiter = 0:
   beta = 1 (what the library uses for solids); limiter = 1: beta = min(3 max((u_l - u_r) / c, 0),
   1) with c the mean sound speed, dissipation only under compression. ENO eq. 16 prints
   (p_l + p_r)(u_l - u_r)/(rho_l c_l + rho_r c_r) inside the max, which is not dimensionless;
   we use the velocity jump over the sound speed instead. */
SPSDEF sps_real sps_riemann_pressure(sps_real rho_l, sps_real u_l, sps_real p_l, sps_real c_l,
                                     sps_real rho_r, sps_real u_r, sps_real p_r, sps_real c_r, int limiter);

#ifndef SPHSOLID_NO_STDIO
/* Options of sps_world_write_vtk_ex. sps_default_vtk_options() (all fields 0) gives what
   sps_world_write_vtk writes. */
typedef struct sps_vtk_options {
    int binary;           /* 0: ASCII, 9 significant digits. 1: binary legacy VTK, big-endian as
                             the format requires, values exact; 8-15x faster to write than
                             ASCII, 0.9x its size in double, 0.5x with single_precision (2D
                             plate, bench/VALIDATION.md). Default 0. */
    int single_precision; /* 1: reals written as 32-bit floats (type float, about 7 significant
                             digits). Default 0: sps_real's precision. */
    int stress;           /* 1: also the Cauchy stress sigma = -p I + tau [Pa] ("stress", 9
                             components, row-major; tau = 0 where a body does not track it; the
                             z row and column are 0 in 2D). Default 0. */
} sps_vtk_options;
SPSDEF sps_vtk_options sps_default_vtk_options(void);
/* Legacy VTK file (POLYDATA, one vertex per particle, in the current particle order) with the
   point data velocity, displacement, pressure, density, von_mises (and stress; plastic_strain
   when a body is J2; deformation_gradient, 9 values row-major and 0 for the other bodies, when
   a body is total-Lagrangian; damage, 0 for the other bodies, when a body has damage), body and id in one FIELD block, so that VTK's legacy reader (ParaView) shows every array with its default
   settings. options NULL: the defaults. SPS_ERR_INVALID_ARG (w or path NULL, an option not 0
   or 1), SPS_ERR_IO (cannot open or write; the message names the path). No allocation; O(N). */
SPSDEF sps_result sps_world_write_vtk_ex(sps_world* w, const char* path, const sps_vtk_options* options);
/* sps_world_write_vtk_ex with the default options (ASCII). */
SPSDEF sps_result sps_world_write_vtk(sps_world* w, const char* path);
/* Snapshot `index` of a time series: writes the VTK file dir/name_NNNN.vtk (NNNN the index, 4
   digits or more) as sps_world_write_vtk_ex does, and adds it, at the world's time, to the
   series file dir/name.vtk.series (ParaView's file-series JSON, version 1.0: File > Open
   name.vtk.series gives one data set whose time slider shows the physical times; ParaView's
   .pvd collections take only XML data sets, not legacy .vtk files). index 0 starts the series
   afresh; index k > 0 appends to it (only the closing lines are rewritten, so it is complete
   after every call). dir "" is the current folder; name letters, digits, '_', '-' and '.' only
   (it is written into the JSON). SPS_ERR_INVALID_ARG (NULL, index < 0, another character in
   name, a path longer than 4095), SPS_ERR_IO (a file cannot be opened or written, or the
   series file does not end as this function writes it: the message names it). No allocation;
   O(N). */
SPSDEF sps_result sps_world_write_vtk_series(sps_world* w, const char* dir, const char* name, int index, const sps_vtk_options* options);

/* Restart files (RESTART): sps_world_save writes the world's state between steps to path;
   sps_world_restore reads it into a world the program has built the same way (same defs,
   bodies, fills, velocities set, constraints, walls, contact settings, observers), and the run
   goes on bit for bit as the saved one would have, for any thread count.
   save: SPS_ERR_INVALID_ARG (w or path NULL), SPS_ERR_STATE (a world that cannot step: stopped
   at an instability, particles added since the last step: step first, or a state a restore
   would refuse, e.g. a density gone negative in the last sub-step, which the next step's guard
   stops at), SPS_ERR_IO (cannot open or write). Allocates the state's size in scratch (freed);
   O(N neighbours) (the file holds the neighbour lists); does not change the world.
   restore: SPS_ERR_INVALID_ARG (NULL, not a restart file, another format version, byte order
   or sps_real), SPS_ERR_STATE (the file's scene differs from the world's: the message names
   the first item, e.g. a def field such as gravity[1] or a body's shear, a particle count, or
   the reference positions),
   SPS_ERR_IO (cannot open or read, truncated, checksum wrong, or any item of the state out of
   its range: the file is untrusted, every index, count and real is checked before anything is
   applied, and the message names the item, the particle or body, the value and the range); on
   error the world's state is unchanged (it may have been prepared for stepping, as the first
   step does), and a restored world passes sps_world_validate. Allocates the
   file's size in scratch (freed) and, before the first step, what the first step allocates;
   O(N neighbours). Compiled out with SPHSOLID_NO_STDIO. */
SPSDEF sps_result sps_world_save(const sps_world* w, const char* path);
SPSDEF sps_result sps_world_restore(sps_world* w, const char* path);
#endif

#ifndef SPHSOLID_NO_GEOMETRY
/* Geometry from files and arrays (GEOMETRY; chapter >>geometry; compiled out with
   SPHSOLID_NO_GEOMETRY). A mesh is a closed triangle surface (3D) or a set of closed rings of
   segments, outer boundaries and holes (2D); sps_mesh_sdf is its exact signed distance (to the
   triangles or segments, negative inside) and fits the sdf callback of sps_body_add_sdf,
   sps_body_add_sdf_relaxed and sps_measure_fill. A mesh is read-only once made: one mesh may
   serve any number of worlds and threads. */
typedef struct sps_mesh sps_mesh;
typedef struct sps_mesh_def {
    sps_real scale;          /* factor on the coordinates (0.001: a file in millimetres), > 0.
                                Default 1. */
    int centre;              /* 1: after scaling, the bounding box's centre moved to the origin.
                                Default 0. */
    sps_real rotate[3];      /* then rotated [rad] about x, then y, then z (2D: rotate[2] only).
                                Default 0. */
    sps_real translate[3];   /* then moved [m]. Default 0. */
    int flip;                /* 1: every triangle turned over (a mesh whose normals point
                                inwards, which is refused otherwise). Default 0. */
    int allow_open;          /* 3D: 1 accepts a mesh with boundary edges or inconsistently
                                oriented triangles (the sign is then the side of the nearest
                                triangle, right only near it); 0 refuses it. Default 0. */
    sps_real chord_error;    /* SVG: the largest distance of the flattened curves from the
                                Bezier curves, in the drawing's units, >= 0; 0: 1e-3 of the
                                drawing's size. Default 0. */
    sps_allocator allocator; /* Default: SPHSOLID_MALLOC / SPHSOLID_FREE. */
    int internal_cookie;     /* set by sps_default_mesh_def(); do not touch. */
} sps_mesh_def;
/* What a mesh holds (after the def's transform). */
typedef struct sps_mesh_info {
    int dim;                     /* 3: triangles; 2: segments of closed rings */
    int elements;                /* triangles (segments) kept */
    int vertices;                /* distinct vertices */
    int rings;                   /* 2D: closed rings (outer boundaries and holes) */
    int degenerate;              /* triangles of zero area (segments of zero length) skipped */
    int boundary_edges;          /* 3D: edges of one triangle only (0: closed) */
    int inconsistent_edges;      /* 3D: edges two triangles run along in the same direction */
    int nonmanifold_edges;       /* 3D: edges of more than two triangles */
    int closed, oriented;        /* 1: no boundary (or non-manifold) edge; 1: consistently oriented */
    sps_real lo[3], hi[3];       /* bounding box [m] */
    sps_real volume, area;       /* enclosed volume [m^3] and surface area [m^2]; 2D: area [m^2]
                                    and perimeter [m] */
} sps_mesh_info;
SPSDEF sps_mesh_def sps_default_mesh_def(void);
/* A mesh from nv vertices xyz (3 reals each) and nt triangles tri (3 vertex indices each,
   0-based, counter-clockwise seen from outside). def NULL: the defaults. On error *out is NULL
   and msg (may be NULL) gets the reason, naming the triangle or vertex: SPS_ERR_INVALID_ARG
   (NULL arrays, counts < 1, an index out of range, a coordinate not finite, no triangle of
   non-zero area, an open or inconsistently oriented mesh without allow_open, a mesh that faces
   inwards: negative signed volume), SPS_ERR_OUT_OF_MEMORY. Allocates O(nt); O(nt log^2 nt). */
SPSDEF sps_result sps_mesh_from_triangles(int nv, const sps_real* xyz, int nt, const int* tri, const sps_mesh_def* def, sps_mesh** out,
                                          char* msg, size_t msg_size);
/* A 2D mesh from nrings closed rings: ring r has ring_points[r] >= 3 points, all of them in xy
   (2 reals each, ring after ring; a last point equal to the first is dropped). Outer boundaries
   and holes in any orientation (inside = inside an odd number of rings). Errors as
   sps_mesh_from_triangles, and a ring that crosses itself or another ring. */
SPSDEF sps_result sps_mesh_from_rings(int nrings, const int* ring_points, const sps_real* xy, const sps_mesh_def* def, sps_mesh** out,
                                      char* msg, size_t msg_size);
#ifndef SPHSOLID_NO_STDIO
/* A mesh from a file, its format told by its content (GEOMETRY): binary STL (its size is
   84 + 50 x its triangle count), ASCII STL, Wavefront OBJ, an SVG drawing's paths, or an
   outline (lines "x y", a blank line between rings). Errors as sps_mesh_from_triangles, and
   SPS_ERR_IO (missing, empty, unreadable or not a mesh file; a binary STL whose size disagrees
   with its count; a syntax error), the message naming the file and the line or triangle. */
SPSDEF sps_result sps_mesh_load(const char* path, const sps_mesh_def* def, sps_mesh** out, char* msg, size_t msg_size);
#endif
SPSDEF void sps_mesh_destroy(sps_mesh* m);
SPSDEF sps_mesh_info sps_mesh_get_info(const sps_mesh* m);
/* The signed distance [m] from x to the mesh (negative inside; 2D: x[2] ignored; NaN for an x
   that is not finite). mesh is an sps_mesh*. O(log n) near the surface (a bounding-volume
   hierarchy; deep inside a curved mesh more triangles are near-equidistant); thread-safe; no
   allocation. */
SPSDEF sps_real sps_mesh_sdf(const sps_real x[3], void* mesh);
/* Fills body b with the mesh's inside, cut by the box [lo, hi] (both NULL: no cut; e.g. water
   up to a level), on the world's lattice (points (k + 1/2) dp, whatever the box):
   relax_iterations < 0 a lattice fill (sps_body_add_sdf), else relaxed (sps_body_add_sdf_relaxed,
   the cut a surface too; 0 selects 300). Errors as those, and a mesh of another dim. */
SPSDEF sps_result sps_body_add_mesh(sps_world* w, sps_body b, const sps_mesh* m, const sps_real lo[3], const sps_real hi[3],
                                    int relax_iterations, int* added);
/* A container: fills body b (a wall body) with the lattice points whose distance outside the
   mesh is in (0, layers dp), a shell around the mesh's surface (the container's inner surface),
   cut by [lo, hi] (NULL: no cut; a hi at the mesh's top leaves a glass open). Fill the fluid with
   sps_body_add_mesh: the same lattice, its first layer dp from the wall's. layers in [1, 20]. */
SPSDEF sps_result sps_body_add_mesh_shell(sps_world* w, sps_body b, const sps_mesh* m, const sps_real lo[3], const sps_real hi[3],
                                          int layers, int* added);
#endif

#ifdef __cplusplus
}
#endif
#endif /* SPHSOLID_H_INCLUDED */

/* ============================================================================================ */
#ifdef SPHSOLID_IMPLEMENTATION
#ifndef SPHSOLID_IMPLEMENTATION_INCLUDED
#define SPHSOLID_IMPLEMENTATION_INCLUDED

#include <math.h>
#include <string.h>
#include <stdarg.h>
#include <stdio.h>
#include <time.h>
#include <limits.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#if defined(SPHSOLID_MALLOC) && !defined(SPHSOLID_FREE) || !defined(SPHSOLID_MALLOC) && defined(SPHSOLID_FREE)
#error "define both SPHSOLID_MALLOC and SPHSOLID_FREE, or neither"
#endif
#ifndef SPHSOLID_MALLOC
#include <stdlib.h>
#define SPHSOLID_MALLOC(sz, u) ((void)(u), malloc(sz))
#define SPHSOLID_FREE(p, u) ((void)(u), free(p))
#endif
#ifndef SPS_ASSERT
#include <assert.h>
#define SPS_ASSERT(c) assert(c)
#endif

#if defined(__GNUC__) || defined(__clang__)
#define SPS__INLINE static inline __attribute__((always_inline))
#define SPS__RESTRICT __restrict
#else
#define SPS__INLINE static inline
#define SPS__RESTRICT
#endif

#ifdef _OPENMP
#define SPS__PRAGMA(x) _Pragma(#x)
#else
#define SPS__PRAGMA(x)
#endif
/* Unrolls a short loop (over dimensions, matrix entries or OAS's exponent) inside a lane loop:
   GCC vectorises a lane loop only when no loop is left inside it. */
#if defined(__GNUC__) && !defined(__INTEL_COMPILER)
#define SPS__UNROLL _Pragma("GCC unroll 12")
#else
#define SPS__UNROLL
#endif
/* Parallel loop with its own thread team (configuration updates, diagnostics): static schedule
   so each thread's share is fixed; serial when the loop is too small to pay for the fork. */
#define SPS__PARALLEL_FOR(w, n) SPS__PRAGMA(omp parallel for schedule(static) num_threads((w)->threads) if ((n) > 256))

#ifdef SPHSOLID_FLOAT
#define SPS__SQRT sqrtf
#define SPS__SIN sinf
#define SPS__COS cosf
#define SPS__FLOOR floorf
#define SPS__ATAN2 atan2f
#define SPS__EXPM1 expm1f
#define SPS__LOG logf
#define SPS__EXP expf
#define SPS__FABS fabsf
#define SPS__CBRT cbrtf
#else
#define SPS__SQRT sqrt
#define SPS__SIN sin
#define SPS__COS cos
#define SPS__FLOOR floor
#define SPS__ATAN2 atan2
#define SPS__EXPM1 expm1
#define SPS__LOG log
#define SPS__EXP exp
#define SPS__FABS fabs
#define SPS__CBRT cbrt
#endif
#define SPS__PI SPS_R(3.14159265358979323846)
#define SPS__COOKIE 0x5350531
/* Particles per lane group: the neighbour passes work on SPS__LANES consecutive particles at
   once, one per SIMD lane (two 512-bit vectors of sps_real: 16 doubles or 32 floats). Measured
   on the 2D plate (bench/VALIDATION.md, design notes): 16 doubles in 512-bit vectors 1.2x faster than 8 in
   256-bit ones, 4 doubles 1.6x slower, 32 barely faster than 16.
   Per-particle arrays carry SPS__LANES zeroed slots beyond the capacity so a group that runs
   past the last particle reads valid memory. */
#define SPS__LANES (128 / (int)sizeof(sps_real))
#define SPS__MAX_BODIES 4096
#define SPS__OAS_MAX_EXPONENT 12 /* the largest oas_exponent */
#define SPS__MAX_THREADS 1024
#define SPS__WARNED 32 /* warning texts remembered per world (sps__warn prints each once) */
#define SPS__DT_COLLAPSE 1e-3 /* acoustic dt / dt at rest below which a run is unstable */
#define SPS__MAX_PARTICLES 200000000 /* 2e8: keeps every per-particle array index inside an int */

/* >>state */

/* The model of a body as data (the tables and their use: chapter >>model). */
/* ---- materials ---- */
typedef struct sps__material_constants {
    sps_real c0; /* signal speed [m/s]: the time step and the Riemann impedance rho0 c0 */
    sps_real G;  /* shear modulus [Pa] */
    sps_real K;  /* bulk modulus [Pa]: the equation of state p = K (rho/rho0 - 1) = c0^2 (rho - rho0) */
} sps__material_constants;

/* The yield surface of a plastic material. */
typedef enum { SPS__YIELD_NONE, SPS__YIELD_VON_MISES, SPS__YIELD_DRUCKER_PRAGER } sps__yield;
/* How walls act on a body (a material row's column, chapter >>walls for fluids). */
typedef enum {
    SPS__MIRROR_NONE,     /* the solids' wall penalty (chapter >>contact) */
    SPS__MIRROR_PRESSURE, /* mirror particles carrying the particle's pressure, corners imaged too (a fluid) */
    SPS__MIRROR_STRESS    /* mirror particles carrying the particle's stress (continued by equilibrium at a
                             no-slip wall), the no-slip image velocity in its velocity gradient, each wall
                             on its own with its Coulomb friction and no corner images (granular media) */
} sps__mirror_kind;

/* The Drucker-Prager cone of a body (>>material: Drucker-Prager). */
typedef struct sps__yield_cone {
    sps_real alpha_phi, k_c, alpha_psi; /* UTVF eq. 14 */
    sps_real k0; /* 1 - sin(phi): the geostatic stress's horizontal to vertical ratio */
} sps__yield_cone;

/* The shared fields a kind reads beyond its density (sps__material_model.reads): the def items
   of the other kinds get a warning when set (sps__warn_unread_fields). A kind's own parameter
   sub-struct (material.j2, .fluid, .granular) is read by that kind alone: its chapter's reads
   function (sps__reads_j2, ...) says so. */
enum {
    SPS__READS_MODULI = 1, /* youngs_modulus, poisson_ratio */
    SPS__READS_STRESS = 2  /* track_stress and, updated Lagrangian, the shear formulation: a stress of its own */
};

/* A material's row: its name and the properties the step reads, one row in each material's
   chapter (its check, constants and energy: the switches of chapter >>generic). */
typedef struct sps__material_model {
    sps_material_kind kind;
    const char* name;
    int kinematic; /* its particles move as prescribed: no passes, no forces (a wall body) */
    sps__yield plastic; /* the yield surface its stress is returned onto, if any */
    int shear;     /* it has a shear stress: 0 for a fluid */
    /* The Riemann solver's terms (UTVF eqs. 16-20). limiter: the coefficient eta of the
       dissipation limiter beta = min(eta max(-v_ij . e_ij / c0, 0), 1) of the momentum
       equation, or 0 for beta = 1 (the reference code's choice for solids); riemann_density:
       the continuity equation's pressure term (p_i - p_j) / (rho0 c0), which the reference
       code leaves out for solids (DESIGN: facts from the reference implementation);
       limiter_per_dim: a further eta per space dimension (granular: 20 d). */
    sps_real limiter, limiter_per_dim;
    int riemann_density;
    sps__mirror_kind mirrored; /* walls act on it through mirror particles (>>walls for fluids), or not:
                     the solids' penalty */
    int pressure_of_density; /* p = c0^2 (rho - rho0) at every half drift; 0: p is -tr(sigma)/3 of
                                its integrated stress and rho = rho0 + p / c0^2 (Drucker-Prager) */
    int viscous; /* the force of its material.viscosity (an SPS__VISCOUS_ value): NONE refuses it */
    int reads;   /* the material fields it reads (SPS__READS_ bits) */
} sps__material_model;

/* ---- stabilisations (the shear formulations; SHEAR FORMULATIONS in the manual) ---- */
typedef struct sps__stabilisation {
    sps_shear shear;
    const char* name;
    int stress_force;      /* divergence of tau in the momentum equation (ENO eq. 17) */
    int eno;               /* accumulated Laplacian of velocity (ENO eq. 24) */
    int penalty;           /* accumulated hourglass penalty, a pass of its own (ANG eqs. 43-46) */
    int projected;         /* the penalty projected on e_ij (ANG eq. 46) */
    int artificial_stress; /* Gray et al.'s artificial stress */
    int rotated;           /* the -A variants: increments turned with the body (def rotation) */
    sps_real stable_cfl[2];/* the largest cfl_acoustic measured stable in 2D and 3D (STABLE CFL) */
} sps__stabilisation;

/* How the stored shear increments of a body turn with it (ANG Algorithms 1-2). */
typedef enum {
    SPS__TURN_NONE,     /* not turned (ENO, GNO, OG) or kept per pair (SPS_ROTATION_PAIR) */
    SPS__TURN_MEAN,     /* by the body's mean Rodrigues matrix (ANG eqs. 41-42) */
    SPS__TURN_PARTICLE  /* by each particle's own (ANG eq. 34) */
} sps__turn;

/* A pass kernel: one lane group g of body b (see sps__run_groups). */
struct sps__body;
typedef void (*sps__group_kernel)(sps_world* w, const struct sps__body* b, int g, sps_real dt);

/* A pair loop: the neighbour sums of lane group g of body b with the pair terms `terms` (an
   SPS__TERM_ bit set) into its lane arrays (struct sps__lane_sums, chapter >>solver: the
   updated-Lagrangian passes): an instance compiled for one dimension, pair geometry and set of
   terms (which ignores `terms`, its own being literals), or a pass's generic loop, which reads
   the pair geometry and the terms at run time (SPS__INSTANCES). A pass's kernel runs its pair
   loop and then its finish, which is compiled once per dimension only. */
struct sps__lane_sums;
typedef void (*sps__pair_loop)(sps_world* w, const struct sps__body* b, int g, sps_real dt, int terms, struct sps__lane_sums* sums);

/* The pass kernels of a body: the kernels the step runs, NULL when the body has no such pass
   (penalty: no penalty; stress, run before the pressure pass: all but total-Lagrangian bodies;
   continuity: those), and the pair loops of the world's mode they call. */
typedef struct sps__passes {
    sps__group_kernel pressure, continuity, penalty, stress;
    sps__pair_loop pressure_pairs, continuity_pairs, penalty_pairs;
    /* penalty_in_pressure_pass: the pressure pass's pair loop that also sums the previous
       sub-step's penalty (NULL without) */
    sps__pair_loop pressure_penalty_pairs;
    /* the pair terms each of those loops runs with (SPS__TERM_ bits) */
    int pressure_terms, continuity_terms, penalty_terms, pressure_penalty_terms;
    /* the pressure pass's rare terms, each a loop of its own, or NULL: OAS's artificial stress, a
       solid's Kelvin-Voigt damping */
    sps__pair_loop art_pairs, damping_pairs;
} sps__passes;

/* A body's viscous force (sps__model.viscous): none, a fluid's Newtonian viscosity (FLUIDS), a
   solid's Kelvin-Voigt material damping (>>material: Kelvin-Voigt). */
enum { SPS__VISCOUS_NONE, SPS__VISCOUS_NEWTON, SPS__VISCOUS_KELVIN_VOIGT };

/* What the step runs for a body, resolved once from its def. */
typedef struct sps__model {
    const sps__material_model* material;
    const sps__stabilisation* stabilisation;
    sps__turn turn;
    int paired;   /* increments kept per neighbour pair (SPS_ROTATION_PAIR on a -A variant) */
    int stress;   /* the shear stress tau is integrated (stress force, or track_stress) */
    int gradient; /* the velocity gradient L is needed (stress, or a turned rotation) */
    int artificial_stress; /* Gray's artificial stress is computed (OAS) */
    int plastic;  /* an sps__yield: the return map after the stress update (J2's radial return, the
                     Drucker-Prager cone); plastic strain and work fields */
    int scaled_penalty; /* the GNO penalty scaled per pair by the particles' return factors */
    int penalty_in_pressure; /* the GNO penalty summed in the next sub-step's pressure pass
                                (penalty_in_pressure_pass; chapter >>solver: the penalty) */
    int limited;  /* the Riemann dissipation limited (material limiter > 0: fluids) */
    int viscous;  /* SPS__VISCOUS_NEWTON: a Newtonian viscous force (a fluid with viscosity > 0);
                     SPS__VISCOUS_KELVIN_VOIGT: a solid's material damping (>>material: Kelvin-Voigt) */
    int riemann_density; /* the continuity equation's Riemann pressure term (fluids, granular) */
    int diffusion; /* the stress diffusion of a Drucker-Prager body (material.granular.stress_diffusion > 0) */
    sps__mirror_kind mirrored; /* walls act through mirror particles (the material's choice) */
    int pressure_of_density; /* the half drift sets p from rho (not for Drucker-Prager) */
    sps_transport transport; /* the transport correction after each sub-step (>>transport) */
    int total_lagrangian; /* reference neighbours and gradients (chapter >>solver: total Lagrangian) */
    int damage;   /* total Lagrangian with material.tl.damage_strain > 0: the damage field (TL eqs. 45-46) */
    int free_rigid; /* a free rigid body: its particles move as one body by Newton-Euler (chapter
                       >>material: free rigid bodies); its row is kinematic (no pass of its own) */
    sps__passes pass;
} sps__model;

/* The motion of a free rigid body (chapter >>material: free rigid bodies). The particles sit at
   x_i = x + turn axes^T (X_i - reference_centre), X_i their reference positions; turn maps the
   principal axes to the world. */
typedef struct sps__rigid {
    int ready;                   /* set up from its particles (sps__rigid_setup) for count particles */
    int count;
    int mass_set;                /* sps_body_set_mass_properties was called */
    sps_real mass, moment[3];    /* mass and principal moments of inertia about the centre of mass */
    sps_real axes[9];            /* the principal axes in the reference configuration (columns) */
    sps_real reference_centre[3];
    sps_real x[3], turn[9], v[3], L[3]; /* at the ends of sub-steps: centre of mass, rotation
                                           (principal axes to world), velocity, angular momentum
                                           about the centre of mass (world axes) */
    sps_real mid_x[3], mid_turn[9];     /* at the middle of the sub-step (half drift) */
    sps_real applied_force[3], applied_point[3]; /* sps_body_set_force; the point in principal axes */
    sps_real force[3], torque[3];       /* the last sub-step's resultant */
    unsigned lock_translation, lock_rotation;
    int contacts;                       /* its particles that received a force in the last sub-step */
} sps__rigid;


/* The churn watch of a fluid body (sps__watch_churn). */
typedef struct sps__churn {
    sps_real weight_height;          /* m |g| H at its first check [J]; 0 before */
    sps_real window_end, window_max; /* the current quarter second and its largest kinetic energy */
    sps_real previous_max;           /* the last whole window's */
    int rises, warned;               /* windows in a row each SPS__CHURN_RISE times the one before */
} sps__churn;

typedef struct sps__body {
    sps_body_def def;
    char name[32];
    int begin, end;       /* particle range in the current (sorted) order */
    int group0, ngroups;  /* its lane groups: SPS__LANES particles each from begin, the last partial */
    sps__model model;     /* what the step runs for it (sps__resolve_model, sps__choose_passes) */
    sps__material_constants mat; /* its material's c0, G and K */
    sps_real rho0, zeta;
    sps_real z_riemann;   /* rho0 c0: dissipation impedance of the Riemann solver */
    sps_real rest_pressure_gradient[3]; /* a fluid: rho0 g, the pressure gradient of water at rest,
                                           which the density diffusion leaves alone (>>material:
                                           weakly compressible fluid); 0 for other bodies */
    sps_real xi, oas_eps, oas_w_dp;
    sps_real oas_factor[SPS__OAS_MAX_EXPONENT]; /* OAS: 1 for the first oas_exponent factors of f^n, then 0 */
    sps_real mean_rotation[9];
    sps_real mean_spin[9];     /* angular velocity of mean_rotation as a skew matrix (sps__kick) */
    sps_real frame_velocity[3]; /* its mass-weighted mean velocity at the start of the advection
                                   step: the time-step speeds are measured against it */
    sps_acceleration_fn acceleration; /* external acceleration (sps_body_set_acceleration), or NULL */
    void* acceleration_user;
    int count;                 /* particles added (a body must have some before the first step) */
    sps_real reach;            /* largest distance of a reference position from the reference
                                  centre of mass: the body's size for the escape guard */
    sps_real escape_limit;     /* a particle farther than this from the current centre of mass
                                  has escaped (sps__check_escape) */
    int fragment_reported;     /* report_fragments: the warning was given */
    int driven;                /* the watchdog counts the work done on it: a rigid body (its
                                  work on the others), a moving velocity constraint or an
                                  external acceleration */
    sps_real energy_start;     /* its account (kinetic + strain + contact + gravity potential + plastic
                                  work - work of prescribed motions) at the watchdog's start */
    sps__churn churn;          /* a fluid's kinetic energy, watched for a churn (sps__watch_churn) */
    /* its optional per-particle arrays (the sps__fields rows owned by a body), allocated at commit
       when its model needs them, else NULL: particle begin + k at [components k], with
       SPS__LANES zeroed slots of lane padding after the last */
    sps_real *acc_d[3], *tau, *art, *grad;
    sps_real* driven_work; /* driven: work done by its prescribed motion through each particle */
    sps_real *plastic_strain, *plastic_work, *return_factor; /* J2 bodies */
    sps_real* transport;   /* TVF, UTVF: SPS__TRANSPORT_VALUES per particle (>>transport) */
    sps_real* diffusion;   /* Drucker-Prager with stress diffusion: its rate (6 per particle) */
    sps_real* next_pressure; /* Drucker-Prager: the pressure of the stress update (sps__finish) */
    sps_real* wall_equilibrium; /* Drucker-Prager at no-slip walls: SPS__EQUILIBRIUM_VALUES per particle */
    int wall_equilibrium_needed; /* sps__wants_wall_equilibrium, as of the last commit */
    sps__yield_cone cone;  /* Drucker-Prager: the yield cone */
    sps_real limiter_eta_c0; /* eta / c0 of the Riemann dissipation limiter (UTVF eq. 20), 0: none */
    sps_real density_diffusion; /* 1: the Riemann solver's density term in the continuity sums, 0: none
                                   (a fluid's material.fluid.dissipation = none; sps__fluid_rest_gradient) */
    sps_real diffusion_rate; /* 2 zeta h c0 of the stress diffusion */
    sps_real viscous_coefficient; /* a viscous fluid: 2 mu / the lattice's kernel-gradient moment
                                     (sps__fluid_rest_gradient; the Newtonian force's factor) */
    sps_real divergence_scale; /* fluid, Drucker-Prager: 1 / the lattice's kernel-gradient moment
                                  (sps__lattice_gradient_moment), the pressure force's and
                                  stress divergence's scale */
    sps_real geostatic[6]; /* -rho0 [g^ g^ + K0 (I - g^ g^)] (g^ = g/|g|): the geostatic stress
                              difference of a pair is this times g . x_ij, which the stress
                              diffusion leaves alone */
    sps_real transport_alpha; /* alpha of UTVF eq. 30 */
    sps_real *tl_correction, *tl_deformation, *tl_stress; /* total-Lagrangian bodies: B_i, F_i, P_i B_i */
    sps_real* tl_plastic; /* total-Lagrangian J2 bodies: C_p^-1 - I (sps__tl_j2) */
    sps_real* damage;     /* total-Lagrangian bodies with damage: D in [0, 1] (sps__tl_damage) */
    sps_real* viscous_work; /* Kelvin-Voigt bodies: the work each particle's viscous force dissipated [J] */
    int field_count; /* particles they hold: its count at the last commit */
    int field_room;  /* particles they have room for (a body with zones: the world's capacity) */
    int built_count; /* its count as the program built it (a world with zones: the restart fingerprint's) */
    int zoned;       /* it has open-boundary zones: its particle count changes in a run */
    int reference_built; /* total Lagrangian: its reference neighbour lists and B_i are built (they
                            are rebuilt only when a commit re-sorts the particles) */
    sps_real tl_c_ref;   /* total Lagrangian: its signal speed in the reference state (sps__tl_signal_speeds) */
    sps_real* tl_pairs;  /* total Lagrangian: its reference pair table, SPS__TLP_ROWS(dim) rows of tl_slots
                            (sps__tl_pair_table) */
    int* tl_reverse;     /* ... for each slot the slot of the same pair in the neighbour's list */
    long tl_slots;       /* ... the body's lane slots, the rows' length (0: to be built) */
    int* reference_slots; /* total Lagrangian: its lane slots' neighbours (nb_j from its first
                             slot), placed again by every list rebuild (sps__place_reference_slots) */
    int hexagonal;       /* its fills use the hexagonal lattice (def.lattice resolved: sps__kind_fills_hexagonal) */
    int coupled;         /* a fluid that touches a solid body: its continuity pass takes the solid's
                            particles as wall images (chapter >>coupling: fluid-structure) */
    sps__rigid rigid;    /* a free rigid body's motion (model.free_rigid) */
    sps__rigid rigid_good; /* its copy with the last good state (keep_last_good_state) */
} sps__body;

/* How two bodies touch (the world's touch table): by the contact law, or a fluid and a solid
   by the fluid-structure coupling (chapter >>coupling: fluid-structure). */
enum { SPS__TOUCH_NONE, SPS__TOUCH_CONTACT, SPS__TOUCH_COUPLED };

/* The transport correction's values per particle (chapter >>transport): the consistency sum
   g = sum_j grad W_ij V_j (then the shift), the position divergence, the unit surface normal. */
enum { SPS__TR_G, SPS__TR_DIVR = 3, SPS__TR_NORMAL = 4, SPS__TRANSPORT_VALUES = 7 };

/* An analytic rigid wall (chapter >>contact): the half-space (x - point) . normal < 0 is solid. */
typedef struct sps__wall {
    sps_real point[3], normal[3]; /* normal of unit length */
    sps_wall_slip slip;
    sps_real friction; /* its Coulomb coefficient (sps_world_set_wall_friction) */
    sps_real velocity[3]; /* its surface's tangential velocity (sps_world_set_wall_velocity) */
} sps__wall;
#define SPS__WALL_TABLE 64 /* intervals of the wall tables over [0, 2h] */

typedef struct sps__constraint {
    unsigned mask;
    sps_real velocity[3];
} sps__constraint;

/* An open-boundary zone (chapter >>open boundaries). */
typedef struct sps__zone {
    sps_zone_def def;
    int body;
    sps_real depth;    /* hi - lo along its axis: where a new inflow particle goes behind the one that left */
    sps_real rho_out;  /* outflow: the density of the outlet pressure, rho0 + p / c0^2 */
    long created, removed;
    /* outflow: the velocity of the fluid within 2h upstream of the buffer, per dp-wide bin of the
       box's cross-section (sums of v, then the count: 4 reals a bin), which its buffer takes */
    sps_real* bins;
    int bin_n[3], nbins;
} sps__zone;

typedef struct sps__observer {
    int body, first, count; /* weights in obs_ids / obs_weights [first, first + count) */
} sps__observer;

/* The advection step under way (ENO eqs. 25-26): what its sub-steps have used of it. A real-time
   frame ends where its simulated time does, mid-step, and the next frame continues the step
   (open = 1) instead of rebuilding the neighbour lists (>>realtime). */
typedef struct sps__advection_step {
    int open;         /* 1: the next frame continues this step without a configuration update */
    int substeps;     /* its acoustic sub-steps so far */
    int max_substeps; /* its cap: def.max_substeps (1 with single stepping) */
    sps_real elapsed; /* simulated time it has covered */
    sps_real travel;  /* the distance its fastest particle may have moved (the sum of vmax dt) */
    sps_real travel_max, dt_ad; /* its ends: CFL_ad h of travel and ENO eq. 25's dt_ad */
} sps__advection_step;

struct sps_world {
    sps_world_def def;
    int dim, threads;
    uint32_t tag; /* identifies handles of this world */
    sps_real h, support, kernel_norm, dp_volume, inv_h, dw_scale; /* dw_scale = kernel_norm / h */
    char error[1024];
    struct { uint64_t hash; int count; char head[96]; } warned[SPS__WARNED]; /* each warning's text, once */
    int nwarned, warnings_issued;

    /* particles (SoA, capacity cap) */
    int n, cap;
    int reserved; /* the most particles sps_world_reserve asked room for (sps__trim_particle_arrays keeps it) */
    sps_real *pos[3], *vel[3], *ref[3], *acc_p[3], *acc_s[3];
    sps_real *rho, *drho, *p, *vol, *mass;
    int *id, *body, *slot_of_id, *cons;
    sps_real *zone, *zone_vel[3]; /* open boundaries: NULL without zones (>>open boundaries) */
    int needs_sort_by_body; /* particles were added since the last step */

    /* run-time guards (sps__check_state, sps__check_time_step) */
    int stopped;                   /* a step failed with SPS_ERR_UNSTABLE: no more steps */
    struct {                       /* the energy watchdog (sps__watch_energy) */
        int armed, fired;          /* its start is taken; it has warned */
        long checked_at;           /* acoustic steps at its last check */
        sps_real start, scale, start_time; /* the account at the start, the largest mechanical energy since */
        sps_real noise;            /* growth below it is round-off (sps__energy_round_off, set by the commit) */
        sps_real worst;            /* the largest growth / scale found (sps_diagnostics.energy_growth) */
        int events;                /* checks above the limit (sps_diagnostics.energy_growth_events) */
    } watch;
    int lists_valid;               /* the neighbour lists match the particle order (a failed
                                      configuration update may leave them half built) */
    char failure[1024];            /* ... and its message */
    /* last good state (keep_last_good_state): positions, velocities, density, pressure (and the
       stress) at the last configuration update, field-major with stride good_cap, in the
       particle order of that moment (good_id) */
    sps_real* good;
    int *good_id, good_n, good_cap;
    sps_real good_time;

    sps__body* bodies;
    int nbodies, bodies_cap;
    int free_rigid_bodies; /* bodies with model.free_rigid: the kick sums their forces (>>material: free rigid bodies) */
    int wall_equilibrium;  /* a body continues its no-slip images' shear by equilibrium (sps__measure_wall_equilibrium) */
    sps__constraint* constraints;
    int ncons;
    struct sps__zone* zones; /* open boundaries (>>open boundaries) */
    int nzones;
    int built;              /* a world with zones: the scene as built is recorded (its first zone update) */
    int built_n;            /* ... its particle count */
    uint64_t built_scene;   /* ... and its scene hash (the restart fingerprint's, sps__scene_hash) */
    sps__observer* observers;
    int nobs;
    int *obs_ids;
    sps_real* obs_weights;
    int obs_len;

    /* Neighbours, in lane-group slots: group g owns slots [nb_group_start[g], nb_group_start[g + 1]),
       SPS__LANES per neighbour rank k: slot nb_group_start[g] + k SPS__LANES + lane holds the k-th
       neighbour of the lane's particle, or the particle itself (padding) past its nb_count.
       A particle's neighbours are nb_j[nb_first[i] + k SPS__LANES], k < nb_count[i]. */
    int *nb_group_start, *nb_first, *nb_j, *nb_count;
    int* list_chunk; /* the lists of SPS__LIST_CHUNK particles on their way into the slots (sps__list_body) */
    int ell_width, group_cap; /* ell_width: the most neighbours of one particle (neighbor_capacity) */
    long slot_cap; /* slots of nb_j (and nb_dw, nb_inv_r): sized from the counts (sps__ensure_slots) */
    sps_real *nb_dw, *nb_inv_r; /* frozen geometry per slot: dW/dr and 1/r_0 at the update (0 in padding) */
    /* SPS_ROTATION_PAIR: the accumulated shear force g_ij per slot [N] (0 in padding), and its
       copy kept at the end of each step for the next list rebuild: each particle's pairs
       contiguous, with the id of the neighbour, from kept_first[its id] (kept_count of them;
       ids < kept_ids) */
    sps_real *pair_force, *kept_force;
    int *kept_neighbor_id, *kept_first, *kept_count;
    long pair_force_cap; /* slots of pair_force */
    long kept_pair_cap;  /* pairs kept_force and kept_neighbor_id hold */
    int kept_cap, kept_ids;
    int *cell_of, *cell_start, *perm;
    int cell_cap;
    void* scratch;     /* the sort's permutation buffer: a real per particle (open boundaries: 5, sps__open_boundaries) */
    int scratch_zoned; /* ... allocated for a world with zones */
    sps_real* group_sum; /* per lane group: its sum of Rodrigues matrices (mean rotation, fixed order) */
    sps_real* diag_scratch; /* 28 * cap reals: B, displacement gradient, position divergence,
                               velocity gradient */
    int diag_cap;
    int grid_wrap[3], grid_n[3];
    sps_real grid_lo[3], grid_cell[3]; /* grid_cell: the cell size per axis (the support, or a
                                          periodic axis's period over its cell count) */
    int periodic;                             /* any axis periodic (chapter >>periodic) */
    sps_real period[3], inv_period[3];        /* per axis: L and 1/L, both 0 if not periodic */

    /* contact (chapter >>contact): walls, which bodies touch, contact pairs (CSR, rebuilt at every
       configuration update), contact densities */
    sps__wall* walls;
    int nwalls;
    sps_real wall_sigma[SPS__WALL_TABLE + 1], wall_plane[SPS__WALL_TABLE + 1];
    sps_real rest_wall_sigma, rest_pair_sigma; /* contact densities at rest (contact_rest): a
                                                  wall's at rest_wall_distance, a flush lattice's */
    sps_real rest_wall_distance;
    int *separate, nseparate;   /* body pairs turned off by sps_world_set_contact */
    unsigned char* touch;       /* nbodies x nbodies: 0, or how bodies a and b touch (SPS__TOUCH_*) */
    int touch_n, contact_bodies, contact_dirty;
    int friction;           /* some contact has friction: the contact pass adds it (>>contact) */
    int contact_damped;     /* some body has contact_damping: the contact pass adds the dashpot */
    sps_real* pair_friction; /* nbodies x nbodies: the friction coefficient of two touching bodies
                                (allocated when a body has friction) */
    int *ct_first, *ct_j, *ct_cell, *ct_order, *ct_cell_start, ct_cap;
    int* ct_cell_body; /* per cell of the contact grid: the one body its particles belong to, or -1 */
    long ct_pair_cap;
    sps_real* sigma;
    int sigma_cap;
    sps_real coupling_c0; /* the fluid-structure coupling's signal speed, 0 without it (sps__coupling_speed) */

    /* time */
    sps_real time, dt, c0_max;
    sps_real viscous_speed; /* the largest nu / h of the viscous fluids: the advection step's
                               speed when the flow is slower (sps__step_until) */
    sps_real viscous_dt;    /* the longest acoustic step the Kelvin-Voigt bodies and the viscous
                               fluids allow (INFINITY: none; sps__kelvin_voigt_dt, sps__newton_dt) */
    sps_real vmax;     /* the time-step speed: the largest particle speed in its body's frame, or
                          approach if larger (sps__frame_speeds) */
    int impact_warned; /* sps__warn_impact has spoken */
    sps_real approach; /* the largest relative speed of two bodies that touch, or of a body
                          towards the walls (at rest), at the start of the advection step */
    sps_real thread_max[SPS__MAX_THREADS]; /* per-thread max |v|^2 of the kick */
    long acoustic_steps, advection_steps;
    int allocated_for; /* particles the neighbour storage was sized for (sps__ensure_neighbor_storage) */
    double substep_wall_s; /* wall seconds of one sub-step in the last budgeted frame (>>realtime) */
    sps__advection_step step; /* the advection step under way, which a frame may leave open (>>stepping) */
};

/* A change through the API between two frames (particles added or moved, velocities, walls,
   contact, masses; not forces, accelerations and drags, which the next sub-step's kick reads):
   the next frame starts a fresh advection step, with the configuration update and the time-step
   speed of the changed world, instead of continuing the one the last frame left open. */
static void sps__world_changed(sps_world* w) { w->step.open = 0; }

/* >>fields */

/* The per-particle arrays, one row each: what it is, when it is needed and what housekeeping
   it gets. Allocation, growth, sorting, freeing, the finiteness guard, the last good state,
   sps_world_validate and the access by name are loops over this table, so a new array is one
   new row (and its pointer in sps_world, or in sps__body for an array a body owns). */
typedef enum {
    SPS__NEED_ALWAYS,      /* every particle: grown with the particles (sps__reserve) */
    SPS__NEED_GRADIENT,    /* a body needs the velocity gradient L (model.gradient) */
    SPS__NEED_STRESS,      /* a body integrates the shear stress (model.stress) */
    SPS__NEED_MEAN_TURN,   /* a body turns its increments by the mean rotation */
    SPS__NEED_ARTIFICIAL,  /* a body has Gray's artificial stress (OAS) */
    SPS__NEED_PLASTIC,     /* a body's material is plastic (J2, Drucker-Prager) */
    SPS__NEED_SCALED_PENALTY, /* a plastic body's GNO penalty is scaled by its return factors */
    SPS__NEED_CONSTRAINTS, /* allocated by the first sps_body_constrain_box */
    SPS__NEED_ZONES,       /* allocated by the first sps_body_add_zone (>>open boundaries) */
    SPS__NEED_DRIVEN,      /* a body whose prescribed motion does work (sps__body.driven) */
    SPS__NEED_TRANSPORT,   /* a body with a transport correction (TVF, UTVF) */
    SPS__NEED_DIFFUSION,   /* a Drucker-Prager body with stress diffusion */
    SPS__NEED_GRANULAR,    /* a Drucker-Prager body */
    SPS__NEED_WALL_EQUILIBRIUM, /* a Drucker-Prager body in a world with a no-slip wall */
    SPS__NEED_TOTAL_LAGRANGIAN, /* a total-Lagrangian body */
    SPS__NEED_TOTAL_LAGRANGIAN_PLASTIC, /* a total-Lagrangian J2 body */
    SPS__NEED_DAMAGE,      /* a total-Lagrangian body with damage (material.tl.damage_strain > 0) */
    SPS__NEED_KELVIN_VOIGT /* a solid with material damping (material.viscosity > 0) or contact
                              damping (contact_damping > 0): the dissipated work */
} sps__need;

enum {
    SPS__CARRIED = 1,  /* follows its particle through every sort (others are rebuilt before read) */
    SPS__CHECKED = 4,  /* must be finite at every configuration update (sps__check_finite) */
    SPS__POSITIVE = 8, /* must also be > 0 wherever checked */
    SPS__GOOD = 16,    /* copied into the last good state (keep_last_good_state) */
    SPS__VALIDATED = 32 /* checked by sps_world_validate */
};

#define SPS__EQUILIBRIUM_VALUES 21 /* "wall_equilibrium": 6 x 3 stress derivatives, then rho b */

typedef struct sps__field_info {
    const char* name;  /* for sps_world_field_by_name; per-axis arrays add _x, _y, _z */
    const char* what;  /* in messages */
    int per_body;      /* 0: one array for the world (sps_world); 1: one for each body that needs
                          it (sps__body), so a body pays only for the arrays of its own model */
    size_t offset;     /* of its pointer in sps_world or sps__body (the x axis' for per-axis arrays) */
    int axes;          /* 1: one array per axis (dim of them used); 0: one array */
    int components;    /* values per particle in one array */
    int is_int;        /* int values (else sps_real) */
    sps__need need;
    unsigned care;
} sps__field_info;

#define SPS__OFF(member) offsetof(struct sps_world, member)
#define SPS__BOFF(member) offsetof(sps__body, member)
static const sps__field_info sps__fields[] = {
    {"velocity", "velocity", 0, SPS__OFF(vel), 1, 1, 0, SPS__NEED_ALWAYS, SPS__CARRIED | SPS__CHECKED | SPS__GOOD | SPS__VALIDATED},
    {"position", "position", 0, SPS__OFF(pos), 1, 1, 0, SPS__NEED_ALWAYS, SPS__CARRIED | SPS__CHECKED | SPS__GOOD | SPS__VALIDATED},
    {"reference", "reference position", 0, SPS__OFF(ref), 1, 1, 0, SPS__NEED_ALWAYS, SPS__CARRIED | SPS__VALIDATED},
    {"pressure_acceleration", "pressure acceleration", 0, SPS__OFF(acc_p), 1, 1, 0, SPS__NEED_ALWAYS, 0},
    {"shear_acceleration", "shear acceleration", 0, SPS__OFF(acc_s), 1, 1, 0, SPS__NEED_ALWAYS, SPS__CARRIED | SPS__CHECKED | SPS__VALIDATED},
    {"shear_increment", "shear increment", 1, SPS__BOFF(acc_d), 1, 1, 0, SPS__NEED_MEAN_TURN, 0},
    {"density", "density", 0, SPS__OFF(rho), 0, 1, 0, SPS__NEED_ALWAYS, SPS__CARRIED | SPS__CHECKED | SPS__POSITIVE | SPS__GOOD | SPS__VALIDATED},
    {"density_rate", "density rate", 0, SPS__OFF(drho), 0, 1, 0, SPS__NEED_ALWAYS, SPS__CARRIED},
    {"pressure", "pressure", 0, SPS__OFF(p), 0, 1, 0, SPS__NEED_ALWAYS, SPS__CARRIED | SPS__CHECKED | SPS__GOOD | SPS__VALIDATED},
    {"volume", "volume", 0, SPS__OFF(vol), 0, 1, 0, SPS__NEED_ALWAYS, SPS__CARRIED | SPS__POSITIVE | SPS__VALIDATED},
    {"mass", "mass", 0, SPS__OFF(mass), 0, 1, 0, SPS__NEED_ALWAYS, SPS__CARRIED | SPS__POSITIVE | SPS__VALIDATED},
    {"shear_stress", "shear stress", 1, SPS__BOFF(tau), 0, 6, 0, SPS__NEED_STRESS, SPS__CARRIED | SPS__CHECKED | SPS__GOOD | SPS__VALIDATED},
    {"artificial_stress", "artificial stress", 1, SPS__BOFF(art), 0, 3, 0, SPS__NEED_ARTIFICIAL, 0},
    /* carried: the next kick reads it (the per-particle half-step rotation) */
    {"velocity_gradient", "velocity gradient", 1, SPS__BOFF(grad), 0, 9, 0, SPS__NEED_GRADIENT, SPS__CARRIED},
    {"prescribed_work", "prescribed work", 1, SPS__BOFF(driven_work), 0, 1, 0, SPS__NEED_DRIVEN, SPS__CARRIED},
    /* J2: the equivalent plastic strain alpha; Drucker-Prager: the accumulated deviatoric plastic strain */
    {"plastic_strain", "plastic strain", 1, SPS__BOFF(plastic_strain), 0, 1, 0, SPS__NEED_PLASTIC, SPS__CARRIED | SPS__CHECKED | SPS__GOOD | SPS__VALIDATED},
    {"plastic_work", "plastic work", 1, SPS__BOFF(plastic_work), 0, 1, 0, SPS__NEED_PLASTIC, SPS__CARRIED | SPS__CHECKED | SPS__GOOD},
    /* rebuilt at every sub-step (>>transport) */
    {"transport", "transport correction", 1, SPS__BOFF(transport), 0, SPS__TRANSPORT_VALUES, 0, SPS__NEED_TRANSPORT, 0},
    /* written by the pressure pass, read by the continuity pass of the same sub-step */
    {"stress_diffusion", "stress diffusion", 1, SPS__BOFF(diffusion), 0, 6, 0, SPS__NEED_DIFFUSION, 0},
    /* Drucker-Prager: -tr(sigma)/3 of the stress update, written by the continuity pass (whose
       Riemann term reads the neighbours' p) and moved into p when the sub-step finishes */
    {"next_pressure", "next pressure", 1, SPS__BOFF(next_pressure), 0, 1, 0, SPS__NEED_GRANULAR, 0},
    /* Drucker-Prager at a no-slip wall: d sigma / dx and rho b, written by the contact pass and
       read by the images of the same pass (>>walls for fluids, the granular images' shear) */
    {"wall_equilibrium", "wall equilibrium", 1, SPS__BOFF(wall_equilibrium), 0, SPS__EQUILIBRIUM_VALUES, 0, SPS__NEED_WALL_EQUILIBRIUM, 0},
    /* written by the continuity pass, read by the penalty pass of the same sub-step */
    {"return_factor", "return factor", 1, SPS__BOFF(return_factor), 0, 1, 0, SPS__NEED_SCALED_PENALTY, 0},
    /* total Lagrangian: B_i = -L_i^-1 (TL eq. 15) of the reference configuration, F_i (TL eq. 17)
       and P_i B_i, written by the stress pass and read by the force pass of the same sub-step */
    {"reference_correction", "reference correction", 1, SPS__BOFF(tl_correction), 0, 9, 0, SPS__NEED_TOTAL_LAGRANGIAN, 0},
    {"deformation_gradient", "deformation gradient", 1, SPS__BOFF(tl_deformation), 0, 9, 0, SPS__NEED_TOTAL_LAGRANGIAN, SPS__CARRIED | SPS__CHECKED},
    {"corrected_piola_stress", "corrected Piola stress", 1, SPS__BOFF(tl_stress), 0, 9, 0, SPS__NEED_TOTAL_LAGRANGIAN, 0},
    /* total-Lagrangian J2: the inverse plastic right Cauchy-Green tensor less I (xx xy xz yy yz zz; 0: no plastic flow yet) */
    {"plastic_metric", "plastic metric", 1, SPS__BOFF(tl_plastic), 0, 6, 0, SPS__NEED_TOTAL_LAGRANGIAN_PLASTIC,
     SPS__CARRIED | SPS__CHECKED | SPS__GOOD | SPS__VALIDATED},
    /* total-Lagrangian damage D (TL eqs. 45-46): state, advanced by the stress pass */
    {"damage", "damage", 1, SPS__BOFF(damage), 0, 1, 0, SPS__NEED_DAMAGE, SPS__CARRIED | SPS__CHECKED | SPS__GOOD | SPS__VALIDATED},
    /* Kelvin-Voigt: the dissipated work, summed by the energy account (>>material: Kelvin-Voigt) */
    {"viscous_work", "viscous work", 1, SPS__BOFF(viscous_work), 0, 1, 0, SPS__NEED_KELVIN_VOIGT, SPS__CARRIED | SPS__CHECKED | SPS__GOOD},
    {"id", "id", 0, SPS__OFF(id), 0, 1, 1, SPS__NEED_ALWAYS, SPS__CARRIED},
    {"body", "body", 0, SPS__OFF(body), 0, 1, 1, SPS__NEED_ALWAYS, SPS__CARRIED},
    {"slot_of_id", "slot of id", 0, SPS__OFF(slot_of_id), 0, 1, 1, SPS__NEED_ALWAYS, 0},
    {"constraint", "constraint", 0, SPS__OFF(cons), 0, 1, 1, SPS__NEED_CONSTRAINTS, SPS__CARRIED},
    /* open boundaries: the zone a buffer particle is in (-1: none; a real, so that
       sps_world_field_by_name shows it) and the velocity the kick holds it at */
    {"zone", "zone", 0, SPS__OFF(zone), 0, 1, 0, SPS__NEED_ZONES, SPS__CARRIED | SPS__VALIDATED},
    {"zone_velocity", "zone velocity", 0, SPS__OFF(zone_vel), 1, 1, 0, SPS__NEED_ZONES, SPS__CARRIED | SPS__CHECKED | SPS__VALIDATED},
};
#undef SPS__OFF
#undef SPS__BOFF
#define SPS__NFIELDS ((int)(sizeof sps__fields / sizeof sps__fields[0]))

/* The address of the pointer of field f's array for axis a (a = 0 for one-array fields) in its
   owner: the world w, or the body b for a per-body field. */
/* Whether the world holds world field f's arrays: always, or since the first constraint or zone. */
static int sps__world_field_allocated(const sps_world* w, const sps__field_info* f) {
    return f->need == SPS__NEED_ALWAYS || (f->need == SPS__NEED_CONSTRAINTS && w->cons) || (f->need == SPS__NEED_ZONES && w->zone);
}
static void* sps__field_slot(const sps_world* w, const sps__body* b, const sps__field_info* f, int a) {
    return (f->per_body ? (char*)b : (char*)w) + f->offset + (size_t)a * (f->is_int ? sizeof(int*) : sizeof(sps_real*));
}
static int sps__field_arrays(const sps__field_info* f) { return f->axes ? 3 : 1; }
static size_t sps__field_bytes(const sps__field_info* f) { return (size_t)f->components * (f->is_int ? sizeof(int) : sizeof(sps_real)); }
static sps_real* sps__real_array(const sps_world* w, const sps__body* b, const sps__field_info* f, int a) {
    sps_real* p;
    memcpy(&p, sps__field_slot(w, b, f, a), sizeof p);
    return p;
}
static int* sps__int_array(const sps_world* w, const sps__field_info* f, int a) {
    int* p;
    memcpy(&p, sps__field_slot(w, NULL, f, a), sizeof p);
    return p;
}
/* The values of a real field (axis a) for body b's particles, the first of them at the returned
   pointer (components each): a slice of the world's array, or the body's own; NULL if missing. */
static sps_real* sps__body_values(const sps_world* w, const sps__body* b, const sps__field_info* f, int a) {
    sps_real* x = sps__real_array(w, b, f, a);
    return x && !f->per_body ? x + (size_t)b->begin * (size_t)f->components : x;
}
static const sps__field_info* sps__field_named(const char* name) {
    int k;
    for (k = 0; k < SPS__NFIELDS; ++k)
        if (strcmp(sps__fields[k].name, name) == 0) return &sps__fields[k];
    return NULL;
}

/* >>util */

/* A symmetric 3 x 3 tensor (a stress) stored as its six entries xx xy xz yy yz zz: entry k is
   row sps__sym_row[k], column sps__sym_col[k]; entry 3 a + c of the full matrix is entry
   sps__sym9[3 a + c]. */
enum { SPS__XX, SPS__XY, SPS__XZ, SPS__YY, SPS__YZ, SPS__ZZ };
static const int sps__sym_row[6] = {0, 0, 0, 1, 1, 2}, sps__sym_col[6] = {0, 1, 2, 1, 2, 2};
static const int sps__sym9[9] = {0, 1, 2, 1, 3, 4, 2, 4, 5};
SPS__INLINE int sps__sym_diagonal(int k) { return k == SPS__XX || k == SPS__YY || k == SPS__ZZ; }
/* a : b */
SPS__INLINE sps_real sps__sym_contract(const sps_real a[6], const sps_real b[6]) {
    return a[0] * b[0] + a[3] * b[3] + a[5] * b[5] + 2 * (a[1] * b[1] + a[2] * b[2] + a[4] * b[4]);
}
/* The deviator s = sig - I1/3 I into s; returns I1 = tr(sig). */
SPS__INLINE sps_real sps__sym_deviator(const sps_real sig[6], sps_real s[6]) {
    const sps_real i1 = sig[SPS__XX] + sig[SPS__YY] + sig[SPS__ZZ];
    int k;
    SPS__UNROLL
    for (k = 0; k < 6; ++k) s[k] = sig[k] - (sps__sym_diagonal(k) ? i1 / 3 : 0);
    return i1;
}

static void sps__vset_error(sps_world* w, int level, const char* fmt, va_list ap) {
    vsnprintf(w->error, sizeof w->error, fmt, ap);
    if (w->def.log) w->def.log(level, w->error, w->def.log_user);
}
static void sps__set_error(sps_world* w, int level, const char* fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    sps__vset_error(w, level, fmt, ap);
    va_end(ap);
}
/* Whether a warning with this text was issued before (then counted, not printed again): a cause
   that recurs in a loop, or at every commit of the contacts, speaks once. The table keeps the
   first SPS__WARNED texts; beyond it every warning prints. */
static int sps__warned_before(sps_world* w, const char* msg) {
    uint64_t hash = 1469598103934665603ull; /* FNV-1a */
    const char* c;
    int k;
    for (c = msg; *c; ++c) hash = (hash ^ (unsigned char)*c) * 1099511628211ull;
    ++w->warnings_issued;
    for (k = 0; k < w->nwarned; ++k)
        if (w->warned[k].hash == hash) return ++w->warned[k].count, 1;
    if (w->nwarned == SPS__WARNED) return 0;
    w->warned[w->nwarned].hash = hash;
    w->warned[w->nwarned].count = 1;
    for (k = 0; msg[k] && k + 1 < (int)sizeof w->warned[0].head; ++k) w->warned[w->nwarned].head[k] = msg[k];
    w->warned[w->nwarned].head[k] = 0;
    ++w->nwarned;
    return 0;
}

/* A warning (log level 1): a call that did what it was asked but probably not what was meant.
   It goes to the log only; the world's last error stays as it was. Every world is allocated
   non-const (sps_world_create): the warning table is written through a const world's pointer,
   as the error message is (sps__set_error_const). */
static void sps__warn(const sps_world* w, const char* fmt, ...) {
    char msg[1024];
    va_list ap;
    int repeated;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    SPS__PRAGMA(omp critical(sps__warn_table))
    repeated = sps__warned_before((sps_world*)w, msg);
    if (repeated || !w->def.log) return;
    w->def.log(1, msg, w->def.log_user);
}

/* A Coulomb coefficient above any pair of materials' (rubber on dry concrete is about 1): most
   likely an angle typed in degrees, whose coefficient is tan(angle). `field` names the setting. */
#define SPS__MU_MAX_REAL 2
static void sps__warn_friction(const sps_world* w, const char* field, sps_real mu) {
    if (mu > SPS__MU_MAX_REAL && mu < 90)
        sps__warn(w, "%s = %g: a Coulomb coefficient above %d, more than any pair of materials has (rubber on dry concrete: about 1); "
                  "if %g is a friction angle in degrees, its coefficient is tan(%g deg) = %.3g", field, (double)mu, SPS__MU_MAX_REAL,
                  (double)mu, (double)mu, tan((double)mu * 3.14159265358979323846 / 180));
    else if (mu > SPS__MU_MAX_REAL)
        sps__warn(w, "%s = %g: a Coulomb coefficient above %d, more than any pair of materials has (rubber on dry concrete: about 1); "
                  "for a contact that does not slide use a no-slip wall", field, (double)mu, SPS__MU_MAX_REAL);
}

/* At destroy: how often each warning that recurred was issued. */
static void sps__report_repeated_warnings(const sps_world* w) {
    int k;
    for (k = 0; k < w->nwarned && w->def.log; ++k)
        if (w->warned[k].count > 1) {
            char msg[256];
            snprintf(msg, sizeof msg, "the warning \"%.80s%s\" was issued %d times (printed once)", w->warned[k].head,
                     strlen(w->warned[k].head) > 80 ? "..." : "", w->warned[k].count);
            w->def.log(1, msg, w->def.log_user);
        }
}

/* For the calls that take a const world: the error message is the one thing they write. Every
   world is allocated non-const (sps_world_create), so casting the const away is defined. */
static void sps__set_error_const(const sps_world* w, const char* fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    sps__vset_error((sps_world*)w, 0, fmt, ap);
    va_end(ap);
}
/* The energy watchdog (sps__watch_energy) is on unless energy_growth_limit is INFINITY. */
static int sps__watchdog_on(const sps_world* w) { return w->def.energy_growth_limit < (sps_real)INFINITY; }
/* A call that changes the contacts on purpose (positions, walls, which bodies touch) makes the
   watchdog take a new start at the next step. */
static void sps__rearm_watchdog(sps_world* w) { w->watch.armed = 0; }
/* A call that sets velocities or adds particles moves the watchdog's start by the kinetic and
   gravity energy it gave (a new start would miss the strain energy the bodies hold then, which
   the account leaves out: a bent beam swinging back would read as a gain). Wall bodies are not
   in the account (free rigid bodies are: their particles' energies are the body's, but for the
   cells' own rotational inertia). */
static void sps__watch_adjust(sps_world* w, int body, sps_real kinetic_change, sps_real potential_change) {
    if (!w->watch.armed || (w->bodies[body].model.material->kinematic && !w->bodies[body].model.free_rigid)) return;
    w->watch.start += kinetic_change + potential_change;
    w->bodies[body].energy_start += kinetic_change + potential_change;
}
/* Particle i's kinetic energy 1/2 m |v|^2. */
static sps_real sps__kinetic(const sps_world* w, int i) {
    sps_real v2 = 0;
    int a;
    for (a = 0; a < w->dim; ++a) v2 += w->vel[a][i] * w->vel[a][i];
    return SPS_R(0.5) * w->mass[i] * v2;
}

/* Reports a failed allocation (what: the data it was for); returns SPS_ERR_OUT_OF_MEMORY. */
static sps_result sps__oom(sps_world* w, const char* what) {
    sps__set_error(w, 0, "out of memory: the allocator returned NULL for %s", what);
    return SPS_ERR_OUT_OF_MEMORY;
}

#ifndef SPHSOLID_NO_STDIO
static void sps__stderr_log(int level, const char* message, void* user) {
    (void)user;
    fprintf(stderr, "sphsolid %s: %s\n", level == 0 ? "error" : level == 1 ? "warning" : "info", message);
}
#endif

static void* sps__alloc(const sps_world* w, size_t size) {
    if (size == 0) size = 1;
    return w->def.allocator.alloc(size, w->def.allocator.user);
}
static void sps__free(const sps_world* w, void* p) {
    if (p) w->def.allocator.free(p, w->def.allocator.user);
}
static void* sps__default_alloc(size_t size, void* user) { return SPHSOLID_MALLOC(size, user); }
static void sps__default_free(void* p, void* user) { SPHSOLID_FREE(p, user); }

/* Grows the array whose pointer lives at field (the address of a T*) from old_n to new_n
   elements of size elem, keeping the contents and zeroing the rest. The pointer is read and
   written with memcpy so no T** is accessed through a void** (strict aliasing). Returns 0
   when out of memory. */
static int sps__grow(sps_world* w, void* field, size_t elem, size_t old_n, size_t new_n) {
    void *old, *q = sps__alloc(w, elem * new_n);
    if (!q) return 0;
    memcpy(&old, field, sizeof old);
    if (old && old_n) memcpy(q, old, elem * old_n);
    memset((char*)q + elem * old_n, 0, elem * (new_n - old_n));
    sps__free(w, old);
    memcpy(field, &q, sizeof q);
    return 1;
}

static int sps__finite(sps_real x) { return x == x && x - x == 0; }
/* A point argument: not NULL, and its dim coordinates finite. */
static int sps__finite_point(const sps_world* w, const sps_real* x) {
    int a;
    if (!x) return 0;
    for (a = 0; a < w->dim; ++a)
        if (!sps__finite(x[a])) return 0;
    return 1;
}

SPSDEF const char* sps_version(void) { return SPHSOLID_VERSION_STRING; }
SPSDEF int sps_is_double(void) { return sizeof(sps_real) == sizeof(double); }

SPSDEF const char* sps_result_string(sps_result r) {
    switch (r) {
    case SPS_OK: return "ok";
    case SPS_ERR_INVALID_ARG: return "invalid argument";
    case SPS_ERR_OUT_OF_MEMORY: return "out of memory";
    case SPS_ERR_UNSTABLE: return "simulation unstable";
    case SPS_ERR_IO: return "i/o error";
    case SPS_ERR_STATE: return "invalid state";
    }
    return "unknown result";
}

/* >>defaults */

SPSDEF sps_world_def sps_default_world_def(void) {
    sps_world_def d;
    memset(&d, 0, sizeof d);
    d.dim = 2;
    d.dp = SPS_R(0.01);
    d.h_over_dp = SPS_R(1.3);
    d.kernel = SPS_KERNEL_WENDLAND_C2;
    d.stepping = SPS_STEPPING_DUAL;
    d.cfl_acoustic = SPS_R(0.4);
    d.cfl_advection = SPS_R(0.2);
    d.max_substeps = 100;
    d.frozen_geometry = 0;
    d.neighbor_capacity = SPS_R(2.0);
    d.energy_growth_limit = SPS_R(0.05);
    d.internal_cookie = SPS__COOKIE;
    return d;
}

static void sps__material_defaults(sps_material_def* m); /* >>generic */

SPSDEF sps_material_def sps_default_material_def(void) {
    sps_material_def m;
    memset(&m, 0, sizeof m);
    m.kind = SPS_MATERIAL_ELASTIC;
    m.density = SPS_R(1000.0);
    m.youngs_modulus = SPS_R(1e6);
    m.poisson_ratio = SPS_R(0.3);
    sps__material_defaults(&m);
    return m;
}

SPSDEF sps_real sps_fluid_sound_speed(sps_real gravity, sps_real depth, sps_real flow_speed, sps_real density_error) {
    sps_real fall, speed;
    if (!sps__finite(gravity) || !sps__finite(depth) || !sps__finite(flow_speed) || gravity < 0 || depth < 0 || flow_speed < 0 ||
        !(density_error > 0 && density_error <= SPS_R(0.5)))
        return 0;
    fall = SPS__SQRT(2 * gravity * depth);
    speed = flow_speed > fall ? flow_speed : fall;
    return speed / SPS__SQRT(density_error);
}

SPSDEF sps_body_def sps_default_body_def(void) {
    sps_body_def d;
    memset(&d, 0, sizeof d);
    d.name = "body";
    d.material = sps_default_material_def();
    d.shear = SPS_SHEAR_ENO_A;
    d.rotation = SPS_ROTATION_AUTO; /* the pair rotation survives tumbling and impacts (bench/VALIDATION.md, user scenes) */
    d.oas_epsilon = SPS_R(0.3);
    d.oas_exponent = 4;
    d.contact = 1;
    d.internal_cookie = SPS__COOKIE;
    return d;
}

/* Appends one rule violation to msg. */
static void sps__rule(char* msg, size_t size, int* broken, const char* fmt, ...) {
    size_t len;
    va_list ap;
    ++*broken;
    if (!msg || size == 0) return;
    len = strlen(msg);
    if (len + 2 >= size) return;
    if (len) { msg[len++] = ';'; msg[len++] = ' '; msg[len] = 0; }
    va_start(ap, fmt);
    vsnprintf(msg + len, size - len, fmt, ap);
    va_end(ap);
}

/* A range check "lo < x < hi" (strict) or "lo <= x <= hi" that also rejects NaN. */
static void sps__periodic_check(const sps_world_def* def, char* msg, size_t msg_size, int* broken);
static void sps__periodic_setup(sps_world* w);
static int sps__periodic_allows_body(sps_world* w, const sps_body_def* def);
#define SPS__CHECK(cond, ...) do { if (!(cond)) sps__rule(msg, msg_size, &broken, __VA_ARGS__); } while (0)

SPSDEF sps_result sps_world_def_check(const sps_world_def* def, char* msg, size_t msg_size) {
    int broken = 0;
    if (msg && msg_size) msg[0] = 0;
    if (!def) { sps__rule(msg, msg_size, &broken, "world def is NULL"); return SPS_ERR_INVALID_ARG; }
    SPS__CHECK(def->internal_cookie == SPS__COOKIE, "world def not initialised: start from sps_default_world_def()");
    SPS__CHECK(def->dim == 2 || def->dim == 3, "dim = %d, allowed 2 or 3", def->dim);
    /* 1e-9 .. 1e9 m keeps dp^3, the kernel's 1/h^4 and the masses well inside float's range */
    SPS__CHECK(def->dp >= SPS_R(1e-9) && def->dp <= SPS_R(1e9), "dp = %g, allowed [1e-9, 1e9] m", (double)def->dp);
    /* below 1 the support 2h misses lattice neighbours and B_i turns singular */
    SPS__CHECK(def->h_over_dp >= 1 && def->h_over_dp <= 3, "h_over_dp = %g, allowed [1, 3]", (double)def->h_over_dp);
    SPS__CHECK(def->kernel == SPS_KERNEL_WENDLAND_C2 || def->kernel == SPS_KERNEL_CUBIC_SPLINE, "kernel = %d, allowed 0 (Wendland C2) or 1 (cubic spline)", (int)def->kernel);
    SPS__CHECK(def->stepping == SPS_STEPPING_DUAL || def->stepping == SPS_STEPPING_SINGLE, "stepping = %d, allowed 0 (dual) or 1 (single)", (int)def->stepping);
    SPS__CHECK(def->cfl_acoustic > 0 && def->cfl_acoustic <= 1, "cfl_acoustic = %g, allowed (0, 1]", (double)def->cfl_acoustic);
    SPS__CHECK(def->cfl_advection > 0 && def->cfl_advection <= 1, "cfl_advection = %g, allowed (0, 1]", (double)def->cfl_advection);
    /* a scene at rest has no advection limit: this bound is what ends its advection steps */
    SPS__CHECK(def->max_substeps >= 1 && def->max_substeps <= 10000, "max_substeps = %d, allowed [1, 10000]", def->max_substeps);
    SPS__CHECK(sps__finite(def->gravity[0]) && sps__finite(def->gravity[1]) && sps__finite(def->gravity[2]), "gravity = (%g, %g, %g), allowed finite", (double)def->gravity[0], (double)def->gravity[1], (double)def->gravity[2]);
    SPS__CHECK(def->frozen_geometry == 0 || def->frozen_geometry == 1, "frozen_geometry = %d, allowed 0 or 1", def->frozen_geometry);
    SPS__CHECK(def->neighbor_capacity >= 1 && def->neighbor_capacity <= 64, "neighbor_capacity = %g, allowed [1, 64]", (double)def->neighbor_capacity);
    SPS__CHECK(def->threads >= 0 && def->threads <= SPS__MAX_THREADS, "threads = %d, allowed [0, %d]", def->threads, SPS__MAX_THREADS);
    SPS__CHECK(def->escape_distance >= 0, "escape_distance = %g, allowed 0 (automatic), > 0 or INFINITY", (double)def->escape_distance);
    SPS__CHECK(def->contact_rest == SPS_CONTACT_REST_FLUSH || def->contact_rest == SPS_CONTACT_REST_KERNEL, "contact_rest = %d, allowed 0 (flush) or 1 (kernel)", (int)def->contact_rest);
    SPS__CHECK(def->keep_last_good_state == 0 || def->keep_last_good_state == 1, "keep_last_good_state = %d, allowed 0 or 1", def->keep_last_good_state);
    SPS__CHECK(def->report_fragments == 0 || def->report_fragments == 1, "report_fragments = %d, allowed 0 or 1", def->report_fragments);
    SPS__CHECK(def->energy_growth_limit > 0, "energy_growth_limit = %g, allowed > 0 (INFINITY: off)", (double)def->energy_growth_limit);
    SPS__CHECK(def->energy_growth_stops == 0 || def->energy_growth_stops == 1, "energy_growth_stops = %d, allowed 0 or 1", def->energy_growth_stops);
    SPS__CHECK((def->allocator.alloc == NULL) == (def->allocator.free == NULL), "allocator: set both alloc and free, or neither");
    sps__periodic_check(def, msg, msg_size, &broken);
    return broken ? SPS_ERR_INVALID_ARG : SPS_OK;
}

/* The def fields that change results: every field of sps_world_def and sps_body_def, one row
   each, with which bodies read it. A restart must agree on all of them (chapter >>restart: the
   fingerprint is written, checked and named from these rows, whatever the kind reads, so the
   rule stays one line); a body field set away from its default on a body that does not read
   it gets a warning (sps__warn_unread_fields). Left out, by design: threads (results are bit
   for bit the same at any thread count), report_fragments (a warning only), name, the
   callbacks, allocator, user data and cookies. A new def field that changes results gets a row
   here, and the fingerprint, its check, its message and the warning follow. */
typedef enum sps__def_type { SPS__DEF_INT, SPS__DEF_REAL } sps__def_type;
typedef struct sps__def_item {
    const char* name;   /* the field as the user writes it */
    size_t offset;      /* in the def */
    sps__def_type type; /* SPS__DEF_INT: an int or an enum (the same size, checked below) */
    int (*reads)(const sps_body_def* def); /* body rows: whether such a body reads it (NULL: every body) */
} sps__def_item;
typedef char sps__enums_are_ints[sizeof(sps_kernel_type) == sizeof(int) && sizeof(sps_stepping) == sizeof(int) &&
                                         sizeof(sps_shear) == sizeof(int) && sizeof(sps_rotation) == sizeof(int) &&
                                         sizeof(sps_material_kind) == sizeof(int) && sizeof(sps_solver) == sizeof(int) &&
                                         sizeof(sps_transport) == sizeof(int) && sizeof(sps_hourglass) == sizeof(int) &&
                                         sizeof(sps_fluid_dissipation) == sizeof(int) && sizeof(sps_lattice) == sizeof(int)
                                     ? 1 : -1];
#define SPS__WORLD_ITEM(field, type) {#field, offsetof(sps_world_def, field), type, NULL}
#define SPS__BODY_ITEM(field, type) {#field, offsetof(sps_body_def, field), type, NULL}
#define SPS__BODY_ITEM_READ_BY(field, type, reads) {#field, offsetof(sps_body_def, field), type, reads}

/* Which bodies read a field (the rows below): by the fields their kind's row reads, the solver
   and the shear formulation the model resolves from them (sps__resolve_model). */
static const sps__material_model* sps__material_of(sps_material_kind kind);              /* >>generic */
static const sps__stabilisation* sps__kind_stabilisation(const sps_body_def* def);      /* >>generic */
static const sps__stabilisation* sps__stabilisation_of(sps_shear shear);                /* >>model */
static int sps__reads(const sps_body_def* d, int fields) {
    const sps__material_model* m = sps__material_of(d->material.kind);
    return m && (m->reads & fields);
}
static int sps__updated_solid(const sps_body_def* d) {
    return d->solver == SPS_SOLVER_UPDATED_LAGRANGIAN && sps__reads(d, SPS__READS_STRESS);
}
static int sps__reads_elastic_moduli(const sps_body_def* d) { return sps__reads(d, SPS__READS_MODULI); }
static int sps__reads_total_lagrangian(const sps_body_def* d) { return d->solver == SPS_SOLVER_TOTAL_LAGRANGIAN; }
static int sps__reads_stress(const sps_body_def* d) { return sps__reads(d, SPS__READS_STRESS); }
static int sps__reads_transport_coefficient(const sps_body_def* d) { return d->transport != SPS_TRANSPORT_NONE; }
/* a kind's own stabilisation (a granular body's stress divergence) replaces the shear
   formulation, unless it is that formulation (GNO or GNO-A adding ANG's penalty to a granular body) */
static int sps__reads_shear(const sps_body_def* d) {
    const sps__stabilisation* own = sps__kind_stabilisation(d);
    return sps__updated_solid(d) && (!own || own == sps__stabilisation_of(d->shear));
}
static int sps__reads_rotation(const sps_body_def* d) { return sps__reads_shear(d) && (d->shear == SPS_SHEAR_ENO_A || d->shear == SPS_SHEAR_GNO_A); }
static int sps__reads_zeta(const sps_body_def* d) { return sps__reads_shear(d) && (d->shear == SPS_SHEAR_ENO || d->shear == SPS_SHEAR_ENO_A); }
static int sps__reads_xi(const sps_body_def* d) { return sps__reads_shear(d) && (d->shear == SPS_SHEAR_GNO || d->shear == SPS_SHEAR_GNO_A); }
static int sps__reads_oas(const sps_body_def* d) { return sps__reads_shear(d) && d->shear == SPS_SHEAR_OAS; }
static const sps__def_item sps__world_def_items[] = {
    SPS__WORLD_ITEM(dim, SPS__DEF_INT), SPS__WORLD_ITEM(dp, SPS__DEF_REAL), SPS__WORLD_ITEM(h_over_dp, SPS__DEF_REAL),
    SPS__WORLD_ITEM(kernel, SPS__DEF_INT), SPS__WORLD_ITEM(stepping, SPS__DEF_INT), SPS__WORLD_ITEM(cfl_acoustic, SPS__DEF_REAL),
    SPS__WORLD_ITEM(cfl_advection, SPS__DEF_REAL), SPS__WORLD_ITEM(max_substeps, SPS__DEF_INT),
    SPS__WORLD_ITEM(gravity[0], SPS__DEF_REAL), SPS__WORLD_ITEM(gravity[1], SPS__DEF_REAL), SPS__WORLD_ITEM(gravity[2], SPS__DEF_REAL),
    SPS__WORLD_ITEM(frozen_geometry, SPS__DEF_INT), SPS__WORLD_ITEM(neighbor_capacity, SPS__DEF_REAL),
    SPS__WORLD_ITEM(escape_distance, SPS__DEF_REAL), SPS__WORLD_ITEM(energy_growth_limit, SPS__DEF_REAL),
    SPS__WORLD_ITEM(energy_growth_stops, SPS__DEF_INT), SPS__WORLD_ITEM(keep_last_good_state, SPS__DEF_INT),
    SPS__WORLD_ITEM(contact_rest, SPS__DEF_INT),
    SPS__WORLD_ITEM(periodic[0], SPS__DEF_REAL), SPS__WORLD_ITEM(periodic[1], SPS__DEF_REAL), SPS__WORLD_ITEM(periodic[2], SPS__DEF_REAL),
    SPS__WORLD_ITEM(periodic_origin[0], SPS__DEF_REAL), SPS__WORLD_ITEM(periodic_origin[1], SPS__DEF_REAL),
    SPS__WORLD_ITEM(periodic_origin[2], SPS__DEF_REAL)};
#define SPS__WORLD_DEF_ITEMS ((int)(sizeof sps__world_def_items / sizeof sps__world_def_items[0]))
/* The body rows: sps__body_def_items (chapter >>generic (continued): the body def items), each
   kind's rows from its chapter; the total-Lagrangian solver's (material.tl) here. */
#define SPS__TL_DEF_ITEMS                                                                                   \
    SPS__BODY_ITEM_READ_BY(material.tl.hourglass_alpha, SPS__DEF_REAL, sps__reads_total_lagrangian),      \
    SPS__BODY_ITEM_READ_BY(material.tl.hourglass, SPS__DEF_INT, sps__reads_total_lagrangian),             \
    SPS__BODY_ITEM(material.tl.artificial_viscosity, SPS__DEF_REAL), /* refused on updated-Lagrangian bodies */ \
    SPS__BODY_ITEM(material.tl.damage_strain, SPS__DEF_REAL),        /* refused on updated-Lagrangian bodies */
/* The value of a def item, as a double (exact for ints and sps_real). */
static double sps__def_value(const void* def, const sps__def_item* item) {
    const char* at = (const char*)def + item->offset;
    if (item->type == SPS__DEF_INT) {
        int v;
        memcpy(&v, at, sizeof v);
        return v;
    } else {
        sps_real v;
        memcpy(&v, at, sizeof v);
        return (double)v;
    }
}

/* >>model */

/* A body's model is data: a material row (in the material's chapter, found by sps__material_of),
   a stabilisation row (sps__stabilisations) and the def's rotation, resolved once by
   sps__resolve_model when the body is added into what the step runs (sps__model) and which pass
   kernels it calls (sps__passes, chosen by sps__choose_passes in the solver chapter). Adding a
   material means adding its chapter and its cases in the switches of chapter >>generic (which
   lists the places); the step is not edited. */

/* >>material: linear elastic */

/* Linear elastic: K = E/(3(1-2nu)), c0 = sqrt(K/rho0) (ENO eq. 5), G = E/(2(1+nu)). */
static sps__material_constants sps__elastic_constants(const sps_material_def* m) {
    sps__material_constants c;
    c.K = m->youngs_modulus / (3 * (1 - 2 * m->poisson_ratio));
    c.c0 = SPS__SQRT(c.K / m->density);
    c.G = m->youngs_modulus / (2 * (1 + m->poisson_ratio));
    return c;
}
static void sps__elastic_check(const sps_material_def* m, char* msg, size_t msg_size, int* broken_out) {
    int broken = 0;
    SPS__CHECK(m->density > 0 && sps__finite(m->density), "material.density = %g, allowed finite > 0", (double)m->density);
    SPS__CHECK(m->youngs_modulus > 0 && sps__finite(m->youngs_modulus), "material.youngs_modulus = %g, allowed finite > 0", (double)m->youngs_modulus);
    SPS__CHECK(m->poisson_ratio > -1 && m->poisson_ratio < SPS_R(0.5), "material.poisson_ratio = %g, allowed (-1, 0.5)", (double)m->poisson_ratio);
    if (!broken) { /* each field in range, yet the derived constants may over- or underflow */
        const sps__material_constants c = sps__elastic_constants(m);
        SPS__CHECK(c.c0 > 0 && sps__finite(c.c0) && sps__finite(c.G),
                   "material: sound speed c0 = %g m/s and shear modulus G = %g Pa from density = %g, youngs_modulus = %g, "
                   "poisson_ratio = %g, allowed finite > 0", (double)c.c0, (double)c.G, (double)m->density, (double)m->youngs_modulus,
                   (double)m->poisson_ratio);
    }
    *broken_out += broken;
}
/* tau:tau/(4G) + p^2/(2K): the shear and volumetric parts of the linear elastic energy */
static sps_real sps__elastic_energy_density(const sps__material_constants* c, sps_real tau_tau, sps_real p) {
    return tau_tau / (4 * c->G) + p * p / (2 * c->K);
}
/* Its row (sps__material_model): kind, name, kinematic, plastic, shear, limiter eta + per dim,
   Riemann density, mirrored walls, pressure of density, viscous force, fields read. */
static const sps__material_model sps__elastic_material = {SPS_MATERIAL_ELASTIC, "elastic", 0, SPS__YIELD_NONE, 1, 0, 0, 0, SPS__MIRROR_NONE, 1,
                                                          SPS__VISCOUS_KELVIN_VOIGT, SPS__READS_MODULI | SPS__READS_STRESS};

/* >>material: rigid (wall bodies) */

/* A rigid body's particles move as prescribed: it stores no energy. Its elastic constants give
   the stiffness of its contacts (sps__contact_stiffness). */
static sps_real sps__rigid_energy_density(const sps__material_constants* c, sps_real tau_tau, sps_real p) {
    (void)c; (void)tau_tau; (void)p;
    return 0;
}
/* Its model (sps__kind_model): a wall body runs no pass and needs no field of its own. */
static void sps__rigid_model(sps__model* m) {
    m->paired = m->stress = m->gradient = m->artificial_stress = 0;
    m->turn = SPS__TURN_NONE;
}
/* Its combination rules (sps__combination_rules): nothing moves its particles but the user. */
static int sps__rigid_kind(const sps_body_def* def) {
    const sps__material_model* material = sps__material_of(def->material.kind);
    return material && material->kinematic;
}
static int sps__damped_wall(int dim, const sps_body_def* def) { (void)dim; return def->damping > 0 && def->material.kind == SPS_MATERIAL_RIGID; }
static int sps__moving_wall_particles(int dim, const sps_body_def* def) {
    (void)dim;
    return def->transport != SPS_TRANSPORT_NONE && sps__rigid_kind(def);
}
/* Its row (sps__material_model; the columns: >>material: linear elastic). */
static const sps__material_model sps__rigid_material = {SPS_MATERIAL_RIGID, "rigid", 1, SPS__YIELD_NONE, 1, 0, 0, 0, SPS__MIRROR_NONE, 1,
                                                        SPS__VISCOUS_NONE, SPS__READS_MODULI};

/* >>material: free rigid bodies (Box2D's dynamic bodies; FREE RIGID BODIES in the manual)

   A free rigid body is a wall body whose motion the step integrates: its row is kinematic (no
   pass of its own, no neighbour lists, no stress, no waves: the time step sees its contact
   stiffness c0 = sqrt(K / rho0) and its speed), and the kick sums the forces its particles
   received into a force and a torque on one body (chapter >>material: free rigid bodies
   (continued): motion). Its rules, energy and model are the wall body's (their composition:
   chapter >>generic), and its model adds: */
static void sps__free_rigid_model(sps__model* m) { m->free_rigid = 1; }
/* Not in a periodic world (sps__kind_not_periodic): its pose is the centre of mass of its
   particles, which a body across the boundary does not have. */
static const char* const sps__free_rigid_not_periodic = "a free rigid body (its pose has no periodic image)";
/* Its row (sps__material_model; the columns: >>material: linear elastic). */
static const sps__material_model sps__free_rigid_material = {SPS_MATERIAL_RIGID_DYNAMIC, "free rigid", 1, SPS__YIELD_NONE, 1, 0, 0,
                                                             0, SPS__MIRROR_NONE, 1, SPS__VISCOUS_NONE, SPS__READS_MODULI};

/* >>material: J2 plasticity (von Mises, linear isotropic hardening; ANG section 2.2) */

/* The elastic constants and checks (chapter >>generic composes them with its own), and the yield
   stress and hardening modulus. The return map: sps__j2_stress_lanes (chapter >>material: J2
   plasticity (continued)) and in the total-Lagrangian frame sps__j2_tl_law. */
static void sps__j2_check(const sps_material_def* m, char* msg, size_t msg_size, int* broken_out) {
    int broken = 0;
    SPS__CHECK(m->j2.yield_stress > 0 && sps__finite(m->j2.yield_stress), "material.j2.yield_stress = %g, allowed finite > 0 Pa for J2",
               (double)m->j2.yield_stress);
    SPS__CHECK(m->j2.hardening_modulus >= 0 && sps__finite(m->j2.hardening_modulus),
               "material.j2.hardening_modulus = %g, allowed finite >= 0 Pa for J2 (0: perfect plasticity)", (double)m->j2.hardening_modulus);
    *broken_out += broken;
}
/* Its rows of the def items (sps__body_def_items: restart fingerprint, unread-field warnings):
   material.j2, read by J2 bodies alone. */
static int sps__reads_j2(const sps_body_def* d) { return d->material.kind == SPS_MATERIAL_J2; }
#define SPS__J2_DEF_ITEMS                                                               \
    SPS__BODY_ITEM_READ_BY(material.j2.yield_stress, SPS__DEF_REAL, sps__reads_j2),      \
    SPS__BODY_ITEM_READ_BY(material.j2.hardening_modulus, SPS__DEF_REAL, sps__reads_j2),
/* Its combination rule (sps__combination_rules): the return map needs the stress force. */
static int sps__plastic_without_stress_force(int dim, const sps_body_def* def) {
    (void)dim;
    return def->material.kind == SPS_MATERIAL_J2 && def->solver == SPS_SOLVER_UPDATED_LAGRANGIAN &&
           (def->shear == SPS_SHEAR_ENO || def->shear == SPS_SHEAR_ENO_A);
}
/* Its row (sps__material_model; the columns: >>material: linear elastic). The stored energy of a
   J2 body is its elastic part; the return map's share is plastic work. */
static const sps__material_model sps__j2_material = {SPS_MATERIAL_J2, "J2", 0, SPS__YIELD_VON_MISES, 1, 0, 0, 0, SPS__MIRROR_NONE, 1,
                                                     SPS__VISCOUS_KELVIN_VOIGT, SPS__READS_MODULI | SPS__READS_STRESS};

/* >>material: Kelvin-Voigt (material damping of solids; DAMPING in the manual)

   A solid with material.viscosity = eta > 0 carries, besides its elastic (or elastic-plastic)
   stress, the viscous stress of a Kelvin-Voigt material, sigma_v = 2 eta D + eta tr(D) I (D the
   rate of deformation: Lame viscosities lambda_v = mu_v = eta). It enters as the central pair
   force of the ENO Laplacian (ENO eq. 24, without the time integration),
       a_v,i = (2 (d + 2) eta / rho_i) sum_j (v_ij . e_ij) dW_ij / r_ij V_j e_ij,
   whose continuum limit is (eta / rho)(lap v + 2 grad div v) = div(sigma_v) / rho: the second
   moment of the kernel gives sum_j (v_ij . e_ij) e_ij dW_ij / r_ij V_j -> (lap v + 2 grad div
   v) / (2 (d + 2)) (isotropic fourth moment; int r W' dV = -d). Why this form for every shear
   formulation and not 2 eta dev(D) added to the stress of the OG family: a central pair force
   vanishes exactly for any rigid motion (v_ij . e_ij = 0 for a translation and a rotation), so a
   falling or spinning body is not braked; it conserves linear and angular momentum exactly;
   it needs no velocity gradient (ENO-A with pair rotation has none) and costs one multiply-add
   per pair in the pressure pass, which already forms v_ij . e_ij for the Riemann dissipation.
   The price: a central pair force has its bulk viscosity tied to its shear viscosity (the
   Cauchy relation of pair potentials), eta (d + 2) / d, so the volumetric part is there and not
   set apart; the beam-mode damping ratio follows from both (bench/VALIDATION.md, KV).
   The dissipated work, -m_i a_v,i . v_i dt per sub-step (v_i at the force's evaluation), is
   summed per particle (field "viscous_work") and counted in the energy account
   (sps_diagnostics.viscous_work), together with that of the Riemann solver's dissipation
   Z (v_ij . e_ij) dW V_j of the same body (the same kind of central viscous pair force; without
   it the account of a bouncing ball misses the ~10 % per bounce that it takes). Total-Lagrangian bodies take the same pair force over their
   reference neighbours with the reference dW/dR and the current direction (sps__tl_force's hook
   sps__tl_kelvin_voigt). The time step: an explicit viscous term is stable when the largest
   rate it damps, 4 (d + 2) nu S / d (nu = eta / rho0, S = sum_j |dW_ij| / r_ij V_j, the
   continuum integral of |W'| / r), times dt stays below 1 (the kick's bound is 2):
   sps__kelvin_voigt_dt, a cap on the acoustic step. */

/* The coefficient 2 (d + 2) eta of the viscous pair force of body b. */
static sps_real sps__kelvin_voigt_coefficient(int dim, const sps__body* b) { return 2 * (dim + 2) * b->def.material.viscosity; }

/* S, the continuum value of sum_j |dW_ij| / r_ij V_j: 2 pi W(0) in 2D, 4 pi int_0^2h W dr in 3D
   (by parts). The longest acoustic step body b's Kelvin-Voigt viscosity allows: dt = d / (4
   (d + 2) nu S). */
static sps_real sps__viscous_rate_sum(const sps_world* w) {
    sps_real S = 0;
    int k;
    if (w->dim == 2) S = 2 * SPS__PI * sps_world_kernel(w, 0);
    else
        for (k = 0; k < 256; ++k) S += 4 * SPS__PI * sps_world_kernel(w, (k + SPS_R(0.5)) * w->support / 256) * w->support / 256;
    return S;
}
static sps_real sps__kelvin_voigt_dt(const sps_world* w, const sps__body* b) {
    const sps_real nu = b->def.material.viscosity / b->rho0;
    return w->dim / (4 * (w->dim + 2) * nu * sps__viscous_rate_sum(w));
}
/* >>material: weakly compressible fluid (UTVF sections 2.1, 3.1.1) */

static sps_real sps__lattice_gradient_moment(const sps_world* w, int hexagonal); /* >>kernel */

/* The longest acoustic step a viscous fluid body b allows: the Newtonian force (2 mu / rho_i)
   sum_j v_ij dW / r_ij V_j (Morris et al. 1997) damps a zigzag (v_ij = 2 v_i) at the rate
   4 nu S, kept below 1 / dt as the Kelvin-Voigt one: dt = 1 / (4 nu S) = h^2 / (14 nu) in 2D
   (Wendland C2), inside Morris et al.'s bound 0.125 h^2 / nu. Without it a channel at h^2 / nu
   below 5 advection steps (0.2 h^2 / nu each) blew up. */
static sps_real sps__newton_dt(const sps_world* w, const sps__body* b) {
    return 1 / (4 * b->def.material.viscosity / b->rho0 * sps__viscous_rate_sum(w));
}

/* Its combination rule (sps__combination_rules): a fluid without the Riemann solver's momentum
   dissipation needs the viscosity, the only damping left of its particles' noise (an inviscid
   fluid without it has nothing to stop a zigzag mode). */
static int sps__inviscid_undissipated(int dim, const sps_body_def* def) {
    (void)dim;
    return def->material.kind == SPS_MATERIAL_FLUID && def->material.fluid.dissipation != SPS_FLUID_DISSIPATION_RIEMANN &&
           !(def->material.viscosity > 0);
}

/* c0 is given (material.fluid.sound_speed), K = rho0 c0^2 and no shear modulus: a fluid's pressure is its only
   stress, besides the viscous force when viscosity > 0 (sps__pressure). */
static sps__material_constants sps__fluid_constants(const sps_material_def* m) {
    sps__material_constants c;
    c.c0 = m->fluid.sound_speed;
    c.K = m->density * m->fluid.sound_speed * m->fluid.sound_speed;
    c.G = 0;
    return c;
}
static void sps__fluid_check(const sps_material_def* m, char* msg, size_t msg_size, int* broken_out) {
    int broken = 0;
    SPS__CHECK(m->density > 0 && sps__finite(m->density), "material.density = %g, allowed finite > 0", (double)m->density);
    SPS__CHECK(m->fluid.sound_speed > 0 && sps__finite(m->fluid.sound_speed),
               "material.fluid.sound_speed = %g, allowed finite > 0 m/s for a fluid (about 10 times the largest flow speed)", (double)m->fluid.sound_speed);
    SPS__CHECK(m->viscosity >= 0 && sps__finite(m->viscosity), "material.viscosity = %g, allowed finite >= 0 Pa s (0: inviscid)",
               (double)m->viscosity);
    SPS__CHECK(m->fluid.dissipation == SPS_FLUID_DISSIPATION_RIEMANN || m->fluid.dissipation == SPS_FLUID_DISSIPATION_DENSITY ||
                   m->fluid.dissipation == SPS_FLUID_DISSIPATION_NONE,
               "material.fluid.dissipation = %d, allowed 0 (the Riemann solver's), 1 (density diffusion only) or 2 (none) for a fluid",
               (int)m->fluid.dissipation);
    if (!broken) {
        const sps__material_constants c = sps__fluid_constants(m);
        SPS__CHECK(sps__finite(c.K) && c.K > 0, "material: bulk modulus rho0 c0^2 = %g Pa from density = %g and fluid.sound_speed = %g, allowed finite > 0",
                   (double)c.K, (double)m->density, (double)m->fluid.sound_speed);
    }
    *broken_out += broken;
}
/* Its rows of the def items (sps__body_def_items: restart fingerprint, unread-field warnings):
   material.fluid, read by fluids alone. */
static int sps__reads_fluid(const sps_body_def* d) { return d->material.kind == SPS_MATERIAL_FLUID; }
#define SPS__FLUID_DEF_ITEMS                                                                \
    SPS__BODY_ITEM_READ_BY(material.fluid.sound_speed, SPS__DEF_REAL, sps__reads_fluid),    \
    SPS__BODY_ITEM_READ_BY(material.fluid.dissipation, SPS__DEF_INT, sps__reads_fluid),
/* p^2/(2K): a fluid stores energy in its compression only */
static sps_real sps__fluid_energy_density(const sps__material_constants* c, sps_real tau_tau, sps_real p) {
    (void)tau_tau;
    return p * p / (2 * c->K);
}
/* The stabilisation of a body without shear stress (a fluid): no shear term at all. Stable CFL
   measured in 2D (elliptical drop, dam break): 0.6 runs, 0.8 trips the energy watchdog, 1.0
   blows up; 3D is taken the same, unmeasured. */
static const sps__stabilisation sps__no_shear = {(sps_shear)-1, "no shear (fluid)", 0, 0, 0, 0, 0, 0, {0.6, 0.6}};
/* Its row (sps__material_model; the columns: >>material: linear elastic): eta = 3 for fluids
   (UTVF section 3.1.1, after Zhang et al. 2017). */
static const sps__material_model sps__fluid_material = {SPS_MATERIAL_FLUID, "fluid", 0, SPS__YIELD_NONE, 0, 3, 0, 1, SPS__MIRROR_PRESSURE, 1,
                                                        SPS__VISCOUS_NEWTON, 0};
/* Whether the world has gravity (a fluid then has a hydrostatic state to hold). */
static int sps__has_gravity(const sps_world* w) {
    const sps_real* g = w->def.gravity;
    return g[0] * g[0] + g[1] * g[1] + g[2] * g[2] > 0;
}
/* Its model (sps__kind_model): no shear stress to track (track_stress is moot). Under gravity no
   velocity gradient either: the density rate is the pair sum of the continuity pass, the adjoint
   of the pressure force (sps__continuity_pairs), so that water at rest keeps its energy; without
   gravity the divergence is tr L of the corrected gradient, exact for a linear flow where a free
   surface cuts the kernel (FLUIDS; bench/VALIDATION.md, "Still water": the elliptical drop's
   semi-axis converges with tr L, +0.39 % at dp 0.02 and +0.27 % at 0.01, but not with the pair
   sum, +0.25 / +0.41 / +0.65 % at dp 0.1 / 0.05 / 0.02). */
static void sps__fluid_model(const sps_world* w, sps__model* m) {
    m->stress = 0;
    m->gradient = !sps__has_gravity(w);
}
/* A fluid's constants: the divergence's scale (sps__lattice_gradient_moment: the pressure
   force reads the hydrostatic gradient at its lattice value) and the rest pressure gradient.
   The density diffusion of the Riemann solver, drho_i += rho_i sum_j (p_i - p_j) / (rho0 c0)
   dW_ij V_j (sps__continuity_pairs), acts on the pressure difference of a pair less its
   hydrostatic part rho0 g . x_ij: in water at rest p_i - p_j is that part, and where the
   kernel is cut by the free surface its sum is not zero (below a surface particle, no
   neighbour above), so the surface's density would grow for as long as the water rests (by
   about g / c0 a second: the level and the pressure creep up, bench/VALIDATION.md "Fluid at
   rest over long times"). Without gravity the term is that of UTVF eq. 18 unchanged (the
   granular stress diffusion leaves its geostatic part alone the same way). */
static void sps__fluid_rest_gradient(const sps_world* w, sps__body* b) {
    int a;
    for (a = 0; a < 3; ++a) b->rest_pressure_gradient[a] = a < w->dim ? b->rho0 * w->def.gravity[a] : 0;
    b->divergence_scale = b->model.gradient ? 1 : 1 / sps__lattice_gradient_moment(w, b->hexagonal); /* tr L: no scale */
    /* Morris et al.'s Laplacian sum_j 2 v_ij dW/r V_j gives a quadratic flow's Laplacian times the
       same moment -sum_j x_ij,x^2 dW/r V_j (0.974 at h = 1.3 dp in 2D): Poiseuille flow ran 2.7 %
       fast at every resolution until it was divided out */
    b->viscous_coefficient = 2 * b->def.material.viscosity / sps__lattice_gradient_moment(w, b->hexagonal);
    /* material.fluid.dissipation: the limiter at 0 makes beta = 0 in every pair (no momentum term), the
       density term's factor 0 leaves its sum out; the default keeps both bit for bit */
    if (b->def.material.fluid.dissipation != SPS_FLUID_DISSIPATION_RIEMANN) b->limiter_eta_c0 = 0;
    if (b->def.material.fluid.dissipation == SPS_FLUID_DISSIPATION_NONE) b->density_diffusion = 0;
}
/* Whether the world gives a fluid a hydrostatic column: gravity along an axis that is not
   periodic. */
static int sps__hydrostatic_column(const sps_world* w) {
    int a, column = 0;
    for (a = 0; a < w->dim; ++a) column |= w->def.gravity[a] != 0 && !(w->period[a] > 0);
    return column;
}

/* Water at rest under gravity on the square lattice does not stay at rest: the lattice is a
   saddle of the pressure forces, and its rows slide in alternate directions (towards the
   hexagonal packing) from round-off, at a rate that grows as sqrt(p) / dp, fastest over the
   floor (24/s at the floor of 0.5 m of water at dp 0.02, h = 1.3 dp: churning within 1.5 s; at
   h = 2 dp the burst comes after 8-14 s). On the hexagonal lattice at h = 1.3 dp the same tank
   stays at rest (largest speed 1.3e-3 m/s at 20 s, decaying), and its free surface's pressure is rho0 g
   dp/2 (on the churned square lattice 0.1-0.2 dp of head higher, which floats a body that much
   too high); at h = 1.5-2 dp the hexagonal lattice churns after 4-14 s (bench/VALIDATION.md,
   "Water left running"). So a fluid with a hydrostatic column in 2D at h_over_dp < 1.4 fills on
   the hexagonal lattice (lattice = SPS_LATTICE_AUTO); 3D has no close-packed fill. */
#define SPS__HEXAGONAL_H_OVER_DP_MAX SPS_R(1.4)
static int sps__fluid_fills_hexagonal(const sps_world* w) {
    return w->dim == 2 && sps__hydrostatic_column(w) && w->def.h_over_dp < SPS__HEXAGONAL_H_OVER_DP_MAX;
}

/* Its warnings (sps__material_warnings): water under gravity on a lattice and at a smoothing
   length at which water at rest does not stay at rest (sps__fluid_fills_hexagonal). */
#define SPS__FLUID_STILL_H_OVER_DP SPS_R(2)
static void sps__fluid_warnings(const sps_world* w, const sps__body* b) {
    const sps_real h_over_dp = w->def.h_over_dp;
    if (!sps__hydrostatic_column(w)) return;
    if (!b->hexagonal && h_over_dp < SPS__FLUID_STILL_H_OVER_DP - SPS_R(1e-6))
        sps__warn(w, "body '%s': a fluid under gravity on the square lattice at h_over_dp = %g: water at rest does not stay at rest (its "
                  "rows slide within seconds); in 2D fill it on the hexagonal lattice at h_over_dp = 1.3 (lattice = "
                  "SPS_LATTICE_AUTO or SPS_LATTICE_HEXAGONAL), or set the world's h_over_dp = %g, where it holds for 8-14 s "
                  "(bench/VALIDATION.md, \"Water left running\")", b->name, (double)h_over_dp, (double)SPS__FLUID_STILL_H_OVER_DP);
    if (b->hexagonal && !(h_over_dp < SPS__HEXAGONAL_H_OVER_DP_MAX))
        sps__warn(w, "body '%s': a fluid under gravity on the hexagonal lattice at h_over_dp = %g: water at rest on it churns after 4-14 "
                  "s at h_over_dp 1.5-2 (it holds at 1.3: bench/VALIDATION.md, \"Water left running\")", b->name, (double)h_over_dp);
}
/* >>material: Drucker-Prager (granular media; UTVF sections 2.3, 3.1.3)

   Elastic-perfectly plastic: the linear elastic law (c0 = sqrt(K/rho0), as the reference code),
   the yield cone f = alpha_phi I1 + sqrt(J2) - k_c (UTVF eq. 11) and the plastic potential
   g = alpha_psi I1 + sqrt(J2) (eq. 12), with I1 = tr(sigma) and J2 = s:s/2 of the deviator
   s (eq. 14 gives the constants). The whole stress sigma = tau - p I is integrated (tau the
   deviator, 3 x 3 also in 2D: plane strain has sigma_zz), so the pressure is -I1/3 of the
   stress, not the equation of state. One particle's update is sps__drucker_prager_update; the
   lane loop that calls it is sps__granular_stress_lanes (chapter >>material: Drucker-Prager
   (continued)), and the stress diffusion's pair sums and their store are below, which the
   pressure pass reaches through sps__kind_pressure_pair and sps__kind_pressure_store (chapter
   >>generic (continued): the updated-Lagrangian passes' hooks). */

/* The cones through Mohr-Coulomb's compression (sign -1) and extension (+1) meridians, for the
   angle theta (phi or psi): alpha = 2 sin / (sqrt3 (3 -+ sin)), k_c = 6 c cos / (sqrt3 (3 -+ sin)). */
static sps_real sps__meridian_alpha(sps_real theta, sps_real meridian) {
    return 2 * SPS__SIN(theta) / (SPS__SQRT(SPS_R(3.0)) * (3 + meridian * SPS__SIN(theta)));
}
static sps_real sps__meridian_k(sps_real phi, sps_real cohesion, sps_real meridian) {
    return 6 * cohesion * SPS__COS(phi) / (SPS__SQRT(SPS_R(3.0)) * (3 + meridian * SPS__SIN(phi)));
}
/* UTVF eq. 14's alpha for the angle theta: tan / sqrt(9 + 12 tan^2), the inscribed cone. */
static sps_real sps__inscribed_alpha(sps_real theta) {
    const sps_real tan_theta = SPS__SIN(theta) / SPS__COS(theta);
    return tan_theta / SPS__SQRT(9 + 12 * tan_theta * tan_theta);
}
/* The cone of a def (its granular.yield_cone): alpha_phi, k_c, alpha_psi and K0 = 1 - sin(phi), the
   at-rest ratio of horizontal to vertical stress (Jaky) of the geostatic stress.
   Plane strain: with the potential's alpha_psi = a (the inscribed form, which gives the plane-
   strain dilatancy sin psi), zero plastic strain out of the plane sets s_zz = -2 a sqrt(J2), so
   sqrt(J2) = t / sqrt(1 - 3a^2) and I1 = 3 p_m - 3 a t / sqrt(1 - 3a^2) for the in-plane mean p_m
   and radius t of Mohr's circle; the cone is then Mohr-Coulomb's t = c cos phi - p_m sin phi when
   alpha_phi = sin phi / (3 (sqrt(1 - 3a^2) + a sin phi)) and k_c = c cos phi (1 - 3 alpha_phi a) /
   sqrt(1 - 3a^2) (for a = alpha_phi: UTVF eq. 14; for psi = 0: sin phi / 3 and c cos phi). */
static sps__yield_cone sps__yield_cone_of(const sps_material_def* m) {
    const sps_real deg = SPS_R(3.14159265358979323846) / 180, phi = m->granular.friction_angle * deg, psi = m->granular.dilatancy_angle * deg;
    sps__yield_cone c;
    switch (m->granular.yield_cone) {
    case SPS_CONE_PLANE_STRAIN: {
        const sps_real a = sps__inscribed_alpha(psi), root = SPS__SQRT(1 - 3 * a * a);
        c.alpha_phi = SPS__SIN(phi) / (3 * (root + a * SPS__SIN(phi)));
        c.k_c = m->granular.cohesion * SPS__COS(phi) * (1 - 3 * c.alpha_phi * a) / root;
        c.alpha_psi = a;
        break;
    }
    case SPS_CONE_PAPERS: {
        const sps_real tan_phi = SPS__SIN(phi) / SPS__COS(phi), root_phi = SPS__SQRT(9 + 12 * tan_phi * tan_phi);
        c.alpha_phi = tan_phi / root_phi;
        c.k_c = 3 * m->granular.cohesion / root_phi;
        c.alpha_psi = sps__inscribed_alpha(psi);
        break;
    }
    case SPS_CONE_COMPRESSION:
    case SPS_CONE_EXTENSION: {
        const sps_real meridian = m->granular.yield_cone == SPS_CONE_COMPRESSION ? -1 : 1;
        c.alpha_phi = sps__meridian_alpha(phi, meridian);
        c.k_c = sps__meridian_k(phi, m->granular.cohesion, meridian);
        c.alpha_psi = sps__meridian_alpha(psi, meridian);
        break;
    }
    case SPS_CONE_COMPROMISE:
        c.alpha_phi = (sps__meridian_alpha(phi, -1) + sps__meridian_alpha(phi, 1)) / 2;
        c.k_c = (sps__meridian_k(phi, m->granular.cohesion, -1) + sps__meridian_k(phi, m->granular.cohesion, 1)) / 2;
        c.alpha_psi = (sps__meridian_alpha(psi, -1) + sps__meridian_alpha(psi, 1)) / 2;
        break;
    }
    c.k0 = 1 - SPS__SIN(phi);
    return c;
}
static void sps__drucker_prager_check(const sps_material_def* m, char* msg, size_t msg_size, int* broken_out) {
    int broken = 0;
    SPS__CHECK(m->granular.cohesion >= 0 && sps__finite(m->granular.cohesion), "material.granular.cohesion = %g, allowed finite >= 0 Pa for Drucker-Prager",
               (double)m->granular.cohesion);
    SPS__CHECK(m->granular.friction_angle >= 0 && m->granular.friction_angle < 90, "material.granular.friction_angle = %g, allowed [0, 90) degrees for Drucker-Prager",
               (double)m->granular.friction_angle);
    SPS__CHECK(m->granular.dilatancy_angle >= 0 && m->granular.dilatancy_angle <= m->granular.friction_angle,
               "material.granular.dilatancy_angle = %g, allowed [0, material.granular.friction_angle = %g] degrees for Drucker-Prager", (double)m->granular.dilatancy_angle,
               (double)m->granular.friction_angle);
    SPS__CHECK(m->granular.yield_cone >= SPS_CONE_PLANE_STRAIN && m->granular.yield_cone <= SPS_CONE_COMPROMISE,
               "material.granular.yield_cone = %d, allowed %d (SPS_CONE_PLANE_STRAIN) to %d (SPS_CONE_COMPROMISE) for Drucker-Prager",
               (int)m->granular.yield_cone, (int)SPS_CONE_PLANE_STRAIN, (int)SPS_CONE_COMPROMISE);
    SPS__CHECK(m->granular.stress_diffusion >= 0 && m->granular.stress_diffusion <= 1,
               "material.granular.stress_diffusion = %g, allowed [0, 1] (0: off) for Drucker-Prager", (double)m->granular.stress_diffusion);
    *broken_out += broken;
}
/* Its parameters' defaults (sps__material_defaults) other than zero: the stress diffusion's
   zeta = 0.1 (Feng et al. 2021, as UTVF section 3.1.3). */
static void sps__granular_defaults(sps_granular_def* granular) { granular->stress_diffusion = SPS_R(0.1); }
/* Its rows of the def items (sps__body_def_items: restart fingerprint, unread-field warnings):
   material.granular, read by Drucker-Prager bodies alone. */
static int sps__reads_drucker_prager(const sps_body_def* d) { return d->material.kind == SPS_MATERIAL_DRUCKER_PRAGER; }
#define SPS__GRANULAR_DEF_ITEMS                                                                           \
    SPS__BODY_ITEM_READ_BY(material.granular.cohesion, SPS__DEF_REAL, sps__reads_drucker_prager),          \
    SPS__BODY_ITEM_READ_BY(material.granular.friction_angle, SPS__DEF_REAL, sps__reads_drucker_prager),    \
    SPS__BODY_ITEM_READ_BY(material.granular.dilatancy_angle, SPS__DEF_REAL, sps__reads_drucker_prager),   \
    SPS__BODY_ITEM_READ_BY(material.granular.yield_cone, SPS__DEF_INT, sps__reads_drucker_prager),         \
    SPS__BODY_ITEM_READ_BY(material.granular.stress_diffusion, SPS__DEF_REAL, sps__reads_drucker_prager),
/* A Drucker-Prager body's stabilisation: the divergence of its stress (UTVF eq. 25) and the
   stress diffusion (its def's granular.stress_diffusion), no hourglass penalty (the reference code's). */
static const sps__stabilisation sps__granular_stress = {SPS_SHEAR_OG, "granular stress", 1, 0, 0, 0, 0, 0, {0.4, 0.4}};
/* Its row (sps__material_model; the columns: >>material: linear elastic): eta = 20 d for granular
   bodies (UTVF section 3.1.3, after Zhang et al. 2024); mirror walls as the reference code's
   dummy wall particles; no Riemann density term: the density follows the pressure (sps__finish). */
static const sps__material_model sps__drucker_prager_material = {SPS_MATERIAL_DRUCKER_PRAGER, "Drucker-Prager", 0, SPS__YIELD_DRUCKER_PRAGER, 1,
                                                                  0, 20, 0, SPS__MIRROR_STRESS, 0, SPS__VISCOUS_NONE,
                                                                  SPS__READS_MODULI | SPS__READS_STRESS};
/* Its stabilisation (sps__kind_stabilisation): the divergence of its stress, or ANG's penalty
   with it where the def asks GNO or GNO-A (GRANULAR). */
static const sps__stabilisation* sps__granular_stabilisation(const sps_body_def* def) {
    return def->shear == SPS_SHEAR_GNO || def->shear == SPS_SHEAR_GNO_A ? sps__stabilisation_of(def->shear) : &sps__granular_stress;
}
/* Its warnings (sps__material_warnings): angles that look like radians. */
static void sps__granular_warnings(const sps_world* w, const sps__body* b) {
    const sps_material_def* m = &b->def.material;
    if (m->granular.friction_angle > 0 && m->granular.friction_angle <= SPS__PI / 2) /* soils and granular media: 20 to 45 degrees */
        sps__warn(w, "body '%s': material.granular.friction_angle = %g and dilatancy_angle = %g look like radians (%g and %g degrees); both are "
                  "in degrees, plausible range [5, 60]", b->name, (double)m->granular.friction_angle, (double)m->granular.dilatancy_angle,
                  (double)(m->granular.friction_angle * 180 / SPS__PI), (double)(m->granular.dilatancy_angle * 180 / SPS__PI));
}
/* Its model (sps__kind_model): the stress diffusion where the def sets it. */
static void sps__granular_model(const sps_body_def* def, sps__model* m) { m->diffusion = def->material.granular.stress_diffusion > 0; }
/* Its combination rule (sps__combination_rules): the penalty is kept per particle. */
static int sps__granular_pair_rotation(int dim, const sps_body_def* def) {
    (void)dim;
    return def->material.kind == SPS_MATERIAL_DRUCKER_PRAGER && def->shear == SPS_SHEAR_GNO_A && def->rotation == SPS_ROTATION_PAIR;
}

/* A Drucker-Prager body's constants: its cone, the stress diffusion's 2 zeta h c0, the
   divergence's scale and the geostatic difference tensor (sps__body.geostatic). */
static void sps__granular_setup(const sps_world* w, sps__body* b) {
    const sps_real* g = w->def.gravity;
    const sps_real g_norm = SPS__SQRT(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    int a;
    b->cone = sps__yield_cone_of(&b->def.material);
    b->diffusion_rate = 2 * b->def.material.granular.stress_diffusion * w->h * b->mat.c0;
    b->divergence_scale = 1 / sps__lattice_gradient_moment(w, b->hexagonal);
    for (a = 0; a < 6; ++a) {
        const sps_real vertical = g_norm > 0 ? g[sps__sym_row[a]] * g[sps__sym_col[a]] / (g_norm * g_norm) : 0;
        b->geostatic[a] = g_norm > 0 ? -b->rho0 * (vertical + b->cone.k0 * (sps__sym_diagonal(a) - vertical)) : 0;
    }
}


/* The return mapping of a trial stress sig (xx xy xz yy yz zz) onto the cone, as the reference
   code's: first the tension cut-off (a mean stress beyond the apex I1 = k_c / alpha_phi is
   moved back to it), then the deviator scaled by r = (k_c - alpha_phi I1) / sqrt(J2) where it
   exceeds the cone. Branch-free (selects), for the lane loops. */
SPS__INLINE void sps__drucker_prager_return(sps_real sig[6], const sps__yield_cone* c) {
    const sps_real apex = c->alpha_phi > 0 ? c->k_c / c->alpha_phi : (sps_real)INFINITY;
    sps_real i1 = sig[SPS__XX] + sig[SPS__YY] + sig[SPS__ZZ], s[6], j2, strength, r;
    int a;
    if (i1 > apex) i1 = apex;
    /* s: sig less the mean after the cut-off (where the cut-off acted, strength is 0 and r takes s to 0) */
    SPS__UNROLL
    for (a = 0; a < 6; ++a) s[a] = sig[a] - (sps__sym_diagonal(a) ? i1 / 3 : 0);
    j2 = SPS_R(0.5) * sps__sym_contract(s, s);
    strength = c->k_c - c->alpha_phi * i1; /* >= 0 after the cut-off */
    r = j2 > strength * strength ? strength / SPS__SQRT(j2) : 1;
    SPS__UNROLL
    for (a = 0; a < 6; ++a) sig[a] = r * s[a] + (sps__sym_diagonal(a) ? i1 / 3 : 0);
}

/* One particle's stress update over dt (UTVF eqs. 10, 13, 15, then the return mapping): from
   its stress sig (xx xy xz yy yz zz) and velocity gradient L (9 entries, row-major, zero
   outside dim), the Jaumann rate 2G dev(D) + K tr(D) I + W sig - sig W, less the plastic
   flow gamma' (3 K alpha_psi I + G s / sqrt(J2)) where the stress is on or beyond the cone
   (gamma' of eq. 13, kept >= 0: an unloading particle does not flow; the reference code
   lets it go negative), plus the stress diffusion rate (NULL: none), then
   sps__drucker_prager_return. *elastic_trial gets the stress the elastic rate alone would give:
   the difference is the plastic part of the step. */
SPS__INLINE void sps__drucker_prager_update(sps_real sig[6], const sps_real* L, int ls, const sps_real* diffusion, int ds,
                                            const sps__yield_cone* c, sps_real G, sps_real K, sps_real dt, sps_real elastic_trial[6]) {
    const int* row = sps__sym_row;
    const int* col = sps__sym_col;
    sps_real D[6], S[9], tr_d, i1, s[6], j2, f, gamma_rate = 0, rate[6];
    int a, m;
    SPS__UNROLL
    for (a = 0; a < 6; ++a) D[a] = SPS_R(0.5) * (L[(3 * row[a] + col[a]) * ls] + L[(3 * col[a] + row[a]) * ls]);
    tr_d = D[SPS__XX] + D[SPS__YY] + D[SPS__ZZ];
    SPS__UNROLL
    for (a = 0; a < 9; ++a) S[a] = sig[sps__sym9[a]];
    i1 = sps__sym_deviator(sig, s);
    j2 = SPS_R(0.5) * sps__sym_contract(s, s);
    f = c->alpha_phi * i1 + SPS__SQRT(j2) - c->k_c;
    if (f >= 0 && j2 > 0) { /* eq. 13 */
        const sps_real root = SPS__SQRT(j2);
        gamma_rate = (3 * c->alpha_phi * K * tr_d + G / root * sps__sym_contract(s, D)) / (9 * c->alpha_phi * K * c->alpha_psi + G);
        if (!(gamma_rate > 0)) gamma_rate = 0;
    }
    SPS__UNROLL
    for (a = 0; a < 6; ++a) {
        const int diagonal = sps__sym_diagonal(a);
        sps_real spin = 0; /* (W sig - sig W)_ab, W = (L - L^T)/2 */
        SPS__UNROLL
        for (m = 0; m < 3; ++m)
            spin += SPS_R(0.5) * (L[(3 * row[a] + m) * ls] - L[(3 * m + row[a]) * ls]) * S[3 * m + col[a]] -
                    S[3 * row[a] + m] * SPS_R(0.5) * (L[(3 * m + col[a]) * ls] - L[(3 * col[a] + m) * ls]);
        rate[a] = 2 * G * (D[a] - (diagonal ? tr_d / 3 : 0)) + (diagonal ? K * tr_d : 0) + spin + (diffusion ? diffusion[a * ds] : 0);
        elastic_trial[a] = sig[a] + dt * rate[a];
        if (gamma_rate > 0)
            rate[a] -= gamma_rate * ((diagonal ? 3 * K * c->alpha_psi : 0) + G * s[a] / SPS__SQRT(j2));
        sig[a] += dt * rate[a];
    }
    sps__drucker_prager_return(sig, c);
}

/* The constants its pair terms in the pressure pass read, loaded once before the pair loop
   (sps__kind_pressure_constants_of): 0.01 h^2 and the world's gravity. */
typedef struct sps__granular_pair_constants {
    sps_real soft2;
    const sps_real* gravity;
} sps__granular_pair_constants;
SPS__INLINE sps__granular_pair_constants sps__granular_pair_constants_of(const sps_world* w) {
    sps__granular_pair_constants c;
    c.soft2 = SPS_R(0.01) * w->h * w->h;
    c.gravity = w->def.gravity;
    return c;
}
/* Its pair terms in the pressure pass (SPS__TERM_GRANULAR, reached through
   sps__kind_pressure_pair): the stress diffusion (Feng et al. 2021), sum_j (sigma_i - sigma_j -
   geostatic difference) w_ij with the weight w_ij = r dW/(r^2 + 0.01 h^2) V_j (unscaled by the
   lattice moment: a smoothing, not the divergence), summed per particle, not per pair: the
   weights' sum W, sum_j w_ij tau_j, sum_j w_ij p_j and the geostatic sum G = sum_j w_ij g . x_ij,
   which the store combines into W sigma_i - sum_j w_ij sigma_j - G geostatic. The pair then costs
   its weight and one product-sum per row (the difference formed per pair took four operations
   per stress entry). The rows of those sums, from SPS__SPREAD on: */
enum {
    SPS__SPREAD_TAU = 0,       /* 6: sum_j w_ij tau_j (xx xy xz yy yz zz) */
    SPS__SPREAD_WEIGHT = 6,    /* W = sum_j w_ij */
    SPS__SPREAD_PRESSURE = 7,  /* sum_j w_ij p_j */
    SPS__SPREAD_GEOSTATIC = 8, /* G = sum_j w_ij g . x_ij */
    SPS__SPREAD_ROWS = 9
};
/* ... lane l of the pair (i, j) at distance rij with dW and V_j, j's deviator at tau + tj (an
   int offset from the array, a gather, which a pointer to j's entries defeats). The division is
   kept: r/(r^2 + 0.01 h^2) has no cheaper exact form (with the pair's 1/r it is still
   1/(r + 0.01 h^2/r)). */
SPS__INLINE void sps__granular_diffusion_pair(const sps__granular_pair_constants* c, sps_real (*spread)[SPS__LANES], int l,
                                              const sps_real* tau, int tj, sps_real rij, sps_real dw, sps_real vol_j, sps_real ex,
                                              sps_real ey, sps_real ez, const sps_real* p, int j, const int dim) {
    const sps_real* gravity = c->gravity;
    const sps_real weight = rij * dw * vol_j / (rij * rij + c->soft2);
    const sps_real g_x = rij * (gravity[0] * ex + gravity[1] * ey + (dim == 3 ? gravity[2] * ez : 0)); /* g . x_ij */
    spread[SPS__SPREAD_TAU + 0][l] += weight * tau[tj];
    spread[SPS__SPREAD_TAU + 1][l] += weight * tau[tj + 1];
    spread[SPS__SPREAD_TAU + 3][l] += weight * tau[tj + 3];
    spread[SPS__SPREAD_TAU + 5][l] += weight * tau[tj + 5];
    if (dim == 3) {
        spread[SPS__SPREAD_TAU + 2][l] += weight * tau[tj + 2];
        spread[SPS__SPREAD_TAU + 4][l] += weight * tau[tj + 4];
    }
    spread[SPS__SPREAD_WEIGHT][l] += weight;
    spread[SPS__SPREAD_PRESSURE][l] += weight * p[j];
    spread[SPS__SPREAD_GEOSTATIC][l] += weight * g_x;
}
/* ... and the pressure pass's finish (sps__kind_pressure_store): the stress diffusion rate
   2 zeta h c0 (W sigma_i - sum_j w_ij sigma_j - G geostatic), sigma = tau - p I, for the lanes of
   the group from particle i0. The differences are formed here, of sums of the size of the
   stress, where the pair's difference was small: in float, a rounding of the pressure (about
   1e-7 of it) per particle rather than per pair, as the pressure itself is rounded. */
SPS__INLINE void sps__granular_store_diffusion(const sps_world* w, const sps__body* b, int i0, sps_real (*spread)[SPS__LANES]) {
    const sps_real* geostatic = b->geostatic;
    int l, a;
    for (l = 0; l < SPS__LANES && i0 + l < b->end; ++l) {
        const int i = i0 + l;
        const sps_real* tau_i = b->tau + (size_t)6 * (i - b->begin);
        const sps_real weight = spread[SPS__SPREAD_WEIGHT][l], p_sum = spread[SPS__SPREAD_PRESSURE][l];
        const sps_real g_sum = spread[SPS__SPREAD_GEOSTATIC][l];
        for (a = 0; a < 6; ++a) {
            const int diagonal = sps__sym_diagonal(a);
            const sps_real own = weight * (tau_i[a] - (diagonal ? w->p[i] : 0)), others = spread[SPS__SPREAD_TAU + a][l] - (diagonal ? p_sum : 0);
            b->diffusion[(size_t)6 * (i - b->begin) + a] = b->diffusion_rate * (own - others - geostatic[a] * g_sum);
        }
    }
}

/* >>material: Saint Venant-Kirchhoff (total Lagrangian; TL eqs. 18-20) */

/* The hyperelastic laws of total-Lagrangian bodies take the linear elastic checks; their
   signal speed is the P-wave speed c_p = sqrt((K + 4G/3)/rho0) of the linearised law, since
   the full stress tensor, not only its pressure, carries waves (the time step, chapter
   >>stepping). Stress and stored energy: sps__saint_venant_kirchhoff_law (chapter >>material:
   Saint Venant-Kirchhoff (continued): its law). */
static sps__material_constants sps__hyperelastic_constants(const sps_material_def* m, sps__material_constants elastic) {
    sps__material_constants c = elastic;
    c.c0 = SPS__SQRT((c.K + c.G * 4 / 3) / m->density);
    return c;
}
/* Its row (sps__material_model; the columns: >>material: linear elastic): total-Lagrangian
   bodies only, their stored energy comes from F (sps__tl_energy). */
static const sps__material_model sps__saint_venant_kirchhoff_material = {SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF, "Saint Venant-Kirchhoff", 0,
                                                                          SPS__YIELD_NONE, 1, 0, 0, 0, SPS__MIRROR_NONE, 1, SPS__VISCOUS_KELVIN_VOIGT,
                                                                          SPS__READS_MODULI | SPS__READS_STRESS};

/* >>material: Neo-Hookean (total Lagrangian; TL eq. 44) */

/* Its checks and constants are Saint Venant-Kirchhoff's (sps__hyperelastic_constants); its row
   (sps__material_model; the columns: >>material: linear elastic) as Saint Venant-Kirchhoff's;
   its law: sps__neo_hookean_law (chapter >>material: Neo-Hookean (continued): its law). */
static const sps__material_model sps__neo_hookean_material = {SPS_MATERIAL_NEO_HOOKEAN, "Neo-Hookean", 0, SPS__YIELD_NONE, 1, 0, 0, 0, SPS__MIRROR_NONE, 1,
                                                               SPS__VISCOUS_KELVIN_VOIGT, SPS__READS_MODULI | SPS__READS_STRESS};

/* >>generic: the material hooks, dispatched in one place

   Every choice that depends on the material kind is made here, by a switch over
   sps_material_kind (and over sps_solver where that is the choice) that calls the hook in the
   kind's own chapter (>>material: ...), as sokol_gfx's generic backend and Box2D's joint.c do.
   No switch has a default label, so -Wswitch (in -Wall) names every switch a new kind misses; a
   value outside the enum (a def not checked yet) falls out of the switch to the line after it.
   Kinds a build leaves out (CONFIG MACROS) keep their cases: sps__left_out_by refuses their
   bodies at sps_world_add_body, so their other cases are not reached.
   The rest of the library reads the row's properties (sps__material_model: kinematic, shear,
   mirrored walls, the density update, the Riemann terms), resolved once per body into its model
   (sps__resolve_model), and never asks which kind a body is.

   Adding a material touches these places and nothing else (a Maxwell viscoelastic kind, added as
   a trial, touched exactly these):
   1. its value in sps_material_kind (>>public), the next one (the def check lists the kinds
      from the rows: sps__material_kinds);
   2. if it has parameters of its own, their sub-struct in sps_material_def (>>public, one field
      named for the kind, each parameter with units, range and default); if some default is not
      zero, a function in its chapter that sets them (sps__<kind>_defaults) and its call in
      sps__material_defaults here;
   3. its chapter (>>material: ...): its row (sps__material_model), its check, its constants
      (c0, G, K), its stored energy, the rows of its parameters (SPS__<KIND>_DEF_ITEMS and the
      reads function they name: the restart's fingerprint and the unread-field warnings follow;
      new rows change the restart file's layout, so SPS__RESTART_VERSION goes up, chapter
      >>restart, and tests/restore_corpus is saved again)
      and, where they differ from an existing kind's, its setup, warnings, combination rules,
      stress update (a lane update: a "(continued)" chapter after the updated-Lagrangian
      solver's lane helpers), total-Lagrangian law, pair terms and per-particle state rows;
   4. its case in each switch over sps_material_kind here and in this chapter's continuations
      (>>generic (continued): the updated-Lagrangian passes' hooks; ... the laws of
      total-Lagrangian bodies): the compiler lists every switch that lacks it (an enum value
      added without its cases warns in the 17 switches of these chapters, and nowhere else),
      plus its SPS__<KIND>_DEF_ITEMS in sps__body_def_items (>>generic (continued): the body def
      items) and its rules in sps__combination_rules (>>generic (continued): the combination
      rules), if it has any.
   A kind with a stress update of its own has its case in sps__stress_update_lanes (a switch
   over the kind, as the others); one whose stress has a yield surface also adds an sps__yield
   value (what reads it: the plastic fields and the penalty's scale); a kind whose walls act through mirror particles takes an
   sps__mirror_kind in its row; a kind with pair terms of its own in the pressure pass adds an
   SPS__TERM_ bit (its case in sps__kind_pressure_terms), its part of
   sps__kind_pressure_constants and its calls in sps__kind_pressure_pair and
   sps__kind_pressure_store, and a pressure loop with that bit (SPS__PRESSURE_LOOPS). The step,
   the passes and the solvers are not edited otherwise: bench/material_census.sh lists, per
   kind, the functions outside its chapters and this one that name it (its enum value,
   parameters, hooks or state). */

/* The row of a kind, or NULL for a value outside the enum (sps__body_def_check names it). */
static const sps__material_model* sps__material_of(sps_material_kind kind) {
    switch (kind) {
    case SPS_MATERIAL_ELASTIC: return &sps__elastic_material;
    case SPS_MATERIAL_RIGID: return &sps__rigid_material;
    case SPS_MATERIAL_RIGID_DYNAMIC: return &sps__free_rigid_material;
    case SPS_MATERIAL_J2: return &sps__j2_material;
    case SPS_MATERIAL_FLUID: return &sps__fluid_material;
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF: return &sps__saint_venant_kirchhoff_material;
    case SPS_MATERIAL_NEO_HOOKEAN: return &sps__neo_hookean_material;
    case SPS_MATERIAL_DRUCKER_PRAGER: return &sps__drucker_prager_material;
    }
    return NULL;
}

/* The kinds, as the def check lists them: "0 (elastic), 1 (rigid), ... or 6 (Drucker-Prager)"
   (the values of sps_material_kind run from 0 without a gap). */
static const char* sps__material_kinds(char* out, size_t size) {
    size_t len = 0;
    int k;
    out[0] = 0;
    for (k = 0; sps__material_of((sps_material_kind)k) && len < size; ++k) {
        const char* separator = k == 0 ? "" : sps__material_of((sps_material_kind)(k + 1)) ? ", " : " or ";
        len += (size_t)snprintf(out + len, size - len, "%s%d (%s)", separator, k, sps__material_of((sps_material_kind)k)->name);
    }
    return out;
}

/* Appends every broken rule of the material's fields (a kind outside the enum: none here). */
static void sps__material_check(const sps_material_def* m, char* msg, size_t msg_size, int* broken) {
    switch (m->kind) {
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: sps__elastic_check(m, msg, msg_size, broken); return;
    case SPS_MATERIAL_J2: /* the linear elastic law's checks, then its own */
        sps__elastic_check(m, msg, msg_size, broken);
        sps__j2_check(m, msg, msg_size, broken);
        return;
    case SPS_MATERIAL_FLUID: sps__fluid_check(m, msg, msg_size, broken); return;
    case SPS_MATERIAL_DRUCKER_PRAGER: /* the same */
        sps__elastic_check(m, msg, msg_size, broken);
        sps__drucker_prager_check(m, msg, msg_size, broken);
        return;
    }
}

/* Every parameter sub-struct of a material def at its defaults (sps_default_material_def): the
   kinds (and the total-Lagrangian solver) whose defaults are not all zero set theirs in their
   chapters; the others' stay as sps_default_material_def zeroed them. */
static void sps__tl_defaults(sps_tl_def* tl); /* >>solver: total Lagrangian */
static void sps__material_defaults(sps_material_def* m) {
    sps__granular_defaults(&m->granular);
    sps__tl_defaults(&m->tl);
}

/* c0, G and K of a checked material def (signal speed, shear and bulk moduli). */
static sps__material_constants sps__material_constants_of(const sps_material_def* m) {
    switch (m->kind) {
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_J2:
    case SPS_MATERIAL_DRUCKER_PRAGER: break;
    case SPS_MATERIAL_FLUID: return sps__fluid_constants(m);
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: return sps__hyperelastic_constants(m, sps__elastic_constants(m));
    }
    return sps__elastic_constants(m);
}

/* The stored-energy density [J/m^3] of a body of this kind from tau:tau of its shear stress (0
   when not tracked) and its pressure p. A total-Lagrangian body's whole energy comes from F
   (sps__tl_energy); for the pressure it is given at the start (sps_body_set_pressure) its
   hyperelastic law's small-strain limit is the linear elastic one. */
static sps_real sps__material_energy_density(sps_material_kind kind, const sps__material_constants* c, sps_real tau_tau, sps_real p) {
    switch (kind) {
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_J2:
    case SPS_MATERIAL_DRUCKER_PRAGER:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: break;
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC: return sps__rigid_energy_density(c, tau_tau, p);
    case SPS_MATERIAL_FLUID: return sps__fluid_energy_density(c, tau_tau, p);
    }
    return sps__elastic_energy_density(c, tau_tau, p);
}

/* The longest acoustic step body b's viscous force allows (INFINITY: none), by the row's viscous
   column: the solids' Kelvin-Voigt damping or a fluid's Newtonian viscosity. */
static sps_real sps__viscous_dt(const sps_world* w, const sps__body* b) {
    switch (b->model.viscous) {
    case SPS__VISCOUS_NONE: break;
    case SPS__VISCOUS_KELVIN_VOIGT: return sps__kelvin_voigt_dt(w, b);
    case SPS__VISCOUS_NEWTON: return sps__newton_dt(w, b);
    }
    return (sps_real)INFINITY;
}

/* The constants a body of this kind derives from the world when it is added (gravity, the
   kernel): a fluid's rest pressure gradient, a granular body's cone and stress diffusion. */
static void sps__material_setup(const sps_world* w, sps__body* b) {
    switch (b->def.material.kind) {
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_J2:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: return;
    case SPS_MATERIAL_FLUID: sps__fluid_rest_gradient(w, b); return;
    case SPS_MATERIAL_DRUCKER_PRAGER: sps__granular_setup(w, b); return;
    }
}

/* The stabilisation a kind always runs, or NULL: the def's shear formulation. */
static const sps__stabilisation* sps__kind_stabilisation(const sps_body_def* def) {
    switch (def->material.kind) {
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_J2:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: break;
    case SPS_MATERIAL_FLUID: return &sps__no_shear;
    case SPS_MATERIAL_DRUCKER_PRAGER: return sps__granular_stabilisation(def);
    }
    return NULL;
}

/* What a kind sets in the model sps__resolve_model builds from a checked def, after the parts
   every kind shares (the total-Lagrangian solver's parts come after it). */
static void sps__kind_model(const sps_world* w, const sps_body_def* def, sps__model* m) {
    switch (def->material.kind) {
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_J2:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: return;
    case SPS_MATERIAL_RIGID: sps__rigid_model(m); return;
    case SPS_MATERIAL_RIGID_DYNAMIC:
        sps__rigid_model(m);
        sps__free_rigid_model(m);
        return;
    case SPS_MATERIAL_FLUID: sps__fluid_model(w, m); return;
    case SPS_MATERIAL_DRUCKER_PRAGER: sps__granular_model(def, m); return;
    }
}

/* Whether a kind has a law for the updated-Lagrangian solver: the hyperelastic laws take the
   deformation gradient of the reference configuration (a value outside the enum: 1, the kind
   check names it). */
static int sps__updated_lagrangian_law(sps_material_kind kind) {
    switch (kind) {
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_J2:
    case SPS_MATERIAL_FLUID:
    case SPS_MATERIAL_DRUCKER_PRAGER: return 1;
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: return 0;
    }
    return 1;
}

/* The warnings a kind gives when its body is added (values that look like a mistake). */
static void sps__material_warnings(const sps_world* w, const sps__body* b) {
    switch (b->def.material.kind) {
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_J2:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: return;
    case SPS_MATERIAL_FLUID: sps__fluid_warnings(w, b); return;
    case SPS_MATERIAL_DRUCKER_PRAGER: sps__granular_warnings(w, b); return;
    }
}

/* Whether a kind's fills default to the hexagonal lattice (lattice = SPS_LATTICE_AUTO). */
static int sps__kind_fills_hexagonal(const sps_world* w, const sps_body_def* def) {
    switch (def->material.kind) {
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_J2:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN:
    case SPS_MATERIAL_DRUCKER_PRAGER: return 0;
    case SPS_MATERIAL_FLUID: return sps__fluid_fills_hexagonal(w);
    }
    return 0;
}

/* What a kind is that a periodic world cannot hold (sps__periodic_allows_body), or NULL. */
static const char* sps__kind_not_periodic(sps_material_kind kind) {
    switch (kind) {
    case SPS_MATERIAL_RIGID_DYNAMIC: return sps__free_rigid_not_periodic;
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_J2:
    case SPS_MATERIAL_FLUID:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN:
    case SPS_MATERIAL_DRUCKER_PRAGER: break;
    }
    return NULL;
}

/* The macro that left this body's kind or solver out of the build (CONFIG MACROS), or NULL. */
static const char* sps__left_out_by(const sps_body_def* def) {
    switch (def->material.kind) {
    case SPS_MATERIAL_FLUID:
#ifdef SPHSOLID_NO_FLUID
        return "SPHSOLID_NO_FLUID";
#endif
        break;
    case SPS_MATERIAL_DRUCKER_PRAGER:
#ifdef SPHSOLID_NO_GRANULAR
        return "SPHSOLID_NO_GRANULAR";
#endif
        break;
    case SPS_MATERIAL_J2:
#ifdef SPHSOLID_NO_PLASTICITY
        return "SPHSOLID_NO_PLASTICITY";
#endif
        break;
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: break;
    }
    switch (def->solver) {
    case SPS_SOLVER_TOTAL_LAGRANGIAN:
#ifdef SPHSOLID_NO_TOTAL_LAGRANGIAN
        return "SPHSOLID_NO_TOTAL_LAGRANGIAN";
#endif
        break;
    case SPS_SOLVER_UPDATED_LAGRANGIAN: break;
    }
    return NULL;
}

/* Whether a kind has a law of the deformation gradient for the total-Lagrangian solver (its
   case in sps__tl_law, chapter >>generic (continued): the laws of total-Lagrangian bodies); a
   kind without one is refused by the combination rules, and sps__tl_passes finds no kernel for
   it, which sps_world_add_body reports (sps__missing_pass). */
static int sps__tl_has_law(sps_material_kind kind) {
    switch (kind) {
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN:
    case SPS_MATERIAL_J2: return 1;
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_FLUID:
    case SPS_MATERIAL_DRUCKER_PRAGER: return 0;
    }
    return 0; /* a value outside the enum (refused by the def check) */
}

/* >>generic (continued): the body def items

   The rows of sps_body_def's fields that change results (sps__def_item: the restart's
   fingerprint, its check and message, the unread-field warning): the fields every body has,
   then each kind's rows from its chapter (SPS__<KIND>_DEF_ITEMS; a new kind with parameters
   adds its macro here), the total-Lagrangian solver's, and the rest of the body def. */
static const sps__def_item sps__body_def_items[] = {
    SPS__BODY_ITEM(solver, SPS__DEF_INT),
    SPS__BODY_ITEM(material.kind, SPS__DEF_INT),
    SPS__BODY_ITEM(material.density, SPS__DEF_REAL),
    SPS__BODY_ITEM_READ_BY(material.youngs_modulus, SPS__DEF_REAL, sps__reads_elastic_moduli),
    SPS__BODY_ITEM_READ_BY(material.poisson_ratio, SPS__DEF_REAL, sps__reads_elastic_moduli),
    SPS__BODY_ITEM(material.viscosity, SPS__DEF_REAL), /* the kinds that do not read it refuse it (sps__combination_rules) */
    SPS__J2_DEF_ITEMS
    SPS__FLUID_DEF_ITEMS
    SPS__GRANULAR_DEF_ITEMS
    SPS__TL_DEF_ITEMS
    SPS__BODY_ITEM_READ_BY(shear, SPS__DEF_INT, sps__reads_shear),
    SPS__BODY_ITEM_READ_BY(rotation, SPS__DEF_INT, sps__reads_rotation),
    SPS__BODY_ITEM_READ_BY(zeta, SPS__DEF_REAL, sps__reads_zeta),
    SPS__BODY_ITEM_READ_BY(xi, SPS__DEF_REAL, sps__reads_xi),
    SPS__BODY_ITEM_READ_BY(penalty_in_pressure_pass, SPS__DEF_INT, sps__reads_xi),
    SPS__BODY_ITEM_READ_BY(oas_epsilon, SPS__DEF_REAL, sps__reads_oas),
    SPS__BODY_ITEM_READ_BY(oas_exponent, SPS__DEF_REAL, sps__reads_oas),
    SPS__BODY_ITEM_READ_BY(track_stress, SPS__DEF_INT, sps__reads_stress),
    SPS__BODY_ITEM(transport, SPS__DEF_INT),
    SPS__BODY_ITEM(contact, SPS__DEF_INT),
    SPS__BODY_ITEM_READ_BY(transport_coefficient, SPS__DEF_REAL, sps__reads_transport_coefficient),
    SPS__BODY_ITEM(damping, SPS__DEF_REAL),
    SPS__BODY_ITEM(friction, SPS__DEF_REAL),
    SPS__BODY_ITEM(contact_damping, SPS__DEF_REAL),
    SPS__BODY_ITEM_READ_BY(transport_carries_velocity, SPS__DEF_INT, sps__reads_transport_coefficient),
    SPS__BODY_ITEM(lattice, SPS__DEF_INT)};
#define SPS__BODY_DEF_ITEMS ((int)(sizeof sps__body_def_items / sizeof sps__body_def_items[0]))

/* >>model (continued): the rows */

/* ---- stabilisations ---- */
static const sps__stabilisation sps__stabilisations[] = {
    /* shear           name     force eno  pen  proj art  rotated  stable CFL 2D, 3D */
    {SPS_SHEAR_ENO,   "ENO",   0,    1,   0,   0,   0,   0,       {0.6, 0.5}},
    {SPS_SHEAR_ENO_A, "ENO-A", 0,    1,   0,   0,   0,   1,       {0.6, 0.5}},
    {SPS_SHEAR_OG,    "OG",    1,    0,   0,   0,   0,   0,       {0.8, 0.8}},
    {SPS_SHEAR_OAS,   "OAS",   1,    0,   0,   0,   1,   0,       {1, 0}},
    {SPS_SHEAR_GNO,   "GNO",   1,    0,   1,   0,   0,   0,       {0.8, 0.6}},
    {SPS_SHEAR_GNO_A, "GNO-A", 1,    0,   1,   1,   0,   1,       {0.8, 0.8}},
};
#define SPS__NSTABILISATIONS ((int)(sizeof sps__stabilisations / sizeof sps__stabilisations[0]))
/* A total-Lagrangian body's stabilisation is the hourglass force of TL eq. 32 (its def's shear
   is not used). Stable CFL: the default 0.4, with the hourglass springs in the signal speed
   (sps__tl_reference); the plate ran at 0.8 too, and the instabilities of D1-D4 come at the
   same strain at 0.05 as at 0.4 (bench/VALIDATION.md), so they are not the time step's. */
static const sps__stabilisation sps__tl_hourglass = {SPS_SHEAR_OG, "TL hourglass", 1, 0, 0, 0, 0, 0, {0.4, 0.4}};

static const sps__stabilisation* sps__stabilisation_of(sps_shear shear) {
    int k;
    for (k = 0; k < SPS__NSTABILISATIONS; ++k)
        if (sps__stabilisations[k].shear == shear) return &sps__stabilisations[k];
    return NULL;
}

/* The allowed combinations of a body's model, one rule a row: a def that breaks one gets the
   row's message (a format of the world's dim). */
typedef struct sps__combination_rule {
    int (*broken)(int dim, const sps_body_def* def);
    const char* message;
} sps__combination_rule;
static int sps__oas_outside_2d(int dim, const sps_body_def* def) { return def->shear == SPS_SHEAR_OAS && dim != 2; }
static int sps__hyperelastic_updated(int dim, const sps_body_def* def) {
    (void)dim;
    return def->solver != SPS_SOLVER_TOTAL_LAGRANGIAN && !sps__updated_lagrangian_law(def->material.kind);
}
static int sps__total_lagrangian_other_law(int dim, const sps_body_def* def) {
    (void)dim;
    return def->solver == SPS_SOLVER_TOTAL_LAGRANGIAN && !sps__tl_has_law(def->material.kind);
}
static int sps__shifted_reference(int dim, const sps_body_def* def) {
    (void)dim;
    return def->transport != SPS_TRANSPORT_NONE && def->solver == SPS_SOLVER_TOTAL_LAGRANGIAN;
}
static int sps__damage_updated(int dim, const sps_body_def* def) {
    (void)dim;
    return def->material.tl.damage_strain > 0 && def->solver != SPS_SOLVER_TOTAL_LAGRANGIAN;
}
static int sps__viscosity_updated(int dim, const sps_body_def* def) {
    (void)dim;
    return def->material.tl.artificial_viscosity > 0 && def->solver != SPS_SOLVER_TOTAL_LAGRANGIAN;
}
static int sps__viscosity_without_viscous_force(int dim, const sps_body_def* def) {
    const sps__material_model* material = sps__material_of(def->material.kind);
    (void)dim;
    return def->material.viscosity > 0 && material && material->viscous == SPS__VISCOUS_NONE;
}
static int sps__friction_without_contact(int dim, const sps_body_def* def) { (void)dim; return def->friction > 0 && !def->contact; }
static int sps__friction_of_mirrored(int dim, const sps_body_def* def) {
    const sps__material_model* material = sps__material_of(def->material.kind);
    (void)dim;
    return def->friction > 0 && material && material->mirrored;
}
static int sps__contact_damping_without_contact(int dim, const sps_body_def* def) {
    const sps__material_model* material = sps__material_of(def->material.kind);
    (void)dim;
    return def->contact_damping > 0 && (!def->contact || (material && material->mirrored));
}
/* penalty_in_pressure_pass where its pressure pass cannot hold the penalty: a pair force g_ij
   (rotation = pair), which that pass reads, or a kind with pressure terms of its own (a
   Drucker-Prager body's stress diffusion: sps__kind_pressure_terms), whose loops have no penalty */
static int sps__kind_pressure_terms(sps_material_kind kind); /* >>generic */
static int sps__penalty_outside_pressure_pass(int dim, const sps_body_def* def) {
    (void)dim;
    return def->penalty_in_pressure_pass == 1 && sps__reads_xi(def) &&
           (sps__kind_pressure_terms(def->material.kind) != 0 || (def->shear == SPS_SHEAR_GNO_A && def->rotation == SPS_ROTATION_PAIR)); /* GNO-A's auto: mean */
}
/* >>generic (continued): the combination rules, one row each: the kinds' rules are in their
   chapters, the solver's and the stabilisations' above */

static const sps__combination_rule sps__combination_rules[] = {
    {sps__viscosity_without_viscous_force, "material.viscosity > 0 with a material.kind that has no viscous force: the Kelvin-Voigt damping "
                                    "is for elastic, J2, Saint Venant-Kirchhoff and Neo-Hookean bodies, the Newtonian viscosity for "
                                    "fluids (a wall body moves as given; a granular body dissipates by plastic flow)"},
    {sps__friction_without_contact, "friction > 0 with contact = 0: a body without contact has no friction"},
    {sps__friction_of_mirrored, "friction > 0 with material.kind = fluid or Drucker-Prager: walls act on these through mirror particles "
                                "(a no-slip wall holds them), not the solids' contact, so there is no Coulomb friction to set"},
    {sps__contact_damping_without_contact, "contact_damping > 0 with contact = 0 or material.kind = fluid or Drucker-Prager: the "
                                           "dashpot acts in the solids' contact (walls act on fluid and granular bodies through mirror "
                                           "particles)"},
    {sps__granular_pair_rotation, "material.kind = Drucker-Prager with shear = GNO-A and rotation = pair: a granular body keeps its "
                                  "penalty per particle; use rotation = mean or per particle"},
    {sps__penalty_outside_pressure_pass, "penalty_in_pressure_pass = 1 with rotation = pair or material.kind = Drucker-Prager: the "
                                         "pressure pass reads the pair forces the penalty writes, and a granular body's pressure pass "
                                         "has no penalty terms; use 0 (the penalty's own pass) or, for GNO-A, rotation = mean or per "
                                         "particle"},
    {sps__inviscid_undissipated, "material.fluid.dissipation = 1 or 2 with material.viscosity = 0: without the Riemann solver's momentum "
                                 "dissipation only the physical viscosity damps the particles' noise; set material.viscosity > 0 "
                                 "or material.fluid.dissipation = 0"},
    {sps__moving_wall_particles, "transport = TVF or UTVF with material.kind = rigid: a wall body's particles keep the motion given to them"},
    {sps__shifted_reference, "transport = TVF or UTVF with solver = total Lagrangian: its neighbours are those of the reference "
                             "configuration, which a shift of the particles would not move"},
    {sps__hyperelastic_updated, "material.kind = Saint Venant-Kirchhoff or Neo-Hookean with solver = updated Lagrangian: these laws "
                                "take the deformation gradient of the reference configuration; use solver = total Lagrangian"},
    {sps__total_lagrangian_other_law, "solver = total Lagrangian with material.kind other than Saint Venant-Kirchhoff (4), Neo-Hookean "
                                      "(5) or J2 (2): a total-Lagrangian body needs a law of the deformation gradient"},
    {sps__damage_updated, "material.tl.damage_strain > 0 with solver = updated Lagrangian: the damage model (TL eqs. 45-46) reads the "
                          "deformation gradient of the reference configuration; use solver = total Lagrangian"},
    {sps__viscosity_updated, "material.tl.artificial_viscosity > 0 with solver = updated Lagrangian: it acts between the reference "
                             "neighbours of a total-Lagrangian body; use solver = total Lagrangian"},
    {sps__oas_outside_2d, "shear = OAS with dim = %d: Gray et al.'s artificial stress is 2D only"},
    {sps__damped_wall, "damping > 0 with material.kind = rigid: a wall body's particles keep the velocity given to them"},
    /* ANG sections 4.1 and 5.2: ENO's shear force is an accumulated Laplacian of velocity, not
       the divergence of the stress, so a return map on tau would not limit it */
    {sps__plastic_without_stress_force, "material.kind = J2 with shear = ENO or ENO-A: their shear force is an accumulated "
                                        "Laplacian of velocity, not the divergence of the stress, so the yield surface cannot "
                                        "limit it (ANG 5.2: ENO-A is for elastic materials); use GNO-A (or OG, OAS, GNO)"},
};

/* >>model (continued) */

static sps_result sps__body_def_check(int dim, const sps_body_def* def, char* msg, size_t msg_size) {
    int broken = 0, k;
    const sps__material_model* material = sps__material_of(def->material.kind);
    SPS__CHECK(def->internal_cookie == SPS__COOKIE, "body def not initialised: start from sps_default_body_def()");
    if (!material) {
        char kinds[256];
        sps__rule(msg, msg_size, &broken, "material.kind = %d, allowed %s", (int)def->material.kind, sps__material_kinds(kinds, sizeof kinds));
    }
    sps__material_check(&def->material, msg, msg_size, &broken);
    SPS__CHECK(sps__stabilisation_of(def->shear) != NULL, "shear = %d, allowed 0..5 (ENO, ENO-A, OG, OAS, GNO, GNO-A)", (int)def->shear);
    SPS__CHECK(def->solver == SPS_SOLVER_UPDATED_LAGRANGIAN || def->solver == SPS_SOLVER_TOTAL_LAGRANGIAN,
               "solver = %d, allowed 0 (updated Lagrangian) or 1 (total Lagrangian)", (int)def->solver);
    SPS__CHECK(def->material.tl.hourglass_alpha >= 0 && def->material.tl.hourglass_alpha <= 1000, "material.tl.hourglass_alpha = %g, allowed [0, 1000]",
               (double)def->material.tl.hourglass_alpha);
    SPS__CHECK(def->material.tl.hourglass == SPS_HOURGLASS_VARIATIONAL || def->material.tl.hourglass == SPS_HOURGLASS_PAPER,
               "material.tl.hourglass = %d, allowed 0 (variational) or 1 (paper: TL eq. 32 as printed)", (int)def->material.tl.hourglass);
    SPS__CHECK(def->material.tl.artificial_viscosity >= 0 && def->material.tl.artificial_viscosity <= 1, "material.tl.artificial_viscosity = %g, allowed [0, 1] (0: none)",
               (double)def->material.tl.artificial_viscosity);
    SPS__CHECK(def->material.tl.damage_strain >= 0 && def->material.tl.damage_strain <= 100,
               "material.tl.damage_strain = %g, allowed [0, 100] (a principal Green-Lagrange strain; 0: no damage)", (double)def->material.tl.damage_strain);
    SPS__CHECK(def->transport == SPS_TRANSPORT_NONE || def->transport == SPS_TRANSPORT_TVF || def->transport == SPS_TRANSPORT_UTVF,
               "transport = %d, allowed 0 (none), 1 (TVF) or 2 (UTVF)", (int)def->transport);
    SPS__CHECK(def->transport_coefficient >= 0 && def->transport_coefficient <= 1,
               "transport_coefficient = %g, allowed 0 (default 0.2) or (0, 1]", (double)def->transport_coefficient);
    SPS__CHECK(def->transport_carries_velocity == 0 || def->transport_carries_velocity == 1,
               "transport_carries_velocity = %d, allowed 0 (positions only) or 1 (the velocity with them)", def->transport_carries_velocity);
    SPS__CHECK(def->lattice == SPS_LATTICE_AUTO || def->lattice == SPS_LATTICE_SQUARE || def->lattice == SPS_LATTICE_HEXAGONAL,
               "lattice = %d, allowed 0 (auto), 1 (square) or 2 (hexagonal, 2D)", (int)def->lattice);
    SPS__CHECK(def->lattice != SPS_LATTICE_HEXAGONAL || dim == 2, "lattice = 2 (hexagonal) in a %dD world, allowed in 2D only (3D: 0 or 1)", dim);
    for (k = 0; k < (int)(sizeof sps__combination_rules / sizeof sps__combination_rules[0]); ++k)
        SPS__CHECK(!sps__combination_rules[k].broken(dim, def), sps__combination_rules[k].message, dim);
    SPS__CHECK(!sps__left_out_by(def), "material.kind = %d with solver = %d: this build left it out (%s is defined)",
               (int)def->material.kind, (int)def->solver, sps__left_out_by(def));
    SPS__CHECK(def->xi >= 0 && def->xi <= 100, "xi = %g, allowed 0 (default 2) or (0, 100]", (double)def->xi);
    SPS__CHECK(def->penalty_in_pressure_pass == 0 || def->penalty_in_pressure_pass == 1,
               "penalty_in_pressure_pass = %d, allowed 0 (the penalty's own pass, the paper's) or 1 (in the next pressure pass)",
               def->penalty_in_pressure_pass);
    SPS__CHECK(def->oas_epsilon >= 0 && def->oas_epsilon <= 1, "oas_epsilon = %g, allowed [0, 1]", (double)def->oas_epsilon);
    SPS__CHECK(def->oas_exponent >= 1 && def->oas_exponent <= SPS__OAS_MAX_EXPONENT, "oas_exponent = %g, allowed [1, %d]", (double)def->oas_exponent, SPS__OAS_MAX_EXPONENT);
    SPS__CHECK(def->rotation == SPS_ROTATION_MEAN || def->rotation == SPS_ROTATION_PER_PARTICLE || def->rotation == SPS_ROTATION_PAIR ||
                   def->rotation == SPS_ROTATION_AUTO,
               "rotation = %d, allowed 0 (mean), 1 (per particle), 2 (pair) or 3 (auto)", (int)def->rotation);
    SPS__CHECK(def->zeta >= 0 && def->zeta <= 100, "zeta = %g, allowed 0 (default 0.7 d + 2.1) or (0, 100]", (double)def->zeta);
    SPS__CHECK(def->track_stress == 0 || def->track_stress == 1, "track_stress = %d, allowed 0 or 1", def->track_stress);
    SPS__CHECK(def->contact == 0 || def->contact == 1, "contact = %d, allowed 0 or 1", def->contact);
    SPS__CHECK(def->damping >= 0 && sps__finite(def->damping), "damping = %g, allowed finite >= 0 1/s (0: off)", (double)def->damping);
    SPS__CHECK(def->friction >= 0 && sps__finite(def->friction), "friction = %g, allowed finite >= 0 (Coulomb coefficient; 0: none)",
               (double)def->friction);
    SPS__CHECK(def->contact_damping >= 0 && def->contact_damping <= 1,
               "contact_damping = %g, allowed [0, 1] (the damping ratio of the normal contact dashpot; 0: none)", (double)def->contact_damping);
    if (material && material->shear)
        SPS__CHECK(def->material.viscosity >= 0 && sps__finite(def->material.viscosity),
                   "material.viscosity = %g, allowed finite >= 0 Pa s (the Kelvin-Voigt viscosity eta; 0: none)", (double)def->material.viscosity);
    return broken ? SPS_ERR_INVALID_ARG : SPS_OK;
}

/* The pass kernels of a model in the world's dimension and pair geometry (chapter >>forces). */
static sps__passes sps__choose_passes(const sps_world* w, const sps__model* m);
static int sps__missing_pass(const sps__model* m, const sps__passes* p, char* msg, size_t size);

/* SPS_ROTATION_AUTO: the rotation measured best for the formulation (bench/VALIDATION.md, user
   scenes). ENO-A: pair, whose forces are central pair forces (momentum exact, no energy gained
   by a tumbling body; the mean rotation gains). GNO-A: mean, ANG's choice: its stress
   divergence is not central, and the pair rotation gained energy where the mean did not (a disc
   spinning at 50 rad/s on a free-slip floor: 5.9 % against none); granular GNO-A bodies cannot
   keep per-pair increments anyway. */
static sps_rotation sps__rotation_of(const sps_body_def* def) {
    if (def->rotation != SPS_ROTATION_AUTO) return def->rotation;
    return def->shear == SPS_SHEAR_GNO_A ? SPS_ROTATION_MEAN : SPS_ROTATION_PAIR;
}

/* The model of a checked def in world w (pass kernels excepted: sps__choose_passes). */
static sps__model sps__resolve_model(const sps_world* w, const sps_body_def* def) {
    const sps_rotation rotation = sps__rotation_of(def);
    sps__model m;
    memset(&m, 0, sizeof m);
    m.material = sps__material_of(def->material.kind);
    m.stabilisation = sps__kind_stabilisation(def);
    if (!m.stabilisation) m.stabilisation = sps__stabilisation_of(def->shear);
    m.paired = m.stabilisation->rotated && rotation == SPS_ROTATION_PAIR;
    m.turn = !m.stabilisation->rotated || m.paired ? SPS__TURN_NONE
             : rotation == SPS_ROTATION_MEAN ? SPS__TURN_MEAN : SPS__TURN_PARTICLE;
    m.stress = m.stabilisation->stress_force || def->track_stress;
    m.gradient = m.turn != SPS__TURN_NONE || m.stress;
    m.artificial_stress = m.stabilisation->artificial_stress;
    m.plastic = m.material->plastic; /* a plastic body is of the OG family (combination rules): m.stress is set */
    m.scaled_penalty = m.plastic && m.stabilisation->penalty;
    m.mirrored = m.material->mirrored;
    m.pressure_of_density = m.material->pressure_of_density;
    m.limited = m.material->limiter > 0 || m.material->limiter_per_dim > 0;
    m.viscous = def->material.viscosity > 0 ? m.material->viscous : SPS__VISCOUS_NONE;
    m.riemann_density = m.material->riemann_density;
    m.transport = def->transport;
    sps__kind_model(w, def, &m);
    if (def->solver == SPS_SOLVER_TOTAL_LAGRANGIAN) { /* its stress comes from F: tau holds its Cauchy stress + p I */
        m.stabilisation = &sps__tl_hourglass;
        m.total_lagrangian = m.stress = 1; /* m.plastic stays: a J2 body's return map is sps__tl_j2 */
        m.damage = def->material.tl.damage_strain > 0;
        m.paired = m.gradient = m.artificial_stress = m.scaled_penalty = 0;
        m.turn = SPS__TURN_NONE;
    }
    m.penalty_in_pressure = def->penalty_in_pressure_pass && m.stabilisation->penalty;
    return m;
}

/* >>kernel */

/* Kernel shape f(q) and df/dq with q = r/h and support q < 2; W = norm f, dW/dr = norm f'/h.
   Branch-free (clamps and selects) so the neighbour loops that call them vectorise. */
SPS__INLINE sps_real sps__kernel_f(int type, sps_real q) {
    if (type == SPS_KERNEL_WENDLAND_C2) { /* (1 - q/2)^4 (2q + 1) */
        sps_real a = 1 - SPS_R(0.5) * q, a2;
        a = a > 0 ? a : 0;
        a2 = a * a;
        return a2 * a2 * (2 * q + 1);
    } else {
        sps_real a = 2 - q, outer;
        a = a > 0 ? a : 0;
        outer = SPS_R(0.25) * a * a * a;
        return q < 1 ? 1 - SPS_R(1.5) * q * q + SPS_R(0.75) * q * q * q : outer;
    }
}
SPS__INLINE sps_real sps__kernel_df(int type, sps_real q) {
    if (type == SPS_KERNEL_WENDLAND_C2) { /* -5 q (1 - q/2)^3 */
        sps_real a = 1 - SPS_R(0.5) * q;
        a = a > 0 ? a : 0;
        return -5 * q * a * a * a;
    } else {
        sps_real a = 2 - q, outer;
        a = a > 0 ? a : 0;
        outer = SPS_R(-0.75) * a * a;
        return q < 1 ? -3 * q + SPS_R(2.25) * q * q : outer;
    }
}
/* Normalisation so that the kernel integrates to one (2D / 3D). */
static sps_real sps__kernel_norm(int type, int dim, sps_real h) {
    if (type == SPS_KERNEL_WENDLAND_C2)
        return dim == 2 ? 7 / (4 * SPS__PI * h * h) : 21 / (16 * SPS__PI * h * h * h);
    return dim == 2 ? 10 / (7 * SPS__PI * h * h) : 1 / (SPS__PI * h * h * h);
}

SPSDEF sps_real sps_world_kernel(const sps_world* w, sps_real r) {
    return w ? w->kernel_norm * sps__kernel_f(w->def.kernel, r / w->h) : 0;
}
SPSDEF sps_real sps_world_kernel_derivative(const sps_world* w, sps_real r) {
    return w ? w->kernel_norm / w->h * sps__kernel_df(w->def.kernel, r / w->h) : 0;
}

/* The kernel-gradient moment c = -(1/d) sum_j r_ij dW/dr(r_ij) V_j of a particle inside the
   square (cubic) lattice of spacing dp, V_j = dp^d. The continuum's integral is 1; the lattice
   sum is not (Wendland C2 at h = 1.3 dp: 0.974 in 2D), so the stress divergence
   sum_j (sigma_i + sigma_j) grad W_ij V_j reads a linear stress's gradient c times too small and
   a layer at rest balances its weight only at 1/c of its hydrostatic or geostatic stress
   (measured: a granular layer +3.1 % at mid-depth, dp 0.05; +0.9 % at h = 1.5 dp, where c =
   0.997; water 0.5 m deep at dp 0.02 +2.6 % at its floor, bench/VALIDATION.md "Still water").
   The pressure force of a fluid and the stress divergence of a Drucker-Prager body are divided
   by c (sps__body.divergence_scale): the lattice value of the correction B_i = (-sum_j r_ij (x)
   grad W_ij V_j)^-1 (ANG eq. 21), which keeps the pair forces antisymmetric (momentum exact)
   and costs nothing per pair. A body filled on the hexagonal lattice (2D, sps_lattice) takes
   that lattice's sum (0.985 at h = 1.3 dp; the square lattice's value left its water 1 % off
   its hydrostatic balance at the start). */
static sps_real sps__lattice_gradient_moment(const sps_world* w, int hexagonal) {
    const int reach = (int)(w->support / w->def.dp) + 2, dim = w->dim;
    const sps_real volume = dim == 2 ? w->def.dp * w->def.dp : w->def.dp * w->def.dp * w->def.dp;
    const double spacing = hexagonal ? sqrt(2 / sqrt(3.0)) : 1; /* along a row [dp]; the rows sqrt(3)/2 of it apart */
    sps_real sum = 0;
    int a, b, c;
    for (a = -reach; a <= reach; ++a)
        for (b = -reach; b <= reach; ++b)
            for (c = dim == 3 ? -reach : 0; c <= (dim == 3 ? reach : 0); ++c) {
                const double x = hexagonal ? (a + 0.5 * (b & 1)) * spacing : a, y = hexagonal ? b * spacing * sqrt(3.0) / 2 : b;
                const sps_real r = w->def.dp * (sps_real)sqrt(x * x + y * y + (double)(c * c));
                if (r > 0 && r < w->support) sum += r * sps_world_kernel_derivative(w, r) * volume;
            }
    return -sum / dim;
}


/* dW/dr for the world's kernel, used in the hot loops (no division: constants precomputed). */
SPS__INLINE sps_real sps__dwdr(const sps_world* w, sps_real r) {
    return w->dw_scale * sps__kernel_df(w->def.kernel, r * w->inv_h);
}

/* The kernel summed over what lies beyond a flat surface, for the sums whose neighbours are
   missing there (rigid walls, body-fitted particles): at depth z_k = k 2h / n, k = 0..n,
       plane[k]  = integral of W over the plane at distance z_k (2D: a line),
       beyond[k] = integral of W over the half-space beyond it = int_{z_k}^{2h} plane.
   Simpson's rule in the plane (400 panels: the kernel is smooth), trapezoids in depth. */
static void sps__kernel_plane_tables(const sps_world* w, int n, sps_real* plane, sps_real* beyond) {
    const int m = 400;
    const double support = (double)w->support;
    int k, q;
    for (k = 0; k <= n; ++k) {
        const double d = support * k / n, span = sqrt(support * support - d * d);
        double sum = 0;
        for (q = 0; q <= m; ++q) { /* s along the plane from the foot of the perpendicular */
            const double s = span * q / m, r = sqrt(d * d + s * s);
            const double f = (double)sps_world_kernel(w, (sps_real)r) * (w->dim == 2 ? 2.0 : 2.0 * 3.14159265358979323846 * s);
            sum += f * (q == 0 || q == m ? 1 : q % 2 ? 4 : 2);
        }
        plane[k] = (sps_real)(sum * span / (3.0 * m));
    }
    beyond[n] = 0;
    for (k = n - 1; k >= 0; --k) beyond[k] = beyond[k + 1] + (sps_real)(0.5 * support / n) * (plane[k] + plane[k + 1]);
}

/* A table of sps__kernel_plane_tables (n intervals over [0, 2h]) at depth z (linear
   interpolation; its value at 0 below 0, 0 from 2h on). */
static sps_real sps__plane_table_at(const sps_world* w, const sps_real* table, int n, sps_real z) {
    const sps_real x = z / w->support * (sps_real)n;
    int k;
    if (!(x > 0)) return table[0];
    if (x >= (sps_real)n) return 0;
    k = (int)x;
    return table[k] + (x - (sps_real)k) * (table[k + 1] - table[k]);
}

/* >>riemann */

SPSDEF sps_real sps_riemann_pressure(sps_real rho_l, sps_real u_l, sps_real p_l, sps_real c_l,
                                     sps_real rho_r, sps_real u_r, sps_real p_r, sps_real c_r, int limiter) {
    sps_real zl = rho_l * c_l, zr = rho_r * c_r;
    sps_real beta = 1;
    if (limiter) { /* dissipation only under compression (ENO eq. 16, made dimensionless) */
        sps_real b = 3 * (u_l - u_r) / (SPS_R(0.5) * (c_l + c_r));
        beta = b < 0 ? 0 : b > 1 ? 1 : b;
    }
    /* ENO eq. 14 */
    return (zl * p_r + zr * p_l + beta * zl * zr * (u_l - u_r)) / (zl + zr);
}

/* >>create */

/* Tag that marks the handles of a world: a process-wide serial number, so a handle from another
   world (or from a destroyed world whose memory was reused) is rejected. 15 bits, never zero:
   only worlds created 32767 creations apart can share a tag. The counter is the library's only
   global; it is updated under a critical section when OpenMP is on. */
static uint32_t sps__next_world_tag(void) {
    static uint32_t serial = 0;
    uint32_t tag;
    SPS__PRAGMA(omp critical(sps__world_tag))
    {
        serial = serial % 0x7fff + 1;
        tag = serial;
    }
    return tag;
}

/* Sends a creation error to the def's log (or the default one): there is no world to keep it. */
static sps_result sps__create_error(const sps_world_def* def, sps_result r, const char* msg) {
    sps_log_fn log = def ? def->log : NULL;
#ifndef SPHSOLID_NO_STDIO
    if (!log) log = sps__stderr_log;
#endif
    if (log) log(0, msg, def ? def->log_user : NULL);
    return r;
}

/* Where contacts are at rest (contact_rest; chapter >>contact). SPS_CONTACT_REST_FLUSH: a
   wall's contact density above its value at dp/2 pushes, and a particle's density from other
   bodies above the density a lattice row sees from a flush lattice of the same spacing beyond
   the surface between them (rows at dp, 2 dp, ... straight across; summed, not integrated, so
   that two filled boxes side by side start at rest to round-off). SPS_CONTACT_REST_KERNEL: all
   of it pushes (the papers' law), a wall up to the kernel's edge. The wall's density at rest
   waits for the wall tables (sps_world_add_wall). */
static void sps__contact_rest(sps_world* w) {
    const int reach = (int)(w->support / w->def.dp) + 1;
    double sum = 0;
    int m, k, l;
    w->rest_pair_sigma = 0;
    w->rest_wall_distance = w->support;
    if (w->def.contact_rest == SPS_CONTACT_REST_KERNEL) return;
    for (m = 1; m <= reach; ++m)
        for (k = -reach; k <= reach; ++k)
            for (l = w->dim == 3 ? -reach : 0; l <= (w->dim == 3 ? reach : 0); ++l)
                sum += (double)sps_world_kernel(w, w->def.dp * SPS__SQRT((sps_real)(m * m + k * k + l * l)));
    w->rest_pair_sigma = (sps_real)sum * w->dp_volume;
    w->rest_wall_distance = SPS_R(0.5) * w->def.dp;
}

SPSDEF sps_result sps_world_create(const sps_world_def* def, sps_world** out) {
    char msg[1024];
    sps_world_def d;
    sps_world* w;
    sps_result r;
    if (!out) return sps__create_error(def, SPS_ERR_INVALID_ARG, "sps_world_create: out must not be NULL");
    *out = NULL;
    r = sps_world_def_check(def, msg, sizeof msg);
    if (r != SPS_OK) return sps__create_error(def, r, msg);
    d = *def;
    if (!d.allocator.alloc) { d.allocator.alloc = sps__default_alloc; d.allocator.free = sps__default_free; }
#ifndef SPHSOLID_NO_STDIO
    if (!d.log) d.log = sps__stderr_log;
#endif
    w = (sps_world*)d.allocator.alloc(sizeof *w, d.allocator.user);
    if (!w) return sps__create_error(def, SPS_ERR_OUT_OF_MEMORY, "sps_world_create: out of memory: the allocator returned NULL for the world");
    memset(w, 0, sizeof *w);
    w->def = d;
    w->dim = d.dim;
    w->threads = d.threads;
#ifdef _OPENMP
    if (w->threads <= 0) w->threads = omp_get_max_threads();
    if (w->threads > SPS__MAX_THREADS) w->threads = SPS__MAX_THREADS;
#else
    if (w->threads > 1)
        sps__warn(w, "threads = %d, but this build has no OpenMP: the world runs on 1 thread (compile with -fopenmp)", w->threads);
    w->threads = 1;
#endif
    w->tag = sps__next_world_tag();
    w->h = d.h_over_dp * d.dp;
    w->support = 2 * w->h;
    w->kernel_norm = sps__kernel_norm(d.kernel, d.dim, w->h);
    w->inv_h = 1 / w->h;
    w->dw_scale = w->kernel_norm / w->h;
    w->dp_volume = d.dim == 2 ? d.dp * d.dp : d.dp * d.dp * d.dp;
    w->viscous_dt = (sps_real)INFINITY;
    sps__periodic_setup(w);
    sps__contact_rest(w);
    if (d.dim == 2 && d.gravity[2] != 0)
        sps__warn(w, "gravity[2] = %g m/s^2 in a 2D world: a 2D world has the axes x and y only, so it acts on nothing; set gravity[1] "
                  "(y up: -9.81) or dim = 3", (double)d.gravity[2]);
    *out = w;
    return SPS_OK;
}

/* Frees the arrays of field f in its owner (the world, or body b) and marks them NULL. */
static void sps__free_field(sps_world* w, sps__body* b, const sps__field_info* f) {
    int a;
    for (a = 0; a < sps__field_arrays(f); ++a) {
        void *array, *none = NULL;
        memcpy(&array, sps__field_slot(w, b, f, a), sizeof array);
        sps__free(w, array);
        memcpy(sps__field_slot(w, b, f, a), &none, sizeof none);
    }
}

static void sps__free_particle_fields(sps_world* w) {
    int k, bi;
    for (k = 0; k < SPS__NFIELDS; ++k)
        if (!sps__fields[k].per_body) sps__free_field(w, NULL, &sps__fields[k]);
        else
            for (bi = 0; bi < w->nbodies; ++bi) sps__free_field(w, &w->bodies[bi], &sps__fields[k]);
    sps__free(w, w->nb_group_start); sps__free(w, w->nb_first); sps__free(w, w->nb_j); sps__free(w, w->nb_count);
    sps__free(w, w->list_chunk);
    sps__free(w, w->nb_dw); sps__free(w, w->nb_inv_r);
    for (bi = 0; bi < w->nbodies; ++bi) {
        sps__free(w, w->bodies[bi].tl_pairs);
        sps__free(w, w->bodies[bi].tl_reverse);
        sps__free(w, w->bodies[bi].reference_slots);
    }
    sps__free(w, w->pair_force); sps__free(w, w->kept_force); sps__free(w, w->kept_neighbor_id);
    sps__free(w, w->kept_first); sps__free(w, w->kept_count);
    sps__free(w, w->cell_of); sps__free(w, w->cell_start); sps__free(w, w->perm);
    sps__free(w, w->scratch); sps__free(w, w->group_sum); sps__free(w, w->diag_scratch);
    sps__free(w, w->good); sps__free(w, w->good_id);
    sps__free(w, w->walls); sps__free(w, w->separate); sps__free(w, w->touch); sps__free(w, w->pair_friction); sps__free(w, w->sigma);
    sps__free(w, w->ct_first); sps__free(w, w->ct_j); sps__free(w, w->ct_cell); sps__free(w, w->ct_order);
    sps__free(w, w->ct_cell_start); sps__free(w, w->ct_cell_body);
}

SPSDEF void sps_world_destroy(sps_world* w) {
    int k;
    if (!w) return;
    sps__report_repeated_warnings(w);
    sps__free_particle_fields(w);
    sps__free(w, w->bodies);
    sps__free(w, w->constraints);
    for (k = 0; k < w->nzones; ++k) sps__free(w, w->zones[k].bins);
    sps__free(w, w->zones);
    sps__free(w, w->observers);
    sps__free(w, w->obs_ids);
    sps__free(w, w->obs_weights);
    w->def.allocator.free(w, w->def.allocator.user);
}

SPSDEF const sps_world_def* sps_world_get_def(const sps_world* w) { return w ? &w->def : NULL; }
SPSDEF const char* sps_world_last_error(const sps_world* w) {
    return w ? w->error : "world is NULL (sps_world_create failed? sps_world_def_check(&def, msg, size) lists every broken rule of its def)";
}
SPSDEF sps_real sps_world_time(const sps_world* w) { return w ? w->time : 0; }
SPSDEF long sps_world_substep_count(const sps_world* w) { return w ? w->acoustic_steps : 0; }
SPSDEF int sps_world_particle_count(const sps_world* w) { return w ? w->n : 0; }

/* >>bodies */

/* Body handle: low 16 bits index + 1, high 16 bits the world tag. */
static int sps__body_slot(const sps_world* w, sps_body b) {
    int idx = (int)(b.id & 0xffff) - 1;
    if (!w || (b.id >> 16) != w->tag || idx < 0 || idx >= w->nbodies) return -1;
    return idx;
}
SPSDEF int sps_body_is_valid(const sps_world* w, sps_body b) { return sps__body_slot(w, b) >= 0; }
SPSDEF int sps_body_index(const sps_world* w, sps_body b) { return sps__body_slot(w, b); }

static int sps__check_body(sps_world* w, sps_body b, const char* fn) {
    int k = sps__body_slot(w, b);
    if (k < 0) sps__set_error(w, 0, "%s: body handle %u is not a body of this world", fn, (unsigned)b.id);
    return k;
}

/* A body field set away from its default on a body that does not read it (sps__body_def_items'
   reads column): one warning naming each, so that a parameter is never ignored without a word. */
static void sps__warn_unread_fields(sps_world* w, const sps__body* b) {
    const sps_body_def defaults = sps_default_body_def();
    char list[512];
    size_t used = 0;
    int k;
    list[0] = 0;
    for (k = 0; k < SPS__BODY_DEF_ITEMS; ++k) {
        const sps__def_item* item = &sps__body_def_items[k];
        const double value = sps__def_value(&b->def, item);
        if (!item->reads || item->reads(&b->def) || value == sps__def_value(&defaults, item) || used + 2 >= sizeof list) continue;
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s = %g", used ? ", " : "", item->name, value);
        if (used >= sizeof list) used = sizeof list - 1; /* cut: the message ends where the buffer does */
    }
    if (used)
        sps__warn(w, "body '%s': %s set, which this body (%s, %s%s%s) does not read: no effect (MODELS AND FIELDS)", b->name, list,
                  b->model.material->name, b->def.solver == SPS_SOLVER_TOTAL_LAGRANGIAN ? "total Lagrangian" : "updated Lagrangian",
                  sps__reads_shear(&b->def) ? ", " : "", sps__reads_shear(&b->def) ? b->model.stabilisation->name : "");
}

SPSDEF sps_result sps_world_add_body(sps_world* w, const sps_body_def* def, sps_body* out) {
    char msg[768];
    sps__body* b;
    int k;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (out) out->id = 0;
    if (!def || !out) { sps__set_error(w, 0, "sps_world_add_body: def and out must not be NULL"); return SPS_ERR_INVALID_ARG; }
    msg[0] = 0;
    if (sps__body_def_check(w->dim, def, msg, sizeof msg) != SPS_OK) {
        sps__set_error(w, 0, "sps_world_add_body: %s", msg);
        return SPS_ERR_INVALID_ARG;
    }
    if (!sps__periodic_allows_body(w, def)) return SPS_ERR_INVALID_ARG;
    if (w->nbodies >= SPS__MAX_BODIES) { sps__set_error(w, 0, "sps_world_add_body: at most %d bodies", SPS__MAX_BODIES); return SPS_ERR_INVALID_ARG; }
    if (w->nbodies == w->bodies_cap) {
        int nc = w->bodies_cap ? 2 * w->bodies_cap : 4;
        if (!sps__grow(w, &w->bodies, sizeof *w->bodies, (size_t)w->nbodies, (size_t)nc)) return sps__oom(w, "sps_world_add_body: the body table");
        w->bodies_cap = nc;
    }
    b = &w->bodies[w->nbodies];
    memset(b, 0, sizeof *b);
    b->def = *def;
    snprintf(b->name, sizeof b->name, "%s", def->name ? def->name : "body");
    b->def.name = b->name;
    b->model = sps__resolve_model(w, def);
    b->model.pass = sps__choose_passes(w, &b->model);
    if (sps__missing_pass(&b->model, &b->model.pass, msg, sizeof msg)) {
        sps__set_error(w, 0, "sps_world_add_body: body '%s': %s", b->name, msg);
        return SPS_ERR_INVALID_ARG;
    }
    if (def->transport != SPS_TRANSPORT_NONE && def->transport_carries_velocity && !b->model.gradient) {
        sps__set_error(w, 0, "sps_world_add_body: body '%s': transport_carries_velocity = 1 without a velocity gradient to carry the "
                       "velocity by (a fluid under gravity has none: FLUIDS), allowed 0", b->name);
        return SPS_ERR_INVALID_ARG;
    }
    if (b->model.paired && w->nzones > 0) { /* >>open boundaries renumbers the ids its kept pair forces go by */
        sps__set_error(w, 0, "sps_world_add_body: body '%s': rotation = SPS_ROTATION_PAIR in a world with open-boundary zones, allowed "
                       "the mean or per-particle rotation (the pair forces are kept by particle id, which zones renumber)", b->name);
        return SPS_ERR_INVALID_ARG;
    }
    b->rho0 = def->material.density;
    b->mat = sps__material_constants_of(&def->material);
    b->zeta = def->zeta > 0 ? def->zeta : SPS_R(0.7) * w->dim + SPS_R(2.1); /* ENO section 4 */
    b->z_riemann = b->rho0 * b->mat.c0;
    b->xi = def->xi > 0 ? def->xi : 2; /* ANG section 5: xi_G = 2 */
    b->oas_eps = def->oas_epsilon;
    for (k = 0; k < SPS__OAS_MAX_EXPONENT; ++k) b->oas_factor[k] = (sps_real)(k < (int)def->oas_exponent);
    b->oas_w_dp = sps_world_kernel(w, w->def.dp);
    b->transport_alpha = def->transport_coefficient > 0 ? def->transport_coefficient : SPS_R(0.2); /* UTVF section 3.2 */
    b->limiter_eta_c0 = (b->model.material->limiter + b->model.material->limiter_per_dim * w->dim) / b->mat.c0;
    b->density_diffusion = 1;
    b->hexagonal = def->lattice == SPS_LATTICE_HEXAGONAL || (def->lattice == SPS_LATTICE_AUTO && sps__kind_fills_hexagonal(w, def));
    sps__material_setup(w, b);
    b->mean_rotation[0] = b->mean_rotation[4] = b->mean_rotation[8] = 1;
    b->driven = b->model.material->kinematic && !b->model.free_rigid && sps__watchdog_on(w);
    w->free_rigid_bodies += b->model.free_rigid;
    /* wall bodies: no waves; a free rigid body: its contact stiffness sqrt(K / rho0) */
    if ((!b->model.material->kinematic || b->model.free_rigid) && b->mat.c0 > w->c0_max) w->c0_max = b->mat.c0;
    if (sps__viscous_dt(w, b) < w->viscous_dt) w->viscous_dt = sps__viscous_dt(w, b);
    if (b->model.viscous == SPS__VISCOUS_NEWTON && def->material.viscosity / (b->rho0 * w->h) > w->viscous_speed)
        w->viscous_speed = def->material.viscosity / (b->rho0 * w->h);
    if (!b->model.material->kinematic && w->def.cfl_acoustic > b->model.stabilisation->stable_cfl[w->dim - 2])
        sps__warn(w, "body '%s': cfl_acoustic = %g is above %g, the largest value measured stable for %s in %dD (bench/VALIDATION.md, "
                  "stability map): the run may blow up, which the energy watchdog reports", b->name, (double)w->def.cfl_acoustic,
                  (double)b->model.stabilisation->stable_cfl[w->dim - 2], b->model.stabilisation->name, w->dim);
    sps__material_warnings(w, b);
    if (def->material.poisson_ratio > SPS_R(0.499)) { /* nearly incompressible: say what it costs */
        sps_material_def ref = def->material;
        ref.poisson_ratio = SPS_R(0.3);
        sps__warn(w, "body '%s': material.poisson_ratio = %g is within 1e-3 of 0.5: the sound speed, %g m/s, is %.3g times that at "
                  "nu = 0.3, and the time step as many times shorter", b->name, (double)def->material.poisson_ratio, (double)b->mat.c0,
                  (double)(b->mat.c0 / sps__material_constants_of(&ref).c0));
    }
    sps__warn_unread_fields(w, b);
    if (def->friction > SPS__MU_MAX_REAL) {
        char field[96];
        snprintf(field, sizeof field, "body '%.60s': friction", b->name);
        sps__warn_friction(w, field, def->friction);
    }
    w->contact_dirty = 1;
    out->id = ((uint32_t)w->tag << 16) | (uint32_t)(w->nbodies + 1);
    w->nbodies++;
    return SPS_OK;
}

SPSDEF sps_result sps_body_material_constants(const sps_world* w, sps_body b, sps_real* c0, sps_real* G, sps_real* K) {
    int k = sps__body_slot(w, b);
    if (!w) return SPS_ERR_INVALID_ARG;
    if (k < 0) { sps__set_error_const(w, "sps_body_material_constants: body handle %u is not a body of this world", (unsigned)b.id); return SPS_ERR_INVALID_ARG; }
    if (c0) *c0 = w->bodies[k].mat.c0;
    if (G) *G = w->bodies[k].mat.G;
    if (K) *K = w->bodies[k].mat.K;
    return SPS_OK;
}

/* >>particles */

/* Makes room for at least need particles in every world array needed always (and the
   constraint index once it exists); the bodies' arrays follow at the next commit. */
static sps_result sps__reserve(sps_world* w, int need) {
    int k, a, nc;
    size_t o = (size_t)w->n, m;
    if (need <= w->cap) return SPS_OK;
    nc = w->cap ? w->cap + w->cap / 2 : 256;
    if (nc < need) nc = need;
    m = (size_t)nc + SPS__LANES; /* + the zeroed lane padding */
    for (k = 0; k < SPS__NFIELDS; ++k) {
        const sps__field_info* f = &sps__fields[k];
        if (!sps__world_field_allocated(w, f)) continue;
        for (a = 0; a < sps__field_arrays(f); ++a)
            if (!sps__grow(w, sps__field_slot(w, NULL, f, a), sps__field_bytes(f), o, m)) return SPS_ERR_OUT_OF_MEMORY;
    }
    w->cap = nc;
    return SPS_OK;
}

/* Trims the particle arrays to the particles (or to what sps_world_reserve asked for) at a commit
   before the first step: adding particles grows them by half when full (sps__reserve), room
   that a scene built before it steps would carry to the end (a cube of 1e6 particles had room
   for 1.28e6). Not in a world with open-boundary zones, whose particles fill the room as it
   runs, nor after the first step (particles added between steps keep the growth by half).
   Only when more than an eighth is empty. SPS_ERR_OUT_OF_MEMORY when an array could not be
   reallocated: it keeps its size (larger), the others are trimmed, and the next call goes on. */
static sps_result sps__trim_particle_arrays(sps_world* w) {
    const int room = w->n > w->reserved ? w->n : w->reserved;
    int k, a;
    if (w->nzones || w->acoustic_steps > 0 || w->cap - room <= room / 8) return SPS_OK;
    w->cap = room;
    for (k = 0; k < SPS__NFIELDS; ++k) {
        const sps__field_info* f = &sps__fields[k];
        if (!sps__world_field_allocated(w, f)) continue;
        for (a = 0; a < sps__field_arrays(f); ++a)
            if (!sps__grow(w, sps__field_slot(w, NULL, f, a), sps__field_bytes(f), (size_t)w->n, (size_t)room + SPS__LANES))
                return SPS_ERR_OUT_OF_MEMORY;
    }
    return SPS_OK;
}

static sps_result sps__add_one(sps_world* w, int body, const sps_real x[3], sps_real volume) {
    int i = w->n, a;
    sps__body* b = &w->bodies[body];
    sps_result r = sps__reserve(w, w->n + 1);
    if (r != SPS_OK) return sps__oom(w, "the particle arrays");
    for (a = 0; a < 3; ++a) {
        sps_real xa = a < w->dim ? x[a] : 0;
        w->pos[a][i] = xa; w->ref[a][i] = xa;
        w->vel[a][i] = 0; w->acc_p[a][i] = 0; w->acc_s[a][i] = 0;
    }
    w->rho[i] = b->rho0; w->drho[i] = 0; w->p[i] = 0;
    w->mass[i] = b->rho0 * volume; w->vol[i] = volume;
    w->id[i] = i; w->slot_of_id[i] = i; w->body[i] = body;
    if (w->cons) w->cons[i] = -1;
    if (w->zone) { /* not in a zone (sps__zone_hold puts it in one) */
        w->zone[i] = -1;
        for (a = 0; a < 3; ++a) w->zone_vel[a][i] = 0;
    }
    for (a = 0; a < w->dim; ++a) sps__watch_adjust(w, body, 0, -w->mass[i] * w->def.gravity[a] * w->pos[a][i]);
    b->count++;
    w->n++;
    w->needs_sort_by_body = 1;
    sps__world_changed(w);
    return SPS_OK;
}

static int sps__check_box(sps_world* w, const char* fn, const sps_real lo[3], const sps_real hi[3]) {
    int a;
    if (!lo || !hi) { sps__set_error(w, 0, "%s: lo and hi must not be NULL", fn); return 0; }
    for (a = 0; a < w->dim; ++a)
        if (!sps__finite(lo[a]) || !sps__finite(hi[a]) || !(lo[a] < hi[a])) {
            sps__set_error(w, 0, "%s: box axis %d is [%g, %g), allowed finite with lo < hi", fn, a, (double)lo[a], (double)hi[a]);
            return 0;
        }
    return 1;
}

/* The warning of a fill that added no particle (a box thinner than dp, or an sdf < 0 nowhere). */
static void sps__warn_empty_fill(const sps_world* w, const char* fn, sps_body b, int with_sdf) {
    sps__warn(w, "%s: no lattice point of spacing dp = %g lies in the box%s: body '%s' got no particle", fn, (double)w->def.dp,
              with_sdf ? " where sdf < 0" : "", w->bodies[sps__body_slot(w, b)].name);
}

/* A free rigid body takes its particles' reference frame at its first step (sps__rigid_setup):
   particles added after it would reset its turn, so the fills refuse them. */
static int sps__rigid_fill_closed(sps_world* w, int k, const char* fn) {
    if (!w->bodies[k].model.free_rigid || !w->bodies[k].rigid.ready) return 0;
    sps__set_error(w, 0, "%s: body '%s' is a free rigid body that has stepped (its particles set its mass, inertia and frame at the "
                   "first step); add all of its particles before the first step, or add another body", fn, w->bodies[k].name);
    return 1;
}

/* Adds the lattice point x of volume `volume` to body k if it lies inside sdf (NULL: the box). */
static sps_result sps__fill_point(sps_world* w, int k, const sps_real x[3], sps_real volume, sps_real (*sdf)(const sps_real x[3], void* user),
                                  void* user, int* total) {
    sps_result r;
    if (sdf && !(sdf(x, user) < 0)) return SPS_OK;
    if ((r = sps__add_one(w, k, x, volume)) != SPS_OK) return r;
    ++*total;
    return SPS_OK;
}

/* The square lattice's points lo + (i + 1/2) dp per axis, cnt[a] along axis a. */
static sps_result sps__fill_square(sps_world* w, int k, const sps_real lo[3], const int cnt[3], sps_real (*sdf)(const sps_real x[3], void* user),
                                   void* user, int* total) {
    const sps_real dp = w->def.dp;
    int i, j, l;
    sps_result r;
    for (l = 0; l < cnt[2]; ++l)
        for (j = 0; j < cnt[1]; ++j)
            for (i = 0; i < cnt[0]; ++i) {
                sps_real x[3];
                x[0] = lo[0] + (i + SPS_R(0.5)) * dp;
                x[1] = lo[1] + (j + SPS_R(0.5)) * dp;
                x[2] = w->dim == 3 ? lo[2] + (l + SPS_R(0.5)) * dp : 0;
                if ((r = sps__fill_point(w, k, x, w->dp_volume, sdf, user, total)) != SPS_OK) return r;
            }
    return SPS_OK;
}

/* The hexagonal lattice of the box (2D; sps_lattice): `columns` along x at the spacing ax =
   width / columns, `rows` along y at ay = height / rows, each particle of volume ax ay (dp^2 to
   the rounding of the counts). Even rows at lo + (c + 1/2) ax; odd rows at lo + c ax, 0 < c <
   columns, and where that puts a particle on the box's x faces, a half particle (ax ay / 2) a
   quarter spacing inside each, so the rows tile the box and no particle stands on a wall there.
   A box that spans a periodic x axis has whole odd rows, lo + c ax for c < columns (the period
   wraps them). */
static sps_result sps__fill_hexagonal(sps_world* w, int k, const sps_real lo[3], const sps_real hi[3], int columns, int rows,
                                      sps_real (*sdf)(const sps_real x[3], void* user), void* user, int* total) {
    const sps_real ax = (hi[0] - lo[0]) / columns, ay = (hi[1] - lo[1]) / rows, volume = ax * ay;
    const int wraps = w->period[0] > 0 && SPS__FABS(hi[0] - lo[0] - w->period[0]) < SPS_R(1e-6) * w->def.dp;
    int c, j;
    sps_result r;
    for (j = 0; j < rows; ++j) {
        sps_real x[3] = {0, 0, 0};
        x[1] = lo[1] + (j + SPS_R(0.5)) * ay;
        for (c = 0; c < columns; ++c) {
            if (j % 2 && c == 0 && !wraps) continue; /* the half particles below */
            x[0] = j % 2 ? lo[0] + c * ax : lo[0] + (c + SPS_R(0.5)) * ax;
            if ((r = sps__fill_point(w, k, x, volume, sdf, user, total)) != SPS_OK) return r;
        }
        if (j % 2 == 0 || wraps) continue;
        x[0] = lo[0] + SPS_R(0.25) * ax;
        if ((r = sps__fill_point(w, k, x, SPS_R(0.5) * volume, sdf, user, total)) != SPS_OK) return r;
        x[0] = hi[0] - SPS_R(0.25) * ax;
        if ((r = sps__fill_point(w, k, x, SPS_R(0.5) * volume, sdf, user, total)) != SPS_OK) return r;
    }
    return SPS_OK;
}

/* The hexagonal lattice's counts for the box: the spacing along a row dp sqrt(2 / sqrt 3) (a
   regular lattice of dp^2 a particle) rounded to fill the width, then the rows to keep dp^2 a
   particle (an even count where y is periodic and the box spans it, so the rows' shifts wrap). */
static void sps__hexagonal_counts(const sps_world* w, const sps_real lo[3], const sps_real hi[3], double* columns, double* rows) {
    const double dp = (double)w->def.dp, width = (double)(hi[0] - lo[0]), height = (double)(hi[1] - lo[1]);
    const int wraps_y = w->period[1] > 0 && fabs(height - (double)w->period[1]) < 1e-6 * dp;
    *columns = floor(width / (dp * sqrt(2 / sqrt(3.0))) + 0.5);
    if (*columns < 1) *columns = width >= dp ? 1 : 0;
    *rows = *columns > 0 ? floor(height * (width / *columns) / (dp * dp) + 0.5) : 0;
    if (wraps_y) *rows = 2 * floor(*rows / 2 + 0.5);
    if (*rows < 1) *rows = height >= dp ? 1 : 0;
}

static sps_result sps__fill(sps_world* w, const char* fn, sps_body b, const sps_real lo[3], const sps_real hi[3],
                            sps_real (*sdf)(const sps_real x[3], void* user), void* user, int* added) {
    int k, cnt[3] = {1, 1, 1}, a, total = 0;
    double cells = 1, columns = 0, rows = 0;
    sps_real dp;
    sps_result r;
    if (added) *added = 0;
    if (!w) return SPS_ERR_INVALID_ARG;
    if ((k = sps__check_body(w, b, fn)) < 0 || !sps__check_box(w, fn, lo, hi) || sps__rigid_fill_closed(w, k, fn)) return SPS_ERR_INVALID_ARG;
    dp = w->def.dp;
    if (w->bodies[k].hexagonal) {
        sps__hexagonal_counts(w, lo, hi, &columns, &rows);
        cells = (columns + 1) * rows;
    } else
        for (a = 0; a < w->dim; ++a) {
            /* count lattice points inside [lo, hi); the slack absorbs the rounding of lo, hi and dp,
               relative 1e-7 in float: 1e-6 dp lost a whole column of a 204-dp plate there */
            double c = SPS__FLOOR((hi[a] - lo[a]) / dp + (sizeof(sps_real) == sizeof(float) ? SPS_R(1e-3) : SPS_R(1e-6)));
            cells *= c;
            cnt[a] = (int)(c < 1e9 ? c : 1e9);
        }
    if (!(cells >= 1)) { /* no lattice point along an axis (and 0 x inf is NaN) */
        sps__warn_empty_fill(w, fn, b, sdf != NULL);
        return SPS_OK;
    }
    if (cells > (double)(SPS__MAX_PARTICLES - w->n)) {
        sps__set_error(w, 0, "%s: box holds %.3g lattice points, the world %d particles; allowed a total of %d", fn, cells, w->n, SPS__MAX_PARTICLES);
        return SPS_ERR_INVALID_ARG;
    }
    r = w->bodies[k].hexagonal ? sps__fill_hexagonal(w, k, lo, hi, (int)columns, (int)rows, sdf, user, &total)
                               : sps__fill_square(w, k, lo, cnt, sdf, user, &total);
    if (r != SPS_OK) return r;
    if (added) *added = total;
    if (total == 0) sps__warn_empty_fill(w, fn, b, sdf != NULL);
    return SPS_OK;
}

SPSDEF sps_result sps_body_add_box(sps_world* w, sps_body b, const sps_real lo[3], const sps_real hi[3], int* added) {
    return sps__fill(w, "sps_body_add_box", b, lo, hi, NULL, NULL, added);
}

SPSDEF sps_result sps_body_add_sdf(sps_world* w, sps_body b, const sps_real lo[3], const sps_real hi[3],
                                   sps_real (*sdf)(const sps_real x[3], void* user), void* user, int* added) {
    if (!sdf && w) { sps__set_error(w, 0, "sps_body_add_sdf: sdf must not be NULL"); return SPS_ERR_INVALID_ARG; }
    return sps__fill(w, "sps_body_add_sdf", b, lo, hi, sdf, user, added);
}

SPSDEF sps_result sps_body_add_particles(sps_world* w, sps_body b, int n, const sps_real* xyz, const sps_real* vol) {
    int k, i, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    if ((k = sps__check_body(w, b, "sps_body_add_particles")) < 0 || sps__rigid_fill_closed(w, k, "sps_body_add_particles")) return SPS_ERR_INVALID_ARG;
    if (n < 0 || n > SPS__MAX_PARTICLES - w->n || (n > 0 && !xyz)) {
        sps__set_error(w, 0, "sps_body_add_particles: n = %d with xyz %s, allowed 0 <= n <= %d (the world has %d) and xyz != NULL",
                       n, xyz ? "set" : "NULL", SPS__MAX_PARTICLES - w->n, w->n);
        return SPS_ERR_INVALID_ARG;
    }
    for (i = 0; i < n; ++i) {
        for (a = 0; a < w->dim; ++a)
            if (!sps__finite(xyz[3 * i + a])) { sps__set_error(w, 0, "sps_body_add_particles: xyz[%d] = %g, allowed finite", 3 * i + a, (double)xyz[3 * i + a]); return SPS_ERR_INVALID_ARG; }
        if (vol && !(vol[i] > 0 && sps__finite(vol[i]))) { sps__set_error(w, 0, "sps_body_add_particles: vol[%d] = %g, allowed finite > 0", i, (double)vol[i]); return SPS_ERR_INVALID_ARG; }
    }
    for (i = 0; i < n; ++i) {
        sps_result r = sps__add_one(w, k, xyz + 3 * i, vol ? vol[i] : w->dp_volume);
        if (r != SPS_OK) return r;
    }
    return SPS_OK;
}

/* A velocity set on a body before its particles are added would be lost silently (the fill
   starts them at rest): say so instead. */
static int sps__body_is_empty(sps_world* w, int k, const char* fn) {
    int i;
    for (i = 0; i < w->n; ++i)
        if (w->body[i] == k) return 0;
    sps__set_error(w, 0, "%s: body '%s' has no particles yet: add them first (sps_body_add_box, _sdf, _particles), then set its "
                   "velocity", fn, w->bodies[k].name);
    return 1;
}

static void sps__rigid_take_velocities(sps_world* w, sps__body* b); /* >>material: free rigid bodies */
SPSDEF sps_result sps_body_set_velocity(sps_world* w, sps_body b, sps_velocity_fn fn, void* user) {
    int k, i, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if ((k = sps__check_body(w, b, "sps_body_set_velocity")) < 0) return SPS_ERR_INVALID_ARG;
    if (!fn) { sps__set_error(w, 0, "sps_body_set_velocity: fn must not be NULL"); return SPS_ERR_INVALID_ARG; }
    if (sps__body_is_empty(w, k, "sps_body_set_velocity")) return SPS_ERR_STATE;
    for (i = 0; i < w->n; ++i) {
        sps_real x[3], v[3] = {0, 0, 0}, before;
        if (w->body[i] != k) continue;
        for (a = 0; a < 3; ++a) x[a] = w->ref[a][i];
        fn(x, v, user);
        for (a = 0; a < w->dim; ++a)
            if (!sps__finite(v[a])) { sps__set_error(w, 0, "sps_body_set_velocity: velocity component %d = %g at particle %d, allowed finite", a, (double)v[a], w->id[i]); return SPS_ERR_INVALID_ARG; }
        before = sps__kinetic(w, i);
        for (a = 0; a < w->dim; ++a) w->vel[a][i] = v[a];
        sps__watch_adjust(w, k, sps__kinetic(w, i) - before, 0);
    }
    if (w->bodies[k].model.free_rigid && w->bodies[k].rigid.ready) sps__rigid_take_velocities(w, &w->bodies[k]); /* its rigid part */
    return SPS_OK;
}

SPSDEF sps_result sps_body_set_rigid_motion(sps_world* w, sps_body b, const sps_real velocity[3], const sps_real omega[3]) {
    sps_real centre[3] = {0, 0, 0}, mass = 0;
    int k, i, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if ((k = sps__check_body(w, b, "sps_body_set_rigid_motion")) < 0) return SPS_ERR_INVALID_ARG;
    if (!velocity || !omega) { sps__set_error(w, 0, "sps_body_set_rigid_motion: velocity and omega must not be NULL"); return SPS_ERR_INVALID_ARG; }
    for (a = 0; a < 3; ++a)
        if (!sps__finite(velocity[a]) || !sps__finite(omega[a])) {
            sps__set_error(w, 0, "sps_body_set_rigid_motion: velocity[%d] = %g, omega[%d] = %g, allowed finite", a, (double)velocity[a], a,
                           (double)omega[a]);
            return SPS_ERR_INVALID_ARG;
        }
    if (sps__body_is_empty(w, k, "sps_body_set_rigid_motion")) return SPS_ERR_STATE;
    for (i = 0; i < w->n; ++i) /* the current centre of mass, in particle order (deterministic) */
        if (w->body[i] == k) {
            for (a = 0; a < w->dim; ++a) centre[a] += w->mass[i] * w->pos[a][i];
            mass += w->mass[i];
        }
    for (a = 0; a < w->dim; ++a) centre[a] /= mass;
    for (i = 0; i < w->n; ++i) {
        sps_real r[3] = {0, 0, 0}, before;
        if (w->body[i] != k) continue;
        for (a = 0; a < w->dim; ++a) r[a] = w->pos[a][i] - centre[a];
        before = sps__kinetic(w, i);
        /* v + omega x r; in 2D only omega_z turns the plane */
        w->vel[0][i] = velocity[0] + omega[1] * r[2] - omega[2] * r[1];
        w->vel[1][i] = velocity[1] + omega[2] * r[0] - omega[0] * r[2];
        if (w->dim == 3) w->vel[2][i] = velocity[2] + omega[0] * r[1] - omega[1] * r[0];
        sps__watch_adjust(w, k, sps__kinetic(w, i) - before, 0);
    }
    if (w->bodies[k].model.free_rigid && w->bodies[k].rigid.ready) sps__rigid_take_velocities(w, &w->bodies[k]);
    return SPS_OK;
}

SPSDEF sps_result sps_body_set_pressure(sps_world* w, sps_body b, sps_pressure_fn fn, void* user) {
    const sps__body* body;
    int k, i, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if ((k = sps__check_body(w, b, "sps_body_set_pressure")) < 0) return SPS_ERR_INVALID_ARG;
    if (!fn) { sps__set_error(w, 0, "sps_body_set_pressure: fn must not be NULL"); return SPS_ERR_INVALID_ARG; }
    body = &w->bodies[k];
    if (body->model.material->kinematic) {
        sps__set_error(w, 0, "sps_body_set_pressure: body '%s' is a wall body (material.kind = rigid): it has no pressure", body->name);
        return SPS_ERR_INVALID_ARG;
    }
    for (i = 0; i < w->n; ++i) {
        sps_real x[3], p, before;
        if (w->body[i] != k) continue;
        for (a = 0; a < 3; ++a) x[a] = w->ref[a][i];
        p = fn(x, user);
        if (!sps__finite(p) || !(p > -body->mat.K)) {
            sps__set_error(w, 0, "sps_body_set_pressure: pressure = %g Pa at particle %d, allowed finite and > -rho0 c0^2 = %g Pa (a positive density)",
                           (double)p, w->id[i], (double)-body->mat.K);
            return SPS_ERR_INVALID_ARG;
        }
        before = w->vol[i] * sps__material_energy_density(body->def.material.kind, &body->mat, 0, w->p[i]);
        w->p[i] = p;
        w->rho[i] = body->rho0 + p / (body->mat.c0 * body->mat.c0);
        w->vol[i] = w->mass[i] / w->rho[i];
        sps__watch_adjust(w, k, w->vol[i] * sps__material_energy_density(body->def.material.kind, &body->mat, 0, p) - before, 0);
    }
    return SPS_OK;
}

static sps_result sps__ready_to_step(sps_world* w);
SPSDEF sps_result sps_body_set_geostatic_stress(sps_world* w, sps_body b, sps_real surface_height, sps_real k0) {
    const sps_real* g = w ? w->def.gravity : NULL;
    const sps_real g_norm = g ? SPS__SQRT(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]) : 0;
    sps__body* body;
    sps_result r;
    int k, i, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if ((k = sps__check_body(w, b, "sps_body_set_geostatic_stress")) < 0) return SPS_ERR_INVALID_ARG;
    body = &w->bodies[k];
    if (body->model.pressure_of_density) { /* its whole stress is integrated: the granular kinds */
        sps__set_error(w, 0, "sps_body_set_geostatic_stress: body '%s' has material.kind = %d, allowed 6 (Drucker-Prager)", body->name,
                       (int)body->def.material.kind);
        return SPS_ERR_INVALID_ARG;
    }
    if (!(g_norm > 0) || !sps__finite(g_norm)) {
        sps__set_error(w, 0, "sps_body_set_geostatic_stress: world gravity = (%g, %g, %g) m/s^2, allowed finite and not zero", (double)g[0],
                       (double)g[1], (double)g[2]);
        return SPS_ERR_INVALID_ARG;
    }
    if (!sps__finite(surface_height) || !(k0 >= 0 && k0 <= 10)) {
        sps__set_error(w, 0, "sps_body_set_geostatic_stress: surface_height = %g m, allowed finite; k0 = %g, allowed [0, 10] (0: 1 - sin(phi))",
                       (double)surface_height, (double)k0);
        return SPS_ERR_INVALID_ARG;
    }
    if ((r = sps__ready_to_step(w)) != SPS_OK) return r;
    body = &w->bodies[k]; /* the sort by body may have moved its range */
    if (k0 == 0) k0 = body->cone.k0;
    for (i = body->begin; i < body->end; ++i) {
        sps_real height = 0, before, sigma[6], vertical_stress;
        sps_real* tau = body->tau + (size_t)6 * (i - body->begin);
        for (a = 0; a < w->dim; ++a) height -= g[a] / g_norm * w->ref[a][i];
        vertical_stress = -body->rho0 * g_norm * (surface_height > height ? surface_height - height : 0);
        for (a = 0; a < 6; ++a) /* sigma_h I + (sigma_v - sigma_h) g^ g^, sigma_h = k0 sigma_v */
            sigma[a] = k0 * vertical_stress * sps__sym_diagonal(a) +
                       (1 - k0) * vertical_stress * g[sps__sym_row[a]] * g[sps__sym_col[a]] / (g_norm * g_norm);
        before = w->vol[i] * sps__material_energy_density(body->def.material.kind, &body->mat, sps__sym_contract(tau, tau), w->p[i]);
        w->p[i] = -sps__sym_deviator(sigma, tau) / 3; /* tau: the deviator */
        w->rho[i] = body->rho0 + w->p[i] / (body->mat.c0 * body->mat.c0); /* its density follows its pressure (GRANULAR) */
        w->vol[i] = w->mass[i] / w->rho[i];
        sps__watch_adjust(w, k, w->vol[i] * sps__material_energy_density(body->def.material.kind, &body->mat, sps__sym_contract(tau, tau), w->p[i]) - before, 0);
    }
    return SPS_OK;
}

SPSDEF sps_result sps_body_set_acceleration(sps_world* w, sps_body b, sps_acceleration_fn fn, void* user) {
    int k;
    if (!w) return SPS_ERR_INVALID_ARG;
    if ((k = sps__check_body(w, b, "sps_body_set_acceleration")) < 0) return SPS_ERR_INVALID_ARG;
    if (fn && w->bodies[k].model.material->kinematic && !w->bodies[k].model.free_rigid) {
        sps__set_error(w, 0, "sps_body_set_acceleration: body '%s' is a wall body (material.kind = rigid): its particles keep the velocity given to them",
                       w->bodies[k].name);
        return SPS_ERR_INVALID_ARG;
    }
    w->bodies[k].acceleration = fn;
    w->bodies[k].acceleration_user = fn ? user : NULL;
    if (fn && sps__watchdog_on(w) && !w->bodies[k].driven) { /* its work enters the energy account */
        w->bodies[k].driven = 1;
        w->needs_sort_by_body = 1; /* the next step's commit allocates its prescribed_work */
    }
    return SPS_OK;
}

SPSDEF sps_result sps_body_constrain_box(sps_world* w, sps_body b, const sps_real lo[3], const sps_real hi[3],
                                         unsigned mask, const sps_real velocity[3], int* count) {
    int k, i, a, c = 0;
    sps__constraint con;
    if (count) *count = 0;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if ((k = sps__check_body(w, b, "sps_body_constrain_box")) < 0 || !sps__check_box(w, "sps_body_constrain_box", lo, hi)) return SPS_ERR_INVALID_ARG;
    if (mask == 0 || mask > SPS_AXIS_ALL) { sps__set_error(w, 0, "sps_body_constrain_box: mask = %u, allowed 1..7 (SPS_AXIS_X|Y|Z)", mask); return SPS_ERR_INVALID_ARG; }
    if (w->bodies[k].model.free_rigid) { /* its particles move with the body: a held particle would be ignored */
        sps__set_error(w, 0, "sps_body_constrain_box: body '%s' is a free rigid body (material.kind = %d), whose particles move as one; "
                       "hold it with sps_body_lock_axes, or make it a wall body (SPS_MATERIAL_RIGID) for a prescribed motion",
                       w->bodies[k].name, (int)w->bodies[k].def.material.kind);
        return SPS_ERR_INVALID_ARG;
    }
    con.mask = mask;
    for (a = 0; a < 3; ++a) {
        con.velocity[a] = velocity ? velocity[a] : 0;
        if (!sps__finite(con.velocity[a])) { sps__set_error(w, 0, "sps_body_constrain_box: velocity[%d] = %g, allowed finite", a, (double)con.velocity[a]); return SPS_ERR_INVALID_ARG; }
    }
    if (!w->cons) {
        w->cons = (int*)sps__alloc(w, sizeof(int) * (size_t)(w->cap ? w->cap : 1));
        if (!w->cons) return sps__oom(w, "sps_body_constrain_box: the constraint index");
        for (i = 0; i < w->n; ++i) w->cons[i] = -1;
    }
    if (!sps__grow(w, &w->constraints, sizeof con, (size_t)w->ncons, (size_t)w->ncons + 1)) return sps__oom(w, "sps_body_constrain_box: the constraint table");
    w->constraints[w->ncons] = con;
    for (i = 0; i < w->n; ++i) {
        int inside = w->body[i] == k;
        for (a = 0; a < w->dim && inside; ++a) inside = w->ref[a][i] >= lo[a] && w->ref[a][i] <= hi[a];
        if (!inside) continue;
        sps_real before = sps__kinetic(w, i);
        w->cons[i] = w->ncons;
        for (a = 0; a < w->dim; ++a)
            if (mask & (1u << a)) w->vel[a][i] = con.velocity[a];
        sps__watch_adjust(w, k, sps__kinetic(w, i) - before, 0);
        ++c;
    }
    w->ncons++;
    for (a = 0; a < w->dim && c > 0 && sps__watchdog_on(w) && !w->bodies[k].driven; ++a)
        if ((mask & (1u << a)) && con.velocity[a] != 0) { /* a moving constraint does work: count it */
            w->bodies[k].driven = 1;
            w->needs_sort_by_body = 1; /* the next step's commit allocates its prescribed_work */
        }
    if (c == 0)
        sps__warn(w, "sps_body_constrain_box: no particle of body '%s' has its reference position in the box: nothing is constrained",
                  w->bodies[k].name);
    if (count) *count = c;
    return SPS_OK;
}

/* >>fill: body-fitted particles (sps_body_add_sdf_relaxed)

   The lattice fill of sps_body_add_sdf gives curved bodies staircase surfaces. Following the
   level-set based pre-processing of Yu, Zhu, Zhang, Haidn & Hu (Comput. Phys. Commun. 289 (2023)
   108744; ENO ref. [55], used for the rings and balls of ENO sections 6.3-6.8), the lattice
   particles are relaxed inside the shape:
   1. Lattice: x = lo + (i + 1/2) dp per axis where phi(x) < 0 (the points of sps_body_add_sdf),
      with phi(x) = max(sdf(x), box(x)), box(x) = max_a max(lo_a - x_a, x_a - hi_a): the body is
      the shape cut by the box, as for the lattice fill.
   2. Shifting (the particle-shifting / transport-velocity form, Lind et al. 2012; Adami, Hu &
      Adams 2013; Yu et al. 2023 eq. for the relaxation "acceleration" -2 p0 sum grad W V): every
      iteration moves every particle (Jacobi: all shifts from the old positions) by
          dx_i = -alpha h^2 G_i,       G_i = sum_j grad_i W_ij V_j + S_i,       alpha = 0.3,
      grad_i W_ij = dW/dr(r_ij) (x_i - x_j)/r_ij, V_j = dp^d, |dx_i| capped at 0.2 dp. Our
      change: below the distance of its peak (h/2 for Wendland C2) dW/dr is held at the peak,
      since the kernel's repulsion vanishes as r -> 0 and pressed pairs (sharp corners, parts
      thinner than 2 dp) would merge and stay merged; coincident points split along x.
      G_i is the gradient of the particle number density sum_j W_ij V_j; it vanishes for a
      uniform distribution with full support, so the shift drives particles towards one.
   3. The surface: the neighbours missing beyond the surface are represented by the surface
      itself (the level-set "kernel gradient integral" of Yu et al., here for a locally flat
      surface): a uniform continuum filling phi > 0 would add
          S_i = integral_{phi > 0} grad_i W(x_i - y) dy = n_i Wp(d_i),
          Wp(z) = integral over the plane at distance z of W   (2D: 2 int_0^sqrt(4h^2 - z^2)
                  W(sqrt(z^2 + s^2)) ds; 3D: 2 pi int_z^2h W(r) r dr; tabulated once),
      with d_i = -phi(x_i) (the depth; phi must be a signed distance near the surface) and n_i
      the outward normal grad phi / |grad phi| (central differences, step dp/10). S_i pushes a
      particle closer than about dp/2 to the surface back in; the rows inside (at dp/2, 3dp/2, ...
      deep) balance it when the outer row lies dp/2 inside, so the outer layer settles on a
      smooth surface dp/2 inside the shape (the particle volumes then tile the shape).
   4. Bounding (Yu et al.'s "surface bounding", as in SPHinXsys' ShapeSurfaceBounding): after
      each move, a particle closer than dp/2 to the surface (phi > -dp/2; this includes any that
      crossed it) is projected along the gradient onto the layer phi = -dp/2:
      x -= (phi + dp/2) grad phi / |grad phi|^2 (a Newton step; two at most).
   alpha = 0.3 is 2.5x below the measured stability limit (~0.8: the shift then overshoots and
   the particles jitter at the 0.2 dp cap); convergence is diffusive (long waves need ~(L/h)^2
   iterations), 300 iterations by default.
   The number of particles is the lattice's (no particle is added or removed). Cost O(N) per
   iteration (a cell list of cell size 2h, rebuilt every iteration), O(N) sdf calls per
   iteration plus 2 d per particle within 2h of the surface. Deterministic: no threads, sums in
   a fixed order; the same input gives the same particles bit for bit. */

#define SPS__RELAX_TABLE 128           /* Wp(z) table points on z in [0, 2h] */
#define SPS__RELAX_ALPHA SPS_R(0.3)    /* shift coefficient: unstable from ~0.8 (2D ring, 3D ball, h = 1.3 dp) */
#define SPS__RELAX_MAX_STEP SPS_R(0.2) /* largest shift per iteration [dp] */
#define SPS__RELAX_BOUND SPS_R(0.5)     /* surface bounding: depth < dp/2 is projected to dp/2 */
#define SPS__RELAX_DEFAULT_ITERATIONS 300
#define SPS__RELAX_MAX_POINTS 200000000.0 /* the world's particle cap (2e8) */

typedef struct sps__relax_ctx {
    const sps_world* w;
    int dim;
    sps_real dp, h, support, vol; /* support = 2h, vol = dp^d */
    sps_real (*sdf)(const sps_real x[3], void* user);
    void* user;
    sps_real lo[3], hi[3];
    int bad;             /* the sdf returned NaN (or the gradient was not finite) */
    sps_real bad_x[3];   /* where */
    sps_real wp[SPS__RELAX_TABLE + 1]; /* Wp(z_k), z_k = k 2h / TABLE */
    sps_real wf[SPS__RELAX_TABLE + 1]; /* F(z_k) = int_{z_k}^{2h} Wp: kernel mass beyond a flat surface */
    sps_real dw_peak, r_peak; /* the most negative dW/dr and where (sampled on 1024 points of 2h) */
    /* cell list */
    int cap_cells, nc[3];
    sps_real cmin[3], csize;
    int *start, *order, *cell;
} sps__relax_ctx;


/* phi = max(sdf, box); NaN is recorded in c->bad (and returned as +1e30: outside). */
static sps_real sps__relax_phi(sps__relax_ctx* c, const sps_real x[3]) {
    sps_real p = c->sdf(x, c->user);
    int a;
    if (p != p) {
        if (!c->bad) { c->bad = 1; memcpy(c->bad_x, x, sizeof c->bad_x); }
        return SPS_R(1e30);
    }
    for (a = 0; a < c->dim; ++a) {
        sps_real e = c->lo[a] - x[a] > x[a] - c->hi[a] ? c->lo[a] - x[a] : x[a] - c->hi[a];
        if (e > p) p = e;
    }
    return p;
}

/* Central-difference gradient of phi, step dp/10; returns |g|^2 (0 if not usable). */
static sps_real sps__relax_grad(sps__relax_ctx* c, const sps_real x[3], sps_real g[3]) {
    sps_real e = SPS_R(0.1) * c->dp, y[3], g2 = 0;
    int a;
    g[0] = g[1] = g[2] = 0;
    for (a = 0; a < c->dim; ++a) {
        sps_real fp, fm;
        memcpy(y, x, sizeof y);
        y[a] = x[a] + e; fp = sps__relax_phi(c, y);
        y[a] = x[a] - e; fm = sps__relax_phi(c, y);
        g[a] = (fp - fm) / (2 * e);
        g2 += g[a] * g[a];
    }
    if (!(g2 < SPS_R(1e30)) && !c->bad) { c->bad = 1; memcpy(c->bad_x, x, sizeof c->bad_x); }
    return g2 > SPS_R(1e-12) && g2 < SPS_R(1e30) ? g2 : 0;
}

/* Linear interpolation in a table on [0, 2h] (0 beyond 2h; the value at 0 for z < 0). */
static sps_real sps__relax_table(const sps__relax_ctx* c, const sps_real* t, sps_real z) {
    return sps__plane_table_at(c->w, t, SPS__RELAX_TABLE, z);
}

/* Fills the constants and the Wp, F tables (Simpson's rule, 64 intervals per entry). */
static void sps__relax_setup(sps__relax_ctx* c, const sps_world* w, const sps_real lo[3], const sps_real hi[3],
                             sps_real (*sdf)(const sps_real x[3], void* user), void* user) {
    const sps_world_def* d = sps_world_get_def(w);
    int k, a;
    memset(c, 0, sizeof *c);
    c->w = w; c->dim = d->dim; c->dp = d->dp; c->h = d->h_over_dp * d->dp; c->support = 2 * c->h;
    c->vol = d->dim == 2 ? c->dp * c->dp : c->dp * c->dp * c->dp;
    c->sdf = sdf; c->user = user;
    for (a = 0; a < 3; ++a) {
        c->lo[a] = a < c->dim ? lo[a] : 0;
        c->hi[a] = a < c->dim ? hi[a] : 0;
    }
    sps__kernel_plane_tables(w, SPS__RELAX_TABLE, c->wp, c->wf);
    c->dw_peak = 0; c->r_peak = 0;
    for (k = 1; k < 1024; ++k) {
        sps_real r = c->support * (sps_real)k / 1024, dw = sps_world_kernel_derivative(w, r);
        if (dw < c->dw_peak) { c->dw_peak = dw; c->r_peak = r; }
    }
}

/* Lattice points lo + (i + 1/2) dp with phi < 0 (the points of sps_body_add_sdf, same count
   rule); writes them to xyz (3 reals each) if not NULL. Returns the count, or -1 when the box
   holds more than the world's particle cap. */
static long sps__relax_lattice(sps__relax_ctx* c, sps_real* xyz) {
    int cnt[3] = {1, 1, 1}, a, i, j, l;
    double cells = 1;
    long n = 0;
    for (a = 0; a < c->dim; ++a) {
        /* the slack of sps__fill (absorbs the rounding of lo, hi and dp) */
        double q = floor((double)((c->hi[a] - c->lo[a]) / c->dp +
                                  (sizeof(sps_real) == sizeof(float) ? SPS_R(1e-3) : SPS_R(1e-6))));
        if (q < 1) return 0;
        cells *= q;
        if (cells > SPS__RELAX_MAX_POINTS) return -1;
        cnt[a] = (int)q;
    }
    for (l = 0; l < cnt[2]; ++l)
        for (j = 0; j < cnt[1]; ++j)
            for (i = 0; i < cnt[0]; ++i) {
                sps_real x[3], p;
                x[0] = c->lo[0] + (i + SPS_R(0.5)) * c->dp;
                x[1] = c->lo[1] + (j + SPS_R(0.5)) * c->dp;
                x[2] = c->dim == 3 ? c->lo[2] + (l + SPS_R(0.5)) * c->dp : 0;
                p = c->sdf(x, c->user);
                if (!(p < 0)) { /* sps__fill's test, on the sdf alone; NaN is an error here */
                    if (p != p && !c->bad) { c->bad = 1; memcpy(c->bad_x, x, sizeof x); }
                    continue;
                }
                if (xyz) memcpy(xyz + 3 * n, x, sizeof x);
                ++n;
            }
    return n;
}

/* Cell list of the n points: cells of side >= 2h over their bounding box, at most cap_cells
   cells (the side grows when the box is large). Counting sort: the points of cell k are
   order[start[k] .. start[k+1]); cell[i] is point i's cell. */
static void sps__relax_grid(sps__relax_ctx* c, int n, const sps_real* xyz) {
    sps_real mx[3] = {0, 0, 0};
    double total;
    int a, i, k, ncell;
    for (a = 0; a < 3; ++a) { c->cmin[a] = 0; c->nc[a] = 1; }
    for (a = 0; a < c->dim; ++a) {
        c->cmin[a] = mx[a] = xyz[a];
        for (i = 1; i < n; ++i) {
            if (xyz[3 * i + a] < c->cmin[a]) c->cmin[a] = xyz[3 * i + a];
            if (xyz[3 * i + a] > mx[a]) mx[a] = xyz[3 * i + a];
        }
    }
    c->csize = c->support;
    for (;;) {
        total = 1;
        for (a = 0; a < c->dim; ++a) total *= floor((double)((mx[a] - c->cmin[a]) / c->csize)) + 1;
        if (total <= c->cap_cells) break;
        c->csize *= SPS_R(1.25);
    }
    for (a = 0; a < c->dim; ++a) c->nc[a] = (int)floor((double)((mx[a] - c->cmin[a]) / c->csize)) + 1;
    ncell = c->nc[0] * c->nc[1] * c->nc[2];
    memset(c->start, 0, sizeof(int) * (size_t)(ncell + 1));
    for (i = 0; i < n; ++i) {
        int ci[3] = {0, 0, 0};
        for (a = 0; a < c->dim; ++a) {
            ci[a] = (int)((xyz[3 * i + a] - c->cmin[a]) / c->csize);
            if (ci[a] >= c->nc[a]) ci[a] = c->nc[a] - 1;
            if (ci[a] < 0) ci[a] = 0;
        }
        c->cell[i] = (ci[2] * c->nc[1] + ci[1]) * c->nc[0] + ci[0];
        c->start[c->cell[i] + 1]++;
    }
    for (k = 0; k < ncell; ++k) c->start[k + 1] += c->start[k];
    for (i = 0; i < n; ++i) c->order[c->start[c->cell[i]]++] = i; /* start[k] now ends cell k */
    for (k = ncell; k > 0; --k) c->start[k] = c->start[k - 1];
    c->start[0] = 0;
}

/* Over the neighbours j != i within 2h of point i (cell list current): grad_out (if not NULL) +=
   sum_j grad_i W_ij V, and returns sum_j W_ij V (without the self term); *rmin gets the
   smallest distance. Fixed order (cells, then points in index order). */
static sps_real sps__relax_sums(const sps__relax_ctx* c, const sps_real* xyz, int i, sps_real grad_out[3], sps_real* rmin) {
    int ci[3], a, dz, dy, dx;
    sps_real nd = 0, s2 = c->support * c->support, r2min = SPS_R(1e30);
    const sps_real* xi = xyz + 3 * i;
    ci[0] = c->cell[i] % c->nc[0];
    ci[1] = (c->cell[i] / c->nc[0]) % c->nc[1];
    ci[2] = c->cell[i] / (c->nc[0] * c->nc[1]);
    for (dz = -1; dz <= 1; ++dz) {
        if (ci[2] + dz < 0 || ci[2] + dz >= c->nc[2]) continue;
        for (dy = -1; dy <= 1; ++dy) {
            if (ci[1] + dy < 0 || ci[1] + dy >= c->nc[1]) continue;
            for (dx = -1; dx <= 1; ++dx) {
                int k, p;
                if (ci[0] + dx < 0 || ci[0] + dx >= c->nc[0]) continue;
                k = ((ci[2] + dz) * c->nc[1] + ci[1] + dy) * c->nc[0] + ci[0] + dx;
                for (p = c->start[k]; p < c->start[k + 1]; ++p) {
                    int j = c->order[p];
                    sps_real d[3], r2 = 0, r;
                    if (j == i) continue;
                    for (a = 0; a < 3; ++a) { d[a] = xi[a] - xyz[3 * j + a]; r2 += d[a] * d[a]; }
                    if (r2 < r2min) r2min = r2;
                    if (!(r2 < s2)) continue;
                    r = (sps_real)sqrt((double)r2);
                    nd += sps_world_kernel(c->w, r) * c->vol;
                    if (grad_out) {
                        /* dW/dr, but not weaker than its peak below the peak's distance: the
                           kernel's repulsion vanishes at r -> 0 (Wendland C2: peak at r = h/2),
                           so pressed pairs (corners, thin parts) could merge and stay merged */
                        sps_real f = (r < c->r_peak ? c->dw_peak : sps_world_kernel_derivative(c->w, r)) * c->vol;
                        if (r > 0) f /= r;
                        else { d[0] = j < i ? 1 : -1; d[1] = d[2] = 0; } /* coincident: split along x, by index */
                        for (a = 0; a < 3; ++a) grad_out[a] += f * d[a];
                    }
                }
            }
        }
    }
    if (rmin) *rmin = (sps_real)sqrt((double)r2min);
    return nd;
}

/* Moves x onto the layer phi = target (Newton steps along grad phi, two at most); returns phi. */
static sps_real sps__relax_project(sps__relax_ctx* c, sps_real x[3], sps_real phi, sps_real target) {
    int it, a;
    for (it = 0; it < 2 && phi > target + SPS_R(1e-3) * c->dp; ++it) { /* stop once well inside */
        sps_real g[3], g2 = sps__relax_grad(c, x, g);
        if (g2 == 0) break;
        for (a = 0; a < c->dim; ++a) x[a] -= (phi - target) * g[a] / g2;
        phi = sps__relax_phi(c, x);
    }
    return phi;
}

/* The relaxation of n points xyz (3 reals each, inside the shape) in place: iterations steps
   of the shift (see the chapter's comment). phi (n) and dx (3n) and the cell list come from
   sps__relax_work. Every particle stays inside (phi < 0) after every iteration. */
static void sps__relax_iterate(sps__relax_ctx* c, int n, sps_real* xyz, sps_real* phi, sps_real* dx, int iterations) {
    int it, i, a;
    sps_real alpha_h2 = SPS__RELAX_ALPHA * c->h * c->h, cap = SPS__RELAX_MAX_STEP * c->dp;
    for (i = 0; i < n; ++i) phi[i] = sps__relax_phi(c, xyz + 3 * i);
    for (it = 0; it < iterations && !c->bad; ++it) {
        sps__relax_grid(c, n, xyz);
        for (i = 0; i < n; ++i) {
            sps_real gsum[3] = {0, 0, 0}, depth = -phi[i], len2 = 0;
            sps__relax_sums(c, xyz, i, gsum, NULL);
            if (depth < c->support) { /* the surface stands in for the missing neighbours: n Wp(d) */
                sps_real g[3], g2 = sps__relax_grad(c, xyz + 3 * i, g);
                if (g2 > 0) {
                    sps_real f = sps__relax_table(c, c->wp, depth) / (sps_real)sqrt((double)g2);
                    for (a = 0; a < c->dim; ++a) gsum[a] += f * g[a];
                }
            }
            for (a = 0; a < 3; ++a) { dx[3 * i + a] = -alpha_h2 * gsum[a]; len2 += dx[3 * i + a] * dx[3 * i + a]; }
            if (len2 > cap * cap) {
                sps_real s = cap / (sps_real)sqrt((double)len2);
                for (a = 0; a < 3; ++a) dx[3 * i + a] *= s;
            }
        }
        for (i = 0; i < n; ++i) {
            sps_real* x = xyz + 3 * i, old[3], p;
            memcpy(old, x, sizeof old);
            for (a = 0; a < c->dim; ++a) x[a] += dx[3 * i + a];
            p = sps__relax_phi(c, x);
            if (p > -SPS__RELAX_BOUND * c->dp) p = sps__relax_project(c, x, p, -SPS_R(0.5) * c->dp);
            if (p < 0) phi[i] = p;
            else memcpy(x, old, sizeof old); /* no layer dp/2 deep here (a shape thinner than dp,
                                                a sharp corner): the particle stays where it was,
                                                so every particle stays inside (phi < 0) */
        }
    }
}

/* Allocation in one place: the work arrays of n points. Returns the block (NULL: out of memory). */
static void* sps__relax_work(sps__relax_ctx* c, int n, sps_real** phi, sps_real** dx) {
    size_t nr = (size_t)n * 4, ni;
    char* blk;
    c->cap_cells = 2 * n + 64; /* at most ~2 cells per point: O(N) memory whatever the box */
    ni = (size_t)n * 2 + (size_t)c->cap_cells + 1;
    blk = (char*)sps__alloc(c->w, nr * sizeof(sps_real) + ni * sizeof(int));
    if (!blk) return NULL;
    *phi = (sps_real*)blk;
    *dx = *phi + n;
    c->start = (int*)(void*)(*dx + 3 * (size_t)n);
    c->order = c->start + c->cap_cells + 1;
    c->cell = c->order + n;
    return blk;
}

/* sps_measure_fill: see its declaration. */
SPSDEF sps_result sps_measure_fill(const sps_world* w, int n, const sps_real* xyz, const sps_real lo[3], const sps_real hi[3],
                                  sps_real (*sdf)(const sps_real x[3], void* user), void* user, sps_fill_quality* q) {
    sps__relax_ctx c;
    sps_real *phi, *dx, rmin = SPS_R(1e30);
    double s1 = 0, s2 = 0, t1 = 0, t2 = 0, e2 = 0;
    void* blk;
    int i;
    memset(q, 0, sizeof *q);
    if (!w || !sdf || !xyz || n <= 0) return SPS_ERR_INVALID_ARG;
    sps__relax_setup(&c, w, lo, hi, sdf, user);
    if (!(blk = sps__relax_work(&c, n, &phi, &dx))) return SPS_ERR_OUT_OF_MEMORY;
    sps__relax_grid(&c, n, xyz);
    q->particles = n;
    for (i = 0; i < n; ++i) {
        sps_real r, depth = -sps__relax_phi(&c, xyz + 3 * i);
        double nd = (double)(sps__relax_sums(&c, xyz, i, NULL, &r) + sps_world_kernel(w, 0) * c.vol);
        double full = nd + (double)(depth >= 0 ? sps__relax_table(&c, c.wf, depth) : 1 - sps__relax_table(&c, c.wf, -depth));
        if (r < rmin) rmin = r;
        s1 += full; s2 += full * full;
        if (depth > c.support) { q->inner++; t1 += nd; t2 += nd * nd; }
        if (depth < c.dp) { double e = (double)(depth / c.dp) - 0.5; q->surface++; e2 += e * e; }
    }
    sps__free(w, blk);
    s1 /= n; s2 /= n;
    q->density_spread = (sps_real)(sqrt(fmax(s2 - s1 * s1, 0)) / s1);
    if (q->inner) { t1 /= q->inner; t2 /= q->inner; q->density_spread_inner = (sps_real)(sqrt(fmax(t2 - t1 * t1, 0)) / t1); }
    q->min_spacing = rmin / c.dp;
    q->surface_rms = q->surface ? (sps_real)sqrt(e2 / q->surface) : 0;
    return c.bad ? SPS_ERR_INVALID_ARG : SPS_OK;
}

/* Lattice fill of [lo, hi) where sdf(x, user) < 0 (the points of sps_body_add_sdf), relaxed to a
   uniform distribution whose outer layer lies on a smooth surface dp/2 inside the shape (see
   BODY-FITTED PARTICLES above). sdf must be a signed distance (|grad| = 1) within 2h of the
   surface, negative inside; the box should contain the shape (a shape cut by the box is relaxed
   as the intersection). iterations: shifting steps, >= 0; 0 selects 300. *added (may be NULL)
   gets the number added: the lattice's count (the particles keep their volume dp^d).
   Errors: SPS_ERR_INVALID_ARG for a NULL world, sdf or lo/hi, an invalid body, a box not finite
   with lo < hi, iterations < 0, more lattice points than the world's cap, or an sdf that returns
   NaN (at a lattice point or during the relaxation): nothing is added.
   SPS_ERR_OUT_OF_MEMORY; errors of sps_body_add_particles. Allocates O(N) scratch; O(N) per
   iteration; deterministic. */
SPSDEF sps_result sps_body_add_sdf_relaxed(sps_world* w, sps_body b, const sps_real lo[3], const sps_real hi[3],
                                           sps_real (*sdf)(const sps_real x[3], void* user), void* user, int iterations, int* added) {
    static const char* fn = "sps_body_add_sdf_relaxed";
    sps__relax_ctx c;
    sps_real *xyz, *phi, *dx;
    void* blk;
    long n;
    sps_result r;
    if (added) *added = 0;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (sps__check_body(w, b, fn) < 0) return SPS_ERR_INVALID_ARG;
    if (!sdf) { sps__set_error(w, 0, "%s: sdf must not be NULL", fn); return SPS_ERR_INVALID_ARG; }
    if (!sps__check_box(w, fn, lo, hi)) return SPS_ERR_INVALID_ARG;
    if (iterations < 0) { sps__set_error(w, 0, "%s: iterations = %d, allowed >= 0 (0: %d)", fn, iterations, SPS__RELAX_DEFAULT_ITERATIONS); return SPS_ERR_INVALID_ARG; }
    if (iterations == 0) iterations = SPS__RELAX_DEFAULT_ITERATIONS;
    sps__relax_setup(&c, w, lo, hi, sdf, user);
    n = sps__relax_lattice(&c, NULL);
    if (n < 0) { sps__set_error_const(w, "%s: the box holds more than %.0f lattice points", fn, SPS__RELAX_MAX_POINTS); return SPS_ERR_INVALID_ARG; }
    if (c.bad) {
        sps__set_error_const(w, "%s: sdf returned NaN at (%g, %g, %g)", fn, (double)c.bad_x[0], (double)c.bad_x[1], (double)c.bad_x[2]);
        return SPS_ERR_INVALID_ARG;
    }
    if (n == 0) return SPS_OK;
    if (!(blk = sps__relax_work(&c, (int)n, &phi, &dx))) { sps__set_error_const(w, "%s: out of memory for the work arrays of %ld points", fn, n); return SPS_ERR_OUT_OF_MEMORY; }
    xyz = (sps_real*)sps__alloc(w, sizeof(sps_real) * 3 * (size_t)n);
    if (!xyz) { sps__free(w, blk); sps__set_error_const(w, "%s: out of memory for %ld points", fn, n); return SPS_ERR_OUT_OF_MEMORY; }
    sps__relax_lattice(&c, xyz);
    sps__relax_iterate(&c, (int)n, xyz, phi, dx, iterations);
    if (c.bad) {
        sps__set_error_const(w, "%s: sdf returned NaN (or a gradient that is not finite) near (%g, %g, %g)", fn,
                         (double)c.bad_x[0], (double)c.bad_x[1], (double)c.bad_x[2]);
        r = SPS_ERR_INVALID_ARG;
    } else {
        r = sps_body_add_particles(w, b, (int)n, xyz, NULL);
        if (r == SPS_OK && added) *added = (int)n;
    }
    sps__free(w, xyz);
    sps__free(w, blk);
    return r;
}

/* >>periodic: periodic axes (PERIODIC in the manual)

   An axis with world def periodic[a] = L > 0 repeats with period L from periodic_origin[a].
   Every pair offset x_i - x_j along it is the nearest image's, x_ij - L round(x_ij / L) (the
   minimum-image convention: right for every pair within the support, since L >= 3 supports);
   the cell grid along it has a whole number of cells, each at least the support, and wraps
   (sps__setup_grid), so a cell's 3^d neighbours include those across the boundary; and at
   each configuration update and after each step a particle that has left [origin, origin + L)
   is moved back by a whole number of periods (sps__wrap_positions), so outputs and
   diagnostics report positions in the box. Between two wraps a particle may stand a fraction
   of dp outside: nothing reads its absolute position along the axis but gravity's potential,
   which the wrap accounts for. The neighbour loops of a world without periodic axes are
   compiled without any of it (sps__mode: the periodic pair geometry is a mode of its own). */

/* The periodic rules of a world def (sps_world_def_check). */
static void sps__periodic_check(const sps_world_def* def, char* msg, size_t msg_size, int* broken) {
    /* the grid needs 3 cells of at least the support along the axis so the 3 cells around a
       cell are distinct; 3 supports also keep every pair within the support at its nearest image */
    const double least = 3 * 2 * (double)def->h_over_dp * (double)def->dp;
    int a, any = 0;
    for (a = 0; a < 3; ++a) {
        const double L = (double)def->periodic[a];
        if (!sps__finite(def->periodic[a]) || L < 0 || (L > 0 && L < least))
            sps__rule(msg, msg_size, broken, "periodic[%d] = %g m, allowed 0 (not periodic) or a period >= 3 supports = 6 h = %g m", a, L, least);
        if (!sps__finite(def->periodic_origin[a]))
            sps__rule(msg, msg_size, broken, "periodic_origin[%d] = %g, allowed finite", a, (double)def->periodic_origin[a]);
        any |= L > 0;
    }
    if (def->dim == 2 && def->periodic[2] != 0)
        sps__rule(msg, msg_size, broken, "periodic[2] = %g m in a 2D world, allowed 0 (a 2D world has the axes x and y only)", (double)def->periodic[2]);
    if (any && def->frozen_geometry)
        sps__rule(msg, msg_size, broken, "frozen_geometry = %d with a periodic axis, allowed 0 (the stored pair geometry has no periodic images)",
                  def->frozen_geometry);
}

/* Sets the world's periods from its def (sps_world_create). */
static void sps__periodic_setup(sps_world* w) {
    int a;
    for (a = 0; a < w->dim; ++a)
        if (w->def.periodic[a] > 0) {
            w->period[a] = w->def.periodic[a];
            w->inv_period[a] = 1 / w->def.periodic[a];
            w->periodic = 1;
        }
}

/* The nearest image of the offset d along axis a: d itself on an axis that is not periodic
   (L = 1/L = 0 there, so the loops that call it need no branch). */
SPS__INLINE sps_real sps__nearest_image(const sps_world* w, int a, sps_real d) {
    return d - w->period[a] * SPS__FLOOR(d * w->inv_period[a] + SPS_R(0.5));
}

/* The offset x_i - x_j of particles i and j (the nearest image) into d; returns |d|^2. */
static sps_real sps__offset(const sps_world* w, int i, int j, sps_real d[3]) {
    sps_real r2 = 0;
    int a;
    for (a = 0; a < 3; ++a) {
        d[a] = a < w->dim ? sps__nearest_image(w, a, w->pos[a][i] - w->pos[a][j]) : 0;
        r2 += d[a] * d[a];
    }
    return r2;
}

/* The offset x_i - x_j into d (zero past dim) and its |d|^2: the nearest image in a periodic
   world, the plain difference otherwise (bit for bit as before periodic axes existed). */
static sps_real sps__pair_offset(const sps_world* w, int i, int j, sps_real d[3]) {
    sps_real r2 = 0;
    int a;
    if (w->periodic) return sps__offset(w, i, j, d);
    for (a = 0; a < 3; ++a) {
        d[a] = a < w->dim ? w->pos[a][i] - w->pos[a][j] : 0;
        r2 += d[a] * d[a];
    }
    return r2;
}
/* The displacement of i relative to j along axis a, u_i - u_j (u = x - X), given their offset
   d_a (sps__pair_offset): in a periodic world d_a less the nearest image of X_i - X_j (a wrap
   moves x, not X). */
static sps_real sps__relative_displacement(const sps_world* w, int i, int j, int a, sps_real d_a) {
    if (w->periodic) return d_a - sps__nearest_image(w, a, w->ref[a][i] - w->ref[a][j]);
    return (w->pos[a][i] - w->ref[a][i]) - (w->pos[a][j] - w->ref[a][j]);
}

/* Moves every particle that has left a periodic axis's box [origin, origin + L) back by whole
   periods. Gravity's potential -m g.x jumps by m g_a k L for a shift of -k L: the energy
   watchdog's start moves with it (a flow down a periodic channel is not a gain). */
static void sps__wrap_positions(sps_world* w) {
    int a, i;
    for (a = 0; a < w->dim; ++a) {
        const sps_real L = w->period[a], inv = w->inv_period[a], origin = w->def.periodic_origin[a], g = w->def.gravity[a];
        if (!(L > 0)) continue;
        for (i = 0; i < w->n; ++i) {
            const sps_real k = SPS__FLOOR((w->pos[a][i] - origin) * inv);
            if (k == 0) continue;
            w->pos[a][i] -= k * L;
            if (w->pos[a][i] < origin) w->pos[a][i] = origin; /* rounding at the box's ends */
            if (w->pos[a][i] >= origin + L) w->pos[a][i] = origin;
            if (g != 0) sps__watch_adjust(w, w->body[i], 0, w->mass[i] * g * k * L);
        }
    }
}

/* What a periodic world cannot hold: a total-Lagrangian body (its reference configuration, the
   source of its neighbours and of F, has no periodic images) and a free rigid body (its pose is
   the centre of mass of its particles, which a body across the boundary does not have).
   Returns 0 with the world's error set for those. */
static int sps__periodic_allows_body(sps_world* w, const sps_body_def* def) {
    const char* what = def->solver == SPS_SOLVER_TOTAL_LAGRANGIAN ? "a total-Lagrangian body (its reference configuration has no periodic images)"
                                                                   : sps__kind_not_periodic(def->material.kind);
    if (!w->periodic || !what) return 1;
    sps__set_error(w, 0, "sps_world_add_body: body '%s' is %s, and the world has periodic axes (periodic = (%g, %g, %g) m); allowed in a "
                   "periodic world: updated-Lagrangian bodies and wall bodies", def->name ? def->name : "body", what,
                   (double)w->period[0], (double)w->period[1], (double)w->period[2]);
    return 0;
}

/* A wall whose normal has a component along a periodic axis would cut the period: refused.
   Returns 0 with the world's error set. */
static int sps__periodic_allows_wall(sps_world* w, const sps_real normal[3], sps_real length) {
    int a;
    for (a = 0; a < w->dim; ++a)
        if (w->period[a] > 0 && SPS__FABS(normal[a]) > SPS_R(1e-9) * length) {
            sps__set_error(w, 0, "sps_world_add_wall: normal = (%g, %g, %g) has a component along periodic axis %d (periodic[%d] = %g m), "
                           "allowed walls parallel to the periodic axes (normal[%d] = 0)", (double)normal[0], (double)normal[1],
                           w->dim == 3 ? (double)normal[2] : 0.0, a, a, (double)w->period[a], a);
            return 0;
        }
    return 1;
}

/* >>neighbours */

/* Sorts the particles of [begin, end) by key (stable counting sort; keys < nkeys) and applies
   the permutation to every per-particle field. */
static void sps__permute_real(sps_world* w, sps_real* f, int begin, int count, int stride) {
    sps_real* tmp = (sps_real*)w->scratch;
    int i, s;
    if (!f) return;
    if (stride == 1) { /* most fields: a plain gather the compiler vectorises */
        for (i = 0; i < count; ++i) tmp[i] = f[begin + w->perm[i]];
        memcpy(f + begin, tmp, sizeof(sps_real) * (size_t)count);
        return;
    }
    for (s = 0; s < stride; ++s) { /* a component at a time: the scratch holds a real per particle */
        for (i = 0; i < count; ++i) tmp[i] = f[(size_t)(begin + w->perm[i]) * stride + s];
        for (i = 0; i < count; ++i) f[(size_t)(begin + i) * stride + s] = tmp[i];
    }
}
static void sps__permute_int(sps_world* w, int* f, int begin, int count) {
    int* tmp = (int*)w->scratch;
    int i;
    if (!f) return;
    for (i = 0; i < count; ++i) tmp[i] = f[begin + w->perm[i]];
    memcpy(f + begin, tmp, sizeof(int) * (size_t)count);
}

/* Counting sort of count keys (< nkeys) into w->perm (perm[new] = old), stable. */
static void sps__sort_keys(sps_world* w, int count, const int* key, int nkeys) {
    int i, *start = w->cell_start;
    for (i = 0; i <= nkeys; ++i) start[i] = 0;
    for (i = 0; i < count; ++i) start[key[i] + 1]++;
    for (i = 0; i < nkeys; ++i) start[i + 1] += start[i];
    for (i = 0; i < count; ++i) w->perm[start[key[i]]++] = i;
}

/* Applies w->perm to the count values of field f from index `from` of each of its arrays
   (x: a real array, or NULL to take the world's int array). */
static void sps__permute_field(sps_world* w, const sps__field_info* f, sps_real* x, int a, int from, int count) {
    if (f->is_int) sps__permute_int(w, sps__int_array(w, f, a), from, count);
    else sps__permute_real(w, x, from, count, f->components);
}

/* Groups the particles by body (stable; at commit): the world's carried fields follow. The
   bodies' own arrays do not move: each body's particles keep their order (sps__ensure_body_field). */
static void sps__sort_by_body(sps_world* w) {
    int i, k, a;
    sps__sort_keys(w, w->n, w->body, w->nbodies);
    for (k = 0; k < SPS__NFIELDS; ++k) {
        const sps__field_info* f = &sps__fields[k];
        if (!(f->care & SPS__CARRIED) || f->per_body) continue;
        for (a = 0; a < sps__field_arrays(f); ++a) sps__permute_field(w, f, f->is_int ? NULL : sps__real_array(w, NULL, f, a), a, 0, w->n);
    }
    for (i = 0; i < w->n; ++i) w->slot_of_id[w->id[i]] = i;
}

/* Sorts body b's particles by key (their cells; keys < nkeys): every field marked SPS__CARRIED
   follows its particle, the world's and the body's own; the others are rebuilt before they are
   read. */
static void sps__sort_body(sps_world* w, const sps__body* b, const int* key, int nkeys) {
    const int count = b->end - b->begin;
    int i, k, a;
    sps__sort_keys(w, count, key, nkeys);
    for (k = 0; k < SPS__NFIELDS; ++k) {
        const sps__field_info* f = &sps__fields[k];
        if (!(f->care & SPS__CARRIED)) continue;
        for (a = 0; a < sps__field_arrays(f); ++a) {
            if (f->per_body) sps__permute_field(w, f, sps__real_array(w, b, f, a), a, 0, count);
            else sps__permute_field(w, f, f->is_int ? NULL : sps__real_array(w, NULL, f, a), a, b->begin, count);
        }
    }
    for (i = b->begin; i < b->end; ++i) w->slot_of_id[w->id[i]] = i;
}

/* Cell grid of particles [begin, end) at positions x (the current ones, or a total-Lagrangian
   body's reference ones): cell size = support (along a periodic axis its period over a whole
   number of cells, chapter >>periodic); dims capped near 4 cells per particle, each at least 3
   so the 3^d neighbour cells of a cell are distinct even when the grid wraps. */
static int sps__setup_grid(sps_world* w, sps_real* const x[3], int begin, int end) {
    int a, i;
    double total = 1, cap = 4.0 * (end - begin) + 64;
    sps_real lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (a = 0; a < w->dim; ++a) {
        lo[a] = hi[a] = x[a][begin];
        for (i = begin + 1; i < end; ++i) {
            const sps_real xa = x[a][i];
            if (xa < lo[a]) lo[a] = xa;
            if (xa > hi[a]) hi[a] = xa;
        }
    }
    for (a = 0; a < 3; ++a) {
        double span = a < w->dim ? ((double)hi[a] - (double)lo[a]) / (double)w->support : 0;
        double n = floor(span) + 1;
        if (w->period[a] > 0) n = floor((double)w->period[a] / (double)w->support); /* >= 3 (sps__periodic_check) */
        if (n < 3) n = 3;
        if (n > 1e6) n = 1e6;
        w->grid_n[a] = a < w->dim ? (int)n : 1;
        w->grid_lo[a] = w->period[a] > 0 ? w->def.periodic_origin[a] : lo[a];
        w->grid_cell[a] = w->period[a] > 0 ? w->period[a] / (sps_real)n : w->support;
        w->grid_wrap[a] = w->period[a] > 0;
        total *= w->grid_n[a];
    }
    while (total > cap) { /* halve the longest axis: the grid wraps (periodic hashing) */
        int m = 0;
        for (a = 1; a < w->dim; ++a)
            if (w->grid_n[a] > w->grid_n[m]) m = a;
        if (w->grid_n[m] <= 3) break;
        total /= w->grid_n[m];
        w->grid_n[m] = w->grid_n[m] / 2 < 3 ? 3 : w->grid_n[m] / 2;
        /* a periodic axis keeps a whole number of cells in its period: larger cells, not hashing */
        if (w->period[m] > 0) w->grid_cell[m] = w->period[m] / (sps_real)w->grid_n[m];
        w->grid_wrap[m] = 1;
        total *= w->grid_n[m];
    }
    return (int)total;
}

/* Integer cell coordinate of x along axis a (wrapped). fmod keeps huge coordinates exact and
   finite so a runaway particle cannot overflow an integer conversion. */
SPS__INLINE int sps__cell_coord(const sps_world* w, int a, sps_real x) {
    double c = floor(((double)x - (double)w->grid_lo[a]) / (double)w->grid_cell[a]);
    c = fmod(c, (double)w->grid_n[a]);
    if (c < 0) c += w->grid_n[a];
    return (int)c;
}

static sps_result sps__ensure_neighbor_storage(sps_world* w);
SPS__INLINE void sps__blended_inverse(const sps_real* a, int as, sps_real* b, int bs, const int dim);
static void sps__carry_pair_forces(sps_world* w, const sps__body* b, int i, int s, int len);
static sps_result sps__tl_pair_table(sps_world* w, sps__body* b);

/* The k-th neighbour of particle i (k < nb_count[i]). */
SPS__INLINE int sps__neighbor(const sps_world* w, int i, int k) { return w->nb_j[w->nb_first[i] + k * SPS__LANES]; }

/* The neighbours of particle gi of the body starting at begin, in cell c of the body's grid,
   into list (at most width; returns the count): the particles of the 3^d cells around c within
   the support at positions x. Where an axis does not wrap, the three cells of a row are adjacent
   in the sorted order, so each row is one contiguous run of candidates. periodic (a literal):
   offsets to the nearest image (chapter >>periodic). */
SPS__INLINE int sps__collect_neighbors(const sps_world* w, sps_real* const x[3], int begin, int gi, int c, int* list, int width,
                                       const int dim, const int periodic) {
    const int gx = w->grid_n[0], gy = w->grid_n[1], gz = w->grid_n[2];
    const int cx = c % gx, cy = c / gx % gy, cz = c / (gx * gy);
    const sps_real cut2 = w->support * w->support, xi = x[0][gi], yi = x[1][gi];
    const sps_real zi = dim == 3 ? x[2][gi] : 0;
    int m = 0, dy, dz, cell[3], ncell, k, x0, x1;
    if (!w->grid_wrap[0]) { /* one run per row: cells x0..x1 */
        x0 = cx > 0 ? cx - 1 : 0;
        x1 = cx < gx - 1 ? cx + 1 : gx - 1;
    } else {
        x0 = x1 = 0;
    }
    for (dz = -(dim == 3); dz <= (dim == 3); ++dz) {
        int z = cz + dz;
        if (!w->grid_wrap[2] && (z < 0 || z >= gz)) continue;
        z = (z + gz) % gz;
        for (dy = -1; dy <= 1; ++dy) {
            int y = cy + dy, row;
            if (!w->grid_wrap[1] && (y < 0 || y >= gy)) continue;
            y = (y + gy) % gy;
            row = gx * (y + gy * z);
            if (!w->grid_wrap[0]) {
                cell[0] = row + x0;
                ncell = 1;
            } else { /* a wrapped axis has at least 3 cells: the three are distinct */
                for (k = 0; k < 3; ++k) cell[k] = row + (cx - 1 + k + gx) % gx;
                ncell = 3;
            }
            for (k = 0; k < ncell; ++k) {
                const int s0 = w->cell_start[cell[k]], s1 = w->cell_start[cell[k] + (ncell == 1 ? x1 - x0 + 1 : 1)];
                int s;
                for (s = s0; s < s1; ++s) {
                    const int gj = begin + s;
                    sps_real dx = xi - x[0][gj], dyy = yi - x[1][gj], dzz = dim == 3 ? zi - x[2][gj] : 0, r2;
                    if (periodic) {
                        dx = sps__nearest_image(w, 0, dx);
                        dyy = sps__nearest_image(w, 1, dyy);
                        dzz = sps__nearest_image(w, 2, dzz);
                    }
                    r2 = dx * dx + dyy * dyy + dzz * dzz;
                    /* itself and coincident particles (r = 0, no direction) do not interact. Branch-free:
                       about half the candidates pass, a branch on it would miss half the time
                       (measured: the search took 16% of a fast run, now 8%). Slot m is free, so a
                       candidate written there and not counted is overwritten by the next. */
                    if (m < width) list[m] = gj;
                    m += (r2 < cut2) & (r2 > 0);
                }
            }
        }
    }
    return m;
}

static void sps__tl_reference(sps_world* w, sps__body* b);

/* A lane group g of body b: its first particle, its first slot and its length in slots per lane. */
typedef struct sps__group {
    int i0, s0, len;
} sps__group;

SPS__INLINE sps__group sps__group_of(const sps_world* w, const sps__body* b, int g) {
    sps__group q;
    q.i0 = b->begin + g * SPS__LANES;
    q.s0 = w->nb_group_start[b->group0 + g];
    q.len = (w->nb_group_start[b->group0 + g + 1] - q.s0) / SPS__LANES;
    return q;
}

/* Frozen geometry: dW/dr and 1/r of lane group q's slots (zeros in padding), with
   literal dim and kernel so the lane loop vectorises. The direction e_ij is not stored: see
   sps__pair. */
SPS__INLINE void sps__freeze_lanes(sps_world* w, sps__group q, const int dim, const int kernel) {
    const sps_real *SPS__RESTRICT px = w->pos[0], *SPS__RESTRICT py = w->pos[1], *SPS__RESTRICT pz = w->pos[2];
    const int* SPS__RESTRICT nb_j = w->nb_j;
    sps_real *SPS__RESTRICT nb_dw = w->nb_dw, *SPS__RESTRICT nb_inv_r = w->nb_inv_r;
    const sps_real dw_scale = w->dw_scale, inv_h = w->inv_h;
    int k, l;
    for (k = 0; k < q.len; ++k) {
        SPS__PRAGMA(omp simd)
        for (l = 0; l < SPS__LANES; ++l) {
            const int i = q.i0 + l, s = q.s0 + k * SPS__LANES + l, j = nb_j[s];
            const sps_real dx = px[i] - px[j], dy = py[i] - py[j], dz = dim == 3 ? pz[i] - pz[j] : 0, r2 = dx * dx + dy * dy + dz * dz;
            /* padding slots point at the particle itself; particles at the same point (a
               collapsed cluster) have no direction and no force either */
            const int real = r2 > 0;
            const sps_real r = SPS__SQRT(real ? r2 : 1), inv_r = real ? 1 / r : 0;
            const sps_real dw = real ? dw_scale * sps__kernel_df(kernel, r * inv_h) : 0;
            nb_dw[s] = dw;
            nb_inv_r[s] = inv_r;
        }
    }
}

/* The frozen geometry of lane group q (sps__freeze_lanes for the world's dim and kernel). */
static void sps__freeze_group(sps_world* w, sps__group q) {
    const int spline = w->def.kernel == SPS_KERNEL_CUBIC_SPLINE;
    if (w->dim == 2 && spline) sps__freeze_lanes(w, q, 2, SPS_KERNEL_CUBIC_SPLINE);
    else if (w->dim == 2) sps__freeze_lanes(w, q, 2, SPS_KERNEL_WENDLAND_C2);
    else if (spline) sps__freeze_lanes(w, q, 3, SPS_KERNEL_CUBIC_SPLINE);
    else sps__freeze_lanes(w, q, 3, SPS_KERNEL_WENDLAND_C2);
}

/* A list rebuild finds the lists SPS__LIST_CHUNK particles at a time (whole lane groups): a
   chunk's per-particle lists (at most ell_width each) go into list_chunk and from there into
   the lane slots, so that they never exist for every particle at once (for all of them, in 3D,
   they took more memory than the slots they fill). The chunk's size changes no result, only
   how often a parallel loop starts. */
#define SPS__LIST_CHUNK (128 * SPS__LANES)

/* A list rebuild under way. */
typedef struct sps__rebuild {
    long slots;                    /* the lane slots placed so far: the next group's first */
    int particles;                 /* the particles whose lists are placed */
    const unsigned char* restored; /* sps_world_restore: the file's lists, particle after
                                      particle (nb_count holds their counts); NULL: the lists
                                      are found in the cell grid */
    long read;                     /* ... the neighbours read from them so far */
} sps__rebuild;

/* Room for `slots` lane slots in every per-slot array (nb_j; nb_dw and nb_inv_r with frozen
   geometry; pair_force when paired): when they hold fewer, `want` (the slots the rebuild will
   place, estimated, at least `slots`) and an eighth more (a world with open-boundary zones: for
   its capacity of particles at the same slots per particle, so that the particles its zones
   create find theirs). Grown only when a rebuild places more than they hold, never shrunk, so
   that a scene in steady state does not allocate while it steps. The first `used` slots keep
   their values. Returns 0 when out of memory: every array as it was, or larger with its values. */
static int sps__ensure_slots(sps_world* w, long slots, long want, long used, int paired) {
    if (slots > w->slot_cap) {
        long cap = want > slots ? want : slots;
        cap += cap / 8;
        if (w->nzones && w->n > 0 && w->cap > w->n) cap = (long)((double)cap * w->cap / w->n);
        if (!sps__grow(w, &w->nb_j, sizeof(int), (size_t)used, (size_t)cap)) return 0;
        if (w->def.frozen_geometry && (!sps__grow(w, &w->nb_dw, sizeof(sps_real), (size_t)used, (size_t)cap) ||
                                       !sps__grow(w, &w->nb_inv_r, sizeof(sps_real), (size_t)used, (size_t)cap)))
            return 0;
        w->slot_cap = cap;
    }
    if (paired && w->pair_force_cap < w->slot_cap) {
        if (!sps__grow(w, &w->pair_force, sizeof(sps_real), (size_t)used, (size_t)w->slot_cap)) return 0;
        w->pair_force_cap = w->slot_cap;
    }
    return 1;
}

/* Room for `pairs` kept pair forces (SPS_ROTATION_PAIR: what sps__keep_pair_forces keeps of the
   lists just built, or what a restart file holds), an eighth more, grown like the slots, with
   every kept force (a failed configuration update leaves them for the next one). Returns 0
   when out of memory: the arrays as they were, or larger with their values. */
static int sps__ensure_kept(sps_world* w, long pairs) {
    const long room = pairs + pairs / 8;
    if (pairs <= w->kept_pair_cap) return 1;
    if (!sps__grow(w, &w->kept_force, sizeof(sps_real), (size_t)w->kept_pair_cap, (size_t)room) ||
        !sps__grow(w, &w->kept_neighbor_id, sizeof(int), (size_t)w->kept_pair_cap, (size_t)room))
        return 0;
    w->kept_pair_cap = room;
    return 1;
}

/* The first slots of body b's lane groups [g0, g1), from rb->slots on, each group as long as its
   longest list (a serial prefix sum: deterministic), and the slots grown to hold them (the
   estimate: the slots per particle placed so far, for every particle). */
static sps_result sps__lay_out_groups(sps_world* w, const sps__body* b, int g0, int g1, sps__rebuild* rb) {
    const int last = b->begin + g1 * SPS__LANES < b->end ? b->begin + g1 * SPS__LANES : b->end;
    long total = rb->slots;
    int g, l;
    for (g = g0; g < g1; ++g) {
        const int i0 = b->begin + g * SPS__LANES;
        int longest = 0;
        for (l = 0; l < SPS__LANES && i0 + l < b->end; ++l)
            if (w->nb_count[i0 + l] > longest) longest = w->nb_count[i0 + l];
        w->nb_group_start[b->group0 + g] = (int)total;
        total += (long)longest * SPS__LANES;
        if (total > INT_MAX) { /* the slot indices are ints */
            sps__set_error(w, 0, "out of memory: %ld neighbour slots and more at t = %g, beyond the %d the lane slots index", total,
                           (double)w->time, INT_MAX);
            return SPS_ERR_OUT_OF_MEMORY;
        }
    }
    w->nb_group_start[b->group0 + g1] = (int)total; /* the next group's first slot */
    rb->particles += last - (b->begin + g0 * SPS__LANES);
    if ((total > w->slot_cap || (b->model.paired && total > w->pair_force_cap)) &&
        !sps__ensure_slots(w, total, (long)((double)total * w->n / rb->particles), rb->slots, b->model.paired))
        return sps__oom(w, "the neighbour slots");
    rb->slots = total;
    return SPS_OK;
}

/* The len slots of particle i (a lane of its group, first slot s): its neighbours (list), then
   itself as padding; lanes past the body's end get padding only. */
static void sps__fill_particle_slots(sps_world* w, const sps__body* b, int i, int s, int len, const int* list) {
    const int count = i < b->end ? w->nb_count[i] : 0;
    int k;
    if (i < b->end) w->nb_first[i] = s;
    for (k = 0; k < len; ++k, s += SPS__LANES) w->nb_j[s] = k < count ? list[k] : i;
}

/* The lists of body b's particles [i0, i1) (whole lane groups; list_chunk holds them from i0 on)
   into the lane slots: each group's neighbours and padding, SPS_ROTATION_PAIR's pair forces
   carried over, the frozen geometry. */
static sps_result sps__place_chunk(sps_world* w, const sps__body* b, int i0, int i1, sps__rebuild* rb) {
    const int g0 = (i0 - b->begin) / SPS__LANES, g1 = (i1 - b->begin + SPS__LANES - 1) / SPS__LANES;
    const int frozen = w->def.frozen_geometry, width = w->ell_width;
    int g;
    sps_result r;
    if ((r = sps__lay_out_groups(w, b, g0, g1, rb)) != SPS_OK) return r;
    SPS__PARALLEL_FOR(w, i1 - i0)
    for (g = g0; g < g1; ++g) {
        const sps__group q = sps__group_of(w, b, g);
        int l;
        for (l = 0; l < SPS__LANES; ++l) {
            const int i = q.i0 + l;
            sps__fill_particle_slots(w, b, i, q.s0 + l, q.len, i < b->end ? w->list_chunk + (size_t)(i - i0) * width : NULL);
            if (b->model.paired) sps__carry_pair_forces(w, b, i, q.s0 + l, q.len);
        }
        if (frozen) sps__freeze_group(w, q);
    }
    return SPS_OK;
}

/* The lists of body b's particles [i0, i1) into list_chunk: found in the cell grid of positions
   x (the body sorted by cell, cell_of the sorted particles' cells). A list longer than
   ell_width stops the run. */
static sps_result sps__find_lists(sps_world* w, const sps__body* b, sps_real* const x[3], int i0, int i1) {
    const int dim = w->dim, width = w->ell_width, begin = b->begin;
    int i, overflow = -1;
    SPS__PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (i1 - i0 > 256) reduction(max : overflow))
    for (i = i0; i < i1; ++i) {
        int* list = w->list_chunk + (size_t)(i - i0) * width;
        const int c = w->cell_of[i - begin];
        const int m = w->periodic ? (dim == 2 ? sps__collect_neighbors(w, x, begin, i, c, list, width, 2, 1)
                                              : sps__collect_neighbors(w, x, begin, i, c, list, width, 3, 1))
                                  : (dim == 2 ? sps__collect_neighbors(w, x, begin, i, c, list, width, 2, 0)
                                              : sps__collect_neighbors(w, x, begin, i, c, list, width, 3, 0));
        w->nb_count[i] = m;
        if (m > width && i > overflow) overflow = i;
    }
    if (overflow >= 0) {
        sps__set_error(w, 0, "t = %g: particle %d of body '%s' has %d neighbours, more than the capacity %d "
                       "(particles are clustering; raise world def neighbor_capacity if the compression is physical)",
                       (double)w->time, w->id[overflow], b->name, w->nb_count[overflow], width);
        return SPS_ERR_UNSTABLE;
    }
    return SPS_OK;
}

/* The lists of particles [i0, i1) into list_chunk without a search: a restart file's
   (rb->restored; the counts are in nb_count), or none for a wall body (no pass reads its own
   neighbours). */
static void sps__read_lists(sps_world* w, int i0, int i1, sps__rebuild* rb) {
    int i, m, j;
    for (i = i0; i < i1; ++i) {
        if (!rb->restored) w->nb_count[i] = 0; /* a wall body */
        for (m = 0; m < w->nb_count[i]; ++m, ++rb->read) {
            memcpy(&j, rb->restored + sizeof(int) * (size_t)rb->read, sizeof j); /* unaligned in the payload */
            w->list_chunk[(size_t)(i - i0) * w->ell_width + m] = j;
        }
    }
}

/* A total-Lagrangian body's lane slots after its reference lists are found, slots [base, end):
   kept (reference_slots) for the rebuilds after this one, which place them again. Returns 0
   when out of memory. */
static int sps__keep_reference_slots(sps_world* w, sps__body* b, long base, long end) {
    sps__free(w, b->reference_slots);
    b->reference_slots = (int*)sps__alloc(w, sizeof(int) * (size_t)(end - base + 1));
    if (!b->reference_slots) return 0;
    memcpy(b->reference_slots, w->nb_j + base, sizeof(int) * (size_t)(end - base));
    return 1;
}

/* A total-Lagrangian body whose reference lists are built: the same lane slots again (its lists
   and particle order never change; its counts stay in nb_count) from rb->slots on. */
static sps_result sps__place_reference_slots(sps_world* w, const sps__body* b, sps__rebuild* rb) {
    const long base = rb->slots;
    int g;
    sps_result r;
    if ((r = sps__lay_out_groups(w, b, 0, b->ngroups, rb)) != SPS_OK) return r;
    memcpy(w->nb_j + base, b->reference_slots, sizeof(int) * (size_t)(rb->slots - base));
    SPS__PARALLEL_FOR(w, b->end - b->begin)
    for (g = 0; g < b->ngroups; ++g) {
        const sps__group q = sps__group_of(w, b, g);
        int l;
        for (l = 0; l < SPS__LANES && q.i0 + l < b->end; ++l) w->nb_first[q.i0 + l] = q.s0 + l;
        if (w->def.frozen_geometry) sps__freeze_group(w, q);
    }
    return SPS_OK;
}

/* Body b's neighbour lists (same body only) into the lane slots, chunk by chunk: its particles
   sorted by cell and their lists found in the cell grid, or a restart file's lists in its
   order (rb->restored). A total-Lagrangian body's lists are those of its reference positions,
   found once after each commit (and B_i with them, sps__tl_reference), then placed again with
   its particle order: neither is touched again. */
static sps_result sps__list_body(sps_world* w, sps__body* b, sps__rebuild* rb) {
    const int count = b->end - b->begin, search = !rb->restored && !b->model.material->kinematic;
    sps_real* const* x = b->model.total_lagrangian ? w->ref : w->pos;
    const long base = rb->slots;
    int i, i0, c, a, ncell;
    sps_result r;
    if (count == 0) return SPS_OK;
    if (b->model.total_lagrangian && b->reference_built) return sps__place_reference_slots(w, b, rb);
    if (search) {
        ncell = sps__setup_grid(w, x, b->begin, b->end);
        for (i = 0; i < count; ++i) {
            for (c = 0, a = w->dim - 1; a >= 0; --a) c = c * w->grid_n[a] + sps__cell_coord(w, a, x[a][b->begin + i]);
            w->cell_of[i] = c;
        }
        sps__sort_body(w, b, w->cell_of, ncell);
        /* sps__sort_keys left cell_start[c] = end of cell c: shift to starts, and note each
           sorted particle's cell */
        for (c = ncell; c > 0; --c) w->cell_start[c] = w->cell_start[c - 1];
        w->cell_start[0] = 0;
        for (c = 0; c < ncell; ++c)
            for (i = w->cell_start[c]; i < w->cell_start[c + 1]; ++i) w->cell_of[i] = c;
    }
    for (i0 = b->begin; i0 < b->end; i0 += SPS__LIST_CHUNK) {
        const int i1 = b->end - i0 > SPS__LIST_CHUNK ? i0 + SPS__LIST_CHUNK : b->end;
        if (search && (r = sps__find_lists(w, b, x, i0, i1)) != SPS_OK) return r;
        if (!search) sps__read_lists(w, i0, i1, rb);
        if ((r = sps__place_chunk(w, b, i0, i1, rb)) != SPS_OK) return r;
    }
    if (b->model.total_lagrangian) {
        if (!sps__keep_reference_slots(w, b, base, rb->slots)) return sps__oom(w, "the total-Lagrangian reference lists");
        sps__tl_reference(w, b);
    }
    return SPS_OK;
}

/* The neighbour lists of every body in lane-group slots (sps__list_body): found in the cell grid,
   or (restored, sps_world_restore) a restart file's lists, each particle's after the last's.
   Then the room for the pair forces sps__keep_pair_forces keeps of them, and each
   total-Lagrangian body's pair table, once per reference build. */
static sps_result sps__build_neighbors(sps_world* w, const unsigned char* restored) {
    sps__rebuild rb;
    long pairs = 0;
    int bi, i;
    sps_result r;
    rb.slots = 0;
    rb.particles = 0;
    rb.restored = restored;
    rb.read = 0;
    for (bi = 0; bi < w->nbodies; ++bi)
        if ((r = sps__list_body(w, &w->bodies[bi], &rb)) != SPS_OK) return r;
    if (w->nbodies) w->nb_group_start[w->bodies[w->nbodies - 1].group0 + w->bodies[w->nbodies - 1].ngroups] = (int)rb.slots;
    for (i = 0; i < w->n; ++i)
        if (w->bodies[w->body[i]].model.paired) pairs += w->nb_count[i];
    if (!sps__ensure_kept(w, pairs)) return sps__oom(w, "the kept pair forces");
    for (bi = 0; bi < w->nbodies; ++bi) { /* a total-Lagrangian body's table, once per reference build */
        sps__body* b = &w->bodies[bi];
        if (b->model.total_lagrangian && b->reference_built && b->tl_slots == 0 && (r = sps__tl_pair_table(w, b)) != SPS_OK) return r;
    }
    return SPS_OK;
}

/* SPS_ROTATION_PAIR: the len slots of particle i (a lane of its group, first slot s) take the
   force of the same pair from the copy kept at the end of the last step, found by the
   neighbour's id (the lists keep their order from one rebuild to the next, so the search
   resumes after the last hit); a new pair and the padding get 0. */
static void sps__carry_pair_forces(sps_world* w, const sps__body* b, int i, int s, int len) {
    const int count = i < b->end ? w->nb_count[i] : 0, id = i < b->end ? w->id[i] : -1;
    const int kept = id >= 0 && id < w->kept_ids ? w->kept_count[id] : 0;
    const int first = kept ? w->kept_first[id] : 0;
    int k, m, next = 0; /* the kept rank where the search starts */
    for (k = 0; k < len; ++k, s += SPS__LANES) {
        sps_real g = 0;
        if (k < count) {
            const int neighbor_id = w->id[w->nb_j[s]];
            int t = next;
            for (m = 0; m < kept; ++m, ++t) {
                if (t == kept) t = 0;
                if (w->kept_neighbor_id[first + t] == neighbor_id) {
                    g = w->kept_force[first + t];
                    next = t + 1;
                    break;
                }
            }
        }
        w->pair_force[s] = g;
    }
}

/* SPS_ROTATION_PAIR: keeps the pair forces, with the ids of both particles, for the next list
   rebuild (which may re-sort the particles and moves every slot): each particle's pairs
   contiguous from kept_first[its id], so the search in sps__carry_pair_forces reads one run. */
static void sps__keep_pair_forces(sps_world* w) {
    int i, first = 0;
    for (i = 0; i < w->n; ++i) { /* offsets: a prefix sum in particle order */
        const int count = w->bodies[w->body[i]].model.paired ? w->nb_count[i] : 0;
        w->kept_first[w->id[i]] = first;
        w->kept_count[w->id[i]] = count;
        first += count;
    }
    SPS__PARALLEL_FOR(w, w->n)
    for (i = 0; i < w->n; ++i) {
        const int id = w->id[i];
        int k;
        for (k = 0; k < w->kept_count[id]; ++k) {
            const int s = w->nb_first[i] + k * SPS__LANES;
            w->kept_neighbor_id[w->kept_first[id] + k] = w->id[w->nb_j[s]];
            w->kept_force[w->kept_first[id] + k] = w->pair_force[s];
        }
    }
    w->kept_ids = w->n;
}

/* >>linalg */

/* Inverse of a symmetric d x d matrix blended with the identity when nearly singular:
   B = w A^-1 + (1 - w) I, w = det^2 / (det^2 + 1e-6). Exact for well-posed A; bounded for
   isolated particles (their B tends to I instead of blowing up). A's entries xx xy xz yy yz zz
   are a[k as], B's nine (row-major, 3 per row) b[k bs]: strides so that the lane loops can keep
   one matrix per lane (stride SPS__LANES) and vectorise this branch-free code. */
SPS__INLINE void sps__blended_inverse(const sps_real* a, int as, sps_real* b, int bs, const int dim) {
    const sps_real xx = a[0], xy = a[as], yy = a[3 * as];
    const sps_real xz = dim == 3 ? a[2 * as] : 0, yz = dim == 3 ? a[4 * as] : 0, zz = dim == 3 ? a[5 * as] : 1;
    /* cofactors; in 2D zz = 1 and xz = yz = 0 reduce them to the 2x2 ones */
    const sps_real c00 = yy * zz - yz * yz, c01 = xz * yz - xy * zz, c02 = xy * yz - xz * yy;
    const sps_real c11 = xx * zz - xz * xz, c12 = xy * xz - xx * yz, c22 = xx * yy - xy * xy;
    const sps_real det = xx * c00 + xy * c01 + xz * c02;
    const sps_real scale = det / (det * det + SPS_R(1e-6)), keep = 1 - det * scale; /* w / det and 1 - w */
    b[0] = scale * c00 + keep;
    b[bs] = b[3 * bs] = scale * c01;
    b[4 * bs] = scale * c11 + keep;
    if (dim == 3) {
        b[2 * bs] = b[6 * bs] = scale * c02;
        b[5 * bs] = b[7 * bs] = scale * c12;
        b[8 * bs] = scale * c22 + keep;
    }
}

/* Adds pair (i, j)'s term to A = B_i^-1 = -sum_j r_ij (x) grad_i W_ij V_j (ANG eq. 21): with
   r_ij = r e_ij and grad W = dW e_ij, A -= r dW V_j e_ij (x) e_ij, rdwv = r dW V_j. A's entries
   xx xy xz yy yz zz at A[k as] (the lane sums of the continuity pass, or one matrix). The
   continuity pass and the diagnostics both build B this way. */
/* out = A B, or A B^T with transposed, for 3 x 3 row-major matrices (out aliases neither). */
SPS__INLINE void sps__mat3_product(const sps_real A[9], const sps_real B[9], int transposed, sps_real out[9]) {
    int a, c, k;
    SPS__UNROLL
    for (a = 0; a < 3; ++a)
        SPS__UNROLL
        for (c = 0; c < 3; ++c) {
            sps_real s = 0;
            SPS__UNROLL
            for (k = 0; k < 3; ++k) s += A[3 * a + k] * (transposed ? B[3 * c + k] : B[3 * k + c]);
            out[3 * a + c] = s;
        }
}

SPS__INLINE void sps__add_moment(sps_real* A, int as, sps_real ex, sps_real ey, sps_real ez, sps_real rdwv, const int dim) {
    A[0] -= rdwv * ex * ex;
    A[as] -= rdwv * ex * ey;
    A[3 * as] -= rdwv * ey * ey;
    if (dim == 3) {
        A[2 * as] -= rdwv * ex * ez;
        A[4 * as] -= rdwv * ey * ez;
        A[5 * as] -= rdwv * ez * ez;
    }
}

/* >>commit */

/* The mass-weighted centre of body b's positions x (the reference or the current ones). */
static void sps__centre_of_mass(const sps_world* w, const sps__body* b, sps_real* const x[3], sps_real c[3]) {
    sps_real m = 0;
    int i, a;
    c[0] = c[1] = c[2] = 0;
    for (i = b->begin; i < b->end; ++i) {
        m += w->mass[i];
        for (a = 0; a < w->dim; ++a) c[a] += w->mass[i] * x[a][i];
    }
    for (a = 0; a < w->dim && m > 0; ++a) c[a] /= m;
}

/* Each body's escape limit (world def escape_distance) around its own size, its reach from the
   reference centre of mass; set whenever particles were added. */
static void sps__set_escape_limits(sps_world* w) {
    int bi, i, a;
    for (bi = 0; bi < w->nbodies; ++bi) {
        sps__body* b = &w->bodies[bi];
        sps_real c[3], reach2 = 0, extra = w->def.escape_distance;
        sps__centre_of_mass(w, b, w->ref, c);
        for (i = b->begin; i < b->end; ++i) {
            sps_real d2 = 0;
            for (a = 0; a < w->dim; ++a) d2 += (w->ref[a][i] - c[a]) * (w->ref[a][i] - c[a]);
            if (d2 > reach2) reach2 = d2;
        }
        b->reach = SPS__SQRT(reach2);
        if (extra == 0) extra = 20 * b->reach > 100 * w->def.dp ? 20 * b->reach : 100 * w->def.dp; /* 10 body sizes */
        b->escape_limit = b->reach + extra;
    }
}

/* Sorts particles by body (after adds), sets body ranges and allocates what the scene needs:
   neighbour lists, scratch and the optional fields (velocity gradient, B, stress, rotation). */
/* SPS_ROTATION_PAIR storage by particle id: where each particle's kept pair forces start and how
   many (the forces themselves are per slot and per pair, sized at the list rebuilds:
   sps__ensure_slots). Grown with their contents: they describe the kept forces of the last
   step until the rebuild after this allocation reads them. */
static sps_result sps__ensure_pair_storage(sps_world* w) {
    if (w->kept_cap < w->cap) {
        if (!sps__grow(w, &w->kept_first, sizeof(int), (size_t)w->kept_cap, (size_t)w->cap) ||
            !sps__grow(w, &w->kept_count, sizeof(int), (size_t)w->kept_cap, (size_t)w->cap))
            return SPS_ERR_OUT_OF_MEMORY;
        w->kept_cap = w->cap;
    }
    return SPS_OK;
}

/* Whether body b's model needs the arrays of kind need (a per-body field's row, sps__fields).
   The world's arrays (NEED_ALWAYS, and those the first constraint or zone allocates) are not a
   body's: 0. Every need is a case and there is no default, so -Wswitch names a new one here. */
static int sps__body_needs(const sps__body* b, sps__need need) {
    const sps__model* m = &b->model;
    switch (need) {
    case SPS__NEED_ALWAYS:
    case SPS__NEED_CONSTRAINTS:
    case SPS__NEED_ZONES: return 0;
    case SPS__NEED_GRADIENT: return m->gradient;
    case SPS__NEED_STRESS: return m->stress;
    case SPS__NEED_MEAN_TURN: return m->turn == SPS__TURN_MEAN;
    case SPS__NEED_ARTIFICIAL: return m->artificial_stress;
    case SPS__NEED_PLASTIC: return m->plastic != SPS__YIELD_NONE;
    case SPS__NEED_SCALED_PENALTY: return m->scaled_penalty;
    case SPS__NEED_DRIVEN: return b->driven;
    case SPS__NEED_TRANSPORT: return m->transport != SPS_TRANSPORT_NONE;
    case SPS__NEED_DIFFUSION: return m->diffusion;
    case SPS__NEED_GRANULAR: return !m->pressure_of_density;
    case SPS__NEED_WALL_EQUILIBRIUM: return b->wall_equilibrium_needed;
    case SPS__NEED_TOTAL_LAGRANGIAN: return m->total_lagrangian;
    case SPS__NEED_TOTAL_LAGRANGIAN_PLASTIC: return m->total_lagrangian && m->plastic != SPS__YIELD_NONE;
    case SPS__NEED_DAMAGE: return m->damage;
    case SPS__NEED_KELVIN_VOIGT: return m->viscous == SPS__VISCOUS_KELVIN_VOIGT || b->def.contact_damping > 0;
    }
    return 0;
}

/* Body b's array(s) of the per-body field f for its count particles and the lane padding,
   zeroed past the field_count particles they held (which keep their values: a commit sorts
   the particles by body stably, so each body's particles keep their order and the new ones
   come last), with room for `room` particles (its count; a body with zones: the world's
   capacity, so that the particles its zones create fit without a new allocation). Returns 0
   when out of memory. */
static int sps__ensure_body_field(sps_world* w, sps__body* b, const sps__field_info* f, int room) {
    const size_t bytes = sps__field_bytes(f);
    int a;
    for (a = 0; a < sps__field_arrays(f); ++a) {
        char* x;
        memcpy(&x, sps__field_slot(w, b, f, a), sizeof x);
        if (x && room <= b->field_room) /* room enough (a body with zones): the new particles' slots zeroed */
            memset(x + bytes * (size_t)b->field_count, 0, bytes * (size_t)(b->field_room + SPS__LANES - b->field_count));
        else if (!sps__grow(w, sps__field_slot(w, b, f, a), bytes, x ? (size_t)b->field_count : 0, (size_t)room + SPS__LANES))
            return 0;
    }
    return 1;
}

static int sps__wants_wall_equilibrium(const sps_world* w, const sps__body* b); /* >>walls for fluids */
static sps_real sps__energy_round_off(const sps_world* w);                       /* >>guards */
static sps_result sps__commit(sps_world* w) {
    int i, bi, k;
    if (sps__trim_particle_arrays(w) != SPS_OK || sps__ensure_neighbor_storage(w) != SPS_OK) return SPS_ERR_OUT_OF_MEMORY;
    for (bi = 0; bi < w->nbodies; ++bi)
        if (w->bodies[bi].model.paired) {
            if (sps__ensure_pair_storage(w) != SPS_OK) return SPS_ERR_OUT_OF_MEMORY;
            break;
        }
    w->wall_equilibrium = 0;
    for (bi = 0; bi < w->nbodies; ++bi) {
        sps__body* b = &w->bodies[bi];
        const int room = b->zoned && w->cap > b->count ? w->cap : b->count, equilibrium = sps__wants_wall_equilibrium(w, b);
        w->wall_equilibrium |= equilibrium;
        if (b->field_count == b->count && room <= b->field_room && equilibrium == b->wall_equilibrium_needed) continue;
        b->wall_equilibrium_needed = equilibrium; /* a no-slip wall added after the first step: its array now */
        for (k = 0; k < SPS__NFIELDS; ++k)
            if (sps__fields[k].per_body && sps__body_needs(b, sps__fields[k].need) && !sps__ensure_body_field(w, b, &sps__fields[k], room))
                return SPS_ERR_OUT_OF_MEMORY;
        b->field_count = b->count;
        if (room > b->field_room) b->field_room = room;
    }
    for (bi = 0; bi < w->nbodies; ++bi) w->bodies[bi].reference_built = 0; /* the sort by body moves their ranges */
    w->allocated_for = w->cap;
    /* group particles by body (stable), then set ranges */
    sps__sort_by_body(w);
    for (bi = 0; bi < w->nbodies; ++bi) w->bodies[bi].begin = w->bodies[bi].end = 0;
    for (i = w->n - 1; i >= 0; --i) w->bodies[w->body[i]].begin = i;
    for (i = 0; i < w->n; ++i) w->bodies[w->body[i]].end = i + 1;
    for (bi = 0, i = 0; bi < w->nbodies; ++bi) {
        sps__body* b = &w->bodies[bi];
        b->group0 = i;
        b->ngroups = (b->end - b->begin + SPS__LANES - 1) / SPS__LANES;
        i += b->ngroups;
    }
    w->watch.noise = sps__energy_round_off(w); /* the energy watchdog's floor: it changes with the particles only */
    w->needs_sort_by_body = 0;
    return SPS_OK;
}

/* The per-particle neighbour storage, sized by the capacity, not the count, so that particles
   created up to it (open boundaries, sps_world_reserve) find theirs, and the list chunk: lists
   of at most a full lattice support (counted once for this dim, kernel and h/dp) times
   neighbor_capacity. The lane slots are sized from the counts at the list rebuilds
   (sps__ensure_slots). */
static sps_result sps__ensure_neighbor_storage(sps_world* w) {
    int lattice = 0, reach = (int)(w->support / w->def.dp) + 1, i, j, k, width;
    const int chunk = w->cap < SPS__LIST_CHUNK ? w->cap : SPS__LIST_CHUNK;
    size_t cap = (size_t)w->cap;
    for (i = -reach; i <= reach; ++i)
        for (j = -reach; j <= reach; ++j)
            for (k = (w->dim == 3 ? -reach : 0); k <= (w->dim == 3 ? reach : 0); ++k) {
                sps_real r = w->def.dp * SPS__SQRT((sps_real)(i * i + j * j + k * k));
                if ((i || j || k) && r < w->support) ++lattice;
            }
    width = (int)(lattice * w->def.neighbor_capacity) + 1;
    if (w->allocated_for >= w->cap && w->ell_width == width && w->scratch_zoned == (w->nzones > 0)) return SPS_OK;
    sps__free(w, w->nb_group_start); sps__free(w, w->nb_first); sps__free(w, w->nb_count); sps__free(w, w->list_chunk);
    sps__free(w, w->cell_of); sps__free(w, w->cell_start); sps__free(w, w->perm); sps__free(w, w->scratch);
    sps__free(w, w->group_sum);
    w->ell_width = 0; /* until every array below is there */
    w->cell_cap = 4 * w->cap + 64 + 1;
    w->group_cap = w->cap / SPS__LANES + w->nbodies + 1;
    w->nb_group_start = (int*)sps__alloc(w, sizeof(int) * ((size_t)w->group_cap + 1));
    w->nb_first = (int*)sps__alloc(w, sizeof(int) * cap);
    w->nb_count = (int*)sps__alloc(w, sizeof(int) * cap);
    w->list_chunk = (int*)sps__alloc(w, sizeof(int) * (size_t)chunk * (size_t)width);
    w->cell_of = (int*)sps__alloc(w, sizeof(int) * cap);
    w->cell_start = (int*)sps__alloc(w, sizeof(int) * ((size_t)w->cell_cap + (size_t)w->nbodies + 1));
    w->perm = (int*)sps__alloc(w, sizeof(int) * cap);
    w->scratch = sps__alloc(w, sizeof(sps_real) * cap * (w->nzones ? 5 : 1));
    w->scratch_zoned = w->nzones > 0;
    w->group_sum = (sps_real*)sps__alloc(w, sizeof(sps_real) * 9 * (size_t)w->group_cap);
    if (!w->nb_group_start || !w->nb_first || !w->nb_count || !w->list_chunk || !w->cell_of || !w->cell_start || !w->perm || !w->scratch ||
        !w->group_sum)
        return SPS_ERR_OUT_OF_MEMORY;
    w->ell_width = width;
    return SPS_OK;
}

/* >>pairs: the geometry of a neighbour pair */

/* Pair geometry modes, a literal in the neighbour loops so they carry no branch on it: the
   stored geometry, or recomputed with the Wendland C2 or the cubic-spline kernel, or
   recomputed from the nearest periodic image with the world's kernel (a world with a periodic
   axis, chapter >>periodic: the other modes carry none of its arithmetic). */
enum { SPS__GEO_WENDLAND, SPS__GEO_SPLINE, SPS__GEO_FROZEN, SPS__GEO_PERIODIC, SPS__GEO_MODES };
/* The kernel of pair geometry geo: a literal for the recomputed modes (the loops carry no
   branch on it), the world's for the frozen and periodic ones. */
SPS__INLINE int sps__geo_kernel(const sps_world* w, const int geo) {
    return geo == SPS__GEO_SPLINE ? SPS_KERNEL_CUBIC_SPLINE : geo == SPS__GEO_WENDLAND ? SPS_KERNEL_WENDLAND_C2 : w->def.kernel;
}
/* The pair geometry recomputed from the current positions (not the stored one). */
static int sps__plain_geo(const sps_world* w) {
    return w->periodic ? SPS__GEO_PERIODIC : w->def.kernel == SPS_KERNEL_CUBIC_SPLINE ? SPS__GEO_SPLINE : SPS__GEO_WENDLAND;
}
/* The pair geometry of the world's passes. */
static int sps__geo(const sps_world* w) {
    return w->def.frozen_geometry ? SPS__GEO_FROZEN : sps__plain_geo(w); /* frozen is not periodic (sps__periodic_check) */
}
static int sps__mode(const sps_world* w) {
    return (w->dim == 3) * SPS__GEO_MODES + sps__geo(w);
}

/* Pair geometry of slot s = (i, j) from the offset x_i - x_j = (dx, dy, dz): e_ij, dW/dr,
   dW/dr / r_ij and r_ij; when frozen, dW/dr is the configuration update's. A padding slot (j = i) gives
   zeros: stored zeros when frozen, and here r = 1 with dW = 0 (no division by zero). Returned by
   value (no addressable locals) so the neighbour loops that call it vectorise. */
typedef struct sps__pair_geometry {
    sps_real ex, ey, ez, dw, dw_r, r;
} sps__pair_geometry;

SPS__INLINE sps__pair_geometry sps__pair_of_offset(const sps_world* w, int s, sps_real dx, sps_real dy, sps_real dz, const int geo) {
    sps__pair_geometry q;
    if (geo == SPS__GEO_FROZEN) {
        /* dW as stored, but e_ij and 1/r from the current positions: a stored direction lags a
           rotating pair, and e_0.v_ij = -r w sin(w t) < 0 whatever the sense of rotation, so
           every rotating pair would look as if it were shortening, and ENO-A's accumulated
           shear and the density would drift (measured: the 2D plate's period grew 0.55% per
           cycle). A stored 1/r would misjudge v_ij / r_ij against L e_ij by the strain since
           the update, which GNO's penalty (ANG eq. 43) amplifies (GNO-A at H/dp 30: period
           -1.6%). 1/|x_ij| is the stored 1/r_0 after one Newton step (relative error 1.5 x the
           square of the strain since the update; the factor is kept >= 1/2, so e_ij never
           turns round however far the pair stretches). */
        const sps_real r2 = dx * dx + dy * dy + dz * dz, inv_r0 = w->nb_inv_r[s], t = r2 * inv_r0 * inv_r0;
        const sps_real inv_r = inv_r0 * (SPS_R(1.5) - SPS_R(0.5) * (t < 2 ? t : 2));
        q.ex = dx * inv_r;
        q.ey = dy * inv_r;
        q.ez = dz * inv_r;
        q.dw = w->nb_dw[s];
        q.dw_r = q.dw * inv_r;
        q.r = r2 * inv_r;
    } else {
        /* pad: a padding slot (j = i) or two particles at the same point, which have no
           direction between them and no force (dW(0) = 0): both take e = 0, dW = 0 */
        if (geo == SPS__GEO_PERIODIC) { /* the nearest image (chapter >>periodic) */
            dx = sps__nearest_image(w, 0, dx);
            dy = sps__nearest_image(w, 1, dy);
            dz = sps__nearest_image(w, 2, dz);
        }
        const sps_real r2 = dx * dx + dy * dy + dz * dz;
        const sps_real pad = (sps_real)(r2 == 0), r = SPS__SQRT(r2 == 0 ? 1 : r2), inv = 1 / r; /* a select, not r2 + pad: GCC
                                                    would branch round the add, and AVX2 (no masked add) could not vectorise it */
        q.ex = dx * inv;
        q.ey = dy * inv;
        q.ez = dz * inv;
        q.dw = (1 - pad) * w->dw_scale * sps__kernel_df(sps__geo_kernel(w, geo), r * w->inv_h);
        q.dw_r = q.dw * inv;
        q.r = r;
    }
    return q;
}

/* The pair geometry of slot s = (i, j) from the current positions (sps__pair_of_offset). */
SPS__INLINE sps__pair_geometry sps__pair(const sps_world* w, int i, int s, int j, const int dim, const int geo) {
    const sps_real dx = w->pos[0][i] - w->pos[0][j], dy = w->pos[1][i] - w->pos[1][j];
    const sps_real dz = dim == 3 ? w->pos[2][i] - w->pos[2][j] : 0;
    return sps__pair_of_offset(w, s, dx, dy, dz, geo);
}

/* The pair geometry of slot s = (i, j) at the positions before the half drift x += h v of this
   sub-step (sps__drift_range): x - h v, x^(n+1) in sub-step n+1's pressure pass. */
SPS__INLINE sps__pair_geometry sps__pair_before_drift(const sps_world* w, int i, int s, int j, const int dim, const int geo, sps_real h) {
    const sps_real dx = w->pos[0][i] - w->pos[0][j] - h * (w->vel[0][i] - w->vel[0][j]);
    const sps_real dy = w->pos[1][i] - w->pos[1][j] - h * (w->vel[1][i] - w->vel[1][j]);
    const sps_real dz = dim == 3 ? w->pos[2][i] - w->pos[2][j] - h * (w->vel[2][i] - w->vel[2][j]) : 0;
    return sps__pair_of_offset(w, s, dx, dy, dz, geo);
}

/* Correction matrices B_i (ANG eq. 21) from the current positions into out (9 per particle,
   row-major), summed and inverted as in the continuity pass (sps__add_moment), and the trace of
   B_i^-1, the position divergence (UTVF eq. 31), into divr. */
static void sps__correction_matrices(sps_world* w, int begin, int end, sps_real* out, sps_real* divr) {
    const int geo = sps__plain_geo(w);
    int i;
    SPS__PARALLEL_FOR(w, end - begin)
    for (i = begin; i < end; ++i) {
        sps_real A[6] = {0, 0, 0, 0, 0, 0}, *B = out + (size_t)9 * i;
        int k;
        for (k = 0; k < 9; ++k) B[k] = 0;
        for (k = 0; k < w->nb_count[i]; ++k) {
            const int j = sps__neighbor(w, i, k);
            const sps__pair_geometry e = sps__pair(w, i, w->nb_first[i] + k * SPS__LANES, j, w->dim, geo);
            sps__add_moment(A, 1, e.ex, e.ey, e.ez, e.r * (e.dw * w->vol[j]), w->dim);
        }
        if (w->dim == 2) sps__blended_inverse(A, 1, B, 1, 2);
        else sps__blended_inverse(A, 1, B, 1, 3);
        divr[i] = A[0] + A[3] + (w->dim == 3 ? A[5] : 0);
    }
}

/* >>solver: the updated-Lagrangian passes (ENO section 5, ANG sections 3-4): each pass a kernel
   per lane group that runs the body's pair loop, one instance per dimension, pair geometry and
   pair terms (SPS__INSTANCES), and then the pass's finish, compiled per dimension only */

/* The first of body b's lane groups (of the group starts `start`, ngroups + 1 of them) whose
   first slot is at or after slot `target`. */
static int sps__group_at_slot(const int* start, int ngroups, long target) {
    int lo = 0, hi = ngroups;
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (start[mid] < target) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

/* The calling thread's number *me in a team of *nt (0 of 1 outside a parallel region). */
static void sps__team_rank(int* nt, int* me) {
    *nt = 1;
    *me = 0;
#ifdef _OPENMP
    *nt = omp_get_num_threads();
    *me = omp_get_thread_num();
#endif
}

/* The lane groups [g0, g1) of body b that the calling thread runs in a neighbour pass: the
   body's slots split evenly, since a group costs about its slots (an even split of the groups
   left one of two threads 6% more slots on the 2D plate). Every group has exactly one owner:
   neighbouring threads compute their common bound the same way. */
static void sps__group_share(const sps_world* w, const sps__body* b, int* g0, int* g1) {
    const int* start = w->nb_group_start + b->group0;
    const long first = start[0], total = start[b->ngroups] - first;
    int nt, me;
    sps__team_rank(&nt, &me);
    *g0 = me == 0 ? 0 : sps__group_at_slot(start, b->ngroups, first + total * me / nt);
    *g1 = me == nt - 1 ? b->ngroups : sps__group_at_slot(start, b->ngroups, first + total * (me + 1) / nt);
}

/* The `count` entries of a per-particle array (count values per particle, particle k of the
   array at count k) of the SPS__LANES particles from array index first, side by side: out[a][l]
   is entry a of lane l. A pair loop reads its lanes' own tensors from here, not as a strided
   group of count values, which GCC vectorises only for 1, 2, 3 or 4. */
SPS__INLINE void sps__own_lanes(const sps_real* array, int count, int first, sps_real (*out)[SPS__LANES]) {
    int a, l;
    for (a = 0; a < count; ++a)
        for (l = 0; l < SPS__LANES; ++l) out[a][l] = array[count * (first + l) + a];
}

/* The pair loop of every neighbour pass, the skeleton each pass fills with its terms: for each
   neighbour rank k of lane group q, the lanes l side by side in one SIMD loop, each with its
   particle i, its neighbour j (i itself in padding slots), the slot s and the pair geometry e
   (sps__pair) declared for TERMS, the pass's statements, which add to the lanes' sums. Each lane
   sums its own particle's neighbours in list order, so no result depends on the vector width.
   k and l are the caller's ints. SPS__PAIR_NEIGHBOR(js_, l) is lane l's neighbour; the
   speed probe bench/pass_bound.c redefines it as js_[0], one neighbour for every lane, read
   without gathers, to time a pass's arithmetic alone. */
#ifndef SPS__PAIR_NEIGHBOR
#define SPS__PAIR_NEIGHBOR(js_, l) (js_)[l]
#endif
#define SPS__PAIR_LOOP(w, q, dim, geo, k, l, ...)                                            \
    for (k = 0; k < (q).len; ++k) {                                                          \
        const int* SPS__RESTRICT js_ = (w)->nb_j + (q).s0 + k * SPS__LANES;                 \
        SPS__PRAGMA(omp simd)                                                                \
        for (l = 0; l < SPS__LANES; ++l) {                                                   \
            const int i = (q).i0 + l, s = (q).s0 + k * SPS__LANES + l, j = SPS__PAIR_NEIGHBOR(js_, l); \
            const sps__pair_geometry e = sps__pair(w, i, s, j, dim, geo);                    \
            __VA_ARGS__                                                                      \
        }                                                                                    \
    }

/* Runs a pass kernel over the lane groups of body b that the calling thread owns
   (sps__group_share), then waits for the other threads. */
static void sps__run_groups(sps_world* w, const sps__body* b, sps__group_kernel kernel, sps_real dt) {
    int g, g0, g1;
    if (!kernel) return; /* a body without this pass (a wall body): no barrier needed either */
    sps__group_share(w, b, &g0, &g1);
    for (g = g0; g < g1; ++g) kernel(w, b, g, dt);
    SPS__PRAGMA(omp barrier)
}

/* The pair terms of a pair loop's instance: a bit set, a literal in each instance (SPS__INSTANCES)
   so that the loop carries no branch on them. */
enum {
    SPS__TERM_STRESS = 1 << 0,    /* pressure: the divergence of the shear stress (OG family) */
    SPS__TERM_PAIRED = 1 << 1,    /* pressure: the accumulated pair forces; continuity, penalty: the
                                     increments go to the pair forces (SPS_ROTATION_PAIR) */
    SPS__TERM_LIMITED = 1 << 2,   /* pressure: the Riemann dissipation limiter (fluids, granular bodies) */
    SPS__TERM_NEWTON = 1 << 3,    /* pressure: a fluid's Newtonian viscous force */
    SPS__TERM_ART = 1 << 4,       /* rare pressure terms: Gray et al.'s artificial stress (OAS) */
    SPS__TERM_DAMPING = 1 << 5,   /* rare pressure terms: a solid's Kelvin-Voigt damping */
    SPS__TERM_GRADIENT = 1 << 6,  /* continuity: the velocity gradient's sums M and A */
    SPS__TERM_LAPLACIAN = 1 << 7, /* continuity: ENO's Laplacian per particle */
    SPS__TERM_RIEMANN = 1 << 8,   /* continuity: the Riemann solver's density term (fluids) */
    SPS__TERM_PROJECTED = 1 << 9, /* penalty: projected on e_ij (GNO-A) */
    SPS__TERM_SCALED = 1 << 10,   /* penalty: scaled by the return factors (plastic bodies) */
    SPS__TERM_DIFFUSION = 1 << 11, /* pressure: a granular body's stress diffusion is stored (its loop
                                     sums it in any case: a row, not a loop of its own) */
    SPS__TERM_PENALTY = 1 << 12,   /* pressure: also the previous sub-step's GNO penalty sums
                                     (penalty_in_pressure_pass), PROJECTED and SCALED as the penalty's */
    SPS__TERM_DIVERGENCE = 1 << 13, /* continuity, with RIEMANN: a fluid's velocity divergence as the pair
                                     sum, scaled as its pressure force (sps__continuity_pairs) */
    SPS__TERM_GRANULAR = 1 << 14  /* pressure: a Drucker-Prager body's terms: its stress divergence scaled
                                     as a fluid's pressure force, its stress diffusion's sums
                                     (sps__kind_pressure_terms, sps__kind_pressure_pair) */
};

/* The sums of a pass's pair loop, per lane, that it hands to the pass's finish: lane arrays
   (contiguous per entry, so the lanes vectorise), their rows named by the pass's enum. */
/* continuity: density rate, Laplacian, uncorrected velocity gradient M (row-major) and the
   symmetric A = B^-1 */
enum {
    SPS__DRHO, SPS__LX, SPS__LY, SPS__LZ,
    SPS__M00, SPS__M01, SPS__M02, SPS__M10, SPS__M11, SPS__M12, SPS__M20, SPS__M21, SPS__M22,
    SPS__A00, SPS__A01, SPS__A02, SPS__A11, SPS__A12, SPS__A22, SPS__NSUM
};
/* pressure: the acceleration's sum, Gray's artificial stress, the accumulated shear forces, the
   stress diffusion's rate, the Kelvin-Voigt damping (with the Riemann dissipation); with the
   penalty in the pressure pass, the penalty's sums after them */
enum {
    SPS__ACC = 0, SPS__GRAY = 3, SPS__SHEAR = 5, SPS__SPREAD = 8, SPS__DAMP = SPS__SPREAD + SPS__SPREAD_ROWS,
    SPS__PRESSURE_SUMS = SPS__DAMP + 3, SPS__PENALTY_SUMS = SPS__PRESSURE_SUMS
};
enum { SPS__SUM_ROWS = SPS__PENALTY_SUMS + 3 > SPS__NSUM ? SPS__PENALTY_SUMS + 3 : SPS__NSUM };
typedef struct sps__lane_sums {
    sps_real row[SPS__SUM_ROWS][SPS__LANES];
} sps__lane_sums;

/* Zeroes the first `rows` rows of sums. */
static void sps__clear_sums(sps__lane_sums* sums, int rows) {
    int t, l;
    for (t = 0; t < rows; ++t)
        for (l = 0; l < SPS__LANES; ++l) sums->row[t][l] = 0;
}

/* A pair loop's instances and its mode table sps__<loop>_<variant>[mode] (sps__mode: dimension x
   pair geometry). The Wendland C2 kernel's geometries (recomputed from the positions, the
   default; frozen_geometry; a periodic world's) have an instance per dimension and set of pair
   terms, a named function (it shows up in a profiler) that calls the loop's body with the
   dimension, the pair geometry and the terms (an SPS__TERM_ bit set) literals, so that its loop
   carries no branch. The cubic spline kernel runs the pass's generic loop of the dimension, one
   function per pass and dimension (SPS__GENERIC_LOOPS) that reads the pair geometry and the
   terms at run time: the same operations in the same order, so the same results bit for bit,
   but not vectorised: about 3x the cost of an instance (bench/VALIDATION.md, "Instances for the
   Wendland kernel only"); SPHSOLID_ALL_PAIR_LOOPS (CONFIG MACROS) instances it too. Only the pair loops are instanced: a pass's
   finish, what it does once per lane group after the loop (the velocity gradient's correction,
   the stress update and return maps, the rotations, the increments' store), reads the body's
   model at run time and is compiled once per dimension. An instance for every mode and set of
   terms (248 pair loops) took half of the implementation's compile time. */
#define SPS__INSTANCE(loop, variant, mode, dim, geo, terms)                                                     \
    static void sps__##loop##_##variant##_##mode(sps_world* w, const sps__body* b, int g, sps_real dt,         \
                                                 int terms_of_call, sps__lane_sums* SPS__RESTRICT sums) {       \
        (void)terms_of_call; /* the instance's terms are its literal */                                         \
        sps__##loop(w, b, g, dt, sums, dim, geo, terms);                                                        \
    }
/* The rare mode of dimension dim in a mode table (the cubic spline kernel): its instances with
   SPHSOLID_ALL_PAIR_LOOPS, else the pass's generic loop of the dimension, defined once per pass
   (SPS__GENERIC_LOOPS). */
#ifdef SPHSOLID_ALL_PAIR_LOOPS
#define SPS__GENERIC_LOOPS(loop)
#define SPS__RARE_INSTANCES(loop, variant, dim, terms) SPS__INSTANCE(loop, variant, dim##d_spline, dim, SPS__GEO_SPLINE, terms)
#define SPS__RARE_MODE(loop, variant, dim) sps__##loop##_##variant##_##dim##d_spline
#else
#define SPS__GENERIC_LOOP(loop, dim)                                                                            \
    static void sps__##loop##_generic_##dim##d(sps_world* w, const sps__body* b, int g, sps_real dt, int terms, \
                                               sps__lane_sums* SPS__RESTRICT sums) {                            \
        sps__##loop(w, b, g, dt, sums, dim, sps__geo(w), terms);                                                \
    }
#define SPS__GENERIC_LOOPS(loop) SPS__GENERIC_LOOP(loop, 2) SPS__GENERIC_LOOP(loop, 3)
#define SPS__RARE_INSTANCES(loop, variant, dim, terms)
#define SPS__RARE_MODE(loop, variant, dim) sps__##loop##_generic_##dim##d
#endif
/* The instances of a pair loop in dimension dim: the default geometry, frozen_geometry's (the
   reference code's stored geometry, a speed knob in double) and a periodic world's (the channels
   and boxes of fluids), then the rare mode. In the mode table's order (sps__geo's). */
#define SPS__INSTANCES_OF_DIM(loop, variant, dim, terms)                                                        \
    SPS__INSTANCE(loop, variant, dim##d_wendland, dim, SPS__GEO_WENDLAND, terms)                                \
    SPS__INSTANCE(loop, variant, dim##d_frozen, dim, SPS__GEO_FROZEN, terms)                                    \
    SPS__INSTANCE(loop, variant, dim##d_periodic, dim, SPS__GEO_PERIODIC, terms)                                \
    SPS__RARE_INSTANCES(loop, variant, dim, terms)
#define SPS__MODES_OF_DIM(loop, variant, dim)                                                                   \
    sps__##loop##_##variant##_##dim##d_wendland, SPS__RARE_MODE(loop, variant, dim),                            \
        sps__##loop##_##variant##_##dim##d_frozen, sps__##loop##_##variant##_##dim##d_periodic
#define SPS__INSTANCES(loop, variant, terms)                                                                    \
    SPS__INSTANCES_OF_DIM(loop, variant, 2, terms)                                                              \
    SPS__INSTANCES_OF_DIM(loop, variant, 3, terms)                                                              \
    static const sps__pair_loop sps__##loop##_##variant[2 * SPS__GEO_MODES] = {                                 \
        SPS__MODES_OF_DIM(loop, variant, 2), SPS__MODES_OF_DIM(loop, variant, 3)};
/* The instances of a 2D-only term (OAS's: a combination rule refuses it in 3D): none in 3D, where
   the mode table holds NULL (sps__missing_pass would name the combination). */
#define SPS__INSTANCES_2D_ONLY(loop, variant, terms)                                                            \
    SPS__INSTANCES_OF_DIM(loop, variant, 2, terms)                                                              \
    static const sps__pair_loop sps__##loop##_##variant[2 * SPS__GEO_MODES] = {                                 \
        SPS__MODES_OF_DIM(loop, variant, 2), NULL, NULL, NULL, NULL};

/* The dissipation limiter of a pair approaching at -u (u = v_ij . e_ij), eta_c0 = eta / c0:
   beta = min(eta max(-u / c0, 0), 1) (UTVF eq. 20). Branch-free for the lane loops. */
SPS__INLINE sps_real sps__riemann_limiter(sps_real u, sps_real eta_c0) {
    const sps_real beta = -u * eta_c0;
    return beta > 1 ? 1 : beta > 0 ? beta : 0;
}

/* u = v_ij . e_ij of pair (i, j) with direction (ex, ey, ez). */
SPS__INLINE sps_real sps__approach(const sps_world* w, int i, int j, sps_real ex, sps_real ey, sps_real ez, const int dim) {
    const sps_real *SPS__RESTRICT vx = w->vel[0], *SPS__RESTRICT vy = w->vel[1], *SPS__RESTRICT vz = w->vel[2];
    return (vx[i] - vx[j]) * ex + (vy[i] - vy[j]) * ey + (dim == 3 ? (vz[i] - vz[j]) * ez : 0);
}

/* The GNO penalty's term of a pair: v^_ij / r_ij dW per axis and the pair's weight. */
typedef struct sps__penalty_velocity {
    sps_real v[3], scale;
} sps__penalty_velocity;

/* The GNO penalty's term of pair (i, j) in lane l with geometry e (sps__penalty_pairs; the
   pressure pass sums it too with penalty_in_pressure_pass): v^_ij / r_ij dW = v_ij dW/r -
   1/2 (L_i + L_j) e_ij dW per axis (ANG eq. 44 with r_ij = r e_ij), weighted by the scale
   1/2 (r_i + r_j) when scaled (1 unscaled); L_i the lanes' own gradients. Returned by value, as
   sps__pair, so that the loops vectorise. */
SPS__INLINE sps__penalty_velocity sps__penalty_term(const sps_world* w, const sps__body* b, int i, int j, int l, sps__pair_geometry e,
                                                    sps_real L_i[9][SPS__LANES], const int dim, const int scaled) {
    const sps_real* SPS__RESTRICT L = b->grad;
    const sps_real* SPS__RESTRICT factor = b->return_factor; /* J2 and Drucker-Prager bodies only */
    const sps_real *SPS__RESTRICT vx = w->vel[0], *SPS__RESTRICT vy = w->vel[1], *SPS__RESTRICT vz = w->vel[2];
    const int begin = b->begin, lj = 9 * (j - begin); /* an int offset from the array: a gather */
    const sps_real dv[3] = {vx[i] - vx[j], vy[i] - vy[j], dim == 3 ? vz[i] - vz[j] : 0};
    const sps_real dir[3] = {e.ex, e.ey, e.ez};
    sps__penalty_velocity t;
    int a, c;
    t.scale = scaled ? SPS_R(0.5) * (factor[i - begin] + factor[j - begin]) : 1;
    t.v[2] = 0;
    SPS__UNROLL
    for (a = 0; a < dim; ++a) {
        sps_real le = 0;
        SPS__UNROLL
        for (c = 0; c < dim; ++c) le += (L_i[3 * a + c][l] + L[lj + 3 * a + c]) * dir[c];
        t.v[a] = dv[a] * e.dw_r - SPS_R(0.5) * le * e.dw;
        if (scaled) t.v[a] *= t.scale;
    }
    return t;
}

/* Adds the penalty term t of a pair with geometry e and neighbour volume V_j to lane l's sums:
   v^_ij / r_ij dW V_j (GNO, ANG eq. 43) or its projection on e_ij (GNO-A, ANG eq. 46). */
SPS__INLINE void sps__add_penalty_term(sps_real (*sum)[SPS__LANES], int l, sps__penalty_velocity t, sps__pair_geometry e, sps_real vol_j,
                                       const int dim, const int projected) {
    const sps_real dir[3] = {e.ex, e.ey, e.ez};
    sps_real vhat[3], u = 0;
    int a;
    SPS__UNROLL
    for (a = 0; a < dim; ++a) {
        vhat[a] = t.v[a] * vol_j;
        u += vhat[a] * dir[a];
    }
    SPS__UNROLL
    for (a = 0; a < dim; ++a) sum[a][l] += projected ? u * dir[a] : vhat[a];
}

/* >>generic (continued): the updated-Lagrangian passes' hooks: the pressure pass's terms of a
   kind's own (its pair terms, their store) */

/* The pressure pass's pair terms of a kind's own (sps__pressure_terms): Drucker-Prager's
   (SPS__TERM_GRANULAR); 0 for a kind that has none. */
static int sps__kind_pressure_terms(sps_material_kind kind) {
    switch (kind) {
    case SPS_MATERIAL_DRUCKER_PRAGER: return SPS__TERM_GRANULAR;
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_J2:
    case SPS_MATERIAL_FLUID:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: return 0;
    }
    return 0;
}

/* The constants of the pair terms of a kind's own, one part per kind that has such terms, loaded
   by sps__kind_pressure_constants_of once before the pair loop (read in the loop, the loads
   stay in it and the instance's code changes). */
typedef struct sps__kind_pressure_constants {
    sps__granular_pair_constants granular; /* SPS__TERM_GRANULAR */
} sps__kind_pressure_constants;
SPS__INLINE sps__kind_pressure_constants sps__kind_pressure_constants_of(const sps_world* w, const sps__body* b) {
    sps__kind_pressure_constants c;
    c.granular = sps__granular_pair_constants_of(w);
    (void)b;
    return c;
}

/* The pair terms of a kind's own in the pressure pass (terms: the instance's literal, whose
   kind bits sps__kind_pressure_terms gives), lane l of the pair (i, j) with geometry e: j's
   deviator at tau + tj, V_j and the pressures p; into the kind's rows of the sums (SPS__SPREAD).
   Inlined into the pair loop, so that an instance without the bits has no trace of them (the
   instances with them compile to the instructions of the terms written in the loop). */
SPS__INLINE void sps__kind_pressure_pair(const sps__kind_pressure_constants* c, sps__lane_sums* sums, int l, const sps_real* tau, int tj,
                                         sps__pair_geometry e, sps_real vol_j, const sps_real* p, int j, const int dim, const int terms) {
    if (terms & SPS__TERM_GRANULAR)
        sps__granular_diffusion_pair(&c->granular, sums->row + SPS__SPREAD, l, tau, tj, e.r, e.dw, vol_j, e.ex, e.ey, e.ez, p, j, dim);
}

/* The pressure pass's finish of a kind's own sums for lane group q, where the body's model
   stores them: Drucker-Prager's stress diffusion rate (model.diffusion). */
SPS__INLINE void sps__kind_pressure_store(const sps_world* w, const sps__body* b, sps__group q, sps__lane_sums* sums) {
    if (b->model.diffusion) sps__granular_store_diffusion(w, b, q.i0, sums->row + SPS__SPREAD);
}

/* >>solver: the updated-Lagrangian passes (continued): the pressure pass */

/* Pressure pass (step 2) for the particles of lane group g: Riemann pressure force with
   beta = 1 and Z = rho0 c0; with stress (OG family) also the divergence of the shear stress
   (ENO eq. 17); with paired (SPS_ROTATION_PAIR) the accumulated shear forces (1/m_i) sum_j g_ij
   e_ij along the current e_ij. For fluids, with limited, the dissipation Z beta with the limiter
   beta = min(eta max(-v_ij . e_ij / c0, 0), 1) (UTVF eq. 20: only approaching pairs, fully from
   a 1/eta of c0 on), and with newton the Newtonian viscous force
   (2 mu / rho_i) sum_j v_ij dW / r_ij V_j (Morris et al. 1997) divided by the lattice moment
   (sps__fluid_rest_gradient; dW/r stays finite as r -> 0 for both kernels). A fluid's pressure force and a granular body's divergence (limited)
   are scaled (sps__lattice_gradient_moment); a kind's own pair terms are summed by
   sps__kind_pressure_pair (a granular body's stress diffusion, stored where its def has it).
   The rare terms, which add to sums of their own, have a pair loop of their own
   (sps__rare_pressure_pairs); a Kelvin-Voigt body's Riemann dissipation is among them (kept
   with its viscous force, for its work), so its pressure force here has Z = 0, which leaves
   (p_i + p_j) dW V_j bit for bit. With penalty (penalty_in_pressure_pass) the loop also sums the
   previous sub-step's GNO penalty terms into rows SPS__PENALTY_SUMS in that penalty's pair
   geometry (sps__pair_before_drift; chapter >>solver: the penalty in the next pressure pass).
   Each lane sums its own particle's neighbours in list order, so the result does not depend on
   the vector width. */
SPS__INLINE void sps__pressure_pairs(sps_world* w, const sps__body* b, int g, sps_real dt, sps__lane_sums* SPS__RESTRICT sums, const int dim,
                                     const int geo, const int terms) {
    const int stress = (terms & SPS__TERM_STRESS) != 0, paired = (terms & SPS__TERM_PAIRED) != 0;
    const int limited = (terms & SPS__TERM_LIMITED) != 0, newton = (terms & SPS__TERM_NEWTON) != 0;
    const int granular = (terms & SPS__TERM_GRANULAR) != 0; /* its stress divergence scaled too */
    const int penalty = (terms & SPS__TERM_PENALTY) != 0, projected = (terms & SPS__TERM_PROJECTED) != 0;
    const int scaled = (terms & SPS__TERM_SCALED) != 0;
    const sps__group q = sps__group_of(w, b, g);
    const sps_real z = b->model.viscous == SPS__VISCOUS_KELVIN_VOIGT ? 0 : b->z_riemann, eta_c0 = limited ? b->limiter_eta_c0 : 0;
    const sps_real scale = limited ? b->divergence_scale : 1; /* fluid, granular: sps__lattice_gradient_moment */
    const sps_real two_mu = b->viscous_coefficient;
    const sps__kind_pressure_constants kind_constants = sps__kind_pressure_constants_of(w, b);
    const int begin = b->begin; /* the body's own arrays (tau) hold particle begin + k at k */
    const sps_real *SPS__RESTRICT p = w->p, *SPS__RESTRICT vol = w->vol, *SPS__RESTRICT tau = b->tau;
    const sps_real *SPS__RESTRICT vx = w->vel[0], *SPS__RESTRICT vy = w->vel[1], *SPS__RESTRICT vz = w->vel[2];
    const sps_real* SPS__RESTRICT pair_force = w->pair_force;
    sps_real(*acc)[SPS__LANES] = sums->row + SPS__ACC;
    sps_real(*shear)[SPS__LANES] = sums->row + SPS__SHEAR;
    sps_real(*penalty_sum)[SPS__LANES] = sums->row + SPS__PENALTY_SUMS;
    sps_real tau_i[6][SPS__LANES], L_i[9][SPS__LANES];
    int k, l;
    (void)dt;
    if (stress) sps__own_lanes(tau, 6, q.i0 - begin, tau_i);
    if (penalty) sps__own_lanes(b->grad, 9, q.i0 - begin, L_i);
    SPS__PAIR_LOOP(w, q, dim, geo, k, l, {
            const sps_real ex = e.ex, ey = e.ey, ez = e.ez, dw = e.dw;
            const sps_real u = sps__approach(w, i, j, ex, ey, ez, dim);
            sps_real f2, beta = 1;
            if (limited) beta = sps__riemann_limiter(u, eta_c0);
            f2 = ((p[i] + p[j]) * scale - z * beta * u) * dw * vol[j]; /* 2 P* dW V_j, ENO eqs. 12-14 */
            acc[0][l] -= f2 * ex;
            acc[1][l] -= f2 * ey;
            if (dim == 3) acc[2][l] -= f2 * ez;
            if (newton) {
                const sps_real fv = two_mu * e.dw_r * vol[j]; /* dW/r: finite as r -> 0, 0 in padding */
                acc[0][l] += fv * (vx[i] - vx[j]);
                acc[1][l] += fv * (vy[i] - vy[j]);
                if (dim == 3) acc[2][l] += fv * (vz[i] - vz[j]);
            }
            if (paired) {
                const sps_real f = pair_force[s];
                shear[0][l] += f * ex;
                shear[1][l] += f * ey;
                if (dim == 3) shear[2][l] += f * ez;
            }
            if (stress) { /* (tau_i + tau_j) . e_ij dW V_j */
                const int tj = 6 * (j - begin); /* an int offset from the array: a gather (a pointer to j's entries defeats it) */
                const sps_real dwv = granular ? dw * vol[j] * scale : dw * vol[j];
                const sps_real sxx = tau_i[0][l] + tau[tj], sxy = tau_i[1][l] + tau[tj + 1], syy = tau_i[3][l] + tau[tj + 3];
                if (dim == 3) {
                    const sps_real sxz = tau_i[2][l] + tau[tj + 2], syz = tau_i[4][l] + tau[tj + 4], szz = tau_i[5][l] + tau[tj + 5];
                    acc[0][l] += (sxx * ex + sxy * ey + sxz * ez) * dwv;
                    acc[1][l] += (sxy * ex + syy * ey + syz * ez) * dwv;
                    acc[2][l] += (sxz * ex + syz * ey + szz * ez) * dwv;
                } else {
                    acc[0][l] += (sxx * ex + sxy * ey) * dwv;
                    acc[1][l] += (sxy * ex + syy * ey) * dwv;
                }
                sps__kind_pressure_pair(&kind_constants, sums, l, tau, tj, e, vol[j], p, j, dim, terms);
            }
            if (penalty) { /* in the penalty's configuration, before this sub-step's half drift */
                const sps__pair_geometry e_kicked = sps__pair_before_drift(w, i, s, j, dim, geo, SPS_R(0.5) * dt);
                const sps__penalty_velocity t = sps__penalty_term(w, b, i, j, l, e_kicked, L_i, dim, scaled);
                sps__add_penalty_term(penalty_sum, l, t, e_kicked, vol[j], dim, projected);
            }
    })
}

/* The pressure pass's rare terms for lane group g, each into a sum of its own (so that a loop
   of their own leaves every sum bit for bit; one loop each, for the rare body that has both):
   with art (OAS, 2D) Gray et al.'s artificial
   stress sum_j m_j f_ij^n (R_i + R_j) . grad W_ij, f_ij = W(r_ij)/W(dp); with damping a solid's
   material damping (>>material: Kelvin-Voigt) 2 (d + 2) eta (v_ij . e_ij) dW / r_ij V_j e_ij, with
   the Riemann dissipation Z (v_ij . e_ij) dW V_j e_ij (a Kelvin-Voigt body is never limited:
   beta = 1), kept apart from the pressure force for the work they dissipate. */
SPS__INLINE void sps__rare_pressure_pairs(sps_world* w, const sps__body* b, int g, sps_real dt, sps__lane_sums* SPS__RESTRICT sums, const int dim,
                                          const int geo, const int terms) {
    const int art = (terms & SPS__TERM_ART) != 0, damping = (terms & SPS__TERM_DAMPING) != 0;
    const sps__group q = sps__group_of(w, b, g);
    const sps_real z = b->z_riemann, beta = 1;
    const sps_real kelvin_voigt = damping ? sps__kelvin_voigt_coefficient(dim, b) : 0;
    const sps_real* SPS__RESTRICT vol = w->vol;
    const sps_real* SPS__RESTRICT art_r = b->art; /* OAS only: particle begin + k at 3 k */
    const sps_real oas_w_dp = b->oas_w_dp;
    const sps_real* oas_factor = b->oas_factor; /* f^n as a product of 12 factors, each 1 f + 0 or 0 f + 1 exactly: a
                                                   lane-uniform select the vectoriser takes (a loop to n it does not) */
    const int kernel = sps__geo_kernel(w, geo), begin = b->begin;
    sps_real(*gray)[SPS__LANES] = sums->row + SPS__GRAY;
    sps_real(*damp)[SPS__LANES] = sums->row + SPS__DAMP;
    sps_real art_i[3][SPS__LANES];
    int k, l;
    (void)dt;
    if (art) sps__own_lanes(art_r, 3, q.i0 - begin, art_i);
    SPS__PAIR_LOOP(w, q, dim, geo, k, l, {
            const sps_real ex = e.ex, ey = e.ey, ez = e.ez, dw = e.dw, rij = e.r;
            if (damping) {
                const sps_real u = sps__approach(w, i, j, ex, ey, ez, dim);
                const sps_real fk = (kelvin_voigt / rij + z * beta) * u * dw * vol[j]; /* 2 (d + 2) eta (v_ij . e_ij) dW / r_ij V_j e_ij */
                damp[0][l] += fk * ex;
                damp[1][l] += fk * ey;
                if (dim == 3) damp[2][l] += fk * ez;
            }
            if (art) {
                const int rj = 3 * (j - begin); /* an int offset: a gather */
                const sps_real f = w->kernel_norm * sps__kernel_f(kernel, rij * w->inv_h) / oas_w_dp;
                sps_real fn = 1, mf;
                int m;
                SPS__UNROLL
                for (m = 0; m < SPS__OAS_MAX_EXPONENT; ++m) fn *= oas_factor[m] * f + (1 - oas_factor[m]); /* f^n */
                mf = w->mass[j] * fn * dw;
                gray[0][l] += mf * ((art_i[0][l] + art_r[rj]) * ex + (art_i[1][l] + art_r[rj + 1]) * ey);
                gray[1][l] += mf * ((art_i[1][l] + art_r[rj + 1]) * ex + (art_i[2][l] + art_r[rj + 2]) * ey);
            }
    })
}

/* The pressure pass's finish for lane group q: the acceleration acc/rho_i + Gray's term, then the
   shear forces / m_i, then the Kelvin-Voigt damping / rho_i and its work, in this order (the
   sums' order of the fused pass, bit for bit); then the kind's own sums (sps__kind_pressure_store:
   the stress diffusion's rate). The choices are the body's model's. */
SPS__INLINE void sps__pressure_finish(sps_world* w, const sps__body* b, sps__group q, sps_real dt, sps__lane_sums* sums, const int dim) {
    sps_real(*acc)[SPS__LANES] = sums->row + SPS__ACC, (*gray)[SPS__LANES] = sums->row + SPS__GRAY;
    sps_real(*shear)[SPS__LANES] = sums->row + SPS__SHEAR;
    sps_real(*damp)[SPS__LANES] = sums->row + SPS__DAMP;
    const int paired = b->model.paired, damping = b->model.viscous == SPS__VISCOUS_KELVIN_VOIGT;
    int l, k, a;
    for (l = 0; l < SPS__LANES && q.i0 + l < b->end; ++l) {
        const int i = q.i0 + l;
        w->acc_p[0][i] = acc[0][l] / w->rho[i] + gray[0][l];
        w->acc_p[1][i] = acc[1][l] / w->rho[i] + gray[1][l];
        if (dim == 3) w->acc_p[2][i] = acc[2][l] / w->rho[i];
        if (paired)
            for (k = 0; k < dim; ++k) w->acc_p[k][i] += shear[k][l] / w->mass[i];
        if (damping) {
            sps_real power = 0; /* of the viscous force, at the velocities it was evaluated with */
            for (a = 0; a < dim; ++a) {
                w->acc_p[a][i] += damp[a][l] / w->rho[i];
                power += damp[a][l] / w->rho[i] * w->vel[a][i];
            }
            b->viscous_work[i - b->begin] -= w->mass[i] * power * dt;
        }
    }
    sps__kind_pressure_store(w, b, q, sums);
}

/* The pressure pass for lane group g with the pair loop `pairs` and its terms (the body's, or the
   one that also sums the penalty) into the cleared sums: that loop, the rare terms' loops, the
   finish. */
static void sps__pressure_sums(sps_world* w, const sps__body* b, int g, sps_real dt, sps__pair_loop pairs, int terms,
                               sps__lane_sums* sums) {
    const sps__group q = sps__group_of(w, b, g);
    pairs(w, b, g, dt, terms, sums);
    if (b->model.pass.art_pairs) b->model.pass.art_pairs(w, b, g, dt, SPS__TERM_ART, sums);
    if (b->model.pass.damping_pairs) b->model.pass.damping_pairs(w, b, g, dt, SPS__TERM_DAMPING, sums);
    if (w->dim == 2) sps__pressure_finish(w, b, q, dt, sums, 2);
    else sps__pressure_finish(w, b, q, dt, sums, 3);
}

/* The pressure pass's kernel for lane group g. */
static void sps__pressure(sps_world* w, const sps__body* b, int g, sps_real dt) {
    sps__lane_sums sums;
    sps__clear_sums(&sums, SPS__PRESSURE_SUMS);
    sps__pressure_sums(w, b, g, dt, b->model.pass.pressure_pairs, b->model.pass.pressure_terms, &sums);
}

/* The pressure pass's pair loops: (name, pair terms). */
/* The loops of the kinds a build can leave out (CONFIG MACROS: SPHSOLID_NO_FLUID,
   SPHSOLID_NO_GRANULAR): an empty list there, and sps_world_add_body refuses the kind. */
#ifdef SPHSOLID_NO_FLUID
#define SPS__PRESSURE_FLUID_LOOPS(X)
#else
#define SPS__PRESSURE_FLUID_LOOPS(X)                       \
    X(fluid, SPS__TERM_LIMITED)                            \
    X(fluid_viscous, SPS__TERM_LIMITED | SPS__TERM_NEWTON)
#endif
#ifdef SPHSOLID_NO_GRANULAR
#define SPS__PRESSURE_GRANULAR_LOOPS(X)
#else
#define SPS__PRESSURE_GRANULAR_LOOPS(X) X(granular, SPS__TERM_STRESS | SPS__TERM_LIMITED | SPS__TERM_GRANULAR)
#endif
/* with the GNO penalty of the previous sub-step (penalty_in_pressure_pass; J2 bodies' scaled) */
#ifdef SPHSOLID_NO_PLASTICITY
#define SPS__PRESSURE_J2_PENALTY_LOOPS(X)
#else
#define SPS__PRESSURE_J2_PENALTY_LOOPS(X)                                                \
    X(stress_gno_j2, SPS__TERM_STRESS | SPS__TERM_PENALTY | SPS__TERM_SCALED)             \
    X(stress_gno_a_j2, SPS__TERM_STRESS | SPS__TERM_PENALTY | SPS__TERM_PROJECTED | SPS__TERM_SCALED)
#endif
#define SPS__PRESSURE_LOOPS(X)                             \
    X(plain, 0)                                            \
    X(pairs, SPS__TERM_PAIRED)                             \
    X(stress, SPS__TERM_STRESS)                            \
    X(stress_pairs, SPS__TERM_STRESS | SPS__TERM_PAIRED)   \
    X(stress_gno, SPS__TERM_STRESS | SPS__TERM_PENALTY)    \
    X(stress_gno_a, SPS__TERM_STRESS | SPS__TERM_PENALTY | SPS__TERM_PROJECTED) \
    SPS__PRESSURE_J2_PENALTY_LOOPS(X)                      \
    SPS__PRESSURE_FLUID_LOOPS(X)                           \
    SPS__PRESSURE_GRANULAR_LOOPS(X)
#define SPS__PRESSURE_INSTANCES(variant, terms) SPS__INSTANCES(pressure_pairs, variant, terms)
SPS__GENERIC_LOOPS(pressure_pairs)
SPS__PRESSURE_LOOPS(SPS__PRESSURE_INSTANCES)
/* The rare terms' loops; OAS's in 2D only. */
SPS__GENERIC_LOOPS(rare_pressure_pairs)
SPS__INSTANCES(rare_pressure_pairs, damping, SPS__TERM_DAMPING)
SPS__INSTANCES_2D_ONLY(rare_pressure_pairs, art, SPS__TERM_ART)

/* Gray et al.'s artificial stress R_i (2D): in the principal frame of sigma = -p I + tau each
   tensile principal stress s > 0 gives R' = -eps s / rho^2; rotated back (xx, xy, yy). */
static void sps__artificial_stress(sps_world* w, const sps__body* b, int i) {
    const sps_real* t = b->tau + (size_t)6 * (i - b->begin);
    sps_real sxx = t[0] - w->p[i], sxy = t[1], syy = t[3] - w->p[i], rho2 = w->rho[i] * w->rho[i];
    sps_real th = SPS_R(0.5) * SPS__ATAN2(2 * sxy, sxx - syy), c = SPS__COS(th), s = SPS__SIN(th);
    sps_real pxx = c * c * sxx + 2 * c * s * sxy + s * s * syy, pyy = s * s * sxx - 2 * c * s * sxy + c * c * syy;
    sps_real rxx = pxx > 0 ? -b->oas_eps * pxx / rho2 : 0, ryy = pyy > 0 ? -b->oas_eps * pyy / rho2 : 0;
    sps_real* r = b->art + (size_t)3 * (i - b->begin);
    r[0] = c * c * rxx + s * s * ryy;
    r[1] = c * s * (rxx - ryy);
    r[2] = s * s * rxx + c * c * ryy;
}

/* exp(W dt) for the spin W = (L - L^T)/2 of a velocity gradient L (9 entries, row-major), in
   the Rodrigues form R = I + s1 W + s2 W^2 with s1 = sin(th)/|w|, s2 = (1 - cos th)/|w|^2,
   th = |w| dt (ANG eqs. 38-40; in 2D W has only its xy entries); L[k ls] and R[k rs]. With
   series = 1 (a literal), s1 and s2 come from their Taylor series in th^2, exact in double for
   th below 0.01 (every sub-step of a sound run) and free of sqrt, sin and branches, so lane
   loops vectorise them. Returns th^2: the caller checks the series held. */
#define SPS__SERIES_THETA2 SPS_R(1e-4) /* th < 0.01: the series to th^9 is exact in double */

SPS__INLINE sps_real sps__rodrigues_form(const sps_real* L, int ls, sps_real dt, const int dim, const int series, sps_real* R, int rs) {
    /* W = [0 a b; -a 0 c; -b -c 0] */
    const sps_real wa = SPS_R(0.5) * (L[ls] - L[3 * ls]);
    const sps_real wb = dim == 3 ? SPS_R(0.5) * (L[2 * ls] - L[6 * ls]) : 0, wc = dim == 3 ? SPS_R(0.5) * (L[5 * ls] - L[7 * ls]) : 0;
    const sps_real om2 = wa * wa + wb * wb + wc * wc, t2 = om2 * dt * dt;
    sps_real s1, s2;
    if (series) {
        s1 = dt * (1 - t2 / 6 * (1 - t2 / 20 * (1 - t2 / 42)));
        s2 = SPS_R(0.5) * dt * dt * (1 - t2 / 12 * (1 - t2 / 30 * (1 - t2 / 56)));
    } else {
        sps_real om = SPS__SQRT(om2), th = om * dt, sh = SPS__SIN(SPS_R(0.5) * th);
        s1 = om > 0 ? SPS__SIN(th) / om : dt;
        s2 = om > 0 ? 2 * sh * sh / om2 : SPS_R(0.5) * dt * dt; /* 1 - cos th = 2 sin^2(th/2): no cancellation */
    }
    /* R = I + s1 W + s2 W^2, W^2 written out */
    R[0] = 1 - s2 * (wa * wa + wb * wb);
    R[rs] = s1 * wa - s2 * wb * wc;
    R[3 * rs] = -s1 * wa - s2 * wb * wc;
    R[4 * rs] = 1 - s2 * (wa * wa + wc * wc);
    R[2 * rs] = s1 * wb + s2 * wa * wc;
    R[5 * rs] = s1 * wc - s2 * wa * wb;
    R[6 * rs] = -s1 * wb + s2 * wa * wc;
    R[7 * rs] = -s1 * wc - s2 * wa * wb;
    R[8 * rs] = 1 - s2 * (wb * wb + wc * wc);
    return t2;
}

/* The Rodrigues matrix of L over dt into R (9 entries), by the series when it is exact, else
   by sin and cos. */
static void sps__rodrigues(const sps_real* L, sps_real dt, const int dim, sps_real R[9]) {
    if (dim == 2) {
        if (sps__rodrigues_form(L, 1, dt, 2, 1, R, 1) >= SPS__SERIES_THETA2) sps__rodrigues_form(L, 1, dt, 2, 0, R, 1);
    } else if (sps__rodrigues_form(L, 1, dt, 3, 1, R, 1) >= SPS__SERIES_THETA2) {
        sps__rodrigues_form(L, 1, dt, 3, 0, R, 1);
    }
}

/* The angular velocity of a rotation matrix R that turned over dt: its axial vector is
   sin(th) n and its trace gives cos(th), so omega = th n / dt. Written as a skew velocity
   gradient S (S_yx = omega_z, ...) so that sps__rodrigues(S, t) rotates by omega t. */
static void sps__spin_of_rotation(const sps_real R[9], sps_real dt, const int dim, sps_real S[9]) {
    sps_real n[3] = {0, 0, 0}, sn, cs, th, f;
    int a;
    for (a = 0; a < 9; ++a) S[a] = 0;
    if (dim == 2) {
        n[2] = R[3] - R[1]; /* 2 sin th */
        cs = R[0] + R[4];   /* 2 cos th */
    } else {
        n[0] = R[7] - R[5];
        n[1] = R[2] - R[6];
        n[2] = R[3] - R[1];
        cs = R[0] + R[4] + R[8] - 1;
    }
    sn = SPS__SQRT(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(sn > 0) || !(dt > 0)) return;
    th = (sps_real)atan2((double)sn, (double)cs);
    f = th / (sn * dt);
    S[1] = -f * n[2]; S[3] = f * n[2];
    S[2] = f * n[1];  S[6] = -f * n[1];
    S[5] = -f * n[0]; S[7] = f * n[0];
}

/* Jaumann update of the shear stress (ENO eqs. 6-8) for one particle: next = tau + dt (2G dev(D)
   + W tau - tau W), from tau's entries (xx xy xz yy yz zz) t6[k ts] and L's nine L[k ls]
   (row-major); strides so that a lane loop keeps one particle per lane and vectorises. Writes
   the entries of next that exist in dim (xx xy yy in 2D). */
SPS__INLINE void sps__next_stress(const sps_real* t6, int ts, const sps_real* L, int ls, sps_real G, sps_real dt, const int dim,
                                  sps_real next[6]) {
    const int* sym = sps__sym9;
    sps_real T[9], D[9], W[9], tr = 0, rate;
    int a, c, m;
    SPS__UNROLL
    for (a = 0; a < 9; ++a) T[a] = t6[sym[a] * ts];
    SPS__UNROLL
    for (a = 0; a < dim; ++a) tr += L[4 * a * ls];
    SPS__UNROLL
    for (a = 0; a < dim; ++a)
        SPS__UNROLL
        for (c = 0; c < dim; ++c) {
            D[3 * a + c] = SPS_R(0.5) * (L[(3 * a + c) * ls] + L[(3 * c + a) * ls]);
            W[3 * a + c] = SPS_R(0.5) * (L[(3 * a + c) * ls] - L[(3 * c + a) * ls]);
        }
    SPS__UNROLL
    for (a = 0; a < dim; ++a)
        SPS__UNROLL
        for (c = a; c < dim; ++c) {
            rate = 2 * G * (D[3 * a + c] - (a == c ? tr / dim : 0));
            SPS__UNROLL
            for (m = 0; m < dim; ++m) rate += W[3 * a + m] * T[3 * m + c] - T[3 * a + m] * W[3 * m + c];
            next[sym[3 * a + c]] = T[3 * a + c] + dt * rate;
        }
}

/* Stores a lane's updated shear stress next (xx xy xz yy yz zz) into tau: in 2D only the
   in-plane components, the others stay 0. */
SPS__INLINE void sps__store_stress(sps_real* tau, const sps_real next[6], const int dim) {
    tau[0] = next[0];
    tau[1] = next[1];
    tau[3] = next[3];
    if (dim == 3) {
        tau[2] = next[2];
        tau[4] = next[4];
        tau[5] = next[5];
    }
}

/* The Jaumann update of the particles of lane group q from their velocity gradients in the
   lane arrays L (contiguous per entry: the lanes vectorise; measured 6% of a 2D plate run as a
   scalar loop). Padding lanes compute and do not store. */
SPS__INLINE void sps__stress_lanes(const sps__body* b, sps__group q, const int dim, sps_real dt, sps_real L[9][SPS__LANES]) {
    sps_real* SPS__RESTRICT tau = b->tau + (size_t)6 * (q.i0 - b->begin);
    const sps_real G = b->mat.G;
    const int end = b->end;
    int l;
    SPS__PRAGMA(omp simd)
    for (l = 0; l < SPS__LANES; ++l) {
        sps_real next[6];
        sps__next_stress(tau + 6 * l, 1, &L[0][l], SPS__LANES, G, dt, dim, next);
        if (q.i0 + l < end) sps__store_stress(tau + 6 * l, next, dim);
    }
}

/* >>material: J2 plasticity (continued): the updated-Lagrangian return map

   Called per lane group by the continuity pass's finish through sps__stress_update_lanes
   (chapter >>generic); sps__next_stress is the Jaumann update every stress shares. */

/* Radial return (J2 plasticity, ANG section 2.2) of one trial stress t (the Jaumann update,
   entries xx xy xz yy yz zz, those of dim): with |t| = sqrt(t:t) = sqrt(2 J2) and the yield
   radius y = sqrt(2/3)(sigma_Y + kappa alpha), a trial outside (f = |t| - y > 0, ANG eq. 11)
   flows by d_gamma = f / (2G + 2 kappa/3) along t/|t|, alpha grows by sqrt(2/3) d_gamma and t is
   scaled by r = sqrt(2/3)(sigma_Y + kappa alpha_new)/|t| (ANG eq. 14 with the hardened radius),
   which puts it exactly on the new surface: r |t| = |t| - 2G d_gamma. Inside, r = 1. Returns r;
   *alpha is updated and *dissipated gets the elastic energy density the return removed,
   (t:t)(1 - r^2)/(4G) = d_gamma (|t| + r |t|)/2: the trapezoidal rule for the plastic work
   sigma : d_eps_p of the step. Branch-free (selects) so that lane loops vectorise it. */
SPS__INLINE sps_real sps__radial_return(sps_real t[6], const int dim, sps_real G, sps_real yield_stress, sps_real hardening,
                                        sps_real* alpha, sps_real* dissipated) {
    const sps_real sqrt_2_3 = SPS_R(0.81649658092772603273); /* sqrt(2/3) */
    const sps_real tt = t[0] * t[0] + t[3] * t[3] + 2 * t[1] * t[1] +
                        (dim == 3 ? t[5] * t[5] + 2 * (t[2] * t[2] + t[4] * t[4]) : 0);
    const sps_real norm = SPS__SQRT(tt), over = norm - sqrt_2_3 * (yield_stress + hardening * *alpha);
    const int yielding = over > 0;
    const sps_real d_gamma = yielding ? over / (2 * G + SPS_R(2.0) / 3 * hardening) : 0;
    const sps_real alpha_new = *alpha + sqrt_2_3 * d_gamma;
    const sps_real r = yielding ? sqrt_2_3 * (yield_stress + hardening * alpha_new) / (yielding ? norm : 1) : 1;
    int a;
    SPS__UNROLL
    for (a = 0; a < 6; ++a) t[a] *= r;
    *alpha = alpha_new;
    *dissipated = tt * (1 - r * r) / (4 * G);
    return r;
}

/* The Jaumann update of a J2 body's lane group q followed by the radial return
   (sps__radial_return): the stress, the equivalent plastic strain, the plastic work of each
   particle (its current volume m/rho times the dissipated energy density) and, for a body
   with the scaled GNO penalty (literal scaled), its return factor r (the reference code's
   per-particle penalty scale) and, with relax (a literal: the penalty is stored per particle,
   not per pair), the stored penalty acceleration a_s scaled by r too (sps__penalty explains
   why). Padding lanes compute and do not store. */
SPS__INLINE void sps__j2_stress_lanes(sps_world* w, const sps__body* b, sps__group q, const int dim, sps_real dt,
                                      sps_real L[9][SPS__LANES], const int scaled, const int relax) {
    const size_t k0 = (size_t)(q.i0 - b->begin);
    sps_real* SPS__RESTRICT tau = b->tau + 6 * k0;
    sps_real* SPS__RESTRICT alpha = b->plastic_strain + k0;
    sps_real* SPS__RESTRICT work = b->plastic_work + k0;
    sps_real* SPS__RESTRICT factor = scaled ? b->return_factor + k0 : NULL;
    const sps_real *SPS__RESTRICT mass = w->mass + q.i0, *SPS__RESTRICT rho = w->rho + q.i0;
    const sps_real G = b->mat.G, yield_stress = b->def.material.j2.yield_stress, hardening = b->def.material.j2.hardening_modulus;
    const int end = b->end;
    int l;
    SPS__PRAGMA(omp simd)
    for (l = 0; l < SPS__LANES; ++l) {
        const sps_real rho_l = q.i0 + l < end ? rho[l] : 1; /* padding lanes: no 1/0 */
        sps_real next[6] = {0, 0, 0, 0, 0, 0}, a = alpha[l], dissipated, r;
        sps__next_stress(tau + 6 * l, 1, &L[0][l], SPS__LANES, G, dt, dim, next);
        r = sps__radial_return(next, dim, G, yield_stress, hardening, &a, &dissipated);
        if (q.i0 + l < end) {
            sps__store_stress(tau + 6 * l, next, dim);
            alpha[l] = a;
            work[l] += mass[l] / rho_l * dissipated;
            if (scaled) factor[l] = r;
            if (relax) {
                int c;
                SPS__UNROLL
                for (c = 0; c < dim; ++c) w->acc_s[c][q.i0 + l] *= r;
            }
        }
    }
}

/* >>material: Drucker-Prager (continued): the stress update of a lane group

   Called per lane group by the continuity pass's finish through sps__stress_update_lanes
   (chapter >>generic). */

/* The Drucker-Prager update (sps__drucker_prager_update) of lane l of granular body b's lane
   group q from its velocity gradient (gradient) and the stress diffusion of the pressure pass
   (spread; NULL: none), both as tau, its stress deviator, entries SPS__LANES apart (the lane
   arrays of sps__granular_stress_lanes): sigma = tau - p I, its deviator back into tau and
   -tr(sigma)/3 into next_pressure (p itself is read by the neighbours' continuity sums of this
   pass), the accumulated
   deviatoric plastic strain, grown by sqrt(2/3) |dev(t - sigma)| / (2G) with t the elastic trial
   (the plastic strain increment's deviator), and the plastic work, grown by the particle's
   volume times sigma : d_eps_p, the work of the returned stress on the plastic strain
   increment d_eps_p = C^-1 (t - sigma): s:(s_t - s)/(2G) + p (p_t - p)/K (backward Euler; the
   energy difference e(t) - e(sigma) counted a cut-off from zero stress, a dilute front
   particle's every sub-step, as dissipation). With the GNO penalty (scaled, relax), the
   particle's penalty factor is 1 if the step was elastic and 0 if the return mapping acted (on
   the cone: flowing) or its stress is at the apex (a free grain, whose few neighbours make its
   velocity gradient, and so the penalty's v^_ij, meaningless: C4 at L = 0.1 shot one off at
   0.60 s), and its stored penalty is relaxed by it:
   the penalty, an elastic stiffness xi G against the zigzag mode, acts between particles with
   an elastic reserve (a layer at rest) and not in flow, where a particle's stress is held on
   the cone. J2's |s|/|s_trial| (within O(dt) of 1 in a sub-step) left the penalty on in flow:
   measured in C4, 521 particles closer than 0.5 dp (118 with this switch, 88 without a
   penalty) and, before the divergence's lattice scale, a front particle shot off at 0.51 s.
   Padding lanes compute and do not store. */
SPS__INLINE void sps__granular_stress_lane(sps_world* w, const sps__body* b, sps__group q, int l, sps_real* tau, const sps_real* spread,
                                           const sps_real* gradient, const int dim, sps_real dt, const int scaled, const int relax) {
    const size_t k = (size_t)(q.i0 + l - b->begin);
    const int i = q.i0 + l, mine = i < b->end;
    const sps_real rho_read = w->rho[i], rho_i = mine ? rho_read : 1; /* padding lanes: no 1/0 */
    const sps_real G = b->mat.G, K = b->mat.K, sqrt_2_3 = SPS_R(0.81649658092772603273);
    const sps__yield_cone cone = b->cone;
    /* the arrays read before the branch: GCC masks no load of a pointer */
    sps_real *SPS__RESTRICT next_p = b->next_pressure, *SPS__RESTRICT strain = b->plastic_strain, *SPS__RESTRICT work = b->plastic_work;
    sps_real *SPS__RESTRICT factor = b->return_factor, *SPS__RESTRICT acc_s[3] = {w->acc_s[0], w->acc_s[1], w->acc_s[2]};
    const sps_real* SPS__RESTRICT mass = w->mass;
    sps_real sig[6], trial[6], rate[6], flow[6], i1, flow_trace, p_next, p_trial, s_trial[6], s_next[6];
    int a;
    SPS__UNROLL
    for (a = 0; a < 6; ++a) {
        sig[a] = tau[a * SPS__LANES] - (sps__sym_diagonal(a) ? w->p[i] : 0);
        rate[a] = spread ? spread[a * SPS__LANES] : 0;
    }
    sps__drucker_prager_update(sig, gradient, SPS__LANES, rate, 1, &cone, G, K, dt, trial);
    i1 = sig[SPS__XX] + sig[SPS__YY] + sig[SPS__ZZ];
    p_next = -i1 / 3;
    p_trial = -(trial[SPS__XX] + trial[SPS__YY] + trial[SPS__ZZ]) / 3;
    flow_trace = p_next - p_trial; /* tr(t - sigma)/3 */
    SPS__UNROLL
    for (a = 0; a < 6; ++a) {
        const int diagonal = sps__sym_diagonal(a);
        s_next[a] = sig[a] + (diagonal ? p_next : 0);
        s_trial[a] = trial[a] + (diagonal ? p_trial : 0);
        flow[a] = trial[a] - sig[a] - (diagonal ? flow_trace : 0);
        tau[a * SPS__LANES] = s_next[a];
    }
    if (mine) {
        next_p[k] = p_next;
        strain[k] += sqrt_2_3 * SPS__SQRT(sps__sym_contract(flow, flow)) / (2 * G);
        if (scaled) { /* the penalty's factor: 1 while elastic, 0 on the cone (see the function's head) */
            const sps_real trial_norm2 = sps__sym_contract(s_trial, s_trial), norm2 = sps__sym_contract(s_next, s_next);
            const sps_real r = trial_norm2 > norm2 || cone.alpha_phi * i1 >= cone.k_c ? 0 : 1; /* returned, or at the apex */
            int c;
            factor[k] = r;
            if (relax)
                SPS__UNROLL
                for (c = 0; c < dim; ++c) acc_s[c][i] *= r;
        }
        SPS__UNROLL
        for (a = 0; a < 6; ++a) s_trial[a] -= s_next[a];
        work[k] += mass[i] / rho_i * (sps__sym_contract(s_next, s_trial) / (2 * G) + p_next * (p_trial - p_next) / K);
    }
}
/* The lane loop, vectorised: each lane's update is a function of its own, so that its tensors
   (sig, trial, ...) are no locals of the SIMD loop (OpenMP gives each addressable local of the
   loop a copy per lane, an array GCC does not vectorise), and the lanes' stresses and stress
   diffusions are side by side (sps__own_lanes: GCC vectorises no group of six strided
   entries). In 2D the velocity gradient's entries outside dim are made 0 first: the update
   reads all nine. */
SPS__INLINE void sps__granular_stress_lanes(sps_world* w, const sps__body* b, sps__group q, const int dim, sps_real dt,
                                            sps_real L[9][SPS__LANES], const int diffused, const int scaled, const int relax) {
    const int first = q.i0 - b->begin;
    sps_real tau[6][SPS__LANES], spread[6][SPS__LANES];
    int l, a;
    for (a = 0; a < 9; ++a)
        if (a / 3 >= dim || a % 3 >= dim)
            for (l = 0; l < SPS__LANES; ++l) L[a][l] = 0;
    sps__own_lanes(b->tau, 6, first, tau);
    if (diffused) sps__own_lanes(b->diffusion, 6, first, spread);
    SPS__PRAGMA(omp simd)
    for (l = 0; l < SPS__LANES; ++l)
        sps__granular_stress_lane(w, b, q, l, &tau[0][l], diffused ? &spread[0][l] : NULL, &L[0][l], dim, dt, scaled, relax);
    for (l = 0; l < SPS__LANES && q.i0 + l < b->end; ++l)
        for (a = 0; a < 6; ++a) b->tau[(size_t)6 * (first + l) + a] = tau[a][l];
}

/* >>generic (continued): the updated-Lagrangian passes' hooks (continued): the stress update of a
   lane group, by its yield surface */

/* The stress update of lane group q from its velocity gradients L (the continuity pass's
   finish), by the body's kind: the return map of its yield surface (chapters >>material: J2
   plasticity and >>material: Drucker-Prager) or, for the kinds without a stress update of
   their own, the Jaumann update of a tracked stress. A plastic body is never ENO (combination
   rules) and its stress is always integrated (it is of the OG family). relax: the GNO penalty
   is stored per particle (not per pair), so a scaled penalty's stored acceleration relaxes
   with the stress (sps__penalty). A kind the build left out has no body (CONFIG MACROS), so its
   case is empty there. */
SPS__INLINE void sps__stress_update_lanes(sps_world* w, const sps__body* b, sps__group q, const int dim, sps_real dt,
                                          sps_real L[9][SPS__LANES], int relax) {
    const sps__model* m = &b->model;
    (void)w; (void)relax; /* read by the return maps only, which a build may leave out */
    switch (m->material->kind) {
    case SPS_MATERIAL_DRUCKER_PRAGER:
#ifndef SPHSOLID_NO_GRANULAR
        sps__granular_stress_lanes(w, b, q, dim, dt, L, m->diffusion, m->scaled_penalty, relax);
#endif
        return;
    case SPS_MATERIAL_J2:
#ifndef SPHSOLID_NO_PLASTICITY
        if (m->scaled_penalty && relax) sps__j2_stress_lanes(w, b, q, dim, dt, L, 1, 1);
        else if (m->scaled_penalty) sps__j2_stress_lanes(w, b, q, dim, dt, L, 1, 0);
        else sps__j2_stress_lanes(w, b, q, dim, dt, L, 0, 0);
#endif
        return;
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_FLUID:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: break;
    }
    if (m->stress) sps__stress_lanes(b, q, dim, dt, L);
}

/* >>solver: the updated-Lagrangian passes (continued) */

/* The Rodrigues matrix of each particle of lane group q from its velocity gradient: from the
   lane arrays L when given (the continuity pass has them at hand; contiguous, so the lanes
   vectorise), else from the body's velocity gradients. Lanes that turned more than 0.01 rad are redone by sin and cos. */
SPS__INLINE void sps__rotation_lanes(const sps__body* b, sps__group q, sps_real dt, const int dim, sps_real L[9][SPS__LANES],
                                     sps_real R[9][SPS__LANES]) {
    const sps_real* SPS__RESTRICT grad = b->grad + (size_t)9 * (q.i0 - b->begin);
    sps_real theta2[SPS__LANES], exact[9];
    int l, a;
    if (L) {
        SPS__PRAGMA(omp simd)
        for (l = 0; l < SPS__LANES; ++l) theta2[l] = sps__rodrigues_form(&L[0][l], SPS__LANES, dt, dim, 1, &R[0][l], SPS__LANES);
    } else {
        for (l = 0; l < SPS__LANES; ++l) theta2[l] = sps__rodrigues_form(grad + 9 * l, 1, dt, dim, 1, &R[0][l], SPS__LANES);
    }
    for (l = 0; l < SPS__LANES; ++l)
        if (theta2[l] >= SPS__SERIES_THETA2) {
            sps__rodrigues(grad + 9 * l, dt, dim, exact);
            for (a = 0; a < 9; ++a) R[a][l] = exact[a];
        }
}

/* Adds the increments da of lane group q to the accumulated shear acceleration a_s: plainly
   (turn SPS__TURN_NONE: ENO, GNO), after rotating a_s by the particle's Rodrigues matrix
   (SPS__TURN_PARTICLE, ANG eq. 34), or, for SPS__TURN_MEAN, stored in acc_d and applied in
   sps__finish once the mean is known (ANG eq. 42). turn is a literal at every call.
   R: the lanes' Rodrigues matrices, used by the per-particle rotation only. */
SPS__INLINE void sps__add_increments(sps_world* w, const sps__body* b, sps__group q, const int dim,
                                     sps_real da[3][SPS__LANES], sps_real R[9][SPS__LANES], const int turn) {
    const int end = b->end;
    int l, a, c;
    SPS__PRAGMA(omp simd)
    for (l = 0; l < SPS__LANES; ++l) {
        const int i = q.i0 + l;
        sps_real next[3];
        SPS__UNROLL
        for (a = 0; a < dim; ++a) {
            next[a] = da[a][l];
            if (turn == SPS__TURN_NONE) next[a] += w->acc_s[a][i];
            else if (turn == SPS__TURN_PARTICLE)
                SPS__UNROLL
                for (c = 0; c < dim; ++c) next[a] += R[3 * a + c][l] * w->acc_s[c][i];
        }
        if (i < end)
            SPS__UNROLL
            for (a = 0; a < dim; ++a) {
                if (turn == SPS__TURN_MEAN) b->acc_d[a][i - b->begin] = next[a];
                else w->acc_s[a][i] = next[a];
            }
    }
}

/* The lane-parallel end of the continuity pass for lane group q: density rate, the ENO
   increment without rotation (ENO eq. 24) into da, and, with gradient (a literal), the velocity
   gradient L = M B^T (ANG eq. 20; B from this pass's A, also with frozen geometry: a B kept
   from the configuration update would lag a rotating body). */
SPS__INLINE void sps__continuity_lanes(sps_world* w, const sps__body* b, sps__group q, const int dim, const int gradient,
                                       const int corrected, sps_real shear_rate, sps_real sum[SPS__NSUM][SPS__LANES],
                                       sps_real da[3][SPS__LANES], sps_real L[9][SPS__LANES]) {
    const sps_real* SPS__RESTRICT rho = w->rho + q.i0;
    sps_real* SPS__RESTRICT drho = w->drho + q.i0;
    sps_real* SPS__RESTRICT grad = gradient ? b->grad + (size_t)9 * (q.i0 - b->begin) : NULL;
    const int end = b->end;
    sps_real B[9][SPS__LANES];
    int l, a, c, m;
    SPS__PRAGMA(omp simd)
    for (l = 0; l < SPS__LANES; ++l) {
        const int mine = q.i0 + l < end;
        const sps_real rho_read = rho[l], rho_l = mine ? rho_read : 1; /* padding lanes: no 1/0 */
        SPS__UNROLL
        for (a = 0; a < dim; ++a) da[a][l] = shear_rate / rho_l * sum[SPS__LX + a][l];
        if (mine && !corrected) drho[l] = rho_l * sum[SPS__DRHO][l];
        if (gradient) { /* L = M B^T, i.e. -sum v_ij (x) (B grad W) V_j */
            sps__blended_inverse(&sum[SPS__A00][l], SPS__LANES, &B[0][l], SPS__LANES, dim);
            SPS__UNROLL
            for (a = 0; a < dim; ++a)
                SPS__UNROLL
                for (c = 0; c < dim; ++c) {
                    sps_real s = 0;
                    SPS__UNROLL
                    for (m = 0; m < dim; ++m) s += sum[SPS__M00 + 3 * a + m][l] * B[3 * c + m][l];
                    L[3 * a + c][l] = s;
                    if (mine) grad[9 * l + 3 * a + c] = s;
                }
            if (mine && corrected) drho[l] = rho_l * (sum[SPS__DRHO][l] - L[0][l] - L[4][l] - (dim == 3 ? L[8][l] : 0));
        }
    }
}

/* >>walls for fluids: mirror particles (chapter >>contact has the solids' walls)

   A fluid next to an analytic wall sees, for every neighbour j (and itself) within 2h of the
   wall, its mirror image j' across the wall: at the reflected position, with the reflected
   velocity (its normal component reversed; in the viscous force of a no-slip wall all of it:
   no slip is a viscous condition, after Adami et al. 2012) and the pressure
   p_j + rho0 g . (x_j' - x_j) (the hydrostatic continuation: the ghost particles of Libersky
   et al. 1993 and Colagrossi and Landrini 2003). The images complete the particle's kernel, so
   a fluid at rest stands on its floor at dp/2 with its hydrostatic pressure; they enter the
   pressure force (sps__mirror_force, in the contact pass) and the continuity sums, the velocity
   gradient and B (sps__mirror_continuity) as neighbours would. Only the neighbours' images
   count (an image is never nearer than its particle); in a corner the image across both walls
   is missing. The solids' penalty contact with walls (sigma) is not applied to a fluid. */

/* The distance of particle i from wall wl along its normal, in dim dimensions (a literal in
   the lane loops; sps__wall_distance: the world's). */
SPS__INLINE sps_real sps__wall_distance_in(const sps_world* w, const sps__wall* wl, int i, const int dim) {
    sps_real d = 0;
    int a;
    SPS__UNROLL
    for (a = 0; a < dim; ++a) d += (w->pos[a][i] - wl->point[a]) * wl->normal[a];
    return d;
}
static sps_real sps__wall_distance(const sps_world* w, const sps__wall* wl, int i) { return sps__wall_distance_in(w, wl, i, w->dim); }

/* An image: of particle j (its volume, its stress), at x, with velocity v (reflected), vv (the
   viscous force's: at a no-slip wall 2 v_wall - v_j, the wall's surface velocity 0 unless set)
   and pressure p. No pointer (the wall it is across is its pass's): a lane loop's images are
   SIMD lanes' private copies, which a pointer would stop from vectorising. */
typedef struct sps__image {
    int j;
    sps_real x[3], v[3], vv[3], p;
} sps__image;

/* The image of particle j across wall wl, at distance d_j from it (sps__wall_distance): the
   pressure continued hydrostatically, p_j + rho0 g . (x' - x_j). */
SPS__INLINE sps__image sps__mirror(const sps_world* w, const sps__body* b, const sps__wall* wl, int j, sps_real d_j, const int dim) {
    sps__image m;
    sps_real vn = 0, gd = 0;
    int a;
    m.j = j;
    SPS__UNROLL
    for (a = 0; a < dim; ++a) vn += w->vel[a][j] * wl->normal[a];
    SPS__UNROLL
    for (a = 0; a < 3; ++a) {
        /* read whatever the wall: a read under a condition is a masked load, which stops vectorisation */
        const sps_real x_j = a < dim ? w->pos[a][j] : 0, v_j = a < dim ? w->vel[a][j] : 0, v_wall = wl->velocity[a];
        m.x[a] = a < dim ? x_j - 2 * d_j * wl->normal[a] : 0;
        m.v[a] = a < dim ? v_j - 2 * vn * wl->normal[a] : 0;
        m.vv[a] = a < dim && wl->slip == SPS_WALL_NO_SLIP ? 2 * v_wall - v_j : m.v[a];
        gd += a < dim ? w->def.gravity[a] * (m.x[a] - x_j) : 0;
    }
    m.p = w->p[j] + b->rho0 * gd;
    return m;
}
/* Image m reflected across a second wall wl at right angles to its own (a corner): position,
   velocities and the pressure continued hydrostatically across the second reflection. */
SPS__INLINE void sps__reflect_image(const sps_world* w, const sps__body* b, const sps__wall* wl, sps__image* m, const int dim) {
    sps_real d = 0, vn = 0, vvn = 0, gd = 0;
    int a;
    SPS__UNROLL
    for (a = 0; a < dim; ++a) {
        d += (m->x[a] - wl->point[a]) * wl->normal[a];
        vn += m->v[a] * wl->normal[a];
        vvn += m->vv[a] * wl->normal[a];
    }
    SPS__UNROLL
    for (a = 0; a < dim; ++a) {
        gd -= 2 * d * w->def.gravity[a] * wl->normal[a];
        m->x[a] -= 2 * d * wl->normal[a];
        m->v[a] -= 2 * vn * wl->normal[a];
        m->vv[a] -= 2 * vvn * wl->normal[a];
    }
    m->p += b->rho0 * gd;
}

/* An image pair's geometry, particle i and image m at x (as sps__pair_of_offset's): e = (x_i -
   x') / r, dW/dr, and r; dW/dr = 0 with r = 1 unless `on` and the image within the support.
   Branch-free, for the lane loops. */
SPS__INLINE sps__pair_geometry sps__image_geometry(const sps_world* w, int i, sps__image m, int on, const int dim) {
    sps__pair_geometry q;
    sps_real e[3], r2 = 0, r;
    int a;
    SPS__UNROLL
    for (a = 0; a < 3; ++a) {
        e[a] = sps__nearest_image(w, a, a < dim ? w->pos[a][i] - m.x[a] : 0); /* across a period: exact on other axes, no branch */
        r2 += e[a] * e[a];
    }
    r = SPS__SQRT(r2);
    on &= (r > 0) & (r < w->support);
    r = on ? r : 1;
    q.ex = e[0] / r;
    q.ey = e[1] / r;
    q.ez = e[2] / r;
    q.dw = sps__dwdr(w, r) * (sps_real)on; /* not a select: a read of the kernel's constants under one stops vectorisation */
    q.dw_r = q.dw / r;
    q.r = r;
    return q;
}

/* The particles of a SIMD pass over images, one per lane: a lane group's own (the continuity and
   transport passes, whose sums are the group's), or the particles within 2h of a wall taken
   LANES at a time from a thread's share of the body (the force and equilibrium passes, which
   write each particle's result: most particles are far from every wall, and a lane group's
   lanes next to a side wall are few). A lane's result depends on its particle alone, so no
   result depends on which particles share a pass. */
typedef struct sps__image_lanes {
    int i[SPS__LANES];     /* each lane's particle (an unused lane repeats one, and is never among) */
    int among[SPS__LANES]; /* the lanes that take images */
    int len;               /* neighbour ranks to visit: the most neighbours of any lane */
} sps__image_lanes;

/* The walls and corners whose images a lane set sees: a reflection, across one wall or across
   the two or three walls of a corner at right angles, with the lanes within 2h of all of its
   walls. Without a corner's images a particle in the corner misses the images diagonally across
   it, and the pressure of the rest pulls it into the corner (the corner particle of a 2D tank
   at rest: 33 m/s^2 at h = 1.3 dp; bench/VALIDATION.md, "Still water"). Exact for a box; walls
   at other angles get none (the backstop holds their corners). */
typedef struct sps__reflection {
    const sps__wall* wall[3]; /* the wall, or the corner's walls */
    int count;                /* 1: a wall; 2 or 3: a corner */
    int on[SPS__LANES];       /* the lanes within 2h of each of its walls */
    sps_real d_i[SPS__LANES]; /* the lanes' distances from wall[0]; 2h for a lane that is off */
} sps__reflection;
/* A pass's images of the lanes across reflection rf (its user data: the sums). */
typedef void (*sps__reflection_fn)(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, const sps__reflection* rf, void* user);

/* Whether walls a and b meet at a right angle (their normals orthogonal to rounding). */
static int sps__walls_square(const sps_world* w, const sps__wall* a, const sps__wall* b) {
    sps_real dot = 0;
    int c;
    for (c = 0; c < w->dim; ++c) dot += a->normal[c] * b->normal[c];
    return dot * dot < SPS_R(1e-10);
}

/* The distances d of the lanes' particles from wall wl (2h for those not `among`), and which of
   the lanes `among` are within 2h of it (on); returns how many are. */
SPS__INLINE int sps__lanes_near_wall_in(const sps_world* w, const sps__image_lanes* lanes, const sps__wall* wl, const int* among, sps_real* d,
                                        int* on, const int dim) {
    const sps__wall wall = *wl; /* a local: no pointer read in the loop */
    int l, count = 0;
    SPS__PRAGMA(omp simd reduction(+ : count))
    for (l = 0; l < SPS__LANES; ++l) {
        const sps_real distance = sps__wall_distance_in(w, &wall, lanes->i[l], dim);
        d[l] = among[l] ? distance : w->support;
        on[l] = among[l] & (distance < w->support);
        count += on[l];
    }
    return count;
}
static int sps__lanes_near_wall(const sps_world* w, const sps__image_lanes* lanes, const sps__wall* wl, const int* among, sps_real* d, int* on) {
    return w->dim == 2 ? sps__lanes_near_wall_in(w, lanes, wl, among, d, on, 2) : sps__lanes_near_wall_in(w, lanes, wl, among, d, on, 3);
}

/* A corner's d_i (its first wall's) set to 2h for the lanes not within 2h of all its walls. */
static void sps__corner_lanes(const sps_world* w, sps__reflection* rf) {
    int l;
    for (l = 0; l < SPS__LANES; ++l)
        if (!rf->on[l]) rf->d_i[l] = w->support;
}

/* Calls visit for each reflection seen by some of the lanes among (particles of body b): wall
   k, then with corners the corners of k with walls k2 > k, each followed by the corners of three
   walls k3 > k2 (3D). Each lane sums its images in this order, whatever the other lanes'. */
static void sps__each_reflection(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, int corners, sps__reflection_fn visit,
                                 void* user) {
    sps__reflection rf[3];
    sps_real d[SPS__LANES];
    int k, k2, k3;
    for (k = 0; k < w->nwalls; ++k) {
        rf[0].wall[0] = &w->walls[k];
        rf[0].wall[1] = rf[0].wall[2] = NULL;
        rf[0].count = 1;
        if (!sps__lanes_near_wall(w, lanes, rf[0].wall[0], lanes->among, rf[0].d_i, rf[0].on)) continue;
        visit(w, b, lanes, &rf[0], user);
        for (k2 = k + 1; k2 < w->nwalls && corners; ++k2) {
            rf[1] = rf[0];
            rf[1].wall[1] = &w->walls[k2];
            rf[1].count = 2;
            if (!sps__walls_square(w, rf[1].wall[0], rf[1].wall[1]) || !sps__lanes_near_wall(w, lanes, rf[1].wall[1], rf[0].on, d, rf[1].on))
                continue;
            sps__corner_lanes(w, &rf[1]);
            visit(w, b, lanes, &rf[1], user);
            for (k3 = k2 + 1; k3 < w->nwalls && w->dim == 3; ++k3) {
                rf[2] = rf[1];
                rf[2].wall[2] = &w->walls[k3];
                rf[2].count = 3;
                if (!sps__walls_square(w, rf[2].wall[0], rf[2].wall[2]) || !sps__walls_square(w, rf[2].wall[1], rf[2].wall[2]) ||
                    !sps__lanes_near_wall(w, lanes, rf[2].wall[2], rf[1].on, d, rf[2].on))
                    continue;
                sps__corner_lanes(w, &rf[2]);
                visit(w, b, lanes, &rf[2], user);
            }
        }
    }
}

/* The image of neighbour j across the walls of a reflection (count of them: wall0, and a
   corner's wall1 and wall2), and whether it counts (sps__image_counts): the lane is on (its
   distance d_i from wall0 within 2h: the reflection's d_i is 2h for a lane that is off), j a neighbour (listed: not a padding slot) within 2h of each of the reflection's
   walls and, across one wall, d_i + d_j within the support. The image of j is d_i + d_j from i
   along the wall's normal, so no image with d_i + d_j beyond the support is within it: those
   (most of the neighbours' images of the second and third row) count for nothing. The bound
   has a margin of a thousandth of the support for the rounding, so an image at the support's
   edge is still left to sps__image_geometry's own test. */
SPS__INLINE sps__image sps__image_across(const sps_world* w, const sps__body* b, const sps__wall* wall0, const sps__wall* wall1,
                                         const sps__wall* wall2, int count, int j, const int dim, const int corner) {
    sps__image m = sps__mirror(w, b, wall0, j, sps__wall_distance_in(w, wall0, j, dim), dim);
    if (corner) { /* a literal: most images are a single wall's, and their loops carry none of this */
        sps__reflect_image(w, b, wall1, &m, dim);
        if (dim == 3) { /* formed for every 3D corner, kept for a corner of three walls: no masked gather */
            sps__image m3 = m;
            sps__reflect_image(w, b, wall2, &m3, dim);
            if (count == 3) m = m3;
        }
    }
    return m;
}
SPS__INLINE int sps__image_counts(const sps_world* w, const sps__wall* wall0, const sps__wall* wall1, const sps__wall* wall2, int count, sps_real d_i,
                                  int j, int listed, const int dim, const int corner) {
    const sps_real d_j = sps__wall_distance_in(w, wall0, j, dim);
    int near = d_j < w->support; /* & rather than &&: a branch-free mask for the lane loops */
    if (corner) {
        near &= sps__wall_distance_in(w, wall1, j, dim) < w->support;
        if (dim == 3) near &= (count < 3) | (sps__wall_distance_in(w, wall2, j, dim) < w->support);
    } else {
        near &= !(d_i + d_j > w->support * SPS_R(1.001));
    }
    return (d_i < w->support) & listed & near;
}

/* The images across a reflection that count, gathered per lane in neighbour order before their
   terms are evaluated: of a lane's 2h of neighbours, only those near the wall have an image
   within its support (the second and third rows' images mostly not), so evaluating every rank
   for every lane would mostly add zeros. */
#define SPS__IMAGE_BATCH 16 /* images gathered per lane before their terms are evaluated */
typedef struct sps__image_batch {
    int j[SPS__IMAGE_BATCH][SPS__LANES]; /* each lane's images' neighbours (the lane's own particle for its own) */
    int count[SPS__LANES];               /* how many each lane holds */
    int most;                            /* the most any lane holds */
    int next_rank;                       /* the next neighbour rank to gather (-1: each lane's own image) */
    sps__wall wall[3]; /* the reflection's walls copied: a read from a local cannot fault, so a conditional one
                          needs no masked load (which stops vectorisation); a wall a reflection lacks repeats one */
} sps__image_batch;

static void sps__image_batch_begin(const sps__reflection* rf, sps__image_batch* batch) {
    batch->next_rank = -1;
    batch->wall[0] = *rf->wall[0];
    batch->wall[1] = rf->count > 1 ? *rf->wall[1] : batch->wall[0];
    batch->wall[2] = rf->count > 2 ? *rf->wall[2] : batch->wall[1];
}

/* Gathers into batch the images across rf that count (sps__image_counts, and within the
   support) from rank batch->next_rank on, until a lane holds SPS__IMAGE_BATCH or the ranks run
   out; returns 0 when there was no rank left. A lane past its own neighbours reads its first
   one again (a slot that exists), or the array's first slot if it has none, and takes no image
   of it. */
SPS__INLINE int sps__gather_images(const sps_world* w, const sps__body* b, const sps__image_lanes* lanes, const sps__reflection* rf,
                                   sps__image_batch* batch, const int dim, const int corner) {
    const int *SPS__RESTRICT counts = w->nb_count, *SPS__RESTRICT firsts = w->nb_first;
    int keep[SPS__LANES], neighbour[SPS__LANES], l;
    batch->most = 0;
    for (l = 0; l < SPS__LANES; ++l) batch->count[l] = 0;
    if (batch->next_rank >= lanes->len) return 0;
    while (batch->next_rank < lanes->len && batch->most < SPS__IMAGE_BATCH) {
        const int m = batch->next_rank++;
        const int* SPS__RESTRICT js = m < 0 ? lanes->i : w->nb_j;
        SPS__PRAGMA(omp simd)
        for (l = 0; l < SPS__LANES; ++l) {
            const int i = lanes->i[l], listed = counts[i], first = firsts[i], rank = m < listed ? m : 0; /* read unconditionally */
            const int j = js[m < 0 ? l : listed > 0 ? first + rank * SPS__LANES : 0];
            const int on = sps__image_counts(w, &batch->wall[0], &batch->wall[1], &batch->wall[2], rf->count, rf->d_i[l], j, m < listed, dim, corner);
            const sps__image im = sps__image_across(w, b, &batch->wall[0], &batch->wall[1], &batch->wall[2], rf->count, j, dim, corner);
            keep[l] = sps__image_geometry(w, i, im, on, dim).dw != 0;
            neighbour[l] = j;
        }
        for (l = 0; l < SPS__LANES; ++l)
            if (keep[l]) {
                batch->j[batch->count[l]++][l] = neighbour[l];
                if (batch->count[l] > batch->most) batch->most = batch->count[l];
            }
    }
    return 1;
}

/* The loop over the images of the lanes across reflection rf, the images' counterpart of
   SPS__PAIR_LOOP: for each image rank k of the gathered images (sps__gather_images), the lanes l
   side by side in one SIMD loop, each with its particle i, the image im of its neighbour j and
   the pair geometry e (dW = 0 past a lane's images: the statements add zeros for them),
   declared for the pass's statements; corner (a literal) whether rf is a corner. Each lane
   takes its images in neighbour order. k and l are the caller's ints. */
#define SPS__IMAGE_LOOP(w, b, lanes, rf, dim, corner, k, l, ...)                                                  \
    {                                                                                                           \
        sps__image_batch batch_;                                                                                \
        sps__image_batch_begin(rf, &batch_);                                                                    \
        while (sps__gather_images(w, b, lanes, rf, &batch_, dim, corner))                                       \
            for (k = 0; k < batch_.most; ++k) {                                                                 \
                SPS__PRAGMA(omp simd)                                                                           \
                for (l = 0; l < SPS__LANES; ++l) {                                                              \
                    const int i = (lanes)->i[l], on_ = k < batch_.count[l], j = on_ ? batch_.j[k][l] : i;       \
                    const sps__image im = sps__image_across(w, b, &batch_.wall[0], &batch_.wall[1], &batch_.wall[2], \
                                                            (rf)->count, j, dim, corner);                       \
                    const sps__pair_geometry e = sps__image_geometry(w, i, im, on_, dim);                      \
                    __VA_ARGS__                                                                                 \
                }                                                                                               \
            }                                                                                                   \
    }

/* >>walls for fluids (continued): the granular images' shear, continued by equilibrium

   A no-slip wall holds a granular body through its images' stress. Given the particle's own
   deviator (an even reflection, as the reference code's dummy particles), the images carry no
   gradient of the shear traction across the wall, and the row next to the floor of an infinite
   slope feels none of the shear that holds the layer above it: the layer slides on the floor
   about a degree below the cone's limit angle, and a GNO penalty lets it slide at 20 degrees
   (bench/VALIDATION.md, "Infinite slope"). The image of j at x' (delta = (x' - x_j) . n) takes
   instead the traction sigma_an (a along the wall) continued by equilibrium,
       d sigma_an / dn = -rho_j b_a - (I - n n)_cd d sigma_ad / dx_c,
   with the body force b = g plus the body's external acceleration at x_j (the wall at rest:
   Adami, Hu and Adams 2012's wall pressure, p_w = p_f + rho (g - a_w) . r_wf, extended to the
   traction) and the divergence along the wall measured at j: tau' = tau_j + delta (s n + n s),
   s the tangential part of the right-hand side. On an infinite slope the stress varies across
   the layer only, and the images carry the shear gradient rho g sin(theta); at a vertical wall
   beside a column the weight is carried by d sigma_yy / dy, and s = 0 there as for the
   even image. The pressure is continued hydrostatically as for a fluid (sps__mirror). The
   gradient is measured once per sub-step, in the contact pass, for the particles within 2h of
   a no-slip wall (sps__measure_wall_equilibrium), into the field "wall_equilibrium": d sigma /
   dx (the 6 stress entries times 3 directions, scaled by the lattice's gradient moment as the
   divergence) and rho b (3). */

/* Whether body b continues its no-slip images' shear by equilibrium: a body whose images carry
   its stress (SPS__MIRROR_STRESS: granular) in a world with a no-slip wall. */
static int sps__wants_wall_equilibrium(const sps_world* w, const sps__body* b) {
    int k;
    if (b->model.mirrored != SPS__MIRROR_STRESS) return 0;
    for (k = 0; k < w->nwalls; ++k)
        if (w->walls[k].slip == SPS_WALL_NO_SLIP) return 1;
    return 0;
}

/* The Cauchy stress -p I + tau (6 entries) from a pressure and a deviator. */
SPS__INLINE void sps__cauchy_of(sps_real p, const sps_real tau[6], sps_real s[6]) {
    int a;
    SPS__UNROLL
    for (a = 0; a < 6; ++a) s[a] = tau[a] - (sps__sym_diagonal(a) ? p : 0);
}

/* Adds (sigma_k - sigma_i) dW e V_k to the stress gradient g (6 x 3) of particle i. */
static void sps__add_stress_difference(const sps_world* w, const sps_real si[6], const sps_real sk[6], const sps_real e[3], sps_real dwv,
                                       sps_real g[18]) {
    int a, c;
    for (a = 0; a < 6; ++a)
        for (c = 0; c < w->dim; ++c) g[3 * a + c] += (sk[a] - si[a]) * dwv * e[c];
}

/* How an image carries its particle's deviator tau_j, a literal of the lane loops: none (a
   fluid); reflected across a slip wall, M tau_j M with M = I - 2 n n (no shear traction); as
   it is at a no-slip wall (even: the pass that measures equilibrium reads it so), or continued
   across it by equilibrium (above). */
enum { SPS__IMAGE_STRESS_NONE, SPS__IMAGE_STRESS_REFLECTED, SPS__IMAGE_STRESS_EVEN, SPS__IMAGE_STRESS_CONTINUED };
/* How body b's images across wall wl carry its stress (even: no-slip images as they are). */
static int sps__image_stress_mode(const sps__body* b, const sps__wall* wl, int even) {
    if (b->model.mirrored != SPS__MIRROR_STRESS) return SPS__IMAGE_STRESS_NONE;
    if (wl->slip != SPS_WALL_NO_SLIP) return SPS__IMAGE_STRESS_REFLECTED;
    return even || !b->wall_equilibrium ? SPS__IMAGE_STRESS_EVEN : SPS__IMAGE_STRESS_CONTINUED;
}

/* The deviator t (3 x 3) of image m of body b across wall `wall`, which carries it in mode `mode`. */
SPS__INLINE void sps__image_stress(const sps_world* w, const sps__body* b, const sps__wall* wall, sps__image m, sps_real t[9], const int dim,
                                   const int mode) {
    const int tj = 6 * (m.j - b->begin); /* int offsets from the arrays: gathers in the lane loops */
    const sps_real* n = wall->normal;
    int a, c, d;
    SPS__UNROLL
    for (a = 0; a < 9; ++a) t[a] = b->tau[tj + sps__sym9[a]];
    if (mode == SPS__IMAGE_STRESS_CONTINUED) {
        const sps_real* equilibrium = b->wall_equilibrium;
        const int row = SPS__EQUILIBRIUM_VALUES * (m.j - b->begin);
        sps_real s[3] = {0, 0, 0}, sn = 0, delta = 0;
        SPS__UNROLL
        for (a = 0; a < dim; ++a) delta += (m.x[a] - w->pos[a][m.j]) * n[a];
        SPS__UNROLL
        for (a = 0; a < dim; ++a) { /* s_a = -rho b_a - (I - n n)_cd d sigma_ad / dx_c */
            s[a] = -equilibrium[row + 18 + a];
            SPS__UNROLL
            for (c = 0; c < dim; ++c)
                SPS__UNROLL
                for (d = 0; d < dim; ++d) s[a] -= ((c == d) - n[c] * n[d]) * equilibrium[row + 3 * sps__sym9[3 * a + d] + c];
        }
        SPS__UNROLL
        for (a = 0; a < dim; ++a) sn += s[a] * n[a];
        SPS__UNROLL
        for (a = 0; a < dim; ++a) s[a] -= sn * n[a]; /* along the wall: the normal part is the pressure's */
        SPS__UNROLL
        for (a = 0; a < dim; ++a)
            SPS__UNROLL
            for (c = 0; c < dim; ++c) t[3 * a + c] += delta * (s[a] * n[c] + n[a] * s[c]);
    } else if (mode == SPS__IMAGE_STRESS_REFLECTED) {
        sps_real M[9], Mt[9];
        SPS__UNROLL
        for (a = 0; a < 3; ++a)
            SPS__UNROLL
            for (c = 0; c < 3; ++c) M[3 * a + c] = (a == c) - 2 * (a < dim ? n[a] : 0) * (c < dim ? n[c] : 0);
        sps__mat3_product(M, t, 0, Mt);
        sps__mat3_product(Mt, M, 0, t);
    }
}

/* The dispatch of a pass's lane loop over the dimension, and over whether reflection rf is a
   corner: literals in each call. */
#define SPS__BY_DIM(w, call2, call3) \
    do {                            \
        if ((w)->dim == 2) call2;   \
        else call3;                 \
    } while (0)
#define SPS__BY_CORNER(rf, call_wall, call_corner) \
    do {                                          \
        if ((rf)->count == 1) call_wall;          \
        else call_corner;                         \
    } while (0)

/* The stress gradients of the lanes of a group within 2h of a no-slip wall, summed in
   sps__measure_wall_equilibrium: their Cauchy stresses si and gradients g (6 x 3 rows). */
typedef struct sps__gradient_sums {
    sps_real si[6][SPS__LANES], g[18][SPS__LANES];
} sps__gradient_sums;
/* Adds image m's (sigma' - sigma_i) dW e V_j to particle i's stress gradient g (rows `stride`
   apart; as sps__add_stress_difference), its stress in mode `mode` (slip walls: reflected;
   no-slip: even), si particle i's Cauchy stress (entries `stride` apart). */
SPS__INLINE void sps__image_stress_gradient(const sps_world* w, const sps__body* b, const sps__wall* wall, sps__image m, sps__pair_geometry e,
                                            const sps_real* si, sps_real* g, int stride, const int dim, const int mode) {
    const sps_real dir[3] = {e.ex, e.ey, e.ez}, dwv = e.dw * w->vol[m.j];
    sps_real t[9], tau[6], sk[6];
    int a, c;
    sps__image_stress(w, b, wall, m, t, dim, mode);
    SPS__UNROLL
    for (a = 0; a < 6; ++a) tau[a] = t[3 * sps__sym_row[a] + sps__sym_col[a]];
    sps__cauchy_of(m.p, tau, sk);
    SPS__UNROLL
    for (a = 0; a < 6; ++a)
        SPS__UNROLL
        for (c = 0; c < dim; ++c) g[(3 * a + c) * stride] += (sk[a] - si[a * stride]) * dwv * dir[c];
}
SPS__INLINE void sps__images_stress_gradient_lanes(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, const sps__reflection* rf,
                                                   sps__gradient_sums* SPS__RESTRICT s, const int dim, const int mode) {
    const sps__wall* wall = rf->wall[0];
    int m, l;
    SPS__IMAGE_LOOP(w, b, lanes, rf, dim, 0, m, l, /* a stress body's images: no corners */
                    { sps__image_stress_gradient(w, b, wall, im, e, &s->si[0][l], &s->g[0][l], SPS__LANES, dim, mode); })
}
static void sps__images_stress_gradient(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, const sps__reflection* rf, void* user) {
    sps__gradient_sums* s = (sps__gradient_sums*)user;
    if (sps__image_stress_mode(b, rf->wall[0], 1) == SPS__IMAGE_STRESS_REFLECTED)
        SPS__BY_DIM(w, sps__images_stress_gradient_lanes(w, b, lanes, rf, s, 2, SPS__IMAGE_STRESS_REFLECTED),
                    sps__images_stress_gradient_lanes(w, b, lanes, rf, s, 3, SPS__IMAGE_STRESS_REFLECTED));
    else
        SPS__BY_DIM(w, sps__images_stress_gradient_lanes(w, b, lanes, rf, s, 2, SPS__IMAGE_STRESS_EVEN),
                    sps__images_stress_gradient_lanes(w, b, lanes, rf, s, 3, SPS__IMAGE_STRESS_EVEN));
}

/* The external acceleration of body b at particle i and time t (sps_body_set_acceleration), as
   the kick evaluates it, into acc (zeroed first). */
static void sps__external_acceleration_at(const sps_world* w, const sps__body* b, int i, sps_real t, sps_real acc[3]) {
    sps_real x[3] = {0, 0, 0}, x0[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    int a;
    for (a = 0; a < 3; ++a) acc[a] = 0;
    for (a = 0; a < w->dim; ++a) {
        x[a] = w->pos[a][i];
        x0[a] = w->ref[a][i];
        v[a] = w->vel[a][i];
    }
    b->acceleration(x, x0, v, t, acc, b->acceleration_user);
}

/* Particle i's Cauchy stress si and its stress gradient from its neighbours into g (6 x 3). */
static void sps__neighbours_stress_gradient(const sps_world* w, const sps__body* b, int i, sps_real si[6], sps_real g[18]) {
    int m, a;
    for (a = 0; a < 18; ++a) g[a] = 0;
    sps__cauchy_of(w->p[i], b->tau + (size_t)6 * (i - b->begin), si);
    for (m = 0; m < w->nb_count[i]; ++m) {
        const int k = sps__neighbor(w, i, m);
        sps_real d[3], e[3], r, sk[6];
        const sps_real r2 = sps__pair_offset(w, i, k, d);
        r = SPS__SQRT(r2);
        if (!(r > 0) || !(r < w->support)) continue;
        for (a = 0; a < 3; ++a) e[a] = d[a] / r;
        sps__cauchy_of(w->p[k], b->tau + (size_t)6 * (k - b->begin), sk);
        sps__add_stress_difference(w, si, sk, e, sps__dwdr(w, r) * w->vol[k], g);
    }
}

/* The rows of "wall_equilibrium" of the lanes' particles of body b (granular, with a no-slip
   wall), those within 2h of a no-slip wall (the others' rows are not read): their stress
   gradient from their neighbours and their images (even), and rho_i b at the sub-step's middle
   time t. */
static void sps__measure_wall_equilibrium(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, sps_real t) {
    sps__gradient_sums s;
    int l, a;
    for (l = 0; l < SPS__LANES; ++l) {
        sps_real si[6] = {0, 0, 0, 0, 0, 0}, grad[18] = {0}; /* a lane not among: zeros, so its image terms are finite */
        if (lanes->among[l]) sps__neighbours_stress_gradient(w, b, lanes->i[l], si, grad);
        for (a = 0; a < 6; ++a) s.si[a][l] = si[a];
        for (a = 0; a < 18; ++a) s.g[a][l] = grad[a];
    }
    sps__each_reflection(w, b, lanes, 0, sps__images_stress_gradient, &s);
    for (l = 0; l < SPS__LANES && lanes->among[l]; ++l) {
        const int i = lanes->i[l];
        sps_real* row = b->wall_equilibrium + (size_t)SPS__EQUILIBRIUM_VALUES * (i - b->begin), acc[3] = {0, 0, 0};
        for (a = 0; a < 18; ++a) row[a] = s.g[a][l] * b->divergence_scale;
        if (b->acceleration) sps__external_acceleration_at(w, b, i, t, acc);
        for (a = 0; a < 3; ++a) row[18 + a] = a < w->dim ? w->rho[i] * (w->def.gravity[a] + acc[a]) : 0;
    }
}

/* The pressure pass's terms of image m of particle i with geometry e, added to acc (entries
   `stride` apart; per unit mass times rho_i): the Riemann pressure, a viscous fluid's force
   (newton) and, for images that carry the stress (stress: its mode; granular), the stress
   divergence across wall `wall` with particle i's deviator tau_i (entries `stride` apart). Also the fluid-structure coupling's, whose images are solid
   particles (no wall, no stress). */
SPS__INLINE void sps__image_force(const sps_world* w, const sps__body* b, const sps__wall* wall, int i, sps__image m, sps__pair_geometry e,
                                  const sps_real* tau_i, sps_real* acc, int stride, const int dim, const int newton, const int stress) {
    const sps_real vol = w->vol[m.j], dir[3] = {e.ex, e.ey, e.ez};
    sps_real u = 0, beta, f2;
    int a, c;
    SPS__UNROLL
    for (a = 0; a < dim; ++a) u += (w->vel[a][i] - m.v[a]) * dir[a];
    beta = sps__riemann_limiter(u, b->limiter_eta_c0);
    f2 = ((w->p[i] + m.p) * b->divergence_scale - b->z_riemann * beta * u) * e.dw * vol; /* scaled as in sps__pressure */
    SPS__UNROLL
    for (a = 0; a < dim; ++a) {
        acc[a * stride] -= f2 * dir[a];
        if (newton) acc[a * stride] += b->viscous_coefficient * e.dw * vol / e.r * (w->vel[a][i] - m.vv[a]);
    }
    if (stress != SPS__IMAGE_STRESS_NONE) { /* (tau_i + tau_j') . e dW V_j */
        sps_real tj[9];
        sps__image_stress(w, b, wall, m, tj, dim, stress);
        SPS__UNROLL
        for (a = 0; a < dim; ++a)
            SPS__UNROLL
            for (c = 0; c < dim; ++c) acc[a * stride] += (tau_i[sps__sym9[3 * a + c] * stride] + tj[3 * a + c]) * dir[c] * e.dw * vol * b->divergence_scale;
    }
}
SPS__INLINE void sps__images_force_lanes(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, const sps__reflection* rf,
                                         sps_real (*SPS__RESTRICT acc)[SPS__LANES], const int dim, const int corner, const int newton, const int stress) {
    const sps__wall* wall = rf->wall[0];
    sps_real tau_i[6][SPS__LANES]; /* the lanes' own deviators side by side (as sps__own_lanes) */
    int m, l;
    if (stress != SPS__IMAGE_STRESS_NONE)
        for (m = 0; m < 6; ++m)
            for (l = 0; l < SPS__LANES; ++l) tau_i[m][l] = b->tau[6 * (lanes->i[l] - b->begin) + m];
    SPS__IMAGE_LOOP(w, b, lanes, rf, dim, corner, m, l,
                    { sps__image_force(w, b, wall, i, im, e, &tau_i[0][l], &acc[0][l], SPS__LANES, dim, newton, stress); })
}
/* Adds the images' force across reflection rf to the lanes' sums acc (3 rows). A stress body's
   images (granular) have no corners. */
static void sps__images_force(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, const sps__reflection* rf, void* acc_rows) {
    sps_real(*acc)[SPS__LANES] = (sps_real(*)[SPS__LANES])acc_rows;
    switch (sps__image_stress_mode(b, rf->wall[0], 0)) {
    case SPS__IMAGE_STRESS_REFLECTED:
        SPS__BY_DIM(w, sps__images_force_lanes(w, b, lanes, rf, acc, 2, 0, 0, SPS__IMAGE_STRESS_REFLECTED),
                    sps__images_force_lanes(w, b, lanes, rf, acc, 3, 0, 0, SPS__IMAGE_STRESS_REFLECTED));
        break;
    case SPS__IMAGE_STRESS_EVEN:
        SPS__BY_DIM(w, sps__images_force_lanes(w, b, lanes, rf, acc, 2, 0, 0, SPS__IMAGE_STRESS_EVEN),
                    sps__images_force_lanes(w, b, lanes, rf, acc, 3, 0, 0, SPS__IMAGE_STRESS_EVEN));
        break;
    case SPS__IMAGE_STRESS_CONTINUED:
        SPS__BY_DIM(w, sps__images_force_lanes(w, b, lanes, rf, acc, 2, 0, 0, SPS__IMAGE_STRESS_CONTINUED),
                    sps__images_force_lanes(w, b, lanes, rf, acc, 3, 0, 0, SPS__IMAGE_STRESS_CONTINUED));
        break;
    default: /* a fluid (no stress), viscous or not, with its corners */
        if (b->model.viscous == SPS__VISCOUS_NEWTON)
            SPS__BY_DIM(w,
                        SPS__BY_CORNER(rf, sps__images_force_lanes(w, b, lanes, rf, acc, 2, 0, 1, SPS__IMAGE_STRESS_NONE),
                                       sps__images_force_lanes(w, b, lanes, rf, acc, 2, 1, 1, SPS__IMAGE_STRESS_NONE)),
                        SPS__BY_CORNER(rf, sps__images_force_lanes(w, b, lanes, rf, acc, 3, 0, 1, SPS__IMAGE_STRESS_NONE),
                                       sps__images_force_lanes(w, b, lanes, rf, acc, 3, 1, 1, SPS__IMAGE_STRESS_NONE)));
        else
            SPS__BY_DIM(w,
                        SPS__BY_CORNER(rf, sps__images_force_lanes(w, b, lanes, rf, acc, 2, 0, 0, SPS__IMAGE_STRESS_NONE),
                                       sps__images_force_lanes(w, b, lanes, rf, acc, 2, 1, 0, SPS__IMAGE_STRESS_NONE)),
                        SPS__BY_CORNER(rf, sps__images_force_lanes(w, b, lanes, rf, acc, 3, 0, 0, SPS__IMAGE_STRESS_NONE),
                                       sps__images_force_lanes(w, b, lanes, rf, acc, 3, 1, 0, SPS__IMAGE_STRESS_NONE)));
    }
}

static sps_real sps__wall_sigma(const sps_world* w, sps_real d);
static void sps__add_friction(sps_real mu, sps_real f_n, sps_real drag, const sps_real v_t[3], int dim, sps_real f[3]);
/* The backstop of wall wl on particle i, added to acc (force per volume): closer to the wall
   than dp/2, where no particle of a lattice fill stands, the solids' contact pressure K sigma
   counted from sigma(dp/2) on, which holds the particles that the corners' missing images
   would let through; for a body on the hexagonal lattice from dp/5 on (its rows' half
   particles stand a quarter spacing, 0.27 dp, from the box's faces: pushed off a wall from dp/2
   on, water on it started with a jolt and churned; sps_lattice). */
#define SPS__HEXAGONAL_BACKSTOP SPS_R(0.2) /* [dp] */
static void sps__add_backstop(const sps_world* w, const sps__body* b, int i, const sps__wall* wl, sps_real acc[3]) {
    const sps_real d = sps__wall_distance(w, wl, i), depth = (b->hexagonal ? SPS__HEXAGONAL_BACKSTOP : SPS_R(0.5)) * w->def.dp;
    int a;
    if (!(d < depth)) return;
    for (a = 0; a < w->dim; ++a)
        acc[a] += 2 * b->mat.K * (sps__wall_sigma(w, d) - sps__wall_sigma(w, depth)) * sps__plane_table_at(w, w->wall_plane, SPS__WALL_TABLE, d) *
                  wl->normal[a];
}

/* The force per volume of wall wl on a granular particle i: its images' and the
   backstop's and, on a free-slip wall with sps_world_set_wall_friction(mu) (its reflected
   images take no shear), Coulomb's friction mu f_n against the tangential velocity, f_n the
   normal part of the images' and backstop's force (sps__add_friction, with the solids' stick
   drag rho_i / (2 dt)): the basal friction of a granular flow on a smooth bed. A no-slip wall
   takes the shear through its images' stress, as much as the particle's stress can carry; a
   Coulomb bound tan(phi) f_n added there stopped C4's free grains but shot a particle out of
   C7 at dp 0.04 (11 m/s at 0.5 s), so it is not applied (bench/VALIDATION.md). Here for lane
   group q's lanes within 2h of the wall (rf's), added to the sums of sps__mirror_force. */
typedef struct sps__wall_forces {
    sps_real acc[3][SPS__LANES]; /* the lanes' sums */
    sps_real dt;
} sps__wall_forces;
static void sps__stress_images_wall_force(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, const sps__reflection* rf, void* user) {
    sps__wall_forces* s = (sps__wall_forces*)user;
    const sps__wall* wl = rf->wall[0];
    sps_real f[3][SPS__LANES];
    int l, a;
    memset(f, 0, sizeof f);
    sps__images_force(w, b, lanes, rf, f);
    for (l = 0; l < SPS__LANES; ++l) {
        const int i = lanes->i[l];
        sps_real fl[3], f_n = 0, v_n = 0, v_t[3] = {0, 0, 0};
        if (!rf->on[l]) continue; /* no image, no backstop, no friction: most particles */
        for (a = 0; a < 3; ++a) fl[a] = f[a][l];
        sps__add_backstop(w, b, i, wl, fl);
        if (wl->slip != SPS_WALL_NO_SLIP && wl->friction > 0) {
            for (a = 0; a < w->dim; ++a) {
                f_n += fl[a] * wl->normal[a];
                v_n += w->vel[a][i] * wl->normal[a];
            }
            for (a = 0; a < w->dim; ++a) v_t[a] = w->vel[a][i] - v_n * wl->normal[a];
            if (f_n > 0) sps__add_friction(wl->friction, f_n, w->rho[i] / (2 * s->dt), v_t, w->dim, fl);
        }
        for (a = 0; a < w->dim; ++a) s->acc[a][l] += fl[a];
    }
}

/* Adds the walls' force to the lanes' particles of body b (acc_p; the contact pass, after their
   contact forces): their images' pressure (and viscous, and stress) force and the backstops; a
   granular body's wall by wall with each wall's Coulomb bound (sps__stress_images_wall_force). */
static void sps__mirror_force(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, sps_real dt) {
    sps__wall_forces s;
    int l, a, k;
    memset(&s, 0, sizeof s);
    s.dt = dt;
    if (b->model.mirrored == SPS__MIRROR_STRESS) { /* wall by wall, for each wall's friction */
        sps__each_reflection(w, b, lanes, 0, sps__stress_images_wall_force, &s);
    } else {
        sps__each_reflection(w, b, lanes, 1, sps__images_force, s.acc);
        for (l = 0; l < SPS__LANES && lanes->among[l]; ++l) {
            sps_real acc[3];
            for (a = 0; a < 3; ++a) acc[a] = s.acc[a][l];
            for (k = 0; k < w->nwalls; ++k) sps__add_backstop(w, b, lanes->i[l], &w->walls[k], acc);
            for (a = 0; a < 3; ++a) s.acc[a][l] = acc[a];
        }
    }
    for (l = 0; l < SPS__LANES && lanes->among[l]; ++l)
        for (a = 0; a < w->dim; ++a) w->acc_p[a][lanes->i[l]] += s.acc[a][l] / w->rho[lanes->i[l]];
}

/* Which particles of lane group q of body b are within 2h of a wall (of a no-slip wall with
   no_slip), into near: the others take no images, no backstop (their force is 0) and measure no
   equilibrium. */
SPS__INLINE void sps__group_near_walls_in(const sps_world* w, const sps__body* b, sps__group q, int no_slip, int* near, const int dim) {
    int k, l;
    for (l = 0; l < SPS__LANES; ++l) near[l] = 0;
    for (k = 0; k < w->nwalls; ++k) {
        const sps__wall wall = w->walls[k]; /* a local: no pointer read in the loop */
        if (no_slip && wall.slip != SPS_WALL_NO_SLIP) continue;
        SPS__PRAGMA(omp simd)
        for (l = 0; l < SPS__LANES; ++l) near[l] |= sps__wall_distance_in(w, &wall, q.i0 + l, dim) < w->support; /* padded arrays */
    }
    for (l = 0; l < SPS__LANES; ++l) near[l] &= q.i0 + l < b->end;
}

/* Lanes n and on (unused) repeat lane 0's particle and are not among; len is the most
   neighbours of any lane's particle. */
static void sps__pad_lanes(const sps_world* w, sps__image_lanes* lanes, int n) {
    int l;
    lanes->len = 0;
    for (l = 0; l < SPS__LANES; ++l) {
        if (l >= n) lanes->i[l] = lanes->i[0];
        lanes->among[l] = l < n;
        if (w->nb_count[lanes->i[l]] > lanes->len) lanes->len = w->nb_count[lanes->i[l]];
    }
}

/* Runs `pass` over the particles of body b within 2h of a wall (of a no-slip wall with
   no_slip), LANES at a time in the order of the body, from the lane groups the calling thread
   owns (sps__group_share), then waits for the other threads. */
static void sps__run_near_walls(sps_world* w, const sps__body* b, int no_slip,
                                void (*pass)(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, sps_real arg), sps_real arg) {
    sps__image_lanes lanes;
    int g, g0, g1, l, near[SPS__LANES], n = 0;
    sps__group_share(w, b, &g0, &g1);
    for (g = g0; g < g1; ++g) {
        const sps__group q = sps__group_of(w, b, g);
        SPS__BY_DIM(w, sps__group_near_walls_in(w, b, q, no_slip, near, 2), sps__group_near_walls_in(w, b, q, no_slip, near, 3));
        for (l = 0; l < SPS__LANES; ++l) {
            if (!near[l]) continue;
            lanes.i[n++] = q.i0 + l;
            if (n < SPS__LANES) continue;
            sps__pad_lanes(w, &lanes, n);
            pass(w, b, &lanes, arg);
            n = 0;
        }
    }
    if (n > 0) {
        sps__pad_lanes(w, &lanes, n);
        pass(w, b, &lanes, arg);
    }
    SPS__PRAGMA(omp barrier)
}

/* Lane group q of body b as image lanes: its lanes past the body's end repeat its first
   particle and are not among. */
static void sps__group_lanes(const sps__body* b, sps__group q, sps__image_lanes* lanes) {
    int l;
    for (l = 0; l < SPS__LANES; ++l) {
        lanes->among[l] = q.i0 + l < b->end;
        lanes->i[l] = lanes->among[l] ? q.i0 + l : q.i0;
    }
    lanes->len = q.len;
}

/* The continuity pass's terms (sps__continuity_pairs with riemann) of image m of particle i
   with geometry e, added to sum (rows `stride` apart): with gradient the velocity gradient's
   sums, else a fluid's divergence as sps__continuity_pairs'. The velocity gradient of a body
   whose images carry its stress (stress; granular) takes the no-slip image velocity at a
   no-slip wall (the shear that carries the wall's friction); a fluid's the reflected one (the
   normal part alone enters its density rate). Also the fluid-structure coupling's. */
SPS__INLINE void sps__image_continuity(const sps_world* w, const sps__body* b, int i, sps__image m, sps__pair_geometry e, sps_real* sum,
                                       int stride, const int dim, const int gradient, const int stress) {
    const sps_real* v = stress ? m.vv : m.v;
    const sps_real* rest = b->rest_pressure_gradient;
    const sps_real dir[3] = {e.ex, e.ey, e.ez}, dwv = e.dw * w->vol[m.j];
    sps_real dv[3], rest_dp;
    int a, c;
    SPS__UNROLL
    for (a = 0; a < 3; ++a) dv[a] = a < dim ? w->vel[a][i] - v[a] : 0;
    rest_dp = e.r * (rest[0] * dir[0] + rest[1] * dir[1] + rest[2] * dir[2]); /* the image pair's hydrostatic difference */
    sum[SPS__DRHO * stride] += (w->p[i] - m.p - rest_dp) / b->z_riemann * dwv * b->density_diffusion;
    if (!gradient) {
        sum[SPS__DRHO * stride] += b->divergence_scale * (dv[0] * dir[0] + dv[1] * dir[1] + dv[2] * dir[2]) * dwv;
        return;
    }
    SPS__UNROLL
    for (a = 0; a < dim; ++a)
        SPS__UNROLL
        for (c = 0; c < dim; ++c) sum[(SPS__M00 + 3 * a + c) * stride] -= dv[a] * dwv * dir[c];
    sps__add_moment(&sum[SPS__A00 * stride], stride, e.ex, e.ey, e.ez, e.r * dwv, dim);
}
SPS__INLINE void sps__images_continuity_lanes(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, const sps__reflection* rf,
                                              sps_real (*SPS__RESTRICT sum)[SPS__LANES], const int dim, const int corner, const int gradient, const int stress) {
    int m, l;
    SPS__IMAGE_LOOP(w, b, lanes, rf, dim, corner, m, l, { sps__image_continuity(w, b, i, im, e, &sum[0][l], SPS__LANES, dim, gradient, stress); })
}
/* Adds the images' terms across reflection rf to the continuity sums (sps__lane_sums rows). */
static void sps__images_continuity(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, const sps__reflection* rf, void* sum_rows) {
    sps_real(*sum)[SPS__LANES] = (sps_real(*)[SPS__LANES])sum_rows;
    if (b->model.mirrored == SPS__MIRROR_STRESS) /* granular: the velocity gradient, from the viscous image velocity; no corners */
        SPS__BY_DIM(w, sps__images_continuity_lanes(w, b, lanes, rf, sum, 2, 0, 1, 1), sps__images_continuity_lanes(w, b, lanes, rf, sum, 3, 0, 1, 1));
    else if (b->model.gradient) /* a fluid without gravity */
        SPS__BY_DIM(w,
                    SPS__BY_CORNER(rf, sps__images_continuity_lanes(w, b, lanes, rf, sum, 2, 0, 1, 0),
                                   sps__images_continuity_lanes(w, b, lanes, rf, sum, 2, 1, 1, 0)),
                    SPS__BY_CORNER(rf, sps__images_continuity_lanes(w, b, lanes, rf, sum, 3, 0, 1, 0),
                                   sps__images_continuity_lanes(w, b, lanes, rf, sum, 3, 1, 1, 0)));
    else
        SPS__BY_DIM(w,
                    SPS__BY_CORNER(rf, sps__images_continuity_lanes(w, b, lanes, rf, sum, 2, 0, 0, 0),
                                   sps__images_continuity_lanes(w, b, lanes, rf, sum, 2, 1, 0, 0)),
                    SPS__BY_CORNER(rf, sps__images_continuity_lanes(w, b, lanes, rf, sum, 3, 0, 0, 0),
                                   sps__images_continuity_lanes(w, b, lanes, rf, sum, 3, 1, 0, 0)));
}

/* Adds the images' terms to the continuity sums of lane group q of body b. */
static void sps__mirror_continuity(sps_world* w, const sps__body* b, sps__group q, sps_real sum[SPS__NSUM][SPS__LANES]) {
    sps__image_lanes lanes;
    sps__group_lanes(b, q, &lanes);
    sps__each_reflection(w, b, &lanes, b->model.mirrored != SPS__MIRROR_STRESS, sps__images_continuity, sum);
}

/* >>coupling: fluid-structure (Zhang, Rezavand and Hu 2021, JCP 429, 110028, section 3; the
   reference code's fluid-structure examples)

   A fluid particle f sees the particles s of a solid body it touches (elastic, J2, total
   Lagrangian, rigid) as a moving wall, as the walls' mirror images (>>walls for fluids) but
   with the solid's own particles in place of the images: each is an image at x_s, of volume
   V_s, with the velocity 2 v_s - v_f (the fluid's velocity reflected about the wall's, so the
   Riemann solver's interface velocity is the solid's) and the wall pressure
       p_w = p_f + rho_f g . (x_s - x_f)
   (the fluid's own pressure continued by its acceleration relative to the wall; the solid's
   acceleration is left out, and unlike the reference code the term is not clamped at 0, as
   the mirror images' hydrostatic continuation: a clamp pushes a fluid at a vertical wall
   down). The solid particles complete the fluid particle's kernel, so water at rest stands
   on a solid as on an analytic wall (its first layer dp from the solid's surface particles)
   and water filled up to a solid on the lattice starts at rest. The images enter the fluid's
   pressure force (sps__image_force: 2 P* dW V_s with the limited Riemann dissipation, and the
   no-slip viscous force of a viscous fluid) and its continuity sums (sps__image_continuity:
   the density rate, the Riemann density term, the velocity gradient, B). The solid receives
   the pair's force with the opposite sign, computed by the same function from the same
   values: momentum is exact (the pair force is along e_fs only for an inviscid fluid, so
   angular momentum is exact then). The pairs are the contact lists' (a fluid-solid pair of
   bodies that touch: the contact penalty is not applied to it), so a fluid pays for the
   coupling only where it is within 2h of a solid, and a scene without one runs none of it. */

/* Whether bodies a and b are a fluid and a solid (in either order): a fluid is a material
   without shear stress (its row's shear = 0), a solid a body whose walls are not mirror images
   (elastic, J2, total Lagrangian, rigid; not granular). */
static int sps__fluid_solid(const sps_world* w, int a, int b) {
    const sps__material_model *ma = w->bodies[a].model.material, *mb = w->bodies[b].model.material;
    return (!ma->shear && !mb->mirrored) || (!mb->shear && !ma->mirrored);
}

static int sps__bodies_touch(const sps_world* w, int a, int b);
/* Warns of each fluid-solid pair of bodies that does not touch (a def's contact = 0 or
   sps_world_set_contact(w, a, b, 0)): the fluid would flow through the solid. */
static void sps__warn_uncoupled(const sps_world* w) {
    int a, b;
    for (a = 0; a < w->nbodies; ++a)
        for (b = a + 1; b < w->nbodies; ++b)
            if (sps__fluid_solid(w, a, b) && !sps__bodies_touch(w, a, b))
                sps__warn(w, "bodies '%s' and '%s' (a fluid and a solid) do not touch (contact = %d and %d, or sps_world_set_contact "
                          "turned the pair off): the fluid flows through the solid; the fluid-structure coupling needs contact = 1 on "
                          "both and the pair not separated", w->bodies[a].name, w->bodies[b].name, w->bodies[a].def.contact,
                          w->bodies[b].def.contact);
}

/* The signal speed of the coupled pairs: a solid particle held by a fluid's pressure moves as
   in a medium of the fluid's bulk modulus and the solid's density, c = c0_f sqrt(rho0_f /
   rho0_s), which exceeds both bodies' own speeds when the solid is light and soft (the added-
   mass limit of an explicit coupling); the time step takes it beside the bodies' speeds. Measured
   (bench/VALIDATION.md, fluid-structure): without it a block of density 20 and E = 4 kPa
   in water blew up in the first steps. 0 without coupled pairs (the touch table set). */
static sps_real sps__coupling_speed(const sps_world* w) {
    sps_real c_max = 0;
    int a, b;
    for (a = 0; a < w->nbodies; ++a)
        for (b = 0; b < w->nbodies; ++b) {
            const sps__body *fluid = &w->bodies[a], *solid = &w->bodies[b];
            sps_real c;
            if (w->touch[(size_t)a * w->nbodies + b] != SPS__TOUCH_COUPLED || fluid->model.material->shear ||
                solid->model.material->kinematic)
                continue;
            c = fluid->mat.c0 * SPS__SQRT(fluid->rho0 / solid->rho0);
            if (c > c_max) c_max = c;
        }
    return c_max;
}

/* Whether the bodies of particles i and j are a coupled fluid-solid pair (their touch flag). */
static int sps__coupled_pair(const sps_world* w, int i, int j) {
    return w->touch[(size_t)w->body[i] * w->nbodies + w->body[j]] == SPS__TOUCH_COUPLED;
}

/* Solid particle s as the wall image of fluid particle f (see the chapter's head). */
static void sps__solid_image(const sps_world* w, int f, int s, sps__image* image) {
    sps_real gd = 0;
    int a;
    image->j = s;
    for (a = 0; a < 3; ++a) {
        image->x[a] = a < w->dim ? w->pos[a][s] : 0;
        image->v[a] = image->vv[a] = a < w->dim ? 2 * w->vel[a][s] - w->vel[a][f] : 0;
        gd += a < w->dim ? w->def.gravity[a] * (w->periodic ? sps__nearest_image(w, a, w->pos[a][s] - w->pos[a][f]) : w->pos[a][s] - w->pos[a][f]) : 0;
    }
    image->p = w->p[f] + w->rho[f] * gd;
}

/* Adds the force of the pair (i, j) on particle i [N] (N/m in 2D) to force: one of them a fluid
   particle f, the other a solid particle s. The force on f is V_f times sps__image_force's
   sum; s gets its opposite. */
static void sps__coupling_force(sps_world* w, int i, int j, sps_real force[3]) {
    const int i_fluid = !w->bodies[w->body[i]].model.material->shear; /* the fluid: no shear stress */
    const int f = i_fluid ? i : j, s = i_fluid ? j : i;
    const sps_real sign = i_fluid ? w->vol[f] : -w->vol[f];
    const sps__body* fluid = &w->bodies[w->body[f]];
    sps_real acc[3] = {0, 0, 0};
    sps__image image;
    int a;
    sps__solid_image(w, f, s, &image);
    sps__image_force(w, fluid, NULL, f, image, sps__image_geometry(w, f, image, 1, w->dim), NULL, acc, 1, w->dim,
                     fluid->model.viscous == SPS__VISCOUS_NEWTON, SPS__IMAGE_STRESS_NONE);
    for (a = 0; a < w->dim; ++a) force[a] += sign * acc[a];
}

/* The next coupled solid particle within 2h of fluid particle f from its contact *k on, as its
   image (the walls' images for the solids): 1 with *k at it, 0 past f's last contact. */
static int sps__next_solid_image(const sps_world* w, int f, int* k, sps__image* image) {
    for (; *k < w->ct_first[f + 1]; ++*k)
        if (sps__coupled_pair(w, f, w->ct_j[*k])) {
            sps__solid_image(w, f, w->ct_j[*k], image);
            return 1;
        }
    return 0;
}

/* Adds the solid images' terms to the continuity sums of lane group q of fluid body b. */
static void sps__coupling_continuity(sps_world* w, const sps__body* b, sps__group q, sps_real sum[SPS__NSUM][SPS__LANES]) {
    sps__image image;
    int l, k;
    for (l = 0; l < SPS__LANES && q.i0 + l < b->end; ++l)
        for (k = w->ct_first[q.i0 + l]; sps__next_solid_image(w, q.i0 + l, &k, &image); ++k)
            sps__image_continuity(w, b, q.i0 + l, image, sps__image_geometry(w, q.i0 + l, image, 1, w->dim), &sum[0][l], SPS__LANES, w->dim,
                                  b->model.gradient, 0);
}

/* The pair loop of the continuity pass for lane group g. Pair terms: u = v_ij.e_ij; drho += u dW
   V_j (ANG eq. 15); with laplacian lap += u/r dW V_j e_ij (ENO eq. 23); with gradient M -= v_ij
   (x) e_ij dW V_j (velocity gradient before correction) and A -= r_ij (x) e_ij dW V_j (B^-1);
   paired (SPS_ROTATION_PAIR) adds each ENO increment to its pair's force g_ij += 2 zeta G dt
   (v_ij . e_ij) dW/r V_i V_j instead of the particle's Laplacian: every factor is symmetric in
   i, j bit for bit, so g_ij = g_ji and the shear forces stay exactly antisymmetric. riemann (a
   fluid) adds the Riemann solver's pressure term to the density rate, drho += (p_i - p_j -
   rho0 g . x_ij) / (rho0 c0) dW V_j (UTVF eqs. 16, 18: 2 (v_i - v*) . e_ij with the acoustic
   U*), which diffuses the density (less its hydrostatic part: sps__fluid_rest_gradient), in
   place of u dW V_j: a granular body's velocity divergence is tr L (sps__continuity_lanes), and
   so is a fluid's without gravity (sps__fluid_model); under gravity a fluid's (divergence) is
   u dW V_j / c, scaled by the lattice moment as its pressure force
   (sps__lattice_gradient_moment), so that the two are adjoint and a fluid's energy is
   conserved (tr L is not: water at rest gained energy and its pressure crept up, and a
   standing wave its amplitude; bench/VALIDATION.md, "Still water"). */
SPS__INLINE void sps__continuity_pairs(sps_world* w, const sps__body* b, int g, sps_real dt, sps__lane_sums* SPS__RESTRICT sums, const int dim,
                                       const int geo, const int terms) {
    const int gradient = (terms & SPS__TERM_GRADIENT) != 0, paired = (terms & SPS__TERM_PAIRED) != 0;
    const int laplacian = (terms & SPS__TERM_LAPLACIAN) != 0, riemann = (terms & SPS__TERM_RIEMANN) != 0;
    const int divergence = (terms & SPS__TERM_DIVERGENCE) != 0;
    const sps__group q = sps__group_of(w, b, g);
    const sps_real scale = divergence ? b->divergence_scale : 0;
    const sps_real shear_rate = 2 * b->zeta * b->mat.G * dt; /* ENO eq. 24 without 1/rho_i */
    const sps_real inv_z = riemann ? b->density_diffusion / b->z_riemann : 0; /* 0: material.fluid.dissipation = none */
    const sps_real rest_x = b->rest_pressure_gradient[0], rest_y = b->rest_pressure_gradient[1], rest_z = b->rest_pressure_gradient[2];
    const sps_real *SPS__RESTRICT vol = w->vol, *SPS__RESTRICT p = w->p;
    const sps_real *SPS__RESTRICT vx = w->vel[0], *SPS__RESTRICT vy = w->vel[1], *SPS__RESTRICT vz = w->vel[2];
    sps_real* SPS__RESTRICT pair_force = w->pair_force;
    sps_real(*sum)[SPS__LANES] = sums->row;
    int k, l;
    SPS__PAIR_LOOP(w, q, dim, geo, k, l, {
            const sps_real ex = e.ex, ey = e.ey, ez = e.ez, dw = e.dw, dw_r = e.dw_r;
            const sps_real dvx = vx[i] - vx[j], dvy = vy[i] - vy[j], dvz = dim == 3 ? vz[i] - vz[j] : 0;
            const sps_real u = dvx * ex + dvy * ey + dvz * ez, dwv = dw * vol[j];
            const sps_real rest_dp = riemann ? e.r * (rest_x * ex + rest_y * ey + (dim == 3 ? rest_z * ez : 0)) : 0;
            sum[SPS__DRHO][l] += riemann ? (p[i] - p[j] - rest_dp) * inv_z * dwv + scale * u * dwv : u * dwv; /* granular: u in tr L */
            if (paired) {
                pair_force[s] += shear_rate * (u * dw_r) * (vol[i] * vol[j]);
            } else if (laplacian) {
                const sps_real lv = u * dw_r * vol[j];
                sum[SPS__LX][l] += lv * ex;
                sum[SPS__LY][l] += lv * ey;
                if (dim == 3) sum[SPS__LZ][l] += lv * ez;
            }
            if (gradient) {
                const sps_real gx = dvx * dwv, gy = dvy * dwv, gz = dvz * dwv, rdwv = e.r * dwv;
                sum[SPS__M00][l] -= gx * ex; sum[SPS__M01][l] -= gx * ey;
                sum[SPS__M10][l] -= gy * ex; sum[SPS__M11][l] -= gy * ey;
                if (dim == 3) {
                    sum[SPS__M02][l] -= gx * ez; sum[SPS__M12][l] -= gy * ez;
                    sum[SPS__M20][l] -= gz * ex; sum[SPS__M21][l] -= gz * ey; sum[SPS__M22][l] -= gz * ez;
                }
                sps__add_moment(&sum[SPS__A00][l], SPS__LANES, ex, ey, ez, rdwv, dim);
            }
    })
}

/* The continuity pass's finish for lane group q (g), from the pair loop's sums: the walls' and
   the coupled solids' images, the density rate and the velocity gradient
   (sps__continuity_lanes), the stress update with the body's return map, the Rodrigues matrices
   and this group's share of the mean rotation (ANG eq. 41, summed in group order by
   sps__continuity_pass), and the ENO increments (on ENO bodies without the pair rotation). The
   choices are the body's model's. */
SPS__INLINE void sps__continuity_finish(sps_world* w, const sps__body* b, sps__group q, int g, sps_real dt, sps__lane_sums* sums,
                                        const int dim) {
    const sps__model* m = &b->model;
    const int end = b->end, eno_particles = m->stabilisation->eno && !m->paired, relax = !m->paired;
    /* the turn this pass applies: ENO's increments, and the mean rotation's sum for GNO-A too */
    const sps__turn turn = eno_particles || m->turn == SPS__TURN_MEAN ? m->turn : SPS__TURN_NONE;
    const sps_real shear_rate = 2 * b->zeta * b->mat.G * dt; /* ENO eq. 24 without 1/rho_i */
    sps_real(*sum)[SPS__LANES] = sums->row;
    sps_real da[3][SPS__LANES], L[9][SPS__LANES], R[9][SPS__LANES];
    sps_real rsum[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    int l, a;
    if (m->mirrored && w->nwalls > 0) sps__mirror_continuity(w, b, q, sum);
    if (m->riemann_density && b->coupled) sps__coupling_continuity(w, b, q, sum);
    if (!m->gradient) sps__continuity_lanes(w, b, q, dim, 0, 0, shear_rate, sum, da, L);
    else if (!m->riemann_density) sps__continuity_lanes(w, b, q, dim, 1, 0, shear_rate, sum, da, L);
    else sps__continuity_lanes(w, b, q, dim, 1, 1, shear_rate, sum, da, L); /* granular: the divergence tr L */
    sps__stress_update_lanes(w, b, q, dim, dt, L, relax);
    if (turn != SPS__TURN_NONE) sps__rotation_lanes(b, q, dt, dim, L, R);
    if (turn == SPS__TURN_MEAN) {
        for (l = 0; l < SPS__LANES && q.i0 + l < end; ++l)
            for (a = 0; a < 9; ++a) rsum[a] += R[a][l];
        memcpy(w->group_sum + (size_t)9 * (b->group0 + g), rsum, sizeof rsum);
    }
    if (!eno_particles) return;
    switch (turn) {
    case SPS__TURN_NONE: sps__add_increments(w, b, q, dim, da, R, SPS__TURN_NONE); break;
    case SPS__TURN_MEAN: sps__add_increments(w, b, q, dim, da, R, SPS__TURN_MEAN); break;
    case SPS__TURN_PARTICLE: sps__add_increments(w, b, q, dim, da, R, SPS__TURN_PARTICLE); break;
    }
}

/* Continuity pass (step 4) for lane group g: the body's pair loop, then the finish. */
static void sps__continuity(sps_world* w, const sps__body* b, int g, sps_real dt) {
    sps__lane_sums sums;
    const sps__group q = sps__group_of(w, b, g);
    sps__clear_sums(&sums, SPS__NSUM);
    b->model.pass.continuity_pairs(w, b, g, dt, b->model.pass.continuity_terms, &sums);
    if (w->dim == 2) sps__continuity_finish(w, b, q, g, dt, &sums, 2);
    else sps__continuity_finish(w, b, q, g, dt, &sums, 3);
}

/* The continuity pass's pair loops: (name, pair terms). */
#ifdef SPHSOLID_NO_FLUID
#define SPS__CONTINUITY_FLUID_LOOPS(X)
#else
#define SPS__CONTINUITY_FLUID_LOOPS(X) X(fluid, SPS__TERM_RIEMANN | SPS__TERM_DIVERGENCE)
#endif
#if defined(SPHSOLID_NO_GRANULAR) && defined(SPHSOLID_NO_FLUID)
#define SPS__CONTINUITY_RIEMANN_GRADIENT_LOOPS(X)
#else /* granular media, and fluids without gravity (sps__fluid_model): the divergence tr L */
#define SPS__CONTINUITY_RIEMANN_GRADIENT_LOOPS(X) X(riemann_gradient, SPS__TERM_GRADIENT | SPS__TERM_RIEMANN)
#endif
#define SPS__CONTINUITY_LOOPS(X)                                  \
    X(eno, SPS__TERM_LAPLACIAN)                                   \
    X(eno_gradient, SPS__TERM_LAPLACIAN | SPS__TERM_GRADIENT)     \
    X(eno_pairs, SPS__TERM_PAIRED)                                \
    X(eno_pairs_gradient, SPS__TERM_PAIRED | SPS__TERM_GRADIENT)  \
    X(gradient, SPS__TERM_GRADIENT)                               \
    SPS__CONTINUITY_FLUID_LOOPS(X)                                \
    SPS__CONTINUITY_RIEMANN_GRADIENT_LOOPS(X)
#define SPS__CONTINUITY_INSTANCES(variant, terms) SPS__INSTANCES(continuity_pairs, variant, terms)
SPS__GENERIC_LOOPS(continuity_pairs)
SPS__CONTINUITY_LOOPS(SPS__CONTINUITY_INSTANCES)

static void sps__continuity_pass(sps_world* w, sps__body* b, sps_real dt) {
    int g, a;
    sps_real acc[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    if (b->end == b->begin || !b->model.pass.continuity) return;
    sps__run_groups(w, b, b->model.pass.continuity, dt);
    if (b->model.turn != SPS__TURN_MEAN) return;
    SPS__PRAGMA(omp single)
    {
        for (g = 0; g < b->ngroups; ++g) /* ANG eq. 41: mean rotation, groups in a fixed order */
            for (a = 0; a < 9; ++a) acc[a] += w->group_sum[(size_t)9 * (b->group0 + g) + a];
        for (a = 0; a < 9; ++a) b->mean_rotation[a] = acc[a] / (b->end - b->begin);
        sps__spin_of_rotation(b->mean_rotation, dt, w->dim, b->mean_spin);
    }
}

/* Hourglass penalty of GNO / GNO-A for lane group g with v^_ij = v_ij - 1/2 (L_i + L_j) r_ij,
   the velocity difference the linear field does not explain (ANG eq. 44):
   GNO   (ANG eq. 43): da = xi G/rho_i dt sum_j v^_ij / r_ij dW_ij V_j
   GNO-A (ANG eq. 46, projected): da = xi G/rho_i dt sum_j (v^_ij . e_ij) / r_ij dW_ij e_ij V_j,
   then rotated (sps__penalty_finish).
   With r_ij = r e_ij: v^_ij / r_ij dW = v_ij dW/r - 1/2 (L_i + L_j) e_ij dW.
   paired (SPS_ROTATION_PAIR): GNO-A's increment goes to the pair's force,
   g_ij += xi G dt (v^_ij . e_ij) / r_ij dW V_i V_j (symmetric in i, j bit for bit).
   scaled (J2 bodies): each pair's term is weighted by 1/2 (r_i + r_j), the mean of the two
   particles' radial-return factors of this sub-step (1 while elastic): the reference code's
   xi_i = xi r_i, so that the penalty, an elastic stiffness G, softens where the stress is held
   on the yield surface. Our extension: the stored penalty is relaxed by the same factors (a_s_i
   by r_i in sps__j2_stress_lanes; a pair force g_ij by 1/2 (r_i + r_j) here), as the return
   map relaxes the stress. r is within O(dt) of 1 in a sub-step, so scaling only the increments
   leaves the stored penalty an elastic spring of stiffness xi G against the non-affine part of
   a plastic flow, which grows without bound and, once the particles have rearranged, does
   work: measured, the square Taylor bar gained 27 % (L/dp 16) and 54 % (L/dp 20) of its
   impact energy and the round bar (R/9) five times it (bench/VALIDATION.md, B). The pair loop,
   its sums into rows 0-2. */
SPS__INLINE void sps__penalty_pairs(sps_world* w, const sps__body* b, int g, sps_real dt, sps__lane_sums* SPS__RESTRICT sums, const int dim,
                                    const int geo, const int terms) {
    const int projected = (terms & SPS__TERM_PROJECTED) != 0, paired = (terms & SPS__TERM_PAIRED) != 0;
    const int scaled = (terms & SPS__TERM_SCALED) != 0;
    const sps__group q = sps__group_of(w, b, g);
    const sps_real* SPS__RESTRICT vol = w->vol;
    const sps_real penalty_rate = b->xi * b->mat.G * dt; /* ANG eqs. 43, 46 without 1/rho_i */
    sps_real(*sum)[SPS__LANES] = sums->row;
    sps_real L_i[9][SPS__LANES];
    int k, l, a;
    sps__own_lanes(b->grad, 9, q.i0 - b->begin, L_i);
    SPS__PAIR_LOOP(w, q, dim, geo, k, l, {
            const sps__penalty_velocity t = sps__penalty_term(w, b, i, j, l, e, L_i, dim, scaled);
            if (paired) {
                const sps_real dir[3] = {e.ex, e.ey, e.ez};
                sps_real u_pair = 0;
                SPS__UNROLL
                for (a = 0; a < dim; ++a) u_pair += t.v[a] * dir[a];
                if (scaled) w->pair_force[s] *= t.scale;
                w->pair_force[s] += penalty_rate * u_pair * (vol[i] * vol[j]);
            } else {
                sps__add_penalty_term(sum, l, t, e, vol[j], dim, projected);
            }
    })
}

/* The penalty pass's finish for lane group q: the increments da = xi G dt / rho_i sum (the sums'
   rows sum), turned as the body's model says (sps__add_increments). With the penalty in the
   pressure pass, sps__finish has already turned a_s by the mean rotation (without increments),
   so they are added to it: a_s = mean(R) a_s + da as ANG eq. 42 in two places. */
SPS__INLINE void sps__penalty_finish(sps_world* w, const sps__body* b, sps__group q, sps_real dt, sps_real (*sum)[SPS__LANES],
                                     const int dim) {
    const sps_real penalty_rate = b->xi * b->mat.G * dt; /* ANG eqs. 43, 46 without 1/rho_i */
    const sps__turn turn = b->model.penalty_in_pressure && b->model.turn == SPS__TURN_MEAN ? SPS__TURN_NONE : b->model.turn;
    sps_real da[3][SPS__LANES], R[9][SPS__LANES];
    int l, a;
    SPS__PRAGMA(omp simd)
    for (l = 0; l < SPS__LANES; ++l) {
        const sps_real rho = q.i0 + l < b->end ? w->rho[q.i0 + l] : 1;
        SPS__UNROLL
        for (a = 0; a < dim; ++a) da[a][l] = penalty_rate / rho * sum[a][l];
    }
    switch (turn) {
    case SPS__TURN_NONE: sps__add_increments(w, b, q, dim, da, R, SPS__TURN_NONE); break;
    case SPS__TURN_MEAN: sps__add_increments(w, b, q, dim, da, R, SPS__TURN_MEAN); break;
    case SPS__TURN_PARTICLE:
        sps__rotation_lanes(b, q, dt, dim, NULL, R);
        sps__add_increments(w, b, q, dim, da, R, SPS__TURN_PARTICLE);
        break;
    }
}

/* Penalty pass for lane group g: the body's pair loop, then (its increments kept per particle)
   the finish. */
static void sps__penalty(sps_world* w, const sps__body* b, int g, sps_real dt) {
    sps__lane_sums sums;
    const sps__group q = sps__group_of(w, b, g);
    sps__clear_sums(&sums, 3);
    b->model.pass.penalty_pairs(w, b, g, dt, b->model.pass.penalty_terms, &sums);
    if (b->model.paired) return; /* the pair loop added to the pair forces */
    if (w->dim == 2) sps__penalty_finish(w, b, q, dt, sums.row, 2);
    else sps__penalty_finish(w, b, q, dt, sums.row, 3);
}

/* >>solver: the updated-Lagrangian passes (continued): the penalty in the next pressure pass
   (penalty_in_pressure_pass)

   Sub-step n's penalty reads v^(n+1) and the L^(n+1) of every neighbour, which nothing changes
   before sub-step n+1's kick, so sub-step n+1's pressure loop can sum it: two neighbour passes
   per sub-step instead of three, the pair's gathers (x_j, v_j, V_j) and loop shared. Its pair
   geometry is the paper's: the half drift moved every particle by dt/2 v^(n+1), so the loop
   forms e_ij, dW and 1/r_ij again from x^(n+1) = x - dt/2 v (sps__pair_before_drift; with the
   half-drifted geometry instead, the GNO-A plate's period moved +0.6 % at CFL 0.4 and +0.3 %
   at 0.2: the lag of r_ij against L^(n+1) r_ij, first order in dt). What lags: V_j and rho_i
   are those of rho^(n+3/2) instead of rho^(n+1/2) (a relative change of dt drho/rho, about
   1e-6 a sub-step). The increments, da = xi G dt_n / rho_i sum with the sub-step's own length
   dt_n, reach a_s before sub-step n+1's kick, as in the paper, so that kick sees the same
   penalty; the mean rotation (ANG eq. 42) turns a_s in sub-step n's finish and the increments
   are added after it; a per-particle rotation is made here from L^(n+1) and dt_n, as in the
   paper's pass. An advection step's last sub-step runs the penalty as a pass of its own after
   the sub-step (sps__step_until), so a step always returns with every increment applied
   (outputs, diagnostics and restarts see the paper's state) and the next step's first
   pressure pass has none pending. */

/* The pressure pass's kernel for lane group g with the previous sub-step's penalty (of length
   penalty_dt) in the same pair loop. */
static void sps__pressure_and_penalty(sps_world* w, const sps__body* b, int g, sps_real dt, sps_real penalty_dt) {
    sps__lane_sums sums;
    const sps__group q = sps__group_of(w, b, g);
    sps__clear_sums(&sums, SPS__PENALTY_SUMS + 3);
    sps__pressure_sums(w, b, g, dt, b->model.pass.pressure_penalty_pairs, b->model.pass.pressure_penalty_terms, &sums);
    if (w->dim == 2) sps__penalty_finish(w, b, q, penalty_dt, sums.row + SPS__PENALTY_SUMS, 2);
    else sps__penalty_finish(w, b, q, penalty_dt, sums.row + SPS__PENALTY_SUMS, 3);
}

/* The pressure pass of body b: with the previous sub-step's penalty in it when the body has it
   there and one is pending (penalty_dt > 0, that sub-step's length). */
static void sps__pressure_pass(sps_world* w, const sps__body* b, sps_real dt, sps_real penalty_dt) {
    int g, g0, g1;
    if (!b->model.penalty_in_pressure || !(penalty_dt > 0)) {
        sps__run_groups(w, b, b->model.pass.pressure, dt);
        return;
    }
    sps__group_share(w, b, &g0, &g1);
    for (g = g0; g < g1; ++g) sps__pressure_and_penalty(w, b, g, dt, penalty_dt);
    SPS__PRAGMA(omp barrier)
}

/* The penalty of the last sub-step of an advection step for the bodies that have it in the
   pressure pass, as a pass of its own (the paper's, with dt the sub-step's length). */
static void sps__pending_penalties(sps_world* w, sps_real dt) {
    int bi;
    for (bi = 0; bi < w->nbodies; ++bi)
        if (w->bodies[bi].model.penalty_in_pressure) sps__run_groups(w, &w->bodies[bi], w->bodies[bi].model.pass.penalty, dt);
}

/* The penalty pass's pair loops: (name, pair terms). */
#define SPS__PENALTY_LOOPS(X)                                                     \
    X(gno, 0)                                                                     \
    X(gno_a, SPS__TERM_PROJECTED)                                                 \
    X(gno_a_pairs, SPS__TERM_PROJECTED | SPS__TERM_PAIRED)                        \
    SPS__PENALTY_PLASTIC_LOOPS(X)
/* the scaled penalty of plastic bodies (J2 and Drucker-Prager with GNO, GNO-A): out only when
   both kinds are */
#if defined(SPHSOLID_NO_PLASTICITY) && defined(SPHSOLID_NO_GRANULAR)
#define SPS__PENALTY_PLASTIC_LOOPS(X)
#else
#define SPS__PENALTY_PLASTIC_LOOPS(X)                                             \
    X(gno_j2, SPS__TERM_SCALED)                                                   \
    X(gno_a_j2, SPS__TERM_PROJECTED | SPS__TERM_SCALED)                           \
    X(gno_a_pairs_j2, SPS__TERM_PROJECTED | SPS__TERM_PAIRED | SPS__TERM_SCALED)
#endif
#define SPS__PENALTY_INSTANCES(variant, terms) SPS__INSTANCES(penalty_pairs, variant, terms)
SPS__GENERIC_LOOPS(penalty_pairs)
SPS__PENALTY_LOOPS(SPS__PENALTY_INSTANCES)

/* The pass kernels of a model in the world's mode: each pass's rows searched for the one whose
   pair terms are the model's (every resolvable model has one), which names the pair loop that
   serves it. The choices made after the loop (the turn, the return map, the stress update) are
   not terms: one loop serves them all. */
typedef struct sps__loop_row {
    int terms;                   /* the pair terms it computes (SPS__TERM_ bits) */
    const sps__pair_loop* modes; /* its instances, by world mode */
} sps__loop_row;
#define SPS__PRESSURE_ROW(variant, terms) {terms, sps__pressure_pairs_##variant},
#define SPS__CONTINUITY_ROW(variant, terms) {terms, sps__continuity_pairs_##variant},
#define SPS__PENALTY_ROW(variant, terms) {terms, sps__penalty_pairs_##variant},
/* a granular body's loop sums its stress diffusion whether or not the finish stores it */
#ifdef SPHSOLID_NO_GRANULAR
#define SPS__PRESSURE_DIFFUSION_ROW
#else
#define SPS__PRESSURE_DIFFUSION_ROW {SPS__TERM_STRESS | SPS__TERM_LIMITED | SPS__TERM_GRANULAR | SPS__TERM_DIFFUSION, sps__pressure_pairs_granular},
#endif
static const sps__loop_row sps__pressure_rows[] = {SPS__PRESSURE_LOOPS(SPS__PRESSURE_ROW) SPS__PRESSURE_DIFFUSION_ROW};
static const sps__loop_row sps__continuity_rows[] = {SPS__CONTINUITY_LOOPS(SPS__CONTINUITY_ROW)};
static const sps__loop_row sps__penalty_rows[] = {SPS__PENALTY_LOOPS(SPS__PENALTY_ROW)};
#define SPS__NROWS(rows) ((int)(sizeof rows / sizeof rows[0]))

/* The instance in mode of the row whose terms are terms; NULL when no row has them or the row
   has no instance in that mode (the caller names the combination: sps__missing_pass). */
static sps__pair_loop sps__find_loop(const sps__loop_row* rows, int nrows, int terms, int mode) {
    int r;
    for (r = 0; r < nrows; ++r)
        if (rows[r].terms == terms) return rows[r].modes[mode];
    return NULL;
}

/* The pair terms of a model's passes. */
static int sps__pressure_terms(const sps__model* m) {
    return (m->stabilisation->stress_force ? SPS__TERM_STRESS : 0) | (m->paired ? SPS__TERM_PAIRED : 0) |
           (m->limited ? SPS__TERM_LIMITED : 0) | (m->viscous == SPS__VISCOUS_NEWTON ? SPS__TERM_NEWTON : 0) |
           (m->diffusion ? SPS__TERM_DIFFUSION : 0) | sps__kind_pressure_terms(m->material->kind);
}
static int sps__continuity_terms(const sps__model* m) {
    const int eno = m->stabilisation->eno;
    return (m->gradient ? SPS__TERM_GRADIENT : 0) | (eno && !m->paired ? SPS__TERM_LAPLACIAN : 0) | (eno && m->paired ? SPS__TERM_PAIRED : 0) |
           (m->riemann_density ? SPS__TERM_RIEMANN : 0) | (m->riemann_density && !m->gradient ? SPS__TERM_DIVERGENCE : 0);
}
static int sps__penalty_terms(const sps__model* m) {
    return (m->stabilisation->projected ? SPS__TERM_PROJECTED : 0) | (m->paired ? SPS__TERM_PAIRED : 0) |
           (m->scaled_penalty ? SPS__TERM_SCALED : 0);
}

static sps__passes sps__tl_passes(const sps_world* w, const sps__model* m);
static sps__passes sps__choose_passes(const sps_world* w, const sps__model* m) {
    const int mode = sps__mode(w);
    sps__passes p;
    memset(&p, 0, sizeof p);
    if (m->material->kinematic) return p;
    if (m->total_lagrangian) return sps__tl_passes(w, m);
    p.pressure_terms = sps__pressure_terms(m);
    p.continuity_terms = sps__continuity_terms(m);
    p.penalty_terms = sps__penalty_terms(m);
    p.pressure_penalty_terms = p.pressure_terms | SPS__TERM_PENALTY | p.penalty_terms;
    p.pressure_pairs = sps__find_loop(sps__pressure_rows, SPS__NROWS(sps__pressure_rows), p.pressure_terms, mode);
    if (m->stabilisation->artificial_stress) p.art_pairs = sps__rare_pressure_pairs_art[mode];
    if (m->viscous == SPS__VISCOUS_KELVIN_VOIGT) p.damping_pairs = sps__rare_pressure_pairs_damping[mode];
    p.continuity_pairs = sps__find_loop(sps__continuity_rows, SPS__NROWS(sps__continuity_rows), p.continuity_terms, mode);
    if (m->stabilisation->penalty) p.penalty_pairs = sps__find_loop(sps__penalty_rows, SPS__NROWS(sps__penalty_rows), p.penalty_terms, mode);
    if (m->penalty_in_pressure)
        p.pressure_penalty_pairs = sps__find_loop(sps__pressure_rows, SPS__NROWS(sps__pressure_rows), p.pressure_penalty_terms, mode);
    p.pressure = p.pressure_pairs && (p.art_pairs || !m->stabilisation->artificial_stress) ? sps__pressure : NULL;
    p.continuity = p.continuity_pairs ? sps__continuity : NULL;
    p.penalty = p.penalty_pairs ? sps__penalty : NULL;
    return p;
}

/* A pass the model needs but sps__choose_passes found no instance for (a combination the
   loop lists do not hold): its name and the model's choices into msg, 1; else 0. Checked by
   sps_world_add_body in every build, so a missing instance is an error there and not a pass
   the step would skip (sps__run_groups runs nothing for a NULL kernel). */
static int sps__missing_pass(const sps__model* m, const sps__passes* p, char* msg, size_t size) {
    const sps__stabilisation* st = m->stabilisation;
    const char* pass = NULL;
    if (m->material->kinematic) return 0; /* a wall body runs no pass */
    if (!p->pressure) pass = m->total_lagrangian ? "total-Lagrangian force" : "pressure";
    else if (m->total_lagrangian && !p->stress) pass = "total-Lagrangian stress";
    else if (!m->total_lagrangian && !p->continuity) pass = "continuity";
    else if (!m->total_lagrangian && st->penalty && !p->penalty) pass = "penalty";
    else if (m->penalty_in_pressure && !p->pressure_penalty_pairs) pass = "pressure with the penalty (penalty_in_pressure_pass)";
    if (!pass) return 0;
    snprintf(msg, size, "no %s pass instance for material.kind = %s with %s (stress force %d, artificial stress %d, pair forces %d, "
             "limiter %d, viscous %d, stress diffusion %d, gradient %d, Riemann density %d, turn %d, scaled penalty %d): add its pair "
             "loop to the pass's list (SPS__PRESSURE_LOOPS, SPS__CONTINUITY_LOOPS, SPS__PENALTY_LOOPS)", pass,
             m->material->name, st->name, st->stress_force, st->artificial_stress, m->paired, m->limited, (int)m->viscous, m->diffusion,
             m->gradient, m->riemann_density, (int)m->turn, m->scaled_penalty);
    return 1;
}

/* >>solver: total Lagrangian (TL sections 2-3; TOTAL-LAGRANGIAN in the manual)

   A total-Lagrangian body keeps the neighbour lists of its reference positions X (built once by
   sps__build_neighbors, which never re-sorts its particles after that) and the correction
   matrices B_i = -L_i^-1 of TL eq. 15 (sps__tl_reference). With the reference pair direction
   E_ij = (X_i - X_j)/R_ij and dW = dW/dR (< 0), the corrected kernel gradient of TL eq. 14 is
   L_i^-1 grad W_i(X_ij) = dW B_i E_ij, and the other side's L_j^-1 grad W_j(X_ji) = -dW B_j E_ij.
   Since the lists never change, the pairs' reference geometry is computed once, into a table
   in the order the passes walk the lane slots (sps__tl_pair_table). Each sub-step runs two
   passes after the half drift: the stress pass (F_i by TL eq. 17, P_i by the body's law, the
   springs of i with F_i, Q_i = (P_i + Pi_i) B_i with the hourglass stress Pi_i below, the
   Cauchy stress and density for output) and, after a barrier, the force pass in the pressure
   pass's place (TL eq. 24 and the hourglass springs' pair forces in one loop), whose
   acceleration the kick applies. No continuity pass: the density is rho0/J.

   The hourglass springs (TL eqs. 25-32). Particle i holds a spring to each reference neighbour
   j, of stiffness k_ij = 1/2 alpha E_i V0_i V0_j W_ij / R_ij^2 and stretch
   delta^i_ij = p^i_ij . e_ij, where p^i_ij = F_i X_ij - x_ij (X_ij = X_j - X_i, x_ij = x_j - x_i,
   e_ij = x_ij/|x_ij|) is the error of F_i's prediction of j's position (TL eqs. 25-27). Their
   energy is Phi = sum_i sum_j 1/2 k_ij (delta^i_ij)^2. TL eq. 32 is the part of -dPhi/dx that
   holds F and e fixed: f_i = -sum_j (k_ij delta^i_ij + k_ji delta^j_ij) e_ij (with
   delta^j_ji = delta^j_ij, p^j_ij = F_j X_ij - x_ij). It is not the gradient of any energy: its
   stiffness is not symmetric (on the irregular D1 patch a quarter of the eigenvalues are
   complex) and it feeds energy into the motion (flutter: the D1 patch blew up after a few
   periods). The full gradient (SPS_HOURGLASS_VARIATIONAL, the default) adds the two parts it
   drops, derived from d delta = dp . e + p . de:
   - the turn of the pair, de = (I - e e) dx_ij / |x_ij|: a force across the pair,
     f_i += sum_j (k_ij delta^i_ij p^i_perp + k_ji delta^j_ij p^j_perp) / |x_ij|, p_perp = p - (p.e) e;
   - F_i, linear in the positions of i and its neighbours (TL eq. 17): dPhi/dF_i =
     sum_j k_ij delta^i_ij e_ij (x) X_ij = V0_i Pi_i. TL eq. 24 is -d/dx of sum_i V0_i psi(F_i)
     for P_i = dpsi/dF_i (whatever psi), so this part is TL eq. 24 applied to the hourglass
     stress Pi_i, added to P_i where Q_i is formed (the Cauchy stress output keeps P_i alone).
   With d = p . x_ij / |x_ij|^2 (so delta e = d x_ij and delta p_perp / |x_ij| = d (p - d x_ij)):
   Pi_i = sum_j 1/2 alpha E_i V0_j W_ij / R_ij^2 d^i_ij x_ij (x) X_ij, and the pair forces
   f_i += sum_j -(k_ij d^i + k_ji d^j) x_ij (TL eq. 32) + k_ij d^i (p^i - d^i x_ij) +
   k_ji d^j (p^j - d^j x_ij) (the turn). Phi is invariant under
   rotation and translation, so its gradient conserves both momenta; it is counted with the
   strain energy (sps__tl_energy). SPS_HOURGLASS_PAPER applies TL eq. 32 alone. */

/* Its parameters' defaults (material.tl; sps__material_defaults) other than zero: the hourglass
   coefficient alpha = 50 (TL section 4.2, Table 1). */
static void sps__tl_defaults(sps_tl_def* tl) { tl->hourglass_alpha = 50; }

/* The reference geometry of pair (i, j): E_ij, R_ij, W(R_ij) and dW/dR. */
typedef struct sps__ref_pair {
    sps_real ex, ey, ez, r, w, dw;
} sps__ref_pair;
SPS__INLINE sps__ref_pair sps__tl_pair(const sps_world* w, int i, int j, const int dim) {
    sps__ref_pair q;
    const sps_real dx = w->ref[0][i] - w->ref[0][j], dy = w->ref[1][i] - w->ref[1][j], dz = dim == 3 ? w->ref[2][i] - w->ref[2][j] : 0;
    const sps_real inv = 1 / SPS__SQRT(dx * dx + dy * dy + dz * dz); /* the lists hold no coincident pair */
    q.r = (dx * dx + dy * dy + dz * dz) * inv;
    q.ex = dx * inv;
    q.ey = dy * inv;
    q.ez = dz * inv;
    q.w = w->kernel_norm * sps__kernel_f(w->def.kernel, q.r * w->inv_h);
    q.dw = w->dw_scale * sps__kernel_df(w->def.kernel, q.r * w->inv_h);
    return q;
}

/* The reference volume V0 = m/rho0 of particle i of body b (TL eq. 7). */
#define SPS__V0(w, b, i) ((w)->mass[i] / (b)->rho0)

/* One Newton step B <- B (2 I - A B) towards A^-1 (A symmetric: xx xy xz yy yz zz; B row-major). */
static void sps__newton_inverse_step(const sps_real A6[6], sps_real B[9], const int dim) {
    const sps_real A[9] = {A6[0], A6[1], A6[2], A6[1], A6[3], A6[4], A6[2], A6[4], A6[5]};
    sps_real R[9], N[9];
    int a, c, k;
    for (a = 0; a < dim; ++a)
        for (c = 0; c < dim; ++c) {
            sps_real s = 0;
            for (k = 0; k < dim; ++k) s += A[3 * a + k] * B[3 * k + c];
            R[3 * a + c] = 2 * (a == c) - s;
        }
    for (a = 0; a < dim; ++a)
        for (c = 0; c < dim; ++c) {
            sps_real s = 0;
            for (k = 0; k < dim; ++k) s += B[3 * a + k] * R[3 * k + c];
            N[3 * a + c] = s;
        }
    for (a = 0; a < dim; ++a)
        for (c = 0; c < dim; ++c) B[3 * a + c] = N[3 * a + c];
}

/* B_i of every particle of body b from its reference lists (called by sps__list_body once they
   are in the lane slots), summed and inverted
   as the updated-Lagrangian B (sps__add_moment, sps__blended_inverse), then refined by two
   Newton steps B <- B (2 I - A B): the blend's relative error (1e-6 / det^2, larger at corners)
   is squared twice, so that F is exact for affine motions to round-off (TL eq. 16; the blend
   alone gave |F - F_exact| = 7e-6 for a 20 % stretch, one step 2.4e-10) while an isolated
   particle's B stays bounded. The pair table and the signal speed follow the lane slots
   (sps__tl_pair_table). */
static void sps__tl_reference(sps_world* w, sps__body* b) {
    const int dim = w->dim;
    int i;
    SPS__PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (b->end - b->begin > 256))
    for (i = b->begin; i < b->end; ++i) {
        sps_real A[6] = {0, 0, 0, 0, 0, 0}, *B = b->tl_correction + (size_t)9 * (i - b->begin);
        int k;
        for (k = 0; k < 9; ++k) B[k] = 0;
        for (k = 0; k < w->nb_count[i]; ++k) {
            const int j = sps__neighbor(w, i, k);
            const sps__ref_pair e = dim == 2 ? sps__tl_pair(w, i, j, 2) : sps__tl_pair(w, i, j, 3);
            sps__add_moment(A, 1, e.ex, e.ey, e.ez, e.r * e.dw * SPS__V0(w, b, j), dim);
        }
        if (dim == 2) sps__blended_inverse(A, 1, B, 1, 2);
        else sps__blended_inverse(A, 1, B, 1, 3);
        sps__newton_inverse_step(A, B, dim);
        sps__newton_inverse_step(A, B, dim);
    }
    b->reference_built = 1;
    b->tl_slots = 0; /* the pair table is built from the lane slots (sps__build_neighbors) */
}

/* The pair table of a total-Lagrangian body (tl_pairs): the reference lists never change, so
   every pair's reference geometry is computed once, in the order the passes walk the lane
   slots: table slot t is lane slot nb_group_start[group0] + t, padding zero. Rows (each
   tl_slots long; dim is the world's): the pair weight w_ij = V0_i V0_j dW(R_ij) E_ij, whose
   sums give F (TL eq. 17: V0_i F_i = V0_i I + sum_j (u_j - u_i) (x) w_ij B_i) and the force of
   TL eq. 24 (f_i = sum_j (Q_i + Q_j) w_ij); X_ij = X_j - X_i; the spring factor
   1/2 V0_i V0_j W_ij / R_ij^2 (k_ij = alpha E_i times it, TL eq. 31); and the force a^i_ij of
   i's spring to j on i, which each stress pass writes where it has d^i_ij and the force pass
   reads from both ends of the pair (tl_reverse: the slot of pair (j, i) in j's list). Memory:
   (3 d + 1) reals and an int per slot, about 1.7 KB per particle in 2D and 6 KB in 3D at the
   default h (the updated-Lagrangian lists: 2 reals and an int per slot). */
#define SPS__TLP_WEIGHT(dim, a) (a)
#define SPS__TLP_X(dim, a) ((dim) + (a))
#define SPS__TLP_SPRING(dim) (2 * (dim))
#define SPS__TLP_FORCE(dim, a) (2 * (dim) + 1 + (a))
#define SPS__TLP_ROWS(dim) (3 * (dim) + 1)

/* The hourglass spring of pair (i, j) seen from a particle with deformation gradient F: the error
   vector p = F X_ij - x_ij (TL eq. 25) into p, and d = p . x_ij / |x_ij|^2 returned (inv_x2 =
   1/|x_ij|^2), so that delta = d |x_ij| (TL eq. 27) and delta e_ij = d x_ij. */
SPS__INLINE sps_real sps__tl_spring(const sps_real F[9], const sps_real X[3], const sps_real x[3], sps_real inv_x2, const int dim,
                                    sps_real p[3]) {
    sps_real px = 0;
    int a, c;
    for (a = 0; a < dim; ++a) {
        p[a] = -x[a];
        for (c = 0; c < dim; ++c) p[a] += F[3 * a + c] * X[c];
        px += p[a] * x[a];
    }
    return px * inv_x2;
}

/* Lame constants of a total-Lagrangian body: mu = G, lambda = K - 2G/3. */
#define SPS__LAME_LAMBDA(b) ((b)->mat.K - (b)->mat.G * 2 / 3)

/* The law of a total-Lagrangian kind (dispatched by sps__tl_law in chapter >>generic): the
   first Piola-Kirchhoff stress P (row-major 3 x 3) of the deformation gradient F (row-major
   3 x 3; in 2D, plane strain, F_zz = 1 and the out-of-plane entries 0) at particle o of body b,
   J = det F, and the stored energy per reference volume, returned. A law with a state of its
   own (J2) advances it when update is 1 (the stress pass; 0: the energy account reads it) and
   puts the plastic work density of the step in *work. */

/* >>material: Saint Venant-Kirchhoff (continued): its law

   S = lambda tr(E) I + 2 mu E, E = (F^T F - I)/2, P = F S, psi = lambda/2 tr(E)^2 + mu E:E
   (TL eqs. 18-20). */
SPS__INLINE sps_real sps__saint_venant_kirchhoff_law(const sps__body* b, const sps_real F[9], sps_real P[9]) {
    const sps_real mu = b->mat.G, lambda = SPS__LAME_LAMBDA(b);
    sps_real E[9], S[9], tr = 0, ee = 0;
    int a, c, k;
    for (a = 0; a < 3; ++a)
        for (c = 0; c < 3; ++c) {
            sps_real C = 0;
            for (k = 0; k < 3; ++k) C += F[3 * k + a] * F[3 * k + c];
            E[3 * a + c] = SPS_R(0.5) * (C - (a == c));
        }
    for (a = 0; a < 3; ++a) tr += E[4 * a];
    for (k = 0; k < 9; ++k) {
        S[k] = 2 * mu * E[k] + (k % 4 == 0 ? lambda * tr : 0);
        ee += E[k] * E[k];
    }
    sps__mat3_product(F, S, 0, P);
    return SPS_R(0.5) * lambda * tr * tr + mu * ee;
}

/* >>material: Neo-Hookean (continued): its law

   P = F S = mu (F - F^-T) + lambda ln(J) F^-T, psi = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2
   (TL eq. 44). */
SPS__INLINE sps_real sps__neo_hookean_law(const sps__body* b, const sps_real F[9], sps_real J, sps_real P[9]) {
    const sps_real mu = b->mat.G, lambda = SPS__LAME_LAMBDA(b);
    /* F^-T from the cofactors: (F^-T)_ac = cof(F)_ac / J */
    const sps_real lnJ = SPS__LOG(J), inv_J = 1 / J;
    sps_real cof[9], trC = 0;
    int k;
    cof[0] = F[4] * F[8] - F[5] * F[7];
    cof[1] = F[5] * F[6] - F[3] * F[8];
    cof[2] = F[3] * F[7] - F[4] * F[6];
    cof[3] = F[2] * F[7] - F[1] * F[8];
    cof[4] = F[0] * F[8] - F[2] * F[6];
    cof[5] = F[1] * F[6] - F[0] * F[7];
    cof[6] = F[1] * F[5] - F[2] * F[4];
    cof[7] = F[2] * F[3] - F[0] * F[5];
    cof[8] = F[0] * F[4] - F[1] * F[3];
    for (k = 0; k < 9; ++k) {
        P[k] = mu * F[k] + (lambda * lnJ - mu) * cof[k] * inv_J;
        trC += F[k] * F[k];
    }
    return SPS_R(0.5) * mu * (trC - 3) - mu * lnJ + SPS_R(0.5) * lambda * lnJ * lnJ;
}

/* >>solver: total Lagrangian (continued) */

/* det F of a row-major 3 x 3 matrix. */
SPS__INLINE sps_real sps__det3(const sps_real F[9]) {
    return F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) + F[2] * (F[3] * F[7] - F[4] * F[6]);
}

/* >>material: J2 plasticity in the total-Lagrangian frame (TL section 4.5; the multiplicative
   hyperelastic-plastic model of Bonet and Wood's appendix the paper cites)

   F = F_e F_p. The state is C_p^-1 = (F_p^T F_p)^-1 (stored less I, field "plastic_metric") and
   the equivalent plastic strain alpha. At each stress pass: the trial elastic left
   Cauchy-Green tensor b_e = F C_p^-1 F^T = sum_a lambda_a^2 n_a (x) n_a (Jacobi), logarithmic
   strains eps_a = ln lambda_a, Hencky's Kirchhoff stresses tau_a = lambda tr(eps) + 2 mu eps_a;
   if the von Mises stress q = sqrt(3/2 |dev tau|^2) exceeds sigma_Y + kappa alpha, the radial
   return in the principal logarithmic strains: d_gamma = f / (3 mu + kappa), dev tau and
   dev eps scaled by 1 - 3 mu d_gamma / q, alpha += d_gamma; then b_e = sum exp(2 eps_a) n_a (x) n_a,
   C_p^-1 = F^-1 b_e F^-T, P = tau F^-T, and the plastic work grows by the elastic energy the
   return removed, V0 (psi(eps_trial) - psi(eps)), psi = lambda/2 tr(eps)^2 + mu eps:eps. */

/* Eigenvalues d and eigenvectors (columns of Q, row-major) of the symmetric 3 x 3 matrix A
   (row-major), by cyclic Jacobi rotations until the off-diagonal part is below 1e-15 of the
   norm (deterministic: a fixed order of rotations). */
static void sps__eigen3(const sps_real A[9], sps_real d[3], sps_real Q[9]) {
    sps_real M[9];
    int k, sweep, p, q, r;
    for (k = 0; k < 9; ++k) {
        M[k] = A[k];
        Q[k] = (sps_real)(k % 4 == 0);
    }
    for (sweep = 0; sweep < 30; ++sweep) {
        sps_real off = M[1] * M[1] + M[2] * M[2] + M[5] * M[5], norm = off;
        for (k = 0; k < 3; ++k) norm += M[4 * k] * M[4 * k];
        if (!(off > SPS_R(1e-30) * norm)) break; /* NaN stops too: the guards see it */
        for (p = 0; p < 2; ++p)
            for (q = p + 1; q < 3; ++q) {
                const sps_real apq = M[3 * p + q];
                sps_real theta, t, c, s;
                if (apq == 0) continue;
                theta = (M[3 * q + q] - M[3 * p + p]) / (2 * apq);
                t = (theta >= 0 ? 1 : -1) / (SPS__FABS(theta) + SPS__SQRT(theta * theta + 1));
                c = 1 / SPS__SQRT(t * t + 1);
                s = t * c;
                for (r = 0; r < 3; ++r) { /* M <- M J (columns p, q) */
                    const sps_real mp = M[3 * r + p], mq = M[3 * r + q];
                    M[3 * r + p] = c * mp - s * mq;
                    M[3 * r + q] = s * mp + c * mq;
                }
                for (r = 0; r < 3; ++r) { /* M <- J^T M (rows p, q) */
                    const sps_real mp = M[3 * p + r], mq = M[3 * q + r];
                    M[3 * p + r] = c * mp - s * mq;
                    M[3 * q + r] = s * mp + c * mq;
                }
                for (r = 0; r < 3; ++r) { /* Q <- Q J */
                    const sps_real qp = Q[3 * r + p], qq = Q[3 * r + q];
                    Q[3 * r + p] = c * qp - s * qq;
                    Q[3 * r + q] = s * qp + c * qq;
                }
            }
    }
    for (k = 0; k < 3; ++k) d[k] = M[4 * k];
}

/* The inverse of a row-major 3 x 3 matrix with determinant J. */
static void sps__inverse3(const sps_real F[9], sps_real J, sps_real G[9]) {
    G[0] = (F[4] * F[8] - F[5] * F[7]) / J;
    G[1] = (F[2] * F[7] - F[1] * F[8]) / J;
    G[2] = (F[1] * F[5] - F[2] * F[4]) / J;
    G[3] = (F[5] * F[6] - F[3] * F[8]) / J;
    G[4] = (F[0] * F[8] - F[2] * F[6]) / J;
    G[5] = (F[2] * F[3] - F[0] * F[5]) / J;
    G[6] = (F[3] * F[7] - F[4] * F[6]) / J;
    G[7] = (F[1] * F[6] - F[0] * F[7]) / J;
    G[8] = (F[0] * F[4] - F[1] * F[3]) / J;
}

/* The J2 law of a total-Lagrangian body at F (J = det F) from the state cp (C_p^-1 - I, 6 values)
   and alpha: P; with update = 1 the state is advanced (cp, alpha) and *work gets the plastic
   work density of the return. Returns the elastic energy density psi per reference volume. */
static sps_real sps__tl_j2(sps_real lambda, sps_real mu, sps_real yield, sps_real hardening, const sps_real F[9], sps_real J,
                           sps_real* cp, sps_real* alpha, int update, sps_real P[9], sps_real* work) {
    const sps_real C[9] = {1 + cp[0], cp[1], cp[2], cp[1], 1 + cp[3], cp[4], cp[2], cp[4], 1 + cp[5]};
    sps_real FC[9], be[9], d[3], Q[9], eps[3], tau[3], Finv[9], T[9], Bn[9], tr = 0, mean, q2 = 0, psi_trial, psi, ee = 0;
    int a, c, k;
    sps__mat3_product(F, C, 0, FC);
    sps__mat3_product(FC, F, 1, be);
    sps__eigen3(be, d, Q);
    for (a = 0; a < 3; ++a) {
        eps[a] = SPS_R(0.5) * SPS__LOG(d[a]);
        tr += eps[a];
        ee += eps[a] * eps[a];
    }
    psi_trial = SPS_R(0.5) * lambda * tr * tr + mu * ee;
    for (a = 0; a < 3; ++a) tau[a] = lambda * tr + 2 * mu * eps[a];
    mean = (tau[0] + tau[1] + tau[2]) / 3;
    for (a = 0; a < 3; ++a) q2 += (tau[a] - mean) * (tau[a] - mean);
    {
        const sps_real q = SPS__SQRT(SPS_R(1.5) * q2), f = q - (yield + hardening * *alpha);
        if (f > 0) {
            const sps_real dgamma = f / (3 * mu + hardening), scale = 1 - 3 * mu * dgamma / q;
            for (a = 0; a < 3; ++a) {
                tau[a] = mean + (tau[a] - mean) * scale;
                eps[a] = tr / 3 + (eps[a] - tr / 3) * scale;
            }
            if (update) *alpha += dgamma;
        }
    }
    ee = 0;
    for (a = 0; a < 3; ++a) ee += eps[a] * eps[a];
    psi = SPS_R(0.5) * lambda * tr * tr + mu * ee;
    sps__inverse3(F, J, Finv);
    /* Kirchhoff stress T = Q diag(tau) Q^T; P = T F^-T */
    for (a = 0; a < 3; ++a)
        for (c = 0; c < 3; ++c) {
            sps_real s = 0, t = 0;
            for (k = 0; k < 3; ++k) {
                s += Q[3 * a + k] * tau[k] * Q[3 * c + k];
                t += Q[3 * a + k] * SPS__EXP(2 * eps[k]) * Q[3 * c + k];
            }
            T[3 * a + c] = s;
            Bn[3 * a + c] = t;
        }
    sps__mat3_product(T, Finv, 1, P);
    if (update) { /* C_p^-1 = F^-1 b_e F^-T */
        sps_real G[9], H[9];
        sps__mat3_product(Finv, Bn, 0, G);
        sps__mat3_product(G, Finv, 1, H);
        cp[0] = H[0] - 1; cp[1] = SPS_R(0.5) * (H[1] + H[3]); cp[2] = SPS_R(0.5) * (H[2] + H[6]);
        cp[3] = H[4] - 1; cp[4] = SPS_R(0.5) * (H[5] + H[7]); cp[5] = H[8] - 1;
        *work = psi_trial - psi;
    }
    return psi;
}

/* J2's law in the frame (sps__tl_law): the state C_p^-1 - I and alpha of particle o, advanced
   with update, a copy left unchanged without (the energy account). */
static sps_real sps__j2_tl_law(const sps__body* b, int o, const sps_real F[9], sps_real J, int update, sps_real P[9], sps_real* work) {
    sps_real *cp = b->tl_plastic + (size_t)6 * o, *alpha = b->plastic_strain + o, cp_copy[6], alpha_copy;
    if (!update) {
        memcpy(cp_copy, cp, sizeof cp_copy);
        alpha_copy = *alpha;
        cp = cp_copy;
        alpha = &alpha_copy;
    }
    return sps__tl_j2(SPS__LAME_LAMBDA(b), b->mat.G, b->def.material.j2.yield_stress, b->def.material.j2.hardening_modulus, F, J, cp, alpha,
                      update, P, work);
}
/* The modulus of the hourglass springs at a J2 particle that has flowed: the yield stress
   instead of E (TL section 4.5; sps__tl_hourglass_modulus). */
static sps_real sps__j2_tl_flowed_modulus(const sps__body* b) { return b->def.material.j2.yield_stress; }

/* >>generic (continued): the laws of total-Lagrangian bodies */

/* The law of body b's kind at particle o (sps__saint_venant_kirchhoff_law explains the
   arguments). A kind without a law has no total-Lagrangian kernel (sps__tl_passes), so its case
   is not reached; P is zeroed there all the same. */
SPS__INLINE sps_real sps__tl_law(const sps__body* b, int o, const sps_real F[9], sps_real J, int update, sps_real P[9], sps_real* work) {
    int k;
    switch (b->def.material.kind) {
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF: return sps__saint_venant_kirchhoff_law(b, F, P);
    case SPS_MATERIAL_NEO_HOOKEAN: return sps__neo_hookean_law(b, F, J, P);
    case SPS_MATERIAL_J2: return sps__j2_tl_law(b, o, F, J, update, P, work);
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_FLUID:
    case SPS_MATERIAL_DRUCKER_PRAGER: break;
    }
    for (k = 0; k < 9; ++k) P[k] = 0;
    return 0;
}
/* The hourglass springs' modulus at a particle of body b that has flowed (plastic kinds only:
   sps__tl_hourglass_modulus reads it where plastic_strain > 0); E for the others. */
static sps_real sps__tl_flowed_modulus(const sps__body* b) {
    switch (b->def.material.kind) {
    case SPS_MATERIAL_J2: return sps__j2_tl_flowed_modulus(b);
    case SPS_MATERIAL_ELASTIC:
    case SPS_MATERIAL_RIGID:
    case SPS_MATERIAL_RIGID_DYNAMIC:
    case SPS_MATERIAL_FLUID:
    case SPS_MATERIAL_DRUCKER_PRAGER:
    case SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF:
    case SPS_MATERIAL_NEO_HOOKEAN: break;
    }
    return b->def.material.youngs_modulus;
}

/* >>solver: total Lagrangian (continued): damage (TL section 4.6, eqs. 45-46)

   A body with material.tl.damage_strain = eps_max > 0 carries the damage D in [0, 1] of each particle (field
   "damage"). The rate model of TL eq. 45: while the largest principal Green-Lagrange strain of
   F_i exceeds eps_max, D^(1/3) grows at 0.4 c0 / h, with c0 the P-wave speed
   sqrt((K + 4G/3)/rho0) and h the kernel radius (the support 2h here: where W reaches 0), so
   that a crack crosses a particle no faster than 0.4 times the speed of sound; D never falls.
   TL eq. 46: of the principal stresses only the positive ones are scaled by 1 - D, so that a
   broken particle still resists being pushed into. It is applied to the Kirchhoff stress
   tau = P F^T = J sigma (the principal axes and signs of sigma), and P = tau~ F^-T. A particle
   with D = 0 keeps its law's P untouched. The hourglass force weakens with 1 - D too
   (sps__tl_hourglass_modulus). */

/* The growth of D^(1/3) per second of body b (TL eq. 45): 0.4 c0 / h. */
static sps_real sps__tl_damage_rate(const sps_world* w, const sps__body* b) {
    return SPS_R(0.4) * SPS__SQRT((b->mat.K + b->mat.G * 4 / 3) / b->rho0) / w->support;
}

/* Advances the damage *D of a particle at F (J = det F) by dt with D^(1/3) growing at rate
   (TL eq. 45), then scales the positive principal values of its Kirchhoff stress P F^T by
   1 - D (TL eq. 46) in P. */
static void sps__tl_damage(sps_real rate, sps_real eps_max, sps_real dt, const sps_real F[9], sps_real J, sps_real* D, sps_real P[9]) {
    sps_real B[9], d[3], Q[9], T[9], Ts[9], Finv[9], largest;
    int a, c, k;
    sps__mat3_product(F, F, 1, B); /* F F^T: the principal stretches squared, as of F^T F */
    sps__eigen3(B, d, Q);
    largest = d[0] > d[1] ? d[0] : d[1];
    if (d[2] > largest) largest = d[2];
    if (SPS_R(0.5) * (largest - 1) > eps_max) { /* the largest principal Green-Lagrange strain */
        const sps_real root = SPS__CBRT(*D) + rate * dt;
        *D = root >= 1 ? 1 : root * root * root;
    }
    if (*D == 0) return;
    sps__mat3_product(P, F, 1, T);
    for (a = 0; a < 3; ++a) /* symmetric up to round-off: the Jacobi rotations read its upper part */
        for (c = 0; c < 3; ++c) Ts[3 * a + c] = SPS_R(0.5) * (T[3 * a + c] + T[3 * c + a]);
    sps__eigen3(Ts, d, Q);
    for (a = 0; a < 3; ++a)
        if (d[a] > 0) d[a] *= 1 - *D;
    for (a = 0; a < 3; ++a)
        for (c = 0; c < 3; ++c) {
            sps_real s = 0;
            for (k = 0; k < 3; ++k) s += Q[3 * a + k] * d[k] * Q[3 * c + k];
            T[3 * a + c] = s;
        }
    sps__inverse3(F, J, Finv);
    sps__mat3_product(T, Finv, 1, P);
}

/* Lame constants of a total-Lagrangian body: mu = G, lambda = K - 2G/3. */
#define SPS__LAME_LAMBDA(b) ((b)->mat.K - (b)->mat.G * 2 / 3)

/* F = I + M B_i / V0_i (TL eq. 17) from M = sum_j (u_j - u_i) (x) w_ij, row-major 3 x 3,
   F_zz = 1 in 2D. */
SPS__INLINE void sps__tl_gradient(const sps_real M[9], const sps_real B[9], sps_real inv_v0, const int dim, sps_real F[9]) {
    int a, c, k;
    for (a = 0; a < 3; ++a)
        for (c = 0; c < 3; ++c) {
            sps_real s = 0;
            for (k = 0; k < dim; ++k) s += M[3 * a + k] * B[3 * k + c];
            F[3 * a + c] = a < dim && c < dim ? (a == c) + s * inv_v0 : (sps_real)(a == c);
        }
}

/* Deformation gradient of particle i at the current positions (TL eq. 17), from the pair
   table, into F: the sums of the stress pass in the same order, so the same F. */
SPS__INLINE void sps__tl_deformation(const sps_world* w, const sps__body* b, int i, const int dim, sps_real F[9]) {
    const long n = b->tl_slots, base = w->nb_group_start[b->group0];
    sps_real M[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    int k, a, c;
    for (k = 0; k < w->nb_count[i]; ++k) {
        const int s = w->nb_first[i] + k * SPS__LANES, j = w->nb_j[s];
        const sps_real* row = b->tl_pairs + (s - base);
        for (a = 0; a < dim; ++a) {
            const sps_real du = (w->pos[a][j] - w->pos[a][i]) - row[SPS__TLP_X(dim, a) * n];
            for (c = 0; c < dim; ++c) M[3 * a + c] += du * row[SPS__TLP_WEIGHT(dim, c) * n];
        }
    }
    sps__tl_gradient(M, b->tl_correction + (size_t)9 * (i - b->begin), 1 / SPS__V0(w, b, i), dim, F);
}

/* The modulus of particle o's side of the hourglass force (TL eq. 32): Young's modulus E, the
   yield strength Y once a J2 particle has flowed (plastic, a literal; TL section 4.5), times
   1 - D with damage: a broken particle, which carries no tension, holds no hourglass spring
   (undegraded, the springs of broken particles alone kept a broken section of the D6 specimen
   carrying load at alpha 50). */
SPS__INLINE sps_real sps__tl_hourglass_modulus(const sps__body* b, int o, sps_real E, sps_real Y, const int plastic) {
    const sps_real modulus = plastic && b->plastic_strain[o] > 0 ? Y : E;
    return b->damage ? modulus * (1 - b->damage[o]) : modulus;
}

/* The energy of particle i's hourglass springs at its deformation gradient F (modulus:
   sps__tl_hourglass_modulus): sum_j 1/2 k_ij (delta^i_ij)^2 = sum_j 1/2 k_ij (d^i_ij)^2 |x_ij|^2. */
static sps_real sps__tl_springs(const sps_world* w, const sps__body* b, int i, const int dim, const sps_real F[9], sps_real modulus) {
    const long n = b->tl_slots, base = w->nb_group_start[b->group0];
    const sps_real alpha_E = b->def.material.tl.hourglass_alpha * modulus;
    sps_real energy = 0;
    int k, a;
    for (k = 0; k < w->nb_count[i]; ++k) {
        const int s = w->nb_first[i] + k * SPS__LANES, j = w->nb_j[s];
        const sps_real* row = b->tl_pairs + (s - base);
        sps_real X[3], x[3], p[3], x2 = 0, d;
        for (a = 0; a < dim; ++a) {
            X[a] = row[SPS__TLP_X(dim, a) * n];
            x[a] = w->pos[a][j] - w->pos[a][i];
            x2 += x[a] * x[a];
        }
        d = sps__tl_spring(F, X, x, 1 / x2, dim, p);
        energy += SPS_R(0.5) * alpha_E * row[SPS__TLP_SPRING(dim) * n] * d * d * x2;
    }
    return energy;
}

/* The hourglass form of body b: 0 without springs (alpha = 0), 1 the paper's TL eq. 32, 2 the
   variational form. */
static int sps__tl_hourglass_form(const sps__body* b) {
    return !(b->def.material.tl.hourglass_alpha > 0) ? 0 : b->def.material.tl.hourglass == SPS_HOURGLASS_VARIATIONAL ? 2 : 1;
}

/* >>solver: total Lagrangian (continued): the stress and force passes, the stored energy */

/* Stress pass of lane group g: F_i (TL eq. 17) from the pair weights, P_i by the body's law
   (degraded by its damage, TL eqs. 45-46, when the body has damage), then the hourglass springs
   of i with F_i (hourglass: 0 none, alpha = 0; 1 TL eq. 32; 2 the variational form): d^i_ij,
   the force a^i_ij of i's spring on i into the pair table, a^i_ij = -k_ij d^i x_ij (TL eq. 32)
   and, in the variational form, + k_ij d^i (p^i - d^i x_ij) (the turn of the pair), and the
   hourglass stress Pi_i = alpha E_i / V0_i sum_j (k_ij / (alpha E_i)) d^i x_ij (x) X_ij; then
   Q_i = (P_i + Pi_i) B_i, the Cauchy stress sigma = P F^T / J stored as tau = sigma + p I (so
   that -p I + tau, what the output reads, is sigma) and the density rho0/J (TL eq. 3). The
   pair loops run the lanes side by side (sps__pressure_pairs); the law, per particle, between
   them. dim and hourglass are literals. */
SPS__INLINE void sps__tl_stress(sps_world* w, const sps__body* b, int g, sps_real dt, const int dim, const int plastic, const int hourglass) {
    const sps__group q = sps__group_of(w, b, g);
    const long n = b->tl_slots, t0 = q.s0 - w->nb_group_start[b->group0];
    const sps_real damage_rate = b->damage ? sps__tl_damage_rate(w, b) : 0;
    const sps_real E = b->def.material.youngs_modulus, Y = sps__tl_flowed_modulus(b), alpha = b->def.material.tl.hourglass_alpha;
    const sps_real *SPS__RESTRICT px = w->pos[0], *SPS__RESTRICT py = w->pos[1], *SPS__RESTRICT pz = w->pos[2];
    const int* SPS__RESTRICT js = w->nb_j + q.s0;
    const sps_real* SPS__RESTRICT wx = b->tl_pairs + t0 + SPS__TLP_WEIGHT(dim, 0) * n;
    const sps_real* SPS__RESTRICT wy = wx + n;
    const sps_real* SPS__RESTRICT wz = dim == 3 ? wx + 2 * n : wx;
    const sps_real* SPS__RESTRICT Xx = b->tl_pairs + t0 + SPS__TLP_X(dim, 0) * n;
    const sps_real* SPS__RESTRICT Xy = Xx + n;
    const sps_real* SPS__RESTRICT Xz = dim == 3 ? Xx + 2 * n : Xx;
    const sps_real* SPS__RESTRICT spring = b->tl_pairs + t0 + SPS__TLP_SPRING(dim) * n;
    sps_real* SPS__RESTRICT ax = b->tl_pairs + t0 + SPS__TLP_FORCE(dim, 0) * n;
    sps_real* SPS__RESTRICT ay = ax + n;
    sps_real* SPS__RESTRICT az = dim == 3 ? ax + 2 * n : ax;
    sps_real M[9][SPS__LANES], Fl[9][SPS__LANES], Pl[9][SPS__LANES], Pil[9][SPS__LANES], Jl[SPS__LANES], El[SPS__LANES];
    int k, l, a, c;
    for (a = 0; a < 9; ++a)
        for (l = 0; l < SPS__LANES; ++l) M[a][l] = Pil[a][l] = 0;
    for (k = 0; k < q.len; ++k) { /* M = sum_j (u_j - u_i) (x) w_ij, u_j - u_i = x_ij - X_ij */
        const int* SPS__RESTRICT jk = js + k * SPS__LANES;
        const long o = (long)k * SPS__LANES;
        SPS__PRAGMA(omp simd)
        for (l = 0; l < SPS__LANES; ++l) {
            const int i = q.i0 + l, j = jk[l];
            const sps_real x = px[j] - px[i], y = py[j] - py[i], dx = x - Xx[o + l], dy = y - Xy[o + l];
            const sps_real ex = wx[o + l], ey = wy[o + l];
            ax[o + l] = x; /* x_ij for the springs' loop, which then writes a^i_ij there */
            ay[o + l] = y;
            M[0][l] += dx * ex;
            M[1][l] += dx * ey;
            M[3][l] += dy * ex;
            M[4][l] += dy * ey;
            if (dim == 3) {
                const sps_real z = pz[j] - pz[i], dz = z - Xz[o + l], ez = wz[o + l];
                az[o + l] = z;
                M[2][l] += dx * ez;
                M[5][l] += dy * ez;
                M[6][l] += dz * ex;
                M[7][l] += dz * ey;
                M[8][l] += dz * ez;
            }
        }
    }
    for (l = 0; l < SPS__LANES; ++l) { /* F_i and the law; lanes past the body: F = I, no springs */
        const int i = q.i0 + l, o = i - b->begin;
        sps_real Mi[9], F[9], P[9], J;
        if (i >= b->end) {
            for (a = 0; a < 9; ++a) Fl[a][l] = Pl[a][l] = (sps_real)(a % 4 == 0);
            Jl[l] = 1;
            El[l] = 0;
            continue;
        }
        for (a = 0; a < 9; ++a) Mi[a] = M[a][l];
        sps__tl_gradient(Mi, b->tl_correction + (size_t)9 * o, 1 / SPS__V0(w, b, i), dim, F);
        J = sps__det3(F);
        {
            sps_real work = 0;
            sps__tl_law(b, o, F, J, 1, P, &work);
            if (plastic) b->plastic_work[o] += SPS__V0(w, b, i) * work;
        }
        if (b->damage) sps__tl_damage(damage_rate, b->def.material.tl.damage_strain, dt, F, J, b->damage + o, P);
        for (a = 0; a < 9; ++a) {
            b->tl_deformation[(size_t)9 * o + a] = Fl[a][l] = F[a];
            Pl[a][l] = P[a];
        }
        Jl[l] = J;
        El[l] = hourglass ? alpha * sps__tl_hourglass_modulus(b, o, E, Y, plastic) : 0;
    }
    for (k = 0; hourglass && k < q.len; ++k) { /* the springs of i: p^i = F_i X_ij - x_ij, d^i = p^i . x_ij / |x_ij|^2 */
        const long o = (long)k * SPS__LANES;
        SPS__PRAGMA(omp simd)
        for (l = 0; l < SPS__LANES; ++l) {
            const sps_real x = ax[o + l], y = ay[o + l], z = dim == 3 ? az[o + l] : 0;
            const sps_real X = Xx[o + l], Yr = Xy[o + l], Z = dim == 3 ? Xz[o + l] : 0;
            const sps_real x2 = x * x + y * y + z * z, inv_x2 = 1 / (x2 > 0 ? x2 : 1); /* padding: x = 0, its factor 0 */
            sps_real p_x = Fl[0][l] * X + Fl[1][l] * Yr - x, p_y = Fl[3][l] * X + Fl[4][l] * Yr - y, p_z = 0, d, kd;
            if (dim == 3) {
                p_x += Fl[2][l] * Z;
                p_y += Fl[5][l] * Z;
                p_z = Fl[6][l] * X + Fl[7][l] * Yr + Fl[8][l] * Z - z;
            }
            d = (p_x * x + p_y * y + p_z * z) * inv_x2;
            kd = El[l] * spring[o + l] * d; /* k_ij d^i */
            if (hourglass == 2) {
                const sps_real sd = spring[o + l] * d;
                Pil[0][l] += sd * x * X;
                Pil[1][l] += sd * x * Yr;
                Pil[3][l] += sd * y * X;
                Pil[4][l] += sd * y * Yr;
                if (dim == 3) {
                    Pil[2][l] += sd * x * Z;
                    Pil[5][l] += sd * y * Z;
                    Pil[6][l] += sd * z * X;
                    Pil[7][l] += sd * z * Yr;
                    Pil[8][l] += sd * z * Z;
                }
                ax[o + l] = kd * (p_x - (d + 1) * x);
                ay[o + l] = kd * (p_y - (d + 1) * y);
                if (dim == 3) az[o + l] = kd * (p_z - (d + 1) * z);
            } else {
                ax[o + l] = -kd * x;
                ay[o + l] = -kd * y;
                if (dim == 3) az[o + l] = -kd * z;
            }
        }
    }
    for (l = 0; l < SPS__LANES && q.i0 + l < b->end; ++l) {
        const int i = q.i0 + l, o = i - b->begin;
        const sps_real *B = b->tl_correction + (size_t)9 * o, pi_scale = hourglass == 2 ? El[l] / SPS__V0(w, b, i) : 0;
        sps_real *Q = b->tl_stress + (size_t)9 * o, *tau = b->tau + (size_t)6 * o, sigma[9];
        for (a = 0; a < 3; ++a)
            for (c = 0; c < 3; ++c) {
                sps_real s = 0, t = 0;
                for (k = 0; k < dim; ++k) s += (Pl[3 * a + k][l] + pi_scale * Pil[3 * a + k][l]) * B[3 * k + c];
                for (k = 0; k < 3; ++k) t += Pl[3 * a + k][l] * Fl[3 * c + k][l];
                Q[3 * a + c] = s;
                sigma[3 * a + c] = t / Jl[l];
            }
        tau[0] = sigma[0] + w->p[i];
        tau[1] = sigma[1];
        tau[2] = sigma[2];
        tau[3] = sigma[4] + w->p[i];
        tau[4] = sigma[5];
        tau[5] = dim == 3 ? sigma[8] + w->p[i] : 0;
        w->rho[i] = b->rho0 / Jl[l];
    }
}

/* The Kelvin-Voigt force on particle i from its reference neighbour j (>>material: Kelvin-Voigt),
   added to f: 2 (d + 2) eta V0_i V0_j dW(R_ij) / R_ij (v_ij . e_ij) e_ij with the current
   direction e_ij (xij = x_j - x_i, inv_r = 1/|xij|); weight = V0_i V0_j dW / R_ij. Central and
   zero for a rigid motion, as for the updated-Lagrangian bodies. */
static void sps__tl_kelvin_voigt(const sps_world* w, const sps__body* b, int i, int j, const sps_real xij[3], sps_real inv_r,
                                 sps_real weight, int dim, sps_real f[3]) {
    sps_real u = 0, s;
    int a;
    for (a = 0; a < dim; ++a) u += (w->vel[a][i] - w->vel[a][j]) * xij[a];
    s = sps__kelvin_voigt_coefficient(dim, b) * weight * u * inv_r * inv_r;
    for (a = 0; a < dim; ++a) f[a] += s * xij[a];
}

/* The rare pair terms of particle i's force, added to f (damp: the Kelvin-Voigt force, for its
   work): with artificial_viscosity = q1 > 0 (viscosity = q1 c_p h rho0), Monaghan's linear
   artificial viscosity between reference neighbours (as the TL author's LAMMPS input uses it,
   there q1 = 0.06; the paper's runs had none): f_i += sum_j q1 c_p h rho0 V0_i V0_j |dW(R_ij)|
   (v_ij . x_ij) x_ij / (|x_ij| (|x_ij|^2 + 0.01 h^2)), v_ij = v_j - v_i, c_p the P-wave speed:
   central and antisymmetric (both momenta kept), zero for rigid motions, and its power
   -sum_pairs C (v_ij . x_ij)^2 is never positive: it only damps the pairs' stretching rates,
   the hourglass modes' among them; and the Kelvin-Voigt force (sps__tl_kelvin_voigt). */
static void sps__tl_rare_pairs(const sps_world* w, const sps__body* b, int i, sps_real viscosity, const int dim, sps_real f[3], sps_real damp[3]) {
    const sps_real vi = SPS__V0(w, b, i);
    int k, a;
    for (k = 0; k < w->nb_count[i]; ++k) {
        const int j = w->nb_j[w->nb_first[i] + k * SPS__LANES];
        const sps__ref_pair e = sps__tl_pair(w, i, j, dim);
        const sps_real vv = vi * SPS__V0(w, b, j);
        sps_real x[3], x2 = 0;
        for (a = 0; a < dim; ++a) {
            x[a] = w->pos[a][j] - w->pos[a][i];
            x2 += x[a] * x[a];
        }
        if (viscosity > 0) {
            sps_real vx = 0, damper;
            for (a = 0; a < dim; ++a) vx += (w->vel[a][j] - w->vel[a][i]) * x[a];
            damper = -viscosity * vv * e.dw * vx / (SPS__SQRT(x2) * (x2 + SPS_R(0.01) * w->h * w->h));
            for (a = 0; a < dim; ++a) f[a] += damper * x[a];
        }
        if (b->viscous_work) sps__tl_kelvin_voigt(w, b, i, j, x, 1 / SPS__SQRT(x2), vv * e.dw / e.r, dim, damp);
    }
}

/* Force pass of lane group g (in the pressure pass's place): the stress force of TL eq. 24,
   f_i = sum_j V0_i V0_j (P_i L_i^-1 grad W_i(X_ij) - P_j L_j^-1 grad W_j(X_ji))
       = sum_j (Q_i + Q_j) w_ij = Q_i sum_j w_ij + sum_j Q_j w_ij
   (Q holds the hourglass stress too), and the springs' pair forces (springs, a literal):
   f_i += sum_j a^i_ij - a^j_ji, i's spring's force from its own slot and j's from the reverse
   slot (sps__tl_stress; a^j_ji = -a^j_ij, the spring of j seen from j), which is TL eq. 32,
   f_i += -sum_j (k_ij d^i + k_ji d^j) x_ij, and in the variational form the turn of the pair,
   f_i += sum_j k_ij d^i (p^i - d^i x_ij) + k_ji d^j (p^j - d^j x_ij) (k with E Young's modulus,
   or for a J2 body the yield stress at particles that have flowed, TL section 4.5). All are
   antisymmetric in i, j (w_ji = -w_ij exactly), so the pair sums conserve linear momentum; the
   stress force exerts no torque (P F^T = J sigma is symmetric), and the springs' forces, the
   gradient of a rotation-invariant energy (or, in the paper's form, central), none either.
   Then the rare terms (sps__tl_rare_pairs). acc_p = f_i / m_i. */
SPS__INLINE void sps__tl_force(sps_world* w, const sps__body* b, int g, sps_real dt, const int dim, const int springs) {
    const sps__group q = sps__group_of(w, b, g);
    const long n = b->tl_slots, t0 = q.s0 - w->nb_group_start[b->group0];
    const int begin = b->begin;
    const sps_real viscosity = b->def.material.tl.artificial_viscosity * SPS__SQRT((b->mat.K + b->mat.G * 4 / 3) / b->rho0) * w->h * b->rho0;
    const int rare = viscosity > 0 || b->viscous_work;
    const int* SPS__RESTRICT js = w->nb_j + q.s0;
    const int* SPS__RESTRICT reverse = b->tl_reverse + t0;
    const sps_real* SPS__RESTRICT Q = b->tl_stress;
    const sps_real* SPS__RESTRICT wx = b->tl_pairs + t0 + SPS__TLP_WEIGHT(dim, 0) * n;
    const sps_real* SPS__RESTRICT wy = wx + n;
    const sps_real* SPS__RESTRICT wz = dim == 3 ? wx + 2 * n : wx;
    const sps_real* SPS__RESTRICT ax_all = b->tl_pairs + SPS__TLP_FORCE(dim, 0) * n; /* read at the reverse slots */
    const sps_real* SPS__RESTRICT ay_all = ax_all + n;
    const sps_real* SPS__RESTRICT az_all = dim == 3 ? ax_all + 2 * n : ax_all;
    sps_real f[3][SPS__LANES], sw[3][SPS__LANES]; /* sw: sum_j w_ij */
    int k, l, a, c;
    for (a = 0; a < 3; ++a)
        for (l = 0; l < SPS__LANES; ++l) f[a][l] = sw[a][l] = 0;
    for (k = 0; k < q.len; ++k) {
        const int* SPS__RESTRICT jk = js + k * SPS__LANES;
        const long o = (long)k * SPS__LANES;
        SPS__PRAGMA(omp simd)
        for (l = 0; l < SPS__LANES; ++l) {
            const int qj = 9 * (jk[l] - begin); /* an int offset from the array: a gather */
            const sps_real ex = wx[o + l], ey = wy[o + l];
            sw[0][l] += ex;
            sw[1][l] += ey;
            if (dim == 3) {
                const sps_real ez = wz[o + l];
                sw[2][l] += ez;
                f[0][l] += Q[qj] * ex + Q[qj + 1] * ey + Q[qj + 2] * ez;
                f[1][l] += Q[qj + 3] * ex + Q[qj + 4] * ey + Q[qj + 5] * ez;
                f[2][l] += Q[qj + 6] * ex + Q[qj + 7] * ey + Q[qj + 8] * ez;
            } else {
                f[0][l] += Q[qj] * ex + Q[qj + 1] * ey;
                f[1][l] += Q[qj + 3] * ex + Q[qj + 4] * ey;
            }
            if (springs) {
                const long t = t0 + o + l, r = reverse[o + l];
                f[0][l] += ax_all[t] - ax_all[r];
                f[1][l] += ay_all[t] - ay_all[r];
                if (dim == 3) f[2][l] += az_all[t] - az_all[r];
            }
        }
    }
    for (l = 0; l < SPS__LANES && q.i0 + l < b->end; ++l) {
        const int i = q.i0 + l, o = i - begin;
        const sps_real* Qi = Q + (size_t)9 * o;
        sps_real fi[3] = {0, 0, 0}, damp[3] = {0, 0, 0};
        for (a = 0; a < dim; ++a) {
            sps_real s = f[a][l];
            for (c = 0; c < dim; ++c) s += Qi[3 * a + c] * sw[c][l];
            fi[a] = s;
        }
        if (rare) sps__tl_rare_pairs(w, b, i, viscosity, dim, fi, damp);
        for (a = 0; a < dim; ++a) w->acc_p[a][i] = fi[a] / w->mass[i];
        if (b->viscous_work) {
            for (a = 0; a < dim; ++a) w->acc_p[a][i] += damp[a] / w->mass[i];
            b->viscous_work[o] -= dt * (damp[0] * w->vel[0][i] + damp[1] * w->vel[1][i] + (dim == 3 ? damp[2] * w->vel[2][i] : 0));
        }
    }
}

/* The passes' kernels: compiled once per dimension and hourglass form (a total-Lagrangian
   body's pair geometry is its reference one: no mode of its own), the law (sps__tl_law)
   dispatched at run time. */
#ifndef SPHSOLID_NO_TOTAL_LAGRANGIAN /* else no kernel: sps_world_add_body refuses the bodies */
static void sps__tl_stress_pass(sps_world* w, const sps__body* b, int g, sps_real dt) {
    const int plastic = b->model.plastic != SPS__YIELD_NONE, form = sps__tl_hourglass_form(b);
    if (w->dim == 2) {
        if (form == 2) sps__tl_stress(w, b, g, dt, 2, plastic, 2);
        else if (form == 1) sps__tl_stress(w, b, g, dt, 2, plastic, 1);
        else sps__tl_stress(w, b, g, dt, 2, plastic, 0);
    } else {
        if (form == 2) sps__tl_stress(w, b, g, dt, 3, plastic, 2);
        else if (form == 1) sps__tl_stress(w, b, g, dt, 3, plastic, 1);
        else sps__tl_stress(w, b, g, dt, 3, plastic, 0);
    }
}
static void sps__tl_force_pass(sps_world* w, const sps__body* b, int g, sps_real dt) {
    const int springs = b->def.material.tl.hourglass_alpha > 0;
    if (w->dim == 2) {
        if (springs) sps__tl_force(w, b, g, dt, 2, 1);
        else sps__tl_force(w, b, g, dt, 2, 0);
    } else {
        if (springs) sps__tl_force(w, b, g, dt, 3, 1);
        else sps__tl_force(w, b, g, dt, 3, 0);
    }
}
#endif

static sps__passes sps__tl_passes(const sps_world* w, const sps__model* m) {
    sps__passes p;
    memset(&p, 0, sizeof p);
    (void)w;
#ifndef SPHSOLID_NO_TOTAL_LAGRANGIAN
    if (!sps__tl_has_law(m->material->kind)) return p; /* no kernel: sps__missing_pass names it */
    p.stress = sps__tl_stress_pass;
    p.pressure = sps__tl_force_pass;
#else
    (void)m;
#endif
    return p;
}

/* The linearised forces of total-Lagrangian body b at its reference state (F = I, x = X) for the
   displacements u (dim rows of the body's count) into f (the same layout): the passes above with
   the laws' common tangent at F = I, P = lambda tr(H) I + mu (H + H^T), H = F - I (Saint
   Venant-Kirchhoff, Neo-Hookean and Hencky's J2 all reduce to it), and with the hourglass form
   (sps__tl_hourglass_form) the springs' pair forces a^i_ij = -k_ij d^i X_ij,
   d^i = (H_i X_ij - u_ij) . X_ij / R_ij^2, and in the variational form the hourglass stress with
   x_ij = X_ij (the turn of the pair is of second order in u). Q: 9 reals per particle of
   scratch; the table's force rows are overwritten (each stress pass writes them again). */
static void sps__tl_linear_forces(sps_world* w, sps__body* b, int form, const sps_real* u, sps_real* f, sps_real* Q) {
    const int dim = w->dim, count = b->end - b->begin;
    const long n = b->tl_slots, base = w->nb_group_start[b->group0];
    const sps_real mu = b->mat.G, lambda = SPS__LAME_LAMBDA(b), alpha_E = b->def.material.tl.hourglass_alpha * b->def.material.youngs_modulus;
    int o;
    SPS__PARALLEL_FOR(w, count)
    for (o = 0; o < count; ++o) {
        const int i = b->begin + o;
        const sps_real *B = b->tl_correction + (size_t)9 * o, inv_v0 = 1 / SPS__V0(w, b, i);
        sps_real M[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, H[9], P[9], Pi[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, tr = 0;
        int k, a, c, m;
        for (k = 0; k < w->nb_count[i]; ++k) {
            const int s = w->nb_first[i] + k * SPS__LANES, oj = w->nb_j[s] - b->begin;
            const sps_real* row = b->tl_pairs + (s - base);
            for (a = 0; a < dim; ++a)
                for (c = 0; c < dim; ++c) M[3 * a + c] += (u[a * count + oj] - u[a * count + o]) * row[SPS__TLP_WEIGHT(dim, c) * n];
        }
        for (a = 0; a < dim; ++a)
            for (c = 0; c < dim; ++c) {
                sps_real s = 0;
                for (m = 0; m < dim; ++m) s += M[3 * a + m] * B[3 * m + c];
                H[3 * a + c] = s * inv_v0;
            }
        for (a = 0; a < dim; ++a) tr += H[4 * a];
        for (a = 0; a < dim; ++a)
            for (c = 0; c < dim; ++c) P[3 * a + c] = mu * (H[3 * a + c] + H[3 * c + a]) + (a == c ? lambda * tr : 0);
        for (k = 0; form && k < w->nb_count[i]; ++k) {
            const int s = w->nb_first[i] + k * SPS__LANES, oj = w->nb_j[s] - b->begin;
            sps_real* row = b->tl_pairs + (s - base);
            sps_real X[3], d = 0, R2 = 0;
            for (a = 0; a < dim; ++a) {
                X[a] = row[SPS__TLP_X(dim, a) * n];
                R2 += X[a] * X[a];
            }
            for (a = 0; a < dim; ++a) {
                sps_real p = u[a * count + o] - u[a * count + oj]; /* H X_ij - u_ij */
                for (c = 0; c < dim; ++c) p += H[3 * a + c] * X[c];
                d += p * X[a] / R2;
            }
            for (a = 0; a < dim; ++a) row[SPS__TLP_FORCE(dim, a) * n] = -alpha_E * row[SPS__TLP_SPRING(dim) * n] * d * X[a];
            for (a = 0; form == 2 && a < dim; ++a)
                for (c = 0; c < dim; ++c) Pi[3 * a + c] += row[SPS__TLP_SPRING(dim) * n] * d * X[a] * X[c];
        }
        for (a = 0; a < dim; ++a)
            for (c = 0; c < dim; ++c) {
                sps_real s = 0;
                for (m = 0; m < dim; ++m) s += (P[3 * a + m] + alpha_E * inv_v0 * Pi[3 * a + m]) * B[3 * m + c];
                Q[(size_t)9 * o + 3 * a + c] = s;
            }
    }
    SPS__PARALLEL_FOR(w, count)
    for (o = 0; o < count; ++o) {
        const int i = b->begin + o;
        sps_real fi[3] = {0, 0, 0};
        int k, a, c;
        for (k = 0; k < w->nb_count[i]; ++k) {
            const int s = w->nb_first[i] + k * SPS__LANES, oj = w->nb_j[s] - b->begin;
            const long t = s - base, r = b->tl_reverse[t];
            for (a = 0; a < dim; ++a) {
                for (c = 0; c < dim; ++c)
                    fi[a] += (Q[(size_t)9 * o + 3 * a + c] + Q[(size_t)9 * oj + 3 * a + c]) * b->tl_pairs[SPS__TLP_WEIGHT(dim, c) * n + t];
                if (form) fi[a] += b->tl_pairs[SPS__TLP_FORCE(dim, a) * n + t] - b->tl_pairs[SPS__TLP_FORCE(dim, a) * n + r];
            }
        }
        for (a = 0; a < dim; ++a) f[a * count + o] = fi[a];
    }
}

/* Power iterations on the linearised system at the reference state (sps__tl_linear_forces with
   the hourglass form): the largest eigenvalue omega^2 of M^-1 K, K = -df/du, by the Rayleigh
   quotient u.K u / u.M u of the iterate, from a fixed pseudo-random start. Returns omega. The
   sums are serial: the same value for any thread count. scratch: (2 d + 9) reals per particle. */
#define SPS__TL_POWER_STEPS 100
static sps_real sps__tl_highest_frequency(sps_world* w, sps__body* b, int form, sps_real* scratch) {
    const int count = b->end - b->begin, nu = w->dim * count;
    sps_real *u = scratch, *f = u + nu, *Q = f + nu, omega2 = 0;
    unsigned state = 12345u;
    int it, k;
    for (k = 0; k < nu; ++k) {
        state = state * 1103515245u + 12345u;
        u[k] = (state >> 16) & 1 ? 1 : -1;
    }
    for (it = 0; it < SPS__TL_POWER_STEPS; ++it) {
        sps_real uKu = 0, uMu = 0, norm = 0;
        sps__tl_linear_forces(w, b, form, u, f, Q);
        for (k = 0; k < nu; ++k) {
            const sps_real m = w->mass[b->begin + k % count];
            uKu -= u[k] * f[k];
            uMu += m * u[k] * u[k];
            f[k] /= -m; /* M^-1 K u */
            norm += m * f[k] * f[k];
        }
        omega2 = uKu / uMu;
        if (!(norm > 0)) break; /* u in the null space (rigid motions) */
        norm = 1 / SPS__SQRT(norm);
        for (k = 0; k < nu; ++k) u[k] = f[k] * norm;
    }
    return SPS__SQRT(omega2 > 0 ? omega2 : 0);
}

/* Builds the pair table of total-Lagrangian body b from its lane slots (after
   sps__build_neighbors, whenever sps__tl_reference has run), and its signal speed in the
   reference state. The time step: TL section 3 integrates with leapfrog at "a CFL-stable time
   step"; the elastic body's (alpha = 0) is the CFL condition with its P-wave speed
   c_p = sqrt((K + 4G/3)/rho0). The hourglass springs (TL eqs. 25-32) stiffen the modes they
   control and raise the highest frequency omega_max of the discrete system, so c_ref =
   c_p omega_max(alpha) / omega_max(0), both measured by power iterations on the linearised passes
   (sps__tl_highest_frequency): the springs take the margin omega_max dt of the elastic body's
   step, no more. The Rayleigh quotients approach omega_max from below: after the 100 iterations
   the ratio was 0.23-0.31 % under its converged value (3,000 iterations) on the 2D plate at
   H/dp 10, 20 and 40, the D2 beam and the 3D D6 specimen, hence SPS__TL_FREQUENCY_MARGIN = 1.01
   (three times the largest shortfall). (The bound c_p^2 + alpha E h^2 max_i S_i / (d rho0),
   S_i = sum_j V0_j W_ij / R_ij^2, adds the springs' largest stiffness to the elastic one, both at
   their maximum, as if they acted on the same mode: on the 2D plate at alpha 50 it was 3.4 c_p
   against the measured 2.34 c_p; bench/VALIDATION.md, "Total-Lagrangian cost and time step".) */
#define SPS__TL_FREQUENCY_MARGIN SPS_R(1.01)
static sps_result sps__tl_pair_table(sps_world* w, sps__body* b) {
    const int dim = w->dim, rows = SPS__TLP_ROWS(dim), base = w->nb_group_start[b->group0], form = sps__tl_hourglass_form(b);
    const long n = w->nb_group_start[b->group0 + b->ngroups] - base;
    sps_real c = SPS__SQRT((b->mat.K + b->mat.G * 4 / 3) / b->rho0);
    int g;
    sps__free(w, b->tl_pairs);
    sps__free(w, b->tl_reverse);
    b->tl_pairs = (sps_real*)sps__alloc(w, sizeof(sps_real) * (size_t)rows * (size_t)n);
    b->tl_reverse = (int*)sps__alloc(w, sizeof(int) * (size_t)n);
    if (!b->tl_pairs || !b->tl_reverse) return sps__oom(w, "the total-Lagrangian pair table");
    SPS__PARALLEL_FOR(w, b->end - b->begin)
    for (g = 0; g < b->ngroups; ++g) {
        const sps__group q = sps__group_of(w, b, g);
        int k, l, a, m;
        for (k = 0; k < q.len; ++k)
            for (l = 0; l < SPS__LANES; ++l) {
                const int i = q.i0 + l, s = q.s0 + k * SPS__LANES + l, t = s - base, j = w->nb_j[s];
                sps_real* row = b->tl_pairs + t;
                for (a = 0; a < rows; ++a) row[a * n] = 0;
                b->tl_reverse[t] = t; /* padding: a^i - a^i = 0 */
                if (i >= b->end || k >= w->nb_count[i]) continue;
                {
                    const sps__ref_pair e = dim == 2 ? sps__tl_pair(w, i, j, 2) : sps__tl_pair(w, i, j, 3);
                    const sps_real vv = SPS__V0(w, b, i) * SPS__V0(w, b, j), dir[3] = {e.ex, e.ey, e.ez};
                    for (a = 0; a < dim; ++a) {
                        row[SPS__TLP_WEIGHT(dim, a) * n] = vv * e.dw * dir[a];
                        row[SPS__TLP_X(dim, a) * n] = w->ref[a][j] - w->ref[a][i];
                    }
                    row[SPS__TLP_SPRING(dim) * n] = SPS_R(0.5) * vv * e.w / (e.r * e.r);
                    for (m = 0; m < w->nb_count[j]; ++m) /* the lists are symmetric: i is in j's */
                        if (w->nb_j[w->nb_first[j] + m * SPS__LANES] == i) b->tl_reverse[t] = w->nb_first[j] + m * SPS__LANES - base;
                }
            }
    }
    b->tl_slots = n;
    if (form) {
        sps_real* scratch = (sps_real*)sps__alloc(w, sizeof(sps_real) * (size_t)(2 * dim + 9) * (size_t)(b->end - b->begin));
        sps_real omega, omega_elastic;
        if (!scratch) return sps__oom(w, "the total-Lagrangian frequency estimate");
        omega = sps__tl_highest_frequency(w, b, form, scratch);
        omega_elastic = sps__tl_highest_frequency(w, b, 0, scratch);
        sps__free(w, scratch);
        if (omega > omega_elastic) c *= SPS__TL_FREQUENCY_MARGIN * omega / omega_elastic;
    }
    b->mat.c0 = b->tl_c_ref = c;
    if (c > w->c0_max) w->c0_max = c;
    return SPS_OK;
}

/* At every configuration update, after the lists: each total-Lagrangian body's signal speed for
   the time step follows its deformation, c = c_ref / s^2 with s the smallest principal stretch
   (sqrt of the smallest eigenvalue of F^T F, at most 1) of its particles at the current
   positions: a direction compressed by s has its spacing shrunk by s and, for both laws, its
   tangent stiffness grown as 1/s^2 (measured: the D3 block at cfl 0.4 with the reference speed
   stopped with a NaN at 31 % compression; at cfl 0.1 it reached 50 %). Then the world's c0_max,
   the largest signal speed of its deformable bodies, is taken again: for a world without
   total-Lagrangian bodies the same value as before, bit for bit. Serial: a fixed order. */
static void sps__tl_signal_speeds(sps_world* w) {
    sps_real c_max = 0;
    int bi, i, a, c, k;
    for (bi = 0; bi < w->nbodies; ++bi) {
        sps__body* b = &w->bodies[bi];
        if (b->model.material->kinematic && !b->model.free_rigid) continue; /* a free rigid body: its contact stiffness */
        if (b->model.total_lagrangian && b->tl_slots) {
            sps_real s2 = 1; /* the smallest squared principal stretch */
            for (i = b->begin; i < b->end; ++i) {
                sps_real F[9], C[9], d[3], Q[9];
                sps__tl_deformation(w, b, i, w->dim, F);
                for (a = 0; a < 3; ++a)
                    for (c = 0; c < 3; ++c) {
                        sps_real v = 0;
                        for (k = 0; k < 3; ++k) v += F[3 * k + a] * F[3 * k + c];
                        C[3 * a + c] = v;
                    }
                sps__eigen3(C, d, Q);
                for (a = 0; a < 3; ++a)
                    if (!(d[a] >= s2)) s2 = d[a]; /* NaN is kept: the guards report the state */
            }
            b->mat.c0 = b->tl_c_ref / (s2 > SPS_R(1e-6) ? s2 : SPS_R(1e-6)); /* a collapsed particle: the guards stop the run */
        }
        if (b->mat.c0 > c_max) c_max = b->mat.c0;
    }
    w->c0_max = c_max;
}

/* The stored energy V0 psi(F) of particle i of total-Lagrangian body b, F from the current
   positions (the neighbour lists are valid wherever energies are summed: diagnostics and the
   watchdog at configuration updates), plus the energy of its hourglass springs (in either form:
   the paper's force is not its gradient, and the account shows the energy it feeds in); 0
   before its reference lists are built. A damaged particle's law energy is counted as
   (1 - D) V0 psi(F): the rate model of TL eq. 45 has no potential, and a broken one (D = 1)
   stores nothing however far its crack opens, so the energy account falls by what damage
   dissipates (its springs' modulus has the factor 1 - D already). */
static sps_real sps__tl_energy(const sps_world* w, const sps__body* b, int i) {
    sps_real F[9], P[9], psi, modulus, springs;
    if (!b->tl_slots) return 0;
    sps__tl_deformation(w, b, i, w->dim, F);
    psi = sps__tl_law(b, i - b->begin, F, sps__det3(F), 0, P, NULL); /* the state is not advanced */
    if (b->damage) psi *= 1 - b->damage[i - b->begin];
    modulus = sps__tl_hourglass_modulus(b, i - b->begin, b->def.material.youngs_modulus, sps__tl_flowed_modulus(b),
                                        b->model.plastic != SPS__YIELD_NONE);
    springs = b->def.material.tl.hourglass_alpha > 0 ? sps__tl_springs(w, b, i, w->dim, F, modulus) : 0;
    return SPS__V0(w, b, i) * psi + springs;
}

/* >>contact: rigid walls and contact between bodies */

/* Contact follows the reference code's contact density (DESIGN of the ENO paper's section 6.3):
   each particle i of a body that touches others has the contact density
       sigma_i = sum_{j of the bodies it touches} W_ij V_j   (dimensionless, 0 away from contact)
   and feels the repulsion
       F_i = -V_i sum_j K_ij (sigma_i + sigma_j) dW_ij e_ij V_j,
   K_ij = 2 K_a K_b / (K_a + K_b) (the bodies' bulk moduli rho0 c0^2, harmonic mean). Every
   factor is symmetric in i and j and e_ji = -e_ij, so F_j = -F_i: linear momentum is exact, and
   each pair's force is central (angular momentum too). A gather like every other pass: the
   thread that owns i writes only i.
   An analytic wall is the same law with the solid half-space behind it taken as a continuum of
   contact density sigma_i: its sums become integrals of the kernel, functions of the distance
   d of the particle from the wall, tabulated once per world:
       sigma_wall(d) = int_{half-space} W dV,    int_{half-space} grad_i W dV = -n W_plane(d),
   W_plane(d) the kernel integrated over the wall's plane at distance d, so the wall adds
       sigma_i += sigma_wall(d),    F_i += 2 V_i K sigma_i W_plane(d) n
   (K the body's). A no-slip wall adds F_i -= 2 V_i rho0 c0 W_plane(d) v_t, a drag on the
   tangential velocity with the Riemann solver's impedance (it brings the contact layer to rest
   in about one acoustic time).
   Coulomb friction (mu > 0: body friction, sps_world_set_wall_friction; a pair's coefficient
   is the geometric mean sqrt(mu_a mu_b), Box2D's b2MixFriction) is that drag bounded by mu
   times the normal force of the same pair or wall:
       F_t = -min(D |v_t|, mu F_n) v_t / |v_t|,
   a velocity-regularised law: below the bound the contact sticks through the drag D (it creeps
   at the speed that makes D |v_t| carry the load), above it the contact slides with the
   Coulomb force. Why not a tangential spring (elastic stick, no creep): it needs a history per
   contact pair and per particle and wall, carried over list rebuilds and saved in restarts, for
   a creep that the drag already keeps below 1 % of the motion it stops. For a wall,
   F_n = 2 V_i K sigma_i W_plane(d) and D = rho_i V_i / (2 dt), the strongest drag the explicit
   kick carries (it halves v_t in a sub-step): a block with mu = 0.3 on a 10-degree slope creeps
   0.36 % of its frictionless distance in 1 s, against 4.5 % with the no-slip wall's impedance
   drag 2 V_i rho0 c0 W_plane(d), which lives in the kernel's tail where a resting body sits
   (bench/VALIDATION.md, "Friction and material damping"). SPS_WALL_NO_SLIP keeps its meaning,
   that impedance drag with no Coulomb bound (mu = infinity). For a pair of particles of two
   bodies (a particle has many partners, whose drags add up: the kick's bound rules out the
   wall's), F_n = -V_i V_j K_ij (sigma_i + sigma_j) dW_ij (the
   repulsion's magnitude) and D = -2 V_i V_j Z_ij dW_ij, Z_ij the harmonic mean of the bodies'
   impedances rho0 c0, v_t the tangential part of v_i - v_j: both symmetric in i and j and v_t
   antisymmetric, so F_t,ji = -F_t,ij and linear momentum stays exact (a tangential pair force
   has a torque about the pair's midpoint: angular momentum is not exact with friction between
   bodies, as the torque is real for two bodies in contact only when the forces act at one
   point). A scene without friction runs none of this (w->friction = 0).
   Normal contact damping (contact_damping = zeta of a body, CONTACT in the manual): a dashpot
   on the normal relative velocity v_n of the same contact forces, F_d = -c v_n n, with the
   friction's drags as its scale: c = zeta 2 rho0 c0 W_plane(d) V_i at a wall (zeta times the
   no-slip wall's impedance drag), c = zeta_ij D between bodies (zeta_ij the mean of the two
   bodies'); bounded by the repulsion while the contact opens (no pull). Its work is summed
   into viscous_work. A scene without it runs none of this (w->contact_damped = 0). */

SPSDEF sps_result sps_world_add_wall(sps_world* w, const sps_real point[3], const sps_real normal[3], sps_wall_slip slip) {
    sps__wall wall;
    sps_real len2 = 0;
    int a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (!sps__finite_point(w, point) || !sps__finite_point(w, normal)) {
        sps__set_error(w, 0, "sps_world_add_wall: point %s and normal %s, allowed finite", point ? "set" : "NULL", normal ? "set" : "NULL");
        return SPS_ERR_INVALID_ARG;
    }
    for (a = 0; a < w->dim; ++a) len2 += normal[a] * normal[a];
    if (!(len2 > 0) || !sps__finite(len2)) {
        sps__set_error(w, 0, "sps_world_add_wall: normal = (%g, %g, %g) has length %g, allowed > 0", (double)normal[0], (double)normal[1],
                       w->dim == 3 ? (double)normal[2] : 0.0, (double)SPS__SQRT(len2));
        return SPS_ERR_INVALID_ARG;
    }
    if (slip != SPS_WALL_FREE_SLIP && slip != SPS_WALL_NO_SLIP) {
        sps__set_error(w, 0, "sps_world_add_wall: slip = %d, allowed 0 (free slip) or 1 (no slip)", (int)slip);
        return SPS_ERR_INVALID_ARG;
    }
    if (!sps__periodic_allows_wall(w, normal, SPS__SQRT(len2))) return SPS_ERR_INVALID_ARG;
    memset(&wall, 0, sizeof wall);
    for (a = 0; a < w->dim; ++a) {
        wall.point[a] = point[a];
        wall.normal[a] = normal[a] / SPS__SQRT(len2);
    }
    wall.slip = slip;
    if (!sps__grow(w, &w->walls, sizeof wall, (size_t)w->nwalls, (size_t)w->nwalls + 1)) return sps__oom(w, "sps_world_add_wall: the wall table");
    if (w->nwalls == 0) {
        sps__kernel_plane_tables(w, SPS__WALL_TABLE, w->wall_plane, w->wall_sigma);
        w->rest_wall_sigma = sps__wall_sigma(w, w->rest_wall_distance);
    }
    w->walls[w->nwalls++] = wall;
    w->contact_dirty = 1;
    if (slip == SPS_WALL_NO_SLIP) w->needs_sort_by_body = 1; /* a granular body's "wall_equilibrium" (the commit) */
    sps__rearm_watchdog(w);
    return SPS_OK;
}

SPSDEF sps_result sps_world_add_box_walls(sps_world* w, const sps_real lo[3], const sps_real hi[3], unsigned open_faces, sps_wall_slip slip) {
    int a, side;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (!sps__check_box(w, "sps_world_add_box_walls", lo, hi)) return SPS_ERR_INVALID_ARG;
    if (open_faces >= (1u << (2 * w->dim))) {
        sps__set_error(w, 0, "sps_world_add_box_walls: open_faces = %u, allowed a mask of SPS_FACE_* below %u", open_faces, 1u << (2 * w->dim));
        return SPS_ERR_INVALID_ARG;
    }
    for (a = 0; a < w->dim; ++a)
        for (side = 0; side < 2; ++side) {
            sps_real point[3] = {0, 0, 0}, normal[3] = {0, 0, 0};
            sps_result r;
            if (open_faces & (1u << (2 * a + side))) continue;
            point[a] = side ? hi[a] : lo[a];
            normal[a] = side ? -1 : 1; /* inwards */
            if ((r = sps_world_add_wall(w, point, normal, slip)) != SPS_OK) return r;
        }
    return SPS_OK;
}

SPSDEF sps_result sps_world_set_wall_friction(sps_world* w, int wall, sps_real mu) {
    int k;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (!(mu >= 0) || !sps__finite(mu)) {
        sps__set_error(w, 0, "sps_world_set_wall_friction: mu = %g, allowed finite >= 0 (Coulomb coefficient; 0: none)", (double)mu);
        return SPS_ERR_INVALID_ARG;
    }
    if (wall < -1 || wall >= w->nwalls || w->nwalls == 0) {
        sps__set_error(w, 0, "sps_world_set_wall_friction: wall = %d, allowed -1 (all) or 0..%d (the walls added so far, %d)", wall,
                       w->nwalls - 1, w->nwalls);
        return SPS_ERR_INVALID_ARG;
    }
    for (k = 0; k < w->nwalls; ++k)
        if ((wall < 0 || k == wall) && w->walls[k].slip == SPS_WALL_NO_SLIP && mu > 0) {
            sps__set_error(w, 0, "sps_world_set_wall_friction: wall %d is no-slip, which holds the tangential velocity with no Coulomb "
                           "bound (mu = infinity); mu = %g is allowed on free-slip walls", k, (double)mu);
            return SPS_ERR_INVALID_ARG;
        }
    for (k = 0; k < w->nwalls; ++k)
        if (wall < 0 || k == wall) w->walls[k].friction = mu;
    sps__warn_friction(w, "sps_world_set_wall_friction: mu", mu);
    w->contact_dirty = 1;
    sps__rearm_watchdog(w);
    return SPS_OK;
}

SPSDEF sps_result sps_world_set_wall_velocity(sps_world* w, int wall, const sps_real velocity[3]) {
    sps_real vn = 0;
    int a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (wall < 0 || wall >= w->nwalls) {
        sps__set_error(w, 0, "sps_world_set_wall_velocity: wall = %d, allowed 0..%d (the walls added so far, %d)", wall, w->nwalls - 1, w->nwalls);
        return SPS_ERR_INVALID_ARG;
    }
    if (!sps__finite_point(w, velocity)) {
        sps__set_error(w, 0, "sps_world_set_wall_velocity: velocity %s, allowed finite", velocity ? "not finite" : "NULL");
        return SPS_ERR_INVALID_ARG;
    }
    for (a = 0; a < w->dim; ++a) vn += velocity[a] * w->walls[wall].normal[a];
    if (SPS__FABS(vn) > SPS_R(1e-9) * (SPS__FABS(velocity[0]) + SPS__FABS(velocity[1]) + SPS__FABS(velocity[2]))) {
        sps__set_error(w, 0, "sps_world_set_wall_velocity: velocity = (%g, %g, %g) has %g m/s along wall %d's normal, allowed 0 (a wall "
                       "does not move: the velocity is its surface's, along it)", (double)velocity[0], (double)velocity[1],
                       w->dim == 3 ? (double)velocity[2] : 0.0, (double)vn, wall);
        return SPS_ERR_INVALID_ARG;
    }
    for (a = 0; a < 3; ++a) w->walls[wall].velocity[a] = a < w->dim ? velocity[a] : 0;
    sps__rearm_watchdog(w);
    return SPS_OK;
}

/* Whether bodies a and b (indices, a != b) touch: both defs ask for contact and no call of
   sps_world_set_contact turned the pair off. */
static int sps__bodies_touch(const sps_world* w, int a, int b) {
    int k;
    if (!w->bodies[a].def.contact || !w->bodies[b].def.contact) return 0;
    for (k = 0; k < w->nseparate; ++k)
        if ((w->separate[2 * k] == a && w->separate[2 * k + 1] == b) || (w->separate[2 * k] == b && w->separate[2 * k + 1] == a)) return 0;
    return 1;
}

SPSDEF sps_result sps_world_set_contact(sps_world* w, sps_body a, sps_body b, int touch) {
    int ka, kb, k;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if ((ka = sps__check_body(w, a, "sps_world_set_contact")) < 0 || (kb = sps__check_body(w, b, "sps_world_set_contact")) < 0) return SPS_ERR_INVALID_ARG;
    if (ka == kb || (touch != 0 && touch != 1)) {
        sps__set_error(w, 0, "sps_world_set_contact: bodies %d and %d with touch = %d, allowed two different bodies and touch 0 or 1", ka, kb, touch);
        return SPS_ERR_INVALID_ARG;
    }
    for (k = 0; k < w->nseparate; ++k) /* drop the pair from the list of separated ones */
        if ((w->separate[2 * k] == ka && w->separate[2 * k + 1] == kb) || (w->separate[2 * k] == kb && w->separate[2 * k + 1] == ka)) {
            w->separate[2 * k] = w->separate[2 * (w->nseparate - 1)];
            w->separate[2 * k + 1] = w->separate[2 * (w->nseparate - 1) + 1];
            --w->nseparate;
            break;
        }
    if (!touch) {
        if (!sps__grow(w, &w->separate, 2 * sizeof(int), (size_t)w->nseparate, (size_t)w->nseparate + 1)) return sps__oom(w, "sps_world_set_contact: the pair table");
        w->separate[2 * w->nseparate] = ka;
        w->separate[2 * w->nseparate + 1] = kb;
        ++w->nseparate;
    }
    w->contact_dirty = 1;
    sps__rearm_watchdog(w);
    return SPS_OK;
}

/* Whether any two bodies touch (then the configuration update finds contact pairs). */
static int sps__any_contact(const sps_world* w) {
    int a, b;
    for (a = 0; a < w->nbodies; ++a)
        for (b = a + 1; b < w->nbodies; ++b)
            if (sps__bodies_touch(w, a, b)) return 1;
    return 0;
}

/* The contact partners of particle i in the cell grid of sps__find_contact_pairs: the particles
   of the bodies its body touches within the support, in cell order, written to out (NULL: only
   counted). Returns their count. */
static int sps__contact_partners(const sps_world* w, int i, int* out) {
    const int dim = w->dim, bi = w->body[i], cx = w->ct_cell[i] % w->grid_n[0], cy = w->ct_cell[i] / w->grid_n[0] % w->grid_n[1];
    const int cz = w->ct_cell[i] / (w->grid_n[0] * w->grid_n[1]);
    const sps_real cut2 = w->support * w->support;
    int dx, dy, dz, m = 0;
    for (dz = -(dim == 3); dz <= (dim == 3); ++dz)
        for (dy = -1; dy <= 1; ++dy)
            for (dx = -1; dx <= 1; ++dx) {
                int x = cx + dx, y = cy + dy, z = cz + dz, s, c;
                if ((!w->grid_wrap[0] && (x < 0 || x >= w->grid_n[0])) || (!w->grid_wrap[1] && (y < 0 || y >= w->grid_n[1])) ||
                    (!w->grid_wrap[2] && (z < 0 || z >= w->grid_n[2])))
                    continue;
                x += x < 0 ? w->grid_n[0] : x >= w->grid_n[0] ? -w->grid_n[0] : 0; /* wrapped (one cell at most) */
                y += y < 0 ? w->grid_n[1] : y >= w->grid_n[1] ? -w->grid_n[1] : 0;
                z += z < 0 ? w->grid_n[2] : z >= w->grid_n[2] ? -w->grid_n[2] : 0;
                c = x + w->grid_n[0] * (y + w->grid_n[1] * z);
                if (w->ct_cell_body[c] == bi) continue; /* its own body's particles only (most cells, inside a body) */
                for (s = w->ct_cell_start[c]; s < w->ct_cell_start[c + 1]; ++s) {
                    const int j = w->ct_order[s];
                    sps_real r2 = 0;
                    int a;
                    if (w->body[j] == bi || !w->touch[(size_t)bi * w->nbodies + w->body[j]]) continue;
                    if (w->periodic) {
                        sps_real d[3];
                        r2 = sps__offset(w, i, j, d);
                    } else
                        for (a = 0; a < dim; ++a) r2 += (w->pos[a][i] - w->pos[a][j]) * (w->pos[a][i] - w->pos[a][j]);
                    if (!(r2 < cut2)) continue;
                    if (out) out[m] = j;
                    ++m;
                }
            }
    return m;
}

/* Contact pairs (at each configuration update): for every particle, the particles of the
   bodies its body touches within the support, found through one cell grid over the world that
   orders particle indices by cell (the particles themselves are not moved); in cell order, so
   the lists, and the sums over them, do not depend on the thread count. CSR: particle i's are
   ct_j[ct_first[i] .. ct_first[i + 1]). */
static sps_result sps__find_contact_pairs(sps_world* w) {
    const int n = w->n, dim = w->dim;
    int i, c, ncell, total = 0;
    if (w->ct_cap < w->cap) {
        sps__free(w, w->ct_first); sps__free(w, w->ct_cell); sps__free(w, w->ct_order); sps__free(w, w->ct_cell_start);
        sps__free(w, w->ct_cell_body);
        w->ct_first = (int*)sps__alloc(w, sizeof(int) * ((size_t)w->cap + 1));
        w->ct_cell = (int*)sps__alloc(w, sizeof(int) * (size_t)w->cap);
        w->ct_order = (int*)sps__alloc(w, sizeof(int) * (size_t)w->cap);
        w->ct_cell_start = (int*)sps__alloc(w, sizeof(int) * (4 * (size_t)w->cap + 64 + 2));
        w->ct_cell_body = (int*)sps__alloc(w, sizeof(int) * (4 * (size_t)w->cap + 64 + 1));
        w->ct_cap = w->ct_first && w->ct_cell && w->ct_order && w->ct_cell_start && w->ct_cell_body ? w->cap : 0;
        if (!w->ct_cap) return sps__oom(w, "the contact lists");
    }
    ncell = sps__setup_grid(w, w->pos, 0, n);
    for (i = 0; i < n; ++i) {
        int a;
        for (c = 0, a = dim - 1; a >= 0; --a) c = c * w->grid_n[a] + sps__cell_coord(w, a, w->pos[a][i]);
        w->ct_cell[i] = c;
    }
    for (c = 0; c <= ncell; ++c) w->ct_cell_start[c] = 0; /* counting sort of the indices */
    for (i = 0; i < n; ++i) w->ct_cell_start[w->ct_cell[i] + 1]++;
    for (c = 0; c < ncell; ++c) w->ct_cell_start[c + 1] += w->ct_cell_start[c];
    for (i = 0; i < n; ++i) w->ct_order[w->ct_cell_start[w->ct_cell[i]]++] = i;
    for (c = ncell; c > 0; --c) w->ct_cell_start[c] = w->ct_cell_start[c - 1];
    w->ct_cell_start[0] = 0;
    for (c = 0; c < ncell; ++c) { /* a cell of one body has no partner for that body's particles */
        int s, only = w->ct_cell_start[c] < w->ct_cell_start[c + 1] ? w->body[w->ct_order[w->ct_cell_start[c]]] : -1;
        for (s = w->ct_cell_start[c] + 1; s < w->ct_cell_start[c + 1] && only >= 0; ++s)
            if (w->body[w->ct_order[s]] != only) only = -1;
        w->ct_cell_body[c] = only;
    }
    /* each particle's partners counted, then written to its own run of ct_j: in parallel, the
       lists the same for any thread count */
    SPS__PARALLEL_FOR(w, n)
    for (i = 0; i < n; ++i) w->ct_first[i] = sps__contact_partners(w, i, NULL);
    for (i = 0; i < n; ++i) { /* counts to offsets */
        const int m = w->ct_first[i];
        w->ct_first[i] = total;
        total += m;
    }
    w->ct_first[n] = total;
    if (total > w->ct_pair_cap) { /* grows when more particles come into contact */
        const long cap = (long)total + total / 2 + 64;
        sps__free(w, w->ct_j);
        if (!(w->ct_j = (int*)sps__alloc(w, sizeof(int) * (size_t)cap))) { w->ct_pair_cap = 0; return sps__oom(w, "the contact pairs"); }
        w->ct_pair_cap = cap;
    }
    SPS__PARALLEL_FOR(w, n)
    for (i = 0; i < n; ++i)
        if (w->ct_first[i + 1] > w->ct_first[i]) sps__contact_partners(w, i, w->ct_j + w->ct_first[i]);
    return SPS_OK;
}

/* A contact's friction coefficient from its two sides' (the chapter's head). */
static sps_real sps__mix_friction(sps_real mu_a, sps_real mu_b) { return SPS__SQRT(mu_a * mu_b); }

/* Whether the scene has friction (w->friction) and, if two touching bodies have, the table of
   their coefficients (nbodies^2, made at commit after the touch table). */
static sps_result sps__commit_friction(sps_world* w) {
    int a, b, k, pairs = 0;
    for (a = 0; a < w->nbodies; ++a) {
        const sps_real mu = w->bodies[a].def.friction;
        int rubs = 0; /* some contact of body a has friction */
        for (k = 0; k < w->nwalls; ++k) rubs |= sps__mix_friction(mu, w->walls[k].friction) > 0;
        w->friction |= rubs;
        for (b = 0; b < w->nbodies; ++b) {
            const int pair = w->touch[(size_t)a * w->nbodies + b] == SPS__TOUCH_CONTACT && sps__mix_friction(mu, w->bodies[b].def.friction) > 0;
            pairs |= pair;
            rubs |= pair;
        }
        if (mu > 0 && !rubs) /* a setting that does nothing is said, not ignored silently */
            sps__warn(w, "body '%s': friction = %g, but none of its contacts has friction (a contact's mu is sqrt(mu_a mu_b): it needs a "
                      "wall with sps_world_set_wall_friction > 0 or a touching body with friction > 0)", w->bodies[a].name, (double)mu);
    }
    w->friction |= pairs;
    sps__free(w, w->pair_friction);
    w->pair_friction = NULL;
    if (!pairs) return SPS_OK;
    if (!(w->pair_friction = (sps_real*)sps__alloc(w, sizeof(sps_real) * (size_t)w->nbodies * (size_t)w->nbodies))) return SPS_ERR_OUT_OF_MEMORY;
    for (a = 0; a < w->nbodies; ++a)
        for (b = 0; b < w->nbodies; ++b)
            w->pair_friction[(size_t)a * w->nbodies + b] = sps__mix_friction(w->bodies[a].def.friction, w->bodies[b].def.friction);
    return SPS_OK;
}

/* The pair table of which bodies touch (nbodies^2 flags), made at commit; and the contact
   storage that the scene needs: none without walls or touching bodies. */
static sps_result sps__commit_contact(sps_world* w) {
    int a, b;
    sps__warn_uncoupled(w);
    for (a = 0; a < w->nbodies; ++a) w->bodies[a].coupled = 0; /* set below for the pairs that touch */
    w->coupling_c0 = 0;
    w->contact_bodies = sps__any_contact(w);
    w->friction = w->contact_damped = 0;
    if (!w->contact_bodies && w->nwalls == 0) {
        for (a = 0; a < w->nbodies; ++a)
            if (w->bodies[a].def.friction > 0)
                sps__warn(w, "body '%s': friction = %g in a scene without contact (no walls, no other body it touches): it does nothing",
                          w->bodies[a].name, (double)w->bodies[a].def.friction);
        return SPS_OK;
    }
    if (w->touch_n != w->nbodies) {
        sps__free(w, w->touch);
        w->touch_n = 0;
        if (!(w->touch = (unsigned char*)sps__alloc(w, (size_t)w->nbodies * (size_t)w->nbodies))) return SPS_ERR_OUT_OF_MEMORY;
        w->touch_n = w->nbodies;
    }
    for (a = 0; a < w->nbodies; ++a)
        for (b = 0; b < w->nbodies; ++b) {
            const int coupled = sps__fluid_solid(w, a, b);
            w->touch[(size_t)a * w->nbodies + b] = (unsigned char)(a == b || !sps__bodies_touch(w, a, b) ? SPS__TOUCH_NONE
                                                                   : coupled ? SPS__TOUCH_COUPLED : SPS__TOUCH_CONTACT);
            if (w->touch[(size_t)a * w->nbodies + b] == SPS__TOUCH_COUPLED) w->bodies[a].coupled = w->bodies[b].coupled = 1;
        }
    w->coupling_c0 = sps__coupling_speed(w);
    for (a = 0; a < w->nbodies; ++a) w->contact_damped |= w->bodies[a].def.contact_damping > 0;
    if (sps__commit_friction(w) != SPS_OK) return SPS_ERR_OUT_OF_MEMORY;
    if (w->sigma_cap < w->cap) {
        sps__free(w, w->sigma);
        w->sigma_cap = 0;
        if (!(w->sigma = (sps_real*)sps__alloc(w, sizeof(sps_real) * (size_t)w->cap))) return SPS_ERR_OUT_OF_MEMORY;
        w->sigma_cap = w->cap;
    }
    return SPS_OK;
}

/* The wall's contact density at distance d (negative: the particle is inside the wall). A
   particle pushed into the wall sees more than half of its kernel there, 1 - sigma_wall(-d),
   up to 1, while the plane integral stays at its peak: the repulsion grows with the penetration
   instead of fading, so a particle cannot be squeezed through a wall. */
static sps_real sps__wall_sigma(const sps_world* w, sps_real d) {
    return d >= 0 ? sps__plane_table_at(w, w->wall_sigma, SPS__WALL_TABLE, d) : 1 - sps__plane_table_at(w, w->wall_sigma, SPS__WALL_TABLE, -d);
}

/* Contact density of particle i from the other bodies' particles (its contact pairs), above
   its rest value. */
static sps_real sps__pair_contact_density(const sps_world* w, int i) {
    sps_real sigma = 0;
    int k;
    if (!w->contact_bodies) return 0; /* no contact lists */
    for (k = w->ct_first[i]; k < w->ct_first[i + 1]; ++k) {
        const int j = w->ct_j[k];
        sps_real r2 = 0;
        sps_real d[3];
        if (sps__coupled_pair(w, i, j)) continue; /* a fluid-solid pair: no contact density (>>coupling) */
        r2 = sps__pair_offset(w, i, j, d);
        sigma += sps_world_kernel(w, SPS__SQRT(r2)) * w->vol[j];
    }
    return sigma > w->rest_pair_sigma ? sigma - w->rest_pair_sigma : 0;
}
/* sigma plus the contact density of particle i from the walls, each above its rest value. */
static sps_real sps__wall_contact_density(const sps_world* w, int i, sps_real sigma) {
    int k;
    for (k = 0; k < w->nwalls; ++k) {
        const sps__wall* wl = &w->walls[k];
        const sps_real d = sps__wall_distance(w, wl, i);
        if (d < w->rest_wall_distance) sigma += sps__wall_sigma(w, d) - w->rest_wall_sigma;
    }
    return sigma;
}
/* Contact density of particle i (its pairs and the walls). */
static sps_real sps__contact_density(const sps_world* w, int i) { return sps__wall_contact_density(w, i, sps__pair_contact_density(w, i)); }

/* Harmonic mean of two bulk moduli: the stiffness of a contact between two bodies. */
static sps_real sps__contact_stiffness(sps_real ka, sps_real kb) { return 2 * ka * kb / (ka + kb); }

/* The energy stored in particle i's contacts [J] (J/m in 2D). The contact force between bodies
   is the gradient of U = 1/2 sum_i K V_i sigma_i^2 (sigma_i its contact density from the other
   bodies; K of its pair of bodies, here that of its first contact partner: exact for two bodies
   or equal moduli), and the wall force that of K V_i sigma_w,i^2 (sigma_w,i its density of
   wall); a particle near both gets the sum of the two, the cross term of the force law left out.
   Volumes are taken as fixed, as in the force. */
static sps_real sps__contact_energy(const sps_world* w, int i) {
    const sps__body* bi = &w->bodies[w->body[i]];
    const sps_real sigma = sps__pair_contact_density(w, i), sigma_wall = sps__wall_contact_density(w, i, 0);
    const sps_real k_pair = w->contact_bodies && w->ct_first[i + 1] > w->ct_first[i]
                            ? sps__contact_stiffness(bi->mat.K, w->bodies[w->body[w->ct_j[w->ct_first[i]]]].mat.K) : 0;
    const sps_real k_wall = bi->model.mirrored ? 0 : bi->mat.K; /* a fluid's or granular body's wall force is its mirror particles' */
    return w->vol[i] * (SPS_R(0.5) * k_pair * sigma * sigma + k_wall * sigma_wall * sigma_wall);
}

/* A free rigid body's friction takes the velocity of the contact surface, not of its particle
   (chapter >>material: free rigid bodies (continued): friction at the surface). */
static void sps__rigid_contact_velocity(const sps_world* w, const sps__body* b, const sps_real offset[3], sps_real v[3]);
static void sps__rigid_wall_contact_offset(const sps_world* w, const sps_real normal[3], sps_real distance, sps_real offset[3]);
static void sps__rigid_friction_couple(const sps_world* w, int i, const sps_real offset[3], const sps_real before[3], const sps_real f[3]);
static sps_real sps__rigid_stick_drag(const sps_world* w, const sps__body* b, int i, sps_real dt);

/* The Coulomb friction force per volume of particle i, added to f: -min(drag |v_t|, mu f_n) v_t/|v_t|
   for the tangential velocity v_t, normal force f_n and stick drag `drag` of one contact (the
   chapter's head). */
static void sps__add_friction(sps_real mu, sps_real f_n, sps_real drag, const sps_real v_t[3], int dim, sps_real f[3]) {
    const sps_real speed = SPS__SQRT(v_t[0] * v_t[0] + v_t[1] * v_t[1] + v_t[2] * v_t[2]), bound = mu * f_n;
    const sps_real coefficient = drag * speed > bound ? bound / speed : drag; /* sliding : sticking */
    int a;
    for (a = 0; a < dim; ++a) f[a] -= coefficient * v_t[a];
}

/* The friction of particle i with particle j of another body (bodies bi, bj), d = x_i - x_j at
   distance r, dw = dW(r), normal force per volume f_n (chapter's head). */
static void sps__pair_friction(const sps_world* w, const sps__body* bi, int i, int j, const sps_real d[3], sps_real r, sps_real dw,
                               sps_real f_n, sps_real f[3]) {
    const sps__body* bj = &w->bodies[w->body[j]];
    const sps_real mu = w->pair_friction[(size_t)w->body[i] * w->nbodies + w->body[j]];
    const sps_real half[3] = {-SPS_R(0.5) * d[0], -SPS_R(0.5) * d[1], -SPS_R(0.5) * d[2]}, before[3] = {f[0], f[1], f[2]};
    sps_real v[3] = {0, 0, 0}, v_t[3] = {0, 0, 0}, un = 0;
    int a;
    if (!(mu > 0)) return;
    for (a = 0; a < w->dim; ++a) v[a] = w->vel[a][i] - w->vel[a][j];
    /* at the pair's midpoint: v_i + omega_i x (-d/2) - (v_j + omega_j x (d/2)) */
    if (bi->model.free_rigid) sps__rigid_contact_velocity(w, bi, half, v);
    if (bj->model.free_rigid) sps__rigid_contact_velocity(w, bj, half, v);
    for (a = 0; a < w->dim; ++a) un += v[a] * d[a] / r;
    for (a = 0; a < w->dim; ++a) v_t[a] = v[a] - un * d[a] / r;
    sps__add_friction(mu, f_n, -2 * sps__contact_stiffness(bi->z_riemann, bj->z_riemann) * dw * w->vol[j], v_t, w->dim, f);
    if (bi->model.free_rigid) sps__rigid_friction_couple(w, i, half, before, f);
}

/* The normal contact dashpot of one contact, added to f (force per volume of the particle):
   -c v_n n for the normal relative velocity v_n = v . n (n pointing from the other side to the
   particle) and the dashpot coefficient c, bounded while the contact opens (v_n > 0) so that
   it never pulls harder than the repulsion f_n pushes: a contact cannot stick (the usual
   clip of a linear spring-dashpot, whose dashpot would otherwise pull the bodies together as
   they part). */
static void sps__add_contact_dashpot(sps_real c, sps_real v_n, sps_real f_n, const sps_real n[3], int dim, sps_real f[3]) {
    sps_real f_d = -c * v_n;
    int a;
    if (f_d < -f_n) f_d = -f_n;
    for (a = 0; a < dim; ++a) f[a] += f_d * n[a];
}

/* The normal dashpot of particle i with particle j of another body (the chapter's head):
   coefficient c = zeta_ij D, D = -2 V_j Z_ij dW_ij the pair friction's drag per volume of i,
   zeta_ij = (zeta_a + zeta_b) / 2; symmetric in i and j with v_n and e_ij antisymmetric, so
   the pair's dashpot forces are equal, opposite and central. */
static void sps__pair_dashpot(const sps_world* w, const sps__body* bi, int i, int j, const sps_real d[3], sps_real r, sps_real dw,
                              sps_real f_n, sps_real f[3]) {
    const sps__body* bj = &w->bodies[w->body[j]];
    const sps_real zeta = SPS_R(0.5) * (bi->def.contact_damping + bj->def.contact_damping);
    sps_real e[3] = {0, 0, 0}, v_n = 0;
    int a;
    if (!(zeta > 0)) return;
    for (a = 0; a < w->dim; ++a) { e[a] = d[a] / r; v_n += (w->vel[a][i] - w->vel[a][j]) * e[a]; }
    sps__add_contact_dashpot(-2 * zeta * sps__contact_stiffness(bi->z_riemann, bj->z_riemann) * dw * w->vol[j], v_n, f_n, e, w->dim, f);
}

/* The friction of particle i with wall wl in a sub-step dt: the stick drag rho_i / (2 dt) per
   volume bounded by mu times the wall's normal force per volume f_n (chapter's head). */
static void sps__wall_friction(const sps_world* w, const sps__body* bi, int i, const sps__wall* wl, sps_real f_n, sps_real dt, sps_real f[3]) {
    const sps_real mu = sps__mix_friction(bi->def.friction, wl->friction);
    sps_real v[3] = {0, 0, 0}, v_t[3] = {0, 0, 0}, vn = 0, offset[3] = {0, 0, 0}, before[3] = {f[0], f[1], f[2]};
    int a;
    if (!(mu > 0)) return;
    for (a = 0; a < w->dim; ++a) v[a] = w->vel[a][i];
    if (bi->model.free_rigid) { /* at its surface facing the wall (chapter >>material: free rigid bodies) */
        sps__rigid_wall_contact_offset(w, wl->normal, sps__wall_distance(w, wl, i), offset);
        sps__rigid_contact_velocity(w, bi, offset, v);
    }
    for (a = 0; a < w->dim; ++a) vn += v[a] * wl->normal[a];
    for (a = 0; a < w->dim; ++a) v_t[a] = v[a] - vn * wl->normal[a];
    sps__add_friction(mu, f_n, bi->model.free_rigid ? sps__rigid_stick_drag(w, bi, i, dt) : w->rho[i] / (2 * dt), v_t, w->dim, f);
    if (bi->model.free_rigid) sps__rigid_friction_couple(w, i, offset, before, f);
}

/* Adds the dashpot force per volume of particle i to acc_p and its work in a sub-step dt, at
   the velocity it was evaluated with, to the body's dissipated work (field "viscous_work"). */
static void sps__add_dashpot_acceleration(sps_world* w, const sps__body* bi, int i, const sps_real dashpot[3], sps_real dt) {
    int a;
    for (a = 0; a < w->dim; ++a) w->acc_p[a][i] += w->vol[i] / w->mass[i] * dashpot[a];
    if (bi->viscous_work && i - bi->begin < bi->field_count)
        bi->viscous_work[i - bi->begin] -= dt * w->vol[i] * (dashpot[0] * w->vel[0][i] + dashpot[1] * w->vel[1][i] + dashpot[2] * w->vel[2][i]);
}

/* Adds the contact accelerations of particle i to acc_p (see the chapter's head). */
static void sps__contact_force(sps_world* w, int i, sps_real dt) {
    const sps__body* bi = &w->bodies[w->body[i]];
    const sps_real si = w->sigma[i], vi_mi = w->vol[i] / w->mass[i];
    sps_real f[3] = {0, 0, 0}, coupling[3] = {0, 0, 0}, dashpot[3] = {0, 0, 0};
    int k, a;
    if (w->contact_bodies)
        for (k = w->ct_first[i]; k < w->ct_first[i + 1]; ++k) {
            const int j = w->ct_j[k];
            const sps_real kij = sps__contact_stiffness(bi->mat.K, w->bodies[w->body[j]].mat.K);
            sps_real d[3] = {0, 0, 0}, r2 = 0, r, s, dw;
            if (sps__coupled_pair(w, i, j)) { /* a fluid-solid pair: the coupling's force instead */
                sps__coupling_force(w, i, j, coupling);
                continue;
            }
            r2 = sps__pair_offset(w, i, j, d);
            r = SPS__SQRT(r2);
            if (!(r > 0)) continue; /* coincident particles: no direction */
            dw = sps_world_kernel_derivative(w, r);
            s = -kij * (si + w->sigma[j]) * dw / r * w->vol[j];
            for (a = 0; a < w->dim; ++a) f[a] += s * d[a];
            if (w->pair_friction) sps__pair_friction(w, bi, i, j, d, r, dw, s * r, f);
            if (w->contact_damped) sps__pair_dashpot(w, bi, i, j, d, r, dw, s * r, dashpot);
        }
    for (k = 0; k < w->nwalls && !bi->model.mirrored; ++k) { /* fluids' and granular walls: sps__mirror_force */
        const sps__wall* wl = &w->walls[k];
        const sps_real d = sps__wall_distance(w, wl, i);
        sps_real plane, vn = 0;
        if (!(d < w->rest_wall_distance)) continue;
        plane = sps__plane_table_at(w, w->wall_plane, SPS__WALL_TABLE, d); /* at its peak for d <= 0 */
        for (a = 0; a < w->dim; ++a) f[a] += 2 * bi->mat.K * si * plane * wl->normal[a];
        if (wl->slip == SPS_WALL_NO_SLIP) {
            for (a = 0; a < w->dim; ++a) vn += w->vel[a][i] * wl->normal[a];
            for (a = 0; a < w->dim; ++a) f[a] -= 2 * bi->z_riemann * plane * (w->vel[a][i] - vn * wl->normal[a]);
        } else if (w->friction) {
            sps__wall_friction(w, bi, i, wl, 2 * bi->mat.K * si * plane, dt, f);
        }
        if (w->contact_damped && bi->def.contact_damping > 0) {
            for (vn = 0, a = 0; a < w->dim; ++a) vn += w->vel[a][i] * wl->normal[a];
            sps__add_contact_dashpot(2 * bi->def.contact_damping * bi->z_riemann * plane, vn, 2 * bi->mat.K * si * plane, wl->normal, w->dim,
                                     dashpot);
        }
    }
    for (a = 0; a < w->dim; ++a) w->acc_p[a][i] += vi_mi * f[a];
    if (w->contact_damped) sps__add_dashpot_acceleration(w, bi, i, dashpot, dt);
    if (bi->coupled)
        for (a = 0; a < w->dim; ++a) w->acc_p[a][i] += coupling[a] / w->mass[i];
}

/* The contact pass of a sub-step (after the pressure pass, before the kick): the contact
   densities of all particles, then their forces. Work-shared over the step's team. */
static void sps__contact_pass(sps_world* w, sps_real t, sps_real dt) {
    int i, bi;
    if (!w->contact_bodies && w->nwalls == 0) return;
    SPS__PRAGMA(omp for schedule(static))
    for (i = 0; i < w->n; ++i) w->sigma[i] = sps__contact_density(w, i);
    for (bi = 0; bi < w->nbodies && w->wall_equilibrium; ++bi)
        if (w->bodies[bi].wall_equilibrium) sps__run_near_walls(w, &w->bodies[bi], 1, sps__measure_wall_equilibrium, t);
    SPS__PRAGMA(omp for schedule(static))
    for (i = 0; i < w->n; ++i) sps__contact_force(w, i, dt);
    for (bi = 0; bi < w->nbodies && w->nwalls > 0; ++bi) /* the walls' images, after the contact forces */
        if (w->bodies[bi].model.mirrored) sps__run_near_walls(w, &w->bodies[bi], 0, sps__mirror_force, dt);
}

/* >>material: free rigid bodies (continued): motion

   Newton-Euler in the sub-step's drift-kick-drift (position Verlet, the order every particle
   follows; STEP BY STEP in the manual):
   1. half drift: x += dt/2 v, and the body turns freely for dt/2 at its angular momentum L; its
      particles are placed at that pose, with the velocities v + omega x r;
   2. the neighbour passes of the other bodies and the contact pass leave in acc_p the force each
      particle received (contact with bodies and walls with friction and damping, the fluid's
      coupling force), as for a wall body;
   3. kick: F = M g + sum_i m_i acc_p,i (plus external accelerations and the applied force),
      tau = sum_i r_i x m_i acc_p,i (r_i from the centre of mass at mid-step), v += dt F / M,
      L += dt tau; then x += dt/2 v and the second free turn of dt/2; the particles placed at
      the end pose, acc_p cleared.
   The free turn (torque-free rotation over h at fixed world L) is the implicit midpoint rule for
   Euler's equations in the principal frame, L_b' = cay(-h W) L_b, W the skew matrix of omega_m =
   I^-1 (L_b + L_b') / 2 (iterated to round-off), and the rotation turn' = turn cay(h W), the
   Cayley transform cay(A) = (1 - A/2)^-1 (1 + A/2), orthogonal exactly. The implicit midpoint
   rule keeps every quadratic invariant of an ODE, here |L_b|^2 and the energy 1/2 L_b . I^-1 L_b,
   and turn' L_b' = turn cay(h W) cay(-h W) L_b = turn L_b: the world angular momentum is not
   changed by the turn at all. It is energy-consistent and time-reversible (not the symplectic
   splitting about the principal axes, whose energy oscillates by O((omega dt)^2)). In 2D the turn
   is the exact rotation by h L_z / I_zz. Locked rotation axes: the body turns exactly about the
   omega of the free block of its world inertia, omega = 0 on the locked axes.
   The sums over a body's particles are serial, in particle order, by the team's master thread
   (a fixed order: bit-identical for any thread count), between two barriers, which only a scene
   with a free rigid body pays. */

static void sps__thread_share(const sps__body* b, int* i0, int* i1); /* >>step */

static void sps__rigid_cross(const sps_real a[3], const sps_real b[3], sps_real c[3]) {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
/* y = A x, or A^T x with transposed (3 x 3 row-major). */
static void sps__rigid_apply(const sps_real A[9], const sps_real x[3], int transposed, sps_real y[3]) {
    int a;
    for (a = 0; a < 3; ++a)
        y[a] = transposed ? A[a] * x[0] + A[3 + a] * x[1] + A[6 + a] * x[2] : A[3 * a] * x[0] + A[3 * a + 1] * x[1] + A[3 * a + 2] * x[2];
}
/* The rotation by the angle |theta| about theta (Rodrigues' formula, exact), row-major. */
static void sps__rigid_rotation(const sps_real theta[3], sps_real R[9]) {
    const sps_real angle = SPS__SQRT(theta[0] * theta[0] + theta[1] * theta[1] + theta[2] * theta[2]);
    const sps_real s = angle > 0 ? SPS__SIN(angle) / angle : 1, c = angle > 0 ? (1 - SPS__COS(angle)) / (angle * angle) : 0;
    const sps_real K[9] = {0, -theta[2], theta[1], theta[2], 0, -theta[0], -theta[1], theta[0], 0};
    sps_real K2[9];
    int k;
    sps__mat3_product(K, K, 0, K2);
    for (k = 0; k < 9; ++k) R[k] = (sps_real)(k % 4 == 0) + s * K[k] + c * K2[k];
}
/* Its inertia tensor about the centre of mass in world axes at rotation turn: turn diag(I) turn^T. */
static void sps__rigid_world_inertia(const sps__rigid* r, const sps_real turn[9], sps_real Iw[9]) {
    int a, c, k;
    for (a = 0; a < 3; ++a)
        for (c = 0; c < 3; ++c) {
            sps_real s = 0;
            for (k = 0; k < 3; ++k) s += turn[3 * a + k] * r->moment[k] * turn[3 * c + k];
            Iw[3 * a + c] = s;
        }
}

/* The angular velocity at rotation turn: I^-1 L, or with locked rotation axes the solution of
   the free block of the world inertia for the free components of L (0 on the locked axes). */
static void sps__rigid_omega(const sps_world* w, const sps__rigid* r, const sps_real turn[9], sps_real omega[3]) {
    sps_real Lb[3], Iw[9];
    int f[3], nfree = 0, a;
    omega[0] = omega[1] = omega[2] = 0;
    if (w->dim == 2) {
        if (!(r->lock_rotation & SPS_AXIS_Z)) omega[2] = r->L[2] / r->moment[2];
        return;
    }
    if (!r->lock_rotation) {
        sps__rigid_apply(turn, r->L, 1, Lb);
        for (a = 0; a < 3; ++a) Lb[a] /= r->moment[a];
        sps__rigid_apply(turn, Lb, 0, omega);
        return;
    }
    sps__rigid_world_inertia(r, turn, Iw);
    for (a = 0; a < 3; ++a)
        if (!(r->lock_rotation & (1u << a))) f[nfree++] = a;
    if (nfree == 1) omega[f[0]] = r->L[f[0]] / Iw[4 * f[0]];
    if (nfree == 2) { /* Cramer's rule; the block of a positive definite tensor is */
        const sps_real a00 = Iw[4 * f[0]], a01 = Iw[3 * f[0] + f[1]], a11 = Iw[4 * f[1]], det = a00 * a11 - a01 * a01;
        omega[f[0]] = (a11 * r->L[f[0]] - a01 * r->L[f[1]]) / det;
        omega[f[1]] = (a00 * r->L[f[1]] - a01 * r->L[f[0]]) / det;
    }
}

/* The rotation after turning freely over h at the body's angular momentum (the chapter's head). */
static void sps__rigid_free_turn(const sps_world* w, const sps__rigid* r, const sps_real turn[9], sps_real h, sps_real out[9]) {
    sps_real omega[3], theta[3], R[9], Lb[3], Lb1[3], s[3], s_x_L[3], s_s_L[3], S[9], S2[9], c = 0;
    int a, k, iteration;
    if (w->dim == 2 || r->lock_rotation) { /* a fixed axis: the exact rotation by omega h */
        sps__rigid_omega(w, r, turn, omega);
        for (a = 0; a < 3; ++a) theta[a] = h * omega[a];
        sps__rigid_rotation(theta, R);
        sps__mat3_product(R, turn, 0, out);
        return;
    }
    sps__rigid_apply(turn, r->L, 1, Lb);
    for (a = 0; a < 3; ++a) Lb1[a] = Lb[a];
    for (iteration = 0; iteration < 100; ++iteration) { /* contracts by about |omega| h per iteration */
        sps_real change = 0, size = 0;
        for (a = 0; a < 3; ++a) s[a] = SPS_R(0.25) * h * (Lb[a] + Lb1[a]) / r->moment[a]; /* h omega_m / 2 */
        c = 2 / (1 + s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        sps__rigid_cross(s, Lb, s_x_L);
        sps__rigid_cross(s, s_x_L, s_s_L);
        for (a = 0; a < 3; ++a) {
            const sps_real next = Lb[a] + c * (s_s_L[a] - s_x_L[a]); /* cay(-h W) L_b */
            change += (next - Lb1[a]) * (next - Lb1[a]);
            size += next * next;
            Lb1[a] = next;
        }
        if (!(change > SPS_R(1e-32) * size)) break;
    }
    for (a = 0; a < 3; ++a) s[a] = SPS_R(0.25) * h * (Lb[a] + Lb1[a]) / r->moment[a];
    c = 2 / (1 + s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    S[0] = S[4] = S[8] = 0;
    S[1] = -s[2]; S[2] = s[1]; S[3] = s[2]; S[5] = -s[0]; S[6] = -s[1]; S[7] = s[0];
    sps__mat3_product(S, S, 0, S2);
    for (k = 0; k < 9; ++k) R[k] = (sps_real)(k % 4 == 0) + c * (S[k] + S2[k]); /* cay(h W) */
    sps__mat3_product(turn, R, 0, out);
}

/* Places particles i0 .. i1-1 of body b at the pose (x, turn), with velocities v + omega x r for
   the body's v and L; clears their acc_p with clear. Returns the range's max |v - frame|^2 above
   vmax2 (sps__frame_speeds). */
static sps_real sps__rigid_place(sps_world* w, const sps__body* b, int i0, int i1, const sps_real x[3], const sps_real turn[9],
                                 sps_real vmax2, int clear) {
    const sps__rigid* r = &b->rigid;
    const sps_real* frame = b->frame_velocity;
    const int dim = w->dim;
    sps_real A[9], omega[3], u[3];
    int i, a;
    sps__mat3_product(turn, r->axes, 1, A); /* reference to current */
    sps__rigid_omega(w, r, turn, omega);
    for (a = 0; a < 3; ++a) u[a] = r->v[a] - frame[a]; /* the time step's speeds are relative to the frame */
    for (i = i0; i < i1; ++i) { /* x + A d and v + omega x A d, d = X_i - reference centre */
        const sps_real dx = w->ref[0][i] - r->reference_centre[0], dy = w->ref[1][i] - r->reference_centre[1];
        const sps_real dz = dim == 3 ? w->ref[2][i] - r->reference_centre[2] : 0;
        const sps_real rx = A[0] * dx + A[1] * dy + A[2] * dz, ry = A[3] * dx + A[4] * dy + A[5] * dz, rz = A[6] * dx + A[7] * dy + A[8] * dz;
        const sps_real wx = omega[1] * rz - omega[2] * ry, wy = omega[2] * rx - omega[0] * rz, wz = omega[0] * ry - omega[1] * rx;
        sps_real v2 = (u[0] + wx) * (u[0] + wx) + (u[1] + wy) * (u[1] + wy);
        w->pos[0][i] = x[0] + rx;
        w->pos[1][i] = x[1] + ry;
        w->vel[0][i] = r->v[0] + wx;
        w->vel[1][i] = r->v[1] + wy;
        if (dim == 3) {
            w->pos[2][i] = x[2] + rz;
            w->vel[2][i] = r->v[2] + wz;
            v2 += (u[2] + wz) * (u[2] + wz);
        }
        if (clear)
            for (a = 0; a < dim; ++a) w->acc_p[a][i] = w->acc_s[a][i] = 0;
        if (!(v2 <= vmax2)) vmax2 = v2 == v2 ? v2 : (sps_real)INFINITY;
    }
    return vmax2;
}

/* Step 1 for free rigid body b: the half drift of its pose, its particles placed there (each
   thread its share; every thread computes the same pose, the master keeps it for the kick). */
static void sps__rigid_half_drift(sps_world* w, sps__body* b, sps_real dt) {
    sps__rigid* r = &b->rigid;
    sps_real x[3], turn[9];
    int a, i0, i1;
    for (a = 0; a < 3; ++a) x[a] = r->x[a] + SPS_R(0.5) * dt * r->v[a];
    sps__rigid_free_turn(w, r, r->turn, SPS_R(0.5) * dt, turn);
    sps__thread_share(b, &i0, &i1);
    sps__rigid_place(w, b, i0, i1, x, turn, 0, 0);
    SPS__PRAGMA(omp master)
    {
        memcpy(r->mid_x, x, sizeof x);
        memcpy(r->mid_turn, turn, sizeof turn);
    }
}

/* Step 3 for free rigid body b (serial): the resultant force and torque about the centre of mass
   at mid-step, Newton-Euler over dt, the second half drift. The work of external accelerations
   and the applied force goes to the energy watchdog's account (driven_work). */
static void sps__rigid_newton_euler(sps_world* w, sps__body* b, sps_real t, sps_real dt) {
    sps__rigid* r = &b->rigid;
    /* damping c (DAMPING): dv/dt = F/M - c v and dL/dt = tau - c L integrated exactly over dt */
    const sps_real decay_minus_1 = b->def.damping > 0 ? SPS__EXPM1(-b->def.damping * dt) : 0;
    const sps_real decay = 1 + decay_minus_1, kick = b->def.damping > 0 ? -decay_minus_1 / b->def.damping : dt;
    sps_real F[3] = {0, 0, 0}, tau[3] = {0, 0, 0}, omega[3], p[3], f[3], torque[3];
    int i, a;
    r->contacts = 0;
    for (i = b->begin; i < b->end; ++i) {
        sps_real rr[3] = {0, 0, 0}, acc[3] = {0, 0, 0};
        for (a = 0; a < w->dim; ++a) {
            rr[a] = w->pos[a][i] - r->mid_x[a];
            acc[a] = w->acc_p[a][i];
        }
        r->contacts += acc[0] != 0 || acc[1] != 0 || acc[2] != 0;
        if (b->acceleration) { /* external acceleration (the drag): at the particle, at mid-step */
            sps_real x[3] = {0, 0, 0}, x0[3] = {0, 0, 0}, v[3] = {0, 0, 0}, ext[3] = {0, 0, 0}, power = 0;
            for (a = 0; a < w->dim; ++a) { x[a] = w->pos[a][i]; x0[a] = w->ref[a][i]; v[a] = w->vel[a][i]; }
            b->acceleration(x, x0, v, t + SPS_R(0.5) * dt, ext, b->acceleration_user);
            for (a = 0; a < w->dim; ++a) { acc[a] += ext[a]; power += ext[a] * v[a]; }
            if (b->driven_work) b->driven_work[i - b->begin] += w->mass[i] * power * dt;
        }
        for (a = 0; a < 3; ++a) f[a] = w->mass[i] * acc[a];
        sps__rigid_cross(rr, f, torque);
        if (w->dim == 2) torque[2] += w->mass[i] * w->acc_s[0][i]; /* friction's couples (sps__rigid_friction_couple) */
        else
            for (a = 0; a < 3; ++a) torque[a] += w->mass[i] * w->acc_s[a][i];
        for (a = 0; a < 3; ++a) { F[a] += f[a]; tau[a] += torque[a]; }
    }
    sps__rigid_apply(r->mid_turn, r->applied_point, 0, p); /* the applied force's material point */
    sps__rigid_cross(p, r->applied_force, torque);
    if (b->driven_work) { /* its power at the point's velocity */
        sps_real wp[3], power = 0;
        sps__rigid_omega(w, r, r->mid_turn, omega);
        sps__rigid_cross(omega, p, wp);
        for (a = 0; a < w->dim; ++a) power += r->applied_force[a] * (r->v[a] + wp[a]);
        b->driven_work[0] += power * dt;
    }
    for (a = 0; a < 3; ++a) {
        F[a] += r->applied_force[a] + (a < w->dim ? r->mass * w->def.gravity[a] : 0);
        tau[a] += torque[a];
        if (w->dim == 2 && a < 2) tau[a] = 0;
        r->force[a] = F[a]; /* what a lock holds is reported too */
        r->torque[a] = tau[a];
        if (r->lock_translation & (1u << a)) F[a] = r->v[a] = 0;
        r->v[a] = decay * r->v[a] + kick * F[a] / r->mass;
        r->L[a] = decay * r->L[a] + kick * tau[a];
        r->x[a] = r->mid_x[a] + SPS_R(0.5) * dt * r->v[a];
    }
    sps__rigid_free_turn(w, r, r->mid_turn, SPS_R(0.5) * dt, r->turn);
}

/* Step 3 for every free rigid body (after the other bodies' kick): the master integrates each
   body while the others wait (the sums read every particle's acc_p), then each thread places its
   share of the particles at the end pose. Returns the max |v - frame|^2 above vmax2. */
static sps_real sps__rigid_kick(sps_world* w, sps_real t, sps_real dt, sps_real vmax2) {
    int bi, i0, i1;
    SPS__PRAGMA(omp barrier) /* every received force is in acc_p */
    SPS__PRAGMA(omp master)
    for (bi = 0; bi < w->nbodies; ++bi)
        if (w->bodies[bi].model.free_rigid) sps__rigid_newton_euler(w, &w->bodies[bi], t, dt);
    SPS__PRAGMA(omp barrier)
    for (bi = 0; bi < w->nbodies; ++bi) {
        const sps__body* b = &w->bodies[bi];
        if (!b->model.free_rigid) continue;
        sps__thread_share(b, &i0, &i1);
        vmax2 = sps__rigid_place(w, b, i0, i1, b->rigid.x, b->rigid.turn, vmax2, 1);
    }
    return vmax2;
}

/* Its velocity and angular momentum from its particles' velocities (the rigid motion with their
   momentum and angular momentum: what sps_body_set_velocity and _set_rigid_motion gave them),
   about its current centre of mass; the particles are then placed on that motion. */
static void sps__rigid_take_velocities(sps_world* w, sps__body* b) {
    sps__rigid* r = &b->rigid;
    sps_real m = 0, mv[3] = {0, 0, 0}, Lp[3] = {0, 0, 0}, Ip[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, omega[3] = {0, 0, 0}, Iw[9];
    sps_real d[3], Q[9], y[3];
    int i, a, c;
    for (i = b->begin; i < b->end; ++i) {
        m += w->mass[i];
        for (a = 0; a < w->dim; ++a) mv[a] += w->mass[i] * w->vel[a][i];
    }
    for (a = 0; a < 3; ++a) r->v[a] = a < w->dim ? mv[a] / m : 0;
    for (i = b->begin; i < b->end; ++i) {
        sps_real rr[3] = {0, 0, 0}, v[3] = {0, 0, 0}, l[3];
        for (a = 0; a < w->dim; ++a) { rr[a] = w->pos[a][i] - r->x[a]; v[a] = w->vel[a][i] - r->v[a]; }
        sps__rigid_cross(rr, v, l);
        for (a = 0; a < 3; ++a) {
            Lp[a] += w->mass[i] * l[a];
            for (c = 0; c < 3; ++c) Ip[3 * a + c] += w->mass[i] * ((a == c) * (rr[0] * rr[0] + rr[1] * rr[1] + rr[2] * rr[2]) - rr[a] * rr[c]);
        }
    }
    if (w->dim == 2) {
        omega[2] = Ip[8] > 0 ? Lp[2] / Ip[8] : 0;
    } else { /* Ip omega = Lp on the particles' inertia (a line of particles: its axis left out) */
        sps__eigen3(Ip, d, Q);
        sps__rigid_apply(Q, Lp, 1, y);
        for (a = 0; a < 3; ++a) y[a] = d[a] > SPS_R(1e-12) * (d[0] + d[1] + d[2]) ? y[a] / d[a] : 0;
        sps__rigid_apply(Q, y, 0, omega);
    }
    sps__rigid_world_inertia(r, r->turn, Iw);
    sps__rigid_apply(Iw, omega, 0, r->L);
    if (w->dim == 2) r->L[0] = r->L[1] = 0;
    for (a = 0; a < 3; ++a)
        if (r->lock_translation & (1u << a)) r->v[a] = 0;
    sps__rigid_place(w, b, b->begin, b->end, r->x, r->turn, 0, 0); /* the watchdog's start moved with the velocities set */
}

/* Sets the principal moments and axes from an inertia tensor I about the centre of mass in the
   reference world axes, keeping the rotation since the reference configuration. */
static void sps__rigid_set_inertia(sps_world* w, sps__rigid* r, const sps_real I[9]) {
    sps_real R[9], d[3], Q[9];
    int a;
    sps__mat3_product(r->turn, r->axes, 1, R);
    if (w->dim == 2) {
        for (a = 0; a < 9; ++a) Q[a] = (sps_real)(a % 4 == 0);
        d[0] = d[1] = d[2] = I[8];
    } else {
        sps__eigen3(I, d, Q);
        if (Q[0] * (Q[4] * Q[8] - Q[5] * Q[7]) - Q[1] * (Q[3] * Q[8] - Q[5] * Q[6]) + Q[2] * (Q[3] * Q[7] - Q[4] * Q[6]) < 0)
            for (a = 0; a < 3; ++a) Q[3 * a + 2] = -Q[3 * a + 2]; /* a rotation, not a reflection */
    }
    memcpy(r->axes, Q, sizeof Q);
    memcpy(r->moment, d, sizeof d);
    sps__mat3_product(R, Q, 0, r->turn);
}

/* Body b's mass, centre and inertia from its particles (each particle a cell of its volume:
   m_i (|r_i|^2 1 - r_i r_i^T) plus the cell's own m_i V_i^(2/d) / 6 on the diagonal), its pose
   from their current positions (no rotation since they were added) and its motion from their
   velocities. At the first step (or when a call on it needs it), again after particles are added. */
static void sps__rigid_setup(sps_world* w, sps__body* b) {
    sps__rigid* r = &b->rigid;
    sps_real m = 0, I[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    int i, a, c;
    sps__centre_of_mass(w, b, w->ref, r->reference_centre);
    sps__centre_of_mass(w, b, w->pos, r->x);
    for (i = b->begin; i < b->end; ++i) {
        sps_real d[3] = {0, 0, 0}, d2 = 0;
        const sps_real cell = w->mass[i] * SPS__EXP(SPS__LOG(w->vol[i]) * 2 / w->dim) / 6;
        for (a = 0; a < w->dim; ++a) { d[a] = w->ref[a][i] - r->reference_centre[a]; d2 += d[a] * d[a]; }
        m += w->mass[i];
        for (a = 0; a < 3; ++a)
            for (c = 0; c < 3; ++c) I[3 * a + c] += w->mass[i] * ((a == c) * d2 - d[a] * d[c]) + (a == c) * cell;
    }
    if (!r->mass_set) { /* else kept (sps_body_set_mass_properties) */
        for (a = 0; a < 9; ++a) r->turn[a] = r->axes[a] = (sps_real)(a % 4 == 0);
        r->mass = m;
        sps__rigid_set_inertia(w, r, I);
    }
    memcpy(r->turn, r->axes, sizeof r->turn);
    memcpy(r->mid_x, r->x, sizeof r->x);
    memcpy(r->mid_turn, r->turn, sizeof r->turn);
    r->ready = 1;
    r->count = b->count;
    sps__rigid_take_velocities(w, b);
}

/* Every free rigid body whose particles changed since its setup (after a commit). */
static void sps__rigid_setup_bodies(sps_world* w) {
    int bi;
    for (bi = 0; bi < w->nbodies; ++bi)
        if (w->bodies[bi].model.free_rigid && (!w->bodies[bi].rigid.ready || w->bodies[bi].rigid.count != w->bodies[bi].count))
            sps__rigid_setup(w, &w->bodies[bi]);
}

/* Friction at the surface: a particle of a rigid body sits dp/2 or more inside its surface, and
   friction on the particle's velocity holds the body at that particle layer, so a disc rolls on a
   radius smaller than its own (on the particle layer R - dp/2: 2/3 g sin theta came out 3 % low
   at R/dp = 20). The contact point p is the body's surface facing the wall, dp/2 from the
   particle towards it (p = x_i - min(d, dp/2) n: not beyond the wall's plane), or the midpoint of
   a pair, p = x_i - (x_i - x_j) / 2 (both sides then take opposite offsets, so the pair's
   friction forces stay equal and opposite: linear momentum exact). Why the body's surface and not
   the wall's plane: the contact layer holds a body at rest some way above the plane (1.3 dp for a
   disc of E 1e6 on a slope), and a body rolling on the plane rolls on a radius that much larger
   than its own (0.8 dp: 2/3 g sin theta came out 2.6 % high at R/dp = 20). Its velocity as a
   point of the body, v_i + omega x (p - x_i), is the slip friction acts on, and the friction
   force acts at p: moved to the particle, it brings the couple (p - x_i) x F_t, which the kick
   adds to the body's torque (kept per mass in the particle's acc_s, unused by a rigid body;
   without it the rolling disc lost 2 % of its energy in 0.4 s, friction working on the particle
   layer's slip). */
static void sps__rigid_contact_velocity(const sps_world* w, const sps__body* b, const sps_real offset[3], sps_real v[3]) {
    sps_real omega[3], wo[3];
    int a;
    sps__rigid_omega(w, &b->rigid, b->rigid.mid_turn, omega);
    sps__rigid_cross(omega, offset, wo);
    for (a = 0; a < w->dim; ++a) v[a] += wo[a];
}
/* The offset p - x_i of the contact point of a particle at distance d from a wall (normal n). */
static void sps__rigid_wall_contact_offset(const sps_world* w, const sps_real normal[3], sps_real distance, sps_real offset[3]) {
    const sps_real depth = distance < SPS_R(0.5) * w->def.dp ? distance : SPS_R(0.5) * w->def.dp;
    int a;
    for (a = 0; a < 3; ++a) offset[a] = -depth * normal[a];
}
/* Adds the couple offset x (f - before) (a friction force per volume) per mass of particle i. */
static void sps__rigid_friction_couple(const sps_world* w, int i, const sps_real offset[3], const sps_real before[3], const sps_real f[3]) {
    const sps_real ft[3] = {f[0] - before[0], f[1] - before[1], f[2] - before[2]};
    sps_real couple[3];
    int a;
    sps__rigid_cross(offset, ft, couple);
    for (a = 0; a < 3; ++a) couple[a] *= w->vol[i] / w->mass[i];
    if (w->dim == 2) w->acc_s[0][i] += couple[2]; /* the z couple (acc_s has dim arrays) */
    else
        for (a = 0; a < 3; ++a) w->acc_s[a][i] += couple[a];
}

/* The stick drag per volume of particle i of free rigid body b at a wall in a sub-step dt: the
   particle's share of the body's effective mass at it, m_eff = 1 / (1/M + r^2 / I_min) (r its
   distance from the centre of mass, I_min the smallest principal moment), over the particles in
   contact in the last sub-step, over 2 dt: the contacts together halve the slip in a sub-step,
   as a deformable particle's drag rho_i / (2 dt) halves its own. That particle's drag alone
   would leave a rigid body, whose mass is not the contact layer's, creeping: a disc of 1264
   particles rolling on 30 degrees slipped 4 % of its speed. */
static sps_real sps__rigid_stick_drag(const sps_world* w, const sps__body* b, int i, sps_real dt) {
    const sps__rigid* r = &b->rigid;
    sps_real r2 = 0, I = r->moment[2];
    int a;
    for (a = 0; a < w->dim; ++a) r2 += (w->pos[a][i] - r->mid_x[a]) * (w->pos[a][i] - r->mid_x[a]);
    for (a = 0; a < 2 && w->dim == 3; ++a)
        if (r->moment[a] < I) I = r->moment[a];
    return 1 / (1 / r->mass + r2 / I) / ((r->contacts > 0 ? r->contacts : 1) * 2 * dt * w->vol[i]);
}

/* Its kinetic energy 1/2 M |v|^2 + 1/2 omega . I omega, gravity potential -M g . x, linear
   momentum M v and angular momentum about the origin M x X v + I omega: what its particles
   would carry as a continuum of their cells (DIAGNOSTICS reads these, not the particle sums). */
static void sps__rigid_energies(const sps_world* w, const sps__body* b, sps_real* kinetic, sps_real* potential, sps_real p[3],
                                sps_real l[3]) {
    const sps__rigid* r = &b->rigid;
    sps_real omega[3], Iw[9], Iomega[3], xv[3], v2 = 0;
    int a;
    sps__rigid_omega(w, r, r->turn, omega);
    sps__rigid_world_inertia(r, r->turn, Iw);
    sps__rigid_apply(Iw, omega, 0, Iomega);
    sps__rigid_cross(r->x, r->v, xv);
    *kinetic = *potential = 0;
    for (a = 0; a < 3; ++a) {
        v2 += r->v[a] * r->v[a];
        *kinetic += SPS_R(0.5) * omega[a] * Iomega[a];
        *potential -= a < w->dim ? r->mass * w->def.gravity[a] * r->x[a] : 0;
        p[a] = r->mass * r->v[a];
        l[a] = r->mass * xv[a] + Iomega[a];
    }
    *kinetic += SPS_R(0.5) * r->mass * v2;
}

/* The free rigid body of handle b, set up (sorting the world's particles as a first step would),
   or -1 with the error set in *result. */
static int sps__free_rigid_body(sps_world* w, sps_body b, const char* fn, sps_result* result) {
    int k = sps__check_body(w, b, fn);
    *result = SPS_ERR_INVALID_ARG;
    if (k < 0) return -1;
    if (!w->bodies[k].model.free_rigid) {
        sps__set_error(w, 0, "%s: body '%s' has material.kind = %d (%s), allowed %d (free rigid: SPS_MATERIAL_RIGID_DYNAMIC)", fn,
                       w->bodies[k].name, (int)w->bodies[k].def.material.kind, w->bodies[k].model.material->name, (int)sps__free_rigid_material.kind);
        return -1;
    }
    *result = SPS_ERR_STATE;
    if (w->bodies[k].count == 0) {
        sps__set_error(w, 0, "%s: body '%s' has no particles: fill it first (a rigid body's mass and inertia come from them)", fn,
                       w->bodies[k].name);
        return -1;
    }
    if ((*result = sps__ready_to_step(w)) != SPS_OK) return -1;
    sps__rigid_setup_bodies(w);
    return k;
}

/* Whether the n values of x are all finite (and x not NULL). */
static int sps__finite_values(const sps_real* x, int n) {
    int a;
    for (a = 0; x && a < n; ++a)
        if (!sps__finite(x[a])) return 0;
    return x != NULL;
}

SPSDEF sps_result sps_body_rigid_state(sps_world* w, sps_body b, sps_rigid_state* out) {
    sps_result res;
    const sps__rigid* r;
    int k, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (!out) { sps__set_error(w, 0, "sps_body_rigid_state: out must not be NULL"); return SPS_ERR_INVALID_ARG; }
    memset(out, 0, sizeof *out);
    if ((k = sps__free_rigid_body(w, b, "sps_body_rigid_state", &res)) < 0) return res;
    r = &w->bodies[k].rigid;
    sps__rigid_omega(w, r, r->turn, out->angular_velocity);
    sps__mat3_product(r->turn, r->axes, 1, out->rotation);
    sps__rigid_world_inertia(r, r->turn, out->inertia);
    if (w->dim == 2)
        for (a = 0; a < 8; ++a) out->inertia[a] = 0;
    for (a = 0; a < 3; ++a) {
        out->position[a] = r->x[a];
        out->velocity[a] = r->v[a];
        out->angular_momentum[a] = r->L[a];
        out->force[a] = r->force[a];
        out->torque[a] = r->torque[a];
    }
    out->mass = r->mass;
    return SPS_OK;
}

SPSDEF sps_result sps_body_set_rigid_pose(sps_world* w, sps_body b, const sps_real position[3], const sps_real rotation[9]) {
    sps_result res;
    sps__rigid* r;
    sps_real RtR[9], det = 1, error = 0;
    int k, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (!sps__finite_values(position, 3) || (rotation && !sps__finite_values(rotation, 9))) {
        sps__set_error(w, 0, "sps_body_set_rigid_pose: position %s, rotation %s: allowed finite values (rotation may be NULL)",
                       position ? "given" : "NULL", rotation ? "given" : "NULL");
        return SPS_ERR_INVALID_ARG;
    }
    if (rotation) {
        sps__mat3_product(rotation, rotation, 1, RtR);
        for (a = 0; a < 9; ++a) error += SPS__FABS(RtR[a] - (sps_real)(a % 4 == 0));
        det = rotation[0] * (rotation[4] * rotation[8] - rotation[5] * rotation[7]) - rotation[1] * (rotation[3] * rotation[8] - rotation[5] * rotation[6]) +
              rotation[2] * (rotation[3] * rotation[7] - rotation[4] * rotation[6]);
        if (w->dim == 2) error += SPS__FABS(rotation[2]) + SPS__FABS(rotation[5]) + SPS__FABS(rotation[6]) + SPS__FABS(rotation[7]);
        if (!(error < SPS_R(1e-6)) || !(SPS__FABS(det - 1) < SPS_R(1e-6))) {
            sps__set_error(w, 0, "sps_body_set_rigid_pose: rotation has |R R^T - 1| = %g and det = %g, allowed a rotation (orthonormal, det 1, "
                           "within 1e-6; in 2D about z only)", (double)error, (double)det);
            return SPS_ERR_INVALID_ARG;
        }
    }
    if ((k = sps__free_rigid_body(w, b, "sps_body_set_rigid_pose", &res)) < 0) return res;
    r = &w->bodies[k].rigid;
    for (a = 0; a < 3; ++a) r->x[a] = a < w->dim ? position[a] : 0;
    if (rotation) sps__mat3_product(rotation, r->axes, 0, r->turn);
    sps__rigid_place(w, &w->bodies[k], w->bodies[k].begin, w->bodies[k].end, r->x, r->turn, 0, 0);
    w->lists_valid = 0; /* the next step rebuilds the lists */
    sps__rearm_watchdog(w);
    return SPS_OK;
}

SPSDEF sps_result sps_body_set_mass_properties(sps_world* w, sps_body b, sps_real mass, const sps_real inertia[9]) {
    sps_result res;
    sps__rigid* r;
    sps_real I[9], d[3], Q[9], omega[3], Iw[9], scale;
    int k, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (!(mass > 0) || !sps__finite(mass)) {
        sps__set_error(w, 0, "sps_body_set_mass_properties: mass = %g, allowed finite > 0 kg", (double)mass);
        return SPS_ERR_INVALID_ARG;
    }
    if (inertia) {
        int symmetric = sps__finite_values(inertia, 9);
        if (w->dim == 3)
            symmetric = symmetric && inertia[1] == inertia[3] && inertia[2] == inertia[6] && inertia[5] == inertia[7];
        if (symmetric && w->dim == 3) sps__eigen3(inertia, d, Q);
        else d[0] = d[1] = d[2] = inertia[8];
        if (!symmetric || !(d[0] > 0 && d[1] > 0 && d[2] > 0) || (w->dim == 3 && !(d[0] + d[1] >= d[2] && d[1] + d[2] >= d[0] && d[0] + d[2] >= d[1]))) {
            sps__set_error(w, 0, "sps_body_set_mass_properties: inertia with principal moments (%g, %g, %g)%s, allowed a symmetric positive "
                           "definite tensor [kg m^2] (in 3D each moment at most the sum of the other two; in 2D inertia[8] > 0)",
                           (double)d[0], (double)d[1], (double)d[2], symmetric ? "" : " is not symmetric or not finite");
            return SPS_ERR_INVALID_ARG;
        }
    }
    if ((k = sps__free_rigid_body(w, b, "sps_body_set_mass_properties", &res)) < 0) return res;
    r = &w->bodies[k].rigid;
    sps__rigid_omega(w, r, r->turn, omega); /* kept */
    scale = mass / r->mass;
    if (inertia) memcpy(I, inertia, sizeof I);
    else { /* the current principal tensor in the reference axes, scaled */
        sps_real D[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, AD[9];
        for (a = 0; a < 3; ++a) D[4 * a] = scale * r->moment[a];
        sps__mat3_product(r->axes, D, 0, AD);
        sps__mat3_product(AD, r->axes, 1, I);
    }
    r->mass = mass;
    r->mass_set = 1;
    sps__rigid_set_inertia(w, r, I);
    sps__rigid_world_inertia(r, r->turn, Iw);
    sps__rigid_apply(Iw, omega, 0, r->L);
    sps__rearm_watchdog(w);
    return SPS_OK;
}

SPSDEF sps_result sps_body_apply_impulse(sps_world* w, sps_body b, const sps_real impulse[3], const sps_real point[3]) {
    sps_result res;
    sps__rigid* r;
    sps_real d[3] = {0, 0, 0}, J[3] = {0, 0, 0}, dL[3];
    int k, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (!sps__finite_values(impulse, 3) || (point && !sps__finite_values(point, 3))) {
        sps__set_error(w, 0, "sps_body_apply_impulse: impulse %s, point %s: allowed finite values (point may be NULL)", impulse ? "given" : "NULL",
                       point ? "given" : "NULL");
        return SPS_ERR_INVALID_ARG;
    }
    if ((k = sps__free_rigid_body(w, b, "sps_body_apply_impulse", &res)) < 0) return res;
    r = &w->bodies[k].rigid;
    for (a = 0; a < w->dim; ++a) {
        J[a] = r->lock_translation & (1u << a) ? 0 : impulse[a];
        d[a] = point ? point[a] - r->x[a] : 0;
        r->v[a] += J[a] / r->mass;
    }
    for (a = 0; a < w->dim; ++a) J[a] = impulse[a]; /* a locked axis takes the force, not its torque */
    sps__rigid_cross(d, J, dL);
    for (a = 0; a < 3; ++a) r->L[a] += w->dim == 2 && a < 2 ? 0 : dL[a];
    sps__rigid_place(w, &w->bodies[k], w->bodies[k].begin, w->bodies[k].end, r->x, r->turn, 0, 0);
    sps__rearm_watchdog(w);
    return SPS_OK;
}

SPSDEF sps_result sps_body_set_force(sps_world* w, sps_body b, const sps_real force[3], const sps_real point[3]) {
    sps_result res;
    sps__rigid* r;
    sps_real d[3] = {0, 0, 0};
    int k, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (!sps__finite_values(force, 3) || (point && !sps__finite_values(point, 3))) {
        sps__set_error(w, 0, "sps_body_set_force: force %s, point %s: allowed finite values (point may be NULL)", force ? "given" : "NULL",
                       point ? "given" : "NULL");
        return SPS_ERR_INVALID_ARG;
    }
    if ((k = sps__free_rigid_body(w, b, "sps_body_set_force", &res)) < 0) return res;
    r = &w->bodies[k].rigid;
    for (a = 0; a < 3; ++a) {
        r->applied_force[a] = a < w->dim ? force[a] : 0;
        d[a] = point && a < w->dim ? point[a] - r->x[a] : 0;
    }
    sps__rigid_apply(r->turn, d, 1, r->applied_point); /* in the principal axes: it turns with the body */
    if (sps__watchdog_on(w) && !w->bodies[k].driven) { /* its work enters the energy account */
        w->bodies[k].driven = 1;
        w->needs_sort_by_body = 1; /* the next step's commit allocates its prescribed_work */
    }
    return SPS_OK;
}

SPSDEF sps_result sps_body_lock_axes(sps_world* w, sps_body b, unsigned translation, unsigned rotation) {
    sps_result res;
    sps__rigid* r;
    int k, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (translation > SPS_AXIS_ALL || rotation > SPS_AXIS_ALL) {
        sps__set_error(w, 0, "sps_body_lock_axes: translation = %u, rotation = %u, allowed masks of SPS_AXIS_X|Y|Z (0..7)", translation, rotation);
        return SPS_ERR_INVALID_ARG;
    }
    if ((k = sps__free_rigid_body(w, b, "sps_body_lock_axes", &res)) < 0) return res;
    r = &w->bodies[k].rigid;
    r->lock_translation = translation;
    r->lock_rotation = w->dim == 2 ? rotation & SPS_AXIS_Z : rotation;
    for (a = 0; a < 3; ++a)
        if (translation & (1u << a)) r->v[a] = 0;
    sps__rigid_place(w, &w->bodies[k], w->bodies[k].begin, w->bodies[k].end, r->x, r->turn, 0, 0);
    sps__rearm_watchdog(w);
    return SPS_OK;
}

/* >>step: the per-particle updates of a sub-step */

/* The contiguous share [i0, i1) of body b that the calling thread updates in the per-particle
   steps (drift, kick, finish). All three use the same share, so between two barriers a thread
   touches only particles it updated itself. */
static void sps__thread_share(const sps__body* b, int* i0, int* i1) {
    const long count = b->end - b->begin;
    int nt, me;
    sps__team_rank(&nt, &me);
    *i0 = b->begin + (int)(count * me / nt);
    *i1 = b->begin + (int)(count * (me + 1) / nt);
}

/* Step 1 for particles i0 .. i1-1, dim a literal: half-step density, pressure (ENO eq. 4),
   volume and position. restrict and no branch, so the loop vectorises. */
SPS__INLINE void sps__drift_range(sps_world* w, int i0, int i1, sps_real h, sps_real c2, sps_real rho0, const int dim,
                                  const int pressure_of_density) {
    sps_real *SPS__RESTRICT rho = w->rho, *SPS__RESTRICT p = w->p, *SPS__RESTRICT vol = w->vol;
    sps_real *SPS__RESTRICT px = w->pos[0], *SPS__RESTRICT py = w->pos[1], *SPS__RESTRICT pz = w->pos[2];
    const sps_real *SPS__RESTRICT drho = w->drho, *SPS__RESTRICT mass = w->mass;
    const sps_real *SPS__RESTRICT vx = w->vel[0], *SPS__RESTRICT vy = w->vel[1], *SPS__RESTRICT vz = w->vel[2];
    int i;
    for (i = i0; i < i1; ++i) {
        if (pressure_of_density) { /* else the density follows the pressure (sps__finish) */
            rho[i] += h * drho[i];
            p[i] = c2 * (rho[i] - rho0);
        }
        vol[i] = mass[i] / rho[i];
        px[i] += h * vx[i];
        py[i] += h * vy[i];
        if (dim == 3) pz[i] += h * vz[i];
    }
}

/* Step 1: half-step density, pressure, volume and position (and OAS artificial stress). */
static void sps__half_drift(sps_world* w, sps_real dt) {
    int bi;
    for (bi = 0; bi < w->nbodies; ++bi) {
        const sps__body* b = &w->bodies[bi];
        const sps_real c2 = b->mat.c0 * b->mat.c0, rho0 = b->rho0, h = SPS_R(0.5) * dt;
        int i, i0, i1;
        if (b->model.free_rigid) { /* its pose drifts (>>material: free rigid bodies) */
            sps__rigid_half_drift(w, &w->bodies[bi], dt);
            continue;
        }
        sps__thread_share(b, &i0, &i1);
        if (!b->model.pressure_of_density) { /* Drucker-Prager: p comes from the stress update */
            if (w->dim == 2) sps__drift_range(w, i0, i1, h, c2, rho0, 2, 0);
            else sps__drift_range(w, i0, i1, h, c2, rho0, 3, 0);
        } else if (w->dim == 2) {
            sps__drift_range(w, i0, i1, h, c2, rho0, 2, 1);
        } else {
            sps__drift_range(w, i0, i1, h, c2, rho0, 3, 1);
        }
        if (b->model.artificial_stress) /* after its own particles' pressure */
            for (i = i0; i < i1; ++i) sps__artificial_stress(w, b, i);
    }
    SPS__PRAGMA(omp barrier) /* the pressure pass reads the neighbours' drifted state */
}

/* Step 3 for particles i0 .. i1-1 of body b, dim and damped literals (the loops unroll: measured
   14 ns a particle with a variable dim): velocity update with the -A variants' turned a_s (see
   sps__kick), constraints, second half drift of positions. Returns the range's max |v|^2, above
   vmax2 (NaN compares false: it is kept visible as infinity for the caller's check).
   A damped body (DAMPING) integrates dv/dt = a - c v exactly over the sub-step for the
   acceleration a of this kick: v = e^(-c dt) v + (1 - e^(-c dt))/c a, which is stable for any
   c dt (an explicit v -= c dt v grows for c dt > 2), and at rest under a balanced load it leaves
   v = 0 as an undamped kick does. It damps the absolute velocity, a particle's own: no sum over
   the body, and the mean velocity, which carries most of a cantilever's first mode, is damped
   too (DAMPING says why not the velocity relative to the mean). */
SPS__INLINE sps_real sps__kick_range(sps_world* w, const sps__body* b, int i0, int i1, sps_real dt, const sps_real Hmean[9],
                                     sps_real vmax2, const int dim, const int damped) {
    const int rotated = b->model.turn != SPS__TURN_NONE, per_particle = b->model.turn == SPS__TURN_PARTICLE;
    const sps_real *g = w->def.gravity, *frame = b->frame_velocity;
    const sps_real decay_minus_1 = damped ? SPS__EXPM1(-b->def.damping * dt) : 0; /* e^(-c dt) - 1, exact for small c dt */
    const sps_real decay = 1 + decay_minus_1, kick = damped ? -decay_minus_1 / b->def.damping : dt;
    sps_real Hp[9];
    int i, a, c;
    for (i = i0; i < i1; ++i) {
        sps_real v2 = 0, as[3] = {0, 0, 0};
        SPS__UNROLL
        for (a = 0; a < dim; ++a) as[a] = w->acc_s[a][i];
        if (rotated) {
            const sps_real* H = Hmean;
            if (per_particle) {
                sps__rodrigues(b->grad + (size_t)9 * (i - b->begin), SPS_R(0.5) * dt, dim, Hp);
                H = Hp;
            }
            SPS__UNROLL
            for (a = 0; a < dim; ++a) {
                as[a] = 0;
                SPS__UNROLL
                for (c = 0; c < dim; ++c) as[a] += H[3 * a + c] * w->acc_s[c][i];
            }
        }
        if (damped) {
            SPS__UNROLL
            for (a = 0; a < dim; ++a) w->vel[a][i] = decay * w->vel[a][i] + kick * (w->acc_p[a][i] + as[a] + g[a]);
        } else {
            SPS__UNROLL
            for (a = 0; a < dim; ++a) w->vel[a][i] += dt * (w->acc_p[a][i] + as[a] + g[a]);
        }
        if (w->cons && w->cons[i] >= 0) {
            const sps__constraint* cn = &w->constraints[w->cons[i]];
            sps_real work = 0; /* the constraint's force m (v_set - v_free)/dt times v_set, over dt */
            SPS__UNROLL
            for (a = 0; a < dim; ++a)
                if (cn->mask & (1u << a)) {
                    work += (cn->velocity[a] - w->vel[a][i]) * cn->velocity[a];
                    w->vel[a][i] = cn->velocity[a];
                }
            if (b->driven_work) b->driven_work[i - b->begin] += w->mass[i] * work;
        }
        if (w->zone && w->zone[i] >= 0) { /* an open boundary's buffer particle (>>open boundaries) */
            sps_real work = 0; /* the zone's force m (v_zone - v_free)/dt times v_zone, over dt: the inflow's work */
            SPS__UNROLL
            for (a = 0; a < dim; ++a) {
                work += (w->zone_vel[a][i] - w->vel[a][i]) * w->zone_vel[a][i];
                w->vel[a][i] = w->zone_vel[a][i];
            }
            if (b->driven_work) b->driven_work[i - b->begin] += w->mass[i] * work;
            if (w->zones[(int)w->zone[i]].def.kind == SPS_ZONE_OUTFLOW) w->rho[i] = w->zones[(int)w->zone[i]].rho_out;
        }
        SPS__UNROLL
        for (a = 0; a < dim; ++a) {
            w->pos[a][i] += SPS_R(0.5) * dt * w->vel[a][i];
            v2 += (w->vel[a][i] - frame[a]) * (w->vel[a][i] - frame[a]);
        }
        if (!(v2 <= vmax2)) vmax2 = v2 == v2 ? v2 : (sps_real)INFINITY;
    }
    return vmax2;
}

/* The kick of an elastic body's share, specialised per body (not per particle) for its
   dimension and whether it is damped: an undamped body runs the loop it ran before damping
   existed, bit for bit. */
static sps_real sps__kick_body(sps_world* w, const sps__body* b, int i0, int i1, sps_real dt, const sps_real Hmean[9], sps_real vmax2) {
    if (b->def.damping > 0)
        return w->dim == 2 ? sps__kick_range(w, b, i0, i1, dt, Hmean, vmax2, 2, 1) : sps__kick_range(w, b, i0, i1, dt, Hmean, vmax2, 3, 1);
    return w->dim == 2 ? sps__kick_range(w, b, i0, i1, dt, Hmean, vmax2, 2, 0) : sps__kick_range(w, b, i0, i1, dt, Hmean, vmax2, 3, 0);
}

/* The external acceleration of body b (sps_body_set_acceleration) for particles i0 .. i1-1,
   added to the neighbour passes' acceleration that the kick reads: evaluated where the kick
   acts, at the half-drifted position x and time t (the middle of the sub-step), with the
   velocity before the kick. */
static void sps__add_external_acceleration(sps_world* w, const sps__body* b, int i0, int i1, sps_real t, sps_real dt) {
    int i, a;
    for (i = i0; i < i1; ++i) {
        sps_real acc[3], power = 0;
        sps__external_acceleration_at(w, b, i, t, acc);
        for (a = 0; a < w->dim; ++a) {
            w->acc_p[a][i] += acc[a];
            power += acc[a] * w->vel[a][i];
        }
        if (b->driven_work) b->driven_work[i - b->begin] += w->mass[i] * power * dt; /* the energy watchdog's account */
    }
}

/* |v - frame velocity of its body|^2 of particle i: the speed the time steps see
   (sps__frame_speeds). The kick computes the same in its vectorised lane loop. */
static sps_real sps__frame_speed2(const sps_world* w, int i) {
    const sps_real* frame = w->bodies[w->body[i]].frame_velocity;
    sps_real v2 = 0;
    int a;
    for (a = 0; a < w->dim; ++a) v2 += (w->vel[a][i] - frame[a]) * (w->vel[a][i] - frame[a]);
    return v2;
}

/* Step 3 for the particles i0 .. i1-1 of a wall body: they keep their velocity (second half
   drift only). The contact pass left the force of the other bodies on each of them in acc_p:
   the opposite force, at the particle's velocity over dt, is the work the wall body does on
   them (driven); acc_p is then cleared for the next sub-step's contacts. Returns the range's
   max |v|^2 above vmax2. */
static sps_real sps__move_range(sps_world* w, const sps__body* b, int i0, int i1, sps_real dt, sps_real vmax2) {
    int i, a;
    for (i = i0; i < i1; ++i) {
        sps_real v2 = 0, power = 0;
        for (a = 0; a < w->dim; ++a) {
            power -= w->acc_p[a][i] * w->vel[a][i];
            w->acc_p[a][i] = 0;
        }
        if (b->driven_work) b->driven_work[i - b->begin] += w->mass[i] * power * dt;
        for (a = 0; a < w->dim; ++a) w->pos[a][i] += SPS_R(0.5) * dt * w->vel[a][i];
        v2 = sps__frame_speed2(w, i);
        if (!(v2 <= vmax2)) vmax2 = v2 == v2 ? v2 : (sps_real)INFINITY;
    }
    return vmax2;
}

/* Step 3: velocity update, constraints, second half drift of positions; returns the max over
   particles of |v - frame velocity of its body|^2 (sps__frame_speeds; the same value in every thread: per-thread maxima, then a barrier, then their max).
   For the -A variants the accumulated a_s is aligned with the body at the end of the last
   sub-step, while this kick acts half a step (dt/2 of this sub-step) later: it is applied
   rotated by that half step's rotation H, which removes a spurious torque of order
   omega^2 dt (spinning plate, ENO-A: 2.1 % -> 1.1 % angular-momentum error; bench/VALIDATION.md). */
static sps_real sps__kick(sps_world* w, sps_real t, sps_real dt) {
    sps_real vmax2 = 0;
    int thread, bi, nt, me;
    const int dim = w->dim;
    sps__team_rank(&nt, &me);
    for (bi = 0; bi < w->nbodies; ++bi) {
        const sps__body* b = &w->bodies[bi];
        sps_real Hmean[9];
        int i0, i1;
        sps__thread_share(b, &i0, &i1);
        sps__rodrigues(b->mean_spin, SPS_R(0.5) * dt, dim, Hmean); /* half of this kick's turn */
        if (b->model.free_rigid) continue; /* below, as one body */
        if (b->model.material->kinematic) {
            vmax2 = sps__move_range(w, b, i0, i1, dt, vmax2);
            continue;
        }
        if (b->acceleration) sps__add_external_acceleration(w, b, i0, i1, t + SPS_R(0.5) * dt, dt);
        vmax2 = sps__kick_body(w, b, i0, i1, dt, Hmean, vmax2);
    }
    if (w->free_rigid_bodies) vmax2 = sps__rigid_kick(w, t, dt, vmax2);
    w->thread_max[me] = vmax2;
    SPS__PRAGMA(omp barrier)
    for (thread = 0; thread < nt; ++thread)
        if (w->thread_max[thread] > vmax2) vmax2 = w->thread_max[thread];
    return vmax2;
}

/* Step 5: second half of the density update; mean rotation of the accumulated a_s (ENO-A).
   No barrier: the next pass that reads other particles' fields (the pressure pass) comes after
   the half drift's barrier, and each thread drifts the share it finishes here. */
static void sps__finish(sps_world* w, sps_real dt) {
    int bi;
    for (bi = 0; bi < w->nbodies; ++bi) {
        const sps__body* b = &w->bodies[bi];
        const int dim = w->dim, mean = b->model.turn == SPS__TURN_MEAN;
        const int increments = !b->model.penalty_in_pressure; /* else added in the next pressure pass */
        const sps_real* R = b->mean_rotation;
        int i, i0, i1;
        sps__thread_share(b, &i0, &i1);
        if (b->next_pressure) /* Drucker-Prager: the stress update's pressure, and the density of its
                                 elastic volume change (GRANULAR) */
            for (i = i0; i < i1; ++i) {
                w->p[i] = b->next_pressure[i - b->begin];
                w->rho[i] = b->rho0 + w->p[i] / (b->mat.c0 * b->mat.c0);
            }
        for (i = i0; i < i1; ++i) {
            int a, c;
            if (!b->next_pressure) w->rho[i] += SPS_R(0.5) * dt * w->drho[i];
            if (mean) { /* ANG eq. 42: a_s = mean(R) a_s + da */
                sps_real old[3];
                for (a = 0; a < dim; ++a) old[a] = w->acc_s[a][i];
                for (a = 0; a < dim; ++a) {
                    sps_real s = increments ? b->acc_d[a][i - b->begin] : 0;
                    for (c = 0; c < dim; ++c) s += R[3 * a + c] * old[c];
                    w->acc_s[a][i] = s;
                }
            }
        }
    }
}

/* >>guards: what stops a run that has gone wrong, and the last good state */

/* The first of particles [0, n) whose values in array x (components each) are not finite (or,
   positive, not > 0), with the value; n if none. Branch-free scan: a sound run never fails. */
static int sps__first_bad(const sps_real* x, int n, int components, int positive, sps_real* value) {
    const long total = (long)n * components;
    long k;
    for (k = 0; k < total; ++k)
        if (!sps__finite(x[k]) || (positive && !(x[k] > 0))) {
            *value = x[k];
            return (int)(k / components);
        }
    return n;
}

/* Names the first particle with a non-finite value in a field marked SPS__CHECKED (or a value
   <= 0 in one marked SPS__POSITIVE as well): velocity, position, shear acceleration, density,
   pressure, shear stress. Once per advection step: about one read of the state. */
static sps_result sps__check_finite(sps_world* w, const char* where) {
    int k, a, bi, first = w->n;
    const char* what = NULL;
    sps_real val = 0;
    for (bi = 0; bi < w->nbodies && !what; ++bi) { /* bodies in particle order: the first bad one */
        const sps__body* b = &w->bodies[bi];
        int local = b->end - b->begin;
        for (k = 0; k < SPS__NFIELDS; ++k) {
            const sps__field_info* f = &sps__fields[k];
            for (a = 0; (f->care & SPS__CHECKED) && a < (f->axes ? w->dim : 1); ++a) {
                const sps_real* x = sps__body_values(w, b, f, a);
                sps_real v = 0;
                const int i = x ? sps__first_bad(x, local, f->components, (f->care & SPS__POSITIVE) != 0, &v) : local;
                if (i < local) { local = i; what = f->what; val = v; first = b->begin + i; }
            }
        }
    }
    if (what) {
        sps__set_error(w, 0, "unstable at t = %g (%s): particle %d of body '%s' has %s %g; "
                       "the time step or the material is out of range for this scene",
                       (double)w->time, where, w->id[first], w->bodies[w->body[first]].name, what, (double)val);
        return SPS_ERR_UNSTABLE;
    }
    return SPS_OK;
}

/* Names the first particle farther than its body's escape limit from the body's current centre
   of mass: a body that travels or turns, however far, keeps its particles; a particle flung ten
   body sizes away from its body has escaped (a blow-up, or with a debris cloud an escape
   distance the scene should set). */
static sps_result sps__check_escape(sps_world* w) {
    int bi, i, a;
    for (bi = 0; bi < w->nbodies; ++bi) {
        const sps__body* b = &w->bodies[bi];
        const sps_real limit2 = b->escape_limit * b->escape_limit;
        sps_real c[3];
        if (!(limit2 < (sps_real)INFINITY)) continue;
        sps__centre_of_mass(w, b, w->pos, c);
        for (i = b->begin; i < b->end; ++i) {
            sps_real d2 = 0;
            for (a = 0; a < w->dim; ++a) /* along a periodic axis nothing escapes (and a body across it has no centre there) */
                if (!(w->period[a] > 0)) d2 += (w->pos[a][i] - c[a]) * (w->pos[a][i] - c[a]);
            if (!(d2 > limit2)) continue;
            sps__set_error(w, 0, "unstable at t = %g: particle %d of body '%s' escaped to (%g, %g, %g), %g m from the body's centre "
                           "of mass (%g, %g, %g), beyond its size (%g m from the centre) plus escape_distance (%g m)", (double)w->time,
                           w->id[i], b->name, (double)w->pos[0][i], (double)w->pos[1][i], w->dim == 3 ? (double)w->pos[2][i] : 0.0,
                           (double)SPS__SQRT(d2), (double)c[0], (double)c[1], (double)c[2], (double)b->reach,
                           (double)(b->escape_limit - b->reach));
            return SPS_ERR_UNSTABLE;
        }
    }
    return SPS_OK;
}

/* report_fragments: a warning, once per body, when one of its particles has no neighbour left
   within the support 2h: it has broken off (a fragment of one particle; a larger piece keeps
   neighbours and is not reported). Wall bodies keep no neighbour lists and are skipped. */
static void sps__report_fragments(sps_world* w) {
    int bi, i;
    for (bi = 0; bi < w->nbodies && w->def.report_fragments; ++bi) {
        sps__body* b = &w->bodies[bi];
        if (b->fragment_reported || b->model.material->kinematic) continue;
        for (i = b->begin; i < b->end; ++i)
            if (w->nb_count[i] == 0) {
                sps__warn(w, "t = %g: particle %d of body '%s' broke off its body (no neighbour within 2h = %g m) at (%g, %g, %g); "
                          "further fragments of this body are not reported", (double)w->time, w->id[i], b->name, (double)w->support,
                          (double)w->pos[0][i], (double)w->pos[1][i], w->dim == 3 ? (double)w->pos[2][i] : 0.0);
                b->fragment_reported = 1;
                break;
            }
    }
}

/* The acoustic step dt = CFL_ac h / (c0 + v) (v: the time-step speed, sps__frame_speeds) falls
   below 1e-3 of its value at rest (CFL_ac h / c0) only when a particle moves at more than
   999 c0 relative to its body, or two bodies approach that fast: the run has blown up, and going
   on would take ever more steps for nothing. Names the fastest particle in its body's frame. */
static sps_result sps__check_time_step(sps_world* w) {
    const sps_real dt_rest = w->def.cfl_acoustic * w->h / w->c0_max, dt = w->def.cfl_acoustic * w->h / (w->c0_max + w->vmax);
    sps_real v2max = -1;
    int i, fastest = 0;
    if (dt >= SPS__DT_COLLAPSE * dt_rest) return SPS_OK;
    for (i = 0; i < w->n; ++i) {
        const sps_real v2 = sps__frame_speed2(w, i);
        if (v2 > v2max) { v2max = v2; fastest = i; }
    }
    sps__set_error(w, 0, "unstable at t = %g: the acoustic time step collapsed to dt = %g s, below %g of its value at rest (%g s): "
                   "particle %d of body '%s' moves at %g m/s relative to its body (bodies approach each other or the walls at "
                   "%g m/s), %.0f times the sound speed c0 = %g m/s",
                   (double)w->time, (double)dt, SPS__DT_COLLAPSE, (double)dt_rest, w->id[fastest], w->bodies[w->body[fastest]].name,
                   (double)SPS__SQRT(v2max), (double)w->approach, (double)(w->vmax / w->c0_max), (double)w->c0_max);
    return SPS_ERR_UNSTABLE;
}

/* A body without particles is almost always a mistake (a box narrower than dp holds none):
   said before the first step instead of simulated silently. It also keeps the body count
   below the particle count, which the sort by body relies on (cell_start has 4 cap slots). */
static sps_result sps__check_bodies_filled(sps_world* w) {
    int k;
    if (w->n == 0) { sps__set_error(w, 0, "the world has no particles (add a body and fill it before stepping)"); return SPS_ERR_STATE; }
    for (k = 0; k < w->nbodies; ++k)
        if (w->bodies[k].count == 0) {
            sps__set_error(w, 0, "body '%s' (index %d) has no particles: fill it before stepping (a box narrower than dp holds none)",
                           w->bodies[k].name, k);
            return SPS_ERR_STATE;
        }
    if (!(w->c0_max > 0)) { /* the time step comes from the deformable bodies' sound speeds */
        sps__set_error(w, 0, "the world has only rigid bodies (material.kind = SPS_MATERIAL_RIGID): add a deformable body to simulate");
        return SPS_ERR_STATE;
    }
    return SPS_OK;
}

/* Reals per particle in the last good state: the components of the fields marked SPS__GOOD
   (16: position 3, velocity 3, density, pressure, shear stress 6, plastic strain and work). */
static size_t sps__good_reals(void) {
    size_t total = 0;
    int k;
    for (k = 0; k < SPS__NFIELDS; ++k)
        if (sps__fields[k].care & SPS__GOOD) total += (size_t)sps__field_arrays(&sps__fields[k]) * (size_t)sps__fields[k].components;
    return total;
}

/* keep_last_good_state: room for the copy, allocated with the other step fields. */
static sps_result sps__ensure_good_state(sps_world* w) {
    if (!w->def.keep_last_good_state || w->good_cap >= w->cap) return SPS_OK;
    sps__free(w, w->good); sps__free(w, w->good_id);
    w->good_cap = w->good_n = 0;
    w->good = (sps_real*)sps__alloc(w, sizeof(sps_real) * sps__good_reals() * (size_t)w->cap);
    w->good_id = (int*)sps__alloc(w, sizeof(int) * (size_t)w->cap);
    if (!w->good || !w->good_id) return sps__oom(w, "the last good state");
    w->good_cap = w->cap;
    return SPS_OK;
}

/* keep_last_good_state: copies the fields marked SPS__GOOD (plain copies, in the current
   particle order, remembered in good_id): field after field, each array good_cap values per
   component, one array per axis, the bodies' own arrays side by side in particle order. */
static void sps__save_good_state(sps_world* w) {
    const size_t n = (size_t)w->n, c = (size_t)w->good_cap;
    size_t base = 0;
    int k, a, bi;
    if (!w->good || w->good_cap < w->n) return;
    for (k = 0; k < SPS__NFIELDS; ++k) {
        const sps__field_info* f = &sps__fields[k];
        if (!(f->care & SPS__GOOD)) continue;
        for (a = 0; a < sps__field_arrays(f); ++a, base += (size_t)f->components)
            for (bi = 0; bi < w->nbodies && !(f->axes && a >= w->dim); ++bi) { /* a body without the field: zeros */
                const sps__body* b = &w->bodies[bi];
                const sps_real* x = sps__body_values(w, b, f, a);
                sps_real* to = w->good + base * c + (size_t)b->begin * (size_t)f->components;
                if (x) memcpy(to, x, sps__field_bytes(f) * (size_t)(b->end - b->begin));
                else memset(to, 0, sps__field_bytes(f) * (size_t)(b->end - b->begin));
            }
    }
    memcpy(w->good_id, w->id, sizeof(int) * n);
    for (bi = 0; bi < w->nbodies; ++bi) /* a free rigid body's motion goes back with its particles */
        if (w->bodies[bi].model.free_rigid) w->bodies[bi].rigid_good = w->bodies[bi].rigid;
    w->good_n = w->n;
    w->good_time = w->time;
}

/* ---- the energy watchdog ----
   A run can go wrong and stay finite: past its stable time step or formulation the energy grows
   while every guard above stays quiet. The account E = kinetic + strain + contact + gravity
   potential + plastic work - work of the prescribed motions is conserved by the continuous
   equations (the Riemann dissipation and no-slip walls only take energy away), so its growth
   above its start is numerical. The shear strain energy is left out (sps__body_energies): the
   account is a lower bound, judged by its kinetic energy. Checked at the configuration
   updates, at most every 10 acoustic sub-steps (one serial O(N) sum, ~1 % of a sub-step's cost
   spread over 10). */

/* Kinetic and strain energy of particle i of body b [J] (J/m in 2D; DIAGNOSTICS), the shear
   part from the tracked stress only if with_shear. */
static void sps__particle_energies(const sps_world* w, const sps__body* b, int i, int with_shear, sps_real* kinetic, sps_real* strain) {
    sps_real tt = 0;
    if (with_shear && b->model.stress && i - b->begin < b->field_count) { /* particles added since the last commit have no stress yet */
        const sps_real* t = b->tau + (size_t)6 * (i - b->begin);
        tt = t[0] * t[0] + t[3] * t[3] + t[5] * t[5] + 2 * (t[1] * t[1] + t[2] * t[2] + t[4] * t[4]);
    }
    *kinetic = sps__kinetic(w, i);
    *strain = b->model.total_lagrangian ? sps__tl_energy(w, b, i) /* the whole hyperelastic energy, exact under rotation */
                                        : w->mass[i] / w->rho[i] * sps__material_energy_density(b->def.material.kind, &b->mat, tt, w->p[i]);
}

/* The energies of body b [J]: kinetic + volumetric strain, contact, gravity potential
   -sum m g.x, the work its plastic flow dissipated (J2), and the work its prescribed motion
   has done (serial sums: a fixed order). The shear strain energy tau:tau/(4G) is left out: with the Jaumann rate it is not conserved under
   large rotations (3D cantilever at tip speed 0.05 c0: it reads 5 % (GNO-A) to 24 % (ENO) above
   the start at the largest bending, while the peaks of the kinetic energy stay below it), so the
   account is a lower bound of the energy, judged by its kinetic part. */
typedef struct { sps_real motion, contact, potential, plastic, work; } sps__energies;
static sps__energies sps__body_energies(const sps_world* w, const sps__body* b) {
    const sps_real* g = w->def.gravity;
    const int contacts = w->contact_bodies || w->nwalls > 0;
    sps__energies e = {0, 0, 0, 0, 0};
    int i, a;
    for (i = b->begin; i < b->end; ++i) {
        sps_real kinetic, strain;
        sps__particle_energies(w, b, i, 0, &kinetic, &strain);
        e.motion += kinetic + strain;
        if (contacts) e.contact += sps__contact_energy(w, i);
        for (a = 0; a < w->dim; ++a) e.potential -= w->mass[i] * g[a] * w->pos[a][i];
    }
    if (b->model.free_rigid) { /* its motion is the body's, not its particles' */
        sps_real p[3], l[3];
        sps__rigid_energies(w, b, &e.motion, &e.potential, p, l);
    }
    for (i = 0; b->driven_work && i < b->end - b->begin; ++i) e.work += b->driven_work[i];
    for (i = 0; b->plastic_work && i < b->end - b->begin && i < b->field_count; ++i) e.plastic += b->plastic_work[i];
    for (i = 0; b->viscous_work && i < b->end - b->begin && i < b->field_count; ++i) e.plastic += b->viscous_work[i]; /* dissipated too */
    return e;
}

/* Body b's share of the account (below) and its mechanical energy: kinetic + strain + contact;
   a wall body moves as prescribed, so its own kinetic and potential energy are not the
   simulation's, but its side of the contacts and its work on the others are. */
static void sps__body_account(const sps_world* w, const sps__body* b, sps_real* account, sps_real* mechanical) {
    const sps__energies e = sps__body_energies(w, b);
    const int prescribed = b->model.material->kinematic && !b->model.free_rigid;
    *mechanical = prescribed ? e.contact : e.motion + e.contact;
    *account = *mechanical + (prescribed ? 0 : e.potential) + e.plastic - e.work;
}

/* The world's account E (kinetic + strain + contact + gravity potential + plastic work - work
   of the prescribed motions) and its mechanical energy. */
static void sps__energy_account(const sps_world* w, sps_real* account, sps_real* mechanical) {
    int bi;
    *account = *mechanical = 0;
    for (bi = 0; bi < w->nbodies; ++bi) {
        sps_real a, m;
        sps__body_account(w, &w->bodies[bi], &a, &m);
        *account += a;
        *mechanical += m;
    }
}

/* Particles of body bi on the solid side of wall k ((x - point) . normal < 0). */
static int sps__particles_behind_wall(const sps_world* w, int bi, int k) {
    const sps__wall* wall = &w->walls[k];
    int i, a, count = 0;
    for (i = 0; i < w->n; ++i) {
        sps_real depth = 0;
        if (w->body[i] != bi) continue;
        for (a = 0; a < w->dim; ++a) depth += (w->pos[a][i] - wall->point[a]) * wall->normal[a];
        count += depth < 0;
    }
    return count;
}

/* The watchdog's diagnosis, most likely first: what in body b's model or the world's settings
   is known to gain energy (the stability map and the user scenes of bench/VALIDATION.md), and
   the setting that fixes it. */
/* Water at rest fewer particles deep than this can gain potential energy (bench/VALIDATION.md,
   "Shallow water": a 2D tank 0.32 m deep with c0 = 10 sqrt(2 g H), 8, 10, 12 particles deep,
   +37, +14, +2.3 % of its compression energy in 1 s at h = 1.3 dp, the same at half the CFL
   number; 14, 16 and 32 deep lose energy; with c0 = 10 sqrt(g H) 8 deep gains, 12 deep loses). */
#define SPS__FLUID_SHALLOW_ROWS 14
/* The spread of body b's particles' heights along gravity [m] (0 for none). */
static sps_real sps__height_spread(const sps_world* w, const sps__body* b) {
    const sps_real* g = w->def.gravity;
    const sps_real g_norm = SPS__SQRT(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    sps_real lo = (sps_real)INFINITY, hi = -(sps_real)INFINITY;
    int i, a;
    for (i = b->begin; i < b->end; ++i) {
        sps_real up = 0;
        for (a = 0; a < w->dim; ++a) up -= g[a] / g_norm * w->pos[a][i];
        if (up < lo) lo = up;
        if (up > hi) hi = up;
    }
    return b->end > b->begin ? hi - lo : 0;
}
/* The depth of fluid body b along gravity [m]: its particles' heights' spread plus dp. */
static sps_real sps__fluid_depth(const sps_world* w, const sps__body* b) { return sps__height_spread(w, b) + w->def.dp; }

static void sps__growth_causes(const sps_world* w, const sps__body* b, char* out, size_t size) {
    const sps__stabilisation* st = b->model.stabilisation;
    const sps_real stable = st->stable_cfl[w->dim - 2];
    const int uses_shear = !sps__kind_stabilisation(&b->def); /* the def's shear is used */
    const sps_real rows = sps__fluid_depth(w, b) / w->def.dp; /* its depth in particles (read for a fluid) */
    int causes = 0, k, behind = 0;
    out[0] = 0;
    if (st->eno && b->model.turn != SPS__TURN_NONE) /* ENO-A: the pair rotation (SPS_ROTATION_AUTO) holds */
        sps__rule(out, size, &causes, "its rotation = %s, which gains energy when an ENO-A body spins, tumbles or hits something: set "
                  "rotation = SPS_ROTATION_PAIR (or SPS_ROTATION_AUTO, the default)", b->model.turn == SPS__TURN_MEAN ? "mean" : "per particle");
    if (st->penalty && st->rotated && b->model.turn != SPS__TURN_MEAN) /* GNO-A: the mean rotation (SPS_ROTATION_AUTO) holds */
        sps__rule(out, size, &causes, "its rotation = %s, which gains energy when a GNO-A body spins fast: set rotation = "
                  "SPS_ROTATION_MEAN (or SPS_ROTATION_AUTO, the default)", b->model.paired ? "pair" : "per particle");
    if (stable > 0 && w->def.cfl_acoustic > stable)
        sps__rule(out, size, &causes, "cfl_acoustic = %g is above %g, the largest measured stable for %s in %dD: lower it",
                  (double)w->def.cfl_acoustic, (double)stable, st->name, w->dim);
    if (!st->eno && !st->penalty && !b->model.material->kinematic && b->model.material->shear && b->model.plastic == SPS__YIELD_NONE)
        sps__rule(out, size, &causes, "shear = %s resists no hourglass mode: use ENO-A or GNO-A", st->name);
    if (!b->model.material->shear && !b->model.material->kinematic && sps__has_gravity(w) &&
        rows < SPS__FLUID_SHALLOW_ROWS) /* a fluid: no shear stress */
        sps__rule(out, size, &causes, "it is %.0f particles deep: water at rest fewer than %d particles deep can gain potential energy "
                  "as its rows under the free surface close up towards it, whatever the time step; fill it with a smaller dp "
                  "(bench/VALIDATION.md, \"Shallow water\")", (double)rows, SPS__FLUID_SHALLOW_ROWS);
    for (k = 0; k < w->nwalls; ++k) behind += sps__particles_behind_wall(w, (int)(b - w->bodies), k);
    if (behind > 0)
        sps__rule(out, size, &causes, "%d of its particles are on the solid side of a wall: check that each wall's normal points into "
                  "the free side", behind);
    if (causes == 0)
        sps__rule(out, size, &causes, "the time step%s beyond its stable range for this scene: halve cfl_acoustic (now %g)%s "
                  "(bench/VALIDATION.md, stability map)", uses_shear ? " or the shear formulation" : "", (double)w->def.cfl_acoustic,
                  uses_shear ? " or try shear = GNO-A" : "");
}

/* Takes the start of the account (after a user's change: sps__rearm_watchdog) or compares with
   it: a growth above energy_growth_limit times the largest mechanical energy seen is reported
   once (log level 1), naming the body whose account grew most, or stops the run
   (energy_growth_stops). */
/* A fluid at rest that churns: its kinetic energy grows without anything driving it, while it
   stays far below what its weight could give (a dam break's or a splash's grows as fast, but
   from its potential energy, to a good fraction of m g H within the first quarter second). The
   account of sps__watch_energy cannot see it: the churn's energy comes from the water settling
   (its potential energy falls more than its kinetic energy rises). Watched per fluid body under
   gravity at the watchdog's checks: the largest kinetic energy of each quarter second of
   simulated time (windows end with an advection step); SPS__CHURN_WINDOWS windows in a row each
   SPS__CHURN_RISE times the one before, ending between SPS__CHURN_FLOOR (the round-off of water
   at rest) and SPS__CHURN_SMALL of m |g| H (H its height at the first check): warn once with the
   likely causes. Measured (2D tank at rest, h = 1.3 dp, depth/dp 15): the kinetic energy rose
   31-, 300- and 13-fold in three windows (0.3 s each: a window ends with the advection step
   that passes its quarter second), to 8e-5 m g H; a dam break's kinetic energy
   passes 1e-3 m g H within its first window. */
#define SPS__CHURN_WINDOW SPS_R(0.25)
#define SPS__CHURN_WINDOWS 3
#define SPS__CHURN_RISE SPS_R(2)
#define SPS__CHURN_FLOOR SPS_R(1e-7)
#define SPS__CHURN_SMALL SPS_R(1e-3)
static void sps__watch_churn(sps_world* w, sps__body* b) {
    sps__churn* c = &b->churn;
    const sps_real* g = w->def.gravity;
    const sps_real g_norm = SPS__SQRT(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    sps_real kinetic = 0;
    int i;
    for (i = b->begin; i < b->end; ++i) kinetic += sps__kinetic(w, i);
    if (c->weight_height == 0) { /* the first check: the scale and the first window */
        const sps_real spread = sps__height_spread(w, b);
        sps_real mass = 0;
        for (i = b->begin; i < b->end; ++i) mass += w->mass[i];
        c->weight_height = mass * g_norm * (spread > 0 ? spread : w->def.dp);
        c->window_end = w->time + SPS__CHURN_WINDOW;
    }
    if (kinetic > c->window_max) c->window_max = kinetic;
    if (w->time < c->window_end) return;
    c->rises = c->window_max > SPS__CHURN_RISE * c->previous_max && c->previous_max > 0 ? c->rises + 1 : 0;
    c->previous_max = c->window_max;
    c->window_max = 0;
    c->window_end = w->time + SPS__CHURN_WINDOW;
    if (c->rises < SPS__CHURN_WINDOWS || c->warned || !(c->previous_max < SPS__CHURN_SMALL * c->weight_height) ||
        !(c->previous_max > SPS__CHURN_FLOOR * c->weight_height))
        return;
    c->warned = 1;
    sps__warn(w, "body '%s' churns at t = %g: its kinetic energy rose in %d windows of a quarter second in a row, each at least %g-fold, to %g J (%.2g of its "
              "weight times its height), with nothing driving it; likely cause: %s", b->name, (double)w->time, c->rises,
              (double)SPS__CHURN_RISE, (double)c->previous_max, (double)(c->previous_max / c->weight_height),
              !b->hexagonal && w->def.h_over_dp < SPS__FLUID_STILL_H_OVER_DP - SPS_R(1e-6)
                  ? "the square lattice at h_over_dp below 2, whose rows slide: in 2D fill it on the hexagonal lattice at h_over_dp = 1.3 "
                    "(lattice = SPS_LATTICE_AUTO), or set the world's h_over_dp = 2 (bench/VALIDATION.md, \"Water left running\")"
                  : "a slot at a wall, a corner of walls not at right angles, water filled from boxes whose hexagonal rows do not meet, or the "
                    "free surface's density diffusion (a square-lattice tank at h_over_dp = 2 bursts after 8-14 s: bench/VALIDATION.md, "
                    "\"Still water\")");
}

/* The round-off of the energy account: (100 eps)^2 sum m c0^2, the energy of velocities of 100
   units of round-off of the sound speeds. A scene that starts at rest has a largest mechanical
   energy of round-off too, and without the floor its first growth reads as 100 % of it (Turek
   and Hron's channel, a ramped inflow from rest: 4e-29 J at t = 0.008 s). */
#ifdef SPHSOLID_FLOAT
#define SPS__ROUND_OFF SPS_R(1.1920929e-7)
#else
#define SPS__ROUND_OFF SPS_R(2.220446049250313e-16)
#endif
static sps_real sps__energy_round_off(const sps_world* w) {
    sps_real sum = 0;
    int i;
    for (i = 0; i < w->n; ++i) {
        const sps_real c0 = w->bodies[w->body[i]].mat.c0;
        sum += w->mass[i] * c0 * c0;
    }
    return 100 * SPS__ROUND_OFF * 100 * SPS__ROUND_OFF * sum;
}

static sps_result sps__watch_energy(sps_world* w) {
    char msg[768];
    sps_real account, mechanical, growth, gain = 0;
    int bi, most = 0;
    if (!sps__watchdog_on(w) || (w->watch.armed && w->acoustic_steps - w->watch.checked_at < 10)) return SPS_OK;
    w->watch.checked_at = w->acoustic_steps;
    for (bi = 0; bi < w->nbodies && sps__has_gravity(w); ++bi)
        if (!w->bodies[bi].model.material->shear && !w->bodies[bi].model.material->kinematic) /* a fluid: no shear stress */
            sps__watch_churn(w, &w->bodies[bi]);
    sps__energy_account(w, &account, &mechanical);
    if (!w->watch.armed) {
        w->watch.armed = 1;
        w->watch.start = account;
        w->watch.scale = mechanical;
        w->watch.start_time = w->time;
        for (bi = 0; bi < w->nbodies; ++bi) {
            sps_real share;
            sps__body_account(w, &w->bodies[bi], &w->bodies[bi].energy_start, &share);
        }
        return SPS_OK;
    }
    if (mechanical > w->watch.scale) w->watch.scale = mechanical;
    growth = account - w->watch.start;
    if (w->watch.scale > 0 && growth / w->watch.scale > w->watch.worst) w->watch.worst = growth / w->watch.scale;
    if (!(growth > w->def.energy_growth_limit * w->watch.scale) || !(growth > w->watch.noise)) return SPS_OK;
    ++w->watch.events; /* counted at every check above the limit: the caller's evidence (diagnostics) */
    if (w->watch.fired && !w->def.energy_growth_stops) return SPS_OK; /* warned once */
    w->watch.fired = 1;
    for (bi = 0; bi < w->nbodies; ++bi) { /* the body whose account grew most: where it went wrong */
        sps_real body_account, m;
        sps__body_account(w, &w->bodies[bi], &body_account, &m);
        if (bi == 0 || body_account - w->bodies[bi].energy_start > gain) { gain = body_account - w->bodies[bi].energy_start; most = bi; }
    }
    snprintf(msg, sizeof msg,
             "energy watchdog at t = %g: the energy (kinetic + volumetric strain + contact + gravity potential + plastic work - work of "
             "prescribed motions) "
             "grew from %g J to %g J since t = %g, by %.3g %% of the largest mechanical energy %g J (energy_growth_limit = %g %%); "
             "body '%s' gained most (%g J). Likely cause: ",
             (double)w->time, (double)w->watch.start, (double)account, (double)w->watch.start_time,
             (double)(100 * growth / w->watch.scale), (double)w->watch.scale, (double)(100 * w->def.energy_growth_limit),
             w->bodies[most].name, (double)gain);
    sps__growth_causes(w, &w->bodies[most], msg + strlen(msg), sizeof msg - strlen(msg));
    if (!w->def.energy_growth_stops) { sps__warn(w, "%s", msg); return SPS_OK; }
    sps__set_error(w, 0, "unstable: %s", msg);
    return SPS_ERR_UNSTABLE;
}

/* >>transport: the transport-velocity corrections TVF and UTVF (UTVF sections 3.2-3.3)

   After every acoustic sub-step each particle of a body with transport = TVF or UTVF is moved by
   dr = -2 alpha h^2 g_i, g_i = sum_j grad W_ij V_j (UTVF eq. 30; grad W_ij = dW/dr e_ij, so the
   shift points away from where the neighbours crowd), which drives the particles towards
   zero-order consistency (sum_j W_ij V_j = 1) and so against the clustering of tensile
   instability. Velocities are untouched: linear momentum is kept exactly, angular momentum
   and the kinetic energy are not changed either (only positions move).
   Free-surface particles, whose kernel is cut, would be pushed out of the body: a particle is
   on the surface if its position divergence div r_i = -sum_j r_ij . grad W_ij V_j (UTVF eq. 31,
   trace of B_i^-1; d inside) is below 0.75 d, or if one with is within h of it (the second
   layer). TVF leaves them where they are (the earlier formulations, Zhang et al. 2025);
   UTVF moves them along the surface only, dr - (dr . n) n with the normal n = B_i g_i / |B_i g_i|
   (UTVF eqs. 35-37). Neither moves a particle with div r below 0.6 d (too few neighbours for a
   normal: a splash). The reference code's rule, which is DESIGN's; the paper's further rule for
   splashed particles (no near-surface particle around) is not applied.
   Two passes (the sums; the flags and shifts) and a per-particle move, in every thread. Once
   per sub-step, as UTVF eq. 42 stands after the time integration: once per advection step
   (the reference code's fluids) was measured too weak to hold OG's zigzag modes (the plate of
   C3 at H/dp 20 broke within 0.1 s; per sub-step it swings with min spacing 0.83 dp).
   With transport_carries_velocity the shift takes the velocity along, v_i += L_i dr_i, the
   velocity field's first-order value at the new position (L from this sub-step's continuity
   pass): a shift that holds the particles near a lattice while the flow shears them otherwise
   leaves their velocities behind, and the flow between them loses its advection (the role of
   Adami, Hu and Adams 2013's extra stress rho u (u~ - u) in the momentum equation); and UTVF's
   sums take the walls' images as TVF's do (sps__transport_wall_sums).
   Linear momentum is then not exact (sum m_i L_i dr_i is not zero in general). */

/* Transport pass 1, the pair loop for lane group g: g_i into rows 0-2, B_i^-1 into rows 3-8. */
SPS__INLINE void sps__transport_sum_pairs(sps_world* w, const sps__body* b, int g, sps_real dt, sps__lane_sums* SPS__RESTRICT sums, const int dim,
                                          const int geo, const int terms) {
    const sps__group q = sps__group_of(w, b, g);
    const sps_real* SPS__RESTRICT vol = w->vol;
    sps_real(*sum)[SPS__LANES] = sums->row, (*A)[SPS__LANES] = sums->row + 3;
    int k, l;
    (void)dt;
    (void)terms;
    SPS__PAIR_LOOP(w, q, dim, geo, k, l, {
            const sps_real dwv = e.dw * vol[j];
            sum[0][l] += dwv * e.ex;
            sum[1][l] += dwv * e.ey;
            if (dim == 3) sum[2][l] += dwv * e.ez;
            sps__add_moment(&A[0][l], SPS__LANES, e.ex, e.ey, e.ez, e.r * dwv, dim);
    })
}

/* Transport pass 1's finish: g_i, div r_i and, for UTVF, the normal. */
SPS__INLINE void sps__transport_sums_finish(const sps__body* b, sps__group q, sps__lane_sums* sums, const int dim) {
    const int normal = b->model.transport == SPS_TRANSPORT_UTVF;
    sps_real(*sum)[SPS__LANES] = sums->row, (*A)[SPS__LANES] = sums->row + 3;
    sps_real B[9][SPS__LANES];
    int l, a, c;
    for (l = 0; l < SPS__LANES && q.i0 + l < b->end; ++l) {
        sps_real* t = b->transport + (size_t)SPS__TRANSPORT_VALUES * (q.i0 + l - b->begin);
        sps_real n[3] = {0, 0, 0}, n2 = 0;
        if (normal) sps__blended_inverse(&A[0][l], SPS__LANES, &B[0][l], SPS__LANES, dim);
        for (a = 0; a < dim && normal; ++a) {
            for (c = 0; c < dim; ++c) n[a] += B[3 * a + c][l] * sum[c][l];
            n2 += n[a] * n[a];
        }
        for (a = 0; a < 3; ++a) {
            t[SPS__TR_G + a] = a < dim ? sum[a][l] : 0;
            t[SPS__TR_NORMAL + a] = n2 > 0 ? n[a] / SPS__SQRT(n2) : 0;
        }
        t[SPS__TR_DIVR] = A[0][l] + A[3][l] + (dim == 3 ? A[5][l] : 0);
    }
}

/* Transport pass 2, the pair loop for lane group g: the neighbours within h on the surface (div
   r below 0.75 d), per lane into row 0. */
SPS__INLINE void sps__transport_surface_pairs(sps_world* w, const sps__body* b, int g, sps_real dt, sps__lane_sums* SPS__RESTRICT sums, const int dim,
                                              const int geo, const int terms) {
    const sps__group q = sps__group_of(w, b, g);
    const sps_real* SPS__RESTRICT t = b->transport;
    const int begin = b->begin;
    const sps_real surface_divr = SPS_R(0.75) * dim, h = w->h;
    sps_real* near = sums->row[0];
    int k, l;
    (void)dt;
    (void)terms;
    SPS__PAIR_LOOP(w, q, dim, geo, k, l, {
            const int outer_j = t[SPS__TRANSPORT_VALUES * (j - begin) + SPS__TR_DIVR] < surface_divr; /* an int offset: a gather */
            near[l] += (sps_real)(outer_j & (e.r < h) & (e.dw != 0)); /* padding (j = i, dW = 0) counts not; & not &&: no branch */
    })
}

/* Transport pass 2's finish: the surface flags (div r of the particle and of its neighbours
   within h) and the shift, into the particle's first values. */
SPS__INLINE void sps__transport_shift_finish(sps_world* w, const sps__body* b, sps__group q, sps__lane_sums* sums, const int dim) {
    const int begin = b->begin, utvf = b->model.transport == SPS_TRANSPORT_UTVF;
    const sps_real surface_divr = SPS_R(0.75) * dim, splash_divr = SPS_R(0.6) * dim;
    const sps_real scale = -2 * b->transport_alpha * w->h * w->h;
    const sps_real* near = sums->row[0];
    int l, a;
    for (l = 0; l < SPS__LANES && q.i0 + l < b->end; ++l) {
        sps_real* ti = b->transport + (size_t)SPS__TRANSPORT_VALUES * (q.i0 + l - begin);
        const sps_real divr = ti[SPS__TR_DIVR], *n = ti + SPS__TR_NORMAL;
        const int surface = divr < surface_divr || near[l] > 0;
        sps_real dr[3], dn = 0;
        for (a = 0; a < 3; ++a) {
            dr[a] = scale * ti[SPS__TR_G + a];
            dn += dr[a] * n[a];
        }
        for (a = 0; a < 3; ++a) {
            if (divr < splash_divr || (surface && !utvf)) dr[a] = 0;
            else if (surface) dr[a] -= dn * n[a]; /* UTVF eq. 36 */
            ti[SPS__TR_G + a] = dr[a];
        }
    }
}
SPS__GENERIC_LOOPS(transport_sum_pairs)
SPS__GENERIC_LOOPS(transport_surface_pairs)
SPS__INSTANCES(transport_sum_pairs, plain, 0)
SPS__INSTANCES(transport_surface_pairs, plain, 0)

/* TVF's sums at a wall: the analytic walls' mirror images (>>walls for fluids) and the coupled
   solids' particles (>>coupling: fluid-structure) complete the kernel as they do in the
   continuity sums, so a particle next to a wall has g_i of the whole support and div r_i = d:
   it is not taken for a surface particle and is kept at its spacing from the wall (the
   reference code's correction counts its walls too). Without them TVF froze the two layers
   next to every wall, and the wake of Turek and Hron's cylinder tore voids along the channel's
   walls that nothing closed (bench/VALIDATION.md, "Turek-Hron"). UTVF keeps the paper's sums
   over the body's own particles unless it carries the velocity (transport_carries_velocity). */
/* An image's terms of the transport sums (sps__transport_sum_pairs'), added to sums (rows
   `stride` apart). */
SPS__INLINE void sps__image_transport(const sps_world* w, sps__image m, sps__pair_geometry e, sps_real* sums, int stride, const int dim) {
    const sps_real dwv = e.dw * w->vol[m.j], dir[3] = {e.ex, e.ey, e.ez};
    int a;
    SPS__UNROLL
    for (a = 0; a < dim; ++a) sums[a * stride] += dwv * dir[a];
    sps__add_moment(&sums[3 * stride], stride, e.ex, e.ey, e.ez, e.r * dwv, dim);
}
SPS__INLINE void sps__images_transport_lanes(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, const sps__reflection* rf,
                                             sps__lane_sums* SPS__RESTRICT sums, const int dim, const int corner) {
    int m, l;
    SPS__IMAGE_LOOP(w, b, lanes, rf, dim, corner, m, l, { sps__image_transport(w, im, e, &sums->row[0][l], SPS__LANES, dim); })
}
static void sps__images_transport(sps_world* w, const sps__body* b, const sps__image_lanes* lanes, const sps__reflection* rf, void* sums) {
    sps__lane_sums* lane_sums = (sps__lane_sums*)sums;
    SPS__BY_DIM(w,
                SPS__BY_CORNER(rf, sps__images_transport_lanes(w, b, lanes, rf, lane_sums, 2, 0), sps__images_transport_lanes(w, b, lanes, rf, lane_sums, 2, 1)),
                SPS__BY_CORNER(rf, sps__images_transport_lanes(w, b, lanes, rf, lane_sums, 3, 0), sps__images_transport_lanes(w, b, lanes, rf, lane_sums, 3, 1)));
}
static void sps__transport_wall_sums(sps_world* w, const sps__body* b, sps__group q, sps__lane_sums* sums) {
    sps__image image;
    sps__image_lanes lanes;
    int l, k;
    sps__group_lanes(b, q, &lanes);
    if (b->model.mirrored) sps__each_reflection(w, b, &lanes, b->model.mirrored != SPS__MIRROR_STRESS, sps__images_transport, sums);
    for (l = 0; l < SPS__LANES && lanes.among[l] && b->coupled; ++l)
        for (k = w->ct_first[q.i0 + l]; sps__next_solid_image(w, q.i0 + l, &k, &image); ++k)
            sps__image_transport(w, image, sps__image_geometry(w, q.i0 + l, image, 1, w->dim), &sums->row[0][l], SPS__LANES, w->dim);
}

/* The transport passes' kernels for lane group g: the world mode's pair loop, the finish. */
static void sps__transport_sums(sps_world* w, const sps__body* b, int g, sps_real dt) {
    sps__lane_sums sums;
    const sps__group q = sps__group_of(w, b, g);
    sps__clear_sums(&sums, 9);
    sps__transport_sum_pairs_plain[sps__mode(w)](w, b, g, dt, 0, &sums);
    if ((b->model.transport == SPS_TRANSPORT_TVF || b->def.transport_carries_velocity) && ((b->model.mirrored && w->nwalls > 0) || b->coupled))
        sps__transport_wall_sums(w, b, q, &sums);
    if (w->dim == 2) sps__transport_sums_finish(b, q, &sums, 2);
    else sps__transport_sums_finish(b, q, &sums, 3);
}
static void sps__transport_shift(sps_world* w, const sps__body* b, int g, sps_real dt) {
    sps__lane_sums sums;
    const sps__group q = sps__group_of(w, b, g);
    sps__clear_sums(&sums, 1);
    sps__transport_surface_pairs_plain[sps__mode(w)](w, b, g, dt, 0, &sums);
    if (w->dim == 2) sps__transport_shift_finish(w, b, q, &sums, 2);
    else sps__transport_shift_finish(w, b, q, &sums, 3);
}

/* The transport correction of every body that has one, by every thread of the step's team. */
static void sps__transport(sps_world* w) {
    int bi, i, i0, i1, a;
    for (bi = 0; bi < w->nbodies; ++bi) {
        const sps__body* b = &w->bodies[bi];
        if (b->model.transport == SPS_TRANSPORT_NONE || b->end == b->begin) continue;
        sps__run_groups(w, b, sps__transport_sums, 0);
        sps__run_groups(w, b, sps__transport_shift, 0);
        sps__thread_share(b, &i0, &i1);
        for (i = i0; i < i1; ++i) {
            const sps_real* dr = b->transport + (size_t)SPS__TRANSPORT_VALUES * (i - b->begin) + SPS__TR_G;
            if (w->zone && w->zone[i] >= 0) continue; /* a buffer particle moves as its zone holds it (>>open boundaries) */
            for (a = 0; a < w->dim; ++a) w->pos[a][i] += dr[a];
            if (b->def.transport_carries_velocity) { /* v(x + dr) = v + L dr */
                const sps_real* L = b->grad + (size_t)9 * (i - b->begin);
                int c;
                for (a = 0; a < w->dim; ++a)
                    for (c = 0; c < w->dim; ++c) w->vel[a][i] += L[3 * a + c] * dr[c];
            }
        }
        SPS__PRAGMA(omp barrier)
    }
}

/* >>open boundaries: kill, inflow and outflow zones (OPEN BOUNDARIES in the manual)

   The buffer-zone form of Lastiwka, Basa and Quinlan 2009 (Int. J. Numer. Meth. Fluids 61,
   709-724): an inflow buffer of lattice particles moves at the prescribed velocity and gives
   the fluid next to it a full support; a buffer particle that crosses into the domain becomes
   fluid and a new one is created one box depth behind it, which is one lattice spacing behind
   the last of its row, so the buffer stays a lattice. An outflow buffer holds the particles that
   crossed into it at the outlet pressure and at the velocity of the fluid just upstream
   (extrapolated with zero gradient along the axis, per bin of the cross-section: the pressure
   is the boundary condition; a held velocity keeps the truncated support at the buffer's end
   from pushing them out), and removes them when they leave it downstream. A kill zone removes
   what enters it.
   The particle count changes only here, once per advection step before the configuration
   update (DESIGN: open boundaries): the zones are matched in particle order (deterministic for
   any thread count), the removed particles are squeezed out of every array (the survivors keep
   their order and their ids are renumbered in creation order: ids stay 0..n-1), the new ones
   are appended and the commit sorts them into their body. Between updates the kick holds a
   buffer particle at its zone velocity (sps__kick_range). */

/* Whether v is a valid zone index for the particle in slot i: -1, or a whole number naming a
   buffer zone (inflow, outflow) of its body (sps_world_validate, restart files). */
static int sps__zone_index_valid(const sps_world* w, int i, sps_real v) {
    const int k = (int)v;
    if (v == -1) return 1;
    return v >= 0 && v < w->nzones && (sps_real)k == v && w->zones[k].body == w->body[i] && w->zones[k].def.kind != SPS_ZONE_KILL;
}

static int sps__zone_contains(const sps_world* w, const sps__zone* z, int i) {
    int a;
    for (a = 0; a < w->dim; ++a)
        if (!(w->pos[a][i] >= z->def.lo[a] && w->pos[a][i] < z->def.hi[a])) return 0;
    return 1;
}
/* How far past the face of zone z that the flow leaves it by (inflow: into the domain; outflow:
   downstream) position x lies along its axis: >= 0 once it has left. */
static sps_real sps__zone_past_exit(const sps__zone* z, sps_real x) {
    const sps_real face = z->def.direction > 0 ? z->def.hi[z->def.axis] : z->def.lo[z->def.axis];
    return z->def.direction > 0 ? x - face : face - x;
}

/* The bin of zone z's cross-section that particle i lies in (clamped to the box). */
static int sps__zone_bin(const sps_world* w, const sps__zone* z, int i) {
    int a, bin = 0;
    for (a = w->dim - 1; a >= 0; --a) {
        int k = (int)SPS__FLOOR((w->pos[a][i] - z->def.lo[a]) / w->def.dp);
        if (a == z->def.axis) continue;
        k = k < 0 ? 0 : k >= z->bin_n[a] ? z->bin_n[a] - 1 : k;
        bin = bin * z->bin_n[a] + k;
    }
    return bin;
}
/* An outflow zone's bins: the mean velocity of the fluid of its body within 2h upstream of its
   entry face, per bin of the cross-section (Lastiwka et al. extrapolate the flow into the
   outflow buffer; a velocity frozen at entry would leave the fluid that is at rest there at the
   start at rest for good, a plug). */
static void sps__zone_sample(sps_world* w, sps__zone* z) {
    const int ax = z->def.axis;
    const sps_real entry = z->def.direction > 0 ? z->def.lo[ax] : z->def.hi[ax];
    int i, a;
    memset(z->bins, 0, sizeof(sps_real) * 4 * (size_t)z->nbins);
    for (i = w->bodies[z->body].begin; i < w->bodies[z->body].end; ++i) {
        const sps_real upstream = z->def.direction > 0 ? entry - w->pos[ax][i] : w->pos[ax][i] - entry;
        sps_real* bin;
        if (w->zone[i] >= 0 || !(upstream > 0 && upstream <= w->support)) continue;
        for (a = 0; a < w->dim; ++a)
            if (a != ax && !(w->pos[a][i] >= z->def.lo[a] && w->pos[a][i] < z->def.hi[a])) break;
        if (a < w->dim) continue;
        bin = z->bins + 4 * sps__zone_bin(w, z, i);
        for (a = 0; a < w->dim; ++a) bin[a] += w->vel[a][i];
        bin[3] += 1;
    }
}

/* The prescribed velocity of inflow zone z at x, time t into v; SPS_ERR_INVALID_ARG naming the
   zone, the point and the value if it is not finite. */
static sps_result sps__zone_velocity(sps_world* w, int zi, const sps_real x[3], sps_real v[3]) {
    const sps__zone* z = &w->zones[zi];
    int a;
    v[0] = v[1] = v[2] = 0;
    if (z->def.velocity_fn) z->def.velocity_fn(x, w->time, z->def.velocity_user, v);
    else memcpy(v, z->def.velocity, sizeof z->def.velocity);
    for (a = 0; a < w->dim; ++a)
        if (!sps__finite(v[a])) {
            sps__set_error(w, 0, "zone %d: velocity_fn gave v[%d] = %g at x = (%g, %g, %g), t = %g, allowed finite", zi, a, (double)v[a],
                           (double)x[0], (double)x[1], (double)x[2], (double)w->time);
            return SPS_ERR_INVALID_ARG;
        }
    for (a = w->dim; a < 3; ++a) v[a] = 0;
    return SPS_OK;
}

/* Holds buffer particle i of zone zi: the zone's velocity (inflow: the prescribed one; outflow:
   the one it has) and, at an outflow, the outlet pressure. */
static sps_result sps__zone_hold(sps_world* w, int zi, int i) {
    const sps__zone* z = &w->zones[zi];
    sps_real x[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    int a;
    sps_result r;
    for (a = 0; a < w->dim; ++a) { x[a] = w->pos[a][i]; v[a] = w->vel[a][i]; }
    if (z->def.kind == SPS_ZONE_INFLOW && (r = sps__zone_velocity(w, zi, x, v)) != SPS_OK) return r;
    if (z->def.kind == SPS_ZONE_OUTFLOW) {
        const sps_real* bin = z->bins + 4 * sps__zone_bin(w, z, i);
        for (a = 0; a < w->dim && bin[3] > 0; ++a) v[a] = bin[a] / bin[3]; /* the upstream fluid's (zero gradient along the axis) */
        w->rho[i] = z->rho_out;
        w->p[i] = z->def.pressure;
        w->vol[i] = w->mass[i] / w->rho[i];
    }
    w->zone[i] = (sps_real)zi;
    for (a = 0; a < w->dim; ++a) w->zone_vel[a][i] = w->vel[a][i] = v[a];
    return SPS_OK;
}

/* Squeezes out the particles marked in gone[] (n of them slot by slot, `removed` in all): every
   world array and each body's own, survivors in order; ids renumbered in creation order. The
   scratch new_id holds n ints. The commit that follows sets the bodies' ranges. */
static void sps__remove_marked(sps_world* w, const int* gone, int* new_id, int removed) {
    int k, a, bi, i, j, id;
    const int n = w->n;
    for (i = 0; i < n; ++i) new_id[w->id[i]] = gone[i] ? -1 : 0;
    for (id = 0, j = 0; id < n; ++id)
        if (new_id[id] == 0) new_id[id] = j++;
    for (k = 0; k < SPS__NFIELDS; ++k) {
        const sps__field_info* f = &sps__fields[k];
        const size_t bytes = sps__field_bytes(f);
        for (a = 0; a < sps__field_arrays(f); ++a) {
            if (!f->per_body) {
                char* x;
                memcpy(&x, sps__field_slot(w, NULL, f, a), sizeof x);
                if (!x) continue;
                for (i = 0, j = 0; i < n; ++i)
                    if (!gone[i]) memmove(x + bytes * (size_t)j++, x + bytes * (size_t)i, bytes);
                memset(x + bytes * (size_t)j, 0, bytes * (size_t)(n - j)); /* as unused slots were */
                continue;
            }
            for (bi = 0; bi < w->nbodies; ++bi) {
                const sps__body* b = &w->bodies[bi];
                char* x;
                int m, kept;
                memcpy(&x, sps__field_slot(w, b, f, a), sizeof x);
                if (!x) continue;
                for (m = 0, kept = 0; m < b->field_count; ++m)
                    if (!gone[b->begin + m]) memmove(x + bytes * (size_t)kept++, x + bytes * (size_t)m, bytes);
                memset(x + bytes * (size_t)kept, 0, bytes * (size_t)(b->field_count - kept)); /* the lane padding after the last */
            }
        }
    }
    for (bi = 0; bi < w->nbodies; ++bi) {
        sps__body* b = &w->bodies[bi];
        int m, lost = 0;
        for (m = b->begin; m < b->end; ++m) lost += gone[m];
        b->count -= lost;
        b->field_count -= lost;
    }
    w->n -= removed;
    for (i = 0; i < w->n; ++i) w->id[i] = new_id[w->id[i]];
    for (i = 0; i < w->n; ++i) w->slot_of_id[w->id[i]] = i;
    w->good_n = 0; /* its ids are gone: the last good state is taken again at this update */
}

/* Appends a new inflow particle of zone zi at x with density rho, held at the zone velocity. */
static sps_result sps__zone_create(sps_world* w, int zi, const sps_real x[3], sps_real rho) {
    sps__zone* z = &w->zones[zi];
    const int i = w->n;
    sps_result r;
    if ((r = sps__add_one(w, z->body, x, w->dp_volume)) != SPS_OK) return r;
    w->rho[i] = rho;
    w->p[i] = w->bodies[z->body].mat.c0 * w->bodies[z->body].mat.c0 * (rho - w->bodies[z->body].rho0);
    w->vol[i] = w->mass[i] / rho;
    z->created++;
    return sps__zone_hold(w, zi, i);
}

/* The scene as the program built it, before the zones change it: a restart's fingerprint (the
   program builds it again to restore). */
#ifndef SPHSOLID_NO_STDIO
static uint64_t sps__scene_hash(const sps_world* w);
#endif
static void sps__record_built_scene(sps_world* w) {
    int bi;
    if (w->built) return;
    w->built = 1;
    w->built_n = w->n;
    for (bi = 0; bi < w->nbodies; ++bi) w->bodies[bi].built_count = w->bodies[bi].count;
#ifndef SPHSOLID_NO_STDIO
    w->built_scene = sps__scene_hash(w);
#endif
}

/* Once per advection step, before the configuration update: each particle of a body with zones
   against its zones, in particle order; then the removals and the new inflow particles. */
static sps_result sps__open_boundaries(sps_world* w) {
    int *gone, *new_id, i, k, removed = 0, spawned = 0, n0;
    sps_real* spawn; /* per new particle: x, y, z, density, zone */
    sps_result r;
    if ((r = sps__ready_to_step(w)) != SPS_OK) return r; /* sorted by body, the scratch allocated */
    sps__record_built_scene(w);
    n0 = w->n;
    gone = w->perm;      /* cap ints each: free between configuration updates */
    new_id = w->cell_of;
    spawn = (sps_real*)w->scratch; /* 5 cap reals in a world with zones (sps__ensure_neighbor_storage) */
    for (k = 0; k < w->nzones; ++k)
        if (w->zones[k].def.kind == SPS_ZONE_OUTFLOW) sps__zone_sample(w, &w->zones[k]);
    for (i = 0; i < n0; ++i) {
        const int bi = w->body[i];
        int zi = (int)w->zone[i];
        gone[i] = 0;
        if (!w->bodies[bi].zoned) continue;
        if (zi >= 0) { /* a buffer particle */
            sps__zone* z = &w->zones[zi];
            const sps_real past = sps__zone_past_exit(z, w->pos[z->def.axis][i]);
            if (z->def.kind == SPS_ZONE_INFLOW && past >= 0) { /* into the domain: fluid, and a new one behind it */
                sps_real* s = spawn + (size_t)5 * spawned++;
                int a;
                for (a = 0; a < 3; ++a) s[a] = a < w->dim ? w->pos[a][i] : 0;
                s[z->def.axis] -= z->def.direction * z->depth;
                s[3] = w->rho[i];
                s[4] = (sps_real)zi;
                w->zone[i] = -1;
            } else if (z->def.kind == SPS_ZONE_OUTFLOW && !sps__zone_contains(w, z, i)) {
                if (past >= 0) { gone[i] = 1; z->removed++; ++removed; continue; } /* downstream: out of the world */
                w->zone[i] = -1; /* back upstream: fluid again */
            } else if ((r = sps__zone_hold(w, zi, i)) != SPS_OK) return r; /* the velocity profile of this time */
        }
        for (k = 0; k < w->nzones && (zi = (int)w->zone[i]) < 0; ++k) {
            sps__zone* z = &w->zones[k];
            if (z->body != bi || z->def.kind == SPS_ZONE_INFLOW || !sps__zone_contains(w, z, i)) continue;
            if (z->def.kind == SPS_ZONE_KILL) { gone[i] = 1; z->removed++; ++removed; break; }
            if ((r = sps__zone_hold(w, k, i)) != SPS_OK) return r; /* into the outflow buffer */
        }
        if (!gone[i] && zi >= 0) /* a kill zone also takes buffer particles */
            for (k = 0; k < w->nzones; ++k)
                if (w->zones[k].body == bi && w->zones[k].def.kind == SPS_ZONE_KILL && sps__zone_contains(w, &w->zones[k], i)) {
                    gone[i] = 1; w->zones[k].removed++; ++removed;
                    break;
                }
    }
    if (removed) sps__remove_marked(w, gone, new_id, removed);
    for (k = 0; k < spawned; ++k) {
        const sps_real* s = spawn + (size_t)5 * k;
        if ((r = sps__zone_create(w, (int)s[4], s, s[3])) != SPS_OK) return r;
    }
    if (removed || spawned) w->needs_sort_by_body = 1; /* the commit sets the ranges and sorts the new particles into their body */
    sps__rearm_watchdog(w); /* energy flows in and out through the zones: the account starts again at every step */
    return SPS_OK;
}

SPSDEF sps_zone_def sps_default_zone_def(void) {
    sps_zone_def d;
    memset(&d, 0, sizeof d);
    d.kind = SPS_ZONE_KILL;
    d.direction = 1;
    d.internal_cookie = SPS__COOKIE;
    return d;
}

/* The rules of a zone def for body k (sps_body_add_zone); 0 with the message set if one breaks. */
static int sps__check_zone(sps_world* w, int k, const sps_zone_def* d) {
    static const char* const fn = "sps_body_add_zone";
    const sps__body* b = &w->bodies[k];
    const int flow = d->kind == SPS_ZONE_INFLOW || d->kind == SPS_ZONE_OUTFLOW;
    const sps_real tol = SPS_R(1e-6) * w->def.dp;
    int a, c, bi;
    if (d->internal_cookie != SPS__COOKIE) { sps__set_error(w, 0, "%s: zone def not initialised: start from sps_default_zone_def()", fn); return 0; }
    if ((int)d->kind < 0 || (int)d->kind > 2) {
        sps__set_error(w, 0, "%s: kind = %d, allowed 0..2 (SPS_ZONE_KILL, SPS_ZONE_INFLOW, SPS_ZONE_OUTFLOW)", fn, (int)d->kind);
        return 0;
    }
    if (!sps__check_box(w, fn, d->lo, d->hi)) return 0;
    if (d->axis < 0 || d->axis >= w->dim) { sps__set_error(w, 0, "%s: axis = %d, allowed [0, %d)", fn, d->axis, w->dim); return 0; }
    if (d->direction != 1 && d->direction != -1) { sps__set_error(w, 0, "%s: direction = %d, allowed +1 or -1", fn, d->direction); return 0; }
    for (a = 0; a < 3; ++a)
        if (!sps__finite(d->velocity[a])) { sps__set_error(w, 0, "%s: velocity[%d] = %g, allowed finite", fn, a, (double)d->velocity[a]); return 0; }
    if (!sps__finite(d->pressure)) { sps__set_error(w, 0, "%s: pressure = %g, allowed finite", fn, (double)d->pressure); return 0; }
    if (b->model.material->kinematic || b->model.total_lagrangian) {
        sps__set_error(w, 0, "%s: body '%s' is a %s body, whose particles %s; allowed fluid, granular and updated-Lagrangian solid bodies",
                       fn, b->name, b->model.free_rigid ? "free rigid" : b->model.total_lagrangian ? "total-Lagrangian" : "wall",
                       b->model.total_lagrangian ? "keep their reference neighbours for the whole run" : "set its motion and mass together");
        return 0;
    }
    if (flow && (b->model.material->shear || !b->model.pressure_of_density)) {
        sps__set_error(w, 0, "%s: kind = %s on body '%s', which is not a fluid (its stress is not a pressure of its density); allowed on "
                       "fluid bodies only (SPS_ZONE_KILL takes any deforming body)", fn, d->kind == SPS_ZONE_INFLOW ? "SPS_ZONE_INFLOW" : "SPS_ZONE_OUTFLOW", b->name);
        return 0;
    }
    if (flow && d->hi[d->axis] - d->lo[d->axis] < w->support * (1 - SPS_R(1e-6))) {
        sps__set_error(w, 0, "%s: the box's depth along axis %d = %g m, allowed >= the kernel support 2h = %g m (a full support of buffer)", fn,
                       d->axis, (double)(d->hi[d->axis] - d->lo[d->axis]), (double)w->support);
        return 0;
    }
    for (a = 0; a < w->dim; ++a) {
        const sps_real o = w->def.periodic_origin[a], L = w->def.periodic[a];
        if (L > 0 && flow && a == d->axis) {
            sps__set_error(w, 0, "%s: axis = %d is periodic (periodic[%d] = %g): a flow through it comes back; allowed a non-periodic axis", fn, a, a, (double)L);
            return 0;
        }
        if (L > 0 && (d->lo[a] < o - tol || d->hi[a] > o + L + tol)) {
            sps__set_error(w, 0, "%s: lo[%d], hi[%d] = %g, %g straddle the periodic box [%g, %g); allowed within it", fn, a, a, (double)d->lo[a],
                           (double)d->hi[a], (double)o, (double)(o + L));
            return 0;
        }
    }
    for (c = 0; c < w->nwalls; ++c) /* every corner of the box on the wall's free side */
        for (a = 0; a < (1 << w->dim); ++a) {
            sps_real s = 0;
            int e;
            for (e = 0; e < w->dim; ++e) s += (((a >> e) & 1 ? d->hi[e] : d->lo[e]) - w->walls[c].point[e]) * w->walls[c].normal[e];
            if (s < -tol) {
                sps__set_error(w, 0, "%s: the box [lo, hi] reaches %g m behind wall %d (normal (%g, %g, %g)), outside the domain; allowed on the "
                               "walls' free side", fn, (double)-s, c, (double)w->walls[c].normal[0], (double)w->walls[c].normal[1],
                               (double)w->walls[c].normal[2]);
                return 0;
            }
        }
    for (bi = 0; bi < w->nbodies; ++bi)
        if (w->bodies[bi].model.paired) {
            sps__set_error(w, 0, "%s: body '%s' has rotation = SPS_ROTATION_PAIR, whose pair forces are kept by particle id across steps; "
                           "allowed with zones: the mean or per-particle rotation", fn, w->bodies[bi].name);
            return 0;
        }
    if (w->nobs > 0) {
        sps__set_error(w, 0, "%s: the world has %d observers, which hold particle ids that a zone's removals renumber; allowed: zones "
                       "without observers (read the fields near the point instead)", fn, w->nobs);
        return 0;
    }
    return 1;
}

SPSDEF sps_result sps_body_add_zone(sps_world* w, sps_body b, const sps_zone_def* def, int* zone_id) {
    int k, i, a, added = 0;
    sps__zone* z;
    sps_result r;
    if (zone_id) *zone_id = -1;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (!def) { sps__set_error(w, 0, "sps_body_add_zone: def must not be NULL"); return SPS_ERR_INVALID_ARG; }
    if ((k = sps__check_body(w, b, "sps_body_add_zone")) < 0 || !sps__check_zone(w, k, def)) return SPS_ERR_INVALID_ARG;
    if (!w->zone) { /* the zone index and velocity, -1 and 0 for the particles so far */
        const size_t room = (size_t)w->cap + SPS__LANES;
        for (a = 0; a < 3; ++a)
            if (!sps__grow(w, &w->zone_vel[a], sizeof(sps_real), 0, room)) return sps__oom(w, "sps_body_add_zone: the zone velocities");
        if (!sps__grow(w, &w->zone, sizeof(sps_real), 0, room)) return sps__oom(w, "sps_body_add_zone: the zone index");
        for (i = 0; i < w->n; ++i) w->zone[i] = -1;
    }
    if (!sps__grow(w, &w->zones, sizeof(sps__zone), (size_t)w->nzones, (size_t)w->nzones + 1)) return sps__oom(w, "sps_body_add_zone: the zone");
    z = &w->zones[w->nzones];
    z->def = *def;
    z->body = k;
    z->depth = def->hi[def->axis] - def->lo[def->axis];
    z->rho_out = w->bodies[k].rho0 + def->pressure / (w->bodies[k].mat.c0 * w->bodies[k].mat.c0);
    z->bins = NULL;
    z->nbins = 1;
    for (a = 0; a < 3; ++a) {
        const double cells = a < w->dim && a != def->axis ? ceil((double)((def->hi[a] - def->lo[a]) / w->def.dp)) : 1;
        if (cells > 1e6 || (z->nbins *= (int)cells) > 1000000) {
            sps__set_error(w, 0, "sps_body_add_zone: the box's cross-section holds %.3g spacings dp, allowed 1e6", cells * z->nbins);
            return SPS_ERR_INVALID_ARG;
        }
        z->bin_n[a] = (int)cells;
    }
    if (def->kind == SPS_ZONE_OUTFLOW && !(z->bins = (sps_real*)sps__alloc(w, sizeof(sps_real) * 4 * (size_t)z->nbins)))
        return sps__oom(w, "sps_body_add_zone: the outflow bins");
    if (z->bins) memset(z->bins, 0, sizeof(sps_real) * 4 * (size_t)z->nbins);
    w->nzones++;
    w->bodies[k].zoned = 1;
    if (def->kind != SPS_ZONE_KILL && sps__watchdog_on(w) && !w->bodies[k].driven) { /* a buffer's held velocity does work: count it */
        w->bodies[k].driven = 1;
        w->needs_sort_by_body = 1; /* the next step's commit allocates its prescribed_work */
    }
    if (def->kind == SPS_ZONE_INFLOW) { /* the buffer: the box's lattice points, at the prescribed velocity */
        const int first = w->n;
        if ((r = sps__fill(w, "sps_body_add_zone", b, def->lo, def->hi, NULL, NULL, &added)) != SPS_OK || added == 0) {
            w->nzones--;
            if (r == SPS_OK) sps__set_error(w, 0, "sps_body_add_zone: the inflow box holds no lattice point of spacing dp = %g", (double)w->def.dp);
            return r == SPS_OK ? SPS_ERR_INVALID_ARG : r;
        }
        for (i = first; i < w->n; ++i)
            if ((r = sps__zone_hold(w, w->nzones - 1, i)) != SPS_OK) return r;
    }
    if (zone_id) *zone_id = w->nzones - 1;
    return SPS_OK;
}

static int sps__check_zone_index(sps_world* w, int zone, const char* fn) {
    if (zone >= 0 && zone < w->nzones) return 1;
    sps__set_error(w, 0, "%s: zone = %d, allowed [0, %d)", fn, zone, w->nzones);
    return 0;
}

SPSDEF sps_result sps_world_set_zone_velocity(sps_world* w, int zone, const sps_real velocity[3], sps_zone_velocity_fn fn, void* user) {
    static const char* const name = "sps_world_set_zone_velocity";
    int a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (!sps__check_zone_index(w, zone, name)) return SPS_ERR_INVALID_ARG;
    if (w->zones[zone].def.kind != SPS_ZONE_INFLOW) { sps__set_error(w, 0, "%s: zone %d is not an inflow zone (kind = %d), allowed SPS_ZONE_INFLOW", name, zone, (int)w->zones[zone].def.kind); return SPS_ERR_INVALID_ARG; }
    if (!velocity) { sps__set_error(w, 0, "%s: velocity must not be NULL", name); return SPS_ERR_INVALID_ARG; }
    for (a = 0; a < 3; ++a)
        if (!sps__finite(velocity[a])) { sps__set_error(w, 0, "%s: velocity[%d] = %g, allowed finite", name, a, (double)velocity[a]); return SPS_ERR_INVALID_ARG; }
    memcpy(w->zones[zone].def.velocity, velocity, sizeof w->zones[zone].def.velocity);
    w->zones[zone].def.velocity_fn = fn;
    w->zones[zone].def.velocity_user = user;
    return SPS_OK;
}

SPSDEF sps_result sps_world_zone_counts(const sps_world* w, int zone, long* created, long* removed) {
    if (created) *created = 0;
    if (removed) *removed = 0;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (zone < 0 || zone >= w->nzones) { sps__set_error_const(w, "sps_world_zone_counts: zone = %d, allowed [0, %d)", zone, w->nzones); return SPS_ERR_INVALID_ARG; }
    if (created) *created = w->zones[zone].created;
    if (removed) *removed = w->zones[zone].removed;
    return SPS_OK;
}

SPSDEF sps_result sps_world_reserve(sps_world* w, int n_particles) {
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (n_particles < 0 || n_particles > SPS__MAX_PARTICLES) {
        sps__set_error(w, 0, "sps_world_reserve: n_particles = %d, allowed [0, %d]", n_particles, SPS__MAX_PARTICLES);
        return SPS_ERR_INVALID_ARG;
    }
    if (n_particles > w->reserved) w->reserved = n_particles;
    if (n_particles > w->cap) {
        if (sps__reserve(w, n_particles) != SPS_OK) return sps__oom(w, "sps_world_reserve: the particle arrays");
        w->needs_sort_by_body = 1; /* the next step sizes the neighbour storage and the bodies' arrays for it */
    }
    return SPS_OK;
}

/* >>stepping: configuration updates, the advection step and its acoustic sub-steps */

/* One acoustic sub-step (steps 1-5) from time t, called by every thread of the step's team.
   Returns max |v|^2 after the kick. A GNO body's three neighbour passes cannot share a pair loop
   bit for bit: the pressure pass sees the half-drifted positions x^(n+1/2), the continuity and
   penalty passes the kicked x^(n+1), and the penalty (ANG eqs. 43-46) reads the L_j of every
   neighbour, which the continuity pass finishes (a barrier between the two). With
   penalty_in_pressure_pass the previous sub-step's penalty, of length penalty_dt (0: none
   pending), is summed in this one's pressure loop in its own geometry, not bit for bit the
   paper's (chapter >>solver: the penalty in the next pressure pass; bench/VALIDATION.md, "Pass
   fusion"). */
static sps_real sps__acoustic_substep(sps_world* w, sps_real t, sps_real dt, sps_real penalty_dt) {
    int bi;
    sps_real vmax2;
    sps__half_drift(w, dt);
    for (bi = 0; bi < w->nbodies; ++bi) sps__run_groups(w, &w->bodies[bi], w->bodies[bi].model.pass.stress, dt); /* TL */
    for (bi = 0; bi < w->nbodies; ++bi) sps__pressure_pass(w, &w->bodies[bi], dt, penalty_dt);
    sps__contact_pass(w, t + SPS_R(0.5) * dt, dt);
    vmax2 = sps__kick(w, t, dt);
    for (bi = 0; bi < w->nbodies; ++bi) sps__continuity_pass(w, &w->bodies[bi], dt);
    for (bi = 0; bi < w->nbodies; ++bi) /* after the pass above: needs every L_j */
        if (w->bodies[bi].model.pass.penalty && !w->bodies[bi].model.penalty_in_pressure)
            sps__run_groups(w, &w->bodies[bi], w->bodies[bi].model.pass.penalty, dt);
    sps__finish(w, dt);
    return vmax2;
}

/* Impacts faster than this fraction of the sound speed (of the softer deformable body) are
   warned of: the papers validate contact up to 0.12 c0 (ENO section 6.7), and at 0.2 c0 the
   contact stability map (bench/VALIDATION.md) has OG stopping and GNO, GNO-A blowing up. */
#define SPS__IMPACT_MACH 0.2

/* Warns, once per world, when bodies bi and bj (bj < 0: the walls) that can touch move at
   relative speed sqrt(v2) above SPS__IMPACT_MACH c0. */
static void sps__warn_impact(sps_world* w, int bi, int bj, sps_real v2) {
    const sps__body *a = &w->bodies[bi], *b = bj >= 0 ? &w->bodies[bj] : NULL;
    char who[160];
    sps_real c0 = a->model.material->kinematic ? (sps_real)INFINITY : a->mat.c0;
    if (w->impact_warned) return;
    if (b && !b->model.material->kinematic && b->mat.c0 < c0) c0 = b->mat.c0;
    if (!(v2 > (sps_real)(SPS__IMPACT_MACH * SPS__IMPACT_MACH) * c0 * c0) || !(c0 < (sps_real)INFINITY)) return;
    w->impact_warned = 1;
    if (b) snprintf(who, sizeof who, "bodies '%s' and '%s' move at %g m/s relative to each other", a->name, b->name, (double)SPS__SQRT(v2));
    else snprintf(who, sizeof who, "body '%s' moves at %g m/s relative to the walls", a->name, (double)SPS__SQRT(v2));
    sps__warn(w, "t = %g: %s, %.2f times the sound speed c0 = %g m/s: contact is validated up to 0.12 c0 (ENO section 6.7); beyond "
              "%.1f c0 expect strong dissipation, tearing or blow-ups (bench/VALIDATION.md, contact stability map), which the energy "
              "watchdog reports", (double)w->time, who, (double)(SPS__SQRT(v2) / c0), (double)c0, SPS__IMPACT_MACH);
}

/* The speeds of the time-step criteria (ENO eqs. 25-26), measured in each body's own frame:
   its mass-weighted mean velocity, kept in frame_velocity for the advection step, so that a
   uniform motion of the scene does not change the discretisation (Galilean invariance). Bodies
   that can touch each other move relative to one another, and those in a world with walls
   relative to the walls: approach is the largest such speed (of the bodies' mean velocities),
   which bounds how far they travel towards each other between configuration updates. Returns
   the larger of approach and the fastest particle speed in its body's frame. */
static sps_real sps__frame_speeds(sps_world* w) {
    sps_real vmax2 = 0, approach2 = 0;
    int i, a, bi, bj;
    for (bi = 0; bi < w->nbodies; ++bi) { /* serial sums: a fixed order */
        sps__body* b = &w->bodies[bi];
        sps_real m = 0, mv[3] = {0, 0, 0};
        for (i = b->begin; i < b->end; ++i) {
            m += w->mass[i];
            for (a = 0; a < w->dim; ++a) mv[a] += w->mass[i] * w->vel[a][i];
        }
        for (a = 0; a < 3; ++a) b->frame_velocity[a] = a < w->dim && m > 0 ? mv[a] / m : 0;
        for (i = b->begin; i < b->end; ++i) {
            const sps_real v2 = sps__frame_speed2(w, i);
            if (!(v2 <= vmax2)) vmax2 = v2; /* NaN is kept: the caller's finiteness check sees it */
        }
    }
    for (bi = 0; bi < w->nbodies; ++bi) {
        const sps_real* vi = w->bodies[bi].frame_velocity;
        sps_real v2 = 0;
        if (w->nwalls > 0) {
            for (a = 0; a < w->dim; ++a) v2 += vi[a] * vi[a];
            if (v2 > approach2) approach2 = v2;
            sps__warn_impact(w, bi, -1, v2);
        }
        for (bj = bi + 1; bj < w->nbodies && w->touch; ++bj) {
            const sps_real* vj = w->bodies[bj].frame_velocity;
            if (!w->touch[(size_t)bi * w->nbodies + bj]) continue;
            v2 = 0;
            for (a = 0; a < w->dim; ++a) v2 += (vi[a] - vj[a]) * (vi[a] - vj[a]);
            if (v2 > approach2) approach2 = v2;
            sps__warn_impact(w, bi, bj, v2);
        }
    }
    w->approach = SPS__SQRT(approach2);
    return !(vmax2 <= approach2) ? SPS__SQRT(vmax2) : w->approach;
}

/* A scene that can step, with the storage its state needs (after adds: sorted by body, the
   neighbour lists, the step fields, the last good state). Allocates only after adds (or after a
   refusal). */
/* At the first step: a deformable body that starts (partly) on the solid side of a wall is
   thrown out at contact stiffness, or sinks through, so it is refused with the count. */
static sps_result sps__check_bodies_outside_walls(sps_world* w) {
    int k, bi;
    for (k = 0; k < w->nwalls; ++k)
        for (bi = 0; bi < w->nbodies; ++bi) {
            const sps__wall* wall = &w->walls[k];
            const int behind = w->bodies[bi].model.material->kinematic && !w->bodies[bi].model.free_rigid ? 0 : sps__particles_behind_wall(w, bi, k);
            if (behind == 0) continue;
            sps__set_error(w, 0, "wall %d (point (%g, %g, %g), normal (%g, %g, %g)): %d of the %d particles of body '%s' start on its "
                           "solid side ((x - point) . normal < 0); the normal points from the solid into the free side: flip it or "
                           "move the body", k, (double)wall->point[0], (double)wall->point[1], (double)wall->point[2],
                           (double)wall->normal[0], (double)wall->normal[1], (double)wall->normal[2], behind,
                           w->bodies[bi].count, w->bodies[bi].name);
            return SPS_ERR_STATE;
        }
    return SPS_OK;
}

/* At the first step: a fluid or granular body that comes within a kernel radius of a wall but
   leaves a slot of 3/4 dp or more between its surface (dp/2 beyond its particles) and the wall
   runs into it at the start, a dam break in miniature: the usual cause is a box whose size is
   not a multiple of dp (sps_body_add_box fills whole spacings from lo and leaves the rest at
   hi). Narrower slots close as the particles settle by a fraction of dp. Warned with the
   slot's width. */
static void sps__warn_slots_at_walls(const sps_world* w) {
    int k, bi, i, a;
    for (bi = 0; bi < w->nbodies; ++bi) {
        const sps__body* b = &w->bodies[bi];
        if (!b->model.mirrored) continue;
        for (k = 0; k < w->nwalls; ++k) {
            const sps__wall* wall = &w->walls[k];
            sps_real nearest = (sps_real)INFINITY;
            for (i = 0; i < w->n; ++i) {
                sps_real d = 0;
                if (w->body[i] != bi) continue;
                for (a = 0; a < w->dim; ++a) d += (w->pos[a][i] - wall->point[a]) * wall->normal[a];
                if (d < nearest) nearest = d;
            }
            if (nearest > SPS_R(1.25) * w->def.dp && nearest < w->support)
                sps__warn(w, "body '%s' comes within %g m of wall %d (normal (%g, %g, %g)) but not to dp/2 = %g m: a slot %.2g dp wide that "
                          "it runs into at the start; a box whose size is not a multiple of dp leaves one (sps_body_add_box fills whole "
                          "spacings from lo): size the fill to a multiple of dp, flush with the walls", b->name, (double)nearest, k,
                          (double)wall->normal[0], (double)wall->normal[1], (double)wall->normal[2], SPS_R(0.5) * (double)w->def.dp,
                          (double)((nearest - SPS_R(0.5) * w->def.dp) / w->def.dp));
        }
    }
}

static sps_result sps__ready_to_step(sps_world* w) {
    sps_result r;
    if ((r = sps__check_bodies_filled(w)) != SPS_OK) return r;
    if (w->needs_sort_by_body) {
        w->lists_valid = 0; /* the sort by body reorders the particles */
        if ((r = sps__commit(w)) != SPS_OK) return r == SPS_ERR_OUT_OF_MEMORY ? sps__oom(w, "the neighbour lists and step fields") : r;
        sps__set_escape_limits(w);
        if (w->free_rigid_bodies) sps__rigid_setup_bodies(w);
    }
    return sps__ensure_good_state(w);
}

/* Configuration update: neighbour lists, pair geometry and correction matrices. */
static sps_result sps__update_configuration(sps_world* w) {
    sps_result r;
    if ((r = sps__ready_to_step(w)) != SPS_OK) return r;
    if ((r = sps__check_finite(w, "configuration update")) != SPS_OK) return r;
    if ((r = sps__check_escape(w)) != SPS_OK) return r;
    if (w->periodic) sps__wrap_positions(w);
    w->lists_valid = 0;
    if ((r = sps__build_neighbors(w, NULL)) != SPS_OK) return r; /* also B_i when a body needs the velocity gradient */
    sps__tl_signal_speeds(w); /* total-Lagrangian bodies: the time step follows their deformation */
    sps__report_fragments(w);
    if ((w->contact_dirty || w->sigma_cap < w->cap) && sps__commit_contact(w) != SPS_OK) return sps__oom(w, "the contact tables");
    w->contact_dirty = 0;
    if (w->coupling_c0 > w->c0_max) w->c0_max = w->coupling_c0; /* after the bodies' own speeds (sps__tl_signal_speeds) */
    if (w->contact_bodies && (r = sps__find_contact_pairs(w)) != SPS_OK) return r;
    w->lists_valid = 1;
    sps__save_good_state(w);
    return SPS_OK;
}

/* Acoustic sub-step size at time t with maximum speed vmax: ENO eq. 26, shortened to end the
   advection step at dt_ad and to land on t_limit. Every thread computes it from its own copies
   of t and vmax, which are identical in all threads. */
static sps_real sps__substep_dt(const sps_world* w, sps_real t, sps_real vmax, int sub, sps_real elapsed, sps_real dt_ad,
                                sps_real t_limit) {
    sps_real dt = w->def.cfl_acoustic * w->h / (w->c0_max + vmax);
    if (dt > w->viscous_dt) dt = w->viscous_dt; /* Kelvin-Voigt bodies (INFINITY without) */
    if (sub > 0 && elapsed + dt > dt_ad) dt = dt_ad - elapsed;
    if (t + dt > t_limit) dt = t_limit - t;
    return dt;
}

/* The start of an advection step: the particle count's change (open boundaries), the
   configuration update, the time-step speed and the step's ends (ENO eq. 25; the travel bound
   also ends the step when the speed grows within it, so particles never move more than CFL_ad h
   between list updates). */
static sps_result sps__begin_advection_step(sps_world* w) {
    sps__advection_step* step = &w->step;
    sps_result r;
    if (w->nzones && (r = sps__open_boundaries(w)) != SPS_OK) return r; /* the count changes only here */
    if ((r = sps__update_configuration(w)) != SPS_OK) return r;
    w->advection_steps++;
    w->vmax = sps__frame_speeds(w);
    if (!(w->vmax < (sps_real)INFINITY)) { /* |v|^2 overflowed: the time step would be zero */
        sps__set_error(w, 0, "unstable at t = %g: a particle speed is so large (|v|^2 = %g) that the time step is zero",
                       (double)w->time, (double)w->vmax);
        return SPS_ERR_UNSTABLE;
    }
    if ((r = sps__check_time_step(w)) != SPS_OK) return r;
    if (!w->watch.armed) sps__watch_energy(w); /* the watchdog's start: this step's first state */
    step->travel_max = w->def.cfl_advection * w->h;
    step->dt_ad = w->vmax > 0 ? step->travel_max / w->vmax : (sps_real)INFINITY;
    if (w->viscous_speed > w->vmax) step->dt_ad = step->travel_max / w->viscous_speed; /* momentum diffuses h in h / (nu / h) */
    step->max_substeps = w->def.stepping == SPS_STEPPING_SINGLE ? 1 : w->def.max_substeps;
    step->substeps = 0;
    step->elapsed = step->travel = 0;
    return SPS_OK;
}

/* Runs acoustic sub-steps until the advection step ends, or earlier at t_limit or after
   call_cap sub-steps. may_stay_open: a frame's call (>>realtime), which continues the step a
   frame left open and leaves one open when it stops early; every other call runs whole steps
   from a fresh configuration update (a step stopped by t_limit ends there). */
static sps_result sps__step_until(sps_world* w, sps_real t_limit, int call_cap, int may_stay_open) {
    sps_result r;
    int unstable = 0;
    long steps_before;
    const int resume = may_stay_open && w->step.open && w->lists_valid && !w->needs_sort_by_body;
    if (!resume && (r = sps__begin_advection_step(w)) != SPS_OK) return r;
    w->step.open = 0; /* until the step stops early in a frame's call */
    steps_before = w->acoustic_steps;
    /* One thread team for the whole advection step: the passes are work-shared loops. Every
       thread runs this loop control on its own copies of the time and the maximum speed, which
       stay identical in all threads (the kick returns the same max |v|^2 to each), so all leave
       the loop together and no barrier is spent on shared loop state. */
    SPS__PRAGMA(omp parallel num_threads(w->threads) if (w->n > 512))
    {
        const sps__advection_step step = w->step;
        sps_real elapsed = step.elapsed, travel = step.travel, t = w->time, vmax = w->vmax, dt_last = w->dt, penalty_dt = 0;
        int sub = step.substeps, done = 0, blew_up = 0, ended = 0;
        for (;;) {
            sps_real dt = sps__substep_dt(w, t, vmax, sub, elapsed, step.dt_ad, t_limit), vmax2;
            if (!(dt > 0)) break;
            vmax2 = sps__acoustic_substep(w, t, dt, penalty_dt);
            elapsed += dt;
            ++sub;
            if (!(vmax2 < (sps_real)INFINITY)) { blew_up = 1; break; } /* same in all threads */
            penalty_dt = dt; /* its penalty is pending where it goes into the next pressure pass */
            sps__transport(w); /* UTVF eq. 42, after the step's eqs. 39-41 */
            t += dt; /* the time of the last finished sub-step */
            dt_last = dt;
            ++done;
            vmax = SPS__SQRT(vmax2);
            if (vmax < w->approach) vmax = w->approach;
            travel += vmax * dt;
            ended = sub >= step.max_substeps || elapsed >= step.dt_ad || travel >= step.travel_max;
            if (ended || t >= t_limit || done >= call_cap) break;
        }
        if (!blew_up && penalty_dt > 0) sps__pending_penalties(w, penalty_dt); /* the call returns complete */
        SPS__PRAGMA(omp barrier) /* every thread has left the loop before the shared state changes */
        SPS__PRAGMA(omp master)
        {
            unstable = blew_up;
            w->time = t;
            w->vmax = vmax;
            w->dt = dt_last;
            w->acoustic_steps += done;
            w->step.substeps = sub;
            w->step.elapsed = elapsed;
            w->step.travel = travel;
            w->step.open = may_stay_open && !ended && !blew_up && done > 0;
        }
    }
    if (unstable) {
        if (sps__check_finite(w, "acoustic step") == SPS_OK)
            sps__set_error(w, 0, "unstable at t = %g: the maximum speed is not finite", (double)w->time);
        return SPS_ERR_UNSTABLE;
    }
    if (w->acoustic_steps == steps_before && w->time < t_limit) { /* guards sps_world_advance from looping */
        sps__set_error(w, 0, "no progress at t = %g: the time step underflowed (c0 = %g m/s, max speed %g m/s, h = %g m)",
                       (double)w->time, (double)w->c0_max, (double)w->vmax, (double)w->h);
        return SPS_ERR_UNSTABLE;
    }
    if (w->pair_force) sps__keep_pair_forces(w);
    return sps__watch_energy(w);
}

/* keep_last_good_state: puts the saved state back (by particle id: a failed configuration
   update may have re-sorted the particles since) and rebuilds the neighbour lists for it, so
   diagnostics and output describe that state. The same positions fitted the capacity when
   they were saved; if the rebuild fails anyway, the lists stay marked invalid. */
static void sps__restore_good_state(sps_world* w) {
    const size_t c = (size_t)w->good_cap;
    size_t base = 0;
    int k, a, m, j;
    if (!w->good || w->good_n == 0) return;
    for (k = 0; k < SPS__NFIELDS; ++k) {
        const sps__field_info* f = &sps__fields[k];
        if (!(f->care & SPS__GOOD)) continue;
        for (a = 0; a < sps__field_arrays(f); ++a, base += (size_t)f->components) {
            const sps_real* saved = w->good + base * c;
            if (f->axes && a >= w->dim) continue;
            for (j = 0; j < w->good_n; ++j) {
                const int i = w->slot_of_id[w->good_id[j]];
                const sps__body* b = &w->bodies[w->body[i]];
                sps_real* x = sps__body_values(w, b, f, a);
                if (!x) continue;
                for (m = 0; m < f->components; ++m)
                    x[(size_t)(i - b->begin) * f->components + m] = saved[(size_t)j * f->components + m];
            }
        }
    }
    for (j = 0; j < w->good_n; ++j) { /* the volume follows from the restored density */
        const int i = w->slot_of_id[w->good_id[j]];
        w->vol[i] = w->mass[i] / w->rho[i];
    }
    for (k = 0; k < w->nbodies; ++k) /* a free rigid body's motion (what the restart file holds of it too) */
        if (w->bodies[k].model.free_rigid) {
            sps__rigid* r = &w->bodies[k].rigid;
            const sps__rigid* g = &w->bodies[k].rigid_good;
            memcpy(r->x, g->x, sizeof r->x); memcpy(r->turn, g->turn, sizeof r->turn);
            memcpy(r->v, g->v, sizeof r->v); memcpy(r->L, g->L, sizeof r->L);
            memcpy(r->applied_force, g->applied_force, sizeof r->applied_force);
            memcpy(r->applied_point, g->applied_point, sizeof r->applied_point);
            memcpy(r->force, g->force, sizeof r->force); memcpy(r->torque, g->torque, sizeof r->torque);
            r->contacts = g->contacts;
        }
    w->time = w->good_time;
    if (!w->needs_sort_by_body) w->lists_valid = sps__build_neighbors(w, NULL) == SPS_OK;
}

/* A step that fails with SPS_ERR_UNSTABLE stops the world for good: the state (or the last
   good one) stays readable, and further steps return the same error instead of going on from
   a state that is broken or (rolled back) incomplete. */
static sps_result sps__step_guarded(sps_world* w, sps_real t_limit, int call_cap, int may_stay_open) {
    sps_result r;
    if (w->stopped) {
        sps__set_error(w, 0, "the world stopped at an instability and cannot step further (read or destroy it): %s", w->failure);
        return SPS_ERR_UNSTABLE;
    }
    if (w->acoustic_steps == 0 && (r = sps__check_bodies_outside_walls(w)) != SPS_OK) return r;
    if (w->acoustic_steps == 0) sps__warn_slots_at_walls(w);
    r = sps__step_until(w, t_limit, call_cap, may_stay_open);
    if (r == SPS_OK && w->periodic) sps__wrap_positions(w); /* outputs read positions in the box */
    if (r == SPS_ERR_UNSTABLE) {
        w->stopped = 1;
        memcpy(w->failure, w->error, sizeof w->failure);
        sps__restore_good_state(w);
    }
    return r;
}

SPSDEF sps_result sps_world_step(sps_world* w) {
    if (!w) return SPS_ERR_INVALID_ARG;
    return sps__step_guarded(w, (sps_real)INFINITY, INT_MAX, 0);
}

/* A run of more than 1e10 particle sub-steps (hours on a desktop core) gets a one-line hint of
   its size before it starts, so that a t_end given in the wrong unit does not look like a hang. */
static void sps__hint_run_length(const sps_world* w, sps_real t_end) {
    const double substep = (double)(w->def.cfl_acoustic * w->h / (w->c0_max + w->vmax));
    const double substeps = (double)(t_end - w->time) / substep;
    if (w->c0_max > 0 && substeps * (double)w->n > 1e10)
        sps__warn(w, "sps_world_advance: t_end = %g s is about %.3g acoustic sub-steps of %.3g s (c0 = %g m/s) for %d particles, %.3g "
                  "particle sub-steps: a long run (sps_world_step in a loop shows progress)", (double)t_end, substeps, substep,
                  (double)w->c0_max, w->n, substeps * (double)w->n);
}

SPSDEF sps_result sps_world_advance(sps_world* w, sps_real t_end, sps_step_fn fn, void* user) {
    if (!w) return SPS_ERR_INVALID_ARG;
    if (!sps__finite(t_end)) { sps__set_error(w, 0, "sps_world_advance: t_end = %g, allowed finite", (double)t_end); return SPS_ERR_INVALID_ARG; }
    if (t_end < w->time) {
        sps__set_error(w, 0, "sps_world_advance: t_end = %g s is before the world's time %g s, allowed >= it (t_end is an absolute time: "
                       "pass sps_world_time(w) + duration)", (double)t_end, (double)w->time);
        return SPS_ERR_INVALID_ARG;
    }
    sps__hint_run_length(w, t_end);
    while (w->time < t_end) {
        sps_result r = sps__step_guarded(w, t_end, INT_MAX, 0);
        if (r != SPS_OK) return r;
        if (fn && fn(w, user)) break;
    }
    return SPS_OK;
}

/* >>validate */

/* One per-particle rule of sps_world_validate: how many particles break it, and the first. */
typedef struct { int count, first; double value; } sps__tally;
static void sps__tally_check(sps__tally* t, int ok, int i, sps_real value) {
    if (ok) return;
    if (t->count++ == 0) { t->first = i; t->value = (double)value; }
}
static void sps__tally_report(const sps_world* w, const sps__tally* t, const char* rule, char* msg, size_t msg_size, int* broken) {
    if (t->count == 0) return;
    sps__rule(msg, msg_size, broken, "%s: %d particle(s), the first id %d of body '%s' with %g", rule, t->count,
              w->id[t->first], w->bodies[w->body[t->first]].name, t->value);
}

/* The values a real field may hold, one rule for sps_world_validate and for the check of a
   restart file (chapter >>restart): finite; > 0 where marked SPS__POSITIVE (density, mass,
   volume); a state variable within the range its law keeps it in (sps__state_ranges). */
typedef struct {
    double lo, hi;
    int lo_open; /* 1: lo itself excluded; 2: any value, even NaN (sps__any_range) */
} sps__range;
static const struct {
    const char* field;
    sps__range range;
} sps__state_ranges[] = {
    {"damage", {0, 1, 0}},                 /* D starts at 0, never falls and stops at 1 (TL eq. 45) */
    {"plastic_strain", {0, HUGE_VAL, 0}}, /* accumulated from 0 by |increments| (J2, Drucker-Prager) */
    {"zone", {-1, 2147483647.0, 0}},      /* -1 or a zone's index (sps__check_zone_field: one of the particle's body) */
};
static sps__range sps__field_range(const sps__field_info* f) {
    const sps__range finite = {-HUGE_VAL, HUGE_VAL, 0}, positive = {0, HUGE_VAL, 1};
    size_t k;
    for (k = 0; k < sizeof sps__state_ranges / sizeof sps__state_ranges[0]; ++k)
        if (strcmp(sps__state_ranges[k].field, f->name) == 0) return sps__state_ranges[k].range;
    return f->care & SPS__POSITIVE ? positive : finite;
}
static int sps__in_range(const sps__range* r, sps_real v) {
    return r->lo_open == 2 || (sps__finite(v) && (r->lo_open ? v > r->lo : v >= r->lo) && v <= r->hi);
}
/* The range in words, for messages: "finite", "finite > 0", "finite >= 0", "in [0, 1]". */
static const char* sps__range_text(const sps__range* r, char* text, size_t size) {
    if (r->lo == -HUGE_VAL && r->hi == HUGE_VAL) return "finite";
    if (r->hi == HUGE_VAL) snprintf(text, size, "finite %s %g", r->lo_open ? ">" : ">=", r->lo);
    else snprintf(text, size, "in %s%g, %g]", r->lo_open ? "(" : "[", r->lo, r->hi);
    return text;
}

/* Tallies the count values (components each) of x, particle first + k at k, outside range. */
static void sps__tally_values(sps__tally* t, const sps_real* x, int first, int count, int components, const sps__range* range) {
    int k, m;
    for (k = 0; x && k < count; ++k)
        for (m = 0; m < components; ++m) {
            const sps_real v = x[(size_t)k * components + m];
            sps__tally_check(t, sps__in_range(range, v), first + k, v);
        }
}

/* Particles: every value of the fields marked SPS__VALIDATED in its range (sps__field_range),
   ids a permutation, body indices in range. */
static void sps__validate_particles(const sps_world* w, char* msg, size_t msg_size, int* broken) {
    sps__tally id = {0, 0, 0};
    char rule[64];
    int i, k, a;
    for (i = 0; i < w->n; ++i)
        if (w->body[i] < 0 || w->body[i] >= w->nbodies) { /* the reports name the body: not this one */
            sps__rule(msg, msg_size, broken, "particle in slot %d: body index %d, allowed [0, %d)", i, w->body[i], w->nbodies);
            return;
        }
    for (k = 0; k < SPS__NFIELDS; ++k) {
        const sps__field_info* f = &sps__fields[k];
        const sps__range range = sps__field_range(f);
        sps__tally t = {0, 0, 0};
        char text[32];
        int bi;
        if (!(f->care & SPS__VALIDATED)) continue;
        for (a = 0; a < (f->axes ? w->dim : 1); ++a) {
            if (!f->per_body) sps__tally_values(&t, sps__real_array(w, NULL, f, a), 0, w->n, f->components, &range);
            else /* a body's arrays hold its particles of the last commit (none before the first step) */
                for (bi = 0; bi < w->nbodies; ++bi)
                    sps__tally_values(&t, sps__real_array(w, &w->bodies[bi], f, a), w->bodies[bi].begin, w->bodies[bi].field_count, f->components, &range);
        }
        snprintf(rule, sizeof rule, "%s not %s", f->what, sps__range_text(&range, text, sizeof text));
        sps__tally_report(w, &t, rule, msg, msg_size, broken);
    }
    for (i = 0; i < w->n; ++i) sps__tally_check(&id, w->id[i] >= 0 && w->id[i] < w->n && w->slot_of_id[w->id[i]] == i, i, w->id[i]);
    sps__tally_report(w, &id, "id not a permutation of 0..n-1", msg, msg_size, broken);
}

/* Constraints and observers refer to existing tables, particles and bodies. */
static void sps__validate_links(const sps_world* w, char* msg, size_t msg_size, int* broken) {
    int k, i, a;
    for (k = 0; k < w->ncons; ++k) {
        const sps__constraint* c = &w->constraints[k];
        if (c->mask == 0 || c->mask > SPS_AXIS_ALL) sps__rule(msg, msg_size, broken, "constraint %d: mask = %u, allowed 1..7", k, c->mask);
        for (a = 0; a < 3; ++a)
            if (!sps__finite(c->velocity[a])) sps__rule(msg, msg_size, broken, "constraint %d: velocity[%d] = %g, allowed finite", k, a, (double)c->velocity[a]);
    }
    for (i = 0; w->zone && i < w->n; ++i)
        if (!sps__zone_index_valid(w, i, w->zone[i])) {
            sps__rule(msg, msg_size, broken, "particle id %d: zone %g, allowed -1 or an inflow or outflow zone of its body", w->id[i], (double)w->zone[i]);
            break;
        }
    for (i = 0; w->cons && i < w->n; ++i)
        if (w->cons[i] < -1 || w->cons[i] >= w->ncons) {
            sps__rule(msg, msg_size, broken, "particle id %d: constraint index %d, allowed -1 (none) or [0, %d)", w->id[i], w->cons[i], w->ncons);
            break;
        }
    for (k = 0; k < w->nobs; ++k) {
        const sps__observer* o = &w->observers[k];
        sps_real sum = 0;
        if (o->body < 0 || o->body >= w->nbodies || o->first < 0 || o->count < 1 || o->first + o->count > w->obs_len) {
            sps__rule(msg, msg_size, broken, "observer %d: body %d, weights [%d, %d), allowed a body of [0, %d) and weights within [0, %d)",
                      k, o->body, o->first, o->first + o->count, w->nbodies, w->obs_len);
            continue;
        }
        for (i = o->first; i < o->first + o->count; ++i) {
            int id = w->obs_ids[i];
            if (id < 0 || id >= w->n || w->body[w->slot_of_id[id]] != o->body) {
                sps__rule(msg, msg_size, broken, "observer %d: particle id %d is not a particle of its body '%s'", k, id, w->bodies[o->body].name);
                break;
            }
            sum += w->obs_weights[i];
        }
        /* Shepard weights sum to one; 1e-6: a few hundred weights summed in float */
        if (!(sum > 1 - SPS_R(1e-6) && sum < 1 + SPS_R(1e-6)))
            sps__rule(msg, msg_size, broken, "observer %d: weights sum to %g, allowed 1", k, (double)sum);
    }
}

SPSDEF sps_result sps_world_validate(const sps_world* w, char* msg, size_t msg_size) {
    char sub[768];
    int broken = 0, k;
    if (msg && msg_size) msg[0] = 0;
    if (!w) { sps__rule(msg, msg_size, &broken, "world is NULL"); return SPS_ERR_INVALID_ARG; }
    if (sps_world_def_check(&w->def, sub, sizeof sub) != SPS_OK) sps__rule(msg, msg_size, &broken, "world def: %s", sub);
    for (k = 0; k < w->nbodies; ++k) {
        const sps__body* b = &w->bodies[k];
        sub[0] = 0;
        if (sps__body_def_check(w->dim, &b->def, sub, sizeof sub) != SPS_OK) sps__rule(msg, msg_size, &broken, "body '%s': %s", b->name, sub);
        if (b->count == 0) sps__rule(msg, msg_size, &broken, "body '%s' (index %d) has no particles", b->name, k);
    }
    sps__validate_particles(w, msg, msg_size, &broken);
    sps__validate_links(w, msg, msg_size, &broken);
    if (w->stopped) sps__rule(msg, msg_size, &broken, "stopped at an instability: %s", w->failure);
    return broken ? SPS_ERR_STATE : SPS_OK;
}

/* >>diagnostics */

/* Whether particle i has a value in its body's own arrays: they hold the body's particles of
   the last commit (none before the first step); those added since have none yet. */
static int sps__in_body_arrays(const sps__body* b, int i) { return i >= b->begin && i - b->begin < b->field_count; }

/* The Cauchy stress sigma = -p I + tau of particle i (xx xy xz yy yz zz; tau = 0 where the body
   does not track it). In 2D sigma_zz is not part of the state: 0. */
static void sps__cauchy_stress(const sps_world* w, int i, sps_real s[6]) {
    const sps__body* b = &w->bodies[w->body[i]];
    int a;
    for (a = 0; a < 6; ++a) s[a] = b->tau && sps__in_body_arrays(b, i) ? b->tau[(size_t)6 * (i - b->begin) + a] : 0;
    s[0] -= w->p[i]; s[3] -= w->p[i];
    if (w->dim == 3) s[5] -= w->p[i];
    else s[5] = 0;
}

static sps_real sps__von_mises(const sps_world* w, int i) {
    sps_real s[6];
    sps__cauchy_stress(w, i, s);
    if (w->dim == 2) return SPS__SQRT(s[0] * s[0] + s[3] * s[3] - s[0] * s[3] + 3 * s[1] * s[1]);
    return SPS__SQRT(SPS_R(0.5) * ((s[0] - s[3]) * (s[0] - s[3]) + (s[3] - s[5]) * (s[3] - s[5]) + (s[5] - s[0]) * (s[5] - s[0])) +
                     3 * (s[1] * s[1] + s[2] * s[2] + s[4] * s[4]));
}

/* The equivalent plastic strain of particle i (0 unless its body is plastic, and for particles
   added since the last commit). */
static sps_real sps__plastic_strain(const sps_world* w, int i) {
    const sps__body* b = &w->bodies[w->body[i]];
    return b->plastic_strain && i - b->begin < b->field_count ? b->plastic_strain[i - b->begin] : 0;
}
/* Particle i's damage D (0 unless its body has damage). */
static sps_real sps__damage(const sps_world* w, int i) {
    const sps__body* b = &w->bodies[w->body[i]];
    return b->damage && i - b->begin < b->field_count ? b->damage[i - b->begin] : 0;
}

/* The displacement and velocity gradients Gu_i, Gv_i (9 each, zero outside dim x dim) of
   particle i with its correction matrix B_i. dim is a literal (2 or 3), so the small loops over
   the axes unroll (the caller's parallel loop picks the dim: inside a function with its own
   parallel loop, OpenMP would outline the loop before the literal reached it). */
SPS__INLINE void sps__diagnostic_gradients(const sps_world* w, int i, const sps_real* B, sps_real* Gu, sps_real* Gv, const int dim) {
    sps_real M[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, Mv[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    int k, a, c, m;
    for (k = 0; k < w->nb_count[i]; ++k) {
        int j = sps__neighbor(w, i, k);
        sps_real d[3] = {0, 0, 0}, r2 = 0, r, f;
        r2 = sps__pair_offset(w, i, j, d);
        r = SPS__SQRT(r2);
        f = r > 0 ? sps__dwdr(w, r) / r * w->vol[j] : 0; /* particles at one point: no direction (sps__pair) */
        for (a = 0; a < dim; ++a) {
            sps_real uij = sps__relative_displacement(w, i, j, a, d[a]);
            const sps_real vij = w->vel[a][i] - w->vel[a][j];
            for (c = 0; c < dim; ++c) M[3 * a + c] -= uij * d[c] * f;
            for (c = 0; c < dim; ++c) Mv[3 * a + c] -= vij * d[c] * f;
        }
    }
    for (a = 0; a < 3; ++a)
        for (c = 0; c < 3; ++c) {
            sps_real s = 0, sv = 0;
            for (m = 0; m < dim; ++m) s += M[3 * a + m] * B[(size_t)9 * i + 3 * c + m];
            for (m = 0; m < dim; ++m) sv += Mv[3 * a + m] * B[(size_t)9 * i + 3 * c + m];
            Gu[(size_t)9 * i + 3 * a + c] = a < dim && c < dim ? s : 0;
            Gv[(size_t)9 * i + 3 * a + c] = a < dim && c < dim ? sv : 0;
        }
}

/* The pair sums of the two indicators over the pairs of [begin, end), serial in a fixed order
   (deterministic): sum[0] |u_ij - Gu r_ij|, sum[1] r_ij, sum[2] |v_ij - Gv r_ij|, sum[3]
   |Gv r_ij| (the gradients averaged over i and j). Returns the smallest squared pair distance,
   -1 without pairs. dim is a literal (2 or 3). */
SPS__INLINE sps_real sps__hourglass_sums(const sps_world* w, int begin, int end, const sps_real* Gu, const sps_real* Gv, sps_real sum[4],
                                         const int dim) {
    sps_real num = 0, den = 0, rmin2 = -1, zig_num = 0, zig_den = 0;
    int i;
    for (i = begin; i < end; ++i) {
        int k, a, c;
        for (k = 0; k < w->nb_count[i]; ++k) {
            int j = sps__neighbor(w, i, k);
            sps_real d[3] = {0, 0, 0}, r2 = 0, e2 = 0, ev2 = 0, smooth2 = 0;
            r2 = sps__pair_offset(w, i, j, d);
            for (a = 0; a < dim; ++a) {
                sps_real err = sps__relative_displacement(w, i, j, a, d[a]);
                sps_real smooth = 0; /* the relative velocity the velocity gradient gives the pair */
                for (c = 0; c < dim; ++c) err -= SPS_R(0.5) * (Gu[(size_t)9 * i + 3 * a + c] + Gu[(size_t)9 * j + 3 * a + c]) * d[c];
                for (c = 0; c < dim; ++c) smooth += SPS_R(0.5) * (Gv[(size_t)9 * i + 3 * a + c] + Gv[(size_t)9 * j + 3 * a + c]) * d[c];
                e2 += err * err;
                ev2 += (w->vel[a][i] - w->vel[a][j] - smooth) * (w->vel[a][i] - w->vel[a][j] - smooth);
                smooth2 += smooth * smooth;
            }
            num += SPS__SQRT(e2);
            zig_num += SPS__SQRT(ev2);
            zig_den += SPS__SQRT(smooth2);
            den += SPS__SQRT(r2);
            if (rmin2 < 0 || r2 < rmin2) rmin2 = r2;
        }
    }
    sum[0] = num;
    sum[1] = den;
    sum[2] = zig_num;
    sum[3] = zig_den;
    return rmin2;
}

/* Hourglass indicator and zigzag indicator (see DIAGNOSTICS) of the particles [begin, end) (whole
   bodies): displacement and velocity gradients with B from current positions; also the smallest
   spacing and the count of surface particles. Only the range is computed: a call for one body
   costs that body's pairs. */
static sps_real sps__hourglass(sps_world* w, int begin, int end, sps_real* min_spacing, int* surface, sps_real* zigzag) {
    sps_real *B = w->diag_scratch, *Gu = w->diag_scratch + (size_t)9 * w->cap, *divr = w->diag_scratch + (size_t)18 * w->cap;
    sps_real* Gv = w->diag_scratch + (size_t)19 * w->cap;
    sps_real sum[4], rmin2;
    int i;
    sps__correction_matrices(w, begin, end, B, divr);
    *surface = 0;
    for (i = begin; i < end; ++i) *surface += divr[i] < SPS_R(0.75) * w->dim;
    /* a body's neighbours are of the same body: a range of whole bodies needs nothing outside it */
    SPS__PARALLEL_FOR(w, end - begin)
    for (i = begin; i < end; ++i) {
        if (w->dim == 2) sps__diagnostic_gradients(w, i, B, Gu, Gv, 2);
        else sps__diagnostic_gradients(w, i, B, Gu, Gv, 3);
    }
    rmin2 = w->dim == 2 ? sps__hourglass_sums(w, begin, end, Gu, Gv, sum, 2) : sps__hourglass_sums(w, begin, end, Gu, Gv, sum, 3);
    *min_spacing = rmin2 < 0 ? 0 : SPS__SQRT(rmin2) / w->def.dp;
    /* no velocity gradient anywhere: no zigzag if nothing moves relative to anything, else all is */
    *zigzag = sum[3] > 0 ? sum[2] / sum[3] : sum[2] > 0 ? (sps_real)INFINITY : 0;
    return sum[1] > 0 ? sum[0] / sum[1] : 0;
}

SPSDEF sps_result sps_world_diagnostics(sps_world* w, sps_body body, sps_diagnostics* out) {
    int begin = 0, end, i, a, bi, k = -1;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (!out) { sps__set_error(w, 0, "sps_world_diagnostics: out must not be NULL"); return SPS_ERR_INVALID_ARG; }
    memset(out, 0, sizeof *out);
    end = w->n;
    if (body.id != 0) {
        if ((k = sps__check_body(w, body, "sps_world_diagnostics")) < 0) return SPS_ERR_INVALID_ARG;
    }
    if (w->needs_sort_by_body || !w->lists_valid) {
        sps_result r = sps__update_configuration(w); /* lists for the hourglass indicator */
        if (r != SPS_OK) return r;
    }
    if (k >= 0) { begin = w->bodies[k].begin; end = w->bodies[k].end; }
    if (w->diag_cap < w->cap) {
        sps__free(w, w->diag_scratch);
        w->diag_scratch = (sps_real*)sps__alloc(w, sizeof(sps_real) * 28 * (size_t)w->cap);
        if (!w->diag_scratch) { w->diag_cap = 0; return sps__oom(w, "sps_world_diagnostics: the scratch"); }
        w->diag_cap = w->cap;
    }
    out->time = w->time;
    out->acoustic_steps = w->acoustic_steps;
    out->advection_steps = w->advection_steps;
    out->dt_acoustic = w->dt;
    out->particles = end - begin;
    out->min_density = end > begin ? w->rho[begin] : 0;
    out->max_density = out->min_density;
    for (i = begin; i < end; ++i) { /* serial: a fixed summation order */
        const sps__body* b = &w->bodies[w->body[i]];
        sps_real m = w->mass[i], v2 = 0, x[3], v[3], kinetic, strain;
        for (a = 0; a < 3; ++a) {
            x[a] = w->pos[a][i];
            v[a] = a < w->dim ? w->vel[a][i] : 0;
            v2 += v[a] * v[a];
        }
        sps__particle_energies(w, b, i, 1, &kinetic, &strain);
        if (b->model.free_rigid) { /* the body's motion, once (sps__rigid_energies) */
            sps_real potential = 0, p[3] = {0, 0, 0}, l[3] = {0, 0, 0};
            kinetic = 0;
            if (i == b->begin) sps__rigid_energies(w, b, &kinetic, &potential, p, l);
            out->potential_energy += potential;
            for (a = 0; a < 3; ++a) {
                out->linear_momentum[a] += p[a];
                out->angular_momentum[a] += l[a];
            }
        } else {
            for (a = 0; a < 3; ++a) out->linear_momentum[a] += m * v[a];
            out->angular_momentum[0] += m * (x[1] * v[2] - x[2] * v[1]);
            out->angular_momentum[1] += m * (x[2] * v[0] - x[0] * v[2]);
            out->angular_momentum[2] += m * (x[0] * v[1] - x[1] * v[0]);
        }
        out->kinetic_energy += kinetic;
        out->strain_energy += strain;
        if (!b->model.material->kinematic)
            for (a = 0; a < w->dim; ++a) out->potential_energy -= m * w->def.gravity[a] * x[a];
        if (w->contact_bodies || w->nwalls > 0) out->contact_energy += sps__contact_energy(w, i);
        if (b->model.plastic && i - b->begin < b->field_count) { /* particles added since the last commit have none yet */
            const sps_real alpha = b->plastic_strain[i - b->begin];
            out->plastic_work += b->plastic_work[i - b->begin];
            if (alpha > out->max_plastic_strain) out->max_plastic_strain = alpha;
        }
        if (b->viscous_work && i - b->begin < b->field_count) out->viscous_work += b->viscous_work[i - b->begin];
        if (SPS__SQRT(v2) > out->max_speed) out->max_speed = SPS__SQRT(v2);
        if (w->rho[i] < out->min_density) out->min_density = w->rho[i];
        if (w->rho[i] > out->max_density) out->max_density = w->rho[i];
    }
    for (bi = 0; bi < w->nbodies; ++bi) {
        const sps__body* b = &w->bodies[bi];
        for (i = 0; b->driven_work && (k < 0 || bi == k) && i < b->end - b->begin; ++i) out->prescribed_work += b->driven_work[i];
    }
    out->hourglass = sps__hourglass(w, begin, end, &out->min_spacing, &out->surface_particles, &out->zigzag);
    out->energy_growth = w->watch.worst;
    out->energy_growth_events = w->watch.events;
    out->warnings = w->warnings_issued;
    return SPS_OK;
}

SPSDEF const char* sps_diagnostics_csv_header(void) {
    return "time,kinetic_energy,strain_energy,total_energy,momentum_x,momentum_y,momentum_z,"
           "angular_momentum_x,angular_momentum_y,angular_momentum_z,max_speed,min_density,max_density,"
           "hourglass,min_spacing,acoustic_steps,advection_steps,dt_acoustic,contact_energy,potential_energy,prescribed_work,"
           "plastic_work,max_plastic_strain,surface_particles,viscous_work,zigzag";
}

SPSDEF int sps_diagnostics_csv_row(const sps_diagnostics* d, char* buf, size_t size) {
    if (!d || (!buf && size)) return -1;
    /* total_energy: kinetic + strain + plastic work + viscous work */
    return snprintf(buf, size, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6g,%.6g,%ld,%ld,%.6g,%.9g,%.9g,%.9g,%.9g,%.6g,%d,%.9g,%.6g",
                    (double)d->time, (double)d->kinetic_energy, (double)d->strain_energy,
                    (double)(d->kinetic_energy + d->strain_energy + d->plastic_work + d->viscous_work), (double)d->linear_momentum[0],
                    (double)d->linear_momentum[1], (double)d->linear_momentum[2], (double)d->angular_momentum[0],
                    (double)d->angular_momentum[1], (double)d->angular_momentum[2], (double)d->max_speed,
                    (double)d->min_density, (double)d->max_density, (double)d->hourglass, (double)d->min_spacing, d->acoustic_steps,
                    d->advection_steps, (double)d->dt_acoustic, (double)d->contact_energy, (double)d->potential_energy,
                    (double)d->prescribed_work, (double)d->plastic_work, (double)d->max_plastic_strain, d->surface_particles,
                    (double)d->viscous_work, (double)d->zigzag);
}

/* >>access */

/* The field row and axis of a public field name ("density", "velocity_x", ...); NULL (and the
   error set, naming the caller fn) if it is unknown, an int field or an axis beyond dim. */
static const sps__field_info* sps__field_of_name(const sps_world* w, const char* fn, const char* name, int* axis) {
    static const char* const suffix[3] = {"_x", "_y", "_z"};
    const sps__field_info* f = NULL;
    char base[64];
    size_t len;
    int k;
    *axis = 0;
    if (!name) { sps__set_error_const(w, "%s: name is NULL", fn); return NULL; }
    len = strlen(name);
    for (k = 0; k < 3 && !f; ++k) /* a per-axis name: the field's name and the axis' suffix */
        if (len > 2 && len < sizeof base && strcmp(name + len - 2, suffix[k]) == 0) {
            memcpy(base, name, len - 2);
            base[len - 2] = 0;
            if ((f = sps__field_named(base)) && f->axes) *axis = k;
            else f = NULL;
        }
    if (!f && (f = sps__field_named(name)) && f->axes) f = NULL;
    if (!f || f->is_int) {
        char names[768] = "";
        size_t used = 0;
        for (k = 0; k < SPS__NFIELDS && used < sizeof names; ++k)
            if (!sps__fields[k].is_int)
                used += (size_t)snprintf(names + used, sizeof names - used, "%s%s%s", used ? ", " : "", sps__fields[k].name,
                                         sps__fields[k].axes ? "_x/_y/_z" : "");
        sps__set_error_const(w, "%s: name = '%s', allowed %s", fn, name, names);
        return NULL;
    }
    if (*axis >= w->dim) { sps__set_error_const(w, "%s: '%s' with dim = %d", fn, name, w->dim); return NULL; }
    return f;
}

SPSDEF const sps_real* sps_world_field_by_name(const sps_world* w, const char* name, int* components) {
    const sps__field_info* f;
    int axis;
    if (components) *components = 0;
    if (!w || !(f = sps__field_of_name(w, "sps_world_field_by_name", name, &axis))) return NULL;
    if (f->per_body) {
        sps__set_error_const(w, "sps_world_field_by_name: '%s' is kept per body (only bodies whose model needs it have it): use sps_body_field", name);
        return NULL;
    }
    if (components) *components = f->components;
    return sps__real_array(w, NULL, f, axis);
}

SPSDEF const sps_real* sps_body_field(const sps_world* w, sps_body body, const char* name, int* components, int* first, int* count) {
    const sps__field_info* f;
    const sps__body* b;
    const sps_real* x;
    int axis, k = sps__body_slot(w, body);
    if (components) *components = 0;
    if (first) *first = 0;
    if (count) *count = 0;
    if (!w) return NULL;
    if (k < 0) { sps__set_error_const(w, "sps_body_field: body handle %u is not a body of this world", (unsigned)body.id); return NULL; }
    if (!(f = sps__field_of_name(w, "sps_body_field", name, &axis))) return NULL;
    b = &w->bodies[k];
    if (w->needs_sort_by_body) { sps__set_error_const(w, "sps_body_field: particles were added since the last step: step first"); return NULL; }
    if (!(x = sps__body_values(w, b, f, axis))) {
        sps__set_error_const(w, "sps_body_field: body '%s' has no '%s' (its model does not need it)%s", b->name, name,
                             f->need == SPS__NEED_STRESS || f->need == SPS__NEED_GRADIENT
                                 ? "; an ENO or ENO-A body integrates the stress (and the velocity gradient) with track_stress = 1 in its body def"
                                 : "");
        return NULL;
    }
    if (components) *components = f->components;
    if (first) *first = b->begin;
    if (count) *count = b->end - b->begin;
    return x;
}

SPSDEF const sps_real* sps_world_field(const sps_world* w, sps_field f) {
    static const char* const names[] = {"position_x", "position_y", "position_z", "velocity_x", "velocity_y", "velocity_z",
                                        "reference_x", "reference_y", "reference_z", "density", "pressure", "mass"};
    if (!w) return NULL;
    if ((int)f < 0 || f > SPS_FIELD_MASS) {
        sps__set_error_const(w, "sps_world_field: field = %d, allowed 0..%d (SPS_FIELD_POSITION_X..SPS_FIELD_MASS)", (int)f, (int)SPS_FIELD_MASS);
        return NULL;
    }
    if (f <= SPS_FIELD_REFERENCE_Z && (int)f % 3 >= w->dim) return NULL; /* z in 2D: NULL, not an error */
    return sps_world_field_by_name(w, names[f], NULL);
}

SPSDEF const int* sps_world_particle_ids(const sps_world* w) { return w ? w->id : NULL; }

SPSDEF sps_result sps_world_particle(const sps_world* w, int id, sps_particle_state* out) {
    int i, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (!out || id < 0 || id >= w->n) {
        sps__set_error_const(w, "sps_world_particle: id = %d with out %s, allowed id in [0, %d) and out != NULL", id, out ? "set" : "NULL", w->n);
        return SPS_ERR_INVALID_ARG;
    }
    i = w->slot_of_id[id];
    memset(out, 0, sizeof *out);
    for (a = 0; a < w->dim; ++a) {
        out->position[a] = w->pos[a][i];
        out->velocity[a] = w->vel[a][i];
        out->displacement[a] = w->pos[a][i] - w->ref[a][i];
    }
    out->density = w->rho[i];
    out->pressure = w->p[i];
    out->von_mises = sps__von_mises(w, i);
    out->body_index = w->body[i];
    out->plastic_strain = sps__plastic_strain(w, i);
    out->damage = sps__damage(w, i);
    return SPS_OK;
}

SPSDEF sps_result sps_world_set_particle(sps_world* w, int id, const sps_real position[3], const sps_real velocity[3]) {
    int i, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (id < 0 || id >= w->n || (position && !sps__finite_point(w, position)) || (velocity && !sps__finite_point(w, velocity))) {
        sps__set_error(w, 0, "sps_world_set_particle: id = %d, position %s, velocity %s; allowed id in [0, %d) and finite values", id,
                       !position ? "NULL" : sps__finite_point(w, position) ? "finite" : "not finite",
                       !velocity ? "NULL" : sps__finite_point(w, velocity) ? "finite" : "not finite", w->n);
        return SPS_ERR_INVALID_ARG;
    }
    i = w->slot_of_id[id];
    if (velocity) {
        const sps_real before = sps__kinetic(w, i);
        for (a = 0; a < w->dim; ++a) w->vel[a][i] = velocity[a];
        sps__watch_adjust(w, w->body[i], sps__kinetic(w, i) - before, 0);
    }
    if (position) { /* moves its contacts and strain: the watchdog starts anew */
        for (a = 0; a < w->dim; ++a) w->pos[a][i] = position[a];
        sps__rearm_watchdog(w);
    }
    return SPS_OK;
}

SPSDEF int sps_world_nearest_particle(const sps_world* w, sps_body b, const sps_real x[3]) {
    int k = sps__body_slot(w, b), i, a, best = -1;
    sps_real best_d2 = 0;
    if (!w) return -1;
    if (k < 0 || !sps__finite_point(w, x)) {
        sps__set_error_const(w, "sps_world_nearest_particle: body handle %u%s, x %s; allowed a body of this world and a finite x",
                             (unsigned)b.id, k < 0 ? " (not a body of this world)" : "", !x ? "NULL" : sps__finite_point(w, x) ? "finite" : "not finite");
        return -1;
    }
    for (i = 0; i < w->n; ++i) {
        sps_real d2 = 0;
        if (w->body[i] != k) continue;
        for (a = 0; a < w->dim; ++a) d2 += (w->ref[a][i] - x[a]) * (w->ref[a][i] - x[a]);
        if (best < 0 || d2 < best_d2) { best = w->id[i]; best_d2 = d2; }
    }
    return best;
}

/* >>observers */

SPSDEF sps_result sps_world_add_observer(sps_world* w, sps_body b, const sps_real x[3], sps_observer* out) {
    int k, i, a, count = 0;
    sps_real wsum = 0;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (out) out->id = 0;
    if ((k = sps__check_body(w, b, "sps_world_add_observer")) < 0) return SPS_ERR_INVALID_ARG;
    if (w->nzones > 0) {
        sps__set_error(w, 0, "sps_world_add_observer: the world has %d open-boundary zones, whose removals renumber the particle ids an "
                       "observer holds; allowed: observers without zones", w->nzones);
        return SPS_ERR_INVALID_ARG;
    }
    if (!out || !sps__finite_point(w, x)) {
        sps__set_error(w, 0, "sps_world_add_observer: x %s and out %s, allowed a finite x and out != NULL",
                       x ? "set" : "NULL", out ? "set" : "NULL");
        return SPS_ERR_INVALID_ARG;
    }
    for (i = 0; i < w->n; ++i) {
        sps_real d2 = 0;
        if (w->body[i] != k) continue;
        for (a = 0; a < w->dim; ++a) d2 += (w->ref[a][i] - x[a]) * (w->ref[a][i] - x[a]);
        if (d2 < w->support * w->support) ++count;
    }
    if (count == 0) { sps__set_error(w, 0, "sps_world_add_observer: no particle of body '%s' within 2h of (%g, %g, %g)", w->bodies[k].name, (double)x[0], (double)x[1], (double)x[2]); return SPS_ERR_INVALID_ARG; }
    if (!sps__grow(w, &w->obs_ids, sizeof(int), (size_t)w->obs_len, (size_t)(w->obs_len + count)) ||
        !sps__grow(w, &w->obs_weights, sizeof(sps_real), (size_t)w->obs_len, (size_t)(w->obs_len + count)) ||
        !sps__grow(w, &w->observers, sizeof(sps__observer), (size_t)w->nobs, (size_t)w->nobs + 1))
        return sps__oom(w, "sps_world_add_observer: the observer tables");
    w->observers[w->nobs].body = k;
    w->observers[w->nobs].first = w->obs_len;
    w->observers[w->nobs].count = count;
    for (i = 0; i < w->n; ++i) { /* Shepard weights W(X - X_j) V_j / sum, reference configuration */
        sps_real d2 = 0;
        if (w->body[i] != k) continue;
        for (a = 0; a < w->dim; ++a) d2 += (w->ref[a][i] - x[a]) * (w->ref[a][i] - x[a]);
        if (d2 >= w->support * w->support) continue;
        w->obs_ids[w->obs_len] = w->id[i];
        w->obs_weights[w->obs_len] = sps_world_kernel(w, SPS__SQRT(d2)) * (w->mass[i] / w->bodies[k].rho0);
        wsum += w->obs_weights[w->obs_len];
        w->obs_len++;
    }
    for (i = w->observers[w->nobs].first; i < w->obs_len; ++i) w->obs_weights[i] /= wsum;
    w->nobs++;
    out->id = ((uint32_t)w->tag << 16) | (uint32_t)w->nobs;
    return SPS_OK;
}

SPSDEF sps_result sps_observer_read(const sps_world* w, sps_observer o, sps_real displacement[3], sps_real velocity[3]) {
    int idx = (int)(o.id & 0xffff) - 1, s, a;
    const sps__observer* ob;
    if (!w) return SPS_ERR_INVALID_ARG;
    if ((o.id >> 16) != w->tag || idx < 0 || idx >= w->nobs) {
        sps__set_error_const(w, "sps_observer_read: observer handle %u is not an observer of this world", (unsigned)o.id);
        return SPS_ERR_INVALID_ARG;
    }
    ob = &w->observers[idx];
    for (a = 0; a < 3; ++a) {
        if (displacement) displacement[a] = 0;
        if (velocity) velocity[a] = 0;
    }
    for (s = ob->first; s < ob->first + ob->count; ++s) {
        int i = w->slot_of_id[w->obs_ids[s]];
        sps_real f = w->obs_weights[s];
        for (a = 0; a < w->dim; ++a) {
            if (displacement) displacement[a] += f * (w->pos[a][i] - w->ref[a][i]);
            if (velocity) velocity[a] += f * w->vel[a][i];
        }
    }
    return SPS_OK;
}

/* >>output */

#ifndef SPHSOLID_NO_STDIO
/* The point-data arrays of the VTK files, one row each: an array is either a row of sps__fields
   (a per-body one is 0 for the bodies without it), or computed per particle by value. A new
   output is one row. */
/* When a row of sps__vtk_arrays is written: always, with sps_vtk_options.stress, or when a
   body is plastic (J2), total-Lagrangian, or has damage, or the world has zones. */
typedef enum { SPS__VTK_ALWAYS, SPS__VTK_WITH_STRESS, SPS__VTK_IF_PLASTIC, SPS__VTK_IF_TOTAL_LAGRANGIAN, SPS__VTK_IF_DAMAGE, SPS__VTK_IF_ZONES } sps__vtk_shown_when;
typedef struct sps__vtk_array {
    const char* name;
    int components; /* per point (a per-axis field: 3, z = 0 in 2D) */
    int is_int;
    const char* field; /* the sps__fields row it shows, or NULL */
    void (*value)(const sps_world* w, int i, sps_real* out); /* for field NULL */
    sps__vtk_shown_when shown;
} sps__vtk_array;

static void sps__vtk_displacement(const sps_world* w, int i, sps_real* out) {
    int a;
    for (a = 0; a < 3; ++a) out[a] = a < w->dim ? w->pos[a][i] - w->ref[a][i] : 0;
}
static void sps__vtk_von_mises(const sps_world* w, int i, sps_real* out) { out[0] = sps__von_mises(w, i); }
static void sps__vtk_plastic_strain(const sps_world* w, int i, sps_real* out) { out[0] = sps__plastic_strain(w, i); }
static void sps__vtk_stress(const sps_world* w, int i, sps_real* out) { /* the full tensor, row-major */
    static const int of[9] = {0, 1, 2, 1, 3, 4, 2, 4, 5};
    sps_real s[6];
    int k;
    sps__cauchy_stress(w, i, s);
    for (k = 0; k < 9; ++k) out[k] = s[of[k]];
}

static const sps__vtk_array sps__vtk_arrays[] = {
    {"velocity", 3, 0, "velocity", NULL, SPS__VTK_ALWAYS},
    {"displacement", 3, 0, NULL, sps__vtk_displacement, SPS__VTK_ALWAYS},
    {"pressure", 1, 0, "pressure", NULL, SPS__VTK_ALWAYS},
    {"density", 1, 0, "density", NULL, SPS__VTK_ALWAYS},
    {"von_mises", 1, 0, NULL, sps__vtk_von_mises, SPS__VTK_ALWAYS},
    {"stress", 9, 0, NULL, sps__vtk_stress, SPS__VTK_WITH_STRESS},
    {"plastic_strain", 1, 0, NULL, sps__vtk_plastic_strain, SPS__VTK_IF_PLASTIC},
    {"deformation_gradient", 9, 0, "deformation_gradient", NULL, SPS__VTK_IF_TOTAL_LAGRANGIAN},
    {"damage", 1, 0, "damage", NULL, SPS__VTK_IF_DAMAGE},
    {"body", 1, 1, "body", NULL, SPS__VTK_ALWAYS},
    {"id", 1, 1, "id", NULL, SPS__VTK_ALWAYS},
    {"zone", 1, 0, "zone", NULL, SPS__VTK_IF_ZONES},
};
#define SPS__VTK_ARRAYS ((int)(sizeof sps__vtk_arrays / sizeof sps__vtk_arrays[0]))

/* Whether a row of sps__vtk_arrays is written for world w with options opt. */
static int sps__vtk_shown(const sps_world* w, const sps__vtk_array* row, const sps_vtk_options* opt) {
    int bi;
    if (row->shown == SPS__VTK_WITH_STRESS) return opt->stress;
    for (bi = 0; row->shown == SPS__VTK_IF_PLASTIC && bi < w->nbodies; ++bi)
        if (w->bodies[bi].model.plastic) return 1;
    for (bi = 0; row->shown == SPS__VTK_IF_TOTAL_LAGRANGIAN && bi < w->nbodies; ++bi)
        if (w->bodies[bi].model.total_lagrangian) return 1;
    for (bi = 0; row->shown == SPS__VTK_IF_DAMAGE && bi < w->nbodies; ++bi)
        if (w->bodies[bi].model.damage) return 1;
    if (row->shown == SPS__VTK_IF_ZONES) return w->nzones > 0;
    return row->shown == SPS__VTK_ALWAYS;
}

/* The values of registry field f for particle i into out (components of the VTK array). */
static void sps__vtk_field_values(const sps_world* w, const sps__field_info* f, int i, int components, double* out) {
    const sps__body* b = &w->bodies[w->body[i]];
    const int owned = !f->per_body || sps__in_body_arrays(b, i), at = f->per_body ? i - b->begin : i;
    int a, m;
    for (m = 0; m < components; ++m) out[m] = 0;
    if (!owned) return;
    if (f->is_int) {
        out[0] = sps__int_array(w, f, 0)[at];
        return;
    }
    for (a = 0; a < (f->axes ? w->dim : 1); ++a) {
        const sps_real* x = sps__real_array(w, b, f, a);
        for (m = 0; x && m < f->components && a + m < components; ++m) out[a + m] = x[(size_t)at * f->components + m];
    }
}

/* Writes the values of a legacy VTK file: ASCII text (9 significant digits, a point per line),
   or binary, big-endian as the format requires, through a buffer. */
typedef struct sps__vtk_out {
    FILE* f;
    int binary, single, little_endian, fresh; /* single: reals as 32-bit floats */
    const char* real_type;                    /* "double" or "float" */
    size_t used;
    unsigned char buf[8192];
} sps__vtk_out;
static void sps__vtk_flush(sps__vtk_out* o) {
    if (o->used) fwrite(o->buf, 1, o->used, o->f);
    o->used = 0;
}
static void sps__vtk_bytes(sps__vtk_out* o, const void* v, size_t size) {
    const unsigned char* c = (const unsigned char*)v;
    size_t k;
    if (o->used + size > sizeof o->buf) sps__vtk_flush(o);
    for (k = 0; k < size; ++k) o->buf[o->used++] = c[o->little_endian ? size - 1 - k : k];
}
static void sps__vtk_value(sps__vtk_out* o, double v, int is_int) {
    if (o->binary && is_int) {
        const int32_t x = (int32_t)v;
        sps__vtk_bytes(o, &x, sizeof x);
    } else if (o->binary && o->single) {
        const float x = (float)v;
        sps__vtk_bytes(o, &x, sizeof x);
    } else if (o->binary) {
        const sps_real x = (sps_real)v;
        sps__vtk_bytes(o, &x, sizeof x);
    } else {
        fprintf(o->f, is_int ? "%s%.0f" : "%s%.9g", o->fresh ? "" : " ", o->single && !is_int ? (double)(float)v : v);
        o->fresh = 0;
    }
}
static void sps__vtk_end_point(sps__vtk_out* o) {
    if (!o->binary) fputc('\n', o->f);
    o->fresh = 1;
}
static void sps__vtk_end_block(sps__vtk_out* o) { /* a binary block ends with a newline */
    sps__vtk_flush(o);
    if (o->binary) fputc('\n', o->f);
}

static void sps__vtk_write_array(const sps_world* w, const sps__vtk_array* row, sps__vtk_out* o) {
    const sps__field_info* f = row->field ? sps__field_named(row->field) : NULL;
    double v[9];
    sps_real r[9];
    int i, m;
    fprintf(o->f, "%s %d %d %s\n", row->name, row->components, w->n, row->is_int ? "int" : o->real_type);
    SPS_ASSERT(!row->field || f); /* a row names a field of sps__fields */
    for (i = 0; i < w->n; ++i) {
        if (f) sps__vtk_field_values(w, f, i, row->components, v);
        else {
            row->value(w, i, r);
            for (m = 0; m < row->components; ++m) v[m] = (double)r[m];
        }
        for (m = 0; m < row->components; ++m) sps__vtk_value(o, v[m], row->is_int);
        sps__vtk_end_point(o);
    }
    sps__vtk_end_block(o);
}

SPSDEF sps_vtk_options sps_default_vtk_options(void) {
    sps_vtk_options o;
    memset(&o, 0, sizeof o);
    return o;
}

SPSDEF sps_result sps_world_write_vtk_ex(sps_world* w, const char* path, const sps_vtk_options* options) {
    const sps_vtk_options opt = options ? *options : sps_default_vtk_options();
    const uint16_t one = 1;
    sps__vtk_out o;
    int i, k, arrays = 0, a;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (!path) { sps__set_error(w, 0, "sps_world_write_vtk: path must not be NULL"); return SPS_ERR_INVALID_ARG; }
    if ((opt.binary != 0 && opt.binary != 1) || (opt.single_precision != 0 && opt.single_precision != 1) || (opt.stress != 0 && opt.stress != 1)) {
        sps__set_error(w, 0, "sps_world_write_vtk_ex: options binary = %d, single_precision = %d, stress = %d, each allowed 0 or 1",
                       opt.binary, opt.single_precision, opt.stress);
        return SPS_ERR_INVALID_ARG;
    }
    o.f = fopen(path, opt.binary ? "wb" : "w");
    if (!o.f) { sps__set_error(w, 0, "sps_world_write_vtk: cannot open '%s' for writing", path); return SPS_ERR_IO; }
    o.binary = opt.binary;
    o.single = opt.single_precision && sizeof(sps_real) > sizeof(float);
    o.real_type = o.single || sizeof(sps_real) == sizeof(float) ? "float" : "double";
    o.little_endian = *(const unsigned char*)&one == 1;
    o.fresh = 1;
    o.used = 0;
    fprintf(o.f, "# vtk DataFile Version 3.0\nsphsolid %s t=%.9g\n%s\nDATASET POLYDATA\nPOINTS %d %s\n", SPHSOLID_VERSION_STRING,
            (double)w->time, opt.binary ? "BINARY" : "ASCII", w->n, o.real_type);
    for (i = 0; i < w->n; ++i) {
        for (a = 0; a < 3; ++a) sps__vtk_value(&o, a < w->dim ? (double)w->pos[a][i] : 0, 0);
        sps__vtk_end_point(&o);
    }
    sps__vtk_end_block(&o);
    fprintf(o.f, "VERTICES %d %d\n", w->n, 2 * w->n);
    for (i = 0; i < w->n; ++i) {
        sps__vtk_value(&o, 1, 1);
        sps__vtk_value(&o, i, 1);
        sps__vtk_end_point(&o);
    }
    sps__vtk_end_block(&o);
    for (k = 0; k < SPS__VTK_ARRAYS; ++k) arrays += sps__vtk_shown(w, &sps__vtk_arrays[k], &opt);
    /* a FIELD block: the legacy reader shows every array of it (with SCALARS and VECTORS it
       shows only the first of each) */
    fprintf(o.f, "POINT_DATA %d\nFIELD FieldData %d\n", w->n, arrays);
    for (k = 0; k < SPS__VTK_ARRAYS; ++k)
        if (sps__vtk_shown(w, &sps__vtk_arrays[k], &opt)) sps__vtk_write_array(w, &sps__vtk_arrays[k], &o);
    if (ferror(o.f) | (fclose(o.f) != 0)) { sps__set_error(w, 0, "sps_world_write_vtk: error writing '%s'", path); return SPS_ERR_IO; }
    return SPS_OK;
}

SPSDEF sps_result sps_world_write_vtk(sps_world* w, const char* path) { return sps_world_write_vtk_ex(w, path, NULL); }

/* The series file's closing lines: an entry is added by overwriting them with a comma, the
   entry and them again, so the file is valid JSON after every snapshot. */
static const char sps__series_tail[] = "\n  ]\n}\n";

/* Adds file `file` at time t to the series file `path`; first: a new series. */
static sps_result sps__series_add(sps_world* w, const char* path, const char* file, double t, int first) {
    const long tail = (long)(sizeof sps__series_tail - 1);
    char seen[sizeof sps__series_tail];
    FILE* f = fopen(path, first ? "wb" : "r+b");
    if (!f) {
        sps__set_error(w, 0, "sps_world_write_vtk_series: cannot open '%s'%s", path, first ? " for writing" : " (index > 0 appends to the series that index 0 started)");
        return SPS_ERR_IO;
    }
    if (first) {
        fputs("{\n  \"file-series-version\" : \"1.0\",\n  \"files\" : [\n", f);
    } else if (fseek(f, -tail, SEEK_END) != 0 || fread(seen, 1, (size_t)tail, f) != (size_t)tail || memcmp(seen, sps__series_tail, (size_t)tail) != 0 ||
               fseek(f, -tail, SEEK_END) != 0) {
        fclose(f);
        sps__set_error(w, 0, "sps_world_write_vtk_series: '%s' does not end as a series file this function writes: start the series with index 0", path);
        return SPS_ERR_IO;
    }
    fprintf(f, "%s    { \"name\" : \"%s\", \"time\" : %.17g }%s", first ? "" : ",\n", file, t, sps__series_tail);
    if (ferror(f) | (fclose(f) != 0)) { sps__set_error(w, 0, "sps_world_write_vtk_series: error writing '%s'", path); return SPS_ERR_IO; }
    return SPS_OK;
}

SPSDEF sps_result sps_world_write_vtk_series(sps_world* w, const char* dir, const char* name, int index, const sps_vtk_options* options) {
    char vtk_path[4096], series_path[4096], file[4096];
    const char* sep;
    const char* c;
    sps_result r;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (!dir || !name || !*name) { sps__set_error(w, 0, "sps_world_write_vtk_series: dir and name must not be NULL, name not empty"); return SPS_ERR_INVALID_ARG; }
    if (index < 0) { sps__set_error(w, 0, "sps_world_write_vtk_series: index = %d, allowed >= 0", index); return SPS_ERR_INVALID_ARG; }
    for (c = name; *c; ++c)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '_' || *c == '-' || *c == '.')) {
            sps__set_error(w, 0, "sps_world_write_vtk_series: name '%s' has the character '%c': allowed letters, digits, '_', '-' and '.'", name, *c);
            return SPS_ERR_INVALID_ARG;
        }
    sep = *dir && dir[strlen(dir) - 1] != '/' ? "/" : "";
    if (snprintf(file, sizeof file, "%s_%04d.vtk", name, index) >= (int)sizeof file ||
        snprintf(vtk_path, sizeof vtk_path, "%s%s%s", dir, sep, file) >= (int)sizeof vtk_path ||
        snprintf(series_path, sizeof series_path, "%s%s%s.vtk.series", dir, sep, name) >= (int)sizeof series_path) {
        sps__set_error(w, 0, "sps_world_write_vtk_series: the path in '%s' of '%s' is longer than %d characters", dir, name, (int)sizeof vtk_path - 1);
        return SPS_ERR_INVALID_ARG;
    }
    if ((r = sps_world_write_vtk_ex(w, vtk_path, options)) != SPS_OK) return r;
    return sps__series_add(w, series_path, file, (double)w->time, index == 0);
}
#endif

/* >>restart: sps_world_save and sps_world_restore (RESTART in the manual)

   A restart file holds what the next step reads and cannot rebuild: the time and step counters,
   every per-particle array the configuration update carries (the rows of sps__fields marked
   SPS__CARRIED; the others are rebuilt before they are read) in the current particle order
   (the order is state too: the next update's stable sort by cell starts from it), each body's
   mean rotation and spin (the next kick reads the spin), the pair forces kept for the next list
   rebuild (SPS_ROTATION_PAIR), the last good state (keep_last_good_state), the stopped flag,
   and the neighbour lists of the last update, so that diagnostics read right after a restore
   see the same pairs as the uninterrupted run. Callbacks, walls, constraints, observers and
   contact settings are the scene's: the program rebuilds them before it restores.
   Layout (native byte order and sps_real, both recorded):
     header       magic, byte-order mark, format version, sizeof(sps_real), payload bytes
     fingerprint  the world items of sps__world_print, a hash of the scene (reference
                  positions, masses, bodies and constraints by particle id), the body items of
                  sps__body_print for each body: all must equal the world's
     payload      the state (sps__transfer_state, one list of items for both ways), then its
                  FNV-1a hash */
#ifndef SPHSOLID_NO_STDIO

static const char sps__restart_magic[16] = {'s', 'p', 'h', 's', 'o', 'l', 'i', 'd', '-', 'r', 'e', 's', 't', 'a', 'r', 't'};
#define SPS__RESTART_BYTE_ORDER 0x01020304u
#define SPS__RESTART_VERSION 8u /* 2: the fingerprint holds every def item (sps__world_def_items); 3: contact_rest and free rigid bodies; 4: the periodic axes; 5: material.yield_cone and open-boundary zones; 6: fluid_dissipation, transport_carries_velocity; 7: lattice; 8: the body items grouped by the material def's sub-structs (material.j2, .fluid, .granular, .tl) */
#define SPS__FNV_OFFSET 14695981039346656037ULL

/* FNV-1a, 64 bits: the payload's checksum and the scene hash. */
static uint64_t sps__fnv(uint64_t hash, const void* data, size_t size) {
    const unsigned char* c = (const unsigned char*)data;
    size_t k;
    for (k = 0; k < size; ++k) hash = (hash ^ c[k]) * 1099511628211ULL;
    return hash;
}

/* The world items of the fingerprint: the def items (the causes, named first), then the counts
   that lay out the state. */
static const char* const sps__world_count_names[] = {"particle count", "body count", "wall count", "constraint count", "contact pairs turned off",
                                                      "zone count"};
#define SPS__WORLD_PRINT (SPS__WORLD_DEF_ITEMS + (int)(sizeof sps__world_count_names / sizeof sps__world_count_names[0]))
static const char* sps__world_print_name(int k) {
    return k < SPS__WORLD_DEF_ITEMS ? sps__world_def_items[k].name : sps__world_count_names[k - SPS__WORLD_DEF_ITEMS];
}
static void sps__world_print(const sps_world* w, double v[SPS__WORLD_PRINT]) {
    double* counts = v + SPS__WORLD_DEF_ITEMS;
    int k;
    for (k = 0; k < SPS__WORLD_DEF_ITEMS; ++k) v[k] = sps__def_value(&w->def, &sps__world_def_items[k]);
    counts[0] = w->built ? w->built_n : w->n; /* with zones: as built (the state's own count is in the payload) */
    counts[1] = w->nbodies; counts[2] = w->nwalls; counts[3] = w->ncons; counts[4] = w->nseparate; counts[5] = w->nzones;
}
/* ... and those of each body: its def items, then its particle count. */
#define SPS__BODY_PRINT (SPS__BODY_DEF_ITEMS + 1)
static const char* sps__body_print_name(int k) { return k < SPS__BODY_DEF_ITEMS ? sps__body_def_items[k].name : "particle count"; }
static void sps__body_print(const sps__body* b, double v[SPS__BODY_PRINT]) {
    int k;
    for (k = 0; k < SPS__BODY_DEF_ITEMS; ++k) v[k] = sps__def_value(&b->def, &sps__body_def_items[k]);
    v[SPS__BODY_DEF_ITEMS] = b->built_count > 0 ? b->built_count : b->count;
}
/* ... and those of each zone: its def (the callback by whether there is one). */
static const char* const sps__zone_print_names[] = {"body", "kind", "lo[0]", "lo[1]", "lo[2]", "hi[0]", "hi[1]", "hi[2]", "axis", "direction",
                                                    "velocity[0]", "velocity[1]", "velocity[2]", "velocity_fn set", "pressure"};
#define SPS__ZONE_PRINT ((int)(sizeof sps__zone_print_names / sizeof sps__zone_print_names[0]))
static void sps__zone_print(const sps__zone* z, double v[SPS__ZONE_PRINT]) {
    const sps_zone_def* d = &z->def;
    int a;
    v[0] = z->body; v[1] = (double)d->kind;
    for (a = 0; a < 3; ++a) { v[2 + a] = d->lo[a]; v[5 + a] = d->hi[a]; v[10 + a] = d->velocity[a]; }
    v[8] = d->axis; v[9] = d->direction; v[13] = d->velocity_fn != NULL; v[14] = d->pressure;
}
/* The scene as built: body, reference position, mass and constraint of each particle by id,
   from the world's arrays or (restoring) from a payload's, as bytes: the same hash of either. */
typedef struct sps__scene_arrays {
    const unsigned char *body, *ref[3], *mass, *cons; /* cons NULL: no constraints */
} sps__scene_arrays;
static uint64_t sps__scene_hash_of(const sps_world* w, const int* slot_of_id, const sps__scene_arrays* at) {
    uint64_t hash = SPS__FNV_OFFSET;
    int id, a;
    for (id = 0; id < w->n; ++id) {
        const size_t i = (size_t)slot_of_id[id];
        hash = sps__fnv(hash, at->body + i * sizeof(int), sizeof(int));
        for (a = 0; a < w->dim; ++a) hash = sps__fnv(hash, at->ref[a] + i * sizeof(sps_real), sizeof(sps_real));
        hash = sps__fnv(hash, at->mass + i * sizeof(sps_real), sizeof(sps_real));
        if (at->cons) hash = sps__fnv(hash, at->cons + i * sizeof(int), sizeof(int));
    }
    return hash;
}
static uint64_t sps__scene_hash(const sps_world* w) {
    sps__scene_arrays at;
    int a;
    at.body = (const unsigned char*)w->body;
    for (a = 0; a < 3; ++a) at.ref[a] = (const unsigned char*)w->ref[a];
    at.mass = (const unsigned char*)w->mass;
    at.cons = (const unsigned char*)w->cons;
    return sps__scene_hash_of(w, w->slot_of_id, &at);
}

/* Block m of the last good state of good_n particles that holds values, in
   sps__save_good_state's layout (field by field, one block per axis up to dim, each
   good_n * components values from its start), its length in reals and its field; NULL past
   the last. */
static sps_real* sps__good_block(const sps_world* w, int good_n, int m, size_t* length, const sps__field_info** field) {
    size_t base = 0;
    int k, a;
    for (k = 0; k < SPS__NFIELDS; ++k) {
        const sps__field_info* f = &sps__fields[k];
        if (!(f->care & SPS__GOOD)) continue;
        for (a = 0; a < sps__field_arrays(f); ++a, base += (size_t)f->components)
            if (!(f->axes && a >= w->dim) && m-- == 0) {
                *length = (size_t)good_n * (size_t)f->components;
                *field = f;
                return w->good + base * (size_t)w->good_cap;
            }
    }
    return NULL;
}

/* Where the state goes: a file (hashed as written), memory (mem: the payload, checked before
   it is written), or nowhere (both NULL: only counts the bytes). */
typedef struct sps__writer {
    FILE* f;
    unsigned char* mem;
    uint64_t bytes, hash;
    int failed;
} sps__writer;
static void sps__put(sps__writer* s, const void* data, size_t size) {
    if (s->mem) memcpy(s->mem + s->bytes, data, size);
    s->bytes += size;
    if (!s->f || s->failed) return;
    s->hash = sps__fnv(s->hash, data, size);
    if (fwrite(data, 1, size, s->f) != size) s->failed = 1;
}
static void sps__put_int(sps__writer* s, int v) { sps__put(s, &v, sizeof v); }

/* Where the state comes from: the payload in memory. A file is untrusted (damaged and its
   checksum recomputed, or crafted): nothing of it reaches the world before every rule below
   holds on the payload itself, so that a refused file leaves the world as it was and a
   restored world passes sps_world_validate. The payload is read three times, by the same
   list of items (sps__transfer_state):
     SPS__READ_LAYOUT  every length and count, and every index: the ids a permutation of
                       0..n-1, each particle in the body its slot lies in, the constraint
                       indices, the neighbour lists (within the particle's own body, not the
                       particle itself, none for a wall body), the kept pairs' and the last
                       good state's ids, the flags;
     SPS__READ_VALUES  every real within the range the library keeps it in (the fields':
                       sps__field_range, as sps_world_validate checks them), after the layout
                       so that a message can name the particle by its id; then the bodies,
                       reference positions, masses and constraints by id against the header's
                       scene hash (sps__check_scene);
     SPS__READ_APPLY   the same reads, into the world.
   The first rule broken is reported: the item, the particle or body, the value, the range. */
enum { SPS__READ_LAYOUT, SPS__READ_VALUES, SPS__READ_APPLY };
typedef struct sps__reader {
    const unsigned char* at;
    size_t left;
    int pass;          /* SPS__READ_* */
    const char* bad;   /* the item found wrong, or NULL */
    char why[320];     /* what is wrong with it; empty when it is its length */
    int id_field;      /* the index of field "id" in sps__fields */
    int* slot_of_id;   /* the file's ids inverted (n of them), built by SPS__READ_LAYOUT */
    unsigned char* seen; /* the last good state's ids met so far (n) */
    const unsigned char* field_at[SPS__NFIELDS]; /* a world field's first array in the payload, once its rule held */
    long kept_pairs;   /* the kept pair forces in the payload (their storage is grown to them before SPS__READ_APPLY) */
    const unsigned char* lists; /* the neighbour lists in the payload (sps__transfer_lists) */
} sps__reader;
static int sps__applying(const sps__reader* r) { return r->pass == SPS__READ_APPLY; }
/* The first broken rule: the item, and what is wrong with it. */
static void sps__refuse(sps__reader* r, const char* what, const char* fmt, ...) {
    va_list ap;
    if (r->bad) return;
    r->bad = what;
    va_start(ap, fmt);
    vsnprintf(r->why, sizeof r->why, fmt, ap);
    va_end(ap);
}
static const unsigned char* sps__take(sps__reader* r, size_t size, const char* what) {
    const unsigned char* p = r->at;
    if (r->bad) return NULL;
    if (size > r->left) { r->bad = what; return NULL; }
    r->at += size;
    r->left -= size;
    return p;
}
/* Value k of an array in the payload (which aligns nothing: copied out). */
static sps_real sps__real_at(const unsigned char* p, size_t k) {
    sps_real v;
    memcpy(&v, p + k * sizeof v, sizeof v);
    return v;
}
static int sps__int_at(const unsigned char* p, size_t k) {
    int v;
    memcpy(&v, p + k * sizeof v, sizeof v);
    return v;
}
/* A count always read (a dry run needs it too), checked against [0, limit]. */
static int sps__get_count(sps__reader* r, int limit, const char* what) {
    const unsigned char* p = sps__take(r, sizeof(int), what);
    int v = 0;
    if (p) memcpy(&v, p, sizeof v);
    if (!r->bad && (v < 0 || v > limit)) sps__refuse(r, what, "%s = %d, allowed [0, %d]", what, v, limit);
    return r->bad ? 0 : v;
}
/* The particle in slot i, for messages: its id once the ids have been checked, and its body. */
static const char* sps__particle_name(const sps_world* w, const sps__reader* r, int i, char* text, size_t size) {
    const unsigned char* ids = r->field_at[r->id_field];
    if (ids) snprintf(text, size, "particle id %d (body '%s')", sps__int_at(ids, (size_t)i), w->bodies[w->body[i]].name);
    else snprintf(text, size, "the particle in slot %d (body '%s')", i, w->bodies[w->body[i]].name);
    return text;
}
/* Refuses real value v of item `what` (axis a, or -1) of the particle in slot i: out of range. */
static void sps__refuse_value(const sps_world* w, sps__reader* r, const char* what, int a, int i, sps_real v, const sps__range* range) {
    char name[96], text[32];
    sps__refuse(r, what, "%s%s of %s = %g, allowed %s", what, a < 0 ? "" : a == 0 ? "[0]" : a == 1 ? "[1]" : "[2]",
                sps__particle_name(w, r, i, name, sizeof name), (double)v, sps__range_text(range, text, sizeof text));
}

/* The payload goes one way: out (sps_world_save) or in (sps_world_restore). Its items are
   listed once, in sps__transfer_state, for both ways, so the layout written is the layout read. */
typedef struct sps__stream {
    sps__writer* out; /* saving: the writer; NULL when reading */
    sps__reader* in;  /* restoring: the reader; NULL when writing */
} sps__stream;
static int sps__stream_bad(const sps__stream* s) { return s->in && s->in->bad; }
/* An int in [0, limit]: written, or read (always, a dry run needs it too), checked and, when
   the reader applies, stored. Returns the value. */
static int sps__count_item(sps__stream* s, int* v, int limit, const char* what) {
    int read;
    if (s->out) { sps__put_int(s->out, *v); return *v; }
    read = sps__get_count(s->in, limit, what);
    if (sps__applying(s->in) && !s->in->bad) *v = read;
    return read;
}
/* count reals in range: written, or read, checked and (applying) stored. Of body bi, or of the
   world (bi < 0). */
static const sps__range sps__finite_range = {-HUGE_VAL, HUGE_VAL, 0}, sps__nonnegative_range = {0, HUGE_VAL, 0};
/* The energy watchdog's account may overflow in a run at extreme values (a state the guards
   let through gives inf, inf - inf gives NaN); it is only compared, so it is taken as written. */
static const sps__range sps__any_range = {-HUGE_VAL, HUGE_VAL, 2};
static void sps__real_item(sps__stream* s, sps_world* w, int bi, sps_real* x, int count, const sps__range* range, const char* what) {
    const size_t bytes = sizeof(sps_real) * (size_t)count;
    const unsigned char* p;
    int k;
    if (s->out) { sps__put(s->out, x, bytes); return; }
    if (!(p = sps__take(s->in, bytes, what))) return;
    if (sps__applying(s->in)) memcpy(x, p, bytes);
    else if (s->in->pass == SPS__READ_VALUES)
        for (k = 0; k < count; ++k) {
            const sps_real v = sps__real_at(p, (size_t)k);
            char text[32], index[16] = "", body[64] = "";
            if (sps__in_range(range, v)) continue;
            if (count > 1) snprintf(index, sizeof index, "[%d]", k);
            if (bi >= 0) snprintf(body, sizeof body, " of body %d ('%s')", bi, w->bodies[bi].name);
            sps__refuse(s->in, what, "%s%s%s = %g, allowed %s", what, index, body, (double)v, sps__range_text(range, text, sizeof text));
            return;
        }
}
/* A step counter (int64_t or long, size bytes): written, or read, checked >= 0 and within a
   long (the world's counters), and (applying) stored. */
static void sps__counter_item(sps__stream* s, void* x, size_t size, const char* what) {
    const int64_t long_max = (int64_t)(~0UL >> 1); /* LONG_MAX, without <limits.h> */
    const unsigned char* p;
    int64_t v;
    if (s->out) { sps__put(s->out, x, size); return; }
    if (!(p = sps__take(s->in, size, what))) return;
    if (sps__applying(s->in)) { memcpy(x, p, size); return; }
    if (size == sizeof(long)) {
        long l;
        memcpy(&l, p, sizeof l);
        v = l;
    } else memcpy(&v, p, sizeof v);
    if (v < 0 || v > long_max) sps__refuse(s->in, what, "%s = %.0f, allowed [0, %.0f]", what, (double)v, (double)long_max);
}
/* A message of size bytes: written, or read, checked to end within them, and (applying)
   stored. Returns its first character (0 when empty or refused). */
static char sps__text_item(sps__stream* s, char* x, size_t size, const char* what) {
    const unsigned char* p;
    if (s->out) { sps__put(s->out, x, size); return x[0]; }
    if (!(p = sps__take(s->in, size, what))) return 0;
    if (sps__applying(s->in)) memcpy(x, p, size);
    else if (!memchr(p, 0, size)) sps__refuse(s->in, what, "%s has no end within its %u bytes", what, (unsigned)size);
    return s->in->bad ? 0 : (char)p[0];
}

/* SPS__READ_LAYOUT: the file's ids (slot order) are a permutation of 0..n-1; inverted into
   r->slot_of_id. */
static void sps__check_ids(const sps_world* w, sps__reader* r, const unsigned char* ids) {
    char name[96];
    int i;
    for (i = 0; i < w->n; ++i) r->slot_of_id[i] = -1;
    for (i = 0; i < w->n; ++i) {
        const int id = sps__int_at(ids, (size_t)i);
        if (id < 0 || id >= w->n || r->slot_of_id[id] >= 0) {
            sps__refuse(r, "id", "id of %s = %d, allowed a permutation of 0..%d (%s)", sps__particle_name(w, r, i, name, sizeof name), id,
                        w->n - 1, id < 0 || id >= w->n ? "out of range" : "a duplicate");
            return;
        }
        r->slot_of_id[id] = i;
    }
}
/* SPS__READ_LAYOUT: a carried int field, by its rule; one without a rule here is refused, so
   that a new one cannot pass unchecked (give it its rule). */
static void sps__check_int_field(const sps_world* w, sps__reader* r, const sps__field_info* f, const unsigned char* p) {
    char name[96];
    int i;
    if (f == &sps__fields[r->id_field]) sps__check_ids(w, r, p);
    else if (strcmp(f->name, "body") == 0) { /* the layout the world was committed in: the counts are the header's */
        for (i = 0; i < w->n; ++i)
            if (sps__int_at(p, (size_t)i) != w->body[i]) {
                const sps__body* b = &w->bodies[w->body[i]];
                sps__refuse(r, f->what, "body of %s = %d, allowed %d (its slot %d lies in body %d's slots [%d, %d))",
                            sps__particle_name(w, r, i, name, sizeof name), sps__int_at(p, (size_t)i), w->body[i], i, w->body[i], b->begin, b->end);
                return;
            }
    } else if (strcmp(f->name, "constraint") == 0) { /* sps_world_validate's rule */
        for (i = 0; i < w->n; ++i)
            if (sps__int_at(p, (size_t)i) < -1 || sps__int_at(p, (size_t)i) >= w->ncons) {
                sps__refuse(r, f->what, "constraint index of %s = %d, allowed -1 (none) or [0, %d)", sps__particle_name(w, r, i, name, sizeof name),
                            sps__int_at(p, (size_t)i), w->ncons);
                return;
            }
    } else sps__refuse(r, f->what, "%s: no rule checks this field of a restart file (sps__check_int_field)", f->what);
}
/* SPS__READ_VALUES: the values of array a (of dim, or -1 for a one-array field) of real field
   f, particles first .. first + count - 1, within the field's range. */
static void sps__check_real_field(const sps_world* w, sps__reader* r, const sps__field_info* f, int a, const unsigned char* p, int first,
                                  int count) {
    const sps__range range = sps__field_range(f);
    const size_t values = (size_t)count * (size_t)f->components;
    char name[96];
    size_t k;
    for (k = 0; k < values; ++k)
        if (!sps__in_range(&range, sps__real_at(p, k))) {
            sps__refuse_value(w, r, f->what, a, first + (int)(k / (size_t)f->components), sps__real_at(p, k), &range);
            return;
        }
    for (k = 0; f->need == SPS__NEED_ZONES && a < 0 && k < values; ++k) /* the zone index: -1 or a zone of the particle's body */
        if (!sps__zone_index_valid(w, first + (int)k, sps__real_at(p, k))) {
            sps__refuse(r, f->what, "zone of %s = %g, allowed -1 or a zone of its body (%d zones)", sps__particle_name(w, r, first + (int)k, name, sizeof name),
                        (double)sps__real_at(p, k), w->nzones);
            return;
        }
}
/* Array a of field f (count particles: of body b, or of the world) from the payload into x:
   checked by the dry runs, copied when applying. */
static void sps__read_field(sps_world* w, const sps__body* b, const sps__field_info* f, int a, void* x, int count, sps__reader* r) {
    const size_t bytes = sps__field_bytes(f) * (size_t)count;
    const unsigned char* p = sps__take(r, bytes, f->what);
    if (!p) return;
    if (sps__applying(r)) memcpy(x, p, bytes);
    else if (f->is_int && r->pass == SPS__READ_LAYOUT) sps__check_int_field(w, r, f, p);
    else if (!f->is_int && r->pass == SPS__READ_VALUES) sps__check_real_field(w, r, f, f->axes ? a : -1, p, b ? b->begin : 0, count);
    if (!f->per_body && a == 0 && !r->bad) r->field_at[f - sps__fields] = p;
}

/* The arrays of field f for body b (per-body fields) or the world (b NULL): count values per
   array, the axes up to dim; a leading byte tells whether they exist (the models decide it: a
   file that disagrees is damaged). */
static void sps__transfer_field(sps_world* w, sps__body* b, const sps__field_info* f, int count, sps__stream* s) {
    const int arrays = f->axes ? w->dim : 1;
    void* first;
    unsigned char present;
    int a;
    memcpy(&first, sps__field_slot(w, b, f, 0), sizeof first);
    present = first != NULL;
    if (s->out) sps__put(s->out, &present, 1);
    else {
        const unsigned char* in_file = sps__take(s->in, 1, f->what);
        if (in_file && (*in_file != 0) != present) s->in->bad = f->what;
    }
    for (a = 0; a < arrays && present && !sps__stream_bad(s); ++a) {
        void* x;
        memcpy(&x, sps__field_slot(w, b, f, a), sizeof x);
        if (s->out) sps__put(s->out, x, sps__field_bytes(f) * (size_t)count);
        else sps__read_field(w, b, f, a, x, count, s->in);
    }
}

/* The neighbour lists: counts, then each particle's neighbours, each count and index checked: a
   neighbour is a particle of the same body other than itself (the passes index the body's
   arrays with it), and a wall body has no lists (sps__read_lists). Applying reads the counts
   into nb_count and notes where the neighbours are: sps__restore places them in the lane slots
   from the payload (sps__build_neighbors). */
static void sps__transfer_lists(sps_world* w, sps__stream* s) {
    const unsigned char* counts;
    char name[96];
    int i, m;
    if (s->out) {
        sps__put(s->out, w->nb_count, sizeof(int) * (size_t)w->n);
        for (i = 0; i < w->n; ++i)
            for (m = 0; m < w->nb_count[i]; ++m) sps__put_int(s->out, sps__neighbor(w, i, m));
        return;
    }
    counts = sps__take(s->in, sizeof(int) * (size_t)w->n, "neighbour counts");
    s->in->lists = s->in->at;
    for (i = 0; i < w->n && counts && !s->in->bad; ++i) {
        const sps__body* b = &w->bodies[w->body[i]];
        const int count = sps__int_at(counts, (size_t)i), limit = b->model.material->kinematic ? 0 : w->ell_width;
        if (count < 0 || count > limit) {
            sps__refuse(s->in, "neighbour counts", "neighbour count of %s = %d, allowed [0, %d]%s", sps__particle_name(w, s->in, i, name, sizeof name),
                        count, limit, limit ? "" : " (a wall body has no neighbour lists)");
            break;
        }
        if (sps__applying(s->in)) w->nb_count[i] = count;
        for (m = 0; m < count && !s->in->bad; ++m) {
            const int j = sps__get_count(s->in, w->n - 1, "neighbours");
            if (!sps__applying(s->in) && !s->in->bad && (j < b->begin || j >= b->end || j == i))
                sps__refuse(s->in, "neighbours", "neighbour %d of %s: slot %d, allowed a slot of its body, [%d, %d), other than its own (%d)", m,
                            sps__particle_name(w, s->in, i, name, sizeof name), j, b->begin, b->end, i);
        }
    }
}

/* SPS_ROTATION_PAIR: the kept pair forces of `kept` ids, laid out by id: the counts, then each
   id's neighbour ids and forces (at most a full list each, ids in range, forces finite). */
static void sps__transfer_kept_forces(sps_world* w, int kept, sps__stream* s) {
    const unsigned char *counts, *ids, *forces;
    long first = 0;
    int id, k;
    if (s->out) {
        sps__put(s->out, w->kept_count, sizeof(int) * (size_t)kept);
        for (id = 0; id < kept; ++id) {
            sps__put(s->out, w->kept_neighbor_id + w->kept_first[id], sizeof(int) * (size_t)w->kept_count[id]);
            sps__put(s->out, w->kept_force + w->kept_first[id], sizeof(sps_real) * (size_t)w->kept_count[id]);
        }
        return;
    }
    counts = sps__take(s->in, sizeof(int) * (size_t)kept, "kept pair counts");
    for (id = 0; id < kept && counts && !s->in->bad; ++id) {
        const int count = sps__int_at(counts, (size_t)id);
        if (count < 0 || count > w->ell_width) {
            sps__refuse(s->in, "kept pair counts", "kept pair count of particle id %d = %d, allowed [0, %d]", id, count, w->ell_width);
            break;
        }
        if (sps__applying(s->in)) { w->kept_first[id] = (int)first; w->kept_count[id] = count; }
        ids = sps__take(s->in, sizeof(int) * (size_t)count, "kept pairs");
        forces = sps__take(s->in, sizeof(sps_real) * (size_t)count, "kept pair forces");
        if (!forces) break;
        if (sps__applying(s->in)) {
            memcpy(w->kept_neighbor_id + first, ids, sizeof(int) * (size_t)count);
            memcpy(w->kept_force + first, forces, sizeof(sps_real) * (size_t)count);
        }
        for (k = 0; k < count && !sps__applying(s->in) && !s->in->bad; ++k) {
            const int j = sps__int_at(ids, (size_t)k);
            const sps_real g = sps__real_at(forces, (size_t)k);
            if (j < 0 || j >= w->n)
                sps__refuse(s->in, "kept pairs", "kept pair %d of particle id %d: neighbour id %d, allowed [0, %d)", k, id, j, w->n);
            else if (s->in->pass == SPS__READ_VALUES && !sps__finite(g))
                sps__refuse(s->in, "kept pair forces", "kept pair force %d of particle id %d = %g, allowed finite", k, id, (double)g);
        }
        first += count;
    }
    s->in->kept_pairs = first;
}

/* keep_last_good_state: the copy of the last configuration update of good_n particles: its
   time, its ids (distinct, in range), its blocks (sps__good_block), each value in its field's
   range. */
static void sps__rigid_transfer(sps__stream* s, sps_world* w, int bi, sps__rigid* r);
static void sps__transfer_good(sps_world* w, int good_n, sps__stream* s) {
    const unsigned char *ids = NULL, *p;
    const sps__field_info* f;
    sps_real* block;
    size_t length, k;
    int m, j;
    sps__real_item(s, w, -1, &w->good_time, 1, &sps__nonnegative_range, "last good time");
    if (s->out) sps__put(s->out, w->good_id, sizeof(int) * (size_t)good_n);
    else if ((ids = sps__take(s->in, sizeof(int) * (size_t)good_n, "last good ids")) != NULL) {
        if (sps__applying(s->in)) memcpy(w->good_id, ids, sizeof(int) * (size_t)good_n);
        else if (s->in->pass == SPS__READ_LAYOUT) {
            memset(s->in->seen, 0, (size_t)w->n);
            for (j = 0; j < good_n; ++j) {
                const int id = sps__int_at(ids, (size_t)j);
                if (id < 0 || id >= w->n || s->in->seen[id]) {
                    sps__refuse(s->in, "last good ids", "last good id %d = %d, allowed distinct ids in [0, %d)", j, id, w->n);
                    break;
                }
                s->in->seen[id] = 1;
            }
        }
    }
    for (m = 0; (block = sps__good_block(w, good_n, m, &length, &f)) != NULL && !sps__stream_bad(s); ++m) {
        if (s->out) { sps__put(s->out, block, sizeof(sps_real) * length); continue; }
        if (!(p = sps__take(s->in, sizeof(sps_real) * length, "last good state"))) break;
        if (sps__applying(s->in)) memcpy(block, p, sizeof(sps_real) * length);
        else if (s->in->pass == SPS__READ_VALUES) {
            const sps__range range = sps__field_range(f);
            for (k = 0; k < length; ++k)
                if (!sps__in_range(&range, sps__real_at(p, k))) {
                    const int id = sps__int_at(ids, k / (size_t)f->components);
                    sps__refuse_value(w, s->in, "last good state", -1, s->in->slot_of_id[id], sps__real_at(p, k), &range);
                    break;
                }
        }
    }
    for (m = 0; m < w->nbodies && !sps__stream_bad(s); ++m) /* a free rigid body's motion with it */
        if (w->bodies[m].model.free_rigid) sps__rigid_transfer(s, w, m, &w->bodies[m].rigid_good);
}

/* A free rigid body's motion (its mass properties and locks are the scene's calls, made again
   by the program). The rotation's entries are those of a rotation, within [-1, 1]. */
static void sps__rigid_transfer(sps__stream* s, sps_world* w, int bi, sps__rigid* r) {
    static const sps__range rotation_range = {-1 - 1e-9, 1 + 1e-9, 0};
    sps__real_item(s, w, bi, r->x, 3, &sps__finite_range, "rigid centre of mass");
    sps__real_item(s, w, bi, r->turn, 9, &rotation_range, "rigid rotation");
    sps__real_item(s, w, bi, r->v, 3, &sps__finite_range, "rigid velocity");
    sps__real_item(s, w, bi, r->L, 3, &sps__finite_range, "rigid angular momentum");
    sps__real_item(s, w, bi, r->applied_force, 3, &sps__finite_range, "rigid applied force");
    sps__real_item(s, w, bi, r->applied_point, 3, &sps__finite_range, "rigid applied point");
    sps__real_item(s, w, bi, r->force, 3, &sps__finite_range, "rigid force");
    sps__real_item(s, w, bi, r->torque, 3, &sps__finite_range, "rigid torque");
    sps__count_item(s, &r->contacts, w->bodies[bi].count, "rigid contact count"); /* it scales the stick drag */
}

/* A world with zones: the particle counts of the state (the world was resized to them before
   the passes, sps__zone_resize: they must agree) and each zone's tallies. */
static void sps__transfer_zones(sps_world* w, sps__stream* s) {
    int n = w->n, bi, count;
    if (sps__count_item(s, &n, SPS__MAX_PARTICLES, "particle count in the state") != w->n && s->in)
        sps__refuse(s->in, "particle count in the state", "particle count in the state = %d, allowed %d", n, w->n);
    for (bi = 0; bi < w->nbodies; ++bi) {
        count = w->bodies[bi].count;
        if (sps__count_item(s, &count, SPS__MAX_PARTICLES, "body particle count in the state") != w->bodies[bi].count && s->in)
            sps__refuse(s->in, "body particle count in the state", "particle count of body %d in the state = %d, allowed %d", bi, count, w->bodies[bi].count);
    }
    for (bi = 0; bi < w->nzones; ++bi) {
        sps__counter_item(s, &w->zones[bi].created, sizeof w->zones[bi].created, "zone created count");
        sps__counter_item(s, &w->zones[bi].removed, sizeof w->zones[bi].removed, "zone removed count");
    }
}

/* The payload, both ways: every item of the state once, in file order. Saving passes the
   world cast from const (nothing is written into it); restoring runs it three times (the
   passes of sps__reader), into a world whose storage is committed (sps__ready_to_step).
   Returns whether the payload holds the neighbour lists. */
static int sps__transfer_state(sps_world* w, sps__stream* s) {
    int64_t steps[2];
    int k, bi, kept, good_n, lists, stopped;
    char failure;
    steps[0] = w->acoustic_steps; steps[1] = w->advection_steps;
    if (w->nzones) sps__transfer_zones(w, s); /* first: the counts the rest is laid out by (sps__zone_resize) */
    sps__real_item(s, w, -1, &w->time, 1, &sps__nonnegative_range, "time");
    sps__real_item(s, w, -1, &w->dt, 1, &sps__nonnegative_range, "time step");
    sps__real_item(s, w, -1, &w->vmax, 1, &sps__nonnegative_range, "maximum speed");
    sps__counter_item(s, &steps[0], sizeof steps[0], "acoustic step count");
    sps__counter_item(s, &steps[1], sizeof steps[1], "advection step count");
    stopped = sps__count_item(s, &w->stopped, 1, "stopped flag");
    failure = sps__text_item(s, w->failure, sizeof w->failure, "failure message");
    if (s->in && !sps__applying(s->in) && (stopped || failure)) /* sps_world_save refuses a stopped world */
        sps__refuse(s->in, stopped ? "stopped flag" : "failure message", "%s, allowed a run that has not stopped (nothing goes on from a state "
                    "that failed: sps_world_save refuses it)", stopped ? "stopped flag = 1" : "failure message not empty");
    sps__count_item(s, &w->watch.armed, 1, "energy watchdog flag"); /* the guards' memory: the watchdog's start, what was said */
    sps__count_item(s, &w->watch.fired, 1, "energy watchdog flag");
    sps__counter_item(s, &w->watch.checked_at, sizeof w->watch.checked_at, "energy watchdog check");
    sps__real_item(s, w, -1, &w->watch.start, 1, &sps__any_range, "energy watchdog start");
    sps__real_item(s, w, -1, &w->watch.scale, 1, &sps__any_range, "energy watchdog scale");
    sps__real_item(s, w, -1, &w->watch.start_time, 1, &sps__any_range, "energy watchdog start time");
    sps__count_item(s, &w->impact_warned, 1, "impact warning flag");
    for (bi = 0; bi < w->nbodies; ++bi) {
        sps__body* b = &w->bodies[bi];
        sps__real_item(s, w, bi, b->mean_rotation, 9, &sps__finite_range, "mean rotation");
        sps__real_item(s, w, bi, b->mean_spin, 9, &sps__finite_range, "mean spin");
        sps__real_item(s, w, bi, &b->energy_start, 1, &sps__any_range, "energy watchdog start");
        sps__count_item(s, &b->fragment_reported, 1, "fragment warning flag");
        if (b->model.free_rigid) sps__rigid_transfer(s, w, bi, &b->rigid); /* a scene without one: the file as before */
    }
    for (k = 0; k < SPS__NFIELDS; ++k) {
        const sps__field_info* f = &sps__fields[k];
        if (!(f->care & SPS__CARRIED)) continue;
        if (!f->per_body) sps__transfer_field(w, NULL, f, w->n, s);
        else
            for (bi = 0; bi < w->nbodies; ++bi) sps__transfer_field(w, &w->bodies[bi], f, w->bodies[bi].count, s);
    }
    lists = w->lists_valid; /* saving: whether the lists are written; restoring: whether the file has them */
    if ((lists = sps__count_item(s, &lists, 1, "list flag")) != 0) sps__transfer_lists(w, s);
    kept = w->kept_first ? w->kept_ids : 0; /* a world with a paired body (sps__ensure_pair_storage) */
    if ((kept = sps__count_item(s, &kept, w->kept_first ? w->n : 0, "kept pair count")) != 0) sps__transfer_kept_forces(w, kept, s);
    good_n = w->good ? w->good_n : 0;
    if ((good_n = sps__count_item(s, &good_n, w->good ? w->n : 0, "last good state")) != 0) sps__transfer_good(w, good_n, s);
    if (s->in && sps__applying(s->in) && !s->in->bad) {
        if (kept) w->kept_ids = kept;
        w->good_n = good_n;
        w->acoustic_steps = (long)steps[0];
        w->advection_steps = (long)steps[1];
    }
    if (s->in && !s->in->bad && s->in->left != 0) s->in->bad = "payload length";
    return lists;
}

/* SPS__READ_VALUES, last: the payload's bodies, reference positions, masses and constraints by
   id hash to the scene hash of the header, which the world's matched (sps__read_fingerprint):
   the file's state belongs to this scene, particle by particle. */
static void sps__check_scene(const sps_world* w, sps__reader* r, uint64_t scene) {
    const int ref = (int)(sps__field_named("reference") - sps__fields);
    sps__scene_arrays at;
    int a;
    at.body = r->field_at[sps__field_named("body") - sps__fields];
    at.mass = r->field_at[sps__field_named("mass") - sps__fields];
    at.cons = w->cons ? r->field_at[sps__field_named("constraint") - sps__fields] : NULL;
    for (a = 0; a < 3; ++a) at.ref[a] = r->field_at[ref] ? r->field_at[ref] + (size_t)a * (size_t)w->n * sizeof(sps_real) : NULL;
    if (!at.body || !at.mass || !at.ref[0] || (w->cons && !at.cons))
        sps__refuse(r, "scene", "the bodies, reference positions, masses or constraints are missing");
    else if (sps__scene_hash_of(w, r->slot_of_id, &at) != scene)
        sps__refuse(r, "scene", "the particles' bodies, reference positions, masses or constraints by id are not the scene's of its header");
}

/* Reads the payload with reader r in the passes of sps__reader up to `last`, until a rule is
   broken (r->bad); the scratch of the checks is allocated here and freed. Returns
   SPS_ERR_OUT_OF_MEMORY or SPS_OK, and in *lists whether the payload holds the neighbour lists. */
static sps_result sps__read_passes(sps_world* w, sps__reader* r, const unsigned char* payload, size_t bytes, uint64_t scene, int last,
                                   int* lists) {
    sps__stream reading;
    int pass;
    memset(r, 0, sizeof *r);
    r->id_field = (int)(sps__field_named("id") - sps__fields);
    r->slot_of_id = (int*)sps__alloc(w, (sizeof(int) + 1) * (size_t)w->n); /* and the marks of `seen` after them */
    if (!r->slot_of_id) return SPS_ERR_OUT_OF_MEMORY;
    r->seen = (unsigned char*)(r->slot_of_id + w->n);
    reading.out = NULL;
    reading.in = r;
    for (pass = SPS__READ_LAYOUT; pass <= last && !r->bad; ++pass) {
        if (pass == SPS__READ_APPLY && !sps__ensure_kept(w, r->kept_pairs)) {
            sps__free(w, r->slot_of_id); /* nothing was applied */
            return SPS_ERR_OUT_OF_MEMORY;
        }
        r->at = payload;
        r->left = bytes;
        r->pass = pass;
        *lists = sps__transfer_state(w, &reading);
        if (pass == SPS__READ_VALUES && !r->bad && !w->nzones) sps__check_scene(w, r, scene); /* zones create and remove particles */
    }
    sps__free(w, r->slot_of_id);
    r->slot_of_id = NULL;
    r->seen = NULL;
    return SPS_OK;
}

static void sps__put_header(const sps_world* w, uint64_t payload_bytes, sps__writer* s) {
    const uint32_t words[3] = {SPS__RESTART_BYTE_ORDER, SPS__RESTART_VERSION, (uint32_t)sizeof(sps_real)};
    double print[SPS__WORLD_PRINT], body[SPS__BODY_PRINT];
    const uint64_t scene = w->built ? w->built_scene : sps__scene_hash(w);
    double zone[SPS__ZONE_PRINT];
    int bi;
    sps__put(s, sps__restart_magic, sizeof sps__restart_magic);
    sps__put(s, words, sizeof words);
    sps__put(s, &payload_bytes, sizeof payload_bytes);
    sps__world_print(w, print);
    sps__put(s, print, sizeof print);
    sps__put(s, &scene, sizeof scene);
    for (bi = 0; bi < w->nbodies; ++bi) {
        sps__body_print(&w->bodies[bi], body);
        sps__put(s, body, sizeof body);
    }
    for (bi = 0; bi < w->nzones; ++bi) {
        sps__zone_print(&w->zones[bi], zone);
        sps__put(s, zone, sizeof zone);
    }
}

SPSDEF sps_result sps_world_save(const sps_world* w, const char* path) {
    sps__writer count = {NULL, NULL, 0, 0, 0}, mem = {NULL, NULL, 0, 0, 0}, out = {NULL, NULL, 0, SPS__FNV_OFFSET, 0};
    sps__stream counting = {NULL, NULL}, writing = {NULL, NULL};
    sps__reader check;
    uint64_t hash;
    int lists;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (!path) { sps__set_error_const(w, "sps_world_save: path must not be NULL"); return SPS_ERR_INVALID_ARG; }
    if (w->n == 0 || w->needs_sort_by_body) {
        sps__set_error_const(w, "sps_world_save: %s: step first (a restart holds the state between steps)",
                             w->n == 0 ? "the world has no particles" : "particles were added since the last step");
        return SPS_ERR_STATE;
    }
    /* a world that cannot step (an empty body added since, or stopped at an instability) has
       no state to go on from; the check writes only the error message (see sps__set_error_const) */
    if (sps__check_bodies_filled((sps_world*)w) != SPS_OK) return SPS_ERR_STATE;
    if (w->stopped) {
        sps__set_error_const(w, "sps_world_save: the world stopped at an instability and cannot go on from its state (save before the failure, "
                             "e.g. every few steps): %s", w->failure);
        return SPS_ERR_STATE;
    }
    /* the payload in memory, checked by the reader's rules: what is saved restores (a state the
       guards have not met yet, e.g. a density gone negative in the last sub-step, is refused
       here rather than in the restore) */
    counting.out = &count;
    sps__transfer_state((sps_world*)w, &counting); /* writes nothing into the world (see sps__transfer_state) */
    if (count.bytes > (uint64_t)((size_t)-1) || !(mem.mem = (unsigned char*)sps__alloc(w, (size_t)count.bytes)))
        return sps__oom((sps_world*)w, "sps_world_save: the state");
    writing.out = &mem;
    sps__transfer_state((sps_world*)w, &writing);
    if (sps__read_passes((sps_world*)w, &check, mem.mem, (size_t)count.bytes, sps__scene_hash(w), SPS__READ_VALUES, &lists) != SPS_OK) {
        sps__free(w, mem.mem);
        return sps__oom((sps_world*)w, "sps_world_save: the check of the state");
    }
    if (check.bad) {
        sps__set_error_const(w, "sps_world_save: the world's state is out of range (a restore would refuse it; a step stops at it): %s",
                             check.why[0] ? check.why : check.bad);
        sps__free(w, mem.mem);
        return SPS_ERR_STATE;
    }
    out.f = fopen(path, "wb");
    if (!out.f) { sps__free(w, mem.mem); sps__set_error_const(w, "sps_world_save: cannot open '%s' for writing", path); return SPS_ERR_IO; }
    sps__put_header(w, count.bytes, &out);
    out.hash = SPS__FNV_OFFSET; /* the checksum covers the payload */
    sps__put(&out, mem.mem, (size_t)count.bytes);
    sps__free(w, mem.mem);
    hash = out.hash;
    sps__put(&out, &hash, sizeof hash);
    if (fclose(out.f) != 0 || out.failed) { sps__set_error_const(w, "sps_world_save: error writing '%s'", path); return SPS_ERR_IO; }
    return SPS_OK;
}

/* The header: magic, byte order, version and sps_real of this build; the payload's length. */
static sps_result sps__read_header(sps_world* w, FILE* f, const char* path, uint64_t* payload_bytes) {
    char magic[sizeof sps__restart_magic];
    uint32_t words[3];
    const uint32_t swapped = 0x04030201u;
    if (fread(magic, 1, sizeof magic, f) != sizeof magic || memcmp(magic, sps__restart_magic, sizeof magic) != 0) {
        sps__set_error(w, 0, "sps_world_restore: '%s' is not a sphsolid restart file (no restart header)", path);
        return SPS_ERR_INVALID_ARG;
    }
    if (fread(words, sizeof words, 1, f) != 1 || fread(payload_bytes, sizeof *payload_bytes, 1, f) != 1) {
        sps__set_error(w, 0, "sps_world_restore: '%s' is truncated: it ends inside the header", path);
        return SPS_ERR_IO;
    }
    if (words[0] != SPS__RESTART_BYTE_ORDER) {
        sps__set_error(w, 0, "sps_world_restore: '%s' %s", path, words[0] == swapped ? "was written on a machine of the other byte order"
                                                                                         : "is damaged (byte-order mark)");
        return SPS_ERR_INVALID_ARG;
    }
    if (words[1] != SPS__RESTART_VERSION) {
        sps__set_error(w, 0, "sps_world_restore: '%s' has format version %u, this library reads version %u", path, (unsigned)words[1],
                       (unsigned)SPS__RESTART_VERSION);
        return SPS_ERR_INVALID_ARG;
    }
    if (words[2] != sizeof(sps_real)) {
        sps__set_error(w, 0, "sps_world_restore: '%s' holds %u-byte reals, this build's sps_real has %u bytes (%s build)", path,
                       (unsigned)words[2], (unsigned)sizeof(sps_real), sizeof(sps_real) == sizeof(double) ? "double" : "SPHSOLID_FLOAT");
        return SPS_ERR_INVALID_ARG;
    }
    return SPS_OK;
}

/* The fingerprint: every world and body item, and the scene hash (returned in *scene), must be
   the world's. */
static sps_result sps__read_fingerprint(sps_world* w, FILE* f, const char* path, uint64_t* scene_hash) {
    double file[SPS__WORLD_PRINT], mine[SPS__WORLD_PRINT], body_file[SPS__BODY_PRINT], body_mine[SPS__BODY_PRINT];
    uint64_t scene;
    int k, bi;
    if (fread(file, sizeof file, 1, f) != 1 || fread(&scene, sizeof scene, 1, f) != 1) {
        sps__set_error(w, 0, "sps_world_restore: '%s' is truncated: it ends inside the header", path);
        return SPS_ERR_IO;
    }
    sps__world_print(w, mine);
    for (k = 0; k < SPS__WORLD_PRINT; ++k) /* bit for bit: a NaN the checks let through (a field the kind does not read) equals itself */
        if (memcmp(&file[k], &mine[k], sizeof file[k]) != 0) {
            sps__set_error(w, 0, "sps_world_restore: '%s' was saved from another scene: %s = %g in the file, %g in this world "
                           "(build the scene as it was built before the save, then restore)", path, sps__world_print_name(k), file[k], mine[k]);
            return SPS_ERR_STATE;
        }
    for (bi = 0; bi < w->nbodies; ++bi) {
        if (fread(body_file, sizeof body_file, 1, f) != 1) {
            sps__set_error(w, 0, "sps_world_restore: '%s' is truncated: it ends inside the header", path);
            return SPS_ERR_IO;
        }
        sps__body_print(&w->bodies[bi], body_mine);
        for (k = 0; k < SPS__BODY_PRINT; ++k)
            if (memcmp(&body_file[k], &body_mine[k], sizeof body_file[k]) != 0) {
                sps__set_error(w, 0, "sps_world_restore: '%s' was saved from another scene: body %d ('%s') %s = %g in the file, %g in this "
                               "world (build the scene as it was built before the save, then restore)", path, bi, w->bodies[bi].name,
                               sps__body_print_name(k), body_file[k], body_mine[k]);
                return SPS_ERR_STATE;
            }
    }
    for (bi = 0; bi < w->nzones; ++bi) {
        double zone_file[SPS__ZONE_PRINT], zone_mine[SPS__ZONE_PRINT];
        if (fread(zone_file, sizeof zone_file, 1, f) != 1) {
            sps__set_error(w, 0, "sps_world_restore: '%s' is truncated: it ends inside the header", path);
            return SPS_ERR_IO;
        }
        sps__zone_print(&w->zones[bi], zone_mine);
        for (k = 0; k < SPS__ZONE_PRINT; ++k)
            if (memcmp(&zone_file[k], &zone_mine[k], sizeof zone_file[k]) != 0) {
                sps__set_error(w, 0, "sps_world_restore: '%s' was saved from another scene: zone %d %s = %g in the file, %g in this world "
                               "(build the scene as it was built before the save, then restore)", path, bi, sps__zone_print_names[k],
                               zone_file[k], zone_mine[k]);
                return SPS_ERR_STATE;
            }
    }
    if (scene != (w->built ? w->built_scene : sps__scene_hash(w))) {
        sps__set_error(w, 0, "sps_world_restore: '%s' was saved from another scene: the particles' reference positions, masses, "
                       "bodies or constraints differ (build the scene as it was built before the save, then restore)", path);
        return SPS_ERR_STATE;
    }
    *scene_hash = scene;
    return SPS_OK;
}

/* The payload and its checksum, read whole (the file's length is checked first, so a
   truncated file is refused before anything is allocated or changed). */
static sps_result sps__read_payload(sps_world* w, FILE* f, const char* path, uint64_t payload_bytes, unsigned char** payload) {
    const long here = ftell(f);
    long end;
    uint64_t hash;
    if (here < 0 || fseek(f, 0, SEEK_END) != 0 || (end = ftell(f)) < 0 || fseek(f, here, SEEK_SET) != 0) {
        sps__set_error(w, 0, "sps_world_restore: cannot find the length of '%s'", path);
        return SPS_ERR_IO;
    }
    if ((uint64_t)(end - here) != payload_bytes + sizeof hash) {
        sps__set_error(w, 0, "sps_world_restore: '%s' is %s: %ld bytes, its header says %.0f", path,
                       (uint64_t)(end - here) < payload_bytes + sizeof hash ? "truncated" : "damaged (too long)", end,
                       (double)((uint64_t)here + payload_bytes + sizeof hash));
        return SPS_ERR_IO;
    }
    if (payload_bytes > (uint64_t)((size_t)-1)) return sps__oom(w, "sps_world_restore: the file's state");
    *payload = (unsigned char*)sps__alloc(w, (size_t)payload_bytes);
    if (!*payload) return sps__oom(w, "sps_world_restore: the file's state");
    if (fread(*payload, 1, (size_t)payload_bytes, f) != (size_t)payload_bytes || fread(&hash, sizeof hash, 1, f) != 1) {
        sps__set_error(w, 0, "sps_world_restore: error reading '%s'", path);
        return SPS_ERR_IO;
    }
    if (hash != sps__fnv(SPS__FNV_OFFSET, *payload, (size_t)payload_bytes)) {
        sps__set_error(w, 0, "sps_world_restore: '%s' is damaged: the checksum of its state does not match", path);
        return SPS_ERR_IO;
    }
    return SPS_OK;
}

static void sps__zone_resize_back(sps_world* w, const int* old_counts);
/* Sets the bodies' particles to consecutive slots of the world's order, counts[b] each. */
static void sps__zone_lay_out(sps_world* w, const int* counts) {
    int bi, i, first = 0;
    for (bi = 0; bi < w->nbodies; ++bi) {
        for (i = first; i < first + counts[bi]; ++i) w->body[i] = bi;
        w->bodies[bi].count = counts[bi];
        first += counts[bi];
    }
    w->n = first;
    w->needs_sort_by_body = 1;
}
/* A world with zones, before the passes read the payload: the state's particle counts (its
   head, sps__transfer_zones), checked, and the world resized to them (the layout by body; the
   values come from the passes). *old_counts gets the world's counts for sps__zone_resize_back. */
static sps_result sps__zone_resize(sps_world* w, const unsigned char* payload, size_t bytes, const char* path, int** old_counts) {
    const size_t head = sizeof(int) * (size_t)(1 + w->nbodies);
    int bi, n, sum = 0, *counts;
    sps_result res;
    if (bytes < head) { sps__set_error(w, 0, "sps_world_restore: '%s' is damaged: its particle counts do not fit this world", path); return SPS_ERR_IO; }
    n = sps__int_at(payload, 0);
    for (bi = 0; bi < w->nbodies; ++bi) {
        const int c = sps__int_at(payload, (size_t)1 + (size_t)bi);
        if (c < 1 || c > SPS__MAX_PARTICLES || (sum += c) > SPS__MAX_PARTICLES) {
            sps__set_error(w, 0, "sps_world_restore: '%s' is damaged: particle count of body %d in the state = %d, allowed [1, %d] in all", path,
                           bi, c, SPS__MAX_PARTICLES);
            return SPS_ERR_IO;
        }
    }
    if (n != sum) {
        sps__set_error(w, 0, "sps_world_restore: '%s' is damaged: particle count in the state = %d, allowed the bodies' sum %d", path, n, sum);
        return SPS_ERR_IO;
    }
    sps__record_built_scene(w); /* the scene as built (this world's, which the fingerprint matched) */
    if (!(counts = (int*)sps__alloc(w, sizeof(int) * (size_t)(2 * w->nbodies + 1)))) return sps__oom(w, "sps_world_restore: the counts");
    for (bi = 0; bi < w->nbodies; ++bi) {
        counts[bi] = w->bodies[bi].count;
        counts[w->nbodies + bi] = sps__int_at(payload, (size_t)1 + (size_t)bi);
    }
    *old_counts = counts;
    if (sps__reserve(w, n) != SPS_OK) return sps__oom(w, "sps_world_restore: the particle arrays");
    sps__zone_lay_out(w, counts + w->nbodies);
    if ((res = sps__ready_to_step(w)) != SPS_OK) sps__zone_resize_back(w, counts);
    return res;
}
/* A refused file: the world's own counts and layout back (its values were not touched). */
static void sps__zone_resize_back(sps_world* w, const int* old_counts) {
    int bi, i;
    sps__zone_lay_out(w, old_counts);
    for (bi = 0; bi < w->nbodies; ++bi) w->bodies[bi].field_count = old_counts[bi]; /* its arrays kept those values */
    for (i = 0; i < w->n; ++i) w->slot_of_id[w->id[i]] = i;
}

static sps_result sps__restore(sps_world* w, FILE* f, const char* path) {
    uint64_t payload_bytes = 0, scene = 0;
    unsigned char* payload = NULL;
    sps__reader r;
    sps_result res;
    int i, lists, *old_counts = NULL;
    if ((res = sps__read_header(w, f, path, &payload_bytes)) != SPS_OK || (res = sps__read_fingerprint(w, f, path, &scene)) != SPS_OK) return res;
    if ((res = sps__ready_to_step(w)) != SPS_OK) return res; /* the storage the state goes into */
    if ((res = sps__read_payload(w, f, path, payload_bytes, &payload)) != SPS_OK) { sps__free(w, payload); return res; }
    if (w->nzones && (res = sps__zone_resize(w, payload, (size_t)payload_bytes, path, &old_counts)) != SPS_OK) {
        sps__free(w, payload);
        return res;
    }
    res = sps__read_passes(w, &r, payload, (size_t)payload_bytes, scene, SPS__READ_APPLY, &lists);
    if (w->nzones && (res != SPS_OK || r.bad)) sps__zone_resize_back(w, old_counts);
    sps__free(w, old_counts);
    if (res != SPS_OK || r.bad) sps__free(w, payload);
    if (res != SPS_OK) return sps__oom(w, "sps_world_restore: the check of the file's state"); /* nothing was applied */
    if (r.bad) { /* nothing was applied */
        if (r.why[0]) sps__set_error(w, 0, "sps_world_restore: '%s' is damaged: %s", path, r.why);
        else sps__set_error(w, 0, "sps_world_restore: '%s' is damaged: its %s do not fit this world", path, r.bad);
        return SPS_ERR_IO;
    }
    for (i = 0; i < w->n; ++i) w->slot_of_id[w->id[i]] = i; /* a permutation (SPS__READ_LAYOUT) */
    for (i = 0; lists && i < w->nbodies; ++i) /* total Lagrangian: the restored lists are the reference ones */
        if (w->bodies[i].model.total_lagrangian) w->bodies[i].reference_built = 0;
    w->lists_valid = lists && sps__build_neighbors(w, r.lists) == SPS_OK; /* from the payload; else diagnostics rebuild them */
    sps__free(w, payload);
    return SPS_OK;
}

SPSDEF sps_result sps_world_restore(sps_world* w, const char* path) {
    FILE* f;
    sps_result res;
    if (!w) return SPS_ERR_INVALID_ARG;
    sps__world_changed(w);
    if (!path) { sps__set_error(w, 0, "sps_world_restore: path must not be NULL"); return SPS_ERR_INVALID_ARG; }
    f = fopen(path, "rb");
    if (!f) { sps__set_error(w, 0, "sps_world_restore: cannot open '%s' for reading", path); return SPS_ERR_IO; }
    res = sps__restore(w, f, path);
    fclose(f);
    return res;
}
#endif

/* >>geometry: meshes and outlines from files and arrays (GEOMETRY in the manual)

   Every reader ends in the same place, sps__mesh_finish, with vertices and elements (triangles
   in 3D, segments of closed rings in 2D) whose coordinates are finite and whose indices are in
   range; it skips degenerate elements, welds equal vertices (numbered by first use, so a
   triangle soup and an indexed mesh of the same triangles end up identical), applies the def's
   transform, checks the topology and builds the hierarchy.
   Signed distance: the distance is exact, to the nearest triangle (segment), found in a
   bounding-volume hierarchy (median split of the elements' centroids along the longest axis,
   leaves of up to SPS__MESH_LEAF; a query descends nearer child first and prunes a box farther
   than the best so far: O(log n)). 3D sign: the angle-weighted pseudo-normal of the nearest
   feature (face, edge or vertex; Baerentzen and Aanaes 2005, IEEE TVCG 11(3), 243-253): for a
   closed, consistently oriented mesh, (x - q) . n > 0 exactly when x is outside, also where the
   nearest point q is an edge or a vertex, where a face normal alone gives the wrong sign. 2D
   sign: the parity of the crossings of a ray from x towards +x with the segments (each counted
   on the half-open rule (y_a > y) != (y_b > y), so a ray through a vertex counts once): inside
   an odd number of rings is inside, whatever the rings' orientation. */
#ifndef SPHSOLID_NO_GEOMETRY

#define SPS__MESH_LEAF 4
#define SPS__MESH_STACK 128                  /* a median split's depth is log2(n / leaf) + 1 < 30 */
#define SPS__MESH_MAX_ELEMENTS 50000000      /* keeps every index and byte count inside an int / size_t */
#define SPS__MESH_MAX_BYTES 2000000000L      /* the largest file read */
#define SPS__MESH_DEGENERATE 1e-12           /* |cross| / longest edge^2 below which a triangle is a line */
#define SPS__SVG_MAX_PIECES 10000            /* segments of one flattened curve at most */
#define SPS__MESH_MAX_COORDINATE 1e12        /* [m]: products of coordinates (volumes, cross products) stay finite */

typedef struct sps__mesh_node {
    double lo[3], hi[3];      /* the axis-aligned box (the rays' test) */
    double centre[3], axis[3][3], half[3]; /* an oriented box, one axis along the elements' mean
                                              normal: on a curved surface it is as thick as the
                                              patch's sagitta, where the axis-aligned box is as
                                              thick as the patch is wide (the distance's test) */
    int first, count; /* elements order[first .. first + count) of a leaf */
    int left;         /* the children left, left + 1; -1 for a leaf */
} sps__mesh_node;

struct sps_mesh {
    sps_allocator a;
    int dim, nv, ne, nnodes;
    double* v;             /* 3 per vertex */
    int* e;                /* dim per element: vertex indices */
    int* ring;             /* 2D: the ring of each segment */
    double* face;          /* 3D: per triangle its unit normal (3), its edges' pseudo-normals (ab, bc, ca: 9) */
    double* vnormal;       /* 3D: per vertex its angle-weighted pseudo-normal */
    sps__mesh_node* node;
    int* order;
    sps_mesh_info info;
};

/* The raw mesh a reader builds: growable arrays, the allocator of the def. */
typedef struct sps__mesh_raw {
    sps_allocator a;
    int dim;
    double* v; int nv, cap_v;   /* 3 reals per vertex (z = 0 in 2D) */
    int* e; int ne, cap_e;      /* dim indices per element */
    int* ring; int cap_ring;    /* 2D: the ring of each segment */
    int nrings, degenerate;     /* 2D: rings ended; repeated points dropped */
    char* msg; size_t msg_size;
    const char* name;           /* the file's path or the function's name, for the messages */
} sps__mesh_raw;

static void sps__mesh_say(char* msg, size_t size, const char* fmt, ...) {
    va_list ap;
    if (!msg || !size) return;
    va_start(ap, fmt);
    vsnprintf(msg, size, fmt, ap);
    va_end(ap);
}
static void* sps__mesh_alloc(const sps_allocator* a, size_t size) { return a->alloc(size ? size : 1, a->user); }
static void sps__mesh_free(const sps_allocator* a, void* p) { if (p) a->free(p, a->user); }
/* Grows *p (of *cap items of item bytes) to hold need items; 1 when out of memory. */
static int sps__mesh_grow(const sps_allocator* a, void** p, int* cap, int need, size_t item) {
    void* q;
    int c = *cap ? *cap : 64;
    if (need <= *cap) return 0;
    if (need > SPS__MESH_MAX_ELEMENTS * 3) return 1;
    while (c < need) c = c > SPS__MESH_MAX_ELEMENTS * 3 / 2 ? SPS__MESH_MAX_ELEMENTS * 3 : 2 * c;
    q = sps__mesh_alloc(a, (size_t)c * item);
    if (!q) return 1;
    if (*p) memcpy(q, *p, (size_t)*cap * item);
    sps__mesh_free(a, *p);
    *p = q; *cap = c;
    return 0;
}
static int sps__raw_vertex(sps__mesh_raw* r, double x, double y, double z) {
    if (r->nv >= SPS__MESH_MAX_ELEMENTS) return 1;
    if (sps__mesh_grow(&r->a, (void**)&r->v, &r->cap_v, r->nv + 1, 3 * sizeof(double))) return 1;
    r->v[3 * r->nv] = x; r->v[3 * r->nv + 1] = y; r->v[3 * r->nv + 2] = z;
    ++r->nv;
    return 0;
}
static int sps__raw_element(sps__mesh_raw* r, const int* idx) {
    int k;
    if (r->ne >= SPS__MESH_MAX_ELEMENTS) return 1;
    if (sps__mesh_grow(&r->a, (void**)&r->e, &r->cap_e, r->ne + 1, (size_t)r->dim * sizeof(int))) return 1;
    for (k = 0; k < r->dim; ++k) r->e[r->dim * r->ne + k] = idx[k];
    if (r->dim == 2) {
        if (sps__mesh_grow(&r->a, (void**)&r->ring, &r->cap_ring, r->ne + 1, sizeof(int))) return 1;
        r->ring[r->ne] = r->nrings;
    }
    ++r->ne;
    return 0;
}
static void sps__raw_free(sps__mesh_raw* r) {
    sps__mesh_free(&r->a, r->v); sps__mesh_free(&r->a, r->e); sps__mesh_free(&r->a, r->ring);
    r->v = NULL; r->e = NULL; r->ring = NULL;
}
/* Ends the ring whose points are the vertices first .. nv - 1: a last point equal to the first
   dropped, consecutive equal points merged (counted as degenerate segments); its segments
   added. 0, or 1 with the message (fewer than 3 points, out of memory). */
static int sps__raw_close_ring(sps__mesh_raw* r, int first, int line) {
    int i, n, k = first;
    for (i = first; i < r->nv; ++i) { /* merge repeats */
        if (i > first && r->v[3 * i] == r->v[3 * (k - 1)] && r->v[3 * i + 1] == r->v[3 * (k - 1) + 1]) { ++r->degenerate; continue; }
        r->v[3 * k] = r->v[3 * i]; r->v[3 * k + 1] = r->v[3 * i + 1]; r->v[3 * k + 2] = 0;
        ++k;
    }
    if (k - first >= 2 && r->v[3 * (k - 1)] == r->v[3 * first] && r->v[3 * (k - 1) + 1] == r->v[3 * first + 1]) { --k; ++r->degenerate; }
    r->nv = k;
    n = k - first;
    if (n < 3) {
        if (line > 0) sps__mesh_say(r->msg, r->msg_size, "%s: line %d: ring %d has %d distinct point%s: a ring needs 3 at least", r->name, line,
                                    r->nrings + 1, n, n == 1 ? "" : "s");
        else sps__mesh_say(r->msg, r->msg_size, "%s: ring %d has %d distinct point%s: a ring needs 3 at least", r->name, r->nrings, n, n == 1 ? "" : "s");
        return 1;
    }
    for (i = 0; i < n; ++i) {
        int seg[2];
        seg[0] = first + i; seg[1] = first + (i + 1) % n;
        if (sps__raw_element(r, seg)) { sps__mesh_say(r->msg, r->msg_size, "%s: out of memory", r->name); return 1; }
    }
    ++r->nrings;
    return 0;
}

/* ---- small vector helpers ---- */
static void sps__v3_sub(const double* a, const double* b, double* c) { c[0] = a[0] - b[0]; c[1] = a[1] - b[1]; c[2] = a[2] - b[2]; }
static double sps__v3_dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void sps__v3_cross(const double* a, const double* b, double* c) {
    c[0] = a[1] * b[2] - a[2] * b[1]; c[1] = a[2] * b[0] - a[0] * b[2]; c[2] = a[0] * b[1] - a[1] * b[0];
}

/* ---- stable merge sort of an index array by a comparison (welding, edges, the hierarchy) ---- */
typedef int (*sps__mesh_less)(int a, int b, const void* ctx);
static void sps__mesh_sort(int* x, int* tmp, int n, sps__mesh_less less, const void* ctx) {
    int width, i;
    for (width = 1; width < n; width *= 2) {
        for (i = 0; i < n; i += 2 * width) {
            int lo = i, mid = i + width < n ? i + width : n, hi = i + 2 * width < n ? i + 2 * width : n, a = lo, b = mid, k = lo;
            while (a < mid && b < hi) tmp[k++] = less(x[b], x[a], ctx) ? x[b++] : x[a++];
            while (a < mid) tmp[k++] = x[a++];
            while (b < hi) tmp[k++] = x[b++];
        }
        memcpy(x, tmp, (size_t)n * sizeof(int));
    }
}
static int sps__vertex_less(int a, int b, const void* ctx) {
    const double* v = (const double*)ctx;
    int k;
    for (k = 0; k < 3; ++k)
        if (v[3 * a + k] != v[3 * b + k]) return v[3 * a + k] < v[3 * b + k];
    return 0;
}

/* ---- the hierarchy ---- */
typedef struct sps__bvh_build {
    sps_mesh* m;
    double* centroid; /* 3 per element */
    int* tmp;
    int axis;
} sps__bvh_build;
static int sps__centroid_less(int a, int b, const void* ctx) {
    const sps__bvh_build* c = (const sps__bvh_build*)ctx;
    return c->centroid[3 * a + c->axis] < c->centroid[3 * b + c->axis];
}
static void sps__bvh_bounds(const sps_mesh* m, sps__mesh_node* nd) {
    int i, k, a;
    for (a = 0; a < 3; ++a) { nd->lo[a] = HUGE_VAL; nd->hi[a] = -HUGE_VAL; }
    for (i = nd->first; i < nd->first + nd->count; ++i)
        for (k = 0; k < m->dim; ++k) {
            const double* p = m->v + 3 * m->e[m->dim * m->order[i] + k];
            for (a = 0; a < 3; ++a) {
                if (p[a] < nd->lo[a]) nd->lo[a] = p[a];
                if (p[a] > nd->hi[a]) nd->hi[a] = p[a];
            }
        }
}
/* The oriented box of a node: axes the elements' area-weighted mean normal (3D), a direction
   across it and their cross product; the axis-aligned box's when the normals cancel (a closed
   patch) or in 2D. */
static void sps__bvh_oriented(const sps_mesh* m, sps__mesh_node* nd) {
    double n[3] = {0, 0, 0}, total = 0, len, lo[3], hi[3];
    int i, k, a, b;
    memset(nd->axis, 0, sizeof nd->axis);
    for (a = 0; a < 3; ++a) nd->axis[a][a] = 1;
    for (i = nd->first; m->dim == 3 && i < nd->first + nd->count; ++i) {
        const int* e = m->e + 3 * m->order[i];
        double u[3], w[3], c[3];
        sps__v3_sub(m->v + 3 * e[1], m->v + 3 * e[0], u);
        sps__v3_sub(m->v + 3 * e[2], m->v + 3 * e[0], w);
        sps__v3_cross(u, w, c);
        for (a = 0; a < 3; ++a) n[a] += c[a];
        total += sqrt(sps__v3_dot(c, c));
    }
    len = sqrt(sps__v3_dot(n, n));
    if (m->dim == 3 && len > 0.5 * total) { /* the normals agree: a patch, not a closed piece */
        const int* e = m->e + 3 * m->order[nd->first];
        double u[3], s;
        for (a = 0; a < 3; ++a) nd->axis[0][a] = n[a] / len;
        sps__v3_sub(m->v + 3 * e[1], m->v + 3 * e[0], u);
        s = sps__v3_dot(u, nd->axis[0]);
        for (a = 0; a < 3; ++a) u[a] -= s * nd->axis[0][a];
        s = sqrt(sps__v3_dot(u, u));
        if (s > 0) {
            for (a = 0; a < 3; ++a) nd->axis[1][a] = u[a] / s;
            sps__v3_cross(nd->axis[0], nd->axis[1], nd->axis[2]);
        } else { memset(nd->axis, 0, sizeof nd->axis); for (a = 0; a < 3; ++a) nd->axis[a][a] = 1; }
    }
    for (b = 0; b < 3; ++b) { lo[b] = HUGE_VAL; hi[b] = -HUGE_VAL; }
    for (i = nd->first; i < nd->first + nd->count; ++i)
        for (k = 0; k < m->dim; ++k)
            for (b = 0; b < 3; ++b) {
                const double x = sps__v3_dot(m->v + 3 * m->e[m->dim * m->order[i] + k], nd->axis[b]);
                if (x < lo[b]) lo[b] = x;
                if (x > hi[b]) hi[b] = x;
            }
    for (a = 0; a < 3; ++a) nd->centre[a] = 0;
    for (b = 0; b < 3; ++b) {
        nd->half[b] = 0.5 * (hi[b] - lo[b]);
        for (a = 0; a < 3; ++a) nd->centre[a] += 0.5 * (lo[b] + hi[b]) * nd->axis[b][a];
    }
}
/* Splits node n (recursively): its elements sorted along the longest axis of their centroids,
   halved at the median. Nodes are numbered in creation order (the children of n at left, left + 1). */
static void sps__bvh_split(sps__bvh_build* c, int n) {
    sps_mesh* m = c->m;
    sps__mesh_node* nd = &m->node[n];
    double clo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, chi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    int i, a, half, first = nd->first, count = nd->count, left;
    sps__bvh_bounds(m, nd);
    sps__bvh_oriented(m, nd);
    nd->left = -1;
    if (count <= SPS__MESH_LEAF) return;
    for (i = first; i < first + count; ++i)
        for (a = 0; a < 3; ++a) {
            const double x = c->centroid[3 * m->order[i] + a];
            if (x < clo[a]) clo[a] = x;
            if (x > chi[a]) chi[a] = x;
        }
    c->axis = chi[1] - clo[1] > chi[0] - clo[0] ? 1 : 0;
    if (chi[2] - clo[2] > chi[c->axis] - clo[c->axis]) c->axis = 2;
    sps__mesh_sort(m->order + first, c->tmp, count, sps__centroid_less, c);
    half = count / 2;
    left = m->nnodes;
    m->nnodes += 2;
    nd->left = left;
    m->node[left].first = first; m->node[left].count = half;
    m->node[left + 1].first = first + half; m->node[left + 1].count = count - half;
    sps__bvh_split(c, left);
    sps__bvh_split(c, left + 1);
}
static int sps__bvh_create(sps_mesh* m) {
    sps__bvh_build c;
    int i, k, a;
    m->node = (sps__mesh_node*)sps__mesh_alloc(&m->a, (size_t)(2 * m->ne) * sizeof(sps__mesh_node));
    m->order = (int*)sps__mesh_alloc(&m->a, (size_t)m->ne * sizeof(int));
    c.centroid = (double*)sps__mesh_alloc(&m->a, (size_t)m->ne * 3 * sizeof(double));
    c.tmp = (int*)sps__mesh_alloc(&m->a, (size_t)m->ne * sizeof(int));
    c.m = m; c.axis = 0;
    if (!m->node || !m->order || !c.centroid || !c.tmp) { sps__mesh_free(&m->a, c.centroid); sps__mesh_free(&m->a, c.tmp); return 1; }
    for (i = 0; i < m->ne; ++i) {
        m->order[i] = i;
        for (a = 0; a < 3; ++a) {
            double s = 0;
            for (k = 0; k < m->dim; ++k) s += m->v[3 * m->e[m->dim * i + k] + a];
            c.centroid[3 * i + a] = s / m->dim;
        }
    }
    m->nnodes = 1;
    m->node[0].first = 0; m->node[0].count = m->ne;
    sps__bvh_split(&c, 0);
    sps__mesh_free(&m->a, c.centroid);
    sps__mesh_free(&m->a, c.tmp);
    return 0;
}
/* A lower bound of the squared distance from p to the node's elements: the larger of the
   distances to its two boxes (0 inside; the oriented one's only when the other is below best). */
static double sps__box_distance2(const sps__mesh_node* nd, const double p[3], double best) {
    double d[3], d2 = 0, o2 = 0;
    int a;
    for (a = 0; a < 3; ++a) {
        const double e = p[a] < nd->lo[a] ? nd->lo[a] - p[a] : p[a] > nd->hi[a] ? p[a] - nd->hi[a] : 0;
        d2 += e * e;
    }
    if (d2 >= best) return d2;
    sps__v3_sub(p, nd->centre, d);
    for (a = 0; a < 3; ++a) {
        const double u = fabs(sps__v3_dot(d, nd->axis[a])) - nd->half[a];
        if (u > 0) o2 += u * u;
    }
    return d2 > o2 ? d2 : o2;
}

/* ---- nearest points ---- */
enum { SPS__FEATURE_FACE, SPS__FEATURE_AB, SPS__FEATURE_BC, SPS__FEATURE_CA, SPS__FEATURE_A, SPS__FEATURE_B, SPS__FEATURE_C };
/* The point q of triangle abc nearest p, and the feature it lies on (Ericson, Real-Time
   Collision Detection, 2005, section 5.1.5: the Voronoi regions of the vertices, edges, face).
   Returns |p - q|^2. */
static double sps__triangle_nearest(const double p[3], const double a[3], const double b[3], const double c[3], double q[3], int* feature) {
    double ab[3], ac[3], ap[3], bp[3], cp[3], d[3];
    double d1, d2, d3, d4, d5, d6, va, vb, vc, s, t;
    int k;
    sps__v3_sub(b, a, ab); sps__v3_sub(c, a, ac); sps__v3_sub(p, a, ap);
    d1 = sps__v3_dot(ab, ap); d2 = sps__v3_dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) { memcpy(q, a, 3 * sizeof(double)); *feature = SPS__FEATURE_A; goto done; }
    sps__v3_sub(p, b, bp);
    d3 = sps__v3_dot(ab, bp); d4 = sps__v3_dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) { memcpy(q, b, 3 * sizeof(double)); *feature = SPS__FEATURE_B; goto done; }
    vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        s = d1 / (d1 - d3);
        for (k = 0; k < 3; ++k) q[k] = a[k] + s * ab[k];
        *feature = SPS__FEATURE_AB; goto done;
    }
    sps__v3_sub(p, c, cp);
    d5 = sps__v3_dot(ab, cp); d6 = sps__v3_dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) { memcpy(q, c, 3 * sizeof(double)); *feature = SPS__FEATURE_C; goto done; }
    vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        t = d2 / (d2 - d6);
        for (k = 0; k < 3; ++k) q[k] = a[k] + t * ac[k];
        *feature = SPS__FEATURE_CA; goto done;
    }
    va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (k = 0; k < 3; ++k) q[k] = b[k] + t * (c[k] - b[k]);
        *feature = SPS__FEATURE_BC; goto done;
    }
    s = 1 / (va + vb + vc);
    for (k = 0; k < 3; ++k) q[k] = a[k] + ab[k] * (vb * s) + ac[k] * (vc * s);
    *feature = SPS__FEATURE_FACE;
done:
    sps__v3_sub(p, q, d);
    return sps__v3_dot(d, d);
}
/* The point q of segment ab nearest p; returns |p - q|^2. */
static double sps__segment_nearest(const double p[3], const double a[3], const double b[3], double q[3]) {
    double ab[3], ap[3], d[3], t;
    int k;
    sps__v3_sub(b, a, ab); sps__v3_sub(p, a, ap);
    t = sps__v3_dot(ap, ab) / sps__v3_dot(ab, ab);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    for (k = 0; k < 3; ++k) q[k] = a[k] + t * ab[k];
    sps__v3_sub(p, q, d);
    return sps__v3_dot(d, d);
}
/* The distance from p to element t squared, the nearest point q and (3D) its feature. */
static double sps__element_nearest(const sps_mesh* m, int t, const double p[3], double q[3], int* feature) {
    const int* e = m->e + m->dim * t;
    *feature = SPS__FEATURE_FACE;
    return m->dim == 3 ? sps__triangle_nearest(p, m->v + 3 * e[0], m->v + 3 * e[1], m->v + 3 * e[2], q, feature)
                       : sps__segment_nearest(p, m->v + 3 * e[0], m->v + 3 * e[1], q);
}
/* The nearest element to p nearer than sqrt(best) (*element, q, *feature as they come in
   otherwise: best may be the distance to a known element): its squared distance, the point q,
   the element and (3D) the feature. */
static double sps__mesh_nearest(const sps_mesh* m, const double p[3], double best, double q[3], int* element, int* feature) {
    int stack[SPS__MESH_STACK], sp = 0, i;
    stack[sp++] = 0;
    while (sp > 0) {
        const sps__mesh_node* nd = &m->node[stack[--sp]];
        if (sps__box_distance2(nd, p, best) >= best) continue;
        if (nd->left < 0) {
            for (i = nd->first; i < nd->first + nd->count; ++i) {
                const int t = m->order[i];
                double qt[3], d2;
                int f;
                d2 = sps__element_nearest(m, t, p, qt, &f);
                if (d2 < best) { best = d2; memcpy(q, qt, sizeof qt); *element = t; *feature = f; }
            }
        } else {
            const double dl = sps__box_distance2(&m->node[nd->left], p, best), dr = sps__box_distance2(&m->node[nd->left + 1], p, best);
            const int nearer = dl <= dr ? nd->left : nd->left + 1, farther = dl <= dr ? nd->left + 1 : nd->left;
            if ((dl <= dr ? dr : dl) < best) stack[sp++] = farther;
            if ((dl <= dr ? dl : dr) < best) stack[sp++] = nearer;
        }
    }
    return best;
}
/* 2D: whether p is inside (an odd number of crossings of the ray from p towards +x). */
static int sps__mesh_inside2(const sps_mesh* m, const double p[3]) {
    int stack[SPS__MESH_STACK], sp = 0, i, crossings = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const sps__mesh_node* nd = &m->node[stack[--sp]];
        if (!(nd->lo[1] <= p[1] && p[1] < nd->hi[1]) || nd->hi[0] <= p[0]) continue;
        if (nd->left >= 0) { stack[sp++] = nd->left; stack[sp++] = nd->left + 1; continue; }
        for (i = nd->first; i < nd->first + nd->count; ++i) {
            const int* e = m->e + 2 * m->order[i];
            const double *a = m->v + 3 * e[0], *b = m->v + 3 * e[1];
            if ((a[1] > p[1]) != (b[1] > p[1]) && a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]) > p[0]) ++crossings;
        }
    }
    return crossings & 1;
}
/* 3D: whether p is inside by the parity of the crossings of a ray from p along dir with the
   triangles (Moeller and Trumbore 1997, J. Graphics Tools 2(1), 21-28): 1 inside, 0 outside, -1
   undecided (the ray passes within 1e-9 (barycentric) of an edge or runs along a triangle: the
   crossing could count once, twice or not at all). Only for points away from the surface (a
   crossing at t ~ 0 is never looked at). */
static int sps__mesh_ray_parity(const sps_mesh* m, const double p[3], const double dir[3]) {
    const double eps = 1e-9;
    double inv[3];
    int stack[SPS__MESH_STACK], sp = 0, i, a, crossings = 0;
    for (a = 0; a < 3; ++a) inv[a] = 1 / dir[a];
    stack[sp++] = 0;
    while (sp > 0) {
        const sps__mesh_node* nd = &m->node[stack[--sp]];
        double tmin = 0, tmax = HUGE_VAL;
        for (a = 0; a < 3; ++a) { /* the slabs of the box */
            const double t1 = (nd->lo[a] - p[a]) * inv[a], t2 = (nd->hi[a] - p[a]) * inv[a];
            if ((t1 < t2 ? t1 : t2) > tmin) tmin = t1 < t2 ? t1 : t2;
            if ((t1 < t2 ? t2 : t1) < tmax) tmax = t1 < t2 ? t2 : t1;
        }
        if (tmin > tmax) continue;
        if (nd->left >= 0) { stack[sp++] = nd->left; stack[sp++] = nd->left + 1; continue; }
        for (i = nd->first; i < nd->first + nd->count; ++i) {
            const int* e = m->e + 3 * m->order[i];
            const double *v0 = m->v + 3 * e[0];
            double e1[3], e2[3], pv[3], tv[3], qv[3], det, u, v;
            sps__v3_sub(m->v + 3 * e[1], v0, e1);
            sps__v3_sub(m->v + 3 * e[2], v0, e2);
            sps__v3_cross(dir, e2, pv);
            det = sps__v3_dot(e1, pv);
            if (fabs(det) <= 1e-12 * (sps__v3_dot(e1, e1) + sps__v3_dot(e2, e2))) return -1;
            sps__v3_sub(p, v0, tv);
            u = sps__v3_dot(tv, pv) / det;
            if (u < -eps || u > 1 + eps) continue;
            sps__v3_cross(tv, e1, qv);
            v = sps__v3_dot(dir, qv) / det;
            if (v < -eps || u + v > 1 + eps) continue;
            if (u < eps || v < eps || u + v > 1 - eps) return -1;
            if (sps__v3_dot(e2, qv) / det > 0) ++crossings;
        }
    }
    return crossings & 1;
}
/* The signed distance from p, exact where it is below band; beyond, +-band (the sign from the
   ray parity: a far point's nearest triangles need not be searched). *hint (may be NULL): an
   element near the last point asked, whose distance bounds the search from the start (the
   relaxation asks about nearby points one after the other). */
static double sps__mesh_distance(const sps_mesh* m, const double p[3], double band, int* hint) {
    static const double dirs[3][3] = {{0.4636, 0.7291, 0.5033}, {-0.6817, 0.2853, 0.6737}, {0.3019, -0.5932, 0.7466}};
    double q[3] = {0, 0, 0}, best = band * band, r[3];
    int t = -1, f = SPS__FEATURE_FACE, k;
    if (hint && *hint >= 0) {
        double qh[3];
        int fh;
        const double d2 = sps__element_nearest(m, *hint, p, qh, &fh);
        if (d2 < best) { best = d2; t = *hint; f = fh; memcpy(q, qh, sizeof q); }
    }
    best = sps__mesh_nearest(m, p, best, q, &t, &f);
    if (t >= 0) {
        const double d = sqrt(best);
        if (hint) *hint = t;
        if (m->dim == 2) return sps__mesh_inside2(m, p) ? -d : d;
        {
            const double* n = f == SPS__FEATURE_FACE ? m->face + 12 * t
                            : f <= SPS__FEATURE_CA ? m->face + 12 * t + 3 * f
                            : m->vnormal + 3 * m->e[3 * t + f - SPS__FEATURE_A];
            sps__v3_sub(p, q, r);
            return sps__v3_dot(r, n) < 0 ? -d : d;
        }
    }
    if (m->dim == 2) return sps__mesh_inside2(m, p) ? -band : band;
    for (k = 0; k < 3; ++k) {
        const int inside = sps__mesh_ray_parity(m, p, dirs[k]);
        if (inside >= 0) return inside ? -band : band;
    }
    if (band == HUGE_VAL) return HUGE_VAL; /* the whole search found no triangle: p so far away that d^2 overflows */
    return sps__mesh_distance(m, p, HUGE_VAL, NULL); /* three undecided rays: the whole search */
}
SPSDEF sps_real sps_mesh_sdf(const sps_real x[3], void* mesh) {
    const sps_mesh* m = (const sps_mesh*)mesh;
    double p[3];
    SPS_ASSERT(m);
    p[0] = (double)x[0]; p[1] = (double)x[1]; p[2] = m->dim == 3 ? (double)x[2] : 0;
    if (!(p[0] - p[0] == 0 && p[1] - p[1] == 0 && p[2] - p[2] == 0)) return (sps_real)NAN; /* not finite */
    return (sps_real)sps__mesh_distance(m, p, HUGE_VAL, NULL);
}

/* ---- building a mesh from a raw one ---- */
/* Skips degenerate triangles (two equal vertices after welding, or |cross| below
   SPS__MESH_DEGENERATE of the longest edge squared), welds equal vertices (numbered by first
   use, in triangle order). Returns 1 when out of memory. */
static int sps__mesh_weld(sps__mesh_raw* r, int* degenerate) {
    int *order = (int*)sps__mesh_alloc(&r->a, (size_t)r->nv * sizeof(int)), *tmp = (int*)sps__mesh_alloc(&r->a, (size_t)r->nv * sizeof(int));
    int *rep = (int*)sps__mesh_alloc(&r->a, (size_t)r->nv * sizeof(int)), *num = (int*)sps__mesh_alloc(&r->a, (size_t)r->nv * sizeof(int));
    double* v = (double*)sps__mesh_alloc(&r->a, (size_t)r->nv * 3 * sizeof(double));
    int i, k, n = 0, ne = 0;
    if (!order || !tmp || !rep || !num || !v) {
        sps__mesh_free(&r->a, order); sps__mesh_free(&r->a, tmp); sps__mesh_free(&r->a, rep); sps__mesh_free(&r->a, num); sps__mesh_free(&r->a, v);
        return 1;
    }
    for (i = 0; i < r->nv; ++i) { order[i] = i; num[i] = -1; }
    sps__mesh_sort(order, tmp, r->nv, sps__vertex_less, r->v);
    for (i = 0; i < r->nv; ++i) /* the first of a run of equal vertices (the smallest index: the sort is stable) */
        rep[order[i]] = i > 0 && !sps__vertex_less(order[i - 1], order[i], r->v) ? rep[order[i - 1]] : order[i];
    for (i = 0; i < r->ne; ++i) {
        int t[3];
        double ab[3], bc[3], ca[3], c[3], longest;
        for (k = 0; k < 3; ++k) t[k] = rep[r->e[3 * i + k]];
        sps__v3_sub(r->v + 3 * t[1], r->v + 3 * t[0], ab);
        sps__v3_sub(r->v + 3 * t[2], r->v + 3 * t[1], bc);
        sps__v3_sub(r->v + 3 * t[0], r->v + 3 * t[2], ca);
        sps__v3_cross(ab, bc, c);
        longest = sps__v3_dot(ab, ab);
        if (sps__v3_dot(bc, bc) > longest) longest = sps__v3_dot(bc, bc);
        if (sps__v3_dot(ca, ca) > longest) longest = sps__v3_dot(ca, ca);
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0] || !(sqrt(sps__v3_dot(c, c)) > SPS__MESH_DEGENERATE * longest)) { ++*degenerate; continue; }
        for (k = 0; k < 3; ++k) {
            if (num[t[k]] < 0) { num[t[k]] = n; memcpy(v + 3 * n, r->v + 3 * t[k], 3 * sizeof(double)); ++n; }
            r->e[3 * ne + k] = num[t[k]];
        }
        ++ne;
    }
    sps__mesh_free(&r->a, r->v);
    r->v = v; r->nv = n; r->ne = ne;
    sps__mesh_free(&r->a, order); sps__mesh_free(&r->a, tmp); sps__mesh_free(&r->a, rep); sps__mesh_free(&r->a, num);
    return 0;
}
/* Scale, centre, rotate (x, then y, then z), translate. */
static void sps__mesh_transform(sps_mesh* m, const sps_mesh_def* d) {
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    int i, a, b, k;
    for (i = 0; i < m->nv; ++i)
        for (a = 0; a < 3; ++a) {
            double* x = &m->v[3 * i + a];
            *x *= (double)d->scale;
            if (*x < lo[a]) lo[a] = *x;
            if (*x > hi[a]) hi[a] = *x;
        }
    for (k = 0; k < 3; ++k) { /* R = Rz Ry Rx */
        const double angle = m->dim == 2 && k < 2 ? 0 : (double)d->rotate[k], c = cos(angle), s = sin(angle);
        const int p = (k + 1) % 3, q = (k + 2) % 3;
        double S[3][3];
        for (a = 0; a < 3; ++a) {
            S[k][a] = R[k][a];
            S[p][a] = c * R[p][a] - s * R[q][a];
            S[q][a] = s * R[p][a] + c * R[q][a];
        }
        memcpy(R, S, sizeof R);
    }
    for (i = 0; i < m->nv; ++i) {
        double x[3], y[3];
        for (a = 0; a < 3; ++a) x[a] = m->v[3 * i + a] - (d->centre ? 0.5 * (lo[a] + hi[a]) : 0);
        for (a = 0; a < 3; ++a) {
            y[a] = (double)d->translate[a] * (m->dim == 3 || a < 2);
            for (b = 0; b < 3; ++b) y[a] += R[a][b] * x[b];
        }
        memcpy(m->v + 3 * i, y, sizeof y);
    }
}

/* 3D topology: sorted edges (vertex pair, lower first), each run of equal pairs one edge. */
typedef struct sps__edge_ctx { const int* key; } sps__edge_ctx; /* 2 per half-edge: lower, higher vertex */
static int sps__edge_less(int a, int b, const void* ctx) {
    const int* k = ((const sps__edge_ctx*)ctx)->key;
    return k[2 * a] != k[2 * b] ? k[2 * a] < k[2 * b] : k[2 * a + 1] < k[2 * b + 1];
}
/* Normals and pseudo-normals, volume, area; counts boundary, inconsistent and non-manifold
   edges (the first of each kind written to where[]: the half-edge). Returns 1 when out of memory. */
static int sps__mesh_topology(sps_mesh* m, int where[3]) {
    const int nh = 3 * m->ne;
    int *key = (int*)sps__mesh_alloc(&m->a, (size_t)nh * 2 * sizeof(int)), *order = (int*)sps__mesh_alloc(&m->a, (size_t)nh * sizeof(int));
    int* tmp = (int*)sps__mesh_alloc(&m->a, (size_t)nh * sizeof(int));
    sps__edge_ctx c;
    double volume = 0, area = 0, centre[3];
    int i, j, k, a;
    m->face = (double*)sps__mesh_alloc(&m->a, (size_t)m->ne * 12 * sizeof(double));
    m->vnormal = (double*)sps__mesh_alloc(&m->a, (size_t)m->nv * 3 * sizeof(double));
    if (!key || !order || !tmp || !m->face || !m->vnormal) {
        sps__mesh_free(&m->a, key); sps__mesh_free(&m->a, order); sps__mesh_free(&m->a, tmp);
        return 1;
    }
    for (a = 0; a < 3; ++a) centre[a] = 0.5 * ((double)m->info.lo[a] + (double)m->info.hi[a]);
    memset(m->vnormal, 0, (size_t)m->nv * 3 * sizeof(double));
    for (i = 0; i < m->ne; ++i) {
        const int* e = m->e + 3 * i;
        double ab[3], ac[3], n[3], len, p[3][3];
        sps__v3_sub(m->v + 3 * e[1], m->v + 3 * e[0], ab);
        sps__v3_sub(m->v + 3 * e[2], m->v + 3 * e[0], ac);
        sps__v3_cross(ab, ac, n);
        len = sqrt(sps__v3_dot(n, n));
        area += 0.5 * len;
        for (a = 0; a < 3; ++a) m->face[12 * i + a] = n[a] / len;
        for (k = 0; k < 3; ++k) sps__v3_sub(m->v + 3 * e[k], centre, p[k]);
        sps__v3_cross(p[1], p[2], n);
        volume += sps__v3_dot(p[0], n) / 6; /* the divergence theorem, about the box's centre */
        for (k = 0; k < 3; ++k) { /* the angle at corner k weighs the face normal into the vertex's */
            double u[3], w[3], angle;
            sps__v3_sub(m->v + 3 * e[(k + 1) % 3], m->v + 3 * e[k], u);
            sps__v3_sub(m->v + 3 * e[(k + 2) % 3], m->v + 3 * e[k], w);
            sps__v3_cross(u, w, n);
            angle = atan2(sqrt(sps__v3_dot(n, n)), sps__v3_dot(u, w));
            for (a = 0; a < 3; ++a) m->vnormal[3 * e[k] + a] += angle * m->face[12 * i + a];
            /* half-edge 3 i + k: from corner k to corner k + 1 */
            key[2 * (3 * i + k)] = e[k] < e[(k + 1) % 3] ? e[k] : e[(k + 1) % 3];
            key[2 * (3 * i + k) + 1] = e[k] < e[(k + 1) % 3] ? e[(k + 1) % 3] : e[k];
            order[3 * i + k] = 3 * i + k;
        }
    }
    m->info.volume = (sps_real)volume;
    m->info.area = (sps_real)area;
    c.key = key;
    sps__mesh_sort(order, tmp, nh, sps__edge_less, &c);
    for (i = 0; i < nh; i = j) {
        int h0 = order[i], count, t0, t1;
        for (j = i + 1; j < nh && !sps__edge_less(h0, order[j], &c); ++j) {}
        count = j - i;
        t0 = h0 / 3;
        for (k = i; k < j; ++k) { /* the edge's pseudo-normal: the sum of its faces' normals (each at angle pi) */
            const int h = order[k];
            for (a = 0; a < 3; ++a) {
                double s = 0;
                int l;
                for (l = i; l < j && l < i + 2; ++l) s += m->face[12 * (order[l] / 3) + a];
                m->face[12 * (h / 3) + 3 + 3 * (h % 3) + a] = s;
            }
        }
        if (count == 1) { if (m->info.boundary_edges++ == 0) where[0] = h0; }
        else if (count > 2) { if (m->info.nonmanifold_edges++ == 0) where[2] = h0; }
        else {
            t1 = order[i + 1] / 3;
            /* consistent: the two triangles run along the edge in opposite directions */
            if (m->e[3 * t0 + h0 % 3] == m->e[3 * t1 + order[i + 1] % 3]) { if (m->info.inconsistent_edges++ == 0) where[1] = h0; }
        }
    }
    /* the edges ab, bc, ca of the pseudo-normal layout are half-edges 0, 1, 2 */
    sps__mesh_free(&m->a, key); sps__mesh_free(&m->a, order); sps__mesh_free(&m->a, tmp);
    m->info.closed = m->info.boundary_edges == 0 && m->info.nonmanifold_edges == 0;
    m->info.oriented = m->info.inconsistent_edges == 0;
    return 0;
}

/* 2D: orientation of c about ab (> 0: counter-clockwise). */
static double sps__orient2(const double* a, const double* b, const double* c) {
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}
/* Whether segments ab and cd cross or touch. */
static int sps__segments_meet(const double* a, const double* b, const double* c, const double* d) {
    const double o1 = sps__orient2(a, b, c), o2 = sps__orient2(a, b, d), o3 = sps__orient2(c, d, a), o4 = sps__orient2(c, d, b);
    int k;
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return 1;
    for (k = 0; k < 4; ++k) { /* a point on the other segment's line, within its box */
        const double *p = k == 0 ? c : k == 1 ? d : k == 2 ? a : b, *s = k < 2 ? a : c, *t = k < 2 ? b : d;
        const double o = k == 0 ? o1 : k == 1 ? o2 : k == 2 ? o3 : o4;
        if (o == 0 && p[0] >= (s[0] < t[0] ? s[0] : t[0]) && p[0] <= (s[0] < t[0] ? t[0] : s[0]) && p[1] >= (s[1] < t[1] ? s[1] : t[1])
            && p[1] <= (s[1] < t[1] ? t[1] : s[1]))
            return 1;
    }
    return 0;
}
/* 2D: the first pair of segments (not neighbours in a ring) that cross or touch, found in the
   hierarchy; 1 and the pair in *s, *t if there is one. */
static int sps__rings_cross(const sps_mesh* m, int* s_out, int* t_out) {
    int s;
    for (s = 0; s < m->ne; ++s) {
        const double *a = m->v + 3 * m->e[2 * s], *b = m->v + 3 * m->e[2 * s + 1];
        int stack[SPS__MESH_STACK], sp = 0, i;
        stack[sp++] = 0;
        while (sp > 0) {
            const sps__mesh_node* nd = &m->node[stack[--sp]];
            if ((a[0] < b[0] ? a[0] : b[0]) > nd->hi[0] || (a[0] < b[0] ? b[0] : a[0]) < nd->lo[0] || (a[1] < b[1] ? a[1] : b[1]) > nd->hi[1]
                || (a[1] < b[1] ? b[1] : a[1]) < nd->lo[1])
                continue;
            if (nd->left >= 0) { stack[sp++] = nd->left; stack[sp++] = nd->left + 1; continue; }
            for (i = nd->first; i < nd->first + nd->count; ++i) {
                const int t = m->order[i];
                const int* et = m->e + 2 * t;
                if (t <= s || et[0] == m->e[2 * s] || et[0] == m->e[2 * s + 1] || et[1] == m->e[2 * s] || et[1] == m->e[2 * s + 1]) continue;
                if (sps__segments_meet(a, b, m->v + 3 * et[0], m->v + 3 * et[1])) { *s_out = s; *t_out = t; return 1; }
            }
        }
    }
    return 0;
}
/* 2D: area (each ring's |area| added, or taken away when inside an odd number of other rings:
   a hole) and perimeter. */
static void sps__rings_measure(sps_mesh* m) {
    double area = 0, perimeter = 0;
    int i = 0, r;
    while (i < m->ne) {
        int j = i, s, other;
        double ring_area = 0, p[3];
        for (; j < m->ne && m->ring[j] == m->ring[i]; ++j) {
            const double *a = m->v + 3 * m->e[2 * j], *b = m->v + 3 * m->e[2 * j + 1];
            ring_area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
            perimeter += sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]));
        }
        memcpy(p, m->v + 3 * m->e[2 * i], sizeof p);
        for (other = 0, s = 0; s < m->ne; ++s) { /* the rings around this ring's first point */
            const double *a = m->v + 3 * m->e[2 * s], *b = m->v + 3 * m->e[2 * s + 1];
            if (m->ring[s] != m->ring[i] && (a[1] > p[1]) != (b[1] > p[1]) && a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]) > p[0]) ++other;
        }
        r = other & 1;
        area += (r ? -1 : 1) * fabs(ring_area);
        i = j;
    }
    m->info.volume = (sps_real)area;
    m->info.area = (sps_real)perimeter;
}

/* Makes the mesh from the raw one (freed here); 0, or an error with its message. */
static sps_result sps__mesh_finish(sps__mesh_raw* r, const sps_mesh_def* d, sps_mesh** out) {
    sps_mesh* m;
    int degenerate = 0, i, a, where[3] = {0, 0, 0}, s, t;
    if (r->dim == 3 && r->ne > 0 && sps__mesh_weld(r, &degenerate)) goto oom_raw;
    if (r->dim == 2) degenerate = r->degenerate;
    if (r->ne == 0) {
        sps__mesh_say(r->msg, r->msg_size, "%s: no %s of non-zero %s (%d degenerate skipped)", r->name, r->dim == 3 ? "triangle" : "segment",
                      r->dim == 3 ? "area" : "length", degenerate);
        sps__raw_free(r);
        return SPS_ERR_INVALID_ARG;
    }
    m = (sps_mesh*)sps__mesh_alloc(&r->a, sizeof *m);
    if (!m) goto oom_raw;
    memset(m, 0, sizeof *m);
    m->a = r->a; m->dim = r->dim; m->nv = r->nv; m->ne = r->ne;
    m->v = r->v; m->e = r->e; m->ring = r->ring;
    r->v = NULL; r->e = NULL; r->ring = NULL;
    if (d->flip && m->dim == 3)
        for (i = 0; i < m->ne; ++i) { const int x = m->e[3 * i + 1]; m->e[3 * i + 1] = m->e[3 * i + 2]; m->e[3 * i + 2] = x; }
    sps__mesh_transform(m, d);
    m->info.dim = m->dim; m->info.elements = m->ne; m->info.vertices = m->nv; m->info.degenerate = degenerate;
    m->info.rings = r->nrings;
    for (a = 0; a < 3; ++a) { m->info.lo[a] = (sps_real)HUGE_VAL; m->info.hi[a] = (sps_real)-HUGE_VAL; }
    for (i = 0; i < m->nv; ++i)
        for (a = 0; a < 3; ++a) {
            if (!(fabs(m->v[3 * i + a]) <= SPS__MESH_MAX_COORDINATE)) {
                sps__mesh_say(r->msg, r->msg_size, "%s: vertex (%g, %g, %g) (after the def's transform): coordinates must be within %g m of the origin",
                              r->name, m->v[3 * i], m->v[3 * i + 1], m->v[3 * i + 2], SPS__MESH_MAX_COORDINATE);
                sps_mesh_destroy(m);
                return SPS_ERR_INVALID_ARG;
            }
            if (m->v[3 * i + a] < m->info.lo[a]) m->info.lo[a] = (sps_real)m->v[3 * i + a];
            if (m->v[3 * i + a] > m->info.hi[a]) m->info.hi[a] = (sps_real)m->v[3 * i + a];
        }
    if (sps__bvh_create(m)) goto oom;
    if (m->dim == 3) {
        if (sps__mesh_topology(m, where)) goto oom;
        if (!d->allow_open && (!m->info.closed || !m->info.oriented)) {
            const int h = !m->info.closed ? (m->info.boundary_edges ? where[0] : where[2]) : where[1];
            const double *p = m->v + 3 * m->e[h], *q = m->v + 3 * m->e[3 * (h / 3) + (h % 3 + 1) % 3];
            sps__mesh_say(r->msg, r->msg_size,
                          "%s: %s: %d boundary, %d non-manifold and %d inconsistently oriented edges (the first: triangle %d, edge "
                          "(%g, %g, %g)-(%g, %g, %g)); set allow_open = 1 to accept it (the sign is then right only near the surface)",
                          r->name, !m->info.closed ? "the mesh is not closed" : "the triangles are not consistently oriented",
                          m->info.boundary_edges, m->info.nonmanifold_edges, m->info.inconsistent_edges, h / 3 + 1, p[0], p[1], p[2], q[0], q[1],
                          q[2]);
            sps_mesh_destroy(m);
            return SPS_ERR_INVALID_ARG;
        }
        if (m->info.closed && m->info.oriented && !(m->info.volume > 0)) {
            sps__mesh_say(r->msg, r->msg_size,
                          "%s: the triangles face inwards (signed volume %g m^3 <= 0): the normals must point out of the body; set flip = %d to "
                          "turn them over",
                          r->name, (double)m->info.volume, !d->flip);
            sps_mesh_destroy(m);
            return SPS_ERR_INVALID_ARG;
        }
    } else {
        m->info.closed = m->info.oriented = 1;
        if (sps__rings_cross(m, &s, &t)) {
            const double* p = m->v + 3 * m->e[2 * s];
            sps__mesh_say(r->msg, r->msg_size, "%s: ring %d %s: its segment %d (from (%g, %g)) and segment %d meet; rings must not cross themselves or "
                          "each other", r->name, m->ring[s] + 1, m->ring[s] == m->ring[t] ? "crosses itself" : "crosses another ring", s + 1, p[0], p[1], t + 1);
            sps_mesh_destroy(m);
            return SPS_ERR_INVALID_ARG;
        }
        sps__rings_measure(m);
    }
    *out = m;
    return SPS_OK;
oom:
    sps_mesh_destroy(m);
oom_raw:
    sps__raw_free(r);
    sps__mesh_say(r->msg, r->msg_size, "%s: out of memory", r->name);
    return SPS_ERR_OUT_OF_MEMORY;
}

SPSDEF sps_mesh_def sps_default_mesh_def(void) {
    sps_mesh_def d;
    memset(&d, 0, sizeof d);
    d.scale = 1;
    d.allocator.alloc = sps__default_alloc;
    d.allocator.free = sps__default_free;
    d.internal_cookie = SPS__COOKIE;
    return d;
}
SPSDEF void sps_mesh_destroy(sps_mesh* m) {
    sps_allocator a;
    if (!m) return;
    a = m->a;
    sps__mesh_free(&a, m->v); sps__mesh_free(&a, m->e); sps__mesh_free(&a, m->ring); sps__mesh_free(&a, m->face);
    sps__mesh_free(&a, m->vnormal); sps__mesh_free(&a, m->node); sps__mesh_free(&a, m->order);
    sps__mesh_free(&a, m);
}
SPSDEF sps_mesh_info sps_mesh_get_info(const sps_mesh* m) {
    sps_mesh_info i;
    if (m) return m->info;
    memset(&i, 0, sizeof i);
    return i;
}
/* Checks the def (NULL: the defaults, into *store); 0, or 1 with the message. */
static int sps__mesh_def_check(const sps_mesh_def** d, sps_mesh_def* store, const char* name, char* msg, size_t msg_size) {
    int a;
    if (!*d) { *store = sps_default_mesh_def(); *d = store; }
    if ((*d)->internal_cookie != SPS__COOKIE) { sps__mesh_say(msg, msg_size, "%s: the def was not made by sps_default_mesh_def()", name); return 1; }
    if (!((*d)->scale > 0 && (*d)->scale < (sps_real)INFINITY)) {
        sps__mesh_say(msg, msg_size, "%s: scale = %g: must be finite and > 0", name, (double)(*d)->scale); return 1;
    }
    for (a = 0; a < 3; ++a)
        if (!((*d)->rotate[a] - (*d)->rotate[a] == 0 && (*d)->translate[a] - (*d)->translate[a] == 0)) {
            sps__mesh_say(msg, msg_size, "%s: rotate[%d] = %g, translate[%d] = %g: must be finite", name, a, (double)(*d)->rotate[a], a,
                          (double)(*d)->translate[a]);
            return 1;
        }
    if (!((*d)->chord_error >= 0 && (*d)->chord_error < (sps_real)INFINITY)) {
        sps__mesh_say(msg, msg_size, "%s: chord_error = %g: must be finite and >= 0", name, (double)(*d)->chord_error); return 1;
    }
    if (!(*d)->allocator.alloc || !(*d)->allocator.free) { sps__mesh_say(msg, msg_size, "%s: the allocator's alloc and free must be set", name); return 1; }
    return 0;
}
static void sps__raw_start(sps__mesh_raw* r, const sps_mesh_def* d, int dim, const char* name, char* msg, size_t msg_size) {
    memset(r, 0, sizeof *r);
    r->a = d->allocator; r->dim = dim; r->name = name; r->msg = msg; r->msg_size = msg_size;
}
static int sps__mesh_finite(double x) { return x - x == 0; }

SPSDEF sps_result sps_mesh_from_triangles(int nv, const sps_real* xyz, int nt, const int* tri, const sps_mesh_def* def, sps_mesh** out,
                                          char* msg, size_t msg_size) {
    static const char* fn = "sps_mesh_from_triangles";
    sps_mesh_def store;
    sps__mesh_raw r;
    int i, k;
    if (out) *out = NULL;
    if (!out || !xyz || !tri) { sps__mesh_say(msg, msg_size, "%s: out, xyz and tri must not be NULL", fn); return SPS_ERR_INVALID_ARG; }
    if (nv < 3 || nt < 1 || nv > SPS__MESH_MAX_ELEMENTS || nt > SPS__MESH_MAX_ELEMENTS) {
        sps__mesh_say(msg, msg_size, "%s: nv = %d, nt = %d: need 3 <= nv and 1 <= nt, both <= %d", fn, nv, nt, SPS__MESH_MAX_ELEMENTS);
        return SPS_ERR_INVALID_ARG;
    }
    if (sps__mesh_def_check(&def, &store, fn, msg, msg_size)) return SPS_ERR_INVALID_ARG;
    sps__raw_start(&r, def, 3, fn, msg, msg_size);
    for (i = 0; i < nv; ++i) {
        if (!sps__mesh_finite((double)xyz[3 * i]) || !sps__mesh_finite((double)xyz[3 * i + 1]) || !sps__mesh_finite((double)xyz[3 * i + 2])) {
            sps__mesh_say(msg, msg_size, "%s: vertex %d = (%g, %g, %g): coordinates must be finite", fn, i, (double)xyz[3 * i], (double)xyz[3 * i + 1],
                          (double)xyz[3 * i + 2]);
            sps__raw_free(&r);
            return SPS_ERR_INVALID_ARG;
        }
        if (sps__raw_vertex(&r, (double)xyz[3 * i], (double)xyz[3 * i + 1], (double)xyz[3 * i + 2])) goto oom;
    }
    for (i = 0; i < nt; ++i) {
        for (k = 0; k < 3; ++k)
            if (tri[3 * i + k] < 0 || tri[3 * i + k] >= nv) {
                sps__mesh_say(msg, msg_size, "%s: triangle %d: vertex index %d out of range [0, %d]", fn, i, tri[3 * i + k], nv - 1);
                sps__raw_free(&r);
                return SPS_ERR_INVALID_ARG;
            }
        if (sps__raw_element(&r, tri + 3 * i)) goto oom;
    }
    return sps__mesh_finish(&r, def, out);
oom:
    sps__raw_free(&r);
    sps__mesh_say(msg, msg_size, "%s: out of memory", fn);
    return SPS_ERR_OUT_OF_MEMORY;
}

SPSDEF sps_result sps_mesh_from_rings(int nrings, const int* ring_points, const sps_real* xy, const sps_mesh_def* def, sps_mesh** out,
                                      char* msg, size_t msg_size) {
    static const char* fn = "sps_mesh_from_rings";
    sps_mesh_def store;
    sps__mesh_raw r;
    int i, k, p = 0;
    if (out) *out = NULL;
    if (!out || !ring_points || !xy) { sps__mesh_say(msg, msg_size, "%s: out, ring_points and xy must not be NULL", fn); return SPS_ERR_INVALID_ARG; }
    if (nrings < 1 || nrings > SPS__MESH_MAX_ELEMENTS) {
        sps__mesh_say(msg, msg_size, "%s: nrings = %d: must be in [1, %d]", fn, nrings, SPS__MESH_MAX_ELEMENTS);
        return SPS_ERR_INVALID_ARG;
    }
    if (sps__mesh_def_check(&def, &store, fn, msg, msg_size)) return SPS_ERR_INVALID_ARG;
    sps__raw_start(&r, def, 2, fn, msg, msg_size);
    for (i = 0; i < nrings; ++i) {
        const int first = r.nv;
        if (ring_points[i] < 3 || ring_points[i] > SPS__MESH_MAX_ELEMENTS - p) {
            sps__mesh_say(msg, msg_size, "%s: ring %d has ring_points = %d: must be >= 3 (and all rings together <= %d)", fn, i, ring_points[i],
                          SPS__MESH_MAX_ELEMENTS);
            sps__raw_free(&r);
            return SPS_ERR_INVALID_ARG;
        }
        for (k = 0; k < ring_points[i]; ++k, ++p) {
            if (!sps__mesh_finite((double)xy[2 * p]) || !sps__mesh_finite((double)xy[2 * p + 1])) {
                sps__mesh_say(msg, msg_size, "%s: ring %d, point %d = (%g, %g): coordinates must be finite", fn, i, k, (double)xy[2 * p],
                              (double)xy[2 * p + 1]);
                sps__raw_free(&r);
                return SPS_ERR_INVALID_ARG;
            }
            if (sps__raw_vertex(&r, (double)xy[2 * p], (double)xy[2 * p + 1], 0)) goto oom;
        }
        if (sps__raw_close_ring(&r, first, 0)) { sps__raw_free(&r); return SPS_ERR_INVALID_ARG; }
    }
    return sps__mesh_finish(&r, def, out);
oom:
    sps__raw_free(&r);
    sps__mesh_say(msg, msg_size, "%s: out of memory", fn);
    return SPS_ERR_OUT_OF_MEMORY;
}

/* ---- filling bodies ---- */
/* The shape a fill fills: the mesh's inside (thickness 0) or the shell (0, thickness) outside
   it, cut by the box [lo, hi] when clip is set. */
typedef struct sps__mesh_fill {
    const sps_mesh* m;
    sps_real thickness;
    int clip;
    sps_real lo[3], hi[3];
    double band; /* the distance is exact below it: where the fills look at it (2h and the gradient's step, the shell) */
    int hint;    /* the element nearest the last point asked (the fills ask one point after another) */
} sps__mesh_fill;
static sps_real sps__mesh_fill_sdf(const sps_real x[3], void* user) {
    sps__mesh_fill* f = (sps__mesh_fill*)user;
    double p[3];
    sps_real d;
    int a;
    p[0] = (double)x[0]; p[1] = (double)x[1]; p[2] = f->m->dim == 3 ? (double)x[2] : 0;
    if (!(p[0] - p[0] == 0 && p[1] - p[1] == 0 && p[2] - p[2] == 0)) return (sps_real)NAN;
    d = (sps_real)sps__mesh_distance(f->m, p, f->band, &f->hint);
    if (f->thickness > 0) d = -d > d - f->thickness ? -d : d - f->thickness;
    for (a = 0; f->clip && a < f->m->dim; ++a) {
        if (f->lo[a] - x[a] > d) d = f->lo[a] - x[a];
        if (x[a] - f->hi[a] > d) d = x[a] - f->hi[a];
    }
    return d;
}
/* Checks the arguments and sets up the shape and the fill's box: the mesh's box grown by the
   shell and a cell, its faces on multiples of dp (so every fill has the same lattice). 0, or 1
   with the world's error. */
static int sps__mesh_fill_setup(sps_world* w, const sps_mesh* m, const sps_real lo[3], const sps_real hi[3], sps_real thickness, const char* fn,
                                sps__mesh_fill* f, sps_real box_lo[3], sps_real box_hi[3]) {
    const sps_real dp = sps_world_get_def(w)->dp;
    int a;
    if (!m) { sps__set_error(w, 0, "%s: mesh must not be NULL", fn); return 1; }
    if (m->dim != sps_world_get_def(w)->dim) {
        sps__set_error(w, 0, "%s: the mesh is %dD (%s), the world %dD", fn, m->dim, m->dim == 3 ? "triangles" : "rings", sps_world_get_def(w)->dim);
        return 1;
    }
    if (!lo != !hi) { sps__set_error(w, 0, "%s: lo and hi must both be NULL (no cut) or both set", fn); return 1; }
    memset(f, 0, sizeof *f);
    f->m = m; f->thickness = thickness; f->clip = lo != NULL; f->hint = -1;
    /* an open mesh has no inside for the rays to find: the whole search everywhere */
    f->band = m->dim == 3 && !(m->info.closed && m->info.oriented) ? HUGE_VAL
            : (double)(thickness + (2 * sps_world_get_def(w)->h_over_dp + 1) * dp);
    for (a = 0; a < 3; ++a) {
        if (f->clip && a < m->dim && !(lo[a] < hi[a] && sps__finite(lo[a]) && sps__finite(hi[a]))) {
            sps__set_error(w, 0, "%s: the cut [%g, %g] on axis %d: must be finite with lo < hi", fn, (double)lo[a], (double)hi[a], a);
            return 1;
        }
        if (f->clip) { f->lo[a] = lo[a]; f->hi[a] = hi[a]; }
        box_lo[a] = a < m->dim ? (SPS__FLOOR(m->info.lo[a] / dp) - 1) * dp - thickness : 0;
        box_hi[a] = a < m->dim ? (-SPS__FLOOR(-m->info.hi[a] / dp) + 1) * dp + thickness : 0;
    }
    return 0;
}
SPSDEF sps_result sps_body_add_mesh(sps_world* w, sps_body b, const sps_mesh* m, const sps_real lo[3], const sps_real hi[3],
                                    int relax_iterations, int* added) {
    sps__mesh_fill f;
    sps_real box_lo[3], box_hi[3];
    if (added) *added = 0;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (sps__mesh_fill_setup(w, m, lo, hi, 0, "sps_body_add_mesh", &f, box_lo, box_hi)) return SPS_ERR_INVALID_ARG;
    if (relax_iterations < 0) return sps_body_add_sdf(w, b, box_lo, box_hi, sps__mesh_fill_sdf, &f, added);
    return sps_body_add_sdf_relaxed(w, b, box_lo, box_hi, sps__mesh_fill_sdf, &f, relax_iterations, added);
}
SPSDEF sps_result sps_body_add_mesh_shell(sps_world* w, sps_body b, const sps_mesh* m, const sps_real lo[3], const sps_real hi[3],
                                          int layers, int* added) {
    sps__mesh_fill f;
    sps_real box_lo[3], box_hi[3];
    if (added) *added = 0;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (layers < 1 || layers > 20) { sps__set_error(w, 0, "sps_body_add_mesh_shell: layers = %d: must be in [1, 20]", layers); return SPS_ERR_INVALID_ARG; }
    if (sps__mesh_fill_setup(w, m, lo, hi, (sps_real)layers * sps_world_get_def(w)->dp, "sps_body_add_mesh_shell", &f, box_lo, box_hi))
        return SPS_ERR_INVALID_ARG;
    return sps_body_add_sdf(w, b, box_lo, box_hi, sps__mesh_fill_sdf, &f, added);
}

#ifndef SPHSOLID_NO_STDIO
/* ---- the readers ---- */
/* Reads the whole file into a NUL-terminated buffer. */
static sps_result sps__read_whole(const char* path, const sps_allocator* a, char** out, long* size, char* msg, size_t msg_size) {
    FILE* f = fopen(path, "rb");
    char* buf = NULL;
    long cap = 0, n = 0;
    *out = NULL; *size = 0;
    if (!f) { sps__mesh_say(msg, msg_size, "%s: cannot open the file for reading", path); return SPS_ERR_IO; }
    for (;;) {
        size_t got;
        if (n == cap) {
            char* bigger;
            long c = cap ? 2 * cap : 65536;
            if (cap >= SPS__MESH_MAX_BYTES) {
                sps__mesh_say(msg, msg_size, "%s: larger than %ld bytes", path, SPS__MESH_MAX_BYTES);
                sps__mesh_free(a, buf); fclose(f); return SPS_ERR_IO;
            }
            if (c > SPS__MESH_MAX_BYTES) c = SPS__MESH_MAX_BYTES;
            bigger = (char*)sps__mesh_alloc(a, (size_t)c + 1);
            if (!bigger) { sps__mesh_say(msg, msg_size, "%s: out of memory", path); sps__mesh_free(a, buf); fclose(f); return SPS_ERR_OUT_OF_MEMORY; }
            if (buf) memcpy(bigger, buf, (size_t)n);
            sps__mesh_free(a, buf);
            buf = bigger; cap = c;
        }
        got = fread(buf + n, 1, (size_t)(cap - n), f);
        n += (long)got;
        if (got == 0) break;
    }
    if (ferror(f)) { sps__mesh_say(msg, msg_size, "%s: read error", path); sps__mesh_free(a, buf); fclose(f); return SPS_ERR_IO; }
    fclose(f);
    buf[n] = 0;
    *out = buf; *size = n;
    return SPS_OK;
}
static unsigned sps__le32(const unsigned char* p) { return (unsigned)p[0] | (unsigned)p[1] << 8 | (unsigned)p[2] << 16 | (unsigned)p[3] << 24; }
static double sps__le_float(const unsigned char* p) {
    const unsigned u = sps__le32(p); /* IEEE 754 single precision, as STL stores it */
    float f;
    SPS_ASSERT(sizeof f == sizeof u);
    memcpy(&f, &u, sizeof f);
    return (double)f;
}
/* Binary STL: an 80-byte header, a 32-bit count n, n records of 50 bytes (normal, 3 vertices,
   attribute). */
static sps_result sps__read_stl_binary(sps__mesh_raw* r, const unsigned char* b, unsigned n) {
    unsigned t;
    int k, a, idx[3];
    for (t = 0; t < n; ++t) {
        const unsigned char* rec = b + 84 + 50 * (size_t)t + 12;
        for (k = 0; k < 3; ++k) {
            double x[3];
            for (a = 0; a < 3; ++a) {
                x[a] = sps__le_float(rec + 12 * k + 4 * a);
                if (!sps__mesh_finite(x[a])) {
                    sps__mesh_say(r->msg, r->msg_size, "%s: triangle %u, vertex %d: coordinate %c is %g (not finite)", r->name, t + 1, k + 1, "xyz"[a], x[a]);
                    return SPS_ERR_IO;
                }
            }
            if (sps__raw_vertex(r, x[0], x[1], x[2])) return SPS_ERR_OUT_OF_MEMORY;
            idx[k] = r->nv - 1;
        }
        if (sps__raw_element(r, idx)) return SPS_ERR_OUT_OF_MEMORY;
    }
    return SPS_OK;
}

/* A text cursor: the position and its line. */
typedef struct sps__text { const char* p; int line; } sps__text;
/* Skips blanks (and newlines, counted) ; returns the next character. */
static char sps__text_skip(sps__text* t) {
    while (*t->p == ' ' || *t->p == '\t' || *t->p == '\r' || *t->p == '\n' || *t->p == '\f' || *t->p == '\v') {
        if (*t->p == '\n') ++t->line;
        ++t->p;
    }
    return *t->p;
}
/* The next whitespace-separated word (at most size - 1 characters kept). */
static int sps__text_word(sps__text* t, char* word, size_t size) {
    size_t n = 0;
    sps__text_skip(t);
    while (*t->p && !(*t->p == ' ' || *t->p == '\t' || *t->p == '\r' || *t->p == '\n' || *t->p == '\f' || *t->p == '\v')) {
        if (n + 1 < size) word[n++] = *t->p;
        ++t->p;
    }
    word[n] = 0;
    return n > 0;
}
/* A number: the whole word must be one, and finite. */
static int sps__parse_number(const char* word, double* x) {
    char* end;
    if (!*word) return 0;
    *x = strtod(word, &end);
    return *end == 0 && sps__mesh_finite(*x);
}
static int sps__text_number(sps__text* t, double* x, char* word, size_t size) {
    return sps__text_word(t, word, size) && sps__parse_number(word, x);
}
static sps_result sps__stl_expect(sps__mesh_raw* r, sps__text* t, const char* what) {
    char word[64];
    if (sps__text_word(t, word, sizeof word) && strcmp(word, what) == 0) return SPS_OK;
    sps__mesh_say(r->msg, r->msg_size, "%s: line %d: expected '%s', found '%s'", r->name, t->line, what, *word ? word : "the end of the file");
    return SPS_ERR_IO;
}
/* ASCII STL: solid name / facet normal n n n / outer loop / vertex x y z (3) / endloop / endfacet
   ... / endsolid (several solids one after the other). */
static sps_result sps__read_stl_ascii(sps__mesh_raw* r, const char* text) {
    sps__text t;
    char word[64];
    int k, a, idx[3];
    t.p = text; t.line = 1;
    while (sps__text_skip(&t)) {
        if (sps__stl_expect(r, &t, "solid")) return SPS_ERR_IO;
        while (*t.p && *t.p != '\n') ++t.p; /* the name */
        for (;;) {
            const int line = (sps__text_skip(&t), t.line);
            if (!sps__text_word(&t, word, sizeof word)) { sps__mesh_say(r->msg, r->msg_size, "%s: line %d: the file ends inside a solid (no 'endsolid')", r->name, line); return SPS_ERR_IO; }
            if (strcmp(word, "endsolid") == 0) { while (*t.p && *t.p != '\n') ++t.p; break; }
            if (strcmp(word, "facet") != 0) { sps__mesh_say(r->msg, r->msg_size, "%s: line %d: expected 'facet' or 'endsolid', found '%s'", r->name, line, word); return SPS_ERR_IO; }
            if (sps__stl_expect(r, &t, "normal")) return SPS_ERR_IO;
            for (a = 0; a < 3; ++a) /* the normal: ignored (the triangles' order gives it) */
                if (!sps__text_word(&t, word, sizeof word)) {
                    sps__mesh_say(r->msg, r->msg_size, "%s: line %d: the file ends inside a facet's normal", r->name, t.line);
                    return SPS_ERR_IO;
                }
            if (sps__stl_expect(r, &t, "outer") || sps__stl_expect(r, &t, "loop")) return SPS_ERR_IO;
            for (k = 0; k < 3; ++k) {
                double x[3];
                if (sps__stl_expect(r, &t, "vertex")) return SPS_ERR_IO;
                for (a = 0; a < 3; ++a)
                    if (!sps__text_number(&t, &x[a], word, sizeof word)) {
                        sps__mesh_say(r->msg, r->msg_size, "%s: line %d: triangle %d, vertex %d: coordinate %c '%s' is not a finite number", r->name, t.line,
                                      r->ne + 1, k + 1, "xyz"[a], word);
                        return SPS_ERR_IO;
                    }
                if (sps__raw_vertex(r, x[0], x[1], x[2])) return SPS_ERR_OUT_OF_MEMORY;
                idx[k] = r->nv - 1;
            }
            if (sps__stl_expect(r, &t, "endloop") || sps__stl_expect(r, &t, "endfacet")) return SPS_ERR_IO;
            if (sps__raw_element(r, idx)) return SPS_ERR_OUT_OF_MEMORY;
        }
    }
    return SPS_OK;
}

/* The line starting at p: its end (the '\n' or the NUL). */
static const char* sps__line_end(const char* p) { while (*p && *p != '\n') ++p; return p; }
/* The first word of a line (copied, at most size - 1 characters) and where it ends. */
static const char* sps__line_word(const char* p, const char* end, char* word, size_t size) {
    size_t n = 0;
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
    while (p < end && !(*p == ' ' || *p == '\t' || *p == '\r')) { if (n + 1 < size) word[n++] = *p; ++p; }
    word[n] = 0;
    return p;
}
/* Wavefront OBJ: "v x y z", "f a b c ..." (a polygon, triangulated as a fan; an index i, i/t,
   i//n or i/t/n, 1-based, negative counting back from the last vertex); every other
   statement (vt, vn, g, o, s, usemtl, mtllib, l, comments) ignored. */
static sps_result sps__read_obj(sps__mesh_raw* r, const char* text) {
    const char* p = text;
    int line = 1;
    char word[64];
    for (; *p; ++line) {
        const char* end = sps__line_end(p);
        const char* q = sps__line_word(p, end, word, sizeof word);
        if (strcmp(word, "v") == 0) {
            double x[3];
            int a;
            for (a = 0; a < 3; ++a) {
                q = sps__line_word(q, end, word, sizeof word);
                if (!sps__parse_number(word, &x[a])) {
                    sps__mesh_say(r->msg, r->msg_size, "%s: line %d: vertex %d: coordinate %c '%s' is not a finite number", r->name, line, r->nv + 1,
                                  "xyz"[a], word);
                    return SPS_ERR_IO;
                }
            }
            if (sps__raw_vertex(r, x[0], x[1], x[2])) return SPS_ERR_OUT_OF_MEMORY;
        } else if (strcmp(word, "f") == 0) {
            int idx[3], corners = 0;
            for (;;) {
                char* after;
                long i;
                q = sps__line_word(q, end, word, sizeof word);
                if (!*word) break;
                i = strtol(word, &after, 10);
                if (after == word || (*after && *after != '/')) {
                    sps__mesh_say(r->msg, r->msg_size, "%s: line %d: face corner '%s' is not a vertex index", r->name, line, word);
                    return SPS_ERR_IO;
                }
                if (i < 0) i += r->nv + 1L;
                if (i < 1 || i > r->nv) {
                    sps__mesh_say(r->msg, r->msg_size, "%s: line %d: face corner '%s': vertex index out of range (%d vertices so far)", r->name, line, word,
                                  r->nv);
                    return SPS_ERR_IO;
                }
                if (corners < 2) idx[corners] = (int)i - 1;
                else {
                    idx[2] = (int)i - 1;
                    if (sps__raw_element(r, idx)) return SPS_ERR_OUT_OF_MEMORY;
                    idx[1] = idx[2]; /* the fan around the first corner */
                }
                ++corners;
            }
            if (corners < 3) { sps__mesh_say(r->msg, r->msg_size, "%s: line %d: a face needs 3 corners at least, this one has %d", r->name, line, corners); return SPS_ERR_IO; }
        }
        p = *end ? end + 1 : end;
    }
    return SPS_OK;
}

/* An outline: lines "x y" (or "x, y"), a blank line between rings, '#' starting a comment. */
static sps_result sps__read_outline(sps__mesh_raw* r, const char* text) {
    const char* p = text;
    int line = 1, first = 0;
    char word[64];
    for (; *p; ++line) {
        const char* end = sps__line_end(p);
        const char* q = p;
        double x[2];
        int a, blank = 1;
        for (q = p; q < end && *q != '#'; ++q) if (!(*q == ' ' || *q == '\t' || *q == '\r' || *q == ',')) blank = 0;
        if (blank) {
            if (q == end && r->nv > first) { /* a blank line (not a comment) ends the ring */
                if (sps__raw_close_ring(r, first, line)) return SPS_ERR_IO;
                first = r->nv;
            }
            p = *end ? end + 1 : end;
            continue;
        }
        q = p;
        for (a = 0; a < 2; ++a) {
            size_t n = 0;
            while (q < end && (*q == ' ' || *q == '\t' || *q == '\r' || *q == ',')) ++q;
            while (q < end && !(*q == ' ' || *q == '\t' || *q == '\r' || *q == ',' || *q == '#')) { if (n + 1 < sizeof word) word[n++] = *q; ++q; }
            word[n] = 0;
            if (!sps__parse_number(word, &x[a])) {
                sps__mesh_say(r->msg, r->msg_size, "%s: line %d: %c '%s' is not a finite number (an outline's lines are \"x y\")", r->name, line, "xy"[a], word);
                return SPS_ERR_IO;
            }
        }
        while (q < end && (*q == ' ' || *q == '\t' || *q == '\r' || *q == ',')) ++q;
        if (q < end && *q != '#') { sps__mesh_say(r->msg, r->msg_size, "%s: line %d: more than two numbers (an outline's lines are \"x y\")", r->name, line); return SPS_ERR_IO; }
        if (sps__raw_vertex(r, x[0], x[1], 0)) return SPS_ERR_OUT_OF_MEMORY;
        p = *end ? end + 1 : end;
    }
    if (r->nv > first && sps__raw_close_ring(r, first, line)) return SPS_ERR_IO;
    return SPS_OK;
}

/* ---- SVG: the paths' d attributes and polygons' points, curves flattened ---- */
typedef struct sps__svg {
    sps__mesh_raw* r;
    double tol;       /* the chord error; <= 0: measuring (control points into the box, no flattening) */
    double lo[2], hi[2];
    int first;        /* the current ring's first vertex */
    int line;
} sps__svg;
static int sps__svg_point(sps__svg* s, double x, double y) {
    if (s->tol <= 0) {
        if (x < s->lo[0]) s->lo[0] = x;
        if (x > s->hi[0]) s->hi[0] = x;
        if (y < s->lo[1]) s->lo[1] = y;
        if (y > s->hi[1]) s->hi[1] = y;
        return 0;
    }
    return sps__raw_vertex(s->r, x, -y, 0); /* SVG's y points down */
}
static int sps__svg_close(sps__svg* s) {
    int bad = 0;
    if (s->tol > 0 && s->r->nv > s->first) bad = sps__raw_close_ring(s->r, s->first, s->line);
    s->first = s->r->nv;
    return bad;
}
/* A Bezier curve of degree 2 or 3 (c: its control points, 2 reals each, the start first), in
   n pieces: the chord of a piece of parameter length 1/n lies within |B''|max / (8 n^2) of the
   curve, |B''| <= 6 max|P0 - 2P1 + P2|, |P1 - 2P2 + P3| (cubic), 2 |P0 - 2P1 + P2| (quadratic). */
static int sps__svg_curve(sps__svg* s, const double* c, int degree) {
    double second = 0, u;
    int n, i, k;
    if (s->tol <= 0) {
        for (k = 1; k <= degree; ++k) if (sps__svg_point(s, c[2 * k], c[2 * k + 1])) return 1;
        return 0;
    }
    for (k = 0; k + 2 <= degree; ++k) {
        const double dx = c[2 * k] - 2 * c[2 * k + 2] + c[2 * k + 4], dy = c[2 * k + 1] - 2 * c[2 * k + 3] + c[2 * k + 5];
        if (sqrt(dx * dx + dy * dy) > second) second = sqrt(dx * dx + dy * dy);
    }
    second *= degree == 3 ? 6 : 2;
    u = ceil(sqrt(second / (8 * s->tol)));
    n = !(u <= SPS__SVG_MAX_PIECES) ? SPS__SVG_MAX_PIECES : u < 1 ? 1 : (int)u; /* NaN from overflowing control points: the most */
    for (i = 1; i <= n; ++i) {
        const double t = (double)i / n, m = 1 - t;
        double x, y;
        if (degree == 3) {
            x = m * m * m * c[0] + 3 * m * m * t * c[2] + 3 * m * t * t * c[4] + t * t * t * c[6];
            y = m * m * m * c[1] + 3 * m * m * t * c[3] + 3 * m * t * t * c[5] + t * t * t * c[7];
        } else {
            x = m * m * c[0] + 2 * m * t * c[2] + t * t * c[4];
            y = m * m * c[1] + 2 * m * t * c[3] + t * t * c[5];
        }
        if (sps__svg_point(s, x, y)) return 1;
    }
    return 0;
}
/* The next number of path data (separated by blanks or commas); 0 when there is none. */
static int sps__svg_number(const char** p, const char* end, double* x) {
    char buf[64], *e;
    size_t n = 0;
    const char* q;
    while (*p < end && (**p == ' ' || **p == '\t' || **p == '\r' || **p == '\n' || **p == ',')) ++*p;
    q = *p;
    if (q < end && (*q == '-' || *q == '+')) buf[n++] = *q++;
    while (q < end && n + 1 < sizeof buf && ((*q >= '0' && *q <= '9') || *q == '.' || *q == 'e' || *q == 'E' ||
                                            ((*q == '-' || *q == '+') && (q[-1] == 'e' || q[-1] == 'E')))) {
        if (*q == '.' && memchr(buf, '.', n)) break; /* "1.5.5" is 1.5 and .5 */
        buf[n++] = *q++;
    }
    buf[n] = 0;
    *x = strtod(buf, &e);
    if (e == buf) return 0;
    *p += e - buf;
    return sps__mesh_finite(*x);
}
/* One path's d attribute (p .. end). */
static sps_result sps__svg_path(sps__svg* s, const char* p, const char* end) {
    double cur[2] = {0, 0}, start[2] = {0, 0}, last_control[2] = {0, 0}, a[6];
    char cmd = 0, previous = 0;
    static const char* args = "MmLlHhVvCcSsQqTtZzAa";
    static const int count[] = {2, 2, 2, 2, 1, 1, 1, 1, 6, 6, 4, 4, 4, 4, 2, 2, 0, 0, 7, 7};
    for (;;) {
        const char* c;
        int n, k, rel;
        while (p < end && (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n' || *p == ',')) ++p;
        if (p >= end) break;
        if ((*p >= 'A' && *p <= 'Z') || (*p >= 'a' && *p <= 'z')) {
            c = strchr(args, *p);
            if (!c || !*p) { sps__mesh_say(s->r->msg, s->r->msg_size, "%s: line %d: unknown path command '%c'", s->r->name, s->line, *p); return SPS_ERR_IO; }
            if (*p == 'A' || *p == 'a') {
                sps__mesh_say(s->r->msg, s->r->msg_size, "%s: line %d: elliptical arcs (path command '%c') are not read: convert them to curves in the editor",
                              s->r->name, s->line, *p);
                return SPS_ERR_IO;
            }
            cmd = *p++;
            if (cmd == 'Z' || cmd == 'z') {
                if (sps__svg_close(s)) return SPS_ERR_IO;
                cur[0] = start[0]; cur[1] = start[1];
                previous = cmd;
                continue;
            }
        } else if (!cmd || cmd == 'Z' || cmd == 'z') {
            sps__mesh_say(s->r->msg, s->r->msg_size, "%s: line %d: path data: a number where a command is expected", s->r->name, s->line);
            return SPS_ERR_IO;
        }
        n = count[strchr(args, cmd) - args];
        for (k = 0; k < n; ++k)
            if (!sps__svg_number(&p, end, &a[k])) {
                sps__mesh_say(s->r->msg, s->r->msg_size, "%s: line %d: path command '%c' needs %d finite numbers", s->r->name, s->line, cmd, n);
                return SPS_ERR_IO;
            }
        rel = cmd >= 'a';
        if ((previous == 'Z' || previous == 'z') && cmd != 'M' && cmd != 'm') { /* a new subpath from the closed one's start */
            if (sps__svg_point(s, cur[0], cur[1])) return SPS_ERR_OUT_OF_MEMORY;
        }
        switch (cmd) {
        case 'M': case 'm':
            if (sps__svg_close(s)) return SPS_ERR_IO;
            cur[0] = a[0] + rel * cur[0]; cur[1] = a[1] + rel * cur[1];
            start[0] = cur[0]; start[1] = cur[1];
            if (sps__svg_point(s, cur[0], cur[1])) return SPS_ERR_OUT_OF_MEMORY;
            cmd = rel ? 'l' : 'L'; /* further pairs are lines */
            break;
        case 'L': case 'l': case 'H': case 'h': case 'V': case 'v':
            if (cmd == 'H' || cmd == 'h') { a[1] = rel ? 0 : cur[1]; }
            else if (cmd == 'V' || cmd == 'v') { a[1] = a[0]; a[0] = rel ? 0 : cur[0]; }
            cur[0] = a[0] + rel * cur[0]; cur[1] = a[1] + rel * cur[1];
            if (sps__svg_point(s, cur[0], cur[1])) return SPS_ERR_OUT_OF_MEMORY;
            break;
        default: { /* curves: C, S (cubic), Q, T (quadratic) */
            const int cubic = cmd == 'C' || cmd == 'c' || cmd == 'S' || cmd == 's';
            const int smooth = cmd == 'S' || cmd == 's' || cmd == 'T' || cmd == 't';
            const int after_curve = cubic ? strchr("CcSs", previous) != NULL : strchr("QqTt", previous) != NULL;
            double c[8];
            int j = 2;
            c[0] = cur[0]; c[1] = cur[1];
            if (smooth) { /* the reflection of the last control point, or the current point */
                c[2] = previous && after_curve ? 2 * cur[0] - last_control[0] : cur[0];
                c[3] = previous && after_curve ? 2 * cur[1] - last_control[1] : cur[1];
                j = 4;
            }
            for (k = 0; k < n; k += 2, j += 2) { c[j] = a[k] + rel * cur[0]; c[j + 1] = a[k + 1] + rel * cur[1]; }
            last_control[0] = c[j - 4]; last_control[1] = c[j - 3];
            if (sps__svg_curve(s, c, cubic ? 3 : 2)) return SPS_ERR_OUT_OF_MEMORY;
            cur[0] = c[j - 2]; cur[1] = c[j - 1];
        }
        }
        previous = cmd;
    }
    if (sps__svg_close(s)) return SPS_ERR_IO;
    return SPS_OK;
}
/* The value of attribute name in the element [p, end) (after a blank, name, '=', a quote). */
static const char* sps__svg_attribute(const char* p, const char* end, const char* name, const char** value_end) {
    const size_t len = strlen(name);
    for (; p + len + 2 < end; ++p)
        if ((p[-1] == ' ' || p[-1] == '\t' || p[-1] == '\n' || p[-1] == '\r') && strncmp(p, name, len) == 0) {
            const char* q = p + len;
            while (q < end && (*q == ' ' || *q == '\t')) ++q;
            if (q < end && *q == '=') {
                char quote;
                ++q;
                while (q < end && (*q == ' ' || *q == '\t')) ++q;
                if (q >= end || (*q != '"' && *q != '\'')) return NULL;
                quote = *q++;
                *value_end = q;
                while (*value_end < end && **value_end != quote) ++*value_end;
                return *value_end < end ? q : NULL;
            }
        }
    return NULL;
}
/* One pass over the drawing's elements (measuring, or flattening). */
static sps_result sps__svg_pass(sps__svg* s, const char* text) {
    const char *p = text, *counted = text; /* the newlines before counted are in s->line */
    s->line = 1;
    while ((p = strchr(p, '<')) != NULL) {
        const char *end = strchr(p, '>'), *q, *value, *value_end;
        int is_path, is_polygon;
        sps_result res;
        for (q = counted; q < p; ++q) if (*q == '\n') ++s->line;
        counted = p;
        if (!end) { sps__mesh_say(s->r->msg, s->r->msg_size, "%s: line %d: an element is not closed with '>'", s->r->name, s->line); return SPS_ERR_IO; }
        is_path = strncmp(p, "<path", 5) == 0 && (p[5] == ' ' || p[5] == '\t' || p[5] == '\n' || p[5] == '\r');
        is_polygon = (strncmp(p, "<polygon", 8) == 0 || strncmp(p, "<polyline", 9) == 0);
        if (strncmp(p, "<rect", 5) == 0 || strncmp(p, "<circle", 7) == 0 || strncmp(p, "<ellipse", 8) == 0) {
            sps__mesh_say(s->r->msg, s->r->msg_size, "%s: line %d: <rect>, <circle> and <ellipse> are not read: convert them to paths in the editor",
                          s->r->name, s->line);
            return SPS_ERR_IO;
        }
        if ((is_path || is_polygon || strncmp(p, "<g", 2) == 0) && sps__svg_attribute(p + 1, end, "transform", &value_end)) {
            sps__mesh_say(s->r->msg, s->r->msg_size, "%s: line %d: a transform attribute is not applied: apply it to the paths in the editor", s->r->name,
                          s->line);
            return SPS_ERR_IO;
        }
        if (is_path || is_polygon) {
            int line = s->line;
            value = sps__svg_attribute(p + 1, end, is_path ? "d" : "points", &value_end);
            if (!value) { sps__mesh_say(s->r->msg, s->r->msg_size, "%s: line %d: a <%s> without its %s attribute", s->r->name, s->line, is_path ? "path" : "polygon", is_path ? "d" : "points"); return SPS_ERR_IO; }
            if (is_path) res = sps__svg_path(s, value, value_end);
            else {
                double xy[2];
                res = SPS_OK;
                while (res == SPS_OK && sps__svg_number(&value, value_end, &xy[0])) {
                    if (!sps__svg_number(&value, value_end, &xy[1])) {
                        sps__mesh_say(s->r->msg, s->r->msg_size, "%s: line %d: a polygon's points come in pairs", s->r->name, line); res = SPS_ERR_IO;
                    } else if (sps__svg_point(s, xy[0], xy[1])) res = SPS_ERR_OUT_OF_MEMORY;
                }
                if (res == SPS_OK) {
                    while (value < value_end && (*value == ' ' || *value == '\t' || *value == '\r' || *value == '\n' || *value == ',')) ++value;
                    if (value < value_end) { sps__mesh_say(s->r->msg, s->r->msg_size, "%s: line %d: a polygon's points must be finite numbers", s->r->name, line); res = SPS_ERR_IO; }
                    else if (sps__svg_close(s)) res = SPS_ERR_IO;
                }
            }
            if (res == SPS_ERR_OUT_OF_MEMORY) sps__mesh_say(s->r->msg, s->r->msg_size, "%s: out of memory", s->r->name);
            if (res != SPS_OK) return res;
        }
        p = end + 1;
    }
    return SPS_OK;
}
static sps_result sps__read_svg(sps__mesh_raw* r, const char* text, double chord_error) {
    sps__svg s;
    sps_result res;
    memset(&s, 0, sizeof s);
    s.r = r;
    s.lo[0] = s.lo[1] = HUGE_VAL; s.hi[0] = s.hi[1] = -HUGE_VAL;
    if ((res = sps__svg_pass(&s, text)) != SPS_OK) return res; /* measuring */
    if (!(s.hi[0] >= s.lo[0])) { sps__mesh_say(r->msg, r->msg_size, "%s: an SVG drawing without paths or polygons", r->name); return SPS_ERR_IO; }
    s.tol = chord_error > 0 ? chord_error : 1e-3 * (s.hi[0] - s.lo[0] > s.hi[1] - s.lo[1] ? s.hi[0] - s.lo[0] : s.hi[1] - s.lo[1]);
    if (!(s.tol > 0)) { sps__mesh_say(r->msg, r->msg_size, "%s: the drawing has no extent", r->name); return SPS_ERR_IO; }
    s.first = 0;
    return sps__svg_pass(&s, text);
}

/* Whether the first word of the first line that is not blank or a comment is an OBJ statement. */
static int sps__looks_obj(const char* text) {
    static const char* words[] = {"v", "vt", "vn", "vp", "f", "g", "o", "s", "l", "p", "usemtl", "mtllib"};
    const char* p = text;
    char word[16];
    int k;
    while (*p) {
        const char* end = sps__line_end(p);
        sps__line_word(p, end, word, sizeof word);
        if (*word && *word != '#') {
            for (k = 0; k < (int)(sizeof words / sizeof *words); ++k) if (strcmp(word, words[k]) == 0) return 1;
            return 0;
        }
        p = *end ? end + 1 : end;
    }
    return 0;
}
/* Reads the formats by content: a binary STL by its size, else text (no control characters):
   SVG, ASCII STL, OBJ or an outline. */
static sps_result sps__mesh_parse(sps__mesh_raw* r, const char* bytes, long size, const sps_mesh_def* d) {
    const unsigned char* b = (const unsigned char*)bytes;
    long i;
    int text = 1;
    sps__text t;
    char word[64];
    if (size == 0) { sps__mesh_say(r->msg, r->msg_size, "%s: the file is empty", r->name); return SPS_ERR_IO; }
    if (size >= 84 && (long)sps__le32(b + 80) <= (size - 84) / 50 && 84 + 50 * (long)sps__le32(b + 80) == size) {
        if (sps__le32(b + 80) == 0) { sps__mesh_say(r->msg, r->msg_size, "%s: a binary STL of 0 triangles", r->name); return SPS_ERR_IO; }
        r->dim = 3;
        return sps__read_stl_binary(r, b, sps__le32(b + 80));
    }
    for (i = 0; i < size && text; ++i) text = b[i] >= 32 || b[i] == '\n' || b[i] == '\r' || b[i] == '\t' || b[i] == '\f' || b[i] == '\v';
    if (!text) {
        if (size >= 84)
            sps__mesh_say(r->msg, r->msg_size, "%s: not a mesh file: binary content, and as a binary STL its count of %u triangles needs %.0f bytes "
                          "(84 + 50 per triangle), the file has %ld", r->name, sps__le32(b + 80), 84 + 50.0 * sps__le32(b + 80), size);
        else sps__mesh_say(r->msg, r->msg_size, "%s: not a mesh file: binary content, and %ld bytes are too few for a binary STL (84 at least)", r->name, size);
        return SPS_ERR_IO;
    }
    t.p = bytes; t.line = 1;
    sps__text_word(&t, word, sizeof word);
    if (strstr(bytes, "<svg")) { r->dim = 2; return sps__read_svg(r, bytes, (double)d->chord_error); }
    if (strcmp(word, "solid") == 0) { r->dim = 3; return sps__read_stl_ascii(r, bytes); }
    if (sps__looks_obj(bytes)) { r->dim = 3; return sps__read_obj(r, bytes); }
    if (*word == '<') { sps__mesh_say(r->msg, r->msg_size, "%s: not a mesh file: markup without an <svg> element", r->name); return SPS_ERR_IO; }
    {
        double x;
        char* comma = strchr(word, ',');
        if (comma) *comma = 0; /* "x,y" */
        if (!(*word == '#' || sps__parse_number(word, &x))) {
            sps__mesh_say(r->msg, r->msg_size, "%s: not a mesh file: its first word '%s' starts no binary or ASCII STL, OBJ, SVG or outline (\"x y\" lines)",
                          r->name, word);
            return SPS_ERR_IO;
        }
    }
    r->dim = 2;
    return sps__read_outline(r, bytes);
}
SPSDEF sps_result sps_mesh_load(const char* path, const sps_mesh_def* def, sps_mesh** out, char* msg, size_t msg_size) {
    sps_mesh_def store;
    sps__mesh_raw r;
    char* bytes;
    long size;
    sps_result res;
    if (out) *out = NULL;
    if (!path || !out) { sps__mesh_say(msg, msg_size, "sps_mesh_load: path and out must not be NULL"); return SPS_ERR_INVALID_ARG; }
    if (sps__mesh_def_check(&def, &store, path, msg, msg_size)) return SPS_ERR_INVALID_ARG;
    if ((res = sps__read_whole(path, &def->allocator, &bytes, &size, msg, msg_size)) != SPS_OK) return res;
    sps__raw_start(&r, def, 3, path, msg, msg_size);
    res = sps__mesh_parse(&r, bytes, size, def);
    sps__mesh_free(&def->allocator, bytes);
    if (res == SPS_ERR_OUT_OF_MEMORY) sps__mesh_say(msg, msg_size, "%s: out of memory", path);
    if (res != SPS_OK) { sps__raw_free(&r); return res; }
    return sps__mesh_finish(&r, def, out);
}
#endif /* SPHSOLID_NO_STDIO */
#endif /* SPHSOLID_NO_GEOMETRY */

/* >>realtime */

#ifndef SPHSOLID_WALL_SECONDS
#ifdef CLOCK_MONOTONIC /* POSIX, when <time.h> declares it (_POSIX_C_SOURCE >= 199309L) */
static double sps__monotonic_seconds(void) {
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) return (double)clock() / CLOCKS_PER_SEC;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
#define SPHSOLID_WALL_SECONDS() sps__monotonic_seconds()
#else
/* C99 has no wall clock: clock() counts the processor time of the process (all its threads). */
#define SPHSOLID_WALL_SECONDS() ((double)clock() / CLOCKS_PER_SEC)
#endif
#endif

/* Sub-steps that still fit in the budget at the cost per sub-step measured so far in the frame
   (a sub-step's share of the neighbour-list rebuild included); huge when nothing is measured. */
static double sps__substeps_fitting(double budget_s, double spent_s, int done) {
    if (done == 0 || spent_s <= 0) return 1e18;
    return (budget_s - spent_s) / (spent_s / done);
}

SPSDEF sps_result sps_world_advance_substeps(sps_world* w, int max_substeps, double wall_budget_s, sps_real* covered) {
    sps_result r = SPS_OK;
    sps_real t0;
    double start = 0;
    int done = 0, budget_ok;
    if (covered) *covered = 0;
    if (!w) return SPS_ERR_INVALID_ARG;
    budget_ok = wall_budget_s >= 0 && wall_budget_s - wall_budget_s == 0; /* >= 0 and finite */
    if (max_substeps < 1 || !budget_ok) {
        char msg[256] = "";
        int broken = 0;
        if (max_substeps < 1) sps__rule(msg, sizeof msg, &broken, "max_substeps = %d, allowed >= 1", max_substeps);
        if (!budget_ok)
            sps__rule(msg, sizeof msg, &broken, "wall_budget_s = %g, allowed 0 (no budget) or finite > 0", wall_budget_s);
        sps__set_error(w, 0, "sps_world_advance_substeps: %s", msg);
        return SPS_ERR_INVALID_ARG;
    }
    t0 = w->time;
    if (wall_budget_s > 0) start = SPHSOLID_WALL_SECONDS();
    while (done < max_substeps) {
        long before = w->acoustic_steps;
        double chunk = max_substeps - done;
        if (wall_budget_s > 0) {
            double fitting = sps__substeps_fitting(wall_budget_s, SPHSOLID_WALL_SECONDS() - start, done);
            if (fitting < 1) break;
            if (fitting < chunk) chunk = fitting;
        }
        if ((r = sps__step_guarded(w, (sps_real)INFINITY, (int)chunk, !w->periodic)) != SPS_OK) break;
        done += (int)(w->acoustic_steps - before);
    }
    if (covered) *covered = w->time - t0;
    return r;
}

/* A budgeted frame in seconds: every step is cut to the sub-steps that fit in what is left of
   the budget, at the cost per sub-step measured so far in this frame or, for its first step,
   in the last budgeted frame; every frame runs one sub-step at least (slow motion when even
   that does not fit). The step lands on the frame's end like any step of sps_world_advance. */
SPSDEF sps_result sps_world_advance_frame(sps_world* w, sps_real frame_seconds, double wall_budget_s, sps_real* covered) {
    sps_result r = SPS_OK;
    const sps_real t0 = w ? w->time : 0, t_end = t0 + frame_seconds;
    double start = 0;
    long done = 0;
    if (covered) *covered = 0;
    if (!w) return SPS_ERR_INVALID_ARG;
    if (!(frame_seconds > 0 && frame_seconds <= 1) || !(wall_budget_s >= 0 && wall_budget_s - wall_budget_s == 0)) {
        sps__set_error(w, 0, "sps_world_advance_frame: frame_seconds = %g, allowed (0, 1] s of simulated time (for a count of sub-steps "
                       "use sps_world_advance_substeps); wall_budget_s = %g, allowed 0 (no budget) or finite > 0",
                       (double)frame_seconds, wall_budget_s);
        return SPS_ERR_INVALID_ARG;
    }
    if (wall_budget_s > 0) start = SPHSOLID_WALL_SECONDS();
    while (w->time < t_end) {
        const long before = w->acoustic_steps;
        double fitting = 1e18;
        if (wall_budget_s > 0) {
            const double spent = SPHSOLID_WALL_SECONDS() - start;
            const double per_substep = done > 0 ? spent / (double)done : w->substep_wall_s;
            /* one sub-step's time kept for the step's neighbour-list rebuild */
            fitting = per_substep > 0 ? (wall_budget_s - spent) / per_substep - 1 : 1;
            /* the frame's first sub-step runs anyway: the last frame's cost alone (say the first
               sub-step ever, with its allocations) must not stop the world */
            if (fitting < 1 && done > 0) break;
            if (fitting < 1) fitting = 1;
        }
        if (fitting > INT_MAX) fitting = INT_MAX;
        if ((r = sps__step_guarded(w, t_end, (int)fitting, !w->periodic)) != SPS_OK) break;
        done += w->acoustic_steps - before;
    }
    if (wall_budget_s > 0 && done > 0) w->substep_wall_s = (SPHSOLID_WALL_SECONDS() - start) / (double)done;
    if (covered) *covered = w->time - t0;
    return r;
}

/* The drag's external acceleration (sps_body_drag_begin): the kernel weight of the particle's
   reference distance from the anchor, scaled to the drag's radius. */
static void sps__drag_acceleration(const sps_real x[3], const sps_real x0[3], const sps_real v[3], sps_real t, sps_real a[3],
                                   void* user) {
    const sps_drag* drag = (const sps_drag*)user;
    const sps_world* w = drag->world;
    sps_real r2 = 0, weight;
    int k;
    (void)t;
    for (k = 0; k < w->dim; ++k) r2 += (x0[k] - drag->anchor[k]) * (x0[k] - drag->anchor[k]);
    if (r2 >= drag->radius * drag->radius) return;
    weight = sps_world_kernel(w, SPS__SQRT(r2) * w->support / drag->radius) / drag->weight_sum; /* phi_i / m_i */
    for (k = 0; k < w->dim; ++k) a[k] = weight * (drag->stiffness * (drag->target[k] - x[k]) - drag->damping * v[k]);
}

SPSDEF sps_result sps_body_drag_begin(sps_world* w, sps_body b, const sps_real point[3], sps_real stiffness, sps_real damping,
                                      sps_real radius, sps_drag* drag) {
    int k, i, a, nearest = -1;
    sps_real best = 0;
    if (!w) return SPS_ERR_INVALID_ARG;
    if ((k = sps__check_body(w, b, "sps_body_drag_begin")) < 0) return SPS_ERR_INVALID_ARG;
    if (!point || !drag) { sps__set_error(w, 0, "sps_body_drag_begin: point and drag must not be NULL"); return SPS_ERR_INVALID_ARG; }
    if (!(stiffness >= 0 && sps__finite(stiffness)) || !(damping >= 0 && sps__finite(damping)) ||
        !(radius == 0 || (radius >= w->support && sps__finite(radius)))) {
        sps__set_error(w, 0, "sps_body_drag_begin: stiffness = %g, allowed finite >= 0 N/m; damping = %g, allowed finite >= 0 N s/m; "
                       "radius = %g, allowed 0 (2h) or >= 2h = %g m", (double)stiffness, (double)damping, (double)radius, (double)w->support);
        return SPS_ERR_INVALID_ARG;
    }
    if (sps__body_is_empty(w, k, "sps_body_drag_begin")) return SPS_ERR_STATE;
    for (i = 0; i < w->n; ++i) { /* the grabbed material point: the particle nearest to point now */
        sps_real d2 = 0;
        if (w->body[i] != k) continue;
        for (a = 0; a < w->dim; ++a) d2 += (w->pos[a][i] - point[a]) * (w->pos[a][i] - point[a]);
        if (nearest < 0 || d2 < best) { best = d2; nearest = i; }
    }
    memset(drag, 0, sizeof *drag);
    drag->stiffness = stiffness;
    drag->damping = damping;
    drag->body = b;
    drag->world = w;
    drag->radius = radius > 0 ? radius : w->support;
    for (a = 0; a < 3; ++a) { drag->target[a] = point[a]; drag->anchor[a] = a < w->dim ? w->ref[a][nearest] : 0; }
    for (i = 0; i < w->n; ++i) { /* the normalisation, in particle order */
        sps_real r2 = 0;
        if (w->body[i] != k) continue;
        for (a = 0; a < w->dim; ++a) r2 += (w->ref[a][i] - drag->anchor[a]) * (w->ref[a][i] - drag->anchor[a]);
        if (r2 < drag->radius * drag->radius) drag->weight_sum += w->mass[i] * sps_world_kernel(w, SPS__SQRT(r2) * w->support / drag->radius);
    }
    return sps_body_set_acceleration(w, b, sps__drag_acceleration, drag);
}

SPSDEF sps_result sps_body_drag_end(sps_world* w, sps_drag* drag) {
    if (!w || !drag) return SPS_ERR_INVALID_ARG;
    return sps_body_set_acceleration(w, drag->body, NULL, NULL);
}

#endif /* SPHSOLID_IMPLEMENTATION_INCLUDED */
#endif /* SPHSOLID_IMPLEMENTATION */

/*
------------------------------------------------------------------------------
MIT License
Copyright (c) 2026 the sphsolid.h authors
Permission is hereby granted, free of charge, to any person obtaining a copy of this software
and associated documentation files (the "Software"), to deal in the Software without
restriction, including without limitation the rights to use, copy, modify, merge, publish,
distribute, sublicense, and/or sell copies of the Software, and to permit persons to whom the
Software is furnished to do so, subject to the following conditions:
The above copyright notice and this permission notice shall be included in all copies or
substantial portions of the Software.
THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR IMPLIED, INCLUDING
BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY, FITNESS FOR A PARTICULAR PURPOSE AND
NONINFRINGEMENT. IN NO EVENT SHALL THE AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM,
DAMAGES OR OTHER LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE SOFTWARE.
------------------------------------------------------------------------------
*/
