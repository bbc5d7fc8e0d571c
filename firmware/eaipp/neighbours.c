#include "neighbours.h"

void neighbours_clear(neighbours_t *t)
{
    t->count = 0u;
}

/* States of the robots that hold a gradient (nodes and the sources). */
static uint8_t holder_state(uint8_t state)
{
    return (uint8_t)(state == EAIPP_ST_NODE || state == EAIPP_ST_NEST || state == EAIPP_ST_FOOD);
}

/* An entry that is, or may be, a node or a source: its STATE says so, or it
 * has sent GRADIENT or ROOT frames (only those send them) and no STATE yet. */
static uint8_t entry_holder(const neighbour_t *nb)
{
    if ((nb->heard & NB_HEARD_STATE) != 0u) {
        return holder_state(nb->state);
    }
    return (uint8_t)((nb->heard & (NB_HEARD_GRADIENT | NB_HEARD_ROOT)) != 0u);
}

neighbour_t *neighbours_hear(neighbours_t *t, const eaipp_msg_t *m, uint16_t range_mm,
                             int16_t bearing_mrad)
{
    neighbour_t *nb = 0;
    uint8_t i;
    for (i = 0; i < t->count; i++) {
        if (t->n[i].id == m->id) {
            nb = &t->n[i];
            break;
        }
    }
    if (nb == 0) {
        if (t->count < NEIGHBOURS_MAX) {
            nb = &t->n[t->count++];
        } else {
            /* Full (a crowd: the maze's 70 robots).  Nodes and sources come
             * first, since Algorithm 4 must count every node heard: a frame
             * of a node or source takes the place of the moving robot heard
             * longest ago, even one heard this period; failing that, as any
             * frame, of the entry heard longest ago, unless all were heard
             * this period.  (Oldest-first alone let moving robots push nodes
             * out of the table, and explorers that kept one node entry
             * became nodes beside other nodes.) */
            uint8_t oldest = NEIGHBOURS_MAX, mover = NEIGHBOURS_MAX;
            uint8_t incoming_holder = (uint8_t)(m->kind == EAIPP_MSG_GRADIENT || m->kind == EAIPP_MSG_ROOT
                                                || (m->kind == EAIPP_MSG_STATE && holder_state(m->state)));
            for (i = 0; i < t->count; i++) {
                if (oldest == NEIGHBOURS_MAX || t->n[i].age > t->n[oldest].age) {
                    oldest = i;
                }
                if (!entry_holder(&t->n[i]) && (mover == NEIGHBOURS_MAX || t->n[i].age > t->n[mover].age)) {
                    mover = i;
                }
            }
            if (incoming_holder && mover < NEIGHBOURS_MAX) {
                nb = &t->n[mover];
            } else if (mover < NEIGHBOURS_MAX && t->n[mover].age > 0u) {
                nb = &t->n[mover];
            } else if (incoming_holder && t->n[oldest].age > 0u) {
                nb = &t->n[oldest];
            } else {
                return 0;
            }
        }
        nb->id = m->id;
        nb->heard = 0u;
        nb->state = 0u;
        nb->flags = 0u;
        nb->gradient = (uint8_t)EAIPP_GRADIENT_MAX;
        nb->root = 0u;
        nb->exit_units = (uint8_t)EAIPP_MSG_EXIT_UNKNOWN;
    }
    nb->age = 0u;
    nb->range_mm = range_mm;
    nb->bearing_mrad = bearing_mrad;
    switch (m->kind) {
    case EAIPP_MSG_STATE:
        nb->heard = (uint8_t)(nb->heard | NB_HEARD_STATE);
        nb->state = m->state;
        nb->flags = (uint8_t)((nb->flags & NB_FLAG_GRADIENT_SOURCE)
                              | (m->source != 0u ? NB_FLAG_STATE_SOURCE : 0u)
                              | (m->contraction != 0u ? NB_FLAG_CONTRACTION : 0u));
        break;
    case EAIPP_MSG_GRADIENT:
        nb->heard = (uint8_t)(nb->heard | NB_HEARD_GRADIENT);
        nb->gradient = m->gradient;
        nb->flags = (uint8_t)((nb->flags & (uint8_t)~NB_FLAG_GRADIENT_SOURCE)
                              | (m->source != 0u ? NB_FLAG_GRADIENT_SOURCE : 0u));
        break;
    case EAIPP_MSG_ROOT:
        nb->heard = (uint8_t)(nb->heard | NB_HEARD_ROOT);
        nb->root = m->root;
        break;
    default:
        nb->heard = (uint8_t)(nb->heard | NB_HEARD_EXIT);
        nb->exit_units = m->exit_units;
        break;
    }
    return nb;
}

void neighbours_age(neighbours_t *t, uint8_t timeout)
{
    uint8_t i = 0u;
    while (i < t->count) {
        if (t->n[i].age < 255u) {
            t->n[i].age++;
        }
        if (t->n[i].age >= timeout) {
            t->n[i] = t->n[t->count - 1u];   /* order does not matter */
            t->count--;
        } else {
            i++;
        }
    }
}

const neighbour_t *neighbours_find(const neighbours_t *t, uint8_t id)
{
    uint8_t i;
    for (i = 0; i < t->count; i++) {
        if (t->n[i].id == id) {
            return &t->n[i];
        }
    }
    return 0;
}

uint8_t neighbour_is(const neighbour_t *nb, uint8_t state)
{
    return (uint8_t)((nb->heard & NB_HEARD_STATE) != 0u && nb->state == state);
}

uint8_t neighbour_gradient_source(const neighbour_t *nb)
{
    return (uint8_t)((nb->flags & NB_FLAG_GRADIENT_SOURCE) != 0u);
}

uint8_t neighbour_contraction(const neighbour_t *nb)
{
    return (uint8_t)((nb->flags & NB_FLAG_CONTRACTION) != 0u);
}
