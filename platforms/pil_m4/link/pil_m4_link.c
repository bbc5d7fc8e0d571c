/* pil_m4_link.c - pil_m4_link.h. */
#include "pil_m4_link.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "pil_m4.h"

/* Instructions to SysTick ticks (PIL_M4_TICKS_TO_INSNS's inverse), clamped
 * to its 24 bits; 0: the most. */
static uint32_t ticks(uint64_t insns)
{
    uint64_t t = insns * 21u / 125u;
    return insns == 0u || t > PIL_M4_SYST_MAX + 1u ? PIL_M4_SYST_MAX + 1u : (uint32_t)(t ? t : 1u);
}

int pil_m4_link_open(pil_avr_link_t *l, const pil_m4_link_def_t *def, char err[PIL_HOST_ERR])
{
    char step[96], boot[96], kernel[PIL_HOST_ERR];
    if (access(def->image, R_OK) != 0) {
        memset(l, 0, sizeof *l);
        l->pid = -1;
        l->to = l->from = -1;
        snprintf(err, PIL_HOST_ERR, "image %s: %s (make pil-m4 builds the images)", def->image, strerror(errno));
        return -1;
    }
    /* The budgets into the port's scratch words, by QEMU's loader device
     * (written at reset, before the first instruction). */
    snprintf(step, sizeof step, "loader,addr=0x%08" PRIx32 ",data=%" PRIu32 ",data-len=4",
             (uint32_t)(PIL_M4_SCRATCH_ADDR + 4u * PIL_M4_STEP_BUDGET), ticks(def->budget));
    snprintf(boot, sizeof boot, "loader,addr=0x%08" PRIx32 ",data=%" PRIu32 ",data-len=4",
             (uint32_t)(PIL_M4_SCRATCH_ADDR + 4u * PIL_M4_BOOT_BUDGET), ticks(def->boot_budget));
    snprintf(kernel, sizeof kernel, "%s", def->image);
    const char *const argv[] = {
        PIL_M4_QEMU, "-M", "netduinoplus2", "-nodefaults", "-display", "none", "-monitor", "none",
        "-semihosting-config", "enable=on,target=native", "-icount", "shift=0",
        "-device", step, "-device", boot, "-kernel", kernel, NULL
    };
    pil_avr_link_def_t d = pil_avr_link_default_def();
    d.emulator = PIL_M4_QEMU;
    d.image = def->image;
    d.timeout_ms = def->timeout_ms;
    d.boot_timeout_ms = def->boot_timeout_ms;
    d.argv = argv;
    d.unit = "instructions";
    d.what = PIL_M4_QEMU " (Debian's qemu-system-arm)";
    return pil_avr_link_open(l, &d, err);
}
