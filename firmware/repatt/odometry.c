#include "odometry.h"

#include "units.h"

/* sin over a quarter turn in 64 parts, Q14. */
static const int16_t sin_table[65] = {
    0, 402, 804, 1205, 1606, 2006, 2404, 2801, 3196, 3590, 3981, 4370, 4756, 5139, 5520, 5897,
    6270, 6639, 7005, 7366, 7723, 8076, 8423, 8765, 9102, 9434, 9760, 10080, 10394, 10702, 11003,
    11297, 11585, 11866, 12140, 12406, 12665, 12916, 13160, 13395, 13623, 13842, 14053, 14256,
    14449, 14635, 14811, 14978, 15137, 15286, 15426, 15557, 15679, 15791, 15893, 15986, 16069,
    16143, 16207, 16261, 16305, 16340, 16364, 16379, 16384
};

/* Turning by d = right - left steps turns the robot by d x 0.12881 mm /
 * 53 mm = d x 2430.29 urad (hal/units.h's wheel and axle). */
#define URAD_PER_DSTEP_X100 243029L
/* Travel of the centre per (left + right) steps: 0.12881 / 2 mm = 64.403 um. */
#define UM_PER_SSTEP_X1000 64403L
#define PI_URAD 3141593L
#define TWO_PI_URAD 6283185L

int32_t odo_wrap_mrad(int32_t mrad)
{
    mrad %= UNITS_TWO_PI_MRAD;
    if (mrad > UNITS_PI_MRAD) {
        mrad -= UNITS_TWO_PI_MRAD;
    } else if (mrad <= -UNITS_PI_MRAD) {
        mrad += UNITS_TWO_PI_MRAD;
    }
    return mrad;
}

/* sin of a quarter-turn fraction w in [0, 16384]. */
static int16_t quarter_sin(int32_t w)
{
    int32_t i = w >> 8;
    int32_t frac = w & 0xFF;
    if (i >= 64) {
        return sin_table[64];
    }
    return (int16_t)(sin_table[i] + ((int32_t)(sin_table[i + 1] - sin_table[i]) * frac) / 256);
}

/* A 16-bit binary angle of `mrad`: 65536 to the turn. */
static int32_t binary_angle(int32_t mrad)
{
    int32_t m = mrad % UNITS_TWO_PI_MRAD;
    if (m < 0) {
        m += UNITS_TWO_PI_MRAD;
    }
    return (m * 65536L) / UNITS_TWO_PI_MRAD;   /* < 6283 x 65536 < 2^31 */
}

static int16_t sin_binary(int32_t bam)
{
    int32_t w = bam & 0x3FFF;
    switch ((bam >> 14) & 3) {
    case 0: return quarter_sin(w);
    case 1: return quarter_sin(16384 - w);
    case 2: return (int16_t)-quarter_sin(w);
    default: return (int16_t)-quarter_sin(16384 - w);
    }
}

int16_t odo_sin_q14(int32_t mrad)
{
    return sin_binary(binary_angle(mrad));
}

int16_t odo_cos_q14(int32_t mrad)
{
    return sin_binary(binary_angle(mrad) + 16384L);   /* a quarter turn on */
}

int16_t odo_atan2_mrad(int32_t y, int32_t x)
{
    uint32_t ax = (x < 0) ? (uint32_t)0 - (uint32_t)x : (uint32_t)x;
    uint32_t ay = (y < 0) ? (uint32_t)0 - (uint32_t)y : (uint32_t)y;
    uint32_t lo, hi;
    int32_t z, a;
    if (ax == 0u && ay == 0u) {
        return 0;
    }
    lo = (ax < ay) ? ax : ay;
    hi = (ax < ay) ? ay : ax;
    while (hi >= 0x10000UL) {   /* lo / hi in Q14 without overflow */
        hi >>= 1;
        lo >>= 1;
    }
    z = (int32_t)((lo * 16384UL) / hi);
    /* atan z ~ z (pi/4 + 0.273 (1 - z)) on [0, 1], within 4 mrad
     * (Rajan et al.): in urad / 16, then mrad. */
    a = (z * ((1058398L - (z * 16663L) / 1000L) / 16L)) / 1024L;   /* urad; 273000 / 16384 = 16.663 */
    a = (a + 500L) / 1000L;
    if (ay > ax) {
        a = UNITS_HALF_PI_MRAD - a;
    }
    if (x < 0) {
        a = UNITS_PI_MRAD - a;
    }
    if (y < 0) {
        a = -a;
    }
    return (int16_t)odo_wrap_mrad(a);
}

void odometry_reset(odometry_t *o)
{
    o->x_um = 0;
    o->y_um = 0;
    o->heading_urad = 0;
    o->last_left = 0;
    o->last_right = 0;
    o->primed = 0u;
}

int16_t odo_counter_delta(int16_t now, int16_t last)
{
    int32_t d = (int32_t)now - (int32_t)last;
    if (d > 32767L) {
        d -= 65536L;
    } else if (d < -32768L) {
        d += 65536L;
    }
    if (d > ODO_MAX_STEP_DELTA) {
        d = ODO_MAX_STEP_DELTA;
    } else if (d < -ODO_MAX_STEP_DELTA) {
        d = -ODO_MAX_STEP_DELTA;
    }
    return (int16_t)d;
}

static int32_t clamp_um(int64_t v)
{
    if (v > ODO_LIMIT_UM) {
        return ODO_LIMIT_UM;
    }
    if (v < -ODO_LIMIT_UM) {
        return -ODO_LIMIT_UM;
    }
    return (int32_t)v;
}

void odometry_update(odometry_t *o, int16_t left, int16_t right, int16_t *d_left, int16_t *d_right)
{
    int16_t dl = 0, dr = 0;
    int32_t dtheta, mid_mrad, ds_um;
    if (o->primed != 0u) {
        dl = odo_counter_delta(left, o->last_left);
        dr = odo_counter_delta(right, o->last_right);
    }
    o->primed = 1u;
    o->last_left = left;
    o->last_right = right;
    *d_left = dl;
    *d_right = dr;
    if (dl == 0 && dr == 0) {
        return;
    }
    /* |dr - dl| <= 8000: 8000 x 243029 < 2^31. */
    dtheta = ((int32_t)(dr - dl) * URAD_PER_DSTEP_X100) / 100L;
    ds_um = ((int32_t)(dl + dr) * UM_PER_SSTEP_X1000) / 1000L;
    /* Along the mean heading of the period (exact for an arc's chord
     * direction). */
    mid_mrad = (o->heading_urad + dtheta / 2L) / 1000L;
    o->x_um = clamp_um((int64_t)o->x_um + ((int64_t)ds_um * odo_cos_q14(mid_mrad)) / 16384);
    o->y_um = clamp_um((int64_t)o->y_um + ((int64_t)ds_um * odo_sin_q14(mid_mrad)) / 16384);
    o->heading_urad += dtheta;   /* |heading| <= pi + 19.5 rad: no overflow */
    while (o->heading_urad > PI_URAD) {
        o->heading_urad -= TWO_PI_URAD;
    }
    while (o->heading_urad <= -PI_URAD) {
        o->heading_urad += TWO_PI_URAD;
    }
}

int16_t odometry_home_bearing_mrad(const odometry_t *o)
{
    int32_t to_home;
    if (o->x_um == 0 && o->y_um == 0) {
        return 0;
    }
    to_home = odo_atan2_mrad(-o->y_um, -o->x_um);
    return (int16_t)odo_wrap_mrad(to_home - o->heading_urad / 1000L);
}

uint8_t odometry_within_mm(const odometry_t *o, uint16_t radius_mm)
{
    int32_t x = o->x_um / 1000L;
    int32_t y = o->y_um / 1000L;
    int32_t r = (int32_t)radius_mm;
    if (x > r || x < -r || y > r || y < -r) {
        return 0u;
    }
    return (uint8_t)((uint64_t)((int64_t)x * x) + (uint64_t)((int64_t)y * y) <= (uint64_t)r * (uint64_t)r);
}
