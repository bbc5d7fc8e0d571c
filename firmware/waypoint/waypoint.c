#include "waypoint.h"

#include "common/motion.h"
#include "units.h"
#include "repatt/odometry.h"

void waypoint_default_params(waypoint_params_t *params)
{
    /* RepAtt's (repatt.c): seed 002 at the plan's e-puck scale. */
    params->speed_steps_s = 776;        /* 0.10 m/s / 0.12881 mm */
    params->turn_speed_steps_s = 776;
    params->steer_gain = 1000;
    /* RepAtt's steer() turns in place beyond a quarter turn. */
    params->turn_in_place_mrad = 1571u;
    /* The simulator's targets task takes a target whose centre is within
     * 35 (body) + 10 (target) + 10 (pick_reach) = 55 mm of the robot's:
     * 30 mm leaves 25 mm for the tracker's error. */
    params->arrive_mm = 30u;
    /* Off: among clustered targets, a robot blocked by another near its
     * target and picking up from there takes the nearest target, often a
     * neighbour's, and a later robot then finds its own gone (7 of 30
     * One50m runs never reached 180).  The planner moves stops off the
     * walls instead (swarmtools.plan.routes.stop_point).  45 mm would stay
     * within the 55 mm the targets task reaches. */
    params->reach_mm = 0u;
    params->home_radius_mm = 100u;      /* RepAtt's unloading radius */
    /* At 0.10 m/s a fix 300 ms old is 30 mm (arrive_mm) behind the robot;
     * it also keeps the steering loop's delay where it stays damped (about
     * 5 rad/s of turn per rad of error: 300 ms is 1.5 rad of phase). */
    params->pose_max_age_ms = 300u;
    params->avoid_enter = 300u;         /* RepAtt's: about 25 mm from a sensor */
    params->side_turn_mrad = 785u;      /* RepAtt's 45 deg */
    params->oa_run_max_mm = 165u;       /* RepAtt's 1 m x 0.16529 */
    params->pick_time_ms = 5000u;       /* seed 002's 5 s */
}

void waypoint_init(waypoint_t *self, const waypoint_params_t *params, uint32_t seed)
{
    self->params = *params;
    self->seed = seed;
    waypoint_reset(self);
}

void waypoint_reset(waypoint_t *self)
{
    uint8_t i;
    rng_seed(&self->rng, self->seed);
    self->route.n = 0u;
    for (i = 0u; i < ROUTE_MAX_TARGETS; i++) {
        self->route.target[i].x_mm = 0;
        self->route.target[i].y_mm = 0;
    }
    self->route.drop.x_mm = 0;
    self->route.drop.y_mm = 0;
    avoid_reset(&self->avoid);
    self->last_left = 0;
    self->last_right = 0;
    self->primed = 0u;
    self->state = WAYPOINT_WAIT_ROUTE;
    self->index = 0u;
    self->timer = 0u;
    self->bearing_mrad = 0;
    self->has_pose = 0u;
    self->routes = 0u;
    self->picks = 0u;
    self->deliveries = 0u;
    self->no_pose = 0u;
    self->bad_msgs = 0u;
    self->oae_count = 0u;
}

/* ------------------------------------------------------------ helpers */

static void stop(hal_t *hal)
{
    hal_set_wheel_speeds(hal, 0, 0);
}

/* A tracker coordinate bounded as route coordinates are, so that their
 * differences stay within +-2 km. */
static int32_t bound_mm(int32_t v)
{
    if (v > ROUTE_COORD_MAX_MM) {
        return ROUTE_COORD_MAX_MM;
    }
    if (v < -ROUTE_COORD_MAX_MM) {
        return -ROUTE_COORD_MAX_MM;
    }
    return v;
}

/* 1 when (dx, dy) is within `r` mm: squares compared without overflow
 * (each at most 65535^2 < 2^32 once both are within r). */
static uint8_t within_mm(int32_t dx, int32_t dy, uint16_t r)
{
    uint32_t ax = (uint32_t)(dx < 0 ? -dx : dx);
    uint32_t ay = (uint32_t)(dy < 0 ? -dy : dy);
    uint32_t r2 = (uint32_t)r * (uint32_t)r;
    if (ax > r || ay > r) {
        return 0u;
    }
    return (uint8_t)(ax * ax <= r2 - ay * ay);
}

/* GO while targets are left, else HOME. */
static uint8_t travel_state(const waypoint_t *self)
{
    return (uint8_t)((self->index < self->route.n) ? WAYPOINT_GO : WAYPOINT_HOME);
}

/* ------------------------------------------------------------ messages */

/* 1 when two routes have the same targets and drop-off (field by field:
 * route_t has padding). */
static uint8_t same_route(const route_t *a, const route_t *b)
{
    uint8_t i;
    if (a->n != b->n || a->drop.x_mm != b->drop.x_mm || a->drop.y_mm != b->drop.y_mm) {
        return 0u;
    }
    for (i = 0u; i < a->n && i < ROUTE_MAX_TARGETS; i++) {
        if (a->target[i].x_mm != b->target[i].x_mm || a->target[i].y_mm != b->target[i].y_mm) {
            return 0u;
        }
    }
    return 1u;
}

/* One host message this period: a route starts (or replaces) the route;
 * anything malformed is counted and changes nothing. */
static void take_message(waypoint_t *self, hal_t *hal)
{
    uint8_t buf[HAL_HOST_MSG_MAX];
    uint8_t len = 0u;
    route_t next;
    hal_status_t s = hal_host_receive(hal, buf, (uint8_t)sizeof buf, &len);
    if (s == HAL_ERR_RANGE) {
        /* Longer than any host message may be: it stays in the queue and
         * is counted each period it is met. */
        self->bad_msgs++;
        return;
    }
    if (s != HAL_OK) {
        return;   /* none waiting, or no host link */
    }
    if (len > sizeof buf || route_msg_decode(buf, len, &next) != ROUTE_MSG_OK) {
        self->bad_msgs++;
        return;
    }
    if (self->routes > 0u && same_route(&next, &self->route) != 0u) {
        return;   /* the host's resend of the route being followed */
    }
    self->route = next;
    self->routes++;
    self->index = 0u;
    self->timer = 0u;
    if (self->state != WAYPOINT_AVOID && self->state != WAYPOINT_AVOID_RUN) {
        self->state = WAYPOINT_GO;
    }
}

/* ------------------------------------------------------------ motion */

/* Toward a bearing error: in place when it is large, else forward with a
 * proportional difference (repatt.c's steer, with the threshold a
 * parameter and the difference kept when a wheel would saturate). */
static void steer(const waypoint_t *self, hal_t *hal, int16_t error_mrad)
{
    const waypoint_params_t *p = &self->params;
    int16_t w = p->turn_speed_steps_s;
    int32_t d, v;
    if (error_mrad > (int32_t)p->turn_in_place_mrad) {
        hal_set_wheel_speeds(hal, (int16_t)-w, w);
        return;
    }
    if (error_mrad < -(int32_t)p->turn_in_place_mrad) {
        hal_set_wheel_speeds(hal, w, (int16_t)-w);
        return;
    }
    d = motion_clamp_speed((int32_t)p->steer_gain * (int32_t)error_mrad / 1000);
    /* Slower rather than a saturated wheel: the difference, which sets
     * the turn, is kept whole. */
    v = (int32_t)p->speed_steps_s;
    if (v > HAL_WHEEL_SPEED_MAX - (d < 0 ? -d : d)) {
        v = HAL_WHEEL_SPEED_MAX - (d < 0 ? -d : d);
    }
    hal_set_wheel_speeds(hal, motion_clamp_speed(v - d), motion_clamp_speed(v + d));
}

/* The tracker's fix, if there is one and it is fresh enough. */
static uint8_t usable_pose(const waypoint_t *self, hal_t *hal, hal_pose_t *pose)
{
    if (hal_pose(hal, pose) != HAL_OK) {
        return 0u;
    }
    return (uint8_t)(pose->age_ms <= self->params.pose_max_age_ms);
}

static void start_avoidance(waypoint_t *self, hal_t *hal, uint8_t where)
{
    const waypoint_params_t *p = &self->params;
    self->oae_count++;
    self->state = WAYPOINT_AVOID;
    avoid_start_turn(&self->avoid, &self->rng, where, p->side_turn_mrad);
    if (avoid_turn_step(&self->avoid, hal, p->turn_speed_steps_s) != 0u) {
        return;
    }
    /* A turn of 0 steps (side_turn_mrad 0): the run at once. */
    self->state = WAYPOINT_AVOID_RUN;
    avoid_start_run(&self->avoid, &self->rng, p->oa_run_max_mm);
    if (avoid_run_step(&self->avoid, hal, p->speed_steps_s) == 0u) {
        stop(hal);   /* a run of 0 mm: GO or HOME again next period */
        self->state = travel_state(self);
    }
}

static void start_pick(waypoint_t *self, hal_t *hal)
{
    self->state = WAYPOINT_PICK;
    self->timer = 1u;   /* this period is the first stood still */
    stop(hal);
}

/* GO and HOME: avoid (or, blocked within reach of the target, pick it up
 * from there), stop without a fix, arrive, or steer. */
static void travel(waypoint_t *self, hal_t *hal)
{
    const waypoint_params_t *p = &self->params;
    const route_point_t *goal = (self->index < self->route.n) ? &self->route.target[self->index]
                                                              : &self->route.drop;
    hal_pose_t pose;
    int32_t dx = 0, dy = 0;
    uint8_t where = avoid_obstacle(hal, p->avoid_enter);
    uint8_t fix = usable_pose(self, hal, &pose);
    if (fix != 0u) {
        dx = goal->x_mm - bound_mm(pose.x_mm);
        dy = goal->y_mm - bound_mm(pose.y_mm);
    }
    if (where != AVOID_NONE) {
        if (fix != 0u && self->state == WAYPOINT_GO && p->reach_mm != 0u && within_mm(dx, dy, p->reach_mm) != 0u) {
            start_pick(self, hal);
            return;
        }
        start_avoidance(self, hal, where);
        return;
    }
    if (fix == 0u) {
        self->has_pose = 0u;
        self->no_pose++;
        stop(hal);
        return;
    }
    self->has_pose = 1u;
    self->bearing_mrad = (int16_t)odo_wrap_mrad((int32_t)odo_atan2_mrad(dy, dx) - pose.heading_mrad);
    if (self->state == WAYPOINT_GO && within_mm(dx, dy, p->arrive_mm) != 0u) {
        start_pick(self, hal);
        return;
    }
    if (self->state == WAYPOINT_HOME && within_mm(dx, dy, p->home_radius_mm) != 0u) {
        self->state = WAYPOINT_DONE;
        self->deliveries++;
        stop(hal);
        return;
    }
    steer(self, hal, self->bearing_mrad);
}

/* ------------------------------------------------------------ states */

/* Wheels (0, 0) for the whole wait, then on to the next point. */
static void pick_step(waypoint_t *self, hal_t *hal)
{
    if (self->timer < motion_periods(hal, self->params.pick_time_ms)) {
        self->timer++;
        stop(hal);
        return;
    }
    self->picks++;
    self->index++;
    self->timer = 0u;
    self->state = travel_state(self);
    travel(self, hal);
}

static void avoid_turn_state(waypoint_t *self, hal_t *hal)
{
    const waypoint_params_t *p = &self->params;
    if (avoid_turn_step(&self->avoid, hal, p->turn_speed_steps_s) != 0u) {
        return;
    }
    self->state = WAYPOINT_AVOID_RUN;
    avoid_start_run(&self->avoid, &self->rng, p->oa_run_max_mm);
    if (avoid_run_step(&self->avoid, hal, p->speed_steps_s) != 0u) {
        return;
    }
    self->state = travel_state(self);   /* a run of 0 mm */
    travel(self, hal);
}

static void avoid_run_state(waypoint_t *self, hal_t *hal)
{
    const waypoint_params_t *p = &self->params;
    uint8_t where = avoid_obstacle(hal, p->avoid_enter);
    if (where != AVOID_NONE) {
        start_avoidance(self, hal, where);   /* another obstacle on the way */
        return;
    }
    if (avoid_run_step(&self->avoid, hal, p->speed_steps_s) != 0u) {
        return;
    }
    self->state = travel_state(self);   /* run done */
    travel(self, hal);
}

/* What the last command did to a turn or run in progress: the counters
 * are read every period, so that a manoeuvre starts from the right count. */
static void count_wheels(waypoint_t *self, hal_t *hal)
{
    int16_t l, r;
    uint8_t phase = (uint8_t)AVOID_IDLE;
    hal_wheel_steps(hal, &l, &r);
    if (self->state == WAYPOINT_AVOID) {
        phase = (uint8_t)AVOID_TURNING;
    } else if (self->state == WAYPOINT_AVOID_RUN) {
        phase = (uint8_t)AVOID_RUNNING;
    }
    if (self->primed != 0u) {
        avoid_count(&self->avoid, phase, odo_counter_delta(l, self->last_left),
                    odo_counter_delta(r, self->last_right));
    }
    self->primed = 1u;
    self->last_left = l;
    self->last_right = r;
}

void waypoint_step(waypoint_t *self, hal_t *hal)
{
    count_wheels(self, hal);
    take_message(self, hal);

    switch (self->state) {
    case WAYPOINT_WAIT_ROUTE:
    case WAYPOINT_DONE:
        stop(hal);
        break;
    case WAYPOINT_GO:
    case WAYPOINT_HOME:
        travel(self, hal);
        break;
    case WAYPOINT_PICK:
        pick_step(self, hal);
        break;
    case WAYPOINT_AVOID:
        avoid_turn_state(self, hal);
        break;
    case WAYPOINT_AVOID_RUN:
        avoid_run_state(self, hal);
        break;
    default:
        /* Not a state (corrupted memory): still, waiting for a route. */
        self->state = WAYPOINT_WAIT_ROUTE;
        stop(hal);
        break;
    }
}

const char *waypoint_state_name(const waypoint_t *self)
{
    switch (self->state) {
    case WAYPOINT_WAIT_ROUTE: return "wait_route";
    case WAYPOINT_GO: return "go";
    case WAYPOINT_PICK: return "pick";
    case WAYPOINT_HOME: return "home";
    case WAYPOINT_DONE: return "done";
    case WAYPOINT_AVOID: return "avoid";
    case WAYPOINT_AVOID_RUN: return "avoid_run";
    default: return "?";
    }
}
