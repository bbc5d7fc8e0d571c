/*
 * control.c - commands to a running simulation over LCM (control.h).
 */
#include "control.h"

#include <stdarg.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lcm/lcm.h>

#include "models/model.h"
#include "schema.h"
#include "sim_internal.h"
#include "swarmlcm_control_status_t.h"
#include "swarmlcm_control_t.h"
#include "swarmlcm_robot_detail_t.h"
#include "units.h"

/** Seconds of wall time between two statuses. */
#define STATUS_PERIOD_S 0.5
/** Milliseconds a paused run waits for a command before it looks at *stop. */
#define PAUSED_POLL_MS 100
/** Commands summary.json lists (all are counted, and all are events). */
#define RECORD_MAX 1000
#define TEXT_MAX 240
/** Live keys a robot's details list. */
#define DETAIL_PARAMS_MAX 32
#define VALUE_MAX 40

struct control {
    lcm_t *lcm;
    swarmlcm_control_t_subscription_t *sub;
    sim_t *sim;
    telemetry_t *tel;
    char key[33];
    int paused;
    int64_t steps;               /* the run's */
    int64_t pending;             /* steps of a `step` command still to run */
    double realtime;
    int32_t selected;            /* -1: none */
    /* Each robot's state as last seen and the step it was first seen in it
     * (robot_detail_t's state_time_s): kept for every robot, from the run's
     * start, so that selecting a robot shows its whole time in its state. */
    const char **state_seen;
    int64_t *state_since;
    int32_t commands;            /* recorded */
    int touched;
    uint64_t foreign;            /* commands with another key, ignored */
    /* The answer to the latest command. */
    int64_t seq;
    int ok;
    char text[TEXT_MAX];
    double status_at;            /* wall time of the last status */
    /* summary.json's lines, as a memstream. */
    char *record;
    size_t record_len;
    FILE *record_f;
};

static double wall_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* 16 random bytes as hex: from the system's source, never from the run's
 * streams (the run must not know it is controlled). */
static int make_key(char out[33])
{
    uint8_t b[16];
    FILE *f = fopen("/dev/urandom", "rb");
    size_t got = f ? fread(b, 1, sizeof b, f) : 0;
    if (f) fclose(f);
    if (got != sizeof b) {
        return -1;
    }
    for (int k = 0; k < 16; k++) {
        snprintf(out + 2 * k, 3, "%02x", b[k]);
    }
    return 0;
}

static void send_status(control_t *c)
{
    const struct sim *sim = c->sim;
    swarmlcm_control_status_t m;
    m.version = SWARMLCM_CONTROL_STATUS_T_VERSION;
    m.utime = (int64_t)sim->step * sim->sc->control_period_ms * 1000;
    m.run = (int64_t)sim->seed;
    m.key = c->key;
    m.step = (int64_t)sim->step;
    m.steps = c->steps;
    m.paused = c->paused && c->pending == 0;
    m.steps_pending = c->pending;
    m.realtime = c->realtime;
    m.selected = c->selected;
    m.commands = c->commands;
    m.seq = c->seq;
    m.ok = c->ok;
    m.text = c->text;
    swarmlcm_control_status_t_publish(c->lcm, CONTROL_CHANNEL_STATUS, &m);
    c->status_at = wall_s();
}

/* Robot i's latest readings (model.h's model_inspect_t) and what its
 * robot_state_t would say. */
static void send_detail(control_t *c)
{
    const struct sim *sim = c->sim;
    if (c->selected < 0 || (uint32_t)c->selected >= sim->n) {
        return;
    }
    uint32_t i = (uint32_t)c->selected;
    const sim_robot_t *r = &sim->robots[i];
    model_inspect_t in;
    sim_robot_inspect(sim, i, &in);
    robot_telemetry_platform_t p;
    sim_robot_platform(sim, i, 1, &p);
    float values[64];
    int8_t blob_colour[HAL_MAX_BLOBS];
    int16_t blob_bearing[HAL_MAX_BLOBS], blob_width[HAL_MAX_BLOBS];
    float mic[HAL_SOUND_BANDS];
    int32_t heard_value[MODEL_INSPECT_HEARD];
    int16_t heard_bearing[MODEL_INSPECT_HEARD], heard_range[MODEL_INSPECT_HEARD];
    int16_t prox[HAL_IR_COUNT], ambient[HAL_IR_COUNT];

    swarmlcm_robot_detail_t m;
    memset(&m, 0, sizeof m);
    m.version = SWARMLCM_ROBOT_DETAIL_T_VERSION;
    m.utime = (int64_t)sim->step * sim->sc->control_period_ms * 1000;
    m.run = (int64_t)sim->seed;
    m.robot_id = (int16_t)i;
    m.controller = (char *)r->def->name;
    m.state = (char *)sim_robot_state_name(sim, i);
    m.state_time_s = (float)((double)(sim->step - (uint64_t)c->state_since[i]) * sim->sc->control_period_ms / 1000.0);
    m.x = r->x;
    m.y = r->y;
    m.theta = r->theta;
    m.wheel_left = p.wheel_left;
    m.wheel_right = p.wheel_right;
    m.leds = p.leds;
    m.values = values;
    for (const observable_t *o = r->def->observables; r->ctrl && o && o->name && m.n_values < 64; o++) {
        values[m.n_values++] = observable_read(o, r->ctrl);
    }
    m.prox_known = in.prox_known != 0;
    m.ambient_known = in.ambient_known != 0;
    for (uint32_t k = 0; k < HAL_IR_COUNT; k++) {
        prox[k] = (int16_t)in.prox[k];
        ambient[k] = (int16_t)in.ambient[k];
        m.prox[k] = prox[k];
        m.ambient[k] = ambient[k];
        m.ir_bearing_mrad[k] = in.ir_bearing_mrad[k];
    }
    m.n_blobs = in.n_blobs;
    for (int8_t k = 0; k < in.n_blobs; k++) {
        blob_colour[k] = (int8_t)in.blobs[k].colour;
        blob_bearing[k] = in.blobs[k].bearing_mrad;
        blob_width[k] = (int16_t)(in.blobs[k].width_mrad > INT16_MAX ? INT16_MAX : in.blobs[k].width_mrad);
    }
    if (m.n_blobs < 0) {
        m.n_blobs = 0;   /* the array's length; the camera not read yet shows no blobs */
    }
    m.blob_colour = blob_colour;
    m.blob_bearing_mrad = blob_bearing;
    m.blob_width_mrad = blob_width;
    m.camera_fov_rad = in.camera_fov_rad;
    m.camera_range_m = in.camera_range_m;
    m.n_bands = (int8_t)in.n_bands;
    for (uint8_t k = 0; k < in.n_bands; k++) {
        mic[k] = in.mic[k + 1];
    }
    m.mic = mic;
    m.n_heard = (int8_t)in.n_heard;
    for (uint8_t k = 0; k < in.n_heard; k++) {
        heard_value[k] = in.heard[k].value;
        heard_bearing[k] = in.heard[k].bearing_mrad;
        heard_range[k] = (int16_t)(in.heard[k].range_mm > INT16_MAX ? INT16_MAX : in.heard[k].range_mm);
    }
    m.heard_value = heard_value;
    m.heard_bearing_mrad = heard_bearing;
    m.heard_range_mm = heard_range;
    m.ircom_range_m = in.ircom_range_m;
    char names[DETAIL_PARAMS_MAX][VALUE_MAX], shown[DETAIL_PARAMS_MAX][VALUE_MAX], ranges[DETAIL_PARAMS_MAX][VALUE_MAX];
    char *name_p[DETAIL_PARAMS_MAX], *value_p[DETAIL_PARAMS_MAX], *range_p[DETAIL_PARAMS_MAX];
    m.group = (char *)sim->sc->groups[r->group].name;
    for (const param_desc_t *d = r->def->params; r->ctrl && r->def->params_in_state && d && d->key; d++) {
        if (d->live && m.n_params < DETAIL_PARAMS_MAX) {
            int k = m.n_params++;
            snprintf(names[k], VALUE_MAX, "%s", d->key);
            schema_format_value(d, (const uint8_t *)r->ctrl + r->def->params_offset, shown[k], VALUE_MAX);
            schema_format_range(d, ranges[k], VALUE_MAX);
            name_p[k] = names[k], value_p[k] = shown[k], range_p[k] = ranges[k];
        }
    }
    m.param_names = name_p;
    m.param_values = value_p;
    m.param_ranges = range_p;
    swarmlcm_robot_detail_t_publish(c->lcm, CONTROL_CHANNEL_DETAIL, &m);
}

/* A command done: an event, a line of the summary. */
static void record(control_t *c, int32_t robot, const char *detail, int32_t value)
{
    telemetry_event(c->tel, c->sim, robot, "control", detail, value);
    if (c->record_f && c->commands < RECORD_MAX) {
        fprintf(c->record_f, "%s{\"step\": %llu, \"robot\": %d, \"command\": \"%s\"}", c->commands ? ",\n      " : "",
                (unsigned long long)sim_step_count(c->sim), (int)robot, detail);
    }
    c->commands++;
}

/* The answer: ok, or why not (nothing changed). */
static int refuse(control_t *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int refuse(control_t *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->text, sizeof c->text, fmt, ap);
    va_end(ap);
    c->ok = 0;
    return -1;
}

/* The live keys of `def`, for messages: "alpha, beta" or "none". */
static void live_keys(const controller_def_t *def, char *buf, size_t len)
{
    buf[0] = '\0';
    for (const param_desc_t *d = def->params; def->params_in_state && d && d->key; d++) {
        if (d->live) {
            schema_list_key(buf, len, d->key);
        }
    }
    if (!buf[0]) {
        snprintf(buf, len, "none");
    }
}

/* `set`: a live key of one robot's controller or of a whole group's,
 * checked as the scenario's loader checks it, then written into each
 * robot's state (controller.h: CONTROLLER_LIVE_PARAMS), all or nothing. */
static void set_param(control_t *c, const swarmlcm_control_t *m)
{
    struct sim *sim = c->sim;
    const scenario_t *sc = sim->sc;
    char detail[TEXT_MAX], keys[120], value[VALUE_MAX], err[SIM_ERR_MAX];
    uint32_t first, end, g;
    if (m->group[0]) {
        for (g = 0; g < sc->group_count && strcmp(sc->groups[g].name, m->group) != 0; g++) {
        }
        if (g == sc->group_count) {
            char names[120] = "";
            for (uint32_t k = 0; k < sc->group_count; k++) {
                schema_list_key(names, sizeof names, sc->groups[k].name);
            }
            refuse(c, "set: no group '%.40s' in this run (its groups: %s)", m->group, names);
            return;
        }
        for (first = 0; first < sim->n && sim->robots[first].group != g; first++) {
        }
        for (end = first; end < sim->n && sim->robots[end].group == g; end++) {
        }
        if (first == end) {
            refuse(c, "set: group '%.40s' has no robots", m->group);
            return;
        }
    } else if (m->robot_id < 0 || (uint32_t)m->robot_id >= sim->n) {
        refuse(c, "set: no robot %d in this run (ids 0 to %u)", (int)m->robot_id, sim->n - 1u);
        return;
    } else {
        first = (uint32_t)m->robot_id;
        end = first + 1u;
    }
    const sim_robot_t *r0 = &sim->robots[first];
    const controller_def_t *def = r0->def;
    const param_desc_t *d = def->params;
    while (d && d->key && strcmp(d->key, m->param) != 0) {
        d++;
    }
    live_keys(def, keys, sizeof keys);
    if (!d || !d->key) {
        refuse(c, "set: %s has no key '%.40s' (live keys: %s)", def->name, m->param, keys);
        return;
    }
    if (!d->live || !def->params_in_state || !r0->ctrl) {
        refuse(c, "set: %s's key '%s' is not settable while the run goes: its init derives from it "
               "(live keys: %s)", def->name, d->key, keys);
        return;
    }
    for (uint32_t i = first; i < end; i++) {
        if (sim->robots[i].step != def->step) {
            refuse(c, "set: robot %u runs its image on an emulated MCU (PIL): its parameters are in the image", i);
            return;
        }
    }
    uint8_t *p0 = (uint8_t *)r0->ctrl + def->params_offset;
    uint8_t tmp[SCENARIO_CONTROLLER_PARAMS_MAX];
    memcpy(tmp, p0, def->params_size < sizeof tmp ? def->params_size : sizeof tmp);
    if (schema_fill_text(d, m->param_value, "set", tmp, err, sizeof err) != 0) {
        refuse(c, "%s", err);
        return;
    }
    for (uint32_t i = first; i < end; i++) {
        memcpy((uint8_t *)sim->robots[i].ctrl + def->params_offset + d->offset, tmp + d->offset, d->size);
    }
    schema_format_value(d, tmp, value, sizeof value);
    c->touched = 1;
    if (m->group[0]) {
        snprintf(detail, sizeof detail, "set group %s %s %s", m->group, d->key, value);
        record(c, -1, detail, (int32_t)(end - first));
    } else {
        snprintf(detail, sizeof detail, "set %u %s %s", first, d->key, value);
        record(c, (int32_t)first, detail, 1);
    }
    send_detail(c);
}

/* One command with the right key: done, or refused with a reason. */
static void apply(control_t *c, const swarmlcm_control_t *m)
{
    struct sim *sim = c->sim;
    char detail[TEXT_MAX];
    const char *cmd = m->command;
    c->ok = 1;
    c->text[0] = '\0';
    if (m->version != SWARMLCM_CONTROL_T_VERSION) {
        refuse(c, "control_t version %d: this simulator takes version %d", m->version, SWARMLCM_CONTROL_T_VERSION);
    } else if (strcmp(cmd, "pause") == 0) {
        c->paused = 1;
        c->pending = 0;
        record(c, -1, "pause", 0);
    } else if (strcmp(cmd, "resume") == 0) {
        c->paused = 0;
        c->pending = 0;
        telemetry_set_realtime(c->tel, sim, c->realtime);
        record(c, -1, "resume", 0);
    } else if (strcmp(cmd, "step") == 0) {
        if (m->steps < 1 || m->steps > CONTROL_STEPS_MAX) {
            refuse(c, "step: %lld is not a number of control steps in [1, %lld]", (long long)m->steps,
                   CONTROL_STEPS_MAX);
        } else {
            c->paused = 1;
            c->pending = m->steps;
            telemetry_set_realtime(c->tel, sim, c->realtime);
            snprintf(detail, sizeof detail, "step %lld", (long long)m->steps);
            record(c, -1, detail, (int32_t)(m->steps > INT32_MAX ? INT32_MAX : m->steps));
        }
    } else if (strcmp(cmd, "realtime") == 0) {
        if (!(m->value > 0.0 && m->value <= 1e6)) {
            refuse(c, "realtime: %g is not a factor of real time in (0, 1e6]", m->value);
        } else {
            c->realtime = m->value;
            telemetry_set_realtime(c->tel, sim, c->realtime);
            snprintf(detail, sizeof detail, "realtime %g", m->value);
            record(c, -1, detail, 0);
        }
    } else if (strcmp(cmd, "move") == 0) {
        float hw = sim->hw - EPUCK_BODY_RADIUS_M, hh = sim->hh - EPUCK_BODY_RADIUS_M;
        if (m->robot_id < 0 || (uint32_t)m->robot_id >= sim->n) {
            refuse(c, "move: no robot %d in this run (ids 0 to %u)", (int)m->robot_id, sim->n - 1u);
        } else if (!isfinite(m->x) || !isfinite(m->y) || !isfinite(m->theta)) {
            refuse(c, "move: the pose (x, y, theta) must be finite numbers");
        } else if (fabsf(m->x) > hw || fabsf(m->y) > hh) {
            refuse(c, "move: (%.3f, %.3f) m is outside the arena (|x| <= %.3f, |y| <= %.3f m for a robot's body)",
                   (double)m->x, (double)m->y, (double)hw, (double)hh);
        } else {
            sim_set_robot_pose(sim, (uint32_t)m->robot_id, m->x, m->y, m->theta);
            c->touched = 1;
            snprintf(detail, sizeof detail, "move %d %.4f %.4f %.4f", (int)m->robot_id, (double)m->x,
                     (double)m->y, (double)m->theta);
            record(c, m->robot_id, detail, 0);
            send_detail(c);
        }
    } else if (strcmp(cmd, "select") == 0) {
        if (m->robot_id < -1 || (m->robot_id >= 0 && (uint32_t)m->robot_id >= sim->n)) {
            refuse(c, "select: no robot %d in this run (ids 0 to %u; -1: none)", (int)m->robot_id, sim->n - 1u);
        } else {
            c->selected = m->robot_id;
            send_detail(c);
        }
    } else if (strcmp(cmd, "set") == 0) {
        set_param(c, m);
    } else {
        char shown[41];
        snprintf(shown, sizeof shown, "%s", cmd);
        refuse(c, "unknown command '%s' (pause, resume, step, realtime, move, select, set)", shown);
    }
    c->seq = m->seq;
    send_status(c);
}

static void on_command(const lcm_recv_buf_t *rbuf, const char *channel, const swarmlcm_control_t *m, void *user)
{
    control_t *c = user;
    (void)rbuf;
    (void)channel;
    if (strcmp(m->key, c->key) != 0) {
        if (c->foreign++ == 0) {
            fprintf(stderr, "swarmsim: control: a command without this run's key was ignored "
                    "(a stale page, or another run's)\n");
        }
        return;
    }
    apply(c, m);
}

int control_open(const char *url, int paused, sim_t *sim, uint64_t steps, telemetry_t *tel, control_t **out,
                 char err[SIM_ERR_MAX])
{
    control_t *c = calloc(1, sizeof *c);
    *out = NULL;
    if (!c) {
        snprintf(err, SIM_ERR_MAX, "control: out of memory");
        return -1;
    }
    c->sim = sim;
    c->tel = tel;
    c->selected = -1;
    c->steps = (int64_t)steps;
    c->paused = paused != 0;
    c->seq = -1;
    c->ok = 1;
    c->realtime = telemetry_realtime(tel);
    c->record_f = open_memstream(&c->record, &c->record_len);
    c->state_seen = calloc(sim->n ? sim->n : 1, sizeof *c->state_seen);
    c->state_since = calloc(sim->n ? sim->n : 1, sizeof *c->state_since);
    if (!c->state_seen || !c->state_since) {
        snprintf(err, SIM_ERR_MAX, "control: out of memory");
        control_close(c);
        return -1;
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        const char *now = sim_robot_state_name(sim, i);
        c->state_seen[i] = now ? now : "";
        c->state_since[i] = (int64_t)sim->step;
    }
    if (!c->record_f || make_key(c->key) != 0) {
        snprintf(err, SIM_ERR_MAX, "control: %s", c->record_f ? "cannot read /dev/urandom for the key" : "out of memory");
        control_close(c);
        return -1;
    }
    c->lcm = lcm_create(url);
    if (!c->lcm) {
        snprintf(err, SIM_ERR_MAX, "--control-lcm %.200s: no LCM provider takes this URL", url);
        control_close(c);
        return -1;
    }
    c->sub = swarmlcm_control_t_subscribe(c->lcm, CONTROL_CHANNEL, on_command, c);
    if (!c->sub) {
        snprintf(err, SIM_ERR_MAX, "control: cannot subscribe to %s on %.200s", CONTROL_CHANNEL, url);
        control_close(c);
        return -1;
    }
    send_status(c);
    *out = c;
    return 0;
}

/* Handles what came; with wait_ms > 0 waits that long for something. */
static void take(control_t *c, int wait_ms)
{
    if (lcm_handle_timeout(c->lcm, wait_ms) > 0) {
        while (lcm_handle_timeout(c->lcm, 0) > 0) {
        }
    }
}

int control_before_step(control_t *c, const volatile sig_atomic_t *stop)
{
    if (!c) {
        return 0;
    }
    take(c, 0);
    for (;;) {
        if (stop && *stop) {
            return -1;
        }
        if (!c->paused) {
            return 0;
        }
        if (c->pending > 0) {
            c->pending--;
            return 0;
        }
        if (wall_s() - c->status_at >= STATUS_PERIOD_S) {
            send_status(c);
        }
        take(c, PAUSED_POLL_MS);
    }
}

/* Notes each robot that changed state in the step just done (controllers'
 * state names are string literals: the same pointer is the same name). */
static void track_states(control_t *c)
{
    for (uint32_t i = 0; i < c->sim->n; i++) {
        const char *now = sim_robot_state_name(c->sim, i);
        if (!now) {
            now = "";
        }
        if (now != c->state_seen[i] && strcmp(now, c->state_seen[i]) != 0) {
            c->state_since[i] = (int64_t)c->sim->step;
        }
        c->state_seen[i] = now;
    }
}

void control_after_step(control_t *c)
{
    if (!c) {
        return;
    }
    track_states(c);
    send_detail(c);
    if (c->paused && c->pending == 0) {
        send_status(c);     /* the step the page waited for is done */
    } else if (wall_s() - c->status_at >= STATUS_PERIOD_S) {
        send_status(c);
    }
}

int control_touched(const control_t *c) { return c && c->touched; }

char *control_json(const control_t *c)
{
    char *out = NULL;
    size_t len = 0;
    if (!c) {
        return NULL;
    }
    FILE *f = open_memstream(&out, &len);
    if (!f) {
        return NULL;
    }
    fflush(c->record_f);
    fprintf(f, "{\"touched\": %s, \"commands\": %d, \"listed\": [%s%s%s]}", c->touched ? "true" : "false",
            (int)c->commands, c->commands ? "\n      " : "", c->record ? c->record : "", c->commands ? "\n    " : "");
    if (fclose(f) != 0) {
        free(out);
        return NULL;
    }
    return out;
}

void control_close(control_t *c)
{
    if (!c) {
        return;
    }
    if (c->sub) swarmlcm_control_t_unsubscribe(c->lcm, c->sub);
    if (c->lcm) lcm_destroy(c->lcm);
    if (c->record_f) fclose(c->record_f);
    free(c->record);
    free(c->state_seen);
    free(c->state_since);
    free(c);
}
