"""`odgen explain`: the effective placement and hooks of entries, and where each came from."""

from __future__ import annotations

from ..diagnostics import where
from ..model import ObjectDictionary, Sub
from .lookup import perfect_hash
from ..place.options import Pattern
from .packing import packable, packs_values
from ..place.placement import Placements


def _value(od: ObjectDictionary, sub: Sub) -> str:
    """The value in force and the keyword it comes from."""
    value = od.value_in_force(sub)
    if value is None or value.empty:
        return "none (zero, or empty)"
    return f"{value.text.strip()[:60]:<14} from {'ParameterValue' if value is sub.parameter_value else 'DefaultValue'}"


def explain_lines(od: ObjectDictionary, placements: Placements, pattern: Pattern) -> list[str]:
    lines = []
    packed: dict[int, bool] = {}
    commands = packs_values(od, placements)
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
        if subindex > 0 and packed.setdefault(index, packable(od, obj, placements, commands)):
            lines.append(f"  table:   packed: sub-indices 1..{max(obj.subs)} alike share one descriptor "
                         "(8 bytes of FLASH instead of 8 each)")
    return lines


def lookup_lines(od: ObjectDictionary, lookup: str) -> list[str]:
    """How odg_find finds an index in this dictionary, and what the other modes would trade."""
    indices = [o.index for o in od.sorted_objects() if o.index >= 0x1000]
    found = perfect_hash(indices)
    hashed = (f"perfect hash, {len(found.slots)} slots and {len(found.disp)} displacements "
              f"({found.table_bytes} B of FLASH), one multiply and two table reads per lookup")
    modes = {"hash": hashed, "bsearch": "binary search over the entry table, no tables of its own",
             "switch": "a generated switch over the indices (code, larger than the hash tables)"}
    # counted as `odgen report` counts: objects (indices), and entries with every sub-index of each
    entries = sum(len(o.subs) for o in od.objects.values())
    lines = [f"dictionary: {len(od.objects)} objects, {entries} entries counting each sub-index",
             f"lookup: {lookup} over the {len(indices)} indices from 0x1000 ({modes[lookup]})"]
    if lookup == "hash":
        lines.append("  the default: the fastest mode measured (docs/figures.md); "
                     "--lookup bsearch saves the tables at about twice the instructions per lookup")
    return lines
