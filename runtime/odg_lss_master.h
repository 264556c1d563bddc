/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_lss_master.h - LSS master (CiA 305): switch state global and selective, configure
 * node-id and bit timing, activate bit timing, store configuration, inquire node-id, and
 * fastscan to find a slave without node-id. One service at a time; each answer is awaited
 * for `timeout_ms` (odg_lssm_init). Fastscan waits that long after every question, answered
 * or not: several slaves may answer one question, each in a frame of its own on a bus that
 * does not merge identical frames (vcan), and a late answer must not be taken for the next.
 *
 *     odg_lssm_fastscan(&lss);                    ... receive / tick until not BUSY
 *     if (lss.state == ODG_LSSM_DONE) {           lss.identity: the slave found, now in
 *         odg_lssm_configure_node_id(&lss, 12);   configuration mode
 *         ... then odg_lssm_store(&lss), odg_lssm_switch_global(&lss, ODG_LSS_WAITING)
 *     }
 */
#ifndef ODG_LSS_MASTER_H
#define ODG_LSS_MASTER_H

#include <stdint.h>

#include "odg_lss.h"
#include "odg_node.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ms an LSS master waits for an answer (fastscan: for each bit asked). */
#ifndef ODG_LSSM_TIMEOUT_MS
#define ODG_LSSM_TIMEOUT_MS 50u
#endif

/* odg_lssm_t.state */
#define ODG_LSSM_IDLE 0u
#define ODG_LSSM_BUSY 1u
#define ODG_LSSM_DONE 2u      /* the service succeeded (fastscan: a slave was found) */
#define ODG_LSSM_NO_ANSWER 3u /* no slave answered (fastscan: none without node-id) */
#define ODG_LSSM_REFUSED 4u   /* the slave answered with an error (odg_lssm_t.error) */

typedef struct odg_lssm {
    odg_send_fn send;
    void *send_ctx;
    uint32_t timeout_ms;
    uint32_t timer;       /* ms waited for the answer */
    uint32_t identity[4]; /* fastscan: vendor, product, revision, serial found */
    uint8_t state;        /* ODG_LSSM_* */
    uint8_t awaited;      /* the command specifier of the answer awaited; 0: none */
    uint8_t error;        /* ODG_LSSM_REFUSED: the slave's error code */
    uint8_t value;        /* inquire node-id: the node-id */
    uint8_t scan;         /* fastscan: 0 off, 1 looking for slaves, 2 bits, 3 confirming a part */
    uint8_t sub;          /* fastscan: the part of the identity being found */
    uint8_t bit;          /* fastscan: the bit being found */
    uint8_t heard;        /* fastscan: an answer came to the question in flight */
    uint8_t known;        /* fastscan: the parts of the identity given (bit k: part k) */
    uint8_t waiting_seen; /* fastscan: a slave without node-id answered its first question */
} odg_lssm_t;

/* timeout_ms 0: ODG_LSSM_TIMEOUT_MS. */
void odg_lssm_init(odg_lssm_t *m, odg_send_fn send, void *send_ctx, uint32_t timeout_ms);

/* Every slave to ODG_LSS_WAITING or ODG_LSS_CONFIGURATION (no answer: DONE at once). */
odg_abort_t odg_lssm_switch_global(odg_lssm_t *m, uint8_t mode);
/* The slave of this identity (vendor, product, revision, serial) to configuration mode. */
odg_abort_t odg_lssm_switch_selective(odg_lssm_t *m, const uint32_t identity[4]);
/* To the slave(s) in configuration mode: */
odg_abort_t odg_lssm_configure_node_id(odg_lssm_t *m, uint8_t node_id);
odg_abort_t odg_lssm_configure_bit_timing(odg_lssm_t *m, uint8_t table, uint8_t index);
odg_abort_t odg_lssm_activate_bit_timing(odg_lssm_t *m, uint16_t delay_ms); /* no answer */
odg_abort_t odg_lssm_store(odg_lssm_t *m);
odg_abort_t odg_lssm_inquire_node_id(odg_lssm_t *m); /* DONE: odg_lssm_t.value */
/* Find one slave without node-id (in waiting mode) bit by bit; it ends in configuration mode. */
odg_abort_t odg_lssm_fastscan(odg_lssm_t *m);
/* The same for a slave of which parts of the identity are known (bit k of `known`: part k, in
 * identity[k], the vendor-ID being part 0): each known part takes one question instead of 33. */
odg_abort_t odg_lssm_fastscan_known(odg_lssm_t *m, const uint32_t identity[4], uint8_t known);

/* Every received frame: 1 when it was an LSS answer (0x7E4). */
int odg_lssm_receive(odg_lssm_t *m, const odg_frame_t *frame);
void odg_lssm_tick(odg_lssm_t *m, uint32_t elapsed_ms);

#ifdef __cplusplus
}
#endif

#endif /* ODG_LSS_MASTER_H */
