/* Simulated mass-flow controller (node 3): valve mode 0 closed (no flow), 1 control (flow
 * follows the set-point), 2 purge (full scale, 1000 sccm); reports its switch states back. */
#include "odg_app.h"
#include "flow_meter.h"

void odg_app_init(odg_node_t *node)
{
    (void)node;
}

void odg_app_tick(odg_node_t *node, uint32_t elapsed_ms)
{
    uint8_t valve = flow_meter_x6200_write_output_8_bit_s2_valve_mode;
    (void)node;
    (void)elapsed_ms;
    flow_meter_x6000_read_input_8_bit_s1_control_mode_state = flow_meter_x6200_write_output_8_bit_s1_control_mode;
    flow_meter_x6000_read_input_8_bit_s2_valve_mode_state = valve;
    flow_meter_x6401_read_analog_input_16_bit_s1_flow =
        valve == 1u ? flow_meter_x6411_write_analog_output_16_bit_s1_flow_set_point : (int16_t)(valve == 2u ? 1000 : 0);
}
