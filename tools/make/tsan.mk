# tsan.mk - one run's worker threads under ThreadSanitizer (issue 18): the
# library built with -fsanitize=thread; test_sim run with it (its
# test_thread_count_does_not_matter steps 800 full-sensing robots on 1, 2
# and 3 threads: controllers and sensors, IR delivery, the sound field,
# Box2D's solver through our pool), then swarmsim built with it runs one
# scenario of each seed whole on 3 threads in chunks of a few robots
# (SWARMSIM_POOL_CHUNK=1, pool.h).  A data race fails the group
# (halt_on_error); and the PIL walk, its emulated robots stepped on those
# threads.  About 40 s.  Box2D and the generated LCM code are not
# instrumented: a race inside them would not be seen.
TSAN_SCENARIOS := foraging_base repatt_quick eaipp_square
TSAN := -fsanitize=thread -fno-omit-frame-pointer
FW_OBJ_TSAN := $(call objs,tsan,$(FW_SRC))
SIM_OBJ_TSAN := $(call objs,tsan,$(SIM_SRC))
EXTRA_TESTS += tsan-tests
TEST_BUILD += $(BUILD)/tests/tsan/test_sim $(BUILD)/tsan/swarmsim

$(BUILD)/tsan/firmware/%.o $(BUILD)/tsan/hal/%.o $(BUILD)/tsan/wire/%.o: | $(BUILD)/config.mk
$(BUILD)/tsan/firmware/%.o: firmware/%.c
	@mkdir -p $(@D)
	$(CC) $(FW_CFLAGS) $(TSAN) -MMD -MP -c $< -o $@
$(BUILD)/tsan/hal/%.o: hal/%.c
	@mkdir -p $(@D)
	$(CC) $(FW_CFLAGS) $(TSAN) -MMD -MP -c $< -o $@
$(BUILD)/tsan/wire/%.o: wire/%.c
	@mkdir -p $(@D)
	$(CC) $(FW_CFLAGS) $(TSAN) -MMD -MP -c $< -o $@
$(BUILD)/tsan/sim_host/%.o: sim_host/%.c
	@mkdir -p $(@D)
	$(CC) $(SIM_CFLAGS) $(TSAN) -MMD -MP -c $< -o $@

# What registry.mk and lcm.mk give the other variants' objects.
$(BUILD)/tsan/sim_host/registry.o: $(REGISTRY_LIST)
$(BUILD)/tsan/sim_host/registry.o: SIM_CFLAGS += -I$(BUILD)/gen
$(BUILD)/tsan/sim_host/core/telemetry.o $(BUILD)/tsan/sim_host/core/telemetry_scene.o: $(LCM_C_STAMP)
$(BUILD)/tsan/firmware/telemetry/robot_telemetry.o: $(LCM_C_STAMP)

$(BUILD)/libswarm-tsan.a: $(FW_OBJ_TSAN) $(SIM_OBJ_TSAN) $(SIM_EXTRA_OBJ)
	@rm -f $@
	$(AR) rcs $@ $^

$(BUILD)/tests/tsan/%: tests/%.c $(BUILD)/libswarm-tsan.a
	@mkdir -p $(@D)
	$(CC) $(SIM_CFLAGS) $(TSAN) $(CMOCKA_CFLAGS) -MMD -MP -MF $@.d -o $@ $< $(BUILD)/libswarm-tsan.a \
	  $(CMOCKA_LIBS) $(LDLIBS_SIM)

# version.mk comes after this file: its VERSION_H is not yet set here.
$(BUILD)/tsan/sim_host/main.o: $(BUILD)/gen/version.h
$(BUILD)/tsan/sim_host/main.o: SIM_CFLAGS += -I$(BUILD)/gen
$(BUILD)/tsan/swarmsim: $(BUILD)/tsan/sim_host/main.o $(BUILD)/libswarm-tsan.a
	$(CC) $(TSAN) -o $@ $^ $(LDLIBS_SIM)

.PHONY: tsan-tests
tsan-tests: $(BUILD)/tests/tsan/test_sim $(BUILD)/tsan/swarmsim pil-avr
	@echo "== $< (ThreadSanitizer)"
	@cd tests && TSAN_OPTIONS=halt_on_error=1 ../$<
	@set -e; out=$$(mktemp -d); trap 'rm -rf "$$out"' EXIT; for s in $(TSAN_SCENARIOS); do \
	  echo "== sim_host/scenarios/$$s.yaml on 3 threads (ThreadSanitizer)"; \
	  SWARMSIM_POOL_CHUNK=1 TSAN_OPTIONS=halt_on_error=1 $(BUILD)/tsan/swarmsim sim_host/scenarios/$$s.yaml \
	    --lcm off --quiet --threads 1 --run-threads 3 --out "$$out/$$s"; done; \
	  echo "== tests/pil/walk.yaml on 3 threads, 4 robots on emulated MCUs (ThreadSanitizer)"; \
	  SWARMSIM_POOL_CHUNK=1 TSAN_OPTIONS=halt_on_error=1 $(BUILD)/tsan/swarmsim tests/pil/walk.yaml \
	    --lcm off --quiet --threads 1 --run-threads 3 --set pil.dir=$(abspath $(PIL_AVR_OUT)) --out "$$out/pil_walk"

-include $(shell find $(BUILD)/tsan -name '*.d' 2>/dev/null)
