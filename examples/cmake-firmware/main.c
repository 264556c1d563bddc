/*
 * main.c - a host stand-in for a firmware main loop using the generated io_node dictionary:
 * hooks tie 0x6000/0x6200 to "hardware" (here: a loop-back byte), application code uses the
 * typed accessors, and an SDO-style write goes through the runtime's checks.
 */
#include <stdio.h>
#include "io_node.h"

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
    return 0;
}
