/*
 * board.c - stubs of the hardware functions of board.h: they build, link and do nothing (no
 * frame is received, every frame "sent" is dropped, the EEPROM is a RAM array). Replace each
 * body with the vendor HAL's calls; the comments say what each must do.
 */
#include <string.h>

#include "board.h"

void board_init(void)
{
    /* clocks; SysTick: SysTick->LOAD = core_hz / 1000 - 1, ->VAL = 0, ->CTRL = 7;
     * CAN: bit timing, filters (accept all 11-bit identifiers, or those of this node:
     * NMT 0x000, SYNC, TIME, 0x600 + id, the RPDOs' COB-IDs, heartbeats 0x701-0x77F, LSS 0x7E5),
     * automatic bus-off recovery, interrupts: FIFO 0 pending, error passive, bus-off. */
}

int board_can_transmit(const board_can_frame_t *frame)
{
    (void)frame; /* find an empty TX mailbox, write id, DLC, data, request transmission */
    return 0;
}

int board_can_receive(board_can_frame_t *frame)
{
    (void)frame; /* FIFO 0 not empty: copy id, DLC, RTR, data, release the FIFO entry */
    return 0;
}

uint8_t board_can_error_state(void)
{
    return 0; /* the error status register: bus-off flag, error passive flag */
}

static uint8_t eeprom[BOARD_EEPROM_SIZE]; /* stands in for the chip */

int board_eeprom_read(uint32_t addr, void *buf, uint32_t len)
{
    if (addr > BOARD_EEPROM_SIZE || len > BOARD_EEPROM_SIZE - addr) {
        return -1;
    }
    memcpy(buf, &eeprom[addr], len);
    return 0;
}

int board_eeprom_write(uint32_t addr, const void *buf, uint32_t len)
{
    if (addr > BOARD_EEPROM_SIZE || len > BOARD_EEPROM_SIZE - addr) {
        return -1;
    }
    memcpy(&eeprom[addr], buf, len); /* a real chip: page by page, polling for each write cycle */
    return 0;
}

uint8_t board_read_inputs(void)
{
    return 0; /* the input port's data register */
}

void board_write_outputs(uint8_t pins)
{
    (void)pins; /* the output port's data register */
}
