# platforms/epuck2/platform.mk - the e-puck2 (STM32F407 over GCtronic's
# e-puck2 main-processor library and ChibiOS): its images' mains (the
# e-puck1's declarations over this platform's run loop), their gates, the
# host tests of its HAL, and the real build of .elf/.bin files against a
# user's checkout of the library.  Included by tools/make/firmware.mk for the
# line `epuck2` of platforms/platforms.list; the robot's page is
# docs/hardware/epuck2.md.
#
#   make epuck2-gates     every image compiles warning-free and links (against
#                         stubs of the library and of ChibiOS) with
#                         arm-none-eabi-gcc for the Cortex-M4F, hard float;
#                         static RAM, stack and flash within the budgets of
#                         platform.py (tests/firmware/image_gates.py): the
#                         table in build/firmware/epuck2/footprint.md
#   make epuck2-tests     host tests of the HAL (both IR backends, the host
#                         link, the camera's averaging, the microphones'
#                         tone levels at 16 kHz) and an image run against the
#                         stubs, its telemetry frames decoded (ASan/UBSan)
#   make epuck2-pil       phototaxis, forager and waypoint, as the gates built
#                         them, on QEMU's Cortex-M4F (netduinoplus2), their UART's telemetry through the
#                         bridge, the waypoint's route and poses sent on it
#                         (tests/pil_qemu.py); the flasher's tests, its load and
#                         verify through QEMU's gdbstub (tools/tests/flash/test_epuck2.py)
#   make epuck2-flash ELF=build/firmware/epuck2/real/forager.elf PORT=/dev/ttyACM0
#   make epuck2-firmware  .elf and .bin files: EPUCK2_LIB_DIR=/path/to/
#                         e-puck2_main-processor (a checkout with its
#                         submodules: ChibiOS 3.1), FIRMWARE_IMAGES (every
#                         image), ROBOT_ID (0); docs/hardware/epuck2.md
EPUCK2 := platforms/epuck2
EPUCK2_STUBS := $(EPUCK2)/tests/stubs
EPUCK2_GEN := $(FW_GEN)/epuck2
EPUCK2_INC := -I$(EPUCK2)/hal -I$(EPUCK2)/run

.PHONY: epuck2-images epuck2-gates epuck2-tests epuck2-firmware
FW_IMAGE_TARGETS += epuck2-images
FW_GATES += epuck2-gates
PLATFORM_CHECKS += epuck2-gates epuck2-tests epuck2-pil

epuck2-images:
	@$(call fw_generate,epuck2)
$(EPUCK2_GEN)/%_main.c: epuck2-images ;

epuck2-gates: lcm-types epuck2-images | $(BUILD)/config.mk
	@$(PYTHON) tests/firmware/image_gates.py --platform $(EPUCK2) --gen $(EPUCK2_GEN) --build $(FW_OUT)/epuck2 \
	  --lcm-c-dir $(FW_LCM_C_DIR) --lcm-cflags '$(LCM_CFLAGS)'

# ------------------------------------------------ host tests of the HAL
EPUCK2_HOST_CFLAGS := -std=c99 -pedantic -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes \
  -Wmissing-prototypes -g -O1 -Ihal -Iwire -Ifirmware $(EPUCK2_INC) -I$(EPUCK2_STUBS) \
  -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
EPUCK2_HAL_COMMON := $(EPUCK2)/hal/hal_epuck2.c $(EPUCK2)/hal/host_link.c $(EPUCK2)/hal/tone_coeffs_16k.c \
  hal/blob_detect.c hal/hal_common.c hal/units.c hal/tone_detect.c hal/tone_tables.c \
  $(EPUCK2_STUBS)/epuck2_lib_stubs.c $(EPUCK2_STUBS)/epuck2_os_stubs.c wire/telemetry/telemetry_rx.c wire/telemetry/telemetry_host.c \
  wire/telemetry/telemetry_frame.c
EPUCK2_HAL_DEPS := $(wildcard $(EPUCK2)/hal/*.h $(EPUCK2_STUBS)/*.h hal/*.h wire/*/*.h)
# Compiled once for both binaries (they differ in the IR backend and the
# test's -DTEST_LIBIRCOM only).
EPUCK2_HOST_OBJ := $(FW_HOST)/epuck2_obj
epuck2_host_obj = $(patsubst %.c,$(EPUCK2_HOST_OBJ)/%.o,$(1))
EPUCK2_HAL_COMMON_OBJ := $(call epuck2_host_obj,$(EPUCK2_HAL_COMMON))

$(EPUCK2_HOST_OBJ)/%.o: %.c $(EPUCK2_HAL_DEPS) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC,$@)$(CC) $(EPUCK2_HOST_CFLAGS) -c -o $@ $<
$(EPUCK2_HOST_OBJ)/test_randb.o: $(EPUCK2)/tests/test_hal_epuck2.c $(EPUCK2_HAL_DEPS) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC,$@)$(CC) $(EPUCK2_HOST_CFLAGS) -c -o $@ $<
$(EPUCK2_HOST_OBJ)/test_libircom.o: $(EPUCK2)/tests/test_hal_epuck2.c $(EPUCK2_HAL_DEPS) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC,$@)$(CC) $(EPUCK2_HOST_CFLAGS) -DTEST_LIBIRCOM -c -o $@ $<

$(FW_HOST)/test_hal_epuck2_randb: $(EPUCK2_HOST_OBJ)/test_randb.o $(EPUCK2_HAL_COMMON_OBJ) \
    $(call epuck2_host_obj,$(EPUCK2)/hal/ircom_randb.c)
	$(call show,LD,$@)$(CC) $(EPUCK2_HOST_CFLAGS) -o $@ $^ -lm
$(FW_HOST)/test_hal_epuck2_libircom: $(EPUCK2_HOST_OBJ)/test_libircom.o $(EPUCK2_HAL_COMMON_OBJ) \
    $(call epuck2_host_obj,$(EPUCK2)/hal/ircom_libircom.c $(EPUCK2_STUBS)/ircom_stubs.c)
	$(call show,LD,$@)$(CC) $(EPUCK2_HOST_CFLAGS) -o $@ $^ -lm

# The 16 kHz coefficients are generated from hal/sound_bands.h: a change
# there without regenerating them fails here.
.PHONY: epuck2-tone-coeffs
epuck2-tone-coeffs:
	@python3 tools/sound/gen_tone_tables.py --coeffs $$(sed -n 's/^#define EPUCK2_MIC_RATE_HZ \([0-9]*\)u$$/\1/p' \
	  hal/platform_facts.h) tone_band_coeffs_16k | cmp -s - $(EPUCK2)/hal/tone_coeffs_16k.c \
	  || { echo "$(EPUCK2)/hal/tone_coeffs_16k.c is not what tools/sound/gen_tone_tables.py --coeffs 16000 tone_band_coeffs_16k writes: regenerate it" >&2; exit 1; }
	@echo "epuck2: tone_coeffs_16k.c is generated from hal/sound_bands.h"

epuck2-tests: $(FW_HOST)/test_hal_epuck2_randb $(FW_HOST)/test_hal_epuck2_libircom epuck2-tone-coeffs
	@set -e; for t in $(FW_HOST)/test_hal_epuck2_randb $(FW_HOST)/test_hal_epuck2_libircom; do \
	  ASAN_OPTIONS=detect_leaks=1 $$t; done

# ------------------------------------------------ the real build
# Our side of an image (the controllers, hal/, wire/, this HAL, the image's
# main, lcm-gen's C for telemetry) compiled here with the e-puck2's flags
# into one archive per image; the library's Makefile (ChibiOS 3.1's rules,
# through chibios/Makefile) builds the library, ChibiOS and the glue
# (chibios/epuck2_os.c) and links the archive: one library build, shared by
# every image (EPUCK2_REAL/chibios), one relink per image.
EPUCK2_LIB_DIR ?=
# ROBOT_ID is shared with the e-puck1's flasher (empty there when not given).
EPUCK2_ROBOT_ID = $(or $(ROBOT_ID),0)
EPUCK2_IMAGES = $(call fw_images,epuck2,ir telemetry)
EPUCK2_FIRMWARE_IMAGES = $(or $(FIRMWARE_IMAGES),$(foreach r,$(EPUCK2_IMAGES),$(call fw_field,$(r),1)))
EPUCK2_REAL := $(FW_OUT)/epuck2/real
EPUCK2_ARCH := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16
EPUCK2_REAL_CFLAGS := $(EPUCK2_ARCH) -std=c99 -pedantic $(WARN) -O2 -ggdb -ffunction-sections -fdata-sections \
  $(FW_INC) $(EPUCK2_INC) -I$(FW_LCM_C_DIR) $(LCM_CFLAGS)
EPUCK2_REAL_COMMON := $(filter-out $(FW_ROBOT_TELEMETRY_SRC),$(FW_SRC)) \
  $(EPUCK2)/hal/hal_epuck2.c $(EPUCK2)/hal/host_link.c $(EPUCK2)/hal/tone_coeffs_16k.c
EPUCK2_REAL_TELEMETRY := $(FW_ROBOT_TELEMETRY_SRC) $(EPUCK2)/run/image_telemetry.c $(FW_LCM_SRC)
epuck2_real_obj = $(patsubst %.c,$(EPUCK2_REAL)/obj/%.o,$(1))
epuck2_row = $(filter $(1):%,$(EPUCK2_IMAGES))
# The sources of image $(1): ours, its IR backend, its telemetry.
epuck2_real_srcs = $(EPUCK2_GEN)/$(1)_main.c $(EPUCK2_REAL_COMMON) \
  $(EPUCK2)/hal/ircom_$(call fw_field,$(call epuck2_row,$(1)),2).c \
  $(if $(filter yes,$(call fw_field,$(call epuck2_row,$(1)),3)),$(EPUCK2_REAL_TELEMETRY))

$(EPUCK2_REAL)/obj/%.o: %.c $(FW_LCM_STAMP) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,E2-CC,$<)arm-none-eabi-gcc $(EPUCK2_REAL_CFLAGS) -c $< -o $@

# Defined for the goals that build images (make epuck2-firmware runs them
# in a sub-make), so other goals do not read the declarations.
ifneq ($(filter $(EPUCK2_REAL)/%,$(MAKECMDGOALS)),)
EPUCK2_IMAGES := $(EPUCK2_IMAGES)
define EPUCK2_IMAGE_RULES
$(EPUCK2_REAL)/lib/lib$(1).a: $(call epuck2_real_obj,$(call epuck2_real_srcs,$(1)))
	@mkdir -p $$(@D)
	$$(call show,AR,$$@)rm -f $$@ && arm-none-eabi-ar rcs $$@ $$^
$(EPUCK2_REAL)/$(1).bin: $(EPUCK2_REAL)/lib/lib$(1).a $(EPUCK2)/chibios/Makefile $(EPUCK2)/chibios/epuck2_os.c \
    $(EPUCK2_REAL)/robot_id
	@mkdir -p $(EPUCK2_REAL)/chibios
	@# The glue holds ROBOT_ID, which the library's rules do not track.
	@rm -f $(EPUCK2_REAL)/chibios/build/obj/epuck2_os.o
	$$(MAKE) --no-print-directory -C $(EPUCK2_REAL)/chibios -f $(abspath $(EPUCK2)/chibios/Makefile) \
	  GLOBAL_PATH=$(abspath $(EPUCK2_LIB_DIR)) PROJECT=$(1) IMAGE_LIB=$(abspath $(EPUCK2_REAL)/lib/lib$(1).a) \
	  ROBOT_ID=$(EPUCK2_ROBOT_ID)
	cp $(EPUCK2_REAL)/chibios/build/$(1).elf $(EPUCK2_REAL)/$(1).elf
	cp $(EPUCK2_REAL)/chibios/build/$(1).bin $$@
	@arm-none-eabi-size $(EPUCK2_REAL)/$(1).elf
	@echo "epuck2-firmware: $$@ (flash it: docs/hardware/epuck2.md)"
endef
$(foreach r,$(EPUCK2_IMAGES),$(eval $(call EPUCK2_IMAGE_RULES,$(call fw_field,$(r),1))))
endif

# Says exactly what is missing, then builds what was asked.
epuck2-firmware:
	@missing=0; say() { echo "epuck2-firmware: $$*" >&2; missing=1; }; \
	command -v arm-none-eabi-gcc > /dev/null || say "arm-none-eabi-gcc not found: install gcc-arm-none-eabi (make deps)"; \
	if [ -z "$(EPUCK2_LIB_DIR)" ]; then \
	  say "EPUCK2_LIB_DIR is not set: git clone --recursive https://github.com/e-puck2/e-puck2_main-processor and pass EPUCK2_LIB_DIR=/path/to/e-puck2_main-processor"; \
	elif [ ! -f "$(EPUCK2_LIB_DIR)/Makefile" ] || [ ! -f "$(EPUCK2_LIB_DIR)/src/motors.h" ]; then \
	  say "EPUCK2_LIB_DIR=$(EPUCK2_LIB_DIR) is not the e-puck2_main-processor library (no Makefile and src/motors.h there)"; \
	elif [ ! -f "$(EPUCK2_LIB_DIR)/ChibiOS/os/rt/rt.mk" ] || [ ! -f "$(EPUCK2_LIB_DIR)/src/msgbus/messagebus.h" ]; then \
	  say "$(EPUCK2_LIB_DIR): its submodules are missing (ChibiOS, src/msgbus, ...): run git submodule update --init there"; fi; \
	case "$(EPUCK2_ROBOT_ID)" in *[!0-9]*) say "ROBOT_ID must be a number 0..65534 (not '$(ROBOT_ID)')";; \
	  *) [ "$(EPUCK2_ROBOT_ID)" -le 65534 ] || say "ROBOT_ID must be 0..65534 (not $(ROBOT_ID))";; esac; \
	for i in $(EPUCK2_FIRMWARE_IMAGES); do case " $(EPUCK2_IMAGES) " in *" $$i:"*) ;; \
	  *) say "unknown image '$$i' (images: $(foreach r,$(EPUCK2_IMAGES),$(call fw_field,$(r),1)))";; esac; done; \
	if [ $$missing != 0 ]; then echo "epuck2-firmware: nothing built (make epuck2-gates checks the images without the library)" >&2; exit 1; fi
	@$(MAKE) --no-print-directory lcm-types epuck2-images
	@# The id the images are built with: rewritten when it changes, so they are rebuilt.
	@mkdir -p $(EPUCK2_REAL) && echo $(EPUCK2_ROBOT_ID) | cmp -s - $(EPUCK2_REAL)/robot_id \
	  || echo $(EPUCK2_ROBOT_ID) > $(EPUCK2_REAL)/robot_id
	@$(MAKE) --no-print-directory $(foreach i,$(EPUCK2_FIRMWARE_IMAGES),$(EPUCK2_REAL)/$(i).bin)

# ------------------------------------------------ processor in the loop
# Images with telemetry on QEMU's netduinoplus2 (the e-puck2's Cortex-M4F
# core): the very objects the gates measured (epuck2-gates: the e-puck2's
# flags, -Os), the library's stubs, and a glue over the emulated SysTick
# and USART1 (tests/qemu/epuck2_qemu_os.c) instead of ChibiOS.
# tests/pil_qemu.py runs each for 3 s of emulated time, sends the host
# link's frames to the one with it, and passes what comes out of its UART
# through the serial bridge (swarmtools.telemetry.bridge) to the LCM types.
EPUCK2_PIL_IMAGES ?= phototaxis forager waypoint
EPUCK2_PIL := $(FW_OUT)/epuck2/pil
EPUCK2_GATE_OBJ := $(FW_OUT)/epuck2/arm/obj
epuck2_gate_obj = $(patsubst %.c,$(EPUCK2_GATE_OBJ)/%.o,$(1))
EPUCK2_PIL_CFLAGS := $(EPUCK2_ARCH) -std=c99 -pedantic $(WARN) -Os -ffunction-sections -fdata-sections \
  -I$(EPUCK2)/hal
$(EPUCK2_PIL)/obj/%.o: $(EPUCK2)/tests/qemu/%.c $(EPUCK2)/hal/epuck2_os.h | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,E2-CC,$<)arm-none-eabi-gcc $(EPUCK2_PIL_CFLAGS) -c $< -o $@
ifneq ($(filter $(EPUCK2_PIL)/%,$(MAKECMDGOALS)),)
EPUCK2_IMAGES := $(EPUCK2_IMAGES)
define EPUCK2_PIL_RULES
$(EPUCK2_PIL)/$(1).elf: $(call epuck2_gate_obj,$(call epuck2_real_srcs,$(1)) $(EPUCK2_STUBS)/epuck2_lib_stubs.c \
    $(EPUCK2_STUBS)/ircom_stubs.c) $(EPUCK2_PIL)/obj/epuck2_qemu_os.o $(EPUCK2)/tests/qemu/epuck2_qemu.ld
	@mkdir -p $$(@D)
	$$(call show,E2-LD,$$@)arm-none-eabi-gcc $(EPUCK2_ARCH) -nostartfiles --specs=nano.specs \
	  -T $(EPUCK2)/tests/qemu/epuck2_qemu.ld -Wl,--gc-sections -o $$@ $$(filter %.o,$$^) -lm
endef
$(foreach r,$(EPUCK2_IMAGES),$(eval $(call EPUCK2_PIL_RULES,$(call fw_field,$(r),1))))
endif

# The emulated runs and the flasher's tests are independent: side by side
# under make -j (make test).
.PHONY: epuck2-pil epuck2-pil-elfs epuck2-pil-qemu epuck2-pil-flasher
epuck2-pil: epuck2-pil-qemu epuck2-pil-flasher
epuck2-pil-elfs: epuck2-gates deps
	@$(MAKE) --no-print-directory $(foreach i,$(EPUCK2_PIL_IMAGES),$(EPUCK2_PIL)/$(i).elf)
epuck2-pil-qemu: epuck2-pil-elfs
	@$(PYTHON) $(EPUCK2)/tests/pil_qemu.py --elf-dir $(EPUCK2_PIL) $(EPUCK2_PIL_IMAGES)
epuck2-pil-flasher: epuck2-pil-elfs
	@$(PYTHON) -m tools.tests.flash.test_epuck2 $(EPUCK2_PIL)/phototaxis.elf

# ------------------------------------------------ flashing
ELF ?=
PORT ?=
.PHONY: epuck2-flash
epuck2-flash:
	@if [ -z "$(ELF)" ] || [ -z "$(PORT)" ]; then \
	  echo "usage: make epuck2-flash ELF=build/firmware/epuck2/real/forager.elf PORT=/dev/ttyACM0" >&2; exit 2; fi
	$(PYTHON) -m swarmtools.flash.epuck2 $(ELF) $(PORT)
