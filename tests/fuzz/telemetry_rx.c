/*
 * telemetry_rx.c - fuzz target: the robot's streaming decoder of the
 * frames a host sends it (wire/telemetry/telemetry_rx.c: poses and
 * routes over Bluetooth, docs/host_link.md), against the reference of
 * ref_deframe.h (its COBS and CRC, written from the format alone) applied
 * run by run with the decoder's rules: version 1, any channel, a body of
 * at most the decoder's buffer.  The first byte picks the buffer's size
 * (8..255 bytes); the rest is the wire, fed one byte at a time.  Every
 * frame the decoder gives must be the reference's next good frame, none
 * missed; good + bad frames must be the reference's count of runs.
 */
#include "fuzz.h"
#include "ref_deframe.h"

#include "telemetry/telemetry_rx.h"

/* The reference's verdict on one run between zeros, with the decoder's
 * buffer of `cap` bytes: 1 and *f for a good frame. */
static int ref_run(const uint8_t *run, size_t n, size_t cap, ref_frame_t *f)
{
    uint8_t body[REF_MAX_BODY + 300];
    long len = ref_cobs_decode(run, n, body, sizeof body);
    if (len < REF_HEADER + REF_CRC || (size_t)len > cap) {
        return 0;
    }
    uint16_t crc = ref_crc16(body, (size_t)len - REF_CRC);
    if (body[len - 2] != (crc >> 8) || body[len - 1] != (crc & 0xFF) || body[0] != 1) {
        return 0;
    }
    f->channel = body[1];
    f->robot_id = (uint16_t)(body[2] * 256 + body[3]);
    f->seq = (uint16_t)(body[4] * 256 + body[5]);
    f->len = (uint16_t)(len - REF_HEADER - REF_CRC);
    memcpy(f->payload, body + REF_HEADER, f->len);
    return 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static uint8_t buf[255];
    telemetry_rx_t rx;
    telemetry_rx_frame_t got;
    ref_frame_t want;
    size_t cap, start = 1, good = 0, runs = 0;
    if (size < 1) {
        return 0;
    }
    cap = 8u + data[0] % 248u;
    telemetry_rx_init(&rx, buf, (uint16_t)cap);
    for (size_t i = 1; i < size; i++) {
        uint8_t done = telemetry_rx_feed(&rx, data[i], &got);
        if (data[i] != 0) {
            FUZZ_CHECK(done == 0);   /* a frame ends only at a zero */
            continue;
        }
        int is_frame = i > start && ref_run(data + start, i - start, cap, &want);
        runs += i > start;
        FUZZ_CHECK(done == (uint8_t)is_frame);
        if (is_frame) {
            good++;
            FUZZ_CHECK(got.channel == want.channel && got.robot_id == want.robot_id && got.seq == want.seq);
            FUZZ_CHECK(got.len == want.len && memcmp(got.payload, want.payload, got.len) == 0);
        }
        start = i + 1;
    }
    FUZZ_CHECK(rx.frames == (uint16_t)good);
    /* One verdict a run; a run still open at the end counts only if it
     * already overflowed the buffer (counted when met: state 2, skipping). */
    FUZZ_CHECK((size_t)rx.frames + rx.bad == runs + (rx.state == 2u));
    return 0;
}
