/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg.c - core of the odgen runtime: find, read, write, hooks, PDO mapping check (the
 * self-check of a dictionary's tables is odg_verify.c).
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
#include <string.h>

#include "odg.h"
#include "odg_impl.h"
#include "odg_persist.h" /* odg_init marks the groups NV_ERROR until the persistence layer boots them */

#define IS_UNICODE(s) (ODG_CFG_UNICODE && (s)->type == ODG_T_UNICODE_STRING)
#define IS_DOMAIN(s) (ODG_CFG_DOMAINS && (s)->type == ODG_T_DOMAIN)
#define IS_COMMAND(s) (ODG_CFG_COMMAND && ODG_S_CLASS((s)->storage) == ODG_S_COMMAND)

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

num_t odg_num_get_(const void *p, uint32_t size)
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

void odg_num_put_(void *p, uint32_t size, num_t v)
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
 * ODG_S_COMMAND (no value) or DOMAIN (see dom_of). ROM values are only ever read through it. */
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
        v = odg_num_get_(odg_value_(r->dict, s), s->size);
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
    if (ODG_CFG_HASH_WIDE && d->hash_bits > 8u) { /* a build without such tables keeps fewer
                                                   * values in registers */
        const uint16_t *disp = (const uint16_t *)d->hash_disp;
        return ((const uint16_t *)d->hash_slots)[(base ^ disp[top]) & mask];
    }
    return ((const uint8_t *)d->hash_slots)[(base ^ ((const uint8_t *)d->hash_disp)[top]) & mask];
}
#endif

/* Position of sub-index `sub` among entry `e`'s descriptors (from e->first); e->count and
 * above when absent. */
static inline uint32_t sub_index(const odg_dict_t *dict, const odg_entry_t *e, uint8_t sub)
{
    uint32_t k = sub;
    if (!(e->code & ODG_E_DENSE)) {
        for (k = 0; k < e->count && dict->subs[e->first + k].sub != sub; k++) {
        }
    }
    return k;
}

#if ODG_CFG_SHARED
const odg_sub_t *odg_sub_at_(const odg_dict_t *d, const odg_entry_t *e, uint32_t pos,
                             odg_sub_t *copy)
{
    const odg_sub_t *s = &d->subs[pos];
    if (!(e->code & ODG_E_SHARED)) {
        return s;
    }
    *copy = *s;
    copy->offset = (uint16_t)(s->offset + (uint32_t)e->index * (uint32_t)(s->size >> 8));
    copy->size = (uint16_t)(s->size & 0xFFu);
    return copy;
}
#endif

#if ODG_CFG_PACKED
/* Element `sub` (> 0) of a packed ARRAY or RECORD: a descriptor of its own, in the reference
 * (made from the member's copy of the shared descriptor in a shared run). Out of line: the
 * lookup of every other sub-entry pays one bit test for it. */
ODG_NOINLINE_
static odg_abort_t find_element(const odg_dict_t *dict, const odg_entry_t *e, uint8_t sub,
                                odg_ref_t *ref)
{
    uint32_t k = e->first + 1u;
    if (sub > dict->subs[k].sub) {
        return ODG_ABORT_NO_SUB;
    }
    odg_element_(odg_sub_at_(dict, e, k, &ref->elem), sub, &ref->elem);
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
    uint32_t k;
#if ODG_CFG_PACKED
    if (sub > 0u && (e->code & ODG_E_PACKED)) {
        return find_element(dict, e, sub, ref);
    }
#endif
    k = sub_index(dict, e, sub);
    if (k >= e->count) {
        return ODG_ABORT_NO_SUB;
    }
    k += e->first;
    ref->dict = dict;
    ref->entry = e;
    ref->sub = &dict->subs[k];
    ref->sub_pos = (uint16_t)k;
#if ODG_CFG_SHARED
    if (e->code & ODG_E_SHARED) { /* a member of a shared run: a copy, out of line */
        ref->sub = odg_sub_at_(dict, e, k, &ref->elem);
    }
#endif
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
        odg_num_put_(odg_value_(ref->dict, s), s->size, v);
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
    dict->state->node_id = node_id;
    dict->state->clients = NULL;
    /* no stored values yet: every group runs on defaults until odg_persist_init */
    dict->state->boot_seen = (uint8_t)(dict->n_groups > 0u ? 1u << ODG_BOOT_NV_ERROR : 0u);
    if (dict->reset) {
        dict->reset(dict);
        odg_add_node_id_(dict, ODG_ALL_STORAGE_);
    }
    return ODG_OK;
}

/* One loop for every dictionary instead of a statement per $NODEID value in each generated
 * reset: smaller as soon as the persistence layer links it for a group's defaults. */
void odg_add_node_id_(const odg_dict_t *d, unsigned storage)
{
    const odg_entry_t *e;
    odg_sub_t m;
    uint32_t p;
    for (e = d->entries; e < d->entries + d->n_entries; e++) {
        for (p = e->first; p < (uint32_t)e->first + e->count; p++) {
            const odg_sub_t *s = odg_sub_at_(d, e, p, &m); /* each member of a shared run */
            if ((s->attr & ODG_A_NODEID) && (storage == ODG_ALL_STORAGE_ || s->storage == storage)) {
                uint8_t *v = odg_value_(d, s);
                odg_num_put_(v, s->size, odg_num_get_(v, s->size) + d->state->node_id);
            }
        }
    }
}

void odg_copy(void *dst, const void *src, uint32_t n)
{
    uint8_t *d = (uint8_t *)dst;
    const uint8_t *s = (const uint8_t *)src;
    while (n-- > 0u) {
        *d++ = *s++;
    }
}

void odg_group_reset(const odg_group_t *g)
{
    odg_group_defaults(g, 0, g->size, g->mirror);
}

void odg_group_defaults(const odg_group_t *g, uint32_t from, uint32_t n, void *dst)
{
    const uint16_t *r = g->spread;
    const uint8_t *v = (const uint8_t *)g->defaults;
    uint8_t *p = (uint8_t *)dst;
    uint32_t k;
    for (k = 0; k < n; k++) {
        p[k] = 0;
    }
    for (; r[1] != 0u; r += 2) { /* each run, its bytes from v on */
        for (k = r[0]; k < r[1]; k++, v++) {
            if (k - from < n) {
                p[k - from] = *v;
            }
        }
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
    if (IS_STREAM(r->sub) || ODG_S_CLASS(r->sub->storage) == ODG_S_COMMAND ||
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

/* ---- what the self-check (odg_verify.c) shares; left out of a firmware that does not call it */

num_t odg_limit_key_(const odg_sub_t *s, uint64_t bits)
{
    return limit_key(s, bits);
}

int32_t odg_limit_of_(const odg_dict_t *d, uint16_t pos)
{
    return limit_of(d, pos);
}
