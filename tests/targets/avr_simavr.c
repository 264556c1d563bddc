/*
 * avr_simavr.c - what an AVR needs to run odgen's self-test under simavr: stdout written to
 * simavr's console register, and an exit simavr notices (it stops when the CPU sleeps with
 * interrupts off). Built with the self-test: --cflags "-mmcu=MCU -Wl,--section-start=.mmcu=0x910000
 * avr_simavr.c" (.mmcu out of flash: between .text and .data it would shift the initial data
 * simavr loads right after .text); run with
 * simavr -m MCU -f FREQ.
 */
#include <avr/io.h>
#include <stdint.h>
#include <stdio.h>

#define CONSOLE GPIOR0 /* an I/O register nothing else uses */

/* simavr reads its settings from the ELF's .mmcu section: tag AVR_MMCU_TAG_SIMAVR_CONSOLE
 * (11) and the data address of the register whose writes it prints. */
struct mmcu_addr {
    uint8_t tag;
    uint8_t len;
    void *what;
} __attribute__((packed));
__attribute__((section(".mmcu"), used)) static const struct mmcu_addr console_tag = {
    11, sizeof(void *), (void *)&CONSOLE};

/* simavr prints the console's line on '\r' (prefixed "O:") and drops other control bytes. */
static int console_put(char c, FILE *stream)
{
    (void)stream;
    CONSOLE = (uint8_t)(c == '\n' ? '\r' : c);
    return 0;
}

static FILE console = FDEV_SETUP_STREAM(console_put, NULL, _FDEV_SETUP_WRITE);

__attribute__((constructor)) static void console_open(void)
{
    stdout = &console;
    stderr = &console;
}

/* Between exit()'s cli and its endless loop (avr-libc runs the .fini sections in between):
 * sleep with interrupts off, which ends the simulation. */
__attribute__((naked, used, section(".fini1"))) static void stop_simulation(void)
{
    __asm__ volatile("sleep");
}
