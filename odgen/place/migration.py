"""Boot migration of a stored persistence group: the policy the runtime implements (docs/persistence.md).

A stored image carries the layout it was written with (per entry: index, sub, data type, length).
When that layout differs from the firmware's, each entry of the firmware's layout is restored by
its key (index, sub), never by its position:

    keep     same data type and length: the stored value, checked against the current limits
    convert  integer widened without loss (UNSIGNED8 -> UNSIGNED16/32/..., INTEGER16 -> INTEGER32,
             UNSIGNED16 -> INTEGER32): zero- or sign-extended, then checked against the limits
    resize   string or domain capacity changed: what fits is kept (cut at the new capacity)
    drop     stored, but no longer in the group: forgotten (a loss)
    default  new in the group (added, not a loss), or narrowed, retyped, out of the current
             limits (a loss: a value stored and not served)
    follow   sub 0 of an ARRAY or RECORD whose highest sub-index changed: the count follows the
             array (the default), counted as converted, not as a loss

`plan` says what will happen to each entry from the two layouts alone (what `odgen diff`
reports); `migrate` applies the policy to stored values, as the runtime does at boot, and counts
kept / converted / defaulted / dropped entries for the group's status. Pure functions, no I/O.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Mapping
from dataclasses import dataclass, field

from ..model.datatypes import BASIC_TYPES, DataType
from ..model.wire import wire_bytes, wire_number

KEEP, CONVERT, RESIZE, DROP, DEFAULT, FOLLOW = "keep", "convert", "resize", "drop", "default", "follow"
ACTIONS = (KEEP, CONVERT, RESIZE, DROP, DEFAULT, FOLLOW)
DESCRIPTOR_BYTES = 6  # per entry in an image: index u16, sub u8, data type u8, length u16 (little endian)
DOMAIN_TYPE = 0x000F

Key = tuple[int, int]
Number = int | float


@dataclass(frozen=True)
class EntryLayout:
    """One entry of a group as stored: `length` is the type's size, or the capacity of a string or domain.
    `low`/`high` are the current limits (the type's range when the description gives none); they are
    the firmware's and never part of an image."""

    index: int
    sub: int
    data_type: int
    length: int
    low: Number | None = None
    high: Number | None = None

    @property
    def key(self) -> Key:
        return (self.index, self.sub)

    @property
    def dtype(self) -> DataType | None:
        return BASIC_TYPES.get(self.data_type)


@dataclass(frozen=True)
class GroupLayout:
    name: str
    entries: tuple[EntryLayout, ...] = ()

    def by_key(self) -> dict[Key, EntryLayout]:
        return {e.key: e for e in self.entries}


@dataclass(frozen=True)
class Step:
    """What boot migration does with one entry. `checked` says the current limits exclude values the
    old layout allowed, so a stored value may still end as the default."""

    index: int
    sub: int
    action: str
    reason: str
    old: EntryLayout | None
    new: EntryLayout | None
    checked: bool = False


@dataclass
class Counts:
    kept: int = 0
    converted: int = 0
    defaulted: int = 0
    dropped: int = 0
    added: int = 0  # new in the group: the default, nothing was lost

    @property
    def migrated(self) -> bool:
        return bool(self.converted or self.defaulted or self.dropped or self.added)

    @property
    def lost(self) -> bool:
        """A value stored was not served: what the storage EMCY reports."""
        return bool(self.defaulted or self.dropped)


@dataclass
class Migration:
    values: dict[Key, bytes | None] = field(default_factory=dict)  # None: serve the default
    counts: Counts = field(default_factory=Counts)


# -- the policy from the layouts alone ---------------------------------------------------------


def entry_action(old: EntryLayout | None, new: EntryLayout | None) -> tuple[str, str]:
    """(action, reason) for one key present in the old layout, the new one, or both."""
    if old is None:
        return DEFAULT, "new in the group"
    if new is None:
        return DROP, "no longer in the group"
    a, b = old.dtype, new.dtype
    if a is None or b is None:
        return DEFAULT, "data type without a stored form"
    if a.code == b.code:
        if b.bits or old.length == new.length:
            return (KEEP, "") if old.length == new.length else (DEFAULT, "stored length does not match the type")
        grown = "grown" if new.length > old.length else "shrunk"
        return RESIZE, f"capacity {grown} from {old.length} to {new.length} bytes"
    if widens(a, b):
        return CONVERT, f"widened from {a.name} to {b.name}"
    narrowed = a.is_integer and b.is_integer and a.kind == b.kind and b.bits < a.bits
    return DEFAULT, f"{'narrowed' if narrowed else 'retyped'} from {a.name} to {b.name}"


def widens(a: DataType, b: DataType) -> bool:
    """Every value of integer type a is a value of integer type b."""
    if a.kind not in ("int", "uint") or b.kind not in ("int", "uint") or b.bits <= a.bits:
        return False
    return a.kind == b.kind or (a.kind == "uint" and b.kind == "int")


def narrower_limits(old: EntryLayout, new: EntryLayout) -> bool:
    """The new limits exclude a value the old entry could hold."""
    lo_a, hi_a = _range(old)
    lo_b, hi_b = _range(new)
    if None in (lo_b, hi_b):
        return False
    if lo_a is None or hi_a is None:
        return True
    return lo_b > lo_a or hi_b < hi_a  # type: ignore[operator]


def _range(e: EntryLayout) -> tuple[Number | None, Number | None]:
    dtype = e.dtype
    if dtype is None or not dtype.is_numeric:
        return None, None
    low = e.low if e.low is not None else dtype.min
    high = e.high if e.high is not None else dtype.max
    return low, high


def plan(old: GroupLayout | None, new: GroupLayout | None) -> list[Step]:
    """One step per key of either layout, in (index, sub) order."""
    before = old.by_key() if old is not None else {}
    after = new.by_key() if new is not None else {}
    steps = []
    for key in sorted(set(before) | set(after)):
        a, b = before.get(key), after.get(key)
        action, reason = entry_action(a, b)
        if key[1] == 0 and action in (KEEP, CONVERT) and _highest(before, key[0]) != _highest(after, key[0]):
            action = FOLLOW
            reason = (f"the highest sub-index changed from {_highest(before, key[0])} to "
                      f"{_highest(after, key[0])}: sub 0 follows it")
        checked = action in (KEEP, CONVERT) and a is not None and b is not None and narrower_limits(a, b)
        steps.append(Step(key[0], key[1], action, reason, a, b, checked))
    return steps


def _highest(entries: dict[Key, EntryLayout], index: int) -> int:
    """The highest sub-index of `index` among the group's entries (0 when only sub 0 is there)."""
    return max((sub for i, sub in entries if i == index), default=0)


# -- the image: layout descriptor and value sizes ---------------------------------------------


def value_size(e: EntryLayout) -> int:
    """Bytes of the entry's value in an image: a domain adds its used length (u32) before its bytes."""
    return e.length + 4 if e.data_type == DOMAIN_TYPE else e.length


def descriptor(entries: tuple[EntryLayout, ...]) -> bytes:
    """The layout descriptor an image starts with, one DESCRIPTOR_BYTES record per entry."""
    return b"".join(struct.pack("<HBBH", e.index, e.sub, e.data_type, e.length) for e in entries)


def parse_descriptor(data: bytes) -> tuple[EntryLayout, ...] | None:
    """The entries of a descriptor, or None when it cannot be one (the image is damaged)."""
    if len(data) % DESCRIPTOR_BYTES:
        return None
    entries = tuple(EntryLayout(*struct.unpack_from("<HBBH", data, at))
                    for at in range(0, len(data), DESCRIPTOR_BYTES))
    keys = [e.key for e in entries]
    return entries if keys == sorted(set(keys)) else None


# -- applying the policy to stored values ------------------------------------------------------


def migrate(old: GroupLayout, new: GroupLayout, stored: Mapping[Key, bytes]) -> Migration:
    """The values the firmware's layout starts with, from the values stored under the old layout
    (wire format, `value_size` bytes each); None where the default is served."""
    result = Migration()
    for step in plan(old, new):
        if step.action == DROP:
            result.counts.dropped += 1
            continue
        value, changed = None, False
        raw = stored.get((step.index, step.sub))
        if step.action not in (DEFAULT, FOLLOW) and step.old is not None and step.new is not None \
                and raw is not None:
            value, changed = _restore(step.action, step.old, step.new, raw)
        result.values[(step.index, step.sub)] = value
        if step.action == FOLLOW:
            result.counts.converted += 1
        elif step.old is None:
            result.counts.added += 1
        elif value is None:
            result.counts.defaulted += 1
        elif changed:
            result.counts.converted += 1
        else:
            result.counts.kept += 1
    return result


def _restore(action: str, old: EntryLayout, new: EntryLayout, raw: bytes) -> tuple[bytes | None, bool]:
    """The restored value (None: the default) and whether it differs from what was stored."""
    dtype = new.dtype
    if len(raw) != value_size(old) or dtype is None:
        return None, False
    if action == RESIZE:
        return _resize(dtype, raw, new.length)
    if not dtype.is_numeric:
        return raw, False
    number = decode(old, raw)
    return (encode(new, number) if within(new, number) else None), action == CONVERT


def decode(e: EntryLayout, raw: bytes) -> Number:
    dtype = e.dtype
    assert dtype is not None and dtype.is_numeric
    return wire_number(raw, dtype)


def encode(e: EntryLayout, number: Number) -> bytes:
    dtype = e.dtype
    assert dtype is not None and dtype.is_numeric
    return wire_bytes(number, dtype)


def within(e: EntryLayout, number: Number) -> bool:
    """The value is one of the type and inside the current limits (a NaN is inside none)."""
    low, high = _range(e)
    if isinstance(number, float) and math.isnan(number):
        return e.low is None and e.high is None
    return (low is None or number >= low) and (high is None or number <= high)


def _resize(dtype: DataType, raw: bytes, length: int) -> tuple[bytes, bool]:
    """Keep what fits, and say whether anything was cut: strings end at their terminator and are cut
    at a whole character; a domain keeps its first bytes and says how many."""
    if dtype.code == DOMAIN_TYPE:
        used = min(int.from_bytes(raw[:4], "little"), len(raw) - 4)
        kept = min(used, length)
        return kept.to_bytes(4, "little") + raw[4:4 + kept] + bytes(length - kept), kept < used
    unit = 2 if dtype.kind == "ustring" else 1
    content = raw if dtype.kind == "ostring" else _until_terminator(raw, unit)
    kept_bytes = content[: length - length % unit]
    return kept_bytes + bytes(length - len(kept_bytes)), len(kept_bytes) < len(content)


def _until_terminator(raw: bytes, unit: int) -> bytes:
    for at in range(0, len(raw) - unit + 1, unit):
        if raw[at:at + unit] == bytes(unit):
            return raw[:at]
    return raw[: len(raw) - len(raw) % unit]
