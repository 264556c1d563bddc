"""The layout of each persistence group of a placed dictionary, as boot migration sees it."""

from __future__ import annotations

from ..model import ObjectDictionary, Sub
from ..model.capacity import domain_capacity, limit_value, string_capacity, string_default
from ..model.datatypes import DataType
from .migration import DOMAIN_TYPE, EntryLayout, GroupLayout
from .placement import Placement, Placements


def group_layouts(od: ObjectDictionary, placements: Placements) -> dict[str, GroupLayout]:
    """Every persistence group with its entries in (index, sub) order; entries of a type without a
    stored form (a DEFSTRUCT type) are left out, as the generator refuses them."""
    groups: dict[str, list[EntryLayout]] = {}
    persisted = sorted((key, group, placement) for key, placement in placements.items()
                       if (group := placement.group) is not None)
    for (index, subindex), group, placement in persisted:
        sub = od.find(index, subindex)
        dtype = sub.dtype if sub is not None else None
        if sub is not None and dtype is not None:
            groups.setdefault(group, []).append(entry_layout(index, sub, dtype, placement))
    return {name: GroupLayout(name, tuple(entries)) for name, entries in sorted(groups.items())}


def entry_layout(index: int, sub: Sub, dtype: DataType, placement: Placement) -> EntryLayout:
    return EntryLayout(index, sub.subindex, dtype.code, stored_length(sub, dtype, placement),
                       *_limits(sub, dtype))


def stored_length(sub: Sub, dtype: DataType, placement: Placement) -> int:
    """The bytes the generated dictionary reserves for the value (capacities as the generator sizes them)."""
    if dtype.bits:
        return max(1, dtype.bits // 8)
    if dtype.code == DOMAIN_TYPE:
        return domain_capacity(sub.default, placement.capacity)
    return string_capacity(dtype, string_default(dtype, sub.default), placement.capacity)


def _limits(sub: Sub, dtype: DataType) -> tuple[int | float | None, int | float | None]:
    if not dtype.is_numeric:
        return None, None
    return limit_value(sub.low, None), limit_value(sub.high, None)
