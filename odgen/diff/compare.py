"""Classes (a) and (c): what changed between two models, object by object and sub-entry by sub-entry.

Only what every format can say is compared: data type, object code, access, PDO mapping,
limits, defaults, names, and ObjFlags; Denotation and ParameterValue only between two configured
files (DCF/XDC). SubNumber, CompactSubObj, storage locations and CANopenEditor's extras are how a
file is written, not what a master sees.
"""

from __future__ import annotations

from collections.abc import Callable

from ..model import Obj, ObjectDictionary, Sub, Value
from ..model.capacity import string_capacity, string_default
from ..model.cia301 import (
    EMCY_COB_ID, SYNC_COB_ID, TIME_COB_ID, is_pdo_mapping, is_sdo_parameter, pdo_communication)
from ..model.od import OBJECT_CODES
from .changes import Change

Number = int | float
REVISION = (0x1018, 3)  # its change is judged by version.py, not reported as a default change


def object_changes(old: ObjectDictionary, new: ObjectDictionary, stored: set[tuple[int, int]]) -> list[Change]:
    """`stored`: the (index, sub) keys that are persistent in NEW (a default change there is class b)."""
    out: list[Change] = []
    for index in sorted(set(old.objects) | set(new.objects)):
        a, b = old.objects.get(index), new.objects.get(index)
        if b is None:
            out.append(Change("DIF101", f"'{a.name}' removed" if a else "removed", index, old_line=a.line if a else 0))
        elif a is None:
            out.append(Change("DIF301", f"'{b.name}' added", index, line=b.line))
        else:
            out += _object(a, b, old.is_config and new.is_config, stored)
    return out


def _object(a: Obj, b: Obj, configured: bool, stored: set[tuple[int, int]]) -> list[Change]:
    out: list[Change] = []
    if a.name != b.name and not b.is_var:
        out.append(Change("DIF303", f"name '{a.name}' -> '{b.name}'", b.index, line=b.line))
    if a.object_code != b.object_code:
        codes = f"{OBJECT_CODES.get(a.object_code, a.object_code)} -> {OBJECT_CODES.get(b.object_code, b.object_code)}"
        return out + [Change("DIF104", f"object code {codes}", b.index, line=b.line_of("objecttype"))]
    if a.obj_flags != b.obj_flags:
        out.append(Change("DIF308", f"ObjFlags {a.obj_flags} -> {b.obj_flags}", b.index, line=b.line_of("objflags")))
    for subindex in sorted(set(a.subs) | set(b.subs)):
        sa, sb = a.subs.get(subindex), b.subs.get(subindex)
        sub = None if b.is_var else subindex
        if sb is None:
            out.append(Change("DIF102", f"'{sa.name}' removed" if sa else "removed", b.index, sub,
                              line=b.line, old_line=sa.line if sa else 0))
        elif sa is None:
            out.append(Change("DIF302", f"'{sb.name}' added", b.index, sub, line=sb.line))
        else:
            out += _sub(b.index, sub, sa, sb, configured, (b.index, subindex) in stored)
    return out


def _sub(index: int, sub: int | None, a: Sub, b: Sub, configured: bool, stored: bool) -> list[Change]:
    def change(kind: str, message: str, keyword: str) -> Change:
        return Change(kind, message, index, sub, line=b.line_of(keyword))

    out: list[Change] = []
    if a.name != b.name:
        out.append(change("DIF303", f"name '{a.name}' -> '{b.name}'", "parametername"))
    if a.data_type != b.data_type:
        return out + [change("DIF103", f"data type {_type_name(a)} -> {_type_name(b)}", "datatype")]
    out += _access(a, b, change)
    if a.pdo_mapping != b.pdo_mapping:
        kind = "DIF106" if a.pdo_mapping else "DIF305"
        out.append(change(kind, "no longer PDO-mappable" if a.pdo_mapping else "now PDO-mappable", "pdomapping"))
    limits = _limits(a, b, change)
    out += limits
    if _value(a.default) != _value(b.default) and (index, b.subindex) != REVISION:
        narrowed = any(c.kind == "DIF108" for c in limits)
        out.append(_default_change(index, b.subindex, stored, change, f"{_shown(a.default)} -> {_shown(b.default)}",
                                   narrowed))
        out += _capacity(a, b, change)
    if configured and _value(a.parameter_value) != _value(b.parameter_value):
        shown = f"{_shown(a.parameter_value)} -> {_shown(b.parameter_value)}"
        out.append(change("DIF308", f"ParameterValue {shown}", "parametervalue"))
    if configured and (a.denotation or "") != (b.denotation or ""):
        out.append(change("DIF308", f"Denotation '{a.denotation or ''}' -> '{b.denotation or ''}'", "denotation"))
    if a.obj_flags != b.obj_flags:
        out.append(change("DIF308", f"ObjFlags {a.obj_flags} -> {b.obj_flags}", "objflags"))
    return out


def _default_change(index: int, subindex: int, stored: bool, change: Callable[[str, str, str], Change],
                    shown: str, narrowed: bool = False) -> Change:
    if communication_default(index, subindex):
        return change("DIF107", f"default {shown}", "defaultvalue")
    if stored:
        keeps = ("a device that stored a value inside the new limits keeps it; one outside them gets the new "
                 "default at boot (a loss, reported)") if narrowed else "a device that stored a value keeps it"
        return change("DIF206", f"default {shown}; {keeps}", "defaultvalue")
    return change("DIF307", f"default {shown}", "defaultvalue")


def _capacity(a: Sub, b: Sub, change: Callable[[str, str, str], Change]) -> list[Change]:
    """A string whose capacity follows its default (no capacity in an options file) and shrinks."""
    dtype = b.dtype
    if dtype is None or dtype.kind not in ("vstring", "ostring", "ustring") or a.dtype != dtype:
        return []
    before = string_capacity(dtype, string_default(dtype, a.default), None)
    after = string_capacity(dtype, string_default(dtype, b.default), None)
    if after >= before:
        return []
    return [change("DIF109", f"capacity {before} -> {after} bytes (it follows the default's length): a write "
                   f"of up to {before} bytes is refused unless the options file sets capacity", "defaultvalue")]


def _access(a: Sub, b: Sub, change: Callable[[str, str, str], Change]) -> list[Change]:
    if a.access == b.access:
        return []
    narrowed = (a.readable and not b.readable) or (a.writable and not b.writable)
    return [change("DIF105" if narrowed else "DIF304", f"access {a.access} -> {b.access}", "accesstype")]


def _limits(a: Sub, b: Sub, change: Callable[[str, str, str], Change]) -> list[Change]:
    dtype = b.dtype
    if dtype is None or not dtype.is_numeric:
        return []
    out = []
    for name, key, fallback, tighter in (("low", "LowLimit", dtype.min, lambda x, y: y > x),
                                         ("high", "HighLimit", dtype.max, lambda x, y: y < x)):
        before, after = _bound(getattr(a, name), fallback), _bound(getattr(b, name), fallback)
        if before == after:
            continue
        label = f"{key} {_shown(getattr(a, name))} -> {_shown(getattr(b, name))}"
        comparable = isinstance(before, (int, float)) and isinstance(after, (int, float))
        narrowed = not comparable or tighter(before, after)
        out.append(change("DIF108" if narrowed else "DIF306", label, key.lower()))
    return out


# CiA 301 communication entries whose defaults a master's configuration builds on.
def communication_default(index: int, sub: int) -> bool:
    if index in (SYNC_COB_ID, TIME_COB_ID, EMCY_COB_ID):
        return True
    if is_sdo_parameter(index) or pdo_communication(index):  # COB-IDs; a PDO's transmission type
        return sub in (1, 2)
    return is_pdo_mapping(index)


def _value(value: Value | None) -> object:
    """A value as compared: empty is none; strings without trailing blanks, which INI cannot keep."""
    if value is None or value.empty:
        return None
    if value.error is not None:
        return value.text.strip()
    parsed = value.parsed.rstrip() if isinstance(value.parsed, str) else value.parsed
    return parsed, value.nodeid


def _bound(value: Value | None, fallback: Number | None) -> object:
    if value is None or value.empty:
        return fallback
    if value.error is None and not value.nodeid and isinstance(value.parsed, (int, float)):
        return value.parsed
    return value.text.strip()


def _shown(value: Value | None) -> str:
    return "(none)" if value is None or value.empty else value.text.strip()


def _type_name(sub: Sub) -> str:
    if sub.dtype is not None:
        return sub.dtype.name
    return "(none)" if sub.data_type is None else f"0x{sub.data_type:04X}"
