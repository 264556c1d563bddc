/*
 * odg.c - core of the odgen runtime: find, read, write, hooks, PDO mapping check, self-check.
 *
 * C99, no malloc, no stdio. Values are kept in native C types (see odg.h); the wire format is
 * built byte by byte (little-endian), never by copying a native multi-byte integer, so the
 * code is endian-portable. All numeric types share one path: a value is widened to 64 bits,
 * packed to / unpacked from `size` wire bytes, sign-extended for signed types.
 * Build options: -DODG_NO_ABORT_TEXT (odg_abort_text returns ""), -DODG_NO_PERSIST (no
 * odg_persist.c: 0x1010/0x1011 abort with DATA_STORE, odg_init ignores `nv`).
 */
#include <float.h>
#include <string.h>

#include "odg.h"
#include "odg_impl.h"

/* Type classes as bit masks over the type code (all codes are below 32). */
#define TBIT(t) ((uint32_t)1u << ((uint32_t)(t) & 31u))
#define T_SIGNED                                                                           \
    (TBIT(ODG_T_INTEGER8) | TBIT(ODG_T_INTEGER16) | TBIT(ODG_T_INTEGER32) |                \
     TBIT(ODG_T_INTEGER24) | TBIT(ODG_T_INTEGER40) | TBIT(ODG_T_INTEGER48) |               \
     TBIT(ODG_T_INTEGER56) | TBIT(ODG_T_INTEGER64))
#define T_REAL (TBIT(ODG_T_REAL32) | TBIT(ODG_T_REAL64))
#define T_STREAM                                                                           \
    (TBIT(ODG_T_VISIBLE_STRING) | TBIT(ODG_T_OCTET_STRING) | TBIT(ODG_T_UNICODE_STRING) |  \
     TBIT(ODG_T_DOMAIN))
#define IS_STREAM(s) ((TBIT((s)->type) & T_STREAM) != 0u)

/* 0x1010 / 0x1011 command words ("save" / "load" read as a little-endian UNSIGNED32). */
#define CMD_SAVE 0x65766173u
#define CMD_LOAD 0x64616F6Cu

/* ---- abort texts ---------------------------------------------------------------- */

#ifndef ODG_NO_ABORT_TEXT
#define ODG_TEXT_(name, code, text) {code, text},
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

void *odg_mut_(const void *p)
{
    union {
        const void *c;
        void *m;
    } u;
    u.c = p;
    return u.m;
}

uint64_t odg_load_(const void *p, uint32_t size)
{
    uint8_t b;
    uint16_t h;
    uint32_t w;
    uint64_t d;
    if (size == 1u) {
        memcpy(&b, p, 1);
        return b;
    }
    if (size == 2u) {
        memcpy(&h, p, 2);
        return h;
    }
    if (size <= 4u) {
        memcpy(&w, p, 4);
        return w;
    }
    memcpy(&d, p, 8);
    return d;
}

void odg_store_(void *p, uint32_t size, uint64_t v)
{
    uint8_t b = (uint8_t)v;
    uint16_t h = (uint16_t)v;
    uint32_t w = (uint32_t)v;
    if (size == 1u) {
        memcpy(p, &b, 1);
    } else if (size == 2u) {
        memcpy(p, &h, 2);
    } else if (size <= 4u) {
        memcpy(p, &w, 4);
    } else {
        memcpy(p, &v, 8);
    }
}

/* The wire bytes of a numeric value (8 bytes; the first `size` count). */
static void pack(const odg_sub_t *s, uint8_t *b)
{
    /* a 0x1010/0x1011 command reads 1: "saves / restores on command" */
    uint64_t v = ODG_S_CLASS(s->storage) == ODG_S_STORE ? 1u : odg_load_(s->data, s->size);
    unsigned i;
    for (i = 0; i < 8u; i++, v >>= 8) {
        b[i] = (uint8_t)v;
    }
}

/* The value of `size` wire bytes, sign-extended to 64 bits for signed types. */
static uint64_t unpack(const odg_sub_t *s, const uint8_t *b)
{
    uint32_t i = s->size;
    uint64_t v = (TBIT(s->type) & T_SIGNED) && (b[i - 1u] & 0x80u) ? ~(uint64_t)0 : 0u;
    while (i-- > 0u) {
        v = v << 8 | b[i];
    }
    return v;
}

#define SIGN64 ((uint64_t)1u << 63)

/* An unsigned key that orders values of the sub-entry's type: signed integers with the sign
 * bit flipped; IEEE 754 bits (REAL32 moved to the top 32 bits) as sign and magnitude turned
 * into an order, -0 as +0. */
static uint64_t key(const odg_sub_t *s, uint64_t v)
{
    if (!(TBIT(s->type) & T_REAL)) {
        return (TBIT(s->type) & T_SIGNED) ? v ^ SIGN64 : v;
    }
    if (v == SIGN64) {
        v = 0;
    }
    return (v & SIGN64) ? ~v : v | SIGN64;
}

/* A limit (double bits) as a key; for REAL32 first rounded to the nearest float. */
static uint64_t limit_key(const odg_sub_t *s, uint64_t bits)
{
    if (s->type == ODG_T_REAL32) {
        double d;
        float f;
        uint32_t w;
        memcpy(&d, &bits, sizeof d);
        f = (float)d; /* odg_verify: REAL32 limits are within the float range */
        memcpy(&w, &f, sizeof w);
        bits = (uint64_t)w << 32;
    }
    return key(s, bits);
}

/* ---- strings and domains ------------------------------------------------------------- */

static const odg_domain_t *dom_of(const odg_sub_t *s)
{
    return (const odg_domain_t *)s->data;
}

static uint32_t capacity(const odg_sub_t *s)
{
    return s->type == ODG_T_DOMAIN ? dom_of(s)->capacity : s->size;
}

static uint8_t *bytes_of(const odg_sub_t *s)
{
    return s->type == ODG_T_DOMAIN ? dom_of(s)->data : (uint8_t *)odg_mut_(s->data);
}

uint32_t odg_length(const odg_ref_t *ref)
{
    const odg_sub_t *s = ref->sub;
    uint32_t n = 0;
    if (s->type == ODG_T_VISIBLE_STRING) {
        const char *c = (const char *)s->data;
        while (n < s->size && c[n] != 0) {
            n++;
        }
    } else if (s->type == ODG_T_UNICODE_STRING) {
        const uint16_t *u = (const uint16_t *)s->data;
        while (2u * n + 1u < s->size && u[n] != 0u) {
            n++;
        }
        n *= 2u;
    } else if (s->type == ODG_T_DOMAIN) {
        n = *dom_of(s)->length;
        if (n > dom_of(s)->capacity) {
            n = dom_of(s)->capacity;
        }
    } else {
        n = s->size; /* numbers, OCTET_STRING, 0x1010/0x1011 commands */
    }
    return n;
}

/* ---- hooks ------------------------------------------------------------------------ */

/* Binary search of a table whose rows start with a sorted uint16_t key. */
static int32_t bsearch16(const void *base, uint32_t stride, uint32_t n, uint16_t key)
{
    uint32_t lo = 0, hi = n;
    while (lo < hi) {
        uint32_t mid = (lo + hi) >> 1;
        uint16_t k = *(const uint16_t *)(const void *)((const uint8_t *)base + mid * stride);
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

static int32_t hook_slot(const odg_dict_t *d, uint16_t sub_pos)
{
    return bsearch16(d->hook_map, sizeof *d->hook_map, d->n_hooks, sub_pos);
}

static odg_abort_t hook(const odg_ref_t *r, unsigned kind, const void *data, uint32_t len)
{
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
}

odg_abort_t odg_hook_register(const odg_dict_t *dict, uint16_t index, uint8_t sub, odg_hook_fn fn,
                              void *ctx)
{
    odg_ref_t r;
    int32_t i;
    odg_abort_t ac = odg_find(dict, index, sub, &r);
    if (ac != ODG_OK) {
        return ac;
    }
    if (!(r.sub->attr & ODG_A_HOOK) || (i = hook_slot(dict, r.sub_pos)) < 0) {
        return ODG_ABORT_UNSUPPORTED;
    }
    dict->hook_slots[i].fn = NULL;
    dict->hook_slots[i].ctx = ctx;
    dict->hook_slots[i].fn = fn;
    return ODG_OK;
}

/* ---- find ----------------------------------------------------------------------------- */

odg_abort_t odg_find(const odg_dict_t *dict, uint16_t index, uint8_t sub, odg_ref_t *ref)
{
    const odg_entry_t *e;
    uint32_t p, end;
    int32_t i = dict->find ? dict->find(index)
                           : bsearch16(dict->entries, sizeof *dict->entries, dict->n_entries, index);
    if (i < 0) {
        return ODG_ABORT_NO_OBJECT;
    }
    e = &dict->entries[i];
    p = e->first;
    end = p + e->count;
    if (e->code & ODG_E_DENSE) {
        p += sub;
    } else {
        while (p < end && dict->subs[p].sub != sub) {
            p++;
        }
    }
    if (p >= end) {
        return ODG_ABORT_NO_SUB;
    }
    ref->dict = dict;
    ref->entry = e;
    ref->sub = &dict->subs[p];
    ref->sub_pos = (uint16_t)p;
    return ODG_OK;
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
        src = bytes_of(s);
    } else {
        pack(s, tmp);
    }
    if (offset > len) {
        offset = len;
    }
    len -= offset;
    if (len > cap) {
        len = cap;
    }
    for (i = 0; i < len; i++) {
        uint32_t k = offset + i;
        out[i] = s->type == ODG_T_UNICODE_STRING
                     ? (uint8_t)(((const uint16_t *)s->data)[k >> 1] >> ((k & 1u) * 8u))
                     : src[k];
    }
    *n = len;
    return ODG_OK;
}

/* ---- write --------------------------------------------------------------------------------- */

/* Access and length of a download of `len` bytes at `off` of a `total`-byte value. */
static odg_abort_t wcheck(const odg_sub_t *s, uint32_t off, uint32_t len, uint32_t total)
{
    uint32_t c = capacity(s);
    if (!(s->attr & ODG_A_WRITE) || ODG_S_CLASS(s->storage) == ODG_S_ROM) {
        return ODG_ABORT_READ_ONLY;
    }
    if (total > c || off > total || len > total - off) {
        return ODG_ABORT_TOO_LONG;
    }
    if (total < c && (s->type == ODG_T_OCTET_STRING || !IS_STREAM(s))) {
        return ODG_ABORT_TOO_SHORT;
    }
    if (s->type == ODG_T_UNICODE_STRING && (total & 1u)) {
        return ODG_ABORT_TYPE_LENGTH;
    }
    return ODG_OK;
}

/* Range of a numeric value (sign-extended; REAL as its bits). */
static odg_abort_t check(const odg_dict_t *d, const odg_sub_t *s, uint64_t v)
{
    const odg_limit_t *l;
    if (s->type == ODG_T_BOOLEAN && v > 1u) {
        return ODG_ABORT_VALUE_RANGE;
    }
    if (!(s->attr & ODG_A_LIMIT)) {
        return ODG_OK;
    }
    l = &d->limits[s->limit];
    if (s->type == ODG_T_REAL32) {
        v <<= 32;
    }
    if ((TBIT(s->type) & T_REAL) &&
        (v & ~SIGN64) > (s->type == ODG_T_REAL32 ? 0x7F80000000000000u : 0x7FF0000000000000u)) {
        return ODG_ABORT_VALUE_RANGE; /* NaN */
    }
    v = key(s, v);
    if (v > limit_key(s, l->high)) {
        return ODG_ABORT_VALUE_HIGH;
    }
    return v < limit_key(s, l->low) ? ODG_ABORT_VALUE_LOW : ODG_OK;
}

/* 0x1010 / 0x1011 after the command word was checked: `sub` 1 acts on every group, another
 * on the groups with that store_sub. */
static odg_abort_t command(const odg_ref_t *r)
{
    const odg_dict_t *d = r->dict;
    int restore = (r->sub->storage & ODG_S_RESTORE_FLAG) != 0;
    odg_abort_t ac = ODG_ABORT_DATA_STORE; /* also when no group matches */
#ifndef ODG_NO_PERSIST
    uint8_t g;
    for (g = 0; g < d->n_groups; g++) {
        if (r->sub->sub == 1u || d->groups[g].store_sub == r->sub->sub) {
            ac = restore ? odg_persist_restore(d, g) : odg_persist_store(d, g);
            if (ac != ODG_OK) {
                break;
            }
        }
    }
#else
    (void)d;
    (void)restore;
#endif
    return ac;
}

/* Store `len` wire bytes at wire offset `off` of a string or domain. */
static void put(const odg_sub_t *s, uint32_t off, const uint8_t *b, uint32_t len)
{
    uint8_t *dst = bytes_of(s);
    uint32_t i;
    for (i = 0; i < len; i++, off++) {
        if (s->type == ODG_T_UNICODE_STRING) {
            uint16_t *u = (uint16_t *)odg_mut_(s->data) + (off >> 1);
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
    if (s->type == ODG_T_DOMAIN) {
        *dom_of(s)->length = total;
    } else if (s->type != ODG_T_OCTET_STRING) {
        /* clear the rest: char[size + 1] or uint16_t[size / 2 + 1] */
        uint32_t w = s->type == ODG_T_UNICODE_STRING ? 2u : 1u;
        memset((uint8_t *)odg_mut_(s->data) + total, 0, s->size + w - total);
    }
    return hook(r, ODG_HOOK_POST_WRITE, NULL, 0);
}

odg_abort_t odg_write(const odg_ref_t *ref, const void *buf, uint32_t len)
{
    const odg_sub_t *s = ref->sub;
    const uint8_t *b = (const uint8_t *)buf;
    uint64_t v;
    odg_abort_t ac = wcheck(s, 0, len, len);
    if (ac != ODG_OK) {
        return ac;
    }
    if (IS_STREAM(s)) {
        if ((ac = hook(ref, ODG_HOOK_PRE_WRITE, buf, len)) != ODG_OK) {
            return ac;
        }
        put(s, 0, b, len);
        return finish(ref, len);
    }
    v = unpack(s, b);
    if (ODG_S_CLASS(s->storage) == ODG_S_STORE) {
        ac = (v == ((s->storage & ODG_S_RESTORE_FLAG) ? CMD_LOAD : CMD_SAVE) && ref->dict->state->nv)
                 ? ODG_OK
                 : ODG_ABORT_DATA_STORE;
    } else {
        ac = check(ref->dict, s, v);
    }
    if (ac != ODG_OK || (ac = hook(ref, ODG_HOOK_PRE_WRITE, buf, len)) != ODG_OK) {
        return ac;
    }
    if (ODG_S_CLASS(s->storage) == ODG_S_STORE) {
        if ((ac = command(ref)) != ODG_OK) {
            return ac;
        }
    } else {
        odg_store_(odg_mut_(s->data), s->size, v);
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
        ac = wcheck(s, 0, total, total);
        return ac != ODG_OK ? ac : ODG_ABORT_UNSUPPORTED;
    }
    if ((ac = wcheck(s, offset, len, total)) != ODG_OK) {
        return ac;
    }
    if (offset == 0u && (ac = hook(ref, ODG_HOOK_PRE_WRITE, NULL, total)) != ODG_OK) {
        return ac;
    }
    put(s, offset, (const uint8_t *)buf, len);
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

odg_abort_t odg_init(const odg_dict_t *dict, uint8_t node_id, const odg_nv_driver_t *nv,
                     odg_boot_status_t *boot)
{
    uint8_t g;
    if (dict == NULL || dict->state == NULL) {
        return ODG_ABORT_NO_DICTIONARY;
    }
    /* the generated reset reads the node-id from the state, and stores need the driver */
    dict->state->node_id = node_id;
#ifdef ODG_NO_PERSIST
    nv = NULL;
#endif
    dict->state->nv = nv;
    if (dict->reset) {
        dict->reset(dict);
    }
#ifndef ODG_NO_PERSIST
    if (nv != NULL) {
        return odg_persist_boot(dict, nv, boot);
    }
#endif
    for (g = 0; boot != NULL && g < dict->n_groups; g++) {
        boot[g] = ODG_BOOT_NV_ERROR; /* no driver: defaults in RAM, NV untouched */
    }
    return ODG_OK;
}

/* ---- self-check ------------------------------------------------------------------------------ */

/* Wire size by type code; 0 for strings and domains, 0xFF for codes that are not basic types. */
static const uint8_t wire_size[0x1C] = {
    0xFF, 1, 1, 2, 4, 1, 2, 4, 4, 0, 0, 0, 6, 6, 0xFF, 0,
    3,    8, 5, 6, 7, 8, 3, 0xFF, 5, 6, 7, 8};

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
static uint64_t native_value(const odg_sub_t *s, const void *p)
{
    uint8_t b[8];
    uint64_t v = odg_load_(p, s->size);
    unsigned i;
    for (i = 0; i < 8u; i++, v >>= 8) {
        b[i] = (uint8_t)v;
    }
    return unpack(s, b);
}

static int sub_ok(const odg_dict_t *d, const odg_sub_t *s)
{
    uint32_t cls = ODG_S_CLASS(s->storage), m = TBIT(s->type), n;
    const odg_domain_t *dom = dom_of(s);
    const void *value = s->data;
    if (s->type >= sizeof wire_size || wire_size[s->type] == 0xFFu || (s->attr & 0x80u)) {
        return 0;
    }
    if (cls == ODG_S_STORE) {
        return s->type == ODG_T_UNSIGNED32 && s->size == 4u && s->data == NULL &&
               !(s->attr & (ODG_A_NODEID | ODG_A_LIMIT)) && !(s->storage & 0x7Cu);
    }
    if (s->data == NULL || (cls != ODG_S_PERSIST && s->storage > 3u) ||
        (cls == ODG_S_ROM && (s->attr & (ODG_A_WRITE | ODG_A_NODEID)))) {
        return 0;
    }
    /* first where the value lies (`n` bytes at `value`), before reading anything there */
    if (m & T_STREAM) {
        if (s->attr & (ODG_A_NODEID | ODG_A_LIMIT) ||
            (s->type == ODG_T_UNICODE_STRING && (s->size & 1u))) {
            return 0;
        }
        n = s->type == ODG_T_OCTET_STRING ? s->size
                                          : s->size + (s->type == ODG_T_UNICODE_STRING ? 2u : 1u);
        if (s->type == ODG_T_DOMAIN) {
            if (dom->data == NULL || dom->length == NULL || dom->capacity < s->size) {
                return 0;
            }
            value = dom->data;
            n = dom->capacity;
        }
    } else {
        n = s->size <= 2u ? s->size : (s->size <= 4u ? 4u : 8u);
        if (s->size != wire_size[s->type] || ((s->attr & ODG_A_NODEID) && (m & T_REAL)) ||
            ((s->attr & ODG_A_LIMIT) && d->limits == NULL)) {
            return 0;
        }
    }
    if (cls == ODG_S_PERSIST) {
        const odg_group_t *g;
        if (ODG_S_GROUP(s->storage) >= d->n_groups) {
            return 0;
        }
        g = &d->groups[ODG_S_GROUP(s->storage)];
        if (!in_object(value, n, g->mirror, g->size) ||
            (s->type == ODG_T_DOMAIN && !in_object(dom->length, 4u, g->mirror, g->size))) {
            return 0;
        }
        if (!(m & T_STREAM)) { /* the default in the FLASH copy must be in range, too */
            const uint8_t *def = (const uint8_t *)g->defaults +
                                 ((uintptr_t)s->data - (uintptr_t)g->mirror);
            if (check(d, s, native_value(s, def)) != ODG_OK) {
                return 0;
            }
        }
    }
    /* then the value itself */
    if (s->type == ODG_T_VISIBLE_STRING) {
        return ((const char *)s->data)[s->size] == 0;
    }
    if (s->type == ODG_T_UNICODE_STRING) {
        return ((const uint16_t *)s->data)[s->size / 2u] == 0u;
    }
    if (s->type == ODG_T_DOMAIN) {
        return *dom->length <= dom->capacity;
    }
    if (m & T_STREAM) {
        return 1;
    }
    if ((s->attr & ODG_A_LIMIT) && !limits_ordered(s, &d->limits[s->limit])) {
        return 0;
    }
    return check(d, s, native_value(s, s->data)) == ODG_OK;
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
        (d->n_groups && d->groups == NULL)) {
        return ODG_ABORT_INTERNAL;
    }
    for (i = 0; i < d->n_entries; i++) {
        const odg_entry_t *e = &d->entries[i];
        *bad_index = e->index;
        if ((i > 0u && e->index <= e[-1].index) || e->first != next || e->count == 0u ||
            (uint32_t)e->first + e->count > d->n_subs) {
            return ODG_ABORT_INTERNAL;
        }
        if (d->find != NULL &&
            (d->find(e->index) != (int32_t)i ||
             (e->index < 0xFFFFu && (i + 1u == d->n_entries || e[1].index != e->index + 1u) &&
              d->find((uint16_t)(e->index + 1u)) >= 0))) {
            return ODG_ABORT_INTERNAL;
        }
        for (k = 0; k < e->count; k++) {
            const odg_sub_t *s = &d->subs[e->first + k];
            if ((k > 0u && s->sub <= s[-1].sub) || ((e->code & ODG_E_DENSE) && s->sub != k) ||
                !sub_ok(d, s)) {
                return ODG_ABORT_INTERNAL;
            }
            hooked += (s->attr & ODG_A_HOOK) ? 1u : 0u;
        }
        next += e->count;
    }
    *bad_index = 0xFFFFu;
    if (next != d->n_subs || hooked != d->n_hooks) {
        return ODG_ABORT_INTERNAL;
    }
    for (i = 0; i < d->n_hooks; i++) {
        uint16_t pos = d->hook_map[i].sub_pos;
        *bad_index = owner(d, pos);
        if (pos >= d->n_subs || !(d->subs[pos].attr & ODG_A_HOOK) ||
            (i > 0u && pos <= d->hook_map[i - 1u].sub_pos) || d->hook_map[i].kinds == 0u ||
            (d->hook_map[i].kinds & ~7u)) {
            return ODG_ABORT_INTERNAL;
        }
    }
    *bad_index = 0xFFFFu;
    for (i = 0; i < d->n_groups; i++) {
        const odg_group_t *g = &d->groups[i];
        uint32_t len = 2u * ODG_PERSIST_SLOT_SIZE(g->size);
        if (g->mirror == NULL || g->defaults == NULL || g->size == 0u ||
            g->size > 0x7FFFFFF0u - 2u * ODG_PERSIST_HEADER_SIZE - 2u * ODG_PERSIST_ALIGN ||
            g->nv_addr > 0xFFFFFFFFu - len) {
            return ODG_ABORT_INTERNAL;
        }
        for (k = 0; k < i; k++) {
            const odg_group_t *h = &d->groups[k];
            if (g->nv_addr < h->nv_addr + 2u * ODG_PERSIST_SLOT_SIZE(h->size) &&
                h->nv_addr < g->nv_addr + len) {
                return ODG_ABORT_INTERNAL;
            }
        }
    }
    *bad_index = 0;
    return ODG_OK;
}
