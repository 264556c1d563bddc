"""The conformance checks: what a CiA 301 conformance test looks at, run against a live node.

Each check is a function of the client returning a Check (roundtrip's: passed count,
failures, or a reason to skip). Expected values come from the description alone; a check
whose object the description lacks is skipped, saying why. Checks leave the node as they
found it where they can (values written back, pre-operational, 0x1017 restored).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

from ..model.expect import expected_bytes, write_cases
from ..model.wire import wire_bytes, wire_number
from ..model import Obj, Sub
from ..model.cia301 import COMMUNICATION_AREA, CONSUMER_HEARTBEAT, ERROR_BEHAVIOUR, ERROR_HISTORY, ERROR_REGISTER, \
    GUARD_TIME, HEARTBEAT, IDENTITY, LIFE_TIME_FACTOR, MANUFACTURER_AREA, PRODUCER_HEARTBEAT, SDO_REQUEST, \
    SDO_RESPONSE, SDO_SERVER, SYNC_COB_ID, SYNC_OVERFLOW, SYNC_PERIOD, is_store_command
from ..model.header import header_field, header_int
from ..model.datatypes import BASIC_TYPES, DataType
from .verdict import ABORTS, ACTIVE, NO_OBJECT, NO_SUB, WRITE_ONLY, Check
from .allowed import NO_DATA, RUN_TIME_STATE, code_text, consumer_room, watched_elsewhere, write_refusals
from .client import DEADLINE, SDO_TIMEOUT, SILENCE, Client

READ_ONLY = ABORTS["ODG_ABORT_READ_ONLY"]
RANGE = 0x06090030  # "value range of parameter exceeded": the general code a node may give
LENGTH = 0x06070010  # "data type does not match, length does not match": likewise
NOT_MAPPABLE, MAP_TOO_LONG, INCOMPATIBLE = 0x06040041, 0x06040042, 0x06040043
SIGNATURE = 0x08000020
EMCY_RPDO_LENGTH = 0x8210
# Accepted in place of the specific code: CiA 301 lets a device answer with the general one.
ALSO = {0x06090031: RANGE, 0x06090032: RANGE, 0x06070012: LENGTH, 0x06070013: LENGTH}


@dataclass
class Entry:
    obj: Obj
    sub: Sub
    dtype: DataType

    @property
    def label(self) -> str:
        return f"0x{self.obj.index:04X}sub{self.sub.subindex}"

    @property
    def key(self) -> tuple[int, int]:
        return self.obj.index, self.sub.subindex


def entries(c: Client) -> list[Entry]:
    out = []
    for obj in c.od.sorted_objects():
        for sub in obj.sorted_subs():
            dtype = BASIC_TYPES.get(sub.data_type or 0)
            if dtype is not None and obj.index >= COMMUNICATION_AREA[0]:
                out.append(Entry(obj, sub, dtype))
    return out


def is_command(e: Entry) -> bool:
    return is_store_command(e.obj.index, e.sub.subindex)


def _code_ok(got: int, want: int) -> bool:
    return got == want or (want in ALSO and got == ALSO[want])


def _hex(data: bytes | None) -> str:
    return "none" if data is None else (data.hex(" ") if len(data) <= 16 else data[:16].hex(" ") + " ...")


def _same_value(e: Entry, got: bytes, want: bytes) -> bool:
    """An OCTET_STRING may be stored longer than its default: zero padding is the same value."""
    if e.dtype.kind == "ostring":
        return got[:len(want)] == want and not got[len(want):].strip(b"\0")
    return got == want


# ---- SDO: values, limits, lengths ---------------------------------------------------------------


def check_uploads(c: Client) -> Check:
    """every readable entry uploads the described value"""
    check = Check("every readable entry uploads the described value (run-time state: a consistent one)")
    for e in entries(c):
        if not e.sub.readable or e.obj.index in RUN_TIME_STATE:
            continue
        data, code = c.upload(*e.key)
        want = expected_bytes(c.od, e.sub, e.dtype, c.node_id) if _compared(c, e) else None
        if code:
            check.expect(False, f"{e.label}: upload gave {code_text(code)}")
        elif want is not None:
            check.expect(_same_value(e, data or b"", want), f"{e.label}: uploaded {_hex(data)}, described {_hex(want)}")
        else:
            _within_limits(check, e, data or b"")
    _run_time_state(c, check)
    return check


def _compared(c: Client, e: Entry) -> bool:
    """Whether the described value is the one the node must hold now. Not for commands; on a
    node that may have been configured (not `fresh`) not for writable entries but where a
    DCF states the configured value, nor for process inputs (mappable read-only entries of the
    application) or the serial number, which differ from device to device."""
    if is_command(e):
        return False
    if c.settings.fresh:
        return True
    if e.sub.writable:
        return c.od.is_config and e.sub.parameter_value is not None and not e.sub.parameter_value.empty
    return not (e.sub.pdo_mapping and e.obj.index >= MANUFACTURER_AREA[0]) and e.key != (IDENTITY, 4)


def _within_limits(check: Check, e: Entry, data: bytes) -> None:
    """A value not compared with the description: a number has its type's size and lies within the
    described limits."""
    cases = write_cases(e.sub, e.dtype) if e.dtype.is_numeric and not is_command(e) else []
    if not cases:
        check.expect(True, "")
        return
    size = len(cases[0][0])
    if len(data) != size:
        check.expect(False, f"{e.label}: uploaded {len(data)} bytes, the type has {size}")
        return
    value, lo, hi = wire_number(data, e.dtype), wire_number(cases[0][0], e.dtype), wire_number(cases[1][0], e.dtype)
    check.expect(lo <= value <= hi, f"{e.label}: uploaded {value}, outside the described limits {lo}..{hi}")


def _run_time_state(c: Client, check: Check) -> None:
    """0x1001 and 0x1003 as CiA 301 has them whatever errors the node has: any error register
    bit sets the generic bit; 0x1003 sub 0 counts at most the sub-entries there are, each one
    counted answers, one beyond may say "no data" (0x08000024)."""
    register = c.upload(ERROR_REGISTER, 0) if c.od.find(ERROR_REGISTER) is not None else None
    if register is not None:
        data, code = register
        check.expect(code == 0 and data is not None and len(data) == 1, f"0x1001: upload gave {code_text(code)}, "
                                                                         f"{_hex(data)}")
        if data:
            check.expect(data[0] == 0 or data[0] & 0x01 != 0,
                         f"0x1001 reads 0x{data[0]:02X}: an error bit without the generic bit 0")
    history = c.od.objects.get(ERROR_HISTORY)
    if history is None or 0 not in history.subs:
        return
    last = max(history.subs)
    count = c.number(ERROR_HISTORY, 0)
    check.expect(count is not None and count <= last, f"0x1003sub0 reads {count}, the object has sub-entries 1..{last}")
    for sub in range(1, last + 1):
        if sub not in history.subs:
            continue
        data, code = c.upload(ERROR_HISTORY, sub)
        if count is not None and sub <= count:
            check.expect(code == 0 and data is not None and len(data) == 4,
                         f"0x1003sub{sub}: one of {count} errors, upload gave {code_text(code)}")
        else:
            check.expect(code in (0, NO_DATA), f"0x1003sub{sub}: beyond the {count} errors, upload gave "
                                               f"{code_text(code)} (0x{NO_DATA:08X} or a value allowed)")


def _writable_numbers(c: Client) -> list[Entry]:
    """Sub-indices of one object described alike (type, access, limits) behave alike: the first stands
    for the others, which keeps a run over a large array short."""
    seen, out = set(), []
    for e in entries(c):
        cases = write_cases(e.sub, e.dtype) if e.sub.writable and e.dtype.is_numeric else []
        key = (e.obj.index, e.sub.access, tuple(cases))
        if cases and e.obj.index not in ACTIVE and not is_command(e) and key not in seen:
            seen.add(key)
            out.append(e)
    return out


def _downloads(c: Client, check: Check, keep: Callable[[str], bool]) -> None:
    for e in _writable_numbers(c):
        original = c.upload(*e.key)[0] if e.sub.readable else None
        for data, expect in write_cases(e.sub, e.dtype):
            if not keep(expect):
                continue
            code, want = c.download(*e.key, data), ABORTS[expect]
            refusals = write_refusals(c, *e.key, data)
            if code in refusals and not _code_ok(code, want):
                check.expect(True, "")
                _note(check, f"{e.label}: {_hex(data)} refused with 0x{code:08X}: {refusals[code]}")
                continue
            also = "".join(f", or {'/'.join(f'0x{k:08X}' for k, w in refusals.items() if w == why)} ({why})"
                           for why in dict.fromkeys(refusals.values()))
            check.expect(_code_ok(code, want), f"{e.label}: download {_hex(data)} gave {code_text(code)}, "
                                               f"expected 0x{want:08X}{also}")
            if code == 0 and want == 0 and e.sub.readable:
                back = c.upload(*e.key)[0]
                check.expect(back == data, f"{e.label}: wrote {_hex(data)}, read back {_hex(back)}")
        if original is not None:
            c.download(*e.key, original)
    if not check.passed and not check.failures:
        check.skipped = "no writable number outside the communication objects"


def _note(check: Check, text: str) -> None:
    if len(check.notes) < 10 and text not in check.notes:
        check.notes.append(text)


def check_limits(c: Client) -> Check:
    check = Check("writable entries take values at their limits and refuse values beyond them")
    _downloads(c, check, lambda expect: expect in ("ODG_OK", "ODG_ABORT_VALUE_HIGH", "ODG_ABORT_VALUE_LOW"))
    return check


def check_lengths(c: Client) -> Check:
    check = Check("writable entries refuse downloads of the wrong length (0x06070012/13)")
    _downloads(c, check, lambda expect: expect in ("ODG_ABORT_TOO_LONG", "ODG_ABORT_TOO_SHORT"))
    return check


# ---- access rules -------------------------------------------------------------------------------


def check_read_only(c: Client) -> Check:
    check = Check("a write to a read-only entry aborts 0x06010002")
    for e in entries(c):
        if e.sub.writable or not e.dtype.is_numeric or is_command(e):
            continue
        data = expected_bytes(c.od, e.sub, e.dtype, c.node_id) or wire_bytes(0, e.dtype)
        code = c.download(*e.key, data)
        check.expect(code == READ_ONLY, f"{e.label}: write to {e.sub.access} gave {code_text(code)}, "
                                        f"expected 0x{READ_ONLY:08X}")
    if not check.passed and not check.failures:
        check.skipped = "no read-only number"
    return check


def check_write_only(c: Client) -> Check:
    check = Check("a read of a write-only entry aborts 0x06010001")
    for e in entries(c):
        if not e.sub.readable and not is_command(e):
            code = c.upload(*e.key)[1]
            check.expect(code == WRITE_ONLY, f"{e.label}: read of {e.sub.access} gave {code_text(code)}, "
                                             f"expected 0x{WRITE_ONLY:08X}")
    if not check.passed and not check.failures:
        check.skipped = "no write-only entry"
    return check


def check_missing(c: Client) -> Check:
    check = Check("a missing object aborts 0x06020000, a missing sub-index 0x06090011")
    missing = next(i for i in range(0x5FFF, 0x1FFF, -1) if i not in c.od.objects)
    for index in sorted({missing, 0x1FFF} - set(c.od.objects)):  # application and communication area
        code = c.upload(index, 0)[1]
        check.expect(code == NO_OBJECT, f"0x{index:04X}: read gave {code_text(code)}, expected 0x{NO_OBJECT:08X}")
    for obj in c.od.sorted_objects():
        if obj.index >= COMMUNICATION_AREA[0] and obj.subs:
            absent = next((i for i in range(0xFE, 0, -1) if i not in obj.subs), None)
            if absent is not None:
                code = c.upload(obj.index, absent)[1]
                check.expect(code == NO_SUB, f"0x{obj.index:04X}sub{absent}: read gave {code_text(code)}, "
                                             f"expected 0x{NO_SUB:08X}")
                break
    return check


# ---- NMT and heartbeat --------------------------------------------------------------------------


def check_nmt_states(c: Client) -> Check:
    check = Check("NMT: SDO answers in pre-operational and operational, not in stopped; heartbeat shows the state")
    hb = c.od.find(PRODUCER_HEARTBEAT)
    original = c.upload(PRODUCER_HEARTBEAT, 0)[0] if hb is not None else None
    if hb is not None and hb.writable:
        c.download(PRODUCER_HEARTBEAT, 0, (100).to_bytes(2, "little"))  # a heartbeat soon after each command
    beating = _heartbeat_period(c)
    patience = min(DEADLINE, max(3.0, 10 * beating / 1000))  # heartbeats enough for the new state to show
    for command, state, sdo in (("OPERATIONAL", 0x05, True), ("STOPPED", 0x04, False),
                                ("PRE-OPERATIONAL", 0x7F, True)):
        sent = c.nmt(command)
        if beating and not c.heartbeat_state(sent, state, patience):
            if command != "OPERATIONAL" or not _kept_by_error(c, check, sent):
                check.expect(False, f"{command}: no heartbeat with state 0x{state:02X}")
            if check.skipped:
                break
        elif beating:
            check.expect(True, "")
        answered = c.answers()
        check.expect(answered == sdo, f"{command}: the SDO server {'did not answer' if sdo else 'answered'}")
    if original is not None and hb is not None and hb.writable:
        c.download(PRODUCER_HEARTBEAT, 0, original)
    return check


# 0x1029 sub 1 (communication errors) and sub 2.. (others): the state CiA 301 lets them leave the node in
ERROR_STATES = {0: (0x7F, "pre-operational"), 1: (None, "no change of state"), 2: (0x04, "stopped")}
REG_COMMUNICATION_BIT = 0x10


def _kept_by_error(c: Client, check: Check, sent: float) -> bool:
    """After "start" the heartbeat does not say operational. With an error active (0x1001 not 0)
    0x1029 may keep the node where it is: judged against 0x1029 where described (True: the
    finding is made here), skipped with the reason where not."""
    register = c.number(ERROR_REGISTER) or 0
    beats = [d for _, d in c.frames_since(sent, HEARTBEAT + c.node_id) if len(d) == 1]
    state = beats[-1][0] & 0x7F if beats else None  # where the node stayed
    if not register:
        return False
    did = f"after \"start\" the heartbeat says {'none' if state is None else f'0x{state:02X}'} with 0x1001 = " \
          f"0x{register:02X} (an error active)"
    sub = 1 if register & REG_COMMUNICATION_BIT else 2
    if c.od.find(ERROR_BEHAVIOUR, sub) is None:
        check.skipped = f"{did}; CiA 301 lets 0x1029 keep a device with an error out of operational, and the " \
                        f"description has no 0x1029 sub {sub} to judge by"
        return True
    behaviour = c.number(ERROR_BEHAVIOUR, sub)
    want, meaning = ERROR_STATES.get(behaviour if behaviour is not None else -1, (None, "manufacturer-specific"))
    if behaviour is not None and behaviour >= 0x80:
        check.notes.append(f"{did}; 0x1029sub{sub} = {behaviour}: manufacturer-specific, allowed")
        return True
    check.expect(want is not None and state == want,
                 f"{did}, but 0x1029sub{sub} = {behaviour} asks for {meaning}")
    if want is not None and state == want:
        check.notes.append(f"{did}: as 0x1029sub{sub} = {behaviour} ({meaning}) asks")
    return True


def check_bootup(c: Client) -> Check:
    """boot-up after reset communication and after reset node"""
    check = Check("boot-up after reset communication and after reset node")
    for command in ("RESET COMMUNICATION", "RESET"):
        sent = c.nmt(command)
        booted = c.wait_frame(sent, lambda cob, d: cob == 0x700 + c.node_id and d[:1] == b"\x00")
        check.expect(booted is not None, f"{command.lower()}: no boot-up within {DEADLINE:g} s")
        check.expect(c.answers(), f"{command.lower()}: the SDO server does not answer after the boot-up")
    return check


def _booted(c: Client, command: str) -> bool:
    sent = c.nmt(command)
    return c.wait_frame(sent, lambda cob, d: cob == HEARTBEAT + c.node_id and d[:1] == b"\x00") is not None


def _changes(c: Client, first: int, last: int, most: int) -> list[tuple[Entry, bytes, bytes, bytes | None]]:
    """Up to `most` writable numbers of first..last the node takes another valid value for, written:
    (entry, described value, value written, value before). Objects with steps of their own are left
    alone, but for the heartbeat period."""
    out: list[tuple[Entry, bytes, bytes, bytes | None]] = []
    for e in entries(c):
        if len(out) >= most or not first <= e.obj.index <= last or not e.sub.writable or not e.sub.readable:
            continue
        if not e.dtype.is_numeric or is_command(e) or (e.obj.index in ACTIVE and e.obj.index != PRODUCER_HEARTBEAT):
            continue
        described = expected_bytes(c.od, e.sub, e.dtype, c.node_id)
        before = c.upload(*e.key)[0]
        other = next((d for d, expect in write_cases(e.sub, e.dtype)
                      if expect == "ODG_OK" and d not in (described, before) and not write_refusals(c, *e.key, d)),
                     None)
        if described is not None and other is not None and c.download(*e.key, other) == 0:
            out.append((e, described, other, before))
    return out


def check_reset_communication(c: Client) -> Check:
    """reset communication: the communication area takes back its power-on values"""
    check = Check("reset communication: the communication area takes back its values, the application area keeps its")
    comm = _changes(c, *COMMUNICATION_AREA, most=8)
    app = _changes(c, MANUFACTURER_AREA[0], 0xFFFF, most=1)
    if not comm:
        check.skipped = "no communication entry a client may change (but PDO, SDO, SYNC, EMCY ones)"
        return check
    check.expect(_booted(c, "RESET COMMUNICATION"), f"reset communication: no boot-up within {DEADLINE:g} s")
    for e, described, written, before in comm:
        back = c.upload(*e.key)[0]
        # the power-on value: the described one, or on a node that may have been configured a stored
        # one, which is what it had before the battery wrote (as far as the battery can know)
        allowed = {described} if c.settings.fresh else {described, before}
        check.expect(back in allowed, f"{e.label}: {_hex(back)} after reset communication, {_hex(written)} "
                                      f"written, {_hex(described)} described, {_hex(before)} before")
        if back != before and before is not None:
            c.download(*e.key, before)  # put back
    for e, _described, written, before in app:
        back = c.upload(*e.key)[0]
        check.expect(back == written, f"{e.label}: {_hex(back)} after reset communication, {_hex(written)} written")
        if before is not None:
            c.download(*e.key, before)
    return check


def check_sdo_server(c: Client) -> Check:
    check = Check("the SDO server answers on the COB-IDs of 0x1200, also after reset communication")
    if c.od.find(SDO_SERVER, 1) is None or c.od.find(SDO_SERVER, 2) is None:
        check.skipped = "no 0x1200 sub 1/2: the pre-defined COB-IDs, checked by every other step"
        return check
    for sub, used in ((1, c.sdo_rx), (2, c.sdo_tx)):
        value = c.number(SDO_SERVER, sub)
        check.expect(value == used, f"0x1200sub{sub} reads {value if value is None else hex(value)}, "
                                    f"the server uses 0x{used:03X} (bit 31 clear)")
    if not c.settings.destructive:
        check.notes.append("not tried: the server after a reset communication (run with --allow destructive)")
    else:
        check.expect(_booted(c, "RESET COMMUNICATION"), f"reset communication: no boot-up within {DEADLINE:g} s")
        check.expect(c.answers(), "no SDO answer after reset communication")
    if (c.sdo_rx, c.sdo_tx) != (SDO_REQUEST + c.node_id, SDO_RESPONSE + c.node_id):
        c.watch(SDO_RESPONSE + c.node_id)
        sent = time.monotonic()
        c.send(SDO_REQUEST + c.node_id, bytes([0x40, 0x00, 0x10, 0, 0, 0, 0, 0]))  # upload 0x1000
        stray = c.wait_frame(sent, lambda cob, d: cob == SDO_RESPONSE + c.node_id, deadline=SILENCE)
        check.expect(stray is None, "the server moved by 0x1200 still answers on the pre-defined COB-IDs")
    return check


def _heartbeat_period(c: Client) -> int:
    data = c.upload(PRODUCER_HEARTBEAT, 0)[0] if c.od.find(PRODUCER_HEARTBEAT) is not None else None
    return int.from_bytes(data, "little") if data else 0


def _ms(medians: list[float | None]) -> str:
    return ", ".join("none" if m is None else str(round(m)) for m in medians)


def check_heartbeat(c: Client) -> Check:
    check = Check("heartbeat period as configured in 0x1017")
    hb = c.od.find(PRODUCER_HEARTBEAT)
    if hb is None:
        check.skipped = "no 0x1017"
        return check
    original = c.upload(PRODUCER_HEARTBEAT, 0)[0]
    period = 100 if hb.writable else _heartbeat_period(c)
    if hb.writable:
        check.expect(c.download(PRODUCER_HEARTBEAT, 0, period.to_bytes(2, "little")) == 0, "0x1017 = 100 ms refused")
    if not period or period > 2000:
        check.skipped = f"0x1017 is read-only with {period} ms"
        return check
    medians = c.period(0x700 + c.node_id, period * 8 / 1000, lambda m: 0.8 * period <= m <= 1.3 * period)
    check.expect(medians[-1] is not None and 0.8 * period <= medians[-1] <= 1.3 * period,
                 f"heartbeat every {_ms(medians)} ms, configured {period}")
    if original is not None and hb.writable:
        c.download(PRODUCER_HEARTBEAT, 0, original)
    return check


# ---- SYNC producer ------------------------------------------------------------------------------

SYNC_GENERATE, DEVICE_STATE = 0x40000000, 0x08000022


def check_sync_producer(c: Client) -> Check:
    check = Check("SYNC producer: 0x1005 bit 30, period 0x1006, counter 0x1019 (written only while 0x1006 is 0)")
    cob, period, counter = c.od.find(SYNC_COB_ID), c.od.find(SYNC_PERIOD), c.od.find(SYNC_OVERFLOW)
    if cob is None or period is None or not (cob.writable and period.writable):
        check.skipped = "0x1005 and 0x1006 are not both writable"
        return check
    saved = {index: c.upload(index, 0)[0] for index in (SYNC_COB_ID, SYNC_PERIOD, SYNC_OVERFLOW)
             if c.od.find(index) is not None}
    sync_id = (c.number(SYNC_COB_ID) or 0x80) & 0x7FF
    c.watch(sync_id)
    c.download(SYNC_PERIOD, 0, bytes(4))
    overflow = counter is not None and counter.writable
    if overflow:
        check.expect(c.download(SYNC_OVERFLOW, 0, b"\x03") == 0, "0x1019 = 3 refused while 0x1006 is 0")
    check.expect(c.download(SYNC_PERIOD, 0, (20000).to_bytes(4, "little")) == 0, "0x1006 = 20000 us refused")
    if overflow:
        code = c.download(SYNC_OVERFLOW, 0, b"\x04")
        check.expect(code == DEVICE_STATE, f"0x1019 written while 0x1006 is not 0 gave {code_text(code)}, "
                                             f"expected 0x{DEVICE_STATE:08X}")
    code = c.download(SYNC_COB_ID, 0, (sync_id | SYNC_GENERATE).to_bytes(4, "little"))
    if code == RANGE:
        check.skipped = NO_SYNC_PRODUCER
        _put_back_sync(c, saved)
        return check
    check.expect(code == 0, f"0x1005 bit 30 gave {code_text(code)}, expected 0 or 0x{RANGE:08X} (no SYNC producer)")
    start = time.monotonic()
    medians = c.period(sync_id, 0.3, lambda m: 14 <= m <= 30)
    check.expect(medians[-1] is not None and 14 <= medians[-1] <= 30, f"SYNC every {_ms(medians)} ms, want 20")
    frames = [d for _, d in c.frames_since(start, sync_id)]
    if overflow:
        bad = [(a, b) for a, b in zip(frames, frames[1:], strict=False)
               if len(a) != 1 or len(b) != 1 or b[0] != a[0] % 3 + 1]
        check.expect(bool(frames) and not bad, f"SYNC counters 1, 2, 3, 1, ... expected, got {frames[:8]}")
    _put_back_sync(c, saved)
    return check


# CiA 301: a device that cannot produce SYNC refuses 0x1005 bit 30 with 0x06090030
NO_SYNC_PRODUCER = "0x1005 bit 30 refused with 0x06090030: the node is no SYNC producer, as CiA 301 allows"


def _put_back_sync(c: Client, saved: dict[int, bytes | None]) -> None:
    c.download(SYNC_COB_ID, 0, saved.get(SYNC_COB_ID) or (0x80).to_bytes(4, "little"))
    c.download(SYNC_PERIOD, 0, bytes(4))  # 0x1019 may only be written while 0x1006 is 0
    for index in (SYNC_OVERFLOW, SYNC_PERIOD):
        if saved.get(index) is not None:
            c.download(index, 0, saved[index] or b"")


# ---- heartbeat consumer and 0x1029 ----------------------------------------------------------------

EMCY_HEARTBEAT = 0x8130
# 0x1029 sub 1 -> the heartbeat state an operational node must show after a communication error
AFTER_ERROR = {0: 0x7F, 1: 0x05, 2: 0x04}


def played_node(c: Client, sub: int) -> int:
    """A node-id whose heartbeat the battery plays for 0x1016 `sub`: not the node's own, none its
    other 0x1016 sub-entries watch (CiA 301: 0x06040043), none heard on the bus so far."""
    taken = watched_elsewhere(c, sub) | {c.node_id}
    with c.lock:
        taken |= {cob - HEARTBEAT for _, cob, _ in c.frames if HEARTBEAT < cob <= HEARTBEAT + 127}
    return next(n for k in range(1, 128) if (n := (c.node_id + k - 1) % 127 + 1) not in taken)


def check_hb_consumer(c: Client) -> Check:
    """heartbeat consumer (0x1016): EMCY 0x8130 when a watched heartbeat stops"""
    check = Check("heartbeat consumer (0x1016): EMCY 0x8130 when a watched heartbeat stops; 0x1029 sub 1 obeyed")
    entry, hb = c.od.find(CONSUMER_HEARTBEAT, 1), c.od.find(PRODUCER_HEARTBEAT)
    emcy = c.emcy_cob()
    if entry is None or not entry.writable or emcy is None or emcy & 0x80000000:
        check.skipped = "no writable 0x1016 sub 1, or EMCY disabled"
        return check
    if room := consumer_room(c, 1):
        check.skipped = room
        return check
    other = played_node(c, 1)
    saved, saved_hb = c.upload(CONSUMER_HEARTBEAT, 1)[0], c.upload(PRODUCER_HEARTBEAT, 0)[0] if hb is not None else None
    beating = hb is not None and hb.writable and c.download(PRODUCER_HEARTBEAT, 0, (100).to_bytes(2, "little")) == 0
    c.watch(emcy & 0x7FF)
    c.nmt("OPERATIONAL")
    check.expect(c.download(CONSUMER_HEARTBEAT, 1, (other << 16 | 200).to_bytes(4, "little")) == 0,
                 "0x1016sub1 refused")
    for _ in range(3):
        c.send(0x700 + other, b"\x05")
        time.sleep(0.05)  # pacing the heartbeats of the node played here
    last = time.monotonic()
    frame = c.wait_frame(last, lambda cob, d: cob == emcy & 0x7FF and d[:2] == EMCY_HEARTBEAT.to_bytes(2, "little"))
    check.expect(frame is not None, f"no EMCY 0x{EMCY_HEARTBEAT:04X} after node {other}'s heartbeat stopped")
    behaviour = c.upload(ERROR_BEHAVIOUR, 1)[0] if c.od.find(ERROR_BEHAVIOUR, 1) is not None else b"\x00"
    want = AFTER_ERROR.get(behaviour[0] if behaviour else 0)
    if beating and want is not None:
        check.expect(c.heartbeat_state(time.monotonic(), want),
                     f"0x1029sub1 = {behaviour!r}: no heartbeat with state 0x{want:02X} after the error")
    c.nmt("PRE-OPERATIONAL")
    c.download(CONSUMER_HEARTBEAT, 1, saved or bytes(4))
    if saved_hb is not None and beating:
        c.download(PRODUCER_HEARTBEAT, 0, saved_hb)
    return check


# ---- node guarding and life guarding --------------------------------------------------------------


def _guard(c: Client) -> bytes | None:
    sent = time.monotonic()
    c.send(0x700 + c.node_id, b"", remote=True)
    return c.wait_frame(sent, lambda cob, d: cob == 0x700 + c.node_id and len(d) == 1, deadline=2.0)


def check_guarding(c: Client) -> Check:
    check = Check("node guarding answers state and toggle; life guarding (0x100C x 0x100D) raises EMCY 0x8130")
    guard, factor, hb = c.od.find(GUARD_TIME), c.od.find(LIFE_TIME_FACTOR), c.od.find(PRODUCER_HEARTBEAT)
    if guard is None or factor is None or (hb is not None and not hb.writable and _heartbeat_period(c)):
        check.skipped = "no 0x100C/0x100D, or a heartbeat that cannot be switched off"
        return check
    saved = {index: c.upload(index, 0)[0] for index in (GUARD_TIME, LIFE_TIME_FACTOR, PRODUCER_HEARTBEAT)
             if c.od.find(index) is not None}
    if hb is not None:
        c.download(PRODUCER_HEARTBEAT, 0, b"\x00\x00")  # guarding and heartbeat are not used together
    answers = [_guard(c), _guard(c)]
    check.expect(None not in answers, f"no answer to a remote frame on 0x{0x700 + c.node_id:03X}")
    if None not in answers:
        first, second = answers[0] or b"\x00", answers[1] or b"\x00"
        check.expect(first[0] & 0x7F == 0x7F and second[0] & 0x7F == 0x7F, f"states {answers}, want 0x7F")
        check.expect((first[0] ^ second[0]) & 0x80 != 0, f"the toggle bit did not alternate: {answers}")
    emcy = c.emcy_cob()
    if guard.writable and factor.writable and emcy is not None and not emcy & 0x80000000:
        c.watch(emcy & 0x7FF)
        c.download(GUARD_TIME, 0, (100).to_bytes(2, "little"))
        c.download(LIFE_TIME_FACTOR, 0, b"\x02")
        _guard(c)
        sent = time.monotonic()
        frame = c.wait_frame(sent, lambda cob, d: cob == emcy & 0x7FF and d[:2] == EMCY_HEARTBEAT.to_bytes(2, "little"))
        check.expect(frame is not None, "no EMCY 0x8130 after the remote frames stopped (life time 200 ms)")
    c.nmt("PRE-OPERATIONAL")
    for index in (GUARD_TIME, LIFE_TIME_FACTOR, PRODUCER_HEARTBEAT):
        if saved.get(index) is not None:
            c.download(index, 0, saved[index] or b"")
    return check


# ---- LSS (CiA 305) --------------------------------------------------------------------------------

LSS_INQUIRE = (0x5A, 0x5B, 0x5C, 0x5D)  # vendor-ID, product code, revision, serial number: 0x1018 sub 1-4


def check_lss(c: Client) -> Check:
    check = Check("LSS: selected by its 0x1018 sub 1-4, the node answers its identity and node-id in configuration "
                  "mode")
    if header_int(header_field(c.od, "DeviceInfo", "LSS_Supported")) != 1:
        check.skipped = "the description does not say LSS_Supported=1"
        return check
    from canopen.lss import LssError  # the client's, loaded with it

    identity = [c.number(IDENTITY, sub) if c.od.find(IDENTITY, sub) is not None else None for sub in range(1, 5)]
    if None in identity and not c.settings.destructive:
        check.skipped = ("0x1018 sub 1-4 do not all answer, so only switch state global could select the node, "
                         "which switches every LSS slave on the bus: run with --allow destructive")
        return check
    lss = c.network.lss
    lss.RESPONSE_TIMEOUT = SDO_TIMEOUT
    try:
        if None in identity:
            lss.send_switch_state_global(lss.CONFIGURATION_STATE)
        else:  # the node alone, by its LSS address
            check.expect(lss.send_switch_state_selective(*identity), "switch state selective: no answer")
        for sub, (command, want) in enumerate(zip(LSS_INQUIRE, identity, strict=True), start=1):
            got = lss.inquire_lss_address(command)
            check.expect(want is None or got == want, f"inquire 0x{command:02X}: 0x{got:08X}, 0x1018sub{sub} "
                                                      f"reads {want if want is None else hex(want)}")
        node_id = lss.inquire_node_id()
        check.expect(node_id == c.node_id, f"inquire node-id: {node_id}, the node is {c.node_id}")
    except LssError as err:
        check.expect(False, f"no LSS answer in configuration mode: {err}")
    finally:
        lss.send_switch_state_global(lss.WAITING_STATE)
    check.expect(c.answers(), "no SDO answer after LSS configuration mode and back to waiting")
    return check
