/*
 * nest_link.c - fuzz target: the nest-link IR messages
 * (firmware/foraging/nest_link.c), the one robot-to-robot message format in
 * firmware/.  A frame is 16 bits, so every one of the 65,536 frames is
 * decoded once per process (LLVMFuzzerInitialize); the fuzzer then drives
 * the encoders with arbitrary values.  Expectations come from the format
 * as nest_link.h documents it, not from the decoder.
 *
 * Input: frame (2 bytes), a value (4), a robot id (2), a second total (1).
 */
#include "fuzz.h"

#include "foraging/nest_link.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);

static void check_frame(uint16_t frame)
{
    nest_link_frame_t f;
    uint8_t type = (uint8_t)(frame >> 14);
    uint8_t kind = (uint8_t)((frame >> 12) & 3u);
    uint8_t got = nest_link_decode(frame, &f);

    FUZZ_CHECK(got == f.type);
    if (type == NL_INVALID || (type == NL_BEACON && kind == 3u)) {
        FUZZ_CHECK(got == NL_INVALID && f.kind == 0u && f.robot_id == 0u && f.value == 0);
        return;
    }
    FUZZ_CHECK(got == type);
    if (type == NL_DEPOSITS || type == NL_OAES) {
        FUZZ_CHECK(f.kind == 0u);
        FUZZ_CHECK(f.robot_id == ((frame >> 8) & 63u) && f.robot_id < NL_ID_COUNT);
        FUZZ_CHECK(f.value == (frame & 0xFF));
        /* Every bit of a report means something: it re-encodes exactly. */
        FUZZ_CHECK((type == NL_DEPOSITS ? nest_link_encode_deposits(f.robot_id, (uint32_t)f.value)
                                        : nest_link_encode_oaes(f.robot_id, (uint32_t)f.value)) == frame);
        return;
    }
    FUZZ_CHECK(f.kind == kind && f.robot_id == 0u);
    switch (kind) {
    case NL_KIND_FOOD: {
        int32_t v12 = frame & 0x0FFF;
        FUZZ_CHECK(f.value == (v12 >= 2048 ? v12 - 4096 : v12));
        FUZZ_CHECK(nest_link_encode_food(f.value) == frame);
        break;
    }
    case NL_KIND_WAITING:
        FUZZ_CHECK(f.value == (frame & 0x0FFF));
        FUZZ_CHECK(nest_link_encode_waiting((uint16_t)f.value) == frame);
        break;
    default:
        FUZZ_CHECK(f.value == (frame & 0x0FFF));
        FUZZ_CHECK(nest_link_encode_mean_oae((uint32_t)f.value) == frame);
        break;
    }
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    uint32_t frame;
    (void)argc;
    (void)argv;
    for (frame = 0; frame <= 0xFFFFu; frame++) {
        check_frame((uint16_t)frame);
    }
    return 0;
}

/* Decodes `frame`, which must be valid, of the expected type and kind. */
static int16_t decoded(uint16_t frame, uint8_t type, uint8_t kind, uint8_t robot_id)
{
    nest_link_frame_t f;
    FUZZ_CHECK(nest_link_decode(frame, &f) == type);
    FUZZ_CHECK(f.kind == (type == NL_BEACON ? kind : 0u) && f.robot_id == robot_id);
    return f.value;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_in_t in = fuzz_in(data, size);
    uint16_t frame = fuzz_u16(&in);
    uint32_t v = fuzz_u32(&in);
    uint16_t id = fuzz_u16(&in);
    uint8_t before = fuzz_u8(&in);
    int32_t sv = (int32_t)v;

    check_frame(frame);

    /* Beacon values saturate to their 12-bit ranges. */
    FUZZ_CHECK(decoded(nest_link_encode_food(sv), NL_BEACON, NL_KIND_FOOD, 0)
               == (sv < NL_FOOD_Q4_MIN ? NL_FOOD_Q4_MIN : sv > NL_FOOD_Q4_MAX ? NL_FOOD_Q4_MAX : sv));
    FUZZ_CHECK(decoded(nest_link_encode_waiting((uint16_t)v), NL_BEACON, NL_KIND_WAITING, 0)
               == ((uint16_t)v > NL_VALUE_MAX ? (int32_t)NL_VALUE_MAX : (int32_t)(uint16_t)v));
    FUZZ_CHECK(decoded(nest_link_encode_mean_oae(v), NL_BEACON, NL_KIND_MEAN_OAE, 0)
               == (v > NL_VALUE_MAX ? (int32_t)NL_VALUE_MAX : (int32_t)v));
    /* Reports carry the id mod 64 and the total mod 256. */
    FUZZ_CHECK(decoded(nest_link_encode_deposits(id, v), NL_DEPOSITS, 0, (uint8_t)(id & 63u))
               == (int16_t)(v & 0xFFu));
    FUZZ_CHECK(decoded(nest_link_encode_oaes(id, v), NL_OAES, 0, (uint8_t)(id & 63u))
               == (int16_t)(v & 0xFFu));
    /* The events between two totals: adding them to the old total gives
     * the new one, mod 256. */
    FUZZ_CHECK((uint8_t)(before + nest_link_count_diff((uint8_t)v, before)) == (uint8_t)v);
    return 0;
}
