/*
 * telemetry.c - LCM telemetry of a simulation run (telemetry.h).
 *
 * Messages are encoded by the lcm-gen C code of lcm_types/ (build/lcm_c/)
 * and go either to lcm_publish (a URL) or to the default log file, with the
 * simulated time as each event's timestamp.  Everything a message holds is
 * a function of the simulation state, never of the wall clock.
 *
 * The log file is LCM's log format, byte for byte what lcm_eventlog_write_event
 * writes (tests/test_telemetry.c compares the two), but each event goes out
 * in one fwrite from the encoding buffer: lcm_eventlog_write_event makes nine
 * fwrite calls per event, which was 40 % of the telemetry's cost.
 */
#define _GNU_SOURCE 1   /* __fsetlocking */
#include "telemetry.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdio_ext.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <sys/stat.h>

#include <lcm/lcm.h>

#include "models/uart/uart.h"
#include "sim_internal.h"
#include "swarmlcm_event_t.h"
#include "swarmlcm_robot_state_t.h"
#include "swarmlcm_run_info_t.h"
#include "swarmlcm_run_summary_t.h"
#include "swarmlcm_schema_t.h"
#include "swarmlcm_swarm_state_t.h"
#include "telemetry_scene.h"

/** Distinct controller states counted in SWARM_STATE. */
#define MAX_STATES 32
/** RUN_INFO is repeated every this many simulated seconds. */
#define INFO_PERIOD_S 10.0
#define DETAIL_MAX 48

struct telemetry {
    lcm_t *lcm;                  /* URL sink, or NULL */
    FILE *log;                   /* log file sink, or NULL */
    int64_t log_events;          /* events written to the log */
    char path[1024], tmp[1040];  /* the log file and its temporary name */
    int write_error;             /* errno of the first failed write, or 0 */
    uint64_t publish_errors;     /* lcm_publish failures (URL sink) */
    uint64_t messages;

    uint64_t seed;
    uint64_t steps;              /* steps the run will do */
    uint32_t robot_every, swarm_every, info_every;   /* steps; 0: never */
    double robot_hz, swarm_hz;
    uint64_t robot_sent_step, swarm_sent_step;       /* last step sent, +1 (0: none) */
    double realtime;
    double summary_pause_s;      /* before RUN_SUMMARY on a bus (see telemetry_end) */
    struct timespec wall0;

    uint8_t *buf;                /* encoding buffer */
    size_t buf_size;

    /* Per robot, as of the previous step: what events are told against. */
    uint32_t n;
    uint32_t n_counters;         /* counter observables of the robot with the most */
    float *prev_counter;         /* n x n_counters, in each robot's table order */
    const char **prev_state;
    uint8_t *prev_escaped;

    /* The robots' own telemetry (robot_telemetry.enabled): republished on
     * prefixed channels; raw bytes dumped per robot on request. */
    char fw_channel[TELEMETRY_CH_COUNT][48];
    int fw_channel_len[TELEMETRY_CH_COUNT];
    char dump_dir[1024];         /* "" when not dumping */
    FILE **dump;                 /* per robot, opened at its first bytes */

    telemetry_scene_t *scene;    /* SCENE and TASK_DRAWING (telemetry_scene.h) */

    /* Controller states seen so far, for SWARM_STATE's robots by state. */
    uint16_t n_states;
    const char *state_names[MAX_STATES];
    int16_t state_counts[MAX_STATES];
};

void telemetry_default_options(telemetry_options_t *opt)
{
    opt->enabled = 1;
    opt->url = NULL;
    opt->robot_hz = TELEMETRY_DEFAULT_ROBOT_HZ;
    opt->swarm_hz = TELEMETRY_DEFAULT_SWARM_HZ;
    opt->realtime = 0.0;
}

static int parse_hz(const char *text, const char *stop, double *out)
{
    char *end;
    if (text == stop || !((*text >= '0' && *text <= '9') || *text == '.')) {
        return -1;   /* no sign, space, nan or inf */
    }
    errno = 0;
    double v = strtod(text, &end);
    if (end != stop || errno || !(v >= 0.0 && v <= 1000.0)) {
        return -1;
    }
    *out = v;
    return 0;
}

int telemetry_check_url(const char *option, const char *url, char err[SIM_ERR_MAX])
{
    lcm_t *lcm = lcm_create(url);
    if (!lcm) {
        snprintf(err, SIM_ERR_MAX, "%s %s: no LCM provider takes this URL (udpm://GROUP:PORT?ttl=0, "
                 "file://PATH?mode=w, memq://)", option, url);
        return -1;
    }
    lcm_destroy(lcm);
    return 0;
}

int telemetry_parse_rate(const char *text, telemetry_options_t *opt)
{
    double robot, swarm = opt->swarm_hz;
    const char *comma = strchr(text, ',');
    const char *stop = comma ? comma : text + strlen(text);
    if (parse_hz(text, stop, &robot) != 0 || (comma && parse_hz(comma + 1, comma + 1 + strlen(comma + 1), &swarm) != 0)) {
        return -1;
    }
    opt->robot_hz = robot;
    opt->swarm_hz = swarm;
    return 0;
}

/* Steps between two messages at `hz` (0: never): the nearest whole number
 * of control periods, at least one. */
static uint32_t every_steps(double hz, uint16_t period_ms)
{
    if (hz <= 0.0) {
        return 0;
    }
    double steps = floor(1000.0 / (hz * period_ms) + 0.5);
    return steps < 1.0 ? 1u : steps > 4e9 ? 4000000000u : (uint32_t)steps;
}

static int64_t utime_of(const struct sim *sim)
{
    return (int64_t)sim->step * sim->sc->control_period_ms * 1000;
}

/* lcm-gen's C code computes each type's fingerprint lazily into a static:
 * compute them once before any two runs can race on it. */
static pthread_once_t hashes_once = PTHREAD_ONCE_INIT;
static void compute_hashes(void)
{
    (void)__swarmlcm_robot_state_t_get_hash();
    (void)__swarmlcm_swarm_state_t_get_hash();
    (void)__swarmlcm_event_t_get_hash();
    (void)__swarmlcm_run_info_t_get_hash();
    (void)__swarmlcm_run_summary_t_get_hash();
    (void)__swarmlcm_schema_t_get_hash();
}

int telemetry_open(const telemetry_options_t *opt, const sim_t *simp, const char *log_path,
                   telemetry_t **out, char err[SIM_ERR_MAX])
{
    const struct sim *sim = simp;
    *out = NULL;
    if (!opt->enabled) {
        return 0;
    }
    pthread_once(&hashes_once, compute_hashes);
    telemetry_t *t = calloc(1, sizeof *t);
    uint32_t n = sim->n ? sim->n : 1;
    if (t) {
        t->n = sim->n;
        t->buf_size = 4096;
        t->buf = malloc(t->buf_size);
        for (uint32_t g = 0; g < sim->sc->group_count; g++) {   /* the most a robot has */
            uint32_t c = 0;
            for (const observable_t *o = sim->sc->groups[g].def->observables; o && o->name; o++) {
                c += o->kind == OBS_COUNTER;
            }
            t->n_counters = c > t->n_counters ? c : t->n_counters;
        }
        t->prev_counter = calloc((size_t)n * (t->n_counters ? t->n_counters : 1), sizeof *t->prev_counter);
        t->prev_state = calloc(n, sizeof *t->prev_state);
        t->prev_escaped = calloc(n, sizeof *t->prev_escaped);
        t->scene = telemetry_scene_create(sim);
    }
    if (!t || !t->buf || !t->prev_counter || !t->prev_state || !t->prev_escaped || !t->scene) {
        snprintf(err, SIM_ERR_MAX, "telemetry: out of memory");
        telemetry_close(t, 0, err);
        return -1;
    }
    if (uart_config(sim->sc)->enabled) {
        static const char *const names[TELEMETRY_CH_COUNT] = TELEMETRY_CHANNEL_NAMES;
        for (int c = 1; c < TELEMETRY_CH_COUNT; c++) {
            t->fw_channel_len[c] = snprintf(t->fw_channel[c], sizeof t->fw_channel[c], "%s%s",
                                            uart_config(sim->sc)->channel_prefix, names[c]);
        }
        if (uart_config(sim->sc)->dump && log_path) {
            const char *slash = strrchr(log_path, '/');
            size_t len = slash ? (size_t)(slash - log_path) : 0;
            snprintf(t->dump_dir, sizeof t->dump_dir, "%.*s%suart", (int)len, log_path, len ? "/" : "");
            t->dump = calloc(n, sizeof *t->dump);
            if (!t->dump || (mkdir(t->dump_dir, 0777) != 0 && errno != EEXIST)) {
                snprintf(err, SIM_ERR_MAX, "%.150s: cannot create: %.60s", t->dump_dir, strerror(errno ? errno : ENOMEM));
                telemetry_close(t, 0, err);
                return -1;
            }
        }
    }
    t->seed = sim->seed;
    t->robot_hz = opt->robot_hz;
    t->swarm_hz = opt->swarm_hz;
    t->robot_every = every_steps(opt->robot_hz, sim->sc->control_period_ms);
    t->swarm_every = every_steps(opt->swarm_hz, sim->sc->control_period_ms);
    t->info_every = every_steps(1.0 / INFO_PERIOD_S, sim->sc->control_period_ms);
    t->realtime = opt->realtime;
    if (opt->url) {
        /* Live listeners lose what comes while their queue is full (an LCM
         * subscription holds 30 unhandled messages by default): the summary,
         * sent right after the last burst of states, waits until they have
         * taken that burst.  memq:// has no listener running meanwhile. */
        t->summary_pause_s = strncmp(opt->url, "memq://", 7) ? 0.05 + 1e-4 * (double)n : 0.0;
        t->lcm = lcm_create(opt->url);
        if (!t->lcm) {
            snprintf(err, SIM_ERR_MAX, "telemetry: cannot open LCM URL '%s' (see lcm_create's message above)", opt->url);
            telemetry_close(t, 0, err);
            return -1;
        }
    } else {
        if (snprintf(t->path, sizeof t->path, "%s", log_path) >= (int)sizeof t->path) {
            snprintf(err, SIM_ERR_MAX, "telemetry: log path too long");
            telemetry_close(t, 0, err);
            return -1;
        }
        snprintf(t->tmp, sizeof t->tmp, "%s.tmp", log_path);
        t->log = fopen(t->tmp, "wb");
        if (!t->log) {
            snprintf(err, SIM_ERR_MAX, "%.150s: cannot write: %.60s", t->tmp, strerror(errno));
            t->tmp[0] = '\0';
            telemetry_close(t, 0, err);
            return -1;
        }
        /* One thread writes this file: no stdio locking, and a larger buffer. */
        __fsetlocking(t->log, FSETLOCKING_BYCALLER);
        setvbuf(t->log, NULL, _IOFBF, 1 << 16);
    }
    clock_gettime(CLOCK_MONOTONIC, &t->wall0);
    *out = t;
    return 0;
}

/* An LCM log event's header: magic, event number, timestamp, channel
 * length, data length (big-endian), then the channel name. */
#define LOG_MAGIC 0xEDA1DA01u
#define LOG_HEADER 28

static void put_be(uint8_t *p, uint64_t v, int bytes)
{
    for (int k = bytes - 1; k >= 0; k--) {
        p[k] = (uint8_t)(v & 0xFF);
        v >>= 8;
    }
}

/* Publishes the `len` bytes at buf + off, an encoded message; the `off`
 * bytes before it are room for the log event's header and channel. */
static void publish(telemetry_t *t, const char *channel, int channel_len, uint8_t *buf, int off, int len,
                    int64_t utime)
{
    t->messages++;
    if (t->log) {
        put_be(buf, LOG_MAGIC, 4);
        put_be(buf + 4, (uint64_t)t->log_events++, 8);
        put_be(buf + 12, (uint64_t)utime, 8);
        put_be(buf + 20, (uint64_t)channel_len, 4);
        put_be(buf + 24, (uint64_t)len, 4);
        memcpy(buf + LOG_HEADER, channel, (size_t)channel_len);
        if (fwrite(buf, (size_t)(off + len), 1, t->log) != 1 && !t->write_error) {
            t->write_error = errno ? errno : EIO;
        }
    } else if (lcm_publish(t->lcm, channel, buf + off, (unsigned)len) != 0) {
        t->publish_errors++;
    }
}

static uint8_t *reserve(telemetry_t *t, int size)
{
    if ((size_t)size > t->buf_size) {
        size_t want = t->buf_size;
        while (want < (size_t)size) want *= 2;
        uint8_t *b = realloc(t->buf, want);
        if (!b) {
            return NULL;
        }
        t->buf = b;
        t->buf_size = want;
    }
    return t->buf;
}

/* Encodes `msg` of lcm-gen type TYPE after room for the log header and
 * publishes it on CHANNEL (a string literal). */
#define SEND(t, TYPE, channel, msg, utime) do {                                   \
        int chlen_ = (int)sizeof(channel) - 1, off_ = LOG_HEADER + chlen_;         \
        int size_ = TYPE##_encoded_size(msg);                                     \
        uint8_t *b_ = reserve((t), off_ + size_);                                  \
        if (b_ && TYPE##_encode(b_, off_, size_, (msg)) == size_) {                \
            publish((t), (channel), chlen_, b_, off_, size_, (utime));             \
        } else if (!(t)->write_error) {                                            \
            (t)->write_error = ENOMEM;                                             \
        }                                                                          \
    } while (0)

/* ------------------------------------------------------------ robots' own frames */

/* What robot i's image sent this step, republished as the bridge does
 * (the payload as it came, on the prefixed channel of its id), and its raw
 * bytes dumped when asked. */
static void send_robot_frames(telemetry_t *t, const struct sim *sim, uint32_t i)
{
    const robot_link_t *l = sim_robot_link(sim, i);
    for (uint8_t k = 0; k < l->n_frames; k++) {
        const robot_link_frame_t *f = &l->frames[k];
        int off = LOG_HEADER + t->fw_channel_len[f->channel];
        uint8_t *b = reserve(t, off + f->len);
        if (!b) {
            t->write_error = t->write_error ? t->write_error : ENOMEM;
            return;
        }
        memcpy(b + off, f->payload, f->len);
        publish(t, t->fw_channel[f->channel], t->fw_channel_len[f->channel], b, off, f->len, utime_of(sim));
    }
    if (t->dump && l->raw_len) {
        if (!t->dump[i]) {
            char path[1100];
            snprintf(path, sizeof path, "%s/robot_%u.bin", t->dump_dir, i);
            t->dump[i] = fopen(path, "wb");
        }
        if (!t->dump[i] || fwrite(l->raw, l->raw_len, 1, t->dump[i]) != 1) {
            t->write_error = t->write_error ? t->write_error : (errno ? errno : EIO);
        }
    }
}

/* ------------------------------------------------------------ robot state */

/* Most values a controller declares that telemetry sends. */
#define MAX_VALUES 64

static void robot_message(const telemetry_t *t, const struct sim *sim, uint32_t i,
                          swarmlcm_robot_state_t *m, float *values)
{
    const sim_robot_t *r = &sim->robots[i];
    m->version = SWARMLCM_ROBOT_STATE_T_VERSION;
    m->utime = utime_of(sim);
    m->run = (int64_t)t->seed;
    m->robot_id = (int16_t)i;
    m->group = (char *)sim->sc->groups[r->group].name;
    m->controller = (char *)r->def->name;
    m->state = (char *)sim_robot_state_name(sim, i);
    robot_telemetry_platform_t p;
    sim_robot_platform(sim, i, 1, &p);   /* the latest readings, whenever taken */
    m->wheel_left = p.wheel_left;
    m->wheel_right = p.wheel_right;
    m->leds = p.leds;
    m->ir_max = p.ir_max;
    m->ir_max_index = p.ir_max_index;
    m->ambient_min = p.ambient_min;
    m->blobs = p.blobs;
    m->pose_known = 1;
    m->x = r->x;
    m->y = r->y;
    m->theta = r->theta;
    m->n_values = 0;
    m->values = values;
    for (const observable_t *o = r->def->observables; r->ctrl && o && o->name && m->n_values < MAX_VALUES; o++) {
        values[m->n_values++] = observable_read(o, r->ctrl);
    }
}

static void nap(double s)
{
    struct timespec d = { (time_t)s, (long)((s - floor(s)) * 1e9) };
    nanosleep(&d, NULL);
}

static void send_robots(telemetry_t *t, const struct sim *sim)
{
    swarmlcm_robot_state_t m;
    float values[MAX_VALUES];
    /* Watched live (--realtime on a bus), every robot's state would leave in
     * the same instant, more at once than a listener's queue holds (30 by
     * default in LCM): they are spread over at most half of the step's wall
     * time, 1 ms apart at most.  The log file is written as before. */
    double gap = (t->lcm && t->realtime > 0) ? sim->sc->control_period_ms / 1000.0 / t->realtime / (2.0 * sim->n) : 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        robot_message(t, sim, i, &m, values);
        SEND(t, swarmlcm_robot_state_t, TELEMETRY_CHANNEL_ROBOT_STATE, &m, m.utime);
        if (gap > 0) nap(gap < 1e-3 ? gap : 1e-3);
    }
    t->robot_sent_step = sim->step + 1;
}

/* ------------------------------------------------------------ swarm state */

static void count_states(telemetry_t *t, const struct sim *sim)
{
    for (uint16_t s = 0; s < t->n_states; s++) {
        t->state_counts[s] = 0;
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        const char *name = sim_robot_state_name(sim, i);
        uint16_t s = 0;
        while (s < t->n_states && t->state_names[s] != name) {
            s++;
        }
        if (s == t->n_states) {   /* the same name at another address? */
            s = 0;
            while (s < t->n_states && strcmp(t->state_names[s], name) != 0) {
                s++;
            }
        }
        if (s == t->n_states) {
            if (s == MAX_STATES) {
                continue;
            }
            t->state_names[s] = name;
            t->n_states++;
        }
        t->state_counts[s]++;
    }
}

static void send_swarm(telemetry_t *t, const struct sim *sim)
{
    metric_list_t row;
    swarmlcm_swarm_state_t m;
    metrics_sample(sim, &row);
    count_states(t, sim);
    m.version = SWARMLCM_SWARM_STATE_T_VERSION;
    m.utime = utime_of(sim);
    m.run = (int64_t)t->seed;
    m.step = (int64_t)sim->step;
    m.robots = (int32_t)sim->n;
    m.n_states = (int16_t)t->n_states;
    m.state_names = (char **)t->state_names;
    m.state_counts = t->state_counts;
    m.n_values = (int16_t)row.count;
    m.values = row.value;
    SEND(t, swarmlcm_swarm_state_t, TELEMETRY_CHANNEL_SWARM_STATE, &m, m.utime);
    t->swarm_sent_step = sim->step + 1;
}

/* ------------------------------------------------------------ run info and schemas */

static void send_schema(telemetry_t *t, const struct sim *sim, const char *kind, const char *name,
                        int16_t n, char **names, char **units, int8_t *counters, char **docs)
{
    swarmlcm_schema_t m;
    m.version = SWARMLCM_SCHEMA_T_VERSION;
    m.utime = utime_of(sim);
    m.run = (int64_t)t->seed;
    m.kind = (char *)kind;
    m.name = (char *)name;
    m.total = n;
    m.first = 0;
    m.n = n;
    m.names = names;
    m.units = units;
    m.counters = counters;
    m.docs = docs;
    SEND(t, swarmlcm_schema_t, TELEMETRY_CHANNEL_SCHEMA, &m, m.utime);
}

/* One schema per controller the groups run, and the swarm's. */
static void send_schemas(telemetry_t *t, const struct sim *sim)
{
    const scenario_t *sc = sim->sc;
    char *names[METRICS_MAX > MAX_VALUES ? METRICS_MAX : MAX_VALUES];
    char *units[METRICS_MAX > MAX_VALUES ? METRICS_MAX : MAX_VALUES];
    char *docs[METRICS_MAX > MAX_VALUES ? METRICS_MAX : MAX_VALUES];
    int8_t counters[METRICS_MAX > MAX_VALUES ? METRICS_MAX : MAX_VALUES];
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const controller_def_t *def = sc->groups[g].def;
        uint32_t h = 0;
        while (h < g && sc->groups[h].def != def) {
            h++;
        }
        if (h < g) {
            continue;   /* sent with an earlier group */
        }
        int16_t n = 0;
        for (const observable_t *o = def->observables; def->state_size && o && o->name && n < MAX_VALUES; o++, n++) {
            names[n] = (char *)o->name;
            units[n] = (char *)(o->unit ? o->unit : "");
            docs[n] = (char *)(o->doc ? o->doc : "");
            counters[n] = o->kind == OBS_COUNTER;
        }
        send_schema(t, sim, "controller", def->name, n, names, units, counters, docs);
    }
    metric_list_t row;
    metrics_sample(sim, &row);
    for (unsigned k = 0; k < row.count; k++) {
        names[k] = (char *)row.name[k];
        units[k] = (char *)row.unit[k];
        docs[k] = (char *)row.doc[k];
        counters[k] = 0;
    }
    send_schema(t, sim, "swarm", "swarm", (int16_t)row.count, names, units, counters, docs);
}

static void send_info(telemetry_t *t, const struct sim *sim)
{
    const scenario_t *sc = sim->sc;
    swarmlcm_run_info_t m;
    char *gnames[SCENARIO_MAX_GROUPS], *gctrl[SCENARIO_MAX_GROUPS], *gpol[SCENARIO_MAX_GROUPS];
    int32_t gcount[SCENARIO_MAX_GROUPS];
    char *tasks[SCENARIO_MAX_TASKS];
    for (uint32_t g = 0; g < sc->group_count; g++) {
        gnames[g] = (char *)sc->groups[g].name;
        gctrl[g] = (char *)sc->groups[g].controller;
        gpol[g] = (char *)sc->groups[g].policy;
        gcount[g] = (int32_t)sc->groups[g].count;
    }
    for (uint32_t k = 0; k < sc->task_count; k++) {
        tasks[k] = (char *)sc->tasks[k].def->name;
    }
    m.version = SWARMLCM_RUN_INFO_T_VERSION;
    m.utime = utime_of(sim);
    m.run = (int64_t)t->seed;
    m.scenario = (char *)sc->name;
    m.scenario_file = (char *)sc->path;
    m.steps = (int64_t)t->steps;
    m.control_period_ms = sc->control_period_ms;
    m.arena_width = sc->arena.width;
    m.arena_height = sc->arena.height;
    m.robots = (int32_t)sim->n;
    m.n_groups = (int16_t)sc->group_count;
    m.group_names = gnames;
    m.group_controllers = gctrl;
    m.group_policies = gpol;
    m.group_counts = gcount;
    m.n_tasks = (int16_t)sc->task_count;
    m.tasks = tasks;
    m.robot_state_hz = (float)t->robot_hz;
    m.swarm_state_hz = (float)t->swarm_hz;
    SEND(t, swarmlcm_run_info_t, TELEMETRY_CHANNEL_RUN_INFO, &m, m.utime);
    send_schemas(t, sim);
}

/* The arena (with `force`: at the start and with RUN_INFO) and the tasks'
 * drawing (then too, and whenever it changed). */
static void send_scene(telemetry_t *t, const struct sim *sim, int force)
{
    swarmlcm_scene_t s;
    swarmlcm_task_drawing_t d;
    if (force) {
        telemetry_scene_fill(t->scene, sim, &s);
        SEND(t, swarmlcm_scene_t, TELEMETRY_CHANNEL_SCENE, &s, s.utime);
    }
    int due = telemetry_scene_drawing(t->scene, sim, force, &d);
    if (due > 0) {
        SEND(t, swarmlcm_task_drawing_t, TELEMETRY_CHANNEL_TASK_DRAWING, &d, d.utime);
    } else if (due < 0 && !t->write_error) {
        t->write_error = ENOMEM;
    }
}

/* ------------------------------------------------------------ events */

static void send_event(telemetry_t *t, const struct sim *sim, uint32_t i, const char *kind,
                       const char *detail, int32_t val)
{
    swarmlcm_event_t e;
    e.version = SWARMLCM_EVENT_T_VERSION;
    e.utime = utime_of(sim);
    e.run = (int64_t)t->seed;
    e.robot_id = (int16_t)i;
    e.kind = (char *)kind;
    e.detail = (char *)detail;
    e.value = val;
    e.pose_known = 1;
    e.x = sim->robots[i].x;
    e.y = sim->robots[i].y;
    SEND(t, swarmlcm_event_t, TELEMETRY_CHANNEL_EVENT, &e, e.utime);
}

void telemetry_event(telemetry_t *t, const sim_t *simp, int32_t robot, const char *kind, const char *detail,
                     int32_t value)
{
    const struct sim *sim = simp;
    if (!t) {
        return;
    }
    if (robot >= 0 && (uint32_t)robot < sim->n) {
        send_event(t, sim, (uint32_t)robot, kind, detail, value);
        return;
    }
    swarmlcm_event_t e;
    e.version = SWARMLCM_EVENT_T_VERSION;
    e.utime = utime_of(sim);
    e.run = (int64_t)t->seed;
    e.robot_id = -1;
    e.kind = (char *)kind;
    e.detail = (char *)detail;
    e.value = value;
    e.pose_known = 0;
    e.x = e.y = 0.0f;
    SEND(t, swarmlcm_event_t, TELEMETRY_CHANNEL_EVENT, &e, e.utime);
}

/* Robot i's state now, to tell the next step's events against. */
static void remember(telemetry_t *t, const struct sim *sim, uint32_t i)
{
    const sim_robot_t *r = &sim->robots[i];
    float *prev = t->prev_counter + (size_t)i * t->n_counters;
    uint32_t c = 0;
    for (const observable_t *o = r->def->observables; r->ctrl && o && o->name; o++) {
        if (o->kind == OBS_COUNTER) {
            prev[c++] = observable_read(o, r->ctrl);
        }
    }
    t->prev_state[i] = sim_robot_state_name(sim, i);
    t->prev_escaped[i] = r->escaped;
}

/* The events of robot i in the last step, each told once: what changed
 * since the previous step.  Then remembers the new state. */
static void robot_events(telemetry_t *t, const struct sim *sim, uint32_t i)
{
    const sim_robot_t *r = &sim->robots[i];
    float *prev = t->prev_counter + (size_t)i * t->n_counters;
    char detail[DETAIL_MAX];
    uint32_t c = 0;
    for (const observable_t *o = r->def->observables; r->ctrl && o && o->name; o++) {
        if (o->kind != OBS_COUNTER) {
            continue;
        }
        float now = observable_read(o, r->ctrl);
        for (float k = prev[c] + 1.0f; k <= now; k += 1.0f) {
            send_event(t, sim, i, o->name, "", (int32_t)k);
        }
        prev[c++] = now;
    }
    const char *state = sim_robot_state_name(sim, i);
    if (state != t->prev_state[i] && strcmp(state, t->prev_state[i]) != 0) {
        snprintf(detail, sizeof detail, "%s->%s", t->prev_state[i], state);
        send_event(t, sim, i, "state", detail, 0);
    }
    t->prev_state[i] = state;
    if (r->escaped != t->prev_escaped[i]) {
        if (r->escaped) {
            send_event(t, sim, i, "escaped", "", 0);
        }
        t->prev_escaped[i] = r->escaped;
    }
}

/* ------------------------------------------------------------ the run */

void telemetry_begin(telemetry_t *t, const sim_t *simp, uint64_t steps)
{
    const struct sim *sim = simp;
    if (!t) {
        return;
    }
    t->steps = steps;
    for (uint32_t i = 0; i < sim->n; i++) {
        remember(t, sim, i);
    }
    send_info(t, sim);
    send_scene(t, sim, 1);
    if (t->swarm_every) send_swarm(t, sim);
    if (t->robot_every) send_robots(t, sim);
}

static void pace(telemetry_t *t, const struct sim *sim)
{
    double sim_s = (double)sim->step * sim->sc->control_period_ms / 1000.0;
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    double wall = (double)(now.tv_sec - t->wall0.tv_sec) + 1e-9 * (double)(now.tv_nsec - t->wall0.tv_nsec);
    double ahead = sim_s / t->realtime - wall;
    if (ahead > 0.001) {
        nap(ahead);
    }
}

void telemetry_set_realtime(telemetry_t *t, const sim_t *simp, double factor)
{
    const struct sim *sim = simp;
    if (!t || !(factor > 0.0)) {
        return;
    }
    double sim_s = (double)sim->step * sim->sc->control_period_ms / 1000.0;
    double back = sim_s / factor;
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    double whole = floor(back);
    long ns = (long)((back - whole) * 1e9);
    t->wall0.tv_sec = now.tv_sec - (time_t)whole;
    t->wall0.tv_nsec = now.tv_nsec - ns;
    if (t->wall0.tv_nsec < 0) {
        t->wall0.tv_nsec += 1000000000L;
        t->wall0.tv_sec--;
    }
    t->realtime = factor;
}

void telemetry_step(telemetry_t *t, const sim_t *simp)
{
    const struct sim *sim = simp;
    const sim_event_rec_t *ev;
    if (!t) {
        return;
    }
    uint32_t n_ev = sim_events(simp, &ev);
    for (uint32_t k = 0; k < n_ev; k++) {
        send_event(t, sim, ev[k].robot, ev[k].kind, ev[k].detail, ev[k].value);
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        robot_events(t, sim, i);
    }
    for (uint32_t i = 0; sim_robot_link(sim, 0) && i < sim->n; i++) {
        send_robot_frames(t, sim, i);
    }
    int info_due = t->info_every && sim->step % t->info_every == 0;
    int swarm_due = t->swarm_every && sim->step % t->swarm_every == 0;
    if (info_due) send_info(t, sim);
    if (info_due || swarm_due) send_scene(t, sim, info_due);
    if (swarm_due) send_swarm(t, sim);
    if (t->robot_every && sim->step % t->robot_every == 0) send_robots(t, sim);
    if (t->realtime > 0) pace(t, sim);
}

void telemetry_end(telemetry_t *t, const sim_t *simp, const metric_list_t *final, uint64_t state_hash)
{
    const struct sim *sim = simp;
    const scenario_t *sc = sim->sc;
    if (!t) {
        return;
    }
    send_scene(t, sim, 0);
    if (t->swarm_every && t->swarm_sent_step != sim->step + 1) send_swarm(t, sim);
    if (t->robot_every && t->robot_sent_step != sim->step + 1) send_robots(t, sim);
    char hash[17];
    char *names[METRICS_MAX];
    double values[METRICS_MAX];
    snprintf(hash, sizeof hash, "%016llx", (unsigned long long)state_hash);
    for (unsigned k = 0; k < final->count; k++) {
        names[k] = (char *)final->name[k];
        values[k] = final->value[k];
    }
    swarmlcm_run_summary_t m;
    m.version = SWARMLCM_RUN_SUMMARY_T_VERSION;
    m.utime = utime_of(sim);
    m.run = (int64_t)t->seed;
    m.scenario = (char *)sc->name;
    m.scenario_file = (char *)sc->path;
    m.robots = (int32_t)sim->n;
    m.steps = (int64_t)sim->step;
    m.control_period_ms = sc->control_period_ms;
    m.state_hash = hash;
    m.n_metrics = (int16_t)final->count;
    m.metric_names = names;
    m.metric_values = values;
    if (t->summary_pause_s > 0) nap(t->summary_pause_s);
    SEND(t, swarmlcm_run_summary_t, TELEMETRY_CHANNEL_RUN_SUMMARY, &m, m.utime);
}

int telemetry_close(telemetry_t *t, int keep, char err[SIM_ERR_MAX])
{
    int rc = 0;
    if (!t) {
        return 0;
    }
    if (t->log) {
        int bad = ferror(t->log);
        if ((fclose(t->log) != 0 || bad) && !t->write_error) {
            t->write_error = errno ? errno : EIO;
        }
        if (keep && !t->write_error && rename(t->tmp, t->path) != 0) {
            t->write_error = errno;
        }
        if (!keep || t->write_error) {
            remove(t->tmp);
        }
        if (keep && t->write_error) {
            snprintf(err, SIM_ERR_MAX, "%.150s: cannot write: %.60s", t->path, strerror(t->write_error));
            rc = -1;
        }
    }
    if (t->lcm) {
        if (t->publish_errors) {
            fprintf(stderr, "swarmsim: telemetry: %llu of %llu messages could not be published\n",
                    (unsigned long long)t->publish_errors, (unsigned long long)t->messages);
        }
        lcm_destroy(t->lcm);
    }
    for (uint32_t i = 0; t->dump && i < t->n; i++) {
        if (t->dump[i] && fclose(t->dump[i]) != 0 && !t->write_error) {
            t->write_error = errno ? errno : EIO;
        }
    }
    free(t->dump);
    free(t->buf);
    free(t->prev_counter);
    free(t->prev_state);
    free(t->prev_escaped);
    telemetry_scene_destroy(t->scene);
    free(t);
    return rc;
}

uint64_t telemetry_message_count(const telemetry_t *t) { return t ? t->messages : 0; }

double telemetry_realtime(const telemetry_t *t) { return t ? t->realtime : 0.0; }

struct _lcm_t *telemetry_lcm(telemetry_t *t) { return t ? t->lcm : NULL; }
