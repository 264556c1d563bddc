"""On vcan0: a CANopenNode-style description keeps its PDO, SDO and heartbeat configuration across
"save" and reset node (issue 25, sequence 1: `;StorageLocation=PERSIST_COMM` on the object,
`;StorageLocation=RAM` on each sub-entry).

    python tests/node/vcan_canopennode_save.py NODE WORKDIR      (inside tools/vcan/run.py)

python-canopen writes TPDO 1's transmission type and event timer, the SDO client's server
node-id and the producer heartbeat time, saves with 0x1010 sub 1, resets the node (NMT), and
reads them back after the boot-up; then the node restarts (a power cycle) and they are still
there. Prints "vcan canopennode save: ok".
"""

from __future__ import annotations

import os
import struct
import sys

from vcan_node import Bootups, remote, start, stop

NODE = 9
WRITES = ((0x1800, 2, b"\x01"), (0x1800, 5, struct.pack("<H", 500)), (0x1280, 3, b"\x22"),
          (0x1017, 0, struct.pack("<H", 250)))


def main() -> int:
    exe, workdir = sys.argv[1:3]
    nv = os.path.join(workdir, "od.nv")
    net, node = remote(NODE)
    up = Bootups(net, NODE)
    procs = []
    try:
        procs.append(start(exe, NODE, "--nv", nv))
        up.wait()
        defaults = {(i, s): node.sdo.upload(i, s) for i, s, _ in WRITES}
        assert all(defaults[(i, s)] != v for i, s, v in WRITES), defaults
        for index, sub, value in WRITES:
            node.sdo.download(index, sub, value)
        node.sdo.download(0x1010, 1, b"save")
        up.arm()
        node.nmt.state = "RESET"
        up.wait()
        for index, sub, value in WRITES:
            got = node.sdo.upload(index, sub)
            assert got == value, f"0x{index:04X}sub{sub}: {got.hex()} after reset node, stored {value.hex()}"
        stop(procs.pop())
        up.arm()
        procs.append(start(exe, NODE, "--nv", nv))  # power cycle
        up.wait()
        for index, sub, value in WRITES:
            assert node.sdo.upload(index, sub) == value, f"0x{index:04X}sub{sub} after a power cycle"
        stop(procs.pop())
    finally:
        for p in procs:
            p.kill()
        net.disconnect()
    print("vcan canopennode save: ok", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
