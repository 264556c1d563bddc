"""Values on the CAN bus: how CiA 301 encodes a value of each basic type in an SDO or PDO.

Little-endian integers of the type's size (two's complement for signed types), IEEE 754
for REAL32/REAL64, strings as their bytes (UNICODE_STRING as UTF-16LE). The self-test's
expectations, the round trip and the persistence migration all encode and decode here;
the runtime's C builds the same bytes on its own (runtime/odg.c, byte by byte), and the
compiled self-test of `odgen check` compares the two.
"""

from __future__ import annotations

import struct

from .datatypes import DataType


def wire_bytes(value: int | float | bytes | str, dtype: DataType) -> bytes:
    """The bytes of `value` as a `dtype` on the bus."""
    if dtype.kind == "real":
        return struct.pack(_real_format(dtype), float(value))
    if dtype.kind in ("int", "uint", "bool", "time"):
        size = max(dtype.bits // 8, 1)
        return (int(value) & ((1 << (8 * size)) - 1)).to_bytes(size, "little")
    if isinstance(value, bytes):
        return value
    if dtype.kind == "ustring":
        return str(value).encode("utf-16-le")
    return str(value).encode("utf-8")


def wire_number(data: bytes, dtype: DataType) -> int | float:
    """The number a numeric `dtype` carries in `data` (as long as the type)."""
    if dtype.kind == "real":
        return float(struct.unpack(_real_format(dtype), data)[0])
    return int.from_bytes(data, "little", signed=dtype.kind == "int")


def _real_format(dtype: DataType) -> str:
    return "<f" if dtype.bits == 32 else "<d"
