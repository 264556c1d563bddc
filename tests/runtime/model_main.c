/*
 * model_main.c - the C runtime side of the model-based persistence test
 * (tests/persist_model.py): several firmware versions of one device, each a generated
 * dictionary (v0, v1, ...) linked into this one program (versions.h, written by the test),
 * booted in turn on one NV memory (the NOR model of nv_fault.c). Commands on stdin, one a line:
 *
 *   nv SIZE          a new blank NV of SIZE bytes                          -> "ok"
 *   window SIZE      the driver shows SIZE bytes of the same NV (a driver sized by each
 *                    firmware's NAME_NV_SIZE); bytes past it keep what they hold -> "ok"
 *   boot K           boot version K: per group whether its region was blank before
 *                    ("blank G 0|1"), the boot ("rc", "group", "seen" lines), then every
 *                    persisted value as odg_read serves it ("value IIII SS HEX"), "end"
 *   set IIII SS HEX  odg_write of the wire bytes HEX                       -> "set ABORT"
 *   save | load      "save" / "load" written to 0x1010 / 0x1011 sub 1      -> "save ABORT"
 *   cut N            the power fails once N more bytes are programmed or erased (the byte in
 *                    progress left half done)                              -> "ok"
 *   power            the power is back                                     -> "ok"
 *   failwrite N      the N-th write call from now fails (the driver says so) -> "ok"
 *   sizes            NAME_NV_SIZE of each version                          -> "sizes N..."
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "nv_fault.h"
#include "versions.h" /* VERSIONS[], NV_SIZES[], N_VERSIONS */

#define NV_MAX 0x80000u /* room for regions above 64 KiB (ODG_PERSIST_MAX_REGION) */

static uint8_t mem[NV_MAX];
static nv_fault_t nv;
static odg_persist_t persist;
static const odg_dict_t *cur;

static int blank(uint32_t addr, uint32_t len)
{
    uint32_t i;
    for (i = 0; i < len; i++) {
        if (addr + i >= nv.size || mem[addr + i] != 0xFFu) {
            return addr + i < nv.size ? 0 : 1;
        }
    }
    return 1;
}

static void values(const odg_dict_t *d)
{
    uint16_t e, p;
    for (e = 0; e < d->n_entries; e++) {
        const odg_entry_t *en = &d->entries[e];
        for (p = en->first; p < en->first + en->count; p++) {
            const odg_sub_t *s = &d->subs[p];
            /* the elements 1..N of a packed ARRAY share one descriptor */
            unsigned k = (en->code & ODG_E_PACKED) && p > en->first ? 1u : s->sub;
            if (ODG_S_CLASS(s->storage) != ODG_S_PERSIST) {
                continue;
            }
            for (; k <= s->sub; k++) {
                odg_ref_t ref;
                uint8_t buf[512];
                uint32_t len = 0, i;
                if (odg_find(d, en->index, (uint8_t)k, &ref) != ODG_OK ||
                    odg_read(&ref, 0, buf, sizeof buf, &len) != ODG_OK) {
                    len = 0;
                }
                printf("value %04X %02X ", en->index, k);
                for (i = 0; i < len; i++) {
                    printf("%02X", buf[i]);
                }
                printf("\n");
            }
        }
    }
}

static void boot(unsigned k)
{
    static odg_boot_t b[16];
    odg_abort_t rc;
    uint8_t g;
    cur = VERSIONS[k];
    for (g = 0; g < cur->n_groups; g++) {
        printf("blank %u %d\n", g, blank(cur->groups[g].nv_addr, cur->groups[g].region));
    }
    memset(b, 0, sizeof b);
    odg_init(cur, 5);
    rc = odg_persist_boot(&persist, cur, &nv.driver, b);
    printf("rc %08lX\n", (unsigned long)rc);
    for (g = 0; g < cur->n_groups; g++) {
        printf("group %u status %u kept %u converted %u defaulted %u dropped %u added %u\n", g,
               b[g].status, b[g].kept, b[g].converted, b[g].defaulted, b[g].dropped, b[g].added);
    }
    printf("seen %u %u %u %u\n", cur->state->boot_seen, cur->state->boot_counts[0],
           cur->state->boot_counts[1], cur->state->boot_counts[2]);
    values(cur);
    printf("end\n");
}

static odg_abort_t write_hex(uint16_t index, uint8_t sub, const char *hex)
{
    uint8_t bytes[512];
    size_t i, n = strlen(hex) / 2;
    odg_ref_t ref;
    odg_abort_t ac;
    for (i = 0; i < n && i < sizeof bytes; i++) {
        unsigned b;
        if (sscanf(hex + 2 * i, "%2x", &b) != 1) {
            return ODG_ABORT_GENERAL;
        }
        bytes[i] = (uint8_t)b;
    }
    ac = odg_find(cur, index, sub, &ref);
    return ac == ODG_OK ? odg_write(&ref, bytes, (uint32_t)n) : ac;
}

int main(void)
{
    static char line[2300];
    char hex[2100];
    unsigned a, b;
    nv_fault_init(&nv, mem, NV_MAX, 7u);
    cur = VERSIONS[0];
    while (fgets(line, sizeof line, stdin) != NULL) {
        hex[0] = '\0';
        if (sscanf(line, "nv %u", &a) == 1 && a <= NV_MAX) {
            nv_fault_init(&nv, mem, NV_MAX, a | 1u); /* all of it blank: a window may grow */
            nv.size = a;
            printf("ok\n");
        } else if (sscanf(line, "window %u", &a) == 1 && a <= NV_MAX) {
            nv.size = a;
            printf("ok\n");
        } else if (sscanf(line, "boot %u", &a) == 1 && a < N_VERSIONS) {
            boot(a);
        } else if (sscanf(line, "set %x %x %2099s", &a, &b, hex) >= 2) {
            printf("set %08lX\n", (unsigned long)write_hex((uint16_t)a, (uint8_t)b, hex));
        } else if (strncmp(line, "save", 4) == 0 || strncmp(line, "load", 4) == 0) {
            int save = line[0] == 's';
            printf("%s %08lX\n", save ? "save" : "load",
                   (unsigned long)write_hex(save ? 0x1010u : 0x1011u, 1u, save ? "73617665" : "6C6F6164"));
        } else if (sscanf(line, "cut %u", &a) == 1) {
            nv.torn = 1;
            nv_fault_cut_after(&nv, (long)a);
            printf("ok\n");
        } else if (sscanf(line, "failwrite %u", &a) == 1) {
            nv.fail_write = (long)a;
            printf("ok\n");
        } else if (strncmp(line, "power", 5) == 0) {
            nv_fault_power_on(&nv);
            printf("ok\n");
        } else if (strncmp(line, "sizes", 5) == 0) {
            printf("sizes");
            for (a = 0; a < N_VERSIONS; a++) {
                printf(" %lu", (unsigned long)NV_SIZES[a]);
            }
            printf("\n");
        } else {
            printf("bad command: %s", line);
            return 2;
        }
    }
    return 0;
}
