/*
 * tsasr_msg.c - TSASR's turret frames (tsasr_msg.h): PFIAS's codec in its
 * format PFIAS_FMT_RETREAT.
 */
#include "tsasr/tsasr_msg.h"

uint16_t tsasr_msg_nest(uint16_t id) { return pfias_fmt_frame(PFIAS_FMT_RETREAT, PFIAS_MSG_NEST, id); }
uint16_t tsasr_msg_food(uint16_t id) { return pfias_fmt_frame(PFIAS_FMT_RETREAT, PFIAS_MSG_FOOD, id); }
uint16_t tsasr_msg_explorer(uint16_t id) { return pfias_fmt_frame(PFIAS_FMT_RETREAT, PFIAS_MSG_EXPLORER, id); }

uint16_t tsasr_msg_chain(uint16_t id, uint8_t colour, uint8_t tail, uint8_t prey, uint8_t retreat)
{
    return pfias_fmt_chain(PFIAS_FMT_RETREAT, id, colour, tail, prey, retreat);
}

uint8_t tsasr_msg_decode(uint16_t f, tsasr_msg_t *out)
{
    return pfias_fmt_decode(PFIAS_FMT_RETREAT, f, out);
}
