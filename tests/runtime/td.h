/*
 * td.h - a HAND-WRITTEN object dictionary "td" for the runtime tests, laid out exactly as
 * odgen's templates emit one (one struct per storage class with const defaults; const
 * descriptor tables whose values are offsetof() into those structs, a DOMAIN table, limits
 * keyed by sub position; hook map and slots, persistence groups, state, reset). It covers
 * every basic data type 0x01-0x1B, rom/ram/persist storage, $NODEID values, dense and sparse
 * entries, a hooked entry of each kind, and the 0x1010/0x1011 commands.
 */
#ifndef TD_H
#define TD_H

#include <stdint.h>

#include "odg.h"
#include "odg_persist.h" /* as a generated NAME.h does */

#ifndef ODG_ATTR_ROM
#define ODG_ATTR_ROM
#endif
#ifndef ODG_ATTR_RAM
#define ODG_ATTR_RAM
#endif
#ifndef TD_NV_BASE
#define TD_NV_BASE 0u
#endif

#define TD_POS_2300_S1 64u /* first hooked sub */
#define TD_N_ENTRIES 40u
#define TD_N_SUBS 78u
#define TD_N_HOOKS 6u
#define TD_N_LIMITS 10u
#define TD_N_DOMAINS 3u

/* td_rom: ODG_ATTR_ROM */
typedef struct {
    uint32_t x1000;
    uint32_t x1018_s1;
    uint32_t x1018_s2;
    uint32_t x1018_s3;
    char x1008[9];
    uint8_t x1010_s0;
    uint8_t x1011_s0;
    uint8_t x1018_s0;
    uint8_t x1400_s0;
    uint8_t x2100_s0;
    uint8_t x2200_s0;
    uint8_t x2300_s0;
    uint8_t x2500_s0;
} td_rom_t;
extern const td_rom_t td_rom;

/* td_ram: ODG_ATTR_RAM */
typedef struct {
    uint64_t x200C;
    uint64_t x200D;
    double x2011;
    int64_t x2012;
    int64_t x2013;
    int64_t x2014;
    int64_t x2015;
    uint64_t x2018;
    uint64_t x2019;
    uint64_t x201A;
    uint64_t x201B;
    double x2200_s4;
    uint64_t x2200_s6;
    int64_t x2200_s7;
    int64_t x2200_s8;
    uint32_t x1014;
    uint32_t x1018_s4;
    int32_t x2004;
    uint32_t x2007;
    float x2008;
    uint32_t x200F_len;
    int32_t x2010;
    uint32_t x2016;
    uint32_t x2100_s5;
    uint32_t x2200_s2;
    float x2200_s3;
    int32_t x2200_s5;
    float x2200_s9;
    uint32_t x2300_s1;
    uint32_t x2300_s6_len;
    uint32_t x2400;
    uint32_t x2401;
    int16_t x2003;
    uint16_t x2006;
    uint16_t x200B[5];
    uint16_t x2100_s1;
    uint16_t x2101_s1;
    uint16_t x2101_s2;
    int16_t x2200_s1;
    uint16_t x2300_s2;
    uint8_t x2001;
    int8_t x2002;
    uint8_t x2005;
    char x2009[9];
    uint8_t x200A[4];
    uint8_t x200F_buf[16];
    int8_t x2100_s200;
    uint8_t x2300_s3;
    char x2300_s4[9];
    uint8_t x2300_s5;
    uint8_t x2300_s6_buf[8];
} td_ram_t;
extern td_ram_t td_ram;

/* td_persist_comm: ODG_ATTR_PERSIST_COMM */
typedef struct {
    uint32_t x1400_s1;
    uint16_t x1017;
    uint8_t x1400_s2;
} td_persist_comm_t;
extern td_persist_comm_t td_persist_comm;

/* td_persist_app: ODG_ATTR_PERSIST_APP */
typedef struct {
    int64_t x2500_s3;
    uint32_t x2500_s1;
    uint32_t x2500_s4_len;
    uint16_t x2500_s5;
    char x2500_s2[9];
    uint8_t x2500_s4_buf[8];
} td_persist_app_t;
extern td_persist_app_t td_persist_app;

#define TD_GROUP_COMM 0u
#define TD_GROUP_APP 1u
#define TD_SIGNATURE_COMM 0x5C0FFEE1u
#define TD_SIGNATURE_APP 0xA991A992u

/* The dictionary. */
extern const odg_dict_t td;

/* The FLASH defaults of the RAM structs (generated as static; exported for the tests). */
extern const td_ram_t td_ram_defaults;
extern const td_persist_comm_t td_persist_comm_defaults;
extern const td_persist_app_t td_persist_app_defaults;

/* Declared by the options file as the hook of 0x2300sub3: registered in the slot table. */
odg_abort_t td_notice(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, uint32_t len,
                      void *ctx);

/* The generated switch lookup, for a copy of td that uses it instead of binary search. */
int32_t td_find_switch(uint16_t index);

#endif /* TD_H */
