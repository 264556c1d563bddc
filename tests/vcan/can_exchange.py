"""python-can over SocketCAN: frames between two sockets, two processes, and CAN FD.

Run inside tools/vcan/run.py (or on any host with vcan0 up):
    python tests/vcan/can_exchange.py            # prints "python-can: ok ..." and exits 0
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

import can

CHANNEL = os.environ.get("ODGEN_VCAN_IFACES", "vcan0").split(",")[0]
ECHO_ID = 0x321


def _bus(fd: bool = False) -> can.BusABC:
    return can.Bus(interface="socketcan", channel=CHANNEL, fd=fd)


def _expect(bus: can.BusABC, arbitration_id: int, data: bytes, timeout: float = 2.0) -> can.Message:
    deadline = time.monotonic() + timeout
    while (left := deadline - time.monotonic()) > 0:
        msg = bus.recv(timeout=left)
        if msg is not None and msg.arbitration_id == arbitration_id:
            if bytes(msg.data) != data:
                raise AssertionError(f"0x{arbitration_id:X}: got {bytes(msg.data).hex()}, want {data.hex()}")
            return msg
    raise AssertionError(f"no frame 0x{arbitration_id:X} on {CHANNEL} within {timeout} s")


def two_sockets() -> None:
    """Two sockets in one process see each other's frames (standard and extended ids)."""
    with _bus() as a, _bus() as b:
        a.send(can.Message(arbitration_id=0x123, data=b"\x01\x02\x03\x04", is_extended_id=False))
        _expect(b, 0x123, b"\x01\x02\x03\x04")
        b.send(can.Message(arbitration_id=0x1ABCDE0F, data=b"pong", is_extended_id=True))
        msg = _expect(a, 0x1ABCDE0F, b"pong")
        assert msg.is_extended_id


def can_fd() -> None:
    """A 64-byte CAN FD frame with bit-rate switch."""
    payload = bytes(range(64))
    with _bus(fd=True) as a, _bus(fd=True) as b:
        a.send(can.Message(arbitration_id=0x456, data=payload, is_fd=True, bitrate_switch=True, is_extended_id=False))
        msg = _expect(b, 0x456, payload)
        assert msg.is_fd


def two_processes() -> None:
    """A frame to a second process and its echo back (id + 1, data reversed)."""
    child = subprocess.Popen(
        [sys.executable, os.path.abspath(__file__), "--echo"], stdout=subprocess.PIPE, text=True
    )
    try:
        assert child.stdout is not None
        assert child.stdout.readline().strip() == "ready", "echo process did not start"
        with _bus() as bus:
            bus.send(can.Message(arbitration_id=ECHO_ID, data=b"ping", is_extended_id=False))
            _expect(bus, ECHO_ID + 1, b"gnip", timeout=5.0)
        assert child.wait(timeout=5) == 0, "echo process failed"
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()


def echo() -> int:
    with _bus() as bus:
        print("ready", flush=True)
        deadline = time.monotonic() + 5.0
        while time.monotonic() < deadline:
            msg = bus.recv(timeout=0.5)
            if msg is not None and msg.arbitration_id == ECHO_ID:
                bus.send(can.Message(arbitration_id=ECHO_ID + 1, data=bytes(msg.data)[::-1], is_extended_id=False))
                return 0
    return 1


def main() -> int:
    two_sockets()
    can_fd()
    two_processes()
    print(f"python-can: ok (two sockets, CAN FD, two processes on {CHANNEL})", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(echo() if sys.argv[1:] == ["--echo"] else main())
