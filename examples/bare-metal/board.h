/*
 * board.h - what the firmware needs from the hardware, kept to a few functions so that the
 * CANopen part (main.c, can.c, nv_eeprom.c) reads the same on any part. board.c has stubs that
 * build and link; replace their bodies with the vendor's HAL or register accesses.
 */
#ifndef BOARD_H
#define BOARD_H

#include <stdint.h>

/* Interrupt handlers (startup.c puts them in the vector table). */
void SysTick_Handler(void);
void CAN_RX_IRQHandler(void);
void CAN_SCE_IRQHandler(void);

/* Clocks, pins, SysTick at 1 kHz, the CAN controller at the bus's bit rate, its interrupts on. */
void board_init(void);

/* The CAN controller (11-bit identifiers). */
typedef struct board_can_frame {
    uint32_t id;
    uint8_t len;
    uint8_t rtr;
    uint8_t data[8];
} board_can_frame_t;
int board_can_transmit(const board_can_frame_t *frame); /* 0: in a free mailbox; else all busy */
int board_can_receive(board_can_frame_t *frame);        /* 1: a frame taken from the RX FIFO */
uint8_t board_can_error_state(void); /* 0 error active, 1 error passive, 2 bus-off */

/* An EEPROM (I2C or SPI, byte-writable): blocking reads and writes within its size. */
#define BOARD_EEPROM_SIZE 4096u
int board_eeprom_read(uint32_t addr, void *buf, uint32_t len);
int board_eeprom_write(uint32_t addr, const void *buf, uint32_t len);

/* Digital I/O of the io-node example: 8 inputs, 8 outputs. */
uint8_t board_read_inputs(void);
void board_write_outputs(uint8_t pins);

/* Interrupts off and on around the few lines that share data with an interrupt handler and
 * cannot do it with a single aligned word (see can.c). */
static inline uint32_t board_irq_save(void)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n cpsid i" : "=r"(primask) : : "memory");
    return primask;
}

static inline void board_irq_restore(uint32_t primask)
{
    __asm__ volatile("msr primask, %0" : : "r"(primask) : "memory");
}

/* Sleep until the next interrupt (the tick at the latest). */
static inline void board_wait_for_interrupt(void)
{
    __asm__ volatile("wfi" : : : "memory");
}

#endif /* BOARD_H */
