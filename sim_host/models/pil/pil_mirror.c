/* pil_mirror.c - pil_mirror.h. */
#include "pil_mirror.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int pil_mirror_load(pil_mirror_t *m, const char *path, char err[SIM_ERR_MAX])
{
    memset(m, 0, sizeof *m);
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, SIM_ERR_MAX, "%s: %s (make pil-avr writes the images' state maps)", path, strerror(errno));
        return -1;
    }
    char line[256], word[16], type[64];
    unsigned version, avr_size, host_size;
    int ok = fgets(line, sizeof line, f) != NULL
             && sscanf(line, "pil-state-map %u %u %u %63s", &version, &avr_size, &host_size, type) == 4
             && version == 1u && avr_size <= 0xFFFFu;
    uint32_t lineno = 1, cap = 0;
    while (ok && fgets(line, sizeof line, f)) {
        unsigned a, h, sa = 0, sh = 0, sg = 0;
        lineno++;
        pil_mirror_op_t op = { 0, 0, 0, 0, 0, 0 };
        if (sscanf(line, "%15s", word) != 1) {
            continue;
        }
        if (!strcmp(word, "copy") && sscanf(line, "copy %u %u %u", &a, &h, &sa) == 3) {
            op.kind = PIL_MIRROR_COPY;
            sh = sa;
        } else if (!strcmp(word, "int") && sscanf(line, "int %u %u %u %u %u", &a, &h, &sa, &sh, &sg) == 5
                   && sa >= 1 && sa <= 8 && sh >= 1 && sh <= 8) {
            op.kind = PIL_MIRROR_INT;
        } else if (!strcmp(word, "double") && sscanf(line, "double %u %u", &a, &h) == 2) {
            op.kind = PIL_MIRROR_DOUBLE;
            sa = 4;
            sh = 8;
        } else if (!strcmp(word, "skip")) {
            continue;
        } else {
            ok = 0;
            break;
        }
        if (a + sa > avr_size || h + sh > host_size) {
            ok = 0;
            break;
        }
        op.avr_off = (uint16_t)a;
        op.host_off = (uint16_t)h;
        op.avr_size = (uint16_t)sa;
        op.host_size = (uint16_t)sh;
        op.is_signed = (uint8_t)(sg != 0);
        if (m->n == cap) {
            cap = cap ? 2 * cap : 16;
            pil_mirror_op_t *grown = realloc(m->ops, cap * sizeof *grown);
            if (!grown) {
                fclose(f);
                snprintf(err, SIM_ERR_MAX, "out of memory for %s", path);
                return -1;
            }
            m->ops = grown;
        }
        m->ops[m->n++] = op;
    }
    fclose(f);
    if (!ok) {
        snprintf(err, SIM_ERR_MAX, "%s:%u: not a line of a PIL state map (platforms/pil_avr/state_map.py)", path,
                 lineno);
        pil_mirror_free(m);
        return -1;
    }
    m->avr_size = (uint16_t)avr_size;
    m->host_size = host_size;
    return 0;
}

void pil_mirror_free(pil_mirror_t *m)
{
    free(m->ops);
    m->ops = NULL;
    m->n = 0;
}

void pil_mirror_apply(const pil_mirror_t *m, const uint8_t *avr, void *host)
{
    uint8_t *out = host;
    for (uint32_t k = 0; k < m->n; k++) {
        const pil_mirror_op_t *op = &m->ops[k];
        const uint8_t *src = avr + op->avr_off;
        uint8_t *dst = out + op->host_off;
        if (op->kind == PIL_MIRROR_COPY) {
            memcpy(dst, src, op->avr_size);
        } else if (op->kind == PIL_MIRROR_INT) {
            /* Little-endian both: low bytes as they are, then the extension. */
            uint8_t fill = (op->is_signed && (src[op->avr_size - 1u] & 0x80u)) ? 0xFFu : 0x00u;
            for (uint16_t b = 0; b < op->host_size; b++) {
                dst[b] = b < op->avr_size ? src[b] : fill;
            }
        } else {
            float f;
            memcpy(&f, src, sizeof f);
            double d = f;
            memcpy(dst, &d, sizeof d);
        }
    }
}
