# floor_bench.mk - the simulator against its floor (tools/bench/floor_bench.c):
# CPU time per robot-step of Box2D alone stepping the random walk's world,
# beside the random walk and full sensing, interleaved in one process.
#   make bench-floor   20 to 100,000 robots, 1 and 2 threads (about 10 min)
#   make bench-guard   the short regression guard: 20 and 2,000 robots, one
#                      thread (about 1 min); its multiples of the floor are
#                      recorded in docs/development/benchmarks.md per commit
#                      that changes stepping
# make test builds it and checks it (tests/cli/floor_bench.sh).
# BENCH_FLOOR_ARGS: e.g. "--counts 2000:50 --threads 1 --reps 9", or
# "--set sound.noise_draws=summed" (a scenario key of both worlds).
.PHONY: bench-floor bench-guard
$(BUILD)/floor_bench: tools/bench/floor_bench.c $(BUILD)/libswarm.a
	$(call show,CC,$@)$(CC) $(SIM_CFLAGS) -o $@ $< $(BUILD)/libswarm.a $(LDLIBS_SIM)

bench-floor: $(BUILD)/floor_bench
	$(BUILD)/floor_bench $(BENCH_FLOOR_ARGS)

bench-guard: $(BUILD)/floor_bench
	$(BUILD)/floor_bench --counts 20:2000,2000:50 --threads 1 --reps 15 $(BENCH_FLOOR_ARGS)

# tests/cli/floor_bench.sh runs it (20 robots, 20 steps: its checks, not a timing).
TEST_BUILD += $(BUILD)/floor_bench
cli-tests: $(BUILD)/floor_bench
