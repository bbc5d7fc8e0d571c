# evolve.mk - swarm-evolve (swarmtools.evolve): `make evolve EVOLVE=file.yaml`
# runs an evolution file (EVOLVE_ARGS: --out, --jobs, --backend slurm, ...);
# rerunning the same command resumes it.  Its tests are in python-tests
# (tools/tests/evolve/).
EVOLVE ?= studies/nnea_evolve.yaml
EVOLVE_ARGS ?=

.PHONY: evolve
evolve: deps $(BUILD)/swarmsim
	$(PYTHON) -m swarmtools.evolve $(EVOLVE) --sim $(BUILD)/swarmsim $(EVOLVE_ARGS)
