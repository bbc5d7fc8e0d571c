# docs.mk - the documentation site (mkdocs.yml, docs/, tools/docs/):
#
#   make docs         build it into build/site/ (mkdocs build --strict: a broken
#                     link or anchor, a missing page or one left out of the nav
#                     fails it); the reference pages are generated from
#                     build/swarmsim --help and the tools' --help
#   make docs-serve   serve it at http://127.0.0.1:$(DOCS_PORT)/, rebuilt on every edit
#   make docs-tests   the build, then every command of the pages' runnable
#                     blocks (tests/docs/runnable.py); part of make test

DOCS_PORT ?= 8000
DOCS_ENV = NO_MKDOCS_2_WARNING=1 SWARMSIM=$(BUILD)/swarmsim VENV=$(VENV)

.PHONY: docs docs-serve docs-tests
docs: deps $(BUILD)/swarmsim
	@$(DOCS_ENV) $(VENV)/bin/mkdocs build --strict --quiet && echo "docs: the site is in $(BUILD)/site/ (open $(BUILD)/site/index.html)"

docs-serve: deps $(BUILD)/swarmsim
	$(DOCS_ENV) $(VENV)/bin/mkdocs serve --strict --dev-addr 127.0.0.1:$(DOCS_PORT)

docs-tests: docs
	@$(PYTHON) tests/docs/runnable.py

EXTRA_TESTS += docs-tests
