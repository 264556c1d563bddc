/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ds401.c - CiA 401 (generic I/O) application glue over a dictionary made by
 * `odgen profile ds401 --generate`. The generated ds401_app.h configures it (channel counts,
 * the analog objects and their C types) and declares the interface; compile this file with
 * that header's directory on the include path. C99, no malloc, no stdio.
 *
 * Values go through the typed access of odg.h (odg_get / odg_set): the inputs can be stored
 * although they are read-only on the bus, and no hook runs from inside another.
 */
#include <string.h>

#include "ds401_app.h"

#define DS401_TPDOS (ODG_NODE_MAX_TPDO < 32u ? ODG_NODE_MAX_TPDO : 32u)

static uint8_t get_u8(const odg_dict_t *d, uint16_t index, uint8_t sub, uint8_t absent)
{
    uint8_t v;
    return odg_get_u8(d, index, sub, &v) == ODG_OK ? v : absent;
}


#if DS401_DI_GROUPS > 0 || DS401_AI_CHANNELS > 0

static uint32_t get_u32(const odg_dict_t *d, uint16_t index, uint8_t sub)
{
    uint32_t v;
    return odg_get_u32(d, index, sub, &v) == ODG_OK ? v : 0u;
}

/* The TPDOs (bit k: 0x1800 + k) whose mapping holds index/sub now. */
static uint32_t tpdos_mapping(const odg_dict_t *d, uint16_t index, uint8_t sub)
{
    uint32_t mask = 0, k, i, want = (uint32_t)index << 8 | sub;
    for (k = 0; k < DS401_TPDOS; k++) {
        uint16_t map = (uint16_t)(0x1A00u + k);
        uint32_t count = get_u8(d, map, 0, 0);
        for (i = 1; i <= count; i++) {
            if (get_u32(d, map, (uint8_t)i) >> 8 == want) {
                mask |= (uint32_t)1u << k; /* up to 32 TPDOs: 1u has 16 bits on AVR */
                break;
            }
        }
    }
    return mask;
}
#endif

#if DS401_DI_GROUPS > 0
/* ---- digital inputs ------------------------------------------------------------------- */

static uint8_t di_now[DS401_DI_GROUPS], di_last[DS401_DI_GROUPS];

/* Read the pins, apply the polarity (0x6002: 1 inverts the line) and store into 0x6000. */
static void refresh_inputs(const odg_dict_t *d)
{
    uint16_t g;
    ds401_read_inputs(di_now, (uint16_t)DS401_DI_GROUPS);
    for (g = 0; g < DS401_DI_GROUPS; g++) {
        uint8_t sub = (uint8_t)(g + 1u);
        di_now[g] = (uint8_t)(di_now[g] ^ get_u8(d, 0x6002, sub, 0));
        (void)odg_set_u8(d, 0x6000, sub, di_now[g]);
    }
}

/* Lines whose change is an event: any change under 0x6006, rising under 0x6007, falling under
 * 0x6008, all only while 0x6005 is TRUE. */
static uint32_t digital_events(const odg_dict_t *d)
{
    uint32_t want = 0;
    uint16_t g;
    int enabled = get_u8(d, 0x6005, 0, 1) != 0u;
    refresh_inputs(d);
    for (g = 0; g < DS401_DI_GROUPS; g++) {
        uint8_t sub = (uint8_t)(g + 1u);
        unsigned now = di_now[g], changed = now ^ di_last[g];
        unsigned hit = (changed & get_u8(d, 0x6006, sub, 0)) |
                       (changed & now & get_u8(d, 0x6007, sub, 0)) |
                       (changed & ~now & get_u8(d, 0x6008, sub, 0));
        di_last[g] = di_now[g];
        if (enabled && hit != 0u) {
            want |= tpdos_mapping(d, 0x6000, sub);
        }
    }
    return want;
}
#endif

#if DS401_DO_GROUPS > 0
/* ---- digital outputs ------------------------------------------------------------------ */

static uint8_t do_pins[DS401_DO_GROUPS];

/* 0x6200 with the polarity of 0x6202 (1 inverts the line) to the pins. */
static void apply_outputs(const odg_dict_t *d)
{
    uint16_t g;
    for (g = 0; g < DS401_DO_GROUPS; g++) {
        uint8_t sub = (uint8_t)(g + 1u);
        do_pins[g] = (uint8_t)(get_u8(d, 0x6200, sub, 0) ^ get_u8(d, 0x6202, sub, 0));
    }
    ds401_write_outputs(do_pins, (uint16_t)DS401_DO_GROUPS);
}
#endif

#if DS401_AI_CHANNELS > 0
/* ---- analog inputs -------------------------------------------------------------------- */

static ds401_ai_t ai_now[DS401_AI_CHANNELS], ai_base[DS401_AI_CHANNELS];
static uint8_t ai_above[DS401_AI_CHANNELS], ai_below[DS401_AI_CHANNELS];

static int32_t get_i32(const odg_dict_t *d, uint16_t index, uint8_t sub)
{
    int32_t v;
    return odg_get_i32(d, index, sub, &v) == ODG_OK ? v : 0;
}

static void refresh_analog(const odg_dict_t *d)
{
    uint16_t c;
    ds401_read_analog(ai_now, (uint16_t)DS401_AI_CHANNELS);
    for (c = 0; c < DS401_AI_CHANNELS; c++) {
        (void)odg_set(d, DS401_AI_INDEX, (uint8_t)(c + 1u), &ai_now[c], (uint32_t)sizeof ai_now[c]);
    }
}

/* One channel against 0x6421 (bit 0 upper limit exceeded, 1 below the lower limit, 2 changed
 * by more than the delta, 3 fell by more, 4 rose by more): limits count when crossed. */
static int analog_event(const odg_dict_t *d, uint16_t c)
{
    uint8_t sub = (uint8_t)(c + 1u);
    unsigned select = get_u8(d, 0x6421, sub, 0x07);
    int64_t v = ai_now[c], base = ai_base[c], delta = get_u32(d, 0x6426, sub);
    int64_t upper = get_i32(d, 0x6424, sub), lower = get_i32(d, 0x6425, sub);
    int above = v > upper, below = v < lower, hit;
    hit = ((select & 1u) && above && !ai_above[c]) || ((select & 2u) && below && !ai_below[c]) ||
          ((select & 4u) && (v - base > delta || base - v > delta)) ||
          ((select & 8u) && base - v > delta) || ((select & 16u) && v - base > delta);
    ai_above[c] = (uint8_t)above;
    ai_below[c] = (uint8_t)below;
    return hit;
}

static uint32_t analog_events(const odg_dict_t *d)
{
    uint32_t want = 0;
    uint16_t c;
    int enabled = get_u8(d, 0x6423, 0, 0) != 0u;
    refresh_analog(d);
    for (c = 0; c < DS401_AI_CHANNELS; c++) {
        if (analog_event(d, c) && enabled) {
            ai_base[c] = ai_now[c];
            want |= tpdos_mapping(d, DS401_AI_INDEX, (uint8_t)(c + 1u));
        } else if (!enabled) {
            ai_base[c] = ai_now[c];
        }
    }
    return want;
}
#endif

#if DS401_AO_CHANNELS > 0
/* ---- analog outputs ------------------------------------------------------------------- */

static ds401_ao_t ao_values[DS401_AO_CHANNELS];

static void apply_analog(const odg_dict_t *d)
{
    uint16_t c;
    for (c = 0; c < DS401_AO_CHANNELS; c++) {
        (void)odg_get(d, DS401_AO_INDEX, (uint8_t)(c + 1u), &ao_values[c],
                      (uint32_t)sizeof ao_values[c]);
    }
    ds401_write_analog(ao_values, (uint16_t)DS401_AO_CHANNELS);
}
#endif

/* ---- interface ------------------------------------------------------------------------ */

/* The one hook of the process data: inputs refreshed before a read (PRE_READ on 0x6000 and the
 * analog inputs), outputs applied after a write (POST_WRITE on 0x6200, 0x6202 and the analog
 * outputs), as `odgen profile ds401 --generate` declares them. */
static odg_abort_t io_hook(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data,
                           uint32_t len, void *ctx)
{
    uint16_t index = ref->entry->index;
    (void)kind, (void)data, (void)len, (void)ctx, (void)index;
#if DS401_DI_GROUPS > 0
    if (index == 0x6000u) {
        refresh_inputs(ref->dict);
    }
#endif
#if DS401_DO_GROUPS > 0
    if (index == 0x6200u || index == 0x6202u) {
        apply_outputs(ref->dict);
    }
#endif
#if DS401_AI_CHANNELS > 0
    if (index == DS401_AI_INDEX) {
        refresh_analog(ref->dict);
    }
#endif
#if DS401_AO_CHANNELS > 0
    if (index == DS401_AO_INDEX) {
        apply_analog(ref->dict);
    }
#endif
    return ODG_OK;
}

/* io_hook for sub-indices 1..n of `index`. */
static odg_abort_t hook_range(const odg_dict_t *d, uint16_t index, uint32_t n)
{
    uint32_t s;
    odg_abort_t ac = ODG_OK;
    for (s = 1; s <= n && ac == ODG_OK; s++) {
        ac = odg_hook_register(d, index, (uint8_t)s, io_hook, NULL);
    }
    return ac;
}

odg_abort_t ds401_init(odg_node_t *node)
{
    const odg_dict_t *d = node->cfg.dict;
    odg_abort_t ac = ODG_OK;
#if DS401_DI_GROUPS > 0
    ac = hook_range(d, 0x6000, DS401_DI_GROUPS);
    refresh_inputs(d);
    memcpy(di_last, di_now, sizeof di_last);
#endif
#if DS401_DO_GROUPS > 0
    if (ac == ODG_OK) {
        ac = hook_range(d, 0x6200, DS401_DO_GROUPS);
    }
    if (ac == ODG_OK) {
        ac = hook_range(d, 0x6202, DS401_DO_GROUPS);
    }
    apply_outputs(d);
#endif
#if DS401_AI_CHANNELS > 0
    if (ac == ODG_OK) {
        ac = hook_range(d, DS401_AI_INDEX, DS401_AI_CHANNELS);
    }
    refresh_analog(d);
    memcpy(ai_base, ai_now, sizeof ai_base);
#endif
#if DS401_AO_CHANNELS > 0
    if (ac == ODG_OK) {
        ac = hook_range(d, DS401_AO_INDEX, DS401_AO_CHANNELS);
    }
    apply_analog(d);
#endif
    (void)d, (void)hook_range, (void)get_u8;
    return ac;
}

void ds401_poll(odg_node_t *node)
{
    uint32_t want = 0, k;
#if DS401_DI_GROUPS > 0
    want |= digital_events(node->cfg.dict);
#endif
#if DS401_AI_CHANNELS > 0
    want |= analog_events(node->cfg.dict);
#endif
    for (k = 0; k < DS401_TPDOS; k++) {
        if (want >> k & 1u) {
            odg_node_tpdo_request(node, (uint16_t)k);
        }
    }
}
