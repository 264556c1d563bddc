"""Where each value lives and which hooks it has, and where each decision came from.

Layers, later wins: the auto rule, then the description (`;StorageLocation=` in
EDS, `CO_storageGroup` in XDD), then the options file entries in order.

Auto rule: const, or ro and not PDO-mappable, without hooks and not $NODEID-relative
-> rom (FLASH); everything else -> ram. Persistence groups come only from the
description or the options file. 0x1010/0x1011 sub-entries 1.. are the store and
restore commands. `RAM` in a description is CANopenNode's default written on every
entry, so it is read as "no preference", not as a decision.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from ..catalogue.gen import GEN002, GEN003
from ..diagnostics import Diagnostics, Loc
from ..model import Obj, ObjectDictionary, Sub
from ..model.cia301 import RUNTIME_UPDATED, is_store_command
from ..cnames import identifier
from .options import OptionEntry, Options


# The storage class of a 0x1010/0x1011 sub-entry: no value, a "save" / "load" command the runtime
# answers (ODG_S_COMMAND in C, a dictionary client's `command` function).
COMMAND_CLASS = "command"


@dataclass
class Placement:
    storage: str  # rom | ram | persist:<group> | command
    storage_from: str
    hooks: tuple[str, ...] = ()
    hooks_from: str = "none"
    function: str | None = None
    function_loc: Loc | None = None  # the options entry that named the function
    capacity: int | None = None
    capacity_from: str = "default"

    @property
    def group(self) -> str | None:
        return self.storage.split(":", 1)[1] if self.storage.startswith("persist:") else None


# Every (index, sub) of a dictionary with its placement; stages after `place` only read it.
Placements = Mapping[tuple[int, int], Placement]


def storage_from_description(text: str | None) -> str | None:
    if text is None or not text.strip() or text.strip().upper() == "RAM":
        return None
    name = text.strip().upper()
    if name == "ROM":
        return "rom"
    group = name[len("PERSIST_"):] if name.startswith("PERSIST_") else name
    return "persist:" + identifier(group, "nv")


def auto_storage(index: int, sub: Sub) -> tuple[str, str]:
    if is_store_command(index, sub.subindex):
        return COMMAND_CLASS, "auto: 0x1010/0x1011 store/restore commands"
    if sub.data_type == 0x000F and sub.access == "const" and sub.default is not None and not sub.default.empty:
        return "rom", "auto: a const DOMAIN whose value is fixed at generation"
    if sub.data_type == 0x000F:
        return "ram", "auto: DOMAIN buffers live in RAM"
    if index in RUNTIME_UPDATED:
        return "ram", "auto: the stack updates it at run time (CiA 301)"
    nodeid = sub.default is not None and sub.default.nodeid
    if sub.access == "const" and not nodeid:  # a $NODEID value is worked out at start-up (OBJ030)
        return "rom", "auto: const"
    if sub.access == "ro" and not sub.pdo_mapping and not nodeid:
        return "rom", "auto: ro, not PDO-mappable"
    reason = "$NODEID-relative" if nodeid else "writable or PDO-mappable"
    return "ram", f"auto: {reason}"


def place(od: ObjectDictionary, options: Options, diags: Diagnostics) -> dict[tuple[int, int], Placement]:
    """Placement of every (index, sub) of the dictionary; GEN findings into `diags`."""
    result: dict[tuple[int, int], Placement] = {}
    entries = [(entry, loc, str(loc)) for entry in options.entries for loc in [Loc(entry.source, entry.line)]]
    status = options.persist.status_object  # odgen's own object: the runtime sets it at boot
    for obj in od.sorted_objects():
        for sub in obj.sorted_subs():
            result[(obj.index, sub.subindex)] = Placement("ram", "[persist] status_object") \
                if obj.index == status else _place_one(od, obj, sub, entries)
    for entry in options.entries:
        if not entry.used:
            patterns = ", ".join(p.text for p in entry.patterns)
            diags.add(GEN002, Loc(entry.source, entry.line), f"match {patterns} selects no entry")
    for (index, subindex), placement in result.items():
        if placement.storage == "rom":
            _validate(od, index, subindex, placement, diags)
    return result


def _place_one(od: ObjectDictionary, obj: Obj, sub: Sub, entries: list[tuple[OptionEntry, Loc, str]]) -> Placement:
    """The placement of one sub-entry; `entries` are the options' entries with their place (and its text)."""
    storage, why = auto_storage(obj.index, sub)
    described, text, line = _described(obj, sub)
    if described is not None and storage != COMMAND_CLASS:
        storage, why = described, f"{od.source}:{line}: storage location {text}"
        if storage == "rom" and _unfit_for_rom(sub):  # CANopenNode v1: CO_OD_ROM is RAM that 0x1010 saves
            storage, why = "persist:rom", why + " (CANopenNode v1: kept in RAM, saved by 0x1010)"
    placement = Placement(storage, why)
    for entry, loc, origin in entries:
        if any(p.matches(obj.index, sub.subindex) for p in entry.patterns):
            entry.used = True
            _apply(placement, entry, loc, origin)
    return placement


def _described(obj: Obj, sub: Sub) -> tuple[str | None, str, int]:
    """The storage the description decides for a sub-entry, its text and line: the sub-entry's
    own `StorageLocation` when it decides one, else the object's. A sub-level `RAM` is
    CANopenNode's "no preference" (CANopenEditor writes it on every sub-entry and places whole
    objects with the object-level key), so it never overrides the object's `PERSIST_COMM`."""
    own = storage_from_description(sub.storage)
    if own is not None:
        return own, sub.storage or "", sub.line_of("storagelocation")
    if obj.storage:
        return storage_from_description(obj.storage), obj.storage, obj.line_of("storagelocation")
    return None, "", 0


def _apply(placement: Placement, entry: OptionEntry, loc: Loc, origin: str) -> None:
    if entry.storage is not None and placement.storage != COMMAND_CLASS:
        storage = "persist:app" if entry.storage == "persist" else entry.storage  # the default group
        placement.storage, placement.storage_from = storage, origin
    if entry.hooks is not None:
        placement.hooks, placement.hooks_from = entry.hooks, origin
        placement.function, placement.function_loc = entry.function, loc
    if entry.capacity is not None:
        placement.capacity, placement.capacity_from = entry.capacity, origin


def _unfit_for_rom(sub: Sub) -> list[str]:
    """Why a value cannot live in FLASH, as the description gives it."""
    reasons = []
    if sub.writable:
        reasons.append(f"it is writable ({sub.access})")
    if sub.default is not None and sub.default.nodeid:
        reasons.append("its default is $NODEID-relative")
    if sub.data_type == 0x000F and sub.access != "const":
        reasons.append("a DOMAIN that is not const keeps its buffer and length in RAM")
    return reasons


def _validate(od: ObjectDictionary, index: int, subindex: int, placement: Placement, diags: Diagnostics) -> None:
    if placement.storage != "rom":
        return
    obj = od.objects[index]
    sub = obj.subs[subindex]
    reasons = _unfit_for_rom(sub)
    if "pre_read" in placement.hooks:
        reasons.append("a pre_read hook refreshes it")
    if reasons:
        diags.add(GEN003, Loc(od.source, sub.line),
                  f"is placed in rom ({placement.storage_from}) but {' and '.join(reasons)}",
                  index, None if obj.is_var else subindex)
