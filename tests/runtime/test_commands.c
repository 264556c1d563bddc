/*
 * test_commands.c - "save" and "load" through 0x1010 / 0x1011 of a generated dictionary whose
 * commands share one descriptor (ODG_E_PACKED, tests/runtime/commands.eds): sub 1 acts on every
 * group, sub 2 on the communication group (0x1017), sub 3 on the application group (0x2000),
 * each across reboots on one NV; a read answers the capabilities (1), a wrong word aborts.
 */
#include <string.h>

#include "check.h"
#include "cmd.h"
#include "nv_fault.h"
#include "odg_persist.h"

static uint8_t mem[CMD_NV_SIZE];
static nv_fault_t nv;
static odg_persist_t layer;

static odg_abort_t command(uint16_t index, uint8_t sub, const char *word)
{
    odg_ref_t ref;
    odg_abort_t ac = odg_find(&cmd, index, sub, &ref);
    return ac != ODG_OK ? ac : odg_write(&ref, word, 4);
}

/* The heartbeat time (UNSIGNED16) and the parameter (UNSIGNED8) in native byte order. */
static uint32_t get(uint16_t index)
{
    uint16_t hb = 0;
    uint8_t par = 0;
    if (index == 0x1017) {
        CHECK_EQ(odg_get(&cmd, index, 0, &hb, sizeof hb), ODG_OK);
        return hb;
    }
    CHECK_EQ(odg_get(&cmd, index, 0, &par, sizeof par), ODG_OK);
    return par;
}

static void set(uint16_t index, uint32_t v)
{
    uint16_t hb = (uint16_t)v;
    uint8_t par = (uint8_t)v;
    CHECK_EQ(index == 0x1017 ? odg_set(&cmd, index, 0, &hb, sizeof hb) : odg_set(&cmd, index, 0, &par, sizeof par),
             ODG_OK);
}

/* A reboot: the dictionary from its defaults, then the groups from NV. */
static void reboot(void)
{
    odg_boot_status_t st[2]; /* the groups app and comm */
    CHECK_EQ(odg_init(&cmd, 5), ODG_OK);
    CHECK_EQ(odg_persist_init(&layer, &cmd, &nv.driver, st), ODG_OK);
}

/* `word` written to `index` sub `sub`, a reboot, then what each group serves. */
static void after(uint16_t index, uint8_t sub, const char *word, uint32_t hb, uint32_t par)
{
    CHECK_EQ(command(index, sub, word), ODG_OK);
    reboot();
    CHECK_EQ(get(0x1017), hb);
    CHECK_EQ(get(0x2000), par);
}

int main(void)
{
    odg_ref_t ref;
    uint8_t buf[4];
    uint32_t n = 0;
    uint16_t bad = 0;
    uint8_t sub;
    nv_fault_init(&nv, mem, sizeof mem, 1u);
    reboot();
    CHECK_EQ(odg_verify(&cmd, &bad), ODG_OK);
    for (sub = 1; sub <= 3; sub++) { /* each command reads as its capabilities */
        CHECK_EQ(odg_find(&cmd, 0x1010, sub, &ref), ODG_OK);
        CHECK_EQ(ref.sub->sub, sub);
        CHECK_EQ(odg_read(&ref, 0, buf, sizeof buf, &n), ODG_OK);
        CHECK_EQ(n, 4u);
        CHECK_EQ(buf[0] | buf[1] | buf[2] | buf[3], 1u);
        CHECK_EQ(command(0x1010, sub, "load"), ODG_ABORT_DATA_STORE); /* "save" is the word here */
        CHECK_EQ(command(0x1011, sub, "save"), ODG_ABORT_DATA_STORE);
    }
    CHECK_EQ(command(0x1010, 4, "save"), ODG_ABORT_NO_SUB);

    set(0x1017, 250);
    set(0x2000, 9);
    after(0x1010, 2, "save", 250u, 7u); /* sub 2: the heartbeat time only */
    set(0x1017, 500);
    set(0x2000, 9);
    after(0x1010, 3, "save", 250u, 9u); /* sub 3: the parameter only */
    after(0x1011, 2, "load", 1000u, 9u); /* the communication group back to its defaults */
    set(0x1017, 125);
    set(0x2000, 3);
    after(0x1010, 1, "save", 125u, 3u); /* sub 1: every group */
    after(0x1011, 3, "load", 125u, 7u);
    after(0x1011, 1, "load", 1000u, 7u);
    return done();
}
