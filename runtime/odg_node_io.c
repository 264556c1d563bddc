/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_node_io.c - the helpers every service of the node shares: the bottom of the node layer
 * (odg_node_io.h). It calls nothing of the node's.
 */
#include <string.h>

#include "odg_impl.h"
#include "odg_node.h"

int odg_io_send_(const odg_node_t *n, uint32_t cob, const uint8_t *data, uint8_t len)
{
    odg_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = ODG_COB_ID(cob);
    f.len = len;
    odg_copy(f.data, data, len); /* nothing with len 0 (data may be NULL then) */
    return n->cfg.send(n->cfg.send_ctx, &f);
}

odg_abort_t odg_io_get_(const odg_node_t *n, uint16_t index, uint8_t sub, uint32_t *value)
{
    odg_ref_t r;
    uint8_t b[4] = {0, 0, 0, 0}; /* a shorter value leaves the high bytes 0 */
    uint32_t got;
    odg_abort_t ac = odg_find(n->cfg.dict, index, sub, &r);
    if (ac == ODG_OK) {
        ac = odg_read(&r, 0, b, sizeof b, &got);
    }
    *value = ODG_LE32(b);
    return ac;
}

uint32_t odg_io_get_or_(const odg_node_t *n, uint16_t index, uint8_t sub, uint32_t dflt)
{
    uint32_t v;
    return odg_io_get_(n, index, sub, &v) == ODG_OK ? v : dflt;
}

uint32_t odg_io_num_(const odg_node_t *n, uint16_t index, uint8_t sub)
{
    return odg_io_get_or_(n, index, sub, 0);
}
