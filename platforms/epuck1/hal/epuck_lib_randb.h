/*
 * epuck_lib_randb.h - the e-RandB range-and-bearing turret's e-puck driver
 * (e_randb.h of the turret's distribution, I2C mode), user-supplied like
 * the e-puck library (RANDB_DIR, tools/make/firmware.mk).  It talks to the
 * turret over the library's I2C module.  Declarations only.
 *
 * The turret carries 16 data bits per frame, up to about 1 m.
 * e_randb_reception fills the last frame received: its data, the bearing
 * computed on the board in radians, the range in the board's units (we
 * take them as cm: [?] check against a tape measure, the factor is
 * hal_epuck_config_t.randb_range_mm_per_unit) and the turret sensor (0..11)
 * with the strongest signal.  Several calls busy-wait inside the driver
 * (I2C transfers and nop loops of a few ms): platforms/epuck1/hal makes them outside
 * the controller's step.
 */
#ifndef EPUCK_LIB_RANDB_H
#define EPUCK_LIB_RANDB_H

/* e_randb.h: one received frame.  Layout as in the driver (16-bit
 * unsigned int and 32-bit float on XC16). */
typedef struct {
    unsigned int data;
    float bearing;
    unsigned int range;
    unsigned int max_peak;
    unsigned char max_sensor;
} finalDataRegister;

/* e_randb.h: mode of e_init_randb: the turret on the I2C bus. */
#define EPL_RANDB_I2C 0
/* e_randb.h: value of e_randb_set_calculation: range and bearing computed
 * on the turret's own processor. */
#define EPL_RANDB_ON_BOARD 0

void e_init_randb(unsigned char mode);
/* 0 = full range (about 1 m) .. 255 = shortest. */
void e_randb_set_range(unsigned char distance);
void e_randb_set_calculation(unsigned char value);
/* Measures the ambient IR as the offset of later range/bearing estimates. */
void e_randb_store_light_conditions(void);
/* Returns 1 and fills *data when a frame was received since the last call. */
unsigned char e_randb_reception(finalDataRegister *data);
/* Sends 16 data bits through all the turret's emitters. */
void e_randb_send_all_data(unsigned int data);

#endif
