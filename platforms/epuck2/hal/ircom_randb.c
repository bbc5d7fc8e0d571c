/*
 * ircom_randb.c - IR backend of the images with the range-and-bearing
 * turret (16-bit messages, ~1 m), which the e-puck2 drives over its I2C
 * bus (i2c_bus.h) as the library's own turret demo does (src/main.c,
 * selector 4): the turret at address 0x20, its registers
 *   0      non-zero when a frame has been received
 *   1, 2   its 16 data bits, high byte first (reading them takes the frame)
 *   3, 4   its bearing, 0.0001 rad units, high byte first
 *   5, 6   its range, the turret's units, high byte first
 *   9      the turret sensor (0..11) that heard it best
 *   12     the emission range (write; 0 = full)
 *   13, 14 the data bits to send, high then low (writing 14 sends)
 *   16     store the light conditions (write)
 *   17     where range and bearing are computed (write 0: on the turret).
 * Proximity and light come from the library's proximity module at its
 * slow rate (20 Hz), the rate the library's demo runs beside the turret
 * to keep the IR sensors' pulses out of its receivers.
 *
 * Bearings: counter-clockwise positive with 0 ahead [?] (check: a sender
 * on the robot's left must give a positive bearing).  Range: the turret's
 * units times cfg.randb_range_mm_per_unit (10: taken as cm [?]).  Each
 * I2C transfer takes bus time (~0.1 ms at 400 kHz [?]); the reception
 * check is one read per poll, a frame seven more.
 */
#include "hal_epuck2.h"

#include "epuck2_lib.h"

#define RANDB_ADDR 0x20u
#define REG_RX_READY 0u
#define REG_DATA_HI 1u
#define REG_BEARING_HI 3u
#define REG_RANGE_HI 5u
#define REG_SENSOR 9u
#define REG_SET_RANGE 12u
#define REG_TX_HI 13u
#define REG_TX_LO 14u
#define REG_STORE_LIGHT 16u
#define REG_CALCULATION 17u
#define CALCULATION_ON_BOARD 0u
/* read_reg's and write_reg's msg_t for success. */
#define I2C_OK 0

/* Two registers, high byte first: 1 and *out, or 0 on a bus error. */
static uint8_t read_u16(uint8_t reg, uint16_t *out)
{
    uint8_t hi = 0u, lo = 0u;
    if (read_reg(RANDB_ADDR, reg, &hi) != I2C_OK || read_reg(RANDB_ADDR, (uint8_t)(reg + 1u), &lo) != I2C_OK) {
        return 0u;
    }
    *out = (uint16_t)(((uint16_t)hi << 8) | lo);
    return 1u;
}

void hal_epuck2_ir_start(hal_t *hal)
{
    proximity_start(EPUCK2_PROX_SLOW_UPDATE);
    calibrate_ir();
    (void)write_reg(RANDB_ADDR, REG_SET_RANGE, hal->cfg.randb_range);
    (void)write_reg(RANDB_ADDR, REG_CALCULATION, CALCULATION_ON_BOARD);
    (void)write_reg(RANDB_ADDR, REG_STORE_LIGHT, 0u);
}

void hal_epuck2_ir_sample(hal_t *hal)
{
    uint8_t i;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        hal->prox[i] = hal_epuck2_clamp_raw(get_calibrated_prox(i));
        hal->ambient[i] = hal_epuck2_clamp_raw(get_ambient_light(i));
    }
}

void hal_epuck2_ir_poll(hal_t *hal)
{
    uint8_t ready = 0u;
    uint16_t data, bearing, range;
    uint32_t mm;
    hal_ircom_msg_t m;
    if (read_reg(RANDB_ADDR, REG_RX_READY, &ready) != I2C_OK || ready == 0u) {
        return;
    }
    if (read_u16(REG_DATA_HI, &data) == 0u || read_u16(REG_BEARING_HI, &bearing) == 0u
        || read_u16(REG_RANGE_HI, &range) == 0u) {
        return;   /* a bus error: the frame is lost */
    }
    m.value = data;
    /* 0.0001 rad units: mrad = units / 10, rounded. */
    m.bearing_mrad = hal_epuck2_wrap_mrad(((int32_t)bearing + 5) / 10);
    m.sensor = hal_epuck2_nearest_sensor(m.bearing_mrad);
    mm = (uint32_t)range * hal->cfg.randb_range_mm_per_unit;
    m.range_mm = mm > 0xFFFEu ? (uint16_t)0xFFFEu : (uint16_t)mm;
    (void)hal_epuck2_inbox_push(hal, &m);
}

void hal_epuck2_ir_transmit(hal_t *hal, uint16_t value)
{
    (void)hal;
    (void)write_reg(RANDB_ADDR, REG_TX_HI, (uint8_t)(value >> 8));
    (void)write_reg(RANDB_ADDR, REG_TX_LO, (uint8_t)value);
}

uint8_t hal_ircom_payload_bits(hal_t *hal)
{
    (void)hal;
    return 16u;
}
