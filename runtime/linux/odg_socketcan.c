/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_socketcan.c - SocketCAN transport for odg_node. See odg_socketcan.h.
 */
#if !defined(_DEFAULT_SOURCE)
#define _DEFAULT_SOURCE /* struct ifreq, if_nametoindex with -std=c99 */
#endif

#include <errno.h>
#include <fcntl.h>
#include <net/if.h>
#include <poll.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include <linux/can.h>
#include <linux/can/raw.h>

#include "odg_socketcan.h"

int odg_socketcan_open(const char *ifname)
{
    struct sockaddr_can addr;
    unsigned idx = if_nametoindex(ifname);
    int fd, e;
    if (idx == 0u) {
        return -1;
    }
    fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (fd < 0) {
        return -1;
    }
    memset(&addr, 0, sizeof addr);
    addr.can_family = AF_CAN;
    addr.can_ifindex = (int)idx;
    if (bind(fd, (struct sockaddr *)&addr, sizeof addr) != 0 ||
        fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK) != 0) {
        e = errno;
        close(fd);
        errno = e;
        return -1;
    }
    return fd;
}

int odg_socketcan_send(void *ctx, const odg_frame_t *frame)
{
    int fd = *(const int *)ctx, tries;
    struct can_frame cf;
    memset(&cf, 0, sizeof cf);
    cf.can_id = frame->id & CAN_SFF_MASK;
    if (frame->flags & ODG_FRAME_EFF) {
        cf.can_id = (frame->id & CAN_EFF_MASK) | CAN_EFF_FLAG;
    }
    if (frame->flags & ODG_FRAME_RTR) {
        cf.can_id |= CAN_RTR_FLAG;
    }
    cf.can_dlc = frame->len > 8u ? 8u : frame->len;
    memcpy(cf.data, frame->data, cf.can_dlc);
    for (tries = 0; tries < 10; tries++) {
        struct pollfd p;
        if (write(fd, &cf, sizeof cf) == (ssize_t)sizeof cf) {
            return 0;
        }
        if (errno != EAGAIN && errno != EWOULDBLOCK && errno != ENOBUFS && errno != EINTR) {
            return -1;
        }
        /* the queue is full: wait a little for room (ENOBUFS does not wake poll, so 1 ms) */
        p.fd = fd;
        p.events = POLLOUT;
        (void)poll(&p, 1, 1);
    }
    return -1;
}

int odg_socketcan_recv(int fd, odg_frame_t *frame)
{
    struct can_frame cf;
    for (;;) {
        ssize_t r = read(fd, &cf, sizeof cf);
        if (r < 0) {
            return errno == EAGAIN || errno == EWOULDBLOCK ? 0 : errno == EINTR ? 0 : -1;
        }
        if (r != (ssize_t)sizeof cf || (cf.can_id & CAN_ERR_FLAG)) {
            continue; /* CAN FD or error frames: not for the node */
        }
        memset(frame, 0, sizeof *frame);
        frame->flags = (uint8_t)(((cf.can_id & CAN_EFF_FLAG) ? ODG_FRAME_EFF : 0u) |
                                 ((cf.can_id & CAN_RTR_FLAG) ? ODG_FRAME_RTR : 0u));
        frame->id = cf.can_id & ((cf.can_id & CAN_EFF_FLAG) ? CAN_EFF_MASK : CAN_SFF_MASK);
        frame->len = cf.can_dlc > 8u ? 8u : cf.can_dlc;
        memcpy(frame->data, cf.data, frame->len);
        return 1;
    }
}
