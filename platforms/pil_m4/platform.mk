# platforms/pil_m4/platform.mk - the emulated Cortex-M4F of
# processor-in-the-loop (docs/reference/pil.md): the e-puck1's images (as
# platforms/pil_avr/ generates them: the same run loop and HAL) built with
# the e-puck2's flags for QEMU's netduinoplus2 (an STM32F405), over this
# platform's port (a semihosting mailbox, SysTick) and bare-metal start.  QEMU itself
# (Debian's qemu-system-arm) is the emulator: one process per robot.
#
#   make pil-m4           every image's ELF (build/firmware/pil_m4/m4/<image>.elf)
#                         and its state map, and the test images (misbehave, calibrate)
#   make pil-m4-tests     each image on the M4 beside its host build, step by step,
#                         the counts' calibration, every error (part of firmware-check)
#   make pil-m4-compare   the same, longer; its measurement feeds make readme-pil-cpu
#   make pil-m4-bench     the cost of an M4 robot-step (tools/bench/pil.sh)
PIL_M4 := platforms/pil_m4
PIL_M4_OUT := $(FW_OUT)/pil_m4
PIL_M4_INC := -Ihal -Iwire -Ifirmware -I$(PIL_M4)/hal -I$(PIL_AVR)/hal -I$(PIL_AVR)/run -I$(FW_LCM_C_DIR) $(LCM_CFLAGS)
PIL_M4_CC := arm-none-eabi-gcc
# The e-puck2's core and float ABI.
PIL_M4_ARCH := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16
PIL_M4_CFLAGS := $(PIL_M4_ARCH) -std=c99 -pedantic $(WARN) -Os -gdwarf-4 -ffunction-sections -fdata-sections $(PIL_M4_INC)
PIL_M4_LDFLAGS := $(PIL_M4_ARCH) -nostartfiles --specs=nano.specs -T $(PIL_M4)/startup/m4.ld -Wl,--gc-sections
PIL_M4_HDRS := $(PIL_AVR_HDRS) $(wildcard $(PIL_M4)/hal/*.h)
PIL_M4_OBJ := $(patsubst %.c,$(PIL_M4_OUT)/obj/%.o,$(PIL_AVR_LIB_SRC) $(PIL_M4)/hal/pil_port_m4.c $(FW_LCM_SRC))
PIL_M4_START := $(PIL_M4_OUT)/obj/$(PIL_M4)/startup/pil_m4_startup.o

.PHONY: pil-m4 pil-m4-build
$(PIL_M4_OUT)/obj/%.o: %.c $(PIL_M4_HDRS) $(FW_LCM_STAMP) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,M4-CC,$<)$(PIL_M4_CC) $(PIL_M4_CFLAGS) -c $< -o $@
$(PIL_M4_OUT)/libpil.a: $(PIL_M4_OBJ)
	$(call show,AR,$@)rm -f $@ && arm-none-eabi-ar rcs $@ $^
$(PIL_M4_OUT)/m4/%.elf: $(PIL_AVR_GEN)/%_main.c $(PIL_M4_OUT)/libpil.a $(PIL_M4_START) $(PIL_M4)/startup/m4.ld
	@mkdir -p $(@D)
	$(call show,M4-LD,$@)$(PIL_M4_CC) $(PIL_M4_CFLAGS) -I$(PIL_AVR_GEN) $(PIL_M4_LDFLAGS) -o $@ $< \
	  $(PIL_M4_START) $(PIL_M4_OUT)/libpil.a -lm
$(PIL_M4_OUT)/m4/misbehave.elf: $(PIL_AVR)/tests/misbehave_main.c $(PIL_M4_OUT)/libpil.a $(PIL_M4_START)
	@mkdir -p $(@D)
	$(call show,M4-LD,$@)$(PIL_M4_CC) $(PIL_M4_CFLAGS) $(PIL_M4_LDFLAGS) -o $@ $< $(PIL_M4_START) $(PIL_M4_OUT)/libpil.a
# The counts' check: a step of a known number of instructions (tests/).
$(PIL_M4_OUT)/m4/calibrate.elf: $(PIL_M4)/tests/calibrate_main.c $(PIL_M4_OUT)/libpil.a $(PIL_M4_START)
	@mkdir -p $(@D)
	$(call show,M4-LD,$@)$(PIL_M4_CC) $(PIL_M4_CFLAGS) $(PIL_M4_LDFLAGS) -o $@ $< $(PIL_M4_START) $(PIL_M4_OUT)/libpil.a
# Each image's state map: its controller state on the M4 and in the host build.
$(PIL_M4_OUT)/m4/%.map: $(PIL_M4_OUT)/m4/%.elf $(PIL_AVR_OUT)/host/% $(PIL_AVR)/state_map.py
	$(call show,MAP,$@)$(PYTHON) $(PIL_AVR)/state_map.py $< $(PIL_AVR_OUT)/host/$* $@

pil-m4: pil-avr-images lcm-types
	@$(MAKE) --no-print-directory pil-m4-build PIL_NAMES='$(pil_avr_names)'
pil-m4-build: $(PIL_M4_OUT)/m4/misbehave.elf $(PIL_M4_OUT)/m4/calibrate.elf $(foreach i,$(PIL_NAMES),$(PIL_M4_OUT)/m4/$(i).elf $(PIL_M4_OUT)/m4/$(i).map)
	@:

# ------------------------------------------------ the simulator's end
# The PIL model (sim_host/models/pil/) starts QEMU through link/ (linked
# into libswarm; QEMU itself is a program of its own).
$(addsuffix /sim_host/models/pil/%.o,$(PIL_MODEL_VARIANTS)): SIM_CFLAGS += -I$(PIL_M4)/link -I$(PIL_M4)/hal
SIM_EXTRA_OBJ += $(BUILD)/obj/$(PIL_M4)/link/pil_m4_link.o
SIM_EXTRA_OBJ_ASAN += $(BUILD)/asan/$(PIL_M4)/link/pil_m4_link.o
PIL_M4_LINK_CFLAGS = $(SIM_CFLAGS) -I$(PIL_AVR)/link -I$(PIL_M4)/hal
$(BUILD)/obj/$(PIL_M4)/link/%.o: $(PIL_M4)/link/%.c | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC,$<)$(CC) $(PIL_M4_LINK_CFLAGS) -MMD -MP -c $< -o $@
$(BUILD)/asan/$(PIL_M4)/link/%.o: $(PIL_M4)/link/%.c | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC-ASAN,$<)$(CC) $(PIL_M4_LINK_CFLAGS) $(ASAN) -MMD -MP -c $< -o $@
$(BUILD)/fuzz/libswarm.a: $(BUILD)/fuzz/obj/$(PIL_M4)/link/pil_m4_link.o
$(BUILD)/fuzz/obj/$(PIL_M4)/link/%.o: $(PIL_M4)/link/%.c | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(FUZZ_CC) $(PIL_M4_LINK_CFLAGS) $(FUZZ_CFLAGS) -MMD -MP -c $< -o $@

# The simulator's PIL test and the PIL page's example run M4 robots too.
cli-tests docs-tests: pil-m4

# The comparison driver (platforms/pil_avr/tests/pil_compare.c) runs M4
# images too (--m4): this link is linked into it.
PIL_COMPARE_SRC += $(PIL_M4)/link/pil_m4_link.c
PIL_COMPARE_INC += -I$(PIL_M4)/link -I$(PIL_M4)/hal
$(PIL_AVR_COMPARE): $(PIL_M4)/link/pil_m4_link.c $(wildcard $(PIL_M4)/link/*.h $(PIL_M4)/hal/*.h)

# Every image on the M4 beside its host build, step by step (the AVR's
# comparison script, platforms/pil_avr/tests/pil_tests.sh, with M4_OUT),
# the camera frames' images once more with frames; the protocol's errors,
# the budget, a killed or hung QEMU, and no QEMU outliving its driver.
.PHONY: pil-m4-tests pil-m4-compare
PLATFORM_CHECKS += pil-m4-tests
pil-m4-tests: pil-m4 pil-avr
	@PIL_OUT=$(PIL_AVR_OUT) M4_OUT=$(PIL_M4_OUT) STEPS=$(PIL_TEST_STEPS) IMAGES='$(pil_avr_names)' \
	  FRAMES='$(PIL_IMAGES_FRAMES)' bash $(PIL_AVR)/tests/pil_tests.sh
# The same, longer (PIL_COMPARE_STEPS): two robots and seeds per image.
pil-m4-compare: pil-m4 pil-avr
	@PIL_OUT=$(PIL_AVR_OUT) M4_OUT=$(PIL_M4_OUT) STEPS=$(PIL_COMPARE_STEPS) IMAGES='$(pil_avr_names)' \
	  FRAMES='$(PIL_IMAGES_FRAMES)' LONG=1 bash $(PIL_AVR)/tests/pil_tests.sh

# The cost of an M4 robot-step, and how many one core keeps at real time.
.PHONY: pil-m4-bench
pil-m4-bench: pil-m4 pil-avr $(BUILD)/swarmsim
	PLATFORM=pil_m4 bash tools/bench/pil.sh $(BUILD)/swarmsim
