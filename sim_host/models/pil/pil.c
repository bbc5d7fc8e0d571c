/*
 * pil.c - processor-in-the-loop robots (pil.h).
 */
#include "pil.h"

#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/robot_link.h"
#include "core/sim_internal.h"
#include "models/camera/camera.h"
#include "models/ircom/ircom.h"
#include "models/sound/sound.h"
#include "pil/pil_host.h"
#include "pil_avr_link.h"
#include "pil_m4_link.h"
#include "pil_images.h"
#include "pil_mirror.h"

/* The emulated ATmega2560's clock (platforms/pil_avr/emu/), Hz. */
#define PIL_AVR_HZ 16000000u

/* ---------------------------------------------------------------- keys */

static const char *const platform_names[] = { "host", "pil_avr", "pil_m4", NULL };
/* What each platform counts per step (the AVR its cycles, QEMU instructions). */
static const char *const count_names[] = { "", "cycles", "instructions", NULL };

#define P pil_model_config_t
static const param_desc_t pil_params[] = {
    { .key = "cycle_budget", PARAM_FIELD(P, cycle_budget, uint32_t), .min = 0, .max = 4000000000.0,
      .doc = "cycles a control step may take on an emulated MCU (instructions on pil_m4; 0: the control period at 16 MHz, or of pil_m4's emulated time: 1 ns an instruction)" },
    { .key = "boot_budget", PARAM_FIELD(P, boot_budget, uint32_t), .min = 1000, .max = 4000000000.0,
      .doc = "cycles an MCU may take from reset to its first frame" },
    { .key = "timeout_s", PARAM_FIELD(P, timeout_s, float), .min = 0.1, .max = 3600,
      .doc = "wall time an emulator may take to answer, s (a hung one is an error)" },
    { .key = "boot_timeout_s", PARAM_FIELD(P, boot_timeout_s, float), .min = 0.1, .max = 3600,
      .doc = "wall time an emulator may take to start and send its image's first frame, s (starting QEMU takes seconds on a loaded machine)" },
    { .key = "dir", PARAM_STRING_FIELD(P, dir),
      .doc = "folder of the AVR emulator and images (default: firmware/pil_avr beside swarmsim; pil_m4's images are in its sibling pil_m4)" },
    PARAM_END
};
#undef P
MODEL_ONE_SECTION(pil_schema, "pil", pil_params, NULL,
                  "processor-in-the-loop: robots on an emulated MCU (robots[].platform)");

#define G pil_group_config_t
static const param_desc_t group_params[] = {
    { .key = "platform", PARAM_ENUM_FIELD(G, platform, platform_names),
      .doc = "what runs the robots: host (built in), pil_avr (the image on an emulated ATmega2560) or pil_m4 (on an emulated Cortex-M4F, QEMU)" },
    { .key = "image", PARAM_STRING_FIELD(G, image),
      .doc = "the robot image they run (platforms/epuck1/images.list): its parameters and seed" },
    { .key = "platform_robots", PARAM_FIELD(G, platform_robots, uint32_t), .min = 0, .max = 100000,
      .doc = "how many of the group's robots (its first) run on the platform (0: all; the rest host-built)" },
    { .key = "selector", PARAM_FIELD(G, selector, uint8_t), .min = 0, .max = 15,
      .doc = "the selector switch's position at power-on (an image with a selector)" },
    PARAM_END
};
#undef G
static const schema_t pil_group_schema = { group_params, NULL, NULL, NULL };

static void pil_defaults(void *config)
{
    pil_model_config_t *c = config;
    memset(c, 0, sizeof *c);
    c->boot_budget = 16000000u;
    c->timeout_s = 20.0f;
    c->boot_timeout_s = PIL_LINK_BOOT_TIMEOUT_MS / 1000.0f;
}

static void pil_group_defaults(void *config)
{
    memset(config, 0, sizeof(pil_group_config_t));
}

static const pil_group_config_t *group_cfg(const robot_group_t *g)
{
    return scenario_group_model_config(g, SIM_MODEL_pil);
}

static void list_images(char *out, size_t cap)
{
    const pil_image_t *im;
    out[0] = '\0';
    for (size_t i = 0; (im = pil_image_at(i)) != NULL; i++) {
        size_t n = strlen(out);
        snprintf(out + n, cap - n, "%s%s", n ? ", " : "", im->name);
    }
}

static int pil_check(const void *config, const scenario_t *sc, char path[SCHEMA_PATH_MAX], char msg[SIM_ERR_MAX])
{
    (void)config;
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const robot_group_t *grp = &sc->groups[g];
        const pil_group_config_t *c = group_cfg(grp);
        if (c->image[0] == '\0') {
            if (c->platform != PIL_PLATFORM_HOST) {
                char names[400];
                list_images(names, sizeof names);
                snprintf(path, SCHEMA_PATH_MAX, "robots.%u.image", g);
                snprintf(msg, SIM_ERR_MAX, "a group on platform %s runs a robot image: give image: NAME (%s)",
                         platform_names[c->platform], names);
                return -1;
            }
            continue;
        }
        const pil_image_t *im = pil_image_find(c->image);
        if (!im) {
            char names[400];
            list_images(names, sizeof names);
            snprintf(path, SCHEMA_PATH_MAX, "robots.%u.image", g);
            snprintf(msg, SIM_ERR_MAX, "unknown image '%s' (the images: %s)", c->image, names);
            return -1;
        }
        if (strcmp(im->controller, grp->def->name) != 0) {
            snprintf(path, SCHEMA_PATH_MAX, "robots.%u.image", g);
            snprintf(msg, SIM_ERR_MAX, "image %s runs controller %s (%s), not the group's %s", im->name,
                     im->controller, im->where, grp->def->name);
            return -1;
        }
        if (grp->def->default_params && grp->def->params_size <= sizeof(scenario_params_t)) {
            scenario_params_t defaults;
            memset(&defaults, 0, sizeof defaults);
            grp->def->default_params(defaults.bytes);
            if (memcmp(defaults.bytes, grp->params.bytes, grp->def->params_size) != 0 || grp->policy_index != 0) {
                snprintf(path, SCHEMA_PATH_MAX, "robots.%u.image", g);
                snprintf(msg, SIM_ERR_MAX, "a group that runs image %s takes its parameters and policy from the "
                         "image's declaration (%s): give it no params or policy", im->name, im->where);
                return -1;
            }
        }
        if (im->params_size != grp->def->params_size) {
            snprintf(path, SCHEMA_PATH_MAX, "robots.%u.image", g);
            snprintf(msg, SIM_ERR_MAX, "image %s: its parameters are not controller %s's (a stale build?)",
                     im->name, grp->def->name);
            return -1;
        }
    }
    return 0;
}

/* ---------------------------------------------------------------- a run */

/* Each robot's figures, for sim_field and the summary. */
typedef struct pil_robot {
    uint8_t on_mcu;          /* runs on an emulated MCU */
    uint32_t cycles;         /* its last step's */
    uint16_t stack;          /* bytes of stack used at most (painting) */
} pil_robot_t;

/* One robot on an emulated MCU. */
typedef struct pil_mcu {
    uint32_t robot;
    const pil_image_t *image;
    const pil_mirror_t *mirror;
    pil_avr_link_t link;
    int platform;            /* pil_platform_t */
    uint8_t failed;
    uint64_t cycles_sum, cycles_max, steps;
    char err[SIM_ERR_MAX];
    uint8_t *state;          /* the MCU's state bytes, mirror->avr_size */
    pil_host_t host;         /* last: 5 KB of frame buffer */
} pil_mcu_t;

typedef struct pil {
    const pil_model_config_t *cfg;
    uint32_t n;
    pil_mcu_t **mcu;         /* n, NULL for a host-built robot */
    pil_mirror_t mirror[SCENARIO_MAX_GROUPS];
    uint32_t n_mcu;
} pil_t;

static void pil_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    (void)config;
    int any = 0;
    for (uint32_t g = 0; g < sc->group_count; g++) {
        any |= group_cfg(&sc->groups[g])->image[0] != '\0';
    }
    if (any) {
        out->arrays = 1;
        out->elem_size[0] = sizeof(pil_robot_t);
        /* Each robot on an MCU: its link and frame buffer. */
        out->run_bytes = 0;
        for (uint32_t g = 0; g < sc->group_count; g++) {
            if (group_cfg(&sc->groups[g])->platform != PIL_PLATFORM_HOST) {
                out->run_bytes += (size_t)sc->groups[g].count * sizeof(pil_mcu_t);
            }
        }
    }
}

static pil_robot_t *robots(const sim_t *sim) { return sim_model_array(sim, SIM_MODEL_pil, 0); }

/* The folder of the emulator and the images. */
static int pil_dir(const pil_model_config_t *c, int platform, char *out, size_t cap, char err[SIM_ERR_MAX])
{
    if (c->dir[0]) {
        snprintf(out, cap, "%s%s", c->dir, platform == PIL_PLATFORM_M4 ? "/../pil_m4" : "");
        return 0;
    }
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0) {
        snprintf(err, SIM_ERR_MAX, "pil.dir: cannot find the program's folder; give pil.dir");
        return -1;
    }
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    if (slash) {
        *slash = '\0';
    }
    snprintf(out, cap, "%.*s/firmware/%s", (int)(cap - 20), exe, platform_names[platform]);
    return 0;
}

/* ---- the requests, answered through the robot's own hal.h */

static void op_ir(void *ctx, uint16_t out[HAL_IR_COUNT])
{
    for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
        out[k] = hal_ir_proximity(ctx, k);
    }
}

static void op_ambient(void *ctx, uint16_t out[HAL_IR_COUNT])
{
    for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
        out[k] = hal_ir_ambient(ctx, k);
    }
}

static uint8_t op_blobs(void *ctx, hal_blob_t out[HAL_MAX_BLOBS])
{
    return hal_camera_blobs(ctx, out, (uint8_t)HAL_MAX_BLOBS);
}

static int op_frame(void *ctx, uint8_t *out, uint16_t bytes, char *err)
{
    (void)ctx;
    (void)out;
    (void)bytes;
    snprintf(err, PIL_HOST_ERR, "asked for a camera frame, which this simulator does not send (blobs only)");
    return -1;
}

static hal_status_t op_pose(void *ctx, hal_pose_t *out) { return hal_pose(ctx, out); }
static hal_status_t op_rx(void *ctx, hal_ircom_msg_t *out) { return hal_ircom_receive(ctx, out); }

static hal_status_t op_host(void *ctx, uint8_t *buf, uint8_t cap, uint8_t *len)
{
    return hal_host_receive(ctx, buf, cap, len);
}

static hal_status_t op_ground(void *ctx, uint16_t out[HAL_GROUND_COUNT])
{
    hal_status_t st = HAL_OK;
    for (uint8_t k = 0; k < HAL_GROUND_COUNT; k++) {
        st = hal_ground(ctx, k, &out[k]);
    }
    return st;
}

static uint16_t op_telemetry(void *ctx, const uint8_t *bytes, uint16_t len)
{
    return hal_telemetry_write(ctx, bytes, len);
}

static const pil_host_ops_t ops_template = {
    .ir = op_ir, .ambient = op_ambient, .blobs = op_blobs, .frame = op_frame, .pose = op_pose,
    .ircom_receive = op_rx, .host_receive = op_host, .ground = op_ground, .telemetry = op_telemetry,
};

/* The telemetry sink's room this step: the robot's UART's budget. */
static uint16_t telemetry_room(const sim_t *sim, uint32_t i)
{
    const struct robot_link *l = sim_robot_link(sim, i);
    if (!l || l->budget >= PIL_ROOM_UNLIMITED) {
        return PIL_ROOM_UNLIMITED;
    }
    return (uint16_t)l->budget;
}

static void fail(pil_mcu_t *m, uint64_t step, const char *what)
{
    snprintf(m->err, sizeof m->err, "robot %u (image %s on %s), step %" PRIu64 ": %s", m->robot,
             m->image->name, platform_names[m->platform], step, what);
    m->failed = 1;
}

/* The controller's state from the MCU's RAM into the robot's struct. */
static int mirror(pil_mcu_t *m, void *ctrl, char err[PIL_HOST_ERR])
{
    if (pil_avr_link_peek(&m->link, m->host.hello.state_addr, m->mirror->avr_size, m->state, err) != 0) {
        return -1;
    }
    pil_mirror_apply(m->mirror, m->state, ctrl);
    return 0;
}

/* A PIL robot's control step, in place of its controller's (sim_robot_t.step). */
static void pil_step(void *ctrl, hal_t *hal)
{
    pil_t *p = sim_model_self(hal->sim, SIM_MODEL_pil);
    pil_mcu_t *m = p->mcu[hal->index];
    const uint64_t step = sim_step_count(hal->sim);
    char e[PIL_HOST_ERR];
    if (m->failed) {
        return;
    }
    pil_step_t st;
    memset(&st, 0, sizeof st);
    st.step = (uint32_t)step;
    st.time_ms = hal_time_ms(hal);
    hal_wheel_steps(hal, &st.steps_left, &st.steps_right);
    st.telemetry_room = telemetry_room(hal->sim, hal->index);
    if (m->host.hello.flags & PIL_HAS_SOUND) {
        st.mic_count = PIL_MIC_CELLS;
        for (uint8_t mic = 0; mic < HAL_MIC_COUNT; mic++) {
            for (uint8_t band = 1; band < HAL_SOUND_BANDS; band++) {
                pil_mic_cell_t *c = &st.mic[mic * (HAL_SOUND_BANDS - 1u) + band - 1u];
                c->status = hal_mic_level(hal, mic, band, &c->level);
            }
        }
    }
    pil_host_ops_t ops = ops_template;
    ops.ctx = hal;
    pil_act_t act;
    if (pil_host_step(&m->host, &st, &ops, &act, e) != 0) {
        fail(m, step, e);
        return;
    }
    hal_set_wheel_speeds(hal, act.wheel_left, act.wheel_right);
    for (uint8_t k = 0; k < HAL_LED_COUNT; k++) {
        hal_set_led(hal, k, (uint8_t)((act.leds >> k) & 1u));
    }
    hal_set_body_led(hal, (uint8_t)((act.leds >> HAL_LED_WORD_BODY_BIT) & 1u));
    hal_set_front_led(hal, (uint8_t)((act.leds >> HAL_LED_WORD_FRONT_BIT) & 1u));
    if (m->host.hello.flags & PIL_HAS_SOUND) {
        (void)hal_speaker_set(hal, act.speaker);
    }
    for (uint8_t k = 0; k < act.tx_count; k++) {
        if (hal_ircom_send(hal, act.tx[k]) != HAL_OK) {
            fail(m, step, "sent more IR messages than its period takes");
            return;
        }
    }
    if (act.telemetry_len && hal_telemetry_write(hal, act.telemetry, act.telemetry_len) != act.telemetry_len) {
        fail(m, step, "wrote more telemetry than its UART took this step");
        return;
    }
    if (mirror(m, ctrl, e) != 0) {
        fail(m, step, e);
        return;
    }
    pil_robot_t *r = &robots(hal->sim)[hal->index];
    r->cycles = m->host.step_cycles > UINT32_MAX ? UINT32_MAX : (uint32_t)m->host.step_cycles;
    r->stack = m->host.emu.stack_max;
    m->cycles_sum += m->host.step_cycles;
    m->cycles_max = m->host.step_cycles > m->cycles_max ? m->host.step_cycles : m->cycles_max;
    m->steps++;
}

/* The robot's seed by its image's rule. */
static uint32_t image_seed(const sim_t *sim, const pil_image_t *im, uint32_t i)
{
    return im->seed == PIL_SEED_ID ? i : im->seed == PIL_SEED_ZERO ? 0u
                                                              : sim_rand_seed32(sim->seed, i, RAND_CONTROLLER);
}

/* Robot i's MCU: started, its HELLO checked against the scenario, told
 * its CONFIG, READY, its state mirrored. */
static int boot(sim_t *sim, pil_t *p, pil_mcu_t *m, const char *dir, uint32_t g, char err[SIM_ERR_MAX])
{
    const scenario_t *sc = sim->sc;
    const pil_model_config_t *c = p->cfg;
    const ircom_config_t *ic = ircom_config(sc);
    char emu[PATH_MAX], elf[PATH_MAX], e[PIL_HOST_ERR];
    int opened;
    if (m->platform == PIL_PLATFORM_M4) {
        /* One instruction, one emulated ns: the control period is
         * period_ms * 10^6 instructions. */
        snprintf(elf, sizeof elf, "%.3000s/m4/%.32s.elf", dir, m->image->name);
        pil_m4_link_def_t def = { .image = elf, .boot_budget = c->boot_budget,
                                  .timeout_ms = (int)(c->timeout_s * 1000.0f),
                                  .boot_timeout_ms = (int)(c->boot_timeout_s * 1000.0f) };
        def.budget = c->cycle_budget ? c->cycle_budget : (uint64_t)sc->control_period_ms * 1000000u;
        opened = pil_m4_link_open(&m->link, &def, e);
    } else {
        snprintf(emu, sizeof emu, "%.3000s/pil_avr_emu", dir);
        snprintf(elf, sizeof elf, "%.3000s/avr/%.32s.elf", dir, m->image->name);
        pil_avr_link_def_t def = pil_avr_link_default_def();
        def.emulator = emu;
        def.image = elf;
        def.budget = c->cycle_budget ? c->cycle_budget : (uint64_t)sc->control_period_ms * (PIL_AVR_HZ / 1000u);
        def.boot_budget = c->boot_budget;
        def.timeout_ms = (int)(c->timeout_s * 1000.0f);
        def.boot_timeout_ms = (int)(c->boot_timeout_s * 1000.0f);
        opened = pil_avr_link_open(&m->link, &def, e);
    }
    if (opened != 0) {
        snprintf(err, SIM_ERR_MAX, "robot %u (robots.%u, image %s): %s", m->robot, g, m->image->name, e);
        return -1;
    }
    pil_host_io_t io = pil_avr_link_io(&m->link);
    pil_host_init(&m->host, &io);
    const pil_hello_t *h = &m->host.hello;
    const char *wrong = NULL;
    char what[160] = "";
    if (pil_host_hello(&m->host, e) != 0) {
        wrong = e;
    } else if (strcmp(h->name, m->image->name) != 0) {
        snprintf(what, sizeof what, "its ELF says it is image %s (a stale build?)", h->name);
    } else if (h->period_ms != sc->control_period_ms) {
        snprintf(what, sizeof what, "the image's control period is %u ms, the scenario's control_period_ms %u",
                 h->period_ms, sc->control_period_ms);
    } else if (h->ircom_bits != ic->payload_bits) {
        snprintf(what, sizeof what, "the image sends %u-bit IR messages, the scenario's ircom.payload_bits is %u",
                 h->ircom_bits, ic->payload_bits);
    } else if (h->tx_per_period != ic->tx_per_period) {
        snprintf(what, sizeof what, "the image sends %u IR messages a period, the scenario's "
                 "ircom.tx_per_period is %u", h->tx_per_period, ic->tx_per_period);
    } else if (h->state_size != m->mirror->avr_size || m->mirror->host_size > sim->robots[m->robot].def->state_size) {
        snprintf(what, sizeof what, "its controller state (%u bytes) is not its state map's (%u): rebuild with "
                 "make %s", h->state_size, m->mirror->avr_size, m->platform == PIL_PLATFORM_M4 ? "pil-m4" : "pil-avr");
    }
    if (wrong || what[0]) {
        snprintf(err, SIM_ERR_MAX, "robot %u (robots.%u, image %s on %s), boot: %s", m->robot, g,
                 m->image->name, platform_names[m->platform], wrong ? wrong : what);
        return -1;
    }
    const camera_config_t *cam = camera_config(sc);
    m->host.config.robot_id = sim->robots[m->robot].id;  /* its group's first_id, or its index */
    m->host.config.seed = sim_rand_seed32(sim->seed, m->robot, RAND_CONTROLLER);
    m->host.config.period_ms = sc->control_period_ms;
    m->host.config.ircom_bits = ic->payload_bits;
    m->host.config.tx_per_period = ic->tx_per_period;
    m->host.config.flags = sound_config(sc)->enabled ? PIL_SIM_SOUND : 0u;
    m->host.config.cam_width = cam->width_px;
    m->host.config.cam_height = cam->height_px;
    m->host.config.fov_mrad = (uint16_t)(cam->fov * 3.14159265358979 / 180.0 * 1000.0 + 0.5);
    m->host.config.selector = group_cfg(&sc->groups[g])->selector;
    if (pil_host_config(&m->host, e) != 0 || mirror(m, sim->robots[m->robot].ctrl, e) != 0) {
        snprintf(err, SIM_ERR_MAX, "robot %u (robots.%u, image %s on %s), boot: %s", m->robot, g,
                 m->image->name, platform_names[m->platform], e);
        return -1;
    }
    return 0;
}

static int pil_create(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX])
{
    const scenario_t *sc = sim->sc;
    if (!robots(sim)) {
        return 0;   /* no group runs an image */
    }
    pil_t *p = calloc(1, sizeof *p);
    if (!p || !(p->mcu = calloc(sim->n ? sim->n : 1u, sizeof *p->mcu))) {
        free(p);
        snprintf(err, SIM_ERR_MAX, "out of memory for the PIL robots");
        return -1;
    }
    *self = p;
    p->cfg = config;
    p->n = sim->n;
    char dir[PATH_MAX];
    uint32_t i = 0;
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const robot_group_t *grp = &sc->groups[g];
        const pil_group_config_t *gc = group_cfg(grp);
        const pil_image_t *im = gc->image[0] ? pil_image_find(gc->image) : NULL;
        if (im && gc->platform != PIL_PLATFORM_HOST) {
            char map[PATH_MAX + 16];
            if (pil_dir(p->cfg, gc->platform, dir, sizeof dir, err) != 0) {
                return -1;
            }
            snprintf(map, sizeof map, "%.3000s/pil_avr_emu", dir);
            if (gc->platform == PIL_PLATFORM_AVR && access(map, X_OK) != 0) {
                snprintf(err, SIM_ERR_MAX, "robots.%u: the AVR emulator %.300s: %s (make pil-avr builds it; it "
                         "needs simavr: Debian's libsimavr-dev; pil.dir says where it is)", g, map, strerror(errno));
                return -1;
            }
            snprintf(map, sizeof map, "%.3000s/%s/%.32s.map", dir, gc->platform == PIL_PLATFORM_M4 ? "m4" : "avr",
                     im->name);
            if (pil_mirror_load(&p->mirror[g], map, err) != 0) {
                return -1;
            }
        }
        for (uint32_t k = 0; k < grp->count; k++, i++) {
            sim_robot_t *r = &sim->robots[i];
            if (!im) {
                continue;
            }
            /* As the image's run loop starts it: its parameters, its seed. */
            scenario_params_t params;
            im->params(params.bytes, gc->selector);
            if (r->ctrl) {
                r->def->init(r->ctrl, params.bytes, image_seed(sim, im, i));
            }
            if (gc->platform == PIL_PLATFORM_HOST || (gc->platform_robots && k >= gc->platform_robots)) {
                continue;
            }
            pil_mcu_t *m = calloc(1, sizeof *m);
            if (!m || !(m->state = malloc(p->mirror[g].avr_size ? p->mirror[g].avr_size : 1u))) {
                free(m);
                snprintf(err, SIM_ERR_MAX, "out of memory for robot %u's MCU", i);
                return -1;
            }
            p->mcu[i] = m;
            p->n_mcu++;
            m->robot = i;
            m->image = im;
            m->mirror = &p->mirror[g];
            m->platform = gc->platform;
            m->link.pid = -1;
            m->link.to = m->link.from = -1;
            if (boot(sim, p, m, dir, g, err) != 0) {
                return -1;
            }
            r->step = pil_step;
            r->own_telemetry = 1;
            robots(sim)[i].on_mcu = 1;
        }
    }
    return 0;
}

static void pil_destroy(void *self)
{
    pil_t *p = self;
    if (!p) {
        return;
    }
    for (uint32_t i = 0; i < p->n; i++) {
        if (p->mcu[i]) {
            pil_avr_link_close(&p->mcu[i]->link);
            free(p->mcu[i]->state);
            free(p->mcu[i]);
        }
    }
    for (uint32_t g = 0; g < SCENARIO_MAX_GROUPS; g++) {
        pil_mirror_free(&p->mirror[g]);
    }
    free(p->mcu);
    free(p);
}

/* The first robot (by id) whose MCU failed: the run stops. */
static const char *pil_error(const sim_t *sim, const void *self)
{
    const pil_t *p = self;
    (void)sim;
    for (uint32_t i = 0; p && i < p->n; i++) {
        if (p->mcu[i] && p->mcu[i]->failed) {
            return p->mcu[i]->err;
        }
    }
    return NULL;
}

/* What the MCUs measured, in the summary. */
static void pil_write_json(const sim_t *sim, const void *self, FILE *f)
{
    const pil_t *p = self;
    (void)sim;
    if (!p || p->n_mcu == 0) {
        return;
    }
    /* Per platform: the AVR's cycles, the M4's instructions (a mixed run
     * has one line of figures for each). */
    fprintf(f, "  \"pil\": {\"robots\": %u", p->n_mcu);
    int first = 1;
    for (int pf = PIL_PLATFORM_AVR; pf <= PIL_PLATFORM_M4; pf++) {
        uint64_t sum = 0, steps = 0, max = 0;
        uint16_t stack = 0;
        uint32_t n = 0;
        for (uint32_t i = 0; i < p->n; i++) {
            const pil_mcu_t *m = p->mcu[i];
            if (m && m->platform == pf) {
                n++;
                sum += m->cycles_sum;
                steps += m->steps;
                max = m->cycles_max > max ? m->cycles_max : max;
                stack = m->host.emu.stack_max > stack ? m->host.emu.stack_max : stack;
            }
        }
        if (n == 0) {
            continue;
        }
        /* The first platform's figures at the top (as with one platform),
         * any other's in an object of its own. */
        const char *k = count_names[pf];
        if (first) {
            fprintf(f, ", \"platform\": \"%s\", ", platform_names[pf]);
        } else {
            fprintf(f, ", \"%s\": {\"robots\": %u, ", platform_names[pf], n);
        }
        fprintf(f, "\"%s_per_step_mean\": %.1f, \"%s_per_step_max\": %" PRIu64 ", \"stack_bytes_max\": %u%s", k,
                steps ? (double)sum / (double)steps : 0.0, k, max, stack, first ? "" : "}");
        first = 0;
    }
    fprintf(f, "},\n");
}

static const char *const pil_hal_calls[] = { NULL };

static const model_field_t pil_fields[] = {
    { "pil.on_mcu", "", "1 when the robot runs on an emulated MCU", SIM_FIELD_U8, 0,
      offsetof(pil_robot_t, on_mcu), 1 },
    { "pil.cycles", "cycles", "its MCU's cycles in the last control step", SIM_FIELD_U32, 0,
      offsetof(pil_robot_t, cycles), 1 },
    { "pil.stack", "bytes", "its MCU's stack used at most so far (painting)", SIM_FIELD_U16, 0,
      offsetof(pil_robot_t, stack), 1 },
    { NULL, NULL, NULL, SIM_FIELD_U8, 0, 0, 0 }
};

const model_def_t pil_model = {
    .name = "pil",
    .doc = "processor-in-the-loop: a group's robots run its image as machine code on an emulated MCU",
    .config_size = sizeof(pil_model_config_t),
    .default_config = pil_defaults,
    .schema = &pil_schema,
    .check = pil_check,
    .group_config_size = sizeof(pil_group_config_t),
    .default_group_config = pil_group_defaults,
    .group_schema = &pil_group_schema,
    .layout = pil_layout,
    .create = pil_create,
    .destroy = pil_destroy,
    .hal_calls = pil_hal_calls,
    .fields = pil_fields,
    .write_json = pil_write_json,
    .error = pil_error,
};
