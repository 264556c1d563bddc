"""Were the identity revision (0x1018sub3) and the file version raised for the changes found?

Changes of class (a) change the CANopen behaviour: CiA 301 wants the major revision (upper 16
bits of 0x1018sub3) raised. Changes of class (b) want the revision number raised. Both want a
higher FileVersion/FileRevision (an XDD has one fileVersion, which may be written "major.minor").
"""

from __future__ import annotations

import re

from ..model import ObjectDictionary, Value
from ..model.cia301 import IDENTITY
from .changes import BREAKING, STORED, Change, worst

REVISION = 3  # sub-index of 0x1018


def version_changes(old: ObjectDictionary, new: ObjectDictionary, changes: list[Change]) -> list[Change]:
    cls = worst(changes, (BREAKING, STORED))
    if cls is None:
        return []
    return [c for c in (_revision_change(old, new, cls), _file_change(old, new, cls)) if c is not None]


def versions(old: ObjectDictionary, new: ObjectDictionary) -> dict[str, str]:
    """The identity revision and file version of both files, as shown in reports ("?" when unknown)."""
    revisions = [_revision(od) for od in (old, new)]
    files = [file_version(od) for od in (old, new)]
    return {"revision": " -> ".join("?" if r is None else f"0x{r:08X}" for r in revisions),
            "file version": " -> ".join("?" if f is None else _shown(f) for f in files)}


def _revision_change(old: ObjectDictionary, new: ObjectDictionary, cls: str) -> Change | None:
    before, after = _revision(old), _revision(new)
    if before is None or after is None:
        return None
    sub = new.find(IDENTITY, REVISION)
    written = "parametervalue" if sub is not None and _number(sub.parameter_value) is not None else "defaultvalue"
    line = sub.line_of(written) if sub is not None else 0
    shown = f"revision number 0x{before:08X} -> 0x{after:08X}"
    if cls == BREAKING and after >> 16 <= before >> 16:
        return Change("DIF401", f"{shown}: raise the major revision (upper 16 bits) for changes of class (a)",
                      IDENTITY, REVISION, line, cls=cls)
    if after <= before:
        return Change("DIF401", f"{shown}: raise it for changes of class (b)", IDENTITY, REVISION, line, cls=cls)
    return None


def _revision(od: ObjectDictionary) -> int | None:
    sub = od.find(IDENTITY, REVISION)
    if sub is None:
        return None
    for value in (sub.parameter_value, sub.default):
        number = _number(value)
        if number is not None:
            return number
    return None


def _number(value: Value | None) -> int | None:
    if value is None or value.empty or value.error is not None or value.nodeid:
        return None
    return value.parsed if isinstance(value.parsed, int) else None


def _file_change(old: ObjectDictionary, new: ObjectDictionary, cls: str) -> Change | None:
    before, after = file_version(old), file_version(new)
    section = new.section("FileInfo")
    field = section.get("FileRevision") or section.get("FileVersion") if section is not None else None
    line = field.line if field is not None else (section.line if section is not None else 0)
    if before is None or after is None:
        what = "OLD" if before is None else "NEW"
        return Change("DIF402", f"{what} has no numeric FileVersion; cannot tell whether it was raised",
                      line=line, cls=cls)
    if _raised(before, after):
        return None
    return Change("DIF402", f"file version {_shown(before)} -> {_shown(after)}: raise FileVersion or "
                  "FileRevision when a description changes what a master or a stored parameter sees",
                  line=line, cls=cls)


Version = tuple[int, int | None]
# ASCII digits, at most nine: isdigit() is true for `²`, which int() refuses, and int() raises past
# 4300 digits.
_NUMBER = re.compile(r"^\s*([0-9]{1,9})(?:\.([0-9]{1,9}))?\s*$")
_REVISION = re.compile(r"^[0-9]{1,9}$")


def file_version(od: ObjectDictionary) -> Version | None:
    """(FileVersion, FileRevision); an XDD's fileVersion "2.1" reads as (2, 1), "2" as (2, None)."""
    section = od.section("FileInfo")
    if section is None:
        return None
    m = _NUMBER.match(section.text("FileVersion"))
    if m is None:
        return None
    revision = m.group(2)
    written = section.text("FileRevision").strip()
    if _REVISION.match(written):
        revision = written
    return int(m.group(1)), int(revision) if revision is not None else None


def _raised(before: Version, after: Version) -> bool:
    if after[0] != before[0]:
        return after[0] > before[0]
    return before[1] is not None and after[1] is not None and after[1] > before[1]


def _shown(version: Version) -> str:
    return f"{version[0]}" if version[1] is None else f"{version[0]}.{version[1]}"
