/*
 * test_node_wide.c - a node sized by its dictionary alone: built with nothing but
 * -DODG_CONFIG='"wide_node_config.h"', against tests/node/wide-node.eds:
 *
 *   TPDO1 0x180+id  type 255  0x2000 sub1..32, BOOLEAN, one bit each (32 mapping entries)
 *   TPDO2..8        type 255  0x2002 sub2..8, one byte each
 *   RPDO1 0x200+id  type 255  0x2001 sub1..32, BOOLEAN, one bit each (32 mapping entries)
 *   RPDO2..8        type 255  0x2003 sub2..8, one byte each
 *
 * Every PDO is served: the TPDOs all go out when the node starts and again when a mapped value
 * changes, and every RPDO's bytes land in the dictionary.
 */
#include "fake.h"
#include "wide_node.h"

static const uint32_t tpdo_cob[8] = {0x180, 0x280, 0x380, 0x480, 0x1C0, 0x2C0, 0x3C0, 0x4C0};
static const uint32_t rpdo_cob[8] = {0x200, 0x300, 0x400, 0x500, 0x240, 0x340, 0x440, 0x4E0};
static const uint32_t pattern = 0xA5C3F00Fu; /* bit n: sub n + 1 */

static void test_sized_by_the_dictionary(void)
{
    CHECK_EQ(ODG_NODE_MAX_TPDO, 8);
    CHECK_EQ(ODG_NODE_MAX_RPDO, 8);
    CHECK_EQ(ODG_NODE_MAX_MAP, 32);
    CHECK_EQ(ODG_NODE_COMM_BYTES, odg_node_comm_bytes(&wide_node));
    CHECK_EQ(ODG_NODE_LSS, 0);
}

static void test_every_tpdo(void)
{
    uint8_t k;
    start_node(&wide_node, NULL);
    for (k = 0; k < 32u; k++) {
        CHECK_EQ(odg_set_u8(&wide_node, 0x2000, (uint8_t)(k + 1u), (uint8_t)(pattern >> k & 1u)), 0);
    }
    for (k = 2; k <= 8u; k++) {
        CHECK_EQ(odg_set_u8(&wide_node, 0x2002, k, (uint8_t)(0x10u * k)), 0);
    }
    nmt(ODG_NMT_START, NID);
    after(1);
    for (k = 0; k < 8u; k++) {
        CHECK_EQ_AT(count_id(tpdo_cob[k] + NID), 1, k);
    }
    CHECK_EQ(last_id(tpdo_cob[0] + NID)->len, 4);
    CHECK_EQ(le32(last_id(tpdo_cob[0] + NID)->data), pattern);
    for (k = 1; k < 8u; k++) {
        CHECK_EQ_AT(last_id(tpdo_cob[k] + NID)->len, 1, k);
        CHECK_EQ_AT(last_id(tpdo_cob[k] + NID)->data[0], 0x10u * (k + 1u), k);
    }
    /* the 32nd entry of the widest mapping is served: a change of it sends TPDO1 */
    clear();
    CHECK_EQ(odg_set_u8(&wide_node, 0x2000, 32, 0), 0);
    after(1);
    CHECK_EQ(count_id(tpdo_cob[0] + NID), 1);
    CHECK_EQ(le32(last_id(tpdo_cob[0] + NID)->data), pattern & 0x7FFFFFFFu);
    /* and the 8th TPDO */
    clear();
    CHECK_EQ(odg_set_u8(&wide_node, 0x2002, 8, 0x99), 0);
    after(1);
    CHECK_EQ(count_id(tpdo_cob[7] + NID), 1);
    CHECK_EQ(n_sent, 1);
}

static void test_every_rpdo(void)
{
    uint8_t k, v;
    start_node(&wide_node, NULL);
    nmt(ODG_NMT_START, NID);
    rx(rpdo_cob[0] + NID, (uint8_t)pattern, (uint8_t)(pattern >> 8), (uint8_t)(pattern >> 16),
       (uint8_t)(pattern >> 24));
    for (k = 0; k < 32u; k++) {
        CHECK_EQ(odg_get_u8(&wide_node, 0x2001, (uint8_t)(k + 1u), &v), 0);
        CHECK_EQ_AT(v, pattern >> k & 1u, k);
    }
    for (k = 1; k < 8u; k++) {
        rx(rpdo_cob[k] + NID, (uint8_t)(0x20u + k));
    }
    for (k = 2; k <= 8u; k++) {
        CHECK_EQ(odg_get_u8(&wide_node, 0x2003, k, &v), 0);
        CHECK_EQ_AT(v, 0x20u + k - 1u, k);
    }
}

/* The SDO server of a build whose values are all numbers of at most 4 bytes (no strings,
 * domains or types wider than 32 bits: odg_sdo.c then builds no segmented upload): every upload
 * is expedited with its size, segmented downloads of numbers still work, sized or not, and a
 * download announced longer than 8 bytes, or an unsized one going beyond 8 bytes, is refused;
 * an upload segment request finds no transfer under way. */
static void test_sdo_numbers_only(void)
{
    static const uint8_t two[2] = {0x34, 0x12}, nine[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    start_node(&wide_node, NULL);
    CHECK_EQ(ODG_CFG_STRINGS | ODG_CFG_UNICODE | ODG_CFG_DOMAINS | ODG_CFG_INT64, 0);
    CHECK_EQ(sdo(0x40, IDX(0x1000), 0, 0, 0, 0, 0)->data[0], 0x43); /* 4 bytes */
    CHECK_EQ(sdo(0x40, IDX(0x1017), 0, 0, 0, 0, 0)->data[0], 0x4B); /* 2 bytes */
    CHECK_EQ(sdo(0x40, IDX(0x1001), 0, 0, 0, 0, 0)->data[0], 0x4F); /* 1 byte */
    CHECK_EQ(download_segmented(0x1017, 0, two, 2, 1), 0);
    CHECK_EQ(upload_u32(0x1017, 0), 0x1234);
    CHECK_EQ(download_u32(0x1017, 0, 0, 2), 0);
    CHECK_EQ(download_segmented(0x1017, 0, two, 2, 0), 0);
    CHECK_EQ(upload_u32(0x1017, 0), 0x1234);
    CHECK_EQ(download_segmented(0x1017, 0, nine, 9, 1), ODG_ABORT_TOO_LONG);
    CHECK_EQ(download_segmented(0x1017, 0, nine, 9, 0), ODG_ABORT_OUT_OF_MEMORY);
    CHECK_EQ(upload_u32(0x1017, 0), 0x1234);
    CHECK_EQ(abort_of(sdo(0x60, 0, 0, 0, 0, 0, 0, 0)), ODG_ABORT_COMMAND);
}

int main(void)
{
    test_sized_by_the_dictionary();
    test_every_tpdo();
    test_every_rpdo();
    test_sdo_numbers_only();
    return done();
}
