/*
 * route_msg.h - a robot's route as a host message (hal_host_receive): the
 * targets to pick up, in order, then the drop-off point, as a planner on a
 * PC gives them (seed 002's ALNS baseline; firmware/waypoint/waypoint.h).
 *
 * Payload, big-endian (the order a host writes with struct.pack('>...')):
 *   [0]      0x52 ('R'), the kind
 *   [1]      n, targets in the route, 1..ROUTE_MAX_TARGETS
 *   then n pairs (x_mm int32, y_mm int32), the targets in pick-up order,
 *   then one pair (x_mm int32, y_mm int32), the drop-off point.
 * Length exactly ROUTE_MSG_LEN(n) = 2 + 8 (n + 1): 58 bytes at most, within
 * HAL_HOST_MSG_MAX.  Coordinates are in the tracker's arena frame (the
 * frame of hal_pose: origin at the arena's centre, x right, y up) and lie
 * within +-ROUTE_COORD_MAX_MM.
 *
 * The decoder is strict: anything else is refused with an error naming
 * what is wrong, and the route it was given is left as it was.
 */
#ifndef FW_ROUTE_MSG_H
#define FW_ROUTE_MSG_H

#include <stdint.h>

/** The kind byte of a route message ('R'). */
#define ROUTE_MSG_KIND 0x52u
/** Most targets in one route (a robot's capacity in seed 002's plan). */
#define ROUTE_MAX_TARGETS 6u
/** Bytes of a route message with `n` targets. */
#define ROUTE_MSG_LEN(n) (2u + 8u * ((uint8_t)(n) + 1u))
/** The longest route message (6 targets): 58 bytes. */
#define ROUTE_MSG_MAX_LEN ROUTE_MSG_LEN(ROUTE_MAX_TARGETS)
/** Largest coordinate magnitude accepted, mm (1 km: seed 002's largest
 *  world is 100 m across).  Bounded so that the controller's differences
 *  and squared distances cannot overflow. */
#define ROUTE_COORD_MAX_MM 1000000L

/** What decoding a message gave: OK, or why it was refused. */
typedef enum route_msg_status {
    ROUTE_MSG_OK = 0,
    ROUTE_MSG_ERR_LENGTH = -1,   /**< not 2 + 8 (n + 1) bytes (or too short to say) */
    ROUTE_MSG_ERR_KIND = -2,     /**< the first byte is not ROUTE_MSG_KIND */
    ROUTE_MSG_ERR_COUNT = -3,    /**< n is 0 or above ROUTE_MAX_TARGETS */
    ROUTE_MSG_ERR_COORD = -4     /**< a coordinate beyond +-ROUTE_COORD_MAX_MM */
} route_msg_status_t;

/** A point of the arena frame, mm. */
typedef struct route_point {
    int32_t x_mm;
    int32_t y_mm;
} route_point_t;

typedef struct route {
    uint8_t n;                                  /**< targets, 1..ROUTE_MAX_TARGETS */
    route_point_t target[ROUTE_MAX_TARGETS];    /**< in pick-up order */
    route_point_t drop;                         /**< the drop-off point */
} route_t;

/** Decodes `len` bytes of `buf` into *out: ROUTE_MSG_OK, or a
 *  ROUTE_MSG_ERR_* (checked in this order: length to read the header, kind,
 *  count, exact length, coordinates), with *out untouched. */
int8_t route_msg_decode(const uint8_t *buf, uint8_t len, route_t *out);

/** Writes `route` into `buf` (room for `cap` bytes): its length, or 0 when
 *  its n is out of range, a coordinate is, or it does not fit. */
uint8_t route_msg_encode(const route_t *route, uint8_t *buf, uint8_t cap);

#endif
