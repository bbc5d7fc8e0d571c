/*
 * pfias_msg.c - PFIAS's turret frames, and TSASR's (pfias_msg.h,
 * firmware/tsasr/tsasr_msg.h).
 */
#include "pfias/pfias_msg.h"

#define KIND_SHIFT 13
#define COLOUR_SHIFT 11
#define TAIL_BIT 0x0400u
#define PREY_BIT 0x0200u
#define RETREAT_BIT 0x0100u     /* PFIAS_FMT_RETREAT only */
#define FRAME_BITS 0x1FFFu      /* below the kind: flags and id */

static uint16_t id_mask(uint8_t fmt)
{
    return fmt == PFIAS_FMT_RETREAT ? (uint16_t)0x00FFu : (uint16_t)PFIAS_ID_MASK;
}

uint16_t pfias_fmt_id(uint8_t fmt, uint16_t id)
{
    return (uint16_t)(id & id_mask(fmt));
}

uint16_t pfias_fmt_frame(uint8_t fmt, uint8_t kind, uint16_t id)
{
    return (uint16_t)(((uint16_t)kind << KIND_SHIFT) | pfias_fmt_id(fmt, id));
}

uint16_t pfias_fmt_chain(uint8_t fmt, uint16_t id, uint8_t colour, uint8_t tail, uint8_t prey,
                         uint8_t retreat)
{
    uint16_t f = pfias_fmt_frame(fmt, PFIAS_MSG_CHAIN, id);
    f = (uint16_t)(f | ((uint16_t)(colour % PFIAS_COLOURS) << COLOUR_SHIFT));
    if (tail != 0u) {
        f = (uint16_t)(f | TAIL_BIT);
    }
    if (prey != 0u) {
        f = (uint16_t)(f | PREY_BIT);
    }
    if (fmt == PFIAS_FMT_RETREAT && retreat != 0u) {
        f = (uint16_t)(f | RETREAT_BIT);
    }
    return f;
}

uint8_t pfias_fmt_decode(uint8_t fmt, uint16_t f, pfias_msg_t *out)
{
    uint8_t kind = (uint8_t)(f >> KIND_SHIFT);
    uint16_t mask = id_mask(fmt);
    /* The flag bits: 12-9 (PFIAS), 12-8 (PFIAS_FMT_RETREAT). */
    uint16_t flags = (uint16_t)(f & (FRAME_BITS & (uint16_t)~mask));

    out->kind = PFIAS_MSG_INVALID;
    out->colour = 0u;
    out->tail = 0u;
    out->prey = 0u;
    out->retreat = 0u;
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
        if (fmt == PFIAS_FMT_RETREAT) {
            out->retreat = (uint8_t)((f & RETREAT_BIT) != 0u);
        }
        break;
    default:
        return PFIAS_MSG_INVALID;
    }
    out->kind = kind;
    out->id = (uint16_t)(f & mask);
    return kind;
}

uint16_t pfias_msg_nest(uint16_t id) { return pfias_fmt_frame(PFIAS_FMT_PFIAS, PFIAS_MSG_NEST, id); }
uint16_t pfias_msg_food(uint16_t id) { return pfias_fmt_frame(PFIAS_FMT_PFIAS, PFIAS_MSG_FOOD, id); }
uint16_t pfias_msg_explorer(uint16_t id) { return pfias_fmt_frame(PFIAS_FMT_PFIAS, PFIAS_MSG_EXPLORER, id); }

uint16_t pfias_msg_chain(uint16_t id, uint8_t colour, uint8_t tail, uint8_t prey)
{
    return pfias_fmt_chain(PFIAS_FMT_PFIAS, id, colour, tail, prey, 0u);
}

uint8_t pfias_msg_decode(uint16_t f, pfias_msg_t *out)
{
    return pfias_fmt_decode(PFIAS_FMT_PFIAS, f, out);
}

uint8_t pfias_next_colour(uint8_t colour)
{
    return (uint8_t)((colour + 1u) % PFIAS_COLOURS);
}

uint8_t pfias_prev_colour(uint8_t colour)
{
    return (uint8_t)((colour + PFIAS_COLOURS - 1u) % PFIAS_COLOURS);
}
