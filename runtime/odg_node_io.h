/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_node_io.h - the bottom of the node layer: CAN frames, the NMT states, and the helpers
 * every service shares (send a frame, read a number from the dictionary). Part of odg_node.h.
 *
 * The node layer's files, lowest first (docs/design.md, "The node runtime"): odg_node_io.c;
 * odg_time.c, odg_lss.c, odg_comm.c, odg_err.c; odg_hb.c, odg_pdo.c; odg_sync.c; odg_sdo.c;
 * odg_node.c (the hub). A file calls only files below it; tests/test_layers.py checks it.
 */
#ifndef ODG_NODE_IO_H
#define ODG_NODE_IO_H

#include <stdint.h>

#include "odg.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- frames ------------------------------------------------------------------------ */

#define ODG_FRAME_RTR 0x01u /* remote request */
#define ODG_FRAME_EFF 0x02u /* 29-bit identifier */

typedef struct odg_frame {
    uint32_t id;     /* 11-bit CAN identifier (COB-ID) */
    uint8_t len;     /* DLC, 0..8 */
    uint8_t flags;   /* ODG_FRAME_* */
    uint8_t data[8];
} odg_frame_t;

/* Queue one frame for transmission: 0 when queued, non-zero when it could not be (a block
 * upload then resumes from the next tick; other frames are dropped). */
typedef int (*odg_send_fn)(void *ctx, const odg_frame_t *frame);

/* ---- NMT ----------------------------------------------------------------------------- */

/* The values are the heartbeat state bytes of CiA 301 (bit 0 set: the two in which the node
 * talks, see ODG_IO_TALKING). */
typedef enum odg_nmt_state {
    ODG_NMT_INITIALISING = 0x00,
    ODG_NMT_STOPPED = 0x04,
    ODG_NMT_OPERATIONAL = 0x05,
    ODG_NMT_PRE_OPERATIONAL = 0x7F
} odg_nmt_state_t;

/* NMT command specifiers (byte 0 of a frame to COB-ID 0). */
#define ODG_NMT_START 0x01u
#define ODG_NMT_STOP 0x02u
#define ODG_NMT_ENTER_PREOP 0x80u
#define ODG_NMT_RESET_NODE 0x81u
#define ODG_NMT_RESET_COMM 0x82u

/* ---- internal: COB-ID bits and the shared helpers ---------------------------------------- */

#define ODG_COB_INVALID 0x80000000u  /* bit 31 of a COB-ID entry: not valid / not used */
#define ODG_COB_EXTENDED 0x20000000u /* bit 29: a 29-bit CAN-ID */
#define ODG_COB_ID(c) ((c) & 0x7FFu)

struct odg_node;

/* Send `len` bytes on the CAN-ID of `cob` through cfg.send: its result (0: queued). */
int odg_io_send_(const struct odg_node *n, uint32_t cob, const uint8_t *data, uint8_t len);
/* A number of up to 4 bytes from the dictionary (little-endian wire bytes), via odg_read. */
odg_abort_t odg_io_get_(const struct odg_node *n, uint16_t index, uint8_t sub, uint32_t *value);
uint32_t odg_io_get_or_(const struct odg_node *n, uint16_t index, uint8_t sub, uint32_t dflt);
/* The same with the default 0 (one argument less at each of the many calls). */
uint32_t odg_io_num_(const struct odg_node *n, uint16_t index, uint8_t sub);
/* Pre-operational (0x7F) or operational (0x05): the states in which EMCY, TIME and SYNC go
 * out, and the only ones with bit 0 set. A macro on the node's state: a call costs more. */
#define ODG_IO_TALKING(n) (((n)->state & 1u) != 0u)

#ifdef __cplusplus
}
#endif

#endif /* ODG_NODE_IO_H */
