/* pil_frame.c - pil_frame.h. */
#include "pil_frame.h"

#include "telemetry/telemetry_frame.h"

void pil_put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)(v >> 8);
}

void pil_put_u32(uint8_t *p, uint32_t v)
{
    pil_put_u16(p, (uint16_t)(v & 0xFFFFu));
    pil_put_u16(p + 2, (uint16_t)(v >> 16));
}

uint16_t pil_get_u16(const uint8_t *p)
{
    return (uint16_t)((uint16_t)p[0] | (uint16_t)((uint16_t)p[1] << 8));
}

uint32_t pil_get_u32(const uint8_t *p)
{
    return (uint32_t)pil_get_u16(p) | ((uint32_t)pil_get_u16(p + 2) << 16);
}

uint16_t pil_frame_seal(uint8_t *buf, uint16_t cap, uint8_t type, uint8_t seq, uint16_t len)
{
    uint16_t crc;
    if (len > PIL_MAX_PAYLOAD || cap < PIL_FRAME_BYTES(len)) {
        return 0u;
    }
    buf[0] = PIL_MAGIC;
    buf[1] = PIL_VERSION;
    buf[2] = type;
    buf[3] = seq;
    pil_put_u16(buf + 4, len);
    crc = telemetry_crc16(0xFFFFu, buf, (uint16_t)(PIL_HEADER_BYTES + len));
    pil_put_u16(buf + PIL_HEADER_BYTES + len, crc);
    return PIL_FRAME_BYTES(len);
}

uint16_t pil_frame_size(const uint8_t *header)
{
    uint16_t len = pil_get_u16(header + 4);
    if (header[0] != PIL_MAGIC || header[1] != PIL_VERSION || len > PIL_MAX_PAYLOAD) {
        return 0u;
    }
    return PIL_FRAME_BYTES(len);
}

pil_frame_error_t pil_frame_check(const uint8_t *buf, uint16_t n, pil_frame_t *out)
{
    uint16_t len;
    if (n < PIL_FRAME_BYTES(0u)) {
        return PIL_FRAME_SHORT;
    }
    if (buf[0] != PIL_MAGIC) {
        return PIL_FRAME_MAGIC;
    }
    if (buf[1] != PIL_VERSION) {
        return PIL_FRAME_VERSION;
    }
    len = pil_get_u16(buf + 4);
    if (len > PIL_MAX_PAYLOAD) {
        return PIL_FRAME_LENGTH;
    }
    if (n < PIL_FRAME_BYTES(len)) {
        return PIL_FRAME_SHORT;
    }
    if (telemetry_crc16(0xFFFFu, buf, (uint16_t)(PIL_HEADER_BYTES + len)) != pil_get_u16(buf + PIL_HEADER_BYTES + len)) {
        return PIL_FRAME_CRC;
    }
    out->type = buf[2];
    out->seq = buf[3];
    out->len = len;
    out->payload = buf + PIL_HEADER_BYTES;
    return PIL_FRAME_OK;
}

const char *pil_frame_error_name(pil_frame_error_t e)
{
    switch (e) {
    case PIL_FRAME_OK: return "a good frame";
    case PIL_FRAME_SHORT: return "a truncated frame";
    case PIL_FRAME_MAGIC: return "not a frame (bad magic byte)";
    case PIL_FRAME_VERSION: return "a frame of another protocol version";
    case PIL_FRAME_LENGTH: return "a frame longer than the protocol allows";
    case PIL_FRAME_CRC: return "a frame with a bad CRC";
    }
    return "an unknown frame error";
}
