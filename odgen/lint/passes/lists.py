"""LST: [MandatoryObjects]/[OptionalObjects]/[ManufacturerObjects] and index ranges.

CiA 306 rule table rows L1-L4. The object lists exist in EDS/DCF only; the
index-range rule (L4) applies to every format.
"""

from __future__ import annotations

from collections.abc import Iterator

from ...catalogue.lists import (
    LST001, LST002, LST003, LST004, LST005, LST006, LST007, LST008, LST009, LST010, LST011, LST012)
from ...diagnostics import Diagnostics, Loc
from ...model import Field, ObjectDictionary, ObjectList
from ...model.cia301 import object_list_for
from ...model.values import bounded_int, parse_int_literal
from .base import LintOptions, LintPass
from .common import gaps



LISTS = (("mandatoryobjects", "MandatoryObjects"), ("optionalobjects", "OptionalObjects"),
         ("manufacturerobjects", "ManufacturerObjects"))


def _uses_lists(od: ObjectDictionary) -> bool:
    return od.format not in ("xdd", "xdc")


# -- L1 --------------------------------------------------------------------------

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
        diags.add(LST001, Loc(od.source, supported.line if supported else olist.line),
                  f"[{olist.name}] has {what}" if not supported else f"[{olist.name}] {what}")
        return
    if not supported.text.strip().isdigit():
        diags.add(LST010, Loc(od.source, supported.line),
                  f"[{olist.name}] SupportedObjects={supported.text.strip()} is not decimal")
    keys = _entry_keys(od, olist, diags)
    first, missing = gaps(declared, set(keys))
    if missing:
        shown = ", ".join(str(n) for n in first) + (" ..." if missing > len(first) else "")
        diags.add(LST002, Loc(od.source, supported.line),
                  f"[{olist.name}] SupportedObjects={supported.text.strip()} but entr"
                  f"{'y' if missing == 1 else 'ies'} {shown} missing")
    for n, fld in keys.items():
        if not 1 <= n <= declared:
            diags.add(LST003, Loc(od.source, fld.line),
                      f"[{olist.name}] entry {fld.key} is beyond SupportedObjects={supported.text.strip()}")


def _entry_keys(od: ObjectDictionary, olist: ObjectList, diags: Diagnostics) -> dict[int, Field]:
    keys: dict[int, Field] = {}
    for fld in olist.entries:
        n, _ = parse_int_literal(fld.key)
        if n is None:
            diags.add(LST003, Loc(od.source, fld.line), f"[{olist.name}] key '{fld.key}' is not an entry number")
            continue
        if not fld.key.strip().isdigit():
            diags.add(LST010, Loc(od.source, fld.line), f"[{olist.name}] entry key {fld.key} is not decimal")
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


def list_entries(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    if not _uses_lists(od):
        return
    seen: dict[int, Field] = {}
    for key, name, fld in _listed(od):
        _entry(od, key, name, fld, seen, diags)


def _entry(od: ObjectDictionary, key: str, name: str, fld: Field, seen: dict[int, Field],
           diags: Diagnostics) -> None:
    index, _ = parse_int_literal(fld.text)
    if index is None or not 0 <= index <= 0xFFFF:
        diags.add(LST004, Loc(od.source, fld.line),
                  f"[{name}] entry {fld.key}={fld.text.strip()} is not an object index")
        return
    if index in seen:
        diags.add(LST006, Loc(od.source, fld.line), f"[{name}] entry {fld.key} lists 0x{index:04X} again "
                  f"(first at line {seen[index].line})")
        return
    seen[index] = fld
    if index not in od.objects:
        diags.add(LST005, Loc(od.source, fld.line),
                  f"[{name}] entry {fld.key} lists 0x{index:04X}, which has no section{_decimal_hint(od, fld.text)}")
        return  # which list it belongs in matters little for an object that does not exist
    proper = object_list_for(index)
    if proper == key:
        return  # data type definitions (0x0001-0x025F) count as optional objects
    loc = Loc(od.source, fld.line)
    if key == "optionalobjects" and proper == "mandatoryobjects":
        diags.add(LST009, loc, f"[{name}] entry {fld.key} lists mandatory object 0x{index:04X}")
        return
    wanted = dict(LISTS)[proper]
    diags.add(LST008, loc, f"[{name}] entry {fld.key} lists 0x{index:04X}, which belongs in [{wanted}]")


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


def unlisted_objects(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    if not _uses_lists(od) or not od.object_lists:
        return
    listed = set(listed_indices(od))
    listed |= _misread_decimals(od)  # already reported, with a hint, as LST005
    for index, obj in od.objects.items():
        if index not in listed and index >= 0x1000:
            wanted = dict(LISTS)[object_list_for(index)]
            diags.add(LST007, Loc(od.source, obj.line), f"is in no object list (belongs in [{wanted}])", index)


# -- L4 --------------------------------------------------------------------------

def index_ranges(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for index, obj in od.objects.items():
        if index == 0 or 0x0260 <= index <= 0x0FFF:
            diags.add(LST011, Loc(od.source, obj.line), "is in a range CiA 301 reserves", index)
        elif index >= 0xC000:
            diags.add(LST012, Loc(od.source, obj.line), "is in the range 0xC000-0xFFFF CiA 301 reserves", index)


# This family's lint passes, in the order they run.
PASSES: tuple[LintPass, ...] = (list_counts, list_entries, unlisted_objects, index_ranges)
