/*
 * test_sound.c - the simulator's sound field (sim_host/models/sound/sound.h) and its
 * HAL: levels against seed 002's eq 1 at known distances, sums of sources,
 * both silent_robots rules, eq 4's noise statistics, self-masking, the
 * speaker's one-period delay, the cutoff's error, its grid (all pairs when
 * it reaches everyone, one aggregate term beyond it), the scenario section, and
 * the same levels whatever the thread count or the robots' step order.
 * (About 0.03 s; 0.2 s under ASan.)
 */
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sim_fixture.h"

#include "common/random_walk.h"
#include "hal.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "core/sim_internal.h"
#include "models/noise_draws.h"
#include "models/sound/sound.h"

#define A0 299.18
#define AE 48.18

/* ------------------------------------------------------ a probe controller */

/* Plays `emit` every step and records what each microphone heard. */
typedef struct probe {
    uint8_t emit;
    hal_status_t speaker_status;
    hal_status_t status[HAL_MIC_COUNT][HAL_SOUND_BANDS];
    uint32_t level[HAL_MIC_COUNT][HAL_SOUND_BANDS];
} probe_t;

static void probe_init(void *self, const void *params, uint32_t seed)
{
    (void)params;
    (void)seed;
    memset(self, 0, sizeof(probe_t));
}

static void probe_reset(void *self) { memset(self, 0, sizeof(probe_t)); }

static void probe_step(void *self, hal_t *hal)
{
    probe_t *p = self;
    for (uint8_t m = 0; m < HAL_MIC_COUNT; m++) {
        for (uint8_t b = 1; b < HAL_SOUND_BANDS; b++) {
            p->status[m][b] = hal_mic_level(hal, m, b, &p->level[m][b]);
        }
    }
    p->speaker_status = hal_speaker_set(hal, p->emit);
}

static const char *probe_state_name(const void *self)
{
    (void)self;
    return "probe";
}

static void no_params(void *params) { (void)params; }

static const controller_def_t probe_def = {
    .name = "probe", .doc = "test: plays a band, records the microphones",
    .state_size = sizeof(probe_t), .params_size = 0, .default_params = no_params,
    .init = probe_init, .reset = probe_reset, .step = probe_step, .state_name = probe_state_name,
};

/* `robots` static probes, sound on without noise, a 12 m arena. */
static scenario_t *probe_scenario(uint32_t robots)
{
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    scenario_defaults(sc);
    strcpy(sc->groups[0].controller, "probe");
    strcpy(sc->groups[0].name, "probe");
    sc->groups[0].def = &probe_def;
    sc->groups[0].count = robots;
    sc->groups[0].moves = 0;
    sc->groups[0].placement.shape = PLACE_GRID;
    sc->arena.width = sc->arena.height = 12.0f;
    sound_config_mut(sc)->enabled = 1;
    sound_config_mut(sc)->noise = 0.0;
    return sc;
}

static probe_t *probe(sim_t *sim, uint32_t i) { return sim_robot_controller(sim, i); }

/* Eq 1 in counts, computed here on its own. */
static double loud(double d) { return A0 * exp(-0.12 * d) + AE; }
static uint32_t counts(double units) { return (uint32_t)llround(1000.0 * units); }

/* Within one count (the sum's order may differ from the model's). */
static void assert_level(uint32_t got, double want_units)
{
    uint32_t want = counts(want_units);
    if (got + 1 < want || got > want + 1) fail_msg("level %u counts, want %u", got, want);
}

/* ------------------------------------------------------------- eq 1 */

/* One emitter at 0, 1 and 5 m: the listener hears eq 1 in the emitter's
 * band, the emitter's ambient term in the others; every microphone the
 * same; the emitter itself is masked. */
static void test_one_emitter_at_known_distances(void **state)
{
    (void)state;
    static const double dist[] = { 0.0, 1.0, 5.0 };
    scenario_t *sc = probe_scenario(2);
    assert_int_equal(counts(loud(0.0)), 347360u);   /* a0 + ae = 347.36 units */
    for (size_t t = 0; t < 3; t++) {
        sim_t *sim = fixture_sim(sc, 1);
        sim_set_robot_pose(sim, 0, -dist[t] / 2, 0.0, 0.0);
        sim_set_robot_pose(sim, 1, dist[t] / 2, 0.0, 0.0);
        probe(sim, 0)->emit = 1;
        sim_step(sim);   /* step 0: robot 0 sets band 1, which plays during (0, 1] */
        sim_step(sim);   /* step 1: heard */
        const probe_t *p = probe(sim, 1);
        for (uint8_t m = 0; m < HAL_MIC_COUNT; m++) {
            assert_int_equal(p->status[m][1], HAL_OK);
            assert_int_equal(p->level[m][1], counts(loud(dist[t])));
            assert_int_equal(p->level[m][2], counts(AE));
            assert_int_equal(p->level[m][3], counts(AE));
        }
        assert_int_equal(probe(sim, 0)->status[0][1], HAL_ERR_BUSY);
        assert_int_equal(probe(sim, 0)->level[0][1], 0);
        sim_destroy(sim);
    }
    /* The numbers by hand: 313.529 units at 1 m, 212.373 at 5 m. */
    assert_int_equal(counts(loud(1.0)), 313529u);
    assert_int_equal(counts(loud(5.0)), 212373u);
    scenario_free(sc);
    free(sc);
}

/* Two emitters in band 1 sum, a third in band 2 is heard only there; a
 * silent robot adds its ambient term under `ambient` and nothing under
 * `none`. */
static void test_sources_sum_under_both_rules(void **state)
{
    (void)state;
    scenario_t *sc = probe_scenario(5);
    for (int rule = 0; rule < 2; rule++) {
        sound_config_mut(sc)->silent_robots = rule == 0 ? SOUND_SILENT_AMBIENT : SOUND_SILENT_NONE;
        sim_t *sim = fixture_sim(sc, 1);
        sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);    /* the listener */
        sim_set_robot_pose(sim, 1, 1.0, 0.0, 0.0);    /* band 1 at 1 m */
        sim_set_robot_pose(sim, 2, -2.0, 0.0, 0.0);   /* band 1 at 2 m */
        sim_set_robot_pose(sim, 3, 0.0, 3.0, 0.0);    /* band 2 at 3 m */
        sim_set_robot_pose(sim, 4, 0.0, -4.0, 0.0);   /* silent at 4 m */
        probe(sim, 1)->emit = 1;
        probe(sim, 2)->emit = 1;
        probe(sim, 3)->emit = 2;
        sim_step(sim);
        sim_step(sim);
        const probe_t *p = probe(sim, 0);
        double amb = rule == 0 ? AE : 0.0;
        assert_level(p->level[0][1], loud(1.0) + loud(2.0) + 2 * amb);
        assert_level(p->level[0][2], loud(3.0) + 3 * amb);
        assert_level(p->level[0][3], 4 * amb);
        /* Robot 4 (silent) hears all three at their distances from it. */
        const probe_t *q = probe(sim, 4);
        double d1 = sqrt(1.0 + 16.0), d2 = sqrt(4.0 + 16.0);
        assert_level(q->level[1][1], loud(d1) + loud(d2) + 2 * amb);
        assert_level(q->level[2][2], loud(7.0) + 3 * amb);
        sim_destroy(sim);
    }
    scenario_free(sc);
    free(sc);
}

/* ------------------------------------------------------------- eq 4 */

/* B/A over many draws: mean 1, sd `noise`; the bands' draws are
 * independent (each term its own draw). */
static void test_noise_statistics(void **state)
{
    (void)state;
    scenario_t *sc = probe_scenario(2);
    sound_config_mut(sc)->noise = 0.06;
    sim_t *sim = fixture_sim(sc, 7);
    sim_set_robot_pose(sim, 0, -0.5, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.5, 0.0, 0.0);
    probe(sim, 0)->emit = 1;
    sim_step(sim);
    enum { N = 6000 };
    double sum = 0, sq = 0, s1 = 0, s2 = 0, s12 = 0, q1 = 0, q2 = 0;
    int n = 0;
    for (int k = 0; k < N / 2; k++) {
        sim_step(sim);
        const probe_t *p = probe(sim, 1);
        assert_int_equal(p->status[0][1], HAL_OK);
        double r1 = p->level[0][1] / (1000.0 * loud(1.0));   /* the emitter's loud term */
        double r2 = p->level[0][2] / (1000.0 * AE);          /* its ambient term in band 2 */
        sum += r1 + r2;
        sq += r1 * r1 + r2 * r2;
        n += 2;
        s1 += r1;
        s2 += r2;
        s12 += r1 * r2;
        q1 += r1 * r1;
        q2 += r2 * r2;
    }
    double mean = sum / n, sd = sqrt(sq / n - mean * mean);
    double m = N / 2.0, cov = s12 / m - (s1 / m) * (s2 / m);
    double corr = cov / sqrt((q1 / m - (s1 / m) * (s1 / m)) * (q2 / m - (s2 / m) * (s2 / m)));
    print_message("B/A over %d draws: mean %.4f, sd %.4f; bands' correlation %.3f\n", n, mean, sd, corr);
    assert_true(fabs(mean - 1.0) < 0.004);   /* 4 standard errors (0.06 / sqrt(6000)) */
    assert_true(fabs(sd - 0.06) < 0.003);
    assert_true(fabs(corr) < 0.08);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* ------------------------------------------------ masking and the speaker */

/* self_masking: the period after its own tone a robot hears nothing
 * (HAL_ERR_BUSY, level 0); after a silent one it hears again.  Full duplex:
 * both emitters hear the other, never themselves. */
static void test_self_masking_and_duplex(void **state)
{
    (void)state;
    scenario_t *sc = probe_scenario(2);
    for (int duplex = 0; duplex < 2; duplex++) {
        sound_config_mut(sc)->self_masking = (uint8_t)!duplex;
        sim_t *sim = fixture_sim(sc, 1);
        sim_set_robot_pose(sim, 0, -0.5, 0.0, 0.0);
        sim_set_robot_pose(sim, 1, 0.5, 0.0, 0.0);
        probe(sim, 0)->emit = 1;
        probe(sim, 1)->emit = 1;
        sim_step(sim);
        sim_step(sim);
        for (uint32_t i = 0; i < 2; i++) {
            const probe_t *p = probe(sim, i);
            for (uint8_t m = 0; m < HAL_MIC_COUNT; m++) {
                assert_int_equal(p->status[m][1], duplex ? HAL_OK : HAL_ERR_BUSY);
                assert_int_equal(p->level[m][1], duplex ? counts(loud(1.0)) : 0u);
                assert_int_equal(p->level[m][2], duplex ? counts(AE) : 0u);
            }
        }
        /* Silent for a period: it hears again. */
        probe(sim, 0)->emit = 0;
        sim_step(sim);   /* robot 0 sets silence: it still played during the period read next */
        assert_int_equal(probe(sim, 0)->status[0][1], duplex ? HAL_OK : HAL_ERR_BUSY);
        sim_step(sim);
        assert_int_equal(probe(sim, 0)->status[0][1], HAL_OK);
        assert_int_equal(probe(sim, 0)->level[0][1], counts(loud(1.0)));
        /* Robot 1 still plays: masked, or (duplex) hears robot 0's silence. */
        assert_int_equal(probe(sim, 1)->status[0][1], duplex ? HAL_OK : HAL_ERR_BUSY);
        assert_int_equal(probe(sim, 1)->level[0][1], duplex ? counts(AE) : 0u);
        sim_destroy(sim);
    }
    scenario_free(sc);
    free(sc);
}

/* What a robot sets in step t plays during (t, t+1]: heard in step t+1, not
 * in step t; silence likewise a period later.  Read between steps, the HAL
 * gives what the next step's controllers will read. */
static void test_speaker_takes_effect_next_period(void **state)
{
    (void)state;
    scenario_t *sc = probe_scenario(2);
    sim_t *sim = fixture_sim(sc, 1);
    sim_set_robot_pose(sim, 0, -0.5, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.5, 0.0, 0.0);
    hal_t *h0 = sim_robot_hal(sim, 0), *h1 = sim_robot_hal(sim, 1);
    uint32_t level = 9;
    assert_int_equal(hal_speaker_set(h0, HAL_SOUND_BANDS), HAL_ERR_RANGE);
    assert_int_equal(hal_mic_level(h1, 0, 1, &level), HAL_OK);
    assert_int_equal(level, counts(AE));                    /* step 0: nothing played yet */
    probe(sim, 0)->emit = 2;
    sim_step(sim);                                          /* step 0 sets band 2 */
    assert_int_equal(probe(sim, 0)->speaker_status, HAL_OK);
    assert_int_equal(probe(sim, 1)->level[0][2], counts(AE));  /* not in step 0 */
    assert_int_equal(hal_mic_level(h1, 2, 2, &level), HAL_OK);
    assert_int_equal(level, counts(loud(1.0)));             /* what step 1 will read */
    sim_step(sim);
    assert_int_equal(probe(sim, 1)->level[0][2], counts(loud(1.0)));
    assert_int_equal(probe(sim, 1)->level[0][1], counts(AE));
    probe(sim, 0)->emit = 0;
    sim_step(sim);                                          /* step 2 sets silence */
    assert_int_equal(probe(sim, 1)->level[0][2], counts(loud(1.0)));
    sim_step(sim);
    assert_int_equal(probe(sim, 1)->level[0][2], counts(AE));
    /* Driven from outside a step: a speaker set now plays after the next step. */
    assert_int_equal(hal_speaker_set(h0, 3), HAL_OK);
    probe(sim, 0)->emit = 3;
    sim_step(sim);
    assert_int_equal(hal_mic_level(h1, 0, 3, &level), HAL_OK);
    assert_int_equal(level, counts(loud(1.0)));
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* ------------------------------------------------------------- cutoff */

/* Beyond the cutoff an emitter adds only ae: the error is a0 e^(-alpha d),
 * at most a0 e^(-alpha cutoff); inside it the pair is exact. */
static void test_cutoff_error(void **state)
{
    (void)state;
    scenario_t *sc = probe_scenario(3);
    sound_config_mut(sc)->cutoff = 2.0;
    sim_t *sim = fixture_sim(sc, 1);
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 1.0, 0.0, 0.0);   /* inside: exact */
    sim_set_robot_pose(sim, 2, -3.0, 0.0, 0.0);  /* outside: ae only */
    probe(sim, 1)->emit = 1;
    probe(sim, 2)->emit = 2;
    sim_step(sim);
    sim_step(sim);
    const probe_t *p = probe(sim, 0);
    assert_level(p->level[0][1], loud(1.0) + AE);
    assert_level(p->level[0][2], 2 * AE);
    double err = loud(3.0) + AE - p->level[0][2] / 1000.0;
    assert_true(fabs(err - A0 * exp(-0.12 * 3.0)) < 0.002);
    assert_true(err <= A0 * exp(-0.12 * sound_config_mut(sc)->cutoff));
    assert_true(sound_term(sound_config(sc), 3.0, 1) == AE);
    assert_true(sound_term(sound_config(sc), 1.0, 1) == loud(1.0));
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* A cutoff beyond every distance finds every robot near (on the grid, in
 * id order): the same field as all pairs, noise draw for draw, under both
 * rules and with or without self-masking. */
static void test_cutoff_beyond_arena_is_all_pairs(void **state)
{
    (void)state;
    for (int rule = 0; rule < 4; rule++) {
        uint32_t level[2][30][HAL_SOUND_BANDS];
        for (int pass = 0; pass < 2; pass++) {
            scenario_t *sc = probe_scenario(30);
            sound_config_mut(sc)->noise = 0.06;
            sound_config_mut(sc)->silent_robots = (rule & 1) ? SOUND_SILENT_NONE : SOUND_SILENT_AMBIENT;
            sound_config_mut(sc)->self_masking = (rule & 2) ? 1 : 0;
            sound_config_mut(sc)->cutoff = pass ? 100.0 : 0.0;
            sim_t *sim = fixture_sim(sc, 3);
            for (uint32_t i = 0; i < 30; i++) {
                probe(sim, i)->emit = (uint8_t)(i % 4);
            }
            for (int k = 0; k < 5; k++) {
                sim_step(sim);
            }
            for (uint32_t i = 0; i < 30; i++) {
                memcpy(level[pass][i], probe(sim, i)->level[0], sizeof level[pass][i]);
            }
            sim_destroy(sim);
            scenario_free(sc);
            free(sc);
        }
        assert_memory_equal(level[0], level[1], sizeof level[0]);
    }
}

/* Robots beyond the cutoff are one term per band with one draw: the sum of
 * their m ambient terms has mean m ae and sd ae noise sqrt(m), as m draws
 * of their own would. */
static void test_cutoff_far_field_statistics(void **state)
{
    (void)state;
    scenario_t *sc = probe_scenario(25);   /* a 5 x 5 grid, 2.4 m apart */
    sound_config_mut(sc)->noise = 0.06;
    sound_config_mut(sc)->cutoff = 0.5;
    sim_t *sim = fixture_sim(sc, 11);
    double sum = 0.0, sq = 0.0;
    int n = 0;
    for (int k = 0; k < 400; k++) {
        sim_step(sim);
        for (uint32_t i = 0; i < 25; i++) {
            double v = probe(sim, i)->level[0][1] / 1000.0;
            sum += v;
            sq += v * v;
            n++;
        }
    }
    double mean = sum / n, sd = sqrt(sq / n - mean * mean);
    double want_mean = 24 * AE, want_sd = AE * 0.06 * sqrt(24.0);
    print_message("far field of 24: mean %.3f (want %.3f), sd %.3f (want %.3f)\n", mean, want_mean, sd, want_sd);
    assert_true(fabs(mean - want_mean) < 4 * want_sd / sqrt((double)n));
    assert_true(fabs(sd - want_sd) < 0.05 * want_sd);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* noise_draws: summed.  Nine static probes 0.8 m apart, playing bands
 * i % 4 (summed_sim), under both silent_robots rules, all pairs and with a
 * cutoff that leaves some sources far.  Eq 2's mean and eq 4's sd of every
 * level are computed here term by term (expected_level: beyond a cutoff a
 * source's term is ae).  Per term, the levels' z-scores have mean 0, sd 1
 * and uncorrelated bands; summed, every level is exactly mean - sd N, N the
 * listener's own RAND_SOUND draws replayed here, three a step (to a count:
 * the sums' order differs); without noise the two give the same levels. */
enum { SUMMED_ROBOTS = 9, SUMMED_STEPS = 1500 };

static sim_t *summed_sim(scenario_t **sc_out, int setting, int draws, double noise)
{
    scenario_t *sc = probe_scenario(SUMMED_ROBOTS);
    sound_config_mut(sc)->noise = noise;
    sound_config_mut(sc)->self_masking = 0;
    sound_config_mut(sc)->silent_robots = (setting & 1) ? SOUND_SILENT_NONE : SOUND_SILENT_AMBIENT;
    sound_config_mut(sc)->cutoff = (setting & 2) ? 1.0 : 0.0;
    sound_config_mut(sc)->noise_draws = draws;
    sim_t *sim = fixture_sim(sc, 5);
    for (uint32_t i = 0; i < SUMMED_ROBOTS; i++) {
        sim_set_robot_pose(sim, i, 0.8 * (i % 3), 0.8 * (i / 3), 0.0);
        probe(sim, i)->emit = (uint8_t)(i % 4);
    }
    sim_step(sim);   /* the tones play from the next period on */
    *sc_out = sc;
    return sim;
}

static void summed_done(sim_t *sim, scenario_t *sc)
{
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void expected_level(uint32_t i, uint8_t band, int setting, double *mean, double *sd)
{
    int ambient = !(setting & 1);
    double cutoff = (setting & 2) ? 1.0 : 0.0, sum = 0.0, sq = 0.0;
    for (uint32_t j = 0; j < SUMMED_ROBOTS; j++) {
        double d = 0.8 * hypot((double)(i % 3) - (double)(j % 3), (double)(i / 3) - (double)(j / 3));
        double a = (j % 4 == band) ? ((cutoff > 0.0 && d > cutoff) ? AE : loud(d)) : (ambient ? AE : 0.0);
        if (j != i) {
            sum += a;
            sq += a * a;
        }
    }
    *mean = 1000.0 * sum;
    *sd = 1000.0 * 0.06 * sqrt(sq);
}

/* Per term: the z-scores of every level with a term in its band. */
static void per_term_statistics(int setting)
{
    scenario_t *sc;
    sim_t *sim = summed_sim(&sc, setting, NOISE_DRAWS_PER_TERM, 0.06);
    double zs = 0.0, zq = 0.0, z12 = 0.0;
    int n = 0, n12 = 0;
    for (int k = 0; k < SUMMED_STEPS; k++) {
        sim_step(sim);
        for (uint32_t i = 0; i < SUMMED_ROBOTS; i++) {
            double z[HAL_SOUND_BANDS] = { 0.0 }, mean, sd;
            for (uint8_t b = 1; b < HAL_SOUND_BANDS; b++) {
                expected_level(i, b, setting, &mean, &sd);
                if (sd > 0.0) {   /* none: a band without an emitter but itself has no term */
                    z[b] = (probe(sim, i)->level[0][b] - mean) / sd;
                    zs += z[b];
                    zq += z[b] * z[b];
                    n++;
                }
            }
            z12 += z[1] * z[2];
            n12++;
        }
    }
    double mz = zs / n, sdz = sqrt(zq / n - mz * mz), corr = z12 / n12;
    print_message("setting %d, per_term: z mean %.4f, sd %.4f, bands 1-2 %.4f over %d\n", setting, mz, sdz, corr, n);
    assert_true(fabs(mz) < 4.0 / sqrt((double)n));
    assert_true(fabs(sdz - 1.0) < 0.015);   /* its standard error: 1 / sqrt(2 n), under 0.4 % */
    assert_true(fabs(corr) < 4.0 / sqrt((double)n12) + 0.01);
    summed_done(sim, sc);
}

/* Summed: each level from the listener's replayed draws. */
static void summed_replayed(int setting)
{
    scenario_t *sc;
    sim_t *sim = summed_sim(&sc, setting, NOISE_DRAWS_SUMMED, 0.06);
    sim_rand_t r[SUMMED_ROBOTS];
    double z[SUMMED_ROBOTS][HAL_SOUND_BANDS - 1];
    for (uint32_t i = 0; i < SUMMED_ROBOTS; i++) {
        sim_rand_seed(&r[i], 5, i, RAND_SOUND);
        sim_rand_normals(&r[i], z[i], HAL_SOUND_BANDS - 1);   /* the first step's */
    }
    uint32_t worst = 0;
    for (int k = 0; k < SUMMED_STEPS; k++) {
        sim_step(sim);
        for (uint32_t i = 0; i < SUMMED_ROBOTS; i++) {
            sim_rand_normals(&r[i], z[i], HAL_SOUND_BANDS - 1);
            for (uint8_t b = 1; b < HAL_SOUND_BANDS; b++) {
                double mean, sd;
                expected_level(i, b, setting, &mean, &sd);
                double want = fmax(0.0, mean - sd * z[i][b - 1]);
                uint32_t got = probe(sim, i)->level[0][b];
                uint32_t off = (uint32_t)fabs(got - floor(want + 0.5));
                worst = off > worst ? off : worst;
            }
        }
    }
    print_message("setting %d, summed: every level within %u count(s) of its replayed draw\n", setting, worst);
    assert_true(worst <= 1);
    summed_done(sim, sc);
}

static void test_summed_draws_same_distribution(void **state)
{
    (void)state;
    for (int setting = 0; setting < 4; setting++) {
        per_term_statistics(setting);
        summed_replayed(setting);
        uint32_t level[2][SUMMED_ROBOTS][HAL_SOUND_BANDS];
        for (int draws = 0; draws < 2; draws++) {
            scenario_t *sc;
            sim_t *sim = summed_sim(&sc, setting, draws, 0.0);
            sim_step(sim);
            for (uint32_t i = 0; i < SUMMED_ROBOTS; i++) {
                memcpy(level[draws][i], probe(sim, i)->level[0], sizeof level[draws][i]);
            }
            summed_done(sim, sc);
        }
        for (uint32_t i = 0; i < SUMMED_ROBOTS; i++) {
            for (uint8_t b = 1; b < HAL_SOUND_BANDS; b++) {
                assert_true(level[0][i][b] + 1 >= level[1][i][b] && level[1][i][b] + 1 >= level[0][i][b]);
            }
        }
    }
}

/* The count scale and its ends. */
static void test_counts(void **state)
{
    (void)state;
    assert_int_equal(sound_counts(347.36), 347360u);
    assert_int_equal(sound_counts(0.0004), 0u);
    assert_int_equal(sound_counts(0.0005), 1u);
    assert_int_equal(sound_counts(-3.0), 0u);
    assert_int_equal(sound_counts(NAN), 0u);
    assert_int_equal(sound_counts(1e9), UINT32_MAX);
    scenario_t *sc = probe_scenario(1);
    assert_true(sound_term(sound_config(sc), 2.0, 0) == AE);
    sound_config_mut(sc)->silent_robots = SOUND_SILENT_NONE;
    assert_true(sound_term(sound_config(sc), 2.0, 0) == 0.0);
    scenario_free(sc);
    free(sc);
}

/* -------------------------------------------------------------- scenario */

/* The section loads strictly; disabled by default, every HAL call answers
 * HAL_ERR_UNAVAILABLE; a bad word or range names the file's line and key. */
static void test_scenario_section(void **state)
{
    (void)state;
    scenario_t *sc = malloc(sizeof *sc);
    char err[SIM_ERR_MAX];
    assert_non_null(sc);
    if (scenario_load("data/scenarios/sound_small.yaml", NULL, 0, sc, err) != 0) fail_msg("%s", err);
    assert_true(sound_config_mut(sc)->enabled == 1 && sound_config_mut(sc)->self_masking == 1);
    assert_true(sound_config_mut(sc)->alpha == 0.726 && sound_config_mut(sc)->noise == 0.06 && sound_config_mut(sc)->a0 == A0
                && sound_config_mut(sc)->ae == AE && sound_config_mut(sc)->cutoff == 0.0);
    assert_int_equal(sound_config_mut(sc)->silent_robots, SOUND_SILENT_AMBIENT);
    assert_int_equal(sound_config_mut(sc)->noise_draws, NOISE_DRAWS_PER_TERM);

    scenario_override_t bad[] = { { "sound.silent_robots=loud" } };
    assert_int_equal(scenario_load("data/scenarios/sound_small.yaml", bad, 1, sc, err), -1);
    assert_non_null(strstr(err, "sound.silent_robots"));
    assert_non_null(strstr(err, "ambient"));
    scenario_override_t neg[] = { { "sound.cutoff=-1" } };
    assert_int_equal(scenario_load("data/scenarios/sound_small.yaml", neg, 1, sc, err), -1);
    assert_non_null(strstr(err, "sound.cutoff"));
    scenario_override_t summed[] = { { "sound.noise_draws=summed" } }, wrong[] = { { "sound.noise_draws=each" } };
    assert_int_equal(scenario_load("data/scenarios/sound_small.yaml", summed, 1, sc, err), 0);
    assert_int_equal(sound_config(sc)->noise_draws, NOISE_DRAWS_SUMMED);
    scenario_free(sc);
    assert_int_equal(scenario_load("data/scenarios/sound_small.yaml", wrong, 1, sc, err), -1);
    assert_non_null(strstr(err, "sound.noise_draws: expected one of per_term|summed"));

    scenario_override_t typo[] = { { "sound.volume=3" } };
    assert_int_equal(scenario_load("data/scenarios/sound_small.yaml", typo, 1, sc, err), -1);
    assert_non_null(strstr(err, "volume"));

    assert_int_equal(scenario_load("data/scenarios/sound_bad_rule.yaml", NULL, 0, sc, err), -1);
    assert_non_null(strstr(err, "sound_bad_rule.yaml:6: sound.silent_robots: expected one of ambient|none"));

    scenario_defaults(sc);
    assert_int_equal(sound_config_mut(sc)->enabled, 0);
    scenario_free(sc);
    free(sc);
}

/* ---------------------------------------------------------- determinism */

/* random_walk plus a speaker: each step it plays a band drawn from its own
 * stream and folds what it heard (status and levels) into a hash. */
typedef struct chatty {
    random_walk_t walk;
    uint32_t rng;
    uint64_t hash;
    uint32_t heard, busy;   /* readings HAL_OK with a level > 0, HAL_ERR_BUSY */
} chatty_t;

static void chatty_init(void *self, const void *params, uint32_t seed)
{
    chatty_t *c = self;
    memset(c, 0, sizeof *c);
    random_walk_def.init(&c->walk, params, seed);
    c->rng = seed | 1u;
    c->hash = UINT64_C(0xcbf29ce484222325);
}

static void chatty_reset(void *self) { (void)self; }

static void chatty_step(void *self, hal_t *hal)
{
    chatty_t *c = self;
    random_walk_def.step(&c->walk, hal);
    for (uint8_t b = 1; b < HAL_SOUND_BANDS; b++) {
        uint32_t level = 0;
        hal_status_t s = hal_mic_level(hal, (uint8_t)(b - 1), b, &level);
        c->heard += s == HAL_OK && level > 0;
        c->busy += s == HAL_ERR_BUSY;
        c->hash = (c->hash ^ (uint64_t)(uint32_t)s ^ ((uint64_t)level << 8)) * UINT64_C(0x100000001b3);
    }
    c->rng ^= c->rng << 13;
    c->rng ^= c->rng >> 17;
    c->rng ^= c->rng << 5;
    (void)hal_speaker_set(hal, (uint8_t)(c->rng % HAL_SOUND_BANDS));
}

static const char *chatty_state_name(const void *self)
{
    (void)self;
    return "chatty";
}

static controller_def_t chatty_def;

static scenario_t *chatty_scenario(void)
{
    scenario_t *sc = malloc(sizeof *sc);
    char err[SIM_ERR_MAX];
    assert_non_null(sc);
    if (scenario_load("data/scenarios/sound_small.yaml", NULL, 0, sc, err) != 0) fail_msg("%s", err);
    chatty_def = random_walk_def;
    chatty_def.name = "chatty";
    chatty_def.state_size = sizeof(chatty_t);
    chatty_def.init = chatty_init;
    chatty_def.reset = chatty_reset;
    chatty_def.step = chatty_step;
    chatty_def.state_name = chatty_state_name;
    chatty_def.observables = NULL;
    sc->groups[0].def = &chatty_def;
    return sc;
}

enum { CHATTY_STEPS = 400 };

typedef struct chatty_run {
    const scenario_t *sc;
    uint64_t seed;
    int order;
    uint64_t hash, state_hash;
    uint32_t heard, busy;
} chatty_run_t;

static void *chatty_run(void *arg)
{
    chatty_run_t *r = arg;
    char err[SIM_ERR_MAX];
    sim_t *sim = sim_create(r->sc, r->seed, err);
    if (!sim) return NULL;
    sim_set_step_order(sim, r->order, 77);
    for (int k = 0; k < CHATTY_STEPS; k++) sim_step(sim);
    r->hash = UINT64_C(0xcbf29ce484222325);
    for (uint32_t i = 0; i < sim_robot_count(sim); i++) {
        const chatty_t *c = sim_robot_controller_const(sim, i);
        r->hash = (r->hash ^ c->hash) * UINT64_C(0x100000001b3);
        r->heard += c->heard;
        r->busy += c->busy;
    }
    r->state_hash = sim_state_hash(sim);
    sim_destroy(sim);
    return r;
}

/* The same seed hears the same levels run alone or beside three other runs
 * on their own threads, and in any step order; another seed does not. */
static void test_same_levels_any_thread_count(void **state)
{
    (void)state;
    scenario_t *sc = chatty_scenario();
    chatty_run_t one = { sc, 3, 0, 0, 0, 0, 0 };
    assert_non_null(chatty_run(&one));
    assert_true(one.heard > 1000 && one.busy > 1000);   /* the hash saw real levels */

    enum { T = 4 };
    chatty_run_t many[T];
    pthread_t tid[T];
    for (int t = 0; t < T; t++) {
        many[t] = (chatty_run_t){ sc, t == 3 ? 4 : 3, t % 3, 0, 0, 0, 0 };
        assert_int_equal(pthread_create(&tid[t], NULL, chatty_run, &many[t]), 0);
    }
    for (int t = 0; t < T; t++) {
        void *ok = NULL;
        assert_int_equal(pthread_join(tid[t], &ok), 0);
        assert_non_null(ok);
    }
    for (int t = 0; t < 3; t++) {
        assert_true(many[t].hash == one.hash);
        assert_true(many[t].state_hash == one.state_hash);
    }
    assert_true(many[3].hash != one.hash);
    scenario_free(sc);
    free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_emitter_at_known_distances),
        cmocka_unit_test(test_sources_sum_under_both_rules),
        cmocka_unit_test(test_noise_statistics),
        cmocka_unit_test(test_self_masking_and_duplex),
        cmocka_unit_test(test_speaker_takes_effect_next_period),
        cmocka_unit_test(test_cutoff_error),
        cmocka_unit_test(test_cutoff_beyond_arena_is_all_pairs),
        cmocka_unit_test(test_cutoff_far_field_statistics),
        cmocka_unit_test(test_summed_draws_same_distribution),
        cmocka_unit_test(test_counts),
        cmocka_unit_test(test_scenario_section),
        cmocka_unit_test(test_same_levels_any_thread_count),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
