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
 */
#include <math.h>

#include "sim_internal.h"
#include "units.h"

#define IRCOM_MAX_NEAR 256

static int blocked(struct sim *sim, uint32_t from, uint32_t to)
{
    const sim_robot_t *a = &sim->robots[from], *b = &sim->robots[to];
    vec2_t p = v2(a->x, a->y), q = v2(b->x, b->y);
    uint32_t near[IRCOM_MAX_NEAR];
    uint32_t n = sim_gather_obstacles(sim, fminf(p.x, q.x), fminf(p.y, q.y), fmaxf(p.x, q.x),
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
    if (r->rx_count >= SIM_IRCOM_QUEUE) {
        r->rx_dropped++;
        return;
    }
    hal_ircom_msg_t *m = &r->rx[(r->rx_head + r->rx_count) % SIM_IRCOM_QUEUE];
    m->value = value;
    m->sensor = sensor;
    m->bearing_mrad = (int16_t)lroundf(est * 1000.0f);
    m->range_mm = (uint16_t)fmin(range * 1000.0 + 0.5, 65535.0);
    r->rx_count++;
}

void ircom_deliver(struct sim *sim)
{
    float reach = sim->sc->ircom.range;
    uint32_t near[IRCOM_MAX_NEAR];
    uint32_t first = sim->n ? (uint32_t)(sim->step % sim->n) : 0;
    for (uint32_t turn = 0; turn < sim->n; turn++) {
        uint32_t i = first + turn < sim->n ? first + turn : first + turn - sim->n;
        sim_robot_t *s = &sim->robots[i];
        if (s->ircom_tx < 0) {
            continue;
        }
        uint16_t value = (uint16_t)s->ircom_tx;
        s->ircom_tx = -1;
        if (faults_radio_out(sim, i)) {
            continue;           /* a dead radio: the message never leaves */
        }
        uint32_t n = sim_gather_robots(sim, s->x - reach, s->y - reach, s->x + reach, s->y + reach, near,
                                       IRCOM_MAX_NEAR);
        for (uint32_t k = 0; k < n; k++) {
            uint32_t j = near[k];
            const sim_robot_t *r = &sim->robots[j];
            float dx = r->x - s->x, dy = r->y - s->y;
            if (j == i || dx * dx + dy * dy > reach * reach || faults_radio_out(sim, j) || blocked(sim, i, j)) {
                continue;
            }
            receive(sim, j, i, value);
        }
    }
}
