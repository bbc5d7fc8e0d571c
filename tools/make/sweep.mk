# sweep.mk - the sweep engine (swarmtools.sweep): `make sweep SWEEP=file.yaml`
# runs a sweep file (SWEEP_ARGS: --backend slurm, --out, --jobs, ...);
# `make slurm-tests` (part of make test) runs the slurm backend on a real
# single-node SLURM it starts and stops (tools/slurm/local_cluster.sh),
# installing SLURM's Debian packages first when run as root.
SWEEP ?= studies/example_swarm_size.yaml
SWEEP_ARGS ?=

.PHONY: sweep slurm-tests
sweep: deps $(BUILD)/swarmsim
	$(PYTHON) -m swarmtools.sweep run $(SWEEP) --sim $(BUILD)/swarmsim $(SWEEP_ARGS)

slurm-tests: deps $(BUILD)/swarmsim
	@bash tools/slurm/local_cluster.sh install
	@SWARMSIM=$(BUILD)/swarmsim $(PYTHON) -m unittest -v tools.tests.slurm.test_slurm

EXTRA_TESTS += slurm-tests
