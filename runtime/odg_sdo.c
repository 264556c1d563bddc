/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_sdo.c - the node's SDO server: expedited, segmented and (ODG_NODE_SDO_BLOCK) block
 * transfers in both directions, over odg_read / odg_write / odg_write_part. Without block
 * transfer a block initiate is answered with abort 0x05040001, as for any unknown command.
 *
 * Downloads of at most 8 bytes (every number) are collected in sdo.buf and written whole
 * with odg_write when complete; longer ones (strings, domains) go to odg_write_part segment
 * by segment. A block download holds its newest segment back until the end frame, because
 * only that frame says how many of its bytes count; the held bytes complete the value only
 * once the CRC has matched. Uploads take the first 8 bytes with one odg_read at offset 0
 * (which runs the PRE_READ hook once) and the rest at their offsets.
 *
 * The topmost service (odg_sdo.h): calls the checks of odg_sync.c, odg_pdo.c, odg_hb.c and
 * odg_err.c, odg_comm.c after a "save" or "load", and odg_node_io.c.
 */
#include <string.h>

#include "odg_impl.h"
#include "odg_node.h"

#define SIZE_UNKNOWN 0xFFFFFFFFu
/* A download streamed to odg_write_part: only strings and domains are (begin_download refuses
 * the rest), so a build serving none leaves the streaming out. */
#define STREAMING(s) (T_STREAM != 0u && ((s)->flags & ODG_SDO_F_STREAM) != 0u)
/* Values longer than 4 bytes, uploaded in segments: strings, domains and the types wider than
 * 32 bits. A build serving none of them uploads every value expedited (1..4 bytes). */
#define LONG_VALUES (T_STREAM != 0u || ODG_CFG_INT64)


#if ODG_NODE_SDO_BLOCK
/* CRC-16-CCITT of CiA 301 block transfers: polynomial 0x1021, initial value 0, MSB first. */
static uint16_t crc16(uint16_t crc, const uint8_t *p, uint32_t len)
{
    unsigned k;
    while (len-- > 0u) {
        crc = (uint16_t)(crc ^ (unsigned)*p++ << 8);
        for (k = 0; k < 8u; k++) {
            crc = (uint16_t)(crc & 0x8000u ? (unsigned)crc << 1 ^ 0x1021u : (unsigned)crc << 1);
        }
    }
    return crc;
}
#endif

/* An 8-byte frame: byte 0, bytes 1..3 from `mid` and bytes 4..7 from `tail` (little-endian). */
static void send8(odg_node_t *n, uint8_t b0, uint32_t mid, uint32_t tail)
{
    uint8_t d[8];
    odg_put_le32_(d, mid << 8 | b0);
    odg_put_le32_(d + 4, tail);
    (void)odg_io_send_(n, n->sdo_tx, d, 8);
}

/* A response: command byte, index and sub-index of the transfer, then `tail` in bytes 4..7
 * (0 for none). */
static void respond(odg_node_t *n, uint8_t cmd, uint32_t tail)
{
    send8(n, cmd, n->sdo.index | (uint32_t)n->sdo.sub << 16, tail);
}

/* Abort the transfer (or the request) with `code`; the server is idle afterwards. */
static void fail(odg_node_t *n, odg_abort_t code)
{
    respond(n, 0x80, code);
    n->sdo.state = ODG_SDO_IDLE;
}

/* ---- download ------------------------------------------------------------------------- */

/* Before a whole value of at most 4 bytes is stored: the rules of CiA 301 the services keep
 * (0x1003, 0x1016, 0x1019 and the PDO parameters); other entries have none. */
static odg_abort_t check(const odg_node_t *n, uint16_t index, uint8_t sub, const uint8_t *data, uint32_t len)
{
    uint32_t v = 0;
    if (index == 0x1019u) {
        return odg_sync_check_(n, data, len);
    }
    if (len > 4u) {
        return ODG_OK;
    }
    while (len > 0u) {
        len--;
        v = v << 8 | data[len];
    }
    if (index == 0x1016u) {
        return odg_hb_check_(n, sub, v);
    }
    if (index == 0x1003u) {
        return ODG_ERR_CHECK(sub, v);
    }
    return index >= 0x1400u && index < 0x1C00u ? odg_pdo_check_(n, index, sub, v) : ODG_OK;
}

/* Store a complete value of at most 8 bytes: PDO rules first, then the dictionary (which
 * tells the node's client what changed); but a read-only entry answers 0x06010002 from the
 * dictionary, whatever the PDO rules say. */
static odg_abort_t write_whole(odg_node_t *n, const uint8_t *data, uint32_t len)
{
    odg_sdo_t *s = &n->sdo;
    uint8_t storage = s->ref.sub->storage;
    odg_abort_t ac = (s->ref.sub->attr & ODG_A_WRITE) ? check(n, s->index, s->sub, data, len) : ODG_OK;
    if (ac == ODG_OK && (ac = odg_write(&s->ref, data, len)) == ODG_OK && ODG_S_CLASS(storage) == ODG_S_COMMAND) {
        odg_comm_stored_(n, s->sub, (storage & ODG_S_RESTORE_FLAG) != 0u); /* a "save" or "load" done */
    }
    return ac;
}

/* Start a segmented or block download of `total` bytes (SIZE_UNKNOWN: not indicated); a
 * number announced longer than 8 bytes is refused. Strings and domains are streamed (IS_STREAM:
 * of the types the build serves, which are all the dictionary has); every other type is a
 * number of at most 8 bytes. */
#if ODG_NODE_SDO_BLOCK
ODG_NODE_OUTLINE_ /* two callers then: out of line, else inlined into its one caller */
#endif
static odg_abort_t begin_download(odg_node_t *n, uint32_t total)
{
    odg_sdo_t *s = &n->sdo;
    s->total = total;
    s->offset = 0;
    s->toggle = 0;
    s->flags = (uint8_t)(total == SIZE_UNKNOWN ? 0u
                         : total > 8u        ? ODG_SDO_F_SIZED | ODG_SDO_F_STREAM
                                             : ODG_SDO_F_SIZED);
    return total != SIZE_UNKNOWN && total > 8u && !IS_STREAM(s->ref.sub) ? ODG_ABORT_TOO_LONG : ODG_OK;
}

/* Take the next `len` bytes of a download. Without an indicated size the bytes are
 * collected, so at most 8 fit (a number): a longer value without a size cannot go to
 * odg_write_part, which needs the total first. */
static odg_abort_t take(odg_node_t *n, const uint8_t *data, uint32_t len)
{
    odg_sdo_t *s = &n->sdo;
    odg_abort_t ac;
    if (len > s->total - s->offset) { /* without a size total is SIZE_UNKNOWN: never */
        return ODG_ABORT_TOO_LONG;
    }
    if (STREAMING(s)) {
        if ((ac = odg_write_part(&s->ref, s->offset, data, len, s->total)) != ODG_OK) {
            return ac;
        }
    } else if (len > 8u - s->offset) {
        return ODG_ABORT_OUT_OF_MEMORY;
    } else {
        odg_copy(s->buf + s->offset, data, len);
    }
#if ODG_NODE_SDO_BLOCK
    s->crc = crc16(s->crc, data, len);
#endif
    s->offset += len;
    return ODG_OK;
}

/* All bytes are in: write a collected value; a stream completed with its last part. */
static odg_abort_t finish_download(odg_node_t *n)
{
    odg_sdo_t *s = &n->sdo;
    if ((s->flags & ODG_SDO_F_SIZED) && s->offset != s->total) {
        return ODG_ABORT_TOO_SHORT;
    }
    if (STREAMING(s)) {
        return ODG_OK;
    }
    return write_whole(n, s->buf, s->offset);
}

/* Take the next bytes, and with `last` (not 0) finish the download. */
static odg_abort_t take_more(odg_node_t *n, const uint8_t *data, uint32_t len, unsigned last)
{
    odg_abort_t ac = take(n, data, len);
    return ac == ODG_OK && last ? finish_download(n) : ac;
}

/* Each step below answers the client itself and returns ODG_OK, or returns the abort code
 * that odg_sdo_receive_ then sends (fail), which ends the transfer. */

static odg_abort_t download_initiate(odg_node_t *n, const uint8_t *d)
{
    odg_sdo_t *s = &n->sdo;
    odg_abort_t ac;
    if (d[0] & 0x02u) { /* expedited */
        uint32_t len = (d[0] & 0x01u) ? 4u - (d[0] >> 2 & 3u) : 4u;
        ac = write_whole(n, d + 4, len);
        if (ac == ODG_ABORT_TOO_LONG && !(d[0] & 0x01u) && (len = odg_length(&s->ref)) < 4u) {
            ac = write_whole(n, d + 4, len); /* size not indicated: a short number */
        }
    } else {
        ac = begin_download(n, (d[0] & 0x01u) ? ODG_LE32(d + 4) : SIZE_UNKNOWN);
        s->state = ODG_SDO_DN_SEG;
    }
    if (ac == ODG_OK) {
        respond(n, 0x60, 0);
    }
    return ac;
}

static odg_abort_t download_segment(odg_node_t *n, const uint8_t *d)
{
    odg_sdo_t *s = &n->sdo;
    odg_abort_t ac;
    uint8_t toggle = d[0] & 0x10u;
    if ((d[0] >> 5) != 0u) {
        return ODG_ABORT_COMMAND;
    }
    if (toggle != s->toggle) {
        return ODG_ABORT_TOGGLE;
    }
    if ((ac = take_more(n, d + 1, 7u - (d[0] >> 1 & 7u), d[0] & 0x01u)) != ODG_OK) {
        return ac;
    }
    send8(n, (uint8_t)(0x20u | toggle), 0, 0); /* bytes 1..7 reserved */
    s->toggle ^= 0x10u;
    if (d[0] & 0x01u) {
        s->state = ODG_SDO_IDLE;
    }
    return ODG_OK;
}

#if ODG_NODE_SDO_BLOCK
static odg_abort_t block_download_initiate(odg_node_t *n, const uint8_t *d)
{
    odg_sdo_t *s = &n->sdo;
    uint8_t blksize = ODG_NODE_SDO_BLKSIZE;
    odg_abort_t ac = begin_download(n, (d[0] & 0x02u) ? ODG_LE32(d + 4) : SIZE_UNKNOWN);
    if (ac != ODG_OK) {
        return ac;
    }
    if (d[0] & 0x04u) {
        s->flags |= ODG_SDO_F_CRC;
    }
    s->crc = 0;
    s->blksize = blksize;
    s->seq = 0;
    respond(n, 0xA4, blksize); /* sc = 1: the server checks the CRC */
    s->state = ODG_SDO_BLK_DN;
    return ODG_OK;
}

/* A segment of a sub-block: byte 0 is c (last) << 7 | sequence number. A segment out of
 * order (one was lost) is ignored; the ack then names the last good one, and the client
 * repeats the rest in the next sub-block. */
static odg_abort_t block_download_segment(odg_node_t *n, const uint8_t *d)
{
    odg_sdo_t *s = &n->sdo;
    uint8_t seq = d[0] & 0x7Fu, last = d[0] & 0x80u;
    odg_abort_t ac;
    if (seq == 0u || seq > s->blksize) {
        return ODG_ABORT_SEQUENCE;
    }
    if (seq == s->seq + 1u && !(s->flags & ODG_SDO_F_LAST)) {
        if ((s->flags & ODG_SDO_F_HELD) && (ac = take(n, s->seg, 7)) != ODG_OK) {
            return ac;
        }
        odg_copy(s->seg, d + 1, 7);
        s->flags |= (uint8_t)(ODG_SDO_F_HELD | (last ? ODG_SDO_F_LAST : 0u));
        s->seq = seq;
    }
    if (seq == s->blksize || last) {
        send8(n, 0xA2, s->seq | (uint32_t)s->blksize << 8, 0); /* ackseq, blksize for the next sub-block */
        s->seq = 0;
        if (s->flags & ODG_SDO_F_LAST) {
            s->state = ODG_SDO_BLK_DN_END;
        }
    }
    return ODG_OK;
}

static odg_abort_t block_download_end(odg_node_t *n, const uint8_t *d)
{
    odg_sdo_t *s = &n->sdo;
    uint32_t len = 7u - (d[0] >> 2 & 7u);
    odg_abort_t ac;
    if ((d[0] & 0xE3u) != 0xC1u) {
        return ODG_ABORT_COMMAND;
    }
    if ((s->flags & ODG_SDO_F_CRC) &&
        crc16(s->crc, s->seg, len) != (uint16_t)(d[1] | (unsigned)d[2] << 8)) {
        return ODG_ABORT_CRC;
    }
    if ((ac = take_more(n, s->seg, len, 1)) != ODG_OK) {
        return ac;
    }
    send8(n, 0xA1, 0, 0);
    s->state = ODG_SDO_IDLE;
    return ODG_OK;
}
#endif /* ODG_NODE_SDO_BLOCK */

/* ---- upload ----------------------------------------------------------------------------- */

/* `len` bytes of the value from `off` into `out`, which the caller zeroed: the first 8 from the
 * snapshot taken at the start, the rest read now (a value that shrank meanwhile leaves zeros).
 * Only strings and domains have bytes beyond the snapshot: builds without them read none. */
static odg_abort_t upload_data(odg_node_t *n, uint32_t off, uint8_t *out, uint32_t len)
{
    odg_sdo_t *s = &n->sdo;
    uint32_t k = 0, got;
    for (; k < len && off + k < s->n_buf; k++) {
        out[k] = s->buf[off + k];
    }
    return T_STREAM != 0u && k < len ? odg_read(&s->ref, off + k, out + k, len - k, &got) : ODG_OK;
}

/* Read the first bytes (PRE_READ runs here) and the size of the value. */
static odg_abort_t upload_begin(odg_node_t *n)
{
    odg_sdo_t *s = &n->sdo;
    uint32_t got;
    odg_abort_t ac;
    memset(s->buf, 0, sizeof s->buf); /* an expedited upload sends 4 bytes: those not read are 0 */
    ac = odg_read(&s->ref, 0, s->buf, sizeof s->buf, &got);
    s->total = T_STREAM == 0u || got < sizeof s->buf ? got : odg_length(&s->ref); /* a number: got */
    if (LONG_VALUES || ODG_NODE_SDO_BLOCK) { /* for upload_data: segmented and block uploads */
        s->n_buf = (uint8_t)got;
    }
    if (LONG_VALUES) { /* for a segmented upload, which only values longer than 4 bytes take */
        s->offset = 0;
        s->toggle = 0;
    }
    return ac;
}

/* Answer an upload request (the server is idle): expedited for 1..4 bytes, after which it
 * stays idle, else announce a segmented transfer. */
static void upload_respond(odg_node_t *n)
{
    odg_sdo_t *s = &n->sdo;
    if (!LONG_VALUES || (s->total >= 1u && s->total <= 4u)) {
        respond(n, (uint8_t)(0x43u | (4u - s->total) << 2), ODG_LE32(s->buf));
        return;
    }
    respond(n, 0x41, s->total);
    s->state = ODG_SDO_UP_SEG;
}

static odg_abort_t upload_initiate(odg_node_t *n)
{
    odg_abort_t ac = upload_begin(n);
    if (ac == ODG_OK) {
        upload_respond(n);
    }
    return ac;
}

static odg_abort_t upload_segment(odg_node_t *n, const uint8_t *d)
{
    odg_sdo_t *s = &n->sdo;
    uint8_t f[8], toggle = d[0] & 0x10u;
    uint32_t len = s->total - s->offset < 7u ? s->total - s->offset : 7u;
    odg_abort_t ac;
    if ((d[0] & 0xEFu) != 0x60u) {
        return ODG_ABORT_COMMAND;
    }
    if (toggle != s->toggle) {
        return ODG_ABORT_TOGGLE;
    }
    memset(f, 0, sizeof f);
    if ((ac = upload_data(n, s->offset, f + 1, len)) != ODG_OK) {
        return ac;
    }
    s->offset += len;
    f[0] = (uint8_t)(toggle | (7u - len) << 1 | (s->offset >= s->total ? 1u : 0u));
    (void)odg_io_send_(n, n->sdo_tx, f, 8);
    s->toggle ^= 0x10u;
    if (s->offset >= s->total) {
        s->state = ODG_SDO_IDLE;
    }
    return ODG_OK;
}

#if ODG_NODE_SDO_BLOCK
static odg_abort_t block_upload_initiate(odg_node_t *n, const uint8_t *d)
{
    odg_sdo_t *s = &n->sdo;
    odg_abort_t ac;
    if (d[4] == 0u || d[4] > 127u) {
        return ODG_ABORT_BLOCK_SIZE;
    }
    if ((ac = upload_begin(n)) != ODG_OK) {
        return ac;
    }
    if (d[5] != 0u && s->total <= d[5]) {
        upload_respond(n); /* protocol switch threshold: a plain upload is cheaper */
        return ODG_OK;
    }
    s->blksize = d[4];
    s->flags = (d[0] & 0x04u) ? ODG_SDO_F_CRC : 0u;
    respond(n, 0xC6, s->total); /* sc = 1 (CRC supported), s = 1 (size indicated) */
    s->state = ODG_SDO_BLK_UP_START;
    return ODG_OK;
}

/* Send the segments of the sub-block not yet sent; stops early when `send` is busy (the
 * next tick resumes). The last segment carries c = 1, and an empty value one empty segment. */
static odg_abort_t block_upload_pump(odg_node_t *n)
{
    odg_sdo_t *s = &n->sdo;
    uint8_t f[8];
    while (s->state == ODG_SDO_BLK_UP && s->seq < s->blksize && !(s->flags & ODG_SDO_F_LAST)) {
        uint32_t len = s->total - s->offset < 7u ? s->total - s->offset : 7u;
        uint8_t last = s->offset + len >= s->total ? 0x80u : 0u;
        odg_abort_t ac;
        memset(f, 0, sizeof f);
        if ((ac = upload_data(n, s->offset, f + 1, len)) != ODG_OK) {
            return ac;
        }
        f[0] = (uint8_t)(last | (s->seq + 1u));
        if (odg_io_send_(n, n->sdo_tx, f, 8) != 0) {
            break;
        }
        s->seq++;
        s->offset += len;
        s->flags |= last ? ODG_SDO_F_LAST : 0u;
    }
    return ODG_OK;
}

/* CRC of the acknowledged bytes [from, to), read again: cheaper in RAM than keeping a CRC
 * per segment for the case that the client asks for a repetition. */
static odg_abort_t crc_range(odg_node_t *n, uint32_t from, uint32_t to)
{
    uint8_t b[7];
    odg_abort_t ac = ODG_OK;
    while (from < to && ac == ODG_OK) {
        uint32_t len = to - from < 7u ? to - from : 7u;
        memset(b, 0, sizeof b);
        ac = upload_data(n, from, b, len);
        n->sdo.crc = crc16(n->sdo.crc, b, len);
        from += len;
    }
    return ac;
}

static odg_abort_t block_upload_ack(odg_node_t *n, const uint8_t *d)
{
    odg_sdo_t *s = &n->sdo;
    uint32_t sent, acked;
    odg_abort_t ac;
    if (d[1] > s->seq) {
        return ODG_ABORT_SEQUENCE;
    }
    if (d[2] == 0u || d[2] > 127u) {
        return ODG_ABORT_BLOCK_SIZE;
    }
    sent = s->blk_offset + 7u * d[1]; /* 7 bytes a segment, the last one padded */
    acked = sent < s->total ? sent : s->total;
    s->crc = s->blk_crc;
    if ((ac = crc_range(n, s->blk_offset, acked)) != ODG_OK) {
        return ac;
    }
    if (d[1] < s->seq) {
        s->flags &= (uint8_t)~ODG_SDO_F_LAST; /* repeat from the first segment not acked */
    }
    s->blk_offset = s->offset = acked;
    s->blk_crc = s->crc;
    s->blksize = d[2];
    s->seq = 0;
    if (s->flags & ODG_SDO_F_LAST) {
        /* n: the last segment's padding (all 7 bytes of an empty value's one segment); the CRC in
         * bytes 1..2 */
        send8(n, (uint8_t)(0xC1u | (sent - acked) << 2), s->crc, 0);
        s->state = ODG_SDO_BLK_UP_END;
        return ODG_OK;
    }
    return block_upload_pump(n);
}

static odg_abort_t block_upload(odg_node_t *n, const uint8_t *d)
{
    odg_sdo_t *s = &n->sdo;
    /* start 0xA3 (BLK_UP_START), ack 0xA2 (BLK_UP), end 0xA1 (BLK_UP_END): the states in order */
    if (d[0] != 0xA3u - (unsigned)(s->state - ODG_SDO_BLK_UP_START)) {
        return ODG_ABORT_COMMAND;
    }
    if (s->state == ODG_SDO_BLK_UP_START) {
        s->state = ODG_SDO_BLK_UP;
        s->blk_offset = s->offset = 0;
        s->blk_crc = 0;
        s->seq = 0;
        return block_upload_pump(n);
    }
    if (s->state == ODG_SDO_BLK_UP) {
        return block_upload_ack(n, d);
    }
    s->state = ODG_SDO_IDLE; /* the client confirmed the end */
    return ODG_OK;
}
#endif /* ODG_NODE_SDO_BLOCK */

/* ---- dispatch ------------------------------------------------------------------------------ */

static odg_abort_t initiate(odg_node_t *n, const uint8_t *d)
{
    odg_sdo_t *s = &n->sdo;
    odg_abort_t ac;
    unsigned ccs = d[0] >> 5;
    if (!(ccs == 1u || ccs == 2u ||
          (ODG_NODE_SDO_BLOCK && ((ccs == 5u && (d[0] & 3u) == 0u) || (ccs == 6u && (d[0] & 1u) == 0u))))) {
        return ODG_ABORT_COMMAND;
    }
    if ((ac = odg_find(n->cfg.dict, s->index, s->sub, &s->ref)) != ODG_OK) {
        return ac;
    }
    if (ccs == 1u) {
        return download_initiate(n, d);
    }
#if ODG_NODE_SDO_BLOCK
    if (ccs == 5u) {
        return block_upload_initiate(n, d);
    }
    if (ccs == 6u) {
        return block_download_initiate(n, d);
    }
#endif
    return upload_initiate(n);
}

/*
 * Every SDO frame has 8 bytes (CiA 301). A shorter one is answered with an abort
 * 0x05040001 (and ends a transfer in progress) rather than ignored, so that the client learns
 * at once instead of running into its timeout; only a short abort frame is silently taken
 * as the client's abort. An abort from the client (command byte 0x80) drops the transfer
 * without an answer: an abort is never answered.
 */
void odg_sdo_receive_(odg_node_t *n, const odg_frame_t *f)
{
    odg_sdo_t *s = &n->sdo;
    uint8_t d[8];
    odg_abort_t ac = ODG_ABORT_COMMAND;
    memset(d, 0, sizeof d);
    odg_copy(d, f->data, f->len);
    s->timer = 0;
    if (d[0] == 0x80u) { /* an empty frame has d[0] = 0 */
        s->state = ODG_SDO_IDLE;
        return;
    }
    if (s->state == ODG_SDO_IDLE) { /* a request: what it names, which an abort names too */
        s->index = (uint16_t)(d[1] | (unsigned)d[2] << 8);
        s->sub = d[3];
    }
    if (f->len < 8u) {
        /* too short: ac stays ODG_ABORT_COMMAND */
    } else if (s->state == ODG_SDO_IDLE) {
        ac = initiate(n, d);
    } else if (s->state == ODG_SDO_DN_SEG) {
        ac = download_segment(n, d);
    } else if (LONG_VALUES && s->state == ODG_SDO_UP_SEG) {
        ac = upload_segment(n, d);
#if ODG_NODE_SDO_BLOCK
    } else if (s->state == ODG_SDO_BLK_DN) {
        ac = block_download_segment(n, d);
    } else if (s->state == ODG_SDO_BLK_DN_END) {
        ac = block_download_end(n, d);
    } else {
        ac = block_upload(n, d);
#endif
    }
    if (ac != ODG_OK) {
        fail(n, ac);
    }
}

void odg_sdo_tick_(odg_node_t *n, uint32_t ms)
{
    odg_sdo_t *s = &n->sdo;
    odg_abort_t ac = ODG_OK;
    if (s->state == ODG_SDO_IDLE) {
        return;
    }
#if ODG_NODE_SDO_BLOCK
    ac = block_upload_pump(n);
#endif
    if (ac == ODG_OK && ms >= ODG_NODE_SDO_TIMEOUT_MS - s->timer) { /* under way, timer < the timeout */
        ac = ODG_ABORT_TIMEOUT;
    }
    if (ac != ODG_OK) {
        fail(n, ac);
    }
    s->timer += ms;
}
