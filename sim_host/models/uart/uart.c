/*
 * uart.c - the robots' own telemetry down a simulated UART (uart.h).
 */
#include "uart.h"

#include <stdio.h>
#include <stdlib.h>

#include "core/robot_link.h"
#include "core/sim_internal.h"

#define U uart_config_t
static const param_desc_t uart_params[] = {
    { .key = "enabled", PARAM_BOOL_FIELD(U, enabled),
      .doc = "every robot runs the image's telemetry sender; its frames are republished" },
    { .key = "channel_prefix", PARAM_STRING_FIELD(U, channel_prefix),
      .doc = "prefix of the republished channels (as the bridge's --prefix)" },
    { .key = "baud", PARAM_FIELD(U, baud, uint32_t), .min = 0, .max = 10000000,
      .doc = "the UART's rate, bits/s (0: unlimited); bytes beyond it wait in the sender" },
    { .key = "dump", PARAM_BOOL_FIELD(U, dump),
      .doc = "also write each robot's raw byte stream to run_<seed>/uart/robot_<id>.bin" },
    PARAM_END
};
#undef U

MODEL_ONE_SECTION(uart_schema, "robot_telemetry", uart_params, NULL,
                  "the robots' own telemetry, in the loop");

static void uart_defaults(void *config)
{
    uart_config_t *c = config;
    c->enabled = 0;
    snprintf(c->channel_prefix, sizeof c->channel_prefix, "FW_");
    c->baud = 115200;
    c->dump = 0;
}

enum { TX, LINK };

/* Each robot's sender and its end of the link, only when enabled. */
static void uart_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    const uart_config_t *c = config;
    (void)sc;
    if (c->enabled) {
        out->arrays = 2;
        out->elem_size[TX] = sizeof(robot_telemetry_t);
        out->elem_size[LINK] = sizeof(robot_link_t);
    }
}

typedef struct uart {
    uint32_t budget;     /* bytes per step the UART carries */
} uart_t;

static robot_telemetry_t *senders(const sim_t *sim) { return sim_model_array(sim, SIM_MODEL_uart, TX); }
static robot_link_t *links(const sim_t *sim) { return sim_model_array(sim, SIM_MODEL_uart, LINK); }

static int uart_create(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX])
{
    const uart_config_t *c = config;
    if (!c->enabled) {
        return 0;
    }
    uart_t *u = calloc(1, sizeof *u);
    if (!u) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the robots' telemetry links");
        return -1;
    }
    *self = u;
    for (uint32_t i = 0; i < sim->n; i++) {
        robot_telemetry_init(&senders(sim)[i]);
        robot_link_init(&links(sim)[i]);
    }
    /* 8N1: ten bits a byte. */
    uint64_t per_step = (uint64_t)c->baud * sim->sc->control_period_ms / 10000u;
    u->budget = c->baud == 0 || per_step > UINT32_MAX ? UINT32_MAX : (uint32_t)per_step;
    return 0;
}

static void uart_destroy(void *self) { free(self); }

static void uart_before_control(sim_t *sim, void *self)
{
    const uart_t *u = self;
    for (uint32_t i = 0; u && i < sim->n; i++) {
        robot_link_begin_step(&links(sim)[i], u->budget);
    }
}

/* After robot i's step: its image's telemetry sender, as on the robot.  It
 * reads only the robot's own state and this step's sensor caches, so the
 * run is the same with it or without it. */
static void uart_after_robot(sim_t *sim, void *self, uint32_t i)
{
    if (!self) {
        return;
    }
    sim_robot_t *r = &sim->robots[i];
    robot_telemetry_t *tx = &senders(sim)[i];
    robot_telemetry_platform_t p;
    const robot_telemetry_platform_t *due = NULL;
    robot_telemetry_source_t src = {
        .controller = r->def->name, .observables = r->def->observables, .state = r->ctrl,
    };
    if (robot_telemetry_state_due(tx)) {
        sim_robot_platform(sim, i, sim->step + 1, &p);
        src.state_name = r->def->state_name(r->ctrl);
        due = &p;
    }
    robot_telemetry_step(tx, &r->hal, &src, due);
}

const struct robot_link *sim_robot_link(const sim_t *sim, uint32_t i)
{
    return sim_model_self(sim, SIM_MODEL_uart) ? &links(sim)[i] : NULL;
}

uint16_t hal_telemetry_write(hal_t *hal, const uint8_t *bytes, uint16_t len)
{
    /* Down the robot's simulated UART when the scenario runs its telemetry
     * in the loop (robot_link.h); otherwise accepted and dropped. */
    if (sim_model_self(hal->sim, SIM_MODEL_uart)) {
        return robot_link_write(&links(hal->sim)[hal->index], bytes, len);
    }
    (void)bytes;
    return len;
}

static const char *const uart_hal_calls[] = { "hal_telemetry_write", NULL };

const model_def_t uart_model = {
    .name = "uart",
    .doc = "the robot's serial port: its own telemetry sender in the loop, at the UART's rate",
    .config_size = sizeof(uart_config_t),
    .default_config = uart_defaults,
    .schema = &uart_schema,
    .layout = uart_layout,
    .create = uart_create,
    .destroy = uart_destroy,
    .before_control = uart_before_control,
    .after_robot = uart_after_robot,
    .hal_calls = uart_hal_calls,
};
