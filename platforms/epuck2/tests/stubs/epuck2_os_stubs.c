/* epuck2_os_stubs.c - epuck2_stubs.h: the ChibiOS glue (epuck2_os.h): a
 * clock the test sets, the serial queues as the test's buffers. */
#include "epuck2_stubs.h"

#include <stddef.h>

#include "epuck2_os.h"

void epuck2_os_init(void) { epuck2_stub.os_inits++; }
uint32_t epuck2_os_time_ms(void) { return epuck2_stub.now_ms; }
void epuck2_os_idle(void)
{
    epuck2_stub.idles++;
    epuck2_stub.now_ms += epuck2_stub.idle_step_ms;
}
uint16_t epuck2_os_robot_id(void) { return epuck2_stub.robot_id; }
uint16_t epuck2_os_serial_write(const uint8_t *bytes, uint16_t len)
{
    uint16_t n = len, i;
    if (epuck2_stub.tx_room >= 0 && n > (uint16_t)epuck2_stub.tx_room) {
        n = (uint16_t)epuck2_stub.tx_room;
    }
    for (i = 0; i < n && epuck2_stub.tx_len < EPUCK2_STUB_LOG; i++) {
        epuck2_stub.tx_log[epuck2_stub.tx_len++] = bytes[i];
    }
    return n;
}
uint16_t epuck2_os_serial_read(uint8_t *buf, uint16_t cap)
{
    uint16_t n = 0u;
    while (n < cap && epuck2_stub.rx != NULL && epuck2_stub.rx_pos < epuck2_stub.rx_len) {
        buf[n++] = epuck2_stub.rx[epuck2_stub.rx_pos++];
    }
    return n;
}

