/* Simulated frequency inverter (node 4) driving the roughing pump: reports its switch
 * states back (the drive frequency it receives is applied to the simulated motor only). */
#include "odg_app.h"
#include "inverter.h"

void odg_app_init(odg_node_t *node)
{
    (void)node;
}

void odg_app_tick(odg_node_t *node, uint32_t elapsed_ms)
{
    (void)node;
    (void)elapsed_ms;
    inverter_x6000_read_input_8_bit_s1_run_stop_state = inverter_x6200_write_output_8_bit_s1_run_stop;
    inverter_x6000_read_input_8_bit_s2_control_mode_state = inverter_x6200_write_output_8_bit_s2_control_mode;
}
