/*
 * epuck_lib_i2c.h - the e-puck library's I2C protocol functions
 * (I2C/e_I2C_protocol.h, linked in every image with the camera's driver)
 * that hal/epuck uses to read the ground-sensor module.  Declared as
 * epuck_lib.h declares the rest (the library's own types).
 *
 * e_i2cp_read retries until the device answers: it hangs on a robot
 * without the device, which is why the module is declared by the image
 * (hal_epuck_config_t.ground), never probed.
 */
#ifndef EPUCK_LIB_I2C_H
#define EPUCK_LIB_I2C_H

void e_i2cp_init(void);
void e_i2cp_enable(void);
void e_i2cp_disable(void);
/* Register `reg` of the device at 8-bit address `device_add`. */
char e_i2cp_read(char device_add, char reg);

/** The ground-sensor module's I2C address (GCtronic's advanced sercom
 *  reads it at 0xC0: registers 0..5 are the three sensors' values, high
 *  byte first). */
#define EPL_GROUND_I2C_ADDRESS 0xC0u

#endif
