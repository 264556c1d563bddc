"""The bytes a value of variable length takes in the generated dictionary and in a stored image:
its default, widened to the capacity the options give.

Defined once here because two floors ask: the generator sizes the C arrays with it, and the
persistence layout (what boot migration compares between firmware versions) must agree byte for byte.
"""

from __future__ import annotations

import struct

from .datatypes import DataType
from .values import Value

DEFAULT_DOMAIN_CAPACITY = 0  # a DOMAIN holds its default unless the options give a capacity


def string_default(dtype: DataType, value: Value | None) -> bytes | list[int]:
    """A string's default as stored: UTF-8 bytes (VISIBLE_STRING), bytes (OCTET_STRING) or
    UTF-16 code units (UNICODE_STRING); empty when the value is missing or unreadable."""
    text = value.parsed if value is not None and value.error is None else None
    if dtype.kind == "vstring":
        return (text if isinstance(text, str) else "").encode("utf-8")
    if dtype.kind == "ostring":
        return text if isinstance(text, bytes) else b""
    encoded = (text if isinstance(text, str) else "").encode("utf-16-le")
    return list(struct.unpack(f"<{len(encoded) // 2}H", encoded))


def string_capacity(dtype: DataType, default: bytes | list[int], capacity: int | None) -> int:
    """Bytes reserved for a string's value (without a VISIBLE_STRING's terminating zero)."""
    if dtype.kind in ("vstring", "ostring"):
        return max(len(default), capacity or 0)
    return 2 * max(len(default), (capacity or 0) // 2)


def domain_default(value: Value | None) -> bytes:
    """A DOMAIN's default: hex digits as bytes, anything else as its UTF-8 text."""
    raw = value.text.strip() if value is not None else ""
    try:
        return bytes.fromhex(raw.removeprefix("0x"))
    except ValueError:
        return raw.encode("utf-8")


def domain_capacity(value: Value | None, capacity: int | None) -> int:
    """Bytes reserved for a DOMAIN: its default, or the capacity the options give, at least one."""
    return max(len(domain_default(value)), capacity if capacity is not None else DEFAULT_DOMAIN_CAPACITY, 1)


def limit_value(value: Value | None, fallback: int | float | None) -> int | float | None:
    """A numeric limit as a number: `fallback` when absent, None when it cannot be used
    (unreadable, or relative to the node-id)."""
    if value is None or value.empty:
        return fallback
    if value.error is not None or value.nodeid or not isinstance(value.parsed, (int, float)):
        return None
    return value.parsed


def value_limits(low: Value | None, high: Value | None,
                 dtype: DataType) -> tuple[int | float | None, int | float | None]:
    """The limits that apply to a value of `dtype`: each given one, else the type's end; a given limit
    past the type's end bounds nothing beyond it (OBJ014: `HighLimit=65536` on an UNSIGNED16 is
    65535), so it is the type's end too. None where a limit cannot be used."""
    lo, hi = limit_value(low, dtype.min), limit_value(high, dtype.max)
    if dtype.min is not None and lo is not None and lo < dtype.min:
        lo = dtype.min
    if dtype.max is not None and hi is not None and hi > dtype.max:
        hi = dtype.max
    return lo, hi


# A $NODEID value is linear in the node-id, so whether it stays within limits shows at the ends.
NODE_ID_ENDS = (1, 127)


def served_limits(low: Value | None, high: Value | None, value: Value | None, dtype: DataType,
                  writable: bool) -> tuple[int | float, int | float] | None:
    """The limits the C checks a write of the entry against (value_limits()), or None for none.

    A read-only entry keeps no limits that could not hold: reversed ones (OBJ015) or ones its value
    in force lies outside of (OBJ017). No write from the bus reaches such an entry (the SDO server
    refuses it for its access, an RPDO maps writable entries only) and the application's own writes
    are not checked against limits, so the node behaves the same without them, while the runtime's
    table check (odg_verify) would refuse them and the node would not start."""
    lo, hi = value_limits(low, high, dtype)
    if lo is None or hi is None:
        return None
    if writable or lo <= hi and _within(value, lo, hi):
        return lo, hi
    return None


def _within(value: Value | None, lo: int | float, hi: int | float) -> bool:
    if value is None or value.error is not None:
        return True
    for node_id in NODE_ID_ENDS if value.nodeid else NODE_ID_ENDS[:1]:
        v = value.resolve(node_id)
        if isinstance(v, (int, float)) and not lo <= v <= hi:
            return False
    return True
