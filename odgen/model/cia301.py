"""CiA 301 by number: the communication objects odgen knows by index, the predefined
connection set, the 0x1010/0x1011 command words and the SDO abort codes.

Every Python user (rules, placement, self-test, round trip) takes these numbers from here.
The runtime's C mirrors some of them, by name or as literals: the abort codes are
the `ODG_ABORT_*` macros in runtime/odg.h, the command words `CMD_SAVE`/`CMD_LOAD` in runtime/odg.c,
the communication indices literals in runtime/odg_node.c, odg_pdo.c and profiles/ds401.c.
tests/test_cia301.py reads those files and fails when they and this module disagree.
"""

from __future__ import annotations

from collections.abc import Container

# -- communication profile area (0x1000-0x1FFF) ------------------------------------------
DEVICE_TYPE = 0x1000
ERROR_REGISTER = 0x1001
STATUS_REGISTER = 0x1002  # manufacturer status register
ERROR_HISTORY = 0x1003  # pre-defined error field
SYNC_COB_ID = 0x1005
SYNC_PERIOD = 0x1006  # communication cycle period
SYNC_WINDOW = 0x1007
DEVICE_NAME = 0x1008
HARDWARE_VERSION = 0x1009
SOFTWARE_VERSION = 0x100A
GUARD_TIME = 0x100C
LIFE_TIME_FACTOR = 0x100D
STORE = 0x1010  # store parameters: sub 1.. take "save"
RESTORE = 0x1011  # restore default parameters: sub 1.. take "load"
TIME_COB_ID = 0x1012
HIGH_RESOLUTION_TIME = 0x1013
EMCY_COB_ID = 0x1014
EMCY_INHIBIT = 0x1015
CONSUMER_HEARTBEAT = 0x1016
PRODUCER_HEARTBEAT = 0x1017
IDENTITY = 0x1018  # sub 1 vendor-ID, 2 product code, 3 revision, 4 serial number
SYNC_OVERFLOW = 0x1019
ERROR_BEHAVIOUR = 0x1029

COMMUNICATION_AREA = (0x1000, 0x1FFF)
MANUFACTURER_AREA = (0x2000, 0x5FFF)
MANDATORY = {DEVICE_TYPE: "device type", ERROR_REGISTER: "error register", IDENTITY: "identity"}


def object_list_for(index: int) -> str:
    """The object list an index belongs in (CiA 306), by its key: the mandatory objects, the
    manufacturer-specific area 0x2000-0x5FFF, and everything else optional."""
    if index in MANDATORY:
        return "mandatoryobjects"
    if 0x2000 <= index <= 0x5FFF:
        return "manufacturerobjects"
    return "optionalobjects"
# ro by access type, yet written by the communication stack itself.
RUNTIME_UPDATED = frozenset({ERROR_REGISTER, STATUS_REGISTER, ERROR_HISTORY})


def unused_manufacturer_index(used: Container[int]) -> int:
    """The highest index of the manufacturer area not in `used`: one a device answers "no object"."""
    first, last = MANUFACTURER_AREA
    return next(i for i in range(last, first - 1, -1) if i not in used)


# -- the data type and access CiA 301 gives the communication objects ---------------------
U8, U16, U32, VSTR = 0x0005, 0x0006, 0x0007, 0x0009
# Single-value communication objects and their data type.
VAR_TYPES = {DEVICE_TYPE: U32, ERROR_REGISTER: U8, STATUS_REGISTER: U32, SYNC_COB_ID: U32, SYNC_PERIOD: U32,
             SYNC_WINDOW: U32, DEVICE_NAME: VSTR, HARDWARE_VERSION: VSTR, SOFTWARE_VERSION: VSTR, GUARD_TIME: U16,
             LIFE_TIME_FACTOR: U8, TIME_COB_ID: U32, HIGH_RESOLUTION_TIME: U32, EMCY_COB_ID: U32, EMCY_INHIBIT: U16,
             PRODUCER_HEARTBEAT: U16, SYNC_OVERFLOW: U8}
# Records/arrays: sub-index -> type (key 0 = "every sub-index from 1").
ARRAY_TYPES = {ERROR_HISTORY: {0: U32}, STORE: {0: U32}, RESTORE: {0: U32}, CONSUMER_HEARTBEAT: {0: U32},
               IDENTITY: {1: U32, 2: U32, 3: U32, 4: U32}, ERROR_BEHAVIOUR: {0: U8}}
PDO_COMM_TYPES = {1: U32, 2: U8, 3: U16, 4: U8, 5: U16, 6: U8}
SDO_TYPES = {1: U32, 2: U32, 3: U8}
# Read-only whatever a description says.
READ_ONLY = (DEVICE_TYPE, ERROR_REGISTER, DEVICE_NAME, HARDWARE_VERSION, SOFTWARE_VERSION, IDENTITY)


# -- SDO and PDO parameter records: first index and how many ----------------------------
SDO_SERVER, SDO_CLIENT, SDO_COUNT = 0x1200, 0x1280, 0x80
RPDO_COMM, RPDO_MAPPING = 0x1400, 0x1600
TPDO_COMM, TPDO_MAPPING = 0x1800, 0x1A00
PDO_COUNT = 0x200
PDO_MAPPING_ENTRIES = 0x40  # sub-indices 1..64 of a mapping record


def _in(index: int, base: int, count: int) -> bool:
    return base <= index < base + count


def is_sdo_parameter(index: int) -> bool:
    """An SDO server or client parameter record."""
    return _in(index, SDO_SERVER, SDO_COUNT) or _in(index, SDO_CLIENT, SDO_COUNT)


def pdo_communication(index: int) -> str | None:
    """"RPDO" or "TPDO" for a PDO communication parameter record, else None."""
    if _in(index, RPDO_COMM, PDO_COUNT):
        return "RPDO"
    if _in(index, TPDO_COMM, PDO_COUNT):
        return "TPDO"
    return None


def is_store_command(index: int, subindex: int) -> bool:
    """0x1010/0x1011 sub 1..: a read gives the capabilities, a write is a store or restore command."""
    return index in (STORE, RESTORE) and subindex > 0


def is_pdo_mapping(index: int) -> bool:
    return _in(index, RPDO_MAPPING, PDO_COUNT) or _in(index, TPDO_MAPPING, PDO_COUNT)


# -- COB-IDs: the predefined connection set and the flag bits ----------------------------
EMCY_BASE = 0x80
TPDO_BASE, RPDO_BASE, PDO_BASE_STEP = 0x180, 0x200, 0x100  # TPDO1/RPDO1, then +0x100 up to the fourth
PREDEFINED_PDOS = 4
SDO_RESPONSE, SDO_REQUEST = 0x580, 0x600
HEARTBEAT = 0x700
COB_INVALID = 0x80000000  # bit 31: the object does not use this COB-ID
COB_PRODUCER = 0x40000000  # bit 30 of SYNC/TIME: the device produces it
COB_EXTENDED = 0x20000000  # bit 29: a 29-bit identifier
CAN_ID_MASK = 0x7FF

# CAN-IDs CiA 301 reserves for NMT, SYNC/EMCY/TIME, SDO, LSS and heartbeat: no COB-ID may use them.
RESTRICTED_CAN_IDS = ((0x000, 0x07F), (0x101, 0x180), (0x581, 0x5FF), (0x601, 0x67F), (0x6E0, 0x6FF),
                      (0x701, 0x7FF))


def predefined_cob_id(index: int, subindex: int) -> tuple[int, str] | None:
    """(base CAN-ID, name) of an entry the predefined connection set fixes: the COB-IDs of
    RPDO1-4, TPDO1-4 (sub 1) and EMCY (0x1014); the node-id is added to the base."""
    if _in(index, RPDO_COMM, PREDEFINED_PDOS) and subindex == 1:
        return RPDO_BASE + PDO_BASE_STEP * (index - RPDO_COMM), f"RPDO{index - RPDO_COMM + 1}"
    if _in(index, TPDO_COMM, PREDEFINED_PDOS) and subindex == 1:
        return TPDO_BASE + PDO_BASE_STEP * (index - TPDO_COMM), f"TPDO{index - TPDO_COMM + 1}"
    if index == EMCY_COB_ID and subindex == 0:
        return EMCY_BASE, "EMCY"
    return None


# -- 0x1010 / 0x1011 command words: "save" / "load" as little-endian UNSIGNED32 ------------
SAVE, LOAD = b"save", b"load"

# -- SDO abort codes, by the runtime's names (runtime/odg.h, ODG_ABORT_*) ------------------
ABORT_CODES = {
    "ODG_ABORT_TOGGLE": 0x05030000,
    "ODG_ABORT_TIMEOUT": 0x05040000,
    "ODG_ABORT_COMMAND": 0x05040001,
    "ODG_ABORT_BLOCK_SIZE": 0x05040002,
    "ODG_ABORT_SEQUENCE": 0x05040003,
    "ODG_ABORT_CRC": 0x05040004,
    "ODG_ABORT_OUT_OF_MEMORY": 0x05040005,
    "ODG_ABORT_UNSUPPORTED": 0x06010000,
    "ODG_ABORT_WRITE_ONLY": 0x06010001,
    "ODG_ABORT_READ_ONLY": 0x06010002,
    "ODG_ABORT_NO_OBJECT": 0x06020000,
    "ODG_ABORT_NOT_MAPPABLE": 0x06040041,
    "ODG_ABORT_PDO_LENGTH": 0x06040042,
    "ODG_ABORT_INCOMPATIBLE": 0x06040043,
    "ODG_ABORT_INTERNAL": 0x06040047,
    "ODG_ABORT_HARDWARE": 0x06060000,
    "ODG_ABORT_TYPE_LENGTH": 0x06070010,
    "ODG_ABORT_TOO_LONG": 0x06070012,
    "ODG_ABORT_TOO_SHORT": 0x06070013,
    "ODG_ABORT_NO_SUB": 0x06090011,
    "ODG_ABORT_VALUE_RANGE": 0x06090030,
    "ODG_ABORT_VALUE_HIGH": 0x06090031,
    "ODG_ABORT_VALUE_LOW": 0x06090032,
    "ODG_ABORT_MAX_LESS_MIN": 0x06090036,
    "ODG_ABORT_NO_RESOURCE": 0x060A0023,
    "ODG_ABORT_GENERAL": 0x08000000,
    "ODG_ABORT_DATA_STORE": 0x08000020,
    "ODG_ABORT_DATA_LOCAL": 0x08000021,
    "ODG_ABORT_DATA_STATE": 0x08000022,
    "ODG_ABORT_NO_DICTIONARY": 0x08000023,
}
