#include "repatt.h"

#include <stddef.h>

#include "common/motion.h"
#include "units.h"

/* Periods after the pick-up wait in which the target's disappearance still
 * counts as our pick-up (the task removes it at the end of the wait; a few
 * periods of slack for when it sees the wait end). */
#define PICK_GRACE_PERIODS 8u
/* A blob within this of the target's bearing, and at least 3/4 of its
 * width, is the target we wait at, mrad.  Tight on purpose: in a cluster the
 * next target behind the one taken is usually in the same direction, but
 * farther, so narrower (a 1 cm target at 50 mm is 400 mrad wide, at 80 mm
 * 250 mrad); a looser test took it for the one just picked, counted no
 * pick-up and made the robot ignore targets for give_up_ms. */
#define PICK_SAME_MRAD 150
/* With approach_mm: the blob must be this near straight ahead before the
 * blind approach starts, mrad (6 mm off the axis at the 60 mm a 330 mrad
 * wide 1 cm target is from the lens). */
#define APPROACH_CENTRED_MRAD 100
/* 12 uniform 12-bit numbers: mean 12 x 4095 / 2, sd 4096 / sqrt(12) x
 * sqrt(12) = 4096 (Irwin-Hall). */
#define GAUSS_TERMS 12
#define GAUSS_MEAN 24570L
#define GAUSS_SD 4096L

void repatt_apply_policy(repatt_params_t *params, uint8_t policy)
{
    switch (policy) {
    case REPATT_POLICY_REPATT:
        /* Section IV.B-D's best, A4m100d-R1m10d (Figure 3's caption says
         * a_d = 10; the text, Figures 2 and 4 say 100). */
        params->gains.a_m = 4u;
        params->gains.a_d = 100u;
        params->gains.r_m = 1u;
        params->gains.r_d = 10u;
        break;
    case REPATT_POLICY_RANDOM_WALK:
        params->gains.a_m = 1u;
        params->gains.a_d = 1u;
        params->gains.r_m = 1u;
        params->gains.r_d = 1u;
        break;
    default:
        break;
    }
}

void repatt_default_params(repatt_params_t *params)
{
    params->p_b = 0.0025f;
    repatt_apply_policy(params, REPATT_POLICY_REPATT);
    params->queue_size = 40u;
    params->listening = (uint8_t)REPATT_SLOTTED;
    params->capacity = 5u;
    params->speed_steps_s = 776;        /* 0.10 m/s / 0.12881 mm */
    params->turn_speed_steps_s = 776;
    params->steer_gain = 1000;
    params->tumble_mean_mrad = 3142u;
    params->tumble_sd_mrad = 1571u;
    params->avoid_enter = 300u;         /* about 25 mm from a sensor */
    params->side_turn_mrad = 785u;
    params->oa_run_max_mm = 165u;       /* 1 m x 0.16529 */
    params->pick_time_ms = 5000u;
    /* The e-puck's front camera, lens 35 mm ahead of the centre, 30 mm up,
     * 56 x 28 deg: a 1 cm target is 330 mrad wide 61 mm from the lens
     * (centre 96 mm away), still wholly in view; 46 mm on leaves the
     * centres about 50 mm apart, within the targets task's 55 mm. */
    params->reach_width_mrad = 330u;
    params->approach_mm = 46u;
    params->give_up_ms = 10000u;
    params->home_radius_mm = 100u;
}

void repatt_attach_queue(repatt_t *self, uint32_t *storage, uint16_t queue_max)
{
    self->queue = storage;
    self->queue_max = (storage != NULL) ? queue_max : 0u;
}

void repatt_init(repatt_t *self, const repatt_params_t *params, uint32_t seed)
{
    self->params = *params;
    self->seed = seed;
    repatt_reset(self);
}

static void clear_filters(repatt_t *self)
{
    uint16_t y = self->params.queue_size;
    uint8_t b;
    if (y > self->queue_max) {
        y = self->queue_max;
    }
    for (b = 0; b < REPATT_BANDS; b++) {
        chemo_filter_init(&self->filter[b], y);
    }
    self->level_r = 0u;
    self->level_a = 0u;
    self->d_r = 0;
    self->d_a = 0;
}

void repatt_reset(repatt_t *self)
{
    const repatt_params_t *p = &self->params;
    rng_seed(&self->rng, self->seed);
    self->state = REPATT_SEARCH;
    self->cap = p->capacity;
    self->found = 0u;
    clear_filters(self);
    self->p_b_q32 = chemo_probability_q32(p->p_b);
    self->p_t_q32 = self->p_b_q32;
    self->band = 0u;
    self->speaker = 255u;
    odometry_reset(&self->odo);
    avoid_reset(&self->turn);
    self->timer = 0u;
    self->ignore = 0u;
    self->pick_bearing_mrad = 0;
    self->pick_width_mrad = 0u;
    self->oae_count = 0u;
    self->pickups = 0u;
    self->unloads = 0u;
    self->readings = 0u;
}

/* ------------------------------------------------------------ sensing */

/* The target we wait at: a red blob near its bearing, nearly as wide. */
static uint8_t target_still_there(const repatt_t *self, hal_t *hal)
{
    hal_blob_t blobs[HAL_MAX_BLOBS];
    uint8_t n = hal_camera_blobs(hal, blobs, (uint8_t)HAL_MAX_BLOBS);
    uint8_t i;
    for (i = 0; i < n && i < HAL_MAX_BLOBS; i++) {
        int32_t db = (int32_t)blobs[i].bearing_mrad - self->pick_bearing_mrad;
        if (blobs[i].colour == HAL_COLOUR_RED && db < PICK_SAME_MRAD && db > -PICK_SAME_MRAD
            && (uint32_t)blobs[i].width_mrad * 4u >= (uint32_t)self->pick_width_mrad * 3u) {
            return 1u;
        }
    }
    return 0u;
}

/* One reading per band from the microphones that answer HAL_OK (their
 * mean); none when none does (own tone, no sound). */
static void listen(repatt_t *self, hal_t *hal)
{
    uint8_t b, m;
    for (b = 0; b < REPATT_BANDS; b++) {
        uint64_t sum = 0u;
        uint8_t n = 0u;
        for (m = 0; m < HAL_MIC_COUNT; m++) {
            uint32_t level = 0u;
            if (hal_mic_level(hal, m, (uint8_t)(b + 1u), &level) == HAL_OK) {
                sum += level;
                n++;
            }
        }
        if (n != 0u) {
            uint32_t *ring = (self->queue != NULL && self->queue_max != 0u)
                             ? self->queue + (uint16_t)(b * 2u * self->queue_max) : NULL;
            chemo_filter_push(&self->filter[b], ring, (uint32_t)(sum / n));
            if (b == 0u) {
                self->readings++;
            }
        }
    }
    self->level_r = chemo_filter_level(&self->filter[0]);
    self->level_a = chemo_filter_level(&self->filter[1]);
    self->d_r = chemo_filter_sign(&self->filter[0]);
    self->d_a = chemo_filter_sign(&self->filter[1]);
}

/* ------------------------------------------------------------ motion */

/* A turn in place by `mrad` (CCW positive), counted on the step counters. */
static void start_turn(repatt_t *self, uint8_t state, int32_t mrad)
{
    self->state = state;
    avoid_turn_by(&self->turn, mrad);
}

/* Turning: 1 while some of the turn is left (wheels set), 0 when done. */
static uint8_t turn_step(repatt_t *self, hal_t *hal)
{
    return avoid_turn_step(&self->turn, hal, self->params.turn_speed_steps_s);
}

static void forward(repatt_t *self, hal_t *hal)
{
    hal_set_wheel_speeds(hal, self->params.speed_steps_s, self->params.speed_steps_s);
}

/* Toward `bearing_mrad`: in place when it is behind, else forward with a
 * proportional difference. */
static void steer(const repatt_t *self, hal_t *hal, int16_t bearing_mrad)
{
    int16_t w = self->params.turn_speed_steps_s;
    int32_t d, v;
    if (bearing_mrad > UNITS_HALF_PI_MRAD) {
        hal_set_wheel_speeds(hal, (int16_t)-w, w);
        return;
    }
    if (bearing_mrad < -UNITS_HALF_PI_MRAD) {
        hal_set_wheel_speeds(hal, w, (int16_t)-w);
        return;
    }
    d = (int32_t)self->params.steer_gain * (int32_t)bearing_mrad / 1000;
    v = (int32_t)self->params.speed_steps_s;
    hal_set_wheel_speeds(hal, motion_clamp_speed(v - d), motion_clamp_speed(v + d));
}

/* A tumble angle from N(mu, sigma^2), mrad. */
static int32_t tumble_angle(repatt_t *self)
{
    int32_t s = 0;
    uint8_t i;
    for (i = 0; i < GAUSS_TERMS; i++) {
        s += (int32_t)(rng_next(&self->rng) >> 20);   /* 0..4095 */
    }
    return (int32_t)self->params.tumble_mean_mrad
           + ((s - GAUSS_MEAN) * (int32_t)self->params.tumble_sd_mrad) / GAUSS_SD;
}

/* Lines 3-4: the turn of an obstacle avoidance. */
static void start_avoidance(repatt_t *self, uint8_t where)
{
    self->oae_count++;
    self->state = REPATT_AVOID;
    avoid_start_turn(&self->turn, &self->rng, where, self->params.side_turn_mrad);
}

/* ------------------------------------------------------------ states */

static void enter_home(repatt_t *self)
{
    self->state = REPATT_HOME;
    clear_filters(self);   /* deaf until unloaded; fresh queues after */
}

static void home_step(repatt_t *self, hal_t *hal)
{
    if (odometry_within_mm(&self->odo, self->params.home_radius_mm) != 0u) {
        self->cap = self->params.capacity;   /* unloaded */
        self->unloads++;
        self->state = REPATT_SEARCH;
        return;
    }
    steer(self, hal, odometry_home_bearing_mrad(&self->odo));
}

/* PICK: 1 while the robot stays; 0 when it goes on (the other states
 * decide its motion this period). */
static uint8_t pick_step(repatt_t *self, hal_t *hal)
{
    uint16_t wait = motion_periods(hal, self->params.pick_time_ms);
    /* Blind (nothing was seen where it stopped): the whole wait, then carried. */
    uint8_t blind = (self->pick_width_mrad == 0u) ? 1u : 0u;
    uint8_t there = (blind != 0u) ? (uint8_t)(self->timer < wait) : target_still_there(self, hal);
    if (there == 0u) {
        if (self->timer >= wait) {
            if (self->cap > 0u) {
                self->cap--;   /* the task took it after our wait: carried */
            }
            self->pickups++;
        }
        /* Gone during the wait: another robot took it. */
        self->state = REPATT_SEARCH;
        return 0u;
    }
    if (self->timer >= (uint16_t)(wait + PICK_GRACE_PERIODS)) {
        self->ignore = motion_periods(hal, self->params.give_up_ms);   /* out of reach: give up */
        self->state = REPATT_SEARCH;
        return 0u;
    }
    hal_set_wheel_speeds(hal, 0, 0);
    self->timer++;
    return 1u;
}

/* `blob` NULL: nothing to see where the robot stopped (a blind pick-up). */
static void start_pick(repatt_t *self, hal_t *hal, const hal_blob_t *blob)
{
    self->state = REPATT_PICK;
    self->pick_bearing_mrad = (blob != NULL) ? blob->bearing_mrad : 0;
    self->pick_width_mrad = (blob != NULL) ? blob->width_mrad : 0u;
    hal_set_wheel_speeds(hal, 0, 0);
    self->timer = 1u;   /* this period is the first stopped */
}

/* Lines 8-27 for a robot with room for targets. */
static void forage_step(repatt_t *self, hal_t *hal, const hal_blob_t *widest)
{
    /* Lines 8-21: the gains from this period's changes, from 1 each time. */
    self->p_t_q32 = chemo_tumble_q32(self->p_b_q32, &self->params.gains, self->d_r, self->d_a);

    if (self->state == REPATT_PICK) {
        if (pick_step(self, hal) != 0u) {
            return;
        }
        if (self->cap == 0u) {   /* that was the last one it had room for */
            enter_home(self);
            home_step(self, hal);
            if (self->state == REPATT_HOME) {
                return;
            }
        }
    }
    if (self->state == REPATT_APPROACH) {
        if (avoid_run_step(&self->turn, hal, self->params.speed_steps_s) != 0u) {
            return;
        }
        /* There: the target is the blob ahead, if the camera still sees it. */
        start_pick(self, hal, (self->found > 0u && widest->bearing_mrad < APPROACH_CENTRED_MRAD
                               && widest->bearing_mrad > -APPROACH_CENTRED_MRAD) ? widest : NULL);
        return;
    }
    if (self->found > 0u && self->ignore == 0u) {
        if (widest->width_mrad >= self->params.reach_width_mrad && self->params.approach_mm == 0u) {
            start_pick(self, hal, widest);
        } else if (widest->width_mrad >= self->params.reach_width_mrad
                   && widest->bearing_mrad < APPROACH_CENTRED_MRAD && widest->bearing_mrad > -APPROACH_CENTRED_MRAD) {
            self->state = REPATT_APPROACH;
            avoid_start_run_mm(&self->turn, (int32_t)self->params.approach_mm);
            (void)avoid_run_step(&self->turn, hal, self->params.speed_steps_s);
        } else {
            self->state = REPATT_ACQUIRE;
            steer(self, hal, widest->bearing_mrad);
        }
        return;
    }
    if (self->state == REPATT_TUMBLE && turn_step(self, hal) != 0u) {
        return;
    }
    self->state = REPATT_SEARCH;
    /* rng_next() < P_t: probability P_t / 2^32. */
    if (self->p_t_q32 != 0u && rng_next(&self->rng) < self->p_t_q32) {
        start_turn(self, REPATT_TUMBLE, tumble_angle(self));
        if (turn_step(self, hal) != 0u) {
            return;
        }
        self->state = REPATT_SEARCH;   /* a turn of 0 steps */
    }
    forward(self, hal);
}

/* Lines 9-12 for this period, and what the speaker plays next. */
static void set_speaker(repatt_t *self, hal_t *hal)
{
    uint8_t out;
    if (self->cap == 0u || self->state == REPATT_HOME) {
        self->band = 0u;   /* homing, avoidances on the way included */
    } else if (self->state != REPATT_AVOID && self->state != REPATT_AVOID_RUN) {
        /* Avoiding keeps the band of the state it interrupted. */
        if (self->found == 0u) {
            self->band = REPATT_BAND_REPULSION;
        } else if (self->found > self->cap) {
            self->band = REPATT_BAND_ATTRACTION;
        } else {
            self->band = 0u;
        }
    }
    out = self->band;
    if (out != 0u && self->params.listening == REPATT_SLOTTED && (rng_next(&self->rng) & 0x80000000UL) == 0u) {
        out = 0u;   /* a silent period: one to listen in */
    }
    if (out != self->speaker) {
        (void)hal_speaker_set(hal, out);
        self->speaker = out;
    }
}

void repatt_step(repatt_t *self, hal_t *hal)
{
    int16_t l, r, dl, dr;
    hal_blob_t widest;
    uint8_t where;

    hal_wheel_steps(hal, &l, &r);
    odometry_update(&self->odo, l, r, &dl, &dr);
    /* What the last command did to the current turn or run. */
    avoid_count(&self->turn, (self->state == REPATT_TUMBLE || self->state == REPATT_AVOID) ? AVOID_TURNING
                             : (self->state == REPATT_AVOID_RUN || self->state == REPATT_APPROACH) ? AVOID_RUNNING
                             : AVOID_IDLE, dl, dr);
    if (self->ignore > 0u) {
        self->ignore--;
    }

    widest.colour = HAL_COLOUR_NONE;
    widest.bearing_mrad = 0;
    widest.width_mrad = 0u;
    widest.pixels = 0u;
    self->found = hal_camera_widest(hal, (uint8_t)HAL_COLOUR_RED, &widest);
    if (self->cap != 0u) {
        listen(self, hal);   /* homing robots ignore the signals */
    }

    /* Lines 3-4: obstacle avoidance, its turn then its run. */
    where = (self->state == REPATT_PICK || self->state == REPATT_AVOID) ? 0u
            : avoid_obstacle(hal, self->params.avoid_enter);
    if (where != 0u) {
        start_avoidance(self, where);
    }
    if (self->state == REPATT_AVOID) {
        if (turn_step(self, hal) != 0u) {
            set_speaker(self, hal);
            return;
        }
        self->state = REPATT_AVOID_RUN;
        avoid_start_run(&self->turn, &self->rng, self->params.oa_run_max_mm);
    }
    if (self->state == REPATT_AVOID_RUN) {
        if (avoid_run_step(&self->turn, hal, self->params.speed_steps_s) != 0u) {
            set_speaker(self, hal);
            return;
        }
        self->state = REPATT_SEARCH;   /* run done: the other states decide */
    }

    /* Lines 5-6, then 8-27. */
    if (self->cap == 0u) {
        self->state = REPATT_HOME;   /* (the queues were emptied when cap reached 0) */
        home_step(self, hal);
        if (self->state == REPATT_HOME) {
            set_speaker(self, hal);
            return;
        }
    }
    forage_step(self, hal, &widest);
    set_speaker(self, hal);
}

const char *repatt_state_name(const repatt_t *self)
{
    switch (self->state) {
    case REPATT_SEARCH: return "search";
    case REPATT_TUMBLE: return "tumble";
    case REPATT_ACQUIRE: return "acquire";
    case REPATT_PICK: return "pick";
    case REPATT_HOME: return "home";
    case REPATT_AVOID: return "avoid";
    case REPATT_AVOID_RUN: return "avoid_run";
    case REPATT_APPROACH: return "approach";
    default: return "?";
    }
}
