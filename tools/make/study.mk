# Seed 000's simulation study (swarmtools.study.drtm): `make study-drtm`
# runs 5 conditions x {DRTM, ARTM, FRTM} x 50 runs.  Its unit tests are
# among the Python tests (python.mk).
STUDY_ARGS ?=

.PHONY: study-drtm
study-drtm: deps $(BUILD)/swarmsim
	$(PYTHON) -m swarmtools.study.drtm --sim $(BUILD)/swarmsim $(STUDY_ARGS)
