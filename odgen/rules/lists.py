"""LST: [MandatoryObjects]/[OptionalObjects]/[ManufacturerObjects] and index ranges.

CiA 306 rule table rows L1-L4. The object lists exist in EDS/DCF only; the
index-range rule (L4) applies to every format.
"""

from __future__ import annotations

from collections.abc import Iterator

from ..diagnostics import Diagnostics, Loc, Severity, define_rule
from ..model import Field, ObjectDictionary, ObjectList
from ..model.values import bounded_int, parse_int_literal
from . import LintOptions, check
from .common import gaps

E, W, INFO = Severity.ERROR, Severity.WARNING, Severity.INFO

define_rule(
    "LST001", E, "SupportedObjects missing or not a number", ref="CiA 306 table row L1",
    why="Each object list starts with `SupportedObjects=N`, the number of entries 1..N that follow. "
    "Without it readers do not know how many entries to read (Vector: \"SupportedObjects can not be "
    "found\").",
    example="[OptionalObjects]\n1=0x1017",
    fix="Add `SupportedObjects=<number of entries>`.")
define_rule(
    "LST002", E, "object list entry missing", ref="CiA 306 table row L1",
    why="An object list with SupportedObjects=N has the keys 1..N. Readers that loop over 1..N "
    "stop at the first gap or fail (Lely: \"entry missing\").",
    example="[OptionalObjects]\nSupportedObjects=3\n1=0x1008\n2=0x1017",
    fix="Add the missing entries or lower SupportedObjects.")
define_rule(
    "LST003", E, "object list entry beyond SupportedObjects", ref="CiA 306 table row L1",
    why="Keys other than 1..SupportedObjects are not read by tools that loop over 1..N, so the "
    "object is invisible to them (Lely: \"too many entries\").",
    example="[OptionalObjects]\nSupportedObjects=1\n1=0x1008\n2=0x1017",
    fix="Raise SupportedObjects to the number of entries, or renumber them 1..N.")
define_rule(
    "LST004", E, "object list entry is not an index", ref="CiA 306 table row L2",
    why="Each entry names an object index as a number (`0x1017`); other text cannot be resolved.",
    example="[OptionalObjects]\nSupportedObjects=1\n1=Heartbeat",
    fix="Write the index as a hex number, e.g. `1=0x1017`.")
define_rule(
    "LST005", E, "listed object has no section", ref="CiA 306 table row L2",
    why="Every index in an object list needs its `[XXXX]` section; Lely stops with \"object not "
    "found\", other tools silently drop it.",
    example="[OptionalObjects]\nSupportedObjects=1\n1=0x1017\n(no [1017] section)",
    fix="Add the object section, or remove the entry.")
define_rule(
    "LST006", E, "object listed more than once", ref="CiA 306 table row L2",
    why="Each object appears in exactly one object list, once. Repeats inflate SupportedObjects and "
    "make tools create the object twice.",
    example="[OptionalObjects]\nSupportedObjects=2\n1=0x1017\n2=0x1017",
    fix="Remove the repeated entry and renumber the list.")
define_rule(
    "LST007", E, "object section not listed", ref="CiA 306 table row L2",
    why="Tools that read objects through the lists (python canopen, CANopenEditor, Lely) never see an "
    "object that has a section but no list entry.",
    example="[2000]\nParameterName=Speed\n(0x2000 in no [...Objects] list)",
    fix="Add the index to [ManufacturerObjects] (0x2000-0x5FFF) or [OptionalObjects], and update "
    "SupportedObjects.")
define_rule(
    "LST008", E, "object in the wrong list", ref="CiA 306 table row L3",
    why="[MandatoryObjects] holds 0x1000, 0x1001 and 0x1018; [ManufacturerObjects] holds exactly "
    "the manufacturer range 0x2000-0x5FFF; [OptionalObjects] everything else. Lely refuses other "
    "placements.",
    example="[OptionalObjects]\nSupportedObjects=1\n1=0x2000",
    fix="Move the entry to the list for its index range.")
define_rule(
    "LST009", W, "mandatory object listed as optional", ref="CiA 306 table row L3",
    why="CiA 301 v4 makes 0x1000, 0x1001 and 0x1018 mandatory; files written for older versions "
    "list 0x1018 under [OptionalObjects].",
    example="[OptionalObjects]\nSupportedObjects=1\n1=0x1018",
    fix="Move the entry to [MandatoryObjects].")
define_rule(
    "LST010", W, "SupportedObjects or entry key not decimal", ref="CiA 306 table row L1",
    why="Object list counts and keys are decimal numbers. Lely's dcfchk refuses `SupportedObjects=0x03` "
    "(the Lely-ready copies of vendor files in the wild have it rewritten in decimal).",
    example="[MandatoryObjects]\nSupportedObjects=0x03",
    fix="Write the number in decimal: `SupportedObjects=3`.")
define_rule(
    "LST011", E, "object index in a reserved range",
    ref="CiA 306 table row L4 / CiA 301 index ranges",
    why="CiA 301 reserves index 0x0000 and 0x0260-0x0FFF; no device may define objects there. "
    "(0x0001-0x025F data types, 0x1000-0x1FFF communication, 0x2000-0x5FFF manufacturer, "
    "0x6000-0x9FFF device profile, 0xA000-0xBFFF interface profile.)",
    example="[0800]\nParameterName=Misplaced",
    fix="Move the object to the manufacturer range 0x2000-0x5FFF.")
define_rule(
    "LST012", W, "object index in the reserved range 0xC000-0xFFFF",
    ref="CiA 306 table row L4 / CiA 301 index ranges",
    why="CiA 301 reserves 0xC000-0xFFFF for future use; objects there may collide with later "
    "profiles and some tools reject them.",
    example="[C000]\nParameterName=Vendor block",
    fix="Move the object to the manufacturer range 0x2000-0x5FFF.")

LISTS = (("mandatoryobjects", "MandatoryObjects"), ("optionalobjects", "OptionalObjects"),
         ("manufacturerobjects", "ManufacturerObjects"))
MANDATORY = (0x1000, 0x1001, 0x1018)


def _proper_list(index: int) -> str:
    if index in MANDATORY:
        return "mandatoryobjects"
    if 0x2000 <= index <= 0x5FFF:
        return "manufacturerobjects"
    return "optionalobjects"


def _uses_lists(od: ObjectDictionary) -> bool:
    return od.format not in ("xdd", "xdc")


# -- L1 --------------------------------------------------------------------------

@check
def list_counts(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    if not _uses_lists(od):
        return
    for key, _name in LISTS:
        olist = od.object_lists.get(key)
        if olist is not None:
            _count(od, olist, diags)


def _count(od: ObjectDictionary, olist: ObjectList, diags: Diagnostics) -> None:
    supported = olist.supported
    declared, _ = parse_int_literal(supported.text) if supported is not None else (None, [])
    if supported is None or declared is None or declared < 0:
        what = f"SupportedObjects={supported.text.strip()} is not a number" if supported else "no SupportedObjects"
        diags.add("LST001", Loc(od.source, supported.line if supported else olist.line),
                  f"[{olist.name}] has {what}" if not supported else f"[{olist.name}] {what}")
        return
    if not supported.text.strip().isdigit():
        diags.add("LST010", Loc(od.source, supported.line),
                  f"[{olist.name}] SupportedObjects={supported.text.strip()} is not decimal")
    keys = _entry_keys(od, olist, diags)
    first, missing = gaps(declared, set(keys))
    if missing:
        shown = ", ".join(str(n) for n in first) + (" ..." if missing > len(first) else "")
        diags.add("LST002", Loc(od.source, supported.line),
                  f"[{olist.name}] SupportedObjects={supported.text.strip()} but entr"
                  f"{'y' if missing == 1 else 'ies'} {shown} missing")
    for n, fld in keys.items():
        if not 1 <= n <= declared:
            diags.add("LST003", Loc(od.source, fld.line),
                      f"[{olist.name}] entry {fld.key} is beyond SupportedObjects={supported.text.strip()}")


def _entry_keys(od: ObjectDictionary, olist: ObjectList, diags: Diagnostics) -> dict[int, Field]:
    keys: dict[int, Field] = {}
    for fld in olist.entries:
        n, _ = parse_int_literal(fld.key)
        if n is None:
            diags.add("LST003", Loc(od.source, fld.line), f"[{olist.name}] key '{fld.key}' is not an entry number")
            continue
        if not fld.key.strip().isdigit():
            diags.add("LST010", Loc(od.source, fld.line), f"[{olist.name}] entry key {fld.key} is not decimal")
        keys.setdefault(n, fld)
    return keys


# -- L2, L3 ----------------------------------------------------------------------

def _listed(od: ObjectDictionary) -> Iterator[tuple[str, str, Field]]:
    """(list key, list name, entry) of every object list entry, list by list."""
    for key, name in LISTS:
        olist = od.object_lists.get(key)
        for fld in olist.entries if olist is not None else ():
            yield key, name, fld


def listed_indices(od: ObjectDictionary) -> dict[int, tuple[str, Field]]:
    """Index -> (list key, entry) of its first listing."""
    seen: dict[int, tuple[str, Field]] = {}
    for key, _name, fld in _listed(od):
        index, _ = parse_int_literal(fld.text)
        if index is not None:
            seen.setdefault(index, (key, fld))
    return seen


@check
def list_entries(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    if not _uses_lists(od):
        return
    seen: dict[int, Field] = {}
    for key, name, fld in _listed(od):
        _entry(od, key, name, fld, seen, diags)


def _entry(od: ObjectDictionary, key: str, name: str, fld: Field, seen: dict[int, Field],
           diags: Diagnostics) -> None:
    loc = Loc(od.source, fld.line)
    index, _ = parse_int_literal(fld.text)
    if index is None or not 0 <= index <= 0xFFFF:
        diags.add("LST004", loc, f"[{name}] entry {fld.key}={fld.text.strip()} is not an object index")
        return
    if index in seen:
        diags.add("LST006", loc, f"[{name}] entry {fld.key} lists 0x{index:04X} again "
                  f"(first at line {seen[index].line})")
        return
    seen[index] = fld
    if index not in od.objects:
        diags.add("LST005", loc, f"[{name}] entry {fld.key} lists 0x{index:04X}, which has no section"
                  f"{_decimal_hint(od, fld.text)}")
        return  # which list it belongs in matters little for an object that does not exist
    proper = _proper_list(index)
    if proper == key:
        return  # data type definitions (0x0001-0x025F) count as optional objects
    if key == "optionalobjects" and proper == "mandatoryobjects":
        diags.add("LST009", loc, f"[{name}] entry {fld.key} lists mandatory object 0x{index:04X}")
        return
    wanted = dict(LISTS)[proper]
    diags.add("LST008", loc, f"[{name}] entry {fld.key} lists 0x{index:04X}, which belongs in [{wanted}]")


def _decimal_hint(od: ObjectDictionary, text: str) -> str:
    """`1=1018` is decimal 1018 = 0x03FA; say so when the hex reading names an object."""
    index = _hex_reading(text)
    if index is not None and index in od.objects:
        return f" ({text.strip()} is decimal; 0x{index:04X} was probably meant)"
    return ""


def _hex_reading(text: str) -> int | None:
    """The hex value of ASCII decimal digits without a leading zero (isdigit() alone takes '²' and '١')."""
    text = text.strip()
    if not (text.isascii() and text.isdigit()) or text[0] == "0":
        return None
    return bounded_int(text, 16)


def _misread_decimals(od: ObjectDictionary) -> set[int]:
    """Objects an entry names in decimal (`1=1018` for 0x1018)."""
    found = set()
    for olist in od.object_lists.values():
        for fld in olist.entries:
            index = _hex_reading(fld.text)
            if index is not None and index in od.objects and bounded_int(fld.text.strip()) not in od.objects:
                found.add(index)
    return found


@check
def unlisted_objects(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    if not _uses_lists(od) or not od.object_lists:
        return
    listed = set(listed_indices(od))
    listed |= _misread_decimals(od)  # already reported, with a hint, as LST005
    for index, obj in od.objects.items():
        if index not in listed and index >= 0x1000:
            wanted = dict(LISTS)[_proper_list(index)]
            diags.add("LST007", Loc(od.source, obj.line), f"is in no object list (belongs in [{wanted}])", index)


# -- L4 --------------------------------------------------------------------------

@check
def index_ranges(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for index, obj in od.objects.items():
        if index == 0 or 0x0260 <= index <= 0x0FFF:
            diags.add("LST011", Loc(od.source, obj.line), "is in a range CiA 301 reserves", index)
        elif index >= 0xC000:
            diags.add("LST012", Loc(od.source, obj.line), "is in the range 0xC000-0xFFFF CiA 301 reserves", index)
