/*
 * host.c - the host link's messages (host.h).
 */
#include "host.h"

#include <stdlib.h>
#include <string.h>

#include "core/sim_internal.h"

#define HMSG host_message_def_t
static const param_desc_t message_params[] = {
    { .key = "robot", PARAM_FIELD(HMSG, robot, uint32_t), .min = 0, .max = 100000,
      .doc = "robot id, 0-based over every group" },
    { .key = "at", PARAM_FIELD(HMSG, at, float), .min = 0, .max = 1e9,
      .doc = "s: hal_host_receive gives it from the first step at or after this" },
    { .key = "hex", PARAM_STRING_FIELD(HMSG, hex),
      .doc = "the message's bytes, two hex digits each (1 to 64 bytes)" },
    PARAM_END
};
#undef HMSG

static const host_message_def_t message_default = { 0u, 0.0f, "", 0u, { 0u } };

/* A message's hex, decoded into its bytes. */
static int decode_hex(const loader_t *ld, const ynode_t *item, const char *path, void *elem)
{
    host_message_def_t *m = elem;
    char p[SCHEMA_PATH_MAX];
    size_t n = strlen(m->hex);
    schema_join(p, path, "hex");
    if (n == 0 || n % 2u != 0u) {
        return schema_fail(ld, schema_node_of(item, "hex"), p,
                           "%zu hex digits: a message is 1 to %u bytes, two digits each", n,
                           (unsigned)HAL_HOST_MSG_MAX);
    }
    for (size_t k = 0; k < n; k++) {
        char c = m->hex[k];
        int v = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
              : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (v < 0) {
            return schema_fail(ld, schema_node_of(item, "hex"), p, "'%c' (digit %zu) is not a hex digit",
                               c, k + 1);
        }
        m->bytes[k / 2u] = (uint8_t)(k % 2u == 0u ? v << 4 : m->bytes[k / 2u] | v);
    }
    m->len = (uint8_t)(n / 2u);
    return 0;
}

static const schema_t message_schema = { message_params, NULL, NULL, NULL };
/* On the heap: a scenario holds the messages its file lists. */
static const seq_desc_t messages_seq = {
    "messages", HOST_MAX_MESSAGES, sizeof(host_message_def_t), &message_default, &message_schema,
    offsetof(host_config_t, messages), offsetof(host_config_t, message_count), decode_hex, 1, NULL
};
static const child_t host_children[] = {
    { "messages", CHILD_SEQUENCE, NULL, &messages_seq, "one {robot, at, hex} per message" },
    CHILD_END
};
MODEL_ONE_SECTION(host_schema, "host", NULL, host_children,
                  "messages the host sends the robots (hal_host_receive; a planner's routes)");

/* Every message names a robot of the run, and a robot's come in time order
 * (hal_host_receive gives them in file order). */
static int host_check(const void *config, const scenario_t *sc, char path[SCHEMA_PATH_MAX], char msg[SIM_ERR_MAX])
{
    const host_config_t *cfg = config;
    uint32_t robots = scenario_robot_count(sc);
    for (uint32_t i = 0; i < cfg->message_count; i++) {
        const host_message_def_t *m = &cfg->messages[i];
        if (m->robot >= robots) {
            snprintf(path, SCHEMA_PATH_MAX, "host.messages.%u.robot", i);
            snprintf(msg, SIM_ERR_MAX, "robot %u: the run has %u robots (ids 0 to %u)", m->robot, robots,
                     robots ? robots - 1u : 0u);
            return -1;
        }
        for (uint32_t k = i + 1u; k < cfg->message_count; k++) {
            if (cfg->messages[k].robot == m->robot && cfg->messages[k].at < m->at) {
                snprintf(path, SCHEMA_PATH_MAX, "host.messages.%u.at", k);
                snprintf(msg, SIM_ERR_MAX,
                         "%g s is before robot %u's message %u (%g s): list a robot's messages in time order",
                         cfg->messages[k].at, m->robot, i, m->at);
                return -1;
            }
        }
    }
    return 0;
}

static void host_free_config(void *config)
{
    host_config_t *cfg = config;
    free(cfg->messages);
    cfg->messages = NULL;
    cfg->message_count = 0;
}

int host_add_message(scenario_t *sc, const host_message_def_t *m)
{
    host_config_t *cfg = host_config_mut(sc);
    if (cfg->message_count >= HOST_MAX_MESSAGES) {
        return -1;
    }
    host_message_def_t *grown = realloc(cfg->messages, (cfg->message_count + 1u) * sizeof *grown);
    if (grown == NULL) {
        return -1;
    }
    cfg->messages = grown;
    grown[cfg->message_count++] = *m;
    return 0;
}

/* Per robot: where its next message may be in the list. */
static void host_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    (void)config;
    (void)sc;
    out->arrays = 1;
    out->elem_size[0] = sizeof(uint32_t);
}

/* A robot's next message in file order, once its time has come. */
hal_status_t hal_host_receive(hal_t *hal, uint8_t *buf, uint8_t cap, uint8_t *len)
{
    const host_config_t *cfg = sim_model_config(hal->sim, SIM_MODEL_host);
    uint32_t *next = &((uint32_t *)sim_model_array(hal->sim, SIM_MODEL_host, 0))[hal->index];
    *len = 0;
    if (cfg->message_count == 0) {
        return HAL_ERR_UNAVAILABLE;
    }
    uint32_t k = *next;
    while (k < cfg->message_count && cfg->messages[k].robot != hal->index) {
        k++;
    }
    *next = k;   /* the scan resumes here: messages of other robots are skipped once */
    if (k == cfg->message_count
        || (double)hal_time_ms(hal) < 1000.0 * (double)cfg->messages[k].at - 0.5) {
        return HAL_ERR_EMPTY;
    }
    const host_message_def_t *m = &cfg->messages[k];
    if (m->len > cap) {
        return HAL_ERR_RANGE;
    }
    memcpy(buf, m->bytes, m->len);
    *len = m->len;
    *next = k + 1u;
    return HAL_OK;
}

static const char *const host_hal_calls[] = { "hal_host_receive", NULL };

const model_def_t host_model = {
    .name = "host",
    .doc = "the host link: messages the study's PC sends the robots (a planner's routes)",
    .config_size = sizeof(host_config_t),
    .schema = &host_schema,
    .check = host_check,
    .free_config = host_free_config,
    .layout = host_layout,
    .hal_calls = host_hal_calls,
};
