/* pil_host.c - pil_host.h. */
#include "pil_host.h"

#include <stdio.h>
#include <string.h>

#define PAYLOAD (PIL_HEADER_BYTES)
#define ROOM ((uint16_t)(PIL_FRAME_MAX - PIL_HEADER_BYTES - PIL_CRC_BYTES))

static const char *type_name(uint8_t t)
{
    switch (t) {
    case PIL_HELLO: return "HELLO";
    case PIL_REQUEST: return "REQUEST";
    case PIL_ACT: return "ACT";
    case PIL_FAULT: return "FAULT";
    case PIL_READY: return "READY";
    case PIL_CONFIG: return "CONFIG";
    case PIL_STEP: return "STEP";
    case PIL_REPLY: return "REPLY";
    case PIL_EMU: return "EMU";
    }
    return "an unknown frame type";
}

const char *pil_emu_event_name(uint8_t event)
{
    switch (event) {
    case PIL_EMU_FRAME: return "handed over a frame";
    case PIL_EMU_BUDGET: return "ran past its cycle budget without answering";
    case PIL_EMU_CRASH: return "crashed (an access outside its memory or the program counter past its "
                               "flash: simavr's crashed state, a Cortex-M fault)";
    case PIL_EMU_RESET: return "reset (jumped to the reset vector, or reset itself)";
    case PIL_EMU_HALT: return "halted (slept with interrupts off, or its main returned)";
    case PIL_EMU_STACK: return "overflowed its stack (into its static data, or the guard below it)";
    case PIL_EMU_BAD_MAILBOX: return "rang with a mailbox outside its RAM";
    }
    return "stopped for an unknown reason";
}

void pil_host_init(pil_host_t *h, const pil_host_io_t *io)
{
    memset(h, 0, sizeof *h);
    h->io = *io;
}

static int send_frame(pil_host_t *h, uint8_t type, uint8_t seq, uint16_t len, char *err)
{
    uint16_t n = pil_frame_seal(h->buf, (uint16_t)sizeof h->buf, type, seq, len);
    if (n == 0u) {
        snprintf(err, PIL_HOST_ERR, "a %s frame of %u bytes does not fit the protocol", type_name(type), len);
        return -1;
    }
    return h->io.send(h->io.ctx, h->buf, n, err);
}

/* The robot's next frame, checked, of type `want` (or FAULT, which is an
 * error) and step `seq`; its cycles added to the step's. */
static int recv_frame(pil_host_t *h, uint8_t want, uint8_t seq, pil_frame_t *f, char *err)
{
    uint16_t n = 0;
    pil_frame_error_t fe;
    h->emu.event = PIL_EMU_FRAME;
    h->emu.cycles = 0u;
    h->emu.first_mark = h->emu.last_mark = PIL_NO_MARK;
    if (h->io.recv(h->io.ctx, h->buf, (uint16_t)sizeof h->buf, &n, &h->emu, err) != 0) {
        return -1;
    }
    if (h->emu.first_mark != PIL_NO_MARK && !h->marked) {
        h->mark_begin = h->step_cycles + h->emu.first_mark;
        h->marked = 1u;
    }
    if (h->emu.last_mark != PIL_NO_MARK) {
        h->mark_end = h->step_cycles + h->emu.last_mark;
    }
    h->step_cycles += h->emu.cycles;
    fe = pil_frame_check(h->buf, n, f);
    if (fe != PIL_FRAME_OK) {
        snprintf(err, PIL_HOST_ERR, "sent %s (%u bytes) where a %s was due", pil_frame_error_name(fe), n,
                 type_name(want));
        return -1;
    }
    if (f->type == PIL_FAULT) {
        snprintf(err, PIL_HOST_ERR, "could not read the simulator's last frame (FAULT: %s, frame type 0x%02x)",
                 f->len >= 1u && f->payload[0] == PIL_FAULT_FRAME ? "it did not check out"
                 : f->len >= 1u && f->payload[0] == PIL_FAULT_TYPE ? "not the frame it waited for"
                 : f->len >= 1u && f->payload[0] == PIL_FAULT_SEQ ? "of another step"
                 : "its payload did not decode",
                 f->len >= 2u ? f->payload[1] : 0u);
        return -1;
    }
    if (f->type == PIL_REQUEST && want == PIL_ACT) {
        want = PIL_REQUEST;   /* either, during a step */
    }
    if (f->type != want) {
        snprintf(err, PIL_HOST_ERR, "sent a %s frame where a %s was due", type_name(f->type), type_name(want));
        return -1;
    }
    if (f->seq != seq) {
        snprintf(err, PIL_HOST_ERR, "sent a %s frame of step %u (mod 256) during step %u (mod 256)",
                 type_name(f->type), f->seq, seq);
        return -1;
    }
    return 0;
}

int pil_host_hello(pil_host_t *h, char err[PIL_HOST_ERR])
{
    pil_frame_t f;
    h->step_cycles = 0u;
    if (recv_frame(h, PIL_HELLO, 0u, &f, err) != 0) {
        return -1;
    }
    if (pil_hello_decode(f.payload, f.len, &h->hello) != 0) {
        snprintf(err, PIL_HOST_ERR, "sent a HELLO that does not decode (%u bytes)", f.len);
        return -1;
    }
    return 0;
}

int pil_host_config(pil_host_t *h, char err[PIL_HOST_ERR])
{
    pil_frame_t f;
    uint16_t n = pil_config_encode(h->buf + PAYLOAD, ROOM, &h->config);
    if (send_frame(h, PIL_CONFIG, 0u, n, err) != 0 || recv_frame(h, PIL_READY, 0u, &f, err) != 0) {
        return -1;
    }
    if (f.len != 0u) {
        snprintf(err, PIL_HOST_ERR, "sent a READY with a payload (%u bytes)", f.len);
        return -1;
    }
    h->boot_cycles = h->step_cycles;
    return 0;
}

/* The answer to one request, written into h->buf's payload: its length,
 * or -1 with err. */
static int answer(pil_host_t *h, const pil_request_t *q, const pil_host_ops_t *ops, char *err)
{
    uint8_t *p = h->buf + PAYLOAD;
    uint16_t v[HAL_IR_COUNT];
    switch (q->what) {
    case PIL_WHAT_IR:
        ops->ir(ops->ctx, v);
        return pil_reply_readings(p, ROOM, PIL_WHAT_IR, v);
    case PIL_WHAT_AMBIENT:
        ops->ambient(ops->ctx, v);
        return pil_reply_readings(p, ROOM, PIL_WHAT_AMBIENT, v);
    case PIL_WHAT_CAMERA:
        if (h->config.flags & PIL_SIM_FRAMES) {
            uint32_t bytes = 2u * (uint32_t)h->config.cam_width * h->config.cam_height;
            if (bytes + 1u > ROOM || bytes + 1u + PIL_HEADER_BYTES + PIL_CRC_BYTES > h->hello.mailbox) {
                snprintf(err, PIL_HOST_ERR, "asked for a %ux%u camera frame, which does not fit its %u-byte mailbox",
                         h->config.cam_width, h->config.cam_height, h->hello.mailbox);
                return -1;
            }
            if (ops->frame(ops->ctx, p + 1, (uint16_t)bytes, err) != 0) {
                return -1;
            }
            return pil_reply_frame(p, ROOM, (uint16_t)bytes);
        } else {
            hal_blob_t b[HAL_MAX_BLOBS];
            uint8_t n = ops->blobs(ops->ctx, b);
            return pil_reply_blobs(p, ROOM, b, n > HAL_MAX_BLOBS ? (uint8_t)HAL_MAX_BLOBS : n);
        }
    case PIL_WHAT_POSE: {
        hal_pose_t pose;
        hal_status_t st;
        memset(&pose, 0, sizeof pose);
        st = ops->pose(ops->ctx, &pose);
        return pil_reply_pose(p, ROOM, st, &pose);
    }
    case PIL_WHAT_RX: {
        hal_ircom_msg_t m;
        hal_status_t st;
        memset(&m, 0, sizeof m);
        st = ops->ircom_receive(ops->ctx, &m);
        return pil_reply_rx(p, ROOM, st, &m);
    }
    case PIL_WHAT_HOST: {
        uint8_t bytes[HAL_HOST_MSG_MAX], len = 0u;
        uint8_t cap = q->arg < HAL_HOST_MSG_MAX ? q->arg : (uint8_t)HAL_HOST_MSG_MAX;
        hal_status_t st = ops->host_receive(ops->ctx, bytes, cap, &len);
        return pil_reply_host(p, ROOM, st, bytes, st == HAL_OK ? len : 0u);
    }
    case PIL_WHAT_GROUND: {
        uint16_t g[HAL_GROUND_COUNT] = { 0u, 0u, 0u };
        hal_status_t st = ops->ground(ops->ctx, g);
        return pil_reply_ground(p, ROOM, st, g);
    }
    case PIL_WHAT_TELEMETRY: {
        uint8_t copy[PIL_TELEMETRY_MAX];
        memcpy(copy, q->bytes, q->len);   /* the reply is written over them */
        return pil_reply_accepted(p, ROOM, ops->telemetry(ops->ctx, copy, q->len));
    }
    }
    snprintf(err, PIL_HOST_ERR, "asked for channel %u, which the protocol does not have", q->what);
    return -1;
}

int pil_host_step(pil_host_t *h, const pil_step_t *step, const pil_host_ops_t *ops, pil_act_t *act,
                  char err[PIL_HOST_ERR])
{
    uint8_t seq = (uint8_t)(step->step & 0xFFu);
    pil_frame_t f;
    uint16_t n = pil_step_encode(h->buf + PAYLOAD, ROOM, step);
    h->step_cycles = 0u;
    h->control_cycles = 0u;
    h->marked = 0u;
    h->requests = 0u;
    if (n == 0u) {
        snprintf(err, PIL_HOST_ERR, "a STEP frame that does not encode (%u microphone cells)", step->mic_count);
        return -1;
    }
    if (send_frame(h, PIL_STEP, seq, n, err) != 0) {
        return -1;
    }
    for (;;) {
        if (recv_frame(h, PIL_ACT, seq, &f, err) != 0) {
            return -1;
        }
        if (f.type == PIL_ACT) {
            break;
        }
        pil_request_t q;
        int len;
        if (pil_request_decode(f.payload, f.len, &q) != 0) {
            snprintf(err, PIL_HOST_ERR, "sent a REQUEST that does not decode (%u bytes)", f.len);
            return -1;
        }
        h->requests++;
        len = answer(h, &q, ops, err);
        if (len < 0 || send_frame(h, PIL_REPLY, seq, (uint16_t)len, err) != 0) {
            return -1;
        }
    }
    if (pil_act_decode(f.payload, f.len, act) != 0) {
        snprintf(err, PIL_HOST_ERR, "sent an ACT that does not decode (%u bytes)", f.len);
        return -1;
    }
    if (act->tx_count > h->config.tx_per_period) {
        snprintf(err, PIL_HOST_ERR, "sent %u IR messages in one period (it may send %u)", act->tx_count,
                 h->config.tx_per_period);
        return -1;
    }
    h->control_cycles = h->marked && h->mark_end >= h->mark_begin ? h->mark_end - h->mark_begin : h->step_cycles;
    memcpy(h->act_telemetry, act->telemetry, act->telemetry_len);
    act->telemetry = h->act_telemetry;
    return 0;
}
