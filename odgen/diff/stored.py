"""Class (b): what boot migration does to each persistent entry, group by group."""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

from ..codegen.options import load_options
from ..codegen.placement import place
from ..catalogue.gen import GEN001
from ..diagnostics import Diagnostics, Severity
from ..errors import OdgenError
from ..model import ObjectDictionary
from ..persist.layout import group_layouts
from ..persist.migration import CONVERT, DEFAULT, DROP, KEEP, RESIZE, GroupLayout, Step, plan
from ..persist.nvmap import nv_map
from .changes import Change

KINDS = {CONVERT: "DIF201", RESIZE: "DIF202", DROP: "DIF203", DEFAULT: "DIF204", KEEP: "DIF205"}


def layouts(od: ObjectDictionary, options: Path | None) -> dict[str, GroupLayout]:
    """The persistence groups of a description placed with an options file (or none)."""
    diags = Diagnostics()
    placements = place(od, load_options(options, diags), diags)
    errors = [d for d in diags.sorted() if d.rule == GEN001.id and d.severity == Severity.ERROR]
    if errors:
        raise OdgenError(f"{errors[0].text()}; fix the options file")
    return group_layouts(od, placements)


@dataclass
class GroupPlan:
    steps: list[Step]
    moved: str = ""  # how the group's NV region moved, if it did: then nothing stored is found


def plans(old: dict[str, GroupLayout], new: dict[str, GroupLayout]) -> dict[str, GroupPlan]:
    before, after = nv_map(old), nv_map(new)
    out = {}
    for name in sorted(set(old) | set(new)):
        steps = plan(old.get(name), new.get(name))
        a, b = before.get(name), after.get(name)
        if a is None or b is None or a.offset == b.offset:  # a region grown in place is found again
            out[name] = GroupPlan(steps)
            continue
        moved = f"offset 0x{a.offset:X} ({a.size} bytes) -> offset 0x{b.offset:X} ({b.size} bytes)"
        lost = [replace(s, action=DEFAULT, reason="the group's NV region moved", checked=False)
                for s in steps if s.new is not None]
        out[name] = GroupPlan(lost, moved)
    return out


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
                  "stored value(s) are not found at boot (pin the regions in the options file)",
                  line=sub.line if sub is not None else 0)


def _message(step: Step) -> str:
    limits = ""
    if step.checked and step.new is not None:
        low, high = step.new.low, step.new.high
        limits = f"; a stored value outside {_limit(low)}..{_limit(high)} becomes the default"
    if step.action == KEEP:
        return "kept" + limits
    what = {CONVERT: "converted", RESIZE: "resized, what fits kept", DROP: "dropped", DEFAULT: "the default"}
    return f"{what[step.action]} at boot ({step.reason}){limits}"


def _limit(value: int | float | None) -> str:
    return "" if value is None else str(value)
