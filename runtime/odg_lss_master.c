/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_lss_master.c - LSS master: the services, and fastscan as a state machine driven by
 * answers and timeouts. See odg_lss_master.h.
 */
#include "odg_lss_master.h"

#define SCAN_START 1u   /* asked "is any slave without node-id there?" */
#define SCAN_BIT 2u     /* asked whether bit `bit` of part `sub` is 0 */
#define SCAN_CONFIRM 3u /* asked to confirm part `sub` whole and move on */

static int send_cmd(odg_lssm_t *m, uint8_t cs, uint32_t v, uint8_t b5, uint8_t b6, uint8_t b7)
{
    odg_frame_t f;
    f.id = ODG_LSS_MASTER_COB;
    f.len = 8;
    f.flags = 0;
    f.data[0] = cs;
    f.data[1] = (uint8_t)v;
    f.data[2] = (uint8_t)(v >> 8);
    f.data[3] = (uint8_t)(v >> 16);
    f.data[4] = (uint8_t)(v >> 24);
    f.data[5] = b5;
    f.data[6] = b6;
    f.data[7] = b7;
    m->timer = 0;
    return m->send(m->send_ctx, &f);
}

void odg_lssm_init(odg_lssm_t *m, odg_send_fn send, void *send_ctx, uint32_t timeout_ms)
{
    unsigned i;
    m->send = send;
    m->send_ctx = send_ctx;
    m->timeout_ms = timeout_ms != 0u ? timeout_ms : ODG_LSSM_TIMEOUT_MS;
    m->timer = 0;
    for (i = 0; i < 4u; i++) {
        m->identity[i] = 0;
    }
    m->state = ODG_LSSM_IDLE;
    m->awaited = 0;
    m->error = 0;
    m->value = 0;
    m->scan = 0;
    m->sub = 0;
    m->bit = 0;
    m->heard = 0;
    m->known = 0;
    m->waiting_seen = 0;
}

/* Send one command and wait for answer `awaited` (0: none, the service is done). */
static odg_abort_t request(odg_lssm_t *m, uint8_t cs, uint32_t v, uint8_t b5, uint8_t awaited)
{
    if (m->state == ODG_LSSM_BUSY) {
        return ODG_ABORT_DATA_STATE;
    }
    m->error = 0;
    m->scan = 0;
    if (send_cmd(m, cs, v, b5, 0, 0) != 0) {
        m->state = ODG_LSSM_NO_ANSWER;
        return ODG_ABORT_HARDWARE;
    }
    m->awaited = awaited;
    m->state = awaited != 0u ? ODG_LSSM_BUSY : ODG_LSSM_DONE;
    return ODG_OK;
}

odg_abort_t odg_lssm_switch_global(odg_lssm_t *m, uint8_t mode)
{
    return request(m, 0x04u, mode, 0, 0);
}

odg_abort_t odg_lssm_switch_selective(odg_lssm_t *m, const uint32_t identity[4])
{
    unsigned i;
    if (m->state == ODG_LSSM_BUSY) {
        return ODG_ABORT_DATA_STATE;
    }
    for (i = 0; i < 3u; i++) { /* 0x40..0x42 have no answer; 0x43 is answered by 0x44 */
        if (send_cmd(m, (uint8_t)(0x40u + i), identity[i], 0, 0, 0) != 0) {
            m->state = ODG_LSSM_NO_ANSWER;
            return ODG_ABORT_HARDWARE;
        }
    }
    return request(m, 0x43u, identity[3], 0, 0x44u);
}

odg_abort_t odg_lssm_configure_node_id(odg_lssm_t *m, uint8_t node_id)
{
    return request(m, 0x11u, node_id, 0, 0x11u);
}

odg_abort_t odg_lssm_configure_bit_timing(odg_lssm_t *m, uint8_t table, uint8_t index)
{
    return request(m, 0x13u, (uint32_t)table | (uint32_t)index << 8, 0, 0x13u);
}

odg_abort_t odg_lssm_activate_bit_timing(odg_lssm_t *m, uint16_t delay_ms)
{
    return request(m, 0x15u, delay_ms, 0, 0);
}

odg_abort_t odg_lssm_store(odg_lssm_t *m)
{
    return request(m, 0x17u, 0, 0, 0x17u);
}

odg_abort_t odg_lssm_inquire_node_id(odg_lssm_t *m)
{
    return request(m, 0x5Eu, 0, 0, 0x5Eu);
}

/* Fastscan: ask about the current bit (0 assumed) or confirm the part found. */
static void scan_ask(odg_lssm_t *m)
{
    uint8_t next = m->scan == SCAN_CONFIRM ? (uint8_t)((m->sub + 1u) & 3u) : m->sub;
    uint8_t bit = m->scan == SCAN_CONFIRM ? 0u : m->bit;
    if (send_cmd(m, 0x51u, m->identity[m->sub], bit, m->sub, next) != 0) {
        m->state = ODG_LSSM_NO_ANSWER;
    }
}

odg_abort_t odg_lssm_fastscan_known(odg_lssm_t *m, const uint32_t identity[4], uint8_t known)
{
    odg_abort_t ac = request(m, 0x51u, 0, 0x80u, 0x4Fu);
    unsigned i;
    if (ac == ODG_OK) {
        m->scan = SCAN_START;
        m->heard = 0;
        m->waiting_seen = 0;
        m->known = (uint8_t)(known & 0x0Fu);
        for (i = 0; i < 4u; i++) {
            m->identity[i] = (m->known & 1u << i) != 0u ? identity[i] : 0u;
        }
    }
    return ac;
}

odg_abort_t odg_lssm_fastscan(odg_lssm_t *m)
{
    static const uint32_t none[4] = {0, 0, 0, 0};
    return odg_lssm_fastscan_known(m, none, 0);
}

/* Fastscan: the answer (answered = 1) or the silence after the last question. */
static void scan_step(odg_lssm_t *m, int answered)
{
    if (m->scan == SCAN_START || m->scan == SCAN_CONFIRM) {
        if (!answered) {
            m->state = ODG_LSSM_NO_ANSWER;
            return;
        }
        m->waiting_seen = 1;
        if (m->scan == SCAN_CONFIRM && ++m->sub == 4u) {
            m->state = ODG_LSSM_DONE; /* the slave is in configuration mode */
            return;
        }
        m->sub = m->scan == SCAN_START ? 0u : m->sub;
        m->scan = (m->known & 1u << m->sub) != 0u ? SCAN_CONFIRM : SCAN_BIT; /* known: confirm it */
        m->bit = 31;
    } else {
        if (!answered) { /* nobody has a 0 there: the bit is 1 */
            m->identity[m->sub] |= (uint32_t)1u << m->bit;
        }
        if (m->bit == 0u) {
            m->scan = SCAN_CONFIRM;
        } else {
            m->bit--;
        }
    }
    scan_ask(m);
}

int odg_lssm_receive(odg_lssm_t *m, const odg_frame_t *frame)
{
    const uint8_t *d = frame->data;
    if (frame->id != ODG_LSS_SLAVE_COB || frame->len < 1u || (frame->flags & (ODG_FRAME_RTR | ODG_FRAME_EFF)) != 0u) {
        return 0;
    }
    if (m->state != ODG_LSSM_BUSY || d[0] != m->awaited) {
        return 1;
    }
    if (m->scan != 0u) {
        m->heard = 1; /* decided when the question's time is up */
    } else if ((m->awaited == 0x11u || m->awaited == 0x13u || m->awaited == 0x17u) && frame->len > 1u && d[1] != 0u) {
        m->error = d[1];
        m->state = ODG_LSSM_REFUSED;
    } else {
        m->value = frame->len > 1u ? d[1] : 0u;
        m->state = ODG_LSSM_DONE;
    }
    return 1;
}

void odg_lssm_tick(odg_lssm_t *m, uint32_t elapsed_ms)
{
    if (m->state != ODG_LSSM_BUSY) {
        return;
    }
    m->timer += elapsed_ms;
    if (m->timer < m->timeout_ms) {
        return;
    }
    if (m->scan != 0u) {
        uint8_t heard = m->heard;
        m->heard = 0;
        scan_step(m, heard);
    } else {
        m->state = ODG_LSSM_NO_ANSWER;
    }
}
