"""End to end on vcan0: python canopen's LSS master configures an unconfigured odgen node.

    python tests/node/vcan_lss.py LSS_NODE WORKDIR     (inside tools/vcan/run.py)

LSS_NODE is the node program built from tests/node/lss-node.eds with the LSS slave; it is
started without --node-id and with --nv WORKDIR/lss.nv. The master finds it by fastscan,
assigns node-id 10, configures and activates a bit timing (the program logs both), stores the
configuration and switches it back to waiting: the node boots as node 10 and python canopen
reads 0x1018 over SDO. After SIGTERM and a restart without --node-id, the node comes up as
node 10 by itself. Prints "vcan lss: ok" last and exits 0, or raises.
"""

from __future__ import annotations

import os
import signal
import struct
import subprocess
import sys
import time

import can
import canopen
from vcan_node import Bootups

CHANNEL = os.environ.get("ODGEN_VCAN_IFACES", "vcan0").split(",")[0]
IDENTITY = [0x000004D2, 0x00010203, 0x00020001, 0x5EA1C0DE]  # 0x1018 sub 1-4 of lss-node.eds
NODE_ID = 10


def start(exe: str, nv: str) -> subprocess.Popen[bytes]:
    return subprocess.Popen([exe, "--iface", CHANNEL, "--nv", nv], stdout=subprocess.PIPE, stderr=subprocess.PIPE)


def stop(proc: subprocess.Popen[bytes]) -> bytes:
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=5)
    assert proc.returncode == 0 and err == b"", f"exit {proc.returncode}: {err!r}"
    return out


def frames(bus: can.BusABC, seconds: float) -> list[can.Message]:
    """Every frame seen on the bus for `seconds`."""
    seen, deadline = [], time.monotonic() + seconds
    while (left := deadline - time.monotonic()) > 0:
        msg = bus.recv(left)
        if msg is not None:
            seen.append(msg)
    return seen


def boot_ups(seen: list[can.Message]) -> list[int]:
    return [m.arbitration_id - 0x700 for m in seen if 0x701 <= m.arbitration_id <= 0x7FF and bytes(m.data) == b"\0"]


def main() -> int:
    exe, workdir = sys.argv[1:3]
    nv = os.path.join(workdir, "lss.nv")
    net = canopen.Network()
    net.NOTIFIER_CYCLE = 0.1
    net.connect(interface="socketcan", channel=CHANNEL)
    procs: list[subprocess.Popen[bytes]] = []
    try:
        with can.Bus(interface="socketcan", channel=CHANNEL) as bus:
            procs.append(start(exe, nv))
            seen = frames(bus, 1.0)
            assert seen == [], f"an unconfigured node sent {seen}"  # no boot-up, no heartbeat
            net.lss.RESPONSE_TIMEOUT = 0.2
            found, identity = net.lss.fast_scan()
            assert found and identity == IDENTITY, f"fastscan: {found} {identity}"
            assert net.lss.inquire_node_id() == 0xFF
            net.lss.configure_node_id(NODE_ID)
            net.lss.configure_bit_timing(4)  # 125 kbit/s: logged, the interface keeps its rate
            net.lss.activate_bit_timing(50)
            net.lss.store_configuration()
            while bus.recv(0) is not None:
                pass
            net.lss.send_switch_state_global(net.lss.WAITING_STATE)
            assert boot_ups(frames(bus, 0.5)) == [NODE_ID], "no boot-up as node 10"
        node = canopen.RemoteNode(NODE_ID, canopen.ObjectDictionary())
        net.add_node(node)
        node.sdo.RESPONSE_TIMEOUT = 2.0
        assert [struct.unpack("<I", node.sdo.upload(0x1018, k))[0] for k in range(1, 5)] == IDENTITY
        log = stop(procs.pop()).decode()
        assert "bit timing 125 kbit/s configured" in log and "activate bit timing 125 kbit/s after 50 ms" in log, log

        # a restart without --node-id: the stored node-id comes back
        up = Bootups(net, NODE_ID)
        procs.append(start(exe, nv))
        up.wait()
        assert node.sdo.upload(0x1018, 4) == struct.pack("<I", IDENTITY[3])
        stop(procs.pop())
    finally:
        for p in procs:
            p.kill()
        net.disconnect()
    print("vcan lss: ok", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
