/*
 * td.c - the hand-written test dictionary (see td.h), in the shape odgen's templates give.
 */
#include <math.h>

#include "td.h"

/* REAL32/REAL64 values are IEEE 754 single and double. */
typedef char td_assert_real_sizes[(sizeof(float) == 4 && sizeof(double) == 8) ? 1 : -1];

ODG_ATTR_ROM const td_rom_t td_rom = {
    .x1000 = UINT32_C(0x00020191),
    .x1018_s1 = UINT32_C(0x0000ABCD),
    .x1018_s2 = UINT32_C(0x12345678),
    .x1018_s3 = UINT32_C(0x00010002),
    .x1008 = "odg test",
    .x1010_s0 = 4,
    .x1011_s0 = 4,
    .x1018_s0 = 4,
    .x1400_s0 = 2,
    .x2100_s0 = 200,
    .x2200_s0 = 9,
    .x2300_s0 = 6,
    .x2500_s0 = 5,
};

ODG_ATTR_RAM td_ram_t td_ram;
ODG_ATTR_ROM const td_ram_t td_ram_defaults = {
    .x200C = UINT64_C(0x00001234000ABCDE), /* TIME_OF_DAY: 0x0ABCDE ms, day 0x1234 */
    .x200D = UINT64_C(0x0000000700000005),
    .x2011 = -2.25,
    .x2012 = -INT64_C(549755813888), /* INTEGER40 minimum */
    .x2013 = INT64_C(140737488355327), /* INTEGER48 maximum */
    .x2014 = INT64_C(-1),
    .x2015 = (-INT64_C(9223372036854775807) - 1),
    .x2018 = UINT64_C(0xFFFFFFFFFF),
    .x2019 = UINT64_C(0x123456789ABC),
    .x201A = UINT64_C(0xFFEEDDCCBBAA99),
    .x201B = UINT64_C(0xFEDCBA9876543210),
    .x2200_s4 = 1.0,
    .x2200_s6 = UINT64_C(0x1),
    .x2200_s7 = INT64_C(-10),
    .x2200_s8 = INT64_C(0),
    .x1014 = UINT32_C(0x80), /* $NODEID+0x80 */
    .x1018_s4 = UINT32_C(0x0),
    .x2004 = INT32_C(-70000),
    .x2007 = UINT32_C(0x89ABCDEF),
    .x2008 = 1.5f,
    .x200F_len = UINT32_C(3),
    .x2010 = INT32_C(-2),
    .x2016 = UINT32_C(0xFEDCBA),
    .x2100_s5 = UINT32_C(0x55555555),
    .x2200_s2 = UINT32_C(0xA),
    .x2200_s3 = 0.0f,
    .x2200_s5 = INT32_C(0),
    .x2200_s9 = 0.0f,
    .x2300_s1 = UINT32_C(0x0),
    .x2300_s6_len = UINT32_C(0),
    .x2400 = UINT32_C(0x0),
    .x2401 = UINT32_C(0x2401),
    .x2003 = -300,
    .x2006 = 0xABCD,
    .x200B = {0x0068, 0x0069, 0},
    .x2100_s1 = 0x1111,
    .x2101_s1 = 1,
    .x2101_s2 = 2,
    .x2200_s1 = 0,
    .x2300_s2 = 0,
    .x2001 = 1,
    .x2002 = -2,
    .x2005 = 0xAB,
    .x2009 = "abc",
    .x200A = {0x01, 0x02, 0x03, 0x04},
    .x200F_buf = {0xDE, 0xAD, 0xBE},
    .x2100_s200 = -56,
    .x2300_s3 = 0,
    .x2300_s4 = "",
    .x2300_s5 = 0,
    .x2300_s6_buf = {0},
};

ODG_ATTR_RAM td_persist_comm_t td_persist_comm;
ODG_ATTR_ROM const td_persist_comm_t td_persist_comm_defaults = {
    .x1400_s1 = UINT32_C(0x200), /* $NODEID+0x200 */
    .x1017 = 1000,
    .x1400_s2 = 0xFE,
};

ODG_ATTR_RAM td_persist_app_t td_persist_app;
ODG_ATTR_ROM const td_persist_app_t td_persist_app_defaults = {
    .x2500_s3 = INT64_C(-7),
    .x2500_s1 = UINT32_C(0x11223344),
    .x2500_s4_len = UINT32_C(2),
    .x2500_s5 = 0x100, /* $NODEID+0x100 */
    .x2500_s2 = "app",
    .x2500_s4_buf = {0x01, 0x02},
};

/* DOMAIN descriptors, indexed by the offset of their odg_sub_t */
ODG_ATTR_ROM static const odg_domain_t td_domains[3] = {
    {td_ram.x200F_buf, &td_ram.x200F_len, 16u},                   /* 0: 0x200F */
    {td_ram.x2300_s6_buf, &td_ram.x2300_s6_len, 8u},              /* 1: 0x2300sub6 */
    {td_persist_app.x2500_s4_buf, &td_persist_app.x2500_s4_len, 8u}, /* 2: 0x2500sub4 */
};

ODG_ATTR_ROM static const odg_entry_t td_entries[40] = {
    {0x1000, 0, 1, ODG_OBJ_VAR | ODG_E_DENSE},     /* Device type */
    {0x1008, 1, 1, ODG_OBJ_VAR | ODG_E_DENSE},     /* Device name */
    {0x1010, 2, 5, ODG_OBJ_ARRAY | ODG_E_DENSE},   /* Store parameters */
    {0x1011, 7, 5, ODG_OBJ_ARRAY | ODG_E_DENSE},   /* Restore default parameters */
    {0x1014, 12, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* COB-ID EMCY */
    {0x1017, 13, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* Producer heartbeat time */
    {0x1018, 14, 5, ODG_OBJ_RECORD | ODG_E_DENSE}, /* Identity */
    {0x1400, 19, 3, ODG_OBJ_RECORD | ODG_E_DENSE}, /* RPDO 1 communication */
    {0x2001, 22, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* BOOLEAN */
    {0x2002, 23, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* INTEGER8 */
    {0x2003, 24, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* INTEGER16 */
    {0x2004, 25, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* INTEGER32 */
    {0x2005, 26, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* UNSIGNED8 */
    {0x2006, 27, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* UNSIGNED16 */
    {0x2007, 28, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* UNSIGNED32 */
    {0x2008, 29, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* REAL32 */
    {0x2009, 30, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* VISIBLE_STRING */
    {0x200A, 31, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* OCTET_STRING */
    {0x200B, 32, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* UNICODE_STRING */
    {0x200C, 33, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* TIME_OF_DAY */
    {0x200D, 34, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* TIME_DIFFERENCE */
    {0x200F, 35, 1, ODG_OBJ_DOMAIN | ODG_E_DENSE}, /* DOMAIN */
    {0x2010, 36, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* INTEGER24 */
    {0x2011, 37, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* REAL64 */
    {0x2012, 38, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* INTEGER40 */
    {0x2013, 39, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* INTEGER48 */
    {0x2014, 40, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* INTEGER56 */
    {0x2015, 41, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* INTEGER64 */
    {0x2016, 42, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* UNSIGNED24 */
    {0x2018, 43, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* UNSIGNED40 */
    {0x2019, 44, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* UNSIGNED48 */
    {0x201A, 45, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* UNSIGNED56 */
    {0x201B, 46, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* UNSIGNED64 */
    {0x2100, 47, 4, ODG_OBJ_RECORD},               /* sparse record: subs 0, 1, 5, 200 */
    {0x2101, 51, 2, ODG_OBJ_ARRAY},                /* sparse: subs 1, 2 (no sub 0) */
    {0x2200, 53, 10, ODG_OBJ_RECORD | ODG_E_DENSE}, /* limits */
    {0x2300, 63, 7, ODG_OBJ_RECORD | ODG_E_DENSE}, /* hooks */
    {0x2400, 70, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* write-only */
    {0x2401, 71, 1, ODG_OBJ_VAR | ODG_E_DENSE},    /* read-only in RAM */
    {0x2500, 72, 6, ODG_OBJ_RECORD | ODG_E_DENSE}, /* application parameters, persisted */
};

#define RW (ODG_A_READ | ODG_A_WRITE)
#define PDO (ODG_A_TPDO | ODG_A_RPDO)
#define COMM (ODG_S_PERSIST | (TD_GROUP_COMM << 2))
#define APP (ODG_S_PERSIST | (TD_GROUP_APP << 2))

/* offset, size, sub, type, attr, storage: offsetof() into the struct of the storage class,
 * for a DOMAIN the index into td_domains, for 0x1010/0x1011 commands 0 */
ODG_ATTR_ROM static const odg_sub_t td_subs[78] = {
    {offsetof(td_rom_t, x1000), 4, 0, 0x07, ODG_A_READ, ODG_S_ROM},                   /* 0 */
    {offsetof(td_rom_t, x1008), 8, 0, 0x09, ODG_A_READ, ODG_S_ROM},                   /* 1 */
    {offsetof(td_rom_t, x1010_s0), 1, 0, 0x05, ODG_A_READ, ODG_S_ROM},                /* 2 */
    {0, 4, 1, 0x07, RW, ODG_S_COMMAND},                                                 /* 3: save all */
    {0, 4, 2, 0x07, RW, ODG_S_COMMAND},                                                 /* 4: comm */
    {0, 4, 3, 0x07, RW, ODG_S_COMMAND},                                                 /* 5: app */
    {0, 4, 4, 0x07, RW, ODG_S_COMMAND},                                                 /* 6: no group */
    {offsetof(td_rom_t, x1011_s0), 1, 0, 0x05, ODG_A_READ, ODG_S_ROM},                /* 7 */
    {0, 4, 1, 0x07, RW, ODG_S_COMMAND | ODG_S_RESTORE_FLAG},                            /* 8 */
    {0, 4, 2, 0x07, RW, ODG_S_COMMAND | ODG_S_RESTORE_FLAG},                            /* 9 */
    {0, 4, 3, 0x07, RW, ODG_S_COMMAND | ODG_S_RESTORE_FLAG},                            /* 10 */
    {0, 4, 4, 0x07, RW, ODG_S_COMMAND | ODG_S_RESTORE_FLAG},                            /* 11 */
    {offsetof(td_ram_t, x1014), 4, 0, 0x07, RW | ODG_A_NODEID, ODG_S_RAM},            /* 12 */
    {offsetof(td_persist_comm_t, x1017), 2, 0, 0x06, RW, COMM},                       /* 13 */
    {offsetof(td_rom_t, x1018_s0), 1, 0, 0x05, ODG_A_READ, ODG_S_ROM},                /* 14 */
    {offsetof(td_rom_t, x1018_s1), 4, 1, 0x07, ODG_A_READ, ODG_S_ROM},                /* 15 */
    {offsetof(td_rom_t, x1018_s2), 4, 2, 0x07, ODG_A_READ, ODG_S_ROM},                /* 16 */
    {offsetof(td_rom_t, x1018_s3), 4, 3, 0x07, ODG_A_READ, ODG_S_ROM},                /* 17 */
    {offsetof(td_ram_t, x1018_s4), 4, 4, 0x07, ODG_A_READ | ODG_A_TPDO, ODG_S_RAM},   /* 18 */
    {offsetof(td_rom_t, x1400_s0), 1, 0, 0x05, ODG_A_READ, ODG_S_ROM},                /* 19 */
    {offsetof(td_persist_comm_t, x1400_s1), 4, 1, 0x07, RW | ODG_A_NODEID, COMM},     /* 20 */
    {offsetof(td_persist_comm_t, x1400_s2), 1, 2, 0x05, RW, COMM},                    /* 21 */
    {offsetof(td_ram_t, x2001), 1, 0, 0x01, RW | PDO, ODG_S_RAM},                     /* 22 */
    {offsetof(td_ram_t, x2002), 1, 0, 0x02, RW | PDO, ODG_S_RAM},                     /* 23 */
    {offsetof(td_ram_t, x2003), 2, 0, 0x03, RW | PDO, ODG_S_RAM},                     /* 24 */
    {offsetof(td_ram_t, x2004), 4, 0, 0x04, RW | PDO, ODG_S_RAM},                     /* 25 */
    {offsetof(td_ram_t, x2005), 1, 0, 0x05, RW | PDO, ODG_S_RAM},                     /* 26 */
    {offsetof(td_ram_t, x2006), 2, 0, 0x06, RW | PDO, ODG_S_RAM},                     /* 27 */
    {offsetof(td_ram_t, x2007), 4, 0, 0x07, RW | PDO, ODG_S_RAM},                     /* 28 */
    {offsetof(td_ram_t, x2008), 4, 0, 0x08, RW | PDO, ODG_S_RAM},                     /* 29 */
    {offsetof(td_ram_t, x2009), 8, 0, 0x09, RW, ODG_S_RAM},                           /* 30 */
    {offsetof(td_ram_t, x200A), 4, 0, 0x0A, RW, ODG_S_RAM},                           /* 31 */
    {offsetof(td_ram_t, x200B), 8, 0, 0x0B, RW, ODG_S_RAM},                           /* 32 */
    {offsetof(td_ram_t, x200C), 6, 0, 0x0C, RW | PDO, ODG_S_RAM},                     /* 33 */
    {offsetof(td_ram_t, x200D), 6, 0, 0x0D, RW | PDO, ODG_S_RAM},                     /* 34 */
    {0, 16, 0, 0x0F, RW, ODG_S_RAM},                                                  /* 35: td_domains[0] */
    {offsetof(td_ram_t, x2010), 3, 0, 0x10, RW | PDO, ODG_S_RAM},                     /* 36 */
    {offsetof(td_ram_t, x2011), 8, 0, 0x11, RW | PDO, ODG_S_RAM},                     /* 37 */
    {offsetof(td_ram_t, x2012), 5, 0, 0x12, RW | PDO, ODG_S_RAM},                     /* 38 */
    {offsetof(td_ram_t, x2013), 6, 0, 0x13, RW | PDO, ODG_S_RAM},                     /* 39 */
    {offsetof(td_ram_t, x2014), 7, 0, 0x14, RW | PDO, ODG_S_RAM},                     /* 40 */
    {offsetof(td_ram_t, x2015), 8, 0, 0x15, RW | PDO, ODG_S_RAM},                     /* 41 */
    {offsetof(td_ram_t, x2016), 3, 0, 0x16, RW | PDO, ODG_S_RAM},                     /* 42 */
    {offsetof(td_ram_t, x2018), 5, 0, 0x18, RW | PDO, ODG_S_RAM},                     /* 43 */
    {offsetof(td_ram_t, x2019), 6, 0, 0x19, RW | PDO, ODG_S_RAM},                     /* 44 */
    {offsetof(td_ram_t, x201A), 7, 0, 0x1A, RW | PDO, ODG_S_RAM},                     /* 45 */
    {offsetof(td_ram_t, x201B), 8, 0, 0x1B, RW | PDO, ODG_S_RAM},                     /* 46 */
    {offsetof(td_rom_t, x2100_s0), 1, 0, 0x05, ODG_A_READ, ODG_S_ROM},                /* 47 */
    {offsetof(td_ram_t, x2100_s1), 2, 1, 0x06, RW, ODG_S_RAM},                        /* 48 */
    {offsetof(td_ram_t, x2100_s5), 4, 5, 0x07, RW, ODG_S_RAM},                        /* 49 */
    {offsetof(td_ram_t, x2100_s200), 1, 200, 0x02, RW, ODG_S_RAM},                    /* 50 */
    {offsetof(td_ram_t, x2101_s1), 2, 1, 0x06, RW, ODG_S_RAM},                        /* 51 */
    {offsetof(td_ram_t, x2101_s2), 2, 2, 0x06, RW, ODG_S_RAM},                        /* 52 */
    {offsetof(td_rom_t, x2200_s0), 1, 0, 0x05, ODG_A_READ, ODG_S_ROM},                /* 53 */
    {offsetof(td_ram_t, x2200_s1), 2, 1, 0x03, RW | ODG_A_LIMIT, ODG_S_RAM},          /* 54 */
    {offsetof(td_ram_t, x2200_s2), 4, 2, 0x07, RW | ODG_A_LIMIT, ODG_S_RAM},          /* 55 */
    {offsetof(td_ram_t, x2200_s3), 4, 3, 0x08, RW | ODG_A_LIMIT, ODG_S_RAM},          /* 56 */
    {offsetof(td_ram_t, x2200_s4), 8, 4, 0x11, RW | ODG_A_LIMIT, ODG_S_RAM},          /* 57 */
    {offsetof(td_ram_t, x2200_s5), 3, 5, 0x10, RW | ODG_A_LIMIT, ODG_S_RAM},          /* 58 */
    {offsetof(td_ram_t, x2200_s6), 8, 6, 0x1B, RW | ODG_A_LIMIT, ODG_S_RAM},          /* 59 */
    {offsetof(td_ram_t, x2200_s7), 8, 7, 0x15, RW | ODG_A_LIMIT, ODG_S_RAM},          /* 60 */
    {offsetof(td_ram_t, x2200_s8), 5, 8, 0x12, RW | ODG_A_LIMIT, ODG_S_RAM},          /* 61 */
    {offsetof(td_ram_t, x2200_s9), 4, 9, 0x08, RW | ODG_A_LIMIT, ODG_S_RAM},          /* 62 */
    {offsetof(td_rom_t, x2300_s0), 1, 0, 0x05, ODG_A_READ, ODG_S_ROM},                /* 63 */
    {offsetof(td_ram_t, x2300_s1), 4, 1, 0x07, ODG_A_READ | ODG_A_TPDO | ODG_A_HOOK, ODG_S_RAM}, /* 64 */
    {offsetof(td_ram_t, x2300_s2), 2, 2, 0x06, RW | ODG_A_HOOK, ODG_S_RAM},           /* 65 */
    {offsetof(td_ram_t, x2300_s3), 1, 3, 0x05, RW | ODG_A_HOOK, ODG_S_RAM},           /* 66 */
    {offsetof(td_ram_t, x2300_s4), 8, 4, 0x09, RW | ODG_A_HOOK, ODG_S_RAM},           /* 67 */
    {offsetof(td_ram_t, x2300_s5), 1, 5, 0x05, RW | ODG_A_HOOK, ODG_S_RAM},           /* 68 */
    {1, 8, 6, 0x0F, RW | ODG_A_HOOK, ODG_S_RAM},                                      /* 69: td_domains[1] */
    {offsetof(td_ram_t, x2400), 4, 0, 0x07, ODG_A_WRITE | ODG_A_RPDO, ODG_S_RAM},     /* 70 */
    {offsetof(td_ram_t, x2401), 4, 0, 0x07, ODG_A_READ, ODG_S_RAM},                   /* 71 */
    {offsetof(td_rom_t, x2500_s0), 1, 0, 0x05, ODG_A_READ, ODG_S_ROM},                /* 72 */
    {offsetof(td_persist_app_t, x2500_s1), 4, 1, 0x07, RW, APP},                      /* 73 */
    {offsetof(td_persist_app_t, x2500_s2), 8, 2, 0x09, RW, APP},                      /* 74 */
    {offsetof(td_persist_app_t, x2500_s3), 8, 3, 0x15, RW | ODG_A_LIMIT, APP},        /* 75 */
    {2, 8, 4, 0x0F, RW, APP},                                                         /* 76: td_domains[2] */
    {offsetof(td_persist_app_t, x2500_s5), 2, 5, 0x06, RW | ODG_A_NODEID, APP},       /* 77 */
};

/* low, high, sub_pos: sorted by sub_pos */
ODG_ATTR_ROM static const odg_limit_t td_limits[10] = {
    {UINT64_C(0xFFFFFFFFFFFFFF9C), UINT64_C(0x0000000000000064), 54}, /* -100 .. 100 */
    {UINT64_C(0x000000000000000A), UINT64_C(0x00000000000003E8), 55}, /* 10 .. 1000 */
    {UINT64_C(0xBFF8000000000000), UINT64_C(0x4004000000000000), 56}, /* -1.5 .. 2.5 */
    {UINT64_C(0xC08F400000000000), UINT64_C(0x408F400000000000), 57}, /* -1000.0 .. 1000.0 */
    {UINT64_C(0xFFFFFFFFFF85EE00), UINT64_C(0x00000000007A1200), 58}, /* -8000000 .. 8000000 */
    {UINT64_C(0x0000000000000001), UINT64_C(0xFFFFFFFFFFFFFFF0), 59}, /* 1 .. 2^64-16 */
    {UINT64_C(0x8000000000000001), UINT64_C(0xFFFFFFFFFFFFFFFB), 60}, /* -2^63+1 .. -5 */
    {UINT64_C(0xFFFFFF8000000000), UINT64_C(0x0000007FFFFFFFFF), 61}, /* INTEGER40 full range */
    {UINT64_C(0xBFB999999999999A), UINT64_C(0x3FB999999999999A), 62}, /* -0.1 .. 0.1 */
    {UINT64_C(0xFFFFFFFFFFF0BDC0), UINT64_C(0x00000000000F4240), 75}, /* -1000000 .. 1000000 */
};

ODG_ATTR_ROM static const odg_hook_map_t td_hook_map[6] = {
    {64, ODG_HOOK_PRE_READ},                                        /* 0x2300sub1 */
    {65, ODG_HOOK_PRE_WRITE},                                       /* 0x2300sub2 */
    {66, ODG_HOOK_POST_WRITE},                                      /* 0x2300sub3 */
    {67, ODG_HOOK_PRE_WRITE | ODG_HOOK_POST_WRITE},                 /* 0x2300sub4 */
    {68, ODG_HOOK_PRE_WRITE},                                       /* 0x2300sub5 */
    {69, ODG_HOOK_PRE_READ | ODG_HOOK_PRE_WRITE | ODG_HOOK_POST_WRITE}, /* 0x2300sub6 */
};

ODG_ATTR_RAM static odg_hook_slot_t td_hook_slots[6] = {
    {NULL, NULL},      /* 0x2300sub1 */
    {NULL, NULL},      /* 0x2300sub2 */
    {td_notice, NULL}, /* 0x2300sub3 */
    {NULL, NULL},      /* 0x2300sub4 */
    {NULL, NULL},      /* 0x2300sub5 */
    {NULL, NULL},      /* 0x2300sub6 */
};

/* Each group's defaults as one run: a struct of the mirror's layout (odg.h, odg_group_t). */
ODG_ATTR_ROM static const uint16_t td_comm_spread[4] = {0, sizeof(td_persist_comm_t), 0, 0};
ODG_ATTR_ROM static const uint16_t td_app_spread[4] = {0, sizeof(td_persist_app_t), 0, 0};

ODG_ATTR_ROM static const odg_group_t td_groups[2] = {
    {&td_persist_comm, &td_persist_comm_defaults, td_comm_spread, sizeof(td_persist_comm_t), 0x5C0FFEE1u,
     TD_NV_BASE + 0u, 2, 0, 0, 0},
    {&td_persist_app, &td_persist_app_defaults, td_app_spread, sizeof(td_persist_app_t), 0xA991A992u,
     TD_NV_BASE + 0u + 2u * ODG_PERSIST_SLOT_SIZE(sizeof(td_persist_comm_t)), 3, 0, 0, 0},
};

ODG_ATTR_RAM static odg_state_t td_state;

int32_t td_find_switch(uint16_t index)
{
    switch (index) {
    case 0x1000: return 0;
    case 0x1008: return 1;
    case 0x1010: return 2;
    case 0x1011: return 3;
    case 0x1014: return 4;
    case 0x1017: return 5;
    case 0x1018: return 6;
    case 0x1400: return 7;
    case 0x2001: return 8;
    case 0x2002: return 9;
    case 0x2003: return 10;
    case 0x2004: return 11;
    case 0x2005: return 12;
    case 0x2006: return 13;
    case 0x2007: return 14;
    case 0x2008: return 15;
    case 0x2009: return 16;
    case 0x200A: return 17;
    case 0x200B: return 18;
    case 0x200C: return 19;
    case 0x200D: return 20;
    case 0x200F: return 21;
    case 0x2010: return 22;
    case 0x2011: return 23;
    case 0x2012: return 24;
    case 0x2013: return 25;
    case 0x2014: return 26;
    case 0x2015: return 27;
    case 0x2016: return 28;
    case 0x2018: return 29;
    case 0x2019: return 30;
    case 0x201A: return 31;
    case 0x201B: return 32;
    case 0x2100: return 33;
    case 0x2101: return 34;
    case 0x2200: return 35;
    case 0x2300: return 36;
    case 0x2400: return 37;
    case 0x2401: return 38;
    case 0x2500: return 39;
    default: return -1;
    }
}

static void td_reset(const odg_dict_t *dict)
{
    td_ram = td_ram_defaults;
    td_persist_comm = td_persist_comm_defaults;
    td_persist_app = td_persist_app_defaults;
    (void)dict; /* odg_init adds the node-id to the $NODEID values (x1014, x1400_s1, x2500_s5) */
}

ODG_ATTR_ROM const odg_dict_t td = {
    td_entries,
    td_subs,
    &td_rom,
    &td_ram,
    td_domains,
    td_limits,
    td_hook_map,
    td_hook_slots,
    td_groups,
    &td_state,
    NULL,
    td_reset,
    40,
    78,
    6,
    10,
    3,
    2,
    0, /* no boot status object */
    0, 0, 0, 0, 0, NULL, NULL /* no perfect hash: binary search */
};
