/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_node_impl.h - internals shared by odg_node.c, odg_sdo.c and odg_pdo.c. Not API.
 */
#ifndef ODG_NODE_IMPL_H
#define ODG_NODE_IMPL_H

#include "odg_node.h"

#define ODG_COB_INVALID 0x80000000u /* bit 31 of a COB-ID entry: not valid / not used */
#define ODG_COB_EXTENDED 0x20000000u /* bit 29: a 29-bit CAN-ID */
#define ODG_COB_ID(c) ((c) & 0x7FFu)
#define ODG_TIME_CONSUME 0x80000000u /* 0x1012 bit 31 */
#define ODG_TIME_PRODUCE 0x40000000u /* 0x1012 bit 30 */
#define ODG_TIME_MS_MASK 0x0FFFFFFFu /* TIME_OF_DAY: 28 bits of ms */

/* odg_sdo_t.state */
enum {
    ODG_SDO_IDLE,
    ODG_SDO_DN_SEG,       /* segmented download: waiting for a segment */
    ODG_SDO_UP_SEG,       /* segmented upload: waiting for a segment request */
    ODG_SDO_BLK_DN,       /* block download: receiving a sub-block */
    ODG_SDO_BLK_DN_END,   /* block download: waiting for the end frame */
    ODG_SDO_BLK_UP_START, /* block upload: waiting for the start command */
    ODG_SDO_BLK_UP,       /* block upload: sending a sub-block, then waiting for its ack */
    ODG_SDO_BLK_UP_END    /* block upload: waiting for the client's end response */
};

/* odg_sdo_t.flags */
#define ODG_SDO_F_SIZED  0x01u /* download: the client indicated the size */
#define ODG_SDO_F_STREAM 0x02u /* download of more than 8 bytes: odg_write_part as it arrives */
#define ODG_SDO_F_CRC    0x04u /* block transfer: both sides use the CRC */
#define ODG_SDO_F_LAST   0x08u /* block: the last segment was received (down) or sent (up) */
#define ODG_SDO_F_HELD   0x10u /* block download: seg[] holds the newest segment */

/* odg_pdo_t.flags */
#define ODG_PDO_F_REQUEST  0x01u /* TPDO: an event asks for a transmission */
#define ODG_PDO_F_SENT     0x02u /* TPDO: data/len hold the last frame sent */
#define ODG_PDO_F_STARTED  0x04u /* TPDO: the SYNC start value was seen (or none is used) */
#define ODG_PDO_F_RECEIVED 0x08u /* RPDO: data waits for the next SYNC */
#define ODG_PDO_F_LEN_ERR  0x10u /* RPDO: the last frame was too short (EMCY 0x8210 sent) */
#define ODG_PDO_F_DUE      0x20u /* TPDO: synchronous, not sent yet at the last SYNC (window) */
#define ODG_PDO_F_SAMPLED  0x40u /* TPDO type 252: data/len hold what the last SYNC sampled */

/* odg_node.c */
/* After the SDO server wrote "save" (restore 0) or "load" (1) to 0x1010/0x1011 sub `sub`:
 * reset communication brings back what the next boot would load. */
void odg_node_stored_(odg_node_t *n, uint8_t sub, int restore);
int odg_node_send_(odg_node_t *n, uint32_t cob, const uint8_t *data, uint8_t len);
/* A number of up to 4 bytes from the dictionary (little-endian wire bytes), via odg_read. */
odg_abort_t odg_node_get_(const odg_node_t *n, uint16_t index, uint8_t sub, uint32_t *value);
uint32_t odg_node_get_or_(const odg_node_t *n, uint16_t index, uint8_t sub, uint32_t dflt);
/* Before the SDO server stores a whole value: the CiA 301 rules for PDO parameters. */
odg_abort_t odg_node_check_(odg_node_t *n, uint16_t index, uint8_t sub, const uint8_t *data,
                            uint32_t len);

/* odg_time.c */
void odg_time_receive_(odg_node_t *n, const odg_frame_t *f);

/* odg_err.c: the pre-defined error field 0x1003 */
void odg_err_record_(odg_node_t *n, uint16_t code, const uint8_t *vendor, uint8_t n_vendor);
odg_abort_t odg_err_check_(const odg_node_t *n, uint8_t sub, uint32_t value);
void odg_err_written_(odg_node_t *n); /* after an SDO write to 0x1003: sub 0 = 0 clears */
/* At a reset: forget every active error (`all`) or those of communication; 0x1001 follows. */
void odg_err_reset_(odg_node_t *n, int all);
/* Send an EMCY frame now, or when the inhibit time (0x1015) since the last one has passed. */
odg_abort_t odg_emcy_send_(odg_node_t *n, const uint8_t *data);
void odg_emcy_tick_(odg_node_t *n, uint32_t ms);

/* odg_sync.c: the SYNC producer */
void odg_sync_tick_(odg_node_t *n, uint32_t ms);
odg_abort_t odg_sync_check_(const odg_node_t *n, uint16_t index); /* before a write to 0x1019 */

/* odg_hb.c: the heartbeat consumer, node and life guarding, 0x1029 */
void odg_hb_load_(odg_node_t *n);
odg_abort_t odg_hb_check_(const odg_node_t *n, uint8_t sub, uint32_t value); /* before a 0x1016 write */
void odg_hb_receive_(odg_node_t *n, const odg_frame_t *f);
void odg_hb_tick_(odg_node_t *n, uint32_t ms); /* also life guarding */
void odg_guard_rtr_(odg_node_t *n, const odg_frame_t *f); /* a remote frame: node guarding */

/* odg_sdo.c */
void odg_sdo_receive_(odg_node_t *n, const odg_frame_t *f);
void odg_sdo_tick_(odg_node_t *n, uint32_t ms);
void odg_sdo_drop_(odg_node_t *n);

/* odg_pdo.c */
void odg_pdo_load_(odg_node_t *n, int tx, uint16_t k);
void odg_pdo_start_(odg_node_t *n);
odg_abort_t odg_pdo_check_(odg_node_t *n, uint16_t index, uint8_t sub, uint32_t value);
void odg_pdo_sync_(odg_node_t *n, const odg_frame_t *f);
void odg_pdo_receive_(odg_node_t *n, const odg_frame_t *f);
void odg_pdo_tick_(odg_node_t *n, uint32_t ms);
void odg_pdo_request_(odg_node_t *n, uint16_t k);
void odg_pdo_rtr_(odg_node_t *n, const odg_frame_t *f); /* a remote request: TPDOs 252/253 */

#endif /* ODG_NODE_IMPL_H */
