/*
 * pfias.c - PFIAS chain-based path formation (see pfias.h and
 * docs/notes/i15_baselines.md for what is sourced and reconstructed), and
 * the chain model of TSASR (firmware/tsasr/tsasr.h): with params `elim`,
 * step_member's tail timer and retreat, the explorers' respect of a
 * retreating tail, and TSASR's frames (docs/notes/i15_tsasr.md).
 */
#include "pfias/pfias.h"

#include <stddef.h>

#include "units.h"
#include "pfias/pfias_msg.h"
#include "repatt/odometry.h"

void pfias_default_params(pfias_params_t *params)
{
    random_walk_default_params(&params->walk);
    /* P_e->c = 0.01 per control step: the upper end of the best range,
     * [0.005, 0.01], the swarm-bots chain experiments report (notes). */
    params->p_join = 655u;
    /* P_c->e: no published value found; 0.01 per step is our
     * reconstruction (notes), a parameter to sweep. */
    params->p_leave = 655u;
    params->range_mm = 600u;        /* Table 2: R = 0.6 m */
    params->link_mm = 450u;         /* 0.75 R: reconstruction (notes) */
    params->speed_steps_s = 388;    /* Table 2: 5 cm/s */
    params->turn_gain = 388;        /* full speed difference at 1 rad */
    params->forget_steps = 3u;
    params->lost_steps = 30u;       /* 3 s */
    params->leave_needs_no_explorer = 1u;
    /* No elimination (tsasr_default_params turns it on, with its values). */
    params->elim = 0u;
    params->elim_steps = 0u;
    params->retreat_steps = 0u;
    params->elim_cascade = 0u;
    params->elim_explorer_resets = 0u;
    params->role = (uint8_t)PFIAS_ROLE_ROBOT;
    params->walk.speed_steps_s = params->speed_steps_s;
}

void pfias_init(pfias_t *self, const pfias_params_t *params, uint32_t seed)
{
    self->params = *params;
    self->seed = seed;
    pfias_reset(self);
}

void pfias_reset(pfias_t *self)
{
    random_walk_params_t wp = self->params.walk;
    uint8_t i;
    rng_seed(&self->rng, self->seed);
    wp.speed_steps_s = self->params.speed_steps_s;
    /* The walk draws from its own stream, seeded apart from ours. */
    random_walk_init(&self->walk, &wp, self->seed ^ 0x5A5A5A5Au);
    self->state = (uint8_t)(self->params.role == (uint8_t)PFIAS_ROLE_ROBOT ? PFIAS_LOST : PFIAS_SOURCE);
    self->outward = 1u;
    self->ref = PFIAS_REF_NEST;
    self->circle_sign = 1;
    self->colour = 0u;
    self->tail = 0u;
    self->prey = 0u;
    self->retreat = 0u;
    self->follow = 0u;
    self->missing = 0u;
    self->idle = 0u;
    self->joins = 0u;
    self->leaves = 0u;
    self->eliminations = 0u;
    for (i = 0; i < PFIAS_MAX_NEIGHBOURS; i++) {
        self->nb[i].kind = PFIAS_MSG_INVALID;
    }
}

const char *pfias_state_name(const pfias_t *self)
{
    switch (self->state) {
    case PFIAS_LOST: return "lost";
    case PFIAS_EXPLORER: return "explorer";
    case PFIAS_MEMBER: return "member";
    default: return "source";
    }
}

/* ------------------------------------------------------------ neighbours */

static void age_neighbours(pfias_t *self)
{
    uint8_t i;
    for (i = 0; i < PFIAS_MAX_NEIGHBOURS; i++) {
        pfias_neighbour_t *n = &self->nb[i];
        if (n->kind == PFIAS_MSG_INVALID) {
            continue;
        }
        if (n->age >= self->params.forget_steps) {
            n->kind = PFIAS_MSG_INVALID;
        } else {
            n->age++;
        }
    }
}

/* The slot of `id`, else a free one, else the stalest (farthest on a tie). */
static pfias_neighbour_t *slot_for(pfias_t *self, uint16_t id)
{
    pfias_neighbour_t *best = NULL;
    uint8_t i;
    for (i = 0; i < PFIAS_MAX_NEIGHBOURS; i++) {
        pfias_neighbour_t *n = &self->nb[i];
        if (n->kind != PFIAS_MSG_INVALID && n->id == id) {
            return n;
        }
    }
    for (i = 0; i < PFIAS_MAX_NEIGHBOURS; i++) {
        pfias_neighbour_t *n = &self->nb[i];
        if (n->kind == PFIAS_MSG_INVALID) {
            return n;
        }
        if (best == NULL || n->age > best->age
            || (n->age == best->age && n->range_mm > best->range_mm)) {
            best = n;
        }
    }
    return best;
}

/* The frames it sends and reads: PFIAS's, or TSASR's with elimination. */
static uint8_t frame_format(const pfias_t *self)
{
    return self->params.elim != 0u ? (uint8_t)PFIAS_FMT_RETREAT : (uint8_t)PFIAS_FMT_PFIAS;
}

static void hear(pfias_t *self, hal_t *hal)
{
    hal_ircom_msg_t m;
    pfias_msg_t d;
    uint8_t fmt = frame_format(self);
    uint16_t own = pfias_fmt_id(fmt, hal_robot_id(hal));
    while (hal_ircom_receive(hal, &m) == HAL_OK) {
        pfias_neighbour_t *n;
        if (pfias_fmt_decode(fmt, m.value, &d) == PFIAS_MSG_INVALID || m.range_mm > self->params.range_mm
            || d.id == own) {
            continue;   /* not ours, beyond R, or our own echo */
        }
        n = slot_for(self, d.id);
        n->id = d.id;
        n->kind = d.kind;
        n->colour = d.colour;
        n->tail = d.tail;
        n->prey = d.prey;
        n->retreat = d.retreat;
        n->age = 0u;
        n->range_mm = m.range_mm;
        n->bearing_mrad = m.bearing_mrad;
    }
}

const pfias_neighbour_t *pfias_nearest(const pfias_t *self, uint8_t kind, uint8_t colour)
{
    const pfias_neighbour_t *best = NULL;
    uint8_t i;
    for (i = 0; i < PFIAS_MAX_NEIGHBOURS; i++) {
        const pfias_neighbour_t *n = &self->nb[i];
        if (n->kind != kind || (kind == PFIAS_MSG_CHAIN && colour < PFIAS_COLOURS && n->colour != colour)) {
            continue;
        }
        if (best == NULL || n->range_mm < best->range_mm) {
            best = n;
        }
    }
    return best;
}

uint8_t pfias_count(const pfias_t *self, uint8_t kind)
{
    uint8_t i, c = 0u;
    for (i = 0; i < PFIAS_MAX_NEIGHBOURS; i++) {
        if (self->nb[i].kind == kind) {
            c++;
        }
    }
    return c;
}

/* The neighbour an explorer's reference names, or NULL. */
static const pfias_neighbour_t *reference(const pfias_t *self)
{
    if (self->ref == PFIAS_REF_NEST) {
        return pfias_nearest(self, PFIAS_MSG_NEST, 0u);
    }
    return pfias_nearest(self, PFIAS_MSG_CHAIN, self->ref);
}

/* ------------------------------------------------------------ motion */

/* Sums AD and MP about `ref` (NULL: straight ahead) and AO, and drives
 * along the sum: turning in place when it points backwards. */
static void move_about(pfias_t *self, hal_t *hal, const pfias_neighbour_t *ref)
{
    const pfias_params_t *p = &self->params;
    int32_t x = 0, y = 0;   /* robot frame, 1000 = one unit behaviour */
    int32_t angle, fwd, turn;
    uint8_t i;

    if (ref != NULL) {
        int32_t link = p->link_mm > 0u ? (int32_t)p->link_mm : 1;
        int32_t ad = (((int32_t)ref->range_mm - link) * 1000L) / link;
        int32_t perp = (int32_t)ref->bearing_mrad + (int32_t)self->circle_sign * UNITS_HALF_PI_MRAD;
        if (ad > 1000) ad = 1000;
        if (ad < -1000) ad = -1000;
        /* AD: towards the reference when farther than link_mm, away when nearer. */
        x += (ad * odo_cos_q14(ref->bearing_mrad)) / 16384L;
        y += (ad * odo_sin_q14(ref->bearing_mrad)) / 16384L;
        /* MP: perpendicular to the reference's direction: around it. */
        x += (1000L * odo_cos_q14(perp)) / 16384L;
        y += (1000L * odo_sin_q14(perp)) / 16384L;
    } else {
        x += 1000;
    }
    /* AO: away from every excited IR sensor (500 counts ~ one behaviour). */
    for (i = 0; i < HAL_IR_COUNT; i++) {
        int32_t prox = (int32_t)hal_ir_proximity(hal, i);
        int32_t b = hal_ir_bearing_mrad(hal, i);
        if (prox > 4000) prox = 4000;
        x -= (prox * 2L * odo_cos_q14(b)) / 16384L;
        y -= (prox * 2L * odo_sin_q14(b)) / 16384L;
    }
    angle = odo_atan2_mrad(y, x);
    turn = ((int32_t)p->turn_gain * angle) / 1000L;
    if (turn > p->speed_steps_s) turn = p->speed_steps_s;
    if (turn < -p->speed_steps_s) turn = -p->speed_steps_s;
    fwd = 0;
    if (angle > -UNITS_HALF_PI_MRAD && angle < UNITS_HALF_PI_MRAD) {
        fwd = ((int32_t)p->speed_steps_s * odo_cos_q14(angle)) / 16384L;
    }
    hal_set_wheel_speeds(hal, (int16_t)(fwd - turn), (int16_t)(fwd + turn));
}

/* ------------------------------------------------------------ transitions */

static void become_member(pfias_t *self, uint8_t colour, uint8_t prey)
{
    self->state = (uint8_t)PFIAS_MEMBER;
    self->colour = (uint8_t)(colour % PFIAS_COLOURS);
    self->tail = 1u;
    self->prey = prey;
    self->retreat = 0u;
    self->follow = 0u;
    self->missing = 0u;
    self->idle = 0u;
    self->joins++;
}

static void become_explorer(pfias_t *self, uint8_t outward, uint8_t ref)
{
    self->state = (uint8_t)PFIAS_EXPLORER;
    self->outward = outward;
    self->ref = ref;
    self->missing = 0u;
    self->circle_sign = (rng_next(&self->rng) & 1u) != 0u ? 1 : -1;
}

/* Within a quarter link of the link distance: on the circle AD keeps. */
static uint8_t on_link(const pfias_t *self, const pfias_neighbour_t *n)
{
    int32_t d = (int32_t)n->range_mm - (int32_t)self->params.link_mm;
    if (d < 0) d = -d;
    return (uint8_t)(d <= (int32_t)(self->params.link_mm / 4u));
}

static void step_lost(pfias_t *self, hal_t *hal)
{
    const pfias_neighbour_t *member = pfias_nearest(self, PFIAS_MSG_CHAIN, PFIAS_COLOURS);
    if (pfias_nearest(self, PFIAS_MSG_NEST, 0u) != NULL) {
        become_explorer(self, 1u, PFIAS_REF_NEST);
    } else if (member != NULL) {
        become_explorer(self, 1u, member->colour);
    } else {
        random_walk_step(&self->walk, hal);
        return;
    }
    move_about(self, hal, reference(self));
}

/* Steps the reference along the chain: out to the next colour, back to the
 * previous one and then the nest. */
static void advance_reference(pfias_t *self)
{
    if (self->outward != 0u) {
        uint8_t next = self->ref == PFIAS_REF_NEST ? (uint8_t)PFIAS_BLUE : pfias_next_colour(self->ref);
        if (pfias_nearest(self, PFIAS_MSG_CHAIN, next) != NULL) {
            self->ref = next;
        }
    } else if (self->ref != PFIAS_REF_NEST) {
        if (self->ref == PFIAS_BLUE && pfias_nearest(self, PFIAS_MSG_NEST, 0u) != NULL) {
            self->ref = PFIAS_REF_NEST;
        } else if (pfias_nearest(self, PFIAS_MSG_CHAIN, pfias_prev_colour(self->ref)) != NULL) {
            self->ref = pfias_prev_colour(self->ref);
        }
    }
}

static void step_explorer(pfias_t *self, hal_t *hal)
{
    const pfias_params_t *p = &self->params;
    const pfias_neighbour_t *ref;
    uint8_t members = pfias_count(self, PFIAS_MSG_CHAIN);

    advance_reference(self);
    ref = reference(self);
    if (ref == NULL) {
        /* Re-synchronise on whatever of the chain is in view. */
        const pfias_neighbour_t *m = pfias_nearest(self, PFIAS_MSG_CHAIN, PFIAS_COLOURS);
        if (m != NULL) {
            self->ref = m->colour;
        } else if (pfias_nearest(self, PFIAS_MSG_NEST, 0u) != NULL) {
            self->ref = PFIAS_REF_NEST;
        }
        ref = reference(self);
    }
    if (ref == NULL) {
        if (++self->missing > p->lost_steps) {
            self->state = (uint8_t)PFIAS_LOST;
            self->missing = 0u;
        }
        move_about(self, hal, NULL);
        return;
    }
    self->missing = 0u;

    /* The prey rule: extend the chain onto the food at once. */
    if (pfias_nearest(self, PFIAS_MSG_FOOD, 0u) != NULL && members <= 1u) {
        become_member(self, self->ref == PFIAS_REF_NEST ? (uint8_t)PFIAS_BLUE : pfias_next_colour(self->ref), 1u);
        hal_set_wheel_speeds(hal, 0, 0);
        return;
    }
    if (self->outward == 0u && self->ref == PFIAS_REF_NEST && ref->range_mm <= p->link_mm + p->link_mm / 4u) {
        self->outward = 1u;   /* home: out again along a chain */
    }
    /* Elimination: a chain that retracts is not extended; an explorer that
     * reaches its end turns back (and so leaves the chain's robots free to
     * search elsewhere).  (Without elim no frame carries `retreat`.) */
    if (self->outward != 0u && self->ref != PFIAS_REF_NEST && ref->tail != 0u && ref->retreat != 0u) {
        self->outward = 0u;
    }
    /* P_e->c at the tail (only the tail in view) or at a nest without chain. */
    if (self->outward != 0u && on_link(self, ref)
        && ((self->ref == PFIAS_REF_NEST && members == 0u)
            || (self->ref != PFIAS_REF_NEST && ref->tail != 0u && ref->retreat == 0u && members == 1u))
        && rng_chance(&self->rng, p->p_join) != 0u) {
        become_member(self, self->ref == PFIAS_REF_NEST ? (uint8_t)PFIAS_BLUE : pfias_next_colour(self->ref), 0u);
        hal_set_wheel_speeds(hal, 0, 0);
        return;
    }
    move_about(self, hal, ref);
}

/* The reference a member takes when it leaves: back along its chain. */
static uint8_t way_back(const pfias_t *self, uint8_t pred)
{
    return self->colour == PFIAS_BLUE && pred != 0u && pfias_nearest(self, PFIAS_MSG_NEST, 0u) != NULL
               ? (uint8_t)PFIAS_REF_NEST : pfias_prev_colour(self->colour);
}

static void raise_retreat(pfias_t *self)
{
    self->retreat = 1u;
    self->follow = 0u;
    self->idle = 0u;
}

static void step_member(pfias_t *self, hal_t *hal)
{
    const pfias_params_t *p = &self->params;
    uint8_t next = pfias_next_colour(self->colour);
    uint8_t healthy = 0u, retreating = 0u;
    uint8_t pred, i;

    hal_set_wheel_speeds(hal, 0, 0);
    for (i = 0; i < PFIAS_MAX_NEIGHBOURS; i++) {
        const pfias_neighbour_t *n = &self->nb[i];
        if (n->kind == PFIAS_MSG_CHAIN && n->colour == next) {
            if (n->retreat != 0u) {
                retreating = 1u;
            } else {
                healthy = 1u;
            }
        }
    }
    self->tail = (uint8_t)(healthy == 0u && retreating == 0u);
    /* The successor it heard last decides what its leaving means: a healthy
     * one (the chain goes on) clears the mark a retreating one leaves. */
    if (healthy != 0u) {
        self->follow = 0u;
    } else if (retreating != 0u) {
        self->follow = 1u;
    }
    if (pfias_nearest(self, PFIAS_MSG_FOOD, 0u) != NULL) {
        self->prey = 1u;
    }
    pred = (uint8_t)(pfias_nearest(self, PFIAS_MSG_CHAIN, pfias_prev_colour(self->colour)) != NULL
                     || (self->colour == PFIAS_BLUE && pfias_nearest(self, PFIAS_MSG_NEST, 0u) != NULL));
    self->missing = pred != 0u ? 0u : (uint8_t)(self->missing + 1u);
    if (self->missing > p->lost_steps) {
        /* Cut off from the nest: the chain behind it has gone. */
        self->leaves++;
        self->prey = 0u;
        self->retreat = 0u;
        become_explorer(self, 0u, pfias_prev_colour(self->colour));
        return;
    }
    if (self->prey != 0u || healthy != 0u) {
        /* It found the target, or the chain goes on past it: it stays. */
        self->retreat = 0u;
        self->idle = 0u;
        return;
    }
    /* Without elim nothing retreats: the tail goes on to P_c->e below. */
    if (self->retreat != 0u) {
        if (retreating == 0u && ++self->idle >= p->retreat_steps) {
            self->leaves++;
            self->eliminations++;
            self->retreat = 0u;
            become_explorer(self, 0u, way_back(self, pred));
        }
        return;
    }
    if (self->tail == 0u) {
        self->idle = 0u;    /* its successor is retreating: it waits */
        return;
    }
    if (p->elim != 0u) {
        /* The tail.  Its successor left in retreat: the elimination goes on. */
        if (self->follow != 0u && p->elim_cascade != 0u) {
            raise_retreat(self);
            return;
        }
        self->follow = 0u;
        if (p->elim_explorer_resets != 0u && pfias_count(self, PFIAS_MSG_EXPLORER) != 0u) {
            self->idle = 0u;    /* an explorer may yet extend it */
        } else if (++self->idle >= p->elim_steps) {
            raise_retreat(self);   /* this frontier found nothing in time */
            return;
        }
    }
    /* P_c->e: the tail leaves at random, back along its chain. */
    if ((p->leave_needs_no_explorer == 0u || pfias_count(self, PFIAS_MSG_EXPLORER) == 0u)
        && rng_chance(&self->rng, p->p_leave) != 0u) {
        self->leaves++;
        become_explorer(self, 0u, way_back(self, pred));
    }
}

/* What the robot's LEDs would show, as its frame for this period. */
static uint16_t own_frame(const pfias_t *self, uint16_t id)
{
    uint8_t fmt = frame_format(self);
    switch (self->state) {
    case PFIAS_EXPLORER: return pfias_fmt_frame(fmt, PFIAS_MSG_EXPLORER, id);
    case PFIAS_MEMBER: return pfias_fmt_chain(fmt, id, self->colour, self->tail, self->prey, self->retreat);
    case PFIAS_SOURCE:
        return pfias_fmt_frame(fmt, self->params.role == (uint8_t)PFIAS_ROLE_FOOD ? (uint8_t)PFIAS_MSG_FOOD
                                                                                  : (uint8_t)PFIAS_MSG_NEST, id);
    default: return 0u;   /* a lost robot signals nothing */
    }
}

static void show(const pfias_t *self, hal_t *hal)
{
    uint8_t i;
    /* Members light 1..3 ring LEDs for their colour (all eight in retreat),
     * explorers the front LED. */
    for (i = 0; i < HAL_LED_COUNT; i++) {
        hal_set_led(hal, i, (uint8_t)(self->state == PFIAS_MEMBER && (i <= self->colour || self->retreat != 0u)));
    }
    hal_set_body_led(hal, (uint8_t)(self->state == PFIAS_MEMBER || self->state == PFIAS_SOURCE));
    hal_set_front_led(hal, (uint8_t)(self->state == PFIAS_EXPLORER));
}

void pfias_step(pfias_t *self, hal_t *hal)
{
    uint16_t frame;
    age_neighbours(self);
    hear(self, hal);
    switch (self->state) {
    case PFIAS_LOST:
        step_lost(self, hal);
        break;
    case PFIAS_EXPLORER:
        step_explorer(self, hal);
        break;
    case PFIAS_MEMBER:
        step_member(self, hal);
        break;
    default:
        hal_set_wheel_speeds(hal, 0, 0);
        break;
    }
    frame = own_frame(self, hal_robot_id(hal));
    if (frame != 0u) {
        (void)hal_ircom_send(hal, frame);
    }
    show(self, hal);
}
