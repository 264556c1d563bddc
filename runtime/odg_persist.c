/*
 * odg_persist.c - persistence groups in NV memory, safe against power loss.
 *
 * Each group has two slots (A at nv_addr, B right after it). A slot is a header followed by
 * the image (the group's RAM mirror, byte for byte):
 *
 *   offset  size  field (all little-endian, encoded byte by byte)
 *        0     4  magic "ODG1" (0x4F 0x44 0x47 0x31): the commit mark, written last
 *        4     4  sequence number (serial arithmetic: wraps around)
 *        8     4  layout signature of the group (odg_group_t.signature)
 *       12     4  image length in bytes
 *       16     4  CRC-32 of bytes 0..15 and the image
 *       20     n  image
 *
 * A slot is valid when its magic is complete, its length fits the slot and the CRC matches.
 * A store goes to the slot that does NOT hold the newest valid image: erase it, write the
 * image, write header bytes 4..19, and only then the 4 magic bytes. Until the last magic byte
 * lands the slot is invalid (an erased or half-written magic differs from "ODG1", whose
 * bytes are all different from the erased value 0xFF), and the other slot, untouched, still
 * holds the previous image. So a power cut at any byte leaves the old image or the new one,
 * never a mix; corrupted bits beyond that are caught by the CRC. Boot takes the valid slot
 * with the newest sequence number.
 *
 * The layer is a client of the dictionary (odg_client_t): odg_persist_init attaches it, and
 * the core hands it the "save" / "load" commands written to 0x1010 / 0x1011.
 */
#include <string.h>

#include "odg.h"
#include "odg_impl.h"

#define HDR ODG_PERSIST_HEADER_SIZE
#define MAGIC 0x3147444Fu /* "ODG1" as a little-endian UNSIGNED32 */
#define CHUNK 32u         /* bytes read at a time when only checking a slot */

/* ---- CRC-32 (IEEE 802.3), 4 bits at a time ---------------------------------------------- */

uint32_t odg_crc32(uint32_t crc, const void *data, uint32_t len)
{
    static const uint32_t t[16] = {
        0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu, 0x76DC4190u, 0x6B6B51F4u,
        0x4DB26158u, 0x5005713Cu, 0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
        0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu};
    const uint8_t *p = (const uint8_t *)data;
    crc = ~crc;
    while (len--) {
        crc ^= *p++;
        crc = (crc >> 4) ^ t[crc & 15u];
        crc = (crc >> 4) ^ t[crc & 15u];
    }
    return ~crc;
}

/* ---- header encoding -------------------------------------------------------------------- */

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

uint32_t odg_persist_slot_size(uint32_t size)
{
    return ODG_PERSIST_SLOT_SIZE(size);
}

static uint32_t slot_addr(const odg_group_t *g, int k)
{
    return g->nv_addr + (k ? ODG_PERSIST_SLOT_SIZE(g->size) : 0u);
}

/* a is newer than b: a - b in 1 .. 2^31 - 1 */
static int newer(uint32_t a, uint32_t b)
{
    return a - b - 1u < 0x7FFFFFFFu;
}

/* Read and check the slot at `addr` (header into `hdr`; the image into `dst` when not NULL,
 * which must hold `max` bytes). 1: valid, 0: not, -1: the driver failed. */
static int slot_read(const odg_nv_driver_t *nv, uint32_t addr, uint32_t max, uint8_t *hdr,
                     uint8_t *dst)
{
    uint8_t chunk[CHUNK];
    uint32_t crc, len, off, n;
    if (nv->read(nv->ctx, addr, hdr, HDR) != 0) {
        return -1;
    }
    len = get32(hdr + 12);
    if (get32(hdr) != MAGIC || len > max) {
        return 0;
    }
    crc = odg_crc32(0, hdr, 16);
    for (off = 0; off < len; off += n) {
        uint8_t *p = dst ? dst + off : chunk;
        n = len - off;
        if (dst == NULL && n > CHUNK) {
            n = CHUNK;
        }
        if (nv->read(nv->ctx, addr + HDR + off, p, n) != 0) {
            return -1;
        }
        crc = odg_crc32(crc, p, n);
    }
    return crc == get32(hdr + 16);
}

/* Check both slots of group `g`: -2 on a driver error, -1 when neither is valid, else the
 * slot (0 or 1) holding the newest valid image, whose header is then in hdr[that slot]. */
static int newest(const odg_nv_driver_t *nv, const odg_group_t *g, uint8_t hdr[2][HDR])
{
    int v[2], k;
    for (k = 0; k < 2; k++) {
        v[k] = slot_read(nv, slot_addr(g, k), g->size, hdr[k], NULL);
        if (v[k] < 0) {
            return -2;
        }
    }
    if (v[0] && v[1]) {
        return newer(get32(hdr[1] + 4), get32(hdr[0] + 4)) ? 1 : 0;
    }
    return v[0] ? 0 : (v[1] ? 1 : -1);
}

/* Whether the slot at `addr` is erased (every byte 0xFF): 1 yes, 0 no, -1 the driver failed. */
static int slot_blank(const odg_nv_driver_t *nv, uint32_t addr, uint32_t size)
{
    uint8_t chunk[CHUNK];
    uint32_t off, n, i;
    for (off = 0; off < size; off += n) {
        n = size - off < CHUNK ? size - off : CHUNK;
        if (nv->read(nv->ctx, addr + off, chunk, n) != 0) {
            return -1;
        }
        for (i = 0; i < n; i++) {
            if (chunk[i] != 0xFFu) {
                return 0;
            }
        }
    }
    return 1;
}

/* No valid image: DEFAULTS when both slots are erased (first boot, after a restore), DAMAGED
 * when something else is there, since then values once stored were lost. */
static odg_boot_status_t no_image(const odg_nv_driver_t *nv, const odg_group_t *g)
{
    uint32_t size = ODG_PERSIST_SLOT_SIZE(g->size);
    int a = slot_blank(nv, slot_addr(g, 0), size), b;
    if (a < 0) {
        return ODG_BOOT_NV_ERROR;
    }
    b = a ? slot_blank(nv, slot_addr(g, 1), size) : 0;
    return b < 0 ? ODG_BOOT_NV_ERROR : (b ? ODG_BOOT_DEFAULTS : ODG_BOOT_DAMAGED);
}

/* Write the mirror of `gr` as the new newest image. */
static odg_abort_t store_group(const odg_nv_driver_t *nv, const odg_group_t *gr)
{
    uint8_t hdr[2][HDR], h[HDR];
    uint32_t addr, seq = 1;
    int k = newest(nv, gr, hdr);
    if (k == -2) {
        return ODG_ABORT_HARDWARE;
    }
    if (k >= 0) {
        seq = get32(hdr[k] + 4) + 1u;
    }
    addr = slot_addr(gr, k == 0);
    put32(h, MAGIC);
    put32(h + 4, seq);
    put32(h + 8, gr->signature);
    put32(h + 12, gr->size);
    /* the CRC covers the bytes as they are now; should the mirror change while it is being
     * written, the read-back below fails and the previous image stays the newest */
    put32(h + 16, odg_crc32(odg_crc32(0, h, 16), gr->mirror, gr->size));
    if (nv->erase(nv->ctx, addr, ODG_PERSIST_SLOT_SIZE(gr->size)) != 0 ||
        nv->write(nv->ctx, addr + HDR, gr->mirror, gr->size) != 0 ||
        nv->write(nv->ctx, addr + 4u, h + 4, HDR - 4u) != 0 ||
        nv->write(nv->ctx, addr, h, 4u) != 0 ||
        slot_read(nv, addr, gr->size, hdr[0], NULL) != 1 || memcmp(hdr[0], h, HDR) != 0) {
        return ODG_ABORT_HARDWARE;
    }
    return ODG_OK;
}

/* Write the mirror of group `g` as the new newest image. */
static odg_abort_t store(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g)
{
    if (nv == NULL || g >= d->n_groups) {
        return ODG_ABORT_DATA_STORE;
    }
    return store_group(nv, &d->groups[g]);
}

odg_abort_t odg_persist_store_record(const odg_nv_driver_t *nv, const odg_group_t *rec)
{
    return nv != NULL ? store_group(nv, rec) : ODG_ABORT_DATA_STORE;
}

int odg_persist_load_record(const odg_nv_driver_t *nv, const odg_group_t *rec)
{
    uint8_t hdr[2][HDR], h[HDR];
    int k = nv != NULL ? newest(nv, rec, hdr) : -2;
    if (k < 0) {
        return k == -1 ? 0 : -1;
    }
    if (get32(hdr[k] + 8) != rec->signature || get32(hdr[k] + 12) != rec->size) {
        return 0;
    }
    return slot_read(nv, slot_addr(rec, k), rec->size, h, (uint8_t *)rec->mirror) == 1 ? 1 : -1;
}

/* Make the next boot of group `g` use the defaults: erase both slots. */
static odg_abort_t erase(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g)
{
    const odg_group_t *gr;
    uint8_t hdr[2][HDR];
    int k;
    if (nv == NULL || g >= d->n_groups) {
        return ODG_ABORT_DATA_STORE;
    }
    gr = &d->groups[g];
    k = newest(nv, gr, hdr);
    if (k == -2) {
        return ODG_ABORT_HARDWARE;
    }
    /* the older slot first: a power cut in between leaves the newest image (nothing
     * happened), never the older one */
    k = k == 0;
    if (nv->erase(nv->ctx, slot_addr(gr, k), ODG_PERSIST_SLOT_SIZE(gr->size)) != 0 ||
        nv->erase(nv->ctx, slot_addr(gr, !k), ODG_PERSIST_SLOT_SIZE(gr->size)) != 0) {
        return ODG_ABORT_HARDWARE;
    }
    return ODG_OK;
}

/* 0x1010 / 0x1011 sub `sub`, handed over by the core: sub 1 acts on every group, another on
 * the groups with that store_sub; DATA_STORE when none has it. */
static odg_abort_t command(odg_client_t *self, const odg_dict_t *d, uint8_t sub, int restore)
{
    const odg_nv_driver_t *nv = ((const odg_persist_t *)(const void *)self)->nv;
    odg_abort_t ac = ODG_ABORT_DATA_STORE;
    uint8_t g;
    for (g = 0; g < d->n_groups; g++) {
        if (sub == 1u || d->groups[g].store_sub == sub) {
            ac = restore ? erase(d, nv, g) : store(d, nv, g);
            if (ac != ODG_OK) {
                break;
            }
        }
    }
    return ac;
}

/* The driver of the persistence layer attached to `d` (the client with its `command`; the
 * client is the first member of odg_persist_t), or NULL. */
static const odg_nv_driver_t *driver(const odg_dict_t *d)
{
    const odg_client_t *c = d->state->clients;
    while (c != NULL && c->command != command) {
        c = c->next;
    }
    return c != NULL ? ((const odg_persist_t *)(const void *)c)->nv : NULL;
}

odg_abort_t odg_persist_store(const odg_dict_t *dict, uint8_t g)
{
    return store(dict, driver(dict), g);
}

odg_abort_t odg_persist_restore(const odg_dict_t *dict, uint8_t g)
{
    return erase(dict, driver(dict), g);
}

/* Defaults into the mirror of group `g`, with the node-id added to $NODEID values (what the
 * generated reset does for the whole dictionary). */
static void defaults(const odg_dict_t *d, uint8_t g)
{
    const odg_group_t *gr = &d->groups[g];
    uint32_t p;
    memcpy(gr->mirror, gr->defaults, gr->size);
    for (p = 0; p < d->n_subs; p++) {
        const odg_sub_t *s = &d->subs[p];
        if ((s->attr & ODG_A_NODEID) && s->storage == (uint8_t)(ODG_S_PERSIST | (unsigned)g << 2)) {
            uint8_t *v = odg_value_(d, s);
            odg_store_(v, s->size, odg_load_(v, s->size) + d->state->node_id);
        }
    }
}

static odg_boot_status_t boot_group(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g)
{
    const odg_group_t *gr = &d->groups[g];
    uint8_t hdr[2][HDR], h[HDR];
    odg_boot_status_t st = ODG_BOOT_DEFAULTS;
    int k = newest(nv, gr, hdr);
    if (k == -2) {
        st = ODG_BOOT_NV_ERROR;
    } else if (k == -1) {
        st = no_image(nv, gr);
    } else {
        if (get32(hdr[k] + 8) != gr->signature || get32(hdr[k] + 12) != gr->size) {
            st = ODG_BOOT_SIGNATURE;
        } else if (slot_read(nv, slot_addr(gr, k), gr->size, h, (uint8_t *)gr->mirror) == 1 &&
                   memcmp(h, hdr[k], HDR) == 0) {
            return ODG_BOOT_LOADED;
        } else {
            st = ODG_BOOT_NV_ERROR; /* it was valid a moment ago: a flaky read */
        }
    }
    defaults(d, g);
    if (st != ODG_BOOT_NV_ERROR && store(d, nv, g) != ODG_OK) {
        st = ODG_BOOT_NV_ERROR;
    }
    return st;
}

odg_abort_t odg_persist_init(odg_persist_t *p, const odg_dict_t *dict, const odg_nv_driver_t *nv,
                             odg_boot_status_t *boot)
{
    odg_abort_t ac = nv != NULL ? ODG_OK : ODG_ABORT_DATA_STORE;
    uint8_t g;
    if (nv != NULL) {
        p->client.command = command;
        p->client.changed = NULL;
        p->nv = nv;
        odg_attach(dict, &p->client);
    }
    dict->state->boot_seen = 0;
    for (g = 0; g < dict->n_groups; g++) {
        odg_boot_status_t st = nv != NULL ? boot_group(dict, nv, g) : ODG_BOOT_NV_ERROR;
        dict->state->boot_seen = (uint8_t)(dict->state->boot_seen | 1u << st);
        if (st == ODG_BOOT_NV_ERROR && ac == ODG_OK) {
            ac = ODG_ABORT_HARDWARE;
        }
        if (boot != NULL) {
            boot[g] = st;
        }
    }
    odg_changed(dict, NULL);
    return ac;
}
