/*
 * legend.c - a run's legend from its tasks' (legend.h).
 */
#include "legend.h"

#include "sim_internal.h"

/* Appends the keys of every task for which `robot` says whether a key is
 * a robot fill; notes whether one of them is the default body's. */
static uint32_t add_keys(const struct sim *sim, int robot, draw_key_t *keys, uint32_t n, int *has_default)
{
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        for (const draw_key_t *k = sim->tasks[t].def->legend; k && k->label; k++) {
            if ((k->kind == DRAW_KEY_ROBOT) != robot || n >= LEGEND_KEYS_MAX)
                continue;
            keys[n++] = *k;
            *has_default |= robot && k->rgb == 0;
        }
    }
    return n;
}

uint32_t legend_collect(const sim_t *simp, draw_key_t keys[LEGEND_KEYS_MAX])
{
    const struct sim *sim = simp;
    int has_default = 0;
    uint32_t n = add_keys(sim, 1, keys, 0, &has_default);
    if (!has_default) {
        if (n == LEGEND_KEYS_MAX)
            n--;
        keys[n] = (draw_key_t){ 0, n ? "other" : "robot", DRAW_KEY_ROBOT, 0 };
        n++;
    }
    return add_keys(sim, 0, keys, n, &has_default);
}
