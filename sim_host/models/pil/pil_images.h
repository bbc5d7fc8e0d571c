/*
 * pil_images.h - the robot images a simulator group can run (`image:`):
 * the e-puck1's declarations (platforms/epuck1/images.list), each one's
 * parameters made as its run loop makes them, and its seed rule.  The table
 * is generated from the declarations by tools/make/images.py host-list
 * (build/gen/pil_image_list.h), with the build's constants, so a group
 * that runs an image runs what the robot and the emulated MCU run, whether
 * host-built or on the MCU (pil.h).
 */
#ifndef SIM_PIL_IMAGES_H
#define SIM_PIL_IMAGES_H

#include <stddef.h>
#include <stdint.h>

/** The controller's seed (images.py's `seed`). */
typedef enum pil_seed_rule {
    PIL_SEED_RANDOM = 0,   /**< the simulator's per-robot stream, as every host-built robot's */
    PIL_SEED_ID = 1,       /**< the robot id */
    PIL_SEED_ZERO = 2
} pil_seed_rule_t;

typedef struct pil_image {
    const char *name;
    const char *controller;          /**< its controller's registered name */
    size_t params_size;              /**< sizeof its NAME_params_t */
    /** Its parameters into `params`: the controller's defaults, the policy
     *  the selector switch at `selector` picks (or its policy), then its
     *  `param` lines. */
    void (*params)(void *params, uint8_t selector);
    uint8_t seed;                    /**< pil_seed_rule_t */
    const char *where;               /**< its declaration, file:line */
} pil_image_t;

/** The image named `name`, or NULL. */
const pil_image_t *pil_image_find(const char *name);

/** The i-th image (NULL past the last): for lists in errors. */
const pil_image_t *pil_image_at(size_t i);

#endif
