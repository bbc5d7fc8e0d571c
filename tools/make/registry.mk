# The simulator's registry lists, generated from the sources by
# tools/make/registry.sh: a controller's or a task's own files register it.
# The script runs on every build and replaces the header only when its text
# changes, so a description added, renamed or removed is seen at once and
# nothing rebuilds otherwise.
REGISTRY_LIST := $(BUILD)/gen/registry_list.h

.PHONY: registry-list
registry-list:
	@mkdir -p $(dir $(REGISTRY_LIST))
	@bash tools/make/registry.sh $(REGISTRY_LIST)
$(REGISTRY_LIST): registry-list ;

$(BUILD)/obj/sim_host/registry.o $(BUILD)/asan/sim_host/registry.o: $(REGISTRY_LIST)
$(BUILD)/obj/sim_host/registry.o $(BUILD)/asan/sim_host/registry.o: SIM_CFLAGS += -I$(BUILD)/gen
