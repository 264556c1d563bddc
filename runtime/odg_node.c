/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_node.c - NMT slave, heartbeat producer, EMCY producer and frame dispatch of the CANopen
 * node. The SDO server is in odg_sdo.c, SYNC and PDOs in odg_pdo.c. See odg_node.h.
 */
#include <string.h>

#include "odg_impl.h"
#include "odg_node_impl.h"

/* ---- helpers shared with odg_sdo.c and odg_pdo.c ------------------------------------ */

int odg_node_send_(odg_node_t *n, uint32_t cob, const uint8_t *data, uint8_t len)
{
    odg_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = ODG_COB_ID(cob);
    f.len = len;
    if (len > 0u) {
        memcpy(f.data, data, len);
    }
    return n->cfg.send(n->cfg.send_ctx, &f);
}

odg_abort_t odg_node_get_(const odg_node_t *n, uint16_t index, uint8_t sub, uint32_t *value)
{
    odg_ref_t r;
    uint8_t b[4];
    uint32_t got = 0, v = 0;
    odg_abort_t ac = odg_find(n->cfg.dict, index, sub, &r);
    if (ac == ODG_OK) {
        ac = odg_read(&r, 0, b, sizeof b, &got);
    }
    while (got > 0u) {
        got--;
        v = v << 8 | b[got];
    }
    *value = v;
    return ac;
}

uint32_t odg_node_get_or_(const odg_node_t *n, uint16_t index, uint8_t sub, uint32_t dflt)
{
    uint32_t v;
    return odg_node_get_(n, index, sub, &v) == ODG_OK ? v : dflt;
}

odg_abort_t odg_node_check_(odg_node_t *n, uint16_t index, uint8_t sub, const uint8_t *data,
                            uint32_t len)
{
    uint32_t v = 0;
    if (index == 0x1019u) {
        return odg_sync_check_(n, index);
    }
    if ((index != 0x1003u && index != 0x1016u && (index < 0x1400u || index >= 0x1C00u)) || len > 4u) {
        return ODG_OK; /* only 0x1003, 0x1016, 0x1019 and PDO parameters have rules of their own */
    }
    while (len > 0u) {
        len--;
        v = v << 8 | data[len];
    }
    if (index == 0x1016u) {
        return odg_hb_check_(n, sub, v);
    }
    return index == 0x1003u ? odg_err_check_(n, sub, v) : odg_pdo_check_(n, index, sub, v);
}

/* COB-IDs of SYNC, EMCY and TIME: re-read whenever one of them changes. */
static void load_cobs(odg_node_t *n)
{
    uint32_t id = n->cfg.node_id;
    n->sync_cob = odg_node_get_or_(n, 0x1005, 0, 0x80u);
    n->emcy_cob = odg_node_get_or_(n, 0x1014, 0, 0x80u + id);
    n->time_cob = odg_node_get_or_(n, 0x1012, 0, 0);
}

/* The SDO server's COB-IDs from 0x1200 (without it, the pre-defined 0x600/0x580 + node-id), read
 * at boot and by odg_node_reload only: a write to 0x1200 takes effect at the next reset of
 * communication, so the answer to that write still goes where the client waits for it. Bit 31
 * of either (or a 29-bit COB-ID, whose frames the node ignores) disables the server. */
static void load_sdo_cobs(odg_node_t *n)
{
    uint32_t id = n->cfg.node_id;
    n->sdo_rx = odg_node_get_or_(n, 0x1200, 1, 0x600u + id);
    n->sdo_tx = odg_node_get_or_(n, 0x1200, 2, 0x580u + id);
    if ((n->sdo_tx | n->sdo_rx) & (ODG_COB_INVALID | ODG_COB_EXTENDED)) {
        n->sdo_rx |= ODG_COB_INVALID;
    }
}

/* A value changed, whoever wrote it (SDO server, application, persistence layer): re-read
 * what the node caches from the communication entries. */
static void comm_changed(odg_client_t *self, const odg_ref_t *ref)
{
    odg_node_t *n = (odg_node_t *)(void *)self; /* the client is the node's first member */
    uint16_t index;
    if (ref == NULL) {
        odg_node_reload(n);
        return;
    }
    index = ref->entry->index;
    if (index >= 0x1400u && index < 0x1C00u) {
        odg_pdo_load_(n, index >= 0x1800u, (uint16_t)(index & 0x1FFu));
    } else if (index == 0x1005u || index == 0x1014u || index == 0x1012u) {
        load_cobs(n);
    } else if (index == 0x1003u) {
        odg_err_written_(n);
    } else if (index == 0x1016u) {
        odg_hb_load_(n);
    }
}

void odg_node_reload(odg_node_t *node)
{
    uint16_t k;
    load_cobs(node);
    load_sdo_cobs(node);
    odg_hb_load_(node);
    for (k = 0; k < ODG_NODE_MAX_RPDO; k++) {
        odg_pdo_load_(node, 0, k);
    }
    for (k = 0; k < ODG_NODE_MAX_TPDO; k++) {
        odg_pdo_load_(node, 1, k);
    }
}

/* ---- the communication values in force at boot ------------------------------------------- */

/* What reset communication brings back: the numbers in 0x1000-0x1FFF an SDO client may write,
 * but not the error history 0x1003 (events, not parameters) nor the commands 0x1010/0x1011. */
static int comm_value(uint16_t index, const odg_sub_t *s)
{
    uint32_t cls = ODG_S_CLASS(s->storage);
    return index != 0x1003u && (s->attr & ODG_A_WRITE) != 0u && (cls == ODG_S_RAM || cls == ODG_S_PERSIST) &&
           s->size <= 8u && s->type != ODG_T_VISIBLE_STRING && s->type != ODG_T_OCTET_STRING &&
           s->type != ODG_T_UNICODE_STRING && s->type != ODG_T_DOMAIN;
}

/* Bytes of the C type holding a number of wire size `size`: the copy keeps values as stored. */
static uint32_t native_size(uint32_t size)
{
    return size == 3u ? 4u : (size > 4u ? 8u : size);
}

/* A number's default with the node-id added, as the generated reset does for $NODEID values. */
static void add_node_id(uint8_t *v, uint32_t size, uint8_t id)
{
    uint8_t u8;
    uint16_t u16;
    uint32_t u32;
    uint64_t u64;
    if (size == 1u) {
        memcpy(&u8, v, 1);
        u8 = (uint8_t)(u8 + id);
        memcpy(v, &u8, 1);
    } else if (size == 2u) {
        memcpy(&u16, v, 2);
        u16 = (uint16_t)(u16 + id);
        memcpy(v, &u16, 2);
    } else if (size == 4u) {
        memcpy(&u32, v, 4);
        u32 += id;
        memcpy(v, &u32, 4);
    } else {
        memcpy(&u64, v, 8);
        u64 += id;
        memcpy(v, &u64, 8);
    }
}

/* One value and its place in node->comm (the bytes of its C type): COMM_KEEP copies the
 * dictionary's value there, COMM_BACK back; COMM_SAVED and COMM_LOADED act on the values of the
 * persistence groups 0x1010/0x1011 sub `sub` named (1: all), which the next boot would load:
 * the value saved, or the group's default. */
enum { COMM_KEEP, COMM_BACK, COMM_SAVED, COMM_LOADED };

static void comm_copy(odg_node_t *n, const odg_sub_t *s, uint8_t *at, int how, uint8_t sub)
{
    const odg_dict_t *d = n->cfg.dict;
    const odg_group_t *g = ODG_S_CLASS(s->storage) == ODG_S_PERSIST ? &d->groups[ODG_S_GROUP(s->storage)] : NULL;
    uint32_t size = native_size(s->size);
    if (how == COMM_BACK) {
        memcpy(odg_value_(d, s), at, size);
    } else if (how == COMM_KEEP || (g != NULL && (sub == 1u || g->store_sub == sub))) {
        memcpy(at, how == COMM_LOADED ? (const uint8_t *)g->defaults + s->offset : odg_value_(d, s), size);
        if (how == COMM_LOADED && (s->attr & ODG_A_NODEID)) {
            add_node_id(at, size, n->cfg.node_id);
        }
    }
}

/* The communication values of one object: their bytes, and with `n` (not NULL) each copied
 * to `at` in sub-index order. Sub-indices are looked up one by one (odg_find), so that an
 * object's elements are found however the dictionary describes them. */
static uint32_t comm_object(const odg_dict_t *d, odg_node_t *n, const odg_entry_t *en, uint8_t *at, int how,
                            uint8_t sub)
{
    uint8_t last = d->subs[en->first + en->count - 1u].sub, k = 0;
    uint32_t bytes = 0;
    odg_ref_t r;
    do {
        if (odg_find(d, en->index, k, &r) == ODG_OK && comm_value(en->index, r.sub)) {
            if (n != NULL) {
                comm_copy(n, r.sub, at + bytes, how, sub);
            }
            bytes += native_size(r.sub->size);
        }
    } while (k++ < last);
    return bytes;
}

/* Walk the communication values, objects in index order while they fit whole into
 * node->comm (all of them for n == NULL, which only counts); returns the bytes they take. */
static uint32_t comm_walk(odg_node_t *n, const odg_dict_t *d, int how, uint8_t sub)
{
    uint32_t at = 0, size;
    uint16_t e;
    for (e = 0; e < d->n_entries && d->entries[e].index <= 0x1FFFu; e++) {
        const odg_entry_t *en = &d->entries[e];
        if (en->index < 0x1000u) {
            continue; /* data type definitions */
        }
        size = comm_object(d, NULL, en, NULL, how, sub);
        if (n != NULL && at + size > ODG_NODE_COMM_BYTES) {
            break; /* the rest keep their values at reset communication (NODE.md) */
        }
        if (n != NULL) {
            (void)comm_object(d, n, en, &n->comm[at], how, sub);
        }
        at += size;
    }
    return at;
}

uint32_t odg_node_comm_bytes(const odg_dict_t *dict)
{
    return comm_walk(NULL, dict, COMM_KEEP, 0);
}

void odg_node_comm_keep(odg_node_t *node)
{
    (void)comm_walk(node, node->cfg.dict, COMM_KEEP, 0);
}

void odg_node_stored_(odg_node_t *n, uint8_t sub, int restore)
{
    (void)comm_walk(n, n->cfg.dict, restore ? COMM_LOADED : COMM_SAVED, sub);
}

/* ---- NMT ------------------------------------------------------------------------------- */

enum { BOOT_COMM = 0, BOOT_RESET = 1, BOOT_POWER_ON = 2 }; /* boot(): what is reset */

/* After the dictionary was initialised with an NV driver: when a persistence group did not get
 * its stored values back (an image of another layout, a damaged image, a failing driver, an
 * entry defaulted or dropped by migration), an EMCY 0x5530 (data storage) with the generic
 * error bit, in byte 3 the boot statuses seen (bit 1 << odg_boot_status_t, and
 * ODG_BOOT_ENTRIES_LOST), in bytes 4-6 the entries defaulted, dropped and converted. The
 * application learns the details from cfg.boot. */
static void stored_values_lost(odg_node_t *n)
{
    const odg_state_t *s = n->cfg.dict->state;
    uint8_t data[4];
    if (n->cfg.nv != NULL && (s->boot_seen & ODG_BOOT_LOST_MASK) != 0u) {
        data[0] = s->boot_seen;
        memcpy(data + 1, s->boot_counts, 3);
        (void)odg_node_error_set(n, ODG_NODE_EMCY_STORAGE, 0, data, 4);
    }
}

/* Reset the dictionary, load the stored values when there is a driver (else every group runs
 * on defaults), and listen to changes of the communication entries. An NMT reset keeps the
 * clients attached (the application's among them), a power-on starts without. */
static odg_abort_t init_dict(odg_node_t *n, int keep_clients)
{
    const odg_dict_t *d = n->cfg.dict;
    odg_client_t *clients = d->state != NULL ? d->state->clients : NULL;
    uint8_t g;
    odg_abort_t ac = odg_init(d, n->cfg.node_id);
    if (ac != ODG_OK) {
        return ac;
    }
    if (keep_clients) {
        d->state->clients = clients;
    }
    if (n->cfg.nv != NULL && n->cfg.node_id != ODG_LSS_UNCONFIGURED) { /* no $NODEID values yet */
        ac = odg_persist_init(&n->persist, d, n->cfg.nv, n->cfg.boot);
    }
    for (g = 0; n->cfg.nv == NULL && n->cfg.boot != NULL && g < d->n_groups; g++) {
        n->cfg.boot[g] = ODG_BOOT_NV_ERROR;
    }
    n->client.changed = comm_changed;
    odg_attach(d, &n->client);
    return ac;
}

/* Initialising: drop the SDO transfer; for a reset of the node (`what` BOOT_RESET) or the first
 * boot (BOOT_POWER_ON) initialise the dictionary and copy its communication values, for a
 * reset of communication (BOOT_COMM) put that copy back; re-read the communication entries,
 * send the boot-up frame, and go pre-operational. */
static odg_abort_t boot(odg_node_t *n, int what)
{
    static const uint8_t bootup = 0x00;
    odg_abort_t ac = ODG_OK;
    n->state = ODG_NMT_INITIALISING;
    odg_sdo_drop_(n);
    if (odg_lss_activate_(n) && what == BOOT_COMM) {
        what = BOOT_RESET; /* a node-id from LSS: the $NODEID values change */
    }
    if (what != BOOT_COMM) {
        ac = init_dict(n, what == BOOT_RESET);
    }
    if (n->cfg.node_id == ODG_LSS_UNCONFIGURED) {
        return ac; /* waits for an LSS master, silent */
    }
    odg_err_reset_(n, what != BOOT_COMM); /* the errors of what was reset */
    if (what == BOOT_COMM) {
        (void)comm_walk(n, n->cfg.dict, COMM_BACK, 0);
        odg_changed(n->cfg.dict, NULL); /* the node re-reads them, the application hears of it */
    } else {
        (void)comm_walk(n, n->cfg.dict, COMM_KEEP, 0); /* the values reset communication restores */
        odg_node_reload(n);
    }
    n->hb_timer = 0;
    n->sync_prod_us = 0;
    n->sync_counter = 0;
    n->emcy_queued = 0;
    n->guard_started = 0;
    n->guard_toggle = 0;
    n->guard_lost = 0;
    (void)odg_node_send_(n, 0x700u + n->cfg.node_id, &bootup, 1);
    n->state = ODG_NMT_PRE_OPERATIONAL;
    if (what != BOOT_COMM) {
        stored_values_lost(n);
    }
    return ac;
}

static void enter(odg_node_t *n, odg_nmt_state_t s)
{
    if (n->state == (uint8_t)s) {
        return;
    }
    n->state = (uint8_t)s;
    if (s == ODG_NMT_STOPPED) {
        odg_sdo_drop_(n); /* no SDO in stopped: a transfer in progress is dropped silently */
    } else if (s == ODG_NMT_OPERATIONAL) {
        odg_pdo_start_(n);
    }
}

static void nmt(odg_node_t *n, const odg_frame_t *f)
{
    uint8_t cmd = f->data[0];
    if (f->len < 2u || (f->data[1] != 0u && f->data[1] != n->cfg.node_id)) {
        return;
    }
    if (n->state == ODG_NMT_INITIALISING && cmd != ODG_NMT_RESET_NODE && cmd != ODG_NMT_RESET_COMM) {
        return; /* waiting for LSS: only a reset */
    }
    switch (cmd) {
    case ODG_NMT_START:
        enter(n, ODG_NMT_OPERATIONAL);
        break;
    case ODG_NMT_STOP:
        enter(n, ODG_NMT_STOPPED);
        break;
    case ODG_NMT_ENTER_PREOP:
        enter(n, ODG_NMT_PRE_OPERATIONAL);
        break;
    case ODG_NMT_RESET_NODE:
        (void)boot(n, BOOT_RESET);
        break;
    case ODG_NMT_RESET_COMM:
        (void)boot(n, BOOT_COMM);
        break;
    default:
        return; /* unknown commands are ignored, as CiA 301 has no reply for them */
    }
    if (n->cfg.on_nmt) {
        n->cfg.on_nmt(n->cfg.app_ctx, cmd);
    }
}

/* ---- API ----------------------------------------------------------------------------------- */

odg_abort_t odg_node_init(odg_node_t *node, const odg_node_config_t *cfg)
{
    memset(node, 0, sizeof *node);
    node->cfg = *cfg;
    if (cfg->dict == NULL || cfg->send == NULL ||
        ((cfg->node_id < 1u || cfg->node_id > 127u) && !(ODG_NODE_LSS && cfg->node_id == ODG_LSS_UNCONFIGURED))) {
        return ODG_ABORT_INCOMPATIBLE;
    }
    odg_lss_init_(node); /* a node-id stored by an LSS master wins */
    return boot(node, BOOT_POWER_ON);
}

void odg_node_receive(odg_node_t *node, const odg_frame_t *frame)
{
    uint32_t id = frame->id;
    if (frame->flags == ODG_FRAME_RTR && node->state != ODG_NMT_INITIALISING) {
        odg_guard_rtr_(node, frame); /* remote frames: node guarding, and TPDOs 252/253 */
        if (node->state == ODG_NMT_OPERATIONAL) {
            odg_pdo_rtr_(node, frame);
        }
        return;
    }
    if ((frame->flags & (ODG_FRAME_RTR | ODG_FRAME_EFF)) || frame->len > 8u) {
        return;
    }
    if (ODG_NODE_LSS && id == ODG_LSS_MASTER_COB) {
        if (frame->len == 8u && odg_lss_receive_(node, frame->data)) {
            (void)boot(node, BOOT_RESET); /* configured by LSS: boot with the new node-id */
        }
    } else if (id == 0u) {
        nmt(node, frame); /* also while waiting for LSS (initialising): resets only */
    } else if (node->state == ODG_NMT_INITIALISING) {
        return;
    } else if (id > 0x700u && id <= 0x77Fu) {
        odg_hb_receive_(node, frame); /* heartbeats: only the consumer takes them */
    } else if (id == ODG_COB_ID(node->sdo_rx) && !(node->sdo_rx & ODG_COB_INVALID)) {
        if (node->state != ODG_NMT_STOPPED) {
            odg_sdo_receive_(node, frame);
        }
    } else if (id == ODG_COB_ID(node->time_cob) && (node->time_cob & ODG_TIME_CONSUME)) {
        if (node->state != ODG_NMT_STOPPED) {
            odg_time_receive_(node, frame);
        }
    } else if (node->state == ODG_NMT_OPERATIONAL) {
        if (id == ODG_COB_ID(node->sync_cob)) {
            odg_pdo_sync_(node, frame); /* 0x1005 bit 31 is "don't care" for a consumer */
        } else {
            odg_pdo_receive_(node, frame);
        }
    }
}

/* The heartbeat period is read from 0x1017 on every tick, so an SDO write (or an application
 * change) takes effect at once; 0 or an absent 0x1017 stops the heartbeat. */
static void heartbeat(odg_node_t *n, uint32_t ms)
{
    uint32_t period = odg_node_get_or_(n, 0x1017, 0, 0);
    uint32_t t = n->hb_timer + ms;
    if (period == 0u) {
        n->hb_timer = 0;
        return;
    }
    if (t < ms) {
        t = 0xFFFFFFFFu;
    }
    if (t >= period) {
        (void)odg_node_send_(n, 0x700u + n->cfg.node_id, &n->state, 1);
        t -= period; /* keep the phase when ticks do not divide the period ... */
        if (t >= period) {
            t = 0; /* ... but never send a burst after a long pause */
        }
    }
    n->hb_timer = t;
}

void odg_node_tick(odg_node_t *node, uint32_t elapsed_ms)
{
    if (node->state == ODG_NMT_INITIALISING) {
        return;
    }
    heartbeat(node, elapsed_ms);
    odg_sync_tick_(node, elapsed_ms);
    odg_hb_tick_(node, elapsed_ms);
    odg_emcy_tick_(node, elapsed_ms);
    odg_sdo_tick_(node, elapsed_ms);
    if (node->state == ODG_NMT_OPERATIONAL) {
        odg_pdo_tick_(node, elapsed_ms);
    }
}

odg_nmt_state_t odg_node_state(const odg_node_t *node)
{
    return (odg_nmt_state_t)node->state;
}

odg_abort_t odg_node_emcy(odg_node_t *node, uint16_t code, uint8_t error_register,
                          const uint8_t *vendor, uint8_t n_vendor)
{
    uint8_t d[8];
    odg_err_record_(node, code, vendor, n_vendor);
    if ((node->state != ODG_NMT_PRE_OPERATIONAL && node->state != ODG_NMT_OPERATIONAL) ||
        (node->emcy_cob & ODG_COB_INVALID)) {
        return ODG_ABORT_DATA_STATE;
    }
    memset(d, 0, sizeof d);
    d[0] = (uint8_t)code;
    d[1] = (uint8_t)(code >> 8);
    d[2] = error_register;
    if (vendor != NULL) {
        memcpy(d + 3, vendor, n_vendor < 5u ? n_vendor : 5u);
    }
    return odg_emcy_send_(node, d);
}

void odg_node_tpdo_request(odg_node_t *node, uint16_t n)
{
    if (node->state == ODG_NMT_OPERATIONAL && n < ODG_NODE_MAX_TPDO) {
        odg_pdo_request_(node, n);
    }
}
