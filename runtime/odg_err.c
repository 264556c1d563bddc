/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_err.c - the node's errors: those active and the error register 0x1001 that follows them,
 * the pre-defined error field (0x1003: the history of the errors its EMCY frames reported,
 * newest first), and the EMCY inhibit time (0x1015).
 *
 * Active errors (odg_node_error_set / _clear), at most ODG_NODE_MAX_ERRORS, by code: 0x1001 is
 * the union of their register bits with the generic bit, 0 when none is active. An EMCY goes
 * out when an error becomes active, and an "error reset" (0x0000) when the last one is gone;
 * CiA 301 lets a device also send one when some but not all are gone, this one does not.
 *
 * Each EMCY with a non-zero code (odg_node_emcy) pushes code | vendor bytes 0-1 << 16 into
 * sub 1, moving the older ones down; sub 0 counts them, up to the highest sub-index the
 * dictionary has. 0x1003 is read-only for SDO except sub 0, where only 0 may be written
 * (CiA 301: it clears the history; anything else aborts 0x06090030). The values are RAM:
 * a reset of the node empties the history, a reset of communication keeps it.
 *
 * EMCY inhibit time: no EMCY within 0x1015 (100 µs units; 0 or absent: none) of the previous
 * one. An EMCY due earlier waits, in order, in a queue of ODG_NODE_EMCY_QUEUE frames, sent
 * from the ticks (millisecond resolution). The time of the first tick after an EMCY sent
 * between ticks does not count, as it may have passed before the EMCY: the gap is never
 * shorter. When the queue is full, an EMCY is refused (ODG_ABORT_HARDWARE, as when the
 * transport cannot take it). A reset empties the queue.
 */
#include <string.h>

#include "odg_impl.h"
#include "odg_node.h"

#define ERROR_REGISTER 0x1001u
#define HISTORY 0x1003u

/* ---- active errors and the error register ------------------------------------------------ */

uint8_t odg_node_error_bits(uint16_t code)
{
    /* by the code's first digit: 0 error reset / no error, 2 current, 3 voltage, 4 temperature */
    static const uint8_t by_digit[16] = {
        0, ODG_ERR_GENERIC, ODG_ERR_GENERIC | ODG_ERR_CURRENT, ODG_ERR_GENERIC | ODG_ERR_VOLTAGE,
        ODG_ERR_GENERIC | ODG_ERR_TEMPERATURE, ODG_ERR_GENERIC, ODG_ERR_GENERIC, ODG_ERR_GENERIC,
        ODG_ERR_GENERIC, ODG_ERR_GENERIC, ODG_ERR_GENERIC, ODG_ERR_GENERIC,
        ODG_ERR_GENERIC, ODG_ERR_GENERIC, ODG_ERR_GENERIC, ODG_ERR_GENERIC};
    unsigned group = code >> 8;
    uint8_t bits = by_digit[code >> 12];
    if (group == 0x81u || group == 0x82u) {
        bits |= ODG_ERR_COMMUNICATION; /* monitoring: only these are communication, the rest device profiles' */
    } else if (group == 0xFFu) {
        bits |= ODG_ERR_MANUFACTURER;
    }
    return bits;
}

/* The storage of a numeric sub the node may write (0x1001, 0x1003: RAM or a group's mirror, at
 * most 4 bytes: a build without streams and types wider than 32 bits has no other), found into
 * `r`; NULL when there is none. */
static uint8_t *slot(const odg_node_t *n, uint16_t index, uint8_t sub, odg_ref_t *r)
{
    if (odg_find(n->cfg.dict, index, sub, r) != ODG_OK ||
        ((T_STREAM != 0u || ODG_CFG_INT64) && r->sub->size > 4u) ||
        ODG_S_CLASS(r->sub->storage) == ODG_S_ROM || ODG_S_CLASS(r->sub->storage) == ODG_S_COMMAND) {
        return NULL;
    }
    return odg_value_(n->cfg.dict, r->sub);
}

/* 0x1001 from the active errors; read-only for SDO, so set as the application would (odg_set,
 * which the node then need not link). */
static void register_update(odg_node_t *n)
{
    uint8_t k, *p, reg = 0;
    odg_ref_t r;
    for (k = 0; k < n->err.active; k++) {
        reg |= n->err.bits[k];
    }
    n->error_register = reg;
    p = slot(n, ERROR_REGISTER, 0, &r);
    if (p != NULL && odg_num_get_(p, r.sub->size) != reg) {
        odg_num_put_(p, r.sub->size, reg);
        odg_changed(n->cfg.dict, &r); /* the clients hear of changes only */
    }
}

ODG_NODE_OUTLINE_ static uint8_t active(const odg_node_t *n, uint16_t code)
{
    uint8_t k = 0;
    while (k < n->err.active && n->err.code[k] != code) {
        k++;
    }
    return k; /* err_active: not active */
}

/* The last active error takes the place of error k: their order does not matter (0x1001 is the
 * union of their bits), and the node then links no memmove. */
ODG_NODE_OUTLINE_ static void forget(odg_node_t *n, uint32_t k)
{
    n->err.active--;
    n->err.code[k] = n->err.code[n->err.active];
    n->err.bits[k] = n->err.bits[n->err.active];
}

odg_abort_t odg_node_error_set(odg_node_t *node, uint16_t code, uint8_t bits, const uint8_t *vendor,
                               uint8_t n_vendor)
{
    if (code == 0u) {
        return ODG_ABORT_VALUE_RANGE;
    }
    if (active(node, code) < node->err.active) {
        return ODG_OK;
    }
    if (node->err.active >= ODG_NODE_MAX_ERRORS) {
        return ODG_ABORT_NO_RESOURCE;
    }
    node->err.code[node->err.active] = code;
    node->err.bits[node->err.active++] = (uint8_t)(odg_node_error_bits(code) | bits | ODG_ERR_GENERIC);
    register_update(node);
    return odg_node_emcy(node, code, node->error_register, vendor, n_vendor);
}

odg_abort_t odg_node_error_clear(odg_node_t *node, uint16_t code)
{
    uint8_t k = active(node, code);
    if (k >= node->err.active) {
        return ODG_OK;
    }
    forget(node, k);
    register_update(node);
    return node->err.active == 0u ? odg_node_emcy(node, 0x0000, node->error_register, NULL, 0) : ODG_OK;
}

void odg_err_reset_(odg_node_t *n, int all)
{
    uint32_t k = n->err.active;
    while (k-- > 0u) {
        if (all || (n->err.code[k] >> 8) == 0x81u || (n->err.code[k] >> 8) == 0x82u) {
            forget(n, k);
        }
    }
    register_update(n);
}

/* ---- the pre-defined error field --------------------------------------------------------- */

/* The newest entry goes to sub 1, each older one a sub further (which costs one lookup of each
 * sub), up to one past the count or the last sub there is; sub 0 counts those written. The entry
 * of the EMCY frame `d`: its code (bytes 0-1) and first two vendor bytes (3-4) << 16. */
static void record(odg_node_t *n, const uint8_t *d)
{
    uint32_t count, k, old, carry = d[0] | (uint32_t)d[1] << 8 | (uint32_t)d[3] << 16 | (uint32_t)d[4] << 24;
    odg_ref_t r0, r;
    uint8_t *p0, *p;
    if ((carry & 0xFFFFu) == 0u || (p0 = slot(n, HISTORY, 0, &r0)) == NULL) {
        return; /* an error reset (not an error), or no history kept */
    }
    count = (uint32_t)odg_num_get_(p0, r0.sub->size);
    for (k = 1; k <= count + 1u && k <= 254u && (p = slot(n, HISTORY, (uint8_t)k, &r)) != NULL; k++) {
        old = (uint32_t)odg_num_get_(p, r.sub->size);
        odg_num_put_(p, r.sub->size, carry);
        carry = old;
    }
    if (k > 1u) {
        odg_num_put_(p0, r0.sub->size, k - 1u);
    }
}

void odg_err_written_(odg_node_t *n)
{
    uint32_t k;
    odg_ref_t r;
    uint8_t *p = slot(n, HISTORY, 0, &r);
    if (p == NULL || odg_num_get_(p, r.sub->size) != 0u) {
        return; /* the write was refused: the history stays */
    }
    for (k = 1; k < 255u && (p = slot(n, HISTORY, (uint8_t)k, &r)) != NULL; k++) {
        odg_num_put_(p, r.sub->size, 0);
    }
}

/* Send an EMCY frame; the inhibit time (0x1015) starts. The time of the first tick after one
 * sent between ticks does not count. Non-zero when `send` failed. */
static int emcy_out(odg_node_t *n, const uint8_t *data, uint8_t between_ticks)
{
    if (odg_io_send_(n, n->err.cob, data, 8) != 0) {
        return 1;
    }
    n->err.inhibit_us = odg_io_num_(n, 0x1015, 0) * 100u;
    n->err.fresh = between_ticks;
    return 0;
}

/* Send an EMCY frame now, or when the inhibit time since the last one has passed. */
static odg_abort_t emcy_send(odg_node_t *n, const uint8_t *data)
{
    odg_err_t *e = &n->err;
    if (e->inhibit_us == 0u && e->queued == 0u) {
        return emcy_out(n, data, 1) ? ODG_ABORT_HARDWARE : ODG_OK;
    }
    if (e->queued >= ODG_NODE_EMCY_QUEUE) {
        return ODG_ABORT_HARDWARE;
    }
    odg_copy(e->queue[e->queued++], data, 8);
    return ODG_OK;
}

odg_abort_t odg_node_emcy(odg_node_t *node, uint16_t code, uint8_t error_register,
                          const uint8_t *vendor, uint8_t n_vendor)
{
    uint8_t d[8];
    memset(d, 0, sizeof d);
    d[0] = (uint8_t)code;
    d[1] = (uint8_t)(code >> 8);
    d[2] = error_register;
    if (vendor != NULL) {
        odg_copy(d + 3, vendor, n_vendor < 5u ? n_vendor : 5u);
    }
    record(node, d); /* whether it goes out or not */
    if (!ODG_IO_TALKING(node) || (node->err.cob & ODG_COB_INVALID)) {
        return ODG_ABORT_DATA_STATE;
    }
    return emcy_send(node, d);
}

void odg_err_tick_(odg_node_t *n, uint32_t ms)
{
    odg_err_t *e = &n->err;
    uint32_t us = e->fresh ? 0u : ms > 4000000u ? 0xFFFFFFFFu : ms * 1000u;
    e->fresh = 0;
    e->inhibit_us = e->inhibit_us > us ? e->inhibit_us - us : 0u;
    if (e->inhibit_us != 0u || e->queued == 0u || (e->cob & ODG_COB_INVALID) || !ODG_IO_TALKING(n)) {
        return;
    }
    if (emcy_out(n, e->queue[0], 0) == 0) {
        e->queued--;
        /* the rest move up a row: odg_copy goes from the first byte up, so it may overlap so */
        odg_copy(e->queue, (const uint8_t *)e->queue + 8, 8u * e->queued);
    }
}
