"""The vcan harness's smoke check: python-can and canopen on vcan0 in one interpreter.

    tools/vcan/run.py -- .venv/bin/python tests/vcan/smoke.py

Prints one `... ok` line per check and `vcan smoke: ok` last; exits non-zero on failure.
"""

from __future__ import annotations

import os
import platform
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import can_exchange  # noqa: E402
import canopen_sdo  # noqa: E402


def main() -> int:
    start = time.monotonic()
    where = os.environ.get("ODGEN_VCAN", "?")
    print(f"vcan smoke: mode={where} kernel={platform.release()} iface={can_exchange.CHANNEL}", flush=True)
    can_exchange.main()
    canopen_sdo.main()
    print(f"vcan smoke: ok ({time.monotonic() - start:.2f} s)", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
