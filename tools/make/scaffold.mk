# scaffold.mk - a new controller or task from the tutorials' examples
# (tools/scaffold.py), built and run at once:
#
#   make new-controller NAME=foo   firmware/foo/ and sim_host/scenarios/foo.yaml
#   make new-task NAME=bar         sim_host/tasks/bar/ and sim_host/scenarios/bar.yaml
#   make scaffold-tests            both in a copy of the tree, compiled, linked and run (part of make test)

.PHONY: new-controller new-task scaffold-tests
new-controller new-task: deps
	@if [ -z "$(NAME)" ]; then echo "make $@: name it: make $@ NAME=foo" >&2; exit 2; fi
	@set -o pipefail; $(PYTHON) tools/scaffold.py $(patsubst new-%,%,$@) $(NAME) | sed "s/^/  NEW     /"
	@$(MAKE) --no-print-directory $(BUILD)/swarmsim
	$(BUILD)/swarmsim sim_host/scenarios/$(NAME).yaml --out out/$(NAME) --replace --frames 100
	@echo "make $@: edit the files above, then: make run RUN_SCENARIO=sim_host/scenarios/$(NAME).yaml RUN_OUT=out/$(NAME)"

scaffold-tests: $(BUILD)/swarmsim
	@CC='$(CC)' FW_CFLAGS='$(FW_CFLAGS)' SIM_CFLAGS='$(SIM_CFLAGS) -I$(BUILD)/lcm_c' LDLIBS='$(LDLIBS_SIM)' \
	  BUILD='$(BUILD)' PYTHON='$(PYTHON)' bash tests/scaffold/scaffold.sh

EXTRA_TESTS += scaffold-tests
