# scale_bench.mk - cost per robot-step from 20 to 100,000 robots, IR-only
# random walk against full sensing, with and without telemetry
# on 1 and 2 threads inside the run (tools/bench/scale.py, issue 18).  Not
# part of `make bench`: five runs a world, count and thread count take
# about 35 min on 2 cores.
# BENCH_SCALE_ARGS: e.g. "--runs 1 --counts 20:3000,2000:500".
.PHONY: bench-scale
bench-scale: $(BUILD)/swarmsim
	python3 tools/bench/scale.py --sim $(BUILD)/swarmsim $(BENCH_SCALE_ARGS)
