"""What `odgen node`, `odgen roundtrip` and `odgen conformance` need from the host: the [can]
extra and SocketCAN.

Each answers a missing piece with exit 2 and what to do (install, or create the interface),
before anything is built or sent.
"""

from __future__ import annotations

import importlib.util
import socket

from .errors import OdgenError

VCAN_HINT = ("load the vcan module and add the interface (sudo modprobe vcan; sudo ip link add dev vcan0 type vcan; "
             "sudo ip link set up vcan0), or, on a kernel without CAN, run odgen inside the User-Mode Linux guest "
             "of the source tree's tools/vcan (tools/vcan/run.py -- odgen ...; see docs/ci.md)")


def require_can_extra(command: str) -> None:
    missing = [name for name, module in (("python-can", "can"), ("canopen", "canopen"))
               if importlib.util.find_spec(module) is None]
    if missing:
        raise OdgenError(f"`odgen {command}` needs {' and '.join(missing)}: install odgen with its `can` extra "
                         "(pip install 'odgen[can]', or 'odgen-VERSION-py3-none-any.whl[can]' from a wheel, "
                         "'.[can]' from a checkout)")


def require_socketcan(iface: str) -> None:
    family = getattr(socket, "AF_CAN", None)
    if family is None:
        raise OdgenError(f"this system has no SocketCAN: {VCAN_HINT}")
    try:
        sock = socket.socket(family, socket.SOCK_RAW, socket.CAN_RAW)
    except OSError as err:
        raise OdgenError(f"this kernel offers no SocketCAN ({err.strerror or err}): {VCAN_HINT}") from None
    try:
        sock.bind((iface,))
    except OSError as err:
        raise OdgenError(f"no CAN interface {iface} ({err.strerror or err}): name an existing one with --iface, "
                         f"or {VCAN_HINT}") from None
    finally:
        sock.close()
