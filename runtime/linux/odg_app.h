/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_app.h - the application interface of the node program (odg_node_main.c).
 *
 * Built with -DODG_APP, the node program calls these two functions, which another source
 * file on the command line provides: simulated or real I/O, change-of-state triggers.
 * Without ODG_APP the program is a bare dictionary node.
 */
#ifndef ODG_APP_H
#define ODG_APP_H

#include "odg_node.h"

/* Once, after odg_node_init (the dictionary holds its defaults or stored values). */
void odg_app_init(odg_node_t *node);

/* From the main loop, after odg_node_tick, with the milliseconds since the last call. */
void odg_app_tick(odg_node_t *node, uint32_t elapsed_ms);

#endif
