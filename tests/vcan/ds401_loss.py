"""A ds401-io loop-back node loses its master's heartbeat: its outputs must take their error values.

    python tests/vcan/ds401_loss.py NODE_PROGRAM IO_EDS     (inside tools/vcan/run.py; see
                                                              tests/test_node_ds401.py)

The node (outputs wired to inputs by examples/ds401-io/sim.c) watches node 1's heartbeat
(0x1016 sub 1, 400 ms), which this script sends every 50 ms. Digital lines 1-4 of group 1 are set
to take error value 0b0011 (0x6206/0x6207), the rest keep the CiA 401 defaults (all lines to 0,
analog outputs to 0x6444 = 0). The script drives the outputs by RPDO, checks them through the
inputs (SDO uploads of 0x6000 and the analog inputs), stops the heartbeat, waits for the node's
EMCY 0x8130, and checks the inputs again: the error values, while 0x6200 still holds what the
master wrote. Prints "ds401 loss: ok", or exits 1 at the first difference.
"""

from __future__ import annotations

import os
import queue
import subprocess
import sys
import threading
import time

import canopen

IFACE = os.environ.get("ODGEN_VCAN_IFACES", "vcan0").split(",")[0]
NODE_ID = 5
MASTER = 1
HB_TIME = 400  # ms the node waits for the master's heartbeat
TIMEOUT = 15.0


def check(ok: bool, what: str) -> None:
    if not ok:
        print(f"ds401 loss: FAILED: {what}", flush=True)
        sys.exit(1)


def upload(node: canopen.RemoteNode, index: int, sub: int) -> bytes:
    return bytes(node.sdo.upload(index, sub))


def main() -> int:
    exe, eds = sys.argv[1], sys.argv[2]
    network = canopen.Network()
    network.NOTIFIER_CYCLE = 0.1
    network.connect(interface="socketcan", channel=IFACE)
    frames: queue.Queue[tuple[int, bytes]] = queue.Queue()
    for cob in (0x700 + NODE_ID, 0x80 + NODE_ID):
        network.subscribe(cob, lambda cob, data, _ts: frames.put((cob, bytes(data))))
    node = canopen.RemoteNode(NODE_ID, eds)
    network.add_node(node)
    node.sdo.RESPONSE_TIMEOUT = 5.0
    alive = threading.Event()
    alive.set()
    stop = threading.Event()

    def heartbeat() -> None:
        while not stop.is_set():
            if alive.is_set():
                network.send_message(0x700 + MASTER, b"\x05")
            time.sleep(0.05)

    def wait_for(cob: int, data: bytes) -> bool:
        deadline = time.monotonic() + TIMEOUT
        while (left := deadline - time.monotonic()) > 0:
            try:
                got = frames.get(timeout=left)
            except queue.Empty:
                return False
            if got[0] == cob and got[1].startswith(data):
                return True
        return False

    proc = subprocess.Popen([exe, "--iface", IFACE, "--node-id", str(NODE_ID)])
    beat = threading.Thread(target=heartbeat, daemon=True)
    try:
        check(wait_for(0x700 + NODE_ID, b"\x00"), "no boot-up")
        beat.start()
        node.sdo.download(0x1016, 1, (MASTER << 16 | HB_TIME).to_bytes(4, "little"))
        node.sdo.download(0x6206, 1, b"\x0f")
        node.sdo.download(0x6207, 1, b"\x03")
        node.nmt.send_command(0x01)
        time.sleep(0.2)
        network.send_message(0x200 + NODE_ID, bytes([0xA5, 0x5A]))  # RPDO1: 0x6200 sub 1, 2
        network.send_message(0x300 + NODE_ID, (1000).to_bytes(2, "little", signed=True) * 4)  # RPDO2: analog
        time.sleep(0.2)
        check(upload(node, 0x6000, 1) + upload(node, 0x6000, 2) == b"\xa5\x5a", "outputs not looped back")
        check(upload(node, 0x6401, 1) == (1000).to_bytes(2, "little", signed=True), "analog output not looped back")
        time.sleep(1.0)  # watched: no timeout while the master beats
        check(upload(node, 0x6000, 1) == b"\xa5", "error values while the master is alive")
        while not frames.empty():
            frames.get_nowait()
        alive.clear()  # the master falls silent
        check(wait_for(0x80 + NODE_ID, b"\x30\x81"), "no EMCY 0x8130 (heartbeat consumer)")
        time.sleep(0.1)
        got = upload(node, 0x6000, 1) + upload(node, 0x6000, 2)
        check(got == b"\xa3\x00", f"digital outputs {got.hex()}, expected the error values a300")
        got = upload(node, 0x6401, 1)
        check(got == b"\x00\x00", f"analog output {got.hex()}, expected its error value 0000")
        check(upload(node, 0x6200, 1) == b"\xa5", "0x6200 keeps what the master wrote")
        check(proc.poll() is None, f"the node exited ({proc.returncode})")
    finally:
        stop.set()
        proc.terminate()
        proc.wait(5)
        network.disconnect()
    print("ds401 loss: ok", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
