"""The network part of the report (`--network NET.toml`): who sends which PDO to whom.

The nodes and the NET findings are those `odgen lint --network` reads and reports; the PDOs are
the NET rules' view of them (enabled ones, COB-ID resolved with the node's node-id), on the
network as the network file configures it. Each TPDO is drawn with one lane for itself and one
per RPDO that receives its COB-ID, so the bits each consumer takes are under the bits the
producer sends. With a `[master]`, the boot configuration (docs/network.md) and the `[[pdo]]`
wiring are listed too.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from ..lint.driver import RuleFilter
from ..lint.netconfig import IDENTITY, expected_identity
from ..lint.network import LintedNetwork, lint_network_nodes
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
    boot: list[tuple[str, str, str, str, str, str]] = field(default_factory=list)  # per node, with a [master]
    wiring: list[tuple[str, str, str, str]] = field(default_factory=list)  # [[pdo]]: from, to, COB-ID, entries


def _boot(linted: LintedNetwork) -> list[tuple[str, str, str, str, str, str]]:
    """node-id, name, role, identity checked, heartbeat, entries configured: what the master does at boot."""
    if linted.spec.master is None:
        return []
    rows = []
    for node in linted.nodes:
        options = node.spec.options
        if node.spec.master:
            starts = "all at once" if options.get("start_all") else "one by one"
            role = f"master; starts the slaves {starts}; boot time {options.get('boot_time', 0)} ms"
            identity, heartbeat = "", ""
        else:
            role = ("mandatory" if options.get("mandatory") else "optional") + " slave" + \
                (", kept alive" if options.get("keep_alive") else "")
            expected = expected_identity(node)
            identity = ", ".join(f"{key} 0x{expected[sub]:X}" for key, sub in IDENTITY if sub in expected) \
                or "not checked"
            heartbeat = f"{options['heartbeat']} ms" if options.get("heartbeat") else "not watched"
        rows.append((str(node.node_id), node.spec.name, role, identity, heartbeat, str(len(node.values))))
    return rows


def _wiring(linted: LintedNetwork) -> list[tuple[str, str, str, str]]:
    rows = []
    by_name = {n.spec.name: n for n in linted.nodes}
    for pdo in linted.spec.pdos:
        producer = by_name.get(pdo.producer)
        cob = producer.in_force(0x1800 + pdo.tpdo - 1, 1) if producer is not None else None
        rows.append((f"{pdo.producer} TPDO{pdo.tpdo}", f"{pdo.consumer} RPDO{pdo.rpdo}",
                     f"0x{cob:03X}" if cob is not None else "?", ", ".join(f"{a} → {b}" for a, b in pdo.entries)))
    return rows


def _lane(p: NetPdo) -> Lane:
    obj = p.node.od.objects.get(p.comm + 0x200)
    return Lane(p.name, pdo_boxes(p.node.od, obj) if obj is not None else [])


def build_network(path: Path, report_file: Path, can_fd: bool) -> NetworkView:
    linted = lint_network_nodes(path, LintOptions(can_fd=can_fd), RuleFilter())
    findings = [finding(d) for r in linted.results for d in r.diagnostics if d.rule.startswith("NET")]
    nodes = [Node(n.configured_od(), n.node_id) for n in linted.nodes]
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
    return NetworkView(str(path), sorted(listed), ids, matrix, cobs, flows, findings, _boot(linted), _wiring(linted))
