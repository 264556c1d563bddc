"""The header sections of a description (FileInfo, DeviceInfo, DummyUsage ...), read as numbers."""

from __future__ import annotations

from .od import Field, ObjectDictionary
from .values import parse_int_literal


def header_field(od: ObjectDictionary, section_name: str, key: str) -> Field | None:
    """A key of a header section; None when the section or the key is absent."""
    section = od.section(section_name)
    return section.get(key) if section is not None else None


def header_int(fld: Field | None) -> int | None:
    """A header key's value as an integer; None when absent, empty or not a number."""
    if fld is None:
        return None
    value, _ = parse_int_literal(fld.text)
    return value
