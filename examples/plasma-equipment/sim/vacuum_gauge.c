/* Simulated vacuum gauge (node 2): reports its switch states back and, while measuring
 * ("start/stop" 0), a chamber pressure of 12 Pa. */
#include "odg_app.h"
#include "vacuum_gauge.h"

void odg_app_init(odg_node_t *node)
{
    (void)node;
}

void odg_app_tick(odg_node_t *node, uint32_t elapsed_ms)
{
    uint8_t on = vacuum_gauge_x6200_write_output_8_bit_s2_start_stop == 0u;
    (void)node;
    (void)elapsed_ms;
    vacuum_gauge_x6000_read_input_8_bit_s1_control_mode_state = vacuum_gauge_x6200_write_output_8_bit_s1_control_mode;
    vacuum_gauge_x6000_read_input_8_bit_s2_start_stop_state = vacuum_gauge_x6200_write_output_8_bit_s2_start_stop;
    vacuum_gauge_x6401_read_analog_input_16_bit_s1_pressure = (int16_t)(on ? 12 : 0);
}
