# firmware.mk - the real e-puck1 target: firmware images, their portable
# gates, the CPU report, and the XC16 build of .hex files.
#
#   make firmware-check   every image with platforms/epuck1/hal compiles warning-free and
#                         links (against stubs of the e-puck library) with
#                         avr-gcc (XC16's data model) and arm-none-eabi-gcc
#                         (Cortex-M4F); footprint table and the 2 KB static
#                         RAM gate; host tests of platforms/epuck1/hal; flasher tests
#                         against a simulated bootloader; the CPU report;
#                         the forager image run against the stubs, its
#                         telemetry frames decoded (robot_state_t).  Needs
#                         lcm-types (lcm-gen's C for the images' telemetry).
#                         Part of `make test`.
#   make readme-footprint the README's footprint table from the gates' measurement
#   make firmware-cpu     instructions per control step (valgrind callgrind)
#                         and the dsPIC estimate: build/firmware/cpu.md
#   make firmware         .hex files with Microchip XC16 and the user's copy of
#                         GCtronic's e-puck library (never in this repository):
#                           XC16_DIR       XC16 install (bin/xc16-gcc)
#                           EPUCK_LIB_DIR  the e-puck library (its library/ folder
#                                          or the repository holding it)
#                           RANDB_DIR      e-RandB turret driver (e_randb.c), for
#                                          the images on the turret (images.list)
#                           IRCOM_DIR      libIrcom sources, for the images on
#                                          libIrcom (images.list)
#                         FIRMWARE_IMAGES (every image of firmware/apps/images.list),
#                         FORAGER_POLICY (drtm|artm|frtm), FIRMWARE_N_ROBOTS
#                         (20), FIRMWARE_ARENA_MM (4000), FIRMWARE_F_D (20),
#                         FIRMWARE_NEST_RADIUS_MM (750), FIRMWARE_DRTM_THETA
#                         (offset|clip|raw), FIRMWARE_F0 (5),
#                         FIRMWARE_CONSUMPTION_MILLI (2000), FIRMWARE_MOVE_COST
#                         (1), FIRMWARE_E_A (10).
#   make flash HEX=build/firmware/xc16/forager.hex DEVICE=/dev/rfcomm0 ROBOT_ID=7
#
# Images, their IR backend (platforms/epuck1/hal/ircom_*.c) and whether they send
# telemetry: one line each in firmware/apps/images.list.
FW_IMAGE_LIST := firmware/apps/images.list
FW_IMAGE_ROWS := $(shell sed -e 's/\#.*//' $(FW_IMAGE_LIST) | awk 'NF == 3 { print $$1 ":" $$2 ":" $$3 }')
fw_field = $(word $(2),$(subst :, ,$(1)))
FW_IMAGE_SPECS := $(foreach r,$(FW_IMAGE_ROWS),$(call fw_field,$(r),1):$(call fw_field,$(r),2))
FW_TELEMETRY_IMAGES := $(foreach r,$(FW_IMAGE_ROWS),$(if $(filter yes,$(call fw_field,$(r),3)),$(call fw_field,$(r),1)))
# The forager's policies, from their one list (firmware/foraging/task_alloc.h).
FW_POLICIES := $(shell sed -n 's/^\#define TA_POLICY_NAMES //p' firmware/foraging/task_alloc.h | tr -d '",')
FW_OUT := $(BUILD)/firmware

.PHONY: firmware firmware-check firmware-cpu firmware-gates firmware-hal-tests \
        firmware-flash-tests flash

EXTRA_TESTS += firmware-check

# Images with telemetry send robot_state_t and schema_t
# (firmware/telemetry/robot_telemetry.c): they link lcm-gen's C of those two
# types, as generated library code with our warnings and
# -ffunction-sections, so --gc-sections drops its malloc-using decoders.
FW_LCM_C_DIR := $(BUILD)/lcm_c
FW_LCM_STAMP := $(FW_LCM_C_DIR)/.stamp
FW_LCM_SRC := $(FW_LCM_C_DIR)/swarmlcm_robot_state_t.c $(FW_LCM_C_DIR)/swarmlcm_schema_t.c
FW_ROBOT_TELEMETRY_SRC := firmware/telemetry/robot_telemetry.c

firmware-check: lcm-types firmware-gates firmware-hal-tests firmware-flash-tests firmware-cpu
	@echo "firmware-check: all passed"

firmware-gates: lcm-types | $(BUILD)/config.mk
	@$(PYTHON) tests/firmware/image_gates.py --build $(FW_OUT) --lcm-c-dir $(FW_LCM_C_DIR) \
	  --lcm-cflags '$(LCM_CFLAGS)' --images $(FW_IMAGE_LIST)

# The README's footprint table, written from the gates' measurement (which
# fails while the README's differs from it).  The gates run first; their
# failure on that difference is the reason to run this, so it is ignored.
.PHONY: readme-footprint
readme-footprint: lcm-types | $(BUILD)/config.mk
	@$(PYTHON) tests/firmware/image_gates.py --build $(FW_OUT) --lcm-c-dir $(FW_LCM_C_DIR) \
	  --lcm-cflags '$(LCM_CFLAGS)' --images $(FW_IMAGE_LIST) > /dev/null || true
	@$(PYTHON) tests/firmware/readme_footprint.py --update --table $(FW_OUT)/footprint_readme.md

firmware-flash-tests: deps
	@$(PYTHON) tools/tests/flash/test_epuck.py

# ------------------------------------------------ host tests of platforms/epuck1/hal
FW_HOST := $(FW_OUT)/host
FW_HOST_CFLAGS := -std=c99 -pedantic -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes \
  -Wmissing-prototypes -g -O1 -Ihal -Iwire -Ifirmware -Iplatforms/epuck1/hal -Iplatforms/epuck1/tests/stubs \
  -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FW_HAL_COMMON := platforms/epuck1/hal/hal_epuck.c platforms/epuck1/hal/host_link.c hal/blob_detect.c hal/hal_common.c hal/units.c \
  hal/tone_detect.c hal/tone_tables.c platforms/epuck1/tests/stubs/epuck_lib_stubs.c \
  wire/telemetry/telemetry_rx.c wire/telemetry/telemetry_host.c wire/telemetry/telemetry_frame.c
FW_HAL_DEPS := platforms/epuck1/tests/test_hal_epuck.c $(FW_HAL_COMMON) $(wildcard platforms/epuck1/hal/*.h) \
  $(wildcard hal/*.h) $(wildcard wire/*/*.h) platforms/epuck1/tests/stubs/epuck_stubs.h

$(FW_HOST)/test_hal_epuck_randb: $(FW_HAL_DEPS) platforms/epuck1/hal/ircom_randb.c \
    platforms/epuck1/tests/stubs/adscan_stubs.c platforms/epuck1/tests/stubs/randb_stubs.c | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(CC) $(FW_HOST_CFLAGS) -o $@ platforms/epuck1/tests/test_hal_epuck.c $(FW_HAL_COMMON) \
	  platforms/epuck1/hal/ircom_randb.c platforms/epuck1/tests/stubs/adscan_stubs.c platforms/epuck1/tests/stubs/randb_stubs.c
$(FW_HOST)/test_hal_epuck_libircom: $(FW_HAL_DEPS) platforms/epuck1/hal/ircom_libircom.c \
    platforms/epuck1/tests/stubs/ircom_stubs.c | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(CC) $(FW_HOST_CFLAGS) -DTEST_LIBIRCOM -o $@ platforms/epuck1/tests/test_hal_epuck.c $(FW_HAL_COMMON) \
	  platforms/epuck1/hal/ircom_libircom.c platforms/epuck1/tests/stubs/ircom_stubs.c
# The host link (host_link.c) over the turret backend: it does not depend on
# the IR backend, so it is built once.
$(FW_HOST)/test_hal_epuck_host: platforms/epuck1/tests/test_hal_epuck_host.c $(filter-out platforms/epuck1/tests/test_hal_epuck.c,$(FW_HAL_DEPS)) \
    platforms/epuck1/hal/ircom_randb.c platforms/epuck1/tests/stubs/adscan_stubs.c platforms/epuck1/tests/stubs/randb_stubs.c | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(CC) $(FW_HOST_CFLAGS) -o $@ platforms/epuck1/tests/test_hal_epuck_host.c $(FW_HAL_COMMON) \
	  platforms/epuck1/hal/ircom_randb.c platforms/epuck1/tests/stubs/adscan_stubs.c platforms/epuck1/tests/stubs/randb_stubs.c

# The forager image itself (its main renamed) over the stubs: its telemetry
# frames decoded.  --gc-sections drops the generated publish functions
# (no liblcm here).
FW_APP_TEST_SRC := $(FW_SRC) \
  platforms/epuck1/hal/hal_epuck.c platforms/epuck1/hal/host_link.c platforms/epuck1/hal/ircom_randb.c platforms/epuck1/tests/stubs/epuck_lib_stubs.c \
  platforms/epuck1/tests/stubs/adscan_stubs.c platforms/epuck1/tests/stubs/randb_stubs.c firmware/apps/app_telemetry.c \
  $(FW_LCM_SRC)
$(FW_HOST)/test_app_telemetry: platforms/epuck1/tests/test_app_telemetry.c firmware/apps/forager_main.c \
    firmware/apps/app_telemetry.h firmware/apps/app_telemetry.c \
    $(filter-out $(FW_LCM_SRC),$(FW_APP_TEST_SRC)) $(FW_LCM_STAMP) $(wildcard firmware/*/*.h hal/*.h platforms/epuck1/hal/*.h) \
    platforms/epuck1/tests/stubs/epuck_stubs.h | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(CC) $(FW_HOST_CFLAGS) -I$(FW_LCM_C_DIR) $(LCM_CFLAGS) -ffunction-sections -Wl,--gc-sections \
	  -o $@ platforms/epuck1/tests/test_app_telemetry.c $(FW_APP_TEST_SRC) -lm

firmware-hal-tests: $(FW_HOST)/test_hal_epuck_randb $(FW_HOST)/test_hal_epuck_libircom $(FW_HOST)/test_hal_epuck_host \
    $(FW_HOST)/test_app_telemetry
	@set -e; for t in $^; do ASAN_OPTIONS=detect_leaks=1 $$t; done

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

# ------------------------------------------------ flashing
HEX ?=
DEVICE ?=
ROBOT_ID ?=
flash:
	@if [ -z "$(HEX)" ] || [ -z "$(DEVICE)" ]; then \
	  echo "usage: make flash HEX=build/firmware/xc16/forager.hex DEVICE=/dev/rfcomm0 [ROBOT_ID=N]" >&2; exit 2; fi
	$(PYTHON) -m swarmtools.flash.epuck $(HEX) $(DEVICE) $(if $(ROBOT_ID),--robot-id $(ROBOT_ID))

# ------------------------------------------------ XC16 build
XC16_DIR ?=
EPUCK_LIB_DIR ?=
RANDB_DIR ?=
IRCOM_DIR ?=
FIRMWARE_IMAGES ?= $(foreach s,$(FW_IMAGE_SPECS),$(firstword $(subst :, ,$(s))))
FORAGER_POLICY ?= drtm
FIRMWARE_N_ROBOTS ?= 20
FIRMWARE_ARENA_MM ?= 4000
# The experiment's other constants (seed 000's simulation values by default;
# README, seed 000, has its real-robot experiments' make lines).
FIRMWARE_F_D ?= 20
FIRMWARE_NEST_RADIUS_MM ?= 750
FIRMWARE_DRTM_THETA ?= offset
FIRMWARE_F0 ?= 5
FIRMWARE_CONSUMPTION_MILLI ?= 2000
FIRMWARE_MOVE_COST ?= 1
FIRMWARE_E_A ?= 10

# The library's own folder, whether EPUCK_LIB_DIR names it or its repository.
EPL := $(if $(wildcard $(EPUCK_LIB_DIR)/library/motor_led),$(EPUCK_LIB_DIR)/library,$(EPUCK_LIB_DIR))
XC16_BIN := $(XC16_DIR)/bin
XC16_CC := $(XC16_BIN)/xc16-gcc
FWX := $(FW_OUT)/xc16
XC16_ARCH := -mcpu=30F6014A -omf=elf -mlarge-code -mlarge-data
XC16_OURS := $(XC16_ARCH) -std=gnu99 -O1 -Wall -ffunction-sections -fdata-sections \
  -Ihal -Iwire -Ifirmware -Iplatforms/epuck1/hal -I$(FW_LCM_C_DIR) $(LCM_CFLAGS)
# The speaker (hal_speaker_set): the library's codec module WITHOUT its
# sound table codec/e_const_sound.s (five recorded voices, 19,044 words):
# e_play_sound plays only from the table named e_sound_sample, so the link
# names ours (hal/tone_tables.c's tone_speaker_table, in program memory:
# XC16 keeps const data there, read through PSV as the library does) by
# that name, and keeps it (-u) although only the library's assembly uses
# it.  Not tried with XC16 here [?]: if the alias fails, assemble the
# table into the library's e_const_sound.s instead (see
# docs/notes/i14_detector.md).
FW_EPL_CODEC := codec/e_sound.c codec/e_init_codec_slave.s codec/e_init_dci_master.s \
  codec/e_isr_dci.s codec/e_sub_dci_kickoff.s
FW_SOUND_LDFLAGS := -Wl,-u,_tone_speaker_table,--defsym=e_sound_sample=_tone_speaker_table
XC16_LIBFLAGS := $(XC16_ARCH) -O1 -ffunction-sections -fdata-sections -I$(EPL) -I$(EPL)/uart \
  -I$(EPL)/motor_led -I$(EPL)/motor_led/advance_one_timer -I$(EPL)/I2C \
  -I$(EPL)/a_d/advance_ad_scan -I$(EPL)/camera/fast_2_timer -I$(EPL)/utility
XC16_LDFLAGS := $(XC16_ARCH) -Wl,--heap=128,--stack=500,--gc-sections,--report-mem $(FW_SOUND_LDFLAGS)

FW_POLICY_DEF := TA_$(shell echo '$(FORAGER_POLICY)' | tr a-z A-Z)
FW_APP_DEFS := -DAPP_N_ROBOTS=$(FIRMWARE_N_ROBOTS)u -DAPP_ARENA_L_MM=$(FIRMWARE_ARENA_MM)u \
  -DAPP_FORAGER_POLICY=$(FW_POLICY_DEF) -DAPP_F_D_TOKENS=$(FIRMWARE_F_D) \
  -DAPP_NEST_RADIUS_MM=$(FIRMWARE_NEST_RADIUS_MM)u \
  -DAPP_DRTM_THETA=TA_THETA_$(shell echo '$(FIRMWARE_DRTM_THETA)' | tr a-z A-Z) \
  -DAPP_F0_TOKENS=$(FIRMWARE_F0) -DAPP_C_RATE_MILLI=$(FIRMWARE_CONSUMPTION_MILLI)u \
  -DAPP_MOVE_COST=$(FIRMWARE_MOVE_COST)u -DAPP_E_A=$(FIRMWARE_E_A)u

FW_OURS_SRC := $(filter-out $(FW_ROBOT_TELEMETRY_SRC),$(FW_SRC)) \
  platforms/epuck1/hal/hal_epuck.c platforms/epuck1/hal/host_link.c platforms/epuck1/hal/xc16/robot_id.c
FW_EPL_COMMON := motor_led/e_init_port.c motor_led/advance_one_timer/e_agenda.c \
  motor_led/advance_one_timer/e_motors.c motor_led/advance_one_timer/e_led.c \
  camera/fast_2_timer/e_common.c camera/fast_2_timer/e_calc_po3030k.c \
  camera/fast_2_timer/e_calc_po6030k.c camera/fast_2_timer/e_calc_po8030d.c \
  camera/fast_2_timer/e_po3030k_registers.c camera/fast_2_timer/e_po6030k_registers.c \
  camera/fast_2_timer/e_po8030d_registers.c camera/fast_2_timer/e_timers.c \
  camera/fast_2_timer/e_interrupt.s I2C/e_I2C_master_module.c I2C/e_I2C_protocol.c \
  uart/e_init_uart1.s uart/e_uart1_rx_char.s uart/e_uart1_tx_char.s utility/utility.c \
  $(FW_EPL_CODEC)
FW_EPL_ADSCAN := a_d/advance_ad_scan/e_ad_conv.c a_d/advance_ad_scan/e_prox.c \
  a_d/advance_ad_scan/e_micro.c a_d/advance_ad_scan/e_acc.c

fw_obj = $(FWX)/ours/$(basename $(1)).o
fw_epl_obj = $(FWX)/epl/$(basename $(1)).o
FW_OURS_OBJ := $(foreach s,$(FW_OURS_SRC),$(call fw_obj,$(s)))
FW_EPL_COMMON_OBJ := $(foreach s,$(FW_EPL_COMMON),$(call fw_epl_obj,$(s)))
FW_EPL_ADSCAN_OBJ := $(foreach s,$(FW_EPL_ADSCAN),$(call fw_epl_obj,$(s)))
FW_RANDB_OBJ := $(FWX)/randb/e_randb.o
FW_IRCOM_SRC := $(notdir $(wildcard $(IRCOM_DIR)/*.c))
FW_IRCOM_OBJ := $(patsubst %.c,$(FWX)/ircom/%.o,$(FW_IRCOM_SRC))

FW_BACKEND_OBJ_randb := $(call fw_obj,platforms/epuck1/hal/ircom_randb.c) $(FW_EPL_ADSCAN_OBJ) $(FW_RANDB_OBJ)
FW_BACKEND_OBJ_libircom := $(call fw_obj,platforms/epuck1/hal/ircom_libircom.c) $(FW_IRCOM_OBJ)
fw_backend = $(patsubst $(1):%,%,$(filter $(1):%,$(FW_IMAGE_SPECS)))
FW_HEX := $(patsubst %,$(FWX)/%.hex,$(FIRMWARE_IMAGES))
# lcm-gen's C, for the images that send telemetry (robot_state_t and
# schema_t: no double, which is 32-bit under XC16).
FW_LCM_OBJ := $(FWX)/lcm/swarmlcm_robot_state_t.o $(FWX)/lcm/swarmlcm_schema_t.o
fw_lcm_objs = $(if $(filter $(1),$(FW_TELEMETRY_IMAGES)),$(FW_LCM_OBJ) \
  $(call fw_obj,$(FW_ROBOT_TELEMETRY_SRC)) $(call fw_obj,firmware/apps/app_telemetry.c))

$(FWX)/ours/%.o: %.c | $(FW_LCM_STAMP)
	@mkdir -p $(@D)
	$(XC16_CC) $(XC16_OURS) $(if $(findstring apps/,$<),$(FW_APP_DEFS)) -c $< -o $@
$(FWX)/epl/%.o: $(EPL)/%.c
	@mkdir -p $(@D)
	$(XC16_CC) $(XC16_LIBFLAGS) -c $< -o $@
$(FWX)/epl/%.o: $(EPL)/%.s
	@mkdir -p $(@D)
	$(XC16_CC) $(XC16_LIBFLAGS) -Wa,-I$(dir $<) -c $< -o $@
$(FWX)/lcm/%.o: $(FW_LCM_C_DIR)/%.c $(FW_LCM_STAMP)
	@mkdir -p $(@D)
	$(XC16_CC) $(XC16_OURS) -c $< -o $@
$(FWX)/randb/%.o: $(RANDB_DIR)/%.c
	@mkdir -p $(@D)
	$(XC16_CC) $(XC16_LIBFLAGS) -I$(RANDB_DIR) -c $< -o $@
$(FWX)/ircom/%.o: $(IRCOM_DIR)/%.c
	@mkdir -p $(@D)
	$(XC16_CC) $(XC16_LIBFLAGS) -I$(IRCOM_DIR) -c $< -o $@

# One image: its app, our code, the common library modules, its backend.
define FW_IMAGE_RULES
$(FWX)/$(1).elf: $(call fw_obj,firmware/apps/$(1)_main.c) $(FW_OURS_OBJ) $(FW_EPL_COMMON_OBJ) \
    $$(FW_BACKEND_OBJ_$(call fw_backend,$(1))) $(call fw_lcm_objs,$(1))
	$$(XC16_CC) $$(XC16_LDFLAGS) -Wl,-Map=$(FWX)/$(1).map -o $$@ $$^
$(FWX)/$(1).hex: $(FWX)/$(1).elf
	$$(XC16_BIN)/xc16-bin2hex $$< -a -omf=elf
	@echo "firmware: $$@ (flash it: make flash HEX=$$@ DEVICE=/dev/rfcommN ROBOT_ID=N)"
endef
$(foreach s,$(FW_IMAGE_SPECS),$(eval $(call FW_IMAGE_RULES,$(firstword $(subst :, ,$(s))))))

# The asked images by IR backend.
fw_images_with = $(foreach i,$(FIRMWARE_IMAGES),$(if $(filter $(i):$(1),$(FW_IMAGE_SPECS)),$(i)))
FW_RANDB_IMAGES = $(call fw_images_with,randb)
FW_IRCOM_IMAGES = $(call fw_images_with,libircom)

# Says exactly what is missing, then builds what was asked.
firmware:
	@missing=0; say() { echo "firmware: $$*" >&2; missing=1; }; \
	if [ -z "$(XC16_DIR)" ]; then \
	  say "XC16_DIR is not set: install Microchip XC16 (a free download from microchip.com, not in any package registry) and run make firmware XC16_DIR=/opt/microchip/xc16/vX.YY ..."; \
	elif [ ! -x "$(XC16_CC)" ]; then say "$(XC16_CC) not found: XC16_DIR must be the XC16 install folder (with bin/xc16-gcc)"; \
	elif [ ! -x "$(XC16_BIN)/xc16-bin2hex" ]; then say "$(XC16_BIN)/xc16-bin2hex not found in the XC16 install"; fi; \
	if [ -z "$(EPUCK_LIB_DIR)" ]; then \
	  say "EPUCK_LIB_DIR is not set: get GCtronic's e-puck library (the e-puck-library repository on GitHub, folder library/) and pass EPUCK_LIB_DIR=/path/to/e-puck-library"; \
	else for f in $(FW_EPL_COMMON) $(if $(FW_RANDB_IMAGES),$(FW_EPL_ADSCAN)); do \
	  [ -f "$(EPL)/$$f" ] || say "EPUCK_LIB_DIR: $(EPL)/$$f not found (is EPUCK_LIB_DIR the e-puck library?)"; done; fi; \
	for i in $(FIRMWARE_IMAGES); do case " $(FW_IMAGE_SPECS) " in *" $$i:"*) ;; *) say "unknown image '$$i' (images: $(FW_IMAGE_SPECS))";; esac; done; \
	if [ -n "$(FW_RANDB_IMAGES)" ]; then \
	  if [ -z "$(RANDB_DIR)" ]; then say "RANDB_DIR is not set: $(FW_RANDB_IMAGES) need the e-RandB range-and-bearing turret's e-puck driver (e_randb.c, e_randb.h) from the turret's distribution; or leave them out of FIRMWARE_IMAGES"; \
	  elif [ ! -f "$(RANDB_DIR)/e_randb.c" ]; then say "$(RANDB_DIR)/e_randb.c not found"; fi; fi; \
	if [ -n "$(FW_IRCOM_IMAGES)" ]; then \
	  if [ -z "$(IRCOM_DIR)" ]; then say "IRCOM_DIR is not set: $(FW_IRCOM_IMAGES) need libIrcom's sources (ircom.c, ircomSend.c, ..., its e_ad_conv.c); or leave them out of FIRMWARE_IMAGES"; \
	  elif [ ! -f "$(IRCOM_DIR)/ircom.c" ]; then say "$(IRCOM_DIR)/ircom.c not found (is IRCOM_DIR libIrcom's source folder?)"; fi; fi; \
	case " $(FW_POLICIES) " in *" $(FORAGER_POLICY) "*) ;; *) say "FORAGER_POLICY must be one of: $(FW_POLICIES)";; esac; \
	if [ $$missing != 0 ]; then echo "firmware: nothing built (make firmware-check runs the portable gates without XC16)" >&2; exit 1; fi
	@$(MAKE) --no-print-directory $(FW_HEX)
