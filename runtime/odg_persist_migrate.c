/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_persist_migrate.c - self-describing images ("ODG2") and their migration at boot: a
 * group generated with migration (the default) keeps its values in wire format after the
 * layout they were written with, in two slots at the start and the middle of its own region;
 * at boot a stored image of another layout is migrated entry by entry (docs/persistence.md;
 * the policy is odgen/place/migration.py). Left out when ODG_CFG_PERSIST_MIGRATION is 0.
 */
#include <string.h>

#include "odg_persist_migrate.h"

#if ODG_CFG_PERSIST_MIGRATION

/* A helper called from several places stays out of line where GCC's -Os would copy it into
 * each caller (measured: fewer bytes on Cortex-M4). */
#if defined(__GNUC__)
#define OUTLINE __attribute__((noinline))
#else
#define OUTLINE
#endif

/* Header words are read with ODG_LE32, inline: -Os makes it one load where the core allows,
 * less than a call of odg_get32_ (measured on Cortex-M4). */
#define DESCRIBED_HDR ODG_PERSIST_HEADER2_SIZE
#define DESCRIBED_MAGIC 0x3247444Fu /* "ODG2" */
/* What described_read keeps of a valid slot: its header and then the image's record count, so
 * that the migration need not read the count again */
#define HEAD (DESCRIBED_HDR + 2u)
#define REC 6u             /* a layout descriptor record: index u16, sub u8, type u8, length u16 */

/* The numeric types by CiA 301 code: wire size in the low nibble (0 for strings, domains and
 * unknown codes), NUM_INT for UNSIGNEDn and INTEGERn, NUM_SIGNED for INTEGERn. */
#define NUM_INT 0x10u
#define NUM_SIGNED 0x20u
#define NUM_SI (NUM_INT | NUM_SIGNED) /* INTEGERn */
static const uint8_t num_type[0x1C] = {
    0, 1, 1 | NUM_SI, 2 | NUM_SI, 4 | NUM_SI, 1 | NUM_INT, 2 | NUM_INT, 4 | NUM_INT, /* 0x00 */
    4, 0, 0, 0, 6, 6, 0, 0,                                                         /* 0x08 */
    3 | NUM_SI, 8, 5 | NUM_SI, 6 | NUM_SI, 7 | NUM_SI, 8 | NUM_SI, 3 | NUM_INT, 0,   /* 0x10 */
    5 | NUM_INT, 6 | NUM_INT, 7 | NUM_INT, 8 | NUM_INT};                            /* 0x18 */

static unsigned num_of(uint8_t t)
{
    return t < 0x1Cu ? num_type[t] : 0u;
}

#define BIT(t) ((uint32_t)1u << (t))
/* Strings and domains among the persisted entries this build serves (odg.h: ODG_CFG_*): 0 when
 * none, so that the compiler leaves out their paths. */
#define STREAMS                                                                          \
    (ODG_CFG_PERSIST_STREAMS                                                             \
         ? (ODG_CFG_STRINGS ? BIT(ODG_T_VISIBLE_STRING) | BIT(ODG_T_OCTET_STRING) : 0u) | \
               (ODG_CFG_UNICODE ? BIT(ODG_T_UNICODE_STRING) : 0u) |                      \
               (ODG_CFG_DOMAINS ? BIT(ODG_T_DOMAIN) : 0u)                                \
         : 0u)
#define IS(t, type) ((STREAMS & BIT(type)) != 0u && (t) == (type))

/* Whether `t` is a string or domain this build serves (STREAMS): never in a build without. */
#define STREAMED(t) (STREAMS != 0u && streamed(t))
static int streamed(uint8_t t)
{
    return t < 0x1Cu && (BIT(t) & STREAMS) != 0u;
}

static uint16_t get16(const uint8_t *p)
{
    return (uint16_t)(p[0] | (unsigned)p[1] << 8);
}

OUTLINE static uint32_t rec_key(const uint8_t *rec)
{
    return (uint32_t)get16(rec) << 8 | rec[2];
}

/* Bytes of an entry's value in an image: a domain's used length (u32) precedes its bytes. */
OUTLINE static uint32_t value_size(const uint8_t *rec)
{
    return get16(rec + 4) + (rec[3] == ODG_T_DOMAIN ? 4u : 0u);
}

/* The firmware's layout descriptor of a group: its persisted sub-entries entry by entry in
 * dict->subs order (each element of a packed ARRAY in turn, each member of a shared run with
 * its own values), each a record (index, sub, type, length) read from the tables (odg_verify:
 * n_layout of them). */
typedef struct recs {
    const odg_dict_t *d;
    const odg_entry_t *e; /* the entry of the current sub-entry */
    unsigned pos;         /* position in dict->subs after its descriptor */
    uint16_t left;        /* records still to come */
    uint8_t storage;      /* ODG_S_PERSIST | group << 2 */
    const odg_sub_t *of;  /* the descriptor of the packed elements walked last (done when
                           * elem.sub is its sub), or NULL */
    odg_sub_t elem;       /* the descriptor made for an element of a packed ARRAY */
    odg_sub_t member;     /* the descriptor made for a member of a shared run (ODG_E_SHARED) */
} recs_t;

static void recs_start(recs_t *r, const odg_dict_t *d, uint8_t g)
{
    r->d = d;
    r->e = d->entries;
    r->pos = d->entries[0].first;
    r->left = d->groups[g].n_layout;
    r->storage = (uint8_t)(ODG_S_PERSIST | (unsigned)g << 2);
    r->of = NULL;
}

/* The next persisted sub-entry (its descriptor at position r->pos - 1), or NULL after the last. */
static const odg_sub_t *recs_next(recs_t *r)
{
    const odg_dict_t *d = r->d;
    const odg_entry_t *end = d->entries + d->n_entries;
    const odg_sub_t *s = &r->elem;
    while (r->left > 0u) {
        if (ODG_CFG_PACKED && r->of != NULL && r->elem.sub < r->of->sub) {
            odg_element_(r->of, (uint8_t)(r->elem.sub + 1u), &r->elem);
            s = &r->elem;
        } else if (r->e < end) {
            r->of = NULL; /* it may point to r->member, made anew below */
            if (r->pos >= (uint32_t)r->e->first + r->e->count) { /* the entry's last: the next */
                if (++r->e < end) {
                    r->pos = r->e->first;
                }
                continue;
            }
            s = odg_sub_at_(d, r->e, r->pos++, &r->member);
            if (s->storage != r->storage) {
                continue;
            }
            if (ODG_CFG_PACKED && (r->e->code & ODG_E_PACKED) && s->sub > 0u) {
                r->of = s; /* its elements come from the next turns */
                r->elem.sub = 0;
                continue;
            }
        } else {
            break;
        }
        r->left--;
        return s;
    }
    return NULL;
}

/* Bytes of a sub-entry's value in an image (value_size of its record). */
static uint32_t sub_value_size(const odg_sub_t *s)
{
    return s->size + (IS(s->type, ODG_T_DOMAIN) ? 4u : 0u);
}

/* Bytes of group `g`'s image: the record count, the records and the values. */
static uint32_t image_size(const odg_dict_t *d, uint8_t g)
{
    uint32_t n = 2u;
    const odg_sub_t *s;
    recs_t r;
    recs_start(&r, d, g);
    while ((s = recs_next(&r)) != NULL) {
        n += REC + sub_value_size(s);
    }
    return n;
}

/* The group id an "ODG2" slot of group `gr` carries: the CRC-32 of its name mixed with the
 * region's place in NV (an odd multiplier: two places never give one tag), so that an image of
 * this group written at another place (its region moved) is not taken for one of this region.
 * Images written before carry the plain CRC-32 and are still taken (docs/persistence.md). */
static uint32_t tagged_id(const odg_group_t *gr)
{
    return gr->id ^ ((gr->nv_addr + 1u) * 0x9E3779B1u);
}

static int our_id(const odg_group_t *gr, uint32_t id)
{
    return id == tagged_id(gr) || id == gr->id;
}

/* Read and check the "ODG2" slot at `addr` (header into `h`, HEAD bytes: the record count
 * after it when valid) as an image of group `gr`: its id,
 * and at slot A or at the middle of the region it names. A valid image has a descriptor of
 * records with increasing keys whose values fill it. 1 valid, 0 not, -1 the driver failed, 2
 * a header of ours whose image runs past the region and cannot be read there: an image of a
 * larger region on an NV that ends before it, which is a loss, never "nothing there".
 * A header that is not of this group (no "ODG2", another id) names no region: its region word
 * in `h` is made 0, so that the place walk reads the place slot A names without checking the
 * header again (named). */
static int described_read(const odg_nv_driver_t *nv, const odg_group_t *gr, uint32_t addr, uint8_t *h)
{
    uint8_t c[REC];
    uint32_t len, region, cnt, sum, prev = 0, rend;
    int v = odg_hdr_read_(nv, addr, h, HEAD, DESCRIBED_MAGIC); /* the record count too */
    if (v != 1 || !our_id(gr, ODG_LE32(h + 8))) {
        memset(h + 12, 0, 4);
        return v < 0 ? -1 : 0;
    }
    region = ODG_LE32(h + 12);
    len = ODG_LE32(h + 16);
    /* len from 2 (the record count) up to what half the region holds after the header: one
     * unsigned compare, len below 2 wraps round */
    if (region > 0x01000001u || region / 2u < DESCRIBED_HDR + 2u || /* 16 MiB, a load mark */
        len - 2u > region / 2u - DESCRIBED_HDR - 2u ||
        (addr != gr->nv_addr && addr - gr->nv_addr != region / 2u)) {
        return 0;
    }
    v = odg_crc_ok_(nv, addr, h, DESCRIBED_HDR, len, NULL);
    if (v < 0 && addr + DESCRIBED_HDR + len > gr->nv_addr + gr->region) {
        return 2;
    }
    if (v != 1) {
        return v; /* 0 a CRC error, -1 the driver failed */
    }
    cnt = get16(h + DESCRIBED_HDR);
    addr += DESCRIBED_HDR + 2u; /* the records */
    for (rend = addr + REC * cnt, sum = 2u + REC * cnt; addr != rend && sum <= len; addr += REC) {
        if (nv->read(nv->ctx, addr, c, REC) != 0) {
            return -1;
        }
        if (rec_key(c) < prev) {
            return 0;
        }
        prev = rec_key(c) + 1u; /* the keys increase */
        sum += value_size(c);
    }
    return sum == len;
}

/* Whether the slot at `addr` reads back as the valid image whose header is `h`: the CRC, which
 * covers the rest of the header and the image, is the same (the ODG1 store checks the same). */
static int reads_back(const odg_nv_driver_t *nv, const odg_group_t *gr, uint32_t addr,
                      const uint8_t *h)
{
    uint8_t t[HEAD];
    return described_read(nv, gr, addr, t) == 1 && ODG_LE32(t + 20) == ODG_LE32(h + 20);
}

/* The places an image of group `gr` can be, as offsets from its region's start after `half`:
 * slot A (0), slot B of its region (the middle), then slot B of every other region size the
 * group may have had, in place (powers of two from 64 bytes up to ODG_PERSIST_MAX_REGION): a
 * region that grew or shrank keeps its images where they were written, and each image's
 * header names the region it was written for. 0 after the last. */
OUTLINE static uint32_t next_place(const odg_group_t *gr, uint32_t half)
{
    if (half == 0u) {
        return gr->region / 2u;
    }
    half = half == gr->region / 2u ? 32u : 2u * half;
    if (half == gr->region / 2u) {
        half *= 2u;
    }
    return half <= ODG_PERSIST_MAX_REGION / 2u ? half : 0u;
}

/* The bytes a slot's image takes, rounded up to the slot alignment. */
static uint32_t extent(const uint8_t *h)
{
    return (DESCRIBED_HDR + ODG_LE32(h + 16) + ODG_PERSIST_ALIGN - 1u) & ~((uint32_t)ODG_PERSIST_ALIGN - 1u);
}

/* The place (as `half`) slot A's header `a` names, as described_read left it (the image not
 * checked): the middle of the region it was written for when it is a header of this group,
 * else 0 (slot A itself). */
static uint32_t named(const uint8_t *a)
{
    return ODG_LE32(a + 12) / 2u;
}

/* An image found: where it is, and its header and record count (HEAD; one argument for both:
 * fewer on the stack). */
typedef struct found {
    uint32_t at;
    uint8_t h[HEAD];
} found_t;

/* The bytes of a slot header, rounded up to the slot alignment: erasing them is enough to make
 * an image invalid (its magic is gone), and leaves the rest of its bytes where they are. */
#define HDR_EXTENT ((DESCRIBED_HDR + ODG_PERSIST_ALIGN - 1u) & ~((uint32_t)ODG_PERSIST_ALIGN - 1u))

/* The newest image of group `gr` of `d` at its places inside the dictionary's NV (up to its
 * NAME_NV_SIZE) and the place slot A's header names past it (the slot B of a larger region a
 * later firmware used): 1 valid, 2 a header of ours whose image cannot be read (described_read
 * says 2), 0 none, -1 the driver failed inside the region (a failing read past it means no NV
 * there); its address (nv_addr when none) and its header in *f. With `wipe`, the headers of
 * the valid images past the region other than at `keep` are erased on the way (-1 when that
 * fails): past the region lies the region of a group that boots later, and the rest of such
 * an image is what tells that group's boot that its region held bytes of another (a loss,
 * DAMAGED), where an erased region would be a first boot. */
static int walk(const odg_dict_t *d, const odg_nv_driver_t *nv, const odg_group_t *gr, found_t *f,
                int wipe, uint32_t keep)
{
    uint8_t t[HEAD];
    /* far: the place slot A names (0 until slot A is read: slot A is never past the NV);
     * inside: the bytes of slot A's valid image, at whose places lies no image of ours (a store
     * there would have broken slot A's image): a value of it, an OCTET_STRING say, that looks
     * like one is never taken */
    uint32_t half = 0u, addr, end = ODG_NV_END_(d), far = 0u, inside = 0u;
    int v, k = 0;
    f->at = gr->nv_addr;
    do {
        if (half != far && gr->nv_addr + half + HEAD > end) {
            continue; /* past the dictionary's NV */
        }
        addr = gr->nv_addr + half;
        v = described_read(nv, gr, addr, t);
        if (v < 0 && half < gr->region) {
            return -1;
        }
        if (half == 0u) {
            far = named(t);
        }
        if (v <= 0 || half < inside) {
            continue;
        }
        if (wipe && v == 1 && half >= gr->region && addr != keep && odg_wipe_(nv, addr, addr + HDR_EXTENT)) {
            return -1;
        }
        if (!k || ODG_NEWER_(ODG_LE32(t + 4), ODG_LE32(f->h + 4))) {
            k = v;
            f->at = addr;
            odg_copy(f->h, t, HEAD);
        }
        if (half == 0u) { /* valid, or (2) unreadable past the NV: its header says how far it goes */
            inside = extent(t);
        }
    } while ((half = next_place(gr, half)) != 0u);
    return k;
}

static int newest(const odg_dict_t *d, const odg_nv_driver_t *nv, const odg_group_t *gr, found_t *f)
{
    return walk(d, nv, gr, f, 0, 0u);
}

/* Image bytes on their way to NV, CRC-32 on the fly. */
typedef struct out {
    const odg_nv_driver_t *nv;
    uint32_t addr; /* where buf goes */
    uint32_t crc;
    uint32_t n;    /* bytes in buf */
    int fail;      /* not 0 once the driver failed */
    uint8_t buf[ODG_PERSIST_CHUNK_];
} out_t;

static void flush(out_t *o)
{
    if (o->n > 0u && !o->fail) {
        o->fail = o->nv->write(o->nv->ctx, o->addr, o->buf, o->n);
        o->crc = odg_crc32(o->crc, o->buf, o->n);
        o->addr += o->n;
    }
    o->n = 0;
}

/* The `n` (up to 4) low bytes of `v`, little endian: 32 bits, so that no call passes a 64-bit
 * value (emit_value splits a wider number). */
static void emit(out_t *o, uint32_t n, uint32_t v)
{
    while (n-- > 0u) {
        o->buf[o->n++] = (uint8_t)v;
        v >>= 8;
        if (o->n == ODG_PERSIST_CHUNK_) {
            flush(o);
        }
    }
}

/* One value in wire format: strings padded with zeros after their terminator, a domain as its
 * used length and then `size` bytes of its buffer, zeros after the used ones. */
static void emit_value(out_t *o, const odg_dict_t *d, const odg_sub_t *s)
{
    uint32_t i, n = s->size, keep = n, zero = 0;
    const uint8_t *p;
    odg_num_t v;
    if (IS(s->type, ODG_T_DOMAIN)) {
        const odg_domain_t *dm = &d->domains[s->offset];
        keep = *dm->length;
        keep = keep < n ? keep : n;
        keep = keep < dm->capacity ? keep : dm->capacity;
        emit(o, 4, keep);
        p = dm->data;
    } else {
        p = odg_value_(d, s);
    }
    if (!STREAMED(s->type)) {
        v = odg_num_get_(p, n);
        if (ODG_CFG_INT64 && n > 4u) { /* the low 32 bits first */
            emit(o, 4, (uint32_t)v);
            v = v >> 16 >> 16; /* twice 16: no shift by the width of a 32-bit odg_num_t */
            n -= 4u;
        }
        emit(o, n, (uint32_t)v);
    } else if (IS(s->type, ODG_T_UNICODE_STRING)) {
        for (i = 0; i < n; i += 2u) {
            uint16_t u;
            memcpy(&u, p + i, 2);
            zero |= u == 0u;
            emit(o, n - i < 2u ? 1u : 2u, zero ? 0u : u);
        }
    } else {
        for (i = 0; i < n; i++) {
            zero |= i >= keep || (p[i] == 0u && s->type == ODG_T_VISIBLE_STRING);
            emit(o, 1, zero ? 0u : p[i]);
        }
    }
}

/* Write the mirror of group `g` as its newest image: into slot A when the newest is in slot B
 * of the current region, else into that slot B (past the whole old region when the region
 * grew). Slot A, which names the old region, stays until the newest is in the current slot B,
 * so an image in the old slot B is found until then.
 * With `load` (0x1011) the image is a mark (bit 0 of its region word set) that makes the next
 * boot serve the defaults (DEFAULTS): stored as a save is, so that every firmware that would
 * find a save finds the mark, and a power cut leaves the newest image or the mark. One store
 * for both commands: smaller than an erase that must order its wipes so that no older image
 * outlives the newest, and a rollback that cannot see past its NV finds the mark through slot
 * A's header as it finds a save (an erased slot A would name nothing, and its stores would
 * start their sequence over below the mark's). */
odg_abort_t odg_described_store_(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g, int load)
{
    const odg_group_t *gr = &d->groups[g];
    uint8_t h[DESCRIBED_HDR];
    found_t t;
    uint32_t seq = 1, half = gr->region / 2u, addr = gr->nv_addr, size = image_size(d, g);
    const odg_sub_t *s;
    recs_t r;
    out_t o;
    int k = newest(d, nv, gr, &t);
    if (k < 0) {
        return ODG_ABORT_HARDWARE;
    }
    if (k > 0) {
        /* the slot beside the newest; should the newest be an image of a larger region that
         * reaches into it (after a rollback), it is written over: it was read (and migrated) at
         * boot, and keeping it would refuse every store for good. A power cut before the new
         * image is committed then loses both, so the group's other images past the region (of
         * the larger region: slot B, which slot A's header names) are erased first: the next
         * boot finds none of them and reports the loss, never serves an older store. Only an
         * image in slot A can reach into slot B: one at another place of the region is of a
         * region at most half as large, and ends before the middle. */
        seq = ODG_LE32(t.h + 4) + 1u;
        addr = t.at == gr->nv_addr + half ? gr->nv_addr : gr->nv_addr + half;
        if (t.at == gr->nv_addr && extent(t.h) > half && walk(d, nv, gr, &t, 1, t.at) < 0) {
            return ODG_ABORT_HARDWARE;
        }
    }
    if (DESCRIBED_HDR + size > half) {
        return ODG_ABORT_DATA_STORE; /* odg_verify: never for a generated dictionary */
    }
    odg_put_le32_(h, DESCRIBED_MAGIC);
    odg_put_le32_(h + 4, seq);
    odg_put_le32_(h + 8, tagged_id(gr));
    odg_put_le32_(h + 12, gr->region | (uint32_t)load);
    odg_put_le32_(h + 16, size);
    o.nv = nv;
    o.addr = addr + DESCRIBED_HDR;
    o.crc = odg_crc32(0, h, 20);
    o.n = 0;
    o.fail = nv->erase(nv->ctx, addr, half);
    emit(&o, 2, gr->n_layout);
    for (recs_start(&r, d, g); (s = recs_next(&r)) != NULL;) { /* the layout descriptor */
        emit(&o, 4, r.e->index | (uint32_t)s->sub << 16 | (uint32_t)s->type << 24);
        emit(&o, 2, s->size);
    }
    for (recs_start(&r, d, g); (s = recs_next(&r)) != NULL;) {
        emit_value(&o, d, s);
    }
    flush(&o);
    /* the CRC covers the bytes written; the read-back below checks that they landed */
    odg_put_le32_(h + 20, o.crc);
    /* when the newest was an image in slot A that runs past the NV this firmware's driver shows
     * (2), its header goes once the new image is committed: it would hide the new image, which
     * lies inside its bytes (the boot takes no image there) */
    if (o.fail || nv->write(nv->ctx, addr + 4u, h + 4, DESCRIBED_HDR - 4u) != 0 ||
        nv->write(nv->ctx, addr, h, 4u) != 0 || !reads_back(nv, gr, addr, h) ||
        (k == 2 && t.at == gr->nv_addr && nv->erase(nv->ctx, t.at, HDR_EXTENT) != 0)) {
        return ODG_ABORT_HARDWARE;
    }
    return ODG_OK;
}

/* After a boot of group `gr`: erase what its region holds besides its own images (at its
 * places, visited in address order: slot A, then the middle of every power-of-two region up to
 * its own): images of other groups or of this one written at another place, and bytes of
 * neither, left there by a firmware whose NV map differed, which must never come back as a
 * group's values when the map changes again. Its own older images stay: a rollback firmware
 * that cannot see the newest one (past its NV) finds the one the newest was migrated from.
 * -1 when the driver failed. */
static int scrub(const odg_nv_driver_t *nv, const odg_group_t *gr)
{
    uint8_t t[HEAD];
    uint32_t end = gr->nv_addr + gr->region, pos = gr->nv_addr, half = 0u, addr, e;
    int v;
    do {
        addr = gr->nv_addr + half;
        v = described_read(nv, gr, addr, t);
        if (v < 0) {
            return -1;
        }
        if (v > 0) {
            if (odg_clear_(nv, pos, addr)) {
                return -1;
            }
            e = addr + extent(t);
            pos = e > pos ? e : pos;
        }
        half = 2u * half > 32u ? 2u * half : 32u; /* 0, 32, 64, ... */
    } while (half < gr->region);
    return odg_clear_(nv, pos, end) ? -1 : 0; /* nothing when pos is past the end */
}

/* ---- boot migration: docs/persistence.md section 3, odgen/persist/migration.py ----------- */

/* What became of an entry; n[DEFAULTED .. CONVERTED] go to odg_state_t.boot_counts. ADDED: new
 * in the group (the default, no loss). */
enum { KEPT = 0, DEFAULTED = 1, DROPPED = 2, CONVERTED = 3, ADDED = 4, FAILED = -1 };

/* A string (unit 1, or 2 for UNICODE_STRING): what fits, up to its terminator; converted when
 * the stored content went on past the new capacity. */
static int read_string(const odg_nv_driver_t *nv, const odg_sub_t *s, uint8_t *p, uint32_t sl,
                       uint32_t addr)
{
    uint32_t unit = IS(s->type, ODG_T_UNICODE_STRING) ? 2u : 1u, fl = s->size, i;
    uint8_t c[2];
    uint16_t u;
    memset(p, 0, fl - fl % unit + unit);
    for (i = 0; i + unit <= sl; i += unit) {
        if (nv->read(nv->ctx, addr + i, c, unit) != 0) {
            return FAILED;
        }
        u = (uint16_t)(unit == 2u ? c[0] | (unsigned)c[1] << 8 : c[0]);
        if (u == 0u) {
            return KEPT;
        }
        if (i + unit > fl) {
            return CONVERTED; /* a character past the new capacity */
        }
        if (unit == 2u) {
            memcpy(p + i, &u, 2);
        } else {
            p[i] = c[0];
        }
    }
    return KEPT;
}

/* A string or domain of the same type: keep what fits (resized). An OCTET_STRING and a domain
 * keep their first bytes (a domain's used ones, after its used length). */
static int read_stream(const odg_dict_t *d, const odg_nv_driver_t *nv, const odg_sub_t *s, uint32_t sl,
                       uint32_t addr)
{
    const odg_domain_t *dm = NULL;
    uint8_t c[4], *p;
    uint32_t used = sl, cap = s->size, n;
    if (IS(s->type, ODG_T_DOMAIN)) {
        dm = &d->domains[s->offset];
        if (nv->read(nv->ctx, addr, c, 4) != 0) {
            return FAILED;
        }
        used = ODG_LE32(c);
        used = used < sl ? used : sl;
        cap = cap < dm->capacity ? cap : dm->capacity;
        p = dm->data;
        addr += 4u;
    } else {
        p = odg_value_(d, s);
        if (s->type != ODG_T_OCTET_STRING) {
            return read_string(nv, s, p, sl, addr);
        }
        memset(p, 0, cap);
    }
    n = used < cap ? used : cap;
    if ((n > 0u || dm == NULL) && nv->read(nv->ctx, addr, p, n) != 0) {
        return FAILED;
    }
    if (dm != NULL) {
        *dm->length = n;
    }
    return n < used ? CONVERTED : KEPT;
}

/* carried's answer for a string or domain of the same type, beside num_type's bits; never in a
 * build without them (STREAMS) */
#define STREAM 0x40u
#define AS_STREAM(a) (STREAMS != 0u && (a) == STREAM)

/* How the stored entry `st` carries into the firmware's sub-entry `s`: as a string or domain
 * of the same type (STREAM: kept or resized), or as a number of the same type, or an integer
 * widened, with its type's length (migration.py: KEEP or CONVERT): its stored type's num_type
 * (never 0); else 0: it is narrowed, retyped, or of a length that does not fit its type, and
 * defaulted. One answer for the value's read and for the test of a sub 0 that follows. */
static unsigned carried(const odg_sub_t *s, const uint8_t *st)
{
    unsigned a = num_of(st[3]), b = num_of(s->type), sl = get16(st + 4);
    /* a widened integer: UNSIGNEDn -> UNSIGNEDm, INTEGERn -> INTEGERm, UNSIGNEDn -> INTEGERm
     * with m > n */
    int widens = (a & b & NUM_INT) && (b & 0xFu) > (a & 0xFu) && !(a & ~b & NUM_SIGNED);
    if (s->type == st[3] && STREAMED(s->type)) {
        return STREAM;
    }
    return (s->type == st[3] || widens) && sl != 0u && sl == (a & 0xFu) ? a : 0u;
}

/* Read the firmware's sub-entry `s` (at `pos` in dict->subs) from the stored entry `st`, whose
 * value lies at `addr` (emit_value's counterpart), carried as `a` says (carried): kept,
 * converted, or defaulted (the mirror keeps the default). */
static int read_value(const odg_dict_t *d, const odg_nv_driver_t *nv, uint32_t pos,
                      const odg_sub_t *s, const uint8_t *st, uint32_t addr, unsigned a)
{
    uint32_t sl = get16(st + 4), i;
    uint8_t c[8];
    odg_num_t v;
    if (AS_STREAM(a)) {
        return read_stream(d, nv, s, sl, addr);
    }
    /* a number of a type this build serves: no wider than odg_num_t (ODG_CFG_INT64) */
    if (a == 0u) {
        return DEFAULTED;
    }
    if (nv->read(nv->ctx, addr, c, sl) != 0) {
        return FAILED;
    }
    v = (a & NUM_SIGNED) && (c[sl - 1u] & 0x80u) ? ~(odg_num_t)0 : 0u;
    for (i = sl; i-- > 0u;) {
        v = v << 8 | c[i];
    }
    if (odg_check_(d, (uint16_t)pos, v) != ODG_OK) {
        return DEFAULTED; /* outside the current limits */
    }
    odg_num_put_(odg_value_(d, s), s->size, v);
    return s->type == st[3] ? KEPT : CONVERTED;
}

/* The highest sub-index of `index` among the records from `ra` up to `rend` (addresses: the
 * records of one image), 0 when none; -1 when the driver failed. */
static long stored_highest(const odg_nv_driver_t *nv, uint32_t ra, uint32_t rend, uint16_t index)
{
    uint8_t st[REC];
    long high = 0;
    for (; ra != rend; ra += REC) {
        if (nv->read(nv->ctx, ra, st, REC) != 0) {
            return -1;
        }
        if (get16(st) != index) {
            break;
        }
        high = st[2];
    }
    return high;
}

/* Whether sub 0 stored as `st`, carried as `a`, follows the firmware's entry when its highest
 * sub-index changed: only a value kept as it is (a string of the same capacity too) or widened
 * follows; one narrowed or retyped is defaulted, one resized is resized (migration.py: plan). */
static int follows(const odg_sub_t *s, const uint8_t *st, unsigned a)
{
    return AS_STREAM(a) ? get16(st + 4) == s->size : a != 0u;
}

/* The highest sub-index among the firmware's records of the entry whose sub 0 the layout walk
 * `fw` is at (0 when none follows): the sub of the entry's last sub-entry in the group (a packed
 * descriptor's is its last element's), found from the entry's end back to sub 0 at the latest
 * (the members of a shared run have the run's sub-indices and storage). */
static uint8_t fw_highest(const recs_t *fw)
{
    const odg_sub_t *s = &fw->d->subs[fw->e->first + fw->e->count];
    while ((--s)->storage != fw->storage) {
    }
    return s->sub;
}

/* Every entry of group `g` from the valid image `f` (its record count read with its header),
 * merged by key with the firmware's layout; the mirror holds the defaults before. Counts into
 * n[KEPT .. ADDED]; -1 when the driver failed. Sub 0 of an entry whose highest sub-index
 * changed follows it (the default, converted). */
static int migrate(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g, const found_t *f,
                   uint16_t n[5])
{
    uint8_t st[REC];
    /* ra: the next record's address; in: the address of the record in st (rend: none) */
    uint32_t ra = f->at + HEAD, rend, vo, key, fkey, cnt = get16(f->h + DESCRIBED_HDR), in;
    const odg_sub_t *s;
    recs_t fw;
    long high;
    unsigned a;
    int r;
    rend = ra + REC * cnt; /* past the records, where the values start */
    vo = in = rend;
    for (recs_start(&fw, d, g); (s = recs_next(&fw)) != NULL;) {
        r = ADDED;
        fkey = (uint32_t)fw.e->index << 8 | s->sub; /* the firmware record's key */
        while (ra != rend) { /* stored entries before this key are no longer in the group */
            if (in != ra && nv->read(nv->ctx, ra, st, REC) != 0) {
                return -1;
            }
            in = ra;
            key = rec_key(st);
            if (key > fkey) {
                break; /* not stored: the default */
            }
            /* a key before it: no longer in the group, dropped (counted at the end) */
            if (key == fkey) {
                a = carried(s, st);
                if ((fkey & 0xFFu) == 0u && follows(s, st, a) &&
                    (high = stored_highest(nv, ra + REC, rend, fw.e->index)) != (long)fw_highest(&fw)) {
                    if (high < 0) {
                        return -1;
                    }
                    r = CONVERTED; /* the count follows the entry: its default */
                } else if ((r = read_value(d, nv, fw.pos - 1u, s, st, vo, a)) == FAILED) {
                    return -1;
                }
            }
            vo += value_size(st);
            ra += REC;
            if (key == fkey) {
                break;
            }
        }
        n[r]++;
    }
    n[DROPPED] = (uint16_t)(cnt - n[KEPT] - n[DEFAULTED] - n[CONVERTED]); /* not matched */
    return 0;
}

/* No image of ours: DEFAULTS when the region is blank (a first boot, or a region that moved
 * onto erased NV); SIGNATURE for an "ODG1" image (the format before: its commit mark where the
 * region starts, at its slot A); else DAMAGED: corrupt bytes, another group's image or this
 * group's written at another place (the NV map changed), all losses. */
static odg_boot_status_t described_no_image(const odg_nv_driver_t *nv, const odg_group_t *gr)
{
    uint8_t t[4];
    int v = odg_slot_blank_(nv, gr->nv_addr, gr->region);
    if (v == 0) {
        v = odg_hdr_read_(nv, gr->nv_addr, t, 4u, ODG_PERSIST_ODG1_MAGIC);
        return v < 0 ? ODG_BOOT_NV_ERROR : (v ? ODG_BOOT_SIGNATURE : ODG_BOOT_DAMAGED);
    }
    return v < 0 ? ODG_BOOT_NV_ERROR : ODG_BOOT_DEFAULTS;
}

/* The counts of a boot that migrated an image, into `b` and the totals of the EMCY. */
static void count(odg_state_t *s, odg_boot_t *b, const uint16_t n[5])
{
    unsigned i, t;
    b->kept = n[KEPT];
    b->converted = n[CONVERTED];
    b->defaulted = n[DEFAULTED];
    b->dropped = n[DROPPED];
    b->added = n[ADDED];
    for (i = 0; i < 3; i++) { /* entries defaulted, dropped, converted */
        t = s->boot_counts[i] + (unsigned)n[i + 1u]; /* odg_add_sat_ inline: no call, and a build
                                                       * without the status object links none */
        s->boot_counts[i] = (uint8_t)(t > 255u ? 255u : t);
    }
    if (n[DEFAULTED] || n[DROPPED]) { /* values stored and not served */
        s->boot_seen = (uint8_t)(s->boot_seen | ODG_BOOT_ENTRIES_LOST);
    }
}

/* Boot group `g`: the newest image migrated (stored at once when anything changed), or the
 * defaults stored; then the scrub. When the driver fails on the way, or the image does not
 * read the same a second time: NV_ERROR with the defaults, and no count. */
odg_boot_status_t odg_described_boot_(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g,
                                      odg_boot_t *b)
{
    const odg_group_t *gr = &d->groups[g];
    found_t f;
    uint16_t n[5] = {0, 0, 0, 0, 0}; /* entries KEPT, DEFAULTED, DROPPED, CONVERTED, ADDED */
    odg_boot_status_t st = ODG_BOOT_NV_ERROR;
    int k = newest(d, nv, gr, &f);
    odg_defaults_(d, g); /* the mirror starts from the defaults (RAM only: no NV access) */
    if (k > 0 && (f.h[12] & 1u)) {
        /* the mark of a "load" (0x1011), no counts: also one whose image this firmware cannot
         * read (2: past the NV its driver shows), as its committed header says what it is */
        st = ODG_BOOT_DEFAULTS;
        k = 0;
    } else if (k == 1) {
        if (migrate(d, nv, g, &f, n) == 0 && reads_back(nv, gr, f.at, f.h)) {
            /* LOADED: every stored entry kept (each is matched once at most, so none was
             * defaulted, dropped or converted) and none added */
            st = n[KEPT] != get16(f.h + DESCRIBED_HDR) || n[ADDED] ? ODG_BOOT_MIGRATED : ODG_BOOT_LOADED;
        }
    } else if (k >= 0) { /* 2: the newest image cannot be read: its values are lost */
        st = k == 2 ? ODG_BOOT_DAMAGED : described_no_image(nv, gr);
    }
    /* a migrated image, or the defaults, are stored at once with the A/B commit; so is an image
     * loaded that reaches past the region (after a rollback to a smaller region; its strings
     * may have a larger capacity than this layout's, with nothing cut): it lies in part in the
     * region of a group placed after this one, whose boot would write over it */
    if (st != ODG_BOOT_NV_ERROR &&
        (((st != ODG_BOOT_LOADED || f.at + extent(f.h) > gr->nv_addr + gr->region) &&
          odg_described_store_(d, nv, g, 0) != ODG_OK) ||
         scrub(nv, gr) != 0)) {
        st = ODG_BOOT_NV_ERROR;
    }
    if (st == ODG_BOOT_NV_ERROR) {
        odg_defaults_(d, g);
    } else if (k == 1) {
        count(d->state, b, n);
    }
    return st;
}

#else
typedef int odg_persist_migrate_unused_; /* ISO C: a translation unit declares something */
#endif /* ODG_CFG_PERSIST_MIGRATION */
