/*
 * test_nnea.c - seed 003's NNEA baseline (firmware/nnea/) on the fake HAL:
 * the fixed-point logistic against the real one, what each sensor feeds the
 * network, the leaky hidden neurons, the wheels' stop band, the colour
 * message, trips between the floor areas, the fixed sources, and reset.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "nnea/nnea.h"
#include "fake_hal.h"

#define IN_IR 0u
#define IN_GROUND 4u
#define IN_PEERS 6u

static void zero_genome(nnea_params_t *p)
{
    nnea_default_params(p);
    memset(p->w_in, 0, sizeof p->w_in);
    memset(p->w_rec, 0, sizeof p->w_rec);
    memset(p->b_hidden, 0, sizeof p->b_hidden);
    memset(p->tau, 0, sizeof p->tau);
    memset(p->w_out, 0, sizeof p->w_out);
    memset(p->b_out, 0, sizeof p->b_out);
}

static void test_sigmoid_matches_the_logistic(void **state)
{
    int32_t x, worst = 0;
    int16_t last = -1;
    (void)state;
    assert_int_equal(nnea_sigmoid(0), 2048);
    assert_int_equal(nnea_sigmoid(-100 * NNEA_ONE), 1);
    assert_int_equal(nnea_sigmoid(100 * NNEA_ONE), 4095);
    for (x = -9 * NNEA_ONE; x <= 9 * NNEA_ONE; x += 7) {
        int16_t y = nnea_sigmoid(x);
        double want = 4096.0 / (1.0 + exp(-(double)x / NNEA_ONE));
        int32_t err = (int32_t)fabs((double)y - want);
        assert_true(y >= last);              /* monotone */
        last = y;
        worst = err > worst ? err : worst;
    }
    assert_true(worst <= 4);                 /* 8e-4 of 1, as nnea.h states */
}

static void test_zero_genome_stands_still_and_signals(void **state)
{
    nnea_params_t p;
    nnea_t self;
    hal_t hal;
    (void)state;
    fake_hal_init(&hal, 3);
    zero_genome(&p);
    nnea_init(&self, &p, 7u);
    hal.left = hal.right = 99;
    nnea_step(&self, &hal);
    assert_string_equal(nnea_state_name(&self), "run");
    assert_int_equal(self.output[0], 2048);  /* sigma(0): inside the stop band */
    assert_int_equal(hal.left, 0);
    assert_int_equal(hal.right, 0);
    assert_int_equal(self.colour, 0);        /* 1/2 is not above 1/2 */
    assert_int_equal(hal.out_count, 1);
    assert_int_equal(hal.last_sent, NNEA_MSG_TAG);
}

static void test_outputs_drive_the_wheels(void **state)
{
    nnea_params_t p;
    nnea_t self;
    hal_t hal;
    (void)state;
    fake_hal_init(&hal, 1);
    zero_genome(&p);
    p.b_out[0] = NNEA_WEIGHT_MAX;            /* +8: left wheel almost full ahead */
    p.b_out[1] = -NNEA_WEIGHT_MAX;           /* -8: right wheel almost full back */
    p.b_out[2] = 512;                        /* +2: colour 1 */
    nnea_init(&self, &p, 1u);
    nnea_step(&self, &hal);
    assert_int_equal(self.output[0], 4094);  /* sigma(7.996) */
    assert_int_equal(self.output[1], 1);
    assert_int_equal(hal.left, 387);
    assert_int_equal(hal.right, -387);
    assert_int_equal(hal.left, (int16_t)((int32_t)(2 * 4094 - 4096) * 388 / 4096));
    assert_int_equal(hal.right, (int16_t)((int32_t)(2 * 1 - 4096) * 388 / 4096));
    assert_int_equal(self.colour, 1);
    assert_int_equal(hal.front_led, 1);
    assert_int_equal(hal.last_sent, NNEA_MSG_TAG | 1u);
    /* Just outside the stop band moves; just inside stops. */
    p.b_out[0] = 60;                         /* 0.234: sigma = 0.558, 2o-1 = 0.117 > 0.1 */
    p.b_out[1] = 40;                         /* 0.156: 2o-1 = 0.078 < 0.1 */
    nnea_init(&self, &p, 1u);
    nnea_step(&self, &hal);
    assert_true(hal.left > 0);
    assert_int_equal(hal.right, 0);
}

static void test_inputs(void **state)
{
    nnea_params_t p;
    nnea_t self;
    hal_t hal;
    (void)state;
    fake_hal_init(&hal, 1);
    zero_genome(&p);
    nnea_init(&self, &p, 1u);
    hal.proximity[7] = 1000;                 /* front-left: half of ir_full */
    hal.proximity[2] = 4000;                 /* right: saturates */
    hal.has_ground = 1;
    hal.ground[0] = 120;
    hal.ground[1] = 100;                     /* all three over black: the nest */
    hal.ground[2] = 90;
    assert_int_equal(fake_hal_push(&hal, NNEA_MSG_TAG | 1u, 300, 300), 1);   /* ahead-left, R/2 */
    assert_int_equal(fake_hal_push(&hal, NNEA_MSG_TAG, 150, -2000), 1);      /* back-right */
    assert_int_equal(fake_hal_push(&hal, NNEA_MSG_TAG, 450, -2100), 1);      /* farther: weaker */
    assert_int_equal(fake_hal_push(&hal, 0x31u, 10, 0), 1);                  /* not ours */
    nnea_step(&self, &hal);
    assert_int_equal(self.input[IN_IR + 0], 2048);
    assert_int_equal(self.input[IN_IR + 1], NNEA_ONE);
    assert_int_equal(self.input[IN_IR + 2], 0);
    assert_int_equal(self.input[IN_GROUND + 0], NNEA_ONE);
    assert_int_equal(self.input[IN_GROUND + 1], 0);
    assert_int_equal(self.input[IN_PEERS + 4 + 0], 2048);      /* colour 1, front-left */
    assert_int_equal(self.input[IN_PEERS + 0 + 2], 3072);      /* colour 0, back-right: the nearer */
    assert_int_equal(self.input[IN_PEERS + 0 + 0], 0);
    assert_int_equal(self.area, 1);
    /* Messages are read once: the next step hears nothing. */
    nnea_step(&self, &hal);
    assert_int_equal(self.input[IN_PEERS + 4 + 0], 0);
}

static void test_trips_between_areas(void **state)
{
    static const uint16_t floor_seq[] = { 1000, 100, 1000, 500, 500, 1000, 500, 100, 100, 1000 };
    static const uint32_t trips_after[] = { 0, 0, 0, 1, 1, 1, 1, 2, 2, 2 };
    nnea_params_t p;
    nnea_t self;
    hal_t hal;
    size_t i;
    (void)state;
    fake_hal_init(&hal, 1);
    hal.has_ground = 1;
    zero_genome(&p);
    nnea_init(&self, &p, 1u);
    for (i = 0; i < sizeof floor_seq / sizeof floor_seq[0]; i++) {
        hal.ground[0] = hal.ground[1] = hal.ground[2] = floor_seq[i];
        nnea_step(&self, &hal);
        assert_int_equal(self.trips, trips_after[i]);
    }
    /* One sensor alone in a band (noise, or the disc's edge) is no area. */
    hal.ground[0] = 1000;
    hal.ground[1] = 500;
    hal.ground[2] = 1000;
    nnea_step(&self, &hal);
    assert_int_equal(self.area, 0);
    hal.ground[0] = 500;
    hal.ground[2] = 100;
    nnea_step(&self, &hal);
    assert_int_equal(self.area, 0);
    /* Without the module the floor reads as bare. */
    hal.has_ground = 0;
    nnea_step(&self, &hal);
    assert_int_equal(self.area, 0);
}

static void test_hidden_leak_and_recurrence(void **state)
{
    nnea_params_t p;
    nnea_t self;
    hal_t hal;
    (void)state;
    fake_hal_init(&hal, 1);
    zero_genome(&p);
    p.b_hidden[0] = NNEA_WEIGHT_MAX;         /* drives h0 to ~1 */
    p.tau[0] = 128;                          /* halves the gap each step */
    p.w_rec[1 * NNEA_HIDDEN + 0] = -NNEA_WEIGHT_MAX;   /* h0 inhibits h1 */
    nnea_init(&self, &p, 1u);
    nnea_step(&self, &hal);
    assert_int_equal(self.hidden[0], 4094 / 2);   /* sigma(7.996) = 4094 */
    assert_int_equal(self.hidden[1], 2048);  /* read h0 before this step: 0 */
    nnea_step(&self, &hal);
    assert_int_equal(self.hidden[0], (128 * 2047 + 128 * 4094) / 256);
    assert_true(self.hidden[1] < 100);       /* -8 x 0.5: sigma(-4) = 0.018 */
    nnea_reset(&self);
    assert_int_equal(self.hidden[0], 0);
    assert_int_equal(self.trips, 0);
}

static void test_sources_stand_still_and_are_silent(void **state)
{
    nnea_params_t p;
    nnea_t self;
    hal_t hal;
    (void)state;
    fake_hal_init(&hal, 0);
    zero_genome(&p);
    p.b_out[0] = NNEA_WEIGHT_MAX;
    p.role = NNEA_ROLE_FOOD;
    nnea_init(&self, &p, 1u);
    hal.left = 5;
    nnea_step(&self, &hal);
    assert_string_equal(nnea_state_name(&self), "source");
    assert_int_equal(hal.left, 0);
    assert_int_equal(hal.body_led, 1);
    assert_int_equal(hal.out_count, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sigmoid_matches_the_logistic),
        cmocka_unit_test(test_zero_genome_stands_still_and_signals),
        cmocka_unit_test(test_outputs_drive_the_wheels),
        cmocka_unit_test(test_inputs),
        cmocka_unit_test(test_trips_between_areas),
        cmocka_unit_test(test_hidden_leak_and_recurrence),
        cmocka_unit_test(test_sources_stand_still_and_are_silent),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
