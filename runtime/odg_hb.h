/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_hb.h - NMT error control of the node: heartbeat producer (0x1017) and consumer (0x1016),
 * node and life guarding (0x100C, 0x100D), the CAN controller's state and what a communication
 * error does (0x1029). Part of odg_node.h (which declares the API: odg_node_on_heartbeat,
 * odg_node_can_state, odg_node_comm_errors); below it odg_err.h and odg_node_io.h.
 *
 * The NMT state itself is the hub's (odg_node.c): a communication error here does not change
 * it but returns the NMT command 0x1029 asks for, which the hub carries out.
 */
#ifndef ODG_HB_H
#define ODG_HB_H

#include "odg_node_io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Heartbeat consumer: how many 0x1016 entries (sub 1..) the node watches. */
#ifndef ODG_NODE_MAX_HB
#define ODG_NODE_MAX_HB 8u
#endif

/* The event odg_node_on_heartbeat reports when a watched node's heartbeat is overdue; other
 * events are the NMT state a heartbeat newly says (odg_nmt_state_t values). */
#define ODG_HB_TIMEOUT 0xFFu

/* The CAN controller's state, as the CAN driver reports it (odg_node_can_state). */
typedef enum odg_can_state {
    ODG_CAN_ERROR_ACTIVE = 0,  /* both error counters below 128: normal */
    ODG_CAN_ERROR_PASSIVE = 1, /* an error counter above 127 */
    ODG_CAN_BUS_OFF = 2,       /* the transmit error counter passed 255: off the bus */
    ODG_CAN_RX_OVERRUN = 3     /* not a state, an event: received frames were lost */
} odg_can_state_t;

/* EMCY error codes of the CAN controller's states (CiA 301). */
#define ODG_EMCY_CAN_OVERRUN 0x8110u
#define ODG_EMCY_CAN_PASSIVE 0x8120u
#define ODG_EMCY_BUS_OFF_RECOVERED 0x8140u

/* One watched heartbeat (0x1016 entry), or life guarding (internal). */
typedef struct odg_hb_watch {
    uint32_t elapsed; /* ms since its last heartbeat (remote frame) */
    uint32_t time;    /* ms allowed between them; 0: not watched */
    uint8_t id;       /* node-id watched (life guarding: the node's own) */
    uint8_t state;    /* the state its last heartbeat said */
    uint8_t started;  /* a heartbeat came since the entry was set or timed out */
    uint8_t lost;     /* timed out, and none since (EMCY 0x8130 active) */
} odg_hb_watch_t;

/* The NMT error control service's state (odg_node_t.hb, internal). */
typedef struct odg_hb {
    uint32_t timer;          /* producer: ms since the last heartbeat */
    void (*on_heartbeat)(void *ctx, uint8_t node_id, uint8_t event);
    void *on_heartbeat_ctx;
    /* the consumer's entries, then life guarding, which times out as they do */
    odg_hb_watch_t watch[ODG_NODE_MAX_HB + 1u];
    uint8_t guard_toggle;    /* node guarding: the toggle bit of the next answer, as its bit 7 */
    uint8_t can_state;       /* odg_can_state_t the CAN driver reported last */
} odg_hb_t;

/* Internal, called by odg_sdo.c (the check) and odg_node.c. The functions returning uint8_t
 * return the NMT command a communication error asks for (0x1029 sub 1), or 0. */
void odg_hb_load_(struct odg_node *n); /* 0x1016 read again */
odg_abort_t odg_hb_check_(const struct odg_node *n, uint8_t sub, uint32_t value); /* before a 0x1016 write */
void odg_hb_receive_(struct odg_node *n, const odg_frame_t *f);
void odg_hb_produce_(struct odg_node *n, uint32_t ms); /* the heartbeat producer */
uint8_t odg_hb_tick_(struct odg_node *n, uint32_t ms);  /* the consumer, life guarding */
void odg_hb_rtr_(struct odg_node *n, const odg_frame_t *f); /* a remote frame: node guarding */
uint8_t odg_hb_can_state_(struct odg_node *n, odg_can_state_t state);
void odg_hb_boot_(struct odg_node *n); /* after the boot-up: timers start afresh */

#ifdef __cplusplus
}
#endif

#endif /* ODG_HB_H */
