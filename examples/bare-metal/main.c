/*
 * main.c - a CANopen I/O node on a Cortex-M: the io-node example's dictionary (8 digital
 * inputs 0x6000, 8 outputs 0x6200, parameters kept in an EEPROM), the odgen runtime and node,
 * a CAN driver (can.c), an NV driver (nv_eeprom.c) and a 1 ms tick. docs/porting.md explains
 * each piece; board.c has the hardware stubs to replace.
 *
 * Built with -DODG_CONFIG='"io_node_config.h"' only: the generated header sizes the node to the
 * dictionary and leaves out of the runtime what the dictionary does not use.
 */
#include <string.h>

#include "board.h"
#include "can.h"
#include "io_node.h"
#include "nv_eeprom.h"
#include "odg_node.h"

#define NODE_ID 5u /* or from DIP switches, or unset and configured by LSS */

/* The NV the node uses must fit the EEPROM. */
typedef char nv_fits[IO_NODE_NV_SIZE <= BOARD_EEPROM_SIZE ? 1 : -1];

static volatile uint32_t ms_now; /* written by SysTick only; one aligned word: read whole */

void SysTick_Handler(void)
{
    ms_now++;
}

/* The hooks io-node.toml names: 0x6000 sub 1 is read from the pins whenever an SDO upload or
 * a TPDO reads it; a write to 0x6200 sub 1 (SDO or RPDO) drives them. */
odg_abort_t io_node_read_inputs(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                                void *ctx)
{
    (void)ref; (void)kind; (void)data; (void)len; (void)ctx;
    io_node_x6000_read_input_8_bit_s1_read_input_1h_to_8h = board_read_inputs();
    return ODG_OK;
}

odg_abort_t io_node_apply_outputs(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                                  void *ctx)
{
    (void)ref; (void)data; (void)len; (void)ctx;
    if (kind == ODG_HOOK_POST_WRITE) {
        board_write_outputs(io_node_x6200_write_output_8_bit_s1_write_output_1h_to_8h);
    }
    return ODG_OK;
}

int main(void)
{
    static odg_node_t node; /* all of the node's state: static, not on the stack */
    odg_node_config_t cfg;
    uint32_t last;
    board_init();
    memset(&cfg, 0, sizeof cfg);
    cfg.dict = &io_node;
    cfg.node_id = NODE_ID;
    cfg.nv = &nv_eeprom;
    cfg.send = can_send;
    /* Boot-up, pre-operational. Not ODG_OK: the EEPROM failed and the node runs on the
     * defaults (and told the master by EMCY 0x5530); nothing to do here but go on. */
    (void)odg_node_init(&node, &cfg);
    last = ms_now;
    for (;;) {
        uint32_t now;
        can_poll(&node);           /* received frames, lost frames, bus-off and error passive */
        now = ms_now;
        if (now != last) {
            odg_node_tick(&node, now - last); /* heartbeat, timers, event-driven TPDOs */
            last = now;
        }
        board_wait_for_interrupt(); /* a frame or the tick wakes it */
    }
}
