# prefilter - Makefile (the primary build). Header-only: nothing to build for users.
# Every job below starts with tests/deps.sh JOB: it installs the Debian packages that job needs
# (as root or with password-less sudo) or stops at once with the apt-get line to run
# (PF_NO_INSTALL=1: never install). The package list and the reason for each are in that script.
#   make test         every test in every build (C99 float/double, C++11, clang sanitizers,
#                     -ffast-math edge tests); ends with "N passed, N failed"
#   make bench        the main job: tables, CSV under bench/out/, charts (gnuplot), on every core
#                     (PFB_THREADS=N: N threads; timings always run alone on one core)
#   make bench PROFILE=1   also branch counts and per-method callgrind profiles (bench/out/profile/)
#   make bench MAP=f  the ground truth on your own height or normal map (docs/maps.md)
#   make bench-determinism  the quick bench with 1 thread and with every core: CSVs must match
#   make portability  tcc, nvcc, GLSL -> SPIR-V -> HLSL/MSL, Cortex-M4F, amalgamation, matrix, ARM
#   make install      headers + pkg-config (PREFIX, DESTDIR); make amalgamate: prefilter.h
#   make clean

CC    ?= gcc
CXX   ?= g++
CLANG ?= clang
BUILD ?= build

WARN_C   := -std=c99 -pedantic -Wall -Wextra -Werror -Wdouble-promotion
WARN_CXX := -std=c++11 -Wall -Wextra -Werror
INC      := -Iinclude -Itests -Itests/reference

HEADERS  := $(wildcard include/*.h) $(wildcard tests/*.h) $(wildcard tests/reference/*.h)
TEST_SRC := $(wildcard tests/test_*.c)
TESTS    := $(TEST_SRC:tests/%.c=%)

# Test builds: name, compiler, flags. The fastmath builds run only the edge_ tests.
CONFIGS := c99-float c99-double cxx11-float clang-san-float clang-san-double fastmath-float fastmath-double
TCC_c99-float        = $(CC)
TFLAGS_c99-float     = $(WARN_C) -O2
TCC_c99-double       = $(CC)
TFLAGS_c99-double    = $(WARN_C) -O2 -DPF_DOUBLE
TCC_cxx11-float      = $(CXX) -x c++
TFLAGS_cxx11-float   = $(WARN_CXX) -O2
TCC_clang-san-float  = $(CLANG)
TFLAGS_clang-san-float = $(WARN_C) -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
TCC_clang-san-double  = $(CLANG)
TFLAGS_clang-san-double = $(TFLAGS_clang-san-float) -DPF_DOUBLE
TCC_fastmath-float   = $(CC)
TFLAGS_fastmath-float  = $(WARN_C) -O2 -ffast-math
TCC_fastmath-double  = $(CC)
TFLAGS_fastmath-double = $(WARN_C) -O2 -ffast-math -DPF_DOUBLE

define test_rule
$(BUILD)/$(1)/%: tests/%.c $(HEADERS)
	@mkdir -p $$(@D)
	$$(TCC_$(1)) $$(TFLAGS_$(1)) -DPF_TEST_CONFIG='"$(1)"' $(INC) $$< -o $$@ -lm
endef
$(foreach c,$(CONFIGS),$(eval $(call test_rule,$(c))))

TEST_BINS := $(foreach c,$(CONFIGS),$(addprefix $(BUILD)/$(c)/,$(TESTS)))

# Tests that link a system library: tests/maps/test_*.c (the map loaders of make bench MAP=...,
# tests/reference/pf_maps.h; libpng, Debian libpng-dev), built and run in every config above with -lpng.
# They live apart from tests/test_*.c because the portability cells compile those with -lm
# only, and with cross compilers that have no libpng.
LIB_TEST_SRC := $(wildcard tests/maps/test_*.c)
LIB_TESTS    := $(LIB_TEST_SRC:tests/maps/%.c=%)
define lib_test_rule
$(BUILD)/$(1)/%: tests/maps/%.c $(HEADERS)
	@mkdir -p $$(@D)
	$$(TCC_$(1)) $$(TFLAGS_$(1)) -DPF_TEST_CONFIG='"$(1)"' $(INC) $$< -o $$@ -lpng -lm
endef
$(foreach c,$(CONFIGS),$(eval $(call lib_test_rule,$(c))))
TEST_BINS += $(foreach c,$(CONFIGS),$(addprefix $(BUILD)/$(c)/,$(LIB_TESTS)))

# C++ tests that cross-check against GLM (tests/test_*.cpp; Debian libglm-dev): C++11, float
# and double. GLM is a test-only dependency, never needed by the headers.
GLM_TEST_SRC := $(wildcard tests/test_*.cpp)
GLM_TESTS    := $(GLM_TEST_SRC:tests/%.cpp=%)
GLM_CONFIGS  := glm-float glm-double
$(BUILD)/glm-float/%: tests/%.cpp $(HEADERS)
	@mkdir -p $(@D)
	$(CXX) $(WARN_CXX) -O2 -DPF_TEST_CONFIG='"glm-float"' $(INC) $< -o $@ -lm
$(BUILD)/glm-double/%: tests/%.cpp $(HEADERS)
	@mkdir -p $(@D)
	$(CXX) $(WARN_CXX) -O2 -DPF_DOUBLE -DPF_TEST_CONFIG='"glm-double"' $(INC) $< -o $@ -lm
TEST_BINS += $(foreach c,$(GLM_CONFIGS),$(addprefix $(BUILD)/$(c)/,$(GLM_TESTS)))

.PHONY: test test-build bench bench-run bench-map portability docs clean deps
test-build: $(TEST_BINS)

# The dependency step first, alone, then the parallel build (a recursive make, so that -j never
# starts a compile before the packages are there).
test:
	@sh tests/deps.sh test
	@$(MAKE) --no-print-directory test-build
	@sh tests/run.sh $(BUILD) "$(CONFIGS)" "$(TESTS) $(LIB_TESTS)" "$(GLM_CONFIGS)" "$(GLM_TESTS)"

# ---------------------------------------------------------------- bench (the main job)
#   make bench                  float + double builds of bench/bench_*.c, run by bench/run.sh:
#                               tables on stdout; bench/out/<module>.csv, <module>_<family>.svg
#                               (gnuplot), summary.md
#   make bench CALLGRIND=0/1    instructions per evaluation (valgrind --tool=callgrind) of every
#                               method, float and double (default: on in a full run, off under
#                               BENCH_QUICK=1); one callgrind run per binary, all at once
#   make bench PROFILE=1        the opt-in profile mode: callgrind's branch simulation and the
#                               per-method profiles (callgrind_annotate), bench/out/profile/, which
#                               nothing in docs/ or the report reads
#   make bench PFB_THREADS=N    threads (and processes) per stage; default every core; 1 = serial
#   make bench BENCH_BUDGET_MS=B   measured ms per method and input order of the per-module timings
#                               (default bench/pf_bench.h's PFB_BUDGET_MS; sh bench/times.sh spread
#                               shows how repeatable the medians are at a budget)
#   Every stage runs on every core except the timing loops, which run alone on one core after
#   the untimed stages (bench/run.sh's header has the order); builds run in parallel too.
#   make bench BENCH_OPT="-O3 -march=native"   other optimisation flags (recorded in summary.md)
# -falign-functions=64: every timing loop starts on a cache line, so two methods compiled to
# identical code time alike (without it, placement alone moved a 1 ns loop by 10-15%).
BENCH_SRC   := $(wildcard bench/bench_*.c)
BENCH_OPT   ?= -O2 -falign-functions=64
BENCH_FLAGS := $(WARN_C) $(BENCH_OPT) -Ibench -Iinclude -Itests/reference
BENCH_BINS  := $(BENCH_SRC:bench/%.c=$(BUILD)/bench/%-float) $(BENCH_SRC:bench/%.c=$(BUILD)/bench/%-double)
BENCH_STAMP := $(BUILD)/bench/flags.txt

# rebuilt only when the compiler or the flags change, so BENCH_OPT=... takes effect at once
$(BENCH_STAMP): pf-bench-always
	@mkdir -p $(@D)
	@echo '$(CC) $(BENCH_FLAGS)' | cmp -s - $@ || echo '$(CC) $(BENCH_FLAGS)' > $@
pf-bench-always:

# With gcc, each build also writes which loops it vectorized (BIN.vec, -fopt-info-vec-optimized:
# no effect on the code), which bench/run.sh's summary reads instead of compiling everything again
# (a .vec exists only when the last build of its binary wrote it).
# With valgrind's client-request header, a bench's setup runs uninstrumented under callgrind
# (bench/pf_bench.h, PFB_HAVE_CALLGRIND_H: the counts are the same, the callgrind stage faster).
BENCH_VEC = $(if $(BENCH_VEC_OK),-fopt-info-vec-optimized=$@.vec) $(BENCH_CG_H)
BENCH_VEC_OK := $(shell $(CC) -fopt-info-vec-optimized=/dev/null -x c -c /dev/null -o /dev/null 2>/dev/null && echo 1)
BENCH_CG_H := $(shell printf '\043include <valgrind/callgrind.h>\n' | $(CC) -E -x c - > /dev/null 2>&1 && echo -DPFB_HAVE_CALLGRIND_H)
$(BUILD)/bench/%-float: bench/%.c $(HEADERS) $(wildcard bench/*.h) $(BENCH_STAMP)
	@mkdir -p $(@D) && rm -f $@.vec
	$(CC) $(BENCH_FLAGS) $(BENCH_VEC) -pthread $< -o $@ -lm
$(BUILD)/bench/%-double: bench/%.c $(HEADERS) $(wildcard bench/*.h) $(BENCH_STAMP)
	@mkdir -p $(@D) && rm -f $@.vec
	$(CC) $(BENCH_FLAGS) $(BENCH_VEC) -pthread -DPF_DOUBLE $< -o $@ -lm

# The report's own programs (not bench_*.c: they are not per-module method tables), each built
# once in float (the library's default) and run once by bench/run.sh:
#   bench/microsurface.c  ground truth: library answers against brute force on synthetic
#                         microsurfaces, error tables and charts, cost against footprint size
#   bench/pictures.c      brute force against the filtered formulas, side by side (PNG drawn by
#                         gnuplot, bench/pictures.gp: titled panels, numbered colour bars)
#   bench/specaa.c        roughness mips baked from normal maps against the engines' formulas
#                         and the exact footprint NDF; a supersampled sphere with the geometry kernel
# They include tests/reference/pf_microsurface.h, the synthetic microsurfaces and brute-force reference.
REPORT_PROGS := microsurface pictures specaa
REPORT_BINS  := $(REPORT_PROGS:%=$(BUILD)/bench/%)
$(BUILD)/bench/%: bench/%.c $(HEADERS) $(wildcard bench/*.h) $(wildcard bench/*.gp) $(BENCH_STAMP)
	@mkdir -p $(@D)
	$(CC) $(BENCH_FLAGS) -pthread $< -o $@ -lpng -lm

# The frame on a Vulkan driver (bench/frame/: frame.c the host, frame.frag/.vert the shaders, run.sh
# the step): pictures.c's scenes rendered by the GLSL path from GPU textures, against the brute
# force and the CPU float path; lavapipe unless PF_VK_DEVICE names a device. make frame: that step
# alone (BENCH_QUICK=1: small frames); make bench runs it too.
FRAME_BIN := $(BUILD)/bench/frame
$(FRAME_BIN): bench/frame/frame.c bench/frame/frame_curved.h bench/frame/curved_shade.h tests/gpu/vk_common.h $(HEADERS) $(wildcard bench/*.h) $(BENCH_STAMP)
	@mkdir -p $(@D)
	$(CC) $(BENCH_FLAGS) -pthread -Itests -Itests/reference -Itests/gpu $< -o $@ -lvulkan -lm
bench-run: $(FRAME_BIN)
.PHONY: frame
frame:
	@sh tests/deps.sh bench
	@$(MAKE) --no-print-directory $(FRAME_BIN)
	@BENCH_QUICK='$(BENCH_QUICK)' sh bench/frame/run.sh $(BUILD)/bench bench/out

# The ground truth on the user's own map (bench/map.sh, docs/maps.md): with MAP set, make bench
# runs bench/microsurface.c and bench/pictures.c on that map instead of the full run, and writes
# $(MAP_OUT)/report.md (default bench/out/map): slope statistics, errors by footprint and view,
# pictures, the cheapest method per error target on that surface. A few minutes for 512 x 512.
#   make bench MAP=rock.png                           8/16-bit grey PNG height map
#   make bench MAP=rock_n.png MAP_KIND=normal-gl      RGB PNG normal map (normal-dx: DirectX green)
#   make bench MAP=h.raw MAP_RAW_SIZE=1024x512        raw little-endian float32 heights
#   MAP_SCALE=s (height of full white in texels; raw: factor) or MAP_RMS_SLOPE=r (default 0.3 for
#   height maps); MAP_BORDER=clamped for maps that do not tile (mirrored to 2n x 2n)
MAP_OUT ?= bench/out/map
# the bench's binaries are built on every core (unless make already runs with -j)
BENCH_JOBS ?= $(or $(PFB_THREADS),$(shell getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1))
bench:
	@sh tests/deps.sh bench
	@$(MAKE) --no-print-directory $(if $(findstring jobserver,$(MAKEFLAGS)),,-j$(BENCH_JOBS)) \
	    $(if $(MAP),$(REPORT_BINS),bench-build)
	@$(MAKE) --no-print-directory $(if $(MAP),bench-map,bench-run)
# only the binaries (bench/times.sh builds first, so that it times the runs alone): the
# stability sweep's four builds first (the longest: make -j starts prerequisites in order), the
# frame's host too (else built alone by bench-run, after the parallel builds)
.PHONY: bench-build
bench-build: bench-stability-build $(BENCH_BINS) $(REPORT_BINS) $(FRAME_BIN)
# the stability sweep's four -O2 builds (bench/stability.sh --build-only; each skipped when up to
# date), beside the other builds, so that the bench's stability stage only runs the sweep
.PHONY: bench-stability-build
bench-stability-build:
	@CC='$(CC)' sh bench/stability.sh --build-only $(BUILD)
bench-map: $(REPORT_BINS)
	@CC='$(CC)' BENCH_FLAGS='$(BENCH_FLAGS)' BENCH_QUICK='$(BENCH_QUICK)' MAP='$(MAP)' MAP_KIND='$(MAP_KIND)' \
	    MAP_SCALE='$(MAP_SCALE)' MAP_RMS_SLOPE='$(MAP_RMS_SLOPE)' MAP_BORDER='$(MAP_BORDER)' \
	    MAP_RAW_SIZE='$(MAP_RAW_SIZE)' MAP_OUT='$(MAP_OUT)' sh bench/map.sh $(BUILD)/bench
bench-run: $(BENCH_BINS) $(REPORT_BINS)
	@CC='$(CC)' BENCH_FLAGS='$(BENCH_FLAGS)' CALLGRIND='$(CALLGRIND)' PROFILE='$(PROFILE)' BENCH_QUICK='$(BENCH_QUICK)' \
	    BENCH_BUDGET_MS='$(BENCH_BUDGET_MS)' sh bench/run.sh $(BUILD)/bench

# The determinism check (bench/determinism.sh): the quick bench with PFB_THREADS=1 and with every
# core (instruction counts included), then every CSV of the two runs compared except the timing
# columns; fails on any difference. About twice a quick run.
# (PF_GPU_CACHE empty: both runs count every shader, none reads the other's counts)
.PHONY: bench-determinism
bench-determinism:
	@sh tests/deps.sh bench
	@PF_GPU_CACHE= sh bench/determinism.sh

# The stability table (docs/stability.md): every public evaluator swept with seeded inputs from
# its documented domain in float, double and both under -ffast-math (bench/stability.sh; make
# bench runs it with 10^6 inputs per evaluator and build, STABILITY_N=... for more).
# The libFuzzer harnesses, one per module (tests/fuzz/run.sh; clang with libclang-rt-dev):
#   make fuzz FUZZ_SECONDS=5     each harness, float and double, 5 s (CI); longer by hand
.PHONY: fuzz stability
fuzz:
	@sh tests/deps.sh fuzz
	@FUZZ_SECONDS='$(or $(FUZZ_SECONDS),5)' CLANG='$(CLANG)' sh tests/fuzz/run.sh $(BUILD)
stability:
	@CC='$(CC)' BENCH_QUICK='$(BENCH_QUICK)' sh bench/stability.sh $(BUILD)

# docs/<module>.md regions marked <!-- BEGIN GENERATED: module --> ... <!-- END GENERATED: module -->
# are replaced by that module's section of bench/out/summary.md (run make bench first), so the
# tables in docs are the bench's, never typed by hand.
DOC_TESTS := core smith beckmann moments map map_downsample toksvig shadow gaussgrid height vmf vmf_fit vmf_scale horizon masks encode specaa
docs: $(foreach t,$(DOC_TESTS),$(BUILD)/c99-float/test_$(t) $(BUILD)/c99-double/test_$(t))
	@BUILD=$(BUILD) sh bench/update_docs.sh bench/out/summary.md docs

.PHONY: pf-bench-always

# ---------------------------------------------------------------- portability
#   make portability        every check of tests/portability/run.sh: tcc, nvcc, GLSL -> SPIR-V ->
#                           HLSL/MSL, Cortex-M4F, the amalgamation, the compiler/flag matrix, the
#                           float suite on ARM under qemu-arm, the consumer projects (docs/porting.md)
#   make portability PF_PORT_ONLY="m4f-float amalgam"   only the named checks (prefix match)
portability:
	@sh tests/deps.sh portability
	@PF_PORT_ONLY='$(PF_PORT_ONLY)' sh tests/portability/run.sh $(BUILD)

# Only the compiler/flag matrix, the ARM run, the consumer projects (subsets of portability).
.PHONY: matrix arm consumers amalgamate install uninstall
matrix:
	@sh tests/deps.sh portability
	@PF_PORT_ONLY=mx- sh tests/portability/run.sh $(BUILD)
arm:
	@sh tests/deps.sh portability
	@PF_PORT_ONLY=arm- sh tests/portability/run.sh $(BUILD)
consumers:
	@sh tests/deps.sh portability
	@PF_PORT_ONLY=consumer- sh tests/portability/run.sh $(BUILD)

# docs/porting.md's generated tables: the float-versus-double accuracy table from the C99 test
# builds' notes (tests/portability/accuracy.sh; with the ARM column when make portability ran),
# and the Cortex-M4F size table (run make portability with PF_PORT_UPDATE_DOCS=1 for that one).
.PHONY: porting-docs
porting-docs: $(addprefix $(BUILD)/c99-float/,$(TESTS)) $(addprefix $(BUILD)/c99-double/,$(TESTS))
	@sh tests/portability/accuracy.sh $(BUILD) --update

# ---------------------------------------------------------------- amalgamation, install
# prefilter.h (committed) = every include/pf_*.h in dependency order; regenerate after editing.
amalgamate:
	@sh tests/portability/amalgamate.sh prefilter.h && echo "prefilter.h regenerated"

# make install PREFIX=/usr/local [DESTDIR=...]: the headers (include/pf_*.h and prefilter.h) and
# the pkg-config file (Cflags only). Nothing is compiled. CMake users: cmake --install instead.
PREFIX     ?= /usr/local
INCLUDEDIR ?= $(PREFIX)/include
PCDIR      ?= $(PREFIX)/share/pkgconfig
PF_VERSION := $(shell awk '/^project.prefilter VERSION/ { print $$3 }' CMakeLists.txt)
PF_INSTALL_HEADERS := $(notdir $(wildcard include/pf_*.h)) prefilter.h
install:
	install -d '$(DESTDIR)$(INCLUDEDIR)' '$(DESTDIR)$(PCDIR)'
	install -m 644 $(wildcard include/pf_*.h) prefilter.h '$(DESTDIR)$(INCLUDEDIR)'
	sed -e 's|@PF_PREFIX@|$(PREFIX)|' -e 's|@PF_INCLUDEDIR@|$(INCLUDEDIR)|' \
	    -e 's|@PF_VERSION@|$(PF_VERSION)|' prefilter.pc.in > '$(DESTDIR)$(PCDIR)/prefilter.pc'
	chmod 644 '$(DESTDIR)$(PCDIR)/prefilter.pc'
uninstall:
	rm -f $(addprefix '$(DESTDIR)$(INCLUDEDIR)'/,$(PF_INSTALL_HEADERS)) '$(DESTDIR)$(PCDIR)/prefilter.pc'

# Only the dependency step: make deps JOBS="test bench" (default: every job).
deps:
	@sh tests/deps.sh $(or $(JOBS),test bench portability fuzz)

clean:
	rm -rf $(BUILD)
