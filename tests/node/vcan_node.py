"""End to end on vcan0: the node program (runtime/linux/odg_node_main.c) against python-canopen.

    python tests/node/vcan_node.py ALLTYPES_NODE IO_NODE WORKDIR     (inside tools/vcan/run.py)

ALLTYPES_NODE serves the alltypes dictionary as node 5 (with --nv WORKDIR/alltypes.nv),
IO_NODE the io-node example as node 6. Checks boot-up, heartbeat, NMT, SDO expedited,
segmented and block transfers, aborts, PDOs, and that a value stored through 0x1010 survives
SIGTERM and a restart. Prints "vcan node: ok" last and exits 0, or raises.
"""

from __future__ import annotations

import os
import signal
import struct
import subprocess
import sys
import threading
import time

import can
import canopen
from canopen.sdo.exceptions import SdoAbortedError

CHANNEL = os.environ.get("ODGEN_VCAN_IFACES", "vcan0").split(",")[0]
# Deadlines for things that happen within milliseconds on an idle machine: generous, since
# waiting ends at the event, and a loaded machine (or the guest) may be slow.
DEADLINE = 30.0


class Bootups:
    """Boot-up frames seen since arm(): listening starts before the node does, so a boot-up
    sent before a wait could begin is not lost (canopen's wait_for_bootup only sees later ones)."""

    def __init__(self, net: canopen.Network, node_id: int) -> None:
        self.seen = threading.Event()
        net.subscribe(0x700 + node_id, lambda _cob, data, _ts: data[:1] == b"\x00" and self.seen.set())

    def arm(self) -> None:
        self.seen.clear()

    def wait(self) -> None:
        assert self.seen.wait(DEADLINE), f"no boot-up within {DEADLINE:g} s"


def start(exe: str, node_id: int, *extra: str) -> subprocess.Popen[bytes]:
    return subprocess.Popen([exe, "--iface", CHANNEL, "--node-id", str(node_id), *extra],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)


def remote(node_id: int) -> tuple[canopen.Network, canopen.RemoteNode]:
    """python canopen on the test bus, and the node `node_id` as a remote node of it (no description:
    the scripts upload and download raw bytes)."""
    net = canopen.Network()
    net.NOTIFIER_CYCLE = 0.1
    net.connect(interface="socketcan", channel=CHANNEL)
    node = canopen.RemoteNode(node_id, canopen.ObjectDictionary())
    net.add_node(node)
    node.sdo.RESPONSE_TIMEOUT = 2.0
    return net, node


def stop(proc: subprocess.Popen[bytes]) -> None:
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=DEADLINE)
    assert proc.returncode == 0, f"exit {proc.returncode}: {err!r}"
    assert out == b"" and err == b"", f"the node printed {out!r} {err!r}"


def sdo_checks(node: canopen.RemoteNode) -> None:
    sdo = node.sdo
    assert sdo.upload(0x2007, 0) == struct.pack("<I", 0x180 + node.id)  # $NODEID applied
    sdo.download(0x2005, 0, b"\x2a")  # expedited
    assert sdo.upload(0x2005, 0) == b"\x2a"
    sdo.download(0x2019, 0, struct.pack("<Q", 0x0102030405060708))  # segmented, 8 bytes
    assert sdo.upload(0x2019, 0) == struct.pack("<Q", 0x0102030405060708)
    label = b"written by python-canopen, 40 bytes...."
    sdo.download(0x2009, 0, label)
    assert sdo.upload(0x2009, 0) == label
    with sdo.open(0x2009, 0, "wb", size=22, block_transfer=True) as f:  # block download
        f.write(b"block transfer, 22 b.!")
    with sdo.open(0x2009, 0, "rb", block_transfer=True) as f:  # block upload, CRC checked
        assert f.read() == b"block transfer, 22 b.!"
    sdo.download(0x200E, 0, bytes(range(16)))  # domain
    assert sdo.upload(0x200E, 0) == bytes(range(16))
    for index, sub, data, code in [(0x3000, 0, None, 0x06020000), (0x2100, 0, b"\0\0\0\0", 0x06010002),
                                   (0x2002, 0, b"\x65", 0x06090031)]:
        try:
            sdo.upload(index, sub) if data is None else sdo.download(index, sub, data)
        except SdoAbortedError as e:
            assert e.code == code, f"{index:#x}: {e.code:#x}"
        else:
            raise AssertionError(f"{index:#x}: no abort")


def wait_for_state(node: canopen.RemoteNode, state: str) -> None:
    """The first heartbeat after a command may predate it: wait for one that shows `state`."""
    deadline = time.monotonic() + DEADLINE
    while (seen := node.nmt.wait_for_heartbeat(DEADLINE)) != state:
        assert time.monotonic() < deadline, f"heartbeat says {seen}, want {state}"


def main() -> int:
    alltypes_exe, io_exe, workdir = sys.argv[1:4]
    nv = os.path.join(workdir, "alltypes.nv")
    net = canopen.Network()
    net.NOTIFIER_CYCLE = 0.1
    net.connect(interface="socketcan", channel=CHANNEL)
    procs: list[subprocess.Popen[bytes]] = []
    try:
        node = canopen.RemoteNode(5, canopen.ObjectDictionary())
        io = canopen.RemoteNode(6, canopen.ObjectDictionary())
        net.add_node(node)
        net.add_node(io)
        for n in (node, io):
            n.sdo.RESPONSE_TIMEOUT = 5.0
        node_up, io_up = Bootups(net, 5), Bootups(net, 6)

        procs.append(start(alltypes_exe, 5, "--nv", nv))
        node_up.wait()
        wait_for_state(node, "PRE-OPERATIONAL")  # 0x1017 = 1000 ms
        sdo_checks(node)
        for state in ("OPERATIONAL", "STOPPED"):
            node.nmt.state = state
            wait_for_state(node, state)
        node.nmt.state = "PRE-OPERATIONAL"

        # store, change, restart: the stored value comes back
        node.sdo.download(0x2005, 0, b"\x63")
        node.sdo.download(0x1010, 1, b"save")
        node.sdo.download(0x2005, 0, b"\x07")
        stop(procs.pop())
        node_up.arm()
        procs.append(start(alltypes_exe, 5, "--nv", nv))
        node_up.wait()
        assert node.sdo.upload(0x2005, 0) == b"\x63", "the stored value did not survive a restart"

        # PDOs of the io-node: TPDO 0x186 (inputs, event timer 100 ms), RPDO 0x206 (outputs)
        procs.append(start(io_exe, 6))
        io_up.wait()
        with can.Bus(interface="socketcan", channel=CHANNEL) as bus:
            io.nmt.state = "OPERATIONAL"
            deadline, tpdos = time.monotonic() + DEADLINE, 0
            while time.monotonic() < deadline and tpdos < 3:
                msg = bus.recv(0.5)
                if msg is not None and msg.arbitration_id == 0x186:
                    assert bytes(msg.data) == b"\x00"
                    tpdos += 1
            assert tpdos == 3, f"{tpdos} TPDOs in {DEADLINE:g} s"
            bus.send(can.Message(arbitration_id=0x206, data=b"\x3c", is_extended_id=False))
        # The node handles frames in bus order: the RPDO before this SDO request.
        assert io.sdo.upload(0x6200, 1) == b"\x3c"
        while procs:
            stop(procs.pop())
    finally:
        for p in procs:
            p.kill()
        net.disconnect()
    print("vcan node: ok", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
