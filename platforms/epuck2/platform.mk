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
