"""OBJ: object and sub-object entries (CiA 306 rule table rows O1-O13, O15)."""

from __future__ import annotations

from collections.abc import Iterator

from ..catalogue.objects import (
    OBJ001, OBJ002, OBJ003, OBJ004, OBJ005, OBJ006, OBJ007, OBJ008, OBJ009, OBJ010, OBJ011, OBJ012, OBJ013, OBJ014,
    OBJ015, OBJ016, OBJ017, OBJ018, OBJ019, OBJ020, OBJ021, OBJ022, OBJ023, OBJ024, OBJ025, OBJ026, OBJ027, OBJ028,
    OBJ029)
from ..catalogue.rule import Rule
from ..diagnostics import Diagnostics, Loc
from ..model import (ACCESS_TYPES, ARRAY, DEFSTRUCT, DEFTYPE, DOMAIN, RECORD, VAR, Field, Obj, ObjectDictionary, Sub,
                     Value)
from ..model.cia301 import ERROR_HISTORY, PDO_COUNT, RPDO_MAPPING, TPDO_MAPPING
from ..model.datatypes import BASIC_TYPES, DataType
from ..model.od import OBJECT_CODES
from . import LintOptions, lint_pass
from .common import addr, at, default_line, node_span, number, plain_int, value_in_force, value_line



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
# Objects whose sub0 is not "highest sub-index supported".
_SUB0_COUNTS = ((ERROR_HISTORY, ERROR_HISTORY), (RPDO_MAPPING, RPDO_MAPPING + PDO_COUNT - 1),
                (TPDO_MAPPING, TPDO_MAPPING + PDO_COUNT - 1))


# -- entries -------------------------------------------------------------------

def written_subs(obj: Obj) -> Iterator[Sub]:
    """Entries written as sections: a VAR's own, or an ARRAY/RECORD's sub-sections."""
    if obj.is_var:
        if 0 in obj.subs:
            yield obj.subs[0]
        return
    for sub in obj.subs.values():
        if not sub.compact:
            yield sub


def value_subs(obj: Obj) -> Iterator[Sub]:
    """Entries that carry a value: written ones, and a CompactSubObj template once."""
    yield from written_subs(obj)
    if not obj.is_var and obj.compact_sub_obj and 1 in obj.subs and obj.subs[1].compact:
        yield obj.subs[1]


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

@lint_pass
def parameter_names(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        if not obj.name.strip():
            diags.add(OBJ001, Loc(od.source, obj.line), "has no ParameterName", obj.index)
        if obj.is_var:
            continue
        # one report per object: generated files tend to miss every sub-object's name at once
        nameless = [sub for sub in written_subs(obj) if not sub.name.strip()]
        if nameless:
            elements = obj.object_code == ARRAY and all(sub.subindex > 0 for sub in nameless)
            more = f" (nor do {len(nameless) - 1} more of its sub-objects)" if len(nameless) > 1 else ""
            diags.add(OBJ027 if elements else OBJ001, Loc(od.source, nameless[0].line),
                      f"has no ParameterName{more}", obj.index, nameless[0].subindex)


@lint_pass
def object_types(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        if obj.object_code not in VALID_OBJECT_CODES:
            diags.add(OBJ002, Loc(od.source, obj.line_of("objecttype")),
                      f"ObjectType=0x{obj.object_code:X} is not a CiA 301 object code "
                      "(0x2, 0x5, 0x6, 0x7, 0x8, 0x9)", obj.index)
        if obj.is_var:
            continue
        for sub in written_subs(obj):
            if sub.object_type is not None and sub.object_type != VAR:
                diags.add(OBJ028, Loc(od.source, sub.line_of("objecttype")),
                          f"ObjectType=0x{sub.object_type:X} on a sub-object; sub-objects are VAR (0x7)",
                          obj.index, sub.subindex)


# -- O3, O7 --------------------------------------------------------------------

def _attribute_holders(obj: Obj) -> Iterator[tuple[Sub, int | None, int]]:
    """(entry, sub-index for messages, line) for every place DataType/AccessType is required."""
    if obj.is_var:
        if 0 in obj.subs:
            yield obj.subs[0], None, obj.line
        return
    if obj.compact_sub_obj and 1 in obj.subs and obj.subs[1].compact:
        yield obj.subs[1], None, obj.line
    for sub in written_subs(obj):
        yield sub, sub.subindex, sub.line


@lint_pass
def required_attributes(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        for sub, subindex, line in _attribute_holders(obj):
            loc = Loc(od.source, line)
            if sub.data_type is None and "datatype" not in sub.lines and obj.object_code != DOMAIN:
                diags.add(OBJ003, loc, "has no DataType", obj.index, subindex)
            if sub.access is None:
                diags.add(OBJ004, loc, "has no AccessType", obj.index, subindex)
            elif sub.access not in ACCESS_TYPES:
                diags.add(OBJ005, Loc(od.source, sub.line_of("accesstype")),
                          f"AccessType={sub.access} is not one of ro, wo, rw, rwr, rww, const",
                          obj.index, subindex)


@lint_pass
def container_keywords(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        if obj.object_code not in VALID_OBJECT_CODES:
            continue
        has_number = obj.sub_number is not None or "subnumber" in obj.lines
        has_compact = obj.compact_sub_obj is not None or "compactsubobj" in obj.lines
        if obj.object_code in CONTAINER_CODES:
            _container_shape(od, obj, has_number, has_compact, diags)
        elif has_number or has_compact:
            key = "subnumber" if has_number else "compactsubobj"
            name = "SubNumber" if has_number else "CompactSubObj"
            diags.add(OBJ007, Loc(od.source, obj.line_of(key)),
                      f"{name} on a {OBJECT_CODES.get(obj.object_code, 'VAR')} object", obj.index)


def _container_shape(od: ObjectDictionary, obj: Obj, has_number: bool, has_compact: bool,
                     diags: Diagnostics) -> None:
    kind = OBJECT_CODES[obj.object_code]
    if has_number == has_compact:
        what = "both SubNumber and CompactSubObj" if has_number else "neither SubNumber nor CompactSubObj"
        diags.add(OBJ006, Loc(od.source, obj.line), f"{kind} has {what}", obj.index)
    if has_compact:
        return
    stray = [obj.extra[k].key for k in HEADER_VALUE_KEYS if k in obj.extra]
    if stray:
        first = min(obj.extra[k.lower()].line for k in stray)
        diags.add(OBJ008, Loc(od.source, first),
                  f"{', '.join(stray)} on the {kind} header is ignored without CompactSubObj", obj.index)


# -- O4, O5 --------------------------------------------------------------------

@lint_pass
def sub_counts(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        if obj.object_code not in CONTAINER_CODES or obj.compact_sub_obj or obj.sub_number is None:
            continue
        present = sum(1 for sub in obj.subs.values() if not sub.compact)
        if present != obj.sub_number:
            diags.add(OBJ009, Loc(od.source, obj.sub_number_line or obj.line_of("subnumber")),
                      f"SubNumber={obj.sub_number} but {present} sub-object"
                      f"{'' if present == 1 else 's'} {'is' if present == 1 else 'are'} defined", obj.index)


@lint_pass
def sub0_entries(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        if obj.object_code not in (ARRAY, RECORD) or not obj.subs:
            continue
        sub0 = obj.subs.get(0)
        if sub0 is None:
            diags.add(OBJ010, Loc(od.source, obj.line), "has no sub0 (highest sub-index)", obj.index)
            continue
        if sub0.data_type is not None and sub0.data_type != 0x0005:
            dtype = BASIC_TYPES.get(sub0.data_type)
            name = f" ({dtype.name})" if dtype else ""
            diags.add(OBJ010, Loc(od.source, sub0.line_of("datatype")),
                      f"DataType=0x{sub0.data_type:04X}{name} is not UNSIGNED8", obj.index, 0)
        _sub0_value(od, obj, sub0, diags)


def _sub0_value(od: ObjectDictionary, obj: Obj, sub0: Sub, diags: Diagnostics) -> None:
    if any(lo <= obj.index <= hi for lo, hi in _SUB0_COUNTS):
        return
    default = sub0.default
    declared = plain_int(default)
    if default is None or declared is None:
        return
    highest = max(obj.subs)
    if highest == 0 or declared == highest:
        return
    if declared < highest and sub0.writable:
        return  # sub0 counts the valid entries, as 0x1003 does: vendors use that pattern for other objects
    diags.add(OBJ011, Loc(od.source, default_line(sub0)),
              f"DefaultValue={_show(default)} but the highest sub-index is {highest}", obj.index, 0)


# -- O9 ------------------------------------------------------------------------

@lint_pass
def data_types(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    defined = defined_types(od)
    for obj in od.objects.values():
        for sub, subindex, _line in _attribute_holders(obj):
            code = sub.data_type
            if code is None or code in BASIC_TYPES or code in defined:
                continue
            diags.add(OBJ012, Loc(od.source, sub.line_of("datatype")),
                      f"DataType=0x{code:04X} is neither a basic type nor defined in the file",
                      obj.index, subindex)


# -- O10, O11 ------------------------------------------------------------------

@lint_pass
def limits(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    span = node_span(od, options)
    for obj in od.objects.values():
        for sub in value_subs(obj):
            dtype = sub.dtype
            if dtype is None or (sub.low is None and sub.high is None):
                continue
            where_sub = addr(obj, sub)
            if not dtype.is_numeric:
                _non_numeric_limits(od, obj, sub, dtype, diags)
                continue
            for keyword, value in (("lowlimit", sub.low), ("highlimit", sub.high)):
                _type_range(od, obj.index, where_sub, sub, keyword, value, dtype, span, OBJ014, diags)
            _ordered(od, obj.index, where_sub, sub, span, diags)


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
                      f"{_LABEL[keyword]}={_show(value)}{node} is {side}", index, where_sub)
            return


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
              f"LowLimit={_show(sub.low)} is above HighLimit={_show(sub.high)}{node}", index, where_sub)


@lint_pass
def value_ranges(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    span = node_span(od, options)
    for obj in od.objects.values():
        for sub in value_subs(obj):
            dtype = sub.dtype
            if dtype is None or not dtype.is_numeric:
                continue
            for keyword, value in (("defaultvalue", sub.default), ("parametervalue", sub.parameter_value)):
                if value is None or number(value) is None:
                    continue
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
                  f"{_LABEL[keyword]}={_show(value)} is {side} {name}={_show(limit)}{node}",
                  obj.index, addr(obj, sub))
        return


# -- O8 ------------------------------------------------------------------------

@lint_pass
def pdo_mapping_flags(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        undirected = None
        for sub in value_subs(obj):
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

@lint_pass
def string_values(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        for sub in value_subs(obj):
            dtype = sub.dtype
            if dtype is None:
                continue
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


@lint_pass
def file_keywords(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        for sub in written_subs(obj):
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

@lint_pass
def obj_flags(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        holders: list[tuple[int | None, int | None, int]] = [(obj.obj_flags, None, obj.line_of("objflags"))]
        holders += [(s.obj_flags, addr(obj, s), s.line_of("objflags")) for s in written_subs(obj)]
        for flags, subindex, line in holders:
            if flags is not None and not 0 <= flags <= 3:
                diags.add(OBJ023, Loc(od.source, line),
                          f"ObjFlags=0x{flags:X} sets bits other than 0 and 1", obj.index, subindex)
                break


_DCF_ONLY = (("parametervalue", "ParameterValue"), ("denotation", "Denotation"), ("paramrefd", "ParamRefd"))


@lint_pass
def dcf_only_content(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    """Once per keyword and file: such files carry the keyword on every entry."""
    if od.format != "eds":
        return
    section = od.section("DeviceComissioning")
    if section is not None:
        diags.add(OBJ024, Loc(od.source, section.line), f"[{section.name}] in an EDS")
    found: dict[str, list[tuple[Obj, Sub]]] = {key: [] for key, _ in _DCF_ONLY}
    for obj in od.sorted_objects():
        for sub in written_subs(obj):
            for key in found:
                if key in sub.lines:
                    found[key].append((obj, sub))
    for key, name in _DCF_ONLY:
        if not found[key]:
            continue
        obj, sub = found[key][0]
        more = f" (and {len(found[key]) - 1} more entries)" if len(found[key]) > 1 else ""
        diags.add(OBJ024, Loc(od.source, sub.lines[key]), f"{name} in an EDS{more}",
                  obj.index, addr(obj, sub))


@lint_pass
def unknown_keywords(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    if od.format not in ("eds", "dcf"):
        return  # XDD extensions are attributes, checked against the schema by the XML reader
    for obj in od.objects.values():
        places: list[tuple[dict[str, Field], int | None]] = [(obj.extra, None)] if not obj.is_var else []
        places += [(sub.extra, addr(obj, sub)) for sub in written_subs(obj)]
        for extra, subindex in places:
            for key, fld in extra.items():
                if key not in KNOWN_KEYS:
                    diags.add(OBJ025, Loc(od.source, fld.line),
                              f"'{fld.key}' is not a CiA 306 keyword", obj.index, subindex)


# -- ARRAY element types -------------------------------------------------------

@lint_pass
def array_elements(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        if obj.object_code != ARRAY or obj.compact_sub_obj:
            continue
        first: Sub | None = None
        for sub in obj.sorted_subs():
            if sub.subindex == 0 or sub.data_type is None:
                continue
            if first is None:
                first = sub
            elif sub.data_type != first.data_type:
                diags.add(OBJ026, Loc(od.source, sub.line_of("datatype")),
                          f"DataType=0x{sub.data_type:04X} but sub{first.subindex} has "
                          f"0x{first.data_type:04X}; generated as a RECORD", obj.index, sub.subindex)
                break


# -- strings the runtime serves as C strings -----------------------------------

@lint_pass
def visible_strings(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj in od.objects.values():
        for sub in obj.subs.values():
            value, keyword = value_in_force(od, sub)
            at_nul = value.text.find(NUL) if value is not None and sub.data_type == VISIBLE_STRING else -1
            if value is not None and at_nul >= 0:
                diags.add(OBJ029, Loc(od.source, value_line(sub, value, keyword)),
                          f"value has a NUL at character {at_nul + 1}; the runtime would end the string there",
                          obj.index, addr(obj, sub))
