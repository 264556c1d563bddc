/* SPDX-License-Identifier: Apache-2.0 */
/*
 * odg_persist_migrate.h - self-describing images and boot migration (odg_persist_migrate.c):
 * what the persistence layer (odg_persist.c) calls for a group generated with migration.
 * Not part of the API; without migration (ODG_CFG_PERSIST_MIGRATION 0) none of it exists.
 */
#ifndef ODG_PERSIST_MIGRATE_H
#define ODG_PERSIST_MIGRATE_H

#include "odg_persist_impl.h"

#if ODG_CFG_PERSIST_MIGRATION
/* Boot group `g`: find its newest image at any place it may have had, migrate it to the
 * firmware's layout, store the result when anything changed, clear the rest of its region. */
odg_boot_status_t odg_described_boot_(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g,
                                      odg_boot_t *b);
/* 0x1010 (load 0): the mirror as the group's newest image; 0x1011 (load 1): a mark as the
 * newest image, so that the group's next boot uses the defaults. */
odg_abort_t odg_described_store_(const odg_dict_t *d, const odg_nv_driver_t *nv, uint8_t g, int load);
#endif

#endif /* ODG_PERSIST_MIGRATE_H */
