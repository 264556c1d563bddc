/*
 * test_node_ds401.c - CiA 401 outputs on communication loss: the glue (runtime/profiles/ds401.c,
 * `odgen profile ds401 --di 16 --do 16 --ai 4 --ao 4 --generate`) on a node over the fake
 * transport. When the master's heartbeat (0x1016) stops, on bus-off and on NMT stop, the
 * digital lines 0x6206 selects take their 0x6207 bits and the analog outputs 0x6443 selects
 * take 0x6444; they stay so until the master writes the outputs again.
 */
#include <string.h>

#include "fake.h"
#include "ds401_app.h"
#include "io.h"

#define MASTER 1u
#define HB_TIME 100u /* ms the node waits for the master's heartbeat */

static uint8_t pins_out[DS401_DO_GROUPS];
static ds401_ao_t analog_out[DS401_AO_CHANNELS];

void ds401_read_inputs(uint8_t *groups, uint16_t n)
{
    memset(groups, 0, n);
}

void ds401_write_outputs(const uint8_t *groups, uint16_t n)
{
    memcpy(pins_out, groups, n);
}

void ds401_read_analog(ds401_ai_t *values, uint16_t n)
{
    memset(values, 0, n * sizeof *values);
}

void ds401_write_analog(const ds401_ao_t *values, uint16_t n)
{
    memcpy(analog_out, values, n * sizeof *values);
}

static void loop_ms(unsigned ms)
{
    while (ms-- > 0u) {
        odg_node_tick(&node, 1);
        ds401_poll(&node);
    }
}

/* ms of the main loop with the master's heartbeat every 20 ms */
static void master_alive(unsigned ms)
{
    unsigned t;
    for (t = 0; t < ms; t += 20u) {
        rx(0x700u + MASTER, ODG_NMT_OPERATIONAL);
        loop_ms(20);
    }
}

static void outputs(uint8_t g1, uint8_t g2, int16_t a1, int16_t a2)
{
    CHECK_EQ(download_u32(0x6200, 1, g1, 1), 0);
    CHECK_EQ(download_u32(0x6200, 2, g2, 1), 0);
    CHECK_EQ(download_u32(DS401_AO_INDEX, 1, (uint16_t)a1, 2), 0);
    CHECK_EQ(download_u32(DS401_AO_INDEX, 2, (uint16_t)a2, 2), 0);
}

static void boot(void)
{
    start_node(&io, NULL);
    CHECK_EQ(ds401_init(&node), 0);
    CHECK_EQ(download_u32(0x1016, 1, MASTER << 16 | HB_TIME, 4), 0);
    CHECK_EQ(download_u32(0x6206, 1, 0x0F, 1), 0); /* lines 1-4 take an error value, 5-8 keep theirs */
    CHECK_EQ(download_u32(0x6207, 1, 0x03, 1), 0);
    CHECK_EQ(download_u32(0x6444, 1, 70000, 4), 0);  /* beyond INTEGER16: saturated */
    CHECK_EQ(download_u32(0x6443, 2, 0, 1), 0);      /* channel 2 keeps its value */
    CHECK_EQ(download_u32(0x6444, 3, (uint32_t)-5, 4), 0);
    nmt(ODG_NMT_START, NID);
    outputs(0xA5, 0x5A, 1000, -1000);
    master_alive(200);
}

static void check_error_values(void)
{
    CHECK_EQ(pins_out[0], 0xA3); /* 0xA5: lines 1-4 from 0x6207 (0x3), 5-8 kept (0xA) */
    CHECK_EQ(pins_out[1], 0x00); /* 0x6206 default 0xFF, 0x6207 default 0x00 */
    CHECK_EQ(analog_out[0], 32767);
    CHECK_EQ(analog_out[1], -1000);
    CHECK_EQ(analog_out[2], -5);
    CHECK_EQ(analog_out[3], 0);
}

static void test_heartbeat_loss(void)
{
    boot();
    CHECK_EQ(pins_out[0], 0xA5);
    CHECK_EQ(analog_out[0], 1000);
    loop_ms(HB_TIME - 30u); /* the last heartbeat came 20 ms before: 90 ms, not late yet */
    CHECK_EQ(pins_out[0], 0xA5);
    loop_ms(20);
    check_error_values();
    CHECK_EQ(odg_node_state(&node), ODG_NMT_PRE_OPERATIONAL); /* 0x1029 absent: as 0 */
    /* the master is back and starts the node: the outputs keep their error values ... */
    master_alive(100);
    nmt(ODG_NMT_START, NID);
    loop_ms(5);
    check_error_values();
    /* ... until it writes them: a digital write releases the digital lines, an analog one the
     * analog outputs */
    CHECK_EQ(download_u32(0x6200, 1, 0x11, 1), 0);
    CHECK_EQ(pins_out[0], 0x11);
    CHECK_EQ(pins_out[1], 0x5A);
    CHECK_EQ(analog_out[0], 32767);
    CHECK_EQ(download_u32(DS401_AO_INDEX, 4, 7, 2), 0);
    CHECK_EQ(analog_out[0], 1000);
    CHECK_EQ(analog_out[3], 7);
    /* by RPDO too: RPDO1 maps the digital outputs */
    master_alive(40);
    loop_ms(HB_TIME + 10u);
    CHECK_EQ(pins_out[0], 0x13);
    nmt(ODG_NMT_START, NID);
    rx(0x200u + NID, 0x22, 0x44);
    CHECK_EQ(pins_out[0], 0x22);
    CHECK_EQ(pins_out[1], 0x44);
}

static void test_polarity_applies_to_error_values(void)
{
    boot();
    CHECK_EQ(download_u32(0x6202, 2, 0xF0, 1), 0);
    CHECK_EQ(pins_out[1], 0xAA);
    loop_ms(HB_TIME + 30u);
    CHECK_EQ(pins_out[1], 0xF0); /* error value 0x00, inverted by 0x6202 */
    CHECK_EQ(download_u32(0x6202, 2, 0x0F, 1), 0); /* polarity alone does not release */
    CHECK_EQ(pins_out[1], 0x0F);
}

static void test_nmt_stop_and_bus_off(void)
{
    boot();
    nmt(ODG_NMT_STOP, NID);
    master_alive(40);
    check_error_values();
    nmt(ODG_NMT_START, NID);
    outputs(0xA5, 0x5A, 1000, -1000);
    master_alive(40);
    CHECK_EQ(pins_out[0], 0xA5);
    nmt(ODG_NMT_ENTER_PREOP, NID); /* pre-operational: the outputs stay */
    master_alive(40);
    CHECK_EQ(pins_out[0], 0xA5);
    CHECK_EQ(analog_out[0], 1000);
    odg_node_can_state(&node, ODG_CAN_BUS_OFF);
    master_alive(40);
    check_error_values();
}

int main(void)
{
    test_heartbeat_loss();
    test_polarity_applies_to_error_values();
    test_nmt_stop_and_bus_off();
    return done();
}
