"""On vcan0: stored parameters survive a firmware update (docs/persistence.md).

    python tests/node/vcan_migration.py V1_NODE V2_NODE WORKDIR      (inside tools/vcan/run.py)

The node built from v1 (node 7, --nv WORKDIR/od.nv) gets values from python-canopen and stores
them with 0x1010; the node built from v2 then boots on the same NV file. python-canopen reads the
migrated values, the boot status object 0x2FF0 and the storage EMCY. Prints "vcan migration: ok".
"""

from __future__ import annotations

import os
import struct
import sys
import time

from vcan_node import Bootups, remote, start, stop

NODE = 7
MIGRATED, LOADED = 5, 0


def main() -> int:
    v1, v2, workdir = sys.argv[1:4]
    nv = os.path.join(workdir, "od.nv")
    net, node = remote(NODE)
    up = Bootups(net, NODE)
    procs = []
    try:
        procs.append(start(v1, NODE, "--nv", nv))
        up.wait()
        node.sdo.download(0x2000, 0, b"\xfa")  # UNSIGNED8 250: widened to UNSIGNED32 by v2
        node.sdo.download(0x2001, 0, struct.pack("<H", 57920))  # kept
        node.sdo.download(0x2002, 0, struct.pack("<h", -123))  # below v2's LowLimit: default
        node.sdo.download(0x1017, 0, struct.pack("<H", 250))  # group comm, unchanged
        node.sdo.download(0x1010, 1, b"save")
        stop(procs.pop())

        node.emcy.reset()
        up.arm()
        procs.append(start(v2, NODE, "--nv", nv))
        up.wait()
        assert node.sdo.upload(0x2000, 0) == struct.pack("<I", 250)
        assert node.sdo.upload(0x2001, 0) == struct.pack("<H", 57920)
        assert node.sdo.upload(0x2002, 0) == struct.pack("<h", -5)  # v2's default
        assert node.sdo.upload(0x2003, 0) == struct.pack("<I", 42)  # new in v2: its default
        assert node.sdo.upload(0x1017, 0) == struct.pack("<H", 250)
        # the status object: sub 0 the groups, sub 1 app, sub 2 comm (NAME_GROUP_* order)
        assert node.sdo.upload(0x2FF0, 0) == b"\x02"
        app = struct.unpack("<I", node.sdo.upload(0x2FF0, 1))[0]
        # 1 converted, 1 defaulted (0x2002, below v2's LowLimit), 0 dropped; 0x2003 is added, no loss
        assert app == MIGRATED | 1 << 8 | 1 << 16, hex(app)
        assert struct.unpack("<I", node.sdo.upload(0x2FF0, 2))[0] == LOADED
        deadline = time.monotonic() + 2
        while not node.emcy.log and time.monotonic() < deadline:
            time.sleep(0.05)
        assert node.emcy.log, "no storage EMCY"
        emcy = node.emcy.log[0]
        assert emcy.code == 0x5530 and emcy.register & 1, emcy
        assert emcy.data[:4] == bytes([0x80 | 1 << LOADED | 1 << MIGRATED, 1, 0, 1]), emcy.data.hex()
        stop(procs.pop())
    finally:
        for p in procs:
            p.kill()
        net.disconnect()
    print("vcan migration: ok", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
