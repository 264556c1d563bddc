/*
 * test_node_io.c - the example io-node (examples/io-node, generated with its options file) as
 * a running node: input hook sampled for the TPDO, output hook driven by the RPDO, and the
 * communication settings stored through 0x1010 into a file (odg_nv_file) surviving a power
 * cycle, and reloaded from NV while the node runs. Run in a scratch directory: it creates
 * io_node.nv there.
 */
#include <stdio.h>
#include <string.h>

#include "fake.h"
#include "io_node.h"
#include "odg_nv_file.h"

#define TPDO1 (0x180u + NID)
#define RPDO1 (0x200u + NID)
#define NV_PATH "io_node.nv"
#define INVALID_COB 0x80000000u

/* the hardware: 8 input pins, 8 output pins */
static uint8_t pins_in, pins_out;
static unsigned input_reads, output_writes;

odg_abort_t io_node_read_inputs(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data,
                                uint32_t len, void *ctx)
{
    (void)ref, (void)kind, (void)data, (void)len, (void)ctx;
    input_reads++;
    io_node_x6000_read_input_8_bit_s1_read_input_1h_to_8h = pins_in;
    return ODG_OK;
}

/* 0xFF would short the drivers: refused before it is stored */
odg_abort_t io_node_apply_outputs(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data,
                                  uint32_t len, void *ctx)
{
    (void)ref, (void)len, (void)ctx;
    if (kind == ODG_HOOK_PRE_WRITE) {
        return ((const uint8_t *)data)[0] == 0xFFu ? ODG_ABORT_DATA_LOCAL : ODG_OK;
    }
    output_writes++;
    pins_out = io_node_x6200_write_output_8_bit_s1_write_output_1h_to_8h;
    return ODG_OK;
}

static odg_nv_file_t nvf;

/* NV bytes of both groups */
static uint32_t nv_size(void)
{
    return odg_persist_nv_size(&io_node);
}

static void power_on(void)
{
    odg_boot_status_t boot[2];
    odg_node_config_t cfg;
    CHECK_EQ(odg_nv_file_open(&nvf, NV_PATH, nv_size()), 0);
    memset(&cfg, 0, sizeof cfg);
    cfg.dict = &io_node;
    cfg.node_id = NID;
    cfg.nv = &nvf.driver;
    cfg.boot = boot;
    cfg.send = fake_send;
    clear();
    CHECK_EQ(odg_node_init(&node, &cfg), 0);
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(sent[0].id, 0x700u + NID);
    node.cfg.boot = NULL; /* `boot` goes out of scope; later resets do not need it */
}

static void power_off(void)
{
    CHECK_EQ(odg_nv_file_close(&nvf), 0);
}

static void test_io(void)
{
    unsigned reads;
    remove(NV_PATH);
    power_on();
    CHECK_EQ(download_u32(0x1017, 0, 0, 2), 0); /* quiet: no heartbeats among the PDOs */
    pins_in = 0xA5;
    nmt(ODG_NMT_START, NID);
    clear();
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    CHECK_EQ(last_id(TPDO1)->len, 1);
    CHECK_EQ(last_id(TPDO1)->data[0], 0xA5);
    /* the inputs are sampled every tick: a change goes out at once */
    reads = input_reads;
    run_ms(10);
    CHECK_EQ(input_reads, reads + 10u);
    CHECK_EQ(count_id(TPDO1), 1);
    pins_in = 0x5A;
    after(1);
    CHECK_EQ(count_id(TPDO1), 2);
    CHECK_EQ(last_id(TPDO1)->data[0], 0x5A);
    /* and the event timer (100 ms) repeats it */
    clear();
    run_ms(1000);
    CHECK_EQ(count_id(TPDO1), 10);
    /* SDO upload runs the same hook */
    pins_in = 0x0F;
    CHECK_EQ(upload_u32(0x6000, 1), 0x0F);

    /* RPDO drives the outputs through the hooks; a refused value is dropped */
    rx(RPDO1, 0x3C);
    CHECK_EQ(pins_out, 0x3C);
    CHECK_EQ(output_writes, 1);
    rx(RPDO1, 0xFF);
    CHECK_EQ(pins_out, 0x3C);
    CHECK_EQ(output_writes, 1);
    CHECK_EQ(download_u32(0x6200, 1, 0xFF, 1), ODG_ABORT_DATA_LOCAL);
    CHECK_EQ(download_u32(0x6200, 1, 0x01, 1), 0);
    CHECK_EQ(pins_out, 0x01);
    /* 0x2000 has limits and is not mappable */
    CHECK_EQ(download_u32(0x2000, 0, 501, 2), ODG_ABORT_VALUE_HIGH);
    CHECK_EQ(download_u32(0x1800, 1, 0x80000000u | TPDO1, 4), 0);
    CHECK_EQ(download_u32(0x1A00, 0, 0, 1), 0);
    CHECK_EQ(download_u32(0x1A00, 1, 0x20000010, 4), ODG_ABORT_NOT_MAPPABLE);
    CHECK_EQ(download_u32(0x1A00, 0, 1, 1), 0);
    CHECK_EQ(download_u32(0x1800, 1, TPDO1, 4), 0);
}

static void test_power_cycle(void)
{
    static const uint8_t save[4] = {'s', 'a', 'v', 'e'}, load[4] = {'l', 'o', 'a', 'd'};
    /* settings changed and stored (0x1010 sub 1: every group) ... */
    CHECK_EQ(download_u32(0x1017, 0, 250, 2), 0);
    CHECK_EQ(download_u32(0x1800, 5, 500, 2), 0);
    CHECK_EQ(download_u32(0x2000, 0, 20, 2), 0);
    CHECK_EQ(download(0x1010, 1, save, 4), 0);
    /* ... then changed again without storing */
    CHECK_EQ(download_u32(0x1017, 0, 333, 2), 0);
    power_off();

    power_on();
    CHECK_EQ(upload_u32(0x1017, 0), 250);
    CHECK_EQ(upload_u32(0x1800, 5), 500);
    CHECK_EQ(upload_u32(0x2000, 0), 20);
    clear();
    run_ms(1000);
    CHECK_EQ(count_id(0x700u + NID), 4);
    nmt(ODG_NMT_START, NID);
    clear();
    run_ms(1000);
    CHECK_EQ(count_id(TPDO1), 2); /* at start, then after 500 ms */

    /* restore defaults: effective at the next reset */
    CHECK_EQ(download(0x1011, 1, load, 4), 0);
    CHECK_EQ(upload_u32(0x1017, 0), 250);
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(upload_u32(0x1017, 0), 1000);
    CHECK_EQ(upload_u32(0x1800, 5), 100);
    CHECK_EQ(upload_u32(0x2000, 0), 10);
    power_off();
    power_on();
    CHECK_EQ(upload_u32(0x1017, 0), 1000);
    power_off();
    remove(NV_PATH);
}

/* Reset communication brings back the communication values of the boot (defaults on erased
 * NV), then those saved by 0x1010, then after 0x1011 "load" the defaults; the application
 * parameter 0x2000 keeps its RAM value through each. */
static void test_reset_communication(void)
{
    static const uint8_t save[4] = {'s', 'a', 'v', 'e'}, load[4] = {'l', 'o', 'a', 'd'};
    remove(NV_PATH);
    power_on();
    CHECK_EQ(download_u32(0x1017, 0, 250, 2), 0);
    CHECK_EQ(download_u32(0x1800, 5, 500, 2), 0);
    CHECK_EQ(download_u32(0x2000, 0, 20, 2), 0);
    nmt(ODG_NMT_RESET_COMM, NID);
    CHECK_EQ(upload_u32(0x1017, 0), 1000);
    CHECK_EQ(upload_u32(0x1800, 5), 100);
    CHECK_EQ(upload_u32(0x2000, 0), 20);
    CHECK_EQ(download_u32(0x1017, 0, 300, 2), 0);
    CHECK_EQ(download(0x1010, 1, save, 4), 0);
    CHECK_EQ(download_u32(0x1017, 0, 400, 2), 0);
    CHECK_EQ(download_u32(0x2000, 0, 30, 2), 0);
    nmt(ODG_NMT_RESET_COMM, NID);
    CHECK_EQ(upload_u32(0x1017, 0), 300); /* saved */
    CHECK_EQ(upload_u32(0x2000, 0), 30);
    CHECK_EQ(download(0x1011, 1, load, 4), 0);
    CHECK_EQ(upload_u32(0x1017, 0), 300); /* "load" takes effect at the next reset ... */
    nmt(ODG_NMT_RESET_COMM, NID);
    CHECK_EQ(upload_u32(0x1017, 0), 1000); /* ... of communication, for communication values */
    CHECK_EQ(upload_u32(0x1400, 1), 0x200u + NID); /* $NODEID defaults */
    CHECK_EQ(upload_u32(0x2000, 0), 30);
    nmt(ODG_NMT_RESET_NODE, NID);
    CHECK_EQ(upload_u32(0x2000, 0), 10);
    CHECK_EQ(upload_u32(0x1017, 0), 1000);
    power_off();
    remove(NV_PATH);
}

/* Values loaded by the persistence layer reach the node like any other write: the stored
 * TPDO settings come back, and the node serves them without a reset. */
static void test_reload_from_nv(void)
{
    static const uint8_t save[4] = {'s', 'a', 'v', 'e'};
    static odg_persist_t again; /* stays attached until the next odg_init */
    remove(NV_PATH);
    power_on();
    CHECK_EQ(download_u32(0x1017, 0, 0, 2), 0);
    CHECK_EQ(download_u32(0x1800, 1, INVALID_COB | TPDO1, 4), 0); /* TPDO1 off, and stored */
    CHECK_EQ(download(0x1010, 1, save, 4), 0);
    CHECK_EQ(download_u32(0x1800, 1, TPDO1, 4), 0); /* on again, not stored */
    nmt(ODG_NMT_START, NID);
    clear();
    after(1);
    CHECK_EQ(count_id(TPDO1), 1);
    /* the application loads the stored values (a second persistence layer on the same NV) */
    CHECK_EQ(odg_persist_init(&again, &io_node, &nvf.driver, NULL), ODG_OK);
    CHECK_EQ(upload_u32(0x1800, 1), INVALID_COB | TPDO1);
    clear();
    pins_in = (uint8_t)(pins_in ^ 0xFFu);
    run_ms(300);
    CHECK_EQ(count_id(TPDO1), 0);
    power_off();
    remove(NV_PATH);
}

int main(void)
{
    test_io();
    test_power_cycle();
    test_reset_communication();
    test_reload_from_nv();
    return done();
}
