/*
 * telemetry_host.c - POSE payloads (telemetry_host.h).  Bytes are shifted
 * through uint32_t so that 16-bit int never holds a 32-bit field.
 */
#include "telemetry/telemetry_host.h"

#include "units.h"

static void put_u32(uint8_t *out, uint32_t v)
{
    out[0] = (uint8_t)(v >> 24);
    out[1] = (uint8_t)((v >> 16) & 0xFFu);
    out[2] = (uint8_t)((v >> 8) & 0xFFu);
    out[3] = (uint8_t)(v & 0xFFu);
}

static uint32_t get_u32(const uint8_t *in)
{
    return ((uint32_t)in[0] << 24) | ((uint32_t)in[1] << 16) | ((uint32_t)in[2] << 8) | (uint32_t)in[3];
}

/* Two's complement back to signed without relying on an implementation-
 * defined conversion of a value above INT32_MAX. */
static int32_t to_i32(uint32_t u)
{
    return u <= 0x7FFFFFFFu ? (int32_t)u : (int32_t)(u - 0x80000000u) - INT32_C(0x7FFFFFFF) - 1;
}

void telemetry_pose_pack(const hal_pose_t *pose, uint8_t out[TELEMETRY_POSE_PAYLOAD])
{
    uint16_t h = (uint16_t)pose->heading_mrad;
    put_u32(out, (uint32_t)pose->x_mm);
    put_u32(out + 4, (uint32_t)pose->y_mm);
    out[8] = (uint8_t)(h >> 8);
    out[9] = (uint8_t)(h & 0xFFu);
}

uint8_t telemetry_pose_unpack(const uint8_t *payload, uint16_t len, hal_pose_t *pose)
{
    uint16_t hu;
    int32_t h;
    if (len != TELEMETRY_POSE_PAYLOAD) {
        return 0u;
    }
    hu = (uint16_t)(((uint16_t)payload[8] << 8) | payload[9]);
    h = hu <= 0x7FFFu ? (int32_t)hu : (int32_t)hu - INT32_C(0x10000);
    while (h > UNITS_PI_MRAD) {
        h -= UNITS_TWO_PI_MRAD;
    }
    while (h <= -UNITS_PI_MRAD) {
        h += UNITS_TWO_PI_MRAD;
    }
    pose->x_mm = to_i32(get_u32(payload));
    pose->y_mm = to_i32(get_u32(payload + 4));
    pose->heading_mrad = (int16_t)h;
    pose->age_ms = 0u;
    return 1u;
}
