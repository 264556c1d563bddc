"""Expectations for the generated self-test, computed from the model by a second path.

The view-model turns values into C initializers; this module turns the same model
values into CANopen wire bytes (odgen.model.wire) directly, so the self-test compares
what the compiled dictionary serves with what the description says.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..model import Obj, ObjectDictionary, Sub
from ..model.cia301 import COMMUNICATION_AREA, RESTORE, STORE, unused_manufacturer_index
from ..model.datatypes import BASIC_TYPES, DataType
from ..model.wire import wire_bytes
from .memory import value_rows
from ..place.placement import Placement, Placements
from .viewmodel import DictView
from ..model.expect import expected_bytes, write_cases

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


def build_selftest(od: ObjectDictionary, placements: Placements, view: DictView,
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

