/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_lss.c - LSS slave (CiA 305): switch state global and selective, configure node-id and
 * bit timing, activate bit timing, store configuration, inquire identity and node-id, identify
 * (non-configured) remote slave, fastscan. Calls the persistence layer's record functions
 * and odg_node_io.c. See odg_lss.h and NODE.md.
 */
#include "odg_impl.h"
#include "odg_node.h"

/* The stored configuration, a persistence record (odg_persist_store_record): node-id | bit
 * timing index << 8. Its tag "LSS1" names this layout. */
#define TAG 0x3153534Cu

/* End of the persistence groups' regions: the LSS record goes after them. */
static uint32_t groups_end(const odg_dict_t *d)
{
    return odg_persist_nv_size(d);
}

#if ODG_NODE_LSS

/* The NV address of the record: the first past the groups, aligned as a slot is. */
static uint32_t record_at(const odg_dict_t *d)
{
    uint32_t a = (uint32_t)ODG_PERSIST_ALIGN - 1u;
    return (groups_end(d) + a) & ~a;
}

uint32_t odg_lss_nv_size(const odg_dict_t *dict)
{
    return record_at(dict) + 2u * ODG_PERSIST_RECORD_SLOT;
}

static int valid_id(uint8_t id)
{
    return (id >= 1u && id <= 127u) || id == ODG_LSS_UNCONFIGURED;
}

void odg_lss_init_(odg_node_t *n)
{
    uint32_t r; /* node-id | bit timing index << 8, as stored */
    if (odg_persist_load_record(n->cfg.nv, record_at(n->cfg.dict), TAG, &r) != 1 || !valid_id((uint8_t)r)) {
        r = n->cfg.node_id | (uint32_t)ODG_LSS_NO_BIT_TIMING << 8; /* none stored */
    }
    n->lss.mode = ODG_LSS_WAITING;
    n->lss.pending = (uint8_t)r;
    n->lss.bit_index = (uint8_t)(r >> 8);
}

int odg_lss_activate_(odg_node_t *n)
{
    int changed = n->lss.pending != n->cfg.node_id;
    n->cfg.node_id = n->lss.pending;
    return changed;
}

/* 0x1018 sub 1 + part: vendor-ID, product code, revision number, serial number */
static uint32_t identity(const odg_node_t *n, unsigned part)
{
    return odg_io_get_or_(n, 0x1018, (uint8_t)(part + 1u), 0);
}

static void reply(odg_node_t *n, uint8_t cs, uint32_t value)
{
    uint8_t d[8];
    unsigned k;
    d[0] = cs;
    for (k = 1; k < 8u; k++, value >>= 8) { /* the value little-endian, then zeros */
        d[k] = (uint8_t)value;
    }
    (void)odg_io_send_(n, ODG_LSS_SLAVE_COB, d, 8);
}

/* Switch state selective (0x40..0x43): the four parts of the identity in order; a wrong one
 * starts over. All four matched: configuration mode, answered with 0x44. */
static void selective(odg_node_t *n, unsigned part, uint32_t v)
{
    int go = part == 0u || n->lss.selective == part; /* the vendor-ID (re)starts it */
    unsigned got = go && v == identity(n, part) ? part + 1u : 0u;
    n->lss.selective = (uint8_t)(got & 3u); /* all four: done, 0 again */
    if (got == 4u) {
        n->lss.mode = ODG_LSS_CONFIGURATION;
        reply(n, 0x44, 0);
    }
}

/* Identify remote slave (0x46..0x4B): vendor, product, revision low/high, serial low/high;
 * after the last, answer 0x4F when all six checks passed. */
static void identify(odg_node_t *n, unsigned part, uint32_t v)
{
    uint32_t id = identity(n, part < 2u ? part : (part + 2u) >> 1); /* 2, 3: revision; 4, 5: serial */
    /* vendor and product (0, 1) must equal id, a low bound (2, 4) be <= id, a high one (3, 5)
     * >= id: a value above id fails parts 0, 1, 2, 4 (bits 0x17), one below it 0, 1, 3, 5 (0x2B) */
    unsigned ok = ((v > id ? 0x17u : (v < id ? 0x2Bu : 0u)) >> part & 1u) ^ 1u;
    uint8_t seen = (uint8_t)(part == 0u ? 0u : n->lss.identify);
    n->lss.identify = seen = (uint8_t)(seen | ok << part);
    if (part == 5u && seen == 0x3Fu) {
        reply(n, 0x4F, 0);
    }
}

/* Fastscan (0x51): only a non-configured slave in waiting mode takes part. bitChecked 0x80
 * starts a scan (every such slave answers); else the slave answers when the master asks for
 * its current part (LSSSub) and the bits bitChecked..31 match. A full match (bitChecked 0)
 * moves it on to LSSNext; going back (LSSNext < LSSSub: the serial number matched) selects it: the slave
 * enters configuration mode. */
static void fastscan(odg_node_t *n, const uint8_t *d)
{
    uint32_t id = ODG_LE32(d + 1);
    uint8_t bit = d[5], sub = d[6], next = d[7];
    if (n->cfg.node_id != ODG_LSS_UNCONFIGURED || n->lss.mode != ODG_LSS_WAITING) {
        return;
    }
    if (bit == 0x80u) {
        n->lss.fastscan = 0;
    } else if (bit > 31u || next > 3u || sub != n->lss.fastscan || /* that is 0..3: so is sub */
               (id ^ identity(n, sub)) >> bit != 0u) { /* a bit bitChecked..31 differs */
        return;
    } else if (bit == 0u) {
        n->lss.fastscan = next;
        if (next < sub) { /* back to the vendor-ID: all four parts matched */
            n->lss.mode = ODG_LSS_CONFIGURATION;
        }
    }
    reply(n, 0x4F, 0);
}

/* Commands of configuration mode; others are ignored. v: bytes 1..4, little-endian. */
static void configure(odg_node_t *n, uint8_t cs, uint32_t v)
{
    uint8_t b1 = (uint8_t)v, b2 = (uint8_t)(v >> 8);
    odg_abort_t ac;
    unsigned part;
    uint8_t err = 0;
    switch (cs) {
    case 0x11: /* configure node-id: 1..127, or 0xFF to make the node non-configured */
        if (valid_id(b1)) {
            n->lss.pending = b1;
        } else {
            err = 1;
        }
        break;
    case 0x13: /* configure bit timing: table 0 (CiA), index, accepted by the application */
        if (b1 != 0u || b2 > 9u || n->cfg.on_bit_timing == NULL ||
            n->cfg.on_bit_timing(n->cfg.app_ctx, b2, 0, 0) != 0) {
            err = 1;
        } else {
            n->lss.bit_index = b2;
        }
        break;
    case 0x15: /* activate bit timing: no answer */
        if (n->cfg.on_bit_timing != NULL && n->lss.bit_index != ODG_LSS_NO_BIT_TIMING) {
            (void)n->cfg.on_bit_timing(n->cfg.app_ctx, n->lss.bit_index, (uint16_t)v, 1);
        }
        return;
    case 0x17: /* store configuration: 1 no NV, 2 the NV failed */
        ac = odg_persist_store_record(n->cfg.nv, record_at(n->cfg.dict), TAG,
                                      n->lss.pending | (uint32_t)n->lss.bit_index << 8);
        err = (uint8_t)(ac == ODG_OK ? 0u : (ac == ODG_ABORT_DATA_STORE ? 1u : 2u));
        break;
    default:
        part = cs - 0x5Au;
        if (part <= 4u) { /* inquire identity (0x5A..0x5D), node-id (the active one) */
            reply(n, cs, part < 4u ? identity(n, part) : n->cfg.node_id);
        }
        return;
    }
    reply(n, cs, err);
}

int odg_lss_receive_(odg_node_t *n, const uint8_t *d)
{
    uint8_t cs = d[0];
    uint32_t v = ODG_LE32(d + 1);
    if (cs == 0x04u && d[1] <= 1u) { /* switch state global */
        n->lss.mode = d[1];
        n->lss.selective = 0;
        /* a non-configured node that got a node-id boots when sent back to waiting */
        return d[1] == ODG_LSS_WAITING && n->cfg.node_id == ODG_LSS_UNCONFIGURED &&
               n->lss.pending != ODG_LSS_UNCONFIGURED;
    }
    if (cs >= 0x40u && cs <= 0x43u) {
        if (n->lss.mode == ODG_LSS_WAITING) {
            selective(n, cs - 0x40u, v);
        }
    } else if (cs >= 0x46u && cs <= 0x4Bu) {
        identify(n, cs - 0x46u, v);
    } else if (cs == 0x4Cu) {
        if (n->cfg.node_id == ODG_LSS_UNCONFIGURED && n->lss.pending == ODG_LSS_UNCONFIGURED) {
            reply(n, 0x50, 0);
        }
    } else if (cs == 0x51u) {
        fastscan(n, d);
    } else if (n->lss.mode == ODG_LSS_CONFIGURATION) {
        configure(n, cs, v);
    }
    return 0;
}

#else /* without ODG_NODE_LSS: nothing but the NV size */

uint32_t odg_lss_nv_size(const odg_dict_t *dict)
{
    return groups_end(dict);
}

void odg_lss_init_(odg_node_t *n)
{
    (void)n;
}

int odg_lss_activate_(odg_node_t *n)
{
    (void)n;
    return 0;
}

int odg_lss_receive_(odg_node_t *n, const uint8_t *d)
{
    (void)n, (void)d;
    return 0;
}

#endif
