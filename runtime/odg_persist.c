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
        return odg_described_store_(d, nv, g, restore);
    }
#endif
    return restore ? odg_fixed_erase_(d, nv, g) : odg_fixed_store_(d, nv, g);
}

/* `nv` when the NV behind it holds the dictionary's NAME_NV_SIZE bytes (its last byte reads),
 * else NULL: the callers then touch no NV. */
static const odg_nv_driver_t *fitting(const odg_dict_t *d, const odg_nv_driver_t *nv)
{
    uint32_t size = ODG_NV_END_(d);
    uint8_t c;
    return nv != NULL && (size == 0u || nv->read(nv->ctx, size - 1u, &c, 1) == 0) ? nv : NULL;
}

#define NOT_ACTED 1u /* no group acted yet (no abort code is 1) */

/* 0x1010 / 0x1011 sub `sub`, handed over by the core: sub 1 acts on every group, another on
 * the groups with that store_sub, each of them even past one that fails (the first failure is
 * the answer); DATA_STORE when none has it, or the NV is smaller than the dictionary's (`nv`
 * NULL: no group acts). `ac` stays NOT_ACTED until a group acted, then holds the first failure. */
static odg_abort_t command(odg_client_t *self, const odg_dict_t *d, uint8_t sub, int restore)
{
    const odg_nv_driver_t *nv = fitting(d, ((const odg_persist_t *)(const void *)self)->nv);
    odg_abort_t ac = NOT_ACTED, r;
    unsigned g; /* below 256: no narrowing at every turn */
    for (g = 0; nv != NULL && g < d->n_groups; g++) {
        if (sub == 1u || d->groups[g].store_sub == sub) {
            r = act(d, nv, (uint8_t)g, restore); /* every group, even past one that failed */
            ac = ac == ODG_OK || ac == NOT_ACTED ? r : ac;
        }
    }
    return ac == NOT_ACTED ? ODG_ABORT_DATA_STORE : ac;
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

/* Boot group `g` (`nv` NULL, no driver or an NV smaller than the dictionary's: NV_ERROR,
 * nothing read or written) and record what it found: in the dictionary's state (boot_all
 * answers HARDWARE from its NV_ERROR bit), the status object, `st` and `boot` (when not NULL). */
static void boot_one(const odg_dict_t *d, const odg_nv_driver_t *nv, unsigned g,
                     odg_boot_status_t *st, odg_boot_t *boot)
{
    odg_boot_t own, *b = boot != NULL ? &boot[g] : &own; /* the counts straight into `boot` */
    odg_boot_status_t r = ODG_BOOT_NV_ERROR;
    memset(b, 0, sizeof *b); /* the counts of a boot that migrated nothing */
    if (nv != NULL) {
        r = boot_group(d, nv, (uint8_t)g, b);
    }
    b->status = (uint8_t)r;
    d->state->boot_seen = (uint8_t)(d->state->boot_seen | 1u << r);
    report(d, (uint8_t)g, b);
    if (st != NULL) {
        st[g] = r;
    }
}

#if ODG_CFG_PERSIST_TWO_PASS
/* Boot the groups in the order of their regions in NV, the lowest first. A group's boot writes
 * only inside its own region, and a group finds its images only at places from its region's
 * start on; so an image of group h that lies in the region of group g (the NV map changed) starts
 * before that region ends, and h's region, which does not overlap g's, lies before g's. Booting
 * by address, h has moved its image home before g's boot (its store and the clearing of its
 * region) writes over it, however the images were displaced (a chain: A's newest in B's region,
 * B's in C's), and no image of g lies in the region of a group that booted before g. Regions
 * do not overlap (odg_verify), so their starts differ. */
static void boot_ordered(const odg_dict_t *d, const odg_nv_driver_t *nv,
                         odg_boot_status_t *st, odg_boot_t *boot)
{
    uint32_t from = 0, low, at; /* from: past the region start of the group booted last */
    unsigned n, g, next = 0;
    for (n = 0; n < d->n_groups; n++) {
        low = 0xFFFFFFFFu;
        for (g = 0; g < d->n_groups; g++) { /* the lowest region start from `from` on */
            at = d->groups[g].nv_addr;
            if (at >= from && at <= low) {
                low = at;
                next = g;
            }
        }
        from = low + 1u; /* wraps to 0 only after a region at the last address, booted last */
        boot_one(d, nv, next, st, boot);
    }
}
#endif

/* Attach the layer and boot every group; the statuses into `st`, the counts into `boot`
 * (either may be NULL). */
static odg_abort_t boot_all(odg_persist_t *p, const odg_dict_t *dict, const odg_nv_driver_t *nv,
                            odg_boot_status_t *st, odg_boot_t *boot)
{
    odg_state_t *s = dict->state;
    const odg_nv_driver_t *fit; /* nv, or NULL on an NV smaller than the dictionary's */
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
    fit = fitting(dict, nv);
#if ODG_CFG_PERSIST_TWO_PASS
    boot_ordered(dict, fit, st, boot);
#else
    { /* one group: no other group's boot can write over its image */
        unsigned g; /* below 256: no narrowing at every turn */
        for (g = 0; g < dict->n_groups; g++) {
            boot_one(dict, fit, g, st, boot);
        }
    }
#endif
    odg_changed(dict, NULL);
    /* boot_seen has bit NV_ERROR once a group booted NV_ERROR (a migration adds only ENTRIES_LOST) */
    return nv == NULL ? ODG_ABORT_DATA_STORE
                      : (s->boot_seen & 1u << ODG_BOOT_NV_ERROR) != 0u ? ODG_ABORT_HARDWARE : ODG_OK;
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
