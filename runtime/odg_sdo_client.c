/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_sdo_client.c - SDO client channel: expedited and segmented transfers. See odg_sdo_client.h.
 */
#include "odg_impl.h"
#include "odg_sdo_client.h"

/* odg_sdoc_t.phase: the answer the channel waits for */
#define WAIT_DL_INIT 1u /* 0x60: download initiated */
#define WAIT_DL_SEG 2u  /* 0x20 | toggle: segment taken */
#define WAIT_UL_INIT 3u /* 0x4x: upload initiated (expedited: done) */
#define WAIT_UL_SEG 4u  /* a segment */

uint32_t odg_sdoc_u32(const uint8_t *wire, uint32_t n)
{
    uint32_t v = 0, i;
    for (i = n < 4u ? n : 4u; i > 0u; i--) {
        v = v << 8 | wire[i - 1u];
    }
    return v;
}

/* Send command byte `cs` with the multiplexer (index, sub) and 4 more bytes. */
static int send_frame(odg_sdoc_t *ch, uint8_t cs, const uint8_t *rest, int mux)
{
    odg_frame_t f;
    unsigned i;
    f.id = ch->cob_tx;
    f.len = 8;
    f.flags = 0;
    f.data[0] = cs;
    for (i = 1; i < 8u; i++) {
        f.data[i] = 0;
    }
    if (mux) {
        f.data[1] = (uint8_t)ch->index;
        f.data[2] = (uint8_t)(ch->index >> 8);
        f.data[3] = ch->sub;
    }
    for (i = 0; rest != NULL && i < (mux ? 4u : 7u); i++) {
        f.data[(mux ? 4u : 1u) + i] = rest[i];
    }
    ch->timer = 0;
    return ch->send(ch->send_ctx, &f);
}

static void finish(odg_sdoc_t *ch, uint32_t abort)
{
    ch->abort = abort;
    ch->state = abort == ODG_OK ? ODG_SDOC_DONE : ODG_SDOC_ABORTED;
    ch->phase = 0;
}

void odg_sdoc_abort(odg_sdoc_t *ch, uint32_t code)
{
    uint8_t b[4];
    if (ch->state != ODG_SDOC_BUSY) {
        return;
    }
    odg_put_le32_(b, code);
    (void)send_frame(ch, 0x80u, b, 1);
    finish(ch, code);
}

void odg_sdoc_init(odg_sdoc_t *ch, uint8_t node_id, uint32_t cob_tx, uint32_t cob_rx, odg_send_fn send,
                   void *send_ctx)
{
    uint8_t *p = (uint8_t *)ch;
    uint32_t i;
    for (i = 0; i < (uint32_t)sizeof *ch; i++) {
        p[i] = 0;
    }
    ch->send = send;
    ch->send_ctx = send_ctx;
    ch->cob_tx = cob_tx != 0u ? cob_tx : 0x600u + node_id;
    ch->cob_rx = cob_rx != 0u ? cob_rx : 0x580u + node_id;
}

void odg_sdoc_cobs(const odg_dict_t *dict, uint8_t node_id, uint32_t *cob_tx, uint32_t *cob_rx)
{
    uint32_t tx, rx, index;
    uint8_t server;
    *cob_tx = 0x600u + node_id;
    *cob_rx = 0x580u + node_id;
    for (index = 0x1280u; index <= 0x12FFu; index++) {
        tx = rx = 0x80000000u;
        server = 0;
        if (odg_get_u8(dict, (uint16_t)index, 3, &server) == ODG_OK && server == node_id &&
            odg_get_u32(dict, (uint16_t)index, 1, &tx) == ODG_OK && odg_get_u32(dict, (uint16_t)index, 2, &rx) == ODG_OK &&
            (tx & 0x80000000u) == 0u && (rx & 0x80000000u) == 0u) {
            *cob_tx = tx & 0x7FFu;
            *cob_rx = rx & 0x7FFu;
            return;
        }
    }
}

/* Bytes [n, n + cap) of the download's source into seg; how many there were. */
static uint32_t source(odg_sdoc_t *ch, uint8_t *seg, uint32_t cap)
{
    uint32_t left = ch->total - ch->n, got = 0, i;
    if (cap > left) {
        cap = left;
    }
    if (ch->src.dict != NULL) {
        if (odg_read(&ch->src, ch->src_offset + ch->n, seg, cap, &got) != ODG_OK || got != cap) {
            return 0xFFFFFFFFu;
        }
    } else {
        for (i = 0; i < cap; i++) {
            seg[i] = ch->data[ch->n + i];
        }
    }
    return cap;
}

static odg_abort_t start(odg_sdoc_t *ch, uint16_t index, uint8_t sub, uint8_t phase)
{
    if (ch->state == ODG_SDOC_BUSY) {
        return ODG_ABORT_DATA_STATE;
    }
    ch->index = index;
    ch->sub = sub;
    ch->n = 0;
    ch->toggle = 0;
    ch->abort = 0;
    ch->state = ODG_SDOC_BUSY;
    ch->phase = phase;
    return ODG_OK;
}

static odg_abort_t begin_download(odg_sdoc_t *ch)
{
    uint8_t b[4] = {0, 0, 0, 0};
    int sent;
    if (ch->total <= 4u && ch->total > 0u) { /* expedited: e, s, n = 4 - len */
        if (source(ch, b, 4) != ch->total) {
            finish(ch, ODG_ABORT_DATA_LOCAL);
            return ODG_ABORT_DATA_LOCAL;
        }
        sent = send_frame(ch, (uint8_t)(0x23u | (4u - ch->total) << 2), b, 1);
    } else {
        odg_put_le32_(b, ch->total);
        sent = send_frame(ch, 0x21u, b, 1);
    }
    if (sent != 0) {
        finish(ch, ODG_ABORT_HARDWARE);
        return ODG_ABORT_HARDWARE;
    }
    return ODG_OK;
}

odg_abort_t odg_sdoc_download(odg_sdoc_t *ch, uint16_t index, uint8_t sub, const void *data, uint32_t len)
{
    odg_abort_t ac = start(ch, index, sub, WAIT_DL_INIT);
    if (ac != ODG_OK) {
        return ac;
    }
    ch->src.dict = NULL;
    ch->data = (const uint8_t *)data;
    ch->total = len;
    return begin_download(ch);
}

odg_abort_t odg_sdoc_download_ref(odg_sdoc_t *ch, uint16_t index, uint8_t sub, const odg_ref_t *src,
                                  uint32_t offset, uint32_t len)
{
    odg_abort_t ac = start(ch, index, sub, WAIT_DL_INIT);
    if (ac != ODG_OK) {
        return ac;
    }
    ch->src = *src;
    if (src->sub == &src->elem) { /* a packed element: the copy points to its own descriptor */
        ch->src.sub = &ch->src.elem;
    }
    ch->src_offset = offset;
    ch->total = len;
    return begin_download(ch);
}

odg_abort_t odg_sdoc_upload(odg_sdoc_t *ch, uint16_t index, uint8_t sub, void *buf, uint32_t cap)
{
    odg_abort_t ac = start(ch, index, sub, WAIT_UL_INIT);
    if (ac != ODG_OK) {
        return ac;
    }
    ch->buf = (uint8_t *)buf;
    ch->cap = cap;
    ch->total = 0;
    if (send_frame(ch, 0x40u, NULL, 1) != 0) {
        finish(ch, ODG_ABORT_HARDWARE);
        return ODG_ABORT_HARDWARE;
    }
    return ODG_OK;
}

/* The next download segment, or the end of the transfer when every byte went. */
static void next_segment(odg_sdoc_t *ch)
{
    uint8_t seg[7] = {0, 0, 0, 0, 0, 0, 0};
    uint32_t k;
    if (ch->n == ch->total && ch->phase == WAIT_DL_SEG) {
        finish(ch, ODG_OK);
        return;
    }
    k = source(ch, seg, 7);
    if (k > 7u) {
        odg_sdoc_abort(ch, ODG_ABORT_DATA_LOCAL);
        return;
    }
    ch->n += k;
    ch->phase = WAIT_DL_SEG;
    if (send_frame(ch, (uint8_t)((uint32_t)ch->toggle << 4 | (7u - k) << 1 | (ch->n == ch->total ? 1u : 0u)), seg, 0) != 0) {
        finish(ch, ODG_ABORT_HARDWARE);
    }
}

/* Keep `k` received bytes; 0 when they do not fit (the transfer is aborted). */
static int keep(odg_sdoc_t *ch, const uint8_t *d, uint32_t k)
{
    uint32_t i;
    if (ch->n + k > ch->cap) {
        odg_sdoc_abort(ch, ODG_ABORT_OUT_OF_MEMORY);
        return 0;
    }
    for (i = 0; i < k; i++) {
        ch->buf[ch->n + i] = d[i];
    }
    ch->n += k;
    return 1;
}

static void upload_initiated(odg_sdoc_t *ch, const uint8_t *d)
{
    if ((d[0] & 0x02u) != 0u) { /* expedited: 4 - n bytes when the size is indicated */
        if (keep(ch, d + 4, (d[0] & 0x01u) != 0u ? 4u - (d[0] >> 2 & 3u) : 4u)) {
            finish(ch, ODG_OK);
        }
        return;
    }
    ch->total = (d[0] & 0x01u) != 0u ? odg_sdoc_u32(d + 4, 4) : 0xFFFFFFFFu;
    if (ch->total != 0xFFFFFFFFu && ch->total > ch->cap) {
        odg_sdoc_abort(ch, ODG_ABORT_OUT_OF_MEMORY);
        return;
    }
    ch->phase = WAIT_UL_SEG;
    if (send_frame(ch, 0x60u, NULL, 0) != 0) {
        finish(ch, ODG_ABORT_HARDWARE);
    }
}

static void upload_segment(odg_sdoc_t *ch, const uint8_t *d)
{
    if ((d[0] & 0xE0u) != 0u) {
        odg_sdoc_abort(ch, ODG_ABORT_COMMAND);
        return;
    }
    if ((d[0] >> 4 & 1u) != ch->toggle) {
        odg_sdoc_abort(ch, ODG_ABORT_TOGGLE);
        return;
    }
    if (!keep(ch, d + 1, 7u - (d[0] >> 1 & 7u))) {
        return;
    }
    ch->toggle ^= 1u;
    if ((d[0] & 0x01u) != 0u) {
        finish(ch, ch->total == 0xFFFFFFFFu || ch->total == ch->n ? ODG_OK : ODG_ABORT_TYPE_LENGTH);
        if (ch->state == ODG_SDOC_ABORTED) {
            ch->state = ODG_SDOC_BUSY; /* tell the server too */
            odg_sdoc_abort(ch, ODG_ABORT_TYPE_LENGTH);
        }
    } else if (send_frame(ch, (uint8_t)(0x60u | (uint32_t)ch->toggle << 4), NULL, 0) != 0) {
        finish(ch, ODG_ABORT_HARDWARE);
    }
}

/* An initiate answer must name the object asked for. */
static int same_object(const odg_sdoc_t *ch, const uint8_t *d)
{
    return d[1] == (uint8_t)ch->index && d[2] == (uint8_t)(ch->index >> 8) && d[3] == ch->sub;
}

int odg_sdoc_receive(odg_sdoc_t *ch, const odg_frame_t *frame)
{
    const uint8_t *d = frame->data;
    uint8_t scs = (uint8_t)(d[0] >> 5);
    if (frame->id != ch->cob_rx || (frame->flags & (ODG_FRAME_RTR | ODG_FRAME_EFF)) != 0u) {
        return 0;
    }
    if (ch->state != ODG_SDOC_BUSY) {
        return 1; /* a late answer to a finished transfer */
    }
    if (frame->len < 8u) {
        odg_sdoc_abort(ch, ODG_ABORT_COMMAND);
    } else if ((d[0] == 0x80u || scs == 2u || scs == 3u) && !same_object(ch, d)) {
        /* an abort or initiate answer about another object: a late answer to a transfer given
         * up before (the server rebooted, say), not this one's: ignored */
    } else if (d[0] == 0x80u) { /* the server aborted */
        finish(ch, odg_sdoc_u32(d + 4, 4) != 0u ? odg_sdoc_u32(d + 4, 4) : ODG_ABORT_GENERAL);
    } else if (ch->phase == WAIT_DL_INIT && scs == 3u) {
        if (ch->total <= 4u && ch->total > 0u) {
            finish(ch, ODG_OK);
        } else {
            next_segment(ch);
        }
    } else if (ch->phase == WAIT_DL_SEG && scs == 1u && (d[0] >> 4 & 1u) == ch->toggle) {
        ch->toggle ^= 1u;
        next_segment(ch);
    } else if (ch->phase == WAIT_UL_INIT && scs == 2u) {
        upload_initiated(ch, d);
    } else if (ch->phase == WAIT_UL_SEG && scs == 0u) {
        upload_segment(ch, d);
    } else if (ch->phase == WAIT_DL_SEG && scs == 1u) {
        odg_sdoc_abort(ch, ODG_ABORT_TOGGLE);
    } else {
        odg_sdoc_abort(ch, ODG_ABORT_COMMAND);
    }
    return 1;
}

void odg_sdoc_tick(odg_sdoc_t *ch, uint32_t elapsed_ms)
{
    if (ch->state != ODG_SDOC_BUSY) {
        return;
    }
    ch->timer = ch->timer + elapsed_ms < ch->timer ? 0xFFFFFFFFu : ch->timer + elapsed_ms;
    if (ch->timer >= ODG_SDOC_TIMEOUT_MS) {
        odg_sdoc_abort(ch, ODG_ABORT_TIMEOUT);
    }
}
