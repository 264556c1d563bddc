/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_sync.c - the node's SYNC service (CiA 301: 0x1005, 0x1006, 0x1019): consumer and producer.
 * Calls odg_pdo.c and odg_node_io.c (odg_sync.h).
 *
 * A SYNC received in operational (on the COB-ID of 0x1005, whose bit 31 a consumer ignores)
 * goes to the PDOs (odg_pdo_sync_), which apply the RPDO data received since the last one and
 * send the synchronous TPDOs due; they also keep the SYNC window (0x1007).
 *
 * When 0x1005 has bit 30 ("generate") set and the communication cycle period 0x1006 (µs) is
 * not 0, the node sends SYNC on the COB-ID of 0x1005 every period, in pre-operational and
 * operational. With a synchronous counter overflow value (0x1019) of 2..240 the frame carries
 * one byte, counting 1..value and again from 1; with 0 (or no 0x1019) the frame is empty.
 * The counter starts at 1 whenever the production starts. The node's own synchronous PDOs
 * act on its SYNC as on any other. 0x1019 may only be written while 0x1006 is 0
 * (0x08000022 otherwise), as CiA 301 requires, and only with 0 or 2..240: CiA 301 reserves 1
 * and 241..255 (0x06090030). Time runs in the ticks' milliseconds.
 */
#include "odg_node.h"

#define SYNC_GENERATE 0x40000000u

void odg_sync_receive_(odg_node_t *n, const odg_frame_t *f)
{
    odg_pdo_sync_(n, f);
}

void odg_sync_tick_(odg_node_t *n, uint32_t ms)
{
    odg_frame_t f;
    uint32_t period = odg_io_num_(n, 0x1006, 0), overflow;
    uint32_t us = ms > 4000000u ? 0xFFFFFFFFu : ms * 1000u;
    if (!(n->sync.cob & SYNC_GENERATE) || period == 0u ||
        !ODG_IO_TALKING(n)) {
        n->sync.prod_us = 0;
        n->sync.counter = 0; /* production stopped: the counter starts again at 1 */
        return;
    }
    n->sync.prod_us = n->sync.prod_us + us < n->sync.prod_us ? 0xFFFFFFFFu : n->sync.prod_us + us;
    if (n->sync.prod_us < period) {
        return;
    }
    n->sync.prod_us = n->sync.prod_us - period >= period ? 0u : n->sync.prod_us - period; /* no burst after a pause */
    overflow = odg_io_num_(n, 0x1019, 0);
    f.id = ODG_COB_ID(n->sync.cob);
    f.flags = 0;
    f.len = 0;
    if (overflow >= 2u && overflow <= 240u) {
        n->sync.counter = (uint8_t)(n->sync.counter >= overflow ? 1u : n->sync.counter + 1u);
        f.data[0] = n->sync.counter;
        f.len = 1;
    }
    (void)odg_io_send_(n, f.id, f.data, f.len);
    if (n->state == ODG_NMT_OPERATIONAL) {
        odg_pdo_sync_(n, &f);
    }
}

odg_abort_t odg_sync_check_(const odg_node_t *n, const uint8_t *data, uint32_t len)
{
    if (len == 1u && (data[0] == 1u || data[0] > 240u)) {
        return ODG_ABORT_VALUE_RANGE; /* reserved counter overflow values */
    }
    return odg_io_num_(n, 0x1006, 0) != 0u ? ODG_ABORT_DATA_STATE : ODG_OK;
}
