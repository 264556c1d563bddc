"""`odgen diff OLD NEW`: what an update of a description changes for masters and for stored parameters.

Both files go through the readers into the one model (EDS, DCF, XDD, XDC in any mix), then:
compare.py finds classes (a) and (c), stored.py class (b) from the boot-migration policy
(odgen/place/migration.py), version.py whether revision and file version were raised.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from ..diagnostics import Diagnostic, Severity
from ..errors import OdgenError
from ..formats import load_path
from ..model import ObjectDictionary
from .changes import CLASSES, Change, worst
from .compare import object_changes
from .stored import GroupPlan, placed_groups, plans, stored_changes
from .version import version_changes, versions

__all__ = ["CLASSES", "Change", "DiffResult", "diff_models", "diff_paths", "fails"]


@dataclass
class DiffResult:
    old: str
    new: str
    changes: list[Change] = field(default_factory=list)
    groups: dict[str, GroupPlan] = field(default_factory=dict)  # boot migration per persistence group
    read_errors: list[Diagnostic] = field(default_factory=list)  # errors the readers found in OLD or NEW
    versions: dict[str, str] = field(default_factory=dict)  # "revision" / "file version": "OLD -> NEW"

    def count(self, cls: str) -> int:
        return sum(1 for c in self.changes if c.change_class == cls)


def diff_paths(old: Path, new: Path, old_options: Path | None = None, new_options: Path | None = None) -> DiffResult:
    old_od, old_errors = _load(old)
    new_od, new_errors = _load(new)
    result = diff_models(old_od, new_od, old_options, new_options)
    result.read_errors = old_errors + new_errors
    return result


def diff_models(old: ObjectDictionary, new: ObjectDictionary, old_options: Path | None = None,
                new_options: Path | None = None) -> DiffResult:
    group_plans = plans(placed_groups(old, old_options), placed_groups(new, new_options))
    # entries stored before and after: a new default does not reach devices that stored a value
    stored_keys = {(s.index, s.sub) for p in group_plans.values() for s in p.steps if s.old and s.new}
    changes = object_changes(old, new, stored_keys) + stored_changes(group_plans, old, new)
    changes += version_changes(old, new, changes)
    changes.sort(key=lambda c: (CLASSES.index(c.change_class), -1 if c.index is None else c.index, c.sub or 0, c.kind))
    return DiffResult(old.source, new.source, changes, group_plans, versions=versions(old, new))


def fails(result: DiffResult, fail_on: str) -> bool:
    """A change of class `fail_on` or a more severe one ("none": never)."""
    if fail_on not in CLASSES:
        return False
    cls = worst(result.changes)
    return cls is not None and CLASSES.index(cls) <= CLASSES.index(fail_on)


def _load(path: Path) -> tuple[ObjectDictionary, list[Diagnostic]]:
    od, diags = load_path(path)
    errors = [d for d in diags.sorted() if d.severity == Severity.ERROR]
    if od is None or not od.objects:
        reason = errors[0].text() if errors else f"{path}: not a device description (no object in it)"
        raise OdgenError(f"{reason}; cannot compare it")
    return od, errors
