/*
 * test_node_can.c - the CAN controller's state reported by the driver (odg_node_can_state):
 * error passive (EMCY 0x8120, error register, 0x1003), bus-off (0x1029 sub 1), recovery from
 * bus-off (EMCY 0x8140), receive overrun (EMCY 0x8110), and resets, against the pdo_node
 * dictionary (tests/node/pdo-node.eds: 0x1003 with 3 entries, 0x1015 = 0, 0x1029 sub 1).
 */
#include "fake.h"
#include "pdo_node.h"

#define EMCY (0x80u + NID)

static int emcy_is(const odg_frame_t *f, uint16_t code, uint8_t reg)
{
    return f != NULL && f->id == EMCY && f->len == 8u && f->data[0] == (uint8_t)code &&
           f->data[1] == (uint8_t)(code >> 8) && f->data[2] == reg;
}

static uint8_t error_register(void)
{
    uint8_t reg = 0xEE;
    (void)odg_get_u8(&pdo_node, 0x1001, 0, &reg);
    return reg;
}

static void operational(uint8_t behaviour)
{
    start_node(&pdo_node, NULL);
    CHECK_EQ(download_u32(0x1029, 1, behaviour, 1), 0);
    nmt(ODG_NMT_START, NID);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);
    run_ms(5);
    clear();
}

static void test_error_passive(void)
{
    operational(0);
    odg_node_can_state(&node, ODG_CAN_ERROR_PASSIVE);
    CHECK_EQ(n_sent, 1);
    CHECK(emcy_is(&sent[0], 0x8120, 0x11)); /* generic + communication */
    CHECK_EQ(error_register(), 0x11);
    CHECK_EQ(upload_u32(0x1003, 1) & 0xFFFFu, 0x8120);
    clear();
    odg_node_can_state(&node, ODG_CAN_ERROR_PASSIVE); /* again: nothing */
    CHECK_EQ(n_sent, 0);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL); /* not a communication error */
    odg_node_can_state(&node, ODG_CAN_ERROR_ACTIVE);
    CHECK_EQ(n_sent, 1);
    CHECK(emcy_is(&sent[0], 0x0000, 0x00)); /* error reset: the last error is gone */
    CHECK_EQ(error_register(), 0);
    clear();
    odg_node_can_state(&node, ODG_CAN_ERROR_ACTIVE);
    CHECK_EQ(n_sent, 0);
}

static void test_bus_off(void)
{
    /* 0x1029 sub 1 = 0: operational -> pre-operational; nothing is sent about it (off the bus) */
    operational(0);
    odg_node_can_state(&node, ODG_CAN_ERROR_PASSIVE);
    clear();
    odg_node_can_state(&node, ODG_CAN_BUS_OFF);
    CHECK_EQ(n_sent, 0);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL);
    /* recovered: EMCY 0x8140 (an event), then 0x8120 is gone: error reset */
    odg_node_can_state(&node, ODG_CAN_ERROR_ACTIVE);
    CHECK_EQ(n_sent, 2);
    CHECK(emcy_is(&sent[0], 0x8140, 0x11));
    CHECK(emcy_is(&sent[1], 0x0000, 0x00));
    CHECK_EQ(error_register(), 0);
    CHECK_EQ(upload_u32(0x1003, 1) & 0xFFFFu, 0x8140);
    CHECK_EQ(upload_u32(0x1003, 2) & 0xFFFFu, 0x8120);
    /* bus-off straight from error active, back to error passive: 0x8140, and 0x8120 stays */
    nmt(ODG_NMT_START, NID);
    odg_node_can_state(&node, ODG_CAN_BUS_OFF);
    clear();
    odg_node_can_state(&node, ODG_CAN_ERROR_PASSIVE);
    CHECK_EQ(n_sent, 2);
    CHECK(emcy_is(&sent[0], 0x8140, 0x00));
    CHECK(emcy_is(&sent[1], 0x8120, 0x11));
    /* 0x1029 sub 1 = 2: stopped; = 1: no change */
    operational(2);
    odg_node_can_state(&node, ODG_CAN_BUS_OFF);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_STOPPED);
    odg_node_can_state(&node, ODG_CAN_ERROR_ACTIVE);
    operational(1);
    odg_node_can_state(&node, ODG_CAN_BUS_OFF);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);
    odg_node_can_state(&node, ODG_CAN_ERROR_ACTIVE);
}

static void test_overrun_and_resets(void)
{
    operational(0);
    odg_node_can_state(&node, ODG_CAN_RX_OVERRUN);
    CHECK_EQ(n_sent, 1);
    CHECK(emcy_is(&sent[0], 0x8110, 0x00)); /* an event: the register is unchanged */
    CHECK_EQ(error_register(), 0);
    clear();
    odg_node_can_state(&node, ODG_CAN_RX_OVERRUN); /* each overrun is reported */
    CHECK_EQ(n_sent, 1);
    /* a reset of communication forgets 0x8120; the controller still being error passive, the
     * node raises it again after the boot-up */
    odg_node_can_state(&node, ODG_CAN_ERROR_PASSIVE);
    clear();
    nmt(ODG_NMT_RESET_COMM, NID);
    CHECK_EQ(n_sent, 2);
    CHECK_EQ(sent[0].id, 0x700u + NID);
    CHECK(emcy_is(&sent[1], 0x8120, 0x11));
    CHECK_EQ(error_register(), 0x11);
    odg_node_can_state(&node, ODG_CAN_ERROR_ACTIVE);
    CHECK_EQ(error_register(), 0);
    clear();
    nmt(ODG_NMT_RESET_NODE, NID); /* error active: nothing after the boot-up */
    CHECK_EQ(n_sent, 1);
}

int main(void)
{
    test_error_passive();
    test_bus_off();
    test_overrun_and_resets();
    return done();
}
