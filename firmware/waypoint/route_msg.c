#include "route_msg.h"

/* Big-endian int32 from 4 bytes: assembled in uint32_t so that no shift
 * reaches a 16-bit int's sign bit, then to the signed value without an
 * implementation-defined conversion. */
static int32_t get_i32(const uint8_t *p)
{
    uint32_t u = ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) | (uint32_t)p[3];
    if (u >= 0x80000000UL) {
        return -(int32_t)(0xFFFFFFFFUL - u) - 1;
    }
    return (int32_t)u;
}

static void put_i32(uint8_t *p, int32_t v)
{
    uint32_t u = (uint32_t)v;   /* modulo 2^32: two's complement bytes */
    p[0] = (uint8_t)(u >> 24);
    p[1] = (uint8_t)(u >> 16);
    p[2] = (uint8_t)(u >> 8);
    p[3] = (uint8_t)u;
}

static uint8_t coord_ok(int32_t v)
{
    return (uint8_t)(v <= ROUTE_COORD_MAX_MM && v >= -ROUTE_COORD_MAX_MM);
}

int8_t route_msg_decode(const uint8_t *buf, uint8_t len, route_t *out)
{
    uint8_t n, i;
    if (len < 1u) {
        return ROUTE_MSG_ERR_LENGTH;
    }
    if (buf[0] != ROUTE_MSG_KIND) {
        return ROUTE_MSG_ERR_KIND;
    }
    if (len < 2u) {
        return ROUTE_MSG_ERR_LENGTH;
    }
    n = buf[1];
    if (n < 1u || n > ROUTE_MAX_TARGETS) {
        return ROUTE_MSG_ERR_COUNT;
    }
    if (len != ROUTE_MSG_LEN(n)) {
        return ROUTE_MSG_ERR_LENGTH;
    }
    /* Every coordinate first: a refused message leaves *out as it was. */
    for (i = 2u; i < len; i = (uint8_t)(i + 4u)) {
        if (coord_ok(get_i32(buf + i)) == 0u) {
            return ROUTE_MSG_ERR_COORD;
        }
    }
    out->n = n;
    for (i = 0u; i < n; i++) {
        out->target[i].x_mm = get_i32(buf + 2u + 8u * i);
        out->target[i].y_mm = get_i32(buf + 6u + 8u * i);
    }
    out->drop.x_mm = get_i32(buf + 2u + 8u * n);
    out->drop.y_mm = get_i32(buf + 6u + 8u * n);
    return ROUTE_MSG_OK;
}

uint8_t route_msg_encode(const route_t *route, uint8_t *buf, uint8_t cap)
{
    uint8_t n = route->n, i, len;
    if (n < 1u || n > ROUTE_MAX_TARGETS) {
        return 0u;
    }
    len = (uint8_t)ROUTE_MSG_LEN(n);
    if (cap < len) {
        return 0u;
    }
    for (i = 0u; i < n; i++) {
        if (coord_ok(route->target[i].x_mm) == 0u || coord_ok(route->target[i].y_mm) == 0u) {
            return 0u;
        }
    }
    if (coord_ok(route->drop.x_mm) == 0u || coord_ok(route->drop.y_mm) == 0u) {
        return 0u;
    }
    buf[0] = (uint8_t)ROUTE_MSG_KIND;
    buf[1] = n;
    for (i = 0u; i < n; i++) {
        put_i32(buf + 2u + 8u * i, route->target[i].x_mm);
        put_i32(buf + 6u + 8u * i, route->target[i].y_mm);
    }
    put_i32(buf + 2u + 8u * n, route->drop.x_mm);
    put_i32(buf + 6u + 8u * n, route->drop.y_mm);
    return len;
}
