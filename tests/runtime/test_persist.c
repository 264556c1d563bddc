/*
 * test_persist.c - odg_persist.c and the 0x1010/0x1011 commands against the dictionary td,
 * with a RAM NV driver that models NOR flash (erase sets 0xFF, a write can only clear bits)
 * and injects faults: the power fails after k programmed bytes (optionally leaving the byte
 * being programmed half done), reads fail on the n-th call, bits flip. Then odg_nv_file.c on a
 * real file in the directory given as argv[1].
 * Prints "N passed, M failed"; exit status 0 only when M is 0.
 */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "odg.h"
#include "odg_nv_file.h"
#include "td.h"

#define NODE 5u
#define NV_SIZE 512u
#define HDR ODG_PERSIST_HEADER_SIZE
#define SLOT_COMM ODG_PERSIST_SLOT_SIZE(sizeof(td_persist_comm_t))
#define SLOT_APP ODG_PERSIST_SLOT_SIZE(sizeof(td_persist_app_t))

/* ---- the fault-injecting NV driver ----------------------------------------------------- */

static struct {
    uint8_t mem[NV_SIZE];
    long budget;       /* bytes that may still be programmed or erased; -1: no limit */
    int dead;          /* the power failed: every call fails until the next "power on" */
    int torn;          /* the byte in progress when the power fails is left half done */
    int erase_reverse; /* erase from the last byte down */
    long fail_read_at; /* the n-th read call fails (1-based); 0: none */
    int corrupt_read;  /* that read "succeeds" with a flipped bit instead of failing */
    long reads;
    long bytes; /* bytes programmed or erased */
    long calls; /* write and erase calls */
    void (*during_write)(uint32_t addr, uint32_t len);
} nvm;

static uint32_t rng = 0x12345678u;

static uint32_t rnd(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

static int spend(void)
{
    if (nvm.dead) {
        return 0;
    }
    if (nvm.budget == 0) {
        nvm.dead = 1;
        return 0;
    }
    if (nvm.budget > 0) {
        nvm.budget--;
    }
    nvm.bytes++;
    return 1;
}

static int nv_read(void *ctx, uint32_t addr, void *buf, uint32_t len)
{
    (void)ctx;
    if (nvm.dead || addr > NV_SIZE || len > NV_SIZE - addr) {
        return -1;
    }
    memcpy(buf, nvm.mem + addr, len);
    if (++nvm.reads == nvm.fail_read_at) {
        if (nvm.corrupt_read && len > 0u) {
            ((uint8_t *)buf)[rnd() % len] ^= (uint8_t)(1u << (rnd() & 7u));
            return 0;
        }
        memset(buf, 0x5A, len); /* a failed read may leave anything in the buffer */
        return -1;
    }
    return 0;
}

static int nv_write(void *ctx, uint32_t addr, const void *buf, uint32_t len)
{
    const uint8_t *b = (const uint8_t *)buf;
    uint32_t i;
    (void)ctx;
    if (nvm.dead || addr > NV_SIZE || len > NV_SIZE - addr) {
        return -1;
    }
    nvm.calls++;
    if (nvm.during_write) {
        nvm.during_write(addr, len);
    }
    for (i = 0; i < len; i++) {
        if (!spend()) {
            if (nvm.torn) {
                nvm.mem[addr + i] &= (uint8_t)(b[i] | rnd()); /* some bits not yet cleared */
            }
            return -1;
        }
        nvm.mem[addr + i] &= b[i]; /* NOR flash: programming clears bits only */
    }
    return 0;
}

static int nv_erase(void *ctx, uint32_t addr, uint32_t len)
{
    uint32_t i;
    (void)ctx;
    if (nvm.dead || addr > NV_SIZE || len > NV_SIZE - addr) {
        return -1;
    }
    nvm.calls++;
    for (i = 0; i < len; i++) {
        uint32_t a = addr + (nvm.erase_reverse ? len - 1u - i : i);
        if (!spend()) {
            if (nvm.torn) {
                nvm.mem[a] |= (uint8_t)rnd(); /* some bits not yet set */
            }
            return -1;
        }
        nvm.mem[a] = 0xFF;
    }
    return 0;
}

static const odg_nv_driver_t drv = {nv_read, nv_write, nv_erase, NULL};

static void power_on(void)
{
    nvm.budget = -1;
    nvm.dead = 0;
    nvm.fail_read_at = 0;
    nvm.corrupt_read = 0;
    nvm.during_write = NULL;
}

static void nv_blank(void)
{
    memset(nvm.mem, 0xFF, sizeof nvm.mem);
    power_on();
}

/* ---- an independent reader and writer of the documented slot format ---------------------- */

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

/* Bitwise CRC-32 (IEEE 802.3): a second implementation to check odg_crc32 and the slots. */
static uint32_t crc_ref(uint32_t crc, const uint8_t *p, uint32_t n)
{
    uint32_t i;
    int k;
    crc = ~crc;
    for (i = 0; i < n; i++) {
        crc ^= p[i];
        for (k = 0; k < 8; k++) {
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
        }
    }
    return ~crc;
}

typedef struct {
    int valid;
    uint32_t seq, sig, len;
} slot_t;

static slot_t slot_at(uint32_t addr, uint32_t max)
{
    slot_t s;
    const uint8_t *h = nvm.mem + addr;
    s.seq = get32(h + 4);
    s.sig = get32(h + 8);
    s.len = get32(h + 12);
    s.valid = memcmp(h, "ODG1", 4) == 0 && s.len <= max &&
              crc_ref(crc_ref(0, h, 16), h + HDR, s.len) == get32(h + 16);
    return s;
}

static uint32_t addr_of(uint8_t g, int k)
{
    return td.groups[g].nv_addr + (k ? ODG_PERSIST_SLOT_SIZE(td.groups[g].size) : 0u);
}

static slot_t slot_of(uint8_t g, int k)
{
    return slot_at(addr_of(g, k), td.groups[g].size);
}

static void put_slot(uint8_t g, int k, uint32_t seq, uint32_t sig, const void *img, uint32_t len)
{
    uint8_t *h = nvm.mem + addr_of(g, k);
    memset(h, 0xFF, ODG_PERSIST_SLOT_SIZE(td.groups[g].size));
    memcpy(h, "ODG1", 4);
    put32(h + 4, seq);
    put32(h + 8, sig);
    put32(h + 12, len);
    memcpy(h + HDR, img, len);
    put32(h + 16, crc_ref(crc_ref(0, h, 16), h + HDR, len));
}

/* The hook td's slot table names (0x2300sub3); not exercised here. */
odg_abort_t td_notice(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                      void *ctx)
{
    (void)ref;
    (void)kind;
    (void)data;
    (void)len;
    (void)ctx;
    return ODG_OK;
}

/* ---- values -------------------------------------------------------------------------------- */

static odg_boot_status_t bs[2];
static odg_persist_t persist;

/* odg_init, then the persistence layer with driver `nv`. */
static odg_abort_t start(uint8_t node, const odg_nv_driver_t *nv, odg_boot_status_t *boot)
{
    odg_abort_t ac = odg_init(&td, node);
    return ac != ODG_OK ? ac : odg_persist_init(&persist, &td, nv, boot);
}

static odg_abort_t reboot(uint8_t node)
{
    power_on();
    memset(&td_persist_comm, 0xA5, sizeof td_persist_comm);
    memset(&td_persist_app, 0xA5, sizeof td_persist_app);
    bs[0] = bs[1] = (odg_boot_status_t)99;
    return start(node, &drv, bs);
}

static int comm_is_default(uint8_t node)
{
    return td_persist_comm.x1017 == 1000 && td_persist_comm.x1400_s1 == 0x200u + node &&
           td_persist_comm.x1400_s2 == 0xFE;
}

static int app_is_default(uint8_t node)
{
    return td_persist_app.x2500_s3 == -7 && td_persist_app.x2500_s1 == 0x11223344u &&
           td_persist_app.x2500_s4_len == 2 && td_persist_app.x2500_s5 == 0x100u + node &&
           memcmp(td_persist_app.x2500_s2, "app\0\0\0\0\0", 9) == 0 &&
           td_persist_app.x2500_s4_buf[0] == 1 && td_persist_app.x2500_s4_buf[1] == 2;
}

static void *mirror(uint8_t g)
{
    return td.groups[g].mirror;
}

static uint32_t msize(uint8_t g)
{
    return td.groups[g].size;
}

/* Change every field of group g's mirror in a way that depends on `v`. */
static void scribble(uint8_t g, uint32_t v)
{
    if (g == TD_GROUP_COMM) {
        td_persist_comm.x1017 = (uint16_t)(v * 7u);
        td_persist_comm.x1400_s1 = 0x180u + v;
        td_persist_comm.x1400_s2 = (uint8_t)v;
    } else {
        td_persist_app.x2500_s3 = (int64_t)v - 500;
        td_persist_app.x2500_s1 = v * 0x01010101u;
        td_persist_app.x2500_s4_len = v % 9u;
        td_persist_app.x2500_s5 = (uint16_t)(v + 3u);
        memset(td_persist_app.x2500_s2, 0, sizeof td_persist_app.x2500_s2);
        memset(td_persist_app.x2500_s2, 'a' + (int)(v % 26u), v % 9u);
        memset(td_persist_app.x2500_s4_buf, (int)v, sizeof td_persist_app.x2500_s4_buf);
    }
}

static odg_abort_t command(uint16_t index, uint8_t sub, const char *word)
{
    odg_ref_t r;
    odg_abort_t ac = odg_find(&td, index, sub, &r);
    return ac != ODG_OK ? ac : odg_write(&r, word, 4);
}

/* ---- tests ------------------------------------------------------------------------------------ */

static void test_crc(void)
{
    const uint8_t *s = (const uint8_t *)"123456789";
    uint8_t buf[300];
    uint32_t i;
    CHECK_EQ(odg_crc32(0, s, 9), 0xCBF43926u);
    CHECK_EQ(odg_crc32(odg_crc32(0, s, 4), s + 4, 5), 0xCBF43926u);
    CHECK_EQ(odg_crc32(0, s, 0), 0);
    for (i = 0; i < sizeof buf; i++) {
        buf[i] = (uint8_t)rnd();
    }
    for (i = 0; i < sizeof buf; i += 7u) {
        CHECK_EQ_AT(odg_crc32(0, buf, i), crc_ref(0, buf, i), i);
    }
    CHECK_EQ(odg_persist_slot_size(0), 24);
    CHECK_EQ(odg_persist_slot_size(4), 24);
    CHECK_EQ(odg_persist_slot_size(5), 32);
    CHECK_EQ(odg_persist_slot_size(8), ODG_PERSIST_SLOT_SIZE(8));
    CHECK_EQ(SLOT_COMM, 32);
    CHECK_EQ(SLOT_APP, 64);
}

static void test_boot_and_commands(void)
{
    uint8_t snap[NV_SIZE];
    slot_t a, b;
    long calls;
    nv_blank();
    /* first boot: no image, defaults, written to slot 0 */
    CHECK_EQ(start(NODE, &drv, bs), ODG_OK);
    CHECK_EQ(bs[0], ODG_BOOT_DEFAULTS);
    CHECK_EQ(bs[1], ODG_BOOT_DEFAULTS);
    CHECK(comm_is_default(NODE));
    CHECK(app_is_default(NODE));
    a = slot_of(TD_GROUP_COMM, 0);
    b = slot_of(TD_GROUP_COMM, 1);
    CHECK(a.valid && !b.valid);
    CHECK(a.seq == 1 && a.sig == TD_SIGNATURE_COMM && a.len == sizeof(td_persist_comm_t));
    CHECK(memcmp(nvm.mem + addr_of(TD_GROUP_COMM, 0) + HDR, &td_persist_comm, a.len) == 0);
    a = slot_of(TD_GROUP_APP, 0);
    CHECK(a.valid && a.seq == 1 && a.sig == TD_SIGNATURE_APP);
    /* second boot: loaded */
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK_EQ(bs[0], ODG_BOOT_LOADED);
    CHECK_EQ(bs[1], ODG_BOOT_LOADED);
    CHECK(comm_is_default(NODE) && app_is_default(NODE));
    /* values through the dictionary, saved with 0x1010 sub 1, survive a reboot with another node-id */
    {
        odg_ref_t r;
        CHECK_EQ(odg_find(&td, 0x1017, 0, &r), ODG_OK);
        CHECK_EQ(odg_write(&r, "\xF4\x01", 2), ODG_OK);
        CHECK_EQ(odg_find(&td, 0x1400, 1, &r), ODG_OK);
        CHECK_EQ(odg_write(&r, "\x81\x01\x00\x00", 4), ODG_OK);
        CHECK_EQ(odg_find(&td, 0x2500, 2, &r), ODG_OK);
        CHECK_EQ(odg_write(&r, "persist", 7), ODG_OK);
        CHECK_EQ(odg_find(&td, 0x2500, 4, &r), ODG_OK);
        CHECK_EQ(odg_write(&r, "\x0A\x0B\x0C", 3), ODG_OK);
        CHECK_EQ(odg_find(&td, 0x2500, 3, &r), ODG_OK);
        CHECK_EQ(odg_write(&r, "\x40\xE2\x01\x00\x00\x00\x00\x00", 8), ODG_OK);
        CHECK_EQ(odg_find(&td, 0x2007, 0, &r), ODG_OK);
        CHECK_EQ(odg_write(&r, "\x00\x00\x00\x00", 4), ODG_OK);
    }
    CHECK_EQ(command(0x1010, 1, "save"), ODG_OK);
    CHECK(slot_of(TD_GROUP_COMM, 1).valid && slot_of(TD_GROUP_COMM, 1).seq == 2);
    CHECK(slot_of(TD_GROUP_APP, 1).valid && slot_of(TD_GROUP_APP, 1).seq == 2);
    CHECK_EQ(reboot(9), ODG_OK);
    CHECK(bs[0] == ODG_BOOT_LOADED && bs[1] == ODG_BOOT_LOADED);
    CHECK_EQ(td_persist_comm.x1017, 500);
    CHECK_EQ(td_persist_comm.x1400_s1, 0x181); /* stored values are absolute */
    CHECK_EQ(td_persist_app.x2500_s5, 0x105);
    CHECK(memcmp(td_persist_app.x2500_s2, "persist\0", 9) == 0);
    CHECK(td_persist_app.x2500_s4_len == 3 && td_persist_app.x2500_s4_buf[2] == 0x0C);
    CHECK(td_persist_app.x2500_s3 == 123456);
    CHECK_EQ(td_ram.x2007, 0x89ABCDEFu); /* RAM values are reset */
    CHECK_EQ(td_ram.x1014, 0x89);
    /* 0x1010 sub 2 stores the comm group only, sub 3 the app group only */
    td_persist_comm.x1017 = 600;
    td_persist_app.x2500_s1 = 600;
    memcpy(snap, nvm.mem, NV_SIZE);
    CHECK_EQ(command(0x1010, 2, "save"), ODG_OK);
    CHECK(memcmp(snap + addr_of(TD_GROUP_APP, 0), nvm.mem + addr_of(TD_GROUP_APP, 0), 2 * SLOT_APP) == 0);
    CHECK_EQ(slot_of(TD_GROUP_COMM, 0).seq, 3);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK(td_persist_comm.x1017 == 600 && td_persist_app.x2500_s1 == 0x11223344u);
    td_persist_app.x2500_s1 = 700;
    td_persist_comm.x1017 = 700;
    memcpy(snap, nvm.mem, NV_SIZE);
    CHECK_EQ(command(0x1010, 3, "save"), ODG_OK);
    CHECK(memcmp(snap, nvm.mem, 2 * SLOT_COMM) == 0);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK(td_persist_comm.x1017 == 600 && td_persist_app.x2500_s1 == 700);
    /* wrong words, a sub without a group, wrong lengths: nothing written */
    memcpy(snap, nvm.mem, NV_SIZE);
    calls = nvm.calls;
    CHECK_EQ(command(0x1010, 4, "save"), ODG_ABORT_DATA_STORE);
    CHECK_EQ(command(0x1011, 4, "load"), ODG_ABORT_DATA_STORE);
    CHECK_EQ(command(0x1010, 1, "load"), ODG_ABORT_DATA_STORE);
    CHECK_EQ(command(0x1011, 1, "save"), ODG_ABORT_DATA_STORE);
    CHECK_EQ(command(0x1010, 1, "SAVE"), ODG_ABORT_DATA_STORE);
    {
        odg_ref_t r;
        CHECK_EQ(odg_find(&td, 0x1010, 1, &r), ODG_OK);
        CHECK_EQ(odg_write(&r, "save!", 5), ODG_ABORT_TOO_LONG);
        CHECK_EQ(odg_write(&r, "sav", 3), ODG_ABORT_TOO_SHORT);
    }
    CHECK(memcmp(snap, nvm.mem, NV_SIZE) == 0);
    CHECK_EQ(nvm.calls, calls);
    /* the driver fails: 0x1010 passes the hardware error on */
    nvm.budget = 0;
    CHECK_EQ(command(0x1010, 1, "save"), ODG_ABORT_HARDWARE);
    power_on();
    /* 0x1011 sub 3: the app group restores its defaults at the next boot, RAM unchanged now */
    CHECK_EQ(command(0x1011, 3, "load"), ODG_OK);
    CHECK_EQ(td_persist_app.x2500_s1, 700);
    CHECK(!slot_of(TD_GROUP_APP, 0).valid && !slot_of(TD_GROUP_APP, 1).valid);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK(bs[0] == ODG_BOOT_LOADED && bs[1] == ODG_BOOT_DEFAULTS);
    CHECK(td_persist_comm.x1017 == 600 && app_is_default(NODE));
    /* 0x1011 sub 1: all groups */
    CHECK_EQ(command(0x1011, 1, "load"), ODG_OK);
    CHECK_EQ(reboot(7), ODG_OK);
    CHECK(bs[0] == ODG_BOOT_DEFAULTS && bs[1] == ODG_BOOT_DEFAULTS);
    CHECK(comm_is_default(7) && app_is_default(7));
    CHECK_EQ(reboot(7), ODG_OK);
    CHECK(bs[0] == ODG_BOOT_LOADED && bs[1] == ODG_BOOT_LOADED);
    /* API misuse */
    CHECK_EQ(odg_persist_store(&td, 2), ODG_ABORT_DATA_STORE);
    CHECK_EQ(odg_persist_restore(&td, 2), ODG_ABORT_DATA_STORE);
    CHECK_EQ(odg_persist_init(&persist, &td, NULL, bs), ODG_ABORT_DATA_STORE);
    CHECK(bs[0] == ODG_BOOT_NV_ERROR && bs[1] == ODG_BOOT_NV_ERROR);
    CHECK_EQ(odg_init(&td, NODE), ODG_OK);
    CHECK_EQ(odg_persist_store(&td, 0), ODG_ABORT_DATA_STORE);
    CHECK_EQ(odg_persist_restore(&td, 0), ODG_ABORT_DATA_STORE);
    CHECK_EQ(command(0x1010, 1, "save"), ODG_ABORT_DATA_STORE);
    CHECK_EQ(start(NODE, &drv, NULL), ODG_OK); /* boot status may be NULL */
}

/* Stores alternate between the slots with increasing sequence numbers. */
static void test_alternation(void)
{
    uint32_t i;
    nv_blank();
    CHECK_EQ(reboot(NODE), ODG_OK);
    for (i = 0; i < 6u; i++) {
        int k = (int)((i + 1u) & 1u);
        scribble(TD_GROUP_APP, i);
        CHECK_EQ(odg_persist_store(&td, TD_GROUP_APP), ODG_OK);
        CHECK_EQ_AT(slot_of(TD_GROUP_APP, k).seq, i + 2u, i);
        CHECK(slot_of(TD_GROUP_APP, k).valid && slot_of(TD_GROUP_APP, !k).valid);
        CHECK_EQ_AT(slot_of(TD_GROUP_APP, !k).seq, i + 1u, i);
    }
}

/* Power fails after k bytes of a store, for every k: the old image or the new one, never a mix. */
static void sweep_store(uint8_t g, int torn, int reverse)
{
    uint8_t snap[NV_SIZE], old_img[64], new_img[64];
    uint32_t total, k, n_new = 0, other = g == TD_GROUP_COMM ? TD_GROUP_APP : TD_GROUP_COMM;
    int round;
    for (round = 0; round < 2; round++) { /* the new image goes to slot 0, then to slot 1 */
        nv_blank();
        CHECK_EQ(reboot(NODE), ODG_OK); /* defaults, seq 1 in slot 0 */
        scribble(g, 11);
        CHECK_EQ(odg_persist_store(&td, g), ODG_OK); /* seq 2 in slot 1 */
        if (round == 1) {
            scribble(g, 22);
            CHECK_EQ(odg_persist_store(&td, g), ODG_OK); /* seq 3 in slot 0 */
        }
        memcpy(old_img, mirror(g), msize(g));
        memcpy(snap, nvm.mem, NV_SIZE);
        /* the new image and the number of bytes a store programs */
        scribble(g, 33 + (uint32_t)round);
        memcpy(new_img, mirror(g), msize(g));
        nvm.bytes = 0;
        CHECK_EQ(odg_persist_store(&td, g), ODG_OK);
        total = (uint32_t)nvm.bytes;
        CHECK_EQ(total, ODG_PERSIST_SLOT_SIZE(msize(g)) + msize(g) + HDR);
        CHECK_EQ(slot_of(g, round == 0 ? 0 : 1).seq, (uint32_t)round + 3u);
        for (k = 0; k <= total; k++) {
            odg_abort_t ac;
            memcpy(nvm.mem, snap, NV_SIZE);
            power_on();
            nvm.torn = torn;
            nvm.erase_reverse = reverse;
            nvm.budget = (long)k;
            memcpy(mirror(g), new_img, msize(g));
            ac = odg_persist_store(&td, g);
            CHECK_EQ_AT(ac, k == total ? ODG_OK : ODG_ABORT_HARDWARE, k);
            nvm.torn = 0;
            /* the magic is the commit mark: the new header is complete only once every
             * other byte is written (so a cut never relies on the CRC alone) */
            if (!torn && k < total) {
                const uint8_t *t = nvm.mem + addr_of(g, round == 0 ? 0 : 1);
                if (memcmp(t, "ODG1", 4) == 0 && get32(t + 4) == (uint32_t)round + 3u) {
                    CHECK_EQ_AT(1, 0, k);
                }
            }
            /* the other group's slots are untouched */
            if (memcmp(snap + td.groups[other].nv_addr, nvm.mem + td.groups[other].nv_addr,
                       2u * ODG_PERSIST_SLOT_SIZE(msize((uint8_t)other))) != 0) {
                CHECK_EQ_AT(1, 0, k);
            }
            CHECK_EQ_AT(reboot(NODE), ODG_OK, k);
            CHECK_EQ_AT(bs[g], ODG_BOOT_LOADED, k);
            if (memcmp(mirror(g), new_img, msize(g)) == 0) {
                n_new++;
            } else if (memcmp(mirror(g), old_img, msize(g)) != 0) {
                CHECK_EQ_AT(1, 0, k); /* a mix */
            }
            if (k == total || (!torn && k + 1u < total)) {
                /* complete: new; cut before the last magic byte: old (the torn byte may
                 * happen to come out complete) */
                CHECK_EQ_AT(memcmp(mirror(g), k == total ? new_img : old_img, msize(g)), 0, k);
            }
            /* a later store over the half-written slot works */
            memcpy(mirror(g), new_img, msize(g));
            CHECK_EQ_AT(odg_persist_store(&td, g), ODG_OK, k);
            CHECK_EQ_AT(reboot(NODE), ODG_OK, k);
            CHECK_EQ_AT(memcmp(mirror(g), new_img, msize(g)), 0, k);
        }
    }
    CHECK(n_new >= 2u);
    nvm.erase_reverse = 0;
}

/* Power fails during a restore: the newest image or the defaults, never the older image. */
static void sweep_restore(uint8_t g)
{
    uint8_t snap[NV_SIZE], new_img[64], old_img[64];
    uint32_t total = 2u * ODG_PERSIST_SLOT_SIZE(msize(g)), k, i, n_defaults = 0, n_new = 0;
    int blank;
    nv_blank();
    CHECK_EQ(reboot(NODE), ODG_OK);
    scribble(g, 44);
    memcpy(old_img, mirror(g), msize(g));
    CHECK_EQ(odg_persist_store(&td, g), ODG_OK);
    scribble(g, 55);
    memcpy(new_img, mirror(g), msize(g));
    CHECK_EQ(odg_persist_store(&td, g), ODG_OK); /* newest in slot 0, older in slot 1 */
    memcpy(snap, nvm.mem, NV_SIZE);
    for (k = 0; k <= total; k++) {
        memcpy(nvm.mem, snap, NV_SIZE);
        power_on();
        nvm.budget = (long)k;
        CHECK_EQ_AT(odg_persist_restore(&td, g), k == total ? ODG_OK : ODG_ABORT_HARDWARE, k);
        for (i = 0, blank = 1; i < total; i++) {
            blank &= nvm.mem[td.groups[g].nv_addr + i] == 0xFFu;
        }
        CHECK_EQ_AT(reboot(NODE), ODG_OK, k);
        if (bs[g] == ODG_BOOT_LOADED) {
            CHECK_EQ_AT(memcmp(mirror(g), new_img, msize(g)), 0, k);
            n_new++;
        } else {
            /* both slots erased: DEFAULTS; the newest erased in part: DAMAGED (an erase
             * cut short cannot be told from lost values) */
            CHECK_EQ_AT(bs[g], blank ? ODG_BOOT_DEFAULTS : ODG_BOOT_DAMAGED, k);
            CHECK(g == TD_GROUP_COMM ? comm_is_default(NODE) : app_is_default(NODE));
            n_defaults++;
        }
        if (memcmp(mirror(g), old_img, msize(g)) == 0) {
            CHECK_EQ_AT(1, 0, k);
        }
    }
    CHECK(n_new > 0u && n_defaults > 0u);
}

/* Power fails while the first boot writes the defaults. */
static void sweep_first_boot(void)
{
    uint32_t total, k;
    nv_blank();
    nvm.bytes = 0;
    CHECK_EQ(reboot(NODE), ODG_OK);
    total = (uint32_t)nvm.bytes;
    CHECK_EQ(total, SLOT_COMM + sizeof(td_persist_comm_t) + HDR + SLOT_APP + sizeof(td_persist_app_t) + HDR);
    for (k = 0; k <= total; k++) {
        odg_abort_t ac;
        nv_blank();
        nvm.budget = (long)k;
        memset(&td_persist_comm, 0, sizeof td_persist_comm);
        ac = start(NODE, &drv, bs);
        CHECK_EQ_AT(ac, k == total ? ODG_OK : ODG_ABORT_HARDWARE, k);
        CHECK_EQ_AT(bs[1], k == total ? ODG_BOOT_DEFAULTS : ODG_BOOT_NV_ERROR, k);
        CHECK(comm_is_default(NODE) && app_is_default(NODE)); /* defaults in RAM either way */
        CHECK_EQ_AT(reboot(NODE), ODG_OK, k);
        /* a first image cut short is something in NV that is not an image: DAMAGED */
        CHECK(bs[0] == ODG_BOOT_LOADED || bs[0] == ODG_BOOT_DEFAULTS || bs[0] == ODG_BOOT_DAMAGED);
        CHECK(bs[1] == ODG_BOOT_LOADED || bs[1] == ODG_BOOT_DEFAULTS || bs[1] == ODG_BOOT_DAMAGED);
        CHECK(comm_is_default(NODE) && app_is_default(NODE));
    }
}

/* Bit flips: any single flipped bit in the newest slot falls back to the older image, in the
 * older slot (or in padding) changes nothing; both slots damaged: defaults. */
static void test_bit_flips(uint8_t g)
{
    uint8_t snap[NV_SIZE], old_img[64], new_img[64];
    uint32_t slot = ODG_PERSIST_SLOT_SIZE(msize(g)), base = td.groups[g].nv_addr, p, i;
    int newest, bit;
    for (newest = 0; newest < 2; newest++) {
        nv_blank();
        CHECK_EQ(reboot(NODE), ODG_OK); /* defaults in slot 0 */
        scribble(g, 66);
        CHECK_EQ(odg_persist_store(&td, g), ODG_OK); /* slot 1 */
        if (newest == 0) {
            scribble(g, 77);
            CHECK_EQ(odg_persist_store(&td, g), ODG_OK); /* slot 0 */
        }
        memcpy(new_img, mirror(g), msize(g));
        memcpy(old_img, nvm.mem + base + (newest ? 0u : slot) + HDR, msize(g));
        memcpy(snap, nvm.mem, NV_SIZE);
        CHECK_EQ(slot_of(g, newest).valid && slot_of(g, !newest).valid, 1);
        for (p = 0; p < 2u * slot; p++) {
            for (bit = 0; bit < 8; bit++) {
                int in_newest = p / slot == (uint32_t)newest && p % slot < HDR + msize(g);
                memcpy(nvm.mem, snap, NV_SIZE);
                nvm.mem[base + p] ^= (uint8_t)(1u << bit);
                CHECK_EQ_AT(reboot(NODE), ODG_OK, p);
                CHECK_EQ_AT(bs[g], ODG_BOOT_LOADED, p);
                CHECK_EQ_AT(memcmp(mirror(g), in_newest ? old_img : new_img, msize(g)), 0, p * 8u + (uint32_t)bit);
            }
        }
        /* one random bit in each slot's header or image: defaults, which are then stored */
        for (i = 0; i < 200u; i++) {
            uint32_t p0 = rnd() % (HDR + msize(g)), p1 = rnd() % (HDR + msize(g));
            memcpy(nvm.mem, snap, NV_SIZE);
            nvm.mem[base + p0] ^= (uint8_t)(1u << (rnd() & 7u));
            nvm.mem[base + slot + p1] ^= (uint8_t)(1u << (rnd() & 7u));
            CHECK_EQ_AT(reboot(NODE), ODG_OK, i);
            CHECK_EQ_AT(bs[g], ODG_BOOT_DAMAGED, i); /* stored values lost */
            CHECK_EQ(td.state->boot_seen, 1u << ODG_BOOT_LOADED | 1u << ODG_BOOT_DAMAGED);
            CHECK(g == TD_GROUP_COMM ? comm_is_default(NODE) : app_is_default(NODE));
            CHECK_EQ_AT(reboot(NODE), ODG_OK, i);
            CHECK_EQ_AT(bs[g], ODG_BOOT_LOADED, i);
            CHECK(g == TD_GROUP_COMM ? comm_is_default(NODE) : app_is_default(NODE));
        }
        /* random damage to several bytes of the newest slot */
        for (i = 0; i < 300u; i++) {
            uint32_t n = 1u + rnd() % 8u, j, changed = 0;
            memcpy(nvm.mem, snap, NV_SIZE);
            for (j = 0; j < n; j++) {
                uint32_t q = base + (uint32_t)newest * slot + rnd() % (HDR + msize(g));
                uint8_t v = (uint8_t)rnd();
                changed |= nvm.mem[q] != v;
                nvm.mem[q] = v;
            }
            CHECK_EQ_AT(reboot(NODE), ODG_OK, i);
            CHECK_EQ_AT(bs[g], ODG_BOOT_LOADED, i);
            CHECK_EQ_AT(memcmp(mirror(g), changed ? old_img : new_img, msize(g)), 0, i);
        }
    }
}

static void test_signature_and_sequence(void)
{
    td_persist_comm_t img;
    uint8_t junk[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    memset(&img, 0, sizeof img);
    img.x1017 = 1234;
    img.x1400_s1 = 0x333;
    /* an image of another layout: defaults, written to the other slot with the next sequence */
    nv_blank();
    put_slot(TD_GROUP_COMM, 0, 7, 0xDEADBEEFu, &img, sizeof img);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK_EQ(bs[0], ODG_BOOT_SIGNATURE);
    CHECK_EQ(bs[1], ODG_BOOT_DEFAULTS);
    CHECK(comm_is_default(NODE));
    CHECK(slot_of(TD_GROUP_COMM, 1).valid && slot_of(TD_GROUP_COMM, 1).seq == 8 &&
          slot_of(TD_GROUP_COMM, 1).sig == TD_SIGNATURE_COMM);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK_EQ(bs[0], ODG_BOOT_LOADED);
    CHECK(comm_is_default(NODE));
    /* the newest has another signature, the older one ours: the newest decides */
    nv_blank();
    put_slot(TD_GROUP_COMM, 0, 7, TD_SIGNATURE_COMM, &img, sizeof img);
    put_slot(TD_GROUP_COMM, 1, 8, 0xDEADBEEFu, &img, sizeof img);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK_EQ(bs[0], ODG_BOOT_SIGNATURE);
    CHECK(comm_is_default(NODE));
    /* the same signature with another length: another layout too */
    nv_blank();
    put_slot(TD_GROUP_COMM, 0, 1, TD_SIGNATURE_COMM, junk, 4);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK_EQ(bs[0], ODG_BOOT_SIGNATURE);
    /* a length beyond the slot: not a valid image */
    nv_blank();
    put_slot(TD_GROUP_COMM, 0, 1, TD_SIGNATURE_COMM, &img, sizeof img);
    put32(nvm.mem + 12, 1000);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK_EQ(bs[0], ODG_BOOT_DAMAGED);
    /* our image and an older one of another layout */
    nv_blank();
    put_slot(TD_GROUP_COMM, 0, 7, 0xDEADBEEFu, junk, 4);
    put_slot(TD_GROUP_COMM, 1, 8, TD_SIGNATURE_COMM, &img, sizeof img);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK_EQ(bs[0], ODG_BOOT_LOADED);
    CHECK(td_persist_comm.x1017 == 1234 && td_persist_comm.x1400_s1 == 0x333);
    /* sequence numbers wrap around */
    nv_blank();
    img.x1017 = 1;
    put_slot(TD_GROUP_COMM, 0, 0xFFFFFFFFu, TD_SIGNATURE_COMM, &img, sizeof img);
    img.x1017 = 2;
    put_slot(TD_GROUP_COMM, 1, 0, TD_SIGNATURE_COMM, &img, sizeof img);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK_EQ(bs[0], ODG_BOOT_LOADED);
    CHECK_EQ(td_persist_comm.x1017, 2);
    CHECK_EQ(odg_persist_store(&td, TD_GROUP_COMM), ODG_OK);
    CHECK(slot_of(TD_GROUP_COMM, 0).valid && slot_of(TD_GROUP_COMM, 0).seq == 1);
    nv_blank();
    img.x1017 = 3;
    put_slot(TD_GROUP_COMM, 0, 0, TD_SIGNATURE_COMM, &img, sizeof img);
    img.x1017 = 4;
    put_slot(TD_GROUP_COMM, 1, 0xFFFFFFFFu, TD_SIGNATURE_COMM, &img, sizeof img);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK_EQ(td_persist_comm.x1017, 3);
    nv_blank();
    img.x1017 = 5;
    put_slot(TD_GROUP_COMM, 0, 0x7FFFFFFFu, TD_SIGNATURE_COMM, &img, sizeof img);
    img.x1017 = 6;
    put_slot(TD_GROUP_COMM, 1, 0x80000000u, TD_SIGNATURE_COMM, &img, sizeof img);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK_EQ(td_persist_comm.x1017, 6);
}

static void change_mirror(uint32_t addr, uint32_t len)
{
    (void)addr;
    if (len == sizeof(td_persist_comm_t)) {
        td_persist_comm.x1017 ^= 1u; /* the application writes while the image is stored */
    }
}

static void test_nv_errors(void)
{
    uint8_t snap[NV_SIZE], new_img[64], old_img[64];
    long reads, n;
    int mode;
    /* reads fail: defaults in RAM, NV untouched, odg_init reports it */
    nv_blank();
    CHECK_EQ(reboot(NODE), ODG_OK);
    scribble(TD_GROUP_COMM, 5);
    CHECK_EQ(odg_persist_store(&td, TD_GROUP_COMM), ODG_OK);
    memcpy(old_img, &td_persist_comm, sizeof td_persist_comm);
    scribble(TD_GROUP_COMM, 6);
    CHECK_EQ(odg_persist_store(&td, TD_GROUP_COMM), ODG_OK);
    memcpy(new_img, &td_persist_comm, sizeof td_persist_comm);
    memcpy(snap, nvm.mem, NV_SIZE);
    power_on();
    nvm.reads = 0;
    CHECK_EQ(start(NODE, &drv, bs), ODG_OK);
    reads = nvm.reads;
    for (mode = 0; mode < 2; mode++) {
        for (n = 1; n <= reads; n++) {
            odg_abort_t ac;
            memcpy(nvm.mem, snap, NV_SIZE);
            power_on();
            nvm.reads = 0;
            nvm.fail_read_at = n;
            nvm.corrupt_read = mode;
            memset(&td_persist_comm, 0xA5, sizeof td_persist_comm);
            ac = start(NODE, &drv, bs);
            CHECK(app_is_default(NODE));
            if (bs[0] == ODG_BOOT_LOADED) {
                /* a read that lies about the newest slot may make the older one win */
                if (memcmp(&td_persist_comm, new_img, sizeof td_persist_comm) != 0) {
                    CHECK_EQ_AT(memcmp(&td_persist_comm, old_img, sizeof td_persist_comm), 0, n);
                    CHECK_EQ_AT(mode, 1, n);
                }
            } else {
                CHECK_EQ_AT(bs[0], ODG_BOOT_NV_ERROR, n);
                CHECK_EQ_AT(ac, ODG_ABORT_HARDWARE, n);
                CHECK(comm_is_default(NODE)); /* never a half-loaded image */
            }
            if (mode == 0) {
                CHECK_EQ_AT(memcmp(nvm.mem, snap, NV_SIZE), 0, n); /* boot only read */
            }
            CHECK_EQ_AT(memcmp(nvm.mem, snap, 2 * SLOT_COMM), 0, n);
        }
    }
    /* every read fails */
    memcpy(nvm.mem, snap, NV_SIZE);
    power_on();
    nvm.dead = 1;
    CHECK_EQ(start(NODE, &drv, bs), ODG_ABORT_HARDWARE);
    CHECK(bs[0] == ODG_BOOT_NV_ERROR && bs[1] == ODG_BOOT_NV_ERROR);
    CHECK(comm_is_default(NODE) && app_is_default(NODE));
    CHECK(memcmp(nvm.mem, snap, NV_SIZE) == 0);
    /* the mirror changes while it is being stored: the store fails, the old image stays */
    CHECK_EQ(reboot(NODE), ODG_OK);
    nvm.during_write = change_mirror;
    scribble(TD_GROUP_COMM, 9);
    CHECK_EQ(odg_persist_store(&td, TD_GROUP_COMM), ODG_ABORT_HARDWARE);
    CHECK_EQ(reboot(NODE), ODG_OK);
    CHECK(memcmp(&td_persist_comm, new_img, sizeof td_persist_comm) == 0);
    /* an erase that fails */
    nvm.budget = 0;
    CHECK_EQ(odg_persist_restore(&td, TD_GROUP_COMM), ODG_ABORT_HARDWARE);
    power_on();
    nvm.fail_read_at = 1;
    nvm.reads = 0;
    CHECK_EQ(odg_persist_store(&td, TD_GROUP_COMM), ODG_ABORT_HARDWARE);
    nvm.fail_read_at = 1;
    nvm.reads = 0;
    CHECK_EQ(odg_persist_restore(&td, TD_GROUP_COMM), ODG_ABORT_HARDWARE);
    power_on();
}

/* The file driver: a real file, kept across "power cycles" (close and open). */
static void test_file_driver(const char *dir)
{
    char path[512];
    odg_nv_file_t f;
    uint8_t buf[NV_SIZE];
    uint32_t i;
    int all_ff = 1;
    FILE *fp;
    snprintf(path, sizeof path, "%s/node.nv", dir);
    remove(path);
    CHECK_EQ(odg_nv_file_open(&f, path, 300), 0);
    CHECK_EQ(f.driver.read(f.driver.ctx, 0, buf, 300), 0);
    for (i = 0; i < 300u; i++) {
        all_ff &= buf[i] == 0xFF;
    }
    CHECK(all_ff);
    CHECK_EQ(f.driver.read(f.driver.ctx, 299, buf, 2), -1);
    CHECK_EQ(f.driver.write(f.driver.ctx, 298, buf, 3), -1);
    CHECK_EQ(f.driver.erase(f.driver.ctx, 301, 0), -1);
    CHECK_EQ(f.driver.read(f.driver.ctx, 300, buf, 0), 0);
    CHECK_EQ(start(NODE, &f.driver, bs), ODG_OK);
    CHECK(bs[0] == ODG_BOOT_DEFAULTS && bs[1] == ODG_BOOT_DEFAULTS);
    td_persist_comm.x1017 = 4242;
    memcpy(td_persist_app.x2500_s2, "file", 5);
    CHECK_EQ(command(0x1010, 1, "save"), ODG_OK);
    CHECK_EQ(odg_nv_file_close(&f), 0);
    CHECK_EQ(odg_nv_file_close(&f), 0);
    /* power cycle; a larger area keeps what was there */
    CHECK_EQ(odg_nv_file_open(&f, path, 400), 0);
    f.sync = 0;
    CHECK_EQ(start(NODE, &f.driver, bs), ODG_OK);
    CHECK(bs[0] == ODG_BOOT_LOADED && bs[1] == ODG_BOOT_LOADED);
    CHECK_EQ(td_persist_comm.x1017, 4242);
    CHECK(memcmp(td_persist_app.x2500_s2, "file", 5) == 0);
    CHECK_EQ(f.driver.read(f.driver.ctx, 300, buf, 100), 0);
    CHECK(buf[0] == 0xFF && buf[99] == 0xFF);
    CHECK_EQ(f.driver.erase(f.driver.ctx, 0, 400), 0);
    CHECK_EQ(start(NODE, &f.driver, bs), ODG_OK);
    CHECK_EQ(bs[0], ODG_BOOT_DEFAULTS);
    CHECK_EQ(odg_nv_file_close(&f), 0);
    CHECK_EQ(f.driver.read(f.driver.ctx, 0, buf, 1), -1); /* closed */
    fp = fopen(path, "rb");
    CHECK(fp != NULL);
    if (fp != NULL) {
        CHECK_EQ(fseek(fp, 0, SEEK_END), 0);
        CHECK_EQ(ftell(fp), 400);
        fclose(fp);
    }
    snprintf(path, sizeof path, "%s/no/such/dir/node.nv", dir);
    CHECK_EQ(odg_nv_file_open(&f, path, 100), -1);
}

int main(int argc, char **argv)
{
    test_crc();
    test_boot_and_commands();
    test_alternation();
    sweep_store(TD_GROUP_COMM, 0, 0);
    sweep_store(TD_GROUP_APP, 0, 0);
    sweep_store(TD_GROUP_COMM, 1, 0);
    sweep_store(TD_GROUP_APP, 1, 1);
    sweep_store(TD_GROUP_COMM, 1, 1);
    sweep_restore(TD_GROUP_COMM);
    sweep_restore(TD_GROUP_APP);
    sweep_first_boot();
    test_bit_flips(TD_GROUP_COMM);
    test_bit_flips(TD_GROUP_APP);
    test_signature_and_sequence();
    test_nv_errors();
    test_file_driver(argc > 1 ? argv[1] : ".");
    return done();
}
