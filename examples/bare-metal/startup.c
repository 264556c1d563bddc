/*
 * startup.c - the least a Cortex-M needs before main(): the vector table (initial stack
 * pointer, reset and the exception handlers this firmware uses) and a reset handler that
 * copies .data from flash, clears .bss and calls main. The vendor's startup file does the same
 * (and names every interrupt of the part); use it instead when you have one.
 */
#include <stdint.h>
#include <string.h>

#include "board.h"

extern uint32_t _stack_top, _data_load, _data_start, _data_end, _bss_start, _bss_end;
int main(void);

void Reset_Handler(void);
void Default_Handler(void);

void Reset_Handler(void)
{
    memcpy(&_data_start, &_data_load, (size_t)((uint8_t *)&_data_end - (uint8_t *)&_data_start));
    memset(&_bss_start, 0, (size_t)((uint8_t *)&_bss_end - (uint8_t *)&_bss_start));
    (void)main();
    for (;;) {
    }
}

/* An exception nobody expects: stop here, where a debugger shows it. */
void Default_Handler(void)
{
    for (;;) {
    }
}

typedef void (*vector_t)(void);

/* Exceptions 1..15, then the part's interrupts from IRQ 0: the CAN ones sit where the part's
 * reference manual puts them (here IRQ 20 receive and IRQ 22 status change, as on an STM32F4). */
#define IRQ(n) (16 + (n))
__attribute__((section(".isr_vector"), used)) static const vector_t vectors[IRQ(23)] = {
    [0] = (vector_t)(uintptr_t)&_stack_top,
    [1] = Reset_Handler,
    [2] = Default_Handler,  /* NMI */
    [3] = Default_Handler,  /* HardFault, also an unaligned access on a Cortex-M0 */
    [15] = SysTick_Handler, /* the millisecond tick */
    [IRQ(20)] = CAN_RX_IRQHandler,
    [IRQ(22)] = CAN_SCE_IRQHandler,
};
