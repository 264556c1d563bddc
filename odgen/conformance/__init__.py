"""`odgen conformance FILE --iface CAN --node-id N`: check a live node against its description.

Modelled on what a CiA 301 conformance test looks at: SDO values, limits and lengths, access
rules, NMT and heartbeat, PDO configuration and transmission types, EMCY, and 0x1010/0x1011.
Whoever built the node: nothing is started, the node must be on the bus. The battery expects
only what CiA 301 (CiA 305 for LSS) requires of every device or what the description states
(docs/conformance.md). One result per check, reported as soon as it is known, as text and
as JUnit XML; any failure makes the run fail.
"""

from __future__ import annotations

import difflib
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from xml.etree import ElementTree as ET

from ..errors import OdgenError
from ..fileio import write_atomic
from ..formats import load_path
from ..model import ObjectDictionary
from . import checks, pdo
from .client import NO_ANSWER, Client, Settings, reachable_sdo_server
from .verdict import Check

RESETS = "resets the node or its communication, losing what was configured and not saved"
IMPERSONATES = "plays the heartbeat of another node-id on the bus"
ERASES = "writes 'load' to 0x1011, erasing the stored parameters"


@dataclass(frozen=True)
class Step:
    id: str  # the family is the id's first part (sdo, access, nmt, sync, pdo, emcy, lss, store)
    run: Callable[[Client], Check]
    destructive: str = ""  # what it does that only `--allow destructive` permits


CHECKS: tuple[Step, ...] = (
    Step("sdo.upload", checks.check_uploads),
    Step("sdo.limits", checks.check_limits),
    Step("sdo.lengths", checks.check_lengths),
    Step("access.read-only", checks.check_read_only),
    Step("access.write-only", checks.check_write_only),
    Step("access.missing", checks.check_missing),
    Step("nmt.states", checks.check_nmt_states),
    Step("nmt.heartbeat", checks.check_heartbeat),
    Step("sync.producer", checks.check_sync_producer),
    Step("sync.window", pdo.check_sync_window),
    Step("pdo.sequence", pdo.check_pdo_sequence),
    Step("pdo.tpdo-types", pdo.check_tpdo_types),
    Step("emcy.rpdo-length", pdo.check_emcy),
    Step("emcy.inhibit", pdo.check_emcy_inhibit),
    Step("emcy.error-register", pdo.check_error_register),
    Step("nmt.hb-consumer", checks.check_hb_consumer, IMPERSONATES),
    Step("nmt.guarding", checks.check_guarding),
    Step("nmt.boot-up", checks.check_bootup, RESETS),
    Step("nmt.reset-comm", checks.check_reset_communication, RESETS),
    Step("sdo.server", checks.check_sdo_server),
    Step("lss.inquire", checks.check_lss),
    Step("store.signature", pdo.check_signatures),
    Step("store.save-load", pdo.check_store_restore, ERASES),
)
CHECK_IDS = ("node.answers", *(step.id for step in CHECKS))


@dataclass(frozen=True)
class Selection:
    """--select/--ignore: check ids or id prefixes (`nmt`, `store.save-load`), as lint's rule ids."""

    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()

    def keeps(self, check_id: str) -> bool:
        if self.select and not check_id.startswith(self.select):
            return False
        return not (self.ignore and check_id.startswith(self.ignore))


def check_selectors(ids: Sequence[str], origin: str, known: Sequence[str] = CHECK_IDS) -> None:
    """Every id must be a check id or a prefix of one: a typo is the user's mistake (exit 2)."""
    for given in ids:
        if not any(check_id.startswith(given) for check_id in known):
            close = difflib.get_close_matches(given, [*known, *sorted({k.split(".")[0] for k in known})], n=3,
                                              cutoff=0.5)
            hint = f"; did you mean {', '.join(close)}?" if close else "; docs/conformance.md lists them"
            raise OdgenError(f"{origin}: '{given}' is not a conformance check id or prefix{hint}")


@dataclass
class Result:
    id: str
    check: Check
    seconds: float

    @property
    def failed(self) -> bool:
        return bool(self.check.failures)

    @property
    def state(self) -> str:
        return "FAIL" if self.check.failures else "SKIP" if self.check.skipped else "ok  "


def read_description(path: Path) -> ObjectDictionary:
    od, diags = load_path(path)
    if od is None:
        raise OdgenError(f"{path}: cannot be read: " + "; ".join(d.text() for d in diags)[:500])
    return od


def run(path: Path, iface: str, node_id: int, selection: Selection = Selection(), settings: Settings | None = None,
        on_result: Callable[[Result], None] = lambda _r: None) -> list[Result]:
    """The battery against the node; `on_result` hears each result as soon as it is known."""
    od = read_description(path)
    reachable_sdo_server(od, node_id, path)
    with tempfile.TemporaryDirectory(prefix="odgen-conformance-") as tmp:
        client = Client(od, iface, node_id, Path(tmp), settings or Settings())
        try:
            return run_checks(client, selection, on_result)
        finally:
            client.close()


def run_checks(client: Client, selection: Selection = Selection(),
               on_result: Callable[[Result], None] = lambda _r: None) -> list[Result]:
    results: list[Result] = []

    def done(result: Result) -> None:
        results.append(result)
        on_result(result)

    start = time.monotonic()
    alive = client.upload(0x1000, 0)[1] != NO_ANSWER
    done(Result("node.answers", Check(f"node {client.node_id} answers an SDO upload of 0x1000", passed=int(alive),
                                      failures=[] if alive else ["no SDO answer"]), time.monotonic() - start))
    if not alive:
        return results
    for step in CHECKS:
        if selection.keeps(step.id):
            start = time.monotonic()
            done(Result(step.id, _run_step(client, step), time.monotonic() - start))
    client.nmt("PRE-OPERATIONAL")
    return results


def _run_step(client: Client, step: Step) -> Check:
    name = (step.run.__doc__ or step.id).strip().splitlines()[0]
    if step.destructive and not client.settings.destructive:
        return Check(name, skipped=f"{step.destructive}: run with --allow destructive")
    client.nmt("PRE-OPERATIONAL")
    if not client.answers(patience=True):  # a node gone silent fails what needs it, quickly
        return Check(name, failures=[f"node {client.node_id} does not answer an SDO upload of 0x1000 any more"])
    try:
        return step.run(client)
    except Exception as err:  # a client-side failure is a failed check; the others still run
        return Check(name, failures=[f"raised {type(err).__name__}: {err}"])


def result_lines(r: Result) -> list[str]:
    c = r.check
    detail = f"({c.skipped})" if r.state == "SKIP" else f"{c.passed} passed, {len(c.failures)} failed"
    lines = [f"  {r.state} {r.id}: {c.name}: {detail}"]
    lines.extend(f"       {f}" for f in c.failures[:10])
    if len(c.failures) > 10:
        lines.append(f"       ... {len(c.failures) - 10} more")
    lines.extend(f"       note: {n}" for n in c.notes)
    return lines


def header_line(path: Path, node_id: int) -> str:
    return f"{path}: node {node_id}"


def summary_line(results: list[Result]) -> str:
    failed = sum(r.failed for r in results)
    skipped = sum(1 for r in results if r.state == "SKIP")
    return (f"odgen conformance: {len(results) - failed} of {len(results)} checks passed"
            + (f" ({skipped} skipped)" if skipped else "") + (f", {failed} failed" if failed else ""))


def text_lines(path: Path, node_id: int, results: list[Result]) -> list[str]:
    return [header_line(path, node_id), *(line for r in results for line in result_lines(r)), summary_line(results)]


def junit_xml(path: Path, node_id: int, results: list[Result]) -> str:
    suite = ET.Element("testsuite", name=f"odgen conformance {path.name} node {node_id}", tests=str(len(results)),
                       failures=str(sum(r.failed for r in results)),
                       skipped=str(sum(1 for r in results if r.state == "SKIP")),
                       time=f"{sum(r.seconds for r in results):.3f}")
    for r in results:
        case = ET.SubElement(suite, "testcase", classname=f"conformance.{r.id.split('.')[0]}", name=r.id,
                             time=f"{r.seconds:.3f}")
        if r.failed:
            failure = ET.SubElement(case, "failure", message=f"{r.check.name}: {r.check.failures[0]}")
            failure.text = "\n".join(r.check.failures[:200])
        elif r.check.skipped:
            ET.SubElement(case, "skipped", message=r.check.skipped)
        if r.check.notes:
            ET.SubElement(case, "system-out").text = "\n".join(r.check.notes)
    root = ET.Element("testsuites")
    root.append(suite)
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n"


def write_junit(out: Path, path: Path, node_id: int, results: list[Result]) -> None:
    write_atomic(out, junit_xml(path, node_id, results))
