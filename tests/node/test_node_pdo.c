/*
 * test_node_pdo.c - SYNC, TPDOs, RPDOs, PDO remapping by SDO and EMCY, communication
 * parameters set by the application (odg_set), against the pdo_node
 * dictionary generated at test time from tests/node/pdo-node.eds:
 *
 *   TPDO1 0x180+id  type 255, no timers    0x2000 u8, 0x2001 u16
 *   TPDO2 0x280+id  type 3 (every 3rd SYNC) 0x2002 u32
 *   TPDO3 invalid   type 0                 (nothing mapped)
 *   RPDO1 0x200+id  type 255               0x2005 i16 (-100..100), 0x2004 sub1/sub2 1 bit each
 *   RPDO2 0x300+id  type 1                 0x2002 u32 (static mapping: 0x1601 read-only)
 *   0x1005 = 0x80, 0x1014 = 0x80+id, 0x1017 = 0, eight mapping entries per PDO
 */
#include <stdio.h>
#include <string.h>

#include "fake.h"
#include "pdo_node.h"

#define TPDO1 (0x180u + NID)
#define TPDO2 (0x280u + NID)
#define TPDO3 (0x380u + NID)
#define RPDO1 (0x200u + NID)
#define RPDO2 (0x300u + NID)
#define EMCY (0x80u + NID)
#define INVALID 0x80000000u

static void sync0(void)
{
    rx0(0x80);
}

static void operational(void)
{
    start_node(&pdo_node, NULL);
    nmt(ODG_NMT_START, NID);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);
}

static int frame_is(const odg_frame_t *f, const uint8_t *data, unsigned len)
{
    return f->id != 0u && f->len == len && memcmp(f->data, data, len) == 0;
}
#define FRAME_IS(f, ...) \
    frame_is((f), (const uint8_t[]){__VA_ARGS__}, (unsigned)sizeof((const uint8_t[]){__VA_ARGS__}))

static void test_only_when_operational(void)
{
    start_node(&pdo_node, NULL);
    clear();
    sync0();
    run_ms(100);
    CHECK_EQ(n_sent, 0);
    rx(RPDO1, 10, 0, 0);
    CHECK_EQ(pdo_node_x2005_limited_i16, 0);
    nmt(ODG_NMT_START, NID);
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    nmt(ODG_NMT_STOP, NID);
    clear();
    pdo_node_x2000_u8_value = 0x99;
    sync0();
    sync0();
    sync0();
    run_ms(100);
    rx(RPDO1, 10, 0, 0);
    CHECK_EQ(n_sent, 0);
    CHECK_EQ(pdo_node_x2005_limited_i16, 0);
    /* operational again: event-driven TPDOs are sent at once */
    nmt(ODG_NMT_START, NID);
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    CHECK(FRAME_IS(last_id(TPDO1), 0x99, 0x33, 0x22));
}

static void test_event_driven(void)
{
    uint32_t t;
    operational();
    clear();
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    CHECK(FRAME_IS(last_id(TPDO1), 0x11, 0x33, 0x22));
    run_ms(500);
    CHECK_EQ(count_id(TPDO1), 1); /* no change, no event timer */
    /* a change by SDO, or by the application, is sent at the next tick */
    CHECK_EQ(download_u32(0x2000, 0, 0x12, 1), 0);
    clear();
    after(1);
    CHECK(FRAME_IS(last_id(TPDO1), 0x12, 0x33, 0x22));
    pdo_node_x2001_u16_value = 0xBEEF;
    clear();
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    CHECK(FRAME_IS(last_id(TPDO1), 0x12, 0xEF, 0xBE));
    /* event timer (may change while the PDO is valid): every 100 ms */
    CHECK_EQ(download_u32(0x1800, 5, 100, 2), 0);
    clear();
    run_ms(1000);
    CHECK_EQ(count_id(TPDO1), 10); /* at once (reconfigured), then every 100 ms */
    CHECK_EQ(download_u32(0x1800, 5, 0, 2), 0);
    /* inhibit time: only while the PDO is not valid */
    CHECK_EQ(download_u32(0x1800, 3, 500, 2), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1800, 1, INVALID | TPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1800, 3, 500, 2), 0); /* 50 ms */
    CHECK_EQ(download_u32(0x1800, 1, TPDO1, 4), 0);
    clear();
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    pdo_node_x2000_u8_value = 1;
    for (t = 1; t < 50u; t++) {
        after(1);
    }
    CHECK_EQ(count_id(TPDO1), 1);
    after(1);
    CHECK_EQ(count_id(TPDO1), 2);
    CHECK_EQ(last_id(TPDO1)->data[0], 1);
    /* the application asks for a transmission: sent once the inhibit time is over */
    after(20);
    odg_node_tpdo_request(&node, 0);
    CHECK_EQ(count_id(TPDO1), 2);
    after(30);
    CHECK_EQ(count_id(TPDO1), 3);
    after(60);
    odg_node_tpdo_request(&node, 0);
    CHECK_EQ(count_id(TPDO1), 4); /* at once */
    /* a busy transmit queue: the event stays pending */
    pdo_node_x2000_u8_value = 2;
    run_ms(200);
    clear();
    pdo_node_x2000_u8_value = 3;
    send_fails = 1;
    after(1);
    CHECK_EQ(count_id(TPDO1), 0);
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    CHECK_EQ(last_id(TPDO1)->data[0], 3);
}

static void test_sync(void)
{
    unsigned i;
    operational();
    clear();
    for (i = 1; i <= 9u; i++) {
        sync0();
        CHECK_EQ_AT(count_id(TPDO2), i / 3u, i);
    }
    CHECK(FRAME_IS(last_id(TPDO2), 0x77, 0x66, 0x55, 0x44));
    run_ms(1000);
    CHECK_EQ(count_id(TPDO2), 3); /* only SYNC sends it */
    /* SYNC start value: with a counter in the SYNC, start at counter 2 */
    CHECK_EQ(download_u32(0x1801, 6, 2, 1), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1801, 1, INVALID | TPDO2, 4), 0);
    CHECK_EQ(download_u32(0x1801, 6, 2, 1), 0);
    CHECK_EQ(download_u32(0x1801, 1, TPDO2, 4), 0);
    clear();
    rx(0x80, 1);
    CHECK_EQ(count_id(TPDO2), 0);
    rx(0x80, 2);
    CHECK_EQ(count_id(TPDO2), 1);
    rx(0x80, 3);
    rx(0x80, 4);
    CHECK_EQ(count_id(TPDO2), 1);
    rx(0x80, 5);
    CHECK_EQ(count_id(TPDO2), 2);
    /* type 1: every SYNC, once the start value came again */
    CHECK_EQ(download_u32(0x1801, 2, 1, 1), 0);
    clear();
    rx(0x80, 6);
    CHECK_EQ(count_id(TPDO2), 0);
    rx(0x80, 2);
    rx(0x80, 3);
    CHECK_EQ(count_id(TPDO2), 2);

    /* type 0 (acyclic synchronous): at a SYNC after a change; TPDO3 mapped from scratch */
    CHECK_EQ(download_u32(0x1A02, 1, 0x20070008, 4), 0);
    CHECK_EQ(download_u32(0x1A02, 0, 1, 1), 0);
    CHECK_EQ(download_u32(0x1802, 1, TPDO3, 4), 0);
    clear();
    run_ms(10);
    CHECK_EQ(count_id(TPDO3), 0);
    sync0();
    CHECK_EQ(count_id(TPDO3), 1);
    CHECK(FRAME_IS(last_id(TPDO3), 0x5A));
    sync0();
    CHECK_EQ(count_id(TPDO3), 1);
    pdo_node_x2007_status_input = 0x5B;
    run_ms(10);
    CHECK_EQ(count_id(TPDO3), 1);
    sync0();
    CHECK_EQ(count_id(TPDO3), 2);
    CHECK(FRAME_IS(last_id(TPDO3), 0x5B));
    odg_node_tpdo_request(&node, 2);
    sync0();
    CHECK_EQ(count_id(TPDO3), 3); /* an event without a change */

    /* another SYNC COB-ID */
    CHECK_EQ(download_u32(0x1005, 0, 0x81, 4), 0);
    clear();
    sync0();
    CHECK_EQ(count_id(TPDO2), 0);
    rx0(0x81);
    CHECK_EQ(count_id(TPDO2), 1);
}

static void test_rpdo(void)
{
    operational();
    /* event-driven RPDO: 0x2005 i16 in bits 0..15, flags in bits 16 and 17 */
    rx(RPDO1, 0x32, 0x00, 0x02);
    CHECK_EQ(pdo_node_x2005_limited_i16, 50);
    CHECK_EQ(pdo_node_x2004_flags_s1_flag_1, 0);
    CHECK_EQ(pdo_node_x2004_flags_s2_flag_2, 1);
    rx(RPDO1, 0x9C, 0xFF, 0x01); /* -100 */
    CHECK_EQ(pdo_node_x2005_limited_i16, -100);
    CHECK_EQ(pdo_node_x2004_flags_s1_flag_1, 1);
    CHECK_EQ(pdo_node_x2004_flags_s2_flag_2, 0);
    /* a value beyond the limits is dropped, the others are written */
    rx(RPDO1, 200, 0, 0x03);
    CHECK_EQ(pdo_node_x2005_limited_i16, -100);
    CHECK_EQ(pdo_node_x2004_flags_s2_flag_2, 1);
    /* longer frames are processed */
    rx(RPDO1, 7, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF);
    CHECK_EQ(pdo_node_x2005_limited_i16, 7);
    /* too short: not processed, EMCY 0x8210 once, error reset when it is right again */
    clear();
    rx(RPDO1, 9, 0);
    CHECK_EQ(pdo_node_x2005_limited_i16, 7);
    CHECK_EQ(count_id(EMCY), 1);
    CHECK(FRAME_IS(last_id(EMCY), 0x10, 0x82, 0x11, 0, 0, 0, 0, 0));
    CHECK_EQ(pdo_node_x1001_error_register, 0x11);
    rx(RPDO1, 9, 0);
    CHECK_EQ(count_id(EMCY), 1);
    rx(RPDO1, 9, 0, 0);
    CHECK_EQ(pdo_node_x2005_limited_i16, 9);
    CHECK_EQ(count_id(EMCY), 2);
    CHECK(FRAME_IS(last_id(EMCY), 0, 0, 0, 0, 0, 0, 0, 0));
    CHECK_EQ(pdo_node_x1001_error_register, 0);

    /* synchronous RPDO: applied at the next SYNC */
    rx(RPDO2, 1, 2, 3, 4);
    CHECK_EQ(pdo_node_x2002_u32_value, 0x44556677);
    sync0();
    CHECK_EQ(pdo_node_x2002_u32_value, 0x04030201);
    sync0();
    CHECK_EQ(pdo_node_x2002_u32_value, 0x04030201);
    /* a frame received, then pre-operational: never applied */
    rx(RPDO2, 9, 9, 9, 9);
    nmt(ODG_NMT_ENTER_PREOP, NID);
    nmt(ODG_NMT_START, NID);
    sync0();
    CHECK_EQ(pdo_node_x2002_u32_value, 0x04030201);
}

static void test_remap(void)
{
    operational();
    /* the PDO is valid: no mapping change at all */
    CHECK_EQ(download_u32(0x1A00, 1, 0x20030040, 4), ODG_ABORT_UNSUPPORTED);
    CHECK_EQ(download_u32(0x1A00, 0, 0, 1), ODG_ABORT_UNSUPPORTED);
    /* 1. invalidate */
    CHECK_EQ(download_u32(0x1800, 1, INVALID | TPDO1, 4), 0);
    clear();
    pdo_node_x2000_u8_value = 0x55;
    run_ms(100);
    CHECK_EQ(count_id(TPDO1), 0);
    /* entries only while sub 0 is 0 */
    CHECK_EQ(download_u32(0x1A00, 1, 0x20030040, 4), ODG_ABORT_UNSUPPORTED);
    /* 2. sub 0 = 0 */
    CHECK_EQ(download_u32(0x1A00, 0, 0, 1), 0);
    /* 3. entries: each checked as it is written */
    CHECK_EQ(download_u32(0x1A00, 1, 0x20060020, 4), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(download_u32(0x1A00, 1, 0x30000008, 4), ODG_ABORT_NO_OBJECT);
    CHECK_EQ(download_u32(0x1A00, 1, 0x20040308, 4), ODG_ABORT_NO_SUB);
    CHECK_EQ(download_u32(0x1A00, 1, 0x20000010, 4), ODG_ABORT_NOT_MAPPABLE); /* wrong length */
    CHECK_EQ(download_u32(0x1A00, 1, 0x00050008, 4), ODG_ABORT_NO_OBJECT);   /* dummies: RPDO only */
    CHECK_EQ(download_u32(0x1A00, 1, 0x20030040, 4), 0);
    CHECK_EQ(download_u32(0x1A00, 2, 0x20000008, 4), 0);
    CHECK_EQ(download_u32(0x1A00, 3, 0, 4), 0); /* clearing an entry */
    /* 4. sub 0 = n: at most 64 bits and the entries there are */
    CHECK_EQ(download_u32(0x1A00, 0, 2, 1), ODG_ABORT_PDO_LENGTH);
    CHECK_EQ(download_u32(0x1A00, 0, 3, 1), ODG_ABORT_NO_OBJECT);
    CHECK_EQ(download_u32(0x1A00, 0, 9, 1), ODG_ABORT_PDO_LENGTH);
    CHECK_EQ(download_u32(0x1A00, 0, 1, 1), 0);
    CHECK_EQ(upload_u32(0x1A00, 0), 1);
    /* 5. valid again: sent with the new mapping */
    clear();
    CHECK_EQ(download_u32(0x1800, 1, TPDO1, 4), 0);
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    CHECK(FRAME_IS(last_id(TPDO1), 8, 7, 6, 5, 4, 3, 2, 1));

    /* bit mapping: two 1-bit flags, then a byte at bit 2 */
    CHECK_EQ(download_u32(0x1800, 1, INVALID | TPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1A00, 0, 0, 1), 0);
    CHECK_EQ(download_u32(0x1A00, 1, 0x20040101, 4), 0);
    CHECK_EQ(download_u32(0x1A00, 2, 0x20040201, 4), 0);
    CHECK_EQ(download_u32(0x1A00, 3, 0x20000008, 4), 0);
    CHECK_EQ(download_u32(0x1A00, 0, 3, 1), 0);
    CHECK_EQ(download_u32(0x1800, 1, TPDO1, 4), 0);
    pdo_node_x2004_flags_s1_flag_1 = 0;
    pdo_node_x2004_flags_s2_flag_2 = 1;
    pdo_node_x2000_u8_value = 0xFF;
    clear();
    after(1);
    CHECK(FRAME_IS(last_id(TPDO1), 0xFE, 0x03));

    /* COB-ID: no new CAN-ID while valid; no restricted or 29-bit ones */
    CHECK_EQ(download_u32(0x1800, 1, TPDO1 + 1u, 4), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1800, 1, INVALID | 0x701u, 4), 0);
    CHECK_EQ(download_u32(0x1800, 1, 0x701, 4), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1800, 1, 0x585, 4), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1800, 1, 0x20000186, 4), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1800, 1, 0x40000186, 4), 0); /* bit 30 (no RTR) is fine */
    clear();
    after(1);
    CHECK_EQ(count_id(0x186), 1);
    CHECK_EQ(download_u32(0x1800, 1, 0x186, 4), 0); /* only bit 30 changed */
    /* transmission types 241..251, and 252/253 for an RPDO */
    CHECK_EQ(download_u32(0x1800, 2, 241, 1), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1800, 2, 251, 1), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1400, 2, 253, 1), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1400, 2, 252, 1), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1800, 2, 254, 1), 0);
    CHECK_EQ(download_u32(0x1400, 2, 240, 1), 0);
    CHECK_EQ(download_u32(0x1400, 2, 255, 1), 0);

    /* RPDO: only RPDO-mappable objects; dummies fill gaps */
    CHECK_EQ(download_u32(0x1600, 0, 0, 1), ODG_ABORT_UNSUPPORTED);
    CHECK_EQ(download_u32(0x1400, 1, INVALID | RPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1600, 0, 0, 1), 0);
    CHECK_EQ(download_u32(0x1600, 1, 0x20070008, 4), ODG_ABORT_NOT_MAPPABLE); /* read-only */
    CHECK_EQ(download_u32(0x1600, 1, 0x00050010, 4), ODG_ABORT_NOT_MAPPABLE); /* dummy size */
    CHECK_EQ(download_u32(0x1600, 1, 0x00050008, 4), 0);
    CHECK_EQ(download_u32(0x1600, 2, 0x20000008, 4), 0);
    CHECK_EQ(download_u32(0x1600, 0, 2, 1), 0);
    CHECK_EQ(download_u32(0x1400, 1, RPDO1, 4), 0);
    rx(RPDO1, 0xEE, 0x42);
    CHECK_EQ(pdo_node_x2000_u8_value, 0x42);
}

static void test_emcy_and_resets(void)
{
    operational();
    clear();
    CHECK_EQ(odg_node_emcy(&node, 0x5000, 0x81, (const uint8_t *)"\x01\x02", 2), 0);
    CHECK(FRAME_IS(last_id(EMCY), 0x00, 0x50, 0x81, 1, 2, 0, 0, 0));
    CHECK_EQ(upload_u32(0x1001, 0), 0); /* a frame as given: no error becomes active */
    CHECK_EQ(download_u32(0x1014, 0, 0x90, 4), 0);
    clear();
    CHECK_EQ(odg_node_emcy(&node, 0x5000, 0x81, NULL, 0), 0);
    CHECK_EQ(count_id(0x90), 1);
    CHECK_EQ(download_u32(0x1014, 0, INVALID | 0x90u, 4), 0);
    clear();
    CHECK_EQ(odg_node_emcy(&node, 0x5000, 0x81, NULL, 0), ODG_ABORT_DATA_STATE);
    CHECK_EQ(n_sent, 0);
    /* reset communication: the communication values of the boot again, and the node serves them */
    CHECK_EQ(download_u32(0x1800, 1, INVALID | TPDO1, 4), 0);
    clear();
    nmt(ODG_NMT_RESET_COMM, 0);
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL);
    nmt(ODG_NMT_START, 0);
    after(1);
    CHECK_EQ(count_id(TPDO1), odg_node_comm_bytes(&pdo_node) <= ODG_NODE_COMM_BYTES); /* else kept */
    CHECK_EQ(count_id(EMCY), 0);
    CHECK_EQ(download_u32(0x1800, 1, INVALID | TPDO1, 4), 0);
    /* reset node: the defaults again */
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(upload_u32(0x1001, 0), 0);
    nmt(ODG_NMT_START, 0);
    clear();
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    CHECK_EQ(odg_node_emcy(&node, 0x1000, 0x01, NULL, 0), 0);
    CHECK_EQ(count_id(EMCY), 1);
    /* the application changed a PDO directly: odg_node_reload picks it up */
    pdo_node_ram.x1800_tpdo_communication_parameter_s1_cob_id_used_by_tpdo = INVALID | TPDO1;
    odg_node_reload(&node);
    clear();
    pdo_node_x2000_u8_value = 0x77;
    run_ms(10);
    CHECK_EQ(count_id(TPDO1), 0);
}

/* Reset communication: the values of 0x1000-0x1FFF an SDO client may write come back as they
 * were at boot (here the defaults: RAM only), the application's stay, as do 0x1003 and what
 * odg_node_comm_keep made current. Built with a small ODG_NODE_COMM_BYTES too: the objects
 * past it keep their values. */
static unsigned app_told;

static void app_told_fn(odg_client_t *self, const odg_ref_t *ref)
{
    (void)self;
    app_told += ref == NULL;
}

static void test_reset_communication(void)
{
    static odg_client_t app;
    int all = odg_node_comm_bytes(&pdo_node) <= ODG_NODE_COMM_BYTES;
    CHECK(odg_node_comm_bytes(&pdo_node) > 0u);
    CHECK(all || ODG_NODE_COMM_BYTES < 512u); /* the default holds this dictionary's */
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(odg_node_error_set(&node, 0x5000, 0, NULL, 0), 0);
    CHECK_EQ(download_u32(0x1005, 0, 0x81, 4), 0);
    CHECK_EQ(download_u32(0x1017, 0, 700, 2), 0);
    CHECK_EQ(download_u32(0x1016, 1, 0x00090064u, 4), 0);
    CHECK_EQ(download_u32(0x1029, 1, 2, 1), 0);
    CHECK_EQ(download_u32(0x1800, 1, INVALID | TPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1800, 2, 7, 1), 0);
    CHECK_EQ(download_u32(0x1A00, 0, 0, 1), 0);
    CHECK_EQ(download_u32(0x2000, 0, 0x5A, 1), 0);
    app.changed = app_told_fn;
    odg_attach(&pdo_node, &app);
    app_told = 0;
    nmt(ODG_NMT_RESET_COMM, NID);
    CHECK_EQ(app_told, 1); /* the application hears that any value may have changed */
    CHECK_EQ(upload_u32(0x1005, 0), ODG_NODE_COMM_BYTES >= 4u ? 0x80u : 0x81u); /* the first object */
    CHECK_EQ(upload_u32(0x2000, 0), 0x5A);
    CHECK_EQ(upload_u32(0x1003, 0), 1);     /* the error history is kept ... */
    CHECK_EQ(upload_u32(0x1001, 0), 0x01);  /* ... and the error still active */
    CHECK_EQ(upload_u32(0x1017, 0), all ? 0u : 700u);
    CHECK_EQ(upload_u32(0x1016, 1), all ? 0u : 0x00090064u);
    CHECK_EQ(upload_u32(0x1029, 1), all ? 0u : 2u);
    CHECK_EQ(upload_u32(0x1800, 1), all ? TPDO1 : INVALID | TPDO1);
    CHECK_EQ(upload_u32(0x1800, 2), all ? 255u : 7u);
    CHECK_EQ(upload_u32(0x1A00, 0), all ? 2u : 0u);
    if (all) { /* and served: TPDO1 valid and event-driven again */
        nmt(ODG_NMT_START, NID);
        clear();
        after(1);
        CHECK_EQ(count_id(TPDO1), 1);
    }
    /* what the application configured at start (odg_node_comm_keep) comes back instead */
    CHECK_EQ(odg_set_u16(&pdo_node, 0x1017, 0, 40), ODG_OK);
    odg_node_comm_keep(&node);
    CHECK_EQ(download_u32(0x1017, 0, 90, 2), 0);
    nmt(ODG_NMT_RESET_COMM, NID);
    CHECK_EQ(upload_u32(0x1017, 0), all ? 40u : 90u);
    /* reset node: the defaults, and the start values forgotten */
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(download_u32(0x1017, 0, 90, 2), 0);
    nmt(ODG_NMT_RESET_COMM, NID);
    CHECK_EQ(upload_u32(0x1017, 0), all ? 0u : 90u);
    nmt(ODG_NMT_RESET_NODE, NID);
}

/* The SDO server takes its COB-IDs from 0x1200 at boot and reset communication (read-only for
 * SDO, set here by the application); bit 31 disables it; reset node brings the defaults back. */
static void test_sdo_server_cob_ids(void)
{
    static const uint8_t upload_1000[8] = {0x40, 0x00, 0x10, 0, 0, 0, 0, 0};
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(upload_u32(0x1200, 1), 0x600u + NID);
    CHECK_EQ(upload_u32(0x1200, 2), 0x580u + NID);
    CHECK_EQ(download_u32(0x1200, 1, 0x640, 4), ODG_ABORT_READ_ONLY);
    CHECK_EQ(odg_set_u32(&pdo_node, 0x1200, 1, 0x640), ODG_OK);
    CHECK_EQ(odg_set_u32(&pdo_node, 0x1200, 2, 0x5C0), ODG_OK);
    CHECK_EQ(upload_u32(0x1200, 1), 0x640); /* not yet in force */
    nmt(ODG_NMT_RESET_COMM, NID);
    clear();
    rx_frame(SDO_RX, upload_1000, 8);
    CHECK_EQ(n_sent, 0);
    rx_frame(0x640, upload_1000, 8);
    CHECK_EQ(n_sent, 1);
    CHECK(sent[0].id == 0x5C0 && sent[0].data[0] == 0x43 && sent[0].data[1] == 0x00 && sent[0].data[2] == 0x10);
    CHECK_EQ(odg_set_u32(&pdo_node, 0x1200, 2, INVALID | 0x5C0u), ODG_OK);
    nmt(ODG_NMT_RESET_COMM, NID);
    clear();
    rx_frame(0x640, upload_1000, 8);
    rx_frame(SDO_RX, upload_1000, 8);
    CHECK_EQ(n_sent, 0); /* disabled */
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(upload_u32(0x1200, 1), 0x600u + NID);
}

/* The node hears communication parameters the application sets (odg_set) at once, without
 * odg_node_reload; a write through an odg_ptr pointer only after odg_changed. */
static void test_application_writes(void)
{
    uint32_t *cob;
    operational();
    clear();
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    /* TPDO1 made invalid: a changed mapped value sends nothing */
    CHECK_EQ(odg_set_u32(&pdo_node, 0x1800, 1, INVALID | TPDO1), ODG_OK);
    clear();
    pdo_node_x2000_u8_value = 0x42;
    run_ms(10);
    CHECK_EQ(count_id(TPDO1), 0);
    /* valid again: sent at the first chance */
    CHECK_EQ(odg_set_u32(&pdo_node, 0x1800, 1, TPDO1), ODG_OK);
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    CHECK(FRAME_IS(last_id(TPDO1), 0x42, 0x33, 0x22));
    /* SYNC moved to 0x81: TPDO2 (every 3rd SYNC) counts only those */
    CHECK_EQ(odg_set_u32(&pdo_node, 0x1005, 0, 0x81), ODG_OK);
    clear();
    sync0();
    sync0();
    sync0();
    CHECK_EQ(count_id(TPDO2), 0);
    rx0(0x81);
    rx0(0x81);
    rx0(0x81);
    CHECK_EQ(count_id(TPDO2), 1);
    /* EMCY moved */
    CHECK_EQ(odg_set_u32(&pdo_node, 0x1014, 0, 0x90), ODG_OK);
    clear();
    CHECK_EQ(odg_node_emcy(&node, 0x1000, 0x01, NULL, 0), 0);
    CHECK(count_id(EMCY) == 0 && count_id(0x90) == 1);
    /* behind the dictionary's back: unseen until odg_changed */
    cob = odg_ptr_u32(&pdo_node, 0x1800, 1);
    CHECK(cob != NULL);
    *cob = INVALID | TPDO1;
    clear();
    pdo_node_x2000_u8_value = 0x43;
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    odg_changed(&pdo_node, NULL);
    clear();
    pdo_node_x2000_u8_value = 0x44;
    run_ms(10);
    CHECK_EQ(count_id(TPDO1), 0);
}

/* An application's client stays attached through an NMT reset of the node. */
static unsigned app_heard;

static void app_changed(odg_client_t *self, const odg_ref_t *ref)
{
    (void)self, (void)ref;
    app_heard++;
}

static void test_application_client(void)
{
    static odg_client_t app;
    operational();
    app.changed = app_changed;
    odg_attach(&pdo_node, &app);
    CHECK_EQ(odg_set_u8(&pdo_node, 0x2000, 0, 1), ODG_OK);
    CHECK_EQ(app_heard, 1);
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(odg_set_u8(&pdo_node, 0x2000, 0, 2), ODG_OK);
    CHECK_EQ(app_heard, 2);
    /* and the node itself still hears its parameters */
    nmt(ODG_NMT_START, NID);
    CHECK_EQ(odg_set_u32(&pdo_node, 0x1800, 1, INVALID | TPDO1), ODG_OK);
    clear();
    pdo_node_x2000_u8_value = 0x45;
    run_ms(10);
    CHECK_EQ(count_id(TPDO1), 0);
}

/* A listener that answers a value an RPDO wrote with odg_changed(dict, NULL) makes the node
 * reload its PDOs while the frame is being applied: the values after it still come from the frame. */
static void reload_on_flag_1(odg_client_t *self, const odg_ref_t *ref)
{
    (void)self;
    if (ref != NULL && ref->entry->index == 0x2004u && ref->sub->sub == 1u) {
        odg_changed(&pdo_node, NULL);
    }
}

static void test_rpdo_reloaded_while_applied(void)
{
    static odg_client_t app;
    operational();
    app.changed = reload_on_flag_1;
    odg_attach(&pdo_node, &app);
    rx(RPDO1, 0x34, 0x00, 0x03); /* 0x2005 = 52, flag 1 (the reload), then flag 2 */
    CHECK_EQ(pdo_node_x2005_limited_i16, 52);
    CHECK_EQ(pdo_node_x2004_flags_s1_flag_1, 1);
    CHECK_EQ(pdo_node_x2004_flags_s2_flag_2, 1);
}

/* 0x1003: every EMCY error code enters sub 1, the older ones move down, the oldest falls off
 * past sub 3; sub 0 counts; only 0 may be written to sub 0, and it clears the history. */
static void test_error_history(void)
{
    unsigned k;
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(upload_u32(0x1003, 0), 0);
    CHECK_EQ(odg_node_emcy(&node, 0x8210, 0x11, (const uint8_t *)"\x34\x12", 2), 0);
    CHECK_EQ(upload_u32(0x1003, 0), 1);
    CHECK_EQ(upload_u32(0x1003, 1), 0x12348210u);
    CHECK_EQ(odg_node_emcy(&node, 0, 0, NULL, 0), 0); /* error reset: not an error */
    CHECK_EQ(upload_u32(0x1003, 0), 1);
    for (k = 1; k <= 3; k++) {
        CHECK_EQ(odg_node_emcy(&node, (uint16_t)(0x5000 + k), 0x01, NULL, 0), 0);
    }
    CHECK_EQ(upload_u32(0x1003, 0), 3);
    CHECK_EQ(upload_u32(0x1003, 1), 0x5003);
    CHECK_EQ(upload_u32(0x1003, 2), 0x5002);
    CHECK_EQ(upload_u32(0x1003, 3), 0x5001);
    nmt(ODG_NMT_STOP, NID); /* not sent when stopped, but recorded */
    CHECK_EQ(odg_node_emcy(&node, 0x6000, 0x01, NULL, 0), ODG_ABORT_DATA_STATE);
    nmt(ODG_NMT_ENTER_PREOP, NID);
    CHECK_EQ(upload_u32(0x1003, 1), 0x6000);
    CHECK_EQ(download_u32(0x1003, 1, 0, 4), ODG_ABORT_READ_ONLY);
    CHECK_EQ(download_u32(0x1003, 0, 2, 1), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(upload_u32(0x1003, 0), 3);
    nmt(ODG_NMT_RESET_COMM, NID); /* kept */
    CHECK_EQ(upload_u32(0x1003, 0), 3);
    CHECK_EQ(download_u32(0x1003, 0, 0, 1), 0);
    CHECK_EQ(upload_u32(0x1003, 0), 0);
    CHECK_EQ(upload_u32(0x1003, 1), 0);
    /* a read-only (static) mapping of a valid PDO answers 0x06010002, not the PDO rules' code */
    CHECK_EQ(download_u32(0x1601, 0, 0, 1), ODG_ABORT_READ_ONLY);
    CHECK_EQ(download_u32(0x1601, 1, 0x20020020, 4), ODG_ABORT_READ_ONLY);
}

/* Active errors and the error register 0x1001: bits by the codes' classes plus the caller's,
 * generic while any is active; EMCY when one comes, error reset when the last goes. */
static void test_error_register(void)
{
    unsigned k;
#define REG pdo_node_x1001_error_register
    CHECK_EQ(odg_node_error_bits(0x0000), 0);
    CHECK_EQ(odg_node_error_bits(0x1000), ODG_ERR_GENERIC);
    CHECK_EQ(odg_node_error_bits(0x2310), ODG_ERR_GENERIC | ODG_ERR_CURRENT);
    CHECK_EQ(odg_node_error_bits(0x3210), ODG_ERR_GENERIC | ODG_ERR_VOLTAGE);
    CHECK_EQ(odg_node_error_bits(0x4210), ODG_ERR_GENERIC | ODG_ERR_TEMPERATURE);
    CHECK_EQ(odg_node_error_bits(0x5530), ODG_ERR_GENERIC);
    CHECK_EQ(odg_node_error_bits(0x8110), ODG_ERR_GENERIC | ODG_ERR_COMMUNICATION);
    CHECK_EQ(odg_node_error_bits(0x8210), ODG_ERR_GENERIC | ODG_ERR_COMMUNICATION);
    CHECK_EQ(odg_node_error_bits(0x8611), ODG_ERR_GENERIC); /* CiA 402 following error */
    CHECK_EQ(odg_node_error_bits(0xFF42), ODG_ERR_GENERIC | ODG_ERR_MANUFACTURER);
    nmt(ODG_NMT_RESET_NODE, NID);
    nmt(ODG_NMT_START, NID);
    clear();
    CHECK_EQ(odg_node_error_set(&node, 0x4210, 0, NULL, 0), 0);
    CHECK(FRAME_IS(last_id(EMCY), 0x10, 0x42, 0x09, 0, 0, 0, 0, 0));
    CHECK_EQ(upload_u32(0x1001, 0), 0x09); /* read-only for SDO, set by the node */
    clear();
    CHECK_EQ(odg_node_error_set(&node, 0x4210, 0, NULL, 0), 0); /* still active: nothing new */
    CHECK_EQ(count_id(EMCY), 0);
    CHECK_EQ(odg_node_error_set(&node, 0x3110, 0, (const uint8_t *)"\x07", 1), 0);
    CHECK(FRAME_IS(last_id(EMCY), 0x10, 0x31, 0x0D, 7, 0, 0, 0, 0));
    CHECK_EQ(odg_node_error_set(&node, 0xFF01, ODG_ERR_PROFILE, NULL, 0), 0);
    CHECK(FRAME_IS(last_id(EMCY), 0x01, 0xFF, 0xAD, 0, 0, 0, 0, 0));
    CHECK_EQ(odg_node_error_clear(&node, 0x3110), 0); /* others remain: no EMCY */
    CHECK_EQ(odg_node_error_clear(&node, 0x9000), 0); /* never active */
    CHECK_EQ(count_id(EMCY), 2);
    CHECK_EQ(REG, 0xA9);
    CHECK_EQ(odg_node_error_clear(&node, 0x4210), 0);
    CHECK_EQ(REG, 0xA1);
    CHECK_EQ(odg_node_error_clear(&node, 0xFF01), 0);
    CHECK_EQ(count_id(EMCY), 3);
    CHECK(FRAME_IS(last_id(EMCY), 0, 0, 0, 0, 0, 0, 0, 0));
    CHECK_EQ(REG, 0);
    CHECK_EQ(upload_u32(0x1003, 0), 3); /* an error reset is no error */
    CHECK_EQ(upload_u32(0x1001, 0), 0);
    CHECK_EQ(odg_node_error_set(&node, 0, 0, NULL, 0), ODG_ABORT_VALUE_RANGE);
    /* a full table refuses, changing nothing */
    for (k = 0; k < ODG_NODE_MAX_ERRORS; k++) {
        CHECK_EQ(odg_node_error_set(&node, (uint16_t)(0x1000 + k), 0, NULL, 0), 0);
    }
    clear();
    CHECK_EQ(odg_node_error_set(&node, 0x2000, 0, NULL, 0), ODG_ABORT_NO_RESOURCE);
    CHECK_EQ(n_sent, 0);
    CHECK_EQ(REG, ODG_ERR_GENERIC);
    for (k = 0; k < ODG_NODE_MAX_ERRORS; k++) {
        CHECK_EQ(odg_node_error_clear(&node, (uint16_t)(0x1000 + k)), 0);
    }
    CHECK_EQ(count_id(EMCY), 1);
    /* recorded when stopped, though not sent */
    nmt(ODG_NMT_STOP, NID);
    CHECK_EQ(odg_node_error_set(&node, 0x8110, 0, NULL, 0), ODG_ABORT_DATA_STATE);
    CHECK_EQ(REG, 0x11);
    /* a raw EMCY frame leaves 0x1001 alone */
    nmt(ODG_NMT_START, NID);
    CHECK_EQ(odg_node_emcy(&node, 0x5000, 0x81, NULL, 0), 0);
    CHECK_EQ(REG, 0x11);
    /* reset communication forgets the communication errors, silently; reset node all */
    CHECK_EQ(odg_node_error_set(&node, 0x4210, 0, NULL, 0), 0);
    CHECK_EQ(REG, 0x19);
    clear();
    nmt(ODG_NMT_RESET_COMM, NID);
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(REG, 0x09);
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(n_sent, 2);
    CHECK_EQ(REG, 0);
    CHECK_EQ(odg_node_error_clear(&node, 0x4210), 0);
    CHECK_EQ(n_sent, 2);
    /* the RPDO length error outlives stop and start, and ends with the RPDO reconfigured */
    nmt(ODG_NMT_START, NID);
    rx(RPDO1, 9, 0);
    CHECK_EQ(REG, 0x11);
    nmt(ODG_NMT_STOP, NID);
    nmt(ODG_NMT_START, NID);
    CHECK_EQ(REG, 0x11);
    rx(RPDO1, 9, 0, 0);
    CHECK_EQ(REG, 0);
    rx(RPDO1, 9, 0);
    clear();
    CHECK_EQ(download_u32(0x1400, 1, INVALID | RPDO1, 4), 0);
    CHECK_EQ(REG, 0);
    CHECK(FRAME_IS(last_id(EMCY), 0, 0, 0, 0, 0, 0, 0, 0));
    nmt(ODG_NMT_RESET_NODE, NID);
#undef REG
}

/* SYNC producer: 0x1005 bit 30 and 0x1006 (µs); counter 1..0x1019; TPDO2 (every 3rd SYNC)
 * follows the node's own SYNC; 0x1019 only while 0x1006 is 0, and not 1 or 241..255. */
static void test_sync_producer(void)
{
    unsigned k;
    nmt(ODG_NMT_RESET_NODE, NID);
    clear();
    CHECK_EQ(download_u32(0x1006, 0, 10000, 4), 0); /* 10 ms, but bit 30 not set yet */
    run_ms(50);
    CHECK_EQ(count_id(0x80), 0);
    CHECK_EQ(download_u32(0x1019, 0, 3, 1), ODG_ABORT_DATA_STATE);
    CHECK_EQ(download_u32(0x1006, 0, 0, 4), 0);
    CHECK_EQ(download_u32(0x1019, 0, 1, 1), ODG_ABORT_VALUE_RANGE); /* CiA 301 reserves 1 and 241..255 */
    CHECK_EQ(download_u32(0x1019, 0, 241, 1), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1019, 0, 255, 1), ODG_ABORT_VALUE_RANGE);
    CHECK_EQ(download_u32(0x1019, 0, 240, 1), 0);
    CHECK_EQ(download_u32(0x1019, 0, 3, 1), 0);
    CHECK_EQ(download_u32(0x1006, 0, 10000, 4), 0);
    CHECK_EQ(download_u32(0x1005, 0, 0x40000080u, 4), 0);
    clear();
    run_ms(100);
    CHECK_EQ(count_id(0x80), 10); /* in pre-operational too */
    for (k = 0; k < n_sent; k++) {
        CHECK_EQ(sent[k].len, 1);
        CHECK_EQ(sent[k].data[0], k % 3u + 1u); /* 1, 2, 3, 1, ... */
    }
    nmt(ODG_NMT_START, NID);
    clear();
    run_ms(60);
    CHECK_EQ(count_id(0x80), 6);
    CHECK_EQ(count_id(TPDO2), 2); /* type 3: every third of the node's own SYNCs */
    nmt(ODG_NMT_STOP, NID);
    clear();
    run_ms(50);
    CHECK_EQ(count_id(0x80), 0); /* not in stopped */
    nmt(ODG_NMT_ENTER_PREOP, NID);
    CHECK_EQ(download_u32(0x1006, 0, 0, 4), 0);
    CHECK_EQ(download_u32(0x1019, 0, 0, 1), 0);
    CHECK_EQ(download_u32(0x1006, 0, 10000, 4), 0);
    clear();
    after(1000); /* a long pause: one SYNC, no burst; without a counter, empty */
    CHECK_EQ(count_id(0x80), 1);
    CHECK_EQ(last_id(0x80)->len, 0);
    nmt(ODG_NMT_RESET_NODE, NID);
    clear();
    run_ms(50);
    CHECK_EQ(count_id(0x80), 0);
}

static uint8_t hb_events[16][2];
static unsigned n_hb_events;

static void on_hb(void *ctx, uint8_t id, uint8_t event)
{
    (void)ctx;
    if (n_hb_events < 16u) {
        hb_events[n_hb_events][0] = id;
        hb_events[n_hb_events++][1] = event;
    }
}

/* Heartbeat consumer: node 9 watched with 100 ms from its first heartbeat; state changes and a
 * timeout reported; EMCY 0x8130; 0x1029 sub 1 decides what the node does then. */
static void test_heartbeat_consumer(void)
{
    nmt(ODG_NMT_RESET_NODE, NID);
    odg_node_on_heartbeat(&node, on_hb, NULL);
    n_hb_events = 0;
    CHECK_EQ(download_u32(0x1016, 1, 0x00090064u, 4), 0);
    CHECK_EQ(download_u32(0x1016, 2, 0x000900C8u, 4), ODG_ABORT_INCOMPATIBLE); /* node 9 again */
    CHECK_EQ(download_u32(0x1016, 2, 0x000A00C8u, 4), 0);
    nmt(ODG_NMT_START, NID);
    clear();
    run_ms(300); /* nothing heard from node 9 yet: not watched */
    CHECK_EQ(count_id(EMCY), 0);
    rx(0x709, 0x7F);
    rx(0x709, 0x7F);
    run_ms(80);
    rx(0x709, 0x05);
    CHECK_EQ(n_hb_events, 2);
    CHECK(hb_events[0][0] == 9 && hb_events[0][1] == 0x7F && hb_events[1][1] == 0x05);
    run_ms(100);
    CHECK_EQ(count_id(EMCY), 0);
    run_ms(1);
    CHECK(FRAME_IS(last_id(EMCY), 0x30, 0x81, 0x11, 9, 0, 0, 0, 0));
    CHECK_EQ(n_hb_events, 3);
    CHECK_EQ(hb_events[2][1], ODG_HB_TIMEOUT);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL); /* 0x1029 sub 1 = 0 */
    CHECK_EQ(upload_u32(0x1003, 1), 0x00098130u);
    CHECK_EQ(upload_u32(0x1001, 0), 0x11);
    clear();
    run_ms(500); /* no second EMCY until node 9 is heard again */
    CHECK_EQ(count_id(EMCY), 0);
    rx(0x709, 0x05); /* back: the error is gone */
    CHECK_EQ(count_id(EMCY), 1);
    CHECK(FRAME_IS(last_id(EMCY), 0, 0, 0, 0, 0, 0, 0, 0));
    CHECK_EQ(upload_u32(0x1001, 0), 0);
    /* two nodes late: one EMCY, the error gone when both are heard again */
    rx(0x70A, 0x05);
    clear();
    run_ms(201);
    CHECK_EQ(count_id(EMCY), 1);
    rx(0x709, 0x05);
    CHECK_EQ(count_id(EMCY), 1);
    CHECK_EQ(pdo_node_x1001_error_register, 0x11);
    rx(0x70A, 0x05);
    CHECK_EQ(count_id(EMCY), 2);
    CHECK_EQ(pdo_node_x1001_error_register, 0);
    /* 0x1029 sub 1 = 1: no change; 2: stopped */
    CHECK_EQ(download_u32(0x1029, 1, 1, 1), 0);
    nmt(ODG_NMT_START, NID);
    rx(0x709, 0x05);
    run_ms(101);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);
    CHECK_EQ(download_u32(0x1029, 1, 2, 1), 0);
    rx(0x709, 0x05);
    run_ms(101);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_STOPPED);
    /* an entry of time 0 is unused */
    nmt(ODG_NMT_ENTER_PREOP, NID);
    CHECK_EQ(download_u32(0x1016, 1, 0x00090000u, 4), 0);
    rx(0x709, 0x05);
    clear();
    run_ms(300);
    CHECK_EQ(count_id(EMCY), 0);
    odg_node_on_heartbeat(&node, NULL, NULL);
}

/* EMCY inhibit time 0x1015 = 10 ms: a second EMCY waits, queued ones follow 10 ms apart, a full
 * queue refuses; 0 sends at once again. */
static void test_emcy_inhibit(void)
{
    unsigned k;
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(download_u32(0x1015, 0, 100, 2), 0);
    clear();
    CHECK_EQ(odg_node_emcy(&node, 0x1000, 0x01, NULL, 0), 0);
    CHECK_EQ(odg_node_emcy(&node, 0x2000, 0x01, NULL, 0), 0);
    CHECK_EQ(count_id(EMCY), 1);
    run_ms(10); /* the first tick's millisecond may have passed before the EMCY: not counted */
    CHECK_EQ(count_id(EMCY), 1);
    run_ms(1);
    CHECK_EQ(count_id(EMCY), 2);
    CHECK(FRAME_IS(last_id(EMCY), 0x00, 0x20, 0x01, 0, 0, 0, 0, 0));
    for (k = 0; k < ODG_NODE_EMCY_QUEUE; k++) {
        CHECK_EQ(odg_node_emcy(&node, (uint16_t)(0x3000 + k), 0x01, NULL, 0), 0);
    }
    CHECK_EQ(odg_node_emcy(&node, 0x4000, 0x01, NULL, 0), ODG_ABORT_HARDWARE); /* queue full */
    clear();
    run_ms(10 * ODG_NODE_EMCY_QUEUE - 1);
    CHECK_EQ(count_id(EMCY), ODG_NODE_EMCY_QUEUE - 1);
    run_ms(1);
    CHECK_EQ(count_id(EMCY), ODG_NODE_EMCY_QUEUE);
    CHECK_EQ(last_id(EMCY)->data[1], 0x30);
    CHECK_EQ(last_id(EMCY)->data[0], ODG_NODE_EMCY_QUEUE - 1);
    CHECK_EQ(download_u32(0x1015, 0, 0, 2), 0);
    run_ms(10);
    clear();
    CHECK_EQ(odg_node_emcy(&node, 0x1000, 0x01, NULL, 0), 0);
    CHECK_EQ(odg_node_emcy(&node, 0x1000, 0x01, NULL, 0), 0);
    CHECK_EQ(count_id(EMCY), 2);
}

static void rtr(uint32_t id)
{
    odg_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = id;
    f.flags = ODG_FRAME_RTR;
    odg_node_receive(&node, &f);
}

/* Node guarding: state and toggle on a remote frame while no heartbeat is produced; life
 * guarding with 0x100C x 0x100D: EMCY 0x8130 and 0x1029 when the remote frames stop. */
static void test_guarding(void)
{
    nmt(ODG_NMT_RESET_NODE, NID);
    clear();
    rtr(0x700 + NID);
    rtr(0x700 + NID);
    rtr(0x700 + NID + 1u); /* another node's */
    CHECK_EQ(n_sent, 2);
    CHECK(FRAME_IS(&sent[0], 0x7F) && FRAME_IS(&sent[1], 0xFF));
    nmt(ODG_NMT_START, NID);
    clear();
    rtr(0x700 + NID);
    CHECK(FRAME_IS(last_id(0x700 + NID), 0x05));
    CHECK_EQ(download_u32(0x1017, 0, 1000, 2), 0); /* heartbeat on: no guarding answers */
    clear();
    rtr(0x700 + NID);
    CHECK_EQ(n_sent, 0);
    CHECK_EQ(download_u32(0x1017, 0, 0, 2), 0);
    CHECK_EQ(download_u32(0x100C, 0, 50, 2), 0);
    CHECK_EQ(download_u32(0x100D, 0, 2, 1), 0);
    CHECK_EQ(download_u32(0x1029, 1, 0, 1), 0);
    rtr(0x700 + NID);
    clear();
    run_ms(100);
    CHECK_EQ(count_id(EMCY), 0);
    run_ms(1);
    CHECK(FRAME_IS(last_id(EMCY), 0x30, 0x81, 0x11, NID, 0, 0, 0, 0));
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL);
    clear();
    run_ms(500); /* one event, until the next remote frame */
    CHECK_EQ(count_id(EMCY), 0);
    rtr(0x700 + NID); /* which ends the error */
    CHECK(FRAME_IS(last_id(EMCY), 0, 0, 0, 0, 0, 0, 0, 0));
    CHECK_EQ(upload_u32(0x1001, 0), 0);
    run_ms(101);
    CHECK_EQ(upload_u32(0x1001, 0), 0x11);
    clear();
    nmt(ODG_NMT_RESET_COMM, NID); /* ends it too, silently; toggle from 0 again */
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(upload_u32(0x1001, 0), 0);
    clear();
    rtr(0x700 + NID);
    CHECK(FRAME_IS(last_id(0x700 + NID), 0x7F));
}

/* RTR-triggered TPDOs: type 253 samples and sends on a remote request; type 252 sends what
 * the last SYNC sampled; COB-ID bit 30 forbids remote requests; only in operational. */
static void test_rtr_tpdo(void)
{
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(download_u32(0x1800, 1, INVALID | TPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1800, 2, 253, 1), 0);
    CHECK_EQ(download_u32(0x1800, 1, TPDO1, 4), 0);
    clear();
    rtr(TPDO1); /* pre-operational: no PDOs */
    CHECK_EQ(count_id(TPDO1), 0);
    nmt(ODG_NMT_START, NID);
    pdo_node_x2000_u8_value = 0x21;
    clear();
    run_ms(20);
    CHECK_EQ(count_id(TPDO1), 0); /* not event-driven */
    rtr(TPDO1);
    CHECK_EQ(count_id(TPDO1), 1);
    CHECK_EQ(last_id(TPDO1)->data[0], 0x21);
    nmt(ODG_NMT_ENTER_PREOP, NID);
    CHECK_EQ(download_u32(0x1800, 1, INVALID | TPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1800, 2, 252, 1), 0);
    CHECK_EQ(download_u32(0x1800, 1, TPDO1, 4), 0);
    nmt(ODG_NMT_START, NID);
    clear();
    rtr(TPDO1); /* no SYNC yet: nothing sampled */
    CHECK_EQ(count_id(TPDO1), 0);
    pdo_node_x2000_u8_value = 0x31;
    sync0();
    CHECK_EQ(count_id(TPDO1), 0); /* sampled, not sent */
    pdo_node_x2000_u8_value = 0x32;
    rtr(TPDO1);
    CHECK_EQ(count_id(TPDO1), 1);
    CHECK_EQ(last_id(TPDO1)->data[0], 0x31); /* the value at the SYNC */
    nmt(ODG_NMT_ENTER_PREOP, NID);
    CHECK_EQ(download_u32(0x1800, 1, INVALID | TPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1800, 2, 253, 1), 0);
    CHECK_EQ(download_u32(0x1800, 1, 0x40000000u | TPDO1, 4), 0);
    nmt(ODG_NMT_START, NID);
    clear();
    rtr(TPDO1);
    CHECK_EQ(count_id(TPDO1), 0); /* bit 30: no remote requests */
}

int main(void)
{
    test_only_when_operational();
    test_event_driven();
    test_sync();
    test_rpdo();
    test_remap();
    test_emcy_and_resets();
    test_reset_communication();
    test_sdo_server_cob_ids();
    test_application_writes();
    test_application_client();
    test_rpdo_reloaded_while_applied();
    test_error_history();
    test_error_register();
    test_sync_producer();
    test_heartbeat_consumer();
    test_emcy_inhibit();
    test_guarding();
    test_rtr_tpdo();
    return done();
}
