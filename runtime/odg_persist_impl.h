/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_persist_impl.h - what the persistence layer's sources share: the slots and CRC-32
 * and the defaults of a group (odg_persist_slot.c), the fixed-layout images (odg_persist_fixed.c).
 * Not part of the API.
 */
#ifndef ODG_PERSIST_IMPL_H
#define ODG_PERSIST_IMPL_H

#include "odg_impl.h"
#include "odg_persist.h"

/* Whether group `g` keeps self-describing images (it has a layout descriptor); a build for
 * dictionaries whose every group migrates (ODG_CFG_PERSIST_ODG1 0) leaves the fixed-layout
 * paths out. */
#if !ODG_CFG_PERSIST_MIGRATION
#define ODG_MIGRATES_(g) 0
#elif ODG_CFG_PERSIST_ODG1
#define ODG_MIGRATES_(g) ((g)->n_layout != 0u)
#else
#define ODG_MIGRATES_(g) 1
#endif

/* The end of the groups' NV (odg_persist_nv_size): a constant distance from the start of
 * groups[0]'s region when NAME_config.h gives it (a dictionary whose groups all migrate: the
 * generated C checks it against NAME_NV_SIZE, whatever NAME_NV_BASE), else computed. */
#ifdef ODG_PERSIST_NV_TAIL
#define ODG_NV_END_(d) ((d)->groups[0].nv_addr + ODG_PERSIST_NV_TAIL)
#else
#define ODG_NV_END_(d) odg_persist_nv_size(d)
#endif

#define ODG_PERSIST_ODG1_MAGIC 0x3147444Fu /* "ODG1" as a little-endian UNSIGNED32 */
#define ODG_PERSIST_CHUNK_ 32u /* bytes read at a time when only checking a slot */

/* ---- slots, CRC-32, the groups' NV extent and defaults (odg_persist_slot.c) ---- */
void odg_put32_(uint8_t *p, uint32_t v);
uint32_t odg_get32_(const uint8_t *p);
/* a is newer than b: a - b in 1 .. 2^31 - 1 (ODG_NEWER_ inline, for unsigned 32-bit a and b) */
#define ODG_NEWER_(a, b) ((uint32_t)((a) - (b) - 1u) < 0x7FFFFFFFu)
int odg_newer_(uint32_t a, uint32_t b);
int odg_hdr_read_(const odg_nv_driver_t *nv, uint32_t addr, uint8_t *h, uint32_t n, uint32_t magic);
int odg_crc_ok_(const odg_nv_driver_t *nv, uint32_t addr, const uint8_t *h, uint32_t n, uint32_t len,
                uint8_t *dst);
int odg_slot_blank_(const odg_nv_driver_t *nv, uint32_t addr, uint32_t size);
int odg_wipe_(const odg_nv_driver_t *nv, uint32_t from, uint32_t to); /* failed: not 0 */
int odg_clear_(const odg_nv_driver_t *nv, uint32_t from, uint32_t to);
uint8_t odg_add_sat_(uint8_t total, uint16_t n);
void odg_defaults_(const odg_dict_t *d, uint8_t g);

/* ---- fixed-layout images (odg_persist_fixed.c) ---- */
int odg_fixed_read_(const odg_nv_driver_t *nv, uint32_t addr, uint32_t max, uint8_t *hdr, uint8_t *dst);
odg_boot_status_t odg_fixed_boot_(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g,
                                  odg_boot_t *b);
odg_abort_t odg_fixed_store_(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g);
odg_abort_t odg_fixed_erase_(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g);

#endif /* ODG_PERSIST_IMPL_H */
