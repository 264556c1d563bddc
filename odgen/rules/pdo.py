"""PDO: mapping objects and their pairing with communication objects.

CiA 306 rule table rows C1-C5, H5 (mapping offsets against Granularity) and H6
(NrOfRXPDO/NrOfTXPDO). A DCF is checked with the configured ParameterValue of
a mapping entry where it has one, else with its DefaultValue.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from ..diagnostics import Diagnostics, Loc, Severity, define_rule, where
from ..model import ARRAY, RECORD, Obj, ObjectDictionary, Sub, Value
from ..model.datatypes import BASIC_TYPES, DataType
from . import LintOptions, check
from .common import (disabled, dummy_enabled, granularity, header_field, header_int, number, plain_int,
                     value_in_force, value_line)

E, W, INFO = Severity.ERROR, Severity.WARNING, Severity.INFO

define_rule(
    "PDO001", E, "mapped entry does not exist",
    ref="CiA 306 table row C1 / CiA 301 PDO mapping parameter",
    why="Each mapping entry 1..sub0 of 0x1600-0x17FF/0x1A00-0x1BFF names index, sub-index and length "
    "(0xIIIISSLL) of an existing entry, or of a data type index 0x0001-0x001B enabled as a dummy in "
    "[DummyUsage]. Devices refuse such a mapping at start-up (abort 0x06020000), leaving the PDO dead.",
    example="[1A00sub1]\nDefaultValue=0x60000108\n(no [6000] section)",
    fix="Map an existing entry, add the object, or enable the dummy with `DummyXXXX=1`.")
define_rule(
    "PDO002", E, "mapped entry is not PDO-mappable", ref="CiA 306 table row C2",
    why="Only entries with `PDOMapping=1` may be mapped; devices refuse the mapping with SDO abort "
    "0x06040041 and CANopenEditor reports a \"not mappable OD entry\".",
    example="[6000sub1]\nPDOMapping=0\n[1A00sub1]\nDefaultValue=0x60000108",
    fix="Set `PDOMapping=1` on the entry, or map another one.")
define_rule(
    "PDO003", E, "mapping length differs from the entry's size", ref="CiA 306 table row C3",
    why="The low byte of a mapping entry is the length in bits and must equal the mapped entry's "
    "size (0x08 for UNSIGNED8, 0x20 for UNSIGNED32; BOOLEAN 1 or 8). Otherwise the receiver "
    "decodes every later field at the wrong offset; CANopenNode refuses it at run time.",
    example="[6000sub1]\nDataType=0x0005\n[1A00sub1]\nDefaultValue=0x60000110",
    fix="Write the entry's bit size in the low byte (`0x60000108`).")
define_rule(
    "PDO004", E, "mapped entry cannot be accessed in the PDO's direction",
    ref="CiA 306 table row C2",
    why="An RPDO writes its entries, so they must be writable (wo, rw, rww); a TPDO reads them, so "
    "they must be readable (ro, const, rw, rwr). CANopenEditor and Lely's dcfgen refuse the mapping.",
    example="[6000sub1]\nAccessType=ro\n[1600sub1]\nDefaultValue=0x60000108",
    fix="Map the entry in the other PDO direction, or correct its AccessType.")
define_rule(
    "PDO005", E, "PDO maps more than a frame carries", ref="CiA 306 table row C4",
    why="A CAN frame carries 64 bits of data (CAN FD: 512, with --can-fd). A longer mapping is "
    "refused by the device (abort 0x06040042); Lely's dcfgen reports \"mapping exceeds 64 bits\".",
    example="[1A00sub0]\nDefaultValue=3\n3 entries of 32 bits",
    fix="Move entries to another PDO.")
define_rule(
    "PDO006", E, "more than 64 mapping entries", ref="CiA 301 PDO mapping parameter",
    why="A mapping object has at most 64 entries (sub-index 1..0x40); sub0 cannot count more.",
    example="[1A00sub0]\nDefaultValue=65",
    fix="Map at most 64 entries.")
define_rule(
    "PDO007", E, "mapping offset not a multiple of Granularity", ref="CiA 306 table row H5",
    why="[DeviceInfo] Granularity is the bit granularity the device can map at: with 8, every "
    "entry must start on a byte boundary. A BOOLEAN mapped with length 1 shifts everything "
    "after it. (Granularity=0 means the mapping is fixed and is not checked.)",
    example="Granularity=8\n[1A00sub1]\nDefaultValue=0x20000101\n[1A00sub2]\nDefaultValue=0x20010108",
    fix="Map entries whose lengths keep later entries aligned, or pad with a dummy entry.")
define_rule(
    "PDO008", E, "PDO communication and mapping objects not paired", ref="CiA 306 table row C5",
    why="RPDO n is 0x1400+n with mapping 0x1600+n, TPDO n 0x1800+n with mapping 0x1A00+n; one "
    "without the other is a PDO that cannot be configured or has no data. (With CompactPDO the "
    "missing objects up to NrOfRXPDO/NrOfTXPDO are implied.)",
    example="[1800]\n(no [1A00] section)",
    fix="Add the missing object, or remove the half PDO.")
define_rule(
    "PDO009", W, "NrOfRXPDO/NrOfTXPDO differs from the PDOs present", ref="CiA 306 table row H6",
    why="NrOfRXPDO and NrOfTXPDO in [DeviceInfo] count the RPDOs (0x1400-0x15FF) and TPDOs "
    "(0x1800-0x19FF) the file defines. Masters size their configuration by them. With CompactPDO "
    "the PDOs may be implied, so only more PDOs than declared are reported. Objects CANopenEditor "
    "marks `CO_disabled` are not counted.",
    example="NrOfTXPDO=4\n(only [1800] and [1801])",
    fix="Set the counts to the number of PDOs defined.")
define_rule(
    "PDO010", W, "mapped entry declared for the other PDO direction", ref="CiA 306 table row O8",
    why="`rwr` marks process input (sent by TPDO), `rww` process output (received by RPDO). An "
    "RPDO mapping an rwr entry, or a TPDO mapping an rww one, works but contradicts the "
    "declaration; Vector's checker warns.",
    example="[6000sub1]\nAccessType=rwr\n[1600sub1]\nDefaultValue=0x60000108",
    fix="Map the entry in the declared direction, or correct its AccessType.")

MAPPINGS = {0x1600: ("RPDO", 0x1400), 0x1A00: ("TPDO", 0x1800)}
FRAME_BITS, FD_FRAME_BITS = 64, 512
MPDO = (0xFE, 0xFF)  # mapping sub0 of a multiplexed PDO: SAM-MPDO / DAM-MPDO (CiA 301)


@dataclass
class Entry:
    """One active mapping entry, decoded."""

    sub: Sub
    value: Value
    index: int
    subindex: int
    length: int
    line: int


def _kind(index: int) -> tuple[str, int] | None:
    """("RPDO"|"TPDO", PDO number) for a mapping object index."""
    for base, (kind, _comm) in MAPPINGS.items():
        if base <= index < base + 0x200:
            return kind, index - base
    return None


def mapping_objects(od: ObjectDictionary) -> Iterator[tuple[Obj, str]]:
    for index, obj in od.objects.items():
        kind = _kind(index)
        if kind is not None and obj.object_code in (ARRAY, RECORD):
            yield obj, kind[0]


@check
def mappings(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    gran, _ = granularity(od)
    limit = FD_FRAME_BITS if options.can_fd else FRAME_BITS
    for obj, kind in mapping_objects(od):
        offset = 0
        misaligned = False
        contrary: list[Entry] = []
        for entry in mapping_entries(od, obj, diags):
            _target(od, obj, kind, entry, contrary, diags)
            if gran and gran > 0 and offset % gran and not misaligned:
                misaligned = True
                diags.add("PDO007", Loc(od.source, entry.line),
                          f"maps {where(entry.index, entry.subindex)} at bit offset {offset}, "
                          f"not a multiple of Granularity {gran}", obj.index, entry.sub.subindex)
            offset += entry.length
        _report_contrary(od, obj, kind, contrary, diags)
        if offset > limit:
            _overflow(od, obj, kind, offset, limit, options, diags)


def _overflow(od: ObjectDictionary, obj: Obj, kind: str, offset: int, limit: int, options: LintOptions,
              diags: Diagnostics) -> None:
    sub0 = obj.subs.get(0)
    if sub0 is None:
        return
    value, keyword = value_in_force(od, sub0)
    frame = "CAN FD frame" if options.can_fd else "CAN frame"
    diags.add("PDO005", Loc(od.source, value_line(sub0, value, keyword)),
              f"{kind} maps {offset} bits; a {frame} carries {limit}", obj.index, 0)


def mapping_entries(od: ObjectDictionary, obj: Obj, diags: Diagnostics) -> list[Entry]:
    """The entries sub0 activates, reporting counted entries that are absent or empty."""
    sub0 = obj.subs.get(0)
    value, keyword = value_in_force(od, sub0) if sub0 is not None else (None, "")
    if number(value) in MPDO:
        return []  # multiplexed PDO: the entries are not a fixed mapping
    count = plain_int(value) if sub0 is not None and not sub0.compact else None
    if sub0 is None or value is None or count is None:
        return _decoded(od, obj, max(obj.subs, default=0))[0]  # no count: every entry present is active
    loc, said = Loc(od.source, value_line(sub0, value, keyword)), value.text.strip()
    if count > 64:
        diags.add("PDO006", loc, f"sub0={said} counts more than 64 mapping entries", obj.index, 0)
        return []  # the count itself is wrong: its entries say nothing more
    _absent(obj, count, loc, said, diags)
    entries, empty = _decoded(od, obj, count)
    if empty:
        # once per object: generators write sub0 = highest sub-index over all-zero entries
        more = f" (and {len(empty) - 1} more empty entries)" if len(empty) > 1 else ""
        diags.add("PDO001", Loc(od.source, empty[0].line),
                  f"maps nothing (0x00000000) but sub0={said} counts it{more}", obj.index, empty[0].sub.subindex)
    return entries


def _absent(obj: Obj, count: int, loc: Loc, said: str, diags: Diagnostics) -> None:
    """PDO001 at sub0 (`loc`, written `said`) for the entries 1..count it counts that are not defined."""
    absent = [i for i in range(1, count + 1) if i not in obj.subs]
    if absent:
        names = ", ".join(f"sub{i}" for i in absent[:4]) + (" ..." if len(absent) > 4 else "")
        diags.add("PDO001", loc, f"sub0={said} counts {names}, which {'is' if len(absent) == 1 else 'are'} "
                  "not defined", obj.index, 0)


def _decoded(od: ObjectDictionary, obj: Obj, last: int) -> tuple[list[Entry], list[Entry]]:
    """The readable entries 1..last: those that map something, and the empty ones (0x00000000)."""
    entries: list[Entry] = []
    empty: list[Entry] = []
    for subindex in range(1, last + 1):
        sub = obj.subs.get(subindex)
        entry = _decode(od, sub) if sub is not None else None
        if entry is not None:
            (empty if entry.value.parsed == 0 else entries).append(entry)
    return entries, empty


def _decode(od: ObjectDictionary, sub: Sub) -> Entry | None:
    value, keyword = value_in_force(od, sub)
    raw = plain_int(value)
    if value is None or raw is None or not 0 <= raw <= 0xFFFFFFFF:
        return None
    return Entry(sub, value, raw >> 16, (raw >> 8) & 0xFF, raw & 0xFF, value_line(sub, value, keyword))


def _target(od: ObjectDictionary, obj: Obj, kind: str, entry: Entry, contrary: list[Entry],
            diags: Diagnostics) -> None:
    loc = Loc(od.source, entry.line)
    name = where(entry.index, entry.subindex)
    if entry.index < 0x0020:
        _dummy(od, obj, entry, diags)
        return
    target = od.find(entry.index, entry.subindex)
    if target is None:
        diags.add("PDO001", loc, f"maps {name}, which does not exist", obj.index, entry.sub.subindex)
        return
    if not target.pdo_mapping:
        diags.add("PDO002", loc, f"maps {name}, which has PDOMapping=0", obj.index, entry.sub.subindex)
    _direction(od, obj, kind, entry, target, diags)
    if (kind, target.access) in (("RPDO", "rwr"), ("TPDO", "rww")):
        contrary.append(entry)
    _length(od, obj, entry, target.dtype, name, diags)


def _dummy(od: ObjectDictionary, obj: Obj, entry: Entry, diags: Diagnostics) -> None:
    loc = Loc(od.source, entry.line)
    dtype = BASIC_TYPES.get(entry.index)
    if dtype is None or dtype.bits == 0:
        diags.add("PDO001", loc, f"maps 0x{entry.index:04X}, which is not a data type usable as a dummy",
                  obj.index, entry.sub.subindex)
        return
    if not dummy_enabled(od, entry.index):
        diags.add("PDO001", loc, f"maps dummy 0x{entry.index:04X} ({dtype.name}) but [DummyUsage] "
                  f"Dummy{entry.index:04X} is not 1", obj.index, entry.sub.subindex)
        return
    _length(od, obj, entry, dtype, f"dummy 0x{entry.index:04X}", diags)


def _direction(od: ObjectDictionary, obj: Obj, kind: str, entry: Entry, target: Sub,
               diags: Diagnostics) -> None:
    access = target.access
    loc = Loc(od.source, entry.line)
    name = where(entry.index, entry.subindex)
    if kind == "RPDO" and access in ("ro", "const"):
        diags.add("PDO004", loc, f"RPDO maps {name}, which is {access}", obj.index, entry.sub.subindex)
    elif kind == "TPDO" and access == "wo":
        diags.add("PDO004", loc, f"TPDO maps {name}, which is wo", obj.index, entry.sub.subindex)


def _report_contrary(od: ObjectDictionary, obj: Obj, kind: str, contrary: list[Entry],
                     diags: Diagnostics) -> None:
    """Once per mapping object: one wrong declaration is usually repeated for every entry."""
    if not contrary:
        return
    first = contrary[0]
    access = "rwr" if kind == "RPDO" else "rww"
    other = "TPDO" if kind == "RPDO" else "RPDO"
    more = f" (and {len(contrary) - 1} more entries)" if len(contrary) > 1 else ""
    diags.add("PDO010", Loc(od.source, first.line),
              f"{kind} maps {where(first.index, first.subindex)}, which is {access} ({other} data){more}",
              obj.index, first.sub.subindex)


def _length(od: ObjectDictionary, obj: Obj, entry: Entry, dtype: DataType | None, name: str,
            diags: Diagnostics) -> None:
    """PDO003 when the entry's length is not the size of the data type it maps (`name` in the message)."""
    if dtype is None or dtype.bits == 0:
        return  # strings and domains: size from the value, not checked here
    # BOOLEAN maps as 1 bit (bit-granular devices) or as a byte (byte-granular ones)
    if entry.length != dtype.bits and not (dtype.kind == "bool" and entry.length == 8):
        diags.add("PDO003", Loc(od.source, entry.line),
                  f"maps {name} ({dtype.bits} bit) with length {entry.length}", obj.index, entry.sub.subindex)


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


@check
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
            diags.add("PDO008", Loc(od.source, present.line),
                      f"{kind}{n + 1} has no {what} object 0x{absent:04X}", present.index)


@check
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
            diags.add("PDO009", Loc(od.source, fld.line),
                      f"{fld.key}={fld.text.strip()} but the file defines {present} {kind}"
                      f"{'' if present == 1 else 's'} (0x{comm_base:04X}-0x{comm_base + 0x1FF:04X})")
