#include "forager.h"

#include "common/motion.h"
#include "nest_link.h"
#include "units.h"

/* The walk's stream must differ from the forager's own (n, roulette). */
#define WALK_SEED_SALT UINT32_C(0x5bd1e995)
/* 90 degrees in mrad: a light farther round than this is behind. */
/* A blob this close to straight ahead is centred, mrad. */
#define CENTRED_MRAD 150
/* Steps after steering at a near, centred token in which a grasp counts. */
#define APPROACH_STEPS 10u
/* Steps a wide red blob must stay centred to count as held without an
 * approach before it (2 s): a token the gripper took in passing. */
#define HOLD_STEPS 20u
/* Steps between OAE reports out of the nest. */
#define OUT_REPORT_STEPS 5u
/* No beacon frame this step. */
#define NO_RANGE 0xFFFFu

void forager_default_params(forager_params_t *params)
{
    params->policy = TA_DRTM;
    params->alpha = 3.0f;
    params->beta = 2.0f;
    params->t1_steps = 50u;
    params->n_min = 2u;
    params->n_max = 9u;
    params->theta0 = 3.3f;
    params->theta_min = 1.0f;
    params->theta_max = 10.0f;
    params->artm_delta = 0.5f;
    params->f_d_tokens = 20.0f;
    params->n_robots = 20u;
    params->arena_l_mm = 4000u;
    params->speed_steps_s = 388;   /* 0.05 m/s: T2 = L / (2 v) = 40 s */
    params->steer_gain = 800;      /* a blob at the edge of the view (~490 mrad) turns
                                      at about the forward speed */
    /* Width of a token in the gripper: it fills the 977 mrad view.  A token
     * still on the floor is at most about 850 mrad wide until the scoop
     * takes it, so 900 tells the two apart. */
    params->grasp_width_mrad = 900u;
    params->near_width_mrad = 250u;
    params->lost_steps = 3u;
    params->nest_radius_mm = 750u;
    params->nest_margin_mm = 100u;
    params->nest_confirm = 3u;
    params->light_detect = 3600u;
    params->deposit_steps = 5u;
    params->drtm_theta = (uint8_t)TA_THETA_OFFSET;
    params->decide_each_step = 1u;
    params->leave_nest = 1u;
    params->leave_max_steps = 300u;   /* 30 s: the nest's radius twice over at 0.05 m/s */
    params->grasp_confirm = 3u;
    params->park_steps = 0u;
    params->report_steps = 1u;
    random_walk_default_params(&params->walk);
    params->walk.speed_steps_s = params->speed_steps_s;
    /* Search: a tumble every 20 s on average, a 1 m run at 0.05 m/s (a
     * quarter of the arena side).  Seed 000 does not give its random walk;
     * this is our choice. */
    params->walk.turn_chance = 328u;   /* 0.005 * 65536 */
}

void forager_init(forager_t *self, const forager_params_t *params, uint32_t seed)
{
    self->params = *params;
    /* One forward speed for the whole robot: it sets T2 = L / (2 v). */
    self->params.walk.speed_steps_s = self->params.speed_steps_s;
    self->seed = seed;
    forager_reset(self);
}

void forager_reset(forager_t *self)
{
    const forager_params_t *p = &self->params;
    uint8_t hi = (p->n_max >= p->n_min) ? p->n_max : p->n_min;

    rng_seed(&self->rng, self->seed);
    random_walk_init(&self->walk, &p->walk, self->seed ^ WALK_SEED_SALT);
    /* n differs between robots so that they do not all respond at once. */
    self->n = (uint8_t)rng_range(&self->rng, p->n_min, hi);

    self->state = FORAGER_WAIT;
    self->t1 = 0u;
    /* All robots start in the nest with no OAE: k = M_A = 0. */
    self->theta = (p->policy == TA_DRTM)
                  ? ta_drtm_theta(p->drtm_theta, p->alpha, p->beta, 0.0f, 0.0f, p->theta0, p->theta_min,
                                  p->theta_max)
                  : p->theta0;
    self->S = 0.0f;
    self->S_prev = 0.0f;
    self->P_s = 0.0f;
    self->k = 0.0f;
    self->M_A = 0.0f;
    self->decided = 0u;
    self->deposits = 0u;
    self->beacon_known = 0u;
    self->beacon_food_q4 = 0;
    self->beacon_n_waiting = 0u;
    self->beacon_mean_oae_q8 = 0u;
    self->beacon_range_mm = NO_RANGE;
    self->nest_frames = 0u;
    self->carrying = 0u;
    self->lost = 0u;
    self->timer = 0u;
    self->report_oaes = 0u;
    self->leaving = 0u;
    self->leave_steps = 0u;
    self->out_frames = 0u;
    self->approach = 0u;
    self->grasp_steps = 0u;
    self->out_timer = 0u;
    self->wait_timer = 0u;
}

/* ------------------------------------------------------------ sensing */

/* Pops every message; remembers the beacon's quantities and counts the
 * beacon frames in a row heard from inside the nest. */
static void read_inbox(forager_t *self, hal_t *hal)
{
    hal_ircom_msg_t msg;
    nest_link_frame_t f;
    const forager_params_t *p = &self->params;
    uint16_t inside = (p->nest_radius_mm > p->nest_margin_mm)
                      ? (uint16_t)(p->nest_radius_mm - p->nest_margin_mm) : 0u;
    while (hal_ircom_receive(hal, &msg) == HAL_OK) {
        if (nest_link_decode(msg.value, &f) != NL_BEACON) {
            continue;   /* other robots' reports */
        }
        switch (f.kind) {
        case NL_KIND_FOOD:
            self->beacon_food_q4 = f.value;
            self->beacon_known |= FORAGER_KNOWS_FOOD;
            break;
        case NL_KIND_WAITING:
            self->beacon_n_waiting = (uint16_t)f.value;
            self->beacon_known |= FORAGER_KNOWS_WAITING;
            break;
        default:
            self->beacon_mean_oae_q8 = (uint16_t)f.value;
            self->beacon_known |= FORAGER_KNOWS_MEAN_OAE;
            break;
        }
        self->beacon_range_mm = msg.range_mm;
        /* The range estimate is noisy (about 10 % on the turret): only
         * nest_confirm frames in a row inside the nest count as arrival. */
        if (msg.range_mm < inside) {
            if (self->nest_frames < 255u) {
                self->nest_frames++;
            }
        } else {
            self->nest_frames = 0u;
        }
        if ((uint32_t)msg.range_mm >= (uint32_t)p->nest_radius_mm + p->nest_margin_mm) {
            if (self->out_frames < 255u) {
                self->out_frames++;
            }
        } else {
            self->out_frames = 0u;
        }
    }
}

/* ------------------------------------------------------------ motion */

/* f(x) of eq 1 with A(t) = 1: drive forward, turning toward `bearing_mrad`
 * (CCW positive: a target on the left speeds up the right wheel). */
static void steer(const forager_t *self, hal_t *hal, int16_t bearing_mrad)
{
    int32_t d = (int32_t)self->params.steer_gain * (int32_t)bearing_mrad / 1000;
    int32_t v = (int32_t)self->params.speed_steps_s;
    hal_set_wheel_speeds(hal, motion_clamp_speed(v - d), motion_clamp_speed(v + d));
}

/* Phototaxis toward (away = 0) or away from (away = 1) the brightest
 * ambient sensor (lowest reading).  Returns 0 when no sensor sees the light. */
static uint8_t phototaxis(const forager_t *self, hal_t *hal, uint8_t away)
{
    uint16_t best = HAL_RAW_MAX;
    uint8_t best_i = 0u;
    uint8_t i;
    int16_t bearing;
    int16_t w = self->params.walk.turn_speed_steps_s;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        uint16_t a = hal_ir_ambient(hal, i);
        if (a < best) {
            best = a;
            best_i = i;
        }
    }
    if (best >= self->params.light_detect) {
        return 0u;
    }
    bearing = hal_ir_bearing_mrad(hal, best_i);
    if (away != 0u) {   /* the opposite direction, in (-pi, pi] */
        bearing = (int16_t)(bearing > 0 ? bearing - UNITS_PI_MRAD : bearing + UNITS_PI_MRAD);
    }
    if (bearing > UNITS_HALF_PI_MRAD) {
        hal_set_wheel_speeds(hal, (int16_t)-w, w);   /* behind on the left: turn CCW */
    } else if (bearing < -UNITS_HALF_PI_MRAD) {
        hal_set_wheel_speeds(hal, w, (int16_t)-w);   /* behind on the right: turn CW */
    } else {
        steer(self, hal, bearing);
    }
    return 1u;
}

/* ------------------------------------------------------------ transitions */

static void enter_wait(forager_t *self, hal_t *hal)
{
    self->state = FORAGER_WAIT;
    self->t1 = 0u;
    self->carrying = 0u;
    hal_set_wheel_speeds(hal, 0, 0);
}

/* Leaving the nest: a fresh run of the walk, but the OAE total and the
 * walk's random stream go on. */
static void enter_search(forager_t *self, hal_t *hal)
{
    self->state = FORAGER_SEARCH;
    self->leaving = self->params.leave_nest;
    self->leave_steps = 0u;
    self->out_frames = 0u;
    self->approach = 0u;
    self->grasp_steps = 0u;
    self->walk.state = RW_FORWARD;
    self->walk.turn_sign = 1;
    self->walk.turn_steps_left = 0;
    hal_set_led(hal, 0u, 0u);   /* the walk's avoidance LED */
}

static void enter_return(forager_t *self)
{
    self->state = FORAGER_RETURN;
    self->lost = 0u;
    self->nest_frames = 0u;   /* arrival counts from frames heard from now on */
}

static void enter_deposit(forager_t *self, hal_t *hal)
{
    int16_t v = self->params.speed_steps_s;
    self->state = FORAGER_DEPOSIT;
    hal_set_wheel_speeds(hal, (int16_t)-v, (int16_t)-v);
    self->timer = 1u;   /* this step is the first of backing */
}

/* ------------------------------------------------------------ states */

/* Eqs 2-7 and the roulette in the nest; `update` once per T1: the
 * threshold's own dynamics (ARTM's step) move at the paper's decision
 * period whatever the drawing cadence. */
static void decide(forager_t *self, hal_t *hal, uint8_t update)
{
    const forager_params_t *p = &self->params;
    float food_tokens;

    if (self->beacon_known != FORAGER_KNOWS_ALL) {
        self->P_s = 0.0f;   /* nothing to go on: stay */
        return;
    }
    food_tokens = (float)self->beacon_food_q4 / (float)NL_FOOD_PER_TOKEN;
    self->S = ta_stimulus(p->f_d_tokens, food_tokens);
    self->k = ta_traffic_density(p->n_robots, self->beacon_n_waiting,
                                 (float)p->arena_l_mm * 0.001f);
    self->M_A = (float)self->beacon_mean_oae_q8 / (float)NL_MEAN_OAE_PER_UNIT;
    switch (p->policy) {
    case TA_DRTM:
        self->theta = ta_drtm_theta(p->drtm_theta, p->alpha, p->beta, self->k, self->M_A, p->theta0,
                                    p->theta_min, p->theta_max);
        break;
    case TA_ARTM:
        if (update != 0u) {
            self->theta = ta_artm_update(self->theta, self->S,
                                         self->decided != 0u ? self->S_prev : self->S,
                                         p->artm_delta, p->theta_min, p->theta_max);
        }
        break;
    default:
        self->theta = p->theta0;
        break;
    }
    if (update != 0u) {
        self->S_prev = self->S;
        self->decided = 1u;
    }
    self->P_s = ta_probability(self->S, self->theta, self->n);
    if (ta_roulette(&self->rng, self->P_s) != 0u) {
        enter_search(self, hal);
    }
}

/* Out of the nest: the OAE total every step, for a beacon in range to
 * count OAEs when they happen rather than when the trip ends.  Deposit
 * totals go only from the nest: the beacon counts a robot as waiting by
 * them (nest_link.h). */
static void send_oae_report(forager_t *self, hal_t *hal)
{
    /* Every OUT_REPORT_STEPS steps, staggered by id: a nest crowded with
     * robots coming and going must leave room in the beacon's 20-message
     * queue for the waiting robots' reports, by which it counts N_W. */
    if ((uint16_t)(self->out_timer + hal_robot_id(hal)) % OUT_REPORT_STEPS == 0u) {
        (void)hal_ircom_send(hal, nest_link_encode_oaes(hal_robot_id(hal), self->walk.oae_count));
    }
    self->out_timer++;
}

/* In the nest: a report every report_steps steps, staggered by id, so
 * that a nest full of robots does not send the beacon more frames a step
 * than its receive queue holds. */
static void send_report(forager_t *self, hal_t *hal)
{
    uint16_t id = hal_robot_id(hal);
    uint8_t every = self->params.report_steps > 0u ? self->params.report_steps : 1u;
    uint16_t frame = (self->report_oaes != 0u)
                     ? nest_link_encode_oaes(id, self->walk.oae_count)
                     : nest_link_encode_deposits(id, self->deposits);
    uint8_t due = (uint8_t)((uint16_t)(self->wait_timer + id) % every == 0u);
    self->wait_timer = (uint8_t)((self->wait_timer + 1u) % every);
    if (due != 0u && hal_ircom_send(hal, frame) == HAL_OK) {
        self->report_oaes ^= 1u;
    }
}

static void wait_step(forager_t *self, hal_t *hal)
{
    const forager_params_t *p = &self->params;
    hal_set_wheel_speeds(hal, 0, 0);
    send_report(self, hal);
    self->t1++;
    if (self->t1 >= p->t1_steps) {
        /* Drawing every step after T1 (a minimum waiting time), the count
         * goes T1, ..., 2 T1 - 1, then back to T1: an update every T1. */
        if ((uint32_t)self->t1 >= 2u * (uint32_t)p->t1_steps) {
            self->t1 = p->t1_steps;
        }
        decide(self, hal, (uint8_t)(self->t1 == p->t1_steps));
        if (p->decide_each_step == 0u || self->state != FORAGER_WAIT) {
            self->t1 = 0u;
        }
    }
}

/* Leaving the nest: away from the lamp, round obstacles, until the beacon
 * is heard from outside the nest.  Returns 1 while still leaving. */
static uint8_t leave_step(forager_t *self, hal_t *hal)
{
    const forager_params_t *p = &self->params;
    self->leave_steps++;
    if (self->out_frames >= p->nest_confirm || self->leave_steps >= p->leave_max_steps) {
        self->leaving = 0u;
        return 0u;
    }
    if (random_walk_front_proximity(hal) > p->walk.avoid_enter || self->walk.state == RW_AVOID) {
        random_walk_step(&self->walk, hal);
    } else if (phototaxis(self, hal, 1u) == 0u) {
        self->leaving = 0u;   /* the lamp is out of sight: out of the nest */
        return 0u;
    }
    return 1u;
}

static void search_step(forager_t *self, hal_t *hal)
{
    hal_blob_t blob;
    const forager_params_t *p = &self->params;
    uint8_t seen;

    self->carrying = 0u;
    if (self->leaving != 0u && leave_step(self, hal) != 0u) {
        return;
    }
    seen = hal_camera_widest(hal, (uint8_t)HAL_COLOUR_RED, &blob);
    /* Held: wide and centred for grasp_confirm steps in a row right after
     * approaching it, or for HOLD_STEPS in a row without (a token taken in
     * passing stays put in the gripper while the robot drives and turns; a
     * token carried past by another robot does not). */
    if (seen != 0u && blob.width_mrad >= p->grasp_width_mrad
        && blob.bearing_mrad > -CENTRED_MRAD && blob.bearing_mrad < CENTRED_MRAD) {
        if (self->grasp_steps < 255u) {
            self->grasp_steps++;
        }
    } else {
        self->grasp_steps = 0u;
    }
    if (self->approach != 0u) {
        self->approach--;
    }
    if (self->grasp_steps >= (self->approach != 0u ? p->grasp_confirm : HOLD_STEPS)) {
        self->carrying = 1u;
        enter_return(self);   /* acts from the next step */
    } else if (seen != 0u) {
        /* The token's own IR echo is not an obstacle when we are about to
         * grasp it; anything else in front is. */
        uint8_t near = (uint8_t)(blob.bearing_mrad > -CENTRED_MRAD && blob.bearing_mrad < CENTRED_MRAD
                                 && blob.width_mrad >= p->near_width_mrad);
        if (random_walk_front_proximity(hal) > p->walk.avoid_enter && near == 0u) {
            random_walk_step(&self->walk, hal);
        } else {
            steer(self, hal, blob.bearing_mrad);
            if (near != 0u && blob.width_mrad < p->grasp_width_mrad) {
                /* A token growing in view as we drive at it: a grasp may
                 * follow (one that is wide at once was not approached). */
                self->approach = APPROACH_STEPS;
            }
        }
    } else {
        random_walk_step(&self->walk, hal);
    }
}

/* RETURN and PARK: is the token still in the gripper?  No wide red blob
 * for lost_steps steps in a row means it was lost: SEARCH, and 0. */
static uint8_t still_held(forager_t *self, hal_t *hal)
{
    hal_blob_t blob;
    const forager_params_t *p = &self->params;
    uint8_t seen = hal_camera_widest(hal, (uint8_t)HAL_COLOUR_RED, &blob);

    self->carrying = (uint8_t)(seen != 0u && blob.width_mrad >= p->grasp_width_mrad);
    if (self->carrying == 0u) {
        self->lost++;
        if (self->lost >= p->lost_steps) {
            self->state = FORAGER_SEARCH;   /* dropped it: search on, mid-walk */
            return 0u;
        }
    } else {
        self->lost = 0u;
    }
    return 1u;
}

/* Toward the lamp, round obstacles (the walk's avoidance and its OAE
 * count); the walk itself while the lamp is out of sight. */
static void home_step(forager_t *self, hal_t *hal)
{
    if (random_walk_front_proximity(hal) > self->params.walk.avoid_enter
        || self->walk.state == RW_AVOID) {
        random_walk_step(&self->walk, hal);
    } else if (phototaxis(self, hal, 0u) == 0u) {
        random_walk_step(&self->walk, hal);
    }
}

/* Parking: a step of driving on toward the lamp; after park_steps of them
 * (the arrival step the first), the deposit.  park_steps = 0 deposits at
 * arrival. */
static void park_or_deposit(forager_t *self, hal_t *hal)
{
    if (self->timer >= self->params.park_steps) {
        enter_deposit(self, hal);
        return;
    }
    self->timer++;
    home_step(self, hal);
}

static void enter_park(forager_t *self, hal_t *hal)
{
    self->state = FORAGER_PARK;
    self->timer = 0u;
    park_or_deposit(self, hal);
}

static void park_step(forager_t *self, hal_t *hal)
{
    if (still_held(self, hal) == 0u) {
        return;
    }
    park_or_deposit(self, hal);
}

static void return_step(forager_t *self, hal_t *hal)
{
    if (still_held(self, hal) == 0u) {
        return;
    }
    if (self->nest_frames >= self->params.nest_confirm) {
        enter_park(self, hal);
    } else {
        home_step(self, hal);
    }
}

static void deposit_step(forager_t *self, hal_t *hal)
{
    hal_blob_t blob;
    const forager_params_t *p = &self->params;
    int16_t v = p->speed_steps_s;
    uint8_t seen = hal_camera_widest(hal, (uint8_t)HAL_COLOUR_RED, &blob);

    self->carrying = (uint8_t)(seen != 0u && blob.width_mrad >= p->grasp_width_mrad);
    if (self->timer >= p->deposit_steps) {
        if (self->carrying == 0u) {
            self->deposits++;
            enter_wait(self, hal);
            return;
        }
        if (self->timer >= 2u * (uint16_t)p->deposit_steps) {
            enter_wait(self, hal);   /* still held: give up without counting */
            return;
        }
    }
    hal_set_wheel_speeds(hal, (int16_t)-v, (int16_t)-v);
    self->timer++;
}

void forager_step(forager_t *self, hal_t *hal)
{
    read_inbox(self, hal);

    switch (self->state) {
    case FORAGER_WAIT:
        wait_step(self, hal);
        break;
    case FORAGER_SEARCH:
        search_step(self, hal);
        break;
    case FORAGER_RETURN:
        return_step(self, hal);
        break;
    case FORAGER_PARK:
        park_step(self, hal);
        break;
    case FORAGER_DEPOSIT:
        deposit_step(self, hal);
        break;
    default:
        enter_wait(self, hal);
        break;
    }
    if (self->state != FORAGER_WAIT) {
        send_oae_report(self, hal);   /* after this step's motion: its latest total */
    }
}

char forager_paper_state(uint8_t state)
{
    switch (state) {
    case FORAGER_WAIT: return 'W';
    case FORAGER_SEARCH: return 'S';
    case FORAGER_RETURN: return 'R';
    case FORAGER_DEPOSIT: return 'R';
    case FORAGER_PARK: return 'R';
    default: return '?';
    }
}

const char *forager_state_name(const forager_t *self)
{
    switch (self->state) {
    case FORAGER_WAIT: return "wait";
    case FORAGER_SEARCH: return "search";
    case FORAGER_RETURN: return "return";
    case FORAGER_DEPOSIT: return "deposit";
    case FORAGER_PARK: return "park";
    default: return "?";
    }
}
