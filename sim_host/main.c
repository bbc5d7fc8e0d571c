/*
 * main.c - the swarmsim command line.
 *
 * Exit codes: 0 success, 1 a run failed (I/O, placement), 2 bad command line
 * or scenario (nothing is written).
 */
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "registry.h"
#include "core/runner.h"
#include "core/scenario.h"
#include "core/telemetry.h"

#define MAX_SETS 256

static void usage(FILE *f)
{
    fputs(
"usage: swarmsim SCENARIO.yaml [options]\n"
"\n"
"Runs e-puck firmware controllers in a Box2D world described by a YAML\n"
"scenario, and writes per run a summary.json and a timeseries.csv.\n"
"\n"
"options:\n"
"  --seed N        seed of the first repetition (default: the scenario's `seed`);\n"
"                  repetition r uses seed N + r\n"
"  --reps N        repetitions (default 1); with N > 1 an aggregate\n"
"                  OUT/summary.json holds mean, sd, min, max of each metric\n"
"  --threads N     worker threads for the repetitions (default: CPUs online);\n"
"                  results for a seed are bit-identical for any N\n"
"  --steps N       control steps per run (default: duration / control period)\n"
"  --out DIR       output folder (default out/<scenario name>); each run\n"
"                  writes DIR/run_<seed>/{summary.json,timeseries.csv,\n"
"                  telemetry.lcmlog}\n"
"  --set K=V       override scenario key K (dotted path, e.g. robots.0.count=30,\n"
"                  robots.0.params.speed_steps_s=300, objects.0.x=1.5);\n"
"                  repeatable, applied in order after the file\n"
"  --frames N      write a top-down PNG every N steps, and the last frame,\n"
"                  to DIR/run_<seed>/frames/ (default 0: none)\n"
"  --frame-px N    width of the pictures in pixels (default 800)\n"
"  --lcm URL       LCM telemetry (lcm_types/: RUN_INFO, TELEMETRY_SCHEMA,\n"
"                  SWARM_STATE, ROBOT_STATE, SWARM_EVENT, RUN_SUMMARY, SCENE,\n"
"                  TASK_DRAWING) to an LCM provider URL, e.g.\n"
"                  udpm://239.255.76.67:7667?ttl=0; `off`: none.  Default: an LCM\n"
"                  log DIR/run_<seed>/telemetry.lcmlog stamped with simulated time\n"
"  --telemetry-rate R[,S]  robot states per robot per simulated second (R,\n"
"                  default 1) and swarm states per simulated second (S,\n"
"                  default 10); 0 sends none\n"
"  --realtime X    with telemetry on: run no faster than X times real time\n"
"                  (to watch a run live)\n"
"  --quiet         print nothing on success (errors still go to stderr)\n"
"  --check         load the scenario and its --set overrides, report what is\n"
"                  wrong, and run nothing (exit 0 or 2)\n"
"  --help          this text, the controllers and every scenario key\n"
"\n"
"exit status: 0 ok, 1 a run failed, 2 bad arguments or scenario (nothing written)\n"
"\n", f);
    fputs("controllers (a group's `controller:`):\n", f);
    for (size_t i = 0; registry_controller_at(i); i++) {
        const controller_def_t *c = registry_controller_at(i);
        fprintf(f, "  %-14s %s\n", c->name, c->doc);
        if (c->policies != NULL && c->policies[0] != NULL) {
            fprintf(f, "  %-14s policies (`policy:`): %s (default)", "", c->policies[0]);
            for (size_t k = 1; c->policies[k] != NULL; k++) {
                fprintf(f, ", %s", c->policies[k]);
            }
            fputc('\n', f);
        }
    }
    fputs("\ntasks (a scenario section of that name runs it):\n", f);
    for (size_t i = 0; registry_task_at(i); i++) {
        const task_def_t *t = registry_task_at(i);
        fprintf(f, "  %-14s %s\n", t->name, t->doc);
    }
    fputc('\n', f);
    scenario_print_schema(f);
}

/* Parses an unsigned integer in [lo, hi]; reports and returns -1 if not. */
static int parse_uint(const char *opt, const char *text, uint64_t lo, uint64_t hi, uint64_t *out)
{
    char *end;
    errno = 0;
    unsigned long long v = (text && *text >= '0' && *text <= '9') ? strtoull(text, &end, 10) : 0;
    if (!text || !*text || *text < '0' || *text > '9' || *end || errno || v < lo || v > hi) {
        fprintf(stderr, "swarmsim: %s: '%s' is not an integer in [%" PRIu64 ", %" PRIu64 "]\n",
                opt, text ? text : "", lo, hi);
        return -1;
    }
    *out = v;
    return 0;
}

int main(int argc, char **argv)
{
    const char *path = NULL, *out_dir = NULL;
    scenario_override_t sets[MAX_SETS];
    size_t nsets = 0;
    uint64_t seed = 0, reps = 1, threads = 0, steps = 0, frames = 0, frame_px = 800;
    int have_seed = 0, have_steps = 0, quiet = 0, check_only = 0;
    telemetry_options_t telemetry;
    telemetry_default_options(&telemetry);
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    threads = cpus > 0 ? (uint64_t)cpus : 1;

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = (i + 1 < argc) ? argv[i + 1] : NULL;
        int bad = 0;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            quiet = 1;
            continue;
        } else if (!strcmp(a, "--check")) {
            check_only = 1;
            continue;
        } else if (a[0] != '-') {
            if (path) {
                fprintf(stderr, "swarmsim: more than one scenario given ('%s' and '%s')\n", path, a);
                return 2;
            }
            path = a;
            continue;
        }
        if (!v) {
            fprintf(stderr, "swarmsim: %s needs a value (see --help)\n", a);
            return 2;
        }
        i++;
        if (!strcmp(a, "--seed")) {
            bad = parse_uint(a, v, 0, SCENARIO_SEED_MAX, &seed);
            have_seed = 1;
        } else if (!strcmp(a, "--reps")) {
            bad = parse_uint(a, v, 1, 1000000, &reps);
        } else if (!strcmp(a, "--threads")) {
            bad = parse_uint(a, v, 1, 1024, &threads);
        } else if (!strcmp(a, "--steps")) {
            bad = parse_uint(a, v, 0, UINT64_C(10000000000), &steps);
            have_steps = 1;
        } else if (!strcmp(a, "--frames")) {
            bad = parse_uint(a, v, 0, UINT64_C(1000000000), &frames);
        } else if (!strcmp(a, "--frame-px")) {
            bad = parse_uint(a, v, 16, 8192, &frame_px);
        } else if (!strcmp(a, "--lcm")) {
            telemetry.enabled = strcmp(v, "off") != 0;
            telemetry.url = telemetry.enabled ? v : NULL;
        } else if (!strcmp(a, "--telemetry-rate")) {
            if (telemetry_parse_rate(v, &telemetry) != 0) {
                fprintf(stderr, "swarmsim: --telemetry-rate: '%s' is not R or R,S with rates in [0, 1000] Hz\n", v);
                return 2;
            }
        } else if (!strcmp(a, "--realtime")) {
            char *end;
            telemetry.realtime = strtod(v, &end);
            if (*v == '\0' || *end || !(telemetry.realtime > 0.0 && telemetry.realtime <= 1e6)) {
                fprintf(stderr, "swarmsim: --realtime: '%s' is not a factor in (0, 1e6]\n", v);
                return 2;
            }
        } else if (!strcmp(a, "--out")) {
            out_dir = v;
        } else if (!strcmp(a, "--set")) {
            if (nsets == MAX_SETS) {
                fprintf(stderr, "swarmsim: more than %d --set options\n", MAX_SETS);
                return 2;
            }
            sets[nsets++].text = v;
        } else {
            fprintf(stderr, "swarmsim: unknown option '%s' (see --help)\n", a);
            return 2;
        }
        if (bad) {
            return 2;
        }
    }
    if (!path) {
        fprintf(stderr, "swarmsim: no scenario given\n");
        usage(stderr);
        return 2;
    }

    scenario_t *sc = malloc(sizeof *sc);
    char err[SCENARIO_ERROR_MAX > 512 ? SCENARIO_ERROR_MAX : 512];
    if (!sc) {
        fprintf(stderr, "swarmsim: out of memory\n");
        return 1;
    }
    if (scenario_load(path, sets, nsets, sc, err) != 0) {
        fprintf(stderr, "swarmsim: %s\n", err);
        free(sc);
        return 2;
    }
    uint64_t first_seed = have_seed ? seed : sc->seed;
    if (reps - 1 > SCENARIO_SEED_MAX - first_seed) {
        fprintf(stderr, "swarmsim: seeds %" PRIu64 " + %" PRIu64 " repetitions pass the seed range "
                "[0, %" PRIu64 "]\n", first_seed, reps, SCENARIO_SEED_MAX);
        free(sc);
        return 2;
    }
    if (check_only) {   /* a sweep validates each combination of overrides this way */
        if (!quiet) {
            printf("swarmsim: %s: ok\n", path);
        }
        free(sc);
        return 0;
    }
    char default_out[SCENARIO_NAME_MAX + 8];
    if (!out_dir) {
        snprintf(default_out, sizeof default_out, "out/%s", sc->name);
        out_dir = default_out;
    }
    run_options_t opt = {
        .scenario = sc,
        .seed = first_seed,
        .reps = (uint32_t)reps,
        .threads = (uint32_t)threads,
        .steps = have_steps ? steps : (uint64_t)(sc->duration * 1000.0 / sc->control_period_ms + 0.5),
        .out_dir = out_dir,
        .frames_every = (uint32_t)frames,
        .frame_px = (uint32_t)frame_px,
        .quiet = quiet,
        .progress = !quiet,
        .telemetry = telemetry,
    };
    int rc = runner_run(&opt, err);
    if (rc != 0) {
        fprintf(stderr, "swarmsim: %s\n", err);
    }
    free(sc);
    return rc ? 1 : 0;
}
