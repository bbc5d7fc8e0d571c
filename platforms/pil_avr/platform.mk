# platforms/pil_avr/platform.mk - the emulated ATmega2560 of
# processor-in-the-loop (docs/reference/pil.md): the e-puck1's images built
# for it with avr-gcc, the simavr emulator program that runs them (GPL-3, a
# program of its own: emu/), the host build of every image for the
# step-by-step comparison, and the tests.  Included by tools/make/firmware.mk
# for the line `pil_avr` of platforms/platforms.list.
#
#   make pil-avr          every image's ELF (build/firmware/pil_avr/avr/<image>.elf),
#                         the emulator and the comparison driver
#   make pil-avr-tests    each image on the AVR beside its host build (-funsigned-char,
#                         UBSan with the alignment check), step by step over a
#                         scripted world, some with camera frames; every protocol
#                         error and every way an MCU fails, each an error naming robot
#                         and step.  Part of make firmware-check (make test).
#   make pil-avr-compare  the same comparison, longer (PIL_COMPARE_STEPS, 3000), and the
#                         measured cycles and stack per image into
#                         build/firmware/pil_avr/cpu.md
#   make readme-pil-cpu   that and make pil-m4-compare (the M4's instructions and stack:
#                         platforms/pil_m4/), then the table into
#                         docs/hardware/footprint.md (between its pil-cpu markers)
#   make pil-avr-bench    the cost of a PIL robot-step, and how many PIL robots one
#                         core keeps at real time (tools/bench/pil.sh)
PIL_AVR := platforms/pil_avr
PIL_AVR_GEN := $(FW_GEN)/pil_avr
PIL_AVR_OUT := $(FW_OUT)/pil_avr
PIL_AVR_EMU := $(PIL_AVR_OUT)/pil_avr_emu
PIL_AVR_COMPARE := $(PIL_AVR_OUT)/pil_compare
PIL_AVR_INC := -Ihal -Iwire -Ifirmware -I$(PIL_AVR)/hal -I$(PIL_AVR)/run -I$(FW_LCM_C_DIR) $(LCM_CFLAGS)
PIL_COMPARE_STEPS ?= 3000

.PHONY: pil-avr pil-avr-images pil-avr-tests pil-avr-errors pil-avr-compare readme-pil-cpu pil-avr-bench
FW_IMAGE_TARGETS += pil-avr-images
PLATFORM_CHECKS += pil-avr-tests

pil-avr-images:
	@$(call fw_generate,pil_avr)
$(PIL_AVR_GEN)/%_main.c: pil-avr-images ;

# What every image links (--gc-sections keeps what it uses): the
# controllers, hal/ and wire/ (FW_SRC), this platform's HAL and run loop's
# telemetry, and lcm-gen's C of the two types a robot sends.
PIL_AVR_LIB_SRC := $(FW_SRC) $(PIL_AVR)/hal/hal_pil.c $(PIL_AVR)/run/image_telemetry.c
PIL_AVR_HDRS := $(wildcard hal/*.h wire/*/*.h firmware/*/*.h $(PIL_AVR)/hal/*.h $(PIL_AVR)/run/*.h)

# The AVR build: avr-gcc for the ATmega2560, -Os as on an 8-bit part.
PIL_AVR_CC := avr-gcc
PIL_AVR_CFLAGS := -mmcu=atmega2560 -std=c99 -pedantic $(WARN) -Os -gdwarf-4 -ffunction-sections -fdata-sections $(PIL_AVR_INC)
PIL_AVR_LDFLAGS := -mmcu=atmega2560 -Wl,--gc-sections
PIL_AVR_OBJ := $(patsubst %.c,$(PIL_AVR_OUT)/avr/obj/%.o,$(PIL_AVR_LIB_SRC) $(PIL_AVR)/hal/pil_port_avr.c $(FW_LCM_SRC))
$(PIL_AVR_OUT)/avr/obj/%.o: %.c $(PIL_AVR_HDRS) $(FW_LCM_STAMP) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,AVR-CC,$<)$(PIL_AVR_CC) $(PIL_AVR_CFLAGS) -c $< -o $@
$(PIL_AVR_OUT)/avr/libpil.a: $(PIL_AVR_OBJ)
	$(call show,AR,$@)rm -f $@.tmp.$$$$ && avr-ar rcs $@.tmp.$$$$ $^ && mv $@.tmp.$$$$ $@
$(PIL_AVR_OUT)/avr/%.elf: $(PIL_AVR_GEN)/%_main.c $(PIL_AVR_OUT)/avr/libpil.a
	$(call show,AVR-LD,$@)$(PIL_AVR_CC) $(PIL_AVR_CFLAGS) -I$(PIL_AVR_GEN) $(PIL_AVR_LDFLAGS) -o $@ $< \
	  $(PIL_AVR_OUT)/avr/libpil.a -lm
# The tests' own images: one that misbehaves on cue, one that times the detectors.
$(PIL_AVR_OUT)/avr/misbehave.elf $(PIL_AVR_OUT)/avr/detect.elf: $(PIL_AVR_OUT)/avr/%.elf: $(PIL_AVR)/tests/%_main.c \
    $(PIL_AVR_OUT)/avr/libpil.a
	$(call show,AVR-LD,$@)$(PIL_AVR_CC) $(PIL_AVR_CFLAGS) $(PIL_AVR_LDFLAGS) -o $@ $< $(PIL_AVR_OUT)/avr/libpil.a

# The host build of the same images, for the comparison: -funsigned-char
# (ARM's char, which the AVR cannot show) and UBSan with its alignment
# check (the dsPIC traps on a misaligned 16-bit access; the AVR does not).
PIL_HOST_CFLAGS := -std=c99 -pedantic $(WARN) -O1 -g -funsigned-char -ffunction-sections -fdata-sections -fno-sanitize-recover=all \
  -fsanitize=undefined,alignment -D_POSIX_C_SOURCE=200809L $(PIL_AVR_INC)
PIL_HOST_OBJ := $(patsubst %.c,$(PIL_AVR_OUT)/host/obj/%.o,$(PIL_AVR_LIB_SRC) $(PIL_AVR)/tests/host_port.c $(FW_LCM_SRC))
$(PIL_AVR_OUT)/host/obj/%.o: %.c $(PIL_AVR_HDRS) $(FW_LCM_STAMP) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC,$<)$(CC) $(PIL_HOST_CFLAGS) -c $< -o $@
$(PIL_AVR_OUT)/host/libpil.a: $(PIL_HOST_OBJ)
	$(call show,AR,$@)rm -f $@.tmp.$$$$ && ar rcs $@.tmp.$$$$ $^ && mv $@.tmp.$$$$ $@
$(PIL_AVR_OUT)/host/%: $(PIL_AVR_GEN)/%_main.c $(PIL_AVR_OUT)/host/libpil.a
	$(call show,LD,$@)$(CC) $(PIL_HOST_CFLAGS) -I$(PIL_AVR_GEN) -Wl,--gc-sections -o $@ $< $(PIL_AVR_OUT)/host/libpil.a -lm

# The emulator: the one program that links libsimavr (GPL-3; emu/COPYING).
PIL_WIRE_SRC := wire/pil/pil_frame.c wire/pil/pil_msg.c wire/telemetry/telemetry_frame.c
$(PIL_AVR_EMU): $(PIL_AVR)/emu/pil_avr_emu.c $(PIL_WIRE_SRC) $(wildcard wire/pil/*.h) $(PIL_AVR)/hal/pil_port_avr.h | $(BUILD)/config.mk
	@mkdir -p $(@D)
	@printf '#include <simavr/sim_avr.h>\n' | $(CC) -E -x c - > /dev/null 2>&1 || \
	  { echo "pil_avr: no libsimavr: install the Debian package libsimavr-dev (make deps does, as root)" >&2; exit 1; }
	$(call show,CC,$<)$(CC) -std=c11 -D_POSIX_C_SOURCE=200809L $(WARN) -O2 -g -Ihal -Iwire -I$(PIL_AVR)/hal \
	  -o $@ $(PIL_AVR)/emu/pil_avr_emu.c $(PIL_WIRE_SRC) -lsimavr

# The comparison driver, and the simulator's end of the pipe it uses (and
# platforms/pil_m4/'s, which adds its link to PIL_COMPARE_SRC and PIL_COMPARE_INC).
PIL_COMPARE_SRC := $(PIL_AVR)/tests/pil_compare.c $(PIL_AVR)/tests/pil_script.c $(PIL_AVR)/link/pil_avr_link.c \
  wire/pil/pil_host.c $(PIL_WIRE_SRC)
$(PIL_AVR_COMPARE): $(PIL_COMPARE_SRC) $(wildcard wire/pil/*.h $(PIL_AVR)/link/*.h $(PIL_AVR)/tests/*.h) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC,$<)$(CC) -std=c11 -D_POSIX_C_SOURCE=200809L $(WARN) -O1 -g $(ASAN) -Ihal -Iwire \
	  -I$(PIL_AVR)/hal -I$(PIL_AVR)/link -I$(PIL_AVR)/tests $(PIL_COMPARE_INC) -o $@ $(PIL_COMPARE_SRC)

# Every image's AVR ELF and host build, named from the declarations when
# the goal runs (not at parse time).
pil_avr_names = $(foreach r,$(call fw_images,pil_avr,telemetry),$(call fw_field,$(r),1))
pil-avr: pil-avr-images lcm-types
	@$(MAKE) --no-print-directory pil-avr-build PIL_NAMES='$(pil_avr_names)'
.PHONY: pil-avr-build
pil-avr-build: $(PIL_AVR_EMU) $(PIL_AVR_COMPARE) $(PIL_AVR_OUT)/avr/misbehave.elf $(PIL_AVR_OUT)/avr/detect.elf \
    $(foreach i,$(PIL_NAMES),$(PIL_AVR_OUT)/avr/$(i).elf $(PIL_AVR_OUT)/host/$(i) $(PIL_AVR_OUT)/avr/$(i).map)
	@:

# PIL_IMAGES_FRAMES: the images that also run with camera frames (blob_detect on the MCU).
PIL_IMAGES_FRAMES := forager repatt
PIL_TEST_STEPS ?= 60
pil-avr-tests: pil-avr
	@PIL_OUT=$(PIL_AVR_OUT) STEPS=$(PIL_TEST_STEPS) IMAGES='$(pil_avr_names)' FRAMES='$(PIL_IMAGES_FRAMES)' \
	  bash $(PIL_AVR)/tests/pil_tests.sh

pil-avr-compare: pil-avr
	@PIL_OUT=$(PIL_AVR_OUT) STEPS=$(PIL_COMPARE_STEPS) IMAGES='$(pil_avr_names)' FRAMES='$(PIL_IMAGES_FRAMES)' \
	  LONG=1 REPORT=$(PIL_AVR_OUT)/cpu.md bash $(PIL_AVR)/tests/pil_tests.sh

readme-pil-cpu: pil-avr-compare pil-m4-compare
	@$(PYTHON) $(PIL_AVR)/tests/pil_report.py $(PIL_AVR_OUT)/measure --cpu $(FW_OUT)/cpu.md \
	  --footprint $(FW_OUT)/epuck1/footprint.md --page docs/hardware/footprint.md --m4 $(FW_OUT)/pil_m4/measure

pil-avr-bench: pil-avr $(BUILD)/swarmsim
	bash tools/bench/pil.sh $(BUILD)/swarmsim

# ------------------------------------------------ the simulator's end
# The simulator's model of PIL robots (sim_host/models/pil/) reads the
# images' table generated from the same declarations and constants
# (tools/make/images.py host-list: each image's parameters as its run loop
# makes them) and starts the emulator through link/ (linked into libswarm;
# the emulator itself never is).
PIL_IMAGE_LIST := $(BUILD)/gen/pil_image_list.h
.PHONY: pil-image-list
pil-image-list:
	@mkdir -p $(dir $(PIL_IMAGE_LIST))
	@$(FW_IMAGES_PY) host-list $(call fw_image_list,pil_avr) --platform $(PIL_AVR) --out $(PIL_IMAGE_LIST) \
	  $(foreach v,$(FW_CONSTANTS),--set $(v)='$($(v))')
$(PIL_IMAGE_LIST): pil-image-list ;
# Every variant of the library (obj, asan, and tools/make/tsan.mk's and
# fuzz.mk's, named here literally: those fragments are read after this one).
PIL_MODEL_VARIANTS := $(BUILD)/obj $(BUILD)/asan $(BUILD)/tsan $(BUILD)/fuzz/obj
$(addsuffix /sim_host/models/pil/pil_images.o,$(PIL_MODEL_VARIANTS)): $(PIL_IMAGE_LIST)
$(addsuffix /sim_host/models/pil/%.o,$(PIL_MODEL_VARIANTS)): SIM_CFLAGS += -I$(BUILD)/gen -I$(PIL_AVR)/link
SIM_EXTRA_OBJ += $(BUILD)/obj/$(PIL_AVR)/link/pil_avr_link.o
SIM_EXTRA_OBJ_ASAN += $(BUILD)/asan/$(PIL_AVR)/link/pil_avr_link.o
$(BUILD)/obj/$(PIL_AVR)/link/%.o: $(PIL_AVR)/link/%.c | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC,$<)$(CC) $(SIM_CFLAGS) -MMD -MP -c $< -o $@
$(BUILD)/asan/$(PIL_AVR)/link/%.o: $(PIL_AVR)/link/%.c | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC-ASAN,$<)$(CC) $(SIM_CFLAGS) $(ASAN) -MMD -MP -c $< -o $@
# The fuzz harnesses' library (tools/make/fuzz.mk) links the link too
# (libswarm's PIL model calls it), built with clang as the rest of it.
$(BUILD)/fuzz/libswarm.a: $(BUILD)/fuzz/obj/$(PIL_AVR)/link/pil_avr_link.o
$(BUILD)/fuzz/obj/$(PIL_AVR)/link/%.o: $(PIL_AVR)/link/%.c | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(FUZZ_CC) $(SIM_CFLAGS) $(FUZZ_CFLAGS) -MMD -MP -c $< -o $@

# Each image's state map (state_map.py: its controller state's fields on the
# AVR and here, from both builds' DWARF), beside its ELF.
$(PIL_AVR_OUT)/avr/%.map: $(PIL_AVR_OUT)/avr/%.elf $(PIL_AVR_OUT)/host/% $(PIL_AVR)/state_map.py
	$(call show,MAP,$@)$(PYTHON) $(PIL_AVR)/state_map.py $< $(PIL_AVR_OUT)/host/$* $@

# The simulator's PIL test (tests/cli/pil.sh) and the PIL page's runnable
# example (docs/reference/pil.md) run the images beside swarmsim.
cli-tests docs-tests: pil-avr
