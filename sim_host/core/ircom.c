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
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "pool.h"
#include "sim_internal.h"
#include "units.h"

#define IRCOM_MAX_NEAR 256

static int blocked(struct sim *sim, sim_scratch_t *ws, uint32_t from, uint32_t to)
{
    const sim_robot_t *a = &sim->robots[from], *b = &sim->robots[to];
    vec2_t p = v2(a->x, a->y), q = v2(b->x, b->y);
    uint32_t near[IRCOM_MAX_NEAR];
    uint32_t n = sim_gather_obstacles(sim, ws, fminf(p.x, q.x), fminf(p.y, q.y), fmaxf(p.x, q.x),
                                      fmaxf(p.y, q.y), near, IRCOM_MAX_NEAR);
    for (uint32_t k = 0; k < n; k++) {
        const obstacle_t *o = &sim->obstacles[near[k]];
        if (o->shape == SHAPE_CYLINDER) {
            if (geom_segment_hits_circle(p, q, o->c, o->r)) return 1;
        } else {
            for (int e = 0; e < 4; e++) {
                if (geom_segments_intersect(p, q, o->corner[e], o->corner[(e + 1) & 3])) return 1;
            }
        }
    }
    if (sim->sc->ircom.blocked_by_robots) {
        n = sim_gather_robots(sim, fminf(p.x, q.x) - EPUCK_BODY_RADIUS_M, fminf(p.y, q.y) - EPUCK_BODY_RADIUS_M,
                              fmaxf(p.x, q.x) + EPUCK_BODY_RADIUS_M, fmaxf(p.y, q.y) + EPUCK_BODY_RADIUS_M,
                              near, IRCOM_MAX_NEAR);
        for (uint32_t k = 0; k < n; k++) {
            const sim_robot_t *c = &sim->robots[near[k]];
            if (near[k] != from && near[k] != to && geom_segment_hits_circle(p, q, v2(c->x, c->y), EPUCK_BODY_RADIUS_M)) {
                return 1;
            }
        }
    }
    return 0;
}

static void receive(struct sim *sim, uint32_t to, uint32_t from, uint16_t value)
{
    sim_robot_t *r = &sim->robots[to];
    const sim_robot_t *s = &sim->robots[from];
    const scenario_t *sc = sim->sc;
    if (sim_rand_uniform(&r->ircom_rand) < sc->ircom.loss) {
        return;
    }
    float dx = s->x - r->x, dy = s->y - r->y;
    if (sc->ircom.bearing_noise_vec > 0.0f) {
        /* Seed 003: uniform azimuth, Gaussian length. */
        double az = 2.0 * UNITS_PI * sim_rand_uniform(&r->ircom_rand);
        double len = sc->ircom.bearing_noise_vec * sim_rand_normal(&r->ircom_rand);
        dx += (float)(len * cos(az));
        dy += (float)(len * sin(az));
    }
    float bearing = geom_wrap(atan2f(dy, dx) - r->theta);
    /* The receiving sensor is the one whose bearing is closest. */
    uint8_t sensor = 0;
    float best = INFINITY;
    for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
        float off = fabsf(geom_wrap(bearing - hal_ir_bearing_mrad(&r->hal, k) / 1000.0f));
        if (off < best) {
            best = off;
            sensor = k;
        }
    }
    float est = sc->ircom.quantise_bearing
        ? hal_ir_bearing_mrad(&r->hal, sensor) / 1000.0f
        : geom_wrap(bearing + sc->ircom.bearing_noise * (float)UNITS_PI / 180.0f * (float)sim_rand_normal(&r->ircom_rand));
    double range = sqrt((double)dx * dx + (double)dy * dy);
    range *= 1.0 + sc->ircom.range_noise_rel * sim_rand_normal(&r->ircom_rand);
    if (range < 0.0) range = 0.0;
    if (r->rx_count >= sc->ircom.queue) {
        r->rx_dropped++;
        return;
    }
    hal_ircom_msg_t *m = &r->rx[(r->rx_head + r->rx_count) % sc->ircom.queue];
    m->value = value;
    m->sensor = sensor;
    m->bearing_mrad = (int16_t)lroundf(est * 1000.0f);
    m->range_mm = (uint16_t)fmin(range * 1000.0 + 0.5, 65535.0);
    r->rx_count++;
}

/* Whether robot j hears robot i's frames (range, radios, line of sight). */
static int reaches(struct sim *sim, sim_scratch_t *ws, uint32_t i, uint32_t j, float reach)
{
    const sim_robot_t *s = &sim->robots[i], *r = &sim->robots[j];
    float dx = r->x - s->x, dy = r->y - s->y;
    return j != i && dx * dx + dy * dy <= reach * reach && !faults_radio_out(sim, j) && !blocked(sim, ws, i, j);
}

/* The collision model (`slots`): every frame gets a slot; frames in a slot
 * that two or more reach at one receiver are lost there.  hits[j * slots +
 * k] counts the frames that reach robot j in slot k. */
static void deliver_slotted(struct sim *sim, uint32_t first)
{
    float reach = sim->sc->ircom.range;
    uint32_t slots = sim->sc->ircom.slots;
    uint32_t near[IRCOM_MAX_NEAR];
    uint8_t *hits = calloc((size_t)sim->n * slots, 1);
    uint16_t (*slot_of)[SIM_IRCOM_TX_MAX] = calloc(sim->n, sizeof *slot_of);
    if (hits == NULL || slot_of == NULL) {
        fprintf(stderr, "swarmsim: out of memory in the IR collision model\n");
        abort();
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        sim_robot_t *s = &sim->robots[i];
        /* Distinct random slots for this sender's frames (partial shuffle). */
        for (uint8_t f = 0; f < s->ircom_tx_n; f++) {
            uint16_t k;
            int taken;
            do {
                k = (uint16_t)(sim_rand_uniform(&s->ircom_rand) * slots);
                if (k >= slots) k = (uint16_t)(slots - 1);
                taken = 0;
                for (uint8_t g = 0; g < f; g++) taken |= slot_of[i][g] == k;
            } while (taken);
            slot_of[i][f] = k;
        }
        if (s->ircom_tx_n == 0 || faults_radio_out(sim, i)) continue;
        /* Half duplex: a robot's own frame blinds it in that slot. */
        for (uint8_t f = 0; f < s->ircom_tx_n; f++) {
            uint8_t *h = &hits[(size_t)i * slots + slot_of[i][f]];
            if (*h < 255) (*h)++;
        }
        uint32_t n = sim_gather_robots(sim, s->x - reach, s->y - reach, s->x + reach, s->y + reach, near,
                                       IRCOM_MAX_NEAR);
        for (uint32_t k = 0; k < n; k++) {
            if (!reaches(sim, &sim->scratch[0], i, near[k], reach)) continue;
            for (uint8_t f = 0; f < s->ircom_tx_n; f++) {
                uint8_t *h = &hits[(size_t)near[k] * slots + slot_of[i][f]];
                if (*h < 255) (*h)++;
            }
        }
    }
    for (uint32_t turn = 0; turn < sim->n; turn++) {
        uint32_t i = first + turn < sim->n ? first + turn : first + turn - sim->n;
        sim_robot_t *s = &sim->robots[i];
        uint8_t n_tx = s->ircom_tx_n;
        s->ircom_tx_n = 0;
        if (n_tx == 0 || faults_radio_out(sim, i)) continue;
        uint32_t n = sim_gather_robots(sim, s->x - reach, s->y - reach, s->x + reach, s->y + reach, near,
                                       IRCOM_MAX_NEAR);
        for (uint8_t f = 0; f < n_tx; f++) {
            for (uint32_t k = 0; k < n; k++) {
                uint32_t j = near[k];
                if (reaches(sim, &sim->scratch[0], i, j, reach) && hits[(size_t)j * slots + slot_of[i][f]] == 1) {
                    receive(sim, j, i, s->ircom_tx[f]);
                }
            }
        }
    }
    free(hits);
    free(slot_of);
}

typedef struct delivery {
    struct sim *sim;
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
    sim_scratch_t *ws = &sim->scratch[worker];
    float reach = sim->sc->ircom.range, m = reach * 1.001f + 1e-4f;
    for (uint32_t j = begin; j < end; j++) {
        const sim_robot_t *r = &sim->robots[j];
        uint32_t *from = ws->robots;
        uint32_t n = sim_gather_robots(sim, r->x - m, r->y - m, r->x + m, r->y + m, from, sim->n), kept = 0;
        for (uint32_t c = 0; c < n; c++) {
            uint32_t i = from[c];
            const sim_robot_t *s = &sim->robots[i];
            if (s->ircom_tx_n == 0 || faults_radio_out(sim, i) || r->x < s->x - reach || r->x > s->x + reach
                || r->y < s->y - reach || r->y > s->y + reach) {
                continue;
            }
            /* Insert by turn: (i - first) mod n. */
            uint32_t turn = i >= d->first ? i - d->first : i + sim->n - d->first, at = kept++;
            while (at > 0) {
                uint32_t p = from[at - 1], pt = p >= d->first ? p - d->first : p + sim->n - d->first;
                if (pt < turn) break;
                from[at] = p;
                at--;
            }
            from[at] = i;
        }
        for (uint32_t c = 0; c < kept; c++) {
            uint32_t i = from[c];
            const sim_robot_t *s = &sim->robots[i];
            if (reaches(sim, ws, i, j, reach)) {
                for (uint8_t f = 0; f < s->ircom_tx_n; f++) {
                    receive(sim, j, i, s->ircom_tx[f]);
                }
            }
        }
    }
}

/* Receivers take a microsecond or so each. */
#define RECEIVE_CHUNK 128u

void ircom_deliver(struct sim *sim)
{
    uint32_t first = sim->n ? (uint32_t)(sim->step % sim->n) : 0;
    if (sim->sc->ircom.slots > 0) {
        deliver_slotted(sim, first);
        return;
    }
    uint32_t senders = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        senders += sim->robots[i].ircom_tx_n != 0;
    }
    if (senders > 0) {
        delivery_t d = { sim, first };
        pool_for(sim->pool, sim->n, RECEIVE_CHUNK, receive_range, &d);
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        sim->robots[i].ircom_tx_n = 0;
    }
}
