"""The vcan harness (tools/vcan/): CMD gets a working SocketCAN vcan0 — the host's when it has
CAN, else a User-Mode Linux guest booted for it — and its output and exit status come back.

Never skipped for want of CAN on the host: booting the guest is the point. When the guest
cannot be set up at all (no apt, no ptrace...) the tests fail and say why.
"""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SETUP = ROOT / "tools" / "vcan" / "setup.sh"
RUN = ROOT / "tools" / "vcan" / "run.py"
SMOKE = ROOT / "tests" / "vcan" / "smoke.py"


def host_has_can() -> bool:
    try:
        socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW).close()
    except (OSError, AttributeError):
        return False
    return True


@pytest.fixture(scope="module")
def harness() -> None:
    """Fetch the guest kernel into the cache once (quick no-op when it is there)."""
    # Even on a host with CAN: run.py falls back to the guest when it cannot create vcan0.
    try:
        r = subprocess.run(["bash", str(SETUP)], capture_output=True, text=True, timeout=600)
    except subprocess.TimeoutExpired:
        pytest.fail("tools/vcan/setup.sh took more than 600 s")
    if r.returncode != 0:
        pytest.fail(f"tools/vcan/setup.sh failed (exit {r.returncode}); the vcan harness cannot work:\n{r.stderr}")


def run(*args: str, timeout: float = 120, **kw) -> subprocess.CompletedProcess[bytes]:
    return subprocess.run(
        [sys.executable, str(RUN), *args], capture_output=True, timeout=timeout, stdin=subprocess.DEVNULL, **kw
    )


def explain(r: subprocess.CompletedProcess[bytes]) -> str:
    return (
        f"exit {r.returncode}\n--- stdout ---\n{r.stdout.decode(errors='replace')}"
        f"\n--- stderr ---\n{r.stderr.decode(errors='replace')}"
    )


def test_smoke_python_can_and_canopen_on_vcan(harness: None) -> None:
    start = time.monotonic()
    r = run("--", sys.executable, str(SMOKE), cwd=ROOT)
    wall = time.monotonic() - start
    assert r.returncode == 0, explain(r)
    out = r.stdout.decode()
    assert "python-can: ok" in out, explain(r)
    assert "canopen: ok" in out, explain(r)
    assert out.rstrip().splitlines()[-1].startswith("vcan smoke: ok"), explain(r)
    if not host_has_can():
        assert "mode=uml" in out, explain(r)
    assert wall < 60, f"smoke run took {wall:.1f} s"


def test_status_output_cwd_and_writes_relayed(harness: None, tmp_path: Path) -> None:
    """Exit status, byte-exact stdout (no console CR/LF rewriting), stderr, the cwd, and files
    written to the repo (always read-write) and to a --rw directory reach the host."""
    in_repo = ROOT / "build" / f"vcan-harness-{os.getpid()}.txt"
    script = (
        'pwd; printf "a\\r\\nb\\n\\tc"; echo to-stderr >&2; '
        f'echo from-guest > written.txt; echo repo > {in_repo}; test "$ODGEN_VCAN_PROBE" = "x y"; exit 7'
    )
    try:
        env = dict(os.environ, ODGEN_VCAN_PROBE="x y")
        r = run("--rw", str(tmp_path), "--", "sh", "-c", script, cwd=tmp_path, env=env)
        assert r.returncode == 7, explain(r)
        assert r.stdout == f"{tmp_path}\na\r\nb\n\tc".encode(), explain(r)
        assert b"to-stderr" in r.stderr, explain(r)
        assert (tmp_path / "written.txt").read_text() == "from-guest\n"
        assert in_repo.read_text() == "repo\n"
    finally:
        in_repo.unlink(missing_ok=True)


def test_failure_and_missing_command_relayed(harness: None) -> None:
    r = run("--", "sh", "-c", "echo leftover & exec false", cwd=ROOT)
    assert r.returncode == 1, explain(r)
    r = run("--", "/nonexistent/command", cwd=ROOT)
    assert r.returncode == 127, explain(r)


def test_timeout_kills_the_guest(harness: None, tmp_path: Path) -> None:
    start = time.monotonic()
    r = run("--timeout", "3", "--", "sleep", "60", cwd=ROOT, env=dict(os.environ, TMPDIR=str(tmp_path)), timeout=60)
    wall = time.monotonic() - start
    assert r.returncode == 124, explain(r)
    assert b"timeout" in r.stderr, explain(r)
    assert wall < 20, f"took {wall:.1f} s to time out"
    assert not list(tmp_path.iterdir()), "the run directory was left behind"
