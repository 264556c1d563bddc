"""A diff as text (one gcc-style line per change), JSON, or SARIF 2.1.0 located in NEW."""

from __future__ import annotations

import json
from collections.abc import Callable

from .. import __version__
from ..place.migration import KEEP, Step
from ..lint.reporters.sarif import SCHEMA_URI, artifact_location, uri_base_ids
from . import DiffResult
from .changes import BREAKING, CLASS_TITLES, CLASSES, COMPATIBLE, KINDS, STORED, Change, Kind

LEVELS = {BREAKING: "error", STORED: "warning", COMPATIBLE: "note"}


def summary(result: DiffResult) -> dict[str, int]:
    return {cls: result.count(cls) for cls in CLASSES}


def render_text(result: DiffResult) -> str:
    lines = [c.text(result.new, result.old) for c in result.changes]
    counts = ", ".join(f"{n} {cls}" for cls, n in summary(result).items())
    shown = "; ".join(f"{what} {change}" for what, change in result.versions.items())
    lines.append(f"{result.old} -> {result.new}: {len(result.changes)} change(s): {counts} ({shown})")
    return "\n".join(lines) + "\n"


def _change(c: Change, result: DiffResult) -> dict[str, object]:
    return {"id": c.kind, "class": c.change_class, "file": result.new, "line": c.line, "old_line": c.old_line,
            "index": c.index, "sub": c.sub, "message": c.message, "text": c.text(result.new, result.old)}


def _step(s: Step) -> dict[str, object]:
    return {"index": s.index, "sub": s.sub, "action": s.action, "reason": s.reason, "checked": s.checked,
            "old_type": s.old.data_type if s.old else None, "old_length": s.old.length if s.old else None,
            "new_type": s.new.data_type if s.new else None, "new_length": s.new.length if s.new else None}


def render_json(result: DiffResult) -> str:
    doc = {
        "tool": "odgen",
        "version": __version__,
        "old": result.old,
        "new": result.new,
        "changes": [_change(c, result) for c in result.changes],
        "migration": {group: {"moved": p.moved, "steps": [_step(s) for s in p.steps if s.action != KEEP or s.checked]}
                      for group, p in result.groups.items()},
        "versions": result.versions,
        "summary": summary(result),
    }
    return json.dumps(doc, indent=2) + "\n"


def _rule(kind: Kind) -> dict[str, object]:
    return {"id": kind.id, "name": kind.title, "shortDescription": {"text": kind.title},
            "fullDescription": {"text": kind.why}, "defaultConfiguration": {"level": LEVELS[kind.cls]},
            "properties": {"class": CLASS_TITLES[kind.cls]}}


def _result(c: Change, result: DiffResult, rule_index: dict[str, int]) -> dict[str, object]:
    physical: dict[str, object] = {"artifactLocation": artifact_location(result.new),
                                   "region": {"startLine": max(c.line, 1)}}  # a file-level change: line 1
    location: dict[str, object] = {"physicalLocation": physical}
    if c.index is not None:
        location["logicalLocations"] = [{"name": c.subject, "kind": "member"}]
    body = f"{c.subject} {c.message}" if c.subject else c.message
    return {"ruleId": c.kind, "ruleIndex": rule_index[c.kind], "level": LEVELS[c.change_class],
            "message": {"text": body}, "locations": [location],
            "properties": {"class": c.change_class, "oldLine": c.old_line}}


def render_sarif(result: DiffResult) -> str:
    kinds = [KINDS[k] for k in sorted(KINDS)]
    rule_index = {k.id: i for i, k in enumerate(kinds)}
    run = {
        "tool": {"driver": {"name": "odgen", "version": __version__, "rules": [_rule(k) for k in kinds]}},
        "originalUriBaseIds": uri_base_ids(),
        "artifacts": [{"location": artifact_location(f)} for f in dict.fromkeys((result.new, result.old))],
        "results": [_result(c, result, rule_index) for c in result.changes],
        "columnKind": "unicodeCodePoints",
    }
    return json.dumps({"$schema": SCHEMA_URI, "version": "2.1.0", "runs": [run]}, indent=2) + "\n"


RENDERERS: dict[str, Callable[[DiffResult], str]] = {"text": render_text, "json": render_json,
                                                     "sarif": render_sarif}
