/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_lss.h - the LSS slave (CiA 305) of the node: a master assigns node-id and bit timing to
 * a device, found by its identity (0x1018 sub 1-4) or by fastscan. Part of odg_node.h.
 *
 * Compiled in when ODG_NODE_LSS is 1: NAME_config.h says so when the description says
 * LSS_Supported=1 or the options file has [node] lss = true. Then odg_node_init accepts the
 * node-id ODG_LSS_UNCONFIGURED: such a node sends no boot-up and answers only LSS and NMT
 * reset commands until a master configured a node-id and switched it back to the waiting
 * state; then it boots as CiA 301 says. A node-id (and bit timing) stored by the master with
 * "store configuration" is kept in NV after the persistence groups (odg_lss_nv_size) as a
 * power-safe persistence record (odg_persist_store_record), and wins over cfg.node_id at every
 * power-on.
 */
#ifndef ODG_LSS_H
#define ODG_LSS_H

#include <stdint.h>

#include "odg.h"

#ifndef ODG_NODE_LSS
#define ODG_NODE_LSS 0
#endif

#define ODG_LSS_UNCONFIGURED 0xFFu /* the node-id of a node that waits for LSS */
#define ODG_LSS_MASTER_COB 0x7E5u  /* master -> slaves */
#define ODG_LSS_SLAVE_COB 0x7E4u   /* slave -> master */
#define ODG_LSS_NO_BIT_TIMING 0xFFu

/* LSS modes (CiA 305) */
#define ODG_LSS_WAITING 0u
#define ODG_LSS_CONFIGURATION 1u

/* Bit timing, index into the CiA 305 table (0: 1000 kbit/s, 1: 800, 2: 500, 3: 250, 4: 125,
 * 6: 50, 7: 20, 8: 10, 9: automatic). Called with activate = 0 when a master configures it:
 * return 0 to accept, non-zero for "not supported"; with activate = 1 when the master
 * activates it: switch after delay_ms, then stay silent for delay_ms more. */
typedef int (*odg_lss_bit_timing_fn)(void *ctx, uint8_t index, uint16_t delay_ms, int activate);

/* The LSS slave's state (inside odg_node_t). */
typedef struct odg_lss {
    uint8_t mode;       /* ODG_LSS_WAITING, ODG_LSS_CONFIGURATION */
    uint8_t pending;    /* node-id configured: active from the next reset communication */
    uint8_t bit_index;  /* bit timing configured, ODG_LSS_NO_BIT_TIMING: none */
    uint8_t selective;  /* switch state selective: parts of the identity matched in order */
    uint8_t identify;   /* identify remote slave: bit k set when check k passed */
    uint8_t fastscan;   /* fastscan: the LSSSub this slave answers next */
} odg_lss_t;

/* NV bytes the node needs: the persistence groups' slots and, with ODG_NODE_LSS, the two
 * slots of the LSS configuration after them. */
uint32_t odg_lss_nv_size(const odg_dict_t *dict);

/* Internal, called by odg_node.c. */
struct odg_node;
void odg_lss_init_(struct odg_node *n);
int odg_lss_activate_(struct odg_node *n);
int odg_lss_receive_(struct odg_node *n, const uint8_t *d);

#endif /* ODG_LSS_H */
