"""`odgen roundtrip`: a node built from the description, on a CAN bus, checked by python canopen.

The client is python canopen's RemoteNode loaded from the same description (written as
EDS by odgen, so XDD inputs work too). Expected values come from the model, not from the
node: uploads equal the described defaults, downloads within limits read back, the CiA 301
abort codes come back where they must, NMT and heartbeat behave, PDOs remapped by SDO carry
the right values, and 0x1010/0x1011 store and restore across a restart.
"""

from __future__ import annotations

import logging
import statistics
import subprocess
import tempfile
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..place.placement import COMMAND_CLASS, Placement, Placements
from ..model.expect import expected_bytes, write_cases
from ..conformance import CHECK_IDS as BATTERY_IDS
from ..conformance import Selection
from ..conformance import run_checks as battery
from ..conformance.allowed import write_refusals
from ..conformance.client import Client, Settings
from ..conformance.verdict import ABORTS, ACTIVE, NO_OBJECT, NO_SUB, WRITE_ONLY, Check
from ..model import Obj, ObjectDictionary, Sub
from ..model.cia301 import (
    ABORT_CODES, COMMUNICATION_AREA, LOAD, PRODUCER_HEARTBEAT, RESTORE, RPDO_COMM, RPDO_MAPPING, SAVE, STORE, TPDO_COMM,
    TPDO_MAPPING, unused_manufacturer_index)
from ..model.datatypes import BASIC_TYPES, UNSIGNED16, DataType
from ..model.wire import wire_bytes

NO_BLOCK = ABORT_CODES["ODG_ABORT_COMMAND"]  # a server without block transfer answers its initiate so
BOOT_TIMEOUT = 30.0  # waits end at the boot-up: generous for a loaded machine


@dataclass
class Entry:
    obj: Obj
    sub: Sub
    dtype: DataType
    placement: Placement

    @property
    def label(self) -> str:
        return f"0x{self.obj.index:04X}sub{self.sub.subindex}"


class Session:
    """One node process, and the conformance battery's client (one bus harness) on `iface`."""

    def __init__(self, od: ObjectDictionary, placements: Placements, program: Path,
                 iface: str, node_id: int, workdir: Path) -> None:
        self.od, self.program, self.iface, self.node_id = od, program, iface, node_id
        self.workdir = workdir
        self.nv = workdir / "node.nv"
        self.entries = _entries(od, placements)
        # odgen's own node, freshly built: every check may run and every value is the described one
        stored = frozenset(key for key, placement in placements.items() if placement.group)
        self.client = Client(od, iface, node_id, workdir, Settings(destructive=True, fresh=True, stored=stored))
        self.canopen, self.network, self.node = self.client.canopen, self.client.network, self.client.node
        self.booted = threading.Event()
        # (monotonic time seen, NMT state, the frame's receive time stamp): a loaded machine delays
        # the callback, not the socket's time stamp, so periods are measured on the stamps
        self.heartbeats: list[tuple[float, int, float]] = []
        self.network.subscribe(0x700 + node_id, self._on_heartbeat)
        self.process: subprocess.Popen[bytes] | None = None

    def _on_heartbeat(self, can_id: int, data: bytearray, timestamp: float) -> None:
        if data:
            self.heartbeats.append((time.monotonic(), data[0], timestamp))
            if data[0] == 0:
                self.booted.set()

    def start(self) -> bool:
        self.booted.clear()
        log = open(self.workdir / "node.log", "ab")  # noqa: SIM115 - closed with the process
        cmd = [str(self.program), "--iface", self.iface, "--node-id", str(self.node_id), "--nv", str(self.nv)]
        self.process = subprocess.Popen(cmd, stdout=log, stderr=log)
        log.close()
        return self.booted.wait(BOOT_TIMEOUT)

    def stop(self) -> None:
        if self.process is not None and self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(5)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.process = None

    def close(self) -> None:
        self.stop()
        self.client.close()

    # -- SDO: the conformance client's ------------------------------------------------------

    def upload(self, index: int, sub: int) -> tuple[bytes | None, int]:
        """(data, 0) or (None, abort code); NO_ANSWER when the node did not answer."""
        return self.client.upload(index, sub)

    def download(self, index: int, sub: int, data: bytes) -> int:
        return self.client.download(index, sub, data)


def _entries(od: ObjectDictionary, placements: Placements) -> list[Entry]:
    out = []
    for obj in od.sorted_objects():
        for sub in obj.sorted_subs():
            dtype = BASIC_TYPES.get(sub.data_type or 0)
            if dtype is not None and (obj.index, sub.subindex) in placements and obj.index >= COMMUNICATION_AREA[0]:
                out.append(Entry(obj, sub, dtype, placements[(obj.index, sub.subindex)]))
    return out


def _is_store(e: Entry) -> bool:
    return e.placement.storage == COMMAND_CLASS


# ---- the checks ------------------------------------------------------------------------------


def check_uploads(s: Session) -> Check:
    check = Check("upload every readable entry and compare with the description")
    for e in s.entries:
        if _is_store(e):
            continue
        data, code = s.upload(e.obj.index, e.sub.subindex)
        if not e.sub.readable:
            check.expect(code == WRITE_ONLY, f"{e.label}: read of write-only gave 0x{code:08X}")
            continue
        want = expected_bytes(s.od, e.sub, e.dtype, s.node_id, e.placement.capacity)
        if want is None:
            check.expect(code == 0, f"{e.label}: upload aborted 0x{code:08X}")
        else:
            check.expect(data == want, f"{e.label}: uploaded {_hex(data)}, described {_hex(want)}")
    return check


def check_downloads(s: Session) -> Check:
    check = Check("download limits and a middle value, read back; aborts out of range and for ro")
    for e in s.entries:
        if _is_store(e) or e.obj.index in ACTIVE or not e.dtype.is_numeric:
            continue
        if not e.sub.writable:
            data = expected_bytes(s.od, e.sub, e.dtype, s.node_id) or wire_bytes(0, e.dtype)
            code = s.download(e.obj.index, e.sub.subindex, data)
            check.expect(code == ABORTS["ODG_ABORT_READ_ONLY"], f"{e.label}: write to {e.sub.access} gave 0x{code:08X}")
            continue
        original, _ = s.upload(e.obj.index, e.sub.subindex) if e.sub.readable else (None, 0)
        for data, expect in write_cases(e.sub, e.dtype):
            code = s.download(e.obj.index, e.sub.subindex, data)
            if code != ABORTS[expect] and code in write_refusals(s.client, e.obj.index, e.sub.subindex, data):
                check.expect(True, "")  # refused for a reason of CiA 301's (0x1019 = 255, say), as it must be
                continue
            check.expect(code == ABORTS[expect], f"{e.label}: download {_hex(data)} gave 0x{code:08X}, "
                                                 f"expected 0x{ABORTS[expect]:08X}")
            if code == 0 and e.sub.readable:
                back, _ = s.upload(e.obj.index, e.sub.subindex)
                check.expect(back == data, f"{e.label}: wrote {_hex(data)}, read back {_hex(back)}")
        if original is not None:
            s.download(e.obj.index, e.sub.subindex, original)
    return check


def check_unknown(s: Session) -> Check:
    check = Check("unknown index and sub-index abort 0x06020000 / 0x06090011")
    missing = unused_manufacturer_index(s.od.objects)
    check.expect(s.upload(missing, 0)[1] == NO_OBJECT, f"0x{missing:04X}: no 0x06020000")
    obj = s.od.sorted_objects()[0]
    absent = next(i for i in range(0xFE, 0, -1) if i not in obj.subs)
    check.expect(s.upload(obj.index, absent)[1] == NO_SUB, f"0x{obj.index:04X}sub{absent}: no 0x06090011")
    return check


def check_strings(s: Session) -> Check:
    check = Check("segmented and block transfer of strings and domains")
    for e in s.entries:
        if e.dtype.kind not in ("vstring", "ostring", "domain") or not (e.sub.writable and e.sub.readable):
            continue
        size = _capacity(s, e)
        if size == 0:
            continue
        original, _ = s.upload(e.obj.index, e.sub.subindex)
        data = bytes((0x41 + i % 26) for i in range(size))
        code = s.download(e.obj.index, e.sub.subindex, data)
        back, _ = s.upload(e.obj.index, e.sub.subindex)
        check.expect(code == 0 and back == data, f"{e.label}: segmented {size} bytes came back {_hex(back)}")
        down, up = _block_round_trip(s, e, data[::-1], data)
        for name, worked in (("download", down), ("upload", up)):
            if worked is None:
                _note(check, f"block {name} not supported: its initiate was answered with abort 0x{NO_BLOCK:08X}, "
                             "as CiA 301 allows a server without block transfer")
            else:
                check.expect(worked, f"{e.label}: block {name} of {size} bytes")
        if original is not None:  # the battery's uploads that follow compare with the description
            s.download(e.obj.index, e.sub.subindex, original)
    if not check.passed and not check.failures:
        check.skipped = "no writable string or domain"
    return check


def _note(check: Check, text: str) -> None:
    if text not in check.notes:
        check.notes.append(text)


def _capacity(s: Session, e: Entry) -> int:
    data, _ = s.upload(e.obj.index, e.sub.subindex)
    described = expected_bytes(s.od, e.sub, e.dtype, s.node_id) or b""
    return max(len(described), e.placement.capacity or 0, len(data or b""))


def _block_round_trip(s: Session, e: Entry, data: bytes, held: bytes) -> tuple[bool | None, bool | None]:
    """A block download of `data`, then a block upload that must bring back what the entry holds
    then (`data`, or `held` when the download was not supported): whether each worked, None for
    one whose initiate the node answered with abort 0x05040001 (CiA 301: no block transfer)."""
    down: bool | None = False
    try:
        with _block_open(s, e, "wb", size=len(data)) as f:
            if f is None:
                down, data = None, held
            else:
                f.write(data)
                down = True
    except (s.canopen.SdoAbortedError, s.canopen.SdoCommunicationError):
        return False, False
    try:
        with _block_open(s, e, "rb") as f:
            return down, None if f is None else bytes(f.read()) == data
    except (s.canopen.SdoAbortedError, s.canopen.SdoCommunicationError):
        return down, False


@contextmanager
def _block_open(s: Session, e: Entry, mode: str, **kw: int) -> Iterator[Any]:
    """The block transfer's stream, or None when the node refused its initiate with 0x05040001."""
    try:
        f = s.node.sdo.open(e.obj.index, e.sub.subindex, mode, block_transfer=True, **kw)
    except s.canopen.SdoAbortedError as err:
        if err.code != NO_BLOCK:
            raise
        yield None
        return
    with f:
        yield f


def check_nmt(s: Session) -> Check:
    check = Check("NMT transitions and heartbeat period")
    hb = s.od.find(PRODUCER_HEARTBEAT)
    if hb is None or not hb.writable:
        check.skipped = "no writable 0x1017"
        return check
    original, _ = s.upload(PRODUCER_HEARTBEAT, 0)
    check.expect(s.download(PRODUCER_HEARTBEAT, 0, wire_bytes(100, UNSIGNED16)) == 0,
                 "0x1017 = 100 ms refused")
    for command, state in (("OPERATIONAL", 0x05), ("STOPPED", 0x04), ("PRE-OPERATIONAL", 0x7F)):
        s.node.nmt.state = command
        check.expect(_state_seen(s, state), f"{command}: heartbeat state 0x{state:02X} not seen")
    period = _period(s)
    check.expect(period is not None and 80 <= period <= 130, f"heartbeat period {period} ms, want 100")
    s.booted.clear()
    s.node.nmt.state = "RESET"
    check.expect(s.booted.wait(BOOT_TIMEOUT), "reset node: no boot-up")
    if original is not None:
        s.download(PRODUCER_HEARTBEAT, 0, original)
    return check


def _state_seen(s: Session, state: int) -> bool:
    start = time.monotonic()
    return _wait(lambda: any(t > start and b == state for t, b, _ in list(s.heartbeats)))


def _period(s: Session) -> float | None:
    start = time.monotonic()
    time.sleep(0.65)
    times = [stamp for t, _, stamp in list(s.heartbeats) if t > start]
    gaps = [1000 * (b - a) for a, b in zip(times, times[1:], strict=False)]
    return statistics.median(gaps) if gaps else None


def check_pdos(s: Session) -> Check:
    check = Check("remap a TPDO and an RPDO by SDO, SYNC, compare values")
    tpdo_var = _mappable(s, tpdo=True)
    rpdo_var = _mappable(s, tpdo=False)
    if _remappable(s, TPDO_COMM, TPDO_MAPPING) and tpdo_var is not None:
        _tpdo(s, check, tpdo_var)
    if _remappable(s, RPDO_COMM, RPDO_MAPPING) and rpdo_var is not None:
        _rpdo(s, check, rpdo_var)
    if not check.passed and not check.failures:
        check.skipped = "no remappable PDO pair with a mappable entry"
    return check


def _remappable(s: Session, comm: int, mapping: int) -> bool:
    """The description lets a client remap this PDO: COB-ID and mapping entries are writable."""
    cob, count, first = s.od.find(comm, 1), s.od.find(mapping, 0), s.od.find(mapping, 1)
    return all(x is not None and x.writable for x in (cob, count, first))


def _mappable(s: Session, tpdo: bool) -> Entry | None:
    access = ("ro", "const", "rwr", "rw") if tpdo else ("wo", "rww", "rw")
    for e in s.entries:
        if (e.sub.pdo_mapping and e.sub.access in access and e.dtype.is_numeric and e.obj.index >= 0x2000
                and (tpdo or (e.sub.readable and write_cases(e.sub, e.dtype)))):
            return e
    return None


def _remap(s: Session, check: Check, pdo, name: str, e: Entry, trans_type: int) -> bool:
    """Map `e` alone into `pdo` by SDO (canopen writes it in the CiA 301 order)."""
    try:
        pdo.read(from_od=False)  # only this map: canopen cannot read multiplexed (MPDO) maps
        pdo.clear()
        pdo.add_variable(e.obj.index, e.sub.subindex)
        pdo.trans_type, pdo.enabled = trans_type, True
        pdo.save()
        return True
    except (s.canopen.SdoAbortedError, s.canopen.SdoCommunicationError) as err:
        check.expect(False, f"{name} remap to {e.label} failed: {err}")
        return False


def _tpdo(s: Session, check: Check, e: Entry) -> None:
    pdo = s.node.tpdo[1]
    if not _remap(s, check, pdo, "TPDO1", e, trans_type=1):
        return
    s.node.nmt.state = "OPERATIONAL"
    time.sleep(0.05)
    before = pdo.timestamp
    s.network.sync.transmit()
    got = _wait(lambda: pdo.timestamp != before)  # the TPDO may arrive before any wait could start
    value, _ = s.upload(e.obj.index, e.sub.subindex)
    check.expect(got and value is not None and bytes(pdo.data) == value,
                 f"TPDO1 on SYNC carried {_hex(bytes(pdo.data) if got else None)}, SDO reads {_hex(value)}")


def _wait(condition: Callable[[], bool], timeout: float = 5.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.01)
    return condition()


def _rpdo(s: Session, check: Check, e: Entry) -> None:
    data = write_cases(e.sub, e.dtype)[1][0]  # the high limit: a value other than the default
    s.node.nmt.state = "PRE-OPERATIONAL"
    pdo = s.node.rpdo[1]
    if not _remap(s, check, pdo, "RPDO1", e, trans_type=255):
        return
    s.node.nmt.state = "OPERATIONAL"
    time.sleep(0.05)
    pdo.data = bytearray(data)
    pdo.transmit()
    time.sleep(0.1)
    value, _ = s.upload(e.obj.index, e.sub.subindex)
    check.expect(value == data, f"RPDO1 sent {_hex(data)} to {e.label}, SDO reads {_hex(value)}")


def check_persistence(s: Session) -> Check:
    check = Check("store (0x1010), restart, kept; restore (0x1011), restart, defaults")
    target = next((e for e in s.entries if e.placement.group and e.sub.writable and e.sub.readable
                   and e.obj.index not in ACTIVE and write_cases(e.sub, e.dtype)
                   and not write_refusals(s.client, e.obj.index, e.sub.subindex, write_cases(e.sub, e.dtype)[1][0])),
                  None)
    if target is None or s.od.find(STORE, 1) is None or s.od.find(RESTORE, 1) is None:
        check.skipped = "no persistent writable entry or no 0x1010/0x1011 sub 1"
        return check
    value = write_cases(target.sub, target.dtype)[1][0]
    default = expected_bytes(s.od, target.sub, target.dtype, s.node_id, target.placement.capacity)
    check.expect(s.download(target.obj.index, target.sub.subindex, value) == 0, f"{target.label}: write refused")
    check.expect(s.download(STORE, 1, SAVE) == 0, "0x1010sub1 'save' refused")
    check.expect(s.download(STORE, 1, b"nope") == ABORT_CODES["ODG_ABORT_DATA_STORE"],
                 "0x1010sub1 without 'save' did not abort 0x08000020")
    s.stop()
    check.expect(s.start(), "no boot-up after restart")
    check.expect(s.upload(target.obj.index, target.sub.subindex)[0] == value, f"{target.label}: not kept")
    check.expect(s.download(RESTORE, 1, LOAD) == 0, "0x1011sub1 'load' refused")
    s.stop()
    check.expect(s.start(), "no boot-up after restart")
    check.expect(s.upload(target.obj.index, target.sub.subindex)[0] == default, f"{target.label}: default not back")
    return check


CHECKS: tuple[tuple[str, Callable[[Session], Check]], ...] = (
    ("roundtrip.uploads", check_uploads), ("roundtrip.downloads", check_downloads),
    ("roundtrip.unknown", check_unknown), ("roundtrip.strings", check_strings), ("roundtrip.pdos", check_pdos),
    ("roundtrip.nmt", check_nmt), ("roundtrip.persistence", check_persistence))
# A round trip's checks, then the conformance battery's against the same node
CHECK_IDS = ("roundtrip.boot-up", *(check_id for check_id, _ in CHECKS), *BATTERY_IDS)


def _hex(data: bytes | None) -> str:
    return "none" if data is None else (data.hex(" ") if len(data) <= 16 else data[:16].hex(" ") + " ...")


@contextmanager
def session(od: ObjectDictionary, placements: Placements, program: Path, iface: str,
            node_id: int) -> Iterator[Session]:
    logging.getLogger("canopen").setLevel(logging.CRITICAL)
    with tempfile.TemporaryDirectory(prefix="odgen-roundtrip-") as tmp:
        s = Session(od, placements, program, iface, node_id, Path(tmp))
        try:
            yield s
        finally:
            s.close()


def run_checks(s: Session, selection: Selection | None = None) -> list[tuple[str, Check]]:
    """Boot the node, run the round trip's checks, then the conformance battery (all of it: the node
    is odgen's own, freshly built), as `selection` keeps them: (check id, verdict) each."""
    if not s.start():
        return [("roundtrip.boot-up", Check("boot-up", failures=[
            f"no boot-up from node {s.node_id} within {BOOT_TIMEOUT} s: "
            + (s.workdir / "node.log").read_text(errors="replace")[-500:]]))]
    results = [("roundtrip.boot-up", Check("boot-up", passed=1))]
    selection = selection or Selection()
    for check_id, step in CHECKS:
        if not selection.keeps(check_id):
            continue
        try:
            s.node.nmt.state = "PRE-OPERATIONAL"
            results.append((check_id, step(s)))
        except Exception as err:  # a client-side failure is a failed check, and the others still run
            results.append((check_id, Check(step.__name__, failures=[f"raised {type(err).__name__}: {err}"])))
    if any(selection.keeps(check_id) for check_id in BATTERY_IDS):
        results += [(r.id, r.check) for r in battery(s.client, selection)]
    return results
