"""Machine-readable findings: one object per file, plus the summary."""

from __future__ import annotations

from collections.abc import Sequence

from ... import __version__
from ...diagnostics import Diagnostic
from ..driver import FileResult
from .text import summary


def _diagnostic(d: Diagnostic) -> dict[str, object]:
    return {
        "rule": d.rule,
        "severity": d.severity.label,
        "file": d.loc.file,
        "line": d.loc.line,
        "index": d.index,
        "sub": d.sub,
        "message": d.message,
        "text": d.text(),
    }


def render_json(results: Sequence[FileResult]) -> str:
    doc = {
        "tool": "odgen",
        "version": __version__,
        "files": [
            {"file": r.source, "loaded": r.od is not None,
             "diagnostics": [_diagnostic(d) for d in r.diagnostics],
             "omitted": r.omitted}
            for r in results
        ],
        "summary": summary(results),
    }
    import json  # here, not at the top: `odgen lint` prints text unless asked

    return json.dumps(doc, indent=2, sort_keys=False) + "\n"
