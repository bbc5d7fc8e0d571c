/*
 * robot_id.c - the robot id the flasher stored in program memory (XC16
 * only: it reads program memory with the table-read instructions, as the
 * e-puck library's camera driver does for its EEPROM word).
 *
 * tools/flash/epuck_flash.py --robot-id N writes N into the low 16 bits of
 * the instruction word at program address 0x17F36, in the bootloader's row
 * (just below the relocated user reset vector at 0x17F38).  An erased word
 * reads 0xFFFF: no id was given.
 */
#include <xc.h>
#include <stdint.h>

#include "hal_epuck.h"

#define ROBOT_ID_PAGE 0x0001u     /* 0x17F36 >> 16 */
#define ROBOT_ID_OFFSET 0x7F36u   /* 0x17F36 & 0xFFFF */

uint16_t hal_epuck_flash_robot_id(void)
{
    uint16_t saved = TBLPAG;
    uint16_t id;
    TBLPAG = ROBOT_ID_PAGE;
    id = __builtin_tblrdl(ROBOT_ID_OFFSET);
    TBLPAG = saved;
    return id;
}
