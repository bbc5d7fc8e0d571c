# python.mk - the host tools as one package, swarmtools (pyproject.toml,
# tools/swarmtools/), installed in editable mode into .venv with the
# generated LCM types (package swarmlcm) by `make deps`; its tests and lint.
#
#   make python-tests   every tools/tests/ test (unittest), part of make test
#                       (as python-tests-1 and python-tests-2, side by side)
#   make lint           ruff over every Python file (package, tests, bench), part of make test

SWARMTOOLS_STAMP := $(VENV)/.swarmtools-installed
$(SWARMTOOLS_STAMP): pyproject.toml $(LCM_PY_STAMP) | $(BUILD)/config.mk
	$(call show,PIP,swarmtools into $(VENV) (editable))$(VENV)/bin/pip install --disable-pip-version-check -q --no-deps --no-build-isolation -e .
	@touch $@

deps: $(SWARMTOOLS_STAMP)

# make test runs the tests in two halves side by side (all in one, they were
# the longest group, a third of the groups' wall time).  The halves are
# balanced by time, not by theme: alone on a quiet 2-core machine telemetry
# takes 53 s, sweep 30, fuzz 20, calibrate 13, study 12, plan 9, fake_epuck 8,
# sim 5, evolve 4, sil 3.  Fragments add what the tests need to
# python-tests-deps.
PYTHON_TESTS_1 = telemetry sil evolve plan sim
PYTHON_TESTS_2 = study sweep fuzz fake_epuck calibrate
.PHONY: python-tests python-tests-1 python-tests-2 python-tests-deps lint
python-tests-deps: deps $(LCM_TYPE_OUTPUTS) $(TELEMETRY_FRAME_SO) $(BUILD)/swarmsim
python-tests: python-tests-deps
	@SWARMSIM=$(BUILD)/swarmsim TELEMETRY_FRAME_SO=$(TELEMETRY_FRAME_SO) $(PYTHON) tools/tests/run.py
python-tests-1: python-tests-deps
	@SWARMSIM=$(BUILD)/swarmsim TELEMETRY_FRAME_SO=$(TELEMETRY_FRAME_SO) $(PYTHON) tools/tests/run.py $(PYTHON_TESTS_1)
python-tests-2: python-tests-deps
	@SWARMSIM=$(BUILD)/swarmsim TELEMETRY_FRAME_SO=$(TELEMETRY_FRAME_SO) $(PYTHON) tools/tests/run.py $(PYTHON_TESTS_2)

lint: deps
	@$(VENV)/bin/ruff check pyproject.toml tools/swarmtools tools/tests tools/bench tools/docs docs/examples tools/scaffold.py tools/make tests/firmware tests/fuzz tests/docs platforms && echo "lint: ruff found nothing"

EXTRA_TESTS += lint python-tests-1 python-tests-2
TEST_BUILD += $(TELEMETRY_FRAME_SO)
