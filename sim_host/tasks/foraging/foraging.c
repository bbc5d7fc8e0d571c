/*
 * foraging.c - food tokens, the passive gripper, deliveries and the
 * ground-truth nest ledger of seed 000 (see foraging.h).
 */
#include "foraging.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "foraging/nest_link.h"
#include "core/sim_internal.h"

/* The gripper takes a token whose centre comes within its radius plus this
 * of the robot's front point, and holds it this far ahead of the lens. */
#define GRASP_TOLERANCE 0.025f
#define CARRY_GAP 0.005f
#define PLACE_TRIES 100000

static float nest_radius(const struct sim *sim) { return sim->sc->nest.diameter / 2.0f; }

static int in_nest(const struct sim *sim, float x, float y)
{
    float dx = x - sim->sc->nest.x, dy = y - sim->sc->nest.y, r = nest_radius(sim);
    return dx * dx + dy * dy < r * r;
}

/* A free spot for a token: inside the walls, outside the nest, off the
 * obstacles.  Returns 0, or -1 when the arena has no room. */
static int place_token(struct sim *sim, food_token_t *t)
{
    const scenario_t *sc = sim->sc;
    float r = sc->foraging.token_radius, margin = r + 0.01f;
    for (int k = 0; k < PLACE_TRIES; k++) {
        float x = (float)((2 * sim_rand_uniform(&sim->forage.rand) - 1) * (sim->hw - margin));
        float y = (float)((2 * sim_rand_uniform(&sim->forage.rand) - 1) * (sim->hh - margin));
        float dx = x - sc->nest.x, dy = y - sc->nest.y, nr = nest_radius(sim) + r;
        int ok = dx * dx + dy * dy > nr * nr;
        for (uint32_t o = 0; ok && o < sim->n_obstacles; o++) {
            const obstacle_t *ob = &sim->obstacles[o];
            ok = x < ob->aabb[0] - r || x > ob->aabb[2] + r || y < ob->aabb[1] - r || y > ob->aabb[3] + r;
        }
        if (ok) {
            t->x = x;
            t->y = y;
            t->carrier = -1;
            return 0;
        }
    }
    return -1;
}

int foraging_init(struct sim *sim, char err[256])
{
    const scenario_t *sc = sim->sc;
    foraging_t *f = &sim->forage;
    memset(f, 0, sizeof *f);
    f->n_tokens = sc->foraging.food_count;
    f->tokens = calloc(f->n_tokens ? f->n_tokens : 1, sizeof *f->tokens);
    f->carried = malloc((sim->n ? sim->n : 1) * sizeof *f->carried);
    /* T2 = L / (2 v) (seed 000, eq 5), in control steps. */
    double t2 = sc->arena.width / (2.0 * sc->foraging.robot_speed);
    f->window_len = (uint32_t)fmax(1.0, floor(t2 * 1000.0 / sc->control_period_ms + 0.5));
    f->oae_window = calloc(f->window_len, sizeof *f->oae_window);
    if (!f->tokens || !f->carried || !f->oae_window) {
        snprintf(err, 256, "out of memory for %u food tokens", f->n_tokens);
        return -1;
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        f->carried[i] = -1;
    }
    sim_rand_seed(&f->rand, sim->seed, 0, RAND_FOOD);
    for (uint32_t k = 0; k < f->n_tokens; k++) {
        if (place_token(sim, &f->tokens[k]) != 0) {
            snprintf(err, 256, "cannot place food token %u of %u outside the nest and obstacles",
                     k + 1, f->n_tokens);
            return -1;
        }
    }
    f->food = sc->foraging.initial_food;
    return 0;
}

void foraging_free(struct sim *sim)
{
    free(sim->forage.tokens);
    free(sim->forage.carried);
    free(sim->forage.oae_window);
    memset(&sim->forage, 0, sizeof sim->forage);
}

static int backing(const sim_robot_t *r) { return r->cmd_left < 0 && r->cmd_right < 0; }

void foraging_release(struct sim *sim)
{
    foraging_t *f = &sim->forage;
    for (uint32_t i = 0; i < sim->n_swarm; i++) {
        int32_t k = f->carried[i];
        if (k < 0 || !backing(&sim->robots[i])) {
            continue;
        }
        food_token_t *t = &f->tokens[k];
        f->carried[i] = -1;
        t->carrier = -1;
        if (in_nest(sim, t->x, t->y)) {
            f->delivered++;
            /* A new token appears at random; if none fits, the delivered one
             * stays out of play (counted in the summary as n_tokens). */
            if (place_token(sim, t) != 0) {
                t->x = t->y = NAN;
            }
        } else {
            f->dropped++;
        }
    }
}

int foraging_drop(struct sim *sim, uint32_t i)
{
    foraging_t *f = &sim->forage;
    if (!sim->foraging_on || i >= sim->n_swarm || f->carried[i] < 0) {
        return 0;
    }
    food_token_t *t = &f->tokens[f->carried[i]];
    /* Left on the floor a little ahead, out of the gripper's reach. */
    t->x += 0.1f * cosf(sim->robots[i].theta);
    t->y += 0.1f * sinf(sim->robots[i].theta);
    t->carrier = -1;
    f->carried[i] = -1;
    f->dropped++;
    return 1;
}

static void carry_and_grasp(struct sim *sim)
{
    foraging_t *f = &sim->forage;
    float tr = sim->sc->foraging.token_radius, reach = tr + GRASP_TOLERANCE;
    for (uint32_t i = 0; i < sim->n_swarm; i++) {
        sim_robot_t *r = &sim->robots[i];
        float c = cosf(r->theta), s = sinf(r->theta);
        if (f->carried[i] < 0 && !backing(r)) {
            float fx = r->x + SIM_ROBOT_RADIUS * c, fy = r->y + SIM_ROBOT_RADIUS * s;
            for (uint32_t k = 0; k < f->n_tokens; k++) {
                food_token_t *t = &f->tokens[k];
                float dx = t->x - fx, dy = t->y - fy;
                if (t->carrier < 0 && dx * dx + dy * dy < reach * reach) {
                    t->carrier = (int32_t)i;
                    f->carried[i] = (int32_t)k;
                    break;
                }
            }
        }
        if (f->carried[i] >= 0) {
            food_token_t *t = &f->tokens[f->carried[i]];
            float ahead = SIM_ROBOT_RADIUS + tr + CARRY_GAP;
            t->x = r->x + ahead * c;
            t->y = r->y + ahead * s;
        }
    }
}

void foraging_update(struct sim *sim)
{
    const scenario_t *sc = sim->sc;
    foraging_t *f = &sim->forage;
    carry_and_grasp(sim);

    f->waiting = f->searching = f->returning = 0;
    for (uint32_t i = 0; i < sim->n_swarm; i++) {
        const sim_robot_t *r = &sim->robots[i];
        char st = (r->ctrl && r->ctrl_desc->task_state) ? r->ctrl_desc->task_state(r->ctrl) : 0;
        f->waiting += st == 'W';
        f->searching += st == 'S';
        f->returning += st == 'R';
    }
    /* One unit per step per robot in S_S or S_R (seed 000, 3.1). */
    f->forage_steps += f->searching + f->returning;

    uint64_t oae = sim_oae_total(sim);
    uint32_t new_oae = (uint32_t)(oae - f->oae_seen);
    f->oae_seen = oae;
    f->window_sum += new_oae;
    f->window_sum -= f->oae_window[f->window_pos];
    f->oae_window[f->window_pos] = new_oae;
    f->window_pos = (f->window_pos + 1) % f->window_len;

    double minutes = (double)(sim->step + 1) * sc->control_period_ms / 60000.0;
    f->nest_units = sc->foraging.consumption * sc->foraging.token_energy * minutes;
    f->food = foraging_balance(sim);
    f->deviation_sum += fabs(sc->foraging.desired_food - f->food);
}

double foraging_balance(const struct sim *sim)
{
    const scenario_t *sc = sim->sc;
    const foraging_t *f = &sim->forage;
    double spent = f->nest_units + sc->foraging.move_cost * (double)f->forage_steps
                 + sc->foraging.oae_energy * (double)f->oae_seen;
    return sc->foraging.initial_food + (double)f->delivered - spent / sc->foraging.token_energy;
}

void foraging_broadcast_truth(struct sim *sim)
{
    const scenario_t *sc = sim->sc;
    const foraging_t *f = &sim->forage;
    /* The same frames a nest beacon sends, one per step in turn, with the
     * true values, to every robot within IR range of the nest centre. */
    uint16_t frame;
    switch (sim->step % NL_KIND_COUNT) {
    case NL_KIND_FOOD:
        frame = nest_link_encode_food((int32_t)lround(f->food * 16.0));
        break;
    case NL_KIND_WAITING:
        frame = nest_link_encode_waiting((uint16_t)f->waiting);
        break;
    default:
        frame = nest_link_encode_mean_oae(
            sc->robots.count ? (uint32_t)lround(256.0 * (double)f->window_sum / sc->robots.count) : 0u);
        break;
    }
    for (uint32_t i = 0; i < sim->n_swarm; i++) {
        sim_robot_t *r = &sim->robots[i];
        float dx = sc->nest.x - r->x, dy = sc->nest.y - r->y;
        float d = sqrtf(dx * dx + dy * dy);
        if (d > sc->ircom.range || r->rx_count >= SIM_IRCOM_QUEUE) {
            continue;
        }
        hal_ircom_msg_t *m = &r->rx[(r->rx_head + r->rx_count) % SIM_IRCOM_QUEUE];
        m->value = frame;
        m->bearing_mrad = (int16_t)lroundf(1000.0f * geom_wrap(atan2f(dy, dx) - r->theta));
        m->sensor = 0;
        m->range_mm = (uint16_t)fminf(d * 1000.0f + 0.5f, 65535.0f);
        r->rx_count++;
    }
}
