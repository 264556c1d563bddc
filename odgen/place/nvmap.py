"""The NV map: one fixed region per persistence group (docs/persistence.md, section 1).

Groups are placed comm, app, then the others by name; a region holds slot A at its start and slot
B at its middle; a slot names the region size it was written for, so a group whose region grows
in place still finds its slot B. A region is its need (two slots of the current image) plus
half, rounded up to the next power of two, at least MIN_REGION bytes: a group keeps its region
while its need stays inside that step, and crossing a step moves the groups after it.
"""

from __future__ import annotations

from dataclasses import dataclass

from .migration import DESCRIPTOR_BYTES, GroupLayout, value_size

HEADER_BYTES = 24  # slot header: magic, sequence, group id, region size, image length, CRC-32
COUNT_BYTES = 2  # the image's entry count before the descriptor
MIN_REGION = 64
DEFAULT_ALIGN = 8  # the runtime's ODG_PERSIST_ALIGN when the options set none
FIRST = ("comm", "app")


@dataclass(frozen=True)
class Region:
    group: str
    offset: int  # from NAME_NV_BASE
    size: int  # both slots; slot B starts at offset + size // 2
    need: int  # two slots of the current image

    @property
    def fits(self) -> bool:
        return self.need <= self.size


def image_bytes(layout: GroupLayout) -> int:
    return COUNT_BYTES + DESCRIPTOR_BYTES * len(layout.entries) + sum(value_size(e) for e in layout.entries)


def mirror_bound(layout: GroupLayout) -> int:
    """At least the bytes of the group's C struct ("ODG1" images, without migration): each member
    with its worst padding, strings with their terminator, and the struct's tail padding."""
    total = 7
    for e in layout.entries:
        dtype = e.dtype
        if dtype is not None and dtype.bits:
            size = 1 << (max(1, dtype.bits // 8) - 1).bit_length()  # 3 -> 4, 5..7 -> 8
            total += size + min(size, 8) - 1
        else:
            total += value_size(e) + 4  # a terminator, its alignment (a domain is in RAM)
    return total


def slot_bytes(layout: GroupLayout, align: int = DEFAULT_ALIGN) -> int:
    return _round_up(HEADER_BYTES + image_bytes(layout), align)


def nv_map(layouts: dict[str, GroupLayout], align: int = DEFAULT_ALIGN, headroom: int = 50,
           pinned: dict[str, int] | None = None, migration: bool = True) -> dict[str, Region]:
    """Regions in NV-map order. `headroom` is the percentage of the need kept free before rounding
    up to a power of two; a `pinned` region keeps its size (`Region.fits` says whether the group
    fits). Without `migration` an image is the group's C struct, bounded by `mirror_bound` (the
    generated code checks that it fits). Each slot starts on a multiple of `align` (the erase page of
    a flash NV): a region is at least two of them, and regions follow each other on that multiple."""
    order = [g for g in FIRST if g in layouts] + sorted(g for g in layouts if g not in FIRST)
    regions, offset = {}, 0
    for group in order:
        image = image_bytes(layouts[group]) if migration else mirror_bound(layouts[group])
        need = 2 * _round_up(HEADER_BYTES + image, align)
        grown = need + need * headroom // 100
        size = (pinned or {}).get(group) or max(MIN_REGION, 1 << (grown - 1).bit_length(), 2 * align)
        regions[group] = Region(group, offset, size, need)
        offset = _round_up(offset + size, align)
    return regions


def _round_up(value: int, align: int) -> int:
    return (value + align - 1) // align * align
