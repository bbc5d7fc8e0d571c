# lcm.mk - LCM telemetry: message types (lcm_types/*.lcm) generated into C,
# Python and (with a JDK) a Java jar for lcm-spy; the simulator's publisher
# (sim_host/core/telemetry.c) linked against the wheel's liblcm.  The Python
# tools are the swarmtools package (python.mk).
#
#   make lcm-types     build/lcm_c/, build/lcm_python/, build/lcm_types.jar
#   make spy           lcm-spy with our types  (LCM_URL=udpm://... to choose the bus)
#   make monitor       the terminal dashboard   (LCM_URL as for spy)
#
# Generated code lives in build/ only.

LCM_BIN := $(dir $(LCM_GEN))
LCM_SPY := $(LCM_BIN)lcm-spy
LCM_JAR := $(abspath $(LCM_BIN)../share/java/lcm.jar)
LCM_TYPES := $(sort $(wildcard lcm_types/*.lcm))
LCM_C_DIR := $(BUILD)/lcm_c
LCM_PY_DIR := $(BUILD)/lcm_python
LCM_JAVA_DIR := $(BUILD)/lcm_java
LCM_TYPES_JAR := $(BUILD)/lcm_types.jar
LCM_C_SRC := $(patsubst lcm_types/%.lcm,$(LCM_C_DIR)/swarmlcm_%.c,$(LCM_TYPES))
LCM_C_STAMP := $(LCM_C_DIR)/.stamp
LCM_PY_STAMP := $(LCM_PY_DIR)/.stamp
JAVAC := $(shell command -v javac 2>/dev/null)
JAR := $(shell command -v jar 2>/dev/null)
LCM_URL ?=

# The wheel's static liblcm.a needs GLib (g_* symbols: `nm` it).  A system
# LCM found by pkg-config brings it in LCM_LIBS; otherwise link the GLib the
# wheel's own binaries use (its -dev package may be absent: name the
# runtime library).
ifeq ($(findstring glib,$(LCM_LIBS)),)
LCM_GLIB := $(shell pkg-config --libs glib-2.0 2>/dev/null || echo -l:libglib-2.0.so.0)
endif
LDLIBS_SIM += $(LCM_LIBS) $(LCM_GLIB) -lpthread
SIM_CFLAGS += $(LCM_CFLAGS) -I$(LCM_C_DIR)
# The robot's own telemetry (firmware/telemetry/robot_telemetry.c) encodes
# with the generated C: firmware sees its headers too.
FW_CFLAGS += $(LCM_CFLAGS) -I$(LCM_C_DIR)

# Generated C code: compiled without our -Werror (lcm-gen's style is its own).
LCM_GEN_CFLAGS := -std=c11 -g -O2 -fno-strict-aliasing $(LCM_CFLAGS) -I$(LCM_C_DIR)
LCM_OBJ := $(patsubst $(LCM_C_DIR)/%.c,$(BUILD)/obj/lcm/%.o,$(LCM_C_SRC))
LCM_OBJ_ASAN := $(patsubst $(LCM_C_DIR)/%.c,$(BUILD)/asan/lcm/%.o,$(LCM_C_SRC))
SIM_EXTRA_OBJ += $(LCM_OBJ)
SIM_EXTRA_OBJ_ASAN += $(LCM_OBJ_ASAN)

$(LCM_C_STAMP): $(LCM_TYPES) | $(BUILD)/config.mk
	@rm -rf $(LCM_C_DIR) && mkdir -p $(LCM_C_DIR)
	$(call show,LCM-GEN,C types into $(LCM_C_DIR))$(LCM_GEN) --c --c-cpath $(LCM_C_DIR) --c-hpath $(LCM_C_DIR) $(LCM_TYPES)
	@touch $@
$(LCM_C_SRC): $(LCM_C_STAMP) ;
$(BUILD)/obj/lcm/%.o: $(LCM_C_DIR)/%.c $(LCM_C_STAMP)
	@mkdir -p $(@D)
	$(call show,CC,$<)$(CC) $(LCM_GEN_CFLAGS) -c $< -o $@
$(BUILD)/asan/lcm/%.o: $(LCM_C_DIR)/%.c $(LCM_C_STAMP)
	@mkdir -p $(@D)
	$(call show,CC-ASAN,$<)$(CC) $(LCM_GEN_CFLAGS) $(ASAN) -c $< -o $@

# Sources that include generated headers wait for them.
$(BUILD)/obj/sim_host/core/telemetry.o $(BUILD)/asan/sim_host/core/telemetry.o: $(LCM_C_STAMP)
$(BUILD)/obj/sim_host/core/telemetry_scene.o $(BUILD)/asan/sim_host/core/telemetry_scene.o: $(LCM_C_STAMP)
$(BUILD)/obj/firmware/telemetry/robot_telemetry.o $(BUILD)/asan/firmware/telemetry/robot_telemetry.o: $(LCM_C_STAMP)
$(patsubst tests/%.c,$(BUILD)/tests/%,$(wildcard tests/test_telemetry*.c tests/test_robot_link.c)): $(LCM_C_STAMP)
$(patsubst tests/%.c,$(BUILD)/tests/asan/%,$(wildcard tests/test_telemetry*.c tests/test_robot_link.c)): $(LCM_C_STAMP)

# Python modules (package swarmlcm) for the tools.
$(LCM_PY_STAMP): $(LCM_TYPES) | $(BUILD)/config.mk
	@rm -rf $(LCM_PY_DIR) && mkdir -p $(LCM_PY_DIR)
	$(call show,LCM-GEN,Python types into $(LCM_PY_DIR))$(LCM_GEN) --python --ppath $(LCM_PY_DIR) $(LCM_TYPES)
	@touch $@

# Java classes for lcm-spy, when a JDK is present.
$(LCM_TYPES_JAR): $(LCM_TYPES) | $(BUILD)/config.mk
	@rm -rf $(LCM_JAVA_DIR) && mkdir -p $(LCM_JAVA_DIR)/src $(LCM_JAVA_DIR)/classes
	$(call show,LCM-GEN,Java types for lcm-spy)$(LCM_GEN) --java --jpath $(LCM_JAVA_DIR)/src $(LCM_TYPES)
	$(call show,JAVAC,$(LCM_JAVA_DIR))$(JAVAC) -nowarn -encoding UTF-8 -cp $(LCM_JAR) -d $(LCM_JAVA_DIR)/classes $(LCM_JAVA_DIR)/src/swarmlcm/*.java
	$(call show,JAR,$@)$(JAR) cf $@ -C $(LCM_JAVA_DIR)/classes .

LCM_TYPE_OUTPUTS := $(LCM_C_STAMP) $(LCM_PY_STAMP) $(if $(and $(JAVAC),$(JAR)),$(LCM_TYPES_JAR))

.PHONY: lcm-types spy monitor
lcm-types: $(LCM_TYPE_OUTPUTS)
all: $(LCM_TYPE_OUTPUTS)

# lcm-spy is a Swing window: without a display Java stops with a stack
# trace after building the jar, so the display is checked first (listed
# first, it is made first).  Only an unset DISPLAY is refused: whether a
# set one answers is Java's to find out (X servers differ in where they listen).
.PHONY: spy-display
spy-display:
	@if [ -z "$$DISPLAY" ]; then echo "make spy: lcm-spy opens a window and needs a display, but DISPLAY is not set: run it on a desktop, through ssh -X, or under a virtual display (xvfb-run make spy ...); make monitor shows the bus in a terminal" >&2; exit 1; fi

ifneq ($(and $(JAVAC),$(JAR)),)
spy: spy-display $(LCM_TYPES_JAR)
	CLASSPATH=$(abspath $(LCM_TYPES_JAR)) $(LCM_SPY) $(if $(LCM_URL),--lcm-url='$(LCM_URL)')
else
spy: spy-display
	@echo "make spy: lcm-spy needs a JDK (javac and jar) to build $(LCM_TYPES_JAR); install one (e.g. openjdk-17-jdk-headless)"; exit 1
endif

monitor: deps
	$(PYTHON) -m swarmtools.telemetry.monitor $(if $(LCM_URL),--lcm '$(LCM_URL)')

# The robots' framing (wire/telemetry/telemetry_frame.c, and the robot's
# decoder of a host's frames, telemetry_rx.c and telemetry_host.c) as a
# shared library, so the Python tests check the bridge's decoder against the
# very encoder the robots run, and the host's frames against their decoder.
TELEMETRY_FRAME_SO := $(BUILD)/telemetry/libtelemetry_frame.so
TELEMETRY_SO_SRC := wire/telemetry/telemetry_frame.c wire/telemetry/telemetry_rx.c \
  wire/telemetry/telemetry_host.c
$(TELEMETRY_FRAME_SO): $(TELEMETRY_SO_SRC) $(TELEMETRY_SO_SRC:.c=.h) | $(BUILD)/config.mk
	@mkdir -p $(@D)
	$(call show,CC,$@)$(CC) $(FW_CFLAGS) -fPIC -shared -o $@ $(TELEMETRY_SO_SRC)

.PHONY: clean-lcm
clean: clean-lcm
clean-lcm:
	rm -rf $(LCM_C_DIR) $(LCM_PY_DIR) $(LCM_JAVA_DIR) $(LCM_TYPES_JAR) $(BUILD)/telemetry
