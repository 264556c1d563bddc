"""`odgen explain`: the effective placement and hooks of entries, and where each came from."""

from __future__ import annotations

from ..diagnostics import where
from ..model import ObjectDictionary, Sub
from .options import Pattern
from .placement import Placement


def _value(od: ObjectDictionary, sub: Sub) -> str:
    """The value in force and the keyword it comes from."""
    value = od.value_in_force(sub)
    if value is None or value.empty:
        return "none (zero, or empty)"
    return f"{value.text.strip()[:60]:<14} from {'ParameterValue' if value is sub.parameter_value else 'DefaultValue'}"


def explain_lines(od: ObjectDictionary, placements: dict[tuple[int, int], Placement], pattern: Pattern) -> list[str]:
    lines = []
    for (index, subindex), p in sorted(placements.items()):
        if not pattern.matches(index, subindex):
            continue
        obj = od.objects[index]
        sub = obj.subs[subindex]
        label = where(index, None if obj.is_var else subindex)
        hooks = ", ".join(p.hooks) or "none"
        function = f" -> {p.function}()" if p.function else ""
        lines.append(f"{label} {sub.name or obj.name}")
        lines.append(f"  value:   {_value(od, obj.subs[subindex])}")
        lines.append(f"  storage: {p.storage:<14} from {p.storage_from}")
        lines.append(f"  hooks:   {hooks + function:<14} from {p.hooks_from}")
        if p.capacity is not None:
            lines.append(f"  capacity: {p.capacity} bytes   from {p.capacity_from}")
    return lines
