/*
 * cortex_m.c - what a bare Cortex-M needs to run odgen's self-test under qemu-system-arm:
 * the vector table, a reset handler that sets up .data and .bss and calls main, and the
 * newlib system calls, which print and exit through semihosting (ARM DUI 0471: BKPT 0xAB,
 * operation in r0, argument in r1). A fault prints its name and ends the run as a failure.
 * Built with the self-test: --cflags "-mcpu=... -mthumb --specs=nano.specs -nostartfiles
 * -T cortex_m.ld cortex_m.c".
 */
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/stat.h>

#define SYS_WRITE0 0x04u
#define SYS_EXIT 0x18u
#define ADP_STOPPED_APPLICATION_EXIT 0x20026u /* qemu exits with status 0 */
#define ADP_STOPPED_RUN_TIME_ERROR 0x20023u   /* qemu exits with status 1 */

extern uint32_t __data_start, __data_end, __data_load, __bss_start, __bss_end, __stack_top, end;
int main(void);
void reset_handler(void);
void _exit(int status);

static uint32_t semihost(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

static void print(const char *text)
{
    (void)semihost(SYS_WRITE0, text);
}

static void fault(const char *name)
{
    print(name);
    print(": the self-test stopped\n");
    (void)semihost(SYS_EXIT, (const void *)ADP_STOPPED_RUN_TIME_ERROR);
    for (;;) {
    }
}

static void hard_fault(void) { fault("HardFault (an unaligned access traps here on a Cortex-M0)"); }
static void other_fault(void) { fault("unexpected exception"); }

typedef void (*vector_t)(void);
__attribute__((section(".vectors"), used)) static const vector_t vectors[16] = {
    (vector_t)(uintptr_t)&__stack_top, reset_handler, other_fault, hard_fault,
    other_fault, other_fault, other_fault, 0, 0, 0, 0, other_fault, other_fault, 0, other_fault, other_fault};

void reset_handler(void)
{
    const uint32_t *from = &__data_load;
    uint32_t *to;
#if defined(__ARM_FP)
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20; /* CPACR: the FPU on, before any float */
#endif
    for (to = &__data_start; to < &__data_end;) {
        *to++ = *from++;
    }
    for (to = &__bss_start; to < &__bss_end;) {
        *to++ = 0;
    }
    exit(main()); /* flushes stdout, then _exit */
}

/* ---- newlib system calls --------------------------------------------------------------- */

void _exit(int status)
{
    (void)semihost(SYS_EXIT, (const void *)(status == 0 ? ADP_STOPPED_APPLICATION_EXIT : ADP_STOPPED_RUN_TIME_ERROR));
    for (;;) {
    }
}

int _write(int fd, const char *data, int len);
int _write(int fd, const char *data, int len)
{
    char chunk[65];
    int done = 0;
    (void)fd; /* stdout and stderr both go to the host's output */
    while (done < len) {
        int n = 0;
        while (n < 64 && done < len) {
            char c = data[done++];
            chunk[n++] = c != '\0' ? c : ' ';
        }
        chunk[n] = '\0';
        print(chunk);
    }
    return len;
}

#define STACK_SIZE 4096 /* the top of RAM the heap leaves to the stack */

void *_sbrk(ptrdiff_t incr);
void *_sbrk(ptrdiff_t incr)
{
    static char *brk = (char *)&end;
    char *previous = brk;
    if (incr > (char *)&__stack_top - STACK_SIZE - brk) {
        errno = ENOMEM;
        return (void *)-1;
    }
    brk += incr;
    return previous;
}

int _close(int fd);
int _close(int fd) { (void)fd; return -1; }
int _fstat(int fd, struct stat *st);
int _fstat(int fd, struct stat *st) { (void)fd; st->st_mode = S_IFCHR; return 0; }
int _isatty(int fd);
int _isatty(int fd) { (void)fd; return 1; }
int _lseek(int fd, int offset, int whence);
int _lseek(int fd, int offset, int whence) { (void)fd; (void)offset; (void)whence; return 0; }
int _read(int fd, char *data, int len);
int _read(int fd, char *data, int len) { (void)fd; (void)data; (void)len; return 0; }
int _kill(int pid, int sig);
int _kill(int pid, int sig) { (void)pid; (void)sig; return -1; }
int _getpid(void);
int _getpid(void) { return 1; }
