# video.mk - videos of runs (swarmsim --video, sim_host/core/sim_video.c).
# `make video` films seed 000's base scenario, the first seed, 1200 s in one
# minute (a frame every 10 steps at 20 fps), to out/video/foraging_base.mp4,
# and keeps that run's outputs in out/video/foraging_base/ (VIDEO_SCENARIO=,
# VIDEO_OUT=, VIDEO_ARGS=, e.g. VIDEO_ARGS="--frame-px 480 --steps 3000");
# `make video-tests` (part of make test) checks videos with ffprobe
# (tests/video/video.sh).
VIDEO_SCENARIO ?= sim_host/scenarios/foraging_base.yaml
VIDEO_OUT ?= out/video/$(basename $(notdir $(VIDEO_SCENARIO))).mp4
VIDEO_ARGS ?=

.PHONY: video video-tests
video: deps $(BUILD)/swarmsim
	@mkdir -p $(dir $(VIDEO_OUT))
	$(BUILD)/swarmsim $(VIDEO_SCENARIO) --video $(VIDEO_OUT) --lcm off --quiet \
	  --out $(basename $(VIDEO_OUT)) --replace $(VIDEO_ARGS)
	@echo "video: $(VIDEO_OUT)"

video-tests: deps $(BUILD)/swarmsim
	@bash tests/video/video.sh $(BUILD)/swarmsim

EXTRA_TESTS += video-tests
