# platforms/epuck1/platform.mk - the e-puck1 (dsPIC30F6014A over GCtronic's
# e-puck library): its images' mains, their portable gates, the host tests
# of its HAL, flashing, and the XC16 build of .hex files.  Included by
# tools/make/firmware.mk for the line `epuck1` of platforms/platforms.list.
#
#   make epuck1-gates     every image of images.list, generated from its
#                         declaration, compiles warning-free and links
#                         (against stubs of the e-puck library) with avr-gcc
#                         (XC16's data model) and arm-none-eabi-gcc
#                         (Cortex-M4F); footprint table (build/firmware/
#                         epuck1/footprint.md, and docs/hardware/footprint.md's) and the 2 KB
#                         static RAM gate (tests/firmware/image_gates.py,
#                         described by platform.py)
#   make epuck1-tests     host tests of the HAL (both IR backends, the host
#                         link) and the forager image run against the stubs,
#                         its telemetry frames decoded; the flasher's tests
#   make readme-footprint docs/hardware/footprint.md's table from the gates' measurement
#   make firmware         .hex files with Microchip XC16 and the user's copy of
#                         GCtronic's e-puck library (never in this repository):
#                           XC16_DIR       XC16 install (bin/xc16-gcc)
#                           EPUCK_LIB_DIR  the e-puck library (its library/ folder
#                                          or the repository holding it)
#                           RANDB_DIR      e-RandB turret driver (e_randb.c), for
#                                          the images on the turret (ir randb)
#                           IRCOM_DIR      libIrcom sources, for the images on
#                                          libIrcom (ir libircom)
#                         FIRMWARE_IMAGES (every image of images.list), and the
#                         build-time constants of tools/make/firmware.mk.
#   make flash HEX=build/firmware/xc16/forager.hex DEVICE=/dev/rfcomm0 ROBOT_ID=7
EPUCK1 := platforms/epuck1
EPUCK1_STUBS := $(EPUCK1)/tests/stubs
# Images: NAME:IR:TELEMETRY, from the declarations (read when used: only the
# XC16 build needs them at parse time).
EPUCK1_IMAGES = $(call fw_images,epuck1,ir telemetry)
EPUCK1_GEN := $(FW_GEN)/epuck1
# The run loop and the HAL: the include folders of this platform.
EPUCK1_INC := -I$(EPUCK1)/hal -I$(EPUCK1)/run

.PHONY: epuck1-images epuck1-gates epuck1-tests epuck1-hal-tests firmware-flash-tests \
        readme-footprint firmware flash
FW_IMAGE_TARGETS += epuck1-images
FW_GATES += epuck1-gates
PLATFORM_CHECKS += epuck1-gates epuck1-tests

# The mains, rewritten only when their text changes.
epuck1-images:
	@$(call fw_generate,epuck1)
$(EPUCK1_GEN)/%_main.c: epuck1-images ;

EPUCK1_GATE_ARGS = --platform $(EPUCK1) --gen $(EPUCK1_GEN) --build $(FW_OUT)/epuck1 \
  --lcm-c-dir $(FW_LCM_C_DIR) --lcm-cflags '$(LCM_CFLAGS)'
epuck1-gates: lcm-types epuck1-images | $(BUILD)/config.mk
	@$(PYTHON) tests/firmware/image_gates.py $(EPUCK1_GATE_ARGS)

# The documentation's footprint table, written from the gates' measurement (which
# fails while the page's differs from it).  The gates run first; their
# failure on that difference is the reason to run this, so it is ignored.
readme-footprint: lcm-types epuck1-images | $(BUILD)/config.mk
	@$(PYTHON) tests/firmware/image_gates.py $(EPUCK1_GATE_ARGS) > /dev/null || true
	@$(PYTHON) tests/firmware/readme_footprint.py --update --table $(FW_OUT)/epuck1/footprint_readme.md

epuck1-tests: epuck1-hal-tests firmware-flash-tests

firmware-flash-tests: deps
	@$(PYTHON) tools/tests/flash/test_epuck.py

# ------------------------------------------------ host tests of the HAL
FW_HOST_CFLAGS := -std=c99 -pedantic -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes \
  -Wmissing-prototypes -g -O1 -Ihal -Iwire -Ifirmware $(EPUCK1_INC) -I$(EPUCK1_STUBS) \
  -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
EPUCK1_HAL_COMMON := $(EPUCK1)/hal/hal_epuck.c $(EPUCK1)/hal/host_link.c hal/blob_detect.c hal/hal_common.c \
  hal/units.c hal/tone_detect.c hal/tone_tables.c $(EPUCK1_STUBS)/epuck_lib_stubs.c \
  wire/telemetry/telemetry_rx.c wire/telemetry/telemetry_host.c wire/telemetry/telemetry_frame.c
EPUCK1_RANDB := $(EPUCK1)/hal/ircom_randb.c $(EPUCK1_STUBS)/adscan_stubs.c $(EPUCK1_STUBS)/randb_stubs.c
EPUCK1_LIBIRCOM := $(EPUCK1)/hal/ircom_libircom.c $(EPUCK1_STUBS)/ircom_stubs.c
EPUCK1_HAL_DEPS := $(EPUCK1_HAL_COMMON) $(wildcard $(EPUCK1)/hal/*.h) $(wildcard hal/*.h) $(wildcard wire/*/*.h) \
  $(EPUCK1_STUBS)/epuck_stubs.h

$(FW_HOST)/test_hal_epuck_randb: $(EPUCK1)/tests/test_hal_epuck.c $(EPUCK1_HAL_DEPS) $(EPUCK1_RANDB) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(CC) $(FW_HOST_CFLAGS) -o $@ $(EPUCK1)/tests/test_hal_epuck.c $(EPUCK1_HAL_COMMON) $(EPUCK1_RANDB)
$(FW_HOST)/test_hal_epuck_libircom: $(EPUCK1)/tests/test_hal_epuck.c $(EPUCK1_HAL_DEPS) $(EPUCK1_LIBIRCOM) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(CC) $(FW_HOST_CFLAGS) -DTEST_LIBIRCOM -o $@ $(EPUCK1)/tests/test_hal_epuck.c $(EPUCK1_HAL_COMMON) $(EPUCK1_LIBIRCOM)
# The host link (host_link.c) over the turret backend: it does not depend on
# the IR backend, so it is built once.
$(FW_HOST)/test_hal_epuck_host: $(EPUCK1)/tests/test_hal_epuck_host.c $(EPUCK1_HAL_DEPS) $(EPUCK1_RANDB) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(CC) $(FW_HOST_CFLAGS) -o $@ $(EPUCK1)/tests/test_hal_epuck_host.c $(EPUCK1_HAL_COMMON) $(EPUCK1_RANDB)

# The forager image itself, its generated main (main renamed) over the
# stubs: its telemetry frames decoded.  --gc-sections drops the generated
# publish functions (no liblcm here).
EPUCK1_IMAGE_TEST_SRC := $(FW_SRC) $(EPUCK1)/hal/hal_epuck.c $(EPUCK1)/hal/host_link.c $(EPUCK1_RANDB) \
  $(EPUCK1_STUBS)/epuck_lib_stubs.c $(EPUCK1)/run/image_telemetry.c $(FW_LCM_SRC)
$(FW_HOST)/test_image_telemetry: $(EPUCK1)/tests/test_image_telemetry.c $(EPUCK1_GEN)/forager_main.c \
    $(wildcard $(EPUCK1)/run/*.h) $(filter-out $(FW_LCM_SRC),$(EPUCK1_IMAGE_TEST_SRC)) $(FW_LCM_STAMP) \
    $(wildcard firmware/*/*.h hal/*.h wire/*/*.h $(EPUCK1)/hal/*.h) $(EPUCK1_STUBS)/epuck_stubs.h | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(CC) $(FW_HOST_CFLAGS) -I$(EPUCK1_GEN) -I$(FW_LCM_C_DIR) $(LCM_CFLAGS) -ffunction-sections -Wl,--gc-sections \
	  -o $@ $(EPUCK1)/tests/test_image_telemetry.c $(EPUCK1_IMAGE_TEST_SRC) -lm

epuck1-hal-tests: $(FW_HOST)/test_hal_epuck_randb $(FW_HOST)/test_hal_epuck_libircom $(FW_HOST)/test_hal_epuck_host \
    $(FW_HOST)/test_image_telemetry
	@set -e; for t in $^; do ASAN_OPTIONS=detect_leaks=1 $$t; done

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
FIRMWARE_IMAGES ?= $(foreach r,$(EPUCK1_IMAGES),$(call fw_field,$(r),1))

# The library's own folder, whether EPUCK_LIB_DIR names it or its repository.
EPL := $(if $(wildcard $(EPUCK_LIB_DIR)/library/motor_led),$(EPUCK_LIB_DIR)/library,$(EPUCK_LIB_DIR))
XC16_BIN := $(XC16_DIR)/bin
XC16_CC := $(XC16_BIN)/xc16-gcc
FWX := $(FW_OUT)/xc16
XC16_ARCH := -mcpu=30F6014A -omf=elf -mlarge-code -mlarge-data
XC16_OURS := $(XC16_ARCH) -std=gnu99 -O1 -Wall -ffunction-sections -fdata-sections \
  -Ihal -Iwire -Ifirmware $(EPUCK1_INC) -I$(FW_LCM_C_DIR) $(LCM_CFLAGS)
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

FW_OURS_SRC := $(filter-out $(FW_ROBOT_TELEMETRY_SRC),$(FW_SRC)) \
  $(EPUCK1)/hal/hal_epuck.c $(EPUCK1)/hal/host_link.c $(EPUCK1)/hal/xc16/robot_id.c
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

FW_BACKEND_OBJ_randb := $(call fw_obj,$(EPUCK1)/hal/ircom_randb.c) $(FW_EPL_ADSCAN_OBJ) $(FW_RANDB_OBJ)
FW_BACKEND_OBJ_libircom := $(call fw_obj,$(EPUCK1)/hal/ircom_libircom.c) $(FW_IRCOM_OBJ)
epuck1_row = $(filter $(1):%,$(EPUCK1_IMAGES))
fw_backend = $(call fw_field,$(call epuck1_row,$(1)),2)
FW_HEX := $(patsubst %,$(FWX)/%.hex,$(FIRMWARE_IMAGES))
# lcm-gen's C, for the images that send telemetry (robot_state_t and
# schema_t: no double, which is 32-bit under XC16).
FW_LCM_OBJ := $(FWX)/lcm/swarmlcm_robot_state_t.o $(FWX)/lcm/swarmlcm_schema_t.o
fw_lcm_objs = $(if $(filter yes,$(call fw_field,$(call epuck1_row,$(1)),3)),$(FW_LCM_OBJ) \
  $(call fw_obj,$(FW_ROBOT_TELEMETRY_SRC)) $(call fw_obj,$(EPUCK1)/run/image_telemetry.c))

$(FWX)/ours/%.o: %.c | $(FW_LCM_STAMP)
	@mkdir -p $(@D)
	$(XC16_CC) $(XC16_OURS) -c $< -o $@
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

# One image: its generated main, our code, the common library modules, its
# backend.  Defined for the goals that build .hex files (make firmware runs
# them in a sub-make), so other goals do not read the declarations.
ifneq ($(filter firmware $(FWX)/%,$(MAKECMDGOALS)),)
EPUCK1_IMAGES := $(EPUCK1_IMAGES)
define FW_IMAGE_RULES
$(FWX)/$(1).elf: $(call fw_obj,$(EPUCK1_GEN)/$(1)_main.c) $(FW_OURS_OBJ) $(FW_EPL_COMMON_OBJ) \
    $$(FW_BACKEND_OBJ_$(call fw_backend,$(1))) $(call fw_lcm_objs,$(1))
	$$(XC16_CC) $$(XC16_LDFLAGS) -Wl,-Map=$(FWX)/$(1).map -o $$@ $$^
$(FWX)/$(1).hex: $(FWX)/$(1).elf
	$$(XC16_BIN)/xc16-bin2hex $$< -a -omf=elf
	@echo "firmware: $$@ (flash it: make flash HEX=$$@ DEVICE=/dev/rfcommN ROBOT_ID=N)"
endef
$(foreach r,$(EPUCK1_IMAGES),$(eval $(call FW_IMAGE_RULES,$(call fw_field,$(r),1))))
endif

# The asked images by IR backend.
fw_images_with = $(foreach i,$(FIRMWARE_IMAGES),$(if $(filter $(i):$(1):%,$(EPUCK1_IMAGES)),$(i)))
FW_RANDB_IMAGES = $(strip $(call fw_images_with,randb))
FW_IRCOM_IMAGES = $(strip $(call fw_images_with,libircom))

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
	for i in $(FIRMWARE_IMAGES); do case " $(EPUCK1_IMAGES) " in *" $$i:"*) ;; *) say "unknown image '$$i' (images of $(EPUCK1)/images.list: $(foreach r,$(EPUCK1_IMAGES),$(call fw_field,$(r),1)))";; esac; done; \
	if [ -n "$(FW_RANDB_IMAGES)" ]; then \
	  if [ -z "$(RANDB_DIR)" ]; then say "RANDB_DIR is not set: $(FW_RANDB_IMAGES) need the e-RandB range-and-bearing turret's e-puck driver (e_randb.c, e_randb.h) from the turret's distribution; or leave them out of FIRMWARE_IMAGES"; \
	  elif [ ! -f "$(RANDB_DIR)/e_randb.c" ]; then say "$(RANDB_DIR)/e_randb.c not found"; fi; fi; \
	if [ -n "$(FW_IRCOM_IMAGES)" ]; then \
	  if [ -z "$(IRCOM_DIR)" ]; then say "IRCOM_DIR is not set: $(FW_IRCOM_IMAGES) need libIrcom's sources (ircom.c, ircomSend.c, ..., its e_ad_conv.c); or leave them out of FIRMWARE_IMAGES"; \
	  elif [ ! -f "$(IRCOM_DIR)/ircom.c" ]; then say "$(IRCOM_DIR)/ircom.c not found (is IRCOM_DIR libIrcom's source folder?)"; fi; fi; \
	case " $(FW_POLICIES) " in *" $(FORAGER_POLICY) "*) ;; *) say "FORAGER_POLICY must be one of: $(FW_POLICIES)";; esac; \
	if [ $$missing != 0 ]; then echo "firmware: nothing built (make firmware-check runs the portable gates without XC16)" >&2; exit 1; fi
	@$(MAKE) --no-print-directory epuck1-images
	@$(MAKE) --no-print-directory $(FW_HEX)
