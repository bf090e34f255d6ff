# Virtual Hexaglide for LinuxCNC - top-level build.
#   make          build the realtime modules and the host tool build/hexaglide
#   make install  put the modules in LinuxCNC's module directory and the
#                 man pages in $(MANDIR)/man9 (root); make uninstall removes them
#   make test     all tests; ends with "N passed, N failed, N skipped"
#   make demo     the virtual machine: home, run G-code, plots in out/
#   make run      the same machine in AXIS
#   make bench    speed of kinematics and dynamics; make profile: the step by stage (callgrind)
#   make check    sanitizers and static analysis; make fuzz; make soak
#   make fmu      build/hexaglide.fmu (FMI 3.0 co-simulation) and fmusim (docs/fmu.md)
# Every entry point first installs the Debian packages it needs.

CC      ?= gcc
BUILD   ?= build
# SANITIZE=1 builds the host code into build/asan with ASan + UBSan (make check)
ifeq ($(SANITIZE),1)
BUILD   := build/asan
SANFLAGS := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
endif
# -ffp-contract=off here and in src/Makefile.modules: no fused multiply-add in
# either build, so the host (replay, sim) and the realtime module round alike
# (docs/replay.md); and the same -fno-builtin-sin/cos/sincos as the realtime
# build (rtapi_math has no sincos), so both call the same libm functions
RT_SAME_FLAGS := -ffp-contract=off -fno-builtin-sin -fno-builtin-cos -fno-builtin-sincos
# HOST_ARCH: the host code (CLI, library, tests, benchmarks) with AVX2's
# instructions where the build machine has them (/proc/cpuinfo) and the
# compiler takes -mavx2: three-operand and wider vector code, closed loops
# 1.20-1.22 times faster on this project's VM (docs/benchmarks.md). The answers are
# the same bits: -mavx2 brings no fused multiply-add (FMA is its own flag,
# never given: GCC 12's vectorizer emits vfmaddsub despite -ffp-contract=off
# under -march=native), and GCC reorders no floating-point sum without
# -ffast-math (tests/unit/test_golden holds d20d9e5's states, test_shortcuts
# each shortcut's reference, replay the realtime module's records, bit for
# bit; tests/check/test_host_arch finds no FMA instruction). `make HOST_ARCH=`
# builds code for any x86-64; the FMU and the realtime modules are always
# built that way. A change of flags rebuilds every object ($(FLAGS_STAMP)).
ifeq ($(origin HOST_ARCH),undefined)
HOST_ARCH := $(shell grep -qw avx2 /proc/cpuinfo 2>/dev/null && $(CC) -mavx2 -E -x c /dev/null >/dev/null 2>&1 && echo -mavx2)
endif
CFLAGS_PORTABLE := -std=gnu99 -O2 -g $(RT_SAME_FLAGS) -Wall -Wextra -Werror -pthread -Isrc -Isrc/generated -MMD -MP $(SANFLAGS)
CFLAGS_HOST := $(CFLAGS_PORTABLE) $(HOST_ARCH)
FLAGS_STAMP := $(BUILD)/host-cflags
$(shell mkdir -p $(BUILD) && { echo '$(CC) $(CFLAGS_HOST)' | cmp -s - $(FLAGS_STAMP) || echo '$(CC) $(CFLAGS_HOST)' >$(FLAGS_STAMP); })
LDLIBS_HOST := -lm -pthread $(SANFLAGS)

# pure math, no LinuxCNC dependency: every src/hg_*.c and src/generated/*.c
CORE_SRCS := $(sort $(wildcard src/hg_*.c) $(wildcard src/generated/*.c))
# the host-only core files that start threads (hg_batch: runs over every core);
# not in the FMU (src/fmu/fmu.mk) nor in the realtime modules (src/Makefile.modules)
THREAD_SRCS := src/hg_batch.c
CORE_OBJS := $(patsubst src/%.c,$(BUILD)/host/%.o,$(CORE_SRCS))
CLI_SRCS  := $(sort $(wildcard src/cli/*.c))
CLI_OBJS  := $(patsubst src/%.c,$(BUILD)/host/%.o,$(CLI_SRCS))
UNIT_SRCS := $(sort $(wildcard tests/unit/test_*.c))
UNIT_BINS := $(patsubst tests/unit/%.c,$(BUILD)/tests/%,$(UNIT_SRCS))
BENCH_SRCS := $(sort $(wildcard bench/bench_*.c))
BENCH_BINS := $(patsubst bench/%.c,$(BUILD)/bench/%,$(BENCH_SRCS))

# man pages: `man 9 hexaglidekins` after make install
MANDIR  ?= /usr/local/share/man
MAN9    := $(wildcard docs/man/man9/*.9)

.PHONY: all deps modules host lib install uninstall test check fuzz soak demo run bench profile clean unit-tests fmu

all: deps host modules

deps:
	@tools/install-deps.sh build

host: $(BUILD)/hexaglide $(UNIT_BINS) $(if $(SANFLAGS),,$(BUILD)/libhexaglide.so)

# the core as a shared library for Python (tools/hexaglide.py, docs/python.md)
PIC_OBJS := $(patsubst src/%.c,$(BUILD)/pic/%.o,$(CORE_SRCS))
lib: $(BUILD)/libhexaglide.so
$(BUILD)/libhexaglide.so: $(PIC_OBJS)
	$(CC) -shared -o $@ $^ $(LDLIBS_HOST)
$(BUILD)/pic/%.o: src/%.c $(wildcard src/*.h src/generated/*.h) $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_HOST) -fPIC -c -o $@ $<

# header dependencies from the compiler (-MMD): build/host/**/*.d
$(BUILD)/host/%.o: src/%.c $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_HOST) -c -o $@ $<

$(BUILD)/hexaglide: $(CLI_OBJS) $(CORE_OBJS)
	$(CC) -o $@ $^ $(LDLIBS_HOST)

$(BUILD)/tests/%: tests/unit/%.c tests/unit/hg_test.h $(CORE_OBJS) $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_HOST) -Itests/unit -o $@ $< $(CORE_OBJS) $(LDLIBS_HOST)

unit-tests: $(UNIT_BINS)

# Realtime modules, built by LinuxCNC's Makefile.modinc in build/rt.
modules: deps
	@mkdir -p $(BUILD)/rt
	$(MAKE) -s -C $(BUILD)/rt -f $(CURDIR)/src/Makefile.modules SRC=$(CURDIR)/src modules

install: modules
	$(MAKE) -s -C $(BUILD)/rt -f $(CURDIR)/src/Makefile.modules SRC=$(CURDIR)/src install
	install -d $(DESTDIR)$(MANDIR)/man9
	$(if $(MAN9),install -m 644 $(MAN9) $(DESTDIR)$(MANDIR)/man9/)
	-mandb -q $(DESTDIR)$(MANDIR) >/dev/null 2>&1

uninstall:
	@mkdir -p $(BUILD)/rt
	$(MAKE) -s -C $(BUILD)/rt -f $(CURDIR)/src/Makefile.modules SRC=$(CURDIR)/src uninstall
	rm -f $(addprefix $(DESTDIR)$(MANDIR)/man9/,$(notdir $(MAN9)))

test:
	@tools/install-deps.sh test
	@$(MAKE) -s all
	@$(MAKE) -s fmu
	@$(MAKE) -s install
	@tests/run_all.sh

# sanitizers and static analysis (also part of make test)
check:
	@tools/install-deps.sh test
	@TESTS_ONLY=check tests/run_all.sh

# bounded-time fuzzing, 1,000,000 inputs per target (tools/fuzz.sh)
fuzz:
	@tools/install-deps.sh test
	@tools/fuzz.sh $(FUZZ_RUNS)

# eight hours of simulated closed-loop motion, offline
soak: host
	@$(BUILD)/hexaglide soak --hours 8

bench: all
	@tools/install-deps.sh bench
	@$(MAKE) -s $(BENCH_BINS)
	@bench/run_bench.sh

# each bench/bench_*.c is one program; bench_mujoco* also links MuJoCo
$(BUILD)/bench/%: bench/%.c bench/bench_timing.h bench/bench_loop.h $(CORE_OBJS) $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_HOST) -o $@ $< $(CORE_OBJS) $(LDLIBS_HOST) $(if $(findstring mujoco,$*),-lmujoco)
# ... and includes the MuJoCo model generator
$(filter $(BUILD)/bench/bench_mujoco%,$(BENCH_BINS)): bench/hg_mujoco_model.c bench/hg_mujoco_model.h
# bench_baseline also links commit d20d9e5's core, built from git into
# $(BUILD)/baseline with the same compiler and flags (bench/baseline.sh);
# without that commit in the repository it runs its yardstick alone
BENCH_CODE_FLAGS := $(filter-out -I% -MMD -MP,$(CFLAGS_HOST))
$(BUILD)/bench/bench_baseline: bench/bench_baseline.c bench/engine_shim.c bench/baseline.sh bench/bench_timing.h $(CORE_OBJS)
	@mkdir -p $(dir $@)
	@if bench/baseline.sh $(BUILD)/baseline $(CC) $(BENCH_CODE_FLAGS); then \
	    $(CC) $(CFLAGS_HOST) -DHG_HAVE_BASELINE -o $@ bench/bench_baseline.c bench/engine_shim.c \
	        $(BUILD)/baseline/engine_old.o $(CORE_OBJS) $(LDLIBS_HOST); \
	else \
	    $(CC) $(CFLAGS_HOST) -o $@ bench/bench_baseline.c bench/engine_shim.c $(CORE_OBJS) $(LDLIBS_HOST); \
	fi

# where the default step's time goes: callgrind instruction counts by stage
# (bench/profile_step.sh; PROFILE_ARGS=--baseline profiles d20d9e5's step)
profile: host
	@tools/install-deps.sh bench
	@HOST_ARCH="$(HOST_ARCH)" bench/profile_step.sh $(PROFILE_ARGS)
$(BUILD)/bench/profile_step $(BUILD)/bench/profile_loop: $(BUILD)/bench/%: bench/%.c bench/bench_loop.h $(CORE_OBJS) $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_HOST) -o $@ $< $(CORE_OBJS) $(LDLIBS_HOST)

demo: all
	@tools/install-deps.sh demo
	@tools/demo.sh

run: all
	@tools/install-deps.sh run
	@tools/run.sh

clean:
	rm -rf $(BUILD)

# the FMU, fmusim and their tests (src/fmu/fmu.mk, docs/fmu.md)
include src/fmu/fmu.mk

-include $(shell find $(BUILD)/host $(BUILD)/tests -name '*.d' 2>/dev/null)
