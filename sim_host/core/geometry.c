#include "swarmsim/geometry.h"

#include "units.h"

#define PI_F ((float)UNITS_PI)

float geom_wrap(float angle)
{
    while (angle > PI_F) angle -= 2.0f * PI_F;
    while (angle <= -PI_F) angle += 2.0f * PI_F;
    return angle;
}

cone_t geom_cone(vec2_t p, float angle, float half)
{
    return geom_cone_dir(p, v2(cosf(angle), sinf(angle)), half, cosf(half), sinf(half));
}

cone_t geom_cone_dir(vec2_t p, vec2_t a, float half, float cos_half, float sin_half)
{
    cone_t k;
    k.p = p;
    k.a = a;
    k.half = half;
    k.cos_half = cos_half;
    k.e1 = v2_rot(a, cos_half, sin_half);
    k.e2 = v2_rot(a, cos_half, -sin_half);
    return k;
}

float geom_cone_circle(const cone_t *k, vec2_t c, float r)
{
    vec2_t v = v2_sub(c, k->p);
    float d2 = v2_dot(v, v);
    if (d2 <= r * r) {
        return 0.0f;
    }
    float d = sqrtf(d2);
    float along = v2_dot(v, k->a);
    /* Centre direction inside the cone: the nearest point is straight on. */
    if (along >= d * k->cos_half) {
        return d - r;
    }
    /* Else the nearest in-cone point lies on the edge ray closer to the
     * centre, if that ray meets the circle at all. */
    vec2_t e = (v2_cross(k->a, v) >= 0.0f) ? k->e1 : k->e2;
    float t = v2_dot(v, e);                 /* projection on the edge ray */
    float perp2 = d2 - t * t;               /* squared distance centre-ray */
    if (t <= 0.0f || perp2 > r * r) {
        return INFINITY;
    }
    return t - sqrtf(r * r - perp2);
}

float geom_ray_segment(vec2_t p, vec2_t d, vec2_t a, vec2_t b)
{
    vec2_t s = v2_sub(b, a);
    float den = v2_cross(d, s);
    if (fabsf(den) < 1e-12f) {
        return INFINITY;
    }
    vec2_t ap = v2_sub(a, p);
    float t = v2_cross(ap, s) / den;
    float u = v2_cross(ap, d) / den;
    if (t < 0.0f || u < 0.0f || u > 1.0f) {
        return INFINITY;
    }
    return t;
}

vec2_t geom_closest_on_segment(vec2_t p, vec2_t a, vec2_t b)
{
    vec2_t s = v2_sub(b, a);
    float l2 = v2_dot(s, s);
    float u = (l2 > 0.0f) ? v2_dot(v2_sub(p, a), s) / l2 : 0.0f;
    u = u < 0.0f ? 0.0f : (u > 1.0f ? 1.0f : u);
    return v2_add(a, v2_scale(s, u));
}

static int in_cone(const cone_t *k, vec2_t v, float len)
{
    return v2_dot(v, k->a) >= len * k->cos_half;
}

float geom_cone_segment(const cone_t *k, vec2_t a, vec2_t b)
{
    /* The distance to a segment is convex along it, so the nearest point
     * inside the cone is the global nearest point if that is inside, or
     * else lies on an edge ray or at an endpoint inside the cone. */
    vec2_t q = v2_sub(geom_closest_on_segment(k->p, a, b), k->p);
    float lq = v2_len(q);
    if (lq == 0.0f) {
        return 0.0f;
    }
    if (in_cone(k, q, lq)) {
        return lq;
    }
    float best = fminf(geom_ray_segment(k->p, k->e1, a, b), geom_ray_segment(k->p, k->e2, a, b));
    vec2_t va = v2_sub(a, k->p), vb = v2_sub(b, k->p);
    float la = v2_len(va), lb = v2_len(vb);
    if (in_cone(k, va, la) && la < best) best = la;
    if (in_cone(k, vb, lb) && lb < best) best = lb;
    return best;
}

int geom_segment_hits_circle(vec2_t p, vec2_t q, vec2_t c, float r)
{
    vec2_t n = v2_sub(geom_closest_on_segment(c, p, q), c);
    return v2_dot(n, n) <= r * r;
}

int geom_segments_intersect(vec2_t p, vec2_t q, vec2_t a, vec2_t b)
{
    float d1 = v2_cross(v2_sub(q, p), v2_sub(a, p));
    float d2 = v2_cross(v2_sub(q, p), v2_sub(b, p));
    float d3 = v2_cross(v2_sub(b, a), v2_sub(p, a));
    float d4 = v2_cross(v2_sub(b, a), v2_sub(q, a));
    return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}
