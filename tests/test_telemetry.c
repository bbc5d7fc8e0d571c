/*
 * test_telemetry.c - the simulator's LCM telemetry (sim_host/telemetry):
 * publishing to memq:// (message counts at the configured rates, values
 * equal to the simulation's own, events against ground truth, the run
 * summary), telemetry never changing a run, the --telemetry-rate parser,
 * and the default log file (simulated-time stamps, LCM's log format byte
 * for byte, removed when the run fails).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "sim_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "common/random_walk.h"
#include "swarmsim/metrics.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "core/telemetry.h"
#include "foraging/forager.h"
#include "swarmlcm_event_t.h"
#include "swarmlcm_robot_state_t.h"
#include "swarmlcm_run_info_t.h"
#include "swarmlcm_run_summary_t.h"
#include "swarmlcm_schema_t.h"
#include "swarmlcm_swarm_state_t.h"
#include "tasks/foraging/foraging.h"

#define BASE "../sim_host/scenarios/foraging_base.yaml"
#define WALK "../sim_host/scenarios/random_walk.yaml"
#define MAX_ROBOTS 64
#define MAX_VALUES 64
#define NAME 40

/* Event kinds counted by name. */
static const char *const kinds[] = {
    "oae", "deposits", "state", "escaped", "pickup", "deposit", "token_dropped", "token_lost", NULL
};

/* A schema as a subscriber assembles it. */
typedef struct schema_seen {
    char kind[NAME], name[NAME];
    int n;
    char names[MAX_VALUES][NAME];
    int8_t counters[MAX_VALUES];
} schema_seen_t;

/* What a memq subscriber saw. */
typedef struct seen {
    uint32_t info, swarm, robot, event, summary, schema;
    uint32_t robot_by_id[MAX_ROBOTS];
    uint32_t events_by_kind[8], events_other;
    schema_seen_t schemas[8];
    int n_schemas;
    swarmlcm_robot_state_t last_robot[MAX_ROBOTS];
    float last_values[MAX_ROBOTS][MAX_VALUES];
    char last_state[MAX_ROBOTS][32], last_controller[MAX_ROBOTS][32], last_group[MAX_ROBOTS][32];
    int64_t last_swarm_step;
    int last_swarm_values;
    double swarm_values[MAX_VALUES];
    int swarm_steps_in_order;
    int bad_version;
    double summary_values[METRICS_MAX];
    char summary_names[METRICS_MAX][32];
    int summary_count;
    char summary_hash[17];
    int64_t summary_steps;
    int64_t info_steps;
    int info_groups;
    char info_group0[32];
    uint32_t event_bad_time;
    int64_t now;   /* the utime the sim is at, set by the test */
    swarmlcm_run_info_t_subscription_t *sub_info;
    swarmlcm_swarm_state_t_subscription_t *sub_swarm;
    swarmlcm_robot_state_t_subscription_t *sub_robot;
    swarmlcm_event_t_subscription_t *sub_event;
    swarmlcm_run_summary_t_subscription_t *sub_summary;
    swarmlcm_schema_t_subscription_t *sub_schema;
} seen_t;

static void on_info(const lcm_recv_buf_t *rb, const char *ch, const swarmlcm_run_info_t *m, void *u)
{
    (void)rb;
    (void)ch;
    seen_t *s = u;
    s->info++;
    s->info_steps = m->steps;
    s->info_groups = m->n_groups;
    snprintf(s->info_group0, sizeof s->info_group0, "%s", m->n_groups ? m->group_names[0] : "");
    s->bad_version |= m->version != SWARMLCM_RUN_INFO_T_VERSION;
}

static void on_schema(const lcm_recv_buf_t *rb, const char *ch, const swarmlcm_schema_t *m, void *u)
{
    (void)rb;
    (void)ch;
    seen_t *s = u;
    int k = 0;
    s->schema++;
    s->bad_version |= m->version != SWARMLCM_SCHEMA_T_VERSION;
    while (k < s->n_schemas && strcmp(s->schemas[k].name, m->name) != 0) k++;
    if (k == s->n_schemas && k < 8) s->n_schemas++;
    if (k == 8) return;
    schema_seen_t *sc = &s->schemas[k];
    snprintf(sc->kind, NAME, "%s", m->kind);
    snprintf(sc->name, NAME, "%s", m->name);
    sc->n = m->total;
    for (int i = 0; i < m->n && m->first + i < MAX_VALUES; i++) {
        snprintf(sc->names[m->first + i], NAME, "%s", m->names[i]);
        sc->counters[m->first + i] = m->counters[i];
    }
}

static void on_swarm(const lcm_recv_buf_t *rb, const char *ch, const swarmlcm_swarm_state_t *m, void *u)
{
    (void)rb;
    (void)ch;
    seen_t *s = u;
    if (s->swarm && m->step <= s->last_swarm_step) s->swarm_steps_in_order = 0;
    s->swarm++;
    s->last_swarm_step = m->step;
    s->last_swarm_values = m->n_values;
    for (int k = 0; k < m->n_values && k < MAX_VALUES; k++) s->swarm_values[k] = m->values[k];
    s->bad_version |= m->version != SWARMLCM_SWARM_STATE_T_VERSION;
}

static void on_robot(const lcm_recv_buf_t *rb, const char *ch, const swarmlcm_robot_state_t *m, void *u)
{
    (void)rb;
    (void)ch;
    seen_t *s = u;
    s->robot++;
    s->bad_version |= m->version != SWARMLCM_ROBOT_STATE_T_VERSION;
    if (m->robot_id >= 0 && m->robot_id < MAX_ROBOTS) {
        s->robot_by_id[m->robot_id]++;
        s->last_robot[m->robot_id] = *m;
        s->last_robot[m->robot_id].values = NULL;
        for (int k = 0; k < m->n_values && k < MAX_VALUES; k++) s->last_values[m->robot_id][k] = m->values[k];
        snprintf(s->last_state[m->robot_id], 32, "%s", m->state);
        snprintf(s->last_controller[m->robot_id], 32, "%s", m->controller);
        snprintf(s->last_group[m->robot_id], 32, "%s", m->group);
    }
}

static void on_event(const lcm_recv_buf_t *rb, const char *ch, const swarmlcm_event_t *m, void *u)
{
    (void)rb;
    (void)ch;
    seen_t *s = u;
    int k = 0;
    s->event++;
    while (kinds[k] && strcmp(kinds[k], m->kind) != 0) k++;
    if (kinds[k]) s->events_by_kind[k]++;
    else s->events_other++;
    if (m->utime != s->now) s->event_bad_time++;
    s->bad_version |= m->version != SWARMLCM_EVENT_T_VERSION;
}

static void on_summary(const lcm_recv_buf_t *rb, const char *ch, const swarmlcm_run_summary_t *m, void *u)
{
    (void)rb;
    (void)ch;
    seen_t *s = u;
    s->summary++;
    s->summary_count = m->n_metrics;
    for (int k = 0; k < m->n_metrics && k < METRICS_MAX; k++) {
        snprintf(s->summary_names[k], 32, "%s", m->metric_names[k]);
        s->summary_values[k] = m->metric_values[k];
    }
    snprintf(s->summary_hash, sizeof s->summary_hash, "%s", m->state_hash);
    s->summary_steps = m->steps;
}

static void subscribe_all(lcm_t *lcm, seen_t *s)
{
    s->sub_info = swarmlcm_run_info_t_subscribe(lcm, TELEMETRY_CHANNEL_RUN_INFO, on_info, s);
    s->sub_swarm = swarmlcm_swarm_state_t_subscribe(lcm, TELEMETRY_CHANNEL_SWARM_STATE, on_swarm, s);
    s->sub_robot = swarmlcm_robot_state_t_subscribe(lcm, TELEMETRY_CHANNEL_ROBOT_STATE, on_robot, s);
    s->sub_event = swarmlcm_event_t_subscribe(lcm, TELEMETRY_CHANNEL_EVENT, on_event, s);
    s->sub_summary = swarmlcm_run_summary_t_subscribe(lcm, TELEMETRY_CHANNEL_RUN_SUMMARY, on_summary, s);
    s->sub_schema = swarmlcm_schema_t_subscribe(lcm, TELEMETRY_CHANNEL_SCHEMA, on_schema, s);
}

/* Unsubscribes and closes `t`, expecting success. */
static void close_memq(telemetry_t *t, seen_t *s)
{
    lcm_t *lcm = telemetry_lcm(t);
    char err[SIM_ERR_MAX];
    swarmlcm_run_info_t_unsubscribe(lcm, s->sub_info);
    swarmlcm_swarm_state_t_unsubscribe(lcm, s->sub_swarm);
    swarmlcm_robot_state_t_unsubscribe(lcm, s->sub_robot);
    swarmlcm_event_t_unsubscribe(lcm, s->sub_event);
    swarmlcm_run_summary_t_unsubscribe(lcm, s->sub_summary);
    swarmlcm_schema_t_unsubscribe(lcm, s->sub_schema);
    assert_int_equal(telemetry_close(t, 1, err), 0);
}

static void drain(lcm_t *lcm)
{
    while (lcm_handle_timeout(lcm, 0) > 0) {
    }
}

static telemetry_t *open_memq(const sim_t *sim, double robot_hz, double swarm_hz)
{
    telemetry_options_t opt;
    telemetry_t *t = NULL;
    char err[SIM_ERR_MAX];
    telemetry_default_options(&opt);
    opt.url = "memq://";
    opt.robot_hz = robot_hz;
    opt.swarm_hz = swarm_hz;
    if (telemetry_open(&opt, sim, NULL, &t, err) != 0) fail_msg("%s", err);
    assert_non_null(t);
    assert_non_null(telemetry_lcm(t));
    return t;
}

/* Runs `steps` steps of `sim` with telemetry `t` (NULL: none), as the
 * runner does, draining the memq bus every step into `s`. */
static void run(sim_t *sim, telemetry_t *t, seen_t *s, uint64_t steps)
{
    lcm_t *lcm = telemetry_lcm(t);
    const scenario_t *sc = sim_scenario(sim);
    if (s) s->now = 0;
    telemetry_begin(t, sim, steps);
    if (lcm) drain(lcm);
    for (uint64_t k = 0; k < steps; k++) {
        sim_step(sim);
        if (s) s->now = (int64_t)sim_step_count(sim) * sc->control_period_ms * 1000;
        telemetry_step(t, sim);
        if (lcm) drain(lcm);
    }
    metric_list_t final;
    metrics_final(sim, &final);
    telemetry_end(t, sim, &final, sim_state_hash(sim));
    if (lcm) drain(lcm);
}

static int count_of(const seen_t *s, const char *kind)
{
    for (int k = 0; kinds[k]; k++) {
        if (strcmp(kinds[k], kind) == 0) return (int)s->events_by_kind[k];
    }
    return -1;
}

static const schema_seen_t *schema_named(const seen_t *s, const char *name)
{
    for (int k = 0; k < s->n_schemas; k++) {
        if (strcmp(s->schemas[k].name, name) == 0) return &s->schemas[k];
    }
    fail_msg("no schema named %s", name);
    return NULL;
}

/* Index of value `name` in a schema (fails the test if absent). */
static int column(const schema_seen_t *sc, const char *name)
{
    for (int k = 0; k < sc->n; k++) {
        if (strcmp(sc->names[k], name) == 0) return k;
    }
    fail_msg("schema %s has no %s", sc->name, name);
    return -1;
}

/* The base foraging condition for 2000 steps at the default rates: counts,
 * values and events against the simulation's ground truth, named by the
 * schemas. */
static void test_memq_foraging_run(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(BASE);
    sim_t *sim = fixture_sim(sc, 3);
    seen_t *s = calloc(1, sizeof *s);
    s->swarm_steps_in_order = 1;
    telemetry_t *t = open_memq(sim, TELEMETRY_DEFAULT_ROBOT_HZ, TELEMETRY_DEFAULT_SWARM_HZ);
    subscribe_all(telemetry_lcm(t), s);
    const uint64_t steps = 2000;
    run(sim, t, s, steps);

    uint32_t n = sim_robot_count(sim);   /* 20 foragers and the beacon */
    assert_int_equal(n, 21);
    /* RUN_INFO at 0 and every 10 s (100 steps), each with the schemas of
     * forager, nest_beacon and the swarm; SWARM_STATE every step (10 Hz at
     * 100 ms), 0..2000; ROBOT_STATE every robot every 10 steps. */
    assert_int_equal(s->info, 1 + steps / 100);
    assert_int_equal(s->schema, 3 * (1 + steps / 100));
    assert_int_equal(s->info_steps, steps);
    assert_int_equal(s->info_groups, 2);
    assert_string_equal(s->info_group0, "foragers");
    assert_int_equal(s->swarm, steps + 1);
    assert_true(s->swarm_steps_in_order);
    assert_int_equal(s->robot, n * (steps / 10 + 1));
    for (uint32_t i = 0; i < n; i++) assert_int_equal(s->robot_by_id[i], steps / 10 + 1);
    assert_int_equal(s->summary, 1);
    assert_false(s->bad_version);

    /* The last states are the simulation's, found by the schemas' names. */
    foraging_truth_t f;
    assert_int_equal(foraging_truth(sim, &f), 1);
    uint64_t oaes = 0;
    for (uint32_t i = 0; i < 20; i++) oaes += ((const forager_t *)sim_robot_controller(sim, i))->walk.oae_count;
    const schema_seen_t *sw = schema_named(s, "swarm");
    assert_string_equal(sw->kind, "swarm");
    assert_int_equal(s->last_swarm_step, steps);
    assert_int_equal(s->last_swarm_values, sw->n);
    assert_true(s->swarm_values[column(sw, "time_s")] == steps * 0.1);
    assert_true(s->swarm_values[column(sw, "food_nest")] == f.food);
    assert_true(s->swarm_values[column(sw, "food_collected")] == (double)f.delivered);
    assert_true(s->swarm_values[column(sw, "oae_total")] == (double)oaes);
    assert_true(s->swarm_values[column(sw, "waiting")] + s->swarm_values[column(sw, "searching")]
                + s->swarm_values[column(sw, "returning")] == 20.0);
    const schema_seen_t *fs = schema_named(s, "forager");
    assert_string_equal(fs->kind, "controller");
    assert_int_equal(fs->counters[column(fs, "oae")], 1);
    assert_int_equal(fs->counters[column(fs, "threshold")], 0);
    for (uint32_t i = 0; i < n; i++) {
        double x, y, th;
        sim_robot_pose(sim, i, &x, &y, &th);
        assert_true(s->last_robot[i].x == (float)x && s->last_robot[i].y == (float)y);
        assert_int_equal(s->last_robot[i].utime, (int64_t)steps * 100000);
        assert_string_equal(s->last_controller[i], i < 20 ? "forager" : "nest_beacon");
        assert_string_equal(s->last_group[i], i < 20 ? "foragers" : "nest_beacon");
        assert_string_equal(s->last_state[i], sim_robot_state_name(sim, i));
        if (i < 20) {
            const forager_t *fg = sim_robot_controller(sim, i);
            assert_int_equal(s->last_robot[i].n_values, fs->n);
            assert_true(s->last_values[i][column(fs, "oae")] == (float)fg->walk.oae_count);
            assert_true(s->last_values[i][column(fs, "threshold")] == fg->theta);
            assert_true(s->last_values[i][column(fs, "n")] == (float)fg->n);
        }
    }

    /* Events: every OAE, pick-up and deposit, told once at its step. */
    assert_int_equal(s->event_bad_time, 0);
    assert_int_equal(count_of(s, "oae"), oaes);
    assert_int_equal(count_of(s, "deposit"), f.delivered);
    assert_int_equal(count_of(s, "token_dropped"), f.dropped);
    uint32_t carrying = 0;
    for (uint32_t i = 0; i < 20; i++) carrying += foraging_carried(sim, i) >= 0;
    assert_int_equal(count_of(s, "pickup"), f.delivered + f.dropped + carrying);
    assert_true(f.delivered >= 5);
    assert_true(count_of(s, "state") >= (int)(2 * f.delivered));
    assert_int_equal(s->events_other, 0);

    /* The summary is metrics_final's, with the state hash. */
    metric_list_t final;
    metrics_final(sim, &final);
    assert_int_equal(s->summary_count, final.count);
    for (unsigned k = 0; k < final.count; k++) {
        assert_string_equal(s->summary_names[k], final.name[k]);
        assert_true(s->summary_values[k] == final.value[k] || (isnan(s->summary_values[k]) && isnan(final.value[k])));
    }
    char hash[17];
    snprintf(hash, sizeof hash, "%016llx", (unsigned long long)sim_state_hash(sim));
    assert_string_equal(s->summary_hash, hash);
    assert_int_equal(s->summary_steps, steps);

    close_memq(t, s);
    sim_destroy(sim);
    free(s);
    scenario_free(sc);
    free(sc);
}

/* Rates: 2 Hz robot states and 1 Hz swarm states, or none at all; a
 * controller with one counter and states, and no task. */
static void test_memq_rates(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(WALK);
    const uint64_t steps = 300;   /* 30 s */
    for (int pass = 0; pass < 2; pass++) {
        sim_t *sim = fixture_sim(sc, 1);
        seen_t *s = calloc(1, sizeof *s);
        telemetry_t *t = open_memq(sim, pass ? 0.0 : 2.0, pass ? 0.0 : 1.0);
        subscribe_all(telemetry_lcm(t), s);
        run(sim, t, s, steps);
        uint32_t n = sim_robot_count(sim);
        uint64_t oaes = 0;
        for (uint32_t i = 0; i < n; i++) oaes += ((const random_walk_t *)sim_robot_controller(sim, i))->oae_count;
        assert_int_equal(s->robot, pass ? 0 : n * (steps / 5 + 1));
        assert_int_equal(s->swarm, pass ? 0 : steps / 10 + 1);
        assert_int_equal(s->info, 1 + steps / 100);
        assert_int_equal(s->summary, 1);
        assert_int_equal(count_of(s, "oae"), oaes);
        assert_true(count_of(s, "state") > 0);            /* forward, tumble, avoid */
        assert_int_equal(count_of(s, "pickup"), 0);
        if (!pass) {
            const schema_seen_t *sw = schema_named(s, "swarm");
            assert_int_equal(sw->n, 6);   /* step, time_s, oae_total, contacts x2, distance: no task */
            assert_string_equal(s->last_controller[0], "random_walk");
            assert_int_equal(s->last_robot[0].n_values, 1);
            assert_true(s->last_values[0][0] == (float)((const random_walk_t *)sim_robot_controller(sim, 0))->oae_count);
        }
        close_memq(t, s);
        sim_destroy(sim);
        free(s);
    }
    scenario_free(sc);
    free(sc);
}

/* Telemetry only reads: the same run with and without it ends in the same
 * state (the sensor summaries come from the controllers' own readings). */
static void test_telemetry_does_not_change_a_run(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(BASE);
    sim_t *a = fixture_sim(sc, 11), *b = fixture_sim(sc, 11);
    telemetry_t *t = open_memq(b, 10.0, 10.0);
    seen_t *s = calloc(1, sizeof *s);
    subscribe_all(telemetry_lcm(t), s);
    run(a, NULL, NULL, 1500);
    run(b, t, s, 1500);
    assert_int_equal(sim_state_hash(a), sim_state_hash(b));
    assert_true(s->robot > 0);
    char err[SIM_ERR_MAX];
    close_memq(t, s);
    assert_int_equal(telemetry_close(NULL, 1, err), 0);   /* NULL is nothing */
    sim_destroy(a);
    sim_destroy(b);
    free(s);
    scenario_free(sc);
    free(sc);
}

static void test_parse_rate(void **state)
{
    (void)state;
    telemetry_options_t o;
    telemetry_default_options(&o);
    assert_true(o.enabled && !o.url && o.robot_hz == 1.0 && o.swarm_hz == 10.0 && o.realtime == 0.0);
    assert_int_equal(telemetry_parse_rate("2", &o), 0);
    assert_true(o.robot_hz == 2.0 && o.swarm_hz == 10.0);
    assert_int_equal(telemetry_parse_rate("0.5,1", &o), 0);
    assert_true(o.robot_hz == 0.5 && o.swarm_hz == 1.0);
    assert_int_equal(telemetry_parse_rate("0,0", &o), 0);
    assert_true(o.robot_hz == 0.0 && o.swarm_hz == 0.0);
    const char *bad[] = { "", "-1", "abc", "1,", ",1", "1,x", "2000", "1,2,3", "nan", "inf", " 1" };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        o.robot_hz = 7.0;
        assert_int_equal(telemetry_parse_rate(bad[k], &o), -1);
        assert_true(o.robot_hz == 7.0);
    }
}

/* Disabled telemetry is NULL, and every call takes NULL. */
static void test_disabled(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(WALK);
    sim_t *sim = fixture_sim(sc, 1);
    telemetry_options_t o;
    telemetry_t *t = (telemetry_t *)&o;
    char err[SIM_ERR_MAX];
    telemetry_default_options(&o);
    o.enabled = 0;
    assert_int_equal(telemetry_open(&o, sim, "/nonexistent/x.lcmlog", &t, err), 0);
    assert_null(t);
    run(sim, NULL, NULL, 10);
    assert_int_equal(telemetry_message_count(NULL), 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* Reads a whole file. */
static uint8_t *slurp(const char *path, long *len)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    *len = ftell(f);
    fseek(f, 0, SEEK_SET);
    uint8_t *b = malloc((size_t)*len + 1);
    assert_int_equal(fread(b, 1, (size_t)*len, f), (size_t)*len);
    fclose(f);
    return b;
}

/* The default sink: an LCM log whose timestamps are the simulated time,
 * written as lcm_eventlog writes it (the events, read back with
 * lcm_eventlog and written again with lcm_eventlog_write_event, give the
 * same bytes), in place only once closed with keep. */
static void test_log_file(void **state)
{
    (void)state;
    char dir[] = "/tmp/test_telemetry_XXXXXX", path[256], tmp[300], copy[300], err[SIM_ERR_MAX];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/" TELEMETRY_LOG_NAME, dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    snprintf(copy, sizeof copy, "%s/copy.lcmlog", dir);
    scenario_t *sc = fixture_load(BASE);
    sim_t *sim = fixture_sim(sc, 5);
    telemetry_options_t o;
    telemetry_t *t = NULL;
    telemetry_default_options(&o);
    assert_int_equal(telemetry_open(&o, sim, path, &t, err), 0);
    assert_non_null(t);
    assert_null(telemetry_lcm(t));
    run(sim, t, NULL, 600);
    uint64_t messages = telemetry_message_count(t);
    assert_int_equal(access(path, F_OK), -1);   /* not yet in place */
    assert_int_equal(access(tmp, F_OK), 0);
    assert_int_equal(telemetry_close(t, 1, err), 0);
    assert_int_equal(access(tmp, F_OK), -1);

    lcm_eventlog_t *in = lcm_eventlog_create(path, "r"), *out = lcm_eventlog_create(copy, "w");
    assert_non_null(in);
    assert_non_null(out);
    lcm_eventlog_event_t *ev;
    uint64_t count = 0;
    int64_t last = -1;
    int saw_summary = 0;
    while ((ev = lcm_eventlog_read_next_event(in)) != NULL) {
        assert_int_equal(ev->eventnum, (int64_t)count);
        assert_true(ev->timestamp >= last);                     /* simulated time, in order */
        assert_true(ev->timestamp % 100000 == 0 && ev->timestamp <= 600 * 100000);
        last = ev->timestamp;
        if (strcmp(ev->channel, TELEMETRY_CHANNEL_SWARM_STATE) == 0) {
            swarmlcm_swarm_state_t m;
            assert_true(swarmlcm_swarm_state_t_decode(ev->data, 0, ev->datalen, &m) > 0);
            assert_int_equal(m.utime, ev->timestamp);
            assert_int_equal(m.step * 100000, ev->timestamp);
            swarmlcm_swarm_state_t_decode_cleanup(&m);
        }
        saw_summary |= strcmp(ev->channel, TELEMETRY_CHANNEL_RUN_SUMMARY) == 0;
        assert_int_equal(lcm_eventlog_write_event(out, ev), 0);
        lcm_eventlog_free_event(ev);
        count++;
    }
    lcm_eventlog_destroy(in);
    lcm_eventlog_destroy(out);
    assert_int_equal(count, messages);
    assert_true(saw_summary);
    assert_int_equal(last, 600 * 100000);
    long la, lb;
    uint8_t *a = slurp(path, &la), *b = slurp(copy, &lb);
    assert_int_equal(la, lb);
    assert_memory_equal(a, b, (size_t)la);
    free(a);
    free(b);
    remove(copy);
    remove(path);

    /* A run that failed leaves no log. */
    assert_int_equal(telemetry_open(&o, sim, path, &t, err), 0);
    telemetry_begin(t, sim, 10);
    assert_int_equal(telemetry_close(t, 0, err), 0);
    assert_int_equal(access(path, F_OK), -1);
    assert_int_equal(access(tmp, F_OK), -1);
    /* An unwritable place is an error with a message. */
    assert_int_equal(telemetry_open(&o, sim, "/nonexistent/dir/telemetry.lcmlog", &t, err), -1);
    assert_null(t);
    assert_non_null(strstr(err, "cannot write"));
    rmdir(dir);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* A bad URL is an error with a message, not a crash. */
static void test_bad_url(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(WALK);
    sim_t *sim = fixture_sim(sc, 1);
    telemetry_options_t o;
    telemetry_t *t = NULL;
    char err[SIM_ERR_MAX];
    telemetry_default_options(&o);
    o.url = "nosuchprovider://x";
    assert_int_equal(telemetry_open(&o, sim, NULL, &t, err), -1);
    assert_null(t);
    assert_non_null(strstr(err, "nosuchprovider://x"));
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_memq_foraging_run),
        cmocka_unit_test(test_memq_rates),
        cmocka_unit_test(test_telemetry_does_not_change_a_run),
        cmocka_unit_test(test_parse_rate),
        cmocka_unit_test(test_disabled),
        cmocka_unit_test(test_log_file),
        cmocka_unit_test(test_bad_url),
    };
    return cmocka_run_group_tests_name("telemetry", tests, NULL, NULL);
}
