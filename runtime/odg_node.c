/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_node.c - the hub of the CANopen node: NMT slave (boot, the state machine, resets), frame
 * dispatch and ticks, and the dictionary client that tells each service of a change to its
 * communication entries. It calls the services (odg_sdo.c, odg_sync.c, odg_pdo.c, odg_hb.c,
 * odg_err.c, odg_comm.c, odg_lss.c, odg_time.c) and the helpers of odg_node_io.c; none of them
 * calls it (docs/design.md, "The node runtime"). See odg_node.h.
 */
#include <string.h>

#include "odg_node.h"

/* ---- the services' communication entries ---------------------------------------------- */

/* COB-IDs of SYNC, EMCY and TIME: re-read whenever one of them changes. */
static void load_cobs(odg_node_t *n)
{
    uint32_t id = n->cfg.node_id;
    n->sync.cob = odg_io_get_or_(n, 0x1005, 0, 0x80u);
    n->err.cob = odg_io_get_or_(n, 0x1014, 0, 0x80u + id);
    n->time.cob = odg_io_num_(n, 0x1012, 0);
}

/* The SDO server's COB-IDs from 0x1200 (without it, the pre-defined 0x600/0x580 + node-id), read
 * at boot and by odg_node_reload only: a write to 0x1200 takes effect at the next reset of
 * communication, so the answer to that write still goes where the client waits for it. Bit 31
 * of either (or a 29-bit COB-ID, whose frames the node ignores) disables the server. */
static void load_sdo_cobs(odg_node_t *n)
{
    uint32_t id = n->cfg.node_id;
    n->sdo_rx = odg_io_get_or_(n, 0x1200, 1, 0x600u + id);
    n->sdo_tx = odg_io_get_or_(n, 0x1200, 2, 0x580u + id);
    if ((n->sdo_tx | n->sdo_rx) & (ODG_COB_INVALID | ODG_COB_EXTENDED)) {
        n->sdo_rx |= ODG_COB_INVALID;
    }
}

/* A value changed, whoever wrote it (SDO server, application, persistence layer): the service
 * whose communication entry it is reads it again. */
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
    odg_abort_t ac = ODG_OK;
    n->state = ODG_NMT_INITIALISING;
    n->sdo.state = ODG_SDO_IDLE;
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
        odg_comm_back_(n);
        odg_changed(n->cfg.dict, NULL); /* the node re-reads them, the application hears of it */
    } else {
        odg_node_comm_keep(n); /* the values reset communication restores */
        odg_node_reload(n);
    }
    /* the services' timers and queues start afresh */
    n->sync.prod_us = 0;
    n->sync.counter = 0;
    n->err.queued = 0;
    (void)odg_io_send_(n, 0x700u + n->cfg.node_id, &n->state, 1); /* boot-up: 0, initialising */
    n->state = ODG_NMT_PRE_OPERATIONAL;
    if (what != BOOT_COMM) {
        stored_values_lost(n);
    }
    odg_hb_boot_(n);
    return ac;
}

static void enter(odg_node_t *n, odg_nmt_state_t s)
{
    if (n->state == (uint8_t)s) {
        return;
    }
    n->state = (uint8_t)s;
    if (s == ODG_NMT_STOPPED) {
        n->sdo.state = ODG_SDO_IDLE; /* no SDO in stopped: a transfer in progress is dropped silently */
    } else if (s == ODG_NMT_OPERATIONAL) {
        odg_pdo_start_(n);
    }
}

/* An NMT command addressed to the node, from the master or from a communication error
 * (0x1029); then the application hears of it. */
static void command(odg_node_t *n, uint8_t cmd)
{
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
        return; /* unknown commands (and 0: none) are ignored, as CiA 301 has no reply for them */
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
        odg_hb_rtr_(node, frame); /* remote frames: node guarding, and TPDOs 252/253 */
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
        /* also while waiting for LSS (initialising): resets only */
        if (frame->len >= 2u && (frame->data[1] == 0u || frame->data[1] == node->cfg.node_id)) {
            command(node, frame->data[0]);
        }
    } else if (node->state == ODG_NMT_INITIALISING) {
        return;
    } else if (id > 0x700u && id <= 0x77Fu) {
        odg_hb_receive_(node, frame); /* heartbeats: only the consumer takes them */
    } else if (id == ODG_COB_ID(node->sdo_rx) && !(node->sdo_rx & ODG_COB_INVALID)) {
        if (node->state != ODG_NMT_STOPPED) {
            odg_sdo_receive_(node, frame);
        }
    } else if (id == ODG_COB_ID(node->time.cob) && (node->time.cob & ODG_TIME_CONSUME)) {
        if (node->state != ODG_NMT_STOPPED) {
            odg_time_receive_(node, frame);
        }
    } else if (node->state == ODG_NMT_OPERATIONAL) {
        if (id == ODG_COB_ID(node->sync.cob)) {
            odg_sync_receive_(node, frame); /* 0x1005 bit 31 is "don't care" for a consumer */
        } else {
            odg_pdo_receive_(node, frame);
        }
    }
}

void odg_node_tick(odg_node_t *node, uint32_t elapsed_ms)
{
    if (node->state == ODG_NMT_INITIALISING) {
        return;
    }
    odg_hb_produce_(node, elapsed_ms);
    odg_sync_tick_(node, elapsed_ms);
    command(node, odg_hb_tick_(node, elapsed_ms));
    odg_err_tick_(node, elapsed_ms);
    odg_sdo_tick_(node, elapsed_ms);
    if (node->state == ODG_NMT_OPERATIONAL) {
        odg_pdo_tick_(node, elapsed_ms);
    }
}

odg_nmt_state_t odg_node_state(const odg_node_t *node)
{
    return (odg_nmt_state_t)node->state;
}

void odg_node_tpdo_request(odg_node_t *node, uint16_t n)
{
    if (node->state == ODG_NMT_OPERATIONAL && n < ODG_NODE_MAX_TPDO) {
        odg_pdo_request_(node, n);
    }
}

void odg_node_can_state(odg_node_t *node, odg_can_state_t state)
{
    command(node, odg_hb_can_state_(node, state));
}
