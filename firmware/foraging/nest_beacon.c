#include "nest_beacon.h"

/* Milliseconds per minute: the consumption rate is per minute. */
#define MS_PER_MIN 60000u

void nest_beacon_default_params(nest_beacon_params_t *params)
{
    params->n_robots = 20u;
    params->f0_tokens = 5;
    params->token_energy = 1500u;
    params->c_rate_milli_tokens_per_min = 2000u;
    params->move_cost = 1u;
    params->e_a = 10u;
    params->t2_steps = 400u;   /* L / (2 v) = 4 m / 0.1 m/s = 40 s at 10 Hz */
    params->wait_timeout_steps = 5u;
    params->min_deposit_steps = 20u;
}

void nest_beacon_init(nest_beacon_t *self, const nest_beacon_params_t *params, uint32_t seed)
{
    self->params = *params;
    self->seed = seed;
    nest_beacon_reset(self);
}

void nest_beacon_reset(nest_beacon_t *self)
{
    uint8_t i;
    uint16_t bins = (uint16_t)(self->params.t2_steps / NB_BIN_STEPS);

    if (self->params.token_energy == 0u) {
        self->params.token_energy = 1u;   /* F = ledger / token_energy */
    }
    if (self->params.min_deposit_steps == 0u) {
        self->params.min_deposit_steps = 1u;
    }
    if (self->params.wait_timeout_steps == 0u) {
        self->params.wait_timeout_steps = 1u;
    } else if (self->params.wait_timeout_steps >= NB_AGE_NEVER) {
        self->params.wait_timeout_steps = (uint8_t)(NB_AGE_NEVER - 1u);
    }
    self->n_bins = (uint8_t)(bins < 1u ? 1u : (bins > NB_MAX_BINS ? NB_MAX_BINS : bins));

    self->state = NB_START;
    self->ledger_units = (int32_t)self->params.f0_tokens * (int32_t)self->params.token_energy;
    self->food_q4 = nest_beacon_food_q4(self);
    self->n_waiting = 0u;
    self->m_t2 = 0u;
    self->deposits_total = 0u;
    self->oae_total = 0u;
    for (i = 0; i < NB_SLOTS; i++) {
        /* Robots start with totals 0 together with the beacon. */
        self->last_deposits[i] = 0u;
        self->last_oaes[i] = 0u;
        self->age_steps[i] = NB_AGE_NEVER;
        self->deposit_budget[i] = 0u;   /* robots start at home: nothing to credit yet */
        self->oae_budget[i] = 0u;
    }
    for (i = 0; i < NB_MAX_BINS; i++) {
        self->bins[i] = 0u;
    }
    self->bin = 0u;
    self->bin_step = 0u;
    self->cons_rem_milli_ms = 0u;
    self->cons_rem_milli = 0u;
    self->next_kind = NL_KIND_FOOD;
}

int32_t nest_beacon_food_q4(const nest_beacon_t *self)
{
    int32_t te = (int32_t)self->params.token_energy;
    int32_t lim = te * 2048;   /* 2048 tokens * 16 * 65535 still fits an int32 */
    int32_t e = self->ledger_units;
    if (e > lim) {
        e = lim;
    } else if (e < -lim) {
        e = -lim;
    }
    /* Round half away from zero: C division truncates toward zero. */
    return (e >= 0) ? (e * NL_FOOD_PER_TOKEN + te / 2) / te : (e * NL_FOOD_PER_TOKEN - te / 2) / te;
}

uint32_t nest_beacon_mean_oae_q8(const nest_beacon_t *self)
{
    uint32_t m = self->m_t2 > 65535u ? 65535u : self->m_t2;
    if (self->params.n_robots == 0u) {
        return 0u;
    }
    return (m * 256u) / self->params.n_robots;
}

/* The nest's consumption over one period of `period_ms`, in units, exact
 * over time.  The rate is m = c_rate * token_energy milli-units per minute
 * (2000 * 1500 = 3,000,000): split into whole milli-units per ms and a
 * remainder, so that no product exceeds 32 bits. */
static int32_t consumption_units(nest_beacon_t *self, uint16_t period_ms)
{
    uint32_t m = (uint32_t)self->params.c_rate_milli_tokens_per_min
                 * (uint32_t)self->params.token_energy;
    uint32_t whole = m / MS_PER_MIN;
    uint32_t frac = (m % MS_PER_MIN) * (uint32_t)period_ms + self->cons_rem_milli_ms;
    uint32_t milli = whole * (uint32_t)period_ms + frac / MS_PER_MIN;
    self->cons_rem_milli_ms = frac % MS_PER_MIN;
    milli += self->cons_rem_milli;
    self->cons_rem_milli = (uint16_t)(milli % 1000u);
    return (int32_t)(milli / 1000u);
}

/* Starts a new bin every NB_BIN_STEPS steps; the bin it reuses held the
 * OAEs of T2 ago, which leave the window. */
static void advance_window(nest_beacon_t *self)
{
    if (self->bin_step < NB_BIN_STEPS) {
        return;
    }
    self->bin_step = 0u;
    self->bin = (uint8_t)((self->bin + 1u) % self->n_bins);
    self->m_t2 -= self->bins[self->bin];
    self->bins[self->bin] = 0u;
}

static void age_slots(nest_beacon_t *self)
{
    uint8_t i;
    for (i = 0; i < NB_SLOTS; i++) {
        if (self->age_steps[i] < NB_AGE_NEVER) {
            self->age_steps[i]++;
        }
        if (self->deposit_budget[i] < NB_BUDGET_MAX) {
            self->deposit_budget[i]++;
        }
        if (self->oae_budget[i] < NB_BUDGET_MAX) {
            self->oae_budget[i]++;
        }
    }
}

/* ledger += delta, saturating at +- NB_LEDGER_LIMIT_TOKENS tokens.  Every
 * change of the ledger goes through here: reports are untrusted input. */
static void ledger_add(nest_beacon_t *self, int32_t delta)
{
    int32_t lim = (int32_t)NB_LEDGER_LIMIT_TOKENS * (int32_t)self->params.token_energy;
    int32_t e = self->ledger_units;
    if (delta > 0) {
        e = (e > lim - delta) ? lim : e + delta;
    } else if (delta < 0) {
        e = (e < -lim - delta) ? -lim : e + delta;
    }
    self->ledger_units = e;
}

static uint32_t add_saturated(uint32_t total, uint8_t n)
{
    return (total > 0xFFFFFFFFu - n) ? 0xFFFFFFFFu : total + n;
}

/* What a cumulative report (mod 256) may credit: the rise since what was
 * last credited, but no more than the robot's budget pays for at `cost`
 * steps a unit.  `last` advances only by what is credited, so the rest of
 * a real rise (a lost report's share) is credited by a later report, and a
 * lying or garbled stream gains no faster than a real robot could. */
static uint8_t credit(uint8_t reported, uint8_t *last, uint8_t *budget, uint8_t cost)
{
    uint8_t rise = nest_link_count_diff(reported, *last);
    uint8_t affordable = (uint8_t)(*budget / cost);
    uint8_t n = rise < affordable ? rise : affordable;
    *last = (uint8_t)(*last + n);
    *budget = (uint8_t)(*budget - n * cost);
    return n;
}

static void add_oaes(nest_beacon_t *self, uint8_t n)
{
    uint16_t room = (uint16_t)(65535u - self->bins[self->bin]);
    uint16_t binned = (n > room) ? room : n;   /* a bin saturates rather than wraps */
    self->oae_total = add_saturated(self->oae_total, n);
    ledger_add(self, -(int32_t)n * (int32_t)self->params.e_a);
    self->bins[self->bin] = (uint16_t)(self->bins[self->bin] + binned);
    self->m_t2 += binned;   /* M_T2 stays the sum of the bins */
}

static void read_reports(nest_beacon_t *self, hal_t *hal)
{
    hal_ircom_msg_t msg;
    nest_link_frame_t f;
    while (hal_ircom_receive(hal, &msg) == HAL_OK) {
        uint8_t n;
        switch (nest_link_decode(msg.value, &f)) {
        case NL_DEPOSITS:
            n = credit((uint8_t)f.value, &self->last_deposits[f.robot_id],
                       &self->deposit_budget[f.robot_id], self->params.min_deposit_steps);
            self->deposits_total = add_saturated(self->deposits_total, n);
            ledger_add(self, (int32_t)n * (int32_t)self->params.token_energy);
            self->age_steps[f.robot_id] = 0u;
            break;
        case NL_OAES:   /* from robots in any state: not a sign of waiting */
            n = credit((uint8_t)f.value, &self->last_oaes[f.robot_id], &self->oae_budget[f.robot_id], 1u);
            add_oaes(self, n);
            break;
        default:
            break;   /* other beacons' frames and garbage */
        }
    }
}

static uint16_t count_waiting(const nest_beacon_t *self)
{
    uint16_t n = 0u;
    uint8_t i;
    for (i = 0; i < NB_SLOTS; i++) {
        if (self->age_steps[i] < self->params.wait_timeout_steps) {
            n++;
        }
    }
    return n;
}

static void broadcast(nest_beacon_t *self, hal_t *hal)
{
    uint16_t frame;
    switch (self->next_kind) {
    case NL_KIND_FOOD:
        frame = nest_link_encode_food(self->food_q4);
        break;
    case NL_KIND_WAITING:
        frame = nest_link_encode_waiting(self->n_waiting);
        break;
    default:
        frame = nest_link_encode_mean_oae(nest_beacon_mean_oae_q8(self));
        break;
    }
    (void)hal_ircom_send(hal, frame);   /* a refused frame comes round again in 3 steps */
    self->next_kind = (uint8_t)((self->next_kind + 1u) % (uint8_t)NL_KIND_COUNT);
}

static void keep_ledger(nest_beacon_t *self, hal_t *hal)
{
    uint16_t active;

    hal_set_wheel_speeds(hal, 0, 0);
    advance_window(self);
    age_slots(self);
    read_reports(self, hal);
    self->n_waiting = count_waiting(self);

    active = (self->params.n_robots > self->n_waiting)
             ? (uint16_t)(self->params.n_robots - self->n_waiting) : 0u;
    ledger_add(self, -consumption_units(self, hal_control_period_ms(hal)));
    ledger_add(self, -(int32_t)((uint32_t)active * self->params.move_cost));

    self->food_q4 = nest_beacon_food_q4(self);   /* the ledger is final for this step */
    broadcast(self, hal);
    self->bin_step++;
}

void nest_beacon_step(nest_beacon_t *self, hal_t *hal)
{
    switch (self->state) {
    case NB_START:
        /* The body LED marks the beacon for whoever watches the arena. */
        hal_set_body_led(hal, 1u);
        keep_ledger(self, hal);
        self->state = NB_RUN;
        break;
    case NB_RUN:
        keep_ledger(self, hal);
        break;
    default:
        self->state = NB_START;
        hal_set_wheel_speeds(hal, 0, 0);
        break;
    }
}

const char *nest_beacon_state_name(const nest_beacon_t *self)
{
    switch (self->state) {
    case NB_START: return "start";
    case NB_RUN: return "run";
    default: return "?";
    }
}
