/*
 * rand.h - the simulator's random streams (sensor noise, packet loss,
 * placement).  xoshiro128+ seeded by splitmix64: fast, and every stream is
 * a pure function of (run seed, robot id, purpose), so results do not depend
 * on thread count or evaluation order across robots.
 */
#ifndef SIM_RAND_H
#define SIM_RAND_H

#include <stdint.h>

typedef struct sim_rand {
    uint64_t s[2];
} sim_rand_t;

/** Purposes, so that streams of one robot never overlap. */
enum {
    RAND_PLACEMENT = 1, RAND_SENSORS = 2, RAND_IRCOM = 3, RAND_WHEELS = 4, RAND_CONTROLLER = 5,
    RAND_TASK = 6,      /**< a task's streams (sim_task_rand_seed) */
    RAND_TRACKER = 7,   /**< the overhead tracker's noise and dropout */
    RAND_FAULTS = 8,    /**< which robots fail, when, and their faults' noise */
    RAND_SOUND = 9,     /**< eq 4's per-pair noise of the sound a robot hears */
    RAND_OBSTACLES = 10, /**< the random cylinders' layout (scenario random_cylinders) */
    RAND_WHEEL_BIAS = 11, /**< each robot's wheel biases (wheels.bias_sd): once a run, or every step (bias_per_step) */
    RAND_CAMERA = 12    /**< its camera's frame phase and pixel noise (camera.fps > 0, camera.noise) */
};

/** A purpose from a name, for streams of a model or task added after the
 *  numbered ones above (a model's name): a pure function of the name, so
 *  the stream does not move when other models are listed before it, and
 *  in [128, 255], so it meets none of the numbered ones. */
uint64_t sim_rand_purpose(const char *name);

/** Seeds a stream from the run seed, an index (robot id) and a purpose. */
void sim_rand_seed(sim_rand_t *r, uint64_t seed, uint64_t index, uint64_t purpose);

/** 32-bit seed for a firmware generator, derived the same way. */
uint32_t sim_rand_seed32(uint64_t seed, uint64_t index, uint64_t purpose);

uint64_t sim_rand_u64(sim_rand_t *r);
/** Uniform in [0, 1). */
double sim_rand_uniform(sim_rand_t *r);
/** Standard normal (ziggurat method). */
double sim_rand_normal(sim_rand_t *r);

#endif
