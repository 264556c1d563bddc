"""Class (b): what boot migration does to each persistent entry, group by group."""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

from ..place.persistence import nv_regions
from ..catalogue.gen import GEN001
from ..diagnostics import Severity
from ..errors import OdgenError
from ..model import ObjectDictionary
from ..pipeline import Request, load, placed
from ..place.layout import group_layouts
from ..place.migration import CONVERT, DEFAULT, DROP, FOLLOW, KEEP, RESIZE, GroupLayout, Step, plan
from ..place.nvmap import Region
from .changes import Change

KINDS = {CONVERT: "DIF201", FOLLOW: "DIF201", RESIZE: "DIF202", DROP: "DIF203", DEFAULT: "DIF204", KEEP: "DIF205"}


@dataclass
class Stored:
    """A description's persistence groups as its options place them, and their NV regions."""

    groups: dict[str, GroupLayout]
    regions: dict[str, Region]
    migration: bool  # "ODG2" images migrated at boot, else "ODG1" images of the C struct


def placed_groups(od: ObjectDictionary, options: Path | None) -> Stored:
    """The persistence groups of a description placed with an options file (or none), by the
    pipeline's load and place stages (lint is not asked: a diff compares what is there)."""
    loaded = load(Request(Path(od.source), options=options, model=od))
    where = placed(loaded, loaded.diags)
    errors = [d for d in loaded.diags.sorted() if d.rule == GEN001.id and d.severity == Severity.ERROR]
    if errors:
        raise OdgenError(f"{errors[0].text()}; fix the options file")
    groups = group_layouts(od, where.placements)
    return Stored(groups, nv_regions(groups, where.persist), where.persist.migration)


@dataclass
class GroupPlan:
    steps: list[Step]
    moved: str = ""  # how the group's NV region moved, if it did: then nothing stored is found


def plans(old: Stored, new: Stored) -> dict[str, GroupPlan]:
    out = {}
    for name in sorted(set(old.groups) | set(new.groups)):
        steps = plan(old.groups.get(name), new.groups.get(name))
        a, b = old.regions.get(name), new.regions.get(name)
        if a is not None and b is not None and a.offset != b.offset:  # moved; one grown in place is found again
            moved = f"offset 0x{a.offset:X} ({a.size} bytes) -> offset 0x{b.offset:X} ({b.size} bytes)"
            out[name] = GroupPlan(_defaults(steps, "the group's NV region moved"), moved)
            continue
        why = _unmigrated(old, new, name)
        out[name] = GroupPlan(_defaults(steps, why) if why else steps)
    return out


def _unmigrated(old: Stored, new: Stored, name: str) -> str:
    """Why a group's stored values give way to the defaults without migration, or "" when they do not."""
    if old.migration and new.migration:
        return ""
    if old.migration != new.migration:
        return "the image format changes ([persist] migration is on in one version only)"
    a, b = old.groups.get(name), new.groups.get(name)
    if a is None or b is None or _shape(a) != _shape(b):
        return "the layout changed and [persist] migration is off"
    return ""


def _shape(group: GroupLayout) -> list[tuple[int, int, int, int]]:
    """What an "ODG1" image's layout signature covers: keys, types and lengths, not limits."""
    return [(e.index, e.sub, e.data_type, e.length) for e in group.entries]


def _defaults(steps: list[Step], reason: str) -> list[Step]:
    return [replace(s, action=DEFAULT, reason=reason, checked=False) for s in steps if s.new is not None]


def stored_changes(group_plans: dict[str, GroupPlan], old_od: ObjectDictionary,
                   new_od: ObjectDictionary) -> list[Change]:
    out = []
    for group, group_plan in group_plans.items():
        if group_plan.moved:
            out.append(_moved(group, group_plan, new_od))
            continue
        for step in group_plan.steps:
            if step.action == KEEP and not step.checked:
                continue
            new_sub, old_sub = new_od.find(step.index, step.sub), old_od.find(step.index, step.sub)
            obj = new_od.objects.get(step.index) or old_od.objects.get(step.index)
            sub = None if obj is not None and obj.is_var else step.sub
            out.append(Change(KINDS[step.action], f"in group '{group}': {_message(step)}", step.index, sub,
                              new_sub.line if new_sub else 0, old_sub.line if old_sub else 0))
    return out


def _moved(group: str, group_plan: GroupPlan, new_od: ObjectDictionary) -> Change:
    first = group_plan.steps[0]
    sub = new_od.find(first.index, first.sub)
    return Change("DIF207", f"group '{group}' moves in NV, {group_plan.moved}: its {len(group_plan.steps)} "
                  "stored value(s) are not found at boot; the group boots DEFAULTS where its new region is "
                  "erased, else DAMAGED with the storage EMCY (pin the regions in the options file)",
                  line=sub.line if sub is not None else 0)


def _message(step: Step) -> str:
    limits = ""
    if step.checked and step.new is not None:
        low, high = step.new.low, step.new.high
        limits = f"; a stored value outside {_limit(low)}..{_limit(high)} becomes the default"
    if step.action == KEEP:
        return "kept" + limits
    what = {CONVERT: "converted", FOLLOW: "the default", RESIZE: "resized, what fits kept", DROP: "dropped",
            DEFAULT: "the default"}
    return f"{what[step.action]} at boot ({step.reason}){limits}; {_boot(step)}"


def _boot(step: Step) -> str:
    """What the boot that migrates the group reports for this entry (docs/persistence.md, 4)."""
    if step.action == DEFAULT and step.old is None:
        return "counted as added: MIGRATED, no EMCY"
    if step.action in (DEFAULT, DROP):
        return "a loss: MIGRATED, the storage EMCY (0x5530)"
    return "MIGRATED, no EMCY"


def _limit(value: int | float | None) -> str:
    return "" if value is None else str(value)
