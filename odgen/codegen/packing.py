"""Uniform ARRAY (and RECORD) elements share one sub-entry descriptor (runtime/odg.h, ODG_E_PACKED).

An ARRAY or RECORD whose sub-indices are exactly 0..N (N >= 2), and whose sub-entries 1..N are
numbers alike
in everything the descriptor holds (type, access, PDO mapping, storage) with no hooks, limits or
$NODEID default, is described by sub 0 and one descriptor for all elements: element k lies
(k - 1) * ODG_STRIDE(size) bytes after element 1, which the generated C asserts. The CiA 301
error history (0x1003), the heartbeat consumer (0x1016) and the PDO mapping records (0x16xx,
0x1Axx) are such in most devices; 8 bytes of FLASH per element saved. So are the "save" and
"load" commands of 0x1010 and 0x1011 (no value: the runtime answers them by their sub-index,
which the element's descriptor carries), when the dictionary packs the elements of another
entry: packing needs code in the runtime (ODG_CFG_PACKED) that the commands alone do not save.
"""

from __future__ import annotations

from ..model import ObjectDictionary
from ..model.datatypes import BASIC_TYPES
from ..model.od import Obj
from ..place.placement import Placements, COMMAND_CLASS

ARRAY, RECORD = 8, 9


def packs_values(od: ObjectDictionary, placements: Placements) -> bool:
    """Whether an entry with values packs its elements (then the commands pack too)."""
    return any(packable(od, obj, placements, commands=False) for obj in od.sorted_objects())


def packable(od: ObjectDictionary, obj: Obj, placements: Placements, commands: bool) -> bool:
    """Whether the elements of `obj` share one descriptor in the generated tables; "save" and
    "load" commands only with `commands`."""
    if obj.structure not in (ARRAY, RECORD) or sorted(obj.subs) != list(range(len(obj.subs))) or len(obj.subs) < 3:
        return False
    elements = [obj.subs[k] for k in range(1, len(obj.subs))]
    first = elements[0]
    dtype = BASIC_TYPES.get(first.data_type or 0)
    if dtype is None or not dtype.is_numeric:
        return False
    kinds = set()
    for sub in elements:
        place = placements.get((obj.index, sub.subindex))
        value = od.value_in_force(sub)
        if place is None or place.hooks or (place.storage == COMMAND_CLASS and not commands) or sub.low is not None \
                or sub.high is not None or (value is not None and value.nodeid):
            return False
        kinds.add((sub.data_type, sub.access, sub.pdo_mapping, place.storage))
    return len(kinds) == 1
