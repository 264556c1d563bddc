/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_sdo.h - the node's SDO server: expedited, segmented and (ODG_NODE_SDO_BLOCK) block
 * transfers (CRC-16) over odg_read / odg_write / odg_write_part. Part of odg_node.h; the topmost service: before it
 * stores a value it asks the rules of the services below (odg_err.h, odg_hb.h, odg_pdo.h,
 * odg_sync.h), and after a "save" or "load" tells odg_comm.h.
 */
#ifndef ODG_SDO_H
#define ODG_SDO_H

#include "odg_node_io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* SDO block transfer (CiA 301): 1 serves block upload and download; 0 answers a block initiate
 * with abort 0x05040001 (command specifier not valid), which CiA 301 allows a server without
 * block transfer, and builds none of its code or state. NAME_config.h sets it ([node] sdo_block). */
#ifndef ODG_NODE_SDO_BLOCK
#define ODG_NODE_SDO_BLOCK 1
#endif
/* SDO: ms of silence within a transfer before it is aborted (0x05040000). */
#ifndef ODG_NODE_SDO_TIMEOUT_MS
#define ODG_NODE_SDO_TIMEOUT_MS 1000u
#endif
/* SDO block download: segments per sub-block the server asks for (1..127). */
#ifndef ODG_NODE_SDO_BLKSIZE
#define ODG_NODE_SDO_BLKSIZE 127u
#endif

/* The SDO server's transfer in progress (odg_node_t.sdo, internal). */
typedef struct odg_sdo {
    odg_ref_t ref;        /* the object being transferred */
    uint32_t total;       /* size indicated (download) or taken (upload) */
    uint32_t offset;      /* bytes done: written or collected (down), sent (up) */
    uint32_t timer;       /* ms since the last frame of this transfer */
#if ODG_NODE_SDO_BLOCK
    uint32_t blk_offset;  /* block upload: offset at the start of the sub-block */
    uint16_t crc;         /* CRC-16 of the bytes so far */
    uint16_t blk_crc;     /* block upload: CRC at the start of the sub-block */
#endif
    uint16_t index;
    uint8_t sub;
    uint8_t state;        /* ODG_SDO_* */
    uint8_t flags;        /* ODG_SDO_F_* */
    uint8_t toggle;       /* segmented: the toggle bit expected next, as bit 4 of byte 0 */
    uint8_t n_buf;
    uint8_t buf[8];       /* a number collected whole (down); the first 8 bytes (up) */
#if ODG_NODE_SDO_BLOCK
    uint8_t blksize;      /* segments per sub-block */
    uint8_t seq;          /* last good (download) or last sent (upload) segment number */
    uint8_t seg[7];       /* block download: the newest segment, held until the end frame */
#endif
} odg_sdo_t;

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

/* Internal, called by odg_node.c. A transfer is dropped silently by setting sdo.state to
 * ODG_SDO_IDLE (the NMT state stopped, a reset). */
void odg_sdo_receive_(struct odg_node *n, const odg_frame_t *f);
void odg_sdo_tick_(struct odg_node *n, uint32_t ms);

#ifdef __cplusplus
}
#endif

#endif /* ODG_SDO_H */
