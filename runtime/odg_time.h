/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_time.h - the TIME service of the node (CiA 301 TIME_OF_DAY, 0x1012). Part of odg_node.h;
 * below it only odg_node_io.h.
 */
#ifndef ODG_TIME_H
#define ODG_TIME_H

#include "odg_node_io.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ODG_TIME_CONSUME 0x80000000u /* 0x1012 bit 31 */
#define ODG_TIME_PRODUCE 0x40000000u /* 0x1012 bit 30 */
#define ODG_TIME_MS_MASK 0x0FFFFFFFu /* TIME_OF_DAY: 28 bits of ms */

/* The TIME service's state (odg_node_t.time, internal). */
typedef struct odg_time {
    uint32_t cob; /* 0x1012 (0 when absent) */
} odg_time_t;

/* Internal, called by odg_node.c: a TIME frame received (its COB-ID, consumer bit set). */
void odg_time_receive_(struct odg_node *n, const odg_frame_t *f);

#ifdef __cplusplus
}
#endif

#endif /* ODG_TIME_H */
