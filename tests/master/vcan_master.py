"""End to end on vcan0: the master program (runtime/linux/odg_master_main.c) boots odgen slaves.

    python tests/master/vcan_master.py PLAN.json        (inside tools/vcan/run.py)

PLAN.json names the master program and its node-id, the slave programs by node-id, the DCFs
`odgen network` wrote (the master's and each slave's) by node-id, the PDO wiring ([producer,
TPDO, consumer, RPDO] each), the node-id powered up late, the node-id reset by NMT, the node-id
whose identity the master expects wrong and the node-id of the LSS slave started without one.
Checks, with python canopen: every good slave reaches operational with each value its DCF
configures (a ParameterValue, read by python canopen) in place (uploaded and compared), with
status 2 in the master's 0x5F81; the wrong one stays pre-operational and its status reads 'M'
by SDO; the late one is configured when it comes; the one without node-id gets its node-id by
LSS fastscan and is configured; data written on one side of each wired PDO reaches the other
under the SYNC the master produces (its 0x1005/0x1006, set by the network file: this script
sends none); a slave reset by NMT is configured again. Prints "vcan master: ok" last and exits 0.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

import canopen
from canopen.sdo.exceptions import SdoAbortedError, SdoCommunicationError

CHANNEL = os.environ.get("ODGEN_VCAN_IFACES", "vcan0").split(",")[0]
DEADLINE = 20.0
STATUS = 0x5F81
SYNC = 0x80
RPDO_MAPPING, TPDO_MAPPING = 0x1600, 0x1A00


class States:
    """The NMT state each node's heartbeat said last (boot-up: 0), and the SYNCs heard."""

    def __init__(self, net: canopen.Network) -> None:
        self.state: dict[int, int] = {}
        self.bootups: dict[int, int] = {}
        self.syncs = 0
        self.lock = threading.Lock()
        for node_id in range(1, 128):
            net.subscribe(0x700 + node_id, self._heard)
        net.subscribe(SYNC, self._sync)

    def _sync(self, _cob: int, _data: bytes, _ts: float) -> None:
        with self.lock:
            self.syncs += 1

    def _heard(self, cob: int, data: bytes, _ts: float) -> None:
        with self.lock:
            self.state[cob - 0x700] = data[0] & 0x7F
            if data[:1] == b"\x00":
                self.bootups[cob - 0x700] = self.bootups.get(cob - 0x700, 0) + 1


def wait_for(what: str, check) -> None:
    end, last = time.monotonic() + DEADLINE, ""
    while time.monotonic() < end:
        try:
            if check():
                return
        except SdoCommunicationError as e:  # a loaded machine: ask again
            last = f" (last: {e})"
        time.sleep(0.05)
    raise AssertionError(f"not within {DEADLINE:g} s: {what}{last}")


T = TypeVar("T")


def ask(transfer: Callable[[], T]) -> T:
    """An SDO transfer, asked again after a communication error: on a loaded machine a request
    that timed out may be answered late, and its answer taken for the next request's (canopen
    then reports an unexpected response). Aborts are answers and pass through."""
    end = time.monotonic() + DEADLINE
    while True:
        try:
            return transfer()
        except SdoCommunicationError:
            if time.monotonic() > end:
                raise
            time.sleep(0.2)  # the late answer arrives and is dropped before the next request


def configured_values(dcf: str, node_id: int) -> dict[tuple[int, int], bytes]:
    """Each entry the DCF configures (a ParameterValue), as the bytes its SDO server holds."""
    od = canopen.import_od(dcf, node_id)
    variables = [v for obj in od.values()
                 for v in (obj.values() if isinstance(obj, (canopen.objectdictionary.Record,
                                                             canopen.objectdictionary.Array)) else [obj])]
    return {(v.index, v.subindex): v.encode_raw(v.value) for v in variables if v.value is not None}


def mapped(dcf: str, node_id: int, index: int) -> list[tuple[int, int, int]]:
    """The entries (index, sub, bytes) a PDO mapping object of the DCF maps."""
    od = canopen.import_od(dcf, node_id)
    count = od[index][0].value
    return [((m := od[index][n].value) >> 16, (m >> 8) & 0xFF, (m & 0xFF) // 8) for n in range(1, count + 1)]


def check_pdos(remote: dict, plan: dict) -> int:
    """For each wired PDO, under the master's SYNC: a value written on the producer (or, when its
    entry is read-only there, the one it holds) reaches the consumer, where a different value was
    written last by SDO."""
    dcfs = {int(k): v for k, v in plan["dcfs"].items()}
    flowed = 0
    for producer, tpdo, consumer, rpdo in plan["pdos"]:
        pairs = zip(mapped(dcfs[producer], producer, TPDO_MAPPING + tpdo - 1),
                    mapped(dcfs[consumer], consumer, RPDO_MAPPING + rpdo - 1), strict=True)
        for n, ((pi, ps, size), (ci, cs, _)) in enumerate(pairs, 1):
            sent = bytes([n] * size)
            try:
                ask(lambda: remote[producer].sdo.download(pi, ps, sent))  # noqa: B023
            except SdoAbortedError:  # read-only on the producer: the value it holds
                sent = ask(lambda: remote[producer].sdo.upload(pi, ps))  # noqa: B023
            ask(lambda: remote[consumer].sdo.download(ci, cs, bytes(b ^ 0xFF for b in sent)))  # noqa: B023
            where = f"node {producer} 0x{pi:04X}sub{ps} -> node {consumer} 0x{ci:04X}sub{cs}"
            wait_for(f"{where}: {sent.hex()}", lambda: remote[consumer].sdo.upload(ci, cs) == sent)  # noqa: B023
            flowed += 1
    return flowed


def start(exe: str, node_id: int | None, *extra: str) -> subprocess.Popen[bytes]:
    """A program on the bus; node_id None: an LSS slave that waits for its node-id."""
    args = ["--node-id", str(node_id)] if node_id is not None else []
    return subprocess.Popen([exe, "--iface", CHANNEL, *args, *extra], stdout=subprocess.PIPE, stderr=subprocess.PIPE)


def stop(proc: subprocess.Popen[bytes]) -> tuple[bytes, bytes]:
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=DEADLINE)
    assert proc.returncode == 0, f"exit {proc.returncode}: {err!r}"
    return out, err


def main() -> None:
    plan = json.loads(Path(sys.argv[1]).read_text(encoding="utf-8"))
    slaves = {int(k): v for k, v in plan["slaves"].items()}
    master_id = plan["master_id"]
    values = {node_id: configured_values(plan["dcfs"][str(node_id)], node_id) for node_id in slaves}
    late, wrong, unconfigured = plan["late"], plan["wrong"], plan["unconfigured"]
    booted, flowed = 0.0, 0
    net = canopen.Network()
    net.NOTIFIER_CYCLE = 0.1
    net.connect(interface="socketcan", channel=CHANNEL)
    states = States(net)
    remote = {}
    for node_id in [master_id, *slaves]:
        remote[node_id] = canopen.RemoteNode(node_id, canopen.ObjectDictionary())
        net.add_node(remote[node_id])
        remote[node_id].sdo.RESPONSE_TIMEOUT = 2.0
    procs = {node_id: start(exe, None if node_id == unconfigured else node_id)
             for node_id, exe in slaves.items() if node_id != late}
    master = start(plan["master"], master_id, "--lss", "assign")
    started = time.monotonic()
    try:
        def status(node_id: int) -> int:
            return remote[master_id].sdo.upload(STATUS, node_id)[0]

        def configured(node_id: int) -> bool:
            assert values[node_id], f"node {node_id}: nothing configured"
            for (index, sub), data in values[node_id].items():
                got = ask(lambda: remote[node_id].sdo.upload(index, sub))  # noqa: B023
                assert got == data, f"node {node_id} 0x{index:04X}sub{sub}: {got.hex()} != {data.hex()}"
            return True

        good = [n for n in slaves if n != wrong]
        wait_for("the master's boot-up", lambda: states.bootups.get(master_id, 0) > 0)
        wait_for("the slaves present boot, node-ids by LSS too",
                 lambda: all(status(n) == 2 for n in good if n != late))
        booted = time.monotonic() - started
        wait_for("the absent slave reported", lambda: status(late) == ord("B"))
        procs[late] = start(slaves[late], late)
        wait_for("the late slave boots", lambda: status(late) == 2)
        wait_for("every good slave operational", lambda: all(states.state.get(n) == 5 for n in good))
        for node_id in good:
            assert configured(node_id) and status(node_id) == 2
        assert states.syncs > 0, "no SYNC on the bus: the master produces none"
        flowed = check_pdos(remote, plan)
        # the wrong identity: reported by SDO, not started, not configured
        assert status(wrong) == ord("M"), f"wrong identity status {status(wrong):#x}"
        time.sleep(0.3)
        assert states.state.get(wrong) == 0x7F, f"node {wrong} state {states.state.get(wrong)}"
        # a slave reset by NMT comes back with its defaults and is configured again
        again = plan["reset"]
        ask(lambda: remote[again].sdo.download(0x1017, 0, b"\x10\x27"))  # so that only a new download restores it
        booted = states.bootups.get(again, 0)
        remote[again].nmt.send_command(0x81)
        wait_for("the reset slave's boot-up", lambda: states.bootups.get(again, 0) > booted)
        wait_for("the reset slave configured again",
                 lambda: status(again) == 2 and states.state.get(again) == 5 and configured(again))
        assert states.state.get(master_id) == 5, "the master itself is operational"
    finally:
        for proc in procs.values():
            if proc.poll() is None:
                stop(proc)
        out, err = stop(master)
        net.disconnect()
        sys.stderr.write(f"master stdout:\n{out.decode()}\nmaster stderr:\n{err.decode()}\n")
    log = out.decode()
    assert f"odg-master: node {wrong} status 0x4D" in log, log
    assert f"odg-master: node {late} status 0x42" in log, log
    assert err == b"", err
    print(f"vcan master: the slaves present booted {booted:.2f} s after the master's start (LSS included)")
    print(f"vcan master: {sum(map(len, values.values()))} configured values in place, "
          f"{flowed} mapped entries carried by {len(plan['pdos'])} wired PDOs")
    print("vcan master: ok")


if __name__ == "__main__":
    main()
