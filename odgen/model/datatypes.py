"""The CiA 301 basic data types 0x0001-0x001B, from one table.

`kind` says how a value of the type is written in a description and parsed:
  bool, int (signed), uint, real, vstring, ostring, ustring, time, domain.
Ranges are inclusive; `None` for types without a numeric range.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class DataType:
    code: int
    name: str
    bits: int  # 0 = variable length
    kind: str

    @property
    def is_numeric(self) -> bool:
        return self.kind in ("bool", "int", "uint", "real")

    @property
    def is_integer(self) -> bool:
        return self.kind in ("bool", "int", "uint")

    @property
    def is_string(self) -> bool:
        return self.kind in ("vstring", "ostring", "ustring")

    @property
    def min(self) -> int | float | None:
        if self.kind == "int":
            return -(1 << (self.bits - 1))
        if self.kind in ("uint", "bool"):
            return 0
        if self.kind == "real":
            return -_REAL_MAX[self.bits]
        return None

    @property
    def max(self) -> int | float | None:
        if self.kind == "int":
            return (1 << (self.bits - 1)) - 1
        if self.kind == "uint":
            return (1 << self.bits) - 1
        if self.kind == "bool":
            return 1
        if self.kind == "real":
            return _REAL_MAX[self.bits]
        return None


_REAL_MAX = {32: 3.4028234663852886e38, 64: 1.7976931348623157e308}

_TABLE = [
    (0x0001, "BOOLEAN", 1, "bool"),
    (0x0002, "INTEGER8", 8, "int"),
    (0x0003, "INTEGER16", 16, "int"),
    (0x0004, "INTEGER32", 32, "int"),
    (0x0005, "UNSIGNED8", 8, "uint"),
    (0x0006, "UNSIGNED16", 16, "uint"),
    (0x0007, "UNSIGNED32", 32, "uint"),
    (0x0008, "REAL32", 32, "real"),
    (0x0009, "VISIBLE_STRING", 0, "vstring"),
    (0x000A, "OCTET_STRING", 0, "ostring"),
    (0x000B, "UNICODE_STRING", 0, "ustring"),
    (0x000C, "TIME_OF_DAY", 48, "time"),
    (0x000D, "TIME_DIFFERENCE", 48, "time"),
    (0x000F, "DOMAIN", 0, "domain"),
    (0x0010, "INTEGER24", 24, "int"),
    (0x0011, "REAL64", 64, "real"),
    (0x0012, "INTEGER40", 40, "int"),
    (0x0013, "INTEGER48", 48, "int"),
    (0x0014, "INTEGER56", 56, "int"),
    (0x0015, "INTEGER64", 64, "int"),
    (0x0016, "UNSIGNED24", 24, "uint"),
    (0x0018, "UNSIGNED40", 40, "uint"),
    (0x0019, "UNSIGNED48", 48, "uint"),
    (0x001A, "UNSIGNED56", 56, "uint"),
    (0x001B, "UNSIGNED64", 64, "uint"),
]

BASIC_TYPES: dict[int, DataType] = {row[0]: DataType(*row) for row in _TABLE}
BY_NAME: dict[str, DataType] = {t.name: t for t in BASIC_TYPES.values()}

# Complex types CiA 301 predefines (0x0020-0x0025); a description may also
# define its own with DEFSTRUCT objects.
COMPLEX_TYPES = {
    0x0020: "PDO_COMMUNICATION_PARAMETER",
    0x0021: "PDO_MAPPING",
    0x0022: "SDO_PARAMETER",
    0x0023: "IDENTITY",
    0x0024: "DEBUGGER_PARAMETER",
    0x0025: "COMMAND_PAR",
}

UNSIGNED8 = BASIC_TYPES[0x0005]
UNSIGNED16 = BASIC_TYPES[0x0006]
UNSIGNED32 = BASIC_TYPES[0x0007]


def lookup(code: int | None) -> DataType | None:
    return BASIC_TYPES.get(code) if code is not None else None
