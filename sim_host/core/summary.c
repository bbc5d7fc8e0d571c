/*
 * summary.c - summary.json of a run and of a set of repetitions, with
 * their provenance; a run's summary read back (summary.h).
 */
#include "summary.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim_internal.h"
#include "swarmsim/task.h"

static void json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') fprintf(f, "\\%c", c);
        else if (c < 0x20) fprintf(f, "\\u%04x", c);
        else fputc(c, f);
    }
    fputc('"', f);
}

/* Numbers print with up to 10 significant digits: enough for every
 * metric, and the same bits always print the same text. */
static void json_number(FILE *f, double v)
{
    if (!isfinite(v)) fputs("null", f);
    else fprintf(f, "%.10g", v);
}

/* "scenario", "scenario_file", "groups": [{name, controller, policy,
 * count}, ...], "tasks": [...], then the provenance. */
static void write_head(FILE *f, const scenario_t *sc, const provenance_t *pv)
{
    fputs("{\n  \"scenario\": ", f);
    json_string(f, sc->name);
    fputs(",\n  \"scenario_file\": ", f);
    json_string(f, sc->path);
    fputs(",\n  \"scenario_copy\": \"" SUMMARY_SCENARIO_COPY "\"", f);
    fprintf(f, ",\n  \"scenario_hash\": \"%016" PRIx64 "\",\n  \"overrides\": [", pv->scenario_hash);
    for (size_t i = 0; i < pv->override_count; i++) {
        if (i) fputs(", ", f);
        json_string(f, pv->overrides[i].text);
    }
    fputs("],\n  \"groups\": [", f);
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const robot_group_t *grp = &sc->groups[g];
        fputs(g ? ",\n    {\"name\": " : "\n    {\"name\": ", f);
        json_string(f, grp->name);
        fputs(", \"controller\": ", f);
        json_string(f, grp->controller);
        fputs(", \"policy\": ", f);
        json_string(f, grp->policy);
        fprintf(f, ", \"count\": %u}", grp->count);
    }
    fputs(sc->group_count ? "\n  ],\n  \"tasks\": [" : "],\n  \"tasks\": [", f);
    for (uint32_t t = 0; t < sc->task_count; t++) {
        if (t) fputs(", ", f);
        json_string(f, sc->tasks[t].def->name);
    }
    fputs("],\n  \"code_version\": ", f);
    json_string(f, pv->code_version ? pv->code_version : "unknown");
    fputs(",\n  \"command\": ", f);
    json_string(f, pv->command ? pv->command : "");
    fputs(",\n", f);
    if (pv->control) {       /* commands came while it ran (control.h) */
        fprintf(f, "  \"control\": %s,\n", pv->control);
    }
}

/* Each metric's unit and one-line meaning, as the task or model declared it
 * (metrics_put), so that tools label a metric without a table of their own. */
static void write_metric_docs(FILE *f, const metric_list_t *m)
{
    fputs("  \"metric_docs\": {\n", f);
    for (unsigned k = 0; k < m->count; k++) {
        fprintf(f, "    \"%s\": {\"unit\": ", m->name[k]);
        json_string(f, m->unit[k] ? m->unit[k] : "");
        fputs(", \"doc\": ", f);
        json_string(f, m->doc[k] ? m->doc[k] : "");
        fputs(k + 1 < m->count ? "},\n" : "}\n", f);
    }
    fputs("  }\n", f);
}

void summary_write_run(FILE *f, const scenario_t *sc, const provenance_t *pv, const sim_t *sim,
                       uint64_t seed, uint64_t steps, uint64_t state_hash, const metric_list_t *m)
{
    write_head(f, sc, pv);
    for (uint32_t id = 0; sim != NULL && id < SIM_MODEL_COUNT; id++) {
        const model_def_t *model = sim_models[id];
        if (model->write_json) {
            model->write_json(sim, sim_model_self(sim, (sim_model_id_t)id), f);
        }
    }
    fprintf(f, "  \"seed\": %" PRIu64 ",\n  \"robots\": %u,\n  \"steps\": %" PRIu64 ",\n"
            "  \"control_period_ms\": %u,\n", seed, scenario_robot_count(sc), steps, sc->control_period_ms);
    fprintf(f, "  \"state_hash\": \"%016" PRIx64 "\",\n  \"metrics\": {\n", state_hash);
    for (unsigned k = 0; k < m->count; k++) {
        fprintf(f, "    \"%s\": ", m->name[k]);
        json_number(f, m->value[k]);
        fputs(k + 1 < m->count ? ",\n" : "\n", f);
    }
    fputs("  },\n", f);
    write_metric_docs(f, m);
    fputs("}\n", f);
}

void summary_write_aggregate(FILE *f, const scenario_t *sc, const provenance_t *pv,
                             uint64_t first_seed, uint32_t reps, uint64_t steps,
                             const metric_list_t *const *done, uint32_t n)
{
    write_head(f, sc, pv);
    fprintf(f, "  \"reps\": %u,\n  \"reps_done\": %u,\n  \"complete\": %s,\n  \"first_seed\": %" PRIu64
            ",\n  \"steps\": %" PRIu64 ",\n  \"metrics\": {\n", reps, n, n == reps ? "true" : "false",
            first_seed, steps);
    unsigned count = n ? done[0]->count : 0;
    for (unsigned k = 0; k < count; k++) {
        double sum = 0, sq = 0, lo = INFINITY, hi = -INFINITY;
        for (uint32_t r = 0; r < n; r++) {
            double v = done[r]->value[k];
            sum += v;
            lo = fmin(lo, v);
            hi = fmax(hi, v);
        }
        double mean = sum / n;
        for (uint32_t r = 0; r < n; r++) {
            double d = done[r]->value[k] - mean;
            sq += d * d;
        }
        double sd = n > 1 ? sqrt(sq / (n - 1)) : 0.0;
        fprintf(f, "    \"%s\": {\"mean\": ", done[0]->name[k]);
        json_number(f, mean);
        fputs(", \"sd\": ", f);
        json_number(f, sd);
        fputs(", \"min\": ", f);
        json_number(f, lo);
        fputs(", \"max\": ", f);
        json_number(f, hi);
        fputs(k + 1 < count ? "},\n" : "}\n", f);
    }
    fputs("  }", f);
    if (n) {
        fputs(",\n", f);
        write_metric_docs(f, done[0]);
    } else {
        fputc('\n', f);
    }
    fputs("}\n", f);
}

/* ------------------------------------------------------------ reading */

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len + 4096 + 1 > cap) {
            cap = cap ? 2 * cap : 16384;
            if (cap > (1u << 24)) break;     /* no summary is this large */
            char *nb = realloc(buf, cap);
            if (!nb) break;
            buf = nb;
        }
        size_t got = fread(buf + len, 1, 4096, f);
        len += got;
        if (got < 4096) {
            int bad = ferror(f);
            fclose(f);
            if (bad) {
                free(buf);
                return NULL;
            }
            buf[len] = '\0';
            return buf;
        }
    }
    fclose(f);
    free(buf);
    return NULL;
}

/* The text after `"key": ` at the top level of our own layout, or NULL. */
static const char *field(const char *doc, const char *key)
{
    char pat[80];
    snprintf(pat, sizeof pat, "\n  \"%s\": ", key);
    const char *p = strstr(doc, pat);
    return p ? p + strlen(pat) : NULL;
}

int summary_read_run(const char *path, uint64_t seed, const metric_list_t *names,
                     metric_list_t *out, uint64_t *steps, uint64_t *state_hash)
{
    char *doc = read_all(path);
    if (!doc) return -1;
    int rc = -1;
    const char *p;
    char *end;
    uint64_t v;
    memset(out, 0, sizeof *out);
    if (!(p = field(doc, "seed")) || (errno = 0, v = strtoull(p, &end, 10), errno) || v != seed) goto done;
    if (!(p = field(doc, "steps")) || (errno = 0, *steps = strtoull(p, &end, 10), errno)) goto done;
    if (!(p = field(doc, "state_hash")) || *p != '"') goto done;
    *state_hash = strtoull(p + 1, &end, 16);
    if (end != p + 17 || *end != '"') goto done;
    /* The values from the exact copy beside it (summary.json prints 10
     * digits; an aggregate over resumed runs must equal one over fresh). */
    free(doc);
    char exact_path[1100];
    const char *slash = strrchr(path, '/');
    snprintf(exact_path, sizeof exact_path, "%.*s" SUMMARY_EXACT_METRICS, slash ? (int)(slash - path + 1) : 0,
             path);
    doc = read_all(exact_path);
    if (!doc) return -1;
    for (unsigned k = 0; k < names->count; k++) {
        char pat[96];
        snprintf(pat, sizeof pat, "\n%s ", names->name[k]);
        const char *q = strstr(doc, pat);
        if (!q) goto done;
        q += strlen(pat);
        double x = strtod(q, &end);
        if (end == q) goto done;
        metrics_put(out, names->name[k], names->unit[k], names->doc[k], x);
    }
    rc = out->count == names->count ? 0 : -1;
done:
    free(doc);
    return rc;
}

void summary_write_exact(FILE *f, const metric_list_t *m)
{
    fputs("# swarmsim: this run's metrics, exact (C99 %a), for --resume\n", f);
    for (unsigned k = 0; k < m->count; k++) {
        fprintf(f, "%s %a\n", m->name[k], m->value[k]);
    }
}

uint64_t summary_text_hash(const char *text, size_t len)
{
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < len; i++) {
        h ^= (unsigned char)text[i];
        h *= 1099511628211ull;
    }
    return h;
}
