/*
 * cli.c - swarmsim's options as one table (cli.h): each entry names the
 * option, the value it takes, where it goes and what it means; the parser
 * and --help both read it.
 */
#include "cli.h"

#include <errno.h>
#include <inttypes.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/control.h"
#include "core/pool.h"
#include "models/model.h"
#include "registry.h"

typedef int opt_fn(cli_t *c, const char *opt, const char *value);

typedef struct cli_option {
    const char *name;       /* "--seed" */
    const char *alias;      /* "-h", or NULL */
    const char *value;      /* the value's name in --help, or NULL: a flag */
    uint64_t min, max;      /* an integer's range */
    size_t field;           /* offsetof(cli_t, ...): the integer, or the flag set to 1 */
    size_t given;           /* offsetof(cli_t, ...) of an int set to 1 when given, or NO_FIELD */
    opt_fn *apply;          /* NULL: store into `field` */
    const char *heading;    /* starts a group of --help before this option, or NULL */
    const char *help;
} cli_option_t;

#define NO_FIELD SIZE_MAX
#define STR_(x) #x
#define STR(x) STR_(x)
#define F(member) offsetof(cli_t, member)

static int set_mode(cli_t *c, const char *opt, const char *value);
static int set_lcm(cli_t *c, const char *opt, const char *value);
static int set_rate(cli_t *c, const char *opt, const char *value);
static int set_realtime(cli_t *c, const char *opt, const char *value);
static int set_video(cli_t *c, const char *opt, const char *value);
static int set_control_url(cli_t *c, const char *opt, const char *value);
static int set_out(cli_t *c, const char *opt, const char *value);
static int add_set(cli_t *c, const char *opt, const char *value);

static const cli_option_t options[] = {
    { "--seed", NULL, "N", 0, SCENARIO_SEED_MAX, F(seed), F(have_seed), NULL, NULL,
      "seed of the first repetition (default: the scenario's `seed`); repetition r uses seed N + r" },
    { "--reps", NULL, "N", 1, 1000000, F(reps), NO_FIELD, NULL, NULL,
      "repetitions (default 1); with N > 1 an aggregate OUT/summary.json holds mean, sd, min, max of "
      "each metric" },
    { "--threads", NULL, "N", 1, 1024, F(threads), NO_FIELD, NULL, NULL,
      "worker threads (default: the CPUs this process may use): repetitions run side by side, and with fewer repetitions "
      "than threads the spare ones go inside each run of 500 robots or more; results for a seed are "
      "bit-identical for any N" },
    { "--run-threads", NULL, "N", 1, 64, F(run_threads), NO_FIELD, NULL, NULL,
      "threads inside each run (1 to 64), whatever its size: controllers and sensors, IR delivery, "
      "sound, Box2D's solver" },
    { "--steps", NULL, "N", 0, UINT64_C(10000000000), F(steps), F(have_steps), NULL, NULL,
      "control steps per run (default: duration / control period)" },
    { "--out", NULL, "DIR", 0, 0, NO_FIELD, NO_FIELD, set_out, NULL,
      "output folder; each run writes DIR/run_<seed>/ (summary.json, timeseries.csv, telemetry.lcmlog).  "
      "Without --out: out/<scenario name>, replaced by each invocation when swarmsim made it (the "
      "edit-and-run loop); a given DIR that is not empty is an error unless --replace or --resume" },
    { "--set", NULL, "K=V", 0, 0, NO_FIELD, NO_FIELD, add_set, NULL,
      "override scenario key K (dotted path, e.g. robots.0.count=30, robots.0.params.speed_steps_s=300, "
      "objects.0.x=1.5); repeatable, applied in order after the file" },
    { "--frames", NULL, "N", 0, UINT64_C(1000000000), F(frames), NO_FIELD, NULL, NULL,
      "write a top-down PNG every N steps, and the last frame, to DIR/run_<seed>/frames/ (default 0: none)" },
    { "--frame-px", NULL, "N", 16, 8192, F(frame_px), NO_FIELD, NULL, NULL,
      "width of the pictures in pixels (default 800)" },
    { "--camera-frames", NULL, "ROBOT", 0, 100000, F(camera_robot), F(have_camera_robot), NULL, NULL,
      "save robot ROBOT's (id, 0-based) camera frames, its detected blobs drawn on them, to "
      "DIR/run_<seed>/camera/robot_<ROBOT>/frame_<step>.png (with camera.model geometric the frame is "
      "rendered for the picture only, and the boxes are the model's blobs)" },
    { "--lcm", NULL, "URL", 0, 0, NO_FIELD, NO_FIELD, set_lcm, NULL,
      "LCM telemetry (lcm_types/: RUN_INFO, TELEMETRY_SCHEMA, SWARM_STATE, ROBOT_STATE, SWARM_EVENT, "
      "RUN_SUMMARY, SCENE, TASK_DRAWING) to an LCM provider URL, e.g. udpm://239.255.76.67:7667?ttl=0; "
      "`off`: none.  Default: an LCM log DIR/run_<seed>/telemetry.lcmlog stamped with simulated time" },
    { "--telemetry-rate", NULL, "R[,S]", 0, 0, NO_FIELD, NO_FIELD, set_rate, NULL,
      "robot states per robot per simulated second (R, default 1) and swarm states per simulated second "
      "(S, default 10); 0 sends none" },
    { "--realtime", NULL, "X", 0, 0, NO_FIELD, NO_FIELD, set_realtime, NULL,
      "with telemetry on: run no faster than X times real time (to watch a run live)" },
    { "--control", NULL, NULL, 0, 0, F(control), NO_FIELD, NULL, NULL,
      "with --realtime and one repetition: take commands over LCM (swarm-live's buttons, "
      "python -m swarmtools.control): pause, resume, step N, realtime X, move a robot, select one to "
      "inspect.  Each is an event in the telemetry and a line of summary.json's \"control\"; a moved "
      "robot or a parameter set (set ROBOT|GROUP KEY VALUE, a key its controller declares live) marks the run touched.  On a loopback-only bus (" CONTROL_DEFAULT_URL ") unless "
      "--control-lcm names another" },
    { "--paused", NULL, NULL, 0, 0, F(control_paused), NO_FIELD, NULL, NULL,
      "with --control: wait for a command (resume, step) before the first step" },
    { "--control-lcm", NULL, "URL", 0, 0, NO_FIELD, NO_FIELD, set_control_url, NULL,
      "the bus --control listens on (another machine's commands need ttl=1: anyone on the network may "
      "then steer the run)" },
    { "--quiet", "-q", NULL, 0, 0, F(quiet), NO_FIELD, NULL, NULL,
      "print nothing on success (errors still go to stderr)" },
    { "--replace", NULL, NULL, 0, 0, NO_FIELD, NO_FIELD, set_mode, NULL,
      "the --out folder may hold an earlier invocation's outputs: remove it first (only a folder "
      "swarmsim made, marked .swarmsim-out); without it a non-empty --out is an error" },
    { "--resume", NULL, NULL, 0, 0, NO_FIELD, NO_FIELD, set_mode, NULL,
      "continue an interrupted invocation in its --out folder (same scenario, overrides, seeds, steps "
      "and outputs): its finished runs are kept, the others run" },
    { "--check", NULL, NULL, 0, 0, F(check_only), NO_FIELD, NULL, NULL,
      "load the scenario and its --set overrides, report what is wrong and what a run needs in memory, "
      "and run nothing (exit 0 or 2)" },
    { "--help", "-h", NULL, 0, 0, F(help), NO_FIELD, NULL, NULL,
      "this text, the controllers, the tasks, the models and every scenario key" },
    { "--video", NULL, "FILE.mp4", 0, 0, NO_FIELD, NO_FIELD, set_video, "video (needs ffmpeg)",
      "film the first repetition (seed N) as H.264 MP4, with the time stamp, legend and robot ids of "
      "the PNG frames; written to FILE.mp4.tmp and renamed when complete.  Other repetitions are not "
      "filmed.  Size: --frame-px, made even" },
    { "--video-every", NULL, "N", 0, 0, NO_FIELD, NO_FIELD, set_video, NULL,
      "one frame every N control steps (default " STR(VIDEO_DEFAULT_EVERY) "), and the last" },
    { "--video-fps", NULL, "F", 0, 0, NO_FIELD, NO_FIELD, set_video, NULL,
      "frames per second of the video (default " STR(VIDEO_DEFAULT_FPS) "): a run of S control steps "
      "lasts S / every / fps seconds" },
};

#define N_OPTIONS (sizeof options / sizeof options[0])

/* ---------------------------------------------------------------- values */

/* An unsigned integer in [lo, hi]; reports and returns -1 if not. */
static int parse_uint(const char *opt, const char *text, uint64_t lo, uint64_t hi, uint64_t *out)
{
    char *end;
    errno = 0;
    unsigned long long v = (*text >= '0' && *text <= '9') ? strtoull(text, &end, 10) : 0;
    if (!*text || *text < '0' || *text > '9' || *end || errno || v < lo || v > hi) {
        fprintf(stderr, "swarmsim: %s: '%s' is not an integer in [%" PRIu64 ", %" PRIu64 "]\n", opt, text, lo,
                hi);
        return -1;
    }
    *out = v;
    return 0;
}

static int set_mode(cli_t *c, const char *opt, const char *value)
{
    outdir_mode_t m = strcmp(opt, "--replace") == 0 ? OUTDIR_REPLACE : OUTDIR_RESUME;
    (void)value;
    if (c->out_mode != OUTDIR_NEW && c->out_mode != m) {
        fprintf(stderr, "swarmsim: --replace and --resume exclude each other\n");
        return -1;
    }
    c->out_mode = m;
    return 0;
}

static int set_lcm(cli_t *c, const char *opt, const char *value)
{
    (void)opt;
    c->telemetry.enabled = strcmp(value, "off") != 0;
    c->telemetry.url = c->telemetry.enabled ? value : NULL;
    return 0;
}

static int set_rate(cli_t *c, const char *opt, const char *value)
{
    if (telemetry_parse_rate(value, &c->telemetry) != 0) {
        fprintf(stderr, "swarmsim: %s: '%s' is not R or R,S with rates in [0, 1000] Hz\n", opt, value);
        return -1;
    }
    return 0;
}

static int set_realtime(cli_t *c, const char *opt, const char *value)
{
    char *end;
    c->telemetry.realtime = strtod(value, &end);
    if (*value == '\0' || *end || !(c->telemetry.realtime > 0.0 && c->telemetry.realtime <= 1e6)) {
        fprintf(stderr, "swarmsim: %s: '%s' is not a factor in (0, 1e6]\n", opt, value);
        return -1;
    }
    return 0;
}

static int set_control_url(cli_t *c, const char *opt, const char *value)
{
    (void)opt;
    c->control_url = value;
    return 0;
}

/* --video, --video-every, --video-fps (core/sim_video.c checks them). */
static int set_video(cli_t *c, const char *opt, const char *value)
{
    int bad = 0;
    (void)video_parse_option(opt, value, &c->video, &bad);
    return bad ? -1 : 0;
}

static int set_out(cli_t *c, const char *opt, const char *value)
{
    (void)opt;
    c->out_dir = value;
    return 0;
}

static int add_set(cli_t *c, const char *opt, const char *value)
{
    (void)opt;
    if (c->nsets == CLI_MAX_SETS) {
        fprintf(stderr, "swarmsim: more than %d --set options\n", CLI_MAX_SETS);
        return -1;
    }
    c->sets[c->nsets++].text = value;
    return 0;
}

/* ---------------------------------------------------------------- parsing */

static const cli_option_t *find(const char *arg, size_t len)
{
    for (size_t k = 0; k < N_OPTIONS; k++) {
        const cli_option_t *o = &options[k];
        if ((strlen(o->name) == len && strncmp(o->name, arg, len) == 0)
            || (o->alias && strlen(o->alias) == len && strncmp(o->alias, arg, len) == 0)) {
            return o;
        }
    }
    return NULL;
}

static int apply(cli_t *c, const cli_option_t *o, const char *value)
{
    char *base = (char *)c;
    if (o->given != NO_FIELD) {
        *(int *)(void *)(base + o->given) = 1;
    }
    if (o->apply) {
        return o->apply(c, o->name, value);
    }
    if (o->value == NULL) {
        *(int *)(void *)(base + o->field) = 1;
        return 0;
    }
    return parse_uint(o->name, value, o->min, o->max, (uint64_t *)(void *)(base + o->field));
}

int cli_parse(int argc, char **argv, cli_t *c)
{
    memset(c, 0, sizeof *c);
    c->reps = 1;
    c->frame_px = 800;
    c->threads = pool_cpus();
    c->out_mode = OUTDIR_NEW;
    telemetry_default_options(&c->telemetry);
    c->video = (video_options_t)VIDEO_OPTIONS_DEFAULT;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] != '-' || a[1] == '\0') {
            if (c->path) {
                fprintf(stderr, "swarmsim: more than one scenario given ('%s' and '%s')\n", c->path, a);
                return -1;
            }
            c->path = a;
            continue;
        }
        const char *eq = strchr(a, '=');
        size_t len = eq ? (size_t)(eq - a) : strlen(a);
        const cli_option_t *o = find(a, len);
        if (o == NULL) {
            fprintf(stderr, "swarmsim: unknown option '%.*s' (see --help)\n", (int)len, a);
            return -1;
        }
        const char *value = NULL;
        if (o->value != NULL) {
            if (eq) {
                value = eq + 1;
            } else if (i + 1 < argc) {
                value = argv[++i];
            } else {
                fprintf(stderr, "swarmsim: %s needs a value (see --help)\n", o->name);
                return -1;
            }
        } else if (eq) {
            fprintf(stderr, "swarmsim: %s takes no value\n", o->name);
            return -1;
        }
        if (apply(c, o, value) != 0) {
            return -1;
        }
        if (c->help) {
            return 0;   /* --help wins over anything after it */
        }
    }
    return 0;
}

/* ---------------------------------------------------------------- --help */

#define HELP_INDENT 18
#define HELP_WIDTH 78

/* `text` word-wrapped from column `col` to HELP_WIDTH, later lines at
 * HELP_INDENT. */
static void wrap(FILE *f, const char *text, int col)
{
    while (*text) {
        int room = HELP_WIDTH - col, n = 0, last = -1;
        while (text[n] && n <= room) {
            if (text[n] == ' ') last = n;
            n++;
        }
        if (text[n] == '\0' && n <= room) {
            fprintf(f, "%s\n", text);
            return;
        }
        int cut = last > 0 ? last : n;
        fprintf(f, "%.*s\n%*s", cut, text, HELP_INDENT, "");
        text += cut;
        while (*text == ' ') text++;
        col = HELP_INDENT;
    }
    fputc('\n', f);
}

void cli_print_options(FILE *f)
{
    for (size_t k = 0; k < N_OPTIONS; k++) {
        const cli_option_t *o = &options[k];
        char head[64];
        if (o->heading) {
            fprintf(f, "\n%s:\n", o->heading);
        }
        snprintf(head, sizeof head, "  %s%s%s%s%s", o->name, o->alias ? ", " : "", o->alias ? o->alias : "",
                 o->value ? " " : "", o->value ? o->value : "");
        int col = (int)strlen(head);
        if (col < HELP_INDENT - 1) {
            fprintf(f, "%-*s", HELP_INDENT, head);
            col = HELP_INDENT;
        } else {
            fprintf(f, "%s  ", head);
            col += 2;
        }
        wrap(f, o->help, col);
    }
}

void cli_print_help(FILE *f)
{
    fputs("usage: swarmsim SCENARIO.yaml [options]\n"
          "\n"
          "Runs e-puck firmware controllers in a Box2D world described by a YAML\n"
          "scenario, and writes per run a summary.json and a timeseries.csv.\n"
          "Options take their value as the next argument or after '=' (--seed=3).\n"
          "\n"
          "options:\n", f);
    cli_print_options(f);
    fputs("\nexit status: 0 ok, 1 a run failed, 2 bad arguments or scenario (nothing written),\n"
          "130 / 143 stopped by SIGINT / SIGTERM: finished runs are kept, --resume continues\n"
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
    fputs("\nmodels (sim_host/models/; their sections below), and the HAL calls each serves:\n", f);
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        const model_def_t *m = sim_models[id];
        fprintf(f, "  %-14s %s\n", m->name, m->doc);
        if (m->hal_calls != NULL && m->hal_calls[0] != NULL) {
            fprintf(f, "  %-14s serves:", "");
            for (size_t k = 0; m->hal_calls[k] != NULL; k++) {
                fprintf(f, " %s", m->hal_calls[k]);
            }
            fputc('\n', f);
        }
    }
    fputc('\n', f);
    scenario_print_schema(f);
}
