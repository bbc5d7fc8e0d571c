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
PLATFORM_CHECKS += epuck2-gates epuck2-tests

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
  $(EPUCK2_STUBS)/epuck2_lib_stubs.c wire/telemetry/telemetry_rx.c wire/telemetry/telemetry_host.c \
  wire/telemetry/telemetry_frame.c
EPUCK2_HAL_DEPS := $(EPUCK2_HAL_COMMON) $(wildcard $(EPUCK2)/hal/*.h $(EPUCK2_STUBS)/*.h hal/*.h wire/*/*.h)

$(FW_HOST)/test_hal_epuck2_randb: $(EPUCK2)/tests/test_hal_epuck2.c $(EPUCK2_HAL_DEPS) $(EPUCK2)/hal/ircom_randb.c | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC,$@)$(CC) $(EPUCK2_HOST_CFLAGS) -o $@ $< $(EPUCK2_HAL_COMMON) $(EPUCK2)/hal/ircom_randb.c -lm
$(FW_HOST)/test_hal_epuck2_libircom: $(EPUCK2)/tests/test_hal_epuck2.c $(EPUCK2_HAL_DEPS) $(EPUCK2)/hal/ircom_libircom.c \
    $(EPUCK2_STUBS)/ircom_stubs.c | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC,$@)$(CC) $(EPUCK2_HOST_CFLAGS) -DTEST_LIBIRCOM -o $@ $< $(EPUCK2_HAL_COMMON) \
	  $(EPUCK2)/hal/ircom_libircom.c $(EPUCK2_STUBS)/ircom_stubs.c -lm

# The 16 kHz coefficients are generated from hal/sound_bands.h: a change
# there without regenerating them fails here.
.PHONY: epuck2-tone-coeffs
epuck2-tone-coeffs:
	@python3 tools/sound/gen_tone_tables.py --coeffs $$(sed -n 's/^#define EPUCK2_MIC_RATE_HZ \([0-9]*\)u$$/\1/p' \
	  $(EPUCK2)/hal/epuck2_lib.h) tone_band_coeffs_16k | cmp -s - $(EPUCK2)/hal/tone_coeffs_16k.c \
	  || { echo "$(EPUCK2)/hal/tone_coeffs_16k.c is not what tools/sound/gen_tone_tables.py --coeffs 16000 tone_band_coeffs_16k writes: regenerate it" >&2; exit 1; }
	@echo "epuck2: tone_coeffs_16k.c is generated from hal/sound_bands.h"

epuck2-tests: $(FW_HOST)/test_hal_epuck2_randb $(FW_HOST)/test_hal_epuck2_libircom epuck2-tone-coeffs
	@set -e; for t in $(FW_HOST)/test_hal_epuck2_randb $(FW_HOST)/test_hal_epuck2_libircom; do \
	  ASAN_OPTIONS=detect_leaks=1 $$t; done
