# sphsolid.h - build, run, test and bench. Needs only gcc (or cc), make and libc.
#   make          header checks (C99 gcc/clang, C++, float, static), the README quick start, examples
#   make run      the main job: 2D plate, H/dp = 10, v_f = 0.05, ENO-A, to t = 1 s
#   make test     the README quick start and every example (brief runs, pictures read back), the demo (headless),
#                 the pinned results (tests/pinned.c), the randomized API test (10,000 cases), the test
#                 runner (optimised, OpenMP), and both again under ASan + UBSan (quick tests, 1,000 cases);
#                 crafted restart files under ASan + UBSan (tests/fuzz_restore.c, 1,000 cases); the geometry
#                 readers (tests/test_geometry.c) and damaged mesh files under ASan + UBSan (tests/fuzz_mesh.c)
#   make fuzz-restore-full  the crafted restart files' 10,000 cases (about 3 min)
#   make fuzz-libfuzzer FUZZ_SECONDS=600  the restart reader under clang's libFuzzer (one core)
#   make cad-check  the mesh readers against a part OpenSCAD exports, its volume from admesh (installs both as root)
#   make demo     build/demo: jelly in the terminal, in real time (space, f, p, q)
#   make web      build/web/: the demo in a web browser (WebAssembly: clang, lld, wasi-libc, libclang-rt-14-dev-wasm32)
#   make test-web the web demo in headless Chromium against the native demo (installs its tools as root)
#   make gallery-web  bench/gallery/demo_web.png, the page in headless Chromium
#   make gallery  one picture per example into bench/gallery/ (about 15 s)
#   make probes   the bench probes that read the library's private state (torque_probe, rotation_probe)
#   make memcheck the quick tests and 300 random cases under valgrind (serial build; ~8 min)
#   make bench    speed tables (bench/results/)
#   make bench-knobs  what each setting costs and buys (bench/knobs.sh, about 30 min)
#   make clean
CC      ?= cc
CXX     ?= c++
# -fno-math-errno lets sqrt vectorise (the library never reads errno). On an AVX-512 CPU, GCC's
# generic tuning (what -march=native picks on CPUs it does not name) emits no gather
# instructions, and the neighbour loops need them: -mtune=icelake-server measured 1.6x faster
# on the 2D plate; GCC also prefers 256-bit vectors there, and 512-bit ones run the 16-double
# lane groups 1.2x faster. Elsewhere (AVX2 CPUs such as AMD's, other architectures) -march=native
# keeps the CPU's own tuning: on an AVX2 EPYC the Intel tuning's gathers changed nothing
# (bench/VALIDATION.md, "Speed"). TUNE= on the command line overrides the choice.
AVX512  := $(shell grep -q -w avx512f /proc/cpuinfo 2>/dev/null && echo yes)
TUNE    ?= $(if $(AVX512),-mtune=icelake-server -mprefer-vector-width=512,)
OPT     ?= -O2 -march=native $(TUNE) -fno-math-errno -fno-trapping-math
WARN     = -Wall -Wextra -Wpedantic
CFLAGS   = -std=c99 $(OPT) $(WARN) -fopenmp
LDLIBS   = -lm
SANITIZE = -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all
BUILD    = build
# the examples built with sps_real = float (defined before the rules that name it)
FLOAT    = $(BUILD)/float
# The examples: every .c file in examples/ but the ones in NOT_BENCHMARKS, and the VARIANTS (an
# example's file built again with a -D flag: their rules are under "examples"). A new example is
# its file alone: its head comment's "Smoke: NAME OPTIONS" lines are its runs in make examples-smoke
# (a picture in the README's gallery, if it gets one, is a line of GALLERY_RUNS).
NOT_BENCHMARKS  = hello impl demo
EXAMPLE_SOURCES = $(filter-out $(NOT_BENCHMARKS:%=examples/%.c),$(wildcard examples/*.c))
VARIANTS = spinning_cube ball_plate3d taylor_round
EXAMPLES = $(EXAMPLE_SOURCES:examples/%.c=%) $(VARIANTS)
HEADER   = sphsolid.h
# the test runner tests/test_sphsolid.c includes its parts, one file per part of the library
TEST_FILES = tests/test_numerics.c tests/test_api.c tests/test_solids.c tests/test_fluids.c tests/test_rigid.c tests/test_periodic.c tests/test_open.c

.PHONY: demo demo-smoke gallery probes all check quickstart-run examples examples-smoke run test test-fast test-sanitize fuzz fuzz-sanitize memcheck bench clean

all: check examples $(BUILD)/hello $(BUILD)/beam_reference $(BUILD)/clamp_reference

$(BUILD):
	mkdir -p $(BUILD)

# ---- header checks: every configuration a user may compile it in ----
CHECK_SRC = $(BUILD)/check_impl.c
$(CHECK_SRC): | $(BUILD)
	printf '%s\n' '#define SPHSOLID_IMPLEMENTATION' '#include "../sphsolid.h"' '#include <string.h>' \
	  '/* threads = 2 warns exactly when the build has no OpenMP */' 'static int warned;' \
	  'static void log_fn(int level, const char* m, void* u) { (void)u; warned += level == 1 && strstr(m, "no OpenMP") != 0; }' \
	  'int main(void) {' '    sps_world_def d = sps_default_world_def();' '    sps_world* w = 0;' '    int ok;' \
	  '    d.threads = 2; d.log = log_fn; ok = sps_world_create(&d, &w) == SPS_OK;' '    sps_world_destroy(w);' \
	  '#ifdef _OPENMP' '    return ok && !warned ? 0 : 1;' '#else' '    return ok && warned == 1 ? 0 : 1;' '#endif' '}' > $@
check: $(CHECK_SRC) $(HEADER) README.md examples/hello.c tests/check_compile_out.c
	$(CC) -std=c99 -O1 $(WARN) -Werror -fopenmp $(CHECK_SRC) -o $(BUILD)/check_omp $(LDLIBS)
	$(CC) -std=c99 -O1 $(WARN) -Werror $(CHECK_SRC) -o $(BUILD)/check_serial $(LDLIBS)
	./$(BUILD)/check_omp && ./$(BUILD)/check_serial
	$(CC) -std=c99 -O1 $(WARN) -Werror -DSPHSOLID_FLOAT $(CHECK_SRC) -o $(BUILD)/check_float $(LDLIBS)
	$(CC) -std=c11 -O1 -Wall -Wextra -Werror -DSPHSOLID_STATIC $(CHECK_SRC) -o $(BUILD)/check_static $(LDLIBS)
	cp $(CHECK_SRC) $(BUILD)/check_cpp.cpp
	$(CXX) -std=c++11 -O1 -Wall -Wextra -Werror $(BUILD)/check_cpp.cpp -o $(BUILD)/check_cpp $(LDLIBS)
	@if command -v clang >/dev/null 2>&1; then \
	  clang -std=c99 -O1 $(WARN) -Werror $(CHECK_SRC) -o $(BUILD)/check_clang $(LDLIBS) && echo "clang: ok"; \
	else echo "clang not found: skipped"; fi
	awk '/^## Quick start/{q=1} q&&/^```c/{f=1;next} f&&/^```/{exit} f' README.md > $(BUILD)/quickstart.c
	diff $(BUILD)/quickstart.c examples/hello.c || { echo "the README's quick start differs from examples/hello.c"; exit 1; }
	$(CC) -std=c99 -O1 $(WARN) -Werror -fopenmp -I. $(BUILD)/quickstart.c -o $(BUILD)/quickstart $(LDLIBS)
	{ printf '#define SPHSOLID_IMPLEMENTATION\n#include "sphsolid.h"\n#include <stdio.h>\nint main(void) {\n'; \
	  awk '/QUICK START/{q=1;next} q&&/CONFIG MACROS/{exit} q' $(HEADER); printf 'return 0;\n}\n'; } > $(BUILD)/header_quickstart.c
	$(CC) -std=c99 -O1 $(WARN) -Werror -fopenmp -I. $(BUILD)/header_quickstart.c -o $(BUILD)/header_quickstart $(LDLIBS)
	# the compile-out builds at -O0: they check that each switch compiles cleanly and refuses its kinds;
	# the warnings only the optimiser finds are checked by the -O1 builds of the whole header above
	for out in FLUID GRANULAR PLASTICITY TOTAL_LAGRANGIAN GEOMETRY "FLUID -DSPHSOLID_NO_GRANULAR -DSPHSOLID_NO_PLASTICITY -DSPHSOLID_NO_TOTAL_LAGRANGIAN"; do \
	  $(CC) -std=c99 -O0 $(WARN) -Werror -DSPHSOLID_NO_$$out tests/check_compile_out.c -o $(BUILD)/check_compile_out $(LDLIBS) && \
	  ./$(BUILD)/check_compile_out || { echo "check: SPHSOLID_NO_$$out failed"; exit 1; }; \
	done
	# every bench program (the probes are built only on request) still compiles against the header and the scenes
	for prog in bench/*.c; do $(CC) -std=c99 -fsyntax-only $(WARN) -Werror -fopenmp $$prog || { echo "check: $$prog does not compile"; exit 1; }; done
	@echo "header checks passed (and the quick starts of the README and of the header's manual compile; each compile-out switch; the bench programs)"

# ---- examples ----
$(BUILD)/impl.o: examples/impl.c $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) -c $< -o $@
EXAMPLE_HEADERS = examples/common.h examples/render.h $(wildcard examples/scenes/*.h)
$(BUILD)/%: examples/%.c $(EXAMPLE_HEADERS) $(BUILD)/impl.o
	$(CC) $(CFLAGS) $< $(BUILD)/impl.o -o $@ $(LDLIBS)
examples: $(addprefix $(BUILD)/,$(EXAMPLES))
# the README's quick start: one file, the implementation included, no harness
$(BUILD)/hello: examples/hello.c $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) -I. $< -o $@ $(LDLIBS)
# spinning_cube (A4) is examples/spinning_plate.c (A3) built in 3D
$(BUILD)/spinning_cube: examples/spinning_plate.c $(EXAMPLE_HEADERS) $(BUILD)/impl.o
	$(CC) $(CFLAGS) -DSPINNING_DIM=3 $< $(BUILD)/impl.o -o $@ $(LDLIBS)
$(FLOAT)/spinning_cube: examples/spinning_plate.c $(EXAMPLE_HEADERS) $(FLOAT)/impl.o
	$(CC) $(CFLAGS) -DSPHSOLID_FLOAT -DSPINNING_DIM=3 $< $(FLOAT)/impl.o -o $@ $(LDLIBS)
# ball_plate3d (A10) is examples/ball_plate2d.c (A9) built in 3D
$(BUILD)/ball_plate3d: examples/ball_plate2d.c $(EXAMPLE_HEADERS) $(BUILD)/impl.o
	$(CC) $(CFLAGS) -DBALL_PLATE_DIM=3 $< $(BUILD)/impl.o -o $@ $(LDLIBS)
$(FLOAT)/ball_plate3d: examples/ball_plate2d.c $(EXAMPLE_HEADERS) $(FLOAT)/impl.o
	$(CC) $(CFLAGS) -DSPHSOLID_FLOAT -DBALL_PLATE_DIM=3 $< $(FLOAT)/impl.o -o $@ $(LDLIBS)
# taylor_round (B1) is examples/taylor_square.c (B2) built for the round bar
$(BUILD)/taylor_round: examples/taylor_square.c $(EXAMPLE_HEADERS) $(BUILD)/impl.o
	$(CC) $(CFLAGS) -DTAYLOR_ROUND $< $(BUILD)/impl.o -o $@ $(LDLIBS)
$(FLOAT)/taylor_round: examples/taylor_square.c $(EXAMPLE_HEADERS) $(FLOAT)/impl.o
	$(CC) $(CFLAGS) -DSPHSOLID_FLOAT -DTAYLOR_ROUND $< $(FLOAT)/impl.o -o $@ $(LDLIBS)
# the terminal demo (built like the examples)
demo: $(BUILD)/demo

# ---- the examples built with sps_real = float (bench/knobs.sh measures what float costs) ----
$(FLOAT)/impl.o: examples/impl.c $(HEADER)
	@mkdir -p $(FLOAT)
	$(CC) $(CFLAGS) -DSPHSOLID_FLOAT -c $< -o $@
$(FLOAT)/%: examples/%.c $(EXAMPLE_HEADERS) $(FLOAT)/impl.o
	$(CC) $(CFLAGS) -DSPHSOLID_FLOAT $< $(FLOAT)/impl.o -o $@ $(LDLIBS)
float-examples: $(addprefix $(FLOAT)/,$(EXAMPLES))
# ---- the examples with every pair loop instanced (SPHSOLID_ALL_PAIR_LOOPS: the cubic spline's too;
# bench/side_by_side.sh compares PySPH's spline plate with this build's) ----
ALL_LOOPS = $(BUILD)/all_loops
$(ALL_LOOPS)/impl.o: examples/impl.c $(HEADER)
	@mkdir -p $(ALL_LOOPS)
	$(CC) $(CFLAGS) -DSPHSOLID_ALL_PAIR_LOOPS -c $< -o $@
$(ALL_LOOPS)/%: examples/%.c $(EXAMPLE_HEADERS) $(ALL_LOOPS)/impl.o
	$(CC) $(CFLAGS) $< $(ALL_LOOPS)/impl.o -o $@ $(LDLIBS)

# ---- bench programs: the real-time loop (double and float), the SVG plotter, the file costs ----
$(BUILD)/realtime: bench/realtime.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(FLOAT)/realtime: bench/realtime.c $(EXAMPLE_HEADERS) $(HEADER) $(FLOAT)/impl.o
	$(CC) $(CFLAGS) -DSPHSOLID_FLOAT $< -o $@ $(LDLIBS)
$(BUILD)/user_scenes: bench/user_scenes.c $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/svgplot: bench/svgplot.c | $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) $< -o $@ $(LDLIBS)
$(BUILD)/io_cost: bench/io_cost.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/damping_cost: bench/damping_cost.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/granular_cost: bench/granular_cost.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/rigid_cost: bench/rigid_cost.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/crates_tank: bench/crates_tank.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/periodic_cost: bench/periodic_cost.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/fluid_rest: bench/fluid_rest.c $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/still_water: bench/still_water.c $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/game_tank: bench/game_tank.c $(HEADER) $(EXAMPLE_HEADERS) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/tank_long: bench/tank_long.c $(HEADER) $(EXAMPLE_HEADERS) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/geometry_cost: bench/geometry_cost.c tests/mesh_files.h $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
bench-tools: $(BUILD)/fluid_rest $(BUILD)/still_water $(BUILD)/game_tank $(BUILD)/tank_long $(BUILD)/geometry_cost $(BUILD)/realtime $(FLOAT)/realtime $(BUILD)/user_scenes $(BUILD)/svgplot $(BUILD)/io_cost $(BUILD)/damping_cost $(BUILD)/granular_cost $(BUILD)/rigid_cost $(BUILD)/crates_tank $(BUILD)/periodic_cost
all: float-examples bench-tools
bench-knobs: all
	sh bench/knobs.sh
.PHONY: float-examples bench-tools bench-knobs

run: $(BUILD)/plate2d
	@echo "make run: the 2D plate (H/dp 10, ENO-A) to t = 1 s, about 10 s on 2 cores"
	./$(BUILD)/plate2d --res 10 --vf 0.05 --shear eno-a --tend 1 --out out/plate2d
	@echo "Output in out/plate2d/: the time series plate2d.csv (diagnostics and tip deflection every"; \
	echo "2 ms), VTK snapshots plate2d_0000.vtk ... every 0.1 s (open them in ParaView), and a picture"; \
	echo "of the plate at t = 1 s, plate2d_final.png (von Mises stress; --png-every T for a series)."

# ---- gallery: one picture per example, committed in bench/gallery/ (600 x 400, indexed: 241 KB each) ----
# the 2D plate at its largest deflection (a quarter period), the 3D plate's mode (2,2) at its
# largest deflection, the spinning plate and cube after a few tenths of a turn, the demo scene
# 10 frames after its seventh block was dropped, the punch at 4 ms (pressure), the balls at 5 ms (after the impact),
# the tensile plate at 1 ms, the 2D ball pressing into the plate (0.06 c0, 6 ms), the 3D ball
# pressing into its plate (0.12 c0, 3 ms, seen edge-on)
GALLERY_RUNS = "plate2d --res 10 --tend 0.065" "plate3d --res 2 --mode 2,2 --tend 0.004 --full --png-field displacement --png-view iso" \
               "spinning_plate --dp 0.025 --tend 0.1" "spinning_cube --dp 0.1 --tend 0.1 --png-view iso" \
               "rings2d --dp 0.001 --tend 0.005 --png-field von-mises" \
               "punch2d --dp 0.05 --tend 0.004 --png-field pressure" "balls3d --dp 0.004 --tend 0.005 --png-view iso" \
               "tensile2d --dp 0.025 --tend 0.001" "ball_plate2d --dp 0.005 --v0 0.06 --tend 0.006" \
               "ball_plate3d --dp 0.01 --v0 0.12 --tend 0.003" \
               "taylor_square --res 8" "taylor_round --res 6" "impact2d" \
               "column_collapse2d" "soil_failure2d --transport utvf" "soil_failure3d --res 25 --png-view iso" \
               "flume3d --dp 0.08 --tend 2 --png-view iso" "debris_barrier3d --png-view iso" \
               "tensile3d --res 4 --png-field damage --png-view iso" "floating_block --drop 0.1 --tend 0.45" \
               "hydrostatic_fsi --res 5 --tend 0.1" "elastic_gate --res 3 --tend 0.15" \
               "rigid_float --width 0.2 --height 0.2 --tend 2.5" "rigid_roll --shape disc --dp 0.005 --tend 0.4" \
               "poiseuille --res 20 --tend 0.3" "taylor_green --res 30 --tend 0.5" "cavity --res 20 --tend 2" \
               "channel_flow --res 10 --tend 6" "turek_hron --res 2 --length 1.1 --tend 8"
gallery: examples $(BUILD)/demo $(BUILD)/check_picture
	@mkdir -p bench/gallery
	@for run in $(GALLERY_RUNS); do \
	  set -- $$run; out=$(BUILD)/gallery/$$1; rm -rf $$out; \
	  ./$(BUILD)/$$run --quiet --vtk-every 0 --out $$out >/dev/null && cp $$out/$$1_final.png bench/gallery/$$1.png && \
	  ./$(BUILD)/check_picture bench/gallery/$$1.png || { echo "gallery: $$run failed"; exit 1; }; \
	done
	@./$(BUILD)/demo --headless --frames 140 --png bench/gallery/demo.png >/dev/null && ./$(BUILD)/check_picture bench/gallery/demo.png
	@./$(BUILD)/demo --headless --scene tank --frames 45 --png bench/gallery/demo_tank.png >/dev/null && ./$(BUILD)/check_picture bench/gallery/demo_tank.png
	@echo "gallery: bench/gallery/*.png, one per example"

# ---- tests ----
$(BUILD)/test_sphsolid: tests/test_sphsolid.c $(TEST_FILES) tests/ensure.h $(HEADER) $(wildcard examples/scenes/*.h) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
# the sanitized builds carry no debug information: with -g they took 75 s and 65 s to compile
# (without, 43 s and 40 s), a third of make test's CPU; a report still names the functions, and
# SANITIZE_DEBUG=-g rebuilds them with line numbers
SANITIZE_DEBUG ?=
$(BUILD)/test_sanitize: tests/test_sphsolid.c $(TEST_FILES) tests/ensure.h $(HEADER) $(wildcard examples/scenes/*.h) | $(BUILD)
	$(CC) -std=c99 -O1 $(SANITIZE_DEBUG) $(WARN) -fopenmp $(SANITIZE) $< -o $@ $(LDLIBS)
test-fast: $(BUILD)/test_sphsolid
	./$(BUILD)/test_sphsolid > $(BUILD)/test_fast.log; status=$$?; cat $(BUILD)/test_fast.log; exit $$status
# the thread-count determinism and allocation-counting tests run in the plain runner only: the
# sanitizers add nothing to comparing hashes or counting allocations, and they took 42 s there;
# nor do the longest physics runs (the energy watchdog's scenes, momentum, translation, the
# hydrostatic tank and the long one at rest, the granular block at rest, the tumbling body and the dragged jelly: 21 s + 80 s there), whose code every shorter sanitized test and the sanitized
# random API test (walls, fluids, the watchdog on by default) run too
test-sanitize: $(BUILD)/test_sanitize
	ASAN_OPTIONS=detect_leaks=1 ./$(BUILD)/test_sanitize --quick --exclude determinism_threads --exclude memory_no_allocation \
	  --exclude energy_watchdog --exclude momentum_conservation --exclude translation_keeps_steps --exclude still_water --exclude standing_wave --exclude fluid_rest_long --exclude granular_block \
	  --exclude user_scene_
# the README's quick start, run as printed: it prints only on error and writes strip.vtk
quickstart-run: check
	cd $(BUILD) && rm -f strip.vtk && OMP_WAIT_POLICY=passive ./quickstart > quickstart.out && test ! -s quickstart.out && test -s strip.vtk
	@echo "README quick start: ran to t = 1 s and wrote $(BUILD)/strip.vtk"
# every example, run briefly: it must print its RESULT line and write its CSV, a VTK snapshot and
# its final picture (PNG and SVG, read back by tests/check_picture: valid, and the body visible),
# and a value out of range must end it with exit status 2 (the example contract in the README)
# (the runs: each example's "Smoke:" lines, quoted one run per string; an example without one fails)
SMOKE_RUNS = $(shell sed -n '/^ *Smoke: /{s///;s/ *\*\/.*//;s/.*/"&"/;p;}' $(EXAMPLE_SOURCES))
$(BUILD)/check_picture: tests/check_picture.c | $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) $< -o $@
examples-smoke: examples $(BUILD)/check_picture
	@tested=; for run in $(SMOKE_RUNS); do set -- $$run; tested="$$tested $$1 "; done; \
	for name in $(EXAMPLES); do case "$$tested" in *" $$name "*) ;; \
	  *) echo "examples-smoke: $$name has no \"Smoke: $$name ...\" line in its head comment"; exit 1;; esac; \
	done
	@for run in $(SMOKE_RUNS); do \
	  set -- $$run; out=$(BUILD)/smoke/$$1; rm -rf $$out; \
	  ./$(BUILD)/$$run --quiet --vtk-every 0.005 --svg --out $$out | grep -q '^RESULT case=' && \
	  test -s $$out/$$1.csv && test -s $$out/$$1_0000.vtk && \
	  ./$(BUILD)/check_picture $$out/$$1_final.png && ./$(BUILD)/check_picture --min 50 $$out/$$1_final.svg || \
	  { echo "examples-smoke: $$run failed"; exit 1; }; \
	  ./$(BUILD)/$$1 --cfl 7 >/dev/null 2>&1; status=$$?; \
	  test $$status -eq 2 || { echo "examples-smoke: $$1 --cfl 7 exited $$status, expected 2"; exit 1; }; \
	done
	@out=$(BUILD)/smoke/png_every; rm -rf $$out; \
	./$(BUILD)/plate2d --res 3 --tend 0.01 --quiet --png-every 0.005 --png-field velocity --out $$out >/dev/null && \
	./$(BUILD)/check_picture $$out/plate2d_0000.png $$out/plate2d_0001.png || { echo "examples-smoke: --png-every failed"; exit 1; }
	@echo "examples-smoke: every example ran, wrote CSV, VTK, PNG and SVG, and refused a bad option"
# the demo, headless for 25 frames (a block dropped at frame 10), in each scene: its RESULT line,
# and the same checksum with 1 and 2 threads (frames without a wall budget are deterministic)
demo-smoke: $(BUILD)/demo
	@for scene in playground tank; do \
	one=$$(OMP_NUM_THREADS=1 ./$(BUILD)/demo --headless --frames 25 --scene $$scene) && two=$$(./$(BUILD)/demo --headless --frames 25 --threads 2 --scene $$scene) && \
	echo "$$one" | grep -Eq "^RESULT case=demo frames=25 .*blocks=1 .*checksum=[0-9a-f]{16} .*ms_per_frame=[0-9.]+ .*fps=[0-9.]+ .*scene=$$scene" && \
	test "$$(echo "$$one" | sed 's/.*checksum=\([0-9a-f]*\).*/\1/')" = "$$(echo "$$two" | sed 's/.*checksum=\([0-9a-f]*\).*/\1/')" || \
	{ echo "demo-smoke failed ($$scene): $$one / $$two"; exit 1; }; done; \
	echo "demo-smoke: 25 headless frames in each scene, same checksum with 1 and 2 threads"
# ---- pinned results: hashes of short runs over every formulation, bit for bit (tests/pinned.c) ----
$(BUILD)/pinned: tests/pinned.c tests/pinned_double.inc $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/pinned_float: tests/pinned.c tests/pinned_float.inc $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) -DSPHSOLID_FLOAT $< -o $@ $(LDLIBS)
test-pinned: $(BUILD)/pinned $(BUILD)/pinned_float
	OMP_WAIT_POLICY=passive ./$(BUILD)/pinned
	OMP_WAIT_POLICY=passive ./$(BUILD)/pinned_float
# body-fitted particles (sps_body_add_sdf_relaxed): the papers' ring and ball, determinism, bad input
$(BUILD)/test_relax: tests/test_relax.c tests/ensure.h $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
test-relax: $(BUILD)/test_relax
	./$(BUILD)/test_relax
.PHONY: test-relax
# geometry from files (chapter >>geometry): the readers, every bad input, the sphere's figures, a container
$(BUILD)/test_geometry: tests/test_geometry.c tests/mesh_files.h tests/ensure.h $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
test-geometry: $(BUILD)/test_geometry
	./$(BUILD)/test_geometry $(BUILD)/geometry
.PHONY: test-geometry
# a commit that changes results on purpose regenerates the tables and says why
pinned-update: $(BUILD)/pinned $(BUILD)/pinned_float
	OMP_WAIT_POLICY=passive ./$(BUILD)/pinned --print > tests/pinned_double.inc
	OMP_WAIT_POLICY=passive ./$(BUILD)/pinned_float --print > tests/pinned_float.inc
.PHONY: test-pinned pinned-update

# The parts run two at a time (each prints its output when it is done); the test runner's
# "N passed, M failed" is repeated last so that it closes make test. About 4 minutes on 2 cores.
TEST_PARTS = check quickstart-run examples-smoke demo-smoke test-pinned test-relax test-geometry fuzz fuzz-sanitize fuzz-restore fuzz-mesh test-sanitize test-fast
test:
	@echo "make test: the header checks, examples, demo, pinned results, randomized API test and the test runner (plain and sanitized), two at a time: about 4 minutes on 2 cores (a fresh build included)"
	@$(MAKE) --no-print-directory -j2 --output-sync=target $(TEST_PARTS)
	@tail -n 1 $(BUILD)/test_fast.log

# ---- randomized API test (tests/fuzz_api.c); replay a case: build/fuzz_api --seed S --cases 1 --verbose ----
FUZZ_CASES ?= 10000
$(BUILD)/fuzz_api: tests/fuzz_api.c $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/fuzz_sanitize: tests/fuzz_api.c $(HEADER) | $(BUILD)
	$(CC) -std=c99 -O1 $(SANITIZE_DEBUG) $(WARN) -fopenmp $(SANITIZE) $< -o $@ $(LDLIBS)
# passive OpenMP waits, as the test runner sets for itself: spinning threads crawl on a busy machine
fuzz: $(BUILD)/fuzz_api
	mkdir -p $(BUILD)/fuzz_plain
	OMP_WAIT_POLICY=passive ./$(BUILD)/fuzz_api --cases $(FUZZ_CASES) --out $(BUILD)/fuzz_plain
fuzz-sanitize: $(BUILD)/fuzz_sanitize
	mkdir -p $(BUILD)/fuzz_sanitized
	OMP_WAIT_POLICY=passive ASAN_OPTIONS=detect_leaks=1 ./$(BUILD)/fuzz_sanitize --cases 1000 --out $(BUILD)/fuzz_sanitized

# ---- crafted restart files (tests/fuzz_restore.c): saves of six scenes damaged, their checksum
# recomputed, restored under ASan + UBSan: refused with a message naming the item and the world
# untouched, or restored valid. make test runs FUZZ_RESTORE_CASES of them; fuzz-restore-full the
# 10,000 of the figures in bench/VALIDATION.md ("Untrusted files") ----
FUZZ_RESTORE_CASES ?= 1000
$(BUILD)/fuzz_restore_sanitize: tests/fuzz_restore.c tests/fuzz_restore_scenes.h $(HEADER) | $(BUILD)
	$(CC) -std=c99 -O1 $(SANITIZE_DEBUG) $(WARN) -fopenmp $(SANITIZE) $< -o $@ $(LDLIBS)
fuzz-restore: $(BUILD)/fuzz_restore_sanitize
	OMP_WAIT_POLICY=passive ASAN_OPTIONS=detect_leaks=1 ./$(BUILD)/fuzz_restore_sanitize --cases $(FUZZ_RESTORE_CASES) --dir $(BUILD)
fuzz-restore-full: $(BUILD)/fuzz_restore_sanitize
	OMP_WAIT_POLICY=passive ASAN_OPTIONS=detect_leaks=1 ./$(BUILD)/fuzz_restore_sanitize --cases 10000 --dir $(BUILD)
# coverage-guided (clang's libFuzzer, tests/fuzz_restore_libfuzzer.c) for FUZZ_SECONDS on one core;
# the seeds: tests/restore_corpus/ and this build's saves of the same scenes (a header whose
# fingerprint changed would leave the committed ones behind); findings go to $(BUILD)/libfuzzer/
FUZZ_SECONDS ?= 600
LIBFUZZER_CC ?= clang
$(BUILD)/fuzz_restore_libfuzzer: tests/fuzz_restore_libfuzzer.c tests/fuzz_restore_scenes.h $(HEADER) | $(BUILD)
	$(LIBFUZZER_CC) -std=c99 -O1 -g $(WARN) -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all $< -o $@ $(LDLIBS)
$(BUILD)/fuzz_restore: tests/fuzz_restore.c tests/fuzz_restore_scenes.h $(HEADER) | $(BUILD)
	$(CC) -std=c99 -O1 $(WARN) -fopenmp $< -o $@ $(LDLIBS)
fuzz-libfuzzer: $(BUILD)/fuzz_restore_libfuzzer $(BUILD)/fuzz_restore
	mkdir -p $(BUILD)/libfuzzer/corpus $(BUILD)/libfuzzer/seeds
	./$(BUILD)/fuzz_restore --seeds $(BUILD)/libfuzzer/seeds
	cd $(BUILD)/libfuzzer && ASAN_OPTIONS=detect_leaks=1 nice ../fuzz_restore_libfuzzer -max_total_time=$(FUZZ_SECONDS) -timeout=10 \
	  -rss_limit_mb=2048 -print_final_stats=1 corpus ../../tests/restore_corpus seeds
.PHONY: fuzz-restore fuzz-restore-full fuzz-libfuzzer

# ---- damaged mesh files (tests/fuzz_mesh.c): valid STL, OBJ, outline and SVG files mutated and
# loaded under ASan + UBSan: refused with a message naming the file, or a valid mesh ----
FUZZ_MESH_CASES ?= 10000
$(BUILD)/fuzz_mesh_sanitize: tests/fuzz_mesh.c tests/mesh_files.h $(HEADER) | $(BUILD)
	$(CC) -std=c99 -O1 $(SANITIZE_DEBUG) $(WARN) -fopenmp $(SANITIZE) $< -o $@ $(LDLIBS)
fuzz-mesh: $(BUILD)/fuzz_mesh_sanitize
	ASAN_OPTIONS=detect_leaks=1 ./$(BUILD)/fuzz_mesh_sanitize --cases $(FUZZ_MESH_CASES) --dir $(BUILD)
.PHONY: fuzz-mesh
# the readers against a part OpenSCAD exports, its volume from admesh (tests/cad_check.sh: installs
# Debian's openscad and admesh where it is root, else skips, saying so; .ci/run calls it)
$(BUILD)/cad_check: tests/cad_check.c $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
cad-check: $(BUILD)/cad_check
	sh tests/cad_check.sh $(BUILD)
.PHONY: cad-check

# ---- the demo in a web browser (examples/web/): clang's wasm32 target and Debian's wasi-libc
# (no JavaScript glue to generate: the page's script, demo.js, gives the module the three WASI
# calls wasi-libc makes), one thread (no OpenMP), SIMD128, no FMA contraction (WebAssembly has
# none either): the same checksum as the native headless demo. make test-web opens it in headless
# Chromium (tests/web_check.sh: installs clang, lld, wasi-libc, its wasm32 builtins and chromium as root when missing,
# else skips, saying so; .ci/run calls it). WEB_EXTRA adds compiler flags (web_check.sh shows a
# broken build failing with WEB_EXTRA=-ffast-math). ----
WEB_CC    ?= clang
WEB_EXTRA ?=
# the kinds the demo's scene has no body of are left out (SPHSOLID_NO_*): a 487 KB module instead of 612 KB
WEB_FLAGS  = --target=wasm32-wasi -std=c99 -O2 -msimd128 -ffp-contract=off -fno-math-errno $(WARN) -mexec-model=reactor -Wl,--strip-all \
             -DSPHSOLID_NO_GEOMETRY -DSPHSOLID_NO_TOTAL_LAGRANGIAN -DSPHSOLID_NO_PLASTICITY -DSPHSOLID_NO_GRANULAR
WEB       = $(BUILD)/web
$(WEB)/demo.wasm: examples/web/demo_web.c examples/scenes/demo_play.h $(EXAMPLE_HEADERS) $(HEADER)
	@mkdir -p $(WEB)
	$(WEB_CC) $(WEB_FLAGS) $(WEB_EXTRA) $< -o $@ -lm
$(WEB)/%: examples/web/%
	@mkdir -p $(WEB)
	cp $< $@
web: $(WEB)/demo.wasm $(WEB)/demo.html $(WEB)/demo.js
	@echo "web: $(WEB)/demo.html, demo.js and demo.wasm ($$(cat $^ | wc -c) bytes); serve the folder (python3 -m http.server -d $(WEB)) and open demo.html"
test-web: $(BUILD)/demo
	sh tests/web_check.sh $(BUILD) "$(WEB_EXTRA)"
# the README's picture of the page: headless Chromium, 140 scripted frames (as the gallery's demo.png)
gallery-web: web
	@mkdir -p $(BUILD)/web_check
	node tests/web_run.js $(WEB) 140 $(BUILD)/web_check/gallery_canvas.png bench/gallery/demo_web.png
.PHONY: web test-web gallery-web

# ---- valgrind: serial builds (no OpenMP runtime and its thread caches to suppress) ----
VALGRIND = valgrind -q --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite,indirect
$(BUILD)/test_memcheck: tests/test_sphsolid.c $(TEST_FILES) $(HEADER) $(wildcard examples/scenes/*.h) | $(BUILD)
	$(CC) -std=c99 -O1 -g $(WARN) $< -o $@ $(LDLIBS)
$(BUILD)/fuzz_memcheck: tests/fuzz_api.c $(HEADER) | $(BUILD)
	$(CC) -std=c99 -O1 -g $(WARN) $< -o $@ $(LDLIBS)
# OMP_WAIT_POLICY set: the runner re-executes itself without it, and valgrind does not follow exec.
# The thread-count determinism test is left out: serial, it compares identical runs, and under
# valgrind it alone takes over 5 minutes.
memcheck: $(BUILD)/test_memcheck $(BUILD)/fuzz_memcheck
	OMP_WAIT_POLICY=passive $(VALGRIND) ./$(BUILD)/test_memcheck --quick --exclude determinism_threads
	mkdir -p $(BUILD)/fuzz_memcheck_out
	$(VALGRIND) ./$(BUILD)/fuzz_memcheck --cases 300 --out $(BUILD)/fuzz_memcheck_out

# ---- bench ----
bench: examples
	sh bench/run_bench.sh
# probes that reach into the library's private state (sps__ functions): built only on request
probes: $(BUILD)/torque_probe $(BUILD)/rotation_probe $(BUILD)/pass_bound $(BUILD)/pass_bound_arith $(BUILD)/fsi_cost $(BUILD)/particle_cost $(BUILD)/open_cost $(BUILD)/pair_once
# each neighbour pass against its gathers alone and its arithmetic alone (bench/pass_bound.sh)
$(BUILD)/pass_bound: bench/pass_bound.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/pass_bound_arith: bench/pass_bound.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) -DPASS_BOUND_ARITHMETIC $< -o $@ $(LDLIBS)
# each pair computed once (half lists) against from both sides: the two passes of ENO-A, one thread
$(BUILD)/pair_once: bench/pair_once.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
# what one particle costs: time per sub-step, bytes, neighbours, contact pairs (bench/scaling.sh)
$(BUILD)/particle_cost: bench/particle_cost.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(FLOAT)/particle_cost: bench/particle_cost.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	@mkdir -p $(FLOAT)
	$(CC) $(CFLAGS) -DSPHSOLID_FLOAT $< -o $@ $(LDLIBS)
# open boundaries: the step time while the particle count changes, with and without sps_world_reserve
$(BUILD)/open_cost: bench/open_cost.c $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
# the fluid-structure coupling's cost against the fluid passes alone
$(BUILD)/fsi_cost: bench/fsi_cost.c $(EXAMPLE_HEADERS) $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/torque_probe: bench/torque_probe.c bench/kick_shear.h $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
$(BUILD)/rotation_probe: bench/rotation_probe.c bench/kick_shear.h $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
# the variational TL hourglass force's cost against the paper's, in one process (bench/VALIDATION.md)
$(BUILD)/tl_hourglass_cost: bench/tl_hourglass_cost.c $(HEADER) | $(BUILD)
	$(CC) $(CFLAGS) $< -o $@ $(LDLIBS)
# beam-theory reference for the 2D plate's period: plain C99, libm only (no header, no OpenMP)
$(BUILD)/beam_reference: bench/beam_reference.c bench/cantilever.h | $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) $< -o $@ $(LDLIBS)
# plane-strain finite-element reference for the same period and the clamp's effect (libm only)
$(BUILD)/clamp_reference: bench/clamp_reference.c bench/cantilever.h | $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) $< -o $@ $(LDLIBS)

clean:
	rm -rf $(BUILD) out
