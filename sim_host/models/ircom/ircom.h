/*
 * ircom.h - IR local communication between robots (section `ircom`): what
 * a robot sends with hal_ircom_send reaches the robots in range and line of
 * sight, with loss, an estimated bearing and range, and, optionally, the
 * turret's rate, collisions and seed 003's direction noise (ircom.c says
 * how).  Tasks may stand in for a robot: sim_ircom_inject (sim.h).
 */
#ifndef SIM_MODELS_IRCOM_H
#define SIM_MODELS_IRCOM_H

#include <stdint.h>

#include "models/model.h"

/** Most messages a robot may send per control period (ircom.tx_per_period). */
#define IRCOM_TX_MAX 16u
/** Largest receive queue (ircom.queue). */
#define IRCOM_QUEUE_MAX 64u

typedef struct ircom_config {
    float range;               /**< centre-to-centre reach, m */
    float loss;                /**< probability a message is lost */
    float bearing_noise;       /**< Gaussian sd added to the bearing, deg */
    float range_noise_rel;     /**< relative Gaussian sd of the range */
    uint8_t quantise_bearing;  /**< report the receiving sensor's bearing */
    uint8_t blocked_by_robots; /**< robots also block line of sight */
    uint8_t payload_bits;      /**< 8 (libIrcom) or 16 (range-and-bearing turret) */
    float bearing_noise_vec;   /**< seed 003's direction noise: sd of the length of a
                                    random vector (uniform azimuth) added to the
                                    vector between the robots, m; 0 = none */
    uint8_t tx_per_period;     /**< messages hal_ircom_send accepts per control period */
    uint16_t slots;            /**< collision model: frame times per period (a frame
                                    lands in a random one; two or more in one slot at
                                    a receiver are all lost); 0 = no collisions */
    uint8_t queue;             /**< messages a receiver's inbox holds */
} ircom_config_t;

MODEL_CONFIG_ACCESSORS(ircom, ircom_config_t)

/** This step robot `robot` sends `value` alone (masked to the payload),
 *  whatever its controller queued: a faulty robot's message (faults.c). */
void ircom_set_outgoing(sim_t *sim, uint32_t robot, uint16_t value);

#endif
