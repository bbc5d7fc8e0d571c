# calibrate.mk - the calibration kit's longer check (tools/swarmtools/calibrate/sweep.py):
# CALIBRATE_ROBOTS perturbed robots, each calibrated end to end on a fake
# e-puck with the kit's default procedures; the worst error per parameter
# against the stated tolerances into out/calibrate-sweep/ (summary.md,
# errors.csv).  10 to 15 s a robot on a quiet machine.  Its short form is
# in make test (tools/tests/calibrate/).
CALIBRATE_ROBOTS ?= 10
CALIBRATE_SPREAD ?= 1.0
.PHONY: calibrate-sweep
calibrate-sweep: deps $(SIM_SO)
	$(PYTHON) -m swarmtools.calibrate.sweep --robots $(CALIBRATE_ROBOTS) --spread $(CALIBRATE_SPREAD) --out out/calibrate-sweep
