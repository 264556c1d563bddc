/*
 * test_faults.c - persistence under faults, against the dictionary td, with the NOR-flash
 * driver of nv_fault.c. test_persist.c proves the slot format case by case; this test counts
 * outcomes over many faults and checks, after every boot, that each group's mirror equals
 * exactly one whole image that may legitimately be there (the defaults, the newest image
 * stored, the one before it, or an image whose store was cut short) and never a mix:
 *   - a power cut after every byte of a store (clean and torn bytes), both groups, both slots;
 *   - each write call of a store failing;
 *   - a bit flipped in both slots of a group: defaults, status ODG_BOOT_DAMAGED;
 *   - 10 000 random cycles (fixed seed) of store, power cut / failed write / bit flip, boot.
 * `test_faults DIR --json FILE` also writes the figures as a JSON table.
 * Prints "N passed, M failed"; exit status 0 only when M is 0.
 */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "nv_fault.h"
#include "odg.h"
#include "td.h"

#define NODE 5u
#define NV_SIZE 512u
#define HDR ODG_PERSIST_HEADER_SIZE
#define CYCLES 10000u
#define MAXIMG 64u

static uint8_t mem[NV_SIZE];
static nv_fault_t nv;
static odg_boot_status_t bs[2];

/* Images that a group may load, per group: defaults, newest stored (N), the one before (N-1),
 * and one whose store failed (it may or may not have committed). */
enum { DEF, CUR, PREV, ATT, N_IMG };
static uint8_t img[2][N_IMG][MAXIMG];
static int has_att[2];

/* Outcomes per fault class: the image being stored, the newest stored before it, an older
 * one, the defaults, a mix (never). */
typedef struct {
    const char *name;
    unsigned long trials, att_img, new_img, old_img, defaults, mixed;
} figures_t;

static figures_t fig_cut = {"power cut after every byte of a store (clean and torn byte; both groups, both slots)",
                            0, 0, 0, 0, 0, 0};
static figures_t fig_write = {"a write call of a store fails (image, header, commit mark)", 0, 0, 0, 0, 0, 0};
static figures_t fig_flip = {"one bit flipped in each slot of a group", 0, 0, 0, 0, 0, 0};
static figures_t fig_stress = {"random cycles of store, power cut / failed write / bit flip, boot (per group)", 0,
                               0, 0, 0, 0, 0};
static unsigned long stress_cuts, stress_writes, stress_flips, stress_clean;

/* The hook td's slot table names; not exercised here. */
odg_abort_t td_notice(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len, void *ctx)
{
    (void)ref, (void)kind, (void)data, (void)len, (void)ctx;
    return ODG_OK;
}

static uint8_t *mirror(uint8_t g)
{
    return (uint8_t *)td.groups[g].mirror;
}

static uint32_t msize(uint8_t g)
{
    return td.groups[g].size;
}

static uint32_t store_bytes(uint8_t g)
{
    return ODG_PERSIST_SLOT_SIZE(msize(g)) + msize(g) + HDR; /* erase, image, header */
}

static odg_persist_t persist;

static odg_abort_t boot(void)
{
    odg_abort_t ac;
    nv_fault_power_on(&nv);
    memset(mirror(0), 0xA5, msize(0));
    memset(mirror(1), 0xA5, msize(1));
    bs[0] = bs[1] = (odg_boot_status_t)99;
    ac = odg_init(&td, NODE);
    return ac != ODG_OK ? ac : odg_persist_init(&persist, &td, &nv.driver, bs);
}

/* Which of the group's candidate images the mirror equals, as bits (1 << DEF ...); 0: a mix. */
static unsigned matches(uint8_t g)
{
    unsigned m = 0, k;
    for (k = 0; k < N_IMG; k++) {
        if ((k != ATT || has_att[g]) && memcmp(mirror(g), img[g][k], msize(g)) == 0) {
            m |= 1u << k;
        }
    }
    return m;
}

/* Random bytes into the mirror of group g; values with limits keep their defaults, since a
 * stored value always passed them (odg_write checks them, and boot checks them again: a value
 * outside takes its default, docs/persistence.md). */
static void fill_random(uint8_t g)
{
    uint32_t i;
    uint16_t p;
    for (i = 0; i < msize(g); i++) {
        mirror(g)[i] = (uint8_t)nv_fault_rand(&nv);
    }
    for (p = 0; p < td.n_subs; p++) {
        const odg_sub_t *s = &td.subs[p];
        if (s->storage == (uint8_t)(ODG_S_PERSIST | (unsigned)g << 2) && (s->attr & ODG_A_LIMIT)) {
            odg_group_defaults(&td.groups[g], s->offset, s->size, mirror(g) + s->offset);
        }
    }
}

/* After a boot: check group g against its candidates, count the outcome, and make what was
 * loaded the newest image. `flipped`: a bit of this group's slots was flipped since the last
 * boot, so the newest image may be gone. */
static void judge(uint8_t g, int flipped, figures_t *fig, long at)
{
    unsigned m = matches(g);
    static figures_t none;
    fig = fig != NULL ? fig : &none;
    CHECK_EQ_AT(m != 0u, 1, at);
    if (m == 0u) {
        fig->mixed++;
    } else if (bs[g] == ODG_BOOT_LOADED) {
        CHECK_EQ_AT(m & (1u << CUR | 1u << PREV | 1u << ATT) ? 1 : 0, 1, at);
        if (m & 1u << ATT) {
            fig->att_img++;
        } else if (m & 1u << CUR) {
            fig->new_img++;
        } else {
            CHECK_EQ_AT(flipped, 1, at); /* only damage to the newest brings the older back */
            fig->old_img++;
        }
    } else {
        /* values were in NV but none came back: the status says so, the mirror has defaults */
        CHECK_EQ_AT(bs[g], ODG_BOOT_DAMAGED, at);
        CHECK_EQ_AT(m & (1u << DEF) ? 1 : 0, 1, at);
        CHECK_EQ_AT(flipped, 1, at);
        CHECK_EQ_AT(td.state->boot_seen & ODG_BOOT_LOST_MASK ? 1 : 0, 1, at);
        fig->defaults++;
    }
    if (!(m & 1u << CUR)) {
        memcpy(img[g][PREV], img[g][CUR], msize(g));
        memcpy(img[g][CUR], mirror(g), msize(g));
    }
    has_att[g] = 0;
}

/* Blank NV, boot (defaults stored), then two stored images: N-1 and N. */
static void two_images(void)
{
    uint8_t g;
    nv_fault_init(&nv, mem, NV_SIZE, nv.rng ? nv.rng : 1u);
    CHECK_EQ(boot(), ODG_OK);
    for (g = 0; g < 2u; g++) {
        CHECK_EQ(bs[g], ODG_BOOT_DEFAULTS);
        memcpy(img[g][DEF], mirror(g), msize(g));
        fill_random(g);
        memcpy(img[g][PREV], mirror(g), msize(g));
        CHECK_EQ(odg_persist_store(&td, g), ODG_OK);
        fill_random(g);
        memcpy(img[g][CUR], mirror(g), msize(g));
        CHECK_EQ(odg_persist_store(&td, g), ODG_OK);
        has_att[g] = 0;
    }
}

static void sweep_cuts(void)
{
    uint8_t snap[NV_SIZE], g;
    int torn, extra;
    for (g = 0; g < 2u; g++) {
        for (extra = 0; extra < 2; extra++) { /* the new image goes to one slot, then the other */
            for (torn = 0; torn < 2; torn++) {
                uint32_t k, total = store_bytes(g);
                two_images();
                if (extra) {
                    memcpy(img[g][PREV], img[g][CUR], msize(g));
                    fill_random(g);
                    memcpy(img[g][CUR], mirror(g), msize(g));
                    CHECK_EQ(odg_persist_store(&td, g), ODG_OK);
                }
                fill_random(g);
                memcpy(img[g][ATT], mirror(g), msize(g));
                memcpy(snap, mem, NV_SIZE);
                for (k = 0; k <= total; k++) {
                    odg_abort_t ac;
                    uint8_t keep_cur[MAXIMG], keep_prev[MAXIMG];
                    memcpy(keep_cur, img[g][CUR], MAXIMG);
                    memcpy(keep_prev, img[g][PREV], MAXIMG);
                    memcpy(mem, snap, NV_SIZE);
                    memcpy(mirror(g), img[g][ATT], msize(g));
                    nv_fault_power_on(&nv);
                    nv_fault_cut_after(&nv, (long)k);
                    nv.torn = torn;
                    ac = odg_persist_store(&td, g);
                    CHECK_EQ_AT(ac, k == total ? ODG_OK : ODG_ABORT_HARDWARE, k);
                    has_att[g] = 1;
                    CHECK_EQ_AT(boot(), ODG_OK, k);
                    fig_cut.trials++;
                    judge(g, 0, &fig_cut, (long)k);
                    judge((uint8_t)!g, 0, NULL, (long)k); /* the other group: untouched */
                    memcpy(img[g][CUR], keep_cur, MAXIMG);
                    memcpy(img[g][PREV], keep_prev, MAXIMG);
                }
            }
        }
    }
}

static void sweep_write_failures(void)
{
    uint8_t snap[NV_SIZE], g;
    long n;
    for (g = 0; g < 2u; g++) {
        two_images();
        fill_random(g);
        memcpy(img[g][ATT], mirror(g), msize(g));
        memcpy(snap, mem, NV_SIZE);
        for (n = 1; n <= 3; n++) { /* image, header, magic */
            memcpy(mem, snap, NV_SIZE);
            memcpy(mirror(g), img[g][ATT], msize(g));
            nv_fault_power_on(&nv);
            nv.fail_write = n;
            CHECK_EQ_AT(odg_persist_store(&td, g), ODG_ABORT_HARDWARE, n);
            has_att[g] = 1;
            CHECK_EQ_AT(boot(), ODG_OK, n);
            fig_write.trials++;
            CHECK_EQ_AT(matches(g) & 1u << CUR ? 1 : 0, 1, n); /* the store did not commit */
            judge(g, 0, &fig_write, n);
            /* the same store, retried, works */
            memcpy(mirror(g), img[g][ATT], msize(g));
            CHECK_EQ_AT(odg_persist_store(&td, g), ODG_OK, n);
            CHECK_EQ_AT(boot(), ODG_OK, n);
            CHECK_EQ_AT(memcmp(mirror(g), img[g][ATT], msize(g)), 0, n);
        }
    }
}

static uint32_t slot_byte(uint8_t g, int k, uint32_t off)
{
    return td.groups[g].nv_addr + (k ? ODG_PERSIST_SLOT_SIZE(msize(g)) : 0u) + off;
}

static void flips_in_both_slots(void)
{
    uint8_t snap[NV_SIZE], g;
    long i;
    for (g = 0; g < 2u; g++) {
        two_images();
        memcpy(snap, mem, NV_SIZE);
        for (i = 0; i < 500; i++) {
            memcpy(mem, snap, NV_SIZE);
            nv_fault_flip(&nv, slot_byte(g, 0, nv_fault_rand(&nv) % (HDR + msize(g))), nv_fault_rand(&nv));
            nv_fault_flip(&nv, slot_byte(g, 1, nv_fault_rand(&nv) % (HDR + msize(g))), nv_fault_rand(&nv));
            CHECK_EQ_AT(boot(), ODG_OK, i);
            fig_flip.trials++;
            CHECK_EQ_AT(bs[g], ODG_BOOT_DAMAGED, i);
            judge(g, 1, &fig_flip, i);
            /* the defaults were stored: the next boot loads them, nothing lost any more */
            CHECK_EQ_AT(boot(), ODG_OK, i);
            CHECK_EQ_AT(bs[g], ODG_BOOT_LOADED, i);
            CHECK_EQ_AT(td.state->boot_seen, 1u << ODG_BOOT_LOADED, i);
            CHECK_EQ_AT(memcmp(mirror(g), img[g][DEF], msize(g)), 0, i);
            /* the model of the two images again: N in slot 0, N-1 in slot 1 */
            memcpy(img[g][CUR], snap + slot_byte(g, 0, HDR), msize(g));
            memcpy(img[g][PREV], snap + slot_byte(g, 1, HDR), msize(g));
        }
    }
}

static void stress(void)
{
    unsigned long c;
    two_images();
    for (c = 0; c < CYCLES; c++) {
        uint8_t g = (uint8_t)(nv_fault_rand(&nv) & 1u), h;
        int flipped[2] = {0, 0};
        uint32_t fault = nv_fault_rand(&nv) % 8u;
        fill_random(g);
        memcpy(img[g][ATT], mirror(g), msize(g));
        nv_fault_power_on(&nv);
        if (fault < 4u) {
            nv_fault_cut_after(&nv, (long)(nv_fault_rand(&nv) % (store_bytes(g) + 1u)));
            nv.torn = (int)(nv_fault_rand(&nv) & 1u);
            stress_cuts++;
        } else if (fault == 4u) {
            nv.fail_write = 1 + (long)(nv_fault_rand(&nv) % 3u);
            stress_writes++;
        } else {
            stress_clean++;
        }
        if (odg_persist_store(&td, g) == ODG_OK) {
            memcpy(img[g][PREV], img[g][CUR], msize(g));
            memcpy(img[g][CUR], img[g][ATT], msize(g));
        }
        has_att[g] = 1; /* counted as "the image being stored" when it loads */
        if (nv_fault_rand(&nv) % 4u == 0u) { /* a bit flips at rest, in either slot of either group */
            uint8_t fg = (uint8_t)(nv_fault_rand(&nv) & 1u);
            int k = (int)(nv_fault_rand(&nv) & 1u);
            nv_fault_flip(&nv, slot_byte(fg, k, nv_fault_rand(&nv) % (HDR + msize(fg))), nv_fault_rand(&nv));
            flipped[fg] = 1;
            stress_flips++;
        }
        CHECK_EQ_AT(boot(), ODG_OK, (long)c);
        fig_stress.trials += 2u;
        for (h = 0; h < 2u; h++) {
            judge(h, flipped[h], &fig_stress, (long)c);
        }
    }
}

static void row(FILE *f, const figures_t *x, int last)
{
    fprintf(f, "    [\"%s\", %lu, %lu, %lu, %lu, %lu, %lu]%s\n", x->name, x->trials, x->att_img, x->new_img,
            x->old_img, x->defaults, x->mixed, last ? "" : ",");
}

static int write_json(const char *path)
{
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        printf("cannot write %s\n", path);
        return 1;
    }
    fprintf(f, "{\n  \"title\": \"Persistence under faults (tests/runtime/test_faults.c)\",\n");
    fprintf(f, "  \"columns\": [\"fault\", \"group boots checked\", \"image being stored\", \"newest before it\", "
               "\"older image\", \"defaults (ODG_BOOT_DAMAGED)\", \"mixed images\"],\n  \"rows\": [\n");
    row(f, &fig_cut, 0);
    row(f, &fig_write, 0);
    row(f, &fig_flip, 0);
    row(f, &fig_stress, 1);
    fprintf(f, "  ],\n  \"notes\": [\n");
    fprintf(f, "    \"cut points: %lu bytes at which the power failed during a store\",\n", fig_cut.trials);
    fprintf(f, "    \"random cycles: %lu (seed 1): %lu power cuts, %lu failed writes, %lu clean stores; "
               "%lu bit flips at rest\",\n",
            fig_stress.trials, stress_cuts, stress_writes, stress_clean, stress_flips);
    fprintf(f, "    \"every boot: each group's values equal, byte for byte, exactly one whole image: "
               "the defaults, the newest stored, the one before, or the one whose store was cut\",\n");
    fprintf(f, "    \"image being stored: the store completed, or was cut after its commit mark; otherwise "
               "the newest image before it loads: a cut store never loses it\",\n");
    fprintf(f, "    \"older image: only after a bit flip damaged the newest; defaults: only when both "
               "slots were damaged, reported as ODG_BOOT_DAMAGED and, by the node, EMCY 0x5530\",\n");
    fprintf(f, "    \"random cycles count each of the 2 groups per boot (%lu boots)\"\n", (unsigned long)CYCLES);
    fprintf(f, "  ]\n}\n");
    return fclose(f) != 0;
}

int main(int argc, char **argv)
{
    int i, bad = 0;
    nv.rng = 1u;
    sweep_cuts();
    sweep_write_failures();
    flips_in_both_slots();
    stress();
    CHECK_EQ(fig_stress.trials, 2u * CYCLES);
    CHECK(fig_cut.att_img >= 4u && fig_cut.new_img > 0u && fig_stress.old_img > 0u && fig_stress.defaults > 0u);
    CHECK(fig_cut.mixed + fig_write.mixed + fig_flip.mixed + fig_stress.mixed == 0u);
    for (i = 1; i + 1 < argc; i++) {
        if (strcmp(argv[i], "--json") == 0) {
            bad |= write_json(argv[i + 1]);
        }
    }
    CHECK_EQ(bad, 0);
    return done();
}
