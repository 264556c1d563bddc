/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_persist.h - the persistence layer's API: boot every persistence group from NV, answer
 * "save" / "load" (0x1010 / 0x1011), and what a boot reports (docs/persistence.md, the rule
 * set). The NV driver (odg_nv_driver_t) and the group tables (odg_group_t) are part of the
 * dictionary (odg.h). Sources: odg_persist.c (the layer), odg_persist_slot.c (slots and
 * CRC-32), odg_persist_fixed.c (fixed-layout images and
 * records of other layers), odg_persist_migrate.c (self-describing
 * images and boot migration).
 */
#ifndef ODG_PERSIST_H
#define ODG_PERSIST_H

#include "odg.h"

#ifdef __cplusplus
extern "C" {
#endif

/* NV layout of a group: two slots, at nv_addr and nv_addr + ODG_PERSIST_SLOT_SIZE(size); a slot
 * is a 20-byte header and the image, rounded up to ODG_PERSIST_ALIGN (a power of two; set it to
 * the erase page size of a page-erased flash so that each slot has pages of its own). A constant
 * expression, so generated group tables can place the slots. */
#ifndef ODG_PERSIST_ALIGN
#define ODG_PERSIST_ALIGN 8u
#endif
#define ODG_PERSIST_HEADER_SIZE 20u
#define ODG_PERSIST_HEADER2_SIZE 24u
/* The largest region of another firmware version whose slot B boot looks for; a power of two
 * (docs/persistence.md). By default the largest region the options file allows (16 MiB), so that
 * a group whose region changes between two sizes above 64 KiB still finds its slot B: the places
 * past the NV cost no read. */
#ifndef ODG_PERSIST_MAX_REGION
#define ODG_PERSIST_MAX_REGION 0x1000000u
#endif /* "ODG2": magic, sequence, id, region, length, CRC */
#define ODG_PERSIST_SLOT_SIZE(size)                                                     \
    ((((uint32_t)(size)) + ODG_PERSIST_HEADER_SIZE + ((uint32_t)ODG_PERSIST_ALIGN - 1u)) \
     & ~((uint32_t)ODG_PERSIST_ALIGN - 1u))

/* Outcome of odg_persist_init for one group. */
typedef enum odg_boot_status {
    ODG_BOOT_LOADED = 0,     /* newest valid slot with a matching signature was loaded */
    ODG_BOOT_DEFAULTS = 1,   /* both slots erased (first boot, restore requested): defaults, written to NV */
    ODG_BOOT_SIGNATURE = 2,  /* an image of another layout was found: defaults, written to NV */
    ODG_BOOT_NV_ERROR = 3,   /* the driver failed: defaults in RAM, NV untouched */
    ODG_BOOT_DAMAGED = 4,    /* no valid image, but a slot was not erased either (bits flipped,
                              * a torn write or erase): stored values lost; defaults, written to NV */
    ODG_BOOT_MIGRATED = 5    /* an image of another layout: entries converted, defaulted or
                              * dropped (odg_boot_t counts them); the migrated image written to NV */
} odg_boot_status_t;

/* odg_state_t.boot_seen bit (beside 1 << status): a migration defaulted or dropped an entry. */
#define ODG_BOOT_ENTRIES_LOST 0x80u

/* odg_state_t.boot_seen bits meaning that values stored in NV did not come back at boot. */
#define ODG_BOOT_LOST_MASK \
    (1u << ODG_BOOT_SIGNATURE | 1u << ODG_BOOT_NV_ERROR | 1u << ODG_BOOT_DAMAGED | ODG_BOOT_ENTRIES_LOST)

/* What the boot did to one group: the status and, when an image was found, its entries kept,
 * converted (widened, a string or domain cut, sub 0 of an array whose length changed),
 * defaulted (stored, but retyped, narrowed or out of the current limits: lost), dropped (no
 * longer in the group: lost) and added (new in the group: the default, nothing lost). */
typedef struct odg_boot {
    uint8_t status;          /* odg_boot_status_t */
    uint16_t kept;
    uint16_t converted;
    uint16_t defaulted;
    uint16_t dropped;
    uint16_t added;
} odg_boot_t;

/* The persistence layer's state: a client of the dictionary (it answers 0x1010/0x1011) and
 * the NV driver. Lives as long as it is attached (until the next odg_init). */
typedef struct odg_persist {
    odg_client_t client;
    const odg_nv_driver_t *nv;
} odg_persist_t;

/* After odg_init: attach `p` with driver `nv` to the dictionary, then load every group from
 * NV; a group without a valid image keeps the mirror odg_init's reset produced and writes it
 * to NV. Status per group goes into `boot` (may be NULL; dict->n_groups entries) and
 * dict->state->boot_seen; then the clients hear odg_changed(NULL). HARDWARE when a group's NV
 * failed (that group runs on defaults); DATA_STORE, nothing attached, when `nv` is NULL. */
odg_abort_t odg_persist_init(odg_persist_t *p, const odg_dict_t *dict, const odg_nv_driver_t *nv,
                             odg_boot_status_t *boot);

/* odg_persist_init that also reports the counts of each group (dict->n_groups entries of
 * `boot`; may be NULL). */
odg_abort_t odg_persist_boot(odg_persist_t *p, const odg_dict_t *dict, const odg_nv_driver_t *nv,
                             odg_boot_t *boot);

/* NV bytes the groups of `dict` use from address 0: the end of the last group's region (of its
 * two "ODG1" slots for a group without a layout). */
uint32_t odg_persist_nv_size(const odg_dict_t *dict);

/* Bytes one slot of a group of `size` bytes takes in NV: ODG_PERSIST_SLOT_SIZE(size). */
uint32_t odg_persist_slot_size(uint32_t size);

/* Store group `g` (its RAM mirror) into the older of its two slots, newest sequence, with the
 * driver of the attached odg_persist_t; DATA_STORE when none is attached. */
odg_abort_t odg_persist_store(const odg_dict_t *dict, uint8_t g);

/* Make the next boot of group `g` use the defaults (invalidates both slots). */
odg_abort_t odg_persist_restore(const odg_dict_t *dict, uint8_t g);

/* A record of another layer (not a dictionary group: the LSS slave's configuration, say):
 * one UNSIGNED32 kept power-safe in two slots of ODG_PERSIST_RECORD_SLOT bytes each from NV
 * address `addr` (odg_persist_fixed.c). `tag` names the record's layout; it begins each valid
 * slot, so it must have no byte 0xFF and must differ from the groups' "ODG1" and "ODG2".
 * Store: OK, HARDWARE (the driver failed, or the slot read back differs), DATA_STORE (no
 * driver). Load into `value`: 1 loaded, 0 none stored (or of another tag), -1 the driver
 * failed or there is none; `value` is untouched unless 1. */
#define ODG_PERSIST_RECORD_SLOT \
    ((16u + ((uint32_t)ODG_PERSIST_ALIGN - 1u)) & ~((uint32_t)ODG_PERSIST_ALIGN - 1u))
odg_abort_t odg_persist_store_record(const odg_nv_driver_t *nv, uint32_t addr, uint32_t tag,
                                     uint32_t value);
int odg_persist_load_record(const odg_nv_driver_t *nv, uint32_t addr, uint32_t tag, uint32_t *value);

/* CRC-32 (IEEE 802.3, reflected, init and final xor 0xFFFFFFFF). */
uint32_t odg_crc32(uint32_t crc, const void *data, uint32_t len);

#ifdef __cplusplus
}
#endif

#endif /* ODG_PERSIST_H */
