"""The boot-migration policy (odgen/place/migration.py): the plan from two layouts, the values it
restores from a stored image, and the layout descriptor an image carries."""

from __future__ import annotations

import itertools

import pytest

from odgen.place.options import load_options
from odgen.place.placement import place
from odgen.diagnostics import Diagnostics
from odgen.formats import load_path
from odgen.model.datatypes import BASIC_TYPES
from odgen.place.layout import group_layouts
from odgen.place.nvmap import nv_map, slot_bytes
from odgen.place.migration import (
    CONVERT, DEFAULT, DESCRIPTOR_BYTES, DROP, KEEP, RESIZE, EntryLayout, GroupLayout, decode, descriptor, encode,
    entry_action, migrate, parse_descriptor, plan, value_size, widens,
)

from .conftest import FIXTURES

U8, U16, U32, I8, I16, I32, VSTR, OSTR, USTR, DOM = 0x5, 0x6, 0x7, 0x2, 0x3, 0x4, 0x9, 0xA, 0xB, 0xF
INTEGERS = [t for t in BASIC_TYPES.values() if t.kind in ("int", "uint")]


def entry(index: int, data_type: int, length: int | None = None, sub: int = 0, **limits: int) -> EntryLayout:
    size = length if length is not None else BASIC_TYPES[data_type].bits // 8
    return EntryLayout(index, sub, data_type, size, limits.get("low"), limits.get("high"))


def actions(old: list[EntryLayout], new: list[EntryLayout]) -> dict[tuple[int, int], str]:
    return {(s.index, s.sub): s.action for s in plan(GroupLayout("app", tuple(old)), GroupLayout("app", tuple(new)))}


def test_each_layout_change_has_its_action() -> None:
    old = [entry(0x2001, U8), entry(0x2002, U32), entry(0x2003, U8), entry(0x2004, I16), entry(0x2005, U8),
           entry(0x2006, VSTR, 8), entry(0x2007, VSTR, 8), entry(0x2008, U32), entry(0x2009, I8)]
    new = [entry(0x2001, U8), entry(0x2002, U16), entry(0x2003, I8), entry(0x2004, I32), entry(0x2005, I16),
           entry(0x2006, VSTR, 16), entry(0x2007, VSTR, 4), entry(0x200A, U8), entry(0x2009, U16)]
    assert actions(old, new) == {
        (0x2001, 0): KEEP, (0x2002, 0): DEFAULT, (0x2003, 0): DEFAULT, (0x2004, 0): CONVERT,
        (0x2005, 0): CONVERT, (0x2006, 0): RESIZE, (0x2007, 0): RESIZE, (0x2008, 0): DROP,
        (0x2009, 0): DEFAULT, (0x200A, 0): DEFAULT,
    }
    reasons = {(s.index, s.action): s.reason for s in plan(GroupLayout("a", tuple(old)), GroupLayout("a", tuple(new)))}
    assert reasons[(0x2002, DEFAULT)] == "narrowed from UNSIGNED32 to UNSIGNED16"
    assert reasons[(0x2003, DEFAULT)] == "retyped from UNSIGNED8 to INTEGER8"
    assert reasons[(0x2009, DEFAULT)] == "retyped from INTEGER8 to UNSIGNED16"  # -1 has no UNSIGNED16 value


def test_entries_are_matched_by_key_not_position() -> None:
    old = [entry(0x2001, U8), entry(0x2002, U32, sub=1), entry(0x2002, U16, sub=2)]
    reordered = [old[2], old[0], old[1]]
    assert set(actions(old, reordered).values()) == {KEEP}
    stored = {e.key: encode(e, 7 + n) for n, e in enumerate(old)}
    result = migrate(GroupLayout("app", tuple(old)), GroupLayout("app", tuple(reordered)), stored)
    assert result.values == stored and result.counts.kept == 3 and not result.counts.migrated


@pytest.mark.parametrize("a,b", list(itertools.permutations(INTEGERS, 2)), ids=lambda t: t.name)
def test_integer_retyping_keeps_the_value_or_serves_the_default(a, b) -> None:
    """Every pair of integer types: a widened value reads back unchanged, anything else is the default."""
    old, new = EntryLayout(0x2000, 0, a.code, a.bits // 8), EntryLayout(0x2000, 0, b.code, b.bits // 8)
    for number in (a.min, a.max, 0):
        result = migrate(GroupLayout("g", (old,)), GroupLayout("g", (new,)), {old.key: encode(old, number)})
        restored = result.values[old.key]
        if widens(a, b):
            assert restored is not None and decode(new, restored) == number and result.counts.converted == 1
        else:
            assert restored is None and result.counts.defaulted == 1
    assert entry_action(old, new)[0] == (CONVERT if widens(a, b) else DEFAULT)


def test_tightened_limits_default_only_values_outside_them() -> None:
    old = GroupLayout("app", (entry(0x2002, U8, low=0, high=100), entry(0x2003, U8)))
    new = GroupLayout("app", (entry(0x2002, U8, low=0, high=50), entry(0x2003, U16, low=10, high=20)))
    steps = plan(old, new)
    assert [(s.action, s.checked) for s in steps] == [(KEEP, True), (CONVERT, True)]
    high = migrate(old, new, {(0x2002, 0): bytes([80]), (0x2003, 0): bytes([15])})
    assert high.values == {(0x2002, 0): None, (0x2003, 0): (15).to_bytes(2, "little")}
    assert (high.counts.defaulted, high.counts.converted) == (1, 1)
    low = migrate(old, new, {(0x2002, 0): bytes([30]), (0x2003, 0): bytes([9])})
    assert low.values == {(0x2002, 0): bytes([30]), (0x2003, 0): None}


def test_widened_limits_need_no_check() -> None:
    old = GroupLayout("app", (entry(0x2002, U8, low=0, high=50),))
    new = GroupLayout("app", (entry(0x2002, U8, low=0, high=100),))
    assert [(s.action, s.checked) for s in plan(old, new)] == [(KEEP, False)]


@pytest.mark.parametrize("data_type,unit", [(VSTR, 1), (USTR, 2)])
def test_strings_keep_what_fits(data_type: int, unit: int) -> None:
    text = "pump-station".encode("ascii" if unit == 1 else "utf-16-le")
    old = entry(0x2003, data_type, 16 * unit)
    stored = {old.key: text + bytes(16 * unit - len(text))}
    for capacity, expected, cut in ((24, "pump-station", False), (4, "pump", True), (12, "pump-station", False)):
        new = entry(0x2003, data_type, capacity * unit)
        result = migrate(GroupLayout("g", (old,)), GroupLayout("g", (new,)), stored)
        value = result.values[old.key]
        assert value is not None and len(value) == value_size(new)
        assert value.decode("ascii" if unit == 1 else "utf-16-le").rstrip("\0") == expected
        assert (result.counts.converted, result.counts.kept) == ((1, 0) if cut else (0, 1))


def test_octet_strings_and_domains_keep_their_first_bytes() -> None:
    octets, domain = entry(0x2004, OSTR, 6), entry(0x2005, DOM, 6)
    stored = {octets.key: b"\x01\x02\x03\x04\x05\x06", domain.key: (3).to_bytes(4, "little") + b"abc\0\0\0"}
    small = GroupLayout("g", (entry(0x2004, OSTR, 2), entry(0x2005, DOM, 2)))
    result = migrate(GroupLayout("g", (octets, domain)), small, stored)
    assert result.values == {octets.key: b"\x01\x02", domain.key: (2).to_bytes(4, "little") + b"ab"}
    assert result.counts.converted == 2
    large = GroupLayout("g", (entry(0x2004, OSTR, 8), entry(0x2005, DOM, 8)))
    grown = migrate(GroupLayout("g", (octets, domain)), large, stored)
    assert grown.values[domain.key] == (3).to_bytes(4, "little") + b"abc" + bytes(5)
    assert grown.counts.kept == 2


def test_added_parameter_keeps_the_others_and_downgrade_drops_it() -> None:
    """The issue's v1 -> v2: one parameter added to `app`; then the v2 image booted by v1 firmware."""
    v1 = GroupLayout("app", (entry(0x2001, U8), entry(0x2002, U32)))
    v2 = GroupLayout("app", (entry(0x2001, U8), entry(0x2002, U32), entry(0x2003, U16)))
    stored = {(0x2001, 0): bytes([250]), (0x2002, 0): (123456).to_bytes(4, "little")}
    up = migrate(v1, v2, stored)
    assert up.values == {**stored, (0x2003, 0): None}
    assert (up.counts.kept, up.counts.added, up.counts.defaulted, up.counts.dropped) == (2, 1, 0, 0)
    assert up.counts.migrated and not up.counts.lost  # an added parameter loses nothing
    down = migrate(v2, v1, {**stored, (0x2003, 0): (80).to_bytes(2, "little")})
    assert down.values == stored and (down.counts.kept, down.counts.dropped) == (2, 1)
    assert down.counts.lost  # a value stored and not served


def test_sequence_6_array_sub0_follows_the_array() -> None:
    """Sub 0 of an ARRAY whose highest sub-index changed is the new default (the count follows
    the array), counted as converted, not as a loss; elements keep their values."""
    v1 = GroupLayout("app", (entry(0x2020, U8), *(EntryLayout(0x2020, k, U16, 2) for k in range(1, 5))))
    v2 = GroupLayout("app", (entry(0x2020, U8), *(EntryLayout(0x2020, k, U16, 2) for k in range(1, 7))))
    stored = {(0x2020, 0): bytes([4]), **{(0x2020, k): bytes([k, 0]) for k in range(1, 5)}}
    grown = migrate(v1, v2, stored)
    assert grown.values[(0x2020, 0)] is None and grown.values[(0x2020, 3)] == bytes([3, 0])
    assert (grown.counts.converted, grown.counts.added, grown.counts.kept) == (1, 2, 4)
    assert not grown.counts.lost
    same = migrate(v1, v1, stored)
    assert same.values == stored and not same.counts.migrated


def test_value_of_the_wrong_size_is_not_restored() -> None:
    old = GroupLayout("g", (entry(0x2001, U16),))
    result = migrate(old, old, {(0x2001, 0): b"\x01"})
    assert result.values == {(0x2001, 0): None} and result.counts.defaulted == 1


def test_descriptor_round_trip_and_damage() -> None:
    entries = (entry(0x1017, U16), entry(0x2003, VSTR, 300, sub=1), entry(0x2003, DOM, 65535, sub=2))
    data = descriptor(entries)
    assert len(data) == DESCRIPTOR_BYTES * len(entries)
    assert data[:DESCRIPTOR_BYTES] == bytes([0x17, 0x10, 0x00, U16, 0x02, 0x00])
    assert parse_descriptor(data) == tuple(EntryLayout(e.index, e.sub, e.data_type, e.length) for e in entries)
    assert parse_descriptor(data[:-1]) is None
    assert parse_descriptor(data[DESCRIPTOR_BYTES:] + data[:DESCRIPTOR_BYTES]) is None  # keys out of order


def test_layouts_of_a_description_follow_the_options_file() -> None:
    diags = Diagnostics()
    layouts = {}
    for name in ("base", "stored"):
        od, _ = load_path(FIXTURES / "diff" / f"{name}.eds")
        assert od is not None
        layouts[name] = group_layouts(od, place(od, load_options(FIXTURES / "diff" / "options.toml", diags), diags))
    base = layouts["base"]
    assert sorted(base) == ["app", "comm"]
    assert [(e.index, e.data_type, e.length, e.low, e.high) for e in base["app"].entries] == [
        (0x2001, U8, 1, None, None), (0x2002, U8, 1, 0, 100), (0x2003, VSTR, 4, None, None)]
    assert [e.length for e in layouts["stored"]["app"].entries] == [1, 1, len("pump-station")]


def test_a_group_keeps_its_nv_region_when_another_changes() -> None:
    comm = GroupLayout("comm", (entry(0x1017, U16),))
    app = GroupLayout("app", (entry(0x2001, U8), entry(0x2002, U32)))
    before = nv_map({"app": app, "comm": comm})
    assert [(r.group, r.offset) for r in before.values()] == [("comm", 0), ("app", before["comm"].size)]
    grown_app = GroupLayout("app", app.entries + (entry(0x2003, U32), entry(0x2004, U32)))
    grown_comm = GroupLayout("comm", (entry(0x1017, U32),))  # grows inside its region's step
    for layouts, unchanged in (({"app": grown_app, "comm": comm}, "comm"), ({"app": app, "comm": grown_comm}, "app")):
        after = nv_map(layouts)
        assert after[unchanged] == before[unchanged]
        assert all(r.size // 2 >= slot_bytes(layouts[g]) for g, r in after.items())
    crossing = nv_map({"app": app, "comm": GroupLayout("comm", comm.entries + (entry(0x1800, U8, sub=2),))})
    assert crossing["comm"].offset == 0 and crossing["comm"].size > before["comm"].size  # grows in place
    assert crossing["app"].offset > before["app"].offset  # moves: reported by odgen diff (DIF207)
    extra = nv_map({"app": app, "comm": comm, "calib": GroupLayout("calib", (entry(0x3000, U32),))})
    assert (extra["comm"], extra["app"]) == (before["comm"], before["app"])
