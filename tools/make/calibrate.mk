# calibrate.mk - the calibration kit's longer checks (tools/swarmtools/calibrate/sweep.py):
#   make calibrate-sweep  CALIBRATE_ROBOTS perturbed robots, each calibrated end to end on a
#                         fake e-puck with the kit's default procedures; the worst error per
#                         parameter against the stated tolerances into out/calibrate-sweep/
#                         (summary.md, errors.csv).  10 to 15 s a robot on a quiet machine.
#   make calibrate-pil    the same on the processor-in-the-loop robots: the calibration image's
#                         ELF on the emulated ATmega2560 and Cortex-M4F (CALIBRATE_PIL_ROBOTS
#                         each), into out/calibrate-pil/pil_avr/ and pil_m4/.
# Their short forms are in make test (tools/tests/calibrate/: test_recovery.py on the host
# build, test_pil.py on the AVR, three procedures).
CALIBRATE_ROBOTS ?= 10
CALIBRATE_SPREAD ?= 1.0
CALIBRATE_PIL_ROBOTS ?= 2
.PHONY: calibrate-sweep calibrate-pil
calibrate-sweep: deps $(SIM_SO)
	$(PYTHON) -m swarmtools.calibrate.sweep --robots $(CALIBRATE_ROBOTS) --spread $(CALIBRATE_SPREAD) --out out/calibrate-sweep
calibrate-pil: deps $(SIM_SO) pil-avr pil-m4
	$(PYTHON) -m swarmtools.calibrate.sweep --platform pil_avr --robots $(CALIBRATE_PIL_ROBOTS) --spread $(CALIBRATE_SPREAD) --out out/calibrate-pil/pil_avr
	$(PYTHON) -m swarmtools.calibrate.sweep --platform pil_m4 --robots $(CALIBRATE_PIL_ROBOTS) --spread $(CALIBRATE_SPREAD) --out out/calibrate-pil/pil_m4
# test_pil.py runs the calibration image's AVR ELF.  pil-avr is built once in
# make test's build step, before the groups: python-tests and cli-tests both
# need it and, run side by side, would otherwise rebuild its archives at once.
python-tests-deps: pil-avr
TEST_BUILD += pil-avr
