/*
 * ircom.c - IR local communication between robots (libIrcom style).
 *
 * A message queued by hal_ircom_send during step t reaches every robot within
 * `ircom.range` (centre to centre) whose line of sight to the sender is not
 * blocked by an obstacle (nor by a robot when `blocked_by_robots`), unless
 * it is lost (probability `ircom.loss`, drawn at the receiver).  It is
 * readable from step t+1, so the order robots step in does not matter.
 * The receiver estimates the sender's bearing (the receiving sensor's
 * bearing when `quantise_bearing`, as libIrcom does, else the true bearing
 * plus Gaussian noise) and range (true range with relative Gaussian noise).
 * A full queue drops the new message, as libIrcom does.  Senders are taken
 * in turn from an offset that rotates every step: a receiver hearing more
 * senders than its queue holds loses different ones each step, as on a
 * shared channel, not always the same (the highest ids, which a robot
 * listening to 30 others then never heard).
 *
 * Seed 003's extensions (each off by default, so earlier scenarios run as
 * they did):
 *  - `bearing_noise_vec` (m): the paper's direction noise, a random vector
 *    with uniform azimuth and a Gaussian length (sd bearing_noise_vec) added
 *    to the vector from receiver to sender before the bearing and range are
 *    taken from it (section 5.2.3 (1)).  It comes on top of `bearing_noise`
 *    and `range_noise_rel`; set those to 0 for the paper's model alone.
 *  - `tx_per_period`: how many messages hal_ircom_send accepts in one
 *    control period (1: the HAL's one message a period).  The e-RandB
 *    turret's own frame rate is not documented in what we could find; its
 *    driver busy-waits about 4 ms in every send (hal/epuck/ircom_randb.c),
 *    so a 100 ms period has room for at most ~25 sends [?].
 *  - `slots`: collisions.  The period is `slots` frame times; each frame a
 *    robot sends lands in a slot drawn at random (a sender's frames in
 *    distinct slots), and a receiver within reach of two or more frames in
 *    one slot gets none of them (infrared frames on one carrier overlap; no
 *    capture), nor while it sends one itself (half duplex).  Line of sight
 *    and range decide "within reach", as for delivery; loss is drawn after.
 *  - `queue`: the receiver's inbox size (libIrcom: 20).
 *
 * Delivery runs receiver by receiver, side by side on the run's threads
 * (pool.h): each receiver takes the frames that reach it in the senders'
 * turn order and draws its loss and noise from its own stream, so that what
 * it holds is what one loop over senders would have given it, at any
 * thread count.  (That loop kept at most 256 robots around a sender; this
 * one has no such cap.)  The collision model (`slots`) stays one loop.
 *
 * Per robot, four arrays: what it sends this step, its inbox's ring state,
 * the inbox's `queue` slots, its stream (RAND_IRCOM).
 */
#include "ircom.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/pool.h"
#include "core/sim_internal.h"
#include "models/faults/faults.h"
#include "units.h"

#define C ircom_config_t
static const param_desc_t ircom_params[] = {
    { .key = "range", PARAM_FIELD(C, range, float), .min = 0, .max = 10,
      .doc = "centre-to-centre reach, m" },
    { .key = "loss", PARAM_FIELD(C, loss, float), .min = 0, .max = 1,
      .doc = "probability a message is lost" },
    { .key = "bearing_noise", PARAM_FIELD(C, bearing_noise, float), .min = 0, .max = 180,
      .doc = "Gaussian sd added to the bearing, deg" },
    { .key = "range_noise_rel", PARAM_FIELD(C, range_noise_rel, float), .min = 0, .max = 1,
      .doc = "relative Gaussian sd of the range" },
    { .key = "quantise_bearing", PARAM_BOOL_FIELD(C, quantise_bearing),
      .doc = "report the receiving sensor's bearing" },
    { .key = "blocked_by_robots", PARAM_BOOL_FIELD(C, blocked_by_robots),
      .doc = "robots also block line of sight" },
    { .key = "payload_bits", PARAM_FIELD(C, payload_bits, uint8_t), .min = 8, .max = 16,
      .doc = "data bits per message: 8 libIrcom, 16 range-and-bearing turret" },
    { .key = "bearing_noise_vec", PARAM_FIELD(C, bearing_noise_vec, float), .min = 0, .max = 10,
      .doc = "sd of a random vector (uniform azimuth, Gaussian length) added to the sender's offset, m (seed 003)" },
    { .key = "tx_per_period", PARAM_FIELD(C, tx_per_period, uint8_t), .min = 1, .max = IRCOM_TX_MAX,
      .doc = "messages a robot may send per control period (the turret's rate)" },
    { .key = "slots", PARAM_FIELD(C, slots, uint16_t), .min = 0, .max = 1000,
      .doc = "frame times per control period for collisions (0: no collisions)" },
    { .key = "queue", PARAM_FIELD(C, queue, uint8_t), .min = 1, .max = IRCOM_QUEUE_MAX,
      .doc = "messages a receiver's inbox holds (libIrcom: 20)" },
    PARAM_END
};
#undef C

MODEL_ONE_SECTION(ircom_schema, "ircom", ircom_params, NULL,
                  "IR communication");

/* libIrcom's: 25 cm, 8 bits, one message a period, an inbox of 20; the
 * noise of its estimates (EPUCK.md). */
static void ircom_defaults(void *config)
{
    ircom_config_t *c = config;
    c->range = 0.25f;
    c->loss = 0.1f;
    c->bearing_noise = 5.0f;
    c->range_noise_rel = 0.1f;
    c->quantise_bearing = 1;
    c->blocked_by_robots = 0;
    c->payload_bits = 8;
    c->bearing_noise_vec = 0.0f;
    c->tx_per_period = 1;
    c->slots = 0;
    c->queue = 20;
}

static int ircom_check(const void *config, const scenario_t *sc, char path[SCHEMA_PATH_MAX], char msg[SIM_ERR_MAX])
{
    const ircom_config_t *c = config;
    if (c->slots > 0 && c->tx_per_period > c->slots) {
        snprintf(path, SCHEMA_PATH_MAX, "ircom.tx_per_period");
        snprintf(msg, SIM_ERR_MAX, "%u messages a period do not fit in %u slots (ircom.slots)", c->tx_per_period,
                 c->slots);
        return -1;
    }
    /* What a group's controller sends must fit the platform's messages. */
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const robot_group_t *grp = &sc->groups[g];
        if (grp->count > 0 && grp->def->ircom_bits > c->payload_bits) {
            snprintf(path, SCHEMA_PATH_MAX, "robots.%u.controller", g);
            snprintf(msg, SIM_ERR_MAX, "controller '%s' sends %u-bit IR messages but ircom.payload_bits is %u "
                     "(set ircom.payload_bits: %u, the range-and-bearing turret)", grp->def->name,
                     grp->def->ircom_bits, c->payload_bits, grp->def->ircom_bits);
            return -1;
        }
    }
    return 0;
}

/* ---------------------------------------------------------------- state */

enum { OUT, INBOX, QUEUE, RAND, ARRAYS };

/* What a robot sends this step. */
typedef struct ircom_out {
    uint16_t msg[IRCOM_TX_MAX];
    uint8_t n;                   /* tx_per_period at most */
} ircom_out_t;

/* Its inbox: a ring of `queue` messages. */
typedef struct ircom_inbox {
    uint8_t head, count;
    uint32_t dropped;            /* arrivals a full inbox refused */
} ircom_inbox_t;

typedef struct ircom {
    const ircom_config_t *cfg;
    float sensor_rad[HAL_IR_COUNT];   /* hal_ir_bearing_mrad / 1000, rad: the same ring on every robot */
    ircom_out_t *out;
    ircom_inbox_t *inbox;
    hal_ircom_msg_t *queue;      /* robot i's at i x cfg->queue */
    sim_rand_t *rand;            /* loss and estimate noise at this receiver (and its slots) */
    uint8_t *hits;               /* slots: n x slots frame counts */
    uint16_t (*slot_of)[IRCOM_TX_MAX];   /* slots: each sender's frames' slots */
} ircom_t;

static void ircom_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    const ircom_config_t *c = config;
    uint32_t n = scenario_robot_count(sc);
    out->arrays = ARRAYS;
    out->elem_size[OUT] = sizeof(ircom_out_t);
    out->elem_size[INBOX] = sizeof(ircom_inbox_t);
    out->elem_size[QUEUE] = (size_t)c->queue * sizeof(hal_ircom_msg_t);
    out->elem_size[RAND] = sizeof(sim_rand_t);
    out->run_bytes = sizeof(ircom_t) + (c->slots ? (size_t)n * (c->slots + sizeof(uint16_t[IRCOM_TX_MAX])) : 0);
}

static int ircom_create(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX])
{
    const ircom_config_t *c = config;
    ircom_t *m = calloc(1, sizeof *m);
    size_t n = sim->n ? sim->n : 1;
    if (!m) {
        snprintf(err, SIM_ERR_MAX, "out of memory for IR communication");
        return -1;
    }
    *self = m;
    m->cfg = c;
    m->out = sim_model_array(sim, SIM_MODEL_ircom, OUT);
    m->inbox = sim_model_array(sim, SIM_MODEL_ircom, INBOX);
    m->queue = sim_model_array(sim, SIM_MODEL_ircom, QUEUE);
    m->rand = sim_model_array(sim, SIM_MODEL_ircom, RAND);
    /* The collision model's counts, made once: a step cannot fail. */
    if (c->slots > 0 && (!(m->hits = calloc(n * c->slots, 1)) || !(m->slot_of = calloc(n, sizeof *m->slot_of)))) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the IR collision model (%u robots x %u slots)", sim->n,
                 c->slots);
        return -1;
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        sim_rand_seed(&m->rand[i], sim->seed, i, RAND_IRCOM);
    }
    for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
        m->sensor_rad[k] = units_ir_bearing_mrad(k) / 1000.0f;
    }
    return 0;
}

static void ircom_destroy(void *self)
{
    ircom_t *m = self;
    if (m) {
        free(m->hits);
        free(m->slot_of);
        free(m);
    }
}

#define IRCOM_MAX_NEAR 256

static int blocked(struct sim *sim, const ircom_t *m, sim_scratch_t *ws, uint32_t from, uint32_t to)
{
    vec2_t p = sim_robot_at(sim, from), q = sim_robot_at(sim, to);
    uint32_t near[IRCOM_MAX_NEAR], n;
    if (sim_obstacles_cut(sim, ws, p, q)) {
        return 1;
    }
    if (m->cfg->blocked_by_robots) {
        n = sim_gather_robots(sim, fminf(p.x, q.x) - EPUCK_BODY_RADIUS_M, fminf(p.y, q.y) - EPUCK_BODY_RADIUS_M,
                              fmaxf(p.x, q.x) + EPUCK_BODY_RADIUS_M, fmaxf(p.y, q.y) + EPUCK_BODY_RADIUS_M,
                              near, IRCOM_MAX_NEAR);
        for (uint32_t k = 0; k < n; k++) {
            if (near[k] != from && near[k] != to
                && geom_segment_hits_circle(p, q, sim_robot_at(sim, near[k]), EPUCK_BODY_RADIUS_M)) {
                return 1;
            }
        }
    }
    return 0;
}

static void receive(struct sim *sim, ircom_t *m, uint32_t to, uint32_t from, uint16_t value)
{
    const sim_robot_t *r = &sim->robots[to];
    vec2_t s = sim_robot_at(sim, from);
    const ircom_config_t *cfg = m->cfg;
    sim_rand_t *rnd = &m->rand[to];
    if (sim_rand_uniform(rnd) < cfg->loss) {
        return;
    }
    float dx = s.x - r->x, dy = s.y - r->y;
    if (cfg->bearing_noise_vec > 0.0f) {
        /* Seed 003: uniform azimuth, Gaussian length. */
        double az = 2.0 * UNITS_PI * sim_rand_uniform(rnd);
        double len = cfg->bearing_noise_vec * sim_rand_normal(rnd);
        dx += (float)(len * cos(az));
        dy += (float)(len * sin(az));
    }
    float bearing = geom_wrap(atan2f(dy, dx) - r->theta);
    /* The receiving sensor is the one whose bearing is closest. */
    uint8_t sensor = 0;
    float best = INFINITY;
    for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
        float off = fabsf(geom_wrap(bearing - m->sensor_rad[k]));
        if (off < best) {
            best = off;
            sensor = k;
        }
    }
    float est = cfg->quantise_bearing
        ? m->sensor_rad[sensor]
        : geom_wrap(bearing + cfg->bearing_noise * (float)UNITS_PI / 180.0f * (float)sim_rand_normal(rnd));
    double range = sqrt((double)dx * dx + (double)dy * dy);
    range *= 1.0 + cfg->range_noise_rel * sim_rand_normal(rnd);
    if (range < 0.0) range = 0.0;
    ircom_inbox_t *in = &m->inbox[to];
    if (in->count >= cfg->queue) {
        in->dropped++;
        return;
    }
    uint32_t slot = (uint32_t)in->head + in->count;   /* below 2 x queue: no division */
    hal_ircom_msg_t *msg = &m->queue[(size_t)to * cfg->queue + (slot >= cfg->queue ? slot - cfg->queue : slot)];
    msg->value = value;
    msg->sensor = sensor;
    msg->bearing_mrad = (int16_t)lroundf(est * 1000.0f);
    msg->range_mm = (uint16_t)fmin(range * 1000.0 + 0.5, 65535.0);
    in->count++;
}

/* Whether robot j hears robot i's frames (range, radios, line of sight). */
static int reaches(struct sim *sim, const ircom_t *m, sim_scratch_t *ws, uint32_t i, uint32_t j, float reach)
{
    vec2_t s = sim_robot_at(sim, i), r = sim_robot_at(sim, j);
    float dx = r.x - s.x, dy = r.y - s.y;
    /* Nothing can block a line without obstacles or robots that block: the
     * test's call and its empty queries were half of this function. */
    int can_block = sim->n_obstacles > 0 || m->cfg->blocked_by_robots;
    return j != i && dx * dx + dy * dy <= reach * reach && !faults_radio_out(sim, j)
           && !(can_block && blocked(sim, m, ws, i, j));
}

/* The collision model (`slots`): every frame gets a slot; frames in a slot
 * that two or more reach at one receiver are lost there.  hits[j * slots +
 * k] counts the frames that reach robot j in slot k. */
static void deliver_slotted(struct sim *sim, ircom_t *m, uint32_t first)
{
    float reach = m->cfg->range;
    uint32_t slots = m->cfg->slots;
    uint32_t near[IRCOM_MAX_NEAR];
    uint8_t *hits = m->hits;
    uint16_t (*slot_of)[IRCOM_TX_MAX] = m->slot_of;
    memset(hits, 0, (size_t)sim->n * slots);
    memset(slot_of, 0, (size_t)sim->n * sizeof *slot_of);
    for (uint32_t i = 0; i < sim->n; i++) {
        const sim_robot_t *s = &sim->robots[i];
        const ircom_out_t *o = &m->out[i];
        /* Distinct random slots for this sender's frames (partial shuffle). */
        for (uint8_t f = 0; f < o->n; f++) {
            uint16_t k;
            int taken;
            do {
                k = (uint16_t)(sim_rand_uniform(&m->rand[i]) * slots);
                if (k >= slots) k = (uint16_t)(slots - 1);
                taken = 0;
                for (uint8_t g = 0; g < f; g++) taken |= slot_of[i][g] == k;
            } while (taken);
            slot_of[i][f] = k;
        }
        if (o->n == 0 || faults_radio_out(sim, i)) continue;
        /* Half duplex: a robot's own frame blinds it in that slot. */
        for (uint8_t f = 0; f < o->n; f++) {
            uint8_t *h = &hits[(size_t)i * slots + slot_of[i][f]];
            if (*h < 255) (*h)++;
        }
        uint32_t n = sim_gather_robots(sim, s->x - reach, s->y - reach, s->x + reach, s->y + reach, near,
                                       IRCOM_MAX_NEAR);
        for (uint32_t k = 0; k < n; k++) {
            if (!reaches(sim, m, &sim->scratch[0], i, near[k], reach)) continue;
            for (uint8_t f = 0; f < o->n; f++) {
                uint8_t *h = &hits[(size_t)near[k] * slots + slot_of[i][f]];
                if (*h < 255) (*h)++;
            }
        }
    }
    for (uint32_t turn = 0; turn < sim->n; turn++) {
        uint32_t i = first + turn < sim->n ? first + turn : first + turn - sim->n;
        const sim_robot_t *s = &sim->robots[i];
        ircom_out_t *o = &m->out[i];
        uint8_t n_tx = o->n;
        o->n = 0;
        if (n_tx == 0 || faults_radio_out(sim, i)) continue;
        uint32_t n = sim_gather_robots(sim, s->x - reach, s->y - reach, s->x + reach, s->y + reach, near,
                                       IRCOM_MAX_NEAR);
        for (uint8_t f = 0; f < n_tx; f++) {
            for (uint32_t k = 0; k < n; k++) {
                uint32_t j = near[k];
                if (reaches(sim, m, &sim->scratch[0], i, j, reach) && hits[(size_t)j * slots + slot_of[i][f]] == 1) {
                    receive(sim, m, j, i, o->msg[f]);
                }
            }
        }
    }
}

typedef struct delivery {
    struct sim *sim;
    ircom_t *m;
    uint32_t first;   /**< the sender whose turn comes first this step */
} delivery_t;

/* pool_fn: receivers [begin, end).  Receiver j hears sender i when j lies
 * in the box of half-side `reach` around i (as a query around the sender
 * would find it) and reaches() holds; senders in turn order from `first`,
 * each one's frames in sending order. */
static void receive_range(uint32_t begin, uint32_t end, uint32_t worker, void *ctx)
{
    const delivery_t *d = ctx;
    struct sim *sim = d->sim;
    ircom_t *im = d->m;
    sim_scratch_t *ws = &sim->scratch[worker];
    float reach = im->cfg->range, m = reach * 1.001f + 1e-4f;
    for (uint32_t j = begin; j < end; j++) {
        const sim_robot_t *r = &sim->robots[j];
        uint32_t *from = ws->robots;
        uint32_t n = sim_gather_robots(sim, r->x - m, r->y - m, r->x + m, r->y + m, from, sim->n), kept = 0;
        for (uint32_t c = 0; c < n; c++) {
            uint32_t i = from[c];
            vec2_t s = sim_robot_at(sim, i);
            if (im->out[i].n == 0 || faults_radio_out(sim, i) || r->x < s.x - reach || r->x > s.x + reach
                || r->y < s.y - reach || r->y > s.y + reach) {
                continue;
            }
            /* Kept by turn, (i - first) mod n: sorted as ids, then back. */
            from[kept++] = i >= d->first ? i - d->first : i + sim->n - d->first;
        }
        grid_sort_ids(from, kept);
        for (uint32_t c = 0; c < kept; c++) {
            uint32_t turn = from[c], i = turn < sim->n - d->first ? turn + d->first : turn - (sim->n - d->first);
            const ircom_out_t *o = &im->out[i];
            if (reaches(sim, im, ws, i, j, reach)) {
                for (uint8_t f = 0; f < o->n; f++) {
                    receive(sim, im, j, i, o->msg[f]);
                }
            }
        }
    }
}

/* Receivers take a microsecond or so each. */
#define RECEIVE_CHUNK 128u

/* After the controllers (and the faulty robots' messages): this step's
 * messages reach their receivers, readable from the next step. */
static void ircom_deliver(sim_t *sim, void *self)
{
    ircom_t *m = self;
    uint32_t first = sim->n ? (uint32_t)(sim->step % sim->n) : 0;
    if (m->cfg->slots > 0) {
        deliver_slotted(sim, m, first);
        return;
    }
    uint32_t senders = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        senders += m->out[i].n != 0;
    }
    if (senders > 0) {
        delivery_t d = { sim, m, first };
        pool_for(sim->pool, sim->n, RECEIVE_CHUNK, receive_range, &d);
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        m->out[i].n = 0;
    }
}

void ircom_set_outgoing(sim_t *sim, uint32_t robot, uint16_t value)
{
    ircom_t *m = sim_model_self(sim, SIM_MODEL_ircom);
    m->out[robot].msg[0] = (uint16_t)(value & (uint16_t)((1u << m->cfg->payload_bits) - 1u));
    m->out[robot].n = 1;
}

int sim_ircom_inject(sim_t *sim, uint32_t i, const hal_ircom_msg_t *msg)
{
    ircom_t *m = sim_model_self(sim, SIM_MODEL_ircom);
    ircom_inbox_t *in = &m->inbox[i];
    SIM_ASSERT(i < sim->n);
    if (in->count >= m->cfg->queue) {
        return -1;
    }
    m->queue[(size_t)i * m->cfg->queue + (in->head + in->count) % m->cfg->queue] = *msg;
    in->count++;
    return 0;
}

float sim_ircom_range_m(const sim_t *sim)
{
    return ((const ircom_config_t *)sim_model_config(sim, SIM_MODEL_ircom))->range;
}

/* ---------------------------------------------------------------- HAL */

uint8_t hal_ircom_payload_bits(hal_t *hal)
{
    return ((const ircom_config_t *)sim_model_config(hal->sim, SIM_MODEL_ircom))->payload_bits;
}

hal_status_t hal_ircom_send(hal_t *hal, uint16_t value)
{
    ircom_t *m = sim_model_self(hal->sim, SIM_MODEL_ircom);
    ircom_out_t *o = &m->out[hal->index];
    if (o->n >= m->cfg->tx_per_period) {
        return HAL_ERR_BUSY;
    }
    o->msg[o->n++] = (uint16_t)(value & (uint16_t)((1u << m->cfg->payload_bits) - 1u));
    return HAL_OK;
}

hal_status_t hal_ircom_receive(hal_t *hal, hal_ircom_msg_t *out)
{
    ircom_t *m = sim_model_self(hal->sim, SIM_MODEL_ircom);
    ircom_inbox_t *in = &m->inbox[hal->index];
    if (in->count == 0) {
        return HAL_ERR_EMPTY;
    }
    *out = m->queue[(size_t)hal->index * m->cfg->queue + in->head];
    in->head = (uint8_t)(in->head + 1u == m->cfg->queue ? 0u : in->head + 1u);
    in->count--;
    return HAL_OK;
}

/* What waits in its inbox (delivered, not yet read), oldest first. */
static void ircom_inspect(const sim_t *sim, const void *self, uint32_t robot, model_inspect_t *out)
{
    const ircom_t *m = self;
    (void)sim;
    if (m == NULL) {
        return;
    }
    const ircom_inbox_t *in = &m->inbox[robot];
    out->ircom_range_m = m->cfg->range;
    for (uint8_t k = 0; k < in->count && out->n_heard < MODEL_INSPECT_HEARD; k++) {
        uint32_t at = (in->head + k) % m->cfg->queue;
        out->heard[out->n_heard++] = m->queue[(size_t)robot * m->cfg->queue + at];
    }
}

static const char *const ircom_hal_calls[] = {
    "hal_ircom_payload_bits", "hal_ircom_send", "hal_ircom_receive", NULL
};

static const model_field_t ircom_fields[] = {
    { "ircom.inbox", "messages", "messages waiting in the inbox", SIM_FIELD_U8, INBOX,
      offsetof(ircom_inbox_t, count), 1 },
    { "ircom.dropped", "messages", "arrivals a full inbox refused so far", SIM_FIELD_U32, INBOX,
      offsetof(ircom_inbox_t, dropped), 1 },
    { NULL, NULL, NULL, SIM_FIELD_U8, 0, 0, 0 }
};

const model_def_t ircom_model = {
    .name = "ircom",
    .doc = "IR communication between robots (libIrcom, or the range-and-bearing turret)",
    .config_size = sizeof(ircom_config_t),
    .default_config = ircom_defaults,
    .schema = &ircom_schema,
    .check = ircom_check,
    .layout = ircom_layout,
    .create = ircom_create,
    .destroy = ircom_destroy,
    .after_control = ircom_deliver,
    .inspect = ircom_inspect,
    .hal_calls = ircom_hal_calls,
    .fields = ircom_fields,
};
