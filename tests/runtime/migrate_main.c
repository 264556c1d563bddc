/*
 * migrate_main.c - a host program over a generated dictionary named `od`, to test boot
 * migration across firmware versions on one NV file (tests/test_migration_runtime.py):
 *
 *   migrate_main NVFILE OP...      every run boots `od` from NVFILE first, then:
 *     set:IIII:SS:HEX              odg_write of the wire bytes HEX to index IIII sub SS (hex)
 *     store                        store every group (as 0x1010 sub 1 "save")
 *     restore                      restore every group's defaults (as 0x1011 sub 1 "load")
 *     dump                         the boot of each group and every persisted value (wire hex)
 *     cuts                         the power cut after every byte of the boot's migration store,
 *                                  on a NOR model of NVFILE: each next boot must serve the same
 *                                  values as an uncut migration, as LOADED or MIGRATED
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "nv_fault.h"
#include "od.h"
#include "odg_nv_file.h"

#define NV_BYTES 8192u
#define OUT 65536

static odg_persist_t persist;
static odg_boot_t boot[16];

/* Every persisted value of `od` as "IIII SS HEX" lines, after the boot lines, into `out`. */
static void dump(char *out, size_t cap)
{
    uint16_t e, p;
    size_t n = 0;
    uint8_t g;
    for (g = 0; g < od.n_groups; g++) {
        n += (size_t)snprintf(out + n, cap - n, "group %u status %u kept %u converted %u defaulted %u dropped %u\n",
                              g, boot[g].status, boot[g].kept, boot[g].converted, boot[g].defaulted,
                              boot[g].dropped);
    }
    n += (size_t)snprintf(out + n, cap - n, "seen %u counts %u %u %u\n", od.state->boot_seen,
                          od.state->boot_counts[0], od.state->boot_counts[1], od.state->boot_counts[2]);
    for (e = 0; e < od.n_entries; e++) {
        const odg_entry_t *en = &od.entries[e];
        for (p = en->first; p < en->first + en->count; p++) {
            const odg_sub_t *s = &od.subs[p];
            /* the elements 1..N of a packed ARRAY share one descriptor */
            unsigned k = (en->code & ODG_E_PACKED) && p > en->first ? 1u : s->sub;
            int persisted = ODG_S_CLASS(s->storage) == ODG_S_PERSIST;
            if (!persisted && en->index != od.persist_status) {
                continue;
            }
            for (; k <= s->sub; k++) {
                odg_ref_t ref;
                uint8_t buf[1024];
                uint32_t len = 0, i;
                if (odg_find(&od, en->index, (uint8_t)k, &ref) != ODG_OK ||
                    odg_read(&ref, 0, buf, sizeof buf, &len) != ODG_OK) {
                    len = 0;
                }
                n += (size_t)snprintf(out + n, cap - n, "%s %04X %02X ", persisted ? "value" : "status",
                                      en->index, k);
                for (i = 0; i < len; i++) {
                    n += (size_t)snprintf(out + n, cap - n, "%02X", buf[i]);
                }
                n += (size_t)snprintf(out + n, cap - n, "\n");
            }
        }
    }
}

static odg_abort_t boot_on(const odg_nv_driver_t *nv)
{
    memset(boot, 0, sizeof boot);
    odg_init(&od, 5);
    return odg_persist_boot(&persist, &od, nv, boot);
}

static int set(const char *arg)
{
    unsigned index, sub;
    char hex[2100];
    uint8_t bytes[1024];
    size_t i, n;
    odg_ref_t ref;
    odg_abort_t ac;
    hex[0] = '\0';
    if (sscanf(arg, "set:%x:%x:%2099s", &index, &sub, hex) < 2) {
        return 1;
    }
    n = strlen(hex) / 2;
    for (i = 0; i < n; i++) {
        unsigned b;
        if (sscanf(hex + 2 * i, "%2x", &b) != 1) {
            return 1;
        }
        bytes[i] = (uint8_t)b;
    }
    ac = odg_find(&od, (uint16_t)index, (uint8_t)sub, &ref);
    if (ac == ODG_OK) {
        ac = odg_write(&ref, bytes, (uint32_t)n);
    }
    if (ac != ODG_OK) {
        printf("set %04X sub %u: %s\n", index, sub, odg_abort_text(ac));
        return 1;
    }
    return 0;
}

/* The power cut after every byte the boot writes (the migration store), each followed by a
 * boot without faults: the values must be those of the uncut migration. */
static int cuts(const char *path)
{
    static uint8_t orig[NV_BYTES], mem[NV_BYTES];
    static char want[OUT], got[OUT];
    nv_fault_t f;
    long k, total;
    int bad = 0;
    FILE *fp = fopen(path, "rb");
    if (fp == NULL || fread(orig, 1, NV_BYTES, fp) != NV_BYTES) {
        return 1;
    }
    fclose(fp);
    nv_fault_init(&f, mem, NV_BYTES, 7u); /* erases `mem` */
    memcpy(mem, orig, NV_BYTES);
    boot_on(&f.driver);
    total = f.bytes;
    dump(want, OUT);
    for (k = 0; k < total; k++) {
        nv_fault_init(&f, mem, NV_BYTES, (uint32_t)k + 1u);
        memcpy(mem, orig, NV_BYTES);
        f.torn = (int)(k & 1);
        nv_fault_cut_after(&f, k);
        boot_on(&f.driver);
        nv_fault_power_on(&f);
        boot_on(&f.driver);
        dump(got, OUT);
        /* the values after the boot lines must match; each status LOADED or MIGRATED */
        if (strcmp(strstr(got, "value"), strstr(want, "value")) != 0) {
            printf("cut after %ld bytes: other values\n%s", k, got);
            bad++;
        }
        {
            uint8_t g;
            for (g = 0; g < od.n_groups; g++) {
                if (boot[g].status != ODG_BOOT_LOADED && boot[g].status != ODG_BOOT_MIGRATED) {
                    printf("cut after %ld bytes: group %u status %u\n", k, g, boot[g].status);
                    bad++;
                }
            }
        }
    }
    printf("cuts %ld bad %d\n", total, bad);
    return bad != 0;
}

int main(int argc, char **argv)
{
    static char out[OUT];
    odg_nv_file_t nvf;
    int i;
    if (argc < 2) {
        return 2;
    }
    if (argc == 3 && strcmp(argv[2], "cuts") == 0) {
        return cuts(argv[1]);
    }
    if (odg_nv_file_open(&nvf, argv[1], NV_BYTES) != 0) {
        return 2;
    }
    nvf.sync = 0;
    boot_on(&nvf.driver);
    for (i = 2; i < argc; i++) {
        if (strncmp(argv[i], "set:", 4) == 0) {
            if (set(argv[i]) != 0) {
                return 1;
            }
        } else if (strcmp(argv[i], "store") == 0) {
            uint8_t g;
            for (g = 0; g < od.n_groups; g++) {
                if (odg_persist_store(&od, g) != ODG_OK) {
                    printf("store %u failed\n", g);
                    return 1;
                }
            }
        } else if (strcmp(argv[i], "restore") == 0) {
            uint8_t g;
            for (g = 0; g < od.n_groups; g++) {
                if (odg_persist_restore(&od, g) != ODG_OK) {
                    printf("restore %u failed\n", g);
                    return 1;
                }
            }
        } else if (strcmp(argv[i], "dump") == 0) {
            dump(out, OUT);
            fputs(out, stdout);
        } else {
            return 2;
        }
    }
    return odg_nv_file_close(&nvf) != 0;
}
