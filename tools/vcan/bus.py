"""One vcan session for many commands: the host's vcan when it has one, else one guest.

    bus = VcanBus(shared=DIR)          # DIR: a host directory the commands may write under
    done = bus.run([exe, ...], cwd=..., env=..., timeout=120)   # a CompletedProcess
    bus.close()

On a host with vcan (tools/vcan/run.py's host mode) each command runs directly. Otherwise
the first run() boots one User-Mode Linux guest through tools/vcan/run.py with
tools/vcan/serve.py as its command, and every run() hands its command to that server
(files under DIR/.vcan-bus/); the guest is booted once, however many commands follow.
Waits are on events (files appearing, the guest exiting) with generous deadlines.
Standard library only.
"""

from __future__ import annotations

import contextlib
import ctypes
import importlib.util
import itertools
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
BOOT_DEADLINE = 180.0
POLL = 0.02


def _run_module():
    spec = importlib.util.spec_from_file_location("odgen_vcan_run", HERE / "run.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _die_with_parent() -> None:
    """The guest must not outlive the process that asked for it (PR_SET_PDEATHSIG)."""
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGTERM)


class BusError(Exception):
    """The vcan session itself failed (not the command)."""


class VcanBus:
    def __init__(self, shared: Path, ifaces: tuple[str, ...] = ("vcan0",), mode: str | None = None) -> None:
        self.shared, self.ifaces = Path(shared).resolve(), ifaces
        self.mode = mode or os.environ.get("ODGEN_VCAN_MODE", "auto")
        self.base = self.shared / ".vcan-bus"
        self.guest: subprocess.Popen[bytes] | None = None
        self.host: bool | None = None
        self.numbers = itertools.count(1)
        self.log: list[dict[str, object]] = []  # one record per command: argv, seconds, status

    @property
    def where(self) -> str:
        return "host" if self.host else "uml"

    def run(self, argv: list[str], cwd: Path | str | None = None, env: dict[str, str] | None = None,
            timeout: float = 300.0) -> subprocess.CompletedProcess[str]:
        env = dict(os.environ if env is None else env)
        cwd = str(cwd or os.getcwd())
        started = time.monotonic()
        if self.host is None:
            self.host = self.mode != "uml" and _run_module().host_can_ready(list(self.ifaces))
        if self.host:
            env.update(ODGEN_VCAN="host", ODGEN_VCAN_IFACES=",".join(self.ifaces))
            try:
                raw = subprocess.run(argv, cwd=cwd, env=env, capture_output=True, timeout=timeout,
                                     stdin=subprocess.DEVNULL, check=False)
                done = subprocess.CompletedProcess(argv, raw.returncode, _text(raw.stdout), _text(raw.stderr))
            except subprocess.TimeoutExpired as err:
                done = subprocess.CompletedProcess(argv, 124, _text(err.stdout), _text(err.stderr) + "timeout\n")
        else:
            done = self._in_guest(argv, cwd, env, timeout)
        self.log.append({"argv": [Path(argv[0]).name, *(a[-60:] for a in argv[1:3])], "where": self.where,
                         "status": done.returncode, "seconds": round(time.monotonic() - started, 3)})
        return done

    # -- the guest --------------------------------------------------------------------------

    def _boot(self) -> None:
        for d in ("req", "out", "tmp"):
            (self.base / d).mkdir(parents=True, exist_ok=True)
        self.console = open(self.base / "run.log", "wb")  # noqa: SIM115 - closed in close()
        cmd = [sys.executable, str(HERE / "run.py"), "--mode", "uml", "--rw", str(self.shared), "--timeout", "14400",
               *(a for i in self.ifaces for a in ("--iface", i)),
               "--", sys.executable, str(HERE / "serve.py"), str(self.base)]
        self.guest = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=self.console, stderr=self.console,
                                      preexec_fn=_die_with_parent)
        if not self._wait_for(self.base / "ready", BOOT_DEADLINE):
            raise BusError(f"the vcan guest did not come up within {BOOT_DEADLINE:g} s:\n{self._guest_log()}")

    def _in_guest(self, argv: list[str], cwd: str, env: dict[str, str], timeout: float
                  ) -> subprocess.CompletedProcess[str]:
        if self.guest is None:
            self._boot()
        number = next(self.numbers)
        self._request(number, {"argv": argv, "cwd": cwd, "env": env, "timeout": timeout})
        out = self.base / "out" / str(number)
        # The server kills the command at `timeout`; the margin covers a slow guest.
        if not self._wait_for(out / "status", timeout + 120):
            raise BusError(f"no exit status for {argv[0]} from the vcan guest:\n{self._guest_log()}")
        status = int((out / "status").read_text().split()[0])
        return subprocess.CompletedProcess(argv, status, _text((out / "stdout").read_bytes()),
                                           _text((out / "stderr").read_bytes()))

    def _request(self, number: int, request: dict[str, object]) -> None:
        tmp = self.base / "tmp" / f"{number}.json"
        tmp.write_text(json.dumps(request))
        tmp.rename(self.base / "req" / f"{number}.json")

    def _wait_for(self, path: Path, deadline: float) -> bool:
        end = time.monotonic() + deadline
        while time.monotonic() < end:
            if path.exists():
                return True
            if self.guest is not None and self.guest.poll() is not None:
                return path.exists()
            time.sleep(POLL)
        return path.exists()

    def _guest_log(self) -> str:
        running = self.guest is not None and self.guest.poll() is None
        state = "running" if running else f"exited {self.guest and self.guest.returncode}"
        try:
            text = (self.base / "run.log").read_text(errors="replace")[-4000:]
        except OSError:
            text = ""
        return f"tools/vcan/run.py {state}\n{text}"

    def close(self) -> int | None:
        """Stop the guest; its run.py exit status (0: the server ended cleanly), None without one."""
        if self.guest is None:
            return None
        status: int | None
        self._request(next(self.numbers), {"stop": True})
        try:
            status = self.guest.wait(60)
        except subprocess.TimeoutExpired:
            self.guest.terminate()
            status = self.guest.wait()
        self.console.close()
        self.guest = None
        return status


def _text(data: bytes | str | None) -> str:
    return data.decode(errors="replace") if isinstance(data, bytes) else (data or "")
