/*
 * per_robot.h - a model's parameters fitted to one robot (the calibration
 * kit: tools/swarmtools/calibrate, docs/how-to/calibrate.md).  A model
 * whose section takes them has a `robots:` sequence there, one entry per
 * robot id with the keys it fitted; a robot whose hal_robot_id has no entry
 * takes the section's own keys (the lab's average, in a fragment the kit
 * wrote).  An entry's key left out (NaN, or no `sensors:`) is the
 * section's.
 *
 * Ids can change after a run is made (sim_set_robot_id: a fake e-puck
 * takes the id it was flashed with), so a model resolves a robot's entry
 * when it first needs it and again whenever the id differs from the one
 * it resolved (per_robot_cache_t), on the thread that steps the robot.
 */
#ifndef SIM_MODELS_PER_ROBOT_H
#define SIM_MODELS_PER_ROBOT_H

#include <stddef.h>
#include <stdint.h>

/** Most robots one section lists. */
#define PER_ROBOT_MAX 1024u

/** What a robot's entry was resolved for (8 bytes a robot: a swarm of
 *  100,000 pays 0.8 MB a section). */
typedef struct per_robot_cache {
    int32_t id;            /**< the id it was resolved for; -1: not yet */
    int32_t index;         /**< its entry's, or -1: the section's keys */
} per_robot_cache_t;

/** The index of robot `id`'s entry in `count` entries of `size` bytes whose
 *  uint16_t id is at `id_offset`, or -1. */
static inline int32_t per_robot_find(const void *entries, uint32_t count, size_t size, size_t id_offset,
                                     uint16_t id)
{
    const uint8_t *p = entries;
    for (uint32_t k = 0; k < count; k++, p += size) {
        if (*(const uint16_t *)(const void *)(p + id_offset) == id) {
            return (int32_t)k;
        }
    }
    return -1;
}

/** Robot `id`'s entry through `cache` (resolved again when the id changed). */
static inline const void *per_robot_entry(per_robot_cache_t *cache, const void *entries, uint32_t count,
                                          size_t size, size_t id_offset, uint16_t id)
{
    if (cache->id != (int32_t)id) {
        cache->index = count > 0 ? per_robot_find(entries, count, size, id_offset, id) : -1;
        cache->id = (int32_t)id;
    }
    return cache->index < 0 ? NULL : (const uint8_t *)entries + (size_t)cache->index * size;
}

/** The index of the first entry whose id repeats an earlier one's, or -1
 *  (a model's check: one entry per robot). */
static inline int32_t per_robot_duplicate(const void *entries, uint32_t count, size_t size, size_t id_offset)
{
    const uint8_t *p = entries;
    for (uint32_t k = 1; k < count; k++) {
        uint16_t id = *(const uint16_t *)(const void *)(p + k * size + id_offset);
        if (per_robot_find(entries, k, size, id_offset, id) >= 0) {
            return (int32_t)k;
        }
    }
    return -1;
}

#endif
