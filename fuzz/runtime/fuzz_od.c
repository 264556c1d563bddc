/*
 * fuzz_od.c - odg_read / odg_write / odg_write_part / odg_check_mapping / odg_hook_register
 * and the typed access (odg_get / odg_set / odg_ptr) on the alltypes dictionary (every CiA 301 data type, limits, strings, domains, both
 * persistence groups, 0x1010/0x1011), straight through the runtime API.
 *
 * Input: records led by an opcode byte; most name a sub-entry by 2 bytes (its position in the
 * dictionary, modulo the number of sub-entries), or, for opcode bit 4, by raw index and sub:
 *   op % 8 == 0..1  write: a length byte (0..71), then that many bytes
 *   op % 8 == 2     write_part: offset, length and total bytes, then the data
 *   op % 8 == 3..4  read: offset byte, capacity byte (0..79)
 *   op % 8 == 5     check_mapping: 4 raw bytes, direction from op bit 5
 *   op % 8 == 6     register a hook (accept, refuse or none, from the next byte)
 *   op % 8 == 7     odg_length; odg_get in the C size 1 << (op bits 3-4), odg_set of that value
 * Properties: reads never exceed their capacity; odg_ptr agrees with odg_get; a number written whole reads back as the
 * same bytes; a failed write leaves the value unchanged; and at the end odg_verify still
 * finds the dictionary consistent (every value within its limits, strings terminated,
 * domain lengths within capacity).
 */
#include "alltypes.h"
#include "harness.h"

#define DICT alltypes

static uint8_t nv_booted[sizeof nv_mem];
static odg_hook_slot_t slots_booted[64];
static int have_nv;
static odg_persist_t persist;

static int is_number(const odg_sub_t *s)
{
    return s->type != ODG_T_VISIBLE_STRING && s->type != ODG_T_OCTET_STRING &&
           s->type != ODG_T_UNICODE_STRING && s->type != ODG_T_DOMAIN &&
           ODG_S_CLASS(s->storage) != ODG_S_COMMAND;
}

static odg_abort_t locate(input_t *in, uint8_t op, odg_ref_t *r)
{
    uint16_t index;
    uint8_t sub;
    if (op & 0x10u) {
        index = take16(in);
        sub = take(in);
    } else {
        index = index_of(&DICT, take16(in) % subs_of_entries(&DICT), &sub);
    }
    return odg_find(&DICT, index, sub, r);
}

/* The value's wire bytes before and after a write: unchanged on failure, equal to what was
 * written for a number written whole. Reads without PRE_READ effects only (offset 8 never
 * runs the hook, so reading at 0 is used for numbers, where hooks here change nothing). */
static void write_whole(const odg_ref_t *r, input_t *in)
{
    uint8_t d[72], before[80], after[80];
    uint32_t len = take(in) % 72u, nb = 0, na = 0;
    odg_abort_t rb, ra, ac;
    take_bytes(in, d, len);
    rb = odg_read(r, 0, before, sizeof before, &nb);
    ac = odg_write(r, d, len);
    ra = odg_read(r, 0, after, sizeof after, &na);
    REQUIRE(nb <= sizeof before && na <= sizeof after);
    if (rb != ODG_OK || ra != ODG_OK || ODG_S_CLASS(r->sub->storage) == ODG_S_COMMAND) {
        return;
    }
    if (ac != ODG_OK && ac != ODG_ABORT_GENERAL) { /* refused: nothing stored */
        REQUIRE(na == nb && memcmp(before, after, na) == 0);
    } else if (ac == ODG_OK && is_number(r->sub)) {
        REQUIRE(na == len && memcmp(after, d, len) == 0);
    }
}

/* Typed access in the C size op bits 3-4 pick: a number read back unchanged with odg_set
 * (an arbitrary value could break the limits odg_verify checks at the end), its pointer
 * agreeing; no input consumed, so the seeds keep their meaning. */
static void typed_round_trip(const odg_ref_t *r, uint8_t op)
{
    uint8_t v[8];
    uint32_t size = 1u << ((op >> 3) & 3u);
    uint16_t index = r->entry->index;
    int rom = ODG_S_CLASS(r->sub->storage) == ODG_S_ROM;
    uint8_t *p = (uint8_t *)odg_ptr(&DICT, index, r->sub->sub, size);
    if (odg_get(&DICT, index, r->sub->sub, v, size) != ODG_OK) {
        REQUIRE(p == NULL);
        return;
    }
    REQUIRE(rom ? p == NULL : (p != NULL && memcmp(p, v, size) == 0));
    REQUIRE(odg_set(&DICT, index, r->sub->sub, v, size) == (rom ? ODG_ABORT_READ_ONLY : ODG_OK));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    input_t in;
    in.p = data;
    in.n = size;
    if (!have_nv) {
        memset(nv_mem, 0xFF, sizeof nv_mem);
        REQUIRE(odg_init(&DICT, NID) == ODG_OK && odg_persist_init(&persist, &DICT, &nv_ram, NULL) == ODG_OK);
        memcpy(nv_booted, nv_mem, sizeof nv_mem);
        REQUIRE(DICT.n_hooks <= 64u);
        memcpy(slots_booted, DICT.hook_slots, DICT.n_hooks * sizeof *slots_booted);
        have_nv = 1;
    }
    /* every input starts from the same state: NV as after the first boot, hooks as generated */
    memcpy(nv_mem, nv_booted, sizeof nv_mem);
    memcpy(DICT.hook_slots, slots_booted, DICT.n_hooks * sizeof *slots_booted);
    REQUIRE(odg_init(&DICT, NID) == ODG_OK && odg_persist_init(&persist, &DICT, &nv_ram, NULL) == ODG_OK);
    while (in.n > 0u) {
        uint8_t op = take(&in), buf[80];
        odg_ref_t r;
        uint32_t n = 0;
        if (op % 8u == 5u) {
            (void)odg_check_mapping(&DICT, take32(&in), op & 0x20u ? ODG_A_TPDO : ODG_A_RPDO, &r);
            continue;
        }
        if (locate(&in, op, &r) != ODG_OK) {
            continue;
        }
        switch (op % 8u) {
        case 0:
        case 1:
            write_whole(&r, &in);
            break;
        case 2: {
            uint32_t off = take(&in), len = take(&in) % 72u, total = take(&in);
            take_bytes(&in, buf, len);
            (void)odg_write_part(&r, off, buf, len, total);
            break;
        }
        case 3:
        case 4: {
            uint32_t off = take(&in), cap = take(&in) % 80u;
            (void)odg_read(&r, off, buf, cap, &n);
            REQUIRE(n <= cap);
            break;
        }
        case 6:
            (void)odg_hook_register(&DICT, r.entry->index, r.sub->sub, pick_hook(take(&in)), NULL);
            break;
        default:
            (void)odg_length(&r);
            typed_round_trip(&r, op);
            break;
        }
    }
    {
        uint16_t bad = 0;
        REQUIRE(odg_verify(&DICT, &bad) == ODG_OK);
    }
    return 0;
}
