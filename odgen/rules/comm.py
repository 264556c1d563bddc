"""COM: CiA 301 communication-profile semantics checked against the description.

CiA 306 rule table rows C6-C8, plus what CiA 301 fixes for the communication
objects every master relies on: mandatory objects, data types, identity,
error control, COB-IDs and PDO parameters.
"""

from __future__ import annotations

from collections.abc import Iterator

from ..catalogue.comm import (
    COM001, COM002, COM003, COM004, COM005, COM006, COM007, COM008, COM009, COM010, COM011, COM012, COM013, COM014,
    COM015, COM020, COM021)
from ..diagnostics import Diagnostics, Loc
from ..model import Obj, ObjectDictionary, Sub, Value
from ..model.datatypes import BASIC_TYPES
from . import LintOptions, check
from .common import (addr, at, default_line, header_field, header_int, node_span, number, plain_int, value_in_force,
                     value_line)



U8, U16, U32, VSTR = 0x0005, 0x0006, 0x0007, 0x0009
MANDATORY = {0x1000: "device type", 0x1001: "error register", 0x1018: "identity"}
# Single-value communication objects and their data type.
VAR_TYPES = {0x1000: U32, 0x1001: U8, 0x1002: U32, 0x1005: U32, 0x1006: U32, 0x1007: U32,
             0x1008: VSTR, 0x1009: VSTR, 0x100A: VSTR, 0x100C: U16, 0x100D: U8, 0x1012: U32,
             0x1013: U32, 0x1014: U32, 0x1015: U16, 0x1017: U16, 0x1019: U8}
# Records/arrays: sub-index -> type (key 0 = "every sub-index from 1").
ARRAY_TYPES = {0x1003: {0: U32}, 0x1010: {0: U32}, 0x1011: {0: U32}, 0x1016: {0: U32},
               0x1018: {1: U32, 2: U32, 3: U32, 4: U32}, 0x1029: {0: U8}}
PDO_COMM_TYPES = {1: U32, 2: U8, 3: U16, 4: U8, 5: U16, 6: U8}
SDO_TYPES = {1: U32, 2: U32, 3: U8}
READ_ONLY = (0x1000, 0x1001, 0x1008, 0x1009, 0x100A, 0x1018)
RESTRICTED = ((0x000, 0x07F), (0x101, 0x180), (0x581, 0x5FF), (0x601, 0x67F), (0x6E0, 0x6FF),
              (0x701, 0x7FF))
RPDO, TPDO, SDO_SERVER, SDO_CLIENT = 0x1400, 0x1800, 0x1200, 0x1280


def _in(index: int, base: int, size: int = 0x200) -> bool:
    return base <= index < base + size


def _is_sdo(index: int) -> bool:
    """An SDO server or client parameter record."""
    return _in(index, SDO_SERVER, 0x80) or _in(index, SDO_CLIENT, 0x80)


def _pdo_comm(index: int) -> str | None:
    if _in(index, RPDO):
        return "RPDO"
    if _in(index, TPDO):
        return "TPDO"
    return None


# -- mandatory objects, data types, access -----------------------------------------

@check
def mandatory_objects(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for index, name in MANDATORY.items():
        if index not in od.objects:
            diags.add(COM001, Loc(od.source), f"mandatory object 0x{index:04X} ({name}) is missing")


def _expected_type(obj: Obj, sub: Sub) -> int | None:
    index = obj.index
    if obj.is_var:
        return VAR_TYPES.get(index)
    if sub.subindex == 0:
        return None  # sub0 is UNSIGNED8 everywhere: OBJ010
    if _pdo_comm(index) is not None:
        return PDO_COMM_TYPES.get(sub.subindex)
    if _in(index, 0x1600) or _in(index, 0x1A00):
        return U32 if sub.subindex <= 0x40 else None
    if _is_sdo(index):
        return SDO_TYPES.get(sub.subindex)
    table = ARRAY_TYPES.get(index)
    if table is None:
        return None
    return table.get(sub.subindex, table.get(0))


@check
def comm_data_types(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for index, obj in od.objects.items():
        if not 0x1000 <= index <= 0x1BFF:
            continue
        for sub in obj.subs.values():
            expected = _expected_type(obj, sub)
            if expected is None or sub.data_type is None or sub.data_type == expected:
                continue
            if sub.compact and sub.subindex > 1:
                continue  # a CompactSubObj template is reported once, at sub1
            got = BASIC_TYPES.get(sub.data_type)
            diags.add(COM002, Loc(od.source, sub.line_of("datatype")),
                      f"DataType=0x{sub.data_type:04X}{f' ({got.name})' if got else ''}; "
                      f"CiA 301 defines {BASIC_TYPES[expected].name}", index, addr(obj, sub))


@check
def read_only_identity(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for index in READ_ONLY:
        obj = od.objects.get(index)
        if obj is None:
            continue
        for sub in obj.subs.values():
            if sub.writable and not sub.compact:
                diags.add(COM003, Loc(od.source, sub.line_of("accesstype")),
                          f"AccessType={sub.access}; CiA 301 defines it read-only", index, addr(obj, sub))


# -- C6: COB-IDs -------------------------------------------------------------------

def _predefined(index: int, subindex: int) -> tuple[int, str] | None:
    """(base CAN-ID, name) of an entry the predefined connection set fixes."""
    if _in(index, RPDO, 4) and subindex == 1:
        return 0x200 + 0x100 * (index - RPDO), f"RPDO{index - RPDO + 1}"
    if _in(index, TPDO, 4) and subindex == 1:
        return 0x180 + 0x100 * (index - TPDO), f"TPDO{index - TPDO + 1}"
    if index == 0x1014 and subindex == 0:
        return 0x80, "EMCY"
    return None


def _entry(obj: Obj | None, subindex: int) -> Sub | None:
    """Sub-index 0 of a single-value object, or a sub-index 1.. of an ARRAY/RECORD; else None."""
    if obj is None or obj.is_var != (subindex == 0):
        return None
    return obj.subs.get(subindex)


def _cob_entries(od: ObjectDictionary) -> Iterator[tuple[Obj, Sub, tuple[int, str]]]:
    for index in [0x1014, *range(RPDO, RPDO + 4), *range(TPDO, TPDO + 4)]:  # 0x1200: COM017
        obj = od.objects.get(index)
        if obj is None:
            continue
        for subindex in (0, 1, 2):
            sub = _entry(obj, subindex)
            known = _predefined(index, subindex)
            if sub is not None and known is not None:
                yield obj, sub, known


@check
def predefined_cob_ids(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for obj, sub, (base, name) in _cob_entries(od):
        value, keyword = value_in_force(od, sub)
        raw = number(value)
        if value is None or not isinstance(raw, int):
            continue
        problem = _not_predefined(od, value, raw, base, name)
        if problem:
            diags.add(COM004, Loc(od.source, value_line(sub, value, keyword)),
                      f"COB-ID {value.text.strip()} {problem}", obj.index, addr(obj, sub))


def _not_predefined(od: ObjectDictionary, value: Value, raw: int, base: int, name: str) -> str | None:
    """How a COB-ID (`raw`, the offset of a `$NODEID` value) misses the predefined `$NODEID+base`."""
    if value.nodeid:
        return f"is not the predefined {name} COB-ID $NODEID+0x{base:X}" if raw & 0x7FF != base else None
    if od.is_config or raw & 0x80000000 or not raw & 0x7FF:
        return None
    if raw & 0x7FF == base:  # CANopenNode adds the node-id to a bare base; CiA 301 does not
        return f"lacks the node-id; write $NODEID+0x{base:X}, the predefined {name} COB-ID"
    return f"is fixed; the predefined {name} COB-ID is $NODEID+0x{base:X}"


@check
def pdo_cob_ids(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    span = node_span(od, options)
    for index, obj in od.objects.items():
        if _pdo_comm(index) is None or obj.is_var or 1 not in obj.subs:
            continue
        sub = obj.subs[1]
        value, keyword = value_in_force(od, sub)
        raw = number(value)
        if value is None or not isinstance(raw, int):
            continue
        known = _predefined(index, 1)
        if known and not value.nodeid and raw & 0x7FF == known[0]:
            continue  # a bare predefined base: COM004 says what is missing
        problem = _cob_problem(value, span)
        if problem:
            diags.add(COM005, Loc(od.source, value_line(sub, value, keyword)),
                      f"COB-ID {value.text.strip()} {problem}", index, 1)


def _cob_problem(value: Value, span: tuple[int, int]) -> str | None:
    ids: list[int] = []
    for node_id in span:
        raw = at(value, node_id)
        if not isinstance(raw, int) or raw < 0 or raw & 0x80000000 or raw & 0x20000000:
            return None  # disabled, or a 29-bit identifier
        if raw & 0x1FFFF800:
            return "sets CAN-ID bits above 0x7FF without the 29-bit flag (bit 29)"
        ids.append(raw & 0x7FF)
    lo, hi = ids
    for first, last in RESTRICTED:
        if lo <= last and first <= hi:
            can_id = max(lo, first)
            node = f" for node-id {can_id - (lo - span[0])}" if value.nodeid else ""
            return f"gives the restricted CAN-ID 0x{can_id:03X}{node}"
    return None


# -- C7: identity and error control -----------------------------------------------------

@check
def identity(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    obj = od.objects.get(0x1018)
    if obj is not None and (obj.is_var or 1 not in obj.subs):
        diags.add(COM006, Loc(od.source, obj.line), "has no Vendor-ID (sub1)", 0x1018)
    for index, subindex in ((0x1000, 0), (0x1018, 1)):
        target = od.objects.get(index)
        sub = _entry(target, subindex)
        if target is None or sub is None:
            continue
        value, _ = value_in_force(od, sub)
        if value is None or value.empty:
            what = "device type" if index == 0x1000 else "Vendor-ID"
            diags.add(COM013, Loc(od.source, sub.line), f"{what} has no DefaultValue", index, addr(target, sub))


def _var_int(od: ObjectDictionary, index: int) -> tuple[Sub | None, int | None]:
    """The entry of a single-value object, and the integer in force there (None if not one)."""
    obj = od.objects.get(index)
    sub = obj.var if obj is not None else None
    return sub, (plain_int(value_in_force(od, sub)[0]) if sub is not None else None)


@check
def error_control(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    guard, life = od.objects.get(0x100C), od.objects.get(0x100D)
    if 0x1017 not in od.objects and guard is None and life is None:
        diags.add(COM007, Loc(od.source), "neither heartbeat (0x1017) nor node guarding (0x100C/0x100D)")
    present, absent = (guard, 0x100D) if life is None else (life, 0x100C)
    if present is not None and (guard is None or life is None):
        diags.add(COM014, Loc(od.source, present.line), f"is defined but 0x{absent:04X} is not", present.index)
    heartbeat, hb_time = _var_int(od, 0x1017)
    guard_time, life_factor = _var_int(od, 0x100C)[1], _var_int(od, 0x100D)[1]
    if heartbeat is not None and hb_time and guard_time and life_factor:
        diags.add(COM008, Loc(od.source, default_line(heartbeat)),
                  f"heartbeat {hb_time} ms and node guarding {guard_time} ms x {life_factor} are both enabled",
                  0x1017)


@check
def heartbeat_consumers(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    obj = od.objects.get(0x1016)
    if obj is None or obj.is_var:
        return
    seen: dict[int, int] = {}
    for sub in obj.sorted_subs():
        if sub.subindex == 0:
            continue
        value, keyword = value_in_force(od, sub)
        raw = plain_int(value)
        if value is None or raw is None:
            continue
        node, time = (raw >> 16) & 0xFF, raw & 0xFFFF
        problem = _consumer_problem(raw >> 24, node, time, seen)
        if problem:
            diags.add(COM015, Loc(od.source, value_line(sub, value, keyword)),
                      f"{value.text.strip()} {problem}", 0x1016, sub.subindex)
        elif time:
            seen[node] = sub.subindex


def _consumer_problem(reserved: int, node: int, time: int, seen: dict[int, int]) -> str | None:
    """What is wrong with a 0x1016 entry 0xRRNNTTTT, given the node-ids monitored so far."""
    if reserved:
        return "sets the reserved bits 24-31"
    if time and not 1 <= node <= 127:
        return f"monitors node-id {node}, not 1..127"
    if time and node in seen:
        return f"monitors node-id {node} again (also sub{seen[node]})"
    return None


@check
def device_profile(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    sub, device_type = _var_int(od, 0x1000)
    if sub is None or device_type is None or device_type & 0xFFFF:
        return
    profile = next((i for i in sorted(od.objects) if 0x6000 <= i <= 0x9FFF), None)
    if profile is not None:
        diags.add(COM012, Loc(od.source, default_line(sub)),
                  f"device type 0x{device_type:08X} names no device profile, but the file defines "
                  f"profile objects (first 0x{profile:04X})", 0x1000)


# -- C8: PDO and SDO parameter records -------------------------------------------------

@check
def comm_records(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for index, obj in od.objects.items():
        kind = _pdo_comm(index)
        if obj.is_var or not 0x1200 <= index <= 0x19FF:
            continue
        if kind is not None:
            _pdo_record(od, obj, kind, diags)
        elif _is_sdo(index):
            required = (1, 2, 3) if _in(index, SDO_CLIENT, 0x80) else (1, 2)
            _required(od, obj, required, diags)


def _required(od: ObjectDictionary, obj: Obj, required: tuple[int, ...], diags: Diagnostics) -> bool:
    missing = [s for s in required if s not in obj.subs]
    if missing:
        diags.add(COM010, Loc(od.source, obj.line),
                  f"has no {', '.join(f'sub{s}' for s in missing)}", obj.index)
    return not missing


def _pdo_record(od: ObjectDictionary, obj: Obj, kind: str, diags: Diagnostics) -> None:
    if not _required(od, obj, (1, 2), diags):
        return
    top = 5 if kind == "RPDO" else 6
    sub0 = obj.subs.get(0)
    highest = plain_int(value_in_force(od, sub0)[0]) if sub0 is not None else None
    if highest is None:
        highest = max(obj.subs, default=0)
    if not 2 <= highest <= top and sub0 is not None:
        diags.add(COM009, Loc(od.source, sub0.line_of("defaultvalue")),
                  f"{kind} communication record's highest sub-index is {highest}, CiA 301 defines 2..{top}",
                  obj.index, 0)
    _transmission_type(od, obj, kind, diags)


def _transmission_type(od: ObjectDictionary, obj: Obj, kind: str, diags: Diagnostics) -> None:
    sub = obj.subs.get(2)
    if sub is None:
        return
    value, keyword = value_in_force(od, sub)
    ttype = plain_int(value)
    reserved = range(241, 254) if kind == "RPDO" else range(241, 252)
    if ttype is not None and ttype in reserved:
        diags.add(COM011, Loc(od.source, value_line(sub, value, keyword)),
                  f"transmission type {ttype} is reserved for {kind}s", obj.index, 2)




# -- services: SYNC window, LSS -------------------------------------------------------

@check
def sync_window(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    _, period = _var_int(od, 0x1006)
    window_sub, window = _var_int(od, 0x1007)
    if window_sub is not None and period and window and window > period:
        diags.add(COM020, Loc(od.source, value_line(window_sub, *value_in_force(od, window_sub))),
                  f"window {window} us is longer than the communication cycle period 0x1006 ({period} us)",
                  0x1007, 0)


@check
def lss_identity(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    fld = header_field(od, "DeviceInfo", "LSS_Supported")
    if header_int(fld) != 1 or fld is None:
        return
    obj = od.objects.get(0x1018)
    missing = [k for k in (1, 2, 3, 4) if obj is None or obj.is_var or k not in obj.subs]
    if missing:
        names = ", ".join(f"sub{k}" for k in missing)
        diags.add(COM021, Loc(od.source, fld.line),
                  f"lacks {names} while LSS_Supported=1; an LSS master addresses the device by 0x1018 sub1-4",
                  0x1018)
