"""Runs of alike entries share one list of sub-entry descriptors (runtime/odg.h, ODG_E_SHARED).

Two or more entries of consecutive indices, next to each other in the table, whose descriptors
are alike in all but where their values lie (count, object code, and per sub-entry its sub-index,
type, size, access, PDO mapping, $NODEID and storage), keep one list. The CiA 301 PDO
communication and mapping records are such in most devices: 8 bytes of FLASH per descriptor
saved.

The values stay where they are. A storage block holds its values by alignment, then by (index,
sub) (viewmodel._sorted_struct), so the values of one C width in one block are, member after
member, the same values one after the other: member i's value lies i * stride bytes after
member 0's, the stride being the bytes that the member's values of that width take in that
block. Each descriptor of the list carries its stride in the high byte of `size`, and an offset
biased by -index * stride (modulo 2^16), so that the runtime finds a member's value at
offset + index * stride with no table of its own; the generated C asserts every member's every
value against it. Numbers only: no strings or domains (whose bytes are no one width), no hooks
or limits (found by descriptor position, which the members share), no "save" / "load" commands.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from .runtimecfg import STREAMS, width

if TYPE_CHECKING:  # the view-model calls share() to finish a view
    from .viewmodel import DictView, EntryView, SubView

MAX_STRIDE = 0xFF  # the high byte of odg_sub_t.size


@dataclass
class SharedView:
    """A run (the C asserts its layout): each later member's value offsets against the first's."""
    first: int  # index of the first member
    last: int
    checks: list[tuple[str, str, int]]  # (member's offset, first member's offset, bytes between)


def _rows(subs: list[SubView], entry: EntryView) -> list[SubView]:
    return subs[entry.first:entry.first + entry.count]


def _shape(rows: list[SubView], entry: EntryView) -> tuple[object, ...]:
    return (entry.count, entry.code, tuple((s.size, s.sub, s.type, s.attr, s.storage) for s in rows))


def _alone(rows: list[SubView]) -> bool:
    """Whether the entry's descriptors can never be shared."""
    return any(s.type in STREAMS or s.storage.startswith("ODG_S_COMMAND") or "ODG_A_HOOK" in s.attr
               or "ODG_A_LIMIT" in s.attr for s in rows)


def strides(rows: list[SubView], packed: bool) -> list[int] | None:
    """Bytes from one member's value to the next's, per descriptor, or None when one is too wide."""
    taken: dict[tuple[int, str], int] = {}  # (width, block) -> bytes of one member's values
    for pos, s in enumerate(rows):
        elements = s.sub if packed and pos == 1 else 1  # a packed descriptor: its elements
        key = (width(s.size), s.storage)
        taken[key] = taken.get(key, 0) + width(s.size) * elements
    found = [taken[(width(s.size), s.storage)] for s in rows]
    return found if max(found) <= MAX_STRIDE else None


def _run_end(view: DictView, i: int) -> int:
    """The end of the run of alike entries from entries[i] (i + 1: none)."""
    entries, subs = view.entries, view.subs
    head = entries[i]
    rows = _rows(subs, head)
    j = i + 1
    if _alone(rows):
        return j
    shape = _shape(rows, head)
    while j < len(entries) and entries[j].index == entries[j - 1].index + 1 and \
            _shape(_rows(subs, entries[j]), entries[j]) == shape:
        j += 1
    return j


def share(view: DictView) -> None:
    """Give each run of alike entries one list of descriptors, in place; the positions of hooks
    and limits follow the descriptors they name."""
    entries, subs = view.entries, view.subs
    moved: dict[int, int] = {}  # old position -> new
    out: list[SubView] = []
    i = 0
    while i < len(entries):
        head = entries[i]
        j = _run_end(view, i)
        rows = _rows(subs, head)
        stride = strides(rows, "ODG_E_PACKED" in head.code) if j - i > 1 else None
        for k in range(head.count):
            moved[head.first + k] = len(out) + k
        if stride is None:  # alone, or a stride too wide: the entry keeps its own descriptors
            head.first = len(out)
            out.extend(rows)
            j = i + 1
        else:
            out.extend(_shared(view, entries[i:j], rows, stride, len(out)))
        i = j
    view.subs[:] = out
    for limit in view.limits:
        limit.sub_pos = moved[limit.sub_pos]
    for hook in view.hooks:
        hook.sub_pos = moved[hook.sub_pos]


def _shared(view: DictView, run: list[EntryView], rows: list[SubView], stride: list[int],
            at: int) -> list[SubView]:
    """The run's list, to lie at position `at`, its members pointed at it."""
    head = run[0]
    checks = [(s.offset, rows[pos].offset, k * stride[pos])
              for k, member in enumerate(run[1:], 1) for pos, s in enumerate(_rows(view.subs, member))]
    view.shared.append(SharedView(head.index, run[-1].index, checks))
    for member in run:
        member.first = at
        member.code += " | ODG_E_SHARED"
    span = f"0x{head.index:04X}..0x{run[-1].index:04X}"
    return [s._replace(offset=f"(uint16_t)({s.offset} - 0x{head.index:04X}u * {n}u)", stride=n,
                       note=f"{span}: {s.note}") for s, n in zip(rows, stride, strict=True)]
