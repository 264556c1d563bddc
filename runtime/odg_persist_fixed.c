/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_persist_fixed.c - fixed-layout images: a group generated without migration keeps its RAM
 * mirror byte for byte ("ODG1"), checked by its layout signature; and the records of other
 * layers (the LSS configuration), a few bytes in slots of their own (at the end of the file).
 *
 * Two slots (A at nv_addr, B right after it). A slot is a header followed by
 * the image (the group's RAM mirror, byte for byte):
 *
 *   offset  size  field (all little-endian, encoded byte by byte)
 *        0     4  magic "ODG1" (0x4F 0x44 0x47 0x31): the commit mark, written last
 *        4     4  sequence number (serial arithmetic: wraps around)
 *        8     4  layout signature of the group (odg_group_t.signature)
 *       12     4  image length in bytes
 *       16     4  CRC-32 of bytes 0..15 and the image
 *       20     n  image
 *
 * A slot is valid when its magic is complete, its length fits the slot and the CRC matches.
 * A store goes to the slot that does NOT hold the newest valid image: erase it, write the
 * image, write header bytes 4..19, and only then the 4 magic bytes. Until the last magic byte
 * lands the slot is invalid (an erased or half-written magic differs from "ODG1", whose
 * bytes are all different from the erased value 0xFF), and the other slot, untouched, still
 * holds the previous image. So a power cut at any byte leaves the old image or the new one,
 * never a mix; corrupted bits beyond that are caught by the CRC. Boot takes the valid slot
 * with the newest sequence number.
 *
 */
#include "odg_persist_impl.h"

#define FIXED_HDR ODG_PERSIST_HEADER_SIZE
/* INTEGER8/16/32 (0x02-0x04), INTEGER24/40/48/56/64 (0x10, 0x12-0x15), by CiA 301 code */
#define SIGNED ((uint32_t)0x1Cu | (uint32_t)0x3Du << 16)

uint32_t odg_persist_slot_size(uint32_t size)
{
    return ODG_PERSIST_SLOT_SIZE(size);
}

static uint32_t fixed_slot(const odg_group_t *g, int k)
{
    return g->nv_addr + (k ? ODG_PERSIST_SLOT_SIZE(g->size) : 0u);
}

/* Read and check the slot at `addr` (header into `hdr`; the image into `dst` when not NULL,
 * which must hold `max` bytes). 1: valid, 0: not, -1: the driver failed. */
int odg_fixed_read_(const odg_nv_driver_t *nv, uint32_t addr, uint32_t max, uint8_t *hdr,
                     uint8_t *dst)
{
    int v = odg_hdr_read_(nv, addr, hdr, FIXED_HDR, ODG_PERSIST_ODG1_MAGIC);
    if (v != 1 || odg_get32_(hdr + 12) > max) {
        return v < 0 ? -1 : 0;
    }
    return odg_crc_ok_(nv, addr, hdr, FIXED_HDR, odg_get32_(hdr + 12), dst);
}

/* Check both slots of group `g`: -2 on a driver error, -1 when neither is valid, else the
 * slot (0 or 1) holding the newest valid image, whose header is then in hdr[that slot]. */
static int fixed_newest(const odg_nv_driver_t *nv, const odg_group_t *g, uint8_t hdr[2][FIXED_HDR])
{
    int v[2], k;
    for (k = 0; k < 2; k++) {
        v[k] = odg_fixed_read_(nv, fixed_slot(g, k), g->size, hdr[k], NULL);
        if (v[k] < 0) {
            return -2;
        }
    }
    if (v[0] && v[1]) {
        return odg_newer_(odg_get32_(hdr[1] + 4), odg_get32_(hdr[0] + 4)) ? 1 : 0;
    }
    return v[0] ? 0 : (v[1] ? 1 : -1);
}

/* No valid image: DEFAULTS when both slots are erased (first boot, after a restore), DAMAGED
 * when something else is there, since then values once stored were lost. */
static odg_boot_status_t fixed_no_image(const odg_nv_driver_t *nv, const odg_group_t *g)
{
    int v = odg_slot_blank_(nv, g->nv_addr, 2u * ODG_PERSIST_SLOT_SIZE(g->size)); /* B follows A */
    return v < 0 ? ODG_BOOT_NV_ERROR : (v ? ODG_BOOT_DEFAULTS : ODG_BOOT_DAMAGED);
}

/* The value of sub-entry `s` in the mirror of group `g` checked against the firmware's
 * current limits: outside them (limits tightened since it was stored), its default: 1, else 0. */
static uint16_t recheck_one(const odg_dict_t *d, uint8_t g, uint32_t pos, const odg_sub_t *s)
{
    const odg_group_t *gr = &d->groups[g];
    uint8_t *v = odg_value_(d, s);
    odg_num_t x;
    if (!(ODG_CFG_LIMITS || ODG_CFG_REAL_LIMITS) || !(s->attr & ODG_A_LIMIT) || (s->attr & ODG_A_NODEID) ||
        s->size > sizeof x) {
        return 0; /* a same-layout image holds values of the type; $NODEID ones are not checked */
    }
    x = odg_num_get_(v, s->size);
    if (s->type < 0x20u && (SIGNED >> s->type & 1u) && s->size < sizeof x && ((x >> (8u * s->size - 1u)) & 1u)) {
        x |= ~(odg_num_t)0 << (8u * s->size); /* an INTEGERn: sign-extended */
    }
    if (odg_check_(d, (uint16_t)pos, x) == ODG_OK) {
        return 0;
    }
    odg_group_defaults(gr, (uint32_t)(v - (uint8_t *)gr->mirror), s->size, v);
    return 1;
}

/* An "ODG1" image of the same layout, loaded into the mirror of group `g`: its values outside
 * the current limits take their defaults, as a migration does (docs/persistence.md). How many. */
static uint16_t recheck(const odg_dict_t *d, uint8_t g)
{
    uint8_t storage = (uint8_t)(ODG_S_PERSIST | (unsigned)g << 2);
    uint16_t n = 0, e, p;
    odg_sub_t el, m;
    uint8_t k;
    for (e = 0; e < d->n_entries; e++) {
        const odg_entry_t *en = &d->entries[e];
        for (p = en->first; p < en->first + en->count; p++) {
            const odg_sub_t *s = odg_sub_at_(d, en, p, &m); /* each member of a shared run */
            if (s->storage != storage) {
                continue;
            }
            if (ODG_CFG_PACKED && (en->code & ODG_E_PACKED) && s->sub > 0u) {
                for (k = 1; k <= s->sub; k++) { /* the elements share the descriptor at p */
                    odg_element_(s, k, &el);
                    n = (uint16_t)(n + recheck_one(d, g, p, &el));
                }
            } else {
                n = (uint16_t)(n + recheck_one(d, g, p, s));
            }
        }
    }
    return n;
}

/* Write the mirror of `gr` as the new newest "ODG1" image. */
static odg_abort_t fixed_write(const odg_nv_driver_t *nv, const odg_group_t *gr)
{
    uint8_t hdr[2][FIXED_HDR], h[FIXED_HDR];
    uint32_t addr, seq = 1;
    int k;
    k = fixed_newest(nv, gr, hdr);
    if (k == -2) {
        return ODG_ABORT_HARDWARE;
    }
    if (k >= 0) {
        seq = odg_get32_(hdr[k] + 4) + 1u;
    }
    addr = fixed_slot(gr, k == 0);
    odg_put32_(h, ODG_PERSIST_ODG1_MAGIC);
    odg_put32_(h + 4, seq);
    odg_put32_(h + 8, gr->signature);
    odg_put32_(h + 12, gr->size);
    /* the CRC covers the bytes as they are now; should the mirror change while it is being
     * written, the read-back below fails and the previous image stays the newest */
    odg_put32_(h + 16, odg_crc32(odg_crc32(0, h, 16), gr->mirror, gr->size));
    if (nv->erase(nv->ctx, addr, ODG_PERSIST_SLOT_SIZE(gr->size)) != 0 ||
        nv->write(nv->ctx, addr + FIXED_HDR, gr->mirror, gr->size) != 0 ||
        nv->write(nv->ctx, addr + 4u, h + 4, FIXED_HDR - 4u) != 0 ||
        nv->write(nv->ctx, addr, h, 4u) != 0 ||
        odg_fixed_read_(nv, addr, gr->size, hdr[0], NULL) != 1 || odg_get32_(hdr[0] + 16) != odg_get32_(h + 16)) {
        return ODG_ABORT_HARDWARE;
    }
    return ODG_OK;
}

odg_abort_t odg_fixed_store_(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g)
{
    return fixed_write(nv, &d->groups[g]);
}

/* Make the next boot of group `g` ("ODG1") use the defaults: erase both slots. */
odg_abort_t odg_fixed_erase_(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g)
{
    const odg_group_t *gr = &d->groups[g];
    uint8_t hdr[2][FIXED_HDR];
    int k, n;
    k = fixed_newest(nv, gr, hdr);
    if (k == -2) {
        return ODG_ABORT_HARDWARE;
    }
    /* the older slot first: a power cut in between leaves the newest image (nothing
     * happened), never the older one */
    for (n = 0, k = k == 0; n < 2; n++, k = !k) {
        if (nv->erase(nv->ctx, fixed_slot(gr, k), ODG_PERSIST_SLOT_SIZE(gr->size)) != 0) {
            return ODG_ABORT_HARDWARE;
        }
    }
    return ODG_OK;
}

odg_boot_status_t odg_fixed_boot_(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g,
                                     odg_boot_t *b)
{
    const odg_group_t *gr = &d->groups[g];
    uint8_t hdr[2][FIXED_HDR], h[FIXED_HDR];
    odg_boot_status_t st = ODG_BOOT_DEFAULTS;
    int k = fixed_newest(nv, gr, hdr);
    if (k == -2) {
        st = ODG_BOOT_NV_ERROR;
    } else if (k == -1) {
        st = fixed_no_image(nv, gr);
    } else if (odg_fixed_read_(nv, fixed_slot(gr, k), gr->size, h, (uint8_t *)gr->mirror) != 1) {
        st = ODG_BOOT_NV_ERROR; /* it was valid a moment ago: a flaky read */
    } else if (odg_get32_(h + 8) != gr->signature || odg_get32_(h + 12) != gr->size) {
        st = ODG_BOOT_SIGNATURE; /* an image of another layout, read over the defaults below */
    } else if ((b->defaulted = recheck(d, g)) == 0u) {
        return ODG_BOOT_LOADED;
    } else { /* values outside tightened limits took their defaults: a loss, stored at once */
        d->state->boot_seen = (uint8_t)(d->state->boot_seen | ODG_BOOT_ENTRIES_LOST);
        return fixed_write(nv, gr) == ODG_OK ? ODG_BOOT_MIGRATED : ODG_BOOT_NV_ERROR;
    }
    odg_defaults_(d, g);
    if (st != ODG_BOOT_NV_ERROR && fixed_write(nv, gr) != ODG_OK) {
        st = ODG_BOOT_NV_ERROR;
    }
    return st;
}


/* ---- records of other layers ---------------------------------------------------------------
 *
 * A record is one UNSIGNED32 in two slots (A at addr, B right after it, ODG_PERSIST_RECORD_SLOT
 * bytes each), committed as the images above are, each slot read whole into RAM:
 *
 *   offset  size  field (all little-endian, encoded byte by byte)
 *        0     4  tag of the record (its layout, "LSS1" say): the commit mark, written last
 *        4     4  sequence number (serial arithmetic: wraps around)
 *        8     4  the value
 *       12     4  CRC-32 of bytes 0..11
 *
 * A slot is valid when it starts with the tag and the CRC matches. A store erases the slot
 * that does not hold the newest valid record, writes bytes 4..15, then the tag, and reads both
 * slots back. A tag has no byte 0xFF, so a tag cut short is not the tag; it differs from
 * "ODG1" and "ODG2", so a group's slot is never taken for a record. */

#define REC_BYTES 16u

/* Read the record slot at `addr` into `s`: 1 valid, 0 not, -1 the driver failed. */
static int record_read(const odg_nv_driver_t *nv, uint32_t addr, uint32_t tag, uint8_t *s)
{
    int v = odg_hdr_read_(nv, addr, s, REC_BYTES, tag);
    return v == 1 ? odg_crc_ok_(nv, addr, s, REC_BYTES, 0u, NULL) : v; /* the CRC ends the slot */
}

/* Both slots of a record into s[0] and s[1]: -2 the driver failed, -1 neither is valid, else
 * the slot holding the newest valid record. */
static int record_newest(const odg_nv_driver_t *nv, uint32_t addr, uint32_t tag,
                         uint8_t s[2][REC_BYTES])
{
    int k, v, best = -1;
    for (k = 0; k < 2; k++, addr += ODG_PERSIST_RECORD_SLOT) {
        v = record_read(nv, addr, tag, s[k]);
        if (v < 0) {
            return -2;
        }
        if (v && (best < 0 || odg_newer_(odg_get32_(s[1] + 4), odg_get32_(s[0] + 4)))) {
            best = k;
        }
    }
    return best;
}

odg_abort_t odg_persist_store_record(const odg_nv_driver_t *nv, uint32_t addr, uint32_t tag, uint32_t value)
{
    uint8_t s[2][REC_BYTES];
    uint32_t at;
    int to, k = nv != NULL ? record_newest(nv, addr, tag, s) : -3;
    if (k < -1) {
        return k == -2 ? ODG_ABORT_HARDWARE : ODG_ABORT_DATA_STORE;
    }
    /* into the slot that does not hold the newest record (B when A does, else A), with the
     * sequence number after the newest's (after A's, any, when neither is valid) */
    to = k == 0;
    at = addr + (to ? ODG_PERSIST_RECORD_SLOT : 0u);
    odg_put32_(s[0] + 4, odg_get32_(s[k == 1] + 4) + 1u);
    odg_put32_(s[0], tag);
    odg_put32_(s[0] + 8, value);
    odg_put32_(s[0] + 12, odg_crc32(0, s[0], 12u));
    /* read back: that slot must now be valid and the newest */
    if (nv->erase(nv->ctx, at, ODG_PERSIST_RECORD_SLOT) != 0 ||
        nv->write(nv->ctx, at + 4u, s[0] + 4, 12u) != 0 || nv->write(nv->ctx, at, s[0], 4u) != 0 ||
        record_newest(nv, addr, tag, s) != to) {
        return ODG_ABORT_HARDWARE;
    }
    return ODG_OK;
}

int odg_persist_load_record(const odg_nv_driver_t *nv, uint32_t addr, uint32_t tag, uint32_t *value)
{
    uint8_t s[2][REC_BYTES];
    int k = nv != NULL ? record_newest(nv, addr, tag, s) : -2;
    if (k < 0) {
        return k + 1; /* none: 0; the driver failed: -1 */
    }
    *value = odg_get32_(s[k] + 8);
    return 1;
}
