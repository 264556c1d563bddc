"""Lint driver: read a file, run the rules, filter by --select/--ignore."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ..diagnostics import Diagnostic, Diagnostics, Severity
from ..formats import load_path
from ..gcpause import no_cyclic_gc
from ..model import ObjectDictionary
from .passes import LintOptions, run_rules


@dataclass
class FileResult:
    source: str
    od: ObjectDictionary | None
    diagnostics: list[Diagnostic] = field(default_factory=list)
    omitted: dict[str, int] = field(default_factory=dict)  # rule id -> findings past its cap, not listed

    def count(self, severity: Severity) -> int:
        return sum(1 for d in self.diagnostics if d.severity == severity)


@dataclass(frozen=True)
class RuleFilter:
    """--select/--ignore: rule ids or id prefixes (`PDO`, `SYN01`)."""

    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()

    def keeps(self, rule_id: str) -> bool:
        if self.select and not rule_id.startswith(self.select):
            return False
        return not (self.ignore and rule_id.startswith(self.ignore))


def lint_model(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    with no_cyclic_gc():
        run_rules(od, diags, options)


def lint_path(path: str | Path, options: LintOptions, rule_filter: RuleFilter = RuleFilter(),
              fmt: str | None = None) -> FileResult:
    od, diags = load_path(path, fmt)
    if od is not None:
        lint_model(od, diags, options)
    kept = [d for d in diags.sorted() if rule_filter.keeps(d.rule)]
    omitted = {rule_id: n for rule_id, n in diags.omitted().items() if rule_filter.keeps(rule_id)}
    return FileResult(str(path), od, kept, omitted)


def exit_code(results: Sequence[FileResult], strict: bool) -> int:
    worst = Severity.WARNING if strict else Severity.ERROR
    failed = any(d.severity >= worst for r in results for d in r.diagnostics)
    return 1 if failed else 0
