/*
 * robot_link.c - fuzz target: the serial frame decoder of the host side
 * (sim_host/core/robot_link.c: a robot's UART stream cut into frames and
 * checked exactly as the serial bridge does), as a stream: bytes arrive in
 * chunks of any size, across control steps, under a UART budget per step.
 * After every step what it holds and counts must be what ref_deframe.h
 * finds in the same bytes: the frames completed in that step (the first
 * ROBOT_LINK_FRAMES kept, the others counted as dropped), the bad runs,
 * the bytes taken, and the step's raw bytes for a dump.
 *
 * Input: a list of operations, until the bytes run out:
 *   op % 4 == 0   a new step with a budget of u16 bytes (0xFFFF: no limit);
 *   otherwise     write the next (u16 % 1024) bytes.
 */
#include "fuzz.h"
#include "ref_deframe.h"

#include "core/robot_link.h"

#define MAX_STEP 8192   /* bytes offered in one step that the check keeps */

typedef struct model {
    uint8_t pending[MAX_STEP + 300];   /* the unfinished run, then this step's bytes */
    size_t pending_len, step_start;    /* step_start: where this step's bytes begin */
    uint64_t taken, good, bad, dropped;
} model_t;

/* Ends a step: the frames completed in it must be those the link holds. */
static void check_step(const robot_link_t *l, model_t *m)
{
    ref_frame_t ref[ROBOT_LINK_FRAMES];
    const uint8_t *s = m->pending;
    size_t n = m->pending_len, step_bytes = n - m->step_start;
    ref_result_t r = ref_deframe(s, n, ref, ROBOT_LINK_FRAMES);
    size_t kept = r.frames < ROBOT_LINK_FRAMES ? r.frames : ROBOT_LINK_FRAMES;

    m->good += kept;
    m->dropped += r.frames - kept;
    m->bad += r.bad;
    FUZZ_CHECK(l->bytes == m->taken);
    FUZZ_CHECK(l->good == m->good && l->dropped == m->dropped && l->bad == m->bad);
    FUZZ_CHECK(l->n_frames == kept);
    for (size_t k = 0; k < kept; k++) {
        const robot_link_frame_t *f = &l->frames[k];
        FUZZ_CHECK(f->len <= TELEMETRY_MAX_PAYLOAD);
        FUZZ_CHECK(f->channel == ref[k].channel && f->robot_id == ref[k].robot_id && f->seq == ref[k].seq);
        FUZZ_CHECK(f->len == ref[k].len && memcmp(f->payload, ref[k].payload, f->len) == 0);
    }
    /* The dump keeps the step's first ROBOT_LINK_RAW bytes. */
    FUZZ_CHECK(l->raw_len == (step_bytes < ROBOT_LINK_RAW ? step_bytes : ROBOT_LINK_RAW));
    FUZZ_CHECK(memcmp(l->raw, s + m->step_start, l->raw_len) == 0);

    /* What follows the last zero goes on into the next step. */
    const uint8_t *z = s + n;
    while (z > s && z[-1] != 0) {
        z--;
    }
    size_t rest = (size_t)(s + n - z);
    if (rest > 300) {
        /* Longer than any frame: its end cannot be one either.  Keep 300
         * non-zero bytes, as bad a run as the whole. */
        memmove(m->pending, s + n - 300, 300);
        rest = 300;
    } else {
        memmove(m->pending, z, rest);
    }
    m->pending_len = rest;
    m->step_start = rest;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static robot_link_t link;
    static model_t m;
    fuzz_in_t in = fuzz_in(data, size);

    memset(&m, 0, sizeof m);
    robot_link_init(&link);
    robot_link_begin_step(&link, UINT32_MAX);
    while (in.left > 0) {
        uint8_t op = fuzz_u8(&in);
        if (op % 4u == 0) {
            uint16_t b = fuzz_u16(&in);
            check_step(&link, &m);
            robot_link_begin_step(&link, b == 0xFFFFu ? UINT32_MAX : b);
            continue;
        }
        uint16_t want = (uint16_t)(fuzz_u16(&in) % 1024u);
        uint8_t chunk[1024];
        uint16_t len = (uint16_t)fuzz_bytes(&in, chunk, want);
        uint32_t budget = link.budget;
        uint16_t took = robot_link_write(&link, chunk, len);
        FUZZ_CHECK(took == (len <= budget ? len : budget));
        FUZZ_CHECK(link.budget == budget - took);
        if (m.pending_len + took > sizeof m.pending) {
            return 0;   /* more in one step than the model keeps: stop here */
        }
        memcpy(m.pending + m.pending_len, chunk, took);
        m.pending_len += took;
        m.taken += took;
    }
    check_step(&link, &m);
    return 0;
}
