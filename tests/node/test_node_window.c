/*
 * test_node_window.c - the synchronous window length (0x1007) over the fake bus, against
 * tests/node/lss-node.eds (TPDO1 0x185 type 1 maps 0x2001, RPDO1 0x205 type 1 maps 0x2000):
 * a synchronous TPDO whose frame could not be sent at the SYNC is sent later within the window
 * and dropped (counted) after it; RPDO data received after the window are discarded (counted);
 * without a window nothing is dropped until the next SYNC.
 */
#include <stdio.h>
#include <string.h>

#include "fake.h"
#include "lss_node.h"

#define TPDO (0x180u + NID)
#define RPDO (0x200u + NID)
#define SYNC() rx0(0x80)

static uint32_t output(void)
{
    return upload_u32(0x2000, 0) & 0xFFu;
}

static void operational(void)
{
    start_node(&lss_node, NULL);
    nmt(ODG_NMT_START, NID);
    CHECK_EQ(odg_node_state(&node), ODG_NMT_OPERATIONAL);
    clear();
    SYNC(); /* no window: sent at once */
    CHECK_EQ(count_id(TPDO), 1);
    CHECK_EQ(last_id(TPDO)->data[0], 0x11);
}

static void tpdo_within_and_after_window(void)
{
    CHECK_EQ(download_u32(0x1007, 0, 5000, 4), 0); /* 5 ms */
    clear();
    send_fails = 1;
    SYNC(); /* the frame cannot go out ... */
    CHECK_EQ(count_id(TPDO), 0);
    run_ms(1); /* ... and goes a tick later, within the window */
    CHECK_EQ(count_id(TPDO), 1);
    CHECK_EQ(node.sync_dropped, 0);
    run_ms(10);
    CHECK_EQ(count_id(TPDO), 1); /* once */
    clear();
    send_fails = 1000;
    SYNC();
    run_ms(5);
    CHECK_EQ(node.sync_dropped, 0); /* 5 ms: still in the window */
    run_ms(1);
    CHECK_EQ(node.sync_dropped, 1); /* over: dropped */
    send_fails = 0;
    run_ms(10);
    CHECK_EQ(count_id(TPDO), 0); /* never sent late */
    SYNC();
    CHECK_EQ(count_id(TPDO), 1); /* the next SYNC's is on time */
    CHECK_EQ(node.sync_dropped, 1);
}

static void rpdo_outside_window(void)
{
    SYNC();
    run_ms(2);
    rx(RPDO, 0x33); /* within 5 ms */
    SYNC();         /* applied */
    CHECK_EQ(output(), 0x33);
    run_ms(6);
    rx(RPDO, 0x44); /* 6 ms after the SYNC: discarded */
    CHECK_EQ(node.sync_dropped, 2);
    SYNC();
    CHECK_EQ(output(), 0x33);
    run_ms(5);
    rx(RPDO, 0x55); /* 5 ms: the window's last moment */
    SYNC();
    CHECK_EQ(output(), 0x55);
    CHECK_EQ(node.sync_dropped, 2);
}

static void no_window(void)
{
    CHECK_EQ(download_u32(0x1007, 0, 0, 4), 0);
    SYNC();
    run_ms(500);
    rx(RPDO, 0x66); /* no window: late data count */
    SYNC();
    CHECK_EQ(output(), 0x66);
    clear();
    send_fails = 1000;
    SYNC();
    run_ms(50);
    CHECK_EQ(node.sync_dropped, 2); /* tried on, no window to end it */
    SYNC(); /* a new cycle: the old frame is dropped, the new one cannot go either */
    CHECK_EQ(node.sync_dropped, 3);
    send_fails = 0;
    run_ms(1);
    CHECK_EQ(count_id(TPDO), 1);
    CHECK_EQ(node.sync_dropped, 3);
}

int main(void)
{
    operational();
    tpdo_within_and_after_window();
    rpdo_outside_window();
    no_window();
    return done();
}
