/*
 * test_node_lss.c - the LSS slave (CiA 305) over the fake bus, against tests/node/lss-node.eds
 * (identity 0x000004D2 / 0x00010203 / 0x00020001 / 0x5EA1C0DE) with a RAM NV memory, built
 * with -DODG_NODE_LSS=1: a node started without a node-id is silent until an LSS master finds
 * it by fastscan (a wrong identity gets no answer), gives it node-id 10 and stores it; it
 * then boots as node 10, and again after a power cycle. Every other command, with right and
 * wrong arguments and identities. The stored configuration (a persistence record, runtime/
 * README.md "Records of other layers"): its NV format, a power cut at every byte of a store,
 * damaged slots, sequence numbers that wrap, a driver that fails or drops writes.
 */
#include <stdio.h>
#include <string.h>

#define NID 10u
#include "fake.h"
#include "lss_node.h"

#define M 0x7E5u /* master -> slave */
#define S 0x7E4u /* slave -> master */
#define VENDOR 0x000004D2u
#define PRODUCT 0x00010203u
#define REVISION 0x00020001u
#define SERIAL 0x5EA1C0DEu

static const uint32_t ident[4] = {VENDOR, PRODUCT, REVISION, SERIAL};
static int bt_calls, bt_index, bt_delay, bt_activate, bt_refuse;

static int on_bit_timing(void *ctx, uint8_t index, uint16_t delay_ms, int activate)
{
    (void)ctx;
    bt_calls++;
    bt_index = index;
    bt_delay = delay_ms;
    bt_activate = activate;
    return bt_refuse;
}

static odg_abort_t power_on(uint8_t id, const odg_nv_driver_t *nv)
{
    odg_node_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.dict = &lss_node;
    cfg.node_id = id;
    cfg.nv = nv;
    cfg.send = fake_send;
    cfg.on_bit_timing = on_bit_timing;
    clear();
    return odg_node_init(&node, &cfg);
}

/* One LSS request; returns the slave's answer or NULL when it sent none. */
static const odg_frame_t *lss(uint8_t cs, uint32_t v, uint8_t b5, uint8_t b6, uint8_t b7)
{
    clear();
    rx(M, cs, (uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24), b5, b6, b7);
    CHECK(count_id(S) <= 1u);
    return count_id(S) == 1u ? last_id(S) : NULL;
}

static int answered(const odg_frame_t *r, uint8_t cs)
{
    /* every answer has 8 bytes, the last three reserved: 0 */
    return r != NULL && r->data[0] == cs && r->len == 8u && (r->data[5] | r->data[6] | r->data[7]) == 0u;
}

/* The configure answers: cs, error code. -1 when there was none. */
static int configure(uint8_t cs, uint8_t a, uint8_t b)
{
    const odg_frame_t *r = lss(cs, (uint32_t)a | (uint32_t)b << 8, 0, 0, 0);
    return r != NULL && r->data[0] == cs ? r->data[1] : -1;
}

/* Inquire node-id: the answer, -1 when none came. */
static int inquire_id(void)
{
    const odg_frame_t *r = lss(0x5E, 0, 0, 0, 0);
    return answered(r, 0x5E) ? r->data[1] : -1;
}

/* Fastscan as a master runs it (python canopen's LssMaster.fast_scan): 1 when a slave was
 * found and its identity is in `found`. */
static int fastscan(uint32_t found[4])
{
    int sub, bit;
    if (!answered(lss(0x51, 0, 0x80, 0, 0), 0x4F)) {
        return 0;
    }
    for (sub = 0; sub < 4; sub++) {
        found[sub] = 0;
        for (bit = 31; bit >= 0; bit--) {
            if (!answered(lss(0x51, found[sub], (uint8_t)bit, (uint8_t)sub, (uint8_t)sub), 0x4F)) {
                found[sub] |= 1u << bit;
            }
        }
        if (!answered(lss(0x51, found[sub], 0, (uint8_t)sub, (uint8_t)((sub + 1) & 3)), 0x4F)) {
            return 0;
        }
    }
    return 1;
}

static void unconfigured_is_silent(void)
{
    CHECK_EQ(power_on(ODG_LSS_UNCONFIGURED, &nv_ram), 0);
    CHECK_EQ(n_sent, 0); /* no boot-up */
    CHECK_EQ(odg_node_state(&node), ODG_NMT_INITIALISING);
    rx(0, ODG_NMT_START, 0);
    rx(0x6FF, 0x40, 0x18, 0x10, 1, 0, 0, 0, 0);
    rx(0x600u + NID, 0x40, 0x18, 0x10, 1, 0, 0, 0, 0);
    rx(0x600u + NID, 0x2B, 0x17, 0x10, 0, 10, 0, 0, 0);
    run_ms(500);
    CHECK_EQ(n_sent, 0); /* no SDO answer, no heartbeat */
    CHECK_EQ(odg_node_state(&node), ODG_NMT_INITIALISING);
    CHECK_EQ(odg_node_emcy(&node, 0x1000, 1, NULL, 0), ODG_ABORT_DATA_STATE);
    CHECK_EQ(n_sent, 0);
    rx(0, ODG_NMT_RESET_NODE, 0); /* a reset: still unconfigured, still silent */
    CHECK_EQ(n_sent, 0);
    /* configuration commands need configuration mode */
    CHECK(lss(0x5E, 0, 0, 0, 0) == NULL);
    CHECK_EQ(configure(0x11, 10, 0), -1);
    CHECK(answered(lss(0x4C, 0, 0, 0, 0), 0x50)); /* identify non-configured remote slave */
}

static void fastscan_finds_the_identity(void)
{
    uint32_t found[4];
    int sub;
    /* a wrong identity gets no answer, part by part */
    for (sub = 0; sub < 4; sub++) {
        CHECK(answered(lss(0x51, 0, 0x80, 0, 0), 0x4F));
        for (int k = 0; k < sub; k++) {
            CHECK(answered(lss(0x51, ident[k], 0, (uint8_t)k, (uint8_t)(k + 1)), 0x4F));
        }
        CHECK(lss(0x51, ident[sub] ^ 0x100u, 0, (uint8_t)sub, (uint8_t)((sub + 1) & 3)) == NULL);
        CHECK(lss(0x51, ident[sub] ^ 0x80000000u, 31, (uint8_t)sub, 0) == NULL);
        CHECK(answered(lss(0x51, ident[sub] ^ 0x7FFFFFFFu, 31, (uint8_t)sub, 0), 0x4F));
        CHECK(lss(0x51, ident[sub], 0, (uint8_t)((sub + 1) & 3), 0) == NULL); /* not its part */
        CHECK(lss(0x51, ident[sub], 0, (uint8_t)sub, 4) == NULL); /* LSSNext beyond the serial */
        CHECK(lss(0x51, ident[sub], 32, (uint8_t)sub, 0) == NULL); /* bitChecked beyond 31 */
        CHECK(answered(lss(0x51, ident[sub] ^ 0x7Fu, 7, (uint8_t)sub, (uint8_t)sub), 0x4F)); /* bits 7..31 */
    }
    CHECK(lss(0x51, 0, 0, 4, 0) == NULL); /* LSSSub beyond the serial */
    CHECK(lss(0x5E, 0, 0, 0, 0) == NULL); /* not selected: still waiting */
    CHECK(fastscan(found));
    for (sub = 0; sub < 4; sub++) {
        CHECK_EQ_AT(found[sub], ident[sub], sub);
    }
    /* selected: configuration mode */
    CHECK_EQ(inquire_id(), ODG_LSS_UNCONFIGURED);
}

static void configure_and_store(void)
{
    const odg_frame_t *r;
    unsigned k;
    for (k = 0; k < 4u; k++) { /* inquire identity */
        r = lss((uint8_t)(0x5A + k), 0, 0, 0, 0);
        CHECK(answered(r, (uint8_t)(0x5A + k)));
        CHECK_EQ_AT(r != NULL ? le32(r->data + 1) : 0u, ident[k], k);
    }
    CHECK_EQ(configure(0x11, 0, 0), 1);   /* node-id out of range */
    CHECK_EQ(configure(0x11, 128, 0), 1);
    CHECK_EQ(configure(0x11, NID, 0), 0);
    CHECK_EQ(inquire_id(), ODG_LSS_UNCONFIGURED); /* the active one */
    CHECK_EQ(configure(0x13, 1, 4), 1); /* table 1: not the CiA table */
    CHECK_EQ(configure(0x13, 0, 10), 1);
    bt_refuse = 1;
    CHECK_EQ(configure(0x13, 0, 0), 1); /* the application refuses 1000 kbit/s */
    bt_refuse = 0;
    bt_calls = 0;
    CHECK_EQ(configure(0x13, 0, 4), 0); /* 125 kbit/s */
    CHECK_EQ(bt_calls, 1);
    CHECK_EQ(bt_index, 4);
    CHECK_EQ(bt_activate, 0);
    CHECK(lss(0x15, 250, 0, 0, 0) == NULL); /* activate: no answer, the application hears */
    CHECK_EQ(bt_calls, 2);
    CHECK_EQ(bt_activate, 1);
    CHECK_EQ(bt_delay, 250);
    CHECK_EQ(configure(0x17, 0, 0), 0); /* store */
    CHECK_EQ(n_sent, 1);
    /* back to waiting: the node boots as node 10 */
    CHECK(lss(0x04, 0, 0, 0, 0) == NULL);
    CHECK_EQ(count_id(0x700u + NID), 1);
    CHECK_EQ(last_id(0x700u + NID)->data[0], 0);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL);
    CHECK_EQ(upload_u32(0x1018, 4), SERIAL);
    CHECK_EQ(upload_u32(0x1014, 0), 0x80u + NID); /* $NODEID values of the new node-id */
    CHECK(lss(0x4C, 0, 0, 0, 0) == NULL); /* configured now */
    CHECK(lss(0x51, 0, 0x80, 0, 0) == NULL); /* fastscan is for non-configured slaves */
}

static void survives_power_cycle(void)
{
    /* store a comm value too, so both kinds of stored data come back together */
    CHECK_EQ(download_u32(0x1017, 0, 100, 2), 0);
    CHECK_EQ(download(0x1010, 1, "save", 4), 0);
    CHECK_EQ(power_on(ODG_LSS_UNCONFIGURED, &nv_ram), 0);
    CHECK_EQ(count_id(0x700u + NID), 1); /* boots as node 10 by itself */
    CHECK_EQ(upload_u32(0x1017, 0), 100);
    clear();
    run_ms(100);
    CHECK_EQ(count_id(0x700u + NID), 1); /* heartbeat */
    /* a node-id given by the application does not beat the stored one */
    CHECK_EQ(power_on(7, &nv_ram), 0);
    CHECK_EQ(count_id(0x700u + NID), 1);
    CHECK_EQ(count_id(0x707u), 0);
}

/* Identify remote slave with the ranges given (0x46 .. 0x4B): only the last request may be
 * answered; its answer, or NULL. */
static const odg_frame_t *identify(uint32_t vendor, uint32_t product, uint32_t rev_lo, uint32_t rev_hi,
                                   uint32_t serial_lo, uint32_t serial_hi)
{
    CHECK(lss(0x46, vendor, 0, 0, 0) == NULL);
    CHECK(lss(0x47, product, 0, 0, 0) == NULL);
    CHECK(lss(0x48, rev_lo, 0, 0, 0) == NULL);
    CHECK(lss(0x49, rev_hi, 0, 0, 0) == NULL);
    CHECK(lss(0x4A, serial_lo, 0, 0, 0) == NULL);
    return lss(0x4B, serial_hi, 0, 0, 0);
}

static void selective_and_identify(void)
{
    const odg_frame_t *r;
    /* switch state selective: a wrong part anywhere gets no answer */
    lss(0x40, VENDOR, 0, 0, 0);
    lss(0x41, PRODUCT, 0, 0, 0);
    lss(0x42, REVISION, 0, 0, 0);
    CHECK(lss(0x43, SERIAL + 1u, 0, 0, 0) == NULL);
    lss(0x40, VENDOR, 0, 0, 0);
    lss(0x41, PRODUCT + 1u, 0, 0, 0);
    lss(0x42, REVISION, 0, 0, 0);
    CHECK(lss(0x43, SERIAL, 0, 0, 0) == NULL);
    lss(0x41, PRODUCT, 0, 0, 0); /* out of order */
    lss(0x42, REVISION, 0, 0, 0);
    CHECK(lss(0x43, SERIAL, 0, 0, 0) == NULL);
    CHECK(lss(0x5E, 0, 0, 0, 0) == NULL);
    lss(0x40, VENDOR, 0, 0, 0);
    lss(0x41, PRODUCT, 0, 0, 0);
    lss(0x42, REVISION, 0, 0, 0);
    CHECK(answered(lss(0x43, SERIAL, 0, 0, 0), 0x44));
    r = lss(0x5E, 0, 0, 0, 0);
    CHECK(answered(r, 0x5E));
    CHECK_EQ(r != NULL ? r->data[1] : 0u, NID);
    /* a new node-id takes effect at the next reset communication, operational or not */
    CHECK_EQ(configure(0x11, 20, 0), 0);
    CHECK(lss(0x04, 0, 0, 0, 0) == NULL);
    CHECK_EQ(n_sent, 0); /* a configured node does not boot on "waiting" */
    nmt(ODG_NMT_START, NID);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);
    clear();
    nmt(ODG_NMT_RESET_COMM, NID);
    CHECK_EQ(count_id(0x700u + 20u), 1);
    CHECK_EQ(count_id(0x700u + NID), 0);
    nmt(ODG_NMT_START, NID);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL); /* 10 is not its node-id now */
    nmt(ODG_NMT_START, 20);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);
    /* identify remote slave: vendor, product, revision and serial ranges */
    CHECK(answered(identify(VENDOR, PRODUCT, REVISION - 1u, REVISION, 0, 0xFFFFFFFFu), 0x4F));
    CHECK(identify(VENDOR, PRODUCT, REVISION + 1u, 0xFFFFFFFFu, 0, 0xFFFFFFFFu) == NULL); /* revision below */
    CHECK(identify(VENDOR + 1u, PRODUCT, 0, 0xFFFFFFFFu, 0, 0xFFFFFFFFu) == NULL);          /* another vendor */
    CHECK(identify(VENDOR, PRODUCT, 0, 0xFFFFFFFFu, SERIAL + 1u, 0xFFFFFFFFu) == NULL);    /* serial below */
    CHECK(identify(VENDOR, PRODUCT - 1u, 0, 0xFFFFFFFFu, 0, 0xFFFFFFFFu) == NULL);         /* another product */
    CHECK(identify(VENDOR, PRODUCT, 0, REVISION - 1u, 0, 0xFFFFFFFFu) == NULL);            /* revision above */
    CHECK(identify(VENDOR, PRODUCT, 0, 0xFFFFFFFFu, 0, SERIAL - 1u) == NULL);              /* serial above */
    /* ranges just around the identity; ranges of one value (the bounds count as inside) */
    CHECK(answered(identify(VENDOR, PRODUCT, REVISION - 1u, REVISION + 1u, SERIAL - 1u, SERIAL + 1u), 0x4F));
    CHECK(answered(identify(VENDOR, PRODUCT, REVISION, REVISION, SERIAL, SERIAL), 0x4F));
    CHECK(lss(0x4A, SERIAL, 0, 0, 0) == NULL); /* nor a request repeated after it */
    /* not stored: a power cycle brings back node 10 */
    CHECK(lss(0x04, 1, 0, 0, 0) == NULL); /* switch state global: configuration */
    CHECK_EQ(inquire_id(), 20);
    CHECK_EQ(power_on(ODG_LSS_UNCONFIGURED, &nv_ram), 0);
    CHECK_EQ(count_id(0x700u + NID), 1);
}

static void back_to_unconfigured(void)
{
    CHECK(lss(0x04, 1, 0, 0, 0) == NULL);
    CHECK_EQ(configure(0x11, ODG_LSS_UNCONFIGURED, 0), 0);
    CHECK_EQ(configure(0x17, 0, 0), 0);
    CHECK(lss(0x04, 0, 0, 0, 0) == NULL);
    clear();
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(n_sent, 0);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_INITIALISING);
    CHECK(answered(lss(0x4C, 0, 0, 0, 0), 0x50));
    CHECK_EQ(power_on(ODG_LSS_UNCONFIGURED, &nv_ram), 0);
    CHECK_EQ(n_sent, 0);
    /* without NV: store configuration answers "not supported", node-id given works */
    CHECK_EQ(power_on(NID, NULL), 0);
    CHECK_EQ(count_id(0x700u + NID), 1);
    CHECK(lss(0x04, 1, 0, 0, 0) == NULL);
    CHECK_EQ(configure(0x17, 0, 0), 1);
    CHECK_EQ(power_on(0, NULL), ODG_ABORT_INCOMPATIBLE);
    CHECK_EQ(power_on(128, NULL), ODG_ABORT_INCOMPATIBLE);
}

/* ---- the stored configuration in NV ------------------------------------------------------ */

#define TAG 0x3153534Cu /* "LSS1" */
#define SLOT ODG_PERSIST_RECORD_SLOT
#define NEVER (-1L)

static long cut_after = NEVER; /* steps (erases, bytes written) the NV takes before the power fails */
static int half;               /* the byte being written at the cut is left half programmed */
static int drop_writes;        /* writes answer done but change nothing */

/* A NOR flash over nv_mem: writes clear bits; the power fails after cut_after steps. */
static int cut_write(void *ctx, uint32_t addr, const void *buf, uint32_t len)
{
    const uint8_t *b = (const uint8_t *)buf;
    uint32_t i;
    (void)ctx;
    for (i = 0; i < len && !drop_writes; i++) {
        if (cut_after == 0) {
            if (half) {
                nv_mem[addr + i] &= (uint8_t)(b[i] | 0xF0u); /* the high bits not cleared yet */
            }
            return -1;
        }
        cut_after -= cut_after > 0;
        nv_mem[addr + i] &= b[i];
    }
    return 0;
}

static int cut_erase(void *ctx, uint32_t addr, uint32_t len)
{
    (void)ctx;
    if (cut_after == 0) {
        memset(nv_mem + addr, 0xFF, len / 2u); /* an erase cut short */
        return -1;
    }
    cut_after -= cut_after > 0;
    memset(nv_mem + addr, 0xFF, len);
    return 0;
}

static int dead_read(void *ctx, uint32_t addr, void *buf, uint32_t len)
{
    (void)ctx, (void)addr, (void)buf, (void)len;
    return -1;
}

static const odg_nv_driver_t nv_cut = {nv_read, cut_write, cut_erase, NULL};
static const odg_nv_driver_t nv_dead = {dead_read, nv_write, nv_erase, NULL};

/* NV address of the record: after the groups, aligned, its two slots end the node's NV. */
static uint32_t rec_at(void)
{
    return odg_lss_nv_size(&lss_node) - 2u * SLOT;
}

/* The value the record holds now: -1 when none loads. */
static long long stored(void)
{
    uint32_t v = 0xDEADBEEFu;
    int r = odg_persist_load_record(&nv_ram, rec_at(), TAG, &v);
    return r == 1 ? (long long)v : (r == 0 && v == 0xDEADBEEFu ? -1 : -2);
}

static void put_le32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

/* Slot k written as runtime/README.md documents it: tag, sequence, value, CRC-32 of 0..11. */
static void put_slot(int k, uint32_t seq, uint32_t value)
{
    uint8_t *p = nv_mem + rec_at() + (k ? SLOT : 0u);
    memset(p, 0xFF, SLOT);
    put_le32(p, TAG);
    put_le32(p + 4, seq);
    put_le32(p + 8, value);
    put_le32(p + 12, odg_crc32(0, p, 12u));
}

static void record_format(void)
{
    uint32_t at = rec_at();
    CHECK_EQ(at % ODG_PERSIST_ALIGN, 0);
    CHECK(at >= odg_persist_nv_size(&lss_node));
    CHECK_EQ(SLOT, 16u); /* ALIGN 8 */
    memset(nv_mem + at, 0xFF, 2u * SLOT);
    CHECK_EQ(stored(), -1); /* erased: none */
    CHECK_EQ(odg_persist_store_record(&nv_ram, at, TAG, 0x0412u), ODG_OK);
    CHECK(memcmp(nv_mem + at, "LSS1", 4) == 0); /* into A: tag, sequence, value, CRC */
    CHECK_EQ(le32(nv_mem + at + 8), 0x0412u);
    CHECK_EQ(le32(nv_mem + at + 12), odg_crc32(0, nv_mem + at, 12u));
    CHECK_EQ(nv_mem[at + SLOT], 0xFF); /* B untouched */
    CHECK_EQ(odg_persist_store_record(&nv_ram, at, TAG, 0x0413u), ODG_OK);
    CHECK(memcmp(nv_mem + at + SLOT, "LSS1", 4) == 0); /* into B, the next sequence number */
    CHECK_EQ(le32(nv_mem + at + SLOT + 4), le32(nv_mem + at + 4) + 1u);
    CHECK_EQ(le32(nv_mem + at + 8), 0x0412u); /* A keeps the previous one */
    CHECK_EQ(stored(), 0x0413u);
    /* a slot written by hand as documented is read; another tag is not */
    put_slot(0, 7, 0x0A05u);
    put_slot(1, 6, 0x0B05u);
    CHECK_EQ(stored(), 0x0A05u);
    {
        uint32_t v = 0;
        CHECK_EQ(odg_persist_load_record(&nv_ram, at, 0x3253534Cu, &v), 0); /* "LSS2" */
        CHECK_EQ(odg_persist_load_record(NULL, at, TAG, &v), -1);
        CHECK_EQ(odg_persist_load_record(&nv_dead, at, TAG, &v), -1);
        CHECK_EQ(v, 0);
    }
    /* the node boots with it: node-id 5, bit timing 10 (not checked by the node) */
    CHECK_EQ(power_on(ODG_LSS_UNCONFIGURED, &nv_ram), 0);
    CHECK_EQ(count_id(0x705u), 1);
    /* a driver that cannot read: the groups report it, the node runs with the node-id given */
    CHECK_EQ(power_on(7, &nv_dead), ODG_ABORT_HARDWARE);
    CHECK_EQ(count_id(0x707u), 1);
    CHECK_EQ(odg_persist_store_record(&nv_dead, at, TAG, 1), ODG_ABORT_HARDWARE);
    CHECK_EQ(odg_persist_store_record(NULL, at, TAG, 1), ODG_ABORT_DATA_STORE);
}

/* Sequence numbers compare by serial arithmetic: the newest wins across the wrap, and stores
 * go on across it. */
static void sequence_wraps(void)
{
    static const uint32_t pairs[][3] = { /* sequence in A, in B, the newest */
        {0xFFFFFFFFu, 0, 1}, {0, 0xFFFFFFFFu, 0}, {0x7FFFFFFFu, 0x80000000u, 1}, {5, 4, 0}, {0xFFFFFFF0u, 3, 1}};
    uint32_t at = rec_at(), v;
    unsigned i;
    for (i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
        put_slot(0, pairs[i][0], 0xA0u + i);
        put_slot(1, pairs[i][1], 0xB0u + i);
        CHECK_EQ_AT(stored(), (pairs[i][2] ? 0xB0u : 0xA0u) + i, i);
    }
    put_slot(0, 0xFFFFFFFDu, 1);
    memset(nv_mem + at + SLOT, 0xFF, SLOT);
    for (v = 2; v < 8; v++) { /* sequences 0xFFFFFFFE, 0xFFFFFFFF, 0, 1, 2, 3 alternately in B and A */
        CHECK_EQ_AT(odg_persist_store_record(&nv_ram, at, TAG, v), ODG_OK, v);
        CHECK_EQ_AT(le32(nv_mem + at + ((v & 1u) ? 0u : SLOT) + 4), 0xFFFFFFFCu + v, v);
        CHECK_EQ_AT(stored(), v, v);
    }
}

/* A bit flipped anywhere in the newest slot: the one before loads; in both: none, and the node
 * takes the node-id it is given. */
static void damaged_slots(void)
{
    uint32_t at = rec_at();
    unsigned byte;
    for (byte = 0; byte < 16u; byte++) {
        put_slot(0, 1, 0x0Bu);
        put_slot(1, 2, 0x0Cu);
        nv_mem[at + SLOT + byte] ^= (uint8_t)(1u << (byte & 7u));
        CHECK_EQ_AT(stored(), 0x0Bu, byte);
        nv_mem[at + byte] ^= 0x80u;
        CHECK_EQ_AT(stored(), -1, byte);
    }
    CHECK_EQ(power_on(7, &nv_ram), 0);
    CHECK_EQ(count_id(0x707u), 1);
    put_slot(0, 1, 0x0Bu);
    put_slot(1, 2, 0x0Cu);
    nv_mem[at + SLOT + 9] ^= 1u; /* the newest: a bit of its bit timing flipped */
    CHECK_EQ(power_on(7, &nv_ram), 0);
    CHECK_EQ(count_id(0x70Bu), 1);
    /* a driver that drops writes: the read-back sees it */
    drop_writes = 1;
    CHECK_EQ(odg_persist_store_record(&nv_cut, at, TAG, 0x0Du), ODG_ABORT_HARDWARE);
    drop_writes = 0;
    CHECK_EQ(stored(), 0x0Bu);
}

/* The power fails at every step of a store (the erase, each byte; the byte at the cut whole or
 * half programmed, the erase half done), into slot A and into slot B: afterwards the previous
 * value loads, or the new one once its last tag byte landed, and the next store works. */
static void power_cut_anywhere(void)
{
    static uint8_t snap[sizeof nv_mem];
    uint32_t at = rec_at();
    long k;
    int into_b, h;
    for (into_b = 0; into_b < 2; into_b++) {
        put_slot(0, 0xFFFFFFFFu, 0x11u);
        if (into_b) {
            memset(nv_mem + at + SLOT, 0x00, SLOT); /* garbage in B */
        } else {
            put_slot(1, 0, 0x12u);
        }
        memcpy(snap, nv_mem, sizeof nv_mem);
        for (h = 0; h < 2; h++) {
            for (k = 0; k <= 17; k++) { /* 1 erase + 16 bytes */
                memcpy(nv_mem, snap, sizeof nv_mem);
                cut_after = k;
                half = h;
                CHECK_EQ_AT(odg_persist_store_record(&nv_cut, at, TAG, 0x2Au),
                            k == 17 ? ODG_OK : ODG_ABORT_HARDWARE, k);
                cut_after = NEVER;
                if (k <= 12) { /* the tag is written last: cut before it, it is still erased */
                    CHECK_EQ_AT(le32(nv_mem + at + (into_b ? SLOT : 0u)), 0xFFFFFFFFu, k);
                }
                CHECK_EQ_AT(stored(), k == 17 ? 0x2Au : (into_b ? 0x11u : 0x12u), k);
                CHECK_EQ_AT(odg_persist_store_record(&nv_cut, at, TAG, 0x2Bu), ODG_OK, k);
                CHECK_EQ_AT(stored(), 0x2Bu, k);
            }
        }
    }
    /* a master's store cut short: the node answers "failed" and boots with the node-id before */
    put_slot(0, 1, 0x0Bu);
    memset(nv_mem + at + SLOT, 0xFF, SLOT);
    CHECK_EQ(power_on(ODG_LSS_UNCONFIGURED, &nv_cut), 0);
    CHECK_EQ(count_id(0x70Bu), 1);
    CHECK(lss(0x04, 1, 0, 0, 0) == NULL);
    CHECK_EQ(configure(0x11, 30, 0), 0);
    cut_after = 9;
    CHECK_EQ(configure(0x17, 0, 0), 2);
    cut_after = NEVER;
    CHECK_EQ(power_on(ODG_LSS_UNCONFIGURED, &nv_ram), 0);
    CHECK_EQ(count_id(0x70Bu), 1);
    CHECK(lss(0x04, 1, 0, 0, 0) == NULL);
    CHECK_EQ(configure(0x11, 30, 0), 0);
    CHECK_EQ(configure(0x17, 0, 0), 0);
    CHECK_EQ(power_on(ODG_LSS_UNCONFIGURED, &nv_ram), 0);
    CHECK_EQ(count_id(0x700u + 30u), 1);
}

int main(void)
{
    memset(nv_mem, 0xFF, sizeof nv_mem);
    unconfigured_is_silent();
    fastscan_finds_the_identity();
    configure_and_store();
    survives_power_cycle();
    selective_and_identify();
    back_to_unconfigured();
    record_format();
    sequence_wraps();
    damaged_slots();
    power_cut_anywhere();
    return done();
}
