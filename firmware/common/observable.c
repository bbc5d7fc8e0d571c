/* Reads observables (observable.h): portable, no allocation. */
#include "common/observable.h"

#include <string.h>

uint8_t observable_count(const observable_t *table)
{
    uint8_t n = 0u;
    while (table != 0 && table[n].name != 0) {
        n++;
    }
    return n;
}

float observable_read(const observable_t *obs, const void *self)
{
    const uint8_t *p = (const uint8_t *)self + obs->offset;
    float v;
    /* memcpy: the field may sit at any alignment the struct gives it. */
    switch (obs->type) {
    case OBS_U8: { uint8_t x; memcpy(&x, p, sizeof x); v = (float)x; break; }
    case OBS_I8: { int8_t x; memcpy(&x, p, sizeof x); v = (float)x; break; }
    case OBS_U16: { uint16_t x; memcpy(&x, p, sizeof x); v = (float)x; break; }
    case OBS_I16: { int16_t x; memcpy(&x, p, sizeof x); v = (float)x; break; }
    case OBS_U32: { uint32_t x; memcpy(&x, p, sizeof x); v = (float)x; break; }
    case OBS_I32: { int32_t x; memcpy(&x, p, sizeof x); v = (float)x; break; }
    default: memcpy(&v, p, sizeof v); break;
    }
    return v * obs->scale;
}
