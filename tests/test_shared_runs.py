"""Runs of alike entries sharing one list of descriptors (odgen/codegen/sharing.py, ODG_E_SHARED).

A description built to try to break the sharing: PDO records with $NODEID COB-IDs, packed
mapping records, runs of every C width (BOOLEAN to UNSIGNED64, INTEGER24, REAL64), records
whose sub 0 is constant (FLASH) and the rest in RAM or a persistence group, a record one
attribute apart from its neighbours and a run broken by a gap in the indices. Every member's
every value has a default of its own, so a member served another member's value is seen: the
self-test (`odgen check`) reads each default, writes each value and reads it back, on the host
and on the emulated cores (big-endian, 16-bit int, no unaligned access); a C program writes
each value through the dictionary and finds it in the value's own struct member.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from odgen import check, toolchain
from odgen.assets import runtime_dir
from odgen.cli import main

from .cprog import build, compiler
from .test_migration_runtime import LOADED, Param, eds, eds_head, firmware, run
from .test_target_cores import _check, _core

HEAD = eds_head("shared.eds", "shared runs", "shared", rpdos=4)
U8, U16, U32, U64, I24, R64, BOOL = 0x05, 0x06, 0x07, 0x1B, 0x10, 0x11, 0x01


def _var(index: int, sub: int | None, name: str, dtype: int, access: str, default: str, pdo: int = 0) -> list[str]:
    section = f"{index:04X}" if sub is None else f"{index:04X}sub{sub}"
    return ["", f"[{section}]", f"ParameterName={name}", "ObjectType=0x7", f"DataType=0x{dtype:04X}",
            f"AccessType={access}", f"DefaultValue={default}", f"PDOMapping={pdo}"]


def _record(index: int, name: str, subs: list[tuple[int, str, int, str, str]], kind: int = 9) -> list[str]:
    lines = ["", f"[{index:04X}]", f"ParameterName={name}", f"ObjectType=0x{kind:X}", f"SubNumber={len(subs)}"]
    for sub, sname, dtype, access, default in subs:
        lines += _var(index, sub, sname, dtype, access, default)
    return lines


def description(odd_one: bool = True, real64: bool = True) -> str:
    """The description; `odd_one`: 0x2022 sub 1 is read-only where its neighbours' is read-write;
    `real64`: the mixed records hold a REAL64 (not where double has 4 bytes, as on the AVR)."""
    objs: list[list[str]] = [
        _var(0x1000, None, "Device type", U32, "ro", "0"),
        _var(0x1001, None, "Error register", U8, "ro", "0"),
        _record(0x1018, "Identity", [(0, "Highest", U8, "ro", "1"), (1, "Vendor-ID", U32, "ro", "0")]),
    ]
    for k in range(4):  # RPDO communication: not dense (sub 3, 4 absent), a $NODEID COB-ID
        objs.append(_record(0x1400 + k, "RPDO communication parameter", [
            (0, "Highest sub-index supported", U8, "const", "5"),
            (1, "COB-ID used by RPDO", U32, "rw", f"$NODEID+0x{0x80000200 + 0x100 * k:X}"),
            (2, "Transmission type", U8, "rw", str(1 + k)),
            (5, "Event timer", U16, "rw", str(100 * k + 7))]))
    mapped = ((), (0x2030,), (0x2031, 0x2033), (0x2034, 0x2030))  # 32 bits each, within the PDO
    for k in range(4):  # RPDO mapping: packed (one descriptor for sub 1..8); past the count, values apart
        objs.append(_record(0x1600 + k, "RPDO mapping parameter", [
            (0, "Number of mapped objects", U8, "rw", str(len(mapped[k]))),
            *((s, f"Object {s}", U32, "rw", f"0x{mapped[k][s - 1]:04X}0020" if s <= len(mapped[k])
               else f"0x{0x70000008 + (k << 12) + (s << 8):X}") for s in range(1, 9))]))
    for k in range(3):  # VARs of 8-byte values
        objs.append(_var(0x2000 + k, None, f"Counter {k}", U64, "rw", str(0x1122334455 + k)))
    for k in range(3):  # every width in one record, and a REAL64
        objs.append(_record(0x2010 + k, "Mixed", [
            (0, "Highest", U8, "ro", "6"), (1, "Flag", BOOL, "rw", str(k & 1)), (2, "Word", U16, "rw", str(300 + k)),
            (3, "Int24", I24, "rw", str(-70000 - k)), (4, "Long", U64, "rw", str(0x99AABBCCDD + k)),
            (5, "Real", R64 if real64 else U32, "rw", f"{1.5 + k}" if real64 else str(k)),
            (6, "Byte", U8, "rw", str(9 + k))]))
    for k in range(4):  # 0x2022 is one attribute apart: 0x2020-0x2021 share, 0x2023 is alone
        access = "ro" if odd_one and k == 2 else "rw"
        objs.append(_record(0x2020 + k, "Almost alike", [
            (0, "Highest", U8, "ro", "2"), (1, "Value", U32, access, str(4000 + k)), (2, "Other", U16, "rw", str(k))]))
    for index in (0x2030, 0x2031, 0x2033, 0x2034):  # a gap: two runs, not one
        objs.append(_var(index, None, f"Gap neighbour {index:04X}", U32, "rw", str(index * 3), pdo=1))
    lines = [HEAD, "[ManufacturerObjects]"]
    manufacturer = [o for o in objs if int(o[1][1:5], 16) >= 0x2000]
    optional = [o for o in objs if 0x1000 < int(o[1][1:5], 16) < 0x2000 and o[1][1:5] not in ("1001", "1018")]
    lines += [f"SupportedObjects={len(manufacturer)}"]
    lines += [f"{n}=0x{o[1][1:5]}" for n, o in enumerate(manufacturer, 1)]
    lines += ["", "[OptionalObjects]", f"SupportedObjects={len(optional)}"]
    lines += [f"{n}=0x{o[1][1:5]}" for n, o in enumerate(optional, 1)]
    for o in objs:
        lines += o
    return "\n".join(lines) + "\n"


OPTIONS = """[[entry]]
match = ["0x1400-0x1603", "0x2010-0x2012"]
storage = "persist:comm"

[[entry]]
match = ["0x2000-0x2002", "0x2030-0x2034"]
storage = "persist:app"
"""


@pytest.fixture(scope="module")
def files(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    tmp = tmp_path_factory.mktemp("shared")
    (tmp / "shared.eds").write_text(description(), encoding="utf-8")
    (tmp / "shared.toml").write_text(OPTIONS, encoding="utf-8")
    return tmp / "shared.eds", tmp / "shared.toml"


@pytest.fixture(scope="module")
def generated(files: tuple[Path, Path], tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("shared-out")
    assert main(["generate", str(files[0]), "--options", str(files[1]), "--name", "od", "-o", str(out)]) == 0
    return out


def _codes(od_c: str) -> dict[int, tuple[int, str]]:
    """index -> (first, code) of the generated entries."""
    return {int(m[1], 16): (int(m[2]), m[3]) for m in
            re.finditer(r"\{\.index = 0x([0-9A-F]{4}), \.first = (\d+), \.count = \d+, \.code = ([^}]*)\}", od_c)}


def test_alike_entries_share_and_the_rest_do_not(generated: Path) -> None:
    entries = _codes((generated / "od.c").read_text(encoding="utf-8"))
    shared = {i for i, (_, code) in entries.items() if "ODG_E_SHARED" in code}

    def one_list(*indices: int) -> bool:
        return len({entries[i][0] for i in indices}) == 1 and set(indices) <= shared

    assert one_list(0x1400, 0x1401, 0x1402, 0x1403)  # the $NODEID COB-IDs too
    assert one_list(0x1600, 0x1601, 0x1602, 0x1603) and "ODG_E_PACKED" in entries[0x1600][1]
    assert one_list(0x2000, 0x2001, 0x2002) and one_list(0x2010, 0x2011, 0x2012)
    assert one_list(0x2020, 0x2021)  # one attribute apart: 0x2022 alone, and 0x2023 alone after it
    assert {0x2022, 0x2023}.isdisjoint(shared)
    assert one_list(0x2030, 0x2031) and one_list(0x2033, 0x2034)  # a gap ends a run
    assert entries[0x2031][0] != entries[0x2033][0]
    assert {0x1000, 0x1001, 0x1018}.isdisjoint(shared)  # nothing alike next to them
    config = (generated / "od_config.h").read_text(encoding="utf-8")
    assert re.search(r"#define ODG_CFG_SHARED 1\b", config)


def test_without_the_odd_one_the_run_goes_on(files: tuple[Path, Path], tmp_path: Path) -> None:
    (tmp_path / "alike.eds").write_text(description(odd_one=False), encoding="utf-8")
    assert main(["generate", str(tmp_path / "alike.eds"), "--options", str(files[1]), "--name", "od",
                 "-o", str(tmp_path)]) == 0
    entries = _codes((tmp_path / "od.c").read_text(encoding="utf-8"))
    assert len({entries[i][0] for i in range(0x2020, 0x2024)}) == 1


def test_a_hook_or_a_limit_keeps_an_entry_out_of_a_run(files: tuple[Path, Path], tmp_path: Path) -> None:
    """Hooks and limits are found by descriptor position, which the members of a run share."""
    section = "[2031]\nParameterName=Gap neighbour 2031"
    text = description().replace(section, section.replace("\n", "\nLowLimit=1\n"))
    assert "LowLimit=1" in text
    (tmp_path / "apart.eds").write_text(text, encoding="utf-8")
    options = files[1].read_text(encoding="utf-8") + '\n[[entry]]\nmatch = "0x1402sub5"\nhooks = ["post_write"]\n'
    (tmp_path / "apart.toml").write_text(options, encoding="utf-8")
    assert main(["generate", str(tmp_path / "apart.eds"), "--options", str(tmp_path / "apart.toml"), "--name", "od",
                 "-o", str(tmp_path)]) == 0
    entries = _codes((tmp_path / "od.c").read_text(encoding="utf-8"))
    shared = {i for i, (_, code) in entries.items() if "ODG_E_SHARED" in code}
    assert {0x1400, 0x1401} <= shared and entries[0x1400][0] == entries[0x1401][0]
    assert {0x1402, 0x1403, 0x2030, 0x2031}.isdisjoint(shared)


# Writes a distinct value to each number through odg_set and finds it in the value's own struct
# member (the accessor macros of od.h), after checking every $NODEID value has the node-id added.
DRIVER = r"""
#include <stdio.h>
#include <string.h>
#include "od.h"
static unsigned failed, passed;
static uint16_t bad_index_;
#define CHECK(c, what) do { if (c) passed++; else { failed++; printf("FAIL %s\n", what); } } while (0)
int main(void)
{
    uint16_t bad = 0;
    uint32_t cob;
    CHECK(odg_init(&od, 5) == ODG_OK, "init");
    CHECK(odg_verify(&od, &bad) == ODG_OK, "verify");
    CHECK(odg_get_u32(&od, 0x1400, 1, &cob) == ODG_OK && cob == 0x80000205u, "1400 cob");
    CHECK(odg_get_u32(&od, 0x1403, 1, &cob) == ODG_OK && cob == 0x80000505u, "1403 cob");
    {   /* odg_verify refuses a shared list whose stride is 0, or a member that lost its flag */
        static odg_entry_t entries[256];
        static odg_sub_t subs[256];
        odg_dict_t broken = od;
        uint16_t i = 0;
        memcpy(entries, od.entries, od.n_entries * sizeof entries[0]);
        memcpy(subs, od.subs, od.n_subs * sizeof subs[0]);
        broken.entries = entries;
        broken.subs = subs;
        broken.hash_slots = NULL; /* the binary search: the hash would not find a moved index */
        CHECK(odg_verify(&broken, &bad_index_) == ODG_OK, "copy verifies");
        while (!(entries[i].code & ODG_E_SHARED)) {
            i++;
        }
        subs[entries[i].first + 1].size &= 0xFFu;
        CHECK(odg_verify(&broken, &bad_index_) == ODG_ABORT_INTERNAL && bad_index_ == entries[i].index, "stride 0");
        subs[entries[i].first + 1] = od.subs[entries[i].first + 1];
        entries[i + 1].code = (uint8_t)(entries[i + 1].code & ~ODG_E_SHARED);
        CHECK(odg_verify(&broken, &bad_index_) == ODG_ABORT_INTERNAL && bad_index_ == entries[i + 1].index,
              "a member without the flag");
    }
@CHECKS@
    printf("%u passed, %u failed\n", passed, failed);
    return failed != 0;
}
"""
ACCESSOR = re.compile(r"#define (od_x([0-9A-F]{4})_\w+?(?:_s(\d+)_\w+)?) \((od_(?:ram|persist_\w+))\.(\w+)\)")


def _checks(od_h: str) -> str:
    """For every number in RAM or a group of the shared entries: set it through the dictionary
    and compare with its member."""
    lines = []
    for n, m in enumerate(ACCESSOR.finditer(od_h)):
        index, sub, member = int(m[2], 16), int(m[3] or 0), f"{m[4]}.{m[5]}"
        if not (0x1400 <= index < 0x1700 or 0x2000 <= index < 0x2040):
            continue
        lines.append(f"    {{ __typeof__({member}) v; memset(&v, 0, sizeof v); memset(&v, {n % 200 + 1}, 1);\n"
                     f"      CHECK(odg_set(&od, 0x{index:04X}, {sub}, &v, sizeof v) == ODG_OK"
                     f" && memcmp(&{member}, &v, sizeof v) == 0, \"{index:04X}sub{sub}\"); }}")
    return "\n".join(lines)


@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_each_member_reads_and_writes_its_own_values(generated: Path, cc: str, tmp_path: Path) -> None:
    checks = _checks((generated / "od.h").read_text(encoding="utf-8"))
    assert checks.count("CHECK(") > 80
    (tmp_path / "main.c").write_text(DRIVER.replace("@CHECKS@", checks), encoding="utf-8")
    exe = tmp_path / "main"
    build(cc, ("-O2", "-std=gnu99", "-Wno-pedantic", f"-I{generated}"),
          (tmp_path / "main.c", generated / "od.c", *toolchain.core_sources()),
          (generated, runtime_dir()), exe)
    done = subprocess.run([str(exe)], capture_output=True, text=True, check=False, timeout=60)
    assert done.returncode == 0 and " 0 failed" in done.stdout, done.stdout[-3000:]


@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_the_generated_c_is_warning_free(generated: Path, cc: str, tmp_path: Path) -> None:
    cmd = [compiler(cc), "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-c", f"-I{generated}",
           f"-I{runtime_dir()}", '-DODG_CONFIG="od_config.h"', str(generated / "od.c"), "-o", str(tmp_path / "od.o")]
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr


@pytest.mark.parametrize("core", ["host", "cortex-m0", "powerpc", "avr"])
def test_self_test_reads_and_writes_every_member(files: tuple[Path, Path], core: str, tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    """Big-endian (powerpc), no unaligned access (cortex-m0), 16-bit int and 4-byte double (avr)."""
    source = files[0]
    if core == "avr":
        source = tmp_path / "shared.eds"
        source.write_text(description(real64=False), encoding="utf-8")
    if core == "host":
        code = main(["check", str(source), "--options", str(files[1]), "--verbose"])
        out = capsys.readouterr().out
    else:
        code, out = _check(_core(core), source, files[1], capsys, "--verbose")
    assert code == 0, out[-3000:]
    passed = check.SUMMARY.findall(out)
    assert passed and int(passed[-1][0]) > 200 and passed[-1][1] == "0", out[-2000:]


# NV images written by the runtime before the shared runs (tests/fixtures/nv/shared_*.nv, never
# regenerated): alike ARRAYs and VARs, whose image records are their members' values in index
# order, which the layout walk over the shared lists gives as before.
FIX = Path(__file__).resolve().parent / "fixtures" / "nv"
NV_PARAMS = (*(Param(0x2040 + k, U16, str(k), elements=3) for k in range(4)),
             *(Param(0x2050 + k, U32, str(k)) for k in range(5)))
NV_STORED = {**{(0x2040 + k, s): f"{k:02X}{s:02X}" for k in range(4) for s in (1, 2, 3)},
             **{(0x2050 + k, 0): f"{k + 1:02X}00A0B0" for k in range(5)}}


@pytest.mark.parametrize("fmt", ["odg2", "odg1"])
def test_images_stored_before_the_shared_runs_load(fmt: str, tmp_path: Path) -> None:
    assert eds(NV_PARAMS, 1000, False) == (FIX / "shared.eds").read_text(encoding="utf-8")
    exe, _ = firmware(tmp_path, fmt, NV_PARAMS, 1000, False, "[persist]\nmigration = false\n" if fmt == "odg1" else "")
    assert "ODG_E_SHARED" in (tmp_path / fmt / "od.c").read_text(encoding="utf-8")
    nv = tmp_path / "od.nv"
    nv.write_bytes((FIX / f"shared_{fmt}.nv").read_bytes())
    got = run(exe, nv, "dump")
    assert [g["status"] for g in got.groups] == [LOADED, LOADED], got.groups
    want = {}
    for line in (FIX / f"shared_{fmt}.txt").read_text(encoding="utf-8").splitlines():
        index, sub, *value = line.split()
        want[(int(index, 16), int(sub, 16))] = value[0] if value else ""
    assert got.values == want
    assert all(want[key] == value for key, value in NV_STORED.items())
