"""SARIF 2.1.0 for code-scanning UIs: results with physical locations, rule metadata in the driver."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from urllib.parse import quote

from ... import __version__
from ...diagnostics import RULES, Diagnostic, Rule, Severity, where
from ..driver import FileResult
from ...model import ObjectDictionary
from ...repair import blocking_marks

SCHEMA_URI = "https://json.schemastore.org/sarif-2.1.0.json"
LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}


SRCROOT = "%SRCROOT%"
# Where a finding about the file as a whole points: the sections its rule family reads.
FAMILY_SECTIONS = {"HDR": ("fileinfo", "deviceinfo"), "LST": ("mandatoryobjects", "optionalobjects",
                   "manufacturerobjects"), "COM": ("mandatoryobjects", "deviceinfo"), "PDO": ("deviceinfo",)}


def artifact_location(file: str) -> dict[str, str]:
    """Inputs under the working directory are relative to %SRCROOT% (the checkout, for code scanning)."""
    path = Path(file)
    try:
        rel = path.resolve().relative_to(Path.cwd().resolve())
    except (ValueError, OSError):
        return {"uri": path.resolve().as_uri()}
    return {"uri": quote(rel.as_posix()), "uriBaseId": SRCROOT}


def _line(d: Diagnostic, od: ObjectDictionary | None) -> int:
    """The finding's line, else its object's or sub-object's, else its family's section, else line 1."""
    if d.loc.line > 0:
        return d.loc.line
    if od is not None and d.index is not None and d.index in od.objects:
        obj = od.objects[d.index]
        sub = obj.subs.get(d.sub) if d.sub is not None else None
        line = (sub.line if sub is not None else 0) or obj.line
        if line:
            return line
    if od is not None:
        for name in FAMILY_SECTIONS.get(d.rule.rstrip("0123456789"), ()):
            section = od.section(name)
            if section is not None and section.line > 0:
                return section.line
    return 1


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


def _result(d: Diagnostic, rule_index: dict[str, int], od: ObjectDictionary | None, mark: str) -> dict[str, object]:
    physical: dict[str, object] = {"artifactLocation": artifact_location(d.loc.file),
                                   "region": {"startLine": _line(d, od)}}
    location: dict[str, object] = {"physicalLocation": physical}
    if d.index is not None:
        location["logicalLocations"] = [{"name": where(d.index, d.sub), "kind": "member"}]
    subject = where(d.index, d.sub)
    result: dict[str, object] = {
        "ruleId": d.rule,
        "ruleIndex": rule_index[d.rule],
        "level": LEVELS[d.severity],
        "message": {"text": (f"{subject} {d.message}" if subject else d.message) + mark},
        "locations": [location],
    }
    if mark:  # the same words as the message's mark, for tools that read properties
        result["properties"] = {"blocksGenerate": True, "repair": mark.split("; ", 1)[1].rstrip("]")}
    return result


def uri_base_ids() -> dict[str, dict[str, str]]:
    return {SRCROOT: {"uri": Path.cwd().resolve().as_uri() + "/"}}


def render_sarif(results: Sequence[FileResult]) -> str:
    rules = [RULES[k] for k in sorted(RULES)]
    rule_index = {r.id: i for i, r in enumerate(rules)}
    run = {
        "tool": {"driver": {
            "name": "odgen",
            "version": __version__,
            "rules": [_rule(r) for r in rules],
        }},
        "originalUriBaseIds": uri_base_ids(),
        "artifacts": [{"location": artifact_location(r.source)} for r in results],
        "results": [_result(d, rule_index, r.od if d.loc.file == r.source else None, marks.get(d, ""))
                    for r, marks in ((r, blocking_marks(r.od, r.diagnostics)) for r in results)
                    for d in r.diagnostics],
        "columnKind": "unicodeCodePoints",
    }
    omitted = {r.source: r.omitted for r in results if r.omitted}
    if omitted:  # findings past a rule's cap: counted, not listed
        run["properties"] = {"omittedFindings": omitted}
    doc = {"$schema": SCHEMA_URI, "version": "2.1.0", "runs": [run]}
    import json  # here, not at the top: `odgen lint` prints text unless asked

    return json.dumps(doc, indent=2) + "\n"
