#include "app_telemetry.h"

#include <math.h>

void app_telemetry_init(app_telemetry_t *t)
{
    telemetry_tx_init(&t->tx);
    t->countdown = 0u;
}

uint8_t app_telemetry_due(app_telemetry_t *t)
{
    uint8_t due = (uint8_t)(t->countdown == 0u);
    if (due != 0u) {
        t->countdown = (uint8_t)APP_TELEMETRY_STEPS;
    }
    t->countdown--;
    return due;
}

void app_telemetry_send(app_telemetry_t *t, struct hal *hal, swarmlcm_robot_state_t *m)
{
    int n;
    m->utime = (int64_t)hal_time_ms(hal) * 1000;
    m->run = 0;
    m->robot_id = (int16_t)hal_robot_id(hal);
    /* The commands of this step: the image owns its struct hal. */
    m->wheel_left = hal->speed_left;
    m->wheel_right = hal->speed_right;
    m->leds = (int16_t)hal->leds;
    m->pose_known = 0;
    m->x = m->y = m->theta = NAN;

    n = swarmlcm_robot_state_t_encode(t->payload, 0, (int)sizeof t->payload, m);
    if (n > 0) {
        (void)telemetry_tx_send(&t->tx, hal, (uint8_t)TELEMETRY_CH_ROBOT_STATE, t->payload, (uint16_t)n);
    }
}

void app_telemetry_pump(app_telemetry_t *t, struct hal *hal)
{
    (void)telemetry_tx_pump(&t->tx, hal);
}
