/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_impl.h - internal helpers shared by the core (odg.c), its self-check (odg_verify.c) and
 * the persistence layer (odg_persist*.c). Not part of the API.
 */
#ifndef ODG_IMPL_H
#define ODG_IMPL_H

#include "odg.h"

/* Numbers on the way between wire and storage: 64 bits, or 32 when no type is wider. */
#if ODG_CFG_INT64
typedef uint64_t odg_num_t;
#else
typedef uint32_t odg_num_t;
#endif

/* Type classes as bit masks over the type code (all codes are below 32), for the core and its
 * self-check. */
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
/* A key packing a table row's size and the offset of its 16-bit key member (bsearch16 in odg.c). */
#define KEYED(type, member) ((uint32_t)(sizeof(type) | offsetof(type, member) << 8))

/* The UNSIGNED32 whose little-endian bytes (CANopen's wire order) start at `p`, read byte by
 * byte: any alignment, any byte order. A macro, as -Os would call a function, not inline it. */
#define ODG_LE32(p) \
    ((uint32_t)(p)[0] | (uint32_t)(p)[1] << 8 | (uint32_t)(p)[2] << 16 | (uint32_t)(p)[3] << 24)

/* `v` as the little-endian bytes of an UNSIGNED32 from `p` on, written byte by byte (ODG_LE32
 * reads them back): any alignment, any byte order. */
static inline void odg_put_le32_(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

/* Native value of a numeric sub-entry of wire size `size` (1..8, 1..4 without ODG_CFG_INT64),
 * zero-extended from its C type (uint8_t, uint16_t, uint32_t for 3..4, uint64_t for 5..8;
 * float/double as bits). */
odg_num_t odg_num_get_(const void *p, uint32_t size);

/* Put the low bytes of `v` into the C type that holds a value of wire size `size`. */
void odg_num_put_(void *p, uint32_t size, odg_num_t v);

/* The names before (for one release): "store" and "load" are the 0x1010 / 0x1011 commands. */
#define odg_load_ odg_num_get_
#define odg_store_ odg_num_put_

/* Where the value of `s` lies: `s->offset` bytes into dict->rom, dict->ram or the mirror of
 * its group, by its storage class. Not for ODG_S_COMMAND subs (no value) nor DOMAINs (whose
 * offset indexes dict->domains). Writable except for ODG_S_ROM, which is only ever read. */
uint8_t *odg_value_(const odg_dict_t *d, const odg_sub_t *s);

/* Add the node-id to the $NODEID values (ODG_A_NODEID) of storage class `storage` (a
 * descriptor's `storage` byte), or of all with ODG_ALL_STORAGE_: after a reset to defaults. */
#define ODG_ALL_STORAGE_ 0x100u
void odg_add_node_id_(const odg_dict_t *d, unsigned storage);

/* The range check of a write (BOOLEAN 0/1, NaN, limits) for the numeric sub-entry at position
 * `pos` of dict->subs, on its value sign-extended to 64 bits (REAL as its bits). */
odg_abort_t odg_check_(const odg_dict_t *d, uint16_t pos, odg_num_t v);

/* For the self-check (odg_verify.c): a limit (its 64-bit pattern) as the key the range check
 * orders values of the sub-entry's type by; the position in dict->limits of the limits of the
 * sub-entry at `pos`, or -1. */
odg_num_t odg_limit_key_(const odg_sub_t *s, uint64_t bits);
int32_t odg_limit_of_(const odg_dict_t *d, uint16_t pos);

/* Element `k` (1..N) of a packed ARRAY whose shared descriptor is `s`: its own descriptor. */
static inline void odg_element_(const odg_sub_t *s, uint8_t k, odg_sub_t *out)
{
    *out = *s;
    out->sub = k;
    out->offset = (uint16_t)(s->offset + (uint32_t)(k - 1u) * ODG_STRIDE(s->size));
}

/* The descriptor at position `pos` (first .. first + count - 1) of entry `e` as that entry
 * holds it: dict->subs[pos], or for a member of a shared run (ODG_E_SHARED) a copy in `copy`
 * with the member's offset. Walks over the entries take each sub-entry through it. */
#if ODG_CFG_SHARED
const odg_sub_t *odg_sub_at_(const odg_dict_t *d, const odg_entry_t *e, uint32_t pos,
                             odg_sub_t *copy);
#else
#define odg_sub_at_(d, e, pos, copy) ((void)(e), (void)(copy), &(d)->subs[pos])
#endif

#endif /* ODG_IMPL_H */
