/*
 * test_readings.c - every sensor reading pinned, as golden.sh pins the state.
 *
 * The state hash (sim_state_hash) covers poses, velocities and controller
 * states, not what the sensors returned; a change to a sensor model that
 * alters readings without yet moving a robot would pass golden.sh.  Here the
 * full-sensing benchmark world (tools/bench/bench_full_sensing.yaml: IR
 * proximity and ambient, the geometric camera every step, three sound bands
 * with a 2 m cutoff, so both the near field and the far field's aggregate,
 * IR messages with loss) runs in a 7 m arena with 60 robots, and every
 * robot's readings (sim_robot_inspect: proximity, ambient, blobs,
 * microphone levels, waiting IR messages) are hashed after every step,
 * beside the final state hash.  The variants switch on the paths the base
 * world does not take.  Each variant also runs on 2 threads in chunks of
 * one robot, to the same hash.
 *
 * Reference platform as golden.sh's.  To re-pin after an intended change:
 * READINGS_UPDATE=1 build/tests/test_readings prints the table.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <cmocka.h>

#include "sim_fixture.h"
#include "core/sim_internal.h"
#include "models/model.h"

#define STEPS 100u

typedef struct variant {
    const char *name;
    const char *sets[6];      /**< on top of the common ones; NULL ends */
    uint64_t readings, state; /**< pinned */
} variant_t;

static const char *const common[] = {
    "robots[0].count=60", "arena.width=7", "arena.height=7", "foraging.food_count=60",
};

static variant_t variants[] = {
    { "base", { NULL }, 0x869d8b67040b73b7ull, 0xa0c8e568428bdb87ull },
    { "silent_none_quiet", { "sound.silent_robots=none", "sound.noise=0", NULL },
      0xed65635f75b83ef4ull, 0xa0c8e568428bdb87ull },
    { "self_masking", { "sound.self_masking=true", NULL }, 0xf75afa1aed1cf037ull, 0xa0c8e568428bdb87ull },
    { "all_pairs", { "sound.cutoff=0", NULL }, 0xe68f43a12ca5b892ull, 0xa0c8e568428bdb87ull },
    { "blocked_obstacles",
      { "ircom.blocked_by_robots=true", "random_cylinders.count=40", "random_cylinders.radius_min=0.1",
        "random_cylinders.radius_max=0.2", NULL }, 0xc1b826a3d008f728ull, 0xf5c273fba24f9198ull },
};
#define VARIANTS (sizeof variants / sizeof variants[0])

typedef struct { uint64_t h; } fnv_t;

static void mix(fnv_t *f, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t k = 0; k < n; k++) {
        f->h = (f->h ^ b[k]) * 0x100000001b3ull;
    }
}
#define MIX(f, v) mix((f), &(v), sizeof(v))

/* Field by field: the struct's padding is not a reading. */
static void mix_readings(fnv_t *f, const model_inspect_t *r)
{
    MIX(f, r->prox_known);
    MIX(f, r->ambient_known);
    MIX(f, r->prox);
    MIX(f, r->ambient);
    MIX(f, r->ir_bearing_mrad);
    MIX(f, r->n_blobs);
    for (int b = 0; b < r->n_blobs; b++) {
        MIX(f, r->blobs[b].colour);
        MIX(f, r->blobs[b].bearing_mrad);
        MIX(f, r->blobs[b].width_mrad);
        MIX(f, r->blobs[b].pixels);
    }
    MIX(f, r->n_bands);
    for (unsigned b = 1; b <= r->n_bands && b < HAL_SOUND_BANDS; b++) {
        MIX(f, r->mic[b]);
    }
    MIX(f, r->n_heard);
    for (unsigned m = 0; m < r->n_heard && m < MODEL_INSPECT_HEARD; m++) {
        MIX(f, r->heard[m].value);
        MIX(f, r->heard[m].sensor);
        MIX(f, r->heard[m].bearing_mrad);
        MIX(f, r->heard[m].range_mm);
    }
}

static void run(const variant_t *v, uint32_t threads, uint64_t *readings, uint64_t *state)
{
    scenario_override_t o[12];
    size_t n = 0;
    for (size_t k = 0; k < sizeof common / sizeof common[0]; k++) {
        o[n++].text = common[k];
    }
    for (size_t k = 0; v->sets[k]; k++) {
        o[n++].text = v->sets[k];
    }
    scenario_t *sc = malloc(sizeof *sc);
    char err[SIM_ERR_MAX];
    assert_non_null(sc);
    if (scenario_load("../tools/bench/bench_full_sensing.yaml", o, n, sc, err) != 0) fail_msg("%s: %s", v->name, err);
    sim_t *sim = sim_create_threads(sc, sc->seed, threads, err);
    if (!sim) fail_msg("%s: %s", v->name, err);
    fnv_t f = { 0xcbf29ce484222325ull };
    uint32_t robots = sim_robot_count(sim);
    assert_int_equal(robots, 60);
    model_inspect_t r;
    int heard = 0, blobs = 0, loud = 0;
    for (uint32_t s = 0; s < STEPS; s++) {
        sim_step(sim);
        for (uint32_t i = 0; i < robots; i++) {
            sim_robot_inspect(sim, i, &r);
            mix_readings(&f, &r);
            heard |= r.n_heard > 0;
            blobs |= r.n_blobs > 0;
            for (unsigned b = 1; b <= r.n_bands && b < HAL_SOUND_BANDS; b++) {
                loud |= r.mic[b] > 0.0f;
            }
        }
    }
    /* The world exercises what it pins. */
    assert_true(heard);
    assert_true(blobs);
    assert_true(loud);
    *readings = f.h;
    *state = sim_state_hash(sim);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_readings_pinned(void **unused)
{
    (void)unused;
    int update = getenv("READINGS_UPDATE") != NULL, wrong = 0;
    setenv("SWARMSIM_POOL_CHUNK", "1", 1);
    for (size_t k = 0; k < VARIANTS; k++) {
        uint64_t r1, s1, r2, s2;
        run(&variants[k], 1, &r1, &s1);
        run(&variants[k], 2, &r2, &s2);
        if (r1 != r2 || s1 != s2) {
            print_error("%s: 1 thread %016llx %016llx, 2 threads %016llx %016llx\n", variants[k].name,
                        (unsigned long long)r1, (unsigned long long)s1, (unsigned long long)r2,
                        (unsigned long long)s2);
            wrong = 1;
        }
        if (update) {
            printf("    { \"%s\", ..., 0x%016llxull, 0x%016llxull },\n", variants[k].name, (unsigned long long)r1,
                   (unsigned long long)s1);
        } else if (r1 != variants[k].readings || s1 != variants[k].state) {
            print_error("%s: readings %016llx state %016llx, pinned %016llx %016llx\n", variants[k].name,
                        (unsigned long long)r1, (unsigned long long)s1,
                        (unsigned long long)variants[k].readings, (unsigned long long)variants[k].state);
            wrong = 1;
        }
    }
    assert_false(wrong);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_readings_pinned),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
