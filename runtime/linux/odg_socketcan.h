/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_socketcan.h - SocketCAN (Linux CAN_RAW) transport for odg_node.
 *
 *     int fd = odg_socketcan_open("vcan0");          -1 and errno on failure
 *     cfg.send = odg_socketcan_send; cfg.send_ctx = &fd;
 *     while (odg_socketcan_recv(fd, &frame) == 1) odg_node_receive(&node, &frame);
 *
 * The socket is non-blocking: wait for input with poll(2) on the descriptor.
 */
#ifndef ODG_SOCKETCAN_H
#define ODG_SOCKETCAN_H

#include "odg_node.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A non-blocking CAN_RAW socket bound to interface `ifname`: the descriptor, or -1. */
int odg_socketcan_open(const char *ifname);

/* odg_send_fn: `ctx` points to the int descriptor. A full transmit queue is waited for up
 * to 10 ms; 0 when the frame was written, -1 otherwise. */
int odg_socketcan_send(void *ctx, const odg_frame_t *frame);

/* One received frame: 1, 0 when none is waiting, -1 on an error (errno set). Error frames
 * are skipped; 29-bit and RTR frames come with ODG_FRAME_EFF / ODG_FRAME_RTR set. */
int odg_socketcan_recv(int fd, odg_frame_t *frame);

#ifdef __cplusplus
}
#endif

#endif /* ODG_SOCKETCAN_H */
