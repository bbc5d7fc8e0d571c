# firmware.mk - the robot platforms and their images.
#
# A platform is a folder platforms/<p>/ (its HAL in hal/, its run loop in
# run/, its images.list, platform.mk and platform.py, its tests/) and a line
# in platforms/platforms.list; this file includes each one's platform.mk,
# which adds its checks to PLATFORM_CHECKS and its gates to FW_GATES.  The
# walkthrough is docs/how-to/add-a-platform.md.
#
#   make firmware-check   every platform's checks (the e-puck1's: every image
#                         built from its declaration, gated on avr-gcc and
#                         arm-none-eabi-gcc, the footprint table, the HAL's
#                         host tests, the flasher, the forager image's
#                         telemetry), and the CPU report.  Part of `make test`.
#   make firmware-gates   the gates alone
#   make firmware-images  every image's main, generated from its declaration
#                         (build/firmware/gen/<p>/<image>_main.c)
#   make firmware-cpu     instructions per control step (valgrind callgrind)
#                         and the dsPIC estimate: build/firmware/cpu.md
#
# The images' build-time constants, which declarations name as $(NAME)
# (tools/make/images.py): seed 000's simulation values by default;
# docs/studies/drtm.md has its real-robot experiments' make lines.
#   FORAGER_POLICY (drtm|artm|frtm), FIRMWARE_N_ROBOTS (20), FIRMWARE_ARENA_MM
#   (4000), FIRMWARE_F_D (20), FIRMWARE_NEST_RADIUS_MM (750),
#   FIRMWARE_DRTM_THETA (offset|clip|raw), FIRMWARE_F0 (5),
#   FIRMWARE_CONSUMPTION_MILLI (2000), FIRMWARE_MOVE_COST (1), FIRMWARE_E_A (10),
#   FIRMWARE_PARK_STEPS (50), FIRMWARE_REPORT_STEPS (2; the beacon's wait
#   timeout follows: 4 x it + 1 steps).
FORAGER_POLICY ?= drtm
FIRMWARE_N_ROBOTS ?= 20
FIRMWARE_ARENA_MM ?= 4000
FIRMWARE_F_D ?= 20
FIRMWARE_NEST_RADIUS_MM ?= 750
FIRMWARE_DRTM_THETA ?= offset
FIRMWARE_F0 ?= 5
FIRMWARE_CONSUMPTION_MILLI ?= 2000
FIRMWARE_MOVE_COST ?= 1
FIRMWARE_E_A ?= 10
FIRMWARE_PARK_STEPS ?= 50
FIRMWARE_REPORT_STEPS ?= 2
FW_CONSTANTS := FORAGER_POLICY FIRMWARE_N_ROBOTS FIRMWARE_ARENA_MM FIRMWARE_F_D FIRMWARE_NEST_RADIUS_MM \
  FIRMWARE_DRTM_THETA FIRMWARE_F0 FIRMWARE_CONSUMPTION_MILLI FIRMWARE_MOVE_COST FIRMWARE_E_A \
  FIRMWARE_PARK_STEPS FIRMWARE_REPORT_STEPS
# The forager's policies, from their one list (firmware/foraging/task_alloc.h).
FW_POLICIES := $(shell sed -n 's/^\#define TA_POLICY_NAMES //p' firmware/foraging/task_alloc.h | tr -d '",')

FW_OUT := $(BUILD)/firmware
FW_GEN := $(FW_OUT)/gen
# The image declarations' reader; stdlib Python, also at parse time (the
# image lists), before the virtualenv exists.
FW_IMAGES_PY := python3 tools/make/images.py
# $(call fw_image_list,PLATFORM): its images.list, or the one its
# platform.py names as IMAGES (an emulated robot runs that robot's images).
fw_image_list = $(shell $(FW_IMAGES_PY) list-file platforms/$(1))
# $(call fw_images,PLATFORM,KEYS): NAME:VALUE... for each image of the platform.
fw_images = $(shell $(FW_IMAGES_PY) list $(call fw_image_list,$(1)) --platform platforms/$(1) --fields $(2))
fw_field = $(word $(2),$(subst :, ,$(1)))

# Images with telemetry send robot_state_t and schema_t
# (firmware/telemetry/robot_telemetry.c): they link lcm-gen's C of those two
# types, as generated library code with our warnings and
# -ffunction-sections, so --gc-sections drops its malloc-using decoders.
FW_LCM_C_DIR := $(BUILD)/lcm_c
FW_LCM_STAMP := $(FW_LCM_C_DIR)/.stamp
FW_LCM_SRC := $(FW_LCM_C_DIR)/swarmlcm_robot_state_t.c $(FW_LCM_C_DIR)/swarmlcm_schema_t.c
FW_ROBOT_TELEMETRY_SRC := firmware/telemetry/robot_telemetry.c

PLATFORMS := $(shell sed -e 's/\#.*//' platforms/platforms.list)
PLATFORM_CHECKS :=
FW_GATES :=
FW_IMAGE_TARGETS :=

.PHONY: firmware-check firmware-gates firmware-images firmware-cpu
EXTRA_TESTS += firmware-check
# The mains both firmware groups read, written once before they run side by side.
TEST_BUILD += firmware-images

FW_HOST := $(FW_OUT)/host
# $(call fw_generate,PLATFORM): writes the platform's mains (only those whose
# text changes) from its declarations and the build's constants.
fw_generate = $(FW_IMAGES_PY) generate $(call fw_image_list,$(1)) --platform platforms/$(1) --out $(FW_GEN)/$(1) \
  $(foreach v,$(FW_CONSTANTS),--set $(v)='$($(v))')

include $(foreach p,$(PLATFORMS),platforms/$(p)/platform.mk)

firmware-images: $(FW_IMAGE_TARGETS)
firmware-gates: $(FW_GATES)
firmware-check: lcm-types firmware-image-decls $(PLATFORM_CHECKS) firmware-cpu
	@echo "firmware-check: all passed"

# The declarations' reader: its errors name file and line, its mains.
.PHONY: firmware-image-decls
firmware-image-decls:
	@python3 tests/firmware/test_image_decls.py

# ------------------------------------------------ CPU report
FW_CPU_SRC := firmware/foraging/forager.c firmware/foraging/nest_beacon.c firmware/foraging/nest_link.c \
  firmware/common/motion.c firmware/common/random_walk.c firmware/common/rng.c firmware/foraging/task_alloc.c \
  hal/blob_detect.c \
  hal/hal_common.c hal/units.c hal/tone_detect.c hal/tone_tables.c \
  firmware/repatt/repatt.c firmware/repatt/avoid.c firmware/repatt/chemotaxis.c firmware/repatt/odometry.c
FW_CPU_STEPS ?= 2000

$(FW_HOST)/cpu_harness: tests/firmware/cpu_harness.c $(FW_CPU_SRC) $(wildcard firmware/*/*.h hal/*.h) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(CC) -std=c99 -Wall -Wextra -Werror -g -O2 -Ihal -Iwire -Ifirmware -o $@ tests/firmware/cpu_harness.c $(FW_CPU_SRC)

firmware-cpu: $(FW_HOST)/cpu_harness
	@$< 50 > /dev/null
	@$(PYTHON) tests/firmware/cpu_report.py $< $(FW_CPU_STEPS) --out $(FW_OUT)/cpu.md
