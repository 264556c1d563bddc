/*
 * test_ds401_app.c - the glue (runtime/profiles/ds401.c, configured by the ds401_app.h of
 * `odgen profile ds401 --di 16 --do 16 --ai 4 --ao 4 --generate`) on a node over the fake
 * transport, built with ODG_NODE_TPDO_COS=0: inputs through the hooks with polarity, outputs
 * by RPDO and SDO with polarity, and change-of-state TPDOs under 0x6005-0x6008 and
 * 0x6421-0x6426, following remapping and transmission type 0.
 */
#include <string.h>

#include "fake.h"
#include "ds401_app.h"
#include "io.h"

#define TPDO(k) (0x180u + 0x100u * (k) + NID)
#define RPDO(k) (0x200u + 0x100u * (k) + NID)

/* the hardware */
static uint8_t pins_in[DS401_DI_GROUPS], pins_out[DS401_DO_GROUPS];
static ds401_ai_t analog_in[DS401_AI_CHANNELS];
static ds401_ao_t analog_out[DS401_AO_CHANNELS];
static unsigned output_writes;

void ds401_read_inputs(uint8_t *groups, uint16_t n)
{
    CHECK_EQ(n, DS401_DI_GROUPS);
    memcpy(groups, pins_in, n);
}

void ds401_write_outputs(const uint8_t *groups, uint16_t n)
{
    CHECK_EQ(n, DS401_DO_GROUPS);
    memcpy(pins_out, groups, n);
    output_writes++;
}

void ds401_read_analog(ds401_ai_t *values, uint16_t n)
{
    CHECK_EQ(n, DS401_AI_CHANNELS);
    memcpy(values, analog_in, sizeof analog_in);
}

void ds401_write_analog(const ds401_ao_t *values, uint16_t n)
{
    CHECK_EQ(n, DS401_AO_CHANNELS);
    memcpy(analog_out, values, sizeof analog_out);
}

/* one millisecond of the main loop */
static void loop_ms(unsigned ms)
{
    while (ms-- > 0u) {
        odg_node_tick(&node, 1);
        ds401_poll(&node);
    }
}

static void boot(void)
{
    memset(pins_in, 0, sizeof pins_in);
    memset(analog_in, 0, sizeof analog_in);
    start_node(&io, NULL);
    output_writes = 0;
    CHECK_EQ(ds401_init(&node), 0);
    nmt(ODG_NMT_START, NID);
    loop_ms(2);
    CHECK_EQ(count_id(TPDO(0)), 1); /* every TPDO once on entering operational */
    CHECK_EQ(count_id(TPDO(1)), 1);
    clear();
}

/* Change the input pins and run; how many TPDO(k) frames went out. */
static unsigned set_inputs(uint8_t g1, uint8_t g2, unsigned k)
{
    clear();
    pins_in[0] = g1;
    pins_in[1] = g2;
    loop_ms(5);
    return count_id(TPDO(k));
}

static void test_global_enable_and_any_change(void)
{
    boot();
    loop_ms(20);
    CHECK_EQ(n_sent, 0); /* nothing changed, nothing sent (no COS from the node layer) */
    CHECK_EQ(download_u32(0x6005, 0, 0, 1), 0);
    CHECK_EQ(set_inputs(0x01, 0x00, 0), 0);
    CHECK_EQ(set_inputs(0x03, 0x80, 0), 0);
    CHECK_EQ(upload_u32(0x6000, 1), 0x03); /* the input image is current all the same */
    CHECK_EQ(download_u32(0x6005, 0, 1, 1), 0);
    CHECK_EQ(set_inputs(0x07, 0x80, 0), 1);
    CHECK_EQ(last_id(TPDO(0))->len, 2);
    CHECK_EQ(last_id(TPDO(0))->data[0], 0x07);
    CHECK_EQ(last_id(TPDO(0))->data[1], 0x80);
    CHECK_EQ(n_sent, 1);
    CHECK_EQ(set_inputs(0x07, 0x80, 0), 0);
    /* only the lines of 0x6006 count */
    CHECK_EQ(download_u32(0x6006, 1, 0x0F, 1), 0);
    CHECK_EQ(download_u32(0x6006, 2, 0x00, 1), 0);
    CHECK_EQ(set_inputs(0x37, 0x81, 0), 0); /* lines 5, 6 and 9 */
    CHECK_EQ(set_inputs(0x36, 0x81, 0), 1); /* line 1 */
    CHECK_EQ(last_id(TPDO(0))->data[0], 0x36);
    CHECK_EQ(last_id(TPDO(0))->data[1], 0x81);
}

static void test_edges(void)
{
    boot();
    CHECK_EQ(download_u32(0x6006, 1, 0x00, 1), 0);
    CHECK_EQ(download_u32(0x6006, 2, 0x00, 1), 0);
    CHECK_EQ(download_u32(0x6007, 1, 0x04, 1), 0); /* line 3 rising */
    CHECK_EQ(download_u32(0x6008, 2, 0x01, 1), 0); /* line 9 falling */
    CHECK_EQ(set_inputs(0x04, 0x00, 0), 1);
    CHECK_EQ(set_inputs(0x00, 0x00, 0), 0);
    CHECK_EQ(set_inputs(0x00, 0x01, 0), 0);
    CHECK_EQ(set_inputs(0x00, 0x00, 0), 1);
    CHECK_EQ(last_id(TPDO(0))->data[1], 0x00);
    CHECK_EQ(set_inputs(0xFB, 0xFE, 0), 0); /* every other line, both ways */
    CHECK_EQ(set_inputs(0x00, 0x00, 0), 0);
    CHECK_EQ(download_u32(0x6005, 0, 0, 1), 0);
    CHECK_EQ(set_inputs(0x04, 0x00, 0), 0);
}

/* TPDO1 keeps 0x6000 sub1 and TPDO3 (disabled by default) takes sub2. */
static void remap(void)
{
    CHECK_EQ(download_u32(0x1800, 1, 0x80000000u | TPDO(0), 4), 0);
    CHECK_EQ(download_u32(0x1A00, 0, 0, 1), 0);
    CHECK_EQ(download_u32(0x1A00, 1, 0x60000108u, 4), 0);
    CHECK_EQ(download_u32(0x1A00, 0, 1, 1), 0);
    CHECK_EQ(download_u32(0x1800, 1, TPDO(0), 4), 0);
    CHECK_EQ(download_u32(0x1A02, 0, 0, 1), 0);
    CHECK_EQ(download_u32(0x1A02, 1, 0x60000208u, 4), 0);
    CHECK_EQ(download_u32(0x1A02, 0, 1, 1), 0);
    CHECK_EQ(download_u32(0x1802, 1, TPDO(2), 4), 0);
}

static void test_remapped(void)
{
    boot();
    remap();
    loop_ms(5);
    clear();
    CHECK_EQ(set_inputs(0x00, 0x10, 2), 1);
    CHECK_EQ(count_id(TPDO(0)), 0);
    CHECK_EQ(last_id(TPDO(2))->len, 1);
    CHECK_EQ(last_id(TPDO(2))->data[0], 0x10);
    CHECK_EQ(set_inputs(0x20, 0x10, 0), 1);
    CHECK_EQ(count_id(TPDO(2)), 0);
    CHECK_EQ(last_id(TPDO(0))->data[0], 0x20);
    CHECK_EQ(set_inputs(0x21, 0x11, 0), 1);
    CHECK_EQ(count_id(TPDO(2)), 1);
    CHECK_EQ(n_sent, 2);
}

/* Transmission type 0: a change is sent with the next SYNC, and nothing without one. */
static void test_acyclic_synchronous(void)
{
    boot();
    CHECK_EQ(download_u32(0x1800, 2, 0, 1), 0);
    loop_ms(5);
    rx0(0x80);
    clear();
    CHECK_EQ(set_inputs(0x01, 0x00, 0), 0);
    rx0(0x80);
    CHECK_EQ(count_id(TPDO(0)), 1);
    CHECK_EQ(last_id(TPDO(0))->data[0], 0x01);
    clear();
    rx0(0x80);
    loop_ms(5);
    CHECK_EQ(n_sent, 0);
    /* a change that 0x6006 masks is not an event at SYNC either */
    CHECK_EQ(download_u32(0x6006, 1, 0x00, 1), 0);
    CHECK_EQ(set_inputs(0x03, 0x00, 0), 0);
    rx0(0x80);
    CHECK_EQ(count_id(TPDO(0)), 0);
}

static void test_polarity_and_outputs(void)
{
    int16_t v = -1234;
    boot();
    CHECK_EQ(output_writes, 1); /* ds401_init applied the defaults */
    CHECK_EQ(pins_out[0], 0x00);
    pins_in[0] = 0x0F;
    CHECK_EQ(download_u32(0x6002, 1, 0xFF, 1), 0);
    CHECK_EQ(upload_u32(0x6000, 1), 0xF0);
    rx(RPDO(0), 0x5A, 0x01);
    CHECK_EQ(pins_out[0], 0x5A);
    CHECK_EQ(pins_out[1], 0x01);
    CHECK_EQ(download_u32(0x6202, 2, 0x03, 1), 0); /* polarity applies at once */
    CHECK_EQ(pins_out[1], 0x02);
    CHECK_EQ(download_u32(0x6200, 1, 0xA5, 1), 0);
    CHECK_EQ(pins_out[0], 0xA5);
    CHECK_EQ(upload_u32(0x6200, 1), 0xA5);
    rx(RPDO(1), 1, 0, 2, 0, 3, 0, (uint8_t)v, (uint8_t)((uint16_t)v >> 8));
    CHECK_EQ(analog_out[0], 1);
    CHECK_EQ(analog_out[2], 3);
    CHECK_EQ(analog_out[3], -1234);
}

static void test_analog_interrupt(void)
{
    boot();
    analog_in[1] = 100;
    loop_ms(5);
    CHECK_EQ(count_id(TPDO(1)), 0); /* 0x6423 is FALSE by default */
    CHECK_EQ(upload_u32(0x6401, 2) & 0xFFFFu, 100);
    CHECK_EQ(download_u32(0x6423, 0, 1, 1), 0);
    CHECK_EQ(download_u32(0x6426, 2, 50, 4), 0); /* delta 50 on channel 2 */
    clear();
    analog_in[1] = 140;
    loop_ms(5);
    CHECK_EQ(count_id(TPDO(1)), 0);
    analog_in[1] = 151;
    loop_ms(5);
    CHECK_EQ(count_id(TPDO(1)), 1);
    CHECK_EQ(last_id(TPDO(1))->data[2], 151);
    /* upper limit of channel 1 only: crossing it is one event */
    CHECK_EQ(download_u32(0x6421, 1, 0x01, 1), 0);
    CHECK_EQ(download_u32(0x6424, 1, 1000, 4), 0);
    clear();
    analog_in[0] = 999;
    loop_ms(5);
    CHECK_EQ(count_id(TPDO(1)), 0);
    analog_in[0] = 1001;
    loop_ms(5);
    analog_in[0] = 1500;
    loop_ms(5);
    CHECK_EQ(count_id(TPDO(1)), 1);
}

int main(void)
{
    test_global_enable_and_any_change();
    test_edges();
    test_remapped();
    test_acyclic_synchronous();
    test_polarity_and_outputs();
    test_analog_interrupt();
    return done();
}
