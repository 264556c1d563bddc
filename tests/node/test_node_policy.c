/*
 * test_node_policy.c - a node built from a description that contradicts itself where the node can
 * still do what it describes (tests/fixtures/policy/policy-node.eds, docs/generate.md): each
 * contradiction is a warning, and the node behaves as the file says on the bus.
 */
#include "fake.h"
#include "policy_node.h"

#define RPDO1 (0x200u + NID)
#define RPDO2 (0x300u + NID)
#define TPDO1 (0x180u + NID)
#define INVALID 0x80000000u

static uint32_t get_u16(uint16_t index)
{
    uint16_t v = 0;
    CHECK_EQ(odg_get(&policy_node, index, 0, &v, sizeof v), 0);
    return v;
}

/* 0x2000 (INTEGER8, limits 0x00..0xFF read 0..-1) and 0x2001 ($NODEID+0x180 above HighLimit 0x18F
 * at node-ids 16..127): the node starts (its table check passed in start_node), serves the values
 * and refuses writes for their access, as the described device does. */
static void test_read_only_entries_keep_their_values(void)
{
    uint8_t b[4] = {0};
    uint32_t n = 0, v = 0x1FFu;
    CHECK_EQ(upload(0x2000, 0, b, sizeof b, &n), 0);
    CHECK(n == 1u && b[0] == 1u);
    CHECK_EQ(download_u32(0x2000, 0, 0, 1), ODG_ABORT_READ_ONLY);
    CHECK_EQ(upload_u32(0x2001, 0), 0x180u + NID);
    CHECK_EQ(download_u32(0x2001, 0, 0x181u, 4), ODG_ABORT_READ_ONLY);
    /* the application's own writes were never checked against limits (0x2000 is constant: in ROM) */
    CHECK_EQ(odg_set(&policy_node, 0x2001, 0, &v, sizeof v), 0);
    CHECK_EQ(upload_u32(0x2001, 0), 0x1FFu);
}

/* 0x2002 and 0x2004 have PDOMapping=0, but the file's RPDO1 and TPDO1 map them: both PDOs work. */
static void test_default_mappings_are_served(void)
{
    const odg_frame_t *f;
    rx(RPDO1, 0x22, 0x11);
    CHECK_EQ(get_u16(0x2002), 0x1122u);
    clear();
    after(1);
    f = last_id(TPDO1);
    CHECK(f != NULL && f->len == 2u && f->data[0] == 0x34 && f->data[1] == 0x12);
}

/* ... in the direction the file's mapping uses them only. */
static void test_only_in_their_direction(void)
{
    CHECK_EQ(download_u32(0x1800, 1, INVALID | TPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1A00, 0, 0, 1), 0);
    CHECK_EQ(download_u32(0x1A00, 1, 0x20020010, 4), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(download_u32(0x1A00, 1, 0x20040010, 4), 0);
    CHECK_EQ(download_u32(0x1A00, 0, 1, 1), 0);
    CHECK_EQ(download_u32(0x1800, 1, TPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1400, 1, INVALID | RPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1600, 0, 0, 1), 0);
    CHECK_EQ(download_u32(0x1600, 1, 0x20040010, 4), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(download_u32(0x1600, 1, 0x20020010, 4), 0);
    CHECK_EQ(download_u32(0x1600, 0, 1, 1), 0);
    CHECK_EQ(download_u32(0x1400, 1, RPDO1, 4), 0);
}

/* RPDO2 starts disabled with a mapping of the read-only 0x2003: its frames change nothing, enabling
 * it as it is is refused (0x06040043), and once remapped to a writable entry it works. */
static void test_disabled_pdo_with_an_unserved_mapping(void)
{
    rx(RPDO2, 0x01, 0x02);
    CHECK_EQ(get_u16(0x2003), 7u);
    CHECK_EQ(download_u32(0x1401, 1, RPDO2, 4), ODG_ABORT_INCOMPATIBLE);
    CHECK_EQ(upload_u32(0x1401, 1), INVALID | RPDO2);
    rx(RPDO2, 0x01, 0x02);
    CHECK_EQ(get_u16(0x2003), 7u);
    CHECK_EQ(download_u32(0x1601, 0, 0, 1), 0);
    CHECK_EQ(download_u32(0x1601, 1, 0x20030010, 4), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(download_u32(0x1601, 1, 0x20050010, 4), 0);
    CHECK_EQ(download_u32(0x1601, 0, 1, 1), 0);
    CHECK_EQ(download_u32(0x1401, 1, RPDO2, 4), 0);
    rx(RPDO2, 0x44, 0x33);
    CHECK_EQ(get_u16(0x2005), 0x3344u);
    CHECK_EQ(get_u16(0x2003), 7u);
}

int main(void)
{
    start_node(&policy_node, NULL);
    test_read_only_entries_keep_their_values();
    nmt(ODG_NMT_START, NID);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);
    test_default_mappings_are_served();
    test_only_in_their_direction();
    test_disabled_pdo_with_an_unserved_mapping();
    return done();
}
