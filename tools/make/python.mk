# python.mk - the host tools as one package, swarmtools (pyproject.toml,
# tools/swarmtools/), installed in editable mode into .venv with the
# generated LCM types (package swarmlcm) by `make deps`; its tests and lint.
#
#   make python-tests   every tools/tests/ test (unittest), part of make test
#   make lint           ruff over every Python file (package, tests, bench), part of make test

SWARMTOOLS_STAMP := $(VENV)/.swarmtools-installed
$(SWARMTOOLS_STAMP): pyproject.toml $(LCM_PY_STAMP) | $(BUILD)/config.mk
	$(call show,PIP,swarmtools into $(VENV) (editable))$(VENV)/bin/pip install --disable-pip-version-check -q --no-deps --no-build-isolation -e .
	@touch $@

deps: $(SWARMTOOLS_STAMP)

.PHONY: python-tests lint
python-tests: deps $(LCM_TYPE_OUTPUTS) $(TELEMETRY_FRAME_SO) $(BUILD)/swarmsim
	@SWARMSIM=$(BUILD)/swarmsim TELEMETRY_FRAME_SO=$(TELEMETRY_FRAME_SO) $(PYTHON) tools/tests/run.py

lint: deps
	@$(VENV)/bin/ruff check pyproject.toml tools/swarmtools tools/tests tools/bench tools/docs docs/examples tools/scaffold.py tools/make tests/firmware tests/fuzz tests/docs platforms && echo "lint: ruff found nothing"

EXTRA_TESTS += lint python-tests
TEST_BUILD += $(TELEMETRY_FRAME_SO)
