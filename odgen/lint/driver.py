"""Lint driver: read a file, run the rules, filter by --select/--ignore."""

from __future__ import annotations

import glob
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ..diagnostics import Diagnostic, Diagnostics, Severity
from ..errors import OdgenError
from ..formats import FORMATS, load_path
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


def expand_paths(paths: Sequence[Path], excluded: Callable[[Path], bool] = lambda path: False) -> list[Path]:
    """The files `odgen lint PATH...` reads, in a fixed order.

    A file is read as named (even when the config file excludes it, as ruff does). A folder stands
    for the description files (.eds .dcf .xdd .xdc .xpd) in it and below, hidden folders passed over;
    a glob (`'devices/**/*.eds'`, quoted so the shell leaves it, or on a shell that does not expand
    it) for the description files it matches. Files found in a folder or by a glob that `excluded`
    names are left out. Each argument's files are sorted; a file found twice is read once. A folder
    or glob that yields no description is the user's mistake."""
    found: dict[Path, None] = {}
    for path in paths:
        if path.is_dir():
            files, where = _descriptions_below(path), "in this folder or below"
        elif not path.exists() and any(c in str(path) for c in "*?["):
            files, where = _glob_descriptions(str(path)), "that this pattern matches"
        else:
            found.setdefault(path)
            continue
        kept = [f for f in files if not excluded(f)]
        if not files:
            raise OdgenError(f"{path}: no description file ({' '.join(FORMATS)}) {where}; "
                             "name the files to lint, or a folder that holds some")
        if not kept:
            raise OdgenError(f"{path}: every description file {where} is left out by the config file's "
                             "exclude; name the files to lint them anyway")
        for file in kept:
            found.setdefault(file)
    return list(found)


def _descriptions_below(folder: Path) -> list[Path]:
    files = []
    for here, dirs, names in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        files += [Path(here, n) for n in names if Path(n).suffix.lower() in FORMATS]
    return sorted(files, key=lambda p: p.as_posix())


def _glob_descriptions(pattern: str) -> list[Path]:
    matches = [Path(m) for m in glob.glob(pattern, recursive=True)]
    files = [m for m in matches if m.is_file() and m.suffix.lower() in FORMATS]
    for folder in (m for m in matches if m.is_dir()):
        files += _descriptions_below(folder)
    return sorted(set(files), key=lambda p: p.as_posix())
