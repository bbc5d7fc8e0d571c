/*
 * main.c - the swarmsim command line.
 *
 * Exit codes: 0 success, 1 a run failed (I/O), 2 bad command line or
 * scenario, robots that cannot be placed, an LCM URL no provider takes, an
 * output folder it may not use (nothing is written), 130 / 143 stopped by
 * SIGINT / SIGTERM (finished runs kept; --resume continues).
 */
#include <errno.h>
#include <inttypes.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "registry.h"
#include "version.h"
#include "core/runner.h"
#include "swarmsim/scenario.h"
#include "models/camera/camera.h"
#include "models/camera/camera_render.h"
#include "core/sim_video.h"
#include "core/telemetry.h"

#define MAX_SETS 256
#define COMMAND_MAX 4096

/* The signal that asked to stop (0: none); the runner polls it. */
static volatile sig_atomic_t stop_signal;

static void on_stop_signal(int sig)
{
    stop_signal = sig;
}

static void catch_stop_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

/* argv as one shell-quoted line (provenance: how to run it again). */
static void command_line(int argc, char **argv, char *buf, size_t len)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int i = 0; i < argc && n + 4 < len; i++) {
        const char *a = argv[i];
        int plain = *a != '\0' && strspn(a, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                               "0123456789_-+=./,:@%") == strlen(a);
        if (i) buf[n++] = ' ';
        if (!plain) buf[n++] = '\'';
        for (; *a && n + 6 < len; a++) {
            if (*a == '\'' && !plain) {
                memcpy(buf + n, "'\\''", 4);
                n += 4;
            } else {
                buf[n++] = *a;
            }
        }
        if (!plain) buf[n++] = '\'';
        buf[n] = '\0';
    }
}

/* The effective scenario (file + overrides) as YAML text, malloc'd. */
static char *effective_scenario(const char *path, const scenario_override_t *sets, size_t n,
                                size_t *len, char err[SIM_ERR_MAX])
{
    char *text = NULL;
    FILE *f = open_memstream(&text, len);
    if (!f) {
        snprintf(err, SIM_ERR_MAX, "out of memory");
        return NULL;
    }
    int rc = scenario_write_effective(path, sets, n, f, err);
    if (fclose(f) != 0 || rc != 0) {
        free(text);
        return NULL;
    }
    return text;
}

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
"  --threads N     worker threads (default: CPUs online): repetitions run side\n"
"                  by side, and with fewer repetitions than threads the spare\n"
"                  ones go inside each run of 500 robots or more; results for\n"
"                  a seed are bit-identical for any N\n"
"  --run-threads N threads inside each run (1 to 64), whatever its size:\n"
"                  controllers and sensors, IR delivery, sound, Box2D's solver\n"
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
"  --camera-frames ROBOT  save robot ROBOT's (id, 0-based) camera frames, its\n"
"                  detected blobs drawn on them, to\n"
"                  DIR/run_<seed>/camera/robot_<ROBOT>/frame_<step>.png (with\n"
"                  camera.model geometric the frame is rendered for the picture\n"
"                  only, and the boxes are the model's blobs)\n"
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
"  --replace       the --out folder may hold an earlier invocation's outputs:\n"
"                  remove it first (only a folder swarmsim made, marked\n"
"                  .swarmsim-out); without it a non-empty --out is an error\n"
"  --resume        continue an interrupted invocation in its --out folder\n"
"                  (same scenario, overrides, seeds, steps and outputs): its\n"
"                  finished runs are kept, the others run\n"
"  --check         load the scenario and its --set overrides, report what is\n"
"                  wrong, and run nothing (exit 0 or 2)\n"
"  --help          this text, the controllers and every scenario key\n"
"\n"
"exit status: 0 ok, 1 a run failed, 2 bad arguments or scenario (nothing written),\n"
"130 / 143 stopped by SIGINT / SIGTERM: finished runs are kept, --resume continues\n"
"\n", f);
    video_print_usage(f);
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
    uint64_t seed = 0, reps = 1, threads = 0, run_threads = 0, steps = 0, frames = 0, frame_px = 800, camera_robot = 0;
    int have_camera_robot = 0;
    int have_seed = 0, have_steps = 0, quiet = 0, check_only = 0;
    outdir_mode_t out_mode = OUTDIR_NEW;
    telemetry_options_t telemetry;
    telemetry_default_options(&telemetry);
    video_options_t video = VIDEO_OPTIONS_DEFAULT;
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
        } else if (!strcmp(a, "--replace") || !strcmp(a, "--resume")) {
            outdir_mode_t m = a[3] == 'e' && a[4] == 'p' ? OUTDIR_REPLACE : OUTDIR_RESUME;
            if (out_mode != OUTDIR_NEW && out_mode != m) {
                fprintf(stderr, "swarmsim: --replace and --resume exclude each other\n");
                return 2;
            }
            out_mode = m;
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
        } else if (!strcmp(a, "--run-threads")) {
            bad = parse_uint(a, v, 1, 64, &run_threads);
        } else if (!strcmp(a, "--steps")) {
            bad = parse_uint(a, v, 0, UINT64_C(10000000000), &steps);
            have_steps = 1;
        } else if (!strcmp(a, "--frames")) {
            bad = parse_uint(a, v, 0, UINT64_C(1000000000), &frames);
        } else if (!strcmp(a, "--camera-frames")) {
            bad = parse_uint(a, v, 0, UINT64_C(100000), &camera_robot);
            have_camera_robot = 1;
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
        } else if (video_parse_option(a, v, &video, &bad)) {
            /* --video, --video-every, --video-fps (core/sim_video.c) */
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
    if (video_check_options(&video) != 0) {   /* ffmpeg, the folder: before any run */
        return 2;
    }

    scenario_t *sc = malloc(sizeof *sc);
    char err[SIM_ERR_MAX > 512 ? SIM_ERR_MAX : 512];
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
        scenario_free(sc);
        free(sc);
        return 2;
    }
    if (have_camera_robot && camera_robot >= scenario_robot_count(sc)) {
        fprintf(stderr, "swarmsim: --camera-frames: robot %" PRIu64 " is not in the scenario (ids 0 to %u)\n",
                camera_robot, scenario_robot_count(sc) - 1u);
        scenario_free(sc);
        free(sc);
        return 2;
    }
    if (camera_config(sc)->model == CAMERA_RENDERED || have_camera_robot) {
        camera_render_set_threads();   /* before any OSMesa context (camera_render.h) */
    }
    if (telemetry.realtime > 0.0 && !telemetry.enabled) {
        fprintf(stderr, "swarmsim: --realtime paces live telemetry for watching; with --lcm off there "
                "is nothing to watch (drop one of them)\n");
        scenario_free(sc);
        free(sc);
        return 2;
    }
    if (check_only) {   /* a sweep validates each combination of overrides this way */
        if (!quiet) {
            sim_memory_t m;
            char need[32];
            sim_memory_estimate(sc, 1, &m);
            scenario_format_bytes(m.total, need, sizeof need);
            printf("swarmsim: %s: ok (a run needs about %s)\n", path, need);
        }
        scenario_free(sc);
        free(sc);
        return 0;
    }
    char default_out[SCENARIO_NAME_MAX + 8];
    if (!out_dir) {
        snprintf(default_out, sizeof default_out, "out/%s", sc->name);
        out_dir = default_out;
    }
    size_t text_len = 0;
    char *text = effective_scenario(path, sets, nsets, &text_len, err);
    if (!text) {
        fprintf(stderr, "swarmsim: %s\n", err);
        scenario_free(sc);
        free(sc);
        return 2;
    }
    char command[COMMAND_MAX];
    command_line(argc, argv, command, sizeof command);
    run_options_t opt = {
        .scenario = sc,
        .seed = first_seed,
        .reps = (uint32_t)reps,
        .threads = (uint32_t)threads,
        .run_threads = (uint32_t)run_threads,
        .steps = have_steps ? steps : (uint64_t)(sc->duration * 1000.0 / sc->control_period_ms + 0.5),
        .out_dir = out_dir,
        .frames_every = (uint32_t)frames,
        .frame_px = (uint32_t)frame_px,
        .quiet = quiet,
        .progress = !quiet,
        .telemetry = telemetry,
        .out_mode = out_mode,
        .scenario_text = text,
        .provenance = { .code_version = SWARMSIM_VERSION, .command = command, .overrides = sets,
                        .override_count = nsets, .scenario_hash = summary_text_hash(text, text_len) },
        .stop = &stop_signal,
        .video = video,
        .camera_frames = have_camera_robot,
        .camera_robot = (uint32_t)camera_robot,
    };
    catch_stop_signals();
    int rc = runner_run(&opt, err);
    free(text);
    scenario_free(sc);
    free(sc);
    switch (rc) {
    case RUNNER_OK:
        return 0;
    case RUNNER_SETUP_ERROR:
        fprintf(stderr, "swarmsim: %s\n", err);
        return 2;
    case RUNNER_STOPPED:
        fprintf(stderr, "swarmsim: %s by %s: %s\n", stop_signal ? "interrupted" : "stopped",
                stop_signal == SIGTERM ? "SIGTERM" : "SIGINT", err);
        return 128 + (stop_signal ? (int)stop_signal : SIGINT);
    default:
        fprintf(stderr, "swarmsim: %s\n", err);
        return 1;
    }
}
