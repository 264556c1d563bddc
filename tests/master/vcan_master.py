"""End to end on vcan0: the master program (runtime/linux/odg_master_main.c) boots odgen slaves.

    python tests/master/vcan_master.py PLAN.json        (inside tools/vcan/run.py)

PLAN.json names the master program, the slave programs by node-id, the node-id powered up late,
the node-id whose identity the master expects wrong, the node-id of the LSS slave started
without one, and each slave's configured values (hex bytes by "index:sub"). Checks, with python
canopen: every good slave reaches operational with each configured value in place (uploaded and
compared), the wrong one stays pre-operational and its status in the master's 0x5F81 reads 'M'
by SDO, the late one is configured when it comes, the one without node-id gets its node-id by
LSS fastscan and is configured, and a slave reset by NMT is configured again. Prints
"vcan master: ok" last and exits 0.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import canopen
from canopen.sdo.exceptions import SdoCommunicationError

CHANNEL = os.environ.get("ODGEN_VCAN_IFACES", "vcan0").split(",")[0]
DEADLINE = 20.0
MASTER_ID = 1
STATUS = 0x5F81


class States:
    """The NMT state each node's heartbeat said last (boot-up: 0)."""

    def __init__(self, net: canopen.Network) -> None:
        self.state: dict[int, int] = {}
        self.bootups: dict[int, int] = {}
        self.lock = threading.Lock()
        for node_id in range(1, 128):
            net.subscribe(0x700 + node_id, self._heard)

    def _heard(self, cob: int, data: bytes, _ts: float) -> None:
        with self.lock:
            self.state[cob - 0x700] = data[0] & 0x7F
            if data[:1] == b"\x00":
                self.bootups[cob - 0x700] = self.bootups.get(cob - 0x700, 0) + 1


def wait_for(what: str, check) -> None:
    end = time.monotonic() + DEADLINE
    while time.monotonic() < end:
        try:
            if check():
                return
        except SdoCommunicationError:  # a loaded machine: ask again
            pass
        time.sleep(0.05)
    raise AssertionError(f"not within {DEADLINE:g} s: {what}")


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
    values = {int(k): v for k, v in plan["values"].items()}
    late, wrong, unconfigured = plan["late"], plan["wrong"], plan["unconfigured"]
    booted = 0.0
    net = canopen.Network()
    net.NOTIFIER_CYCLE = 0.1
    net.connect(interface="socketcan", channel=CHANNEL)
    states = States(net)
    remote = {}
    for node_id in [MASTER_ID, *slaves]:
        remote[node_id] = canopen.RemoteNode(node_id, canopen.ObjectDictionary())
        net.add_node(remote[node_id])
        remote[node_id].sdo.RESPONSE_TIMEOUT = 2.0
    procs = {node_id: start(exe, None if node_id == unconfigured else node_id)
             for node_id, exe in slaves.items() if node_id != late}
    master = start(plan["master"], MASTER_ID, "--lss", "assign")
    started = time.monotonic()
    try:
        def status(node_id: int) -> int:
            return remote[MASTER_ID].sdo.upload(STATUS, node_id)[0]

        def configured(node_id: int) -> bool:
            for key, hexdata in values[node_id].items():
                index, sub = (int(x, 16) for x in key.split(":"))
                got = remote[node_id].sdo.upload(index, sub)
                assert got == bytes.fromhex(hexdata), f"node {node_id} 0x{index:04X}sub{sub}: {got.hex()} != {hexdata}"
            return True

        good = [n for n in slaves if n != wrong]
        wait_for("the master's boot-up", lambda: states.bootups.get(MASTER_ID, 0) > 0)
        wait_for("the slaves present boot, node-ids by LSS too",
                 lambda: all(status(n) == 2 for n in good if n != late))
        booted = time.monotonic() - started
        wait_for("the absent slave reported", lambda: status(late) == ord("B"))
        procs[late] = start(slaves[late], late)
        wait_for("the late slave boots", lambda: status(late) == 2)
        wait_for("every good slave operational", lambda: all(states.state.get(n) == 5 for n in good))
        for node_id in good:
            assert configured(node_id)
        # the wrong identity: reported by SDO, not started, not configured
        assert status(wrong) == ord("M"), f"wrong identity status {status(wrong):#x}"
        time.sleep(0.3)
        assert states.state.get(wrong) == 0x7F, f"node {wrong} state {states.state.get(wrong)}"
        # a slave reset by NMT comes back with its defaults and is configured again
        again = good[1]
        remote[again].sdo.download(0x1017, 0, b"\x10\x27")  # so that only a new download restores it
        booted = states.bootups.get(again, 0)
        remote[again].nmt.send_command(0x81)
        wait_for("the reset slave's boot-up", lambda: states.bootups.get(again, 0) > booted)
        wait_for("the reset slave configured again",
                 lambda: status(again) == 2 and states.state.get(again) == 5 and configured(again))
        assert states.state.get(MASTER_ID) == 5, "the master itself is operational"
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
    print("vcan master: ok")


if __name__ == "__main__":
    main()
