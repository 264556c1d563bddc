/*
 * odg_err.c - the node's pre-defined error field (0x1003): the history of the errors its EMCY
 * frames reported, newest first; and the EMCY inhibit time (0x1015).
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
#include "odg_node_impl.h"

#define HISTORY 0x1003u

/* The storage of a numeric 0x1003 sub, or NULL when it has none the node may write. */
static uint8_t *slot(const odg_node_t *n, uint8_t sub, uint32_t *size)
{
    odg_ref_t r;
    if (odg_find(n->cfg.dict, HISTORY, sub, &r) != ODG_OK || r.sub->size > 4u ||
        ODG_S_CLASS(r.sub->storage) == ODG_S_ROM || ODG_S_CLASS(r.sub->storage) == ODG_S_STORE) {
        return NULL;
    }
    *size = r.sub->size;
    return odg_value_(n->cfg.dict, r.sub);
}

void odg_err_record_(odg_node_t *n, uint16_t code, const uint8_t *vendor, uint8_t n_vendor)
{
    uint32_t size0, size, count, k, entry = code;
    uint8_t *p0 = slot(n, 0, &size0), *p, *q;
    if (p0 == NULL || code == 0u) {
        return; /* no history kept, or an error reset (not an error) */
    }
    if (vendor != NULL && n_vendor > 0u) {
        entry |= (uint32_t)vendor[0] << 16 | (n_vendor > 1u ? (uint32_t)vendor[1] << 24 : 0u);
    }
    count = (uint32_t)odg_load_(p0, size0);
    for (k = count + 1u; k > 1u; k--) { /* sub k-1 moves to sub k, where there is one */
        p = slot(n, (uint8_t)k, &size);
        q = slot(n, (uint8_t)(k - 1u), &size);
        if (p != NULL && q != NULL) {
            odg_store_(p, size, odg_load_(q, size));
        } else if (p == NULL) {
            count = k - 2u; /* the oldest falls off the end */
        }
    }
    if ((p = slot(n, 1, &size)) != NULL) {
        odg_store_(p, size, entry);
        odg_store_(p0, size0, count + 1u > 254u ? 254u : count + 1u);
    }
}

odg_abort_t odg_err_check_(const odg_node_t *n, uint8_t sub, uint32_t value)
{
    (void)n;
    return sub == 0u && value != 0u ? ODG_ABORT_VALUE_RANGE : ODG_OK;
}

void odg_err_written_(odg_node_t *n)
{
    uint32_t size, k;
    uint8_t *p = slot(n, 0, &size);
    if (p == NULL || odg_load_(p, size) != 0u) {
        return; /* the write was refused: the history stays */
    }
    for (k = 1; k < 255u && (p = slot(n, (uint8_t)k, &size)) != NULL; k++) {
        odg_store_(p, size, 0);
    }
}

static void emcy_sent(odg_node_t *n, uint8_t between_ticks)
{
    n->emcy_inhibit_us = odg_node_get_or_(n, 0x1015, 0, 0) * 100u;
    n->emcy_fresh = between_ticks;
}

odg_abort_t odg_emcy_send_(odg_node_t *n, const uint8_t *data)
{
    if (n->emcy_inhibit_us == 0u && n->emcy_queued == 0u) {
        if (odg_node_send_(n, n->emcy_cob, data, 8) != 0) {
            return ODG_ABORT_HARDWARE;
        }
        emcy_sent(n, 1);
        return ODG_OK;
    }
    if (n->emcy_queued >= ODG_NODE_EMCY_QUEUE) {
        return ODG_ABORT_HARDWARE;
    }
    memcpy(n->emcy_queue[n->emcy_queued++], data, 8);
    return ODG_OK;
}

void odg_emcy_tick_(odg_node_t *n, uint32_t ms)
{
    uint32_t us = n->emcy_fresh ? 0u : ms > 4000000u ? 0xFFFFFFFFu : ms * 1000u;
    n->emcy_fresh = 0;
    n->emcy_inhibit_us = n->emcy_inhibit_us > us ? n->emcy_inhibit_us - us : 0u;
    if (n->emcy_inhibit_us != 0u || n->emcy_queued == 0u || (n->emcy_cob & ODG_COB_INVALID) ||
        (n->state != ODG_NMT_PRE_OPERATIONAL && n->state != ODG_NMT_OPERATIONAL)) {
        return;
    }
    if (odg_node_send_(n, n->emcy_cob, n->emcy_queue[0], 8) == 0) {
        n->emcy_queued--;
        memmove(n->emcy_queue[0], n->emcy_queue[1], (size_t)n->emcy_queued * 8u);
        emcy_sent(n, 0);
    }
}
