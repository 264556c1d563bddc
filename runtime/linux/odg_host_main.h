/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_host_main.h - what the SocketCAN programs (odg_node_main.c, odg_master_main.c) share:
 * the dictionary's header named by ODG_DICT, a monotonic millisecond clock, and SIGTERM/SIGINT
 * ending the main loop. Included by a program's main file only, after _POSIX_C_SOURCE.
 */
#ifndef ODG_HOST_MAIN_H
#define ODG_HOST_MAIN_H

#include <signal.h>
#include <stdint.h>
#include <string.h>
#include <time.h>

#ifndef ODG_DICT
#error "define ODG_DICT to the dictionary's C name, e.g. -DODG_DICT=io_node"
#endif
#define ODG_STR_(x) #x
#define ODG_STR(x) ODG_STR_(x)
#ifndef ODG_DICT_HEADER
#define ODG_DICT_HEADER ODG_STR(ODG_DICT.h)
#endif
#include ODG_DICT_HEADER

static volatile sig_atomic_t stop_requested;

static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
}

/* SIGTERM and SIGINT set stop_requested; no SA_RESTART, so a blocked poll returns EINTR at once. */
static void stop_on_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);
}

static uint64_t now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u;
}

#endif
