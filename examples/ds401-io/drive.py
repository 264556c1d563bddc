"""Drive the ds401-io node from python canopen: write outputs by SDO and by RPDO, and watch
them come back on the inputs by TPDO (change of state through the loop-back wiring).

    python drive.py [--iface vcan0] [--node-id 5] build/io.eds

Prints each step and "ds401-io: ok"; exits 1 with the reason when something does not arrive.
"""

from __future__ import annotations

import argparse
import sys
import threading
import time

import canopen
from canopen.pdo.base import PdoMap

TIMEOUT = 2.0


class Watch:
    """The values of a TPDO as it last arrived, and a way to wait for the ones expected."""

    def __init__(self, pdo: PdoMap) -> None:
        self.pdo, self.changed = pdo, threading.Condition()
        self.values: list[int] = []
        pdo.add_callback(self._received)

    def _received(self, pdo: PdoMap) -> None:
        with self.changed:
            self.values = [int(var.raw) for var in pdo]
            self.changed.notify_all()

    def expect(self, what: str, values: list[int]) -> None:
        with self.changed:
            if not self.changed.wait_for(lambda: self.values == values, TIMEOUT):
                sys.exit(f"ds401-io: {what}: expected {values} in {self.pdo.name}, last seen {self.values}")
        print(f"{what}: {self.pdo.name} carries {values}", flush=True)


def wait_for_node(node: canopen.RemoteNode) -> None:
    """The node may still be starting: retry the first SDO upload for a few seconds."""
    deadline = time.monotonic() + 5
    while True:
        try:
            print(f"device type 0x1000 = 0x{node.sdo[0x1000].raw:08X}", flush=True)
            return
        except canopen.SdoCommunicationError:
            if time.monotonic() > deadline:
                raise


def drive(node: canopen.RemoteNode) -> None:
    wait_for_node(node)
    node.tpdo.read()  # the current mappings, by SDO
    node.rpdo.read()
    digital, analog = Watch(node.tpdo[1]), Watch(node.tpdo[2])
    node.sdo[0x6423].raw = True  # analog inputs: events on change (CiA 401 default: off)
    node.nmt.state = "OPERATIONAL"

    node.sdo[0x6200][1].raw = 0x5A  # outputs 1..8 by SDO
    digital.expect("SDO 0x6200sub1 = 0x5A", [0x5A, 0x00])

    outputs = list(node.rpdo[1])  # 0x6200 sub1, sub2
    outputs[0].raw, outputs[1].raw = 0x0F, 0xF0
    node.rpdo[1].transmit()
    digital.expect("RPDO1 0x6200 = 0x0F 0xF0", [0x0F, 0xF0])

    for var, value in zip(node.rpdo[2], (100, -200, 300, -400), strict=True):  # 0x6411 sub1..4
        var.raw = value
    node.rpdo[2].transmit()
    analog.expect("RPDO2 0x6411 = 100 -200 300 -400", [100, -200, 300, -400])

    node.sdo[0x6005].raw = False  # digital events off: the inputs change, no TPDO
    node.sdo[0x6200][1].raw = 0x01
    time.sleep(0.2)
    if digital.values != [0x0F, 0xF0]:
        sys.exit(f"ds401-io: TPDO1 sent although 0x6005 is FALSE: {digital.values}")
    print(f"0x6005 FALSE: 0x6000sub1 = 0x{node.sdo[0x6000][1].raw:02X} by SDO, TPDO1 still {digital.values}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("eds")
    parser.add_argument("--iface", default="vcan0")
    parser.add_argument("--node-id", type=int, default=5)
    args = parser.parse_args()
    network = canopen.Network()
    network.connect(interface="socketcan", channel=args.iface)
    try:
        drive(network.add_node(args.node_id, args.eds))
    finally:
        network.disconnect()
    print("ds401-io: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
