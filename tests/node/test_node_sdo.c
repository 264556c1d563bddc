/*
 * test_node_sdo.c - the node's NMT, heartbeat, EMCY and SDO server against the alltypes
 * dictionary (generated at test time from tests/fixtures/generate/alltypes.eds with its
 * options): every transfer type in both directions, strings, domains and 64-bit numbers,
 * and every abort path, each followed by a check that the server still serves.
 */
#include <stdio.h>
#include <string.h>

#include "alltypes.h"
#include "fake.h"

/* the options file names this POST_WRITE hook for 0x2006 */
static unsigned notices;
odg_abort_t alltypes_notice(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                            void *ctx)
{
    (void)ref, (void)kind, (void)data, (void)len, (void)ctx;
    notices++;
    return ODG_OK;
}

static odg_abort_t veto_99(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                           void *ctx)
{
    (void)ref, (void)ctx;
    return kind == ODG_HOOK_PRE_WRITE && len == 1u && ((const uint8_t *)data)[0] == 99u
               ? ODG_ABORT_VALUE_RANGE
               : ODG_OK;
}

/* The server answers a plain upload of 0x1000 after whatever came before. */
static void still_serving(int line)
{
    const odg_frame_t *r = sdo(0x40, IDX(0x1000), 0, 0, 0, 0, 0);
    if (r->data[0] != 0x43u) {
        printf("  (server not serving at line %d)\n", line);
    }
    CHECK_EQ(r->data[0], 0x43);
}
#define STILL_SERVING() still_serving(__LINE__)

static uint8_t nmt_seen[8];
static unsigned n_nmt_seen;

static void on_nmt(void *ctx, uint8_t command)
{
    CHECK(ctx == &nmt_seen);
    if (n_nmt_seen < sizeof nmt_seen) {
        nmt_seen[n_nmt_seen++] = command;
    }
}

static void test_nmt_and_heartbeat(void)
{
    start_node(&alltypes, NULL);
    node.cfg.on_nmt = on_nmt;
    node.cfg.app_ctx = &nmt_seen;
    /* 0x1017 = 1000 ms: the first heartbeat after 1000 ms, with the pre-operational byte */
    clear();
    run_ms(999);
    CHECK_EQ(count_id(0x705), 0);
    run_ms(1);
    CHECK_EQ(count_id(0x705), 1);
    CHECK_EQ(last_id(0x705)->data[0], 0x7F);
    CHECK_EQ(last_id(0x705)->len, 1);
    run_ms(2000);
    CHECK_EQ(count_id(0x705), 3);

    nmt(ODG_NMT_START, NID);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);
    clear();
    after(1000);
    CHECK_EQ(last_id(0x705)->data[0], 0x05);
    nmt(ODG_NMT_STOP, 0); /* broadcast */
    CHECK_EQ(odg_node_state(&node), ODG_NMT_STOPPED);
    clear();
    after(1000);
    CHECK_EQ(last_id(0x705)->data[0], 0x04);
    /* no SDO in stopped */
    clear();
    rx(SDO_RX, 0x40, IDX(0x1000), 0, 0, 0, 0, 0);
    CHECK_EQ(n_sent, 0);
    nmt(ODG_NMT_ENTER_PREOP, NID);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL);
    /* commands for another node, unknown commands and short frames are ignored */
    nmt(ODG_NMT_START, NID + 1u);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL);
    nmt(0x55, NID);
    rx(0, ODG_NMT_START);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL);
    /* stopped -> pre-operational and operational work from every state */
    nmt(ODG_NMT_STOP, NID);
    nmt(ODG_NMT_START, NID);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);

    /* a new period by SDO takes effect at once; the phase restarts from the last beat */
    CHECK_EQ(download_u32(0x1017, 0, 50, 2), 0);
    clear();
    run_ms(1000);
    CHECK_EQ(count_id(0x705), 20);
    /* a tick longer than the period sends one heartbeat, not a burst */
    clear();
    after(500);
    CHECK_EQ(count_id(0x705), 1);
    CHECK_EQ(download_u32(0x1017, 0, 0, 2), 0);
    clear();
    run_ms(3000);
    CHECK_EQ(count_id(0x705), 0);

    /* reset communication: boot-up, pre-operational; the communication values of the boot */
    clear();
    nmt(ODG_NMT_RESET_COMM, NID);
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(sent[0].id, 0x705);
    CHECK_EQ(sent[0].data[0], 0);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL);
    CHECK_EQ(upload_u32(0x1017, 0), 1000);
    /* reset node: the dictionary is initialised again (no NV here: defaults) */
    CHECK_EQ(download_u32(0x2005, 0, 9, 1), 0);
    clear();
    nmt(ODG_NMT_RESET_NODE, 0);
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(sent[0].id, 0x705);
    CHECK_EQ(upload_u32(0x1017, 0), 1000);
    CHECK_EQ(upload_u32(0x2005, 0), 7);
    /* the application heard every command addressed to the node, in order */
    CHECK_EQ(n_nmt_seen, 7);
    CHECK(memcmp(nmt_seen, "\x01\x02\x80\x02\x01\x82\x81", 7) == 0);
}

static void test_persistence(void)
{
    static const uint8_t save[4] = {'s', 'a', 'v', 'e'}, load[4] = {'l', 'o', 'a', 'd'};
    memset(nv_mem, 0xFF, sizeof nv_mem);
    start_node(&alltypes, &nv_ram);
    CHECK_EQ(download_u32(0x1017, 0, 250, 2), 0);
    CHECK_EQ(download_u32(0x2005, 0, 42, 1), 0);
    CHECK_EQ(download(0x1010, 1, save, 4), 0);
    CHECK_EQ(download_u32(0x1017, 0, 700, 2), 0);
    /* reset communication and reset node: what was stored */
    nmt(ODG_NMT_RESET_COMM, NID);
    CHECK_EQ(upload_u32(0x1017, 0), 250);
    CHECK_EQ(download_u32(0x1017, 0, 700, 2), 0);
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(upload_u32(0x1017, 0), 250);
    CHECK_EQ(upload_u32(0x2005, 0), 42);
    clear();
    run_ms(250);
    CHECK_EQ(count_id(0x705), 1);
    /* "load" (restore defaults) takes effect at the next reset of the node */
    CHECK_EQ(download(0x1011, 1, load, 4), 0);
    CHECK_EQ(upload_u32(0x1017, 0), 250);
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(upload_u32(0x1017, 0), 1000);
    /* a wrong command word is the dictionary's abort */
    CHECK_EQ(download(0x1010, 1, load, 4), ODG_ABORT_DATA_STORE);
}

static void test_expedited(void)
{
    uint8_t b[8];
    uint32_t n;
    start_node(&alltypes, NULL);
    CHECK_EQ(upload_u32(0x2007, 0), 0x180u + NID); /* $NODEID applied */
    CHECK_EQ(upload(0x2002, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, 1);
    CHECK_EQ(b[0], 0xFB); /* -5 */
    CHECK_EQ(download_u32(0x2003, 0, 0xFC18, 2), 0); /* -1000 */
    CHECK_EQ(alltypes_persist_comm.x2003_int16_value, -1000);
    CHECK_EQ(download_u32(0x200F, 0, 0x800000, 3), 0); /* INTEGER24: 3 bytes */
    CHECK_EQ(alltypes_ram.x200F_int24_value, -8388608);
    CHECK_EQ(download(0x200A, 0, "\x0A\x0B\x0C\x0D", 4), 0);
    CHECK_EQ(upload(0x200A, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, 4);
    CHECK_EQ(le32(b), 0x0D0C0B0A);
    /* size not indicated: 4 bytes, or the object's size when it is shorter */
    CHECK_EQ(abort_of(sdo(0x22, IDX(0x2006), 0, 0x34, 0x12, 0xEE, 0xEE)), 0);
    CHECK_EQ(alltypes_persist_comm.x2006_uint16_value, 0x1234);
    CHECK_EQ(abort_of(sdo(0x22, IDX(0x2004), 0, 1, 2, 3, 4)), 0);
    CHECK_EQ(alltypes_persist_comm.x2004_int32_value, 0x04030201);
    /* empty string: a segmented upload of size 0 with one empty segment */
    CHECK_EQ(download_segmented(0x2009, 0, (const uint8_t *)"", 0, 1), 0);
    CHECK_EQ(upload(0x2009, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, 0);
    /* a short string goes expedited */
    CHECK_EQ(download(0x2009, 0, "ab", 2), 0);
    CHECK_EQ(upload(0x2009, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, 2);
    CHECK(memcmp(b, "ab", 2) == 0);
    /* the dictionary's hooks run: POST_WRITE of 0x2006, a registered PRE_WRITE veto */
    notices = 0;
    CHECK_EQ(download_u32(0x2006, 0, 0x10, 2), 0);
    CHECK_EQ(notices, 1);
    CHECK_EQ(odg_hook_register(&alltypes, 0x2005, 0, veto_99, NULL), 0);
    CHECK_EQ(download_u32(0x2005, 0, 99, 1), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x2005, 0, 98, 1), 0);
    CHECK_EQ(odg_hook_register(&alltypes, 0x2005, 0, NULL, NULL), 0);
}

static void test_segmented(void)
{
    static const char label[] = "a label of forty characters, exactly!!!!";
    uint8_t b[64], u64[8] = {1, 2, 3, 4, 5, 6, 7, 0x88};
    uint32_t n;
    start_node(&alltypes, NULL);
    CHECK_EQ(upload(0x2009, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, strlen("odgen \"test\" */ label"));
    CHECK(memcmp(b, "odgen \"test\" */ label", n) == 0);
    CHECK_EQ(download(0x2009, 0, label, 40), 0);
    CHECK_EQ(strcmp(alltypes_ram.x2009_device_label, label), 0);
    CHECK_EQ(upload(0x2009, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, 40);
    CHECK(memcmp(b, label, 40) == 0);
    /* a shorter string clears the rest */
    CHECK_EQ(download(0x2009, 0, "twelve chars", 12), 0);
    CHECK_EQ(strcmp(alltypes_ram.x2009_device_label, "twelve chars"), 0);
    /* 64-bit numbers are collected and written whole */
    CHECK_EQ(download(0x2019, 0, u64, 8), 0);
    CHECK_EQ(alltypes_persist_app.x2019_uint64_value, 0x8807060504030201u);
    CHECK_EQ(upload(0x2019, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, 8);
    CHECK(memcmp(b, u64, 8) == 0);
    CHECK_EQ(download(0x2011, 0, u64, 5), 0); /* INTEGER40 */
    CHECK_EQ(alltypes_persist_app.x2011_int40_value, 0x0504030201);
    /* segmented without a size: up to 8 bytes (a number) are collected */
    CHECK_EQ(download_segmented(0x2014, 0, u64, 8, 0), 0);
    CHECK_EQ((uint64_t)alltypes_persist_app.x2014_int64_value, 0x8807060504030201u);
    CHECK_EQ(download_segmented(0x2009, 0, (const uint8_t *)label, 12, 0), ODG_ABORT_OUT_OF_MEMORY);
    /* a number of 2 bytes sent segmented */
    CHECK_EQ(download_segmented(0x2006, 0, u64, 2, 1), 0);
    CHECK_EQ(alltypes_persist_comm.x2006_uint16_value, 0x0201);
    /* unicode: even lengths only */
    CHECK_EQ(download(0x200B, 0, "x\0y\0z\0", 6), 0);
    CHECK_EQ(alltypes_ram.x200B_unicode_label[2], 'z');
    CHECK_EQ(upload(0x200B, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, 6);
    CHECK_EQ(download(0x200B, 0, "x\0y\0z", 5), ODG_ABORT_TYPE_LENGTH);
    /* domain */
    CHECK_EQ(download(0x200E, 0, "0123456789ABCDEF", 16), 0);
    CHECK_EQ(alltypes_ram.x200E_domain_value_len, 16);
    CHECK_EQ(upload(0x200E, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, 16);
    CHECK(memcmp(b, "0123456789ABCDEF", 16) == 0);
    CHECK_EQ(download(0x200E, 0, "0123456789ABCDEFG", 17), ODG_ABORT_TOO_LONG);
    CHECK_EQ(download(0x2009, 0, label, 41), ODG_ABORT_TOO_LONG);
    STILL_SERVING();
}

static void test_block(void)
{
    static const char text[] = "block transfers carry up to 127 segments";
    uint8_t b[256], u64[8] = {8, 7, 6, 5, 4, 3, 2, 1};
    uint32_t n;
    start_node(&alltypes, NULL);
    /* upload: one sub-block, several, and one with a repeated segment */
    CHECK_EQ(block_upload(0x2009, 0, b, sizeof b, &n, 127, 0, 0), 0);
    CHECK_EQ(n, strlen("odgen \"test\" */ label"));
    CHECK(memcmp(b, "odgen \"test\" */ label", n) == 0);
    CHECK_EQ(download(0x2009, 0, text, 40), 0);
    CHECK_EQ(block_upload(0x2009, 0, b, sizeof b, &n, 2, 0, 0), 0);
    CHECK_EQ(n, 40);
    CHECK(memcmp(b, text, 40) == 0);
    CHECK_EQ(block_upload(0x2009, 0, b, sizeof b, &n, 3, 0, 1), 0);
    CHECK_EQ(n, 40);
    CHECK(memcmp(b, text, 40) == 0);
    CHECK_EQ(block_upload(0x2019, 0, b, sizeof b, &n, 4, 0, 0), 0);
    CHECK_EQ(n, 8);
    /* at or below the protocol switch threshold the node answers with a plain upload */
    CHECK_EQ(block_upload(0x2007, 0, b, sizeof b, &n, 4, 4, 0), 0x40);
    CHECK_EQ(le32(b), 0x180u + NID);
    /* the end frame's n: all 7 bytes of an empty value's one segment, none after a multiple of 7 */
    CHECK_EQ(download(0x2009, 0, "", 0), 0);
    CHECK_EQ(block_upload(0x2009, 0, b, sizeof b, &n, 4, 0, 0), 0);
    CHECK_EQ(n, 0);
    CHECK_EQ(download(0x2009, 0, "seven!!", 7), 0);
    CHECK_EQ(block_upload(0x2009, 0, b, sizeof b, &n, 4, 0, 0), 0);
    CHECK_EQ(n, 7);
    CHECK_EQ(download(0x2009, 0, "fourteen chars", 14), 0);
    CHECK_EQ(block_upload(0x2009, 0, b, sizeof b, &n, 2, 0, 1), 0); /* the second segment repeated */
    CHECK_EQ(n, 14);
    CHECK(memcmp(b, "fourteen chars", 14) == 0);

    /* download: strings, numbers, and a lost segment that the client repeats */
    CHECK_EQ(block_download(0x2009, 0, (const uint8_t *)"blockwise", 9, 0, 0), 0);
    CHECK_EQ(strcmp(alltypes_ram.x2009_device_label, "blockwise"), 0);
    CHECK_EQ(block_download(0x2009, 0, (const uint8_t *)text, 40, 0, 0), 0);
    CHECK_EQ(strcmp(alltypes_ram.x2009_device_label, text), 0);
    CHECK_EQ(block_download(0x2009, 0, (const uint8_t *)"lost one, sent again", 20, 2, 0), 0);
    CHECK_EQ(strcmp(alltypes_ram.x2009_device_label, "lost one, sent again"), 0);
    CHECK_EQ(block_download(0x2019, 0, u64, 8, 0, 0), 0);
    CHECK_EQ(alltypes_persist_app.x2019_uint64_value, 0x0102030405060708u);
    CHECK_EQ(block_download(0x2005, 0, u64, 1, 0, 0), 0);
    CHECK_EQ(alltypes_persist_comm.x2005_uint8_value, 8);
    /* the dictionary's checks apply */
    CHECK_EQ(block_download(0x2005, 0, (const uint8_t *)"\xFF", 1, 0, 0), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(block_download(0x2100, 0, u64, 4, 0, 0), ODG_ABORT_READ_ONLY);
    CHECK_EQ(block_upload(0x2102, 0, b, sizeof b, &n, 4, 0, 0), ODG_ABORT_WRITE_ONLY);
    STILL_SERVING();
}

static void test_aborts(void)
{
    uint8_t b[64];
    uint32_t n;
    const odg_frame_t *r;
    start_node(&alltypes, NULL);
    CHECK_EQ(download_u32(0x1017, 0, 0, 2), 0); /* no heartbeats among the frames counted */

    /* from the dictionary */
    CHECK_EQ(upload(0x3000, 0, b, sizeof b, &n), ODG_ABORT_NO_OBJECT);
    CHECK_EQ(upload(0x2103, 2, b, sizeof b, &n), ODG_ABORT_NO_SUB);
    CHECK_EQ(upload(0x2102, 0, b, sizeof b, &n), ODG_ABORT_WRITE_ONLY);
    CHECK_EQ(download_u32(0x2100, 0, 1, 4), ODG_ABORT_READ_ONLY);
    CHECK_EQ(download_u32(0x2002, 0, 101, 1), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(download_u32(0x2002, 0, 0x9B, 1), ODG_ABORT_VALUE_LOW); /* -101 */
    CHECK_EQ(download_u32(0x2004, 0, 1, 2), ODG_ABORT_TOO_SHORT);
    CHECK_EQ(download(0x2005, 0, "\1\2\3\4\5", 5), ODG_ABORT_TOO_LONG);
    CHECK_EQ(download_u32(0x2001, 0, 2, 1), ODG_ABORT_VALUE_RANGE);
    /* the abort names index and sub-index */
    r = sdo(0x40, IDX(0x3000), 7, 0, 0, 0, 0);
    CHECK_EQ(r->data[1] | r->data[2] << 8, 0x3000);
    CHECK_EQ(r->data[3], 7);
    CHECK_EQ(r->len, 8);

    /* unknown or misplaced command specifiers */
    CHECK_EQ(abort_of(sdo(0xE0, IDX(0x1000), 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND);
    CHECK_EQ(abort_of(sdo(0x60, 0, 0, 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND); /* segment, no transfer */
    CHECK_EQ(abort_of(sdo(0xA3, IDX(0x1000), 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND);
    CHECK_EQ(abort_of(sdo(0xC1, IDX(0x1000), 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND);
    CHECK_EQ(sdo(0x21, IDX(0x2009), 0, 20, 0, 0, 0)->data[0], 0x60);
    CHECK_EQ(abort_of(sdo(0x60, 0, 0, 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND); /* upload request */
    CHECK_EQ(sdo(0x40, IDX(0x2009), 0, 0, 0, 0, 0)->data[0], 0x41);
    CHECK_EQ(abort_of(sdo(0x00, 1, 2, 3, 4, 5, 6, 7)), ODG_ABORT_COMMAND); /* download segment */
    STILL_SERVING();

    /* wrong toggle bits */
    CHECK_EQ(sdo(0x21, IDX(0x2009), 0, 20, 0, 0, 0)->data[0], 0x60);
    CHECK_EQ(sdo(0x00, 'a', 'b', 'c', 'd', 'e', 'f', 'g')->data[0], 0x20);
    r = sdo(0x00, 'a', 'b', 'c', 'd', 'e', 'f', 'g');
    CHECK_EQ(abort_of(r), ODG_ABORT_TOGGLE);
    CHECK_EQ(r->data[1] | r->data[2] << 8, 0x2009);
    CHECK_EQ(sdo(0x40, IDX(0x2009), 0, 0, 0, 0, 0)->data[0], 0x41);
    CHECK_EQ(abort_of(sdo(0x70, 0, 0, 0, 0, 0, 0, 0)), ODG_ABORT_TOGGLE);
    STILL_SERVING();

    /* frames shorter than 8 bytes */
    clear();
    rx(SDO_RX, 0x40, IDX(0x1000), 0);
    CHECK_EQ(abort_of(last_id(SDO_TX)), ODG_ABORT_COMMAND);
    CHECK_EQ(last_id(SDO_TX)->data[1] | last_id(SDO_TX)->data[2] << 8, 0x1000);
    clear();
    rx0(SDO_RX);
    CHECK_EQ(abort_of(last_id(SDO_TX)), ODG_ABORT_COMMAND);
    CHECK_EQ(sdo(0x40, IDX(0x2009), 0, 0, 0, 0, 0)->data[0], 0x41); /* mid-transfer */
    clear();
    rx(SDO_RX, 0x60);
    CHECK_EQ(abort_of(last_id(SDO_TX)), ODG_ABORT_COMMAND);
    CHECK_EQ(last_id(SDO_TX)->data[1] | last_id(SDO_TX)->data[2] << 8, 0x2009);
    CHECK_EQ(abort_of(sdo(0x60, 0, 0, 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND); /* the transfer ended */
    STILL_SERVING();

    /* timeouts: segmented download, segmented upload, block upload waiting for its ack */
    CHECK_EQ(sdo(0x21, IDX(0x2009), 0, 20, 0, 0, 0)->data[0], 0x60);
    sdo_times_out();
    CHECK_EQ(sdo(0x40, IDX(0x2009), 0, 0, 0, 0, 0)->data[0], 0x41);
    run_ms(600);
    CHECK_EQ(sdo(0x60, 0, 0, 0, 0, 0, 0, 0)->data[0] & 0xF0u, 0x00); /* a frame restarts the clock */
    clear();
    run_ms(999);
    CHECK_EQ(n_sent, 0);
    after(5);
    CHECK_EQ(abort_of(last_id(SDO_TX)), ODG_ABORT_TIMEOUT);
    CHECK_EQ(sdo(0xA4, IDX(0x2009), 0, 2, 0, 0, 0)->data[0], 0xC6);
    clear();
    rx(SDO_RX, 0xA3, 0, 0, 0, 0, 0, 0, 0);
    CHECK_EQ(n_sent, 2);
    clear();
    after(1000);
    CHECK_EQ(abort_of(last_id(SDO_TX)), ODG_ABORT_TIMEOUT);
    /* and a block download in the middle of a sub-block */
    CHECK_EQ(sdo(0xC6, IDX(0x2009), 0, 20, 0, 0, 0)->data[0], 0xA4);
    clear();
    rx(SDO_RX, 0x01, 'a', 'b', 'c', 'd', 'e', 'f', 'g');
    after(999);
    CHECK_EQ(n_sent, 0);
    after(1);
    CHECK_EQ(abort_of(last_id(SDO_TX)), ODG_ABORT_TIMEOUT);
    STILL_SERVING();

    /* the client aborts: the transfer is dropped without an answer */
    CHECK_EQ(sdo(0x40, IDX(0x2009), 0, 0, 0, 0, 0)->data[0], 0x41);
    clear();
    rx(SDO_RX, 0x80, IDX(0x2009), 0, 0, 0, 4, 5);
    CHECK_EQ(n_sent, 0);
    run_ms(2000);
    CHECK_EQ(n_sent, 0); /* no timeout either */
    CHECK_EQ(abort_of(sdo(0x60, 0, 0, 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND);
    CHECK_EQ(sdo(0xC6, IDX(0x2009), 0, 20, 0, 0, 0)->data[0], 0xA4);
    clear();
    rx(SDO_RX, 0x01, 'a', 'b', 'c', 'd', 'e', 'f', 'g');
    rx(SDO_RX, 0x80, IDX(0x2009), 0, 0, 0, 4, 5); /* in a sub-block: c = 1 with seq 0 */
    CHECK_EQ(n_sent, 0);
    STILL_SERVING();
    clear();
    rx(SDO_RX, 0x80, IDX(0x2009), 0); /* a short abort frame: ignored as well */
    CHECK_EQ(n_sent, 0);

    /* block download: CRC error (the value stays as it was), bad sequence numbers */
    alltypes_persist_app.x2019_uint64_value = 5;
    CHECK_EQ(block_download(0x2019, 0, (const uint8_t *)"12345678", 8, 0, 1), ODG_ABORT_CRC);
    CHECK_EQ(alltypes_persist_app.x2019_uint64_value, 5);
    CHECK_EQ(block_download(0x2009, 0, (const uint8_t *)"a string of 22 letters", 22, 0, 1),
             ODG_ABORT_CRC);
    STILL_SERVING();
    CHECK_EQ(sdo(0xC6, IDX(0x2009), 0, 20, 0, 0, 0)->data[0], 0xA4);
    CHECK_EQ(abort_of(sdo(0x00, 'a', 'b', 'c', 'd', 'e', 'f', 'g')), ODG_ABORT_SEQUENCE);
    /* more data than the size indicated */
    CHECK_EQ(sdo(0xC6, IDX(0x2009), 0, 3, 0, 0, 0)->data[0], 0xA4);
    clear();
    rx(SDO_RX, 0x01, 'a', 'b', 'c', 'd', 'e', 'f', 'g');
    rx(SDO_RX, 0x82, 'a', 'b', 'c', 'd', 'e', 'f', 'g');
    CHECK_EQ(abort_of(last_id(SDO_TX)), ODG_ABORT_TOO_LONG);
    /* fewer than indicated (no CRC this time: 0xC2) */
    CHECK_EQ(sdo(0xC2, IDX(0x2005), 0, 2, 0, 0, 0)->data[0], 0xA4);
    CHECK_EQ(sdo(0x81, 7, 0, 0, 0, 0, 0, 0)->data[0], 0xA2);
    CHECK_EQ(abort_of(sdo(0xC1 | 6 << 2, 0, 0, 0, 0, 0, 0, 0)), ODG_ABORT_TOO_SHORT);
    /* a wrong end frame */
    CHECK_EQ(sdo(0xC2, IDX(0x2005), 0, 1, 0, 0, 0)->data[0], 0xA4);
    CHECK_EQ(sdo(0x81, 7, 0, 0, 0, 0, 0, 0)->data[0], 0xA2);
    CHECK_EQ(abort_of(sdo(0xA1, 0, 0, 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND);
    STILL_SERVING();

    /* block upload: block sizes 0 and 128, an ack beyond what was sent, a bad new blksize */
    CHECK_EQ(abort_of(sdo(0xA4, IDX(0x2009), 0, 0, 0, 0, 0)), ODG_ABORT_BLOCK_SIZE);
    CHECK_EQ(abort_of(sdo(0xA4, IDX(0x2009), 0, 128, 0, 0, 0)), ODG_ABORT_BLOCK_SIZE);
    CHECK_EQ(sdo(0xA4, IDX(0x2009), 0, 2, 0, 0, 0)->data[0], 0xC6);
    clear();
    rx(SDO_RX, 0xA3, 0, 0, 0, 0, 0, 0, 0);
    CHECK_EQ(n_sent, 2);
    CHECK_EQ(abort_of(sdo(0xA2, 3, 2, 0, 0, 0, 0, 0)), ODG_ABORT_SEQUENCE);
    CHECK_EQ(sdo(0xA4, IDX(0x2009), 0, 2, 0, 0, 0)->data[0], 0xC6);
    clear();
    rx(SDO_RX, 0xA3, 0, 0, 0, 0, 0, 0, 0);
    CHECK_EQ(abort_of(sdo(0xA2, 2, 0, 0, 0, 0, 0, 0)), ODG_ABORT_BLOCK_SIZE);
    CHECK_EQ(sdo(0xA4, IDX(0x2009), 0, 2, 0, 0, 0)->data[0], 0xC6);
    CHECK_EQ(abort_of(sdo(0xA2, 0, 2, 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND); /* ack before start */
    STILL_SERVING();
}

/* A busy transmit queue: a block upload resumes from the next tick. */
static void test_send_busy(void)
{
    static const char text[] = "thirty-five characters of label...";
    uint8_t got[64];
    uint32_t k = 0, i;
    start_node(&alltypes, NULL);
    CHECK_EQ(download(0x2009, 0, text, 34), 0);
    CHECK_EQ(sdo(0xA4, IDX(0x2009), 0, 5, 0, 0, 0)->data[0], 0xC6);
    clear();
    send_fails = 1;
    rx(SDO_RX, 0xA3, 0, 0, 0, 0, 0, 0, 0);
    CHECK_EQ(n_sent, 0);
    after(1);
    CHECK_EQ(n_sent, 5);
    for (i = 0; i < n_sent && k + 7u <= sizeof got; i++, k += 7u) {
        CHECK_EQ(sent[i].data[0] & 0x7Fu, i + 1u);
        memcpy(got + k, sent[i].data + 1, 7);
    }
    CHECK(memcmp(got, text, 34) == 0);
    CHECK_EQ(sent[4].data[0], 0x85);
    CHECK_EQ(sdo(0xA2, 5, 5, 0, 0, 0, 0, 0)->data[0], 0xC1 | 1 << 2);
    CHECK_EQ(last_id(SDO_TX)->data[1] | last_id(SDO_TX)->data[2] << 8, crc16((const uint8_t *)text, 34));
    clear();
    rx(SDO_RX, 0xA1, 0, 0, 0, 0, 0, 0, 0);
    CHECK_EQ(n_sent, 0);
    STILL_SERVING();
}

static void test_emcy(void)
{
    static const uint8_t vendor[5] = {1, 2, 3, 4, 5};
    start_node(&alltypes, NULL);
    clear();
    CHECK_EQ(odg_node_emcy(&node, 0x3210, 0x05, vendor, 5), 0);
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(sent[0].id, 0x80u + NID); /* no 0x1014: the pre-defined COB-ID */
    CHECK_EQ(sent[0].len, 8);
    CHECK_EQ(sent[0].data[0], 0x10);
    CHECK_EQ(sent[0].data[1], 0x32);
    CHECK_EQ(sent[0].data[2], 0x05);
    CHECK(memcmp(sent[0].data + 3, vendor, 5) == 0);
    CHECK_EQ(upload_u32(0x1001, 0), 0); /* a frame as given: 0x1001 follows the active errors */
    CHECK_EQ(odg_node_error_set(&node, 0x3210, 0, vendor, 2), 0);
    CHECK_EQ(upload_u32(0x1001, 0), 0x05); /* read-only for SDO, updated by the node */
    CHECK_EQ(odg_node_error_clear(&node, 0x3210), 0);
    nmt(ODG_NMT_STOP, NID);
    clear();
    CHECK_EQ(odg_node_emcy(&node, 0x0000, 0x00, NULL, 0), ODG_ABORT_DATA_STATE);
    CHECK_EQ(n_sent, 0);
    CHECK_EQ(alltypes_ram.x1001_error_register, 0);
    nmt(ODG_NMT_START, NID);
    send_fails = 1;
    CHECK_EQ(odg_node_emcy(&node, 0x0000, 0x00, NULL, 0), ODG_ABORT_HARDWARE);
}

static void test_bad_config(void)
{
    odg_node_config_t cfg;
    odg_node_t other;
    memset(&cfg, 0, sizeof cfg);
    cfg.dict = &alltypes;
    cfg.send = fake_send;
    clear();
    cfg.node_id = 0;
    CHECK_EQ(odg_node_init(&other, &cfg), ODG_ABORT_INCOMPATIBLE);
    cfg.node_id = 128;
    CHECK_EQ(odg_node_init(&other, &cfg), ODG_ABORT_INCOMPATIBLE);
    cfg.node_id = 1;
    cfg.send = NULL;
    CHECK_EQ(odg_node_init(&other, &cfg), ODG_ABORT_INCOMPATIBLE);
    CHECK_EQ(n_sent, 0);
    /* node-id 127: boot-up on 0x77F, SDO on 0x67F */
    cfg.send = fake_send;
    cfg.node_id = 127;
    CHECK_EQ(odg_node_init(&other, &cfg), 0);
    CHECK_EQ(sent[0].id, 0x77F);
    CHECK_EQ(other.sdo_rx, 0x67F);
}

int main(void)
{
    test_nmt_and_heartbeat();
    test_persistence();
    test_expedited();
    test_segmented();
    test_block();
    test_aborts();
    test_send_busy();
    test_emcy();
    test_bad_config();
    return done();
}
