"""Round trips on a CAN bus: build a node from a description, check it with python canopen: the
round trip's own checks, then the conformance battery (odgen/conformance) with every check allowed."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path

from ..pipeline import Request
from ..conformance import Selection
from ..fileio import write_atomic
from .build import build_node

# What a round trip adds before the user's options: room to write strings and domains, and
# the manufacturer and profile ranges in a persistence group so store/restore can be checked.
ROUNDTRIP_DEFAULTS = """
[[entry]]
match = "*"
capacity = 32

[[entry]]
match = "0x2000-0x9FFF"
storage = "persist:app"
"""


@dataclass
class FileOutcome:
    path: str
    checks: list[dict[str, object]]
    error: str = ""

    @property
    def ok(self) -> bool:
        return not self.error and all(int(str(c["failed"])) == 0 for c in self.checks)


def roundtrip_file(path: Path, iface: str, node_id: int, options: Path | None, input_format: str | None = None,
                   selection: Selection | None = None) -> FileOutcome:
    from ..conformance.client import reachable_sdo_server
    from .checks import run_checks, session  # needs python canopen and a CAN interface

    request = Request(path, name="od", options=options, node_id=node_id, defaults=ROUNDTRIP_DEFAULTS,
                      input_format=input_format)
    program, result = build_node(request)
    assert result.od is not None and result.placements is not None
    reachable_sdo_server(result.od, node_id, path)
    with session(result.od, result.placements, program, iface, node_id) as s:
        checks = run_checks(s, selection or Selection())
    return FileOutcome(str(path), [{"id": check_id, **check.as_dict()} for check_id, check in checks])


def summary_lines(outcome: FileOutcome) -> list[str]:
    lines = [f"{outcome.path}:"]
    if outcome.error:
        return lines + [f"  error: {outcome.error}"]
    for c in outcome.checks:
        state = f"skipped ({c['skipped']})" if c["skipped"] else f"{c['passed']} passed, {c['failed']} failed"
        lines.append(f"  {c['id']}: {c['name']}: {state}")
        lines.extend(f"    FAIL {f}" for f in list(c["failures"])[:10])  # type: ignore[call-overload]
        lines.extend(f"    note: {n}" for n in list(c["notes"]))  # type: ignore[call-overload]
    return lines


def write_report(path: Path, outcomes: list[FileOutcome]) -> None:
    doc = {"files": [{"file": o.path, "ok": o.ok, "error": o.error, "checks": o.checks} for o in outcomes],
           "vcan": os.environ.get("ODGEN_VCAN", "host")}
    write_atomic(path, json.dumps(doc, indent=2) + "\n")
