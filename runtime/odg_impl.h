/*
 * odg_impl.h - internal helpers shared by odg.c and odg_persist.c. Not part of the API.
 */
#ifndef ODG_IMPL_H
#define ODG_IMPL_H

#include "odg.h"

/* Native value of a numeric sub-entry of wire size `size` (1..8), zero-extended from its
 * C type (uint8_t, uint16_t, uint32_t for 3..4, uint64_t for 5..8; float/double as bits). */
uint64_t odg_load_(const void *p, uint32_t size);

/* Store the low bytes of `v` into the C type that holds a value of wire size `size`. */
void odg_store_(void *p, uint32_t size, uint64_t v);

/* The RAM value behind a descriptor's `const void *data` (never called for ODG_S_ROM). */
void *odg_mut_(const void *p);

#endif /* ODG_IMPL_H */
