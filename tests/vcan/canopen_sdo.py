"""python canopen over SocketCAN: an SDO client talks to a canopen LocalNode serving the
example io-node EDS, each on its own Network (socket) on vcan0.

Run inside tools/vcan/run.py (or on any host with vcan0 up):
    python tests/vcan/canopen_sdo.py             # prints "canopen: ok ..." and exits 0
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import canopen

CHANNEL = os.environ.get("ODGEN_VCAN_IFACES", "vcan0").split(",")[0]
EDS = Path(__file__).resolve().parents[2] / "examples" / "io-node" / "io-node.eds"
NODE_ID = 5


def sdo_round_trip() -> None:
    server_net, client_net = canopen.Network(), canopen.Network()
    for net in (server_net, client_net):
        net.NOTIFIER_CYCLE = 0.1  # disconnect() waits up to one cycle for the receive thread
    server_net.connect(interface="socketcan", channel=CHANNEL)
    client_net.connect(interface="socketcan", channel=CHANNEL)
    try:
        server = canopen.LocalNode(NODE_ID, canopen.import_od(str(EDS), NODE_ID))
        server_net.add_node(server)
        client = client_net.add_node(NODE_ID, canopen.import_od(str(EDS), NODE_ID))
        client.sdo.RESPONSE_TIMEOUT = 2.0

        device_type_var, debounce_var = client.sdo[0x1000], client.sdo[0x2000]
        assert isinstance(device_type_var, canopen.sdo.SdoVariable)
        assert isinstance(debounce_var, canopen.sdo.SdoVariable)
        device_type = device_type_var.raw  # SDO upload
        assert isinstance(device_type, int) and device_type == 0x30191, f"0x1000 read {device_type!r}"
        debounce_var.raw = 123  # SDO download to "Debounce time ms" (rw)
        assert server.sdo[0x2000].raw == 123, "download did not reach the server"  # type: ignore[union-attr]
        assert debounce_var.raw == 123, "upload after download differs"
    finally:
        client_net.disconnect()
        server_net.disconnect()
    print(f"canopen: ok (SDO upload 0x1000 = {device_type:#x}, download/upload 0x2000 on {CHANNEL})", flush=True)


def main() -> int:
    sdo_round_trip()
    return 0


if __name__ == "__main__":
    sys.exit(main())
