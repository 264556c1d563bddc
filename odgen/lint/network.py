"""`odgen lint --network NET.toml`: lint every node's file, then the network (NET rules).

    [[node]]
    file = "master.eds"   # relative to NET.toml
    node_id = 1
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, replace
from pathlib import Path

from ..catalogue.network import NET001, NET002, NET003
from ..diagnostics import Diagnostics, Loc
from ..errors import OdgenError
from .driver import FileResult, RuleFilter, lint_path
from .passes import LintOptions
from .passes.network import Node, check_network

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib


@dataclass(frozen=True)
class NodeSpec:
    file: Path
    node_id: int | None  # None when NET002 rejected it
    loc: Loc  # the [[node]] line


def parse_network(text: str, path: Path, diags: Diagnostics) -> list[NodeSpec]:
    source = str(path)
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        m = re.search(r"line (\d+)", str(err))
        diags.add(NET001, Loc(source, int(m.group(1)) if m else 0), f"not valid TOML: {err}")
        return []
    raw_nodes = doc.get("node")
    if set(doc) != {"node"} or not isinstance(raw_nodes, list) or not raw_nodes:
        diags.add(NET001, Loc(source, 1), "expected only [[node]] tables, at least one")
        return []
    lines = [n for n, line in enumerate(text.splitlines(), start=1) if line.strip().startswith("[[node]]")]
    specs: list[NodeSpec] = []
    seen: dict[int, int] = {}
    for n, raw in enumerate(raw_nodes):
        loc = Loc(source, lines[n] if n < len(lines) else 0)
        if not isinstance(raw, dict) or set(raw) != {"file", "node_id"} or not isinstance(raw["file"], str) \
                or not isinstance(raw["node_id"], int) or isinstance(raw["node_id"], bool):
            diags.add(NET001, loc, "[[node]] needs exactly `file` (a string) and `node_id` (an integer)")
            continue
        node_id: int | None = raw["node_id"]
        if not 1 <= raw["node_id"] <= 127:
            diags.add(NET002, loc, f"node_id {raw['node_id']} is outside 1..127")
            node_id = None
        elif raw["node_id"] in seen:
            diags.add(NET002, loc, f"node_id {raw['node_id']} is also the node at line {seen[raw['node_id']]}")
            node_id = None
        else:
            seen[raw["node_id"]] = loc.line
        specs.append(NodeSpec(path.parent / raw["file"], node_id, loc))
    return specs


def lint_network(path: Path, options: LintOptions, rule_filter: RuleFilter) -> tuple[list[FileResult], bool]:
    """The results per file (NET.toml first) and whether a node's file was unreadable."""
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        raise OdgenError(f"{path}: cannot read: {err}") from None
    diags = Diagnostics()
    results: dict[str, FileResult] = {str(path): FileResult(str(path), None)}
    nodes: list[Node] = []
    unreadable = False
    for spec in parse_network(text, path, diags):
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
            nodes.append(Node(result.od, spec.node_id))
    check_network(nodes, diags)
    for d in diags:
        if rule_filter.keeps(d.rule):
            results.setdefault(d.loc.file, FileResult(d.loc.file, None)).diagnostics.append(d)
    for r in results.values():
        r.diagnostics = Diagnostics(list(dict.fromkeys(r.diagnostics))).sorted()
    return list(results.values()), unreadable

