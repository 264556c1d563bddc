"""`odgen conformance FILE --iface CAN --node-id N`: check a live node against its description.

Modelled on what a CiA 301 conformance test looks at: SDO values, limits and lengths, access
rules, NMT and heartbeat, PDO configuration and transmission types, EMCY, and 0x1010/0x1011.
Whoever built the node: nothing is started, the node must be on the bus. One result per
check, as text and as JUnit XML; any failure makes the run fail.
"""

from __future__ import annotations

import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from xml.etree import ElementTree as ET

from ..errors import OdgenError
from ..fileio import write_atomic
from ..formats import load_path
from ..roundtrip.checks import Check, reachable_sdo_server
from . import checks, pdo
from .client import Client

# (id, function): the family is the id's first part (sdo, access, nmt, sync, pdo, emcy, store).
CHECKS: tuple[tuple[str, Callable[[Client], Check]], ...] = (
    ("sdo.upload", checks.check_uploads),
    ("sdo.limits", checks.check_limits),
    ("sdo.lengths", checks.check_lengths),
    ("access.read-only", checks.check_read_only),
    ("access.write-only", checks.check_write_only),
    ("access.missing", checks.check_missing),
    ("nmt.states", checks.check_nmt_states),
    ("nmt.heartbeat", checks.check_heartbeat),
    ("sync.producer", checks.check_sync_producer),
    ("sync.window", pdo.check_sync_window),
    ("pdo.sequence", pdo.check_pdo_sequence),
    ("pdo.tpdo-types", pdo.check_tpdo_types),
    ("emcy.rpdo-length", pdo.check_emcy),
    ("emcy.inhibit", pdo.check_emcy_inhibit),
    ("emcy.error-register", pdo.check_error_register),
    ("nmt.hb-consumer", checks.check_hb_consumer),
    ("nmt.guarding", checks.check_guarding),
    ("nmt.boot-up", checks.check_bootup),
    ("nmt.reset-comm", checks.check_reset_communication),
    ("sdo.server", checks.check_sdo_server),
    ("lss.inquire", checks.check_lss),
    ("store.signature", pdo.check_signatures),
    ("store.save-load", pdo.check_store_restore),
)


@dataclass
class Result:
    id: str
    check: Check
    seconds: float

    @property
    def failed(self) -> bool:
        return bool(self.check.failures)


def run(path: Path, iface: str, node_id: int, only: Callable[[str], bool] = lambda _id: True) -> list[Result]:
    od, diags = load_path(path)
    if od is None:
        raise OdgenError(f"{path}: cannot be read: " + "; ".join(d.text() for d in diags)[:500])
    reachable_sdo_server(od, node_id, path)
    with tempfile.TemporaryDirectory(prefix="odgen-conformance-") as tmp:
        client = Client(od, iface, node_id, Path(tmp))
        try:
            return _run_checks(client, only)
        finally:
            client.close()


def _run_checks(client: Client, only: Callable[[str], bool]) -> list[Result]:
    start = time.monotonic()
    alive = client.upload(0x1000, 0)[1] != -1
    results = [Result("node.answers", Check(f"node {client.node_id} answers an SDO upload of 0x1000",
                                            passed=int(alive), failures=[] if alive else ["no SDO answer"]),
                      time.monotonic() - start)]
    if not alive:
        return results
    for check_id, step in CHECKS:
        if not only(check_id):
            continue
        start = time.monotonic()
        try:
            client.nmt("PRE-OPERATIONAL")
            check = step(client)
        except Exception as err:  # a client-side failure is a failed check; the others still run
            check = Check(step.__doc__ or check_id, failures=[f"raised {type(err).__name__}: {err}"])
        results.append(Result(check_id, check, time.monotonic() - start))
    client.nmt("PRE-OPERATIONAL")
    return results


def text_lines(path: Path, node_id: int, results: list[Result]) -> list[str]:
    lines = [f"{path}: node {node_id}"]
    for r in results:
        c = r.check
        state = "SKIP" if c.skipped and not c.failures else ("FAIL" if c.failures else "ok  ")
        detail = f"({c.skipped})" if state == "SKIP" else f"{c.passed} passed, {len(c.failures)} failed"
        lines.append(f"  {state} {r.id}: {c.name}: {detail}")
        lines.extend(f"       {f}" for f in c.failures[:10])
        if len(c.failures) > 10:
            lines.append(f"       ... {len(c.failures) - 10} more")
    failed = sum(r.failed for r in results)
    lines.append(f"odgen conformance: {len(results) - failed} of {len(results)} checks passed"
                 + (f", {failed} failed" if failed else ""))
    return lines


def junit_xml(path: Path, node_id: int, results: list[Result]) -> str:
    suite = ET.Element("testsuite", name=f"odgen conformance {path.name} node {node_id}", tests=str(len(results)),
                       failures=str(sum(r.failed for r in results)),
                       skipped=str(sum(1 for r in results if r.check.skipped and not r.failed)),
                       time=f"{sum(r.seconds for r in results):.3f}")
    for r in results:
        case = ET.SubElement(suite, "testcase", classname=f"conformance.{r.id.split('.')[0]}", name=r.id,
                             time=f"{r.seconds:.3f}")
        if r.failed:
            failure = ET.SubElement(case, "failure", message=f"{r.check.name}: {r.check.failures[0]}")
            failure.text = "\n".join(r.check.failures[:200])
        elif r.check.skipped:
            ET.SubElement(case, "skipped", message=r.check.skipped)
    root = ET.Element("testsuites")
    root.append(suite)
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n"


def write_junit(out: Path, path: Path, node_id: int, results: list[Result]) -> None:
    write_atomic(out, junit_xml(path, node_id, results))
