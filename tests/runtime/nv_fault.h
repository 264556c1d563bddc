/*
 * nv_fault.h - an NV driver for tests that models NOR flash (erase sets 0xFF, programming can
 * only clear bits) and injects faults: the power fails after a given number of programmed or
 * erased bytes (optionally leaving the byte in progress half done), the n-th write call fails,
 * and bits can be flipped at rest. Counters tell what a run did.
 */
#ifndef NV_FAULT_H
#define NV_FAULT_H

#include <stdint.h>

#include "odg_persist.h"

typedef struct nv_fault {
    odg_nv_driver_t driver; /* ctx points to this struct */
    uint8_t *mem;
    uint32_t size;
    uint32_t rng;      /* xorshift state for torn bytes and nv_fault_rand */
    long budget;       /* bytes that may still be programmed or erased; -1: no limit */
    int dead;          /* the power failed: every call fails until nv_fault_power_on */
    int torn;          /* the byte in progress when the power fails is left half done */
    long fail_write;   /* the n-th write call from now fails, programming nothing; 0: none */
    long bytes;        /* bytes programmed or erased */
    long writes, erases, reads;
} nv_fault_t;

/* `mem` (`size` bytes) starts erased; `seed` must not be 0. */
void nv_fault_init(nv_fault_t *f, uint8_t *mem, uint32_t size, uint32_t seed);
/* Power back: no budget, no pending failure. Memory keeps what the last run left. */
void nv_fault_power_on(nv_fault_t *f);
/* The power fails once `bytes` more bytes have been programmed or erased. */
void nv_fault_cut_after(nv_fault_t *f, long bytes);
void nv_fault_flip(nv_fault_t *f, uint32_t addr, unsigned bit);
uint32_t nv_fault_rand(nv_fault_t *f);

#endif /* NV_FAULT_H */
