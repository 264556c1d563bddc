#!/usr/bin/env python3
"""Run commands on request inside one vcan session (one guest boot for many commands).

    tools/vcan/run.py --rw DIR ... -- python tools/vcan/serve.py DIR

DIR is shared with the host (a --rw directory). The host asks for a command by renaming
a JSON file {"argv", "cwd", "env", "timeout"} into DIR/req/ (name: a sequence number);
this server finds it by listing the directory (hostfs shows the host's changes at once;
names are only opened after a listing has shown them), runs the command with stdin
/dev/null and stdout/stderr in DIR/out/N/, and writes its exit status to DIR/out/N/status
last (temp file + rename): 124 when the command overran its timeout, 127 when it could not
be started, 128+N when killed by signal N. Leftover processes of the command's session are
killed before the next command. {"stop": true} ends the server (exit 0). DIR/ready appears
once the server listens. Commands run one at a time, in name order. Standard library only.
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

POLL = 0.02


def _write_atomic(path: Path, text: str) -> None:
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text)
    tmp.rename(path)


def _killpg(pid: int) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pid, signal.SIGKILL)


def run_one(request: dict, out: Path) -> int:
    env = dict(request["env"])
    for key in ("ODGEN_VCAN", "ODGEN_VCAN_IFACES"):  # where the command really runs
        env[key] = os.environ.get(key, env.get(key, ""))
    with open(out / "stdout", "wb") as stdout, open(out / "stderr", "wb") as stderr:
        try:
            proc = subprocess.Popen(request["argv"], cwd=request["cwd"], env=env, stdin=subprocess.DEVNULL,
                                    stdout=stdout, stderr=stderr, start_new_session=True)
        except OSError as err:
            stderr.write(f"vcan-serve: cannot run {request['argv'][0]}: {err}\n".encode())
            return 127
        try:
            rc = proc.wait(timeout=request.get("timeout") or None)
            status = 128 - rc if rc < 0 else rc
        except subprocess.TimeoutExpired:
            stderr.write(f"vcan-serve: timeout: still running after {request['timeout']:g} s; killed\n".encode())
            status = 124
        _killpg(proc.pid)  # the command, on timeout, and whatever it left running
        proc.wait()
    return status


def serve(base: Path) -> int:
    requests, results = base / "req", base / "out"
    done: set[str] = set()
    _write_atomic(base / "ready", f"{os.environ.get('ODGEN_VCAN', '?')}\n")
    while True:
        names = sorted((n for n in os.listdir(requests) if n.endswith(".json") and n not in done),
                       key=lambda n: int(n.split(".")[0]))
        if not names:
            time.sleep(POLL)
            continue
        for name in names:
            done.add(name)
            request = json.loads((requests / name).read_text())
            if request.get("stop"):
                return 0
            out = results / name.split(".")[0]
            out.mkdir()
            started = time.monotonic()
            status = run_one(request, out)
            _write_atomic(out / "status", f"{status} {time.monotonic() - started:.3f}\n")


if __name__ == "__main__":
    sys.exit(serve(Path(sys.argv[1])))
