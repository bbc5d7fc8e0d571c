# The one entry point.  `make run` runs the default scenario, `make test`
# runs every test.  Both set up what they need first (tools/deps.sh).
#
# Layout of build/: obj/ (normal objects), asan/ (sanitizer build),
# fw/ (firmware hygiene objects), tests/ (test binaries), swarmsim.

.DEFAULT_GOAL := all
BUILD := build
SHELL := /bin/bash

# Short build lines ("  CC      sim_host/core/sim.c"); `make V=1` prints the
# full commands, `make -s` neither.  $(call show,WHAT,FILE) starts a recipe line.
V ?= 0
show = $(if $(or $(filter 1,$(V)),$(findstring s,$(firstword -$(MAKEFLAGS)))),,@printf '  %-7s %s\n' '$(1)' '$(2)';)

# Dependencies: found or installed by tools/deps.sh, recorded in config.mk.
# Make rebuilds an included makefile that is missing or out of date, so
# only goals that build read it: `make clean` installs nothing.
NO_DEPS_GOALS := clean clean-lcm help
ifneq ($(filter-out $(NO_DEPS_GOALS),$(or $(MAKECMDGOALS),all)),)
include $(BUILD)/config.mk
endif
$(BUILD)/config.mk: tools/deps.sh tools/requirements.txt
	@mkdir -p $(BUILD)
	$(call show,DEPS,tools/deps.sh)tools/deps.sh > $@.tmp && mv $@.tmp $@

WARN := -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes
# Layering: firmware sees only hal/, wire/ and firmware/ (tests/firmware/hygiene.sh
# compiles each layer with only what it may include); the simulator sees everything.
FW_INC := -Ihal -Iwire -Ifirmware
SIM_INC := $(FW_INC) -Isim_host -Isim_host/include
CFLAGS_COMMON := $(WARN) -g -O2 -fno-strict-aliasing -ffp-contract=off
# Firmware and HAL helpers are C99; the simulator may use C11.
FW_CFLAGS := -std=c99 -pedantic $(FW_INC) $(CFLAGS_COMMON)
SIM_CFLAGS := -std=c11 -D_POSIX_C_SOURCE=200809L $(SIM_INC) $(CFLAGS_COMMON) $(BOX2D_CFLAGS) $(PNG_CFLAGS)
LDLIBS_SIM := $(BOX2D_LIBS) $(YAML_LIBS) $(PNG_LIBS) $(GL_LIBS) -lpthread -lm

# Controllers: firmware/<folder>/*.c (common/ and one folder per seed); the
# robot images are declared by the platforms (platforms/<p>/images.list,
# tools/make/firmware.mk).
FW_DIRS := $(patsubst %/,%,$(sort $(dir $(wildcard firmware/*/*.c))))
# The wire protocols (wire/<protocol>/*.c: telemetry framing, the host
# link's messages) are linked with them.
FW_SRC := $(sort $(wildcard $(addsuffix /*.c,$(FW_DIRS)))) $(sort $(wildcard hal/*.c)) $(sort $(wildcard wire/*/*.c))
SIM_SRC := $(filter-out sim_host/main.c sim_host/version.c,$(sort $(wildcard sim_host/*.c sim_host/core/*.c sim_host/models/*/*.c sim_host/tasks/*/*.c)))
TEST_SRC := $(sort $(wildcard tests/test_*.c))

# $(call objs,VARIANT,SOURCES)
objs = $(patsubst %.c,$(BUILD)/$(1)/%.o,$(2))

FW_OBJ := $(call objs,obj,$(FW_SRC))
SIM_OBJ := $(call objs,obj,$(SIM_SRC))
FW_OBJ_ASAN := $(call objs,asan,$(FW_SRC))
SIM_OBJ_ASAN := $(call objs,asan,$(SIM_SRC))
TESTS := $(patsubst tests/%.c,$(BUILD)/tests/%,$(TEST_SRC))
TESTS_ASAN := $(patsubst tests/%.c,$(BUILD)/tests/asan/%,$(TEST_SRC))

ASAN := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all

# Feature fragments (tools/make/*.mk) add to these before any rule uses them:
#   SIM_EXTRA_OBJ / SIM_EXTRA_OBJ_ASAN  objects linked into libswarm
#   EXTRA_TESTS                          targets `make test` also runs
EXTRA_TESTS :=
TEST_BUILD :=
SIM_EXTRA_OBJ :=
SIM_EXTRA_OBJ_ASAN :=
include $(sort $(wildcard tools/make/*.mk))

.PHONY: all run test unit-tests asan-tests cli-tests firmware-hygiene bench clean deps help

help:
	@echo "make run        build what is needed and run the default scenario (RUN_SCENARIO=, RUN_ARGS=)"
	@echo "make test       every test group, each with its time"
	@echo "make new-controller NAME=foo / new-task NAME=bar   copy the tutorials' example under your name, build it, run it"
	@echo "make docs       the documentation site, into build/site/ (make docs-serve: at http://127.0.0.1:8000/)"
	@echo "make deps       install what the build and the tools need (.venv, swarmtools)"
	@echo "make V=1 ...    the full compiler commands instead of the short CC lines"
	@echo "make bench      simulator throughput (BENCH_ARGS=)"
	@echo "make video      film seed 000's base run to out/video/foraging_base.mp4 (VIDEO_ARGS=)"
	@echo "make study-drtm seed 000's study (STUDY_ARGS=--quick for a smoke run)"
	@echo "make study-faults seed 000 under faults; make study-repatt seed 002's study (STUDY_ARGS=--quick)"
	@echo "make study-gains seed 002's gains study, reduced (Figs 2a/2b; STUDY_ARGS=--quick, --estimate 120: the full sweep's cost)"
	@echo "make study-eaipp seed 003 (EAIPP, Figs 10-17; STUDY_ARGS=--quick, --figures maze,loss, --picture)"
	@echo "make evolve     evolve a controller's params (EVOLVE=studies/nnea_evolve.yaml, EVOLVE_ARGS=--out, --jobs, --backend slurm)"
	@echo "make firmware-check / firmware / flash   the e-puck gates, .hex files, flashing"
	@echo "make pil-avr-compare  every image on the emulated ATmega2560 beside its host build, 3,000 steps, with cycles and stack (make readme-pil-cpu: into docs/hardware/footprint.md; make pil-avr-bench: PIL robots per core)"
	@echo "make monitor / spy   watch telemetry (LCM_URL=)"
	@echo "make live       watch a swarm in the browser (LOG=file.lcmlog to replay one, LCM_URL=)"
	@echo "make clean      remove what the build made (installs nothing)"

all: $(BUILD)/swarmsim

deps: $(BUILD)/config.mk

$(BUILD)/obj/firmware/%.o $(BUILD)/obj/hal/%.o $(BUILD)/obj/wire/%.o: | $(BUILD)/config.mk
$(BUILD)/obj/firmware/%.o: firmware/%.c
	@mkdir -p $(@D)
	$(call show,CC,$<)$(CC) $(FW_CFLAGS) -MMD -MP -c $< -o $@
$(BUILD)/obj/hal/%.o: hal/%.c
	@mkdir -p $(@D)
	$(call show,CC,$<)$(CC) $(FW_CFLAGS) -MMD -MP -c $< -o $@
$(BUILD)/obj/wire/%.o: wire/%.c
	@mkdir -p $(@D)
	$(call show,CC,$<)$(CC) $(FW_CFLAGS) -MMD -MP -c $< -o $@
$(BUILD)/obj/sim_host/%.o: sim_host/%.c
	@mkdir -p $(@D)
	$(call show,CC,$<)$(CC) $(SIM_CFLAGS) -MMD -MP -c $< -o $@
$(BUILD)/asan/firmware/%.o: firmware/%.c
	@mkdir -p $(@D)
	$(call show,CC-ASAN,$<)$(CC) $(FW_CFLAGS) $(ASAN) -MMD -MP -c $< -o $@
$(BUILD)/asan/hal/%.o: hal/%.c
	@mkdir -p $(@D)
	$(call show,CC-ASAN,$<)$(CC) $(FW_CFLAGS) $(ASAN) -MMD -MP -c $< -o $@
$(BUILD)/asan/wire/%.o: wire/%.c
	@mkdir -p $(@D)
	$(call show,CC-ASAN,$<)$(CC) $(FW_CFLAGS) $(ASAN) -MMD -MP -c $< -o $@
$(BUILD)/asan/sim_host/%.o: sim_host/%.c
	@mkdir -p $(@D)
	$(call show,CC-ASAN,$<)$(CC) $(SIM_CFLAGS) $(ASAN) -MMD -MP -c $< -o $@

$(BUILD)/libswarm.a: $(FW_OBJ) $(SIM_OBJ) $(SIM_EXTRA_OBJ)
	@rm -f $@
	$(call show,AR,$@)$(AR) rcs $@ $^
$(BUILD)/libswarm-asan.a: $(FW_OBJ_ASAN) $(SIM_OBJ_ASAN) $(SIM_EXTRA_OBJ_ASAN)
	@rm -f $@
	$(call show,AR,$@)$(AR) rcs $@ $^

# Linked under another name, then renamed: a run of the old binary (a test
# group beside this build) keeps it whole, and two test groups that relink
# it at once (the checkout changed under them) each rename their own.
$(BUILD)/swarmsim: $(BUILD)/obj/sim_host/main.o $(BUILD)/libswarm.a
	$(call show,LD,$@)$(CC) -o $@.tmp.$$$$ $^ $(LDLIBS_SIM) && mv $@.tmp.$$$$ $@

# Test binaries record the headers they read (-MMD): a changed header
# rebuilds them.
$(BUILD)/tests/%: tests/%.c $(BUILD)/libswarm.a
	@mkdir -p $(@D)
	$(call show,CC,$@)$(CC) $(SIM_CFLAGS) $(CMOCKA_CFLAGS) -MMD -MP -MF $@.d -o $@ $< $(BUILD)/libswarm.a $(CMOCKA_LIBS) $(LDLIBS_SIM)
$(BUILD)/tests/asan/%: tests/%.c $(BUILD)/libswarm-asan.a
	@mkdir -p $(@D)
	$(call show,CC-ASAN,$@)$(CC) $(SIM_CFLAGS) $(ASAN) $(CMOCKA_CFLAGS) -MMD -MP -MF $@.d -o $@ $< $(BUILD)/libswarm-asan.a $(CMOCKA_LIBS) $(LDLIBS_SIM)

# ---------------------------------------------------------------- run
RUN_SCENARIO ?= sim_host/scenarios/foraging_base.yaml
# make run's own folder: each `make run` replaces it whole (--replace removes
# only a folder swarmsim made), so two scenarios' files never mix in it.
RUN_OUT ?= out/run
run: deps $(BUILD)/swarmsim
	$(BUILD)/swarmsim $(RUN_SCENARIO) --out $(RUN_OUT) $(if $(findstring --resume,$(RUN_ARGS)),,--replace) --frames 1000 $(RUN_ARGS)

# ---------------------------------------------------------------- tests
# Each CMocka binary prints its own summary; CMOCKA_MESSAGE_OUTPUT stays on
# the standard output so CI reads it.
unit-tests: $(TESTS)
	@set -e; for t in $(TESTS); do echo "== $$t"; (cd tests && ../$$t); done

asan-tests: $(TESTS_ASAN)
	@set -e; for t in $(TESTS_ASAN); do echo "== $$t (ASan/UBSan)"; \
	  (cd tests && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp UBSAN_OPTIONS=print_stacktrace=1 ../$$t); done

cli-tests: $(BUILD)/swarmsim
	@set -e; for t in $(sort $(wildcard tests/cli/*.sh)); do echo "== $$t"; bash $$t $(BUILD)/swarmsim; done

firmware-hygiene: $(BUILD)/config.mk lcm-types firmware-images
	@LCM_CFLAGS='$(LCM_CFLAGS)' LCM_C_DIR='$(BUILD)/lcm_c' FW_GEN='$(FW_GEN)' bash tests/firmware/hygiene.sh

# Every group (a make target), TEST_JOBS at a time (default: the CPUs; 1:
# one after the other), after one build of what they share (TEST_BUILD;
# fragments add theirs), each group's output together with its time
# (tools/make/timed.sh), the longest first by the last run's times.
TEST_GROUPS = unit-tests asan-tests cli-tests firmware-hygiene $(EXTRA_TESTS)
TEST_JOBS ?= $(shell nproc 2>/dev/null || echo 1)
TEST_BUILD += all $(TESTS) $(TESTS_ASAN)
.PHONY: test-build
test-build: deps $(TEST_BUILD)
test: deps
	@bash tools/make/timed.sh -- $(MAKE) --no-print-directory $(if $(filter -j%,$(MAKEFLAGS)),,-j$(TEST_JOBS)) -- test-build
	@bash tools/make/timed.sh -j $(TEST_JOBS) -t $(BUILD)/test_times.txt -- $(MAKE) --no-print-directory -- $(TEST_GROUPS)
	@echo "make test: all test groups passed"

# ---------------------------------------------------------------- bench
bench: $(BUILD)/swarmsim
	bash tools/bench/bench.sh $(BUILD)/swarmsim

clean:
	rm -rf $(BUILD)/obj $(BUILD)/asan $(BUILD)/tsan $(BUILD)/fw $(BUILD)/tests $(BUILD)/gen $(BUILD)/*.a $(BUILD)/swarmsim

-include $(shell find $(BUILD)/obj $(BUILD)/asan $(BUILD)/tests -name '*.d' 2>/dev/null)
