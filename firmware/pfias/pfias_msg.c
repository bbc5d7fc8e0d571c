#include "pfias/pfias_msg.h"

#define KIND_SHIFT 13
#define COLOUR_SHIFT 11
#define TAIL_BIT 0x0400u
#define PREY_BIT 0x0200u

static uint16_t frame(uint8_t kind, uint16_t id)
{
    return (uint16_t)(((uint16_t)kind << KIND_SHIFT) | (id & PFIAS_ID_MASK));
}

uint16_t pfias_msg_nest(uint16_t id) { return frame(PFIAS_MSG_NEST, id); }
uint16_t pfias_msg_food(uint16_t id) { return frame(PFIAS_MSG_FOOD, id); }
uint16_t pfias_msg_explorer(uint16_t id) { return frame(PFIAS_MSG_EXPLORER, id); }

uint16_t pfias_msg_chain(uint16_t id, uint8_t colour, uint8_t tail, uint8_t prey)
{
    uint16_t f = frame(PFIAS_MSG_CHAIN, id);
    f = (uint16_t)(f | ((uint16_t)(colour % PFIAS_COLOURS) << COLOUR_SHIFT));
    if (tail != 0u) {
        f = (uint16_t)(f | TAIL_BIT);
    }
    if (prey != 0u) {
        f = (uint16_t)(f | PREY_BIT);
    }
    return f;
}

uint8_t pfias_msg_decode(uint16_t f, pfias_msg_t *out)
{
    uint8_t kind = (uint8_t)(f >> KIND_SHIFT);
    uint16_t flags = (uint16_t)(f & 0x1E00u);   /* bits 12-9 */

    out->kind = PFIAS_MSG_INVALID;
    out->colour = 0u;
    out->tail = 0u;
    out->prey = 0u;
    out->id = 0u;

    switch (kind) {
    case PFIAS_MSG_NEST:
    case PFIAS_MSG_FOOD:
    case PFIAS_MSG_EXPLORER:
        if (flags != 0u) {
            return PFIAS_MSG_INVALID;
        }
        break;
    case PFIAS_MSG_CHAIN:
        if (((f >> COLOUR_SHIFT) & 3u) >= PFIAS_COLOURS) {
            return PFIAS_MSG_INVALID;
        }
        out->colour = (uint8_t)((f >> COLOUR_SHIFT) & 3u);
        out->tail = (uint8_t)((f & TAIL_BIT) != 0u);
        out->prey = (uint8_t)((f & PREY_BIT) != 0u);
        break;
    default:
        return PFIAS_MSG_INVALID;
    }
    out->kind = kind;
    out->id = (uint16_t)(f & PFIAS_ID_MASK);
    return kind;
}

uint8_t pfias_next_colour(uint8_t colour)
{
    return (uint8_t)((colour + 1u) % PFIAS_COLOURS);
}

uint8_t pfias_prev_colour(uint8_t colour)
{
    return (uint8_t)((colour + PFIAS_COLOURS - 1u) % PFIAS_COLOURS);
}
