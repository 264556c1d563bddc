"""Boot migration in the C runtime against the policy in Python (odgen/place/migration.py).

Each case generates a v1 and a v2 dictionary (the same name `od`), stores values with v1 into an
NV file, boots v2 on that file (tests/runtime/migrate_main.c) and compares what v2 serves, and the
group's status and counts, with `migrate()` on the same layouts and the values v1 stored. Then the
power is cut after every byte of v2's migration store (the NOR model of tests/runtime/nv_fault.c):
every next boot serves the migrated values.
"""

from __future__ import annotations

import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest

from odgen import toolchain
from odgen.pipeline import Request, prepare
from odgen.place.layout import group_layouts
from odgen.place.migration import DOMAIN_TYPE, EntryLayout, GroupLayout, migrate, value_size
from odgen.place.nvmap import nv_map

from .conftest import ROOT
from .cprog import build

RUNTIME = ROOT / "runtime"
CTESTS = ROOT / "tests" / "runtime"
LOADED, DEFAULTS, SIGNATURE, DAMAGED, MIGRATED = 0, 1, 2, 4, 5



def eds_head(file: str, description: str, product: str, rpdos: int = 0) -> str:
    """The [FileInfo], [DeviceInfo] and [MandatoryObjects] (0x1000, 0x1001, 0x1018) of a test EDS."""
    return f"""[FileInfo]
FileName={file}
FileVersion=1
FileRevision=0
EDSVersion=4.0
Description={description}
CreatedBy=odgen tests

[DeviceInfo]
VendorName=odgen tests
ProductName={product}
BaudRate_125=1
SimpleBootUpSlave=1
Granularity=8
NrOfRXPDO={rpdos}
NrOfTXPDO=0
LSS_Supported=0

[MandatoryObjects]
SupportedObjects=3
1=0x1000
2=0x1001
3=0x1018
"""


HEADER = eds_head("od.eds", "migration fixture", "migration") + """
[1000]
ParameterName=Device type
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=0

[1001]
ParameterName=Error register
ObjectType=0x7
DataType=0x0005
AccessType=ro
DefaultValue=0

[1018]
ParameterName=Identity
ObjectType=0x9
SubNumber=2

[1018sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
DataType=0x0005
AccessType=ro
DefaultValue=1

[1018sub1]
ParameterName=Vendor-ID
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=0

[OptionalObjects]
SupportedObjects=3
1=0x1010
2=0x1011
3=0x1017

[1010]
ParameterName=Store parameters
ObjectType=0x8
SubNumber=2

[1010sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
DataType=0x0005
AccessType=ro
DefaultValue=1

[1010sub1]
ParameterName=Save all parameters
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=1

[1011]
ParameterName=Restore default parameters
ObjectType=0x8
SubNumber=2

[1011sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
DataType=0x0005
AccessType=ro
DefaultValue=1

[1011sub1]
ParameterName=Restore all default parameters
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=1

[1017]
ParameterName=Producer heartbeat time
ObjectType=0x7
DataType=0x0006
AccessType=rw
DefaultValue={heartbeat}
"""


@dataclass(frozen=True)
class Param:
    """A manufacturer parameter, persisted in group app."""

    index: int
    dtype: int
    default: str
    low: str | None = None
    high: str | None = None
    capacity: int | None = None
    elements: int = 0  # an ARRAY of that many elements (sub 1..n) of `dtype` instead of a VAR


@dataclass(frozen=True)
class Case:
    v1: tuple[Param, ...]
    v2: tuple[Param, ...]
    stored: dict[int | tuple[int, int], str]  # index (sub 0) or (index, sub) -> wire hex written with v1
    heartbeat: tuple[int, int] = (1000, 1000)  # 0x1017 default in v1, v2 (group comm)
    order: tuple[bool, bool] = (False, False)  # list v1's / v2's objects in reverse order


U8, U16, U32, I16, I32, R32, VS, OS = 0x05, 0x06, 0x07, 0x03, 0x04, 0x08, 0x09, 0x0A
BASE = (Param(0x2000, U8, "7"), Param(0x2001, U16, "1000"), Param(0x2002, I16, "-5"))
BASE_VALUES = {0x2000: "FA", 0x2001: "40E2", 0x2002: "85FF"}  # 250, 57920, -123

CASES = {
    "unchanged": Case(BASE, BASE, BASE_VALUES),
    "added": Case(BASE, (*BASE, Param(0x2003, U32, "42")), BASE_VALUES),
    "removed": Case(BASE, BASE[:2], BASE_VALUES),
    "retyped": Case(BASE, (BASE[0], Param(0x2001, I16, "3"), BASE[2]), BASE_VALUES),
    "widened": Case(BASE, (Param(0x2000, U32, "7"), Param(0x2001, I32, "1000"), Param(0x2002, I32, "-5")),
                    BASE_VALUES),
    "narrowed": Case((Param(0x2000, U32, "7"), *BASE[1:]), BASE, {**BASE_VALUES, 0x2000: "FA000000"}),
    "narrowed_value_fits": Case((Param(0x2000, U32, "7"), *BASE[1:]), BASE, {**BASE_VALUES, 0x2000: "01000000"}),
    "reordered": Case((BASE[2], BASE[0]), (BASE[2], Param(0x2001, U16, "9"), BASE[0]),
                      {0x2000: "FA", 0x2002: "85FF"}, order=(True, False)),
    "string_grown": Case((Param(0x2010, VS, "abc", capacity=8),), (Param(0x2010, VS, "abc", capacity=16),),
                         {0x2010: b"hello".hex()}),
    "string_shrunk": Case((Param(0x2010, VS, "abc", capacity=16),), (Param(0x2010, VS, "abc", capacity=4),),
                          {0x2010: b"hello world".hex()}),
    "string_shrunk_fits": Case((Param(0x2010, VS, "abc", capacity=16),), (Param(0x2010, VS, "abc", capacity=4),),
                               {0x2010: b"hi".hex()}),
    "octets_grown": Case((Param(0x2011, OS, "0102", capacity=2),), (Param(0x2011, OS, "0102", capacity=4),),
                         {0x2011: "A1B2"}),
    "limits_tightened": Case((Param(0x2000, U8, "7", "0", "100"),), (Param(0x2000, U8, "7", "0", "50"),),
                             {0x2000: "50"}),
    "limits_kept": Case((Param(0x2000, U8, "7", "0", "100"),), (Param(0x2000, U8, "7", "0", "50"),),
                        {0x2000: "20"}),
    "real": Case((Param(0x2004, R32, "1.5"),), (Param(0x2004, R32, "1.5", "0", "10"),),
                 {0x2004: "0000C841"}),  # 25.0: now above the HighLimit
    "two_groups_one_changes": Case(BASE, (*BASE, Param(0x2003, U32, "42")), BASE_VALUES, heartbeat=(1000, 500)),
    "comm_changes": Case(BASE, BASE, BASE_VALUES, heartbeat=(1000, 500)),
    "region_grows": Case(BASE, (*BASE, *(Param(0x2100 + k, U32, str(k)) for k in range(12))), BASE_VALUES),
    "region_shrinks": Case((*BASE, *(Param(0x2100 + k, U32, str(k)) for k in range(12))), BASE, BASE_VALUES),
    # the elements of a uniform ARRAY share one descriptor (packing.py); each is a record of its own
    "array_unchanged": Case((Param(0x2020, U16, "5", elements=4),), (Param(0x2020, U16, "5", elements=4),),
                            {(0x2020, 1): "3412", (0x2020, 4): "FFFF"}),
    "array_grown_widened": Case((Param(0x2020, U16, "5", elements=3),), (Param(0x2020, U32, "6", elements=5),),
                                {(0x2020, 2): "3412", (0x2020, 3): "0100"}),
    "array_shrunk": Case((Param(0x2020, U8, "5", elements=6), *BASE), (*BASE, Param(0x2020, U8, "5", elements=2)),
                         {**BASE_VALUES, (0x2020, 1): "11", (0x2020, 2): "22", (0x2020, 6): "66"}),
    # a VAR that becomes an ARRAY: its value sits where the array's sub 0 (UNSIGNED8) goes. Of the
    # same type sub 0 follows the new count (converted); narrowed, the value is lost (defaulted)
    "var_becomes_array": Case((Param(0x2030, U8, "7"), *BASE), (Param(0x2030, U16, "5", elements=3), *BASE),
                              {**BASE_VALUES, 0x2030: "09"}),
    "var_becomes_array_narrowed": Case((Param(0x2030, U16, "7"), *BASE), (Param(0x2030, U16, "5", elements=3), *BASE),
                                       {**BASE_VALUES, 0x2030: "0900"}),
    # alike entries of consecutive indices share their descriptors (sharing.py): the image still
    # holds a record per member's value, in index order, as the layout in Python says
    "shared_arrays_split": Case(tuple(Param(0x2040 + k, U16, str(k), elements=3) for k in range(4)),
                                (*(Param(0x2040 + k, U16, str(k), elements=3) for k in (0, 1, 3)),
                                 Param(0x2042, U32, "9", elements=3)),
                                {(0x2040 + k, s): f"{k:02X}{s:02X}" for k in range(4) for s in (1, 3)}),
    "shared_vars_gap": Case(tuple(Param(0x2050 + k, U32, str(k)) for k in range(5)),
                            tuple(Param(0x2050 + k, U32, str(k)) for k in (0, 1, 3, 4)),
                            {0x2050 + k: f"{k + 1:02X}00A0B0" for k in range(5)}),
    "downgrade": Case((Param(0x2000, U32, "7"), *BASE[1:], Param(0x2003, U32, "42")), BASE,
                      {**BASE_VALUES, 0x2000: "FA000000", 0x2003: "01020304"}),
}


def eds(params: tuple[Param, ...], heartbeat: int, reverse: bool) -> str:
    listed = sorted(params, key=lambda p: p.index, reverse=reverse)
    lines = [HEADER.format(heartbeat=heartbeat), "[ManufacturerObjects]", f"SupportedObjects={len(params)}"]
    lines += [f"{n}=0x{p.index:04X}" for n, p in enumerate(listed, start=1)]
    for p in listed:
        if p.elements:
            lines += _array(p)
            continue
        lines += ["", f"[{p.index:04X}]", f"ParameterName=Parameter {p.index:04X}", "ObjectType=0x7",
                  f"DataType=0x{p.dtype:04X}", "AccessType=rw", f"DefaultValue={p.default}", "PDOMapping=0"]
        lines += [f"LowLimit={p.low}"] if p.low is not None else []
        lines += [f"HighLimit={p.high}"] if p.high is not None else []
    return "\n".join(lines) + "\n"


def _array(p: Param) -> list[str]:
    lines = ["", f"[{p.index:04X}]", f"ParameterName=Array {p.index:04X}", "ObjectType=0x8",
             f"SubNumber={p.elements + 1}", "", f"[{p.index:04X}sub0]", "ParameterName=Highest sub-index supported",
             "ObjectType=0x7", "DataType=0x0005", "AccessType=ro", f"DefaultValue={p.elements}"]
    for k in range(1, p.elements + 1):
        lines += ["", f"[{p.index:04X}sub{k}]", f"ParameterName=Element {k}", "ObjectType=0x7",
                  f"DataType=0x{p.dtype:04X}", "AccessType=rw", f"DefaultValue={p.default}", "PDOMapping=0"]
    return lines


def _set(key: int | tuple[int, int], hex_: str) -> str:
    index, sub = key if isinstance(key, tuple) else (key, 0)
    return f"set:{index:04X}:{sub:02X}:{hex_}"


def options(params: tuple[Param, ...], extra: str = "") -> str:
    text = '[[entry]]\nmatch = "0x2000-0x2FFF"\nstorage = "persist:app"\n'
    text += '\n[[entry]]\nmatch = "0x1017"\nstorage = "persist:comm"\n'
    for p in params:
        if p.capacity is not None:
            text += f'\n[[entry]]\nmatch = "0x{p.index:04X}"\ncapacity = {p.capacity}\n'
    return extra + text


def firmware(tmp: Path, tag: str, params: tuple[Param, ...], heartbeat: int, reverse: bool,
             extra_options: str = "", configured: bool = False,
             cflags: tuple[str, ...] = ()) -> tuple[Path, dict[str, GroupLayout]]:
    """Generate `od` from the parameters and build migrate_main on it; the program and its layouts.
    `configured`: the runtime built with the generated od_config.h (only what `od` uses)."""
    src = tmp / tag
    src.mkdir()
    (src / "od.eds").write_text(eds(params, heartbeat, reverse), encoding="utf-8")
    (src / "od.toml").write_text(options(params, extra_options), encoding="utf-8")
    request = Request(src / "od.eds", name="od", options=src / "od.toml")
    prepared = prepare(request)
    assert prepared.od is not None and prepared.placements is not None
    layouts = group_layouts(prepared.od, prepared.placements)
    done = subprocess.run(["python3", "-m", "odgen", "generate", str(src / "od.eds"), "--name", "od", "--options",
                           str(src / "od.toml"), "-o", str(src)], capture_output=True, text=True, check=False,
                          cwd=ROOT, env=_env())
    assert done.returncode == 0, done.stdout + done.stderr
    exe = src / "migrate_main"
    flags = ("-O1", '-DODG_CONFIG="od_config.h"', *cflags) if configured else ("-O1", *cflags)
    build("gcc", flags, (CTESTS / "migrate_main.c", src / "od.c", *toolchain.core_sources(),
                            RUNTIME / "odg_nv_file.c", CTESTS / "nv_fault.c"), (src, RUNTIME, CTESTS), exe)
    return exe, layouts


def _env() -> dict[str, str]:
    import os
    import sys
    env = dict(os.environ)
    env["PATH"] = str(Path(sys.executable).parent) + os.pathsep + env.get("PATH", "")
    return env


@dataclass
class Boot:
    groups: list[dict[str, int]]
    values: dict[tuple[int, int], str]
    status: dict[int, str]
    seen: list[int]


def run(exe: Path, nv: Path, *ops: str) -> Boot:
    done = subprocess.run([str(exe), str(nv), *ops], capture_output=True, text=True, check=False, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    boot = Boot([], {}, {}, [])
    for line in done.stdout.splitlines():
        words = line.split()
        if words[0] == "group":
            boot.groups.append({words[k]: int(words[k + 1]) for k in range(2, len(words), 2)})
        elif words[0] == "seen":
            boot.seen = [int(w) for w in (words[1], *words[3:])]
        elif words[0] in ("value", "status"):
            key = (int(words[1], 16), int(words[2], 16))
            (boot.values if words[0] == "value" else boot.status)[key[1]] = words[3] if len(words) > 3 else ""
            if words[0] == "value":
                boot.values[key] = words[3] if len(words) > 3 else ""
    boot.values = {k: v for k, v in boot.values.items() if isinstance(k, tuple)}
    return boot


def to_image(e: EntryLayout, wire: str) -> bytes:
    """What odg_read serves, as the image stores it (value_size bytes)."""
    raw = bytes.fromhex(wire)
    if e.data_type == DOMAIN_TYPE:
        return len(raw).to_bytes(4, "little") + raw + bytes(e.length - len(raw))
    return raw + bytes(value_size(e) - len(raw))


def from_image(e: EntryLayout, raw: bytes) -> str:
    """The image's value as odg_read serves it."""
    if e.data_type == DOMAIN_TYPE:
        return raw[4:4 + int.from_bytes(raw[:4], "little")].hex().upper()
    if e.data_type == 0x09:
        raw = raw.split(b"\0", 1)[0]
    return raw.hex().upper()


@pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")
@pytest.mark.parametrize("runtime", ["full", "configured"])
@pytest.mark.parametrize("name", list(CASES))
def test_migration_matches_policy(name: str, runtime: str, tmp_path: Path) -> None:
    """`configured`: both versions run the runtime built for their own dictionary (od_config.h:
    no string or 64-bit paths where the dictionary has none), as the firmware would."""
    case = CASES[name]
    configured = runtime == "configured"
    v1, old = firmware(tmp_path, "v1", case.v1, case.heartbeat[0], case.order[0], configured=configured)
    v2, new = firmware(tmp_path, "v2", case.v2, case.heartbeat[1], case.order[1], configured=configured)
    nv = tmp_path / "od.nv"
    sets = [_set(key, hex_) for key, hex_ in case.stored.items()] + ["set:1017:00:FA00"]
    stored = run(v1, nv, *sets, "store", "dump")
    fresh = run(v2, tmp_path / "fresh.nv", "dump")
    nv_before = nv.read_bytes()
    got = run(v2, nv, "dump")
    names = sorted(new)  # NAME_GROUP_* order
    for g, group in enumerate(names):
        old_layout = old.get(group, GroupLayout(group))
        values = {e.key: to_image(e, stored.values[e.key]) for e in old_layout.entries}
        want = migrate(old_layout, new[group], values)
        counts = want.counts
        status = MIGRATED if counts.migrated else LOADED
        assert got.groups[g] == {"status": status, "kept": counts.kept, "converted": counts.converted,
                                 "defaulted": counts.defaulted, "dropped": counts.dropped}, (group, got.groups)
        for e in new[group].entries:
            value = want.values[e.key]
            expect = fresh.values[e.key] if value is None else from_image(e, value)
            assert got.values[e.key] == expect, (group, hex(e.index), got.values[e.key], expect)
    lost = any(b["defaulted"] or b["dropped"] for b in got.groups)
    assert bool(got.seen[0] & 0x80) == lost
    assert got.seen[1:] == [sum(b["defaulted"] for b in got.groups), sum(b["dropped"] for b in got.groups),
                            sum(b["converted"] for b in got.groups)]
    again = run(v2, nv, "dump")  # the migrated image was stored: the next boot loads it
    assert all(b["status"] == LOADED for b in again.groups), again.groups
    assert again.values == got.values
    run(v2, nv, "restore")  # 0x1011: the defaults at the next boot, whatever the old regions held
    restored = run(v2, nv, "dump")
    assert all(b["status"] == DEFAULTS for b in restored.groups), restored.groups
    assert restored.values == fresh.values
    if any(b["status"] == MIGRATED for b in got.groups):
        cut = tmp_path / "cut.nv"
        cut.write_bytes(nv_before)
        done = subprocess.run([str(v2), str(cut), "cuts"], capture_output=True, text=True, check=False, timeout=300)
        assert done.returncode == 0, done.stdout[-3000:]
        assert done.stdout.split()[-1] == "0" and int(done.stdout.split()[-3]) >= 64, done.stdout[-300:]


@pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")
@pytest.mark.parametrize("runtime", ["full", "configured"])
@pytest.mark.parametrize("name", ["unchanged", "added", "widened"])
def test_without_migration(name: str, runtime: str, tmp_path: Path) -> None:
    """[persist] migration = false: "ODG1" images of the mirror in the group's region; an unchanged
    layout loads, any change gives the defaults (SIGNATURE), while the other group keeps its values.
    `configured`: the runtime built with od_config.h, which then leaves the migration code out."""
    case = CASES[name]
    off = "[persist]\nmigration = false\n"
    configured = runtime == "configured"
    v1, _ = firmware(tmp_path, "v1", case.v1, 1000, False, off, configured)
    v2, _ = firmware(tmp_path, "v2", case.v2, 1000, False, off, configured)
    assert "#define ODG_CFG_PERSIST_MIGRATION 0" in (tmp_path / "v2" / "od_config.h").read_text()
    nv = tmp_path / "od.nv"
    stored = run(v1, nv, *(_set(k, h) for k, h in case.stored.items()), "set:1017:00:FA00", "store",
                 "dump")
    fresh = run(v2, tmp_path / "fresh.nv", "dump")
    got = run(v2, nv, "dump")
    app, comm = got.groups  # NAME_GROUP_APP, NAME_GROUP_COMM
    assert comm["status"] == LOADED and got.values[(0x1017, 0)] == "FA00"
    if name == "unchanged":
        assert app["status"] == LOADED
        assert got.values == stored.values
    else:
        assert app["status"] == SIGNATURE and got.seen[0] & 1 << SIGNATURE
        assert all(got.values[k] == fresh.values[k] for k in fresh.values if k[0] >= 0x2000)


@pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")
def test_damaged_only_when_bytes_are_corrupt(tmp_path: Path) -> None:
    """A bit flipped in both slots of group app: DAMAGED, with an EMCY-worthy boot_seen and the
    defaults; group comm, in its own region, keeps its value."""
    exe, layouts = firmware(tmp_path, "v1", BASE, 1000, False)
    nv = tmp_path / "od.nv"
    run(exe, nv, *(f"set:{i:04X}:00:{h}" for i, h in BASE_VALUES.items()), "set:1017:00:FA00", "store", "store")
    fresh = run(exe, tmp_path / "fresh.nv", "dump")
    region = nv_map(layouts)["app"]
    data = bytearray(nv.read_bytes())
    for slot in (region.offset, region.offset + region.size // 2):
        data[slot + 30] ^= 0x04
    nv.write_bytes(bytes(data))
    got = run(exe, nv, "dump")
    assert [b["status"] for b in got.groups] == [DAMAGED, LOADED]
    assert got.seen[0] == 1 << DAMAGED | 1 << LOADED
    assert got.values[(0x1017, 0)] == "FA00"
    assert all(got.values[(i, 0)] == fresh.values[(i, 0)] for i in BASE_VALUES)


def test_migration_switched_on_reports_an_odg1_image_as_signature(tmp_path: Path) -> None:
    """v1 without migration stores "ODG1" images; v2, the same layout with migration, finds
    app's image (its commit mark where the region starts) and boots SIGNATURE with the defaults
    and the loss reported; after its store the next boot loads. comm, unchanged, too."""
    case = CASES["unchanged"]
    v1, _ = firmware(tmp_path, "v1", case.v1, 1000, False, "[persist]\nmigration = false\n")
    v2, _ = firmware(tmp_path, "v2", case.v1, 1000, False)
    nv = tmp_path / "od.nv"
    run(v1, nv, *(_set(k, h) for k, h in case.stored.items()), "set:1017:00:FA00", "store", "dump")
    fresh = run(v2, tmp_path / "fresh.nv", "dump")
    got = run(v2, nv, "dump")
    assert [g["status"] for g in got.groups] == [SIGNATURE, SIGNATURE] and got.seen[0] & 1 << SIGNATURE
    assert got.values == fresh.values
    assert [g["status"] for g in run(v2, nv, "dump").groups] == [LOADED, LOADED]


def test_groups_placed_from_an_nv_base_store_and_load_there(tmp_path: Path) -> None:
    """OD_NV_BASE moves every region: the runtime built with od_config.h finds the end of the
    groups' NV from the first group's region (ODG_PERSIST_NV_TAIL): a store lands past the base,
    and the next boot loads it."""
    case = CASES["unchanged"]
    exe, _ = firmware(tmp_path, "v1", case.v1, 1000, False, configured=True, cflags=("-DOD_NV_BASE=1024u",))
    config = (tmp_path / "v1" / "od_config.h").read_text(encoding="utf-8")
    assert "#define ODG_PERSIST_NV_TAIL" in config
    nv = tmp_path / "od.nv"
    stored = run(exe, nv, *(_set(k, h) for k, h in case.stored.items()), "store", "dump")
    image = nv.read_bytes()
    assert set(image[:1024]) <= {0xFF} and b"ODG2" in image[1024:]
    again = run(exe, nv, "dump")
    assert [g["status"] for g in again.groups] == [LOADED, LOADED] and again.values == stored.values
