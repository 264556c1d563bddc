/*
 * fake.h - a fake CAN transport for the odg_node tests, and a small SDO client on top of it.
 *
 * Frames the node sends are captured in sent[]; rx() hands a frame to the node; after() ticks.
 * The SDO client functions speak CiA 301 to the node and return the abort code it answered
 * with (0 on success), so each test reads like a master's session.
 */
#ifndef FAKE_H
#define FAKE_H

#include <string.h>

#include "check.h"
#include "odg_node.h"

#ifndef NID
#define NID 5u
#endif
#define SDO_RX (0x600u + NID)
#define SDO_TX (0x580u + NID)

#define MAX_SENT 1024u
static odg_frame_t sent[MAX_SENT];
static unsigned n_sent;
static int send_fails; /* the next n sends fail */
static odg_node_t node;
static void (*on_send)(const odg_frame_t *f); /* optional: sees every frame the node sends */

static int fake_send(void *ctx, const odg_frame_t *f)
{
    (void)ctx;
    if (on_send != NULL) {
        on_send(f);
    }
    if (send_fails > 0) {
        send_fails--;
        return -1;
    }
    if (n_sent < MAX_SENT) {
        sent[n_sent++] = *f;
    }
    return 0;
}

static void clear(void)
{
    n_sent = 0;
}

static void rx_frame(uint32_t id, const uint8_t *data, unsigned len)
{
    odg_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = id;
    f.len = (uint8_t)len;
    if (len > 0u) {
        memcpy(f.data, data, len);
    }
    odg_node_receive(&node, &f);
}

/* rx(id, bytes...) with at least one byte; rx0(id) for an empty frame */
#define rx(id, ...) \
    rx_frame((id), (const uint8_t[]){__VA_ARGS__}, (unsigned)sizeof((const uint8_t[]){__VA_ARGS__}))
#define rx0(id) rx_frame((id), NULL, 0)

static void after(uint32_t ms)
{
    odg_node_tick(&node, ms);
}

/* tick 1 ms at a time */
static void run_ms(uint32_t ms)
{
    while (ms-- > 0u) {
        odg_node_tick(&node, 1);
    }
}

/* How many captured frames have this id. */
static unsigned count_id(uint32_t id)
{
    unsigned i, c = 0;
    for (i = 0; i < n_sent; i++) {
        c += sent[i].id == id;
    }
    return c;
}

/* The last captured frame with this id, or an all-zero frame (id 0, no data). */
static const odg_frame_t *last_id(uint32_t id)
{
    static const odg_frame_t zero;
    unsigned i = n_sent;
    while (i-- > 0u) {
        if (sent[i].id == id) {
            return &sent[i];
        }
    }
    return &zero;
}

/* ---- SDO client -------------------------------------------------------------------------- */

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint16_t crc16(const uint8_t *p, uint32_t len)
{
    uint16_t crc = 0;
    unsigned k;
    while (len-- > 0u) {
        crc = (uint16_t)(crc ^ (unsigned)*p++ << 8);
        for (k = 0; k < 8u; k++) {
            crc = (uint16_t)(crc & 0x8000u ? (unsigned)crc << 1 ^ 0x1021u : (unsigned)crc << 1);
        }
    }
    return crc;
}

/* Send an SDO request (8 bytes) and return the node's single response (a zero frame if it
 * sent none, which a CHECK then notices). */
static const odg_frame_t *sdo8(const uint8_t *d)
{
    const odg_frame_t *r;
    clear();
    rx_frame(SDO_RX, d, 8);
    r = last_id(SDO_TX);
    CHECK_EQ(count_id(SDO_TX), 1);
    CHECK_EQ(r->len, 8);
    return r;
}

#define sdo(...) sdo8((const uint8_t[8]){__VA_ARGS__})
#define IDX(i) (uint8_t)((i) & 0xFF), (uint8_t)((i) >> 8)

/* The abort code in a response, 0 when it is not an abort. */
static uint32_t abort_of(const odg_frame_t *r)
{
    return r->data[0] == 0x80u ? le32(r->data + 4) : 0u;
}

/* The SDO transfer under way times out: nothing sent for 999 ms (ticked 1 ms at a time), then
 * the server's timeout abort at the 1000th. */
static void sdo_times_out(void)
{
    clear();
    run_ms(999);
    CHECK_EQ(n_sent, 0);
    run_ms(1);
    CHECK_EQ(abort_of(last_id(SDO_TX)), ODG_ABORT_TIMEOUT);
}

static uint32_t upload(uint16_t index, uint8_t sub, uint8_t *buf, uint32_t cap, uint32_t *n)
{
    const odg_frame_t *r = sdo(0x40, IDX(index), sub, 0, 0, 0, 0);
    uint32_t size, got = 0, toggle = 0;
    *n = 0;
    if (r->data[0] == 0x80u) {
        return abort_of(r);
    }
    if ((r->data[0] & 0xE3u) == 0x43u) { /* expedited, size indicated */
        size = 4u - (r->data[0] >> 2 & 3u);
        memcpy(buf, r->data + 4, size < cap ? size : cap);
        *n = size;
        return 0;
    }
    CHECK_EQ(r->data[0], 0x41);
    size = le32(r->data + 4);
    for (;;) {
        uint32_t len;
        r = sdo((uint8_t)(0x60u | toggle << 4), 0, 0, 0, 0, 0, 0, 0);
        if (r->data[0] == 0x80u) {
            return abort_of(r);
        }
        CHECK_EQ(r->data[0] >> 5, 0);
        CHECK_EQ(r->data[0] >> 4 & 1u, toggle);
        len = 7u - (r->data[0] >> 1 & 7u);
        if (got + len <= cap) {
            memcpy(buf + got, r->data + 1, len);
        }
        got += len;
        toggle ^= 1u;
        if (r->data[0] & 1u) {
            break;
        }
        if (got > cap + 7u) {
            CHECK(0);
            break;
        }
    }
    CHECK_EQ(got, size);
    *n = got;
    return 0;
}

static uint32_t upload_u32(uint16_t index, uint8_t sub)
{
    uint8_t b[8] = {0};
    uint32_t n;
    uint32_t ac = upload(index, sub, b, sizeof b, &n);
    CHECK_EQ(ac, 0);
    return le32(b);
}

static uint32_t download_expedited(uint16_t index, uint8_t sub, const uint8_t *data, uint32_t len)
{
    uint8_t d[8] = {0};
    d[0] = (uint8_t)(0x23u | (4u - len) << 2);
    d[1] = (uint8_t)index;
    d[2] = (uint8_t)(index >> 8);
    d[3] = sub;
    memcpy(d + 4, data, len);
    return abort_of(sdo8(d));
}

/* Segmented download; `sized` 0 leaves the size out of the initiate request. */
static uint32_t download_segmented(uint16_t index, uint8_t sub, const uint8_t *data, uint32_t len,
                                   int sized)
{
    const odg_frame_t *r;
    uint32_t off = 0, toggle = 0;
    r = sdo(sized ? 0x21 : 0x20, IDX(index), sub, (uint8_t)len, (uint8_t)(len >> 8), 0, 0);
    if (r->data[0] != 0x60u) {
        return abort_of(r);
    }
    do {
        uint8_t d[8] = {0};
        uint32_t n = len - off < 7u ? len - off : 7u;
        int last = off + n == len;
        d[0] = (uint8_t)(toggle << 4 | (7u - n) << 1 | (last ? 1u : 0u));
        memcpy(d + 1, data + off, n);
        r = sdo8(d);
        if (r->data[0] == 0x80u) {
            return abort_of(r);
        }
        CHECK_EQ(r->data[0], 0x20u | toggle << 4);
        CHECK_EQ(le32(r->data + 1) | le32(r->data + 4), 0); /* reserved bytes */
        off += n;
        toggle ^= 1u;
    } while (off < len);
    return 0;
}

/* Expedited up to 4 bytes, else segmented. */
static uint32_t download(uint16_t index, uint8_t sub, const void *data, uint32_t len)
{
    return len >= 1u && len <= 4u ? download_expedited(index, sub, (const uint8_t *)data, len)
                                  : download_segmented(index, sub, (const uint8_t *)data, len, 1);
}

static uint32_t download_u32(uint16_t index, uint8_t sub, uint32_t v, uint32_t len)
{
    uint8_t b[4];
    b[0] = (uint8_t)v;
    b[1] = (uint8_t)(v >> 8);
    b[2] = (uint8_t)(v >> 16);
    b[3] = (uint8_t)(v >> 24);
    return download_expedited(index, sub, b, len);
}

/* Block download with CRC. `drop` > 0 leaves out segment number `drop` of the first
 * sub-block once (the node then acks the segments before it, and they are repeated);
 * `bad_crc` sends a wrong CRC. */
static uint32_t block_download(uint16_t index, uint8_t sub, const uint8_t *data, uint32_t len,
                               unsigned drop, int bad_crc)
{
    const odg_frame_t *r;
    uint32_t off = 0, blksize;
    r = sdo(0xC6, IDX(index), sub, (uint8_t)len, (uint8_t)(len >> 8), 0, 0);
    if (r->data[0] == 0x80u) {
        return abort_of(r);
    }
    CHECK_EQ(r->data[0], 0xA4);
    blksize = r->data[4];
    CHECK(blksize >= 1u && blksize <= 127u);
    for (;;) {
        uint32_t seq = 0, start = off, pos = off;
        int last = 0;
        clear();
        while (!last && seq < blksize) {
            uint8_t d[8] = {0};
            uint32_t n = len - pos < 7u ? len - pos : 7u;
            last = pos + n >= len;
            seq++;
            d[0] = (uint8_t)((last ? 0x80u : 0u) | seq);
            memcpy(d + 1, data + pos, n);
            pos += n;
            if (seq == drop) {
                drop = 0;
                continue;
            }
            rx_frame(SDO_RX, d, 8);
        }
        r = last_id(SDO_TX);
        CHECK_EQ(count_id(SDO_TX), 1);
        if (r->id != SDO_TX) {
            return 0xFFFFFFFFu;
        }
        if (r->data[0] == 0x80u) {
            return abort_of(r);
        }
        CHECK_EQ(r->data[0], 0xA2);
        off = start + 7u * r->data[1];
        blksize = r->data[2];
        if (off >= len && last && r->data[1] == seq) {
            break;
        }
        off = off > len ? len : off;
    }
    {
        uint32_t used = len == 0u ? 0u : (len - 1u) % 7u + 1u;
        uint16_t crc = (uint16_t)(crc16(data, len) ^ (bad_crc ? 0x5555u : 0u));
        r = sdo((uint8_t)(0xC1u | (7u - used) << 2), (uint8_t)crc, (uint8_t)(crc >> 8), 0, 0, 0, 0, 0);
    }
    if (r->data[0] == 0x80u) {
        return abort_of(r);
    }
    CHECK_EQ(r->data[0], 0xA1);
    return 0;
}

/* Block upload with CRC, `blksize` segments per sub-block, protocol switch threshold `pst`.
 * `short_ack` > 0 acknowledges one segment fewer than received, once. */
static uint32_t block_upload(uint16_t index, uint8_t sub, uint8_t *buf, uint32_t cap, uint32_t *n,
                             uint8_t blksize, uint8_t pst, int short_ack)
{
    const odg_frame_t *r;
    uint32_t size, got = 0, i;
    int done = 0;
    *n = 0;
    r = sdo(0xA4, IDX(index), sub, blksize, pst, 0, 0);
    if (r->data[0] == 0x80u) {
        return abort_of(r);
    }
    if ((r->data[0] & 0xE0u) == 0x40u) { /* the node switched to a plain upload */
        CHECK_EQ(r->data[0] & 0xE3u, 0x43u);
        *n = 4u - (r->data[0] >> 2 & 3u);
        memcpy(buf, r->data + 4, *n);
        return 0x40; /* tells the caller which protocol it was */
    }
    CHECK_EQ(r->data[0], 0xC6);
    size = le32(r->data + 4);
    clear();
    rx(SDO_RX, 0xA3, 0, 0, 0, 0, 0, 0, 0);
    while (!done) {
        uint32_t seq = 0, ack;
        for (i = 0; i < n_sent; i++) {
            const uint8_t *d = sent[i].data;
            CHECK_EQ(sent[i].id, SDO_TX);
            if ((d[0] & 0x7Fu) != seq + 1u) {
                return d[0] == 0x80u ? le32(d + 4) : 0xFFFFFFFFu;
            }
            seq++;
            if (got + 7u > cap) {
                CHECK(0);
                return 0xFFFFFFFFu;
            }
            memcpy(buf + got, d + 1, 7);
            got += 7u;
            if (d[0] & 0x80u) {
                done = 1;
            }
        }
        CHECK(seq == blksize || done);
        ack = seq;
        if (short_ack && seq > 1u) {
            short_ack = 0;
            ack = seq - 1u;
            got -= 7u;
            done = 0;
        }
        clear();
        rx(SDO_RX, 0xA2, (uint8_t)ack, blksize, 0, 0, 0, 0, 0);
        if (done) {
            break;
        }
    }
    r = last_id(SDO_TX);
    CHECK_EQ(count_id(SDO_TX), 1);
    if (r->id != SDO_TX || r->data[0] == 0x80u) {
        return r->id == SDO_TX ? abort_of(r) : 0xFFFFFFFFu;
    }
    CHECK_EQ(r->data[0] & 0xE3u, 0xC1u);
    got -= r->data[0] >> 2 & 7u;
    CHECK_EQ(got, size);
    CHECK_EQ(r->data[1] | r->data[2] << 8, crc16(buf, got));
    clear();
    rx(SDO_RX, 0xA1, 0, 0, 0, 0, 0, 0, 0);
    CHECK_EQ(n_sent, 0);
    *n = got;
    return 0;
}

/* ---- a RAM NV driver ------------------------------------------------------------------- */

static uint8_t nv_mem[4096];

static int nv_read(void *ctx, uint32_t addr, void *buf, uint32_t len)
{
    (void)ctx;
    if (addr > sizeof nv_mem || len > sizeof nv_mem - addr) {
        return -1;
    }
    memcpy(buf, nv_mem + addr, len);
    return 0;
}

static int nv_write(void *ctx, uint32_t addr, const void *buf, uint32_t len)
{
    (void)ctx;
    if (addr > sizeof nv_mem || len > sizeof nv_mem - addr) {
        return -1;
    }
    memcpy(nv_mem + addr, buf, len);
    return 0;
}

static int nv_erase(void *ctx, uint32_t addr, uint32_t len)
{
    (void)ctx;
    if (addr > sizeof nv_mem || len > sizeof nv_mem - addr) {
        return -1;
    }
    memset(nv_mem + addr, 0xFF, len);
    return 0;
}

static const odg_nv_driver_t nv_ram = {nv_read, nv_write, nv_erase, NULL};

/* Start the node: boot-up 0x700 + id with 0x00, pre-operational. */
static void start_node(const odg_dict_t *dict, const odg_nv_driver_t *nv)
{
    odg_node_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.dict = dict;
    cfg.node_id = NID;
    cfg.nv = nv;
    cfg.send = fake_send;
    clear();
    CHECK_EQ(odg_node_init(&node, &cfg), 0);
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(sent[0].id, 0x700u + NID);
    CHECK_EQ(sent[0].len, 1);
    CHECK_EQ(sent[0].data[0], 0x00);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL);
}

static void nmt(uint8_t cmd, uint8_t id)
{
    rx(0, cmd, id);
}

/* Refers to every helper, so that a test that does not call one compiles without
 * -Wunused-function (each test program is a single translation unit). */
void fake_keep_(void);
void fake_keep_(void)
{
    (void)run_ms, (void)after, (void)count_id, (void)last_id, (void)upload, (void)upload_u32;
    (void)download, (void)download_u32, (void)download_segmented, (void)block_download;
    (void)block_upload, (void)nv_ram, (void)start_node, (void)nmt, (void)abort_of;
    (void)sdo_times_out;
}

#endif /* FAKE_H */
