"""Run `odgen conformance` against node programs one after the other on vcan (the checks in-process).

    python tests/vcan/conformance_nodes.py PLAN.json OUT.json     (in the vcan session)

PLAN is a list of {"name", "exe", "file", "junit", "cli", "select", "settings"}: each node program
is started with node-id 5 and a fresh --nv file, its boot-up awaited, the battery run against it
(only the check ids or prefixes of "select" when given; "settings": odgen.conformance.client.Settings
fields, "stored" as [index, sub] pairs; results also written as JUnit XML to "junit"), and the
node stopped ("stop_after": already once that check's result came; "configure": values written
and saved before, and read after a reset node once the battery is done). OUT gets, per node, the ids
of the failed checks, the skips and notes, when each result came, and the text report. Where
"cli" is a list (of more arguments) `python -m odgen conformance` runs against the node too,
to check what the command prints, when, and its exit status ("interrupt_after": SIGINT once
that check's line came).
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import can

from odgen.conformance import Result, Selection, run, text_lines, write_junit
from odgen.conformance.client import Settings

IFACE = os.environ.get("ODGEN_VCAN_IFACES", "vcan0").split(",")[0]
NODE_ID = 5
DEADLINE = 30.0  # ends at the boot-up: generous for a loaded machine


def start(exe: str, nv: Path) -> subprocess.Popen[bytes]:
    with can.Bus(interface="socketcan", channel=IFACE,
                 can_filters=[{"can_id": 0x700 + NODE_ID, "can_mask": 0x7FF}]) as bus:
        proc = subprocess.Popen([exe, "--iface", IFACE, "--node-id", str(NODE_ID), "--nv", str(nv)],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        end = time.monotonic() + DEADLINE
        while time.monotonic() < end:
            msg = bus.recv(0.5)
            if msg is not None and bytes(msg.data) == b"\x00":
                return proc
    proc.kill()
    raise SystemExit(f"{exe}: no boot-up within {DEADLINE:g} s: {proc.communicate()[1]!r}")


def stop(proc: subprocess.Popen[bytes]) -> None:
    proc.terminate()
    try:
        proc.wait(DEADLINE)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()


def _interruptible() -> None:
    """Ctrl-C reaches the command as at a terminal: a command started in the background (as the vcan
    session's are) inherits SIGINT ignored, and Python then never raises KeyboardInterrupt."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def cli(node: dict) -> dict[str, object]:
    """`odgen conformance` on the node, each line of its output with the time it came; SIGINT once
    the line of check "interrupt_after" came (an interrupted run keeps what --junit wrote)."""
    started = time.monotonic()
    proc = subprocess.Popen([sys.executable, "-m", "odgen", "conformance", node["file"], "--iface", IFACE,
                             "--node-id", str(NODE_ID), *node["cli"]], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, preexec_fn=_interruptible)
    assert proc.stdout is not None and proc.stderr is not None
    lines = []
    for line in proc.stdout:
        lines.append((round(time.monotonic() - started, 3), line.rstrip("\n")))
        if node.get("interrupt_after") and line.startswith("  ") and f" {node['interrupt_after']}:" in line:
            proc.send_signal(signal.SIGINT)
    stderr = proc.stderr.read()
    return {"status": proc.wait(), "stdout": "".join(text + "\n" for _, text in lines), "stderr": stderr,
            "lines": lines}


def configured(node: dict, before: bool) -> list[str]:
    """"configure": [index, sub, hex] values written and saved (0x1010 sub 1) before the battery, as
    an integrator leaves a device; after it (and a reset node), what no longer reads so."""
    import canopen

    network = canopen.Network()
    network.connect(interface="socketcan", channel=IFACE)
    try:
        remote = network.add_node(NODE_ID, canopen.ObjectDictionary())
        remote.sdo.RESPONSE_TIMEOUT = 2.0
        if before:
            for index, sub, value in node["configure"]:
                remote.sdo.download(index, sub, bytes.fromhex(value))
            remote.sdo.download(0x1010, 1, b"save")
            return []
        remote.nmt.state = "RESET"
        time.sleep(1.0)  # the boot-up of a node started in milliseconds
        return [f"0x{index:04X}sub{sub}: {bytes(remote.sdo.upload(index, sub)).hex()}, configured {value}"
                for index, sub, value in node["configure"] if bytes(remote.sdo.upload(index, sub)).hex() != value]
    finally:
        network.disconnect()


def check_node(node: dict, proc: subprocess.Popen[bytes]) -> dict[str, object]:
    """The battery in-process, as "select" and "settings" say; "stop_after": the node is stopped
    once that check's result came (the checks after it find no node)."""
    started = time.monotonic()
    given = dict(node.get("settings") or {})
    if given.get("stored") is not None:
        given["stored"] = frozenset(tuple(key) for key in given["stored"])
    heard: list[tuple[str, float]] = []

    def on_result(result: Result) -> None:
        heard.append((result.id, round(time.monotonic() - started, 3)))
        if result.id == node.get("stop_after"):
            stop(proc)

    if node.get("configure"):
        configured(node, before=True)
    results = run(Path(node["file"]), IFACE, NODE_ID, Selection(tuple(node.get("select") or ())), Settings(**given),
                  on_result)
    seconds = time.monotonic() - started
    changed = configured(node, before=False) if node.get("configure") else []
    write_junit(Path(node["junit"]), Path(node["file"]), NODE_ID, results)
    return {"name": node["name"], "seconds": round(seconds, 2), "failed": [r.id for r in results if r.failed],
            "skipped": {r.id: r.check.skipped for r in results if r.state == "SKIP"},
            "notes": {r.id: r.check.notes for r in results if r.check.notes}, "checks": len(results),
            "verdicts": {r.id: [r.state.strip(), r.check.passed, len(r.check.failures)] for r in results},
            "heard": heard, "durations": [round(r.seconds, 3) for r in results], "changed": changed,
            "text": text_lines(Path(node["file"]), NODE_ID, results)}


def main() -> int:
    plan = json.loads(Path(sys.argv[1]).read_text())
    out: list[dict[str, object]] = []
    with tempfile.TemporaryDirectory() as tmp:
        for i, node in enumerate(plan):
            proc = start(node["exe"], Path(tmp) / f"{i}.nv")
            try:
                entry = check_node(node, proc)
                if node.get("cli") is not None:
                    entry["cli"] = cli(node)
                out.append(entry)
                print(f"{node['name']}: {entry['checks']} checks, failed: {entry['failed']} ({entry['seconds']} s)",
                      flush=True)
            finally:
                stop(proc)
    Path(sys.argv[2]).write_text(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
