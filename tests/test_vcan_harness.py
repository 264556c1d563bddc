"""The vcan harness (tools/vcan/): commands get a working SocketCAN vcan0 — the host's when it
has CAN, else one User-Mode Linux guest booted once for the whole test run (tools/vcan/bus.py
hands each command to tools/vcan/serve.py inside it) — and their output and exit status come back.

Never skipped for want of CAN on the host: booting the guest is the point. When the guest
cannot be set up at all (no apt, no ptrace...) the tests fail and say why.
"""

from __future__ import annotations

import os
import socket
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SMOKE = ROOT / "tests" / "vcan" / "smoke.py"


def host_has_can() -> bool:
    try:
        socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW).close()
    except (OSError, AttributeError):
        return False
    return True


def explain(r) -> str:
    return f"exit {r.returncode}\n--- stdout ---\n{r.stdout}\n--- stderr ---\n{r.stderr}"


def test_smoke_python_can_and_canopen_on_vcan(vcan_bus) -> None:
    r = vcan_bus.run([sys.executable, str(SMOKE)], cwd=ROOT, timeout=120)
    assert r.returncode == 0, explain(r)
    assert "python-can: ok" in r.stdout, explain(r)
    assert "canopen: ok" in r.stdout, explain(r)
    assert r.stdout.rstrip().splitlines()[-1].startswith("vcan smoke: ok"), explain(r)
    if not host_has_can():
        assert "mode=uml" in r.stdout, explain(r)


def test_status_output_cwd_and_writes_relayed(vcan_bus, tmp_path: Path) -> None:
    """Exit status, byte-exact stdout, stderr, the cwd, the environment, and files written to the
    repo and to a temporary directory reach the host."""
    in_repo = ROOT / "build" / f"vcan-harness-{os.getpid()}.txt"
    script = (
        'pwd; printf "a\\r\\nb\\n\\tc"; echo to-stderr >&2; '
        f'echo from-guest > written.txt; echo repo > {in_repo}; test "$ODGEN_VCAN_PROBE" = "x y"; exit 7'
    )
    try:
        env = dict(os.environ, ODGEN_VCAN_PROBE="x y")
        r = vcan_bus.run(["sh", "-c", script], cwd=tmp_path, env=env, timeout=60)
        assert r.returncode == 7, explain(r)
        assert r.stdout == f"{tmp_path}\na\r\nb\n\tc", explain(r)
        assert "to-stderr" in r.stderr, explain(r)
        assert (tmp_path / "written.txt").read_text() == "from-guest\n"
        assert in_repo.read_text() == "repo\n"
    finally:
        in_repo.unlink(missing_ok=True)


def test_failure_and_missing_command_relayed(vcan_bus, tmp_path: Path) -> None:
    """A failing command, one that does not exist, and one killed by a signal; a process the
    command left running is ended before the next command."""
    r = vcan_bus.run(["sh", "-c", f"(sleep 2; echo late > {tmp_path}/late) & exec false"], cwd=ROOT, timeout=60)
    assert r.returncode == 1, explain(r)
    r = vcan_bus.run(["/nonexistent/command"], cwd=ROOT, timeout=60)
    assert r.returncode == 127, explain(r)
    r = vcan_bus.run(["sh", "-c", "kill -TERM $$"], cwd=ROOT, timeout=60)
    assert r.returncode == 128 + 15, explain(r)
    r = vcan_bus.run(["sleep", "3"], cwd=ROOT, timeout=60)
    assert r.returncode == 0 and not (tmp_path / "late").exists(), "the leftover process kept running"


def test_timeout_kills_the_command_and_the_bus_lives_on(vcan_bus) -> None:
    r = vcan_bus.run(["sleep", "60"], cwd=ROOT, timeout=3)
    assert r.returncode == 124, explain(r)
    assert "timeout" in r.stderr, explain(r)
    r = vcan_bus.run(["sh", "-c", "echo still here"], cwd=ROOT, timeout=60)
    assert r.returncode == 0 and r.stdout == "still here\n", explain(r)
