/*
 * test_route_msg.c - the route message of the waypoint controller
 * (firmware/waypoint/route_msg.h): a fixed byte vector that a host's
 * encoder (Python's struct.pack('>BB6i', ...)) must produce byte for byte,
 * round trips for every route length, and the decoder's refusals, each
 * with its own error and the route left as it was.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "hal.h"
#include "waypoint/route_msg.h"

/* The fixed vector: 2 targets, (1200, -340) then (-5000, 70000), drop-off
 * (-1, 2):
 *   52 02  00 00 04 B0  FF FF FE AC  FF FF EC 78  00 01 11 70
 *          FF FF FF FF  00 00 00 02
 * (26 bytes), which is what
 *   struct.pack('>BB6i', 0x52, 2, 1200, -340, -5000, 70000, -1, 2)
 * gives in Python. */
static const uint8_t VECTOR[26] = {
    0x52, 0x02, 0x00, 0x00, 0x04, 0xB0, 0xFF, 0xFF, 0xFE, 0xAC, 0xFF, 0xFF, 0xEC, 0x78,
    0x00, 0x01, 0x11, 0x70, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x00, 0x00, 0x02
};

static route_t vector_route(void)
{
    route_t r;
    memset(&r, 0, sizeof r);
    r.n = 2u;
    r.target[0].x_mm = 1200;
    r.target[0].y_mm = -340;
    r.target[1].x_mm = -5000;
    r.target[1].y_mm = 70000;
    r.drop.x_mm = -1;
    r.drop.y_mm = 2;
    return r;
}

static void assert_same_route(const route_t *a, const route_t *b)
{
    uint8_t i;
    assert_int_equal(a->n, b->n);
    for (i = 0; i < a->n; i++) {
        assert_int_equal(a->target[i].x_mm, b->target[i].x_mm);
        assert_int_equal(a->target[i].y_mm, b->target[i].y_mm);
    }
    assert_int_equal(a->drop.x_mm, b->drop.x_mm);
    assert_int_equal(a->drop.y_mm, b->drop.y_mm);
}

/* The vector decodes to its route, and the route encodes to the vector. */
static void test_fixed_vector(void **state)
{
    route_t want = vector_route(), got;
    uint8_t buf[HAL_HOST_MSG_MAX];
    (void)state;
    memset(&got, 0, sizeof got);
    assert_int_equal(route_msg_decode(VECTOR, (uint8_t)sizeof VECTOR, &got), ROUTE_MSG_OK);
    assert_same_route(&got, &want);
    assert_int_equal(route_msg_encode(&want, buf, (uint8_t)sizeof buf), sizeof VECTOR);
    assert_memory_equal(buf, VECTOR, sizeof VECTOR);
}

/* Every route length 1..6 round-trips, with coordinates across the range
 * (both limits, 0, odd bytes); the longest is 58 bytes, within
 * HAL_HOST_MSG_MAX. */
static void test_round_trips(void **state)
{
    static const int32_t values[] = { 0, 1, -1, 255, -256, 65536, -70000, 123456,
                                      ROUTE_COORD_MAX_MM, -ROUTE_COORD_MAX_MM, 999999, -31 };
    uint8_t n, i, k = 0;
    (void)state;
    assert_int_equal(ROUTE_MSG_MAX_LEN, 58);
    assert_true(ROUTE_MSG_MAX_LEN <= HAL_HOST_MSG_MAX);
    for (n = 1; n <= ROUTE_MAX_TARGETS; n++) {
        route_t r, back;
        uint8_t buf[HAL_HOST_MSG_MAX];
        memset(&r, 0, sizeof r);
        memset(&back, 0x5A, sizeof back);
        r.n = n;
        for (i = 0; i < n; i++) {
            r.target[i].x_mm = values[k++ % 12u];
            r.target[i].y_mm = values[k++ % 12u];
        }
        r.drop.x_mm = values[k++ % 12u];
        r.drop.y_mm = values[k++ % 12u];
        assert_int_equal(route_msg_encode(&r, buf, (uint8_t)sizeof buf), 2u + 8u * (n + 1u));
        assert_int_equal(buf[0], 0x52);
        assert_int_equal(buf[1], n);
        assert_int_equal(route_msg_decode(buf, (uint8_t)(2u + 8u * (n + 1u)), &back), ROUTE_MSG_OK);
        assert_same_route(&back, &r);
    }
}

/* Each refusal has its error, and the route given is untouched. */
static void test_refusals(void **state)
{
    uint8_t buf[HAL_HOST_MSG_MAX + 8u];
    route_t r = vector_route(), before = r;
    (void)state;

    assert_int_equal(route_msg_decode(VECTOR, 0u, &r), ROUTE_MSG_ERR_LENGTH);
    assert_int_equal(route_msg_decode(VECTOR, 1u, &r), ROUTE_MSG_ERR_LENGTH);   /* 'R' alone */

    memcpy(buf, VECTOR, sizeof VECTOR);
    buf[0] = 0x72;   /* 'r' */
    assert_int_equal(route_msg_decode(buf, (uint8_t)sizeof VECTOR, &r), ROUTE_MSG_ERR_KIND);
    buf[0] = 0x00;
    assert_int_equal(route_msg_decode(buf, 1u, &r), ROUTE_MSG_ERR_KIND);

    memcpy(buf, VECTOR, sizeof VECTOR);
    buf[1] = 0u;
    assert_int_equal(route_msg_decode(buf, 10u, &r), ROUTE_MSG_ERR_COUNT);
    buf[1] = 7u;
    assert_int_equal(route_msg_decode(buf, 66u, &r), ROUTE_MSG_ERR_COUNT);
    buf[1] = 255u;
    assert_int_equal(route_msg_decode(buf, (uint8_t)sizeof VECTOR, &r), ROUTE_MSG_ERR_COUNT);

    /* One byte short, one byte long, and a 1-target length for n = 2. */
    memcpy(buf, VECTOR, sizeof VECTOR);
    buf[sizeof VECTOR] = 0u;
    assert_int_equal(route_msg_decode(buf, (uint8_t)(sizeof VECTOR - 1u), &r), ROUTE_MSG_ERR_LENGTH);
    assert_int_equal(route_msg_decode(buf, (uint8_t)(sizeof VECTOR + 1u), &r), ROUTE_MSG_ERR_LENGTH);
    assert_int_equal(route_msg_decode(buf, 18u, &r), ROUTE_MSG_ERR_LENGTH);
    assert_int_equal(route_msg_decode(buf, 2u, &r), ROUTE_MSG_ERR_LENGTH);

    /* A coordinate beyond the limit, first and last: INT32_MIN, 1 km + 1 mm. */
    memcpy(buf, VECTOR, sizeof VECTOR);
    buf[2] = 0x80; buf[3] = 0x00; buf[4] = 0x00; buf[5] = 0x00;
    assert_int_equal(route_msg_decode(buf, (uint8_t)sizeof VECTOR, &r), ROUTE_MSG_ERR_COORD);
    memcpy(buf, VECTOR, sizeof VECTOR);
    buf[22] = 0x00; buf[23] = 0x0F; buf[24] = 0x42; buf[25] = 0x41;   /* 1,000,001 */
    assert_int_equal(route_msg_decode(buf, (uint8_t)sizeof VECTOR, &r), ROUTE_MSG_ERR_COORD);

    /* The distinct codes, and nothing refused touched the route. */
    assert_true(ROUTE_MSG_ERR_LENGTH != ROUTE_MSG_ERR_KIND && ROUTE_MSG_ERR_KIND != ROUTE_MSG_ERR_COUNT
                && ROUTE_MSG_ERR_COUNT != ROUTE_MSG_ERR_LENGTH && ROUTE_MSG_ERR_COORD != ROUTE_MSG_ERR_LENGTH
                && ROUTE_MSG_ERR_COORD != ROUTE_MSG_ERR_KIND && ROUTE_MSG_ERR_COORD != ROUTE_MSG_ERR_COUNT);
    assert_same_route(&r, &before);

    buf[25] = 0x40;   /* 1,000,000: at the limit */
    assert_int_equal(route_msg_decode(buf, (uint8_t)sizeof VECTOR, &r), ROUTE_MSG_OK);
    assert_int_equal(r.drop.y_mm, ROUTE_COORD_MAX_MM);
}

/* Whatever the bytes, the decoder refuses all but well-formed messages and
 * never changes the route when it refuses (every length, random bytes). */
static void test_garbage(void **state)
{
    uint8_t buf[255];
    uint32_t x = 2463534242u;
    uint32_t trial, ok = 0;
    uint16_t i;
    (void)state;
    for (trial = 0; trial < 20000u; trial++) {
        route_t r = vector_route(), before = r;
        uint8_t len = (uint8_t)((trial >> 2) % 256u);
        int8_t s;
        for (i = 0; i < sizeof buf; i++) {
            x ^= x << 13; x ^= x >> 17; x ^= x << 5;
            buf[i] = (uint8_t)x;
        }
        if (trial & 1u) {
            buf[0] = 0x52;   /* the right kind: the other checks run */
            buf[1] = (uint8_t)((trial >> 10) % 9u);   /* each n meets every length */
        }
        if (trial & 2u) {
            for (i = 2; i + 1u < sizeof buf; i += 4u) {
                buf[i] = buf[i + 1u] = 0u;   /* small coordinates, within the limit */
            }
        }
        s = route_msg_decode(buf, len, &r);
        if (s == ROUTE_MSG_OK) {
            ok++;
            assert_int_equal(len, 2u + 8u * (r.n + 1u));
        } else {
            assert_true(s == ROUTE_MSG_ERR_LENGTH || s == ROUTE_MSG_ERR_KIND || s == ROUTE_MSG_ERR_COUNT
                        || s == ROUTE_MSG_ERR_COORD);
            assert_same_route(&r, &before);
        }
    }
    assert_true(ok > 0u);   /* well-formed ones did come up */
}

/* The encoder refuses what the decoder would: n out of range, coordinates
 * beyond the limit, no room. */
static void test_encode_refusals(void **state)
{
    route_t r = vector_route();
    uint8_t buf[HAL_HOST_MSG_MAX];
    (void)state;
    assert_int_equal(route_msg_encode(&r, buf, 25u), 0u);
    assert_int_equal(route_msg_encode(&r, buf, 26u), 26u);
    r.n = 0u;
    assert_int_equal(route_msg_encode(&r, buf, (uint8_t)sizeof buf), 0u);
    r.n = 7u;
    assert_int_equal(route_msg_encode(&r, buf, (uint8_t)sizeof buf), 0u);
    r = vector_route();
    r.target[1].y_mm = ROUTE_COORD_MAX_MM + 1;
    assert_int_equal(route_msg_encode(&r, buf, (uint8_t)sizeof buf), 0u);
    r = vector_route();
    r.drop.x_mm = -ROUTE_COORD_MAX_MM - 1;
    assert_int_equal(route_msg_encode(&r, buf, (uint8_t)sizeof buf), 0u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fixed_vector),
        cmocka_unit_test(test_round_trips),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_garbage),
        cmocka_unit_test(test_encode_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
