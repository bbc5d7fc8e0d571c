/*
 * cli.h - swarmsim's command line: one table of options (cli.c) that the
 * parser reads and that writes --help, so that the reference of the
 * options is generated from the table (docs) and cannot drift from it.
 *
 * Options take their value as the next argument or after '='
 * (`--seed 3`, `--seed=3`); names are matched whole (no abbreviations); the
 * scenario is the one argument that is not an option, anywhere on the line.
 */
#ifndef SIM_CLI_H
#define SIM_CLI_H

#include <stdint.h>
#include <stdio.h>

#include "core/outdir.h"
#include "core/sim_video.h"
#include "core/telemetry.h"
#include "swarmsim/scenario.h"

/** Most --set options. */
#define CLI_MAX_SETS 256

/** What the command line asks for. */
typedef struct cli {
    const char *path;             /**< the scenario file */
    const char *out_dir;          /**< --out, or NULL: out/<scenario name> */
    scenario_override_t sets[CLI_MAX_SETS];
    uint32_t nsets;
    uint64_t seed, reps, threads, run_threads, steps, frames, frame_px, camera_robot;
    int have_seed, have_steps, have_camera_robot;
    int quiet, check_only, help;
    outdir_mode_t out_mode;
    telemetry_options_t telemetry;
    int control;                  /**< --control: commands over LCM (core/control.h) */
    int control_paused;           /**< --paused: waits for a command before the first step */
    const char *control_url;      /**< --control-lcm, or NULL: CONTROL_DEFAULT_URL */
    video_options_t video;
} cli_t;

/** Parses argv into `c` (defaults first).  Returns 0, or -1 when something
 *  is wrong with it (reported on stderr: exit 2). */
int cli_parse(int argc, char **argv, cli_t *c);

/** --help: the usage, every option from the table, the exit statuses, the
 *  controllers, the tasks, the models and every scenario key. */
void cli_print_help(FILE *f);

/** The options alone (the docs generate the CLI reference from them). */
void cli_print_options(FILE *f);

#endif
