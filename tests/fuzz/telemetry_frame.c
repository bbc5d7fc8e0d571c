/*
 * telemetry_frame.c - fuzz target: the robots' serial framing
 * (wire/telemetry/telemetry_frame.c: COBS, CRC-16, frames) and its
 * decoder on the host (sim_host/core/robot_link.c, which deframes as the
 * bridge does), both checked against ref_deframe.h, a decoder written in
 * the harness from the format alone.  The first byte picks one of:
 *
 *   0  arbitrary bytes on the wire: the product's decoder and the
 *      reference give the same frames and the same count of bad runs;
 *   1  round trip: a frame telemetry_frame_encode writes for any channel,
 *      id, sequence number and payload (up to 255 bytes: longer than 240
 *      must be refused) decodes, by the reference, to exactly what went
 *      in, and by the product's decoder too when the channel exists;
 *   2  COBS alone: telemetry_cobs_encode of up to 1,000 arbitrary bytes
 *      is the reference's encoding byte for byte (COBS in its common form
 *      has one), unstuffs to the input, and an output one byte short is
 *      refused;
 *   3  frames a faulty or hostile sender could make: an arbitrary body of
 *      0..300 bytes with a correct CRC, stuffed and delimited, between
 *      arbitrary bytes; the two decoders must agree (the format allows
 *      240 payload bytes, no more).
 */
#include "fuzz.h"
#include "ref_deframe.h"

#include "core/robot_link.h"
#include "telemetry/telemetry_frame.h"

#define MAX_STREAM 4096

/* The product's decoder over a whole stream, in one step with no UART
 * limit; its frames must be the reference's, its count of bad runs too. */
static void decode_both(const uint8_t *s, size_t n)
{
    static robot_link_t link;   /* 5 KB: kept off the stack */
    ref_frame_t ref[ROBOT_LINK_FRAMES];
    ref_result_t r;

    robot_link_init(&link);
    robot_link_begin_step(&link, UINT32_MAX);
    FUZZ_CHECK(robot_link_write(&link, s, (uint16_t)n) == n);
    r = ref_deframe(s, n, ref, ROBOT_LINK_FRAMES);

    FUZZ_CHECK(link.bytes == n);
    FUZZ_CHECK(link.good + link.dropped == r.frames);
    FUZZ_CHECK(link.bad == r.bad);
    FUZZ_CHECK(link.n_frames == (r.frames < ROBOT_LINK_FRAMES ? r.frames : ROBOT_LINK_FRAMES));
    for (uint8_t k = 0; k < link.n_frames; k++) {
        const robot_link_frame_t *f = &link.frames[k];
        FUZZ_CHECK(f->len <= TELEMETRY_MAX_PAYLOAD);
        FUZZ_CHECK(f->channel == ref[k].channel && f->robot_id == ref[k].robot_id && f->seq == ref[k].seq);
        FUZZ_CHECK(f->len == ref[k].len && memcmp(f->payload, ref[k].payload, f->len) == 0);
    }
}

static void round_trip(fuzz_in_t *in)
{
    uint8_t channel = fuzz_u8(in);
    uint16_t robot_id = fuzz_u16(in);
    uint16_t seq = fuzz_u16(in);
    uint8_t payload[255];
    uint16_t len = (uint16_t)fuzz_bytes(in, payload, sizeof payload);
    uint8_t wire[TELEMETRY_FRAME_MAX + 8];
    uint16_t n = telemetry_frame_encode(wire, sizeof wire, channel, robot_id, seq, payload, len);
    ref_frame_t f;

    if (len > TELEMETRY_MAX_PAYLOAD) {
        FUZZ_CHECK(n == 0);
        return;
    }
    FUZZ_CHECK(n == TELEMETRY_FRAME_BYTES(len) && n <= TELEMETRY_FRAME_MAX);
    /* Too little room by one byte: nothing usable. */
    FUZZ_CHECK(telemetry_frame_encode(wire, (uint16_t)(n - 1), channel, robot_id, seq, payload, len) == 0);
    n = telemetry_frame_encode(wire, sizeof wire, channel, robot_id, seq, payload, len);
    FUZZ_CHECK(wire[0] == 0 && wire[n - 1] == 0 && memchr(wire + 1, 0, (size_t)n - 2) == NULL);
    if (channel == 0 || channel >= TELEMETRY_CH_COUNT) {
        /* No such channel: not a frame to either decoder; unstuffed, the
         * body is still exactly what the format says. */
        uint8_t body[REF_MAX_BODY];
        long blen = ref_cobs_decode(wire + 1, (size_t)n - 2, body, sizeof body);
        FUZZ_CHECK(blen == (long)(len + REF_HEADER + REF_CRC));
        FUZZ_CHECK(body[0] == TELEMETRY_VERSION && body[1] == channel);
        FUZZ_CHECK(ref_crc16(body, (size_t)blen) == 0);   /* CRC residue of a good body */
        FUZZ_CHECK(memcmp(body + REF_HEADER, payload, len) == 0);
        FUZZ_CHECK(!ref_unframe(wire + 1, (size_t)n - 2, &f));
    } else {
        FUZZ_CHECK(ref_unframe(wire + 1, (size_t)n - 2, &f));
        FUZZ_CHECK(f.channel == channel && f.robot_id == robot_id && f.seq == seq);
        FUZZ_CHECK(f.len == len && memcmp(f.payload, payload, len) == 0);
    }
    decode_both(wire, n);
}

/* COBS in the common form, written here from the format (not the
 * product's encoder), for bodies the product would never send. */
static size_t ref_cobs_encode(const uint8_t *in, size_t n, uint8_t *out)
{
    size_t code_at = 0, o = 1;
    uint8_t code = 1;
    for (size_t i = 0; i < n; i++) {
        if (in[i] == 0) {
            out[code_at] = code;
            code_at = o++;
            code = 1;
            continue;
        }
        out[o++] = in[i];
        if (++code == 0xFF) {
            out[code_at] = code;
            code = 1;
            if (i + 1 == n) {
                return o;
            }
            code_at = o++;
        }
    }
    out[code_at] = code;
    return o;
}

static void cobs_alone(fuzz_in_t *in)
{
    static uint8_t raw[1000], out[1000 + 1000 / 254 + 2], want[sizeof out], back[1000];
    uint16_t len = (uint16_t)fuzz_bytes(in, raw, sizeof raw);
    uint16_t n = telemetry_cobs_encode(raw, len, out, sizeof out);

    /* COBS in its common form is one encoding: byte for byte the
     * reference's, within the documented bound. */
    FUZZ_CHECK(n == ref_cobs_encode(raw, len, want));
    FUZZ_CHECK(memcmp(out, want, n) == 0);
    FUZZ_CHECK(n <= len + 1u + len / 254u);
    FUZZ_CHECK(memchr(out, 0, n) == NULL);
    FUZZ_CHECK(ref_cobs_decode(out, n, back, sizeof back) == (long)len);
    FUZZ_CHECK(memcmp(back, raw, len) == 0);
    FUZZ_CHECK(telemetry_cobs_encode(raw, len, out, (uint16_t)(n - 1)) == 0);
}

static void hostile_sender(fuzz_in_t *in)
{
    static uint8_t stream[MAX_STREAM];
    uint8_t body[300 + REF_CRC];
    uint8_t how = fuzz_u8(in);
    size_t before = fuzz_u8(in) % 64u, after = fuzz_u8(in) % 64u;
    /* Lengths near the format's limit are the interesting ones: half the
     * inputs take 230..259 body bytes, the others 0..300. */
    size_t blen = (how & 1u) ? 230u + fuzz_u8(in) % 30u : fuzz_u16(in) % 301u;
    size_t n = 0;
    uint16_t crc;

    n += fuzz_bytes(in, stream, before);
    stream[n++] = 0;
    blen = fuzz_bytes(in, body, blen);
    if ((how & 2u) && blen >= 2) {
        body[0] = TELEMETRY_VERSION;   /* a header that passes, so the rest is tested */
        body[1] = (uint8_t)(1u + body[1] % (TELEMETRY_CH_COUNT - 1u));
    }
    crc = ref_crc16(body, blen);
    body[blen] = (uint8_t)(crc >> 8);
    body[blen + 1] = (uint8_t)crc;
    n += ref_cobs_encode(body, blen + REF_CRC, stream + n);
    stream[n++] = 0;
    n += fuzz_bytes(in, stream + n, after);
    decode_both(stream, n);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_in_t in = fuzz_in(data, size);
    switch (fuzz_u8(&in) % 4u) {
    case 0:
        if (in.left <= MAX_STREAM) {
            decode_both(in.p, in.left);
        }
        break;
    case 1:
        round_trip(&in);
        break;
    case 2:
        cobs_alone(&in);
        break;
    default:
        hostile_sender(&in);
        break;
    }
    return 0;
}
