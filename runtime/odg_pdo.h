/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_pdo.h - the node's PDOs: TPDOs and RPDOs configured by the dictionary's 0x1400-0x1BFF
 * entries, and what they do at a SYNC (the SYNC window 0x1007 included). Part of odg_node.h
 * (which declares the API: odg_node_tpdo_request, odg_node_unserved); below it odg_err.h and
 * odg_node_io.h. Its state is the node's rpdo[], tpdo[], sync_us and sync_dropped.
 */
#ifndef ODG_PDO_H
#define ODG_PDO_H

#include "odg_node_io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* How many PDOs per direction the node serves (0x1400 + n for n below the limit, 0x1800 + n),
 * and mapped objects per PDO (CiA 301: up to 64). NAME_config.h sets them to what the dictionary
 * has; these defaults serve builds without ODG_CONFIG. */
#ifndef ODG_NODE_MAX_RPDO
#define ODG_NODE_MAX_RPDO 4u
#endif
#ifndef ODG_NODE_MAX_TPDO
#define ODG_NODE_MAX_TPDO 4u
#endif
#ifndef ODG_NODE_MAX_MAP
#define ODG_NODE_MAX_MAP 8u
#endif

/* One PDO as read from its communication and mapping entries (internal). The members used
 * most come first, at offsets that Thumb's short load and store instructions reach. */
typedef struct odg_pdo {
    uint32_t cob;                   /* sub1; bit 31 set: PDO not valid */
    uint8_t type;                   /* transmission type, sub2 */
    uint8_t sync_start;             /* TPDO sub6 */
    uint8_t n_map;                  /* mapped objects; 0: PDO absent, not valid or not mapped */
    uint8_t len;                    /* bytes: mapped length (RPDO), last sent (TPDO) */
    uint8_t count;                  /* TPDO: SYNCs since the last synchronous send */
    uint8_t flags;                  /* ODG_PDO_F_* */
    uint16_t inhibit;               /* TPDO sub3, 100 us units */
    uint16_t event;                 /* TPDO sub5, ms (0: no event timer) */
    uint16_t event_left;            /* ms until the event timer expires */
    uint32_t inhibit_left;          /* TPDO: 100 us units until the next send is allowed */
    uint8_t data[8];                /* TPDO: last sent; RPDO: received, waiting for SYNC */
    uint32_t map[ODG_NODE_MAX_MAP]; /* mapping entries 1..n_map */
} odg_pdo_t;

/* odg_pdo_t.flags */
#define ODG_PDO_F_REQUEST  0x01u /* TPDO: an event asks for a transmission */
#define ODG_PDO_F_SENT     0x02u /* TPDO: data/len hold the last frame sent */
#define ODG_PDO_F_STARTED  0x04u /* TPDO: the SYNC start value was seen (or none is used) */
#define ODG_PDO_F_RECEIVED 0x08u /* RPDO: data waits for the next SYNC */
#define ODG_PDO_F_LEN_ERR  0x10u /* RPDO: the last frame was too short (EMCY 0x8210 sent) */
#define ODG_PDO_F_DUE      0x20u /* TPDO: synchronous, not sent yet at the last SYNC (window) */
#define ODG_PDO_F_SAMPLED  0x40u /* TPDO type 252: data/len hold what the last SYNC sampled */

/* Internal, called by odg_sync.c (odg_pdo_sync_), odg_sdo.c (the check) and odg_node.c. */
void odg_pdo_load_(struct odg_node *n, int tx, uint16_t k); /* 0x1400 + k or 0x1800 + k read again */
void odg_pdo_start_(struct odg_node *n); /* entering operational */
odg_abort_t odg_pdo_check_(const struct odg_node *n, uint16_t index, uint8_t sub, uint32_t value);
void odg_pdo_sync_(struct odg_node *n, const odg_frame_t *f); /* a SYNC, received or produced */
void odg_pdo_receive_(struct odg_node *n, const odg_frame_t *f);
void odg_pdo_tick_(struct odg_node *n, uint32_t ms);
void odg_pdo_request_(struct odg_node *n, uint16_t k);
void odg_pdo_rtr_(struct odg_node *n, const odg_frame_t *f); /* a remote request: TPDOs 252/253 */

#ifdef __cplusplus
}
#endif

#endif /* ODG_PDO_H */
