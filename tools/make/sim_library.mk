# sim_library.mk - the simulator as a shared library, build/libswarmsim.so:
# libswarm.a's objects (less one, below) and the code version (sim_host/version.c),
# for the Python binding (tools/swarmtools/sim/: swarmtools.Sim and
# swarmtools.run, in process) and for any program that loads the public
# API (sim_host/include/swarmsim/) at run time.  Built by `make` (all).
#
# The plain objects (build/obj/) are compiled position-independent, so the
# library, libswarm.a and swarmsim are made of the very same objects (the
# Python API's state hashes are the command line's).
# -fno-semantic-interposition keeps the calls inside the library as direct
# as a program's.  Objects compiled before this rule rebuild once (the
# stamp is newer).
SIM_SO := $(BUILD)/libswarmsim.so
PIC_STAMP := $(BUILD)/obj/.pic
PIC_FLAGS := -fPIC -fno-semantic-interposition

$(BUILD)/obj/%.o: FW_CFLAGS += $(PIC_FLAGS)
$(BUILD)/obj/%.o: SIM_CFLAGS += $(PIC_FLAGS)
$(BUILD)/obj/%.o: LCM_GEN_CFLAGS += $(PIC_FLAGS)
$(FW_OBJ) $(SIM_OBJ) $(LCM_OBJ) $(BUILD)/obj/sim_host/main.o $(BUILD)/obj/sim_host/version.o: $(PIC_STAMP)
$(PIC_STAMP):
	@mkdir -p $(@D) && touch $@

# version.mk, read after this file, makes the header (its VERSION_H is not set yet here).
$(BUILD)/obj/sim_host/version.o: $(BUILD)/gen/version.h
$(BUILD)/obj/sim_host/version.o: SIM_CFLAGS += -I$(BUILD)/gen

# libswarm.a's objects, less the robot's end of the PIL protocol
# (wire/pil/pil_robot.c), which calls its platform's pil_port_exchange and is
# never part of a simulator (swarmsim, linking the archive, never pulls it in).
SIM_SO_OBJ = $(filter-out $(BUILD)/obj/wire/pil/pil_robot.o,$(FW_OBJ)) $(SIM_OBJ) $(SIM_EXTRA_OBJ)
$(SIM_SO): $(BUILD)/libswarm.a $(BUILD)/obj/sim_host/version.o
	$(call show,LD,$@)$(CC) -shared -Wl,--no-undefined -Wl,-Bsymbolic -o $@.tmp $(BUILD)/obj/sim_host/version.o \
	  $(SIM_SO_OBJ) $(LDLIBS_SIM) && mv $@.tmp $@

all: $(SIM_SO)
python-tests-deps: $(SIM_SO)
