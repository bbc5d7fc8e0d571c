/*
 * tsasr.c - TSASR, robot chains with an elimination mechanism: a
 * RECONSTRUCTION (tsasr.h; docs/notes/i15_tsasr.md says what each rule and
 * constant is reconstructed from).  The chain model (states, colours,
 * motion, joining, the prey rule, PFIAS's random leave) follows
 * firmware/pfias/pfias.c, which TSASR builds on; the elimination mechanism
 * is step_member's tail timer and retreat.
 */
#include "tsasr/tsasr.h"

#include <stddef.h>

#include "units.h"
#include "tsasr/tsasr_msg.h"
#include "repatt/odometry.h"

void tsasr_default_params(tsasr_params_t *params)
{
    random_walk_default_params(&params->walk);
    /* The chain model's constants are PFIAS's (firmware/pfias/pfias.c):
     * seed 003 ran TSASR "with the same parameters" as PFIAS and EAIPP
     * (section 5.2, Table 2). */
    params->p_join = 655u;          /* 0.01 per step, PFIAS's P_e->c */
    /* PFIAS's random leave of a tail: reconstructed as kept (0.01 per step,
     * PFIAS's value, only with no explorer in view); TSASR's text on it was
     * not found (notes). */
    params->p_leave = 655u;
    /* Elimination (reconstruction, notes): a tail that has not found the
     * target within 30 s is eliminated; 30 s is EAIPP's PERIOD_TIME_1 in
     * this repository (firmware/eaipp, itself reconstructed: an explorer
     * at 5 cm/s crosses a 0.45 m link in 9 s), the same authors' later
     * form of the mechanism.  It then shows `retreat` for 2 s (20 steps,
     * a bit more than a neighbour's forget time, so that its predecessor
     * and the explorers about it hear the flag) before it leaves. */
    params->elim_steps = 300u;
    params->retreat_steps = 20u;
    params->elim_cascade = 1u;      /* the failed chain is eliminated as a whole (notes) */
    /* The clock runs whether or not explorers are about (the frontier is
     * judged by what it found); EAIPP's rule, "no explorer perceived
     * throughout the period", is the variant elim_explorer_resets (notes). */
    params->elim_explorer_resets = 0u;
    params->range_mm = 600u;        /* Table 2: R = 0.6 m */
    params->link_mm = 450u;         /* 0.75 R, PFIAS's link (and EAIPP's B_UL band's middle) */
    params->speed_steps_s = 388;    /* Table 2: 5 cm/s */
    params->turn_gain = 388;        /* full speed difference at 1 rad */
    params->forget_steps = 3u;
    params->lost_steps = 30u;       /* 3 s */
    params->leave_needs_no_explorer = 1u;
    params->role = (uint8_t)TSASR_ROLE_ROBOT;
    params->walk.speed_steps_s = params->speed_steps_s;
}

void tsasr_init(tsasr_t *self, const tsasr_params_t *params, uint32_t seed)
{
    self->params = *params;
    self->seed = seed;
    tsasr_reset(self);
}

void tsasr_reset(tsasr_t *self)
{
    random_walk_params_t wp = self->params.walk;
    uint8_t i;
    rng_seed(&self->rng, self->seed);
    wp.speed_steps_s = self->params.speed_steps_s;
    /* The walk draws from its own stream, seeded apart from ours. */
    random_walk_init(&self->walk, &wp, self->seed ^ 0x5A5A5A5Au);
    self->state = (uint8_t)(self->params.role == (uint8_t)TSASR_ROLE_ROBOT ? TSASR_LOST : TSASR_SOURCE);
    self->outward = 1u;
    self->ref = TSASR_REF_NEST;
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
    for (i = 0; i < TSASR_MAX_NEIGHBOURS; i++) {
        self->nb[i].kind = TSASR_MSG_INVALID;
    }
}

const char *tsasr_state_name(const tsasr_t *self)
{
    switch (self->state) {
    case TSASR_LOST: return "lost";
    case TSASR_EXPLORER: return "explorer";
    case TSASR_MEMBER: return "member";
    default: return "source";
    }
}

/* ------------------------------------------------------------ neighbours */

static void age_neighbours(tsasr_t *self)
{
    uint8_t i;
    for (i = 0; i < TSASR_MAX_NEIGHBOURS; i++) {
        tsasr_neighbour_t *n = &self->nb[i];
        if (n->kind == TSASR_MSG_INVALID) {
            continue;
        }
        if (n->age >= self->params.forget_steps) {
            n->kind = TSASR_MSG_INVALID;
        } else {
            n->age++;
        }
    }
}

/* The slot of `id`, else a free one, else the stalest (farthest on a tie). */
static tsasr_neighbour_t *slot_for(tsasr_t *self, uint8_t id)
{
    tsasr_neighbour_t *best = NULL;
    uint8_t i;
    for (i = 0; i < TSASR_MAX_NEIGHBOURS; i++) {
        tsasr_neighbour_t *n = &self->nb[i];
        if (n->kind != TSASR_MSG_INVALID && n->id == id) {
            return n;
        }
    }
    for (i = 0; i < TSASR_MAX_NEIGHBOURS; i++) {
        tsasr_neighbour_t *n = &self->nb[i];
        if (n->kind == TSASR_MSG_INVALID) {
            return n;
        }
        if (best == NULL || n->age > best->age
            || (n->age == best->age && n->range_mm > best->range_mm)) {
            best = n;
        }
    }
    return best;
}

static void hear(tsasr_t *self, hal_t *hal)
{
    hal_ircom_msg_t m;
    tsasr_msg_t d;
    uint16_t own = (uint16_t)(hal_robot_id(hal) & TSASR_ID_MASK);
    while (hal_ircom_receive(hal, &m) == HAL_OK) {
        tsasr_neighbour_t *n;
        if (tsasr_msg_decode(m.value, &d) == TSASR_MSG_INVALID || m.range_mm > self->params.range_mm
            || d.id == own) {
            continue;   /* not ours, beyond R, or our own echo */
        }
        n = slot_for(self, (uint8_t)d.id);
        n->id = (uint8_t)d.id;
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

const tsasr_neighbour_t *tsasr_nearest(const tsasr_t *self, uint8_t kind, uint8_t colour)
{
    const tsasr_neighbour_t *best = NULL;
    uint8_t i;
    for (i = 0; i < TSASR_MAX_NEIGHBOURS; i++) {
        const tsasr_neighbour_t *n = &self->nb[i];
        if (n->kind != kind || (kind == TSASR_MSG_CHAIN && colour < TSASR_COLOURS && n->colour != colour)) {
            continue;
        }
        if (best == NULL || n->range_mm < best->range_mm) {
            best = n;
        }
    }
    return best;
}

uint8_t tsasr_count(const tsasr_t *self, uint8_t kind)
{
    uint8_t i, c = 0u;
    for (i = 0; i < TSASR_MAX_NEIGHBOURS; i++) {
        if (self->nb[i].kind == kind) {
            c++;
        }
    }
    return c;
}

/* The neighbour an explorer's reference names, or NULL. */
static const tsasr_neighbour_t *reference(const tsasr_t *self)
{
    if (self->ref == TSASR_REF_NEST) {
        return tsasr_nearest(self, TSASR_MSG_NEST, 0u);
    }
    return tsasr_nearest(self, TSASR_MSG_CHAIN, self->ref);
}

/* ------------------------------------------------------------ motion */

/* Sums AD and MP about `ref` (NULL: straight ahead) and AO, and drives
 * along the sum: turning in place when it points backwards. */
static void move_about(tsasr_t *self, hal_t *hal, const tsasr_neighbour_t *ref)
{
    const tsasr_params_t *p = &self->params;
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

static void become_member(tsasr_t *self, uint8_t colour, uint8_t prey)
{
    self->state = (uint8_t)TSASR_MEMBER;
    self->colour = (uint8_t)(colour % TSASR_COLOURS);
    self->tail = 1u;
    self->prey = prey;
    self->retreat = 0u;
    self->follow = 0u;
    self->missing = 0u;
    self->idle = 0u;
    self->joins++;
}

static void become_explorer(tsasr_t *self, uint8_t outward, uint8_t ref)
{
    self->state = (uint8_t)TSASR_EXPLORER;
    self->outward = outward;
    self->ref = ref;
    self->missing = 0u;
    self->circle_sign = (rng_next(&self->rng) & 1u) != 0u ? 1 : -1;
}

/* Within a quarter link of the link distance: on the circle AD keeps. */
static uint8_t on_link(const tsasr_t *self, const tsasr_neighbour_t *n)
{
    int32_t d = (int32_t)n->range_mm - (int32_t)self->params.link_mm;
    if (d < 0) d = -d;
    return (uint8_t)(d <= (int32_t)(self->params.link_mm / 4u));
}

static void step_lost(tsasr_t *self, hal_t *hal)
{
    const tsasr_neighbour_t *member = tsasr_nearest(self, TSASR_MSG_CHAIN, TSASR_COLOURS);
    if (tsasr_nearest(self, TSASR_MSG_NEST, 0u) != NULL) {
        become_explorer(self, 1u, TSASR_REF_NEST);
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
static void advance_reference(tsasr_t *self)
{
    if (self->outward != 0u) {
        uint8_t next = self->ref == TSASR_REF_NEST ? (uint8_t)TSASR_BLUE : tsasr_next_colour(self->ref);
        if (tsasr_nearest(self, TSASR_MSG_CHAIN, next) != NULL) {
            self->ref = next;
        }
    } else if (self->ref != TSASR_REF_NEST) {
        if (self->ref == TSASR_BLUE && tsasr_nearest(self, TSASR_MSG_NEST, 0u) != NULL) {
            self->ref = TSASR_REF_NEST;
        } else if (tsasr_nearest(self, TSASR_MSG_CHAIN, tsasr_prev_colour(self->ref)) != NULL) {
            self->ref = tsasr_prev_colour(self->ref);
        }
    }
}

static void step_explorer(tsasr_t *self, hal_t *hal)
{
    const tsasr_params_t *p = &self->params;
    const tsasr_neighbour_t *ref;
    uint8_t members = tsasr_count(self, TSASR_MSG_CHAIN);

    advance_reference(self);
    ref = reference(self);
    if (ref == NULL) {
        /* Re-synchronise on whatever of the chain is in view. */
        const tsasr_neighbour_t *m = tsasr_nearest(self, TSASR_MSG_CHAIN, TSASR_COLOURS);
        if (m != NULL) {
            self->ref = m->colour;
        } else if (tsasr_nearest(self, TSASR_MSG_NEST, 0u) != NULL) {
            self->ref = TSASR_REF_NEST;
        }
        ref = reference(self);
    }
    if (ref == NULL) {
        if (++self->missing > p->lost_steps) {
            self->state = (uint8_t)TSASR_LOST;
            self->missing = 0u;
        }
        move_about(self, hal, NULL);
        return;
    }
    self->missing = 0u;

    /* The prey rule: extend the chain onto the food at once. */
    if (tsasr_nearest(self, TSASR_MSG_FOOD, 0u) != NULL && members <= 1u) {
        become_member(self, self->ref == TSASR_REF_NEST ? (uint8_t)TSASR_BLUE : tsasr_next_colour(self->ref), 1u);
        hal_set_wheel_speeds(hal, 0, 0);
        return;
    }
    if (self->outward == 0u && self->ref == TSASR_REF_NEST && ref->range_mm <= p->link_mm + p->link_mm / 4u) {
        self->outward = 1u;   /* home: out again along a chain */
    }
    /* Elimination: a chain that retracts is not extended; an explorer that
     * reaches its end turns back (and so leaves the chain's robots free to
     * search elsewhere). */
    if (self->outward != 0u && self->ref != TSASR_REF_NEST && ref->tail != 0u && ref->retreat != 0u) {
        self->outward = 0u;
    }
    /* P_e->c at the tail (only the tail in view) or at a nest without chain. */
    if (self->outward != 0u && on_link(self, ref)
        && ((self->ref == TSASR_REF_NEST && members == 0u)
            || (self->ref != TSASR_REF_NEST && ref->tail != 0u && ref->retreat == 0u && members == 1u))
        && rng_chance(&self->rng, p->p_join) != 0u) {
        become_member(self, self->ref == TSASR_REF_NEST ? (uint8_t)TSASR_BLUE : tsasr_next_colour(self->ref), 0u);
        hal_set_wheel_speeds(hal, 0, 0);
        return;
    }
    move_about(self, hal, ref);
}

/* The reference a member takes when it leaves: back along its chain. */
static uint8_t way_back(const tsasr_t *self, uint8_t pred)
{
    return self->colour == TSASR_BLUE && pred != 0u && tsasr_nearest(self, TSASR_MSG_NEST, 0u) != NULL
               ? (uint8_t)TSASR_REF_NEST : tsasr_prev_colour(self->colour);
}

static void raise_retreat(tsasr_t *self)
{
    self->retreat = 1u;
    self->follow = 0u;
    self->idle = 0u;
}

static void step_member(tsasr_t *self, hal_t *hal)
{
    const tsasr_params_t *p = &self->params;
    uint8_t next = tsasr_next_colour(self->colour);
    uint8_t healthy = 0u, retreating = 0u;
    uint8_t pred, i;

    hal_set_wheel_speeds(hal, 0, 0);
    for (i = 0; i < TSASR_MAX_NEIGHBOURS; i++) {
        const tsasr_neighbour_t *n = &self->nb[i];
        if (n->kind == TSASR_MSG_CHAIN && n->colour == next) {
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
    if (tsasr_nearest(self, TSASR_MSG_FOOD, 0u) != NULL) {
        self->prey = 1u;
    }
    pred = (uint8_t)(tsasr_nearest(self, TSASR_MSG_CHAIN, tsasr_prev_colour(self->colour)) != NULL
                     || (self->colour == TSASR_BLUE && tsasr_nearest(self, TSASR_MSG_NEST, 0u) != NULL));
    self->missing = pred != 0u ? 0u : (uint8_t)(self->missing + 1u);
    if (self->missing > p->lost_steps) {
        /* Cut off from the nest: the chain behind it has gone. */
        self->leaves++;
        self->prey = 0u;
        self->retreat = 0u;
        become_explorer(self, 0u, tsasr_prev_colour(self->colour));
        return;
    }
    if (self->prey != 0u || healthy != 0u) {
        /* It found the target, or the chain goes on past it: it stays. */
        self->retreat = 0u;
        self->idle = 0u;
        return;
    }
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
    /* The tail.  Its successor left in retreat: the elimination goes on. */
    if (self->follow != 0u && p->elim_cascade != 0u) {
        raise_retreat(self);
        return;
    }
    self->follow = 0u;
    if (p->elim_explorer_resets != 0u && tsasr_count(self, TSASR_MSG_EXPLORER) != 0u) {
        self->idle = 0u;    /* an explorer may yet extend it */
    } else if (++self->idle >= p->elim_steps) {
        raise_retreat(self);   /* this frontier found nothing in time */
        return;
    }
    if ((p->leave_needs_no_explorer == 0u || tsasr_count(self, TSASR_MSG_EXPLORER) == 0u)
        && rng_chance(&self->rng, p->p_leave) != 0u) {
        self->leaves++;
        become_explorer(self, 0u, way_back(self, pred));
    }
}

/* What the robot's LEDs would show, as its frame for this period. */
static uint16_t own_frame(const tsasr_t *self, uint16_t id)
{
    switch (self->state) {
    case TSASR_EXPLORER: return tsasr_msg_explorer(id);
    case TSASR_MEMBER: return tsasr_msg_chain(id, self->colour, self->tail, self->prey, self->retreat);
    case TSASR_SOURCE:
        return self->params.role == (uint8_t)TSASR_ROLE_FOOD ? tsasr_msg_food(id) : tsasr_msg_nest(id);
    default: return 0u;   /* a lost robot signals nothing */
    }
}

static void show(const tsasr_t *self, hal_t *hal)
{
    uint8_t i;
    /* Members light 1..3 ring LEDs for their colour (all eight in retreat),
     * explorers the front LED. */
    for (i = 0; i < HAL_LED_COUNT; i++) {
        hal_set_led(hal, i, (uint8_t)(self->state == TSASR_MEMBER && (i <= self->colour || self->retreat != 0u)));
    }
    hal_set_body_led(hal, (uint8_t)(self->state == TSASR_MEMBER || self->state == TSASR_SOURCE));
    hal_set_front_led(hal, (uint8_t)(self->state == TSASR_EXPLORER));
}

void tsasr_step(tsasr_t *self, hal_t *hal)
{
    uint16_t frame;
    age_neighbours(self);
    hear(self, hal);
    switch (self->state) {
    case TSASR_LOST:
        step_lost(self, hal);
        break;
    case TSASR_EXPLORER:
        step_explorer(self, hal);
        break;
    case TSASR_MEMBER:
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
