/*
 * epuck_ir.c - fuzz target: the e-puck's IR receive path below the
 * controllers, platforms/epuck1/hal: what the IR driver hands over (the e-RandB
 * turret's frame, or libIrcom's message with -DFUZZ_LIBIRCOM) becomes a
 * hal_ircom_msg_t in the HAL's inbox, which hal_ircom_receive gives the
 * controller.  Drivers are the e-puck library's stubs of the firmware
 * tests (platforms/epuck1/tests/stubs/); their floats here are any 32 bits (NaN,
 * infinities, huge values: an I2C glitch or a library bug can give them).
 *
 * Properties: every message received carries the driver's data bits
 * (16 on the turret, 8 on libIrcom), a bearing in (-pi, pi] mrad that is
 * the driver's angle to within float rounding (0 when the angle is not a
 * number or beyond 1000 rad), a sensor 0..7 (on the turret: one nearest to
 * the bearing), the range in mm as hal.h and the backend say, and no
 * message is invented or lost except as counted: libIrcom's transmission
 * errors are dropped, and a full inbox counts what it drops.
 *
 * Input: per step, a count of receptions (1 byte, % 24), then each: turret
 * data (2), bearing (4), range (2); or libIrcom value (4), distance (4),
 * direction (4), sensor (1, signed), error (1, % 2).
 */
#include <math.h>

#include "fuzz.h"

#include "epuck_stubs.h"
#include "hal_epuck.h"

#define MAX_PER_STEP 24u
#define PI_D 3.14159265358979323846

typedef struct expect {
    uint16_t value;
    float rad;          /* the driver's angle */
    uint32_t range_mm;  /* before the 0xFFFE cap */
    int sensor;         /* libIrcom: the receiving sensor, or -1 */
} expect_t;

static double wrap_pi_mrad(double m)
{
    m = fmod(m, 2000.0 * PI_D);
    if (m > 1000.0 * PI_D) {
        m -= 2000.0 * PI_D;
    } else if (m <= -1000.0 * PI_D) {
        m += 2000.0 * PI_D;
    }
    return m;
}

/* Circular distance of two bearings, mrad. */
static double gap(double a, double b)
{
    return fabs(wrap_pi_mrad(a - b));
}

static void check(const hal_ircom_msg_t *m, const expect_t *e)
{
    double want = e->rad * 1000.0;
    FUZZ_CHECK(m->value == e->value);
    FUZZ_CHECK(m->bearing_mrad > -UNITS_PI_MRAD && m->bearing_mrad <= UNITS_PI_MRAD);
    if (!(fabs(want) < 1.0e6)) {
        FUZZ_CHECK(m->bearing_mrad == 0);
    } else {
        /* Float steps of 2 pi from up to 1000 rad: a few mrad at most. */
        FUZZ_CHECK(gap(m->bearing_mrad, want) <= (fabs(want) > 1.0e4 ? 8.0 : 1.0));
    }
    FUZZ_CHECK(m->sensor < HAL_IR_COUNT);
    if (e->sensor >= 0 && e->sensor < (int)HAL_IR_COUNT) {
        FUZZ_CHECK(m->sensor == e->sensor);
    } else {
        for (uint8_t i = 0; i < HAL_IR_COUNT; i++) {
            FUZZ_CHECK(gap(m->bearing_mrad, units_ir_bearing_mrad(m->sensor))
                       <= gap(m->bearing_mrad, units_ir_bearing_mrad(i)));
        }
    }
    FUZZ_CHECK(m->range_mm == (e->range_mm > 0xFFFEu ? 0xFFFEu : e->range_mm));
}

#ifdef FUZZ_LIBIRCOM
/* libIrcom: cm to mm, rounded; not a positive number: 0. */
static uint32_t libircom_range(float cm)
{
    float mm = cm * 10.0f;
    if (!(mm > 0.0f)) {
        return 0u;
    }
    return mm < 65534.0f ? (uint32_t)(mm + 0.5f) : 0xFFFFu;
}

/* Queues one message in libIrcom's stub; 1 if the HAL should keep it. */
static int take(fuzz_in_t *in, expect_t *e)
{
    int k = epuck_stub.ircom_count++;
    epuck_stub.ircom_value[k] = (long)(int32_t)fuzz_u32(in);
    epuck_stub.ircom_distance[k] = fuzz_f32_bits(in);
    epuck_stub.ircom_direction[k] = fuzz_f32_bits(in);
    epuck_stub.ircom_sensor[k] = (int8_t)fuzz_u8(in);
    epuck_stub.ircom_error[k] = fuzz_u8(in) % 2u;   /* 0 good, 1 transmission error */
    e->value = (uint16_t)(epuck_stub.ircom_value[k] & 0xFF);
    e->rad = epuck_stub.ircom_direction[k];
    e->range_mm = libircom_range(epuck_stub.ircom_distance[k]);
    e->sensor = epuck_stub.ircom_sensor[k];
    return epuck_stub.ircom_error[k] == 0;
}
#define STUB_ROOM() (epuck_stub.ircom_count < STUB_QUEUE)
#else
static int take(fuzz_in_t *in, expect_t *e)
{
    int k = epuck_stub.randb_count++;
    epuck_stub.randb_data[k] = fuzz_u16(in);
    epuck_stub.randb_bearing[k] = fuzz_f32_bits(in);
    epuck_stub.randb_range[k] = fuzz_u16(in);
    e->value = (uint16_t)epuck_stub.randb_data[k];
    e->rad = epuck_stub.randb_bearing[k];
    e->range_mm = (uint32_t)epuck_stub.randb_range[k] * 10u;   /* the default 10 mm per unit */
    e->sensor = -1;
    return 1;
}
#define STUB_ROOM() (epuck_stub.randb_count < STUB_QUEUE)
#endif

static void tick(void) {}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static hal_t hal;
    hal_epuck_config_t cfg;
    fuzz_in_t in = fuzz_in(data, size);
    uint32_t dropped = 0;

    epuck_stub_reset();
    hal_epuck_default_config(&cfg);
    cfg.camera = 0u;
    cfg.robot_id = 7u;
    FUZZ_CHECK(hal_epuck_init(&hal, &cfg, NULL, 0u) == 0);
    hal_epuck_start(&hal, tick);
    while (in.left > 0) {
        expect_t want[MAX_PER_STEP];
        hal_ircom_msg_t got;
        uint8_t n = (uint8_t)(fuzz_u8(&in) % MAX_PER_STEP), kept = 0, k;
        /* Between steps: the driver receives, the main loop polls. */
        for (k = 0; k < n; k++) {
            expect_t e;
            if (!STUB_ROOM()) {
                hal_epuck_poll(&hal);
            }
            if (take(&in, &e)) {
                if (kept < HAL_EPUCK_INBOX) {
                    want[kept++] = e;
                } else {
                    dropped++;
                }
            }
            hal_epuck_poll(&hal);
        }
        hal_epuck_poll(&hal);
        /* A step: the controller reads the inbox. */
        hal_epuck_begin_step(&hal);
        for (k = 0; k < kept; k++) {
            FUZZ_CHECK(hal_ircom_receive(&hal, &got) == HAL_OK);
            check(&got, &want[k]);
        }
        FUZZ_CHECK(hal_ircom_receive(&hal, &got) == HAL_ERR_EMPTY);
        FUZZ_CHECK(hal.in_dropped == dropped);
        hal_epuck_end_step(&hal);
    }
    return 0;
}
