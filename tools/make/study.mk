# Every study says what it costs before it starts, and takes
# STUDY_ARGS=--quick for a smoke run of under a minute into out/<study>_quick/
# (swarmtools.study.costs; docs/studies/index.md).
#
# Seed 000's simulation study (swarmtools.study.drtm): `make study-drtm`
# runs 5 conditions x {DRTM, ARTM, FRTM} x 50 runs.  Its unit tests are
# among the Python tests (python.mk).
STUDY_ARGS ?=

.PHONY: study-drtm
study-drtm: deps $(BUILD)/swarmsim
	$(PYTHON) -m swarmtools.study.drtm --sim $(BUILD)/swarmsim $(STUDY_ARGS)

# Seed 000 under faults (swarmtools.study.faults): studies/faults_drtm.yaml,
# 5 conditions x 20 seeds, through the sweep engine.
.PHONY: study-faults
study-faults: deps $(BUILD)/swarmsim
	$(PYTHON) -m swarmtools.study.faults --sim $(BUILD)/swarmsim $(STUDY_ARGS)

# Seed 002's study (swarmtools.study.repatt): Figures 3, 2c and 4 of the paper
# at e-puck scale (studies/repatt_*.yaml), through the sweep engine.
# STUDY_ARGS=--quick: a smoke run (out/study_repatt_quick); --figures worlds for one sweep;
# --figures worlds,alns adds Figure 3's ALNS bars (plans, then the routes run).
.PHONY: study-repatt
study-repatt: deps $(BUILD)/swarmsim
	$(PYTHON) -m swarmtools.study.repatt --sim $(BUILD)/swarmsim $(STUDY_ARGS)

# Seed 002's gains study, reduced to one machine (swarmtools.study.gains):
# Figures 2a/2b: screen the 900 combinations, confirm 40, race 20 over 30
# seeds, in One100m and Uniform100m.  STUDY_ARGS=--estimate 120 measures the
# full sweep's core-hours (studies/repatt_gains.yaml; --backend slurm for it).
.PHONY: study-gains
study-gains: deps $(BUILD)/swarmsim
	$(PYTHON) -m swarmtools.study.gains --sim $(BUILD)/swarmsim $(STUDY_ARGS)

# Seed 003's study (swarmtools.study.eaipp): Figures 10-17 of the paper
# (studies/eaipp_*.yaml: maze, distance, obstacles, bearing, loss, bias),
# through the sweep engine, into out/study_eaipp/.  STUDY_ARGS=--quick: a
# smoke run (out/study_eaipp_quick); --figures maze,loss for some; --picture: the frame strip
# docs/figures/eaipp_square_frames.png (no sweep).
.PHONY: study-eaipp
study-eaipp: deps $(BUILD)/swarmsim
	$(PYTHON) -m swarmtools.study.eaipp --sim $(BUILD)/swarmsim $(STUDY_ARGS)
