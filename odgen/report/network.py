"""The network part of the report (`--network NET.toml`): who sends which PDO to whom.

The nodes and the NET findings are those `odgen lint --network` reads and reports; the PDOs are
the NET rules' view of them (enabled ones, COB-ID resolved with the node's node-id). Each TPDO is
drawn with one lane for itself and one per RPDO that receives its COB-ID, so the bits each
consumer takes are under the bits the producer sends.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..diagnostics import Diagnostics
from ..errors import OdgenError
from ..formats import load_path
from ..lint.driver import RuleFilter
from ..lint.network import lint_network, parse_network
from ..lint.passes import LintOptions
from ..lint.passes.network import Node, pdos
from ..lint.passes.network import Pdo as NetPdo
from .view import Finding, Lane, Pdo, finding, pdo_boxes


@dataclass
class NetworkView:
    source: str
    nodes: list[tuple[int, str, bool]]  # node-id, file, whether it is the report's file
    ids: list[int]  # matrix rows (producers) and columns (consumers)
    matrix: list[list[str]]  # COB-IDs producer -> consumer
    cobs: list[tuple[str, str, str]]  # COB-ID, producer, consumers
    flows: list[Pdo]
    findings: list[Finding]


def _nodes(path: Path) -> list[Node]:
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        raise OdgenError(f"{path}: cannot read: {err}") from None
    nodes = []
    for spec in parse_network(text, path, Diagnostics()).nodes:  # lint_network reports what is wrong
        try:
            od, _ = load_path(spec.file)
        except OdgenError:
            continue
        if od is not None and spec.node_id is not None:
            nodes.append(Node(od, spec.node_id))
    return nodes


def _lane(p: NetPdo) -> Lane:
    obj = p.node.od.objects.get(p.comm + 0x200)
    return Lane(p.name, pdo_boxes(p.node.od, obj) if obj is not None else [])


def build_network(path: Path, report_file: Path, can_fd: bool) -> NetworkView:
    results, _ = lint_network(path, LintOptions(can_fd=can_fd), RuleFilter())
    findings = [finding(d) for r in results for d in r.diagnostics if d.rule.startswith("NET")]
    nodes = _nodes(path)
    every = [p for node in nodes for p in pdos(node)]
    ids = sorted(node.node_id for node in nodes)
    cells: dict[tuple[int, int], list[str]] = {}
    cobs, flows = [], []
    frame = 512 if can_fd else 64
    for cob in sorted({p.cob_id for p in every}):
        senders = [p for p in every if p.cob_id == cob and p.kind == "TPDO"]
        receivers = [p for p in every if p.cob_id == cob and p.kind == "RPDO"]
        cobs.append((f"0x{cob:03X}", ", ".join(p.name for p in senders) or "none",
                     ", ".join(p.name for p in receivers) or "none"))
        for s in senders:
            for r in receivers:
                cells.setdefault((s.node.node_id, r.node.node_id), []).append(f"0x{cob:03X}")
            params = [("COB-ID", f"0x{cob:03X}"), ("Consumers", str(len(receivers)))]
            flows.append(Pdo(s.kind, s.number, s.comm, s.comm + 0x200, frame, params,
                             [_lane(s)] + [_lane(r) for r in receivers], node=s.node.node_id))
    matrix = [[", ".join(cells.get((a, b), [])) for b in ids] for a in ids]
    me = report_file.resolve()
    listed = [(node.node_id, node.od.source, Path(node.od.source).resolve() == me) for node in nodes]
    return NetworkView(str(path), sorted(listed), ids, matrix, cobs, flows, findings)
