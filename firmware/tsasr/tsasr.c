/*
 * tsasr.c - TSASR, robot chains with an elimination mechanism: a
 * RECONSTRUCTION (tsasr.h; docs/notes/i15_tsasr.md says what each rule and
 * constant is reconstructed from).  The chain model (states, colours,
 * motion, joining, the prey rule, PFIAS's random leave) and the
 * elimination mechanism (step_member's tail timer and retreat) are
 * firmware/pfias/pfias.c's, with its params `elim` on: here are TSASR's
 * parameters and its entry points.
 */
#include "tsasr/tsasr.h"

void tsasr_default_params(tsasr_params_t *params)
{
    /* The chain model's constants are PFIAS's (firmware/pfias/pfias.c):
     * seed 003 ran TSASR "with the same parameters" as PFIAS and EAIPP
     * (section 5.2, Table 2): P_e->c 0.01 per step, R = 0.6 m, a 0.45 m
     * link (0.75 R, PFIAS's link and EAIPP's B_UL band's middle), 5 cm/s.
     * PFIAS's random leave of a tail is reconstructed as kept (0.01 per
     * step, PFIAS's value, only with no explorer in view); TSASR's text on
     * it was not found (notes). */
    pfias_default_params(params);
    params->elim = 1u;
    /* Elimination (reconstruction, notes): a tail that has not found the
     * target within 30 s is eliminated; 30 s is EAIPP's PERIOD_TIME_1 in
     * this repository (firmware/eaipp, itself reconstructed: an explorer
     * at 5 cm/s crosses a 0.45 m link in 9 s), the same authors' later
     * form of the mechanism.  It then shows `retreat` for 2 s (20 steps,
     * a bit more than a neighbour's forget time, so that its predecessor
     * and the explorers about it hear the flag) before it leaves. */
    params->elim_steps = 300u;
    params->retreat_steps = 20u;
    params->elim_cascade = 1u;      /* the failed chain is eliminated as a whole (notes) */
    /* The clock runs whether or not explorers are about (the frontier is
     * judged by what it found); EAIPP's rule, "no explorer perceived
     * throughout the period", is the variant elim_explorer_resets (notes). */
    params->elim_explorer_resets = 0u;
}

void tsasr_init(tsasr_t *self, const tsasr_params_t *params, uint32_t seed)
{
    pfias_init(self, params, seed);
}

void tsasr_reset(tsasr_t *self)
{
    pfias_reset(self);
}

const char *tsasr_state_name(const tsasr_t *self)
{
    return pfias_state_name(self);
}

void tsasr_step(tsasr_t *self, hal_t *hal)
{
    pfias_step(self, hal);
}
