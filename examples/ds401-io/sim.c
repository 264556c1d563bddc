/*
 * sim.c - simulated hardware for the ds401-io node: every output is wired back to the input
 * of the same number (0x6200 line n -> 0x6000 line n, 0x6411 channel n -> 0x6401 channel n),
 * so whatever a master writes comes back as a change of state in a TPDO.
 *
 * The node program (runtime/linux/odg_node_main.c, built with -DODG_APP) calls odg_app_init
 * once and odg_app_tick every millisecond; the CiA 401 work is in runtime/profiles/ds401.c.
 */
#include <stdio.h>
#include <string.h>

#include "ds401_app.h"
#include "odg_app.h"

/* +1: no zero-length arrays when a function is absent */
static uint8_t wires[DS401_DO_GROUPS + 1u];
#if DS401_AI_CHANNELS > 0 || DS401_AO_CHANNELS > 0
static ds401_ao_t analog_wires[DS401_AO_CHANNELS + 1u];
#endif

/* How many inputs have an output wired to them. */
static uint16_t wired(uint16_t inputs, uint16_t outputs)
{
    return inputs < outputs ? inputs : outputs;
}

#if DS401_DI_GROUPS > 0
void ds401_read_inputs(uint8_t *groups, uint16_t n)
{
    memset(groups, 0, n);
    memcpy(groups, wires, wired(n, (uint16_t)DS401_DO_GROUPS));
}
#endif

#if DS401_DO_GROUPS > 0
void ds401_write_outputs(const uint8_t *groups, uint16_t n)
{
    memcpy(wires, groups, n);
}
#endif

#if DS401_AI_CHANNELS > 0
/* An output wider than the input saturates at the input's range. */
static ds401_ai_t to_input(int64_t v)
{
    const int64_t top = ((int64_t)1 << (8 * sizeof(ds401_ai_t) - 1)) - 1;
    return (ds401_ai_t)(v > top ? top : v < -top - 1 ? -top - 1 : v);
}

void ds401_read_analog(ds401_ai_t *values, uint16_t n)
{
    uint16_t c, k = wired(n, (uint16_t)DS401_AO_CHANNELS);
    for (c = 0; c < n; c++) {
        values[c] = c < k ? to_input(analog_wires[c]) : 0;
    }
}
#endif

#if DS401_AO_CHANNELS > 0
void ds401_write_analog(const ds401_ao_t *values, uint16_t n)
{
    memcpy(analog_wires, values, n * sizeof *values);
}
#endif

void odg_app_init(odg_node_t *node)
{
    (void)wired, (void)wires;
    odg_abort_t ac = ds401_init(node);
    if (ac != ODG_OK) {
        fprintf(stderr, "ds401-io: ds401_init: 0x%08lX %s\n", (unsigned long)ac, odg_abort_text(ac));
    }
}

void odg_app_tick(odg_node_t *node, uint32_t elapsed_ms)
{
    (void)elapsed_ms;
    ds401_poll(node);
}
