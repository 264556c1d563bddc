"""gcc-style lines, one per finding, and a summary line."""

from __future__ import annotations

from collections.abc import Sequence

from ...diagnostics import Severity, more_line
from ...repair import blocking_marks
from ..driver import FileResult


def summary(results: Sequence[FileResult]) -> dict[str, int]:
    return {
        "files": len(results),
        "errors": sum(r.count(Severity.ERROR) for r in results),
        "warnings": sum(r.count(Severity.WARNING) for r in results),
        "infos": sum(r.count(Severity.INFO) for r in results),
    }


def render_text(results: Sequence[FileResult]) -> str:
    lines = []
    for r in results:
        marks = blocking_marks(r.od, r.diagnostics)  # after the message: `file:line: error[ID]:` stays first
        lines += [d.text() + marks.get(d, "") for d in r.diagnostics]
        lines += [more_line(r.source, rule_id, more) for rule_id, more in r.omitted.items()]
    s = summary(results)
    lines.append(
        f"{s['files']} file(s) checked: {s['errors']} error(s), {s['warnings']} warning(s), "
        f"{s['infos']} info(s)"
    )
    return "\n".join(lines) + "\n"
