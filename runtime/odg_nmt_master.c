/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_nmt_master.c - NMT master: commands, boot-up and heartbeat tracking, node guarding.
 * See odg_nmt_master.h.
 */
#include "odg_nmt_master.h"

static odg_nmtm_slave_t *find(odg_nmtm_t *m, uint8_t node_id)
{
    unsigned i;
    for (i = 0; i < ODG_MASTER_MAX_SLAVES; i++) {
        if (m->slave[i].id == node_id && node_id != 0u) {
            return &m->slave[i];
        }
    }
    return NULL;
}

void odg_nmtm_init(odg_nmtm_t *m, odg_send_fn send, void *send_ctx,
                   void (*on_event)(void *ctx, uint8_t node_id, uint8_t event), void *ctx)
{
    unsigned i;
    m->send = send;
    m->send_ctx = send_ctx;
    m->on_event = on_event;
    m->ctx = ctx;
    for (i = 0; i < ODG_MASTER_MAX_SLAVES; i++) {
        m->slave[i].id = 0;
    }
}

int odg_nmtm_command(odg_nmtm_t *m, uint8_t cs, uint8_t node_id)
{
    odg_frame_t f;
    unsigned i;
    f.id = 0;
    f.len = 2;
    f.flags = 0;
    f.data[0] = cs;
    f.data[1] = node_id;
    for (i = 2; i < 8u; i++) {
        f.data[i] = 0;
    }
    return m->send(m->send_ctx, &f);
}

int odg_nmtm_watch(odg_nmtm_t *m, uint8_t node_id, uint16_t hb_ms, uint16_t guard_ms, uint8_t retry)
{
    odg_nmtm_slave_t *s = find(m, node_id);
    unsigned i;
    for (i = 0; s == NULL && node_id >= 1u && node_id <= 127u && i < ODG_MASTER_MAX_SLAVES; i++) {
        if (m->slave[i].id == 0u) { /* a free slot */
            s = &m->slave[i];
            s->state = ODG_NMTM_UNKNOWN;
        }
    }
    if (s == NULL) {
        return -1;
    }
    s->id = node_id;
    s->hb_ms = hb_ms;
    s->guard_ms = hb_ms == 0u ? guard_ms : 0u;
    s->retry = retry == 0u ? 1u : retry;
    s->elapsed = 0;
    s->guard_left = 0;
    s->lost = 0;
    return 0;
}

void odg_nmtm_unwatch(odg_nmtm_t *m, uint8_t node_id)
{
    odg_nmtm_slave_t *s = find(m, node_id);
    if (s != NULL) {
        s->hb_ms = 0;
        s->guard_ms = 0;
    }
}

uint8_t odg_nmtm_state(const odg_nmtm_t *m, uint8_t node_id)
{
    unsigned i;
    for (i = 0; i < ODG_MASTER_MAX_SLAVES; i++) {
        if (m->slave[i].id == node_id && node_id != 0u) {
            return m->slave[i].state;
        }
    }
    return ODG_NMTM_UNKNOWN;
}

static void report(odg_nmtm_t *m, uint8_t node_id, uint8_t event)
{
    if (m->on_event != NULL) {
        m->on_event(m->ctx, node_id, event);
    }
}

int odg_nmtm_receive(odg_nmtm_t *m, const odg_frame_t *frame)
{
    odg_nmtm_slave_t *s;
    uint8_t state;
    if (frame->id < 0x701u || frame->id > 0x77Fu || frame->len < 1u ||
        (frame->flags & (ODG_FRAME_RTR | ODG_FRAME_EFF)) != 0u) {
        return 0;
    }
    s = find(m, (uint8_t)(frame->id - 0x700u));
    if (s == NULL) {
        return 0;
    }
    state = (uint8_t)(frame->data[0] & 0x7Fu); /* bit 7: the guarding answer's toggle */
    s->elapsed = 0;
    s->lost = 0;
    if (state == ODG_NMTM_BOOTUP) {
        s->state = ODG_NMT_PRE_OPERATIONAL; /* where a node goes after its boot-up */
        report(m, s->id, ODG_NMTM_BOOTUP);
    } else if (state != s->state) {
        s->state = state;
        report(m, s->id, state);
    }
    return 1;
}

static void guard(odg_nmtm_t *m, odg_nmtm_slave_t *s, uint32_t elapsed_ms)
{
    odg_frame_t f;
    if (s->guard_left > elapsed_ms) {
        s->guard_left -= elapsed_ms;
        return;
    }
    s->guard_left = s->guard_ms;
    f.id = 0x700u + s->id;
    f.len = 1;
    f.flags = ODG_FRAME_RTR;
    f.data[0] = 0;
    (void)m->send(m->send_ctx, &f);
}

void odg_nmtm_tick(odg_nmtm_t *m, uint32_t elapsed_ms)
{
    unsigned i;
    for (i = 0; i < ODG_MASTER_MAX_SLAVES; i++) {
        odg_nmtm_slave_t *s = &m->slave[i];
        uint32_t limit = s->hb_ms != 0u ? s->hb_ms : (uint32_t)s->guard_ms * s->retry;
        if (s->id == 0u || limit == 0u || s->lost) {
            continue;
        }
        if (s->hb_ms == 0u) {
            guard(m, s, elapsed_ms);
        }
        s->elapsed = s->elapsed + elapsed_ms < s->elapsed ? 0xFFFFFFFFu : s->elapsed + elapsed_ms;
        if (s->elapsed > limit) {
            s->lost = 1;
            s->state = ODG_NMTM_UNKNOWN;
            report(m, s->id, ODG_HB_TIMEOUT);
        }
    }
}
