"""PDO mappings as CiA 301 defines them: which objects map, and what a mapping object's entries
say in force (a DCF's ParameterValue where it has one, else the DefaultValue).

Decoding only; what is wrong with a mapping is the PDO lint passes' business, and they report
from the `Mapping` decoded here.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

from .cia301 import COB_INVALID, RPDO_COMM, RPDO_MAPPING, TPDO_COMM, TPDO_MAPPING
from .od import ARRAY, RECORD, Obj, ObjectDictionary, Sub
from .values import Value, number, plain_int

MAPPINGS = {RPDO_MAPPING: ("RPDO", RPDO_COMM), TPDO_MAPPING: ("TPDO", TPDO_COMM)}
FRAME_BITS, FD_FRAME_BITS = 64, 512
MPDO = (0xFE, 0xFF)  # mapping sub0 of a multiplexed PDO: SAM-MPDO / DAM-MPDO (CiA 301)
MAX_ENTRIES = 64  # mapping entries a PDO may have (CiA 301)


@dataclass
class MappingEntry:
    """One mapping entry, decoded: the object it maps and the length in bits."""

    sub: Sub
    value: Value
    index: int
    subindex: int
    length: int
    line: int


@dataclass
class Mapping:
    """What a mapping object's entries say in force."""

    entries: list[MappingEntry] = field(default_factory=list)  # active entries that map something
    empty: list[MappingEntry] = field(default_factory=list)  # counted entries mapping nothing (0x00000000)
    absent: list[int] = field(default_factory=list)  # sub-indices sub0 counts that are not defined
    count: int | None = None  # sub0's count, when it gives a usable one
    multiplexed: bool = False  # sub0 0xFE/0xFF: the entries are not a fixed mapping
    too_many: bool = False  # sub0 counts more than MAX_ENTRIES: its entries say nothing


def mapping_kind(index: int) -> tuple[str, int] | None:
    """("RPDO"|"TPDO", PDO number from 0) for a mapping object index."""
    for base, (kind, _comm) in MAPPINGS.items():
        if base <= index < base + 0x200:
            return kind, index - base
    return None


def mapping_objects(od: ObjectDictionary) -> Iterator[tuple[Obj, str]]:
    """The mapping objects of a dictionary, with "RPDO" or "TPDO"."""
    for index, obj in od.objects.items():
        kind = mapping_kind(index)
        if kind is not None and obj.object_code in (ARRAY, RECORD):
            yield obj, kind[0]


def decode_mapping(od: ObjectDictionary, obj: Obj) -> Mapping:
    """The entries sub0 activates; without a usable count, every readable entry present."""
    sub0 = obj.subs.get(0)
    value = od.value_in_force(sub0) if sub0 is not None else None
    if number(value) in MPDO:
        return Mapping(multiplexed=True)
    count = plain_int(value) if sub0 is not None and not sub0.compact else None
    if sub0 is None or value is None or count is None:
        entries, _ = _decoded(od, obj, max(obj.subs, default=0))
        return Mapping(entries)
    if count > MAX_ENTRIES:
        return Mapping(count=count, too_many=True)
    entries, empty = _decoded(od, obj, count)
    absent = [i for i in range(1, count + 1) if i not in obj.subs]
    return Mapping(entries, empty, absent, count)


def _decoded(od: ObjectDictionary, obj: Obj, last: int) -> tuple[list[MappingEntry], list[MappingEntry]]:
    """The readable entries 1..last: those that map something, and the empty ones (0x00000000)."""
    entries: list[MappingEntry] = []
    empty: list[MappingEntry] = []
    for subindex in range(1, last + 1):
        sub = obj.subs.get(subindex)
        entry = decode_entry(od, sub) if sub is not None else None
        if entry is not None:
            (empty if entry.value.parsed == 0 else entries).append(entry)
    return entries, empty


def decode_entry(od: ObjectDictionary, sub: Sub) -> MappingEntry | None:
    """A mapping entry's index, sub-index and length; None when its value is not a 32-bit number."""
    value = od.value_in_force(sub)
    raw = plain_int(value)
    if value is None or raw is None or not 0 <= raw <= 0xFFFFFFFF:
        return None
    line = value.line if value.line else sub.line_of("parametervalue" if value is sub.parameter_value
                                                     else "defaultvalue")
    return MappingEntry(sub, value, raw >> 16, (raw >> 8) & 0xFF, raw & 0xFF, line)


def default_mapped(od: ObjectDictionary) -> dict[tuple[int, int], frozenset[str]]:
    """(index, sub-index) -> the directions ("RPDO", "TPDO") the dictionary's own mappings map the entry in.

    An entry the description's mapping maps is mappable in that direction whatever its PDOMapping says
    (PDO002): the mapping is the more specific statement, a device serves its own default mapping."""
    found: dict[tuple[int, int], frozenset[str]] = {}
    for obj, kind in mapping_objects(od):
        for entry in decode_mapping(od, obj).entries:
            key = (entry.index, entry.subindex)
            found[key] = found.get(key, frozenset()) | {kind}
    return found


# A $NODEID COB-ID is linear in the node-id: what holds at both ends holds for every node-id.
_NODE_ID_ENDS = (1, 127)


def pdo_disabled(od: ObjectDictionary, mapping_index: int) -> bool:
    """Whether the PDO of a mapping object starts disabled: its COB-ID in force has bit 31 set at every
    node-id. The runtime then leaves a mapping it cannot serve unused and refuses to enable the PDO with it
    (odg_pdo.c), so the node starts as the description says."""
    kind = mapping_kind(mapping_index)
    comm = od.objects.get(MAPPINGS[mapping_index - kind[1]][1] + kind[1]) if kind is not None else None
    sub = comm.subs.get(1) if comm is not None else None
    value = od.value_in_force(sub) if sub is not None else None
    if value is None or value.error is not None or not isinstance(value.parsed, int):
        return False
    ends = _NODE_ID_ENDS if value.nodeid else _NODE_ID_ENDS[:1]
    return all(isinstance(v, int) and 0 <= v <= 0xFFFFFFFF and v & COB_INVALID for v in map(value.resolve, ends))
