/*
 * main.c - a host stand-in for a firmware main loop using the generated io_node dictionary:
 * hooks tie 0x6000/0x6200 to "hardware" (here: a loop-back byte), application code uses the
 * typed accessors, an SDO-style write goes through the runtime's checks, and a CANopen node
 * (odgen::node) answers an SDO upload and an NMT start over a CAN "driver" that records frames.
 */
#include <stdio.h>
#include <string.h>

#include "io_node.h"
#include "odg_node.h"

static uint8_t pins; /* the simulated I/O port: outputs loop back to inputs */

odg_abort_t io_node_read_inputs(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                                void *ctx)
{
    (void)ref; (void)kind; (void)data; (void)len; (void)ctx;
    io_node_x6000_read_input_8_bit_s1_read_input_1h_to_8h = pins;
    return ODG_OK;
}

odg_abort_t io_node_apply_outputs(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                                  void *ctx)
{
    (void)ref; (void)len; (void)ctx;
    if (kind == ODG_HOOK_PRE_WRITE) {
        return ((const uint8_t *)data)[0] == 0xFFu ? (odg_abort_t)ODG_ABORT_VALUE_HIGH : (odg_abort_t)ODG_OK;
    }
    pins = io_node_x6200_write_output_8_bit_s1_write_output_1h_to_8h;
    return ODG_OK;
}

static odg_frame_t last;  /* the frame the node sent last */
static unsigned n_frames;

static int can_send(void *ctx, const odg_frame_t *frame)
{
    (void)ctx;
    last = *frame;
    n_frames++;
    return 0; /* queued */
}

/* The node of this dictionary: boot-up, an SDO upload of 0x1017, then operational. */
static int run_node(void)
{
    static odg_node_t node;
    odg_node_config_t cfg;
    odg_frame_t rx;
    unsigned heartbeat;
    memset(&cfg, 0, sizeof cfg);
    cfg.dict = &io_node;
    cfg.node_id = 5;
    cfg.send = can_send;
    if (odg_node_init(&node, &cfg) != ODG_OK || last.id != 0x705u) return 1; /* boot-up */
    memset(&rx, 0, sizeof rx);
    rx.id = 0x605u; /* SDO upload request of 0x1017 sub 0 */
    rx.len = 8;
    rx.data[0] = 0x40;
    rx.data[1] = 0x17;
    rx.data[2] = 0x10;
    odg_node_receive(&node, &rx);
    if (last.id != 0x585u || last.data[0] != 0x4Bu) return 1; /* expedited, two bytes */
    heartbeat = (unsigned)last.data[4] | (unsigned)last.data[5] << 8;
    rx.id = 0;  /* NMT start, all nodes */
    rx.len = 2;
    rx.data[0] = ODG_NMT_START;
    rx.data[1] = 0;
    odg_node_receive(&node, &rx);
    odg_node_tick(&node, 1);
    printf("node: %u frames sent, 0x1017 = %u ms read by SDO, %s\n", n_frames, heartbeat,
           odg_node_state(&node) == ODG_NMT_OPERATIONAL ? "operational" : "not operational");
    return odg_node_state(&node) == ODG_NMT_OPERATIONAL ? 0 : 1;
}

int main(void)
{
    odg_ref_t out, in;
    uint8_t value = 0x5A, read = 0;
    uint32_t n = 0;
    if (odg_init(&io_node, 5) != ODG_OK) return 1;
    if (odg_find(&io_node, IO_NODE_IDX_X6200_WRITE_OUTPUT_8_BIT, 1, &out) != ODG_OK) return 1;
    if (odg_find(&io_node, IO_NODE_IDX_X6000_READ_INPUT_8_BIT, 1, &in) != ODG_OK) return 1;
    if (odg_write(&out, &value, 1) != ODG_OK) return 1;
    if (odg_read(&in, 0, &read, 1, &n) != ODG_OK || read != value) return 1;
    value = 0xFF;
    if (odg_write(&out, &value, 1) != ODG_ABORT_VALUE_HIGH) return 1;
    printf("firmware: outputs 0x%02X looped back to inputs, heartbeat %u ms, SDO COB-ID 0x%03lX\n", read,
           (unsigned)io_node_x1017_producer_heartbeat_time,
           (unsigned long)io_node_x1200_sdo_server_parameter_s1_cob_id_client_to_server_rx);
    return run_node();
}
