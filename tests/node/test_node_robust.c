/*
 * test_node_robust.c - the node under a misbehaving SDO client and a busy bus, against the
 * alltypes dictionary with a RAM NV memory, in simulated time (1 ms ticks): a client that
 * aborts mid-transfer, toggles wrongly, falls silent, or floods the server; 1 000 foreign
 * frames per simulated second for a simulated minute; NMT resets during block transfers;
 * both persistence slots damaged. Throughout, every heartbeat comes within one tick of its
 * period, the server answers a fresh upload after each ordeal, and the values saved with
 * 0x1010 come back after each reset of the node.
 */
#include <stdio.h>
#include <string.h>

#include "alltypes.h"
#include "fake.h"

#define HB_PERIOD 100u   /* ms, saved in 0x1017 */
#define SAVED_U8 42u     /* saved in 0x2005 */
#define SAVED_U32 0x5EEDu /* saved in 0x2015 (UNSIGNED24, persist:app) */

odg_abort_t alltypes_notice(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                            void *ctx)
{
    (void)ref, (void)kind, (void)data, (void)len, (void)ctx;
    return ODG_OK;
}

/* ---- simulated time and the heartbeat watch ---------------------------------------------- */

static uint32_t now;          /* ms */
static uint32_t last_hb;      /* time of the last heartbeat or boot-up */
static uint32_t watch_start;
static int hb_watch;          /* check heartbeat periods */
static unsigned long n_hb, n_timeouts;
static uint32_t rng = 0xC0FFEEu;

static uint32_t rnd(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

static void watch(const odg_frame_t *f)
{
    if (f->id == 0x700u + NID) {
        if (f->data[0] != 0u && hb_watch) { /* a heartbeat: within one tick of its period */
            uint32_t gap = now - last_hb;
            CHECK_EQ_AT(gap + 1u >= HB_PERIOD && gap <= HB_PERIOD + 1u, 1, now);
            n_hb++;
        }
        last_hb = now; /* a heartbeat or a boot-up starts the next period */
    } else if (f->id == SDO_TX && f->data[0] == 0x80u && le32(f->data + 4) == ODG_ABORT_TIMEOUT) {
        n_timeouts++;
    }
}

static void tick(uint32_t ms)
{
    while (ms-- > 0u) {
        now++;
        odg_node_tick(&node, 1);
    }
}

/* The server answers a fresh upload; stored values are what was saved. */
static void serving(int line)
{
    const odg_frame_t *r;
    rx(SDO_RX, 0x80, 0, 0, 0, 0, 0, 0, 0); /* whatever was going on ends */
    r = sdo(0x40, IDX(0x1000), 0, 0, 0, 0, 0);
    if (r->data[0] != 0x43u) {
        printf("  (not serving at line %d)\n", line);
    }
    CHECK_EQ(r->data[0], 0x43);
}
#define SERVING() serving(__LINE__)

static void values_kept(int line)
{
    uint32_t hb = upload_u32(0x1017, 0), u8 = upload_u32(0x2005, 0), u32 = upload_u32(0x2015, 0);
    if (hb != HB_PERIOD || u8 != SAVED_U8 || u32 != SAVED_U32) {
        printf("  (stored values lost at line %d)\n", line);
    }
    CHECK_EQ(hb, HB_PERIOD);
    CHECK_EQ(u8, SAVED_U8);
    CHECK_EQ(u32, SAVED_U32);
}
#define VALUES_KEPT() values_kept(__LINE__)

static void reset_node(void)
{
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(count_id(0x80u + NID), 0); /* nothing was lost: no EMCY */
}

/* ---- the ordeals ------------------------------------------------------------------------- */

static void setup(void)
{
    static const uint8_t save[4] = {'s', 'a', 'v', 'e'};
    memset(nv_mem, 0xFF, sizeof nv_mem);
    on_send = watch;
    start_node(&alltypes, &nv_ram);
    CHECK_EQ(download_u32(0x1017, 0, HB_PERIOD, 2), 0);
    CHECK_EQ(download_u32(0x2005, 0, SAVED_U8, 1), 0);
    CHECK_EQ(download_u32(0x2015, 0, SAVED_U32, 3), 0);
    CHECK_EQ(download(0x1010, 1, save, 4), 0);
    /* changed but not saved: a reset of the node forgets it */
    CHECK_EQ(download_u32(0x2005, 0, 7, 1), 0);
    clear();
    reset_node();
    VALUES_KEPT();
    last_hb = watch_start = now;
    hb_watch = 1;
    tick(1000);
    CHECK(n_hb >= 9u);
}

static void aborts_mid_transfer(void)
{
    /* segmented download, one segment, then the client aborts: no answer, nothing stored */
    CHECK_EQ(sdo(0x21, IDX(0x2009), 0, 20, 0, 0, 0)->data[0], 0x60);
    CHECK_EQ(sdo(0x00, 'a', 'b', 'c', 'd', 'e', 'f', 'g')->data[0], 0x20);
    clear();
    rx(SDO_RX, 0x80, IDX(0x2009), 0, 0, 0, 0, 0x08);
    CHECK_EQ(count_id(SDO_TX), 0);
    tick(3);
    SERVING();
    /* block download, part of a sub-block, abort */
    CHECK_EQ(sdo(0xC6, IDX(0x2009), 0, 30, 0, 0, 0)->data[0], 0xA4);
    rx(SDO_RX, 0x01, 'h', 'i', 'j', 'k', 'l', 'm', 'n');
    rx(SDO_RX, 0x80, 0, 0, 0, 0, 0, 0, 0x08);
    tick(3);
    SERVING();
    /* block upload, after the first sub-block, abort */
    CHECK_EQ(sdo(0xA4, IDX(0x2009), 0, 2, 0, 0, 0)->data[0], 0xC6);
    clear();
    rx(SDO_RX, 0xA3, 0, 0, 0, 0, 0, 0, 0);
    rx(SDO_RX, 0x80, 0, 0, 0, 0, 0, 0, 0x08);
    tick(3);
    SERVING();
    VALUES_KEPT();
}

static void toggles_wrongly(void)
{
    const odg_frame_t *r;
    CHECK_EQ(sdo(0x21, IDX(0x2009), 0, 20, 0, 0, 0)->data[0], 0x60);
    r = sdo(0x10, 'a', 'b', 'c', 'd', 'e', 'f', 'g'); /* toggle 1 where 0 is due */
    CHECK_EQ(abort_of(r), ODG_ABORT_TOGGLE);
    SERVING();
    r = sdo(0x40, IDX(0x2009), 0, 0, 0, 0, 0);
    CHECK_EQ(r->data[0], 0x41);
    CHECK_EQ(sdo(0x60, 0, 0, 0, 0, 0, 0, 0)->data[0] & 0xF0u, 0x00);
    r = sdo(0x60, 0, 0, 0, 0, 0, 0, 0); /* the same toggle twice */
    CHECK_EQ(abort_of(r), ODG_ABORT_TOGGLE);
    tick(2);
    SERVING();
    VALUES_KEPT();
}

static void falls_silent(void)
{
    unsigned long before = n_timeouts;
    uint32_t start;
    CHECK_EQ(sdo(0x21, IDX(0x2009), 0, 20, 0, 0, 0)->data[0], 0x60);
    start = now;
    clear();
    while (n_timeouts == before && now - start < 5u * ODG_NODE_SDO_TIMEOUT_MS) {
        tick(1);
    }
    /* the server's timeout reset it: one abort, within one tick of the timeout */
    CHECK_EQ(n_timeouts, before + 1u);
    CHECK(now - start >= ODG_NODE_SDO_TIMEOUT_MS && now - start <= ODG_NODE_SDO_TIMEOUT_MS + 1u);
    /* a late segment finds no transfer: refused, and the server serves */
    clear();
    rx(SDO_RX, 0x00, 'a', 'b', 'c', 'd', 'e', 'f', 'g');
    CHECK_EQ(abort_of(last_id(SDO_TX)), ODG_ABORT_COMMAND);
    SERVING();
    /* the same for a block upload left waiting for the client */
    CHECK_EQ(sdo(0xA4, IDX(0x2009), 0, 4, 0, 0, 0)->data[0], 0xC6);
    tick(ODG_NODE_SDO_TIMEOUT_MS + 1u);
    CHECK_EQ(n_timeouts, before + 2u);
    SERVING();
    VALUES_KEPT();
}

/* Random frames to the server, 100 per ms for a simulated second: every kind of request and
 * segment, valid or not, some shorter than 8 bytes. */
static void floods(void)
{
    uint32_t ms, i;
    for (ms = 0; ms < 1000u; ms++) {
        for (i = 0; i < 100u; i++) {
            uint8_t d[8];
            uint32_t k;
            for (k = 0; k < 8u; k++) {
                d[k] = (uint8_t)rnd();
            }
            if (rnd() % 4u == 0u) { /* an initiate request to an existing object */
                static const uint16_t objs[] = {0x1000, 0x1017, 0x2005, 0x2009, 0x200E, 0x2103};
                uint16_t o = objs[rnd() % 6u];
                static const uint8_t cmds[] = {0x40, 0x21, 0xA4, 0xC6, 0x2F, 0x60, 0x00, 0xA3, 0xA2};
                d[0] = cmds[rnd() % 9u];
                d[1] = (uint8_t)o;
                d[2] = (uint8_t)(o >> 8);
                d[3] = (uint8_t)(rnd() % 3u);
                if (o == 0x1017u && (d[0] & 0xE0u) == 0x20u) {
                    d[0] = 0x40; /* keep the heartbeat period under test */
                }
            }
            if ((d[0] & 0xE0u) == 0x20u && d[1] == 0x17u && d[2] == 0x10u) {
                d[0] = 0x40;
            }
            clear();
            rx_frame(SDO_RX, d, rnd() % 8u == 0u ? rnd() % 9u : 8u);
        }
        tick(1);
    }
    SERVING();
    reset_node();
    VALUES_KEPT();
}

/* 1 000 frames per simulated second, for a minute, from other nodes: any 11-bit identifier but
 * the NMT and this server's, any length, some remote or extended. Every simulated second the
 * server answers an upload. */
static void foreign_traffic(void)
{
    uint32_t s, ms;
    unsigned long hb_before = n_hb;
    nmt(ODG_NMT_START, NID);
    for (s = 0; s < 60u; s++) {
        for (ms = 0; ms < 1000u; ms++) {
            uint8_t d[8] = {0};
            odg_frame_t f;
            uint32_t id;
            do {
                id = rnd() & 0x7FFu;
            } while (id == 0u || id == SDO_RX);
            memset(&f, 0, sizeof f);
            f.id = id;
            f.len = (uint8_t)(rnd() % 9u);
            f.flags = (uint8_t)(rnd() % 16u == 0u ? rnd() % 4u : 0u);
            d[0] = (uint8_t)rnd();
            d[7] = (uint8_t)rnd();
            memcpy(f.data, d, 8);
            clear();
            odg_node_receive(&node, &f);
            tick(1);
        }
        CHECK_EQ(upload_u32(0x2005, 0), SAVED_U8);
        CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);
    }
    CHECK(n_hb - hb_before >= 599u); /* 60 s at 100 ms */
    SERVING();
    VALUES_KEPT();
}

/* NMT reset (communication, then node) in the middle of a block download and a block upload:
 * the transfer is gone, the rest of its frames are refused, stored values come back. */
static void reset_during_block(void)
{
    static const uint8_t cmds[2] = {ODG_NMT_RESET_COMM, ODG_NMT_RESET_NODE};
    unsigned c;
    for (c = 0; c < 2u; c++) {
        CHECK_EQ(sdo(0xC6, IDX(0x2009), 0, 30, 0, 0, 0)->data[0], 0xA4);
        rx(SDO_RX, 0x01, 'r', 'e', 's', 'e', 't', '!', '!');
        rx(SDO_RX, 0x02, 'r', 'e', 's', 'e', 't', '!', '!');
        clear();
        nmt(cmds[c], NID);
        CHECK_EQ(count_id(0x700u + NID), 1); /* boot-up */
        CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL);
        clear();
        rx(SDO_RX, 0x03, 'r', 'e', 's', 'e', 't', '!', '!');
        rx(SDO_RX, 0x84, 'r', 'e', 's', 0, 0, 0, 0);
        CHECK(count_id(SDO_TX) <= 2u);
        tick(5);
        SERVING();
        VALUES_KEPT();

        CHECK_EQ(sdo(0xA4, IDX(0x2009), 0, 2, 0, 0, 0)->data[0], 0xC6);
        rx(SDO_RX, 0xA3, 0, 0, 0, 0, 0, 0, 0);
        clear();
        nmt(cmds[c], NID);
        CHECK_EQ(count_id(0x700u + NID), 1);
        clear();
        rx(SDO_RX, 0xA2, 2, 2, 0, 0, 0, 0, 0);
        tick(ODG_NODE_SDO_TIMEOUT_MS + 5u);
        CHECK_EQ(count_id(SDO_TX), 1u); /* "unknown command" to the stray ack, nothing else */
        SERVING();
        VALUES_KEPT();
    }
}

/* Both slots of a group damaged: the node boots on defaults and says so with an EMCY 0x5530
 * right after its boot-up frame; the next boot (defaults stored meanwhile) is quiet. */
static void lost_values_emcy(void)
{
    const odg_group_t *g = &alltypes.groups[ALLTYPES_GROUP_COMM];
    const odg_frame_t *e;
    /* the first image byte of slots A and B ("ODG2" images with a layout, else "ODG1") */
    uint32_t a = g->nv_addr + (g->n_layout != 0u ? ODG_PERSIST_HEADER2_SIZE : ODG_PERSIST_HEADER_SIZE);
    uint32_t b = a + (g->n_layout != 0u ? g->region / 2u : odg_persist_slot_size(g->size));
    hb_watch = 0; /* the period goes back to its default */
    nv_mem[a] ^= 0x01u;
    nv_mem[b] ^= 0x10u;
    clear();
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(n_sent, 2);
    CHECK_EQ(sent[0].id, 0x700u + NID);
    e = &sent[1];
    CHECK_EQ(e->id, 0x80u + NID);
    CHECK_EQ(e->len, 8);
    CHECK_EQ(e->data[0] | e->data[1] << 8, ODG_NODE_EMCY_STORAGE);
    CHECK_EQ(e->data[2] & 0x01u, 0x01);
    CHECK_EQ(e->data[3], 1u << ODG_BOOT_LOADED | 1u << ODG_BOOT_DAMAGED);
    CHECK_EQ(upload_u32(0x1001, 0) & 0x01u, 0x01); /* error register */
    CHECK_EQ(upload_u32(0x1017, 0), 1000);           /* the comm group's defaults ... */
    CHECK_EQ(upload_u32(0x2015, 0), SAVED_U32);      /* ... the app group kept its values */
    clear();
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(upload_u32(0x1001, 0), 0);
    /* also at power-on, from odg_node_init (slot 1 still damaged: spoil the defaults in slot 0) */
    nv_mem[a] ^= 0x01u;
    {
        odg_node_config_t cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.dict = &alltypes;
        cfg.node_id = NID;
        cfg.nv = &nv_ram;
        cfg.send = fake_send;
        clear();
        CHECK_EQ(odg_node_init(&node, &cfg), ODG_OK);
        CHECK_EQ(n_sent, 2);
        CHECK_EQ(sent[1].id, 0x80u + NID);
        CHECK_EQ(sent[1].data[0] | sent[1].data[1] << 8, ODG_NODE_EMCY_STORAGE);
    }
    /* without an NV driver there is nothing to lose: no EMCY */
    start_node(&alltypes, NULL);
}

int main(void)
{
    setup();
    aborts_mid_transfer();
    toggles_wrongly();
    falls_silent();
    floods();
    foreign_traffic();
    reset_during_block();
    printf("%lu heartbeats checked over %lu simulated ms\n", n_hb, (unsigned long)now);
    /* a period is restarted (not lost) by each of the 5 boot-ups since the watch began */
    CHECK(n_hb + 5u >= (now - watch_start) / HB_PERIOD && n_hb > 600u);
    lost_values_emcy();
    return done();
}
