# camera_bench.mk - the camera models' cost (tools/bench/camera_bench.c and
# camera.sh): `make bench` runs it after the throughput benchmark;
# `make bench-camera` alone.
.PHONY: bench-camera
$(BUILD)/camera_bench: tools/bench/camera_bench.c $(BUILD)/libswarm.a
	$(CC) $(SIM_CFLAGS) -o $@ $< $(BUILD)/libswarm.a $(LDLIBS_SIM)

bench-camera: $(BUILD)/swarmsim $(BUILD)/camera_bench
	bash tools/bench/camera.sh $(BUILD)/swarmsim $(BUILD)/camera_bench

bench: bench-camera
