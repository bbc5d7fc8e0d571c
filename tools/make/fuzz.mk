# fuzz.mk - the libFuzzer harnesses of tests/fuzz/ (one .c a target, its seed
# corpus in tests/fuzz/corpus/<target>/), built with clang
# -fsanitize=fuzzer,address,undefined against the product's own sources,
# which clang compiles again with coverage into build/fuzz/ (gcc's objects
# cannot carry libFuzzer's instrumentation).
#
#   make fuzz-tests   part of make test: each target runs every input of its
#                     corpus, then fuzzes for FUZZ_TEST_SECONDS (3); then the
#                     known defects' reproducers are run (tests/fuzz/known/)
#   make fuzz         each target for FUZZ_SECONDS (300) and a line of
#                     executions and coverage per target; FUZZ_TARGETS to
#                     choose, -j2 to run two at once.  What it finds stays in
#                     build/fuzz/run/<target>/ (new inputs, crash-* files).
#                     Then the Python property tests (tools/tests/fuzz/) with
#                     FUZZ_PY_EXAMPLES (10,000) random examples a property.
#
# A defect that is known and being fixed elsewhere is listed in
# tests/fuzz/known_defects.supp (UBSan suppressions, so that fuzzing goes on
# past it) with its reproducer in tests/fuzz/known/<target>/; fuzz-tests
# checks that the harness still finds it, and says when it no longer does.
FUZZ_DIR := $(BUILD)/fuzz
FUZZ_SECONDS ?= 300
FUZZ_TEST_SECONDS ?= 3
FUZZ_PY_EXAMPLES ?= 10000
# epuck_ir.c is built once per IR backend of platforms/epuck1/hal, as test_hal_epuck is.
FUZZ_ALL := $(filter-out epuck_ir,$(patsubst tests/fuzz/%.c,%,$(sort $(wildcard tests/fuzz/*.c)))) \
  epuck_ir_randb epuck_ir_libircom
FUZZ_TARGETS ?= $(FUZZ_ALL)
FUZZ_BINS := $(addprefix $(FUZZ_DIR)/bin/,$(FUZZ_ALL))

# UBSan stays recoverable in the build (so that a known defect can be
# suppressed at run time); tests/fuzz/fuzz.h makes every report fatal.
FUZZ_SAN := -fsanitize=address,undefined -fno-omit-frame-pointer -g -O1
FUZZ_CFLAGS = $(FUZZ_SAN) -fsanitize=fuzzer-no-link -I$(BUILD)/gen

FUZZ_OBJ = $(patsubst %.c,$(FUZZ_DIR)/obj/%.o,$(FW_SRC) $(SIM_SRC))
# lcm-gen's C of each type (lcm.mk generates it: build/lcm_c/swarmlcm_<type>.c).
FUZZ_LCM_OBJ := $(patsubst lcm_types/%.lcm,$(FUZZ_DIR)/obj/lcm/swarmlcm_%.o,$(sort $(wildcard lcm_types/*.lcm)))

# The generated headers (LCM types, the registry's lists) come first.
FUZZ_GEN := $(BUILD)/config.mk lcm-types registry-list
$(FUZZ_DIR)/obj/firmware/%.o: firmware/%.c | $(FUZZ_GEN)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FW_CFLAGS) $(FUZZ_CFLAGS) -MMD -MP -c $< -o $@
$(FUZZ_DIR)/obj/hal/%.o: hal/%.c | $(FUZZ_GEN)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FW_CFLAGS) $(FUZZ_CFLAGS) -MMD -MP -c $< -o $@
$(FUZZ_DIR)/obj/wire/%.o: wire/%.c | $(FUZZ_GEN)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FW_CFLAGS) $(FUZZ_CFLAGS) -MMD -MP -c $< -o $@
$(FUZZ_DIR)/obj/sim_host/%.o: sim_host/%.c | $(FUZZ_GEN)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(SIM_CFLAGS) $(FUZZ_CFLAGS) -MMD -MP -c $< -o $@
$(FUZZ_DIR)/obj/lcm/%.o: $(BUILD)/lcm_c/%.c | $(FUZZ_GEN)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(LCM_GEN_CFLAGS) $(FUZZ_CFLAGS) -c $< -o $@

$(FUZZ_DIR)/libswarm.a: $(FUZZ_OBJ) $(FUZZ_LCM_OBJ)
	@rm -f $@
	$(AR) rcs $@ $^

# A harness sees the simulator's include path and tests/ (fake_hal.h).
FUZZ_LINK = $(FUZZ_CC) $(SIM_CFLAGS) $(FUZZ_SAN) -fsanitize=fuzzer -Itests -MMD -MP -MF $@.d
$(FUZZ_DIR)/bin/%: tests/fuzz/%.c $(FUZZ_DIR)/libswarm.a
	@mkdir -p $(@D)
	$(FUZZ_LINK) -o $@ $< $(FUZZ_DIR)/libswarm.a $(LDLIBS_SIM)

# platforms/epuck1/hal over the e-puck library's stubs (platforms/epuck1/tests/stubs/), C99 as
# on the robot, with one IR backend each.
FUZZ_EPUCK_SRC := tests/fuzz/epuck_ir.c platforms/epuck1/hal/hal_epuck.c platforms/epuck1/hal/host_link.c hal/blob_detect.c \
  hal/hal_common.c hal/units.c hal/tone_detect.c hal/tone_tables.c \
  wire/telemetry/telemetry_rx.c wire/telemetry/telemetry_host.c wire/telemetry/telemetry_frame.c \
  platforms/epuck1/tests/stubs/epuck_lib_stubs.c
FUZZ_EPUCK_RANDB := platforms/epuck1/hal/ircom_randb.c platforms/epuck1/tests/stubs/adscan_stubs.c platforms/epuck1/tests/stubs/randb_stubs.c
FUZZ_EPUCK_IRCOM := platforms/epuck1/hal/ircom_libircom.c platforms/epuck1/tests/stubs/ircom_stubs.c
FUZZ_EPUCK_H := tests/fuzz/fuzz.h $(wildcard hal/*.h platforms/epuck1/hal/*.h platforms/epuck1/tests/stubs/*.h)
FUZZ_EPUCK = $(FUZZ_CC) $(FW_CFLAGS) $(FUZZ_SAN) -fsanitize=fuzzer -Iplatforms/epuck1/hal -Iplatforms/epuck1/tests/stubs -o $@
$(FUZZ_DIR)/bin/epuck_ir_randb: $(FUZZ_EPUCK_SRC) $(FUZZ_EPUCK_RANDB) $(FUZZ_EPUCK_H) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(FUZZ_EPUCK) $(FUZZ_EPUCK_SRC) $(FUZZ_EPUCK_RANDB) -lm
$(FUZZ_DIR)/bin/epuck_ir_libircom: $(FUZZ_EPUCK_SRC) $(FUZZ_EPUCK_IRCOM) $(FUZZ_EPUCK_H) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(FUZZ_EPUCK) -DFUZZ_LIBIRCOM $(FUZZ_EPUCK_SRC) $(FUZZ_EPUCK_IRCOM) -lm

FUZZ_RUN = FUZZ_DIR=$(FUZZ_DIR) bash tests/fuzz/run.sh

.PHONY: fuzz fuzz-tests fuzz-build fuzz-python $(addprefix fuzz-run-,$(FUZZ_ALL))
fuzz-build: $(FUZZ_BINS)

fuzz-tests: fuzz-build
	@set -e; for t in $(FUZZ_ALL); do $(FUZZ_RUN) $$t $(FUZZ_TEST_SECONDS); done
	@$(FUZZ_RUN) --known $(FUZZ_ALL)

fuzz: $(addprefix fuzz-run-,$(FUZZ_TARGETS)) fuzz-python
$(addprefix fuzz-run-,$(FUZZ_ALL)): fuzz-run-%: $(FUZZ_DIR)/bin/%
	@$(FUZZ_RUN) $* $(FUZZ_SECONDS)

# The property tests run in make test too (python-tests, 300 derandomized
# examples a property); here at random and at length.
fuzz-python: deps $(BUILD)/telemetry/libtelemetry_frame.so   # TELEMETRY_FRAME_SO, lcm.mk
	@SWARM_HYPOTHESIS=long SWARM_HYPOTHESIS_EXAMPLES=$(FUZZ_PY_EXAMPLES) TELEMETRY_FRAME_SO=$(TELEMETRY_FRAME_SO) \
	  $(PYTHON) -m unittest discover -s tools/tests/fuzz -t .

EXTRA_TESTS += fuzz-tests
TEST_BUILD += fuzz-build

-include $(shell find $(FUZZ_DIR) -name '*.d' 2>/dev/null)
