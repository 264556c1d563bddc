/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_master_main.c - a CiA 302 master program on SocketCAN: the master's dictionary served by
 * a node (odg_node), and the configuration manager (odg_master) booting the slaves it assigns.
 *
 *     odgen generate controller.eds -o gen                 (C name of the dictionary: controller)
 *     cc -std=c99 -O2 -DODG_DICT=controller -DODG_CONFIG='"controller_config.h"' -Igen -Iruntime \
 *        -Iruntime/linux runtime/linux/odg_master_main.c gen/controller.c  RUNTIME  MASTER  HOST
 *     ./controller-master --iface vcan0 --node-id 1 [--lss assign|store]
 *
 * With --lss, slaves without node-id whose identity the master expects get their node-ids by
 * LSS first ("store": kept in the slave's NV); docs/master.md.
 * RUNTIME, MASTER and HOST are the source lists of odgen/toolchain.py (CORE_SOURCES and
 * SERVICE_SOURCES, MASTER_SOURCES, HOST_SOURCES). Every change of a slave's boot status is
 * printed on stdout as "odg-master: node N status S" (S in hex: docs/master.md; with the SDO
 * abort code of a failed check); errors go to
 * stderr; SIGTERM and SIGINT end it with status 0.
 */
#if !defined(_POSIX_C_SOURCE) || _POSIX_C_SOURCE < 200809L
#undef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "odg_master.h"
#include "odg_node.h"
#include "odg_socketcan.h"

#include "odg_host_main.h"

static void on_status(void *ctx, uint8_t node_id, uint8_t status)
{
    const odg_master_slave_t *s = odg_master_slave((const odg_master_t *)ctx, node_id);
    printf("odg-master: node %u status 0x%02X", node_id, status);
    if (s != NULL && s->abort != 0u && status >= (uint8_t)'A') {
        printf(" (SDO abort 0x%08lX %s)", (unsigned long)s->abort, odg_abort_text(s->abort));
    }
    printf("\n");
    fflush(stdout);
}

static int run(int fd, odg_node_t *node, odg_master_t *master)
{
    struct pollfd p;
    odg_frame_t f;
    uint64_t last = now_ms(), now;
    int r;
    p.fd = fd;
    p.events = POLLIN;
    while (!stop_requested) {
        r = poll(&p, 1, 1);
        if (r < 0 && errno != EINTR) {
            fprintf(stderr, "odg-master: poll: %s\n", strerror(errno));
            return 1;
        }
        r = r < 0 ? 0 : r; /* a signal: the loop condition decides */
        while (r > 0 && (r = odg_socketcan_recv(fd, &f)) == 1) {
            odg_node_receive(node, &f);
            odg_master_receive(master, &f);
        }
        if (r < 0) {
            fprintf(stderr, "odg-master: receive: %s\n", strerror(errno));
            return 1;
        }
        now = now_ms();
        if (now > last) {
            odg_node_tick(node, (uint32_t)(now - last));
            odg_master_process(master, (uint32_t)(now - last));
            last = now;
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    static odg_node_t node;
    static odg_master_t master;
    const odg_dict_t *dict = &ODG_DICT;
    const char *iface = NULL;
    odg_node_config_t cfg;
    odg_master_config_t mcfg;
    long node_id = 0;
    uint8_t lss = 0;
    int i, fd, rc;
    odg_abort_t ac;

    for (i = 1; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--iface") == 0) {
            iface = argv[i + 1];
        } else if (strcmp(argv[i], "--node-id") == 0) {
            node_id = strtol(argv[i + 1], NULL, 0);
        } else if (strcmp(argv[i], "--lss") == 0 && strcmp(argv[i + 1], "assign") == 0) {
            lss = ODG_MASTER_LSS;
        } else if (strcmp(argv[i], "--lss") == 0 && strcmp(argv[i + 1], "store") == 0) {
            lss = ODG_MASTER_LSS_STORE;
        } else {
            break;
        }
    }
    if (i != argc || iface == NULL || node_id < 1 || node_id > 127) {
        fprintf(stderr, "usage: %s --iface IFACE --node-id 1..127 [--lss assign|store]\n", argv[0]);
        return 2;
    }
    if ((fd = odg_socketcan_open(iface)) < 0) {
        fprintf(stderr, "odg-master: %s: %s\n", iface, strerror(errno));
        return 1;
    }
    stop_on_signals();

    memset(&cfg, 0, sizeof cfg);
    cfg.dict = dict;
    cfg.node_id = (uint8_t)node_id;
    cfg.send = odg_socketcan_send;
    cfg.send_ctx = &fd;
    ac = odg_node_init(&node, &cfg);
    if (ac != ODG_OK) {
        fprintf(stderr, "odg-master: node init: 0x%08lX %s\n", (unsigned long)ac, odg_abort_text(ac));
        close(fd);
        return 1;
    }
    memset(&mcfg, 0, sizeof mcfg);
    mcfg.dict = dict;
    mcfg.send = odg_socketcan_send;
    mcfg.send_ctx = &fd;
    mcfg.node = &node;
    mcfg.on_status = on_status;
    mcfg.ctx = &master;
    mcfg.lss = lss;
    ac = odg_master_init(&master, &mcfg);
    if (ac != ODG_OK) {
        fprintf(stderr, "odg-master: master init: 0x%08lX %s\n", (unsigned long)ac, odg_abort_text(ac));
        if (ac != ODG_ABORT_NO_RESOURCE) {
            close(fd);
            return 1;
        }
    }
    rc = run(fd, &node, &master);
    close(fd);
    return rc;
}
