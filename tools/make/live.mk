# live.mk - the live view of a swarm in the browser (swarmtools.live,
# console script swarm-live): a local web server that follows LCM telemetry
# or replays a log, and the page it serves.
#
#   make live                   follow the LCM bus (LCM_URL=..., default LCM's own udpm bus)
#   make live LOG=FILE.lcmlog   replay a log (LIVE_ARGS: --speed 10, --port 8081, ...)
#   make live-tests             the page in a real headless chromium (part of make test),
#                               installing Debian's chromium and chromium-driver first
#                               when run as root (tools/make/browser.sh)
#   make live-figure            the live view's picture in the docs, docs/figures/live_view.png
LOG ?=
LIVE_ARGS ?=
LIVE_FIGURE := docs/figures/live_view.png

.PHONY: live live-tests live-figure
live: deps $(LCM_TYPE_OUTPUTS)
	$(PYTHON) -m swarmtools.live $(if $(LOG),--log '$(LOG)',$(if $(LCM_URL),--lcm '$(LCM_URL)')) $(LIVE_ARGS)

live-tests: deps $(LCM_TYPE_OUTPUTS) $(BUILD)/swarmsim
	@bash tools/make/browser.sh install
	@SWARMSIM=$(BUILD)/swarmsim $(PYTHON) -m unittest -v tools.tests.live.test_server tools.tests.live.test_page

# A minute of seed 000's base condition, seen at 45 s.
live-figure: deps $(LCM_TYPE_OUTPUTS) $(BUILD)/swarmsim
	@bash tools/make/browser.sh install
	@rm -rf $(BUILD)/live_figure
	$(BUILD)/swarmsim sim_host/scenarios/foraging_base.yaml --steps 600 --out $(BUILD)/live_figure --quiet
	$(PYTHON) -m tools.tests.live.screenshot $(BUILD)/live_figure/run_1/telemetry.lcmlog $(LIVE_FIGURE) --at 45 --size 1400x1000

EXTRA_TESTS += live-tests
