"""GitHub Actions workflow commands: one `::error file=...,line=...::` annotation per finding."""

from __future__ import annotations

from collections.abc import Sequence

from ...diagnostics import Severity, where
from ...repair import blocking_marks
from ..driver import FileResult

COMMANDS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}


def _escape(text: str, prop: bool = False) -> str:
    """The escaping the runner expects: % CR LF always, and : , inside properties."""
    text = text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")
    return text.replace(":", "%3A").replace(",", "%2C") if prop else text


def render_github(results: Sequence[FileResult]) -> str:
    lines = []
    for r in results:
        marks = blocking_marks(r.od, r.diagnostics)
        for d in r.diagnostics:
            subject = where(d.index, d.sub)
            body = (f"{subject} {d.message}" if subject else d.message) + marks.get(d, "")
            props = f"file={_escape(d.loc.file, True)},line={max(d.loc.line, 1)},title={_escape(d.rule, True)}"
            lines.append(f"::{COMMANDS[d.severity]} {props}::{_escape(f'{d.rule} {body}')}")
    return "".join(line + "\n" for line in lines)
