/*
 * tsasr_msg.c - TSASR's turret frames (tsasr_msg.h).
 */
#include "tsasr/tsasr_msg.h"

#define KIND_SHIFT 13
#define COLOUR_SHIFT 11
#define TAIL_BIT 0x0400u
#define PREY_BIT 0x0200u
#define RETREAT_BIT 0x0100u
#define FLAG_BITS 0x1F00u   /* bits 12-8: chain frames only */

static uint16_t frame(uint8_t kind, uint16_t id)
{
    return (uint16_t)(((uint16_t)kind << KIND_SHIFT) | (id & TSASR_ID_MASK));
}

uint16_t tsasr_msg_nest(uint16_t id) { return frame(TSASR_MSG_NEST, id); }
uint16_t tsasr_msg_food(uint16_t id) { return frame(TSASR_MSG_FOOD, id); }
uint16_t tsasr_msg_explorer(uint16_t id) { return frame(TSASR_MSG_EXPLORER, id); }

uint16_t tsasr_msg_chain(uint16_t id, uint8_t colour, uint8_t tail, uint8_t prey, uint8_t retreat)
{
    uint16_t f = frame(TSASR_MSG_CHAIN, id);
    f = (uint16_t)(f | ((uint16_t)(colour % TSASR_COLOURS) << COLOUR_SHIFT));
    if (tail != 0u) {
        f = (uint16_t)(f | TAIL_BIT);
    }
    if (prey != 0u) {
        f = (uint16_t)(f | PREY_BIT);
    }
    if (retreat != 0u) {
        f = (uint16_t)(f | RETREAT_BIT);
    }
    return f;
}

uint8_t tsasr_msg_decode(uint16_t f, tsasr_msg_t *out)
{
    uint8_t kind = (uint8_t)(f >> KIND_SHIFT);

    out->kind = TSASR_MSG_INVALID;
    out->colour = 0u;
    out->tail = 0u;
    out->prey = 0u;
    out->retreat = 0u;
    out->id = 0u;

    switch (kind) {
    case TSASR_MSG_NEST:
    case TSASR_MSG_FOOD:
    case TSASR_MSG_EXPLORER:
        if ((f & FLAG_BITS) != 0u) {
            return TSASR_MSG_INVALID;
        }
        break;
    case TSASR_MSG_CHAIN:
        if (((f >> COLOUR_SHIFT) & 3u) >= TSASR_COLOURS) {
            return TSASR_MSG_INVALID;
        }
        out->colour = (uint8_t)((f >> COLOUR_SHIFT) & 3u);
        out->tail = (uint8_t)((f & TAIL_BIT) != 0u);
        out->prey = (uint8_t)((f & PREY_BIT) != 0u);
        out->retreat = (uint8_t)((f & RETREAT_BIT) != 0u);
        break;
    default:
        return TSASR_MSG_INVALID;
    }
    out->kind = kind;
    out->id = (uint16_t)(f & TSASR_ID_MASK);
    return kind;
}

uint8_t tsasr_next_colour(uint8_t colour)
{
    return (uint8_t)((colour + 1u) % TSASR_COLOURS);
}

uint8_t tsasr_prev_colour(uint8_t colour)
{
    return (uint8_t)((colour + TSASR_COLOURS - 1u) % TSASR_COLOURS);
}
