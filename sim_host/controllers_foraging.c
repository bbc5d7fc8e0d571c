/*
 * controllers_foraging.c - seed 000's forager and nest beacon as the
 * simulator runs them.  What the robots are told about their task (policy,
 * F_d, N_r, L, nest size, speed, ledger constants) comes from the scenario's
 * `controller.policy`, `arena`, `nest` and `foraging` sections, as a real
 * robot would be built with it; `controller.params` sets the rest.
 */
#include <math.h>
#include <string.h>

#include "controllers.h"
#include "foraging/forager.h"
#include "foraging/nest_beacon.h"
#include "core/sim.h"

/* ---------------------------------------------------------- forager */

#define FG(f) offsetof(forager_params_t, f), sizeof(((forager_params_t *)0)->f)
#define FG_WALK(f) FG(walk.f)
static const param_desc_t forager_param_descs[] = {
    { "alpha", PARAM_FLOAT, FG(alpha), 0, 1000, NULL, "DRTM eq 6 weight of k, per robot/m^2" },
    { "beta", PARAM_FLOAT, FG(beta), 0, 1000, NULL, "DRTM eq 6 weight of M_A, per OAE" },
    { "T1", PARAM_U16, FG(t1_steps), 1, 60000, NULL, "T1, steps between decisions in the nest" },
    { "n_min", PARAM_U8, FG(n_min), 1, 20, NULL, "eq 7 exponent n: per robot, uniform in [n_min, n_max]" },
    { "n_max", PARAM_U8, FG(n_max), 1, 20, NULL, "largest n" },
    { "theta0", PARAM_FLOAT, FG(theta0), 0, 1000, NULL, "ARTM start and FRTM fixed threshold, tokens" },
    { "theta_min", PARAM_FLOAT, FG(theta_min), 0, 1000, NULL, "ARTM lower bound of theta, tokens" },
    { "theta_max", PARAM_FLOAT, FG(theta_max), 0, 1000, NULL, "ARTM upper bound of theta, tokens" },
    { "artm_delta", PARAM_FLOAT, FG(artm_delta), 0, 1000, NULL,
      "ARTM step of theta per decision, tokens (our reconstruction)" },
    { "steer_gain", PARAM_I16, FG(steer_gain), 0, 10000, NULL,
      "wheel speed difference per rad of bearing, steps/s" },
    { "grasp_width_mrad", PARAM_U16, FG(grasp_width_mrad), 1, 3142, NULL,
      "a red blob this wide means a token is held, mrad" },
    { "near_width_mrad", PARAM_U16, FG(near_width_mrad), 1, 3142, NULL,
      "a centred red blob this wide is about to be grasped, mrad" },
    { "lost_steps", PARAM_U8, FG(lost_steps), 1, 255, NULL, "steps without the token before searching again" },
    { "nest_margin_mm", PARAM_U16, FG(nest_margin_mm), 0, 10000, NULL,
      "beacon range must be this far inside the nest radius, mm" },
    { "nest_confirm", PARAM_U8, FG(nest_confirm), 1, 255, NULL,
      "beacon frames in a row inside the nest that mean arrival" },
    { "light_detect", PARAM_U16, FG(light_detect), 0, 4095, NULL,
      "ambient below this means the nest light is seen, counts" },
    { "deposit_steps", PARAM_U8, FG(deposit_steps), 1, 255, NULL, "steps of backing out of a deposited token" },
    RANDOM_WALK_TUNING_DESCS(FG_WALK),
    PARAM_END
};

static const char *const forager_policies[] = { "drtm", "artm", "frtm", NULL };

static void fg_defaults(void *params) { forager_default_params(params); }
static void fg_init(void *state, const void *params, uint32_t seed) { forager_init(state, params, seed); }
static void fg_step(void *state, hal_t *hal) { forager_step(state, hal); }
static uint32_t fg_oae(const void *state) { return ((const forager_t *)state)->walk.oae_count; }
static const char *fg_state(const void *state) { return forager_state_name(((const forager_t *)state)->state); }
static char fg_task(const void *state) { return forager_paper_state(((const forager_t *)state)->state); }

static void fg_configure(void *params, const scenario_t *sc)
{
    forager_params_t *p = params;
    if (strcmp(sc->controller.policy, "artm") == 0) {
        p->policy = TA_ARTM;
    } else if (strcmp(sc->controller.policy, "frtm") == 0) {
        p->policy = TA_FRTM;
    } else {
        p->policy = TA_DRTM;
    }
    p->f_d_tokens = sc->foraging.desired_food;
    p->n_robots = (uint16_t)sc->robots.count;
    p->arena_l_mm = (uint16_t)lround(fmin(sc->arena.width, 65.535) * 1000.0);
    p->nest_radius_mm = (uint16_t)lround(fmin(sc->nest.diameter / 2.0, 65.535) * 1000.0);
    p->speed_steps_s = (int16_t)lround(fmin(sc->foraging.robot_speed / SIM_STEP_M, 1000.0));
    p->walk.speed_steps_s = p->speed_steps_s;
}

const sim_controller_t controller_forager = {
    "forager", "seed 000 forager: S_W/S_S/S_R with DRTM, ARTM or FRTM task allocation",
    sizeof(forager_t), sizeof(forager_params_t), forager_param_descs, forager_policies,
    fg_defaults, fg_init, fg_step, fg_oae, fg_state, fg_configure, fg_task
};

/* ---------------------------------------------------------- nest beacon */

static const param_desc_t beacon_param_descs[] = { PARAM_END };

static void nb_defaults(void *params) { nest_beacon_default_params(params); }
static void nb_init(void *state, const void *params, uint32_t seed) { nest_beacon_init(state, params, seed); }
static void nb_step(void *state, hal_t *hal) { nest_beacon_step(state, hal); }
static uint32_t nb_oae(const void *state) { (void)state; return 0; }
static const char *nb_state(const void *state) { return nest_beacon_state_name(((const nest_beacon_t *)state)->state); }

static void nb_configure(void *params, const scenario_t *sc)
{
    nest_beacon_params_t *p = params;
    double t2_s = sc->arena.width / (2.0 * sc->foraging.robot_speed);   /* T2 = L/(2v) */
    p->n_robots = (uint16_t)sc->robots.count;
    p->f0_tokens = (int16_t)lround(sc->foraging.initial_food);
    p->token_energy = (uint16_t)lround(fmin(sc->foraging.token_energy, 65535.0));
    p->c_rate_milli_tokens_per_min = (uint16_t)lround(fmin(sc->foraging.consumption * 1000.0, 65535.0));
    p->move_cost = (uint16_t)lround(fmin(sc->foraging.move_cost, 65535.0));
    p->e_a = (uint16_t)lround(fmin(sc->foraging.oae_energy, 65535.0));
    p->t2_steps = (uint16_t)lround(fmin(t2_s * 1000.0 / sc->control_period_ms, 65535.0));
}

const sim_controller_t controller_nest_beacon = {
    "nest_beacon", "seed 000 nest beacon: keeps the nest ledger, broadcasts S(t), N_W, M_A (added by foraging.information: beacon)",
    sizeof(nest_beacon_t), sizeof(nest_beacon_params_t), beacon_param_descs, NULL,
    nb_defaults, nb_init, nb_step, nb_oae, nb_state, nb_configure, NULL
};
