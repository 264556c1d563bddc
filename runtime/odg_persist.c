/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_persist.c - the persistence layer: persistence groups in NV memory, safe against power
 * loss (docs/persistence.md). It boots every group from NV, answers the "save" / "load"
 * commands written to 0x1010 / 0x1011 (a client of the dictionary, odg_client_t), and hands
 * each group to its image format: self-describing images migrated at boot
 * (odg_persist_migrate.c) for a group generated with migration, else fixed-layout images
 * (odg_persist_fixed.c); both on the slots of odg_persist_slot.c.
 */
#include <string.h>

#include "odg_persist_migrate.h"

/* Store group `g` (restore = 0) in the format of its group, "ODG2" with a layout, else "ODG1";
 * or make its next boot use the defaults (restore = 1). `nv` is a driver and `g` a group: the
 * callers check (the command once for all its groups). */
static odg_abort_t act(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g, int restore)
{
#if ODG_CFG_PERSIST_MIGRATION
    if (ODG_MIGRATES_(&d->groups[g])) {
        return restore ? odg_described_erase_(d, nv, g) : odg_described_store_(d, nv, g);
    }
#endif
    return restore ? odg_fixed_erase_(d, nv, g) : odg_fixed_store_(d, nv, g);
}

/* Whether the NV behind `nv` holds the dictionary's NAME_NV_SIZE bytes (its last byte reads). */
static int nv_fits(const odg_dict_t *d, const odg_nv_driver_t *nv)
{
    uint32_t size = odg_persist_nv_size(d);
    uint8_t c;
    return nv != NULL && (size == 0u || nv->read(nv->ctx, size - 1u, &c, 1) == 0);
}

/* 0x1010 / 0x1011 sub `sub`, handed over by the core: sub 1 acts on every group, another on
 * the groups with that store_sub, each of them even past one that fails (the first failure is
 * the answer); DATA_STORE when none has it, or the NV is smaller than the dictionary's. */
static odg_abort_t command(odg_client_t *self, const odg_dict_t *d, uint8_t sub, int restore)
{
    const odg_nv_driver_t *nv = ((const odg_persist_t *)(const void *)self)->nv;
    odg_abort_t ac = ODG_OK, r;
    uint8_t g, any = 0;
    if (!nv_fits(d, nv)) {
        return ODG_ABORT_DATA_STORE;
    }
    for (g = 0; g < d->n_groups; g++) {
        if (sub == 1u || d->groups[g].store_sub == sub) {
            r = act(d, nv, g, restore); /* every group, even past one that failed */
            ac = ac == ODG_OK ? r : ac;
            any = 1;
        }
    }
    return any ? ac : ODG_ABORT_DATA_STORE;
}

/* The driver of the persistence layer attached to `d` (the client with its `command`; the
 * client is the first member of odg_persist_t), or NULL. */
static const odg_nv_driver_t *driver(const odg_dict_t *d)
{
    const odg_client_t *c = d->state->clients;
    while (c != NULL && c->command != command) {
        c = c->next;
    }
    return c != NULL ? ((const odg_persist_t *)(const void *)c)->nv : NULL;
}

/* act on group `g` with the attached driver: DATA_STORE when none is attached, or no group `g` */
static odg_abort_t act_attached(const odg_dict_t *d, uint8_t g, int restore)
{
    const odg_nv_driver_t *nv = driver(d);
    return nv == NULL || g >= d->n_groups ? ODG_ABORT_DATA_STORE : act(d, nv, g, restore);
}

odg_abort_t odg_persist_store(const odg_dict_t *dict, uint8_t g)
{
    return act_attached(dict, g, 0);
}

odg_abort_t odg_persist_restore(const odg_dict_t *dict, uint8_t g)
{
    return act_attached(dict, g, 1);
}

static odg_boot_status_t boot_group(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g,
                                     odg_boot_t *b)
{
#if ODG_CFG_PERSIST_MIGRATION
    if (ODG_MIGRATES_(&d->groups[g])) {
        return odg_described_boot_(d, nv, g, b);
    }
#endif
    return odg_fixed_boot_(d, nv, g, b);
}

/* The boot status object: sub g + 1 = status | converted << 8 | defaulted << 16 | dropped << 24 */
static void report(const odg_dict_t *d, uint8_t g, const odg_boot_t *b)
{
    uint32_t v;
    if (ODG_CFG_PERSIST_STATUS && d->persist_status != 0u) { /* the counts only then: calls stay */
        v = (uint32_t)b->status | (uint32_t)odg_add_sat_(0, b->converted) << 8 |
            (uint32_t)odg_add_sat_(0, b->defaulted) << 16 | (uint32_t)odg_add_sat_(0, b->dropped) << 24;
        (void)odg_set(d, d->persist_status, (uint8_t)(g + 1u), &v, (uint32_t)sizeof v);
    }
}

/* What the boot of group `g` found, into the dictionary's state, the status object, `st`
 * (when not NULL) and *ac (HARDWARE on NV_ERROR). */
static void booted(const odg_dict_t *d, uint8_t g, const odg_boot_t *b, odg_boot_status_t *st,
                   odg_abort_t *ac)
{
    odg_state_t *s = d->state;
    s->boot_seen = (uint8_t)(s->boot_seen | 1u << b->status);
    if (b->status == ODG_BOOT_NV_ERROR && *ac == ODG_OK) {
        *ac = ODG_ABORT_HARDWARE;
    }
    report(d, g, b);
    if (st != NULL) {
        st[g] = (odg_boot_status_t)b->status;
    }
}

/* odg_persist_init and odg_persist_boot each get their own copy of the boot, without the
 * output they do not have: a program calls one of them, and its copy links smaller than one
 * shared by both (measured on Cortex-M4). */
#if defined(__GNUC__)
#define EACH_ITS_OWN __attribute__((always_inline)) inline
#else
#define EACH_ITS_OWN inline
#endif

/* Attach the layer and boot every group; the statuses into `st`, the counts into `boot`
 * (either may be NULL). */
static EACH_ITS_OWN odg_abort_t boot_all(odg_persist_t *p, const odg_dict_t *dict, const odg_nv_driver_t *nv,
                            odg_boot_status_t *st, odg_boot_t *boot)
{
    odg_abort_t ac = nv != NULL ? ODG_OK : ODG_ABORT_DATA_STORE;
    odg_state_t *s = dict->state;
    unsigned g; /* a group's number (below 256): no narrowing at every turn */
    int fits, pass;
#if ODG_CFG_PERSIST_TWO_PASS
    uint8_t done[32]; /* the groups booted in the first pass */
#endif
    if (nv != NULL) {
        p->client.command = command;
        p->client.changed = NULL;
        p->nv = nv;
        odg_attach(dict, &p->client);
    }
    s->boot_seen = 0;
#if ODG_CFG_PERSIST_MIGRATION /* the counts of entries a migration converted, defaulted, dropped */
    s->boot_counts[0] = s->boot_counts[1] = s->boot_counts[2] = 0;
#endif
    fits = nv_fits(dict, nv);
#if ODG_CFG_PERSIST_TWO_PASS
    /* two passes: first the groups whose newest image lies outside their region (in a region
     * of another group, after the NV map changed), which move it home before that group's
     * boot writes over it; then the others. With one group (ODG_CFG_PERSIST_TWO_PASS 0) no
     * other boot writes over its image: one pass. */
    memset(done, 0, sizeof done);
    for (pass = fits ? 0 : 1; pass < 2; pass++) {
#else
    for (pass = 1; pass < 2; pass++) {
#endif
        for (g = 0; g < dict->n_groups; g++) {
            odg_boot_t own, *b = boot != NULL ? &boot[g] : &own; /* the counts straight into `boot` */
#if ODG_CFG_PERSIST_TWO_PASS
            if ((done[g >> 3] >> (g & 7u)) & 1u || (pass == 0 && !odg_described_displaced_(dict, nv, (uint8_t)g))) {
                continue;
            }
            done[g >> 3] = (uint8_t)(done[g >> 3] | 1u << (g & 7u));
#endif
            b->status = ODG_BOOT_NV_ERROR;
            b->kept = b->converted = b->defaulted = b->dropped = b->added = 0;
            if (fits) { /* an NV smaller than the dictionary's: NV_ERROR, nothing written */
                b->status = (uint8_t)boot_group(dict, nv, (uint8_t)g, b);
            }
            booted(dict, (uint8_t)g, b, st, &ac);
        }
    }
    odg_changed(dict, NULL);
    return ac;
}

odg_abort_t odg_persist_boot(odg_persist_t *p, const odg_dict_t *dict, const odg_nv_driver_t *nv,
                             odg_boot_t *boot)
{
    return boot_all(p, dict, nv, NULL, boot);
}

odg_abort_t odg_persist_init(odg_persist_t *p, const odg_dict_t *dict, const odg_nv_driver_t *nv,
                             odg_boot_status_t *boot)
{
    return boot_all(p, dict, nv, boot, NULL);
}
