/*
 * scenario.c - fuzz target: the scenario loader with `--set` overrides
 * (sim_host/core/scenario.c, schema.c, yaml_tree.c) and, for what loads, a
 * small world built from it and stepped (sim.c and everything under it:
 * placement, sensors, IR, the tasks, the robots' controllers and their own
 * telemetry when the scenario runs it).
 *
 * Input: a scenario file's text, in which every line that starts with
 * "--set " is instead one override (the rest of the line; up to 8, in
 * order), as `swarmsim FILE --set ...` would take them.
 *
 * Properties, besides the sanitizers and LeakSanitizer:
 *   - a refused scenario says why, naming the file or the --set it came
 *     from (scenario.h: "FILE:LINE: key: what", "--set TEXT: ...");
 *   - the effective scenario (scenario_write_effective, what swarmsim keeps
 *     beside a run's outputs) loads, without the overrides, to exactly the
 *     same scenario;
 *   - a world that is built steps alike twice (the same state hash).
 * Big worlds are skipped here, not refused by the product, so that one
 * input stays fast: over 40 robots, 64 obstacles, 16 physics sub-steps,
 * 50 food tokens, a 20 m arena side or a 4,096-pixel camera; and at most
 * 8 steps are run.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fuzz.h"

#include "swarmsim/scenario.h"
/* The host model's messages live on the heap (compared apart). */
#include "models/camera/camera.h"
#include "models/host/host.h"
#include "swarmsim/sim.h"
#include "tasks/foraging/foraging.h"

#define MAX_SETS 8
#define MAX_STEPS 8u
#define MAX_TEXT 65536

static char dir[256], file_in[300], file_out[300];
static scenario_t *sc, *again;

static void remove_files(void)
{
    char sub[300];
    unlink(file_in);
    unlink(file_out);
    snprintf(sub, sizeof sub, "%s/in", dir);
    rmdir(sub);
    snprintf(sub, sizeof sub, "%s/out", dir);
    rmdir(sub);
    rmdir(dir);
}

/* Two files of the same name in two folders, so that both loads give the
 * scenario the same name. */
static void setup(void)
{
    const char *tmp = getenv("TMPDIR");
    char sub[300];
    snprintf(dir, sizeof dir, "%s/fuzz-scenario-XXXXXX", tmp != NULL && *tmp ? tmp : "/tmp");
    FUZZ_CHECK(mkdtemp(dir) != NULL);
    snprintf(sub, sizeof sub, "%s/in", dir);
    FUZZ_CHECK(mkdir(sub, 0700) == 0);
    snprintf(sub, sizeof sub, "%s/out", dir);
    FUZZ_CHECK(mkdir(sub, 0700) == 0);
    snprintf(file_in, sizeof file_in, "%s/in/s.yaml", dir);
    snprintf(file_out, sizeof file_out, "%s/out/s.yaml", dir);
    sc = malloc(sizeof *sc);
    again = malloc(sizeof *again);
    FUZZ_CHECK(sc != NULL && again != NULL);
    atexit(remove_files);
}

/* Splits the input: the file's lines go to `file_in`, the "--set " lines
 * into `sets` (their text in `buf`).  Returns the number of overrides. */
static size_t split(const uint8_t *data, size_t size, char *buf, scenario_override_t *sets)
{
    FILE *f = fopen(file_in, "wb");
    size_t n = 0, at = 0;
    FUZZ_CHECK(f != NULL);
    memcpy(buf, data, size);
    buf[size] = '\0';
    while (at < size) {
        char *line = buf + at;
        char *nl = memchr(line, '\n', size - at);
        size_t len = nl != NULL ? (size_t)(nl - line) : size - at;
        if (len >= 6 && memcmp(line, "--set ", 6) == 0 && n < MAX_SETS) {
            line[len] = '\0';   /* an override ends at its line (or at a NUL in it) */
            sets[n++].text = line + 6;
        } else {
            fwrite(line, 1, len + (nl != NULL), f);
        }
        at += len + 1;
    }
    FUZZ_CHECK(fclose(f) == 0);
    return n;
}

/* The error names where the bad value came from. */
static void check_error(const char *err, const scenario_override_t *sets, size_t n)
{
    size_t len = strnlen(err, SIM_ERR_MAX);
    FUZZ_CHECK(len > 0 && len < SIM_ERR_MAX);
    if (strncmp(err, file_in, strlen(file_in)) == 0) {
        return;
    }
    FUZZ_CHECK(strncmp(err, "--set ", 6) == 0);
    for (size_t i = 0; i < n; i++) {
        size_t t = strlen(sets[i].text);
        /* A message cut at the end of err[] may end inside the text. */
        size_t room = len - 6;
        if (strncmp(err + 6, sets[i].text, t < room ? t : room) == 0 && (t >= room || err[6 + t] == ':')) {
            return;
        }
    }
    FUZZ_CHECK(!"the error names a --set that was not given");
}

static int too_big(const scenario_t *s)
{
    const foraging_config_t *fc = scenario_task_config(s, &foraging_task);
    return scenario_robot_count(s) > 40u || s->object_count > 64u || s->physics_substeps > 16u
           || s->arena.width > 20.0f || s->arena.height > 20.0f
           || (uint32_t)camera_config(s)->width_px * camera_config(s)->height_px > 4096u
           || (fc != NULL && fc->food_count > 50u);
}

/* The effective scenario, written and read back, is the scenario. */
static void check_effective(const scenario_override_t *sets, size_t n)
{
    char err[SIM_ERR_MAX];
    FILE *f = fopen(file_out, "wb");
    FUZZ_CHECK(f != NULL);
    FUZZ_CHECK(scenario_write_effective(file_in, sets, n, f, err) == 0);
    FUZZ_CHECK(fclose(f) == 0);
    if (scenario_load(file_out, NULL, 0, again, err) != 0) {
        fprintf(stderr, "effective scenario refused: %s\n", err);
        FUZZ_CHECK(!"the effective scenario loads");
    }
    memset(again->path, 0, sizeof again->path);
    memset(sc->path, 0, sizeof sc->path);
    /* The objects and the host's messages are on the heap: compared as
     * arrays, their pointers left out of the struct's bytes. */
    FUZZ_CHECK(sc->object_count == again->object_count);
    FUZZ_CHECK(sc->object_count == 0 ||
               memcmp(sc->objects, again->objects, sc->object_count * sizeof *sc->objects) == 0);
    host_config_t *hs = host_config_mut(sc), *ha = host_config_mut(again);
    FUZZ_CHECK(hs->message_count == ha->message_count);
    FUZZ_CHECK(hs->message_count == 0 ||
               memcmp(hs->messages, ha->messages, hs->message_count * sizeof *hs->messages) == 0);
    object_def_t *objects_sc = sc->objects, *objects_again = again->objects;
    host_message_def_t *messages_sc = hs->messages, *messages_again = ha->messages;
    sc->objects = again->objects = NULL;
    hs->messages = ha->messages = NULL;
    int differ = memcmp(sc, again, sizeof *sc) != 0;
    sc->objects = objects_sc;
    again->objects = objects_again;
    hs->messages = messages_sc;
    ha->messages = messages_again;
    scenario_free(again);
    if (differ) {
        const uint8_t *a = (const uint8_t *)sc, *b = (const uint8_t *)again;
        size_t at = 0;
        while (a[at] == b[at]) {
            at++;
        }
        fprintf(stderr, "the scenarios differ from byte %zu of %zu (effective file: %s)\n", at, sizeof *sc,
                file_out);
        FUZZ_CHECK(!"the effective scenario is the scenario");
    }
}

static uint64_t run(uint32_t steps)
{
    char err[SIM_ERR_MAX];
    uint64_t h;
    sim_t *sim = sim_create(sc, sc->seed, err);
    if (sim == NULL) {
        FUZZ_CHECK(err[0] != '\0');
        return 0;
    }
    for (uint32_t k = 0; k < steps && !sim_done(sim); k++) {
        sim_step(sim);
    }
    h = sim_state_hash(sim);
    sim_destroy(sim);
    return h;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char *buf;
    scenario_override_t sets[MAX_SETS];
    char err[SIM_ERR_MAX];
    size_t n;

    if (size > MAX_TEXT) {
        return 0;
    }
    if (sc == NULL) {
        setup();
        buf = malloc(MAX_TEXT + 1);
        FUZZ_CHECK(buf != NULL);
    }
    n = split(data, size, buf, sets);
    if (scenario_load(file_in, sets, n, sc, err) != 0) {
        check_error(err, sets, n);
        return 0;
    }
    check_effective(sets, n);
    if (!too_big(sc)) {
        double per_step = sc->control_period_ms / 1000.0;
        uint32_t steps = sc->duration / per_step < MAX_STEPS ? (uint32_t)(sc->duration / per_step) : MAX_STEPS;
        FUZZ_CHECK(run(steps) == run(steps));
    }
    scenario_free(sc);
    return 0;
}
