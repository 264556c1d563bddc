/*
 * nv_eeprom.c - the NV driver (odg_nv_driver_t) of the persistence layer over an EEPROM.
 *
 * The runtime's contract (runtime/README.md): each call returns 0 when done and finished
 * (blocking), writes land in the order issued, erase sets the bytes to 0xFF, and writes only
 * go to erased bytes. An EEPROM has no erase: writing 0xFF is one. Addresses start at 0 here;
 * the EEPROM's first byte belongs to the dictionary's groups (NAME_NV_SIZE bytes, and the
 * LSS slave's after them: odg_lss_nv_size).
 */
#include "nv_eeprom.h"

#include "board.h"

static int nv_read(void *ctx, uint32_t addr, void *buf, uint32_t len)
{
    (void)ctx;
    return board_eeprom_read(addr, buf, len);
}

static int nv_write(void *ctx, uint32_t addr, const void *buf, uint32_t len)
{
    (void)ctx;
    return board_eeprom_write(addr, buf, len);
}

static int nv_erase(void *ctx, uint32_t addr, uint32_t len)
{
    static const uint8_t erased[32] = {
        0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,
        0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
    (void)ctx;
    while (len > 0u) {
        uint32_t n = len < sizeof erased ? len : (uint32_t)sizeof erased;
        if (board_eeprom_write(addr, erased, n) != 0) {
            return -1;
        }
        addr += n;
        len -= n;
    }
    return 0;
}

const odg_nv_driver_t nv_eeprom = {nv_read, nv_write, nv_erase, NULL};
