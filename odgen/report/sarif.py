"""SARIF 2.1.0 for code-scanning UIs: results with physical locations, rule metadata in the driver."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from urllib.parse import quote

from .. import __version__
from ..diagnostics import RULES, Diagnostic, Rule, Severity, where
from ..lint import FileResult

SCHEMA_URI = "https://json.schemastore.org/sarif-2.1.0.json"
LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}


def _uri(file: str) -> str:
    path = Path(file)
    return path.resolve().as_uri() if path.is_absolute() else quote(path.as_posix())


def _rule(rule: Rule) -> dict[str, object]:
    return {
        "id": rule.id,
        "name": rule.title,
        "shortDescription": {"text": rule.title},
        "fullDescription": {"text": rule.why},
        "help": {"text": f"{rule.fix}\n\nExample:\n{rule.example}"},
        "defaultConfiguration": {"level": LEVELS[rule.severity]},
        "properties": {"reference": rule.ref} if rule.ref else {},
    }


def _result(d: Diagnostic, rule_index: dict[str, int]) -> dict[str, object]:
    physical: dict[str, object] = {"artifactLocation": {"uri": _uri(d.loc.file)}}
    if d.loc.line > 0:
        physical["region"] = {"startLine": d.loc.line}
    location: dict[str, object] = {"physicalLocation": physical}
    if d.index is not None:
        location["logicalLocations"] = [{"name": where(d.index, d.sub), "kind": "member"}]
    subject = where(d.index, d.sub)
    return {
        "ruleId": d.rule,
        "ruleIndex": rule_index[d.rule],
        "level": LEVELS[d.severity],
        "message": {"text": f"{subject} {d.message}" if subject else d.message},
        "locations": [location],
    }


def render_sarif(results: Sequence[FileResult]) -> str:
    rules = [RULES[k] for k in sorted(RULES)]
    rule_index = {r.id: i for i, r in enumerate(rules)}
    run = {
        "tool": {"driver": {
            "name": "odgen",
            "version": __version__,
            "rules": [_rule(r) for r in rules],
        }},
        "artifacts": [{"location": {"uri": _uri(r.source)}} for r in results],
        "results": [_result(d, rule_index) for r in results for d in r.diagnostics],
        "columnKind": "unicodeCodePoints",
    }
    omitted = {r.source: r.omitted for r in results if r.omitted}
    if omitted:  # findings past a rule's cap: counted, not listed
        run["properties"] = {"omittedFindings": omitted}
    doc = {"$schema": SCHEMA_URI, "version": "2.1.0", "runs": [run]}
    return json.dumps(doc, indent=2) + "\n"
