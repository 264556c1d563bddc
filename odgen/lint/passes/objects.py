"""OBJ: object and sub-object entries (CiA 306 rule table rows O1-O13, O15)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ...catalogue.objects import (
    OBJ001, OBJ002, OBJ003, OBJ004, OBJ005, OBJ006, OBJ007, OBJ008, OBJ009, OBJ010, OBJ011, OBJ012, OBJ013, OBJ014,
    OBJ015, OBJ016, OBJ017, OBJ018, OBJ019, OBJ020, OBJ021, OBJ022, OBJ023, OBJ024, OBJ025, OBJ026, OBJ027, OBJ028,
    OBJ029, OBJ030)
from ...catalogue.rule import Rule
from ...diagnostics import Diagnostics, Loc, Severity
from ...model import (ACCESS_TYPES, ARRAY, DEFSTRUCT, DEFTYPE, DOMAIN, RECORD, VAR, Field, Obj, ObjectDictionary, Sub,
                     Value)
from ...model.cia301 import ERROR_HISTORY, PDO_COUNT, RPDO_MAPPING, TPDO_MAPPING
from ...model.datatypes import BASIC_TYPES, DataType
from ...model.od import OBJECT_CODES
from .base import LintOptions, LintPass
from ...model.values import number, plain_int
from .common import addr, at, default_line, node_span, value_in_force, value_line



VISIBLE_STRING, NUL = 0x0009, chr(0)
VALID_OBJECT_CODES = (0x0, DOMAIN, DEFTYPE, DEFSTRUCT, VAR, ARRAY, RECORD)
CONTAINER_CODES = (DEFSTRUCT, ARRAY, RECORD)
# Keywords CiA 306 defines for object/sub-object sections (lower case), plus
# CANopenNode's `;StorageLocation` and CANopenEditor's `CountLabel`.
KNOWN_KEYS = frozenset((
    "parametername", "objecttype", "datatype", "accesstype", "defaultvalue", "lowlimit",
    "highlimit", "pdomapping", "objflags", "subnumber", "compactsubobj", "parametervalue",
    "denotation", "paramrefd", "uploadfile", "downloadfile", "storagelocation", "countlabel",
))
HEADER_VALUE_KEYS = ("datatype", "accesstype", "defaultvalue", "lowlimit", "highlimit", "pdomapping",
                     "parametervalue")


# -- entries -------------------------------------------------------------------

def written_subs(obj: Obj) -> list[Sub]:
    """Entries written as sections: a VAR's own, or an ARRAY/RECORD's sub-sections."""
    if obj.is_var:
        sub0 = obj.subs.get(0)
        return [sub0] if sub0 is not None else []
    return [sub for sub in obj.subs.values() if not sub.compact]


def template(obj: Obj) -> Sub | None:
    """The entry a CompactSubObj header describes (sub1, expanded), if there is one."""
    sub1 = obj.subs.get(1) if obj.compact_sub_obj and not obj.is_var else None
    return sub1 if sub1 is not None and sub1.compact else None


@dataclass(slots=True)
class Walk:
    """What the object checks share: the file, its findings, and what is computed once per file."""

    od: ObjectDictionary
    diags: Diagnostics
    span: tuple[int, int]  # the node-ids a $NODEID value must work for
    defined: set[int]  # data types the file defines
    dcf_only: dict[str, list[tuple[Obj, Sub]]]  # DCF keyword -> the EDS entries that have it


# Each question looks at one object: its entries written as sections (`written`), and those that carry a
# value (`valued`: the written ones and a CompactSubObj template). One walk serves them all, since a
# walk per rule over thousands of objects costs more than the questions themselves.
# OBJECT_QUESTIONS (at the end of this module) lists them in the order they are asked.
ObjectQuestion = Callable[[Walk, Obj, list[Sub], list[Sub]], None]


def object_entries(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    walk = Walk(od, diags, node_span(od, options), defined_types(od), {key: [] for key, _ in _DCF_ONLY})
    for obj in od.objects.values():
        written = written_subs(obj)
        tmpl = template(obj)
        valued = written if tmpl is None else [*written, tmpl]
        for question in OBJECT_QUESTIONS:
            question(walk, obj, written, valued)
    dcf_only_content(walk)


def defined_types(od: ObjectDictionary) -> set[int]:
    return {i for i, o in od.objects.items() if 0x0001 <= i <= 0x025F and o.object_code in (DEFTYPE, DEFSTRUCT)}


def _show(value: Value) -> str:
    """The value as written, with its reading when that is not obvious (0xFF as INTEGER8 is -1)."""
    text = value.text.strip()
    n = number(value)
    if isinstance(n, int) and n < 0 and not text.startswith("-") and not value.nodeid:
        return f"{text} ({n})"
    return text


# -- O1, O2 --------------------------------------------------------------------

def parameter_names(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    od, diags = walk.od, walk.diags
    if not obj.name.strip():
        diags.add(OBJ001, Loc(od.source, obj.line), "has no ParameterName", obj.index)
    if obj.is_var:
        return
    # one report per object: generated files tend to miss every sub-object's name at once
    if all(sub.name.strip() for sub in written):
        return
    nameless = [sub for sub in written if not sub.name.strip()]
    if nameless:
        elements = obj.object_code == ARRAY and all(sub.subindex > 0 for sub in nameless)
        more = f" (nor do {len(nameless) - 1} more of its sub-objects)" if len(nameless) > 1 else ""
        diags.add(OBJ027 if elements else OBJ001, Loc(od.source, nameless[0].line),
                  f"has no ParameterName{more}", obj.index, nameless[0].subindex)


def object_types(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    od, diags = walk.od, walk.diags
    if obj.object_code not in VALID_OBJECT_CODES:
        diags.add(OBJ002, Loc(od.source, obj.line_of("objecttype")),
                  f"ObjectType=0x{obj.object_code:X} is not a CiA 301 object code "
                  "(0x2, 0x5, 0x6, 0x7, 0x8, 0x9)", obj.index)
    if obj.is_var:
        return
    for sub in written:
        if sub.object_type is not None and sub.object_type != VAR:
            diags.add(OBJ028, Loc(od.source, sub.line_of("objecttype")),
                      f"ObjectType=0x{sub.object_type:X} on a sub-object; sub-objects are VAR (0x7)",
                      obj.index, sub.subindex)


# -- O3, O7, O9 ----------------------------------------------------------------

def required_attributes(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    """DataType and AccessType present (O3) and valid (O7), DataType known (O9), wherever they are required:
    a VAR's entry and a CompactSubObj template (located at the object), the sub-objects of the others."""
    if obj.is_var:
        for sub in written:
            _attributes(walk, obj, sub, None, obj.line)
        return
    tmpl = template(obj)
    if tmpl is not None:
        _attributes(walk, obj, tmpl, None, obj.line)
    for sub in written:
        _attributes(walk, obj, sub, sub.subindex, sub.line)


def _attributes(walk: Walk, obj: Obj, sub: Sub, subindex: int | None, line: int) -> None:
    code = sub.data_type
    if code is not None and sub.access in ACCESS_TYPES and (code in BASIC_TYPES or code in walk.defined):
        return  # the common case, decided here
    od, diags = walk.od, walk.diags
    if code is None and "datatype" not in sub.lines and obj.object_code != DOMAIN:
        diags.add(OBJ003, Loc(od.source, line), "has no DataType", obj.index, subindex)
    if sub.access is None:
        diags.add(OBJ004, Loc(od.source, line), "has no AccessType", obj.index, subindex)
    elif sub.access not in ACCESS_TYPES:
        diags.add(OBJ005, Loc(od.source, sub.line_of("accesstype")),
                  f"AccessType={sub.access} is not one of ro, wo, rw, rwr, rww, const",
                  obj.index, subindex)
    if code is not None and code not in BASIC_TYPES and code not in walk.defined:
        diags.add(OBJ012, Loc(od.source, sub.line_of("datatype")),
                  f"DataType=0x{code:04X} is neither a basic type nor defined in the file",
                  obj.index, subindex)


def container_keywords(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    if obj.object_code not in VALID_OBJECT_CODES:
        return
    has_number = obj.sub_number is not None or "subnumber" in obj.lines
    has_compact = obj.compact_sub_obj is not None or "compactsubobj" in obj.lines
    if obj.object_code in CONTAINER_CODES:
        _container_shape(walk.od, obj, has_number, has_compact, walk.diags)
    elif has_number or has_compact:
        key = "subnumber" if has_number else "compactsubobj"
        name = "SubNumber" if has_number else "CompactSubObj"
        walk.diags.add(OBJ007, Loc(walk.od.source, obj.line_of(key)),
                       f"{name} on a {OBJECT_CODES.get(obj.object_code, 'VAR')} object", obj.index)


def _container_shape(od: ObjectDictionary, obj: Obj, has_number: bool, has_compact: bool,
                     diags: Diagnostics) -> None:
    kind = OBJECT_CODES[obj.object_code]
    if has_number == has_compact:
        what = "both SubNumber and CompactSubObj" if has_number else "neither SubNumber nor CompactSubObj"
        # with neither keyword the sub-object sections present are the container, as every reader takes them
        diags.add(OBJ006, Loc(od.source, obj.line), f"{kind} has {what}", obj.index,
                  blocks=has_number or not any(not s.compact for s in obj.subs.values()))
    if has_compact or not obj.extra:
        return
    stray = [obj.extra[k].key for k in HEADER_VALUE_KEYS if k in obj.extra]
    if stray:
        first = min(obj.extra[k.lower()].line for k in stray)
        diags.add(OBJ008, Loc(od.source, first),
                  f"{', '.join(stray)} on the {kind} header is ignored without CompactSubObj", obj.index)


# -- O4, O5 --------------------------------------------------------------------

def sub_counts(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    if obj.object_code not in CONTAINER_CODES or obj.compact_sub_obj or obj.sub_number is None:
        return
    present = len(written)  # a container's sub-objects that are not expanded from CompactSubObj
    if present != obj.sub_number:
        walk.diags.add(OBJ009, Loc(walk.od.source, obj.sub_number_line or obj.line_of("subnumber")),
                       f"SubNumber={obj.sub_number} but {present} sub-object"
                       f"{'' if present == 1 else 's'} {'is' if present == 1 else 'are'} defined", obj.index)


def sub0_entries(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    if obj.object_code not in (ARRAY, RECORD) or not obj.subs:
        return
    od, diags = walk.od, walk.diags
    sub0 = obj.subs.get(0)
    if sub0 is None:
        diags.add(OBJ010, Loc(od.source, obj.line), "has no sub0 (highest sub-index)", obj.index, blocks=False)
        return
    if sub0.data_type is not None and sub0.data_type != 0x0005:
        dtype = BASIC_TYPES.get(sub0.data_type)
        name = f" ({dtype.name})" if dtype else ""
        # a read-only count in a wider unsigned type the C serves as written (an upload states its size);
        # a writable one refuses a master's one-byte write, and a count of another kind is no count
        count = dtype is not None and dtype.kind == "uint" and not sub0.writable
        diags.add(OBJ010, Loc(od.source, sub0.line_of("datatype")),
                  f"DataType=0x{sub0.data_type:04X}{name} is not UNSIGNED8", obj.index, 0, blocks=not count)
    _sub0_value(od, obj, sub0, diags)


def _sub0_value(od: ObjectDictionary, obj: Obj, sub0: Sub, diags: Diagnostics) -> None:
    index = obj.index
    if index == ERROR_HISTORY or RPDO_MAPPING <= index < RPDO_MAPPING + PDO_COUNT \
            or TPDO_MAPPING <= index < TPDO_MAPPING + PDO_COUNT:
        return  # sub0 is not "highest sub-index supported" here
    value, keyword = value_in_force(od, sub0)  # a DCF's ParameterValue is what the device starts with
    declared = plain_int(value)
    if value is None or declared is None:
        return
    highest = max(obj.subs)
    if highest == 0 or declared == highest:
        return
    if declared < highest and sub0.writable:
        return  # sub0 counts the valid entries, as 0x1003 does: vendors use that pattern for other objects
    diags.add(OBJ011, Loc(od.source, value_line(sub0, value, keyword)),
              f"{_LABEL[keyword]}={_show(value)} but the highest sub-index is {highest}", obj.index, 0)


# -- O10, O11 ------------------------------------------------------------------

def limits(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    od, diags = walk.od, walk.diags
    for sub in valued:
        if sub.low is None and sub.high is None:
            continue
        dtype = sub.dtype
        if dtype is None:
            continue
        where_sub = addr(obj, sub)
        if not dtype.is_numeric:
            _non_numeric_limits(od, obj, sub, dtype, diags)
            continue
        for keyword, value in (("lowlimit", sub.low), ("highlimit", sub.high)):
            _type_range(od, obj.index, where_sub, sub, keyword, value, dtype, walk.span, OBJ014, diags)
        _ordered(od, obj.index, where_sub, sub, walk.span, diags)


def _non_numeric_limits(od: ObjectDictionary, obj: Obj, sub: Sub, dtype: DataType, diags: Diagnostics) -> None:
    written = [v for v in (sub.low, sub.high) if v is not None and not v.empty]
    if written:
        diags.add(OBJ013, Loc(od.source, written[0].line or sub.line),
                  f"LowLimit/HighLimit on a {dtype.name} entry", obj.index, addr(obj, sub))


_LABEL = {"lowlimit": "LowLimit", "highlimit": "HighLimit", "defaultvalue": "DefaultValue",
          "parametervalue": "ParameterValue"}


def _type_range(od: ObjectDictionary, index: int, where_sub: int | None, sub: Sub, keyword: str,
                value: Value | None, dtype: DataType, span: tuple[int, int], rule: Rule,
                diags: Diagnostics) -> None:
    bounds = _bounds(dtype)
    if value is None or bounds is None or number(value) is None:
        return
    low, high = bounds
    for node_id in span if value.nodeid else span[:1]:
        v = at(value, node_id)
        if v is None or v != v:  # NaN has no range
            return
        if v < low or v > high:
            side = f"below the {dtype.name} minimum {_num(low)}" if v < low else \
                f"above the {dtype.name} maximum {_num(high)}"
            node = f" (= {_num(v)} for node-id {node_id})" if value.nodeid else ""
            diags.add(rule, Loc(od.source, value_line(sub, value, keyword)),
                      f"{_LABEL[keyword]}={_show(value)}{node} is {side}", index, where_sub,
                      blocks=not (rule is OBJ014 and _restricts_nothing(keyword, v, dtype)))
            return


def _restricts_nothing(keyword: str, v: int | float, dtype: DataType) -> bool:
    """A limit beyond the end of the type it bounds (HighLimit above the maximum, LowLimit below the
    minimum) that the runtime still compares as the number it is: odg.c compares the limits of an
    integer type as 64-bit numbers, unsigned or signed as the type is. The C then restricts nothing
    there, as the file means. (REAL32 limits beyond the float range odg_verify refuses.)"""
    if not isinstance(v, int) or dtype.min is None or dtype.max is None or dtype.kind == "real":
        return False
    signed = dtype.min < 0
    fits = -(1 << 63) <= v < (1 << 63) if signed else 0 <= v < (1 << 64)
    return fits and (v > dtype.max if keyword == "highlimit" else v < dtype.min)


_TEXT_TYPES = frozenset(t.code for t in BASIC_TYPES.values() if t.kind in ("vstring", "domain"))
_BOUNDS = {t.code: (t.min, t.max) for t in BASIC_TYPES.values() if t.min is not None and t.max is not None}


def _bounds(dtype: DataType) -> tuple[int | float, int | float] | None:
    return _BOUNDS.get(dtype.code)


def _num(v: int | float) -> str:
    if isinstance(v, float):
        return f"{v:g}"
    return str(v)


def _below(a: Value, b: Value, span: tuple[int, int]) -> int | None:
    """A node-id where a < b, or None. Both are linear in the node-id: the ends suffice."""
    for node_id in span if a.nodeid or b.nodeid else span[:1]:
        va, vb = at(a, node_id), at(b, node_id)
        if va is not None and vb is not None and va < vb:
            return node_id
    return None


def _ordered(od: ObjectDictionary, index: int, where_sub: int | None, sub: Sub, span: tuple[int, int],
             diags: Diagnostics) -> None:
    if sub.low is None or sub.high is None:
        return
    node_id = _below(sub.high, sub.low, span)
    if node_id is None:
        return
    node = f" for node-id {node_id}" if sub.low.nodeid or sub.high.nodeid else ""
    diags.add(OBJ015, Loc(od.source, value_line(sub, sub.low, "lowlimit")),
              f"LowLimit={_show(sub.low)} is above HighLimit={_show(sub.high)}{node}{_unchecked(sub)}", index,
              where_sub, blocks=sub.writable, severity=_milder(sub))


def _milder(sub: Sub) -> Severity | None:
    return None if sub.writable else Severity.WARNING


def _unchecked(sub: Sub) -> str:
    """What the C does with the limits of a read-only entry that could not hold (model.capacity.served_limits)."""
    return "" if sub.writable else f"; {sub.access} entry: no write is checked, the C leaves the limits out"




def value_ranges(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    for sub in valued:
        bounds = _BOUNDS.get(sub.data_type) if sub.data_type is not None else None  # numeric types have bounds
        if bounds is None:
            continue
        no_limits = sub.low is None and sub.high is None
        for keyword, value in (("defaultvalue", sub.default), ("parametervalue", sub.parameter_value)):
            if value is None:
                continue
            n = value.parsed
            if no_limits and (type(n) is int or type(n) is float) and not value.error and not value.nodeid \
                    and bounds[0] <= n <= bounds[1]:  # type(): a bool is not a number here
                continue  # the common case, decided here: a number in range, and no limits to compare with
            if number(value) is not None:
                _value_range(walk, obj, sub, keyword, value)


def _value_range(walk: Walk, obj: Obj, sub: Sub, keyword: str, value: Value) -> None:
    od, diags, span, dtype = walk.od, walk.diags, walk.span, sub.dtype
    if dtype is None:
        return
    before = len(diags)
    _type_range(od, obj.index, addr(obj, sub), sub, keyword, value, dtype, span, OBJ016, diags)
    if len(diags) == before:
        _within_limits(od, obj, sub, keyword, value, span, diags)


def _within_limits(od: ObjectDictionary, obj: Obj, sub: Sub, keyword: str, value: Value,
                   span: tuple[int, int], diags: Diagnostics) -> None:
    for limit, below in ((sub.low, True), (sub.high, False)):
        if limit is None or number(limit) is None:
            continue
        node_id = _below(value, limit, span) if below else _below(limit, value, span)
        if node_id is None:
            continue
        name = "LowLimit" if below else "HighLimit"
        node = f" for node-id {node_id}" if value.nodeid or limit.nodeid else ""
        side = "below" if below else "above"
        diags.add(OBJ017, Loc(od.source, value_line(sub, value, keyword)),
                  f"{_LABEL[keyword]}={_show(value)} is {side} {name}={_show(limit)}{node}{_unchecked(sub)}",
                  obj.index, addr(obj, sub), blocks=sub.writable, severity=_milder(sub))
        return


# -- O8 ------------------------------------------------------------------------

def pdo_mapping_flags(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    od, diags = walk.od, walk.diags
    undirected = None
    for sub in valued:
        if not sub.pdo_mapping:
            continue
        if sub.access == "rw" and undirected is None:
            undirected = sub
        dtype = sub.dtype
        if dtype is not None and dtype.kind == "domain":
            diags.add(OBJ019, Loc(od.source, sub.line_of("pdomapping")),
                      "is a DOMAIN but has PDOMapping=1", obj.index, addr(obj, sub))
    if undirected is not None:
        diags.add(OBJ018, Loc(od.source, undirected.line_of("accesstype")),
                  "AccessType=rw with PDOMapping=1: write rwr (TPDO) or rww (RPDO)",
                  obj.index, addr(obj, undirected))


# -- O12 -----------------------------------------------------------------------

def string_values(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    od, diags = walk.od, walk.diags
    for sub in valued:
        if sub.data_type not in _TEXT_TYPES:
            continue
        dtype = BASIC_TYPES[sub.data_type]
        if dtype.kind == "vstring":
            _visible(od, obj, sub, diags)
        elif dtype.kind == "domain" and sub.default is not None and sub.default.text.strip() not in ("", "0"):
            diags.add(OBJ021, Loc(od.source, default_line(sub)),
                      "DOMAIN has a DefaultValue", obj.index, addr(obj, sub))


def _visible(od: ObjectDictionary, obj: Obj, sub: Sub, diags: Diagnostics) -> None:
    for keyword, value in (("defaultvalue", sub.default), ("parametervalue", sub.parameter_value)):
        if value is None:
            continue
        bad = next((c for c in value.text if not " " <= c <= "~" and c != NUL), None)  # NUL: OBJ029
        if bad is not None:
            diags.add(OBJ020, Loc(od.source, value_line(sub, value, keyword)),
                      f"{_LABEL[keyword]} contains {bad!r} (U+{ord(bad):04X}), not printable ASCII",
                      obj.index, addr(obj, sub))


def file_keywords(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    od, diags = walk.od, walk.diags
    for sub in written:
        if sub.upload_file is None and sub.download_file is None:
            continue
        if sub.access is None or sub.access not in ACCESS_TYPES:
            continue
        if sub.upload_file is not None and sub.access not in ("ro", "const"):
            diags.add(OBJ022, Loc(od.source, sub.line_of("uploadfile")),
                      f"UploadFile with AccessType={sub.access}; an uploaded entry is ro or const",
                      obj.index, addr(obj, sub))
        if sub.download_file is not None and sub.access != "wo":
            diags.add(OBJ022, Loc(od.source, sub.line_of("downloadfile")),
                      f"DownloadFile with AccessType={sub.access}; a downloaded entry is wo",
                      obj.index, addr(obj, sub))


# -- O13, O15, unknown keys ----------------------------------------------------

def obj_flags(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    """At most once per object: the header's ObjFlags, else the first entry's."""
    flags = obj.obj_flags
    if flags is not None and not 0 <= flags <= 3:
        _bad_flags(walk, obj, flags, None, obj.line_of("objflags"))
        return
    for sub in written:
        flags = sub.obj_flags
        if flags is not None and not 0 <= flags <= 3:
            _bad_flags(walk, obj, flags, addr(obj, sub), sub.line_of("objflags"))
            return


def _bad_flags(walk: Walk, obj: Obj, flags: int, subindex: int | None, line: int) -> None:
    walk.diags.add(OBJ023, Loc(walk.od.source, line), f"ObjFlags=0x{flags:X} sets bits other than 0 and 1",
                   obj.index, subindex)


_DCF_ONLY = (("parametervalue", "ParameterValue"), ("denotation", "Denotation"), ("paramrefd", "ParamRefd"))


def dcf_only_keywords(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    """The entries of an EDS with DCF keywords, reported by dcf_only_content once the walk is done."""
    if walk.od.format != "eds":
        return
    for sub in written:
        lines = sub.lines
        if "parametervalue" not in lines and "denotation" not in lines and "paramrefd" not in lines:
            continue
        for key, found in walk.dcf_only.items():
            if key in lines:
                found.append((obj, sub))


def dcf_only_content(walk: Walk) -> None:
    """Once per keyword and file: such files carry the keyword on every entry."""
    od, diags, found = walk.od, walk.diags, walk.dcf_only
    if od.format != "eds":
        return
    section = od.section("DeviceComissioning")
    if section is not None:
        diags.add(OBJ024, Loc(od.source, section.line), f"[{section.name}] in an EDS")
    for key, name in _DCF_ONLY:
        if not found[key]:
            continue
        obj, sub = min(found[key], key=lambda entry: entry[0].index)  # the first in index order
        more = f" (and {len(found[key]) - 1} more entries)" if len(found[key]) > 1 else ""
        diags.add(OBJ024, Loc(od.source, sub.lines[key]), f"{name} in an EDS{more}",
                  obj.index, addr(obj, sub))


def unknown_keywords(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    if walk.od.format not in ("eds", "dcf"):
        return  # XDD extensions are attributes, checked against the schema by the XML reader
    if obj.extra and not obj.is_var:
        _unknown_keys(walk, obj, obj.extra, None)
    for sub in written:
        if sub.extra:
            _unknown_keys(walk, obj, sub.extra, addr(obj, sub))


def _unknown_keys(walk: Walk, obj: Obj, extra: dict[str, Field], subindex: int | None) -> None:
    for key, fld in extra.items():
        if key not in KNOWN_KEYS:
            walk.diags.add(OBJ025, Loc(walk.od.source, fld.line),
                           f"'{fld.key}' is not a CiA 306 keyword", obj.index, subindex)


# -- ARRAY element types -------------------------------------------------------

def array_elements(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    if obj.object_code != ARRAY or obj.compact_sub_obj:
        return
    first: Sub | None = None
    for sub in obj.sorted_subs():
        if sub.subindex == 0 or sub.data_type is None:
            continue
        if first is None:
            first = sub
        elif sub.data_type != first.data_type:
            walk.diags.add(OBJ026, Loc(walk.od.source, sub.line_of("datatype")),
                           f"DataType=0x{sub.data_type:04X} but sub{first.subindex} has "
                           f"0x{first.data_type:04X}; generated as a RECORD", obj.index, sub.subindex)
            return


# -- strings the runtime serves as C strings -----------------------------------

def const_nodeid_values(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    od = walk.od
    for sub in valued:
        value, keyword = value_in_force(od, sub)
        if sub.access == "const" and value is not None and value.nodeid:
            walk.diags.add(OBJ030, Loc(od.source, sub.line_of("accesstype")),
                           f"is const but its value {value.text.strip()} is relative to the node-id",
                           obj.index, addr(obj, sub))


def visible_strings(walk: Walk, obj: Obj, written: list[Sub], valued: list[Sub]) -> None:
    od = walk.od
    for sub in obj.subs.values():
        if sub.data_type != VISIBLE_STRING:
            continue
        value, keyword = value_in_force(od, sub)
        at_nul = value.text.find(NUL) if value is not None else -1
        if value is not None and at_nul >= 0:
            walk.diags.add(OBJ029, Loc(od.source, value_line(sub, value, keyword)),
                           f"value has a NUL at character {at_nul + 1}; the runtime would end the string there",
                           obj.index, addr(obj, sub))


OBJECT_QUESTIONS: tuple[ObjectQuestion, ...] = (
    parameter_names,
    object_types,
    required_attributes,
    container_keywords,
    sub_counts,
    sub0_entries,
    limits,
    value_ranges,
    pdo_mapping_flags,
    string_values,
    file_keywords,
    obj_flags,
    dcf_only_keywords,
    unknown_keywords,
    array_elements,
    visible_strings,
    const_nodeid_values,
)


# This family's lint passes, in the order they run.
PASSES: tuple[LintPass, ...] = (object_entries,)
