/*
 * nnea.c - the evolved CTRNN of seed 003's baseline NNEA (nnea.h): sense,
 * one network step in fixed point, act.
 */
#include "nnea/nnea.h"

#include <string.h>

#include "nnea/nnea_evolved.h"

/* sigma(-8 + k/4) in Q12, k = 0..64. */
static const int16_t sigmoid_q12[65] = {
    1, 2, 2, 3, 4, 5, 6, 8, 10, 13, 17, 21, 27, 35, 45, 58, 74, 94, 120, 153, 194, 246,
    311, 391, 488, 606, 747, 912, 1102, 1314, 1546, 1793, 2048, 2303, 2550, 2782, 2994,
    3184, 3349, 3490, 3608, 3705, 3785, 3850, 3902, 3943, 3976, 4002, 4022, 4038, 4051,
    4061, 4069, 4075, 4079, 4083, 4086, 4088, 4090, 4091, 4092, 4093, 4094, 4094, 4095
};

/* Sector of a bearing (mrad, CCW, 0 ahead): 0 front-left, 1 back-left,
 * 2 back-right, 3 front-right. */
#define HALF_PI_MRAD 1571

/* The logistic's table spans [-SIG_SPAN, SIG_SPAN], Q12 (int32: 16-bit int
 * cannot hold 8 x 4096). */
#define SIG_SPAN ((int32_t)8 * NNEA_ONE)

/* Input slots. */
#define IN_IR 0u        /* 4: front, right, back, left */
#define IN_GROUND 4u    /* 2: nest, food */
#define IN_PEERS 6u     /* 8: colour * 4 + sector */

static const char *const nnea_state_names[] = { "run", "source" };

void nnea_default_params(nnea_params_t *params)
{
    static const int16_t w_in[] = NNEA_EVOLVED_W_IN;
    static const int16_t w_rec[] = NNEA_EVOLVED_W_REC;
    static const int16_t b_hidden[] = NNEA_EVOLVED_B_HIDDEN;
    static const uint8_t tau[] = NNEA_EVOLVED_TAU;
    static const int16_t w_out[] = NNEA_EVOLVED_W_OUT;
    static const int16_t b_out[] = NNEA_EVOLVED_B_OUT;
    /* The evolved genome's shape must be the network's (a build error if not). */
    typedef char w_in_fits[sizeof w_in == sizeof params->w_in ? 1 : -1];
    typedef char w_rec_fits[sizeof w_rec == sizeof params->w_rec ? 1 : -1];
    typedef char b_hidden_fits[sizeof b_hidden == sizeof params->b_hidden ? 1 : -1];
    typedef char tau_fits[sizeof tau == sizeof params->tau ? 1 : -1];
    typedef char w_out_fits[sizeof w_out == sizeof params->w_out ? 1 : -1];
    typedef char b_out_fits[sizeof b_out == sizeof params->b_out ? 1 : -1];
    memset(params, 0, sizeof *params);
    memcpy(params->w_in, w_in, sizeof w_in);
    memcpy(params->w_rec, w_rec, sizeof w_rec);
    memcpy(params->b_hidden, b_hidden, sizeof b_hidden);
    memcpy(params->tau, tau, sizeof tau);
    memcpy(params->w_out, w_out, sizeof w_out);
    memcpy(params->b_out, b_out, sizeof b_out);
    params->speed_steps_s = 388u;    /* 5 cm/s: seed 003's speed (Table 2) */
    params->stop_band = 205;         /* 0.05 of Q12 each side of 1/2 */
    params->sense_range_mm = 600u;   /* R: the turret's range in seed 003 */
    params->ir_full = 2000u;
    params->ground_dark_max = 250u;  /* black ~0, grey 0.5 ~500, white ~1000 counts */
    params->ground_grey_max = 750u;  /* white's noise (sd 10 %) dips below now and then: see sense_floor */
    params->role = NNEA_ROLE_ROBOT;
    (void)sizeof(w_in_fits); (void)sizeof(w_rec_fits); (void)sizeof(b_hidden_fits);
    (void)sizeof(tau_fits); (void)sizeof(w_out_fits); (void)sizeof(b_out_fits);
}

void nnea_reset(nnea_t *self)
{
    self->state = self->params.role == NNEA_ROLE_ROBOT ? NNEA_RUN : NNEA_SOURCE;
    self->colour = 0;
    self->area = 0;
    self->last_area = 0;
    self->trips = 0;
    memset(self->input, 0, sizeof self->input);
    memset(self->hidden, 0, sizeof self->hidden);
    memset(self->output, 0, sizeof self->output);
}

void nnea_init(nnea_t *self, const nnea_params_t *params, uint32_t seed)
{
    self->params = *params;
    self->seed = seed;
    nnea_reset(self);
}

const char *nnea_state_name(const nnea_t *self)
{
    return nnea_state_names[self->state <= NNEA_SOURCE ? self->state : 0];
}

int16_t nnea_sigmoid(int32_t x_q12)
{
    int32_t u, k, frac;
    if (x_q12 <= -SIG_SPAN) {
        return sigmoid_q12[0];
    }
    if (x_q12 >= SIG_SPAN) {
        return sigmoid_q12[64];
    }
    u = x_q12 + SIG_SPAN;             /* 0 .. 65535: a quarter is 1024 */
    k = u / 1024;
    frac = u % 1024;
    return (int16_t)(sigmoid_q12[k] + ((int32_t)(sigmoid_q12[k + 1] - sigmoid_q12[k]) * frac) / 1024);
}

static int16_t q12_of(uint16_t value, uint16_t full)
{
    uint32_t v = value < full ? value : full;
    return (int16_t)(full > 0u ? (v * (uint32_t)NNEA_ONE) / full : 0);
}

static uint16_t max_u16(uint16_t a, uint16_t b)
{
    return a > b ? a : b;
}

/* Obstacle sectors from the 8 IR sensors (0, 7 ahead; 1, 2 right; 3, 4
 * behind; 5, 6 left). */
static void sense_obstacles(nnea_t *self, hal_t *hal)
{
    uint16_t p[HAL_IR_COUNT];
    uint8_t i;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        p[i] = hal_ir_proximity(hal, i);
    }
    self->input[IN_IR + 0u] = q12_of(max_u16(p[0], p[7]), self->params.ir_full);
    self->input[IN_IR + 1u] = q12_of(max_u16(p[1], p[2]), self->params.ir_full);
    self->input[IN_IR + 2u] = q12_of(max_u16(p[3], p[4]), self->params.ir_full);
    self->input[IN_IR + 3u] = q12_of(max_u16(p[5], p[6]), self->params.ir_full);
}

/* The floor under the three ground sensors: the nest's black disc or the
 * food's grey one when all three read it (one sensor's noise on the white
 * floor can dip into the grey band; three at once do not), else neither;
 * counts a trip on entering the area other than the one last visited. */
static uint8_t area_of(const nnea_params_t *p, uint16_t g)
{
    return g < p->ground_dark_max ? 1u : g < p->ground_grey_max ? 2u : 0u;
}

static void sense_floor(nnea_t *self, hal_t *hal)
{
    uint16_t g = 0;
    uint8_t area = 0, i;
    for (i = 0; i < HAL_GROUND_COUNT; i++) {
        uint8_t a;
        if (hal_ground(hal, i, &g) != HAL_OK) {
            area = 0;
            break;
        }
        a = area_of(&self->params, g);
        if (i > 0u && a != area) {
            area = 0;
            break;
        }
        area = a;
    }
    self->input[IN_GROUND + 0u] = area == 1u ? NNEA_ONE : 0;
    self->input[IN_GROUND + 1u] = area == 2u ? NNEA_ONE : 0;
    if (area != 0u && area != self->last_area) {
        if (self->last_area != 0u) {
            self->trips++;
        }
        self->last_area = area;
    }
    self->area = area;
}

/* Neighbours' colours by sector, each the strongest (nearest) heard. */
static void sense_peers(nnea_t *self, hal_t *hal)
{
    hal_ircom_msg_t m;
    uint8_t i;
    for (i = 0; i < 8u; i++) {
        self->input[IN_PEERS + i] = 0;
    }
    while (hal_ircom_receive(hal, &m) == HAL_OK) {
        uint8_t sector, slot;
        int16_t strength;
        uint16_t range = self->params.sense_range_mm;
        if ((m.value & NNEA_MSG_MASK) != NNEA_MSG_TAG || range == 0u) {
            continue;
        }
        sector = m.bearing_mrad >= 0 ? (m.bearing_mrad < HALF_PI_MRAD ? 0u : 1u)
                                     : (m.bearing_mrad < -HALF_PI_MRAD ? 2u : 3u);
        strength = m.range_mm >= range ? 0
                   : (int16_t)(((uint32_t)(range - m.range_mm) * (uint32_t)NNEA_ONE) / range);
        slot = (uint8_t)(IN_PEERS + (m.value & 1u) * 4u + sector);
        if (strength > self->input[slot]) {
            self->input[slot] = strength;
        }
    }
}

/* One network step: hidden leaky integrators (reading the last step's
 * hidden activations), then the outputs. */
static void network_step(nnea_t *self)
{
    const nnea_params_t *p = &self->params;
    int16_t before[NNEA_HIDDEN];
    uint8_t i, j, k;
    memcpy(before, self->hidden, sizeof before);
    for (i = 0; i < NNEA_HIDDEN; i++) {
        int32_t acc = (int32_t)p->b_hidden[i] * NNEA_ONE;          /* Q8 x Q12 = Q20 */
        int32_t tau = p->tau[i], s;
        for (j = 0; j < NNEA_INPUTS; j++) {
            acc += (int32_t)p->w_in[i * NNEA_INPUTS + j] * self->input[j];
        }
        for (j = 0; j < NNEA_HIDDEN; j++) {
            acc += (int32_t)p->w_rec[i * NNEA_HIDDEN + j] * before[j];
        }
        s = nnea_sigmoid(acc / 256);                               /* Q20 -> Q12 */
        self->hidden[i] = (int16_t)((tau * before[i] + (256 - tau) * s) / 256);
    }
    for (k = 0; k < NNEA_OUTPUTS; k++) {
        int32_t acc = (int32_t)p->b_out[k] * NNEA_ONE;
        for (i = 0; i < NNEA_HIDDEN; i++) {
            acc += (int32_t)p->w_out[k * NNEA_HIDDEN + i] * self->hidden[i];
        }
        self->output[k] = nnea_sigmoid(acc / 256);
    }
}

/* Output o (Q12) as a wheel speed: (2 o - 1) of the top speed, 0 within
 * the stop band around 1/2 (a robot can stand still, and so be a node of
 * a chain as the paths task counts one). */
static int16_t wheel_of(const nnea_params_t *p, int16_t o)
{
    int32_t centred = (int32_t)o * 2 - NNEA_ONE;   /* -4096 .. 4096 */
    int32_t band = (int32_t)p->stop_band * 2;
    if (centred > -band && centred < band) {
        return 0;
    }
    return (int16_t)((centred * (int32_t)p->speed_steps_s) / NNEA_ONE);
}

void nnea_step(nnea_t *self, hal_t *hal)
{
    switch (self->state) {
    case NNEA_SOURCE:
        hal_set_wheel_speeds(hal, 0, 0);
        hal_set_body_led(hal, 1u);
        break;
    case NNEA_RUN:
    default:
        sense_obstacles(self, hal);
        sense_floor(self, hal);
        sense_peers(self, hal);
        network_step(self);
        self->colour = self->output[2] > NNEA_ONE / 2 ? 1u : 0u;
        hal_set_wheel_speeds(hal, wheel_of(&self->params, self->output[0]),
                             wheel_of(&self->params, self->output[1]));
        hal_set_front_led(hal, self->colour);
        (void)hal_ircom_send(hal, (uint16_t)(NNEA_MSG_TAG | self->colour));
        break;
    }
}
