"""PDO: mapping objects and their pairing with communication objects.

CiA 306 rule table rows C1-C5, H5 (mapping offsets against Granularity) and H6
(NrOfRXPDO/NrOfTXPDO). A DCF is checked with the configured ParameterValue of
a mapping entry where it has one, else with its DefaultValue.
"""

from __future__ import annotations

from ...catalogue import RULES
from ...catalogue.pdo import PDO001, PDO002, PDO003, PDO004, PDO005, PDO006, PDO007, PDO008, PDO009, PDO010, PDO011
from ...diagnostics import Diagnostics, Loc, Severity, where
from ...model import Obj, ObjectDictionary, Sub
from ...model.pdo import (FD_FRAME_BITS, FRAME_BITS, MAPPINGS, MAX_ENTRIES, MappingEntry, decode_mapping,
                         mapping_objects, pdo_disabled)
from ...model.datatypes import BASIC_TYPES, DataType
from .base import LintOptions, LintPass
from ...model.header import header_field, header_int
from .common import disabled, dummy_enabled, granularity, value_in_force, value_line



def mappings(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    gran, _ = granularity(od)
    limit = FD_FRAME_BITS if options.can_fd else FRAME_BITS
    for obj, kind in mapping_objects(od):
        offset = 0
        misaligned = False
        contrary: list[MappingEntry] = []
        found = Diagnostics()  # the findings that block, unless the PDO starts disabled
        for entry in mapping_entries(od, obj, diags, found):
            _target(od, obj, kind, entry, contrary, found, diags)
            if gran and gran > 0 and offset % gran and not misaligned:
                misaligned = True
                diags.add(PDO007, Loc(od.source, entry.line),
                          f"maps {where(entry.index, entry.subindex)} at bit offset {offset}, "
                          f"not a multiple of Granularity {gran}", obj.index, entry.sub.subindex)
            offset += entry.length
        _report_contrary(od, obj, kind, contrary, diags)
        if offset > limit:
            _overflow(od, obj, kind, offset, limit, options, found)
        _unserved(od, obj, kind, found, diags)


def _unserved(od: ObjectDictionary, obj: Obj, kind: str, found: Diagnostics, diags: Diagnostics) -> None:
    """A mapping the runtime cannot serve blocks, unless its PDO starts disabled (model.pdo.pdo_disabled):
    the node then leaves the PDO unused, as the description starts it, and refuses to enable it with this
    mapping (abort 0x06040043), so a master remaps it first."""
    off = pdo_disabled(od, obj.index)
    for d in found:
        if not off or not d.blocks:
            diags.add(RULES[d.rule], d.loc, d.message, d.index, d.sub, blocks=d.blocking, severity=d.severity)
            continue
        diags.add(RULES[d.rule], d.loc, f"{d.message}; {kind}{(obj.index & 0x1FF) + 1} starts disabled and the node "
                  "refuses to enable it with this mapping", d.index, d.sub, blocks=False, severity=Severity.WARNING)
    for rule_id, omitted in found.omitted().items():  # past the cap: counted, not listed
        diags.counts[rule_id] += omitted


def _overflow(od: ObjectDictionary, obj: Obj, kind: str, offset: int, limit: int, options: LintOptions,
              diags: Diagnostics) -> None:
    sub0 = obj.subs.get(0)
    if sub0 is None:
        return
    value, keyword = value_in_force(od, sub0)
    frame = "CAN FD frame" if options.can_fd else "CAN frame"
    diags.add(PDO005, Loc(od.source, value_line(sub0, value, keyword)),
              f"{kind} maps {offset} bits; a {frame} carries {limit}", obj.index, 0)


def mapping_entries(od: ObjectDictionary, obj: Obj, diags: Diagnostics,
                    unserved: Diagnostics | None = None) -> list[MappingEntry]:
    """The entries sub0 activates, reporting counted entries that are absent or empty (absent ones, which
    the runtime cannot serve, into `unserved` when given)."""
    mapping = decode_mapping(od, obj)
    sub0 = obj.subs.get(0)
    if mapping.count is None or sub0 is None:
        return mapping.entries
    value, keyword = value_in_force(od, sub0)
    loc, said = Loc(od.source, value_line(sub0, value, keyword)), value.text.strip() if value else ""
    if mapping.too_many:
        diags.add(PDO006, loc, f"sub0={said} counts more than {MAX_ENTRIES} mapping entries", obj.index, 0)
        return []  # the count itself is wrong: its entries say nothing more
    if mapping.absent:
        absent = mapping.absent
        names = ", ".join(f"sub{i}" for i in absent[:4]) + (" ..." if len(absent) > 4 else "")
        (diags if unserved is None else unserved).add(
            PDO001, loc, f"sub0={said} counts {names}, which {'is' if len(absent) == 1 else 'are'} not defined",
            obj.index, 0)
    if mapping.empty:
        # once per object: generators write sub0 = highest sub-index over all-zero entries
        empty = mapping.empty
        more = f" (and {len(empty) - 1} more empty entries)" if len(empty) > 1 else ""
        diags.add(PDO011, Loc(od.source, empty[0].line),
                  f"maps nothing (0x00000000) but sub0={said} counts it{more}", obj.index, empty[0].sub.subindex)
    return mapping.entries


def _target(od: ObjectDictionary, obj: Obj, kind: str, entry: MappingEntry, contrary: list[MappingEntry],
            diags: Diagnostics, direct: Diagnostics) -> None:
    """The mapped entry's findings: those the runtime could not serve into `diags`, the others (a dummy
    the runtime serves whatever [DummyUsage] says) into `direct`."""
    loc = Loc(od.source, entry.line)
    name = where(entry.index, entry.subindex)
    if entry.index < 0x0020:
        _dummy(od, obj, entry, direct)
        return
    target = od.find(entry.index, entry.subindex)
    if target is None:
        diags.add(PDO001, loc, f"maps {name}, which does not exist", obj.index, entry.sub.subindex)
        return
    if not target.pdo_mapping:
        _unflagged(od, obj, kind, entry, target, diags)
    _direction(od, obj, kind, entry, target, diags)
    if (kind, target.access) in (("RPDO", "rwr"), ("TPDO", "rww")):
        contrary.append(entry)
    _length(od, obj, entry, target.dtype, name, diags)


def _unflagged(od: ObjectDictionary, obj: Obj, kind: str, entry: MappingEntry, target: Sub,
               diags: Diagnostics) -> None:
    """PDO002: the description's own mapping is the more specific statement, so the C makes a number it
    maps mappable in that direction (model.pdo.default_mapped); other types no PDO carries."""
    loc, name = Loc(od.source, entry.line), where(entry.index, entry.subindex)
    dtype = target.dtype
    if dtype is None or not dtype.is_numeric:
        diags.add(PDO002, loc, f"maps {name}, which has PDOMapping=0", obj.index, entry.sub.subindex)
        return
    diags.add(PDO002, loc, f"maps {name}, which has PDOMapping=0; the C makes it {kind}-mappable, as this "
              "mapping uses it", obj.index, entry.sub.subindex, blocks=False, severity=Severity.WARNING)


def _dummy(od: ObjectDictionary, obj: Obj, entry: MappingEntry, diags: Diagnostics) -> None:
    loc = Loc(od.source, entry.line)
    dtype = BASIC_TYPES.get(entry.index)
    if dtype is None or dtype.bits == 0:
        diags.add(PDO001, loc, f"maps 0x{entry.index:04X}, which is not a data type usable as a dummy",
                  obj.index, entry.sub.subindex)
        return
    if not dummy_enabled(od, entry.index):
        diags.add(PDO001, loc, f"maps dummy 0x{entry.index:04X} ({dtype.name}) but [DummyUsage] "
                  f"Dummy{entry.index:04X} is not 1", obj.index, entry.sub.subindex)
        return
    _length(od, obj, entry, dtype, f"dummy 0x{entry.index:04X}", diags)


def _direction(od: ObjectDictionary, obj: Obj, kind: str, entry: MappingEntry, target: Sub,
               diags: Diagnostics) -> None:
    access = target.access
    loc = Loc(od.source, entry.line)
    name = where(entry.index, entry.subindex)
    if kind == "RPDO" and access in ("ro", "const"):
        diags.add(PDO004, loc, f"RPDO maps {name}, which is {access}", obj.index, entry.sub.subindex)
    elif kind == "TPDO" and access == "wo":
        diags.add(PDO004, loc, f"TPDO maps {name}, which is wo", obj.index, entry.sub.subindex)


def _report_contrary(od: ObjectDictionary, obj: Obj, kind: str, contrary: list[MappingEntry],
                     diags: Diagnostics) -> None:
    """Once per mapping object: one wrong declaration is usually repeated for every entry."""
    if not contrary:
        return
    first = contrary[0]
    access = "rwr" if kind == "RPDO" else "rww"
    other = "TPDO" if kind == "RPDO" else "RPDO"
    more = f" (and {len(contrary) - 1} more entries)" if len(contrary) > 1 else ""
    diags.add(PDO010, Loc(od.source, first.line),
              f"{kind} maps {where(first.index, first.subindex)}, which is {access} ({other} data){more}",
              obj.index, first.sub.subindex)


def _length(od: ObjectDictionary, obj: Obj, entry: MappingEntry, dtype: DataType | None, name: str,
            diags: Diagnostics) -> None:
    """PDO003 when the entry's length is not the size of the data type it maps (`name` in the message)."""
    if dtype is None or dtype.bits == 0:
        return  # strings and domains: size from the value, not checked here
    # BOOLEAN maps as 1 bit (bit-granular devices) or as a byte (byte-granular ones)
    if entry.length != dtype.bits and not (dtype.kind == "bool" and entry.length == 8):
        short = dtype.code in SHORT_MAPPED and entry.length == 32  # served as CANopenNode does (odg_pdo.c)
        diags.add(PDO003, Loc(od.source, entry.line),
                  f"maps {name} ({dtype.bits} bit) with length {entry.length}"
                  + ("; the runtime serves its low-order 32 bits, as CANopenNode does" if short else ""),
                  obj.index, entry.sub.subindex, blocks=not short, severity=Severity.WARNING if short else None)


# INTEGER64 and UNSIGNED64: mapped with 32 bits, the runtime serves their low-order four bytes
SHORT_MAPPED = frozenset((0x0015, 0x001B))


# -- C5, H6 ----------------------------------------------------------------------

def _compact_pdo(od: ObjectDictionary) -> bool:
    return bool(header_int(header_field(od, "DeviceInfo", "CompactPDO")))


def _present(od: ObjectDictionary, index: int) -> Obj | None:
    obj = od.objects.get(index)
    return obj if obj is not None and not disabled(obj) else None


def _half_pdo(od: ObjectDictionary, comm_index: int, map_index: int) -> tuple[Obj, int, str] | None:
    """(object present, index missing, what is missing) for a PDO with only one of its two objects."""
    comm, mapping = _present(od, comm_index), _present(od, map_index)
    if comm is not None and mapping is None:
        return comm, map_index, "mapping"
    if mapping is not None and comm is None:
        return mapping, comm_index, "communication"
    return None


def pairing(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    compact = _compact_pdo(od)
    for map_base, (kind, comm_base) in MAPPINGS.items():
        implied = header_int(header_field(od, "DeviceInfo", f"NrOf{kind[0]}XPDO"))
        implied = implied if compact and implied else 0
        for n in range(0x200):
            half = _half_pdo(od, comm_base + n, map_base + n)
            if half is None or n < implied:
                continue
            present, absent, what = half
            diags.add(PDO008, Loc(od.source, present.line),
                      f"{kind}{n + 1} has no {what} object 0x{absent:04X}", present.index)


def pdo_counts(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    section = od.section("DeviceInfo")
    if section is None:
        return
    compact = _compact_pdo(od)
    for map_base, (kind, comm_base) in MAPPINGS.items():
        key = f"NrOf{kind[0]}XPDO"
        fld = section.get(key)
        declared = header_int(fld)
        present = sum(1 for n in range(0x200) if _present(od, comm_base + n) or _present(od, map_base + n))
        if fld is None or declared is None:
            continue
        if present != declared and not (compact and present < declared):
            diags.add(PDO009, Loc(od.source, fld.line),
                      f"{fld.key}={fld.text.strip()} but the file defines {present} {kind}"
                      f"{'' if present == 1 else 's'} (0x{comm_base:04X}-0x{comm_base + 0x1FF:04X})")


# This family's lint passes, in the order they run.
PASSES: tuple[LintPass, ...] = (mappings, pairing, pdo_counts)
