/*
 * test_node_short.c - a short PDO mapping, served as CANopenNode serves it: a 64-bit entry
 * mapped with 32 bits carries its low-order four bytes (runtime/odg_pdo.c). Against the
 * pdo_node dictionary (tests/node/pdo-node.eds): 0x2003 is UNSIGNED64 rw, PDO-mappable.
 */
#include <string.h>

#include "fake.h"
#include "pdo_node.h"

#define TPDO1 (0x180u + NID)
#define RPDO1 (0x200u + NID)
#define INVALID 0x80000000u

static void remap(uint16_t comm, uint16_t map, uint32_t cob, uint32_t entry)
{
    CHECK_EQ(download_u32(comm, 1, INVALID | cob, 4), 0);
    CHECK_EQ(download_u32(map, 0, 0, 1), 0);
    CHECK_EQ(download_u32(map, 1, entry, 4), 0);
    CHECK_EQ(download_u32(map, 0, 1, 1), 0);
    CHECK_EQ(download_u32(comm, 1, cob, 4), 0);
}

static void test_tpdo_sends_the_low_part(void)
{
    const odg_frame_t *f;
    remap(0x1800, 0x1A00, TPDO1, 0x20030020);
    pdo_node_x2003_u64_value = UINT64_C(0x1122334455667788);
    clear();
    after(1);
    f = last_id(TPDO1);
    CHECK(f != NULL && f->len == 4u);
    CHECK(f != NULL && f->data[0] == 0x88 && f->data[1] == 0x77 && f->data[2] == 0x66 && f->data[3] == 0x55);
}

static void test_rpdo_writes_the_low_part_and_keeps_the_rest(void)
{
    remap(0x1400, 0x1600, RPDO1, 0x20030020);
    pdo_node_x2003_u64_value = UINT64_C(0x1122334455667788);
    rx(RPDO1, 0xAA, 0xBB, 0xCC, 0xDD);
    CHECK(pdo_node_x2003_u64_value == UINT64_C(0x11223344DDCCBBAA));
}

static void test_other_short_lengths_stay_refused(void)
{
    CHECK_EQ(download_u32(0x1800, 1, INVALID | TPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1A00, 0, 0, 1), 0);
    CHECK_EQ(download_u32(0x1A00, 1, 0x20030010, 4), ODG_ABORT_NOT_MAPPABLE); /* 64-bit entry, 16 bits */
    CHECK_EQ(download_u32(0x1A00, 1, 0x20020010, 4), ODG_ABORT_NOT_MAPPABLE); /* 32-bit entry, 16 bits */
    CHECK_EQ(download_u32(0x1A00, 1, 0x20030040, 4), 0);
}

int main(void)
{
    start_node(&pdo_node, NULL);
    nmt(ODG_NMT_START, NID);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);
    test_tpdo_sends_the_low_part();
    test_rpdo_writes_the_low_part_and_keeps_the_rest();
    test_other_short_lengths_stay_refused();
    return done();
}
