"""Run the plasma-equipment network on a CAN bus and check every process value crosses it.

    python run_network.py [BUILD]        (default build/; needs vcan0 or $ODGEN_VCAN_IFACES)

Starts the five node programs that `make` built (master 127, slaves 1..4), starts them with
NMT, and then, for two sets of commands: writes the commands into the master by SDO, drives
SYNC, and checks (1) that each slave's RPDO1 landed in its outputs, (2) that each slave's
TPDO1 report (from its simulated device) landed in the master's inputs, and (3) that every
PDO frame on the bus, 0x201..0x204 and 0x181..0x184, carries exactly those bytes. Prints
"plasma network: ok" last and exits 0, or raises.
"""

from __future__ import annotations

import os
import signal
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path

import canopen

import describe

CHANNEL = os.environ.get("ODGEN_VCAN_IFACES", "vcan0").split(",")[0]
SYNC_PERIOD = 0.02
SETTLE_TIMEOUT = 10.0  # seconds of SYNCs before a value that has not arrived is an error
NAMES = {0x6000: "B", 0x6200: "B", 0x6401: "h", 0x6410: "b", 0x6411: "h"}  # struct codes by object

# Two sets of commands, by the master's (index, sub): every value differs between the sets.
COMMANDS = (
    {(0x6200, 1): 0, (0x6200, 2): 0, (0x6410, 1): 40, (0x6200, 3): 1, (0x6200, 4): 0,
     (0x6200, 5): 0, (0x6200, 6): 1, (0x6411, 1): 250, (0x6200, 7): 0, (0x6200, 8): 1, (0x6411, 2): 500},
    {(0x6200, 1): 1, (0x6200, 2): 1, (0x6410, 1): 75, (0x6200, 3): 0, (0x6200, 4): 1,
     (0x6200, 5): 1, (0x6200, 6): 2, (0x6411, 1): -300, (0x6200, 7): 1, (0x6200, 8): 0, (0x6411, 2): 123},
)


def device_reports(cmd: dict[tuple[int, int], int]) -> dict[tuple[int, int], int]:
    """What the simulated devices (sim/*.c) report for the commands, by the master's (index, sub)."""
    hv_on, level = cmd[0x6200, 1] == 0, max(0, min(100, cmd[0x6410, 1]))
    valve = cmd[0x6200, 6]
    return {(0x6401, 1): level * 3 if hv_on else 0, (0x6401, 2): level * 100 if hv_on else 0,
            (0x6401, 3): 12 if cmd[0x6200, 4] == 0 else 0, (0x6000, 1): cmd[0x6200, 3], (0x6000, 2): cmd[0x6200, 4],
            (0x6000, 3): cmd[0x6200, 5], (0x6000, 4): valve,
            (0x6401, 4): cmd[0x6411, 1] if valve == 1 else 1000 if valve == 2 else 0,
            (0x6000, 5): cmd[0x6200, 7], (0x6000, 6): cmd[0x6200, 8]}


def pack(index: int, value: int) -> bytes:
    return struct.pack("<" + NAMES[index], value)


def unpack(index: int, data: bytes) -> int:
    return int(struct.unpack("<" + NAMES[index], data)[0])


class Sniffer:
    """The last payload seen per PDO COB-ID."""

    def __init__(self, net: canopen.Network, cob_ids: list[int]) -> None:
        self.lock = threading.Lock()
        self.last: dict[int, bytes] = {}
        for cob in cob_ids:
            net.subscribe(cob, self._seen)

    def _seen(self, cob: int, data: bytearray, _timestamp: float) -> None:
        with self.lock:
            self.last[cob] = bytes(data)

    def clear(self) -> None:
        with self.lock:
            self.last.clear()

    def payload(self, cob: int) -> bytes | None:
        with self.lock:
            return self.last.get(cob)


class BootWatch:
    """Boot-up frames (0x700 + id, data 0) of the given nodes."""

    def __init__(self, net: canopen.Network, ids: list[int]) -> None:
        self.pending = set(ids)
        self.done = threading.Condition()
        for node_id in ids:
            net.subscribe(0x700 + node_id, self._seen)

    def _seen(self, cob: int, data: bytearray, _timestamp: float) -> None:
        if bytes(data) == b"\0":
            with self.done:
                self.pending.discard(cob - 0x700)
                self.done.notify_all()

    def wait(self, timeout: float) -> None:
        with self.done:
            assert self.done.wait_for(lambda: not self.pending, timeout), f"no boot-up from {sorted(self.pending)}"


def start_nodes(build: Path) -> list[subprocess.Popen[bytes]]:
    programs = [("master", describe.MASTER_ID)] + [(s.file[:-4], s.node_id) for s in describe.SLAVES]
    return [subprocess.Popen([str(build / f"{name}-node"), "--iface", CHANNEL, "--node-id", str(node_id)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE) for name, node_id in programs]


def stop_nodes(procs: list[subprocess.Popen[bytes]]) -> None:
    for proc in procs:
        if proc.poll() is None:
            proc.send_signal(signal.SIGTERM)
    for proc in procs:
        out, err = proc.communicate(timeout=5)
        assert proc.returncode == 0 and out == b"" and err == b"", f"{proc.args[0]}: {proc.returncode} {err!r}"


def drive_sync(net: canopen.Network, count: int) -> None:
    for _ in range(count):
        net.send_message(0x80, b"")
        time.sleep(SYNC_PERIOD)


def check_round(net: canopen.Network, nodes: dict[int, canopen.RemoteNode], sniff: Sniffer,
                cmd: dict[tuple[int, int], int]) -> None:
    master = nodes[describe.MASTER_ID]
    for (index, sub), value in cmd.items():
        master.sdo.download(index, sub, pack(index, value))
    report = device_reports(cmd)
    want = {0x200 + s.node_id: payload(s.commands, cmd) for s in describe.SLAVES}
    want.update({0x180 + s.node_id: payload(s.report, report) for s in describe.SLAVES})
    settle(net, sniff, want)
    for slave in describe.SLAVES:
        node = nodes[slave.node_id]
        own = describe.renumbered(slave.commands)
        for (index, sub, _b, what), (_i, own_sub, _b2, _w) in zip(slave.commands, own, strict=True):
            got = unpack(index, node.sdo.upload(index, own_sub))
            assert got == cmd[index, sub], f"node {slave.node_id} {what}: {got} != {cmd[index, sub]}"
    for (index, sub), value in report.items():
        got = unpack(index, master.sdo.upload(index, sub))
        assert got == value, f"master {index:#06x}sub{sub}: {got} != {value}"


def payload(maps: tuple[describe.Mapped, ...], values: dict[tuple[int, int], int]) -> bytes:
    return b"".join(pack(index, values[index, sub]) for index, sub, _bits, _what in maps)


def settle(net: canopen.Network, sniff: Sniffer, want: dict[int, bytes]) -> None:
    """SYNC until every PDO carries the new values, then twice more for the master to apply them.

    A value needs four SYNCs to go round (master sends, slave applies and its device reacts,
    slave reports, master applies); a loaded machine may take more, so this waits for the
    frames rather than counting."""
    sniff.clear()
    deadline = time.monotonic() + SETTLE_TIMEOUT
    while any(sniff.payload(cob) != data for cob, data in want.items()):
        late = {f"{cob:#x}": sniff.payload(cob) for cob, data in want.items() if sniff.payload(cob) != data}
        assert time.monotonic() < deadline, f"PDOs without the expected bytes: {late}"
        drive_sync(net, 1)
    drive_sync(net, 2)


def main() -> int:
    build = Path(sys.argv[1] if len(sys.argv) > 1 else "build").resolve()
    net = canopen.Network()
    net.NOTIFIER_CYCLE = 0.1
    net.connect(interface="socketcan", channel=CHANNEL)
    ids = [describe.MASTER_ID] + [s.node_id for s in describe.SLAVES]
    nodes = {i: net.add_node(canopen.RemoteNode(i, canopen.ObjectDictionary())) for i in ids}
    booted = BootWatch(net, ids)
    procs = start_nodes(build)
    try:
        booted.wait(30.0)  # ends at the last boot-up: generous for a loaded machine
        for node in nodes.values():
            node.sdo.RESPONSE_TIMEOUT = 5.0
        sniff = Sniffer(net, [0x200 + i for i in ids[1:]] + [0x180 + i for i in ids[1:]])
        net.nmt.state = "OPERATIONAL"  # NMT start, all nodes
        time.sleep(0.1)
        for cmd in COMMANDS:
            check_round(net, nodes, sniff, cmd)
    finally:
        net.disconnect()
        stop_nodes(procs)
    print("plasma network: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
