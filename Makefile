# sinew — top-level build.  `make` builds the runtime library (and, later, the
# compiler); `make test` and `make demo` install missing Debian packages first
# (scripts/deps.sh) and then re-enter make so pkg-config sees them.
#
# Layout of build outputs (never committed):
#   build/libsinewrt.a          optimised runtime, for this machine's CPU
#                               (-O3 -march=native; what sinewc links)
#   build/libsinewrt-portable.a for any x86-64 (-O3, baseline ISA; sinewc --portable)
#   build/asan/libsinewrt.a     runtime under AddressSanitizer + UBSan
#   build/tests/test_*          optimised test binaries (cmocka, TAP output)
#   build/asan/tests/test_*     sanitizer test binaries
CC      ?= cc
PKGS     = hdf5 gsl
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null)
WARN     = -Wall -Wextra -Wshadow -Wstrict-prototypes -Wmissing-prototypes
STD      = -std=c11 -D_DEFAULT_SOURCE
# The runtime is built for the CPU of the machine `make` runs on, like the
# simulators sinewc builds (docs/benchmarks.md); -fopenmp: the kernels'
# `#pragma omp simd` loops and the threads of a step (libgomp, which comes
# with GCC).
OPT      = -O3 -march=native -fno-math-errno -fopenmp -g
PORTABLE = -O3 -fno-math-errno -fopenmp -g
CFLAGS  ?= $(OPT)
SAN      = -O1 -g -fopenmp -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all
# The runtime's rooms (docs/runtime.md): the public header's parts in
# runtime/include/, what every file may include as "sinew.h"; a room's own
# headers by name within it ("internal.h"), another room's by its path from
# runtime/ ("engine/internal.h"), so the arrows between rooms show in the
# includes (tests/lang/test_layout.sh checks them).
RT_INC   = -Iruntime/include -Iruntime
# The white-box tests and benchmarks reach the rooms' internal headers by name.
TEST_INC = -Iruntime/engine -Iruntime/io -Iruntime/study
ALL_CFLAGS = $(STD) $(WARN) $(CFLAGS) $(RT_INC) $(PKG_CFLAGS)
SAN_CFLAGS = $(STD) $(WARN) $(SAN) $(RT_INC) $(PKG_CFLAGS)
# Our own programs (sinewc, the tests, the benchmarks) are linked by gold
# where the compiler has it, as sinewc links the simulators
# (scripts/sim_linker.sh): an ASan test binary's link 0.44-0.64 s with GNU
# ld, 0.24-0.28 s with gold, and `make test` links some sixty of them.
LD_FAST := $(shell sh scripts/sim_linker.sh $(CC))
LIBS     = $(LD_FAST) $(PKG_LIBS) -lm

# The runtime in its rooms: include/ (the public header), engine/, io/,
# study/, sim/.  study/study_mpi.c is the one runtime file that needs MPI: it
# is built on its own (below), only where mpicc exists, and never into the
# libraries.
RT_ROOMS = engine io study sim
RT_SRC   = $(filter-out runtime/study/study_mpi.c,$(foreach r,$(RT_ROOMS),$(wildcard runtime/$(r)/*.c)))
RT_HDR   = $(wildcard runtime/include/*.h) $(foreach r,$(RT_ROOMS),$(wildcard runtime/$(r)/*.h))
RT_OBJ   = $(RT_SRC:runtime/%.c=build/rt/%.o)
RT_SOBJ  = $(RT_SRC:runtime/%.c=build/asan/rt/%.o)
RT_POBJ  = $(RT_SRC:runtime/%.c=build/portable/rt/%.o)

TEST_SRC = $(wildcard tests/runtime/test_*.c)
TEST_BIN = $(TEST_SRC:tests/runtime/%.c=build/tests/%)
# Tests cheap enough to run again under the sanitizers (the long validation
# runs are exercised there with reduced sizes via SW_SANITIZED=1).
TEST_SBIN = $(TEST_SRC:tests/runtime/%.c=build/asan/tests/%)

.PHONY: all deps test check check-build demo bench clean install plots
all: build/libsinewrt.a build/libsinewrt-portable.a $(MPI_OBJ) bin/sinewc

# ---- the compiler: flex + bison front end (lang/), checker and generator
# (compiler/).  Generated parser sources are build outputs, never committed.
CC_SRC   = $(wildcard compiler/*.c)
CC_HDR   = $(wildcard compiler/*.h) build/lang/sinew.tab.h
CC_OBJ   = $(CC_SRC:compiler/%.c=build/cc/%.o) build/cc/sinew.tab.o build/cc/lex.yy.o
CC_SOBJ  = $(CC_SRC:compiler/%.c=build/asan/cc/%.o) build/asan/cc/sinew.tab.o build/asan/cc/lex.yy.o
CC_INC   = -Icompiler -Ibuild/lang -Iruntime/include
# flex output is not written for our warning set
GEN_WARN = -Wno-unused-function -Wno-sign-compare -Wno-missing-prototypes -Wno-unused-parameter
# MPI (OpenMPI from Debian): where mpicc exists, runtime/study/study_mpi.c becomes
# build/sinewrt_mpi.o, which sinewc links into every simulator beside the
# runtime (with mpicc's libraries), so that `mpirun -np N SIM --optimize`
# farms the evaluations out; without mpicc the simulators build and study on
# one machine (docs/optimisation.md).
# (openmpi-bin has mpicc; its mpi.h comes with libopenmpi-dev)
MPICC     := $(shell command -v mpicc 2>/dev/null)
ifneq ($(MPICC),)
MPI_CFLAGS := $(shell mpicc --showme:compile 2>/dev/null)
ifneq ($(wildcard $(patsubst -I%,%/mpi.h,$(filter -I%,$(MPI_CFLAGS)))),)
MPI_LIBS   := $(shell mpicc --showme:link)
MPI_OBJ    := build/sinewrt_mpi.o
endif
endif
# (named again here: `all`'s line above is read before MPI_OBJ is set)
all: $(MPI_OBJ)
# the flags sinewc passes to the C compiler when it builds a simulator:
# HDF5 from its static archive where one links (scripts/hdf5_link.sh says
# why), run only when sinewc.c is compiled (the variable is expanded there),
# and LD_FAST above, gold where the compiler has it
HDF5_LINK = $(shell sh scripts/hdf5_link.sh $(CC))
RT_LINK  = -DSW_RT_CFLAGS='"$(PKG_CFLAGS)"' \
           -DSW_RT_LIBS='"$(HDF5_LINK) $(shell pkg-config --libs gsl 2>/dev/null) -lm"' \
           -DSW_RT_MPI_LIBS='"$(MPI_LIBS)"' \
           -DSW_RT_LDFLAGS='"$(LD_FAST)"' -DSW_RT_CC='"$(CC)"'

build/lang/sinew.tab.c build/lang/sinew.tab.h: lang/sinew.y | build/lang
	bison -Wall -Werror -d -o build/lang/sinew.tab.c lang/sinew.y
build/lang/lex.yy.c: lang/sinew.l build/lang/sinew.tab.h | build/lang
	flex -o $@ lang/sinew.l
build/cc/%.o: compiler/%.c $(CC_HDR) $(RT_HDR) | build/cc
	$(CC) $(ALL_CFLAGS) $(CC_INC) -c $< -o $@
build/cc/sinewc.o: compiler/sinewc.c $(CC_HDR) $(RT_HDR) scripts/hdf5_link.sh | build/cc
	$(CC) $(ALL_CFLAGS) $(CC_INC) $(RT_LINK) -c $< -o $@
build/cc/%.o: build/lang/%.c $(CC_HDR) $(RT_HDR) | build/cc
	$(CC) $(ALL_CFLAGS) $(GEN_WARN) $(CC_INC) -c $< -o $@
build/asan/cc/%.o: compiler/%.c $(CC_HDR) $(RT_HDR) | build/asan/cc
	$(CC) $(SAN_CFLAGS) $(CC_INC) -c $< -o $@
build/asan/cc/sinewc.o: compiler/sinewc.c $(CC_HDR) $(RT_HDR) scripts/hdf5_link.sh | build/asan/cc
	$(CC) $(SAN_CFLAGS) $(CC_INC) $(RT_LINK) -c $< -o $@
build/asan/cc/%.o: build/lang/%.c $(CC_HDR) $(RT_HDR) | build/asan/cc
	$(CC) $(SAN_CFLAGS) $(GEN_WARN) $(CC_INC) -c $< -o $@
bin/sinewc: $(CC_OBJ) build/libsinewrt.a | bin
	$(CC) $(ALL_CFLAGS) $(CC_OBJ) -o $@ build/libsinewrt.a $(LIBS)
build/asan/sinewc: $(CC_SOBJ) build/asan/libsinewrt.a
	$(CC) $(SAN_CFLAGS) $(CC_SOBJ) -o $@ build/asan/libsinewrt.a $(LIBS)
# The fuzzing harness (tests/fuzz/fuzz_sinewc.c, docs/fuzzing.md) built with
# the plain C compiler is a replay program, `fuzz_sinewc FILE...`: the front
# end of sinewc (every compiler object but sinewc.o) under the sanitizers,
# which tests/lang/test_fuzz_harness.sh runs on the seeds and regressions, so
# that the harness scripts/fuzz.sh builds for AFL++ keeps building.
FUZZ_SOBJ = $(filter-out build/asan/cc/sinewc.o,$(CC_SOBJ))
build/asan/fuzz_sinewc: tests/fuzz/fuzz_sinewc.c $(FUZZ_SOBJ) build/asan/libsinewrt.a $(CC_HDR)
	$(CC) $(SAN_CFLAGS) $(CC_INC) $< $(FUZZ_SOBJ) -o $@ build/asan/libsinewrt.a $(LIBS)
build/lang build/cc build/asan/cc bin:
	@mkdir -p $@

deps:
	@sh scripts/deps.sh

build/rt/%.o: runtime/%.c $(RT_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -c $< -o $@
build/asan/rt/%.o: runtime/%.c $(RT_HDR)
	@mkdir -p $(@D)
	$(CC) $(SAN_CFLAGS) -c $< -o $@
build/libsinewrt.a: $(RT_OBJ)
	rm -f $@ && ar rcs $@ $^
# for any x86-64 (like the portable library): it only passes messages
build/sinewrt_mpi.o: runtime/study/study_mpi.c $(RT_HDR) | build/rt
	$(CC) $(STD) $(WARN) $(PORTABLE) $(RT_INC) $(MPI_CFLAGS) -c $< -o $@
build/asan/libsinewrt.a: $(RT_SOBJ)
	rm -f $@ && ar rcs $@ $^
build/portable/rt/%.o: runtime/%.c $(RT_HDR)
	@mkdir -p $(@D)
	$(CC) $(STD) $(WARN) $(PORTABLE) $(RT_INC) $(PKG_CFLAGS) -c $< -o $@
build/libsinewrt-portable.a: $(RT_POBJ)
	rm -f $@ && ar rcs $@ $^

build/tests/%: tests/runtime/%.c tests/runtime/testutil.h tests/runtime/h5read.h tests/runtime/twist_rod.h build/libsinewrt.a | build/tests
	$(CC) $(ALL_CFLAGS) $(TEST_INC) -Itests/runtime $< -o $@ build/libsinewrt.a $(LIBS) -lcmocka
build/asan/tests/%: tests/runtime/%.c tests/runtime/testutil.h tests/runtime/h5read.h tests/runtime/twist_rod.h build/asan/libsinewrt.a | build/asan/tests
	$(CC) $(SAN_CFLAGS) $(TEST_INC) -Itests/runtime $< -o $@ build/asan/libsinewrt.a $(LIBS) -lcmocka

build/rt build/tests build/asan/tests build/bench:
	@mkdir -p $@

# `make test`: install what is missing, then build everything, one compiler
# per core (a clean build, serial, took about a third of CI's time), and run
# everything under prove (TAP); prove's summary is the last line.  The tests
# run from a make of their own, without the parallel build's jobserver,
# which the makes some tests start would otherwise inherit.
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
test: deps
	@$(MAKE) --no-print-directory -j$(JOBS) check-build
	@$(MAKE) --no-print-directory check

# Language tests are TAP shell scripts (tests/lang/test_*.sh) driving the
# compiler: the optimised bin/sinewc and the sanitizer build build/asan/sinewc.
LANG_TESTS = $(wildcard tests/lang/test_*.sh)
# End-to-end tests compile models with the sanitizer build of sinewc, run the
# simulators and check their HDF5 output against closed forms.
# test_elbow runs the arm scenes of issue 4 with the optimised bin/sinewc (long);
# test_snake, test_swimmer, test_walker and test_chain likewise run their example scenes with it.
E2E_BIN  = build/tests/test_e2e build/tests/test_elbow build/tests/test_snake \
           build/tests/test_swimmer build/tests/test_walker build/tests/test_chain
$(E2E_BIN): build/tests/test_%: tests/e2e/test_%.c tests/e2e/e2e.h tests/runtime/h5read.h | build/tests
	$(CC) $(ALL_CFLAGS) -Itests/runtime -Itests/e2e $< -o $@ $(LIBS) -lcmocka
# tests/mpi/mpi_study.c: the study driver under mpirun (test_mpi.sh), where
# mpicc exists
MPI_TEST = $(if $(MPI_OBJ),build/tests/mpi_study)
build/tests/mpi_study: tests/mpi/mpi_study.c $(MPI_OBJ) build/libsinewrt.a | build/tests
	$(CC) $(ALL_CFLAGS) $(TEST_INC) $< -o $@ $(MPI_OBJ) build/libsinewrt.a $(LIBS) $(MPI_LIBS)
# Three test files at a time on two cores: several wait on mpirun, xvfb or a
# timeout much of their run (381 s of tests with -j2, 344 s with -j3, this
# machine idle), which kept `.ci/run` inside its 10 minutes there.  On a
# later machine (AMD EPYC, cpu family 26, two logical CPUs, 2026-12-01) the
# same suite is CPU-bound and its time follows the machine's load: the
# whole `.ci/run` took 606, 650 and 698 s in three clean-clone runs within
# an hour (the tests' CPU 915, 982 and 1059 s), against 562-579 s the
# day before; 634 s on 2026-12-02 (tests 500 s), then 582 s (tests 444 s)
# with the simulators linked by gold (scripts/sim_linker.sh: the suite
# builds 441 of them, 0.69 s each under its load with GNU ld), 604 s in
# another run, and 599 s (tests 484 s) with our own links by gold too.
# The runtime's unit tests run under the sanitizers (TEST_SBIN), the
# stricter build of the same code (there are no paths of its own in the
# optimised one: no intrinsics, no -march-specific source); the optimised
# runtime runs in every scene of E2E_BIN and tests/lang.  `make check-opt`
# runs the unit tests optimised too (once part of `make test`: 46 s of CPU
# for nothing the sanitizer run did not already check).
CHECK_BUILD = $(TEST_SBIN) $(E2E_BIN) build/libsinewrt.a build/libsinewrt-portable.a \
              $(MPI_OBJ) $(MPI_TEST) bin/sinewc build/asan/sinewc build/asan/fuzz_sinewc
check-build: $(CHECK_BUILD)
check: $(CHECK_BUILD)
	@mkdir -p build/validation   # measured tables the validation tests leave for `make plots`
	@SINEWC=build/asan/sinewc CMOCKA_MESSAGE_OUTPUT=TAP prove -j3 --timer --exec '' \
	  $(E2E_BIN) $(TEST_SBIN) $(LANG_TESTS)
.PHONY: check-opt
check-opt: $(TEST_BIN)
	@CMOCKA_MESSAGE_OUTPUT=TAP prove -j2 --exec '' $(TEST_BIN)

BENCH_BIN = build/bench/bench_rod
# The benchmark report states the flags the runtime was built with; they are
# not known at run time, so they are passed in as a string.
BENCH_FLAGS = -DSW_BENCH_CFLAGS='"$(CC) $(STD) $(CFLAGS)"'
build/bench/bench_rod: bench/bench_rod.c build/libsinewrt.a | build/bench
	$(CC) $(ALL_CFLAGS) $(BENCH_FLAGS) $< -o $@ build/libsinewrt.a $(LIBS)
# The x86-64 levels side by side (bench/bench_isa.sh): the runtime and
# bench_rod built for x86-64-v3 (AVX2 and FMA: most laptops, AMD Zen 2 and 3)
# and for x86-64-v4 (AVX-512), both with the generic tuning, so that on a
# CPU that runs both the one difference between them is the instruction set.
# Built by `make bench` only (bench/bench_isa.sh builds and runs the v4 one
# only where the CPU has AVX-512).
ISA_OPT = -O3 -fno-math-errno -fopenmp -g
RT_V3OBJ = $(RT_SRC:runtime/%.c=build/v3/rt/%.o)
RT_V4OBJ = $(RT_SRC:runtime/%.c=build/v4/rt/%.o)
build/v3/rt/%.o: runtime/%.c $(RT_HDR)
	@mkdir -p $(@D)
	$(CC) $(STD) $(WARN) -march=x86-64-v3 $(ISA_OPT) $(RT_INC) $(PKG_CFLAGS) -c $< -o $@
build/v4/rt/%.o: runtime/%.c $(RT_HDR)
	@mkdir -p $(@D)
	$(CC) $(STD) $(WARN) -march=x86-64-v4 $(ISA_OPT) $(RT_INC) $(PKG_CFLAGS) -c $< -o $@
build/libsinewrt-v3.a: $(RT_V3OBJ)
	rm -f $@ && ar rcs $@ $^
build/libsinewrt-v4.a: $(RT_V4OBJ)
	rm -f $@ && ar rcs $@ $^
build/bench/bench_rod_v3 build/bench/bench_rod_v4: build/bench/bench_rod_%: bench/bench_rod.c build/libsinewrt-%.a | build/bench
	$(CC) $(STD) $(WARN) -march=x86-64-$* $(ISA_OPT) $(RT_INC) $(PKG_CFLAGS) \
	  -DSW_BENCH_CFLAGS='"$(CC) $(STD) -march=x86-64-$* $(ISA_OPT)"' $< -o $@ build/libsinewrt-$*.a $(LIBS)
# bench_rigid (one bone elastic vs rigid) replaces or appends its own section
# of the report bench_rod has just written.
BENCH_RIGID = build/bench/bench_rigid
build/bench/bench_rigid: bench/bench_rigid.c bench/bench_util.h build/libsinewrt.a | build/bench
	$(CC) $(ALL_CFLAGS) $< -o $@ build/libsinewrt.a $(LIBS)
# bench_contact (rod-rod contact: grid vs brute force against rod count)
# replaces or appends its own section.
BENCH_CONTACT = build/bench/bench_contact
build/bench/bench_contact: bench/bench_contact.c bench/bench_util.h build/libsinewrt.a | build/bench
	$(CC) $(ALL_CFLAGS) $(TEST_INC) $< -o $@ build/libsinewrt.a $(LIBS)
# bench_obstacle (the obstacles' broad phase: chunk boxes vs brute force
# against the number of obstacles) replaces or appends its own section.
BENCH_OBSTACLE = build/bench/bench_obstacle
build/bench/bench_obstacle: bench/bench_obstacle.c bench/bench_util.h build/libsinewrt.a | build/bench
	$(CC) $(ALL_CFLAGS) $(TEST_INC) $< -o $@ build/libsinewrt.a $(LIBS)
# bench_pile (contact-heavy scenes: a rope pile settled in a box, a rope on
# a post, ns per element-step against the contacts) replaces or appends its
# own section.
BENCH_PILE = build/bench/bench_pile
build/bench/bench_pile: bench/bench_pile.c bench/bench_util.h build/libsinewrt.a | build/bench
	$(CC) $(ALL_CFLAGS) $(BENCH_FLAGS) $(TEST_INC) $< -o $@ build/libsinewrt.a $(LIBS)
# bench_scaling (10^2 to 10^6 elements, one rod or many, 1 and 2 threads,
# memory per element) replaces or appends its own section.
BENCH_SCALING = build/bench/bench_scaling
build/bench/bench_scaling: bench/bench_scaling.c bench/bench_util.h build/libsinewrt.a | build/bench
	$(CC) $(ALL_CFLAGS) $< -o $@ build/libsinewrt.a $(LIBS)
bench: deps
	@$(MAKE) --no-print-directory $(BENCH_BIN) $(BENCH_RIGID) $(BENCH_CONTACT) $(BENCH_OBSTACLE) $(BENCH_PILE) $(BENCH_SCALING) bin/sinewc
	@./$(BENCH_BIN) docs/benchmarks.md
	@sh bench/bench_isa.sh docs/benchmarks.md   # bench_rod at x86-64-v3 and -v4, before issue 31 and now, side by side, and the vectorizer on aarch64 (~6 min, ~3 more the first time)
	@sh bench/bench_aarch64.sh docs/benchmarks.md   # the whole runtime and compiler built for 64-bit Arm (NEON, SVE), the rod step's bits and the fast runtime tests under qemu-aarch64 (~5 min; ~2 more the first time, for the packages)
	@sh bench/bench_pyelastica.sh docs/benchmarks.md   # PyElastica's Verlet against bench_rod's, n = 50, 100, 200, interleaved (~6 min; only with PyElastica's source in SW_PYELASTICA or build/pyelastica)
	@sh bench/bench_assisted.sh docs/benchmarks.md   # the assisted elbow against the reference's Elbow.cpp, 2 ms at 50 ns, interleaved (~4 min; only with its binary in SW_ELASTICA_ELBOW)
	@./$(BENCH_RIGID) docs/benchmarks.md
	@./$(BENCH_CONTACT) docs/benchmarks.md
	@./$(BENCH_OBSTACLE) docs/benchmarks.md
	@./$(BENCH_PILE) docs/benchmarks.md   # ~1 min
	@./$(BENCH_SCALING) docs/benchmarks.md   # ~2 min
	@sh bench/bench_speedup.sh      # the elbow, before issue 10 and now, side by side (~2 min)
	@sh bench/bench_elbow.sh        # the elbow at 50 ns and at the stable dt (~20 min)
	@sh bench/bench_snake.sh        # the snake scenes in full (~3 min)
	@sh bench/bench_stiff.sh        # imex on the elbow and the bone chain (~5 min)
	@sh bench/bench_implicit_snake.sh # the hardened snakes, explicit vs implicit rods (~4 min)
	@sh bench/bench_implicit_step.sh f3f867e # the implicit rod step against the explicit one, n = 50, 100, 200, before issue 31 and now, interleaved (~3 min; prints the table of docs/benchmarks.md, "The implicit rod step (issue 31)")
	@sh bench/bench_rigid_groups.sh # the implicit rigid joints, before issue 13's groups and now (~5 min)
	@sh bench/bench_snake_eval.sh d64eaa7 # the muscular snake's 5 s evaluation and example, before their rings and Hill damping joined the system and now, interleaved (~4 min; the table of docs/benchmarks.md, "Rings and Hill damping in the system")
	@sh bench/bench_study.sh        # a study's evaluations per second on 1, 2 and 4 MPI ranks, and the muscular snake's on 1 and 2 (~5 min)
	@sh bench/bench_time_to_solution.sh # each study of Zhang et al. 2019: its step checked against a quarter of it, its whole simulated time run (~8 min of CPU; 16 min on a shared machine)

# `make bench-sundials`: SUNDIALS's ARKODE (IMEX ARKStep, MRIStep) against
# the imex kick on a 1-D model of a biceps filament between its tendons
# (bench/eval_sundials.c; the figures and the decision are in
# docs/dependencies.md).  Optional: libsundials-dev is installed here, when
# missing, and nowhere else; neither `make test` nor `make bench` needs it.
# SUNDIALS_SRC=<a SUNDIALS source tree> also runs it against that release
# built with optimisation (bench/eval_sundials.sh), as Debian's is not.
SUNDIALS_LIBS = -lsundials_arkode -lsundials_nvecserial -lsundials_sunlinsoldense \
                -lsundials_sunmatrixdense -lm
SUNDIALS_SRC ?=
.PHONY: bench-sundials
bench-sundials:
	@[ -e /usr/include/arkode/arkode_arkstep.h ] || { echo "bench-sundials: installing libsundials-dev" >&2; \
	  SUDO=""; [ "$$(id -u)" = 0 ] || SUDO=sudo; export DEBIAN_FRONTEND=noninteractive; \
	  $$SUDO apt-get update -qq >/dev/null && \
	  $$SUDO apt-get install -y -qq --no-install-recommends libsundials-dev >/dev/null; }
	@$(MAKE) --no-print-directory build/bench/eval_sundials
	./build/bench/eval_sundials
	@if [ -n "$(SUNDIALS_SRC)" ]; then sh bench/eval_sundials.sh "$(SUNDIALS_SRC)"; fi
build/bench/eval_sundials: bench/eval_sundials.c bench/bench_util.h | build/bench
	$(CC) $(STD) $(WARN) -O3 -march=native -g -DEVAL_SUNDIALS_BUILD='"Debian libsundials-dev"' \
	  $< -o $@ $(SUNDIALS_LIBS)

# `make demo`: the elbow of examples/elbow_flexion.sinew (0.5 s) in its
# fastest configuration within 1% of the 50 ns reference (docs/physics.md,
# "Joints on implicit rods"): the full arm (20/7/14 elements), its bones and
# tendons implicit with every joint on them and the filaments' Hill damping
# in one linear system, imex at dt = 125 us, 8 steps per 1 ms frame (the
# stable-step estimate --info prints, 1.59 ms, does not hold for this
# configuration: it runs to 450 us, and 500 us is 45% off).  It prints
# --info, runs the scene (~0.5 s of one core), compares the elbow angle and
# the long head's force with the reference's curves stored in DEMO_REF and
# plots both runs into build/demo/elbow_flexion.png; its last line says how
# long the run took and how far it is from the reference (more than 1% is
# a failure).
DEMO_MODEL = examples/elbow_flexion.sinew
DEMO_LETS = --let implicit_bones=true --let implicit_tendons=true
DEMO_RUN = --integrator imex --dt 125us
DEMO_REF = examples/reference/elbow_flexion_50ns.csv
demo: deps
	@$(MAKE) --no-print-directory bin/sinewc
	@mkdir -p build/demo
	./bin/sinewc $(DEMO_MODEL) $(DEMO_LETS) -o build/demo/sim
	./build/demo/sim $(DEMO_RUN) --info | grep -v '\.f[0-9][0-9]'
	@echo "./build/demo/sim $(DEMO_RUN) --out build/demo/elbow_flexion.h5"; \
	  t0=$$(date +%s.%N); \
	  ./build/demo/sim $(DEMO_RUN) --out build/demo/elbow_flexion.h5 || exit $$?; \
	  t1=$$(date +%s.%N); \
	  scripts/demo_elbow.py compare build/demo/elbow_flexion.h5 $(DEMO_REF) \
	    -o build/demo/elbow_flexion.png --within 1 --wall $$(awk "BEGIN { print $$t1 - $$t0 }")

# `make demo-reference`: run the reference of `make demo` again (position
# Verlet, the scene's integrator, at 50 ns: ~5 min of one core) and store its
# curves in DEMO_REF, for when the scene or the model has changed
# (tests/lang/test_demo_reference.sh fails then).
.PHONY: demo-reference
demo-reference: deps
	@$(MAKE) --no-print-directory bin/sinewc
	@mkdir -p build/demo
	./bin/sinewc $(DEMO_MODEL) -o build/demo/sim_reference
	@echo "./build/demo/sim_reference --dt 50ns --quiet --out build/demo/reference_50ns.h5"; \
	  t0=$$(date +%s.%N); \
	  ./build/demo/sim_reference --dt 50ns --quiet --out build/demo/reference_50ns.h5 || exit $$?; \
	  t1=$$(date +%s.%N); \
	  scripts/demo_elbow.py reference build/demo/reference_50ns.h5 -o $(DEMO_REF) \
	    --command "bin/sinewc $(DEMO_MODEL) -o SIM && SIM --dt 50ns" \
	    --wall $$(awk "BEGIN { print $$t1 - $$t0 }")

# `make plots`: the figures of docs/img/ from the outputs that exist
# (scripts/plots.sh says which inputs it found and which it skipped).
plots: deps
	@sh scripts/plots.sh

# `make study-snake`: the muscular snake's bottom-up study (Zhang et al. 2019,
# Suppl. Note 4, Fig. 2; issue 13): CMA-ES over 1 to 5 muscle-tendon pairs
# and over the continuum snake, 300 evaluations of 5 s each, under
# `mpirun -np 2`; study files in study/ (an interrupted study continues
# where it stopped), the table in study/report.md and the plots
# docs/img/study_snake_*.png (~1.5 h on this machine's 2 cores; never part
# of `make test`, whose test_snake_muscular runs a short study).
# STUDY_ARGS="--budget 1000 --np 8" for a larger one, or a subset: "4 5";
# STUDY_ARGS="--chain --budget 250" for the chained study (2 to 5 pairs,
# each started at the best design with one pair fewer; ~1.2 h here).
.PHONY: study-snake
study-snake: deps
	@$(MAKE) --no-print-directory all
	@sh scripts/study_snake.sh --out study $(STUDY_ARGS)

# `make wing`: the feathered wing's full runs (docs/validation.md, "The
# feathered wing"): models/pigeon_wing.sinew over its 0.51 s, the original
# and Suppl. Fig. 13's variants two at a time, then the angles, the stroke's
# frames and the variants' table and plot in build/wing/ (about 1.5 h on
# this machine's 2 cores; never part of `make test`, whose test_wing runs
# 20 us).  WING_ARGS="original" for the original alone (~10 min on an idle
# machine, more when the other core is busy: docs/benchmarks.md);
# WING_ARGS="original resolved" adds the fully resolved wing (about 26 min)
# and its angles against the original's (build/wing/resolved.png);
# "resolved resolved_soft resolved_soft_twist" Fig. 13 (c) and (d) on the
# resolved wing (build/wing/resolved_fig13.md; about 45 min, two at a time),
# resolved_hard its (b) (about 80 min); control, muscle twist x0.99.
.PHONY: wing
wing: deps
	@$(MAKE) --no-print-directory all
	@sh scripts/wing_study.sh --out build/wing $(WING_ARGS)

# `make assisted`: the injured elbow assisted by an artificial muscle
# (docs/validation.md, "The elbow assisted by an artificial muscle"; Zhang
# et al. 2019, Suppl. Fig. 7): examples/elbow_assisted.sinew healthy,
# injured and with the AM at three release rates, 0.7 s each, two at a
# time, then build/assisted/assisted.png and assisted.md (about 8 min on
# this machine's 2 cores; never part of `make test`, whose test_assisted
# runs 30 ms).  ASSISTED_ARGS="am_1" for one case.
.PHONY: assisted
assisted: deps
	@$(MAKE) --no-print-directory all
	@sh scripts/assisted_study.sh --out build/assisted $(ASSISTED_ARGS)

# `make plectoneme`: the twisted rod under tension that buckles into a
# plectoneme with self-contact (docs/validation.md, "Self-contact: the
# plectoneme"; issue 34): examples/plectoneme.sinew at three twisting rates,
# the control without self-contact and a thinner rod, then
# docs/img/plectoneme.png and build/plectoneme/plectoneme.md (about 4 min
# on this machine's 2 cores; never part of `make test`, whose
# test_plectoneme runs one short case).
.PHONY: plectoneme
plectoneme: deps
	@$(MAKE) --no-print-directory bin/sinewc
	@sh scripts/plectoneme_study.sh --out build/plectoneme

# `make tradeoff`: speed against accuracy, measured (docs/tradeoff.md): runs
# scripts/sinew-study over the cantilever, the elbow (five compile-time
# variants, 0.5 s against Verlet at 50 ns) and the snake, and rewrites the
# tables of docs/tradeoff.md and docs/img/tradeoff_*.png (~20-25 min; like
# `make bench`, never part of `make test`).  ELBOW_DURATION=0.1s for a
# shorter elbow; SCENES="cantilever snake_continuum" for a subset.
.PHONY: tradeoff
tradeoff: deps
	@$(MAKE) --no-print-directory bin/sinewc
	@sh scripts/tradeoff.sh

# `make reproduce quick` (about half an hour on two cores) or `make
# reproduce full` (the reference's settings, hours): every study of Zhang et
# al. 2019 that sinew reproduces, run by scripts/reproduce.sh, and
# docs/reproduction.md written from what the runs measured (a claim of the
# reference, sinew's figure, a verdict, the evidence when they differ).
# REPRODUCE_STUDIES="snake_continuum walker" for some of them.
.PHONY: reproduce quick full
reproduce: deps
	@$(MAKE) --no-print-directory all
	@sh scripts/reproduce.sh $(or $(filter quick full,$(MAKECMDGOALS)),quick) $(REPRODUCE_STUDIES)
quick full:
	@:

# `make install PREFIX=...`: compiler, runtime library and header, models,
# and the plot tool.
PREFIX ?= /usr/local
install: bin/sinewc build/libsinewrt.a build/libsinewrt-portable.a $(MPI_OBJ)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib $(DESTDIR)$(PREFIX)/include/sinew \
	  $(DESTDIR)$(PREFIX)/share/sinew/models
	install -m 755 bin/sinewc $(DESTDIR)$(PREFIX)/bin/sinewc
	install -m 755 scripts/sinew-plot $(DESTDIR)$(PREFIX)/bin/sinew-plot
	install -m 644 build/libsinewrt.a $(DESTDIR)$(PREFIX)/lib/libsinewrt.a
	install -m 644 build/libsinewrt-portable.a $(DESTDIR)$(PREFIX)/lib/libsinewrt-portable.a
	@if [ -n "$(MPI_OBJ)" ]; then install -m 644 $(MPI_OBJ) $(DESTDIR)$(PREFIX)/lib/sinewrt_mpi.o; fi
	install -m 644 runtime/include/*.h $(DESTDIR)$(PREFIX)/include/sinew/
	@if ls models/*.sinew >/dev/null 2>&1; then \
	  install -m 644 models/*.sinew $(DESTDIR)$(PREFIX)/share/sinew/models/; fi

clean:
	rm -rf build bin

# ---- fuzzing (docs/fuzzing.md): AFL++ on the whole front end for
# FUZZ_SECONDS (default 10 minutes); crashes and hangs are minimised into
# tests/fuzz/regressions/, which tests/lang/test_fuzz_regressions.sh replays.
FUZZ_SECONDS ?= 600
.PHONY: fuzz
fuzz: deps
	@sh scripts/fuzz.sh $(FUZZ_SECONDS)
