/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_persist_slot.c - the slots both image formats share: the CRC-32, header bytes, the
 * sequence order, erased-NV checks and erasures, and what both read of the groups: the NV they
 * span and their defaults (docs/persistence.md, runtime/README.md). The lowest file of the
 * persistence layer: it calls only the core. Internal to the layer (odg_persist_impl.h).
 */
#include "odg_persist_impl.h"

/* ---- CRC-32 (IEEE 802.3), bit by bit: no table in FLASH ------------------------------- */

uint32_t odg_crc32(uint32_t crc, const void *data, uint32_t len)
{
    const uint8_t *p = (const uint8_t *)data;
    unsigned k;
    crc = ~crc;
    while (len--) {
        crc ^= *p++;
        for (k = 0; k < 8u; k++) {
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
        }
    }
    return ~crc;
}

/* ---- header encoding -------------------------------------------------------------------- */

void odg_put32_(uint8_t *p, uint32_t v)
{
    odg_put_le32_(p, v);
}

uint32_t odg_get32_(const uint8_t *p)
{
    return ODG_LE32(p);
}

/* a is newer than b: a - b in 1 .. 2^31 - 1 */
int odg_newer_(uint32_t a, uint32_t b)
{
    return ODG_NEWER_(a, b);
}

/* Read the `n`-byte header of the slot at `addr` into `h`: 1 when it starts with `magic`, 0 when
 * not, -1 when the driver failed. Both formats have it so. */
int odg_hdr_read_(const odg_nv_driver_t *nv, uint32_t addr, uint8_t *h, uint32_t n,
                    uint32_t magic)
{
    if (nv->read(nv->ctx, addr, h, n) != 0) {
        return -1;
    }
    return ODG_LE32(h) == magic; /* inline: one load where the core allows, less than a call */
}

/* Whether the CRC-32 that ends the `n`-byte header `h` of the slot at `addr` matches the header
 * before it and the `len` image bytes after it (read into `dst` when not NULL, which must hold
 * them): 1 yes, 0 no, -1 the driver failed. Both formats have it so. */
int odg_crc_ok_(const odg_nv_driver_t *nv, uint32_t addr, const uint8_t *h, uint32_t n,
                  uint32_t len, uint8_t *dst)
{
    uint8_t chunk[ODG_PERSIST_CHUNK_], *p = dst != NULL ? dst : chunk;
    uint32_t crc, k;
    n -= 4u; /* the bytes before the CRC */
    crc = odg_crc32(0, h, n);
    for (addr += n + 4u; len > 0u; addr += k, len -= k) {
        k = dst == NULL && len > ODG_PERSIST_CHUNK_ ? ODG_PERSIST_CHUNK_ : len; /* into dst at once */
        if (nv->read(nv->ctx, addr, p, k) != 0) {
            return -1;
        }
        crc = odg_crc32(crc, p, k);
    }
    h += n; /* ODG_LE32 inline, from one pointer: one load where the core allows */
    return crc == ODG_LE32(h);
}

/* Whether the slot at `addr` is erased (every byte 0xFF): 1 yes, 0 no, -1 the driver failed. */
int odg_slot_blank_(const odg_nv_driver_t *nv, uint32_t addr, uint32_t size)
{
    uint8_t chunk[ODG_PERSIST_CHUNK_];
    uint32_t n;
    while (size > 0u) {
        n = size < ODG_PERSIST_CHUNK_ ? size : ODG_PERSIST_CHUNK_;
        if (nv->read(nv->ctx, addr, chunk, n) != 0) {
            return -1;
        }
        for (addr += n, size -= n; n > 0u; n--) { /* the chunk's bytes from its last */
            if (chunk[n - 1u] != 0xFFu) {
                return 0;
            }
        }
    }
    return 1;
}

/* Erase the bytes from `from` up to `to` (none when to <= from): whether the driver failed, as
 * the driver answered (not 0 when it failed; the callers only test it). */
int odg_wipe_(const odg_nv_driver_t *nv, uint32_t from, uint32_t to)
{
    return from < to ? nv->erase(nv->ctx, from, to - from) : 0;
}

/* Erase the bytes from `from` up to `to` that are not erased yet: whether the driver failed (not
 * 0, as odg_wipe_). */
int odg_clear_(const odg_nv_driver_t *nv, uint32_t from, uint32_t to)
{
    int v = from < to ? odg_slot_blank_(nv, from, to - from) : 1;
    return v == 0 ? odg_wipe_(nv, from, to) : v < 0;
}

/* total + n, at most 255 */
uint8_t odg_add_sat_(uint8_t total, uint16_t n)
{
    return (uint8_t)(total + n > 255u ? 255u : total + n);
}

/* ---- the groups: their NV extent and defaults ------------------------------------------ */

uint32_t odg_persist_nv_size(const odg_dict_t *dict)
{
    const odg_group_t *gr = dict->groups;
    uint32_t end = 0, e;
    unsigned n;
    for (n = dict->n_groups; n > 0u; n--, gr++) {
        e = gr->nv_addr + (ODG_MIGRATES_(gr) ? gr->region : 2u * ODG_PERSIST_SLOT_SIZE(gr->size));
        end = e > end ? e : end;
    }
    return end;
}

/* Defaults into the mirror of group `g`, with the node-id added to $NODEID values (what
 * odg_init does for the whole dictionary). */
void odg_defaults_(const odg_dict_t *d, uint8_t g)
{
    odg_group_reset(&d->groups[g]);
    odg_add_node_id_(d, ODG_S_PERSIST | (unsigned)g << 2);
}
