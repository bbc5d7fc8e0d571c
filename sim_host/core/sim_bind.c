/*
 * sim_bind.c - the parts of the public API (sim.h, scenario.h) that serve
 * bindings and stand-in robots rather than the run loop: a scenario on the
 * heap, many steps a call, a group's observables and every robot's state
 * in one call, the summary as text, a robot's id and UART bytes.  The
 * Python binding (tools/swarmtools/sim/) calls only the public API; these
 * are its pieces the core did not have.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim_internal.h"
#include "summary.h"

scenario_t *scenario_create(const char *path, const scenario_override_t *overrides, size_t override_count,
                            char err[SIM_ERR_MAX])
{
    scenario_t *sc = malloc(sizeof *sc);
    if (sc == NULL) {
        snprintf(err, SIM_ERR_MAX, "out of memory for a scenario");
        return NULL;
    }
    if (scenario_load(path, overrides, override_count, sc, err) != 0) {
        free(sc);
        return NULL;
    }
    return sc;
}

void scenario_destroy(scenario_t *sc)
{
    if (sc != NULL) {
        scenario_free(sc);
        free(sc);
    }
}

uint64_t scenario_steps(const scenario_t *sc)
{
    return (uint64_t)(sc->duration * 1000.0 / sc->control_period_ms + 0.5);
}

uint64_t scenario_seed(const scenario_t *sc) { return sc->seed; }

uint32_t sim_group_count(const sim_t *sim) { return sim->sc->group_count; }

const char *sim_group_name(const sim_t *sim, uint32_t g)
{
    SIM_ASSERT(g < sim->sc->group_count);
    return sim->sc->groups[g].name;
}

uint64_t sim_step_n(sim_t *sim, uint64_t n)
{
    uint64_t done = 0;
    while (done < n && !sim_done(sim) && sim_error(sim) == NULL) {
        sim_step(sim);
        done++;
    }
    return done;
}

void sim_group_robots(const sim_t *sim, uint32_t g, uint32_t *first, uint32_t *count)
{
    SIM_ASSERT(g < sim->sc->group_count);
    uint32_t i = 0;
    for (uint32_t k = 0; k < g; k++) {
        i += sim->sc->groups[k].count;
    }
    *first = i;
    *count = sim->sc->groups[g].count;
}

static const sim_field_type_t field_of_obs[] = {
    [OBS_U8] = SIM_FIELD_U8, [OBS_I8] = SIM_FIELD_I8, [OBS_U16] = SIM_FIELD_U16, [OBS_I16] = SIM_FIELD_I16,
    [OBS_U32] = SIM_FIELD_U32, [OBS_I32] = SIM_FIELD_I32, [OBS_FLOAT] = SIM_FIELD_F32,
};

int sim_group_observable_at(const sim_t *sim, uint32_t g, uint32_t k, sim_field_t *out, float *scale)
{
    SIM_ASSERT(g < sim->sc->group_count);
    const controller_def_t *def = sim->sc->groups[g].def;
    if (def->observables == NULL || k >= observable_count(def->observables)
        || sim->ctrl_blocks[g] == NULL) {
        return -1;
    }
    const observable_t *o = &def->observables[k];
    SIM_ASSERT(o->type < sizeof field_of_obs / sizeof field_of_obs[0]);
    out->name = o->name;
    out->unit = o->unit ? o->unit : "";
    out->doc = o->doc ? o->doc : "";
    out->type = field_of_obs[o->type];
    out->base = (const uint8_t *)sim->ctrl_blocks[g] + o->offset;
    out->stride = (def->state_size + 15u) & ~(size_t)15u;   /* as sim.c lays the states out */
    out->count = 1;
    *scale = o->scale;
    return 0;
}

void sim_robot_state_names(const sim_t *sim, uint32_t first, uint32_t count, const char **names)
{
    SIM_ASSERT(first <= sim->n && count <= sim->n - first);
    for (uint32_t j = 0; j < count; j++) {
        const sim_robot_t *r = &sim->robots[first + j];
        names[j] = r->ctrl ? r->def->state_name(r->ctrl) : NULL;
    }
}

uint16_t sim_robot_id(const sim_t *sim, uint32_t i)
{
    SIM_ASSERT(i < sim->n);
    return sim->robots[i].id;
}

void sim_set_robot_id(sim_t *sim, uint32_t i, uint16_t id)
{
    SIM_ASSERT(i < sim->n);
    sim->robots[i].id = id;
}

uint32_t sim_robot_uart(const sim_t *sim, uint32_t i, const uint8_t **bytes)
{
    SIM_ASSERT(i < sim->n);
    const robot_link_t *l = sim_robot_link(sim, i);
    *bytes = l ? l->raw : NULL;
    return l ? l->raw_len : 0u;
}

char *sim_summary_json(const sim_t *sim, const char *code_version, const char *command,
                       const scenario_override_t *overrides, size_t override_count, char err[SIM_ERR_MAX])
{
    const scenario_t *sc = sim->sc;
    char *effective = NULL, *text = NULL;
    size_t effective_len = 0, text_len = 0;
    FILE *f = open_memstream(&effective, &effective_len);
    if (f == NULL) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the summary");
        return NULL;
    }
    int rc = scenario_write_effective(sc->path, overrides, override_count, f, err);
    if (fclose(f) != 0 || rc != 0) {
        if (rc == 0) snprintf(err, SIM_ERR_MAX, "out of memory for the summary");
        free(effective);
        return NULL;
    }
    provenance_t pv = {
        .code_version = code_version, .command = command, .overrides = overrides,
        .override_count = override_count, .scenario_hash = summary_text_hash(effective, effective_len),
    };
    free(effective);
    metric_list_t m;
    metrics_final(sim, &m);
    f = open_memstream(&text, &text_len);
    if (f == NULL) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the summary");
        return NULL;
    }
    summary_write_run(f, sc, &pv, sim, sim->seed, sim->step, sim_state_hash(sim), &m);
    if (fclose(f) != 0) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the summary");
        free(text);
        return NULL;
    }
    return text;
}
