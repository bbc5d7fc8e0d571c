# The code version swarmsim writes into every summary (its provenance):
# tools/make/code_version.sh: `git describe --always --dirty` of the
# checkout and, when it is dirty, the diff's hash; "unknown" outside git.
# Looked up on every build; the header is replaced only when the text
# changes, so only main.c recompiles, and only then.
VERSION_H := $(BUILD)/gen/version.h

.PHONY: version-header
version-header:
	@mkdir -p $(dir $(VERSION_H))
	@v=$$(bash tools/make/code_version.sh); \
	 t=$(VERSION_H).tmp.$$$$; printf '#define SWARMSIM_VERSION "%s"\n' "$$v" > $$t; \
	 if cmp -s $$t $(VERSION_H); then rm -f $$t; else mv $$t $(VERSION_H); fi
$(VERSION_H): version-header ;

$(BUILD)/obj/sim_host/main.o: $(VERSION_H)
$(BUILD)/obj/sim_host/main.o: SIM_CFLAGS += -I$(BUILD)/gen
