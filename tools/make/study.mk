# Seed 000's simulation study (tools/study): `make study-drtm` runs
# 5 conditions x {DRTM, ARTM, FRTM} x 50 runs; its unit tests run in `make test`.
STUDY_ARGS ?=
STUDY_STAMP := $(VENV)/.study-installed

$(STUDY_STAMP): tools/requirements-study.txt | $(BUILD)/config.mk
	$(VENV)/bin/pip install --disable-pip-version-check -q -r tools/requirements-study.txt
	touch $@

.PHONY: study-drtm study-tests
study-drtm: $(BUILD)/swarmsim $(STUDY_STAMP)
	$(PYTHON) tools/study/study_drtm.py --sim $(BUILD)/swarmsim $(STUDY_ARGS)

study-tests: $(STUDY_STAMP)
	@echo "== tools/study (unittest)"
	@$(PYTHON) -m unittest discover -s tools/study -p 'test_*.py'

EXTRA_TESTS += study-tests
