/*
 * test_waypoint.c - the route follower (firmware/waypoint) on a fake HAL:
 * waiting for a route, starting and replacing one, steering (wheel signs
 * for a waypoint ahead, left, right, behind), the pick-up wait of exactly
 * pick_time, homing and done, malformed messages, a lost or stale pose,
 * RepAtt's obstacle avoidance, closed loops over five targets, and
 * hostile input.  The fake HAL does not move the robot: step() integrates
 * the commanded wheel speeds (differential drive, hal/units.h's e-puck:
 * 41 mm wheels, 1000 steps a turn, 53 mm apart) into the step counters and
 * a true pose in the arena frame, which the fake tracker reports.  About
 * 0.02 s (ASan/UBSan: 0.2 s).
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fake_hal.h"
#include "fake_drive.h"
#include "waypoint/waypoint.h"
#include "units.h"

#define M_PI UNITS_PI
#define PERIOD_MS 25u
/* pick_time_ms (5000) in 25 ms periods. */
#define PICK_PERIODS 200u

static hal_t H;
static waypoint_t W;
/* The robot as the tracker sees it (arena frame, mm, rad), the wheels'
 * exact steps, and whether the tracker reports it. */
static fake_drive_t D;
static int tracking;
/* The tracker's fix period in control periods (1: every period, age 0). */
static uint32_t fix_every;
static uint32_t steps_done;
static hal_pose_t last_fix;

static void start_with(const waypoint_params_t *p, double x, double y, double th)
{
    fake_hal_init(&H, 5u);
    H.period_ms = PERIOD_MS;
    memset(&W, 0, sizeof W);
    waypoint_init(&W, p, 42u);
    fake_drive_start(&D, x, y, th);
    tracking = 1;
    fix_every = 1u;
    steps_done = 0u;
}

static void start_at(double x, double y, double th)
{
    waypoint_params_t p;
    waypoint_default_params(&p);
    start_with(&p, x, y, th);
}

/* The tracker's view of the true pose now: a fix every fix_every periods,
 * aged by the periods since. */
static void update_tracker(void)
{
    if (!tracking) {
        fake_hal_lose_pose(&H);
        return;
    }
    if (steps_done % fix_every == 0u) {
        last_fix.x_mm = (int32_t)lround(D.x);
        last_fix.y_mm = (int32_t)lround(D.y);
        last_fix.heading_mrad = (int16_t)lround(fake_drive_wrap_pi(D.th) * 1000.0);
        if (last_fix.heading_mrad <= -3142) {
            last_fix.heading_mrad = 3142;
        }
    }
    fake_hal_set_pose(&H, last_fix.x_mm, last_fix.y_mm, last_fix.heading_mrad,
                      (uint16_t)((steps_done % fix_every) * PERIOD_MS));
}

/* One control period: the tracker, the controller, then the wheels move as
 * commanded. */
static void step(void)
{
    update_tracker();
    waypoint_step(&W, &H);
    fake_drive_move(&D, &H, PERIOD_MS);
    fake_hal_end_step(&H);
    steps_done++;
}

static void steps(uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; i++) {
        step();
    }
}

/* Queues a route of `n` targets (x, y pairs in `xy`) and the drop-off. */
static void send_route(uint8_t n, const int32_t *xy, int32_t drop_x, int32_t drop_y)
{
    route_t r;
    uint8_t buf[HAL_HOST_MSG_MAX];
    uint8_t i, len;
    memset(&r, 0, sizeof r);
    r.n = n;
    for (i = 0; i < n; i++) {
        r.target[i].x_mm = xy[2u * i];
        r.target[i].y_mm = xy[2u * i + 1u];
    }
    r.drop.x_mm = drop_x;
    r.drop.y_mm = drop_y;
    len = route_msg_encode(&r, buf, (uint8_t)sizeof buf);
    assert_true(len > 0u);
    assert_true(fake_hal_host_push(&H, buf, len));
}

static void send_bytes(const uint8_t *bytes, uint8_t len)
{
    assert_true(fake_hal_host_push(&H, bytes, len));
}

static double dist_to(double x, double y)
{
    return sqrt((D.x - x) * (D.x - x) + (D.y - y) * (D.y - y));
}

/* ------------------------------------------------------------ waiting */

/* Without a route the robot stands still, polling the host every period;
 * the defaults are in their descriptors' ranges. */
static void test_waits_without_route(void **state)
{
    const param_desc_t *d;
    waypoint_params_t p;
    (void)state;
    start_at(0.0, 0.0, 0.0);
    steps(400u);
    assert_int_equal(W.state, WAYPOINT_WAIT_ROUTE);
    assert_string_equal(waypoint_state_name(&W), "wait_route");
    assert_int_equal(H.left, 0);
    assert_int_equal(H.right, 0);
    assert_int_equal(H.host_polls, 400u);
    assert_true(D.x == 0.0 && D.y == 0.0);
    assert_int_equal(W.routes, 0u);
    assert_int_equal(W.no_pose, 0u);   /* waiting needs no fix */

    /* Also without a host link at all. */
    H.host_unavailable = 1u;
    steps(10u);
    assert_int_equal(W.state, WAYPOINT_WAIT_ROUTE);
    assert_int_equal(W.bad_msgs, 0u);

    waypoint_default_params(&p);
    for (d = waypoint_def.params; d->key != NULL; d++) {
        double v = 0.0;
        const uint8_t *f = (const uint8_t *)&p + d->offset;
        if (d->type == PARAM_I16) {
            int16_t x;
            memcpy(&x, f, sizeof x);
            v = x;
        } else {
            uint16_t x;
            assert_int_equal(d->type, PARAM_U16);
            memcpy(&x, f, sizeof x);
            v = x;
        }
        assert_true(v >= d->min && v <= d->max);
    }
    assert_string_equal(waypoint_def.name, "waypoint");
    assert_int_equal(p.speed_steps_s, 776);
    assert_int_equal(p.pick_time_ms, 5000u);
}

/* A route message starts the route toward its first target, at once. */
static void test_route_starts(void **state)
{
    static const int32_t xy[] = { 500, 0, 800, 200 };
    (void)state;
    start_at(0.0, 0.0, 0.0);
    steps(3u);
    send_route(2u, xy, 0, 0);
    step();
    assert_int_equal(W.state, WAYPOINT_GO);
    assert_string_equal(waypoint_state_name(&W), "go");
    assert_int_equal(W.routes, 1u);
    assert_int_equal(W.index, 0u);
    assert_int_equal(W.route.n, 2u);
    assert_int_equal(H.left, 776);   /* straight ahead */
    assert_int_equal(H.right, 776);
    steps(40u);
    assert_true(D.x > 90.0 && fabs(D.y) < 1.0);
}

/* ------------------------------------------------------------ steering */

/* The wheels for a waypoint (tx, ty) seen from (0, 0) heading th. */
static void wheels_for(double th, int32_t tx, int32_t ty)
{
    int32_t xy[2];
    xy[0] = tx;
    xy[1] = ty;
    start_at(0.0, 0.0, th);
    send_route(1u, xy, 0, 0);
    step();
    assert_int_equal(W.state, WAYPOINT_GO);
}

static void test_steering_signs(void **state)
{
    (void)state;
    /* Ahead: straight at speed. */
    wheels_for(0.0, 600, 0);
    assert_int_equal(H.left, 776);
    assert_int_equal(H.right, 776);
    /* Ahead-left: forward, the right wheel faster; ahead-right: the left. */
    wheels_for(0.0, 600, 200);
    assert_true(H.right > H.left && H.left > 0);
    wheels_for(0.0, 600, -200);
    assert_true(H.left > H.right && H.right > 0);
    /* Proportional: 0.32 rad right is 322 steps/s each way (atan2 within
     * 5 mrad); the left wheel would be above 1000 steps/s, so both slow by
     * the excess and the difference is kept. */
    assert_true(abs((H.left - H.right) / 2 - 322) <= 6);
    assert_int_equal(H.left, 1000);
    /* Behind (beyond 90 deg): in place, CCW for a point behind-left, CW
     * behind-right. */
    wheels_for(0.0, -600, 50);
    assert_int_equal(H.left, -776);
    assert_int_equal(H.right, 776);
    wheels_for(0.0, -600, -50);
    assert_int_equal(H.left, 776);
    assert_int_equal(H.right, -776);
    /* The frame: heading +90 deg (facing +y), a point at +x is on the
     * right; facing -y, on the left.  Heading is CCW from +x. */
    wheels_for(M_PI / 2.0, 600, 400);
    assert_true(H.left > H.right);
    wheels_for(-M_PI / 2.0, 600, -400);
    assert_true(H.right > H.left);
    /* Heading near +-pi (facing -x): a point at -x is ahead. */
    wheels_for(M_PI - 0.0005, -600, 0);
    assert_true(abs(H.left - 776) <= 3 && abs(H.right - 776) <= 3);
    wheels_for(-M_PI + 0.0005, -600, 0);
    assert_true(abs(H.left - 776) <= 3 && abs(H.right - 776) <= 3);
}

/* ------------------------------------------------------------ picking */

/* Arrival: wheels (0, 0) for exactly pick_time (200 periods of 25 ms),
 * then on to the next target; the count of waits done.  With 100 ms
 * periods, 50; 4990 ms rounds up to 200 periods. */
static void test_pick_exactly(void **state)
{
    static const int32_t xy[] = { 20, 10, 600, 10 };
    static const uint16_t periods_ms[] = { 25u, 100u, 25u };
    static const uint16_t pick_ms[] = { 5000u, 5000u, 4990u };
    static const uint32_t want[] = { 200u, 50u, 200u };
    uint32_t k;
    (void)state;
    for (k = 0; k < 3u; k++) {
        waypoint_params_t p;
        uint32_t still = 0;
        waypoint_default_params(&p);
        p.pick_time_ms = pick_ms[k];
        start_with(&p, 0.0, 0.0, 0.0);
        H.period_ms = periods_ms[k];
        send_route(2u, xy, 0, 0);
        step();   /* 22 mm from the first target: there */
        assert_int_equal(W.state, WAYPOINT_PICK);
        assert_string_equal(waypoint_state_name(&W), "pick");
        while (H.left == 0 && H.right == 0 && still < 1000u) {
            assert_int_equal(H.wheel_calls, still + 1u);   /* commanded each period */
            still++;
            if (still < want[k]) {
                assert_int_equal(W.picks, 0u);
            }
            waypoint_step(&W, &H);   /* still: no motion to integrate */
            fake_hal_end_step(&H);
        }
        assert_int_equal(still, want[k]);
        assert_int_equal(W.picks, 1u);
        assert_int_equal(W.index, 1u);
        assert_int_equal(W.state, WAYPOINT_GO);
        assert_true(H.left > 0 && H.right > 0);   /* toward (600, 10) */
    }
}

/* After the last target, home to the drop-off; within home_radius_mm,
 * done and still, until a new route. */
static void test_home_and_done(void **state)
{
    static const int32_t xy[] = { 300, 0 }, other[] = { 0, 300 };
    uint32_t i;
    (void)state;
    start_at(0.0, 0.0, 0.0);
    send_route(1u, xy, 0, 0);
    for (i = 0; i < 2000u && W.state != WAYPOINT_PICK; i++) {
        step();
    }
    assert_int_equal(W.state, WAYPOINT_PICK);
    assert_true(dist_to(300.0, 0.0) <= 30.5);   /* arrive_mm on the tracker's whole mm */
    steps(PICK_PERIODS);
    assert_int_equal(W.state, WAYPOINT_HOME);
    assert_string_equal(waypoint_state_name(&W), "home");
    assert_int_equal(W.index, 1u);
    for (i = 0; i < 2000u && W.state != WAYPOINT_DONE; i++) {
        step();
    }
    assert_int_equal(W.state, WAYPOINT_DONE);
    assert_string_equal(waypoint_state_name(&W), "done");
    assert_true(dist_to(0.0, 0.0) <= 100.0 && dist_to(0.0, 0.0) > 90.0);
    assert_int_equal(W.deliveries, 1u);
    {
        double x = D.x, y = D.y;
        steps(500u);
        assert_int_equal(W.state, WAYPOINT_DONE);
        assert_int_equal(H.left, 0);
        assert_int_equal(H.right, 0);
        assert_true(D.x == x && D.y == y);
    }
    /* The same route again is a resend: still done (a host that resends
     * routes must not make robots run them twice); a new route starts. */
    send_route(1u, xy, 0, 0);
    step();
    assert_int_equal(W.state, WAYPOINT_DONE);
    send_route(1u, other, 0, 0);
    step();
    assert_int_equal(W.state, WAYPOINT_GO);
    assert_int_equal(W.routes, 2u);
    assert_int_equal(W.index, 0u);
}

/* ------------------------------------------------------------ messages */

static void test_malformed_ignored(void **state)
{
    static const int32_t xy[] = { 800, 0, 800, 400 };
    static const uint8_t wrong_kind[26] = { 0x72, 0x02 };
    static const uint8_t zero_targets[10] = { 0x52, 0x00 };
    static const uint8_t seven_targets[66] = { 0x52, 0x07 };
    static const uint8_t short_len[25] = { 0x52, 0x02 };
    static const uint8_t empty[1] = { 0 };
    uint8_t far[26] = { 0x52, 0x02, 0x7F, 0xFF, 0xFF, 0xFF };
    (void)state;
    start_at(0.0, 0.0, 0.0);
    send_bytes(wrong_kind, (uint8_t)sizeof wrong_kind);
    send_bytes(zero_targets, (uint8_t)sizeof zero_targets);
    send_bytes(seven_targets, 64u);   /* cut to the HAL's most: its n still says 7 */
    send_bytes(short_len, (uint8_t)sizeof short_len);
    send_bytes(empty, 0u);
    send_bytes(far, (uint8_t)sizeof far);
    steps(10u);
    assert_int_equal(W.bad_msgs, 6u);
    assert_int_equal(W.state, WAYPOINT_WAIT_ROUTE);
    assert_int_equal(W.route.n, 0u);
    assert_int_equal(H.left, 0);

    /* During a route: counted, and the route goes on unchanged. */
    send_route(2u, xy, 0, 0);
    steps(20u);
    assert_int_equal(W.state, WAYPOINT_GO);
    send_bytes(wrong_kind, (uint8_t)sizeof wrong_kind);
    step();
    assert_int_equal(W.bad_msgs, 7u);
    assert_int_equal(W.state, WAYPOINT_GO);
    assert_int_equal(W.route.n, 2u);
    assert_int_equal(W.route.target[0].x_mm, 800);
    assert_int_equal(W.index, 0u);
    assert_int_equal(H.left, 776);

    /* Longer than any host message: it stays in the HAL's queue (hal.h),
     * so it is counted every period it blocks it; the route goes on. */
    {
        uint8_t long_msg[HAL_HOST_MSG_MAX] = { 0x52 };
        send_bytes(long_msg, (uint8_t)(HAL_HOST_MSG_MAX + 1u));
        steps(5u);
        assert_int_equal(W.bad_msgs, 12u);
        assert_int_equal(W.state, WAYPOINT_GO);
        assert_int_equal(H.left, 776);
    }
}

/* A route message during a route replaces it, from its first target: in
 * GO after a pick, during a pick (abandoned), during an avoidance (which
 * finishes first). */
static void test_replaced_route(void **state)
{
    static const int32_t first[] = { 20, 0, 900, 0, 900, 900 };
    static const int32_t second[] = { 0, -700 };
    uint32_t i;
    (void)state;
    start_at(0.0, 0.0, 0.0);
    send_route(3u, first, 0, 0);
    step();
    assert_int_equal(W.state, WAYPOINT_PICK);
    steps(PICK_PERIODS + 20u);
    assert_int_equal(W.index, 1u);
    assert_int_equal(W.state, WAYPOINT_GO);
    /* In GO: the new route's first target (behind-right of the robot now,
     * which faces +x) at once. */
    send_route(1u, second, 100, 100);
    step();
    assert_int_equal(W.routes, 2u);
    assert_int_equal(W.index, 0u);
    assert_int_equal(W.route.n, 1u);
    assert_int_equal(W.route.drop.x_mm, 100);
    assert_int_equal(W.state, WAYPOINT_GO);
    assert_true(H.left > H.right);   /* turning right, toward (0, -700) */

    /* During a pick: abandoned for the new route. */
    start_at(0.0, 0.0, 0.0);
    send_route(3u, first, 0, 0);
    steps(50u);
    assert_int_equal(W.state, WAYPOINT_PICK);
    send_route(1u, second, 0, 0);
    step();
    assert_int_equal(W.state, WAYPOINT_GO);
    assert_int_equal(W.picks, 0u);
    assert_true(H.left != 0 || H.right != 0);

    /* During an avoidance: it finishes, then the new route. */
    start_at(0.0, 0.0, 0.0);
    send_route(2u, first + 2, 0, 0);   /* (900, 0) first */
    steps(5u);
    H.proximity[0] = 2000u;
    step();
    H.proximity[0] = 0u;
    assert_int_equal(W.state, WAYPOINT_AVOID);
    send_route(1u, second, 0, 0);
    step();
    assert_int_equal(W.routes, 2u);
    assert_int_equal(W.index, 0u);
    assert_int_equal(W.state, WAYPOINT_AVOID);
    for (i = 0; i < 1000u && W.state != WAYPOINT_GO; i++) {
        assert_true(W.state == WAYPOINT_AVOID || W.state == WAYPOINT_AVOID_RUN);
        step();
    }
    assert_int_equal(W.state, WAYPOINT_GO);
    assert_int_equal(W.route.target[0].y_mm, -700);
}

/* The same route again is the host's resend: nothing changes, not the
 * target reached nor the count; a different one replaces it. */
static void test_resent_route(void **state)
{
    static const int32_t first[] = { 20, 0, 900, 0 };
    (void)state;
    start_at(0.0, 0.0, 0.0);
    send_route(2u, first, 0, 0);
    steps(PICK_PERIODS + 20u);
    assert_int_equal(W.index, 1u);
    send_route(2u, first, 0, 0);
    step();
    assert_int_equal(W.routes, 1u);
    assert_int_equal(W.index, 1u);
    assert_int_equal(W.state, WAYPOINT_GO);
    send_route(2u, first, 0, 1);   /* another drop-off: another route */
    step();
    assert_int_equal(W.routes, 2u);
    assert_int_equal(W.index, 0u);
}

/* With reach_mm 45, blocked within it of the target (by a wall): picked
 * up from there; blocked farther away: avoided.  By default (0) blocked
 * is avoided however near. */
static void test_blocked_within_reach(void **state)
{
    static const int32_t near[] = { 40, 0 }, far[] = { 60, 0 };
    waypoint_params_t p;
    (void)state;
    start_at(0.0, 0.0, 0.0);
    send_route(1u, near, 0, 0);
    H.proximity[0] = 2000u;
    step();
    assert_int_equal(W.state, WAYPOINT_AVOID);   /* the default: never */

    waypoint_default_params(&p);
    p.reach_mm = 45u;
    start_with(&p, 0.0, 0.0, 0.0);
    send_route(1u, near, 0, 0);
    H.proximity[0] = 2000u;
    step();
    assert_int_equal(W.state, WAYPOINT_PICK);
    assert_int_equal(W.oae_count, 0u);
    assert_true(H.left == 0 && H.right == 0);
    steps(PICK_PERIODS + 1u);
    assert_int_equal(W.picks, 1u);

    start_with(&p, 0.0, 0.0, 0.0);
    send_route(1u, far, 0, 0);
    H.proximity[0] = 2000u;
    step();
    assert_int_equal(W.state, WAYPOINT_AVOID);
    assert_int_equal(W.oae_count, 1u);
}

/* ------------------------------------------------------------ pose */

/* No fix, or one older than pose_max_age_ms (300): wheels (0, 0), counted
 * per period, the state kept; a fix again: on its way. */
static void test_no_pose_stops(void **state)
{
    static const int32_t xy[] = { 900, 0 };
    double x;
    (void)state;
    start_at(0.0, 0.0, 0.0);
    send_route(1u, xy, 0, 0);
    steps(10u);
    assert_int_equal(H.left, 776);
    tracking = 0;
    step();
    assert_int_equal(H.left, 0);
    assert_int_equal(H.right, 0);
    x = D.x;
    steps(39u);
    assert_int_equal(W.no_pose, 40u);
    assert_int_equal(W.state, WAYPOINT_GO);
    assert_int_equal(W.has_pose, 0u);
    assert_true(D.x == x);
    tracking = 1;
    step();
    assert_int_equal(H.left, 776);
    assert_int_equal(W.has_pose, 1u);
    assert_int_equal(W.no_pose, 40u);

    /* Stale: 300 ms is still a fix, 301 ms is not, nor 1001 (the HAL's). */
    fake_hal_set_pose(&H, (int32_t)D.x, 0, 0, 300u);
    waypoint_step(&W, &H);
    assert_int_equal(H.left, 776);
    fake_hal_set_pose(&H, (int32_t)D.x, 0, 0, 301u);
    waypoint_step(&W, &H);
    assert_int_equal(H.left, 0);
    assert_int_equal(W.no_pose, 41u);
    fake_hal_set_pose(&H, (int32_t)D.x, 0, 0, 1001u);
    waypoint_step(&W, &H);
    assert_int_equal(H.left, 0);
    assert_int_equal(W.no_pose, 42u);
    assert_int_equal(W.state, WAYPOINT_GO);
}

/* ------------------------------------------------------------ avoidance */

/* An obstacle at IR sensor `ir` while going: the turn it makes (rad, CCW
 * positive); then the run (straight, at most 165 mm), then GO again. */
static double avoid_turn(uint8_t ir)
{
    static const int32_t xy[] = { 3000, 0 };
    double th0, x0, y0, th1;
    uint32_t i;
    start_at(0.0, 0.0, 0.0);
    send_route(1u, xy, 0, 0);
    step();
    th0 = D.th;
    H.proximity[ir] = 2000u;
    step();
    assert_int_equal(W.state, WAYPOINT_AVOID);
    assert_string_equal(waypoint_state_name(&W), "avoid");
    assert_int_equal(W.oae_count, 1u);
    H.proximity[ir] = 0u;
    for (i = 0; i < 400u && W.state == WAYPOINT_AVOID; i++) {
        assert_true(H.left == -H.right);
        step();
    }
    assert_true(W.state == WAYPOINT_AVOID_RUN || W.state == WAYPOINT_GO);
    x0 = D.x;
    y0 = D.y;
    th1 = D.th;
    for (i = 0; i < 400u && W.state == WAYPOINT_AVOID_RUN; i++) {
        assert_string_equal(waypoint_state_name(&W), "avoid_run");
        assert_true(H.left == H.right && H.left > 0);
        step();
    }
    assert_int_equal(W.state, WAYPOINT_GO);
    assert_true(sqrt((D.x - x0) * (D.x - x0) + (D.y - y0) * (D.y - y0)) <= 165.0 + 3.0);
    return fake_drive_wrap_pi(th1 - th0);
}

static void test_obstacle_avoidance(void **state)
{
    double a;
    uint8_t ir;
    (void)state;
    /* Right side (IR1, IR2): 45 deg to the left; left side (IR5, IR6): to
     * the right (the turn is counted on the steps: within a step's turn). */
    for (ir = 1; ir <= 2u; ir++) {
        a = avoid_turn(ir);
        assert_true(fabs(a - M_PI / 4.0) < 0.01);
    }
    for (ir = 5; ir <= 6u; ir++) {
        a = avoid_turn(ir);
        assert_true(fabs(a + M_PI / 4.0) < 0.01);
    }
    /* In front (IR0, IR7): more than 90 deg, either way. */
    a = avoid_turn(0u);
    assert_true(fabs(a) > M_PI / 2.0 && fabs(a) <= M_PI + 0.01);
    a = avoid_turn(7u);
    assert_true(fabs(a) > M_PI / 2.0 && fabs(a) <= M_PI + 0.01);
    /* At or below avoid_enter (300), and behind (IR3, IR4): no avoidance. */
    {
        static const int32_t xy[] = { 3000, 0 };
        start_at(0.0, 0.0, 0.0);
        send_route(1u, xy, 0, 0);
        H.proximity[0] = 300u;
        H.proximity[2] = 300u;
        H.proximity[3] = 4000u;
        H.proximity[4] = 4000u;
        steps(20u);
        assert_int_equal(W.state, WAYPOINT_GO);
        assert_int_equal(W.oae_count, 0u);
    }
    /* Still robots do not avoid: waiting, picking, done. */
    {
        static const int32_t xy[] = { 10, 0 };
        start_at(0.0, 0.0, 0.0);
        H.proximity[0] = 3000u;
        steps(5u);
        assert_int_equal(W.state, WAYPOINT_WAIT_ROUTE);
        send_route(1u, xy, 2000, 0);
        H.proximity[0] = 0u;
        step();
        assert_int_equal(W.state, WAYPOINT_PICK);
        H.proximity[0] = 3000u;
        steps(20u);
        assert_int_equal(W.state, WAYPOINT_PICK);
        assert_int_equal(W.oae_count, 0u);
    }
    /* Without a fix an obstacle is still avoided (steps, not the pose). */
    {
        static const int32_t xy[] = { 3000, 0 };
        start_at(0.0, 0.0, 0.0);
        send_route(1u, xy, 0, 0);
        step();
        tracking = 0;
        H.proximity[2] = 2000u;
        step();
        assert_int_equal(W.state, WAYPOINT_AVOID);
        assert_true(H.right > 0 && H.left < 0);
    }
}

/* ------------------------------------------------------------ closed loop */

/* Five targets around the arena's centre, home to it: the route is done
 * within 90 s of simulated time.  Every pick-up wait is one the simulator's
 * targets task counts: the robot's centre within its reach (55 mm) of the
 * target, wheels (0, 0) for 200 consecutive periods.  Run with a fix every
 * period (the simulator's tracker) and every 4th period, up to 75 ms old
 * (a 10 Hz tracker over Bluetooth). */
static void closed_loop(uint32_t every, double start_th, uint16_t arrive_mm)
{
    static const int32_t xy[] = { 400, 300, 700, -200, 200, -600, -500, -300, -300, 400 };
    uint32_t i, k = 0, still = 0;
    uint8_t prev = WAYPOINT_GO;
    waypoint_params_t p;
    waypoint_default_params(&p);
    p.arrive_mm = arrive_mm;
    start_with(&p, -100.0, 50.0, start_th);
    fix_every = every;
    send_route(5u, xy, 0, 0);
    for (i = 0; i < 3600u && W.state != WAYPOINT_DONE; i++) {
        step();
        if (H.left == 0 && H.right == 0) {
            still++;
        } else {
            still = 0;
        }
        if (W.state == WAYPOINT_PICK && prev != WAYPOINT_PICK) {
            assert_true(k < 5u);
            /* arrive_mm, and what the robot moved on a fix up to 75 ms old. */
            assert_true(dist_to(xy[2u * k], xy[2u * k + 1u]) <= arrive_mm + 10.0);
        }
        if (prev == WAYPOINT_PICK && W.state != WAYPOINT_PICK) {
            /* Left after exactly the wait; stood within reach all along. */
            assert_true(dist_to(xy[2u * k], xy[2u * k + 1u]) <= 55.0);
            k++;
        }
        if (W.state == WAYPOINT_PICK) {
            assert_true(still >= 1u && still <= PICK_PERIODS);
        }
        prev = W.state;
    }
    assert_int_equal(W.state, WAYPOINT_DONE);
    assert_int_equal(k, 5u);
    assert_int_equal(W.picks, 5u);
    assert_int_equal(W.deliveries, 1u);
    assert_int_equal(W.oae_count, 0u);
    assert_int_equal(W.no_pose, 0u);
    assert_true(dist_to(0.0, 0.0) <= 100.0);
    /* 5 waits of 5 s and about 3.7 m at 0.10 m/s: about 62 s. */
    assert_true(i * PERIOD_MS <= 90000u);
    print_message("closed loop (fix every %u periods, arrive_mm %u): done in %.1f s\n", (unsigned)every,
                  (unsigned)arrive_mm, i * PERIOD_MS / 1000.0);
    steps(200u);
    assert_int_equal(W.state, WAYPOINT_DONE);
    assert_int_equal(H.left, 0);
}

static void test_closed_loop(void **state)
{
    (void)state;
    closed_loop(1u, 0.0, 30u);
    closed_loop(4u, 2.5, 30u);
    closed_loop(1u, 0.0, 10u);
    closed_loop(4u, -1.0, 10u);
    closed_loop(1u, 1.0, 3u);
}

/* A blocked path: an obstacle met on the way (the IR reading while the
 * robot is within 60 mm of a point between two targets) is avoided, and
 * the route still ends at the drop-off point with all its picks. */
static void test_closed_loop_with_obstacle(void **state)
{
    static const int32_t xy[] = { 600, 0, 600, 500 };
    uint32_t i;
    (void)state;
    start_at(0.0, 0.0, 0.0);
    send_route(2u, xy, 0, 0);
    for (i = 0; i < 6000u && W.state != WAYPOINT_DONE; i++) {
        double ox = D.x + 40.0 * cos(D.th), oy = D.y + 40.0 * sin(D.th);
        /* A post at (300, 10): seen by the front sensors when near ahead. */
        H.proximity[0] = H.proximity[7] =
            (uint16_t)(((ox - 300.0) * (ox - 300.0) + (oy - 10.0) * (oy - 10.0) < 30.0 * 30.0) ? 2000u : 0u);
        step();
    }
    assert_int_equal(W.state, WAYPOINT_DONE);
    assert_true(W.oae_count >= 1u);
    assert_int_equal(W.picks, 2u);
}

/* ------------------------------------------------------------ hostile input */

/* Random host messages (routes with coordinates up to the limit, and
 * garbage), poses anywhere in int32 with any heading and age, IR readings,
 * counter jumps and periods: no overflow (UBSan in asan-tests), the state,
 * the route and the wheels stay in range, and every message taken is
 * counted once, as a route or as refused. */
static void test_hostile(void **state)
{
    uint32_t x = 0x9E3779B9u, i, sent = 0;
    (void)state;
    start_at(0.0, 0.0, 0.0);
    for (i = 0; i < 60000u; i++) {
        uint8_t buf[HAL_HOST_MSG_MAX];
        uint8_t k;
        x ^= x << 13; x ^= x >> 17; x ^= x << 5;
        if ((x & 0x1FFu) == 0u && H.host_count < FAKE_HOST_QUEUE_MAX) {
            uint8_t len = (uint8_t)((x >> 8) % (HAL_HOST_MSG_MAX + 1u));
            for (k = 0; k < sizeof buf; k++) {
                x ^= x << 13; x ^= x >> 17; x ^= x << 5;
                buf[k] = (uint8_t)x;
            }
            if (x & 1u) {   /* a well-formed route, coordinates anywhere allowed */
                route_t r;
                memset(&r, 0, sizeof r);
                r.n = (uint8_t)(1u + (x >> 1) % ROUTE_MAX_TARGETS);
                for (k = 0; k <= r.n; k++) {
                    route_point_t *pt = (k < r.n) ? &r.target[k] : &r.drop;
                    x ^= x << 13; x ^= x >> 17; x ^= x << 5;
                    pt->x_mm = (int32_t)(x % 2000001u) - ROUTE_COORD_MAX_MM;
                    pt->y_mm = (int32_t)((x >> 7) % 2000001u) - ROUTE_COORD_MAX_MM;
                }
                len = route_msg_encode(&r, buf, (uint8_t)sizeof buf);
            }
            assert_true(fake_hal_host_push(&H, buf, len));
            sent++;
        }
        x ^= x << 13; x ^= x >> 17; x ^= x << 5;
        switch (x & 7u) {
        case 0: fake_hal_lose_pose(&H); break;
        case 1: fake_hal_set_pose(&H, INT32_MAX, INT32_MIN, 3142, 0u); break;
        case 2: fake_hal_set_pose(&H, INT32_MIN, INT32_MAX, -3141, (uint16_t)(x >> 16)); break;
        case 3:
            if (W.route.n > 0u) {   /* at the current point: picks and deliveries */
                const route_point_t *g = W.index < W.route.n ? &W.route.target[W.index] : &W.route.drop;
                fake_hal_set_pose(&H, g->x_mm, g->y_mm, 0, 0u);
            }
            break;
        default:
            fake_hal_set_pose(&H, (int32_t)(x >> 3) - (int32_t)0x0FFFFFFF, (int32_t)(x >> 8) - 0x007FFFFF,
                              (int16_t)((int32_t)((x >> 4) % 6283u) - 3141), (uint16_t)((x >> 20) % 1200u));
            break;
        }
        memset(H.proximity, 0, sizeof H.proximity);
        if (((x >> 24) & 15u) == 0u) {
            H.proximity[(x >> 5) % HAL_IR_COUNT] = (uint16_t)((x >> 9) & 0xFFFu);
        }
        if ((x & 0x3F00u) == 0u) {
            H.steps_left = (int16_t)(uint16_t)(x >> 16);   /* counter jumps */
        } else {
            H.steps_left = (int16_t)(H.steps_left + H.left / 40);
            H.steps_right = (int16_t)(H.steps_right + H.right / 40);
        }
        H.period_ms = (x & 0x7000u) == 0u ? (uint16_t)((x >> 12) % 3u * 100u) : PERIOD_MS;
        waypoint_step(&W, &H);
        fake_hal_end_step(&H);
        assert_true(W.state <= WAYPOINT_AVOID_RUN);
        assert_true(strcmp(waypoint_state_name(&W), "?") != 0);
        assert_true(W.route.n <= ROUTE_MAX_TARGETS);
        assert_true(W.index <= W.route.n);
        assert_true(H.left >= -1000 && H.left <= 1000 && H.right >= -1000 && H.right <= 1000);
        assert_true(W.bearing_mrad > -3142 && W.bearing_mrad <= 3142);
    }
    assert_int_equal(W.routes + W.bad_msgs, sent - H.host_count);
    print_message("hostile: %u routes, %u refused, %u picks, %u deliveries, %u avoidances\n", (unsigned)W.routes,
                  (unsigned)W.bad_msgs, (unsigned)W.picks, (unsigned)W.deliveries, (unsigned)W.oae_count);
    assert_true(W.routes > 0u && W.bad_msgs > 0u && W.picks > 0u && W.deliveries > 0u && W.oae_count > 0u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_waits_without_route),
        cmocka_unit_test(test_route_starts),
        cmocka_unit_test(test_steering_signs),
        cmocka_unit_test(test_pick_exactly),
        cmocka_unit_test(test_home_and_done),
        cmocka_unit_test(test_malformed_ignored),
        cmocka_unit_test(test_replaced_route),
        cmocka_unit_test(test_resent_route),
        cmocka_unit_test(test_blocked_within_reach),
        cmocka_unit_test(test_no_pose_stops),
        cmocka_unit_test(test_obstacle_avoidance),
        cmocka_unit_test(test_closed_loop),
        cmocka_unit_test(test_closed_loop_with_obstacle),
        cmocka_unit_test(test_hostile),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
