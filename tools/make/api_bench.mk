# api_bench.mk - the Python API's cost over the C loop
# (tools/bench/python_api.py against tools/bench/api_loop.c):
# `make bench-api`, and `make bench` runs it too; and how fast a log
# reaches pandas (`make bench-load-log`).
.PHONY: bench-api
$(BUILD)/api_loop: tools/bench/api_loop.c $(BUILD)/libswarm.a
	$(call show,CC,$@)$(CC) $(SIM_CFLAGS) -o $@ $< $(BUILD)/libswarm.a $(LDLIBS_SIM)

bench-api: deps $(BUILD)/api_loop $(BUILD)/libswarmsim.so
	$(PYTHON) tools/bench/python_api.py --c-loop $(BUILD)/api_loop $(BENCH_API_ARGS)

bench: bench-api

# How fast a telemetry log reaches pandas (tools/bench/load_log.py):
# `make bench-load-log` (BENCH_LOAD_ARGS="--mb 300"); not part of `make bench`.
.PHONY: bench-load-log
bench-load-log: deps $(BUILD)/swarmsim
	$(PYTHON) tools/bench/load_log.py --swarmsim $(BUILD)/swarmsim $(BENCH_LOAD_ARGS)
