/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_master.c - the CiA 302-2 configuration manager. See odg_master.h and docs/master.md.
 *
 * Each slave runs its own boot-up process on its own SDO client channel, so slaves boot side
 * by side: wait for it, 0x1000 against 0x1F84, 0x1018 sub 1..4 against 0x1F85..0x1F88 (where
 * non-zero), 0x1020 against 0x1F26/0x1F27 (when both are non-zero; equal: no download), the
 * concise DCF of 0x1F22 entry by entry, then error control and the start.
 */
#include "odg_master.h"

/* odg_master_slave_t.phase */
#define P_IDLE 0u    /* not assigned */
#define P_WAIT 1u    /* waiting: the next attempt when `timer` runs out, or at a boot-up */
#define P_DEVTYPE 2u /* uploading 0x1000 */
#define P_IDENT 3u   /* uploading 0x1018 sub `step` */
#define P_DATE 4u    /* uploading 0x1020 sub `step` */
#define P_HBTIME 5u  /* keep-alive, its NMT state unknown: uploading its heartbeat time 0x1017 */
#define P_DCF 6u     /* downloading concise DCF entries */
#define P_DONE 7u    /* booted (or found operational): error control runs */
#define P_FAILED 8u  /* a check failed: boots again at its next boot-up */
#define P_STATE 9u   /* keep-alive: waiting `timer` ms for its first heartbeat (its NMT state) */

#define DCF_HEADER 7u /* index (2), sub (1), size (4) before each entry's data */

/* odg_master_t.lss_step */
#define LSS_OVER 0u
#define LSS_SCAN 1u      /* fastscan for the identity of slave[lss_slave] */
#define LSS_NODE_ID 2u   /* configuring the node-id of the slave found */
#define LSS_STORE 3u     /* storing it */

static uint32_t array_u32(const odg_master_t *m, uint16_t index, uint8_t sub)
{
    uint32_t v = 0;
    return odg_get_u32(m->cfg.dict, index, sub, &v) == ODG_OK ? v : 0u;
}

static odg_master_slave_t *find(odg_master_t *m, uint8_t node_id)
{
    unsigned i;
    for (i = 0; i < m->n_slaves; i++) {
        if (m->slave[i].id == node_id) {
            return &m->slave[i];
        }
    }
    return NULL;
}

static odg_sdoc_t *channel(odg_master_t *m, const odg_master_slave_t *s)
{
    return &m->sdo[s - m->slave];
}

static int is_error(uint8_t status)
{
    return status >= 'A' && status <= 'Z';
}

static void set_status(odg_master_t *m, odg_master_slave_t *s, uint8_t status)
{
    uint8_t vendor[2];
    if (s->status == status) {
        return;
    }
    s->status = status;
    (void)odg_set_u8(m->cfg.dict, ODG_MASTER_STATUS_INDEX, s->id, status);
    if (is_error(status) && status != ODG_SLAVE_OPERATIONAL && m->cfg.node != NULL) {
        vendor[0] = status;
        vendor[1] = s->id;
        (void)odg_node_emcy(m->cfg.node,
                            status == ODG_SLAVE_HEARTBEAT || status == ODG_SLAVE_GUARDING ? ODG_MASTER_EMCY_LOST
                                                                                         : ODG_MASTER_EMCY_BOOT,
                            m->cfg.node->error_register, vendor, 2);
    }
    if (m->cfg.on_status != NULL) {
        m->cfg.on_status(m->cfg.ctx, s->id, status);
    }
}

/* An NMT command: on the bus unless it is for the master alone, and to the master's own node
 * when it concerns it. */
static void command(odg_master_t *m, uint8_t cs, uint8_t node_id)
{
    odg_frame_t f;
    int own = node_id == m->cfg.dict->state->node_id;
    if (!own) {
        (void)odg_nmtm_command(&m->nmt, cs, node_id);
    }
    if (m->cfg.node != NULL && (node_id == 0u || own)) {
        f.id = 0;
        f.len = 2;
        f.flags = 0;
        f.data[0] = cs;
        f.data[1] = node_id;
        odg_node_receive(m->cfg.node, &f);
    }
}

static void upload(odg_master_t *m, odg_master_slave_t *s, uint8_t phase, uint16_t index, uint8_t sub)
{
    s->phase = phase;
    if (odg_sdoc_upload(channel(m, s), index, sub, s->value, sizeof s->value) != ODG_OK) {
        s->phase = P_WAIT; /* could not send: try again later */
        s->timer = ODG_MASTER_RETRY_MS;
    }
}

/* The boot-up process from its start. A retry of a slave that is absent or was lost keeps its
 * error status until the slave answers; a boot-up message or the master's start announces it. */
static void begin(odg_master_t *m, odg_master_slave_t *s, int announce)
{
    odg_sdoc_abort(channel(m, s), ODG_ABORT_GENERAL); /* a transfer of the boot before */
    odg_nmtm_unwatch(&m->nmt, s->id);
    if (announce || !is_error(s->status)) {
        set_status(m, s, ODG_SLAVE_BOOTING);
    }
    upload(m, s, P_DEVTYPE, 0x1000u, 0);
}

static void try_later(odg_master_slave_t *s, uint32_t ms)
{
    s->phase = P_WAIT;
    s->timer = ms;
}

static void check_network(odg_master_t *m);

/* A check failed: report it. A slave that did not answer (absent, or an SDO timeout in any
 * step: status B) is tried again; a wrong one at its next boot-up. No answer from a slave already in error (lost, or
 * absent before) keeps that error. */
static void fail(odg_master_t *m, odg_master_slave_t *s, uint8_t status)
{
    int silent = status == ODG_SLAVE_NO_ANSWER || s->abort == ODG_ABORT_TIMEOUT;
    status = silent ? ODG_SLAVE_NO_ANSWER : status;
    if (!silent || !is_error(s->status)) {
        set_status(m, s, status);
    }
    s->tried = 1;
    if (silent) {
        try_later(s, ODG_MASTER_RETRY_MS);
    } else {
        s->phase = P_FAILED;
    }
    check_network(m);
}

/* Heartbeat consumer time the master has for `node_id` (0x1016), 0 when none. */
static uint16_t heartbeat_ms(const odg_master_t *m, uint8_t node_id)
{
    uint8_t n = 0, i;
    uint32_t v;
    (void)odg_get_u8(m->cfg.dict, 0x1016u, 0, &n);
    for (i = 1; i <= n; i++) {
        v = array_u32(m, 0x1016u, i);
        if ((uint8_t)(v >> 16) == node_id && (uint16_t)v != 0u) {
            return (uint16_t)v;
        }
    }
    return 0;
}

static void start_error_control(odg_master_t *m, odg_master_slave_t *s)
{
    (void)odg_nmtm_watch(&m->nmt, s->id, heartbeat_ms(m, s->id), (uint16_t)(s->assignment >> 16),
                         (uint8_t)(s->assignment >> 8));
}

/* Configured: error control, and the start once the network is up. */
static void booted(odg_master_t *m, odg_master_slave_t *s)
{
    s->phase = P_DONE;
    s->tried = 1;
    start_error_control(m, s);
    set_status(m, s, ODG_SLAVE_BOOTED);
    if (m->network_up && (m->startup & ODG_STARTUP_NO_START) == 0u) {
        command(m, ODG_NMT_START, s->id);
    }
    check_network(m);
}

/* The network comes up once every mandatory slave booted and every other had a first try:
 * the slaves are started (one command to all when every slave booted and 0x1F80 bit 1 asks for
 * it, else each booted one), then the master itself unless 0x1F80 bit 2 is set. */
static void check_network(odg_master_t *m)
{
    unsigned i;
    int all = 1;
    if (m->network_up) {
        return;
    }
    for (i = 0; i < m->n_slaves; i++) {
        const odg_master_slave_t *s = &m->slave[i];
        if (!s->tried || ((s->assignment & ODG_ASSIGN_MANDATORY) != 0u && s->phase != P_DONE)) {
            return;
        }
        all = all && s->status == ODG_SLAVE_BOOTED;
    }
    m->network_up = 1;
    m->boot_left = 0;
    if ((m->startup & ODG_STARTUP_NO_START) == 0u) {
        if (all && (m->startup & ODG_STARTUP_START_ALL) != 0u) {
            (void)odg_nmtm_command(&m->nmt, ODG_NMT_START, 0);
        } else {
            for (i = 0; i < m->n_slaves; i++) {
                if (m->slave[i].status == ODG_SLAVE_BOOTED) {
                    (void)odg_nmtm_command(&m->nmt, ODG_NMT_START, m->slave[i].id);
                }
            }
        }
    }
    if ((m->startup & ODG_STARTUP_NO_SELF) == 0u && m->cfg.node != NULL) {
        command(m, ODG_NMT_START, m->cfg.dict->state->node_id);
    }
}

/* The next concise DCF entry, or the end of the configuration. */
static void next_entry(odg_master_t *m, odg_master_slave_t *s)
{
    odg_ref_t ref;
    uint8_t h[DCF_HEADER];
    uint32_t n = 0, size, length;
    if (s->dcf_left == 0u) {
        booted(m, s);
        return;
    }
    if (odg_find(m->cfg.dict, 0x1F22u, s->id, &ref) != ODG_OK) {
        fail(m, s, ODG_SLAVE_DOWNLOAD);
        return;
    }
    length = odg_length(&ref);
    if (odg_read(&ref, s->dcf_at, h, DCF_HEADER, &n) != ODG_OK || n != DCF_HEADER) {
        s->abort = ODG_ABORT_DATA_LOCAL;
        fail(m, s, ODG_SLAVE_DOWNLOAD);
        return;
    }
    size = odg_sdoc_u32(h + 3, 4);
    if (size > length - s->dcf_at - DCF_HEADER) { /* the entry runs past the DCF's end */
        s->abort = ODG_ABORT_DATA_LOCAL;
        fail(m, s, ODG_SLAVE_DOWNLOAD);
        return;
    }
    s->phase = P_DCF;
    s->dcf_left--;
    if (odg_sdoc_download_ref(channel(m, s), (uint16_t)(h[0] | (uint32_t)h[1] << 8), h[2], &ref, s->dcf_at + DCF_HEADER,
                              size) != ODG_OK) {
        try_later(s, ODG_MASTER_RETRY_MS);
    }
    s->dcf_at += DCF_HEADER + size;
}

static void download(odg_master_t *m, odg_master_slave_t *s)
{
    odg_ref_t ref;
    uint8_t c[4];
    uint32_t n = 0;
    s->dcf_at = 4;
    s->dcf_left = 0;
    if (s->same_date) {
        booted(m, s); /* 0x1020 says the slave holds this configuration already */
        return;
    }
    if (odg_find(m->cfg.dict, 0x1F22u, s->id, &ref) == ODG_OK && odg_length(&ref) >= 4u &&
        odg_read(&ref, 0, c, 4, &n) == ODG_OK && n == 4u) {
        s->dcf_left = odg_sdoc_u32(c, 4);
    }
    next_entry(m, s);
}

/* A keep-alive slave checked (device type, identity, date) that runs operational is left as it
 * runs (CiA 302-2 'L'); one known in another state is configured. Its state unknown (no
 * heartbeat heard yet), the master reads its heartbeat time and waits that long for one. */
static void keep_alive_configure(odg_master_t *m, odg_master_slave_t *s)
{
    uint8_t state = odg_nmtm_state(&m->nmt, s->id);
    if (state == ODG_NMT_OPERATIONAL) {
        set_status(m, s, ODG_SLAVE_OPERATIONAL);
        s->phase = P_DONE;
        s->tried = 1;
        start_error_control(m, s);
        check_network(m);
    } else if (state == ODG_NMTM_UNKNOWN && s->phase != P_HBTIME && s->phase != P_STATE) {
        upload(m, s, P_HBTIME, 0x1017u, 0);
    } else {
        download(m, s);
    }
}

static void configure(odg_master_t *m, odg_master_slave_t *s)
{
    if ((s->assignment & ODG_ASSIGN_KEEP_ALIVE) != 0u) {
        keep_alive_configure(m, s);
    } else {
        download(m, s);
    }
}

/* One node guarding remote frame: its answer tells the slave's NMT state. */
static void ask_state(odg_master_t *m, const odg_master_slave_t *s)
{
    odg_frame_t f;
    f.id = 0x700u + s->id;
    f.len = 1;
    f.flags = ODG_FRAME_RTR;
    f.data[0] = 0;
    (void)m->cfg.send(m->cfg.send_ctx, &f);
}

/* Its heartbeat time read: a heartbeat comes within it (half again for the jitter). It produces
 * none (0, or no 0x1017): guarded (0x1F81 guard time), it is asked once and has the guard time
 * to answer; else no state will come and it is configured at once. */
static void await_state(odg_master_t *m, odg_master_slave_t *s, int ok, uint32_t hb_ms)
{
    uint32_t guard_ms = s->assignment >> 16, wait_ms = ok ? hb_ms : 0u;
    if (odg_nmtm_state(&m->nmt, s->id) == ODG_NMTM_UNKNOWN && wait_ms == 0u && guard_ms != 0u) {
        ask_state(m, s);
        wait_ms = guard_ms;
    }
    if (odg_nmtm_state(&m->nmt, s->id) != ODG_NMTM_UNKNOWN || wait_ms == 0u) {
        keep_alive_configure(m, s);
        return;
    }
    s->phase = P_STATE;
    s->timer = wait_ms + wait_ms / 2u;
}

/* The configuration date and time (0x1020) when 0x1F26 and 0x1F27 expect one. */
static void check_date(odg_master_t *m, odg_master_slave_t *s, uint8_t sub)
{
    s->step = sub;
    if (array_u32(m, 0x1F26u, s->id) == 0u || array_u32(m, 0x1F27u, s->id) == 0u || sub > 2u) {
        configure(m, s);
        return;
    }
    upload(m, s, P_DATE, 0x1020u, sub);
}

/* 0x1018 sub `sub` onwards, skipping those 0x1F85..0x1F88 do not check. */
static void check_identity(odg_master_t *m, odg_master_slave_t *s, uint8_t sub)
{
    while (sub <= 4u && array_u32(m, (uint16_t)(0x1F84u + sub), s->id) == 0u) {
        sub++;
    }
    s->step = sub;
    if (sub > 4u) {
        s->same_date = 0;
        check_date(m, s, 1);
        return;
    }
    upload(m, s, P_IDENT, 0x1018u, sub);
}

/* The channel finished the transfer of the current phase. */
static void step(odg_master_t *m, odg_master_slave_t *s)
{
    static const uint8_t identity_error[5] = {0, ODG_SLAVE_VENDOR, ODG_SLAVE_PRODUCT, ODG_SLAVE_REVISION,
                                              ODG_SLAVE_SERIAL};
    const odg_sdoc_t *ch = channel(m, s);
    int ok = ch->state == ODG_SDOC_DONE;
    uint32_t v = odg_sdoc_u32(s->value, ch->n);
    s->abort = ok ? 0u : ch->abort;
    switch (s->phase) {
    case P_DEVTYPE:
        if (!ok) {
            fail(m, s, ODG_SLAVE_NO_ANSWER);
            break;
        }
        set_status(m, s, ODG_SLAVE_BOOTING); /* it answers: a retry's error status ends */
        if (array_u32(m, 0x1F84u, s->id) != 0u && v != array_u32(m, 0x1F84u, s->id)) {
            fail(m, s, ODG_SLAVE_DEVICE_TYPE);
        } else {
            check_identity(m, s, 1);
        }
        break;
    case P_IDENT:
        if (!ok || v != array_u32(m, (uint16_t)(0x1F84u + s->step), s->id)) {
            fail(m, s, identity_error[s->step]);
        } else {
            check_identity(m, s, (uint8_t)(s->step + 1u));
        }
        break;
    case P_DATE:
        if (ok && v == array_u32(m, (uint16_t)(0x1F25u + s->step), s->id)) {
            s->same_date = s->step == 1u ? 1u : s->same_date;
            check_date(m, s, (uint8_t)(s->step + 1u));
        } else {
            s->same_date = 0;
            configure(m, s);
        }
        break;
    case P_HBTIME:
        await_state(m, s, ok, v & 0xFFFFu);
        break;
    case P_DCF:
        if (!ok) {
            fail(m, s, ODG_SLAVE_DOWNLOAD);
        } else {
            next_entry(m, s);
        }
        break;
    default:
        break;
    }
}

/* The whole network boots again after an NMT reset node to all nodes (the master's own node
 * included, whose dictionary, and so the status object, went back to its defaults): every slave
 * waits for its boot-up as at the master's start, and the slaves are started again once the
 * network is up. */
static void reboot_all(odg_master_t *m)
{
    unsigned i;
    m->network_up = 0;
    for (i = 0; i < m->n_slaves; i++) {
        odg_master_slave_t *s = &m->slave[i];
        odg_sdoc_abort(&m->sdo[i], ODG_ABORT_GENERAL);
        odg_nmtm_unwatch(&m->nmt, s->id);
        s->status = 0xFFu; /* written again whatever the cache says */
        set_status(m, s, ODG_SLAVE_BOOTING);
        s->tried = 0;
        try_later(s, ODG_MASTER_RETRY_MS);
    }
}

/* Error control lost a booted slave: report it, then as 0x1F80 and 0x1F81 say. A mandatory
 * slave lost stops every node (bit 6; the application decides what follows) or resets them all
 * (bit 4); otherwise it is reset alone, and tried again from time to time when it is mandatory
 * or 0x1F81 bit 2 says so (else its boot-up begins its boot). */
static void lost(odg_master_t *m, odg_master_slave_t *s)
{
    int mandatory = (s->assignment & ODG_ASSIGN_MANDATORY) != 0u;
    set_status(m, s, heartbeat_ms(m, s->id) != 0u ? ODG_SLAVE_HEARTBEAT : ODG_SLAVE_GUARDING);
    if (mandatory && (m->startup & ODG_STARTUP_STOP_ALL) != 0u) {
        command(m, ODG_NMT_STOP, 0);
        s->phase = P_FAILED; /* until its boot-up */
    } else if (mandatory && (m->startup & ODG_STARTUP_RESET_ALL) != 0u) {
        command(m, ODG_NMT_RESET_NODE, 0);
        reboot_all(m);
    } else {
        /* reset it: heard, its boot-up begins its boot; else the retries find it (bit 2) */
        command(m, ODG_NMT_RESET_NODE, s->id);
        if (mandatory || (s->assignment & ODG_ASSIGN_REBOOT) != 0u) {
            try_later(s, ODG_MASTER_RETRY_MS);
        } else {
            s->phase = P_FAILED;
        }
    }
}

static void on_nmt_event(void *ctx, uint8_t node_id, uint8_t event)
{
    odg_master_t *m = (odg_master_t *)ctx;
    odg_master_slave_t *s = find(m, node_id);
    if (s == NULL) {
        return;
    }
    if (event == ODG_NMTM_BOOTUP) {
        begin(m, s, 1); /* a slave that (re)booted is configured again */
    } else if (event == ODG_HB_TIMEOUT) {
        if (s->phase == P_DONE) {
            lost(m, s);
        }
    } else if ((s->assignment & ODG_ASSIGN_KEEP_ALIVE) != 0u) {
        /* a keep-alive slave's first heartbeat (it sends no boot-up): its boot at once, or the
         * state its boot waited for */
        if (s->phase == P_WAIT) {
            begin(m, s, 0);
        } else if (s->phase == P_STATE) {
            keep_alive_configure(m, s);
        }
    }
}

/* The identity the master expects of `s` (0x1F85..0x1F88) into want[]: bit k of the result set
 * when part k is non-zero. */
static uint8_t expected_identity(const odg_master_t *m, const odg_master_slave_t *s, uint32_t want[4])
{
    uint8_t known = 0, k;
    for (k = 0; k < 4u; k++) {
        want[k] = array_u32(m, (uint16_t)(0x1F85u + k), s->id);
        known = (uint8_t)(known | (want[k] != 0u ? 1u << k : 0u));
    }
    return known;
}

/* Node-ids by LSS: for each assigned slave whose vendor-ID and product code the master expects
 * (0x1F85, 0x1F86; with 0x1F87, 0x1F88 when non-zero), a fastscan for that identity (the parts
 * known take one question each); the slave found gets its node-id (and stores it) and stays in
 * configuration mode. After the last (after the one slave of a retry), every slave goes back to
 * waiting: those configured boot with their node-ids, and their boot-up processes begin. */
static void lss_target(odg_master_t *m)
{
    uint32_t want[4];
    uint8_t known;
    m->lss_tries++;
    for (; m->lss_slave < m->n_slaves; m->lss_slave++, m->lss_tries = 1) {
        known = expected_identity(m, &m->slave[m->lss_slave], want);
        if ((known & 3u) == 3u) {
            m->lss_step = LSS_SCAN;
            (void)odg_lssm_fastscan_known(&m->lss, want, known);
            return;
        }
    }
    m->lss_step = LSS_OVER;
    m->lss_only = 0;
    (void)odg_lssm_switch_global(&m->lss, ODG_LSS_WAITING);
}

static void lss_next(odg_master_t *m)
{
    if (m->lss.state == ODG_LSSM_BUSY) {
        return;
    }
    if (m->lss_step == LSS_SCAN && m->lss.state == ODG_LSSM_DONE) {
        m->lss_step = LSS_NODE_ID;
        (void)odg_lssm_configure_node_id(&m->lss, m->slave[m->lss_slave].id);
    } else if (m->lss_step == LSS_NODE_ID && m->lss.state == ODG_LSSM_DONE && m->cfg.lss == ODG_MASTER_LSS_STORE) {
        m->lss_step = LSS_STORE;
        (void)odg_lssm_store(&m->lss);
    } else if (m->lss_step == LSS_SCAN && m->lss.waiting_seen && m->lss_tries < ODG_MASTER_LSS_TRIES) {
        lss_target(m); /* slaves without node-id answered, but the scan went astray: again */
    } else { /* not found, configured, stored or refused: the next slave (none after a retry's) */
        m->lss_slave = m->lss_only ? m->n_slaves : (uint8_t)(m->lss_slave + 1u);
        m->lss_tries = 0;
        lss_target(m);
    }
}

/* A retry of slave `i` that LSS could give a node-id: a fastscan for it alone first (a slave
 * without node-id that powered up after the master's start). */
static void lss_retry(odg_master_t *m, uint8_t i)
{
    uint32_t want[4];
    if (m->cfg.lss == 0u || m->lss_step != LSS_OVER || (expected_identity(m, &m->slave[i], want) & 3u) != 3u) {
        return;
    }
    m->lss_slave = i;
    m->lss_only = 1;
    m->lss_tries = 0;
    lss_target(m);
}

/* Slave `node_id` of assignment `a`: its channel, tracked by the NMT master, reset; its boot
 * begins at its boot-up, or at the first retry when none comes. A keep-alive slave is not reset
 * and sends no boot-up: its boot begins at once (CiA 302-2: its state is checked, not reset). */
static void add_slave(odg_master_t *m, uint8_t node_id, uint32_t a)
{
    odg_master_slave_t *s = &m->slave[m->n_slaves];
    uint32_t tx, rx;
    s->assignment = a;
    s->id = node_id;
    s->status = 0xFFu; /* set_status below always writes */
    s->tried = 0;
    s->same_date = 0;
    s->abort = 0;
    odg_sdoc_cobs(m->cfg.dict, node_id, &tx, &rx);
    odg_sdoc_init(&m->sdo[m->n_slaves], node_id, tx, rx, m->cfg.send, m->cfg.send_ctx);
    (void)odg_nmtm_watch(&m->nmt, node_id, 0, 0, 0); /* boot-ups and states from now on */
    m->n_slaves++;
    set_status(m, s, ODG_SLAVE_BOOTING);
    if ((a & ODG_ASSIGN_KEEP_ALIVE) != 0u) {
        begin(m, s, 1);
    } else {
        try_later(s, ODG_MASTER_RETRY_MS);
        (void)odg_nmtm_command(&m->nmt, ODG_NMT_RESET_COMM, node_id);
    }
}

odg_abort_t odg_master_init(odg_master_t *m, const odg_master_config_t *cfg)
{
    unsigned i;
    uint32_t a;
    odg_abort_t ac = ODG_OK;
    m->n_slaves = 0;
    m->network_up = 0;
    m->lss_step = LSS_OVER;
    m->lss_only = 0;
    if (cfg == NULL || cfg->dict == NULL || cfg->send == NULL) {
        return ODG_ABORT_INCOMPATIBLE;
    }
    m->cfg = *cfg;
    odg_nmtm_init(&m->nmt, cfg->send, cfg->send_ctx, on_nmt_event, m);
    m->startup = array_u32(m, 0x1F80u, 0);
    m->boot_left = array_u32(m, 0x1F89u, 0);
    if ((m->startup & ODG_STARTUP_MASTER) == 0u) {
        return ODG_ABORT_DATA_STATE;
    }
    for (i = 1; i <= 127u; i++) {
        a = array_u32(m, 0x1F81u, (uint8_t)i);
        if ((a & ODG_ASSIGN_SLAVE) == 0u || i == cfg->dict->state->node_id) {
            continue;
        }
        if (m->n_slaves == ODG_MASTER_MAX_SLAVES) {
            ac = ODG_ABORT_NO_RESOURCE;
            break;
        }
        add_slave(m, (uint8_t)i, a);
    }
    if (cfg->lss != 0u && m->n_slaves > 0u) {
        odg_lssm_init(&m->lss, cfg->send, cfg->send_ctx, 0);
        m->lss_slave = 0;
        m->lss_tries = 0;
        m->lss_only = 0;
        lss_target(m);
    }
    check_network(m); /* no slave at all: the master starts itself */
    return ac;
}

void odg_master_receive(odg_master_t *m, const odg_frame_t *frame)
{
    unsigned i;
    if (m->lss_step != LSS_OVER && odg_lssm_receive(&m->lss, frame)) {
        lss_next(m);
        return;
    }
    if (odg_nmtm_receive(&m->nmt, frame)) {
        return;
    }
    for (i = 0; i < m->n_slaves; i++) {
        if (odg_sdoc_receive(&m->sdo[i], frame)) {
            if (m->sdo[i].state != ODG_SDOC_BUSY && m->slave[i].phase >= P_DEVTYPE && m->slave[i].phase <= P_DCF) {
                step(m, &m->slave[i]);
            }
            return;
        }
    }
}

void odg_master_process(odg_master_t *m, uint32_t elapsed_ms)
{
    unsigned i;
    odg_nmtm_tick(&m->nmt, elapsed_ms);
    if (m->lss_step != LSS_OVER) {
        odg_lssm_tick(&m->lss, elapsed_ms);
        lss_next(m);
    }
    for (i = 0; i < m->n_slaves; i++) {
        odg_master_slave_t *s = &m->slave[i];
        odg_sdoc_tick(&m->sdo[i], elapsed_ms);
        if (s->phase == P_WAIT && m->lss_step != LSS_OVER) {
            continue; /* no attempt without a boot-up while node-ids are given */
        }
        if (s->phase == P_WAIT || s->phase == P_STATE) {
            s->timer = s->timer > elapsed_ms ? s->timer - elapsed_ms : 0u;
        }
        if (s->phase == P_WAIT && s->timer == 0u) {
            begin(m, s, 0);
            lss_retry(m, (uint8_t)i);
        } else if (s->phase == P_STATE && s->timer == 0u) {
            download(m, s); /* no heartbeat within its time: not operational */
        } else if (s->phase >= P_DEVTYPE && s->phase <= P_DCF && m->sdo[i].state != ODG_SDOC_BUSY) {
            step(m, s); /* timed out */
        }
    }
    if (m->boot_left != 0u && m->lss_step == LSS_OVER) {
        m->boot_left = m->boot_left > elapsed_ms ? m->boot_left - elapsed_ms : 0u;
        if (m->boot_left == 0u && !m->network_up && m->cfg.on_status != NULL) {
            m->cfg.on_status(m->cfg.ctx, 0, ODG_MASTER_BOOT_TIMEOUT);
        }
    }
}

const odg_master_slave_t *odg_master_slave(const odg_master_t *m, uint8_t node_id)
{
    unsigned i;
    for (i = 0; i < m->n_slaves; i++) {
        if (m->slave[i].id == node_id) {
            return &m->slave[i];
        }
    }
    return NULL;
}

void odg_master_reboot(odg_master_t *m, uint8_t node_id)
{
    odg_master_slave_t *s = find(m, node_id);
    if (s != NULL) {
        begin(m, s, 1);
    }
}
