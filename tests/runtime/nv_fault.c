/*
 * nv_fault.c - the fault-injecting NV driver of nv_fault.h.
 */
#include <string.h>

#include "nv_fault.h"

uint32_t nv_fault_rand(nv_fault_t *f)
{
    f->rng ^= f->rng << 13;
    f->rng ^= f->rng >> 17;
    f->rng ^= f->rng << 5;
    return f->rng;
}

static int in_range(const nv_fault_t *f, uint32_t addr, uint32_t len)
{
    return !f->dead && addr <= f->size && len <= f->size - addr;
}

/* One more byte may be programmed or erased; else the power fails now. */
static int spend(nv_fault_t *f)
{
    if (f->budget == 0) {
        f->dead = 1;
        return 0;
    }
    if (f->budget > 0) {
        f->budget--;
    }
    f->bytes++;
    return 1;
}

static int nv_read(void *ctx, uint32_t addr, void *buf, uint32_t len)
{
    nv_fault_t *f = (nv_fault_t *)ctx;
    if (!in_range(f, addr, len)) {
        return -1;
    }
    f->reads++;
    memcpy(buf, f->mem + addr, len);
    return 0;
}

static int nv_write(void *ctx, uint32_t addr, const void *buf, uint32_t len)
{
    nv_fault_t *f = (nv_fault_t *)ctx;
    const uint8_t *b = (const uint8_t *)buf;
    uint32_t i;
    if (!in_range(f, addr, len)) {
        return -1;
    }
    f->writes++;
    if (f->fail_write > 0 && --f->fail_write == 0) {
        return -1;
    }
    for (i = 0; i < len; i++) {
        if (!spend(f)) {
            if (f->torn) {
                f->mem[addr + i] &= (uint8_t)(b[i] | nv_fault_rand(f)); /* some bits not yet cleared */
            }
            return -1;
        }
        f->mem[addr + i] &= b[i];
    }
    return 0;
}

static int nv_erase(void *ctx, uint32_t addr, uint32_t len)
{
    nv_fault_t *f = (nv_fault_t *)ctx;
    uint32_t i;
    if (!in_range(f, addr, len)) {
        return -1;
    }
    f->erases++;
    for (i = 0; i < len; i++) {
        if (!spend(f)) {
            if (f->torn) {
                f->mem[addr + i] |= (uint8_t)nv_fault_rand(f); /* some bits not yet set */
            }
            return -1;
        }
        f->mem[addr + i] = 0xFF;
    }
    return 0;
}

void nv_fault_init(nv_fault_t *f, uint8_t *mem, uint32_t size, uint32_t seed)
{
    memset(f, 0, sizeof *f);
    f->driver.read = nv_read;
    f->driver.write = nv_write;
    f->driver.erase = nv_erase;
    f->driver.ctx = f;
    f->mem = mem;
    f->size = size;
    f->rng = seed;
    memset(mem, 0xFF, size);
    nv_fault_power_on(f);
}

void nv_fault_power_on(nv_fault_t *f)
{
    f->budget = -1;
    f->dead = 0;
    f->torn = 0;
    f->fail_write = 0;
}

void nv_fault_cut_after(nv_fault_t *f, long bytes)
{
    f->budget = bytes;
}

void nv_fault_flip(nv_fault_t *f, uint32_t addr, unsigned bit)
{
    if (addr < f->size) {
        f->mem[addr] ^= (uint8_t)(1u << (bit & 7u));
    }
}
