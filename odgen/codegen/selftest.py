"""Expectations for the generated self-test, computed from the model by a second path.

The view-model turns values into C initializers; this module turns the same model
values into CANopen wire bytes (odgen.model.wire) directly, so the self-test compares
what the compiled dictionary serves with what the description says.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..model import Obj, ObjectDictionary, Sub, Value
from ..model.cia301 import COMMUNICATION_AREA, RESTORE, STORE, unused_manufacturer_index
from ..model.datatypes import BASIC_TYPES, DataType
from ..model.wire import wire_bytes
from .memory import value_rows
from .placement import Placement
from .viewmodel import DictView, initial_number

MAX_WRITE_CASES = 3


@dataclass
class WriteCase:
    data: str  # C byte list
    length: int
    expect: str  # abort code name


@dataclass
class Expect:
    index: int
    sub: int
    label: str
    readable: bool
    writable: bool
    value: str  # C byte list of the expected upload, "" when not compared
    length: int
    compare: bool
    writes: list[WriteCase] = field(default_factory=list)
    hook_kinds: str = "0"
    persistent: bool = False


@dataclass
class SelfTest:
    name: str
    upper: str  # the prefix of the dictionary's macros (NAME_NV_SIZE)
    node_id: int
    expects: list[Expect]
    functions: list[str]
    missing_index: int
    groups: int
    has_store: bool
    structs: list[tuple[str, str, str]]  # (label, C variable, where it lives)

    @property
    def test_persistence(self) -> bool:
        return self.groups > 0 and self.has_store


def c_bytes(data: bytes) -> str:
    return "{" + ", ".join(f"0x{b:02X}" for b in data) + "}" if data else "{0}"


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


def _bound(value: Value | None, fallback: int | float | None) -> int | float | None:
    if value is None or value.empty:
        return fallback
    if value.error is not None or value.nodeid or not isinstance(value.parsed, (int, float)):
        return None
    return value.parsed


def _limits(sub: Sub, dtype: DataType) -> tuple[int | float, int | float] | None:
    lo, hi = _bound(sub.low, dtype.min), _bound(sub.high, dtype.max)
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


def _write_cases(sub: Sub, dtype: DataType) -> list[WriteCase]:
    return [WriteCase(c_bytes(data), len(data), expect) for data, expect in write_cases(sub, dtype)]


def _expect(od: ObjectDictionary, obj: Obj, sub: Sub, placement: Placement, node_id: int) -> Expect | None:
    dtype = BASIC_TYPES.get(sub.data_type or 0)
    if dtype is None or obj.index < COMMUNICATION_AREA[0] or (obj.index in (STORE, RESTORE) and sub.subindex > 0):
        return None
    expected = expected_bytes(od, sub, dtype, node_id, placement.capacity)
    label = f"0x{obj.index:04X}sub{sub.subindex}"
    exp = Expect(obj.index, sub.subindex, label, sub.readable, sub.writable,
                 c_bytes(expected or b""), len(expected or b""), expected is not None and dtype.kind != "domain",
                 hook_kinds=" | ".join(f"ODG_HOOK_{k.upper()}" for k in placement.hooks) or "0",
                 persistent=placement.storage.startswith("persist:"))
    if sub.writable:
        exp.writes = _write_cases(sub, dtype)
    elif dtype.is_numeric:
        data = expected or wire_bytes(0, dtype)
        exp.writes = [WriteCase(c_bytes(data), len(data), "ODG_ABORT_READ_ONLY")]
    return exp


def build_selftest(od: ObjectDictionary, placements: dict[tuple[int, int], Placement], view: DictView,
                   node_id: int) -> SelfTest:
    expects = []
    for obj in od.sorted_objects():
        for sub in obj.sorted_subs():
            exp = _expect(od, obj, sub, placements[(obj.index, sub.subindex)], node_id)
            if exp is not None:
                expects.append(exp)
    missing = unused_manufacturer_index(od.objects)
    structs = [(row.label, row.var, row.where) for row in value_rows(view)]
    store = od.objects.get(STORE)
    return SelfTest(view.name, view.upper, node_id, expects, view.functions, missing, len(view.groups),
                    store is not None and 1 in store.subs and RESTORE in od.objects, structs)

