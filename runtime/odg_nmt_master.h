/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_nmt_master.h - NMT master (CiA 301): NMT commands, and the slaves' error control as a
 * master sees it: boot-up messages, heartbeat states and timeouts, node guarding.
 *
 *     odg_nmtm_t nmt;
 *     odg_nmtm_init(&nmt, can_send, &can, on_event, app);
 *     odg_nmtm_watch(&nmt, 5, 300, 0, 0);          node 5: heartbeat expected every 300 ms
 *     odg_nmtm_command(&nmt, ODG_NMT_START, 0);    start all nodes
 *     ... odg_nmtm_receive(&nmt, &frame) for every received frame, odg_nmtm_tick(&nmt, ms) ...
 *
 * on_event(ctx, node_id, event) hears ODG_NMTM_BOOTUP, each new NMT state a heartbeat (or a
 * guarding answer) says (odg_nmt_state_t), and ODG_HB_TIMEOUT when one is overdue.
 */
#ifndef ODG_NMT_MASTER_H
#define ODG_NMT_MASTER_H

#include <stdint.h>

#include "odg_node.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Slaves a master watches at most (the configuration manager's slaves too). NAME_config.h may
 * set it; this default serves builds without ODG_CONFIG. */
#ifndef ODG_MASTER_MAX_SLAVES
#define ODG_MASTER_MAX_SLAVES 8u
#endif

#define ODG_NMTM_BOOTUP 0x00u    /* event: a boot-up message */
#define ODG_NMTM_UNKNOWN 0xFFu   /* odg_nmtm_state: nothing heard yet */

typedef struct odg_nmtm_slave {
    uint32_t elapsed;   /* ms since its last heartbeat, guarding answer or the watch began */
    uint32_t guard_left; /* guarding: ms until the next remote request */
    uint16_t hb_ms;     /* heartbeat expected within (0: none) */
    uint16_t guard_ms;  /* node guarding period (0: none; used when hb_ms is 0) */
    uint8_t retry;      /* guarding: life time factor (periods without answer before the event) */
    uint8_t id;         /* node-id; 0: slot free */
    uint8_t state;      /* its last NMT state, ODG_NMTM_UNKNOWN before any */
    uint8_t lost;       /* timed out, and nothing heard since */
} odg_nmtm_slave_t;

typedef struct odg_nmtm {
    odg_send_fn send;
    void *send_ctx;
    void (*on_event)(void *ctx, uint8_t node_id, uint8_t event);
    void *ctx;
    odg_nmtm_slave_t slave[ODG_MASTER_MAX_SLAVES];
} odg_nmtm_t;

void odg_nmtm_init(odg_nmtm_t *m, odg_send_fn send, void *send_ctx,
                   void (*on_event)(void *ctx, uint8_t node_id, uint8_t event), void *ctx);

/* Send NMT command `cs` (ODG_NMT_START, _STOP, _ENTER_PREOP, _RESET_NODE, _RESET_COMM) to
 * `node_id`, 0 for all nodes: the send function's result. */
int odg_nmtm_command(odg_nmtm_t *m, uint8_t cs, uint8_t node_id);

/* Track `node_id` (1..127): its boot-ups and states, and from now on its heartbeat within hb_ms,
 * or (hb_ms 0) node guarding every guard_ms with life time factor `retry` (0 counts as 1);
 * both 0: no timeout. Calling it again re-arms the timer. -1 when every slot is taken. */
int odg_nmtm_watch(odg_nmtm_t *m, uint8_t node_id, uint16_t hb_ms, uint16_t guard_ms, uint8_t retry);

/* Stop the timeouts of `node_id` (boot-ups and states are still tracked). */
void odg_nmtm_unwatch(odg_nmtm_t *m, uint8_t node_id);

/* The NMT state `node_id` said last (ODG_NMTM_UNKNOWN: nothing heard, or not tracked). */
uint8_t odg_nmtm_state(const odg_nmtm_t *m, uint8_t node_id);

/* Every received frame: 1 when it was an error control message of a tracked node. */
int odg_nmtm_receive(odg_nmtm_t *m, const odg_frame_t *frame);

/* Advance time: heartbeat timeouts, guarding requests and their timeouts. */
void odg_nmtm_tick(odg_nmtm_t *m, uint32_t elapsed_ms);

#ifdef __cplusplus
}
#endif

#endif /* ODG_NMT_MASTER_H */
