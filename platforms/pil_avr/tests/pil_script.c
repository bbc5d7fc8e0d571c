/* pil_script.c - pil_script.h. */
#include "pil_script.h"

#include <stdarg.h>
#include <string.h>

/* splitmix64 of the inputs: the script's one source of numbers. */
static uint64_t mix(uint64_t x)
{
    x += UINT64_C(0x9E3779B97F4A7C15);
    x = (x ^ (x >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    x = (x ^ (x >> 27)) * UINT64_C(0x94D049BB133111EB);
    return x ^ (x >> 31);
}

static uint64_t h(const pil_script_t *s, uint32_t channel, uint32_t k)
{
    return mix(mix(mix(s->seed ^ ((uint64_t)s->robot << 32)) ^ s->step) ^ ((uint64_t)channel << 32 | k));
}

static void logf_(pil_script_t *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (s->log_len < sizeof s->log) {
        int n = vsnprintf(s->log + s->log_len, sizeof s->log - s->log_len, fmt, ap);
        if (n > 0) {
            s->log_len += (size_t)n;
        }
    }
    va_end(ap);
}

void pil_script_init(pil_script_t *s, uint64_t seed, uint32_t robot, uint16_t period_ms, int frames)
{
    memset(s, 0, sizeof *s);
    s->seed = seed;
    s->robot = robot;
    s->period_ms = period_ms;
    s->frames = frames;
    s->cam_w = 40;
    s->cam_h = 20;
}

pil_config_t pil_script_config(const pil_script_t *s, const pil_hello_t *hello)
{
    pil_config_t c;
    memset(&c, 0, sizeof c);
    c.robot_id = (uint16_t)s->robot;
    c.seed = (uint32_t)mix(s->seed * 31u + s->robot);
    c.period_ms = hello->period_ms;
    c.ircom_bits = hello->ircom_bits;
    c.tx_per_period = hello->tx_per_period;
    c.flags = PIL_SIM_SOUND | (s->frames ? PIL_SIM_FRAMES : 0u);
    c.cam_width = s->cam_w;
    c.cam_height = s->cam_h;
    c.fov_mrad = 977;   /* 56 degrees */
    c.selector = 0;
    return c;
}

pil_step_t pil_script_begin(pil_script_t *s)
{
    pil_step_t st;
    memset(&st, 0, sizeof st);
    s->log_len = 0;
    s->log[0] = '\0';
    st.step = s->step;
    st.time_ms = s->step * s->period_ms;
    st.steps_left = (int16_t)(uint16_t)(uint32_t)s->steps_left;
    st.steps_right = (int16_t)(uint16_t)(uint32_t)s->steps_right;
    /* A UART's room at 115,200 baud, as a scenario may impose. */
    st.telemetry_room = (uint16_t)(11520u * s->period_ms / 1000u);
    st.mic_count = PIL_MIC_CELLS;
    for (uint8_t k = 0; k < PIL_MIC_CELLS; k++) {
        uint64_t v = h(s, 'M', k);
        st.mic[k].status = s->speaker_played ? HAL_ERR_BUSY : HAL_OK;
        st.mic[k].level = s->speaker_played ? 0u : (uint32_t)(v % 400000u);
    }
    /* New IR messages arrive between steps. */
    uint64_t arrivals = h(s, 'Q', 0) % 4u;
    for (uint32_t k = 0; k < arrivals; k++) {
        uint64_t v = h(s, 'q', k);
        if (s->q_count == PIL_SCRIPT_QUEUE) {
            break;
        }
        hal_ircom_msg_t *m = &s->queue[(s->q_head + s->q_count) % PIL_SCRIPT_QUEUE];
        m->value = (uint16_t)v;
        m->sensor = (uint8_t)((v >> 16) % 8u);
        m->bearing_mrad = (int16_t)((int32_t)((v >> 24) % 6284u) - 3141);
        m->range_mm = (uint16_t)(40u + (v >> 40) % 900u);
        s->q_count++;
    }
    return st;
}

void pil_script_end(pil_script_t *s, const pil_act_t *act)
{
    logf_(s, "ACT wheels %d %d leds %04x speaker %u tx", act->wheel_left, act->wheel_right, act->leds, act->speaker);
    for (uint8_t k = 0; k < act->tx_count; k++) {
        logf_(s, " %04x", act->tx[k]);
    }
    logf_(s, " telemetry %u bytes", act->telemetry_len);
    uint32_t sum = 0;
    for (uint16_t k = 0; k < act->telemetry_len; k++) {
        sum = sum * 31u + act->telemetry[k];
    }
    logf_(s, " (hash %08x)\n", sum);
    if (s->telemetry_out && act->telemetry_len) {
        fwrite(act->telemetry, 1, act->telemetry_len, s->telemetry_out);
    }
    s->telemetry_bytes += act->telemetry_len;
    s->steps_left += act->wheel_left * (int32_t)s->period_ms / 1000;
    s->steps_right += act->wheel_right * (int32_t)s->period_ms / 1000;
    s->speaker_played = act->speaker;
    s->step++;
}

static void ir(void *ctx, uint16_t out[HAL_IR_COUNT])
{
    pil_script_t *s = ctx;
    uint64_t obstacle = h(s, 'O', 0) % 100u;
    for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
        uint64_t v = h(s, 'I', k);
        out[k] = (uint16_t)(obstacle < 15u && (v % 8u) < 3u ? 300u + v % 3796u : v % 120u);
    }
    logf_(s, "IR %u..%u\n", out[0], out[7]);
}

static void ambient(void *ctx, uint16_t out[HAL_IR_COUNT])
{
    pil_script_t *s = ctx;
    for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
        out[k] = (uint16_t)(1500u + h(s, 'A', k) % 2596u);
    }
    logf_(s, "AMBIENT %u..%u\n", out[0], out[7]);
}

static uint8_t blobs(void *ctx, hal_blob_t out[HAL_MAX_BLOBS])
{
    pil_script_t *s = ctx;
    uint8_t n = (uint8_t)(h(s, 'B', 0) % 4u);
    uint16_t pixels = 400;
    for (uint8_t k = 0; k < n; k++) {
        uint64_t v = h(s, 'b', k);
        pixels = (uint16_t)(pixels - 1u - v % 90u);
        out[k].colour = (uint8_t)(1u + v % 3u);
        out[k].bearing_mrad = (int16_t)((int32_t)((v >> 8) % 977u) - 488);
        out[k].width_mrad = (uint16_t)(20u + (v >> 20) % 400u);
        out[k].pixels = pixels;
    }
    logf_(s, "BLOBS %u\n", n);
    return n;
}

/* A frame of grey with up to three coloured bars, big-endian RGB565. */
static int frame(void *ctx, uint8_t *out, uint16_t bytes, char *err)
{
    pil_script_t *s = ctx;
    (void)err;
    uint16_t w = s->cam_w, hgt = s->cam_h;
    static const uint16_t colour[3] = { 0xF800u, 0x07E0u, 0x001Fu };
    uint8_t bars = (uint8_t)(h(s, 'F', 0) % 4u);
    for (uint16_t y = 0; y < hgt; y++) {
        for (uint16_t x = 0; x < w; x++) {
            uint16_t px = 0x8410u;   /* grey */
            for (uint8_t b = 0; b < bars; b++) {
                uint64_t v = h(s, 'f', b);
                uint16_t x0 = (uint16_t)(v % w), bw = (uint16_t)(1u + (v >> 8) % 10u);
                uint16_t y0 = (uint16_t)((v >> 16) % hgt);
                if (x >= x0 && x < x0 + bw && y >= y0) {
                    px = colour[(v >> 24) % 3u];
                }
            }
            size_t at = 2u * ((size_t)y * w + x);
            if (at + 1u < bytes) {
                out[at] = (uint8_t)(px >> 8);
                out[at + 1] = (uint8_t)px;
            }
        }
    }
    logf_(s, "FRAME %u bars\n", bars);
    return 0;
}

static hal_status_t pose(void *ctx, hal_pose_t *out)
{
    pil_script_t *s = ctx;
    uint64_t v = h(s, 'P', 0);
    if (v % 20u == 0u) {
        logf_(s, "POSE none\n");
        return HAL_ERR_UNAVAILABLE;
    }
    out->x_mm = (int32_t)((v >> 8) % 4001u) - 2000;
    out->y_mm = (int32_t)((v >> 24) % 4001u) - 2000;
    out->heading_mrad = (int16_t)((int32_t)((v >> 40) % 6283u) - 3141);
    out->age_ms = 0;
    logf_(s, "POSE %d %d %d\n", (int)out->x_mm, (int)out->y_mm, out->heading_mrad);
    return HAL_OK;
}

static hal_status_t rx(void *ctx, hal_ircom_msg_t *out)
{
    pil_script_t *s = ctx;
    if (s->q_count == 0) {
        logf_(s, "RX empty\n");
        return HAL_ERR_EMPTY;
    }
    *out = s->queue[s->q_head];
    s->q_head = (uint8_t)((s->q_head + 1u) % PIL_SCRIPT_QUEUE);
    s->q_count--;
    logf_(s, "RX %04x\n", out->value);
    return HAL_OK;
}

/* Every 100 steps a route (firmware/waypoint/route_msg.h), now and then a
 * message that is not one. */
static hal_status_t host(void *ctx, uint8_t *buf, uint8_t cap, uint8_t *len)
{
    pil_script_t *s = ctx;
    uint8_t msg[HAL_HOST_MSG_MAX], n;
    *len = 0;
    if (s->step / 100u < s->host_sent || s->step % 100u > 20u) {
        logf_(s, "HOST empty\n");
        return HAL_ERR_EMPTY;
    }
    uint64_t v = h(s, 'H', 0);
    if (v % 7u == 0u) {
        n = (uint8_t)(1u + v % 30u);
        for (uint8_t k = 0; k < n; k++) {
            msg[k] = (uint8_t)h(s, 'h', k);
        }
    } else {
        uint8_t t = (uint8_t)(1u + v % 6u);
        msg[0] = 0x52u;
        msg[1] = t;
        n = (uint8_t)(2u + 8u * (t + 1u));
        for (uint8_t k = 0; k <= t; k++) {
            for (uint8_t c = 0; c < 2; c++) {
                int32_t mm = (int32_t)(h(s, 'r', 2u * k + c) % 3001u) - 1500;
                uint8_t *p = msg + 2 + 8 * k + 4 * c;
                p[0] = (uint8_t)((uint32_t)mm >> 24);
                p[1] = (uint8_t)((uint32_t)mm >> 16);
                p[2] = (uint8_t)((uint32_t)mm >> 8);
                p[3] = (uint8_t)mm;
            }
        }
    }
    if (n > cap) {
        logf_(s, "HOST too long %u > %u\n", n, cap);
        return HAL_ERR_RANGE;
    }
    memcpy(buf, msg, n);
    *len = n;
    s->host_sent = s->step / 100u + 1u;
    logf_(s, "HOST %u bytes\n", n);
    return HAL_OK;
}

static hal_status_t ground(void *ctx, uint16_t out[HAL_GROUND_COUNT])
{
    pil_script_t *s = ctx;
    for (uint8_t k = 0; k < HAL_GROUND_COUNT; k++) {
        out[k] = (uint16_t)(h(s, 'G', k) % 1100u);
    }
    logf_(s, "GROUND %u %u %u\n", out[0], out[1], out[2]);
    return HAL_OK;
}

static uint16_t telemetry(void *ctx, const uint8_t *bytes, uint16_t len)
{
    pil_script_t *s = ctx;
    uint32_t sum = 0;
    for (uint16_t k = 0; k < len; k++) {
        sum = sum * 31u + bytes[k];
    }
    logf_(s, "TELEMETRY %u bytes (hash %08x)\n", len, sum);
    if (s->telemetry_out) {
        fwrite(bytes, 1, len, s->telemetry_out);
    }
    s->telemetry_bytes += len;
    return len;
}

pil_host_ops_t pil_script_ops(pil_script_t *s)
{
    pil_host_ops_t o = {
        .ctx = s, .ir = ir, .ambient = ambient, .blobs = blobs, .frame = frame, .pose = pose,
        .ircom_receive = rx, .host_receive = host, .ground = ground, .telemetry = telemetry,
    };
    return o;
}
