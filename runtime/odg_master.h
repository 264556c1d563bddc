/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_master.h - a CiA 302-2 configuration manager: boots the slaves the master's dictionary
 * assigns (0x1F81), checks each one's device type and identity, downloads its concise DCF
 * (0x1F22) and starts it as 0x1F80 says; watches the slaves afterwards and boots again a slave
 * that resets or is lost. See docs/master.md.
 *
 * The master sits above the node: the application runs its own odg_node_t (the master's
 * dictionary, its SDO server, heartbeat, EMCY) and, beside it, an odg_master_t on the same
 * dictionary, handing every received frame to both and ticking both:
 *
 *     odg_node_init(&node, &node_cfg);
 *     mcfg.dict = &controller; mcfg.send = can_send; mcfg.send_ctx = &can; mcfg.node = &node;
 *     odg_master_init(&master, &mcfg);            -> slaves reset, their boot begins
 *     for (;;) {
 *         while (can_read(&f)) { odg_node_receive(&node, &f); odg_master_receive(&master, &f); }
 *         odg_node_tick(&node, ms); odg_master_process(&master, ms);
 *     }
 *
 * Each slave's boot status is in the master's dictionary at ODG_MASTER_STATUS_INDEX, sub-index
 * = node-id (readable by SDO), and reported to cfg.on_status.
 */
#ifndef ODG_MASTER_H
#define ODG_MASTER_H

#include <stdint.h>

#include "odg.h"
#include "odg_node.h"
#include "odg_lss_master.h"
#include "odg_nmt_master.h"
#include "odg_sdo_client.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The slave boot status object (docs/master.md): ARRAY of UNSIGNED8, sub-index = node-id; the
 * index odgen network gives it in the master's dictionary. */
#ifndef ODG_MASTER_STATUS_INDEX
#define ODG_MASTER_STATUS_INDEX 0x5F81u
#endif
/* Fastscans for one slave's identity while slaves without node-id answer but none with it is
 * found (a late answer on a loaded bus spoils a scan). */
#ifndef ODG_MASTER_LSS_TRIES
#define ODG_MASTER_LSS_TRIES 3u
#endif
/* ms between two attempts to reach an absent slave (CiA 302-2: optional slaves are retried). */
#ifndef ODG_MASTER_RETRY_MS
#define ODG_MASTER_RETRY_MS 1000u
#endif

/* Boot status values (0x5F81): */
#define ODG_SLAVE_NOT_BOOTED 0x00u
#define ODG_SLAVE_BOOTING 0x01u
#define ODG_SLAVE_BOOTED 0x02u
/* the CiA 302-2 boot error status letters */
#define ODG_SLAVE_NO_ANSWER 'B'   /* no answer to the upload of 0x1000 */
#define ODG_SLAVE_DEVICE_TYPE 'C' /* 0x1000 differs from 0x1F84 */
#define ODG_SLAVE_VENDOR 'D'      /* 0x1018 sub 1 differs from 0x1F85 */
#define ODG_SLAVE_HEARTBEAT 'E'   /* heartbeat lost */
#define ODG_SLAVE_GUARDING 'F'    /* no answer to node guarding */
#define ODG_SLAVE_DOWNLOAD 'J'    /* configuration download failed */
#define ODG_SLAVE_OPERATIONAL 'L' /* a keep-alive slave was found operational: left as it was */
#define ODG_SLAVE_PRODUCT 'M'     /* 0x1018 sub 2 differs from 0x1F86 */
#define ODG_SLAVE_REVISION 'N'    /* 0x1018 sub 3 differs from 0x1F87 */
#define ODG_SLAVE_SERIAL 'O'      /* 0x1018 sub 4 differs from 0x1F88 */
/* on_status with node-id 0: the boot time 0x1F89 passed before the network came up (every
 * mandatory slave booted, every slave tried once: docs/master.md) */
#define ODG_MASTER_BOOT_TIMEOUT 0xFEu

/* EMCY codes the master sends (vendor bytes: status, node-id) through cfg.node */
#define ODG_MASTER_EMCY_BOOT 0x8100u /* a slave failed its boot (communication, generic) */
#define ODG_MASTER_EMCY_LOST 0x8130u /* a booted slave's heartbeat or guarding was lost */

/* 0x1F80 bits */
#define ODG_STARTUP_MASTER 0x01u      /* the device is the NMT master */
#define ODG_STARTUP_START_ALL 0x02u   /* start the slaves with one command to all nodes */
#define ODG_STARTUP_NO_SELF 0x04u     /* the master does not enter operational by itself */
#define ODG_STARTUP_NO_START 0x08u    /* the application starts the slaves */
#define ODG_STARTUP_RESET_ALL 0x10u   /* mandatory slave lost: NMT reset node to all */
#define ODG_STARTUP_STOP_ALL 0x40u    /* mandatory slave lost: NMT stop to all (wins over bit 4) */
/* 0x1F81 bits */
#define ODG_ASSIGN_SLAVE 0x01u
#define ODG_ASSIGN_REBOOT 0x04u       /* on an error control event, boot the slave again */
#define ODG_ASSIGN_MANDATORY 0x08u
#define ODG_ASSIGN_KEEP_ALIVE 0x10u   /* not reset at the master's start */

/* odg_master_config_t.lss: node-ids by LSS before the boot (docs/master.md, "Node-ids by LSS") */
#define ODG_MASTER_LSS 1u        /* give a slave without node-id the node-id its identity says */
#define ODG_MASTER_LSS_STORE 2u  /* the same, and store it in the slave (LSS store configuration) */

typedef struct odg_master_config {
    const odg_dict_t *dict;  /* the master's dictionary, holding the CiA 302 objects */
    odg_send_fn send;
    void *send_ctx;
    struct odg_node *node;   /* the master's own node (EMCY, its own NMT state), or NULL */
    void (*on_status)(void *ctx, uint8_t node_id, uint8_t status); /* each new status; or NULL */
    void *ctx;
    uint8_t lss;             /* 0, ODG_MASTER_LSS or ODG_MASTER_LSS_STORE */
} odg_master_config_t;

typedef struct odg_master_slave {
    uint32_t assignment;  /* 0x1F81 */
    uint32_t timer;       /* ms left before the next attempt (waiting) */
    uint32_t dcf_at;      /* the next concise DCF entry's offset */
    uint32_t dcf_left;    /* entries left to download */
    uint32_t abort;       /* the SDO abort code of the transfer that failed a check (0: none);
                           * ODG_ABORT_TIMEOUT: no answer, the boot is tried again */
    uint8_t value[4];     /* an uploaded number */
    uint8_t id;           /* node-id */
    uint8_t phase;        /* what the boot-up process does (odg_master.c) */
    uint8_t step;         /* identity: sub-index of 0x1018; configuration date: 1 or 2 */
    uint8_t status;       /* ODG_SLAVE_* */
    uint8_t tried;        /* the first boot attempt is over (for the start of the network) */
    uint8_t same_date;    /* 0x1020 sub 1 matched 0x1F26 */
} odg_master_slave_t;

typedef struct odg_master {
    odg_master_config_t cfg;
    odg_nmtm_t nmt;
    odg_sdoc_t sdo[ODG_MASTER_MAX_SLAVES];        /* one client channel per slave */
    odg_master_slave_t slave[ODG_MASTER_MAX_SLAVES];
    odg_lssm_t lss;        /* node-ids by LSS (cfg.lss) */
    uint32_t startup;      /* 0x1F80 */
    uint32_t boot_left;    /* ms of the boot time 0x1F89 left (0: none, or over) */
    uint8_t n_slaves;
    uint8_t network_up;    /* the slaves were started (as 0x1F80 says) once */
    uint8_t lss_step;      /* node-ids by LSS: what the LSS master does (odg_master.c); 0: over */
    uint8_t lss_slave;     /* node-ids by LSS: the slave looked for */
    uint8_t lss_tries;     /* node-ids by LSS: fastscans for it so far */
    uint8_t lss_only;      /* node-ids by LSS: for that slave alone (its retry) */
} odg_master_t;

/* Read 0x1F80 and 0x1F81 from cfg->dict, take the first ODG_MASTER_MAX_SLAVES assigned slaves,
 * reset communication of those not kept alive and begin their boot (with cfg->lss, after the
 * slaves without node-id got theirs). ODG_ABORT_DATA_STATE when
 * 0x1F80 does not say NMT master (nothing happens then), ODG_ABORT_NO_RESOURCE when more slaves
 * are assigned than fit (the others are ignored), ODG_ABORT_INCOMPATIBLE without dict or send. */
odg_abort_t odg_master_init(odg_master_t *m, const odg_master_config_t *cfg);

/* Every received frame (any identifier). */
void odg_master_receive(odg_master_t *m, const odg_frame_t *frame);

/* Advance time (call every ms or so): SDO timeouts, retries, heartbeats, boot time. */
void odg_master_process(odg_master_t *m, uint32_t elapsed_ms);

/* A slave's record (NULL when node_id is not an assigned slave). */
const odg_master_slave_t *odg_master_slave(const odg_master_t *m, uint8_t node_id);

/* Begin the boot of an assigned slave again (after the application fixed it, say). */
void odg_master_reboot(odg_master_t *m, uint8_t node_id);

#ifdef __cplusplus
}
#endif

#endif /* ODG_MASTER_H */
