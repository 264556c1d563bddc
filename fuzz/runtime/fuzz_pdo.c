/*
 * fuzz_pdo.c - PDO reception (and transmission) with arbitrary mappings, set through the SDO
 * server first as CiA 301 orders it, against tests/node/pdo-node.eds.
 *
 * Input: a count byte (n % 5 PDOs to configure), then per PDO:
 *   k        bit 7: a TPDO, else an RPDO; k % 4 is the PDO number
 *   n        mapping entries (n % 10: up to one more than the node serves)
 *   entries  per entry one byte e: bit 7 clear: mappable object e % count (or a dummy
 *            index for an RPDO), with its own length unless bit 6 is set, then a length byte;
 *            bit 7 set: 4 raw bytes
 *   type     transmission type byte, and 2 bytes for the COB-ID's 11 bits (0: the default)
 * then the node is started (operational) and records follow, led by an opcode byte:
 *   0x00-0x7F  an RPDO frame: PDO op % 4, a DLC byte (0..15), 8 data bytes
 *   0x80-0x9F  a SYNC, with a counter byte when bit 0 is set
 *   0xA0-0xBF  time passes: the next byte in ms
 *   0xC0-0xDF  an expedited SDO download to a mapped object: entry byte, 4 value bytes
 *   0xE0-0xEF  a frame to any COB-ID: 2 identifier bytes, DLC, 8 data bytes
 *   0xF0-0xFF  an application request for TPDO op % 4
 * Properties: as fuzz_sdo.c (well-formed frames, NV in range, the server still serves).
 */
#include "harness.h"
#include "pdo_node.h"

#define DICT pdo_node

static uint32_t mappable[256];
static unsigned n_mappable;

/* Every sub-entry that may be mapped, as a mapping entry with its own length: each entry's, as
 * odg_find gives them (the members of a shared run have a list of descriptors in common). */
static void collect(void)
{
    const odg_entry_t *e;
    uint32_t p;
    for (e = DICT.entries; e < DICT.entries + DICT.n_entries; e++) {
        for (p = e->first; p < (uint32_t)e->first + e->count && n_mappable < 256u; p++) {
            odg_ref_t r;
            if (odg_find(&DICT, e->index, DICT.subs[p].sub, &r) == ODG_OK &&
                (r.sub->attr & (ODG_A_TPDO | ODG_A_RPDO))) {
                uint32_t bits = r.sub->type == ODG_T_BOOLEAN ? 1u : 8u * r.sub->size;
                mappable[n_mappable++] = (uint32_t)e->index << 16 | (uint32_t)r.sub->sub << 8 | bits;
            }
        }
    }
}

static uint32_t entry(input_t *in, int tx)
{
    uint8_t e = take(in);
    uint32_t m;
    if (e & 0x80u) {
        return take32(in);
    }
    if (!tx && e % 8u == 7u) {
        m = (uint32_t)(1u + e / 8u % 7u) << 16 | 8u; /* a dummy index 0x0001..0x0007 */
    } else {
        m = n_mappable ? mappable[e % n_mappable] : 0u;
    }
    return e & 0x40u ? (m & 0xFFFFFF00u) | take(in) : m;
}

/* CiA 301 order: invalidate, sub 0 = 0, entries, sub 0 = n, type, validate. The answers may
 * be aborts: the fuzzer explores refused configurations too. */
static void configure(input_t *in)
{
    uint8_t k = take(in), n = (uint8_t)(take(in) % 10u), i;
    int tx = (k & 0x80u) != 0;
    uint16_t comm = (uint16_t)((tx ? 0x1800u : 0x1400u) + k % 4u);
    uint16_t map = (uint16_t)(comm + 0x200u);
    uint32_t id, cob = (tx ? 0x180u : 0x200u) + 0x100u * (k % 4u) + NID; /* the pre-defined one */
    (void)sdo_write(comm, 1, 0x80000000u | cob, 4);
    (void)sdo_write(map, 0, 0, 1);
    for (i = 1; i <= n; i++) {
        (void)sdo_write(map, i, entry(in, tx), 4);
    }
    (void)sdo_write(map, 0, n, 1);
    (void)sdo_write(comm, 2, take(in), 1);
    id = take16(in) & 0x7FFu;
    (void)sdo_write(comm, 1, id != 0u ? id : cob, 4);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    input_t in;
    uint8_t count, i, d[8];
    static const uint8_t start[8] = {ODG_NMT_START, 0};
    in.p = data;
    in.n = size;
    if (n_mappable == 0u) {
        collect();
    }
    node_start(&DICT);
    count = (uint8_t)(take(&in) % 5u);
    for (i = 0; i < count; i++) {
        configure(&in);
    }
    frame(0, 0, start, 2);
    while (in.n > 0u) {
        uint8_t op = take(&in);
        if (op < 0x80u) {
            uint32_t cob = node.rpdo[op % ODG_NODE_MAX_RPDO].cob;
            uint8_t len = (uint8_t)(take(&in) & 15u);
            take_bytes(&in, d, 8);
            frame(cob & 0x7FFu, 0, d, len);
        } else if (op < 0xA0u) {
            d[0] = take(&in);
            frame(0x80, 0, d, (uint8_t)(op & 1u));
        } else if (op < 0xC0u) {
            odg_node_tick(&node, take(&in));
        } else if (op < 0xE0u) {
            static const uint8_t abort_[8] = {0x80, 0, 0, 0, 0, 0, 0, 0};
            uint32_t m = n_mappable ? mappable[take(&in) % n_mappable] : 0u;
            uint32_t v = take32(&in);
            uint8_t len = (uint8_t)((m & 0xFFu) / 8u);
            if (len >= 1u && len <= 4u) {
                /* a foreign frame to the server may have begun a transfer (in a block download
                 * this request would be a segment, rightly unanswered): end it first */
                frame(SDO_RX, 0, abort_, 8);
                (void)sdo_write((uint16_t)(m >> 16), (uint8_t)(m >> 8), v, len);
            }
        } else if (op < 0xF0u) {
            uint16_t id = (uint16_t)(take16(&in) & 0x7FFu);
            uint8_t len = (uint8_t)(take(&in) & 15u);
            take_bytes(&in, d, 8);
            frame(id, 0, d, len);
        } else {
            odg_node_tpdo_request(&node, (uint16_t)(op % 4u));
        }
    }
    still_serving();
    return 0;
}
