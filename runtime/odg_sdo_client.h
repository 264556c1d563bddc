/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_sdo_client.h - an SDO client channel (CiA 301): expedited and segmented download and
 * upload to one server, with its own state and timeout, so that a master keeps one channel per
 * slave and has as many transfers in flight as it has channels.
 *
 *     odg_sdoc_t ch;
 *     odg_sdoc_init(&ch, 5, 0, 0, can_send, &can);   node 5: 0x605 / 0x585
 *     odg_sdoc_download(&ch, 0x1017, 0, bytes, 2);
 *     ... odg_sdoc_receive(&ch, &frame) for every received frame, odg_sdoc_tick(&ch, ms) ...
 *     if (ch.state == ODG_SDOC_DONE) ...            ODG_SDOC_ABORTED: ch.abort says why
 *
 * A download reads its bytes from a buffer or, with odg_sdoc_download_ref, from a value of a
 * local dictionary (a concise DCF in a DOMAIN, say) through odg_read, a segment at a time.
 * Numbers travel little endian on the wire; the caller's buffers hold wire bytes.
 */
#ifndef ODG_SDO_CLIENT_H
#define ODG_SDO_CLIENT_H

#include <stdint.h>

#include "odg.h"
#include "odg_node.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ms without an answer from the server before the client aborts with ODG_ABORT_TIMEOUT. */
#ifndef ODG_SDOC_TIMEOUT_MS
#define ODG_SDOC_TIMEOUT_MS 500u
#endif

/* odg_sdoc_t.state */
#define ODG_SDOC_IDLE 0u    /* no transfer yet */
#define ODG_SDOC_BUSY 1u    /* a transfer is in flight */
#define ODG_SDOC_DONE 2u    /* the last transfer succeeded (upload: ch.n bytes in the buffer) */
#define ODG_SDOC_ABORTED 3u /* the last transfer failed: ch.abort (sent or received) */

typedef struct odg_sdoc {
    odg_send_fn send;
    void *send_ctx;
    odg_ref_t src;          /* download from the dictionary: the value read (src.dict != NULL) */
    const uint8_t *data;    /* download from a buffer */
    uint8_t *buf;           /* upload: where the bytes go */
    uint32_t src_offset;    /* download from the dictionary: the first byte's offset in src */
    uint32_t total;         /* download: bytes to send; upload: size the server indicated */
    uint32_t n;             /* bytes done: sent (download) or received (upload) */
    uint32_t cap;           /* upload: room in buf */
    uint32_t timer;         /* ms since the request went out */
    uint32_t abort;         /* the abort code of an ODG_SDOC_ABORTED transfer */
    uint32_t cob_tx, cob_rx; /* client -> server (0x600 + id), server -> client (0x580 + id) */
    uint16_t index;
    uint8_t sub;
    uint8_t state;          /* ODG_SDOC_* */
    uint8_t phase;          /* the answer awaited (odg_sdo_client.c) */
    uint8_t toggle;
} odg_sdoc_t;

/* A channel to server `node_id` (1..127): COB-IDs 0x600 + id and 0x580 + id, unless cob_tx /
 * cob_rx are non-zero (from the client parameter 0x1280 + n, say). */
void odg_sdoc_init(odg_sdoc_t *ch, uint8_t node_id, uint32_t cob_tx, uint32_t cob_rx, odg_send_fn send,
                   void *send_ctx);

/* The COB-IDs for server `node_id`: those of the first SDO client parameter of `dict`
 * (0x1280..0x12FF) whose sub 3 names that server and whose COB-IDs are valid (bit 31 clear),
 * else 0x600 + id / 0x580 + id. */
void odg_sdoc_cobs(const odg_dict_t *dict, uint8_t node_id, uint32_t *cob_tx, uint32_t *cob_rx);

/* Start a download of `len` bytes (expedited up to 4, else segmented). `data` must stay valid
 * until the transfer ends. ODG_ABORT_DATA_STATE while a transfer is in flight (nothing sent),
 * ODG_ABORT_HARDWARE when the request could not be sent (state ABORTED). */
odg_abort_t odg_sdoc_download(odg_sdoc_t *ch, uint16_t index, uint8_t sub, const void *data, uint32_t len);

/* The same, the bytes read from `src` at `offset` (odg_read) as the transfer needs them. */
odg_abort_t odg_sdoc_download_ref(odg_sdoc_t *ch, uint16_t index, uint8_t sub, const odg_ref_t *src,
                                  uint32_t offset, uint32_t len);

/* Start an upload into `buf` (`cap` bytes): a value longer than cap aborts OUT_OF_MEMORY. */
odg_abort_t odg_sdoc_upload(odg_sdoc_t *ch, uint16_t index, uint8_t sub, void *buf, uint32_t cap);

/* Abort the transfer in flight with `code` (an abort frame to the server); nothing when idle. */
void odg_sdoc_abort(odg_sdoc_t *ch, uint32_t code);

/* Every received frame: 1 when it was this channel's answer, else 0. */
int odg_sdoc_receive(odg_sdoc_t *ch, const odg_frame_t *frame);

/* Advance time: a transfer without an answer for ODG_SDOC_TIMEOUT_MS aborts TIMEOUT. */
void odg_sdoc_tick(odg_sdoc_t *ch, uint32_t elapsed_ms);

/* A received upload's bytes as a number (little endian, up to 4 bytes). */
uint32_t odg_sdoc_u32(const uint8_t *wire, uint32_t n);

#ifdef __cplusplus
}
#endif

#endif /* ODG_SDO_CLIENT_H */
