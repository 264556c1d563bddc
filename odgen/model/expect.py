"""What a device built from a description must answer, computed from the model alone: the
bytes an upload gives and the result of downloads at and past the limits.

`odgen check`'s self-test, the round trip and the conformance battery compare a device with
these; the generator reaches the same values by another path (C initializers), which is the
point of comparing.
"""

from __future__ import annotations

from .capacity import value_limits
from .datatypes import DataType
from .od import ObjectDictionary, Sub
from .values import Value
from .wire import wire_bytes


def initial_number(od: ObjectDictionary, sub: Sub, dtype: DataType) -> int | float:
    """The value an entry starts with: its default, or without one 0 moved into its limits."""
    return initial_value(od.value_in_force(sub), sub, dtype)


def initial_value(value: Value | None, sub: Sub, dtype: DataType) -> int | float:
    """initial_number() of a given value."""
    parsed = value.parsed if value is not None and value.error is None else None
    if isinstance(parsed, (int, float)) and not isinstance(parsed, bool):
        return float(parsed) if dtype.kind == "real" else int(parsed)
    zero: int | float = 0.0 if dtype.kind == "real" else 0
    for bound, pick in ((sub.low, max), (sub.high, min)):
        if bound is not None and bound.error is None and not bound.nodeid and isinstance(bound.parsed, (int, float)):
            zero = pick(zero, bound.parsed)
    return zero


def expected_bytes(od: ObjectDictionary, sub: Sub, dtype: DataType, node_id: int,
                   capacity: int | None = None) -> bytes | None:
    """The wire bytes an upload of `sub` must give on node `node_id` (None: not comparable).
    An OCTET_STRING is as long as its capacity: the default padded with zero bytes."""
    data = _described_bytes(od, sub, dtype, node_id)
    if data is not None and dtype.kind == "ostring":
        return data.ljust(capacity or 0, b"\0")
    return data


def _described_bytes(od: ObjectDictionary, sub: Sub, dtype: DataType, node_id: int) -> bytes | None:
    value = od.value_in_force(sub)
    if dtype.kind == "domain":
        return None  # domains are compared by length only in hooks/streams, not by text form
    if value is None or value.error is not None or value.parsed is None:
        return b"" if dtype.is_string else wire_bytes(initial_number(od, sub, dtype), dtype)
    resolved = value.resolve(node_id)
    if resolved is None:
        return None
    if dtype.kind == "ostring" and isinstance(resolved, bytes):
        return resolved
    return wire_bytes(resolved, dtype)


def _limits(sub: Sub, dtype: DataType) -> tuple[int | float, int | float] | None:
    lo, hi = value_limits(sub.low, sub.high, dtype)
    return (lo, hi) if lo is not None and hi is not None and lo <= hi else None


def write_cases(sub: Sub, dtype: DataType) -> list[tuple[bytes, str]]:
    """Downloads to try on a writable numeric entry: low, high and middle value, one byte too
    many and one too few, and one past each limit narrower than the type; with the expected result."""
    bounds = _limits(sub, dtype) if dtype.is_numeric else None
    if bounds is None:
        return []
    lo, hi = bounds
    mid = (lo + hi) / 2 if dtype.kind == "real" else (int(lo) + int(hi)) // 2
    cases = [(wire_bytes(v, dtype), "ODG_OK") for v in (lo, hi, mid)]
    cases.append((wire_bytes(lo, dtype) + b"\x00", "ODG_ABORT_TOO_LONG"))
    if len(wire_bytes(lo, dtype)) > 1:
        cases.append((wire_bytes(lo, dtype)[:-1], "ODG_ABORT_TOO_SHORT"))
    if dtype.is_integer and dtype.min is not None and dtype.max is not None:
        if int(hi) < int(dtype.max):
            cases.append((wire_bytes(int(hi) + 1, dtype), "ODG_ABORT_VALUE_HIGH"))
        if int(lo) > int(dtype.min):
            cases.append((wire_bytes(int(lo) - 1, dtype), "ODG_ABORT_VALUE_LOW"))
    return cases
