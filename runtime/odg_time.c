/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_time.c - the TIME object (CiA 301 TIME_OF_DAY) of the node: consumed when 0x1012 bit 31
 * is set and handed to cfg.on_time, produced by odg_node_time_send when bit 30 is set. Both
 * in pre-operational and operational. Calls only odg_node_io.c (odg_time.h). See odg_node.h.
 */
#include <string.h>

#include "odg_impl.h"
#include "odg_node.h"

void odg_time_receive_(odg_node_t *n, const odg_frame_t *f)
{
    const uint8_t *d = f->data;
    uint32_t ms;
    if (f->len < 6u || n->cfg.on_time == NULL) {
        return; /* TIME_OF_DAY is 6 bytes: a shorter frame carries no time */
    }
    ms = ODG_LE32(d) & ODG_TIME_MS_MASK;
    n->cfg.on_time(n->cfg.app_ctx, ms, (uint16_t)(d[4] | (unsigned)d[5] << 8));
}

odg_abort_t odg_node_time_send(odg_node_t *node, uint32_t ms, uint16_t days)
{
    uint8_t d[6];
    if (ms > ODG_TIME_MS_MASK) {
        return ODG_ABORT_VALUE_RANGE;
    }
    if (!ODG_IO_TALKING(node) || !(node->time.cob & ODG_TIME_PRODUCE)) {
        return ODG_ABORT_DATA_STATE;
    }
    d[0] = (uint8_t)ms;
    d[1] = (uint8_t)(ms >> 8);
    d[2] = (uint8_t)(ms >> 16);
    d[3] = (uint8_t)(ms >> 24); /* the 4 reserved bits are 0 */
    d[4] = (uint8_t)days;
    d[5] = (uint8_t)(days >> 8);
    return odg_io_send_(node, node->time.cob, d, 6) == 0 ? ODG_OK : ODG_ABORT_HARDWARE;
}
