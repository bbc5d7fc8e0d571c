#include "eaipp_msg.h"

#define ID_SHIFT 9
#define ID_MASK 0x7Fu
#define KIND_SHIFT 7
#define PAYLOAD_MASK 0x7Fu

static uint16_t frame(uint16_t id, uint8_t kind, uint16_t payload7)
{
    return (uint16_t)(((id & ID_MASK) << ID_SHIFT) | ((uint16_t)(kind & 3u) << KIND_SHIFT)
                      | (payload7 & PAYLOAD_MASK));
}

uint16_t eaipp_msg_state(uint16_t id, uint8_t state, uint8_t source, uint8_t contraction)
{
    uint16_t p = (uint16_t)(((uint16_t)(state & 7u) << 4) | ((uint16_t)(source != 0u) << 3)
                            | ((uint16_t)(contraction != 0u) << 2));
    return frame(id, EAIPP_MSG_STATE, p);
}

uint16_t eaipp_msg_gradient(uint16_t id, uint8_t source, uint8_t gradient)
{
    uint8_t g = gradient > EAIPP_GRADIENT_LAST ? (uint8_t)EAIPP_GRADIENT_MAX : gradient;
    return frame(id, EAIPP_MSG_GRADIENT, (uint16_t)(((uint16_t)(source != 0u) << 6) | g));
}

uint16_t eaipp_msg_root(uint16_t id, uint16_t root_id)
{
    return frame(id, EAIPP_MSG_ROOT, root_id);
}

uint16_t eaipp_msg_exit(uint16_t id, uint16_t distance_mm, uint8_t known)
{
    uint16_t u = (uint16_t)EAIPP_MSG_EXIT_UNKNOWN;
    if (known != 0u) {
        /* Rounded to the nearest unit without overflow in 16 bits. */
        u = (uint16_t)(distance_mm / EAIPP_MSG_EXIT_MM);
        if (distance_mm % EAIPP_MSG_EXIT_MM >= EAIPP_MSG_EXIT_MM / 2u) {
            u++;
        }
        if (u > EAIPP_MSG_EXIT_UNKNOWN - 1u) {
            u = EAIPP_MSG_EXIT_UNKNOWN - 1u;
        }
    }
    return frame(id, EAIPP_MSG_EXIT, u);
}

uint8_t eaipp_msg_decode(uint16_t f, eaipp_msg_t *out)
{
    uint8_t p = (uint8_t)(f & PAYLOAD_MASK);
    out->valid = 1u;
    out->id = (uint8_t)((f >> ID_SHIFT) & ID_MASK);
    out->kind = (uint8_t)((f >> KIND_SHIFT) & 3u);
    out->state = 0u;
    out->source = 0u;
    out->contraction = 0u;
    out->gradient = 0u;
    out->root = 0u;
    out->exit_units = 0u;
    switch (out->kind) {
    case EAIPP_MSG_STATE:
        out->state = (uint8_t)(p >> 4);
        out->source = (uint8_t)((p >> 3) & 1u);
        out->contraction = (uint8_t)((p >> 2) & 1u);
        if (out->state >= (uint8_t)EAIPP_ST_COUNT || (p & 3u) != 0u) {
            out->valid = 0u;   /* states 6, 7 and the spare bits are not ours */
        }
        break;
    case EAIPP_MSG_GRADIENT:
        out->source = (uint8_t)(p >> 6);
        out->gradient = (uint8_t)(p & 0x3Fu);
        break;
    case EAIPP_MSG_ROOT:
        out->root = p;
        break;
    default:
        out->exit_units = p;
        break;
    }
    return out->valid;
}
