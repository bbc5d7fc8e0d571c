/*
 * test_nest_link.c - the 16-bit forager <-> nest beacon frames
 * (firmware/nest_link): round trips, saturation, invalid frames, id masking.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "foraging/nest_link.h"

static nest_link_frame_t decode_as(uint16_t frame, uint8_t type)
{
    nest_link_frame_t f;
    assert_int_equal(nest_link_decode(frame, &f), type);
    assert_int_equal(f.type, type);
    return f;
}

static void test_food_round_trip(void **state)
{
    /* 1/16 token: 5 tokens = 80, -3.5 = -56, and the 12-bit extremes. */
    static const int32_t values[] = { 0, 80, 320, -56, -1, 1, 2047, -2048 };
    size_t i;
    (void)state;
    for (i = 0; i < sizeof values / sizeof values[0]; i++) {
        uint16_t frame = nest_link_encode_food(values[i]);
        nest_link_frame_t f = decode_as(frame, NL_BEACON);
        assert_int_equal(frame >> 14, 3);
        assert_int_equal(f.kind, NL_KIND_FOOD);
        assert_int_equal(f.value, values[i]);
    }
    /* -1 is all ones in 12 bits. */
    assert_int_equal(nest_link_encode_food(-1), 0xCFFF);
}

static void test_food_saturates(void **state)
{
    (void)state;
    /* +127.9375 and -128 tokens are the limits. */
    assert_int_equal(decode_as(nest_link_encode_food(2048), NL_BEACON).value, 2047);
    assert_int_equal(decode_as(nest_link_encode_food(100000), NL_BEACON).value, 2047);
    assert_int_equal(decode_as(nest_link_encode_food(-2049), NL_BEACON).value, -2048);
    assert_int_equal(decode_as(nest_link_encode_food(-100000), NL_BEACON).value, -2048);
}

static void test_waiting_round_trip(void **state)
{
    static const uint16_t values[] = { 0u, 1u, 20u, 4095u };
    size_t i;
    (void)state;
    for (i = 0; i < sizeof values / sizeof values[0]; i++) {
        nest_link_frame_t f = decode_as(nest_link_encode_waiting(values[i]), NL_BEACON);
        assert_int_equal(f.kind, NL_KIND_WAITING);
        assert_int_equal(f.value, values[i]);
    }
    assert_int_equal(decode_as(nest_link_encode_waiting(4096u), NL_BEACON).value, 4095);
    assert_int_equal(decode_as(nest_link_encode_waiting(65535u), NL_BEACON).value, 4095);
}

static void test_mean_oae_round_trip(void **state)
{
    /* M_A in 1/256: 1.85 -> 473, 15.996 -> 4095. */
    static const uint32_t values[] = { 0u, 1u, 473u, 2048u, 4095u };
    size_t i;
    (void)state;
    for (i = 0; i < sizeof values / sizeof values[0]; i++) {
        nest_link_frame_t f = decode_as(nest_link_encode_mean_oae(values[i]), NL_BEACON);
        assert_int_equal(f.kind, NL_KIND_MEAN_OAE);
        assert_int_equal(f.value, values[i]);
    }
    assert_int_equal(decode_as(nest_link_encode_mean_oae(4096u), NL_BEACON).value, 4095);
    assert_int_equal(decode_as(nest_link_encode_mean_oae(1000000u), NL_BEACON).value, 4095);
}

static void test_reports_round_trip(void **state)
{
    nest_link_frame_t f;
    (void)state;
    f = decode_as(nest_link_encode_deposits(7u, 3u), NL_DEPOSITS);
    assert_int_equal(f.robot_id, 7);
    assert_int_equal(f.value, 3);
    f = decode_as(nest_link_encode_oaes(63u, 200u), NL_OAES);
    assert_int_equal(f.robot_id, 63);
    assert_int_equal(f.value, 200);
    /* Totals are sent mod 256. */
    f = decode_as(nest_link_encode_oaes(5u, 256u + 17u), NL_OAES);
    assert_int_equal(f.value, 17);
    f = decode_as(nest_link_encode_deposits(0u, 0u), NL_DEPOSITS);
    assert_int_equal(f.robot_id, 0);
    assert_int_equal(f.value, 0);
    /* Bit layout: type 1, id 7, count 3. */
    assert_int_equal(nest_link_encode_deposits(7u, 3u), (1u << 14) | (7u << 8) | 3u);
    assert_int_equal(nest_link_encode_oaes(7u, 3u), (2u << 14) | (7u << 8) | 3u);
}

static void test_id_masking(void **state)
{
    (void)state;
    /* Ids are 6 bits: 70 -> 6, 64 -> 0, 65534 -> 62; the count is untouched. */
    assert_int_equal(decode_as(nest_link_encode_deposits(70u, 9u), NL_DEPOSITS).robot_id, 6);
    assert_int_equal(decode_as(nest_link_encode_deposits(64u, 9u), NL_DEPOSITS).robot_id, 0);
    assert_int_equal(decode_as(nest_link_encode_oaes(65534u, 9u), NL_OAES).robot_id, 62);
    assert_int_equal(decode_as(nest_link_encode_oaes(65534u, 9u), NL_OAES).value, 9);
}

static void test_invalid_frames(void **state)
{
    nest_link_frame_t f;
    (void)state;
    /* A zero frame (and any type 0) is invalid, and the output is cleared. */
    f.type = 99u;
    f.value = 99;
    assert_int_equal(nest_link_decode(0u, &f), NL_INVALID);
    assert_int_equal(f.type, NL_INVALID);
    assert_int_equal(f.value, 0);
    assert_int_equal(nest_link_decode(0x3FFFu, &f), NL_INVALID);
    /* Beacon kind 3 is unused. */
    assert_int_equal(nest_link_decode((uint16_t)(0xC000u | 0x3000u | 5u), &f), NL_INVALID);
    /* An 8-bit platform drops bits 15-8: every frame becomes type 0. */
    assert_int_equal(nest_link_decode((uint16_t)(nest_link_encode_food(80) & 0xFFu), &f), NL_INVALID);
    assert_int_equal(nest_link_decode((uint16_t)(nest_link_encode_oaes(3u, 4u) & 0xFFu), &f), NL_INVALID);
}

static void test_count_diff_heals(void **state)
{
    (void)state;
    /* Lost reports: the next total covers them. */
    assert_int_equal(nest_link_count_diff(5u, 2u), 3);
    assert_int_equal(nest_link_count_diff(5u, 5u), 0);
    /* Across the mod-256 wrap: 254 -> 3 is 5 events. */
    assert_int_equal(nest_link_count_diff(3u, 254u), 5);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_food_round_trip),
        cmocka_unit_test(test_food_saturates),
        cmocka_unit_test(test_waiting_round_trip),
        cmocka_unit_test(test_mean_oae_round_trip),
        cmocka_unit_test(test_reports_round_trip),
        cmocka_unit_test(test_id_masking),
        cmocka_unit_test(test_invalid_frames),
        cmocka_unit_test(test_count_diff_heals),
    };
    return cmocka_run_group_tests_name("nest_link", tests, NULL, NULL);
}
