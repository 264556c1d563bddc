/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_sync.h - the node's SYNC service: consumer and producer (CiA 301: 0x1005, 0x1006, 0x1019).
 * A SYNC, received or produced, goes to the PDOs (odg_pdo_sync_), which apply and sample what
 * is synchronous. Part of odg_node.h; below it odg_pdo.h and odg_node_io.h.
 */
#ifndef ODG_SYNC_H
#define ODG_SYNC_H

#include "odg_node_io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The SYNC service's state (odg_node_t.sync, internal). */
typedef struct odg_sync {
    uint32_t cob;     /* 0x1005 */
    uint32_t prod_us; /* producer: µs since the last SYNC sent */
    uint8_t counter;  /* producer: the last counter sent (0: none yet) */
} odg_sync_t;

/* Internal, called by odg_sdo.c (the check) and odg_node.c. */
void odg_sync_receive_(struct odg_node *n, const odg_frame_t *f); /* a SYNC frame, in operational */
void odg_sync_tick_(struct odg_node *n, uint32_t ms);            /* the producer */
odg_abort_t odg_sync_check_(const struct odg_node *n, const uint8_t *data, uint32_t len); /* before a write to 0x1019 */

#ifdef __cplusplus
}
#endif

#endif /* ODG_SYNC_H */
