/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_err.h - the node's errors and EMCY producer: active errors and the error register 0x1001,
 * the pre-defined error field 0x1003, EMCY frames and their inhibit time 0x1015. Part of
 * odg_node.h (which declares the API: odg_node_error_set, odg_node_emcy, ...); below it only
 * odg_node_io.h. The services above raise and clear errors here.
 */
#ifndef ODG_ERR_H
#define ODG_ERR_H

#include "odg_node_io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* EMCY frames held back by the inhibit time (0x1015) at most; more are refused. */
#ifndef ODG_NODE_EMCY_QUEUE
#define ODG_NODE_EMCY_QUEUE 4u
#endif
/* Errors active at once (odg_node_error_set) at most; more are refused. */
#ifndef ODG_NODE_MAX_ERRORS
#define ODG_NODE_MAX_ERRORS 8u
#endif

/* Error register bits (0x1001, CiA 301). odg_node_error_bits says which an error code sets. */
#define ODG_ERR_GENERIC 0x01u       /* set while any error is active */
#define ODG_ERR_CURRENT 0x02u       /* codes 0x2xxx */
#define ODG_ERR_VOLTAGE 0x04u       /* codes 0x3xxx */
#define ODG_ERR_TEMPERATURE 0x08u   /* codes 0x4xxx */
#define ODG_ERR_COMMUNICATION 0x10u /* codes 0x81xx (communication) and 0x82xx (protocol) */
#define ODG_ERR_PROFILE 0x20u       /* device profile specific: by the caller (bits) */
#define ODG_ERR_MANUFACTURER 0x80u  /* codes 0xFFxx (device specific) */

/* The errors and EMCY service's state (odg_node_t.err, internal). */
typedef struct odg_err {
    uint32_t cob;            /* 0x1014 */
    uint32_t inhibit_us;     /* µs until the next EMCY may be sent */
    uint8_t queue[ODG_NODE_EMCY_QUEUE][8]; /* EMCY frames waiting for the inhibit time */
    uint8_t queued;
    uint8_t fresh;           /* one was sent since the last tick */
    uint8_t active;          /* errors active */
    uint8_t bits[ODG_NODE_MAX_ERRORS];  /* the error register bits of each */
    uint16_t code[ODG_NODE_MAX_ERRORS]; /* their codes */
} odg_err_t;

/* Internal, called by the services above and odg_node.c. */
/* 0x1003: before an SDO write (sub 0 takes only 0: a macro, the rule is one test), and after
 * one (0 clears the history). */
#define ODG_ERR_CHECK(sub, value) ((sub) == 0u && (value) != 0u ? ODG_ABORT_VALUE_RANGE : ODG_OK)
void odg_err_written_(struct odg_node *n);
/* At a reset: forget every active error (`all`) or those of communication; 0x1001 follows. */
void odg_err_reset_(struct odg_node *n, int all);
/* Send EMCY frames held back by the inhibit time once it has passed. */
void odg_err_tick_(struct odg_node *n, uint32_t ms);

#ifdef __cplusplus
}
#endif

#endif /* ODG_ERR_H */
