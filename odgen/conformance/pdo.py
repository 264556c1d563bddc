"""Conformance checks of PDO configuration and transmission, EMCY, and store/restore (0x1010/0x1011).

PDOs are configured by plain SDO writes in the CiA 301 order, so the sequence itself is what
is checked: invalidate (COB-ID bit 31), mapping sub 0 = 0, entries, sub 0 = n, transmission
type, validate. The PDO's parameters are written back afterwards.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

from ..model.expect import expected_bytes, write_cases
from ..model.cia301 import CAN_ID_MASK, CONSUMER_HEARTBEAT, EMCY_INHIBIT, ERROR_HISTORY, ERROR_REGISTER, HEARTBEAT, \
    LOAD, RESTORE, SAVE, STORE, SYNC_COB_ID, SYNC_PERIOD, SYNC_WINDOW
from .verdict import ACTIVE, Check
from .checks import EMCY_HEARTBEAT, EMCY_RPDO_LENGTH, INCOMPATIBLE, MAP_TOO_LONG, NOT_MAPPABLE, RANGE, SIGNATURE, \
    NO_SYNC_PRODUCER, SYNC_GENERATE, Entry, _hex, entries, is_command, played_node
from .allowed import code_text, consumer_room, write_refusals
from .client import Client

INVALID = 0x80000000
RTR_ONLY = 0xFD  # TPDO transmission type: sampled and sent on a remote request


@dataclass
class Pdo:
    comm: int      # 0x14xx / 0x18xx
    mapping: int   # 0x16xx / 0x1Axx
    cob: int       # the COB-ID it is enabled with (11 bits)


def _find_pdo(c: Client, tx: bool) -> Pdo | None:
    """The first PDO whose COB-ID, type and mapping the description lets a client write."""
    base = 0x1800 if tx else 0x1400
    for k in range(512):
        comm, mapping = base + k, base + 0x200 + k
        needed = [c.od.find(comm, 1), c.od.find(comm, 2), c.od.find(mapping, 0), c.od.find(mapping, 1)]
        if all(s is not None and s.writable for s in needed):
            cob = (c.number(comm, 1) or 0) & 0x7FF
            default = (0x180 if tx else 0x200) + 0x100 * (k % 4) + c.node_id
            return Pdo(comm, mapping, cob if cob and k < 4 else default)
    return None


def _mappable(c: Client, tx: bool) -> Entry | None:
    access = ("ro", "const", "rwr", "rw") if tx else ("wo", "rww", "rw")
    for e in entries(c):
        if (e.sub.pdo_mapping and e.sub.access in access and e.dtype.is_numeric and e.obj.index >= 0x2000
                and e.dtype.bits <= 64 and (tx or (e.sub.readable and write_cases(e.sub, e.dtype)))):
            return e
    return None


def _map_word(e: Entry) -> bytes:
    return (e.obj.index << 16 | e.sub.subindex << 8 | e.dtype.bits).to_bytes(4, "little")


class Configured:
    """A PDO mapped to one entry with a transmission type, in the CiA 301 sequence; the
    original parameters are written back on exit."""

    def __init__(self, c: Client, pdo: Pdo, e: Entry, trans_type: int) -> None:
        self.c, self.pdo, self.e, self.trans_type = c, pdo, e, trans_type
        self.ok = False
        self.failed: tuple[str, int] = ("", 0)  # the step that aborted, and its code

    def __enter__(self) -> Configured:
        c, p = self.c, self.pdo
        self.saved = {(p.comm, 1): c.upload(p.comm, 1)[0], (p.comm, 2): c.upload(p.comm, 2)[0],
                      (p.mapping, 0): c.upload(p.mapping, 0)[0], (p.mapping, 1): c.upload(p.mapping, 1)[0]}
        steps = [("invalidate", p.comm, 1, (p.cob | INVALID).to_bytes(4, "little")),
                 ("mapping sub 0 = 0", p.mapping, 0, b"\x00"),
                 (f"map {self.e.label}", p.mapping, 1, _map_word(self.e)),
                 ("mapping sub 0 = 1", p.mapping, 0, b"\x01")]
        steps += [(f"transmission type {self.trans_type}", p.comm, 2, bytes([self.trans_type])),
                  ("validate", p.comm, 1, p.cob.to_bytes(4, "little"))]
        for what, index, sub, data in steps:
            code = c.download(index, sub, data)
            if code:
                self.failed = (what, code)
                return self
        self.ok = True
        return self

    def finding(self, what: str) -> str:
        """The step that aborted, as a finding about `what` (the PDO)."""
        return f"{what}: {self.failed[0]} aborted 0x{self.failed[1]:08X}"

    def __exit__(self, *exc: object) -> None:
        c, p = self.c, self.pdo
        c.nmt("PRE-OPERATIONAL")
        c.download(p.comm, 1, (p.cob | INVALID).to_bytes(4, "little"))
        c.download(p.mapping, 0, b"\x00")
        for key in ((p.mapping, 1), (p.mapping, 0), (p.comm, 2), (p.comm, 1)):  # the CiA 301 order again
            data = self.saved[key]
            if data is not None:
                c.download(*key, data)


def _setup(c: Client, check: Check, tx: bool) -> tuple[Pdo, Entry] | None:
    pdo, e = _find_pdo(c, tx), _mappable(c, tx)
    if pdo is None or e is None:
        check.skipped = f"no {'T' if tx else 'R'}PDO the description lets a client map, or nothing to map"
        return None
    return pdo, e


def check_pdo_sequence(c: Client) -> Check:
    check = Check("PDO mapping: the CiA 301 sequence works, wrong steps abort")
    found = _setup(c, check, tx=True)
    if found is None:
        return check
    pdo, e = found
    with Configured(c, pdo, e, 1) as conf:
        check.expect(conf.ok, conf.finding(f"0x{pdo.mapping:04X}"))
        code = c.download(pdo.mapping, 0, b"\x00")
        check.expect(code != 0, f"0x{pdo.mapping:04X}sub0 = 0 while the PDO is valid was accepted")
        c.download(pdo.comm, 1, (pdo.cob | INVALID).to_bytes(4, "little"))
        c.download(pdo.mapping, 0, b"\x00")
        unmappable = next((x for x in entries(c) if not x.sub.pdo_mapping and x.dtype.is_numeric
                           and x.obj.index >= 0x2000 and not is_command(x)), None)
        if unmappable is not None:
            code = c.download(pdo.mapping, 1, _map_word(unmappable))
            check.expect(code == NOT_MAPPABLE, f"mapping {unmappable.label} (not mappable) gave "
                                                f"{code_text(code)}, expected 0x{NOT_MAPPABLE:08X}")
        sub2 = c.od.find(pdo.mapping, 2)
        if e.dtype.bits == 64 and sub2 is not None and sub2.writable:
            c.download(pdo.mapping, 1, _map_word(e))
            c.download(pdo.mapping, 2, _map_word(e))
            code = c.download(pdo.mapping, 0, b"\x02")
            check.expect(code in (MAP_TOO_LONG, INCOMPATIBLE),
                         f"128 bits mapped gave {code_text(code)}, "
                         f"expected 0x{MAP_TOO_LONG:08X} or 0x{INCOMPATIBLE:08X}")
    return check


def check_tpdo_types(c: Client) -> Check:
    check = Check("TPDOs by transmission type: SYNC, event timer, RTR")
    found = _setup(c, check, tx=True)
    if found is None:
        return check
    pdo, e = found
    c.watch(pdo.cob)
    sync_cob = (c.number(SYNC_COB_ID) or 0x80) & 0x7FF if c.od.find(SYNC_COB_ID) is not None else 0x80
    with Configured(c, pdo, e, 1) as conf:
        if conf.ok:
            c.nmt("OPERATIONAL")
            value = c.upload(*e.key)[0]
            sent = time.monotonic()
            c.send(sync_cob, b"")
            got = c.wait_frame(sent, lambda cob, d: cob == pdo.cob)
            check.expect(got is not None and got == value, f"type 1: after a SYNC got {got!r}, the entry is {value!r}")
    timer = c.od.find(pdo.comm, 5)
    if timer is not None and timer.writable:
        with Configured(c, pdo, e, 0xFE) as conf:
            if conf.ok and c.download(pdo.comm, 5, (100).to_bytes(2, "little")) == 0:
                c.nmt("OPERATIONAL")
                medians = c.period(pdo.cob, 0.5, lambda m: 70 <= m <= 150)
                check.expect(medians[-1] is not None and 70 <= medians[-1] <= 150,
                             f"type 254, event timer 100 ms: a TPDO every {medians} ms")
            c.download(pdo.comm, 5, b"\x00\x00")
    with Configured(c, pdo, e, RTR_ONLY) as conf:
        if not conf.ok:
            what, code = conf.failed
            # A node may refuse RTR transmission (CiA recommends against RTR): then with 0x06090030.
            check.expect(what.startswith("transmission type") and code == RANGE,
                         f"type 0xFD: {what} aborted {code_text(code)}, only 0x{RANGE:08X} (no RTR) allowed")
        else:
            c.nmt("OPERATIONAL")
            sent = time.monotonic()
            c.send(pdo.cob, b"", remote=True)
            got = c.wait_frame(sent, lambda cob, d: cob == pdo.cob)
            check.expect(got is not None, "type 0xFD: no TPDO after a remote request")
    return check


WINDOW_US, SYNC_EVERY_US = 10000, 50000


def _late(syncs: list[float], tpdos: list[float]) -> list[str]:
    """SYNCs (but the last, whose TPDO may still come) without a TPDO within the window."""
    late = []
    for at in syncs[:-1]:
        after = [t for t in tpdos if t >= at]
        delay = 1000 * (after[0] - at) if after else None
        if delay is None or delay > WINDOW_US / 1000:
            late.append("none" if delay is None else f"{delay:.1f} ms")
    return late


def check_sync_window(c: Client) -> Check:
    check = Check("SYNC window (0x1007): a type 1 TPDO follows each SYNC the node produces within 10 ms")
    needed = [c.od.find(index) for index in (SYNC_COB_ID, SYNC_PERIOD, SYNC_WINDOW)]
    found = _setup(c, check, tx=True)
    if found is None or not all(s is not None and s.writable for s in needed):
        check.skipped = check.skipped or "0x1005, 0x1006 and 0x1007 are not all writable"
        return check
    pdo, e = found
    saved = {index: c.upload(index, 0)[0] for index in (SYNC_COB_ID, SYNC_PERIOD, SYNC_WINDOW)}
    sync_id = (c.number(SYNC_COB_ID) or 0x80) & CAN_ID_MASK
    c.watch(sync_id)
    c.watch(pdo.cob)
    check.expect(c.download(SYNC_WINDOW, 0, WINDOW_US.to_bytes(4, "little")) == 0, "0x1007 = 10000 us refused")
    with Configured(c, pdo, e, 1) as conf:
        check.expect(conf.ok, conf.finding(f"TPDO 0x{pdo.comm:04X}"))
        if conf.ok:
            c.nmt("OPERATIONAL")
            c.download(SYNC_PERIOD, 0, SYNC_EVERY_US.to_bytes(4, "little"))
            if c.download(SYNC_COB_ID, 0, (sync_id | SYNC_GENERATE).to_bytes(4, "little")) == RANGE:
                check.skipped = NO_SYNC_PRODUCER
                late = []
            else:
                late = _window(c, sync_id, pdo.cob)
            check.expect(not late, f"SYNCs without their TPDO within the window: {late[:5]}")
            c.download(SYNC_COB_ID, 0, saved[SYNC_COB_ID] or sync_id.to_bytes(4, "little"))
            c.download(SYNC_PERIOD, 0, bytes(4))
    for index in (SYNC_PERIOD, SYNC_WINDOW):
        if saved[index] is not None:
            c.download(index, 0, saved[index] or b"")
    return check


def _window(c: Client, sync_id: int, tpdo: int) -> list[str]:
    """SYNCs the node produces without the TPDO within the window (measured again, up to three
    windows, when the machine stalled)."""
    late: list[str] = []
    for _ in range(3):  # a machine stalled between the two frames: measured again
        start = time.monotonic()
        time.sleep(0.5)  # a measuring window, not a wait for an event
        syncs, tpdos = c.received_since(start, sync_id), c.received_since(start, tpdo)
        late = _late(syncs, tpdos) if len(syncs) >= 3 else ["fewer than 3 SYNCs in 0.5 s"]
        if not late:
            break
    return late


# ---- EMCY -----------------------------------------------------------------------------------


def _rpdo_and_emcy(c: Client, check: Check) -> tuple[Pdo, Entry, int] | None:
    """An RPDO to provoke length errors with, its entry, and the EMCY CAN-ID (watched); None, the
    check skipped, without them."""
    found = _setup(c, check, tx=False)
    emcy = c.emcy_cob()
    if found is None:
        return None
    if emcy is None or emcy & INVALID:
        check.skipped = "EMCY disabled (0x1014 bit 31)"
        return None
    c.watch(emcy & CAN_ID_MASK)
    return found[0], found[1], emcy & CAN_ID_MASK


def _short_rpdo(c: Client, pdo: Pdo, size: int, matches: Callable[[int, bytes], bool]) -> bytes | None:
    """Operational, then the RPDO one byte shorter than its mapping (`size` bytes): the frame after
    it that `matches` (CAN-ID, data) accepts, or None."""
    c.nmt("OPERATIONAL")
    sent = time.monotonic()
    c.send(pdo.cob, bytes(size - 1))
    return c.wait_frame(sent, matches)


def check_emcy(c: Client) -> Check:
    check = Check("EMCY on an RPDO length error; error register and 0x1003 follow; reset EMCY")
    found = _rpdo_and_emcy(c, check)
    if found is None:
        return check
    pdo, e, cob = found
    size = e.dtype.bits // 8 or 1
    before = c.number(ERROR_REGISTER) or 0  # an error already active: no error reset EMCY is due
    with Configured(c, pdo, e, 0xFF) as conf:
        if not conf.ok:
            check.expect(False, conf.finding(f"RPDO 0x{pdo.comm:04X}"))
            return check
        frame = _short_rpdo(c, pdo, size, lambda got, d: got == cob and d[:2] != b"\x00\x00")
        check.expect(frame is not None and int.from_bytes(frame[:2], "little") == EMCY_RPDO_LENGTH,
                     f"short RPDO: EMCY {frame!r}, want code 0x{EMCY_RPDO_LENGTH:04X}")
        if frame is None:
            return check
        register = c.upload(ERROR_REGISTER, 0)[0]
        check.expect(frame[2] != 0 and register == frame[2:3],
                     f"error register: EMCY says {frame[2]:#04x}, 0x1001 reads {register!r}")
        if c.od.find(ERROR_HISTORY, 1) is not None:
            count, first = c.upload(ERROR_HISTORY, 0)[0], c.upload(ERROR_HISTORY, 1)[0]
            check.expect(count is not None and count != b"\x00" and first is not None
                         and int.from_bytes(first[:2], "little") == EMCY_RPDO_LENGTH,
                         f"0x1003: {count!r} errors, newest {first!r}")
            history = c.od.find(ERROR_HISTORY, 0)
            if history is not None and history.writable and not c.settings.destructive:
                check.notes.append("0x1003 sub 0 = 0 (clearing the error history) not tried: run with "
                                   "--allow destructive")
            elif history is not None and history.writable:
                code = c.download(ERROR_HISTORY, 0, b"\x01")
                check.expect(code == RANGE, f"0x1003sub0 = 1 gave {code_text(code)}, expected 0x{RANGE:08X}")
                check.expect(c.download(ERROR_HISTORY, 0, b"\x00") == 0 and c.upload(ERROR_HISTORY, 0)[0] == b"\x00",
                             "0x1003sub0 = 0 did not clear the history")
        sent = time.monotonic()
        c.send(pdo.cob, bytes(size))
        if before:
            _still_active(c, check, before)
            return check
        frame = c.wait_frame(sent, lambda got, d: got == cob)
        check.expect(frame is not None and frame[:2] == b"\x00\x00", f"right length again: EMCY {frame!r}, want 0x0000")
    return check


def _still_active(c: Client, check: Check, before: int) -> None:
    """The error provoked is gone, one the node had before is not: CiA 301 requires the error reset
    EMCY only when no error is left, so none is awaited; 0x1001 must be back to what it was."""
    time.sleep(0.2)  # no frame to wait for: the node's own errors decide 0x1001
    register = c.number(ERROR_REGISTER)
    check.expect(register == before, f"right length again: 0x1001 reads {register}, 0x{before:02X} before the check")
    check.notes.append(f"0x1001 was 0x{before:02X} before the check (an error of the node's own): no error reset "
                       "EMCY awaited")


def check_emcy_inhibit(c: Client) -> Check:
    check = Check("EMCY inhibit time (0x1015): two errors in a row, the second EMCY not within 100 ms")
    inhibit = c.od.find(EMCY_INHIBIT)
    found = _setup(c, check, tx=False)
    emcy = c.emcy_cob()
    if found is None or inhibit is None or not inhibit.writable or emcy is None or emcy & INVALID:
        check.skipped = check.skipped or "no writable 0x1015, or EMCY disabled"
        return check
    pdo, e = found
    cob = emcy & 0x7FF
    c.watch(cob)
    if c.number(ERROR_REGISTER):
        check.skipped = ("an error of the node's own is active (0x1001 is not 0), so the error reset EMCY that "
                         "would be timed against the error's is not due (CiA 301)")
        return check
    saved = c.upload(EMCY_INHIBIT, 0)[0]
    check.expect(c.download(EMCY_INHIBIT, 0, (1000).to_bytes(2, "little")) == 0, "0x1015 = 1000 (100 ms) refused")
    size = e.dtype.bits // 8 or 1
    with Configured(c, pdo, e, 0xFF) as conf:
        if conf.ok:
            c.nmt("OPERATIONAL")
            start = time.monotonic()
            c.send(pdo.cob, bytes(size - 1))  # an error (EMCY 0x8210) ...
            c.send(pdo.cob, bytes(size))  # ... and at once its reset (EMCY 0x0000)
            c.wait_frame(start, lambda got, d: got == cob and d[:2] == b"\x00\x00")
            stamps = c.received_since(start, cob)
            gap = 1000 * (stamps[1] - stamps[0]) if len(stamps) >= 2 else None
            check.expect(gap is not None and gap >= 90, f"two EMCYs {gap and round(gap)} ms apart, inhibit 100 ms")
    c.download(EMCY_INHIBIT, 0, saved or b"\x00\x00")
    return check


# Error register bits (0x1001): generic, and communication for the 0x81xx/0x82xx codes.
REG_GENERIC, REG_COMMUNICATION = 0x01, 0x10


def _register_follows(c: Client, check: Check, frame: bytes | None, code: int, when: str) -> None:
    """An EMCY of `code` came, its error register has the generic and communication bits, and
    0x1001 reads the same."""
    check.expect(frame is not None, f"{when}: no EMCY 0x{code:04X}")
    if frame is not None:
        register = c.number(ERROR_REGISTER)
        want = REG_GENERIC | REG_COMMUNICATION
        check.expect(frame[2] & want == want, f"{when}: EMCY register 0x{frame[2]:02X}, want bits 0x{want:02X}")
        check.expect(register == frame[2], f"{when}: 0x1001 reads {register}, the EMCY said 0x{frame[2]:02X}")


def _heartbeat_error(c: Client, check: Check, cob: int) -> None:
    """A second error while the first is active: a watched heartbeat stops (EMCY 0x8130); when it
    comes back, 0x1001 still shows the first error."""
    other = played_node(c, 1)
    saved = c.upload(CONSUMER_HEARTBEAT, 1)[0]
    if c.download(CONSUMER_HEARTBEAT, 1, (other << 16 | 200).to_bytes(4, "little")) != 0:
        check.expect(False, "0x1016sub1 refused")
        return
    for _ in range(3):
        c.send(HEARTBEAT + other, b"\x05")
        time.sleep(0.05)  # pacing the heartbeats of the node played here
    stopped = time.monotonic()
    frame = c.wait_frame(stopped, lambda got, d: got == cob and d[:2] == EMCY_HEARTBEAT.to_bytes(2, "little"))
    _register_follows(c, check, frame, EMCY_HEARTBEAT, "a watched heartbeat stopped")
    c.send(HEARTBEAT + other, b"\x05")  # back: its error is gone, the RPDO's is not
    c.download(CONSUMER_HEARTBEAT, 1, saved or bytes(4))
    register = c.number(ERROR_REGISTER) or 0
    want = REG_GENERIC | REG_COMMUNICATION
    check.expect(register & want == want, f"heartbeat back, the RPDO still too short: 0x1001 reads 0x{register:02X}")


def check_error_register(c: Client) -> Check:
    check = Check("error register 0x1001 follows the active errors; EMCY error reset when the last is gone")
    found = _rpdo_and_emcy(c, check)
    if found is None:
        return check
    pdo, e, cob = found
    size = e.dtype.bits // 8 or 1
    consumer = c.od.find(CONSUMER_HEARTBEAT, 1)
    before = c.number(ERROR_REGISTER) or 0
    with Configured(c, pdo, e, 0xFF) as conf:
        if not conf.ok:
            check.expect(False, conf.finding(f"RPDO 0x{pdo.comm:04X}"))
            return check
        frame = _short_rpdo(c, pdo, size, lambda got, d: got == cob and d[:2] == EMCY_RPDO_LENGTH.to_bytes(2, "little"))
        _register_follows(c, check, frame, EMCY_RPDO_LENGTH, "short RPDO")
        if consumer is not None and consumer.writable and consumer_room(c, 1):
            check.notes.append(f"a second error (a watched heartbeat that stops) not tried: {consumer_room(c, 1)}")
        elif consumer is not None and consumer.writable and c.settings.destructive:
            _heartbeat_error(c, check, cob)
            c.nmt("OPERATIONAL")  # 0x1029 may have left it
        elif consumer is not None and consumer.writable:
            check.notes.append("a second error (a watched heartbeat that stops) not tried: it plays another "
                               "node's heartbeat, run with --allow destructive")
        sent = time.monotonic()
        c.send(pdo.cob, bytes(size))
        if before:
            _still_active(c, check, before)
            return check
        frame = c.wait_frame(sent, lambda got, d: got == cob and d[:2] == b"\x00\x00")
        check.expect(frame is not None, "right length again, no error active: no error reset EMCY (0x0000)")
        register = c.number(ERROR_REGISTER)
        check.expect(frame is None or frame[2] == 0, f"error reset EMCY with register 0x{(frame or bytes(3))[2]:02X}")
        check.expect(register == 0, f"no error active: 0x1001 reads {register}")
    return check


# ---- 0x1010 / 0x1011 ------------------------------------------------------------------------


def check_signatures(c: Client) -> Check:
    check = Check("0x1010/0x1011 refuse a wrong signature (0x08000020)")
    for index, word in ((STORE, b"save"), (RESTORE, b"load")):
        if c.od.find(index, 1) is not None:
            code = c.download(index, 1, b"nope")
            check.expect(code == SIGNATURE, f"0x{index:04X}sub1 without '{word.decode()}' gave {code_text(code)}, "
                                                f"expected 0x{SIGNATURE:08X}")
    if not check.passed and not check.failures:
        check.skipped = "no 0x1010/0x1011 sub 1"
    return check


def _reset(c: Client, check: Check) -> None:
    sent = c.nmt("RESET")
    check.expect(c.wait_frame(sent, lambda cob, d: cob == 0x700 + c.node_id and d[:1] == b"\x00") is not None,
                 "reset node: no boot-up")


def _stored_numbers(c: Client) -> list[Entry]:
    """Writable, readable numbers the options put in a stored group (commands and objects with
    steps of their own left out)."""
    stored = c.settings.stored or frozenset()
    found = [e for e in entries(c) if e.key in stored and e.sub.writable and e.sub.readable and e.dtype.is_numeric
             and e.obj.index not in ACTIVE and not is_command(e) and write_cases(e.sub, e.dtype)]
    return sorted(found, key=lambda e: e.obj.index < 0x2000)  # the application's first: no CiA 301 rules


def _other_value(c: Client, e: Entry, present: bytes | None) -> bytes | None:
    """A value `e` takes (within its limits, none CiA 301 lets the node refuse) that is neither the
    described one nor `present`."""
    default = expected_bytes(c.od, e.sub, e.dtype, c.node_id)
    return next((d for d, expect in write_cases(e.sub, e.dtype) if expect == "ODG_OK"
                 and d not in (default, present) and not write_refusals(c, *e.key, d)), None)


def check_store_restore(c: Client) -> Check:
    """'save' keeps a value across a reset node, 'load' brings the defaults back"""
    check = Check("'save' keeps a stored value across a reset node; 'load' and a reset node bring the described "
                  "values back")
    if c.od.find(STORE, 1) is None or c.od.find(RESTORE, 1) is None:
        check.skipped = "no 0x1010/0x1011 sub 1"
        return check
    if c.settings.stored is None:
        check.skipped = ("a description does not say which entries 0x1010 stores: name them with --options "
                         "(a placement options file with a persist: storage)")
        return check
    stored = _stored_numbers(c)
    if not stored:
        check.skipped = "the options put no writable number (outside the communication objects) in a stored group"
        return check
    snapshot = {e.key: c.upload(*e.key)[0] for e in stored}
    # the first stored entry that has a valid value other than the described and the present one
    picked = next(((e, d) for e in stored if (d := _other_value(c, e, snapshot[e.key])) is not None), None)
    if picked is None:
        check.skipped = f"{stored[0].label}: no valid value other than the described and the present one"
        return check
    target, value = picked
    check.expect(c.download(*target.key, value) == 0, f"{target.label}: write refused")
    check.expect(c.download(STORE, 1, SAVE) == 0, "0x1010sub1 'save' refused")
    _reset(c, check)
    back = c.upload(*target.key)[0]
    check.expect(back == value, f"{target.label}: saved {value.hex()}, after reset node {_hex(back)}")
    check.expect(c.download(RESTORE, 1, LOAD) == 0, "0x1011sub1 'load' refused")
    _reset(c, check)
    for e in stored:  # after a restore the user allowed, the described values are the ones in force
        back, want = c.upload(*e.key)[0], expected_bytes(c.od, e.sub, e.dtype, c.node_id)
        check.expect(want is None or back == want, f"{e.label}: after 'load' and reset node {_hex(back)}, "
                                                   f"described {_hex(want)}")
    for key, data in snapshot.items():  # put back what was there, and store it again
        if data is not None:
            c.download(*key, data)
    check.expect(c.download(STORE, 1, SAVE) == 0, "0x1010sub1 'save' of the values put back refused")
    return check
