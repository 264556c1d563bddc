/*
 * can.h - the CAN driver of the node (can.c): send, receive through a queue the receive
 * interrupt fills, and the controller's state.
 */
#ifndef CAN_H
#define CAN_H

#include "odg_node.h"

/* odg_node_config_t.send: queue one frame in a free transmit mailbox. */
int can_send(void *ctx, const odg_frame_t *frame);

/* From the main loop: every frame received since the last call into odg_node_receive, then
 * a lost frame or a new controller state into odg_node_can_state. */
void can_poll(odg_node_t *node);

#endif /* CAN_H */
