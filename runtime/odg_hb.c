/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_hb.c - NMT error control: the heartbeat producer (CiA 301: 0x1017) and consumer (0x1016),
 * node guarding and life guarding (0x100C, 0x100D), and what a communication error does (0x1029
 * sub 1). Calls odg_err.c and odg_node_io.c (odg_hb.h).
 *
 * Each 0x1016 entry (node-id in bits 16..23, time in ms in bits 0..15; node-id 0 or time 0:
 * unused) watches one node's heartbeat. Watching starts with the first heartbeat from that
 * node. A new state is reported to the application (odg_node_on_heartbeat); when no heartbeat
 * came within the time, the node sends EMCY 0x8130 (heartbeat error; error register: generic
 * and communication bits), reports ODG_HB_TIMEOUT, reacts as 0x1029 sub 1 says (2: stopped;
 * 1: no change; 0, other values or none: operational -> pre-operational; the hub carries the
 * reaction out after the tick's heartbeat and life guarding events), and watches again
 * from the next heartbeat. Entries are read at boot and after every SDO write to 0x1016; a
 * write naming a node-id that another used entry already watches aborts 0x06040043.
 * Heartbeats are consumed in every state but initialising.
 *
 * Node guarding: a remote frame on 0x700 + node-id is answered with the NMT state and a
 * toggle bit (bit 7, 0 in the first answer after a boot, then alternating), while the node
 * produces no heartbeat (0x1017 = 0 or absent: CiA 301 uses one or the other). Life
 * guarding: with guard time 0x100C (ms) and life time factor 0x100D both non-zero, from the
 * first remote frame on, no remote frame for their product is a life guarding event: error
 * 0x8130 (EMCY byte 3: the node's own id), then 0x1029 sub 1 as above; watched again from (and
 * the error gone with) the next remote frame.
 *
 * The CAN controller's state (odg_node_can_state, from the CAN driver): error passive is the
 * error 0x8120, bus-off a communication error (0x1029 sub 1), leaving bus-off the EMCY 0x8140.
 */
#include <string.h>

#include "odg_node.h"

#define EMCY_HEARTBEAT 0x8130u

/* ---- the heartbeat producer --------------------------------------------------------------- */

/* The heartbeat period is read from 0x1017 on every tick, so an SDO write (or an application
 * change) takes effect at once; 0 or an absent 0x1017 stops the heartbeat. */
void odg_hb_produce_(odg_node_t *n, uint32_t ms)
{
    uint32_t period = odg_io_num_(n, 0x1017, 0);
    uint32_t t = n->hb.timer + ms;
    if (period == 0u) {
        n->hb.timer = 0;
        return;
    }
    if (t < ms) {
        t = 0xFFFFFFFFu;
    }
    if (t >= period) {
        (void)odg_io_send_(n, 0x700u + n->cfg.node_id, &n->state, 1);
        t -= period; /* keep the phase when ticks do not divide the period ... */
        if (t >= period) {
            t = 0; /* ... but never send a burst after a long pause */
        }
    }
    n->hb.timer = t;
}

/* ---- the heartbeat consumer ---------------------------------------------------------------- */

#define GUARD ODG_NODE_MAX_HB /* watch[GUARD]: life guarding */

/* The error 0x8130 is gone when no watched node and no life guarding is in error. */
static void errors_gone(odg_node_t *n)
{
    uint32_t k;
    for (k = 0; k <= GUARD; k++) {
        if (n->hb.watch[k].lost) {
            return;
        }
    }
    (void)odg_node_error_clear(n, EMCY_HEARTBEAT);
}

/* A heartbeat (a remote frame, for life guarding) came: watched again from now. */
ODG_NODE_OUTLINE_ static void heard(odg_node_t *n, odg_hb_watch_t *w)
{
    w->elapsed = 0;
    w->started = 1;
    if (w->lost) {
        w->lost = 0;
        errors_gone(n);
    }
}

static uint8_t watched_id(uint32_t entry)
{
    uint8_t id = (uint8_t)(entry >> 16);
    return (entry & 0xFFFFu) != 0u && id >= 1u && id <= 127u ? id : 0u;
}

void odg_hb_load_(odg_node_t *n)
{
    uint32_t k, entry;
    odg_hb_watch_t *w = n->hb.watch;
    memset(w, 0, ODG_NODE_MAX_HB * sizeof *w); /* life guarding (watch[GUARD]) goes on */
    for (k = 0; k < ODG_NODE_MAX_HB; k++, w++) {
        entry = odg_io_num_(n, 0x1016, (uint8_t)(k + 1u)); /* 0 (not watched) when absent */
        w->id = watched_id(entry);
        if (w->id != 0u) {
            w->time = (uint16_t)entry;
        }
    }
    errors_gone(n); /* entries rewritten: none is in error */
}

odg_abort_t odg_hb_check_(const odg_node_t *n, uint8_t sub, uint32_t value)
{
    uint32_t k;
    uint8_t id = watched_id(value);
    for (k = 1; id != 0u && k <= 127u; k++) {
        if (k != sub && watched_id(odg_io_num_(n, 0x1016, (uint8_t)k)) == id) {
            return ODG_ABORT_INCOMPATIBLE;
        }
    }
    return ODG_OK;
}

static void report(odg_node_t *n, uint8_t id, uint8_t event)
{
    if (n->hb.on_heartbeat != NULL) {
        n->hb.on_heartbeat(n->hb.on_heartbeat_ctx, id, event);
    }
}

void odg_hb_receive_(odg_node_t *n, const odg_frame_t *f)
{
    uint32_t k;
    uint8_t id = (uint8_t)(f->id - 0x700u);
    for (k = 0; k < ODG_NODE_MAX_HB && f->len >= 1u; k++) {
        odg_hb_watch_t *w = &n->hb.watch[k];
        if (w->id == id) {
            if (!w->started || w->state != f->data[0]) {
                w->state = f->data[0];
                report(n, id, w->state);
            }
            heard(n, w);
        }
    }
}

/* A communication error: the NMT command 0x1029 sub 1 asks for (the hub carries it out), or 0. */
static uint8_t communication_error(const odg_node_t *n)
{
    uint32_t behaviour = odg_io_num_(n, 0x1029, 1);
    if (behaviour == 1u || (behaviour != 2u && n->state != ODG_NMT_OPERATIONAL)) {
        return 0; /* 0 and the values CiA 301 leaves to manufacturers: as 0 */
    }
    return (uint8_t)(behaviour == 2u ? ODG_NMT_STOP : ODG_NMT_ENTER_PREOP);
}

void odg_hb_rtr_(odg_node_t *n, const odg_frame_t *f)
{
    uint8_t answer;
    if (f->id != 0x700u + n->cfg.node_id || odg_io_num_(n, 0x1017, 0) != 0u) {
        return;
    }
    answer = (uint8_t)(n->state | n->hb.guard_toggle);
    if (odg_io_send_(n, f->id, &answer, 1) == 0) {
        n->hb.guard_toggle ^= 0x80u;
    }
    heard(n, &n->hb.watch[GUARD]);
}

/* The watched heartbeats, then life guarding (its time the product of 0x100C and 0x100D, read at
 * each tick): one overdue is an error 0x8130 (EMCY byte 3: the node-id watched, for life
 * guarding the node's own) and a communication error; a heartbeat's is also reported. */
uint8_t odg_hb_tick_(odg_node_t *n, uint32_t ms)
{
    uint32_t k;
    uint8_t cmd = 0;
    odg_hb_watch_t *w = n->hb.watch;
    w[GUARD].id = n->cfg.node_id;
    w[GUARD].time = odg_io_num_(n, 0x100C, 0) * odg_io_num_(n, 0x100D, 0);
    for (k = 0; k <= GUARD; k++, w++) {
        if (w->time == 0u || !w->started) {
            continue;
        }
        w->elapsed = w->elapsed + ms < w->elapsed ? 0xFFFFFFFFu : w->elapsed + ms;
        if (w->elapsed > w->time) {
            w->started = 0; /* watched again from its next heartbeat */
            w->lost = 1;
            (void)odg_node_error_set(n, EMCY_HEARTBEAT, 0, &w->id, 1);
            if (k < GUARD) {
                report(n, w->id, ODG_HB_TIMEOUT);
            }
            cmd = communication_error(n); /* the same for each: 0 or the one command 0x1029 asks for */
        }
    }
    return cmd;
}

void odg_node_on_heartbeat(odg_node_t *node, void (*fn)(void *ctx, uint8_t node_id, uint8_t event),
                           void *ctx)
{
    node->hb.on_heartbeat = fn;
    node->hb.on_heartbeat_ctx = ctx;
}

/* ---- the CAN controller's state ------------------------------------------------------------ */

uint8_t odg_hb_can_state_(odg_node_t *node, odg_can_state_t state)
{
    uint8_t was = node->hb.can_state;
    if (state == ODG_CAN_RX_OVERRUN) {
        (void)odg_node_emcy(node, ODG_EMCY_CAN_OVERRUN, node->error_register, NULL, 0);
        return 0;
    }
    if ((uint8_t)state == was || state > ODG_CAN_RX_OVERRUN) {
        return 0;
    }
    node->hb.can_state = (uint8_t)state;
    if (state == ODG_CAN_BUS_OFF) {
        return communication_error(node);
    }
    if (was == ODG_CAN_BUS_OFF) {
        (void)odg_node_emcy(node, ODG_EMCY_BUS_OFF_RECOVERED, node->error_register, NULL, 0);
    }
    if (state == ODG_CAN_ERROR_PASSIVE) {
        (void)odg_node_error_set(node, ODG_EMCY_CAN_PASSIVE, 0, NULL, 0);
    } else {
        (void)odg_node_error_clear(node, ODG_EMCY_CAN_PASSIVE);
    }
    return 0;
}

uint8_t odg_node_comm_errors(const odg_node_t *node)
{
    uint8_t bits = 0;
    uint32_t k;
    for (k = 0; k < GUARD; k++) {
        if (node->hb.watch[k].lost) {
            bits = ODG_COMM_HEARTBEAT;
        }
    }
    if (node->hb.watch[GUARD].lost) {
        bits |= ODG_COMM_GUARDING;
    }
    if (node->hb.can_state == ODG_CAN_BUS_OFF) {
        bits |= ODG_COMM_BUS_OFF;
    }
    return bits;
}

void odg_hb_boot_(odg_node_t *n)
{
    n->hb.timer = 0;
    n->hb.guard_toggle = 0;
    n->hb.watch[GUARD].started = 0; /* life guarding from the first remote frame */
    n->hb.watch[GUARD].lost = 0;
    if (n->hb.can_state == ODG_CAN_ERROR_PASSIVE || n->hb.can_state == ODG_CAN_BUS_OFF) {
        (void)odg_node_error_set(n, ODG_EMCY_CAN_PASSIVE, 0, NULL, 0);
    }
}
