#include "chemotaxis.h"

#include <stddef.h>

void chemo_filter_init(chemo_filter_t *f, uint16_t y)
{
    f->sum_new = 0u;
    f->sum_old = 0u;
    f->y = (y == 0u) ? 1u : (y > CHEMO_Y_MAX ? (uint16_t)CHEMO_Y_MAX : y);
    f->count = 0u;
    f->head = 0u;
}

/* The ring holds 2y readings in time order, `head` at the oldest once it
 * is full.  With x_t the new reading, x_(t-y) moves from the new window to
 * the old one (it sits y places from head: -y = +y modulo 2y) and
 * x_(t-2y), at head, leaves the old window. */
void chemo_filter_push(chemo_filter_t *f, uint32_t *ring, uint32_t reading)
{
    uint16_t len = (uint16_t)(2u * f->y);
    uint32_t mid = 0u;
    uint32_t out = 0u;
    if (ring == NULL) {
        return;
    }
    if (f->head >= len) {
        f->head = 0u;   /* a y changed under the filter: never index outside */
    }
    if (f->count >= f->y) {
        mid = ring[(uint16_t)((f->head + f->y) % len)];
    }
    if (f->count >= len) {
        out = ring[f->head];
    }
    /* Each sum holds the reading it loses: no unsigned wrap. */
    f->sum_new = f->sum_new - mid + reading;
    f->sum_old = f->sum_old - out + mid;
    ring[f->head] = reading;
    f->head = (uint16_t)((f->head + 1u) % len);
    if (f->count < len) {
        f->count++;
    }
}

int8_t chemo_filter_sign(const chemo_filter_t *f)
{
    if (f->count < (uint16_t)(2u * f->y)) {
        return 0;
    }
    if (f->sum_new > f->sum_old) {
        return 1;
    }
    return (f->sum_new < f->sum_old) ? (int8_t)-1 : (int8_t)0;
}

uint32_t chemo_filter_level(const chemo_filter_t *f)
{
    uint16_t n = (f->count < f->y) ? f->count : f->y;
    if (n == 0u) {
        return 0u;
    }
    return (uint32_t)(f->sum_new / n);   /* a mean of uint32 readings fits */
}

static uint32_t gain(uint16_t g)
{
    if (g == 0u) {
        return 1u;
    }
    return (g > CHEMO_GAIN_MAX) ? CHEMO_GAIN_MAX : g;
}

uint32_t chemo_tumble_q32(uint32_t p_b_q32, const chemo_gains_t *g, int8_t d_repulsion, int8_t d_attraction)
{
    /* Multipliers over divisors: P_b (< 2^32) x 1000 x 1000 < 2^52. */
    uint64_t num = p_b_q32;
    uint32_t den = 1u;
    uint64_t p;
    if (d_repulsion > 0) {
        num *= gain(g->r_m);
    } else if (d_repulsion < 0) {
        den *= gain(g->r_d);
    }
    if (d_attraction > 0) {
        den *= gain(g->a_d);
    } else if (d_attraction < 0) {
        num *= gain(g->a_m);
    }
    p = num / den;
    return (p > UINT32_MAX) ? UINT32_MAX : (uint32_t)p;
}

uint32_t chemo_probability_q32(float p)
{
    float s;
    if (!(p > 0.0f)) {
        return 0u;   /* also NaN */
    }
    s = p * 4294967296.0f;
    /* The largest float below 2^32 is 2^32 - 256. */
    if (s >= 4294967040.0f) {
        return UINT32_MAX;
    }
    return (uint32_t)s;
}
