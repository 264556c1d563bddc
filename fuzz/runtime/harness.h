/*
 * harness.h - what the runtime fuzz harnesses share: an input cursor, a CAN bus that checks
 * every frame the node sends, a RAM NV memory, a minimal SDO client, and the final check
 * that the node still serves. Each harness is one translation unit that includes this file
 * and defines LLVMFuzzerTestOneInput. A property violation calls abort(), which libFuzzer
 * and the replay program (replay.c) both report as a finding.
 */
#ifndef HARNESS_H
#define HARNESS_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "odg_node.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define NID 5u
#define SDO_RX (0x600u + NID)
#define SDO_TX (0x580u + NID)

/* A property of the runtime does not hold: a finding. */
#define REQUIRE(cond)    \
    do {                 \
        if (!(cond)) {   \
            abort();     \
        }                \
    } while (0)

/* ---- input ------------------------------------------------------------------------------ */

typedef struct {
    const uint8_t *p;
    size_t n;
} input_t;

/* The next byte, 0 once the input is used up. */
static uint8_t take(input_t *in)
{
    uint8_t b = 0;
    if (in->n > 0u) {
        b = *in->p++;
        in->n--;
    }
    return b;
}

static uint16_t take16(input_t *in)
{
    uint16_t lo = take(in);
    return (uint16_t)(lo | (unsigned)take(in) << 8);
}

static uint32_t take32(input_t *in)
{
    uint32_t lo = take16(in);
    return lo | (uint32_t)take16(in) << 16;
}

static void take_bytes(input_t *in, uint8_t *dst, size_t len)
{
    size_t i;
    for (i = 0; i < len; i++) {
        dst[i] = take(in);
    }
}

/* ---- the bus ----------------------------------------------------------------------------- */

static odg_node_t node;
static odg_frame_t last_sdo; /* the newest frame on SDO_TX */
static unsigned n_sdo;       /* frames on SDO_TX since bus_clear() */
static int send_fails;       /* the next n sends fail (a busy controller) */

/* Every frame the node sends is a well-formed 11-bit frame; SDO responses have 8 bytes. */
static int bus_send(void *ctx, const odg_frame_t *f)
{
    (void)ctx;
    REQUIRE(f->len <= 8u && f->id <= 0x7FFu && f->flags == 0u);
    REQUIRE(f->id != SDO_TX || f->len == 8u);
    if (send_fails > 0) {
        send_fails--;
        return -1;
    }
    if (f->id == SDO_TX) {
        last_sdo = *f;
        n_sdo++;
    }
    return 0;
}

static void bus_clear(void)
{
    n_sdo = 0;
    memset(&last_sdo, 0, sizeof last_sdo);
}

static void frame(uint32_t id, uint8_t flags, const uint8_t *data, uint8_t len)
{
    odg_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = id;
    f.flags = flags;
    f.len = len;
    memcpy(f.data, data, 8);
    odg_node_receive(&node, &f);
}

/* ---- NV memory in RAM ---------------------------------------------------------------------- */

static uint8_t nv_mem[4096];

static int nv_in(uint32_t addr, uint32_t len)
{
    return addr <= sizeof nv_mem && len <= sizeof nv_mem - addr;
}

static int nv_read(void *ctx, uint32_t addr, void *buf, uint32_t len)
{
    (void)ctx;
    REQUIRE(nv_in(addr, len)); /* the runtime stays inside the groups' slots */
    memcpy(buf, nv_mem + addr, len);
    return 0;
}

static int nv_write(void *ctx, uint32_t addr, const void *buf, uint32_t len)
{
    (void)ctx;
    REQUIRE(nv_in(addr, len));
    memcpy(nv_mem + addr, buf, len);
    return 0;
}

static int nv_erase(void *ctx, uint32_t addr, uint32_t len)
{
    (void)ctx;
    REQUIRE(nv_in(addr, len));
    memset(nv_mem + addr, 0xFF, len);
    return 0;
}

static const odg_nv_driver_t nv_ram = {nv_read, nv_write, nv_erase, NULL};

/* ---- node and SDO client ---------------------------------------------------------------- */

static void node_start(const odg_dict_t *dict)
{
    odg_node_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.dict = dict;
    cfg.node_id = NID;
    cfg.nv = &nv_ram;
    cfg.send = bus_send;
    send_fails = 0;
    memset(nv_mem, 0xFF, sizeof nv_mem);
    REQUIRE(odg_node_init(&node, &cfg) == ODG_OK);
}

/* An expedited download of 1..4 bytes; the abort code answered (0: done). */
static uint32_t sdo_write(uint16_t index, uint8_t sub, uint32_t value, uint8_t len)
{
    uint8_t d[8];
    d[0] = (uint8_t)(0x23u | (4u - len) << 2);
    d[1] = (uint8_t)index;
    d[2] = (uint8_t)(index >> 8);
    d[3] = sub;
    d[4] = (uint8_t)value;
    d[5] = (uint8_t)(value >> 8);
    d[6] = (uint8_t)(value >> 16);
    d[7] = (uint8_t)(value >> 24);
    bus_clear();
    frame(SDO_RX, 0, d, 8);
    if (odg_node_state(&node) == ODG_NMT_STOPPED) { /* no SDO while stopped */
        REQUIRE(n_sdo == 0u);
        return ODG_ABORT_DATA_STATE;
    }
    REQUIRE(n_sdo == 1u);
    return last_sdo.data[0] == 0x80u ? (uint32_t)last_sdo.data[4] | (uint32_t)last_sdo.data[5] << 8 |
                                           (uint32_t)last_sdo.data[6] << 16 | (uint32_t)last_sdo.data[7] << 24
                                     : 0u;
}

/* Whatever came before, once the bus is quiet and the node pre-operational again, an abort
 * from the client ends any transfer and a fresh upload of 0x1000 is answered, expedited. */
static void still_serving(void)
{
    static const uint8_t preop[8] = {0x80, 0}, abort_[8] = {0x80, 0, 0, 0, 0, 0, 0, 0},
                         up[8] = {0x40, 0x00, 0x10, 0};
    send_fails = 0;
    frame(0, 0, preop, 2);
    frame(SDO_RX, 0, abort_, 8);
    bus_clear();
    frame(SDO_RX, 0, up, 8);
    REQUIRE(n_sdo == 1u && last_sdo.data[0] == 0x43u);
    REQUIRE(last_sdo.data[1] == 0x00u && last_sdo.data[2] == 0x10u && last_sdo.data[3] == 0u);
}

/* The hook the alltypes options name for 0x2006 (POST_WRITE). */
odg_abort_t alltypes_notice(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                            void *ctx);
odg_abort_t alltypes_notice(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                            void *ctx)
{
    (void)ref, (void)kind, (void)data, (void)len, (void)ctx;
    return ODG_OK;
}

/* Hooks the input can switch between: accept everything, or refuse. */
static odg_abort_t hook_ok(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len, void *ctx)
{
    (void)ref, (void)kind, (void)data, (void)len, (void)ctx;
    return ODG_OK;
}

static odg_abort_t hook_refuse(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                               void *ctx)
{
    (void)ref, (void)data, (void)len, (void)ctx;
    return kind == ODG_HOOK_POST_WRITE ? ODG_ABORT_GENERAL : ODG_ABORT_VALUE_RANGE;
}

static odg_hook_fn pick_hook(uint8_t b)
{
    return b % 3u == 0u ? NULL : (b % 3u == 1u ? hook_ok : hook_refuse);
}

/* The number of sub-entry descriptors the entries hold, each member of a shared run
 * (ODG_E_SHARED) counting its own: dict->n_subs when the dictionary has no run. */
static uint32_t subs_of_entries(const odg_dict_t *d)
{
    uint32_t n = 0, k;
    for (k = 0; k < d->n_entries; k++) {
        n += d->entries[k].count;
    }
    return n;
}

/* The sub-entry numbered `k` (below subs_of_entries) of the entries in turn, with its index, as
 * odg_find gives it: entry by entry, so that every member of a shared run is reached (they share
 * their descriptors' positions); without runs, the sub-entry at position k of dict->subs. */
static uint16_t index_of(const odg_dict_t *d, uint32_t k, uint8_t *sub)
{
    const odg_entry_t *e = d->entries;
    while (k >= e->count) {
        k -= e->count;
        e++;
    }
    *sub = d->subs[e->first + k].sub;
    return e->index;
}

/* Refers to every helper, so that a harness that does not call one compiles without
 * -Wunused-function. */
void harness_keep_(void);
void harness_keep_(void)
{
    (void)take32, (void)sdo_write, (void)index_of, (void)subs_of_entries, (void)pick_hook, (void)still_serving,
        (void)node_start;
}

#endif /* HARNESS_H */
