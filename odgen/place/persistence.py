"""Persistence groups in the generated C (docs/persistence.md): each group's NV region from
`odgen.place.nvmap`, its layout descriptor for boot migration, and the optional boot status object.

Kept apart from the view-model of the tables: `status_object` is added to the model when it is
loaded (so lint sees it), `persist_view` works on the placed dictionary.
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass, field

from ..catalogue.gen import GEN001
from ..diagnostics import Diagnostics, Loc
from ..model import ObjectDictionary
from ..model.datatypes import BASIC_TYPES
from ..model.od import RECORD, Obj, Sub
from ..model.values import parse_value
from .layout import group_layouts
from .migration import GroupLayout
from .nvmap import DEFAULT_ALIGN, Region, nv_map
from .options import Options, PersistOptions
from .placement import Placements, place

UNSIGNED8, UNSIGNED32 = 0x05, 0x07


@dataclass
class GroupNv:
    name: str
    offset: int  # from NAME_NV_BASE
    region: int
    id: int  # CRC-32 of the name: a slot of another group is never taken
    # records of its layout descriptor (one per persisted sub-entry; the runtime reads them from
    # the tables), 0 without migration ("ODG1" images)
    n_layout: int = 0


@dataclass
class PersistView:
    migration: bool
    status_object: int | None
    align: int | None = None  # [persist] align: ODG_PERSIST_ALIGN in NAME_config.h
    groups: dict[str, GroupNv] = field(default_factory=dict)
    size: int = 0  # NV bytes of all regions


def status_object(od: ObjectDictionary, options: Options, diags: Diagnostics) -> Obj | None:
    """The boot status object at `[persist] status_object`: a RECORD in RAM, sub n (UNSIGNED32, ro)
    the group NAME_GROUP_* = n - 1 (status | converted << 8 | defaulted << 16 | dropped << 24),
    set by the runtime at boot. Its sub-entries follow the groups the placement makes (their order
    is NAME_GROUP_*'s), so the placement is worked out here once without reporting."""
    index = options.persist.status_object
    if index is None:
        return None
    if index in od.objects:
        diags.add(GEN001, Loc(od.source), f"status_object 0x{index:04X} is an object of the description; "
                  "choose a free index in [persist]", index)
        return None
    placements = place(od, options, Diagnostics())
    groups = sorted({p.group for p in placements.values() if p.group is not None})
    obj = Obj(index, "Stored parameters boot status", object_code=RECORD)
    obj.subs[0] = Sub(0, "Number of groups", data_type=UNSIGNED8, access="ro",
                      default=parse_value(str(len(groups)), BASIC_TYPES[UNSIGNED8]))
    for n, group in enumerate(groups, start=1):
        obj.subs[n] = Sub(n, f"Group {group}", data_type=UNSIGNED32, access="ro",
                          default=parse_value("0", BASIC_TYPES[UNSIGNED32]))
    return obj


def nv_regions(layouts: dict[str, GroupLayout], persist: PersistOptions) -> dict[str, Region]:
    """The NV region of each group as the options ([persist] headroom, migration, [[group]] region) place it."""
    return nv_map(layouts, align=persist.align or DEFAULT_ALIGN, headroom=persist.headroom, pinned=persist.regions,
                  migration=persist.migration)


def persist_view(od: ObjectDictionary, placements: Placements,
                 persist: PersistOptions, diags: Diagnostics) -> PersistView:
    layouts = group_layouts(od, placements)
    regions = nv_regions(layouts, persist)
    view = PersistView(persist.migration, persist.status_object, persist.align if regions else None)
    for name, region in regions.items():
        if not region.fits:
            diags.add(GEN001, Loc(od.source), f"persistence group {name} needs {region.need} bytes of NV, "
                      f"its pinned region has {region.size}; raise region in [[group]] or move entries")
        elif region.size // 2 % (persist.align or DEFAULT_ALIGN):
            diags.add(GEN001, Loc(od.source), f"persistence group {name}: half its pinned region ({region.size // 2} "
                      f"bytes) is not a multiple of [persist] align = {persist.align}; pin a region of "
                      f"{2 * (persist.align or DEFAULT_ALIGN)} bytes or a multiple of it")
        elif persist.migration and name in persist.regions and region.size & (region.size - 1):
            low = 1 << (region.size.bit_length() - 1)
            diags.add(GEN001, Loc(od.source), f"persistence group {name}: its pinned region of {region.size} bytes "
                      "is not a power of two; with migration a group looks for its images at the middle of "
                      f"power-of-two regions (docs/persistence.md, section 1): pin {low} or {2 * low} bytes")
        group = GroupNv(name, region.offset, region.size, zlib.crc32(name.encode("ascii")))
        group.n_layout = len(layouts[name].entries) if persist.migration else 0
        view.groups[name] = group
        view.size = max(view.size, region.offset + region.size)
    for name in sorted(set(persist.regions) - set(regions)):
        diags.add(GEN001, Loc(od.source), f"[[group]] {name} names no persistence group of the dictionary")
    return view
