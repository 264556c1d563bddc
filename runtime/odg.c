/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg.c - core of the odgen runtime: find, read, write, hooks, PDO mapping check, self-check.
 *
 * C99, no malloc, no stdio. Values are kept in native C types (see odg.h), each at its
 * descriptor's `offset` into the block of its storage class (odg_value_); the wire format is
 * built byte by byte (little-endian), never by copying a native multi-byte integer, so the
 * code is endian-portable. All numeric types share one path: a value is widened to 64 bits,
 * packed to / unpacked from `size` wire bytes, sign-extended for signed types.
 * Build options: -DODG_NO_ABORT_TEXT (odg_abort_text returns ""); the ODG_CFG_* switches of
 * odg.h, set by a dictionary's generated NAME_config.h, leave out what it does not use (each
 * `#if ODG_CFG_...` below), and ODG_LITTLE_ENDIAN copies wire bytes on little-endian targets.
 * Layers above (persistence, the node) attach as odg_client_t: the core calls them through
 * their function pointers and knows nothing else of them.
 */
#include <float.h>
#include <string.h>

#include "odg.h"
#include "odg_impl.h"
#include "odg_persist.h" /* odg_verify checks the groups' NV regions against its slot sizes */

/* Type classes as bit masks over the type code (all codes are below 32). */
#define TBIT(t) ((uint32_t)1u << ((uint32_t)(t) & 31u))
#define T_SIGNED                                                                           \
    (TBIT(ODG_T_INTEGER8) | TBIT(ODG_T_INTEGER16) | TBIT(ODG_T_INTEGER32) |                \
     TBIT(ODG_T_INTEGER24) | TBIT(ODG_T_INTEGER40) | TBIT(ODG_T_INTEGER48) |               \
     TBIT(ODG_T_INTEGER56) | TBIT(ODG_T_INTEGER64))
#define T_REAL (TBIT(ODG_T_REAL32) | TBIT(ODG_T_REAL64))
/* Strings and domains of the types this build serves: 0 when it serves none, so that the
 * compiler drops their code. */
#define T_STREAM                                                                           \
    ((ODG_CFG_STRINGS ? TBIT(ODG_T_VISIBLE_STRING) | TBIT(ODG_T_OCTET_STRING) : 0u) |       \
     (ODG_CFG_UNICODE ? TBIT(ODG_T_UNICODE_STRING) : 0u) | (ODG_CFG_DOMAINS ? TBIT(ODG_T_DOMAIN) : 0u))
#define IS_STREAM(s) ((TBIT((s)->type) & T_STREAM) != 0u)
#define IS_UNICODE(s) (ODG_CFG_UNICODE && (s)->type == ODG_T_UNICODE_STRING)
#define IS_DOMAIN(s) (ODG_CFG_DOMAINS && (s)->type == ODG_T_DOMAIN)
#define IS_COMMAND(s) (ODG_CFG_STORE && ODG_S_CLASS((s)->storage) == ODG_S_STORE)

typedef odg_num_t num_t; /* odg_impl.h: 64 bits, or 32 when no type is wider */
#define NUM_BITS (8u * (uint32_t)sizeof(num_t))
#define SIGN ((num_t)1u << (NUM_BITS - 1u))

#if defined(__GNUC__)
#define ODG_NOINLINE_ __attribute__((noinline))
#else
#define ODG_NOINLINE_
#endif

/* 0x1010 / 0x1011 command words ("save" / "load" read as a little-endian UNSIGNED32). */
#define CMD_SAVE 0x65766173u
#define CMD_LOAD 0x64616F6Cu

/* ---- abort texts ---------------------------------------------------------------- */

#ifndef ODG_NO_ABORT_TEXT
#define ODG_TEXT_(name, text) {name, text},
static const struct {
    uint32_t code;
    const char *text;
} odg_texts[] = {ODG_ABORT_CODES(ODG_TEXT_)};
#undef ODG_TEXT_
#endif

const char *odg_abort_text(odg_abort_t code)
{
#ifndef ODG_NO_ABORT_TEXT
    size_t i;
    for (i = 0; i < sizeof odg_texts / sizeof odg_texts[0]; i++) {
        if (odg_texts[i].code == code) {
            return odg_texts[i].text;
        }
    }
    return "unknown abort code";
#else
    (void)code;
    return "";
#endif
}

/* ---- native values ----------------------------------------------------------------- */

static void *odg_mut_(const void *p)
{
    union {
        const void *c;
        void *m;
    } u;
    u.c = p;
    return u.m;
}

num_t odg_load_(const void *p, uint32_t size)
{
    uint8_t b;
    uint16_t h;
    uint32_t w;
    if (size == 1u) {
        memcpy(&b, p, 1);
        return b;
    }
    if (size == 2u) {
        memcpy(&h, p, 2);
        return h;
    }
#if ODG_CFG_INT64
    if (size > 4u) {
        uint64_t d;
        memcpy(&d, p, 8);
        return d;
    }
#endif
    memcpy(&w, p, 4);
    return w;
}

void odg_store_(void *p, uint32_t size, num_t v)
{
    uint8_t b = (uint8_t)v;
    uint16_t h = (uint16_t)v;
    uint32_t w = (uint32_t)v;
    if (size == 1u) {
        memcpy(p, &b, 1);
    } else if (size == 2u) {
        memcpy(p, &h, 2);
    } else if (!ODG_CFG_INT64 || size <= 4u) {
        memcpy(p, &w, 4);
    } else {
        memcpy(p, &v, sizeof v);
    }
}

/* Where the value of `s` lies: `offset` bytes into the block of its storage class. Not for
 * ODG_S_STORE (no value) or DOMAIN (see dom_of). ROM values are only ever read through it. */
uint8_t *odg_value_(const odg_dict_t *d, const odg_sub_t *s)
{
    uint32_t c = ODG_S_CLASS(s->storage);
    const void *b = c == ODG_S_RAM ? d->ram : d->rom;
#if ODG_CFG_GROUPS
    if (c == ODG_S_PERSIST) {
        b = d->groups[ODG_S_GROUP(s->storage)].mirror;
    }
#endif
    return (uint8_t *)odg_mut_(b) + s->offset;
}

/* The wire bytes of a numeric value (8 bytes; the first `size` count). */
static void pack(const odg_ref_t *r, uint8_t *b)
{
    const odg_sub_t *s = r->sub;
    /* a 0x1010/0x1011 command reads 1: "saves / restores on command" */
    num_t v = 1u;
    unsigned i;
    if (!IS_COMMAND(s)) {
#if ODG_LITTLE_ENDIAN
        /* the wire bytes are the first bytes of the C type that holds the value */
        odg_copy(b, odg_value_(r->dict, s), s->size);
        return;
#else
        v = odg_load_(odg_value_(r->dict, s), s->size);
#endif
    }
    for (i = 0; i < sizeof v; i++, v >>= 8) {
        b[i] = (uint8_t)v;
    }
}

/* The value of `size` wire bytes, sign-extended for signed types. */
static num_t unpack(const odg_sub_t *s, const uint8_t *b)
{
    uint32_t n = s->size;
    num_t v = 0, m;
#if ODG_LITTLE_ENDIAN
    odg_copy(&v, b, n); /* n <= sizeof v: odg_verify and the dictionary's configuration check */
#else
    uint32_t i = n;
    while (i-- > 0u) {
        v = v << 8 | b[i];
    }
#endif
    if (TBIT(s->type) & T_SIGNED) {
        m = (num_t)1u << (8u * n - 1u);
        v = (v ^ m) - m;
    }
    return v;
}

/* An unsigned key that orders values of the sub-entry's type: signed integers with the sign
 * bit flipped; IEEE 754 bits (REAL32 moved to the top 32 bits of a 64-bit num_t) as sign and
 * magnitude turned into an order, -0 as +0. */
static num_t key(const odg_sub_t *s, num_t v)
{
#if ODG_CFG_REAL_LIMITS
    if (TBIT(s->type) & T_REAL) {
        if (v == SIGN) {
            v = 0;
        }
        return (v & SIGN) ? ~v : v | SIGN;
    }
#endif
    return (TBIT(s->type) & T_SIGNED) ? v ^ SIGN : v;
}

/* A limit (its 64-bit pattern) as a key; for REAL32 first rounded to the nearest float. */
static num_t limit_key(const odg_sub_t *s, uint64_t bits)
{
#if ODG_CFG_REAL_LIMITS
    if (s->type == ODG_T_REAL32) {
        double d;
        float f;
        uint32_t w;
        memcpy(&d, &bits, sizeof d);
        f = (float)d; /* odg_verify: REAL32 limits are within the float range */
        memcpy(&w, &f, sizeof w);
        bits = (uint64_t)w << (NUM_BITS - 32u);
    }
#endif
    return key(s, (num_t)bits);
}

/* ---- strings and domains ------------------------------------------------------------- */

/* The descriptor of a DOMAIN: its `offset` indexes dict->domains. */
static const odg_domain_t *dom_of(const odg_ref_t *r)
{
    return &r->dict->domains[r->sub->offset];
}

static uint32_t capacity(const odg_ref_t *r)
{
    return IS_DOMAIN(r->sub) ? dom_of(r)->capacity : r->sub->size;
}

/* The bytes of a string (the uint16_t units of a UNICODE_STRING) or of a domain's buffer. */
static uint8_t *bytes_of(const odg_ref_t *r)
{
    return IS_DOMAIN(r->sub) ? dom_of(r)->data : odg_value_(r->dict, r->sub);
}

uint32_t odg_length(const odg_ref_t *ref)
{
    const odg_sub_t *s = ref->sub;
    uint32_t n = 0, w = IS_UNICODE(s) ? 2u : 1u;
    const uint8_t *p;
    if (IS_DOMAIN(s)) {
        const odg_domain_t *dom = dom_of(ref);
        n = *dom->length;
        return n < dom->capacity ? n : dom->capacity;
    }
    if (!(ODG_CFG_STRINGS && s->type == ODG_T_VISIBLE_STRING) && w == 1u) {
        return s->size; /* numbers, OCTET_STRING, 0x1010/0x1011 commands */
    }
    /* up to the terminating char 0 or uint16_t 0 (both of its bytes 0, in either byte order) */
    p = odg_value_(ref->dict, s);
    while (n + w <= s->size && (p[n] | p[n + w - 1u]) != 0u) {
        n += w;
    }
    return n;
}

/* ---- hooks ------------------------------------------------------------------------ */

/* The layout of a table for bsearch16: row size, and where in a row its uint16_t key lies. */
#define KEYED(type, member) ((uint32_t)(sizeof(type) | offsetof(type, member) << 8))

/* Binary search of `n` rows laid out as KEYED says, sorted by that key: the row holding `key`,
 * or -1. `base` is only used when n > 0 (a table may be NULL when empty). */
static int32_t bsearch16(const void *base, uint32_t layout, uint32_t n, uint16_t key)
{
    uint32_t lo = 0, hi = n;
    while (lo < hi) {
        uint32_t mid = (lo + hi) >> 1;
        const uint8_t *row = (const uint8_t *)base + mid * (layout & 0xFFu);
        uint16_t k = *(const uint16_t *)(const void *)(row + (layout >> 8));
        if (k == key) {
            return (int32_t)mid;
        }
        if (k < key) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    return -1;
}

#if ODG_CFG_HOOKS
static int32_t hook_slot(const odg_dict_t *d, uint16_t sub_pos)
{
    return bsearch16(d->hook_map, KEYED(odg_hook_map_t, sub_pos), d->n_hooks, sub_pos);
}
#endif

static odg_abort_t hook(const odg_ref_t *r, unsigned kind, const void *data, uint32_t len)
{
#if !ODG_CFG_HOOKS
    (void)r;
    (void)kind;
    (void)data;
    (void)len;
    return ODG_OK;
#else
    const odg_dict_t *d = r->dict;
    const odg_hook_slot_t *slot;
    int32_t i;
    if (!(r->sub->attr & ODG_A_HOOK) || (i = hook_slot(d, r->sub_pos)) < 0) {
        return ODG_OK;
    }
    slot = &d->hook_slots[i];
    if (!(d->hook_map[i].kinds & kind) || slot->fn == NULL) {
        return ODG_OK;
    }
    return slot->fn(r, (odg_hook_kind_t)kind, data, len, slot->ctx);
#endif
}

odg_abort_t odg_hook_register(const odg_dict_t *dict, uint16_t index, uint8_t sub, odg_hook_fn fn,
                              void *ctx)
{
    odg_ref_t r;
    int32_t i = -1;
    odg_abort_t ac = odg_find(dict, index, sub, &r);
    if (ac != ODG_OK) {
        return ac;
    }
#if ODG_CFG_HOOKS
    if (r.sub->attr & ODG_A_HOOK) {
        i = hook_slot(dict, r.sub_pos);
    }
#endif
    if (i < 0) {
        return ODG_ABORT_UNSUPPORTED;
    }
    dict->hook_slots[i].fn = NULL;
    dict->hook_slots[i].ctx = ctx;
    dict->hook_slots[i].fn = fn;
    return ODG_OK;
}

/* ---- find ----------------------------------------------------------------------------- */

#if ODG_CFG_HASH
/* The hashed slot of `index` (see odg_dict_t): the entry position it holds. */
static uint32_t hash_slot(const odg_dict_t *d, uint16_t index)
{
    uint32_t h = (uint32_t)index * d->hash_mul, mask = d->hash_mask;
    uint32_t top = h >> d->hash_top_shift, base = h >> d->hash_shift;
    if (d->hash_bits > 8u) {
        const uint16_t *disp = (const uint16_t *)d->hash_disp;
        return ((const uint16_t *)d->hash_slots)[(base ^ disp[top]) & mask];
    }
    return ((const uint8_t *)d->hash_slots)[(base ^ ((const uint8_t *)d->hash_disp)[top]) & mask];
}
#endif

#if ODG_CFG_PACKED
/* Element `sub` (> 0) of a packed ARRAY or RECORD: a descriptor of its own, in the reference.
 * Out of line: the lookup of every other sub-entry pays one bit test for it. */
ODG_NOINLINE_
static odg_abort_t find_element(const odg_dict_t *dict, const odg_entry_t *e, uint8_t sub,
                                odg_ref_t *ref)
{
    uint32_t k = e->first + 1u;
    if (sub > dict->subs[k].sub) {
        return ODG_ABORT_NO_SUB;
    }
    odg_element_(&dict->subs[k], sub, &ref->elem);
    ref->dict = dict;
    ref->entry = e;
    ref->sub = &ref->elem;
    ref->sub_pos = (uint16_t)k;
    return ODG_OK;
}
#endif

/* The sub-entry `sub` of entry `e` into `ref`. */
static inline odg_abort_t find_sub(const odg_dict_t *dict, const odg_entry_t *e, uint8_t sub,
                                   odg_ref_t *ref)
{
    uint32_t k = sub;
#if ODG_CFG_PACKED
    if (sub > 0u && (e->code & ODG_E_PACKED)) {
        return find_element(dict, e, sub, ref);
    }
#endif
    if (!(e->code & ODG_E_DENSE)) {
        for (k = 0; k < e->count && dict->subs[e->first + k].sub != sub; k++) {
        }
    }
    if (k >= e->count) {
        return ODG_ABORT_NO_SUB;
    }
    k += e->first;
    ref->dict = dict;
    ref->entry = e;
    ref->sub = &dict->subs[k];
    ref->sub_pos = (uint16_t)k;
    return ODG_OK;
}

/* odg_find without a perfect hash: the generated find or a binary search. Kept out of odg_find
 * so that the hashed path makes no call (and saves no registers). */
#if ODG_CFG_HASH
ODG_NOINLINE_
#endif
static odg_abort_t find_unhashed(const odg_dict_t *dict, uint16_t index, uint8_t sub,
                                 odg_ref_t *ref)
{
    int32_t i = dict->find ? dict->find(index)
                           : bsearch16(dict->entries, KEYED(odg_entry_t, index), dict->n_entries,
                                       index);
    return i < 0 ? ODG_ABORT_NO_OBJECT : find_sub(dict, &dict->entries[i], sub, ref);
}

odg_abort_t odg_find(const odg_dict_t *dict, uint16_t index, uint8_t sub, odg_ref_t *ref)
{
#if ODG_CFG_HASH
    const odg_entry_t *e;
    if (!ODG_CFG_UNHASHED || dict->hash_slots != NULL) {
        e = &dict->entries[hash_slot(dict, index)];
        return e->index != index ? ODG_ABORT_NO_OBJECT : find_sub(dict, e, sub, ref);
    }
#endif
    return find_unhashed(dict, index, sub, ref);
}

/* ---- read ------------------------------------------------------------------------------ */

odg_abort_t odg_read(const odg_ref_t *ref, uint32_t offset, void *buf, uint32_t cap, uint32_t *n)
{
    const odg_sub_t *s = ref->sub;
    uint8_t tmp[8], *out = (uint8_t *)buf;
    const uint8_t *src = tmp;
    uint32_t len, i;
    odg_abort_t ac;
    *n = 0;
    if (!(s->attr & ODG_A_READ)) {
        return ODG_ABORT_WRITE_ONLY;
    }
    if (offset == 0u && (ac = hook(ref, ODG_HOOK_PRE_READ, NULL, 0)) != ODG_OK) {
        return ac;
    }
    len = odg_length(ref);
    if (IS_STREAM(s)) {
        src = bytes_of(ref);
    } else {
        pack(ref, tmp);
    }
    if (offset > len) {
        offset = len;
    }
    len -= offset;
    if (len > cap) {
        len = cap;
    }
    if (!IS_UNICODE(s)) {
        odg_copy(out, src + offset, len); /* a loop here would become a call of libc memcpy */
    }
    for (i = 0; IS_UNICODE(s) && i < len; i++) {
        uint32_t k = offset + i;
        out[i] = (uint8_t)(((const uint16_t *)(const void *)src)[k >> 1] >> ((k & 1u) * 8u));
    }
    *n = len;
    return ODG_OK;
}

/* ---- write --------------------------------------------------------------------------------- */

/* Access and length of a download of `len` bytes at `off` of a `total`-byte value. */
static odg_abort_t wcheck(const odg_ref_t *r, uint32_t off, uint32_t len, uint32_t total)
{
    const odg_sub_t *s = r->sub;
    uint32_t c = capacity(r);
    if (!(s->attr & ODG_A_WRITE) || ODG_S_CLASS(s->storage) == ODG_S_ROM) {
        return ODG_ABORT_READ_ONLY;
    }
    if (total > c || off > total || len > total - off) {
        return ODG_ABORT_TOO_LONG;
    }
    if (total < c && (s->type == ODG_T_OCTET_STRING || !IS_STREAM(s))) {
        return ODG_ABORT_TOO_SHORT;
    }
    if (IS_UNICODE(s) && (total & 1u)) {
        return ODG_ABORT_TYPE_LENGTH;
    }
    return ODG_OK;
}

/* Position in dict->limits of the limits of the sub-entry at `pos` (binary search), or -1. */
static int32_t limit_of(const odg_dict_t *d, uint16_t pos)
{
    return bsearch16(d->limits, KEYED(odg_limit_t, sub_pos), d->n_limits, pos);
}

/* Infinity's bits as num_t (REAL32 in the top 32 bits); anything above is NaN. */
#define INF32 ((num_t)0x7F800000u << (NUM_BITS - 32u))
#if ODG_CFG_INT64
#define INF64 ((num_t)0x7FF0000000000000u)
#else
#define INF64 INF32 /* no REAL64 */
#endif

/* Range of a numeric value (sign-extended; REAL as its bits). */
static odg_abort_t check(const odg_ref_t *r, num_t v)
{
    const odg_sub_t *s = r->sub;
    const odg_limit_t *l;
    int32_t i;
    if (s->type == ODG_T_BOOLEAN && v > 1u) {
        return ODG_ABORT_VALUE_RANGE;
    }
    if (!(ODG_CFG_LIMITS || ODG_CFG_REAL_LIMITS) || !(s->attr & ODG_A_LIMIT) ||
        (i = limit_of(r->dict, r->sub_pos)) < 0) {
        return ODG_OK; /* odg_verify: every ODG_A_LIMIT entry has its limits */
    }
    l = &r->dict->limits[i];
#if ODG_CFG_REAL_LIMITS
    if (s->type == ODG_T_REAL32) {
        v <<= NUM_BITS - 32u;
    }
    if ((TBIT(s->type) & T_REAL) && (v & ~SIGN) > (s->type == ODG_T_REAL32 ? INF32 : INF64)) {
        return ODG_ABORT_VALUE_RANGE; /* NaN */
    }
#endif
    v = key(s, v);
    if (v > limit_key(s, l->high)) {
        return ODG_ABORT_VALUE_HIGH;
    }
    return v < limit_key(s, l->low) ? ODG_ABORT_VALUE_LOW : ODG_OK;
}

/* The range check of a write, for the persistence layer's restored values. */
odg_abort_t odg_check_(const odg_dict_t *d, uint16_t pos, num_t v)
{
    odg_ref_t r;
    r.dict = d;
    r.entry = NULL;
    r.sub = &d->subs[pos];
    r.sub_pos = pos;
    return check(&r, v);
}

/* ---- clients ------------------------------------------------------------------------------ */

void odg_attach(const odg_dict_t *dict, odg_client_t *client)
{
    odg_client_t **p = &dict->state->clients;
    while (*p != NULL && *p != client) {
        p = &(*p)->next;
    }
    if (*p == NULL) {
        client->next = NULL;
        *p = client;
    }
}

void odg_changed(const odg_dict_t *dict, const odg_ref_t *ref)
{
    odg_client_t *c;
    for (c = dict->state->clients; c != NULL; c = c->next) {
        if (c->changed != NULL) {
            c->changed(c, ref);
        }
    }
}

/* The client that answers 0x1010/0x1011 commands, or NULL. */
static odg_client_t *storage(const odg_dict_t *d)
{
    odg_client_t *c = d->state->clients;
    while (c != NULL && c->command == NULL) {
        c = c->next;
    }
    return c;
}

/* Store `len` wire bytes at wire offset `off` of a string or domain. */
static void put(const odg_ref_t *r, uint32_t off, const uint8_t *b, uint32_t len)
{
    uint8_t *dst = bytes_of(r);
    uint32_t i;
    for (i = 0; i < len; i++, off++) {
        if (IS_UNICODE(r->sub)) {
            uint16_t *u = (uint16_t *)(void *)dst + (off >> 1);
            unsigned sh = (off & 1u) * 8u;
            *u = (uint16_t)((*u & ~(0xFFu << sh)) | ((unsigned)b[i] << sh));
        } else {
            dst[off] = b[i];
        }
    }
}

/* A string or domain of `total` bytes is complete: set its length, then POST_WRITE. */
static odg_abort_t finish(const odg_ref_t *r, uint32_t total)
{
    const odg_sub_t *s = r->sub;
    if (IS_DOMAIN(s)) {
        *dom_of(r)->length = total;
    } else if (s->type != ODG_T_OCTET_STRING) {
        /* clear the rest: char[size + 1] or uint16_t[size / 2 + 1] */
        uint32_t w = IS_UNICODE(s) ? 2u : 1u;
        memset(odg_value_(r->dict, s) + total, 0, s->size + w - total);
    }
    odg_changed(r->dict, r);
    return hook(r, ODG_HOOK_POST_WRITE, NULL, 0);
}

odg_abort_t odg_write(const odg_ref_t *ref, const void *buf, uint32_t len)
{
    const odg_sub_t *s = ref->sub;
    const uint8_t *b = (const uint8_t *)buf;
    num_t v;
    odg_abort_t ac = wcheck(ref, 0, len, len);
    if (ac != ODG_OK) {
        return ac;
    }
    if (IS_STREAM(s)) {
        if ((ac = hook(ref, ODG_HOOK_PRE_WRITE, buf, len)) != ODG_OK) {
            return ac;
        }
        put(ref, 0, b, len);
        return finish(ref, len);
    }
    v = unpack(s, b);
    if (IS_COMMAND(s)) {
        ac = (v == ((s->storage & ODG_S_RESTORE_FLAG) ? CMD_LOAD : CMD_SAVE) && storage(ref->dict))
                 ? ODG_OK
                 : ODG_ABORT_DATA_STORE;
    } else {
        ac = check(ref, v);
    }
    if (ac != ODG_OK || (ac = hook(ref, ODG_HOOK_PRE_WRITE, buf, len)) != ODG_OK) {
        return ac;
    }
    if (IS_COMMAND(s)) {
        odg_client_t *c = storage(ref->dict);
        if (c == NULL) {
            return ODG_ABORT_DATA_STORE; /* the PRE_WRITE hook detached it */
        }
        ac = c->command(c, ref->dict, s->sub, (s->storage & ODG_S_RESTORE_FLAG) != 0u);
        if (ac != ODG_OK) {
            return ac;
        }
    } else {
        odg_store_(odg_value_(ref->dict, s), s->size, v);
        odg_changed(ref->dict, ref);
    }
    return hook(ref, ODG_HOOK_POST_WRITE, NULL, 0);
}

odg_abort_t odg_write_part(const odg_ref_t *ref, uint32_t offset, const void *buf, uint32_t len,
                           uint32_t total)
{
    const odg_sub_t *s = ref->sub;
    odg_abort_t ac;
    if (!IS_STREAM(s)) {
        /* numbers are written whole: the SDO layer assembles the (at most 8) bytes */
        if (offset == 0u && len == total) {
            return odg_write(ref, buf, len);
        }
        ac = wcheck(ref, 0, total, total);
        return ac != ODG_OK ? ac : ODG_ABORT_UNSUPPORTED;
    }
    if ((ac = wcheck(ref, offset, len, total)) != ODG_OK) {
        return ac;
    }
    if (offset == 0u && (ac = hook(ref, ODG_HOOK_PRE_WRITE, NULL, total)) != ODG_OK) {
        return ac;
    }
    put(ref, offset, (const uint8_t *)buf, len);
    return offset + len == total ? finish(ref, total) : ODG_OK;
}

/* ---- PDO mapping ----------------------------------------------------------------------- */

odg_abort_t odg_check_mapping(const odg_dict_t *dict, uint32_t mapping, uint8_t direction,
                              odg_ref_t *ref)
{
    odg_ref_t tmp;
    uint32_t bits = mapping & 0xFFu;
    odg_abort_t ac;
    if (ref == NULL) {
        ref = &tmp;
    }
    ac = odg_find(dict, (uint16_t)(mapping >> 16), (uint8_t)(mapping >> 8), ref);
    if (ac != ODG_OK) {
        return ac;
    }
    if (!(ref->sub->attr & direction & (ODG_A_TPDO | ODG_A_RPDO))) {
        return ODG_ABORT_NOT_MAPPABLE;
    }
    if (bits != 8u * ref->sub->size && !(ref->sub->type == ODG_T_BOOLEAN && bits == 1u)) {
        return ODG_ABORT_NOT_MAPPABLE; /* as CANopenNode: a length that does not fit the object */
    }
    return ODG_OK;
}

/* ---- init -------------------------------------------------------------------------------- */

odg_abort_t odg_init(const odg_dict_t *dict, uint8_t node_id)
{
    if (dict == NULL || dict->state == NULL) {
        return ODG_ABORT_NO_DICTIONARY;
    }
    /* the generated reset reads the node-id from the state */
    dict->state->node_id = node_id;
    dict->state->clients = NULL;
    /* no stored values yet: every group runs on defaults until odg_persist_init */
    dict->state->boot_seen = (uint8_t)(dict->n_groups > 0u ? 1u << ODG_BOOT_NV_ERROR : 0u);
    if (dict->reset) {
        dict->reset(dict);
    }
    return ODG_OK;
}

void odg_copy(void *dst, const void *src, uint32_t n)
{
    uint8_t *d = (uint8_t *)dst;
    const uint8_t *s = (const uint8_t *)src;
    while (n-- > 0u) {
        *d++ = *s++;
    }
}

/* ---- typed access ---------------------------------------------------------------------------- */

/* The number at index/sub whose C type is `size` bytes: `ref` filled, its value's address. */
static odg_abort_t typed(const odg_dict_t *d, uint16_t index, uint8_t sub, uint32_t size,
                         odg_ref_t *r)
{
    uint32_t n;
    odg_abort_t ac = odg_find(d, index, sub, r);
    if (ac != ODG_OK) {
        return ac;
    }
    n = r->sub->size;
    if (IS_STREAM(r->sub) || ODG_S_CLASS(r->sub->storage) == ODG_S_STORE ||
        size != (n <= 2u ? n : (n <= 4u ? 4u : 8u))) {
        return ODG_ABORT_TYPE_LENGTH;
    }
    return ODG_OK;
}

odg_abort_t odg_get(const odg_dict_t *dict, uint16_t index, uint8_t sub, void *value,
                    uint32_t size)
{
    odg_ref_t r;
    odg_abort_t ac = typed(dict, index, sub, size, &r);
    if (ac == ODG_OK) {
        odg_copy(value, odg_value_(dict, r.sub), size);
    }
    return ac;
}

odg_abort_t odg_set(const odg_dict_t *dict, uint16_t index, uint8_t sub, const void *value,
                    uint32_t size)
{
    odg_ref_t r;
    odg_abort_t ac = typed(dict, index, sub, size, &r);
    if (ac == ODG_OK && ODG_S_CLASS(r.sub->storage) == ODG_S_ROM) {
        ac = ODG_ABORT_READ_ONLY;
    }
    if (ac == ODG_OK) {
        odg_copy(odg_value_(dict, r.sub), value, size);
        odg_changed(dict, &r);
    }
    return ac;
}

void *odg_ptr(const odg_dict_t *dict, uint16_t index, uint8_t sub, uint32_t size)
{
    odg_ref_t r;
    if (typed(dict, index, sub, size, &r) != ODG_OK || ODG_S_CLASS(r.sub->storage) == ODG_S_ROM) {
        return NULL;
    }
    return odg_value_(dict, r.sub);
}

/* ---- self-check ------------------------------------------------------------------------------ */

/* Wire size by type code; 0 for strings and domains, 0xFF for codes that are not basic types. */
static const uint8_t wire_size[0x1C] = {
    0xFF, 1, 1, 2, 4, 1, 2, 4, 4, 0, 0, 0, 6, 6, 0xFF, 0,
    3,    8, 5, 6, 7, 8, 3, 0xFF, 5, 6, 7, 8};

/* Alignment of the C type that holds each type (see odg.h), 1 where there is none. Generated
 * blocks are structs, so a value lies at its member's offset and is aligned for its type. */
typedef struct { char c; uint16_t v; } al16_t;
typedef struct { char c; uint32_t v; } al32_t;
typedef struct { char c; uint64_t v; } al64_t;
typedef struct { char c; float v; } alf_t;
typedef struct { char c; double v; } ald_t;
#define A16 offsetof(al16_t, v)
#define A32 offsetof(al32_t, v)
#define A64 offsetof(al64_t, v)
static const uint8_t type_align[0x1C] = {
    1,   1, 1, A16, A32, 1, A16, A32, offsetof(alf_t, v), 1, 1, A16, A64, A64, 1, 1,
    A32, offsetof(ald_t, v), A64, A64, A64, A64, A32, 1, A64, A64, A64, A64};

static int in_object(const void *p, uint32_t len, const void *base, uint32_t size)
{
    uintptr_t a = (uintptr_t)p, b = (uintptr_t)base;
    return a >= b && a - b <= size && len <= size - (uint32_t)(a - b);
}

static double as_double(uint64_t bits)
{
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
}

/* REAL32 limits are converted to float: finite within the float range, or infinite. */
static int float_range(double x)
{
    return (x >= -FLT_MAX && x <= FLT_MAX) || x > DBL_MAX || x < -DBL_MAX;
}

static int limits_ordered(const odg_sub_t *s, const odg_limit_t *l)
{
    if (TBIT(s->type) & T_REAL) {
        double lo = as_double(l->low), hi = as_double(l->high);
        if (!(lo <= hi) || (s->type == ODG_T_REAL32 && !(float_range(lo) && float_range(hi)))) {
            return 0; /* reversed, NaN, or beyond the float range */
        }
    }
    return limit_key(s, l->low) <= limit_key(s, l->high);
}

/* The sign-extended value of a native numeric value at `p`. */
static num_t native_value(const odg_sub_t *s, const void *p)
{
    uint8_t b[8];
    uint64_t v = odg_load_(p, s->size);
    unsigned i;
    for (i = 0; i < 8u; i++, v >>= 8) {
        b[i] = (uint8_t)v;
    }
    return unpack(s, b);
}

/* Whether this build of the runtime serves the sub-entry's type, storage, hooks and limits
 * (the ODG_CFG_* switches of odg.h). */
static int configured(const odg_sub_t *s)
{
    uint32_t m = TBIT(s->type), cls = ODG_S_CLASS(s->storage);
    if ((!ODG_CFG_INT64 && wire_size[s->type] > 4u) ||
        (!ODG_CFG_STRINGS && (s->type == ODG_T_VISIBLE_STRING || s->type == ODG_T_OCTET_STRING)) ||
        (!ODG_CFG_UNICODE && s->type == ODG_T_UNICODE_STRING) ||
        (!ODG_CFG_DOMAINS && s->type == ODG_T_DOMAIN) ||
        (!ODG_CFG_GROUPS && cls == ODG_S_PERSIST) || (!ODG_CFG_STORE && cls == ODG_S_STORE) ||
        (!ODG_CFG_HOOKS && (s->attr & ODG_A_HOOK))) {
        return 0;
    }
    return !(s->attr & ODG_A_LIMIT) || ((m & T_REAL) ? ODG_CFG_REAL_LIMITS : ODG_CFG_LIMITS);
}

static int sub_ok(const odg_ref_t *r)
{
    const odg_dict_t *d = r->dict;
    const odg_sub_t *s = r->sub;
    uint32_t cls = ODG_S_CLASS(s->storage), m = TBIT(s->type), n;
    const odg_group_t *g = NULL;
    int32_t li;
    const void *base = cls == ODG_S_ROM ? d->rom : d->ram;
    const uint8_t *value;
    if (s->type >= sizeof wire_size || wire_size[s->type] == 0xFFu || (s->attr & 0x80u) ||
        !configured(s)) {
        return 0;
    }
    if (cls == ODG_S_STORE) {
        return s->type == ODG_T_UNSIGNED32 && s->size == 4u && s->offset == 0u &&
               !(s->attr & (ODG_A_NODEID | ODG_A_LIMIT)) && !(s->storage & 0x7Cu);
    }
    if ((cls != ODG_S_PERSIST && s->storage > 3u) ||
        (cls == ODG_S_ROM && (s->attr & (ODG_A_WRITE | ODG_A_NODEID))) ||
        ((m & T_STREAM) && (s->attr & (ODG_A_NODEID | ODG_A_LIMIT)))) {
        return 0;
    }
    /* the limits (the table is sorted by now, so the binary search is valid) */
    if ((s->attr & ODG_A_LIMIT) &&
        ((li = limit_of(d, r->sub_pos)) < 0 || !limits_ordered(s, &d->limits[li]))) {
        return 0;
    }
    if (cls == ODG_S_PERSIST) {
        if (ODG_S_GROUP(s->storage) >= d->n_groups) {
            return 0;
        }
        g = &d->groups[ODG_S_GROUP(s->storage)];
        base = g->defaults != NULL ? g->mirror : NULL;
    }
    /* first where the value lies, before reading anything there */
    if (s->type == ODG_T_DOMAIN) {
        const odg_domain_t *dom;
        if (s->offset >= d->n_domains) {
            return 0;
        }
        dom = &d->domains[s->offset];
        if (dom->data == NULL || dom->length == NULL || dom->capacity < s->size ||
            (g != NULL && (!in_object(dom->data, dom->capacity, g->mirror, g->size) ||
                           !in_object(dom->length, 4u, g->mirror, g->size)))) {
            return 0;
        }
        return *dom->length <= dom->capacity;
    }
    if (m & T_STREAM) {
        if (s->type == ODG_T_UNICODE_STRING && (s->size & 1u)) {
            return 0;
        }
        n = s->type == ODG_T_OCTET_STRING ? s->size
                                          : s->size + (s->type == ODG_T_UNICODE_STRING ? 2u : 1u);
    } else {
        n = s->size <= 2u ? s->size : (s->size <= 4u ? 4u : 8u);
        if (s->size != wire_size[s->type] || ((s->attr & ODG_A_NODEID) && (m & T_REAL))) {
            return 0;
        }
    }
    if (base == NULL || (g != NULL && (uint32_t)s->offset + n > g->size)) {
        return 0; /* no block, or beyond the group's struct */
    }
    value = (const uint8_t *)base + s->offset;
    if (((uintptr_t)value & (type_align[s->type] - 1u)) != 0u) {
        return 0; /* not where a struct member of its C type could lie */
    }
    /* then the value itself (and for a persisted number the FLASH default, too) */
    if (s->type == ODG_T_VISIBLE_STRING) {
        return value[s->size] == 0u;
    }
    if (s->type == ODG_T_UNICODE_STRING) {
        return ((const uint16_t *)(const void *)value)[s->size / 2u] == 0u;
    }
    if (m & T_STREAM) {
        return 1;
    }
    if (g != NULL &&
        check(r, native_value(s, (const uint8_t *)g->defaults + s->offset)) != ODG_OK) {
        return 0;
    }
    return check(r, native_value(s, value)) == ODG_OK;
}

/* Index of the entry holding sub position `pos` (for error reports). */
static uint16_t owner(const odg_dict_t *d, uint32_t pos)
{
    uint32_t i;
    for (i = 0; i < d->n_entries; i++) {
        if (pos >= d->entries[i].first && pos - d->entries[i].first < d->entries[i].count) {
            return d->entries[i].index;
        }
    }
    return 0xFFFFu;
}

/* A table of `n` rows laid out as KEYED says, keyed by sub position: strictly increasing, each
 * naming a sub-entry that has `attr`. */
static int pos_table_ok(const odg_dict_t *d, const void *base, uint32_t layout, uint32_t n,
                        unsigned attr, uint16_t *bad_index)
{
    uint32_t i, prev = 0;
    for (i = 0; i < n; i++) {
        const uint8_t *row = (const uint8_t *)base + i * (layout & 0xFFu);
        uint32_t pos = *(const uint16_t *)(const void *)(row + (layout >> 8));
        if (pos >= d->n_subs || !(d->subs[pos].attr & attr) || (i > 0u && pos <= prev)) {
            *bad_index = owner(d, pos);
            return 0;
        }
        prev = pos;
    }
    return 1;
}

/* A packed ARRAY or RECORD (ODG_E_PACKED): sub 0, then one descriptor of N >= 1 numbers without hooks,
 * limits or $NODEID, whose last element lies where a value may. */
static int packed_ok(const odg_dict_t *d, const odg_entry_t *e)
{
    const odg_sub_t *s = &d->subs[e->first + 1u];
    odg_ref_t r;
    if (!(e->code & ODG_E_PACKED)) {
        return 1;
    }
    if (!ODG_CFG_PACKED || e->count != 2u ||
        ((e->code & 0x0Fu) != ODG_OBJ_ARRAY && (e->code & 0x0Fu) != ODG_OBJ_RECORD) ||
        d->subs[e->first].sub != 0u || s->sub == 0u || ODG_S_CLASS(s->storage) == ODG_S_STORE ||
        (s->attr & (ODG_A_HOOK | ODG_A_LIMIT | ODG_A_NODEID)) || s->type == ODG_T_VISIBLE_STRING ||
        s->type == ODG_T_OCTET_STRING || s->type == ODG_T_UNICODE_STRING || s->type == ODG_T_DOMAIN) {
        return 0;
    }
    r.dict = d;
    r.entry = e;
    r.sub_pos = (uint16_t)(e->first + 1u);
    r.sub = &r.elem;
    odg_element_(s, s->sub, &r.elem);
    return (uint32_t)s->offset + (s->sub - 1u) * ODG_STRIDE(s->size) <= 0xFFFFu && sub_ok(&r);
}

/* NV bytes group `g` uses: its region, or two "ODG1" slots without a layout descriptor. */
static uint32_t nv_len(const odg_group_t *g)
{
    return g->n_layout != 0u ? g->region : 2u * ODG_PERSIST_SLOT_SIZE(g->size);
}

/* A group with a layout descriptor has n_layout persisted sub-entries (the records the runtime
 * reads from the tables), of the types this build migrates, and its image fits a slot (half the
 * region); one without is served by this build. */
static int layout_ok(const odg_dict_t *d, uint8_t gi)
{
    const odg_group_t *g = &d->groups[gi];
    uint32_t e, p, k, n = 0, bytes = 2u;
    if (g->n_layout == 0u) {
        return ODG_CFG_PERSIST_ODG1;
    }
    if (!ODG_CFG_PERSIST_MIGRATION) {
        return 0;
    }
    for (e = 0; e < d->n_entries; e++) {
        const odg_entry_t *en = &d->entries[e];
        for (p = en->first; p < (uint32_t)en->first + en->count; p++) {
            const odg_sub_t *s = &d->subs[p];
            if (s->storage != (uint8_t)(ODG_S_PERSIST | (unsigned)gi << 2)) {
                continue;
            }
            if (!ODG_CFG_PERSIST_STREAMS && IS_STREAM(s)) {
                return 0;
            }
            /* each element of a packed ARRAY is a record */
            k = (en->code & ODG_E_PACKED) && p > en->first ? s->sub : 1u;
            bytes += k * (6u + s->size + (s->type == ODG_T_DOMAIN ? 4u : 0u));
            n += k;
        }
    }
    return n == g->n_layout && bytes + ODG_PERSIST_HEADER2_SIZE <= g->region / 2u;
}

/* A generated find or hash finds entry `e` (at its first sub-entry), and rejects the index
 * after it when that is absent. */
static int found_alone(const odg_dict_t *d, const odg_entry_t *e)
{
    odg_ref_t r;
    uint16_t next = (uint16_t)(e->index + 1u);
    if (odg_find(d, e->index, d->subs[e->first].sub, &r) != ODG_OK || r.entry != e) {
        return 0;
    }
    return e->index == 0xFFFFu || (e + 1 < d->entries + d->n_entries && e[1].index == next) ||
           odg_find(d, next, 0, &r) == ODG_ABORT_NO_OBJECT;
}

/* The perfect hash's shape, and every slot naming an entry (so a lookup never reads past it). */
static int hash_ok(const odg_dict_t *d)
{
    uint32_t k, n;
    if (d->hash_disp == NULL || d->hash_bits == 0u || d->hash_bits > 16u) {
        return 0;
    }
    n = (uint32_t)1u << d->hash_bits; /* 1u has 16 bits where int has */
    if (d->hash_top_shift == 0u || d->hash_top_shift < d->hash_bits ||
        d->hash_shift != d->hash_top_shift - d->hash_bits || d->hash_mask != n - 1u) {
        return 0;
    }
    for (k = 0; k < n; k++) {
        uint32_t pos = d->hash_bits > 8u ? ((const uint16_t *)d->hash_slots)[k]
                                         : ((const uint8_t *)d->hash_slots)[k];
        if (pos >= d->n_entries) {
            return 0;
        }
    }
    return 1;
}

odg_abort_t odg_verify(const odg_dict_t *dict, uint16_t *bad_index)
{
    uint16_t dummy;
    uint32_t i, k, next = 0, hooked = 0;
    const odg_dict_t *d = dict;
    if (bad_index == NULL) {
        bad_index = &dummy;
    }
    *bad_index = 0xFFFFu; /* table-wide faults */
    if (d == NULL || d->entries == NULL || d->subs == NULL || d->state == NULL ||
        (d->n_hooks && (d->hook_map == NULL || d->hook_slots == NULL)) ||
        (d->n_limits && d->limits == NULL) || (d->n_domains && d->domains == NULL) ||
        (d->n_groups && d->groups == NULL)) {
        return ODG_ABORT_INTERNAL;
    }
    /* the tables searched by sub position: sorted, and only for subs with the attribute (that
     * every ODG_A_LIMIT sub has limits is checked with the sub, the hooks by count below) */
    if (!pos_table_ok(d, d->limits, KEYED(odg_limit_t, sub_pos), d->n_limits, ODG_A_LIMIT,
                      bad_index) ||
        !pos_table_ok(d, d->hook_map, KEYED(odg_hook_map_t, sub_pos), d->n_hooks, ODG_A_HOOK,
                      bad_index)) {
        return ODG_ABORT_INTERNAL;
    }
    if (d->hash_slots != NULL ? !ODG_CFG_HASH || !hash_ok(d) : !ODG_CFG_UNHASHED) {
        return ODG_ABORT_INTERNAL; /* a bad hash, or a lookup this build does not serve */
    }
    if (!ODG_CFG_PERSIST_STATUS && d->persist_status != 0u) {
        return ODG_ABORT_INTERNAL; /* a boot status object this build would not set */
    }
    for (i = 0; i < d->n_entries; i++) {
        const odg_entry_t *e = &d->entries[i];
        *bad_index = e->index;
        if ((i > 0u && e->index <= e[-1].index) || e->first != next || e->count == 0u ||
            (uint32_t)e->first + e->count > d->n_subs) {
            return ODG_ABORT_INTERNAL;
        }
        if (!packed_ok(d, e)) {
            return ODG_ABORT_INTERNAL;
        }
        for (k = 0; k < e->count; k++) {
            odg_ref_t r;
            r.dict = d;
            r.entry = e;
            r.sub_pos = (uint16_t)(e->first + k);
            r.sub = &d->subs[r.sub_pos];
            if ((k > 0u && r.sub->sub <= r.sub[-1].sub) ||
                ((e->code & ODG_E_DENSE) && r.sub->sub != k && !(e->code & ODG_E_PACKED)) ||
                !sub_ok(&r)) {
                return ODG_ABORT_INTERNAL;
            }
            hooked += (r.sub->attr & ODG_A_HOOK) ? 1u : 0u;
        }
        next += e->count;
    }
    *bad_index = 0xFFFFu;
    if (next != d->n_subs || hooked != d->n_hooks) {
        return ODG_ABORT_INTERNAL;
    }
    /* the generated find or hash, once every entry is known sound (a lookup reads its subs) */
    for (i = 0; i < d->n_entries && (d->find != NULL || d->hash_slots != NULL); i++) {
        if (!found_alone(d, &d->entries[i])) {
            *bad_index = d->entries[i].index;
            return ODG_ABORT_INTERNAL;
        }
    }
    *bad_index = 0xFFFFu;
    for (i = 0; i < d->n_hooks; i++) {
        if (d->hook_map[i].kinds == 0u || (d->hook_map[i].kinds & ~7u)) {
            *bad_index = owner(d, d->hook_map[i].sub_pos);
            return ODG_ABORT_INTERNAL;
        }
    }
    for (i = 0; i < d->n_groups; i++) {
        const odg_group_t *g = &d->groups[i];
        uint32_t len;
        if (g->mirror == NULL || g->defaults == NULL || g->size == 0u ||
            g->size > 0x7FFFFFF0u - 2u * ODG_PERSIST_HEADER_SIZE - 2u * ODG_PERSIST_ALIGN ||
            g->nv_addr > 0xFFFFFFFFu - (len = nv_len(g)) || !layout_ok(d, (uint8_t)i)) {
            return ODG_ABORT_INTERNAL;
        }
        for (k = 0; k < i; k++) {
            const odg_group_t *h = &d->groups[k];
            if (g->nv_addr < h->nv_addr + nv_len(h) && h->nv_addr < g->nv_addr + len) {
                return ODG_ABORT_INTERNAL;
            }
        }
    }
    *bad_index = 0;
    return ODG_OK;
}
