/*
 * command.c - what the swarmsim command line does, as a function
 * (swarmsim/command.h): main.c and the Python binding's run() call it.
 */
#include "swarmsim/command.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "registry.h"
#include "core/runner.h"
#include "swarmsim/scenario.h"
#include "models/camera/camera.h"
#include "models/camera/camera_render.h"
#include "core/sim_video.h"
#include "core/control.h"
#include "core/telemetry.h"

#define COMMAND_MAX 4096

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

int swarmsim_command(int argc, char **argv, const char *code_version, volatile sig_atomic_t *stop)
{
    cli_t cli;
    if (cli_parse(argc, argv, &cli) != 0) {
        return 2;
    }
    if (cli.help) {
        cli_print_help(stdout);
        return 0;
    }
    const char *path = cli.path, *out_dir = cli.out_dir;
    const scenario_override_t *sets = cli.sets;
    size_t nsets = cli.nsets;
    uint64_t seed = cli.seed, reps = cli.reps, camera_robot = cli.camera_robot;
    int have_camera_robot = cli.have_camera_robot, quiet = cli.quiet;
    outdir_mode_t out_mode = cli.out_mode;
    telemetry_options_t telemetry = cli.telemetry;
    video_options_t video = cli.video;
    if (!path) {
        fprintf(stderr, "swarmsim: no scenario given (swarmsim SCENARIO.yaml [options]; --help lists them)\n");
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
    uint64_t first_seed = cli.have_seed ? seed : sc->seed;
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
    if ((cli.control_url || cli.control_paused) && !cli.control) {
        fprintf(stderr, "swarmsim: %s is for a run under --control, which is not given\n",
                cli.control_url ? "--control-lcm" : "--paused");
        scenario_free(sc);
        free(sc);
        return 2;
    }
    const char *control_url = NULL;
    if (cli.control) {
        const char *why = telemetry.realtime <= 0.0 ? "--control needs --realtime X: a run as fast as it goes "
                                                      "is over before a command could come"
                          : reps > 1 ? "--control steers one run: drop --reps" : NULL;
        control_url = cli.control_url ? cli.control_url : CONTROL_DEFAULT_URL;
        if (why) {
            fprintf(stderr, "swarmsim: %s\n", why);
        } else if (telemetry_check_url("--control-lcm", control_url, err) != 0) {
            fprintf(stderr, "swarmsim: %s\n", err);
            why = err;
        }
        if (why) {
            scenario_free(sc);
            free(sc);
            return 2;
        }
    }
    if (cli.check_only) {   /* a sweep validates each combination of overrides this way */
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
    /* Without --out: the scenario's own folder, which each invocation
     * replaces when swarmsim made it (edit, run, look, run again). */
    char default_out[SCENARIO_NAME_MAX + 8];
    if (!out_dir) {
        snprintf(default_out, sizeof default_out, "out/%s", sc->name);
        out_dir = default_out;
        if (out_mode == OUTDIR_NEW) {
            out_mode = OUTDIR_DEFAULT;
        }
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
        .threads = (uint32_t)cli.threads,
        .run_threads = (uint32_t)cli.run_threads,
        .steps = cli.have_steps ? cli.steps : scenario_steps(sc),
        .out_dir = out_dir,
        .frames_every = (uint32_t)cli.frames,
        .frame_px = (uint32_t)cli.frame_px,
        .quiet = quiet,
        .progress = !quiet,
        .telemetry = telemetry,
        .control_url = control_url,
        .control_paused = cli.control_paused,
        .out_mode = out_mode,
        .scenario_text = text,
        .provenance = { .code_version = code_version, .command = command, .overrides = sets,
                        .override_count = nsets, .scenario_hash = summary_text_hash(text, text_len) },
        .stop = stop,
        .video = video,
        .camera_frames = have_camera_robot,
        .camera_robot = (uint32_t)camera_robot,
    };
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
    case RUNNER_STOPPED: {
        int sig = stop ? (int)*stop : 0;
        fprintf(stderr, "swarmsim: %s by %s: %s\n", sig ? "interrupted" : "stopped",
                sig == SIGTERM ? "SIGTERM" : "SIGINT", err);
        return 128 + (sig ? sig : SIGINT);
    }
    default:
        fprintf(stderr, "swarmsim: %s\n", err);
        return 1;
    }
}
