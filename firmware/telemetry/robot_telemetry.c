/*
 * robot_telemetry.c - the robot's own robot_state_t and schema_t frames
 * (robot_telemetry.h), encoded by lcm-gen's C code of lcm_types/.
 */
#include "telemetry/robot_telemetry.h"

#include <math.h>

#include "swarmlcm_robot_state_t.h"
#include "swarmlcm_schema_t.h"

void robot_telemetry_init(robot_telemetry_t *t)
{
    telemetry_tx_init(&t->tx);
    t->countdown = 0u;
    t->schema_next = 0u;
}

static void queue(robot_telemetry_t *t, hal_t *hal, uint8_t channel, int n)
{
    if (n > 0) {
        (void)telemetry_tx_send(&t->tx, hal, channel, t->payload, (uint16_t)n);
    }
}

/* The observables sent: the table's, at most ROBOT_TELEMETRY_MAX_VALUES. */
static uint8_t value_count(const robot_telemetry_source_t *src)
{
    uint8_t n = observable_count(src->observables);
    return n > ROBOT_TELEMETRY_MAX_VALUES ? (uint8_t)ROBOT_TELEMETRY_MAX_VALUES : n;
}

static void send_state(robot_telemetry_t *t, hal_t *hal, const robot_telemetry_source_t *src,
                       const robot_telemetry_platform_t *p)
{
    swarmlcm_robot_state_t m;
    float values[ROBOT_TELEMETRY_MAX_VALUES];
    uint8_t n = value_count(src), k;
    for (k = 0u; k < n; k++) {
        values[k] = observable_read(&src->observables[k], src->state);
    }
    m.version = SWARMLCM_ROBOT_STATE_T_VERSION;
    m.utime = (int64_t)hal_time_ms(hal) * 1000;
    m.run = 0;
    m.robot_id = (int16_t)hal_robot_id(hal);
    m.group = (char *)"";
    m.controller = (char *)src->controller;
    m.state = (char *)src->state_name;
    m.wheel_left = p->wheel_left;
    m.wheel_right = p->wheel_right;
    m.leds = p->leds;
    m.ir_max = p->ir_max;
    m.ir_max_index = p->ir_max_index;
    m.ambient_min = p->ambient_min;
    m.blobs = p->blobs;
    m.pose_known = 0;          /* a robot without a tracker */
    m.x = m.y = m.theta = NAN;
    m.n_values = (int8_t)n;
    m.values = values;
    queue(t, hal, (uint8_t)TELEMETRY_CH_ROBOT_STATE,
          swarmlcm_robot_state_t_encode(t->payload, 0, (int)sizeof t->payload, &m));
}

/* The next ROBOT_TELEMETRY_SCHEMA_CHUNK entries of the schema, round and
 * round: a receiver that joins late has it within a few seconds. */
static void send_schema_chunk(robot_telemetry_t *t, hal_t *hal, const robot_telemetry_source_t *src)
{
    swarmlcm_schema_t m;
    char *names[ROBOT_TELEMETRY_SCHEMA_CHUNK], *units[ROBOT_TELEMETRY_SCHEMA_CHUNK];
    char *docs[ROBOT_TELEMETRY_SCHEMA_CHUNK];
    int8_t counters[ROBOT_TELEMETRY_SCHEMA_CHUNK];
    uint8_t total = value_count(src), k;
    if (t->schema_next >= total) {
        t->schema_next = 0u;
    }
    m.version = SWARMLCM_SCHEMA_T_VERSION;
    m.utime = (int64_t)hal_time_ms(hal) * 1000;
    m.run = 0;
    m.kind = (char *)"controller";
    m.name = (char *)src->controller;
    m.total = (int16_t)total;
    m.first = (int16_t)t->schema_next;
    for (k = 0u; k < ROBOT_TELEMETRY_SCHEMA_CHUNK && t->schema_next + k < total; k++) {
        const observable_t *o = &src->observables[t->schema_next + k];
        names[k] = (char *)o->name;
        units[k] = (char *)(o->unit != 0 ? o->unit : "");
        docs[k] = (char *)"";   /* the simulator's schema carries the docs */
        counters[k] = (int8_t)(o->kind == OBS_COUNTER);
    }
    m.n = (int16_t)k;
    m.names = names;
    m.units = units;
    m.counters = counters;
    m.docs = docs;
    t->schema_next = (uint8_t)(t->schema_next + k);
    queue(t, hal, (uint8_t)TELEMETRY_CH_SCHEMA,
          swarmlcm_schema_t_encode(t->payload, 0, (int)sizeof t->payload, &m));
}

uint8_t robot_telemetry_state_due(const robot_telemetry_t *t)
{
    return (uint8_t)(t->countdown == 0u);
}

void robot_telemetry_step(robot_telemetry_t *t, hal_t *hal, const robot_telemetry_source_t *src,
                          const robot_telemetry_platform_t *platform)
{
    if (robot_telemetry_state_due(t) != 0u) {
        t->countdown = (uint8_t)ROBOT_TELEMETRY_STEPS;
        send_state(t, hal, src, platform);
    } else if (t->countdown == ROBOT_TELEMETRY_STEPS / 2u) {
        send_schema_chunk(t, hal, src);
    }
    t->countdown--;
    (void)telemetry_tx_pump(&t->tx, hal);
}
