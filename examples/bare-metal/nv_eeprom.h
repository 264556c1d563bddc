/*
 * nv_eeprom.h - the node's NV driver over a byte-writable EEPROM (nv_eeprom.c).
 */
#ifndef NV_EEPROM_H
#define NV_EEPROM_H

#include "odg_persist.h"

extern const odg_nv_driver_t nv_eeprom;

#endif /* NV_EEPROM_H */
