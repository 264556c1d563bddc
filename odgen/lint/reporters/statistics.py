"""`odgen lint --statistics`: how many findings of each rule, most frequent first."""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence

from ...diagnostics import RULES
from ..driver import FileResult


def render_statistics(results: Sequence[FileResult]) -> str:
    counts = Counter(d.rule for r in results for d in r.diagnostics)
    width = len(str(max(counts.values(), default=0)))
    rows = [f"{n:>{width}}  {rule:<7} {RULES[rule].severity.label:<7}  {RULES[rule].title}"
            for rule, n in sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))]
    return "".join(row + "\n" for row in rows)
