/*
 * test_node_noblock.c - the SDO server built without block transfer: the alltypes dictionary
 * generated with tests/node/noblock-node.toml ([node] sdo_block = false) and built with
 * nothing but -DODG_CONFIG='"noblock_node_config.h"'. Every block initiate, download or
 * upload, with or without CRC or size, is answered with abort 0x05040001 naming its index
 * and sub-index, the server stays idle, and expedited and segmented transfers still work.
 */
#include <string.h>

#include "fake.h"
#include "noblock_node.h"

/* The server answers a plain upload of 0x1000 (idle, nothing left over). */
static void still_serving(void)
{
    CHECK_EQ(sdo(0x40, IDX(0x1000), 0, 0, 0, 0, 0)->data[0], 0x43);
}

static void test_built_without_block(void)
{
    CHECK_EQ(ODG_NODE_SDO_BLOCK, 0);
}

/* Each command byte a client may open a block transfer with. */
static void test_block_initiate_refused(void)
{
    static const uint8_t initiates[] = {
        0xC0, 0xC2, 0xC4, 0xC6, /* block download: size indicated or not, CRC or not */
        0xA0, 0xA4,             /* block upload: CRC or not */
    };
    const odg_frame_t *r;
    unsigned k;
    uint8_t b[8];
    uint32_t n;
    start_node(&noblock_node, NULL);
    for (k = 0; k < sizeof initiates; k++) {
        r = sdo(initiates[k], IDX(0x2009), 3, 20, 0, 0, 0);
        CHECK_EQ(abort_of(r), ODG_ABORT_COMMAND);
        CHECK_EQ(r->data[1] | r->data[2] << 8, 0x2009);
        CHECK_EQ(r->data[3], 3);
        /* nothing was started: a segment or block segment is no transfer's */
        CHECK_EQ(abort_of(sdo(0x01, 'a', 'b', 'c', 'd', 'e', 'f', 'g')), ODG_ABORT_COMMAND);
        still_serving();
    }
    /* the block client's later frames, with no transfer */
    CHECK_EQ(abort_of(sdo(0xA3, 0, 0, 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND);
    CHECK_EQ(abort_of(sdo(0xA2, 1, 4, 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND);
    CHECK_EQ(abort_of(sdo(0xC1, 0, 0, 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND);
    /* the index is not looked at first: an unknown object still answers 0x05040001 */
    CHECK_EQ(abort_of(sdo(0xA4, IDX(0x3000), 0, 4, 0, 0, 0)), ODG_ABORT_COMMAND);
    /* a block initiate in the middle of a segmented transfer ends it */
    CHECK_EQ(sdo(0x40, IDX(0x2009), 0, 0, 0, 0, 0)->data[0], 0x41);
    CHECK_EQ(abort_of(sdo(0xA4, IDX(0x2009), 0, 4, 0, 0, 0)), ODG_ABORT_COMMAND);
    CHECK_EQ(abort_of(sdo(0x60, 0, 0, 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND);
    still_serving();
    /* no timeout follows a refused initiate */
    clear();
    run_ms(2000);
    CHECK_EQ(count_id(SDO_TX), 0);
    CHECK_EQ(upload(0x2009, 0, b, sizeof b, &n), 0);
}

static void test_expedited_and_segmented(void)
{
    static const char label[] = "a label of forty characters, exactly!!!!";
    uint8_t b[64], u64[8] = {1, 2, 3, 4, 5, 6, 7, 0x88};
    uint32_t n;
    start_node(&noblock_node, NULL);
    CHECK_EQ(upload_u32(0x2007, 0), 0x180u + NID); /* expedited upload */
    CHECK_EQ(download_u32(0x2006, 0, 0x1234, 2), 0);
    CHECK_EQ(upload_u32(0x2006, 0), 0x1234);
    CHECK_EQ(download(0x2009, 0, label, 40), 0);
    CHECK_EQ(upload(0x2009, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, 40);
    CHECK(memcmp(b, label, 40) == 0);
    CHECK_EQ(download_segmented(0x2009, 0, (const uint8_t *)"twelve chars", 12, 0), ODG_ABORT_OUT_OF_MEMORY);
    CHECK_EQ(download(0x2019, 0, u64, 8), 0);
    CHECK_EQ(upload(0x2019, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, 8);
    CHECK(memcmp(b, u64, 8) == 0);
    CHECK_EQ(download(0x200E, 0, "0123456789ABCDEF", 16), 0);
    CHECK_EQ(upload(0x200E, 0, b, sizeof b, &n), 0);
    CHECK_EQ(n, 16);
    CHECK(memcmp(b, "0123456789ABCDEF", 16) == 0);
    CHECK_EQ(download(0x2009, 0, label, 41), ODG_ABORT_TOO_LONG);
    /* the segment rules and the timeout are those of a server with block transfer */
    CHECK_EQ(sdo(0x21, IDX(0x2009), 0, 20, 0, 0, 0)->data[0], 0x60);
    CHECK_EQ(abort_of(sdo(0x10, 'a', 'b', 'c', 'd', 'e', 'f', 'g')), ODG_ABORT_TOGGLE);
    CHECK_EQ(sdo(0x40, IDX(0x2009), 0, 0, 0, 0, 0)->data[0], 0x41);
    sdo_times_out();
    still_serving();
}

int main(void)
{
    test_built_without_block();
    test_block_initiate_refused();
    test_expedited_and_segmented();
    return done();
}
