/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_verify.c - the self-check of a dictionary's tables (odg_verify, odg.h): what the core
 * (odg.c) relies on without checking at run time. Called by the generated self-test and by
 * firmware that wants the check at boot; a firmware that does not call it links none of it.
 */
#include <float.h>
#include <stddef.h>
#include <string.h>

#include "odg_impl.h"
#include "odg_persist.h" /* the groups' NV regions are checked against its slot sizes */


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
    return odg_limit_key_(s, l->low) <= odg_limit_key_(s, l->high);
}

/* The sign-extended value of a native numeric value at `p`. */
static odg_num_t native_value(const odg_sub_t *s, const void *p)
{
    odg_num_t v = odg_num_get_(p, s->size), m;
    if (TBIT(s->type) & T_SIGNED) {
        m = (odg_num_t)1u << (8u * s->size - 1u);
        v = (v ^ m) - m;
    }
    return v;
}

/* Whether the runs of group `g`'s defaults lie in its mirror, in order, each of some bytes,
 * with their bytes in `defaults` when there is one. */
static int spread_ok(const odg_group_t *g)
{
    const uint16_t *r = g->spread;
    uint32_t end = 0;
    if (r == NULL) {
        return 0;
    }
    for (; r[1] != 0u; r += 2) {
        if (r[0] < end || r[1] <= r[0] || r[1] > g->size) {
            return 0;
        }
        end = r[1];
    }
    return r[0] == 0u && (end == 0u || g->defaults != NULL);
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
        (!ODG_CFG_GROUPS && cls == ODG_S_PERSIST) || (!ODG_CFG_COMMAND && cls == ODG_S_COMMAND) ||
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
    if (cls == ODG_S_COMMAND) {
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
        ((li = odg_limit_of_(d, r->sub_pos)) < 0 || !limits_ordered(s, &d->limits[li]))) {
        return 0;
    }
    if (cls == ODG_S_PERSIST) {
        if (ODG_S_GROUP(s->storage) >= d->n_groups) {
            return 0;
        }
        g = &d->groups[ODG_S_GROUP(s->storage)];
        base = g->mirror; /* its defaults are NULL when every one is zero (no runs: spread_ok) */
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
    if (g != NULL) {
        odg_num_t def[8u / sizeof(odg_num_t)]; /* the FLASH default: a number's bytes, at most 8 */
        if (!spread_ok(g)) {
            return 0;
        }
        odg_group_defaults(g, s->offset, n, def);
        if (odg_check_(d, r->sub_pos, native_value(s, def)) != ODG_OK) {
            return 0;
        }
    }
    return odg_check_(d, r->sub_pos, native_value(s, value)) == ODG_OK;
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
 * limits or $NODEID, whose last element lies where a value may (or N "save" or "load" commands). */
static int packed_ok(const odg_dict_t *d, const odg_entry_t *e)
{
    odg_sub_t m;
    const odg_sub_t *s = odg_sub_at_(d, e, e->first + 1u, &m); /* of a shared run's member: its own */
    odg_ref_t r;
    if (!(e->code & ODG_E_PACKED)) {
        return 1;
    }
    if (!ODG_CFG_PACKED || e->count != 2u ||
        ((e->code & 0x0Fu) != ODG_OBJ_ARRAY && (e->code & 0x0Fu) != ODG_OBJ_RECORD) ||
        d->subs[e->first].sub != 0u || s->sub == 0u ||
        (s->attr & (ODG_A_HOOK | ODG_A_LIMIT | ODG_A_NODEID)) || s->type == ODG_T_VISIBLE_STRING ||
        s->type == ODG_T_OCTET_STRING || s->type == ODG_T_UNICODE_STRING || s->type == ODG_T_DOMAIN) {
        return 0;
    }
    r.dict = d;
    r.entry = e;
    r.sub_pos = (uint16_t)(e->first + 1u);
    r.sub = &r.elem;
    odg_element_(s, s->sub, &r.elem);
    if (ODG_S_CLASS(s->storage) == ODG_S_COMMAND) {
        r.sub = s; /* "save" or "load" commands: no value, the shared descriptor is checked */
    }
    return (uint32_t)s->offset + (s->sub - 1u) * ODG_STRIDE(s->size) <= 0xFFFFu && sub_ok(&r);
}

/* A shared run's list (ODG_E_SHARED): numbers without hooks, limits or commands, each member's
 * value apart from the next's (where each member's value lies is checked with each sub-entry:
 * sub_ok). */
static int shared_ok(const odg_dict_t *d, const odg_entry_t *e)
{
    const odg_sub_t *s;
    uint32_t p;
    if (!ODG_CFG_SHARED) {
        return 0;
    }
    for (p = e->first; p < (uint32_t)e->first + e->count; p++) {
        s = &d->subs[p];
        if ((s->attr & (ODG_A_HOOK | ODG_A_LIMIT)) || ODG_S_CLASS(s->storage) == ODG_S_COMMAND ||
            s->type >= sizeof wire_size || wire_size[s->type] == 0u || (s->size & 0xFFu) > 8u ||
            (uint32_t)(s->size >> 8) < ODG_STRIDE(s->size & 0xFFu)) { /* values would overlap */
            return 0;
        }
    }
    return 1;
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
            odg_sub_t m;
            const odg_sub_t *s = odg_sub_at_(d, en, p, &m); /* a shared run's: its own size */
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
    if (d->hash_disp == NULL || d->hash_bits == 0u || d->hash_bits > (ODG_CFG_HASH_WIDE ? 16u : 8u)) {
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
    if (!ODG_CFG_PERSIST_TWO_PASS && ODG_CFG_PERSIST_MIGRATION && d->n_groups > 1u) {
        return ODG_ABORT_INTERNAL; /* groups this build would boot in one pass */
    }
    for (i = 0; i < d->n_entries; i++) {
        const odg_entry_t *e = &d->entries[i];
        /* a later member of a shared run: the list of the member before, at the next index */
        int shared = (e->code & ODG_E_SHARED) != 0u;
        int later = shared && i > 0u && (e[-1].code & ODG_E_SHARED) && e[-1].first == e->first;
        *bad_index = e->index;
        if ((i > 0u && e->index <= e[-1].index) || (!later && e->first != next) ||
            (later && (e->count != e[-1].count || e->code != e[-1].code ||
                       e->index != e[-1].index + 1u)) ||
            e->count == 0u || (uint32_t)e->first + e->count > d->n_subs) {
            return ODG_ABORT_INTERNAL;
        }
        if (!packed_ok(d, e) || (shared && !shared_ok(d, e))) {
            return ODG_ABORT_INTERNAL;
        }
        for (k = 0; k < e->count; k++) {
            odg_ref_t r;
            r.dict = d;
            r.entry = e;
            r.sub_pos = (uint16_t)(e->first + k);
            r.sub = odg_sub_at_(d, e, r.sub_pos, &r.elem);
            if ((k > 0u && r.sub->sub <= d->subs[r.sub_pos - 1u].sub) ||
                ((e->code & ODG_E_DENSE) && r.sub->sub != k && !(e->code & ODG_E_PACKED)) ||
                !sub_ok(&r)) {
                return ODG_ABORT_INTERNAL;
            }
            hooked += (r.sub->attr & ODG_A_HOOK) ? 1u : 0u;
        }
        next += later ? 0u : e->count;
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
        if (g->mirror == NULL || !spread_ok(g) || g->size == 0u ||
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
