#include "nest_link.h"

#define TYPE_SHIFT 14
#define KIND_SHIFT 12
#define ID_SHIFT 8
#define VALUE_MASK 0x0FFFu
#define ID_MASK 0x3Fu
#define COUNT_MASK 0xFFu

static uint16_t beacon_frame(uint8_t kind, uint16_t value12)
{
    return (uint16_t)(((uint16_t)NL_BEACON << TYPE_SHIFT) | ((uint16_t)kind << KIND_SHIFT)
                      | (value12 & VALUE_MASK));
}

static uint16_t report_frame(uint8_t type, uint16_t robot_id, uint32_t total)
{
    return (uint16_t)(((uint16_t)type << TYPE_SHIFT) | ((robot_id & ID_MASK) << ID_SHIFT)
                      | (uint16_t)(total & COUNT_MASK));
}

uint16_t nest_link_encode_food(int32_t food_q4)
{
    if (food_q4 < NL_FOOD_Q4_MIN) {
        food_q4 = NL_FOOD_Q4_MIN;
    } else if (food_q4 > NL_FOOD_Q4_MAX) {
        food_q4 = NL_FOOD_Q4_MAX;
    }
    /* Two's complement in 12 bits: a negative value wraps to 4096 + v. */
    if (food_q4 < 0) {
        food_q4 += 4096;
    }
    return beacon_frame(NL_KIND_FOOD, (uint16_t)food_q4);
}

uint16_t nest_link_encode_waiting(uint16_t n_waiting)
{
    return beacon_frame(NL_KIND_WAITING, n_waiting > NL_VALUE_MAX ? NL_VALUE_MAX : n_waiting);
}

uint16_t nest_link_encode_mean_oae(uint32_t mean_oae_q8)
{
    return beacon_frame(NL_KIND_MEAN_OAE,
                        (uint16_t)(mean_oae_q8 > NL_VALUE_MAX ? NL_VALUE_MAX : mean_oae_q8));
}

uint16_t nest_link_encode_deposits(uint16_t robot_id, uint32_t deposits)
{
    return report_frame(NL_DEPOSITS, robot_id, deposits);
}

uint16_t nest_link_encode_oaes(uint16_t robot_id, uint32_t oaes)
{
    return report_frame(NL_OAES, robot_id, oaes);
}

uint8_t nest_link_decode(uint16_t frame, nest_link_frame_t *out)
{
    uint8_t type = (uint8_t)(frame >> TYPE_SHIFT);
    uint16_t value12 = (uint16_t)(frame & VALUE_MASK);

    out->type = NL_INVALID;
    out->kind = 0u;
    out->robot_id = 0u;
    out->value = 0;

    switch (type) {
    case NL_DEPOSITS:
    case NL_OAES:
        out->type = type;
        out->robot_id = (uint8_t)((frame >> ID_SHIFT) & ID_MASK);
        out->value = (int16_t)(frame & COUNT_MASK);
        break;
    case NL_BEACON:
        out->kind = (uint8_t)((frame >> KIND_SHIFT) & 3u);
        if (out->kind >= (uint8_t)NL_KIND_COUNT) {
            out->kind = 0u;   /* kind 3 is unused: reject the frame */
            break;
        }
        out->type = NL_BEACON;
        if (out->kind == (uint8_t)NL_KIND_FOOD && (value12 & 0x0800u) != 0u) {
            out->value = (int16_t)((int16_t)value12 - 4096);   /* sign-extend 12 bits */
        } else {
            out->value = (int16_t)value12;
        }
        break;
    default:
        break;
    }
    return out->type;
}

uint8_t nest_link_count_diff(uint8_t now, uint8_t before)
{
    return (uint8_t)(now - before);
}
