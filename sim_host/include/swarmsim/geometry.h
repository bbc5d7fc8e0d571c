/*
 * geometry.h - 2D distance queries behind the sensor models (metres,
 * radians).  A sensor "cone" is an apex p, a unit axis a and a half-angle;
 * the distance it reports is that of the nearest surface point inside it.
 */
#ifndef SIM_GEOMETRY_H
#define SIM_GEOMETRY_H

#include <math.h>

typedef struct vec2 { float x, y; } vec2_t;

typedef struct cone {
    vec2_t p;          /**< apex */
    vec2_t a;          /**< unit axis */
    float half;        /**< half-angle, rad */
    float cos_half;    /**< cos(half) */
    vec2_t e1, e2;     /**< unit edge directions (axis rotated by +-half) */
} cone_t;

static inline vec2_t v2(float x, float y) { vec2_t v = { x, y }; return v; }
static inline vec2_t v2_sub(vec2_t a, vec2_t b) { return v2(a.x - b.x, a.y - b.y); }
static inline vec2_t v2_add(vec2_t a, vec2_t b) { return v2(a.x + b.x, a.y + b.y); }
static inline vec2_t v2_scale(vec2_t a, float s) { return v2(a.x * s, a.y * s); }
static inline float v2_dot(vec2_t a, vec2_t b) { return a.x * b.x + a.y * b.y; }
static inline float v2_cross(vec2_t a, vec2_t b) { return a.x * b.y - a.y * b.x; }
static inline float v2_len(vec2_t a) { return sqrtf(a.x * a.x + a.y * a.y); }
static inline vec2_t v2_rot(vec2_t a, float c, float s) { return v2(c * a.x - s * a.y, s * a.x + c * a.y); }

/** Wraps an angle to (-pi, pi]. */
float geom_wrap(float angle);

/** A cone at `p` looking along `angle` with half-angle `half`. */
cone_t geom_cone(vec2_t p, float angle, float half);

/** The same from the unit axis `a` and the cosine and sine of the
 *  half-angle (no trigonometry: sensors build 8 cones per robot-step). */
cone_t geom_cone_dir(vec2_t p, vec2_t a, float half, float cos_half, float sin_half);

/** Distance from the apex to the nearest point of the circle (c, r)
 *  inside the cone; INFINITY if none; 0 if the apex is inside. */
float geom_cone_circle(const cone_t *k, vec2_t c, float r);

/** Distance from the apex to the nearest point of segment [a, b] inside
 *  the cone; INFINITY if none. */
float geom_cone_segment(const cone_t *k, vec2_t a, vec2_t b);

/** Distance along the ray p + t*d (d unit) to segment [a, b], or INFINITY. */
float geom_ray_segment(vec2_t p, vec2_t d, vec2_t a, vec2_t b);

/** Whether segment [p, q] passes within r of c. */
int geom_segment_hits_circle(vec2_t p, vec2_t q, vec2_t c, float r);

/** Whether segments [p, q] and [a, b] intersect. */
int geom_segments_intersect(vec2_t p, vec2_t q, vec2_t a, vec2_t b);

/** Closest point to p on segment [a, b]. */
vec2_t geom_closest_on_segment(vec2_t p, vec2_t a, vec2_t b);

#endif
