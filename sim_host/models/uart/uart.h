/*
 * uart.h - the robot's serial port, for software in the loop of the robots'
 * own telemetry (section `robot_telemetry`): every robot runs the image's
 * sender (firmware/telemetry/robot_telemetry.c) after its controller's step,
 * its bytes go down a simulated UART of `baud` bits/s (8N1: ten bits a
 * byte; what does not fit waits in the sender), and the simulator
 * republishes the frames as the serial bridge does (telemetry.c).  Off by
 * default: hal_telemetry_write then accepts every byte and drops it (the
 * simulator publishes from its own view).
 */
#ifndef SIM_MODELS_UART_H
#define SIM_MODELS_UART_H

#include <stdint.h>

#include "models/model.h"

typedef struct uart_config {
    uint8_t enabled;           /**< every robot runs the image's telemetry sender */
    char channel_prefix[16];   /**< before the channel names ("FW_": FW_ROBOT_STATE) */
    uint32_t baud;             /**< the UART's rate, bits/s (0: unlimited) */
    uint8_t dump;              /**< also write each robot's raw bytes (uart/robot_<id>.bin) */
} uart_config_t;

MODEL_CONFIG_ACCESSORS(uart, uart_config_t)

#endif
