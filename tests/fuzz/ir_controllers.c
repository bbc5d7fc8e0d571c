/*
 * ir_controllers.c - fuzz target: received IR messages into seed 000's
 * controllers, the forager and the nest beacon (firmware/foraging/), each
 * on the fake HAL of the unit tests (tests/fake_hal.h), whose IR inbox is
 * the HAL's ircom receive queue.  Any 16-bit value with any range, bearing
 * and sensor may arrive, many per step, for up to MAX_STEPS steps, while
 * the forager's camera, light and proximity are scripted so that it goes
 * through all its states.  With the loop closed (a setup bit) the beacon
 * also hears the forager's reports and the forager the beacon's frames.
 *
 * Properties, besides the sanitizers: the beacon broadcasts one frame a
 * step, cycling food, N_W and M_A, each what its ledger says (saturated as
 * nest_link.h documents); M_T2 stays the sum of its window; N_W counts at
 * most the 64 ids.  The forager keeps the last beacon value of each kind
 * and its range exactly as delivered, reports its own totals under its
 * id, counts a deposit at most once a step, and its probability of
 * leaving stays in [0, 1].
 *
 * Input: setup (1 byte: policy, closed loop, window), the forager's id
 * (2), T2 and the wait timeout of the beacon (2 + 1), then segments:
 * steps (1 byte: 1..128, then 16..2048 in steps of 16), messages per step (1 byte, % 17), world (1 byte),
 * and per message value (2), range (2, to 0xFFFE), bearing (2, to
 * +-3141 mrad), sensor (1, to 0..7), stride (1: added to the value's low
 * byte after each step, as a report's running total grows): the value is
 * anything a sender may put on the air, the rest what a HAL reports
 * (hal.h, hal/epuck).
 */
#include "fuzz.h"

#include "fake_hal.h"
#include "foraging/forager.h"
#include "foraging/nest_beacon.h"
#include "foraging/nest_link.h"

#define MAX_STEPS 3000u
#define MAX_MSGS 16u

typedef struct beacon_seen {
    int16_t food_q4;
    uint16_t waiting, mean_oae_q8, range_mm;
    uint8_t known;
} beacon_seen_t;

static hal_t HF, HB;          /* the forager's and the beacon's HAL */
static forager_t F;
static nest_beacon_t B;

/* Delivers one message to a controller's inbox and, for the forager,
 * remembers what a beacon frame tells it. */
static void deliver(hal_t *h, const hal_ircom_msg_t *m, beacon_seen_t *seen)
{
    nest_link_frame_t f;
    FUZZ_CHECK(fake_hal_push(h, m->value, m->range_mm, m->bearing_mrad));
    h->inbox[(h->in_head + h->in_count - 1u) % FAKE_INBOX_MAX].sensor = m->sensor;
    if (seen == NULL || nest_link_decode(m->value, &f) != NL_BEACON) {
        return;
    }
    if (f.kind == NL_KIND_FOOD) {
        seen->food_q4 = f.value;
    } else if (f.kind == NL_KIND_WAITING) {
        seen->waiting = (uint16_t)f.value;
    } else {
        seen->mean_oae_q8 = (uint16_t)f.value;
    }
    seen->known |= (uint8_t)(1u << f.kind);
    seen->range_mm = m->range_mm;
}

/* The forager's sensors for this segment: a red blob (narrow or held),
 * the nest light on one side, an obstacle in front. */
static void script_world(uint8_t world, int16_t bearing)
{
    uint8_t i;
    fake_hal_clear_blobs(&HF);
    if (world & 1u) {
        fake_hal_show_blob(&HF, HAL_COLOUR_RED, bearing, (world & 2u) ? 950u : 300u);
    }
    for (i = 0; i < HAL_IR_COUNT; i++) {
        HF.ambient[i] = 4000u;
        HF.proximity[i] = (world & 8u) && (i == 0 || i == 7) ? 900u : 20u;
    }
    if (world & 4u) {
        HF.ambient[(world >> 4) % HAL_IR_COUNT] = 500u;
    }
}

/* The fuzzer sees code coverage, not values: an input that drives the
 * beacon's ledger twice as far as any before looks like nothing new, and
 * streams that push a sum toward its limit are never kept.  Each power of
 * two the ledger's size (or M_T2) reaches from 2^16 up is made an edge of
 * its own, so that they are. */
static volatile uint32_t magnitude_sink;
#define LEVEL(v, b)                           \
    if ((v) >= (UINT32_C(1) << (b))) {        \
        magnitude_sink = (b);                 \
    }
static void magnitude_feedback(uint32_t v)
{
    LEVEL(v, 16) LEVEL(v, 17) LEVEL(v, 18) LEVEL(v, 19) LEVEL(v, 20) LEVEL(v, 21) LEVEL(v, 22) LEVEL(v, 23)
    LEVEL(v, 24) LEVEL(v, 25) LEVEL(v, 26) LEVEL(v, 27) LEVEL(v, 28) LEVEL(v, 29) LEVEL(v, 30) LEVEL(v, 31)
}

static void check_beacon(uint32_t sent_before, uint8_t kind)
{
    nest_link_frame_t f;
    int32_t food = B.food_q4 < NL_FOOD_Q4_MIN ? NL_FOOD_Q4_MIN
                   : B.food_q4 > NL_FOOD_Q4_MAX ? NL_FOOD_Q4_MAX : B.food_q4;
    uint32_t mean = nest_beacon_mean_oae_q8(&B);
    uint32_t sum = 0;
    uint8_t i;

    FUZZ_CHECK(B.state == NB_RUN);
    FUZZ_CHECK(HB.left == 0 && HB.right == 0);
    FUZZ_CHECK(HB.out_count == sent_before + 1u);
    FUZZ_CHECK(nest_link_decode(HB.last_sent, &f) == NL_BEACON && f.kind == kind);
    if (kind == NL_KIND_FOOD) {
        FUZZ_CHECK(f.value == food);
    } else if (kind == NL_KIND_WAITING) {
        FUZZ_CHECK(f.value == (B.n_waiting > NL_VALUE_MAX ? (int32_t)NL_VALUE_MAX : (int32_t)B.n_waiting));
    } else {
        FUZZ_CHECK(f.value == (mean > NL_VALUE_MAX ? (int32_t)NL_VALUE_MAX : (int32_t)mean));
    }
    FUZZ_CHECK(B.n_waiting <= NB_SLOTS);
    FUZZ_CHECK(B.n_bins >= 1u && B.n_bins <= NB_MAX_BINS && B.bin < B.n_bins);
    for (i = 0; i < NB_MAX_BINS; i++) {
        sum += B.bins[i];
    }
    FUZZ_CHECK(B.m_t2 == sum);
    magnitude_feedback(B.ledger_units < 0 ? 0u - (uint32_t)B.ledger_units : (uint32_t)B.ledger_units);
    magnitude_feedback(B.m_t2);
}

static void check_forager(const beacon_seen_t *seen, uint32_t sent_before, uint32_t deposits_before)
{
    nest_link_frame_t f;
    FUZZ_CHECK(F.state <= FORAGER_PARK);
    FUZZ_CHECK(F.beacon_known == seen->known);
    if (seen->known & FORAGER_KNOWS_FOOD) {
        FUZZ_CHECK(F.beacon_food_q4 == seen->food_q4);
    }
    if (seen->known & FORAGER_KNOWS_WAITING) {
        FUZZ_CHECK(F.beacon_n_waiting == seen->waiting);
    }
    if (seen->known & FORAGER_KNOWS_MEAN_OAE) {
        FUZZ_CHECK(F.beacon_mean_oae_q8 == seen->mean_oae_q8);
    }
    if (seen->known != 0u) {
        FUZZ_CHECK(F.beacon_range_mm == seen->range_mm);
    }
    FUZZ_CHECK(F.P_s >= 0.0f && F.P_s <= 1.0f);   /* false for a NaN too */
    FUZZ_CHECK(F.deposits - deposits_before <= 1u);
    FUZZ_CHECK(HF.out_count - sent_before <= 1u);
    if (HF.out_count != sent_before) {
        uint8_t type = nest_link_decode(HF.last_sent, &f);
        FUZZ_CHECK(type == NL_DEPOSITS || type == NL_OAES);
        FUZZ_CHECK(f.robot_id == (HF.id & 63u));
        FUZZ_CHECK((uint8_t)f.value == (uint8_t)(type == NL_DEPOSITS ? F.deposits : F.walk.oae_count));
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_in_t in = fuzz_in(data, size);
    uint8_t setup = fuzz_u8(&in);
    forager_params_t fp;
    nest_beacon_params_t bp;
    beacon_seen_t seen = { 0, 0, 0, 0, 0 };
    uint8_t closed = (setup & 4u) != 0u;
    uint16_t from_forager = 0, from_beacon = 0;
    uint8_t kind = NL_KIND_FOOD;
    uint32_t steps = 0;

    fake_hal_init(&HF, fuzz_u16(&in));
    fake_hal_init(&HB, 99u);
    forager_default_params(&fp);
    fp.policy = (ta_policy_t)(setup % 3u);
    if (setup & 16u) {  /* parking and the report cadence; 0 is read as 1 */
        fp.park_steps = fuzz_u8(&in);
        fp.report_steps = (uint8_t)(fuzz_u8(&in) % 51u);
    }
    forager_init(&F, &fp, 1u + setup);
    nest_beacon_default_params(&bp);
    if (setup & 8u) {   /* the documented ranges: T2 10..640 steps, timeout 1..254 */
        bp.t2_steps = (uint16_t)(10u + fuzz_u16(&in) % 631u);
        bp.wait_timeout_steps = (uint8_t)(1u + fuzz_u8(&in) % 254u);
    }
    nest_beacon_init(&B, &bp, 1u);

    while (in.left > 0 && steps < MAX_STEPS) {
        /* 1..128 steps, or long runs in steps of 16 (a stream of reports
         * that goes on for minutes, as a broken or hostile robot's would). */
        uint8_t r = fuzz_u8(&in);
        uint32_t repeat = r < 128u ? 1u + r : 16u * (r - 127u);
        uint8_t n = (uint8_t)(fuzz_u8(&in) % (MAX_MSGS + 1u));
        uint8_t world = fuzz_u8(&in);
        hal_ircom_msg_t msgs[MAX_MSGS];
        uint8_t stride[MAX_MSGS];
        uint8_t k;
        for (k = 0; k < n; k++) {
            /* The value is the sender's, anything; the rest is the
             * receiving HAL's, within what hal.h and hal/epuck give. */
            msgs[k].value = fuzz_u16(&in);
            msgs[k].range_mm = (uint16_t)(fuzz_u16(&in) % 0xFFFFu);
            msgs[k].bearing_mrad = (int16_t)(fuzz_u16(&in) % 6283u - 3141);
            msgs[k].sensor = (uint8_t)(fuzz_u8(&in) % HAL_IR_COUNT);
            stride[k] = fuzz_u8(&in);
        }
        script_world(world, n > 0 ? msgs[0].bearing_mrad : 0);
        for (; repeat > 0 && steps < MAX_STEPS; repeat--, steps++) {
            uint32_t f_sent = HF.out_count, b_sent = HB.out_count, deposits = F.deposits;
            if (closed && steps > 0) {
                hal_ircom_msg_t m = { .value = from_beacon, .sensor = 0u, .bearing_mrad = 0, .range_mm = 300u };
                deliver(&HF, &m, &seen);
                if (from_forager != 0u) {
                    m.value = from_forager;
                    deliver(&HB, &m, NULL);
                }
            }
            for (k = 0; k < n; k++) {
                deliver(&HF, &msgs[k], &seen);
                deliver(&HB, &msgs[k], NULL);
                /* The low byte (a report's total) moves on by the stride
                 * every step: a robot reporting, honestly or not. */
                msgs[k].value = (uint16_t)((msgs[k].value & 0xFF00u) | ((msgs[k].value + stride[k]) & 0xFFu));
            }
            forager_step(&F, &HF);
            nest_beacon_step(&B, &HB);
            check_forager(&seen, f_sent, deposits);
            check_beacon(b_sent, kind);
            kind = (uint8_t)((kind + 1u) % NL_KIND_COUNT);
            from_forager = HF.out_count != f_sent ? HF.last_sent : 0u;
            from_beacon = HB.last_sent;
            fake_hal_end_step(&HF);
            fake_hal_end_step(&HB);
        }
    }
    return 0;
}
