/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_nv_file.h - a file-backed NV driver for Linux/POSIX: tests and host-side node programs.
 *
 *     odg_nv_file_t nvf;
 *     if (odg_nv_file_open(&nvf, "node.nv", 4096) != 0) { ...errno... }
 *     odg_init(&my_dict, node_id);
 *     odg_persist_init(&persist, &my_dict, &nvf.driver, boot);
 *     ...
 *     odg_nv_file_close(&nvf);
 *
 * The file is created when missing and extended to `size` bytes (a longer file is left as
 * it is); bytes never written, and erased ones, read 0xFF as erased flash does. Accesses
 * outside 0..size-1 fail.
 * With `sync` set (the default) every write and erase is flushed with fsync before it
 * returns, so writes reach the disk in the order odg_persist.c issues them.
 */
#ifndef ODG_NV_FILE_H
#define ODG_NV_FILE_H

#include <stdint.h>

#include "odg_persist.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct odg_nv_file {
    odg_nv_driver_t driver; /* pass &nvf.driver to odg_persist_init; driver.ctx points back here */
    int fd;
    uint32_t size;
    int sync; /* 1: fsync after each write/erase (default); 0: leave it to the OS */
} odg_nv_file_t;

/* Open or create `path` as an NV area of `size` bytes. 0 on success, -1 (errno set) on failure. */
int odg_nv_file_open(odg_nv_file_t *nvf, const char *path, uint32_t size);

/* Close the file. 0 on success, -1 on failure. */
int odg_nv_file_close(odg_nv_file_t *nvf);

#ifdef __cplusplus
}
#endif

#endif /* ODG_NV_FILE_H */
