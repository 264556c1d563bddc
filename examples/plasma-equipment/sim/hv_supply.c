/* Simulated high-voltage supply (node 1): on while "start/stop" is 0; the output level
 * 0..100 sets 0..10 kV and 0..300 mA. Measurements go out in TPDO1 at every SYNC. */
#include "odg_app.h"
#include "hv_supply.h"

void odg_app_init(odg_node_t *node)
{
    (void)node;
}

void odg_app_tick(odg_node_t *node, uint32_t elapsed_ms)
{
    int on = hv_supply_x6200_write_output_8_bit_s1_start_stop == 0u;
    int level = hv_supply_x6410_write_analog_output_8_bit_s1_output_level;
    (void)node;
    (void)elapsed_ms;
    level = level < 0 ? 0 : level > 100 ? 100 : level;
    hv_supply_x6401_read_analog_input_16_bit_s1_output_current = (int16_t)(on ? level * 3 : 0);
    hv_supply_x6401_read_analog_input_16_bit_s2_output_voltage = (int16_t)(on ? level * 100 : 0);
}
