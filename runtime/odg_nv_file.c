/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_nv_file.c - file-backed NV driver (POSIX). See odg_nv_file.h.
 */
#if !defined(_POSIX_C_SOURCE) || _POSIX_C_SOURCE < 200809L
#undef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "odg_nv_file.h"

static int in_range(const odg_nv_file_t *f, uint32_t addr, uint32_t len)
{
    return f->fd >= 0 && addr <= f->size && len <= f->size - addr;
}

static int nv_flush(const odg_nv_file_t *f)
{
    return f->sync ? fsync(f->fd) : 0;
}

/* pwrite of `len` bytes, or `len` bytes of `fill` when buf is NULL */
static int put(const odg_nv_file_t *f, uint32_t addr, const uint8_t *buf, uint32_t len, uint8_t fill)
{
    uint8_t block[256];
    if (buf == NULL) {
        memset(block, fill, sizeof block);
    }
    while (len > 0u) {
        size_t n = buf ? len : (len < sizeof block ? len : sizeof block);
        ssize_t w = pwrite(f->fd, buf ? (const void *)buf : (const void *)block, n, (off_t)addr);
        if (w < 0 && errno == EINTR) {
            continue;
        }
        if (w <= 0) {
            return -1;
        }
        addr += (uint32_t)w;
        len -= (uint32_t)w;
        if (buf) {
            buf += w;
        }
    }
    return 0;
}

static int nv_read(void *ctx, uint32_t addr, void *buf, uint32_t len)
{
    odg_nv_file_t *f = (odg_nv_file_t *)ctx;
    uint8_t *p = (uint8_t *)buf;
    if (!in_range(f, addr, len)) {
        return -1;
    }
    while (len > 0u) {
        ssize_t r = pread(f->fd, p, len, (off_t)addr);
        if (r < 0 && errno == EINTR) {
            continue;
        }
        if (r < 0) {
            return -1;
        }
        if (r == 0) { /* beyond the end of a file that was cut short: erased */
            memset(p, 0xFF, len);
            return 0;
        }
        p += r;
        addr += (uint32_t)r;
        len -= (uint32_t)r;
    }
    return 0;
}

static int nv_write(void *ctx, uint32_t addr, const void *buf, uint32_t len)
{
    odg_nv_file_t *f = (odg_nv_file_t *)ctx;
    if (!in_range(f, addr, len) || put(f, addr, (const uint8_t *)buf, len, 0) != 0) {
        return -1;
    }
    return nv_flush(f);
}

static int nv_erase(void *ctx, uint32_t addr, uint32_t len)
{
    odg_nv_file_t *f = (odg_nv_file_t *)ctx;
    if (!in_range(f, addr, len) || put(f, addr, NULL, len, 0xFF) != 0) {
        return -1;
    }
    return nv_flush(f);
}

int odg_nv_file_open(odg_nv_file_t *nvf, const char *path, uint32_t size)
{
    struct stat st;
    nvf->driver.read = nv_read;
    nvf->driver.write = nv_write;
    nvf->driver.erase = nv_erase;
    nvf->driver.ctx = nvf;
    nvf->size = size;
    nvf->sync = 1;
    nvf->fd = open(path, O_RDWR | O_CREAT, 0644);
    if (nvf->fd < 0) {
        return -1;
    }
    if (fstat(nvf->fd, &st) != 0) {
        (void)odg_nv_file_close(nvf);
        return -1;
    }
    if (st.st_size < (off_t)size) { /* new or short: the missing bytes are erased */
        uint32_t from = (uint32_t)st.st_size;
        if (put(nvf, from, NULL, size - from, 0xFF) != 0 || nv_flush(nvf) != 0) {
            int err = errno;
            (void)odg_nv_file_close(nvf);
            errno = err;
            return -1;
        }
    }
    return 0;
}

int odg_nv_file_close(odg_nv_file_t *nvf)
{
    int rc = 0;
    if (nvf->fd >= 0) {
        rc = close(nvf->fd);
        nvf->fd = -1;
    }
    return rc;
}
