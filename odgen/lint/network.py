"""`odgen lint --network NET.toml`: lint every node's file, then the network (NET rules).

    [[node]]
    file = "slave.eds"   # relative to NET.toml
    node_id = 2

The network file (docs/network.md, read by netfile.py) may also name a `[master]`, configure
values and boot options per node and wire PDOs (`[[pdo]]`); netconfig.py works out what is
configured, and the NET passes (passes/network.py) check the PDOs of the network as configured.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

from ..catalogue.network import NET003, NET014
from ..diagnostics import Diagnostics, Loc
from ..errors import OdgenError
from ..formats import load_path
from ..model import ObjectDictionary
from .driver import FileResult, RuleFilter, lint_path
from .netconfig import NodeModel, check_boot, check_sync, configure
from .netfile import NetworkSpec, NodeSpec, parse_network
from .passes import LintOptions
from .passes.network import Node, check_network

__all__ = ["BOOT_STATUS", "LintedNetwork", "NodeSpec", "lint_network", "lint_network_nodes", "parse_network",
           "read_network"]

BOOT_STATUS = 0x5F81  # the master's slave boot status object (docs/network.md)


def read_network(path: Path) -> tuple[str, NetworkSpec, Diagnostics]:
    """The network file's text, what it says, and its NET001/NET002 findings."""
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        raise OdgenError(f"{path}: cannot read: {err}") from None
    diags = Diagnostics()
    return text, parse_network(text, path, diags), diags


def network_checks(spec: NetworkSpec, nodes: list[NodeModel], dcfs: dict[str, ObjectDictionary | None],
                   diags: Diagnostics) -> None:
    """Configure the nodes (NET008-NET012), check boot options (NET011, NET013), the master (NET014),
    SYNC for the synchronous PDOs configured (NET015) and the PDOs of the network as configured
    (NET004-NET007)."""
    configure(spec, nodes, dcfs, diags)
    check_boot(spec, nodes, diags)
    check_sync(nodes, diags)
    master = next((n for n in nodes if n.spec.master), None)
    if master is not None and BOOT_STATUS in master.od.objects:
        diags.add(NET014, Loc(master.od.source, master.od.objects[BOOT_STATUS].line),
                  f"declares 0x{BOOT_STATUS:04X}, which the master's dictionary holds as the slave boot status",
                  BOOT_STATUS)
    check_network([Node(n.configured_od(), n.node_id, {k: v.loc for k, v in n.values.items()}) for n in nodes],
                  diags)


def load_dcfs(spec: NetworkSpec, diags: Diagnostics) -> dict[str, ObjectDictionary | None]:
    """The DCFs `dcf = ...` names, by node name; NET003 for one that cannot be read."""
    dcfs: dict[str, ObjectDictionary | None] = {}
    for node in spec.nodes:
        if node.dcf is None:
            continue
        try:
            dcfs[node.name], _ = load_path(node.dcf)
        except OdgenError as err:
            diags.add(NET003, Loc(spec.source, node.line("dcf")), str(err))
    return dcfs


@dataclass
class LintedNetwork:
    results: list[FileResult]  # per file, NET.toml first
    unreadable: bool  # a node's file could not be read
    spec: NetworkSpec
    nodes: list[NodeModel]  # the nodes whose description was read, with what the network file configures


def lint_network(path: Path, options: LintOptions, rule_filter: RuleFilter) -> tuple[list[FileResult], bool]:
    """The results per file (NET.toml first) and whether a node's file was unreadable."""
    linted = lint_network_nodes(path, options, rule_filter)
    return linted.results, linted.unreadable


def lint_network_nodes(path: Path, options: LintOptions, rule_filter: RuleFilter) -> LintedNetwork:
    """Lint every node's description and the network; the nodes as configured."""
    _, network, diags = read_network(path)
    results: dict[str, FileResult] = {str(path): FileResult(str(path), None)}
    nodes: list[NodeModel] = []
    unreadable = False
    for spec in network.nodes:
        try:
            result = lint_path(spec.file, replace(options, node_id=spec.node_id), rule_filter)
        except OdgenError as err:
            diags.add(NET003, spec.loc, str(err))
            unreadable = True
            continue
        merged = results.setdefault(result.source, FileResult(result.source, result.od))
        merged.diagnostics += [d for d in result.diagnostics if d not in merged.diagnostics]
        merged.omitted.update(result.omitted)
        if result.od is not None and spec.node_id is not None:
            nodes.append(NodeModel(spec, result.od))
    network_checks(network, nodes, load_dcfs(network, diags), diags)
    for d in diags:
        if rule_filter.keeps(d.rule):
            results.setdefault(d.loc.file, FileResult(d.loc.file, None)).diagnostics.append(d)
    for r in results.values():
        r.diagnostics = Diagnostics(list(dict.fromkeys(r.diagnostics))).sorted()
    return LintedNetwork(list(results.values()), unreadable, network, nodes)

