/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_pdo.c - TPDOs and RPDOs of the node, configured by the dictionary's 0x1400-0x15FF /
 * 0x1600-0x17FF (RPDO) and 0x1800-0x19FF / 0x1A00-0x1BFF (TPDO) entries, and what they do at a
 * SYNC (odg_sync.c hands each one over) and within the SYNC window. Calls odg_err.c and
 * odg_node_io.c (odg_pdo.h).
 *
 * Each PDO's parameters are read once into odg_pdo_t (at boot, and again after every SDO
 * write to its entries); mapped values are read and written through the dictionary at each
 * transmission or reception, so hooks and limits apply. Mapping is bit-granular (a BOOLEAN
 * may take 1 bit), at most ODG_NODE_MAX_MAP objects and 64 bits per PDO.
 *
 * ODG_NODE_TPDO_COS (default 1): event-driven (254/255) and acyclic synchronous (0) TPDOs are
 * also sent when a mapped value changed. Define it to 0 when the application decides what is
 * an event (device profiles such as CiA 401 with its interrupt masks) and asks for each
 * transmission with odg_node_tpdo_request; event timers and SYNC still apply.
 */
#include <string.h>

#include "odg_node.h"

#define TYPE_SYNC_MAX 240u /* 0: acyclic synchronous, 1..240: every n-th SYNC */
#define TYPE_RTR_SYNC 252u /* TPDO: sampled at each SYNC, sent on a remote request */
#define TYPE_RTR 253u      /* TPDO: sampled and sent on a remote request */
#define TYPE_EVENT 254u    /* 254, 255: event-driven */
#define COB_NO_RTR 0x40000000u /* TPDO COB-ID bit 30: no remote requests */
#define EMCY_PDO_LENGTH 0x8210u /* PDO not processed due to length error */

#ifndef ODG_NODE_TPDO_COS
#define ODG_NODE_TPDO_COS 1
#endif

static uint16_t comm_index(int tx, uint16_t k)
{
    return (uint16_t)((tx ? 0x1800u : 0x1400u) + k);
}

/* Transmission types CiA 301 reserves: 241..251, and for an RPDO also 252/253 (RTR). */
static int reserved_type(int tx, uint32_t type)
{
    return type > TYPE_SYNC_MAX && type < (tx ? TYPE_RTR_SYNC : TYPE_EVENT);
}

/* Valid (COB-ID bit 31 clear) and mapped: odg_pdo_load_ leaves n_map 0 otherwise. */
static int active(const odg_pdo_t *p)
{
    return p->n_map > 0u;
}

/* Copy `n` bits, LSB first (CiA 301 PDO mapping order), from bit `spos` of `src` to `dpos`. */
static void copy_bits(uint8_t *dst, uint32_t dpos, const uint8_t *src, uint32_t spos, uint32_t n)
{
    for (; n > 0u; n--, dpos++, spos++) { /* flip the destination bit where the two differ */
        unsigned d = dst[dpos >> 3], differ = ((unsigned)src[spos >> 3] >> (spos & 7u) ^ d >> (dpos & 7u)) & 1u;
        dst[dpos >> 3] = (uint8_t)(d ^ differ << (dpos & 7u));
    }
}

/* ---- mapping ---------------------------------------------------------------------------- */

/* A short mapping, served as CANopenNode serves it: a 64-bit integer entry mapped with 32 bits
 * carries its low-order four bytes (the first four on the wire, which is little-endian); an
 * RPDO writes them and keeps the entry's high-order bytes. odgen lint warns of it (PDO003).
 * Other lengths are checked by odg_check_mapping. A build without 64-bit types has none. */
static int short64(const odg_ref_t *r, uint32_t m)
{
    return ODG_CFG_INT64 && (m & 0xFFu) == 32u && r->sub->size == 8u &&
           (r->sub->type == ODG_T_INTEGER64 || r->sub->type == ODG_T_UNSIGNED64);
}

static odg_abort_t map_ref(const odg_dict_t *d, uint32_t m, uint8_t dir, odg_ref_t *r)
{
    odg_abort_t ac = odg_check_mapping(d, m, dir, r);
    if (ODG_CFG_INT64 && ac == ODG_ABORT_NOT_MAPPABLE && (m & 0xFFu) == 32u &&
        odg_check_mapping(d, m + 32u, dir, r) == ODG_OK && short64(r, m)) { /* length 64 */
        return ODG_OK;
    }
    return ac;
}

/* One mapping entry. RPDOs may map the data type indices 0x0001-0x0007 as dummies (gaps of
 * that type's size), which need no object in the dictionary. */
static odg_abort_t check_entry(const odg_node_t *n, int tx, uint32_t m)
{
    static const uint8_t dummy_bits[8] = {0, 1, 8, 16, 32, 8, 16, 32};
    uint32_t index = m >> 16, bits = m & 0xFFu;
    odg_ref_t r;
    if (!tx && index >= 1u && index <= 7u) {
        return (m & 0xFF00u) == 0u && (bits == dummy_bits[index] || (index == 1u && bits == 8u))
                   ? ODG_OK
                   : ODG_ABORT_NOT_MAPPABLE;
    }
    return map_ref(n->cfg.dict, m, tx ? ODG_A_TPDO : ODG_A_RPDO, &r);
}

/* Entries 1..count of mapping entry `index` as the dictionary holds them: each mappable, and
 * together at most 64 bits (else PDO_LENGTH, as for a count beyond the entries there are).
 * With `p`, the entries go to p->map and, when all are served, an RPDO's length to p->len. */
static odg_abort_t read_mapping(const odg_node_t *n, int tx, uint16_t index, uint32_t count,
                                odg_pdo_t *p)
{
    uint32_t i, m, bits = 0;
    odg_abort_t ac;
    if (count > ODG_NODE_MAX_MAP) {
        return ODG_ABORT_PDO_LENGTH;
    }
    for (i = 1; i <= count; i++) {
        if ((ac = odg_io_get_(n, index, (uint8_t)i, &m)) != ODG_OK) {
            return ac == ODG_ABORT_NO_SUB ? ODG_ABORT_PDO_LENGTH : ac;
        }
        if ((ac = check_entry(n, tx, m)) != ODG_OK) {
            return ac;
        }
        bits += m & 0xFFu;
        if (p != NULL) {
            p->map[i - 1u] = m;
        }
    }
    if (bits > 64u) {
        return ODG_ABORT_PDO_LENGTH;
    }
    if (p != NULL && !tx) {
        p->len = (uint8_t)((bits + 7u) / 8u);
    }
    return ODG_OK;
}

/* A TPDO starts afresh (entering operational, or reconfigured): send at the first chance. */
static void restart(odg_pdo_t *p)
{
    p->flags = ODG_PDO_F_REQUEST;
    p->count = 0;
    p->inhibit_left = 0;
    p->event_left = p->event;
}

/* The error 0x8210 is gone when no RPDO's last frame was too short. */
static void length_errors_gone(odg_node_t *n)
{
    uint16_t k;
    for (k = 0; k < ODG_NODE_MAX_RPDO; k++) {
        if (n->rpdo[k].flags & ODG_PDO_F_LEN_ERR) {
            return;
        }
    }
    (void)odg_node_error_clear(n, EMCY_PDO_LENGTH);
}

void odg_pdo_load_(odg_node_t *n, int tx, uint16_t k)
{
    uint16_t comm = comm_index(tx, k);
    uint32_t count;
    odg_pdo_t *p = tx ? n->tpdo : n->rpdo;
    if (k >= (tx ? ODG_NODE_MAX_TPDO : ODG_NODE_MAX_RPDO)) {
        return;
    }
    p += k;
    if (p->flags & ODG_PDO_F_LEN_ERR) { /* an RPDO reconfigured: its length error is moot */
        p->flags = 0;
        length_errors_gone(n);
    }
    memset(p, 0, sizeof *p);
    if (odg_io_get_(n, comm, 1, &p->cob) != ODG_OK) {
        p->cob = ODG_COB_INVALID; /* no such PDO */
        return;
    }
    p->type = (uint8_t)odg_io_get_or_(n, comm, 2, 255);
    p->inhibit = (uint16_t)odg_io_num_(n, comm, 3);
    p->event = (uint16_t)odg_io_num_(n, comm, 5);
    p->sync_start = (uint8_t)odg_io_num_(n, comm, 6);
    count = odg_io_num_(n, (uint16_t)(comm + 0x200u), 0);
    /* a mapping or type the node cannot serve (only possible in the dictionary's defaults,
     * as SDO writes are checked) leaves the PDO unused (n_map and len 0) */
    if (reserved_type(tx, p->type) ||
        read_mapping(n, tx, (uint16_t)(comm + 0x200u), count, p) != ODG_OK) {
        count = 0;
    }
    p->n_map = (uint8_t)(p->cob & ODG_COB_INVALID ? 0u : count); /* an invalid PDO is not active */
    if (tx && n->state == ODG_NMT_OPERATIONAL) {
        restart(p);
    }
}

void odg_pdo_start_(odg_node_t *n)
{
    uint16_t k;
    for (k = 0; k < ODG_NODE_MAX_TPDO; k++) {
        restart(&n->tpdo[k]);
    }
    for (k = 0; k < ODG_NODE_MAX_RPDO; k++) {
        n->rpdo[k].flags &= ODG_PDO_F_LEN_ERR; /* data waiting for a SYNC dropped, the error kept */
    }
}

/* ---- checks before the SDO server stores a PDO parameter ------------------------------ */

/* CAN-IDs CiA 301 reserves for NMT, SYNC/EMCY/TIME ranges, SDO, LSS and error control. */
static int restricted(uint32_t id)
{
    return id <= 0x7Fu || (id >= 0x101u && id <= 0x180u) || (id >= 0x581u && id <= 0x5FFu) ||
           (id >= 0x601u && id <= 0x67Fu) || (id >= 0x6E0u && id <= 0x6FFu) || id >= 0x701u;
}

/* A new COB-ID `v` (sub 1) for the PDO of communication entry `index`, whose COB-ID is `old`:
 * disabling is always allowed; a valid PDO keeps bits 0..29 (CiA 301); only 11-bit identifiers
 * outside the restricted ones can be made valid. A mapping the node cannot serve is only
 * possible in the dictionary's defaults (SDO writes of mappings are checked): the PDO stays
 * unused, and enabling it is refused. */
static odg_abort_t check_cob(const odg_node_t *n, int tx, uint16_t index, uint32_t old, uint32_t v)
{
    uint16_t map = (uint16_t)(index + 0x200u);
    int valid = !(old & ODG_COB_INVALID);
    if (v & ODG_COB_INVALID) {
        return ODG_OK;
    }
    if ((valid && ((v ^ old) & 0x3FFFFFFFu)) || (v & 0x3FFFF800u) || restricted(v & 0x7FFu)) {
        return ODG_ABORT_VALUE_RANGE;
    }
    return valid || read_mapping(n, tx, map, odg_io_num_(n, map, 0), NULL) == ODG_OK ? ODG_OK
                                                                                   : ODG_ABORT_INCOMPATIBLE;
}

/*
 * Mapping entries follow the order of CiA 301: invalidate the PDO (COB-ID bit 31),
 * set sub 0 to 0, write the entries, set sub 0 to their number, make the PDO valid again.
 * Writing a mapping while the PDO is valid, or an entry while sub 0 is not 0, aborts with
 * 0x06010000, as in CANopenNode (0x08000022 would also fit). An entry is checked when
 * written (0 clears it), and all of them again when sub 0 = n: 0x06040041 not mappable,
 * 0x06020000/0x06090011 no such object, 0x06040042 more than 64 bits or entries.
 */
static odg_abort_t check_mapping_write(const odg_node_t *n, int tx, uint16_t index, uint8_t sub,
                                       uint32_t v, int valid)
{
    if (valid) {
        return ODG_ABORT_UNSUPPORTED;
    }
    if (sub == 0u) {
        return read_mapping(n, tx, index, v, NULL);
    }
    if (odg_io_num_(n, index, 0) != 0u) {
        return ODG_ABORT_UNSUPPORTED;
    }
    return v == 0u ? ODG_OK : check_entry(n, tx, v);
}

/* Communication parameters: besides the COB-ID, the transmission types 241..251 (reserved)
 * and, for an RPDO, 252/253 (RTR: TPDOs only), and the inhibit time and SYNC start value of
 * a valid TPDO (CiA 301 forbids changing them while it exists) abort with 0x06090030. */
odg_abort_t odg_pdo_check_(const odg_node_t *n, uint16_t index, uint8_t sub, uint32_t v)
{
    int tx = index >= 0x1800u;
    uint32_t cob = odg_io_get_or_(n, (uint16_t)(index & ~0x200u), 1, ODG_COB_INVALID);
    int valid = !(cob & ODG_COB_INVALID);
    if (index & 0x200u) {
        return check_mapping_write(n, tx, index, sub, v, valid);
    }
    if (sub == 1u) {
        return check_cob(n, tx, index, cob, v);
    }
    if (sub == 2u) {
        return reserved_type(tx, v) ? ODG_ABORT_VALUE_RANGE : ODG_OK;
    }
    return tx && valid && (sub == 3u || sub == 6u) ? ODG_ABORT_VALUE_RANGE : ODG_OK;
}

/* ---- mapped values --------------------------------------------------------------------- */

/* Move the mapped values between the dictionary and a frame. A TPDO (`tx`) reads them now
 * (PRE_READ hooks run) into `frame`, and its length into `len`; the first value it cannot read
 * stops it. An RPDO writes them from `frame`: a value the dictionary refuses (limits, a hook's
 * veto) is dropped, as a PDO has no answer, and dummy entries only take their bits. */
static odg_abort_t move(odg_node_t *n, const odg_pdo_t *p, int tx, uint8_t *frame, uint8_t *len)
{
    uint32_t i, pos = 0;
    uint8_t in[8]; /* an RPDO's data: a write's listener may reload the PDO, which clears p->data */
    if (tx) {
        memset(frame, 0, 8);
    } else {
        memcpy(in, frame, sizeof in);
        frame = in;
    }
    for (i = 0; i < p->n_map; pos += p->map[i++] & 0xFFu) {
        uint32_t m = p->map[i], bits = m & 0xFFu, got, size = (bits + 7u) / 8u;
        odg_ref_t r;
        uint8_t v[8];
        odg_abort_t ac;
        memset(v, 0, sizeof v); /* odg_read writes `got` bytes: the rest stay 0 */
        if (!tx && (m >> 16) <= 7u) {
            continue; /* a dummy */
        }
        ac = map_ref(n->cfg.dict, m, tx ? ODG_A_TPDO : ODG_A_RPDO, &r);
        if (tx) {
            if (ac != ODG_OK || (ac = odg_read(&r, 0, v, sizeof v, &got)) != ODG_OK) {
                return ac;
            }
            copy_bits(frame, pos, v, 0, bits);
        } else if (ac == ODG_OK) {
            if (short64(&r, m)) {
                size = 8u;
                if (odg_read(&r, 0, v, sizeof v, &got) != ODG_OK) {
                    memset(v, 0, sizeof v); /* write-only: the high-order bytes become 0 */
                }
            }
            copy_bits(v, 0, frame, pos, bits);
            (void)odg_write(&r, v, size);
        }
    }
    if (tx) {
        *len = (uint8_t)((pos + 7u) / 8u);
    }
    return ODG_OK;
}

/* ---- TPDO ---------------------------------------------------------------------------------- */

/* Sample and send; unless `force`, only when the data differ from the last frame sent.
 * Non-zero when a frame was due but could not be sent. */
static int transmit(odg_node_t *n, odg_pdo_t *p, int force)
{
    uint8_t d[8], len;
    if (move(n, p, 1, d, &len) != ODG_OK) {
        return 1;
    }
    if (!force && (p->flags & ODG_PDO_F_SENT) && len == p->len) {
        uint8_t k = len;
        while (k > 0u && d[k - 1u] == p->data[k - 1u]) { /* a loop, not memcmp: the node then links none */
            k--;
        }
        if (k == 0u) {
            return 0;
        }
    }
    if (odg_io_send_(n, p->cob, d, len) != 0) {
        return 1; /* the event stays pending */
    }
    memcpy(p->data, d, sizeof d);
    p->len = len;
    p->flags = (uint8_t)((p->flags | ODG_PDO_F_SENT) & ~ODG_PDO_F_REQUEST);
    p->inhibit_left = p->inhibit;
    p->event_left = p->event;
    return 0;
}

/* ---- SYNC window (0x1007, us; 0 or absent: none) --------------------------------------------- */

static int in_window(const odg_node_t *n)
{
    uint32_t window = odg_io_num_(n, 0x1007, 0);
    return window == 0u || n->sync_us <= window;
}

/* Time since the SYNC goes on; a synchronous TPDO whose frame could not be sent at the SYNC is
 * tried again while the window lasts, and dropped (counted in sync_dropped) when it is over. */
static void window_tick(odg_node_t *n, uint32_t ms)
{
    uint16_t k;
    n->sync_us = ms > (0xFFFFFFFFu - n->sync_us) / 1000u ? 0xFFFFFFFFu : n->sync_us + ms * 1000u;
    for (k = 0; k < ODG_NODE_MAX_TPDO; k++) {
        odg_pdo_t *p = &n->tpdo[k];
        int sync;
        if (!(p->flags & ODG_PDO_F_DUE)) {
            continue;
        }
        sync = active(p) && p->type <= TYPE_SYNC_MAX;
        if (sync && !in_window(n)) {
            n->sync_dropped++;
        } else if (sync && transmit(n, p, 1)) {
            continue; /* still due */
        }
        p->flags &= (uint8_t)~(ODG_PDO_F_DUE | ODG_PDO_F_REQUEST);
    }
}

void odg_pdo_request_(odg_node_t *n, uint16_t k)
{
    odg_pdo_t *p = &n->tpdo[k];
    p->flags |= ODG_PDO_F_REQUEST;
    if (active(p) && p->type >= TYPE_EVENT && p->inhibit_left == 0u) {
        (void)transmit(n, p, 1);
    }
}

/* Event-driven TPDOs: sent when requested, when the event timer expires, or (ODG_NODE_TPDO_COS)
 * when a mapped value changed (sampled every tick), but never within the inhibit time of the
 * last one. */
void odg_pdo_tick_(odg_node_t *n, uint32_t ms)
{
    uint32_t ticks = ms > 0x19999999u ? 0xFFFFFFFFu : ms * 10u; /* in 100 us */
    uint16_t k;
    int force;
    window_tick(n, ms);
    for (k = 0; k < ODG_NODE_MAX_TPDO; k++) {
        odg_pdo_t *p = &n->tpdo[k];
        if (!active(p) || p->type < TYPE_EVENT) {
            continue;
        }
        p->inhibit_left = p->inhibit_left > ticks ? p->inhibit_left - ticks : 0u;
        p->event_left = (uint16_t)(p->event_left > ms ? p->event_left - ms : 0u);
        force = (p->flags & ODG_PDO_F_REQUEST) || (p->event != 0u && p->event_left == 0u);
        if (p->inhibit_left == 0u && (force || ODG_NODE_TPDO_COS)) {
            (void)transmit(n, p, force);
        }
    }
}

/* Synchronous TPDOs count SYNCs from the one whose counter byte equals the SYNC start value
 * (when both are used), else from the first. */
static int sync_started(odg_pdo_t *p, const odg_frame_t *f)
{
    if (!(p->flags & ODG_PDO_F_STARTED) &&
        (p->sync_start == 0u || f->len == 0u || f->data[0] == p->sync_start)) {
        p->flags |= ODG_PDO_F_STARTED;
        p->count = (uint8_t)(p->sync_start != 0u && f->len != 0u ? p->type - 1u : 0u);
    }
    return (p->flags & ODG_PDO_F_STARTED) != 0u;
}

/* ---- RPDO -------------------------------------------------------------------------------- */

/* A frame shorter than the mapping is not processed: the error 0x8210 (PDO length) is active
 * until every RPDO's last frame had the right length again, or the RPDO was reconfigured.
 * Longer frames are processed. */
static void length_error(odg_node_t *n, odg_pdo_t *p, int error)
{
    if (error == ((p->flags & ODG_PDO_F_LEN_ERR) != 0u)) {
        return;
    }
    p->flags ^= ODG_PDO_F_LEN_ERR;
    if (error) {
        (void)odg_node_error_set(n, EMCY_PDO_LENGTH, 0, NULL, 0);
    } else {
        length_errors_gone(n);
    }
}

void odg_pdo_receive_(odg_node_t *n, const odg_frame_t *f)
{
    odg_pdo_t *p = n->rpdo, *end = n->rpdo + ODG_NODE_MAX_RPDO; /* the limits are >= 1 */
    int too_short;
    while (!active(p) || ODG_COB_ID(p->cob) != f->id) {
        if (++p == end) {
            return; /* none of ours */
        }
    }
    too_short = f->len < p->len;
    length_error(n, p, too_short);
    if (too_short) {
        return;
    }
    if (p->type <= TYPE_SYNC_MAX && !in_window(n)) {
        n->sync_dropped++; /* CiA 301: synchronous data outside the window are discarded */
    } else {
        memcpy(p->data, f->data, sizeof p->data);
        if (p->type <= TYPE_SYNC_MAX) {
            p->flags |= ODG_PDO_F_RECEIVED; /* applied at the next SYNC */
        } else {
            (void)move(n, p, 0, p->data, NULL);
        }
    }
}

/* ---- at a SYNC (odg_sync.c) --------------------------------------------------------------------- */

/* RPDO data received since the last SYNC take effect first, then synchronous TPDOs sample; one
 * whose frame could not be sent is tried again within the window (window_tick). */
void odg_pdo_sync_(odg_node_t *n, const odg_frame_t *f)
{
    uint16_t k;
    n->sync_us = 0;
    for (k = 0; k < ODG_NODE_MAX_TPDO; k++) {
        if (n->tpdo[k].flags & ODG_PDO_F_DUE) {
            n->tpdo[k].flags &= (uint8_t)~(ODG_PDO_F_DUE | ODG_PDO_F_REQUEST);
            n->sync_dropped++; /* still not sent at the next SYNC */
        }
    }
    for (k = 0; k < ODG_NODE_MAX_RPDO; k++) {
        odg_pdo_t *p = &n->rpdo[k];
        if (active(p) && (p->flags & ODG_PDO_F_RECEIVED)) {
            p->flags &= (uint8_t)~ODG_PDO_F_RECEIVED;
            (void)move(n, p, 0, p->data, NULL);
        }
    }
    for (k = 0; k < ODG_NODE_MAX_TPDO; k++) {
        odg_pdo_t *p = &n->tpdo[k];
        if (!active(p)) {
            continue;
        }
        if (p->type == TYPE_RTR_SYNC && move(n, p, 1, p->data, &p->len) == ODG_OK) {
            p->flags |= ODG_PDO_F_SAMPLED; /* sent when a remote request comes */
        }
        if (p->type > TYPE_SYNC_MAX) {
            continue;
        }
        if (p->type == 0u) {
            /* on an event (odg_node_tpdo_request), or a change unless the application decides */
            if (((p->flags & ODG_PDO_F_REQUEST) || ODG_NODE_TPDO_COS) &&
                transmit(n, p, (p->flags & ODG_PDO_F_REQUEST) != 0u)) {
                p->flags |= ODG_PDO_F_DUE;
            }
        } else if (sync_started(p, f) && ++p->count >= p->type) {
            p->count = 0;
            if (transmit(n, p, 1)) {
                p->flags |= ODG_PDO_F_DUE;
            }
        }
    }
}

/* A remote request for a TPDO of type 252 (the data sampled at the last SYNC, once there was
 * one) or 253 (sampled now), unless its COB-ID forbids remote requests (bit 30). */
void odg_pdo_rtr_(odg_node_t *n, const odg_frame_t *f)
{
    uint16_t k;
    for (k = 0; k < ODG_NODE_MAX_TPDO; k++) {
        odg_pdo_t *p = &n->tpdo[k];
        if (!active(p) || ODG_COB_ID(p->cob) != f->id || (p->cob & COB_NO_RTR)) {
            continue;
        }
        if (p->type == TYPE_RTR) {
            transmit(n, p, 1);
        } else if (p->type == TYPE_RTR_SYNC && (p->flags & ODG_PDO_F_SAMPLED)) {
            (void)odg_io_send_(n, p->cob, p->data, p->len);
        }
    }
}

/* ---- what the build's limits leave out ---------------------------------------------------- */

/* The highest sub-index of entry `index`, or -1 when absent. */
static int32_t highest_sub(const odg_dict_t *d, uint16_t index)
{
    odg_ref_t r;
    if (odg_find(d, index, 0, &r) != ODG_OK) {
        return -1;
    }
    return d->subs[r.entry->first + r.entry->count - 1u].sub;
}

uint16_t odg_node_unserved(const odg_dict_t *dict)
{
    uint16_t k, n = 0;
    for (k = 0; k < 0x200u; k++) {
        int rx_served = k < ODG_NODE_MAX_RPDO, tx_served = k < ODG_NODE_MAX_TPDO;
        if (highest_sub(dict, (uint16_t)(0x1400u + k)) >= 0) {
            n = (uint16_t)(n + (rx_served ? highest_sub(dict, (uint16_t)(0x1600u + k)) > (int32_t)ODG_NODE_MAX_MAP
                                          : 1));
        }
        if (highest_sub(dict, (uint16_t)(0x1800u + k)) >= 0) {
            n = (uint16_t)(n + (tx_served ? highest_sub(dict, (uint16_t)(0x1A00u + k)) > (int32_t)ODG_NODE_MAX_MAP
                                          : 1));
        }
    }
    return n;
}
