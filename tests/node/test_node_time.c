/*
 * test_node_time.c - the TIME object (0x1012, CiA 301 TIME_OF_DAY) over the fake bus, against
 * tests/node/lss-node.eds (0x1012 = 0x80000100: consumer on 0x100): received in
 * pre-operational and operational, not in stopped, short frames dropped, the reserved bits
 * masked; produced on the application's call only when bit 30 is set; a new COB-ID (by SDO)
 * heard at once.
 */
#include <stdio.h>
#include <string.h>

#include "fake.h"
#include "lss_node.h"

static int n_time;
static uint32_t got_ms;
static uint16_t got_days;

static void on_time(void *ctx, uint32_t ms, uint16_t days)
{
    CHECK(ctx == &n_time);
    n_time++;
    got_ms = ms;
    got_days = days;
}

static void consume(void)
{
    odg_node_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.dict = &lss_node;
    cfg.node_id = NID;
    cfg.send = fake_send;
    cfg.on_time = on_time;
    cfg.app_ctx = &n_time;
    CHECK_EQ(odg_node_init(&node, &cfg), 0);
    /* 12:00:00.001 on day 15000; the top 4 bits of byte 3 are reserved and ignored */
    rx(0x100, 0x01, 0x2E, 0x93, 0xF2, 0x98, 0x3A);
    CHECK_EQ(n_time, 1);
    CHECK_EQ(got_ms, 43200001u);
    CHECK_EQ(got_days, 15000u);
    rx(0x100, 1, 2, 3, 4, 5); /* 5 bytes: no time */
    CHECK_EQ(n_time, 1);
    nmt(ODG_NMT_STOP, NID);
    rx(0x100, 1, 0, 0, 0, 1, 0);
    CHECK_EQ(n_time, 1);
    nmt(ODG_NMT_START, NID);
    rx(0x100, 2, 0, 0, 0, 3, 0, 0, 0); /* 8 bytes: the first 6 count */
    CHECK_EQ(n_time, 2);
    CHECK_EQ(got_ms, 2);
    CHECK_EQ(got_days, 3);
    rx(0x101, 2, 0, 0, 0, 3, 0);
    CHECK_EQ(n_time, 2);
    clear();
    CHECK_EQ(odg_node_time_send(&node, 1000, 1), ODG_ABORT_DATA_STATE); /* bit 30 clear */
    CHECK_EQ(n_sent, 0);
}

static void produce(void)
{
    /* producer only, on 0x123 */
    CHECK_EQ(download_u32(0x1012, 0, 0x40000123u, 4), 0);
    rx(0x100, 1, 0, 0, 0, 1, 0);
    rx(0x123, 1, 0, 0, 0, 1, 0);
    CHECK_EQ(n_time, 2); /* not a consumer now */
    clear();
    CHECK_EQ(odg_node_time_send(&node, 43200001u, 15000u), 0);
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(sent[0].id, 0x123);
    CHECK_EQ(sent[0].len, 6);
    CHECK_EQ(le32(sent[0].data), 43200001u);
    CHECK_EQ(sent[0].data[4] | sent[0].data[5] << 8, 15000u);
    CHECK_EQ(odg_node_time_send(&node, 0x10000000u, 0), ODG_ABORT_VALUE_RANGE);
    nmt(ODG_NMT_STOP, NID);
    CHECK_EQ(odg_node_time_send(&node, 1, 0), ODG_ABORT_DATA_STATE);
    nmt(ODG_NMT_ENTER_PREOP, NID);
    CHECK_EQ(odg_node_time_send(&node, 1, 0), 0);
    send_fails = 1;
    CHECK_EQ(odg_node_time_send(&node, 1, 0), ODG_ABORT_HARDWARE);
    /* both: a node hears its own COB-ID only from others, as CAN does */
    CHECK_EQ(download_u32(0x1012, 0, 0xC0000123u, 4), 0);
    rx(0x123, 7, 0, 0, 0, 1, 0);
    CHECK_EQ(n_time, 3);
    CHECK_EQ(got_ms, 7);
    clear();
    CHECK_EQ(odg_node_time_send(&node, 5, 0), 0);
    CHECK_EQ(count_id(0x123), 1);
}

int main(void)
{
    consume();
    produce();
    return done();
}
