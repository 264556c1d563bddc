"""COM: CiA 301 communication-profile semantics checked against the description.

CiA 306 rule table rows C6-C8, plus what CiA 301 fixes for the communication
objects every master relies on: mandatory objects, data types, identity,
error control, COB-IDs and PDO parameters.
"""

from __future__ import annotations

from collections.abc import Iterator

from ...catalogue.comm import (
    COM001, COM002, COM003, COM004, COM005, COM006, COM007, COM008, COM009, COM010, COM011, COM012, COM013, COM014,
    COM015, COM020, COM021)
from ...diagnostics import Diagnostics, Loc
from ...model import Obj, ObjectDictionary, Sub, Value
from ...model.cia301 import (
    ARRAY_TYPES, COB_EXTENDED, COB_INVALID, CONSUMER_HEARTBEAT, DEVICE_TYPE, EMCY_COB_ID, GUARD_TIME, IDENTITY,
    LIFE_TIME_FACTOR, MANDATORY, PDO_COMM_TYPES, PDO_COUNT, PDO_MAPPING_ENTRIES, PREDEFINED_PDOS,
    PRODUCER_HEARTBEAT, READ_ONLY, RESTRICTED_CAN_IDS, RPDO_COMM, SDO_CLIENT, SDO_COUNT, SDO_SERVER, SDO_TYPES,
    TPDO_COMM, TPDO_MAPPING, U32, VAR_TYPES, is_pdo_mapping, is_sdo_parameter, pdo_communication, predefined_cob_id)
from ...model.datatypes import BASIC_TYPES
from .base import LintOptions, LintPass
from ...model.header import header_field, header_int
from ...model.values import number, plain_int
from .common import addr, at, default_line, node_span, value_in_force, value_line



# -- mandatory objects, data types, access -----------------------------------------

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
    if pdo_communication(index) is not None:
        return PDO_COMM_TYPES.get(sub.subindex)
    if is_pdo_mapping(index):
        return U32 if sub.subindex <= PDO_MAPPING_ENTRIES else None
    if is_sdo_parameter(index):
        return SDO_TYPES.get(sub.subindex)
    table = ARRAY_TYPES.get(index)
    if table is None:
        return None
    return table.get(sub.subindex, table.get(0))


# The communication objects the node layer reads or writes (runtime/odg_node*.c, odg_sdo.c, odg_pdo.c):
# a wrong data type there makes the runtime read another size than the C holds, so COM002 blocks there
# only; elsewhere (0x1008-0x100A, ...) the C serves the entry as the file types it.
_RUNTIME_READS = (range(0x1000, 0x1008), range(0x1010, 0x1013), range(0x1014, 0x101A), range(0x1021, 0x1022),
                  range(0x1029, 0x102A), range(0x1200, 0x1300), range(0x1400, 0x1C00))


def runtime_reads(index: int) -> bool:
    return any(index in r for r in _RUNTIME_READS)


def comm_data_types(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for index, obj in od.objects.items():
        if not DEVICE_TYPE <= index < TPDO_MAPPING + PDO_COUNT:
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
                      f"CiA 301 defines {BASIC_TYPES[expected].name}", index, addr(obj, sub),
                      blocks=runtime_reads(index))


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

def _entry(obj: Obj | None, subindex: int) -> Sub | None:
    """Sub-index 0 of a single-value object, or a sub-index 1.. of an ARRAY/RECORD; else None."""
    if obj is None or obj.is_var != (subindex == 0):
        return None
    return obj.subs.get(subindex)


def _cob_entries(od: ObjectDictionary) -> Iterator[tuple[Obj, Sub, tuple[int, str]]]:
    pdos = [*range(RPDO_COMM, RPDO_COMM + PREDEFINED_PDOS), *range(TPDO_COMM, TPDO_COMM + PREDEFINED_PDOS)]
    for index in [EMCY_COB_ID, *pdos]:  # 0x1200: COM017
        obj = od.objects.get(index)
        if obj is None:
            continue
        for subindex in (0, 1, 2):
            sub = _entry(obj, subindex)
            known = predefined_cob_id(index, subindex)
            if sub is not None and known is not None:
                yield obj, sub, known


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
    if od.is_config or raw & COB_INVALID or not raw & 0x7FF:
        return None
    if raw & 0x7FF == base:  # CANopenNode adds the node-id to a bare base; CiA 301 does not
        return f"lacks the node-id; write $NODEID+0x{base:X}, the predefined {name} COB-ID"
    return f"is fixed; the predefined {name} COB-ID is $NODEID+0x{base:X}"


def pdo_cob_ids(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    span = node_span(od, options)
    for index, obj in od.objects.items():
        if not RPDO_COMM <= index < TPDO_COMM + PDO_COUNT or pdo_communication(index) is None or obj.is_var \
                or 1 not in obj.subs:
            continue
        sub = obj.subs[1]
        value, keyword = value_in_force(od, sub)
        raw = number(value)
        if value is None or not isinstance(raw, int):
            continue
        known = predefined_cob_id(index, 1)
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
        if not isinstance(raw, int) or raw < 0 or raw & (COB_INVALID | COB_EXTENDED):
            return None  # disabled, or a 29-bit identifier
        if raw & 0x1FFFF800:
            return "sets CAN-ID bits above 0x7FF without the 29-bit flag (bit 29)"
        ids.append(raw & 0x7FF)
    lo, hi = ids
    for first, last in RESTRICTED_CAN_IDS:
        if lo <= last and first <= hi:
            can_id = max(lo, first)
            node = f" for node-id {can_id - (lo - span[0])}" if value.nodeid else ""
            return f"gives the restricted CAN-ID 0x{can_id:03X}{node}"
    return None


# -- C7: identity and error control -----------------------------------------------------

def identity(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    obj = od.objects.get(IDENTITY)
    if obj is not None and (obj.is_var or 1 not in obj.subs):
        diags.add(COM006, Loc(od.source, obj.line), "has no Vendor-ID (sub1)", IDENTITY)
    for index, subindex in ((DEVICE_TYPE, 0), (IDENTITY, 1)):
        target = od.objects.get(index)
        sub = _entry(target, subindex)
        if target is None or sub is None:
            continue
        value, _ = value_in_force(od, sub)
        if value is None or value.empty:
            what = "device type" if index == DEVICE_TYPE else "Vendor-ID"
            diags.add(COM013, Loc(od.source, sub.line), f"{what} has no DefaultValue", index, addr(target, sub))


def _var_int(od: ObjectDictionary, index: int) -> tuple[Sub | None, int | None]:
    """The entry of a single-value object, and the integer in force there (None if not one)."""
    obj = od.objects.get(index)
    sub = obj.var if obj is not None else None
    return sub, (plain_int(value_in_force(od, sub)[0]) if sub is not None else None)


def error_control(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    guard, life = od.objects.get(GUARD_TIME), od.objects.get(LIFE_TIME_FACTOR)
    if PRODUCER_HEARTBEAT not in od.objects and guard is None and life is None:
        diags.add(COM007, Loc(od.source), "neither heartbeat (0x1017) nor node guarding (0x100C/0x100D)")
    present, absent = (guard, LIFE_TIME_FACTOR) if life is None else (life, GUARD_TIME)
    if present is not None and (guard is None or life is None):
        diags.add(COM014, Loc(od.source, present.line), f"is defined but 0x{absent:04X} is not", present.index)
    heartbeat, hb_time = _var_int(od, PRODUCER_HEARTBEAT)
    guard_time, life_factor = _var_int(od, GUARD_TIME)[1], _var_int(od, LIFE_TIME_FACTOR)[1]
    if heartbeat is not None and hb_time and guard_time and life_factor:
        diags.add(COM008, Loc(od.source, default_line(heartbeat)),
                  f"heartbeat {hb_time} ms and node guarding {guard_time} ms x {life_factor} are both enabled",
                  PRODUCER_HEARTBEAT)


def heartbeat_consumers(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    obj = od.objects.get(CONSUMER_HEARTBEAT)
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
                      f"{value.text.strip()} {problem}", CONSUMER_HEARTBEAT, sub.subindex)
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


def device_profile(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    sub, device_type = _var_int(od, DEVICE_TYPE)
    if sub is None or device_type is None or device_type & 0xFFFF:
        return
    profile = next((i for i in sorted(od.objects) if 0x6000 <= i <= 0x9FFF), None)
    if profile is not None:
        diags.add(COM012, Loc(od.source, default_line(sub)),
                  f"device type 0x{device_type:08X} names no device profile, but the file defines "
                  f"profile objects (first 0x{profile:04X})", DEVICE_TYPE)


# -- C8: PDO and SDO parameter records -------------------------------------------------

def comm_records(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for index, obj in od.objects.items():
        if not SDO_SERVER <= index < TPDO_MAPPING or obj.is_var:
            continue
        kind = pdo_communication(index)
        if kind is not None:
            _pdo_record(od, obj, kind, diags)
        elif is_sdo_parameter(index):
            required = (1, 2, 3) if SDO_CLIENT <= index < SDO_CLIENT + SDO_COUNT else (1, 2)
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

def sync_window(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    _, period = _var_int(od, 0x1006)
    window_sub, window = _var_int(od, 0x1007)
    if window_sub is not None and period and window and window > period:
        diags.add(COM020, Loc(od.source, value_line(window_sub, *value_in_force(od, window_sub))),
                  f"window {window} us is longer than the communication cycle period 0x1006 ({period} us)",
                  0x1007, 0)


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


# This family's lint passes, in the order they run.
PASSES: tuple[LintPass, ...] = (mandatory_objects, comm_data_types, read_only_identity, predefined_cob_ids,
                                pdo_cob_ids, identity, error_control, heartbeat_consumers, device_profile,
                                comm_records, sync_window, lss_identity)
