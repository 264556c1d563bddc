/*
 * fuzz_sdo.c - the SDO server fed arbitrary frame sequences: expedited, segmented and block
 * transfers, aborts, short frames, frames to any COB-ID, NMT commands, time passing and a busy
 * controller, against the alltypes dictionary (every data type, persistence, hooks).
 *
 * Input: one byte chooses the hooks, then records, each led by an opcode byte:
 *   0x00-0x7F  a frame to the SDO server: 8 data bytes follow; the opcode's low 4 bits
 *              give the DLC when below 9 (else 8)
 *   0x80-0x9F  time passes: the next byte times (1 + opcode bits 0..4) ms
 *   0xA0-0xBF  a frame to any COB-ID: 2 bytes of identifier (11 bits), flags in opcode bits
 *              0..1, a DLC byte (0..15), 8 data bytes
 *   0xC0-0xDF  an NMT command: command and node-id bytes
 *   0xE0-0xFF  the next (opcode & 3) sends fail
 * Properties: every frame sent is well formed, NV accesses stay in range, and afterwards the
 * server answers a fresh upload.
 */
#include "alltypes.h"
#include "harness.h"

/* The hooks of the generated table, registered anew for every input from its first byte. */
static void hooks(uint8_t b)
{
    (void)odg_hook_register(&alltypes, 0x2006, 0, alltypes_notice, NULL);
    (void)odg_hook_register(&alltypes, 0x2101, 0, pick_hook(b), NULL);
    (void)odg_hook_register(&alltypes, 0x2005, 0, pick_hook((uint8_t)(b >> 2)), NULL);
    (void)odg_hook_register(&alltypes, 0x2103, 4, pick_hook((uint8_t)(b >> 4)), NULL);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    input_t in;
    in.p = data;
    in.n = size;
    node_start(&alltypes);
    hooks(take(&in));
    while (in.n > 0u) {
        uint8_t op = take(&in), d[8];
        if (op < 0x80u) {
            uint8_t len = (uint8_t)(op & 15u);
            take_bytes(&in, d, 8);
            frame(SDO_RX, 0, d, len <= 8u ? len : 8u);
        } else if (op < 0xA0u) {
            odg_node_tick(&node, (uint32_t)take(&in) * (1u + (op & 31u)));
        } else if (op < 0xC0u) {
            uint16_t id = (uint16_t)(take16(&in) & 0x7FFu);
            uint8_t len = (uint8_t)(take(&in) & 15u);
            take_bytes(&in, d, 8);
            frame(id, (uint8_t)(op & 3u), d, len);
        } else if (op < 0xE0u) {
            memset(d, 0, sizeof d);
            d[0] = take(&in);
            d[1] = take(&in);
            frame(0, 0, d, 2);
        } else {
            send_fails = op & 3;
        }
    }
    still_serving();
    return 0;
}
