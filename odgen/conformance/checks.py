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
from ..model.wire import wire_bytes
from ..model import Obj, Sub
from ..model.cia301 import COMMUNICATION_AREA, CONSUMER_HEARTBEAT, ERROR_BEHAVIOUR, GUARD_TIME, HEARTBEAT, IDENTITY, \
    LIFE_TIME_FACTOR, MANUFACTURER_AREA, PRODUCER_HEARTBEAT, SDO_REQUEST, SDO_RESPONSE, SDO_SERVER, SYNC_COB_ID, \
    SYNC_OVERFLOW, SYNC_PERIOD, is_store_command
from ..model.header import header_field, header_int
from ..model.datatypes import BASIC_TYPES, DataType
from ..roundtrip.checks import ABORTS, ACTIVE, NO_OBJECT, NO_SUB, WRITE_ONLY, Check
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
    check = Check("every readable entry uploads the described value")
    for e in entries(c):
        if not e.sub.readable:
            continue
        data, code = c.upload(*e.key)
        want = None if is_command(e) else expected_bytes(c.od, e.sub, e.dtype, c.node_id)
        if code:
            check.expect(False, f"{e.label}: upload aborted 0x{code:08X}" if code > 0 else f"{e.label}: no answer")
        elif want is not None:
            check.expect(_same_value(e, data or b"", want), f"{e.label}: uploaded {_hex(data)}, described {_hex(want)}")
        else:
            check.expect(True, "")
    return check


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
            code = c.download(*e.key, data)
            want = ABORTS[expect]
            check.expect(_code_ok(code, want), f"{e.label}: download {_hex(data)} gave 0x{code:08X}, "
                                               f"expected 0x{want:08X}")
            if code == 0 and want == 0 and e.sub.readable:
                back = c.upload(*e.key)[0]
                check.expect(back == data, f"{e.label}: wrote {_hex(data)}, read back {_hex(back)}")
        if original is not None:
            c.download(*e.key, original)
    if not check.passed and not check.failures:
        check.skipped = "no writable number outside the communication objects"


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
        check.expect(code == READ_ONLY, f"{e.label}: write to {e.sub.access} gave 0x{code:08X}")
    if not check.passed and not check.failures:
        check.skipped = "no read-only number"
    return check


def check_write_only(c: Client) -> Check:
    check = Check("a read of a write-only entry aborts 0x06010001")
    for e in entries(c):
        if not e.sub.readable and not is_command(e):
            code = c.upload(*e.key)[1]
            check.expect(code == WRITE_ONLY, f"{e.label}: read of {e.sub.access} gave 0x{code:08X}")
    if not check.passed and not check.failures:
        check.skipped = "no write-only entry"
    return check


def check_missing(c: Client) -> Check:
    check = Check("a missing object aborts 0x06020000, a missing sub-index 0x06090011")
    missing = next(i for i in range(0x5FFF, 0x1FFF, -1) if i not in c.od.objects)
    for index in sorted({missing, 0x1FFF} - set(c.od.objects)):  # application and communication area
        code = c.upload(index, 0)[1]
        check.expect(code == NO_OBJECT, f"0x{index:04X}: read gave 0x{code:08X}")
    for obj in c.od.sorted_objects():
        if obj.index >= COMMUNICATION_AREA[0] and obj.subs:
            absent = next((i for i in range(0xFE, 0, -1) if i not in obj.subs), None)
            if absent is not None:
                code = c.upload(obj.index, absent)[1]
                check.expect(code == NO_SUB, f"0x{obj.index:04X}sub{absent}: read gave 0x{code:08X}")
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
    for command, state, sdo in (("OPERATIONAL", 0x05, True), ("STOPPED", 0x04, False),
                                ("PRE-OPERATIONAL", 0x7F, True)):
        sent = c.nmt(command)
        if beating:
            check.expect(c.heartbeat_state(sent, state), f"{command}: no heartbeat with state 0x{state:02X}")
        answered = c.answers()
        check.expect(answered == sdo, f"{command}: the SDO server {'did not answer' if sdo else 'answered'}")
    if original is not None and hb is not None and hb.writable:
        c.download(PRODUCER_HEARTBEAT, 0, original)
    return check


def check_bootup(c: Client) -> Check:
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


def _changes(c: Client, first: int, last: int, most: int) -> list[tuple[Entry, bytes, bytes]]:
    """Up to `most` writable numbers of first..last the node takes another valid value for, written:
    (entry, described value, value written). Objects with steps of their own are left alone, but
    for the heartbeat period."""
    out: list[tuple[Entry, bytes, bytes]] = []
    for e in entries(c):
        if len(out) >= most or not first <= e.obj.index <= last or not e.sub.writable or not e.sub.readable:
            continue
        if not e.dtype.is_numeric or is_command(e) or (e.obj.index in ACTIVE and e.obj.index != PRODUCER_HEARTBEAT):
            continue
        described = expected_bytes(c.od, e.sub, e.dtype, c.node_id)
        other = next((d for d, expect in write_cases(e.sub, e.dtype) if expect == "ODG_OK" and d != described), None)
        if described is not None and other is not None and c.download(*e.key, other) == 0:
            out.append((e, described, other))
    return out


def check_reset_communication(c: Client) -> Check:
    check = Check("reset communication: the communication area takes back its values, the application area keeps its")
    comm = _changes(c, *COMMUNICATION_AREA, most=8)
    app = _changes(c, MANUFACTURER_AREA[0], 0xFFFF, most=1)
    if not comm:
        check.skipped = "no communication entry a client may change (but PDO, SDO, SYNC, EMCY ones)"
        return check
    check.expect(_booted(c, "RESET COMMUNICATION"), f"reset communication: no boot-up within {DEADLINE:g} s")
    for e, described, written in comm:
        back = c.upload(*e.key)[0]
        check.expect(back == described, f"{e.label}: {_hex(back)} after reset communication, "
                                        f"{_hex(written)} written, {_hex(described)} described")
        if back != described:
            c.download(*e.key, described)  # for the checks that follow
    for e, described, written in app:
        back = c.upload(*e.key)[0]
        check.expect(back == written, f"{e.label}: {_hex(back)} after reset communication, {_hex(written)} written")
        c.download(*e.key, described)
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
        check.expect(code == DEVICE_STATE, f"0x1019 written while 0x1006 is not 0 gave 0x{code:08X}")
    check.expect(c.download(SYNC_COB_ID, 0, (sync_id | SYNC_GENERATE).to_bytes(4, "little")) == 0,
                 "0x1005 bit 30 refused")
    start = time.monotonic()
    medians = c.period(sync_id, 0.3, lambda m: 14 <= m <= 30)
    check.expect(medians[-1] is not None and 14 <= medians[-1] <= 30, f"SYNC every {_ms(medians)} ms, want 20")
    frames = [d for _, d in c.frames_since(start, sync_id)]
    if overflow:
        bad = [(a, b) for a, b in zip(frames, frames[1:], strict=False)
               if len(a) != 1 or len(b) != 1 or b[0] != a[0] % 3 + 1]
        check.expect(bool(frames) and not bad, f"SYNC counters 1, 2, 3, 1, ... expected, got {frames[:8]}")
    c.download(SYNC_COB_ID, 0, saved.get(SYNC_COB_ID) or (0x80).to_bytes(4, "little"))
    c.download(SYNC_PERIOD, 0, bytes(4))
    for index in (SYNC_OVERFLOW, SYNC_PERIOD):
        if saved.get(index) is not None:
            c.download(index, 0, saved[index] or b"")
    return check


# ---- heartbeat consumer and 0x1029 ----------------------------------------------------------------

EMCY_HEARTBEAT = 0x8130
# 0x1029 sub 1 -> the heartbeat state an operational node must show after a communication error
AFTER_ERROR = {0: 0x7F, 1: 0x05, 2: 0x04}


def check_hb_consumer(c: Client) -> Check:
    check = Check("heartbeat consumer (0x1016): EMCY 0x8130 when a watched heartbeat stops; 0x1029 sub 1 obeyed")
    entry, hb = c.od.find(CONSUMER_HEARTBEAT, 1), c.od.find(PRODUCER_HEARTBEAT)
    emcy = c.emcy_cob()
    if entry is None or not entry.writable or emcy is None or emcy & 0x80000000:
        check.skipped = "no writable 0x1016 sub 1, or EMCY disabled"
        return check
    other = c.node_id % 127 + 1
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
    check = Check("LSS: in configuration mode the node answers its identity (0x1018 sub 1-4) and node-id")
    if header_int(header_field(c.od, "DeviceInfo", "LSS_Supported")) != 1:
        check.skipped = "the description does not say LSS_Supported=1"
        return check
    from canopen.lss import LssError  # the client's, loaded with it

    identity = [c.number(IDENTITY, sub) if c.od.find(IDENTITY, sub) is not None else None for sub in range(1, 5)]
    lss = c.network.lss
    lss.RESPONSE_TIMEOUT = SDO_TIMEOUT
    lss.send_switch_state_global(lss.CONFIGURATION_STATE)
    try:
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
