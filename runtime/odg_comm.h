/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_comm.h - the communication values in force at boot, which reset communication brings
 * back (objects of 0x1000-0x1FFF an SDO client may write, in index order while they fit whole
 * into odg_node_t.comm). Part of odg_node.h (which declares the API: odg_node_comm_keep,
 * odg_node_comm_bytes); below it only odg_node_io.h.
 */
#ifndef ODG_COMM_H
#define ODG_COMM_H

#include "odg_node_io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Bytes the node keeps of the communication values in force at boot, which reset communication
 * brings back: objects of 0x1000-0x1FFF in index order while they fit whole (the rest keep
 * their values); odg_node_comm_bytes(dict) says how many a dictionary needs. */
#ifndef ODG_NODE_COMM_BYTES
#define ODG_NODE_COMM_BYTES 512u
#endif

/* Internal, called by odg_sdo.c and odg_node.c. */
/* After the SDO server wrote "save" (restore 0) or "load" (1) to 0x1010/0x1011 sub `sub`:
 * reset communication brings back what the next boot would load. */
void odg_comm_stored_(struct odg_node *n, uint8_t sub, int restore);
void odg_comm_back_(struct odg_node *n); /* reset communication: the values kept go back */

#ifdef __cplusplus
}
#endif

#endif /* ODG_COMM_H */
