"""Run ds401-io loop-back node programs one after the other on vcan and check each against a plan.

    python tests/vcan/ds401_io.py PLAN.json      (inside tools/vcan/run.py; see tests/test_ds401_vcan.py)

PLAN is a list of nodes: {"name", "exe", "sdo": [[index, sub, hex]], "steps": [[rpdo_cob, hex,
tpdo_cob, hex]], "writes": [[index, sub, hex]]}. For each: start the program with node-id 5,
wait for its boot-up, check the SDO uploads, do the SDO writes, start it (NMT), then for each
step send the RPDO and wait for the TPDO with exactly those bytes. Prints one line per node and
"ds401 vcan: ok" at the end; exits 1 at the first difference.
"""

from __future__ import annotations

import json
import os
import queue
import subprocess
import sys
import time

import canopen

IFACE = os.environ.get("ODGEN_VCAN_IFACES", "vcan0").split(",")[0]
NODE_ID = 5
TIMEOUT = 15.0  # waits end at the frame: generous for a loaded machine


class Bus:
    def __init__(self) -> None:
        self.network = canopen.Network()
        self.network.NOTIFIER_CYCLE = 0.1
        self.network.connect(interface="socketcan", channel=IFACE)
        self.frames: queue.Queue[tuple[int, bytes]] = queue.Queue()
        for cob in (0x700 + NODE_ID, *(0x180 + 0x100 * k + NODE_ID for k in range(4))):
            self.network.subscribe(cob, lambda cob, data, _ts: self.frames.put((cob, bytes(data))))
        self.node = canopen.RemoteNode(NODE_ID, canopen.ObjectDictionary())
        self.network.add_node(self.node)
        self.node.sdo.RESPONSE_TIMEOUT = 5.0

    def drain(self) -> None:
        while not self.frames.empty():
            self.frames.get_nowait()

    def wait_for(self, cob: int, data: bytes | None) -> bool:
        deadline = time.monotonic() + TIMEOUT
        while (left := deadline - time.monotonic()) > 0:
            try:
                got = self.frames.get(timeout=left)
            except queue.Empty:
                return False
            if got[0] == cob and (data is None or got[1] == data):
                return True
        return False


def check(ok: bool, what: str) -> None:
    if not ok:
        print(f"ds401 vcan: FAILED: {what}", flush=True)
        sys.exit(1)


def run_node(bus: Bus, plan: dict) -> None:
    name = plan["name"]
    bus.drain()
    proc = subprocess.Popen([plan["exe"], "--iface", IFACE, "--node-id", str(NODE_ID)])
    try:
        check(bus.wait_for(0x700 + NODE_ID, b"\x00"), f"{name}: no boot-up")
        for index, sub, value in plan["sdo"]:
            got = bus.node.sdo.upload(index, sub).hex()
            check(got == value, f"{name}: SDO 0x{index:04X}sub{sub} = {got}, expected {value}")
        for index, sub, value in plan["writes"]:
            bus.node.sdo.download(index, sub, bytes.fromhex(value))
        bus.node.nmt.send_command(0x01)
        time.sleep(0.1)  # every TPDO goes out once on entering operational
        for rpdo, out, tpdo, expected in plan["steps"]:
            bus.drain()
            bus.network.send_message(rpdo, bytes.fromhex(out))
            check(bus.wait_for(tpdo, bytes.fromhex(expected)),
                  f"{name}: RPDO 0x{rpdo:03X} {out} did not come back as TPDO 0x{tpdo:03X} {expected}")
        check(proc.poll() is None, f"{name}: the node exited ({proc.returncode})")
    finally:
        proc.terminate()
        proc.wait(5)
    print(f"ds401 vcan: {name}: {len(plan['sdo'])} SDO uploads, {len(plan['steps'])} PDO loops ok", flush=True)


def main() -> int:
    with open(sys.argv[1], encoding="utf-8") as f:
        plans = json.load(f)
    bus = Bus()
    try:
        for plan in plans:
            run_node(bus, plan)
    finally:
        bus.network.disconnect()
    print("ds401 vcan: ok", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
